//! Path generation with prescribed timing through three points: a four-bar whose coupler
//! point P is at Tⱼ when the crank is at θⱼ (rad, counter-clockwise from the frame line
//! O2 → O4, as [`super::error::prescribed_timing`] measures it), j = 1, 2, 3, exactly.
//!
//! **The crank's dyad** in the standard form (Erdman & Sandor, *Mechanism Design*, §8):
//! with W = A − O2 and Z = P − A at the first position (complex numbers), the crank's
//! rotations βⱼ = θⱼ − θ₁ (prescribed) and the coupler's αⱼ (free choices), the loop
//! O2 + W e^{iβⱼ} + Z e^{iαⱼ} = Tⱼ gives, for j = 2, 3, the 2×2 complex linear system
//!
//! W (e^{iβⱼ} − 1) + Z (e^{iαⱼ} − 1) = δⱼ = Tⱼ − T₁,
//!
//! solved by Cramer's rule: O2 = T₁ − W − Z, A = T₁ − Z.
//!
//! **The frame** must make the crank's angle θ₁ at the first position: its direction is
//! arg W − θ₁, and O4 = O2 + d (cos, sin)(arg W − θ₁), d the frame length (a free choice).
//!
//! **The rocker's dyad** by inversion: the coupler moves through the three poses
//! (Tⱼ, αⱼ); O4 is then a centre point, and its circle point B the centre of O4's positions
//! seen from the coupler, [`super::burmester::centre_point`] of the inverted poses
//! (−R(−αⱼ) Tⱼ, −αⱼ).
//!
//! The free choices (α₂, α₃, d): given ([`PathChoice`]), or by default the best of
//! αⱼ ∈ {−75°, −60°, …, 75°} and d ∈ {½, 1, 2, 3}·ℓ (ℓ the largest |Tⱼ − T₁|) by the
//! ranking of [`super::burmester`] (the three positions reached on one branch, a crank
//! that turns first, then the best transmission angle).

use super::burmester::{centre_point, score, REACH};
use super::error::prescribed_timing;
use super::four_bar::FourBar;
use crate::error::MechError;
use crate::kernel::link_state::{wrap, V2};
use nalgebra::Complex;

/// The free choices of the three-point method.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PathChoice {
    /// The coupler's rotations α₂, α₃ from the first position (rad).
    pub coupler_rotations: [f64; 2],
    /// The frame length d = |O2O4| (m).
    pub frame: f64,
}

/// A path generator with prescribed timing.
#[derive(Clone, Debug, PartialEq)]
pub struct PathSynthesis {
    /// The four-bar (SPEC §3f names), drawn at the first position, m.
    pub four_bar: FourBar,
    /// The free choices it was made with.
    pub choice: PathChoice,
    /// [`prescribed_timing`] at the targets and angles, m² (≈ 0).
    pub error: f64,
}

fn c(x: V2) -> Complex<f64> {
    Complex::new(x.x, x.y)
}

fn v(z: Complex<f64>) -> V2 {
    V2::new(z.re, z.im)
}

fn check(targets: &[[f64; 2]], angles: &[f64]) -> Result<f64, MechError> {
    if targets.len() != angles.len() {
        return Err(MechError::InvalidInput(format!(
            "{} targets but {} crank angles: give one angle per target",
            targets.len(),
            angles.len()
        )));
    }
    if targets.len() != 3 {
        return Err(MechError::InvalidInput(format!(
            "the three-point method takes exactly three targets, got {}{}",
            targets.len(),
            if targets.len() > 3 {
                ": for more, use the numerical path synthesis (mech synth path --timing prescribed)"
            } else {
                ": give three points and the crank angle at each"
            }
        )));
    }
    for (i, (t, a)) in targets.iter().zip(angles).enumerate() {
        if !(t[0].is_finite() && t[1].is_finite() && a.is_finite()) {
            return Err(MechError::InvalidInput(format!(
                "target {} ({}, {}) at crank angle {a} is not finite: give x, y (m) and the angle (rad) as finite numbers",
                i + 1,
                t[0],
                t[1]
            )));
        }
    }
    let t0 = V2::new(targets[0][0], targets[0][1]);
    let scale = targets
        .iter()
        .map(|t| (V2::new(t[0], t[1]) - t0).norm())
        .fold(0.0, f64::max);
    for i in 0..3 {
        for j in 0..i {
            let d = (V2::new(targets[i][0] - targets[j][0], targets[i][1] - targets[j][1])).norm();
            if !(d > 1e-12 * scale) {
                return Err(MechError::InvalidInput(format!(
                    "targets {} and {} coincide at ({}, {}): give three distinct points",
                    j + 1,
                    i + 1,
                    targets[i][0],
                    targets[i][1]
                )));
            }
            if wrap(angles[i] - angles[j]).abs() <= 1e-9 {
                return Err(MechError::InvalidInput(format!(
                    "targets {} and {} have the same crank angle {} rad: the crank at one angle puts P at one point; give distinct angles",
                    j + 1,
                    i + 1,
                    angles[i]
                )));
            }
        }
    }
    Ok(scale)
}

/// The four-bar of one choice (normalised: T₁ at the origin, ℓ = 1), or why not.
fn solve(ts: &[V2; 3], angles: &[f64], alpha: [f64; 2], d: f64) -> Option<FourBar> {
    let eb = |j: usize| Complex::from_polar(1.0, angles[j] - angles[0]) - 1.0;
    let ea = |k: usize| Complex::from_polar(1.0, alpha[k]) - 1.0;
    let (d2, d3) = (c(ts[1] - ts[0]), c(ts[2] - ts[0]));
    let det = eb(1) * ea(1) - eb(2) * ea(0);
    if !(det.norm() > 1e-9) {
        return None;
    }
    let w = (d2 * ea(1) - d3 * ea(0)) / det;
    let z = (eb(1) * d3 - eb(2) * d2) / det;
    let o2 = ts[0] - v(w) - v(z);
    let a = ts[0] - v(z);
    let f = w.arg() - angles[0];
    let o4 = o2 + V2::new(f.cos(), f.sin()) * d;
    // The inverted motion: pose j of the fixed plane seen from the coupler.
    let inverted: Vec<[f64; 3]> = [0.0, alpha[0], alpha[1]]
        .iter()
        .zip(ts)
        .map(|(&al, t)| {
            let p = -v(Complex::from_polar(1.0, -al) * c(*t - ts[0]));
            [p.x, p.y, -al]
        })
        .collect();
    let b = centre_point(&inverted, [o4.x - ts[0].x, o4.y - ts[0].y]).ok()?;
    let b = ts[0] + V2::new(b[0], b[1]);
    let pts = [o2, o4, a, b];
    if pts.iter().any(|x| !(x.norm() <= REACH)) {
        return None;
    }
    // Every link of positive length, and A and B apart from P (a link's points are
    // distinct in a mechanism file).
    let apart = [
        (a - o2).norm(),
        (b - a).norm(),
        (b - o4).norm(),
        d,
        (a - ts[0]).norm(),
        (b - ts[0]).norm(),
    ];
    if !apart.iter().all(|&x| x > 1e-9) {
        return None;
    }
    Some(FourBar {
        o2: [o2.x, o2.y],
        o4: [o4.x, o4.y],
        a: [a.x, a.y],
        b: [b.x, b.y],
        p: [ts[0].x, ts[0].y],
    })
}

/// A four-bar whose P is at `targets` (m) at the crank angles `angles` (rad, from the
/// frame line), exactly; `choice` the free choices, or `None` for the default search.
/// `InvalidInput` for other than three targets, a count of angles that differs, a
/// non-finite number, two targets at one point or at one crank angle, and when no choice
/// (or the given one) gives a four-bar that reaches the three positions on one branch.
pub fn three_points(
    targets: &[[f64; 2]],
    angles: &[f64],
    choice: Option<PathChoice>,
) -> Result<PathSynthesis, MechError> {
    let scale = check(targets, angles)?;
    let t0 = V2::new(targets[0][0], targets[0][1]);
    let ts = [0, 1, 2].map(|j| (V2::new(targets[j][0], targets[j][1]) - t0) / scale);
    let back = |fb: FourBar| {
        let m = |p: [f64; 2]| {
            let x = t0 + V2::new(p[0], p[1]) * scale;
            [x.x, x.y]
        };
        FourBar {
            o2: m(fb.o2),
            o4: m(fb.o4),
            a: m(fb.a),
            b: m(fb.b),
            p: targets[0],
        }
    };
    let tol = 1e-18 * scale * scale;
    let attempt = |ch: PathChoice| -> Option<PathSynthesis> {
        let fb = back(solve(&ts, angles, ch.coupler_rotations, ch.frame / scale)?);
        let error = prescribed_timing(&fb, targets, angles);
        (error <= tol).then_some(PathSynthesis {
            four_bar: fb,
            choice: ch,
            error,
        })
    };
    if let Some(ch) = choice {
        if !(ch.frame.is_finite()
            && ch.frame > 0.0
            && ch.coupler_rotations.iter().all(|a| a.is_finite()))
        {
            return Err(MechError::InvalidInput(format!(
                "the choice {ch:?} must have finite coupler rotations (rad) and a frame length > 0 m"
            )));
        }
        return attempt(ch).ok_or_else(|| {
            MechError::InvalidInput(format!(
                "the coupler rotations {:?} rad and frame {} m give no four-bar that reaches the three targets on one branch (or the system is singular); choose others, or let the method choose",
                ch.coupler_rotations, ch.frame
            ))
        });
    }
    let deg = std::f64::consts::PI / 180.0;
    let alphas: Vec<f64> = (-5..=5).map(|k| 15.0 * k as f64 * deg).collect();
    let mut best: Option<((bool, f64), PathSynthesis)> = None;
    for &a2 in &alphas {
        for &a3 in &alphas {
            for d in [0.5, 1.0, 2.0, 3.0] {
                let ch = PathChoice {
                    coupler_rotations: [a2, a3],
                    frame: d * scale,
                };
                let Some(s) = attempt(ch) else { continue };
                let f = super::error::frame_angle(&s.four_bar);
                let thetas: Vec<f64> = angles.iter().map(|a| f + a).collect();
                let sc = score(&s.four_bar, &thetas);
                if best.as_ref().is_none_or(|(b, _)| sc > *b) {
                    best = Some((sc, s));
                }
            }
        }
    }
    best.map(|(_, s)| s).ok_or_else(|| {
        MechError::InvalidInput(
            "no coupler rotations (−75° to 75°) and frame length (½ to 3 times the targets' extent) give a four-bar that reaches the three targets at these crank angles on one branch; give the choice (PathChoice), or other angles".into(),
        )
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::design::synthesis::error::frame_angle;

    fn known() -> FourBar {
        FourBar {
            o2: [0.0, 0.0],
            o4: [0.3, 0.0],
            a: [0.0, 0.1],
            b: [0.25, 0.2],
            p: [0.1, 0.3],
        }
    }

    /// By hand: targets T₁ = (2, 1), T₂ = (0, 1), T₃ = (−1, 0) at crank angles 0, π/2, π
    /// (β₂ = π/2, β₃ = π), coupler rotations α₂ = π, α₃ = −π/2, frame d = 1. Then
    /// δ₂ = −2, δ₃ = −3 − i, e^{iβ₂} − 1 = i − 1, e^{iβ₃} − 1 = −2, e^{iα₂} − 1 = −2,
    /// e^{iα₃} − 1 = −1 − i; the determinant (i − 1)(−1 − i) − (−2)(−2) = −2;
    /// W = (−2(−1 − i) − (−3 − i)(−2))/(−2) = 2, Z = ((i − 1)(−3 − i) − 4)/(−2) = i: O2 = T₁ − W − Z
    /// = (0, 0), A = T₁ − Z = (2, 0), the frame along arg W − θ₁ = 0: O4 = (1, 0). O4 seen
    /// from the coupler, R(−αⱼ)(O4 − Tⱼ): (−1, −1), (−1, 1), (0, 2), whose circumcentre is
    /// (1, 0) (y = 0 from the first two; from the last two (x + 1)² + 1 = x² + 4 ⇒ x = 1), radius √5:
    /// B = T₁ + (1, 0) = (3, 1). The four-bar O2 (0, 0), A (2, 0), B (3, 1), O4 (1, 0), P
    /// (2, 1): frame 1, crank 2, coupler √2, rocker √5 (Grashof, the frame shortest: a drag
    /// link); B at (3, 1), (−1, 1), (−1, −1), on one side of A → O4 at the three positions.
    #[test]
    fn a_hand_worked_case() {
        use std::f64::consts::{FRAC_PI_2, PI};
        let targets = [[2.0, 1.0], [0.0, 1.0], [-1.0, 0.0]];
        let angles = [0.0, FRAC_PI_2, PI];
        let ch = PathChoice {
            coupler_rotations: [PI, -FRAC_PI_2],
            frame: 1.0,
        };
        let s = three_points(&targets, &angles, Some(ch)).unwrap();
        let fb = s.four_bar;
        for (got, want) in [
            (fb.o2, [0.0, 0.0]),
            (fb.a, [2.0, 0.0]),
            (fb.b, [3.0, 1.0]),
            (fb.o4, [1.0, 0.0]),
            (fb.p, [2.0, 1.0]),
        ] {
            assert!(
                (got[0] - want[0]).abs() < 1e-12 && (got[1] - want[1]).abs() < 1e-12,
                "{got:?} vs {want:?}"
            );
        }
        assert!(s.error < 1e-26, "{}", s.error);
        for (t, &a) in targets.iter().zip(&angles) {
            let p = fb.pose(frame_angle(&fb) + a).unwrap().p;
            assert!(
                (p[0] - t[0]).abs() < 1e-12 && (p[1] - t[1]).abs() < 1e-12,
                "{p:?} vs {t:?}"
            );
        }
        assert!(fb.crank_turns());
        // The written file: the run-time input q is the crank's absolute angle.
        let m = crate::Mechanism::from_dsl(&fb.to_mech("PathGenerator", "test")).unwrap();
        for (t, &a) in targets.iter().zip(&angles) {
            let pp = m
                .pose(&[frame_angle(&fb) + a])
                .unwrap()
                .point("P")
                .unwrap()
                .pos;
            assert!((pp.x - t[0]).abs() < 1e-12 && (pp.y - t[1]).abs() < 1e-12);
        }
    }

    /// The targets of a known four-bar at known crank angles: met to 1e-12 by the default
    /// choice; with the known four-bar's own coupler rotations and frame, its pivots come
    /// back.
    #[test]
    fn the_targets_of_a_known_four_bar_are_met() {
        let fb = known();
        let angles = [0.3, 1.2, 2.2];
        let targets: Vec<[f64; 2]> = angles.iter().map(|&t| fb.pose(t).unwrap().p).collect();
        let s = three_points(&targets, &angles, None).unwrap();
        assert!(s.error < 1e-26, "{}", s.error);
        let f = frame_angle(&s.four_bar);
        for (t, &a) in targets.iter().zip(&angles) {
            let p = s.four_bar.pose(f + a).unwrap().p;
            assert!(
                (p[0] - t[0]).abs() < 1e-12 && (p[1] - t[1]).abs() < 1e-12,
                "{p:?} vs {t:?}"
            );
        }
        let rot = |t: f64| {
            let q = fb.pose(t).unwrap();
            (q.b[1] - q.a[1]).atan2(q.b[0] - q.a[0])
        };
        let ch = PathChoice {
            coupler_rotations: [wrap(rot(1.2) - rot(0.3)), wrap(rot(2.2) - rot(0.3))],
            frame: 0.3,
        };
        let s = three_points(&targets, &angles, Some(ch)).unwrap();
        for (x, y) in [
            (s.four_bar.o2, fb.o2),
            (s.four_bar.o4, fb.o4),
            (s.four_bar.b, fb.pose(0.3).unwrap().b),
        ] {
            assert!(
                (x[0] - y[0]).abs() < 1e-12 && (x[1] - y[1]).abs() < 1e-12,
                "{x:?} vs {y:?}"
            );
        }
    }

    #[test]
    fn bad_targets_are_refused_with_the_fix() {
        let msg = |r: Result<PathSynthesis, MechError>| match r {
            Err(MechError::InvalidInput(m)) => m,
            other => panic!("{other:?}"),
        };
        let t = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0]];
        assert!(msg(three_points(&t[..2], &[0.0, 1.0], None)).contains("exactly three"));
        assert!(msg(three_points(&t, &[0.0, 1.0], None)).contains("one angle per target"));
        assert!(
            msg(three_points(&[t[0], t[1], t[0]], &[0.0, 1.0, 2.0], None)).contains("coincide")
        );
        assert!(msg(three_points(
            &t,
            &[0.0, 1.0, 1.0 + std::f64::consts::TAU],
            None
        ))
        .contains("same crank angle"));
        assert!(msg(three_points(&t, &[0.0, f64::NAN, 2.0], None)).contains("not finite"));
    }
}
