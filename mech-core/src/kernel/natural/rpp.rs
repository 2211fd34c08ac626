//! The RPP dyad's kernels (their derivation: the folder's docs, [`super`]).

use super::prp::{axes_inverse, set_acceleration, set_velocity};
use super::DyadSystem;
use super::{about, about_point, local_in, pin_point, point_rates, push, reported, solved_link};
use crate::kernel::constraints::{JointGeom, Level};
use crate::kernel::kinetostatics::{Reaction, Wrench};
use crate::kernel::link_state::{cross, dir_of, perp, point_of, LinkState, V2};
use crate::MechError;

/// Rates of an RPP dyad (module docs): `b1` pinned at A to a solved link by `ja` and
/// sliding on `b2` by the prismatic `jp`, `b2` sliding on a solved link G by `jq`, placed
/// with A at `points[0]` ([`crate::kernel::dyad::position`]). Both turn with G
/// (ω = ω_G, α = α_G, rad/s, rad/s²); with u_p, u_q the current unit axes of `jp` and `jq`
/// and Δv = v_G(A) − v_A, b₂'s slide on G ṡ_q = (Δv × u_p)/(u_p × u_q) and b₁'s on b₂
/// ṡ_p = (Δv × u_q)/(u_p × u_q) (m/s); s̈_q (m/s²) the same with
/// Δa + 2 ω (ṡ_q perp(u_q) − ṡ_p perp(u_p)) on the right. `Singular` near parallel axes:
/// κ_F = 2/|u_p × u_q|. Returns [`DyadSystem::None`] (nothing is kept).
#[cfg_attr(debug_assertions, inline)]
#[cfg_attr(not(debug_assertions), inline(always))]
#[allow(clippy::too_many_arguments)]
pub fn rpp_rates(
    joints: &[JointGeom],
    s: &mut [LinkState],
    b1: usize,
    b2: usize,
    ja: usize,
    jp: usize,
    jq: usize,
    points: [V2; 3],
    upto: Level,
) -> Result<DyadSystem, MechError> {
    if !matches!(upto, Level::Velocity | Level::Acceleration) {
        return Ok(DyadSystem::None);
    }
    let a = points[0];
    let (ga, gq) = (&joints[ja], &joints[jq]);
    let (la, lg) = (solved_link(ga, b1), solved_link(gq, b2));
    let (up, uq) = (dir_of(s, lg, joints[jp].axis), dir_of(s, lg, gq.axis));
    let inv = axes_inverse(up, uq)?;
    let ((va, aa), (vga, aga)) = (point_rates(s, la, a), point_rates(s, lg, a));
    let dv = vga - va;
    let sdq = cross(dv, up) * inv;
    let w = set_velocity(s, b1, lg, local_in(ga, b1), a, va);
    // b₂ moves as G's material point at its anchor plus the slide.
    let pos2 = s[b2].pos;
    let (vg2, ag2) = point_rates(s, lg, pos2);
    set_velocity(s, b2, lg, V2::zeros(), pos2, vg2 + uq * sdq);
    if upto == Level::Acceleration {
        let (ac2, rhs) = if lg == 0 {
            (ag2, aga - aa)
        } else {
            let sdp = cross(dv, uq) * inv;
            let corq = perp(uq) * (2.0 * w * sdq);
            (ag2 + corq, aga - aa + corq - perp(up) * (2.0 * w * sdp))
        };
        let sddq = cross(rhs, up) * inv;
        set_acceleration(s, b1, lg, local_in(ga, b1), a, aa);
        set_acceleration(s, b2, lg, V2::zeros(), pos2, ac2 + uq * sddq);
    }
    Ok(DyadSystem::None)
}

/// d'Alembert for an RPP dyad placed in the states `s` (module docs' notation), `f`
/// holding every link's applied and inertia wrench about its anchor (N, N·m). The force
/// Y (N) of b₁ on b₂ through `jp`, normal to u_p, and G's on b₂, R_q = −Y − F₂, normal to
/// u_q: [u_p −u_q]ᵀ Y = (0, F₂·u_q), so Y = −perp(u_p) (F₂·u_q)/(u_p × u_q). Then the
/// force on b₁ at A, R_A = Y − F₁, and the couples about the prismatics' points P (of
/// `jp`) and Q (of `jq`), each on its joint's second link, from the moments of b₁ about A
/// and of b₂ about Q: M_p = M₁(A) − (P − A) × Y, M_q = −M₂(Q) − M_p − (P − Q) × Y (N·m).
/// Each is reported by the joint's first link on its second; the solved links get −R_A
/// at A and −R_q, −M_q at Q. `Singular` as [`rpp_rates`].
#[cfg_attr(debug_assertions, inline)]
#[cfg_attr(not(debug_assertions), inline(always))]
#[allow(clippy::too_many_arguments)]
pub fn rpp_reactions(
    joints: &[JointGeom],
    s: &[LinkState],
    f: &mut [Wrench],
    b1: usize,
    b2: usize,
    ja: usize,
    jp: usize,
    jq: usize,
    out: &mut [Reaction],
) -> Result<(), MechError> {
    let (ga, gp, gq) = (&joints[ja], &joints[jp], &joints[jq]);
    let (la, lg) = (solved_link(ga, b1), solved_link(gq, b2));
    let (up, uq) = (dir_of(s, lg, gp.axis), dir_of(s, lg, gq.axis));
    let inv = axes_inverse(up, uq)?;
    let a = pin_point(s, ga, la, b1);
    let p = s[gp.b].point(gp.db);
    let q = point_of(s, gq.b, gq.db);
    let (f1, m1) = about_point(&f[b1], s[b1].pos, a, local_in(ga, b1));
    // Q is the joint's point on its second link: b₂'s own when that is b₂.
    let (f2, m2) = if gq.b == b2 {
        about_point(&f[b2], s[b2].pos, q, gq.db)
    } else {
        about(&f[b2], s[b2].pos, q)
    };
    let y = perp(up) * (-f2.dot(&uq) * inv);
    let (ra, rq) = (y - f1, -y - f2);
    let mp = m1 - cross(p - a, y);
    let mq = -(m2 + mp + cross(p - q, y));
    out[ja] = reported(ga, b1, ra, 0.0);
    out[jp] = reported(gp, b2, y, mp);
    out[jq] = reported(gq, b2, rq, mq);
    push(f, s, la, a, -ra, 0.0);
    push(f, s, lg, q, -rq, -mq);
    Ok(())
}
