//! The state of a link: its frame, the motion of its material points, and the plane
//! vector operations every kernel uses.
//!
//! A link's state is its frame: `pos`, the global position of its anchor (its first
//! point, or its cg when it has no point; the ground's anchor is the origin), and `rot`
//! = (cos φ, sin φ), its rotation since the drawing. Every point of a link is stored as
//! a *local vector* `d` = (reference position − reference anchor), so its current
//! position is `pos + R(φ) d`, its velocity `v + ω perp(r)` and its acceleration
//! `a + α perp(r) − ω² r` with r = R(φ) d. The link angle θ of
//! `docs/conventions.md` is θ = θ_ref + φ.

use nalgebra::Vector2;

/// A plane vector, m (or m/s, m/s², N).
pub type V2 = Vector2<f64>;

/// The vector turned +90°: perp(x, y) = (−y, x).
#[inline(always)]
pub fn perp(v: V2) -> V2 {
    V2::new(-v.y, v.x)
}

/// The scalar cross product a × b = a_x b_y − a_y b_x.
#[inline(always)]
pub fn cross(a: V2, b: V2) -> f64 {
    a.x * b.y - a.y * b.x
}

/// Rotate `d` by the unit complex `rot` = (cos φ, sin φ).
#[inline(always)]
pub fn rotate(rot: V2, d: V2) -> V2 {
    V2::new(rot.x * d.x - rot.y * d.y, rot.y * d.x + rot.x * d.y)
}

/// The complex quotient b/a = (a·b, a × b)/|a|²: the rotation and scale that take a to
/// b, so that `rotate(quotient(b, a), a)` = b (a ≠ 0).
#[inline(always)]
pub fn quotient(b: V2, a: V2) -> V2 {
    V2::new(a.dot(&b), cross(a, b)) * (1.0 / a.norm_squared())
}

/// Angle difference wrapped to (−π, π] (rad). Beyond |a| = 1e9 the reduction goes
/// through (sin a, cos a), which is exact for any finite a.
#[inline]
pub fn wrap(a: f64) -> f64 {
    // Already in range (a crank's q, most often): returned as the reduction below would
    // return it (no whole turn to remove, bit for bit), two compares instead of a division.
    if a > -std::f64::consts::PI && a <= std::f64::consts::PI {
        return a;
    }
    if !(a.abs() < 1e9) {
        let (s, c) = a.sin_cos();
        let r = s.atan2(c);
        return if r <= -std::f64::consts::PI {
            std::f64::consts::PI
        } else {
            r
        };
    }
    let t = std::f64::consts::TAU;
    // The nearest whole number of turns by adding and removing 1.5·2⁵² (exact below 2⁵¹
    // in magnitude, here < 1.6e8): the target's baseline has no rounding instruction,
    // and `f64::round` would be a library call.
    const ROUND: f64 = 6_755_399_441_055_744.0;
    let r = a - t * ((a / t + ROUND) - ROUND);
    if r <= -std::f64::consts::PI {
        r + t
    } else {
        r
    }
}

/// Position, velocity and acceleration of a link's frame (see the module docs).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LinkState {
    /// Anchor position, m.
    pub pos: V2,
    /// (cos φ, sin φ), φ the rotation since the drawing.
    pub rot: V2,
    /// Anchor velocity, m/s.
    pub vel: V2,
    /// Angular velocity ω, rad/s.
    pub omega: f64,
    /// Anchor acceleration, m/s².
    pub acc: V2,
    /// Angular acceleration α, rad/s².
    pub alpha: f64,
    /// φ itself, rad, counted over any number of turns: kept exactly by the kernels that
    /// know it (a driven crank from its input, a gear from its partner by Willis, a link
    /// sliding with its guide), which a gear train needs; the other kernels leave it, and
    /// readers ([`crate::elements::gears`]) know from the plan which links have it.
    pub angle: f64,
}

impl Default for LinkState {
    #[inline]
    fn default() -> Self {
        LinkState::at(V2::zeros())
    }
}

impl LinkState {
    /// At rest, unrotated, anchor at `pos` (the drawing's pose when `pos` is the reference anchor).
    pub const fn at(pos: V2) -> Self {
        LinkState {
            pos,
            rot: V2::new(1.0, 0.0),
            vel: V2::new(0.0, 0.0),
            omega: 0.0,
            acc: V2::new(0.0, 0.0),
            alpha: 0.0,
            angle: 0.0,
        }
    }
    /// The current vector from the anchor to the material point of local vector `d`.
    #[inline(always)]
    pub fn r(&self, d: V2) -> V2 {
        rotate(self.rot, d)
    }
    /// Position of the material point with local vector `d`.
    #[inline(always)]
    pub fn point(&self, d: V2) -> V2 {
        self.pos + self.r(d)
    }
    /// Velocity of the material point at current offset `r` from the anchor: v + ω perp(r).
    #[inline(always)]
    pub fn vel_at(&self, r: V2) -> V2 {
        self.vel + perp(r) * self.omega
    }
    /// Acceleration of the material point at offset `r`: a + α perp(r) − ω² r.
    #[inline(always)]
    pub fn acc_at(&self, r: V2) -> V2 {
        self.acc + perp(r) * self.alpha - r * (self.omega * self.omega)
    }
    /// Set ω and the anchor's velocity from the velocity `v_p` of the material point now
    /// at `p` (the same rigid field seen from p): v = v_p + ω perp(pos − p). When p is the
    /// anchor (a link's first point is often its joint's), v = v_p: a branch taken the same
    /// way at every call, and no arithmetic between ω and v (the direct problem waits on it).
    #[inline(always)]
    pub fn set_velocity_through(&mut self, p: V2, v_p: V2, omega: f64) {
        let r = self.pos - p;
        self.set_velocity_by(r.x == 0.0 && r.y == 0.0, r, v_p, omega);
    }
    /// [`LinkState::set_velocity_through`] for the point of local vector `d`: p is the
    /// anchor when d = 0, a test that folds at compile time when d is a literal zero (the
    /// generated code's joints at a link's first point, `JointGeom::with_links`).
    #[inline(always)]
    pub fn set_velocity_at(&mut self, d: V2, p: V2, v_p: V2, omega: f64) {
        self.set_velocity_by(d.x == 0.0 && d.y == 0.0, self.pos - p, v_p, omega);
    }
    #[inline(always)]
    fn set_velocity_by(&mut self, at_anchor: bool, r: V2, v_p: V2, omega: f64) {
        self.omega = omega;
        self.vel = if at_anchor {
            v_p
        } else {
            v_p + perp(r) * omega
        };
    }
    /// Set α and the anchor's acceleration from the acceleration `a_p` of the material
    /// point now at `p`, ω already set: a = a_p + α perp(r) − ω² r, r = pos − p (a = a_p
    /// when p is the anchor, as [`LinkState::set_velocity_through`]).
    #[inline(always)]
    pub fn set_acceleration_through(&mut self, p: V2, a_p: V2, alpha: f64) {
        let r = self.pos - p;
        self.set_acceleration_by(r.x == 0.0 && r.y == 0.0, r, a_p, alpha);
    }
    /// [`LinkState::set_acceleration_through`] for the point of local vector `d`, as
    /// [`LinkState::set_velocity_at`].
    #[inline(always)]
    pub fn set_acceleration_at(&mut self, d: V2, p: V2, a_p: V2, alpha: f64) {
        self.set_acceleration_by(d.x == 0.0 && d.y == 0.0, self.pos - p, a_p, alpha);
    }
    #[inline(always)]
    fn set_acceleration_by(&mut self, at_anchor: bool, r: V2, a_p: V2, alpha: f64) {
        self.alpha = alpha;
        self.acc = if at_anchor {
            a_p
        } else {
            a_p + perp(r) * alpha - r * (self.omega * self.omega)
        };
    }
}

/// The reference data of one link the solvers need: anchor, reference direction,
/// cg and inertia.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LinkGeom {
    /// Reference anchor (m), see the module docs.
    pub anchor: V2,
    /// (cos θ_ref, sin θ_ref): the link angle in the drawing.
    pub dir_ref: V2,
    /// θ_ref = atan2 of [`LinkGeom::dir_ref`] (rad, in (−π, π]): the angle of a link that
    /// never turns (one sliding on the ground, [`crate::model::Model::translates`]), which
    /// [`LinkGeom::angle`] would recompute at every call.
    pub angle_ref: f64,
    /// Local vector of the cg (m).
    pub dcg: V2,
    /// Mass (kg), 0 for massless.
    pub mass: f64,
    /// Moment of inertia about the cg (kg·m²).
    pub inertia: f64,
    /// Moment of inertia about the link's ground pivot O when it turns on one
    /// ([`crate::model::Model::ground_pivot`]), else about its anchor:
    /// I_O = I_G + m |G − O|² (kg·m²), a drawing constant kept so that the solvers do not
    /// recompute it per call ([`crate::solvers::zhukovski::ZhukovskiSums::inertia_about_pivot`]).
    pub inertia_pivot: f64,
    /// The cg in the frame of the link's first two points P₁ (the anchor) and P₂, drawn:
    /// κ = (a·g, a × g)/|a|² with a = P₂ − P₁ and g = G − P₁, so that in any pose
    /// G − P₁ = κ₁ e + κ₂ perp(e), e = P₂ − P₁ now ([`LinkGeom::cg_by_span`]); zero for a
    /// link with fewer than two distinct points.
    pub cg_span: V2,
    /// The axial position z̄ of the cg along the shaft axis z (m), `plane: z`
    /// ([`crate::model::shape::Axial`]): only the shaking couples about x and y read it.
    pub plane: f64,
    /// The products of inertia P = Σ mᵢ (zᵢ − z̄)(rᵢ − G) in the drawing (kg·m²), turning
    /// with the link: in a pose of angle θ it is rotated by θ − θ_ref.
    pub product: V2,
}

/// Position, velocity and acceleration of a point (`docs/conventions.md#generated-api`), m, m/s, m/s².
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct PointMotion {
    /// Position, m.
    pub pos: V2,
    /// Velocity, m/s.
    pub vel: V2,
    /// Acceleration, m/s².
    pub acc: V2,
}

/// Position of a point, m.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct PointPose {
    /// Position, m.
    pub pos: V2,
}

/// Motion of a link (`docs/conventions.md#generated-api`): θ (rad, wrapped to (−π, π]), ω, α, and its cg's motion.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct LinkMotion {
    /// Link angle θ, rad.
    pub angle: f64,
    /// ω, rad/s.
    pub omega: f64,
    /// α, rad/s².
    pub alpha: f64,
    /// cg position, m.
    pub cg: V2,
    /// cg velocity, m/s.
    pub cg_vel: V2,
    /// cg acceleration, m/s².
    pub cg_acc: V2,
}

/// Pose of a link: θ (rad, wrapped to (−π, π]) and cg position (m).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct LinkPose {
    /// Link angle θ, rad.
    pub angle: f64,
    /// cg position, m.
    pub cg: V2,
}

impl LinkGeom {
    /// The cg's current offset from the anchor, G − P₁ = κ₁ e + κ₂ perp(e), from the
    /// current vector e = P₂ − P₁ between the link's first two points
    /// ([`LinkGeom::cg_span`]): the rotation of the link is not needed, only e, which a
    /// dyad has as soon as it has placed its pins.
    #[inline(always)]
    pub fn cg_by_span(&self, e: V2) -> V2 {
        e * self.cg_span.x + perp(e) * self.cg_span.y
    }

    /// The link angle θ = θ_ref + φ, wrapped to (−π, π].
    #[inline]
    pub fn angle(&self, s: &LinkState) -> f64 {
        let d = rotate(s.rot, self.dir_ref);
        d.y.atan2(d.x)
    }
    /// The angle θ (rad, in (−π, π]) of a link that turns with the link `other` (the same
    /// rotation φ since the drawing: the two links of an RPR dyad, a slider and its
    /// guide), from that link's angle θₒ: θ = θₒ − θ_ref,ₒ + θ_ref, brought into (−π, π]
    /// by one turn at most (θₒ is in (−π, π] and each reference angle too, so the sum is
    /// within (−3π, 3π)). No atan2.
    #[inline(always)]
    pub fn angle_with(&self, other: &LinkGeom, other_angle: f64) -> f64 {
        use std::f64::consts::{PI, TAU};
        let a = (other_angle - other.angle_ref) + self.angle_ref;
        if a > PI {
            a - TAU
        } else if a <= -PI {
            a + TAU
        } else {
            a
        }
    }
    /// The angle θ (rad, in (−π, π]) of a link whose turn since the drawing its state
    /// keeps exact over turns ([`LinkState::angle`], a meshing link's): θ = θ_ref + φ
    /// brought into (−π, π] ([`wrap`]). No atan2.
    #[inline(always)]
    pub fn angle_tracked(&self, s: &LinkState) -> f64 {
        wrap(self.angle_ref + s.angle)
    }
    /// The pose of a link that slides on the ground and never turns
    /// ([`crate::model::Model::translates`]): its angle the drawing's, its cg at its
    /// anchor plus the drawn offset (m); nothing is rotated.
    #[inline(always)]
    pub fn pose_translating(&self, s: &LinkState) -> LinkPose {
        LinkPose {
            angle: self.angle_ref,
            cg: s.pos + self.dcg,
        }
    }
    /// The motion of a link that slides on the ground ([`LinkGeom::pose_translating`]):
    /// ω = α = 0, its cg moving as its anchor (m/s, m/s²).
    #[inline(always)]
    pub fn motion_translating(&self, s: &LinkState) -> LinkMotion {
        LinkMotion {
            angle: self.angle_ref,
            omega: 0.0,
            alpha: 0.0,
            cg: s.pos + self.dcg,
            cg_vel: s.vel,
            cg_acc: s.acc,
        }
    }
    /// The link's pose.
    #[inline]
    pub fn pose(&self, s: &LinkState) -> LinkPose {
        self.pose_at(s, self.angle(s))
    }
    /// The link's pose when its angle θ is already known (a crank on the ground: ±q).
    #[inline]
    pub fn pose_at(&self, s: &LinkState, angle: f64) -> LinkPose {
        LinkPose {
            angle,
            cg: s.point(self.dcg),
        }
    }
    /// The link's motion.
    #[inline]
    pub fn motion(&self, s: &LinkState) -> LinkMotion {
        self.motion_at(s, self.angle(s))
    }
    /// The link's motion when its angle θ is already known (a crank on the ground: ±q).
    #[inline]
    pub fn motion_at(&self, s: &LinkState, angle: f64) -> LinkMotion {
        let r = s.r(self.dcg);
        LinkMotion {
            angle,
            omega: s.omega,
            alpha: s.alpha,
            cg: s.pos + r,
            cg_vel: s.vel_at(r),
            cg_acc: s.acc_at(r),
        }
    }
}

/// The current position of the material point of local vector `d` on link `l` of the
/// states `s`. The ground (link 0) never moves and its anchor is the origin, so its points
/// are their local vectors: no rotation is spent on them.
#[inline(always)]
pub fn point_of(s: &[LinkState], l: usize, d: V2) -> V2 {
    if l == 0 {
        d
    } else {
        s[l].point(d)
    }
}

/// The zero vector written as (−0, −0): the identity of IEEE addition (−0 + x = x and
/// −0 − x = −x for every x, where +0 + x is not x when x = −0), so that a term known to be
/// zero (the ground's velocity, a sum's start) costs nothing once the compiler sees it.
#[inline(always)]
pub fn zero() -> V2 {
    V2::new(-0.0, -0.0)
}

/// The current direction of the local vector `d` of link `l` (unrotated on the ground).
#[inline(always)]
pub fn dir_of(s: &[LinkState], l: usize, d: V2) -> V2 {
    if l == 0 {
        d
    } else {
        s[l].r(d)
    }
}

/// The motion of the material point of local vector `d` on link `l` of the states `s`
/// (at rest on the ground, link 0, whose points are their local vectors).
#[inline]
pub fn point_motion(s: &[LinkState], l: usize, d: V2) -> PointMotion {
    if l == 0 {
        return PointMotion {
            pos: d,
            vel: V2::zeros(),
            acc: V2::zeros(),
        };
    }
    let s = &s[l];
    let r = s.r(d);
    PointMotion {
        pos: s.pos + r,
        vel: s.vel_at(r),
        acc: s.acc_at(r),
    }
}

/// The motion of a link's anchor (its first point): the state's own position, velocity
/// and acceleration, nothing rotated.
#[inline(always)]
pub fn anchor_motion(s: &LinkState) -> PointMotion {
    PointMotion {
        pos: s.pos,
        vel: s.vel,
        acc: s.acc,
    }
}

/// The position of a link's anchor (its first point): the state's own.
#[inline(always)]
pub fn anchor_pose(s: &LinkState) -> PointPose {
    PointPose { pos: s.pos }
}

/// The position of the material point of local vector `d` on link `l` of the states `s`.
#[inline]
pub fn point_pose(s: &[LinkState], l: usize, d: V2) -> PointPose {
    PointPose {
        pos: point_of(s, l, d),
    }
}

#[cfg(test)]
mod tests {
    use super::wrap;
    use crate::kernel::measure::within;
    use std::f64::consts::{PI, TAU};

    /// `wrap` against the independent route atan2(sin a, cos a), over the ordinary range
    /// and at the half turns, where the two ways of rounding to whole turns differ.
    #[test]
    fn wrap_matches_atan2_and_keeps_the_half_open_range() {
        for k in -4000..=4000 {
            let a = k as f64 * 0.37 + 1e-3;
            let (s, c) = a.sin_cos();
            let d = wrap(a) - s.atan2(c);
            // measured worst 1.5e-16 (be05608); 100×
            assert!(
                within(d.abs(), 1e-14 * a.abs().max(1.0)),
                "wrap({a}) off by {d:e}"
            );
        }
        for n in -7..=7 {
            let a = (n as f64 + 0.5) * TAU;
            let w = wrap(a);
            assert!(w > -PI && w <= PI, "wrap({a}) = {w}");
            assert!(
                within((w.abs() - PI).abs(), 1e-14 * a.abs().max(1.0)), // measured worst 1.0e-16 (be05608); 100×
                "wrap({a}) = {w}"
            );
        }
        assert_eq!(wrap(0.0), 0.0);
        // In range, the angle itself (the fast path and the reduction agree bit for bit).
        for a in [PI, -PI + 1e-15, 3.0, -3.0, 1e-300, -0.0] {
            assert_eq!(wrap(a).to_bits(), a.to_bits(), "wrap({a})");
        }
        assert_eq!(wrap(1e8 * TAU + 1.0).round(), 1.0);
    }
}
