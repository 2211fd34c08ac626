//! The motor actions by the principle of virtual power (seed, section 2.f), computing no
//! reaction: for each input k, the velocity field that moves input k alone at unit rate,
//! and Q_k = −Σ (F·v + M·ω) over the applied, gravity and inertia wrenches (N·m for a
//! revolute input, N for a prismatic one).

use crate::kernel::kinetostatics::{virtual_power, Wrench};
use crate::kernel::link_state::{LinkGeom, LinkMotion, LinkState, PointMotion, V2};
use crate::MechError;

/// The G motor actions Q_k = −Σ (F·v_k + M·ω_k) (N·m or N) of the wrenches `f` (N, N·m
/// about each link's anchor) in the virtual velocity fields v_k of the mechanism at the
/// states `s`, whose input rates are `qd`.
///
/// With one input (G = 1) moving at q̇ ≠ 0 the motion's own velocities are q̇ times the
/// virtual field, so Q = −Σ (F·v + M·ω) / q̇ with no velocity solve. Otherwise
/// `field(e_k)` gives the velocity field with input rates e_k (1 for input k, 0 for the
/// others) at the same positions, one call per input.
#[inline(always)]
pub fn driver_actions<const G: usize, V: AsRef<[LinkState]>>(
    f: &[Wrench],
    s: &[LinkState],
    qd: &[f64; G],
    mut field: impl FnMut(&[f64; G]) -> Result<V, MechError>,
) -> Result<[f64; G], MechError> {
    let mut out = [0.0; G];
    if G == 1 && qd[0] != 0.0 {
        out[0] = -virtual_power(f, s) / qd[0];
    } else {
        for (k, o) in out.iter_mut().enumerate() {
            let mut unit = [0.0; G];
            unit[k] = 1.0;
            let v = field(&unit)?;
            *o = -virtual_power(f, v.as_ref());
        }
    }
    crate::kernel::finite::finite_few("motor actions", &out)?;
    Ok(out)
}

/// The power balance of a one-input machine over its own motion, for its motor action by
/// virtual power when q̇ ≠ 0 (the motion's velocities are then a virtual velocity field):
/// Q q̇ + P − dT/dt = 0, Q = (dT/dt − P)/q̇, with dT/dt = Σ (m v_G·a_G + I ω α)
/// ([`crate::kernel::energy::kinetic_rate`]) and P the power of the loads and gravity, W. Summed
/// from the link and point motions the kinematics already gives: no wrench is formed.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Power {
    /// dT/dt so far, W.
    pub kinetic_rate: f64,
    /// P so far, W.
    pub applied: f64,
}

impl Power {
    /// Empty sums, started at −0 (the identity of IEEE addition: the first term is taken as
    /// it is, and the compiler drops the addition).
    #[inline(always)]
    pub fn new() -> Self {
        Power {
            kinetic_rate: -0.0,
            applied: -0.0,
        }
    }
    /// Add a link's dT/dt.
    #[inline(always)]
    pub fn inertia(&mut self, l: &LinkGeom, m: &LinkMotion) {
        self.kinetic_rate += crate::kernel::energy::kinetic_rate(l, m);
    }
    /// Add the power of gravity on a link, m g·v_G.
    #[inline(always)]
    pub fn gravity(&mut self, l: &LinkGeom, m: &LinkMotion, g: V2) {
        self.applied += l.mass * g.dot(&m.cg_vel);
    }
    /// Add the power of a force `f` (N) at a point moving with `p`, f·v_P.
    #[inline(always)]
    pub fn force(&mut self, p: &PointMotion, f: V2) {
        self.applied += f.dot(&p.vel);
    }
    /// Add the power of a torque `t` (N·m) on a link, t ω.
    #[inline(always)]
    pub fn torque(&mut self, m: &LinkMotion, t: f64) {
        self.applied += t * m.omega;
    }
    /// Add the power of the force elements in the motion `s`, −Σ T ẋ
    /// ([`crate::elements::springs::power`]).
    #[inline(always)]
    pub fn elements(&mut self, e: &[crate::elements::springs::ElementGeom], s: &[LinkState]) {
        self.applied += crate::elements::springs::power(e, s);
    }
    /// The motor action Q = (dT/dt − P)/q̇ (N·m, or N for a prismatic input); q̇ ≠ 0.
    #[inline(always)]
    pub fn driver(&self, qd: f64) -> Result<f64, MechError> {
        let q = (self.kinetic_rate - self.applied) / qd;
        crate::kernel::finite::finite_few("motor actions", &[q])?;
        Ok(q)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::kernel::link_state::V2;

    fn moving(omega: f64) -> LinkState {
        let mut s = LinkState::at(V2::zeros());
        s.omega = omega;
        s.vel = V2::new(2.0 * omega, 0.0);
        s
    }

    #[test]
    fn one_moving_input_uses_the_motion_itself() {
        let f = [Wrench::new(0.0, 0.0, 0.0), Wrench::new(3.0, 1.0, -2.0)];
        let s = [LinkState::default(), moving(5.0)];
        let q = driver_actions(&f, &s, &[5.0], |_| -> Result<[LinkState; 2], MechError> {
            panic!("no field needed")
        });
        assert_eq!(q, Ok([-(3.0 * 2.0 - 2.0)]));
    }

    #[test]
    fn at_rest_one_field_per_input() {
        let f = [Wrench::new(0.0, 0.0, 0.0), Wrench::new(3.0, 1.0, -2.0)];
        let s = [LinkState::default(), moving(0.0)];
        let mut calls = 0;
        let q = driver_actions(&f, &s, &[0.0, 0.0], |e| {
            calls += 1;
            Ok([LinkState::default(), moving(e[0] + 2.0 * e[1])])
        });
        assert_eq!(q, Ok([-4.0, -8.0]));
        assert_eq!(calls, 2);
    }
}
