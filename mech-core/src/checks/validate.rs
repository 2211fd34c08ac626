//! The checks of `docs/conventions.md#checks` on a resolved [`Model`] (name resolution, check 1, is
//! [`crate::front::resolve`]): the drawing's consistency (check 5, [`drawing`]), Grübler's count
//! (check 2, [`crate::checks::grubler::check`]), structural redundancy (check 3,
//! [`crate::checks::pebble::check`]) and the rank of the constraint Jacobian at the drawing
//! (check 4, [`geometric`]). [`check`] runs them all and collects every [`Issue`].

use crate::front::resolve::{Culprit, Issue};
use crate::kernel::constraints::ConKind;
use crate::model::{ElementKind, JointKind, Model};
use crate::plan::geometry::{all_cons, drawing_states, joint_geoms};
use nalgebra::{DMatrix, DVector};

/// Relative tolerance of the rank decisions of [`geometric`]: a singular value counts as
/// zero when it is at most `RANK_TOL` × the largest one (the Jacobian is dimensionless,
/// see [`jacobian`]).
pub const RANK_TOL: f64 = 1e-9;

/// Relative tolerance below which two points of one link are coincident: `COINCIDENT_TOL`
/// × [`Model::scale`] (m).
pub const COINCIDENT_TOL: f64 = 1e-12;

/// A sliding axis `along (ux, uy)` shorter than this (dimensionless, the axis is a
/// direction) is taken as zero.
pub const AXIS_TOL: f64 = 1e-12;

/// A component of a null vector is significant when it exceeds this fraction of the
/// vector's largest component.
const SIGNIFICANT: f64 = 1e-6;

fn names(items: impl Iterator<Item = String>) -> String {
    items
        .map(|n| format!("`{n}`"))
        .collect::<Vec<_>>()
        .join(", ")
}

fn plural(n: usize, one: &str, many: &str) -> String {
    format!("{n} {}", if n == 1 { one } else { many })
}

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

/// How closely a gear pair's centre distance must match its pitch radii, relative to the
/// drawing's scale.
pub const MESH_TOL: f64 = 1e-9;

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
    out.extend(element_numbers(model));
    if let Some(g) = model.gravity {
        if !g.iter().all(|v| v.is_finite()) {
            out.push(Issue {
                culprits: vec![Culprit::Gravity],
                message: format!("gravity ({}, {}) m/s² must be finite", g[0], g[1]),
            });
        }
    }
    out.extend(mesh_numbers(model));
    out.extend(cam_numbers(model));
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
    out.extend(crate::checks::magnitudes::check(model));
    out
}

/// The dimensionless constraint Jacobian of the whole mechanism at the drawing.
#[derive(Clone, Debug, PartialEq)]
pub struct Jacobian {
    /// J: one row per scalar constraint of [`crate::plan::geometry::all_cons`] (joints and their
    /// drivers, in joint order), columns (x, y, φ·L) of links 1..N (the ground is fixed).
    /// Angle rows are multiplied by L, so every entry is dimensionless.
    pub matrix: DMatrix<f64>,
    /// The joint of each row.
    pub joint: Vec<usize>,
    /// Whether each row is a driver row (an input's equation).
    pub driver: Vec<bool>,
    /// L = [`Model::scale`], m.
    pub scale: f64,
}

impl Jacobian {
    /// The sub-matrix of the rows selected by `keep(row)`.
    fn select(&self, keep: impl Fn(usize) -> bool) -> (DMatrix<f64>, Vec<usize>) {
        let rows: Vec<usize> = (0..self.matrix.nrows()).filter(|&r| keep(r)).collect();
        let mut m = DMatrix::zeros(rows.len(), self.matrix.ncols());
        for (i, &r) in rows.iter().enumerate() {
            m.row_mut(i).copy_from(&self.matrix.row(r));
        }
        (m, rows)
    }
}

/// Assemble the constraint Jacobian ∂Φ/∂(x, y, φ) of every joint and driver at the
/// drawing from [`crate::kernel::constraints::scaled_rows`], scaled to be
/// dimensionless: columns (x, y, φ·L) of links 1..N, angle rows × L, L = [`Model::scale`] (m).
pub fn jacobian(model: &Model) -> Jacobian {
    let geoms = joint_geoms(model);
    let states = drawing_states(model);
    let cons = all_cons(model);
    let n = model.n_links();
    let cols = 3 * n.saturating_sub(1);
    let scale = model.scale();
    let total: usize = cons.iter().map(|c| c.kind.rows()).sum();
    let mut matrix = DMatrix::zeros(total, cols);
    let mut joint = Vec::with_capacity(total);
    let mut driver = Vec::with_capacity(total);
    let mut r = 0;
    for c in &cons {
        crate::kernel::constraints::scaled_rows(
            *c,
            &geoms[c.joint],
            &states,
            scale,
            |k, link, e| {
                if link != 0 && link < n {
                    for (i, x) in e.iter().enumerate() {
                        matrix[(r + k, 3 * (link - 1) + i)] += x;
                    }
                }
            },
        );
        for _ in 0..c.kind.rows() {
            joint.push(c.joint);
            driver.push(matches!(
                c.kind,
                ConKind::DriveRevolute(_) | ConKind::DrivePrismatic(_)
            ));
        }
        r += c.kind.rows();
    }
    Jacobian {
        matrix,
        joint,
        driver,
        scale,
    }
}

/// Rank and null spaces of a matrix by SVD.
struct RankInfo {
    rank: usize,
    /// Basis of {y : yᵀ J = 0} (length = rows).
    left_null: Vec<DVector<f64>>,
    /// Basis of {x : J x = 0} (length = columns).
    right_null: Vec<DVector<f64>>,
}

/// SVD of J padded with zeros to a square matrix, so that both U and V are complete.
/// `None` when J is not finite or the SVD does not converge.
fn rank_info(j: &DMatrix<f64>) -> Option<RankInfo> {
    let (m, n) = j.shape();
    if !j.iter().all(|v| v.is_finite()) {
        return None;
    }
    let s = m.max(n);
    if s == 0 {
        return Some(RankInfo {
            rank: 0,
            left_null: Vec::new(),
            right_null: Vec::new(),
        });
    }
    let mut a = DMatrix::zeros(s, s);
    a.view_mut((0, 0), (m, n)).copy_from(j);
    let svd = a.try_svd(true, true, f64::EPSILON, 100_000)?;
    let sv = &svd.singular_values;
    let tol = RANK_TOL * sv.max();
    let small: Vec<usize> = (0..s).filter(|&i| sv[i] <= tol || sv[i].is_nan()).collect();
    let rank = s - small.len();
    let u = svd.u.as_ref()?;
    let vt = svd.v_t.as_ref()?;
    // Padded rows / columns contribute null vectors supported outside J's range; the
    // restrictions to J's rows / columns of the whole small-σ basis span the true spaces.
    let restrict = |v: DVector<f64>| if v.amax() > 1e-8 { Some(v) } else { None };
    let left_null = small
        .iter()
        .filter_map(|&i| restrict(u.column(i).rows(0, m).into_owned()))
        .collect();
    let right_null = small
        .iter()
        .filter_map(|&i| restrict(vt.row(i).columns(0, n).transpose()))
        .collect();
    Some(RankInfo {
        rank,
        left_null,
        right_null,
    })
}

/// Indices `g` of the groups (joints or links) whose entries in any of `vectors` are
/// significant; `group_of(i)` gives the group of entry `i`.
fn significant(
    vectors: &[DVector<f64>],
    groups: usize,
    group_of: impl Fn(usize) -> usize,
) -> Vec<usize> {
    let mut hit = vec![false; groups];
    for v in vectors {
        let mut mag = vec![0.0f64; groups];
        for (i, x) in v.iter().enumerate() {
            let g = group_of(i);
            mag[g] = mag[g].max(x.abs());
        }
        let top = mag.iter().cloned().fold(0.0, f64::max);
        for (g, &x) in mag.iter().enumerate() {
            if top > 0.0 && x > SIGNIFICANT * top {
                hit[g] = true;
            }
        }
    }
    (0..groups).filter(|&g| hit[g]).collect()
}

/// Check 4 of `docs/conventions.md#checks`: geometric redundancy and determinacy at the drawing
/// (`docs/theory.md` §1.4).
///
/// With J the dimensionless Jacobian of [`jacobian`] (3(N − 1) columns) and rank decided
/// by SVD with the relative tolerance [`RANK_TOL`]:
///
/// - (a) redundancy: the joint rows J_c (drivers excluded) must be independent,
///   rank J_c = rows of J_c; otherwise rows − rank constraints are redundant (the
///   reactions are indeterminate). The joints taking part are those with significant
///   components in a left null vector (a self-stress). An issue unless
///   `#[allow(redundant)]`.
/// - (b) determinacy: with the driver rows, rank J = 3(N − 1); otherwise the inputs do not
///   determine the position (a dead point in the drawing, or a missing input); the links
///   that can still move are those with significant components in a right null vector.
///   Skipped when (a) reported, as its consequence.
/// - with `#[allow(redundant)]`: the mobility at the drawing, 3(N − 1) − rank J_c, must
///   equal the number of inputs, then (b) applies.
///
/// Assumes a finite drawing (check 5); returns no issue when J is not finite.
pub fn geometric(model: &Model) -> Vec<Issue> {
    let mut out = Vec::new();
    let n = model.n_links();
    if n < 2 {
        return out;
    }
    let jac = jacobian(model);
    let cols = jac.matrix.ncols();
    let (jc, crow) = jac.select(|r| !jac.driver[r]);
    let Some(ci) = rank_info(&jc) else {
        return out;
    };
    let nj = model.joints.len();
    let joint_list = |js: &[usize]| names(js.iter().map(|&j| model.joints[j].name.clone()));
    let link_list = |ls: &[usize]| names(ls.iter().map(|&l| model.links[l].name.clone()));
    let redundant = jc.nrows() - ci.rank;
    let takes_part = significant(&ci.left_null, nj, |i| jac.joint[crow[i]]);
    let mut determinacy = true;
    if model.allow_redundant {
        let mobility = cols - ci.rank;
        let k = model.inputs.len();
        if mobility != k {
            determinacy = false;
            let mut culprits = vec![Culprit::Inputs];
            culprits.extend((0..nj).map(Culprit::Joint));
            out.push(Issue {
                culprits,
                message: format!(
                    "with #[allow(redundant)] the inputs must match the mobility at the drawing: the joints' {} have rank {} of 3(N−1) = {cols} coordinates, which leaves {}, but {} declared: declare {}",
                    plural(jc.nrows(), "equation", "equations"),
                    ci.rank,
                    plural(mobility, "DOF", "DOF"),
                    if k == 1 { "1 input was".to_string() } else { format!("{k} inputs were") },
                    plural(mobility, "input", "inputs"),
                ),
            });
        }
    } else if redundant > 0 {
        determinacy = false;
        let mut culprits: Vec<Culprit> = takes_part.iter().map(|&j| Culprit::Joint(j)).collect();
        if culprits.is_empty() {
            culprits.push(Culprit::Mechanism);
        }
        out.push(Issue {
            culprits,
            message: format!(
                "redundant constraints at the drawing: the joints' {} have rank {}, so {} and the reactions are indeterminate (e.g. parallel cranks, or coaxial pins); joints {} take part: remove a joint/link, or accept with #[allow(redundant)] (then only driver actions, no reactions)",
                plural(jc.nrows(), "constraint equation", "constraint equations"),
                ci.rank,
                plural(redundant, "constraint is redundant", "constraints are redundant"),
                joint_list(&takes_part),
            ),
        });
    }
    if determinacy {
        let Some(ai) = rank_info(&jac.matrix) else {
            return out;
        };
        if ai.rank < cols {
            let moving: Vec<usize> = significant(&ai.right_null, n - 1, |i| i / 3)
                .into_iter()
                .map(|l| l + 1)
                .collect();
            let mut culprits = vec![Culprit::Inputs];
            culprits.extend(moving.iter().map(|&l| Culprit::Link(l)));
            out.push(Issue {
                culprits,
                message: format!(
                    "the inputs do not determine the position at the drawing (a dead point, or a missing input): {} {} can still move with the inputs held (the {} of the joints and inputs have rank {} < 3(N−1) = {cols}): redraw the mechanism away from the dead point, or add an input",
                    if moving.len() == 1 { "link" } else { "links" },
                    link_list(&moving),
                    plural(jac.matrix.nrows(), "equation", "equations"),
                    ai.rank,
                ),
            });
        }
    }
    out
}

/// Every check of `docs/conventions.md#checks` on a resolved model (check 1, names, is done by
/// [`crate::front::resolve::resolve`]): [`drawing`] (5), [`crate::checks::grubler::check`] (2),
/// [`crate::checks::pebble::check`] (3), and [`geometric`] (4) only when the drawing and the counts
/// passed, to avoid cascades. A structural issue that covers the whole mechanism is
/// dropped when Grübler's count already failed (it restates the count). Returns every
/// issue found, in that order; empty when the mechanism is accepted.
pub fn check(model: &Model) -> Vec<Issue> {
    let mut out = drawing(model);
    let drawing_ok = out.is_empty();
    let grubler = crate::checks::grubler::check(model);
    let mut pebble = crate::checks::pebble::check(model);
    if grubler.is_some() {
        let n = model.n_links();
        pebble.retain(|i| {
            i.culprits
                .iter()
                .filter(|c| matches!(c, Culprit::Link(_)))
                .count()
                < n
        });
    }
    // Grübler below the inputs with a drawing that really moves (parallel cranks): the
    // rank check tells the true story — redundant constraints — so report that instead.
    if drawing_ok && !model.allow_redundant && grubler.is_some() {
        let g = crate::checks::grubler::count(model).grubler;
        if g < model.inputs.len() as i64 {
            let relaxed = Model {
                allow_redundant: true,
                ..model.clone()
            };
            if geometric(&relaxed).is_empty() {
                let strict = geometric(model);
                if !strict.is_empty() {
                    out.extend(strict.into_iter().map(|mut i| {
                            i.message = format!(
                                "{} (Grübler's count gives G = {g} for {} input(s), but the drawing moves: the count is fooled by the redundant constraints)",
                                i.message,
                                model.inputs.len()
                            );
                            i
                        }));
                    return out;
                }
            }
        }
    }
    let counts_ok = grubler.is_none() && pebble.is_empty();
    out.extend(grubler);
    out.extend(pebble);
    if drawing_ok && counts_ok {
        out.extend(geometric(model));
        if out.is_empty() {
            out.extend(meshes_solvable(model));
        }
    }
    out
}

/// A gear pair or rack must be solved by Willis' relation (`crate::elements::gears`): the meshing
/// link alone, held by its pin (or slide) and the mesh, after its partner and carrier, or
/// a gear-train group of up to three links pinned at their centres. A mesh inside another
/// group (a gear that closes a loop of a linkage) is refused.
pub fn meshes_solvable(model: &Model) -> Vec<Issue> {
    let Ok(plan) = crate::plan::assur::plan(model) else {
        return Vec::new();
    };
    let mut out = Vec::new();
    for g in &plan {
        if matches!(
            g.kernel,
            crate::plan::assur::Kernel::Mesh(_)
                | crate::plan::assur::Kernel::Train(_)
                | crate::plan::assur::Kernel::Rolling(_)
                | crate::plan::assur::Kernel::Cam(_)
        ) {
            continue;
        }
        for c in g.cons.iter().filter(|c| c.kind == ConKind::Rolling) {
            let jt = &model.joints[c.joint];
            out.push(Issue {
                culprits: vec![Culprit::Joint(c.joint)],
                message: format!(
                    "rolling joint `{}` is not solvable in closed form: its links {} form one group with other joints; a rolling wheel must be driven by its travel (the joint as an input) or be pinned at its centre to a rod pinned to a solved link (a crank–rod–wheel)",
                    jt.name,
                    names(g.bodies.iter().map(|&b| model.links[b].name.clone()))
                ),
            });
        }
        for c in g.cons.iter().filter(|c| c.kind == ConKind::Mesh) {
            let jt = &model.joints[c.joint];
            out.push(Issue {
                culprits: vec![Culprit::Joint(c.joint)],
                message: format!(
                    "{} `{}` is not solvable gear by gear: its links {} form one group with other joints; a meshing link must be held by one pin at its centre (or, for a rack, one slide) and be driven by the mesh alone after its partner and its carrier, or be one of at most three gears pinned at their centres that mesh with one another; closing a linkage's loop through a mesh is not supported",
                    jt.kind.keyword(),
                    jt.name,
                    names(g.bodies.iter().map(|&b| model.links[b].name.clone()))
                ),
            });
        }
    }
    out
}

/// The checks that depend on the numbers rather than the topology, for a model whose
/// topology already passed [`check`] (e.g. at compile time) and whose parameters changed
/// at run time: [`drawing`] (check 5), then [`geometric`] (check 4, redundancy and
/// determinacy at the new drawing) when the drawing passed. Empty when accepted.
pub fn runtime(model: &Model) -> Vec<Issue> {
    let out = drawing(model);
    if !out.is_empty() {
        return out;
    }
    geometric(model)
}

#[cfg(test)]
mod tests {
    use super::*;

    use crate::front::resolve::model_of as model;

    const SLIDER_CRANK: &str = r#"
        /// Offset slider-crank of a single-cylinder engine.
        pub struct SliderCrank {
            gravity: (0.0, -9.81),
            ground { O2: (0.0, 0.0) },
            link crank {
                points { O2, A: (0.038302, 0.032139) },
                mass: 1.2, inertia: 2.1e-3, cg: (0.0089, 0.0127),
            },
            link rod {
                points { A, B: (0.237285, 0.012) },
                mass: 2.4, inertia: 9.5e-3, cg: (0.1030, 0.0256),
            },
            link piston {
                points { B },
                mass: 1.7, cg: (0.237285, 0.012),
            },
            joints {
                O2: revolute(ground, crank),
                A: revolute(crank, rod),
                B: revolute(rod, piston),
                guide: prismatic(ground, piston) at B along (1.0, 0.0),
            },
            input: O2,
            loads {
                gas: force on piston at B,
                load: torque on crank,
            },
        }
    "#;

    /// Four-bar; `B_AT` is the coupler–rocker pin.
    const FOUR_BAR: &str = r#"
        pub struct FourBar {
            ground { O2: (0.0, 0.0), O4: (3.0, 0.0) },
            link crank { points { O2, A: (0.0, 1.0) } },
            link coupler { points { A, B: B_AT } },
            link rocker { points { B, O4 } },
            joints {
                O2: revolute(ground, crank),
                A: revolute(crank, coupler),
                B: revolute(coupler, rocker),
                O4: revolute(rocker, ground),
            },
            input: O2,
        }
    "#;

    const DOUBLE_PARALLELOGRAM: &str = r#"
        pub struct Parallel {
            ground { O1: (0.0, 0.0), O2: (1.0, 0.0), O3: (2.0, 0.0) },
            link c1 { points { O1, A1: (0.0, 1.0) } },
            link c2 { points { O2, A2: (1.0, 1.0) } },
            link c3 { points { O3, A3: (2.0, 1.0) } },
            link coupler { points { A1, A2, A3 }, mass: 1.0, cg: (1.0, 1.0) },
            joints {
                O1: revolute(ground, c1),
                O2: revolute(ground, c2),
                O3: revolute(ground, c3),
                A1: revolute(c1, coupler),
                A2: revolute(c2, coupler),
                A3: revolute(c3, coupler),
            },
            input: O1,
        }
    "#;

    fn culprit_links(i: &Issue) -> Vec<usize> {
        i.culprits
            .iter()
            .filter_map(|c| {
                if let Culprit::Link(l) = c {
                    Some(*l)
                } else {
                    None
                }
            })
            .collect()
    }

    #[test]
    fn slider_crank_passes_everything() {
        let m = model(SLIDER_CRANK);
        assert_eq!(check(&m), vec![]);
        let j = jacobian(&m);
        assert_eq!(j.matrix.shape(), (9, 9));
        assert_eq!(j.driver.iter().filter(|&&d| d).count(), 1);
        // Dimensionless: every entry is of order one.
        assert!(j.matrix.amax() <= 1.0 + 1e-12);
    }

    #[test]
    fn four_bar_and_slot_pass() {
        assert_eq!(
            check(&model(&FOUR_BAR.replace("B_AT", "(2.5, 2.0)"))),
            vec![]
        );
        let yoke = model(
            r#"pub struct Yoke {
                ground { O: (0.0, 0.0) },
                link crank { points { O, A: (0.1, 0.05) } },
                link yoke { points { C: (0.3, 0.0) }, mass: 2.0, cg: (0.3, 0.0) },
                joints {
                    O: revolute(ground, crank),
                    slot: pin_in_slot(yoke, crank) at A along (0.0, 1.0),
                    guide: prismatic(ground, yoke) at C along (1.0, 0.0),
                },
                input: O,
            }"#,
        );
        assert_eq!(check(&yoke), vec![]);
        // A prismatic driver (an actuator) on an inclined guide.
        let lever = model(
            r#"pub struct Lever {
                ground { O: (0.0, 0.0), C: (1.0, -0.5) },
                link arm { points { O, A: (1.0, 0.3) } },
                link cyl { points { C } },
                link rod { points { A, P: (1.0, -0.1) } },
                joints {
                    O: revolute(ground, arm),
                    A: revolute(arm, rod),
                    C: revolute(ground, cyl),
                    stroke: prismatic(cyl, rod) at P along (0.0, 1.0),
                },
                input: stroke,
            }"#,
        );
        assert_eq!(check(&lever), vec![]);
    }

    #[test]
    fn grubler_mismatch_is_reported_with_numbers() {
        let m = model(
            &FOUR_BAR
                .replace("B_AT", "(2.5, 2.0)")
                .replace("input: O2", "inputs: [O2, O4]"),
        );
        let issues = check(&m);
        assert_eq!(issues.len(), 1, "{issues:#?}");
        let msg = &issues[0].message;
        assert!(
            msg.contains("N = 4") && msg.contains("P_I = 4") && msg.contains("P_II = 0"),
            "{msg}"
        );
        assert!(
            msg.contains("= 1") && msg.contains("9 equations") && msg.contains("9 unknowns"),
            "{msg}"
        );
        assert!(msg.contains("2 inputs were declared"), "{msg}");
    }

    #[test]
    fn double_parallelogram_is_redundant() {
        let m = model(DOUBLE_PARALLELOGRAM);
        let issues = geometric(&m);
        assert_eq!(issues.len(), 1, "{issues:#?}");
        let msg = &issues[0].message;
        assert!(msg.starts_with("redundant constraints at the drawing: the joints' 12 constraint equations have rank 11, so 1 constraint is redundant"), "{msg}");
        assert!(
            msg.contains("joints `O1`, `O2`, `O3`, `A1`, `A2`, `A3` take part"),
            "{msg}"
        );
        assert!(msg.contains("#[allow(redundant)]"), "{msg}");
        assert_eq!(issues[0].culprits.len(), 6);
        // Through `check`, Grübler (G = 0 with one input) would say it cannot move; the
        // rank shows it does, so the redundancy is what is reported.
        let all = check(&m);
        assert_eq!(all.len(), 1, "{all:#?}");
        assert!(
            all[0]
                .message
                .starts_with("redundant constraints at the drawing"),
            "{}",
            all[0].message
        );
        assert!(
            all[0].message.contains("G = 0 for 1 input(s)"),
            "{}",
            all[0].message
        );
        assert!(all[0].message.contains("#[allow(redundant)]"));
        // Accepted when declared.
        let ok = model(&format!("#[allow(redundant)] {DOUBLE_PARALLELOGRAM}"));
        assert_eq!(check(&ok), vec![]);
        // ... but with #[allow(redundant)] the inputs must still match the true mobility.
        let two = model(&format!(
            "#[allow(redundant)] {}",
            DOUBLE_PARALLELOGRAM.replace("input: O1", "inputs: [O1, O2]")
        ));
        let issues = check(&two);
        assert_eq!(issues.len(), 1, "{issues:#?}");
        assert!(
            issues[0]
                .message
                .contains("leaves 1 DOF, but 2 inputs were declared: declare 1 input"),
            "{}",
            issues[0].message
        );
    }

    #[test]
    fn dead_point_fails_determinacy() {
        // Coupler and rocker collinear: A = (0, 1), B = (1.5, 0.5), O4 = (3, 0). With the
        // crank held, B can still move normal to the line A–O4.
        let m = model(&FOUR_BAR.replace("B_AT", "(1.5, 0.5)"));
        assert!(drawing(&m).is_empty());
        assert_eq!(crate::checks::grubler::check(&m), None);
        assert!(crate::checks::pebble::check(&m).is_empty());
        let issues = check(&m);
        assert_eq!(issues.len(), 1, "{issues:#?}");
        let msg = &issues[0].message;
        assert!(
            msg.starts_with("the inputs do not determine the position at the drawing (a dead point, or a missing input): links `coupler`, `rocker` can still move"),
            "{msg}"
        );
        assert!(msg.contains("have rank 8 < 3(N−1) = 9"), "{msg}");
        assert!(
            msg.contains("redraw the mechanism away from the dead point, or add an input"),
            "{msg}"
        );
        assert_eq!(issues[0].culprits[0], Culprit::Inputs);
        assert_eq!(culprit_links(&issues[0]), vec![2, 3]);
        // Crank and coupler collinear is the crank's own dead point only when the rocker
        // drives; with the crank as input the drawing is determinate.
        let m = model(
            &FOUR_BAR
                .replace("B_AT", "(0.0, 2.5)")
                .replace("O4: (3.0, 0.0)", "O4: (2.0, 0.5)"),
        );
        assert_eq!(check(&m), vec![]);
    }

    #[test]
    fn missing_input_fails_determinacy() {
        let m = model(
            &FOUR_BAR
                .replace("B_AT", "(2.5, 2.0)")
                .replace("input: O2,", ""),
        );
        let issues = geometric(&m);
        assert_eq!(issues.len(), 1, "{issues:#?}");
        assert_eq!(culprit_links(&issues[0]), vec![1, 2, 3]);
    }

    #[test]
    fn drawing_errors() {
        let neg = model(&SLIDER_CRANK.replace("mass: 2.4", "mass: -2.4"));
        let issues = drawing(&neg);
        assert_eq!(issues.len(), 1, "{issues:#?}");
        assert_eq!(issues[0].culprits[0], Culprit::Mass(2));
        assert!(
            issues[0]
                .message
                .starts_with("link `rod` has mass -2.4 kg: a mass must be finite and ≥ 0"),
            "{}",
            issues[0].message
        );
        assert!(!check(&neg).is_empty());

        let neg_i = model(&SLIDER_CRANK.replace("inertia: 2.1e-3", "inertia: -2.1e-3"));
        let issues = drawing(&neg_i);
        assert_eq!(issues.len(), 1);
        assert_eq!(issues[0].culprits[0], Culprit::Inertia(1));
        assert!(
            issues[0]
                .message
                .contains("moment of inertia -0.0021 kg·m²"),
            "{}",
            issues[0].message
        );

        let zero_axis = model(&SLIDER_CRANK.replace("along (1.0, 0.0)", "along (0.0, 0.0)"));
        let issues = drawing(&zero_axis);
        assert_eq!(issues.len(), 1, "{issues:#?}");
        assert_eq!(issues[0].culprits[0], Culprit::Axis(3));
        assert!(
            issues[0].message.starts_with(
                "prismatic joint `guide` has sliding axis along (0, 0), which is zero"
            ),
            "{}",
            issues[0].message
        );
        // The geometric check is not run on a bad drawing (no cascade).
        assert_eq!(check(&zero_axis).len(), 1);

        let same = model(
            &SLIDER_CRANK
                .replace("B: (0.237285, 0.012)", "B: (0.038302, 0.032139)")
                .replace("cg: (0.237285, 0.012)", "cg: (0.038302, 0.032139)"),
        );
        let issues = drawing(&same);
        assert_eq!(issues.len(), 1, "{issues:#?}");
        assert_eq!(
            issues[0].culprits,
            vec![Culprit::Point(2), Culprit::Link(2)]
        );
        assert!(
            issues[0]
                .message
                .starts_with("points `A` and `B` of link `rod` coincide"),
            "{}",
            issues[0].message
        );
        assert_eq!(check(&same).len(), 1);

        let mut nan = model(SLIDER_CRANK);
        nan.gravity = Some([0.0, f64::NAN]);
        nan.points[1].pos[0] = f64::INFINITY;
        let issues = drawing(&nan);
        assert_eq!(issues.len(), 2, "{issues:#?}");
        assert!(issues.iter().any(|i| i.culprits == vec![Culprit::Gravity]));
        assert!(issues.iter().any(|i| i.culprits == vec![Culprit::Point(1)]));
        let _ = geometric(&nan); // must neither panic nor hang
    }
}
