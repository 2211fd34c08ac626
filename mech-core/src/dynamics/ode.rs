//! Explicit Runge–Kutta integrators for y' = f(t, y), y ∈ ℝᴺ, written once and shared by
//! every dynamics problem of the crate (`docs/theory.md` §6: the direct dynamic problem).
//!
//! - [`Rk4`]: the classical fixed-step fourth-order method, cubic Hermite dense output.
//! - [`DormandPrince`]: Dormand–Prince 5(4) with error control (local extrapolation,
//!   FSAL, 6 new evaluations a step) and Shampine's quartic dense output.
//! - [`Dop853`]: Hairer's DOP853, order 8 with the 5(3) error estimator (12 new evaluations
//!   a step) and its seventh-order dense output (3 more evaluations, only when asked).
//!
//! The state is a fixed-size array `[f64; N]` and the right-hand side a closure
//! `FnMut(t, &y) -> Result<[f64; N], MechError>`: stepping allocates nothing. The loop that
//! drives a method to the end time, stops at an event located on the dense output, and
//! feeds an observer is [`solve`], written once for all methods.
//!
//! No crate of the ecosystem fits: the maintained ones either collect every step into a
//! `Vec`, or lack event location on the dense output, or take dynamically sized states.

// The published coefficients keep all their digits; `!(x > 0.0)` also rejects NaN; the
// kernels index several arrays in lockstep and pass the integrator's whole state.
#![allow(
    clippy::excessive_precision,
    clippy::neg_cmp_op_on_partial_ord,
    clippy::needless_range_loop,
    clippy::too_many_arguments,
    clippy::type_complexity
)]

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
fn lincomb<const N: usize, const S: usize>(
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
fn finite<const N: usize>(y: &[f64; N]) -> bool {
    crate::error::all_finite(y)
}

fn check_run<const N: usize>(t0: f64, y0: &[f64; N], t_end: f64) -> Result<(), MechError> {
    crate::error::check_finite("t0, t_end", &[t0, t_end])?;
    crate::error::check_finite("y0", y0)
}

#[inline]
fn eval<const N: usize, F>(
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

/// Integrate y' = f(t, y) from (t0, y0) to `t_end` (either direction) with `method`.
///
/// With `event`, the run stops at the first zero crossing of g, located on the dense output
/// by the Illinois variant of regula falsi to `t_tol`. `observer` sees every accepted step's
/// dense output in order; the last one contains the returned time (with an event it may
/// reach past it). Errors: the right-hand
/// side's own, [`MechError::InvalidInput`] for non-finite input or a state that becomes
/// non-finite, [`MechError::StepUnderflow`] from an adaptive method.
pub fn solve<const N: usize, M, F>(
    method: &mut M,
    mut f: F,
    t0: f64,
    y0: [f64; N],
    t_end: f64,
    mut event: Option<&mut Event<'_, N>>,
    mut observer: Option<&mut dyn FnMut(&M::Dense)>,
) -> Result<Outcome<N>, MechError>
where
    M: Method<N>,
    F: FnMut(f64, &[f64; N]) -> Result<[f64; N], MechError>,
{
    check_run(t0, &y0, t_end)?;
    let mut stats = Stats::default();
    let (mut t, mut y) = (t0, y0);
    if t0 == t_end {
        return Ok(Outcome {
            t,
            y,
            event: false,
            stats,
        });
    }
    let mut dy = eval(&mut f, t, &y, &mut stats)?;
    method.start(&mut f, t, &y, &dy, t_end, &mut stats)?;
    // Observers may interpolate anywhere; an event needs the interpolant of its step only.
    let dense = observer.is_some();
    let mut g_prev = event.as_mut().map_or(0.0, |e| (e.g)(t, &y));
    while t != t_end {
        let mut d = method.step(&mut f, t, &y, &dy, t_end, dense, &mut stats)?;
        stats.steps += 1;
        let y1 = d.y_end();
        if !finite(&y1) {
            return Err(MechError::InvalidInput(format!(
                "the state became non-finite at t = {:.6e} s",
                d.t_end()
            )));
        }
        if let Some(e) = event.as_mut() {
            let g1 = (e.g)(d.t_end(), &y1);
            let crossed = (g_prev < 0.0 && g1 >= 0.0 && e.direction >= 0)
                || (g_prev > 0.0 && g1 <= 0.0 && e.direction <= 0);
            if crossed {
                if !dense {
                    method.densify(&mut f, &mut d, &mut stats)?;
                }
                let te = locate(&mut *e.g, &d, g_prev, g1, e.t_tol);
                let ye = d.eval(te);
                if let Some(o) = observer.as_mut() {
                    o(&d);
                }
                return Ok(Outcome {
                    t: te,
                    y: ye,
                    event: true,
                    stats,
                });
            }
            if g1 != 0.0 || g_prev == 0.0 {
                g_prev = g1;
            }
        }
        if let Some(o) = observer.as_mut() {
            o(&d);
        }
        t = d.t_end();
        y = y1;
        dy = d.dy_end();
    }
    Ok(Outcome {
        t,
        y,
        event: false,
        stats,
    })
}

/// The zero of g on the step's dense output between its ends (g(a) = ga, g(b) = gb of
/// opposite signs or gb = 0): Illinois regula falsi, bracket kept, to |Δt| ≤ tol.
fn locate<const N: usize, D: Dense<N>>(
    g: &mut dyn FnMut(f64, &[f64; N]) -> f64,
    d: &D,
    ga: f64,
    gb: f64,
    tol: f64,
) -> f64 {
    let (mut a, mut b, mut fa, mut fb) = (d.t_start(), d.t_end(), ga, gb);
    if fb == 0.0 {
        return b;
    }
    let tol = tol.max(4.0 * f64::EPSILON * a.abs().max(b.abs()));
    let mut side = 0i8;
    for _ in 0..200 {
        if (b - a).abs() <= tol {
            break;
        }
        let mut c = (a * fb - b * fa) / (fb - fa);
        if !(c.is_finite()) || (c - a) * (c - b) >= 0.0 {
            c = 0.5 * (a + b);
        }
        let fc = g(c, &d.eval(c));
        if fc == 0.0 {
            return c;
        }
        if (fc < 0.0) == (fa < 0.0) {
            a = c;
            fa = fc;
            if side == -1 {
                fb *= 0.5;
            }
            side = -1;
        } else {
            b = c;
            fb = fc;
            if side == 1 {
                fa *= 0.5;
            }
            side = 1;
        }
    }
    // The crossing is in (a, b]: report the end on the far side of the zero.
    b
}

/// Integrate from (t0, y0) to `t_end`, no event, no observer: the final state and the work.
pub fn integrate<const N: usize, M, F>(
    method: &mut M,
    f: F,
    t0: f64,
    y0: [f64; N],
    t_end: f64,
) -> Result<Outcome<N>, MechError>
where
    M: Method<N>,
    F: FnMut(f64, &[f64; N]) -> Result<[f64; N], MechError>,
{
    solve(method, f, t0, y0, t_end, None, None)
}

/// Integrate from (t0, y0) through the increasing (or, backwards, decreasing) `times` and
/// write the dense-output state at each into `out` (same length): one run to the last time.
pub fn sample<const N: usize, M, F>(
    method: &mut M,
    f: F,
    t0: f64,
    y0: [f64; N],
    times: &[f64],
    out: &mut [[f64; N]],
) -> Result<Stats, MechError>
where
    M: Method<N>,
    F: FnMut(f64, &[f64; N]) -> Result<[f64; N], MechError>,
{
    if times.len() != out.len() {
        return Err(MechError::InvalidInput(format!(
            "{} times for {} outputs",
            times.len(),
            out.len()
        )));
    }
    crate::error::check_finite("times", times)?;
    let Some(&t_last) = times.last() else {
        return Ok(Stats::default());
    };
    let dir = if t_last >= t0 { 1.0 } else { -1.0 };
    if times.windows(2).any(|w| dir * (w[1] - w[0]) < 0.0) || dir * (times[0] - t0) < 0.0 {
        return Err(MechError::InvalidInput(
            "sample times must be ordered in the direction of integration".into(),
        ));
    }
    let mut next = 0;
    while next < times.len() && times[next] == t0 {
        out[next] = y0;
        next += 1;
    }
    let mut obs = |d: &M::Dense| {
        while next < times.len() && dir * (times[next] - d.t_end()) <= 0.0 {
            out[next] = if times[next] == d.t_end() {
                d.y_end()
            } else {
                d.eval(times[next])
            };
            next += 1;
        }
    };
    let r = solve(method, f, t0, y0, t_last, None, Some(&mut obs))?;
    Ok(r.stats)
}

// ---------------------------------------------------------------------------------------
// The dense output of one step, shared by every method

/// The continuous solution over one step [t0, t0 + h]: the step's ends and the method's
/// interpolating polynomial `poly` in θ = (t − t0)/h.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct StepDense<const N: usize, P> {
    t0: f64,
    h: f64,
    y0: [f64; N],
    y1: [f64; N],
    f1: [f64; N],
    poly: P,
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
    f0: [f64; N],
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

// ---------------------------------------------------------------------------------------
// RK4

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
fn clip_step(t: f64, h_abs: f64, t_end: f64) -> (f64, f64) {
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

// ---------------------------------------------------------------------------------------
// Adaptive step-size control, shared by DormandPrince and Dop853

/// Tolerances and limits of an adaptive method. A step is accepted when the RMS over the
/// components of eᵢ / (atol + rtol·max(|y0ᵢ|, |y1ᵢ|)) is ≤ 1 (e the error estimate); the next
/// step is h·min(10, max(0.2, 0.9·err^(−1/(p+1) + 0.03)·err_prev^0.04)), p the estimator's
/// order (Lund-stabilized controller, β = 0.04, fewer rejected steps than the plain one).
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
}

impl Tolerance {
    /// rtol and atol, no step limit, automatic first step.
    pub fn new(rtol: f64, atol: f64) -> Self {
        Tolerance {
            rtol,
            atol,
            h_max: f64::INFINITY,
            h_init: None,
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
            && !matches!(tol.h_init, Some(h) if !(h > 0.0 && h.is_finite()));
        if ok {
            Ok(())
        } else {
            Err(MechError::InvalidInput(format!(
                "bad tolerance {tol:?}: rtol > 0, atol >= 0, h_max > 0, h_init > 0 required"
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

/// An embedded Runge–Kutta pair: one step attempt with its error estimate, and its
/// interpolant. Implemented by [`Dp5`] and [`Dop8`]; [`Adaptive`] adds the step control.
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

// ---------------------------------------------------------------------------------------
// Dormand–Prince 5(4)

/// Dormand–Prince 5(4) (Hairer's DOPRI5): fifth-order solution, fourth-order embedded
/// error estimate, 7 stages with the last one reused (FSAL: 6 new evaluations a step),
/// Shampine's quartic dense output.
pub type DormandPrince = Adaptive<Dp5>;

/// The Dormand–Prince 5(4) pair (see [`DormandPrince`]).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Dp5;

mod dp5 {
    pub const C: [f64; 7] = [0.0, 1.0 / 5.0, 3.0 / 10.0, 4.0 / 5.0, 8.0 / 9.0, 1.0, 1.0];
    pub const A2: [f64; 1] = [1.0 / 5.0];
    pub const A3: [f64; 2] = [3.0 / 40.0, 9.0 / 40.0];
    pub const A4: [f64; 3] = [44.0 / 45.0, -56.0 / 15.0, 32.0 / 9.0];
    pub const A5: [f64; 4] = [
        19372.0 / 6561.0,
        -25360.0 / 2187.0,
        64448.0 / 6561.0,
        -212.0 / 729.0,
    ];
    pub const A6: [f64; 5] = [
        9017.0 / 3168.0,
        -355.0 / 33.0,
        46732.0 / 5247.0,
        49.0 / 176.0,
        -5103.0 / 18656.0,
    ];
    /// The fifth-order weights (also the 7th stage's row: FSAL).
    pub const B: [f64; 6] = [
        35.0 / 384.0,
        0.0,
        500.0 / 1113.0,
        125.0 / 192.0,
        -2187.0 / 6784.0,
        11.0 / 84.0,
    ];
    /// b − b̂ (fifth minus fourth order), over the 7 stages.
    pub const E: [f64; 7] = [
        71.0 / 57600.0,
        0.0,
        -71.0 / 16695.0,
        71.0 / 1920.0,
        -17253.0 / 339200.0,
        22.0 / 525.0,
        -1.0 / 40.0,
    ];
    /// Shampine's dense output: y(t0 + θh) = y0 + h Σ_j k_j Σ_m P[j][m] θ^(m+1).
    pub const P: [[f64; 4]; 7] = [
        [
            1.0,
            -8048581381.0 / 2820520608.0,
            8663915743.0 / 2820520608.0,
            -12715105075.0 / 11282082432.0,
        ],
        [0.0, 0.0, 0.0, 0.0],
        [
            0.0,
            131558114200.0 / 32700410799.0,
            -68118460800.0 / 10900136933.0,
            87487479700.0 / 32700410799.0,
        ],
        [
            0.0,
            -1754552775.0 / 470086768.0,
            14199869525.0 / 1410260304.0,
            -10690763975.0 / 1880347072.0,
        ],
        [
            0.0,
            127303824393.0 / 49829197408.0,
            -318862633887.0 / 49829197408.0,
            701980252875.0 / 199316789632.0,
        ],
        [
            0.0,
            -282668133.0 / 205662961.0,
            2019193451.0 / 616988883.0,
            -1453857185.0 / 822651844.0,
        ],
        [
            0.0,
            40617522.0 / 29380423.0,
            -110615467.0 / 29380423.0,
            69997945.0 / 29380423.0,
        ],
    ];
}

/// Shampine's quartic dense output of [`DormandPrince`]: y0 + h Σ_m Q_m θ^(m+1), Q = Kᵀ P.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Dp5Poly<const N: usize> {
    q: [[f64; N]; 4],
}

impl<const N: usize> Interpolant<N> for Dp5Poly<N> {
    fn at(d: &StepDense<N, Self>, s: f64) -> [f64; N] {
        let q = &d.poly.q;
        let mut out = d.y0;
        for i in 0..N {
            let p = ((q[3][i] * s + q[2][i]) * s + q[1][i]) * s + q[0][i];
            out[i] += d.h * s * p;
        }
        out
    }
}

impl<const N: usize> Tableau<N> for Dp5 {
    const ERROR_ORDER: u32 = 4;
    type Poly = Dp5Poly<N>;
    fn attempt<F>(
        f: &mut F,
        t: f64,
        y: &[f64; N],
        dy: &[f64; N],
        h: f64,
        _: &Tolerance,
        stats: &mut Stats,
    ) -> Result<([f64; N], [f64; N], [f64; N], Dp5Poly<N>), MechError>
    where
        F: FnMut(f64, &[f64; N]) -> Result<[f64; N], MechError>,
    {
        use dp5::*;
        let mut k = [[0.0; N]; 7];
        k[0] = *dy;
        k[1] = eval(f, t + C[1] * h, &lincomb(y, h, &A2, &[k[0]]), stats)?;
        k[2] = eval(f, t + C[2] * h, &lincomb(y, h, &A3, &[k[0], k[1]]), stats)?;
        k[3] = eval(
            f,
            t + C[3] * h,
            &lincomb(y, h, &A4, &[k[0], k[1], k[2]]),
            stats,
        )?;
        k[4] = eval(
            f,
            t + C[4] * h,
            &lincomb(y, h, &A5, &[k[0], k[1], k[2], k[3]]),
            stats,
        )?;
        k[5] = eval(
            f,
            t + C[5] * h,
            &lincomb(y, h, &A6, &[k[0], k[1], k[2], k[3], k[4]]),
            stats,
        )?;
        let y1 = lincomb(y, h, &B, &[k[0], k[1], k[2], k[3], k[4], k[5]]);
        k[6] = eval(f, t + h, &y1, stats)?;
        let e = lincomb(&[0.0; N], h, &E, &k);
        let mut q = [[0.0; N]; 4];
        for (m, qm) in q.iter_mut().enumerate() {
            let col: [f64; 7] = core::array::from_fn(|j| P[j][m]);
            *qm = lincomb(&[0.0; N], 1.0, &col, &k);
        }
        Ok((y1, e, k[6], Dp5Poly { q }))
    }
}

// ---------------------------------------------------------------------------------------
// DOP853

/// Hairer's DOP853: an eighth-order explicit Runge–Kutta method with a combined 5th/3rd
/// order error estimate (12 stages, the 13th, f at the new point, reused), and a
/// seventh-order dense output that costs 3 more evaluations a step, spent on every step
/// for an observer and only on the event's step for an event.
pub type Dop853 = Adaptive<Dop8>;

/// The DOP853 method's coefficients and error estimate (see [`Dop853`]).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Dop8;

/// The dense output of [`Dop853`].
pub type Dop853Dense<const N: usize> = StepDense<N, Dop8Poly<N>>;

/// The coefficients of DOP853 (Hairer, Nørsett, Wanner, Solving ODEs I; the published
/// dop853.f values).
mod dop853 {
    pub const C: [f64; 16] = [
        0.0,
        0.526001519587677318785587544488e-01,
        0.789002279381515978178381316732e-01,
        0.118350341907227396726757197510,
        0.281649658092772603273242802490,
        0.333333333333333333333333333333,
        0.25,
        0.307692307692307692307692307692,
        0.651282051282051282051282051282,
        0.6,
        0.857142857142857142857142857142,
        1.0,
        1.0,
        0.1,
        0.2,
        0.777777777777777777777777777778,
    ];

    /// Lower-triangular stage matrix, rows 1..15 (row 12 = the weights b).
    pub const A: [[f64; 16]; 16] = {
        let mut a = [[0.0; 16]; 16];
        a[1][0] = 5.26001519587677318785587544488e-2;

        a[2][0] = 1.97250569845378994544595329183e-2;
        a[2][1] = 5.91751709536136983633785987549e-2;

        a[3][0] = 2.95875854768068491816892993775e-2;
        a[3][2] = 8.87627564304205475450678981324e-2;

        a[4][0] = 2.41365134159266685502369798665e-1;
        a[4][2] = -8.84549479328286085344864962717e-1;
        a[4][3] = 9.24834003261792003115737966543e-1;

        a[5][0] = 3.7037037037037037037037037037e-2;
        a[5][3] = 1.70828608729473871279604482173e-1;
        a[5][4] = 1.25467687566822425016691814123e-1;

        a[6][0] = 3.7109375e-2;
        a[6][3] = 1.70252211019544039314978060272e-1;
        a[6][4] = 6.02165389804559606850219397283e-2;
        a[6][5] = -1.7578125e-2;

        a[7][0] = 3.70920001185047927108779319836e-2;
        a[7][3] = 1.70383925712239993810214054705e-1;
        a[7][4] = 1.07262030446373284651809199168e-1;
        a[7][5] = -1.53194377486244017527936158236e-2;
        a[7][6] = 8.27378916381402288758473766002e-3;

        a[8][0] = 6.24110958716075717114429577812e-1;
        a[8][3] = -3.36089262944694129406857109825;
        a[8][4] = -8.68219346841726006818189891453e-1;
        a[8][5] = 2.75920996994467083049415600797e1;
        a[8][6] = 2.01540675504778934086186788979e1;
        a[8][7] = -4.34898841810699588477366255144e1;

        a[9][0] = 4.77662536438264365890433908527e-1;
        a[9][3] = -2.48811461997166764192642586468;
        a[9][4] = -5.90290826836842996371446475743e-1;
        a[9][5] = 2.12300514481811942347288949897e1;
        a[9][6] = 1.52792336328824235832596922938e1;
        a[9][7] = -3.32882109689848629194453265587e1;
        a[9][8] = -2.03312017085086261358222928593e-2;

        a[10][0] = -9.3714243008598732571704021658e-1;
        a[10][3] = 5.18637242884406370830023853209;
        a[10][4] = 1.09143734899672957818500254654;
        a[10][5] = -8.14978701074692612513997267357;
        a[10][6] = -1.85200656599969598641566180701e1;
        a[10][7] = 2.27394870993505042818970056734e1;
        a[10][8] = 2.49360555267965238987089396762;
        a[10][9] = -3.0467644718982195003823669022;

        a[11][0] = 2.27331014751653820792359768449;
        a[11][3] = -1.05344954667372501984066689879e1;
        a[11][4] = -2.00087205822486249909675718444;
        a[11][5] = -1.79589318631187989172765950534e1;
        a[11][6] = 2.79488845294199600508499808837e1;
        a[11][7] = -2.85899827713502369474065508674;
        a[11][8] = -8.87285693353062954433549289258;
        a[11][9] = 1.23605671757943030647266201528e1;
        a[11][10] = 6.43392746015763530355970484046e-1;

        a[12][0] = 5.42937341165687622380535766363e-2;
        a[12][5] = 4.45031289275240888144113950566;
        a[12][6] = 1.89151789931450038304281599044;
        a[12][7] = -5.8012039600105847814672114227;
        a[12][8] = 3.1116436695781989440891606237e-1;
        a[12][9] = -1.52160949662516078556178806805e-1;
        a[12][10] = 2.01365400804030348374776537501e-1;
        a[12][11] = 4.47106157277725905176885569043e-2;

        a[13][0] = 5.61675022830479523392909219681e-2;
        a[13][6] = 2.53500210216624811088794765333e-1;
        a[13][7] = -2.46239037470802489917441475441e-1;
        a[13][8] = -1.24191423263816360469010140626e-1;
        a[13][9] = 1.5329179827876569731206322685e-1;
        a[13][10] = 8.20105229563468988491666602057e-3;
        a[13][11] = 7.56789766054569976138603589584e-3;
        a[13][12] = -8.298e-3;

        a[14][0] = 3.18346481635021405060768473261e-2;
        a[14][5] = 2.83009096723667755288322961402e-2;
        a[14][6] = 5.35419883074385676223797384372e-2;
        a[14][7] = -5.49237485713909884646569340306e-2;
        a[14][10] = -1.08347328697249322858509316994e-4;
        a[14][11] = 3.82571090835658412954920192323e-4;
        a[14][12] = -3.40465008687404560802977114492e-4;
        a[14][13] = 1.41312443674632500278074618366e-1;

        a[15][0] = -4.28896301583791923408573538692e-1;
        a[15][5] = -4.69762141536116384314449447206;
        a[15][6] = 7.68342119606259904184240953878;
        a[15][7] = 4.06898981839711007970213554331;
        a[15][8] = 3.56727187455281109270669543021e-1;
        a[15][12] = -1.39902416515901462129418009734e-3;
        a[15][13] = 2.9475147891527723389556272149;
        a[15][14] = -9.15095847217987001081870187138;
        a
    };

    /// Third-order error weights: b − (b̂₃ at stages 0, 8, 11).
    pub const E3: [f64; 13] = {
        let mut e = [0.0; 13];
        let mut j = 0;
        while j < 12 {
            e[j] = A[12][j];
            j += 1;
        }
        e[0] -= 0.244094488188976377952755905512;
        e[8] -= 0.733846688281611857341361741547;
        e[11] -= 0.220588235294117647058823529412e-1;
        e
    };

    /// Fifth-order error weights.
    pub const E5: [f64; 13] = {
        let mut e = [0.0; 13];
        e[0] = 0.1312004499419488073250102996e-1;
        e[5] = -0.1225156446376204440720569753e1;
        e[6] = -0.4957589496572501915214079952;
        e[7] = 0.1664377182454986536961530415e1;
        e[8] = -0.3503288487499736816886487290;
        e[9] = 0.3341791187130174790297318841;
        e[10] = 0.8192320648511571246570742613e-1;
        e[11] = -0.2235530786388629525884427845e-1;
        e
    };

    /// Dense-output weights of the 4 highest interpolant terms, over the 16 stages.
    pub const D: [[f64; 16]; 4] = {
        let mut d = [[0.0; 16]; 4];
        d[0][0] = -0.84289382761090128651353491142e1;
        d[0][5] = 0.56671495351937776962531783590;
        d[0][6] = -0.30689499459498916912797304727e1;
        d[0][7] = 0.23846676565120698287728149680e1;
        d[0][8] = 0.21170345824450282767155149946e1;
        d[0][9] = -0.87139158377797299206789907490;
        d[0][10] = 0.22404374302607882758541771650e1;
        d[0][11] = 0.63157877876946881815570249290;
        d[0][12] = -0.88990336451333310820698117400e-1;
        d[0][13] = 0.18148505520854727256656404962e2;
        d[0][14] = -0.91946323924783554000451984436e1;
        d[0][15] = -0.44360363875948939664310572000e1;

        d[1][0] = 0.10427508642579134603413151009e2;
        d[1][5] = 0.24228349177525818288430175319e3;
        d[1][6] = 0.16520045171727028198505394887e3;
        d[1][7] = -0.37454675472269020279518312152e3;
        d[1][8] = -0.22113666853125306036270938578e2;
        d[1][9] = 0.77334326684722638389603898808e1;
        d[1][10] = -0.30674084731089398182061213626e2;
        d[1][11] = -0.93321305264302278729567221706e1;
        d[1][12] = 0.15697238121770843886131091075e2;
        d[1][13] = -0.31139403219565177677282850411e2;
        d[1][14] = -0.93529243588444783865713862664e1;
        d[1][15] = 0.35816841486394083752465898540e2;

        d[2][0] = 0.19985053242002433820987653617e2;
        d[2][5] = -0.38703730874935176555105901742e3;
        d[2][6] = -0.18917813819516756882830838328e3;
        d[2][7] = 0.52780815920542364900561016686e3;
        d[2][8] = -0.11573902539959630126141871134e2;
        d[2][9] = 0.68812326946963000169666922661e1;
        d[2][10] = -0.10006050966910838403183860980e1;
        d[2][11] = 0.77771377980534432092869265740;
        d[2][12] = -0.27782057523535084065932004339e1;
        d[2][13] = -0.60196695231264120758267380846e2;
        d[2][14] = 0.84320405506677161018159903784e2;
        d[2][15] = 0.11992291136182789328035130030e2;

        d[3][0] = -0.25693933462703749003312586129e2;
        d[3][5] = -0.15418974869023643374053993627e3;
        d[3][6] = -0.23152937917604549567536039109e3;
        d[3][7] = 0.35763911791061412378285349910e3;
        d[3][8] = 0.93405324183624310003907691704e2;
        d[3][9] = -0.37458323136451633156875139351e2;
        d[3][10] = 0.10409964950896230045147246184e3;
        d[3][11] = 0.29840293426660503123344363579e2;
        d[3][12] = -0.43533456590011143754432175058e2;
        d[3][13] = 0.96324553959188282948394950600e2;
        d[3][14] = -0.39177261675615439165231486172e2;
        d[3][15] = -0.14972683625798562581422125276e3;
        d
    };
}

/// The interpolant of [`Dop853`]: the seventh-degree polynomial of Hairer's `contd8`,
/// y = y0 + θ(F0 + (1−θ)(F1 + θ(F2 + (1−θ)(F3 + θ(F4 + (1−θ)(F5 + θ F6)))))). Until the
/// extra stages are computed ([`Method::densify`]) it is the cubic Hermite interpolant
/// (F3..F6 = 0).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Dop8Poly<const N: usize> {
    coef: [[f64; N]; 7],
    /// The 16 stages (the last 3 only once the interpolant is complete).
    k: [[f64; N]; 16],
    degree7: bool,
}

impl<const N: usize> Interpolant<N> for Dop8Poly<N> {
    fn at(d: &StepDense<N, Self>, s: f64) -> [f64; N] {
        let s1 = 1.0 - s;
        let top = if d.poly.degree7 { 7 } else { 3 };
        let mut out = [0.0; N];
        for i in 0..N {
            let mut acc = 0.0;
            for (m, c) in d.poly.coef[..top].iter().enumerate().rev() {
                acc += c[i];
                acc *= if m % 2 == 0 { s } else { s1 };
            }
            out[i] = d.y0[i] + acc;
        }
        out
    }
}

impl<const N: usize> Tableau<N> for Dop8 {
    const ERROR_ORDER: u32 = 7;
    type Poly = Dop8Poly<N>;
    fn attempt<F>(
        f: &mut F,
        t: f64,
        y: &[f64; N],
        dy: &[f64; N],
        h: f64,
        tol: &Tolerance,
        stats: &mut Stats,
    ) -> Result<([f64; N], [f64; N], [f64; N], Dop8Poly<N>), MechError>
    where
        F: FnMut(f64, &[f64; N]) -> Result<[f64; N], MechError>,
    {
        use dop853::*;
        let mut k = [[0.0; N]; 16];
        k[0] = *dy;
        for s in 1..12 {
            let ys = lincomb(y, h, &A[s], &k);
            k[s] = eval(f, t + C[s] * h, &ys, stats)?;
        }
        let y1 = lincomb(y, h, &A[12], &k);
        k[12] = eval(f, t + h, &y1, stats)?;
        // Hairer's combined estimate |h| ‖e5‖² / sqrt(‖e5‖² + 0.01 ‖e3‖²), returned as the
        // vector e = ratio · e5 whose scaled RMS norm equals it.
        let (mut n5, mut n3) = (0.0, 0.0);
        let mut e5 = [0.0; N];
        for i in 0..N {
            let (mut a5, mut a3) = (0.0, 0.0);
            for j in 0..13 {
                a5 += E5[j] * k[j][i];
                a3 += E3[j] * k[j][i];
            }
            let sc = tol.scale(y[i], y1[i]);
            e5[i] = a5;
            n5 += (a5 / sc).powi(2);
            n3 += (a3 / sc).powi(2);
        }
        let ratio = if n5 == 0.0 && n3 == 0.0 {
            0.0
        } else {
            h.abs() * n5.sqrt() / (n5 + 0.01 * n3).sqrt()
        };
        let e = e5.map(|v| ratio * v);
        let mut coef = [[0.0; N]; 7];
        for i in 0..N {
            let dyi = y1[i] - y[i];
            coef[0][i] = dyi;
            coef[1][i] = h * k[0][i] - dyi;
            coef[2][i] = 2.0 * dyi - h * (k[12][i] + k[0][i]);
        }
        Ok((
            y1,
            e,
            k[12],
            Dop8Poly {
                coef,
                k,
                degree7: false,
            },
        ))
    }

    fn densify<F>(
        f: &mut F,
        d: &mut StepDense<N, Dop8Poly<N>>,
        stats: &mut Stats,
    ) -> Result<(), MechError>
    where
        F: FnMut(f64, &[f64; N]) -> Result<[f64; N], MechError>,
    {
        use dop853::*;
        if d.poly.degree7 {
            return Ok(());
        }
        let (t, h) = (d.t0, d.h);
        for s in 13..16 {
            let ys = lincomb(&d.y0, h, &A[s], &d.poly.k);
            d.poly.k[s] = eval(f, t + C[s] * h, &ys, stats)?;
        }
        for m in 0..4 {
            d.poly.coef[3 + m] = lincomb(&[0.0; N], h, &D[m], &d.poly.k);
        }
        d.poly.degree7 = true;
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn exp_rhs(_: f64, y: &[f64; 1]) -> Result<[f64; 1], MechError> {
        Ok([y[0]])
    }
    /// x'' = −x as (x, v).
    fn oscillator(_: f64, y: &[f64; 2]) -> Result<[f64; 2], MechError> {
        Ok([y[1], -y[0]])
    }

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
        assert!(e2 < 1e-9, "{e2}");
        let order = (e1 / e2).log2();
        assert!((order - 4.0).abs() < 0.1, "observed order {order}");
        let r = integrate(&mut Rk4 { h: 0.01 }, exp_rhs, 0.0, [1.0], 1.0).unwrap();
        assert_eq!(r.stats.steps, 100);
        assert_eq!(r.stats.rhs_evals, 1 + 4 * 100);
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
                2e-9,
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
                2e-10,
            ),
        ] {
            assert!(
                (r.y[0] - t_end.cos()).abs() < tol,
                "{name}: {:e}",
                r.y[0] - t_end.cos()
            );
            assert!(
                (r.y[1] + t_end.sin()).abs() < tol,
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
        assert!((r.y[0] - 2f64.cos()).abs() < 1e-10 && (r.y[1] - 2f64.sin()).abs() < 1e-10);
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
            e_lo < 1e-8 && e_hi < 1e-4 && e_lo < e_hi / 100.0,
            "{e_hi:e} {e_lo:e}"
        );
        let e8 =
            err(&mut || integrate(&mut Dop853::new(1e-13, 0.0), exp_rhs, 0.0, [1.0], 3.0).unwrap());
        assert!(e8 < 1e-12, "{e8:e}");
    }

    #[test]
    fn dense_output_matches_the_solution() {
        let times: Vec<f64> = (0..=200).map(|i| i as f64 * 0.05).collect();
        let mut out = vec![[0.0; 2]; times.len()];
        for (name, tol) in [("rk4", 1e-8), ("dp5", 1e-8), ("dop853", 1e-11)] {
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
                    (y[0] - t.cos()).abs() < tol,
                    "{name} at {t}: {:e}",
                    y[0] - t.cos()
                );
                assert!(
                    (y[1] + t.sin()).abs() < tol,
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
            assert!((a[i] - y0[i]).abs() < 1e-15 && (b[i] - d.y_end()[i]).abs() < 1e-15);
        }
    }

    #[test]
    fn event_is_located_on_the_dense_output() {
        for method in 0..3 {
            let mut g = |_: f64, y: &[f64; 2]| y[0];
            let mut ev = Event {
                g: &mut g,
                direction: -1,
                t_tol: 1e-14,
            };
            let r = match method {
                0 => solve(
                    &mut Rk4 { h: 1e-3 },
                    oscillator,
                    0.0,
                    [1.0, 0.0],
                    10.0,
                    Some(&mut ev),
                    None,
                ),
                1 => solve(
                    &mut DormandPrince::new(1e-12, 1e-14),
                    oscillator,
                    0.0,
                    [1.0, 0.0],
                    10.0,
                    Some(&mut ev),
                    None,
                ),
                _ => solve(
                    &mut Dop853::new(1e-12, 1e-14),
                    oscillator,
                    0.0,
                    [1.0, 0.0],
                    10.0,
                    Some(&mut ev),
                    None,
                ),
            }
            .unwrap();
            assert!(r.event);
            let tol = if method == 0 { 1e-11 } else { 1e-10 };
            assert!(
                (r.t - std::f64::consts::FRAC_PI_2).abs() < tol,
                "method {method}: {:e}",
                r.t - std::f64::consts::FRAC_PI_2
            );
            assert!((r.y[1] + 1.0).abs() < 1e-9);
        }
        // Upward crossings only: x = cos t first rises through 0 at 3π/2.
        let mut g = |_: f64, y: &[f64; 2]| y[0];
        let mut ev = Event {
            g: &mut g,
            direction: 1,
            t_tol: 1e-14,
        };
        let r = solve(
            &mut Dop853::new(1e-12, 1e-14),
            oscillator,
            0.0,
            [1.0, 0.0],
            10.0,
            Some(&mut ev),
            None,
        )
        .unwrap();
        assert!((r.t - 1.5 * std::f64::consts::PI).abs() < 1e-10);
    }

    #[test]
    fn errors_not_panics() {
        // y' = y² blows up at t = 1: the step size underflows there.
        let blow = |_: f64, y: &[f64; 1]| -> Result<[f64; 1], MechError> { Ok([y[0] * y[0]]) };
        match integrate(&mut DormandPrince::new(1e-8, 1e-8), blow, 0.0, [1.0], 2.0) {
            Err(MechError::StepUnderflow { t }) => assert!((t - 1.0).abs() < 1e-3, "{t}"),
            Err(MechError::InvalidInput(_)) => {}
            other => panic!("{other:?}"),
        }
        assert!(matches!(
            integrate(&mut Rk4 { h: 0.0 }, exp_rhs, 0.0, [1.0], 1.0),
            Err(MechError::InvalidInput(_))
        ));
        assert!(matches!(
            integrate(&mut Rk4 { h: 0.1 }, exp_rhs, 0.0, [f64::NAN], 1.0),
            Err(MechError::InvalidInput(_))
        ));
        assert!(matches!(
            integrate(&mut DormandPrince::new(-1.0, 0.0), exp_rhs, 0.0, [1.0], 1.0),
            Err(MechError::InvalidInput(_))
        ));
        assert!(matches!(
            integrate(&mut Rk4 { h: 0.6 }, blow, 0.0, [1.0], 2.0),
            Err(MechError::InvalidInput(_))
        ));
        let fails = |t: f64, _: &[f64; 1]| -> Result<[f64; 1], MechError> {
            if t > 0.5 {
                Err(MechError::NoAssembly)
            } else {
                Ok([1.0])
            }
        };
        assert_eq!(
            integrate(&mut Dop853::new(1e-6, 1e-6), fails, 0.0, [0.0], 1.0).unwrap_err(),
            MechError::NoAssembly
        );
    }
}
