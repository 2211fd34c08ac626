//! Zhukovski's sums in lanes: the twin of `solvers::zhukovski::ZhukovskiSums` (method for
//! method, the same names) and of its `acceleration`, over the states of the motion with
//! q̇ = 1, q̈ = 0 (`docs/theory.md` §6).

use super::simd::{Backend, Base, Mask, L, V2L};
use super::LinkLanes;
use crate::kernel::link_state::{LinkGeom, V2};

/// I*, dI*/dq and M* accumulated link by link and load by load in four configurations,
/// each term as `solvers::zhukovski::ZhukovskiSums` computes it:
/// I* = Σ (m |g_G|² + I_G g²), dI*/dq = 2 Σ (m g_G·g'_G + I_G g g'),
/// M* = Σ F·g_P + Σ M g + Σ m g·g_G (gravity), g and g' the velocities and accelerations
/// of the states.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ZhukovskiLanes<B: Backend = Base> {
    /// I*, kg·m² (kg for a prismatic input).
    pub inertia: L<B>,
    /// dI*/dq, kg·m²/rad (kg/m for a prismatic input).
    pub inertia_derivative: L<B>,
    /// M*, N·m (N for a prismatic input).
    pub moment: L<B>,
}

impl<B: Backend> Default for ZhukovskiLanes<B> {
    /// [`ZhukovskiLanes::new`].
    #[inline(always)]
    fn default() -> Self {
        Self::new()
    }
}

impl<B: Backend> ZhukovskiLanes<B> {
    /// Empty sums, started at −0 (the identity of IEEE addition), as `ZhukovskiSums::new`.
    #[inline(always)]
    pub fn new() -> Self {
        ZhukovskiLanes {
            inertia: L::splat(-0.0),
            inertia_derivative: L::splat(-0.0),
            moment: L::splat(-0.0),
        }
    }
    /// Add a link's inertia to I* and dI*/dq: with r = G − anchor = R(φ) d_cg, v_G = v +
    /// ω perp(r), I* += m |v_G|² + I_G ω², dI*/dq += 2m v_G·(a − ω² r) + (2m v_G·perp(r) +
    /// 2 I_G ω) α (kg·m², kg·m²/rad).
    #[inline(always)]
    pub fn inertia(&mut self, l: &LinkGeom, s: &LinkLanes<B>) {
        self.inertia_at(l, s, s.r(l.dcg));
    }
    /// [`ZhukovskiLanes::inertia`] for a link whose second point is the anchor of the link
    /// in state `next`: r = κ₁ e + κ₂ perp(e), e = next.pos − pos (`LinkGeom::cg_by_span`).
    #[inline(always)]
    pub fn inertia_spanned(&mut self, l: &LinkGeom, s: &LinkLanes<B>, next: &LinkLanes<B>) {
        let e = next.pos - s.pos;
        self.inertia_at(l, s, e * l.cg_span.x + e.perp() * l.cg_span.y);
    }
    /// [`ZhukovskiLanes::inertia`] with the cg's current offset r = G − anchor (m) given.
    #[inline(always)]
    pub fn inertia_at(&mut self, l: &LinkGeom, s: &LinkLanes<B>, r: V2L<B>) {
        let v = s.vel_at(r);
        let m2 = 2.0 * l.mass;
        self.inertia += v.norm_squared() * l.mass + s.omega * l.inertia * s.omega;
        let without_alpha = v.dot(s.acc - r * (s.omega * s.omega)) * m2;
        let per_alpha = v.dot(r.perp()) * m2 + s.omega * (2.0 * l.inertia);
        self.inertia_derivative += without_alpha + per_alpha * s.alpha;
    }
    /// Add the inertia of a link turning about its ground pivot, a fixed pin: I* += I_O ω²,
    /// dI*/dq += 2 I_O ω α, I_O = `l.inertia_pivot` (kg·m²).
    #[inline(always)]
    pub fn inertia_about_pivot(&mut self, l: &LinkGeom, s: &LinkLanes<B>) {
        let io = l.inertia_pivot;
        self.inertia += s.omega * io * s.omega;
        self.inertia_derivative += (s.omega * (2.0 * io)) * s.alpha;
    }
    /// Add the inertia of a link that slides on the ground: I* += m |v|²,
    /// dI*/dq += 2m v·a (kg).
    #[inline(always)]
    pub fn inertia_translating(&mut self, l: &LinkGeom, s: &LinkLanes<B>) {
        self.inertia += s.vel.norm_squared() * l.mass;
        self.inertia_derivative += s.vel.dot(s.acc) * (2.0 * l.mass);
    }
    /// Add the power of gravity `g` (m/s²) on a link that slides on the ground, m g·v, to M*.
    #[inline(always)]
    pub fn gravity_translating(&mut self, l: &LinkGeom, s: &LinkLanes<B>, g: V2) {
        self.moment += s.vel.dot_v(g) * l.mass;
    }
    /// Add the power of gravity `g` (m/s²) on a link, m g·v_G, to M*.
    #[inline(always)]
    pub fn gravity(&mut self, l: &LinkGeom, s: &LinkLanes<B>, g: V2) {
        self.gravity_at(l, s, g, s.r(l.dcg));
    }
    /// [`ZhukovskiLanes::gravity`] for a link whose second point is the anchor of the link
    /// in state `next`, as [`ZhukovskiLanes::inertia_spanned`].
    #[inline(always)]
    pub fn gravity_spanned(&mut self, l: &LinkGeom, s: &LinkLanes<B>, next: &LinkLanes<B>, g: V2) {
        let e = next.pos - s.pos;
        self.gravity_at(l, s, g, e * l.cg_span.x + e.perp() * l.cg_span.y);
    }
    /// [`ZhukovskiLanes::gravity`] with the cg's offset r = G − anchor (m) given.
    #[inline(always)]
    pub fn gravity_at(&mut self, l: &LinkGeom, s: &LinkLanes<B>, g: V2, r: V2L<B>) {
        self.moment += s.vel_at(r).dot_v(g) * l.mass;
    }
    /// Add the power of a force `f` (N, the same in every lane) at the material point of
    /// local vector `d` (m), f·v_P, to M* (v_P the anchor's when d = 0).
    #[inline(always)]
    pub fn force(&mut self, s: &LinkLanes<B>, d: V2, f: V2) {
        self.moment += point_velocity(s, d).dot_v(f);
    }
    /// [`ZhukovskiLanes::force`] with a force `[f_x, f_y]` (N) per configuration.
    #[inline(always)]
    pub fn force_lanes(&mut self, s: &LinkLanes<B>, d: V2, f: [L<B>; 2]) {
        let v = point_velocity(s, d);
        self.moment += f[0] * v.x + f[1] * v.y;
    }
    /// Add the power of a force `f` (N, the same in every lane) on a link that slides on
    /// the ground, f·v (every point of it moves as its anchor), to M*.
    #[inline(always)]
    pub fn force_translating(&mut self, s: &LinkLanes<B>, f: V2) {
        self.moment += s.vel.dot_v(f);
    }
    /// Add the power of a torque `t` (N·m, the same in every lane) on a link, t ω, to M*.
    #[inline(always)]
    pub fn torque(&mut self, s: &LinkLanes<B>, t: f64) {
        self.moment += s.omega * t;
    }
    /// [`ZhukovskiLanes::torque`] with a torque `t` (N·m) per configuration.
    #[inline(always)]
    pub fn torque_lanes(&mut self, s: &LinkLanes<B>, t: L<B>) {
        self.moment += t * s.omega;
    }
}

/// The velocity of the material point of local vector `d` (the anchor's when d = 0).
#[inline(always)]
fn point_velocity<B: Backend>(s: &LinkLanes<B>, d: V2) -> V2L<B> {
    if d.x == 0.0 && d.y == 0.0 {
        s.vel
    } else {
        s.vel_at(s.r(d))
    }
}

/// The generalised acceleration q̈ = (driver + M* − ½ dI*/dq q̇²) / I* (rad/s² or m/s²)
/// per configuration, from the sums `z`, the input rate `qd` and the driver's torque (or
/// force) `driver`, as `solvers::zhukovski::acceleration`. The mask holds the lanes where
/// that returns `Err`: I*, dI*/dq or M* not finite, I* ≤ 0 (or a NaN), q̈ not finite.
#[inline(always)]
pub fn acceleration_lanes<B: Backend>(
    z: &ZhukovskiLanes<B>,
    qd: L<B>,
    driver: L<B>,
) -> (L<B>, Mask) {
    let sums = (z.inertia + z.inertia_derivative + z.moment).non_finite();
    let positive = z.inertia.not_greater(L::splat(0.0));
    let inv = 1.0 / z.inertia;
    let qdd = (driver + z.moment - z.inertia_derivative * (qd * qd * 0.5)) * inv;
    (qdd, sums.or(positive).or(qdd.non_finite()).mask())
}
