//! A link as a straight beam between its two joints A (s = 0) and B (s = L), pinned at both
//! (no end moment), under the transverse force V_A at A and a transverse distributed load
//! varying linearly from w_A at A to w_B at B (N/m): the inertia load of a uniform moving
//! link, −(m/L) a_t(s), is linear in s because a rigid link's acceleration is (the
//! connecting rod's "whip").
//!
//! Shear and bending moment along it (transverse positive one way, the loads signed alike):
//! V(s) = V_A − w_A s − (w_B − w_A) s²/(2L),
//! M(s) = V_A s − w_A s²/2 − (w_B − w_A) s³/(6L).
//! The largest |M| is at an end or where V(s) = 0 (a root of the quadratic in (0, L)).

/// The bending moment M(s), N·m.
pub fn moment(shear_a: f64, w_a: f64, w_b: f64, length: f64, s: f64) -> f64 {
    shear_a * s - w_a * s * s / 2.0 - (w_b - w_a) * s * s * s / (6.0 * length)
}

/// The shear force V(s), N.
pub fn shear(shear_a: f64, w_a: f64, w_b: f64, length: f64, s: f64) -> f64 {
    shear_a - w_a * s - (w_b - w_a) * s * s / (2.0 * length)
}

/// Where |M| is largest along [0, L] and its value: (s, M(s)).
pub fn largest_moment(shear_a: f64, w_a: f64, w_b: f64, length: f64) -> (f64, f64) {
    let mut at = [0.0, length, f64::NAN, f64::NAN];
    // V(s) = 0: a s² + b s + c with a = −(w_B − w_A)/(2L), b = −w_A, c = V_A.
    let (a, b, c) = (-(w_b - w_a) / (2.0 * length), -w_a, shear_a);
    if a.abs() > 1e-300 {
        let disc = b * b - 4.0 * a * c;
        if disc >= 0.0 {
            let q = -0.5 * (b + b.signum() * disc.sqrt());
            at[2] = q / a;
            at[3] = if q != 0.0 { c / q } else { f64::NAN };
        }
    } else if b != 0.0 {
        at[2] = -c / b;
    }
    at.iter()
        .filter(|s| s.is_finite() && (0.0..=length).contains(*s))
        .map(|&s| (s, moment(shear_a, w_a, w_b, length, s)))
        .fold(
            (0.0, 0.0),
            |best, x| if x.1.abs() > best.1.abs() { x } else { best },
        )
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The textbook connecting rod: a triangular inertia load from 0 at the gudgeon pin
    /// (s = 0) to w at the crank pin, the ends pinned: V_A = wL/6, the largest moment
    /// w L² / (9√3) at s = L/√3.
    #[test]
    fn the_connecting_rod_whip_is_largest_at_l_over_root_3() {
        let (w, l) = (2.0e4, 0.15);
        let (s, m) = largest_moment(w * l / 6.0, 0.0, w, l);
        assert!((s - l / 3f64.sqrt()).abs() < 1e-15, "{s}");
        assert!(
            (m - w * l * l / (9.0 * 3f64.sqrt())).abs() < 1e-12 * m,
            "{m}"
        );
        // Pinned at B too: M(L) = 0.
        assert!(moment(w * l / 6.0, 0.0, w, l, l).abs() < 1e-12);
    }

    /// A uniform load: V_A = wL/2, the largest moment wL²/8 at mid-span; a crank as a
    /// cantilever-free end load: M grows linearly to V_A L.
    #[test]
    fn uniform_and_end_loads() {
        let (w, l) = (1e3, 0.4);
        let (s, m) = largest_moment(w * l / 2.0, w, w, l);
        assert!((s - l / 2.0).abs() < 1e-15 && (m - w * l * l / 8.0).abs() < 1e-12);
        let (s, m) = largest_moment(500.0, 0.0, 0.0, 0.1);
        assert_eq!(s, 0.1);
        assert!((m - 50.0).abs() < 1e-12);
        assert!((shear(500.0, 0.0, 0.0, 0.1, 0.05) - 500.0).abs() < 1e-12);
    }
}
