//! Hand-written closed forms of the crank-shaper `QuickReturn` of
//! `tests/common/mechanisms.rs` (a module of `hand.rs`, whose conventions it keeps).

use super::*;

/// The crank-shaper quick-return: the crank O2–A carries the block 3 on its pin A; the
/// block slides in the slot of the lever 4 (O4–C), pivoted on the ground at O4, whose slot
/// runs through O4 (an RPR group: pin A, slot, pin O4).
///
/// With d = A − O4 = s u (s = |d|, u the slot's unit direction, n = perp(u)), differentiating
/// d = s u (u̇ = ω₄ n) gives v_A = ṡ u + s ω₄ n and
/// a_A = (s̈ − s ω₄²) u + (2 ṡ ω₄ + s α₄) n, so
/// ṡ = v_A·u,  ω₄ = (u × v_A)/s,  α₄ = (u × a_A − 2 ṡ ω₄)/s.
/// The block turns with the lever (ω₃ = ω₄, α₃ = α₄); lever-fixed offsets are stored in
/// the slot frame (u, n), absolute (u is a unit vector).
#[derive(Clone, Copy, Debug)]
pub struct QuickReturnHand {
    o2: V2,
    o4: V2,
    /// r₂, crank length (m).
    r2: f64,
    /// θ₄ in the drawing (the block's zero: it turns with the lever).
    theta4_ref: f64,
    /// cg of the crank in its frame O2→A, scaled by 1/r₂.
    g2: (f64, f64),
    /// Block cg − A in the slot frame (m).
    g3: (f64, f64),
    /// Lever cg − O4 in the slot frame (m).
    g4: (f64, f64),
    /// C − O4 in the slot frame (m).
    c4: (f64, f64),
    /// Masses (kg) and inertias about the cgs (kg·m²).
    m2: f64,
    m3: f64,
    m4: f64,
    i2: f64,
    i3: f64,
    i4: f64,
    /// I_O2 = I₂ + m₂|G₂ − O2|² (kg·m²).
    io2: f64,
    /// I_O4 + I₃ = I₄ + m₄|G₄ − O4|² + I₃: everything that turns at ω₄ about a fixed
    /// point or its own cg (kg·m²).
    io4_i3: f64,
    /// Weights m_k·g (N).
    w2: V2,
    w3: V2,
    w4: V2,
}

/// Result of [`QuickReturnHand::pose`].
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct QuickReturnHandPose {
    /// Crank: θ₂ = q (not wrapped), cg.
    pub crank: HandLinkPose,
    /// Block: its rotation since the drawing (the lever's), cg.
    pub block: HandLinkPose,
    /// Lever: θ₄ = atan2(C − O4), cg.
    pub lever: HandLinkPose,
    /// O2, O4 (fixed), A, C (m).
    pub o2: V2,
    pub o4: V2,
    pub a: V2,
    pub c: V2,
}

/// Result of [`QuickReturnHand::kinematics`].
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct QuickReturnHandMotion {
    /// Crank: θ₂ = q, ω₂ = q̇, α₂ = q̈, its cg.
    pub crank: HandLinkMotion,
    /// Block: the lever's rotation since the drawing, ω₄, α₄, its cg.
    pub block: HandLinkMotion,
    /// Lever: θ₄, ω₄, α₄, its cg.
    pub lever: HandLinkMotion,
    /// O2, O4 (fixed), A, C.
    pub o2: HandPointMotion,
    pub o4: HandPointMotion,
    pub a: HandPointMotion,
    pub c: HandPointMotion,
}

/// Result of [`QuickReturnHand::kinetostatics`]: the driver torque (N·m) and the
/// reactions, each BY the joint's first link ON its second (N, N·m).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct QuickReturnHandForces {
    /// Motor torque on the crank.
    pub driver: f64,
    /// R_O2: ground on crank.
    pub o2: V2,
    /// R_A: crank on block.
    pub a: V2,
    /// Slot: lever on block, its force (normal to the slot) and moment about A.
    pub slot: V2,
    pub slot_moment: f64,
    /// R_O4: ground on lever.
    pub o4: V2,
}

/// The slot frame of one crank angle.
#[derive(Clone, Copy, Debug)]
struct Slot {
    /// A − O2, A.
    a2: V2,
    a: V2,
    /// 1/s and the slot's unit direction u = (A − O4)/s.
    inv_s: f64,
    u: V2,
}

/// (u·v, u × v): the coordinates of v in the frame (u, perp(u)) of a unit u.
fn frame(u: V2, v: V2) -> (f64, f64) {
    (u.dot(&v), cross(u, v))
}

impl QuickReturnHand {
    /// Precompute the drawing's constants from `p`. Panics unless the slot runs through O4
    /// (this machine's geometry: the code is written for it).
    pub fn new(p: &QuickReturnParams) -> Self {
        let (o2, o4, a, c) = (p.points.O2, p.points.O4, p.points.A, p.points.C);
        let (crank, block, lever) = (&p.links.crank, &p.links.block, &p.links.lever);
        let d = a - o4;
        let u0 = d.normalize();
        assert!(
            cross(p.axes.slot.normalize(), d).abs() <= 1e-12 * d.norm(),
            "QuickReturnHand: the slot must run through O4"
        );
        let io4 = lever.inertia + lever.mass * (lever.cg - o4).norm_squared();
        QuickReturnHand {
            o2,
            o4,
            r2: (a - o2).norm(),
            theta4_ref: (c.y - o4.y).atan2(c.x - o4.x),
            g2: local_scaled(o2, a, crank.cg),
            g3: frame(u0, block.cg - a),
            g4: frame(u0, lever.cg - o4),
            c4: frame(u0, c - o4),
            m2: crank.mass,
            m3: block.mass,
            m4: lever.mass,
            i2: crank.inertia,
            i3: block.inertia,
            i4: lever.inertia,
            io2: crank.inertia + crank.mass * (crank.cg - o2).norm_squared(),
            io4_i3: io4 + block.inertia,
            w2: p.gravity * crank.mass,
            w3: p.gravity * block.mass,
            w4: p.gravity * lever.mass,
        }
    }

    /// A = O2 + r₂(cos q, sin q) and the slot's direction u = (A − O4)/|A − O4|; `None`
    /// when A is on O4 (never for this drawing: |O2 O4| > r₂).
    #[inline(always)]
    fn slot(&self, q: f64) -> Option<Slot> {
        let (sn, cs) = q.sin_cos();
        let a2 = V2::new(self.r2 * cs, self.r2 * sn);
        let a = self.o2 + a2;
        let d = a - self.o4;
        let s2 = d.norm_squared();
        if s2 > 0.0 {
            let inv_s = 1.0 / s2.sqrt();
            Some(Slot {
                a2,
                a,
                inv_s,
                u: d * inv_s,
            })
        } else {
            None // (NaN too)
        }
    }

    /// θ₄ = atan2(C − O4) and the block's angle, its rotation since the drawing (the
    /// lever's): θ₄ − θ₄(drawing), in (−π, π].
    #[inline(always)]
    fn angles(&self, rc: V2) -> (f64, f64) {
        let theta4 = rc.y.atan2(rc.x);
        (theta4, wrap_difference(theta4 - self.theta4_ref))
    }

    /// Position analysis: θ₂ = q, the block's rotation, θ₄ = atan2(C − O4), the cgs, A, C.
    #[inline(never)]
    pub fn pose(&self, q: f64) -> Option<QuickReturnHandPose> {
        let Slot { a2, a, u, .. } = self.slot(q)?;
        let rc = at(V2::zeros(), u, self.c4);
        let (theta4, theta3) = self.angles(rc);
        Some(QuickReturnHandPose {
            crank: HandLinkPose {
                angle: q,
                cg: at(self.o2, a2, self.g2),
            },
            block: HandLinkPose {
                angle: theta3,
                cg: at(a, u, self.g3),
            },
            lever: HandLinkPose {
                angle: theta4,
                cg: at(self.o4, u, self.g4),
            },
            o2: self.o2,
            o4: self.o4,
            a,
            c: self.o4 + rc,
        })
    }

    /// Position, velocity and acceleration analysis at (q, q̇, q̈) (see the type's docs).
    #[inline(never)]
    pub fn kinematics(&self, q: f64, qd: f64, qdd: f64) -> Option<QuickReturnHandMotion> {
        let Slot { a2, a, inv_s, u } = self.slot(q)?;
        let (w2, al2) = (qd, qdd);
        let va = perp(a2) * w2;
        let aa = perp(a2) * al2 - a2 * (w2 * w2);
        let sd = va.dot(&u);
        let w4 = cross(u, va) * inv_s;
        let al4 = (cross(u, aa) - 2.0 * sd * w4) * inv_s;

        let r = at(V2::zeros(), a2, self.g2);
        let crank = HandLinkMotion {
            angle: q,
            omega: w2,
            alpha: al2,
            cg: self.o2 + r,
            cg_vel: perp(r) * w2,
            cg_acc: perp(r) * al2 - r * (w2 * w2),
        };
        let rc = at(V2::zeros(), u, self.c4);
        let (theta4, theta3) = self.angles(rc);
        let r = at(V2::zeros(), u, self.g3);
        let block = HandLinkMotion {
            angle: theta3,
            omega: w4,
            alpha: al4,
            cg: a + r,
            cg_vel: va + perp(r) * w4,
            cg_acc: aa + perp(r) * al4 - r * (w4 * w4),
        };
        let r = at(V2::zeros(), u, self.g4);
        let lever = HandLinkMotion {
            angle: theta4,
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
        Some(QuickReturnHandMotion {
            crank,
            block,
            lever,
            o2: fixed(self.o2),
            o4: fixed(self.o4),
            a: HandPointMotion {
                pos: a,
                vel: va,
                acc: aa,
            },
            c: HandPointMotion {
                pos: self.o4 + rc,
                vel: perp(rc) * w4,
                acc: perp(rc) * al4 - rc * (w4 * w4),
            },
        })
    }

    /// Kinetostatics by d'Alembert, the group (block, lever) first, then the crank.
    ///
    /// Per link k: F_k = m_k g − m_k a_Gk and its moment about the link's pin
    /// M_k = (G_k − pin) × F_k − I_k α_k (+ the loads: (C − O4) × F_cut on the lever, the
    /// friction torque on the crank). The slot's reaction on the block is N n at A with a
    /// moment M_s. The block's moments about A give M_s = −M₃; the lever's about O4,
    /// −N s − M_s + M₄ = 0, give N = (M₃ + M₄)/s, so N n = (M₃ + M₄) perp(d)/s² with
    /// d = A − O4. Then the force balances R_A = −N n − F₃, R_O4 = N n − F₄ − F_cut,
    /// R_O2 = R_A − F₂, and the crank's moments about O2: T = a₂ × R_A − M₂.
    #[inline(never)]
    pub fn kinetostatics(
        &self,
        m: &QuickReturnHandMotion,
        loads: &QuickReturnLoads,
    ) -> QuickReturnHandForces {
        let a2 = m.a.pos - self.o2;
        let d = m.a.pos - self.o4;
        let f2 = self.w2 - m.crank.cg_acc * self.m2;
        let f3 = self.w3 - m.block.cg_acc * self.m3;
        let f4 = self.w4 - m.lever.cg_acc * self.m4;
        let m2 = cross(m.crank.cg - self.o2, f2) - self.i2 * m.crank.alpha + loads.friction;
        let m3 = cross(m.block.cg - m.a.pos, f3) - self.i3 * m.block.alpha;
        let m4 = cross(m.lever.cg - self.o4, f4) + cross(m.c.pos - self.o4, loads.cut)
            - self.i4 * m.lever.alpha;
        let slot = perp(d) * ((m3 + m4) / d.norm_squared());
        let ra = -slot - f3;
        QuickReturnHandForces {
            driver: cross(a2, ra) - m2,
            o2: ra - f2,
            a: ra,
            slot,
            slot_moment: -m3,
            o4: slot - f4 - loads.cut,
        }
    }

    /// The driver torque by virtual power, no reaction computed:
    /// T ω₂ + Σ_k [F_k·v_Gk − I_k α_k ω_k] + F_cut·v_C + T_friction ω₂ = 0 (q̇ ≠ 0).
    #[inline(never)]
    pub fn driver_action(&self, m: &QuickReturnHandMotion, loads: &QuickReturnLoads) -> f64 {
        let p2 = (self.w2 - m.crank.cg_acc * self.m2).dot(&m.crank.cg_vel)
            - self.i2 * m.crank.alpha * m.crank.omega;
        let p3 = (self.w3 - m.block.cg_acc * self.m3).dot(&m.block.cg_vel)
            - self.i3 * m.block.alpha * m.block.omega;
        let p4 = (self.w4 - m.lever.cg_acc * self.m4).dot(&m.lever.cg_vel)
            - self.i4 * m.lever.alpha * m.lever.omega;
        let pl = loads.cut.dot(&m.c.vel) + loads.friction * m.crank.omega;
        -(p2 + p3 + p4 + pl) / m.crank.omega
    }

    /// The velocity coefficients at q (per unit q̇): with q̇ = 1, q̈ = 0 (v_A = perp(a₂),
    /// a_A = −a₂) the formulas of the type's docs give
    /// k_s = ds/dq = a₂ × u,  k₄ = dθ₄/dq = (u·a₂)/s,  k₄' = k_s (1 − 2k₄)/s,
    /// and the block's cg, at r₃ from A, g_G3 = perp(a₂) + k₄ perp(r₃),
    /// g'_G3 = −a₂ + k₄' perp(r₃) − k₄² r₃. Returns (k₄, k₄', g_G3, g'_G3, a₂, u).
    #[inline(always)]
    fn coefficients(&self, q: f64) -> Option<(f64, f64, V2, V2, V2, V2)> {
        let Slot { a2, inv_s, u, .. } = self.slot(q)?;
        let ks = cross(a2, u);
        let k4 = u.dot(&a2) * inv_s;
        let k4d = ks * (1.0 - 2.0 * k4) * inv_s;
        let r3 = at(V2::zeros(), u, self.g3);
        let g3 = perp(a2) + perp(r3) * k4;
        let g3d = perp(r3) * k4d - a2 - r3 * (k4 * k4);
        Some((k4, k4d, g3, g3d, a2, u))
    }

    /// Zhukovski's I* = I_O2 + (I_O4 + I₃) k₄² + m₃|g_G3|² and
    /// dI*/dq = 2 ((I_O4 + I₃) k₄ k₄' + m₃ g_G3·g'_G3); `None` without assembly.
    #[inline(never)]
    pub fn reduced(&self, q: f64) -> Option<HandReduced> {
        let (k4, k4d, g3, g3d, ..) = self.coefficients(q)?;
        Some(HandReduced {
            inertia: self.io2 + self.io4_i3 * k4 * k4 + self.m3 * g3.norm_squared(),
            inertia_derivative: 2.0 * (self.io4_i3 * k4 * k4d + self.m3 * g3.dot(&g3d)),
        })
    }

    /// M* = m₂g·g_G2 + m₃g·g_G3 + k₄ [(G₄ − O4) × m₄g + (C − O4) × F_cut] + T_friction,
    /// with m₂g·g_G2 = (G₂ − O2) × m₂g.
    #[inline(always)]
    fn moment_of(&self, k4: f64, g3: V2, a2: V2, u: V2, loads: &QuickReturnLoads) -> f64 {
        let r2 = at(V2::zeros(), a2, self.g2);
        let r4 = at(V2::zeros(), u, self.g4);
        let rc = at(V2::zeros(), u, self.c4);
        cross(r2, self.w2)
            + self.w3.dot(&g3)
            + k4 * (cross(r4, self.w4) + cross(rc, loads.cut))
            + loads.friction
    }

    /// Zhukovski's reduced moment M*(q) of the loads and gravity (N·m).
    #[inline(never)]
    pub fn reduced_moment(&self, q: f64, loads: &QuickReturnLoads) -> Option<f64> {
        let (k4, _, g3, _, a2, u) = self.coefficients(q)?;
        Some(self.moment_of(k4, g3, a2, u, loads))
    }

    /// The direct problem: q̈ = (T + M* − ½ dI*/dq q̇²)/I*.
    #[inline(never)]
    pub fn acceleration(
        &self,
        q: f64,
        qd: f64,
        driver: f64,
        loads: &QuickReturnLoads,
    ) -> Option<f64> {
        let (k4, k4d, g3, g3d, a2, u) = self.coefficients(q)?;
        let inertia = self.io2 + self.io4_i3 * k4 * k4 + self.m3 * g3.norm_squared();
        let half_derivative = self.io4_i3 * k4 * k4d + self.m3 * g3.dot(&g3d);
        Some((driver + self.moment_of(k4, g3, a2, u, loads) - half_derivative * qd * qd) / inertia)
    }
}
