//! The RRR and RRP dyads in lanes: the twins of [`crate::kernel::kinematics::solve_chain`]
//! for those kinds (positions as [`crate::kernel::dyad::circle_circle`] and
//! [`crate::kernel::dyad::circle_line_along`], rates in natural coordinates as
//! [`crate::kernel::natural::rrr_rates`] and [`crate::kernel::natural::rrp_rates`]).

use super::simd::{Backend, Bits, Mask, ALL, L, V2L};
use super::{dir_of, inlined, pin, place_by_point, LinkLanes};
use crate::kernel::constraints::{JointGeom, Level};
use crate::kernel::dyad::Solver;
use crate::kernel::linalg::SINGULAR_CONDITION;
use crate::kernel::link_state::V2;

/// The band, relative to the discriminant's scale, below which a lane is masked: 10⁻⁸
/// (the scalar NoAssembly threshold is −10⁻¹² of that scale, `kernel::dyad`'s
/// `TANGENT_TOL`). Within it the point is less than 10⁻⁴ of a radius from a tangency, where
/// the square root amplifies the roundoff by which the inputs of lanes and scalar differ
/// beyond 10⁻¹² of the dyad's size.
const NO_ASSEMBLY_GUARD: f64 = 1e-8;

/// The threshold of the scalar `Singular` test in the mask: [`SINGULAR_CONDITION`] less a
/// relative margin of 10⁻⁶, so that a lane whose estimate differs from the scalar one by
/// roundoff is masked whenever the scalar test may fail.
const MASK_CONDITION: f64 = SINGULAR_CONDITION * (1.0 - 1e-6);

/// The dyad's own condition estimate beyond which a lane is masked although the scalar
/// kernel succeeds: κ = ‖M‖²_F / |det M| of the RRR system [perp(e₁) −perp(e₂)]
/// (= (|e₁|² + |e₂|²)/|e₁ × e₂|), and of the RRP system with its second column scaled by
/// |e₁| (= 2|e₁|/|x|). Velocities amplify the roundoff by which lanes and scalar differ (an
/// ulp of [`super::sin_cos`]) by up to κ, accelerations by κ², so that beyond about 30 the
/// two could differ by more than 10⁻¹² of the rates' magnitude (a lane at κ = 66 was measured
/// 1.8·10⁻¹² apart). κ ≥ 30 means a transmission angle below 4° to 10° (an RRR with links
/// one to five times as long as each other), an RRP rod within 4° of the normal to its
/// guide: the neighbourhood of a change point, where the scalar kernels' own results carry
/// that much roundoff.
pub const PRECISE_CONDITION: f64 = 30.0;

/// Solve a closed-form RRR or RRP dyad up to `upto` in four configurations, formula for
/// formula as [`crate::kernel::kinematics::solve_chain`]: the links placed on the drawing's
/// branch `sign` (±1, [`crate::kernel::dyad::branch_quantity`]), then their velocities and
/// accelerations in natural coordinates (`kernel::natural`'s module docs), `scale` the
/// length scale L (m) of the RRP condition estimate.
///
/// The mask holds every lane where the scalar kernel returns `Err`, with a margin, and the
/// lanes too ill-conditioned to agree with it to 10⁻¹²:
/// - `NoAssembly`: RRR, |B − A|² = 0 or H = r₁² |d|² − k² below 10⁻⁸ max(r₁², r₂²) |d|²
///   (the scalar fails below −10⁻¹² of the same); RRP, r² − h² below 10⁻⁸ r² (the scalar
///   fails below −10⁻¹² r²);
/// - `Singular` (from [`Level::Velocity`] on, as the scalar): RRR, ‖M‖²_F ≥ 30 |det M|
///   ([`PRECISE_CONDITION`], which contains the scalar test of
///   [`crate::kernel::linalg::Inverse2::new`] at [`SINGULAR_CONDITION`]); RRP, the test of
///   [`crate::kernel::natural::SlideFrame::new`], |e₁|² + L² ≥ κ |x L| with
///   κ = [`SINGULAR_CONDITION`]·(1 − 10⁻⁶), and 2|e₁| ≥ 30 |x|; either not finite;
/// - from [`Level::Velocity`] on, a non-finite position, velocity or acceleration of
///   either link (positions alone are tested by their caller, on the points it publishes);
/// - every lane for another solver kind.
#[allow(clippy::too_many_arguments)]
#[inline(always)]
pub fn solve_chain_lanes<B: Backend>(
    solver: Solver,
    joints: &[JointGeom],
    s: &mut [LinkLanes<B>],
    sign: f64,
    scale: f64,
    upto: Level,
) -> Mask {
    let (b1, b2, mask) = match solver {
        Solver::Rrr { b1, b2, ja, jc, jb } => {
            (b1, b2, rrr(joints, s, [b1, b2], [ja, jc, jb], sign, upto))
        }
        Solver::Rrp { b1, b2, ja, jc, jp } => (
            b1,
            b2,
            rrp(joints, s, [b1, b2], [ja, jc, jp], sign, scale, upto),
        ),
        _ => return ALL,
    };
    if !matches!(upto, Level::Velocity | Level::Acceleration) {
        // Positions alone feed the points (`points_many`), which test what they publish
        // as the scalar `points` does: the states are not tested here, so that a link no
        // point lies on is not placed at all (its placement folds away unread).
        return mask.mask();
    }
    let mut sum = L::splat(0.0);
    for b in [&s[b1], &s[b2]] {
        sum += b.pos.x + b.pos.y + b.rot.x + b.rot.y;
        if matches!(upto, Level::Velocity | Level::Acceleration) {
            sum += b.vel.x + b.vel.y + b.omega;
            if upto == Level::Acceleration {
                sum += b.acc.x + b.acc.y + b.alpha;
            }
        }
    }
    mask.or(sum.non_finite()).mask()
}

/// The solved link on the other side of joint `g` from `body`.
#[inline(always)]
fn solved_link(g: &JointGeom, body: usize) -> usize {
    if g.b == body {
        g.a
    } else {
        g.b
    }
}

/// The local vector in `body` of joint `g`'s point.
#[inline(always)]
fn local_in(g: &JointGeom, body: usize) -> V2 {
    if g.b == body {
        g.db
    } else {
        g.da
    }
}

/// The velocity and acceleration of the material point of link `l` now at `p`; zero on
/// the ground.
#[inline(always)]
fn point_rates<B: Backend>(s: &[LinkLanes<B>], l: usize, p: V2L<B>) -> (V2L<B>, V2L<B>) {
    if l == 0 {
        let z = V2L::splat(crate::kernel::link_state::zero());
        (z, z)
    } else {
        let r = p - s[l].pos;
        (s[l].vel_at(r), s[l].acc_at(r))
    }
}

/// Place a link from two of its points (local d1, d2, now at p1, p2), as
/// [`crate::kernel::dyad::place_by_two_points`]: the rotation (a·b, a × b)/|a|² with
/// a = d2 − d1 (shared, so 1/|a|² is one scalar division) and b = p2 − p1.
#[inline(always)]
fn place_by_two_points<B: Backend>(s: &mut LinkLanes<B>, d1: V2, d2: V2, p1: V2L<B>, p2: V2L<B>) {
    let a = d2 - d1;
    let b = p2 - p1;
    let inv = 1.0 / a.norm_squared();
    let rot = V2L::new(b.dot_v(a), b.y * a.x - b.x * a.y) * inv;
    place_by_point(s, rot, d1, p1);
}

/// The lanes that fail the condition test `norm2 < limit` (a NaN fails; see
/// [`solve_chain_lanes`]).
#[inline(always)]
fn ill_conditioned<B: Backend>(norm2: L<B>, limit: L<B>) -> Bits<B> {
    norm2.not_less(limit)
}

/// An RRR dyad: positions, then rates (`natural::rrr_rates`).
#[inline(always)]
fn rrr<B: Backend>(
    joints: &[JointGeom],
    s: &mut [LinkLanes<B>],
    [b1, b2]: [usize; 2],
    [ja, jc, jb]: [usize; 3],
    sign: f64,
    upto: Level,
) -> Bits<B> {
    let (a, da) = pin(&joints[ja], s, b1);
    let (b, db) = pin(&joints[jb], s, b2);
    let gc = &joints[jc];
    let (dc1, dc2) = if gc.a == b1 {
        (gc.da, gc.db)
    } else {
        (gc.db, gc.da)
    };
    let (r1sq, r2sq) = ((dc1 - da).norm_squared(), (dc2 - db).norm_squared());
    // circle_circle: X = A + (k d + sign √H perp(d)) / |d|².
    let d = b - a;
    let l2 = d.norm_squared();
    let inv = 1.0 / l2;
    let k = (l2 + r1sq - r2sq) * 0.5;
    let h2 = r1sq * l2 - k * k;
    let guard = l2 * (r1sq.max(r2sq) * NO_ASSEMBLY_GUARD);
    let mask = h2.less(guard).or(l2.not_greater(L::splat(0.0)));
    let h2 = h2.max(L::splat(0.0));
    let c = a + (d * k + d.perp() * (h2.sqrt() * sign)) * inv;
    place_by_two_points(&mut s[b1], da, dc1, a, c);
    place_by_two_points(&mut s[b2], db, dc2, b, c);
    if !matches!(upto, Level::Velocity | Level::Acceleration) {
        return mask;
    }
    // natural::rrr_rates with its points [A, B, C] = our [a, c, b].
    let (la, lc) = (solved_link(&joints[ja], b1), solved_link(&joints[jb], b2));
    let (e1, e2) = (c - a, c - b);
    let (p1, p2) = (e1.perp(), e2.perp());
    // M = [[p1.x, −p2.x], [p1.y, −p2.y]]
    let (m00, m01, m10, m11) = (p1.x, -p2.x, p1.y, -p2.y);
    let det = m00 * m11 - m01 * m10;
    let norm2 = (m00 * m00 + m10 * m10) + (m01 * m01 + m11 * m11);
    let mask = mask.or(ill_conditioned(norm2, det.abs() * PRECISE_CONDITION));
    let inv_det = 1.0 / det;
    let solve = inlined(
        #[inline(always)]
        |x: L<B>, y: L<B>| ((m11 * x - m01 * y) * inv_det, (m00 * y - m10 * x) * inv_det),
    );
    let ((va, aa), (vc, ac)) = (point_rates(s, la, a), point_rates(s, lc, b));
    let dv = vc - va;
    let (w1, w2) = solve(dv.x, dv.y);
    let (da, dc) = (local_in(&joints[ja], b1), local_in(&joints[jb], b2));
    s[b1].set_velocity_at(da, a, va, w1);
    s[b2].set_velocity_at(dc, b, vc, w2);
    if upto == Level::Acceleration {
        let rhs = ac - aa + e1 * (w1 * w1) - e2 * (w2 * w2);
        let (al1, al2) = solve(rhs.x, rhs.y);
        s[b1].set_acceleration_at(da, a, aa, al1);
        s[b2].set_acceleration_at(dc, b, ac, al2);
    }
    mask
}

/// An RRP dyad: positions (`dyad::rrp`), then rates (`natural::rrp_rates`).
#[allow(clippy::too_many_arguments)]
#[inline(always)]
fn rrp<B: Backend>(
    joints: &[JointGeom],
    s: &mut [LinkLanes<B>],
    [b1, b2]: [usize; 2],
    [ja, jc, jp]: [usize; 3],
    sign: f64,
    scale: f64,
    upto: Level,
) -> Bits<B> {
    let (a, da) = pin(&joints[ja], s, b1);
    let gp = &joints[jp];
    let guide = if gp.b == b2 { gp.a } else { gp.b };
    let gc = &joints[jc];
    let (dc1, dc2) = if gc.a == b1 {
        (gc.da, gc.db)
    } else {
        (gc.db, gc.da)
    };
    let (q, dq) = if gp.b == b2 {
        (super::point_of(s, gp.a, gp.da), gp.db)
    } else {
        (super::point_of(s, gp.b, gp.db), gp.da)
    };
    let p = q + dir_of(s, guide, dc2 - dq);
    let u = dir_of(s, guide, gp.axis);
    // circle_line_along: the foot at t₀ = d·u, h = u × d, x = sign √(r² − h²).
    let rsq = (dc1 - da).norm_squared();
    let d = a - p;
    let t0 = d.dot(u);
    let h = u.cross(d);
    let w2 = rsq - h * h;
    let mask = w2.less(L::splat(NO_ASSEMBLY_GUARD * rsq));
    let x = w2.max(L::splat(0.0)).sqrt() * sign;
    let c = p + u * (t0 + x);
    let y = -h;
    place_by_two_points(&mut s[b1], da, dc1, a, c);
    s[b2].rot = if guide == 0 {
        V2L::splat(V2::new(1.0, 0.0))
    } else {
        s[guide].rot
    };
    s[b2].pos = c - dir_of(s, guide, dc2);
    if !matches!(upto, Level::Velocity | Level::Acceleration) {
        return mask;
    }
    let (la, lg) = (solved_link(&joints[ja], b1), solved_link(gp, b2));
    let u = dir_of(s, lg, gp.axis);
    // SlideFrame::new: κ_F = (|e₁|² + L²)/|x L|.
    let e1sq = x * x + y * y;
    let mask = mask
        .or(ill_conditioned(
            e1sq + scale * scale,
            (x * scale).abs() * MASK_CONDITION,
        ))
        .or(ill_conditioned(
            e1sq * 4.0,
            x * x * (PRECISE_CONDITION * PRECISE_CONDITION),
        ));
    let inv_x = 1.0 / x;
    // (ω₁, ṡ) with [perp(e₁) −u] (ω₁, ṡ)ᵀ = b: ω₁ = (u × b)/x, ṡ = −(b·u + y ω₁).
    let solve = inlined(
        #[inline(always)]
        |b: V2L<B>| {
            let w = u.cross(b) * inv_x;
            (w, -(b.dot(u) + y * w))
        },
    );
    let (da, dc) = (local_in(&joints[ja], b1), local_in(&joints[jc], b2));
    let ((va, aa), (vg, ag)) = (point_rates(s, la, a), point_rates(s, lg, c));
    let (wg, alg) = if lg == 0 {
        (L::splat(0.0), L::splat(0.0))
    } else {
        (s[lg].omega, s[lg].alpha)
    };
    let (w1, sd) = solve(vg - va);
    s[b1].set_velocity_at(da, a, va, w1);
    let vc = vg + u * sd;
    if lg == 0 {
        s[b2].omega = L::splat(0.0);
        s[b2].vel = vc;
    } else {
        s[b2].set_velocity_at(dc, c, vc, wg);
    }
    if upto == Level::Acceleration {
        let coriolis = if lg == 0 {
            V2L::splat(crate::kernel::link_state::zero())
        } else {
            u.perp() * ((wg * 2.0) * sd)
        };
        let (b0, b1_) = solve(ag + coriolis - aa);
        let kk = y * inv_x;
        let (k0, k1) = (kk, -(x + y * kk));
        let w1sq = w1 * w1;
        let (al1, sdd) = (b0 + k0 * w1sq, b1_ + k1 * w1sq);
        s[b1].set_acceleration_at(da, a, aa, al1);
        let ac = ag + coriolis + u * sdd;
        if lg == 0 {
            s[b2].alpha = L::splat(0.0);
            s[b2].acc = ac;
        } else {
            s[b2].set_acceleration_at(dc, c, ac, alg);
        }
    }
    mask
}
