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
//!
//! The module's files, by aspect: `method` (the [`Method`] and [`Dense`] traits, a run's
//! [`Event`], [`Outcome`] and [`Stats`]), `driver` ([`solve`], [`integrate`], [`sample`]
//! and the event location), `dense` (the dense output of one step, [`StepDense`]), `rk4`
//! ([`Rk4`]), `adaptive` (the step-size control, [`Tolerance`], [`Tableau`],
//! [`Adaptive`]), `dormand_prince` ([`DormandPrince`]), `dop853` and
//! `dop853_coefficients` ([`Dop853`]).

// The published coefficients keep all their digits; `!(x > 0.0)` also rejects NaN; the
// kernels index several arrays in lockstep and pass the integrator's whole state.
#![allow(
    clippy::excessive_precision,
    clippy::neg_cmp_op_on_partial_ord,
    clippy::needless_range_loop,
    clippy::too_many_arguments,
    clippy::type_complexity
)]

mod adaptive;
mod dense;
mod dop853;
mod dop853_coefficients;
mod dormand_prince;
mod driver;
mod method;
mod rk4;

pub use adaptive::{Adaptive, Tableau, Tolerance, DEFAULT_MAX_STEPS};
pub use dense::{Hermite, Interpolant, StepDense};
pub use dop853::{Dop8, Dop853, Dop853Dense, Dop8Poly};
pub use dormand_prince::{DormandPrince, Dp5, Dp5Poly};
pub use driver::{integrate, sample, solve};
pub use method::{Dense, Event, Method, Outcome, Stats};
pub use rk4::Rk4;

/// The right-hand sides the unit tests of the files share.
#[cfg(test)]
mod test_rhs {
    use crate::MechError;

    pub(super) fn exp_rhs(_: f64, y: &[f64; 1]) -> Result<[f64; 1], MechError> {
        Ok([y[0]])
    }
    /// x'' = −x as (x, v).
    pub(super) fn oscillator(_: f64, y: &[f64; 2]) -> Result<[f64; 2], MechError> {
        Ok([y[1], -y[0]])
    }
}
