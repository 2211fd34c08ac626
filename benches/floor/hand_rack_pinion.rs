//! Hand-written closed forms of the `RackPinion` of `benches/floor/machines.rs` (a module
//! of `hand.rs`, whose conventions it keeps): the rack's travel linear in the pinion's
//! turn, the tooth force from the rack's balance along its guide.

use super::*;

/// The pinion's pitch radius r (m), as declared in `RackPinion`'s `mesh` (the radius is
/// not among the generated parameters; `tests/floor.rs` checks both constants against the
/// loaded model).
pub const RACK_PINION_RADIUS: f64 = 0.030;
/// The mesh's pressure angle α (rad), as declared (20°).
pub const RACK_PRESSURE_ANGLE: f64 = 20.0 * std::f64::consts::PI / 180.0;

/// The rack and pinion: the pinion 1 (the input, q its rotation since the drawing) turns
/// about O; the rack 2 slides without turning on the ground guide u (unit, through R), its
/// pitch line parallel to u at r from O, on R's side.
///
/// **The mesh** (`docs/conventions.md#gears`): n is the unit normal to u from O towards the
/// pitch line, the pitch point K = O + r n is fixed and the common tangent is the rack's
/// axis u. The pitch line rolls on the pitch circle: the pinion's point at K moves at
/// q̇ r perp(n) = κ r q̇ u with κ = perp(n)·u = ±1 (+1 with the rack below O and u to the
/// right), so every point X of the rack is at X₀ + s u with the travel s = κ r q (m):
/// v = κ r q̇ u, a = κ r q̈ u.
///
/// **The tooth force** of the pinion on the rack at K is F = f_t u + |f_t| tan α n (its
/// radial part pushes the rack away from the pinion), tooth load |f_t|/cos α, flank
/// sign(f_t).
#[derive(Clone, Copy, Debug)]
pub struct RackPinionHand {
    o: V2,
    /// The guide's unit direction u and the unit normal n from O towards the pitch line.
    u: V2,
    n: V2,
    /// κ r u (m): the rack's displacement per unit q (its velocity per unit q̇).
    ku: V2,
    /// κ r (m): the lever of the tooth force's tangential part about O.
    kr: f64,
    /// R, L and the rack's cg in the drawing (m).
    r0: V2,
    l0: V2,
    g20: V2,
    /// K − R₀, G₂ − R and L − R (m): constant, the rack does not turn.
    kr0: V2,
    g2r: V2,
    lr: V2,
    /// The rack's angle R → L (rad), constant.
    theta2: f64,
    /// The pinion's cg − O in the drawing (it turns by q).
    g1: V2,
    /// tan α and 1/cos α.
    tan_alpha: f64,
    sec_alpha: f64,
    /// Masses (kg), the pinion's inertia about its cg (kg·m²); the rack's needs none.
    m1: f64,
    m2: f64,
    i1: f64,
    /// I* = I_O1 + m₂ r² (kg·m²), constant.
    inertia: f64,
    /// Weights m·g (N), global.
    w1: V2,
    w2: V2,
}

/// Result of [`RackPinionHand::pose`].
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct RackPinionHandPose {
    /// Pinion: θ₁ = q (not wrapped), cg.
    pub pinion: HandLinkPose,
    /// Rack: θ₂ the direction R → L (constant), cg.
    pub rack: HandLinkPose,
    /// O (fixed), R, L (m).
    pub o: V2,
    pub r: V2,
    pub l: V2,
}

/// Result of [`RackPinionHand::kinematics`].
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct RackPinionHandMotion {
    /// Pinion: θ₁ = q, ω₁ = q̇, α₁ = q̈, its cg.
    pub pinion: HandLinkMotion,
    /// Rack: θ₂ constant, ω₂ = α₂ = 0, its cg.
    pub rack: HandLinkMotion,
    /// O (fixed), R, L.
    pub o: HandPointMotion,
    pub r: HandPointMotion,
    pub l: HandPointMotion,
}

/// Result of [`RackPinionHand::kinetostatics`]: the driver torque (N·m, by the ground on
/// the pinion) and the reactions, each BY the joint's first link ON its second (N, N·m).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct RackPinionHandForces {
    /// Motor torque on the pinion.
    pub driver: f64,
    /// R_O: ground on pinion.
    pub o: V2,
    /// Guide: ground on rack, its force (normal to u) and moment about R where it is now.
    pub guide: V2,
    pub guide_moment: f64,
    /// Mesh: the tooth force of the pinion on the rack at K, its magnitude and flank (+1
    /// when it pushes the rack along u).
    pub mesh: V2,
    pub tooth_load: f64,
    pub flank: f64,
}

impl RackPinionHand {
    /// Precompute the drawing's constants from `p`, the pitch radius and the pressure angle
    /// (`RACK_PINION_RADIUS`, `RACK_PRESSURE_ANGLE`).
    pub fn new(p: &RackPinionParams) -> Self {
        let (o, r0, l0) = (p.points.O, p.points.R, p.points.L);
        let l = &p.links;
        let r = RACK_PINION_RADIUS;
        let u = p.axes.guide.normalize();
        let n = perp(u) * perp(u).dot(&(r0 - o)).signum();
        let kappa = perp(n).dot(&u);
        let k = o + n * r;
        let g1 = l.pinion.cg - o;
        let io1 = l.pinion.inertia + l.pinion.mass * g1.norm_squared();
        RackPinionHand {
            o,
            u,
            n,
            ku: u * (kappa * r),
            kr: kappa * r,
            r0,
            l0,
            g20: l.rack.cg,
            kr0: k - r0,
            g2r: l.rack.cg - r0,
            lr: l0 - r0,
            theta2: (l0.y - r0.y).atan2(l0.x - r0.x),
            g1,
            tan_alpha: RACK_PRESSURE_ANGLE.tan(),
            sec_alpha: 1.0 / RACK_PRESSURE_ANGLE.cos(),
            m1: l.pinion.mass,
            m2: l.rack.mass,
            i1: l.pinion.inertia,
            inertia: io1 + l.rack.mass * r * r,
            w1: p.gravity * l.pinion.mass,
            w2: p.gravity * l.rack.mass,
        }
    }

    /// Position analysis: the pinion's cg turned by q, the rack moved by s u = κ r q u.
    #[inline(never)]
    pub fn pose(&self, q: f64) -> Option<RackPinionHandPose> {
        let d = self.ku * q;
        Some(RackPinionHandPose {
            pinion: HandLinkPose {
                angle: q,
                cg: self.o + rotate(turn(q), self.g1),
            },
            rack: HandLinkPose {
                angle: self.theta2,
                cg: self.g20 + d,
            },
            o: self.o,
            r: self.r0 + d,
            l: self.l0 + d,
        })
    }

    /// Position, velocity and acceleration analysis at (q, q̇, q̈): the pinion's cg
    /// G₁ = O + r₁ (r₁ turned by q), v = q̇ perp(r₁), a = q̈ perp(r₁) − q̇² r₁; every point of
    /// the rack X₀ + κ r q u, v = κ r q̇ u, a = κ r q̈ u.
    #[inline(never)]
    pub fn kinematics(&self, q: f64, qd: f64, qdd: f64) -> Option<RackPinionHandMotion> {
        let r1 = rotate(turn(q), self.g1);
        let (d, v, a) = (self.ku * q, self.ku * qd, self.ku * qdd);
        let rack_point = |x0: V2| HandPointMotion {
            pos: x0 + d,
            vel: v,
            acc: a,
        };
        Some(RackPinionHandMotion {
            pinion: HandLinkMotion {
                angle: q,
                omega: qd,
                alpha: qdd,
                cg: self.o + r1,
                cg_vel: perp(r1) * qd,
                cg_acc: perp(r1) * qdd - r1 * (qd * qd),
            },
            rack: HandLinkMotion {
                angle: self.theta2,
                omega: 0.0,
                alpha: 0.0,
                cg: self.g20 + d,
                cg_vel: v,
                cg_acc: a,
            },
            o: HandPointMotion {
                pos: self.o,
                vel: V2::zeros(),
                acc: V2::zeros(),
            },
            r: rack_point(self.r0),
            l: rack_point(self.l0),
        })
    }

    /// Kinetostatics by d'Alembert, the rack then the pinion.
    ///
    /// With W = m₂ g − m₂ a (the rack's weight and inertia force, at G₂) and the push F_L at
    /// L: the rack's forces along u give the tangential tooth force
    /// f_t = −(W + F_L)·u (the guide takes nothing along u), F = f_t u + |f_t| tan α n, the
    /// guide's force R_g = −(F + W + F_L) (normal to u), and its moment about R (where it is
    /// now: K − R = (K − R₀) − s u, G₂ − R and L − R constant)
    /// M_g = −[(K − R) × F + (G₂ − R) × W + (L − R) × F_L]. The pinion, with
    /// F₁ = m₁ g − m₁ a_G1: R_O = F − F₁ and, about O ((K − O) × F = κ r f_t),
    /// T = κ r f_t − r₁ × F₁ + I₁ q̈ − T_resist.
    #[inline(never)]
    pub fn kinetostatics(
        &self,
        m: &RackPinionHandMotion,
        loads: &RackPinionLoads,
    ) -> RackPinionHandForces {
        let w = self.w2 - m.rack.cg_acc * self.m2;
        let f1 = self.w1 - m.pinion.cg_acc * self.m1;
        let push = loads.push;
        let ft = -(w + push).dot(&self.u);
        let mesh = self.u * ft + self.n * (ft.abs() * self.tan_alpha);
        let k = self.kr0 - (m.r.pos - self.r0);
        RackPinionHandForces {
            driver: self.kr * ft - cross(m.pinion.cg - self.o, f1) + self.i1 * m.pinion.alpha
                - loads.resist,
            o: mesh - f1,
            guide: -(mesh + w + push),
            guide_moment: -(cross(k, mesh) + cross(self.g2r, w) + cross(self.lr, push)),
            mesh,
            tooth_load: ft.abs() * self.sec_alpha,
            flank: if ft >= 0.0 { 1.0 } else { -1.0 },
        }
    }

    /// The driver torque by virtual power, no reaction computed:
    /// T q̇ + F₁·v_G1 − I₁ q̈ q̇ + T_resist q̇ + (W + F_L)·v = 0 (q̇ ≠ 0; v the rack's
    /// velocity; the guide and the tooth force do no work).
    #[inline(never)]
    pub fn driver_action(&self, m: &RackPinionHandMotion, loads: &RackPinionLoads) -> f64 {
        let p1 = (self.w1 - m.pinion.cg_acc * self.m1).dot(&m.pinion.cg_vel)
            + (loads.resist - self.i1 * m.pinion.alpha) * m.pinion.omega;
        let p2 = (self.w2 - m.rack.cg_acc * self.m2 + loads.push).dot(&m.rack.cg_vel);
        -(p1 + p2) / m.pinion.omega
    }

    /// Zhukovski's I* = I₁ + m₁|r₁|² + m₂ (κ r)² = I_O1 + m₂ r² (kg·m²), constant: the rack
    /// moves at κ r u per unit q̇; dI*/dq = 0.
    #[inline(never)]
    pub fn reduced(&self, _q: f64) -> Option<HandReduced> {
        Some(HandReduced {
            inertia: self.inertia,
            inertia_derivative: 0.0,
        })
    }

    /// M* = r₁ × m₁g + T_resist + κ r (m₂ g + F_L)·u, r₁ = G₁ − O turned by q (one
    /// `sin_cos`).
    #[inline(always)]
    fn moment_of(&self, q: f64, loads: &RackPinionLoads) -> f64 {
        let r1 = rotate(turn(q), self.g1);
        cross(r1, self.w1) + loads.resist + (self.w2 + loads.push).dot(&self.ku)
    }

    /// Zhukovski's reduced moment M*(q) of the loads and gravity (N·m).
    #[inline(never)]
    pub fn reduced_moment(&self, q: f64, loads: &RackPinionLoads) -> Option<f64> {
        Some(self.moment_of(q, loads))
    }

    /// The direct problem: q̈ = (T + M*)/I* (dI*/dq = 0: no q̇² term).
    #[inline(never)]
    pub fn acceleration(
        &self,
        q: f64,
        _qd: f64,
        driver: f64,
        loads: &RackPinionLoads,
    ) -> Option<f64> {
        Some((driver + self.moment_of(q, loads)) / self.inertia)
    }
}
