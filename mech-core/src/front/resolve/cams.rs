//! The cams of [`super::resolve`]: the carrier the cam is pinned to and the follower
//! slides on (or is pinned to), the lifts' kind, and the pitch point.

use super::Diagnostic;
use crate::model::*;

/// Cams: the carrier the cam is pinned to and the follower slides on (or is pinned to).
pub(super) fn cams<S: Clone>(
    d: &Description<S>,
    joints: &mut [Joint],
    links: &[Link],
    errs: &mut Vec<Diagnostic<S>>,
) {
    for (k, j) in d.joints.iter().enumerate() {
        let Some(decl) = &j.cam else { continue };
        cam(d, k, decl, joints, links, errs);
    }
}

/// The carrier, the cam's centre and the follower's slide (or pin) of a cam between
/// links `a` (the cam) and `b` (the follower).
fn carrier_of(joints: &[Joint], a: usize, b: usize) -> Option<(usize, usize, usize)> {
    [JointKind::Prismatic, JointKind::Revolute]
        .iter()
        .find_map(|&kind| {
            joints.iter().enumerate().find_map(|(i, sl)| {
                if sl.kind != kind || !(sl.a == b || sl.b == b) {
                    return None;
                }
                let c = if sl.a == b { sl.b } else { sl.a };
                let pin = joints.iter().find(|r| {
                    c != a
                        && r.kind == JointKind::Revolute
                        && ((r.a == c && r.b == a) || (r.b == c && r.a == a))
                })?;
                Some((c, pin.point, i))
            })
        })
}

/// Cam joint `k`, declared by `decl`: its [`CamSpec`], or a diagnostic.
fn cam<S: Clone>(
    d: &Description<S>,
    k: usize,
    decl: &CamDecl<S>,
    joints: &mut [Joint],
    links: &[Link],
    errs: &mut Vec<Diagnostic<S>>,
) {
    let j = &d.joints[k];
    let (a, b) = (joints[k].a, joints[k].b);
    if a == b {
        return;
    }
    let found = carrier_of(joints, a, b);
    let Some((carrier, centre, slide)) = found else {
        errs.push(Diagnostic::at(
            j.kind_span.clone(),
            format!(
                "cam `{}`: the follower `{}` must slide (a prismatic joint) on the link the cam `{}` is pinned to (a revolute joint at the cam's centre), or be pinned to it (an oscillating follower); no link carries both",
                j.name.text, links[b].name, links[a].name
            ),
        ));
        return;
    };
    let rocker = joints[slide].kind == JointKind::Revolute;
    let lifts = decl.angular.unwrap_or(rocker);
    if lifts != rocker {
        let (how, why) = if rocker {
            ("angles (`rise 15 deg`)", "turns about its pin")
        } else {
            ("lengths (`rise 10 mm`)", "slides on its prismatic joint")
        };
        errs.push(Diagnostic::at(
            decl.law_span.clone(),
            format!(
                "cam `{}`: its follower `{}` {why} `{}` on `{}`, so its lifts are {how}, but they are written as {}",
                j.name.text,
                links[b].name,
                d.joints[slide].name.text,
                links[carrier].name,
                if lifts { "angles" } else { "lengths" }
            ),
        ));
        return;
    }
    match (&j.at, rocker) {
        (Some(at), false) => {
            errs.push(Diagnostic::at(
                at.span.clone(),
                format!("cam `{}` takes no `at`: its follower `{}` slides, and its pitch point is its prismatic joint's point", j.name.text, links[b].name),
            ));
            return;
        }
        (None, true) => {
            errs.push(Diagnostic::at(
                j.kind_span.clone(),
                format!("cam `{}`: its follower `{}` is pinned to `{}` (an oscillating follower), so the cam needs its pitch point: write `cam({}, {}) at P ..`, P the roller's centre (the knife's edge, the flat face's point on the base circle) in the drawing", j.name.text, links[b].name, links[carrier].name, links[a].name, links[b].name),
            ));
            return;
        }
        (None, false) => joints[k].point = joints[slide].point,
        (Some(_), true) => {}
    }
    joints[k].cam = Some(Box::new(CamSpec {
        base_radius: decl.base_radius.value,
        face: decl.face,
        segments: decl.segments.iter().map(|(g, _)| *g).collect(),
        table: decl.table.clone(),
        carrier,
        centre,
        slide,
        angular: rocker,
    }));
}
