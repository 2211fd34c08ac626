//! The motor actions of a spatial mechanism by virtual power, without reactions.
//!
//! For input k, the velocity coefficients x'_k (every body's (v, ω) per unit q̇_k, the
//! others held) solve J x'_k = e_k (1 on input k's driver row). Virtual power over all the
//! bodies, the constraints doing none: τ_k = −Σ_bodies (Q − inertia wrench)·x'_k, with the
//! wrenches of `kinetostatics::wrenches` (m a_G and I α + ω × (I ω) against each body's
//! applied force and moment at its reference point).

use super::kinematics::{solve, Layout, SpatialMotion};
use super::kinetostatics::{wrenches, SpatialLoads};
use crate::MechError;
use nalgebra::DVector;

/// The velocity coefficients at the motion's pose: one vector of 6(N − 1) per input.
pub(crate) fn coefficients(
    layout: &Layout,
    m: &SpatialMotion,
) -> Result<Vec<DVector<f64>>, MechError> {
    let s: Vec<_> = m.bodies.iter().map(|b| b.state).collect();
    let (rows, owners) = layout.rows(&s, &m.q);
    let j = layout.jacobian(&rows, &owners);
    let first = rows.len() - m.q.len() - layout.spins.len();
    (0..m.q.len())
        .map(|k| {
            let mut e = DVector::zeros(rows.len());
            e[first + k] = 1.0;
            solve(j.clone(), e)
        })
        .collect()
}

/// τ_k = −(Q − inertia wrenches)·x'_k for every input k (N·m or N, by the input joint's
/// first link on its second).
pub(crate) fn driver_actions(
    layout: &Layout,
    m: &SpatialMotion,
    loads: &SpatialLoads,
) -> Result<Vec<f64>, MechError> {
    let w = wrenches(layout, m, loads, true)?;
    let out: Vec<f64> = coefficients(layout, m)?.iter().map(|x| -w.dot(x)).collect();
    crate::kernel::finite::finite_few("the motor actions", &out)?;
    Ok(out)
}
