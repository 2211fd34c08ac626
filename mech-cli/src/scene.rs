//! The linkage as shapes: one [`Frame`] per input value, every frame with the same shapes
//! in the same order (so that a frame sequence animates attribute by attribute), in the
//! coordinates of the drawing (m, y up). [`crate::svg`] writes them.
//!
//! - a link with two points: a bar between them; with more: the polygon of its points;
//!   a link with one point (a slider block): a rectangle along its guide;
//! - a revolute joint: a pin (a small circle) at its point; on the ground, a pivot (a
//!   triangle under the pin, hatched by [`crate::svg`]);
//! - a prismatic joint: the guide line through its point along the axis (turning with the
//!   guide's link); a pin in a slot: the slot, two lines along the axis;
//! - a gear pair or rack: each gear's pitch circle (a polygon) with a spoke that turns
//!   with it;
//! - a spring: a zigzag between its points; a damper: a line between them;
//! - a rolling wheel: its circle with a spoke, and the track under it;
//! - a cam: its profile, turning with it, and a roller follower's roller;
//! - every point: its name.

use crate::Failure;
use mech_core::kernel::link_state::{perp, rotate, V2};
use mech_core::model::{JointKind, Model};
use mech_core::Mechanism;

/// What a shape is, for its style.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Role {
    /// A link with two points.
    Bar,
    /// A link with three or more points.
    Plate,
    /// A slider block.
    Block,
    /// A guide or a slot line.
    Guide,
    /// A pin of a revolute joint.
    Pin,
    /// A ground pivot's support.
    Pivot,
    /// A point's name.
    Label,
    /// The path of a point.
    Path,
    /// A reaction arrow.
    Arrow,
    /// A gear's pitch circle.
    Gear,
    /// A spring (a zigzag).
    Spring,
    /// A damper or a gear's spoke (a line).
    Damper,
}

/// One shape: its role, its index among the link (or joint, point) it draws, a name
/// (the link, joint or point), and its points (m).
#[derive(Clone, Debug, PartialEq)]
pub struct Shape {
    /// Style.
    pub role: Role,
    /// The link, joint or point it draws.
    pub name: String,
    /// Its vertices (a circle: the centre; a label: the anchor), m.
    pub points: Vec<V2>,
}

/// The shapes of the linkage at one input value.
#[derive(Clone, Debug, PartialEq)]
pub struct Frame {
    /// The input values.
    pub q: Vec<f64>,
    /// The shapes, in drawing order (links, guides, pivots, pins, labels).
    pub shapes: Vec<Shape>,
}

/// Half the length of a guide line drawn through a slider, as a fraction of the drawing.
const GUIDE: f64 = 0.35;

/// A block's half length and half width, as fractions of the drawing.
const BLOCK: (f64, f64) = (0.045, 0.025);

/// The size of the drawing (m): its largest distance between two points.
pub fn size(model: &Model) -> f64 {
    model.scale()
}

/// The rotation of link `l` from the drawing at `angle` (unit complex number).
fn turn(model: &Model, l: usize, angle: f64) -> V2 {
    let d = angle - model.reference_angle(l);
    V2::new(d.cos(), d.sin())
}

/// The frame of mechanism `m` at inputs `q`.
pub fn frame(m: &Mechanism, q: &[f64]) -> Result<Frame, Failure> {
    let model = m.model();
    let pose = m.pose(q)?;
    let at = |p: usize| pose.points[p].pos;
    let s = size(model);
    let mut shapes = Vec::new();
    // Guides and slots first (under the links).
    for j in &model.joints {
        if j.kind == JointKind::Cam {
            // The cam's surface, turning with the cam about its centre.
            if let (Some(g), Some(c)) = (mech_core::plan::geometry::cam_geom(model, j), &j.cam) {
                let o = at(c.centre);
                let turn = pose.links[j.a].angle - model.reference_angle(j.a);
                let (sn, cs) = turn.sin_cos();
                let rot = V2::new(cs, sn);
                let u = g.axis;
                let xh = V2::new(u.y, -u.x);
                let points = g
                    .profile
                    .points(180)
                    .iter()
                    .map(|p| o + rotate(rot, xh * p.contact[0] + u * p.contact[1]))
                    .collect();
                shapes.push(Shape {
                    role: Role::Gear,
                    name: j.name.clone(),
                    points,
                });
                // A roller: its circle about the pitch point, on the cam's surface.
                if let mech_core::elements::cam::Face::Roller(r) = g.profile.face {
                    let p = at(j.point);
                    shapes.push(Shape {
                        role: Role::Gear,
                        name: j.name.clone(),
                        points: (0..48)
                            .map(|i| {
                                let t = std::f64::consts::TAU * i as f64 / 48.0;
                                p + V2::new(t.cos(), t.sin()) * r
                            })
                            .collect(),
                    });
                }
            }
            continue;
        }
        if j.kind == JointKind::Revolute || j.kind.mesh() {
            continue;
        }
        let n = if j.around.is_some() {
            V2::new(1.0, 0.0)
        } else {
            V2::new(j.axis[0], j.axis[1]).normalize()
        };
        let u = rotate(turn(model, j.a, pose.links[j.a].angle), n);
        let p = at(j.point);
        let half = GUIDE * s;
        if j.kind == JointKind::Rolling {
            // The track (under the wheel, or its circle), and the wheel with a spoke that
            // turns with it.
            if let Some((d, inside)) = j.around {
                let c = at(d);
                let rho = (model.points[j.point].pos[0] - model.points[d].pos[0])
                    .hypot(model.points[j.point].pos[1] - model.points[d].pos[1]);
                let big = if inside {
                    rho + j.radius
                } else {
                    rho - j.radius
                };
                shapes.push(Shape {
                    role: Role::Path,
                    name: j.name.clone(),
                    points: (0..=96)
                        .map(|i| {
                            let t = std::f64::consts::TAU * i as f64 / 96.0;
                            c + V2::new(t.cos(), t.sin()) * big
                        })
                        .collect(),
                });
            } else {
                let k = p - perp(u) * j.radius;
                shapes.push(Shape {
                    role: Role::Guide,
                    name: j.name.clone(),
                    points: vec![k - u * half, k + u * half],
                });
            }
            let rot = turn(model, j.b, pose.links[j.b].angle);
            let circle = (0..48)
                .map(|i| {
                    let t = std::f64::consts::TAU * i as f64 / 48.0;
                    p + rotate(rot, V2::new(t.cos(), t.sin())) * j.radius
                })
                .collect();
            shapes.push(Shape {
                role: Role::Gear,
                name: j.name.clone(),
                points: circle,
            });
            shapes.push(Shape {
                role: Role::Damper,
                name: j.name.clone(),
                points: vec![p, p + rotate(rot, V2::new(j.radius, 0.0))],
            });
            continue;
        }
        let (a, b) = (p - u * half, p + u * half);
        if j.kind == JointKind::Prismatic {
            shapes.push(Shape {
                role: Role::Guide,
                name: j.name.clone(),
                points: vec![a, b],
            });
        } else {
            let w = perp(u) * (0.012 * s);
            shapes.push(Shape {
                role: Role::Guide,
                name: j.name.clone(),
                points: vec![a + w, b + w],
            });
            shapes.push(Shape {
                role: Role::Guide,
                name: j.name.clone(),
                points: vec![a - w, b - w],
            });
        }
    }
    // Pitch circles with a spoke, under the links.
    for j in &model.joints {
        let Some(mesh) = &j.mesh else { continue };
        let gears = [
            (j.a, mesh.centres[0], mesh.ra),
            (j.b, mesh.centres[1], mesh.rb),
        ];
        for &(l, centre, r) in gears.iter().filter(|g| g.2 > 0.0 && g.0 != 0) {
            let c = at(centre);
            let rot = turn(model, l, pose.links[l].angle);
            let circle = (0..48)
                .map(|k| {
                    let t = std::f64::consts::TAU * k as f64 / 48.0;
                    c + rotate(rot, V2::new(t.cos(), t.sin())) * r
                })
                .collect();
            shapes.push(Shape {
                role: Role::Gear,
                name: j.name.clone(),
                points: circle,
            });
            shapes.push(Shape {
                role: Role::Damper,
                name: j.name.clone(),
                points: vec![c, c + rotate(rot, V2::new(r, 0.0))],
            });
        }
    }
    // Springs and dampers, between their points.
    for e in &model.elements {
        let Some([p, q]) = e.points else { continue };
        let (a, b) = (at(p), at(q));
        if e.kind == mech_core::model::ElementKind::Spring {
            let d = b - a;
            let w = perp(d.normalize()) * (0.015 * s);
            let zig = (0..=12)
                .map(|k| {
                    let side = match k {
                        0 | 12 => 0.0,
                        k if k % 2 == 1 => 1.0,
                        _ => -1.0,
                    };
                    a + d * (k as f64 / 12.0) + w * side
                })
                .collect();
            shapes.push(Shape {
                role: Role::Spring,
                name: e.name.clone(),
                points: zig,
            });
        } else {
            shapes.push(Shape {
                role: Role::Damper,
                name: e.name.clone(),
                points: vec![a, b],
            });
        }
    }
    for (l, link) in model.links.iter().enumerate().skip(1) {
        let pts: Vec<V2> = link.points.iter().map(|&p| at(p)).collect();
        match pts.len() {
            0 => {}
            1 => {
                // A slider block along the guide it slides on, else square to the frame.
                let guide = model
                    .joints
                    .iter()
                    .find(|j| j.kind == JointKind::Prismatic && (j.b == l || j.a == l));
                let u = match guide {
                    Some(j) => rotate(
                        turn(model, j.a, pose.links[j.a].angle),
                        V2::new(j.axis[0], j.axis[1]).normalize(),
                    ),
                    None => turn(model, l, pose.links[l].angle),
                };
                let (h, w) = (u * (BLOCK.0 * s), perp(u) * (BLOCK.1 * s));
                let c = pts[0];
                shapes.push(Shape {
                    role: Role::Block,
                    name: link.name.clone(),
                    points: vec![c - h - w, c + h - w, c + h + w, c - h + w],
                });
            }
            2 => shapes.push(Shape {
                role: Role::Bar,
                name: link.name.clone(),
                points: pts,
            }),
            _ => shapes.push(Shape {
                role: Role::Plate,
                name: link.name.clone(),
                points: pts,
            }),
        }
    }
    for j in &model.joints {
        if j.kind != JointKind::Revolute {
            continue;
        }
        let p = at(j.point);
        if j.a == 0 || j.b == 0 {
            let (w, h) = (0.035 * s, 0.05 * s);
            shapes.push(Shape {
                role: Role::Pivot,
                name: j.name.clone(),
                points: vec![p, p + V2::new(-w, -h), p + V2::new(w, -h)],
            });
        }
        shapes.push(Shape {
            role: Role::Pin,
            name: j.name.clone(),
            points: vec![p],
        });
    }
    for (i, p) in model.points.iter().enumerate() {
        shapes.push(Shape {
            role: Role::Label,
            name: p.name.clone(),
            points: vec![at(i) + V2::new(0.015 * s, 0.015 * s)],
        });
    }
    Ok(Frame {
        q: q.to_vec(),
        shapes,
    })
}

/// The frames of `m` at each of `qs`; an input where the mechanism does not assemble
/// repeats the previous frame (the first solvable one when it is the first).
pub fn frames(m: &Mechanism, qs: &[Vec<f64>]) -> Result<Vec<Frame>, Failure> {
    held(qs.iter().map(|q| frame(m, q).ok()).collect())
}

/// The frames of an animation from the solved ones: where an input does not assemble, the
/// last frame that did (the first that did before it); an error when none did.
pub fn held(solved: Vec<Option<Frame>>) -> Result<Vec<Frame>, Failure> {
    let first = solved.iter().flatten().next().cloned().ok_or_else(|| {
        Failure::mechanism("the mechanism does not assemble at any of these inputs")
    })?;
    let mut last = first;
    Ok(solved
        .into_iter()
        .map(|f| {
            if let Some(f) = f {
                last = f;
            }
            last.clone()
        })
        .collect())
}

/// The path of point `name` over `qs` (the inputs where it assembles).
pub fn path(m: &Mechanism, name: &str, qs: &[Vec<f64>]) -> Result<Shape, Failure> {
    let i = m
        .model()
        .point_index(name)
        .ok_or_else(|| no_such_point(name, m.model().points.iter().map(|p| p.name.as_str())))?;
    let points = qs
        .iter()
        .filter_map(|q| m.pose(q).ok())
        .map(|p| p.points[i].pos)
        .collect();
    Ok(Shape {
        role: Role::Path,
        name: name.to_string(),
        points,
    })
}

/// The reaction arrows of `m` at (q, q̇, q̈) with `loads`: at each joint point, the force
/// by the joint's first link on its second, scaled so that the largest is `length` m.
pub fn arrows(
    m: &Mechanism,
    q: &[f64],
    qd: &[f64],
    qdd: &[f64],
    loads: &mech_core::runtime::mechanism::Loads,
    length: f64,
) -> Result<Vec<Shape>, Failure> {
    let motion = m.kinematics(q, qd, qdd)?;
    let forces = m.kinetostatics(&motion, loads)?;
    let Some(scale) = arrow_scale(forces.joints.iter().map(|r| r.force.norm()), length) else {
        return Ok(Vec::new());
    };
    Ok(m.model()
        .joints
        .iter()
        .zip(&forces.joints)
        .map(|(j, r)| {
            let p = motion.points[j.point].pos;
            Shape {
                role: Role::Arrow,
                name: j.name.clone(),
                points: vec![p, p + r.force * scale],
            }
        })
        .collect())
}

/// The usage error of `--path NAME` when the mechanism has no point `name`, listing its
/// `points` (planar and spatial).
pub fn no_such_point<'a>(name: &str, points: impl Iterator<Item = &'a str>) -> Failure {
    let names: Vec<&str> = points.collect();
    Failure::usage(format!(
        "--path {name}: no such point; the points are {} (name one of them)",
        names.join(", ")
    ))
}

/// The scale (m per N) of the reaction arrows with force magnitudes `norms`: the largest
/// is drawn `length` m long; `None` when every force is zero (no arrow is drawn).
pub fn arrow_scale(norms: impl Iterator<Item = f64>, length: f64) -> Option<f64> {
    let largest = norms.fold(0.0, f64::max);
    (largest > 0.0).then(|| length / largest)
}
