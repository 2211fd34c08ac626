//! A pin's stresses under the reaction R it carries (N, the magnitude).
//!
//! Shear: τ = R / (n π d²/4), n = 1 in single shear, 2 in double shear (a fork).
//! Bearing: p = R / (d t), t the length the pin bears on in the link (its thickness).

use crate::model::Pin;

/// The average shear stress in the pin, Pa.
pub fn shear_stress(pin: &Pin, force: f64) -> f64 {
    let sections = if pin.double { 2.0 } else { 1.0 };
    force.abs() / (sections * std::f64::consts::PI * pin.diameter * pin.diameter / 4.0)
}

/// The bearing pressure of the pin on a link of thickness `t` (m), Pa.
pub fn bearing_pressure(pin: &Pin, force: f64, t: f64) -> f64 {
    force.abs() / (pin.diameter * t)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// 10 kN on a 12 mm pin: single shear 10⁴/(π 36e-6) = 88.42 MPa, double half of it;
    /// bearing on 8 mm: 10⁴ / (12e-3 · 8e-3) = 104.17 MPa.
    #[test]
    fn single_and_double_shear_and_bearing_by_hand() {
        let single = Pin {
            diameter: 0.012,
            double: false,
        };
        let double = Pin {
            diameter: 0.012,
            double: true,
        };
        let t = shear_stress(&single, -1e4);
        assert!((t - 88.419412828e6).abs() < 1.0, "{t}");
        assert!((shear_stress(&double, 1e4) - t / 2.0).abs() < 1e-6);
        let p = bearing_pressure(&single, 1e4, 0.008);
        assert!((p - 104.1666666667e6).abs() < 1.0, "{p}");
    }
}
