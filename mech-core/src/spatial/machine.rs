//! `Machine` and `OneDof` for `SpatialMechanism`, so the generic dynamics run on it.

use super::kinematics::SpatialMotion;
use super::kinetostatics::SpatialLoads;
use super::mechanism::SpatialMechanism;
use crate::kernel::energy::Shaking;
use crate::solvers::traits::{Machine, OneDof};
use crate::solvers::zhukovski::Reduced;
use crate::MechError;
use nalgebra::Vector2;

impl Machine for SpatialMechanism {
    type Loads = SpatialLoads;
    type Motion = SpatialMotion;
    fn dof(&self) -> usize {
        SpatialMechanism::dof(self)
    }
    fn links(&self) -> usize {
        self.model().bodies.len()
    }
    fn motion(&self, q: &[f64], qd: &[f64], qdd: &[f64]) -> Result<SpatialMotion, MechError> {
        self.kinematics(q, qd, qdd)
    }
    fn driver_actions(
        &self,
        m: &SpatialMotion,
        loads: &SpatialLoads,
        out: &mut [f64],
    ) -> Result<(), MechError> {
        let d = self.driver_action(m, loads)?;
        if out.len() != d.len() {
            return Err(MechError::InvalidInput(format!(
                "out has {} values for {} inputs",
                out.len(),
                d.len()
            )));
        }
        out.copy_from_slice(&d);
        Ok(())
    }
    /// ½ m |v_G|² + ½ ωᵀ I ω per link, I turned to the pose (J).
    fn link_kinetic_energies(&self, m: &SpatialMotion, out: &mut [f64]) {
        for ((o, b), bm) in out.iter_mut().zip(&self.model().bodies).zip(&m.bodies) {
            let w = bm.state.w;
            *o = 0.5 * (b.mass * bm.state.v.norm_squared() + w.dot(&(bm.inertia(&b.inertia) * w)));
        }
    }
    /// −Σ m g·r_G (J).
    fn potential_energy(&self, m: &SpatialMotion) -> f64 {
        let Some(g) = self.model().gravity else {
            return 0.0;
        };
        self.model()
            .bodies
            .iter()
            .zip(&m.bodies)
            .skip(1)
            .map(|(b, bm)| -b.mass * g.dot(&bm.state.o))
            .sum()
    }
    /// The planar [`Shaking`] filled from the spatial sums: F = −Σ m a_G (its x and y;
    /// the z component has no place in it), M = −Σ (r_G × m a_G + I α + ω × I ω) about the
    /// origin: `moment` its z component, `mx` and `my` its x and y.
    fn shaking(&self, m: &SpatialMotion) -> Shaking {
        let (mut f, mut mo) = (nalgebra::Vector3::zeros(), nalgebra::Vector3::zeros());
        for (b, bm) in self.model().bodies.iter().zip(&m.bodies).skip(1) {
            let i = bm.inertia(&b.inertia);
            let w = bm.state.w;
            let fa = bm.a * b.mass;
            f -= fa;
            mo -= bm.state.o.cross(&fa) + i * bm.alpha + w.cross(&(i * w));
        }
        Shaking {
            force: Vector2::new(f.x, f.y),
            moment: mo.z,
            mx: mo.x,
            my: mo.y,
        }
    }
}

impl OneDof for SpatialMechanism {
    fn reduced(&self, q: f64) -> Result<Reduced, MechError> {
        SpatialMechanism::reduced(self, q)
    }
    fn reduced_moment(&self, q: f64, loads: &SpatialLoads) -> Result<f64, MechError> {
        SpatialMechanism::reduced_moment(self, q, loads)
    }
    fn acceleration(
        &self,
        q: f64,
        qd: f64,
        driver: f64,
        loads: &SpatialLoads,
    ) -> Result<f64, MechError> {
        SpatialMechanism::acceleration(self, q, qd, driver, loads)
    }
}
