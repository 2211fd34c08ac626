//! The forces of a run-time [`Mechanism`]: the applied and inertia wrenches, d'Alembert
//! group by group (`kinetostatics`), friction, virtual power (`driver_action`), and
//! Zhukovski's reduction, each walking the plan with the same kernels as the generated code.

use crate::error::non_finite;
use crate::kernel::constraints::{Drive, Level};
use crate::kernel::kinematics::DyadSystem;
use crate::kernel::kinetostatics::{
    add_force, add_force_at, add_gravity_of, add_inertia_of, add_torque, PrismaticReaction,
    Reaction, RevoluteReaction, Wrench,
};
use crate::kernel::link_state::{point_motion, LinkState, V2};
use crate::model::{JointKind, Load};
use crate::solvers::friction::{add_joint_friction, flat_len, iterate, Flattener, JointFriction};
use crate::solvers::zhukovski::ZhukovskiSums;
use crate::solvers::zhukovski_series::{Series, Term};
use crate::MechError;
use smallvec::{smallvec, SmallVec};
use std::sync::Arc;

use super::dispatch::{ACCELERATION, VELOCITY};
use super::mechanism::Mechanism;
use super::mechanism::{LoadShare, Scratch, Share};
use super::results::*;

impl Mechanism {
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
        if self.redundant {
            return Err(MechError::Redundant(
                "this mechanism has redundant constraints (`#[allow(redundant)]`): its reactions are statically indeterminate; the motor actions are still determined: call `driver_action` (virtual power)".into(),
            ));
        }
        self.check_motion(m)?;
        let s = &m.states;
        // Per-call buffers on the stack up to 8 links and joints (a `Vec` beyond).
        let (n, nj) = (s.len(), self.inst.joints.len());
        let (mut f_stack, mut f_heap) = ([Wrench::zeros(); 8], Vec::new());
        let f = stack_or_heap(&mut f_stack, &mut f_heap, n, Wrench::zeros());
        self.wrenches_of(m, loads, f)?;
        if let Some(extra) = extra {
            for (fi, e) in f.iter_mut().zip(extra) {
                *fi += e;
            }
        }
        let (mut r_stack, mut r_heap) = ([Reaction::default(); 8], Vec::new());
        let r = stack_or_heap(&mut r_stack, &mut r_heap, nj, Reaction::default());
        super::dispatch::fit(&mut out.driver, self.dof(), 0.0);
        out.driver.fill(0.0);
        // The dyads' systems kept by the kinematics of this mechanism (a motion of another
        // has its systems rebuilt).
        let kept = Arc::ptr_eq(&m.model, &self.model) && m.systems.len() == self.plan.len();
        for (i, g) in self.plan.iter().enumerate().rev() {
            let k = if kept {
                &m.systems[i]
            } else {
                &DyadSystem::None
            };
            self.group_reactions_kept(g, k, s, f, r, &mut out.driver)?;
        }
        crate::kernel::finite::finite_reactions(r, &out.driver)
            .map_err(|e| self.inst.blame_elements(&self.model, s, e))?;
        super::dispatch::fit(&mut out.joints, nj, JointReaction::default());
        for ((o, r), &prismatic) in out.joints.iter_mut().zip(&*r).zip(&self.program.prismatic) {
            *o = JointReaction {
                force: r.force,
                moment: prismatic.then_some(r.moment),
            };
        }
        if !Arc::ptr_eq(&out.model, &self.model) {
            out.model = self.model.clone();
        }
        Ok(())
    }

    /// `InvalidInput` unless the motion `m` has this mechanism's sizes (its links, points
    /// and states): a motion of another mechanism.
    #[inline]
    pub(super) fn check_motion(&self, m: &Motion) -> Result<(), MechError> {
        let (n, np) = (self.inst.links.len(), self.inst.points.len());
        if m.states.len() == n && m.links.len() == n && m.points.len() == np {
            Ok(())
        } else {
            Err(MechError::InvalidInput(format!(
                "the motion has {} links and {} points, this mechanism {n} and {np}: a motion of another mechanism",
                m.links.len(),
                m.points.len()
            )))
        }
    }

    /// `InvalidInput` naming the first load that is not finite, as [`Mechanism::wrenches`]
    /// checks them: every value looked at, one test.
    #[inline]
    pub(super) fn check_loads(&self, loads: &Loads) -> Result<(), MechError> {
        let mut bad = false;
        for v in &loads.values {
            bad |= match *v {
                LoadValue::Force(v) => non_finite(v.x) | non_finite(v.y),
                LoadValue::Torque(t) => non_finite(t),
            };
        }
        if bad {
            return Err(self.bad_loads(loads));
        }
        Ok(())
    }

    #[cold]
    #[inline(never)]
    fn bad_loads(&self, loads: &Loads) -> MechError {
        for v in &loads.values {
            let r = match *v {
                LoadValue::Force(v) => crate::error::check_finite("loads", &[v.x, v.y]),
                LoadValue::Torque(t) => crate::error::check_finite("loads", &[t]),
            };
            if let Err(e) = r {
                return e;
            }
        }
        MechError::InvalidInput("loads must be finite".into())
    }

    /// The applied wrenches (gravity, loads, force elements) and d'Alembert's inertia
    /// wrenches per link about its anchor, from the motion's published cg, cg acceleration
    /// and load points, in the generated `__wrenches`' order, added to `f` (one per link,
    /// zero).
    #[inline]
    pub(super) fn wrenches_of(
        &self,
        m: &Motion,
        loads: &Loads,
        f: &mut [Wrench],
    ) -> Result<(), MechError> {
        self.check_loads(loads)?;
        let s = &m.states;
        let links = &self.inst.links;
        for &(l, _) in &self.program.weighed {
            add_gravity_of(
                &mut f[l],
                s[l].pos,
                &m.links[l],
                &links[l],
                self.inst.gravity,
            );
        }
        for (load, value) in self.model.loads.iter().zip(&loads.values) {
            match (load, *value) {
                (&Load::Force { link, point, .. }, LoadValue::Force(v)) => {
                    add_force_at(&mut f[link], s[link].pos, m.points[point].pos, v)
                }
                (&Load::Torque { link, .. }, LoadValue::Torque(t)) => add_torque(&mut f[link], t),
                // A value of the other kind (set by hand): as `wrenches`.
                (load, LoadValue::Force(v)) => {
                    add_force(&mut f[load.link()], &s[load.link()], V2::zeros(), v)
                }
                (load, LoadValue::Torque(t)) => add_torque(&mut f[load.link()], t),
            }
        }
        if !self.inst.elements.is_empty() {
            crate::elements::springs::add_wrenches(&self.inst.elements, s, f);
        }
        for &(l, _) in &self.program.inertial {
            add_inertia_of(&mut f[l], s[l].pos, &m.links[l], &links[l]);
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
        let mut out = vec![0.0; self.dof()];
        self.driver_action_into(m, loads, &mut out)?;
        Ok(out)
    }

    /// [`Mechanism::driver_action`] into `out` (one value per input): no allocation, for
    /// mechanisms of up to 8 links and inputs. One input moving (q̇ ≠ 0): the power balance
    /// over the motion itself, as the generated code.
    pub(super) fn driver_action_into(
        &self,
        m: &Motion,
        loads: &Loads,
        out: &mut [f64],
    ) -> Result<(), MechError> {
        self.check_motion(m)?;
        let g = self.dof();
        if out.len() != g {
            return Err(MechError::InvalidInput(format!(
                "expected {g} driver slots, got {}",
                out.len()
            )));
        }
        let s = &m.states;
        if g == 1 && m.qd()[0] != 0.0 {
            let d = self.power(m, loads)?.driver(m.qd()[0]);
            out[0] = d.map_err(|e| self.inst.blame_elements(&self.model, s, e))?;
            return Ok(());
        }
        let mut f: Scratch<Wrench> = smallvec![Wrench::zeros(); s.len()];
        self.wrenches_of(m, loads, &mut f)?;
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
        crate::kernel::finite::finite_result("motor actions", out)
            .map_err(|e| self.inst.blame_elements(&self.model, s, e))
    }

    /// Zhukovski's sums over the motion with q̇ = 1, q̈ = 0 (one input); `qd` is the
    /// input rate the dampers' part of M* is taken at.
    #[inline(always)]
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
        crate::error::check_finite("q, qd, qdd", &[q])?;
        let drive: Drive = (&[q], &[1.0], &[0.0]);
        if let (Some(series), Level::Acceleration, Some(_)) = (&self.reduced_series, upto, loads) {
            // Constant ratios: I*(q) was worked out at loading, M* needs the rates alone
            // (I* alone is `OneDof::reduced`'s, without solving).
            let mut z = self.with_states(|s| {
                self.solve_at::<VELOCITY>(drive, s, &mut [])?;
                self.sums(s, loads, qd, false)
            })?;
            z.reduced = series.at(q);
            return Ok(z);
        }
        if let (Some(one), Level::Acceleration) = (&self.program.one_loop, upto) {
            // A crank and one dyad: solved on literal indices, on the stack.
            return one.sums(self, drive, loads, qd);
        }
        self.with_states(|s| {
            match upto {
                Level::Acceleration => self.solve_at::<ACCELERATION>(drive, s, &mut [])?,
                _ => self.solve_at::<VELOCITY>(drive, s, &mut [])?,
            }
            self.sums(s, loads, qd, upto == Level::Acceleration)
        })
    }

    /// Zhukovski's I*(q) of a machine of constant ratios as a sum of cosines
    /// ([`crate::solvers::zhukovski_series`]), from the motion at q₀ = 0 with q̇ = 1 and
    /// each link's [`Pin`](crate::plan::ratios::Pin).
    pub(super) fn series(
        &self,
        pins: &[crate::plan::ratios::Pin],
    ) -> Result<Series<Vec<Term>>, MechError> {
        let terms = vec![Term::default(); crate::plan::ratios::series_len(pins)];
        let drive: Drive = (&[0.0], &[1.0], &[0.0]);
        self.with_states(|s| {
            self.solve_at::<VELOCITY>(drive, s, &mut [])?;
            Series::from_motion(0.0, terms, &self.inst.links, s, &self.inst.joints, pins)
        })
    }

    /// The power balance over the motion `m` (its link and point motions).
    pub(super) fn power(
        &self,
        m: &Motion,
        loads: &Loads,
    ) -> Result<crate::solvers::virtual_power::Power, MechError> {
        self.check_loads(loads)?;
        let mut w = crate::solvers::virtual_power::Power::default();
        let links = &self.inst.links;
        for &(l, _) in &self.program.inertial {
            w.inertia(&links[l], &m.links[l]);
        }
        for &(l, _) in &self.program.weighed {
            w.gravity(&links[l], &m.links[l], self.inst.gravity);
        }
        for (k, (load, value)) in self.model.loads.iter().zip(&loads.values).enumerate() {
            let link = load.link();
            match (load, *value) {
                (&Load::Force { point, .. }, LoadValue::Force(v)) => w.force(&m.points[point], v),
                (_, LoadValue::Force(v)) => {
                    w.force(&point_motion(&m.states, link, self.inst.loads[k]), v)
                }
                (_, LoadValue::Torque(t)) => w.torque(&m.links[link], t),
            }
        }
        if !self.inst.elements.is_empty() {
            w.elements(&self.inst.elements, &m.states);
        }
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
        self.sums_by(|l| &s[l], s, loads, qd, inertia)
    }

    /// [`Mechanism::sums`] with link l's state read as `at(l)`; the force elements (and
    /// the blame of a non-finite sum on one of them) read `all`, the states by the
    /// mechanism's numbers (empty for a mechanism without elements).
    #[inline(always)]
    pub(super) fn sums_by<'s>(
        &self,
        at: impl Fn(usize) -> &'s LinkState,
        all: &[LinkState],
        loads: Option<&Loads>,
        qd: f64,
        inertia: bool,
    ) -> Result<ZhukovskiSums, MechError> {
        let mut z = ZhukovskiSums::new();
        let (links, gravity) = (&self.inst.links[..], self.inst.gravity);
        if inertia {
            for &(l, share) in &self.program.inertial {
                inertia_term(&mut z, share, &links[l], at(l), &at);
            }
        }
        if let Some(loads) = loads {
            self.check_loads(loads)?;
            for &(l, share) in &self.program.weighed {
                gravity_term(&mut z, share, &links[l], at(l), &at, gravity);
            }
            self.load_terms(&mut z, &at, loads);
            if !self.inst.elements.is_empty() {
                z.elements(&self.inst.elements, all, qd);
            }
        }
        crate::kernel::finite::finite_result(
            "reduced inertia and moment",
            &[z.reduced.inertia, z.reduced.inertia_derivative, z.moment],
        )
        .map_err(|e| self.inst.blame_elements(&self.model, all, e))?;
        Ok(z)
    }
}

/// A link's (geometry `g`, state `s`) term of Zhukovski's I* by its share (`at(n)` the
/// state of a spanned link's partner n).
#[inline(always)]
fn inertia_term<'s>(
    z: &mut ZhukovskiSums,
    share: Share,
    g: &crate::kernel::link_state::LinkGeom,
    s: &LinkState,
    at: &impl Fn(usize) -> &'s LinkState,
) {
    match share {
        Share::AboutPivot => z.inertia_about_pivot(g, s),
        Share::Translating => z.inertia_translating(g, s),
        Share::Spanned(n) => z.inertia_spanned(g, s, at(n)),
        Share::General => z.inertia(g, s),
    }
}

/// A link's (geometry `g`, state `s`) power of gravity `gravity` in Zhukovski's M* by
/// its share (as [`inertia_term`]).
#[inline(always)]
fn gravity_term<'s>(
    z: &mut ZhukovskiSums,
    share: Share,
    g: &crate::kernel::link_state::LinkGeom,
    s: &LinkState,
    at: &impl Fn(usize) -> &'s LinkState,
    gravity: V2,
) {
    match share {
        Share::Translating => z.gravity_translating(g, s, gravity),
        Share::Spanned(n) => z.gravity_spanned(g, s, at(n), gravity),
        _ => z.gravity(g, s, gravity),
    }
}

/// The load terms of Zhukovski's M*, which the scalar sums ([`ZhukovskiSums`]) and the
/// lanes (`crate::kernel::lanes::ZhukovskiLanes`) both take, over their own link states
/// `S`: [`Mechanism::load_terms`] chooses among them once for both.
pub(super) trait LoadTerms<S> {
    /// A force `f` at the local vector `d` of the link in state `s`.
    fn force(&mut self, s: &S, d: V2, f: V2);
    /// A force `f` on a link sliding on the ground (every point at its anchor's velocity).
    fn force_translating(&mut self, s: &S, f: V2);
    /// A torque `t` on the link in state `s`.
    fn torque(&mut self, s: &S, t: f64);
}

impl LoadTerms<LinkState> for ZhukovskiSums {
    #[inline(always)]
    fn force(&mut self, s: &LinkState, d: V2, f: V2) {
        ZhukovskiSums::force(self, s, d, f)
    }
    #[inline(always)]
    fn force_translating(&mut self, s: &LinkState, f: V2) {
        ZhukovskiSums::force_translating(self, s, f)
    }
    #[inline(always)]
    fn torque(&mut self, s: &LinkState, t: f64) {
        ZhukovskiSums::torque(self, s, t)
    }
}

impl Mechanism {
    /// Every load's power per unit input rate into `z`, as the generated code takes it: a
    /// force on a link sliding on the ground by its anchor's velocity, a torque on such a
    /// link left out (ω = 0: it does no work), any other force at its point, any other
    /// torque by the link's ω.
    #[inline(always)]
    pub(super) fn load_terms<'s, S: 's, Z: LoadTerms<S>>(
        &self,
        z: &mut Z,
        at: &impl Fn(usize) -> &'s S,
        loads: &Loads,
    ) {
        for (&(link, share), value) in self.program.load_shares.iter().zip(&loads.values) {
            match (*value, share) {
                (LoadValue::Force(v), LoadShare::Translating) => z.force_translating(at(link), v),
                (LoadValue::Force(v), LoadShare::At(d)) => z.force(at(link), d, v),
                (LoadValue::Torque(_), LoadShare::Translating) => {}
                (LoadValue::Torque(t), LoadShare::At(_)) => z.torque(at(link), t),
            }
        }
    }
}

/// `n` values `zero`: the first `n` of `stack` when they fit, else `heap` grown to them.
#[inline(always)]
fn stack_or_heap<'a, T: Copy, const N: usize>(
    stack: &'a mut [T; N],
    heap: &'a mut Vec<T>,
    n: usize,
    zero: T,
) -> &'a mut [T] {
    if n <= N {
        &mut stack[..n]
    } else {
        heap.resize(n, zero);
        heap
    }
}
