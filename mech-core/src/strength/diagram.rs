//! The internal forces along one link at one instant: its axial force N(s), shear V(s) and
//! bending moment M(s), from every action on it.
//!
//! The link is a beam along its axis, the segment of its first two points A (s = 0) and
//! B (s = L), with the unit vectors e = (B − A)/L and n = e rotated +90°. An action at a
//! point P of the link (a reaction, a load, the motor's torque) is moved to the axis at
//! s = (P − A)·e with the couple (P − A − s e) × F it makes there. The link's own weight and inertia are the distributed load of its mass
//! spread evenly over [0, L], q(s) = (m/L)(g − a(s)), linear in s because a rigid link's
//! acceleration a(s) = a_A + α × s e − ω² s e is (the connecting rod's "whip"); what the
//! link's exact mass properties add to that (its rounded ends, a cg off the middle, I_G
//! against m L²/12) is two end forces, so that the diagram closes (N = V = M = 0 past
//! both ends) exactly when the actions balance.
//!
//! Sectioning at s, the part [s_min, s] feels the sum of the actions on it, F_left and
//! the moment M_left about the section, and the internal action of the rest: N = −F_left·e
//! (tension positive), V = −F_left·n, M = −M_left. The extremes of M lie at the point
//! actions, the ends and where V = 0 (dM/ds = −V), a root of a quadratic in each stretch
//! between two point actions.

use crate::kernel::link_state::{cross, perp, V2};
use smallvec::SmallVec;

/// The internal forces at a section: axial N (N, tension positive), shear V (N) and
/// bending moment M (N·m).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Internal {
    /// N, N (tension positive).
    pub axial: f64,
    /// V, N.
    pub shear: f64,
    /// M, N·m.
    pub moment: f64,
}

/// A point action on the axis: where (s, m), the force's axial and transverse components
/// (N) and a couple (N·m).
#[derive(Clone, Copy, Debug, PartialEq)]
struct Action {
    s: f64,
    axial: f64,
    transverse: f64,
    couple: f64,
}

/// The actions on one link at one instant, in the link's frame.
#[derive(Clone, Debug, PartialEq)]
pub struct Diagram {
    a: V2,
    e: V2,
    length: f64,
    actions: SmallVec<[Action; 8]>,
    /// The distributed load q(s) = q0 + q1 s, axial and transverse components, N/m and N/m².
    q0: [f64; 2],
    q1: [f64; 2],
}

impl Diagram {
    /// A link along A → B, no action yet.
    pub fn new(a: V2, b: V2) -> Diagram {
        let d = b - a;
        let length = (d.x * d.x + d.y * d.y).sqrt();
        Diagram {
            a,
            e: V2::new(d.x / length, d.y / length),
            length,
            actions: SmallVec::new(),
            q0: [0.0; 2],
            q1: [0.0; 2],
        }
    }

    /// L, m.
    pub fn length(&self) -> f64 {
        self.length
    }

    fn n(&self) -> V2 {
        perp(self.e)
    }

    /// Where the point `p` projects on the axis: s = (P − A)·e, m.
    pub fn station(&self, p: V2) -> f64 {
        (p - self.a).dot(&self.e)
    }

    /// A force `f` (N, global) at the point `p` (m) and a couple `c` (N·m, CCW).
    pub fn add(&mut self, p: V2, f: V2, c: f64) {
        let s = self.station(p);
        let arm = p - self.a - self.e * s;
        self.actions.push(Action {
            s,
            axial: f.dot(&self.e),
            transverse: f.dot(&self.n()),
            couple: c + cross(arm, f),
        });
    }

    /// The link's weight and inertia: mass `m` (kg), I_G (kg·m²) and cg `g_pos` (m); ω
    /// (rad/s), α (rad/s²), the cg's acceleration (m/s²) and gravity (m/s²). The mass is
    /// spread over [0, L]; the rest of the d'Alembert force −m(a_G − g) and moment
    /// −I_G α is put at the ends.
    #[allow(clippy::too_many_arguments)]
    pub fn add_body(
        &mut self,
        m: f64,
        inertia: f64,
        g_pos: V2,
        omega: f64,
        alpha: f64,
        acc_g: V2,
        gravity: V2,
    ) {
        let (l, e, n) = (self.length, self.e, self.n());
        // a(s) of the axis point at s: a_G + α k × (P − G) − ω² (P − G).
        let r = self.a - g_pos;
        let acc_a = acc_g + perp(r) * alpha - r * (omega * omega);
        let acc_s = n * alpha - e * (omega * omega); // d a / d s
        let rho = m / l;
        let w0 = (gravity - acc_a) * rho;
        let w1 = -acc_s * rho;
        self.q0 = [w0.dot(&e), w0.dot(&n)];
        self.q1 = [w1.dot(&e), w1.dot(&n)];
        // The distributed load's resultant and moment about A against the exact ones.
        let f_d = w0 * l + w1 * (l * l / 2.0);
        let m_d = cross(e, w0) * l * l / 2.0 + cross(e, w1) * l * l * l / 3.0;
        let f_x = (gravity - acc_g) * m;
        let m_x = cross(g_pos - self.a, f_x) - inertia * alpha;
        let (df, dm) = (f_x - f_d, m_x - m_d);
        let at_b = n * (dm / l);
        self.add(self.a + e * l, at_b, 0.0);
        self.add(self.a, df - at_b, 0.0);
    }

    /// The internal forces at s (m): the part up to s taken with the point actions at s
    /// when `past` (the right-hand limit), without them otherwise.
    pub fn at(&self, s: f64, past: bool) -> Internal {
        let (mut fa, mut ft, mut m) = (0.0, 0.0, 0.0);
        for a in &self.actions {
            if a.s < s || (past && a.s == s) {
                fa += a.axial;
                ft += a.transverse;
                m += a.couple + (a.s - s) * a.transverse;
            }
        }
        let t = s.clamp(0.0, self.length);
        let (q0, q1) = (self.q0, self.q1);
        fa += q0[0] * t + q1[0] * t * t / 2.0;
        ft += q0[1] * t + q1[1] * t * t / 2.0;
        m += q0[1] * (t * t / 2.0 - s * t) + q1[1] * (t * t * t / 3.0 - s * t * t / 2.0);
        Internal {
            axial: -fa,
            shear: -ft,
            moment: -m,
        }
    }

    /// The span of the link's actions, [min(0, s_i), max(L, s_i)], m.
    pub fn span(&self) -> (f64, f64) {
        self.actions
            .iter()
            .fold((0.0f64, self.length), |(lo, hi), a| {
                (lo.min(a.s), hi.max(a.s))
            })
    }

    /// The stations of the point actions, sorted, each once.
    pub fn stations(&self) -> SmallVec<[f64; 8]> {
        let mut s: SmallVec<[f64; 8]> = self.actions.iter().map(|a| a.s).collect();
        s.sort_by(f64::total_cmp);
        s.dedup();
        s
    }

    /// Where V = 0 between the point actions: the interior extremes of M.
    pub fn shear_zeros(&self) -> SmallVec<[f64; 8]> {
        let stations = self.stations();
        let mut out = SmallVec::new();
        for w in stations.windows(2) {
            let (lo, hi) = (w[0], w[1].min(self.length));
            if hi <= lo || lo >= self.length {
                continue;
            }
            // V(s) = −(P + q0 s + q1 s²/2) with P the transverse sum left of the stretch.
            let p: f64 = self
                .actions
                .iter()
                .filter(|a| a.s <= lo)
                .map(|a| a.transverse)
                .sum();
            let lo = lo.max(0.0);
            let (a, b, c) = (self.q1[1] / 2.0, self.q0[1], p);
            let mut roots = [f64::NAN; 2];
            if a.abs() > 1e-300 {
                let disc = b * b - 4.0 * a * c;
                if disc >= 0.0 {
                    let q = -0.5 * (b + b.signum() * disc.sqrt());
                    roots = [q / a, if q != 0.0 { c / q } else { f64::NAN }];
                }
            } else if b != 0.0 {
                roots[0] = -c / b;
            }
            out.extend(roots.into_iter().filter(|r| *r > lo && *r < hi));
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::strength::beam;

    /// A connecting rod along x, pinned at both ends, its whip only: a crank-end
    /// acceleration a_B transverse, the gudgeon end still (α L = a_B): the triangular load
    /// and its largest moment w L²/(9√3) at L/√3 (strength::beam's closed form).
    #[test]
    fn the_whip_of_a_uniform_rod_matches_the_closed_form() {
        let (m, l, a_b) = (1.2, 0.15, 2000.0);
        let alpha = a_b / l;
        let mut d = Diagram::new(V2::new(0.0, 0.0), V2::new(l, 0.0));
        let g = V2::new(l / 2.0, 0.0);
        let inertia = m * l * l / 12.0;
        // The gudgeon pin still: a_G = α × (G − A) = α l/2 ŷ.
        d.add_body(
            m,
            inertia,
            g,
            0.0,
            alpha,
            V2::new(0.0, alpha * l / 2.0),
            V2::zeros(),
        );
        let w = m / l * a_b;
        // End reactions balancing the inertia load −w s/L: V_A = wL/6 at A, wL/3 at B (up).
        d.add(V2::new(0.0, 0.0), V2::new(0.0, w * l / 6.0), 0.0);
        d.add(V2::new(l, 0.0), V2::new(0.0, w * l / 3.0), 0.0);
        let zeros = d.shear_zeros();
        assert_eq!(zeros.len(), 1, "{zeros:?}");
        let (s_exact, m_exact) = beam::largest_moment(w * l / 6.0, 0.0, w, l);
        assert!((zeros[0] - s_exact).abs() < 1e-14, "{zeros:?}");
        let mm = d.at(zeros[0], false).moment.abs();
        assert!((mm - m_exact.abs()).abs() < 1e-12 * mm, "{mm} {m_exact}");
        // The diagram closes past B.
        let end = d.at(l, true);
        assert!(
            end.axial.abs() < 1e-9 && end.shear.abs() < 1e-9 && end.moment.abs() < 1e-9,
            "{end:?}"
        );
    }

    /// A crank O→A driven by a torque T at O against a tip force P normal to it: M at the
    /// root T = P L, falling linearly to 0 at A; N from an axial tip pull.
    #[test]
    fn a_crank_under_a_tip_load() {
        let (l, p, pull) = (0.1, 500.0, 300.0);
        let (o, a) = (V2::new(0.0, 0.0), V2::new(0.0, l));
        let mut d = Diagram::new(o, a);
        // e = +y, n = −x: a force −x at the tip is +transverse.
        d.add(a, V2::new(-p, pull), 0.0);
        d.add(o, V2::new(p, -pull), -p * l);
        let root = d.at(0.0, true);
        assert!((root.moment.abs() - p * l).abs() < 1e-12);
        assert!((root.axial - pull).abs() < 1e-12, "tension: {root:?}");
        assert!((d.at(l / 2.0, false).moment.abs() - p * l / 2.0).abs() < 1e-12);
        assert!(d.at(l, true).moment.abs() < 1e-12);
    }
}
