//! The RPR dyad's kernels (their derivation: the folder's docs, [`super`]).

use super::{
    about_point, local_in, pin_point, point_rates, push, reported, solved_link, DyadSystem,
    SlideFrame,
};
use crate::kernel::constraints::{JointGeom, Level};
use crate::kernel::kinetostatics::{Reaction, Wrench};
use crate::kernel::link_state::{cross, perp, LinkState, V2};
use crate::MechError;

/// The guide G, the slider S and their pins (joints) in the solver's terms: `[G, S]` and
/// `[G's pin, S's pin]`, each of the solver's constants. Each kernel below branches on
/// the orientation once and runs its body with constant indices, so that in the generated
/// code the joints and states stay in registers (an index chosen at run time into them
/// would keep them in memory, and every topology test with them).
macro_rules! oriented {
    ($joints:expr, $b1:expr, $b2:expr, $ja:expr, $jp:expr, $jb:expr,
     |$sides:ident, $pins:ident| $body:expr) => {
        if $joints[$jp].a == $b1 {
            let ($sides, $pins) = ([$b1, $b2], [$ja, $jb]);
            $body
        } else {
            let ($sides, $pins) = ([$b2, $b1], [$jb, $ja]);
            $body
        }
    };
}

/// Rates of an RPR dyad (module docs): the links `b1` (pinned by `ja`) and `b2` (pinned by
/// `jb`) slide on each other by the prismatic `jp`, placed with the guide's pin A and the
/// slider's pin B at `points` = [A, B, (x, y)], d = B − A = x u + y n
/// ([`crate::kernel::dyad::position`], which has x from its square root and y, the slide
/// line's offset, before it). ω = (u × (v_B − v_A))/x (rad/s), ṡ = (v_B − v_A)·u + y ω
/// (m/s), α = (u × (a_B − a_A) + ω (y ω − 2 ṡ))/x (rad/s²). `scale` is the length scale
/// L (m). `Singular` near a change point (d ⊥ u, x = 0): κ_F = (|d|² + L²)/|x L|.
/// Returns the system, kept for the reactions.
#[cfg_attr(debug_assertions, inline)]
#[cfg_attr(not(debug_assertions), inline(always))]
#[allow(clippy::too_many_arguments)]
pub fn rpr_rates(
    joints: &[JointGeom],
    s: &mut [LinkState],
    b1: usize,
    b2: usize,
    ja: usize,
    jp: usize,
    jb: usize,
    points: [V2; 3],
    scale: f64,
    upto: Level,
) -> Result<DyadSystem, MechError> {
    if !matches!(upto, Level::Velocity | Level::Acceleration) {
        return Ok(DyadSystem::None);
    }
    oriented!(joints, b1, b2, ja, jp, jb, |sides, pins| rates(
        joints, s, sides, pins, jp, points, scale, upto
    ))
}

/// [`rpr_rates`] with the guide and the slider `[g, sl]` pinned by `[ja, jb]`.
#[inline(always)]
#[allow(clippy::too_many_arguments)]
fn rates(
    joints: &[JointGeom],
    s: &mut [LinkState],
    [g, sl]: [usize; 2],
    [ja, jb]: [usize; 2],
    jp: usize,
    points: [V2; 3],
    scale: f64,
    upto: Level,
) -> Result<DyadSystem, MechError> {
    let [a, b, xy] = points;
    let (ga, gb) = (&joints[ja], &joints[jb]);
    let (la, lb) = (solved_link(ga, g), solved_link(gb, sl));
    let u = s[g].r(joints[jp].axis);
    let m = SlideFrame::new(u, xy.x, xy.y, xy.x * xy.x + xy.y * xy.y, scale)?;
    let ((va, aa), (vb, ab)) = (point_rates(s, la, a), point_rates(s, lb, b));
    let dv = vb - va;
    let w = cross(u, dv) * m.inv_x;
    let (da, db) = (local_in(ga, g), local_in(gb, sl));
    s[g].set_velocity_at(da, a, va, w);
    s[sl].set_velocity_at(db, b, vb, w);
    if upto == Level::Acceleration {
        let sd = dv.dot(&u) + m.y * w;
        // (u × Δa)/x waits only for the frame; ω, the last to come, enters after it.
        let al = cross(u, ab - aa) * m.inv_x + w * (m.y * w - 2.0 * sd) * m.inv_x;
        s[g].set_acceleration_at(da, a, aa, al);
        s[sl].set_acceleration_at(db, b, ab, al);
    }
    Ok(DyadSystem::Rpr(m))
}

/// d'Alembert for an RPR dyad placed in the states `s` (module docs' notation), `f`
/// holding every link's applied and inertia wrench about its anchor (N, N·m). The force
/// of the guide G on the slider S, X = n (M_G(A) + M_S(B))/x (N), normal to u; the
/// forces on G at A and on S at B, R_A = X − F_G and R_B = −X − F_S; the prismatic's
/// couple about its point P on S, M_P = −M_S(B) + (B − P) × X (N·m). Each is reported by
/// the joint's first link on its second; the solved links get −R_A at A and −R_B at B.
/// `scale` is the length scale L of the condition estimate, as in [`rpr_rates`]; `kept`,
/// the system [`rpr_rates`] returned, if any.
#[cfg_attr(debug_assertions, inline)]
#[cfg_attr(not(debug_assertions), inline(always))]
#[allow(clippy::too_many_arguments)]
pub fn rpr_reactions(
    joints: &[JointGeom],
    s: &[LinkState],
    f: &mut [Wrench],
    b1: usize,
    b2: usize,
    ja: usize,
    jp: usize,
    jb: usize,
    scale: f64,
    kept: &DyadSystem,
    out: &mut [Reaction],
) -> Result<(), MechError> {
    oriented!(joints, b1, b2, ja, jp, jb, |sides, pins| reactions(
        joints, s, f, sides, pins, jp, scale, kept, out
    ))
}

/// [`rpr_reactions`] with the guide and the slider `[g, sl]` pinned by `[ja, jb]`.
#[inline(always)]
#[allow(clippy::too_many_arguments)]
fn reactions(
    joints: &[JointGeom],
    s: &[LinkState],
    f: &mut [Wrench],
    [g, sl]: [usize; 2],
    [ja, jb]: [usize; 2],
    jp: usize,
    scale: f64,
    kept: &DyadSystem,
    out: &mut [Reaction],
) -> Result<(), MechError> {
    let (ga, gp, gb) = (&joints[ja], &joints[jp], &joints[jb]);
    let (la, lb) = (solved_link(ga, g), solved_link(gb, sl));
    let a = pin_point(s, ga, la, g);
    let b = pin_point(s, gb, lb, sl);
    let m = match kept {
        DyadSystem::Rpr(m) => *m,
        _ => SlideFrame::of(s[g].r(gp.axis), b - a, scale)?,
    };
    let db = local_in(gb, sl);
    let (fg, mg) = about_point(&f[g], s[g].pos, a, local_in(ga, g));
    let (fs, ms) = about_point(&f[sl], s[sl].pos, b, db);
    let x = perp(m.u) * ((mg + ms) * m.inv_x);
    let (ra, rb) = (x - fg, -x - fs);
    // P is the joint's point on the slider: its pin B when the local vectors agree (two
    // literal zeros in the generated code, so the test folds).
    let mp = if gp.db == db {
        -ms
    } else {
        cross(b - s[sl].point(gp.db), x) - ms
    };
    out[ja] = reported(ga, g, ra, 0.0);
    out[jp] = reported(gp, sl, x, mp);
    out[jb] = reported(gb, sl, rb, 0.0);
    push(f, s, la, a, -ra, 0.0);
    push(f, s, lb, b, -rb, 0.0);
    Ok(())
}
