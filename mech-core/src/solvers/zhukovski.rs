//! Zhukovski's reduction of a one-DOF machine to its input coordinate q (`docs/theory.md` §6).
//!
//! With velocity coefficients g_j = ω_j / q̇ and g_Gj = v_Gj / q̇ (the velocities of the
//! motion with q̇ = 1, q̈ = 0), and their derivatives g'_j, g'_Gj (the accelerations of
//! that same motion):
//! - I*(q) = Σ (m_j |g_Gj|² + I_Gj g_j²)                       (kg·m² for a rotary input)
//! - dI*/dq = 2 Σ (m_j g_Gj·g'_Gj + I_Gj g_j g'_j)
//! - M*(q) = Σ F_k·g_k + Σ M_j g_j                               (N·m), gravity included,
//!   and the force elements' −Σ T x' (a damper's part −c x'² q̇ depends on q̇: it enters
//!   the direct problem, `reduced_moment` takes it at q̇ = 0)
//! - equation of motion: I* q̈ + ½ dI*/dq q̇² = driver + M*.

use crate::kernel::link_state::{perp, LinkGeom, LinkState, V2};

/// Reduced inertia and its derivative at one position.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Reduced {
    /// I*, kg·m² (kg for a prismatic input).
    pub inertia: f64,
    /// dI*/dq, kg·m²/rad (kg/m for a prismatic input).
    pub inertia_derivative: f64,
}

/// I* and dI*/dq from the states of the motion with q̇ = 1, q̈ = 0.
#[inline(always)]
pub fn reduced(links: &[LinkGeom], s: &[LinkState]) -> Reduced {
    let mut out = Reduced::default();
    for (l, st) in links.iter().zip(s) {
        if l.mass == 0.0 && l.inertia == 0.0 {
            continue;
        }
        let r = st.r(l.dcg);
        let (v, a) = (st.vel_at(r), st.acc_at(r));
        out.inertia += l.mass * v.norm_squared() + l.inertia * st.omega * st.omega;
        out.inertia_derivative += 2.0 * (l.mass * v.dot(&a) + l.inertia * st.omega * st.alpha);
    }
    out
}

/// The generalised acceleration q̈ = (driver + M* − ½ dI*/dq q̇²) / I*.
///
/// Errors: an I*, dI*/dq or M* that is not finite, an I* that is not positive
/// (`NonPositiveInertia`), a q̈ that overflows. The common path tests two things only:
/// 0 < 1/I* < ∞ (I* positive and finite) and q̈ finite, which a non-finite dI*/dq or M*
/// reaches (IEEE arithmetic: even ∞·0 is a NaN); which error it is is sorted out after.
/// "1/I* < ∞ and q̈ finite" is one test, (1/I*)·0 + q̈·0 = 0 (±0 for finite values, a NaN
/// otherwise): two compares and a branch, where the two comparisons with ∞ were compiled
/// to integer range tests on the bits (about ten more instructions per call).
#[inline]
pub fn acceleration(
    r: Reduced,
    moment: f64,
    qd: f64,
    driver: f64,
) -> Result<f64, crate::MechError> {
    // 1/I* needs only the velocities, so it is computed while the accelerations (dI*/dq)
    // are: a multiplication, not a division, ends the chain (the direct problem's steps
    // wait for each q̈); ½q̇² is ready before dI*/dq too. (Each term of dI*/dq is written
    // (2m) v·a + (2Iω) α for the same reason: the doublings, exact, leave the chain.)
    let inv = 1.0 / r.inertia;
    let qdd = (driver + moment - r.inertia_derivative * (0.5 * qd * qd)) * inv;
    if inv > 0.0 && inv * 0.0 + qdd * 0.0 == 0.0 {
        Ok(qdd)
    } else {
        acceleration_error(r, moment, qdd)
    }
}

/// [`acceleration`]'s error, in the order of its checks: I*, dI*/dq, M* finite, I* > 0,
/// then q̈ finite.
#[cold]
#[inline(never)]
fn acceleration_error(r: Reduced, moment: f64, qdd: f64) -> Result<f64, crate::MechError> {
    crate::kernel::finite::finite_few(
        "reduced inertia and moment",
        &[r.inertia, r.inertia_derivative, moment],
    )?;
    if !(r.inertia > 0.0) {
        return Err(crate::MechError::NonPositiveInertia(r.inertia));
    }
    crate::kernel::finite::finite_few("acceleration q̈ (with I*, M* and the driver)", &[qdd])?;
    Ok(qdd)
}

/// Zhukovski's sums accumulated link by link and load by load over the motion with q̇ = 1,
/// q̈ = 0 (whose velocities are the velocity coefficients g and whose accelerations are
/// their derivatives g'): I* = Σ (m |g_G|² + I_G g²), dI*/dq = 2 Σ (m g_G·g'_G + I_G g g'),
/// M* = Σ F·g_P + Σ M g + Σ m g·g_G (gravity). Each term is computed once from the link's
/// state, so the direct problem needs no wrench and no reaction.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct ZhukovskiSums {
    /// I* and dI*/dq so far.
    pub reduced: Reduced,
    /// M* so far, N·m (N for a prismatic input).
    pub moment: f64,
}

impl ZhukovskiSums {
    /// Empty sums, started at −0 (the identity of IEEE addition: the first term is taken
    /// as it is, and the compiler drops the addition).
    #[inline(always)]
    pub fn new() -> Self {
        ZhukovskiSums {
            reduced: Reduced {
                inertia: -0.0,
                inertia_derivative: -0.0,
            },
            moment: -0.0,
        }
    }
    /// Add a link's inertia to I* and dI*/dq (needs the accelerations of the motion).
    /// With r = G − anchor, a_G = a + α perp(r) − ω² r, so the term of dI*/dq is
    /// 2m v_G·(a − ω² r) + (2m v_G·perp(r) + 2Iω) α: α, the last number a group's solve
    /// gives, enters by one multiplication.
    #[inline(always)]
    pub fn inertia(&mut self, l: &LinkGeom, s: &LinkState) {
        self.inertia_at(l, s, s.r(l.dcg));
    }
    /// [`ZhukovskiSums::inertia`] for a link whose second point is the anchor of the link in
    /// state `next` ([`crate::model::Model::span_partner`]): the cg's offset from the
    /// span e = next.pos − pos ([`LinkGeom::cg_by_span`]), so that the sum waits for no
    /// rotation of the link.
    #[inline(always)]
    pub fn inertia_spanned(&mut self, l: &LinkGeom, s: &LinkState, next: &LinkState) {
        self.inertia_at(l, s, l.cg_by_span(next.pos - s.pos));
    }
    /// [`ZhukovskiSums::inertia`] with the cg's current offset from the anchor r = G − anchor
    /// given.
    #[inline(always)]
    pub fn inertia_at(&mut self, l: &LinkGeom, s: &LinkState, r: V2) {
        let v = s.vel_at(r);
        let m2 = 2.0 * l.mass;
        self.reduced.inertia += l.mass * v.norm_squared() + l.inertia * s.omega * s.omega;
        let without_alpha = m2 * v.dot(&(s.acc - r * (s.omega * s.omega)));
        let per_alpha = m2 * v.dot(&perp(r)) + 2.0 * l.inertia * s.omega;
        self.reduced.inertia_derivative += without_alpha + per_alpha * s.alpha;
    }
    /// Add the inertia of a link turning about a fixed pin O, its ground pivot
    /// ([`crate::model::Model::ground_pivot`], at the anchor or not): there v_G = ω perp(r)
    /// and v_G·a_G = ω α |r|² (r = G − O), so I* += I_O ω² and dI*/dq += 2 I_O ω α with
    /// I_O = I_G + m |r|² ([`LinkGeom::inertia_pivot`], kg·m²); no cg is placed.
    #[inline(always)]
    pub fn inertia_about_pivot(&mut self, l: &LinkGeom, s: &LinkState) {
        let io = l.inertia_pivot;
        self.reduced.inertia += io * s.omega * s.omega;
        self.reduced.inertia_derivative += (2.0 * io * s.omega) * s.alpha;
    }
    /// Add the inertia of a link that slides on the ground
    /// ([`crate::model::Model::translates`]): ω = α = 0, so I* += m |g_G|² and
    /// dI*/dq += 2 m g_G·g'_G with the cg moving as the anchor; no cg is placed.
    #[inline(always)]
    pub fn inertia_translating(&mut self, l: &LinkGeom, s: &LinkState) {
        self.reduced.inertia += l.mass * s.vel.norm_squared();
        self.reduced.inertia_derivative += (2.0 * l.mass) * s.vel.dot(&s.acc);
    }
    /// Add the power of gravity on a link that slides on the ground, m g·v (its cg moves
    /// as its anchor), to M*.
    #[inline(always)]
    pub fn gravity_translating(&mut self, l: &LinkGeom, s: &LinkState, g: V2) {
        self.moment += l.mass * g.dot(&s.vel);
    }
    /// Add the power of gravity on a link, m g·g_G, to M*.
    #[inline(always)]
    pub fn gravity(&mut self, l: &LinkGeom, s: &LinkState, g: V2) {
        self.gravity_at(l, s, g, s.r(l.dcg));
    }
    /// [`ZhukovskiSums::gravity`] for a link whose second point is the anchor of the link in
    /// state `next`, as [`ZhukovskiSums::inertia_spanned`].
    #[inline(always)]
    pub fn gravity_spanned(&mut self, l: &LinkGeom, s: &LinkState, next: &LinkState, g: V2) {
        self.gravity_at(l, s, g, l.cg_by_span(next.pos - s.pos));
    }
    /// [`ZhukovskiSums::gravity`] with the cg's offset r = G − anchor given.
    #[inline(always)]
    pub fn gravity_at(&mut self, l: &LinkGeom, s: &LinkState, g: V2, r: V2) {
        self.moment += l.mass * g.dot(&s.vel_at(r));
    }
    /// Add the power of a force `f` (N) at the material point of local vector `d`, f·g_P
    /// (g_P the anchor's when d = 0, a test that folds when d is a literal zero).
    #[inline(always)]
    pub fn force(&mut self, s: &LinkState, d: V2, f: V2) {
        let v = if d.x == 0.0 && d.y == 0.0 {
            s.vel
        } else {
            s.vel_at(s.r(d))
        };
        self.moment += f.dot(&v);
    }
    /// Add the power of a force `f` (N) on a link that slides on the ground
    /// ([`crate::model::Model::translates`]), f·v: every point of it moves as its anchor,
    /// wherever the force acts.
    #[inline(always)]
    pub fn force_translating(&mut self, s: &LinkState, f: V2) {
        self.moment += f.dot(&s.vel);
    }
    /// Add the power of a torque `t` (N·m) on a link, t g.
    #[inline(always)]
    pub fn torque(&mut self, s: &LinkState, t: f64) {
        self.moment += t * s.omega;
    }
    /// Add the force elements' part of M* at the input rate `qd`
    /// ([`crate::elements::springs::reduced_moment`]: −Σ T x', a damper's −c x'² q̇ included).
    #[inline(always)]
    pub fn elements(
        &mut self,
        e: &[crate::elements::springs::ElementGeom],
        s: &[LinkState],
        qd: f64,
    ) {
        self.moment += crate::elements::springs::reduced_moment(e, s, qd);
    }
}

#[cfg(test)]
mod tests {
    //! [`acceleration`]: its one test on the common path gives the errors of the checks it
    //! replaces, in their order.
    use super::{acceleration, Reduced};
    use crate::MechError;

    fn at(inertia: f64, inertia_derivative: f64) -> Reduced {
        Reduced {
            inertia,
            inertia_derivative,
        }
    }

    #[test]
    fn every_bad_reduced_quantity_is_an_error_of_its_kind() {
        let (inf, nan) = (f64::INFINITY, f64::NAN);
        // q̈ = (5 + 1 − ½·0.5·2²)/2 = 2.5.
        assert_eq!(acceleration(at(2.0, 0.5), 1.0, 2.0, 5.0).unwrap(), 2.5);
        let overflow = |r: Result<f64, MechError>| matches!(r, Err(MechError::InvalidInput(ref m)) if m.contains("reduced inertia and moment"));
        for (i, d, m, qd) in [
            (inf, 0.5, 1.0, 2.0),
            (nan, 0.5, 1.0, 2.0),
            (-inf, 0.5, 1.0, 2.0),
            (2.0, inf, 1.0, 2.0),
            (2.0, inf, 1.0, 0.0),
            (2.0, nan, 1.0, 2.0),
            (2.0, 0.5, -inf, 2.0),
            (2.0, 0.5, nan, 0.0),
            // Not finite wins over not positive, as before.
            (-1.0, nan, 1.0, 2.0),
        ] {
            assert!(
                overflow(acceleration(at(i, d), m, qd, 5.0)),
                "{i} {d} {m} {qd}"
            );
        }
        for i in [0.0, -0.0, -3.0] {
            assert!(matches!(
                acceleration(at(i, 0.5), 1.0, 2.0, 5.0),
                Err(MechError::NonPositiveInertia(v)) if v == i
            ));
        }
        // Finite and positive I*, but q̈ overflows.
        assert!(matches!(
            acceleration(at(1e-300, 0.5), 1e300, 2.0, 5.0),
            Err(MechError::InvalidInput(ref m)) if m.contains("acceleration q̈")
        ));
    }
}
