//! What every method and every run share: the [`Method`] and [`Dense`] traits, a run's
//! stop [`Event`], its [`Outcome`] and work [`Stats`], and the two stage kernels of the
//! tableaux (a row's linear combination, a counted evaluation of f).

use crate::MechError;

/// Work counters of one integration.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Stats {
    /// Evaluations of the right-hand side f(t, y).
    pub rhs_evals: usize,
    /// Accepted steps.
    pub steps: usize,
    /// Rejected step attempts (adaptive methods).
    pub rejected: usize,
}

/// Where an integration ended.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Outcome<const N: usize> {
    /// Final time, s: the requested end time, or the located event time.
    pub t: f64,
    /// State at `t`.
    pub y: [f64; N],
    /// True when the run stopped at the event rather than at the end time.
    pub event: bool,
    /// Work done.
    pub stats: Stats,
}

/// The continuous solution over one accepted step [t_start, t_end].
pub trait Dense<const N: usize> {
    /// Start of the step, s.
    fn t_start(&self) -> f64;
    /// End of the step, s.
    fn t_end(&self) -> f64;
    /// The state at the end of the step.
    fn y_end(&self) -> [f64; N];
    /// f(t_end, y_end), the derivative at the end of the step (reused by the next step).
    fn dy_end(&self) -> [f64; N];
    /// The interpolated state y(t) for t in [t_start, t_end] (extrapolates outside).
    fn eval(&self, t: f64) -> [f64; N];
}

/// A one-step method: advances (t, y) by one accepted step.
pub trait Method<const N: usize> {
    /// The dense output of one step.
    type Dense: Dense<N>;
    /// Prepare a run from (t0, y0, f(t0, y0)) towards `t_end`: check the settings, forget
    /// the step history, choose the first step of an adaptive method.
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
        F: FnMut(f64, &[f64; N]) -> Result<[f64; N], MechError>;
    /// One accepted step from (t, y, dy = f(t, y)), never past `t_end`. With `dense` the
    /// method prepares its full-order interpolant (DOP853 spends 3 more evaluations).
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
        F: FnMut(f64, &[f64; N]) -> Result<[f64; N], MechError>;
    /// Complete the full-order interpolant of a step taken with `dense = false` (DOP853:
    /// 3 more evaluations); the other methods' dense output is always complete.
    fn densify<F>(
        &mut self,
        _f: &mut F,
        _d: &mut Self::Dense,
        _stats: &mut Stats,
    ) -> Result<(), MechError>
    where
        F: FnMut(f64, &[f64; N]) -> Result<[f64; N], MechError>,
    {
        Ok(())
    }
}

/// A stop event: the run ends at the first zero crossing of g(t, y) after the start.
pub struct Event<'a, const N: usize> {
    /// The event function g(t, y) (any unit).
    pub g: &'a mut dyn FnMut(f64, &[f64; N]) -> f64,
    /// +1: only crossings from g < 0 to g > 0; −1: only from g > 0 to g < 0; 0: either.
    pub direction: i8,
    /// Absolute tolerance on the located event time, s.
    pub t_tol: f64,
}

impl<'a, const N: usize> Event<'a, N> {
    /// A crossing in either direction, located to 1e-13 s.
    pub fn new(g: &'a mut dyn FnMut(f64, &[f64; N]) -> f64) -> Self {
        Event {
            g,
            direction: 0,
            t_tol: 1e-13,
        }
    }
}

/// y + h Σ_j a_j k_j, skipping zero coefficients (a stage of an explicit tableau row).
#[inline]
pub(super) fn lincomb<const N: usize, const S: usize>(
    y: &[f64; N],
    h: f64,
    a: &[f64; S],
    k: &[[f64; N]; S],
) -> [f64; N] {
    let mut out = *y;
    for (aj, kj) in a.iter().zip(k) {
        if *aj != 0.0 {
            let c = h * aj;
            for (o, kji) in out.iter_mut().zip(kj) {
                *o += c * kji;
            }
        }
    }
    out
}

#[inline]
pub(super) fn eval<const N: usize, F>(
    f: &mut F,
    t: f64,
    y: &[f64; N],
    stats: &mut Stats,
) -> Result<[f64; N], MechError>
where
    F: FnMut(f64, &[f64; N]) -> Result<[f64; N], MechError>,
{
    stats.rhs_evals += 1;
    f(t, y)
}
