//! Equivalent mass systems (`docs/theory.md` §9): a rigid link replaced by point masses
//! rigidly joined. *Static* equivalence keeps the mass and the centre of gravity;
//! *complete* equivalence also keeps the inertia.
//!
//! Coordinates are relative to the link's centre of gravity G (m); masses in kg,
//! moments and products of inertia about G in kg·m².

use crate::MechError;
use nalgebra::{SMatrix, SVector};

/// Three point masses of a bar with complete equivalence: at its ends A and B and at G.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BarMasses {
    /// Mass at A, kg.
    pub at_a: f64,
    /// Mass at B, kg.
    pub at_b: f64,
    /// Mass at G, kg (may be negative when I_G > m r_A r_B: then no positive system of
    /// these three points exists).
    pub at_g: f64,
}

fn positive(what: &str, v: f64) -> Result<f64, MechError> {
    if v.is_finite() && v > 0.0 {
        Ok(v)
    } else {
        Err(MechError::InvalidInput(format!(
            "{what} must be finite and > 0, got {v}"
        )))
    }
}

fn non_negative(what: &str, v: f64) -> Result<f64, MechError> {
    if v.is_finite() && v >= 0.0 {
        Ok(v)
    } else {
        Err(MechError::InvalidInput(format!(
            "{what} must be finite and ≥ 0, got {v}"
        )))
    }
}

/// A bar of mass `m` (kg) and inertia `i_g` about G (kg·m²), G at distances `r_a`, `r_b`
/// (m) from its ends, as three masses at A, B and G (complete equivalence):
/// m_A = I_G/(r_A l), m_B = I_G/(r_B l), m_G = m − I_G/(r_A r_B), l = r_A + r_B.
pub fn bar_three_masses(m: f64, i_g: f64, r_a: f64, r_b: f64) -> Result<BarMasses, MechError> {
    let (m, i_g) = (non_negative("mass", m)?, non_negative("inertia", i_g)?);
    let (r_a, r_b) = (positive("r_A", r_a)?, positive("r_B", r_b)?);
    let l = r_a + r_b;
    let out = BarMasses {
        at_a: i_g / (r_a * l),
        at_b: i_g / (r_b * l),
        at_g: m - i_g / (r_a * r_b),
    };
    finite_masses(&[out.at_a, out.at_b, out.at_g])?;
    Ok(out)
}

/// Static equivalence of a bar by two masses at its ends: m_A = m r_B / l, m_B = m r_A / l.
pub fn bar_two_masses_static(m: f64, r_a: f64, r_b: f64) -> Result<(f64, f64), MechError> {
    let m = non_negative("mass", m)?;
    let (r_a, r_b) = (positive("r_A", r_a)?, positive("r_B", r_b)?);
    let l = r_a + r_b;
    let out = (m * r_b / l, m * r_a / l);
    finite_masses(&[out.0, out.1])?;
    Ok(out)
}

/// Complete equivalence of a bar by two masses: one at distance `r_a` from G, the other
/// on the far side at r_B = I_G/(m r_A) (the centre of percussion of A), so that m_G = 0:
/// returns (m_A, m_B, r_B) with m_A = m r_B/(r_A + r_B), m_B = m r_A/(r_A + r_B).
pub fn bar_two_masses_complete(m: f64, i_g: f64, r_a: f64) -> Result<(f64, f64, f64), MechError> {
    let (m, i_g, r_a) = (
        positive("mass", m)?,
        positive("inertia", i_g)?,
        positive("r_A", r_a)?,
    );
    let r_b = i_g / (m * r_a);
    let out = (m * r_b / (r_a + r_b), m * r_a / (r_a + r_b), r_b);
    finite_masses(&[out.0, out.1, out.2])?;
    Ok(out)
}

/// A planar link of mass `m` and inertia `i_g` about G by four masses: three at the
/// given points p_k = (x_k, y_k) relative to G and one at G, from
/// Σ m_k x_k = 0, Σ m_k y_k = 0, Σ m_k (x_k² + y_k²) = I_G, m_G = m − Σ m_k.
/// Returns [m_1, m_2, m_3, m_G]; `Singular` when the three points are collinear with G
/// in a way that leaves the system without a unique solution.
pub fn planar_four_masses(m: f64, i_g: f64, points: [[f64; 2]; 3]) -> Result<[f64; 4], MechError> {
    let (m, i_g) = (non_negative("mass", m)?, non_negative("inertia", i_g)?);
    crate::error::check_finite("points", points.as_flattened())?;
    let a = SMatrix::<f64, 3, 3>::from_fn(|r, c| {
        let [x, y] = points[c];
        [x, y, x * x + y * y][r]
    });
    let b = SVector::<f64, 3>::new(0.0, 0.0, i_g);
    let x = solve(a, b)?;
    let out = [x[0], x[1], x[2], m - x.sum()];
    finite_masses(&out)?;
    Ok(out)
}

/// The inertia of a spatial rigid body about its centre of gravity: moments
/// I_x = Σ m (y² + z²), I_y, I_z and products C_x = Σ m y z, C_y = Σ m x z, C_z = Σ m x y
/// (the notation of `docs/theory.md` §9.3), kg·m².
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SpatialInertia {
    /// I_x, kg·m².
    pub ix: f64,
    /// I_y, kg·m².
    pub iy: f64,
    /// I_z, kg·m².
    pub iz: f64,
    /// C_x = Σ m y z, kg·m².
    pub cx: f64,
    /// C_y = Σ m x z, kg·m².
    pub cy: f64,
    /// C_z = Σ m x y, kg·m².
    pub cz: f64,
}

/// A spatial rigid body of mass `m` by ten point masses at the given points (relative to
/// G, m): the ten linear conditions of `docs/theory.md` §9.3 — Σ m_i = m,
/// Σ m_i (x_i, y_i, z_i) = 0, the three moments and the three products of inertia.
/// `Singular` when the points do not determine the masses.
pub fn spatial_ten_masses(
    m: f64,
    inertia: SpatialInertia,
    points: [[f64; 3]; 10],
) -> Result<[f64; 10], MechError> {
    let m = non_negative("mass", m)?;
    let SpatialInertia {
        ix,
        iy,
        iz,
        cx,
        cy,
        cz,
    } = inertia;
    crate::error::check_finite("inertia", &[ix, iy, iz, cx, cy, cz])?;
    crate::error::check_finite("points", points.as_flattened())?;
    let a = SMatrix::<f64, 10, 10>::from_fn(|r, c| {
        let [x, y, z] = points[c];
        [
            1.0,
            x,
            y,
            z,
            y * y + z * z,
            x * x + z * z,
            x * x + y * y,
            y * z,
            x * z,
            x * y,
        ][r]
    });
    let b = SVector::<f64, 10>::from([m, 0.0, 0.0, 0.0, ix, iy, iz, cx, cy, cz]);
    let x = solve(a, b)?;
    finite_masses(x.as_slice())?;
    Ok(x.into())
}

/// `Ok` when every mass (and distance) is finite; else `InvalidInput`: the numbers
/// given are so far apart (an inertia of 1e15 kg·m² at 1e-300 m) that a mass overflows f64.
fn finite_masses(values: &[f64]) -> Result<(), MechError> {
    if crate::error::all_finite(values) {
        Ok(())
    } else {
        Err(MechError::InvalidInput(format!(
            "the equivalent masses overflow f64 ({values:?}): the mass, inertia and distances given are too far apart in magnitude; check their units"
        )))
    }
}

/// Solve a small square system, `Singular` (with a condition estimate) when it is.
fn solve<const N: usize>(
    a: SMatrix<f64, N, N>,
    b: SVector<f64, N>,
) -> Result<SVector<f64, N>, MechError> {
    let lu = crate::kernel::linalg::Lu::new(a);
    let condition = lu.condition();
    if !(condition < 1e12) {
        return Err(MechError::Singular { condition });
    }
    Ok(lu.solve(&b))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::kernel::measure::within;

    #[test]
    fn uniform_rod_is_one_sixth_at_each_end_and_two_thirds_at_the_middle() {
        let (m, l) = (3.0, 0.8);
        let e = bar_three_masses(m, m * l * l / 12.0, l / 2.0, l / 2.0).unwrap();
        // measured worst 0 (be05608); exact; a few ulps
        assert!(within((e.at_a - m / 6.0).abs(), 1e-15) && within((e.at_b - m / 6.0).abs(), 1e-15));
        // measured worst 0 (be05608); exact; a few ulps
        assert!(within((e.at_g - 2.0 * m / 3.0).abs(), 1e-15));
    }

    #[test]
    fn bar_systems_keep_mass_cg_and_inertia() {
        let (m, i_g, r_a, r_b) = (2.4, 9.5e-3, 0.09, 0.15);
        let e = bar_three_masses(m, i_g, r_a, r_b).unwrap();
        // measured worst 0 (be05608); exact; a few ulps
        assert!(within((e.at_a + e.at_b + e.at_g - m).abs(), 1e-15));
        // measured worst 0 (be05608); exact; a few ulps
        assert!(within((-e.at_a * r_a + e.at_b * r_b).abs(), 1e-15));
        // measured worst 1.7e-18 (be05608); 100×
        assert!(within(
            (e.at_a * r_a * r_a + e.at_b * r_b * r_b - i_g).abs(),
            1e-17
        ));
        let (sa, sb) = bar_two_masses_static(m, r_a, r_b).unwrap();
        // measured worst 0 (be05608); exact; a few ulps
        assert!(within((sa + sb - m).abs(), 1e-15) && within((-sa * r_a + sb * r_b).abs(), 1e-15));
        let (ca, cb, rb) = bar_two_masses_complete(m, i_g, r_a).unwrap();
        // measured worst 0, 1.4e-17 (be05608); 100×
        assert!(within((ca + cb - m).abs(), 1e-14) && within((-ca * r_a + cb * rb).abs(), 1e-15));
        // measured worst 0 (be05608); exact; a few ulps
        assert!(within((ca * r_a * r_a + cb * rb * rb - i_g).abs(), 1e-16));
        assert!(bar_three_masses(m, i_g, 0.0, r_b).is_err());
        assert!(bar_two_masses_complete(f64::NAN, i_g, r_a).is_err());
    }

    /// Numbers each in range but far apart in magnitude made `Ok` with an infinity or a
    /// NaN (found by `mech-fuzz` on the links of mutated mechanisms): an error now.
    #[test]
    fn masses_that_overflow_are_an_error_not_an_infinity() {
        let overflow = |r: Result<Vec<f64>, MechError>| match r {
            Err(MechError::InvalidInput(m)) => assert!(m.contains("overflow"), "{m}"),
            other => panic!("expected the overflow, got {other:?}"),
        };
        // I_G/(r_A l) = 1e15/1e-600.
        overflow(bar_three_masses(1.0, 1e15, 1e-300, 1e-300).map(|e| vec![e.at_a, e.at_b, e.at_g]));
        // r_B = I_G/(m r_A) = inf, then m r_B/(r_A + r_B) = inf/inf = NaN.
        overflow(bar_two_masses_complete(1e-18, 1e15, 1e-300).map(|(a, b, r)| vec![a, b, r]));
        overflow(bar_two_masses_static(1e308, 1e308, 1e308).map(|(a, b)| vec![a, b]));
        // The same bars at ordinary numbers are finite.
        assert!(bar_three_masses(1.0, 1e-3, 0.1, 0.2).is_ok());
        assert!(bar_two_masses_complete(1.0, 1e-3, 0.1).is_ok());
    }

    #[test]
    fn planar_four_masses_keep_mass_cg_and_inertia() {
        let (m, i_g) = (1.377, 0.0079);
        let pts = [[-0.08, -0.05], [0.12, 0.02], [-0.03, 0.09]];
        let w = planar_four_masses(m, i_g, pts).unwrap();
        // measured worst 0 (be05608); exact; a few ulps
        assert!(within((w.iter().sum::<f64>() - m).abs(), 1e-14));
        let sx: f64 = (0..3).map(|k| w[k] * pts[k][0]).sum();
        let sy: f64 = (0..3).map(|k| w[k] * pts[k][1]).sum();
        let si: f64 = (0..3)
            .map(|k| w[k] * (pts[k][0].powi(2) + pts[k][1].powi(2)))
            .sum();
        // measured worst 0 (be05608); exact; a few ulps
        assert!(
            within(sx.abs(), 1e-16) && within(sy.abs(), 1e-16) && within((si - i_g).abs(), 1e-17)
        );
        // Three points on one line through G cannot hold both cg conditions and the inertia.
        assert!(matches!(
            planar_four_masses(m, i_g, [[0.1, 0.0], [0.2, 0.0], [-0.1, 0.0]]),
            Err(MechError::Singular { .. })
        ));
    }

    #[test]
    fn ten_masses_reproduce_a_box() {
        // A uniform box a × b × c: I_x = m (b² + c²)/12, ..., no products.
        let (m, a, b, c) = (5.0f64, 0.3f64, 0.2f64, 0.1f64);
        let inertia = SpatialInertia {
            ix: m * (b * b + c * c) / 12.0,
            iy: m * (a * a + c * c) / 12.0,
            iz: m * (a * a + b * b) / 12.0,
            cx: 0.0,
            cy: 0.0,
            cz: 0.0,
        };
        let pts = [
            [0.0, 0.0, 0.0],
            [0.1, 0.0, 0.0],
            [-0.1, 0.02, 0.0],
            [0.0, 0.1, 0.01],
            [0.02, -0.1, 0.0],
            [0.0, 0.01, 0.05],
            [0.01, 0.0, -0.05],
            [0.07, 0.07, 0.0],
            [0.06, 0.0, 0.04],
            [0.0, 0.05, 0.04],
        ];
        let w = spatial_ten_masses(m, inertia, pts).unwrap();
        let sum = |f: &dyn Fn([f64; 3]) -> f64| (0..10).map(|i| w[i] * f(pts[i])).sum::<f64>();
        // measured worst 8.9e-16 (be05608); 100×
        assert!(within((sum(&|_| 1.0) - m).abs(), 5e-14));
        for k in 0..3 {
            // measured worst 1.9e-17 (be05608); 100×
            assert!(within(sum(&|p| p[k]).abs(), 1e-15));
        }
        // measured worst 3.5e-18 (be05608); 100×
        assert!(within(
            (sum(&|p| p[1] * p[1] + p[2] * p[2]) - inertia.ix).abs(),
            2e-16
        ));
        // measured worst 6.9e-18 (be05608); 100×
        assert!(within(
            (sum(&|p| p[0] * p[0] + p[2] * p[2]) - inertia.iy).abs(),
            5e-16
        ));
        // measured worst 6.9e-18 (be05608); 100×
        assert!(within(
            (sum(&|p| p[0] * p[0] + p[1] * p[1]) - inertia.iz).abs(),
            5e-16
        ));
        assert!(
            within(sum(&|p| p[1] * p[2]).abs(), 2e-17) // measured worst 2.7e-19 (be05608); 100×
                && within(sum(&|p| p[0] * p[2]).abs(), 5e-18) // measured worst 5.4e-20 (be05608); 100×
                && within(sum(&|p| p[0] * p[1]).abs(), 5e-18) // measured worst 0 (be05608); exact; a few ulps
        );
    }
}
