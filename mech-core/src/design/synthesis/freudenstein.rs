//! Function generation by Freudenstein's equation (SPEC §3f `mech synth function`): a
//! four-bar whose output angle follows the input angle at given pairs.
//!
//! **Convention.** The input θ₂ is the angle of O2 → A (the crank) and the output θ₄ that
//! of O4 → B (the rocker), both rad, counter-clockwise from the frame line O2 → O4 (SPEC
//! §3f). With the frame d = |O2O4|, the crank a = |O2A|, the coupler b = |AB| and the rocker
//! c = |O4B|, the loop closure |B − A|² = b² with A = a (cos θ₂, sin θ₂),
//! B = (d + c cos θ₄, c sin θ₄), divided by 2ac, is Freudenstein's equation
//!
//! K₁ cos θ₄ − K₂ cos θ₂ + K₃ = cos(θ₂ − θ₄),  K₁ = d/a,  K₂ = d/c,
//! K₃ = (a² − b² + c² + d²)/(2ac)
//!
//! (Norton's form, *Design of Machinery*, §4.5: K₁ divides the frame by the **crank**;
//! written K₁ cos φ − K₂ cos ψ + K₃ = cos(φ − ψ) it has φ = θ₄ the output and ψ = θ₂ the
//! input, the cosine being even). It is linear in K = (K₁, K₂, K₃): three pairs give the
//! 3×3 system [cos θ₄ᵢ, −cos θ₂ᵢ, 1] K = cos(θ₂ᵢ − θ₄ᵢ), solved exactly (the three
//! precision points are met); more pairs give the same rows solved by linear least squares
//! (the structural error of the equation, not of the angles, is minimised). The four-bar
//! then has, for a chosen frame d: a = d/K₁, c = d/K₂, b² = a² + c² + d² − 2ac K₃.
//!
//! The returned [`FourBar`] has O2 at the origin, O4 at (d, 0) (the frame line is +x, so
//! the crank's absolute angle is θ₂), the drawing at the first pair's input, B on the
//! assembly branch that meets the pairs (least squares: the branch with the smaller
//! error), and P the coupler's middle.

use super::error::frame_angle;
use super::four_bar::FourBar;
use crate::error::MechError;
use crate::kernel::dyad::circle_circle;
use crate::kernel::link_state::{wrap, V2};
use nalgebra::{DMatrix, DVector, Matrix3, Vector3};

/// The pairs Freudenstein's equation needs for an exact solution (three unknowns).
pub const MIN_PAIRS: usize = 3;

/// The largest ratio of the system's extreme singular values before it is called
/// singular: beyond it the K's carry fewer than four significant digits.
pub const CONDITION: f64 = 1e12;

/// The largest output error (rad) at a pair an exact solution may have before the pairs
/// are said to lie on two assembly branches.
pub const EXACT_TOL: f64 = 1e-9;

/// A function generator: the four-bar, Freudenstein's K, and how well it meets the pairs.
#[derive(Clone, Debug, PartialEq)]
pub struct FunctionSynthesis {
    /// The four-bar (SPEC §3f names), m.
    pub four_bar: FourBar,
    /// (K₁, K₂, K₃) of the module's equation, dimensionless.
    pub k: [f64; 3],
    /// Three pairs, solved exactly (true), or more by least squares (false).
    pub exact: bool,
    /// E = Σᵢ (θ₄(θ₂ᵢ) − θ₄ᵢ)², rad² ([`function_error`]).
    pub error: f64,
}

/// Chebyshev spacing of `n` precision points over [lo, hi]:
/// xⱼ = (lo + hi)/2 − (hi − lo)/2 · cos((2j − 1)π/(2n)), j = 1..n, increasing; the
/// spacing that makes the largest structural error between them smallest for a smooth
/// function (Freudenstein 1955).
pub fn chebyshev(lo: f64, hi: f64, n: usize) -> Vec<f64> {
    let (m, h) = (0.5 * (lo + hi), 0.5 * (hi - lo));
    (1..=n)
        .map(|j| m - h * ((2 * j - 1) as f64 * std::f64::consts::PI / (2 * n) as f64).cos())
        .collect()
}

/// Refuse pairs that cannot define a function generator: fewer than [`MIN_PAIRS`], a
/// non-finite angle, or two pairs with the same input (a four-bar has one output per
/// input on its branch).
fn check_pairs(pairs: &[[f64; 2]]) -> Result<(), MechError> {
    if pairs.len() < MIN_PAIRS {
        return Err(MechError::InvalidInput(format!(
            "function synthesis needs at least {MIN_PAIRS} (input, output) pairs, got {}: give three for Freudenstein's exact solution, more for least squares",
            pairs.len()
        )));
    }
    for (i, p) in pairs.iter().enumerate() {
        if !p.iter().all(|x| x.is_finite()) {
            return Err(MechError::InvalidInput(format!(
                "pair {} (input {}, output {}) is not finite: give both angles in rad as finite numbers",
                i + 1,
                p[0],
                p[1]
            )));
        }
    }
    for (i, p) in pairs.iter().enumerate() {
        for (j, q) in pairs.iter().enumerate().take(i) {
            if wrap(p[0] - q[0]).abs() <= 1e-12 {
                return Err(MechError::InvalidInput(format!(
                    "pairs {} and {} have the same input angle {} rad: a four-bar has one output per input; remove one of them or change its input",
                    j + 1,
                    i + 1,
                    p[0]
                )));
            }
        }
    }
    Ok(())
}

/// Freudenstein's (K₁, K₂, K₃) for the pairs (input θ₂ᵢ, output θ₄ᵢ), rad: the 3×3 system solved exactly
/// for three pairs, linear least squares for more. `InvalidInput` for fewer than three
/// pairs, a non-finite angle, two pairs with the same input, or a singular system
/// (condition beyond [`CONDITION`]).
pub fn coefficients(pairs: &[[f64; 2]]) -> Result<[f64; 3], MechError> {
    check_pairs(pairs)?;
    let n = pairs.len();
    let m = DMatrix::from_fn(n, 3, |i, j| {
        let [input, output] = pairs[i];
        [output.cos(), -input.cos(), 1.0][j]
    });
    let rhs = DVector::from_fn(n, |i, _| (pairs[i][0] - pairs[i][1]).cos());
    let sv = m.clone().svd(false, false).singular_values;
    let (hi, lo) = (sv.max(), sv.min());
    if !(lo * CONDITION > hi) {
        return Err(MechError::InvalidInput(format!(
            "the pairs give a singular Freudenstein system (singular values {:.3e} .. {:.3e}): the rows [cos θ₄, −cos θ₂, 1] are (nearly) dependent, e.g. inputs or outputs all with the same cosine; spread the pairs over the range (chebyshev spacing) or change one",
            hi, lo
        )));
    }
    let k = if n == MIN_PAIRS {
        let a = Matrix3::from_fn(|i, j| m[(i, j)]);
        let b = Vector3::new(rhs[0], rhs[1], rhs[2]);
        a.lu().solve(&b).ok_or_else(|| {
            MechError::InvalidInput(
                "the three pairs give a singular Freudenstein system; change one pair".into(),
            )
        })?
    } else {
        let x = m
            .svd(true, true)
            .solve(&rhs, 0.0)
            .map_err(|e| MechError::InvalidInput(format!("least squares failed: {e}")))?;
        Vector3::new(x[0], x[1], x[2])
    };
    Ok([k[0], k[1], k[2]])
}

/// The output angle θ₄ (rad, (−π, π], from the frame line) of `fb` at input θ₂ (rad,
/// from the frame line): the direction of O4 → B at crank angle (frame direction + θ₂), on
/// the drawing's branch; `None` where it does not assemble.
pub fn output_angle(fb: &FourBar, phi: f64) -> Option<f64> {
    let f = frame_angle(fb);
    let p = fb.pose(f + phi)?;
    Some(wrap((p.b[1] - fb.o4[1]).atan2(p.b[0] - fb.o4[0]) - f))
}

/// E = Σᵢ (θ₄(θ₂ᵢ) − θ₄ᵢ)², rad², each difference wrapped to (−π, π]: zero when every pair
/// is met; infinite when the four-bar does not assemble at one of the inputs.
pub fn function_error(fb: &FourBar, pairs: &[[f64; 2]]) -> f64 {
    pairs
        .iter()
        .map(|&[phi, psi]| output_angle(fb, phi).map_or(f64::INFINITY, |o| wrap(o - psi).powi(2)))
        .sum()
}

/// The four-bar of Freudenstein's `k` with frame `frame` (m): O2 = (0, 0), O4 = (d, 0),
/// drawn at the first of `pairs`' inputs where it assembles, on the branch with the smaller
/// [`function_error`]; P the coupler's middle. `InvalidInput` when a K gives a link of
/// negative or infinite length (with the fix: shift the inputs or the outputs by π), when
/// b² ≤ 0, or when it assembles at none of the inputs.
pub fn four_bar(k: [f64; 3], frame: f64, pairs: &[[f64; 2]]) -> Result<FourBar, MechError> {
    let [k1, k2, k3] = k;
    let d = frame;
    if !(d.is_finite() && d > 0.0) {
        return Err(MechError::InvalidInput(format!(
            "the frame length must be a finite number > 0 m, got {d}"
        )));
    }
    for (name, kv, link, fix) in [
        ("K1", k1, "crank a = d/K1", "input"),
        ("K2", k2, "rocker c = d/K2", "output"),
    ] {
        if !(kv.abs() > 1e-9) {
            return Err(MechError::InvalidInput(format!(
                "{name} = {kv:e}: the {link} would be infinitely long; change the pairs (their {fix} angles)"
            )));
        }
        if kv < 0.0 {
            return Err(MechError::InvalidInput(format!(
                "{name} = {kv}: the {link} would be negative, the link pointing opposite to the given {fix} angles; add π to every {fix} angle (the same linkage, that link measured the other way) or choose other pairs"
            )));
        }
    }
    let (a, c) = (d / k1, d / k2);
    let b2 = a * a + c * c + d * d - 2.0 * a * c * k3;
    if !(b2 > 1e-18 * (a * a + c * c + d * d)) {
        return Err(MechError::InvalidInput(format!(
            "K = ({k1}, {k2}, {k3}) gives no coupler (b² = {b2:e} m² ≤ 0, crank {a} m, rocker {c} m, frame {d} m); change the pairs"
        )));
    }
    let (o2, o4) = (V2::zeros(), V2::new(d, 0.0));
    let mut best: Option<(f64, FourBar)> = None;
    for &[phi, _] in pairs {
        let am = V2::new(phi.cos(), phi.sin()) * a;
        for side in [1.0, -1.0] {
            let Ok(bm) = circle_circle(am, b2, o4, c * c, side) else {
                continue;
            };
            let fb = FourBar {
                o2: [o2.x, o2.y],
                o4: [o4.x, o4.y],
                a: [am.x, am.y],
                b: [bm.x, bm.y],
                p: [0.5 * (am.x + bm.x), 0.5 * (am.y + bm.y)],
            };
            let e = function_error(&fb, pairs);
            if best.as_ref().is_none_or(|(b, _)| e < *b) {
                best = Some((e, fb));
            }
        }
        if best.is_some() {
            break;
        }
    }
    best.map(|(_, fb)| fb).ok_or_else(|| {
        MechError::InvalidInput(format!(
            "the four-bar of K = ({k1}, {k2}, {k3}) (crank {a} m, coupler {} m, rocker {c} m, frame {d} m) assembles at none of the inputs; change the pairs",
            b2.sqrt()
        ))
    })
}

/// A function generator through `pairs` (θ₂ᵢ, θ₄ᵢ), rad, with frame `frame` (m): three pairs
/// met exactly (Freudenstein), more by least squares on K. `InvalidInput` as
/// [`coefficients`] and [`four_bar`], and for three pairs that lie on two assembly branches
/// (the branch defect: no single branch meets them all).
pub fn function(pairs: &[[f64; 2]], frame: f64) -> Result<FunctionSynthesis, MechError> {
    let k = coefficients(pairs)?;
    let four_bar = four_bar(k, frame, pairs)?;
    let error = function_error(&four_bar, pairs);
    let exact = pairs.len() == MIN_PAIRS;
    if exact && !(error <= 3.0 * EXACT_TOL * EXACT_TOL) {
        return Err(MechError::InvalidInput(format!(
            "the three pairs lie on the two assembly branches of the four-bar K = ({}, {}, {}) (branch defect: no branch meets them all, error {error:e} rad²); choose pairs closer together or in another range",
            k[0], k[1], k[2]
        )));
    }
    Ok(FunctionSynthesis {
        four_bar,
        k,
        exact,
        error,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The pairs of the hand-worked crank-rocker below.
    fn hand_pairs() -> [[f64; 2]; 3] {
        let x2 = (45.0 + 135f64.sqrt()) / 20.0;
        let y2 = 3.0 * x2 - 6.5;
        [
            [0.0, (63f64.sqrt() / 4.0).atan2(13.0 / 4.0 - 3.0)],
            [std::f64::consts::FRAC_PI_2, y2.atan2(x2 - 3.0)],
            [
                std::f64::consts::PI,
                (135f64.sqrt() / 8.0).atan2(13.0 / 8.0 - 3.0),
            ],
        ]
    }

    /// The pairs of y = log₁₀ x below.
    fn log_pairs() -> Vec<[f64; 2]> {
        chebyshev(1.0, 2.0, 3).into_iter().map(log_map).collect()
    }

    fn log_map(x: f64) -> [f64; 2] {
        let deg = std::f64::consts::PI / 180.0;
        [
            (30.0 + 60.0 * (x - 1.0)) * deg,
            (60.0 + 90.0 * x.log10() / 2f64.log10()) * deg,
        ]
    }

    /// The hand-worked crank-rocker a = 1, b = 3, c = 2, d = 3 (Grashof: 1 + 3 ≤ 2 + 3),
    /// whose K are K₁ = d/a = 3, K₂ = d/c = 3/2, K₃ = (1 − 9 + 4 + 9)/(2·1·2) = 5/4. Its
    /// output at three inputs, by hand (B on the circles (A, 3) and (O4, 2), above the
    /// frame):
    /// - θ₂ = 0, A = (1, 0): subtracting the circles, 4x − 8 = 5, x = 13/4, y = √63/4;
    /// - θ₂ = π/2, A = (0, 1): 6x − 2y = 13 and 10x² − 45x + 47.25 = 0, x = (45 + √135)/20
    ///   (the root above the frame line);
    /// - θ₂ = π, A = (−1, 0): 8x − 8 = 5, x = 13/8, y = √135/8.
    ///
    /// θ₄ = atan2(y, x − 3). Freudenstein's system gives K back to 1e-12, and the four-bar
    /// (frame 3) meets the three outputs to 1e-12.
    #[test]
    fn a_hand_worked_crank_rocker_gives_its_k_back() {
        let pairs = hand_pairs();
        let x2 = (45.0 + 135f64.sqrt()) / 20.0;
        let y2 = 3.0 * x2 - 6.5;
        // y2 is on the circle (O4, 2) by construction of the quadratic.
        assert!(((x2 - 3.0).powi(2) + y2 * y2 - 4.0).abs() < 1e-12);
        let k = coefficients(&pairs).unwrap();
        for (got, want) in k.iter().zip([3.0, 1.5, 1.25]) {
            assert!((got - want).abs() < 1e-12, "{k:?}");
        }
        let s = function(&pairs, 3.0).unwrap();
        assert!(s.exact);
        let r = s.four_bar.lengths();
        for (got, want) in r.iter().zip([3.0, 1.0, 3.0, 2.0]) {
            assert!((got - want).abs() < 1e-12, "{r:?}");
        }
        for &[phi, psi] in &pairs {
            let o = output_angle(&s.four_bar, phi).unwrap();
            assert!(wrap(o - psi).abs() < 1e-12, "{phi}: {o} vs {psi}");
        }
        assert!(s.four_bar.crank_turns());
    }

    /// Freudenstein's classic y = log₁₀ x on 1 ≤ x ≤ 2, three Chebyshev precision points,
    /// the input turning Δθ₂ = 60° from 30° and the output Δθ₄ = 90° from 60°
    /// (θ₂ = 30° + 60° (x − 1), θ₄ = 60° + 90° log₁₀ x / log₁₀ 2). The K against the same
    /// system solved in 50-digit arithmetic (mpmath 1.3, `lu_solve`):
    /// K₁ = 0.3395865098846758189555118, K₂ = 0.1133489457314321906090147,
    /// K₃ = 0.7941602341151814167085249 (for d = 1: a = 2.9447577300393993, b =
    /// 6.8000683081906561, c = 8.8223140810624703), and against Cramer's rule on the f64
    /// rows, to 1e-12; the four-bar meets the three outputs to 1e-12, and between them the
    /// error is small but not zero.
    #[test]
    fn log_x_by_three_chebyshev_points() {
        let xs = chebyshev(1.0, 2.0, 3);
        // cos(π/6), cos(π/2), cos(5π/6): 1.5 ∓ √3/4 and 1.5.
        assert!((xs[0] - (1.5 - 3f64.sqrt() / 4.0)).abs() < 1e-15);
        assert!((xs[1] - 1.5).abs() < 1e-15 && (xs[2] - (1.5 + 3f64.sqrt() / 4.0)).abs() < 1e-15);
        let deg = std::f64::consts::PI / 180.0;
        let pairs = log_pairs();
        let k = coefficients(&pairs).unwrap();
        let rows: Vec<[f64; 4]> = pairs
            .iter()
            .map(|&[f, p]| [p.cos(), -f.cos(), 1.0, (f - p).cos()])
            .collect();
        let det = |c: [usize; 3]| {
            let m = |i: usize, j: usize| rows[i][c[j]];
            m(0, 0) * (m(1, 1) * m(2, 2) - m(1, 2) * m(2, 1))
                - m(0, 1) * (m(1, 0) * m(2, 2) - m(1, 2) * m(2, 0))
                + m(0, 2) * (m(1, 0) * m(2, 1) - m(1, 1) * m(2, 0))
        };
        // The 50-digit values rounded to f64.
        let mp = [0.3395865098846758, 0.11334894573143219, 0.7941602341151814];
        for (a, b) in k.iter().zip(mp) {
            assert!((a - b).abs() < 1e-12, "{k:?} vs {mp:?}");
        }
        let d = det([0, 1, 2]);
        let cramer = [det([3, 1, 2]) / d, det([0, 3, 2]) / d, det([0, 1, 3]) / d];
        for (a, b) in k.iter().zip(cramer) {
            assert!(
                (a - b).abs() < 1e-12 * (1.0 + b.abs()),
                "{k:?} vs {cramer:?}"
            );
        }
        let s = function(&pairs, 1.0).unwrap();
        for &[phi, psi] in &pairs {
            let o = output_angle(&s.four_bar, phi).unwrap();
            assert!(wrap(o - psi).abs() < 1e-12, "{phi}: {o} vs {psi}");
        }
        let mid = log_map(1.25);
        let e = wrap(output_angle(&s.four_bar, mid[0]).unwrap() - mid[1]).abs();
        assert!(
            e > 1e-6 && e < 1.0 * deg,
            "structural error at x = 1.25: {e}"
        );
    }

    /// More pairs than three: least squares; pairs taken from a real four-bar are met
    /// exactly all the same (the system is consistent), pairs off it are not.
    #[test]
    fn least_squares_recovers_a_four_bar_from_many_pairs() {
        let fb = FourBar {
            o2: [0.0, 0.0],
            o4: [1.0, 0.0],
            a: [0.0, 0.4],
            b: [0.9, 0.8],
            p: [0.45, 0.6],
        };
        let pairs: Vec<[f64; 2]> = (0..9)
            .map(|j| {
                let phi = 0.3 + 0.25 * j as f64;
                [phi, output_angle(&fb, phi).unwrap()]
            })
            .collect();
        let s = function(&pairs, 1.0).unwrap();
        assert!(!s.exact);
        assert!(s.error < 1e-24, "{}", s.error);
        for (g, w) in s.four_bar.lengths().iter().zip(fb.lengths()) {
            assert!((g - w).abs() < 1e-12);
        }
        let mut noisy = pairs.clone();
        noisy[4][1] += 0.01;
        let s = function(&noisy, 1.0).unwrap();
        assert!(s.error > 1e-8 && s.error < 1e-3, "{}", s.error);
    }

    /// The written file loads, and its run-time output angle (q is the crank's absolute
    /// angle, the frame line being +x) agrees with the four-bar's own.
    #[test]
    fn the_file_loads_and_moves_like_the_four_bar() {
        let pairs = log_pairs();
        let s = function(&pairs, 0.2).unwrap();
        let m =
            crate::Mechanism::from_dsl(&s.four_bar.to_mech("FunctionGenerator", "test")).unwrap();
        for &[phi, psi] in &pairs {
            let pose = m.pose(&[phi]).unwrap();
            let b = pose.point("B").unwrap().pos;
            let o = (b.y - s.four_bar.o4[1]).atan2(b.x - s.four_bar.o4[0]);
            assert!(wrap(o - psi).abs() < 1e-12, "{o} vs {psi}");
            let p = s.four_bar.pose(phi).unwrap();
            assert!((b.x - p.b[0]).abs() < 1e-12 && (b.y - p.b[1]).abs() < 1e-12);
        }
    }

    #[test]
    fn bad_pairs_are_refused_with_the_fix() {
        let msg = |r: Result<FunctionSynthesis, MechError>| match r {
            Err(MechError::InvalidInput(m)) => m,
            other => panic!("{other:?}"),
        };
        assert!(msg(function(&[[0.1, 0.2], [0.3, 0.4]], 1.0)).contains("at least 3"));
        assert!(msg(function(&[[0.1, 0.2], [0.3, f64::NAN], [0.5, 0.6]], 1.0)).contains("pair 2"));
        assert!(msg(function(&[[0.1, 0.2], [0.3, 0.4], [0.1, 0.6]], 1.0))
            .contains("pairs 1 and 3 have the same input"));
        // Outputs all equal: the column cos θ₄ is a multiple of the column 1.
        assert!(msg(function(&[[0.1, 0.7], [0.3, 0.7], [0.5, 0.7]], 1.0)).contains("singular"));
        let pairs = hand_pairs();
        assert!(msg(function(&pairs, -1.0)).contains("frame"));
        assert!(msg(function(&pairs, f64::NAN)).contains("frame"));
        // The same linkage with the crank (the rocker) measured the other way: K1 < 0
        // (K2 < 0), and the fix says so.
        let pi = std::f64::consts::PI;
        let turned: Vec<[f64; 2]> = pairs.iter().map(|p| [p[0] + pi, p[1]]).collect();
        assert!(msg(function(&turned, 1.0)).contains("add π to every input"));
        let turned: Vec<[f64; 2]> = pairs.iter().map(|p| [p[0], p[1] + pi]).collect();
        assert!(msg(function(&turned, 1.0)).contains("add π to every output"));
    }
}
