//! Energies of one link (`docs/theory.md` §6): the kinetic energy, its rate, and the
//! potential energy of gravity. The generated `link_kinetic_energies` and
//! `potential_energy` call these once per link whose declaration has the term (see
//! [`crate::solvers::params::LinkTerms`]), with the run-time mass and inertia; units SI.

use crate::kernel::link_state::{cross, perp, rotate, LinkGeom, LinkMotion, V2};

/// Kinetic energy of a link, T = ½ (m |v_G|² + I_G ω²) (J), with m (kg), I_G (kg·m²)
/// from `l` and the cg velocity v_G (m/s) and angular velocity ω (rad/s) from `m`.
#[inline]
pub fn kinetic(l: &LinkGeom, m: &LinkMotion) -> f64 {
    0.5 * (l.mass * m.cg_vel.norm_squared() + l.inertia * m.omega * m.omega)
}

/// Rate of change of a link's kinetic energy, dT/dt = m v_G·a_G + I_G ω α (W), with the
/// cg acceleration a_G (m/s²) and angular acceleration α (rad/s²) from `m`.
#[inline]
pub fn kinetic_rate(l: &LinkGeom, m: &LinkMotion) -> f64 {
    l.mass * m.cg_vel.dot(&m.cg_acc) + l.inertia * m.omega * m.alpha
}

/// Potential energy of gravity of a link, V = −m g·r_G (J), with gravity g (m/s²) and the
/// cg position r_G (m) from `m`; zero at the origin of the global frame.
#[inline]
pub fn potential(l: &LinkGeom, m: &LinkMotion, g: V2) -> f64 {
    -(l.mass * g.dot(&m.cg))
}

/// The shaking force and moment of a machine on its frame (`docs/theory.md` §14,
/// SPEC 3g): what the moving links and the motor's stator put on the frame by the links'
/// inertia, with no loads and no gravity, F = −Σ m a_G (N) and, about the origin of the
/// global frame, M = −Σ (r_G × m a_G + I_G α) (N·m, counter-clockwise positive).
///
/// With links in several planes along the shaft axis z (`plane: z`), the inertia forces
/// −mᵢ aᵢ of the mass elements at heights zᵢ also have couples about the transverse axes,
/// M = Σ rᵢ × fᵢ: Mx = −Σ zᵢ f_yᵢ = Σ zᵢ mᵢ a_yᵢ and My = Σ zᵢ f_xᵢ = −Σ zᵢ mᵢ a_xᵢ (N·m),
/// zero when every plane is 0.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Shaking {
    /// F = −Σ m a_G, N.
    pub force: V2,
    /// M = −Σ (r_G × m a_G + I_G α) about the origin, N·m.
    pub moment: f64,
    /// The couple about the x axis, Mx = Σ zᵢ mᵢ a_yᵢ, N·m.
    pub mx: f64,
    /// The couple about the y axis, My = −Σ zᵢ mᵢ a_xᵢ, N·m.
    pub my: f64,
}

impl Shaking {
    /// Add one link's share: −m a_G to the force and −(r_G × m a_G + I_G α) to the
    /// moment, with m (kg), I_G (kg·m²) from `l` and r_G (m), a_G (m/s²), α (rad/s²) from
    /// `m`; and to the transverse couples, with the link's rigid motion
    /// aᵢ = a_G + α k × (rᵢ − G) − ω² (rᵢ − G), its axial moment
    /// A = Σ zᵢ mᵢ aᵢ = m z̄ a_G + α k × P − ω² P (z̄ = `l.plane` m, P = `l.product` kg·m²
    /// turned by the link's rotation θ − θ_ref), Mx += A_y and My −= A_x. The generated
    /// `shaking` and the run-time one call this once per link with inertia terms.
    #[inline]
    pub fn add(&mut self, l: &LinkGeom, m: &LinkMotion) {
        let f = m.cg_acc * l.mass;
        self.force -= f;
        self.moment -= cross(m.cg, f) + l.inertia * m.alpha;
        let mut a = f * l.plane;
        if l.product != V2::zeros() {
            let (s, c) = m.angle.sin_cos();
            // (cos θ, sin θ) times the conjugate of (cos θ_ref, sin θ_ref)
            let turn = V2::new(
                c * l.dir_ref.x + s * l.dir_ref.y,
                s * l.dir_ref.x - c * l.dir_ref.y,
            );
            let p = rotate(turn, l.product);
            a += perp(p) * m.alpha - p * (m.omega * m.omega);
        }
        self.mx += a.y;
        self.my -= a.x;
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::kernel::measure::within;

    fn link() -> LinkGeom {
        LinkGeom {
            anchor: V2::zeros(),
            dir_ref: V2::new(1.0, 0.0),
            angle_ref: 0.0,
            dcg: V2::new(0.3, 0.1),
            mass: 2.0,
            inertia: 0.05,
            inertia_pivot: 0.05 + 2.0 * 0.1,
            cg_span: V2::zeros(),
            plane: 0.0,
            product: V2::zeros(),
        }
    }

    #[test]
    fn kinetic_energy_and_its_rate() {
        let m = LinkMotion {
            angle: 0.0,
            omega: 3.0,
            alpha: -2.0,
            cg: V2::new(1.0, 2.0),
            cg_vel: V2::new(0.5, -1.5),
            cg_acc: V2::new(4.0, 1.0),
        };
        let l = link();
        // measured worst 0 (be05608); exact; a few ulps
        let close = |a: f64, b: f64| assert!(within((a - b).abs(), 1e-15 * b.abs()), "{a} vs {b}");
        close(kinetic(&l, &m), 0.5 * (2.0 * 2.5 + 0.05 * 9.0));
        close(kinetic_rate(&l, &m), 2.0 * (2.0 - 1.5) - 0.05 * 6.0);
        close(potential(&l, &m, V2::new(0.0, -9.81)), 2.0 * 9.81 * 2.0);
        let mut s = Shaking::default();
        s.add(&l, &m);
        // −m a = (−8, −2); −(r × m a + I α) = −((1·2 − 2·8) − 0.1) = 14.1
        close(s.force.x, -8.0);
        close(s.force.y, -2.0);
        close(s.moment, 14.1);
    }
}
