//! Hand-written closed forms of the `Planetary` of `benches/floor/machines.rs` (a module
//! of `hand.rs`, whose conventions it keeps): Willis' relations of the sun–planet and
//! planet–ring meshes solved once, on paper, for the arm's and the planet's ratios.

use super::*;

/// The sun's pitch radius r_s (m), as declared in `Planetary`'s `sp` (the radii are not
/// among the generated parameters; `tests/floor.rs` checks these constants against the
/// loaded model).
pub const PLANETARY_SUN_RADIUS: f64 = 0.020;
/// The planet's pitch radius r_p (m), as declared in `sp` and `pr`.
pub const PLANETARY_PLANET_RADIUS: f64 = 0.025;
/// The ring's pitch radius r_r (m), as declared in `pr` (internal teeth).
pub const PLANETARY_RING_RADIUS: f64 = 0.070;
/// The sun–planet mesh's pressure angle α₁ (rad): the default 20°.
pub const PLANETARY_SUN_PRESSURE_ANGLE: f64 = 20.0 * std::f64::consts::PI / 180.0;
/// The planet–ring mesh's pressure angle α₂ (rad), as declared (25°).
pub const PLANETARY_RING_PRESSURE_ANGLE: f64 = 25.0 * std::f64::consts::PI / 180.0;

/// The planetary reducer: the sun 1 (the input, q its rotation since the drawing) turns
/// about O; the arm 2 turns about O and carries the planet 3 at P (ρ = P − O, |ρ| = L =
/// r_s + r_p); the planet meshes with the sun outside and with the fixed ring (the ground,
/// centre O) inside.
///
/// **Willis** (`docs/conventions.md#gears`, both meshes carried by the arm, φ the rotations
/// since the drawing): r_s (φ₁ − φ₂) + r_p (φ₃ − φ₂) = 0 and r_p (φ₃ − φ₂) − r_r (0 − φ₂)
/// = 0, so φ₂ = c q with c = r_s/(r_s + r_r) and φ₃ = k q with k = c (1 − r_r/r_p); every
/// rate and acceleration is the input's times c or k.
///
/// **The meshes** (e = ρ/L, t = perp(e)): the sun–planet pitch point is K₁ = O + r_s e, the
/// tooth force of the sun on the planet F_sp = f₁ t + |f₁| tan α₁ e; the planet–ring pitch
/// point is K₂ = O + r_r e, the tooth force of the planet on the ring
/// F_pr = −f₂ t + |f₂| tan α₂ e (the ring's tangent is perp(O − P) = −t, its radial part
/// outward).
#[derive(Clone, Copy, Debug)]
pub struct PlanetaryHand {
    o: V2,
    /// c and k, the arm's and the planet's speed ratios to the sun.
    c: f64,
    k: f64,
    /// θ₂₀, the arm's angle (O → P) in the drawing; L = |P − O|.
    theta0: f64,
    l: f64,
    /// ρ in the drawing.
    rho0: V2,
    /// The sun's cg − O and the planet's cg − P in the drawing (they turn by q and k q).
    g1: V2,
    g3: V2,
    /// The arm's cg and its lever end T in the frame O→P scaled by 1/L.
    g2: (f64, f64),
    t: (f64, f64),
    /// S = m₂ (G₂ − O) + m₃ ρ in the frame O→P scaled by 1/L (kg): the first moment about O
    /// of the arm and of the planet's mass carried at P, which gravity's power needs.
    first2: (f64, f64),
    /// r_s, r_p; tan α₁, 1/cos α₁, tan α₂, 1/cos α₂.
    rs: f64,
    rp: f64,
    tan1: f64,
    sec1: f64,
    tan2: f64,
    sec2: f64,
    /// Masses (kg), inertias about the cgs (kg·m²).
    m1: f64,
    m2: f64,
    m3: f64,
    i1: f64,
    i2: f64,
    i3: f64,
    /// I* = j0 + ki (ρ·r₃) with r₃ the planet's cg − P, dI*/dq = kd (ρ × r₃) (see
    /// [`PlanetaryHand::reduced`]).
    j0: f64,
    ki: f64,
    kd: f64,
    /// Weights m·g (N), global; g itself.
    w1: V2,
    w2: V2,
    w3: V2,
    g: V2,
}

/// Result of [`PlanetaryHand::pose`].
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct PlanetaryHandPose {
    /// Sun: θ₁ = q (not wrapped), cg.
    pub sun: HandLinkPose,
    /// Arm: θ₂ = θ₂₀ + c q (not wrapped), cg.
    pub arm: HandLinkPose,
    /// Planet: θ₃ = k q (not wrapped), cg.
    pub planet: HandLinkPose,
    /// O (fixed), P, T (m).
    pub o: V2,
    pub p: V2,
    pub t: V2,
}

/// Result of [`PlanetaryHand::kinematics`].
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct PlanetaryHandMotion {
    /// Sun: θ₁ = q, ω₁ = q̇, α₁ = q̈, its cg.
    pub sun: HandLinkMotion,
    /// Arm: θ₂, ω₂ = c q̇, α₂ = c q̈, its cg.
    pub arm: HandLinkMotion,
    /// Planet: θ₃, ω₃ = k q̇, α₃ = k q̈, its cg.
    pub planet: HandLinkMotion,
    /// O (fixed), P, T.
    pub o: HandPointMotion,
    pub p: HandPointMotion,
    pub t: HandPointMotion,
}

/// Result of [`PlanetaryHand::kinetostatics`]: the driver torque (N·m, by the ground on
/// the sun) and the reactions, each BY the joint's first link ON its second (N).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct PlanetaryHandForces {
    /// Motor torque on the sun.
    pub driver: f64,
    /// R_S: ground on sun; R_O: ground on arm; R_P: arm on planet.
    pub s: V2,
    pub o: V2,
    pub p: V2,
    /// The sun's tooth force on the planet at K₁, its magnitude and flank (+1 along t).
    pub sp: V2,
    pub sp_load: f64,
    pub sp_flank: f64,
    /// The planet's tooth force on the ring at K₂, its magnitude and flank (+1 along −t).
    pub pr: V2,
    pub pr_load: f64,
    pub pr_flank: f64,
}

impl PlanetaryHand {
    /// Precompute the drawing's constants from `p` and the meshes' radii and pressure
    /// angles (`PLANETARY_*`).
    pub fn new(p: &PlanetaryParams) -> Self {
        let (o, pp, t) = (p.points.O, p.points.P, p.points.T);
        let l = &p.links;
        let (rs, rp, rr) = (
            PLANETARY_SUN_RADIUS,
            PLANETARY_PLANET_RADIUS,
            PLANETARY_RING_RADIUS,
        );
        let c = rs / (rs + rr);
        let k = c * (1.0 - rr / rp);
        let rho = pp - o;
        let g3 = l.planet.cg - pp;
        let io1 = l.sun.inertia + l.sun.mass * (l.sun.cg - o).norm_squared();
        let io2 = l.arm.inertia + l.arm.mass * (l.arm.cg - o).norm_squared();
        let ki = 2.0 * l.planet.mass * c * k;
        PlanetaryHand {
            o,
            c,
            k,
            theta0: rho.y.atan2(rho.x),
            l: rho.norm(),
            rho0: rho,
            g1: l.sun.cg - o,
            g3,
            g2: local_scaled(o, pp, l.arm.cg),
            t: local_scaled(o, pp, t),
            first2: local_scaled(o, pp, o + (l.arm.cg - o) * l.arm.mass + rho * l.planet.mass),
            rs,
            rp,
            tan1: PLANETARY_SUN_PRESSURE_ANGLE.tan(),
            sec1: 1.0 / PLANETARY_SUN_PRESSURE_ANGLE.cos(),
            tan2: PLANETARY_RING_PRESSURE_ANGLE.tan(),
            sec2: 1.0 / PLANETARY_RING_PRESSURE_ANGLE.cos(),
            m1: l.sun.mass,
            m2: l.arm.mass,
            m3: l.planet.mass,
            i1: l.sun.inertia,
            i2: l.arm.inertia,
            i3: l.planet.inertia,
            j0: io1
                + c * c * io2
                + k * k * (l.planet.inertia + l.planet.mass * g3.norm_squared())
                + l.planet.mass * c * c * rho.norm_squared(),
            ki,
            kd: ki * (c - k),
            w1: p.gravity * l.sun.mass,
            w2: p.gravity * l.arm.mass,
            w3: p.gravity * l.planet.mass,
            g: p.gravity,
        }
    }

    /// ρ = P − O at q: L (cos θ₂, sin θ₂), θ₂ = θ₂₀ + c q.
    #[inline(always)]
    fn rho(&self, q: f64) -> (f64, V2) {
        let theta = self.theta0 + self.c * q;
        (theta, turn(theta) * self.l)
    }

    /// Position analysis: every angle a multiple of q, the cgs, P and T.
    #[inline(never)]
    pub fn pose(&self, q: f64) -> Option<PlanetaryHandPose> {
        let (theta, rho) = self.rho(q);
        let p = self.o + rho;
        let phi = self.k * q;
        Some(PlanetaryHandPose {
            sun: HandLinkPose {
                angle: q,
                cg: self.o + rotate(turn(q), self.g1),
            },
            arm: HandLinkPose {
                angle: theta,
                cg: at(self.o, rho, self.g2),
            },
            planet: HandLinkPose {
                angle: phi,
                cg: p + rotate(turn(phi), self.g3),
            },
            o: self.o,
            p,
            t: at(self.o, rho, self.t),
        })
    }

    /// Position, velocity and acceleration analysis at (q, q̇, q̈) (see the type's docs).
    #[inline(never)]
    pub fn kinematics(&self, q: f64, qd: f64, qdd: f64) -> Option<PlanetaryHandMotion> {
        let (theta, rho) = self.rho(q);
        let phi = self.k * q;
        let (w2, a2) = (self.c * qd, self.c * qdd);
        let (w3, a3) = (self.k * qd, self.k * qdd);
        let about_o = |r: V2, w: f64, a: f64| HandPointMotion {
            pos: self.o + r,
            vel: perp(r) * w,
            acc: perp(r) * a - r * (w * w),
        };
        let r1 = rotate(turn(q), self.g1);
        let p = about_o(rho, w2, a2);
        let r3 = rotate(turn(phi), self.g3);
        let g2 = about_o(at(V2::zeros(), rho, self.g2), w2, a2);
        let link = |angle, omega, alpha, m: HandPointMotion| HandLinkMotion {
            angle,
            omega,
            alpha,
            cg: m.pos,
            cg_vel: m.vel,
            cg_acc: m.acc,
        };
        Some(PlanetaryHandMotion {
            sun: link(q, qd, qdd, about_o(r1, qd, qdd)),
            arm: link(theta, w2, a2, g2),
            planet: HandLinkMotion {
                angle: phi,
                omega: w3,
                alpha: a3,
                cg: p.pos + r3,
                cg_vel: p.vel + perp(r3) * w3,
                cg_acc: p.acc + perp(r3) * a3 - r3 * (w3 * w3),
            },
            o: HandPointMotion {
                pos: self.o,
                vel: V2::zeros(),
                acc: V2::zeros(),
            },
            p,
            t: about_o(at(V2::zeros(), rho, self.t), w2, a2),
        })
    }

    /// Kinetostatics by d'Alembert, the planet and the arm together, then the sun.
    ///
    /// With F_k = m_k g − m_k a_Gk and the tooth forces F_sp = f₁ t + …, F_pr = −f₂ t + …
    /// (the type's docs): the planet's moments about P give r_p (f₂ − f₁) + M₃ = 0,
    /// M₃ = (G₃ − P) × F₃ − I₃α₃; the arm's about O, with the planet's pin load
    /// −R_P = F_sp − F_pr + F₃, give L (f₁ + f₂) + ρ × F₃ + M₂ = 0,
    /// M₂ = (G₂ − O) × F₂ − I₂α₂ + (T − O) × F_pull + T_brake. So
    /// f₁ = ½ (M₃/r_p − (M₂ + ρ × F₃)/L), f₂ = f₁ − M₃/r_p; R_P = F_pr − F_sp − F₃,
    /// R_O = R_P − F₂ − F_pull; the sun's about O: T = r_s f₁ − M₁,
    /// M₁ = (G₁ − O) × F₁ − I₁α₁, and R_S = F_sp − F₁.
    #[inline(never)]
    pub fn kinetostatics(
        &self,
        m: &PlanetaryHandMotion,
        loads: &PlanetaryLoads,
    ) -> PlanetaryHandForces {
        let rho = m.p.pos - self.o;
        let inv_l = 1.0 / self.l;
        let e = rho * inv_l;
        let t = perp(e);
        let f1 = self.w1 - m.sun.cg_acc * self.m1;
        let f2 = self.w2 - m.arm.cg_acc * self.m2;
        let f3 = self.w3 - m.planet.cg_acc * self.m3;
        let m3 = cross(m.planet.cg - m.p.pos, f3) - self.i3 * m.planet.alpha;
        let m2 = cross(m.arm.cg - self.o, f2) - self.i2 * m.arm.alpha
            + cross(m.t.pos - self.o, loads.pull)
            + loads.brake;
        let m3_rp = m3 / self.rp;
        let ft1 = 0.5 * (m3_rp - (m2 + cross(rho, f3)) * inv_l);
        let ft2 = ft1 - m3_rp;
        let sp = t * ft1 + e * (ft1.abs() * self.tan1);
        let pr = e * (ft2.abs() * self.tan2) - t * ft2;
        let rp = pr - sp - f3;
        let sign = |f: f64| if f >= 0.0 { 1.0 } else { -1.0 };
        PlanetaryHandForces {
            driver: self.rs * ft1 - cross(m.sun.cg - self.o, f1) + self.i1 * m.sun.alpha,
            s: sp - f1,
            o: rp - f2 - loads.pull,
            p: rp,
            sp,
            sp_load: ft1.abs() * self.sec1,
            sp_flank: sign(ft1),
            pr,
            pr_load: ft2.abs() * self.sec2,
            pr_flank: sign(ft2),
        }
    }

    /// The driver torque by virtual power, no reaction computed:
    /// T q̇ + Σ_k [F_k·v_Gk − I_k α_k ω_k] + F_pull·v_T + T_brake ω₂ = 0 (q̇ ≠ 0; the
    /// ring does not move, the tooth forces do no work).
    #[inline(never)]
    pub fn driver_action(&self, m: &PlanetaryHandMotion, loads: &PlanetaryLoads) -> f64 {
        let p1 = (self.w1 - m.sun.cg_acc * self.m1).dot(&m.sun.cg_vel)
            - self.i1 * m.sun.alpha * m.sun.omega;
        let p2 = (self.w2 - m.arm.cg_acc * self.m2).dot(&m.arm.cg_vel)
            + (loads.brake - self.i2 * m.arm.alpha) * m.arm.omega
            + loads.pull.dot(&m.t.vel);
        let p3 = (self.w3 - m.planet.cg_acc * self.m3).dot(&m.planet.cg_vel)
            - self.i3 * m.planet.alpha * m.planet.omega;
        -(p1 + p2 + p3) / m.sun.omega
    }

    /// Zhukovski's I* = I_O1 + c² I_O2 + k² (I₃ + m₃|r₃|²) + m₃ c² L² + 2 m₃ c k (ρ·r₃)
    /// (the planet's cg moves at c perp(ρ) + k perp(r₃) per unit q̇, r₃ = G₃ − P), and
    /// dI*/dq = 2 m₃ c k (c − k)(ρ × r₃): ρ·r₃ and ρ × r₃ depend on q only through the
    /// planet's turn relative to the arm, δ = (k − c) q, one `sin_cos`.
    #[inline(never)]
    pub fn reduced(&self, q: f64) -> Option<HandReduced> {
        let r = rotate(turn((self.k - self.c) * q), self.g3);
        Some(HandReduced {
            inertia: self.j0 + self.ki * self.rho0.dot(&r),
            inertia_derivative: self.kd * cross(self.rho0, r),
        })
    }

    /// M* = r₁ × m₁g + c [S × g + r_T × F_pull + T_brake] + k r₃ × m₃g, with r₁ = G₁ − O,
    /// S = m₂ (G₂ − O) + m₃ ρ the first moment about O of the arm and the planet's mass
    /// carried at P, r_T = T − O and r₃ = G₃ − P at q.
    #[inline(always)]
    fn moment_of(&self, q: f64, rho: V2, r3: V2, loads: &PlanetaryLoads) -> f64 {
        let r1 = rotate(turn(q), self.g1);
        let arm = cross(at(V2::zeros(), rho, self.first2), self.g)
            + cross(at(V2::zeros(), rho, self.t), loads.pull)
            + loads.brake;
        cross(r1, self.w1) + self.c * arm + self.k * cross(r3, self.w3)
    }

    /// Zhukovski's reduced moment M*(q) of the loads and gravity (N·m).
    #[inline(never)]
    pub fn reduced_moment(&self, q: f64, loads: &PlanetaryLoads) -> Option<f64> {
        let (_, rho) = self.rho(q);
        let r3 = rotate(turn(self.k * q), self.g3);
        Some(self.moment_of(q, rho, r3, loads))
    }

    /// The direct problem: q̈ = (T + M* − ½ dI*/dq q̇²)/I*, ρ and r₃ turned once for both.
    #[inline(never)]
    pub fn acceleration(
        &self,
        q: f64,
        qd: f64,
        driver: f64,
        loads: &PlanetaryLoads,
    ) -> Option<f64> {
        let (_, rho) = self.rho(q);
        let r3 = rotate(turn(self.k * q), self.g3);
        let inertia = self.j0 + self.ki * rho.dot(&r3);
        let half_derivative = 0.5 * self.kd * cross(rho, r3);
        Some((driver + self.moment_of(q, rho, r3, loads) - half_derivative * qd * qd) / inertia)
    }
}
