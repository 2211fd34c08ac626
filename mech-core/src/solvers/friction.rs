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

use crate::kernel::constraints::JointGeom;
use crate::kernel::kinetostatics::{PrismaticReaction, RevoluteReaction, SlotReaction, Wrench};
use crate::kernel::link_state::{cross, LinkState, V2};
use crate::model::JointKind;
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
pub fn revolute(
    extra: &mut [Wrench],
    g: &JointGeom,
    s: &[LinkState],
    fr: &JointFriction,
    force: V2,
) {
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
pub fn sliding(
    extra: &mut [Wrench],
    g: &JointGeom,
    s: &[LinkState],
    fr: &JointFriction,
    force: V2,
) {
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

/// The friction of every joint j (`friction[j]`, kind `kinds[j]`) into `extra`, from the
/// reactions of the previous iterate `prev`, flattened as [`Flattener`] writes them for
/// `dof` inputs: [`revolute`] for a revolute joint, [`sliding`] for a prismatic joint or a
/// pin in a slot.
#[inline]
pub fn add_joint_friction(
    extra: &mut [Wrench],
    joints: &[JointGeom],
    kinds: &[JointKind],
    s: &[LinkState],
    friction: &[JointFriction],
    dof: usize,
    prev: &[f64],
) {
    let mut at = dof;
    for (j, &kind) in kinds.iter().enumerate() {
        let force = V2::new(prev[at], prev[at + 1]);
        match kind {
            JointKind::Revolute => revolute(extra, &joints[j], s, &friction[j], force),
            JointKind::Prismatic | JointKind::PinInSlot => {
                sliding(extra, &joints[j], s, &friction[j], force)
            }
            // Tooth friction and rolling resistance are not modelled.
            JointKind::Gear | JointKind::Rack | JointKind::Rolling | JointKind::Cam => {}
        }
        at += flat_width(kind);
    }
}

/// How many values a joint of kind `kind` has in the flattened layout of [`iterate`]:
/// its force (fx, fy, N) and, for a prismatic joint, its moment (N·m).
pub const fn flat_width(kind: JointKind) -> usize {
    match kind {
        JointKind::Prismatic => 3,
        JointKind::Revolute
        | JointKind::PinInSlot
        | JointKind::Gear
        | JointKind::Rack
        | JointKind::Rolling
        | JointKind::Cam => 2,
    }
}

/// The length of the flattened layout of [`iterate`]: the `dof` motor actions first, then
/// per joint of `kinds`, in declaration order, its [`flat_width`] values.
pub const fn flat_len(dof: usize, kinds: &[JointKind]) -> usize {
    let mut n = dof;
    let mut j = 0;
    while j < kinds.len() {
        n += flat_width(kinds[j]);
        j += 1;
    }
    n
}

/// A joint reaction's values in the flattened layout of [`iterate`].
pub trait FlatReaction {
    /// The joint kind's [`flat_width`].
    const WIDTH: usize;
    /// The force (fx, fy, N) and, for a prismatic joint, the moment (N·m), into
    /// `out[..WIDTH]`.
    fn write(&self, out: &mut [f64]);
}

impl FlatReaction for RevoluteReaction {
    const WIDTH: usize = flat_width(JointKind::Revolute);
    #[inline]
    fn write(&self, out: &mut [f64]) {
        out[0] = self.force.x;
        out[1] = self.force.y;
    }
}

impl FlatReaction for PrismaticReaction {
    const WIDTH: usize = flat_width(JointKind::Prismatic);
    #[inline]
    fn write(&self, out: &mut [f64]) {
        out[0] = self.force.x;
        out[1] = self.force.y;
        out[2] = self.moment;
    }
}

impl FlatReaction for SlotReaction {
    const WIDTH: usize = flat_width(JointKind::PinInSlot);
    #[inline]
    fn write(&self, out: &mut [f64]) {
        out[0] = self.force.x;
        out[1] = self.force.y;
    }
}

impl FlatReaction for crate::kernel::kinetostatics::MeshReaction {
    const WIDTH: usize = flat_width(JointKind::Gear);
    #[inline]
    fn write(&self, out: &mut [f64]) {
        out[0] = self.force.x;
        out[1] = self.force.y;
    }
}

impl FlatReaction for crate::kernel::kinetostatics::RollingReaction {
    const WIDTH: usize = flat_width(JointKind::Rolling);
    #[inline]
    fn write(&self, out: &mut [f64]) {
        out[0] = self.force.x;
        out[1] = self.force.y;
    }
}

impl FlatReaction for crate::kernel::kinetostatics::CamReaction {
    const WIDTH: usize = flat_width(JointKind::Cam);
    #[inline]
    fn write(&self, out: &mut [f64]) {
        out[0] = self.force.x;
        out[1] = self.force.y;
    }
}

/// Writes the motor actions, then each joint's reaction in declaration order, into the
/// flattened layout of [`iterate`] (length [`flat_len`]).
pub struct Flattener<'a> {
    out: &'a mut [f64],
    at: usize,
}

impl<'a> Flattener<'a> {
    /// Start the layout in `out` with the motor actions `drivers`.
    #[inline]
    pub fn new(out: &'a mut [f64], drivers: &[f64]) -> Self {
        out[..drivers.len()].copy_from_slice(drivers);
        Flattener {
            out,
            at: drivers.len(),
        }
    }
    /// Append the next joint's reaction.
    #[inline]
    pub fn push<R: FlatReaction>(&mut self, r: &R) {
        r.write(&mut self.out[self.at..self.at + R::WIDTH]);
        self.at += R::WIDTH;
    }
}

/// Largest number of fixed-point iterations.
pub const MAX_ITERATIONS: usize = 200;

/// The fixed point of `step` (the flattened motor actions and reactions after one
/// kinetostatics with the friction of the previous ones), from the frictionless `first`:
/// converged when the largest change is below 1e-13 of the largest value;
/// `SelfLocking` when the changes stop shrinking (gain ≥ 1) or the values blow up.
pub fn iterate<V: AsRef<[f64]> + Clone>(
    first: V,
    mut step: impl FnMut(&V) -> Result<V, MechError>,
) -> Result<V, MechError> {
    let size = |v: &V| v.as_ref().iter().fold(0.0f64, |a, x| a.max(x.abs()));
    let mut prev = first.clone();
    let mut last_change = f64::INFINITY;
    let mut growing = 0;
    for _ in 0..MAX_ITERATIONS {
        let next = step(&prev)?;
        let change = next
            .as_ref()
            .iter()
            .zip(prev.as_ref())
            .fold(0.0f64, |a, (x, y)| a.max((x - y).abs()));
        let scale = size(&next).max(size(&first)).max(f64::MIN_POSITIVE);
        if !change.is_finite() || scale > 1e12 * size(&first).max(1.0) {
            break;
        }
        if change <= 1e-13 * scale {
            return Ok(next);
        }
        growing = if change >= last_change {
            growing + 1
        } else {
            0
        };
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_layout_is_read_where_it_is_written() {
        let kinds = [
            JointKind::Revolute,
            JointKind::Prismatic,
            JointKind::PinInSlot,
        ];
        assert_eq!(flat_len(2, &kinds), 2 + 2 + 3 + 2);
        let mut out = [0.0; flat_len(
            2,
            &[
                JointKind::Revolute,
                JointKind::Prismatic,
                JointKind::PinInSlot,
            ],
        )];
        let mut w = Flattener::new(&mut out, &[-1.0, -2.0]);
        w.push(&RevoluteReaction {
            force: V2::new(1.0, 2.0),
        });
        w.push(&PrismaticReaction {
            force: V2::new(3.0, 4.0),
            moment: 5.0,
        });
        w.push(&SlotReaction {
            force: V2::new(6.0, 7.0),
        });
        assert_eq!(out, [-1.0, -2.0, 1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0]);
    }
}
