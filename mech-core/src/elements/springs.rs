//! Force elements (`docs/theory.md` §10, `docs/conventions.md#elements`): linear springs and
//! dampers between two points, torsion springs and rotary dampers between two links. Each
//! is a spring–damper along its *extension* x:
//!
//! - linear (points P of link a, Q of link b): x = L = |Q − P|, ẋ = e·(v_Q − v_P) with
//!   e = (Q − P)/L; the tension T = k (L − L₀) + c L̇ pulls the points together: −T e on b
//!   at Q, +T e on a at P;
//! - rotary (links a, b): x = θ_b − θ_a, ẋ = ω_b − ω_a; the moment −T on b and +T on a,
//!   with T = k wrap(x − φ₀) + c ẋ (the deflection taken in (−π, π], the shortest turn
//!   from the free angle).
//!
//! A spring has c = 0, a damper k = 0. From T and x every route follows, each formula
//! here once: the wrenches of d'Alembert ([`add_wrenches`]), the power −T ẋ of virtual
//! power ([`power`]), Zhukovski's reduced moment −T x' with x' = dx/dq
//! ([`reduced_moment`]), the potential energy ½ k (x − x₀)² ([`potential`]) and the
//! dissipated power c ẋ² ([`dissipation`]).

use crate::kernel::kinetostatics::Wrench;
use crate::kernel::link_state::{cross, wrap, LinkState, V2};

/// One force element with its points as local vectors of its links (see the module docs).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ElementGeom {
    /// First link (P's).
    pub a: usize,
    /// Second link (Q's).
    pub b: usize,
    /// True for a torsion spring or rotary damper (no points).
    pub rotary: bool,
    /// Local vector of P in link a (linear elements), m.
    pub da: V2,
    /// Local vector of Q in link b (linear elements), m.
    pub db: V2,
    /// k, N/m or N·m/rad.
    pub stiffness: f64,
    /// c, N·s/m or N·m·s/rad.
    pub damping: f64,
    /// x₀, the free length (m) or free angle (rad).
    pub free: f64,
    /// Rotary elements: θ_b − θ_a in the drawing (rad), to which the links' rotations since
    /// the drawing are added.
    pub reference: f64,
}

/// An element's extension in one motion state.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Stretch {
    /// x − x₀: the spring's deflection (m, or rad in (−π, π]).
    pub deflection: f64,
    /// ẋ, m/s or rad/s (per unit q̇ in a state of velocity coefficients).
    pub rate: f64,
    /// e, the unit vector from P to Q (linear elements; zero for rotary ones).
    pub e: V2,
    /// R(φ_a) d_a, P relative to a's anchor.
    pub ra: V2,
    /// R(φ_b) d_b, Q relative to b's anchor.
    pub rb: V2,
}

impl ElementGeom {
    /// The extension of the element in the states `s` (the ground's state, index 0, at rest
    /// and unrotated). A linear element whose points coincide (L = 0) has no direction e:
    /// a spring of zero free length and no damping pulls with T = k L = 0 there, and gets
    /// e = 0, L̇ = 0 (its force k (Q − P) and power are zero, their limits); any other
    /// element's force is undefined there, and its e and rate are NaN, which the callers'
    /// finiteness checks catch and [`undirected`] names.
    #[inline(always)]
    pub fn stretch(&self, s: &[LinkState]) -> Stretch {
        let (sa, sb) = (&s[self.a], &s[self.b]);
        if self.rotary {
            let rel = V2::new(sa.rot.dot(&sb.rot), cross(sa.rot, sb.rot));
            return Stretch {
                deflection: wrap(self.reference + rel.y.atan2(rel.x) - self.free),
                rate: sb.omega - sa.omega,
                e: V2::zeros(),
                ra: V2::zeros(),
                rb: V2::zeros(),
            };
        }
        let (ra, rb) = (sa.r(self.da), sb.r(self.db));
        let d = (sb.pos + rb) - (sa.pos + ra);
        let l = d.norm();
        let e = if l > 0.0 {
            d / l
        } else if self.pulls_at_zero_length() {
            V2::new(f64::NAN, f64::NAN)
        } else {
            V2::zeros()
        };
        Stretch {
            deflection: l - self.free,
            rate: e.dot(&(sb.vel_at(rb) - sa.vel_at(ra))),
            e,
            ra,
            rb,
        }
    }

    /// True when the linear element has a force at zero length, whose direction is then
    /// undefined: a stiffness with a free length, or a damping (a spring of zero free
    /// length and no damping has none).
    #[inline(always)]
    pub fn pulls_at_zero_length(&self) -> bool {
        (self.stiffness != 0.0 && self.free != 0.0) || self.damping != 0.0
    }

    /// T = k (x − x₀) + c ẋ (N or N·m), with ẋ = `rate`.
    #[inline(always)]
    pub fn tension(&self, st: &Stretch, rate: f64) -> f64 {
        self.stiffness * st.deflection + self.damping * rate
    }
}

/// The first linear element whose points coincide in the states `s` while it has a force
/// there ([`ElementGeom::pulls_at_zero_length`]): its index and where its points are (m).
/// Its force has no direction, so every result it enters is NaN; the solvers look here
/// when a result is not finite, to say so instead of reporting an overflow.
#[cold]
pub fn undirected(elements: &[ElementGeom], s: &[LinkState]) -> Option<(usize, V2)> {
    elements.iter().enumerate().find_map(|(k, el)| {
        if el.rotary || !el.pulls_at_zero_length() {
            return None;
        }
        let (sa, sb) = (&s[el.a], &s[el.b]);
        let (p, q) = (sa.pos + sa.r(el.da), sb.pos + sb.r(el.db));
        ((q - p).norm() == 0.0).then_some((k, p))
    })
}

/// Add every element's forces to the links' wrenches `f` (about their anchors) in the
/// states `s`: −T e at Q on b and +T e at P on a (a rotary element: −T on b, +T on a).
#[inline(always)]
pub fn add_wrenches(elements: &[ElementGeom], s: &[LinkState], f: &mut [Wrench]) {
    for el in elements {
        let st = el.stretch(s);
        let t = el.tension(&st, st.rate);
        if el.rotary {
            f[el.b].z -= t;
            f[el.a].z += t;
        } else {
            let force = st.e * t;
            f[el.b] -= Wrench::new(force.x, force.y, cross(st.rb, force));
            f[el.a] += Wrench::new(force.x, force.y, cross(st.ra, force));
        }
    }
}

/// The power of the elements' forces in the motion `s`, P = −Σ T ẋ (W).
#[inline(always)]
pub fn power(elements: &[ElementGeom], s: &[LinkState]) -> f64 {
    elements
        .iter()
        .map(|el| {
            let st = el.stretch(s);
            -el.tension(&st, st.rate) * st.rate
        })
        .sum()
}

/// The elements' part of Zhukovski's reduced moment, M* = −Σ T x' (N·m, or N for a
/// prismatic input), from the states of the motion with q̇ = 1 (whose rates are the
/// velocity coefficients x' = dx/dq) at the input rate `qd`: T = k (x − x₀) + c q̇ x', so a
/// damper adds −c x'² q̇ (zero at `qd` = 0).
#[inline(always)]
pub fn reduced_moment(elements: &[ElementGeom], s: &[LinkState], qd: f64) -> f64 {
    elements
        .iter()
        .map(|el| {
            let st = el.stretch(s);
            -el.tension(&st, qd * st.rate) * st.rate
        })
        .sum()
}

/// The potential energy of the springs, V = Σ ½ k (x − x₀)² (J).
#[inline]
pub fn potential(elements: &[ElementGeom], s: &[LinkState]) -> f64 {
    elements
        .iter()
        .map(|el| {
            let st = el.stretch(s);
            0.5 * el.stiffness * st.deflection * st.deflection
        })
        .sum()
}

/// The power the dampers dissipate, Σ c ẋ² ≥ 0 (W).
#[inline]
pub fn dissipation(elements: &[ElementGeom], s: &[LinkState]) -> f64 {
    elements
        .iter()
        .map(|el| {
            let st = el.stretch(s);
            el.damping * st.rate * st.rate
        })
        .sum()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::kernel::measure::within;

    fn linear(k: f64, c: f64, free: f64) -> ElementGeom {
        ElementGeom {
            a: 0,
            b: 1,
            rotary: false,
            da: V2::new(0.0, 0.0),
            db: V2::new(0.1, 0.0),
            stiffness: k,
            damping: c,
            free,
            reference: 0.0,
        }
    }

    /// A link at (0.3, 0.4) + R(90°)(0.1, 0) = (0.3, 0.5), moving at (1, 2) with ω = 3:
    /// the spring from the origin has L = |(0.3, 0.5)|, L̇ = e·v_Q, and its forces, power,
    /// reduced moment, energy and dissipation follow the closed forms.
    #[test]
    fn linear_element_closed_forms() {
        let mut b = LinkState::at(V2::new(0.3, 0.4));
        b.rot = V2::new(0.0, 1.0);
        b.vel = V2::new(1.0, 2.0);
        b.omega = 3.0;
        let s = [LinkState::default(), b];
        let q = V2::new(0.3, 0.5);
        let vq = V2::new(1.0 - 3.0 * 0.1, 2.0);
        let l = q.norm();
        let e = q / l;
        let ldot = e.dot(&vq);
        let (k, c, l0) = (2000.0, 15.0, 0.4);
        let el = linear(k, c, l0);
        let t = k * (l - l0) + c * ldot;
        let close = |x: f64, y: f64| {
            assert!(
                within((x - y).abs(), 2e-14 * y.abs().max(1.0)),
                "{x} vs {y}"
            )
            // measured worst 2.1e-16 (be05608); 100×
        };
        let mut f = [Wrench::zeros(); 2];
        add_wrenches(&[el], &s, &mut f);
        close(f[1].x, -t * e.x);
        close(f[1].y, -t * e.y);
        // Moment about b's anchor of −T e at Q, r = Q − anchor = (0, 0.1).
        close(f[1].z, cross(V2::new(0.0, 0.1), -e * t));
        close(f[0].x, t * e.x);
        close(f[0].z, 0.0);
        close(power(&[el], &s), -t * ldot);
        // The states as velocity coefficients at q̇ = 2: the damper's force doubles.
        close(
            reduced_moment(&[el], &s, 2.0),
            -(k * (l - l0) + c * 2.0 * ldot) * ldot,
        );
        close(potential(&[el], &s), 0.5 * k * (l - l0).powi(2));
        close(dissipation(&[el], &s), c * ldot * ldot);
        // The power of the wrenches equals −T L̇ (virtual power of the same forces).
        close(
            crate::kernel::kinetostatics::virtual_power(&f, &s),
            -t * ldot,
        );
    }

    /// Ends at the same place: a spring of zero free length and no damper pulls with
    /// k (Q − P) = 0 (finite, zero on every route); one with a free length, or a damper,
    /// has no direction there (NaN, which `undirected` names).
    #[test]
    fn coincident_ends() {
        let mut b = LinkState::at(V2::new(-0.1, 0.0));
        b.omega = 3.0;
        let s = [LinkState::default(), b];
        let zero = linear(2000.0, 0.0, 0.0);
        let st = zero.stretch(&s);
        assert_eq!((st.e, st.rate, st.deflection), (V2::zeros(), 0.0, 0.0));
        let mut f = [Wrench::zeros(); 2];
        add_wrenches(&[zero], &s, &mut f);
        assert_eq!(f, [Wrench::zeros(); 2]);
        assert_eq!(power(&[zero], &s), 0.0);
        assert_eq!(reduced_moment(&[zero], &s, 2.0), 0.0);
        assert_eq!(undirected(&[zero], &s), None);
        for el in [linear(2000.0, 0.0, 0.08), linear(0.0, 5.0, 0.0)] {
            assert!(power(&[el], &s).is_nan());
            assert_eq!(undirected(&[zero, el], &s), Some((1, V2::zeros())));
            // The potential ½ k (0 − L₀)² needs no direction.
            assert!(potential(&[el], &s).is_finite());
        }
    }

    /// A torsion spring turned past ±π from its free angle takes the shortest turn back.
    #[test]
    fn rotary_element_deflection_and_moments() {
        let el = ElementGeom {
            a: 0,
            b: 1,
            rotary: true,
            da: V2::zeros(),
            db: V2::zeros(),
            stiffness: 5.0,
            damping: 0.5,
            free: 0.2,
            reference: 0.3,
        };
        let mut b = LinkState::default();
        let phi: f64 = 3.2;
        b.rot = V2::new(phi.cos(), phi.sin());
        b.omega = -2.0;
        let s = [LinkState::default(), b];
        let st = el.stretch(&s);
        let defl = 0.3 + 3.2 - 0.2 - std::f64::consts::TAU;
        // measured worst 4.4e-16 (be05608); 100×
        assert!(
            within((st.deflection - defl).abs(), 1e-14),
            "{}",
            st.deflection
        );
        let t = 5.0 * defl + 0.5 * -2.0;
        let mut f = [Wrench::zeros(); 2];
        add_wrenches(&[el], &s, &mut f);
        // measured worst 3.6e-15 (be05608); 100×
        assert!(within((f[1].z + t).abs(), 1e-14) && within((f[0].z - t).abs(), 1e-14));
        // measured worst 7.1e-15 (be05608); 100×
        assert!(within((power(&[el], &s) - (-t * -2.0)).abs(), 1e-13));
    }
}
