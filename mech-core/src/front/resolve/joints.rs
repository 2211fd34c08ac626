//! The joints of [`super::resolve`]: each joint's links, point, track and axis, and the
//! points its kind requires of its links; then the links no joint reaches and the shared
//! points no pin holds.

use super::links::Known;
use super::Diagnostic;
use crate::model::*;
use std::collections::HashMap;

/// The joints in declaration order (a cam's and a mesh's placement is completed later),
/// and which links a joint reaches (the ground always).
pub(super) fn joints<S: Clone>(
    d: &Description<S>,
    known: &Known,
    errs: &mut Vec<Diagnostic<S>>,
) -> (Vec<Joint>, Vec<bool>) {
    let links = known.links;
    let mut joints = Vec::new();
    let mut reached = vec![false; links.len()];
    reached[0] = true;
    for j in &d.joints {
        let a = known.find_link(&j.a, errs);
        let b = known.find_link(&j.b, errs);
        let point = joint_point(j, known.point_ix, errs);
        if let (Some(a), Some(b)) = (a, b) {
            if a == b {
                errs.push(Diagnostic::at(
                    j.b.span.clone(),
                    format!(
                        "joint `{}` joins link `{}` with itself: a joint needs two different links",
                        j.name.text, links[a].name
                    ),
                ));
            } else {
                reached[a] = true;
                reached[b] = true;
            }
        }
        let around = track_centre(j, known.point_ix, errs);
        let axis = sliding_axis(j, around, errs);
        if let (Some(a), Some(b), Some(p)) = (a, b, point) {
            on_its_links(j, a, b, p, around, known, errs);
        }
        joints.push(Joint {
            name: j.name.text.clone(),
            kind: j.kind,
            a: a.unwrap_or(0),
            b: b.unwrap_or(0),
            point: point.unwrap_or(0),
            axis,
            mesh: None,
            radius: if j.kind == JointKind::Rolling {
                j.mesh.as_ref().map(|m| m.radii.value[0]).unwrap_or(0.0)
            } else {
                0.0
            },
            around,
            cam: None,
            pin: pin(j, a, b, known, errs),
        });
    }
    (joints, reached)
}

/// A revolute joint's pin: a positive diameter, no larger than the section of a link it
/// goes through that is declared by its shape (a bar's width, a rod's diameter, a tube's
/// outer diameter).
fn pin<S: Clone>(
    j: &JointDecl<S>,
    a: Option<usize>,
    b: Option<usize>,
    known: &Known,
    errs: &mut Vec<Diagnostic<S>>,
) -> Option<Pin> {
    let (d, double) = j.pin.as_ref()?;
    if !(d.value > 0.0 && d.value.is_finite()) {
        errs.push(Diagnostic::at(
            d.span.clone(),
            format!(
                "the pin of joint `{}` must have a positive diameter, got {} m",
                j.name.text, d.value
            ),
        ));
        return None;
    }
    for l in [a, b].into_iter().flatten() {
        let link = &known.links[l];
        let section = match link.body.map(|(s, _)| s) {
            Some(crate::model::shape::Shape::Bar { width, .. }) => Some(("width", width)),
            Some(crate::model::shape::Shape::Rod { diameter }) => Some(("diameter", diameter)),
            Some(crate::model::shape::Shape::Tube { outer, .. }) => Some(("outer diameter", outer)),
            _ => None,
        };
        if let Some((what, size)) = section {
            if d.value >= size {
                errs.push(Diagnostic::at(
                    d.span.clone(),
                    format!(
                        "the pin of joint `{}` ({} mm) is not smaller than the {what} of link `{}` ({} mm) it goes through: take a thinner pin or a wider link",
                        j.name.text,
                        d.value * 1e3,
                        link.name,
                        size * 1e3
                    ),
                ));
            }
        }
    }
    Some(Pin {
        diameter: d.value,
        double: *double,
    })
}

/// The point of joint `j`: its `at`, or the point of its name; a cam's and a mesh's are
/// provisional.
fn joint_point<S: Clone>(
    j: &JointDecl<S>,
    point_ix: &HashMap<String, usize>,
    errs: &mut Vec<Diagnostic<S>>,
) -> Option<usize> {
    let pname = j.at.as_ref().unwrap_or(&j.name);
    let point = if j.kind == JointKind::Cam {
        // A rocker's pitch point is written (`at P`); a translating follower's is its
        // slide's point, found with the carrier below.
        match &j.at {
            Some(at) => point_ix.get(&at.text).copied(),
            None => Some(0),
        }
    } else if j.kind.mesh() {
        // A mesh is placed by its gears' centres, found once every joint is known.
        if let Some(at) = &j.at {
            errs.push(Diagnostic::at(
                at.span.clone(),
                format!("{} `{}` takes no `at`: its pitch point follows from the centres of its gears and their radii", j.kind.keyword(), j.name.text),
            ));
        }
        Some(0)
    } else {
        point_ix.get(&pname.text).copied()
    };
    if point.is_none() {
        let how = if j.at.is_none() {
            format!("joint `{}` has no `at POINT`, so it is placed at the point of the same name, and there is no point `{}`; add `at P`", j.name.text, pname.text)
        } else {
            format!("unknown point `{}` in joint `{}`", pname.text, j.name.text)
        };
        errs.push(Diagnostic::at(pname.span.clone(), how));
    }
    point
}

/// A rolling joint's circular track: its centre's point and whether the wheel rolls inside.
fn track_centre<S: Clone>(
    j: &JointDecl<S>,
    point_ix: &HashMap<String, usize>,
    errs: &mut Vec<Diagnostic<S>>,
) -> Option<(usize, bool)> {
    match (&j.around, j.kind) {
        (Some((d, inside)), JointKind::Rolling) => match point_ix.get(&d.text).copied() {
            Some(di) => Some((di, *inside)),
            _ => {
                errs.push(Diagnostic::at(
                    d.span.clone(),
                    format!(
                        "unknown point `{}`: the centre of rolling joint `{}`'s circular track",
                        d.text, j.name.text
                    ),
                ));
                None
            }
        },
        _ => None,
    }
}

/// The sliding axis `along (ux, uy)`: required of a sliding joint, refused elsewhere.
fn sliding_axis<S: Clone>(
    j: &JointDecl<S>,
    around: Option<(usize, bool)>,
    errs: &mut Vec<Diagnostic<S>>,
) -> [f64; 2] {
    match (j.kind, &j.along) {
        (JointKind::Revolute, Some(al)) => {
            errs.push(Diagnostic::at(
                al.span.clone(),
                format!("revolute joint `{}` takes no `along` axis", j.name.text),
            ));
            [0.0, 0.0]
        }
        (JointKind::Revolute, None) => [0.0, 0.0],
        (k, Some(al)) if k.mesh() => {
            errs.push(Diagnostic::at(
                al.span.clone(),
                format!("{} `{}` takes no `along` axis (a rack slides along its prismatic joint's axis)", k.keyword(), j.name.text),
            ));
            [0.0, 0.0]
        }
        (k, None) if k.mesh() || k == JointKind::Cam => [0.0, 0.0],
        (JointKind::Rolling, None) if around.is_some() => [0.0, 0.0],
        (JointKind::Rolling, Some(al)) if around.is_some() => {
            errs.push(Diagnostic::at(
                al.span.clone(),
                format!("rolling joint `{}` rolls around a circle: it takes `around D` or `along (ux, uy)`, not both", j.name.text),
            ));
            [0.0, 0.0]
        }
        (_, Some(al)) => al.value,
        (k, None) => {
            errs.push(Diagnostic::at(
                j.kind_span.clone(),
                format!(
                    "{} joint `{}` needs its sliding axis: add `along (ux, uy)`",
                    k.keyword(),
                    j.name.text
                ),
            ));
            [1.0, 0.0]
        }
    }
}

/// The points joint `j` (between links `a` and `b`, at point `p`) requires of its links:
/// a pin's point on both, a slider's on the slider only, a track's centre on the track.
fn on_its_links<S: Clone>(
    j: &JointDecl<S>,
    a: usize,
    b: usize,
    p: usize,
    around: Option<(usize, bool)>,
    known: &Known,
    errs: &mut Vec<Diagnostic<S>>,
) {
    let (links, points) = (known.links, known.points);
    let pn = &points[p].name;
    match j.kind {
        JointKind::Revolute => {
            for (l, side) in [(a, &j.a), (b, &j.b)] {
                if !links[l].points.contains(&p) {
                    errs.push(Diagnostic::at(
                        side.span.clone(),
                        format!(
                            "revolute joint `{}` is at point `{pn}`, which link `{}` does not have; list `{pn}` among the points of `{}`",
                            j.name.text, links[l].name, links[l].name
                        ),
                    ));
                }
            }
        }
        JointKind::Gear | JointKind::Rack | JointKind::Cam => {}
        JointKind::Prismatic | JointKind::PinInSlot | JointKind::Rolling => {
            if let (Some((di, _)), Some((dn, _))) = (around, &j.around) {
                if !links[a].points.contains(&di) {
                    errs.push(Diagnostic::at(
                        dn.span.clone(),
                        format!("rolling joint `{}` rolls around `{}`, which must be a point of the track `{}`; list it among `{}`'s points", j.name.text, dn.text, links[a].name, links[a].name),
                    ));
                }
            }
            if !links[b].points.contains(&p) {
                errs.push(Diagnostic::at(
                    j.b.span.clone(),
                    format!(
                        "{} joint `{}` is at point `{pn}`, which must be a point of `{}` ({}); list it among `{}`'s points",
                        j.kind.keyword(), j.name.text, links[b].name,
                        if j.kind == JointKind::Rolling { "the wheel's centre" } else { "the slider or pin" },
                        links[b].name
                    ),
                ));
            }
            if links[a].points.contains(&p) {
                errs.push(Diagnostic::at(
                    j.a.span.clone(),
                    format!(
                        "{} joint `{}`: point `{pn}` belongs to the slider `{}` and must not be listed among the points of the guide `{}` (the guide is given by the axis alone)",
                        j.kind.keyword(), j.name.text, links[b].name, links[a].name
                    ),
                ));
            }
        }
    }
}

/// Every link is reached by a joint (reported once per name).
pub(super) fn unreached<S: Clone>(
    decls: &[&LinkDecl<S>],
    reached: &[bool],
    errs: &mut Vec<Diagnostic<S>>,
) {
    for (i, l) in decls.iter().enumerate() {
        let first_of_its_name = decls[..i].iter().all(|d| d.name.text != l.name.text);
        if !reached[i] && first_of_its_name {
            errs.push(Diagnostic::at(
                l.name.span.clone(),
                format!(
                    "link `{}` is not reached by any joint: connect it with a joint or remove it",
                    l.name.text
                ),
            ));
        }
    }
}

/// Shared points must be pinned by a revolute joint (only once the names are right:
/// a misspelt link in a joint would otherwise look like a missing pin).
pub(super) fn shared_points<S: Clone>(
    decls: &[&LinkDecl<S>],
    known: &Known,
    joints: &[Joint],
    errs: &mut Vec<Diagnostic<S>>,
) {
    let (links, points) = (known.links, known.points);
    let names_ok = errs.is_empty();
    for (pi, p) in points.iter().enumerate().filter(|_| names_ok) {
        let owners: Vec<usize> = (0..links.len())
            .filter(|&l| links[l].points.contains(&pi))
            .collect();
        for w in 1..owners.len() {
            for v in 0..w {
                let (l1, l2) = (owners[v], owners[w]);
                if !pinned(joints, &owners, pi, l1, l2) {
                    let span = decls[l2]
                        .points
                        .iter()
                        .find(|r| r.name.text == p.name)
                        .map(|r| r.name.span.clone())
                        .unwrap_or_else(|| decls[l2].name.span.clone());
                    errs.push(Diagnostic::at(
                        span,
                        format!(
                            "point `{}` is shared by links `{}` and `{}` but no revolute joint pins them there; a shared point is a pin: add `{}: revolute({}, {})`, or give one link its own point",
                            p.name, links[l1].name, links[l2].name, p.name, links[l1].name, links[l2].name
                        ),
                    ));
                }
            }
        }
    }
}

/// Whether links `l1` and `l2`, which share point `pi` with `owners`, are pinned there:
/// by a revolute joint between them, or each to a third owner.
fn pinned(joints: &[Joint], owners: &[usize], pi: usize, l1: usize, l2: usize) -> bool {
    let pinned = joints.iter().any(|j| {
        j.kind == JointKind::Revolute
            && j.point == pi
            && ((j.a == l1 && j.b == l2) || (j.a == l2 && j.b == l1))
    });
    // Links pinned through a third at the same point (a ternary pin) are fine.
    let via_third = owners.iter().any(|&l3| {
        l3 != l1
            && l3 != l2
            && [l1, l2].iter().all(|&lx| {
                joints.iter().any(|j| {
                    j.kind == JointKind::Revolute
                        && j.point == pi
                        && ((j.a == lx && j.b == l3) || (j.a == l3 && j.b == lx))
                })
            })
    });
    pinned || via_third
}
