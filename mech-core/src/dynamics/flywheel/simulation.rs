//! The check by time integration: [`Cycle::simulate`] integrates the machine with its
//! flywheel over one cycle by DOP853 and locates ω_max and ω_min on the dense output
//! ([`CycleSimulation`]).

use super::cycle::Cycle;
use super::extremes::golden_max;
use super::steady_state::{SpeedRange, SteadyState};
use crate::dynamics::ode::{self, Dense, Dop853, Event, Stats, Tolerance};
use crate::solvers::traits::OneDof;
use crate::solvers::zhukovski::{self, Reduced};
use crate::MechError;

/// The step budget of [`Cycle::simulate`]'s one cycle: a cycle of a machine that is not
/// stiff takes hundreds of steps, and a stiff one ends in the budget's error within a
/// fraction of a second.
const CYCLE_MAX_STEPS: usize = 20_000;

/// One simulated cycle ([`Cycle::simulate`]).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct CycleSimulation {
    /// ω_max, ω_min (located on the dense output), ω_a, ε reached.
    pub speeds: SpeedRange,
    /// Speed at the start q0, rad/s.
    pub omega_start: f64,
    /// Speed on return to q0 + λ, rad/s (= `omega_start` in steady state).
    pub omega_end: f64,
    /// Duration of the cycle, s.
    pub duration: f64,
    /// The integrator's work.
    pub stats: Stats,
}

impl<'a, M: OneDof> Cycle<'a, M> {
    /// The check by time integration: the machine with the flywheel (I + I*) q̈ + ½ dI*/dq q̇²
    /// = M*(q), from q0 at ω(q0) of `state`, integrated by DOP853 (relative tolerance `rtol`)
    /// until q = q0 + λ (an event); ω_max and ω_min are located on the dense output where
    /// q̈ changes sign. Errors: bad `rtol`, the machine's and the integrator's errors, and
    /// a cycle that needs more than 20 000 steps (a stiff machine: a cycle of
    /// a real one takes hundreds).
    pub fn simulate(&self, state: &SteadyState, rtol: f64) -> Result<CycleSimulation, MechError> {
        crate::error::check_finite("rtol", &[rtol])?;
        if !(rtol > 0.0) {
            return Err(MechError::InvalidInput(format!(
                "rtol must be positive, got {rtol}"
            )));
        }
        let (q0, q_end) = (self.start, self.start + self.period);
        let omega0 = self.speed(state, q0)?;
        let flywheel = state.flywheel;
        let mut rhs = |_t: f64, y: &[f64; 2]| -> Result<[f64; 2], MechError> {
            let r = self.reduced(y[0])?;
            let total = Reduced {
                inertia: flywheel + r.inertia,
                ..r
            };
            Ok([
                y[1],
                zhukovski::acceleration(total, self.moment(y[0])?, y[1], 0.0)?,
            ])
        };
        let acc0 = rhs(0.0, &[q0, omega0])?[1];
        // Extremes of q̇ over the steps, clipped to q ≤ q0 + λ (the event step overshoots).
        let mut best = Best {
            max: (omega0, q0),
            min: (omega0, q0),
        };
        let mut prev_acc = acc0;
        let mut failure: Option<MechError> = None;
        let mut observe = |d: &<Dop853 as ode::Method<2>>::Dense| {
            let (ta, mut tb) = (d.t_start(), d.t_end());
            if d.y_end()[0] > q_end {
                tb = bisect(|t| d.eval(t)[0] - q_end, ta, tb);
            }
            let yb = d.eval(tb);
            best.add(yb[1], yb[0]);
            let acc = d.dy_end()[1];
            if prev_acc * acc <= 0.0 && tb > ta {
                let s = if prev_acc > 0.0 || acc < 0.0 {
                    1.0
                } else {
                    -1.0
                };
                match golden_max(|t| Ok(s * d.eval(t)[1]), ta, tb) {
                    Ok((t, _)) => {
                        let y = d.eval(t);
                        best.add(y[1], y[0]);
                    }
                    Err(e) => failure = Some(e),
                }
            }
            prev_acc = acc;
        };
        let mut g = |_t: f64, y: &[f64; 2]| y[0] - q_end;
        let mut event = Event {
            g: &mut g,
            direction: 1,
            t_tol: 1e-15,
        };
        // Long enough to pass q0 + λ at the slowest speed the state allows.
        let t_end = 4.0 * self.period / state.speeds.omega_min.max(1e-3 * omega0);
        let mut method = Dop853::with(Tolerance {
            max_steps: CYCLE_MAX_STEPS,
            ..Tolerance::new(rtol, rtol * 1e-6)
        });
        let out = ode::solve(
            &mut method,
            &mut rhs,
            0.0,
            [q0, omega0],
            t_end,
            Some(&mut event),
            Some(&mut observe),
        )?;
        if let Some(e) = failure {
            return Err(e);
        }
        if !out.event {
            return Err(MechError::Stall { q: out.y[0] });
        }
        let ((omega_max, q_max), (omega_min, q_min)) = (best.max, best.min);
        Ok(CycleSimulation {
            speeds: SpeedRange::new(omega_max, q_max, omega_min, q_min),
            omega_start: omega0,
            omega_end: out.y[1],
            duration: out.t,
            stats: out.stats,
        })
    }
}

/// The running extremes (value, position) of a simulation.
struct Best {
    max: (f64, f64),
    min: (f64, f64),
}

impl Best {
    fn add(&mut self, w: f64, q: f64) {
        if w > self.max.0 {
            self.max = (w, q);
        }
        if w < self.min.0 {
            self.min = (w, q);
        }
    }
}

/// The zero of an increasing f on [a, b] with f(a) ≤ 0 ≤ f(b), by bisection to the last bit.
fn bisect(f: impl Fn(f64) -> f64, mut a: f64, mut b: f64) -> f64 {
    loop {
        let m = 0.5 * (a + b);
        if m <= a || m >= b {
            return b;
        }
        if f(m) > 0.0 {
            b = m;
        } else {
            a = m;
        }
    }
}
