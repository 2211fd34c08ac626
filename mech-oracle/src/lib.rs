//! The generic run-time solver (`docs/conventions.md#algorithms-written-once`): a
//! mechanism read at run time from the DSL text (the grammar of [`mech_core::front::dsl`], the checks
//! of [`mech_core::checks::validate`], exactly as the `mechanism!` macro runs them) and solved by an
//! interpreter with heap-allocated (dynamic) nalgebra matrices.
//!
//! It is the baseline every generated solver is measured against, and the engine for
//! mechanisms not known at compile time. It uses the same formulas as the generated code —
//! the constraint kernels [`mech_core::kernel::kinematics::eval`] and the wrench helpers of
//! [`mech_core::kernel::kinetostatics`] — and differs only in assembling ONE global dense system of all
//! 3(N − 1) coordinates instead of one small system per Assur group:
//!
//! - positions: Newton–Raphson on Φ(x; q) = 0 for every coordinate (x, y, φ) of every
//!   moving link at once, started from the drawing and continued along the straight path
//!   q(t) = q_ref + t·Δq, t ∈ [0, 1], from the drawing's input values q_ref (a second-order
//!   predictor x + h x′ + ½h² x″ from the velocity and acceleration analyses, a Newton
//!   corrector, adaptive steps). A step is rejected when the sign of det J changes (the path
//!   crossed a dead point or jumped to another assembly branch), so the solution stays on
//!   the drawing's branch;
//! - velocities J ẋ = −Φ̇, accelerations J ẍ = −Φ̈ (the unknown rates set to zero);
//! - kinetostatics (d'Alembert): one dense system Jᵀ λ = −f of all multipliers, f the
//!   applied, gravity and inertia wrenches; λ of a joint's rows is the reaction BY its
//!   first link ON its second, λ of a driver row the motor action;
//! - driver actions by virtual power, and Zhukovski's I*, dI*/dq, M* for one DOF.
//!
//! The system is scaled to be dimensionless, as the group systems of
//! [`mech_core::kernel::group::GroupSystem`]: columns (x, y, φ·L) and angle rows × L, L the
//! drawing's length scale ([`Model::scale`], m). The condition estimate is the pivot ratio
//! max|U_ii| / min|U_ii| of the LU factorisation; beyond
//! [`HARD_CONDITION`] the solver reports [`MechError::Singular`].
//!
//! Units are SI (m, kg, kg·m², N, N·m, rad, s), as everywhere in `mech`.

pub use mech_core::checks::load::mechanism_text;
use mech_core::checks::load::{parse_model, rust_source_model};
use mech_core::error::{all_finite, check_finite};
use mech_core::kernel::constraints::{
    eval, row_scale, scaled_rows, Con, ConEval, ConKind, Drive, Level,
};
use mech_core::kernel::kinetostatics::{
    add_force, add_gravity, add_inertia, add_torque, slide_force, virtual_power, Wrench,
};
use mech_core::kernel::link_state::{
    point_motion, point_pose, rotate, LinkMotion, LinkPose, LinkState, PointMotion, PointPose, V2,
};
use mech_core::model::{JointKind, Load, Model};
use mech_core::plan::geometry::all_cons;
use mech_core::runtime::results::set_load;
pub use mech_core::runtime::{JointReaction, LoadValue};
use mech_core::solvers::instance::{instance, Instance};
use mech_core::solvers::zhukovski::{self, Reduced};
use mech_core::MechError;
use nalgebra::{DMatrix, DVector, Dyn, LU, SVD};
use std::path::Path;
use std::sync::Arc;

/// Default Newton tolerance of the position analysis: the last Newton step is at most
/// `DEFAULT_TOLERANCE` × L (dimensionless, relative to the drawing's length scale L).
/// Newton converges quadratically, so the position returned (after that last step) is
/// accurate to roundoff.
pub const DEFAULT_TOLERANCE: f64 = 1e-12;

/// Newton tolerance (× L) of the intermediate points of the continuation: they only have
/// to keep the path on its branch.
const PATH_TOLERANCE: f64 = 1e-8;

/// Largest predicted motion of one continuation step, × L (scaled coordinates x, y, φ·L).
const MAX_STEP: f64 = 0.25;

/// A continuation step is accepted only if the corrector moved the prediction by at most
/// this fraction of the predicted motion (plus the path tolerance): a bigger correction
/// means the predictor was poor, and the step may have left the branch.
const MAX_CORRECTION: f64 = 0.5;

/// Newton iterations allowed at an intermediate point, and at the end point.
const PATH_ITERATIONS: usize = 8;
const FINAL_ITERATIONS: usize = 60;

/// Smallest continuation step (fraction of the path) before giving up.
const MIN_STEP: f64 = 1e-12;

/// Most continuation steps of one solve.
const MAX_STEPS: usize = 2_000;

/// A Newton iteration whose step no longer decreases has reached the roundoff floor when
/// the residual |Φ|∞ (rows scaled to lengths) is at most `RESIDUAL_FLOOR` × ε × L; with a
/// larger residual there is no solution (e.g. just past a dead point).
const RESIDUAL_FLOOR: f64 = 16.0;

/// Default largest accepted error bound (dimensionless), see
/// [`GenericMechanism::with_max_error`].
pub const DEFAULT_MAX_ERROR: f64 = 1e-6;

/// The condition estimate beyond which the generic solver refuses whatever `max_error`
/// (its default `max_error` refuses much earlier, from the stated bounds). Looser than
/// the generated code's [`mech_core::kernel::linalg::SINGULAR_CONDITION`], so that the stress
/// suite can measure errors close to a toggle.
pub const HARD_CONDITION: f64 = 1e10;

/// The stated error bound of a position analysis with condition estimate κ: angles
/// within 8 ε κ rad, positions within 8 ε κ × L (ε the f64 machine epsilon). Near a dead
/// point (a fold of the loop equations) the positions are determined by the constraint
/// residual only to this accuracy.
pub fn position_error_bound(condition: f64) -> f64 {
    8.0 * f64::EPSILON * condition
}

/// The stated relative error bound of everything computed from a motion with condition
/// estimate κ — velocities, accelerations, motor actions, reactions, I*, M*: 16 ε κ².
/// The position error (ε κ) perturbs the Jacobian, and solving with it multiplies by κ
/// again. Checked on a four-bar driven to transmission angles of 1e-1 … 1e-7 rad against a
/// 50-digit reference (`tests/stress.rs`): the errors stay within 1–5 ε κ².
pub fn rate_error_bound(condition: f64) -> f64 {
    16.0 * f64::EPSILON * condition * condition
}

/// The values of a generic mechanism's loads, in declaration order (the run-time
/// counterpart of a generated `<Name>Loads`). Made by [`GenericMechanism::loads`], all zero.
#[derive(Clone, Debug, PartialEq)]
pub struct GenericLoads {
    /// One value per declared load, in declaration order.
    pub values: Vec<LoadValue>,
    model: Arc<Model>,
}

impl GenericLoads {
    /// Set the load named `name` from its components (2 for a force, N; 1 for a torque,
    /// N·m); false when there is no such load or the length is wrong.
    pub fn set_by_name(&mut self, name: &str, value: &[f64]) -> bool {
        set_load(&self.model, &mut self.values, name, value)
    }
    /// The value of the load named `name`, if any.
    pub fn get(&self, name: &str) -> Option<LoadValue> {
        self.model
            .loads
            .iter()
            .position(|l| l.name() == name)
            .map(|k| self.values[k])
    }
}

/// Result of [`GenericMechanism::pose`]: positions only.
#[derive(Clone, Debug, PartialEq)]
pub struct GenericPose {
    /// Every link's angle θ (rad, wrapped to (−π, π]) and cg (m), indexed like
    /// [`Model::links`] (index 0 is the ground).
    pub links: Vec<LinkPose>,
    /// Every point's position (m), indexed like [`Model::points`].
    pub points: Vec<PointPose>,
    /// Condition estimate of the constraint Jacobian at this pose (dimensionless pivot ratio).
    pub condition: f64,
    model: Arc<Model>,
}

impl GenericPose {
    /// The stated error bound of this pose, [`position_error_bound`]: rad for angles, × L
    /// (the drawing's size, m) for positions.
    pub fn error_bound(&self) -> f64 {
        position_error_bound(self.condition)
    }
    /// The pose of the link named `name`, if any.
    pub fn link(&self, name: &str) -> Option<&LinkPose> {
        self.model.link_index(name).map(|l| &self.links[l])
    }
    /// The position of the point named `name`, if any.
    pub fn point(&self, name: &str) -> Option<&PointPose> {
        self.model.point_index(name).map(|p| &self.points[p])
    }
}

/// Result of [`GenericMechanism::kinematics`]: positions, velocities, accelerations.
#[derive(Clone, Debug, PartialEq)]
pub struct GenericMotion {
    /// Every link's θ (rad), ω (rad/s), α (rad/s²) and its cg's position (m), velocity
    /// (m/s), acceleration (m/s²), indexed like [`Model::links`] (index 0 is the ground).
    pub links: Vec<LinkMotion>,
    /// Every point's position, velocity, acceleration, indexed like [`Model::points`].
    pub points: Vec<PointMotion>,
    /// The input values q (rad or m) of this motion.
    pub q: Vec<f64>,
    /// The input rates q̇ (rad/s or m/s).
    pub qd: Vec<f64>,
    /// The input accelerations q̈ (rad/s² or m/s²).
    pub qdd: Vec<f64>,
    /// Condition estimate of the constraint Jacobian (dimensionless pivot ratio).
    pub condition: f64,
    states: Vec<LinkState>,
    model: Arc<Model>,
}

impl GenericMotion {
    /// The stated relative error bound of the rates of this motion and of everything
    /// computed from it (motor actions, reactions), [`rate_error_bound`]; its positions are
    /// within [`position_error_bound`].
    pub fn error_bound(&self) -> f64 {
        rate_error_bound(self.condition)
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

/// Result of [`GenericMechanism::kinetostatics`]: the motor actions and every reaction.
#[derive(Clone, Debug, PartialEq)]
pub struct GenericForces {
    /// Motor action of each input: torque by a on b (N·m) for a revolute input, force
    /// along the axis on b (N) for a prismatic one.
    pub driver: Vec<f64>,
    /// The reaction at every joint, indexed like [`Model::joints`].
    pub joints: Vec<JointReaction>,
    /// Condition estimate of the multipliers' system (dimensionless pivot ratio).
    pub condition: f64,
    model: Arc<Model>,
}

impl GenericForces {
    /// The reaction at the joint named `name`: force by a on b (N) and, for a prismatic
    /// joint, the moment (N·m) — the shape of a generated `<Name>Forces::reaction`.
    pub fn reaction(&self, name: &str) -> Option<(V2, Option<f64>)> {
        self.model
            .joint_index(name)
            .map(|j| (self.joints[j].force, self.joints[j].moment))
    }
}

/// A factored, scaled global system (see the module docs).
struct System {
    factor: Factor,
    /// Pivot ratio (LU) or σ_max/σ_min (SVD).
    condition: f64,
    /// Sign of det J (LU only; 1 for SVD).
    det_sign: f64,
}

enum Factor {
    Lu(LU<f64, Dyn, Dyn>),
    /// Least squares for a redundant mechanism (more rows than columns).
    Svd(SVD<f64, Dyn, Dyn>),
}

impl System {
    fn solve(&self, b: &DVector<f64>) -> Result<DVector<f64>, MechError> {
        let x = match &self.factor {
            Factor::Lu(lu) => lu.solve(b),
            Factor::Svd(svd) => svd.solve(b, 0.0).ok(),
        };
        match x {
            Some(x) if x.iter().all(|v| v.is_finite()) => Ok(x),
            _ => Err(MechError::Singular {
                condition: self.condition,
            }),
        }
    }
}

/// A mechanism loaded at run time, solved by the generic interpreter (module docs).
#[derive(Clone, Debug)]
pub struct GenericMechanism {
    model: Arc<Model>,
    inst: Instance,
    cons: Vec<Con>,
    /// First row of each constraint of `cons`.
    first_row: Vec<usize>,
    /// Row scale: L for rows whose unit is an angle, 1 otherwise.
    row_scale: Vec<f64>,
    rows: usize,
    /// The drawing's input values q_ref (rad or m).
    q_ref: Vec<f64>,
    tol: f64,
    max_error: f64,
}

/// `Ok` when every value of `quantity` is finite; else `InvalidInput` naming it: the
/// inputs (speeds, loads, the driver) are too large for f64 with this mechanism (the
/// run-time solvers' overflow error). A result derived from finite inputs may still be
/// infinite (ω² r past f64's range) or NaN (∞ − ∞, a spring of zero length).
fn finite_result(quantity: &str, values: &[f64]) -> Result<(), MechError> {
    if all_finite(values) {
        return Ok(());
    }
    let v = values
        .iter()
        .find(|v| !v.is_finite())
        .copied()
        .unwrap_or(f64::NAN);
    Err(MechError::InvalidInput(format!(
        "the {quantity} overflow ({v}): the inputs, loads or driver are too large for f64 with this mechanism; reduce them"
    )))
}

/// `value` if finite and > 0, else [`MechError::InvalidInput`] naming it.
fn positive(what: &str, value: f64) -> Result<f64, MechError> {
    if value.is_finite() && value > 0.0 {
        Ok(value)
    } else {
        Err(MechError::InvalidInput(format!(
            "{what} must be finite and > 0, got {value}"
        )))
    }
}

impl std::str::FromStr for GenericMechanism {
    type Err = MechError;
    /// Same as [`GenericMechanism::parse`].
    fn from_str(text: &str) -> Result<Self, MechError> {
        GenericMechanism::parse(text)
    }
}

impl GenericMechanism {
    /// Load a mechanism from DSL text: the body of a `mechanism! { ... }` (doc comments,
    /// `#[allow(redundant)]`, `pub struct Name { ... }`), parsed, resolved and validated by
    /// the same code as the macro ([`mech_core::front::dsl::parse_str`], [`mech_core::front::resolve::resolve`],
    /// [`mech_core::checks::validate::check`], [`mech_core::plan::assur::plan`]). Every problem found is reported
    /// in one [`MechError::Invalid`], each message prefixed with its `line:column`.
    pub fn parse(text: &str) -> Result<Self, MechError> {
        Self::parse_named(text, None)
    }

    /// [`GenericMechanism::parse`] of the text of a file named `origin` (shown in every
    /// message as `origin:LINE:COLUMN`).
    pub fn parse_named(text: &str, origin: Option<&str>) -> Result<Self, MechError> {
        Self::build(parse_model(text, origin)?)
    }

    /// Load the mechanism `name` declared with `mechanism! { ... pub struct name { ... } }`
    /// in Rust source text `source` (e.g. `include_str!` of the file that the macro
    /// compiles): the same tokens the macro sees, through the same checks as
    /// [`GenericMechanism::parse`]; messages carry `line:column` in `source`.
    /// [`MechError::Invalid`] when the source does not tokenize or declares no such mechanism.
    pub fn from_rust_source(source: &str, name: &str) -> Result<Self, MechError> {
        Self::build(rust_source_model(source, name)?)
    }
}

impl GenericMechanism {
    /// Load a mechanism from a file of DSL text (see [`GenericMechanism::parse`]); an
    /// unreadable file is a [`MechError::Invalid`] naming the path.
    pub fn load(path: impl AsRef<Path>) -> Result<Self, MechError> {
        let path = path.as_ref();
        let text = std::fs::read_to_string(path)
            .map_err(|e| MechError::Invalid(format!("cannot read {}: {e}", path.display())))?;
        Self::parse(&text)
    }

    /// A mechanism from a resolved [`Model`] (e.g. [`GenericMechanism::model`] with other
    /// masses or coordinates): runs every check of [`mech_core::checks::validate::check`] on it;
    /// [`MechError::Invalid`] with the messages (no source locations) when it fails.
    pub fn from_model(model: Model) -> Result<Self, MechError> {
        let issues = mech_core::checks::validate::check(&model);
        if !issues.is_empty() {
            return Err(MechError::Invalid(
                issues
                    .iter()
                    .map(|i| i.message.as_str())
                    .collect::<Vec<_>>()
                    .join("\n"),
            ));
        }
        if mech_core::plan::assur::plan(&model).is_err() {
            return Err(MechError::Invalid(
                "the links cannot be solved group by group from the inputs".into(),
            ));
        }
        Self::build(model)
    }

    fn build(model: Model) -> Result<Self, MechError> {
        if let Some(j) = model
            .joints
            .iter()
            .find(|j| j.kind.mesh() || j.kind == mech_core::model::JointKind::Rolling)
        {
            return Err(MechError::Invalid(format!(
                "{} `{}`: the generic solver has no gear pairs, racks or rolling wheels (solved in closed form by `mech::gears` and `mech::rolling`); use the generated struct or `Mechanism`",
                j.kind.keyword(),
                j.name
            )));
        }
        let inst = instance(&model)?;
        let cons = all_cons(&model);
        let mut first_row = Vec::with_capacity(cons.len());
        let mut rows = 0;
        for c in &cons {
            first_row.push(rows);
            rows += c.kind.rows();
        }
        let q_ref = (0..model.inputs.len())
            .map(|k| model.reference_input(k))
            .collect();
        let mut g = GenericMechanism {
            model: Arc::new(model),
            inst,
            cons,
            first_row,
            row_scale: vec![1.0; rows],
            rows,
            q_ref,
            tol: DEFAULT_TOLERANCE,
            max_error: DEFAULT_MAX_ERROR,
        };
        // The one scaling rule of `constraints`: L for the rows whose unit is an angle.
        let scale = g.inst.scale;
        let row_scale = g
            .cons
            .iter()
            .flat_map(|c| (0..c.kind.rows()).map(move |k| row_scale(c.kind, k, scale)))
            .collect();
        g.row_scale = row_scale;
        Ok(g)
    }

    /// The resolved model (links, joints, points, loads in declaration order).
    pub fn model(&self) -> &Model {
        &self.model
    }

    /// G, the number of inputs.
    pub fn dof(&self) -> usize {
        self.model.inputs.len()
    }

    /// The drawing's input values q_ref (rad for a revolute input: θ_b − θ_a in the
    /// drawing; 0 m for a prismatic one): where the position continuation starts.
    pub fn reference_inputs(&self) -> &[f64] {
        &self.q_ref
    }

    /// The Newton tolerance of the position analysis (dimensionless, × L).
    pub fn tolerance(&self) -> f64 {
        self.tol
    }

    /// The same mechanism with another Newton tolerance `tol` (dimensionless: the last
    /// Newton step is at most `tol` × L, L the drawing's length scale in m). Must be finite
    /// and > 0, else [`MechError::InvalidInput`]. The default is [`DEFAULT_TOLERANCE`].
    pub fn with_tolerance(mut self, tol: f64) -> Result<Self, MechError> {
        self.tol = positive("the Newton tolerance", tol)?;
        Ok(self)
    }

    /// The largest stated error bound a result may have (dimensionless).
    pub fn max_error(&self) -> f64 {
        self.max_error
    }

    /// The same mechanism refusing, with [`MechError::Singular`], any result whose stated
    /// error bound exceeds `max_error` (dimensionless): a pose when
    /// [`position_error_bound`] (8 ε κ) does, a motion and everything computed from one
    /// when [`rate_error_bound`] (16 ε κ²) does, κ the condition estimate of the
    /// constraint Jacobian. The default [`DEFAULT_MAX_ERROR`] = 1e-6 refuses motions with
    /// κ > 1.7e4 (for a four-bar, a transmission angle of about 1e-4 rad). Must be finite
    /// and > 0, else [`MechError::InvalidInput`]; a system beyond
    /// [`HARD_CONDITION`] is refused whatever `max_error`.
    pub fn with_max_error(mut self, max_error: f64) -> Result<Self, MechError> {
        self.max_error = positive("max_error", max_error)?;
        Ok(self)
    }

    /// All-zero loads of this mechanism.
    pub fn loads(&self) -> GenericLoads {
        let values = self
            .model
            .loads
            .iter()
            .map(|l| match l {
                Load::Force { .. } => LoadValue::Force(V2::zeros()),
                Load::Torque { .. } => LoadValue::Torque(0.0),
            })
            .collect();
        GenericLoads {
            values,
            model: self.model.clone(),
        }
    }

    // ---------------------------------------------------------------------------------
    // The global system
    // ---------------------------------------------------------------------------------

    fn cols(&self) -> usize {
        3 * (self.model.links.len() - 1)
    }

    /// Evaluate every constraint at `level`, calling `f(row, con, eval, k)` per scalar row.
    fn for_rows(
        &self,
        s: &[LinkState],
        drive: Drive,
        level: Level,
        mut f: impl FnMut(usize, &Con, &ConEval, usize),
    ) {
        for (c, &r0) in self.cons.iter().zip(&self.first_row) {
            let e = eval(*c, &self.inst.joints[c.joint], s, drive, level);
            for k in 0..c.kind.rows() {
                f(r0 + k, c, &e, k);
            }
        }
    }

    /// The scaled Jacobian J (rows × 3(N − 1)) at the states `s` and the scaled right-hand
    /// side b = −(row scale × constraint values at `level`).
    fn assemble(
        &self,
        s: &[LinkState],
        drive: Drive,
        level: Level,
    ) -> (DMatrix<f64>, DVector<f64>) {
        let mut j = DMatrix::zeros(self.rows, self.cols());
        for (c, &r0) in self.cons.iter().zip(&self.first_row) {
            scaled_rows(
                *c,
                &self.inst.joints[c.joint],
                s,
                self.inst.scale,
                |k, link, e| {
                    if link != 0 {
                        for (i, x) in e.iter().enumerate() {
                            j[(r0 + k, 3 * (link - 1) + i)] += x;
                        }
                    }
                },
            );
        }
        (j, self.rhs(s, drive, level))
    }

    /// The right-hand side only (for a second solve with the same Jacobian).
    fn rhs(&self, s: &[LinkState], drive: Drive, level: Level) -> DVector<f64> {
        let mut b = DVector::zeros(self.rows);
        self.for_rows(s, drive, level, |r, _, e, k| {
            b[r] = -self.row_scale[r] * e.val[k]
        });
        b
    }

    /// Factor a scaled matrix; [`MechError::Singular`] beyond [`HARD_CONDITION`].
    fn factor(j: DMatrix<f64>) -> Result<System, MechError> {
        let (m, n) = j.shape();
        if n == 0 {
            return Ok(System {
                factor: Factor::Lu(j.lu()),
                condition: 1.0,
                det_sign: 1.0,
            });
        }
        let sys = if m == n {
            let lu = j.lu();
            let (mut lo, mut hi, mut sign) = (f64::INFINITY, 0.0f64, lu.p().determinant::<f64>());
            for i in 0..n {
                let d = lu.lu_internal()[(i, i)];
                lo = lo.min(d.abs());
                hi = hi.max(d.abs());
                sign *= d.signum();
            }
            let condition = if lo > 0.0 { hi / lo } else { f64::INFINITY };
            System {
                factor: Factor::Lu(lu),
                condition,
                det_sign: sign,
            }
        } else {
            let svd = SVD::new(j, true, true);
            let sv = &svd.singular_values;
            let lo = sv.iter().cloned().fold(f64::INFINITY, f64::min);
            let condition = if lo > 0.0 {
                sv.max() / lo
            } else {
                f64::INFINITY
            };
            System {
                factor: Factor::Svd(svd),
                condition,
                det_sign: 1.0,
            }
        };
        // Written to be true for a NaN condition as well.
        if !(sys.condition < HARD_CONDITION) {
            return Err(MechError::Singular {
                condition: sys.condition,
            });
        }
        Ok(sys)
    }

    /// Solve the scaled system and return the links' coordinate increments (x, y, φ) per
    /// moving link, φ in rad.
    fn solve(&self, sys: &System, b: &DVector<f64>) -> Result<DVector<f64>, MechError> {
        let mut x = sys.solve(b)?;
        for i in 0..x.len() / 3 {
            x[3 * i + 2] /= self.inst.scale;
        }
        Ok(x)
    }

    /// Move the links by the coordinate increments `dx`; returns the scaled ∞-norm of dx.
    fn advance(&self, s: &mut [LinkState], dx: &DVector<f64>) -> f64 {
        let scale = self.inst.scale;
        let mut step: f64 = 0.0;
        for (i, st) in s.iter_mut().enumerate().skip(1) {
            let c = 3 * (i - 1);
            st.pos += V2::new(dx[c], dx[c + 1]);
            let (sn, cs) = dx[c + 2].sin_cos();
            st.rot = rotate(st.rot, V2::new(cs, sn)).normalize();
            step = step
                .max(dx[c].abs())
                .max(dx[c + 1].abs())
                .max((dx[c + 2] * scale).abs());
        }
        if step.is_finite() {
            step
        } else {
            f64::INFINITY
        }
    }

    /// Scaled ∞-norm of a coordinate vector (x, y, φ·L).
    fn norm(&self, dx: &DVector<f64>) -> f64 {
        dx.iter().enumerate().fold(0.0f64, |a, (i, v)| {
            a.max(if i % 3 == 2 {
                (v * self.inst.scale).abs()
            } else {
                v.abs()
            })
        })
    }

    /// Set the links' velocities (`level` = Velocity) or accelerations (Acceleration) from
    /// the coordinate rates `x`.
    fn store(s: &mut [LinkState], x: &DVector<f64>, level: Level) {
        for (i, st) in s.iter_mut().enumerate().skip(1) {
            let c = 3 * (i - 1);
            if level == Level::Velocity {
                st.vel = V2::new(x[c], x[c + 1]);
                st.omega = x[c + 2];
            } else {
                st.acc = V2::new(x[c], x[c + 1]);
                st.alpha = x[c + 2];
            }
        }
    }

    /// Newton–Raphson on Φ(x; q) = 0 from `s` at the inputs `q`: iterate until the step is
    /// at most `tol` × L (the step is applied). A step that no longer decreases means the
    /// roundoff floor if the residual is at it ([`RESIDUAL_FLOOR`]), else no solution
    /// ([`MechError::NoAssembly`]). Returns the total correction (sum of the steps'
    /// scaled ∞-norms).
    fn newton(
        &self,
        s: &mut [LinkState],
        q: &[f64],
        tol: f64,
        max_iter: usize,
    ) -> Result<f64, MechError> {
        let zero = vec![0.0; q.len()];
        let scale = self.inst.scale;
        let (mut prev, mut total) = (f64::INFINITY, 0.0);
        for _ in 0..max_iter {
            let (j, b) = self.assemble(s, (q, &zero, &zero), Level::Position);
            let residual = b.amax();
            let sys = Self::factor(j)?;
            let dx = self.solve(&sys, &b)?;
            let step = self.norm(&dx);
            if !step.is_finite() {
                return Err(MechError::NoAssembly);
            }
            if step <= tol * scale {
                self.advance(s, &dx);
                return Ok(total + step);
            }
            if step >= prev {
                return if residual <= RESIDUAL_FLOOR * f64::EPSILON * scale {
                    Ok(total)
                } else {
                    Err(MechError::NoAssembly)
                };
            }
            self.advance(s, &dx);
            total += step;
            prev = step;
        }
        Err(MechError::NoAssembly)
    }

    /// Positions at inputs `q` by continuation from the drawing along q_ref + t·Δq, and the
    /// factored Jacobian there. For a revolute input Δq is q − q_ref reduced to [−π, π]
    /// (as atan2(sin, cos), exact for any finite q) and the path ends at q_ref + Δq, the
    /// same configuration as q (the driver equation is 2π-periodic); for a one-DOF
    /// revolute input whose short way fails, the long way round is tried as well.
    fn positions(&self, q: &[f64]) -> Result<(Vec<LinkState>, System), MechError> {
        if q.len() != self.dof() {
            return Err(MechError::InvalidInput(format!(
                "expected {} input values, got {}",
                self.dof(),
                q.len()
            )));
        }
        check_finite("q", q)?;
        let tau = std::f64::consts::TAU;
        let revolute: Vec<bool> = self
            .model
            .inputs
            .iter()
            .map(|&j| self.model.joints[j].kind == JointKind::Revolute)
            .collect();
        let delta: Vec<f64> = (0..q.len())
            .map(|k| {
                let d = q[k] - self.q_ref[k];
                if revolute[k] {
                    // Reduced through sin and cos, whose argument reduction is exact (a
                    // remainder by the f64 value of 2π is not, for |d| ≫ 1).
                    let (sn, cs) = d.sin_cos();
                    sn.atan2(cs)
                } else {
                    d
                }
            })
            .collect();
        match self.continuation(&delta) {
            Ok(r) => Ok(r),
            Err(e) if q.len() == 1 && revolute[0] && delta[0] != 0.0 => self
                .continuation(&[delta[0] - tau.copysign(delta[0])])
                .map_err(|_| e),
            Err(e) => Err(e),
        }
    }

    fn continuation(&self, delta: &[f64]) -> Result<(Vec<LinkState>, System), MechError> {
        let scale = self.inst.scale;
        let dof = delta.len();
        let q_end: Vec<f64> = (0..dof).map(|k| self.q_ref[k] + delta[k]).collect();
        let zero = vec![0.0; dof];
        let mut s = self.inst.drawing.clone();
        let mut t = 0.0f64;
        let (j, _) = self.assemble(&s, (&self.q_ref, &zero, &zero), Level::Position);
        let mut sys = Self::factor(j)?;
        let mut h = 1.0f64;
        let mut qt = self.q_ref.clone();
        for _ in 0..MAX_STEPS {
            // Tangent x' and curvature x'' of the path at t (q' = Δq, q'' = 0).
            for st in s.iter_mut() {
                st.vel = V2::zeros();
                st.omega = 0.0;
                st.acc = V2::zeros();
                st.alpha = 0.0;
            }
            let d1 = self.solve(&sys, &self.rhs(&s, (&qt, delta, &zero), Level::Velocity))?;
            let mut sv = s.clone();
            Self::store(&mut sv, &d1, Level::Velocity);
            let d2 = self.solve(
                &sys,
                &self.rhs(&sv, (&qt, delta, &zero), Level::Acceleration),
            )?;
            let speed = self.norm(&d1);
            h = h.min(1.0 - t);
            if speed > 0.0 {
                h = h.min(MAX_STEP * scale / speed);
            }
            let mut last_err = MechError::NoAssembly;
            loop {
                if h < MIN_STEP {
                    return Err(last_err);
                }
                let last = t + h >= 1.0;
                let q_new: Vec<f64> = if last {
                    q_end.clone()
                } else {
                    (0..dof)
                        .map(|k| self.q_ref[k] + (t + h) * delta[k])
                        .collect()
                };
                let mut trial = s.clone();
                let pred = &d1 * h + &d2 * (0.5 * h * h);
                let predicted = self.advance(&mut trial, &pred);
                let (tol, iters) = if last {
                    (self.tol, FINAL_ITERATIONS)
                } else {
                    (PATH_TOLERANCE, PATH_ITERATIONS)
                };
                let corrected = self
                    .newton(&mut trial, &q_new, tol, iters)
                    .and_then(|corr| {
                        if corr > MAX_CORRECTION * predicted + PATH_TOLERANCE * scale && !last {
                            return Err(MechError::NoAssembly);
                        }
                        let (j, _) = self.assemble(&trial, (&q_new, &zero, &zero), Level::Position);
                        let next = Self::factor(j)?;
                        if next.det_sign != sys.det_sign {
                            // The path crossed a dead point, or jumped to another branch.
                            return Err(MechError::Singular {
                                condition: next.condition.max(sys.condition),
                            });
                        }
                        Ok(next)
                    });
                match corrected {
                    Ok(next) => {
                        s = trial;
                        sys = next;
                        qt = q_new;
                        if last {
                            for st in s.iter_mut() {
                                st.vel = V2::zeros();
                                st.omega = 0.0;
                            }
                            return Ok((s, sys));
                        }
                        t += h;
                        h *= 2.0;
                        break;
                    }
                    Err(e) => {
                        last_err = e;
                        h *= 0.5;
                    }
                }
            }
        }
        Err(MechError::InvalidInput(format!(
            "the inputs are too far from the drawing: the position continuation needed more than {MAX_STEPS} steps"
        )))
    }

    /// Positions, velocities and (if `upto` is Acceleration) accelerations at (q, q̇, q̈).
    fn solve_states(
        &self,
        q: &[f64],
        qd: &[f64],
        qdd: &[f64],
        upto: Level,
    ) -> Result<(Vec<LinkState>, f64), MechError> {
        if qd.len() != self.dof() || qdd.len() != self.dof() {
            return Err(MechError::InvalidInput(format!(
                "expected {} input rates",
                self.dof()
            )));
        }
        check_finite("q, qd, qdd", q)?;
        check_finite("q, qd, qdd", qd)?;
        check_finite("q, qd, qdd", qdd)?;
        let (mut s, sys) = self.positions(q)?;
        if !(rate_error_bound(sys.condition) <= self.max_error) {
            return Err(MechError::Singular {
                condition: sys.condition,
            });
        }
        let x = self.solve(&sys, &self.rhs(&s, (q, qd, qdd), Level::Velocity))?;
        Self::store(&mut s, &x, Level::Velocity);
        if upto == Level::Acceleration {
            let x = self.solve(&sys, &self.rhs(&s, (q, qd, qdd), Level::Acceleration))?;
            Self::store(&mut s, &x, Level::Acceleration);
        }
        let numbers: Vec<f64> = (s.iter().skip(1))
            .flat_map(|st| {
                [
                    st.pos.x, st.pos.y, st.rot.x, st.rot.y, st.vel.x, st.vel.y, st.omega, st.acc.x,
                    st.acc.y, st.alpha,
                ]
            })
            .collect();
        let n = if upto == Level::Acceleration { 10 } else { 7 };
        finite_result(
            "link velocities or accelerations",
            &numbers
                .chunks(10)
                .flat_map(|c| &c[..n])
                .copied()
                .collect::<Vec<_>>(),
        )?;
        Ok((s, sys.condition))
    }

    // ---------------------------------------------------------------------------------
    // Public solvers
    // ---------------------------------------------------------------------------------

    /// Position analysis at inputs `q` (rad or m, one per input): every link's angle and
    /// cg, every point's position, by Newton on the whole loop system with continuation
    /// from the drawing (module docs). [`MechError::InvalidInput`] for a wrong length or a
    /// non-finite value, [`MechError::NoAssembly`] when the path from the drawing cannot
    /// reach `q`, [`MechError::Singular`] at a dead point or when the stated error bound
    /// [`position_error_bound`] exceeds [`GenericMechanism::max_error`].
    pub fn pose(&self, q: &[f64]) -> Result<GenericPose, MechError> {
        let (s, sys) = self.positions(q)?;
        if !(position_error_bound(sys.condition) <= self.max_error) {
            return Err(MechError::Singular {
                condition: sys.condition,
            });
        }
        let pose = GenericPose {
            links: self
                .inst
                .links
                .iter()
                .zip(&s)
                .map(|(l, st)| l.pose(st))
                .collect(),
            points: self
                .inst
                .points
                .iter()
                .map(|&(o, d)| point_pose(&s, o, d))
                .collect(),
            condition: sys.condition,
            model: self.model.clone(),
        };
        let numbers: Vec<f64> = (pose.links.iter())
            .flat_map(|l| [l.angle, l.cg.x, l.cg.y])
            .chain(pose.points.iter().flat_map(|p| [p.pos.x, p.pos.y]))
            .collect();
        finite_result("positions", &numbers)?;
        Ok(pose)
    }

    /// Position, velocity and acceleration analysis at (q, q̇, q̈): J ẋ = −Φ̇ and
    /// J ẍ = −Φ̈ with the same factored Jacobian J. Errors as [`GenericMechanism::pose`],
    /// with the bound [`rate_error_bound`].
    pub fn kinematics(
        &self,
        q: &[f64],
        qd: &[f64],
        qdd: &[f64],
    ) -> Result<GenericMotion, MechError> {
        let (s, condition) = self.solve_states(q, qd, qdd, Level::Acceleration)?;
        let links: Vec<LinkMotion> = self
            .inst
            .links
            .iter()
            .zip(&s)
            .map(|(l, st)| l.motion(st))
            .collect();
        let points: Vec<PointMotion> = self
            .inst
            .points
            .iter()
            .map(|&(o, d)| point_motion(&s, o, d))
            .collect();
        // The points and cgs derived from finite states can still overflow (ω² r).
        let numbers: Vec<f64> = (links.iter())
            .flat_map(|l| {
                [
                    l.angle, l.omega, l.alpha, l.cg.x, l.cg.y, l.cg_vel.x, l.cg_vel.y, l.cg_acc.x,
                    l.cg_acc.y,
                ]
            })
            .chain(
                points
                    .iter()
                    .flat_map(|p| [p.pos.x, p.pos.y, p.vel.x, p.vel.y, p.acc.x, p.acc.y]),
            )
            .collect();
        finite_result("velocities or accelerations", &numbers)?;
        Ok(GenericMotion {
            links,
            points,
            q: q.to_vec(),
            qd: qd.to_vec(),
            qdd: qdd.to_vec(),
            condition,
            states: s,
            model: self.model.clone(),
        })
    }

    /// The generalised forces (F_x, F_y, M about the anchor; N, N·m) on every link: loads,
    /// gravity m·g at the cg and, when `inertia`, d'Alembert's −m·a_G and −I_G·α.
    fn wrenches(
        &self,
        s: &[LinkState],
        loads: &GenericLoads,
        inertia: bool,
    ) -> Result<Vec<Wrench>, MechError> {
        if loads.values.len() != self.model.loads.len() {
            return Err(MechError::InvalidInput(format!(
                "expected {} load values, got {}",
                self.model.loads.len(),
                loads.values.len()
            )));
        }
        let mut f = vec![Wrench::zeros(); self.model.links.len()];
        if self.model.gravity.is_some() {
            for (l, geom) in self
                .inst
                .links
                .iter()
                .enumerate()
                .skip(1)
                .filter(|(_, g)| g.mass != 0.0)
            {
                add_gravity(&mut f[l], &s[l], geom, self.inst.gravity);
            }
        }
        for (k, (load, value)) in self.model.loads.iter().zip(&loads.values).enumerate() {
            match (load, value) {
                (Load::Force { link, .. }, LoadValue::Force(v)) => {
                    check_finite("loads", &[v.x, v.y])?;
                    add_force(&mut f[*link], &s[*link], self.inst.loads[k], *v);
                }
                (Load::Torque { link, .. }, LoadValue::Torque(t)) => {
                    check_finite("loads", &[*t])?;
                    add_torque(&mut f[*link], *t);
                }
                _ => {
                    return Err(MechError::InvalidInput(format!(
                        "load `{}` has the wrong kind of value (a force needs a vector, a torque a number)",
                        load.name()
                    )))
                }
            }
        }
        mech_core::elements::springs::add_wrenches(&self.inst.elements, s, &mut f);
        if inertia {
            for (l, geom) in self.inst.links.iter().enumerate().skip(1) {
                if geom.mass != 0.0 || geom.inertia != 0.0 {
                    add_inertia(&mut f[l], &s[l], geom);
                }
            }
        }
        // Before a dense solve meets them: a NaN there is a spring of zero length (or an
        // overflow), not a singular system.
        let numbers: Vec<f64> = f.iter().flat_map(|w| [w.x, w.y, w.z]).collect();
        finite_result("applied and inertia forces", &numbers)
            .map_err(|e| self.inst.blame_elements(&self.model, s, e))?;
        Ok(f)
    }

    /// A motion and loads made by this mechanism (or one with the same model).
    fn check_owner(&self, m: &GenericMotion, loads: &GenericLoads) -> Result<(), MechError> {
        let same = |other: &Arc<Model>| Arc::ptr_eq(other, &self.model) || **other == *self.model;
        if !same(&m.model) {
            return Err(MechError::InvalidInput(
                "the motion belongs to another mechanism".into(),
            ));
        }
        if !(Arc::ptr_eq(&loads.model, &self.model) || loads.model.loads == self.model.loads) {
            return Err(MechError::InvalidInput(
                "the loads belong to another mechanism".into(),
            ));
        }
        Ok(())
    }

    /// Kinetostatics by d'Alembert (`docs/theory.md` §4) as ONE dense system of every
    /// multiplier, Jᵀ λ = −f (f: loads, gravity, inertia wrenches per link): the motor
    /// action of every input and the reaction at every joint (force BY the joint's first
    /// link ON its second, N; prismatic joints add the moment, N·m, CCW on the second link).
    /// [`MechError::Redundant`] for a mechanism declared `#[allow(redundant)]` (its
    /// reactions are statically indeterminate), [`MechError::Singular`] at a dead point.
    pub fn kinetostatics(
        &self,
        m: &GenericMotion,
        loads: &GenericLoads,
    ) -> Result<GenericForces, MechError> {
        self.check_owner(m, loads)?;
        if self.rows != self.cols() {
            return Err(MechError::Redundant(format!(
                "{} constraint equations for {} coordinates: the reactions are statically indeterminate; use driver_action",
                self.rows,
                self.cols()
            )));
        }
        let s = &m.states;
        let f = self.wrenches(s, loads, true)?;
        let (j, _) = self.assemble(s, (&m.q, &m.qd, &m.qdd), Level::Position);
        let sys = Self::factor(j.transpose())?;
        // Jᵀ λ = −f in the scaled unknowns: (R J C)ᵀ μ = −C f, λ = R μ.
        let mut rhs = DVector::zeros(self.cols());
        for (k, w) in f.iter().skip(1).enumerate() {
            rhs[3 * k] = -w.x;
            rhs[3 * k + 1] = -w.y;
            rhs[3 * k + 2] = -w.z / self.inst.scale;
        }
        let lam = sys
            .solve(&rhs)?
            .component_mul(&DVector::from_column_slice(&self.row_scale));
        let mut driver = vec![0.0; self.dof()];
        let mut joints = vec![JointReaction::default(); self.model.joints.len()];
        for (c, &r) in self.cons.iter().zip(&self.first_row) {
            let g = &self.inst.joints[c.joint];
            match c.kind {
                ConKind::DriveRevolute(k) | ConKind::DrivePrismatic(k) => driver[k] = lam[r],
                ConKind::Revolute => joints[c.joint].force = V2::new(lam[r], lam[r + 1]),
                ConKind::Prismatic => {
                    joints[c.joint] = JointReaction {
                        force: slide_force(g, s, lam[r]),
                        moment: Some(lam[r + 1]),
                    }
                }
                ConKind::Slot => joints[c.joint].force = slide_force(g, s, lam[r]),
                ConKind::Mesh | ConKind::Rolling => {} // One row of a revolute (never produced by `all_cons`; kept total).
            }
        }
        let numbers: Vec<f64> = (driver.iter().copied())
            .chain(
                joints
                    .iter()
                    .flat_map(|r| [r.force.x, r.force.y, r.moment.unwrap_or(0.0)]),
            )
            .collect();
        finite_result("reactions or motor actions", &numbers)
            .map_err(|e| self.inst.blame_elements(&self.model, s, e))?;
        Ok(GenericForces {
            driver,
            joints,
            condition: sys.condition,
            model: self.model.clone(),
        })
    }

    /// The motor actions by the principle of virtual power, computing no reaction: for
    /// each input k the velocity field with q̇_k = 1, the others 0, and
    /// Q_k = −Σ (F·v + M·ω) over loads, gravity and inertia wrenches (N·m or N).
    /// Works for `#[allow(redundant)]` mechanisms too.
    pub fn driver_action(
        &self,
        m: &GenericMotion,
        loads: &GenericLoads,
    ) -> Result<Vec<f64>, MechError> {
        self.check_owner(m, loads)?;
        let s = &m.states;
        let f = self.wrenches(s, loads, true)?;
        let zero = vec![0.0; self.dof()];
        let (j, _) = self.assemble(s, (&m.q, &zero, &zero), Level::Position);
        let sys = Self::factor(j)?;
        let mut out = Vec::with_capacity(self.dof());
        for k in 0..self.dof() {
            let mut qd = zero.clone();
            qd[k] = 1.0;
            let mut v = s.clone();
            for st in v.iter_mut() {
                st.vel = V2::zeros();
                st.omega = 0.0;
            }
            let x = self.solve(&sys, &self.rhs(&v, (&m.q, &qd, &zero), Level::Velocity))?;
            Self::store(&mut v, &x, Level::Velocity);
            out.push(-virtual_power(&f, &v));
        }
        finite_result("motor actions", &out)
            .map_err(|e| self.inst.blame_elements(&self.model, s, e))?;
        Ok(out)
    }

    fn one_dof(&self) -> Result<(), MechError> {
        if self.dof() == 1 {
            Ok(())
        } else {
            Err(MechError::InvalidInput(format!(
                "Zhukovski's reduction needs one DOF, the mechanism has {}",
                self.dof()
            )))
        }
    }

    /// Zhukovski's reduced inertia of a one-DOF mechanism at q: I* = Σ (m |g_G|² + I_G g²)
    /// (kg·m², kg for a prismatic input) and dI*/dq = 2 Σ (m g_G·g′_G + I_G g g′), from the
    /// motion with q̇ = 1, q̈ = 0 ([`mech_core::solvers::zhukovski::reduced`]).
    pub fn reduced(&self, q: f64) -> Result<Reduced, MechError> {
        self.one_dof()?;
        let (s, _) = self.solve_states(&[q], &[1.0], &[0.0], Level::Acceleration)?;
        let r = zhukovski::reduced(&self.inst.links, &s);
        finite_result("reduced inertia", &[r.inertia, r.inertia_derivative])?;
        Ok(r)
    }

    /// Zhukovski's reduced moment of a one-DOF mechanism at q (N·m, N for a prismatic
    /// input): the power of the loads and gravity per unit input rate, M* = Σ F·g + Σ M·g.
    pub fn reduced_moment(&self, q: f64, loads: &GenericLoads) -> Result<f64, MechError> {
        self.one_dof()?;
        let (s, _) = self.solve_states(&[q], &[1.0], &[0.0], Level::Velocity)?;
        let f = self.wrenches(&s, loads, false)?;
        let moment = virtual_power(&f, &s);
        finite_result("reduced moment", &[moment])
            .map_err(|e| self.inst.blame_elements(&self.model, &s, e))?;
        Ok(moment)
    }

    /// The direct problem of a one-DOF mechanism: q̈ from I* q̈ + ½ dI*/dq q̇² = driver + M*
    /// (driver in N·m or N). [`MechError::NonPositiveInertia`] when I* ≤ 0.
    pub fn acceleration(
        &self,
        q: f64,
        qd: f64,
        driver: f64,
        loads: &GenericLoads,
    ) -> Result<f64, MechError> {
        self.one_dof()?;
        check_finite("q, qd, driver", &[q, qd, driver])?;
        let (s, _) = self.solve_states(&[q], &[1.0], &[0.0], Level::Acceleration)?;
        let f = self.wrenches(&s, loads, false)?;
        zhukovski::acceleration(
            zhukovski::reduced(&self.inst.links, &s),
            virtual_power(&f, &s),
            qd,
            driver,
        )
        .map_err(|e| self.inst.blame_elements(&self.model, &s, e))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use mech_core::kernel::kinematics::wrap;

    /// A crank-rocker four-bar with gravity and a load on the rocker.
    const FOUR_BAR: &str = r#"
        /// Crank-rocker.
        pub struct FourBar {
            gravity: (0.0, -9.81),
            ground { O2: (0.0, 0.0), O4: (0.3, 0.0) },
            link crank { points { O2, A: (0.0, 0.1) }, mass: 0.5, inertia: 1e-3, cg: (0.0, 0.05) },
            link coupler { points { A, B: (0.25, 0.25) }, mass: 1.0, inertia: 5e-3, cg: (0.12, 0.17) },
            link rocker { points { O4, B }, mass: 0.8, inertia: 3e-3, cg: (0.28, 0.12) },
            joints {
                O2: revolute(ground, crank),
                A: revolute(crank, coupler),
                B: revolute(coupler, rocker),
                O4: revolute(ground, rocker),
            },
            input: O2,
            loads { resist: torque on rocker, push: force on coupler at B },
        }
    "#;

    /// Textbook four-bar (Freudenstein's vector loop): angles of coupler and rocker from
    /// the crank angle, on the branch with B above the line A–O4 when `up`.
    fn four_bar_angles(a: f64, b: f64, c: f64, o4: V2, t2: f64, up: bool) -> (f64, f64) {
        let pa = V2::new(a * t2.cos(), a * t2.sin());
        let d = o4 - pa;
        let f = d.norm();
        let base = d.y.atan2(d.x);
        let gamma = ((b * b + f * f - c * c) / (2.0 * b * f)).acos();
        let t3 = if up { base + gamma } else { base - gamma };
        let pb = pa + V2::new(b * t3.cos(), b * t3.sin());
        let t4 = (pb.y - o4.y).atan2(pb.x - o4.x);
        (t3, t4)
    }

    #[test]
    fn generic_four_bar_matches_closed_form_and_routes_agree() {
        let m = GenericMechanism::parse(FOUR_BAR).unwrap();
        assert_eq!(m.dof(), 1);
        let (a, b, c) = (
            0.1,
            (0.25f64.powi(2) + 0.15f64.powi(2)).sqrt(),
            (0.05f64.powi(2) + 0.25f64.powi(2)).sqrt(),
        );
        let mut loads = m.loads();
        assert!(loads.set_by_name("resist", &[-2.0]));
        assert!(loads.set_by_name("push", &[3.0, -1.0]));
        assert!(!loads.set_by_name("push", &[3.0]));
        assert!(!loads.set_by_name("nothing", &[3.0]));
        for &q in &[std::f64::consts::FRAC_PI_2, 0.3, -2.0, 3.0, 7.0, -20.0] {
            let mo = m.kinematics(&[q], &[10.0], &[-4.0]).unwrap();
            let (t3, t4) = four_bar_angles(a, b, c, V2::new(0.3, 0.0), q, true);
            let d3 = wrap(mo.link("coupler").unwrap().angle - t3);
            let d4 = wrap(mo.link("rocker").unwrap().angle - t4);
            assert!(
                d3.abs() < 1e-13 && d4.abs() < 1e-13,
                "q = {q}: {d3:e} {d4:e}"
            );
            let fs = m.kinetostatics(&mo, &loads).unwrap();
            let vp = m.driver_action(&mo, &loads).unwrap();
            let r = m.reduced(q).unwrap();
            let ms = m.reduced_moment(q, &loads).unwrap();
            let zh = r.inertia * -4.0 + 0.5 * r.inertia_derivative * 100.0 - ms;
            let scale = fs.driver[0].abs().max(ms.abs());
            assert!(
                (fs.driver[0] - vp[0]).abs() < 1e-12 * scale,
                "{} {}",
                fs.driver[0],
                vp[0]
            );
            assert!(
                (fs.driver[0] - zh).abs() < 1e-12 * scale,
                "{} {zh}",
                fs.driver[0]
            );
            let acc = m.acceleration(q, 10.0, fs.driver[0], &loads).unwrap();
            assert!((acc + 4.0).abs() < 1e-10, "{acc}");
        }
    }

    #[test]
    fn load_errors_carry_line_and_column() {
        let e = GenericMechanism::parse(
            &FOUR_BAR.replace("revolute(coupler, rocker)", "revolute(coupler, rockr)"),
        )
        .unwrap_err();
        let MechError::Invalid(msg) = e else {
            panic!("{e:?}")
        };
        assert!(msg.starts_with("12:38: unknown link `rockr`"), "{msg}");
        let e = GenericMechanism::parse(&FOUR_BAR.replace("input: O2,", "inputs: [O2, O4],"))
            .unwrap_err();
        let MechError::Invalid(msg) = e else {
            panic!("{e:?}")
        };
        assert!(msg.contains("Grübler") && msg.contains("15:13"), "{msg}");
        let e =
            GenericMechanism::parse("pub struct X { ground { O: (0.0, 0.0) } link }").unwrap_err();
        let MechError::Invalid(msg) = e else {
            panic!("{e:?}")
        };
        assert!(msg.starts_with("1:"), "{msg}");
        assert!(matches!(
            GenericMechanism::load("/nonexistent/mechanism.txt"),
            Err(MechError::Invalid(_))
        ));
    }

    #[test]
    fn mechanisms_are_found_in_rust_source() {
        let source =
            format!("use mech::prelude::*;\n\nfn main() {{}}\n\nmechanism! {{{FOUR_BAR}}}\n");
        let m = GenericMechanism::from_rust_source(&source, "FourBar").unwrap();
        assert_eq!(
            m.pose(&[0.5]).unwrap().points,
            GenericMechanism::parse(FOUR_BAR)
                .unwrap()
                .pose(&[0.5])
                .unwrap()
                .points
        );
        let Err(MechError::Invalid(msg)) = GenericMechanism::from_rust_source(&source, "Nothing")
        else {
            panic!()
        };
        assert!(msg.contains("found: FourBar"), "{msg}");
        // Locations are in the source file: the DSL starts on line 5.
        let bad = source.replace("revolute(coupler, rocker)", "revolute(coupler, rockr)");
        let Err(MechError::Invalid(msg)) = GenericMechanism::from_rust_source(&bad, "FourBar")
        else {
            panic!()
        };
        assert!(msg.starts_with("16:38: unknown link `rockr`"), "{msg}");
        // The declaration's text, as written.
        assert_eq!(mechanism_text(&source, "FourBar").unwrap(), FOUR_BAR);
        assert!(mechanism_text(&source, "Nothing").is_err());
    }

    #[test]
    fn redundant_mechanism_gives_driver_actions_only() {
        let text = r#"#[allow(redundant)]
        pub struct Parallel {
            ground { O1: (0.0, 0.0), O2: (1.0, 0.0), O3: (2.0, 0.0) },
            link c1 { points { O1, A1: (0.0, 1.0) } },
            link c2 { points { O2, A2: (1.0, 1.0) } },
            link c3 { points { O3, A3: (2.0, 1.0) } },
            link coupler { points { A1, A2, A3 }, mass: 1.0, cg: (1.0, 1.0) },
            joints {
                O1: revolute(ground, c1), O2: revolute(ground, c2), O3: revolute(ground, c3),
                A1: revolute(c1, coupler), A2: revolute(c2, coupler), A3: revolute(c3, coupler),
            },
            input: O1,
        }"#;
        let m = GenericMechanism::parse(text).unwrap();
        let q = std::f64::consts::FRAC_PI_2 - 0.4;
        let mo = m.kinematics(&[q], &[2.0], &[0.0]).unwrap();
        // The coupler translates on a circle of radius 1: a_G = −ω² r (centripetal).
        let cg = mo.link("coupler").unwrap();
        assert!((cg.cg - V2::new(1.0 + q.cos(), q.sin())).norm() < 1e-13);
        assert!((cg.cg_acc + V2::new(q.cos(), q.sin()) * 4.0).norm() < 1e-12);
        assert!(matches!(
            m.kinetostatics(&mo, &m.loads()),
            Err(MechError::Redundant(_))
        ));
        // Virtual power: the driver balances the centripetal inertia force only (no gravity).
        let d = m.driver_action(&mo, &m.loads()).unwrap();
        assert!(d[0].abs() < 1e-12, "{d:?}");
    }

    #[test]
    fn bad_inputs_are_errors() {
        let m = GenericMechanism::parse(FOUR_BAR).unwrap();
        assert!(matches!(
            m.pose(&[f64::NAN]),
            Err(MechError::InvalidInput(_))
        ));
        assert!(matches!(
            m.pose(&[1.0, 2.0]),
            Err(MechError::InvalidInput(_))
        ));
        assert!(matches!(
            m.kinematics(&[1.0], &[f64::INFINITY], &[0.0]),
            Err(MechError::InvalidInput(_))
        ));
        let mo = m.kinematics(&[1.0], &[1.0], &[0.0]).unwrap();
        let mut loads = m.loads();
        loads.set_by_name("resist", &[f64::NAN]);
        assert!(matches!(
            m.kinetostatics(&mo, &loads),
            Err(MechError::InvalidInput(_))
        ));
        assert!(matches!(
            m.driver_action(&mo, &loads),
            Err(MechError::InvalidInput(_))
        ));
        assert!(matches!(
            m.acceleration(1.0, f64::NAN, 0.0, &m.loads()),
            Err(MechError::InvalidInput(_))
        ));
        assert!(m.clone().with_tolerance(0.0).is_err());
        assert!(m.clone().with_tolerance(f64::NAN).is_err());
    }
}
