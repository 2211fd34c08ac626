//! Velocities, accelerations and reactions of the three commonest dyads in their natural
//! coordinates (`docs/theory.md` §3.5): the two link angles of an RRR dyad ([`rrr`]), the
//! link angle and the slide of an RRP dyad ([`rrp`]), the common angle and the slide of an
//! RPR dyad ([`rpr`]). Each is one 2×2 system written out, its matrix the same for
//! velocities and accelerations, its transpose that of the reactions (d'Alembert); the
//! other closed-form groups go through the joint screws of [`crate::kernel::screw`].
//!
//! In each, a link's anchor then moves as the material point it is
//! (`LinkState::set_velocity_at`, `set_acceleration_at`): v = v_P + ω perp(r),
//! a = a_P + α perp(r) − ω² r, with P the dyad's point on that link and r = anchor − P.

pub mod rpr;
pub mod rrp;
pub mod rrr;

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

/// An RRP dyad's system [perp(e₁) −u] in the guide's frame ([`rrp`]): the unit axis
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
