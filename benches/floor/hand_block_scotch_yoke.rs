//! Hand-written closed forms of the `BlockScotchYoke` of `benches/floor/machines.rs` (a
//! module of `hand.rs`, whose conventions it keeps).

use super::*;

/// The Scotch yoke with an explicit block: the crank O2–A carries the block 3, pinned at A,
/// which slides in the slot u_s of the yoke 4; the yoke slides on the ground along the
/// guide u_g (at Y). An RPP dyad: the block and the yoke keep their drawing orientation
/// (the yoke's is the ground's, the block's the yoke's), so the block translates with A
/// and the yoke along u_g.
///
/// The yoke's travel x: A = A₀ + x u_g + t u_s (t the block's place in the slot) dotted
/// with the slot's normal n_s gives x = k·(A − A₀), k = n_s/(n_s·u_g): with a₂ = A − O2,
/// x = k·a₂ up to a constant, ẋ = k·v_A, ẍ = k·a_A. Every point of the yoke is at its
/// place at x = 0 (stored) plus x u_g, every point of the block at A plus its drawing
/// offset from A.
#[derive(Clone, Copy, Debug)]
pub struct BlockScotchYokeHand {
    o2: V2,
    /// r₂, crank length (m).
    r2: f64,
    /// The guide's unit direction u_g, the slot's unit normal n_s.
    ug: V2,
    ns: V2,
    /// k = n_s/(n_s·u_g): x = k·a₂.
    k: V2,
    /// u_g/(n_s·u_g): the slot force's magnitude along n_s from the yoke's load W.
    kg: V2,
    /// Y, T and the yoke's cg where x = k·a₂ = 0 (m).
    y0: V2,
    t0: V2,
    gy0: V2,
    /// G₄ − Y and T − Y (constant: the yoke translates).
    ryg: V2,
    ryt: V2,
    /// The yoke's angle, atan2(T − Y) (constant).
    theta4: f64,
    /// The block's cg − A (constant: the block translates).
    rb: V2,
    /// cg of the crank in its frame O2→A, scaled by 1/r₂.
    g2: (f64, f64),
    /// The first moment about O2 of the crank and the block (the block's mass at A), in
    /// the crank's frame scaled by 1/r₂ (kg): m₂(G₂ − O2) + m₃ a₂ = at(0, a₂, this).
    first_moment: (f64, f64),
    /// Masses (kg), the crank's inertia about its cg and I_O2 + m₃r₂² (the block turns
    /// about nothing, its mass goes round at A) (kg·m²).
    m2: f64,
    m3: f64,
    m4: f64,
    i2: f64,
    io2_m3r2sq: f64,
    /// gravity and the weights m·g (N).
    g: V2,
    w2: V2,
    w3: V2,
    w4: V2,
}

/// Result of [`BlockScotchYokeHand::pose`].
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct BlockScotchYokeHandPose {
    /// Crank: θ₂ = q (not wrapped), cg.
    pub crank: HandLinkPose,
    /// Block: θ = 0 (it does not turn), cg.
    pub block: HandLinkPose,
    /// Yoke: θ = atan2(T − Y) (constant), cg.
    pub yoke: HandLinkPose,
    /// O2 (fixed), A, Y, T (m).
    pub o2: V2,
    pub a: V2,
    pub y: V2,
    pub t: V2,
}

/// Result of [`BlockScotchYokeHand::kinematics`].
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct BlockScotchYokeHandMotion {
    /// Crank: θ₂ = q, ω₂ = q̇, α₂ = q̈, its cg.
    pub crank: HandLinkMotion,
    /// Block: θ = ω = α = 0, its cg (moving with A).
    pub block: HandLinkMotion,
    /// Yoke: its constant angle, ω = α = 0, its cg.
    pub yoke: HandLinkMotion,
    /// O2 (fixed), A, Y, T.
    pub o2: HandPointMotion,
    pub a: HandPointMotion,
    pub y: HandPointMotion,
    pub t: HandPointMotion,
}

/// Result of [`BlockScotchYokeHand::kinetostatics`]: the driver torque (N·m) and the
/// reactions, each BY the joint's first link ON its second (N, N·m).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct BlockScotchYokeHandForces {
    /// Motor torque on the crank.
    pub driver: f64,
    /// R_O2: ground on crank.
    pub o2: V2,
    /// R_A: crank on block.
    pub a: V2,
    /// Slot: yoke on block, its force (normal to the slot) and moment about A.
    pub slot: V2,
    pub slot_moment: f64,
    /// Guide: ground on yoke, its force (normal to u_g) and moment about Y.
    pub guide: V2,
    pub guide_moment: f64,
}

impl BlockScotchYokeHand {
    /// Precompute the drawing's constants from `p`.
    pub fn new(p: &BlockScotchYokeParams) -> Self {
        let (o2, a, y, t) = (p.points.O2, p.points.A, p.points.Y, p.points.T);
        let (crank, block, yoke) = (&p.links.crank, &p.links.block, &p.links.yoke);
        let ug = p.axes.guide.normalize();
        let ns = perp(p.axes.slot.normalize());
        let k = ns / ns.dot(&ug);
        // x in the drawing: the yoke's points where x = 0 are theirs less x₀ u_g.
        let shift = ug * k.dot(&(a - o2));
        let g2 = local_scaled(o2, a, crank.cg);
        let r2 = (a - o2).norm();
        BlockScotchYokeHand {
            o2,
            r2,
            ug,
            ns,
            k,
            kg: ug / ns.dot(&ug),
            y0: y - shift,
            t0: t - shift,
            gy0: yoke.cg - shift,
            ryg: yoke.cg - y,
            ryt: t - y,
            theta4: (t.y - y.y).atan2(t.x - y.x),
            rb: block.cg - a,
            g2,
            first_moment: (crank.mass * g2.0 + block.mass, crank.mass * g2.1),
            m2: crank.mass,
            m3: block.mass,
            m4: yoke.mass,
            i2: crank.inertia,
            io2_m3r2sq: crank.inertia
                + crank.mass * (crank.cg - o2).norm_squared()
                + block.mass * r2 * r2,
            g: p.gravity,
            w2: p.gravity * crank.mass,
            w3: p.gravity * block.mass,
            w4: p.gravity * yoke.mass,
        }
    }

    /// a₂ = A − O2 = r₂(cos q, sin q).
    #[inline(always)]
    fn crank(&self, q: f64) -> V2 {
        let (sn, cs) = q.sin_cos();
        V2::new(self.r2 * cs, self.r2 * sn)
    }

    /// Position analysis: θ₂ = q, the yoke's travel x = k·a₂, the cgs, A, Y, T.
    /// (`Option` as the other machines; the dyad always assembles, the slot not being
    /// parallel to the guide.)
    #[inline(never)]
    pub fn pose(&self, q: f64) -> Option<BlockScotchYokeHandPose> {
        let a2 = self.crank(q);
        let a = self.o2 + a2;
        let dx = self.ug * self.k.dot(&a2);
        Some(BlockScotchYokeHandPose {
            crank: HandLinkPose {
                angle: q,
                cg: at(self.o2, a2, self.g2),
            },
            block: HandLinkPose {
                angle: 0.0,
                cg: a + self.rb,
            },
            yoke: HandLinkPose {
                angle: self.theta4,
                cg: self.gy0 + dx,
            },
            o2: self.o2,
            a,
            y: self.y0 + dx,
            t: self.t0 + dx,
        })
    }

    /// Position, velocity and acceleration analysis at (q, q̇, q̈) (see the type's docs).
    #[inline(never)]
    pub fn kinematics(&self, q: f64, qd: f64, qdd: f64) -> Option<BlockScotchYokeHandMotion> {
        let a2 = self.crank(q);
        let a = self.o2 + a2;
        let (w2, al2) = (qd, qdd);
        let va = perp(a2) * w2;
        let aa = perp(a2) * al2 - a2 * (w2 * w2);
        let dx = self.ug * self.k.dot(&a2);
        let v = self.ug * self.k.dot(&va);
        let acc = self.ug * self.k.dot(&aa);
        let r = at(V2::zeros(), a2, self.g2);
        let yoke = |pos| HandPointMotion { pos, vel: v, acc };
        Some(BlockScotchYokeHandMotion {
            crank: HandLinkMotion {
                angle: q,
                omega: w2,
                alpha: al2,
                cg: self.o2 + r,
                cg_vel: perp(r) * w2,
                cg_acc: perp(r) * al2 - r * (w2 * w2),
            },
            block: HandLinkMotion {
                angle: 0.0,
                omega: 0.0,
                alpha: 0.0,
                cg: a + self.rb,
                cg_vel: va,
                cg_acc: aa,
            },
            yoke: HandLinkMotion {
                angle: self.theta4,
                omega: 0.0,
                alpha: 0.0,
                cg: self.gy0 + dx,
                cg_vel: v,
                cg_acc: acc,
            },
            o2: HandPointMotion {
                pos: self.o2,
                vel: V2::zeros(),
                acc: V2::zeros(),
            },
            a: HandPointMotion {
                pos: a,
                vel: va,
                acc: aa,
            },
            y: yoke(self.y0 + dx),
            t: yoke(self.t0 + dx),
        })
    }

    /// Kinetostatics by d'Alembert, the yoke, the block, then the crank.
    ///
    /// With F_k = m_k g − m_k a_Gk: the yoke carries W = F₄ + F_resist, the slot's −S (by
    /// the block, at A, S = σ n_s) and −M_s, the guide's force (normal to u_g) and M_g.
    /// Along u_g: σ = W·u_g/(n_s·u_g); the guide's force is S − W. The block: R_A = −S − F₃,
    /// and its moments about A (it does not turn) M_s = −T_friction − (G₃ − A) × F₃. The
    /// yoke's about Y: M_g = M_s + (A − Y) × S − (G₄ − Y) × F₄ − (T − Y) × F_resist. The
    /// crank: R_O2 = R_A − F₂ and T = a₂ × R_A − M₂, M₂ = (G₂ − O2) × F₂ − I₂α₂.
    #[inline(never)]
    pub fn kinetostatics(
        &self,
        m: &BlockScotchYokeHandMotion,
        loads: &BlockScotchYokeLoads,
    ) -> BlockScotchYokeHandForces {
        let a2 = m.a.pos - self.o2;
        let f2 = self.w2 - m.crank.cg_acc * self.m2;
        let f3 = self.w3 - m.a.acc * self.m3;
        let f4 = self.w4 - m.y.acc * self.m4;
        let slot = self.ns * self.kg.dot(&(f4 + loads.resist));
        let ra = -slot - f3;
        let slot_moment = -loads.friction - cross(self.rb, f3);
        let m2 = cross(m.crank.cg - self.o2, f2) - self.i2 * m.crank.alpha;
        BlockScotchYokeHandForces {
            driver: cross(a2, ra) - m2,
            o2: ra - f2,
            a: ra,
            slot,
            slot_moment,
            guide: slot - f4 - loads.resist,
            guide_moment: slot_moment + cross(m.a.pos - m.y.pos, slot)
                - cross(self.ryg, f4)
                - cross(self.ryt, loads.resist),
        }
    }

    /// The driver torque by virtual power, no reaction computed:
    /// T ω₂ + F₂·v_G2 − I₂α₂ω₂ + F₃·v_A + (F₄ + F_resist)·v_Y = 0 (q̇ ≠ 0; the block's
    /// points all move at v_A, the yoke's at v_Y, and the friction couple on the block,
    /// which does not turn, does no work).
    #[inline(never)]
    pub fn driver_action(
        &self,
        m: &BlockScotchYokeHandMotion,
        loads: &BlockScotchYokeLoads,
    ) -> f64 {
        let p2 = (self.w2 - m.crank.cg_acc * self.m2).dot(&m.crank.cg_vel)
            - self.i2 * m.crank.alpha * m.crank.omega;
        let p3 = (self.w3 - m.a.acc * self.m3).dot(&m.a.vel);
        let p4 = (self.w4 - m.y.acc * self.m4 + loads.resist).dot(&m.y.vel);
        -(p2 + p3 + p4) / m.crank.omega
    }

    /// Zhukovski's I* = I_O2 + m₃r₂² + m₄x'², dI*/dq = 2 m₄ x' x'', with x' = k·perp(a₂),
    /// x'' = −k·a₂.
    #[inline(never)]
    pub fn reduced(&self, q: f64) -> Option<HandReduced> {
        let a2 = self.crank(q);
        let xd = self.k.dot(&perp(a2));
        let m4xd = self.m4 * xd;
        Some(HandReduced {
            inertia: self.io2_m3r2sq + m4xd * xd,
            inertia_derivative: -2.0 * m4xd * self.k.dot(&a2),
        })
    }

    /// M* = (m₂(G₂ − O2) + m₃a₂) × g + (m₄g + F_resist)·u_g x' (the friction couple does
    /// no work).
    #[inline(always)]
    fn moment_of(&self, a2: V2, xd: f64, loads: &BlockScotchYokeLoads) -> f64 {
        cross(at(V2::zeros(), a2, self.first_moment), self.g)
            + (self.w4 + loads.resist).dot(&self.ug) * xd
    }

    /// Zhukovski's reduced moment M*(q) of the loads and gravity (N·m).
    #[inline(never)]
    pub fn reduced_moment(&self, q: f64, loads: &BlockScotchYokeLoads) -> Option<f64> {
        let a2 = self.crank(q);
        Some(self.moment_of(a2, self.k.dot(&perp(a2)), loads))
    }

    /// The direct problem: q̈ = (T + M* − ½ dI*/dq q̇²)/I*.
    #[inline(never)]
    pub fn acceleration(
        &self,
        q: f64,
        qd: f64,
        driver: f64,
        loads: &BlockScotchYokeLoads,
    ) -> Option<f64> {
        let a2 = self.crank(q);
        let xd = self.k.dot(&perp(a2));
        let m4xd = self.m4 * xd;
        let inertia = self.io2_m3r2sq + m4xd * xd;
        let half_derivative = -m4xd * self.k.dot(&a2);
        Some((driver + self.moment_of(a2, xd, loads) - half_derivative * qd * qd) / inertia)
    }
}
