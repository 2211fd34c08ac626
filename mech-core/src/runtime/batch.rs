//! Many configurations per call on the run-time [`Mechanism`] (`docs/batch.md`): the
//! `*_many` methods of the generated structs, with the inputs of G-input mechanisms laid
//! out configuration after configuration (`q[i·G + k]` is input k of configuration i).
//!
//! Each chunk of the batch keeps one buffer of link states (and one [`Motion`]), so a batch
//! allocates a few buffers per thread, not one per configuration.

use super::mechanism::{Mechanism, Scratch};
use super::results::{Forces, Loads, Motion, Pose};
use crate::kernel::constraints::Level;
use crate::kernel::lanes::{
    acceleration_lanes, or, point_lanes, solve_chain_lanes, solve_driven_lanes, Backend, Base,
    LinkLanes, Mask, Wide, ZhukovskiLanes, L, NONE,
};
use crate::kernel::link_state::{LinkPose, LinkState, PointPose};
use crate::plan::assur::Kernel;
use crate::solvers::batch::{
    each, each_lanes, each_with, kinematics_columns, kinetostatics_columns, put_kinematics,
    put_kinetostatics, refuse, same_len, BatchErrors, Block, Nan, Table,
};
use crate::solvers::traits::OneDof;
use crate::MechError;
use smallvec::SmallVec;

impl Nan for Pose {
    fn set_nan(&mut self) {
        self.links.iter_mut().for_each(Nan::set_nan);
        self.points.iter_mut().for_each(Nan::set_nan);
    }
}

/// Four consecutive values from `x[i]` as one lane value.
#[inline(always)]
fn four<B: Backend>(x: &[f64], i: usize) -> L<B> {
    L::new([x[i], x[i + 1], x[i + 2], x[i + 3]])
}

/// The lane states of a mechanism's links, on the stack up to eight links.
type LaneStates<B> = smallvec::SmallVec<[LinkLanes<B>; 8]>;

/// The most points the run-time `points_many` takes four configurations at once (more go
/// one by one).
const MAX_LANE_POINTS: usize = 16;

/// The number of configurations in `q` (G values each); refused when G does not divide it.
fn configs(q: &[f64], g: usize) -> Result<usize, MechError> {
    if g == 0 || q.len() % g != 0 {
        return Err(MechError::InvalidInput(format!(
            "`q` has {} values, not a multiple of the {g} inputs: give G values per configuration",
            q.len()
        )));
    }
    Ok(q.len() / g)
}

/// Configuration i's G inputs.
#[inline]
fn inputs(x: &[f64], g: usize, i: usize) -> &[f64] {
    &x[i * g..(i + 1) * g]
}

impl Mechanism {
    /// A pose with NaN everywhere and this mechanism's links and points: the element of the
    /// output of [`Mechanism::pose_many`] (`vec![m.nan_pose(); n]`).
    pub fn nan_pose(&self) -> Pose {
        let mut p = Pose {
            links: vec![Default::default(); self.inst.links.len()],
            points: vec![Default::default(); self.inst.points.len()],
            model: self.model.clone(),
        };
        p.set_nan();
        p
    }

    /// [`Mechanism::pose`] for every configuration of `q` (G values each) into `out` (one
    /// pose per configuration, reused: its vectors are refilled, not reallocated once they
    /// have the mechanism's sizes). A configuration that fails gets NaN and its index in the
    /// returned [`BatchErrors`].
    pub fn pose_many(&self, q: &[f64], out: &mut [Pose]) -> BatchErrors {
        let g = self.dof();
        let rows = match configs(q, g).and_then(|n| Ok((n, Block::new("out", out, 1, n)?))) {
            Ok(r) => r,
            Err(e) => return refuse(e),
        };
        let zero: Scratch<f64> = SmallVec::from_elem(0.0, g);
        each_with(
            rows.0,
            rows.1,
            Vec::<LinkState>::new,
            |i, r: &mut Block<Pose>, s| {
                let qi = inputs(q, g, i);
                self.solve_into(qi, &zero, &zero, Level::Position, s)?;
                crate::kernel::finite::finite_states(s, Level::Position)?;
                let p = r.at(i);
                p.links.resize(s.len(), Default::default());
                p.links[0] = LinkPose {
                    angle: self.program.ground.angle,
                    cg: self.program.ground.cg,
                };
                for &l in &self.program.angle_order {
                    let o = self.link_pose(l, &s[l], qi, |m| p.links[m].angle);
                    p.links[l] = o;
                }
                p.points.clear();
                p.points
                    .extend((0..self.inst.points.len()).map(|k| PointPose {
                        pos: self.point_at(s, k),
                    }));
                p.model = self.model.clone();
                Ok(())
            },
        )
    }

    /// The points of every configuration of `q` (G values each) into `out`: x and y (m) of
    /// each point in declaration order, configuration after configuration (2 × points
    /// values per configuration). A configuration that fails gets NaN and its index in the
    /// returned [`BatchErrors`].
    pub fn points_many(&self, q: &[f64], out: &mut [f64]) -> BatchErrors {
        let (g, np) = (self.dof(), self.inst.points.len());
        let rows = match configs(q, g).and_then(|n| Ok((n, Block::new("out", out, 2 * np, n)?))) {
            Ok(r) => r,
            Err(e) => return refuse(e),
        };
        if self.lanes && g == 1 && np <= MAX_LANE_POINTS {
            return each_lanes(
                rows.0,
                rows.1,
                &(),
                #[inline(always)]
                |_: &(), i, r: &mut Block<f64>| self.points_four::<Base>(q, i, r),
                #[inline(always)]
                |_: &(), i, r: &mut Block<f64>| self.points_four::<Wide>(q, i, r),
                |i, r: &mut Block<f64>| self.points_into(&q[i..i + 1], &mut Vec::new(), r.row(i)),
            );
        }
        each_with(
            rows.0,
            rows.1,
            Vec::<LinkState>::new,
            |i, r: &mut Block<f64>, s| self.points_into(inputs(q, g, i), s, r.row(i)),
        )
    }

    /// The motor actions by virtual power ([`Mechanism::driver_action`]) at every
    /// configuration (q, q̇, q̈) (G values each) into `out` (G values per configuration: N·m
    /// or N). A configuration that fails gets NaN and its index in the returned
    /// [`BatchErrors`].
    pub fn driver_action_many(
        &self,
        q: &[f64],
        qd: &[f64],
        qdd: &[f64],
        loads: &Loads,
        out: &mut [f64],
    ) -> BatchErrors {
        let g = self.dof();
        let rows = match configs(q, g).and_then(|n| {
            same_len(&[("qd", qd.len()), ("qdd", qdd.len())], q.len())?;
            Ok((n, Block::new("out", out, g, n)?))
        }) {
            Ok(r) => r,
            Err(e) => return refuse(e),
        };
        each_with(
            rows.0,
            rows.1,
            || self.empty_motion(),
            |i, r: &mut Block<f64>, m| {
                let (qi, qdi, qddi) = (inputs(q, g, i), inputs(qd, g, i), inputs(qdd, g, i));
                self.kinematics_into(qi, qdi, qddi, m)?;
                r.row(i).copy_from_slice(&self.driver_action(m, loads)?);
                Ok(())
            },
        )
    }

    /// Zhukovski's I* (kg·m²) and dI*/dq (kg·m²/rad) at every q of a one-input mechanism,
    /// into `inertia` and `derivative` (one value per configuration). A configuration that
    /// fails gets NaN in both and its index in the returned [`BatchErrors`].
    pub fn reduced_many(
        &self,
        q: &[f64],
        inertia: &mut [f64],
        derivative: &mut [f64],
    ) -> BatchErrors {
        let n = q.len();
        let rows = match self.one_input().and_then(|()| {
            Ok((
                Block::new("inertia", inertia, 1, n)?,
                Block::new("derivative", derivative, 1, n)?,
            ))
        }) {
            Ok(r) => r,
            Err(e) => return refuse(e),
        };
        let one = |i: usize, (a, b): &mut (Block<f64>, Block<f64>)| {
            let z = OneDof::reduced(self, q[i])?;
            *a.at(i) = z.inertia;
            *b.at(i) = z.inertia_derivative;
            Ok(())
        };
        if !self.lanes {
            return each(n, rows, one);
        }
        each_lanes(
            n,
            rows,
            &(),
            #[inline(always)]
            |_: &(), i, r: &mut (Block<f64>, Block<f64>)| self.reduced_four::<Base>(q, i, r),
            #[inline(always)]
            |_: &(), i, r: &mut (Block<f64>, Block<f64>)| self.reduced_four::<Wide>(q, i, r),
            one,
        )
    }

    /// The direct problem's q̈ (rad/s²) at every (q, q̇, driver) of a one-input mechanism
    /// ([`OneDof::acceleration`]) into `out`. A configuration that fails gets NaN and its
    /// index in the returned [`BatchErrors`].
    pub fn acceleration_many(
        &self,
        q: &[f64],
        qd: &[f64],
        driver: &[f64],
        loads: &Loads,
        out: &mut [f64],
    ) -> BatchErrors {
        let n = q.len();
        let rows = match self.one_input().and_then(|()| {
            same_len(&[("qd", qd.len()), ("driver", driver.len())], n)?;
            Block::new("out", out, 1, n)
        }) {
            Ok(r) => r,
            Err(e) => return refuse(e),
        };
        let one = |i: usize, r: &mut Block<f64>| {
            *r.at(i) = OneDof::acceleration(self, q[i], qd[i], driver[i], loads)?;
            Ok(())
        };
        if !self.lanes {
            return each(n, rows, one);
        }
        let four = (q, qd, driver, loads);
        each_lanes(
            n,
            rows,
            &(),
            #[inline(always)]
            |_: &(), i, r: &mut Block<f64>| self.acceleration_four::<Base>(four, i, r),
            #[inline(always)]
            |_: &(), i, r: &mut Block<f64>| self.acceleration_four::<Wide>(four, i, r),
            one,
        )
    }

    /// A table for [`Mechanism::kinematics_many`] of `n` configurations, every value NaN:
    /// the columns of [`kinematics_columns`] (every point's `<point>.x`, `.y`, every moving
    /// link's `<link>.angle`, the points' `.vx`, `.vy`, `.ax`, `.ay`, the links' `.omega`,
    /// `.alpha`; SI units), made once and reused.
    pub fn kinematics_table(&self, n: usize) -> Table {
        Table::with_columns(|c| kinematics_columns(&self.model, c), n)
    }

    /// A table for [`Mechanism::kinetostatics_many`] of `n` configurations, every value
    /// NaN: the columns of [`kinetostatics_columns`] (every joint's `<joint>.fx`, `.fy`, a
    /// prismatic joint's `.moment`, then `driver` or `driver.<joint>`; SI units).
    pub fn kinetostatics_table(&self, n: usize) -> Table {
        Table::with_columns(|c| kinetostatics_columns(&self.model, c), n)
    }

    /// [`Mechanism::kinematics`] at every configuration (q, q̇, q̈) (G values each) into the
    /// table `out` ([`Mechanism::kinematics_table`] of as many configurations), structure
    /// of arrays: `out.column("B.x")` holds every configuration's x of B. A configuration
    /// that fails gets NaN in every column and its index in the returned [`BatchErrors`];
    /// slices of different lengths or a table of another size or mechanism are refused.
    /// One motion buffer per chunk.
    pub fn kinematics_many(
        &self,
        q: &[f64],
        qd: &[f64],
        qdd: &[f64],
        out: &mut Table,
    ) -> BatchErrors {
        let g = self.dof();
        let rows = match configs(q, g).and_then(|n| {
            same_len(&[("qd", qd.len()), ("qdd", qdd.len())], q.len())?;
            Ok((
                n,
                out.configurations("kinematics", |c| kinematics_columns(&self.model, c), n)?,
            ))
        }) {
            Ok(r) => r,
            Err(e) => return refuse(e),
        };
        each_with(
            rows.0,
            rows.1,
            || self.empty_motion(),
            |i, r, m| {
                let (qi, qdi, qddi) = (inputs(q, g, i), inputs(qd, g, i), inputs(qdd, g, i));
                self.kinematics_into(qi, qdi, qddi, m)?;
                put_kinematics(r, i, m.points.iter(), m.links[1..].iter());
                Ok(())
            },
        )
    }

    /// [`Mechanism::kinetostatics`] (d'Alembert) at every configuration (q, q̇, q̈) (G
    /// values each) with the same loads into the table `out`
    /// ([`Mechanism::kinetostatics_table`]): every reaction and the motor actions, one
    /// column each. A configuration that fails gets NaN in every column and its index in
    /// the returned [`BatchErrors`]; a mechanism with redundant constraints (no reactions),
    /// slices of different lengths or a table of another size or mechanism are refused.
    pub fn kinetostatics_many(
        &self,
        q: &[f64],
        qd: &[f64],
        qdd: &[f64],
        loads: &Loads,
        out: &mut Table,
    ) -> BatchErrors {
        if self.redundant() {
            return refuse(MechError::Redundant(
                "this mechanism has redundant constraints (`#[allow(redundant)]`): its reactions are statically indeterminate; call `driver_action_many` (virtual power)".into(),
            ));
        }
        let g = self.dof();
        let rows = match configs(q, g).and_then(|n| {
            same_len(&[("qd", qd.len()), ("qdd", qdd.len())], q.len())?;
            Ok((
                n,
                out.configurations(
                    "kinetostatics",
                    |c| kinetostatics_columns(&self.model, c),
                    n,
                )?,
            ))
        }) {
            Ok(r) => r,
            Err(e) => return refuse(e),
        };
        let scratch = || {
            let f = Forces {
                driver: Vec::new(),
                joints: Vec::new(),
                model: self.model.clone(),
            };
            (self.empty_motion(), f)
        };
        each_with(rows.0, rows.1, scratch, |i, r, (m, f)| {
            let (qi, qdi, qddi) = (inputs(q, g, i), inputs(qd, g, i), inputs(qdd, g, i));
            self.kinematics_into(qi, qdi, qddi, m)?;
            self.kinetostatics_into(m, loads, None, f)?;
            put_kinetostatics(
                r,
                i,
                f.joints.iter().map(|j| (j.force, j.moment)),
                &f.driver,
            );
            Ok(())
        })
    }

    /// A motion with empty buffers: the scratch of a chunk.
    pub(super) fn empty_motion(&self) -> Motion {
        Motion {
            links: Vec::new(),
            points: Vec::new(),
            inputs: SmallVec::new(),
            states: Vec::new(),
            systems: Vec::new(),
            model: self.model.clone(),
        }
    }

    /// `points_many`'s four configurations from `q[i]` on backend `B`: the points of the
    /// lanes not masked into their rows, and the mask.
    #[inline(always)]
    fn points_four<B: Backend>(&self, q: &[f64], i: usize, r: &mut Block<f64>) -> Mask {
        let np = self.inst.points.len();
        let zero = L::<B>::splat(0.0);
        let (s, mut mask) = self.solve_lanes(four(q, i), zero, zero, Level::Position);
        let mut sum = zero;
        let mut xy = [[zero; 2]; MAX_LANE_POINTS];
        for (k, &(o, d)) in self.inst.points.iter().enumerate() {
            xy[k] = point_lanes(&s, o, d);
            sum = sum + xy[k][0] + xy[k][1];
        }
        // A NaN or infinite coordinate makes the sum non-finite.
        mask = or(mask, sum.not_finite());
        for (lane, masked) in mask.lanes().into_iter().enumerate() {
            if !masked {
                let row = r.row(i + lane);
                for (k, p) in xy[..np].iter().enumerate() {
                    row[2 * k] = p[0].0[lane];
                    row[2 * k + 1] = p[1].0[lane];
                }
            }
        }
        mask
    }

    /// `reduced_many`'s four configurations from `q[i]` on backend `B`.
    #[inline(always)]
    fn reduced_four<B: Backend>(
        &self,
        q: &[f64],
        i: usize,
        (a, b): &mut (Block<f64>, Block<f64>),
    ) -> Mask {
        let (one, zero) = (L::<B>::splat(1.0), L::splat(0.0));
        let (s, mask) = self.solve_lanes(four(q, i), one, zero, Level::Acceleration);
        let z = self.sums_lanes(&s, None);
        let bad = or(z.inertia.not_finite(), z.inertia_derivative.not_finite());
        let mask = or(mask, bad);
        for (lane, masked) in mask.lanes().into_iter().enumerate() {
            if !masked {
                *a.at(i + lane) = z.inertia.0[lane];
                *b.at(i + lane) = z.inertia_derivative.0[lane];
            }
        }
        mask
    }

    /// `acceleration_many`'s four configurations from index `i` of (q, q̇, driver) with
    /// `loads` on backend `B`.
    #[inline(always)]
    fn acceleration_four<B: Backend>(
        &self,
        (q, qd, driver, loads): (&[f64], &[f64], &[f64], &Loads),
        i: usize,
        r: &mut Block<f64>,
    ) -> Mask {
        let (one, zero) = (L::<B>::splat(1.0), L::splat(0.0));
        let (s, mask) = self.solve_lanes(four(q, i), one, zero, Level::Acceleration);
        let z = self.sums_lanes(&s, Some(loads));
        let (acc, failed) = acceleration_lanes(&z, four(qd, i), four(driver, i));
        let mask = or(mask, failed);
        for (lane, masked) in mask.lanes().into_iter().enumerate() {
            if !masked {
                *r.at(i + lane) = acc.0[lane];
            }
        }
        mask
    }

    /// Four configurations of a one-input mechanism through the lane kernels of its plan
    /// (every group a driven crank or slider, an RRR or an RRP dyad: `Mechanism::lanes`),
    /// and the mask of the lanes the one-configuration solver must redo.
    #[inline(always)]
    fn solve_lanes<B: Backend>(
        &self,
        q: L<B>,
        qd: L<B>,
        qdd: L<B>,
        upto: Level,
    ) -> (LaneStates<B>, Mask) {
        let mut s = LaneStates::from_elem(LinkLanes::default(), self.inst.links.len());
        let joints = &self.inst.joints[..];
        let mut mask = NONE;
        let (q, qd, qdd) = ([q], [qd], [qdd]);
        for (g, &sign) in self.plan.iter().zip(&self.branches) {
            let m = match &g.kernel {
                Kernel::Driven(d) => {
                    solve_driven_lanes(g.solver, d, joints, &mut s, &q, &qd, &qdd, upto)
                }
                _ => solve_chain_lanes(g.solver, joints, &mut s, sign, self.inst.scale, upto),
            };
            mask = or(mask, m);
        }
        (s, mask)
    }

    /// Zhukovski's sums over four configurations' motion with q̇ = 1, q̈ = 0: the lane twin
    /// of the run-time sums (no force element: `Mechanism::lanes`); M* only with `loads`.
    #[inline(always)]
    fn sums_lanes<B: Backend>(
        &self,
        s: &[LinkLanes<B>],
        loads: Option<&Loads>,
    ) -> ZhukovskiLanes<B> {
        let mut z = ZhukovskiLanes::new();
        for (l, t) in self.terms.iter().enumerate().skip(1) {
            let geom = &self.inst.links[l];
            if t.inertia() {
                if self.pinned[l] {
                    z.inertia_about_pivot(geom, &s[l]);
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
            // As the scalar `sums`.
            self.load_terms(&mut z, &|l| &s[l], loads);
        }
        z
    }

    fn one_input(&self) -> Result<(), MechError> {
        match self.dof() {
            1 => Ok(()),
            g => Err(MechError::InvalidInput(format!(
                "Zhukovski's reduction needs one input, the mechanism has {g}: use driver_action_many"
            ))),
        }
    }
}

impl<B: Backend> super::forces::LoadTerms<LinkLanes<B>> for ZhukovskiLanes<B> {
    #[inline(always)]
    fn force(
        &mut self,
        s: &LinkLanes<B>,
        d: crate::kernel::link_state::V2,
        f: crate::kernel::link_state::V2,
    ) {
        ZhukovskiLanes::force(self, s, d, f)
    }
    #[inline(always)]
    fn force_translating(&mut self, s: &LinkLanes<B>, f: crate::kernel::link_state::V2) {
        ZhukovskiLanes::force_translating(self, s, f)
    }
    #[inline(always)]
    fn torque(&mut self, s: &LinkLanes<B>, t: f64) {
        ZhukovskiLanes::torque(self, s, t)
    }
}
