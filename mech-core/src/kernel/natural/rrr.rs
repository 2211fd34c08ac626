//! The RRR dyad's kernels (their derivation: the folder's docs, [`super`]).

use super::{
    about_point, local_in, pin_point, point_rates, push, reported, solved_link, DyadSystem,
};
use crate::kernel::constraints::{JointGeom, Level};
use crate::kernel::kinetostatics::{Reaction, Wrench};
use crate::kernel::linalg::Inverse2;
use crate::kernel::link_state::{perp, LinkState, V2};
use crate::MechError;

/// Rates of an RRR dyad (module docs) whose links `b1`, `b2` are placed with A, B, C at
/// `points` = [A, B, C]; `ja`, `jb` are the pins at A (of b1) and at C (of b2).
/// `Singular` near a change point (e₁ ∥ e₂). Returns the system, kept for the reactions.
#[cfg_attr(debug_assertions, inline)]
#[cfg_attr(not(debug_assertions), inline(always))]
#[allow(clippy::too_many_arguments)]
pub fn rrr_rates(
    joints: &[JointGeom],
    s: &mut [LinkState],
    b1: usize,
    b2: usize,
    ja: usize,
    jb: usize,
    points: [V2; 3],
    upto: Level,
) -> Result<DyadSystem, MechError> {
    if !matches!(upto, Level::Velocity | Level::Acceleration) {
        return Ok(DyadSystem::None);
    }
    let [a, b, c] = points;
    let (la, lc) = (solved_link(&joints[ja], b1), solved_link(&joints[jb], b2));
    let (e1, e2) = (b - a, b - c);
    let (p1, p2) = (perp(e1), perp(e2));
    let m = Inverse2::new([[p1.x, -p2.x], [p1.y, -p2.y]])?;
    let ((va, aa), (vc, ac)) = (point_rates(s, la, a), point_rates(s, lc, c));
    let dv = vc - va;
    let [w1, w2] = m.solve([dv.x, dv.y]);
    let (da, dc) = (local_in(&joints[ja], b1), local_in(&joints[jb], b2));
    s[b1].set_velocity_at(da, a, va, w1);
    s[b2].set_velocity_at(dc, c, vc, w2);
    if upto == Level::Acceleration {
        let rhs = ac - aa + e1 * (w1 * w1) - e2 * (w2 * w2);
        let [al1, al2] = m.solve([rhs.x, rhs.y]);
        s[b1].set_acceleration_at(da, a, aa, al1);
        s[b2].set_acceleration_at(dc, c, ac, al2);
    }
    Ok(DyadSystem::Rrr(m))
}

/// d'Alembert for an RRR dyad placed in the states `s` (module docs' notation), `f`
/// holding every link's applied and inertia wrench about its anchor. With X the force of
/// b₁ on b₂ at B, the moments of b₁ about A and of b₂ about C,
/// e₁ × X = M₁(A), −e₂ × X = M₂(C), are the transpose of the velocity system:
/// [perp(e₁) −perp(e₂)]ᵀ X = (M₁(A), M₂(C)). Then the forces on b₁ at A and on b₂ at C,
/// R_A = X − F₁ and R_C = −X − F₂; the solved links get −R_A and −R_C. `kept`, the
/// system [`rrr_rates`] returned, if any.
#[cfg_attr(debug_assertions, inline)]
#[cfg_attr(not(debug_assertions), inline(always))]
#[allow(clippy::too_many_arguments)]
pub fn rrr_reactions(
    joints: &[JointGeom],
    s: &[LinkState],
    f: &mut [Wrench],
    b1: usize,
    b2: usize,
    ja: usize,
    jc: usize,
    jb: usize,
    kept: &DyadSystem,
    out: &mut [Reaction],
) -> Result<(), MechError> {
    let (ga, gc, gb) = (&joints[ja], &joints[jc], &joints[jb]);
    let (la, lc) = (solved_link(ga, b1), solved_link(gb, b2));
    let a = pin_point(s, ga, la, b1);
    let c = pin_point(s, gb, lc, b2);
    let m = match kept {
        DyadSystem::Rrr(m) => *m,
        _ => {
            let b = s[b1].point(if gc.a == b1 { gc.da } else { gc.db });
            let (p1, p2) = (perp(b - a), perp(b - c));
            Inverse2::new([[p1.x, -p2.x], [p1.y, -p2.y]])?
        }
    };
    let (f1, m1) = about_point(&f[b1], s[b1].pos, a, local_in(ga, b1));
    let (f2, m2) = about_point(&f[b2], s[b2].pos, c, local_in(gb, b2));
    let [x, y] = m.solve_transpose([m1, m2]);
    let x = V2::new(x, y);
    let (ra, rc) = (x - f1, -x - f2);
    out[ja] = reported(ga, b1, ra, 0.0);
    out[jc] = reported(gc, b2, x, 0.0);
    out[jb] = reported(gb, b2, rc, 0.0);
    push(f, s, la, a, -ra, 0.0);
    push(f, s, lc, c, -rc, 0.0);
    Ok(())
}
