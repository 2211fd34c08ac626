//! The motor actions of a spatial mechanism by virtual power, without reactions.
//!
//! For input k, the velocity coefficients x'_k (every body's (v, ω) per unit q̇_k, the
//! others held) solve J x'_k = e_k (1 on input k's driver row). Virtual power over all the
//! bodies, the constraints doing none: τ_k = −Σ_bodies (Q − inertia wrench)·x'_k, with the
//! wrenches of `kinetostatics::wrenches` (m a_G and I α + ω × (I ω) against each body's
//! applied force and moment at its reference point).

use super::frame::{Frame, RowBuffer};
use super::kinematics::{BodyMotion, Layout};
use super::kinetostatics::{states, wrenches};
use crate::MechError;
use nalgebra::Vector3;

/// The velocity coefficients x'_k at the pose of `bodies` (inputs `q`), each handed to
/// `each(k, x'_k)` (6(N − 1) values), J factored once.
pub(crate) fn coefficients<F: Frame>(
    layout: &Layout,
    f: F,
    bodies: &[BodyMotion],
    q: &[f64],
    mut each: impl FnMut(usize, &[f64]),
) -> Result<(), MechError> {
    let s = states(layout, f, bodies);
    let mut rows = f.rows();
    layout.rows_into(s.as_ref(), q, 1.0, &mut rows);
    let first = rows.rows().len() - q.len() - layout.spins.len();
    let j = f.factor(&rows)?;
    for k in 0..q.len() {
        let mut e = f.rhs();
        e.as_mut()[first + k] = 1.0;
        each(k, f.solve(&j, &e)?.as_ref());
    }
    Ok(())
}

/// τ_k = −(Q − inertia wrenches)·x'_k for every input k into `out` (N·m or N, by the input
/// joint's first link on its second).
pub(crate) fn driver_actions_into<F: Frame>(
    layout: &Layout,
    f: F,
    bodies: &[BodyMotion],
    q: &[f64],
    loads: &[Vector3<f64>],
    out: &mut [f64],
) -> Result<(), MechError> {
    if out.len() != q.len()
        || q.len() != layout.model.inputs.len()
        || bodies.len() != layout.o0.len()
    {
        return Err(MechError::InvalidInput(format!(
            "`{}` has {} input(s) and {} bodies; given {} values, {} outputs and {} bodies",
            layout.model.name,
            layout.model.inputs.len(),
            layout.o0.len(),
            q.len(),
            out.len(),
            bodies.len()
        )));
    }
    let w = wrenches(layout, f, bodies, loads, true)?;
    coefficients(layout, f, bodies, q, |k, x| out[k] = -dot(w.as_ref(), x))?;
    crate::kernel::finite::finite_few("the motor actions", out)
}

/// a·b.
pub(crate) fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}
