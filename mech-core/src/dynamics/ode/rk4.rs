//! The fixed-step method: the classical fourth-order Runge–Kutta [`Rk4`], and the step
//! clipping that lands a run on its end time (shared with the adaptive methods).

use super::dense::{Hermite, StepDense};
use super::method::{eval, lincomb, Method, Stats};
use crate::MechError;

/// The classical fourth-order Runge–Kutta method with a fixed step `h` (s); the last step
/// is shortened to land on the end time. Local error O(h⁵), global O(h⁴); 4 evaluations
/// a step (the end derivative is reused as the next step's first stage). Dense output: the
/// cubic Hermite interpolant, O(h⁴) like the method.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Rk4 {
    /// Step size, s (> 0).
    pub h: f64,
}

/// The step that lands on `t_end` when the remainder is within a hair of `h`.
pub(super) fn clip_step(t: f64, h_abs: f64, t_end: f64) -> (f64, f64) {
    let dir = if t_end >= t { 1.0 } else { -1.0 };
    let rem = (t_end - t).abs();
    if h_abs >= rem * (1.0 - 1e-12) {
        (t_end - t, t_end)
    } else {
        (dir * h_abs, t + dir * h_abs)
    }
}

impl<const N: usize> Method<N> for Rk4 {
    type Dense = StepDense<N, Hermite<N>>;
    fn start<F>(
        &mut self,
        _: &mut F,
        _: f64,
        _: &[f64; N],
        _: &[f64; N],
        _: f64,
        _: &mut Stats,
    ) -> Result<(), MechError>
    where
        F: FnMut(f64, &[f64; N]) -> Result<[f64; N], MechError>,
    {
        if !(self.h > 0.0 && self.h.is_finite()) {
            return Err(MechError::InvalidInput(format!(
                "RK4 step must be positive and finite, got {}",
                self.h
            )));
        }
        Ok(())
    }
    fn step<F>(
        &mut self,
        f: &mut F,
        t: f64,
        y: &[f64; N],
        dy: &[f64; N],
        t_end: f64,
        _: bool,
        stats: &mut Stats,
    ) -> Result<Self::Dense, MechError>
    where
        F: FnMut(f64, &[f64; N]) -> Result<[f64; N], MechError>,
    {
        let (h, t1) = clip_step(t, self.h, t_end);
        let k1 = *dy;
        let k2 = eval(f, t + 0.5 * h, &lincomb(y, 0.5 * h, &[1.0], &[k1]), stats)?;
        let k3 = eval(f, t + 0.5 * h, &lincomb(y, 0.5 * h, &[1.0], &[k2]), stats)?;
        let k4 = eval(f, t1, &lincomb(y, h, &[1.0], &[k3]), stats)?;
        let y1 = lincomb(y, h / 6.0, &[1.0, 2.0, 2.0, 1.0], &[k1, k2, k3, k4]);
        let f1 = eval(f, t1, &y1, stats)?;
        Ok(StepDense {
            t0: t,
            h,
            y0: *y,
            y1,
            f1,
            poly: Hermite { f0: k1 },
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::dynamics::ode::integrate;
    use crate::dynamics::ode::test_rhs::exp_rhs;
    use crate::kernel::measure::within;

    #[test]
    fn rk4_is_fourth_order_on_exp() {
        let e = |h: f64| {
            (integrate(&mut Rk4 { h }, exp_rhs, 0.0, [1.0], 1.0)
                .unwrap()
                .y[0]
                - 1f64.exp())
            .abs()
        };
        let (e1, e2) = (e(0.02), e(0.01));
        // measured worst 2.3e-10 (be05608); RK4's step error at h = 0.01
        assert!(within(e2, 1e-9), "{e2}");
        let order = (e1 / e2).log2();
        assert!((order - 4.0).abs() < 0.1, "observed order {order}");
        let r = integrate(&mut Rk4 { h: 0.01 }, exp_rhs, 0.0, [1.0], 1.0).unwrap();
        assert_eq!(r.stats.steps, 100);
        assert_eq!(r.stats.rhs_evals, 1 + 4 * 100);
    }
}
