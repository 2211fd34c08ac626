//! Velocities, accelerations and reactions of the closed-form dyads in their natural
//! coordinates (`docs/theory.md` §3.5): the two link angles of an RRR dyad ([`rrr_rates`]),
//! the link angle and the slide of an RRP dyad ([`rrp_rates`]), the common angle and the
//! slide of an RPR dyad ([`rpr_rates`]), the two slides of a PRP dyad ([`prp_rates`]) and
//! of an RPP dyad ([`rpp_rates`]), whose rotations are their guides'; one file each
//! (`natural/rrr.rs`, `rrp.rs`, `rpr.rs`, `prp.rs`, `rpp.rs`). Each is one 2×2 system
//! written out, its matrix the same for velocities and accelerations, its transpose that
//! of the reactions (d'Alembert); the other closed-form groups go through the joint screws
//! of [`crate::kernel::screw`] (except the slotted slider, in `kernel::dyad`).
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
//! d'Alembert: with X the force of b₁ on b₂ at B, the moments of b₁ about A and of b₂
//! about C, e₁ × X = M₁(A), −e₂ × X = M₂(C), are the transpose of the velocity system.
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
//! **RPR.** The guide G (the prismatic joint's first link, whose axis u turns with it) is
//! pinned to a solved link at A, the slider S (its second link) to a solved link at B, and
//! S slides on G: both turn together (ω_G = ω_S = ω), and S's motion relative to G is the
//! slide ṡ u. With d = B − A, the velocity of B seen from both sides,
//! v_B = v_A + ω perp(d) + ṡ u, and its derivative (ḋ = ω perp(d) + ṡ u, u̇ = ω perp(u)),
//! a_B = a_A + α perp(d) − ω² d + 2 ω ṡ perp(u) + s̈ u, give
//!
//! [perp(d)  u] (ω, ṡ)ᵀ = v_B − v_A,
//! [perp(d)  u] (α, s̈)ᵀ = a_B − a_A + ω² d − 2 ω ṡ perp(u)
//!
//! (the last term is Coriolis'). In the guide's frame (u, n), d = x u + y n with
//! y = n·d the slide line's offset from the pins, a constant of the drawing (the slide
//! condition), and x = ±√(|d|² − y²) straight from the
//! position's square root ([`crate::kernel::dyad::position`]); perp(d) = x n − y u, so the
//! n-row gives the angle's rates alone and the u-row the slide:
//!
//! ω = (u × b)/x,  ṡ = b·u + y ω,  α = (u × (a_B − a_A) + ω (y ω − 2 ṡ))/x
//!
//! (u × d = y, u × perp(u) = 1; s̈ is not needed: both links take α and move as their
//! pins). It is [`SlideFrame`]'s system with the second column negated, so the same
//! frame, det = −x, and condition estimate (the second column a length times L):
//! κ_F = (|d|² + L²)/|x L|, the joint screws' (`ChainSystem`'s pivot at A gives
//! [u perp(A − B)/L], of the same norm and |det|): `Singular` near a change point, where
//! d ⊥ u (the slide line tangent to the circle about A through B).
//!
//! d'Alembert: let X be the force of G on S through the prismatic joint (normal to u),
//! M_p(B) its couple about B, and M_G(A), M_S(B) the moments of each link's applied and
//! inertia wrench about its pin. The moments of S about B, M_S(B) + M_p(B) = 0, and of G
//! about A, M_G(A) − M_p(B) − d × X = 0, give d × X = M_G(A) + M_S(B) with X·u = 0: the
//! transpose [perp(d) u]ᵀ X = (M_G(A) + M_S(B), 0), so X = n (M_G(A) + M_S(B))/x
//! (d × n = x). Then the forces on G at A and on S at B, R_A = X − F_G and
//! R_B = −X − F_S, and the prismatic's couple about its point P on S,
//! M_P = −M_S(B) + (B − P) × X.
//!
//! **PRP.** The slider b₁ slides on a solved link L₁ along its unit axis u₁, the slider
//! b₂ on a solved link L₂ along u₂ (each axis turning with its guide), and b₁ is pinned
//! to b₂ at C, where the two slide lines cross. Each slider turns with its guide
//! (ω₁ = ω_L₁, ω₂ = ω_L₂, and the α's), so the unknowns are the two slides s₁, s₂.
//! With v_Lₖ, a_Lₖ the velocity and acceleration of Lₖ's material point at C, the
//! velocity of C seen from both sides, v_L₁ + ṡ₁ u₁ = v_L₂ + ṡ₂ u₂, and its derivative
//! (the relative motion of each slider a slide along a turning axis: Coriolis' 2 ω ṡ
//! perp(u)) give
//!
//! [u₁  −u₂] (ṡ₁, ṡ₂)ᵀ = v_L₂ − v_L₁,
//! [u₁  −u₂] (s̈₁, s̈₂)ᵀ = a_L₂ − a_L₁ + 2 ω₂ ṡ₂ perp(u₂) − 2 ω₁ ṡ₁ perp(u₁).
//!
//! Crossing with u₂ and u₁ (Cramer) solves it, det = u₁ × u₂:
//!
//! ṡ₁ = (b × u₂)/(u₁ × u₂),  ṡ₂ = (b × u₁)/(u₁ × u₂),
//!
//! and C moves as v_L₁ + ṡ₁ u₁, a_L₁ + s̈₁ u₁ + 2 ω₁ ṡ₁ perp(u₁) (s̈₂ is not needed).
//! Both columns are unit vectors, lengths ratios: no length scale enters, and the
//! condition estimate is that of the joint screws' reduced block [u₁ u₂]
//! (`ChainSystem`, pivot at C), κ_F = 2/|u₁ × u₂|: `Singular` near parallel axes, where
//! the pin runs to infinity.
//!
//! d'Alembert: let X be the force of b₁ on b₂ at C, Fₖ the force of bₖ's applied and
//! inertia wrench. Each guide's force on its slider, R₁ = X − F₁ and R₂ = −X − F₂, is
//! normal to its axis: X·u₁ = F₁·u₁ and −X·u₂ = F₂·u₂, the transpose
//! [u₁ −u₂]ᵀ X = (F₁·u₁, F₂·u₂), so
//! X = ((−F₂·u₂) perp(u₁) − (F₁·u₁) perp(u₂))/(u₁ × u₂) (perp(uₖ)·uₖ = 0,
//! perp(u₁)·u₂ = u₁ × u₂). Each prismatic's couple about its point Pₖ then balances its
//! slider's moments: M₁ = −M₁(P₁) + (C − P₁) × X, M₂ = −M₂(P₂) − (C − P₂) × X.
//!
//! **RPP.** The link b₁ is pinned to a solved link at A and slides on b₂ along u_p (the
//! prismatic jp); b₂ slides on a solved link G along u_q (jq). b₂ turns with G, and b₁,
//! sliding on b₂, with b₂: all three share ω = ω_G and α = α_G, both axes turn with G,
//! and the position ([`crate::kernel::dyad::position`]) places b₁ by its pin A, b₂ where
//! the slide line of b₁ through b₂'s point C meets G's. With ṡ_p the slide of b₂ on b₁
//! and ṡ_q that of b₂ on G, the velocity of b₂'s point C from both sides,
//! v₁(C) + ṡ_p u_p = v_G(C) + ṡ_q u_q, and its derivative give
//!
//! [u_p  −u_q] (ṡ_p, ṡ_q)ᵀ = v_G(C) − v₁(C) = v_G(A) − v_A,
//! [u_p  −u_q] (s̈_p, s̈_q)ᵀ = a_G(A) − a_A + 2 ω (ṡ_q perp(u_q) − ṡ_p perp(u_p)),
//!
//! the two rigid fields of the same ω and α differing by a translation (so C is not
//! needed); ṡ_q = (b × u_p)/(u_p × u_q), ṡ_p = (b × u_q)/(u_p × u_q). b₁ moves as its pin
//! A with ω, α; b₂ as G plus the slide: v₂ = v_G + ṡ_q u_q,
//! a₂ = a_G + s̈_q u_q + 2 ω ṡ_q perp(u_q) at its anchor. Unit columns again: the joint
//! screws' block (pivot at A) is [u_p u_q], κ_F = 2/|u_p × u_q|.
//!
//! d'Alembert: let Y be the force of b₁ on b₂ through jp (normal to u_p) and
//! R_q = −Y − F₂ that of G on b₂ (normal to u_q): Y·u_p = 0, −Y·u_q = F₂·u_q, the
//! transpose [u_p −u_q]ᵀ Y = (0, F₂·u_q), so Y = −perp(u_p) (F₂·u_q)/(u_p × u_q). Then
//! R_A = Y − F₁ on b₁ at A, and the couples about jp's point P and jq's point Q from the
//! moments of b₁ about A and of b₂ about Q: M_p = M₁(A) − (P − A) × Y,
//! M_q = −M₂(Q) − M_p − (P − Q) × Y.
//!
//! In each, a link's anchor then moves as the material point it is
//! (`LinkState::set_velocity_at`, `set_acceleration_at`): v = v_P + ω perp(r),
//! a = a_P + α perp(r) − ω² r, with P the dyad's point on that link and r = anchor − P.

// One file per dyad, its derivation above; its kernels are public here, at the folder's
// path.
mod prp;
mod rpp;
mod rpr;
mod rrp;
mod rrr;

pub use prp::{prp_rates, prp_reactions};
pub use rpp::{rpp_rates, rpp_reactions};
pub use rpr::{rpr_rates, rpr_reactions};
pub use rrp::{rrp_rates, rrp_reactions};
pub use rrr::{rrr_rates, rrr_reactions};

use crate::kernel::constraints::JointGeom;
use crate::kernel::kinetostatics::{Reaction, Wrench};
use crate::kernel::linalg::Inverse2;
use crate::kernel::link_state::{cross, perp, zero, LinkState, V2};
use crate::MechError;

/// The velocity and acceleration (m/s, m/s²) of the material point of link `l` now at
/// `p`; zero on the ground (link 0), whose state is not read (as [`zero`], which the
/// compiler drops from the sums it enters).
#[inline(always)]
pub(crate) fn point_rates(s: &[LinkState], l: usize, p: V2) -> (V2, V2) {
    if l == 0 {
        (zero(), zero())
    } else {
        let r = p - s[l].pos;
        (s[l].vel_at(r), s[l].acc_at(r))
    }
}

/// The local vector in `body` of joint `g`'s point.
#[inline(always)]
pub(crate) fn local_in(g: &JointGeom, body: usize) -> V2 {
    if g.b == body {
        g.db
    } else {
        g.da
    }
}

/// The solved link on the other side of joint `g` from `body`.
#[inline(always)]
pub(crate) fn solved_link(g: &JointGeom, body: usize) -> usize {
    if g.b == body {
        g.a
    } else {
        g.b
    }
}

/// An RRP dyad's system [perp(e₁) −u] in the guide's frame ([`rrp_rates`]): the unit axis
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
/// transpose gives the reactions (the modules' docs), so that d'Alembert neither rebuilds it,
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
    /// An RPR dyad's [perp(d) u], in the guide's frame ([`SlideFrame`]'s system with its
    /// second column negated: the same frame, u, x, y and 1/x).
    Rpr(SlideFrame),
}

/// A link's wrench (force, moment about its anchor `pos`) as its force and its moment
/// about the point `p`: M_P = M + (pos − P) × F.
#[inline(always)]
pub(crate) fn about(w: &Wrench, pos: V2, p: V2) -> (V2, f64) {
    let f = V2::new(w.x, w.y);
    (f, w.z + cross(pos - p, f))
}

/// The point of the pin `g` between the solved link `solved` and the dyad's link `own`:
/// `own`'s anchor when its local vector there is zero (a literal zero in the generated
/// code, so the test folds and nothing is rotated), else the solved link's point.
#[inline(always)]
pub(crate) fn pin_point(s: &[LinkState], g: &JointGeom, solved: usize, own: usize) -> V2 {
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
pub(crate) fn about_point(w: &Wrench, pos: V2, p: V2, d: V2) -> (V2, f64) {
    if d == zero() {
        (V2::new(w.x, w.y), w.z)
    } else {
        about(w, pos, p)
    }
}

/// Add the force `force` at the point now at `p`, and the couple `couple`, to link `l`'s
/// wrench (about its anchor).
#[inline(always)]
pub(crate) fn push(f: &mut [Wrench], s: &[LinkState], l: usize, p: V2, force: V2, couple: f64) {
    let pos = if l == 0 { V2::zeros() } else { s[l].pos };
    f[l] += Wrench::new(force.x, force.y, couple + cross(p - pos, force));
}

/// The reaction at joint `g` reported by the convention (by `g.a` on `g.b`) from the
/// force and moment that link `on` receives through it.
#[inline(always)]
pub(crate) fn reported(g: &JointGeom, on: usize, force: V2, moment: f64) -> Reaction {
    if g.b == on {
        Reaction { force, moment }
    } else {
        Reaction {
            force: -force,
            moment: -moment,
        }
    }
}

#[cfg(test)]
mod tests;
