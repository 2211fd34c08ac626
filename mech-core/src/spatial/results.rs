//! What a spatial motion answers by name (a point's motion, a link's).

use super::kinematics::{BodyMotion, Layout, SpatialMotion};
use nalgebra::{UnitQuaternion, Vector3};

type V3 = Vector3<f64>;

/// One link's motion (SI, global axes).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LinkMotion {
    /// The rotation from the drawing.
    pub rotation: UnitQuaternion<f64>,
    /// ω, rad/s.
    pub omega: V3,
    /// α, rad/s².
    pub alpha: V3,
    /// The cg's position (m): the link's reference point, its cg when declared, else its
    /// first point.
    pub cg: V3,
    /// The cg's velocity, m/s.
    pub cg_velocity: V3,
    /// The cg's acceleration, m/s².
    pub cg_acceleration: V3,
}

/// One link's pose (SI, global axes): what `pose` gives of a link.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LinkPose {
    /// The rotation from the drawing.
    pub rotation: UnitQuaternion<f64>,
    /// The reference point's position (m): the cg when declared, else the first point.
    pub cg: V3,
}

/// One point's position (m, global axes).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PointPose {
    /// The position, m.
    pub pos: V3,
}

/// One point's motion (SI, global axes).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PointMotion {
    /// The position, m.
    pub pos: V3,
    /// The velocity, m/s.
    pub vel: V3,
    /// The acceleration, m/s².
    pub acc: V3,
}

impl From<LinkMotion> for LinkPose {
    fn from(m: LinkMotion) -> Self {
        LinkPose {
            rotation: m.rotation,
            cg: m.cg,
        }
    }
}

impl From<[V3; 3]> for PointMotion {
    fn from([pos, vel, acc]: [V3; 3]) -> Self {
        PointMotion { pos, vel, acc }
    }
}

impl SpatialMotion {
    /// The position (m), velocity (m/s) and acceleration (m/s²) of the point `name`, moved
    /// with the first link that lists it (the ground first).
    pub fn point_motion(&self, name: &str) -> Option<[V3; 3]> {
        let p = self.layout.model.point_index(name)?;
        self.point_motion_at(p)
    }

    /// [`SpatialMotion::point_motion`] of the point with index `p` in the model's points.
    pub fn point_motion_at(&self, p: usize) -> Option<[V3; 3]> {
        let (b, s) = anchor(&self.layout, p)?;
        Some(self.bodies[b].point(s))
    }

    /// The position of the point `name`, m.
    pub fn point(&self, name: &str) -> Option<V3> {
        self.point_motion(name).map(|m| m[0])
    }

    /// The motion of the link `name` (`ground` included).
    pub fn link(&self, name: &str) -> Option<LinkMotion> {
        self.link_at(self.layout.model.body_index(name)?)
    }

    /// [`SpatialMotion::link`] of the body with index `b` (the ground is 0).
    pub fn link_at(&self, b: usize) -> Option<LinkMotion> {
        self.bodies.get(b).map(LinkMotion::from)
    }
}

impl From<&BodyMotion> for LinkMotion {
    fn from(m: &BodyMotion) -> Self {
        LinkMotion {
            rotation: m.state.rot,
            omega: m.state.w,
            alpha: m.alpha,
            cg: m.state.o,
            cg_velocity: m.state.v,
            cg_acceleration: m.a,
        }
    }
}

/// The body a point moves with (the first that lists it, the ground first) and the point's
/// offset from that body's reference point in the drawing, m.
pub(crate) fn anchor(layout: &Layout, p: usize) -> Option<(usize, V3)> {
    let model = &layout.model;
    let b = model.bodies.iter().position(|b| b.points.contains(&p))?;
    Some((b, model.points[p].1 - layout.o0[b]))
}
