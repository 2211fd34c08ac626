//! The plan's dispatch: a [`Mechanism`] walks its Assur groups in order and calls each
//! group kind's entry point (the generated code's kernels) for positions, rates and
//! accelerations; `pose`, `kinematics` and the caller-buffer forms.

use crate::error::non_finite;
use crate::kernel::constraints::{Drive, Level};
use crate::kernel::kinematics;
use crate::kernel::kinetostatics::{Reaction, Wrench};
use crate::kernel::link_state::{
    anchor_motion, point_motion, point_pose, LinkPose, LinkState, PointMotion, V2,
};
use crate::kernel::screw;
use crate::plan::assur::{Group, Kernel};
use crate::MechError;
use smallvec::SmallVec;
use std::sync::Arc;

use super::instances::{crank_alone, slotted_alone};
use super::mechanism::Mechanism;
use super::mechanism::{Owner, Scratch};
use super::newton::system;
use super::results::*;
use crate::plan::rotation::AngleRule;

/// The levels as constants of the solvers' const generic (`Level` itself cannot be one):
/// a solve specialised to its level has every `upto` test of the kernels folded.
pub(super) const POSITION: u8 = 0;
/// [`Level::Velocity`].
pub(super) const VELOCITY: u8 = 1;
/// [`Level::Acceleration`].
pub(super) const ACCELERATION: u8 = 2;

/// The [`Level`] of a level constant.
#[inline(always)]
pub(super) const fn level(upto: u8) -> Level {
    match upto {
        POSITION => Level::Position,
        VELOCITY => Level::Velocity,
        _ => Level::Acceleration,
    }
}

/// The most links of a mechanism whose per-call states live in the thread's scratch
/// ([`Mechanism::with_states`]).
const SCRATCH_LINKS: usize = 8;

std::thread_local! {
    /// Each thread's per-call link states (no allocation: a constant initialiser and no
    /// destructor), so that a call of `pose_into` or Zhukovski's route neither allocates
    /// nor initialises a buffer of states.
    static STATES: std::cell::RefCell<[LinkState; SCRATCH_LINKS]> =
        const { std::cell::RefCell::new([LinkState::at(V2::new(0.0, 0.0)); SCRATCH_LINKS]) };
}

impl Mechanism {
    /// Call `f` with one state per link, of any content but the drawing's where a Newton
    /// group starts from it: the thread's scratch (mechanisms of up to
    /// [`SCRATCH_LINKS`] links, not already in use), else a copy of the drawing.
    #[inline(always)]
    pub(super) fn with_states<R>(&self, f: impl FnOnce(&mut [LinkState]) -> R) -> R {
        let n = self.inst.drawing.len();
        let mut f = Some(f);
        if n <= SCRATCH_LINKS {
            let r = STATES.try_with(|c| {
                let mut s = c.try_borrow_mut().ok()?;
                let s = &mut s[..n];
                if self.newton {
                    s.copy_from_slice(&self.inst.drawing);
                }
                f.take().map(|f| f(s))
            });
            if let Ok(Some(r)) = r {
                return r;
            }
        }
        let mut s: Scratch<LinkState> = SmallVec::from_slice(&self.inst.drawing);
        match f.take() {
            Some(f) => f(&mut s),
            // `f` is taken only by a call that returned.
            None => unreachable!(),
        }
    }

    pub(super) fn check_inputs(&self, v: &[&[f64]]) -> Result<(), MechError> {
        self.check_lengths(v)?;
        for x in v {
            crate::error::check_finite("q, qd, qdd", x)?;
        }
        Ok(())
    }

    /// `InvalidInput` unless every slice of `v` has one value per input.
    #[inline]
    pub(super) fn check_lengths(&self, v: &[&[f64]]) -> Result<(), MechError> {
        let g = self.model.inputs.len();
        if v.iter().all(|x| x.len() == g) {
            return Ok(());
        }
        Err(self.wrong_length(v))
    }

    #[cold]
    #[inline(never)]
    fn wrong_length(&self, v: &[&[f64]]) -> MechError {
        let n = v
            .iter()
            .map(|x| x.len())
            .find(|&n| n != self.dof())
            .unwrap_or(0);
        MechError::InvalidInput(format!("expected {} input values, got {n}", self.dof()))
    }

    /// The error of a solve of the finite-checked inputs `v` that failed with `e`: the
    /// error [`Mechanism::check_inputs`] gives when one of them is not finite (a NaN or an
    /// infinity among the inputs reaches every result, so a solve given one fails), else
    /// `e`. The common path looks at the inputs only here, on failure.
    #[cold]
    #[inline(never)]
    pub(super) fn blame_inputs(&self, v: &[&[f64]], e: MechError) -> MechError {
        match self.check_inputs(v) {
            Err(bad) => bad,
            Ok(()) => e,
        }
    }

    /// Solve the plan up to `upto` at (q, q̇, q̈) into `s` (one state per link), reusing its
    /// allocation: the run-time counterpart of the generated `__solve`. The fields beyond
    /// `upto` (velocities and accelerations at [`Level::Position`]) are not written: they
    /// keep what `s` held (the drawing's rest when some group is solved by Newton).
    pub fn solve_into(
        &self,
        q: &[f64],
        qd: &[f64],
        qdd: &[f64],
        upto: Level,
        s: &mut Vec<LinkState>,
    ) -> Result<(), MechError> {
        self.solve_into_from(q, qd, qdd, upto, s, None)
    }

    /// [`Mechanism::solve_into`] with the triads' Newton started from `start` (a previous
    /// configuration's states, `super::warm::Warm`) where given.
    pub(super) fn solve_into_from(
        &self,
        q: &[f64],
        qd: &[f64],
        qdd: &[f64],
        upto: Level,
        s: &mut Vec<LinkState>,
        start: Option<&[LinkState]>,
    ) -> Result<(), MechError> {
        s.resize(self.inst.drawing.len(), LinkState::default());
        self.solve_slice(q, qd, qdd, upto, s, start)
    }

    /// [`Mechanism::solve_into`] into a slice of one state per link.
    pub(super) fn solve_slice(
        &self,
        q: &[f64],
        qd: &[f64],
        qdd: &[f64],
        upto: Level,
        s: &mut [LinkState],
        start: Option<&[LinkState]>,
    ) -> Result<(), MechError> {
        self.check_inputs(&[q, qd, qdd])?;
        let drive = (q, qd, qdd);
        match upto {
            Level::Position => self.solve_from::<POSITION>(drive, s, &mut [], start),
            Level::Velocity => self.solve_from::<VELOCITY>(drive, s, &mut [], start),
            Level::Acceleration => self.solve_from::<ACCELERATION>(drive, s, &mut [], start),
            Level::Jacobian if self.redundant => {
                let branches: Scratch<f64> = SmallVec::from_slice(&self.branches);
                crate::kernel::branches::search(&branches, |b| self.solve_on(b, drive, upto, s))
            }
            Level::Jacobian => self.solve_on(&self.branches, drive, upto, s),
        }
    }

    /// The plan solved at `drive` up to the level `UPTO` into `s` (one state per link, of
    /// any content: every state a group uses is written first), on the drawing's branches
    /// (past a change point of a redundant mechanism, the others: as the generated code);
    /// what each closed-form dyad keeps for its reactions into `kept` (one per group, or
    /// empty for none). No check of the inputs or of the results.
    #[inline(always)]
    pub(super) fn solve_at<const UPTO: u8>(
        &self,
        drive: Drive,
        s: &mut [LinkState],
        kept: &mut [kinematics::DyadSystem],
    ) -> Result<(), MechError> {
        self.solve_from::<UPTO>(drive, s, kept, None)
    }

    /// [`Mechanism::solve_at`] with the triads' Newton started from `start` (a previous
    /// configuration's states, one per link: the warm start of a sweep,
    /// `super::warm::Warm`) instead of the drawing; the other groups as always.
    #[inline(always)]
    pub(super) fn solve_from<const UPTO: u8>(
        &self,
        drive: Drive,
        s: &mut [LinkState],
        kept: &mut [kinematics::DyadSystem],
        start: Option<&[LinkState]>,
    ) -> Result<(), MechError> {
        if self.redundant {
            // Past a change point the drawing's branches may not close a redundant group:
            // the other combinations are tried, as the generated code does.
            let branches: Scratch<f64> = SmallVec::from_slice(&self.branches);
            return crate::kernel::branches::search(&branches, |b| {
                self.solve_on(b, drive, level(UPTO), s)
            });
        }
        // Newton starts from the drawing; closed forms overwrite every state they use
        // (the ground's is the drawing's always).
        if self.newton {
            s.copy_from_slice(&self.inst.drawing);
        } else {
            s[0] = self.inst.drawing[0];
        }
        let keep = kept.len() == self.plan.len();
        for (i, (g, &sign)) in self.plan.iter().zip(&self.branches).enumerate() {
            let k = self.group_step::<UPTO>(g, sign, drive, s, start)?;
            if keep {
                kept[i] = k;
            }
        }
        Ok(())
    }

    /// True when the mechanism was accepted with redundant constraints.
    pub fn redundant(&self) -> bool {
        self.redundant
    }

    pub(super) fn solve_on(
        &self,
        branches: &[f64],
        drive: Drive,
        upto: Level,
        s: &mut [LinkState],
    ) -> Result<(), MechError> {
        // Newton starts from the drawing; closed forms overwrite every state they use
        // (the ground's is the drawing's always).
        if self.newton {
            s.copy_from_slice(&self.inst.drawing);
        } else {
            s[0] = self.inst.drawing[0];
        }
        for (g, &sign) in self.plan.iter().zip(branches) {
            self.group_positions(g, sign, drive, upto, s, None)?;
        }
        Ok(())
    }

    /// Positions only, into `out` without allocating once `s` has grown: every point's x
    /// and y (m, in the order of [`Model::points`](crate::model::Model::points)), then every moving link's angle (rad).
    /// `out` holds 2 × points + links − 1 values. The row of `crate::runtime::columns` for
    /// positions.
    pub fn positions_into(
        &self,
        q: &[f64],
        s: &mut Vec<LinkState>,
        out: &mut [f64],
    ) -> Result<(), MechError> {
        self.positions_from(q, s, out, None)
    }

    /// [`Mechanism::positions_into`] with the triads' Newton started from `start` where
    /// given (`super::warm::Warm`).
    pub(super) fn positions_from(
        &self,
        q: &[f64],
        s: &mut Vec<LinkState>,
        out: &mut [f64],
        start: Option<&[LinkState]>,
    ) -> Result<(), MechError> {
        let np = self.inst.points.len();
        self.points_from(q, s, &mut out[..2 * np], start)?;
        let angles = &mut out[2 * np..];
        for &l in &self.program.angle_order {
            let a = self.link_angle(l, &s[l], q, |m| angles[m - 1]);
            angles[l - 1] = a;
        }
        crate::kernel::finite::finite_result("link angles", &out[2 * np..])
    }

    /// The points alone, into `out` (x and y of each point, m, in the order of
    /// [`Model::points`](crate::model::Model::points)): [`Mechanism::positions_into`] without the links' angles (no
    /// `atan2`).
    pub fn points_into(
        &self,
        q: &[f64],
        s: &mut Vec<LinkState>,
        out: &mut [f64],
    ) -> Result<(), MechError> {
        self.points_from(q, s, out, None)
    }

    /// [`Mechanism::points_into`] with the triads' Newton started from `start` where given
    /// (`super::warm::Warm`).
    pub(super) fn points_from(
        &self,
        q: &[f64],
        s: &mut Vec<LinkState>,
        out: &mut [f64],
        start: Option<&[LinkState]>,
    ) -> Result<(), MechError> {
        let zero = zeros(q.len());
        self.solve_into_from(q, &zero, &zero, Level::Position, s, start)?;
        let np = self.inst.points.len();
        for (k, xy) in out[..2 * np].chunks_exact_mut(2).enumerate() {
            let p = self.point_at(s, k);
            xy[0] = p.x;
            xy[1] = p.y;
        }
        // What is returned is checked, not the states behind it.
        crate::kernel::finite::finite_result("point positions", &out[..2 * np])
    }

    /// Positions only: every link's angle and cg, every point.
    pub fn pose(&self, q: &[f64]) -> Result<Pose, MechError> {
        let mut p = Pose {
            links: Vec::new(),
            points: Vec::new(),
            model: self.model.clone(),
        };
        self.pose_into(q, &mut p)?;
        Ok(p)
    }

    /// [`Mechanism::pose`] into `out`, reusing its buffers: no allocation once they have
    /// grown (`out` from an earlier call, on this or another mechanism), for mechanisms of
    /// up to 8 links.
    pub fn pose_into(&self, q: &[f64], out: &mut Pose) -> Result<(), MechError> {
        let zero = zeros(self.dof());
        self.with_states(|s| self.pose_from(q, &zero, s, out))
    }

    /// [`Mechanism::pose_into`] with the states `s` to solve into.
    #[inline(always)]
    fn pose_from(
        &self,
        q: &[f64],
        zero: &[f64],
        s: &mut [LinkState],
        out: &mut Pose,
    ) -> Result<(), MechError> {
        let solved = if self.newton || self.redundant {
            // Newton and the branch search are given finite inputs only.
            self.check_inputs(&[q, zero, zero])
                .and_then(|()| self.solve_at::<POSITION>((q, zero, zero), s, &mut []))
        } else {
            self.check_lengths(&[q])
                .and_then(|()| self.solve_at::<POSITION>((q, zero, zero), s, &mut []))
                .map_err(|e| self.blame_inputs(&[q, zero, zero], e))
        };
        solved?;
        let s = &*s;
        let p = &self.program;
        let (n, np) = (s.len(), p.owners.len());
        fit(&mut out.links, n, Default::default());
        fit(&mut out.points, np, Default::default());
        let mut bad = false;
        out.links[0] = LinkPose {
            angle: p.ground.angle,
            cg: p.ground.cg,
        };
        // As `positions_into`, `pose_many`, the columns and `kinematics` (the same numbers
        // bit for bit): every angle by its rule, every point from its owner.
        for &l in &p.angle_order {
            let st = &s[l];
            bad |= nf(st.pos) | nf(st.rot);
            let o = self.link_pose(l, st, q, |m| out.links[m].angle);
            bad |= nf(o.cg);
            out.links[l] = o;
        }
        for (k, o) in out.points.iter_mut().enumerate() {
            o.pos = self.point_at(s, k);
            bad |= nf(o.pos);
        }
        if bad {
            return Err(self.blame_inputs(&[q, zero, zero], overflow()));
        }
        if !Arc::ptr_eq(&out.model, &self.model) {
            out.model = self.model.clone();
        }
        Ok(())
    }

    /// The position (m) of point `k` in the states `s`, from its owner (`Program::owners`,
    /// as the generated code publishes it): a ground point's drawn place, a link's anchor
    /// its state's position (no rotation), any other point through its link's rotation.
    #[inline(always)]
    pub(super) fn point_at(&self, s: &[LinkState], k: usize) -> V2 {
        match self.program.owners[k] {
            Owner::Ground(d) => d,
            Owner::Anchor(l) => s[l].pos,
            Owner::Local(l, d) => point_pose(s, l, d).pos,
        }
    }

    /// The pose of moving link `l` in the state `s`: its angle by its rule
    /// ([`Mechanism::link_angle`]), its cg not rotated when it never turns
    /// ([`crate::kernel::link_state::LinkGeom::pose_translating`]), as the generated code.
    #[inline(always)]
    pub(super) fn link_pose(
        &self,
        l: usize,
        s: &LinkState,
        q: &[f64],
        published: impl FnOnce(usize) -> f64,
    ) -> LinkPose {
        let geom = &self.inst.links[l];
        match self.program.angles[l - 1] {
            AngleRule::Translating => geom.pose_translating(s),
            _ => geom.pose_at(s, self.link_angle(l, s, q, published)),
        }
    }

    /// The motion of moving link `l` in the state `s`, as [`Mechanism::link_pose`] (a link
    /// that never turns: [`crate::kernel::link_state::LinkGeom::motion_translating`]).
    #[inline(always)]
    fn link_motion(
        &self,
        l: usize,
        s: &LinkState,
        q: &[f64],
        published: impl FnOnce(usize) -> f64,
    ) -> crate::kernel::link_state::LinkMotion {
        let geom = &self.inst.links[l];
        match self.program.angles[l - 1] {
            AngleRule::Translating => geom.motion_translating(s),
            _ => geom.motion_at(s, self.link_angle(l, s, q, published)),
        }
    }

    /// The angle θ (rad) of moving link `l` in the state `s` by its rule
    /// ([`crate::plan::rotation::angle_rule`], as the generated code publishes it): a
    /// crank's from its input, a translating link's the drawing's, a tracked link's from its
    /// turn, a partner's from `published(m)` (the angle of its partner m, published before
    /// it in `Program::angle_order`; no `atan2`), else from the rotation.
    #[inline(always)]
    pub(super) fn link_angle(
        &self,
        l: usize,
        s: &LinkState,
        q: &[f64],
        published: impl FnOnce(usize) -> f64,
    ) -> f64 {
        let geom = &self.inst.links[l];
        match self.program.angles[l - 1] {
            AngleRule::Own => geom.angle(s),
            AngleRule::Tracked => geom.angle_tracked(s),
            AngleRule::With(m) => geom.angle_with(&self.inst.links[m], published(m)),
            AngleRule::Crank { input, sign, zero } => kinematics::crank_angle(
                match zero {
                    None => q[input],
                    Some(z) => q[input] + z,
                },
                sign,
            ),
            AngleRule::Translating => geom.angle_ref,
        }
    }

    /// Positions, velocities and accelerations at (q, q̇, q̈).
    pub fn kinematics(&self, q: &[f64], qd: &[f64], qdd: &[f64]) -> Result<Motion, MechError> {
        let mut m = Motion {
            links: Vec::new(),
            points: Vec::new(),
            inputs: SmallVec::new(),
            states: Vec::new(),
            systems: Vec::new(),
            model: self.model.clone(),
        };
        self.kinematics_into(q, qd, qdd, &mut m)?;
        Ok(m)
    }

    /// [`Mechanism::kinematics`] into `out`, reusing its buffers: no allocation once they
    /// have grown (`out` from an earlier call, on this or another mechanism).
    pub fn kinematics_into(
        &self,
        q: &[f64],
        qd: &[f64],
        qdd: &[f64],
        out: &mut Motion,
    ) -> Result<(), MechError> {
        self.kinematics_from(q, qd, qdd, out, None)
    }

    /// [`Mechanism::kinematics_into`] with the triads' Newton started from `start` where
    /// given (`super::warm::Warm`).
    pub(super) fn kinematics_from(
        &self,
        q: &[f64],
        qd: &[f64],
        qdd: &[f64],
        out: &mut Motion,
        start: Option<&[LinkState]>,
    ) -> Result<(), MechError> {
        let v: [&[f64]; 3] = [q, qd, qdd];
        let (n, ng) = (self.inst.drawing.len(), self.plan.len());
        fit(&mut out.states, n, LinkState::default());
        fit(&mut out.systems, ng, kinematics::DyadSystem::None);
        let solved = if self.newton || self.redundant {
            // Newton and the branch search are given finite inputs only.
            self.check_inputs(&v).and_then(|()| {
                let (s, kept) = (&mut out.states, &mut out.systems);
                self.solve_from::<ACCELERATION>((q, qd, qdd), s, kept, start)
            })
        } else {
            self.check_lengths(&v)
                .and_then(|()| {
                    self.solve_at::<ACCELERATION>((q, qd, qdd), &mut out.states, &mut out.systems)
                })
                .map_err(|e| self.blame_inputs(&v, e))
        };
        solved?;
        let s = &out.states[..];
        let p = &self.program;
        let np = p.owners.len();
        fit(&mut out.links, n, Default::default());
        fit(&mut out.points, np, Default::default());
        // Every state and every published value derived from them checked finite, flags
        // joined by OR, one test at the end (the states as `finite_states`, the rest as
        // the points and cgs derived from them; an anchor point is its link's state).
        let mut bad = false;
        out.links[0] = p.ground;
        for &l in &p.angle_order {
            let st = &s[l];
            bad |= nf(st.pos)
                | nf(st.rot)
                | nf(st.vel)
                | nf(st.acc)
                | non_finite(st.omega)
                | non_finite(st.alpha);
            let o = self.link_motion(l, st, q, |m| out.links[m].angle);
            bad |= nf(o.cg) | nf(o.cg_vel) | nf(o.cg_acc);
            out.links[l] = o;
        }
        for (o, owner) in out.points.iter_mut().zip(&p.owners) {
            *o = match *owner {
                Owner::Ground(d) => PointMotion {
                    pos: d,
                    vel: V2::zeros(),
                    acc: V2::zeros(),
                },
                Owner::Anchor(l) => anchor_motion(&s[l]),
                Owner::Local(l, d) => {
                    let pm = point_motion(s, l, d);
                    bad |= nf(pm.pos) | nf(pm.vel) | nf(pm.acc);
                    pm
                }
            };
        }
        if bad {
            return Err(self.blame_inputs(&v, overflow()));
        }
        let g = q.len();
        if out.inputs.len() != 3 * g {
            out.inputs.resize(3 * g, 0.0);
        }
        out.inputs[..g].copy_from_slice(q);
        out.inputs[g..2 * g].copy_from_slice(qd);
        out.inputs[2 * g..].copy_from_slice(qdd);
        if !Arc::ptr_eq(&out.model, &self.model) {
            out.model = self.model.clone();
        }
        Ok(())
    }
}

/// Either coordinate of `v` not finite ([`non_finite`]).
#[inline(always)]
fn nf(v: V2) -> bool {
    non_finite(v.x) | non_finite(v.y)
}

/// `g` zeros (the rates and accelerations of a pose): a slice of a constant up to 16
/// inputs, no copy.
#[inline(always)]
pub(super) fn zeros(g: usize) -> std::borrow::Cow<'static, [f64]> {
    const ZEROS: [f64; 16] = [0.0; 16];
    match ZEROS.get(..g) {
        Some(z) => std::borrow::Cow::Borrowed(z),
        None => std::borrow::Cow::Owned(vec![0.0; g]),
    }
}

/// `v` made `n` long, new entries `zero`; nothing but a comparison when it already is
/// (a caller's buffer from an earlier call).
#[inline(always)]
pub(super) fn fit<T: Clone>(v: &mut Vec<T>, n: usize, zero: T) {
    if v.len() != n {
        v.resize(n, zero);
    }
}

/// The error of a non-finite state or published value:
/// [`crate::kernel::finite::states_overflow`].
#[cold]
#[inline(never)]
fn overflow() -> MechError {
    crate::kernel::finite::states_overflow()
}

/// The specialised dispatch of the common closed forms: each group's solver variant
/// matched once, the kernel called with that variant written out, so that the kernels'
/// own `match` on the solver folds (as in the generated code, where it is a constant).
impl Mechanism {
    /// Solve group `g` on branch `sign` at `drive` up to the level `UPTO`; what a dyad
    /// keeps for its reactions.
    #[inline(always)]
    fn group_step<const UPTO: u8>(
        &self,
        g: &Group,
        sign: f64,
        drive: Drive,
        s: &mut [LinkState],
        start: Option<&[LinkState]>,
    ) -> Result<kinematics::DyadSystem, MechError> {
        use crate::kernel::dyad::Solver;
        let (joints, scale, upto) = (&self.inst.joints[..], self.inst.scale, level(UPTO));
        match (&g.kernel, g.solver) {
            (Kernel::Driven(d), Solver::DrivenRevolute { body, joint, input }) => {
                crank_alone!(
                    d,
                    joints,
                    |dn, jn| {
                        let solver = Solver::DrivenRevolute {
                            body: dn.body,
                            joint: 0,
                            input,
                        };
                        kinematics::solve_driven(solver, &dn, &jn, s, drive, upto)?
                    },
                    {
                        let solver = Solver::DrivenRevolute { body, joint, input };
                        kinematics::solve_driven(solver, d, joints, s, drive, upto)?
                    }
                );
                Ok(kinematics::DyadSystem::None)
            }
            (Kernel::Chain(c), Solver::SlottedSlider { body, jq, js }) => slotted_alone!(
                joints,
                body,
                jq,
                js,
                |local| {
                    let solver = Solver::SlottedSlider { body, jq: 0, js: 1 };
                    kinematics::solve_chain(solver, c, &local, s, drive, sign, scale, upto)
                },
                self.other_step(g, sign, drive, upto, s, start)
            ),
            (Kernel::Chain(c), solver) => written_out!(
                solver,
                |solver| kinematics::solve_chain(solver, c, joints, s, drive, sign, scale, upto),
                self.other_step(g, sign, drive, upto, s, start)
            ),
            _ => self.other_step(g, sign, drive, upto, s, start),
        }
    }

    /// d'Alembert on group `g` with what its kinematics kept (`kept`, or
    /// [`kinematics::DyadSystem::None`] to rebuild it), the common closed forms
    /// specialised as in [`Mechanism::group_step`]; the others through
    /// [`Mechanism::group_reactions`].
    #[inline(always)]
    pub(super) fn group_reactions_kept(
        &self,
        g: &Group,
        kept: &kinematics::DyadSystem,
        s: &[LinkState],
        f: &mut [Wrench],
        r: &mut [Reaction],
        driver: &mut [f64],
    ) -> Result<(), MechError> {
        use crate::kernel::dyad::Solver::SlottedSlider;
        let (joints, scale) = (&self.inst.joints[..], self.inst.scale);
        match &g.kernel {
            Kernel::Driven(k) => crank_alone!(
                k,
                joints,
                |dn, jn| {
                    let mut one = [r[k.screw.joint]];
                    screw::driven_reactions(&dn, &jn, s, f, &mut one, driver);
                    r[k.screw.joint] = one[0];
                },
                screw::driven_reactions(k, joints, s, f, r, driver)
            ),
            Kernel::Chain(c) if matches!(g.solver, SlottedSlider { .. }) => {
                let SlottedSlider { body, jq, js } = g.solver else {
                    unreachable!()
                };
                slotted_alone!(
                    joints,
                    body,
                    jq,
                    js,
                    |local| {
                        let solver = SlottedSlider { body, jq: 0, js: 1 };
                        let mut two = [r[jq], r[js]];
                        kinematics::chain_reactions(
                            solver, c, &local, s, f, scale, kept, &mut two,
                        )?;
                        (r[jq], r[js]) = (two[0], two[1]);
                    },
                    self.other_reactions(g, kept, s, f, r, driver)?
                )
            }
            Kernel::Chain(c) => written_out!(
                g.solver,
                |solver| kinematics::chain_reactions(solver, c, joints, s, f, scale, kept, r)?,
                self.other_reactions(g, kept, s, f, r, driver)?
            ),
            _ => self.other_reactions(g, kept, s, f, r, driver)?,
        }
        Ok(())
    }

    /// [`Mechanism::group_reactions_kept`] of the other kinds, out of line.
    #[inline(never)]
    fn other_reactions(
        &self,
        g: &Group,
        kept: &kinematics::DyadSystem,
        s: &[LinkState],
        f: &mut [Wrench],
        r: &mut [Reaction],
        driver: &mut [f64],
    ) -> Result<(), MechError> {
        if let Kernel::Chain(c) = &g.kernel {
            let (joints, scale) = (&self.inst.joints[..], self.inst.scale);
            return kinematics::chain_reactions(g.solver, c, joints, s, f, scale, kept, r);
        }
        self.group_reactions(g, s, f, r, driver)
    }

    /// [`Mechanism::group_step`] of the other kinds, out of line: through the plan's
    /// dispatch.
    #[inline(never)]
    fn other_step(
        &self,
        g: &Group,
        sign: f64,
        drive: Drive,
        upto: Level,
        s: &mut [LinkState],
        start: Option<&[LinkState]>,
    ) -> Result<kinematics::DyadSystem, MechError> {
        if let Kernel::Chain(c) = &g.kernel {
            let (joints, scale) = (&self.inst.joints[..], self.inst.scale);
            return kinematics::solve_chain(g.solver, c, joints, s, drive, sign, scale, upto);
        }
        self.group_positions(g, sign, drive, upto, s, start)?;
        Ok(kinematics::DyadSystem::None)
    }
}

/// The plan's dispatch: the one place where a group's kernel is matched to its entry
/// point, for positions (and rates, accelerations up to `upto`), the unit-rate velocity
/// field of virtual power, and the reactions. The generated code calls the same entry
/// points, unrolled.
impl Mechanism {
    /// Solve group `g` on assembly branch `sign` at the inputs `drive`, up to `upto`; a
    /// triad's Newton from `start` (a previous configuration's states) when given, else
    /// from the drawing.
    #[inline]
    pub(super) fn group_positions(
        &self,
        g: &Group,
        sign: f64,
        drive: Drive,
        upto: Level,
        s: &mut [LinkState],
        start: Option<&[LinkState]>,
    ) -> Result<(), MechError> {
        let (joints, scale) = (&self.inst.joints[..], self.inst.scale);
        match &g.kernel {
            Kernel::Driven(d) => kinematics::solve_driven(g.solver, d, joints, s, drive, upto)?,
            Kernel::Chain(c) => {
                kinematics::solve_chain(g.solver, c, joints, s, drive, sign, scale, upto)
                    .map(|_| ())?
            }
            Kernel::Mesh(m) => {
                crate::elements::gears::solve_mesh(m, &self.inst.meshes, joints, s, upto)?
            }
            Kernel::Train(t) => {
                let willis = self.willis_of(t);
                crate::elements::gears::solve_train(t, &willis, &self.inst.meshes, joints, s, upto)?
            }
            Kernel::Rolling(r) => crate::elements::rolling::solve_rolling(
                r, joints, s, drive, sign, scale, upto, true,
            )?,
            Kernel::Cam(c) => {
                crate::elements::cam::solve_cam(c, &self.inst.cams, joints, s, upto)?;
            }
            Kernel::System => match &g.triad {
                Some(t) => crate::kernel::triad::triad_solve::<12>(
                    t,
                    &g.bodies,
                    &g.cons,
                    joints,
                    s,
                    drive,
                    scale,
                    upto,
                    &self.inst.drawing,
                    start,
                )
                .map(|_| ())?,
                None => system(g, |n| n.solve(g, joints, s, drive, scale, upto))?,
            },
        }
        Ok(())
    }

    /// The velocities of group `grp` in the field moving the inputs at the rates of
    /// `drive` (virtual power's unit field), into `v`.
    #[inline]
    pub(super) fn group_unit_rates(
        &self,
        grp: &Group,
        drive: Drive,
        v: &mut [LinkState],
    ) -> Result<(), MechError> {
        let (joints, scale) = (&self.inst.joints[..], self.inst.scale);
        match &grp.kernel {
            Kernel::Driven(d) => crank_alone!(
                d,
                joints,
                |dn, jn| screw::driven_rates(&dn, &jn, v, drive, Level::Velocity)?,
                screw::driven_rates(d, joints, v, drive, Level::Velocity)?
            ),
            Kernel::Chain(c) => screw::chain_rates(c, joints, v, scale, Level::Velocity)?,
            Kernel::Mesh(m) => crate::elements::gears::solve_mesh(
                m,
                &self.inst.meshes,
                joints,
                v,
                Level::Velocity,
            )?,
            Kernel::Train(t) => crate::elements::gears::solve_train(
                t,
                &self.willis_of(t),
                &self.inst.meshes,
                joints,
                v,
                Level::Velocity,
            )?,
            Kernel::Cam(c) => {
                crate::elements::cam::solve_cam(c, &self.inst.cams, joints, v, Level::Velocity)?;
            }
            Kernel::Rolling(r) => crate::elements::rolling::solve_rolling(
                r,
                joints,
                v,
                drive,
                1.0,
                scale,
                Level::Velocity,
                false,
            )?,
            Kernel::System => system(grp, |n| n.field(grp, joints, v, drive, scale))?,
        }
        Ok(())
    }

    /// d'Alembert on group `g`: its joints' reactions into `r`, its inputs' motor actions
    /// into `driver`, the reactions on the links inward added to `f`.
    #[inline]
    pub(super) fn group_reactions(
        &self,
        g: &Group,
        s: &[LinkState],
        f: &mut [Wrench],
        r: &mut [Reaction],
        driver: &mut [f64],
    ) -> Result<(), MechError> {
        let (joints, scale) = (&self.inst.joints[..], self.inst.scale);
        match &g.kernel {
            Kernel::Driven(k) => screw::driven_reactions(k, joints, s, f, r, driver),
            Kernel::Chain(c) => kinematics::chain_reactions(
                g.solver,
                c,
                joints,
                s,
                f,
                scale,
                &kinematics::DyadSystem::None,
                r,
            )?,
            Kernel::Mesh(m) => {
                crate::elements::gears::mesh_reactions(m, &self.inst.meshes, joints, s, f, r)?
            }
            Kernel::Train(t) => {
                crate::elements::gears::train_reactions(t, &self.inst.meshes, joints, s, f, r)?
            }
            Kernel::Cam(c) => {
                crate::elements::cam::cam_reactions(c, &self.inst.cams, joints, s, None, f, r)?
            }
            Kernel::Rolling(k) => {
                crate::elements::rolling::rolling_reactions(k, joints, s, f, scale, r, driver)?
            }
            Kernel::System => system(g, |n| n.reactions(g, joints, s, f, scale, r, driver))?,
        }
        Ok(())
    }
}
