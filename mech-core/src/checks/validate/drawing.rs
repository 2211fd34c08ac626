//! Check 5 of `docs/conventions.md#checks`: the drawing's numbers are consistent (masses,
//! coordinates, axes, distinct points; force elements, gear pairs, racks, cams, rolling
//! joints).

use super::{AXIS_TOL, COINCIDENT_TOL, MESH_TOL};
use crate::front::resolve::{Culprit, Issue};
use crate::model::{ElementKind, JointKind, Model};

/// Part of check 5: a cam's law covers one turn and returns to its start, its base
/// radius and roller are > 0, the profile is not undercut, and the drawing sits the
/// follower on the base circle — a translating follower's point P at √(R_p² − e²) from
/// the foot of the cam's centre on its axis (R_p = R_b + r, e the offset), a rocker's pitch
/// point P at R_p from the centre, its pivot off the line through them — to [`MESH_TOL`] ×
/// the drawing's scale (`docs/conventions.md#cams`).
fn cam_numbers(model: &Model) -> Vec<Issue> {
    let mut out = Vec::new();
    for (j, jt) in model.joints.iter().enumerate() {
        let Some(c) = &jt.cam else { continue };
        let mut bad = |message: String| {
            out.push(Issue {
                culprits: vec![Culprit::Joint(j)],
                message,
            })
        };
        if let Err(e) = crate::elements::cam::law_of(&c.segments, &c.table, c.angular) {
            bad(format!("cam `{}`: its law: {e}", jt.name));
            continue;
        }
        let r = match c.face {
            crate::elements::cam::Face::Roller(r) => r,
            _ => 0.0,
        };
        if !(c.base_radius.is_finite() && c.base_radius > 0.0 && r.is_finite() && r >= 0.0) {
            bad(format!("cam `{}` has base radius {} m and roller {} m: both must be finite, the base radius > 0", jt.name, c.base_radius, r));
            continue;
        }
        let (o, p) = (model.points[c.centre].pos, model.points[jt.point].pos);
        let rp = c.base_radius + r;
        let tol = MESH_TOL * model.scale();
        if c.angular {
            let dist = (p[0] - o[0]).hypot(p[1] - o[1]);
            if !((dist - rp).abs() <= tol) {
                bad(format!(
                    "cam `{}`: the rocker's pitch point `{}` is {:.4} mm from the cam's centre, but in the drawing it sits on the prime circle, R_b + r = {:.4} mm: move it, or change the base radius",
                    jt.name, model.points[jt.point].name, dist * 1e3, rp * 1e3
                ));
                continue;
            }
        }
        let Some(g) = crate::plan::geometry::cam_geom(model, jt) else {
            continue;
        };
        if let Some(k) = g.profile.rocker {
            if !(k.pivot[0].abs() > tol) {
                bad(format!(
                    "cam `{}`: the rocker's pivot `{}` lies on the line from the cam's centre through its pitch point `{}` ({:.4} mm off it): a lift could not turn the rocker (the cam would push along its arm); move the pivot sideways",
                    jt.name, model.points[model.joints[c.slide].point].name, model.points[jt.point].name, k.pivot[0].abs() * 1e3
                ));
                continue;
            }
        }
        let chk = g.profile.check(720);
        if let Some(theta) = chk.missing {
            let [_, s1, ..] = g.profile.law.eval(theta);
            bad(format!(
                "cam `{}` has no profile near {:.1}°: the follower turns there at {:.4} rad per radian of cam angle, as fast as the cam (its face would move with the cam's surface): lower the lift or lengthen the segment",
                jt.name,
                theta.to_degrees(),
                s1.abs()
            ));
            continue;
        }
        if chk.undercut {
            let smallest = chk.min_convex_radius;
            bad(match c.face {
                crate::elements::cam::Face::Flat => format!("cam `{}`: its flat-faced follower would need a cusp in the profile (radius of curvature ≤ 0 near {:.1}°): enlarge the base radius", jt.name, smallest.1.to_degrees()),
                _ => format!("cam `{}` is undercut: its roller ({:.4} mm) is larger than the pitch curve's radius of curvature near {:.1}° (the cam surface's radius {:.4} mm ≤ 0): use a smaller roller or a larger base circle", jt.name, r * 1e3, smallest.1.to_degrees(), smallest.0 * 1e3),
            });
            continue;
        }
        if g.profile.rocker.is_some() {
            continue;
        }
        let e = g.profile.offset;
        if !(e.abs() < rp) {
            bad(format!("cam `{}`: the follower's axis passes {:.4} mm from the cam's centre, outside the prime circle (R_b + r = {:.4} mm)", jt.name, e.abs() * 1e3, rp * 1e3));
            continue;
        }
        let u = g.axis;
        let along = (p[0] - o[0]) * u.x + (p[1] - o[1]) * u.y;
        let want = (rp * rp - e * e).sqrt();
        if !((along - want).abs() <= tol) {
            bad(format!(
                "cam `{}`: the follower's point `{}` is {:.4} mm along its axis from the cam's centre, but on the base circle it sits at √(R_p² − e²) = {:.4} mm (R_p = {:.4} mm, e = {:.4} mm): move it, or change the base radius",
                jt.name, model.points[jt.point].name, along * 1e3, want * 1e3, rp * 1e3, e * 1e3
            ));
        }
    }
    out
}

/// Part of check 5: every force element's numbers are finite, its stiffness and damping
/// ≥ 0, a linear spring's free length ≥ 0 (`docs/conventions.md#elements`).
fn element_numbers(model: &Model) -> Vec<Issue> {
    let mut out = Vec::new();
    for (i, e) in model.elements.iter().enumerate() {
        let kind = e.kind.keyword();
        let (coef, unit) = match e.kind {
            ElementKind::Spring => (e.stiffness, "N/m"),
            ElementKind::TorsionSpring => (e.stiffness, "N·m/rad"),
            ElementKind::Damper => (e.damping, "N·s/m"),
            ElementKind::RotaryDamper => (e.damping, "N·m·s/rad"),
        };
        let what = if e.kind.spring() {
            "stiffness"
        } else {
            "damping"
        };
        let finite = coef.is_finite() && e.stiffness.is_finite() && e.damping.is_finite();
        if !finite || coef < 0.0 {
            out.push(Issue {
                culprits: vec![Culprit::Element(i)],
                message: format!("{kind} `{}` has {what} {coef} {unit}: it must be finite and ≥ 0 (a negative {what} would feed energy into the machine)", e.name),
            });
        }
        if !e.free.is_finite() || (e.kind == ElementKind::Spring && e.free < 0.0) {
            out.push(Issue {
                culprits: vec![Culprit::Element(i)],
                message: format!(
                    "{kind} `{}` has free {} {}: it must be finite{}",
                    e.name,
                    if e.kind.linear() { "length" } else { "angle" },
                    e.free,
                    if e.kind.linear() { " and ≥ 0 m (a preload larger than stiffness × drawn length gives a negative one)" } else { " (rad)" }
                ),
            });
        }
    }
    out
}

/// Part of check 5: a gear pair's or rack's pitch radii are finite and > 0, its pressure
/// angle in [0°, 45°), and the drawing meshes: the centre distance equals r_a + r_b
/// (|r_a − r_b| for an internal pair) to [`MESH_TOL`] × [`Model::scale`]
/// (`docs/conventions.md#gears`).
fn mesh_numbers(model: &Model) -> Vec<Issue> {
    let mut out = Vec::new();
    for (j, jt) in model.joints.iter().enumerate() {
        let Some(m) = &jt.mesh else { continue };
        let kind = jt.kind.keyword();
        let radii_ok = m.ra.is_finite()
            && m.ra > 0.0
            && (jt.kind == JointKind::Rack || (m.rb.is_finite() && m.rb > 0.0));
        if !radii_ok {
            out.push(Issue {
                culprits: vec![Culprit::Joint(j)],
                message: if jt.kind == JointKind::Rack {
                    format!(
                        "{kind} `{}` has pinion radius {} m: a pitch radius must be finite and > 0",
                        jt.name, m.ra
                    )
                } else {
                    format!(
                        "{kind} `{}` has pitch radii ({}, {}) m: each must be finite and > 0",
                        jt.name, m.ra, m.rb
                    )
                },
            });
            continue;
        }
        if m.internal && m.ra == m.rb {
            out.push(Issue {
                culprits: vec![Culprit::Joint(j)],
                message: format!("internal {kind} `{}` has equal pitch radii ({} m): the ring must be larger than the gear inside it", jt.name, m.ra),
            });
            continue;
        }
        if !(m.pressure_angle >= 0.0 && m.pressure_angle < 45f64.to_radians()) {
            out.push(Issue {
                culprits: vec![Culprit::Joint(j)],
                message: format!("{kind} `{}` has pressure angle {:.3}°: it must be in [0°, 45°) (20° is standard)", jt.name, m.pressure_angle.to_degrees()),
            });
        }
        let (pa, pb) = (
            model.points[m.centres[0]].pos,
            model.points[m.centres[1]].pos,
        );
        if !(pa.iter().chain(pb.iter()).all(|v| v.is_finite())) {
            continue;
        }
        let (name_a, name_b) = (
            &model.points[m.centres[0]].name,
            &model.points[m.centres[1]].name,
        );
        let tol = MESH_TOL * model.scale();
        if jt.kind == JointKind::Rack {
            continue;
        }
        let d = (pb[0] - pa[0]).hypot(pb[1] - pa[1]);
        let want = if m.internal {
            (m.rb - m.ra).abs()
        } else {
            m.ra + m.rb
        };
        if !((d - want).abs() <= tol) {
            let rule = if m.internal {
                "|r_a − r_b|"
            } else {
                "r_a + r_b"
            };
            out.push(Issue {
                culprits: vec![Culprit::Joint(j), Culprit::Point(m.centres[1])],
                message: format!(
                    "{kind} `{}` does not mesh in the drawing: its centres `{name_a}` and `{name_b}` are {:.4} mm apart, but {rule} = {:.4} mm for pitch radii ({:.4} mm, {:.4} mm); move a centre, or change the radii",
                    jt.name, d * 1e3, want * 1e3, m.ra * 1e3, m.rb * 1e3
                ),
            });
        }
    }
    out
}

/// Check 5 of `docs/conventions.md#checks`: the drawing is consistent.
///
/// - every mass (kg) and moment of inertia (kg·m²) is finite and ≥ 0;
/// - every point's coordinates (m), every cg (m) and the gravity (m/s²) are finite;
/// - every sliding axis `along (ux, uy)` (prismatic, pin in slot) is finite and not (near)
///   zero: |u| > [`AXIS_TOL`]. (The point of a sliding joint lies on its axis by
///   construction: the axis is the line through that point's reference position.)
/// - no two points of one link coincide: |P − Q| > [`COINCIDENT_TOL`] × [`Model::scale`]
///   (a zero-length link has no angle).
///
/// Returns one [`Issue`] per problem.
pub fn drawing(model: &Model) -> Vec<Issue> {
    let mut out = point_numbers(model);
    out.extend(link_numbers(model));
    out.extend(element_numbers(model));
    out.extend(gravity_numbers(model));
    out.extend(mesh_numbers(model));
    out.extend(cam_numbers(model));
    out.extend(rolling_numbers(model));
    out.extend(sliding_axes(model));
    out.extend(coincident_points(model));
    out.extend(crate::checks::magnitudes::check(model));
    out
}

/// Part of check 5: every point's coordinates are finite.
fn point_numbers(model: &Model) -> Vec<Issue> {
    let mut out = Vec::new();
    for (p, pt) in model.points.iter().enumerate() {
        if !pt.pos.iter().all(|v| v.is_finite()) {
            out.push(Issue {
                culprits: vec![Culprit::Point(p)],
                message: format!(
                    "point `{}` has coordinates ({}, {}) m: coordinates must be finite numbers",
                    pt.name, pt.pos[0], pt.pos[1]
                ),
            });
        }
    }
    out
}

/// Part of check 5: every mass, inertia and flywheel is finite and ≥ 0, every cg finite.
fn link_numbers(model: &Model) -> Vec<Issue> {
    let mut out = Vec::new();
    for (i, l) in model.links.iter().enumerate().skip(1) {
        if let Some(m) = l.mass {
            if !(m.is_finite() && m >= 0.0) {
                out.push(Issue {
                    culprits: vec![Culprit::Mass(i), Culprit::Link(i)],
                    message: format!(
                        "link `{}` has mass {m} kg: a mass must be finite and ≥ 0 (kg); correct it, or omit `mass` for a massless link",
                        l.name
                    ),
                });
            }
        }
        if !(l.inertia.is_finite() && l.inertia >= 0.0) {
            out.push(Issue {
                culprits: vec![Culprit::Inertia(i), Culprit::Link(i)],
                message: format!(
                    "link `{}` has moment of inertia {} kg·m² about its cg: an inertia must be finite and ≥ 0 (kg·m²); correct it, or omit `inertia` for 0",
                    l.name, l.inertia
                ),
            });
        }
        if !(l.flywheel.is_finite() && l.flywheel >= 0.0) {
            out.push(Issue {
                culprits: vec![Culprit::Link(i)],
                message: format!("link `{}` has a flywheel of {} kg·m²: a flywheel's inertia must be finite and ≥ 0 (kg·m²)", l.name, l.flywheel),
            });
        }
        if !l.cg.iter().all(|v| v.is_finite()) {
            out.push(Issue {
                culprits: vec![Culprit::Cg(i), Culprit::Link(i)],
                message: format!(
                    "link `{}` has cg ({}, {}) m: the cg must be finite",
                    l.name, l.cg[0], l.cg[1]
                ),
            });
        }
    }
    out
}

/// Part of check 5: the gravity is finite.
fn gravity_numbers(model: &Model) -> Vec<Issue> {
    let mut out = Vec::new();
    if let Some(g) = model.gravity {
        if !g.iter().all(|v| v.is_finite()) {
            out.push(Issue {
                culprits: vec![Culprit::Gravity],
                message: format!("gravity ({}, {}) m/s² must be finite", g[0], g[1]),
            });
        }
    }
    out
}

/// Part of check 5: a rolling joint's wheel radius is finite and > 0, and a wheel that
/// rolls outside a circle is off it.
fn rolling_numbers(model: &Model) -> Vec<Issue> {
    let mut out = Vec::new();
    for (j, jt) in model.joints.iter().enumerate() {
        if jt.kind == JointKind::Rolling && !(jt.radius.is_finite() && jt.radius > 0.0) {
            out.push(Issue {
                culprits: vec![Culprit::Joint(j)],
                message: format!(
                    "rolling joint `{}` has wheel radius {} m: it must be finite and > 0",
                    jt.name, jt.radius
                ),
            });
        } else if let Some((d, false)) = jt.around {
            let (pd, pc) = (model.points[d].pos, model.points[jt.point].pos);
            let rho = (pc[0] - pd[0]).hypot(pc[1] - pd[1]);
            if !(rho > jt.radius) {
                out.push(Issue {
                    culprits: vec![Culprit::Joint(j)],
                    message: format!(
                        "rolling joint `{}` rolls outside a circle about `{}` of radius |C D| − r = {:.4} mm − {:.4} mm ≤ 0: move the wheel's centre farther from the circle's centre, or roll `inside`",
                        jt.name, model.points[d].name, rho * 1e3, jt.radius * 1e3
                    ),
                });
            }
        }
    }
    out
}

/// Part of check 5: every sliding axis is finite and not (near) zero.
fn sliding_axes(model: &Model) -> Vec<Issue> {
    let mut out = Vec::new();
    for (j, jt) in model.joints.iter().enumerate() {
        if jt.kind == JointKind::Revolute
            || jt.kind.mesh()
            || jt.kind == JointKind::Cam
            || jt.around.is_some()
        {
            continue;
        }
        let [ux, uy] = jt.axis;
        let norm = ux.hypot(uy);
        let ok = ux.is_finite() && uy.is_finite() && norm > AXIS_TOL;
        if !ok {
            out.push(Issue {
                culprits: vec![Culprit::Axis(j), Culprit::Joint(j)],
                message: format!(
                    "{} joint `{}` has sliding axis along ({ux}, {uy}), which is {}: give a finite, non-zero direction, e.g. `along (1.0, 0.0)`",
                    jt.kind.keyword(),
                    jt.name,
                    if norm.is_finite() { "zero (no direction)" } else { "not finite" }
                ),
            });
        }
    }
    out
}

/// Part of check 5: no two points of one link coincide.
fn coincident_points(model: &Model) -> Vec<Issue> {
    let mut out = Vec::new();
    // Non-finite coordinates are reported above; the distance test needs a finite scale.
    let tol = COINCIDENT_TOL * model.scale();
    let finite = |p: usize| model.points[p].pos.iter().all(|v| v.is_finite());
    for (i, l) in model.links.iter().enumerate().filter(|_| tol.is_finite()) {
        for (w, &q) in l.points.iter().enumerate() {
            for &p in l.points[..w].iter().filter(|&&p| finite(p) && finite(q)) {
                let (a, b) = (model.points[p].pos, model.points[q].pos);
                let d = (a[0] - b[0]).hypot(a[1] - b[1]);
                if d <= tol {
                    out.push(Issue {
                        culprits: vec![Culprit::Point(q), Culprit::Link(i)],
                        message: format!(
                            "points `{}` and `{}` of link `{}` coincide at ({}, {}) m (closer than {COINCIDENT_TOL:e} × the drawing's size): the points of a link must be distinct (a zero-length link has no angle); use one point, or move one of them",
                            model.points[p].name, model.points[q].name, l.name, a[0], a[1]
                        ),
                    });
                }
            }
        }
    }
    out
}
