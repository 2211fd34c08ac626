//! Motion generation by Burmester theory (SPEC §3f `mech synth motion`): a four-bar whose
//! coupler passes through given poses (xᵢ, yᵢ, angleᵢ): P at (xᵢ, yᵢ), the coupler turned
//! to angleᵢ.
//!
//! **The moving frame.** Pose i places the coupler's plane: a point with coordinates z in
//! the moving frame (m; origin P, x along the pose's angle, y across) is at
//! Zᵢ(z) = Pᵢ + R(angleᵢ) z. A **circle point** z is one whose positions Zᵢ lie on a
//! circle; its **centre point** c, the circle's centre, is a ground pivot, and z the
//! moving pivot of a crank or rocker (a dyad). Two dyads make the four-bar: A the crank's
//! circle point, B the rocker's, O2 and O4 their centres, P the moving frame's origin (so
//! P and the coupler's rotation meet every pose).
//!
//! - **Three poses**: every point is a circle point; its centre is the circumcentre of
//!   its three positions (one 2×2 linear system). The family is the choice of two circle
//!   points (4 numbers, `--circle-points`); by default both on one line along the pose's
//!   direction, (u, k) with k ∈ {0, ±½, ±1}·ℓ and u ∈ {−2, −1, −½, ½, 1, 2}·ℓ (ℓ the
//!   poses' extent, the largest |Pᵢ − P₁|), A before B, the best pair by
//!   [the ranking](#the-ranking).
//! - **Four poses**: z is a circle point when the three equations
//!   2(Zᵢ − Z₁)·c = |Zᵢ|² − |Z₁|², i = 2, 3, 4, have a common solution c: the determinant
//!   of their rows [2(Zᵢ − Z₁), −(Zᵢ − Z₁)·(Zᵢ + Z₁)] (the coefficients of c and of 1),
//!   each affine in z (|z|² cancels), is zero, a cubic in z: the circle-point curve, whose
//!   centres make the centre-point curve (also a cubic). It is sampled along lines of the
//!   moving frame (along the pose's direction, across it and the diagonals, out to
//!   [`REACH`]), on each a cubic in the line's parameter (roots by the companion matrix,
//!   polished by Newton on the determinant); two circle points on one line along the
//!   pose's direction make A → B lie along it, so the angle of A → B meets each pose's
//!   angle exactly; those pairs are preferred, then any two samples.
//! - **Five poses**: the Burmester points, circle points of both curves of poses 1234 and
//!   1235 (up to four real ones), found by Newton on the two determinants from seeds on
//!   the first curve (its points on lines across the reach in four directions), the poles
//!   (P₁₂, P₁₃, P₂₃, common to both curves) discarded by requiring the five positions to be
//!   concyclic; four-bars from pairs of them.
//! - **Six poses or more**: least squares: circle points minimising
//!   Σᵢ (|Zᵢ − c| − ρ)² over (z, c, ρ) (Levenberg–Marquardt from the Burmester points of
//!   five poses spread over the set, and from the twelve lowest local minima of a grid of
//!   z out to 10ℓ, each with the algebraic circle fit), four-bars from pairs of them, the
//!   smallest [`motion_error`] kept.
//!
//! **The offset γ.** SPEC §3f reads a pose's angle as the direction of A → B. The
//! coupler's direction A → B is angleᵢ + γ at every pose, γ the direction of z_B − z_A in
//! the moving frame: γ = 0 for the default three-pose choice and for the preferred
//! four-pose pairs; Burmester points are isolated, so five poses generally give γ ≠ 0 — the
//! rotation from pose to pose is met exactly, the angles along A → B are off by γ, which
//! [`MotionSynthesis::offset`] reports.
//!
//! # The ranking
//!
//! Candidate four-bars must reach every pose on one assembly branch (the drawing's, at the
//! first pose) with every point within [`REACH`]·ℓ of P₁; among them, one whose crank
//! turns fully (Grashof, crank shortest) first, then the one whose smallest sin μ (μ the
//! transmission angle, over the poses, and over the whole turn for a turning crank) is
//! largest. Least squares ranks by error first.

use super::four_bar::FourBar;
use crate::error::MechError;
use crate::kernel::dyad::circle_circle;
use crate::kernel::link_state::{cross, perp, rotate, wrap, V2};
use nalgebra::{DMatrix, DVector, Matrix3};

/// A pose of the coupler: P's position x, y (m) and the coupler's angle (rad, the
/// direction of A → B, counter-clockwise from +x).
pub type Pose = [f64; 3];

/// The most distant a pivot or a circle point may be from P₁, in units of the poses'
/// extent ℓ.
pub const REACH: f64 = 20.0;

/// The error (m², relative to ℓ²) below which a pose counts as met exactly.
const EXACT_TOL: f64 = 1e-18;

/// A dyad: a circle point and its centre point.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Dyad {
    /// The circle point in the moving frame (m; origin P, x along the pose's angle).
    pub circle: [f64; 2],
    /// The centre point, fixed frame (m).
    pub centre: [f64; 2],
}

/// A motion generator: the four-bar and how it meets the poses.
#[derive(Clone, Debug, PartialEq)]
pub struct MotionSynthesis {
    /// The four-bar (SPEC §3f names), drawn at the first pose, m.
    pub four_bar: FourBar,
    /// The crank's dyad: A and O2.
    pub crank: Dyad,
    /// The rocker's dyad: B and O4.
    pub rocker: Dyad,
    /// γ (rad, (−π, π]): the coupler's direction A → B is angleᵢ + γ at pose i (0 when A
    /// and B lie on a line along the pose's direction).
    pub offset: f64,
    /// The crank's absolute angle (rad, O2 → A) at each pose.
    pub crank_angles: Vec<f64>,
    /// Three to five poses, met exactly (true), or more by least squares (false).
    pub exact: bool,
    /// [`motion_error`] at the crank angles, m².
    pub error: f64,
}

/// E = Σᵢ |P(θᵢ) − Pᵢ|² + L² |e(φᵢ − γ) − e(angleᵢ)|², m²: the four-bar at crank angles
/// θᵢ (absolute, rad) against the poses, P's distance and the coupler's turn (φᵢ the
/// direction of A → B at θᵢ, γ the `offset`, L = |AB|, e(α) = (cos α, sin α)); infinite
/// where it does not assemble.
pub fn motion_error(fb: &FourBar, poses: &[Pose], crank_angles: &[f64], offset: f64) -> f64 {
    let l = fb.lengths()[2];
    poses
        .iter()
        .zip(crank_angles)
        .map(|(p, &t)| {
            fb.pose(t).map_or(f64::INFINITY, |s| {
                let phi = (s.b[1] - s.a[1]).atan2(s.b[0] - s.a[0]);
                let turn = e(phi - offset) - e(p[2]);
                (s.p[0] - p[0]).powi(2) + (s.p[1] - p[1]).powi(2) + l * l * turn.norm_squared()
            })
        })
        .sum()
}

fn e(a: f64) -> V2 {
    V2::new(a.cos(), a.sin())
}

fn v(p: [f64; 2]) -> V2 {
    V2::new(p[0], p[1])
}

fn arr(x: V2) -> [f64; 2] {
    [x.x, x.y]
}

/// The poses in normalised coordinates: P₁ at the origin, the extent ℓ the unit.
struct Task {
    /// Pᵢ normalised, and (cos, sin) of angleᵢ.
    poses: Vec<(V2, V2)>,
    origin: V2,
    scale: f64,
}

impl Task {
    /// Check and normalise: at least `min` poses, finite, no two equal, P not the same
    /// point for all.
    fn new(poses: &[Pose], min: usize) -> Result<Task, MechError> {
        if poses.len() < min {
            return Err(MechError::InvalidInput(format!(
                "motion synthesis needs at least {min} poses (x, y, angle), got {}: three to five are met exactly (Burmester), more by least squares",
                poses.len()
            )));
        }
        for (i, p) in poses.iter().enumerate() {
            if !p.iter().all(|x| x.is_finite()) {
                return Err(MechError::InvalidInput(format!(
                    "pose {} ({}, {}, {}) is not finite: give x, y (m) and the angle (rad) as finite numbers",
                    i + 1,
                    p[0],
                    p[1],
                    p[2]
                )));
            }
        }
        let origin = V2::new(poses[0][0], poses[0][1]);
        let scale = poses
            .iter()
            .map(|p| (V2::new(p[0], p[1]) - origin).norm())
            .fold(0.0, f64::max);
        for (i, p) in poses.iter().enumerate() {
            for (j, q) in poses.iter().enumerate().take(i) {
                let d = (V2::new(p[0] - q[0], p[1] - q[1])).norm();
                if d <= 1e-12 * scale && wrap(p[2] - q[2]).abs() <= 1e-12 {
                    return Err(MechError::InvalidInput(format!(
                        "poses {} and {} coincide (({}, {}), {} rad): a pose counts once; remove one or change it",
                        j + 1,
                        i + 1,
                        p[0],
                        p[1],
                        p[2]
                    )));
                }
            }
        }
        if !(scale > 0.0 && scale.is_finite()) {
            return Err(MechError::InvalidInput(format!(
                "every pose puts P at ({}, {}): the coupler only turns about P, which one crank pinned at P does, not a four-bar; move P in one pose at least",
                origin.x, origin.y
            )));
        }
        Ok(Task {
            poses: poses
                .iter()
                .map(|p| ((V2::new(p[0], p[1]) - origin) / scale, e(p[2])))
                .collect(),
            origin,
            scale,
        })
    }

    fn n(&self) -> usize {
        self.poses.len()
    }

    /// Zᵢ(z) = Pᵢ + R(angleᵢ) z.
    fn place(&self, i: usize, z: V2) -> V2 {
        let (p, r) = self.poses[i];
        p + rotate(r, z)
    }

    /// The row of pose i (against pose 0) at z: [2(Zᵢ − Z₀), −(Zᵢ − Z₀)·(Zᵢ + Z₀)].
    fn row(&self, i: usize, z: V2) -> [f64; 3] {
        let (zi, z0) = (self.place(i, z), self.place(0, z));
        let (d, s) = (zi - z0, zi + z0);
        [2.0 * d.x, 2.0 * d.y, -d.dot(&s)]
    }

    /// The row's derivative along `dir` (constant: the row is affine in z, the |z|² of
    /// |Zᵢ|² − |Z₀|² cancelling).
    fn row_along(&self, i: usize, dir: V2) -> [f64; 3] {
        let ((pi, ri), (p0, r0)) = (self.poses[i], self.poses[0]);
        let (ui, u0) = (rotate(ri, dir), rotate(r0, dir));
        let d = ui - u0;
        [2.0 * d.x, 2.0 * d.y, -2.0 * (pi.dot(&ui) - p0.dot(&u0))]
    }

    /// The circle-point determinant of poses 0, i, j, k at z, and its gradient.
    fn curve(&self, idx: [usize; 3], z: V2) -> (f64, V2) {
        let r = idx.map(|i| self.row(i, z));
        let gx = idx.map(|i| self.row_along(i, V2::x()));
        let gy = idx.map(|i| self.row_along(i, V2::y()));
        let d = |m: [[f64; 3]; 3]| Matrix3::from_fn(|i, j| m[i][j]).determinant();
        let along = |g: [[f64; 3]; 3]| {
            (0..3)
                .map(|k| {
                    let mut m = r;
                    m[k] = g[k];
                    d(m)
                })
                .sum::<f64>()
        };
        (d(r), V2::new(along(gx), along(gy)))
    }

    /// The circle points of poses 0, i, j, k on the line z₀ + s·dir: the real roots of the
    /// cubic det(a + s b) (a the rows at z₀, b their derivatives), polished by Newton on
    /// the determinant itself.
    fn on_line(&self, idx: [usize; 3], z0: V2, dir: V2) -> Vec<V2> {
        let a = idx.map(|i| self.row(i, z0));
        let b = idx.map(|i| self.row_along(i, dir));
        let d = |m: [[f64; 3]; 3]| Matrix3::from_fn(|i, j| m[i][j]).determinant();
        let pick = |mask: [bool; 3]| d([0, 1, 2].map(|k| if mask[k] { b[k] } else { a[k] }));
        let c = [
            pick([false, false, false]),
            pick([true, false, false]) + pick([false, true, false]) + pick([false, false, true]),
            pick([true, true, false]) + pick([true, false, true]) + pick([false, true, true]),
            pick([true, true, true]),
        ];
        let mut out: Vec<V2> = Vec::new();
        for s0 in real_roots(c) {
            let mut s = s0;
            for _ in 0..8 {
                let (f, g) = self.curve(idx, z0 + dir * s);
                let df = g.dot(&dir);
                if !(df != 0.0) {
                    break;
                }
                let step = f / df;
                if !step.is_finite() {
                    break;
                }
                s -= step;
                if step.abs() <= 1e-16 * (1.0 + s.abs()) {
                    break;
                }
            }
            let z = z0 + dir * s;
            if s.is_finite() && !out.iter().any(|w| (w - z).norm() <= 1e-9) {
                out.push(z);
            }
        }
        out
    }

    /// The centre of circle point z over every pose: the least-squares solution of
    /// 2(Zᵢ − Z₀)·(c − Z₀) = |Zᵢ − Z₀|² (the circumcentre for three poses), its radius, and
    /// the largest relative misfit ||Zᵢ − c| − ρ|/ρ; `None` when the positions are
    /// (nearly) collinear or coincide (the centre at infinity, or undetermined).
    fn centre(&self, z: V2) -> Option<(V2, f64, f64)> {
        let pts: Vec<V2> = (0..self.n()).map(|i| self.place(i, z)).collect();
        let m = DMatrix::from_fn(pts.len() - 1, 2, |i, j| 2.0 * (pts[i + 1] - pts[0])[j]);
        let rhs = DVector::from_fn(pts.len() - 1, |i, _| (pts[i + 1] - pts[0]).norm_squared());
        let svd = m.svd(true, true);
        let (hi, lo) = (svd.singular_values.max(), svd.singular_values.min());
        if !(lo > 1e-9 * hi) {
            return None;
        }
        let x = svd.solve(&rhs, 0.0).ok()?;
        let c = pts[0] + V2::new(x[0], x[1]);
        let rho = (pts[0] - c).norm();
        let misfit = pts
            .iter()
            .map(|p| ((p - c).norm() - rho).abs())
            .fold(0.0, f64::max)
            / rho;
        (rho > 0.0 && misfit.is_finite()).then_some((c, rho, misfit))
    }

    /// A dyad (normalised) of circle point z when its positions are concyclic.
    fn dyad(&self, z: V2, tol: f64) -> Option<Fit> {
        let (c, rho, misfit) = self.centre(z)?;
        (misfit <= tol && z.norm() <= REACH && c.norm() <= REACH).then_some(Fit { z, c, rho })
    }

    fn denormalise(&self, x: V2) -> [f64; 2] {
        arr(self.origin + x * self.scale)
    }
}

/// A circle point z (moving frame), its centre c and radius ρ (normalised).
#[derive(Clone, Copy, Debug)]
struct Fit {
    z: V2,
    c: V2,
    rho: f64,
}

/// The real roots of c₀ + c₁ s + c₂ s² + c₃ s³ (leading coefficients below 1e-12 of the
/// largest are dropped: their roots are beyond any reach).
fn real_roots(c: [f64; 4]) -> Vec<f64> {
    let m = c.iter().fold(0.0f64, |a, x| a.max(x.abs()));
    if !(m > 0.0 && m.is_finite()) {
        return Vec::new();
    }
    let c = c.map(|x| x / m);
    match (0..4).rev().find(|&k| c[k].abs() > 1e-12) {
        Some(1) => vec![-c[0] / c[1]],
        Some(2) => {
            let disc = c[1] * c[1] - 4.0 * c[2] * c[0];
            if disc < 0.0 {
                return Vec::new();
            }
            let q = -0.5 * (c[1] + c[1].signum() * disc.sqrt());
            let mut r = vec![q / c[2]];
            if q != 0.0 {
                r.push(c[0] / q);
            }
            r
        }
        Some(3) => {
            let (p0, p1, p2) = (c[0] / c[3], c[1] / c[3], c[2] / c[3]);
            let comp = Matrix3::new(0.0, 0.0, -p0, 1.0, 0.0, -p1, 0.0, 1.0, -p2);
            comp.complex_eigenvalues()
                .iter()
                .filter(|l| l.im.abs() <= 1e-6 * (1.0 + l.re.abs()))
                .map(|l| l.re)
                .collect()
        }
        _ => Vec::new(),
    }
}

/// A candidate four-bar (normalised) and how it meets the poses.
#[derive(Clone, Debug)]
struct Candidate {
    fb: FourBar,
    crank: Fit,
    rocker: Fit,
    offset: f64,
    thetas: Vec<f64>,
    error: f64,
    score: (bool, f64),
}

/// The four-bar of two dyads: drawn at pose 0 (A on the crank's circle nearest its
/// position, B the intersection nearest its own), P placed as in the moving frame; the
/// crank angles those of the crank's circle point at each pose. `None` for a degenerate
/// linkage (a zero link), a point beyond [`REACH`], or one that does not assemble.
fn build(t: &Task, ca: Fit, cb: Fit) -> Option<Candidate> {
    let (za, zb) = (ca.z, cb.z);
    let lc = (zb - za).norm();
    // Every link of positive length, and A and B apart from P (a link's points are
    // distinct in a mechanism file).
    let apart = [
        lc,
        ca.rho,
        cb.rho,
        (ca.c - cb.c).norm(),
        za.norm(),
        zb.norm(),
    ];
    if !apart.iter().all(|&d| d > 1e-9) {
        return None;
    }
    let (ta, tb) = (t.place(0, za), t.place(0, zb));
    let a0 = ca.c + (ta - ca.c).normalize() * ca.rho;
    let b0 = [1.0, -1.0]
        .into_iter()
        .filter_map(|s| circle_circle(a0, lc * lc, cb.c, cb.rho * cb.rho, s).ok())
        .min_by(|x, y| (x - tb).norm().total_cmp(&(y - tb).norm()))?;
    let em = (zb - za) / lc;
    let (u, w) = ((-za).dot(&em), (-za).dot(&perp(em)));
    let ed = (b0 - a0) / lc;
    let p0 = a0 + ed * u + perp(ed) * w;
    let fb = FourBar {
        o2: arr(ca.c),
        o4: arr(cb.c),
        a: arr(a0),
        b: arr(b0),
        p: arr(p0),
    };
    if [ca.c, cb.c, a0, b0, p0]
        .iter()
        .any(|x| !(x.norm() <= REACH))
    {
        return None;
    }
    let thetas: Vec<f64> = (0..t.n())
        .map(|i| {
            let d = t.place(i, za) - ca.c;
            d.y.atan2(d.x)
        })
        .collect();
    let offset = em.y.atan2(em.x);
    let poses: Vec<Pose> = t
        .poses
        .iter()
        .map(|(p, r)| [p.x, p.y, r.y.atan2(r.x)])
        .collect();
    let error = motion_error(&fb, &poses, &thetas, offset);
    if !error.is_finite() {
        return None;
    }
    let score = score(&fb, &thetas);
    Some(Candidate {
        fb,
        crank: ca,
        rocker: cb,
        offset,
        thetas,
        error,
        score,
    })
}

/// (the crank turns fully, the smallest sin μ over `thetas` and, for a turning crank, over
/// the whole turn): larger is better.
pub(super) fn score(fb: &FourBar, thetas: &[f64]) -> (bool, f64) {
    let turns = fb.crank_turns();
    let sin_mu = |t: f64| fb.transmission_angle(t).map_or(0.0, f64::sin);
    let mut worst = thetas.iter().map(|&t| sin_mu(t)).fold(1.0, f64::min);
    if turns {
        let t0 = fb.drawn_angle();
        for k in 0..72 {
            worst = worst.min(sin_mu(t0 + std::f64::consts::TAU * k as f64 / 72.0));
        }
    }
    (turns, worst)
}

/// The better of two exact candidates by [the ranking](self#the-ranking).
fn better(a: &Candidate, b: &Candidate) -> bool {
    (a.score.0, a.score.1) > (b.score.0, b.score.1)
}

/// The best exact candidate of `pairs` (met to [`EXACT_TOL`]).
fn best_exact(t: &Task, pairs: impl IntoIterator<Item = (Fit, Fit)>) -> Option<Candidate> {
    let mut best: Option<Candidate> = None;
    for (a, b) in pairs {
        let Some(c) = build(t, a, b) else { continue };
        if c.error <= EXACT_TOL * t.n() as f64 && best.as_ref().is_none_or(|x| better(&c, x)) {
            best = Some(c);
        }
    }
    best
}

fn finish(t: &Task, c: Candidate, exact: bool) -> MotionSynthesis {
    let s = t.scale;
    let fb = &c.fb;
    let four_bar = FourBar {
        o2: t.denormalise(v(fb.o2)),
        o4: t.denormalise(v(fb.o4)),
        a: t.denormalise(v(fb.a)),
        b: t.denormalise(v(fb.b)),
        // An exact four-bar is drawn at the first pose: P there is the pose's own point
        // (the construction's round-off, ~1e-16 of ℓ, left out of the file).
        p: if exact {
            arr(t.origin)
        } else {
            t.denormalise(v(fb.p))
        },
    };
    let dyad = |f: Fit| Dyad {
        circle: arr(f.z * s),
        centre: t.denormalise(f.c),
    };
    MotionSynthesis {
        four_bar,
        crank: dyad(c.crank),
        rocker: dyad(c.rocker),
        offset: c.offset,
        crank_angles: c.thetas,
        exact,
        error: c.error * s * s,
    }
}

/// The centre point of `circle` (moving frame, m) for three or more poses: the centre of
/// the circle through its positions Zᵢ = Pᵢ + R(angleᵢ) z (for three, their circumcentre).
/// `InvalidInput` when the positions are collinear or coincide (the centre at infinity: a
/// slider), or, beyond three poses, when they are not concyclic (z is not a circle point).
pub fn centre_point(poses: &[Pose], circle: [f64; 2]) -> Result<[f64; 2], MechError> {
    let t = Task::new(poses, 3)?;
    let z = v(circle) / t.scale;
    match t.centre(z) {
        None => Err(MechError::InvalidInput(format!(
            "circle point ({}, {}): its positions are collinear or coincide, its centre is at infinity (a slider, not a crank); choose another circle point",
            circle[0], circle[1]
        ))),
        Some((_, _, misfit)) if misfit > 1e-9 => Err(MechError::InvalidInput(format!(
            "({}, {}) is not a circle point of these {} poses: its positions are off a common circle by {misfit:e} of its radius",
            circle[0],
            circle[1],
            poses.len()
        ))),
        Some((c, _, _)) => Ok(t.denormalise(c)),
    }
}

/// Three poses, `circle_points` the circle points of A and B in the moving frame (m), or
/// `None` for the default choice (module docs). `InvalidInput` when a circle point's
/// centre is at infinity, or when the four-bar does not reach the three poses on one
/// branch (with the fix: other circle points).
pub fn three_poses(
    poses: &[Pose],
    circle_points: Option<[[f64; 2]; 2]>,
) -> Result<MotionSynthesis, MechError> {
    let t = Task::new(poses, 3)?;
    if t.n() != 3 {
        return Err(MechError::InvalidInput(format!(
            "three_poses takes three poses, got {}",
            t.n()
        )));
    }
    if let Some([a, b]) = circle_points {
        if !a.iter().chain(&b).all(|x| x.is_finite()) {
            return Err(MechError::InvalidInput(format!(
                "the circle points ({}, {}) and ({}, {}) must be finite (m, moving frame)",
                a[0], a[1], b[0], b[1]
            )));
        }
        let fit = |p: [f64; 2], name: &str| {
            if !(v(p).norm() > 1e-9 * t.scale) {
                return Err(MechError::InvalidInput(format!(
                    "circle point {name} ({}, {}) is P itself: the coupler's points must be distinct; choose another circle point",
                    p[0], p[1]
                )));
            }
            t.dyad(v(p) / t.scale, 1e-9).ok_or_else(|| {
                MechError::InvalidInput(format!(
                    "circle point {name} ({}, {}): its three positions are collinear or coincide (the centre at infinity, a slider), or its centre is beyond {REACH} times the poses' extent; choose another circle point",
                    p[0], p[1]
                ))
            })
        };
        let (fa, fb) = (fit(a, "A")?, fit(b, "B")?);
        return match build(&t, fa, fb) {
            Some(c) if c.error <= EXACT_TOL * 3.0 => Ok(finish(&t, c, true)),
            _ => Err(MechError::InvalidInput(format!(
                "the four-bar of circle points A ({}, {}) and B ({}, {}) does not reach the three poses on one assembly branch (or has a link of zero length); choose other circle points",
                a[0], a[1], b[0], b[1]
            ))),
        };
    }
    let us = [-2.0, -1.0, -0.5, 0.5, 1.0, 2.0];
    let mut cands = Vec::new();
    for k in [0.0, 0.5, -0.5, 1.0, -1.0] {
        let fits: Vec<Option<Fit>> = us.iter().map(|&u| t.dyad(V2::new(u, k), 1e-9)).collect();
        for i in 0..us.len() {
            for j in i + 1..us.len() {
                if let (Some(a), Some(b)) = (fits[i], fits[j]) {
                    cands.push((a, b));
                }
            }
        }
    }
    best_exact(&t, cands).map(|c| finish(&t, c, true)).ok_or_else(|| {
        MechError::InvalidInput(
            "no default pair of circle points (on lines along the pose's direction at 0, ±½, ±1 times the poses' extent from P, at ±½, ±1, ±2 times it along them) gives a four-bar that reaches the three poses on one branch; give two circle points (--circle-points XA,YA,XB,YB, m in the moving frame)".into(),
        )
    })
}

/// The offsets of the lines the circle-point curves are sampled on (normalised): every
/// 0.2 from −4 to 4, then out to [`REACH`].
fn line_offsets() -> Vec<f64> {
    let mut ks: Vec<f64> = (0..=40).map(|k| -4.0 + 0.2 * k as f64).collect();
    for k in [5.0, 6.5, 8.0, 10.0, 13.0, 16.0, 20.0] {
        ks.extend([k, -k]);
    }
    ks
}

/// The directions of the sampling lines: along the pose's direction (x), across it, and
/// the two diagonals. Every branch of a curve within the reach crosses some of the lines.
fn line_directions() -> [V2; 4] {
    let h = std::f64::consts::FRAC_1_SQRT_2;
    [V2::x(), V2::y(), V2::new(h, h), V2::new(h, -h)]
}

/// The centre-point curve of four poses, sampled: the circle points on `lines` lines of
/// the moving frame y = k, k evenly from −2ℓ to 2ℓ (ℓ the poses' extent), with their
/// centres (each a point of the centre-point curve). `InvalidInput` unless four poses.
pub fn centre_point_curve(poses: &[Pose], lines: usize) -> Result<Vec<Dyad>, MechError> {
    let t = Task::new(poses, 4)?;
    if t.n() != 4 {
        return Err(MechError::InvalidInput(format!(
            "the centre-point curve is that of four poses, got {}",
            t.n()
        )));
    }
    let n = lines.max(2);
    let ks = (0..n).map(|k| -2.0 + 4.0 * k as f64 / (n - 1) as f64);
    Ok(ks
        .flat_map(|k| t.on_line([1, 2, 3], V2::new(0.0, k), V2::x()))
        .filter_map(|z| t.dyad(z, 1e-8))
        .map(|f| Dyad {
            circle: arr(f.z * t.scale),
            centre: t.denormalise(f.c),
        })
        .collect())
}

/// Four poses: the circle-point curve sampled on the lines of [`line_offsets`] and
/// [`line_directions`]; pairs on one line along the pose's direction first (γ = 0), else
/// any two samples.
fn four_poses(t: &Task) -> Result<MotionSynthesis, MechError> {
    let dirs = line_directions();
    // lines[d][k]: the circle points on the line of direction d at offset k, in order.
    let lines: Vec<Vec<Vec<Fit>>> = dirs
        .iter()
        .map(|&d| {
            line_offsets()
                .into_iter()
                .map(|k| {
                    let mut f: Vec<Fit> = t
                        .on_line([1, 2, 3], perp(d) * k, d)
                        .into_iter()
                        .filter_map(|z| t.dyad(z, 1e-9))
                        .collect();
                    f.sort_by(|a, b| a.z.dot(&d).total_cmp(&b.z.dot(&d)));
                    f
                })
                .collect()
        })
        .collect();
    // Pairs on one line along the pose's direction, A before B: γ = 0.
    let same = lines[0]
        .iter()
        .flat_map(|l| (0..l.len()).flat_map(move |i| (i + 1..l.len()).map(move |j| (l[i], l[j]))));
    if let Some(c) = best_exact(t, same) {
        return Ok(finish(t, c, true));
    }
    let all: Vec<Fit> = lines.into_iter().flatten().flatten().collect();
    let step = all.len().div_ceil(240).max(1);
    let some: Vec<Fit> = all.into_iter().step_by(step).collect();
    let any = (0..some.len())
        .flat_map(|i| {
            (0..some.len())
                .filter(move |&j| j != i)
                .map(move |j| (i, j))
        })
        .map(|(i, j)| (some[i], some[j]));
    best_exact(t, any).map(|c| finish(t, c, true)).ok_or_else(|| {
        MechError::InvalidInput(
            "no two points of the four poses' circle-point curve (within 20 times the poses' extent) make a four-bar that reaches the four poses on one branch; move a pose, or give three".into(),
        )
    })
}

/// The Burmester points of five poses: the circle points common to the circle-point
/// curves of poses 1234 and 1235, with their centres (at most four real ones; the poles
/// common to both curves are not among them). `InvalidInput` unless five poses.
pub fn burmester_points(poses: &[Pose]) -> Result<Vec<Dyad>, MechError> {
    let t = Task::new(poses, 5)?;
    if t.n() != 5 {
        return Err(MechError::InvalidInput(format!(
            "Burmester points are those of five poses, got {}",
            t.n()
        )));
    }
    Ok(burmester(&t)
        .into_iter()
        .map(|f| Dyad {
            circle: arr(f.z * t.scale),
            centre: t.denormalise(f.c),
        })
        .collect())
}

/// Newton on (det₁₂₃₄, det₁₂₃₅) from seeds on the first curve: its points on lines at
/// distances up to [`REACH`] from P in four directions.
fn burmester(t: &Task) -> Vec<Fit> {
    let (c1, c2) = ([1, 2, 3], [1, 2, 4]);
    let (ks, dirs) = (line_offsets(), line_directions());
    let seeds = ks.iter().flat_map(|&k| {
        dirs.iter()
            .flat_map(|&d| t.on_line(c1, perp(d) * k, d))
            .collect::<Vec<V2>>()
    });
    let mut found: Vec<Fit> = Vec::new();
    for seed in seeds {
        let mut z = seed;
        let mut last = f64::INFINITY;
        for _ in 0..60 {
            let ((f1, g1), (f2, g2)) = (t.curve(c1, z), t.curve(c2, z));
            let det = cross(g1, g2);
            let dz = V2::new(f1 * g2.y - f2 * g1.y, g1.x * f2 - g2.x * f1) / det;
            if !(dz.x.is_finite() && dz.y.is_finite()) {
                break;
            }
            z -= dz;
            last = dz.norm();
            if !(z.norm() <= REACH) || last <= 1e-15 * (1.0 + z.norm()) {
                break;
            }
        }
        if !(last <= 1e-11 * (1.0 + z.norm())) {
            continue;
        }
        if found.iter().any(|f| (f.z - z).norm() <= 1e-7) {
            continue;
        }
        if let Some(f) = t.dyad(z, 1e-8) {
            found.push(f);
        }
    }
    found
}

fn five_poses(t: &Task) -> Result<MotionSynthesis, MechError> {
    let pts = burmester(t);
    if pts.len() < 2 {
        return Err(MechError::InvalidInput(format!(
            "these five poses have {} real Burmester point(s) within {REACH} times their extent; a four-bar needs two: move a pose, or give four",
            pts.len()
        )));
    }
    let pairs = (0..pts.len())
        .flat_map(|i| (0..pts.len()).filter(move |&j| j != i).map(move |j| (i, j)))
        .map(|(i, j)| (pts[i], pts[j]));
    best_exact(t, pairs).map(|c| finish(t, c, true)).ok_or_else(|| {
        MechError::InvalidInput(format!(
            "no pair of the {} Burmester points of these five poses makes a four-bar that reaches them all on one branch; move a pose, or give four",
            pts.len()
        ))
    })
}

/// The algebraic circle fit (Kåsa) of `pts`: centre and radius.
fn kasa(pts: &[V2]) -> Option<(V2, f64)> {
    let m0 = pts.iter().sum::<V2>() / pts.len() as f64;
    let m = DMatrix::from_fn(pts.len(), 3, |i, j| {
        let p = pts[i] - m0;
        [2.0 * p.x, 2.0 * p.y, 1.0][j]
    });
    let rhs = DVector::from_fn(pts.len(), |i, _| (pts[i] - m0).norm_squared());
    let x = m.svd(true, true).solve(&rhs, 1e-14).ok()?;
    let c = V2::new(x[0], x[1]);
    let r2 = x[2] + c.norm_squared();
    (r2 > 0.0).then(|| (m0 + c, r2.sqrt()))
}

/// Σᵢ (|Zᵢ − c| − ρ)² at (z, c, ρ).
fn misfit(t: &Task, f: &Fit) -> f64 {
    (0..t.n())
        .map(|i| ((t.place(i, f.z) - f.c).norm() - f.rho).powi(2))
        .sum()
}

/// Levenberg–Marquardt on (z, c, ρ) from `f`.
fn refine(t: &Task, mut f: Fit) -> Option<Fit> {
    let mut s = misfit(t, &f);
    let mut lambda = 1e-3;
    for _ in 0..200 {
        let n = t.n();
        let mut j = DMatrix::zeros(n, 5);
        let mut r = DVector::zeros(n);
        for i in 0..n {
            let d = t.place(i, f.z) - f.c;
            let dn = d.norm();
            if !(dn > 0.0) {
                return None;
            }
            let u = d / dn;
            let (_, rot) = t.poses[i];
            // ∂|Zᵢ − c|/∂z = Rᵢᵀ u.
            let gz = rotate(V2::new(rot.x, -rot.y), u);
            j.row_mut(i)
                .copy_from_slice(&[gz.x, gz.y, -u.x, -u.y, -1.0]);
            r[i] = dn - f.rho;
        }
        let jt = j.transpose();
        let h = &jt * &j;
        let g = &jt * &r;
        let mut improved = false;
        for _ in 0..20 {
            let mut a = h.clone();
            for k in 0..5 {
                a[(k, k)] += lambda * (1.0 + h[(k, k)]);
            }
            let Some(step) = a.lu().solve(&g) else {
                lambda *= 10.0;
                continue;
            };
            let trial = Fit {
                z: f.z - V2::new(step[0], step[1]),
                c: f.c - V2::new(step[2], step[3]),
                rho: f.rho - step[4],
            };
            let st = misfit(t, &trial);
            if st < s {
                let small = step.norm() <= 1e-15 * (1.0 + trial.z.norm() + trial.c.norm());
                f = trial;
                s = st;
                lambda = (lambda * 0.3).max(1e-12);
                improved = !small;
                break;
            }
            lambda *= 10.0;
        }
        if !improved {
            break;
        }
    }
    (f.rho > 0.0 && f.z.norm() <= REACH && f.c.norm() <= REACH).then_some(f)
}

fn least_squares(t: &Task) -> Result<MotionSynthesis, MechError> {
    let grid: Vec<f64> = {
        let mut g: Vec<f64> = line_offsets()
            .into_iter()
            .filter(|k| k.abs() <= 10.0)
            .collect();
        g.sort_by(f64::total_cmp);
        g
    };
    let g = grid.len();
    let fit_at = |z: V2| {
        let pts: Vec<V2> = (0..t.n()).map(|i| t.place(i, z)).collect();
        kasa(&pts).map(|(c, rho)| {
            let f = Fit { z, c, rho };
            (misfit(t, &f), f)
        })
    };
    let cells: Vec<Option<(f64, Fit)>> = (0..g * g)
        .map(|k| fit_at(V2::new(grid[k % g], grid[k / g])))
        .collect();
    let value = |i: usize, j: usize| cells[j * g + i].map_or(f64::INFINITY, |c| c.0);
    let mut minima: Vec<(f64, Fit)> = Vec::new();
    for j in 0..g {
        for i in 0..g {
            let Some((s, f)) = cells[j * g + i] else {
                continue;
            };
            let neighbours = (-1i64..=1).flat_map(|dj| (-1i64..=1).map(move |di| (di, dj)));
            let lowest = neighbours.filter(|&d| d != (0, 0)).all(|(di, dj)| {
                let (x, y) = (i as i64 + di, j as i64 + dj);
                x < 0
                    || y < 0
                    || x >= g as i64
                    || y >= g as i64
                    || value(x as usize, y as usize) >= s
            });
            if lowest {
                minima.push((s, f));
            }
        }
    }
    minima.sort_by(|a, b| a.0.total_cmp(&b.0));
    // Seeds: the Burmester points of five poses spread over the set (exact when the poses
    // are consistent), then the grid's lowest minima.
    let n = t.n();
    let five: Vec<Pose> = [0, n / 4, n / 2, 3 * n / 4, n - 1]
        .iter()
        .map(|&i| {
            let (p, r) = t.poses[i];
            [p.x, p.y, r.y.atan2(r.x)]
        })
        .collect();
    let mut seeds: Vec<Fit> = Task::new(&five, 5)
        .map(|sub| {
            burmester(&sub)
                .into_iter()
                .map(|f| Fit {
                    z: f.z * sub.scale,
                    c: sub.origin + f.c * sub.scale,
                    rho: f.rho * sub.scale,
                })
                .collect()
        })
        .unwrap_or_default();
    seeds.extend(minima.into_iter().take(12).map(|(_, f)| f));
    let mut fits: Vec<Fit> = Vec::new();
    for f in seeds {
        if let Some(r) = refine(t, f) {
            if !fits.iter().any(|x| (x.z - r.z).norm() <= 1e-6) {
                fits.push(r);
            }
        }
    }
    let mut best: Option<Candidate> = None;
    for (i, a) in fits.iter().enumerate() {
        for (j, b) in fits.iter().enumerate() {
            if i == j {
                continue;
            }
            let Some(c) = build(t, *a, *b) else { continue };
            let key = |c: &Candidate| (c.error, std::cmp::Reverse(c.score.0));
            if best.as_ref().is_none_or(|x| key(&c).0 < key(x).0) {
                best = Some(c);
            }
        }
    }
    best.map(|c| finish(t, c, false)).ok_or_else(|| {
        MechError::InvalidInput(format!(
            "least squares found {} circle point(s) for these {} poses but no pair that makes a four-bar reaching every pose; check the poses, or give five or fewer",
            fits.len(),
            t.n()
        ))
    })
}

/// A motion generator through `poses`: three poses with `circle_points` (A and B in the
/// moving frame, m) or the default choice; four and five poses by the circle-point curve
/// and the Burmester points (`circle_points` must be `None`: they are found); six or more
/// by least squares. `InvalidInput` for fewer than three poses, a non-finite or repeated
/// pose, poses that do not move P, and when no four-bar reaches the poses (the message
/// says what to change).
pub fn motion(
    poses: &[Pose],
    circle_points: Option<[[f64; 2]; 2]>,
) -> Result<MotionSynthesis, MechError> {
    let t = Task::new(poses, 3)?;
    if circle_points.is_some() && t.n() != 3 {
        return Err(MechError::InvalidInput(format!(
            "circle points are a free choice for three poses only; with {} poses they are found (Burmester): drop them",
            t.n()
        )));
    }
    match t.n() {
        3 => three_poses(poses, circle_points),
        4 => four_poses(&t),
        5 => five_poses(&t),
        _ => least_squares(&t),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::{FRAC_PI_2, PI};

    /// Every pose met: P at (x, y) and A → B along angle + γ, at the crank angles given,
    /// by the four-bar's own pose().
    fn assert_meets(s: &MotionSynthesis, poses: &[Pose], tol: f64) {
        for (p, &t) in poses.iter().zip(&s.crank_angles) {
            let q = s.four_bar.pose(t).unwrap();
            assert!(
                (q.p[0] - p[0]).abs() < tol && (q.p[1] - p[1]).abs() < tol,
                "P {:?} vs {p:?}",
                q.p
            );
            let dir = (q.b[1] - q.a[1]).atan2(q.b[0] - q.a[0]);
            assert!(
                wrap(dir - s.offset - p[2]).abs() < tol,
                "direction {dir} vs {}",
                p[2]
            );
        }
        assert!(s.error < tol * tol * 10.0, "{}", s.error);
    }

    /// By hand: poses P = (0, 0) at 0, (1, 1) at π/2, (2, 0) at π (Zᵢ = Pᵢ + R(angleᵢ) z).
    /// - z = (1, 1): (1, 1), (0, 2), (1, −1); equidistant from the first and last ⇒ y = 0,
    ///   from the first two ⇒ (x − 1)² + 1 = x² + 4 ⇒ x = −1: the centre (−1, 0).
    /// - z = (−1, 0): (−1, 0), (1, 0), (3, 0), collinear (a slider): refused.
    /// - z = (0, −1): (0, −1), (2, 1), (2, 1), two coincide: refused.
    /// - A = (−1, 2): (−1, 2), (−1, 0), (3, −2) ⇒ y = 1 and (x + 1)² + y² = (x − 3)² +
    ///   (y + 2)² ⇒ x = 2: O2 = (2, 1), crank √10.
    /// - B = (1, 2): (1, 2), (−1, 2), (1, −2) ⇒ O4 = (0, 0), rocker √5.
    ///
    /// The four-bar: frame √5, crank √10, coupler 2, rocker √5; B on the same side of
    /// A → O4 at the three poses (cross products 4, 2, 4); A and B on the line y = 2 of the
    /// moving frame, so γ = 0.
    #[test]
    fn three_poses_hand_worked() {
        let poses = [[0.0, 0.0, 0.0], [1.0, 1.0, FRAC_PI_2], [2.0, 0.0, PI]];
        let c = centre_point(&poses, [1.0, 1.0]).unwrap();
        assert!((c[0] + 1.0).abs() < 1e-14 && c[1].abs() < 1e-14, "{c:?}");
        assert!(centre_point(&poses, [-1.0, 0.0]).is_err());
        assert!(centre_point(&poses, [0.0, -1.0]).is_err());
        let s = three_poses(&poses, Some([[-1.0, 2.0], [1.0, 2.0]])).unwrap();
        assert_eq!(s.offset, 0.0);
        for (got, want) in [(s.crank.centre, [2.0, 1.0]), (s.rocker.centre, [0.0, 0.0])] {
            assert!(
                (got[0] - want[0]).abs() < 1e-13 && (got[1] - want[1]).abs() < 1e-13,
                "{got:?}"
            );
        }
        let r = s.four_bar.lengths();
        let want = [5f64.sqrt(), 10f64.sqrt(), 2.0, 5f64.sqrt()];
        for (g, w) in r.iter().zip(want) {
            assert!((g - w).abs() < 1e-12, "{r:?}");
        }
        assert_meets(&s, &poses, 1e-12);
    }

    /// The default choice for three poses meets them with A → B along each pose's angle.
    #[test]
    fn three_poses_default_choice() {
        let poses = [[0.1, 0.2, 0.3], [0.25, 0.3, 0.6], [0.4, 0.25, 1.0]];
        let s = motion(&poses, None).unwrap();
        assert!(s.exact);
        assert_eq!(s.offset, 0.0);
        assert_meets(&s, &poses, 1e-12);
    }

    /// Poses taken from a known four-bar: P and the direction of A → B plus `off` at each
    /// crank angle.
    fn poses_of(fb: &FourBar, thetas: &[f64], off: f64) -> Vec<Pose> {
        thetas
            .iter()
            .map(|&t| {
                let q = fb.pose(t).unwrap();
                [
                    q.p[0],
                    q.p[1],
                    (q.b[1] - q.a[1]).atan2(q.b[0] - q.a[0]) + off,
                ]
            })
            .collect()
    }

    fn known() -> FourBar {
        FourBar {
            o2: [0.0, 0.0],
            o4: [0.3, 0.0],
            a: [0.0, 0.1],
            b: [0.25, 0.2],
            p: [0.1, 0.3],
        }
    }

    /// Four poses of a known four-bar, with the poses' angles along A → B and turned by
    /// 0.7 rad from it: the samples of the curve are circle points (their centres those of
    /// centre_point), and the four-bar chosen meets every pose to 1e-12 with A → B along
    /// each pose's angle (γ = 0, a pair on one line y = k).
    #[test]
    fn four_poses_on_the_circle_point_curve() {
        for off in [0.0, 0.7] {
            let poses = poses_of(&known(), &[0.2, 0.9, 1.6, 2.4], off);
            let curve = centre_point_curve(&poses, 81).unwrap();
            assert!(curve.len() > 20);
            for d in &curve {
                let c = centre_point(&poses, d.circle).unwrap();
                assert!((c[0] - d.centre[0]).abs() < 1e-9 && (c[1] - d.centre[1]).abs() < 1e-9);
            }
            let s = motion(&poses, None).unwrap();
            assert!(s.exact);
            assert_eq!(s.offset, 0.0);
            assert_meets(&s, &poses, 1e-12);
        }
    }

    /// Five poses of a known four-bar: its A and B (in the moving frame) are two of the four
    /// Burmester points, with O2 and O4 their centres; the four-bar chosen meets every pose
    /// to 1e-12. With the poses' angles turned by 0.7 rad from A → B, the same points (in
    /// the turned frame) and γ = −0.7: A → B is each pose's angle − 0.7.
    #[test]
    fn five_poses_by_the_burmester_points() {
        let fb = known();
        for off in [0.0, 0.7] {
            let poses = poses_of(&fb, &[0.0, 0.7, 1.3, 2.0, 2.8], off);
            let pts = burmester_points(&poses).unwrap();
            assert_eq!(pts.len(), 4, "{pts:?}");
            let q0 = fb.pose(0.0).unwrap();
            let frame = |x: [f64; 2]| {
                let d = V2::new(x[0] - q0.p[0], x[1] - q0.p[1]);
                arr(rotate(e(-poses[0][2]), d))
            };
            for (pin, pivot) in [(q0.a, fb.o2), (q0.b, fb.o4)] {
                let z = frame(pin);
                let near = |a: [f64; 2], b: [f64; 2]| {
                    (a[0] - b[0]).abs() < 1e-9 && (a[1] - b[1]).abs() < 1e-9
                };
                let hit = pts.iter().find(|d| near(d.circle, z));
                let hit = hit.unwrap_or_else(|| panic!("{z:?} not among {pts:?}"));
                assert!(near(hit.centre, pivot), "{hit:?}");
            }
            let s = motion(&poses, None).unwrap();
            assert!(s.exact);
            assert_meets(&s, &poses, 1e-12);
            assert!((s.offset + off).abs() < 1e-12, "{}", s.offset);
        }
    }

    /// Six poses of a known four-bar: least squares finds it (error ≈ 0); poses off it
    /// leave an error.
    #[test]
    fn six_poses_by_least_squares() {
        let poses = poses_of(&known(), &[0.0, 0.5, 1.0, 1.5, 2.0, 2.5], 0.3);
        let s = motion(&poses, None).unwrap();
        assert!(!s.exact);
        assert!(s.error < 1e-16, "{}", s.error);
        let mut off = poses.clone();
        off[3][0] += 0.003;
        let s = motion(&off, None).unwrap();
        assert!(s.error > 1e-9 && s.error < 1e-3, "{}", s.error);
    }

    /// The file loads; the run-time mechanism (q = the crank's absolute angle) puts P and
    /// the coupler where the four-bar's pose() does.
    #[test]
    fn the_file_moves_like_the_four_bar() {
        let poses = [[0.1, 0.2, 0.3], [0.25, 0.3, 0.6], [0.4, 0.25, 1.0]];
        let s = motion(&poses, None).unwrap();
        let m = crate::Mechanism::from_dsl(&s.four_bar.to_mech("MotionGenerator", "test")).unwrap();
        for (p, &t) in poses.iter().zip(&s.crank_angles) {
            let pose = m.pose(&[t]).unwrap();
            let pp = pose.point("P").unwrap().pos;
            assert!(
                (pp.x - p[0]).abs() < 1e-12 && (pp.y - p[1]).abs() < 1e-12,
                "{pp:?} vs {p:?}"
            );
        }
    }

    #[test]
    fn bad_poses_are_refused_with_the_fix() {
        let msg = |r: Result<MotionSynthesis, MechError>| match r {
            Err(MechError::InvalidInput(m)) => m,
            other => panic!("{other:?}"),
        };
        let good = [[0.0, 0.0, 0.0], [1.0, 1.0, FRAC_PI_2], [2.0, 0.0, PI]];
        assert!(msg(motion(&good[..2], None)).contains("at least 3 poses"));
        assert!(
            msg(motion(&[good[0], good[1], [f64::INFINITY, 0.0, 0.0]], None)).contains("pose 3")
        );
        assert!(msg(motion(&[good[0], good[1], good[0]], None)).contains("poses 1 and 3 coincide"));
        assert!(msg(motion(
            &[[1.0, 1.0, 0.0], [1.0, 1.0, 1.0], [1.0, 1.0, 2.0]],
            None
        ))
        .contains("only turns about P"));
        assert!(msg(three_poses(&good, Some([[-1.0, 0.0], [1.0, 1.0]]))).contains("circle point A"));
        assert!(msg(three_poses(&good, Some([[0.0, 0.0], [1.0, 2.0]]))).contains("is P itself"));
        let four = poses_of(&known(), &[0.2, 0.9, 1.6, 2.4], 0.0);
        assert!(msg(motion(&four, Some([[0.0, 1.0], [1.0, 1.0]]))).contains("three poses only"));
    }

    /// Robustness: the poses of 60 pseudo-random four-bars (their coupler frames turned by
    /// 0.4 rad from A → B) at four, five and seven crank angles: a four-bar that meets
    /// every pose (to 1e-9 of P's position) is found for each, the given one being one
    /// answer.
    #[test]
    fn the_poses_of_random_four_bars_are_met() {
        let mut x = 0x9E37_79B9_7F4A_7C15u64;
        let mut rnd = || {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            (x >> 11) as f64 / (1u64 << 53) as f64
        };
        let mut tried = 0;
        for _ in 0..60 {
            let (o4, a, p) = (
                [0.5 + rnd(), 0.0],
                [0.1 + 0.4 * rnd(), 0.0],
                [rnd() - 0.5, rnd()],
            );
            let (r3, r4) = (0.5 + rnd(), 0.3 + rnd());
            let Ok(b) = circle_circle(v(a), r3 * r3, v(o4), r4 * r4, 1.0) else {
                continue;
            };
            let fb = FourBar {
                o2: [0.0, 0.0],
                o4,
                a,
                b: arr(b),
                p,
            };
            for n in [4usize, 5, 7] {
                let th: Vec<f64> = (0..n).map(|k| 0.2 + 0.5 * k as f64 + 0.1 * rnd()).collect();
                let Some(poses) = th
                    .iter()
                    .map(|&t| {
                        fb.pose(t).map(|q| {
                            [
                                q.p[0],
                                q.p[1],
                                (q.b[1] - q.a[1]).atan2(q.b[0] - q.a[0]) + 0.4,
                            ]
                        })
                    })
                    .collect::<Option<Vec<Pose>>>()
                else {
                    continue;
                };
                tried += 1;
                let s = motion(&poses, None).unwrap_or_else(|e| panic!("{n} poses {poses:?}: {e}"));
                for (p, &t) in poses.iter().zip(&s.crank_angles) {
                    let q = s.four_bar.pose(t).unwrap();
                    assert!(
                        (q.p[0] - p[0]).hypot(q.p[1] - p[1]) < 1e-9,
                        "{n} poses {poses:?}"
                    );
                }
            }
        }
        assert!(tried > 100, "{tried}");
    }
}
