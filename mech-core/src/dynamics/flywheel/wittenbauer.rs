//! The flywheel for a mean speed and an irregularity: Wittenbauer's exact inertia
//! ([`Cycle::wittenbauer`], its [`Tangent`]s), the approximate one (I ≫ I*,
//! [`Cycle::approximate`]) and both ([`Cycle::flywheel`]).

use super::cycle::Cycle;
use super::steady_state::{check_speed, SpeedRange, SteadyState};
use crate::solvers::traits::OneDof;
use crate::MechError;

/// A tangent of the Wittenbauer diagram: the line F = slope · I*_axis + intercept touching
/// the curve (I*(q), F(q)) at `point`.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Tangent {
    /// tan θ = (1 ± ε/2)², the squared speed ratio (ω/ω_a)² reached at the tangent point.
    pub slope: f64,
    /// F at I* = 0, rad: max (or min) over the cycle of F(q) − slope · I*(q), plus 0.
    pub intercept: f64,
    /// Position of the tangent point, rad.
    pub q: f64,
    /// I* at the tangent point, kg·m².
    pub reduced_inertia: f64,
    /// F = 2 S / ω_a² at the tangent point, kg·m² (F has the units of an inertia).
    pub f: f64,
}

/// The exact flywheel by Wittenbauer's method ([`Cycle::wittenbauer`]).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Wittenbauer {
    /// Flywheel inertia I, kg·m²: the abscissa of P is −I. Negative when the machine's
    /// own inertia already keeps the irregularity below ε.
    pub inertia: f64,
    /// C = (I + I*(q0)) (ω0/ω_a)², kg·m²: the ordinate of P is −C.
    pub c: f64,
    /// The tangent of slope (1 + ε/2)² (ω_max).
    pub upper: Tangent,
    /// The tangent of slope (1 − ε/2)² (ω_min).
    pub lower: Tangent,
    /// The motion with this flywheel: ω_a and ε as requested, E = C ω_a²/2.
    pub state: SteadyState,
}

/// The approximate flywheel (I ≫ I*, [`Cycle::approximate`]).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Approximate {
    /// I = (S_max − S_min)/(ε ω_a²), kg·m².
    pub inertia: f64,
    /// Largest accumulated work over the cycle, J, and where (rad).
    pub s_max: f64,
    /// Where S_max is reached, rad.
    pub q_s_max: f64,
    /// Smallest accumulated work, J.
    pub s_min: f64,
    /// Where S_min is reached, rad.
    pub q_s_min: f64,
}

/// Both flywheels for one (ω_a, ε) ([`Cycle::flywheel`]).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Flywheel {
    /// Mean speed ω_a, rad/s.
    pub omega_mean: f64,
    /// Irregularity ε.
    pub irregularity: f64,
    /// Wittenbauer's exact inertia and its diagram.
    pub exact: Wittenbauer,
    /// The approximate inertia.
    pub approximate: Approximate,
}

impl<'a, M: OneDof> Cycle<'a, M> {
    /// The approximate flywheel (`docs/theory.md` §7.5, I ≫ I*):
    /// I = (S_max − S_min)/(ε ω_a²), kg·m².
    /// Errors: ω_a ≤ 0, ε ∉ (0, 2), non-finite input, [`MechError::NotPeriodic`].
    pub fn approximate(
        &self,
        omega_mean: f64,
        irregularity: f64,
    ) -> Result<Approximate, MechError> {
        check_design(omega_mean, irregularity)?;
        let f = self.fluctuation()?;
        let inertia = f.energy / (irregularity * omega_mean * omega_mean);
        finite_design("approximate flywheel inertia", &[inertia])?;
        Ok(Approximate {
            inertia,
            s_max: f.s_max,
            q_s_max: f.q_s_max,
            s_min: f.s_min,
            q_s_min: f.q_s_min,
        })
    }

    /// The exact flywheel by Wittenbauer's method (module documentation):
    /// I = (max(F − a I*) − min(F − b I*))/(a − b), a, b = (1 ± ε/2)², F = 2 S/ω_a², kg·m².
    /// Errors: ω_a ≤ 0, ε ∉ (0, 2), non-finite input, [`MechError::NotPeriodic`], and
    /// [`MechError::NonPositiveInertia`] (with min(I + I*)) when the result leaves
    /// I + I*(q) ≤ 0 somewhere: the machine alone is steadier than ε and no flywheel of
    /// this kind gives exactly ε.
    pub fn wittenbauer(
        &self,
        omega_mean: f64,
        irregularity: f64,
    ) -> Result<Wittenbauer, MechError> {
        check_design(omega_mean, irregularity)?;
        self.check_periodic()?;
        let k = 2.0 / (omega_mean * omega_mean);
        let tangent = |slope: f64, maximize: bool| -> Result<Tangent, MechError> {
            let e = self.extreme(|s, i| k * s - slope * i, maximize)?;
            Ok(Tangent {
                slope,
                intercept: e.value,
                q: e.q,
                reduced_inertia: e.inertia,
                f: k * e.work,
            })
        };
        let (a, b) = (
            (1.0 + 0.5 * irregularity).powi(2),
            (1.0 - 0.5 * irregularity).powi(2),
        );
        let upper = tangent(a, true)?;
        let lower = tangent(b, false)?;
        // a − b = (1 + ε/2)² − (1 − ε/2)² = 2ε exactly: the difference of the rounded
        // squares would lose the digits of a small ε (all of them below 1e-16).
        let inertia = (upper.intercept - lower.intercept) / (2.0 * irregularity);
        let c = a * inertia - upper.intercept;
        let energy = 0.5 * c * omega_mean * omega_mean;
        finite_design(
            "Wittenbauer flywheel's inertia and energy",
            &[
                inertia,
                c,
                energy,
                upper.f,
                lower.f,
                upper.intercept,
                lower.intercept,
            ],
        )?;
        let total = inertia + self.min_inertia()?;
        if !(total > 0.0) {
            return Err(MechError::NonPositiveInertia(total));
        }
        let state = SteadyState {
            flywheel: inertia,
            energy,
            speeds: SpeedRange {
                omega_max: omega_mean * (1.0 + 0.5 * irregularity),
                q_max: upper.q,
                omega_min: omega_mean * (1.0 - 0.5 * irregularity),
                q_min: lower.q,
                omega_mean,
                irregularity,
            },
        };
        Ok(Wittenbauer {
            inertia,
            c,
            upper,
            lower,
            state,
        })
    }

    /// Both flywheels for the mean speed ω_a (rad/s) and the irregularity ε.
    pub fn flywheel(&self, omega_mean: f64, irregularity: f64) -> Result<Flywheel, MechError> {
        Ok(Flywheel {
            omega_mean,
            irregularity,
            exact: self.wittenbauer(omega_mean, irregularity)?,
            approximate: self.approximate(omega_mean, irregularity)?,
        })
    }
}

/// `Ok` when the flywheel's numbers `values` (named `what`) are finite; else
/// `InvalidInput`: a mean speed or an irregularity so extreme (ω_a of 1e200 rad/s, ε of
/// 1e-300) that the inertia or the energy overflows f64.
fn finite_design(what: &str, values: &[f64]) -> Result<(), MechError> {
    if crate::error::all_finite(values) {
        return Ok(());
    }
    Err(MechError::InvalidInput(format!(
        "the {what} overflow f64 ({values:?}): the mean speed or the irregularity is too extreme for this cycle; give a speed and an irregularity of a real machine"
    )))
}

/// ω_a > 0 and 0 < ε < 2 (so that ω_min = ω_a (1 − ε/2) > 0), finite.
fn check_design(omega_mean: f64, irregularity: f64) -> Result<(), MechError> {
    check_speed(omega_mean)?;
    crate::error::check_finite("irregularity", &[irregularity])?;
    if !(irregularity > 0.0 && irregularity < 2.0) {
        return Err(MechError::InvalidInput(format!(
            "the irregularity must be in (0, 2), got {irregularity}"
        )));
    }
    Ok(())
}
