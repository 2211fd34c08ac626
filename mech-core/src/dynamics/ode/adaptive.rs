//! Adaptive step-size control, shared by [`DormandPrince`](super::DormandPrince) and
//! [`Dop853`](super::Dop853): the [`Tolerance`], the controller (Hairer's starting step,
//! Lund-stabilized step control), the [`Tableau`] an embedded pair implements, and the
//! [`Adaptive`] method that joins them.

use super::dense::{Interpolant, StepDense};
use super::method::{eval, lincomb, Method, Stats};
use super::rk4::clip_step;
use crate::MechError;

/// The default step budget of an adaptive run ([`Tolerance::max_steps`]): ten times
/// Hairer's `nmax`, room for 10⁴ periods of an oscillating machine at rtol 1e-11 (3.6e5
/// steps, `tests/elements.rs`), a few seconds of a stiff one before its error.
pub const DEFAULT_MAX_STEPS: usize = 1_000_000;

/// Tolerances and limits of an adaptive method. A step is accepted when the RMS over the
/// components of eᵢ / (atol + rtol·max(|y0ᵢ|, |y1ᵢ|)) is ≤ 1 (e the error estimate); the next
/// step is h·min(10, max(0.2, 0.9·err^(−1/(p+1) + 0.03)·err_prev^0.04)), p the estimator's
/// order (Lund-stabilized controller, β = 0.04, fewer rejected steps than the plain one).
/// A run that needs more than `max_steps` step attempts (accepted or rejected) stops with
/// an error, as Hairer's codes stop at `nmax`: a stiff system (a spring of 1e16 N/m) or a
/// motion that runs away (millions of turns in the span) would otherwise take minutes or
/// hours of tiny steps.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Tolerance {
    /// Relative tolerance (> 0).
    pub rtol: f64,
    /// Absolute tolerance, in the state's units (≥ 0).
    pub atol: f64,
    /// Largest step, s (infinite: no limit).
    pub h_max: f64,
    /// First step, s; `None` chooses it (Hairer's starting-step algorithm, 1 evaluation).
    pub h_init: Option<f64>,
    /// The most step attempts of one run, accepted and rejected (> 0;
    /// [`DEFAULT_MAX_STEPS`]).
    pub max_steps: usize,
}

impl Tolerance {
    /// rtol and atol, no step limit, automatic first step, [`DEFAULT_MAX_STEPS`].
    pub fn new(rtol: f64, atol: f64) -> Self {
        Tolerance {
            rtol,
            atol,
            h_max: f64::INFINITY,
            h_init: None,
            max_steps: DEFAULT_MAX_STEPS,
        }
    }
    /// The error scale of one component, atol + rtol·max(|a|, |b|) (the state's unit).
    #[inline]
    pub fn scale(&self, a: f64, b: f64) -> f64 {
        self.atol + self.rtol * a.abs().max(b.abs())
    }
}

/// The controller's state: the next step to try.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Control {
    tol: Tolerance,
    h: f64,
    /// The previous accepted step's error norm (Lund stabilization).
    err_old: f64,
}

impl Control {
    fn check(tol: &Tolerance) -> Result<(), MechError> {
        let ok = tol.rtol > 0.0
            && tol.rtol.is_finite()
            && tol.atol >= 0.0
            && tol.atol.is_finite()
            && tol.h_max > 0.0
            && tol.max_steps > 0
            && !matches!(tol.h_init, Some(h) if !(h > 0.0 && h.is_finite()));
        if ok {
            Ok(())
        } else {
            Err(MechError::InvalidInput(format!(
                "bad tolerance {tol:?}: rtol > 0, atol >= 0, h_max > 0, h_init > 0, max_steps > 0 required"
            )))
        }
    }

    /// RMS of e / sc(y0, y1).
    #[inline]
    fn norm<const N: usize>(&self, e: &[f64; N], y0: &[f64; N], y1: &[f64; N]) -> f64 {
        let mut s = 0.0;
        for i in 0..N {
            let r = e[i] / self.tol.scale(y0[i], y1[i]);
            s += r * r;
        }
        (s / N.max(1) as f64).sqrt()
    }

    /// Hairer's starting step (Solving ODEs I, II.4), for a method of error order `p`.
    fn start<const N: usize, F>(
        tol: Tolerance,
        p: u32,
        f: &mut F,
        t0: f64,
        y0: &[f64; N],
        f0: &[f64; N],
        t_end: f64,
        stats: &mut Stats,
    ) -> Result<Control, MechError>
    where
        F: FnMut(f64, &[f64; N]) -> Result<[f64; N], MechError>,
    {
        Self::check(&tol)?;
        let span = (t_end - t0).abs();
        let h_max = tol.h_max.min(span);
        let mut c = Control {
            tol,
            h: 0.0,
            err_old: 1e-4,
        };
        if let Some(h) = tol.h_init {
            c.h = h.min(h_max);
            return Ok(c);
        }
        let d0 = c.norm(y0, y0, y0);
        let d1 = c.norm(f0, y0, y0);
        let h0 = if d0 < 1e-5 || d1 < 1e-5 {
            1e-6
        } else {
            0.01 * d0 / d1
        }
        .min(h_max);
        let dir = if t_end >= t0 { 1.0 } else { -1.0 };
        let y1 = lincomb(y0, dir * h0, &[1.0], &[*f0]);
        let f1 = eval(f, t0 + dir * h0, &y1, stats)?;
        let mut diff = [0.0; N];
        for i in 0..N {
            diff[i] = f1[i] - f0[i];
        }
        let d2 = c.norm(&diff, y0, y0) / h0;
        let dm = d1.max(d2);
        let h1 = if dm <= 1e-15 {
            (h0 * 1e-3).max(1e-6)
        } else {
            (0.01 / dm).powf(1.0 / (p as f64 + 1.0))
        };
        c.h = (100.0 * h0).min(h1).min(h_max);
        Ok(c)
    }

    /// One accepted step: try `attempt(h) -> (y1, error estimate, extra)` until the error
    /// norm is ≤ 1, shrinking h; returns (h, extra) and sets the next step,
    /// h·0.9·err^(−1/(p+1) + 0.75β)·err_prev^β (Lund stabilization with β; β = 0 is the
    /// plain controller).
    fn advance<const N: usize, A, X>(
        &mut self,
        p: u32,
        beta: f64,
        t: f64,
        y: &[f64; N],
        t_end: f64,
        stats: &mut Stats,
        mut attempt: A,
    ) -> Result<(f64, X), MechError>
    where
        A: FnMut(f64, &mut Stats) -> Result<([f64; N], [f64; N], X), MechError>,
    {
        const SAFETY: f64 = 0.9;
        const FAC_MIN: f64 = 0.2;
        const FAC_MAX: f64 = 10.0;
        let expo = -1.0 / (p as f64 + 1.0);
        let mut rejected = false;
        loop {
            if stats.steps + stats.rejected >= self.tol.max_steps {
                return Err(too_many_steps(self.tol.max_steps, t, t_end, self.h));
            }
            let h_abs = self.h.min(self.tol.h_max);
            let min_step = 16.0 * f64::EPSILON * t.abs().max(f64::MIN_POSITIVE.sqrt());
            if !(h_abs >= min_step) {
                return Err(MechError::StepUnderflow { t });
            }
            let (h, _) = clip_step(t, h_abs, t_end);
            let (y1, e, extra) = attempt(h, stats)?;
            let err = self.norm(&e, y, &y1);
            if err <= 1.0 {
                let e = err.max(1e-10);
                let mut fac =
                    (SAFETY * e.powf(expo + 0.75 * beta) * self.err_old.powf(beta)).min(FAC_MAX);
                if rejected {
                    fac = fac.min(1.0);
                }
                self.err_old = e.max(1e-4);
                self.h = h.abs() * fac;
                return Ok((h, extra));
            }
            stats.rejected += 1;
            rejected = true;
            let fac = if err.is_finite() {
                (SAFETY * err.powf(expo)).max(FAC_MIN)
            } else {
                FAC_MIN
            };
            self.h = h.abs() * fac;
        }
    }
}

/// The error of a run past its step budget, at time `t` with the step `h` then.
#[cold]
fn too_many_steps(max: usize, t: f64, t_end: f64, h: f64) -> MechError {
    MechError::InvalidInput(format!(
        "the integration took {max} steps (Tolerance::max_steps; `mech simulate --max-steps`) and reached t = {t:e} s of {t_end:e} s, with steps of {h:e} s: the system is stiff (a very stiff spring) or its motion runs away (many turns in the span) for an explicit method at this tolerance; integrate a shorter span, loosen rtol, or raise max_steps"
    ))
}

/// An embedded Runge–Kutta pair: one step attempt with its error estimate, and its
/// interpolant. Implemented by [`Dp5`](super::Dp5) and [`Dop8`](super::Dop8); [`Adaptive`]
/// adds the step control.
pub trait Tableau<const N: usize> {
    /// Order p of the error estimate: the step scales as err^(−1/(p+1)).
    const ERROR_ORDER: u32;
    /// The interpolating polynomial of the dense output.
    type Poly: Interpolant<N>;
    /// One step of size h from (t, y, dy = f(t, y)): (y1, error estimate, f(t + h, y1), the
    /// interpolant). `tol` gives the scale of the error norm where the estimate needs it.
    #[allow(clippy::too_many_arguments)]
    fn attempt<F>(
        f: &mut F,
        t: f64,
        y: &[f64; N],
        dy: &[f64; N],
        h: f64,
        tol: &Tolerance,
        stats: &mut Stats,
    ) -> Result<([f64; N], [f64; N], [f64; N], Self::Poly), MechError>
    where
        F: FnMut(f64, &[f64; N]) -> Result<[f64; N], MechError>;
    /// Complete the interpolant of a step attempted without it (see [`Method::densify`]);
    /// a no-op for a pair whose interpolant needs no more stages.
    fn densify<F>(
        _f: &mut F,
        _d: &mut StepDense<N, Self::Poly>,
        _stats: &mut Stats,
    ) -> Result<(), MechError>
    where
        F: FnMut(f64, &[f64; N]) -> Result<[f64; N], MechError>,
    {
        Ok(())
    }
}

/// An adaptive embedded Runge–Kutta method: the pair `T` with the error-controlled step of
/// [`Tolerance`] (Hairer's starting step, Lund-stabilized controller).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Adaptive<T> {
    /// Tolerances and step limits.
    pub tol: Tolerance,
    control: Option<Control>,
    tableau: core::marker::PhantomData<T>,
}

impl<T> Adaptive<T> {
    /// With relative and absolute tolerances (see [`Tolerance`]).
    pub fn new(rtol: f64, atol: f64) -> Self {
        Self::with(Tolerance::new(rtol, atol))
    }
    /// With full tolerance settings.
    pub fn with(tol: Tolerance) -> Self {
        Adaptive {
            tol,
            control: None,
            tableau: core::marker::PhantomData,
        }
    }
}

impl<const N: usize, T: Tableau<N>> Method<N> for Adaptive<T> {
    type Dense = StepDense<N, T::Poly>;
    fn start<F>(
        &mut self,
        f: &mut F,
        t0: f64,
        y0: &[f64; N],
        dy0: &[f64; N],
        t_end: f64,
        stats: &mut Stats,
    ) -> Result<(), MechError>
    where
        F: FnMut(f64, &[f64; N]) -> Result<[f64; N], MechError>,
    {
        self.control = Some(Control::start(
            self.tol,
            T::ERROR_ORDER,
            f,
            t0,
            y0,
            dy0,
            t_end,
            stats,
        )?);
        Ok(())
    }
    fn step<F>(
        &mut self,
        f: &mut F,
        t: f64,
        y: &[f64; N],
        dy: &[f64; N],
        t_end: f64,
        dense: bool,
        stats: &mut Stats,
    ) -> Result<Self::Dense, MechError>
    where
        F: FnMut(f64, &[f64; N]) -> Result<[f64; N], MechError>,
    {
        let control = self.control.as_mut().ok_or_else(|| {
            MechError::InvalidInput("an adaptive method stepped before start".into())
        })?;
        let tol = control.tol;
        let (h, (y1, f1, poly)) =
            control.advance(T::ERROR_ORDER, 0.04, t, y, t_end, stats, |h, stats| {
                let (y1, e, f1, poly) = T::attempt(f, t, y, dy, h, &tol, stats)?;
                Ok((y1, e, (y1, f1, poly)))
            })?;
        let mut d = StepDense {
            t0: t,
            h,
            y0: *y,
            y1,
            f1,
            poly,
        };
        if dense {
            T::densify(f, &mut d, stats)?;
        }
        Ok(d)
    }
    fn densify<F>(
        &mut self,
        f: &mut F,
        d: &mut Self::Dense,
        stats: &mut Stats,
    ) -> Result<(), MechError>
    where
        F: FnMut(f64, &[f64; N]) -> Result<[f64; N], MechError>,
    {
        T::densify(f, d, stats)
    }
}

#[cfg(test)]
mod tests {
    use crate::dynamics::ode::test_rhs::{exp_rhs, oscillator};
    use crate::dynamics::ode::{integrate, Dop853, DormandPrince, Outcome};
    use crate::kernel::measure::{within, within_at};

    /// A stiff problem, y' = −1e9 (y − cos t), needs steps of about 3e-9 s from an
    /// explicit method: a second of it is 3e8 steps (minutes; `mech-fuzz` found a
    /// simulation of a machine with a spring of 1e16 N/m running past 20 s). The run
    /// stops at its step budget (the default, a million, then 50) with an error that says
    /// so.
    #[test]
    fn a_stiff_run_stops_at_its_step_budget() {
        use crate::dynamics::ode::{Adaptive, Dp5, Tolerance, DEFAULT_MAX_STEPS};
        use crate::MechError;
        let stiff = |t: f64, y: &[f64; 1]| Ok([-1e9 * (y[0] - t.cos())]);
        match integrate(&mut Dop853::new(1e-8, 1e-10), stiff, 0.0, [1.0], 1.0) {
            Err(MechError::InvalidInput(m)) => assert!(
                m.contains(&format!("took {DEFAULT_MAX_STEPS} steps")),
                "{m}"
            ),
            other => panic!("expected the step budget, got {other:?}"),
        }
        let mut small = Adaptive::<Dp5>::with(Tolerance {
            max_steps: 50,
            ..Tolerance::new(1e-8, 1e-10)
        });
        let e = integrate(&mut small, stiff, 0.0, [1.0], 1.0).unwrap_err();
        assert!(e.to_string().contains("took 50 steps"), "{e}");
        // Within its budget the same run is unaffected: a short span of the stiff one.
        let o = integrate(&mut Dop853::new(1e-8, 1e-10), stiff, 0.0, [1.0], 1e-6).unwrap();
        assert!(o.stats.steps + o.stats.rejected < DEFAULT_MAX_STEPS);
        assert!((o.y[0] - 1.0).abs() < 1e-8, "{:?}", o.y);
    }

    #[test]
    fn adaptive_methods_on_the_harmonic_oscillator() {
        let t_end = 20.0 * std::f64::consts::PI + 0.3;
        for (name, r, tol) in [
            (
                "dp5",
                integrate(
                    &mut DormandPrince::new(1e-11, 1e-13),
                    oscillator,
                    0.0,
                    [1.0, 0.0],
                    t_end,
                )
                .unwrap(),
                2e-9, // measured worst 5.5e-11 (be05608); 100×
            ),
            (
                "dop853",
                integrate(
                    &mut Dop853::new(1e-12, 1e-14),
                    oscillator,
                    0.0,
                    [1.0, 0.0],
                    t_end,
                )
                .unwrap(),
                1e-10, // measured worst 1.4e-12 (be05608); 100×
            ),
        ] {
            assert!(
                within_at(name, (r.y[0] - t_end.cos()).abs(), tol),
                "{name}: {:e}",
                r.y[0] - t_end.cos()
            );
            assert!(
                within_at(name, (r.y[1] + t_end.sin()).abs(), tol),
                "{name}: {:e}",
                r.y[1] + t_end.sin()
            );
            assert_eq!(r.t, t_end);
        }
        // Backwards in time.
        let r = integrate(
            &mut Dop853::new(1e-12, 1e-14),
            oscillator,
            1.0,
            [1f64.cos(), -1f64.sin()],
            -2.0,
        )
        .unwrap();
        // measured worst 4.7e-14, 2.0e-14 (be05608); 100×
        assert!(
            within((r.y[0] - 2f64.cos()).abs(), 2e-12)
                && within((r.y[1] - 2f64.sin()).abs(), 1e-12)
        );
    }

    #[test]
    fn tolerance_proportionality_and_order() {
        // Tighter tolerance => smaller error, roughly in proportion.
        let err = |m: &mut dyn FnMut() -> Outcome<1>| (m().y[0] - 3f64.exp()).abs() / 3f64.exp();
        let e_hi = err(&mut || {
            integrate(&mut DormandPrince::new(1e-6, 0.0), exp_rhs, 0.0, [1.0], 3.0).unwrap()
        });
        let e_lo = err(&mut || {
            integrate(
                &mut DormandPrince::new(1e-10, 0.0),
                exp_rhs,
                0.0,
                [1.0],
                3.0,
            )
            .unwrap()
        });
        assert!(
            within(e_lo, 2e-9) && within(e_hi, 2e-5) && e_lo < e_hi / 100.0, // measured worst 4.4e-11, 3.1e-7 (be05608); 100×
            "{e_hi:e} {e_lo:e}"
        );
        let e8 =
            err(&mut || integrate(&mut Dop853::new(1e-13, 0.0), exp_rhs, 0.0, [1.0], 3.0).unwrap());
        // measured worst 5.5e-15 (be05608); 100×
        assert!(within(e8, 5e-13), "{e8:e}");
    }
}
