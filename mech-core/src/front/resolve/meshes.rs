//! The gear pairs and racks of [`super::resolve`]: their carrier and centres, once every
//! joint is known.

use super::Diagnostic;
use crate::model::*;

/// Gear pairs and racks: their carrier and centres, now that every joint is known.
pub(super) fn meshes<S: Clone>(
    d: &Description<S>,
    joints: &mut [Joint],
    links: &[Link],
    points: &[Point],
    errs: &mut Vec<Diagnostic<S>>,
) {
    for (k, j) in d.joints.iter().enumerate() {
        if let (Some(decl), true) = (&j.mesh, j.kind.mesh()) {
            if joints[k].a == joints[k].b {
                continue;
            }
            match mesh_of(joints, links, points, k, decl) {
                Ok(m) => {
                    joints[k].point = m.centres[0];
                    joints[k].mesh = Some(m);
                }
                Err(msg) => errs.push(Diagnostic::at(j.kind_span.clone(), msg)),
            }
        }
    }
}

/// The carrier and centres of the gear pair or rack `k` (`docs/conventions.md#gears`): a
/// gear's centre is the point of one of its revolute joints; a gear pair's carrier is a
/// link (not one of the gears) that has both centres among its points, so that their
/// distance is fixed; a rack's carrier is the link its prismatic joint slides on, which
/// must have the pinion's centre. Among several candidates, the centres whose distance is
/// nearest the pitch radii's sum (difference when internal) are taken.
fn mesh_of<S>(
    joints: &[Joint],
    links: &[Link],
    points: &[Point],
    k: usize,
    decl: &MeshDecl<S>,
) -> Result<Mesh, String> {
    let jt = &joints[k];
    let (a, b) = (jt.a, jt.b);
    let [ra, rb] = decl.radii.value;
    let pressure_angle = decl
        .pressure_angle
        .as_ref()
        .map(|p| p.value)
        .unwrap_or(20f64.to_radians());
    let centres_of = |l: usize| -> Vec<usize> {
        joints
            .iter()
            .filter(|o| o.kind == JointKind::Revolute && (o.a == l || o.b == l))
            .map(|o| o.point)
            .collect()
    };
    let dist = |p: usize, q: usize| {
        let (p, q) = (points[p].pos, points[q].pos);
        (q[0] - p[0]).hypot(q[1] - p[1])
    };
    let name = |l: usize| links[l].name.as_str();
    if jt.kind == JointKind::Rack {
        let slide = joints.iter().find(|o| {
            o.kind == JointKind::Prismatic && (o.b == b || o.a == b) && (o.a != a && o.b != a)
        });
        let Some(slide) = slide else {
            return Err(format!("rack `{}`: the rack `{}` must slide (a prismatic joint) on the link that carries the pinion `{}`; it has no prismatic joint", jt.name, name(b), name(a)));
        };
        let carrier = if slide.a == b { slide.b } else { slide.a };
        let Some(&centre) = centres_of(a)
            .iter()
            .find(|&&p| links[carrier].points.contains(&p))
        else {
            return Err(format!("rack `{}`: the pinion `{}` must be pinned (a revolute joint) at its centre to `{}`, the link the rack slides on", jt.name, name(a), name(carrier)));
        };
        return Ok(Mesh {
            ra,
            rb: 0.0,
            internal: false,
            pressure_angle,
            carrier,
            centres: [centre, slide.point],
        });
    }
    let want = if decl.internal {
        (rb - ra).abs()
    } else {
        ra + rb
    };
    let mut best: Option<(f64, Mesh)> = None;
    for &pa in &centres_of(a) {
        for &pb in &centres_of(b) {
            if pa == pb {
                continue;
            }
            for (c, l) in links.iter().enumerate() {
                if c == a || c == b || !l.points.contains(&pa) || !l.points.contains(&pb) {
                    continue;
                }
                let miss = (dist(pa, pb) - want).abs();
                if best.as_ref().is_none_or(|(m, _)| miss < *m) {
                    best = Some((
                        miss,
                        Mesh {
                            ra,
                            rb,
                            internal: decl.internal,
                            pressure_angle,
                            carrier: c,
                            centres: [pa, pb],
                        },
                    ));
                }
            }
        }
    }
    best.map(|(_, m)| m).ok_or_else(|| {
        format!(
            "gear pair `{}`: `{}` and `{}` must each be pinned (a revolute joint) at its centre, and one carrier link (the ground or an arm) must hold both centres among its points; no link holds a centre of each",
            jt.name,
            name(a),
            name(b)
        )
    })
}
