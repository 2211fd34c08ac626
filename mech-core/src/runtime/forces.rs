//! The forces of a run-time [`Mechanism`]: the applied and inertia wrenches, d'Alembert
//! group by group (`kinetostatics`), friction, virtual power (`driver_action`), and
//! Zhukovski's reduction, each walking the plan with the same kernels as the generated code.

use crate::kernel::constraints::{Drive, Level};
use crate::kernel::kinetostatics::{
    add_force, add_gravity, add_inertia, add_torque, PrismaticReaction, Reaction, RevoluteReaction,
    Wrench,
};
use crate::kernel::link_state::{point_motion, LinkState, V2};
use crate::model::JointKind;
use crate::solvers::friction::{add_joint_friction, flat_len, iterate, Flattener, JointFriction};
use crate::solvers::zhukovski::ZhukovskiSums;
use crate::MechError;
use smallvec::{smallvec, SmallVec};
use std::sync::Arc;

use super::mechanism::Mechanism;
use super::mechanism::Scratch;
use super::results::*;

impl Mechanism {
    /// The applied wrenches (loads, gravity) and, when `inertia`, d'Alembert's inertia
    /// wrenches, per link, with the terms each link's declaration gives it.
    pub(super) fn wrenches(
        &self,
        s: &[LinkState],
        loads: &Loads,
        inertia: bool,
        f: &mut Scratch<Wrench>,
    ) -> Result<(), MechError> {
        f.clear();
        f.resize(s.len(), Wrench::zeros());
        for (l, t) in self.terms.iter().enumerate().skip(1) {
            if t.gravity() {
                add_gravity(&mut f[l], &s[l], &self.inst.links[l], self.inst.gravity);
            }
            if inertia && t.inertia() {
                add_inertia(&mut f[l], &s[l], &self.inst.links[l]);
            }
        }
        for (k, (load, value)) in self.model.loads.iter().zip(&loads.values).enumerate() {
            let link = load.link();
            match *value {
                LoadValue::Force(v) => {
                    crate::error::check_finite("loads", &[v.x, v.y])?;
                    add_force(&mut f[link], &s[link], self.inst.loads[k], v)
                }
                LoadValue::Torque(t) => {
                    crate::error::check_finite("loads", &[t])?;
                    add_torque(&mut f[link], t)
                }
            }
        }
        crate::elements::springs::add_wrenches(&self.inst.elements, s, f);
        Ok(())
    }

    /// d'Alembert: the motor action of every input and the reaction at every joint, group
    /// by group from the outermost Assur group inward. `extra` adds wrenches per link
    /// (friction).
    pub fn kinetostatics_with(
        &self,
        m: &Motion,
        loads: &Loads,
        extra: Option<&[Wrench]>,
    ) -> Result<Forces, MechError> {
        let mut out = Forces {
            driver: Vec::new(),
            joints: Vec::new(),
            model: self.model.clone(),
        };
        self.kinetostatics_into(m, loads, extra, &mut out)?;
        Ok(out)
    }

    /// [`Mechanism::kinetostatics_with`] into `out`, reusing its buffers: no allocation
    /// once they have grown, for mechanisms of up to 8 links and joints.
    pub fn kinetostatics_into(
        &self,
        m: &Motion,
        loads: &Loads,
        extra: Option<&[Wrench]>,
        out: &mut Forces,
    ) -> Result<(), MechError> {
        if self.redundant() {
            return Err(MechError::Redundant(
                "this mechanism has redundant constraints (`#[allow(redundant)]`): its reactions are statically indeterminate; the motor actions are still determined: call `driver_action` (virtual power)".into(),
            ));
        }
        let s = &m.states;
        let mut f = Scratch::new();
        self.wrenches(s, loads, true, &mut f)?;
        if let Some(extra) = extra {
            for (fi, e) in f.iter_mut().zip(extra) {
                *fi += e;
            }
        }
        let (joints, _scale) = (&self.inst.joints[..], self.inst.scale);
        let mut r: Scratch<Reaction> = smallvec![Reaction::default(); joints.len()];
        out.driver.clear();
        out.driver.resize(self.dof(), 0.0);
        for g in self.plan.iter().rev() {
            self.group_reactions(g, s, &mut f, &mut r, &mut out.driver)?;
        }
        crate::kernel::finite::finite_reactions(&r, &out.driver)
            .map_err(|e| self.inst.blame_elements(&self.model, s, e))?;
        out.joints.clear();
        out.joints
            .extend(self.model.joints.iter().zip(r).map(|(j, r)| JointReaction {
                force: r.force,
                moment: (j.kind == JointKind::Prismatic).then_some(r.moment),
            }));
        if !Arc::ptr_eq(&out.model, &self.model) {
            out.model = self.model.clone();
        }
        Ok(())
    }

    /// d'Alembert (see [`Mechanism::kinetostatics_with`]).
    pub fn kinetostatics(&self, m: &Motion, loads: &Loads) -> Result<Forces, MechError> {
        self.kinetostatics_with(m, loads, None)
    }

    /// Kinetostatics with Coulomb friction in the joints (`friction[j]` for joint j in
    /// declaration order, `mech::friction`): d'Alembert iterated to a fixed point, the
    /// friction from the reactions of the previous iterate; `SelfLocking` when no finite
    /// motor action moves the mechanism. The same iteration as the generated struct's.
    pub fn kinetostatics_with_friction(
        &self,
        m: &Motion,
        loads: &Loads,
        friction: &[JointFriction],
    ) -> Result<Forces, MechError> {
        let n = self.model.joints.len();
        if friction.len() != n {
            return Err(MechError::InvalidInput(format!(
                "expected the friction of {n} joints, got {}",
                friction.len()
            )));
        }
        for (j, f) in self.model.joints.iter().zip(friction) {
            if !(f.mu >= 0.0 && f.mu.is_finite() && f.pin_radius >= 0.0 && f.pin_radius.is_finite())
            {
                return Err(MechError::InvalidInput(format!(
                    "the friction of joint `{}` is μ = {}, pin radius {} m: both must be finite and ≥ 0",
                    j.name, f.mu, f.pin_radius
                )));
            }
        }
        let kinds: Vec<JointKind> = self.model.joints.iter().map(|j| j.kind).collect();
        let len = flat_len(self.dof(), &kinds);
        let flat = |f: &Forces| {
            let mut out = vec![0.0; len];
            let mut w = Flattener::new(&mut out, &f.driver);
            for (r, k) in f.joints.iter().zip(&kinds) {
                match k {
                    JointKind::Prismatic => w.push(&PrismaticReaction {
                        force: r.force,
                        moment: r.moment.unwrap_or(0.0),
                    }),
                    _ => w.push(&RevoluteReaction { force: r.force }),
                }
            }
            out
        };
        let mut last = None;
        iterate(flat(&self.kinetostatics(m, loads)?), |prev| {
            let mut extra = vec![Wrench::zeros(); self.model.links.len()];
            add_joint_friction(
                &mut extra,
                &self.inst.joints,
                &kinds,
                &m.states,
                friction,
                self.dof(),
                prev,
            );
            let f = self.kinetostatics_with(m, loads, Some(&extra))?;
            let out = flat(&f);
            last = Some(f);
            Ok(out)
        })?;
        match last {
            Some(f) => Ok(f),
            None => self.kinetostatics(m, loads),
        }
    }

    /// The motor actions by virtual power, no reaction: Q_k = −Σ (F·v + M ω) over loads,
    /// gravity and inertia in the velocity field moving input k alone at unit rate.
    pub fn driver_action(&self, m: &Motion, loads: &Loads) -> Result<Vec<f64>, MechError> {
        let s = &m.states;
        if self.dof() == 1 && m.qd()[0] != 0.0 {
            let d = self.power(m, loads)?.driver(m.qd()[0]);
            return Ok(vec![
                d.map_err(|e| self.inst.blame_elements(&self.model, s, e))?
            ]);
        }
        let mut f = Scratch::new();
        self.wrenches(s, loads, true, &mut f)?;
        let g = self.dof();
        let (_joints, _scale) = (&self.inst.joints[..], self.inst.scale);
        let mut out = vec![0.0; g];
        for (k, o) in out.iter_mut().enumerate() {
            let mut v: Scratch<LinkState> = SmallVec::from_slice(s);
            for st in v.iter_mut() {
                st.vel = V2::zeros();
                st.omega = 0.0;
            }
            let mut qd: Scratch<f64> = smallvec![0.0; g];
            qd[k] = 1.0;
            let zero: Scratch<f64> = smallvec![0.0; g];
            let drive: Drive = (&zero, &qd, &zero);
            for grp in &self.plan {
                self.group_unit_rates(grp, drive, &mut v)?;
            }
            *o = -crate::kernel::kinetostatics::virtual_power(&f, &v);
        }
        crate::kernel::finite::finite_result("motor actions", &out)
            .map_err(|e| self.inst.blame_elements(&self.model, s, e))?;
        Ok(out)
    }

    /// Zhukovski's sums over the motion with q̇ = 1, q̈ = 0 (one input); `qd` is the
    /// input rate the dampers' part of M* is taken at.
    pub(super) fn zhukovski_sums(
        &self,
        q: f64,
        qd: f64,
        loads: Option<&Loads>,
        upto: Level,
    ) -> Result<ZhukovskiSums, MechError> {
        if self.dof() != 1 {
            return Err(MechError::InvalidInput(format!(
                "Zhukovski's reduction needs one input, the mechanism has {}",
                self.dof()
            )));
        }
        let mut s: Scratch<LinkState> = SmallVec::from_slice(&self.inst.drawing);
        self.solve_slice(&[q], &[1.0], &[0.0], upto, &mut s)?;
        self.sums(&s, loads, qd, upto == Level::Acceleration)
    }

    /// The power balance over the motion `m` (its link and point motions).
    pub(super) fn power(
        &self,
        m: &Motion,
        loads: &Loads,
    ) -> Result<crate::solvers::virtual_power::Power, MechError> {
        let mut w = crate::solvers::virtual_power::Power::default();
        for (l, t) in self.terms.iter().enumerate().skip(1) {
            let (geom, lm) = (&self.inst.links[l], &m.links[l]);
            if t.inertia() {
                w.inertia(geom, lm);
            }
            if t.gravity() {
                w.gravity(geom, lm, self.inst.gravity);
            }
        }
        for (k, (load, value)) in self.model.loads.iter().zip(&loads.values).enumerate() {
            let link = load.link();
            match *value {
                LoadValue::Force(v) => {
                    crate::error::check_finite("loads", &[v.x, v.y])?;
                    w.force(&point_motion(&m.states, link, self.inst.loads[k]), v)
                }
                LoadValue::Torque(t) => {
                    crate::error::check_finite("loads", &[t])?;
                    w.torque(&m.links[link], t)
                }
            }
        }
        w.elements(&self.inst.elements, &m.states);
        Ok(w)
    }

    /// Zhukovski's sums over the states `s`: the inertia terms when `inertia`, the power
    /// of gravity, of `loads` and of the force elements (at the input rate `qd`) when
    /// `loads` are given.
    pub(super) fn sums(
        &self,
        s: &[LinkState],
        loads: Option<&Loads>,
        qd: f64,
        inertia: bool,
    ) -> Result<ZhukovskiSums, MechError> {
        let mut z = ZhukovskiSums::new();
        for (l, t) in self.terms.iter().enumerate().skip(1) {
            let geom = &self.inst.links[l];
            if inertia && t.inertia() {
                if self.pinned[l] {
                    z.inertia_about_anchor(geom, &s[l]);
                } else if self.translates[l] {
                    z.inertia_translating(geom, &s[l]);
                } else {
                    z.inertia(geom, &s[l]);
                }
            }
            if loads.is_some() && t.gravity() {
                if self.translates[l] {
                    z.gravity_translating(geom, &s[l], self.inst.gravity);
                } else {
                    z.gravity(geom, &s[l], self.inst.gravity);
                }
            }
        }
        if let Some(loads) = loads {
            for (k, (load, value)) in self.model.loads.iter().zip(&loads.values).enumerate() {
                let link = load.link();
                match *value {
                    LoadValue::Force(v) => {
                        crate::error::check_finite("loads", &[v.x, v.y])?;
                        z.force(&s[link], self.inst.loads[k], v)
                    }
                    LoadValue::Torque(t) => {
                        crate::error::check_finite("loads", &[t])?;
                        z.torque(&s[link], t)
                    }
                }
            }
            z.elements(&self.inst.elements, s, qd);
        }
        crate::kernel::finite::finite_result(
            "reduced inertia and moment",
            &[z.reduced.inertia, z.reduced.inertia_derivative, z.moment],
        )
        .map_err(|e| self.inst.blame_elements(&self.model, s, e))?;
        Ok(z)
    }
}
