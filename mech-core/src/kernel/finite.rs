//! The finiteness of every result: a solver never returns a non-finite number inside
//! `Ok`. The inputs may be finite and still too large for f64 with a given mechanism (a
//! speed of 1e200 rad/s squares to an infinity): the check names the quantity, the cause
//! and the fix. The accepted magnitudes of a drawing are checked before, by
//! `checks::magnitudes`.

use crate::kernel::constraints::Level;
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

/// `Ok(())` when every moving link's state is finite up to the level `upto` solved
/// (position and rotation; velocities from [`Level::Velocity`]; accelerations at
/// [`Level::Acceleration`]); else an overflow error for the link motions. The ground
/// (link 0) never moves and is skipped. [`crate::error::non_finite`] over the fields,
/// joined by OR (a tree a few operations deep); the error path is given no values, so
/// that the states need not be written to memory for it.
#[inline(always)]
pub fn finite_states(
    states: &[crate::kernel::link_state::LinkState],
    upto: Level,
) -> Result<(), MechError> {
    use crate::error::non_finite as bad;
    let mut any = false;
    for s in states.iter().skip(1) {
        any |= bad(s.pos.x) | bad(s.pos.y) | bad(s.rot.x) | bad(s.rot.y);
        if upto == Level::Velocity || upto == Level::Acceleration {
            any |= bad(s.vel.x) | bad(s.vel.y) | bad(s.omega);
        }
        if upto == Level::Acceleration {
            any |= bad(s.acc.x) | bad(s.acc.y) | bad(s.alpha);
        }
    }
    if any {
        Err(states_overflow())
    } else {
        Ok(())
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

/// `Ok(())` when every reaction (force, moment) and motor action is finite:
/// [`crate::error::non_finite`] over them, joined by OR. The error path takes no values:
/// a non-inlined call given the reactions would make them live in memory on the common
/// path too, where the solve has them in registers.
#[inline(always)]
pub fn finite_reactions(
    reactions: &[crate::kernel::kinetostatics::Reaction],
    driver: &[f64],
) -> Result<(), MechError> {
    use crate::error::non_finite as bad;
    let mut any = false;
    for r in reactions {
        any |= bad(r.force.x) | bad(r.force.y) | bad(r.moment);
    }
    for &d in driver {
        any |= bad(d);
    }
    if !any {
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
