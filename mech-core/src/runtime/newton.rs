//! The fixed-size Newton bridge: a group with no closed form is solved by Newton and LU
//! on a system whose size N = 3 × links is a const generic, chosen here at run time from
//! the group's size (up to [`super::mechanism::MAX_GROUP_LINKS`] links), and least squares
//! for a redundant group.

use crate::kernel::constraints::{Drive, Level};
use crate::kernel::group::{group_solve, group_velocity_field, GroupSystem};
use crate::kernel::kinetostatics::{group_reactions, lambda_reactions, Reaction, Wrench};
use crate::kernel::link_state::LinkState;
use crate::plan::assur::Group;
use crate::MechError;

use super::mechanism::{MAX_GROUP_LINKS, MAX_REDUNDANT_ROWS};

/// A Newton group's solvers at its size N = 3 × links (const generic, dispatched here).
struct Newton<const N: usize>;

impl<const N: usize> Newton<N> {
    fn solve(
        &self,
        g: &Group,
        joints: &[crate::kernel::constraints::JointGeom],
        s: &mut [LinkState],
        drive: Drive,
        scale: f64,
        upto: Level,
    ) -> Result<(), MechError> {
        group_solve::<N>(&g.bodies, &g.cons, joints, s, drive, scale, upto).map(|_| ())
    }
    #[allow(clippy::too_many_arguments)]
    fn reactions(
        &self,
        g: &Group,
        joints: &[crate::kernel::constraints::JointGeom],
        s: &[LinkState],
        f: &mut [Wrench],
        scale: f64,
        r: &mut [Reaction],
        d: &mut [f64],
    ) -> Result<(), MechError> {
        let lam = group_reactions::<N>(None, &g.bodies, &g.cons, joints, s, f, scale)?;
        lambda_reactions(&g.cons, joints, s, lam.as_slice(), r, d);
        Ok(())
    }
    fn field(
        &self,
        g: &Group,
        joints: &[crate::kernel::constraints::JointGeom],
        s: &mut [LinkState],
        drive: Drive,
        scale: f64,
    ) -> Result<(), MechError> {
        group_velocity_field::<N, GroupSystem<N>>(None, &g.bodies, &g.cons, joints, s, drive, scale)
    }
}

/// Call `f` with the fixed-size solver of group `g`'s size: N = 3 × links unknowns, and M
/// equations for a redundant group (least squares).
pub(super) fn system<T>(
    g: &Group,
    f: impl FnOnce(&dyn NewtonAny) -> Result<T, MechError>,
) -> Result<T, MechError> {
    macro_rules! dispatch {
        ($($links:literal => $n:literal [$($m:literal)*]),*) => {
            match (g.bodies.len(), g.rows()) {
                $(
                    ($links, $n) => f(&Newton::<$n>),
                    $(($links, $m) => f(&LeastSquares::<$n, $m>),)*
                )*
                (l, m) => Err(MechError::InvalidInput(format!(
                    "a group of {l} links and {m} equations is beyond the run-time interpreter ({MAX_GROUP_LINKS} links, {MAX_REDUNDANT_ROWS} redundant equations)"
                ))),
            }
        };
    }
    dispatch!(1 => 3 [4 5 6], 2 => 6 [7 8 9], 3 => 9 [10 11 12], 4 => 12 [13 14 15], 5 => 15 [16 17 18], 6 => 18 [19 20 21])
}

/// A redundant group's solvers (least squares over its M ≥ N equations).
struct LeastSquares<const N: usize, const M: usize>;

impl<const N: usize, const M: usize> NewtonAny for LeastSquares<N, M> {
    fn solve(
        &self,
        g: &Group,
        joints: &[crate::kernel::constraints::JointGeom],
        s: &mut [LinkState],
        drive: Drive,
        scale: f64,
        upto: Level,
    ) -> Result<(), MechError> {
        crate::kernel::group::group_solve_ls::<N, M>(
            &g.bodies, &g.cons, joints, s, drive, scale, upto,
        )
        .map(|_| ())
    }
    fn reactions(
        &self,
        _: &Group,
        _: &[crate::kernel::constraints::JointGeom],
        _: &[LinkState],
        _: &mut [Wrench],
        _: f64,
        _: &mut [Reaction],
        _: &mut [f64],
    ) -> Result<(), MechError> {
        Err(MechError::Redundant(
            "a redundant group's reactions are statically indeterminate".into(),
        ))
    }
    fn field(
        &self,
        g: &Group,
        joints: &[crate::kernel::constraints::JointGeom],
        s: &mut [LinkState],
        drive: Drive,
        scale: f64,
    ) -> Result<(), MechError> {
        group_velocity_field::<N, crate::kernel::group::LsSystem<N, M>>(
            None, &g.bodies, &g.cons, joints, s, drive, scale,
        )
    }
}

/// The size-erased interface of [`Newton`].
pub(super) trait NewtonAny {
    fn solve(
        &self,
        g: &Group,
        joints: &[crate::kernel::constraints::JointGeom],
        s: &mut [LinkState],
        drive: Drive,
        scale: f64,
        upto: Level,
    ) -> Result<(), MechError>;
    #[allow(clippy::too_many_arguments)]
    fn reactions(
        &self,
        g: &Group,
        joints: &[crate::kernel::constraints::JointGeom],
        s: &[LinkState],
        f: &mut [Wrench],
        scale: f64,
        r: &mut [Reaction],
        d: &mut [f64],
    ) -> Result<(), MechError>;
    fn field(
        &self,
        g: &Group,
        joints: &[crate::kernel::constraints::JointGeom],
        s: &mut [LinkState],
        drive: Drive,
        scale: f64,
    ) -> Result<(), MechError>;
}

impl<const N: usize> NewtonAny for Newton<N> {
    fn solve(
        &self,
        g: &Group,
        joints: &[crate::kernel::constraints::JointGeom],
        s: &mut [LinkState],
        drive: Drive,
        scale: f64,
        upto: Level,
    ) -> Result<(), MechError> {
        Newton::<N>::solve(self, g, joints, s, drive, scale, upto)
    }
    fn reactions(
        &self,
        g: &Group,
        joints: &[crate::kernel::constraints::JointGeom],
        s: &[LinkState],
        f: &mut [Wrench],
        scale: f64,
        r: &mut [Reaction],
        d: &mut [f64],
    ) -> Result<(), MechError> {
        Newton::<N>::reactions(self, g, joints, s, f, scale, r, d)
    }
    fn field(
        &self,
        g: &Group,
        joints: &[crate::kernel::constraints::JointGeom],
        s: &mut [LinkState],
        drive: Drive,
        scale: f64,
    ) -> Result<(), MechError> {
        Newton::<N>::field(self, g, joints, s, drive, scale)
    }
}
