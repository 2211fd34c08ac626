//! From the drawing to the local geometry the solvers use: link anchors, joint local
//! vectors, sliding axes, the constraint list, the drawing's states.

use crate::kernel::constraints::{Con, ConKind, JointGeom};
use crate::kernel::link_state::{LinkState, V2};
use crate::model::{JointKind, Model};

/// The reference anchor of link `l` (m): its first point, else its cg; the origin for the ground.
pub fn anchor(model: &Model, l: usize) -> V2 {
    if l == 0 {
        return V2::zeros();
    }
    let link = &model.links[l];
    let p = link
        .points
        .first()
        .map(|&p| model.points[p].pos)
        .unwrap_or(link.cg);
    V2::new(p[0], p[1])
}

/// Local vector in link `l` of a global reference position `p`.
pub fn local(model: &Model, l: usize, p: [f64; 2]) -> V2 {
    V2::new(p[0], p[1]) - anchor(model, l)
}

/// The pitch point P and the common tangent t (unit) of mesh joint `j` in the drawing
/// (`crate::elements::gears`): for a gear pair from its centres and radii, for a rack on the
/// perpendicular from the pinion's centre to the rack's axis, on the rack's side.
pub fn pitch_point(model: &Model, j: usize) -> Option<(V2, V2)> {
    let jt = &model.joints[j];
    let m = jt.mesh.as_ref()?;
    let pos = |p: usize| V2::new(model.points[p].pos[0], model.points[p].pos[1]);
    let (oa, ob) = (pos(m.centres[0]), pos(m.centres[1]));
    if jt.kind == JointKind::Rack {
        let slide = model.joints.iter().find(|o| {
            o.kind == JointKind::Prismatic
                && ((o.a == jt.b && o.b == m.carrier) || (o.b == jt.b && o.a == m.carrier))
        })?;
        let u = V2::new(slide.axis[0], slide.axis[1]).normalize();
        let side = if crate::kernel::link_state::cross(u, ob - oa) >= 0.0 {
            1.0
        } else {
            -1.0
        };
        return Some((oa + crate::kernel::link_state::perp(u) * (side * m.ra), u));
    }
    let w = (ob - oa).normalize();
    let p = if !m.internal {
        oa + w * m.ra
    } else if m.ra < m.rb {
        oa - w * m.ra
    } else {
        ob + w * m.rb
    };
    Some((p, crate::kernel::link_state::perp(w)))
}

/// The local geometry of joint `j`.
pub fn joint_geom(model: &Model, j: usize) -> JointGeom {
    let jt = &model.joints[j];
    if let (Some(g), Some(c)) = (cam_geom(model, jt), jt.cam.as_ref()) {
        // The contact K and the common normal n in the drawing: the rank test's row.
        let o = model.points[c.centre].pos;
        let (u, xh) = (g.axis, V2::new(g.axis.y, -g.axis.x));
        let k = g.profile.contact(0.0);
        let kw = V2::new(o[0], o[1]) + xh * k.contact.x + u * k.contact.y;
        return JointGeom {
            a: jt.a,
            b: jt.b,
            da: local(model, jt.a, [kw.x, kw.y]),
            db: local(model, jt.b, [kw.x, kw.y]),
            axis: xh * k.normal.x + u * k.normal.y,
            q_ref: 0.0,
            radius: 0.0,
            around: 0.0,
        };
    }
    if let Some((d, inside)) = jt.around {
        let (pd, pc) = (model.points[d].pos, model.points[jt.point].pos);
        return JointGeom {
            a: jt.a,
            b: jt.b,
            da: local(model, jt.a, pd),
            db: local(model, jt.b, pc),
            // C − D in the drawing (the track's reference frame): ρ = its length.
            axis: V2::new(pc[0] - pd[0], pc[1] - pd[1]),
            q_ref: 0.0,
            radius: jt.radius,
            around: if inside { -1.0 } else { 1.0 },
        };
    }
    if let Some((p, t)) = pitch_point(model, j) {
        return JointGeom {
            a: jt.a,
            b: jt.b,
            da: local(model, jt.a, [p.x, p.y]),
            db: local(model, jt.b, [p.x, p.y]),
            axis: t,
            q_ref: 0.0,
            radius: 0.0,
            around: 0.0,
        };
    }
    let p = model.points[jt.point].pos;
    let ax = V2::new(jt.axis[0], jt.axis[1]);
    let n = ax.norm();
    JointGeom {
        a: jt.a,
        b: jt.b,
        da: local(model, jt.a, p),
        db: local(model, jt.b, p),
        axis: if n > 0.0 { ax / n } else { V2::zeros() },
        q_ref: match model.inputs.iter().position(|&i| i == j) {
            Some(k) => model.reference_input(k),
            None if jt.kind == JointKind::Revolute => {
                model.reference_angle(jt.b) - model.reference_angle(jt.a)
            }
            None => 0.0,
        },
        radius: jt.radius,
        around: 0.0,
    }
}

/// Every joint's geometry, in joint order.
pub fn joint_geoms(model: &Model) -> Vec<JointGeom> {
    (0..model.joints.len())
        .map(|j| joint_geom(model, j))
        .collect()
}

/// The constraints a joint imposes: its own kind, plus a driver row when it is input `k`.
pub fn joint_cons(model: &Model, j: usize) -> Vec<Con> {
    let kind = model.joints[j].kind;
    let mut out = vec![Con {
        joint: j,
        kind: match kind {
            JointKind::Revolute => ConKind::Revolute,
            JointKind::Prismatic => ConKind::Prismatic,
            JointKind::PinInSlot => ConKind::Slot,
            JointKind::Gear | JointKind::Rack | JointKind::Cam => ConKind::Mesh,
            JointKind::Rolling => ConKind::Rolling,
        },
    }];
    if let Some(k) = model.inputs.iter().position(|&i| i == j) {
        out.push(Con {
            joint: j,
            kind: if kind == JointKind::Revolute {
                ConKind::DriveRevolute(k)
            } else {
                ConKind::DrivePrismatic(k)
            },
        });
    }
    out
}

/// Every constraint of the mechanism (joints, then their drivers), in joint order.
pub fn all_cons(model: &Model) -> Vec<Con> {
    (0..model.joints.len())
        .flat_map(|j| joint_cons(model, j))
        .collect()
}

/// The links' states in the drawing (at rest).
pub fn drawing_states(model: &Model) -> Vec<LinkState> {
    (0..model.links.len())
        .map(|l| LinkState::at(anchor(model, l)))
        .collect()
}

/// A cam's geometry (`crate::elements::cam::CamGeom`) from the drawing. A translating follower: û
/// along its slide from the cam's centre O towards its point P, the offset
/// e = (P − O)·x̂ with x̂ = (û_y, −û_x). A rocker (pinned to the carrier at A): û from O
/// towards its pitch point P, the pivot (A − O) in (x̂, û), σ = −sign(A_x). The motion law
/// from its segments or table.
pub fn cam_geom(model: &Model, jt: &crate::model::Joint) -> Option<crate::elements::cam::CamGeom> {
    let c = jt.cam.as_ref()?;
    let slide = &model.joints[c.slide];
    let (o, p) = (model.points[c.centre].pos, model.points[jt.point].pos);
    let op = V2::new(p[0] - o[0], p[1] - o[1]);
    let law = crate::elements::cam::law_of(&c.segments, &c.table, c.angular).ok()?;
    let (u, offset, rocker) = if slide.kind == JointKind::Revolute {
        let u = op.try_normalize(0.0)?;
        let xh = V2::new(u.y, -u.x);
        let a = model.points[slide.point].pos;
        let oa = V2::new(a[0] - o[0], a[1] - o[1]);
        let pivot = [oa.dot(&xh), oa.dot(&u)];
        let sign = if pivot[0] > 0.0 { -1.0 } else { 1.0 };
        (u, 0.0, Some(crate::elements::cam::Rocker { pivot, sign }))
    } else {
        let a = V2::new(slide.axis[0], slide.axis[1]).normalize();
        let u = if op.dot(&a) >= 0.0 { a } else { -a };
        (u, op.dot(&V2::new(u.y, -u.x)), None)
    };
    Some(crate::elements::cam::CamGeom {
        profile: crate::elements::cam::Profile {
            law,
            base_radius: c.base_radius,
            offset,
            face: c.face,
            rocker,
        },
        axis: u,
        centre: local(model, jt.a, o),
    })
}
