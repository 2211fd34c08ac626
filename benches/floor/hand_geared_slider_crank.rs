//! Hand-written closed forms of the `GearedSliderCrank` of `benches/floor/machines.rs` (a
//! module of `hand.rs`, whose conventions it keeps): Willis' relation for the gear pair,
//! then the offset slider-crank.

use super::*;

/// The pinion's pitch radius r_a (m), as declared in `GearedSliderCrank`'s `mesh` (the
/// radii are not among the generated parameters; `tests/floor.rs` checks these three
/// against the loaded model).
pub const GEARED_PINION_RADIUS: f64 = 0.025;
/// The gear's pitch radius r_b (m), as declared.
pub const GEARED_GEAR_RADIUS: f64 = 0.075;
/// The pressure angle α (rad), as declared (20°).
pub const GEARED_PRESSURE_ANGLE: f64 = 20.0 * std::f64::consts::PI / 180.0;

/// The geared slider-crank: the pinion 1 (the input, q its rotation since the drawing)
/// turns about O1 and meshes externally with the gear 2 about O2, which carries the crank
/// pin A; the rod 3 (A–B) drives the piston 4 along the guide u through B.
///
/// **Willis** (`docs/conventions.md#gears`, both centres on the ground):
/// r_a φ₁ + r_b φ₂ = 0, so the crank turns by φ₂ = −k q, k = r_a/r_b, ω₂ = −k q̇,
/// α₂ = −k q̈.
///
/// **The slider-crank**, in the guide's frame (u, n = perp(u)): with ψ the crank's angle
/// from u (ψ = ψ₀ − k q), a₂ = A − O2 has the coordinates x_A = r₂ cos ψ, y_A = r₂ sin ψ;
/// the rod d = B − A = X u + Y n with Y = e − y_A (e the guide's offset from O2 along n),
/// X = σ√(l² − Y²). y_A + Y = e differentiated: ω₃ = −(v_A·n)/X,
/// α₃ = (ω₃² Y − a_A·n)/X; v_B = v_A + ω₃ perp(d), a_B = a_A + α₃ perp(d) − ω₃² d.
///
/// **The mesh**: the pitch point P = O1 + r_a w (w the unit O1→O2) is fixed, the common
/// tangent t = perp(w); the tooth force of the pinion on the gear is
/// F_m = f_t t + |f_t| tan α w (its radial part pushes the gear away from the pinion).
#[derive(Clone, Copy, Debug)]
pub struct GearedSliderCrankHand {
    o1: V2,
    o2: V2,
    /// k = r_a/r_b, the speed ratio.
    k: f64,
    /// The guide's unit direction u, n = perp(u), and its angle θ_u.
    u: V2,
    n: V2,
    theta_u: f64,
    /// ψ₀, the crank's angle from u in the drawing.
    psi0: f64,
    /// r₂, crank length; l², rod length squared; e, the guide's offset from O2 along n.
    r2: f64,
    lsq: f64,
    e: f64,
    /// Branch: the sign of X = (B₀ − A₀)·u.
    sigma: f64,
    /// The pinion's cg − O1 in the drawing (it turns by q).
    g1: V2,
    /// Crank cg in the frame O2→A scaled by 1/r₂; rod cg in the frame A→B scaled by 1/l.
    g2: (f64, f64),
    g3: (f64, f64),
    /// The piston's cg − B (constant: the piston translates).
    g4: V2,
    /// The pitch point P, the tangent t, the separating direction w (on the gear).
    pitch: V2,
    t: V2,
    w: V2,
    /// r_a, r_b, tan α and 1/cos α (the tooth load |F_m| = |f_t|/cos α).
    ra: f64,
    rb: f64,
    tan_alpha: f64,
    sec_alpha: f64,
    /// Masses (kg) and inertias about the cgs (kg·m²).
    m1: f64,
    m2: f64,
    m3: f64,
    m4: f64,
    i1: f64,
    i2: f64,
    i3: f64,
    /// I_O1 = I₁ + m₁|G₁ − O1|², I_O2 = I₂ + m₂|G₂ − O2|² (kg·m²).
    io1: f64,
    io2: f64,
    /// Weights m·g (N), global.
    w1: V2,
    w2: V2,
    w3: V2,
    w4: V2,
}

/// Result of [`GearedSliderCrankHand::pose`].
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct GearedSliderCrankHandPose {
    /// Pinion: θ₁ = q (not wrapped), cg.
    pub pinion: HandLinkPose,
    /// Crank: θ₂ = θ_u + ψ (not wrapped), cg.
    pub crank: HandLinkPose,
    /// Rod: θ₃ = atan2(B − A), cg.
    pub rod: HandLinkPose,
    /// Piston: θ = 0 (it translates), cg.
    pub piston: HandLinkPose,
    /// O1, O2 (fixed), A, B (m).
    pub o1: V2,
    pub o2: V2,
    pub a: V2,
    pub b: V2,
}

/// Result of [`GearedSliderCrankHand::kinematics`].
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct GearedSliderCrankHandMotion {
    /// Pinion: θ₁ = q, ω₁ = q̇, α₁ = q̈, its cg.
    pub pinion: HandLinkMotion,
    /// Crank: θ₂, ω₂ = −k q̇, α₂ = −k q̈, its cg.
    pub crank: HandLinkMotion,
    /// Rod: θ₃, ω₃, α₃, its cg.
    pub rod: HandLinkMotion,
    /// Piston: θ = ω = α = 0, its cg.
    pub piston: HandLinkMotion,
    /// O1, O2 (fixed), A, B.
    pub o1: HandPointMotion,
    pub o2: HandPointMotion,
    pub a: HandPointMotion,
    pub b: HandPointMotion,
}

/// Result of [`GearedSliderCrankHand::kinetostatics`]: the driver torque (N·m, by the
/// ground on the pinion) and the reactions, each BY the joint's first link ON its second
/// (N, N·m).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct GearedSliderCrankHandForces {
    /// Motor torque on the pinion.
    pub driver: f64,
    /// R_O1: ground on pinion; R_O2: ground on crank.
    pub o1: V2,
    pub o2: V2,
    /// R_A: crank on rod; R_B: rod on piston.
    pub a: V2,
    pub b: V2,
    /// Guide: ground on piston, its force (normal to u) and moment about B.
    pub guide: V2,
    pub guide_moment: f64,
    /// Mesh: the tooth force of the pinion on the gear at P, its magnitude and flank
    /// (+1 when it pushes the gear along t).
    pub mesh: V2,
    pub tooth_load: f64,
    pub flank: f64,
}

/// The slider-crank's geometry of one q, in the guide's frame.
#[derive(Clone, Copy, Debug)]
struct Crank {
    /// ψ, the crank's angle from u; a₂'s coordinates (x_A, y_A).
    psi: f64,
    xa: f64,
    ya: f64,
    /// The rod's coordinates (X, Y) and 1/X.
    x: f64,
    y: f64,
    inv_x: f64,
}

impl GearedSliderCrankHand {
    /// Precompute the drawing's constants from `p` and the mesh's radii and pressure
    /// angle (`GEARED_*`).
    pub fn new(p: &GearedSliderCrankParams) -> Self {
        let (o1, o2, a, b) = (p.points.O1, p.points.O2, p.points.A, p.points.B);
        let l = &p.links;
        let u = p.axes.guide.normalize();
        let n = perp(u);
        let theta_u = u.y.atan2(u.x);
        let a2 = a - o2;
        let w = (o2 - o1).normalize();
        let (ra, rb) = (GEARED_PINION_RADIUS, GEARED_GEAR_RADIUS);
        GearedSliderCrankHand {
            o1,
            o2,
            k: ra / rb,
            u,
            n,
            theta_u,
            psi0: cross(u, a2).atan2(u.dot(&a2)),
            r2: a2.norm(),
            lsq: (b - a).norm_squared(),
            e: (b - o2).dot(&n),
            sigma: (b - a).dot(&u).signum(),
            g1: l.pinion.cg - o1,
            g2: local_scaled(o2, a, l.crank.cg),
            g3: local_scaled(a, b, l.rod.cg),
            g4: l.piston.cg - b,
            pitch: o1 + w * ra,
            t: perp(w),
            w,
            ra,
            rb,
            tan_alpha: GEARED_PRESSURE_ANGLE.tan(),
            sec_alpha: 1.0 / GEARED_PRESSURE_ANGLE.cos(),
            m1: l.pinion.mass,
            m2: l.crank.mass,
            m3: l.rod.mass,
            m4: l.piston.mass,
            i1: l.pinion.inertia,
            i2: l.crank.inertia,
            i3: l.rod.inertia,
            io1: l.pinion.inertia + l.pinion.mass * (l.pinion.cg - o1).norm_squared(),
            io2: l.crank.inertia + l.crank.mass * (l.crank.cg - o2).norm_squared(),
            w1: p.gravity * l.pinion.mass,
            w2: p.gravity * l.crank.mass,
            w3: p.gravity * l.rod.mass,
            w4: p.gravity * l.piston.mass,
        }
    }

    /// Willis then the slider-crank's position (see the type's docs); `None` when the rod
    /// cannot reach the guide (never for this drawing: r₂ + |e| < l).
    #[inline(always)]
    fn crank(&self, q: f64) -> Option<Crank> {
        let psi = self.psi0 - self.k * q;
        let (sn, cs) = psi.sin_cos();
        let (xa, ya) = (self.r2 * cs, self.r2 * sn);
        let y = self.e - ya;
        let x2 = self.lsq - y * y;
        if x2 <= 0.0 || x2.is_nan() {
            return None;
        }
        let x = self.sigma * x2.sqrt();
        Some(Crank {
            psi,
            xa,
            ya,
            x,
            y,
            inv_x: 1.0 / x,
        })
    }

    /// x u + y n.
    #[inline(always)]
    fn global(&self, x: f64, y: f64) -> V2 {
        self.u * x + self.n * y
    }

    /// The pinion's cg − O1 at q: g₁ turned by q.
    #[inline(always)]
    fn pinion_cg(&self, q: f64) -> V2 {
        let (sn, cs) = q.sin_cos();
        V2::new(
            cs * self.g1.x - sn * self.g1.y,
            sn * self.g1.x + cs * self.g1.y,
        )
    }

    /// Position analysis: θ₁ = q, θ₂ = θ_u + ψ, θ₃ = atan2(d), the cgs, A and B.
    #[inline(never)]
    pub fn pose(&self, q: f64) -> Option<GearedSliderCrankHandPose> {
        let c = self.crank(q)?;
        let a2 = self.global(c.xa, c.ya);
        let d = self.global(c.x, c.y);
        let a = self.o2 + a2;
        let b = a + d;
        Some(GearedSliderCrankHandPose {
            pinion: HandLinkPose {
                angle: q,
                cg: self.o1 + self.pinion_cg(q),
            },
            crank: HandLinkPose {
                angle: self.theta_u + c.psi,
                cg: at(self.o2, a2, self.g2),
            },
            rod: HandLinkPose {
                angle: d.y.atan2(d.x),
                cg: at(a, d, self.g3),
            },
            piston: HandLinkPose {
                angle: 0.0,
                cg: b + self.g4,
            },
            o1: self.o1,
            o2: self.o2,
            a,
            b,
        })
    }

    /// Position, velocity and acceleration analysis at (q, q̇, q̈) (see the type's docs).
    #[inline(never)]
    pub fn kinematics(&self, q: f64, qd: f64, qdd: f64) -> Option<GearedSliderCrankHandMotion> {
        let c = self.crank(q)?;
        let a2 = self.global(c.xa, c.ya);
        let d = self.global(c.x, c.y);
        let (w2, al2) = (-self.k * qd, -self.k * qdd);
        let va = perp(a2) * w2;
        let aa = perp(a2) * al2 - a2 * (w2 * w2);
        let w3 = -va.dot(&self.n) * c.inv_x;
        let al3 = (w3 * w3 * c.y - aa.dot(&self.n)) * c.inv_x;
        let vb = va + perp(d) * w3;
        let ab = aa + perp(d) * al3 - d * (w3 * w3);
        let a = self.o2 + a2;
        let b = a + d;
        let r1 = self.pinion_cg(q);
        let r2 = at(V2::zeros(), a2, self.g2);
        let r3 = at(V2::zeros(), d, self.g3);
        let fixed = |pos| HandPointMotion {
            pos,
            vel: V2::zeros(),
            acc: V2::zeros(),
        };
        Some(GearedSliderCrankHandMotion {
            pinion: HandLinkMotion {
                angle: q,
                omega: qd,
                alpha: qdd,
                cg: self.o1 + r1,
                cg_vel: perp(r1) * qd,
                cg_acc: perp(r1) * qdd - r1 * (qd * qd),
            },
            crank: HandLinkMotion {
                angle: self.theta_u + c.psi,
                omega: w2,
                alpha: al2,
                cg: self.o2 + r2,
                cg_vel: perp(r2) * w2,
                cg_acc: perp(r2) * al2 - r2 * (w2 * w2),
            },
            rod: HandLinkMotion {
                angle: d.y.atan2(d.x),
                omega: w3,
                alpha: al3,
                cg: a + r3,
                cg_vel: va + perp(r3) * w3,
                cg_acc: aa + perp(r3) * al3 - r3 * (w3 * w3),
            },
            piston: HandLinkMotion {
                angle: 0.0,
                omega: 0.0,
                alpha: 0.0,
                cg: b + self.g4,
                cg_vel: vb,
                cg_acc: ab,
            },
            o1: fixed(self.o1),
            o2: fixed(self.o2),
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
        })
    }

    /// Kinetostatics by d'Alembert: the dyad (rod, piston), then the gear, then the
    /// pinion.
    ///
    /// F_k = m_k g − m_k a_Gk (the piston's with the gas force, at B). The piston along
    /// u: R_B·u = −F₄·u =: a_B; the rod's moments about A, d × R_B = M₃ with
    /// M₃ = (G₃ − A) × F₃ − I₃α₃, give R_B = a_B u + b_B n, b_B = (M₃ + a_B Y)/X; then
    /// R_A = R_B − F₃, the guide R_g = −R_B − F₄ and M_g = −(G₄ − B) × (m₄g − m₄a_B).
    /// The gear's moments about O2, M_O = a₂ × (−R_A) + (G₂ − O2) × F₂ − I₂α₂ + T_shaft,
    /// with P − O2 = −r_b w: f_t = M_O/r_b, F_m = f_t t + |f_t| tan α w,
    /// R_O2 = R_A − F₂ − F_m. The pinion's about O1 (P − O1 = r_a w):
    /// T = r_a f_t − (G₁ − O1) × F₁ + I₁α₁, R_O1 = F_m − F₁.
    #[inline(never)]
    pub fn kinetostatics(
        &self,
        m: &GearedSliderCrankHandMotion,
        loads: &GearedSliderCrankLoads,
    ) -> GearedSliderCrankHandForces {
        let d = m.b.pos - m.a.pos;
        let (x, y) = (d.dot(&self.u), d.dot(&self.n));
        let f1 = self.w1 - m.pinion.cg_acc * self.m1;
        let f2 = self.w2 - m.crank.cg_acc * self.m2;
        let f3 = self.w3 - m.rod.cg_acc * self.m3;
        let f4i = self.w4 - m.piston.cg_acc * self.m4;
        let f4 = f4i + loads.gas;
        let m3 = cross(m.rod.cg - m.a.pos, f3) - self.i3 * m.rod.alpha;
        let ab = -f4.dot(&self.u);
        let rb = self.global(ab, (m3 + ab * y) / x);
        let ra = rb - f3;
        let mo = cross(ra, m.a.pos - self.o2) + cross(m.crank.cg - self.o2, f2)
            - self.i2 * m.crank.alpha
            + loads.shaft;
        let ft = mo / self.rb;
        let mesh = self.t * ft + self.w * (ft.abs() * self.tan_alpha);
        GearedSliderCrankHandForces {
            driver: self.ra * ft - cross(m.pinion.cg - self.o1, f1) + self.i1 * m.pinion.alpha,
            o1: mesh - f1,
            o2: ra - f2 - mesh,
            a: ra,
            b: rb,
            guide: -rb - f4,
            guide_moment: -cross(self.g4, f4i),
            mesh,
            tooth_load: ft.abs() * self.sec_alpha,
            flank: if ft >= 0.0 { 1.0 } else { -1.0 },
        }
    }

    /// The driver torque by virtual power, no reaction computed:
    /// T q̇ + Σ_k [F_k·v_Gk − I_k α_k ω_k] + F_gas·v_B + T_shaft ω₂ = 0 (q̇ ≠ 0; the
    /// piston's points all move at v_B).
    #[inline(never)]
    pub fn driver_action(
        &self,
        m: &GearedSliderCrankHandMotion,
        loads: &GearedSliderCrankLoads,
    ) -> f64 {
        let p1 = (self.w1 - m.pinion.cg_acc * self.m1).dot(&m.pinion.cg_vel)
            - self.i1 * m.pinion.alpha * m.pinion.omega;
        let p2 = (self.w2 - m.crank.cg_acc * self.m2).dot(&m.crank.cg_vel)
            + (loads.shaft - self.i2 * m.crank.alpha) * m.crank.omega;
        let p3 = (self.w3 - m.rod.cg_acc * self.m3).dot(&m.rod.cg_vel)
            - self.i3 * m.rod.alpha * m.rod.omega;
        let p4 = (self.w4 - m.piston.cg_acc * self.m4 + loads.gas).dot(&m.b.vel);
        -(p1 + p2 + p3 + p4) / m.pinion.omega
    }

    /// The velocity coefficients per unit crank rate (dψ = 1) and their ψ-derivatives, in
    /// the guide's frame, from y_A + Y = e (as `SliderCrankHand`):
    /// k₃ = −x_A/X, k₃' = (y_A + Y k₃²)/X, k_s = −y_A − Y k₃, k_s' = −x_A − X k₃² − Y k₃';
    /// the rod's cg at r = g₃ᵤ d + g₃ᵥ perp(d) from A: g_G3 = perp(a₂) + k₃ perp(r),
    /// g'_G3 = −a₂ + k₃' perp(r) − k₃² r. Returns the crank-level
    /// J = I_O2 + m₃|g_G3|² + I₃k₃² + m₄k_s², dJ/dψ, and (k_s, g_G3) for M*.
    #[inline(always)]
    fn crank_level(&self, c: &Crank) -> (f64, f64, f64, V2) {
        let k3 = -c.xa * c.inv_x;
        let k3sq = k3 * k3;
        let k3d = (c.ya + c.y * k3sq) * c.inv_x;
        let ks = -c.ya - c.y * k3;
        let ksd = -c.xa - c.x * k3sq - c.y * k3d;
        let rx = self.g3.0 * c.x - self.g3.1 * c.y;
        let ry = self.g3.0 * c.y + self.g3.1 * c.x;
        let g3 = V2::new(-c.ya - k3 * ry, c.xa + k3 * rx);
        let g3d = V2::new(-c.xa - k3d * ry - k3sq * rx, -c.ya + k3d * rx - k3sq * ry);
        (
            self.io2 + self.m3 * g3.norm_squared() + self.i3 * k3sq + self.m4 * ks * ks,
            2.0 * (self.m3 * g3.dot(&g3d) + self.i3 * k3 * k3d + self.m4 * ks * ksd),
            ks,
            g3,
        )
    }

    /// Zhukovski's I* = I_O1 + k² J(ψ) and dI*/dq = −k³ dJ/dψ (dψ/dq = −k);
    /// `None` without assembly.
    #[inline(never)]
    pub fn reduced(&self, q: f64) -> Option<HandReduced> {
        let c = self.crank(q)?;
        let (j, jd, ..) = self.crank_level(&c);
        let k2 = self.k * self.k;
        Some(HandReduced {
            inertia: self.io1 + k2 * j,
            inertia_derivative: -k2 * self.k * jd,
        })
    }

    /// M* = (G₁ − O1) × m₁g − k [(G₂ − O2) × m₂g + m₃g·g_G3 + (m₄g + F_gas)·u k_s
    /// + T_shaft], g_G3 in the guide's frame.
    #[inline(always)]
    fn moment_of(&self, q: f64, c: &Crank, ks: f64, g3: V2, loads: &GearedSliderCrankLoads) -> f64 {
        let a2 = self.global(c.xa, c.ya);
        let crank = cross(at(V2::zeros(), a2, self.g2), self.w2)
            + self.global(g3.x, g3.y).dot(&self.w3)
            + (self.w4 + loads.gas).dot(&self.u) * ks
            + loads.shaft;
        cross(self.pinion_cg(q), self.w1) - self.k * crank
    }

    /// Zhukovski's reduced moment M*(q) of the loads and gravity (N·m).
    #[inline(never)]
    pub fn reduced_moment(&self, q: f64, loads: &GearedSliderCrankLoads) -> Option<f64> {
        let c = self.crank(q)?;
        let (_, _, ks, g3) = self.crank_level(&c);
        Some(self.moment_of(q, &c, ks, g3, loads))
    }

    /// The direct problem: q̈ = (T + M* − ½ dI*/dq q̇²)/I*.
    #[inline(never)]
    pub fn acceleration(
        &self,
        q: f64,
        qd: f64,
        driver: f64,
        loads: &GearedSliderCrankLoads,
    ) -> Option<f64> {
        let c = self.crank(q)?;
        let (j, jd, ks, g3) = self.crank_level(&c);
        let k2 = self.k * self.k;
        let inertia = self.io1 + k2 * j;
        let half_derivative = -0.5 * k2 * self.k * jd;
        Some((driver + self.moment_of(q, &c, ks, g3, loads) - half_derivative * qd * qd) / inertia)
    }
}
