//! Hand-written closed forms of the `InvertedSliderCrank` of `benches/floor/machines.rs`
//! (a module of `hand.rs`, whose conventions it keeps).

use super::*;

/// The inverted slider-crank: the crank O2–A drives the rod 3 (A–P), pinned at A; the
/// rod's slide line, at the signed distance e from A, runs through the block 4 pivoted on
/// the ground at O4 (an RPR group: pin A, slide, pin O4; the guide is the rod).
///
/// In the rod's frame (u along the slide, n = perp(u)), d = O4 − A = t u + e n with t the
/// slide coordinate, so t = σ√(|d|² − e²) (σ: the drawing's side) and
/// u = (t d − e perp(d))/|d|². Differentiating d = t u + e n (u̇ = ω n, ṅ = −ω u), with
/// ḋ = −v_A, d̈ = −a_A:
/// ḋ = (ṫ − eω) u + tω n,  d̈ = (ẗ − eα − tω²) u + (2ṫω − eω² + tα) n, so
/// ω = −(n·v_A)/t,  ṫ = eω − u·v_A,  α = (eω² − n·a_A − 2ṫω)/t.
/// The block turns with the rod. Rod-fixed offsets (from A) and block-fixed ones (from O4)
/// are stored in the frame (u, n), absolute (u is a unit vector).
#[derive(Clone, Copy, Debug)]
pub struct InvertedSliderCrankHand {
    o2: V2,
    o4: V2,
    /// r₂, crank length (m).
    r2: f64,
    /// e, the slide line's signed distance from A (along n), and e² (m, m²).
    e: f64,
    esq: f64,
    /// Branch: sign of t in the drawing.
    sigma: f64,
    /// θ₃ in the drawing (the block's zero: it turns with the rod).
    theta3_ref: f64,
    /// cg of the crank in its frame O2→A, scaled by 1/r₂.
    g2: (f64, f64),
    /// Rod cg − A and P − A in the rod frame (m).
    g3: (f64, f64),
    p3: (f64, f64),
    /// u from P − A: u = c₀ (P − A) + c₁ perp(P − A).
    u_of_p: (f64, f64),
    /// Block cg − O4 in the rod frame (m).
    g4: (f64, f64),
    /// Masses (kg) and inertias about the cgs (kg·m²).
    m2: f64,
    m3: f64,
    m4: f64,
    i2: f64,
    i3: f64,
    i4: f64,
    /// I_O2 = I₂ + m₂|G₂ − O2|² (kg·m²).
    io2: f64,
    /// I_O4 + I₃ = I₄ + m₄|G₄ − O4|² + I₃: everything that turns at ω about a fixed point
    /// or its own cg (kg·m²).
    io4_i3: f64,
    /// Weights m_k·g (N).
    w2: V2,
    w3: V2,
    w4: V2,
}

/// Result of [`InvertedSliderCrankHand::pose`].
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct InvertedSliderCrankHandPose {
    /// Crank: θ₂ = q (not wrapped), cg.
    pub crank: HandLinkPose,
    /// Rod: θ₃ = atan2(P − A), cg.
    pub rod: HandLinkPose,
    /// Block: its rotation since the drawing (the rod's), cg.
    pub block: HandLinkPose,
    /// O2, O4 (fixed), A, P (m).
    pub o2: V2,
    pub o4: V2,
    pub a: V2,
    pub p: V2,
}

/// Result of [`InvertedSliderCrankHand::kinematics`].
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct InvertedSliderCrankHandMotion {
    /// Crank: θ₂ = q, ω₂ = q̇, α₂ = q̈, its cg.
    pub crank: HandLinkMotion,
    /// Rod: θ₃, ω, α, its cg.
    pub rod: HandLinkMotion,
    /// Block: the rod's rotation since the drawing, ω, α, its cg.
    pub block: HandLinkMotion,
    /// O2, O4 (fixed), A, P.
    pub o2: HandPointMotion,
    pub o4: HandPointMotion,
    pub a: HandPointMotion,
    pub p: HandPointMotion,
}

/// Result of [`InvertedSliderCrankHand::kinetostatics`]: the driver torque (N·m) and the
/// reactions, each BY the joint's first link ON its second (N, N·m).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct InvertedSliderCrankHandForces {
    /// Motor torque on the crank.
    pub driver: f64,
    /// R_O2: ground on crank.
    pub o2: V2,
    /// R_A: crank on rod.
    pub a: V2,
    /// Slide: rod on block, its force (normal to the slide) and moment about O4.
    pub slide: V2,
    pub slide_moment: f64,
    /// R_O4: ground on block.
    pub o4: V2,
}

/// The rod's frame at one crank angle.
#[derive(Clone, Copy, Debug)]
struct RodFrame {
    /// A − O2, A.
    a2: V2,
    a: V2,
    /// t, and u (unit, along the slide).
    t: f64,
    u: V2,
}

impl InvertedSliderCrankHand {
    /// Precompute the drawing's constants from `p`.
    pub fn new(p: &InvertedSliderCrankParams) -> Self {
        let (o2, o4, a, pp) = (p.points.O2, p.points.O4, p.points.A, p.points.P);
        let (crank, rod, block) = (&p.links.crank, &p.links.rod, &p.links.block);
        let u0 = p.axes.slide.normalize();
        let frame = |v: V2| (u0.dot(&v), cross(u0, v));
        let d = o4 - a;
        let e = cross(u0, d);
        let p3 = frame(pp - a);
        let p3sq = p3.0 * p3.0 + p3.1 * p3.1;
        let io4 = block.inertia + block.mass * (block.cg - o4).norm_squared();
        InvertedSliderCrankHand {
            o2,
            o4,
            r2: (a - o2).norm(),
            e,
            esq: e * e,
            sigma: u0.dot(&d).signum(),
            theta3_ref: (pp.y - a.y).atan2(pp.x - a.x),
            g2: local_scaled(o2, a, crank.cg),
            g3: frame(rod.cg - a),
            p3,
            u_of_p: (p3.0 / p3sq, -p3.1 / p3sq),
            g4: frame(block.cg - o4),
            m2: crank.mass,
            m3: rod.mass,
            m4: block.mass,
            i2: crank.inertia,
            i3: rod.inertia,
            i4: block.inertia,
            io2: crank.inertia + crank.mass * (crank.cg - o2).norm_squared(),
            io4_i3: io4 + rod.inertia,
            w2: p.gravity * crank.mass,
            w3: p.gravity * rod.mass,
            w4: p.gravity * block.mass,
        }
    }

    /// A = O2 + r₂(cos q, sin q), t and u (see the type's docs); `None` when O4 is nearer
    /// to A than e (never for this drawing).
    #[inline(always)]
    fn close(&self, q: f64) -> Option<RodFrame> {
        let (sn, cs) = q.sin_cos();
        let a2 = V2::new(self.r2 * cs, self.r2 * sn);
        let a = self.o2 + a2;
        let d = self.o4 - a;
        let l2 = d.norm_squared();
        let t2 = l2 - self.esq;
        if t2 > 0.0 {
            let t = self.sigma * t2.sqrt();
            let inv_l2 = 1.0 / l2;
            let u = V2::new(
                (t * d.x + self.e * d.y) * inv_l2,
                (t * d.y - self.e * d.x) * inv_l2,
            );
            Some(RodFrame { a2, a, t, u })
        } else {
            None // (NaN too)
        }
    }

    /// θ₃ = atan2(P − A) and the block's angle, its rotation since the drawing (the
    /// rod's): θ₃ − θ₃(drawing), in (−π, π].
    #[inline(always)]
    fn angles(&self, rp: V2) -> (f64, f64) {
        let theta3 = rp.y.atan2(rp.x);
        (theta3, wrap_difference(theta3 - self.theta3_ref))
    }

    /// Position analysis: θ₂ = q, θ₃ = atan2(P − A), the block's rotation, the cgs, A, P.
    #[inline(never)]
    pub fn pose(&self, q: f64) -> Option<InvertedSliderCrankHandPose> {
        let RodFrame { a2, a, u, .. } = self.close(q)?;
        let rp = at(V2::zeros(), u, self.p3);
        let (theta3, theta4) = self.angles(rp);
        Some(InvertedSliderCrankHandPose {
            crank: HandLinkPose {
                angle: q,
                cg: at(self.o2, a2, self.g2),
            },
            rod: HandLinkPose {
                angle: theta3,
                cg: at(a, u, self.g3),
            },
            block: HandLinkPose {
                angle: theta4,
                cg: at(self.o4, u, self.g4),
            },
            o2: self.o2,
            o4: self.o4,
            a,
            p: a + rp,
        })
    }

    /// Position, velocity and acceleration analysis at (q, q̇, q̈) (see the type's docs).
    #[inline(never)]
    pub fn kinematics(&self, q: f64, qd: f64, qdd: f64) -> Option<InvertedSliderCrankHandMotion> {
        let RodFrame { a2, a, t, u } = self.close(q)?;
        let n = perp(u);
        let inv_t = 1.0 / t;
        let (w2, al2) = (qd, qdd);
        let va = perp(a2) * w2;
        let aa = perp(a2) * al2 - a2 * (w2 * w2);
        let w = -n.dot(&va) * inv_t;
        let td = self.e * w - u.dot(&va);
        let al = (self.e * w * w - n.dot(&aa) - 2.0 * td * w) * inv_t;

        let r = at(V2::zeros(), a2, self.g2);
        let crank = HandLinkMotion {
            angle: q,
            omega: w2,
            alpha: al2,
            cg: self.o2 + r,
            cg_vel: perp(r) * w2,
            cg_acc: perp(r) * al2 - r * (w2 * w2),
        };
        let rp = at(V2::zeros(), u, self.p3);
        let (theta3, theta4) = self.angles(rp);
        let r = at(V2::zeros(), u, self.g3);
        let rod = HandLinkMotion {
            angle: theta3,
            omega: w,
            alpha: al,
            cg: a + r,
            cg_vel: va + perp(r) * w,
            cg_acc: aa + perp(r) * al - r * (w * w),
        };
        let r = at(V2::zeros(), u, self.g4);
        let block = HandLinkMotion {
            angle: theta4,
            omega: w,
            alpha: al,
            cg: self.o4 + r,
            cg_vel: perp(r) * w,
            cg_acc: perp(r) * al - r * (w * w),
        };
        let fixed = |pos| HandPointMotion {
            pos,
            vel: V2::zeros(),
            acc: V2::zeros(),
        };
        Some(InvertedSliderCrankHandMotion {
            crank,
            rod,
            block,
            o2: fixed(self.o2),
            o4: fixed(self.o4),
            a: HandPointMotion {
                pos: a,
                vel: va,
                acc: aa,
            },
            p: HandPointMotion {
                pos: a + rp,
                vel: va + perp(rp) * w,
                acc: aa + perp(rp) * al - rp * (w * w),
            },
        })
    }

    /// Kinetostatics by d'Alembert, the group (rod, block) first, then the crank.
    ///
    /// Per link k: F_k = m_k g − m_k a_Gk and its moment about the link's pin
    /// M_k = (G_k − pin) × F_k − I_k α_k (+ (P − A) × F_push on the rod, + T_resist on the
    /// block). The slide's reaction on the block is N n at O4 with a moment M_s. The
    /// block's moments about O4 give M_s = −M₄; the rod's about A, with
    /// (O4 − A) × (−N n) = −N t, give N = (M₃ + M₄)/t. u comes from P − A (no square root),
    /// t = u·(O4 − A). Then the force balances R_A = N n − F₃ − F_push, R_O4 = −N n − F₄,
    /// R_O2 = R_A − F₂, and the crank's moments about O2: T = a₂ × R_A − M₂.
    #[inline(never)]
    pub fn kinetostatics(
        &self,
        m: &InvertedSliderCrankHandMotion,
        loads: &InvertedSliderCrankLoads,
    ) -> InvertedSliderCrankHandForces {
        let a2 = m.a.pos - self.o2;
        let rp = m.p.pos - m.a.pos;
        let u = at(V2::zeros(), rp, self.u_of_p);
        let t = u.dot(&(self.o4 - m.a.pos));
        let f2 = self.w2 - m.crank.cg_acc * self.m2;
        let f3 = self.w3 - m.rod.cg_acc * self.m3;
        let f4 = self.w4 - m.block.cg_acc * self.m4;
        let m2 = cross(m.crank.cg - self.o2, f2) - self.i2 * m.crank.alpha;
        let m3 = cross(m.rod.cg - m.a.pos, f3) + cross(rp, loads.push) - self.i3 * m.rod.alpha;
        let m4 = cross(m.block.cg - self.o4, f4) - self.i4 * m.block.alpha + loads.resist;
        let slide = perp(u) * ((m3 + m4) / t);
        let ra = slide - f3 - loads.push;
        InvertedSliderCrankHandForces {
            driver: cross(a2, ra) - m2,
            o2: ra - f2,
            a: ra,
            slide,
            slide_moment: -m4,
            o4: -slide - f4,
        }
    }

    /// The driver torque by virtual power, no reaction computed:
    /// T ω₂ + Σ_k [F_k·v_Gk − I_k α_k ω_k] + F_push·v_P + T_resist ω = 0 (q̇ ≠ 0).
    #[inline(never)]
    pub fn driver_action(
        &self,
        m: &InvertedSliderCrankHandMotion,
        loads: &InvertedSliderCrankLoads,
    ) -> f64 {
        let p2 = (self.w2 - m.crank.cg_acc * self.m2).dot(&m.crank.cg_vel)
            - self.i2 * m.crank.alpha * m.crank.omega;
        let p3 = (self.w3 - m.rod.cg_acc * self.m3).dot(&m.rod.cg_vel)
            - self.i3 * m.rod.alpha * m.rod.omega;
        let p4 = (self.w4 - m.block.cg_acc * self.m4).dot(&m.block.cg_vel)
            - self.i4 * m.block.alpha * m.block.omega;
        let pl = loads.push.dot(&m.p.vel) + loads.resist * m.block.omega;
        -(p2 + p3 + p4 + pl) / m.crank.omega
    }

    /// The velocity coefficients at q (per unit q̇): with q̇ = 1, q̈ = 0 (v_A = perp(a₂),
    /// a_A = −a₂) the formulas of the type's docs give
    /// k = dθ₃/dq = −(u·a₂)/t,  k_t = dt/dq = e k − a₂ × u,
    /// k' = (u × a₂ − 2 k_t k + e k²)/t,
    /// and the rod's cg, at r₃ from A, g_G3 = perp(a₂) + k perp(r₃),
    /// g'_G3 = −a₂ + k' perp(r₃) − k² r₃. Returns (k, k', g_G3, g'_G3, a₂, u).
    #[inline(always)]
    fn coefficients(&self, q: f64) -> Option<(f64, f64, V2, V2, V2, V2)> {
        let RodFrame { a2, t, u, .. } = self.close(q)?;
        let inv_t = 1.0 / t;
        let k = -u.dot(&a2) * inv_t;
        let kt = self.e * k - cross(a2, u);
        let kd = (cross(u, a2) - 2.0 * kt * k + self.e * k * k) * inv_t;
        let r3 = at(V2::zeros(), u, self.g3);
        let g3 = perp(a2) + perp(r3) * k;
        let g3d = perp(r3) * kd - a2 - r3 * (k * k);
        Some((k, kd, g3, g3d, a2, u))
    }

    /// Zhukovski's I* = I_O2 + (I_O4 + I₃) k² + m₃|g_G3|² and
    /// dI*/dq = 2 ((I_O4 + I₃) k k' + m₃ g_G3·g'_G3); `None` without assembly.
    #[inline(never)]
    pub fn reduced(&self, q: f64) -> Option<HandReduced> {
        let (k, kd, g3, g3d, ..) = self.coefficients(q)?;
        Some(HandReduced {
            inertia: self.io2 + self.io4_i3 * k * k + self.m3 * g3.norm_squared(),
            inertia_derivative: 2.0 * (self.io4_i3 * k * kd + self.m3 * g3.dot(&g3d)),
        })
    }

    /// M* = (G₂ − O2) × m₂g + m₃g·g_G3 + F_push·g_P + k [(G₄ − O4) × m₄g + T_resist], with
    /// g_P = perp(a₂) + k perp(P − A).
    #[inline(always)]
    fn moment_of(&self, k: f64, g3: V2, a2: V2, u: V2, loads: &InvertedSliderCrankLoads) -> f64 {
        let r2 = at(V2::zeros(), a2, self.g2);
        let rp = at(V2::zeros(), u, self.p3);
        let r4 = at(V2::zeros(), u, self.g4);
        cross(r2, self.w2)
            + self.w3.dot(&g3)
            + loads.push.dot(&(perp(a2) + perp(rp) * k))
            + k * (cross(r4, self.w4) + loads.resist)
    }

    /// Zhukovski's reduced moment M*(q) of the loads and gravity (N·m).
    #[inline(never)]
    pub fn reduced_moment(&self, q: f64, loads: &InvertedSliderCrankLoads) -> Option<f64> {
        let (k, _, g3, _, a2, u) = self.coefficients(q)?;
        Some(self.moment_of(k, g3, a2, u, loads))
    }

    /// The direct problem: q̈ = (T + M* − ½ dI*/dq q̇²)/I*.
    #[inline(never)]
    pub fn acceleration(
        &self,
        q: f64,
        qd: f64,
        driver: f64,
        loads: &InvertedSliderCrankLoads,
    ) -> Option<f64> {
        let (k, kd, g3, g3d, a2, u) = self.coefficients(q)?;
        let inertia = self.io2 + self.io4_i3 * k * k + self.m3 * g3.norm_squared();
        let half_derivative = self.io4_i3 * k * kd + self.m3 * g3.dot(&g3d);
        Some((driver + self.moment_of(k, g3, a2, u, loads) - half_derivative * qd * qd) / inertia)
    }
}
