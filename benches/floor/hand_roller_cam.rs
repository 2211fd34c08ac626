//! Hand-written closed forms of the `RollerCam` of `benches/floor/machines.rs` (a module of
//! `hand.rs`, whose conventions it keeps): the cycloidal law, then the offset translating
//! roller follower.

use super::*;
use std::f64::consts::TAU;

/// The cam's base radius R_b (m), as declared in `RollerCam`'s `lobe` (the cam's data are
/// not among the generated parameters; `tests/floor.rs` checks these against the loaded
/// model).
pub const CAM_BASE_RADIUS: f64 = 0.040;
/// The roller's radius r (m), as declared.
pub const CAM_ROLLER_RADIUS: f64 = 0.010;
/// The lift L of the rise and of the fall (m), as declared.
pub const CAM_LIFT: f64 = 0.015;
/// The law's segment ends θ₁ (end of the rise), θ₂ (end of the dwell at L), θ₃ (end of
/// the fall), rad; the dwell at 0 ends at 2π.
pub const CAM_SEGMENTS: [f64; 3] = [
    120.0 * TAU / 360.0,
    180.0 * TAU / 360.0,
    270.0 * TAU / 360.0,
];

/// A cycloidal segment from (θ₀, h₀) rising by L (< 0: a fall) over β: with
/// x = (θ − θ₀)/β, s = h₀ + L (x − sin 2πx/2π), s′ = (L/β)(1 − cos 2πx),
/// s″ = (2πL/β²) sin 2πx (`docs/theory.md` §13).
#[derive(Clone, Copy, Debug)]
struct Cycloid {
    /// θ₀, 1/β, h₀, L, L/β, 2πL/β².
    start: f64,
    inv_beta: f64,
    from: f64,
    rise: f64,
    k1: f64,
    k2: f64,
}

impl Cycloid {
    fn new(start: f64, end: f64, from: f64, rise: f64) -> Self {
        let beta = end - start;
        Cycloid {
            start,
            inv_beta: 1.0 / beta,
            from,
            rise,
            k1: rise / beta,
            k2: TAU * rise / (beta * beta),
        }
    }

    /// (s, s′, s″) at θ in the segment.
    #[inline(always)]
    fn eval(&self, theta: f64) -> [f64; 3] {
        let x = (theta - self.start) * self.inv_beta;
        let (sn, cs) = (TAU * x).sin_cos();
        [
            self.from + self.rise * (x - sn / TAU),
            self.k1 * (1.0 - cs),
            self.k2 * sn,
        ]
    }
}

/// The disc cam with an offset translating roller follower: the cam 2 (the input: q its
/// rotation since the drawing, counter-clockwise) turns about O; the follower 3 slides
/// along u, its roller's centre P on the axis at the offset e from O.
///
/// **The law**: θ = q taken in [0, 2π); a cycloidal rise of L to θ₁, a dwell at L to
/// θ₂, a cycloidal fall of L to θ₃, a dwell at 0 to 2π ([`CAM_SEGMENTS`]). The follower
/// moves by s(θ) along u: v_P = s′ q̇ u, a_P = (s″ q̇² + s′ q̈) u.
///
/// **The contact** (`docs/conventions.md#cams`): in the axis frame (x̂, u), x̂ = u turned
/// by −90°, the roller's centre is F = (e, d + s), d = √(R_p² − e²), R_p = R_b + r; seen
/// from the cam it moves at v = F′ − perp(F) = (d + s, s′ − e), so the common normal is
/// n ∝ perp(v) = (e − s′, d + s) (through F: the contact force passes through the
/// roller's centre, which is the slide's point P).
#[derive(Clone, Copy, Debug)]
pub struct RollerCamHand {
    o: V2,
    /// The axis u (unit) and x̂ = (u_y, −u_x).
    u: V2,
    xh: V2,
    /// P, T and the follower's cg in the drawing (s = 0).
    p0: V2,
    t0: V2,
    g3: V2,
    /// G₃ − P and T − P (constant: the follower translates), and the follower's angle,
    /// that of P→T.
    r3: V2,
    rt: V2,
    theta3: f64,
    /// e, the axis' offset from O along x̂; d = √(R_p² − e²).
    e: f64,
    d: f64,
    /// The law's segment ends and its two cycloids.
    t1: f64,
    t2: f64,
    t3: f64,
    lift: f64,
    rise: Cycloid,
    fall: Cycloid,
    /// The cam's cg − O in the drawing (it turns by q).
    g2: V2,
    /// Cam inertia about its cg, I_O = I₂ + m₂|G₂ − O|², follower and cam masses.
    i2: f64,
    io: f64,
    m2: f64,
    m3: f64,
    /// Weights m·g (N).
    w2: V2,
    w3: V2,
}

/// Result of [`RollerCamHand::pose`].
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct RollerCamHandPose {
    /// Cam: θ₂ = q (not wrapped), cg.
    pub cam: HandLinkPose,
    /// Follower: θ₃ = atan2(T − P) (it translates), cg.
    pub follower: HandLinkPose,
    /// O (fixed), P, T (m).
    pub o: V2,
    pub p: V2,
    pub t: V2,
}

/// Result of [`RollerCamHand::kinematics`].
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct RollerCamHandMotion {
    /// The law at θ: s (m), s′ (m/rad), s″ (m/rad²).
    pub lift: [f64; 3],
    /// Cam: θ₂ = q, ω₂ = q̇, α₂ = q̈, its cg.
    pub cam: HandLinkMotion,
    /// Follower: θ₃ = atan2(T − P), ω = α = 0, its cg.
    pub follower: HandLinkMotion,
    /// O (fixed), P, T (T moves as P).
    pub o: HandPointMotion,
    pub p: HandPointMotion,
    pub t: HandPointMotion,
}

/// Result of [`RollerCamHand::kinetostatics`]: the driver torque (N·m, by the ground on
/// the cam) and the reactions, each BY the joint's first link ON its second (N, N·m).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct RollerCamHandForces {
    /// Motor torque on the cam.
    pub driver: f64,
    /// R_O: ground on cam.
    pub o: V2,
    /// Slide: ground on follower, its force (normal to u) and moment about P.
    pub slide: V2,
    pub slide_moment: f64,
    /// The contact force of the cam on the follower (along the common normal) and its
    /// signed magnitude F_n (> 0 while the cam pushes).
    pub lobe: V2,
    pub normal_force: f64,
}

impl RollerCamHand {
    /// Precompute the drawing's constants from `p` and the cam's law, base circle and
    /// roller ([`CAM_SEGMENTS`], [`CAM_LIFT`], [`CAM_BASE_RADIUS`], [`CAM_ROLLER_RADIUS`]).
    pub fn new(p: &RollerCamParams) -> Self {
        let (o, p0, t0) = (p.points.O, p.points.P, p.points.T);
        let (cam, follower) = (&p.links.cam, &p.links.follower);
        let u = p.axes.slide.normalize();
        let xh = V2::new(u.y, -u.x);
        let e = (p0 - o).dot(&xh);
        let rp = CAM_BASE_RADIUS + CAM_ROLLER_RADIUS;
        let [t1, t2, t3] = CAM_SEGMENTS;
        RollerCamHand {
            o,
            u,
            xh,
            p0,
            t0,
            g3: follower.cg,
            r3: follower.cg - p0,
            rt: t0 - p0,
            theta3: (t0.y - p0.y).atan2(t0.x - p0.x),
            e,
            d: (rp * rp - e * e).sqrt(),
            t1,
            t2,
            t3,
            lift: CAM_LIFT,
            rise: Cycloid::new(0.0, t1, 0.0, CAM_LIFT),
            fall: Cycloid::new(t2, t3, CAM_LIFT, -CAM_LIFT),
            g2: cam.cg - o,
            i2: cam.inertia,
            io: cam.inertia + cam.mass * (cam.cg - o).norm_squared(),
            m2: cam.mass,
            m3: follower.mass,
            w2: p.gravity * cam.mass,
            w3: p.gravity * follower.mass,
        }
    }

    /// (s, s′, s″) at the cam's turn q (see the type's docs).
    #[inline(always)]
    fn law(&self, q: f64) -> [f64; 3] {
        let t = q.rem_euclid(TAU);
        if t < self.t1 {
            self.rise.eval(t)
        } else if t < self.t2 {
            [self.lift, 0.0, 0.0]
        } else if t < self.t3 {
            self.fall.eval(t)
        } else {
            [0.0; 3]
        }
    }

    /// The cam's cg − O at q and q's sine and cosine.
    #[inline(always)]
    fn cam_cg(&self, q: f64) -> V2 {
        let (sn, cs) = q.sin_cos();
        V2::new(
            cs * self.g2.x - sn * self.g2.y,
            sn * self.g2.x + cs * self.g2.y,
        )
    }

    /// Position analysis: θ₂ = q, the follower at s(θ) along u, the cgs, P and T.
    /// (`Option` as the other machines; the cam always drives its follower.)
    #[inline(never)]
    pub fn pose(&self, q: f64) -> Option<RollerCamHandPose> {
        let [s, ..] = self.law(q);
        let lift = self.u * s;
        Some(RollerCamHandPose {
            cam: HandLinkPose {
                angle: q,
                cg: self.o + self.cam_cg(q),
            },
            follower: HandLinkPose {
                angle: self.theta3,
                cg: self.g3 + lift,
            },
            o: self.o,
            p: self.p0 + lift,
            t: self.t0 + lift,
        })
    }

    /// Position, velocity and acceleration analysis at (q, q̇, q̈) (see the type's docs).
    #[inline(never)]
    pub fn kinematics(&self, q: f64, qd: f64, qdd: f64) -> Option<RollerCamHandMotion> {
        let lift = self.law(q);
        let [s, s1, s2] = lift;
        let r = self.cam_cg(q);
        let v = self.u * (s1 * qd);
        let a = self.u * (s2 * qd * qd + s1 * qdd);
        Some(RollerCamHandMotion {
            lift,
            cam: HandLinkMotion {
                angle: q,
                omega: qd,
                alpha: qdd,
                cg: self.o + r,
                cg_vel: perp(r) * qd,
                cg_acc: perp(r) * qdd - r * (qd * qd),
            },
            follower: HandLinkMotion {
                angle: self.theta3,
                omega: 0.0,
                alpha: 0.0,
                cg: self.g3 + self.u * s,
                cg_vel: v,
                cg_acc: a,
            },
            o: HandPointMotion {
                pos: self.o,
                vel: V2::zeros(),
                acc: V2::zeros(),
            },
            p: HandPointMotion {
                pos: self.p0 + self.u * s,
                vel: v,
                acc: a,
            },
            t: HandPointMotion {
                pos: self.t0 + self.u * s,
                vel: v,
                acc: a,
            },
        })
    }

    /// Kinetostatics by d'Alembert, the follower first, then the cam.
    ///
    /// The follower carries W = m₃g − m₃a_P + F_push (the load at T, the inertia and
    /// weight at G₃), the slide's force normal to u and moment, and the contact force
    /// λ (e − s′, d + s) in the axis frame (along the normal, through P). Along u:
    /// λ = −W·u/(d + s); F_n = λ √((e − s′)² + (d + s)²). Then R_slide = −W − F_lobe and,
    /// the contact force passing through P,
    /// M_slide = −(G₃ − P) × (m₃g − m₃a_P) − (T − P) × F_push. The cam:
    /// (F − O) × F_lobe = λ(d + s)s′ = −(W·u) s′ (F the roller's centre), so
    /// T = −(W·u) s′ − (G₂ − O) × F₂ + I₂α₂ − T_drag and R_O = F_lobe − F₂.
    #[inline(never)]
    pub fn kinetostatics(
        &self,
        m: &RollerCamHandMotion,
        loads: &RollerCamLoads,
    ) -> RollerCamHandForces {
        let [s, s1, _] = m.lift;
        let f2 = self.w2 - m.cam.cg_acc * self.m2;
        let f3 = self.w3 - m.p.acc * self.m3;
        let w = f3 + loads.push;
        let wu = w.dot(&self.u);
        let (nx, ny) = (self.e - s1, self.d + s);
        let lambda = -wu / ny;
        let lobe = (self.xh * nx + self.u * ny) * lambda;
        RollerCamHandForces {
            driver: -wu * s1 - cross(m.cam.cg - self.o, f2) + self.i2 * m.cam.alpha - loads.drag,
            o: lobe - f2,
            slide: -w - lobe,
            slide_moment: -cross(self.r3, f3) - cross(self.rt, loads.push),
            lobe,
            normal_force: lambda * (nx * nx + ny * ny).sqrt(),
        }
    }

    /// The driver torque by virtual power, no reaction computed:
    /// T q̇ + F₂·v_G2 − I₂α₂q̇ + T_drag q̇ + (m₃g − m₃a_P + F_push)·v_P = 0 (q̇ ≠ 0; the
    /// follower's points all move at v_P).
    #[inline(never)]
    pub fn driver_action(&self, m: &RollerCamHandMotion, loads: &RollerCamLoads) -> f64 {
        let p2 = (self.w2 - m.cam.cg_acc * self.m2).dot(&m.cam.cg_vel)
            + (loads.drag - self.i2 * m.cam.alpha) * m.cam.omega;
        let p3 = (self.w3 - m.p.acc * self.m3 + loads.push).dot(&m.p.vel);
        -(p2 + p3) / m.cam.omega
    }

    /// Zhukovski's I* = I_O + m₃ s′², dI*/dq = 2 m₃ s′ s″.
    #[inline(never)]
    pub fn reduced(&self, q: f64) -> Option<HandReduced> {
        let [_, s1, s2] = self.law(q);
        let m3s1 = self.m3 * s1;
        Some(HandReduced {
            inertia: self.io + m3s1 * s1,
            inertia_derivative: 2.0 * m3s1 * s2,
        })
    }

    /// M* = (G₂ − O) × m₂g + (m₃g + F_push)·u s′ + T_drag.
    #[inline(always)]
    fn moment_of(&self, q: f64, s1: f64, loads: &RollerCamLoads) -> f64 {
        cross(self.cam_cg(q), self.w2) + (self.w3 + loads.push).dot(&self.u) * s1 + loads.drag
    }

    /// Zhukovski's reduced moment M*(q) of the loads and gravity (N·m).
    #[inline(never)]
    pub fn reduced_moment(&self, q: f64, loads: &RollerCamLoads) -> Option<f64> {
        let [_, s1, _] = self.law(q);
        Some(self.moment_of(q, s1, loads))
    }

    /// The direct problem: q̈ = (T + M* − ½ dI*/dq q̇²)/I*.
    #[inline(never)]
    pub fn acceleration(
        &self,
        q: f64,
        qd: f64,
        driver: f64,
        loads: &RollerCamLoads,
    ) -> Option<f64> {
        let [_, s1, s2] = self.law(q);
        let m3s1 = self.m3 * s1;
        let inertia = self.io + m3s1 * s1;
        Some((driver + self.moment_of(q, s1, loads) - m3s1 * s2 * qd * qd) / inertia)
    }
}
