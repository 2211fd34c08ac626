//! What a run-time [`Mechanism`](crate::Mechanism) returns: [`Pose`], [`Motion`], [`Forces`], and the
//! [`Loads`] it takes, each answering by name (`link`, `point`, `reaction`, `set_by_name`).

use crate::kernel::link_state::{LinkMotion, LinkPose, LinkState, PointMotion, PointPose, V2};
use crate::model::{Load, Model};
use smallvec::SmallVec;
use std::sync::Arc;

/// The values of a run-time mechanism's loads, in declaration order. [`Mechanism::loads`](crate::Mechanism::loads)
/// makes them all zero with the names; `Default` is "no load" (every load zero).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Loads {
    /// One value per declared load (declaration order); missing entries count as zero.
    pub values: Vec<LoadValue>,
    pub(super) model: Option<Arc<Model>>,
}

impl Loads {
    /// Set the load named `name` from its components (2 for a force, N; 1 for a torque,
    /// N·m); false when there is no such load or the length is wrong.
    pub fn set_by_name(&mut self, name: &str, value: &[f64]) -> bool {
        match &self.model {
            Some(model) => set_load(model, &mut self.values, name, value),
            None => false,
        }
    }
}

/// Result of [`Mechanism::pose`](crate::Mechanism::pose): every link's angle (rad) and cg (m), every point (m),
/// indexed like [`Model::links`] (0 = the ground) and [`Model::points`].
#[derive(Clone, Debug, PartialEq)]
pub struct Pose {
    /// Links, ground first.
    pub links: Vec<LinkPose>,
    /// Points.
    pub points: Vec<PointPose>,
    pub(super) model: Arc<Model>,
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

/// Result of [`Mechanism::kinematics`](crate::Mechanism::kinematics): positions, velocities, accelerations of every link
/// and point (indexed like the model), and the input values.
#[derive(Clone, Debug, PartialEq)]
pub struct Motion {
    /// Links, ground first: θ, ω, α, cg and its velocity and acceleration.
    pub links: Vec<LinkMotion>,
    /// Points: position, velocity, acceleration.
    pub points: Vec<PointMotion>,
    /// q, q̇ and q̈ of this motion, one after the other (G values each).
    pub(super) inputs: SmallVec<[f64; 12]>,
    pub(super) states: Vec<LinkState>,
    /// What each group's closed form keeps for its reactions (one per group of the plan),
    /// as the generated motion's `systems`.
    pub(super) systems: Vec<crate::kernel::kinematics::DyadSystem>,
    pub(super) model: Arc<Model>,
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

/// Result of [`Mechanism::kinetostatics`](crate::Mechanism::kinetostatics): the motor action of each input and the reaction
/// at every joint (force BY a ON b, N; a prismatic joint's moment about its point, N·m).
#[derive(Clone, Debug, PartialEq)]
pub struct Forces {
    /// Motor actions: torque (N·m) or axial force (N) by a on b.
    pub driver: Vec<f64>,
    /// Reactions, indexed like [`Model::joints`].
    pub joints: Vec<JointReaction>,
    pub(super) model: Arc<Model>,
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

/// The value of one declared load.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum LoadValue {
    /// A force, N (global vector), applied at the load's point.
    Force(V2),
    /// A pure torque, N·m (CCW positive).
    Torque(f64),
}

/// Set the load named `name` of `model` in `values` (declaration order) from its
/// components: 2 for a force (N), 1 for a torque (N·m); false when there is no such load
/// or the length is wrong. Used by [`Loads::set_by_name`].
pub fn set_load(model: &Model, values: &mut [LoadValue], name: &str, value: &[f64]) -> bool {
    let Some(k) = model.loads.iter().position(|l| l.name() == name) else {
        return false;
    };
    let Some(slot) = values.get_mut(k) else {
        return false;
    };
    match (&model.loads[k], value) {
        (Load::Force { .. }, [x, y]) => *slot = LoadValue::Force(V2::new(*x, *y)),
        (Load::Torque { .. }, [t]) => *slot = LoadValue::Torque(*t),
        _ => return false,
    }
    true
}

/// The reaction at one joint: the force BY its first link ON its second (N, global) and,
/// for a prismatic joint, the moment on the second link about the joint point (N·m, CCW).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct JointReaction {
    /// Force by a on b, N. Normal to the axis for prismatic and slot joints.
    pub force: V2,
    /// Prismatic joints only: moment by a on b about the joint point's position, N·m.
    pub moment: Option<f64>,
}
