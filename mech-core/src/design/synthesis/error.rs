//! The error of a four-bar against path targets (SPEC §3f): with free timing,
//! E = Σᵢ min_θ |P(θ) − Tᵢ|², the squared distance from each target to the nearest point
//! of the coupler curve over a full turn of the crank (on the drawing's branch, where it
//! assembles); with prescribed timing, E = Σᵢ |P(θᵢ) − Tᵢ|², θᵢ the crank's angle O2 → A
//! measured counter-clockwise from the frame line O2 → O4.
//!
//! The nearest point: the curve sampled at [`SAMPLES`] crank angles, then, around the
//! nearest sample, a golden-section search over the two neighbouring intervals to the
//! round-off of θ (the distance is smooth and unimodal there for any curve the samples
//! resolve).

use super::four_bar::FourBar;

/// The crank angles the curve is sampled at before the local search.
pub const SAMPLES: usize = 720;

fn dist2(fb: &FourBar, theta: f64, t: [f64; 2]) -> f64 {
    fb.pose(theta).map_or(f64::INFINITY, |p| {
        (p.p[0] - t[0]).powi(2) + (p.p[1] - t[1]).powi(2)
    })
}

/// The frame line's direction O2 → O4 (rad).
pub fn frame_angle(fb: &FourBar) -> f64 {
    (fb.o4[1] - fb.o2[1]).atan2(fb.o4[0] - fb.o2[0])
}

/// min over θ of |P(θ) − t|² and the θ (rad, absolute) where it is; infinite when the
/// linkage assembles nowhere.
pub fn nearest(fb: &FourBar, t: [f64; 2]) -> (f64, f64) {
    nearest_on(|theta| fb.pose(theta).map(|p| p.p), fb.drawn_angle(), t)
}

/// min over a full turn θ ∈ [θ₀, θ₀ + 2π) of |P(θ) − t|² for any curve `point(θ)` (`None`
/// where the linkage does not assemble), and the θ where it is (the module's method:
/// [`SAMPLES`] samples, then a golden-section search beside the nearest).
pub fn nearest_on(point: impl Fn(f64) -> Option<[f64; 2]>, t0: f64, t: [f64; 2]) -> (f64, f64) {
    let dist2 = |theta: f64| {
        point(theta).map_or(f64::INFINITY, |p| {
            (p[0] - t[0]).powi(2) + (p[1] - t[1]).powi(2)
        })
    };
    let h = std::f64::consts::TAU / SAMPLES as f64;
    let (k, best) = (0..SAMPLES)
        .map(|k| (k, dist2(t0 + h * k as f64)))
        .fold((0, f64::INFINITY), |b, x| if x.1 < b.1 { x } else { b });
    if !best.is_finite() {
        return (f64::INFINITY, f64::NAN);
    }
    // Golden-section search on [θ_k − h, θ_k + h].
    let g = 0.5 * (5f64.sqrt() - 1.0);
    let (mut a, mut b) = (t0 + h * (k as f64 - 1.0), t0 + h * (k as f64 + 1.0));
    let (mut c, mut d) = (b - g * (b - a), a + g * (b - a));
    let (mut fc, mut fd) = (dist2(c), dist2(d));
    for _ in 0..80 {
        if (b - a).abs() <= 1e-15 * (1.0 + b.abs()) {
            break;
        }
        if fc < fd {
            (b, d, fd) = (d, c, fc);
            c = b - g * (b - a);
            fc = dist2(c);
        } else {
            (a, c, fc) = (c, d, fd);
            d = a + g * (b - a);
            fd = dist2(d);
        }
    }
    let (theta, f) = if fc < fd { (c, fc) } else { (d, fd) };
    if f <= best {
        (f, theta)
    } else {
        (best, t0 + h * k as f64)
    }
}

/// E with free timing, m².
pub fn free_timing(fb: &FourBar, targets: &[[f64; 2]]) -> f64 {
    targets.iter().map(|&t| nearest(fb, t).0).sum()
}

/// E with prescribed timing: the crank angles `angles` (rad, from the frame line), m².
pub fn prescribed_timing(fb: &FourBar, targets: &[[f64; 2]], angles: &[f64]) -> f64 {
    let f = frame_angle(fb);
    targets
        .iter()
        .zip(angles)
        .map(|(&t, &a)| dist2(fb, f + a, t))
        .sum()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Targets on the coupler curve have no error; a target off it by δ along the curve's
    /// normal has δ² (a point at distance δ from the drawn P, normal to the curve there).
    #[test]
    fn points_of_the_curve_have_no_error_and_an_offset_its_square() {
        let fb = FourBar {
            o2: [0.0, 0.0],
            o4: [0.3, 0.0],
            a: [0.0, 0.1],
            b: [0.25, 0.2],
            p: [0.1, 0.3],
        };
        let on: Vec<[f64; 2]> = [0.3, 1.7, 2.9, 4.4]
            .iter()
            .map(|&t| fb.pose(t).unwrap().p)
            .collect();
        assert!(free_timing(&fb, &on) < 1e-24, "{}", free_timing(&fb, &on));
        let f = frame_angle(&fb);
        let angles: Vec<f64> = [0.3, 1.7, 2.9, 4.4].iter().map(|t| t - f).collect();
        assert!(prescribed_timing(&fb, &on, &angles) < 1e-28);
        // The curve's tangent at θ = 1.0 by central differences, then a normal offset.
        let (p, q) = (
            fb.pose(1.0 - 1e-6).unwrap().p,
            fb.pose(1.0 + 1e-6).unwrap().p,
        );
        let tan = [q[0] - p[0], q[1] - p[1]];
        let n = (tan[0] * tan[0] + tan[1] * tan[1]).sqrt();
        let c = fb.pose(1.0).unwrap().p;
        let delta = 1e-3;
        let off = [c[0] - tan[1] / n * delta, c[1] + tan[0] / n * delta];
        let e = free_timing(&fb, &[off]);
        assert!((e - delta * delta).abs() < 1e-3 * delta * delta, "{e}");
    }
}
