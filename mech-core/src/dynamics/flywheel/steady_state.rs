//! The periodic motion with a given flywheel: [`Cycle::steady_state`] ([`SteadyState`],
//! its [`SpeedRange`]), the speed ω(q) on it and the coefficient of fluctuation of speed.

use super::cycle::Cycle;
use crate::dynamics::speed_from_energy;
use crate::solvers::traits::OneDof;
use crate::MechError;

/// The speed extremes of a periodic motion over one cycle.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct SpeedRange {
    /// ω_max, rad/s.
    pub omega_max: f64,
    /// Where ω_max is reached, rad.
    pub q_max: f64,
    /// ω_min, rad/s.
    pub omega_min: f64,
    /// Where ω_min is reached, rad.
    pub q_min: f64,
    /// ω_a = (ω_max + ω_min)/2, rad/s.
    pub omega_mean: f64,
    /// ε = (ω_max − ω_min)/ω_a.
    pub irregularity: f64,
}

impl SpeedRange {
    /// From the extremes (rad/s) and where they are reached (rad): ω_a and ε.
    pub fn new(omega_max: f64, q_max: f64, omega_min: f64, q_min: f64) -> Self {
        let omega_mean = 0.5 * (omega_max + omega_min);
        SpeedRange {
            omega_max,
            q_max,
            omega_min,
            q_min,
            omega_mean,
            irregularity: (omega_max - omega_min) / omega_mean,
        }
    }
}

/// A periodic motion of the machine with a flywheel: ω(q)² = 2 (E + S(q)) / (I + I*(q)).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct SteadyState {
    /// Flywheel inertia I added to I* on the input, kg·m².
    pub flywheel: f64,
    /// Kinetic energy at q0, E = ½ (I + I*(q0)) ω0², J.
    pub energy: f64,
    /// ω_max, ω_min, ω_a, ε of the motion.
    pub speeds: SpeedRange,
}

impl<'a, M: OneDof> Cycle<'a, M> {
    /// The coefficient of fluctuation of speed δ = (ω_max − ω_min)/ω_a that a flywheel of
    /// inertia I (kg·m², added on the input) gives at the mean speed ω_a (rad/s): the
    /// steady state of [`Cycle::steady_state`], exact (no I ≫ I* assumption). For a large
    /// flywheel δ → ΔE' / (I ω_a²), ΔE' the range of S(q) − ½ I*(q) ω_a² over the cycle:
    /// ΔE ([`Cycle::fluctuation`]) less the swing of the machine's own kinetic energy,
    /// which the approximate formula neglects and Wittenbauer's method keeps.
    pub fn speed_fluctuation(&self, omega_mean: f64, flywheel: f64) -> Result<f64, MechError> {
        Ok(self.steady_state(omega_mean, flywheel)?.speeds.irregularity)
    }

    /// The periodic motion with a flywheel of inertia I (kg·m², 0 for none) whose mean speed
    /// (ω_max + ω_min)/2 is ω_a (rad/s): the energy E (J) by safeguarded Newton iteration on
    /// ω_a(E), ω_max,min = max,min over q of √(2 (E + S)/(I + I*)). Errors: bad input,
    /// [`MechError::NotPeriodic`], [`MechError::NonPositiveInertia`] when I + I* ≤ 0
    /// somewhere, [`MechError::Stall`] (at the position of S_min) when even the slowest
    /// periodic motion (ω = 0 at S_min) has a mean speed above ω_a: the machine cannot turn
    /// that slowly with this flywheel, it stops.
    pub fn steady_state(&self, omega_mean: f64, flywheel: f64) -> Result<SteadyState, MechError> {
        crate::error::check_finite("flywheel", &[flywheel])?;
        check_speed(omega_mean)?;
        self.check_periodic()?;
        let total = flywheel + self.min_inertia()?;
        if !(total > 0.0) {
            return Err(MechError::NonPositiveInertia(total));
        }
        let s_min = self.extreme(|s, _| s, false)?;
        // (ω_mean(E) − ω_a, its derivative dω/dE = Σ 1/(2 ω (I + I*)), the state).
        let eval = |e: f64| -> Result<(f64, f64, SteadyState), MechError> {
            let hi = self.extreme(|s, i| (e + s) / (flywheel + i), true)?;
            let lo = self.extreme(|s, i| (e + s) / (flywheel + i), false)?;
            let (w_hi, w_lo) = ((2.0 * hi.value).sqrt(), (2.0 * lo.value.max(0.0)).sqrt());
            let d = 0.5 / (w_hi * (flywheel + hi.inertia))
                + if w_lo > 0.0 {
                    0.5 / (w_lo * (flywheel + lo.inertia))
                } else {
                    f64::INFINITY
                };
            let speeds = SpeedRange::new(w_hi, hi.q, w_lo, lo.q);
            Ok((
                speeds.omega_mean - omega_mean,
                d,
                SteadyState {
                    flywheel,
                    energy: e,
                    speeds,
                },
            ))
        };
        let mut lo = -s_min.value;
        let (g_lo, _, _) = eval(lo)?;
        if g_lo >= 0.0 {
            return Err(MechError::Stall { q: s_min.q });
        }
        // An upper bracket: at E = −S_min + ½ (I + max I*) ω_a², (E + S)/(I + I*) ≥ ω_a²/2
        // everywhere, so even the slowest point turns at ω_a or faster.
        let mut hi =
            lo + 0.5 * (flywheel + self.extreme(|_, i| i, true)?.value) * omega_mean * omega_mean;
        while eval(hi)?.0 < 0.0 {
            hi = lo + 2.0 * (hi - lo);
        }
        let mut e = hi;
        for _ in 0..200 {
            let (g, d, state) = eval(e)?;
            if g.abs() <= 4.0 * f64::EPSILON * omega_mean
                || hi - lo <= 4.0 * f64::EPSILON * hi.abs()
            {
                return Ok(state);
            }
            if g < 0.0 {
                lo = e;
            } else {
                hi = e;
            }
            let newton = e - g / d;
            e = if newton > lo && newton < hi {
                newton
            } else {
                0.5 * (lo + hi)
            };
        }
        Ok(eval(e)?.2)
    }

    /// ω(q) = √(2 (E + S(q)) / (I + I*(q))) in the steady state `state`, rad/s.
    /// Errors: [`MechError::Stall`] where E + S ≤ 0, [`MechError::NonPositiveInertia`].
    pub fn speed(&self, state: &SteadyState, q: f64) -> Result<f64, MechError> {
        speed_from_energy(
            state.energy,
            self.work(q)?,
            state.flywheel + self.reduced(q)?.inertia,
            q,
        )
    }
}

/// A finite ω_a > 0.
pub(super) fn check_speed(omega_mean: f64) -> Result<(), MechError> {
    crate::error::check_finite("mean speed", &[omega_mean])?;
    if omega_mean > 0.0 {
        Ok(())
    } else {
        Err(MechError::InvalidInput(format!(
            "the mean speed must be positive, got {omega_mean}"
        )))
    }
}
