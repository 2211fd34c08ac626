//! The plain data of a spatial mechanism (bodies, 3-D points, joints, inputs, loads).

use nalgebra::{Matrix3, Vector3};

/// The kind of a spatial joint and its geometry, all vectors in the drawing's global axes
/// (dimensionless unit vectors; a pitch in m per turn). The class k of a pair is the number
/// of freedoms it leaves (6 − k equations, 6 − k reaction components).
#[derive(Clone, Debug, PartialEq)]
pub enum JointKind {
    /// `revolute(a, b) axis (ux, uy, uz)`: a pin with its axis fixed in both links; class I
    /// (5 equations: the point, and the axis kept in line).
    Revolute {
        /// The pin's axis (unit).
        axis: Vector3<f64>,
    },
    /// `prismatic(a, b) along (ux, uy, uz)`: b slides along an axis fixed in a, no rotation;
    /// class I (5 equations).
    Prismatic {
        /// The sliding direction (unit), fixed in a.
        axis: Vector3<f64>,
    },
    /// `cylindrical(a, b) axis (..)`: b turns about and slides along an axis fixed in a;
    /// class II (4 equations).
    Cylindrical {
        /// The axis (unit), fixed in a.
        axis: Vector3<f64>,
    },
    /// `spherical(a, b)`: a ball joint; class III (3 equations: the point).
    Spherical,
    /// `universal(a, b) axes (u1) (u2)`: a Hooke joint, the cross's first axis fixed in a,
    /// its second (perpendicular in the drawing) fixed in b; class II (4 equations).
    Universal {
        /// The cross's axis fixed in a (unit).
        first: Vector3<f64>,
        /// The cross's axis fixed in b (unit), perpendicular to `first` in the drawing.
        second: Vector3<f64>,
    },
    /// `helical(a, b) axis (..) pitch p`: a screw, b advancing p (m) along the axis per turn
    /// of b about it relative to a: u·d = p θ / (2π); class I (5 equations).
    Helical {
        /// The screw's axis (unit), fixed in a.
        axis: Vector3<f64>,
        /// The lead, m per turn (signed: positive for a right-handed screw about `axis`).
        pitch: f64,
    },
}

impl JointKind {
    /// The DSL word of the kind (`revolute`, `prismatic`, ...).
    pub fn word(&self) -> &'static str {
        match self {
            JointKind::Revolute { .. } => "revolute",
            JointKind::Prismatic { .. } => "prismatic",
            JointKind::Cylindrical { .. } => "cylindrical",
            JointKind::Spherical => "spherical",
            JointKind::Universal { .. } => "universal",
            JointKind::Helical { .. } => "helical",
        }
    }

    /// The class k of the pair: the freedoms it leaves between its links (it removes 6 − k).
    /// Revolute, prismatic, helical: I; cylindrical, universal: II; spherical: III.
    pub fn class(&self) -> usize {
        match self {
            JointKind::Revolute { .. }
            | JointKind::Prismatic { .. }
            | JointKind::Helical { .. } => 1,
            JointKind::Cylindrical { .. } | JointKind::Universal { .. } => 2,
            JointKind::Spherical => 3,
        }
    }
}

/// A rigid body of a spatial mechanism (the ground is body 0).
#[derive(Clone, Debug, PartialEq)]
pub struct Body {
    /// The link's name (`ground` for the frame).
    pub name: String,
    /// Its points, indices into [`SpatialModel::points`].
    pub points: Vec<usize>,
    /// Mass, kg (0: massless, no inertia terms).
    pub mass: f64,
    /// The centre of gravity in the drawing, m; `None` when not declared.
    pub cg: Option<Vector3<f64>>,
    /// The inertia tensor about the cg in the drawing's axes, kg·m²: the matrix
    /// [[Ixx, −Ixy, −Ixz], [−Ixy, Iyy, −Iyz], [−Ixz, −Iyz, Izz]] of the DSL's
    /// `inertia: (Ixx, Iyy, Izz, Ixy, Ixz, Iyz)` (products of inertia Ixy = Σ m x y).
    pub inertia: Matrix3<f64>,
}

/// A joint between two bodies at a point.
#[derive(Clone, Debug, PartialEq)]
pub struct Joint {
    /// The joint's name.
    pub name: String,
    /// Its kind and axes.
    pub kind: JointKind,
    /// The first body (index into [`SpatialModel::bodies`]): the reaction is BY it.
    pub a: usize,
    /// The second body: the reaction acts ON it.
    pub b: usize,
    /// The joint's point (index into [`SpatialModel::points`]); for prismatic, cylindrical
    /// and helical joints a point of b.
    pub point: usize,
}

/// What a load acts on.
#[derive(Clone, Debug, PartialEq)]
pub enum LoadKind {
    /// `force on LINK at P`: a force (N, global axes) at point P of the link.
    Force {
        /// The body.
        body: usize,
        /// The point of application.
        point: usize,
    },
    /// `torque on LINK`: a pure moment (N·m about the global axes).
    Torque {
        /// The body.
        body: usize,
    },
}

/// A named load; its value is given at each call ([`crate::spatial::SpatialLoads`]).
#[derive(Clone, Debug, PartialEq)]
pub struct Load {
    /// The load's name.
    pub name: String,
    /// What it acts on.
    pub kind: LoadKind,
}

/// A spatial mechanism as plain data, SI units, the drawing's global coordinates.
#[derive(Clone, Debug, PartialEq)]
pub struct SpatialModel {
    /// The struct's name.
    pub name: String,
    /// Gravity's acceleration (m/s²), `None` when not declared.
    pub gravity: Option<Vector3<f64>>,
    /// Every point: name and drawing position (m).
    pub points: Vec<(String, Vector3<f64>)>,
    /// The bodies, the ground first.
    pub bodies: Vec<Body>,
    /// The joints in the order written.
    pub joints: Vec<Joint>,
    /// The input joints (indices into `joints`), in the order of q.
    pub inputs: Vec<usize>,
    /// The loads in the order written.
    pub loads: Vec<Load>,
    /// `#[allow(redundant)]`: redundant constraints accepted (the mobility is then the
    /// rank's, 6(N − 1) − rank at the drawing; no reactions, the motor actions by virtual
    /// power).
    pub allow_redundant: bool,
}

impl SpatialModel {
    /// The index of the point `name`.
    pub fn point_index(&self, name: &str) -> Option<usize> {
        self.points.iter().position(|(n, _)| n == name)
    }

    /// The index of the body `name` (`ground` is 0).
    pub fn body_index(&self, name: &str) -> Option<usize> {
        self.bodies.iter().position(|b| b.name == name)
    }

    /// The index of the joint `name`.
    pub fn joint_index(&self, name: &str) -> Option<usize> {
        self.joints.iter().position(|j| j.name == name)
    }
}

/// The inertia tensor (kg·m²) of the DSL's six numbers (Ixx, Iyy, Izz, Ixy, Ixz, Iyz), the
/// products taken as Ixy = Σ m x y: I = [[Ixx, −Ixy, −Ixz], [−Ixy, Iyy, −Iyz], [−Ixz, −Iyz, Izz]].
pub fn inertia_tensor(six: [f64; 6]) -> Matrix3<f64> {
    let [xx, yy, zz, xy, xz, yz] = six;
    Matrix3::new(xx, -xy, -xz, -xy, yy, -yz, -xz, -yz, zz)
}

/// Where a check's finding belongs in the declaration (the macro puts its error there).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Site {
    /// The whole mechanism (its name).
    Whole,
    /// The inputs' declaration (`input:` / `inputs:`).
    Inputs,
    /// A body, index into [`SpatialModel::bodies`].
    Body(usize),
    /// A joint, index into [`SpatialModel::joints`].
    Joint(usize),
}

/// A check's finding: the message, where it belongs and the other places it involves.
#[derive(Clone, Debug, PartialEq)]
pub struct Finding {
    /// Where the message is put.
    pub site: Site,
    /// What is wrong, the numbers and the fix.
    pub message: String,
    /// Other places taking part (shown as "involved here").
    pub involved: Vec<Site>,
}
