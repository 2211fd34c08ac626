//! The plan's dispatch: a [`Mechanism`] walks its Assur groups in order and calls each
//! group kind's entry point (the generated code's kernels) for positions, rates and
//! accelerations; `pose`, `kinematics` and the caller-buffer forms.

use crate::kernel::constraints::{Drive, Level};
use crate::kernel::kinematics;
use crate::kernel::kinetostatics::{Reaction, Wrench};
use crate::kernel::link_state::{point_motion, point_pose, LinkState};
use crate::kernel::screw;
use crate::plan::assur::{Group, Kernel};
use crate::MechError;
use smallvec::SmallVec;
use std::sync::Arc;

use super::mechanism::Mechanism;
use super::mechanism::Scratch;
use super::newton::system;
use super::results::*;

impl Mechanism {
    pub(super) fn check_inputs(&self, v: &[&[f64]]) -> Result<(), MechError> {
        for x in v {
            if x.len() != self.dof() {
                return Err(MechError::InvalidInput(format!(
                    "expected {} input values, got {}",
                    self.dof(),
                    x.len()
                )));
            }
            crate::error::check_finite("q, qd, qdd", x)?;
        }
        Ok(())
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
        s.resize(self.inst.drawing.len(), LinkState::default());
        self.solve_slice(q, qd, qdd, upto, s)
    }

    /// [`Mechanism::solve_into`] into a slice of one state per link.
    pub(super) fn solve_slice(
        &self,
        q: &[f64],
        qd: &[f64],
        qdd: &[f64],
        upto: Level,
        s: &mut [LinkState],
    ) -> Result<(), MechError> {
        self.check_inputs(&[q, qd, qdd])?;
        if self.redundant() {
            // Past a change point the drawing's branches may not close a redundant group:
            // the other combinations are tried, as the generated code does.
            let branches: Scratch<f64> = SmallVec::from_slice(&self.branches);
            return crate::kernel::branches::search(&branches, |b| {
                self.solve_on(b, (q, qd, qdd), upto, s)
            });
        }
        self.solve_on(&self.branches, (q, qd, qdd), upto, s)
    }

    /// True when the mechanism was accepted with redundant constraints.
    pub fn redundant(&self) -> bool {
        self.model.allow_redundant && self.plan.iter().any(|g| g.redundant())
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
            self.group_positions(g, sign, drive, upto, s)?;
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
        let np = self.inst.points.len();
        self.points_into(q, s, &mut out[..2 * np])?;
        for (k, (l, st)) in self.inst.links.iter().zip(s.iter()).enumerate().skip(1) {
            out[2 * np + k - 1] = l.pose(st).angle;
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
        const ZEROS: [f64; 16] = [0.0; 16];
        let zero: Scratch<f64> = if q.len() <= ZEROS.len() {
            SmallVec::from_slice(&ZEROS[..q.len()])
        } else {
            SmallVec::from_elem(0.0, q.len())
        };
        self.solve_into(q, &zero, &zero, Level::Position, s)?;
        let np = self.inst.points.len();
        for (xy, &(o, d)) in out[..2 * np].chunks_exact_mut(2).zip(&self.inst.points) {
            let p = point_pose(s, o, d).pos;
            xy[0] = p.x;
            xy[1] = p.y;
        }
        // What is returned is checked, not the states behind it.
        crate::kernel::finite::finite_result("point positions", &out[..2 * np])
    }

    /// Positions only: every link's angle and cg, every point.
    pub fn pose(&self, q: &[f64]) -> Result<Pose, MechError> {
        let zero = vec![0.0; self.dof()];
        let mut s = Vec::new();
        self.solve_into(q, &zero, &zero, Level::Position, &mut s)?;
        crate::kernel::finite::finite_states(&s, Level::Position)?;
        let links = self
            .inst
            .links
            .iter()
            .zip(&s)
            .map(|(l, st)| l.pose(st))
            .collect();
        let points = self
            .inst
            .points
            .iter()
            .map(|&(o, d)| point_pose(&s, o, d))
            .collect();
        Ok(Pose {
            links,
            points,
            model: self.model.clone(),
        })
    }

    /// Positions, velocities and accelerations at (q, q̇, q̈).
    pub fn kinematics(&self, q: &[f64], qd: &[f64], qdd: &[f64]) -> Result<Motion, MechError> {
        let mut m = Motion {
            links: Vec::new(),
            points: Vec::new(),
            inputs: SmallVec::new(),
            states: Vec::new(),
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
        self.solve_into(q, qd, qdd, Level::Acceleration, &mut out.states)?;
        crate::kernel::finite::finite_states(&out.states, Level::Acceleration)?;
        let s = &out.states;
        out.links.clear();
        out.links
            .extend(self.inst.links.iter().zip(s).map(|(l, st)| l.motion(st)));
        out.points.clear();
        out.points
            .extend(self.inst.points.iter().map(|&(o, d)| point_motion(s, o, d)));
        crate::kernel::finite::finite_motion(&out.links, &out.points)?;
        out.inputs.clear();
        out.inputs.extend_from_slice(q);
        out.inputs.extend_from_slice(qd);
        out.inputs.extend_from_slice(qdd);
        if !Arc::ptr_eq(&out.model, &self.model) {
            out.model = self.model.clone();
        }
        Ok(())
    }
}

/// The plan's dispatch: the one place where a group's kernel is matched to its entry
/// point, for positions (and rates, accelerations up to `upto`), the unit-rate velocity
/// field of virtual power, and the reactions. The generated code calls the same entry
/// points, unrolled.
impl Mechanism {
    /// Solve group `g` on assembly branch `sign` at the inputs `drive`, up to `upto`.
    #[inline]
    pub(super) fn group_positions(
        &self,
        g: &Group,
        sign: f64,
        drive: Drive,
        upto: Level,
        s: &mut [LinkState],
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
                crate::elements::gears::solve_train(t, &self.inst.meshes, joints, s, upto)?
            }
            Kernel::Rolling(r) => crate::elements::rolling::solve_rolling(
                r, joints, s, drive, sign, scale, upto, true,
            )?,
            Kernel::Cam(c) => crate::elements::cam::solve_cam(c, &self.inst.cams, joints, s, upto)?,
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
                    None,
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
            Kernel::Driven(d) => screw::driven_rates(d, joints, v, drive, Level::Velocity)?,
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
                &self.inst.meshes,
                joints,
                v,
                Level::Velocity,
            )?,
            Kernel::Cam(c) => {
                crate::elements::cam::solve_cam(c, &self.inst.cams, joints, v, Level::Velocity)?
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
                crate::elements::cam::cam_reactions(c, &self.inst.cams, joints, s, f, r)?
            }
            Kernel::Rolling(k) => {
                crate::elements::rolling::rolling_reactions(k, joints, s, f, scale, r, driver)?
            }
            Kernel::System => system(g, |n| n.reactions(g, joints, s, f, scale, r, driver))?,
        }
        Ok(())
    }
}
