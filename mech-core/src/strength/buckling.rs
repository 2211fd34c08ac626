//! Buckling of a compressed member of length L, pinned at both ends (K = 1: a link between
//! two revolute joints), radius of gyration r, Young's modulus E, yield strength S_y.
//!
//! The slenderness λ = K L / r against the transition (K L / r)_t = √(2 π² E / S_y):
//! above it Euler's critical load P_cr = π² E A / λ² (σ_cr = π² E / λ²), below it
//! Johnson's parabola σ_cr = S_y − (S_y λ / (2π))² / E, P_cr = σ_cr A. The two meet at the
//! transition, where σ_cr = S_y / 2.

/// The critical stress σ_cr (Pa) of a member of slenderness λ = K L / r.
pub fn critical_stress(slenderness: f64, youngs: f64, yield_strength: f64) -> f64 {
    let pi = std::f64::consts::PI;
    let transition = (2.0 * pi * pi * youngs / yield_strength).sqrt();
    if slenderness >= transition {
        pi * pi * youngs / (slenderness * slenderness)
    } else {
        let k = yield_strength * slenderness / (2.0 * pi);
        yield_strength - k * k / youngs
    }
}

/// Euler's critical load π² E I / (K L)², N.
pub fn euler_load(youngs: f64, inertia: f64, effective_length: f64) -> f64 {
    std::f64::consts::PI.powi(2) * youngs * inertia / (effective_length * effective_length)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A 12 mm steel rod 0.5 m long: λ = 0.5 / 0.003 = 166.7, above the transition
    /// √(2π² 205e9/310e6) = 114.3: Euler, P_cr = π² E π D⁴/64 / L² = 8237.7 N; σ_cr A equals it.
    /// Short (L = 0.1 m, λ = 33.3): Johnson, below S_y; the two branches meet at S_y/2.
    #[test]
    fn euler_and_johnson_by_hand() {
        let (e, sy, d): (f64, f64, f64) = (205e9, 310e6, 0.012);
        let pi = std::f64::consts::PI;
        let (i, a, r) = (pi * d.powi(4) / 64.0, pi * d * d / 4.0, d / 4.0);
        let p = euler_load(e, i, 0.5);
        assert!((p - 8237.75).abs() < 0.01, "{p}");
        let s = critical_stress(0.5 / r, e, sy);
        assert!((s * a - p).abs() < 1e-9 * p);
        let short = critical_stress(0.1 / r, e, sy);
        let by_hand = sy - (sy * (0.1 / r) / (2.0 * pi)).powi(2) / e;
        assert!((short - by_hand).abs() < 1e-6 && short < sy && short > sy / 2.0);
        let t = (2.0 * pi * pi * e / sy).sqrt();
        assert!((critical_stress(t, e, sy) - sy / 2.0).abs() < 1e-6 * sy);
        assert!((critical_stress(t * (1.0 - 1e-12), e, sy) - sy / 2.0).abs() < 1e-3 * sy);
    }
}
