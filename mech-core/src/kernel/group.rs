//! Groups without a closed form (triads, dyads with slots, redundant groups): positions
//! by Newton–Raphson on the group's equations, velocities and accelerations from its
//! fixed-size scaled Jacobian (J ẋ = −Φ̇, J ẍ = −Φ̈ with the group's rates zero), and the
//! factored system kept for the reactions (Jᵀ λ = −f, [`crate::kernel::kinetostatics`]).

use crate::kernel::constraints::{assemble, group_rhs, Con, Drive, JointGeom, Level};
use crate::kernel::linalg::{Lu, SINGULAR_CONDITION};
use crate::kernel::link_state::{rotate, LinkState, V2};
use crate::MechError;
use nalgebra::{SMatrix, SVector};

/// The square system of one Assur group with `N` = 3 × (its links) unknowns.
///
/// Columns are (x, y, φ·L) of each link of the group in order, rows the scalar
/// equations of its constraints in order, angle rows multiplied by L (the drawing's
/// length scale): all entries are then dimensionless and of order one, so the pivot
/// ratio of the LU factorisation is a meaningful condition estimate.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GroupSystem<const N: usize> {
    lu: Lu<N>,
    row_scale: SVector<f64, N>,
    scale: f64,
}

impl<const N: usize> GroupSystem<N> {
    /// Assemble and factor the Jacobian of the group's constraints with respect to its
    /// links' coordinates at the current positions. `scale` is the drawing's length (m).
    #[inline(always)]
    pub fn new(
        bodies: &[usize],
        cons: &[Con],
        joints: &[JointGeom],
        s: &[LinkState],
        scale: f64,
    ) -> Result<Self, MechError> {
        let (j, row_scale) = assemble::<N, N>(bodies, cons, joints, s, scale);
        let lu = Lu::new(j);
        let cond = lu.condition();
        if !(cond < SINGULAR_CONDITION) {
            return Err(MechError::Singular { condition: cond });
        }
        Ok(GroupSystem {
            lu,
            row_scale,
            scale,
        })
    }

    /// Solve J x = b for the links' coordinates rates (x, y, φ per link).
    #[inline(always)]
    pub fn solve(&self, b: &SVector<f64, N>) -> SVector<f64, N> {
        let rhs = b.component_mul(&self.row_scale);
        let mut x = self.lu.solve(&rhs);
        for i in 0..N / 3 {
            x[3 * i + 2] /= self.scale;
        }
        x
    }

    /// Solve Jᵀ λ = f for the multipliers (f = generalised forces (Fx, Fy, M) per link).
    #[inline(always)]
    pub fn solve_transpose(&self, f: &SVector<f64, N>) -> SVector<f64, N> {
        let mut rhs = *f;
        for i in 0..N / 3 {
            rhs[3 * i + 2] /= self.scale;
        }
        self.lu.solve_transpose(&rhs).component_mul(&self.row_scale)
    }
}

/// The over-determined system of a redundant group (M > N rows, accepted with
/// `#[allow(redundant)]`): the equations are consistent, so the least-squares solution of
/// the normal equations JᵀJ x = Jᵀb is the exact one. Its condition is κ(J)², which is
/// what the threshold is applied to.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LsSystem<const N: usize, const M: usize> {
    j: SMatrix<f64, M, N>,
    lu: Lu<N>,
    row_scale: SVector<f64, M>,
    scale: f64,
}

impl<const N: usize, const M: usize> LsSystem<N, M> {
    /// Assemble J and factor JᵀJ at the current positions.
    #[inline(always)]
    pub fn new(
        bodies: &[usize],
        cons: &[Con],
        joints: &[JointGeom],
        s: &[LinkState],
        scale: f64,
    ) -> Result<Self, MechError> {
        let (j, row_scale) = assemble::<M, N>(bodies, cons, joints, s, scale);
        let lu = Lu::new(j.transpose() * j);
        let cond = lu.condition();
        if !(cond < SINGULAR_CONDITION * SINGULAR_CONDITION) {
            return Err(MechError::Singular {
                condition: cond.sqrt(),
            });
        }
        Ok(LsSystem {
            j,
            lu,
            row_scale,
            scale,
        })
    }

    /// Solve J x = b (consistent, M ≥ N) through the normal equations.
    #[inline(always)]
    pub fn solve(&self, b: &SVector<f64, M>) -> SVector<f64, N> {
        let rhs = self.j.transpose() * b.component_mul(&self.row_scale);
        let mut x = self.lu.solve(&rhs);
        for i in 0..N / 3 {
            x[3 * i + 2] /= self.scale;
        }
        x
    }
}

/// Write the solved rates `x` (x, y, φ per link) of a group into its links' velocities
/// (`acc` false) or accelerations (`acc` true).
#[inline(always)]
fn store_rates<const N: usize>(
    bodies: &[usize],
    s: &mut [LinkState],
    x: &SVector<f64, N>,
    acc: bool,
) {
    for (k, &b) in bodies.iter().enumerate() {
        if acc {
            s[b].acc = V2::new(x[3 * k], x[3 * k + 1]);
            s[b].alpha = x[3 * k + 2];
        } else {
            s[b].vel = V2::new(x[3 * k], x[3 * k + 1]);
            s[b].omega = x[3 * k + 2];
        }
    }
}

/// Move a group's links by the coordinate step `dx`; the largest component (m, φ×L).
#[inline(always)]
fn apply_step<const N: usize>(
    bodies: &[usize],
    s: &mut [LinkState],
    dx: &SVector<f64, N>,
    scale: f64,
) -> f64 {
    let mut step: f64 = 0.0;
    for (k, &b) in bodies.iter().enumerate() {
        s[b].pos += V2::new(dx[3 * k], dx[3 * k + 1]);
        let (sn, cs) = dx[3 * k + 2].sin_cos();
        s[b].rot = rotate(s[b].rot, V2::new(cs, sn)).normalize();
        step = step
            .max(dx[3 * k].abs())
            .max(dx[3 * k + 1].abs())
            .max((dx[3 * k + 2] * scale).abs());
    }
    step
}

/// Rates of a group's links from those of the links already solved, at `level`:
/// velocities J ẋ = −Φ̇(known) or accelerations J ẍ = −Φ̈(group's accelerations zero).
/// The group's rates at that level must be zero in `s` on entry.
#[inline(always)]
pub fn group_rates<const N: usize>(
    sys: &GroupSystem<N>,
    bodies: &[usize],
    cons: &[Con],
    joints: &[JointGeom],
    s: &mut [LinkState],
    drive: Drive,
    level: Level,
) {
    store_rates(
        bodies,
        s,
        &sys.rates(cons, joints, s, drive, level),
        level == Level::Acceleration,
    );
}

/// A group's factored linear system: the square [`GroupSystem`] or the least-squares
/// [`LsSystem`] of a redundant group.
pub trait RateSystem<const N: usize>: Copy {
    /// Assemble and factor at the current positions.
    fn build(
        bodies: &[usize],
        cons: &[Con],
        joints: &[JointGeom],
        s: &[LinkState],
        scale: f64,
    ) -> Result<Self, MechError>;
    /// The links' rates (x, y, φ per link) at `level`, J x = −Φ̇ or −Φ̈ of the known rates.
    fn rates(
        &self,
        cons: &[Con],
        joints: &[JointGeom],
        s: &[LinkState],
        drive: Drive,
        level: Level,
    ) -> SVector<f64, N>;
}

impl<const N: usize> RateSystem<N> for GroupSystem<N> {
    #[inline(always)]
    fn build(
        bodies: &[usize],
        cons: &[Con],
        joints: &[JointGeom],
        s: &[LinkState],
        scale: f64,
    ) -> Result<Self, MechError> {
        GroupSystem::new(bodies, cons, joints, s, scale)
    }
    #[inline(always)]
    fn rates(
        &self,
        cons: &[Con],
        joints: &[JointGeom],
        s: &[LinkState],
        drive: Drive,
        level: Level,
    ) -> SVector<f64, N> {
        self.solve(&group_rhs::<N>(cons, joints, s, drive, level))
    }
}

impl<const N: usize, const M: usize> RateSystem<N> for LsSystem<N, M> {
    #[inline(always)]
    fn build(
        bodies: &[usize],
        cons: &[Con],
        joints: &[JointGeom],
        s: &[LinkState],
        scale: f64,
    ) -> Result<Self, MechError> {
        LsSystem::new(bodies, cons, joints, s, scale)
    }
    #[inline(always)]
    fn rates(
        &self,
        cons: &[Con],
        joints: &[JointGeom],
        s: &[LinkState],
        drive: Drive,
        level: Level,
    ) -> SVector<f64, N> {
        self.solve(&group_rhs::<M>(cons, joints, s, drive, level))
    }
}

/// The velocity field of a group only (positions already in `s`, its velocities zero),
/// with the group's factored system `sys` when the kinematics kept it (else it is built).
#[cfg_attr(debug_assertions, inline)]
#[cfg_attr(not(debug_assertions), inline(always))]
pub fn group_velocity_field<const N: usize, S: RateSystem<N>>(
    sys: Option<&S>,
    bodies: &[usize],
    cons: &[Con],
    joints: &[JointGeom],
    s: &mut [LinkState],
    drive: Drive,
    scale: f64,
) -> Result<(), MechError> {
    let sys = match sys {
        Some(sys) => *sys,
        None => S::build(bodies, cons, joints, s, scale)?,
    };
    store_rates(
        bodies,
        s,
        &sys.rates(cons, joints, s, drive, Level::Velocity),
        false,
    );
    Ok(())
}

/// Positions of a group with no closed form: Newton–Raphson on the group's equations,
/// started from the links' current states (the drawing's pose unless the caller passes
/// a better guess). Converges to |Δ| < 1e-14 L or fails with `NoAssembly`.
pub fn group_newton<const N: usize>(
    bodies: &[usize],
    cons: &[Con],
    joints: &[JointGeom],
    s: &mut [LinkState],
    drive: Drive,
    scale: f64,
) -> Result<(), MechError> {
    newton(bodies, s, scale, |s| {
        let sys = GroupSystem::<N>::new(bodies, cons, joints, s, scale)?;
        Ok(sys.solve(&group_rhs::<N>(cons, joints, s, drive, Level::Position)))
    })
}

/// The Newton iteration of a group: apply the steps `step(s)` until the largest is below
/// 1e-14 L (at most 50); `NoAssembly` when a system is singular, a step is not finite,
/// or it does not converge.
#[inline]
fn newton<const N: usize>(
    bodies: &[usize],
    s: &mut [LinkState],
    scale: f64,
    mut step: impl FnMut(&[LinkState]) -> Result<SVector<f64, N>, MechError>,
) -> Result<(), MechError> {
    for _ in 0..50 {
        let dx = step(s).map_err(|_| MechError::NoAssembly)?;
        let size = apply_step(bodies, s, &dx, scale);
        if !size.is_finite() {
            return Err(MechError::NoAssembly);
        }
        if size < 1e-14 * scale {
            return Ok(());
        }
    }
    Err(MechError::NoAssembly)
}

/// Solve a group with no closed form up to `upto`: positions by Newton from the links'
/// current states (the drawing on entry), then, when asked, velocities and accelerations
/// from its linear system. Returns the factored system when it was built (velocity level
/// and beyond), so that kinetostatics can reuse it.
#[inline]
pub fn group_solve<const N: usize>(
    bodies: &[usize],
    cons: &[Con],
    joints: &[JointGeom],
    s: &mut [LinkState],
    drive: Drive,
    scale: f64,
    upto: Level,
) -> Result<Option<GroupSystem<N>>, MechError> {
    group_newton::<N>(bodies, cons, joints, s, drive, scale)?;
    if matches!(upto, Level::Velocity | Level::Acceleration) {
        let sys = GroupSystem::<N>::new(bodies, cons, joints, s, scale)?;
        group_rates(&sys, bodies, cons, joints, s, drive, Level::Velocity);
        if upto == Level::Acceleration {
            group_rates(&sys, bodies, cons, joints, s, drive, Level::Acceleration);
        }
        return Ok(Some(sys));
    }
    Ok(None)
}

/// A redundant group solved up to `upto`: positions by Gauss–Newton from the current
/// states (the drawing), then velocities and accelerations, all through [`LsSystem`].
#[inline]
#[allow(clippy::too_many_arguments)]
pub fn group_solve_ls<const N: usize, const M: usize>(
    bodies: &[usize],
    cons: &[Con],
    joints: &[JointGeom],
    s: &mut [LinkState],
    drive: Drive,
    scale: f64,
    upto: Level,
) -> Result<Option<LsSystem<N, M>>, MechError> {
    newton(bodies, s, scale, |s| {
        let sys = LsSystem::<N, M>::new(bodies, cons, joints, s, scale)?;
        Ok(sys.solve(&group_rhs::<M>(cons, joints, s, drive, Level::Position)))
    })?;
    // Consistent equations have a zero residual; a non-zero one means the links solved
    // before took the other branch at a change point (see the generated `__solve`).
    let r = group_rhs::<M>(cons, joints, s, drive, Level::Position);
    if !(r.amax() < 1e-9 * scale) {
        return Err(MechError::NoAssembly);
    }
    if !matches!(upto, Level::Velocity | Level::Acceleration) {
        return Ok(None);
    }
    let sys = LsSystem::<N, M>::new(bodies, cons, joints, s, scale)?;
    store_rates(
        bodies,
        s,
        &sys.rates(cons, joints, s, drive, Level::Velocity),
        false,
    );
    if upto == Level::Acceleration {
        store_rates(
            bodies,
            s,
            &sys.rates(cons, joints, s, drive, Level::Acceleration),
            true,
        );
    }
    Ok(Some(sys))
}
