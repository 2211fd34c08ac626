//! The loop written once for all methods: [`solve`] drives a [`Method`] to the end time,
//! stops at an [`Event`] located on the dense output (Illinois regula falsi) and feeds an
//! observer; [`integrate`] and [`sample`] are its two common uses.

use super::method::{eval, Dense, Event, Method, Outcome, Stats};
use crate::MechError;

#[inline]
fn finite<const N: usize>(y: &[f64; N]) -> bool {
    crate::error::all_finite(y)
}

fn check_run<const N: usize>(t0: f64, y0: &[f64; N], t_end: f64) -> Result<(), MechError> {
    crate::error::check_finite("t0, t_end", &[t0, t_end])?;
    crate::error::check_finite("y0", y0)
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::dynamics::ode::test_rhs::{exp_rhs, oscillator};
    use crate::dynamics::ode::{Dop853, DormandPrince, Rk4};
    use crate::kernel::measure::{within, within_at};

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
            // RK4, DP5, DOP853: measured worst 5.0e-14, 3.1e-15, 1.7e-14 in t and 2.2e-15,
            // 1.4e-13, 2.9e-15 in y (be05608); 100×.
            let tol = [2e-12, 2e-13, 1e-12][method];
            assert!(
                within_at(
                    ["rk4", "dp5", "dop853"][method],
                    (r.t - std::f64::consts::FRAC_PI_2).abs(),
                    tol
                ),
                "method {method}: {:e}",
                r.t - std::f64::consts::FRAC_PI_2
            );
            assert!(within_at(
                ["rk4", "dp5", "dop853"][method],
                (r.y[1] + 1.0).abs(),
                [2e-13, 1e-11, 2e-13][method]
            ));
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
        // measured worst 9.2e-14 (be05608); 100×
        assert!(within((r.t - 1.5 * std::f64::consts::PI).abs(), 5e-12));
    }

    #[test]
    fn errors_not_panics() {
        // y' = y² blows up at t = 1: the step size underflows there.
        let blow = |_: f64, y: &[f64; 1]| -> Result<[f64; 1], MechError> { Ok([y[0] * y[0]]) };
        match integrate(&mut DormandPrince::new(1e-8, 1e-8), blow, 0.0, [1.0], 2.0) {
            Err(MechError::StepUnderflow { t }) => assert!(within((t - 1.0).abs(), 1e-7), "{t}"), // measured worst 1.1e-9 (be05608); 100×
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
