//! The RRP dyad's kernels (their derivation: the folder's docs, [`super`]).

use super::{
    about, about_point, local_in, pin_point, point_rates, push, reported, solved_link, DyadSystem,
    SlideFrame,
};
use crate::kernel::constraints::{JointGeom, Level};
use crate::kernel::kinetostatics::{Reaction, Wrench};
use crate::kernel::link_state::{cross, dir_of, perp, zero, LinkState, V2};
use crate::MechError;

/// Rates of an RRP dyad (module docs) whose links `b1` (pinned at A by `ja`, to the
/// slider at C by `jc`) and `b2` (the slider, on the guide by the prismatic `jp`) are
/// placed with A and C at `points` = [A, C, (x, y)], e₁ = C − A = x u + y n
/// ([`crate::kernel::dyad::position`], which has x from its square root and y before it).
/// `scale` is the length scale L. `Singular` near a change point (e₁ ⊥ u, x = 0).
/// Returns the system, kept for the reactions.
#[cfg_attr(debug_assertions, inline)]
#[cfg_attr(not(debug_assertions), inline(always))]
#[allow(clippy::too_many_arguments)]
pub fn rrp_rates(
    joints: &[JointGeom],
    s: &mut [LinkState],
    b1: usize,
    b2: usize,
    ja: usize,
    jc: usize,
    jp: usize,
    points: [V2; 3],
    scale: f64,
    upto: Level,
) -> Result<DyadSystem, MechError> {
    if !matches!(upto, Level::Velocity | Level::Acceleration) {
        return Ok(DyadSystem::None);
    }
    let [a, c, xy] = points;
    let gp = &joints[jp];
    let (la, lg) = (solved_link(&joints[ja], b1), solved_link(gp, b2));
    let u = dir_of(s, lg, gp.axis);
    let rsq = xy.x * xy.x + xy.y * xy.y;
    let m = SlideFrame::new(u, xy.x, xy.y, rsq, scale)?;
    let (da, dc) = (local_in(&joints[ja], b1), local_in(&joints[jc], b2));
    let ((va, aa), (vg, ag)) = (point_rates(s, la, a), point_rates(s, lg, c));
    let (wg, alg) = if lg == 0 {
        (0.0, 0.0)
    } else {
        (s[lg].omega, s[lg].alpha)
    };
    let (w1, sd) = m.solve(vg - va);
    s[b1].set_velocity_at(da, a, va, w1);
    let vc = vg + u * sd;
    // On the ground guide the slider does not turn: its anchor moves as C (the zero
    // terms written out would not fold, IEEE arithmetic keeping 0·x).
    if lg == 0 {
        s[b2].omega = 0.0;
        s[b2].vel = vc;
    } else {
        s[b2].set_velocity_at(dc, c, vc, wg);
    }
    if upto == Level::Acceleration {
        let coriolis = if lg == 0 {
            zero()
        } else {
            perp(u) * (2.0 * wg * sd)
        };
        // M⁻¹(b + e₁ω₁²) = M⁻¹b + (M⁻¹e₁) ω₁²: both solves wait only for the frame, so
        // ω₁, the last to come, enters by one multiply-add (the direct problem waits on
        // this chain).
        let (b0, b1_) = m.solve(ag + coriolis - aa);
        let (k0, k1) = m.solve_e1();
        let w1sq = w1 * w1;
        let (al1, sdd) = (b0 + k0 * w1sq, b1_ + k1 * w1sq);
        s[b1].set_acceleration_at(da, a, aa, al1);
        let ac = ag + coriolis + u * sdd;
        if lg == 0 {
            s[b2].alpha = 0.0;
            s[b2].acc = ac;
        } else {
            s[b2].set_acceleration_at(dc, c, ac, alg);
        }
    }
    Ok(DyadSystem::Rrp(m))
}

/// d'Alembert for an RRP dyad placed in the states `s` (module docs' notation). With X
/// the force of b₁ on the slider b₂ at C, the moments of b₁ about A and the slider's
/// forces along the axis, e₁ × X = M₁(A), −u·X = F₂·u, are the transpose of the velocity
/// system: [perp(e₁) −u]ᵀ X = (M₁(A), F₂·u). Then R_A = X − F₁ at A, and the guide's
/// force on the slider R_P = −X − F₂ (normal to u) with the couple that balances the
/// slider's moments about the joint point P, M_P = −(M₂(P) + (C − P) × X). `scale` is
/// the length scale L of the condition estimate, as in [`rrp_rates`]; `kept`, the
/// system [`rrp_rates`] returned, if any.
#[cfg_attr(debug_assertions, inline)]
#[cfg_attr(not(debug_assertions), inline(always))]
#[allow(clippy::too_many_arguments)]
pub fn rrp_reactions(
    joints: &[JointGeom],
    s: &[LinkState],
    f: &mut [Wrench],
    b1: usize,
    b2: usize,
    ja: usize,
    jc: usize,
    jp: usize,
    scale: f64,
    kept: &DyadSystem,
    out: &mut [Reaction],
) -> Result<(), MechError> {
    let (ga, gc, gp) = (&joints[ja], &joints[jc], &joints[jp]);
    let (la, lg) = (solved_link(ga, b1), solved_link(gp, b2));
    let a = pin_point(s, ga, la, b1);
    let c = s[b2].point(if gc.a == b2 { gc.da } else { gc.db });
    let p = crate::kernel::link_state::point_of(s, gp.b, gp.db);
    let u = dir_of(s, lg, gp.axis);
    let m = match kept {
        DyadSystem::Rrp(m) => *m,
        _ => SlideFrame::of(u, c - a, scale)?,
    };
    let (f1, m1) = about_point(&f[b1], s[b1].pos, a, local_in(ga, b1));
    // P is the joint's point on its second link: the slider's own when that is b₂.
    let (f2, m2) = if gp.b == b2 {
        about_point(&f[b2], s[b2].pos, p, gp.db)
    } else {
        about(&f[b2], s[b2].pos, p)
    };
    let x = m.solve_transpose(m1, f2.dot(&u));
    let ra = x - f1;
    let (rp, mp) = (-x - f2, -(m2 + cross(c - p, x)));
    out[ja] = reported(ga, b1, ra, 0.0);
    out[jc] = reported(gc, b2, x, 0.0);
    out[jp] = reported(gp, b2, rp, mp);
    push(f, s, la, a, -ra, 0.0);
    push(f, s, lg, p, -rp, -mp);
    Ok(())
}
