//! The PRP dyad's kernels (their derivation: the folder's docs, [`super`]).

use super::{about, about_point, point_rates, push, reported, solved_link, DyadSystem};
use crate::kernel::constraints::{JointGeom, Level};
use crate::kernel::kinetostatics::{Reaction, Wrench};
use crate::kernel::link_state::{cross, dir_of, perp, point_of, LinkState, V2};
use crate::MechError;

/// 1/(u₁ × u₂) for the system [u₁ −u₂] of two unit axes; `Singular` when
/// κ_F = 2/|u₁ × u₂| ≥ [`crate::kernel::linalg::SINGULAR_CONDITION`] (the joint screws'
/// estimate of the same matrix, `ChainSystem`'s two slide columns) or it is not finite.
#[inline(always)]
pub(super) fn axes_inverse(u1: V2, u2: V2) -> Result<f64, MechError> {
    let den = cross(u1, u2);
    crate::kernel::linalg::check_condition(2.0, den.abs())?;
    Ok(1.0 / den)
}

/// Rates of a PRP dyad (module docs): the slider `b1` on a solved link L₁ by the
/// prismatic `jp1`, the slider `b2` on a solved link L₂ by `jp2`, pinned together at C by
/// `jc`, placed with C at `points[0]` ([`crate::kernel::dyad::position`]). Each turns
/// with its guide (ω₁ = ω_L₁, ω₂ = ω_L₂, rad/s); with u₁, u₂ the guides' current unit axes
/// and Δv = v_L₂(C) − v_L₁(C), the slides' rates (m/s) ṡ₁ = (Δv × u₂)/(u₁ × u₂),
/// ṡ₂ = (Δv × u₁)/(u₁ × u₂), and the same for s̈ (m/s²) with
/// Δa + 2 ω₂ ṡ₂ perp(u₂) − 2 ω₁ ṡ₁ perp(u₁) on the right. `Singular` near parallel axes:
/// κ_F = 2/|u₁ × u₂|. Returns [`DyadSystem::None`] (nothing is kept).
#[cfg_attr(debug_assertions, inline)]
#[cfg_attr(not(debug_assertions), inline(always))]
#[allow(clippy::too_many_arguments)]
pub fn prp_rates(
    joints: &[JointGeom],
    s: &mut [LinkState],
    b1: usize,
    b2: usize,
    jp1: usize,
    jc: usize,
    jp2: usize,
    points: [V2; 3],
    upto: Level,
) -> Result<DyadSystem, MechError> {
    if !matches!(upto, Level::Velocity | Level::Acceleration) {
        return Ok(DyadSystem::None);
    }
    let c = points[0];
    let (g1, gc, g2) = (&joints[jp1], &joints[jc], &joints[jp2]);
    let (l1, l2) = (solved_link(g1, b1), solved_link(g2, b2));
    let (u1, u2) = (dir_of(s, l1, g1.axis), dir_of(s, l2, g2.axis));
    let inv = axes_inverse(u1, u2)?;
    let (dc1, dc2) = if gc.a == b1 {
        (gc.da, gc.db)
    } else {
        (gc.db, gc.da)
    };
    let ((v1, a1), (v2, a2)) = (point_rates(s, l1, c), point_rates(s, l2, c));
    let dv = v2 - v1;
    let (sd1, sd2) = (cross(dv, u2) * inv, cross(dv, u1) * inv);
    let vc = v1 + u1 * sd1;
    // On a ground guide the slider does not turn: every point moves as C (the zero terms
    // written out would not fold, IEEE arithmetic keeping 0·x).
    let w1 = set_velocity(s, b1, l1, dc1, c, vc);
    let w2 = set_velocity(s, b2, l2, dc2, c, vc);
    if upto == Level::Acceleration {
        let cor1 = perp(u1) * (2.0 * w1 * sd1);
        let cor2 = perp(u2) * (2.0 * w2 * sd2);
        let rhs = match (l1 == 0, l2 == 0) {
            (true, true) => a2 - a1,
            (true, false) => a2 - a1 + cor2,
            (false, true) => a2 - a1 - cor1,
            (false, false) => a2 - a1 + cor2 - cor1,
        };
        let sdd1 = cross(rhs, u2) * inv;
        let ac = if l1 == 0 {
            a1 + u1 * sdd1
        } else {
            a1 + cor1 + u1 * sdd1
        };
        set_acceleration(s, b1, l1, dc1, c, ac);
        set_acceleration(s, b2, l2, dc2, c, ac);
    }
    Ok(DyadSystem::None)
}

/// Set the slider `b`'s ω (its guide `l`'s, zero on the ground) and its anchor's velocity
/// from its point's (local `d`, now at `p`) `v`; returns ω.
#[inline(always)]
pub(super) fn set_velocity(s: &mut [LinkState], b: usize, l: usize, d: V2, p: V2, v: V2) -> f64 {
    if l == 0 {
        s[b].omega = 0.0;
        s[b].vel = v;
        0.0
    } else {
        let w = s[l].omega;
        s[b].set_velocity_at(d, p, v, w);
        w
    }
}

/// Set the slider `b`'s α (its guide `l`'s, zero on the ground) and its anchor's
/// acceleration from its point's (local `d`, now at `p`) `a`, ω already set.
#[inline(always)]
pub(super) fn set_acceleration(s: &mut [LinkState], b: usize, l: usize, d: V2, p: V2, a: V2) {
    if l == 0 {
        s[b].alpha = 0.0;
        s[b].acc = a;
    } else {
        let al = s[l].alpha;
        s[b].set_acceleration_at(d, p, a, al);
    }
}

/// d'Alembert for a PRP dyad placed in the states `s` (module docs' notation), `f`
/// holding every link's applied and inertia wrench about its anchor (N, N·m). The force X
/// (N) of b₁ on b₂ at the pin C from the two slides' conditions, the guides' forces
/// normal to their axes: [u₁ −u₂]ᵀ X = (F₁·u₁, F₂·u₂), so
/// X = ((−F₂·u₂) perp(u₁) − (F₁·u₁) perp(u₂))/(u₁ × u₂). Then the guides' forces on the
/// sliders R₁ = X − F₁ and R₂ = −X − F₂ (N), and their couples about each prismatic's
/// point Pₖ (on its second link) from the sliders' moments,
/// M₁ = −M₁(P₁) + (C − P₁) × X and M₂ = −M₂(P₂) − (C − P₂) × X (N·m). Each is reported
/// by the joint's first link on its second; the solved links get −Rₖ and −Mₖ at Pₖ.
/// `Singular` as [`prp_rates`].
#[cfg_attr(debug_assertions, inline)]
#[cfg_attr(not(debug_assertions), inline(always))]
#[allow(clippy::too_many_arguments)]
pub fn prp_reactions(
    joints: &[JointGeom],
    s: &[LinkState],
    f: &mut [Wrench],
    b1: usize,
    b2: usize,
    jp1: usize,
    jc: usize,
    jp2: usize,
    out: &mut [Reaction],
) -> Result<(), MechError> {
    let (g1, gc, g2) = (&joints[jp1], &joints[jc], &joints[jp2]);
    let (l1, l2) = (solved_link(g1, b1), solved_link(g2, b2));
    let (u1, u2) = (dir_of(s, l1, g1.axis), dir_of(s, l2, g2.axis));
    let inv = axes_inverse(u1, u2)?;
    let c = s[b1].point(if gc.a == b1 { gc.da } else { gc.db });
    let (p1, p2) = (point_of(s, g1.b, g1.db), point_of(s, g2.b, g2.db));
    // Pₖ is the joint's point on its second link: the slider's own when that is bₖ.
    let (f1, m1) = if g1.b == b1 {
        about_point(&f[b1], s[b1].pos, p1, g1.db)
    } else {
        about(&f[b1], s[b1].pos, p1)
    };
    let (f2, m2) = if g2.b == b2 {
        about_point(&f[b2], s[b2].pos, p2, g2.db)
    } else {
        about(&f[b2], s[b2].pos, p2)
    };
    let x = (perp(u1) * (-f2.dot(&u2)) - perp(u2) * f1.dot(&u1)) * inv;
    let (r1, r2) = (x - f1, -x - f2);
    let mp1 = cross(c - p1, x) - m1;
    let mp2 = -(m2 + cross(c - p2, x));
    out[jp1] = reported(g1, b1, r1, mp1);
    out[jc] = reported(gc, b2, x, 0.0);
    out[jp2] = reported(g2, b2, r2, mp2);
    push(f, s, l1, p1, -r1, -mp1);
    push(f, s, l2, p2, -r2, -mp2);
    Ok(())
}
