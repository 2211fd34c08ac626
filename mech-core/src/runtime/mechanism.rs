//! The run-time mechanism: a mechanism known only when the program runs (DSL text, a file, a
//! [`Model`] built in code), solved by executing the same Assur plan with the same kernels
//! as the struct the `mechanism!` macro generates.
//!
//! Loading runs the macro's pipeline (resolution, every check, the Assur plan, the drawing's
//! branches); each solver then walks the plan group by group — [`kinematics::solve_driven`](crate::kernel::kinematics::solve_driven)
//! for a driven crank or slider, [`kinematics::solve_chain`](crate::kernel::kinematics::solve_chain) for a closed-form dyad or slot
//! group (rates and reactions by joint screws, `docs/theory.md` §3.4), Newton and a
//! fixed-size LU ([`crate::kernel::group::group_solve`]) for a group with no closed form — into a buffer of
//! link states the caller may keep ([`Mechanism::solve_into`]: no allocation once it has
//! grown). Same accuracy, same `Singular`/`NoAssembly` behaviour and the same branch rule as
//! the generated struct, which the tests check to 1e-12 on every reference machine.
//!
//! A `Mechanism` implements [`Machine`] and, with one input, [`OneDof`], so every algorithm
//! of mech-core (the direct problem, the energy method, Quinn, Lagrange, flywheel sizing)
//! takes it. (The dense whole-system solver that cross-checks it lives outside the library,
//! in the workspace's test oracle `mech-oracle`.)
//!
//! A mechanism accepted with redundant constraints (`#[allow(redundant)]`) is solved as the
//! generated struct solves it (least squares in its redundant groups, the other branches
//! tried past a change point) and has no reactions (`MechError::Redundant`), only the motor
//! actions. Limits: a group of more than six links or more than three redundant equations
//! is refused at loading with [`MechError::InvalidInput`] (the dense test oracle `mech-oracle` has no such limit).

pub use super::results::{Forces, JointReaction, LoadValue, Loads, Motion, Pose};
use crate::kernel::constraints::Level;
use crate::kernel::link_state::V2;
use crate::model::{JointKind, Load, Model, PointOwner};
use crate::plan::assur::{Group, Kernel};
use crate::plan::rotation::AngleRule;
use crate::solvers::batch::BatchErrors;
use crate::solvers::instance::{instance, Instance};
use crate::solvers::params::LinkTerms;
use crate::solvers::traits::{Machine, OneDof};
use crate::solvers::zhukovski::Reduced;
use crate::solvers::zhukovski_series::{Series, Term};
use crate::MechError;
use smallvec::SmallVec;
use std::path::Path;
use std::sync::Arc;

/// Per-call temporaries on the stack for mechanisms of up to 8 links or joints.
pub(super) type Scratch<T> = SmallVec<[T; 8]>;

/// The largest group (in links) the run-time interpreter solves with a fixed-size system.
pub const MAX_GROUP_LINKS: usize = 6;

/// The most redundant equations a group may have (`#[allow(redundant)]`).
pub const MAX_REDUNDANT_ROWS: usize = 3;

/// A mechanism loaded at run time and solved with the generated code's plan and kernels
/// (module docs).
#[derive(Clone, Debug)]
pub struct Mechanism {
    pub(super) model: Arc<Model>,
    pub(super) inst: Instance,
    pub(super) plan: Vec<Group>,
    pub(super) branches: Vec<f64>,
    pub(super) terms: Vec<LinkTerms>,
    /// Per link: it turns about a ground pin ([`Model::ground_pivot`]).
    pub(super) pinned: Vec<bool>,
    /// Per link: it slides on the ground ([`Model::translates`]).
    pub(super) translates: Vec<bool>,
    /// Every group has a lane kernel (`crate::kernel::lanes::supports`) and the mechanism
    /// has no force element and no redundant constraint: its `points_many`, `reduced_many`
    /// and `acceleration_many` take four configurations at once (`runtime::batch`).
    pub(super) lanes: bool,
    /// Some group has no closed form (Newton, started from the drawing).
    pub(super) newton: bool,
    /// Accepted with redundant constraints and some group is redundant
    /// ([`Mechanism::redundant`]).
    pub(super) redundant: bool,
    /// What the solvers read per call, resolved from the plan and the model once at loading.
    pub(super) program: Program,
    /// Each gear-train group's Willis inverse, by the group's first link.
    pub(super) willis: Vec<(usize, crate::elements::gears::Willis)>,
    /// Zhukovski's I*(q) as a constant and a few cosines when every angular velocity
    /// coefficient is a constant ([`crate::plan::ratios`]: a machine of gears; no cosine
    /// when every gear turns on a fixed axis), worked out at loading
    /// ([`crate::solvers::zhukovski_series`]); `None` for the others.
    pub(super) reduced_series: Option<Series<Vec<Term>>>,
}

/// How a point is published, as the generated code does (`emit/results.rs`, `owners`).
#[derive(Clone, Copy, Debug)]
pub(super) enum Owner {
    /// A point of the ground, at rest at its local vector.
    Ground(V2),
    /// The anchor (first point) of this moving link: its state's own motion.
    Anchor(usize),
    /// The material point of this moving link at this local vector.
    Local(usize, V2),
}

/// A link's share of Zhukovski's I* or M*, by what the link does (`emit/traits.rs`).
#[derive(Clone, Copy, Debug)]
pub(super) enum Share {
    /// Turning about a ground pin (inertia only).
    AboutPivot,
    /// Sliding on the ground.
    Translating,
    /// Its cg from the span to this link's anchor ([`Model::span_partner`]).
    Spanned(usize),
    /// Any other motion.
    General,
}

/// How a load's power per unit input rate is taken (the generated code's Zhukovski
/// terms).
#[derive(Clone, Copy, Debug)]
pub(super) enum LoadShare {
    /// On a link sliding on the ground: a force's power is its anchor's, a torque's
    /// nothing (ω = 0).
    Translating,
    /// A force at the point of local vector `d` of its link, a torque by the link's ω.
    At(V2),
}

/// The plan and the model resolved once at loading into what every call reads: how each
/// link and point is published, which links carry which terms, each joint's reaction
/// shape.
#[derive(Clone, Debug)]
pub(super) struct Program {
    /// Per moving link (link l at l − 1): how its angle is published
    /// ([`crate::plan::rotation::angle_rule`], the generated code's rule).
    pub(super) angles: Vec<AngleRule>,
    /// The moving links in the order their angles are published (a link turning with a
    /// partner after it: [`crate::plan::rotation::angle_order`]).
    pub(super) angle_order: Vec<usize>,
    /// Per point: how it is published.
    pub(super) owners: Vec<Owner>,
    /// The ground's motion (constant).
    pub(super) ground: crate::kernel::link_state::LinkMotion,
    /// The links with gravity terms (none without gravity), with their share of M*.
    pub(super) weighed: Vec<(usize, Share)>,
    /// The links with inertia terms, with their share of I*.
    pub(super) inertial: Vec<(usize, Share)>,
    /// Per joint: it is prismatic (its reaction has a moment).
    pub(super) prismatic: Vec<bool>,
    /// Per load: the link it acts on and how its power enters Zhukovski's M*
    /// ([`Mechanism::load_terms`]).
    pub(super) load_shares: Vec<(usize, LoadShare)>,
    /// A crank and one closed-form dyad, solved on literal indices
    /// ([`super::one_loop`]); `None` for the other mechanisms.
    pub(super) one_loop: Option<super::one_loop::OneLoop>,
}

impl Program {
    fn new(model: &Model, plan: &[Group], inst: &Instance) -> Self {
        let n = model.links.len();
        let angles = (1..n)
            .map(|l| crate::plan::rotation::angle_rule(model, plan, l))
            .collect();
        let angle_order = crate::plan::rotation::angle_order(plan, n);
        let owners = (0..model.points.len())
            .map(|pt| {
                let d = inst.points[pt].1;
                match model.point_owner(pt) {
                    PointOwner::Ground => Owner::Ground(d),
                    PointOwner::Anchor(l) => Owner::Anchor(l),
                    PointOwner::Local(l) => Owner::Local(l, d),
                }
            })
            .collect();
        let terms: Vec<LinkTerms> = model.links.iter().map(LinkTerms::of).collect();
        let share = |l: usize, inertia: bool| {
            if inertia && model.ground_pivot(l).is_some() {
                Share::AboutPivot
            } else if model.translates(l) {
                Share::Translating
            } else if let Some(m) = model.span_partner(l) {
                Share::Spanned(m)
            } else {
                Share::General
            }
        };
        let weighed = if model.gravity.is_none() {
            Vec::new()
        } else {
            (1..n)
                .filter(|&l| terms[l].gravity())
                .map(|l| (l, share(l, false)))
                .collect()
        };
        let inertial = (1..n)
            .filter(|&l| terms[l].inertia())
            .map(|l| (l, share(l, true)))
            .collect();
        let load_shares = (model.loads.iter().zip(&inst.loads))
            .map(|(load, &d)| {
                let l = load.link();
                let share = if model.translates(l) {
                    LoadShare::Translating
                } else {
                    LoadShare::At(d)
                };
                (l, share)
            })
            .collect();
        let mut program = Program {
            one_loop: None,
            load_shares,
            angles,
            angle_order,
            owners,
            ground: inst.links[0].motion(&inst.drawing[0]),
            weighed,
            inertial,
            prismatic: model
                .joints
                .iter()
                .map(|j| j.kind == JointKind::Prismatic)
                .collect(),
        };
        program.one_loop = super::one_loop::OneLoop::find(model, plan, &inst.joints);
        program
    }
}

impl Mechanism {
    /// Load from DSL text (the body of a `mechanism! { ... }`): the macro's parse,
    /// resolution and checks; every problem reported together with its line and column.
    pub fn from_dsl(text: &str) -> Result<Self, MechError> {
        Self::from_checked(crate::checks::load::parse_model(text, None)?)
    }

    /// [`Mechanism::from_dsl`] of the text of a file named `origin`: every message starts
    /// with `origin:LINE:COLUMN:`.
    pub fn from_dsl_named(text: &str, origin: &str) -> Result<Self, MechError> {
        Self::from_checked(crate::checks::load::parse_model(text, Some(origin))?)
    }

    /// Load the mechanism `name` declared with `mechanism!` in Rust source text.
    pub fn from_rust_source(source: &str, name: &str) -> Result<Self, MechError> {
        Self::from_checked(crate::checks::load::rust_source_model(source, name)?)
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
                "the group of links {} has {} links and {} equations: the run-time interpreter takes groups of at most {MAX_GROUP_LINKS} links with at most {MAX_REDUNDANT_ROWS} redundant equations",
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
            .map(|l| model.ground_pivot(l).is_some())
            .collect();
        let translates = (0..model.links.len())
            .map(|l| model.translates(l))
            .collect();
        let newton = plan.iter().any(|g| g.kernel == Kernel::System);
        let lanes = model.elements.is_empty()
            && !model.allow_redundant
            && plan.iter().all(|g| {
                matches!(g.kernel, Kernel::Driven(_) | Kernel::Chain(_))
                    && crate::kernel::lanes::supports(g.solver)
            });
        let redundant = model.allow_redundant && plan.iter().any(|g| g.redundant());
        let program = Program::new(&model, &plan, &inst);
        let willis = plan
            .iter()
            .filter_map(|g| match &g.kernel {
                Kernel::Train(t) => Some((
                    t.bodies[0],
                    crate::elements::gears::Willis::new(t, &inst.meshes),
                )),
                _ => None,
            })
            .collect();
        let pins = crate::plan::ratios::pins(&model, &plan);
        let mut m = Mechanism {
            model: Arc::new(model),
            inst,
            plan,
            branches,
            terms,
            pinned,
            translates,
            lanes,
            newton,
            redundant,
            program,
            willis,
            reduced_series: None,
        };
        if let (Some(pins), 1) = (pins, m.dof()) {
            m.reduced_series = Some(m.series(&pins)?);
        }
        Ok(m)
    }

    /// The Willis inverse of the gear-train group `t`, worked out at loading (kept by the
    /// group's first link: a mechanism has a few gear-train groups at most), borrowed.
    #[inline]
    pub(super) fn willis_of(
        &self,
        t: &crate::elements::gears::TrainGroup,
    ) -> std::borrow::Cow<'_, crate::elements::gears::Willis> {
        match self.willis.iter().find(|(b, _)| *b == t.bodies[0]) {
            Some((_, w)) => std::borrow::Cow::Borrowed(w),
            None => {
                std::borrow::Cow::Owned(crate::elements::gears::Willis::new(t, &self.inst.meshes))
            }
        }
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
            ["links", l, "shape", dim] => {
                let i = model
                    .link_index(l)
                    .filter(|&i| i > 0)
                    .ok_or_else(|| bad("unknown moving link"))?;
                let Some((shape, material)) = model.links[i].body else {
                    return Err(bad("the link is not declared by a `shape:`"));
                };
                let new = shape
                    .with_dimension(dim, one(value)?)
                    .map_err(|why| MechError::InvalidInput(format!("`{path}`: {why}")))?;
                model.links[i].body = Some((new, material));
            }
            ["links", l, what] => {
                let i = model
                    .link_index(l)
                    .filter(|&i| i > 0)
                    .ok_or_else(|| bad("unknown moving link"))?;
                let link = &mut model.links[i];
                if link.body.is_some() && matches!(*what, "cg" | "mass" | "inertia") {
                    return Err(MechError::InvalidInput(format!(
                        "`{path}`: link `{l}` is declared by its shape and material, which give its {what}: change a dimension instead (`links.{l}.shape.<dimension>`)"
                    )));
                }
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
                    "use points.<P>, links.<l>.{cg, mass, inertia, flywheel}, links.<l>.shape.<dimension>, axes.<joint>, elements.<e>.{stiffness, free_length, free_angle, damping} or gravity",
                ))
            }
        }
        // A moved point or a new dimension changes the mass of a link made of a shape.
        crate::model::shape::update_bodies(&mut model.links, &model.points)
            .map_err(|why| MechError::InvalidInput(format!("`{path}`: {why}")))?;
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
        self.driver_action_into(m, loads, out)
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
    fn shaking(&self, m: &Motion) -> crate::kernel::energy::Shaking {
        let mut s = crate::kernel::energy::Shaking::default();
        for (l, t) in self.terms.iter().enumerate().skip(1) {
            if let (true, Some(lm)) = (t.inertia(), m.links.get(l)) {
                s.add(&self.inst.links[l], lm);
            }
        }
        s
    }
}

impl Mechanism {
    /// I* and dI*/dq from the motion with q̇ = 1, q̈ = 0 solved at `q`.
    #[inline(never)]
    fn reduced_solved(&self, q: f64) -> Result<Reduced, MechError> {
        Ok(self
            .zhukovski_sums(q, 0.0, None, Level::Acceleration)?
            .reduced)
    }
}

impl OneDof for Mechanism {
    /// Inline, so that a machine of gears' I*, a sum worked out at loading, is evaluated
    /// in the caller; any other machine's is solved out of line
    /// (`Mechanism::reduced_solved`).
    #[inline]
    fn reduced(&self, q: f64) -> Result<Reduced, MechError> {
        if let Some(series) = &self.reduced_series {
            // Constant ratios: I*(q) was worked out at loading, as a sum of cosines.
            crate::error::check_finite("q, qd, qdd", &[q])?;
            return Ok(series.at(q));
        }
        self.reduced_solved(q)
    }
    fn reduced_many(&self, q: &[f64], inertia: &mut [f64], derivative: &mut [f64]) -> BatchErrors {
        Mechanism::reduced_many(self, q, inertia, derivative)
    }
    fn reduced_moment(&self, q: f64, loads: &Loads) -> Result<f64, MechError> {
        Ok(self
            .zhukovski_sums(q, 0.0, Some(loads), Level::Velocity)?
            .moment)
    }
    fn acceleration(&self, q: f64, qd: f64, driver: f64, loads: &Loads) -> Result<f64, MechError> {
        crate::error::check_finite("q, qd, driver", &[q, qd, driver])?;
        let z = self.zhukovski_sums(q, qd, Some(loads), Level::Acceleration)?;
        crate::solvers::zhukovski::acceleration(z.reduced, z.moment, qd, driver)
    }
}
