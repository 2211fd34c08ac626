//! Hand-written closed forms of the `ScotchYoke` of `tests/common/mechanisms.rs` (a module
//! of `hand.rs`, whose conventions it keeps).

use super::*;

/// The Scotch yoke: the crank O2–A runs its pin A in the slot of the yoke 5, which slides
/// on the ground along the guide u_g (at Y) and does not turn (a one-link group: guide
/// and pin in slot).
///
/// The yoke's travel x since the drawing: A = A₀ + x u_g + t u_s (u_s the slot, fixed in
/// the yoke) dotted with the slot's normal n_s gives x = k·(A − A₀), k = n_s/(n_s·u_g),
/// so x = k·a₂ − x₀ (a₂ = A − O2, x₀ = k·(A₀ − O2)), ẋ = k·v_A, ẍ = k·a_A: the yoke
/// moves by x u_g, every point of it alike.
#[derive(Clone, Copy, Debug)]
pub struct ScotchYokeHand {
    o2: V2,
    /// r₂, crank length (m).
    r2: f64,
    /// The guide's unit direction u_g and the slot's unit normal n_s.
    ug: V2,
    ns: V2,
    /// k = n_s/(n_s·u_g) and x₀ = k·(A₀ − O2).
    k: V2,
    x0: f64,
    /// u_g/(n_s·u_g): the slot force's magnitude S from the yoke's load W, S = W·that.
    kg: V2,
    /// Y and the yoke's cg in the drawing (m).
    y0: V2,
    g5: V2,
    /// G₅ − Y (constant: the yoke translates).
    ry: V2,
    /// cg of the crank in its frame O2→A, scaled by 1/r₂.
    g2: (f64, f64),
    /// Crank mass and inertia, I_O2 = I₂ + m₂|G₂ − O2|², yoke mass.
    m2: f64,
    i2: f64,
    io2: f64,
    m5: f64,
    /// Weights m·g (N).
    w2: V2,
    w5: V2,
}

/// Result of [`ScotchYokeHand::pose`].
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct ScotchYokeHandPose {
    /// Crank: θ₂ = q (not wrapped), cg.
    pub crank: HandLinkPose,
    /// Yoke: θ = 0 (it does not turn), cg.
    pub yoke: HandLinkPose,
    /// O2 (fixed), A, Y (m).
    pub o2: V2,
    pub a: V2,
    pub y: V2,
}

/// Result of [`ScotchYokeHand::kinematics`].
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct ScotchYokeHandMotion {
    /// Crank: θ₂ = q, ω₂ = q̇, α₂ = q̈, its cg.
    pub crank: HandLinkMotion,
    /// Yoke: θ = ω = α = 0, its cg.
    pub yoke: HandLinkMotion,
    /// O2 (fixed), A, Y.
    pub o2: HandPointMotion,
    pub a: HandPointMotion,
    pub y: HandPointMotion,
}

/// Result of [`ScotchYokeHand::kinetostatics`]: the driver torque (N·m) and the
/// reactions, each BY the joint's first link ON its second (N, N·m).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct ScotchYokeHandForces {
    /// Motor torque on the crank.
    pub driver: f64,
    /// R_O2: ground on crank.
    pub o2: V2,
    /// Guide: ground on yoke, its force (normal to u_g) and moment about Y.
    pub guide: V2,
    pub guide_moment: f64,
    /// Slot: yoke on crank, normal to the slot, at A.
    pub slot: V2,
}

impl ScotchYokeHand {
    /// Precompute the drawing's constants from `p`.
    pub fn new(p: &ScotchYokeParams) -> Self {
        let (o2, a, y) = (p.points.O2, p.points.A, p.points.Y);
        let (crank, yoke) = (&p.links.crank, &p.links.yoke);
        let ug = p.axes.guide.normalize();
        let ns = perp(p.axes.slot.normalize());
        let k = ns / ns.dot(&ug);
        ScotchYokeHand {
            o2,
            r2: (a - o2).norm(),
            ug,
            ns,
            k,
            x0: k.dot(&(a - o2)),
            kg: ug / ns.dot(&ug),
            y0: y,
            g5: yoke.cg,
            ry: yoke.cg - y,
            g2: local_scaled(o2, a, crank.cg),
            m2: crank.mass,
            i2: crank.inertia,
            io2: crank.inertia + crank.mass * (crank.cg - o2).norm_squared(),
            m5: yoke.mass,
            w2: p.gravity * crank.mass,
            w5: p.gravity * yoke.mass,
        }
    }

    /// a₂ = A − O2 = r₂(cos q, sin q).
    #[inline(always)]
    fn crank(&self, q: f64) -> V2 {
        let (sn, cs) = q.sin_cos();
        V2::new(self.r2 * cs, self.r2 * sn)
    }

    /// Position analysis: θ₂ = q, the yoke's travel x = k·a₂ − x₀, the cgs, A and Y.
    /// (`Option` as the other machines; a Scotch yoke always assembles.)
    #[inline(never)]
    pub fn pose(&self, q: f64) -> Option<ScotchYokeHandPose> {
        let a2 = self.crank(q);
        let x = self.k.dot(&a2) - self.x0;
        Some(ScotchYokeHandPose {
            crank: HandLinkPose {
                angle: q,
                cg: at(self.o2, a2, self.g2),
            },
            yoke: HandLinkPose {
                angle: 0.0,
                cg: self.g5 + self.ug * x,
            },
            o2: self.o2,
            a: self.o2 + a2,
            y: self.y0 + self.ug * x,
        })
    }

    /// Position, velocity and acceleration analysis at (q, q̇, q̈) (see the type's docs).
    #[inline(never)]
    pub fn kinematics(&self, q: f64, qd: f64, qdd: f64) -> Option<ScotchYokeHandMotion> {
        let a2 = self.crank(q);
        let (w2, al2) = (qd, qdd);
        let va = perp(a2) * w2;
        let aa = perp(a2) * al2 - a2 * (w2 * w2);
        let x = self.k.dot(&a2) - self.x0;
        let v = self.ug * self.k.dot(&va);
        let acc = self.ug * self.k.dot(&aa);
        let r = at(V2::zeros(), a2, self.g2);
        Some(ScotchYokeHandMotion {
            crank: HandLinkMotion {
                angle: q,
                omega: w2,
                alpha: al2,
                cg: self.o2 + r,
                cg_vel: perp(r) * w2,
                cg_acc: perp(r) * al2 - r * (w2 * w2),
            },
            yoke: HandLinkMotion {
                angle: 0.0,
                omega: 0.0,
                alpha: 0.0,
                cg: self.g5 + self.ug * x,
                cg_vel: v,
                cg_acc: acc,
            },
            o2: HandPointMotion {
                pos: self.o2,
                vel: V2::zeros(),
                acc: V2::zeros(),
            },
            a: HandPointMotion {
                pos: self.o2 + a2,
                vel: va,
                acc: aa,
            },
            y: HandPointMotion {
                pos: self.y0 + self.ug * x,
                vel: v,
                acc,
            },
        })
    }

    /// Kinetostatics by d'Alembert, the yoke first, then the crank.
    ///
    /// The yoke carries W = m₅g − m₅a_G5 + F_resist, the slot's force −S n_s (at A, by the
    /// crank) and the guide's N n_g and moment M_g (about Y). Along u_g: S = W·u_g/(n_s·u_g);
    /// then R_guide = S n_s − W, and the moments about Y,
    /// M_g = (A − Y) × S n_s − (G₅ − Y) × F₅ (F_resist acts at Y; the yoke does not turn).
    /// The crank: R_O2 = −S n_s − F₂ and T = −a₂ × S n_s − M₂ with
    /// M₂ = (G₂ − O2) × F₂ − I₂α₂ + T_drag.
    #[inline(never)]
    pub fn kinetostatics(
        &self,
        m: &ScotchYokeHandMotion,
        loads: &ScotchYokeLoads,
    ) -> ScotchYokeHandForces {
        let a2 = m.a.pos - self.o2;
        let f2 = self.w2 - m.crank.cg_acc * self.m2;
        let f5 = self.w5 - m.yoke.cg_acc * self.m5;
        let w = f5 + loads.resist;
        let slot = self.ns * self.kg.dot(&w);
        let m2 = cross(m.crank.cg - self.o2, f2) - self.i2 * m.crank.alpha + loads.drag;
        ScotchYokeHandForces {
            driver: -cross(a2, slot) - m2,
            o2: -slot - f2,
            guide: slot - w,
            guide_moment: cross(m.a.pos - m.y.pos, slot) - cross(self.ry, f5),
            slot,
        }
    }

    /// The driver torque by virtual power, no reaction computed:
    /// T ω₂ + F₂·v_G2 − I₂α₂ω₂ + (F₅ + F_resist)·v_Y + T_drag ω₂ = 0 (q̇ ≠ 0; the yoke's
    /// points all move at v_Y).
    #[inline(never)]
    pub fn driver_action(&self, m: &ScotchYokeHandMotion, loads: &ScotchYokeLoads) -> f64 {
        let p2 = (self.w2 - m.crank.cg_acc * self.m2).dot(&m.crank.cg_vel)
            - self.i2 * m.crank.alpha * m.crank.omega;
        let p5 = (self.w5 - m.yoke.cg_acc * self.m5 + loads.resist).dot(&m.y.vel);
        -(p2 + p5 + loads.drag * m.crank.omega) / m.crank.omega
    }

    /// Zhukovski's I* = I_O2 + m₅ x'², dI*/dq = 2 m₅ x' x'', with x' = k·perp(a₂),
    /// x'' = −k·a₂.
    #[inline(never)]
    pub fn reduced(&self, q: f64) -> Option<HandReduced> {
        let a2 = self.crank(q);
        let xd = self.k.dot(&perp(a2));
        let m5xd = self.m5 * xd;
        Some(HandReduced {
            inertia: self.io2 + m5xd * xd,
            inertia_derivative: -2.0 * m5xd * self.k.dot(&a2),
        })
    }

    /// M* = (G₂ − O2) × m₂g + (m₅g + F_resist)·u_g x' + T_drag.
    #[inline(always)]
    fn moment_of(&self, a2: V2, xd: f64, loads: &ScotchYokeLoads) -> f64 {
        cross(at(V2::zeros(), a2, self.g2), self.w2)
            + (self.w5 + loads.resist).dot(&self.ug) * xd
            + loads.drag
    }

    /// Zhukovski's reduced moment M*(q) of the loads and gravity (N·m).
    #[inline(never)]
    pub fn reduced_moment(&self, q: f64, loads: &ScotchYokeLoads) -> Option<f64> {
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
        loads: &ScotchYokeLoads,
    ) -> Option<f64> {
        let a2 = self.crank(q);
        let xd = self.k.dot(&perp(a2));
        let m5xd = self.m5 * xd;
        let inertia = self.io2 + m5xd * xd;
        let half_derivative = -m5xd * self.k.dot(&a2);
        Some((driver + self.moment_of(a2, xd, loads) - half_derivative * qd * qd) / inertia)
    }
}
