//! What a spatial motion answers by name (a point's motion, a link's).

use super::kinematics::SpatialMotion;
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

impl SpatialMotion {
    /// The position (m), velocity (m/s) and acceleration (m/s²) of the point `name`, moved
    /// with the first link that lists it (the ground first).
    pub fn point_motion(&self, name: &str) -> Option<[V3; 3]> {
        let model = &self.layout.model;
        let p = model.point_index(name)?;
        let b = model.bodies.iter().position(|b| b.points.contains(&p))?;
        Some(self.bodies[b].point(model.points[p].1 - self.layout.o0[b]))
    }

    /// The position of the point `name`, m.
    pub fn point(&self, name: &str) -> Option<V3> {
        self.point_motion(name).map(|m| m[0])
    }

    /// The motion of the link `name` (`ground` included).
    pub fn link(&self, name: &str) -> Option<LinkMotion> {
        let b = self.layout.model.body_index(name)?;
        let m = &self.bodies[b];
        Some(LinkMotion {
            rotation: m.state.rot,
            omega: m.state.w,
            alpha: m.alpha,
            cg: m.state.o,
            cg_velocity: m.state.v,
            cg_acceleration: m.a,
        })
    }
}
