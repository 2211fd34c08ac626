//! A driven crank or slider in lanes: the twin of
//! [`crate::kernel::kinematics::solve_driven`] (positions as `kernel::dyad`'s
//! `driven_revolute` and `driven_prismatic`, rates as [`crate::kernel::screw::driven_rates`]).

use super::simd::{sin_cos, Backend, Mask, ALL, L, NONE, V2L};
use super::{dir_of, pin, place_by_point, point_of, LinkLanes};
use crate::kernel::constraints::{JointGeom, Level};
use crate::kernel::dyad::Solver;
use crate::kernel::screw::Driven;

/// Solve a driven crank ([`Solver::DrivenRevolute`]) or slider
/// ([`Solver::DrivenPrismatic`]) up to `upto` in four configurations: its pose from the
/// inputs `q` (rad or m, one lane value per input), then its velocity and acceleration from
/// `qd` and `qdd` (rad/s, rad/s² or m/s, m/s²), formula for formula as
/// [`crate::kernel::kinematics::solve_driven`]:
/// - a crank: φ_b − φ_a = q − q_ref, (sin, cos) by [`super::sin_cos`], the link placed by
///   its pin; a slider: moved by (q − q_ref) u along the guide's axis u;
/// - on the ground about a fixed pin P: ω = σ q̇, α = σ q̈, v = ω perp(r), a = α perp(r) − ω² r
///   (r = anchor − P, σ = ±1 the driver's orientation); otherwise by the joint screw $ at
///   the joint point O: t = t₀ + σ q̇ $, â = â₀ + σ (q̈ $ + q̇ t₀ × $);
/// - with `driven.track`, φ over turns: the base's plus ±(q − q_ref) for a crank.
///
/// The scalar kernel never fails here: the mask holds the lanes with a non-finite result
/// from [`Level::Velocity`] on (positions alone are tested by their caller, on the points),
/// and every lane for another solver kind.
#[allow(clippy::too_many_arguments)]
#[inline(always)]
pub fn solve_driven_lanes<B: Backend>(
    solver: Solver,
    driven: &Driven,
    joints: &[JointGeom],
    s: &mut [LinkLanes<B>],
    q: &[L<B>],
    qd: &[L<B>],
    qdd: &[L<B>],
    upto: Level,
) -> Mask {
    let body = match solver {
        Solver::DrivenRevolute { body, joint, input } => {
            revolute(&joints[joint], s, body, q[input]);
            body
        }
        Solver::DrivenPrismatic { body, joint, input } => {
            prismatic(&joints[joint], s, body, q[input]);
            body
        }
        _ => return ALL,
    };
    let g = &joints[driven.screw.joint];
    if driven.track {
        let turn = if driven.screw.slide {
            L::splat(0.0)
        } else {
            q[driven.input] - g.q_ref
        };
        let base = if driven.from == 0 {
            L::splat(0.0)
        } else {
            s[driven.from].angle
        };
        s[body].angle = base + if g.b == driven.body { turn } else { -turn };
    }
    if !matches!(upto, Level::Velocity | Level::Acceleration) {
        // As `solve_chain_lanes`: positions alone are tested on the points published.
        return NONE;
    }
    driven_rates(driven, g, s, qd[driven.input], qdd[driven.input], upto);
    let b = &s[body];
    let mut sum = b.pos.x + b.pos.y + b.rot.x + b.rot.y + b.vel.x + b.vel.y + b.omega;
    if upto == Level::Acceleration {
        sum += b.acc.x + b.acc.y + b.alpha;
    }
    sum.non_finite().mask()
}

/// The pose of a link driven by its revolute joint `g` at the inputs' angles `q`.
#[inline(always)]
fn revolute<B: Backend>(g: &JointGeom, s: &mut [LinkLanes<B>], body: usize, q: L<B>) {
    let (sn, cs) = sin_cos(q - g.q_ref);
    let (other, rel) = if g.b == body {
        (g.a, V2L::new(cs, sn))
    } else {
        (g.b, V2L::new(cs, -sn))
    };
    let rot = if other == 0 {
        rel
    } else {
        s[other].rot.rotate_l(rel)
    };
    let (p, d) = pin(g, s, body);
    place_by_point(&mut s[body], rot, d, p);
}

/// The pose of a link driven by its prismatic joint `g` at the inputs' lengths `q`.
#[inline(always)]
fn prismatic<B: Backend>(g: &JointGeom, s: &mut [LinkLanes<B>], body: usize, q: L<B>) {
    let q = q - g.q_ref;
    let (guide, d_guide, d_body, q) = if g.b == body {
        (g.a, g.da, g.db, q)
    } else {
        (g.b, g.db, g.da, -q)
    };
    let rot = s[guide].rot;
    let p = point_of(s, guide, d_guide) + rot.rotate(g.axis) * q;
    place_by_point(&mut s[body], rot, d_body, p);
}

/// The rates of the driven link (see [`solve_driven_lanes`]), `qd`, `qdd` its input's.
#[inline(always)]
fn driven_rates<B: Backend>(
    d: &Driven,
    g: &JointGeom,
    s: &mut [LinkLanes<B>],
    qd: L<B>,
    qdd: L<B>,
    upto: Level,
) {
    let sigma = if g.a == d.from { 1.0 } else { -1.0 };
    let (qd, qdd) = (qd * sigma, qdd * sigma);
    let acc = upto == Level::Acceleration;
    if d.from == 0 && !d.screw.slide {
        let p = if g.a == 0 { g.da } else { g.db };
        let b = &mut s[d.body];
        b.omega = qd;
        if d.pinned {
            let z = V2L::splat(crate::kernel::link_state::zero());
            b.pos = V2L::splat(p);
            b.vel = z;
            if acc {
                b.alpha = qdd;
                b.acc = z;
            }
            return;
        }
        let r = b.pos - p;
        b.vel = r.perp() * qd;
        if acc {
            b.alpha = qdd;
            b.acc = r.perp() * qdd - r * (qd * qd);
        }
        return;
    }
    // The joint screw $ = (w, v) at O, the joint's point now.
    let o = point_of(s, g.b, g.db);
    let (sw, sv) = if d.screw.slide {
        (0.0, dir_of(s, g.a, g.axis))
    } else {
        (1.0, (o - point_of(s, g.b, g.db)).perp())
    };
    let zero = V2L::splat(crate::kernel::link_state::V2::zeros());
    // t₀ = the base's twist at O.
    let (t0w, t0v) = if d.from == 0 {
        (L::splat(0.0), zero)
    } else {
        let f = &s[d.from];
        (f.omega, f.vel_at(o - f.pos))
    };
    let (tw, tv) = (t0w + qd * sw, t0v + sv * qd);
    {
        let b = &mut s[d.body];
        b.omega = tw;
        b.vel = tv + (b.pos - o).perp() * tw;
    }
    if acc {
        // â₀ = (α, a(O) − ω perp(v_O)) of the base at O.
        let (a0w, a0v) = if d.from == 0 {
            (L::splat(0.0), zero)
        } else {
            let f = &s[d.from];
            let r = o - f.pos;
            (f.alpha, f.acc_at(r) - f.vel_at(r).perp() * f.omega)
        };
        // t₀ × $ = (0, ω₀ perp(v_$) − w_$ perp(v₀)).
        let cv = sv.perp() * t0w - t0v.perp() * sw;
        let (aw, av) = (a0w + qdd * sw, a0v + sv * qdd + cv * qd);
        let b = &mut s[d.body];
        b.alpha = aw;
        b.acc = av + (b.pos - o).perp() * aw + b.vel.perp() * b.omega;
    }
}
