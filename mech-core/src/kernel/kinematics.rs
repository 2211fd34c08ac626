//! Kinematics of one Assur group, the entry points the generated code calls once per
//! group with the topology as constants (`docs/theory.md` §3):
//! - a driven crank or slider: [`solve_driven`],
//! - a closed-form dyad or slot group: [`solve_chain`] (positions by [`crate::kernel::dyad`],
//!   rates in natural coordinates for the RRR, RRP, RPR, PRP and RPP dyads,
//!   [`crate::kernel::natural`], by joint screws for the others, [`crate::kernel::screw`]),
//! - a group with no closed form (triads, dyads with slots, redundant groups):
//!   [`crate::kernel::group::group_solve`] and [`crate::kernel::group::group_solve_ls`] (Newton and LU).
//!
//! The state of a link and its points is in [`crate::kernel::link_state`], the constraint
//! equations in [`crate::kernel::constraints`]; both are re-exported here.
//!
//! Inlining: in an optimised build (no `debug_assertions`) these kernels are
//! `#[inline(always)]`, so the topology constants of the generated call fold into them
//! (what makes the generated code fast); in a debug build they are plain `#[inline]`
//! functions the generated code calls, which keeps the build cost of a mechanism low
//! (`docs/macro_cost.md`).

pub use crate::kernel::constraints::{eval, Con, ConEval, ConKind, Drive, JointGeom, Level, Row};
pub use crate::kernel::dyad::Solver;
use crate::kernel::kinetostatics::{Reaction, Wrench};
pub use crate::kernel::link_state::{
    anchor_motion, anchor_pose, cross, perp, point_motion, point_pose, rotate, wrap, LinkGeom,
    LinkMotion, LinkPose, LinkState, PointMotion, PointPose, V2,
};
pub use crate::kernel::natural::DyadSystem;
use crate::kernel::screw::{chain_rates, driven_rates, Chain, Driven};
use crate::MechError;

/// Solve a closed-form group up to `upto`: place its links by `solver` on the drawing's
/// branch `sign`, then its velocities and accelerations in natural coordinates for an RRR,
/// RRP, RPR, PRP or RPP dyad ([`crate::kernel::natural`]) and a slotted slider, by the
/// chain's joint screws for the others.
/// `Singular` near a change point, `NoAssembly` where the group does not close. Returns
/// what the dyad keeps for its reactions ([`DyadSystem`]).
#[cfg_attr(debug_assertions, inline)]
#[cfg_attr(not(debug_assertions), inline(always))]
#[allow(clippy::too_many_arguments)]
pub fn solve_chain(
    solver: Solver,
    chain: &Chain,
    joints: &[JointGeom],
    s: &mut [LinkState],
    drive: Drive,
    sign: f64,
    scale: f64,
    upto: Level,
) -> Result<DyadSystem, MechError> {
    let points = crate::kernel::dyad::position(solver, joints, s, drive, sign)?;
    match solver {
        Solver::Rrr { b1, b2, ja, jb, .. } => {
            crate::kernel::natural::rrr_rates(joints, s, b1, b2, ja, jb, points, upto)
        }
        Solver::Rrp { b1, b2, ja, jc, jp } => {
            crate::kernel::natural::rrp_rates(joints, s, b1, b2, ja, jc, jp, points, scale, upto)
        }
        Solver::Rpr { b1, b2, ja, jp, jb } => {
            crate::kernel::natural::rpr_rates(joints, s, b1, b2, ja, jp, jb, points, scale, upto)
        }
        Solver::Prp {
            b1,
            b2,
            jp1,
            jc,
            jp2,
        } => crate::kernel::natural::prp_rates(joints, s, b1, b2, jp1, jc, jp2, points, upto),
        Solver::Rpp { b1, b2, ja, jp, jq } => {
            crate::kernel::natural::rpp_rates(joints, s, b1, b2, ja, jp, jq, points, upto)
        }
        Solver::SlottedSlider { body, jq, js } => crate::kernel::slotted::slotted_slider_rates(
            &joints[jq],
            &joints[js],
            s,
            body,
            points[0].x,
            upto,
        )
        .map(|()| DyadSystem::None),
        _ => chain_rates(chain, joints, s, scale, upto).map(|()| DyadSystem::None),
    }
}

/// d'Alembert for a closed-form group: the reaction at each of its joints into `out`
/// (joint order), and the reactions on the solved links it is jointed to added to their
/// wrenches in `f` (every link's applied and inertia wrench about its anchor, plus the
/// reactions of the groups solved before). In natural coordinates for an RRR, RRP, RPR,
/// PRP or RPP dyad ([`crate::kernel::natural`]) and a slotted slider, by the chain's joint
/// screws for the others. Called from the
/// outermost group inward. `kept` is what [`solve_chain`] returned for the motion.
#[cfg_attr(debug_assertions, inline)]
#[cfg_attr(not(debug_assertions), inline(always))]
#[allow(clippy::too_many_arguments)]
pub fn chain_reactions(
    solver: Solver,
    chain: &Chain,
    joints: &[JointGeom],
    s: &[LinkState],
    f: &mut [Wrench],
    scale: f64,
    kept: &DyadSystem,
    out: &mut [Reaction],
) -> Result<(), MechError> {
    match solver {
        Solver::Rrr { b1, b2, ja, jc, jb } => {
            crate::kernel::natural::rrr_reactions(joints, s, f, b1, b2, ja, jc, jb, kept, out)
        }
        Solver::Rrp { b1, b2, ja, jc, jp } => crate::kernel::natural::rrp_reactions(
            joints, s, f, b1, b2, ja, jc, jp, scale, kept, out,
        ),
        Solver::Rpr { b1, b2, ja, jp, jb } => crate::kernel::natural::rpr_reactions(
            joints, s, f, b1, b2, ja, jp, jb, scale, kept, out,
        ),
        Solver::Prp {
            b1,
            b2,
            jp1,
            jc,
            jp2,
        } => crate::kernel::natural::prp_reactions(joints, s, f, b1, b2, jp1, jc, jp2, out),
        Solver::Rpp { b1, b2, ja, jp, jq } => {
            crate::kernel::natural::rpp_reactions(joints, s, f, b1, b2, ja, jp, jq, out)
        }
        Solver::SlottedSlider { body, jq, js } => {
            crate::kernel::slotted::slotted_slider_reactions(joints, s, f, body, jq, js, out)
        }
        _ => crate::kernel::screw::chain_reactions(chain, joints, s, f, scale, out),
    }
}

/// Solve a driven crank or slider up to `upto`: its pose from the input q, then its
/// velocity and acceleration from q̇ and q̈.
#[cfg_attr(debug_assertions, inline)]
#[cfg_attr(not(debug_assertions), inline(always))]
pub fn solve_driven(
    solver: Solver,
    driven: &Driven,
    joints: &[JointGeom],
    s: &mut [LinkState],
    drive: Drive,
    upto: Level,
) -> Result<(), MechError> {
    crate::kernel::dyad::position(solver, joints, s, drive, 1.0)?;
    if driven.track {
        // The driven link's rotation over turns: its base's plus the input's (a revolute
        // driver), or its base's (a slider).
        let g = &joints[driven.screw.joint];
        let turn = if driven.screw.slide {
            0.0
        } else {
            drive.0[driven.input] - g.q_ref
        };
        let base = if driven.from == 0 {
            0.0
        } else {
            s[driven.from].angle
        };
        s[driven.body].angle = base + if g.b == driven.body { turn } else { -turn };
    }
    driven_rates(driven, joints, s, drive, upto)
}

/// The angle θ (rad, wrapped to (−π, π]) of a crank driven on the ground: q = θ_b − θ_a
/// with the ground's θ = 0, so θ = q when the crank is the joint's second link (`sign` =
/// 1) and −q when it is the first (`sign` = −1). No atan2 needed.
#[inline]
pub fn crank_angle(q: f64, sign: f64) -> f64 {
    wrap(sign * q)
}
