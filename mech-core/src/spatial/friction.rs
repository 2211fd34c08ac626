//! Coulomb friction in the spatial joints: the laws of the planar joints (`docs/theory.md`
//! §8) in three dimensions, each joint given a coefficient μ and a radius r
//! ([`JointFriction`]).
//!
//! With the reaction (F, M at the joint's point P, by a on b), the relative angular velocity
//! ω_r = ω_b − ω_a and the sliding velocity v_r of b's point at P past a's, u the joint's
//! axis at present (fixed in a), the friction on b (the opposite on a) is:
//! - revolute: a moment −sgn(ω_r·u) μ r |F_⊥| u, F_⊥ = F − (F·u) u the radial load (the
//!   thrust and the tilting moments are left to the bearing's faces: no friction);
//! - spherical: a moment −μ r |F| ω_r / |ω_r|;
//! - universal: on each pin of the cross (u fixed in a, w fixed in b, ω_r = α u + β w), a
//!   moment −μ r |F| (sgn α u + sgn β w);
//! - prismatic: a force −sgn(v_r·u) μ |F_⊥| u at P (the moment the guide carries is not
//!   turned into friction: a short block);
//! - cylindrical: the prismatic force and the revolute moment, both from |F_⊥|;
//! - helical: none (thread friction is not modelled).
//!
//! A joint with no relative motion gets none (static friction is indeterminate). The
//! reactions depend on the friction: `kinetostatics` with friction iterates Newton–Euler on
//! the rows' multipliers from the frictionless ones (`crate::solvers::friction::iterate`,
//! `SelfLocking` when the friction feeds back with a gain of one or more); J is factored
//! once, every iterate is one more pair of triangular solves.

use super::constraints::{BodyState, Kind};
use super::kinematics::Layout;
use super::kinetostatics::Reaction;
use crate::solvers::friction::JointFriction;
use crate::MechError;
use nalgebra::Vector3;

type V3 = Vector3<f64>;

/// `InvalidInput` unless there is one friction per joint, each μ and r finite and ≥ 0.
pub(crate) fn check(layout: &Layout, friction: &[JointFriction]) -> Result<(), MechError> {
    let joints = &layout.model.joints;
    if friction.len() != joints.len() {
        return Err(MechError::InvalidInput(format!(
            "expected the friction of {} joints, got {}",
            joints.len(),
            friction.len()
        )));
    }
    for (j, f) in joints.iter().zip(friction) {
        if !(f.mu >= 0.0 && f.mu.is_finite() && f.pin_radius >= 0.0 && f.pin_radius.is_finite()) {
            return Err(MechError::InvalidInput(format!(
                "the friction of joint `{}` is μ = {}, radius {} m: both must be finite and ≥ 0",
                j.name, f.mu, f.pin_radius
            )));
        }
    }
    Ok(())
}

/// The friction of joint `k` on its second body (force at P, moment), N and N·m, under
/// the reaction `r`, the bodies moving as `s` (module docs).
fn on_b(layout: &Layout, s: &[BodyState], k: usize, r: &Reaction, fr: &JointFriction) -> (V3, V3) {
    let g = &layout.joints[k];
    let (a, b) = (&s[g.a], &s[g.b]);
    let u = a.rot * g.axes[0];
    let wr = b.w - a.w;
    let sign = |x: f64| if x == 0.0 { 0.0 } else { x.signum() };
    let radial = (r.force - u * r.force.dot(&u)).norm();
    let turning = |load: f64| u * (-sign(wr.dot(&u)) * fr.mu * fr.pin_radius * load);
    let sliding = || {
        let rb = b.rot * g.sb;
        let p = b.o + rb;
        let vr = b.v + b.w.cross(&rb) - a.v - a.w.cross(&(p - a.o));
        u * (-sign(vr.dot(&u)) * fr.mu * radial)
    };
    match g.kind {
        Kind::Revolute => (V3::zeros(), turning(radial)),
        Kind::Spherical => {
            let n = wr.norm();
            let m = if n > 0.0 {
                wr * (-fr.mu * fr.pin_radius * r.force.norm() / n)
            } else {
                V3::zeros()
            };
            (V3::zeros(), m)
        }
        Kind::Universal => {
            // ω_r = α u + β w: the normal equations of the two pins' axes
            let w = b.rot * g.axes[1];
            let (uw, ru, rw) = (u.dot(&w), wr.dot(&u), wr.dot(&w));
            let det = 1.0 - uw * uw;
            if !(det > 1e-12) {
                return (V3::zeros(), V3::zeros());
            }
            let (al, be) = ((ru - uw * rw) / det, (rw - uw * ru) / det);
            let load = fr.mu * fr.pin_radius * r.force.norm();
            (V3::zeros(), (u * sign(al) + w * sign(be)) * -load)
        }
        Kind::Prismatic => (sliding(), V3::zeros()),
        Kind::Cylindrical => (sliding(), turning(radial)),
        Kind::Helical => (V3::zeros(), V3::zeros()),
    }
}

/// Every joint's friction as applied wrenches about the bodies' reference points, added to
/// `out` (6(N − 1) values, body i's (force, moment) at 6(i − 1)), the reactions given by
/// `reaction(k)`.
pub(crate) fn add_wrenches(
    layout: &Layout,
    s: &[BodyState],
    friction: &[JointFriction],
    reaction: impl Fn(usize) -> Reaction,
    out: &mut [f64],
) {
    let mut add = |body: usize, f: V3, m: V3| {
        if body > 0 {
            for c in 0..3 {
                out[6 * (body - 1) + c] += f[c];
                out[6 * (body - 1) + 3 + c] += m[c];
            }
        }
    };
    for (k, (g, fr)) in layout.joints.iter().zip(friction).enumerate() {
        if fr.mu == 0.0 {
            continue;
        }
        let (f, m) = on_b(layout, s, k, &reaction(k), fr);
        let p = s[g.b].o + s[g.b].rot * g.sb;
        add(g.b, f, m + (p - s[g.b].o).cross(&f));
        add(g.a, -f, -m - (p - s[g.a].o).cross(&f));
    }
}
