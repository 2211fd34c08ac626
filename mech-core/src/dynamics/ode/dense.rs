//! The dense output of one step, shared by every method: [`StepDense`], the step's ends
//! and the method's [`Interpolant`] in θ = (t − t0)/h, and the cubic [`Hermite`]
//! interpolant of [`Rk4`](super::Rk4).

use super::method::Dense;

/// The continuous solution over one step [t0, t0 + h]: the step's ends and the method's
/// interpolating polynomial `poly` in θ = (t − t0)/h.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct StepDense<const N: usize, P> {
    pub(super) t0: f64,
    pub(super) h: f64,
    pub(super) y0: [f64; N],
    pub(super) y1: [f64; N],
    pub(super) f1: [f64; N],
    pub(super) poly: P,
}

/// The interpolating polynomial of a method's dense output.
pub trait Interpolant<const N: usize>: Sized {
    /// y(t0 + θh) on the step `d`.
    fn at(d: &StepDense<N, Self>, theta: f64) -> [f64; N];
}

impl<const N: usize, P: Interpolant<N>> Dense<N> for StepDense<N, P> {
    fn t_start(&self) -> f64 {
        self.t0
    }
    fn t_end(&self) -> f64 {
        self.t0 + self.h
    }
    fn y_end(&self) -> [f64; N] {
        self.y1
    }
    fn dy_end(&self) -> [f64; N] {
        self.f1
    }
    fn eval(&self, t: f64) -> [f64; N] {
        P::at(self, (t - self.t0) / self.h)
    }
}

/// The cubic Hermite interpolant of (y, f) at the step's ends, O(h⁴):
/// y(θ) = (1−θ)y0 + θy1 + θ(θ−1)[(1−2θ)(y1−y0) + (θ−1)h f0 + θ h f1]. `f0` = f(t0, y0).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Hermite<const N: usize> {
    pub(super) f0: [f64; N],
}

impl<const N: usize> Interpolant<N> for Hermite<N> {
    fn at(d: &StepDense<N, Self>, s: f64) -> [f64; N] {
        let mut out = [0.0; N];
        for i in 0..N {
            let dy = d.y1[i] - d.y0[i];
            out[i] = (1.0 - s) * d.y0[i]
                + s * d.y1[i]
                + s * (s - 1.0)
                    * ((1.0 - 2.0 * s) * dy + (s - 1.0) * d.h * d.poly.f0[i] + s * d.h * d.f1[i]);
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::dynamics::ode::test_rhs::oscillator;
    use crate::dynamics::ode::{sample, Dop853, DormandPrince, Method, Rk4, Stats};
    use crate::kernel::measure::{within, within_at};

    #[test]
    fn dense_output_matches_the_solution() {
        let times: Vec<f64> = (0..=200).map(|i| i as f64 * 0.05).collect();
        let mut out = vec![[0.0; 2]; times.len()];
        // Measured worst 7.9e-10 (RK4), 8.4e-13 (DP5), 5.8e-14 (DOP853) (be05608); 100×.
        for (name, tol) in [("rk4", 1e-8), ("dp5", 5e-11), ("dop853", 5e-12)] {
            match name {
                "rk4" => sample(
                    &mut Rk4 { h: 0.01 },
                    oscillator,
                    0.0,
                    [1.0, 0.0],
                    &times,
                    &mut out,
                ),
                "dp5" => sample(
                    &mut DormandPrince::new(1e-12, 1e-14),
                    oscillator,
                    0.0,
                    [1.0, 0.0],
                    &times,
                    &mut out,
                ),
                _ => sample(
                    &mut Dop853::new(1e-13, 1e-15),
                    oscillator,
                    0.0,
                    [1.0, 0.0],
                    &times,
                    &mut out,
                ),
            }
            .unwrap();
            for (t, y) in times.iter().zip(&out) {
                assert!(
                    within_at(name, (y[0] - t.cos()).abs(), tol),
                    "{name} at {t}: {:e}",
                    y[0] - t.cos()
                );
                assert!(
                    within_at(name, (y[1] + t.sin()).abs(), tol),
                    "{name} at {t}: {:e}",
                    y[1] + t.sin()
                );
            }
        }
        // Interpolants reproduce the step's ends.
        let mut f = oscillator;
        let mut st = Stats::default();
        let mut m = Dop853::new(1e-8, 1e-10);
        let y0 = [1.0, 0.0];
        let dy0 = oscillator(0.0, &y0).unwrap();
        m.start(&mut f, 0.0, &y0, &dy0, 5.0, &mut st).unwrap();
        let d = m.step(&mut f, 0.0, &y0, &dy0, 5.0, true, &mut st).unwrap();
        let (a, b) = (d.eval(d.t_start()), d.eval(d.t_end()));
        for i in 0..2 {
            // measured worst 0 (be05608); exact; a few ulps
            assert!(
                within((a[i] - y0[i]).abs(), 1e-15) && within((b[i] - d.y_end()[i]).abs(), 1e-15)
            );
        }
    }
}
