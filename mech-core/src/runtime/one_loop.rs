//! Zhukovski's sums of a machine of one loop solved on a literal numbering. One loop: a
//! crank on the ground and one closed-form dyad (RRR, RRP, RPR, PRP, RPP or a slotted
//! slider), such as the four-bar, the slider-crank, the quick-return, the Scotch yokes and
//! the slotted crank-ram. The plan walk ([`super::dispatch`]) solves them on the
//! mechanism's own link and joint numbers, data read at run time, so every state's place
//! and every side test of a kernel is computed per call. Here the two groups are solved
//! on a local numbering written as literals (the ground 0, the crank 1, the dyad's links 2
//! and 3; the crank's joint 0, the dyad's joints 1 to 3), as the generated code does with
//! its constants: the states are a `[LinkState; 4]` on the stack at constant places, and
//! the kernels' side tests fold. The same kernels run on the same numbers: the results
//! are the plan walk's bit for bit (the tests below, `tests/runtime_peer.rs`).
//!
//! It serves Zhukovski's sums ([`OneLoop::sums`]: `reduced`, `acceleration` and M*), whose
//! result is a few numbers read off the local states. The operations that publish every
//! link and point (`pose`, `kinematics`) keep the plan walk: measured, copying the local
//! states out to the mechanism's numbering cost them more than the literal indices saved.
//!
//! Each joint's sides are literals too:
//! - a revolute's two sides are put in the local order where the mechanism wrote them the
//!   other way (its local vectors swapped with them), which changes no operation: the
//!   kernels read a revolute only through "the side that is not this link"
//!   ([`crate::kernel::dyad::pin`], `natural::local_in`);
//! - a prismatic or slot joint's sides mean something (the guide carries the axis), so
//!   each of its two orders is its own instance (`MASK`), as is which of the dyad's outer
//!   joints is on the crank (`C`): 34 forms, each with the crank's pin at its anchor or
//!   not (`PINNED`). They solve up to the accelerations (I* and dI*/dq need them); M*
//!   alone (velocities) keeps the plan walk.

use crate::kernel::constraints::{Drive, JointGeom, Level};
use crate::kernel::dyad::Solver;
use crate::kernel::kinematics;
use crate::kernel::link_state::LinkState;
use crate::kernel::screw::Driven;
use crate::model::{JointKind, Model};
use crate::plan::assur::{Group, Kernel};
use crate::MechError;

use super::instances::crank_alone;
use super::mechanism::Mechanism;
use super::results::Loads;
use crate::solvers::zhukovski::ZhukovskiSums;

/// The dyad's kind, as the const generic `FORM` of [`OneLoop::sums`]' instances.
const RRR: u8 = 0;
const RRP: u8 = 1;
const RPR: u8 = 2;
const PRP: u8 = 3;
const RPP: u8 = 4;
const SLOTTED: u8 = 5;

/// A mechanism of one loop, found at loading ([`OneLoop::find`]): what its solve reads
/// besides the joints' numbers.
#[derive(Clone, Copy, Debug)]
pub(super) struct OneLoop {
    /// The dyad's kind (`RRR` … `SLOTTED`).
    form: u8,
    /// The dyad's first outer joint (b₁'s pin or guide, a slotted slider's guide) is on
    /// the crank; else on the ground, and the other outer joint on the crank. (With
    /// `mask`, what chose `instance`; read again by the tests, which count the forms.)
    #[cfg_attr(not(test), allow(dead_code))]
    on_crank: bool,
    /// Bit k: the dyad's joint k is a prismatic or slot joint written in the other order
    /// than the local one ([`canonical`]).
    #[cfg_attr(not(test), allow(dead_code))]
    mask: u8,
    /// The crank's joint, then the dyad's three (a slotted slider's two, the second
    /// twice), their local vectors in the local order (a revolute written in the other
    /// order has them swapped); their sides are set as literals at each call.
    local: [JointGeom; 4],
    /// The local number of each of the mechanism's links (the ground 0, the crank 1, b₁
    /// 2, b₂ 3).
    local_of: [usize; 4],
    /// The crank's driven group, its body the local 1.
    driven: Driven,
    /// This form's instance of the solve and the sums ([`OneLoop::sums_form`]), chosen
    /// at loading: a call goes straight to it.
    instance: Instance,
    /// The local numbering is the mechanism's (the crank is link 1, b₁ link 2, b₂ link
    /// 3): Zhukovski's sums then read the local states by the mechanism's numbers, with
    /// no map.
    in_order: bool,
}

/// The local sides (a, b) of the dyad's three joints in the local order: b₁'s outer joint
/// from the solved link `l1` (the crank 1 when `on_crank`, else the ground 0), the inner
/// joint from b₁ (2) to b₂ (3), b₂'s outer joint from the other solved link; a slotted
/// slider's guide from `l1` to its body (2), its slot joint from the body to the other.
const fn canonical(form: u8, on_crank: bool) -> [(usize, usize); 3] {
    let (l1, l2) = if on_crank { (1, 0) } else { (0, 1) };
    if form == SLOTTED {
        [(l1, 2), (2, l2), (2, l2)]
    } else {
        [(l1, 2), (2, 3), (l2, 3)]
    }
}

/// [`canonical`] with joint k's sides exchanged where bit k of `mask` is set: the local
/// sides as the joints are written.
const fn sides(form: u8, on_crank: bool, mask: u8) -> [(usize, usize); 3] {
    let mut e = canonical(form, on_crank);
    let mut k = 0;
    while k < 3 {
        if mask & (1 << k) != 0 {
            e[k] = (e[k].1, e[k].0);
        }
        k += 1;
    }
    e
}

/// The dyad's solver on the local numbering.
const fn local_solver(form: u8) -> Solver {
    match form {
        RRR => Solver::Rrr {
            b1: 2,
            b2: 3,
            ja: 1,
            jc: 2,
            jb: 3,
        },
        RRP => Solver::Rrp {
            b1: 2,
            b2: 3,
            ja: 1,
            jc: 2,
            jp: 3,
        },
        RPR => Solver::Rpr {
            b1: 2,
            b2: 3,
            ja: 1,
            jp: 2,
            jb: 3,
        },
        PRP => Solver::Prp {
            b1: 2,
            b2: 3,
            jp1: 1,
            jc: 2,
            jp2: 3,
        },
        RPP => Solver::Rpp {
            b1: 2,
            b2: 3,
            ja: 1,
            jp: 2,
            jq: 3,
        },
        _ => Solver::SlottedSlider {
            body: 2,
            jq: 1,
            js: 2,
        },
    }
}

/// The literals of one instance, as associated constants (evaluated at compile time).
struct Local<const FORM: u8, const C: bool, const MASK: u8>;

impl<const FORM: u8, const C: bool, const MASK: u8> Local<FORM, C, MASK> {
    const SIDES: [(usize, usize); 3] = sides(FORM, C, MASK);
    const SOLVER: Solver = local_solver(FORM);
}

/// An instance of [`OneLoop::sums_form`].
type Instance =
    fn(&OneLoop, &Mechanism, Drive, Option<&Loads>, f64) -> Result<ZhukovskiSums, MechError>;

/// The instance of the form (`FORM`, `C`, `MASK`) and crank pin (`PINNED`) given, if it
/// is one of the 34 forms.
fn instance(form: u8, on_crank: bool, mask: u8, pinned: bool) -> Option<Instance> {
    macro_rules! by_form {
        ($(($f:ident, $c:literal, $mask:literal)),* $(,)?) => {
            match (form, on_crank, mask) {
                $(($f, $c, $mask) => Some(if pinned {
                    OneLoop::sums_form::<$f, $c, $mask, true>
                } else {
                    OneLoop::sums_form::<$f, $c, $mask, false>
                }),)*
                _ => None,
            }
        };
    }
    by_form!(
        (RRR, true, 0),
        (RRR, false, 0),
        (RRP, true, 0),
        (RRP, false, 0),
        (RRP, true, 4),
        (RRP, false, 4),
        (RPR, true, 0),
        (RPR, false, 0),
        (RPR, true, 2),
        (RPR, false, 2),
        (PRP, true, 0),
        (PRP, false, 0),
        (PRP, true, 1),
        (PRP, false, 1),
        (PRP, true, 4),
        (PRP, false, 4),
        (PRP, true, 5),
        (PRP, false, 5),
        (RPP, true, 0),
        (RPP, false, 0),
        (RPP, true, 2),
        (RPP, false, 2),
        (RPP, true, 4),
        (RPP, false, 4),
        (RPP, true, 6),
        (RPP, false, 6),
        (SLOTTED, true, 0),
        (SLOTTED, false, 0),
        (SLOTTED, true, 1),
        (SLOTTED, false, 1),
        (SLOTTED, true, 2),
        (SLOTTED, false, 2),
        (SLOTTED, true, 3),
        (SLOTTED, false, 3),
    )
}

impl OneLoop {
    /// The one-loop form of the plan `plan` of `model` (its joints' geometry `joints`),
    /// or `None`: two groups, a revolute crank on the ground (the ground the joint's
    /// first link) and one of the six closed-form dyads between the crank and the ground.
    pub(super) fn find(model: &Model, plan: &[Group], joints: &[JointGeom]) -> Option<Self> {
        let [g0, g1] = plan else { return None };
        if model.links.len() > 4 || model.allow_redundant && plan.iter().any(|g| g.redundant()) {
            return None;
        }
        let (Kernel::Driven(d), Kernel::Chain(_)) = (&g0.kernel, &g1.kernel) else {
            return None;
        };
        let crank = d.body;
        if d.from != 0 || d.screw.slide || crank == 0 || joints[d.screw.joint].a != 0 {
            return None;
        }
        let (form, b1, b2, dyad) = match g1.solver {
            Solver::Rrr { b1, b2, ja, jc, jb } => (RRR, b1, b2, [ja, jc, jb]),
            Solver::Rrp { b1, b2, ja, jc, jp } => (RRP, b1, b2, [ja, jc, jp]),
            Solver::Rpr { b1, b2, ja, jp, jb } => (RPR, b1, b2, [ja, jp, jb]),
            Solver::Prp {
                b1,
                b2,
                jp1,
                jc,
                jp2,
            } => (PRP, b1, b2, [jp1, jc, jp2]),
            Solver::Rpp { b1, b2, ja, jp, jq } => (RPP, b1, b2, [ja, jp, jq]),
            Solver::SlottedSlider { body, jq, js } => (SLOTTED, body, body, [jq, js, js]),
            _ => return None,
        };
        let local = |l: usize| match l {
            0 => Some(0),
            _ if l == crank => Some(1),
            _ if l == b1 => Some(2),
            _ if l == b2 && form != SLOTTED => Some(3),
            _ => None,
        };
        let ends = |j: usize| Some((local(joints[j].a)?, local(joints[j].b)?));
        // b₁'s outer joint: on the crank or on the ground.
        let (a, b) = ends(dyad[0])?;
        let on_crank = a == 1 || b == 1;
        let (mut mask, mut local) = (0u8, [joints[d.screw.joint]; 4]);
        // A slotted slider's third joint is its second again (unread).
        let n = if form == SLOTTED { 2 } else { 3 };
        for (k, (&j, want)) in dyad.iter().zip(canonical(form, on_crank)).enumerate() {
            local[k + 1] = joints[j];
            if k >= n {
                continue;
            }
            let (a, b) = ends(j)?;
            if (a, b) == want {
                continue;
            }
            if (b, a) != want {
                return None;
            }
            if model.joints[j].kind == JointKind::Revolute {
                let g = &mut local[k + 1];
                (g.da, g.db) = (g.db, g.da);
            } else {
                mask |= 1 << k;
            }
        }
        let mut one = OneLoop {
            in_order: false,
            form,
            on_crank,
            mask,
            local,
            local_of: {
                // b₁ last: a slotted slider's body is both.
                let mut to = [0; 4];
                for (l, k) in [(crank, 1), (b2, 3), (b1, 2)] {
                    to[l] = k;
                }
                to
            },
            driven: Driven { body: 1, ..*d },
            instance: instance(form, on_crank, mask, d.pinned)?,
        };
        one.in_order = (0..one.len()).all(|l| one.local_of[l] == l);
        // No link outside the loop (its states are the loop's alone), no force element
        // (they read the states by the mechanism's numbers).
        (model.links.len() == one.len() && model.elements.is_empty()).then_some(one)
    }

    /// The mechanism's number of links (the ground, the crank and the dyad's one or two).
    pub(super) fn len(&self) -> usize {
        if self.form == SLOTTED {
            3
        } else {
            4
        }
    }

    /// Zhukovski's sums of `m` ([`Mechanism::sums`]: the inertia terms, and those of
    /// `loads` when given) over its motion at `drive`, solved up to the accelerations on
    /// the local numbering by this form's instance.
    #[inline(always)]
    pub(super) fn sums(
        &self,
        m: &Mechanism,
        drive: Drive,
        loads: Option<&Loads>,
        qd: f64,
    ) -> Result<ZhukovskiSums, MechError> {
        (self.instance)(self, m, drive, loads, qd)
    }

    /// One instance of [`OneLoop::sums`]: the joints rebuilt with the literal sides of
    /// `Local<FORM, C, MASK>`, both groups solved on local states, the sums read them
    /// through the map from the mechanism's numbers.
    fn sums_form<const FORM: u8, const C: bool, const MASK: u8, const PINNED: bool>(
        &self,
        m: &Mechanism,
        drive: Drive,
        loads: Option<&Loads>,
        qd: f64,
    ) -> Result<ZhukovskiSums, MechError> {
        let Kernel::Chain(c) = &m.plan[1].kernel else {
            unreachable!("a one-loop plan's second group is a chain")
        };
        let upto = Level::Acceleration;
        let sides = Local::<FORM, C, MASK>::SIDES;
        let joint = |k: usize| self.local[k + 1].with_links(sides[k].0, sides[k].1, [false; 2]);
        let (dn, [j0]) = crank_alone::<true, PINNED>(&self.driven, &self.local[0]);
        let joints = [j0, joint(0), joint(1), joint(2)];
        // The ground's state is the drawing's, at rest with its anchor at the origin
        // (`plan::geometry::anchor`): a constant, which the kernels' reads of it fold.
        let mut l = [LinkState::default(); 4];
        let crank = Solver::DrivenRevolute {
            body: 1,
            joint: 0,
            input: dn.input,
        };
        kinematics::solve_driven(crank, &dn, &joints, &mut l, drive, upto)?;
        let (sign, scale) = (m.branches[1], m.inst.scale);
        let solver = Local::<FORM, C, MASK>::SOLVER;
        kinematics::solve_chain(solver, c, &joints, &mut l, drive, sign, scale, upto)?;
        let at = |g: usize| match self.local_of[g] {
            0 => &l[0],
            1 => &l[1],
            2 => &l[2],
            _ => &l[3],
        };
        if self.in_order {
            m.sums_by(|g: usize| &l[g], &[], loads, qd, true)
        } else {
            m.sums_by(at, &[], loads, qd, true)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::solvers::traits::OneDof;

    /// Machines of one loop, each dyad kind with b₁'s outer joint on the crank or on the
    /// ground, each dyad joint written as `@k` (both orders tried) and the dyad's links in
    /// two orders.
    const MACHINES: [(&str, [[&str; 2]; 3]); 9] = [
        (
            "pub struct Rrr { gravity: (0.0, -9.81), ground { O2: (0.0, 0.0), O4: (0.1, 0.0) },
             link crank { points { O2, A: (0.0, 0.03) }, mass: 1.0, inertia: 0.001, cg: (0.0, 0.015) },
             @L1 link coupler { points { A, B: (0.09, 0.06) }, mass: 2.0, inertia: 0.002, cg: (0.04, 0.05) },
             @L2 link rocker { points { O4, B }, mass: 1.5, inertia: 0.003, cg: (0.1, 0.03) },
             joints { O2: revolute(ground, crank), A: revolute(@0), B: revolute(@1), O4: revolute(@2) },
             input: O2, loads { resist: torque on rocker } }",
            [
                ["crank, coupler", "coupler, crank"],
                ["coupler, rocker", "rocker, coupler"],
                ["ground, rocker", "rocker, ground"],
            ],
        ),
        (
            "pub struct Rrp { gravity: (0.0, -9.81), ground { O: (0.0, 0.0) },
             link crank { points { O, A: (0.03, 0.01) }, mass: 1.0, inertia: 0.001, cg: (0.01, 0.005) },
             @L1 link rod { points { A, B: (0.15, 0.02) }, mass: 2.0, inertia: 0.002, cg: (0.07, 0.02) },
             @L2 link piston { points { B }, mass: 1.5, inertia: 0.003, cg: (0.16, 0.02) },
             joints { O: revolute(ground, crank), A: revolute(@0), B: revolute(@1),
                      guide: @2 along (1.0, 0.1) },
             input: O, loads { resist: torque on rod } }",
            [
                ["crank, rod", "rod, crank"],
                ["rod, piston", "piston, rod"],
                ["prismatic(ground, piston) at B", "prismatic(piston, ground) at O"],
            ],
        ),
        (
            "pub struct Rpr { gravity: (0.0, -9.81), ground { O2: (0.0, 0.0), O4: (0.28, 0.03) },
             link crank { points { O2, A: (0.04596266658713868, 0.03856725658119235) },
                          mass: 0.9, inertia: 0.0008, cg: (0.0149, 0.0148) },
             @L1 link rod { points { A, P: (0.44547293212306205, 0.015425352350640463) },
                        mass: 1.2, inertia: 0.019, cg: (0.2058, 0.0305) },
             @L2 link block { points { O4 }, mass: 2.4, inertia: 0.011, cg: (0.2454, 0.0370) },
             joints { O2: revolute(ground, crank), A: revolute(@0),
                      slide: @1 along (0.9961434918798252, -0.08773906533277448),
                      O4: revolute(@2) },
             input: O2, loads { push: force on rod at P } }",
            [
                ["crank, rod", "rod, crank"],
                ["prismatic(rod, block) at O4", "prismatic(block, rod) at A"],
                ["ground, block", "block, ground"],
            ],
        ),
        (
            "pub struct Prp { gravity: (0.0, -9.81), ground { O2: (0.0, 0.0) },
             link crank { points { O2, E: (0.058, 0.149) }, mass: 1.1, inertia: 0.0035, cg: (0.03, 0.06) },
             @L1 link block { points { B: (0.037, 0.086) }, mass: 0.3, inertia: 0.00006, cg: (0.039, 0.0885) },
             @L2 link ram { points { B, P: (0.21, 0.095) }, mass: 2.2, inertia: 0.018, cg: (0.13, 0.085) },
             joints { O2: revolute(ground, crank), slot: @0 along (1.0, 3.0),
                      B: revolute(@1), guide: @2 along (1.0, -0.1) },
             input: O2, loads { push: force on ram at P } }",
            [
                ["prismatic(crank, block) at B", "prismatic(block, crank) at E"],
                ["block, ram", "ram, block"],
                ["prismatic(ground, ram) at B", "prismatic(ram, ground) at O2"],
            ],
        ),
        (
            "pub struct Rpp { gravity: (0.0, -9.81), ground { O2: (0.0, 0.0) },
             link crank { points { O2, A: (0.041, 0.029) }, mass: 0.7, inertia: 0.00031, cg: (0.012, 0.016) },
             @L1 link block { points { A }, mass: 0.2, inertia: 0.00002, cg: (0.044, 0.027) },
             @L2 link yoke { points { Y: (0.16, 0.012), T: (0.26, 0.02) }, mass: 1.7, inertia: 0.0075, cg: (0.12, 0.018) },
             joints { O2: revolute(ground, crank), A: revolute(@0),
                      slot: @1 along (0.1, 1.0), guide: @2 along (1.0, 0.0) },
             input: O2, loads { resist: force on yoke at T } }",
            [
                ["crank, block", "block, crank"],
                ["prismatic(yoke, block) at A", "prismatic(block, yoke) at Y"],
                ["prismatic(ground, yoke) at Y", "prismatic(yoke, ground) at O2"],
            ],
        ),
        (
            "pub struct Slotted { gravity: (0.0, -9.81), ground { O2: (0.0, 0.0) },
             link crank { points { O2, A: (0.03856725658119236, 0.045962666587138684) },
                          mass: 0.7, inertia: 0.00031, cg: (0.011, 0.019) },
             @L1 @L2 link yoke { points { Y: (0.2, 0.0) }, mass: 1.9, inertia: 0.0068, cg: (0.13, 0.004) },
             joints { O2: revolute(ground, crank), guide: @0 along (1.0, 0.0),
                      slot: @1 along (0.0, 1.0) },
             input: O2, loads { resist: force on yoke at Y } }",
            [
                ["prismatic(ground, yoke) at Y", "prismatic(yoke, ground) at O2"],
                ["pin_in_slot(yoke, crank) at A", "pin_in_slot(crank, yoke) at Y"],
                ["", ""],
            ],
        ),
        (
            "pub struct RrpOnCrank { gravity: (0.0, -9.81), ground { O: (0.0, 0.0), Q: (0.1, 0.05) },
             link crank { points { O, C: (0.1, 0.0) }, mass: 1.0, inertia: 0.001, cg: (0.03, 0.0) },
             @L1 link rod { points { Q, B: (0.06, 0.0) }, mass: 2.0, inertia: 0.002, cg: (0.08, 0.03) },
             @L2 link piston { points { B }, mass: 1.5, inertia: 0.003, cg: (0.065, 0.002) },
             joints { O: revolute(ground, crank), Q: revolute(@0), B: revolute(@1),
                      guide: @2 along (1.0, 0.0) },
             input: O, loads { resist: torque on rod } }",
            [
                ["ground, rod", "rod, ground"],
                ["rod, piston", "piston, rod"],
                ["prismatic(crank, piston) at B", "prismatic(piston, crank) at C"],
            ],
        ),
        (
            "pub struct RppOnCrank { gravity: (0.0, -9.81), ground { O: (0.0, 0.0), Q: (0.08, 0.03) },
             link crank { points { O, C: (0.1, 0.0) }, mass: 1.0, inertia: 0.001, cg: (0.03, 0.0) },
             @L1 link block { points { Q }, mass: 0.2, inertia: 0.00002, cg: (0.081, 0.03) },
             @L2 link yoke { points { Y: (0.05, 0.0) }, mass: 1.7, inertia: 0.0075, cg: (0.06, 0.01) },
             joints { O: revolute(ground, crank), Q: revolute(@0),
                      slot: @1 along (0.1, 1.0), guide: @2 along (1.0, 0.0) },
             input: O, loads { resist: force on yoke at Y } }",
            [
                ["ground, block", "block, ground"],
                ["prismatic(yoke, block) at Q", "prismatic(block, yoke) at Y"],
                ["prismatic(crank, yoke) at Y", "prismatic(yoke, crank) at C"],
            ],
        ),
        (
            "pub struct SlottedOnCrank { gravity: (0.0, -9.81), ground { O: (0.0, 0.0), Q: (0.08, 0.03) },
             link crank { points { O, C: (0.1, 0.0) }, mass: 1.0, inertia: 0.001, cg: (0.03, 0.0) },
             @L1 @L2 link body { points { Y: (0.05, 0.0) }, mass: 1.7, inertia: 0.0075, cg: (0.06, 0.01) },
             joints { O: revolute(ground, crank), guide: @0 along (1.0, 0.0),
                      slot: @1 along (0.0, 1.0) },
             input: O, loads { resist: force on body at Y } }",
            [
                ["prismatic(crank, body) at Y", "prismatic(body, crank) at C"],
                ["pin_in_slot(body, ground) at Q", "pin_in_slot(ground, body) at Y"],
                ["", ""],
            ],
        ),
    ];

    /// Every text of `MACHINES`: each dyad joint's two orders, the links' two orders.
    fn variants() -> Vec<String> {
        let mut out = Vec::new();
        for (text, sides) in MACHINES {
            for bits in 0..16 {
                let mut t = text.to_string();
                for (k, s) in sides.iter().enumerate() {
                    t = t.replace(&format!("@{k}"), s[(bits >> k) & 1]);
                }
                // The dyad's two links declared in the other order: the second moved
                // before the first.
                let t = if bits & 8 != 0 {
                    let (first, second) = (t.find("@L1").unwrap(), t.find("@L2").unwrap());
                    let end = t[second..].find("\n").map_or(t.len(), |e| second + e);
                    let moved = t[second + 3..end].to_string();
                    format!(
                        "{}{}\n{}{}",
                        &t[..first],
                        moved,
                        &t[first..second],
                        &t[end..]
                    )
                } else {
                    t
                };
                out.push(t.replace("@L1", "").replace("@L2", ""));
            }
        }
        out.sort();
        out.dedup();
        out
    }

    /// The plan walk of the same mechanism.
    fn walk(m: &Mechanism) -> Mechanism {
        let mut w = m.clone();
        w.program.one_loop = None;
        w
    }

    /// Every output of `a` and `b` over a turn, compared through `Debug` (the shortest
    /// text that reads back to the same `f64`: equal text, equal bits).
    fn same(a: &Mechanism, b: &Mechanism, text: &str) {
        let mut loads = a.loads();
        for k in 0..loads.values.len() {
            let name = a.model.loads[k].name().to_string();
            let value: &[f64] = match loads.values[k] {
                crate::runtime::results::LoadValue::Force(_) => &[3.0, -2.0],
                crate::runtime::results::LoadValue::Torque(_) => &[1.5],
            };
            assert!(loads.set_by_name(&name, value));
        }
        let mut solved = 0;
        for i in 0..40 {
            let q = -3.1 + 0.157 * i as f64;
            let show = |x: &dyn std::fmt::Debug| format!("{x:?}");
            let (ka, kb) = (
                a.kinematics(&[q], &[1.3], &[-0.4]),
                b.kinematics(&[q], &[1.3], &[-0.4]),
            );
            assert_eq!(show(&ka), show(&kb), "kinematics at q = {q} of {text}");
            if let (Ok(ka), Ok(kb)) = (&ka, &kb) {
                solved += 1;
                assert_eq!(
                    show(&a.kinetostatics(ka, &loads)),
                    show(&b.kinetostatics(kb, &loads)),
                    "kinetostatics at q = {q} of {text}"
                );
            }
            assert_eq!(
                show(&a.pose(&[q])),
                show(&b.pose(&[q])),
                "pose at {q} of {text}"
            );
            assert_eq!(
                show(&a.reduced(q)),
                show(&b.reduced(q)),
                "reduced at {q} of {text}"
            );
            assert_eq!(
                show(&a.acceleration(q, 2.0, 0.7, &loads)),
                show(&b.acceleration(q, 2.0, 0.7, &loads)),
                "acceleration at {q} of {text}"
            );
        }
        // Not a comparison of failures alone.
        assert!(
            solved >= 8,
            "{solved} of 40 configurations assemble: {text}"
        );
    }

    /// Every variant is solved on one loop, bit for bit as the plan walk, and the variants
    /// reach every form of [`OneLoop::sums`].
    #[test]
    fn every_form_equals_the_plan_walk() {
        let mut seen = std::collections::BTreeSet::new();
        for text in variants() {
            let m = Mechanism::from_dsl(&text).unwrap_or_else(|e| panic!("{e}\n{text}"));
            let one = m
                .program
                .one_loop
                .unwrap_or_else(|| panic!("not one loop:\n{text}"));
            seen.insert((one.form, one.on_crank, one.mask));
            same(&m, &walk(&m), &text);
        }
        assert_eq!(seen.len(), 34, "{seen:?}");
    }

    /// The floor's machines of one loop (`benches/floor.rs`) take this path, in the
    /// order of their links (the sums at constant places).
    #[test]
    fn the_floor_machines_are_one_loop() {
        let reference = include_str!("../../../tests/common/mechanisms.rs");
        let floor = include_str!("../../../benches/floor/machines.rs");
        for (source, name, form) in [
            (reference, "FourBar", RRR),
            (reference, "SliderCrank", RRP),
            (reference, "QuickReturn", RPR),
            (reference, "ScotchYoke", SLOTTED),
            (floor, "InvertedSliderCrank", RPR),
            (floor, "BlockScotchYoke", RPP),
            (floor, "SlottedCrankRam", PRP),
        ] {
            let m = Mechanism::from_rust_source(source, name).unwrap();
            let one = m.program.one_loop.unwrap_or_else(|| panic!("{name}"));
            assert_eq!((one.form, one.in_order), (form, true), "{name}");
        }
        // Three groups (a gear pair before the crank): the plan walk.
        let geared = Mechanism::from_rust_source(floor, "GearedSliderCrank").unwrap();
        assert!(geared.program.one_loop.is_none());
    }
}
