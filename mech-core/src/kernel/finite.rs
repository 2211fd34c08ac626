//! The finiteness of every result: a solver never returns a non-finite number inside
//! `Ok`. The inputs may be finite and still too large for f64 with a given mechanism (a
//! speed of 1e200 rad/s squares to an infinity): the check names the quantity, the cause
//! and the fix. The accepted magnitudes of a drawing are checked before, by
//! `checks::magnitudes`.

use crate::kernel::constraints::Level;
use crate::kernel::link_state::V2;
use crate::MechError;

/// `Ok(())` when every value of `quantity` is finite ([`crate::error::all_finite`]); else
/// an error naming it: the inputs (speeds, loads, the driver) are too large for f64 with
/// this mechanism.
#[inline]
pub fn finite_result(quantity: &str, values: &[f64]) -> Result<(), MechError> {
    if crate::error::all_finite(values) {
        Ok(())
    } else {
        overflow(quantity, values)
    }
}

/// [`finite_result`] for the few numbers a solver returns last (I* and dI*/dq, M*, q̈):
/// each times zero (`zeroed`), summed, one compare, where [`finite_result`] takes a mask,
/// a compare and a branch per value (kept for long slices, whose sum would be a long
/// chain of additions).
#[inline(always)]
pub fn finite_few(quantity: &str, values: &[f64]) -> Result<(), MechError> {
    let sum = values
        .iter()
        .fold(crate::kernel::link_state::zero().x, |sum, &v| sum + v * 0.0);
    if sum == 0.0 {
        Ok(())
    } else {
        overflow(quantity, values)
    }
}

#[cold]
#[inline(never)]
fn overflow(quantity: &str, values: &[f64]) -> Result<(), MechError> {
    let v = values
        .iter()
        .find(|v| !v.is_finite())
        .copied()
        .unwrap_or(f64::NAN);
    Err(overflowed(&format!("{quantity} overflow ({v})")))
}

/// The overflow error: `what` (the quantity, and the value when it is known), then the
/// cause and the fix.
fn overflowed(what: &str) -> MechError {
    MechError::InvalidInput(format!("the {what}: the inputs, loads or driver are too large for f64 with this mechanism; reduce them"))
}

/// v·0 for both components of `v`: (±0, ±0) when `v` is finite, a NaN in each component
/// that is an infinity or a NaN. Summed, such zeros stay zero (exact: no overflow, no
/// false alarm) and a NaN stays a NaN, so one compare at the end tests every value: two
/// operations for two values (a multiplication and an addition in one vector register),
/// where a flag per value takes a mask and a compare each.
#[inline(always)]
fn zeroed(v: V2) -> V2 {
    v * 0.0
}

/// Whether the sum of [`zeroed`] terms is a zero: every value behind it was finite.
#[inline(always)]
fn still_zero(sum: V2) -> bool {
    sum.x + sum.y == 0.0
}

/// `Ok(())` when every moving link's state is finite up to the level `upto` solved
/// (position and rotation; velocities from [`Level::Velocity`]; accelerations at
/// [`Level::Acceleration`]); else an overflow error for the link motions. The ground
/// (link 0) never moves and is skipped. Each field times zero (`zeroed`), summed per
/// link (a tree two or three additions deep) and then over the links; the error path is
/// given no values, so that the states need not be written to memory for it.
#[inline(always)]
pub fn finite_states(
    states: &[crate::kernel::link_state::LinkState],
    upto: Level,
) -> Result<(), MechError> {
    let mut sum = crate::kernel::link_state::zero();
    for s in states.iter().skip(1) {
        let mut t = zeroed(s.pos) + zeroed(s.rot);
        if upto == Level::Acceleration {
            t += (zeroed(s.vel) + zeroed(s.acc)) + zeroed(V2::new(s.omega, s.alpha));
        } else if upto == Level::Velocity {
            t += zeroed(s.vel) + zeroed(V2::new(s.omega, 0.0));
        }
        sum += t;
    }
    if still_zero(sum) {
        Ok(())
    } else {
        Err(states_overflow())
    }
}

/// `Ok(())` when the motions a solver publishes beyond the link states are finite: the
/// velocity and acceleration of each point away from its link's anchor (`points`) and of
/// each moving link's cg (`links`). They derive from finite states but can still overflow
/// (a point far from its anchor at a huge speed: ω² r). Each times zero (`zeroed`),
/// summed, one compare; the error is `states_overflow`'s, given no values.
#[inline(always)]
pub fn finite_derived(
    points: &[&crate::kernel::link_state::PointMotion],
    links: &[&crate::kernel::link_state::LinkMotion],
) -> Result<(), MechError> {
    let mut sum = crate::kernel::link_state::zero();
    for p in points {
        sum += zeroed(p.vel) + zeroed(p.acc);
    }
    for l in links {
        sum += zeroed(l.cg_vel) + zeroed(l.cg_acc);
    }
    if still_zero(sum) {
        Ok(())
    } else {
        Err(states_overflow())
    }
}

/// The overflow error of link motions ([`finite_states`]'s), also that of the run-time
/// `kinematics`' check of the point and cg motions it publishes (derived from finite
/// states, a point far from its link's anchor at a huge speed, ω² r, can still overflow).
#[cold]
#[inline(never)]
pub fn states_overflow() -> MechError {
    overflowed("velocities or accelerations overflow")
}

/// `Ok(())` when every reaction (force, moment) and motor action is finite: each times
/// zero (`zeroed`), summed. The error path takes no values:
/// a non-inlined call given the reactions would make them live in memory on the common
/// path too, where the solve has them in registers.
#[inline(always)]
pub fn finite_reactions(
    reactions: &[crate::kernel::kinetostatics::Reaction],
    driver: &[f64],
) -> Result<(), MechError> {
    let mut sum = crate::kernel::link_state::zero();
    for r in reactions {
        sum += zeroed(r.force) + zeroed(V2::new(r.moment, 0.0));
    }
    for &d in driver {
        sum += zeroed(V2::new(d, 0.0));
    }
    if still_zero(sum) {
        Ok(())
    } else {
        Err(reactions_overflow())
    }
}

#[cold]
#[inline(never)]
fn reactions_overflow() -> MechError {
    overflowed("reactions or motor actions overflow")
}
