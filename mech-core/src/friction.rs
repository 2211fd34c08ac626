//! Coulomb friction in the joints (`docs/theory.md` §8).
//!
//! - Revolute joint of pin radius r: a friction force μ|R| tangent to the pin, i.e. a
//!   moment μ r |R| (N·m) against the relative rotation ω_b − ω_a: on b it is
//!   −sgn(ω_b − ω_a) μ r |R|, on a the opposite.
//! - Prismatic joint and pin in a slot: a force μ|N| (N) along the axis, against the
//!   sliding velocity of b's point relative to a, applied at the joint point (on b; the
//!   opposite on a). For a prismatic joint N is the normal force of the reaction; the
//!   moment it also carries is not turned into friction (a block of negligible length).
//!
//! The friction depends on the reactions, which depend on the friction: the generated
//! `kinetostatics_with_friction` iterates kinetostatics to a fixed point ([`iterate`]).
//! When the friction feeds back on itself with a gain of one or more, there is no finite
//! solution: the mechanism is self-locking (`MechError::SelfLocking`).
//! A joint with no relative motion (ω_rel = 0, v_rel = 0) has indeterminate static
//! friction and gets none.

use crate::constraints::JointGeom;
use crate::link_state::{cross, LinkState, V2};
use crate::kinetostatics::Wrench;
use crate::MechError;

/// The Coulomb friction of one joint.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct JointFriction {
    /// Friction coefficient μ (dimensionless, ≥ 0).
    pub mu: f64,
    /// Pin radius r of a revolute joint (m); unused by sliding joints.
    pub pin_radius: f64,
}

/// Add the friction moment of a revolute joint with reaction `force` (N, by a on b).
#[inline]
pub fn revolute(extra: &mut [Wrench], g: &JointGeom, s: &[LinkState], fr: &JointFriction, force: V2) {
    let rel = s[g.b].omega - s[g.a].omega;
    if rel == 0.0 {
        return;
    }
    let m = -rel.signum() * fr.mu * fr.pin_radius * force.norm();
    extra[g.b].z += m;
    extra[g.a].z -= m;
}

/// Add the friction force of a sliding joint (prismatic or slot) with normal reaction
/// `force` (N, by a on b).
#[inline]
pub fn sliding(extra: &mut [Wrench], g: &JointGeom, s: &[LinkState], fr: &JointFriction, force: V2) {
    let (sa, sb) = (&s[g.a], &s[g.b]);
    let rb = sb.r(g.db);
    let p = sb.pos + rb;
    let ra = p - sa.pos; // a's material point under P
    let u = sa.r(g.axis);
    let v = (sb.vel_at(rb) - sa.vel_at(ra)).dot(&u);
    if v == 0.0 {
        return;
    }
    let f = u * (-v.signum() * fr.mu * force.norm());
    extra[g.b] += Wrench::new(f.x, f.y, cross(rb, f));
    extra[g.a] -= Wrench::new(f.x, f.y, cross(ra, f));
}

/// Largest number of fixed-point iterations.
pub const MAX_ITERATIONS: usize = 200;

/// The fixed point of `step` (the flattened motor actions and reactions after one
/// kinetostatics with the friction of the previous ones), from the frictionless `first`:
/// converged when the largest change is below 1e-13 of the largest value;
/// `SelfLocking` when the changes stop shrinking (gain ≥ 1) or the values blow up.
pub fn iterate<const K: usize>(
    first: [f64; K],
    mut step: impl FnMut(&[f64; K]) -> Result<[f64; K], MechError>,
) -> Result<[f64; K], MechError> {
    let size = |v: &[f64; K]| v.iter().fold(0.0f64, |a, x| a.max(x.abs()));
    let mut prev = first;
    let mut last_change = f64::INFINITY;
    let mut growing = 0;
    for _ in 0..MAX_ITERATIONS {
        let next = step(&prev)?;
        let change = next.iter().zip(&prev).fold(0.0f64, |a, (x, y)| a.max((x - y).abs()));
        let scale = size(&next).max(size(&first)).max(f64::MIN_POSITIVE);
        if !change.is_finite() || scale > 1e12 * size(&first).max(1.0) {
            break;
        }
        if change <= 1e-13 * scale {
            return Ok(next);
        }
        growing = if change >= last_change { growing + 1 } else { 0 };
        if growing >= 5 {
            break;
        }
        last_change = change;
        prev = next;
    }
    Err(MechError::SelfLocking(
        "the friction in the joints feeds back on itself with a gain of one or more: no finite motor action moves the mechanism in this configuration".into(),
    ))
}
