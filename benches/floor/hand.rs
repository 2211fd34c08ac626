//! Hand-written closed-form solvers of the crank-rocker `FourBar`, the offset
//! `SliderCrank`, the crank-shaper `QuickReturn` and the `ScotchYoke` of
//! `tests/common/mechanisms.rs` and of the `InvertedSliderCrank`, the `GearedSliderCrank`,
//! the `RollerCam`, the `CrankRodWheel`, the `BlockScotchYoke`, the `SlottedCrankRam`, the
//! `Planetary` and the `RackPinion` of `benches/floor/machines.rs`: the code an engineer who
//! knows these machines writes in an afternoon, used as the *floor* that the generated
//! solvers are timed against (`benches/floor.rs`) and checked against (`tests/floor.rs`).
//! All but the first two are in modules of their own (`hand_quick_return.rs`,
//! `hand_scotch_yoke.rs`, `hand_inverted_slider_crank.rs`, `hand_geared_slider_crank.rs`,
//! `hand_roller_cam.rs`, `hand_crank_rod_wheel.rs`, `hand_block_scotch_yoke.rs`,
//! `hand_slotted_crank_ram.rs`, `hand_planetary.rs`, `hand_rack_pinion.rs`, beside this
//! file), re-exported here. (The gear pairs' radii and pressure angles and the cam's law,
//! base circle and roller are not generated parameters: the geared slider-crank's, the
//! planetary's, the rack and pinion's and the roller cam's modules hold them as constants,
//! which `tests/floor.rs` checks against the loaded model.)
//!
//! Every operation (`pose`, `kinematics`, `kinetostatics`, `driver_action`, `reduced`,
//! `reduced_moment`, `acceleration`) is `#[inline(never)]`: the bench compares one call
//! with one call, as a user calls either, whatever the compiler decides. Left to it,
//! whether a hand-written operation is inlined into the bench's loop turns on how the
//! crate happens to be split into codegen units, which moves with any unrelated edit of
//! the bench (a machine added elsewhere moved the Scotch yoke's hand-written `pose` into
//! the loop and its ratio by a third), while the generated operations stay calls.
//!
//! Conventions are those of `docs/conventions.md`: x right, y up, angles CCW; a link's
//! angle is the direction of its first listed point → second listed point (a link with one
//! point: its rotation since the drawing); the reaction at a joint declared `(a, b)` is the
//! force BY a ON b at the joint point (and, at a prismatic joint, the moment by a on b
//! about that point); the driver is the torque by the ground on the crank; gravity acts at
//! every cg. The input q is the driven link's angle (the crank's θ₂; the geared
//! slider-crank's pinion's, the roller cam's cam's rotation), no drawing has an input offset.
//!
//! Everything is plain scalar `f64` code (with `Vector2<f64>` as the 2-vector), all
//! constants of the drawing (lengths, branch signs, cg and coupler-point offsets in the
//! link frames, m·g) are precomputed once in `new`, and every result is a `Copy` struct
//! on the stack: no allocation, no iteration, no dynamic dispatch.
//!
//! Local offsets are stored *divided by the link length*: a point with coordinates
//! (u, v) in the frame of a link whose first→second vector is `a` (length L, u along
//! `a`, v to its left) is at `first + (u/L)·a + (v/L)·perp(a)`, so no unit vector and
//! no trigonometric function of a link angle is ever needed, only the angles reported.
//! (The quick-return and the inverted slider-crank keep the offsets of the links that turn
//! with their slide in the slide's frame, whose unit vector they compute anyway.)

#![allow(dead_code)]

use super::machines::{
    BlockScotchYokeLoads, BlockScotchYokeParams, CrankRodWheelLoads, CrankRodWheelParams,
    GearedSliderCrankLoads, GearedSliderCrankParams, InvertedSliderCrankLoads,
    InvertedSliderCrankParams, PlanetaryLoads, PlanetaryParams, RackPinionLoads, RackPinionParams,
    RollerCamLoads, RollerCamParams, SlottedCrankRamLoads, SlottedCrankRamParams,
};
use crate::mechanisms::{
    FourBarLoads, FourBarParams, QuickReturnLoads, QuickReturnParams, ScotchYokeLoads,
    ScotchYokeParams, SliderCrankLoads, SliderCrankParams,
};
use mech::prelude::Vector2;

#[path = "hand_block_scotch_yoke.rs"]
mod block_scotch_yoke;
#[path = "hand_crank_rod_wheel.rs"]
mod crank_rod_wheel;
#[path = "hand_geared_slider_crank.rs"]
mod geared_slider_crank;
#[path = "hand_inverted_slider_crank.rs"]
mod inverted_slider_crank;
#[path = "hand_planetary.rs"]
mod planetary;
#[path = "hand_quick_return.rs"]
mod quick_return;
#[path = "hand_rack_pinion.rs"]
mod rack_pinion;
#[path = "hand_roller_cam.rs"]
mod roller_cam;
#[path = "hand_scotch_yoke.rs"]
mod scotch_yoke;
#[path = "hand_slotted_crank_ram.rs"]
mod slotted_crank_ram;

pub use block_scotch_yoke::*;
pub use crank_rod_wheel::*;
pub use geared_slider_crank::*;
pub use inverted_slider_crank::*;
pub use planetary::*;
pub use quick_return::*;
pub use rack_pinion::*;
pub use roller_cam::*;
pub use scotch_yoke::*;
pub use slotted_crank_ram::*;

/// A plane vector (m, m/s, m/s², N).
pub type V2 = Vector2<f64>;

/// perp(v) = (−v_y, v_x): v turned by +90°.
#[inline(always)]
fn perp(v: V2) -> V2 {
    V2::new(-v.y, v.x)
}

/// a × b = a_x b_y − a_y b_x.
#[inline(always)]
fn cross(a: V2, b: V2) -> f64 {
    a.x * b.y - a.y * b.x
}

/// (cos, sin) of an angle as the rotation (x, y).
#[inline(always)]
fn turn(angle: f64) -> V2 {
    let (sn, cs) = angle.sin_cos();
    V2::new(cs, sn)
}

/// v turned by the rotation `r` = (cos, sin).
#[inline(always)]
fn rotate(r: V2, v: V2) -> V2 {
    V2::new(r.x * v.x - r.y * v.y, r.y * v.x + r.x * v.y)
}

/// A difference of two angles in (−π, π] (of two atan2) brought into (−π, π]: one
/// correction by 2π at most, no division.
#[inline(always)]
fn wrap_difference(a: f64) -> f64 {
    use std::f64::consts::{PI, TAU};
    if a > PI {
        a - TAU
    } else if a <= -PI {
        a + TAU
    } else {
        a
    }
}

/// Coordinates (u/L, v/L) of `p` in the frame of the link from `o` to `e` (L = |e − o|),
/// so that p = o + (u/L)·(e − o) + (v/L)·perp(e − o) in every pose.
fn local_scaled(o: V2, e: V2, p: V2) -> (f64, f64) {
    let a = e - o;
    let d = p - o;
    let l2 = a.norm_squared();
    (a.dot(&d) / l2, cross(a, d) / l2)
}

/// o + ku·a + kv·perp(a).
#[inline(always)]
fn at(o: V2, a: V2, k: (f64, f64)) -> V2 {
    V2::new(o.x + k.0 * a.x - k.1 * a.y, o.y + k.0 * a.y + k.1 * a.x)
}

// ---------------------------------------------------------------------------------------
// Four-bar
// ---------------------------------------------------------------------------------------

/// The crank-rocker four-bar O2–A–B–O4 with the coupler point P, in closed form.
///
/// Links: crank 2 (O2→A, length r₂), coupler 3 (A→B, r₃, carries P), rocker 4 (O4→B, r₄).
#[derive(Clone, Copy, Debug)]
pub struct FourBarHand {
    o2: V2,
    o4: V2,
    /// r₂, crank length (m).
    r2: f64,
    /// r₃², coupler length squared (m²).
    r3sq: f64,
    /// r₃² − r₄² (m²).
    r3sq_m_r4sq: f64,
    /// Assembly branch: sign of (O4 − A) × (B − A) in the drawing.
    sigma: f64,
    /// cg of the crank in its frame O2→A, scaled by 1/r₂.
    g2: (f64, f64),
    /// cg of the coupler in its frame A→B, scaled by 1/r₃.
    g3: (f64, f64),
    /// P in the coupler frame A→B, scaled by 1/r₃.
    p3: (f64, f64),
    /// cg of the rocker in its frame O4→B, scaled by 1/r₄.
    g4: (f64, f64),
    /// Masses m₂, m₃, m₄ (kg) and inertias I₂, I₃, I₄ about the cgs (kg·m²).
    m2: f64,
    m3: f64,
    m4: f64,
    i2: f64,
    i3: f64,
    i4: f64,
    /// Weights m_k·g (N).
    w2: V2,
    w3: V2,
    w4: V2,
    /// Inertias about the fixed pins, I_O2 = I₂ + m₂|G₂ − O2|², I_O4 (kg·m²).
    io2: f64,
    io4: f64,
}

/// Pose of one link: angle θ (rad) and cg position (m).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct HandLinkPose {
    /// θ, rad.
    pub angle: f64,
    /// cg, m.
    pub cg: V2,
}

/// Result of [`FourBarHand::pose`].
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct FourBarHandPose {
    /// Crank: θ₂ = q (not wrapped), cg.
    pub crank: HandLinkPose,
    /// Coupler: θ₃ = atan2(B − A), cg.
    pub coupler: HandLinkPose,
    /// Rocker: θ₄ = atan2(B − O4), cg.
    pub rocker: HandLinkPose,
    /// O2 (fixed), m.
    pub o2: V2,
    /// O4 (fixed), m.
    pub o4: V2,
    /// A = O2 + r₂(cos q, sin q), m.
    pub a: V2,
    /// B, the circle intersection, m.
    pub b: V2,
    /// P on the coupler, m.
    pub p: V2,
}

/// Motion of one link: θ, ω, α and its cg's position, velocity, acceleration.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct HandLinkMotion {
    /// θ, rad.
    pub angle: f64,
    /// ω, rad/s.
    pub omega: f64,
    /// α, rad/s².
    pub alpha: f64,
    /// cg, m.
    pub cg: V2,
    /// cg velocity, m/s.
    pub cg_vel: V2,
    /// cg acceleration, m/s².
    pub cg_acc: V2,
}

/// Position, velocity and acceleration of a point.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct HandPointMotion {
    /// m.
    pub pos: V2,
    /// m/s.
    pub vel: V2,
    /// m/s².
    pub acc: V2,
}

/// Result of [`FourBarHand::kinematics`].
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct FourBarHandMotion {
    /// Crank: θ₂ = q (not wrapped), ω₂ = q̇, α₂ = q̈, its cg.
    pub crank: HandLinkMotion,
    /// Coupler: θ₃, ω₃, α₃, its cg.
    pub coupler: HandLinkMotion,
    /// Rocker: θ₄, ω₄, α₄, its cg.
    pub rocker: HandLinkMotion,
    /// O2: fixed, zero velocity and acceleration.
    pub o2: HandPointMotion,
    /// O4: fixed, zero velocity and acceleration.
    pub o4: HandPointMotion,
    /// A: v = ω₂ perp(a₂), a = α₂ perp(a₂) − ω₂² a₂.
    pub a: HandPointMotion,
    /// B: v = ω₄ perp(a₄), a = α₄ perp(a₄) − ω₄² a₄.
    pub b: HandPointMotion,
    /// P: from A with ω₃, α₃.
    pub p: HandPointMotion,
}

/// Result of [`FourBarHand::kinetostatics`]: driver torque (N·m, by the ground on the
/// crank) and the four pin forces (N), each BY the joint's first link ON its second.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct FourBarHandForces {
    /// Motor torque T on the crank, N·m.
    pub driver: f64,
    /// R_O2: ground on crank.
    pub o2: V2,
    /// R_A: crank on coupler.
    pub a: V2,
    /// R_B: coupler on rocker.
    pub b: V2,
    /// R_O4: ground on rocker.
    pub o4: V2,
}

impl FourBarHand {
    /// Precompute the constants of the drawing `p`: r₂, r₃², r₃² − r₄², the branch σ,
    /// the scaled local offsets of the cgs and of P, the weights m·g.
    pub fn new(p: &FourBarParams) -> Self {
        let (o2, o4, a, b, pp) = (p.points.O2, p.points.O4, p.points.A, p.points.B, p.points.P);
        let (crank, coupler, rocker) = (&p.links.crank, &p.links.coupler, &p.links.rocker);
        let r3sq = (b - a).norm_squared();
        FourBarHand {
            o2,
            o4,
            r2: (a - o2).norm(),
            r3sq,
            r3sq_m_r4sq: r3sq - (b - o4).norm_squared(),
            sigma: cross(o4 - a, b - a).signum(),
            g2: local_scaled(o2, a, crank.cg),
            g3: local_scaled(a, b, coupler.cg),
            p3: local_scaled(a, b, pp),
            g4: local_scaled(o4, b, rocker.cg),
            m2: crank.mass,
            m3: coupler.mass,
            m4: rocker.mass,
            i2: crank.inertia,
            i3: coupler.inertia,
            i4: rocker.inertia,
            w2: p.gravity * crank.mass,
            w3: p.gravity * coupler.mass,
            w4: p.gravity * rocker.mass,
            io2: crank.inertia + crank.mass * (crank.cg - o2).norm_squared(),
            io4: rocker.inertia + rocker.mass * (rocker.cg - o4).norm_squared(),
        }
    }

    /// Loop closure in closed form. A = O2 + r₂(cos q, sin q); B is the intersection of
    /// the circle (A, r₃) with the circle (O4, r₄) on the drawing's side of A→O4: with
    /// d = O4 − A, L² = |d|², k = (r₃² − r₄² + L²)/(2L²), h = √(r₃²/L² − k²),
    /// B = A + k·d + σ·h·perp(d). Returns (a₂, A, B) with a₂ = A − O2, or `None` when
    /// the circles do not meet (no assembly).
    #[inline(always)]
    fn close(&self, q: f64) -> Option<(V2, V2, V2)> {
        let (s, c) = q.sin_cos();
        let a2 = V2::new(self.r2 * c, self.r2 * s);
        let a = self.o2 + a2;
        let d = self.o4 - a;
        let inv_l2 = 1.0 / d.norm_squared();
        let k = 0.5 * (self.r3sq_m_r4sq * inv_l2 + 1.0);
        let h2 = self.r3sq * inv_l2 - k * k;
        if !(h2 >= 0.0) {
            return None;
        }
        let h = self.sigma * h2.sqrt();
        let b = V2::new(a.x + k * d.x - h * d.y, a.y + k * d.y + h * d.x);
        Some((a2, a, b))
    }

    /// Position analysis: θ₂ = q, θ₃ = atan2(B − A), θ₄ = atan2(B − O4), the three cgs
    /// and the points O2, O4, A, B, P (P and the cgs from their scaled local offsets).
    #[inline(never)]
    pub fn pose(&self, q: f64) -> Option<FourBarHandPose> {
        let (a2, a, b) = self.close(q)?;
        let a3 = b - a;
        let a4 = b - self.o4;
        Some(FourBarHandPose {
            crank: HandLinkPose {
                angle: q,
                cg: at(self.o2, a2, self.g2),
            },
            coupler: HandLinkPose {
                angle: a3.y.atan2(a3.x),
                cg: at(a, a3, self.g3),
            },
            rocker: HandLinkPose {
                angle: a4.y.atan2(a4.x),
                cg: at(self.o4, a4, self.g4),
            },
            o2: self.o2,
            o4: self.o4,
            a,
            b,
            p: at(a, a3, self.p3),
        })
    }

    /// Position, velocity and acceleration analysis at (q, q̇, q̈) = (θ₂, ω₂, α₂).
    ///
    /// With a₂ = A − O2, a₃ = B − A, a₄ = B − O4 the loop a₂ + a₃ − a₄ = const gives
    /// ω₃ perp(a₃) − ω₄ perp(a₄) = −ω₂ perp(a₂); dotting with a₄ and with a₃ (Cramer on
    /// the 2×2 system, Δ = a₃ × a₄):
    /// ω₃ = −ω₂ (a₂ × a₄)/Δ,  ω₄ = −ω₂ (a₂ × a₃)/Δ.
    /// Differentiating again, α₃ perp(a₃) − α₄ perp(a₄) = c with
    /// c = ω₂² a₂ + ω₃² a₃ − ω₄² a₄ − α₂ perp(a₂), so α₃ = (c·a₄)/Δ, α₄ = (c·a₃)/Δ.
    /// A point at r from a point Q of link k moves with v = v_Q + ω_k perp(r),
    /// a = a_Q + α_k perp(r) − ω_k² r.
    #[inline(never)]
    pub fn kinematics(&self, q: f64, qd: f64, qdd: f64) -> Option<FourBarHandMotion> {
        let (a2, a, b) = self.close(q)?;
        let a3 = b - a;
        let a4 = b - self.o4;
        let inv_det = 1.0 / cross(a3, a4);
        let (w2, al2) = (qd, qdd);
        let w3 = -w2 * cross(a2, a4) * inv_det;
        let w4 = -w2 * cross(a2, a3) * inv_det;
        let c = a2 * (w2 * w2) + a3 * (w3 * w3) - a4 * (w4 * w4) - perp(a2) * al2;
        let al3 = c.dot(&a4) * inv_det;
        let al4 = c.dot(&a3) * inv_det;

        // A and B.
        let va = perp(a2) * w2;
        let aa = perp(a2) * al2 - a2 * (w2 * w2);
        let vb = perp(a4) * w4;
        let ab = perp(a4) * al4 - a4 * (w4 * w4);

        // Crank cg, about O2.
        let r = at(V2::zeros(), a2, self.g2);
        let crank = HandLinkMotion {
            angle: q,
            omega: w2,
            alpha: al2,
            cg: self.o2 + r,
            cg_vel: perp(r) * w2,
            cg_acc: perp(r) * al2 - r * (w2 * w2),
        };
        // Coupler cg and P, about A.
        let r = at(V2::zeros(), a3, self.g3);
        let coupler = HandLinkMotion {
            angle: a3.y.atan2(a3.x),
            omega: w3,
            alpha: al3,
            cg: a + r,
            cg_vel: va + perp(r) * w3,
            cg_acc: aa + perp(r) * al3 - r * (w3 * w3),
        };
        let rp = at(V2::zeros(), a3, self.p3);
        let p = HandPointMotion {
            pos: a + rp,
            vel: va + perp(rp) * w3,
            acc: aa + perp(rp) * al3 - rp * (w3 * w3),
        };
        // Rocker cg, about O4.
        let r = at(V2::zeros(), a4, self.g4);
        let rocker = HandLinkMotion {
            angle: a4.y.atan2(a4.x),
            omega: w4,
            alpha: al4,
            cg: self.o4 + r,
            cg_vel: perp(r) * w4,
            cg_acc: perp(r) * al4 - r * (w4 * w4),
        };
        let fixed = |pos| HandPointMotion {
            pos,
            vel: V2::zeros(),
            acc: V2::zeros(),
        };
        Some(FourBarHandMotion {
            crank,
            coupler,
            rocker,
            o2: fixed(self.o2),
            o4: fixed(self.o4),
            a: HandPointMotion {
                pos: a,
                vel: va,
                acc: aa,
            },
            b: HandPointMotion {
                pos: b,
                vel: vb,
                acc: ab,
            },
            p,
        })
    }

    /// Kinetostatics by d'Alembert, the dyad (coupler, rocker) first, then the crank.
    ///
    /// Per link k the applied-plus-inertia force is W_k = m_k g − m_k a_Gk (+ the tool
    /// force F_P on the coupler) and its moment about the link's first pin
    /// M_k = (G_k − first) × (m_k g − m_k a_Gk) − I_k α_k (+ (P − A) × F_P on the
    /// coupler, + the resisting torque T₄ on the rocker). Moments about A of the coupler
    /// and about O4 of the rocker give, for R_B (coupler on rocker),
    /// a₃ × R_B = M₃,  a₄ × R_B = −M₄,
    /// solved by Cramer with Δ = a₃ × a₄:
    /// R_B = ((M₃ a₄ₓ + M₄ a₃ₓ)/Δ, (M₃ a₄ᵧ + M₄ a₃ᵧ)/Δ).
    /// Then the force balances R_A = R_B − W₃, R_O4 = −R_B − W₄, R_O2 = R_A − W₂, and the
    /// crank's moments about O2: T = a₂ × R_A − M₂.
    #[inline(never)]
    pub fn kinetostatics(&self, m: &FourBarHandMotion, loads: &FourBarLoads) -> FourBarHandForces {
        let a2 = m.a.pos - self.o2;
        let a3 = m.b.pos - m.a.pos;
        let a4 = m.b.pos - self.o4;
        let f2 = self.w2 - m.crank.cg_acc * self.m2;
        let f3 = self.w3 - m.coupler.cg_acc * self.m3;
        let f4 = self.w4 - m.rocker.cg_acc * self.m4;
        let m2 = cross(m.crank.cg - self.o2, f2) - self.i2 * m.crank.alpha;
        let m3 = cross(m.coupler.cg - m.a.pos, f3) + cross(m.p.pos - m.a.pos, loads.tool)
            - self.i3 * m.coupler.alpha;
        let m4 = cross(m.rocker.cg - self.o4, f4) + loads.resist - self.i4 * m.rocker.alpha;
        let w3 = f3 + loads.tool;
        let inv_det = 1.0 / cross(a3, a4);
        let rb = V2::new(
            (m3 * a4.x + m4 * a3.x) * inv_det,
            (m3 * a4.y + m4 * a3.y) * inv_det,
        );
        let ra = rb - w3;
        let ro4 = -rb - f4;
        let ro2 = ra - f2;
        FourBarHandForces {
            driver: cross(a2, ra) - m2,
            o2: ro2,
            a: ra,
            b: rb,
            o4: ro4,
        }
    }

    /// The driver torque by virtual power, no reaction computed:
    /// T ω₂ + Σ_k [(m_k g − m_k a_Gk)·v_Gk − I_k α_k ω_k] + F_P·v_P + T₄ ω₄ = 0,
    /// so T = −(…)/ω₂. Needs q̇ = ω₂ ≠ 0 (the motion's velocities are used as the
    /// virtual ones).
    #[inline(never)]
    pub fn driver_action(&self, m: &FourBarHandMotion, loads: &FourBarLoads) -> f64 {
        let p2 = (self.w2 - m.crank.cg_acc * self.m2).dot(&m.crank.cg_vel)
            - self.i2 * m.crank.alpha * m.crank.omega;
        let p3 = (self.w3 - m.coupler.cg_acc * self.m3).dot(&m.coupler.cg_vel)
            - self.i3 * m.coupler.alpha * m.coupler.omega;
        let p4 = (self.w4 - m.rocker.cg_acc * self.m4).dot(&m.rocker.cg_vel)
            - self.i4 * m.rocker.alpha * m.rocker.omega;
        let pl = loads.tool.dot(&m.p.vel) + loads.resist * m.rocker.omega;
        -(p2 + p3 + p4 + pl) / m.crank.omega
    }

    /// The points alone, O2, O4, A, B, P: the loop closure and P on the coupler, no angle.
    #[inline(always)]
    pub fn points(&self, q: f64) -> Option<[V2; 5]> {
        let (_, a, b) = self.close(q)?;
        Some([self.o2, self.o4, a, b, at(a, b - a, self.p3)])
    }

    /// Zhukovski's I*(q) and dI*/dq; `None` when the loop does not close.
    ///
    /// The velocity coefficients (q̇ = 1, q̈ = 0 in `kinematics`): k₃ = −(a₂ × a₄)/Δ,
    /// k₄ = −(a₂ × a₃)/Δ, and their q-derivatives k₃' = (c·a₄)/Δ, k₄' = (c·a₃)/Δ with
    /// c = a₂ + k₃² a₃ − k₄² a₄. The coupler's cg, at r₃ from A: g_G3 = perp(a₂) + k₃ perp(r₃),
    /// g'_G3 = −a₂ + k₃' perp(r₃) − k₃² r₃. The crank and the rocker turn about fixed pins:
    /// I* = I_O2 + m₃|g_G3|² + I₃k₃² + I_O4 k₄², dI*/dq = 2 (m₃ g_G3·g'_G3 + I₃k₃k₃' + I_O4 k₄k₄').
    #[inline(never)]
    pub fn reduced(&self, q: f64) -> Option<HandReduced> {
        let k = self.coefficients(q)?;
        Some(self.inertia_of(&k))
    }

    /// The direct problem: q̈ = (T + M* − ½ dI*/dq q̇²)/I*, with
    /// M* = w₂·perp(r₂) + w₃·g_G3 + w₄·k₄ perp(r₄) + F_tool·g_P + T_resist k₄.
    #[inline(never)]
    pub fn acceleration(&self, q: f64, qd: f64, driver: f64, loads: &FourBarLoads) -> Option<f64> {
        let k = self.coefficients(q)?;
        let r = self.inertia_of(&k);
        let gp = perp(k.a2) + perp(k.rp) * k.k3;
        let moment = self.w2.dot(&perp(k.r2))
            + self.w3.dot(&k.g3)
            + self.w4.dot(&perp(k.r4)) * k.k4
            + loads.tool.dot(&gp)
            + loads.resist * k.k4;
        Some((driver + moment - 0.5 * r.inertia_derivative * qd * qd) / r.inertia)
    }

    #[inline(always)]
    fn coefficients(&self, q: f64) -> Option<FourBarCoefficients> {
        let (a2, a, b) = self.close(q)?;
        let a3 = b - a;
        let a4 = b - self.o4;
        let inv_det = 1.0 / cross(a3, a4);
        let k3 = -cross(a2, a4) * inv_det;
        let k4 = -cross(a2, a3) * inv_det;
        let c = a2 + a3 * (k3 * k3) - a4 * (k4 * k4);
        let (k3d, k4d) = (c.dot(&a4) * inv_det, c.dot(&a3) * inv_det);
        let r3 = at(V2::zeros(), a3, self.g3);
        Some(FourBarCoefficients {
            a2,
            k3,
            k4,
            k3d,
            k4d,
            g3: perp(a2) + perp(r3) * k3,
            g3d: -a2 + perp(r3) * k3d - r3 * (k3 * k3),
            r2: at(V2::zeros(), a2, self.g2),
            r4: at(V2::zeros(), a4, self.g4),
            rp: at(V2::zeros(), a3, self.p3),
        })
    }

    #[inline(always)]
    fn inertia_of(&self, k: &FourBarCoefficients) -> HandReduced {
        let (io2, io4) = (self.io2, self.io4);
        HandReduced {
            inertia: io2
                + self.m3 * k.g3.norm_squared()
                + self.i3 * k.k3 * k.k3
                + io4 * k.k4 * k.k4,
            inertia_derivative: 2.0
                * (self.m3 * k.g3.dot(&k.g3d) + self.i3 * k.k3 * k.k3d + io4 * k.k4 * k.k4d),
        }
    }
}

/// The four-bar's velocity coefficients at one crank angle (`FourBarHand::reduced`).
#[derive(Clone, Copy, Debug)]
struct FourBarCoefficients {
    a2: V2,
    k3: f64,
    k4: f64,
    k3d: f64,
    k4d: f64,
    g3: V2,
    g3d: V2,
    /// The cgs of the crank and the rocker and P, from O2, O4 and A.
    r2: V2,
    r4: V2,
    rp: V2,
}

// ---------------------------------------------------------------------------------------
// Slider-crank
// ---------------------------------------------------------------------------------------

/// The offset slider-crank O2–A–B with the piston sliding at B along the guide axis u,
/// in closed form for the direct dynamic problem (Zhukovski's reduction to the crank).
///
/// Axis frame: u = guide direction, n = perp(u); the line of B is at signed offset
/// e = (B₀ − O2)·n. With a₂ = A − O2 = r(cos q, sin q), x_A = a₂·u, y_A = a₂·n and the
/// rod vector in the axis frame (X, Y) = (l cos β, l sin β):
/// Y = e − y_A,  X = σ√(l² − Y²)  (σ: the drawing's side),
/// and the velocity coefficients (per unit q̇) and their q-derivatives, from
/// y_A + Y = e differentiated twice:
/// k₃ = dβ/dq = −x_A/X,  k₃' = (y_A + Y k₃²)/X,
/// k_s = ds_B/dq = −y_A − Y k₃,  k_s' = −x_A − X k₃² − Y k₃'.
#[derive(Clone, Copy, Debug)]
pub struct SliderCrankHand {
    /// r, crank length (m).
    r: f64,
    /// l², rod length squared (m²).
    lsq: f64,
    /// Guide direction u (unit).
    u: V2,
    /// Offset e of the guide line from O2 along n = perp(u) (m).
    e: f64,
    /// Branch: sign of (B₀ − A₀)·u.
    sigma: f64,
    /// Rod cg in the rod frame A→B, scaled by 1/l.
    g3: (f64, f64),
    /// Crank cg in the crank frame O2→A, scaled by 1/r.
    g2: (f64, f64),
    /// I_O2 = I₂ + m₂ |G₂ − O2|², the crank's inertia about its pivot (kg·m²).
    io2: f64,
    /// Rod mass m₃ (kg), rod inertia I₃ about its cg (kg·m²), piston mass m₄ (kg).
    m3: f64,
    i3: f64,
    m4: f64,
    /// Weights in the axis frame: (m·g·u, m·g·n) for the crank, rod and piston (N).
    w2: V2,
    w3: V2,
    w4: V2,
}

/// Zhukovski's reduced inertia and its derivative.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct HandReduced {
    /// I* = Σ m |g_G|² + I g², kg·m².
    pub inertia: f64,
    /// dI*/dq = 2 Σ (m g_G·g'_G + I g g'), kg·m²/rad.
    pub inertia_derivative: f64,
}

/// The velocity coefficients of one crank angle, in the axis frame.
#[derive(Clone, Copy, Debug)]
struct Coefficients {
    /// A − O2 in the axis frame (x_A, y_A).
    xa: f64,
    ya: f64,
    /// k₃, k₃', k_s, k_s'.
    k3: f64,
    k3d: f64,
    ks: f64,
    ksd: f64,
    /// g_G3 and g'_G3 (velocity coefficient of the rod's cg and its q-derivative), axis frame.
    g3: V2,
    g3d: V2,
}

impl SliderCrankHand {
    /// Precompute r, l², u, e, σ, the scaled cg offsets, I_O2 and the weights in the axis
    /// frame from the drawing `p`.
    pub fn new(p: &SliderCrankParams) -> Self {
        let (o2, a, b) = (p.points.O2, p.points.A, p.points.B);
        let u = p.axes.guide.normalize();
        let n = perp(u);
        let (crank, rod, piston) = (&p.links.crank, &p.links.rod, &p.links.piston);
        let axis = |f: V2| V2::new(f.dot(&u), f.dot(&n));
        SliderCrankHand {
            r: (a - o2).norm(),
            lsq: (b - a).norm_squared(),
            u,
            e: (b - o2).dot(&n),
            sigma: (b - a).dot(&u).signum(),
            g3: local_scaled(a, b, rod.cg),
            g2: local_scaled(o2, a, crank.cg),
            io2: crank.inertia + crank.mass * (crank.cg - o2).norm_squared(),
            m3: rod.mass,
            i3: rod.inertia,
            m4: piston.mass,
            w2: axis(p.gravity * crank.mass),
            w3: axis(p.gravity * rod.mass),
            w4: axis(p.gravity * piston.mass),
        }
    }

    /// The velocity coefficients at q (see the type's docs). The rod cg is at
    /// d = (g₃ᵤ X − g₃ᵥ Y, g₃ᵤ Y + g₃ᵥ X) from A (axis frame), so
    /// g_G3 = perp(a₂) + k₃ perp(d),  g'_G3 = −a₂ + k₃' perp(d) − k₃² d.
    #[inline(always)]
    fn coefficients(&self, q: f64) -> Option<Coefficients> {
        let (s, c) = q.sin_cos();
        let (ax, ay) = (self.r * c, self.r * s);
        let xa = ax * self.u.x + ay * self.u.y;
        let ya = ay * self.u.x - ax * self.u.y;
        let y = self.e - ya;
        let x2 = self.lsq - y * y;
        if !(x2 > 0.0) {
            return None;
        }
        let x = self.sigma * x2.sqrt();
        let inv_x = 1.0 / x;
        let k3 = -xa * inv_x;
        let k3sq = k3 * k3;
        let k3d = (ya + y * k3sq) * inv_x;
        let ks = -ya - y * k3;
        let ksd = -xa - x * k3sq - y * k3d;
        let dx = self.g3.0 * x - self.g3.1 * y;
        let dy = self.g3.0 * y + self.g3.1 * x;
        let g3 = V2::new(-ya - k3 * dy, xa + k3 * dx);
        let g3d = V2::new(-xa - k3d * dy - k3sq * dx, -ya + k3d * dx - k3sq * dy);
        Some(Coefficients {
            xa,
            ya,
            k3,
            k3d,
            ks,
            ksd,
            g3,
            g3d,
        })
    }

    /// I* = I_O2 + m₃|g_G3|² + I₃ k₃² + m₄ k_s²,
    /// dI*/dq = 2 (m₃ g_G3·g'_G3 + I₃ k₃ k₃' + m₄ k_s k_s')
    /// (the crank's term is constant; the piston does not turn).
    #[inline(always)]
    fn inertia_of(&self, k: &Coefficients) -> HandReduced {
        HandReduced {
            inertia: self.io2
                + self.m3 * k.g3.norm_squared()
                + self.i3 * k.k3 * k.k3
                + self.m4 * k.ks * k.ks,
            inertia_derivative: 2.0
                * (self.m3 * k.g3.dot(&k.g3d) + self.i3 * k.k3 * k.k3d + self.m4 * k.ks * k.ksd),
        }
    }

    /// M* = m₂g·g_G2 + m₃g·g_G3 + m₄(g·u) k_s + (F_gas·u) k_s + T_shaft, with
    /// g_G2 = perp(G₂ − O2) = g₂ᵤ perp(a₂) − g₂ᵥ a₂.
    #[inline(always)]
    fn moment_of(&self, k: &Coefficients, loads: &SliderCrankLoads) -> f64 {
        let g2 = V2::new(
            -self.g2.0 * k.ya - self.g2.1 * k.xa,
            self.g2.0 * k.xa - self.g2.1 * k.ya,
        );
        self.w2.dot(&g2)
            + self.w3.dot(&k.g3)
            + (self.w4.x + loads.gas.dot(&self.u)) * k.ks
            + loads.shaft
    }

    /// Zhukovski's I*(q) and dI*/dq; `None` when the rod cannot reach the guide.
    #[inline(never)]
    pub fn reduced(&self, q: f64) -> Option<HandReduced> {
        Some(self.inertia_of(&self.coefficients(q)?))
    }

    /// Zhukovski's reduced moment M*(q) of the loads and gravity (N·m).
    #[inline(never)]
    pub fn reduced_moment(&self, q: f64, loads: &SliderCrankLoads) -> Option<f64> {
        Some(self.moment_of(&self.coefficients(q)?, loads))
    }

    /// The direct problem: q̈ = (T + M* − ½ dI*/dq q̇²)/I*.
    #[inline(never)]
    pub fn acceleration(
        &self,
        q: f64,
        qd: f64,
        driver: f64,
        loads: &SliderCrankLoads,
    ) -> Option<f64> {
        let k = self.coefficients(q)?;
        let r = self.inertia_of(&k);
        Some(
            (driver + self.moment_of(&k, loads) - 0.5 * r.inertia_derivative * qd * qd) / r.inertia,
        )
    }
}
