//! Zhukovski's reduced inertia of a machine of constant ratios as a trigonometric sum of q,
//! worked out once.
//!
//! In a machine of gears (`crate::plan::ratios`) every link turns at a constant multiple
//! k_l of the input rate and hangs from the ground through a chain of pins. The velocity
//! coefficient of a point X of link l is then, with u = q − q₀ and the chain's links
//! j₁ = l, j₂, … down to the ground,
//!
//! g_X(q) = Σ_i R(k_i u) a_i,  a_i = k_i perp(Y_{i−1} − Y_i) (a turning link, Y_i its pin
//! and Y₀ = X, all at q₀), a_i = v_i (a link sliding on the ground: its constant velocity
//! coefficient),
//!
//! and with (R(α) a)·(R(β) b) = cos(β − α) a·b − sin(β − α) a × b,
//!
//! I*(q) = C + Σ_t (A_t cos Δ_t u + B_t sin Δ_t u),
//! dI*/dq = Σ_t Δ_t (B_t cos Δ_t u − A_t sin Δ_t u),
//!
//! C = Σ_l (m_l Σ_i |a_i|² + I_l k_l²) (kg·m²), and one term per pair i < i' of a chain:
//! Δ = k_{i'} − k_i, A = 2 m_l a_i·a_{i'}, B = −2 m_l a_i × a_{i'}. A planetary's I* is one
//! constant and one cosine of the planet's angle to its arm, where solving every link's
//! motion at each q costs the train's solve and a sum over the links. Gears on fixed
//! axes leave no term (the sum is the constant C).

use crate::kernel::constraints::JointGeom;
use crate::kernel::link_state::{cross, perp, point_of, LinkGeom, LinkState};
use crate::plan::ratios::{chain, Pin};
use crate::solvers::zhukovski::Reduced;
use crate::MechError;

/// One oscillating term of I*: A cos Δu + B sin Δu, u = q − q₀.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Term {
    /// Δ, the difference of two links' velocity coefficients (rad/rad).
    pub rate: f64,
    /// A (kg·m²).
    pub cos: f64,
    /// B (kg·m²).
    pub sin: f64,
}

/// I*(q) as a constant and oscillating terms about the reference input `q0`: `terms` an
/// array (`[Term; N]`, the generated struct: N from the topology) or a `Vec` (the run-time
/// mechanism).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Series<T> {
    /// q₀ (rad, or m for a prismatic input).
    pub q0: f64,
    /// C (kg·m²).
    pub constant: f64,
    /// The oscillating terms.
    pub terms: T,
}

impl<T: AsRef<[Term]>> Series<T> {
    /// I* and dI*/dq at `q` (see the module's docs).
    #[inline(always)]
    pub fn at(&self, q: f64) -> Reduced {
        let u = q - self.q0;
        let mut r = Reduced {
            inertia: self.constant,
            inertia_derivative: 0.0,
        };
        for t in self.terms.as_ref() {
            let (s, c) = (t.rate * u).sin_cos();
            r.inertia += t.cos * c + t.sin * s;
            r.inertia_derivative += t.rate * (t.sin * c - t.cos * s);
        }
        r
    }
}

impl<T: AsRef<[Term]> + AsMut<[Term]>> Series<T> {
    /// The series about q₀ from the motion `s` at q₀ with q̇ = 1 (the module's formulas),
    /// its terms written into `terms` (`crate::plan::ratios::series_len` long): the links'
    /// mass data `links`, the joints `joints`, each link's [`Pin`]. `Overflow` when a
    /// coefficient is not finite.
    pub fn from_motion(
        q0: f64,
        mut terms: T,
        links: &[LinkGeom],
        s: &[LinkState],
        joints: &[JointGeom],
        pins: &[Pin],
    ) -> Result<Self, MechError> {
        let constant = fill(links, s, joints, pins, terms.as_mut());
        for t in terms.as_ref() {
            crate::kernel::finite::finite_few("reduced inertia", &[t.rate, t.cos, t.sin])?;
        }
        crate::kernel::finite::finite_few("reduced inertia", &[constant])?;
        Ok(Series {
            q0,
            constant,
            terms,
        })
    }
}

/// Fill `terms` (one per pair of links on a chain, in the order of the links and their
/// chains: `crate::plan::ratios::series_len` of them) and return C, from the motion `s` at
/// q₀ with q̇ = 1 (each state's `omega` its k_l, `vel` its velocity coefficient), the
/// links' mass data `links`, the joints `joints` and each link's [`Pin`].
fn fill(
    links: &[LinkGeom],
    s: &[LinkState],
    joints: &[JointGeom],
    pins: &[Pin],
    terms: &mut [Term],
) -> f64 {
    // The point of link `j`'s own pin, where it hangs from its parent.
    let pin_point = |j: usize| {
        let g = &joints[pins[j].joint];
        if g.a == j {
            point_of(s, j, g.da)
        } else {
            point_of(s, j, g.db)
        }
    };
    // (k_i, a_i) down the chain of link `l` from its cg.
    let parts = |l: usize| {
        let st = &s[l];
        chain(pins, l).scan(st.pos + st.r(links[l].dcg), move |here, j| {
            Some(if pins[j].slides {
                (0.0, s[j].vel)
            } else {
                let y = pin_point(j);
                let a = perp(*here - y) * s[j].omega;
                *here = y;
                (s[j].omega, a)
            })
        })
    };
    let mut constant = 0.0;
    let mut t = 0;
    for l in 1..links.len().min(s.len()).min(pins.len()) {
        let m = links[l].mass;
        constant += links[l].inertia * s[l].omega * s[l].omega;
        for (i, (ki, ai)) in parts(l).enumerate() {
            constant += m * ai.norm_squared();
            for (kj, aj) in parts(l).skip(i + 1) {
                if let Some(slot) = terms.get_mut(t) {
                    *slot = Term {
                        rate: kj - ki,
                        cos: 2.0 * m * ai.dot(&aj),
                        sin: -2.0 * m * cross(ai, aj),
                    };
                }
                t += 1;
            }
        }
    }
    constant
}

#[cfg(test)]
mod tests {
    use super::{fill, Series, Term};

    #[test]
    fn one_term_turns_through_its_cosine_and_its_derivative() {
        let s = Series {
            q0: 0.5,
            constant: 2.0,
            terms: [Term {
                rate: 0.6,
                cos: 0.3,
                sin: -0.2,
            }],
        };
        for q in [-3.0, 0.5, 1.0, 40.0] {
            let u = 0.6 * (q - 0.5);
            let r = s.at(q);
            assert!((r.inertia - (2.0 + 0.3 * u.cos() - 0.2 * u.sin())).abs() < 1e-15);
            // Against a central difference of I*.
            let h = 1e-6;
            let fd = (s.at(q + h).inertia - s.at(q - h).inertia) / (2.0 * h);
            assert!((r.inertia_derivative - fd).abs() < 1e-9);
        }
        assert_eq!(fill(&[], &[], &[], &[], &mut []), 0.0);
    }
}
