//! Fatigue under a cycle's fluctuating stress: its mean σ_m = (σ_max + σ_min)/2 and
//! alternating amplitude σ_a = (σ_max − σ_min)/2, against the endurance limit corrected by
//! Marin's factors, S_e = k_a k_b k_c k_d k_e S_e'.
//!
//! The factors used, with their values (the usual machine-design tables):
//! - surface k_a = a S_u^b (S_u in MPa), machined or cold drawn: a = 4.51, b = −0.265;
//! - size k_b = 1.24 d^−0.107 for 2.79 ≤ d ≤ 51 mm, 1.51 d^−0.157 for 51 < d ≤ 254 mm
//!   (d the diameter, or a rectangle's equivalent diameter 0.808 √(W T)), 1 below 2.79 mm;
//!   1 for axial loading;
//! - load k_c = 1 in bending, 0.85 in axial loading, 0.59 in shear (a pin: S_se is then
//!   the endurance in shear, against the ultimate in shear S_su = 0.67 S_u);
//! - temperature k_d = 1 (room temperature);
//! - reliability k_e = 0.814 (99 %).
//!
//! Safety factors: Goodman n = 1 / (σ_a/S_e + σ_m/S_u), Soderberg n = 1 / (σ_a/S_e +
//! σ_m/S_y), with σ_m ≥ 0 (a compressive mean does not shorten the life: σ_m is taken 0
//! then); the smaller of fatigue and first-cycle yield n_y = S_y / (σ_a + |σ_m|) governs.

/// How the member is loaded, for the load factor k_c and the size factor k_b.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Loading {
    /// Bending (and combined): k_c = 1, k_b by size.
    Bending,
    /// Pure axial: k_c = 0.85, k_b = 1.
    Axial,
    /// Shear (a pin): k_c = 0.59, k_b by size.
    Shear,
}

/// Marin's factors for a machined member of ultimate strength `ultimate` (Pa) and size
/// `size` (m) under `loading`: (k_a, k_b, k_c, k_d, k_e).
pub fn marin_factors(ultimate: f64, size: f64, loading: Loading) -> [f64; 5] {
    let ka = (4.51 * (ultimate / 1e6).powf(-0.265)).min(1.0);
    let d = size * 1e3;
    let kb = match loading {
        Loading::Axial => 1.0,
        _ if d < 2.79 => 1.0,
        _ if d <= 51.0 => 1.24 * d.powf(-0.107),
        _ => 1.51 * d.powf(-0.157),
    };
    let kc = match loading {
        Loading::Bending => 1.0,
        Loading::Axial => 0.85,
        Loading::Shear => 0.59,
    };
    [ka, kb, kc, 1.0, 0.814]
}

/// The corrected endurance limit S_e = Π k · S_e', Pa.
pub fn endurance_limit(endurance: f64, ultimate: f64, size: f64, loading: Loading) -> f64 {
    marin_factors(ultimate, size, loading)
        .iter()
        .product::<f64>()
        * endurance
}

/// The mean and alternating stresses of a cycle whose stress ranges over [min, max], Pa.
pub fn mean_and_alternating(max: f64, min: f64) -> (f64, f64) {
    (0.5 * (max + min), 0.5 * (max - min))
}

/// Goodman's factor 1 / (σ_a/S_e + σ_m⁺/S_u) (σ_m⁺ = max(σ_m, 0)).
pub fn goodman(mean: f64, alternating: f64, endurance: f64, ultimate: f64) -> f64 {
    1.0 / (alternating.abs() / endurance + mean.max(0.0) / ultimate)
}

/// Soderberg's factor 1 / (σ_a/S_e + σ_m⁺/S_y).
pub fn soderberg(mean: f64, alternating: f64, endurance: f64, yield_strength: f64) -> f64 {
    1.0 / (alternating.abs() / endurance + mean.max(0.0) / yield_strength)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Worked by hand: steel S_u = 565 MPa, S_y = 310, S_e' = 282.5 MPa; a 20 × 8 mm bar
    /// (d_e = 0.808 √160 = 10.22 mm) in bending from −40 to 120 MPa.
    /// k_a = 4.51 · 565^−0.265 = 0.84117, k_b = 1.24 · 10.2205^−0.107 = 0.96696, k_c = k_d = 1,
    /// k_e = 0.814: S_e = 0.66209 · 282.5 = 187.04 MPa. σ_m = 40, σ_a = 80 MPa:
    /// Goodman 1/(80/187.04 + 40/565) = 2.0060, Soderberg 1/(80/187.04 + 40/310) = 1.7961.
    #[test]
    fn a_fatigue_factor_worked_by_hand() {
        let d = 0.808 * (0.02f64 * 0.008).sqrt();
        let k = marin_factors(565e6, d, Loading::Bending);
        assert!((k[0] - 0.84117).abs() < 5e-6, "{k:?}");
        assert!((k[1] - 0.96696).abs() < 5e-6, "{k:?}");
        let se = endurance_limit(282.5e6, 565e6, d, Loading::Bending);
        assert!((se / 1e6 - 187.04).abs() < 0.01, "{se}");
        let (m, a) = mean_and_alternating(120e6, -40e6);
        assert_eq!((m, a), (40e6, 80e6));
        let g = goodman(m, a, se, 565e6);
        let s = soderberg(m, a, se, 310e6);
        assert!((g - 2.0060).abs() < 1e-4, "{g}");
        assert!((s - 1.7961).abs() < 1e-4, "{s}");
        // A compressive mean counts as zero.
        assert_eq!(goodman(-50e6, a, se, 565e6), se / a);
    }
}
