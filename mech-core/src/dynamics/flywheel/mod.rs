//! Flywheel design of a one-DOF machine in steady state (`docs/theory.md` §7),
//! written once over [`OneDof`](crate::solvers::traits::OneDof).
//!
//! A [`Cycle`] is the machine with its actions over one period λ of its steady state
//! (2π, or 4π for a four-stroke engine), from the input position q0: the loads as a
//! function of q and the driver action (N·m on a revolute input) as a function of q.
//! With M*(q) the reduced moment of every action (driver included, gravity included) and
//! I*(q) the machine's reduced inertia (Zhukovski), a flywheel of constant inertia I on the
//! input gives, by the energy theorem,
//!
//! ```text
//! S(q) = ∫_{q0}^{q} M* dq = ½ (I + I*(q)) ω(q)² − ½ (I + I*(q0)) ω0²          (J)
//! ```
//!
//! - steady state needs a zero net work W = S(q0 + λ) ([`Cycle::check_periodic`],
//!   [`MechError::NotPeriodic`](crate::MechError::NotPeriodic));
//!   [`Cycle::balancing_torque`] is the constant torque T = −W/λ on the input that makes
//!   it zero, [`Cycle::balanced`] adds it to the driver;
//! - ω_a = (ω_max + ω_min)/2, ε = (ω_max − ω_min)/ω_a, so ω_max,min = ω_a (1 ± ε/2);
//! - approximate inertia (I ≫ I*): I = (S_max − S_min)/(ε ω_a²) ([`Cycle::approximate`]);
//! - exact inertia, Wittenbauer ([`Cycle::wittenbauer`]): with F(q) = 2 S(q)/ω_a² and
//!   z = (ω/ω_a)² = (F(q) + C)/(I + I*(q)), C = (I + I*(q0)) z0, the bound z ≤ (1 + ε/2)² =: a
//!   touches at the tangent point of slope a to the F–I* curve and z ≥ (1 − ε/2)² =: b at
//!   the tangent of slope b; both lines pass through P = (−I, −C), hence
//!   `I = (max_q (F − a I*) − min_q (F − b I*)) / (a − b)`, `C = a I − max_q (F − a I*)`;
//! - ω(q) for any flywheel ([`Cycle::steady_state`], [`Cycle::speed`]) and the check by
//!   time integration of the machine with the flywheel ([`Cycle::simulate`], with
//!   [`crate::dynamics::ode::Dop853`] and the event and dense output of [`crate::dynamics::ode::solve`]).
//!
//! Numerics: the cycle is cut into panels (at most λ/720 wide) whose ends include the
//! caller's breakpoints (where the loads are not smooth); S at the panel ends comes from
//! adaptive Gauss–Kronrod quadrature ([`crate::dynamics::gauss_kronrod`], relative
//! tolerance 1e-13; a panel that does not converge within its budget of intervals, M*
//! noisy there near a dead point, is an error), and S(q) inside a panel from the same
//! quadrature over the rest. The extremes over the cycle (tangent points, S_max, S_min,
//! ω_max, ω_min) are bracketed on the panel ends and located by golden-section search to
//! 1e-13 rad (on a plateau, only the panel ends that could beat the best found): the
//! flywheel inertias are accurate to about 1e-12 relative, not read off a drawing.
//!
//! The module's files, by aspect: `cycle` (the [`Cycle`], its table of S(q), the net work
//! and its balancing, [`CycleBuilder`]), `extremes` (samples and extremes over the cycle,
//! the fluctuation of energy), `wittenbauer` (the exact and the approximate flywheel),
//! `steady_state` (the periodic motion with a given flywheel, ω(q)) and `simulation`
//! (the check by time integration).

mod cycle;
mod extremes;
mod simulation;
mod steady_state;
mod wittenbauer;

pub use cycle::{Cycle, CycleBuilder, PANELS_PER_CYCLE, PERIODIC_TOLERANCE, QUADRATURE_RTOL};
pub use extremes::{CyclePoint, Extreme, Fluctuation};
pub use simulation::CycleSimulation;
pub use steady_state::{SpeedRange, SteadyState};
pub use wittenbauer::{Approximate, Flywheel, Tangent, Wittenbauer};
