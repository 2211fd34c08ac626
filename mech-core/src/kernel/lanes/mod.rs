//! Lane kernels: the closed-form kinematics of the commonest groups (a driven crank or
//! slider, the RRR and RRP dyads) and Zhukovski's sums, computed for [`LANES`] = 4
//! configurations at once, for the batched solvers. Each is the twin of a scalar kernel,
//! formula for formula: [`solve_driven_lanes`] of [`crate::kernel::kinematics::solve_driven`],
//! [`solve_chain_lanes`] of [`crate::kernel::kinematics::solve_chain`], [`ZhukovskiLanes`]
//! of `solvers::zhukovski::ZhukovskiSums`.
//!
//! **The mask.** Each entry point returns a [`Mask`] of the lanes that failed or may fail:
//! every lane where the scalar kernel returns `Err` (`NoAssembly`, `Singular`) is set, as is
//! every lane within a margin of the scalar decision (so that inputs that differ from the
//! scalar ones by roundoff cannot hide a failure), and every lane with a non-finite result.
//! The caller recomputes the set lanes with the scalar kernels; the values of the other
//! lanes are those of the scalar kernels up to roundoff (differently ordered operations,
//! [`sin_cos`] within its stated ulps), amplified only by the group's conditioning.
//!
//! **Layout.** A link's state for the four configurations is a [`LinkLanes`] (structure of
//! arrays); a batch solves a mechanism's groups in plan order on one `[LinkLanes]` as the
//! scalar code does on one `[LinkState]`. The joints' geometry, the branch signs and the
//! length scale are shared by all lanes. [`with_simd`] runs a batch with AVX2 enabled
//! (VEX-encoded SSE2 operations) where the processor has it.

mod driven;
mod dyad;
mod simd;
#[cfg(test)]
mod tests;
/// The same tests on the 256-bit backend (skipped where the processor lacks AVX2 and FMA).
#[cfg(test)]
#[path = "tests.rs"]
mod tests_wide;
mod zhukovski;

pub use driven::solve_driven_lanes;
pub use dyad::{solve_chain_lanes, PRECISE_CONDITION};
pub use simd::{
    any, atan2, or, select, sin_cos, wrap, Backend, Base, Bits, Mask, Wide, ALL, L, LANES, NONE,
    SIN_COS_RANGE, V2L,
};
pub use zhukovski::{acceleration_lanes, ZhukovskiLanes};

use crate::kernel::constraints::JointGeom;
use crate::kernel::dyad::Solver;
use crate::kernel::link_state::{LinkGeom, LinkState, V2};

/// The state of one link in [`LANES`] configurations: the lane twin of [`LinkState`]
/// (`crate::kernel::link_state`'s conventions: the anchor's position, velocity and
/// acceleration, the rotation (cos φ, sin φ) since the drawing, ω, α, and φ over turns
/// where a kernel keeps it).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LinkLanes<B: Backend = Base> {
    /// Anchor position, m.
    pub pos: V2L<B>,
    /// (cos φ, sin φ), φ the rotation since the drawing.
    pub rot: V2L<B>,
    /// Anchor velocity, m/s.
    pub vel: V2L<B>,
    /// Angular velocity ω, rad/s.
    pub omega: L<B>,
    /// Anchor acceleration, m/s².
    pub acc: V2L<B>,
    /// Angular acceleration α, rad/s².
    pub alpha: L<B>,
    /// φ over turns, rad (kept by a driven link with `Driven::track`, as the scalar kernel).
    pub angle: L<B>,
}

impl<B: Backend> Default for LinkLanes<B> {
    /// [`LinkState::default`] in every lane: at rest, unrotated, at the origin.
    #[inline]
    fn default() -> Self {
        LinkLanes::from_state(&LinkState::default())
    }
}

impl<B: Backend> LinkLanes<B> {
    /// The state `s` in every lane (the ground, the drawing a batch starts from).
    #[inline(always)]
    pub fn from_state(s: &LinkState) -> Self {
        LinkLanes {
            pos: V2L::splat(s.pos),
            rot: V2L::splat(s.rot),
            vel: V2L::splat(s.vel),
            omega: L::splat(s.omega),
            acc: V2L::splat(s.acc),
            alpha: L::splat(s.alpha),
            angle: L::splat(s.angle),
        }
    }
    /// Lane `i` as a scalar state.
    #[inline(always)]
    pub fn lane(&self, i: usize) -> LinkState {
        LinkState {
            pos: self.pos.lane(i),
            rot: self.rot.lane(i),
            vel: self.vel.lane(i),
            omega: self.omega.0[i],
            acc: self.acc.lane(i),
            alpha: self.alpha.0[i],
            angle: self.angle.0[i],
        }
    }
    /// Store the scalar state `s` as lane `i` (a lane recomputed by the scalar kernels).
    #[inline]
    pub fn set_lane(&mut self, i: usize, s: &LinkState) {
        let put = |v: &mut V2L<B>, w: V2| {
            v.x.0[i] = w.x;
            v.y.0[i] = w.y;
        };
        put(&mut self.pos, s.pos);
        put(&mut self.rot, s.rot);
        put(&mut self.vel, s.vel);
        put(&mut self.acc, s.acc);
        self.omega.0[i] = s.omega;
        self.alpha.0[i] = s.alpha;
        self.angle.0[i] = s.angle;
    }
    /// The current vector R(φ) d from the anchor to the material point of local vector `d` (m).
    #[inline(always)]
    pub fn r(&self, d: V2) -> V2L<B> {
        self.rot.rotate(d)
    }
    /// The position of the material point of local vector `d` (m): pos + R(φ) d.
    #[inline(always)]
    pub fn point(&self, d: V2) -> V2L<B> {
        self.pos + self.r(d)
    }
    /// The velocity of the material point at offset `r` from the anchor: v + ω perp(r) (m/s).
    #[inline(always)]
    pub fn vel_at(&self, r: V2L<B>) -> V2L<B> {
        self.vel + r.perp() * self.omega
    }
    /// The acceleration of the material point at offset `r`: a + α perp(r) − ω² r (m/s²).
    #[inline(always)]
    pub fn acc_at(&self, r: V2L<B>) -> V2L<B> {
        self.acc + r.perp() * self.alpha - r * (self.omega * self.omega)
    }
    /// ω and the anchor's velocity from the velocity `v_p` of the material point of local
    /// vector `d`, now at `p`: v = v_p + ω perp(pos − p), v = v_p when `d` = 0 (the anchor),
    /// as [`LinkState::set_velocity_at`].
    #[inline(always)]
    pub fn set_velocity_at(&mut self, d: V2, p: V2L<B>, v_p: V2L<B>, omega: L<B>) {
        self.omega = omega;
        self.vel = if d.x == 0.0 && d.y == 0.0 {
            v_p
        } else {
            v_p + (self.pos - p).perp() * omega
        };
    }
    /// α and the anchor's acceleration from the acceleration `a_p` of the material point
    /// of local vector `d`, now at `p`, ω already set: a = a_p + α perp(r) − ω² r,
    /// r = pos − p, as [`LinkState::set_acceleration_at`].
    #[inline(always)]
    pub fn set_acceleration_at(&mut self, d: V2, p: V2L<B>, a_p: V2L<B>, alpha: L<B>) {
        self.alpha = alpha;
        self.acc = if d.x == 0.0 && d.y == 0.0 {
            a_p
        } else {
            let r = self.pos - p;
            a_p + r.perp() * alpha - r * (self.omega * self.omega)
        };
    }
}

/// The position of the material point of local vector `d` on link `l` (the local vector
/// itself on the ground, link 0), as [`crate::kernel::link_state::point_of`].
#[inline(always)]
pub(crate) fn point_of<B: Backend>(s: &[LinkLanes<B>], l: usize, d: V2) -> V2L<B> {
    if l == 0 {
        V2L::splat(d)
    } else {
        s[l].point(d)
    }
}

/// The current direction of the local vector `d` of link `l` (unrotated on the ground).
#[inline(always)]
pub(crate) fn dir_of<B: Backend>(s: &[LinkLanes<B>], l: usize, d: V2) -> V2L<B> {
    if l == 0 {
        V2L::splat(d)
    } else {
        s[l].r(d)
    }
}

/// For a joint `g` with link `body` on one side and a solved link on the other: the joint
/// point's current position from the solved side, and its local vector in `body`, as
/// [`crate::kernel::dyad::pin`].
#[inline(always)]
pub(crate) fn pin<B: Backend>(g: &JointGeom, s: &[LinkLanes<B>], body: usize) -> (V2L<B>, V2) {
    if g.b == body {
        (point_of(s, g.a, g.da), g.db)
    } else {
        (point_of(s, g.b, g.db), g.da)
    }
}

/// Place a link from its rotation and one of its points (local `d`, now at `p`):
/// pos = p − R d (p itself when d = 0), as [`crate::kernel::dyad::place_by_point`].
#[inline(always)]
pub(crate) fn place_by_point<B: Backend>(s: &mut LinkLanes<B>, rot: V2L<B>, d: V2, p: V2L<B>) {
    s.rot = rot;
    s.pos = if d.x == 0.0 && d.y == 0.0 {
        p
    } else {
        p - rot.rotate(d)
    };
}

/// `f` itself: a closure marked `#[inline(always)]` where an attribute on a closure is
/// allowed (an argument), so that it is compiled into the function it is called from (with
/// its target features: the AVX2 path of [`with_simd`]).
#[inline(always)]
pub(crate) fn inlined<F>(f: F) -> F {
    f
}

/// Whether the kind `solver` has a lane kernel: a driven crank or slider, an RRR or an RRP
/// dyad. For the other kinds the caller solves the whole batch with the scalar kernels.
#[inline]
pub fn supports(solver: Solver) -> bool {
    matches!(
        solver,
        Solver::DrivenRevolute { .. }
            | Solver::DrivenPrismatic { .. }
            | Solver::Rrr { .. }
            | Solver::Rrp { .. }
    )
}

/// The position (m) of the material point of local vector `d` (m) on link `l` of the
/// states `s`, as `[x, y]`: pos + R(φ) d (d itself on the ground), the twin of
/// [`crate::kernel::link_state::point_pose`].
#[inline(always)]
pub fn point_lanes<B: Backend>(s: &[LinkLanes<B>], l: usize, d: V2) -> [L<B>; 2] {
    point_of(s, l, d).xy()
}

/// The position, velocity and acceleration (m, m/s, m/s²) of the material point of local
/// vector `d` on link `l`, each as `[x, y]`: p = pos + r, v + ω perp(r), a + α perp(r) − ω² r
/// with r = R(φ) d (at rest on the ground), the twin of
/// [`crate::kernel::link_state::point_motion`].
#[inline(always)]
pub fn point_motion_lanes<B: Backend>(s: &[LinkLanes<B>], l: usize, d: V2) -> [[L<B>; 2]; 3] {
    if l == 0 {
        let z = L::splat(0.0);
        return [V2L::splat(d).xy(), [z, z], [z, z]];
    }
    let st = &s[l];
    let r = st.r(d);
    [(st.pos + r).xy(), st.vel_at(r).xy(), st.acc_at(r).xy()]
}

/// The link angle θ = θ_ref + φ (rad, wrapped to (−π, π]) of link `l` in state `s`:
/// atan2 of R(φ)·dir_ref ([`atan2`], within its stated ulps of the scalar
/// `LinkGeom::angle`, which `LinkPose::angle` holds).
#[inline(always)]
pub fn link_angle_lanes<B: Backend>(l: &LinkGeom, s: &LinkLanes<B>) -> L<B> {
    let d = s.rot.rotate(l.dir_ref);
    atan2(d.y, d.x)
}

/// The angle θ (rad, wrapped to (−π, π]) of a crank driven on the ground from its input
/// q (rad): wrap(sign·q), the twin of [`crate::kernel::kinematics::crank_angle`] (the same
/// operations, the same results).
#[inline(always)]
pub fn crank_angle_lanes<B: Backend>(q: L<B>, sign: f64) -> L<B> {
    wrap(q * sign)
}

/// The position of link `l`'s cg (m), as `[x, y]`: pos + R(φ) d_cg, the `cg` of the scalar
/// `LinkPose`.
#[inline(always)]
pub fn cg_lanes<B: Backend>(l: &LinkGeom, s: &LinkLanes<B>) -> [L<B>; 2] {
    s.point(l.dcg).xy()
}

/// Run `wide` with the processor's 256-bit vector instructions (AVX2 and FMA) enabled when
/// it has them (detected at run time, once per call: a cached test), `base` otherwise and
/// on the other architectures. `wide` is meant to call the lane kernels on the [`Wide`]
/// backend (one 256-bit register per lane value), `base` the same kernels on [`Base`] (two
/// 128-bit registers): the kernels are `#[inline(always)]`, so those called in `wide` are
/// compiled for AVX2, provided `wide` itself is inlined there — mark the closure
/// `#[inline(always)]`, else LLVM may call it, compiled for the baseline. FMA is enabled
/// but never contracted into (Rust does not fuse a multiplication and an addition unasked),
/// so both routes give the same results bit for bit.
///
/// `state` is handed to whichever runs (the rows and errors both would borrow).
///
/// The environment variable `MECH_SIMD=0` keeps the baseline path (read once).
#[inline(always)]
pub fn with_simd<T, R>(state: T, base: impl FnOnce(T) -> R, wide: impl FnOnce(T) -> R) -> R {
    #[cfg(target_arch = "x86_64")]
    {
        if simd_allowed() {
            // SAFETY: the processor has AVX2 and FMA (`simd_allowed` detected them).
            return unsafe {
                avx2(
                    #[inline(always)]
                    move || wide(state),
                )
            };
        }
    }
    let _ = wide;
    base(state)
}

/// True where the [`Wide`] backend runs: the processor has AVX2 and FMA and `MECH_SIMD=0`
/// is not set (looked up once).
#[cfg(target_arch = "x86_64")]
pub fn simd_allowed() -> bool {
    static ALLOWED: std::sync::OnceLock<bool> = std::sync::OnceLock::new();
    *ALLOWED.get_or_init(|| {
        !matches!(std::env::var_os("MECH_SIMD"), Some(v) if v == "0")
            && std::is_x86_feature_detected!("avx2")
            && std::is_x86_feature_detected!("fma")
    })
}

/// False outside x86-64: the [`Wide`] backend is [`Base`] there.
#[cfg(not(target_arch = "x86_64"))]
pub fn simd_allowed() -> bool {
    false
}

/// `f` compiled with AVX2 and FMA (the closure and what it inlines).
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2,fma")]
unsafe fn avx2<R>(f: impl FnOnce() -> R) -> R {
    f()
}
