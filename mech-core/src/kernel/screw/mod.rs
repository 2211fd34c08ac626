//! Closed-form rates and reactions of the closed-form groups, by joint screws
//! (`docs/theory.md` §3, §4).
//!
//! Every closed-form group is a serial chain of three elementary joint screws from a
//! solved link B₀ to a solved link B₃ through its moving links (a dyad: B₁, B₂; a
//! single-link slot group: B₁ and the virtual slider block of the slot), or one screw
//! with a known rate from a solved link to a driven crank or slider. With planar twists
//! t = (ω, v_O) taken at one point O of the group (v_O: the velocity of the body point
//! at O) and the unit screws of the joints,
//! - rotation about the joint point P: $ = (1, perp(O − P)),
//! - slide along the axis u (unit, turning with the guide): $ = (0, u),
//!
//! the twist of each link is the previous one plus the joint's: t_k = t_{k−1} + ρ_k $_k.
//! Closing the loop gives the velocities and, differentiated, the accelerations, with the
//! same 3×3 matrix S = [$₁ $₂ $₃]:
//! - S ρ = t₃ − t₀,
//! - S ρ̇ = â₃ − â₀ − Σ ρ_k (t_{k−1} × $_k),
//!
//! where â = (α, v̇_O) is the spatial acceleration and (ω₁, v₁) × (ω₂, v₂) =
//! (0, ω₁ perp(v₂) − ω₂ perp(v₁)) the planar spatial cross product ($_k is fixed in the
//! link before it, so d$_k/dt = t_{k−1} × $_k).
//!
//! The reactions come from the transpose of that same matrix. With W_k = (F, M_O) the
//! wrench that B_{k−1} exerts on B_k through joint k, and F_k the applied and inertia
//! wrench on B_k, equilibrium of B₁ and B₂ gives W₂ = W₁ + F₁, W₃ = W₂ + F₂, and a joint
//! transmits no power along its own screw (W_k · $_k = 0), so
//! Sᵀ W₁ = −(0, F₁·$₂, (F₁ + F₂)·$₃). For a driven link W₁ = −F₁ and the motor action is
//! W₁·$₁. One small system per group (reduced to 2×2 by a pivot, see `ChainSystem`) serves velocities, accelerations and
//! reactions; its condition estimate gives `Singular` near a change point.

use crate::kernel::constraints::{Drive, JointGeom, Level};
use crate::kernel::kinetostatics::{Reaction, Wrench};
use crate::kernel::linalg::Inverse2;
use crate::kernel::link_state::{cross, dir_of, perp, point_of, LinkState, V2};
use crate::MechError;

/// A planar twist (ω rad/s, v_O m/s) at a group's point O, or its time derivative, the
/// spatial acceleration (α, v̇_O).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Twist {
    /// ω (rad/s) or α (rad/s²).
    pub w: f64,
    /// The velocity (acceleration) of the body point at O.
    pub v: V2,
}

impl Twist {
    /// t + k s.
    #[inline(always)]
    fn plus(self, k: f64, s: Twist) -> Twist {
        Twist {
            w: self.w + k * s.w,
            v: self.v + s.v * k,
        }
    }
    /// The planar spatial cross product (ω₁, v₁) × (ω₂, v₂) = (0, ω₁ perp(v₂) − ω₂ perp(v₁)).
    #[inline(always)]
    fn cross(self, s: Twist) -> Twist {
        Twist {
            w: 0.0,
            v: perp(s.v) * self.w - perp(self.v) * s.w,
        }
    }
    /// The twist of a link's state at the point `o`: (ω, v + ω perp(o − pos)).
    #[inline(always)]
    fn of(s: &LinkState, o: V2) -> Twist {
        Twist {
            w: s.omega,
            v: s.vel_at(o - s.pos),
        }
    }
    /// The spatial acceleration of a link's state at `o`: (α, a(o) − ω perp(v_O)).
    #[inline(always)]
    fn acc_of(s: &LinkState, o: V2) -> Twist {
        let r = o - s.pos;
        Twist {
            w: s.alpha,
            v: s.acc_at(r) - perp(s.vel_at(r)) * s.omega,
        }
    }
    /// The twist of link `l` at `o`, zero for the ground (link 0), whose state is not read.
    #[inline(always)]
    fn of_link(s: &[LinkState], l: usize, o: V2) -> Twist {
        if l == 0 {
            Twist::default()
        } else {
            Twist::of(&s[l], o)
        }
    }
    /// The spatial acceleration of link `l` at `o`, zero for the ground.
    #[inline(always)]
    fn acc_of_link(s: &[LinkState], l: usize, o: V2) -> Twist {
        if l == 0 {
            Twist::default()
        } else {
            Twist::acc_of(&s[l], o)
        }
    }
    /// Power of the wrench `w` (at O) on this twist, W.
    #[inline(always)]
    fn power(self, w: &Force) -> f64 {
        w.f.dot(&self.v) + w.m * self.w
    }
}

/// Store a twist `t` (at `o`) as a link's velocity: v = v_O + ω perp(pos − o).
#[inline(always)]
fn set_velocity(s: &mut LinkState, t: Twist, o: V2) {
    s.set_velocity_through(o, t.v, t.w);
}

/// Store a spatial acceleration `a` (at `o`) as a link's acceleration:
/// a = v̇_O + α perp(pos − o) + ω perp(v), the velocity already stored.
#[inline(always)]
fn set_acceleration(s: &mut LinkState, a: Twist, o: V2) {
    s.alpha = a.w;
    s.acc = a.v + perp(s.pos - o) * a.w + perp(s.vel) * s.omega;
}

/// A wrench (F N, M_O N·m about the group's point O).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
struct Force {
    f: V2,
    m: f64,
}

impl Force {
    /// A link wrench (moment about its anchor `pos`) moved to O: M_O = M + (pos − O) × F.
    #[inline(always)]
    fn at(w: &Wrench, pos: V2, o: V2) -> Force {
        let f = V2::new(w.x, w.y);
        Force {
            f,
            m: w.z + cross(pos - o, f),
        }
    }
    /// Back to a link wrench about the anchor `pos`.
    #[inline(always)]
    fn about(self, pos: V2, o: V2) -> Wrench {
        Wrench::new(self.f.x, self.f.y, self.m - cross(pos - o, self.f))
    }
    #[inline(always)]
    fn plus(self, o: Force) -> Force {
        Force {
            f: self.f + o.f,
            m: self.m + o.m,
        }
    }
}

/// One elementary joint screw: the rotation about a joint's point, or the slide along its axis.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct JointScrew {
    /// The joint (index into the joint geometry).
    pub joint: usize,
    /// A slide along the axis (true) or a rotation about the point (false).
    pub slide: bool,
}

impl JointScrew {
    /// The unit screw at `o`: (1, perp(o − P)) or (0, u), u = R(φ_a) axis.
    #[inline(always)]
    fn at(self, joints: &[JointGeom], s: &[LinkState], o: V2) -> Twist {
        let g = &joints[self.joint];
        if self.slide {
            Twist {
                w: 0.0,
                v: dir_of(s, g.a, g.axis),
            }
        } else {
            Twist {
                w: 1.0,
                v: perp(o - point_of(s, g.b, g.db)),
            }
        }
    }
    /// The joint's point now (the point of its second link), m.
    #[inline(always)]
    fn point(self, joints: &[JointGeom], s: &[LinkState]) -> V2 {
        let g = &joints[self.joint];
        point_of(s, g.b, g.db)
    }
}

/// No link: the virtual slider block between the two screws of a pin in a slot.
pub const VIRTUAL: usize = usize::MAX;

/// A closed-form group as a chain of three joint screws from the solved link `from` to
/// the solved link `to` (module docs).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Chain {
    /// B₀, solved.
    pub from: usize,
    /// B₃, solved.
    pub to: usize,
    /// $₁, $₂, $₃ in chain order.
    pub screws: [JointScrew; 3],
    /// B₁ and B₂ (B₂ = [`VIRTUAL`] for a single-link slot group).
    pub links: [usize; 2],
    /// A rotation screw whose point is taken as the origin O (the middle one when it is a
    /// rotation): its column of S is then (1, 0, 0), and S reduces to a 2×2 block.
    pub pivot: usize,
}

/// A link driven by one input through one joint screw with a known rate.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Driven {
    /// The solved link it is jointed to.
    pub from: usize,
    /// The driven link.
    pub body: usize,
    /// The driver joint's screw.
    pub screw: JointScrew,
    /// The input index.
    pub input: usize,
    /// A crank on the ground turning about its anchor (the driver's pin is the link's
    /// first point): its anchor never moves.
    pub pinned: bool,
    /// Keep its [`crate::kernel::link_state::LinkState::angle`] over turns (a gear train reads it;
    /// set by the plan only when the mechanism meshes).
    pub track: bool,
}

/// The chain matrix S at the current positions, reduced by its pivot p: with O at the
/// pivot's point, column p is (1, 0, 0), so the translation rows of S ρ = b read
/// ρ_i v_i + ρ_j v_j = b_v (the 2×2 block M = [v_i v_j], i, j ≠ p) and the rotation row
/// gives ρ_p = b_ω − ρ_i ω_i − ρ_j ω_j. The transpose is solved the same way. M's
/// rotation columns are divided by the length scale L so that its condition estimate is
/// dimensionless.
#[derive(Clone, Copy, Debug)]
struct ChainSystem {
    o: V2,
    sc: [Twist; 3],
    pivot: usize,
    others: [usize; 2],
    col_scale: [f64; 2],
    inv: Inverse2,
}

impl ChainSystem {
    #[inline(always)]
    fn new(
        c: &Chain,
        joints: &[JointGeom],
        s: &[LinkState],
        scale: f64,
    ) -> Result<Self, MechError> {
        let p = c.pivot;
        let others = [[1, 2], [0, 2], [0, 1]][p];
        let o = c.screws[p].point(joints, s);
        let mut sc = [Twist {
            w: 1.0,
            v: V2::zeros(),
        }; 3];
        for k in others {
            sc[k] = c.screws[k].at(joints, s, o);
        }
        let col_scale = others.map(|k| if c.screws[k].slide { 1.0 } else { 1.0 / scale });
        let (a, b) = (
            sc[others[0]].v * col_scale[0],
            sc[others[1]].v * col_scale[1],
        );
        let inv = Inverse2::new([[a.x, b.x], [a.y, b.y]])?;
        Ok(ChainSystem {
            o,
            sc,
            pivot: p,
            others,
            col_scale,
            inv,
        })
    }
    /// ρ from S ρ = b.
    #[inline(always)]
    fn solve(&self, b: Twist) -> [f64; 3] {
        let [i, j] = self.others;
        let x = self.inv.solve([b.v.x, b.v.y]);
        let (ri, rj) = (x[0] * self.col_scale[0], x[1] * self.col_scale[1]);
        let mut rho = [0.0; 3];
        rho[i] = ri;
        rho[j] = rj;
        rho[self.pivot] = b.w - self.sc[i].w * ri - self.sc[j].w * rj;
        rho
    }
    /// W from Sᵀ W = c (W·$_k = c_k).
    #[inline(always)]
    fn solve_transpose(&self, c: [f64; 3]) -> Force {
        let [i, j] = self.others;
        let m = c[self.pivot];
        let y = [
            (c[i] - self.sc[i].w * m) * self.col_scale[0],
            (c[j] - self.sc[j].w * m) * self.col_scale[1],
        ];
        let f = self.inv.solve_transpose(y);
        Force {
            f: V2::new(f[0], f[1]),
            m,
        }
    }
    /// t + ρ $_k.
    #[inline(always)]
    fn step(&self, t: Twist, k: usize, rho: f64) -> Twist {
        if k == self.pivot {
            Twist {
                w: t.w + rho,
                v: t.v,
            }
        } else {
            t.plus(rho, self.sc[k])
        }
    }
    /// t × $_k.
    #[inline(always)]
    fn bias(&self, t: Twist, k: usize) -> Twist {
        if k == self.pivot {
            Twist {
                w: 0.0,
                v: -perp(t.v),
            }
        } else {
            t.cross(self.sc[k])
        }
    }
    /// W·$_k.
    #[inline(always)]
    fn power(&self, k: usize, w: &Force) -> f64 {
        if k == self.pivot {
            w.m
        } else {
            self.sc[k].power(w)
        }
    }
}

/// Velocities (and accelerations when `upto` is [`Level::Acceleration`]) of a chain's
/// links, positions placed and the solved links' rates known. Nothing at
/// [`Level::Position`]. `Singular` near a change point (condition ≥ 1e6).
#[cfg_attr(debug_assertions, inline)]
#[cfg_attr(not(debug_assertions), inline(always))]
pub fn chain_rates(
    c: &Chain,
    joints: &[JointGeom],
    s: &mut [LinkState],
    scale: f64,
    upto: Level,
) -> Result<(), MechError> {
    if !matches!(upto, Level::Velocity | Level::Acceleration) {
        return Ok(());
    }
    let sys = ChainSystem::new(c, joints, s, scale)?;
    let o = sys.o;
    let t0 = Twist::of_link(s, c.from, o);
    let t3 = Twist::of_link(s, c.to, o);
    let rho = sys.solve(t3.plus(-1.0, t0));
    let t1 = sys.step(t0, 0, rho[0]);
    let t2 = sys.step(t1, 1, rho[1]);
    let [l1, l2] = c.links;
    set_velocity(&mut s[l1], t1, o);
    if l2 != VIRTUAL {
        set_velocity(&mut s[l2], t2, o);
    }
    if upto != Level::Acceleration {
        return Ok(());
    }
    let bias = [sys.bias(t0, 0), sys.bias(t1, 1), sys.bias(t2, 2)];
    let a0 = Twist::acc_of_link(s, c.from, o);
    let a3 = Twist::acc_of_link(s, c.to, o);
    let mut b = a3.plus(-1.0, a0);
    for k in 0..3 {
        b = b.plus(-rho[k], bias[k]);
    }
    let rhod = sys.solve(b);
    let a1 = sys.step(a0, 0, rhod[0]).plus(rho[0], bias[0]);
    set_acceleration(&mut s[l1], a1, o);
    if l2 != VIRTUAL {
        let a2 = sys.step(a1, 1, rhod[1]).plus(rho[1], bias[1]);
        set_acceleration(&mut s[l2], a2, o);
    }
    Ok(())
}

/// The orientation of a driver's screw along the chain: +1 when the chain runs from the
/// joint's first link a to its second b (q̇ $ is the twist of b relative to a), else −1.
#[inline(always)]
fn orientation(g: &JointGeom, from: usize) -> f64 {
    if g.a == from {
        1.0
    } else {
        -1.0
    }
}

/// Velocity (and acceleration) of a driven link: t = t₀ + σ q̇ $, â = â₀ + σ (q̈ $ + q̇ t₀ × $).
#[cfg_attr(debug_assertions, inline)]
#[cfg_attr(not(debug_assertions), inline(always))]
pub fn driven_rates(
    d: &Driven,
    joints: &[JointGeom],
    s: &mut [LinkState],
    drive: Drive,
    upto: Level,
) -> Result<(), MechError> {
    if !matches!(upto, Level::Velocity | Level::Acceleration) {
        return Ok(());
    }
    let g = &joints[d.screw.joint];
    let sigma = orientation(g, d.from);
    let (qd, qdd) = (sigma * drive.1[d.input], sigma * drive.2[d.input]);
    if d.from == 0 && !d.screw.slide {
        // A crank on the ground: ω = σ q̇ about the fixed pin P, v = ω perp(r),
        // a = α perp(r) − ω² r with r from P to the anchor.
        let p = if g.a == 0 { g.da } else { g.db };
        let b = &mut s[d.body];
        b.omega = qd;
        if d.pinned {
            // The anchor is the pin: at rest. −0 (not +0) so that adding it folds away.
            b.pos = p;
            b.vel = V2::new(-0.0, -0.0);
            if upto == Level::Acceleration {
                b.alpha = qdd;
                b.acc = V2::new(-0.0, -0.0);
            }
            return Ok(());
        }
        let r = b.pos - p;
        b.vel = perp(r) * qd;
        if upto == Level::Acceleration {
            b.alpha = qdd;
            b.acc = perp(r) * qdd - r * (qd * qd);
        }
        return Ok(());
    }
    let o = d.screw.point(joints, s);
    let sc = d.screw.at(joints, s, o);
    let t0 = Twist::of_link(s, d.from, o);
    set_velocity(&mut s[d.body], t0.plus(qd, sc), o);
    if upto == Level::Acceleration {
        let a = Twist::acc_of_link(s, d.from, o)
            .plus(qdd, sc)
            .plus(qd, t0.cross(sc));
        set_acceleration(&mut s[d.body], a, o);
    }
    Ok(())
}

/// The reaction at joint `j` (by a on b, `docs/conventions.md`) from the wrench `w` (at
/// `o`) that link `before` exerts through it on the next link of the chain: the force,
/// and the moment about the joint's point (zero but for a prismatic joint).
#[inline(always)]
fn reaction(
    g: &JointGeom,
    s: &[LinkState],
    before: usize,
    w: Force,
    o: V2,
    moment: bool,
) -> Reaction {
    let sigma = orientation(g, before);
    let moment = if moment {
        sigma * (w.m - cross(point_of(s, g.b, g.db) - o, w.f))
    } else {
        0.0
    };
    Reaction {
        force: w.f * sigma,
        moment,
    }
}

/// d'Alembert for a chain: the reaction at each of its joints into `out` (joint order),
/// and the reactions on the solved links `from` and `to` added to their wrenches in `f`
/// (`f` holds every link's applied and inertia wrench, plus the reactions of the groups
/// solved before, about its anchor). Called from the outermost group inward.
#[cfg_attr(debug_assertions, inline)]
#[cfg_attr(not(debug_assertions), inline(always))]
pub fn chain_reactions(
    c: &Chain,
    joints: &[JointGeom],
    s: &[LinkState],
    f: &mut [Wrench],
    scale: f64,
    out: &mut [Reaction],
) -> Result<(), MechError> {
    let sys = ChainSystem::new(c, joints, s, scale)?;
    let o = sys.o;
    let [l1, l2] = c.links;
    let f1 = Force::at(&f[l1], s[l1].pos, o);
    let f2 = if l2 != VIRTUAL {
        Force::at(&f[l2], s[l2].pos, o)
    } else {
        Force::default()
    };
    let f12 = f1.plus(f2);
    let w1 = sys.solve_transpose([0.0, -sys.power(1, &f1), -sys.power(2, &f12)]);
    let ws = [w1, w1.plus(f1), w1.plus(f12)];
    let before = [c.from, l1, l2];
    for k in 0..3 {
        let j = c.screws[k].joint;
        // A slot's two screws carry one wrench: report it at the first, whose preceding
        // link is a real one. Only a prismatic joint reports a moment.
        if k > 0 && c.screws[k - 1].joint == j {
            continue;
        }
        let prismatic = c.screws[k].slide && !(k < 2 && c.screws[k + 1].joint == j);
        out[j] = reaction(&joints[j], s, before[k], ws[k], o, prismatic);
    }
    let back = Force { f: -w1.f, m: -w1.m };
    f[c.from] += back.about(s[c.from].pos, o);
    f[c.to] += ws[2].about(s[c.to].pos, o);
    Ok(())
}

/// d'Alembert for a driven link: the reaction at its driver joint into `out`, the motor
/// action into `drivers[input]` (torque or axial force by a on b), and the reaction on
/// the solved link added to `f`. W₁ = −F₁; the motor action is σ W₁·$, the rest of W₁ the
/// joint's reaction (a prismatic driver's axial component is the motor force, not part of
/// the reaction).
#[cfg_attr(debug_assertions, inline)]
#[cfg_attr(not(debug_assertions), inline(always))]
pub fn driven_reactions(
    d: &Driven,
    joints: &[JointGeom],
    s: &[LinkState],
    f: &mut [Wrench],
    out: &mut [Reaction],
    drivers: &mut [f64],
) {
    let g = &joints[d.screw.joint];
    let o = d.screw.point(joints, s);
    let sc = d.screw.at(joints, s, o);
    // O is the joint's point on its second link: the body's anchor when its local vector
    // there is zero (a literal zero in the generated code, so the test folds), and then
    // the body's wrench is already about O.
    let w1 = if g.b == d.body && g.db == crate::kernel::link_state::zero() {
        Force {
            f: V2::new(f[d.body].x, f[d.body].y),
            m: f[d.body].z,
        }
    } else {
        Force::at(&f[d.body], s[d.body].pos, o)
    };
    let w1 = Force { f: -w1.f, m: -w1.m };
    let sigma = orientation(g, d.from);
    // A rotation about O itself, $ = (1, 0) at O, takes the moment alone.
    let action = if d.screw.slide { sc.power(&w1) } else { w1.m };
    drivers[d.input] = sigma * action;
    // Take the motor's component out: what is left does no work along the screw.
    let constraint = if d.screw.slide {
        Force {
            f: w1.f - sc.v * action,
            m: w1.m,
        }
    } else {
        Force { f: w1.f, m: 0.0 }
    };
    out[d.screw.joint] = reaction(g, s, d.from, constraint, o, d.screw.slide);
    f[d.from] += Force { f: -w1.f, m: -w1.m }.about(s[d.from].pos, o);
}

#[cfg(test)]
mod tests;
