//! Zhukovski's reduction of a one-DOF spatial mechanism (I*, dI*/dq, M*).
//!
//! From the motion with q̇ = 1, q̈ = 0 (velocity coefficients v'_G, ω' and their
//! derivatives d v'_G/dq = a_G, dω'/dq = α of that motion), with I = R I_drawing Rᵀ:
//! - I* = Σ (m |v'_G|² + ω'ᵀ I ω')                      (kg·m², or kg for a sliding input)
//! - dI*/dq = 2 Σ (m v'_G·a_G + ω'·I α)                 (the tensor's turning adds
//!   ω'ᵀ(ω'× I − I ω'×)ω' = 0)
//! - M* = Σ Q·x', the applied wrenches' virtual power per unit q̇, gravity included;
//! - the equation of motion I* q̈ + ½ dI*/dq q̇² = driver + M*
//!   (`crate::solvers::zhukovski::acceleration`).

use super::kinematics::{kinematics, Layout};
use super::kinetostatics::{wrenches, SpatialLoads};
use super::virtual_power::coefficients;
use crate::solvers::zhukovski::Reduced;
use crate::MechError;
use std::sync::Arc;

fn one_dof(layout: &Layout) -> Result<(), MechError> {
    match layout.model.inputs.len() {
        1 => Ok(()),
        g => Err(MechError::InvalidInput(format!(
            "Zhukovski's reduction is for one input, this mechanism has {g}"
        ))),
    }
}

/// I*(q) and dI*/dq (module docs).
pub(crate) fn reduced(layout: &Arc<Layout>, q: f64) -> Result<Reduced, MechError> {
    one_dof(layout)?;
    let m = kinematics(layout, &[q], &[1.0], &[0.0])?;
    let mut out = Reduced::default();
    for (b, body) in layout.model.bodies.iter().enumerate().skip(1) {
        let bm = &m.bodies[b];
        let i = bm.inertia(&body.inertia);
        let (v, w) = (bm.state.v, bm.state.w);
        out.inertia += body.mass * v.norm_squared() + w.dot(&(i * w));
        out.inertia_derivative += 2.0 * (body.mass * v.dot(&bm.a) + w.dot(&(i * bm.alpha)));
    }
    crate::kernel::finite::finite_few("I* and dI*/dq", &[out.inertia, out.inertia_derivative])?;
    Ok(out)
}

/// M*(q) (N·m, or N for a sliding input): the applied wrenches' power per unit q̇.
pub(crate) fn reduced_moment(
    layout: &Arc<Layout>,
    q: f64,
    loads: &SpatialLoads,
) -> Result<f64, MechError> {
    one_dof(layout)?;
    let m = kinematics(layout, &[q], &[0.0], &[0.0])?;
    let x = coefficients(layout, &m)?;
    let out = wrenches(layout, &m, loads, false)?.dot(&x[0]);
    crate::kernel::finite::finite_few("M*", &[out])?;
    Ok(out)
}

/// q̈ = (driver + M* − ½ dI*/dq q̇²) / I*.
pub(crate) fn acceleration(
    layout: &Arc<Layout>,
    q: f64,
    qd: f64,
    driver: f64,
    loads: &SpatialLoads,
) -> Result<f64, MechError> {
    crate::error::check_finite("q, q̇, driver", &[q, qd, driver])?;
    let r = reduced(layout, q)?;
    let moment = reduced_moment(layout, q, loads)?;
    crate::solvers::zhukovski::acceleration(r, moment, qd, driver)
}
