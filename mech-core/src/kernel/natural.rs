//! Velocities and accelerations of the two commonest dyads in their natural coordinates
//! (`docs/theory.md` §3.5): the two link angles of an RRR dyad, the link angle and the
//! slide of an RRP dyad. Both are one 2×2 system written out, its matrix the same for
//! velocities and accelerations; the other closed-form groups go through the joint screws
//! of [`crate::kernel::screw`].
//!
//! **RRR.** Link b₁ is pinned to a solved link at A, b₂ at C, and b₁ to b₂ at B. With
//! e₁ = B − A, e₂ = B − C, the velocity of B seen from both sides,
//! v_A + ω₁ perp(e₁) = v_C + ω₂ perp(e₂), gives
//!
//! [perp(e₁)  −perp(e₂)] (ω₁, ω₂)ᵀ = v_C − v_A,
//!
//! and its derivative, with the centripetal terms moved right,
//!
//! [perp(e₁)  −perp(e₂)] (α₁, α₂)ᵀ = a_C − a_A + ω₁² e₁ − ω₂² e₂.
//!
//! **RRP.** Link b₁ is pinned to a solved link at A and to the slider b₂ at C; b₂ slides
//! along the unit axis u of the guide (a solved link G, turning with it: ω₂ = ω_G). With
//! e₁ = C − A, v_G and a_G the velocity and acceleration of G's material point at C and
//! s the slide,
//!
//! [perp(e₁)  −u] (ω₁, ṡ)ᵀ = v_G − v_A,
//! [perp(e₁)  −u] (α₁, s̈)ᵀ = a_G + 2 ω_G ṡ perp(u) − a_A + ω₁² e₁
//!
//! (the last but one term is Coriolis'). The system is solved in the guide's frame
//! ([`SlideFrame`]): with n = perp(u) and e₁ = x u + y n, perp(e₁) = x n − y u, so its
//! n-row gives the angular rate alone and its u-row the slide,
//!
//! ω₁ = (b·n)/x,  ṡ = −b·u − y ω₁,
//!
//! which is the 2×2 inverse written in the frame where it is triangular (det = x).
//! The condition estimate ([`crate::kernel::linalg::Inverse2::scaled`]'s, with the second column
//! times the length scale L so that both columns are lengths) is then
//! κ_F = (|e₁|² + L²)/|x L|: `Singular` near a change point, where e₁ ⊥ u.
//!
//! Each link's anchor then moves as the material point it is (`LinkState::set_velocity_at`,
//! `set_acceleration_at`): v = v_P + ω perp(r),
//! a = a_P + α perp(r) − ω² r, with P the dyad's point on that link and r = anchor − P.

use crate::kernel::constraints::{JointGeom, Level};
use crate::kernel::kinetostatics::{Reaction, Wrench};
use crate::kernel::linalg::Inverse2;
use crate::kernel::link_state::{cross, dir_of, perp, zero, LinkState, V2};
use crate::MechError;

/// The velocity and acceleration (m/s, m/s²) of the material point of link `l` now at
/// `p`; zero on the ground (link 0), whose state is not read (as [`zero`], which the
/// compiler drops from the sums it enters).
#[inline(always)]
fn point_rates(s: &[LinkState], l: usize, p: V2) -> (V2, V2) {
    if l == 0 {
        (zero(), zero())
    } else {
        let r = p - s[l].pos;
        (s[l].vel_at(r), s[l].acc_at(r))
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

/// The solved link on the other side of joint `g` from `body`.
#[inline(always)]
fn solved_link(g: &JointGeom, body: usize) -> usize {
    if g.b == body {
        g.a
    } else {
        g.b
    }
}

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

/// An RRP dyad's system [perp(e₁) −u] in the guide's frame (module docs): the unit axis
/// u, n = perp(u), and e₁ = C − A = x u + y n, with 1/x ready.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SlideFrame {
    /// The guide's unit axis u.
    pub u: V2,
    /// x = e₁·u (m): the determinant of the system.
    pub x: f64,
    /// y = e₁·n (m).
    pub y: f64,
    /// 1/x (1/m).
    pub inv_x: f64,
}

impl SlideFrame {
    /// The frame of e₁ = x u + y n, |e₁|² = `rsq` (m²); `Singular` when
    /// κ_F = (|e₁|² + L²)/|x L| ≥ [`crate::kernel::linalg::SINGULAR_CONDITION`] (L = `scale`) or
    /// it is not finite.
    #[inline(always)]
    pub fn new(u: V2, x: f64, y: f64, rsq: f64, scale: f64) -> Result<Self, MechError> {
        crate::kernel::linalg::check_condition(rsq + scale * scale, (x * scale).abs())?;
        Ok(SlideFrame {
            u,
            x,
            y,
            inv_x: 1.0 / x,
        })
    }
    /// The frame of the states' e₁ = C − A.
    #[inline(always)]
    pub fn of(u: V2, e1: V2, scale: f64) -> Result<Self, MechError> {
        Self::new(u, e1.dot(&u), cross(u, e1), e1.norm_squared(), scale)
    }
    /// (ω₁, ṡ) with [perp(e₁) −u] (ω₁, ṡ)ᵀ = b: ω₁ = (b·n)/x, ṡ = −b·u − y ω₁.
    #[inline(always)]
    pub fn solve(&self, b: V2) -> (f64, f64) {
        let w = cross(self.u, b) * self.inv_x;
        (w, -(b.dot(&self.u) + self.y * w))
    }
    /// The solution for b = e₁ (the centripetal column): (y/x, −x − y²/x).
    #[inline(always)]
    pub fn solve_e1(&self) -> (f64, f64) {
        let k = self.y * self.inv_x;
        (k, -(self.x + self.y * k))
    }
    /// X with [perp(e₁) −u]ᵀ X = (m, f): X·u = −f, X·n = (m − y f)/x; returned in the
    /// plane.
    #[inline(always)]
    pub fn solve_transpose(&self, m: f64, f: f64) -> V2 {
        let xn = (m - self.y * f) * self.inv_x;
        perp(self.u) * xn - self.u * f
    }
}

/// What a dyad's kinematics keeps for its reactions: the 2×2 system of its rates, whose
/// transpose gives the reactions (module docs), so that d'Alembert neither rebuilds it,
/// nor estimates its condition, nor divides again. `None` below the velocity level or
/// for a group solved by its joint screws; the reactions then build the system.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub enum DyadSystem {
    /// Nothing kept.
    #[default]
    None,
    /// An RRR dyad's [perp(e₁) −perp(e₂)].
    Rrr(Inverse2),
    /// An RRP dyad's [perp(e₁) −u], in the guide's frame.
    Rrp(SlideFrame),
}

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

/// A link's wrench (force, moment about its anchor `pos`) as its force and its moment
/// about the point `p`: M_P = M + (pos − P) × F.
#[inline(always)]
fn about(w: &Wrench, pos: V2, p: V2) -> (V2, f64) {
    let f = V2::new(w.x, w.y);
    (f, w.z + cross(pos - p, f))
}

/// The point of the pin `g` between the solved link `solved` and the dyad's link `own`:
/// `own`'s anchor when its local vector there is zero (a literal zero in the generated
/// code, so the test folds and nothing is rotated), else the solved link's point.
#[inline(always)]
fn pin_point(s: &[LinkState], g: &JointGeom, solved: usize, own: usize) -> V2 {
    if local_in(g, own) == zero() {
        s[own].pos
    } else {
        crate::kernel::link_state::point_of(s, solved, if g.a == solved { g.da } else { g.db })
    }
}

/// [`about`] the link's material point `p` of local vector `d`: when `d` is zero, `p` is
/// the anchor and the moment is the wrench's own, with no transfer (a literal zero in the
/// generated code, `JointGeom::with_links`, so the test folds).
#[inline(always)]
fn about_point(w: &Wrench, pos: V2, p: V2, d: V2) -> (V2, f64) {
    if d == zero() {
        (V2::new(w.x, w.y), w.z)
    } else {
        about(w, pos, p)
    }
}

/// Add the force `force` at the point now at `p`, and the couple `couple`, to link `l`'s
/// wrench (about its anchor).
#[inline(always)]
fn push(f: &mut [Wrench], s: &[LinkState], l: usize, p: V2, force: V2, couple: f64) {
    let pos = if l == 0 { V2::zeros() } else { s[l].pos };
    f[l] += Wrench::new(force.x, force.y, couple + cross(p - pos, force));
}

/// The reaction at joint `g` reported by the convention (by `g.a` on `g.b`) from the
/// force and moment that link `on` receives through it.
#[inline(always)]
fn reported(g: &JointGeom, on: usize, force: V2, moment: f64) -> Reaction {
    if g.b == on {
        Reaction { force, moment }
    } else {
        Reaction {
            force: -force,
            moment: -moment,
        }
    }
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
