//! `Machine` and `OneDof` for `SpatialMechanism`, so the generic dynamics run on it.

use super::kinematics::SpatialMotion;
use super::kinetostatics::SpatialLoads;
use super::mechanism::SpatialMechanism;
use super::solver;
use crate::kernel::energy::Shaking;
use crate::solvers::traits::{Machine, OneDof};
use crate::solvers::zhukovski::Reduced;
use crate::MechError;

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
        solver::kinetic_energies(self.layout(), &m.bodies, out)
    }
    /// −Σ m g·r_G (J).
    fn potential_energy(&self, m: &SpatialMotion) -> f64 {
        solver::potential_energy(self.layout(), &m.bodies)
    }
    /// The planar [`Shaking`] filled from the spatial sums: F = −Σ m a_G (its x and y;
    /// the z component has no place in it), M = −Σ (r_G × m a_G + I α + ω × I ω) about the
    /// origin: `moment` its z component, `mx` and `my` its x and y.
    fn shaking(&self, m: &SpatialMotion) -> Shaking {
        solver::shaking(self.layout(), &m.bodies)
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
