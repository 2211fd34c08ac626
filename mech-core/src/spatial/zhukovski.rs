//! Zhukovski's reduction of a one-DOF spatial mechanism (I*, dI*/dq, M*).
//!
//! From the motion with q̇ = 1, q̈ = 0 (velocity coefficients v'_G, ω' and their
//! derivatives d v'_G/dq = a_G, dω'/dq = α of that motion), with I = R I_drawing Rᵀ:
//! - I* = Σ (m |v'_G|² + ω'ᵀ I ω')                      (kg·m², or kg for a sliding input)
//! - dI*/dq = 2 Σ (m v'_G·a_G + ω'·I α)                 (the tensor's turning adds
//!   ω'ᵀ(ω'× I − I ω'×)ω' = 0)
//! - M* = Σ Q·x', the applied wrenches' virtual power per unit q̇, gravity included (at the
//!   pose alone: Q does not depend on the rates);
//! - the equation of motion I* q̈ + ½ dI*/dq q̇² = driver + M*
//!   (`crate::solvers::zhukovski::acceleration`).

use super::frame::Frame;
use super::kinematics::{BodyMotion, Layout};
use super::kinetostatics::wrenches;
use super::virtual_power::{coefficients, dot};
use crate::solvers::zhukovski::Reduced;
use crate::MechError;
use nalgebra::Vector3;

fn one_dof(layout: &Layout) -> Result<(), MechError> {
    match layout.model.inputs.len() {
        1 => Ok(()),
        g => Err(MechError::InvalidInput(format!(
            "Zhukovski's reduction is for one input, this mechanism has {g}"
        ))),
    }
}

/// I*(q) and dI*/dq (module docs).
pub(crate) fn reduced<F: Frame>(layout: &Layout, f: F, q: f64) -> Result<Reduced, MechError> {
    let mut m = f.motions();
    reduce(layout, f, q, m.as_mut())
}

/// I*(q) and dI*/dq from the motion with q̇ = 1, q̈ = 0, written into `m`.
fn reduce<F: Frame>(
    layout: &Layout,
    f: F,
    q: f64,
    m: &mut [BodyMotion],
) -> Result<Reduced, MechError> {
    one_dof(layout)?;
    layout.kinematics_into(f, &[q], &[1.0], &[0.0], m)?;
    let mut out = Reduced::default();
    for (body, bm) in layout.model.bodies.iter().zip(m.iter()).skip(1) {
        let i = bm.inertia(&body.inertia);
        let (v, w) = (bm.state.v, bm.state.w);
        out.inertia += body.mass * v.norm_squared() + w.dot(&(i * w));
        out.inertia_derivative += 2.0 * (body.mass * v.dot(&bm.a) + w.dot(&(i * bm.alpha)));
    }
    crate::kernel::finite::finite_few("I* and dI*/dq", &[out.inertia, out.inertia_derivative])?;
    Ok(out)
}

/// M*(q) (N·m, or N for a sliding input): the applied wrenches' power per unit q̇, at the
/// pose alone (positions, one factorisation, one solve).
pub(crate) fn reduced_moment<F: Frame>(
    layout: &Layout,
    f: F,
    q: f64,
    loads: &[Vector3<f64>],
) -> Result<f64, MechError> {
    one_dof(layout)?;
    let mut m = f.motions();
    layout.pose_into(f, &[q], m.as_mut())?;
    let w = wrenches(layout, f, m.as_ref(), loads, false)?;
    let mut out = f64::NAN;
    coefficients(layout, f, m.as_ref(), &[q], |_, x| out = dot(w.as_ref(), x))?;
    crate::kernel::finite::finite_few("M*", &[out])?;
    Ok(out)
}

/// q̈ = (driver + M* − ½ dI*/dq q̇²) / I*: one kinematics at q̇ = 1 gives I*, dI*/dq and
/// the velocity coefficients M* is the power of.
pub(crate) fn acceleration<F: Frame>(
    layout: &Layout,
    f: F,
    q: f64,
    qd: f64,
    driver: f64,
    loads: &[Vector3<f64>],
) -> Result<f64, MechError> {
    crate::error::check_finite("q, q̇, driver", &[q, qd, driver])?;
    let mut m = f.motions();
    let r = reduce(layout, f, q, m.as_mut())?;
    let w = wrenches(layout, f, m.as_ref(), loads, false)?;
    let moment: f64 = m
        .as_ref()
        .iter()
        .skip(1)
        .zip(w.as_ref().chunks_exact(6))
        .map(|(bm, w)| dot(w, bm.state.v.as_slice()) + dot(&w[3..], bm.state.w.as_slice()))
        .sum();
    crate::kernel::finite::finite_few("M*", &[moment])?;
    crate::solvers::zhukovski::acceleration(r, moment, qd, driver)
}
