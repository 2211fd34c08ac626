//! [`Solver`]: a spatial mechanism's solvers on a chosen [`Frame`], writing into the
//! caller's buffers. On [`Fixed`](super::frame::Fixed) nothing is allocated: the generated
//! struct of a `space` declaration calls these with its N and 6(N − 1) as constants. The
//! run-time [`SpatialMechanism`] calls the same functions on the heap frame.

use super::frame::Frame;
use super::kinematics::{BodyMotion, Layout};
use super::kinetostatics::{reactions_into, ForcesOut};
use super::mechanism::SpatialMechanism;
use crate::kernel::energy::Shaking;
use crate::solvers::friction::JointFriction;
use crate::solvers::zhukovski::Reduced;
use crate::MechError;
use nalgebra::{Vector2, Vector3};

type V3 = Vector3<f64>;

/// A spatial mechanism's solvers on the frame `F` ([`SpatialMechanism::solver`]). Loads are
/// given as one 3-vector per declared load, in the order written (N, or N·m for a torque).
#[derive(Clone, Copy, Debug)]
pub struct Solver<'a, F: Frame> {
    layout: &'a Layout,
    frame: F,
}

impl SpatialMechanism {
    /// The solvers on `frame`: `InvalidInput` when the frame's sizes are not this
    /// mechanism's (a [`Fixed<N, R>`](super::frame::Fixed) needs N bodies, R = 6(N − 1)
    /// rows and as many unknowns).
    pub fn solver<F: Frame>(&self, frame: F) -> Result<Solver<'_, F>, MechError> {
        let layout = self.layout();
        frame.fits(layout.o0.len(), layout.row_count())?;
        Ok(Solver { layout, frame })
    }
}

impl<F: Frame> Solver<'_, F> {
    /// Positions at q (one value per input): every body's motion, rates zero.
    pub fn pose(&self, q: &[f64]) -> Result<F::Motions, MechError> {
        let mut out = self.frame.motions();
        self.layout.pose_into(self.frame, q, out.as_mut())?;
        Ok(out)
    }

    /// Positions, velocities and accelerations at (q, q̇, q̈): every body's motion.
    pub fn kinematics(&self, q: &[f64], qd: &[f64], qdd: &[f64]) -> Result<F::Motions, MechError> {
        let mut out = self.frame.motions();
        self.layout
            .kinematics_into(self.frame, q, qd, qdd, out.as_mut())?;
        Ok(out)
    }

    /// Every joint's reaction (by its first link on its second; N and N·m about the joint's
    /// point), every motor action and each idle spin's moment at the motion (`bodies` at
    /// inputs `q`) into `out`, Newton–Euler with the full inertia tensor; `Redundant` for a
    /// mechanism accepted with `#[allow(redundant)]`.
    pub fn kinetostatics(
        &self,
        bodies: &[BodyMotion],
        q: &[f64],
        loads: &[V3],
        out: ForcesOut<'_>,
    ) -> Result<(), MechError> {
        if self.layout.model.allow_redundant {
            return Err(super::mechanism::indeterminate(self.layout));
        }
        reactions_into(self.layout, self.frame, bodies, q, loads, None, out)
    }

    /// [`Solver::kinetostatics`] with Coulomb friction in the joints (`friction[j]` for
    /// joint j in the order written: μ and the pin or ball radius), Newton–Euler iterated to
    /// a fixed point; `SelfLocking` when no finite motor action moves the mechanism. The
    /// laws of each joint kind are in `docs/spatial.md` ("Friction").
    pub fn kinetostatics_with_friction(
        &self,
        bodies: &[BodyMotion],
        q: &[f64],
        loads: &[V3],
        friction: &[JointFriction],
        out: ForcesOut<'_>,
    ) -> Result<(), MechError> {
        if self.layout.model.allow_redundant {
            return Err(super::mechanism::indeterminate(self.layout));
        }
        reactions_into(
            self.layout,
            self.frame,
            bodies,
            q,
            loads,
            Some(friction),
            out,
        )
    }

    /// The motor actions by virtual power into `out` (N·m or N per input), no reaction.
    pub fn driver_actions(
        &self,
        bodies: &[BodyMotion],
        q: &[f64],
        loads: &[V3],
        out: &mut [f64],
    ) -> Result<(), MechError> {
        super::virtual_power::driver_actions_into(self.layout, self.frame, bodies, q, loads, out)
    }

    /// Zhukovski's I*(q) (kg·m² or kg) and dI*/dq; one input only.
    pub fn reduced(&self, q: f64) -> Result<Reduced, MechError> {
        super::zhukovski::reduced(self.layout, self.frame, q)
    }

    /// Zhukovski's M*(q) (N·m or N), loads and gravity; one input only.
    pub fn reduced_moment(&self, q: f64, loads: &[V3]) -> Result<f64, MechError> {
        super::zhukovski::reduced_moment(self.layout, self.frame, q, loads)
    }

    /// q̈ = (driver + M* − ½ dI*/dq q̇²) / I* (rad/s² or m/s²); one input only.
    pub fn acceleration(
        &self,
        q: f64,
        qd: f64,
        driver: f64,
        loads: &[V3],
    ) -> Result<f64, MechError> {
        super::zhukovski::acceleration(self.layout, self.frame, q, qd, driver, loads)
    }

    /// ½ m |v_G|² + ½ ωᵀ I ω of each body into `out` (J), I turned to the pose.
    pub fn kinetic_energies(&self, bodies: &[BodyMotion], out: &mut [f64]) {
        kinetic_energies(self.layout, bodies, out)
    }

    /// −Σ m g·r_G (J).
    pub fn potential_energy(&self, bodies: &[BodyMotion]) -> f64 {
        potential_energy(self.layout, bodies)
    }

    /// The shaking force and moment: the planar `Shaking` filled from the spatial sums
    /// (`mech::dynamics::Machine::shaking` of the run-time mechanism).
    pub fn shaking(&self, bodies: &[BodyMotion]) -> Shaking {
        shaking(self.layout, bodies)
    }
}

/// ½ m |v_G|² + ½ ωᵀ I ω per body (J), I turned to the pose.
pub(crate) fn kinetic_energies(layout: &Layout, bodies: &[BodyMotion], out: &mut [f64]) {
    for ((o, b), bm) in out.iter_mut().zip(&layout.model.bodies).zip(bodies) {
        let w = bm.state.w;
        *o = 0.5 * (b.mass * bm.state.v.norm_squared() + w.dot(&(bm.inertia(&b.inertia) * w)));
    }
}

/// −Σ m g·r_G (J).
pub(crate) fn potential_energy(layout: &Layout, bodies: &[BodyMotion]) -> f64 {
    let Some(g) = layout.model.gravity else {
        return 0.0;
    };
    layout
        .model
        .bodies
        .iter()
        .zip(bodies)
        .skip(1)
        .map(|(b, bm)| -b.mass * g.dot(&bm.state.o))
        .sum()
}

/// The planar [`Shaking`] filled from the spatial sums: F = −Σ m a_G (its x and y; the z
/// component has no place in it), M = −Σ (r_G × m a_G + I α + ω × I ω) about the origin:
/// `moment` its z component, `mx` and `my` its x and y.
pub(crate) fn shaking(layout: &Layout, bodies: &[BodyMotion]) -> Shaking {
    let (mut f, mut mo) = (V3::zeros(), V3::zeros());
    for (b, bm) in layout.model.bodies.iter().zip(bodies).skip(1) {
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
