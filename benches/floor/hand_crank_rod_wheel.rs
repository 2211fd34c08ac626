//! Hand-written closed forms of the `CrankRodWheel` of `benches/floor/machines.rs` (a
//! module of `hand.rs`, whose conventions it keeps): the offset slider-crank whose slider
//! is a wheel rolling on a straight track.

use super::*;

/// The wheel's radius r (m), as declared in `CrankRodWheel`'s `roll` (not among the
/// generated parameters; `tests/floor.rs` checks it against the loaded model).
pub const WHEEL_RADIUS: f64 = 0.030;

/// Crank, rod and rolling wheel: the crank 2 (O2–A, q its angle) drives the rod 3 (A–C),
/// pinned at C to the centre of the wheel 4, which rolls without slipping on the ground
/// along u (the track at r on the right of the line of C).
///
/// **Positions and rates** as the offset slider-crank's, in the track's frame
/// (u, n = perp(u)): with ψ = q − θ_u the crank's angle from u, x_A = r₂ cos ψ,
/// y_A = r₂ sin ψ, the rod d = C − A = X u + Y n, Y = e − y_A, X = σ√(l² − Y²);
/// ω₃ = −(v_A·n)/X, α₃ = (ω₃² Y − a_A·n)/X, v_C = v_A + ω₃ perp(d),
/// a_C = a_A + α₃ perp(d) − ω₃² d.
///
/// **Rolling** (`docs/conventions.md#rolling`): the centre's travel s = x_A + X − x_C₀
/// turns the wheel by φ₄ = −s/r, so ω₄ = −v_C·u/r, α₄ = −a_C·u/r; its cg is at
/// ρ = R(φ₄)(G₄ − C)₀ from C.
#[derive(Clone, Copy, Debug)]
pub struct CrankRodWheelHand {
    o2: V2,
    /// The track's unit direction u and n = perp(u).
    u: V2,
    n: V2,
    /// ψ₀ = −θ_u: the crank's angle from u is ψ = q − θ_u (q, the crank's angle θ₂).
    psi0: f64,
    /// r₂; l²; e, the line of C's offset from O2 along n; x_C₀ = (C₀ − O2)·u.
    r2: f64,
    lsq: f64,
    e: f64,
    xc0: f64,
    /// Branch: the sign of X.
    sigma: f64,
    /// r and 1/r.
    r: f64,
    inv_r: f64,
    /// Crank cg in the frame O2→A scaled by 1/r₂; rod cg in the frame A→C scaled by 1/l.
    g2: (f64, f64),
    g3: (f64, f64),
    /// The wheel's cg − C in the drawing, in the track's frame.
    g4u: V2,
    /// Masses (kg) and inertias about the cgs (kg·m²), I_O2 = I₂ + m₂|G₂ − O2|².
    m2: f64,
    m3: f64,
    m4: f64,
    i2: f64,
    i3: f64,
    i4: f64,
    io2: f64,
    /// Weights m·g (N), global.
    w2: V2,
    w3: V2,
    w4: V2,
}

/// Result of [`CrankRodWheelHand::pose`].
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct CrankRodWheelHandPose {
    /// Crank: θ₂ = q (not wrapped), cg.
    pub crank: HandLinkPose,
    /// Rod: θ₃ = atan2(C − A), cg.
    pub rod: HandLinkPose,
    /// Wheel: φ₄ = −s/r (not wrapped), cg.
    pub wheel: HandLinkPose,
    /// O2 (fixed), A, C (m).
    pub o2: V2,
    pub a: V2,
    pub c: V2,
}

/// Result of [`CrankRodWheelHand::kinematics`].
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct CrankRodWheelHandMotion {
    /// Crank: θ₂ = q, ω₂ = q̇, α₂ = q̈, its cg.
    pub crank: HandLinkMotion,
    /// Rod: θ₃, ω₃, α₃, its cg.
    pub rod: HandLinkMotion,
    /// Wheel: φ₄, ω₄, α₄, its cg.
    pub wheel: HandLinkMotion,
    /// O2 (fixed), A, C.
    pub o2: HandPointMotion,
    pub a: HandPointMotion,
    pub c: HandPointMotion,
}

/// Result of [`CrankRodWheelHand::kinetostatics`]: the driver torque (N·m, by the ground
/// on the crank) and the reactions, each BY the joint's first link ON its second (N).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct CrankRodWheelHandForces {
    /// Motor torque on the crank.
    pub driver: f64,
    /// R_O2: ground on crank; R_A: crank on rod; R_C: rod on wheel.
    pub o2: V2,
    pub a: V2,
    pub c: V2,
    /// The contact force of the track on the wheel at K = C − r n, its normal part (along
    /// n) and its friction (along u).
    pub roll: V2,
    pub normal: f64,
    pub friction: f64,
}

/// The crank, rod and wheel of one q, in the track's frame.
#[derive(Clone, Copy, Debug)]
struct Pose {
    /// a₂'s coordinates (x_A, y_A); the rod's (X, Y) and 1/X.
    xa: f64,
    ya: f64,
    x: f64,
    y: f64,
    inv_x: f64,
    /// φ₄ and ρ = R(φ₄) g₄ in the track's frame.
    phi: f64,
    rho: V2,
}

impl CrankRodWheelHand {
    /// Precompute the drawing's constants from `p` and the wheel's radius
    /// ([`WHEEL_RADIUS`]).
    pub fn new(p: &CrankRodWheelParams) -> Self {
        let (o2, a, c) = (p.points.O2, p.points.A, p.points.C);
        let l = &p.links;
        let u = p.axes.roll.normalize();
        let n = perp(u);
        let a2 = a - o2;
        let g4 = l.wheel.cg - c;
        CrankRodWheelHand {
            o2,
            u,
            n,
            psi0: -u.y.atan2(u.x),
            r2: a2.norm(),
            lsq: (c - a).norm_squared(),
            e: (c - o2).dot(&n),
            xc0: (c - o2).dot(&u),
            sigma: (c - a).dot(&u).signum(),
            r: WHEEL_RADIUS,
            inv_r: 1.0 / WHEEL_RADIUS,
            g2: local_scaled(o2, a, l.crank.cg),
            g3: local_scaled(a, c, l.rod.cg),
            g4u: V2::new(g4.dot(&u), g4.dot(&n)),
            m2: l.crank.mass,
            m3: l.rod.mass,
            m4: l.wheel.mass,
            i2: l.crank.inertia,
            i3: l.rod.inertia,
            i4: l.wheel.inertia,
            io2: l.crank.inertia + l.crank.mass * (l.crank.cg - o2).norm_squared(),
            w2: p.gravity * l.crank.mass,
            w3: p.gravity * l.rod.mass,
            w4: p.gravity * l.wheel.mass,
        }
    }

    /// The slider-crank's position and the wheel's turn (see the type's docs); `None`
    /// when the rod cannot reach the track (never for this drawing: r₂ + |e| < l).
    #[inline(always)]
    fn pose_of(&self, q: f64) -> Option<Pose> {
        let psi = self.psi0 + q;
        let (sn, cs) = psi.sin_cos();
        let (xa, ya) = (self.r2 * cs, self.r2 * sn);
        let y = self.e - ya;
        let x2 = self.lsq - y * y;
        if x2 <= 0.0 || x2.is_nan() {
            return None;
        }
        let x = self.sigma * x2.sqrt();
        let phi = -(xa + x - self.xc0) * self.inv_r;
        let (sw, cw) = phi.sin_cos();
        Some(Pose {
            xa,
            ya,
            x,
            y,
            inv_x: 1.0 / x,
            phi,
            rho: V2::new(
                cw * self.g4u.x - sw * self.g4u.y,
                sw * self.g4u.x + cw * self.g4u.y,
            ),
        })
    }

    /// x u + y n.
    #[inline(always)]
    fn global(&self, v: V2) -> V2 {
        self.u * v.x + self.n * v.y
    }

    /// Position analysis: θ₂ = q, θ₃ = atan2(d), φ₄ = −s/r, the cgs, A and C.
    #[inline(never)]
    pub fn pose(&self, q: f64) -> Option<CrankRodWheelHandPose> {
        let c = self.pose_of(q)?;
        let a2 = self.global(V2::new(c.xa, c.ya));
        let d = self.global(V2::new(c.x, c.y));
        let a = self.o2 + a2;
        let cc = a + d;
        Some(CrankRodWheelHandPose {
            crank: HandLinkPose {
                angle: q,
                cg: at(self.o2, a2, self.g2),
            },
            rod: HandLinkPose {
                angle: d.y.atan2(d.x),
                cg: at(a, d, self.g3),
            },
            wheel: HandLinkPose {
                angle: c.phi,
                cg: cc + self.global(c.rho),
            },
            o2: self.o2,
            a,
            c: cc,
        })
    }

    /// Position, velocity and acceleration analysis at (q, q̇, q̈) (see the type's docs).
    #[inline(never)]
    pub fn kinematics(&self, q: f64, qd: f64, qdd: f64) -> Option<CrankRodWheelHandMotion> {
        let c = self.pose_of(q)?;
        let a2 = self.global(V2::new(c.xa, c.ya));
        let d = self.global(V2::new(c.x, c.y));
        let (w2, al2) = (qd, qdd);
        let va = perp(a2) * w2;
        let aa = perp(a2) * al2 - a2 * (w2 * w2);
        let w3 = -va.dot(&self.n) * c.inv_x;
        let al3 = (w3 * w3 * c.y - aa.dot(&self.n)) * c.inv_x;
        let vc = va + perp(d) * w3;
        let ac = aa + perp(d) * al3 - d * (w3 * w3);
        let w4 = -vc.dot(&self.u) * self.inv_r;
        let al4 = -ac.dot(&self.u) * self.inv_r;
        let a = self.o2 + a2;
        let cc = a + d;
        let r2 = at(V2::zeros(), a2, self.g2);
        let r3 = at(V2::zeros(), d, self.g3);
        let r4 = self.global(c.rho);
        Some(CrankRodWheelHandMotion {
            crank: HandLinkMotion {
                angle: q,
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
            wheel: HandLinkMotion {
                angle: c.phi,
                omega: w4,
                alpha: al4,
                cg: cc + r4,
                cg_vel: vc + perp(r4) * w4,
                cg_acc: ac + perp(r4) * al4 - r4 * (w4 * w4),
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
            c: HandPointMotion {
                pos: cc,
                vel: vc,
                acc: ac,
            },
        })
    }

    /// Kinetostatics by d'Alembert: the wheel's moments, the dyad (rod, wheel), then the
    /// crank.
    ///
    /// F_k = m_k g − m_k a_Gk (the wheel's with the pull, at C). The wheel's moments about
    /// C, M₄ = (G₄ − C) × (m₄g − m₄a_G4) − I₄α₄ + T_brake, fix the friction f u at K
    /// ((K − C) × u = r): f = −M₄/r. The wheel along u then gives R_C·u = −(F₄·u + f)
    /// =: a_C, and the rod's moments about A, d × R_C = M₃ = (G₃ − A) × F₃ − I₃α₃, give
    /// R_C = a_C u + b_C n, b_C = (M₃ + a_C Y)/X; R_A = R_C − F₃; the contact force
    /// −R_C − F₄ (its u part is f, its n part the normal). The crank: T = a₂ × R_A − M₂,
    /// M₂ = (G₂ − O2) × F₂ − I₂α₂, and R_O2 = R_A − F₂.
    #[inline(never)]
    pub fn kinetostatics(
        &self,
        m: &CrankRodWheelHandMotion,
        loads: &CrankRodWheelLoads,
    ) -> CrankRodWheelHandForces {
        let d = m.c.pos - m.a.pos;
        let (x, y) = (d.dot(&self.u), d.dot(&self.n));
        let f2 = self.w2 - m.crank.cg_acc * self.m2;
        let f3 = self.w3 - m.rod.cg_acc * self.m3;
        let f4i = self.w4 - m.wheel.cg_acc * self.m4;
        let f4 = f4i + loads.pull;
        let m4 = cross(m.wheel.cg - m.c.pos, f4i) - self.i4 * m.wheel.alpha + loads.brake;
        let friction = -m4 * self.inv_r;
        let m3 = cross(m.rod.cg - m.a.pos, f3) - self.i3 * m.rod.alpha;
        let ac = -(f4.dot(&self.u) + friction);
        let rc = self.u * ac + self.n * ((m3 + ac * y) / x);
        let ra = rc - f3;
        let m2 = cross(m.crank.cg - self.o2, f2) - self.i2 * m.crank.alpha;
        let roll = -rc - f4;
        CrankRodWheelHandForces {
            driver: cross(m.a.pos - self.o2, ra) - m2,
            o2: ra - f2,
            a: ra,
            c: rc,
            roll,
            normal: roll.dot(&self.n),
            friction,
        }
    }

    /// The driver torque by virtual power, no reaction computed:
    /// T q̇ + Σ_k [F_k·v_Gk − I_k α_k ω_k] + F_pull·v_C + T_brake ω₄ = 0 (q̇ ≠ 0).
    #[inline(never)]
    pub fn driver_action(&self, m: &CrankRodWheelHandMotion, loads: &CrankRodWheelLoads) -> f64 {
        let p2 = (self.w2 - m.crank.cg_acc * self.m2).dot(&m.crank.cg_vel)
            - self.i2 * m.crank.alpha * m.crank.omega;
        let p3 = (self.w3 - m.rod.cg_acc * self.m3).dot(&m.rod.cg_vel)
            - self.i3 * m.rod.alpha * m.rod.omega;
        let p4 = (self.w4 - m.wheel.cg_acc * self.m4).dot(&m.wheel.cg_vel)
            + (loads.brake - self.i4 * m.wheel.alpha) * m.wheel.omega
            + loads.pull.dot(&m.c.vel);
        -(p2 + p3 + p4) / m.crank.omega
    }

    /// The velocity coefficients per unit q and their q-derivatives, in the track's frame
    /// (as `SliderCrankHand`): k₃ = −x_A/X, k₃' = (y_A + Y k₃²)/X, k_s = −y_A − Y k₃,
    /// k_s' = −x_A − X k₃² − Y k₃'; the rod's cg g_G3 = perp(a₂) + k₃ perp(r₃),
    /// g'_G3 = −a₂ + k₃' perp(r₃) − k₃² r₃; the wheel's turn k₄ = −k_s/r,
    /// k₄' = −k_s'/r and its cg g_G4 = k_s u + k₄ perp(ρ), g'_G4 = k_s' u + k₄' perp(ρ)
    /// − k₄² ρ. Returns (I*, dI*/dq, k_s, k₄, g_G3, g_G4) with
    /// I* = I_O2 + m₃|g_G3|² + I₃k₃² + m₄|g_G4|² + I₄k₄².
    #[inline(always)]
    fn coefficients(&self, c: &Pose) -> (f64, f64, f64, f64, V2, V2) {
        let k3 = -c.xa * c.inv_x;
        let k3sq = k3 * k3;
        let k3d = (c.ya + c.y * k3sq) * c.inv_x;
        let ks = -c.ya - c.y * k3;
        let ksd = -c.xa - c.x * k3sq - c.y * k3d;
        let rx = self.g3.0 * c.x - self.g3.1 * c.y;
        let ry = self.g3.0 * c.y + self.g3.1 * c.x;
        let g3 = V2::new(-c.ya - k3 * ry, c.xa + k3 * rx);
        let g3d = V2::new(-c.xa - k3d * ry - k3sq * rx, -c.ya + k3d * rx - k3sq * ry);
        let k4 = -ks * self.inv_r;
        let k4d = -ksd * self.inv_r;
        let rho = c.rho;
        let g4 = V2::new(ks - k4 * rho.y, k4 * rho.x);
        let g4d = V2::new(
            ksd - k4d * rho.y - k4 * k4 * rho.x,
            k4d * rho.x - k4 * k4 * rho.y,
        );
        (
            self.io2
                + self.m3 * g3.norm_squared()
                + self.i3 * k3sq
                + self.m4 * g4.norm_squared()
                + self.i4 * k4 * k4,
            2.0 * (self.m3 * g3.dot(&g3d)
                + self.i3 * k3 * k3d
                + self.m4 * g4.dot(&g4d)
                + self.i4 * k4 * k4d),
            ks,
            k4,
            g3,
            g4,
        )
    }

    /// Zhukovski's I* and dI*/dq (see `coefficients`); `None` without assembly.
    #[inline(never)]
    pub fn reduced(&self, q: f64) -> Option<HandReduced> {
        let (inertia, inertia_derivative, ..) = self.coefficients(&self.pose_of(q)?);
        Some(HandReduced {
            inertia,
            inertia_derivative,
        })
    }

    /// M* = (G₂ − O2) × m₂g + m₃g·g_G3 + m₄g·g_G4 + (F_pull·u) k_s + T_brake k₄.
    #[inline(always)]
    fn moment_of(
        &self,
        c: &Pose,
        (ks, k4, g3, g4): (f64, f64, V2, V2),
        loads: &CrankRodWheelLoads,
    ) -> f64 {
        let a2 = self.global(V2::new(c.xa, c.ya));
        cross(at(V2::zeros(), a2, self.g2), self.w2)
            + self.global(g3).dot(&self.w3)
            + self.global(g4).dot(&self.w4)
            + loads.pull.dot(&self.u) * ks
            + loads.brake * k4
    }

    /// Zhukovski's reduced moment M*(q) of the loads and gravity (N·m).
    #[inline(never)]
    pub fn reduced_moment(&self, q: f64, loads: &CrankRodWheelLoads) -> Option<f64> {
        let c = self.pose_of(q)?;
        let (_, _, ks, k4, g3, g4) = self.coefficients(&c);
        Some(self.moment_of(&c, (ks, k4, g3, g4), loads))
    }

    /// The direct problem: q̈ = (T + M* − ½ dI*/dq q̇²)/I*.
    #[inline(never)]
    pub fn acceleration(
        &self,
        q: f64,
        qd: f64,
        driver: f64,
        loads: &CrankRodWheelLoads,
    ) -> Option<f64> {
        let c = self.pose_of(q)?;
        let (inertia, derivative, ks, k4, g3, g4) = self.coefficients(&c);
        Some(
            (driver + self.moment_of(&c, (ks, k4, g3, g4), loads) - 0.5 * derivative * qd * qd)
                / inertia,
        )
    }
}
