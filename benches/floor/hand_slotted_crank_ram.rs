//! Hand-written closed forms of the `SlottedCrankRam` of `benches/floor/machines.rs` (a
//! module of `hand.rs`, whose conventions it keeps).

use super::*;

/// The slotted crank driving a ram: the block 3 slides in the slot of the crank 2 (a line
/// fixed in the crank, at the signed distance e from O2) and is pinned at B to the ram 4,
/// which slides on the ground along u_g, its line at the signed distance h from O2. A PRP
/// dyad: the block turns with the crank, the ram does not turn, B is where the two lines
/// cross.
///
/// With β = q + β₀ the slot's direction from u_g (s, c = sin β, cos β; the slot's unit
/// u = c u_g + s n_g, n = perp(u), n_g = perp(u_g)), B − O2 = h n_g + x u_g on the slot's
/// line (B − O2)·n = e gives h c − x s = e, so
/// x = (h c − e)/s,
/// and differentiating twice in q, x' = −(h s + x c)/s = −t/s (t = (B − O2)·u, the block's
/// place along the slot) and x'' = −(e + 2x'c)/s; ẋ = x'q̇, ẍ = x'q̈ + x''q̇². B, the ram
/// and its points move by ẋ u_g; the block turns at q̇ about B. The crank's and the
/// block's offsets are stored in the slot's frame (u, n), absolute (u is a unit vector:
/// one `sin_cos` gives the whole pose). `None` where the slot is parallel to the guide.
#[derive(Clone, Copy, Debug)]
pub struct SlottedCrankRamHand {
    o2: V2,
    /// θ₂ in the drawing (the block's zero: it turns with the crank).
    theta2_ref: f64,
    /// β₀ = the slot's direction from u_g, less θ₂, in the drawing (rad).
    beta0: f64,
    /// The guide's unit direction u_g and its normal n_g.
    ug: V2,
    ng: V2,
    /// h = (B₀ − O2)·n_g, e = (B₀ − O2)·n₀ (m).
    h: f64,
    e: f64,
    /// The crank's cg − O2 and E − O2 in the slot's frame (m).
    g2: (f64, f64),
    pe: (f64, f64),
    /// u from E − O2: u = c₀ (E − O2) + c₁ perp(E − O2).
    u_of_e: (f64, f64),
    /// The block's cg − B in the slot's frame (m).
    g3: (f64, f64),
    /// The ram's cg − B and P − B (constant: the ram translates), its angle atan2(P − B).
    rg4: V2,
    rp: V2,
    theta4: f64,
    /// Masses (kg) and inertias about the cgs (kg·m²).
    m2: f64,
    m3: f64,
    m4: f64,
    i2: f64,
    i3: f64,
    /// I_O2 + I₃ = I₂ + m₂|G₂ − O2|² + I₃: what turns at q̇ about a fixed point or its own
    /// cg (kg·m²).
    io2_i3: f64,
    /// Weights m_k·g (N).
    w2: V2,
    w3: V2,
    w4: V2,
}

/// Result of [`SlottedCrankRamHand::pose`].
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct SlottedCrankRamHandPose {
    /// Crank: θ₂ = q (not wrapped), cg.
    pub crank: HandLinkPose,
    /// Block: its rotation since the drawing (the crank's), q − θ₂(drawing), cg.
    pub block: HandLinkPose,
    /// Ram: θ = atan2(P − B) (constant), cg.
    pub ram: HandLinkPose,
    /// O2 (fixed), E, B, P (m).
    pub o2: V2,
    pub e: V2,
    pub b: V2,
    pub p: V2,
}

/// Result of [`SlottedCrankRamHand::kinematics`].
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct SlottedCrankRamHandMotion {
    /// Crank: θ₂ = q, ω₂ = q̇, α₂ = q̈, its cg.
    pub crank: HandLinkMotion,
    /// Block: the crank's rotation since the drawing, ω₂, α₂, its cg.
    pub block: HandLinkMotion,
    /// Ram: its constant angle, ω = α = 0, its cg.
    pub ram: HandLinkMotion,
    /// O2 (fixed), E, B, P.
    pub o2: HandPointMotion,
    pub e: HandPointMotion,
    pub b: HandPointMotion,
    pub p: HandPointMotion,
}

/// Result of [`SlottedCrankRamHand::kinetostatics`]: the driver torque (N·m) and the
/// reactions, each BY the joint's first link ON its second (N, N·m).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct SlottedCrankRamHandForces {
    /// Motor torque on the crank.
    pub driver: f64,
    /// R_O2: ground on crank.
    pub o2: V2,
    /// Slot: crank on block, its force (normal to the slot) and moment about B.
    pub slot: V2,
    pub slot_moment: f64,
    /// R_B: block on ram.
    pub b: V2,
    /// Guide: ground on ram, its force (normal to u_g) and moment about B.
    pub guide: V2,
    pub guide_moment: f64,
}

/// The slot's frame and the ram's travel at one crank angle.
#[derive(Clone, Copy, Debug)]
struct Slide {
    /// sin β, cos β, u.
    s: f64,
    c: f64,
    u: V2,
    /// x, B = O2 + h n_g + x u_g.
    x: f64,
}

impl SlottedCrankRamHand {
    /// Precompute the drawing's constants from `p`.
    pub fn new(p: &SlottedCrankRamParams) -> Self {
        let (o2, e, b, pp) = (p.points.O2, p.points.E, p.points.B, p.points.P);
        let (crank, block, ram) = (&p.links.crank, &p.links.block, &p.links.ram);
        let u0 = p.axes.slot.normalize();
        let ug = p.axes.guide.normalize();
        let frame = |v: V2| (u0.dot(&v), cross(u0, v));
        let theta2_ref = (e.y - o2.y).atan2(e.x - o2.x);
        let pe = frame(e - o2);
        let pesq = pe.0 * pe.0 + pe.1 * pe.1;
        SlottedCrankRamHand {
            o2,
            theta2_ref,
            beta0: cross(ug, u0).atan2(ug.dot(&u0)) - theta2_ref,
            ug,
            ng: perp(ug),
            h: cross(ug, b - o2),
            e: cross(u0, b - o2),
            g2: frame(crank.cg - o2),
            pe,
            u_of_e: (pe.0 / pesq, -pe.1 / pesq),
            g3: frame(block.cg - b),
            rg4: ram.cg - b,
            rp: pp - b,
            theta4: (pp.y - b.y).atan2(pp.x - b.x),
            m2: crank.mass,
            m3: block.mass,
            m4: ram.mass,
            i2: crank.inertia,
            i3: block.inertia,
            io2_i3: crank.inertia + crank.mass * (crank.cg - o2).norm_squared() + block.inertia,
            w2: p.gravity * crank.mass,
            w3: p.gravity * block.mass,
            w4: p.gravity * ram.mass,
        }
    }

    /// β = q + β₀, the slot's u and the ram's x (see the type's docs); `None` where the
    /// slot is parallel to the guide.
    #[inline(always)]
    fn slide(&self, q: f64) -> Option<Slide> {
        let (s, c) = (q + self.beta0).sin_cos();
        if s == 0.0 {
            return None;
        }
        Some(Slide {
            s,
            c,
            u: self.ug * c + self.ng * s,
            x: (self.h * c - self.e) / s,
        })
    }

    /// x' = −(h s + x c)/s and x'' = −(e + 2x'c)/s.
    #[inline(always)]
    fn rates(&self, k: &Slide) -> (f64, f64) {
        let inv_s = 1.0 / k.s;
        let xd = -(self.h * k.s + k.x * k.c) * inv_s;
        (xd, -(self.e + 2.0 * xd * k.c) * inv_s)
    }

    /// B = O2 + h n_g + x u_g.
    #[inline(always)]
    fn pin(&self, x: f64) -> V2 {
        self.o2 + self.ng * self.h + self.ug * x
    }

    /// Position analysis: θ₂ = q, the block's rotation, the ram's constant angle, the cgs,
    /// E, B, P.
    #[inline(never)]
    pub fn pose(&self, q: f64) -> Option<SlottedCrankRamHandPose> {
        let k = self.slide(q)?;
        let b = self.pin(k.x);
        Some(SlottedCrankRamHandPose {
            crank: HandLinkPose {
                angle: q,
                cg: at(self.o2, k.u, self.g2),
            },
            block: HandLinkPose {
                angle: q - self.theta2_ref,
                cg: at(b, k.u, self.g3),
            },
            ram: HandLinkPose {
                angle: self.theta4,
                cg: b + self.rg4,
            },
            o2: self.o2,
            e: at(self.o2, k.u, self.pe),
            b,
            p: b + self.rp,
        })
    }

    /// Position, velocity and acceleration analysis at (q, q̇, q̈) (see the type's docs).
    #[inline(never)]
    pub fn kinematics(&self, q: f64, qd: f64, qdd: f64) -> Option<SlottedCrankRamHandMotion> {
        let k = self.slide(q)?;
        let (xd, xdd) = self.rates(&k);
        let (w, al) = (qd, qdd);
        let b = self.pin(k.x);
        let vb = self.ug * (xd * w);
        let ab = self.ug * (xd * al + xdd * w * w);
        let ram = |pos| HandPointMotion {
            pos,
            vel: vb,
            acc: ab,
        };
        let about_o2 = |r: V2| HandPointMotion {
            pos: self.o2 + r,
            vel: perp(r) * w,
            acc: perp(r) * al - r * (w * w),
        };
        let r2 = about_o2(at(V2::zeros(), k.u, self.g2));
        let r = at(V2::zeros(), k.u, self.g3);
        Some(SlottedCrankRamHandMotion {
            crank: HandLinkMotion {
                angle: q,
                omega: w,
                alpha: al,
                cg: r2.pos,
                cg_vel: r2.vel,
                cg_acc: r2.acc,
            },
            block: HandLinkMotion {
                angle: q - self.theta2_ref,
                omega: w,
                alpha: al,
                cg: b + r,
                cg_vel: vb + perp(r) * w,
                cg_acc: ab + perp(r) * al - r * (w * w),
            },
            ram: HandLinkMotion {
                angle: self.theta4,
                omega: 0.0,
                alpha: 0.0,
                cg: b + self.rg4,
                cg_vel: vb,
                cg_acc: ab,
            },
            o2: HandPointMotion {
                pos: self.o2,
                vel: V2::zeros(),
                acc: V2::zeros(),
            },
            e: about_o2(at(V2::zeros(), k.u, self.pe)),
            b: ram(b),
            p: ram(b + self.rp),
        })
    }

    /// Kinetostatics by d'Alembert, the ram and the block together, then each, then the
    /// crank.
    ///
    /// Per link k: F_k = m_k g − m_k a_Gk. The block and the ram together carry
    /// W = F₃ + F₄ + F_push, the slot's N n (by the crank) and the guide's force, normal to
    /// u_g: along u_g, N n·u_g = −N s, so N = W·u_g/s (u and s from E − O2:
    /// u = c₀(E − O2) + c₁ perp(E − O2), s = u_g × u). Then R_B = N n + F₃ (the block's
    /// forces), the guide's force −(N n + W) (the ram's), the ram's moments about B
    /// M_g = −(G₄ − B) × F₄ − (P − B) × F_push, the block's
    /// M_s = I₃α₂ − T_resist − (G₃ − B) × F₃, and the crank's about O2, with
    /// (B − O2) × N n = N t (t = (B − O2)·u): T = N t + M_s − M₂,
    /// M₂ = (G₂ − O2) × F₂ − I₂α₂; R_O2 = N n − F₂.
    #[inline(never)]
    pub fn kinetostatics(
        &self,
        m: &SlottedCrankRamHandMotion,
        loads: &SlottedCrankRamLoads,
    ) -> SlottedCrankRamHandForces {
        let u = at(V2::zeros(), m.e.pos - self.o2, self.u_of_e);
        let b = m.b.pos;
        let f2 = self.w2 - m.crank.cg_acc * self.m2;
        let f3 = self.w3 - m.block.cg_acc * self.m3;
        let f4 = self.w4 - m.b.acc * self.m4;
        let w = f3 + f4 + loads.push;
        let big_n = w.dot(&self.ug) / cross(self.ug, u);
        let slot = perp(u) * big_n;
        let slot_moment = self.i3 * m.block.alpha - loads.resist - cross(m.block.cg - b, f3);
        let m2 = cross(m.crank.cg - self.o2, f2) - self.i2 * m.crank.alpha;
        SlottedCrankRamHandForces {
            driver: big_n * u.dot(&(b - self.o2)) + slot_moment - m2,
            o2: slot - f2,
            slot,
            slot_moment,
            b: slot + f3,
            guide: -(slot + w),
            guide_moment: -cross(self.rg4, f4) - cross(self.rp, loads.push),
        }
    }

    /// The driver torque by virtual power, no reaction computed:
    /// T ω₂ + Σ_k [F_k·v_Gk − I_k α_k ω_k] + T_resist ω₂ + F_push·v_B = 0 (q̇ ≠ 0; the
    /// ram's points all move at v_B).
    #[inline(never)]
    pub fn driver_action(
        &self,
        m: &SlottedCrankRamHandMotion,
        loads: &SlottedCrankRamLoads,
    ) -> f64 {
        let w = m.crank.omega;
        let p2 = (self.w2 - m.crank.cg_acc * self.m2).dot(&m.crank.cg_vel);
        let p3 = (self.w3 - m.block.cg_acc * self.m3).dot(&m.block.cg_vel);
        let p4 = (self.w4 - m.b.acc * self.m4 + loads.push).dot(&m.b.vel);
        let turning = (loads.resist - (self.i2 + self.i3) * m.crank.alpha) * w;
        -(p2 + p3 + p4 + turning) / w
    }

    /// The velocity coefficients at q (per unit q̇): x', x'' and the block's cg, at r₃ from
    /// B, g_G3 = x' u_g + perp(r₃), g'_G3 = x'' u_g − r₃. Returns (x', x'', g_G3, g'_G3, u).
    #[inline(always)]
    fn coefficients(&self, q: f64) -> Option<(f64, f64, V2, V2, V2)> {
        let k = self.slide(q)?;
        let (xd, xdd) = self.rates(&k);
        let r3 = at(V2::zeros(), k.u, self.g3);
        Some((xd, xdd, self.ug * xd + perp(r3), self.ug * xdd - r3, k.u))
    }

    /// Zhukovski's I* = I_O2 + I₃ + m₃|g_G3|² + m₄x'² and
    /// dI*/dq = 2 (m₃ g_G3·g'_G3 + m₄x'x''); `None` where the slot is parallel to the guide.
    #[inline(never)]
    pub fn reduced(&self, q: f64) -> Option<HandReduced> {
        let (xd, xdd, g3, g3d, _) = self.coefficients(q)?;
        Some(HandReduced {
            inertia: self.io2_i3 + self.m3 * g3.norm_squared() + self.m4 * xd * xd,
            inertia_derivative: 2.0 * (self.m3 * g3.dot(&g3d) + self.m4 * xd * xdd),
        })
    }

    /// M* = (G₂ − O2) × m₂g + m₃g·g_G3 + (m₄g + F_push)·u_g x' + T_resist.
    #[inline(always)]
    fn moment_of(&self, xd: f64, g3: V2, u: V2, loads: &SlottedCrankRamLoads) -> f64 {
        cross(at(V2::zeros(), u, self.g2), self.w2)
            + self.w3.dot(&g3)
            + (self.w4 + loads.push).dot(&self.ug) * xd
            + loads.resist
    }

    /// Zhukovski's reduced moment M*(q) of the loads and gravity (N·m).
    #[inline(never)]
    pub fn reduced_moment(&self, q: f64, loads: &SlottedCrankRamLoads) -> Option<f64> {
        let (xd, _, g3, _, u) = self.coefficients(q)?;
        Some(self.moment_of(xd, g3, u, loads))
    }

    /// The direct problem: q̈ = (T + M* − ½ dI*/dq q̇²)/I*.
    #[inline(never)]
    pub fn acceleration(
        &self,
        q: f64,
        qd: f64,
        driver: f64,
        loads: &SlottedCrankRamLoads,
    ) -> Option<f64> {
        let (xd, xdd, g3, g3d, u) = self.coefficients(q)?;
        let inertia = self.io2_i3 + self.m3 * g3.norm_squared() + self.m4 * xd * xd;
        let half_derivative = self.m3 * g3.dot(&g3d) + self.m4 * xd * xdd;
        Some((driver + self.moment_of(xd, g3, u, loads) - half_derivative * qd * qd) / inertia)
    }
}
