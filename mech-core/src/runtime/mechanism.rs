//! The run-time mechanism: a mechanism known only when the program runs (DSL text, a file, a
//! [`Model`] built in code), solved by executing the same Assur plan with the same kernels
//! as the struct the `mechanism!` macro generates.
//!
//! Loading runs the macro's pipeline (resolution, every check, the Assur plan, the drawing's
//! branches); each solver then walks the plan group by group — [`kinematics::solve_driven`]
//! for a driven crank or slider, [`kinematics::solve_chain`] for a closed-form dyad or slot
//! group (rates and reactions by joint screws, `docs/theory.md` §3.4), Newton and a
//! fixed-size LU ([`crate::kernel::group::group_solve`]) for a group with no closed form — into a buffer of
//! link states the caller may keep ([`Mechanism::solve_into`]: no allocation once it has
//! grown). Same accuracy, same `Singular`/`NoAssembly` behaviour and the same branch rule as
//! the generated struct, which the tests check to 1e-12 on every reference machine.
//!
//! A `Mechanism` implements [`Machine`] and, with one input, [`OneDof`], so every algorithm
//! of mech-core (the direct problem, the energy method, Quinn, Lagrange, flywheel sizing)
//! takes it. The dense whole-system solver [`crate::runtime::generic::GenericMechanism`] stays as an
//! independent cross-check.
//!
//! A mechanism accepted with redundant constraints (`#[allow(redundant)]`) is solved as the
//! generated struct solves it (least squares in its redundant groups, the other branches
//! tried past a change point) and has no reactions (`MechError::Redundant`), only the motor
//! actions. Limits: a group of more than six links or more than three redundant equations
//! is refused at loading with [`MechError::InvalidInput`] (use `GenericMechanism`).

use crate::kernel::constraints::{Drive, Level};
use crate::kernel::group::{group_solve, group_velocity_field, GroupSystem};
use crate::kernel::kinematics;
use crate::kernel::kinetostatics::{
    add_force, add_gravity, add_inertia, add_torque, group_reactions, lambda_reactions,
    PrismaticReaction, Reaction, RevoluteReaction, Wrench,
};
use crate::kernel::link_state::{
    point_motion, point_pose, LinkMotion, LinkPose, LinkState, PointMotion, PointPose, V2,
};
use crate::kernel::screw;
use crate::model::{JointKind, Load, Model};
use crate::plan::assur::{Group, Kernel};
use crate::runtime::generic::{JointReaction, LoadValue};
use crate::solvers::friction::{add_joint_friction, flat_len, iterate, Flattener, JointFriction};
use crate::solvers::instance::{instance, Instance};
use crate::solvers::params::LinkTerms;
use crate::solvers::traits::{Machine, OneDof};
use crate::solvers::zhukovski::{Reduced, Reduction};
use crate::MechError;
use smallvec::{smallvec, SmallVec};
use std::path::Path;
use std::sync::Arc;

/// Per-call temporaries on the stack for mechanisms of up to 8 links or joints.
type Scratch<T> = SmallVec<[T; 8]>;

/// The largest group (in links) the run-time interpreter solves with a fixed-size system.
pub const MAX_GROUP_LINKS: usize = 6;

/// The most redundant equations a group may have (`#[allow(redundant)]`).
pub const MAX_REDUNDANT_ROWS: usize = 3;

/// A mechanism loaded at run time and solved with the generated code's plan and kernels
/// (module docs).
#[derive(Clone, Debug)]
pub struct Mechanism {
    model: Arc<Model>,
    inst: Instance,
    plan: Vec<Group>,
    branches: Vec<f64>,
    terms: Vec<LinkTerms>,
    /// Per link: it turns about its anchor on a ground pin ([`Model::pinned_at_anchor`]).
    pinned: Vec<bool>,
    /// Per link: it slides on the ground ([`Model::translates`]).
    translates: Vec<bool>,
    /// Some group has no closed form (Newton, started from the drawing).
    newton: bool,
}

/// The values of a run-time mechanism's loads, in declaration order. [`Mechanism::loads`]
/// makes them all zero with the names; `Default` is "no load" (every load zero).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Loads {
    /// One value per declared load (declaration order); missing entries count as zero.
    pub values: Vec<LoadValue>,
    model: Option<Arc<Model>>,
}

impl Loads {
    /// Set the load named `name` from its components (2 for a force, N; 1 for a torque,
    /// N·m); false when there is no such load or the length is wrong.
    pub fn set_by_name(&mut self, name: &str, value: &[f64]) -> bool {
        match &self.model {
            Some(model) => crate::runtime::generic::set_load(model, &mut self.values, name, value),
            None => false,
        }
    }
}

/// Result of [`Mechanism::pose`]: every link's angle (rad) and cg (m), every point (m),
/// indexed like [`Model::links`] (0 = the ground) and [`Model::points`].
#[derive(Clone, Debug, PartialEq)]
pub struct Pose {
    /// Links, ground first.
    pub links: Vec<LinkPose>,
    /// Points.
    pub points: Vec<PointPose>,
    model: Arc<Model>,
}

impl Pose {
    /// The pose of the link named `name`, if any.
    pub fn link(&self, name: &str) -> Option<&LinkPose> {
        self.model.link_index(name).map(|l| &self.links[l])
    }
    /// The position of the point named `name`, if any.
    pub fn point(&self, name: &str) -> Option<&PointPose> {
        self.model.point_index(name).map(|p| &self.points[p])
    }
}

/// Result of [`Mechanism::kinematics`]: positions, velocities, accelerations of every link
/// and point (indexed like the model), and the input values.
#[derive(Clone, Debug, PartialEq)]
pub struct Motion {
    /// Links, ground first: θ, ω, α, cg and its velocity and acceleration.
    pub links: Vec<LinkMotion>,
    /// Points: position, velocity, acceleration.
    pub points: Vec<PointMotion>,
    /// q, q̇ and q̈ of this motion, one after the other (G values each).
    inputs: SmallVec<[f64; 12]>,
    states: Vec<LinkState>,
    model: Arc<Model>,
}

impl Motion {
    /// The input values q (rad or m) of this motion.
    pub fn q(&self) -> &[f64] {
        &self.inputs[..self.inputs.len() / 3]
    }
    /// The input rates q̇.
    pub fn qd(&self) -> &[f64] {
        let g = self.inputs.len() / 3;
        &self.inputs[g..2 * g]
    }
    /// The input accelerations q̈.
    pub fn qdd(&self) -> &[f64] {
        &self.inputs[2 * self.inputs.len() / 3..]
    }
    /// The motion of the link named `name`, if any.
    pub fn link(&self, name: &str) -> Option<&LinkMotion> {
        self.model.link_index(name).map(|l| &self.links[l])
    }
    /// The motion of the point named `name`, if any.
    pub fn point(&self, name: &str) -> Option<&PointMotion> {
        self.model.point_index(name).map(|p| &self.points[p])
    }
}

/// Result of [`Mechanism::kinetostatics`]: the motor action of each input and the reaction
/// at every joint (force BY a ON b, N; a prismatic joint's moment about its point, N·m).
#[derive(Clone, Debug, PartialEq)]
pub struct Forces {
    /// Motor actions: torque (N·m) or axial force (N) by a on b.
    pub driver: Vec<f64>,
    /// Reactions, indexed like [`Model::joints`].
    pub joints: Vec<JointReaction>,
    model: Arc<Model>,
}

impl Forces {
    /// The reaction at the joint named `name`: force by a on b (N) and, for a prismatic
    /// joint, the moment (N·m) — the shape of a generated `<Name>Forces::reaction`.
    pub fn reaction(&self, name: &str) -> Option<(V2, Option<f64>)> {
        self.model
            .joint_index(name)
            .map(|j| (self.joints[j].force, self.joints[j].moment))
    }
}

impl Mechanism {
    /// Load from DSL text (the body of a `mechanism! { ... }`): the macro's parse,
    /// resolution and checks; every problem reported together with its line and column.
    pub fn from_dsl(text: &str) -> Result<Self, MechError> {
        Self::from_checked(crate::runtime::generic::parse_model(text, None)?)
    }

    /// [`Mechanism::from_dsl`] of the text of a file named `origin`: every message starts
    /// with `origin:LINE:COLUMN:`.
    pub fn from_dsl_named(text: &str, origin: &str) -> Result<Self, MechError> {
        Self::from_checked(crate::runtime::generic::parse_model(text, Some(origin))?)
    }

    /// Load the mechanism `name` declared with `mechanism!` in Rust source text.
    pub fn from_rust_source(source: &str, name: &str) -> Result<Self, MechError> {
        Self::from_checked(crate::runtime::generic::rust_source_model(source, name)?)
    }

    /// Load from a file of DSL text; messages name the file.
    pub fn load(path: impl AsRef<Path>) -> Result<Self, MechError> {
        let path = path.as_ref();
        let text = std::fs::read_to_string(path)
            .map_err(|e| MechError::Invalid(format!("cannot read {}: {e}", path.display())))?;
        Self::from_dsl_named(&text, &path.display().to_string())
    }

    /// A mechanism from a resolved [`Model`]: every check of the macro, the Assur plan and
    /// the drawing's branches. [`MechError::Invalid`] when a check fails,
    /// [`MechError::InvalidInput`] for what the interpreter does not take (module docs).
    pub fn from_model(model: Model) -> Result<Self, MechError> {
        let issues = crate::checks::validate::check(&model);
        if !issues.is_empty() {
            return Err(MechError::Invalid(
                issues
                    .iter()
                    .map(|i| i.message.as_str())
                    .collect::<Vec<_>>()
                    .join("\n"),
            ));
        }
        Self::from_checked(model)
    }

    /// [`Mechanism::from_model`] of a model that passed every check already.
    fn from_checked(model: Model) -> Result<Self, MechError> {
        let plan = crate::plan::assur::plan(&model).map_err(|_| {
            MechError::Invalid("the links cannot be solved group by group from the inputs".into())
        })?;
        if let Some(g) = plan.iter().find(|g| {
            g.bodies.len() > MAX_GROUP_LINKS || g.rows() > 3 * g.bodies.len() + MAX_REDUNDANT_ROWS
        }) {
            let names: Vec<&str> = g
                .bodies
                .iter()
                .map(|&b| model.links[b].name.as_str())
                .collect();
            return Err(MechError::InvalidInput(format!(
                "the group of links {} has {} links and {} equations: the run-time interpreter takes groups of at most {MAX_GROUP_LINKS} links with at most {MAX_REDUNDANT_ROWS} redundant equations; load it with `GenericMechanism`",
                names.join(", "),
                g.bodies.len(),
                g.rows()
            )));
        }
        let inst = instance(&model)?;
        let solvers: Vec<_> = plan.iter().map(|g| g.solver).collect();
        let branches = inst.branches(&solvers);
        let terms = model.links.iter().map(LinkTerms::of).collect();
        let pinned = (0..model.links.len())
            .map(|l| model.pinned_at_anchor(l))
            .collect();
        let translates = (0..model.links.len())
            .map(|l| model.translates(l))
            .collect();
        let newton = plan.iter().any(|g| g.kernel == Kernel::System);
        Ok(Mechanism {
            model: Arc::new(model),
            inst,
            plan,
            branches,
            terms,
            pinned,
            translates,
            newton,
        })
    }

    /// Change one number of the drawing by name, re-validated by every check of the
    /// loading (the mechanism is unchanged on error):
    /// - `points.<P>` = `[x, y]` (m), `links.<l>.cg` = `[x, y]` (m),
    /// - `links.<l>.mass` = `[m]` (kg; a link declared without mass gets every term),
    ///   `links.<l>.inertia` = `[I_G]` (kg·m²), `links.<l>.flywheel` = `[I]` (kg·m², a rotor
    ///   keyed to the link, added to its rotational inertia),
    /// - `axes.<joint>` = `[ux, uy]` (a prismatic or slot joint's axis),
    /// - `elements.<e>.stiffness`, `.free_length` (a spring, N/m and m),
    ///   `.free_angle` (a torsion spring, rad), `.damping` (a damper, N·s/m or N·m·s/rad),
    /// - `gravity` = `[gx, gy]` (m/s²; `[]` removes it).
    ///
    /// The run-time counterpart of a generated struct's `from_params`.
    pub fn set_param(&mut self, path: &str, value: &[f64]) -> Result<(), MechError> {
        crate::error::check_finite(path, value)?;
        let mut model = (*self.model).clone();
        let bad = |what: &str| MechError::InvalidInput(format!("no parameter `{path}`: {what}"));
        let pair = |v: &[f64]| -> Result<[f64; 2], MechError> {
            match v {
                [x, y] => Ok([*x, *y]),
                _ => Err(MechError::InvalidInput(format!(
                    "`{path}` takes 2 numbers, got {}",
                    v.len()
                ))),
            }
        };
        let one = |v: &[f64]| -> Result<f64, MechError> {
            match v {
                [x] => Ok(*x),
                _ => Err(MechError::InvalidInput(format!(
                    "`{path}` takes 1 number, got {}",
                    v.len()
                ))),
            }
        };
        let parts: Vec<&str> = path.split('.').collect();
        match parts.as_slice() {
            ["points", p] => {
                let i = model.point_index(p).ok_or_else(|| bad("unknown point"))?;
                model.points[i].pos = pair(value)?;
            }
            ["links", l, what] => {
                let i = model
                    .link_index(l)
                    .filter(|&i| i > 0)
                    .ok_or_else(|| bad("unknown moving link"))?;
                let link = &mut model.links[i];
                match *what {
                    "cg" => link.cg = pair(value)?,
                    "mass" => link.mass = Some(one(value)?),
                    "inertia" => link.inertia = one(value)?,
                    "flywheel" => link.flywheel = one(value)?,
                    _ => return Err(bad("a link has `cg`, `mass`, `inertia` and `flywheel`")),
                }
            }
            ["axes", j] => {
                let i = model.joint_index(j).ok_or_else(|| bad("unknown joint"))?;
                if model.joints[i].kind == JointKind::Revolute {
                    return Err(bad("a revolute joint has no axis"));
                }
                model.joints[i].axis = pair(value)?;
            }
            ["elements", e, what] => {
                let el = model
                    .elements
                    .iter_mut()
                    .find(|el| el.name == *e)
                    .ok_or_else(|| bad("unknown force element"))?;
                match (*what, el.kind.spring()) {
                    ("stiffness", true) => el.stiffness = one(value)?,
                    ("free_length", true) if el.kind.linear() => el.free = one(value)?,
                    ("free_angle", true) if !el.kind.linear() => el.free = one(value)?,
                    ("damping", false) => el.damping = one(value)?,
                    _ => {
                        return Err(bad(if el.kind.spring() {
                            "a spring has `stiffness` and `free_length` (`free_angle` for a torsion spring)"
                        } else {
                            "a damper has `damping`"
                        }))
                    }
                }
            }
            ["gravity"] => {
                model.gravity = if value.is_empty() {
                    None
                } else {
                    Some(pair(value)?)
                }
            }
            _ => {
                return Err(bad(
                    "use points.<P>, links.<l>.{cg, mass, inertia, flywheel}, axes.<joint>, elements.<e>.{stiffness, free_length, free_angle, damping} or gravity",
                ))
            }
        }
        *self = Mechanism::from_model(model)?;
        Ok(())
    }

    /// The resolved model (names, topology and the drawing's numbers).
    pub fn model(&self) -> &Model {
        &self.model
    }

    /// The cams, in joint order: each cam joint's name and geometry (its
    /// [`crate::elements::cam::Profile`]: law, base circle, follower, face), as the generated
    /// struct's `cams()`.
    pub fn cams(&self) -> Vec<(&str, &crate::elements::cam::CamGeom)> {
        self.model
            .joints
            .iter()
            .filter(|j| j.kind == crate::model::JointKind::Cam)
            .map(|j| j.name.as_str())
            .zip(&self.inst.cams)
            .collect()
    }

    /// The cam joint `name`, or the mechanism's only cam when `name` is `None`, with its
    /// geometry; `InvalidInput` naming the cams there are when there is no such cam (or
    /// several and no name).
    pub fn cam(
        &self,
        name: Option<&str>,
    ) -> Result<(&str, &crate::elements::cam::CamGeom), MechError> {
        let cams = self.cams();
        let list = || {
            cams.iter()
                .map(|(n, _)| format!("`{n}`"))
                .collect::<Vec<_>>()
                .join(", ")
        };
        let found = match name {
            Some(n) => cams.iter().find(|(c, _)| *c == n),
            None if cams.len() == 1 => cams.first(),
            None => None,
        };
        found.copied().ok_or_else(|| {
            MechError::InvalidInput(match (name, cams.len()) {
                (_, 0) => "the mechanism has no cam (a `cam(..)` joint)".to_string(),
                (Some(n), _) => format!("no cam `{n}`; its cams: {}", list()),
                (None, _) => format!("the mechanism has several cams ({}): name one", list()),
            })
        })
    }

    /// G, the number of inputs.
    pub fn dof(&self) -> usize {
        self.model.inputs.len()
    }

    /// All loads zero, with their names (for [`Loads::set_by_name`]).
    pub fn loads(&self) -> Loads {
        let values = self
            .model
            .loads
            .iter()
            .map(|l| match l {
                Load::Force { .. } => LoadValue::Force(V2::zeros()),
                Load::Torque { .. } => LoadValue::Torque(0.0),
            })
            .collect();
        Loads {
            values,
            model: Some(self.model.clone()),
        }
    }

    fn check_inputs(&self, v: &[&[f64]]) -> Result<(), MechError> {
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
    fn solve_slice(
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

    fn solve_on(
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
        let (joints, scale) = (&self.inst.joints[..], self.inst.scale);
        for (g, &sign) in self.plan.iter().zip(branches) {
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
                Kernel::Cam(c) => {
                    crate::elements::cam::solve_cam(c, &self.inst.cams, joints, s, upto)?
                }
                Kernel::System => system(g, |n| n.solve(g, joints, s, drive, scale, upto))?,
            }
        }
        Ok(())
    }

    /// Positions only, into `out` without allocating once `s` has grown: every point's x
    /// and y (m, in the order of [`Model::points`]), then every moving link's angle (rad).
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
    /// [`Model::points`]): [`Mechanism::positions_into`] without the links' angles (no
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
        out.inputs.clear();
        out.inputs.extend_from_slice(q);
        out.inputs.extend_from_slice(qd);
        out.inputs.extend_from_slice(qdd);
        if !Arc::ptr_eq(&out.model, &self.model) {
            out.model = self.model.clone();
        }
        Ok(())
    }

    /// The applied wrenches (loads, gravity) and, when `inertia`, d'Alembert's inertia
    /// wrenches, per link, with the terms each link's declaration gives it.
    fn wrenches(
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
        let (joints, scale) = (&self.inst.joints[..], self.inst.scale);
        let mut r: Scratch<Reaction> = smallvec![Reaction::default(); joints.len()];
        out.driver.clear();
        out.driver.resize(self.dof(), 0.0);
        for g in self.plan.iter().rev() {
            match &g.kernel {
                Kernel::Driven(k) => {
                    screw::driven_reactions(k, joints, s, &mut f, &mut r, &mut out.driver)
                }
                Kernel::Chain(c) => kinematics::chain_reactions(
                    g.solver,
                    c,
                    joints,
                    s,
                    &mut f,
                    scale,
                    &kinematics::DyadSystem::None,
                    &mut r,
                )?,
                Kernel::Mesh(m) => crate::elements::gears::mesh_reactions(
                    m,
                    &self.inst.meshes,
                    joints,
                    s,
                    &mut f,
                    &mut r,
                )?,
                Kernel::Train(t) => crate::elements::gears::train_reactions(
                    t,
                    &self.inst.meshes,
                    joints,
                    s,
                    &mut f,
                    &mut r,
                )?,
                Kernel::Cam(c) => crate::elements::cam::cam_reactions(
                    c,
                    &self.inst.cams,
                    joints,
                    s,
                    &mut f,
                    &mut r,
                )?,
                Kernel::Rolling(k) => crate::elements::rolling::rolling_reactions(
                    k,
                    joints,
                    s,
                    &mut f,
                    scale,
                    &mut r,
                    &mut out.driver,
                )?,
                Kernel::System => system(g, |n| {
                    n.reactions(g, joints, s, &mut f, scale, &mut r, &mut out.driver)
                })?,
            }
        }
        crate::kernel::finite::finite_reactions(&r, &out.driver)?;
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
            return Ok(vec![self.power(m, loads)?.driver(m.qd()[0])?]);
        }
        let mut f = Scratch::new();
        self.wrenches(s, loads, true, &mut f)?;
        let g = self.dof();
        let (joints, scale) = (&self.inst.joints[..], self.inst.scale);
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
                match &grp.kernel {
                    Kernel::Driven(d) => {
                        screw::driven_rates(d, joints, &mut v, drive, Level::Velocity)?
                    }
                    Kernel::Chain(c) => {
                        screw::chain_rates(c, joints, &mut v, scale, Level::Velocity)?
                    }
                    Kernel::Mesh(m) => crate::elements::gears::solve_mesh(
                        m,
                        &self.inst.meshes,
                        joints,
                        &mut v,
                        Level::Velocity,
                    )?,
                    Kernel::Train(t) => crate::elements::gears::solve_train(
                        t,
                        &self.inst.meshes,
                        joints,
                        &mut v,
                        Level::Velocity,
                    )?,
                    Kernel::Cam(c) => crate::elements::cam::solve_cam(
                        c,
                        &self.inst.cams,
                        joints,
                        &mut v,
                        Level::Velocity,
                    )?,
                    Kernel::Rolling(r) => crate::elements::rolling::solve_rolling(
                        r,
                        joints,
                        &mut v,
                        drive,
                        1.0,
                        scale,
                        Level::Velocity,
                        false,
                    )?,
                    Kernel::System => system(grp, |n| n.field(grp, joints, &mut v, drive, scale))?,
                }
            }
            *o = -crate::kernel::kinetostatics::virtual_power(&f, &v);
        }
        crate::kernel::finite::finite_result("motor actions", &out)?;
        Ok(out)
    }

    /// Zhukovski's sums over the motion with q̇ = 1, q̈ = 0 (one input); `qd` is the
    /// input rate the dampers' part of M* is taken at.
    fn reduction(
        &self,
        q: f64,
        qd: f64,
        loads: Option<&Loads>,
        upto: Level,
    ) -> Result<Reduction, MechError> {
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
    fn power(
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
    fn sums(
        &self,
        s: &[LinkState],
        loads: Option<&Loads>,
        qd: f64,
        inertia: bool,
    ) -> Result<Reduction, MechError> {
        let mut z = Reduction::new();
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
        )?;
        Ok(z)
    }
}

/// A Newton group's solvers at its size N = 3 × links (const generic, dispatched here).
struct Newton<const N: usize>;

impl<const N: usize> Newton<N> {
    fn solve(
        &self,
        g: &Group,
        joints: &[crate::kernel::constraints::JointGeom],
        s: &mut [LinkState],
        drive: Drive,
        scale: f64,
        upto: Level,
    ) -> Result<(), MechError> {
        group_solve::<N>(&g.bodies, &g.cons, joints, s, drive, scale, upto).map(|_| ())
    }
    #[allow(clippy::too_many_arguments)]
    fn reactions(
        &self,
        g: &Group,
        joints: &[crate::kernel::constraints::JointGeom],
        s: &[LinkState],
        f: &mut [Wrench],
        scale: f64,
        r: &mut [Reaction],
        d: &mut [f64],
    ) -> Result<(), MechError> {
        let lam = group_reactions::<N>(None, &g.bodies, &g.cons, joints, s, f, scale)?;
        lambda_reactions(&g.cons, joints, s, lam.as_slice(), r, d);
        Ok(())
    }
    fn field(
        &self,
        g: &Group,
        joints: &[crate::kernel::constraints::JointGeom],
        s: &mut [LinkState],
        drive: Drive,
        scale: f64,
    ) -> Result<(), MechError> {
        group_velocity_field::<N, GroupSystem<N>>(None, &g.bodies, &g.cons, joints, s, drive, scale)
    }
}

/// Call `f` with the fixed-size solver of group `g`'s size: N = 3 × links unknowns, and M
/// equations for a redundant group (least squares).
fn system<T>(
    g: &Group,
    f: impl FnOnce(&dyn NewtonAny) -> Result<T, MechError>,
) -> Result<T, MechError> {
    macro_rules! dispatch {
        ($($links:literal => $n:literal [$($m:literal)*]),*) => {
            match (g.bodies.len(), g.rows()) {
                $(
                    ($links, $n) => f(&Newton::<$n>),
                    $(($links, $m) => f(&LeastSquares::<$n, $m>),)*
                )*
                (l, m) => Err(MechError::InvalidInput(format!(
                    "a group of {l} links and {m} equations is beyond the run-time interpreter ({MAX_GROUP_LINKS} links, {MAX_REDUNDANT_ROWS} redundant equations)"
                ))),
            }
        };
    }
    dispatch!(1 => 3 [4 5 6], 2 => 6 [7 8 9], 3 => 9 [10 11 12], 4 => 12 [13 14 15], 5 => 15 [16 17 18], 6 => 18 [19 20 21])
}

/// A redundant group's solvers (least squares over its M ≥ N equations).
struct LeastSquares<const N: usize, const M: usize>;

impl<const N: usize, const M: usize> NewtonAny for LeastSquares<N, M> {
    fn solve(
        &self,
        g: &Group,
        joints: &[crate::kernel::constraints::JointGeom],
        s: &mut [LinkState],
        drive: Drive,
        scale: f64,
        upto: Level,
    ) -> Result<(), MechError> {
        crate::kernel::group::group_solve_ls::<N, M>(
            &g.bodies, &g.cons, joints, s, drive, scale, upto,
        )
        .map(|_| ())
    }
    fn reactions(
        &self,
        _: &Group,
        _: &[crate::kernel::constraints::JointGeom],
        _: &[LinkState],
        _: &mut [Wrench],
        _: f64,
        _: &mut [Reaction],
        _: &mut [f64],
    ) -> Result<(), MechError> {
        Err(MechError::Redundant(
            "a redundant group's reactions are statically indeterminate".into(),
        ))
    }
    fn field(
        &self,
        g: &Group,
        joints: &[crate::kernel::constraints::JointGeom],
        s: &mut [LinkState],
        drive: Drive,
        scale: f64,
    ) -> Result<(), MechError> {
        group_velocity_field::<N, crate::kernel::group::LsSystem<N, M>>(
            None, &g.bodies, &g.cons, joints, s, drive, scale,
        )
    }
}

/// The size-erased interface of [`Newton`].
trait NewtonAny {
    fn solve(
        &self,
        g: &Group,
        joints: &[crate::kernel::constraints::JointGeom],
        s: &mut [LinkState],
        drive: Drive,
        scale: f64,
        upto: Level,
    ) -> Result<(), MechError>;
    #[allow(clippy::too_many_arguments)]
    fn reactions(
        &self,
        g: &Group,
        joints: &[crate::kernel::constraints::JointGeom],
        s: &[LinkState],
        f: &mut [Wrench],
        scale: f64,
        r: &mut [Reaction],
        d: &mut [f64],
    ) -> Result<(), MechError>;
    fn field(
        &self,
        g: &Group,
        joints: &[crate::kernel::constraints::JointGeom],
        s: &mut [LinkState],
        drive: Drive,
        scale: f64,
    ) -> Result<(), MechError>;
}

impl<const N: usize> NewtonAny for Newton<N> {
    fn solve(
        &self,
        g: &Group,
        joints: &[crate::kernel::constraints::JointGeom],
        s: &mut [LinkState],
        drive: Drive,
        scale: f64,
        upto: Level,
    ) -> Result<(), MechError> {
        Newton::<N>::solve(self, g, joints, s, drive, scale, upto)
    }
    fn reactions(
        &self,
        g: &Group,
        joints: &[crate::kernel::constraints::JointGeom],
        s: &[LinkState],
        f: &mut [Wrench],
        scale: f64,
        r: &mut [Reaction],
        d: &mut [f64],
    ) -> Result<(), MechError> {
        Newton::<N>::reactions(self, g, joints, s, f, scale, r, d)
    }
    fn field(
        &self,
        g: &Group,
        joints: &[crate::kernel::constraints::JointGeom],
        s: &mut [LinkState],
        drive: Drive,
        scale: f64,
    ) -> Result<(), MechError> {
        Newton::<N>::field(self, g, joints, s, drive, scale)
    }
}

impl Machine for Mechanism {
    type Loads = Loads;
    type Motion = Motion;
    fn dof(&self) -> usize {
        self.model.inputs.len()
    }
    fn links(&self) -> usize {
        self.model.links.len()
    }
    fn motion(&self, q: &[f64], qd: &[f64], qdd: &[f64]) -> Result<Motion, MechError> {
        self.kinematics(q, qd, qdd)
    }
    fn driver_actions(&self, m: &Motion, loads: &Loads, out: &mut [f64]) -> Result<(), MechError> {
        let d = self.driver_action(m, loads)?;
        if out.len() != d.len() {
            return Err(MechError::InvalidInput(format!(
                "expected {} driver slots, got {}",
                d.len(),
                out.len()
            )));
        }
        out.copy_from_slice(&d);
        Ok(())
    }
    fn link_kinetic_energies(&self, m: &Motion, out: &mut [f64]) {
        for (l, o) in out.iter_mut().enumerate() {
            *o = match (self.terms.get(l), m.links.get(l)) {
                (Some(t), Some(lm)) if l > 0 && t.inertia() => {
                    crate::kernel::energy::kinetic(&self.inst.links[l], lm)
                }
                _ => 0.0,
            };
        }
    }
    fn potential_energy(&self, m: &Motion) -> f64 {
        self.terms
            .iter()
            .enumerate()
            .skip(1)
            .filter(|(_, t)| t.gravity())
            .map(|(l, _)| {
                crate::kernel::energy::potential(
                    &self.inst.links[l],
                    &m.links[l],
                    self.inst.gravity,
                )
            })
            .sum::<f64>()
            + crate::elements::springs::potential(&self.inst.elements, &m.states)
    }
}

impl OneDof for Mechanism {
    fn reduced(&self, q: f64) -> Result<Reduced, MechError> {
        Ok(self.reduction(q, 0.0, None, Level::Acceleration)?.reduced)
    }
    fn reduced_moment(&self, q: f64, loads: &Loads) -> Result<f64, MechError> {
        Ok(self.reduction(q, 0.0, Some(loads), Level::Velocity)?.moment)
    }
    fn acceleration(&self, q: f64, qd: f64, driver: f64, loads: &Loads) -> Result<f64, MechError> {
        crate::error::check_finite("q, qd, driver", &[q, qd, driver])?;
        let z = self.reduction(q, qd, Some(loads), Level::Acceleration)?;
        crate::solvers::zhukovski::acceleration(z.reduced, z.moment, qd, driver)
    }
}
