//! The closed-form kernels (joint screws, and natural coordinates for RRR, RRP, RPR, PRP
//! and RPP, through `kinematics::solve_chain` and `kinematics::chain_reactions`) against
//! the absolute-coordinate route: the same positions, then velocities and accelerations
//! from the group's scaled Jacobian (LU) and reactions from its transpose, for every
//! closed-form group kind.

use super::*;
use crate::front::resolve::model_of;
use crate::kernel::group::{group_rates, GroupSystem};
use crate::kernel::kinetostatics::{group_reactions, lambda_reactions};
use crate::kernel::measure::within;
use crate::plan::assur::{plan, Kernel};

/// One mechanism per closed-form kind (and the driven crank and slider).
const TEXTS: &[&str] = &[
    // DrivenRevolute + RRR
    "pub struct A { ground { O2: (0.0, 0.0), O4: (0.3, 0.0) },
      link crank { points { O2, A: (0.0, 0.1) } }, link coupler { points { A, B: (0.25, 0.25) } },
      link rocker { points { O4, B } },
      joints { O2: revolute(ground, crank), A: revolute(crank, coupler), B: revolute(coupler, rocker), O4: revolute(ground, rocker) },
      input: O2 }",
    // RRP, axis in ground, offset
    "pub struct B { ground { O2: (0.0, 0.0) },
      link crank { points { O2, A: (0.04, 0.03) } }, link rod { points { A, B: (0.24, 0.012) } }, link piston { points { B } },
      joints { O2: revolute(ground, crank), A: revolute(crank, rod), B: revolute(rod, piston),
               guide: prismatic(ground, piston) at B along (1.0, 0.1) },
      input: O2 }",
    // RRP with the axis in a moving link (two inputs)
    "pub struct C { ground { O2: (0.0, 0.0), O4: (0.4, 0.0) },
      link crank { points { O2, A: (0.05, 0.05) } }, link arm { points { O4, E: (0.4, 0.3) } },
      link rod { points { A, B: (0.3, 0.2) } }, link block { points { B } },
      joints { O2: revolute(ground, crank), O4: revolute(ground, arm), A: revolute(crank, rod), B: revolute(rod, block),
               slide: prismatic(arm, block) at B along (-0.1, 0.3) },
      inputs: [O2, O4] }",
    // RPR: inverted slider-crank
    "pub struct D { ground { O2: (0.0, 0.0), O4: (0.0, -0.2) },
      link crank { points { O2, A: (0.08, 0.05) } }, link block { points { A } }, link rocker { points { O4, R: (0.1, 0.2) } },
      joints { O2: revolute(ground, crank), A: revolute(crank, block), O4: revolute(ground, rocker),
               slot: prismatic(rocker, block) at A along (0.08, 0.25) },
      input: O2 }",
    // PRP
    "pub struct E { ground { O: (0.0, 0.0) },
      link crank { points { O, T: (0.1, 0.1) } }, link block { points { S: (0.08, 0.08) } }, link slider { points { S } },
      joints { O: revolute(ground, crank), radial: prismatic(crank, block) at S along (1.0, 1.0),
               S: revolute(block, slider), rail: prismatic(ground, slider) at S along (1.0, 0.0) },
      input: O }",
    // RPP
    "pub struct F { ground { O2: (0.0, 0.0) },
      link crank { points { O2, A: (0.04, 0.05) } }, link block { points { A } }, link yoke { points { Y: (0.2, 0.0) } },
      joints { O2: revolute(ground, crank), A: revolute(crank, block),
               slot: prismatic(yoke, block) at A along (0.1, 1.0), guide: prismatic(ground, yoke) at Y along (1.0, 0.0) },
      input: O2 }",
    // pin in a fixed slot
    "pub struct G { ground { O2: (0.0, 0.0) },
      link crank { points { O2, A: (0.05, 0.04) } }, link rod { points { A, B: (0.25, 0.02) } },
      joints { O2: revolute(ground, crank), A: revolute(crank, rod), slot: pin_in_slot(ground, rod) at B along (1.0, 0.2) },
      input: O2 }",
    // slotted lever (quick return)
    "pub struct H { ground { O2: (0.0, 0.2), O4: (0.0, 0.0) },
      link crank { points { O2, A: (0.07, 0.23) } }, link lever { points { O4, C: (0.2, 0.6) } },
      joints { O2: revolute(ground, crank), O4: revolute(ground, lever), slot: pin_in_slot(lever, crank) at A along (0.07, 0.23) },
      input: O2 }",
    // guide and slot (Scotch yoke), slot in the yoke, tilted
    "pub struct J { ground { O2: (0.0, 0.0) },
      link crank { points { O2, A: (0.04, 0.05) } }, link yoke { points { Y: (0.2, 0.01) } },
      joints { O2: revolute(ground, crank), guide: prismatic(ground, yoke) at Y along (1.0, 0.1),
               slot: pin_in_slot(yoke, crank) at A along (0.2, 1.0) },
      input: O2 }",
    // guide and slot, the guide on a turning arm, its axis in the yoke
    "pub struct K { ground { O2: (0.0, 0.0), O4: (0.3, -0.1) },
      link crank { points { O2, A: (0.04, 0.05) } }, link arm { points { O4, Y: (0.2, 0.02) } },
      link yoke { points { C: (0.25, 0.1) } },
      joints { O2: revolute(ground, crank), O4: revolute(ground, arm),
               guide: prismatic(yoke, arm) at Y along (1.0, -0.2),
               slot: pin_in_slot(yoke, crank) at A along (0.3, 1.0) },
      inputs: [O2, O4] }",
    // guide and slot, the slider's pin in the crank's slot
    "pub struct L { ground { O: (0.0, 0.0) },
      link crank { points { O, T: (0.1, 0.1) } }, link slider { points { S: (0.08, 0.06) } },
      joints { O: revolute(ground, crank), radial: pin_in_slot(crank, slider) at S along (1.0, 0.75),
               rail: prismatic(ground, slider) at S along (1.0, 0.0) },
      input: O }",
    // driven slider + RRR
    "pub struct I { ground { O4: (0.3, 0.0) },
      link slider { points { P: (0.0, 0.05) } }, link rod { points { P, B: (0.25, 0.2) } }, link rocker { points { O4, B } },
      joints { drive: prismatic(ground, slider) at P along (1.0, 0.2), P: revolute(slider, rod),
               B: revolute(rod, rocker), O4: revolute(ground, rocker) },
      input: drive }",
];

/// |a − b| ≤ tol (absolute: these mechanisms are about a metre across, their loads unit).
#[track_caller]
fn close(a: f64, b: f64, tol: f64) -> bool {
    within((a - b).abs(), tol)
}

#[test]
fn screw_rates_and_reactions_match_the_jacobian_route() {
    let mut kinds = std::collections::BTreeSet::new();
    for text in TEXTS {
        both_routes_agree(text, &mut kinds);
    }
    let want = [
        "DrivenRevolute",
        "DrivenPrismatic",
        "Rrr",
        "Rrp",
        "Rpr",
        "Prp",
        "Rpp",
        "PinInFixedSlot",
        "SlottedLever",
        "SlottedSlider",
    ];
    for k in want {
        assert!(
            kinds.contains(k),
            "no test mechanism exercises {k}: {kinds:?}"
        );
    }
}

/// Sweeps the inputs of the mechanism `text` over 7 positions and compares both routes
/// at each one that assembles (at least 4); adds the closed-form kinds met to `kinds`.
fn both_routes_agree(text: &str, kinds: &mut std::collections::BTreeSet<String>) {
    let model = model_of(text);
    let inst = crate::solvers::instance::instance(&model).expect("instance");
    let groups = plan(&model).expect("plan");
    let solvers: Vec<_> = groups.iter().map(|g| g.solver).collect();
    let branches = inst.branches(&solvers);
    let n_in = model.inputs.len();
    let mut assembled = 0;
    for k in 0..7 {
        let (q, qd, qdd) = inputs_at(&model, &inst, k);
        let drive = (&q[..], &qd[..], &qdd[..]);
        let Some((sa, sb)) = both_kinematics(text, &inst, &groups, &branches, drive, kinds) else {
            continue;
        };
        for (a, b) in sa.iter().zip(&sb) {
            for (x, y) in [
                (a.pos.x, b.pos.x),
                (a.pos.y, b.pos.y),
                (a.vel.x, b.vel.x),
                (a.vel.y, b.vel.y),
                (a.omega, b.omega),
            ] {
                // measured worst 2.3e-13 (be05608); 100×
                assert!(close(x, y, 2e-11), "{text}: velocity level {x} vs {y}");
            }
            for (x, y) in [(a.acc.x, b.acc.x), (a.acc.y, b.acc.y), (a.alpha, b.alpha)] {
                // measured worst 1.2e-10 (be05608); 100×
                assert!(close(x, y, 1e-8), "{text}: acceleration level {x} vs {y}");
            }
        }
        assembled += 1;
        both_reactions_agree(text, &inst, &groups, &sa, &sb, n_in);
    }
    assert!(
        assembled >= 4,
        "{text}: only {assembled} of 7 inputs assemble"
    );
}

/// The inputs' positions, rates and accelerations at step `k` of the sweep.
fn inputs_at(
    model: &crate::model::Model,
    inst: &crate::solvers::instance::Instance,
    k: usize,
) -> (Vec<f64>, Vec<f64>, Vec<f64>) {
    let n_in = model.inputs.len();
    let q: Vec<f64> = (0..n_in)
        .map(|i| 0.3 * k as f64 - 0.8 + 0.1 * i as f64)
        .collect();
    let q: Vec<f64> = if model.joints[model.inputs[0]].kind == crate::model::JointKind::Revolute {
        q.iter()
            .map(|&x| inst.joints[model.inputs[0]].q_ref + x)
            .collect()
    } else {
        q.iter().map(|&x| 0.05 * x).collect()
    };
    let qd: Vec<f64> = (0..n_in).map(|i| 3.0 - 1.3 * i as f64).collect();
    let qdd: Vec<f64> = (0..n_in).map(|i| -2.0 + 0.7 * i as f64).collect();
    (q, qd, qdd)
}

/// The links' states to accelerations by both routes, group by group: (screw kernels,
/// Jacobian); `None` when a group does not assemble.
fn both_kinematics(
    text: &str,
    inst: &crate::solvers::instance::Instance,
    groups: &[crate::plan::assur::Group],
    branches: &[f64],
    drive: Drive,
    kinds: &mut std::collections::BTreeSet<String>,
) -> Option<(Vec<LinkState>, Vec<LinkState>)> {
    let (mut sa, mut sb) = (inst.drawing.clone(), inst.drawing.clone());
    for (g, &sign) in groups.iter().zip(branches) {
        if crate::kernel::dyad::position(g.solver, &inst.joints, &mut sa.clone(), drive, sign)
            == Err(MechError::NoAssembly)
        {
            return None;
        }
        kinds.insert(
            format!("{:?}", g.solver)
                .split([' ', '{'])
                .next()
                .unwrap()
                .to_string(),
        );
        match &g.kernel {
            Kernel::Chain(c) => crate::kernel::kinematics::solve_chain(
                g.solver,
                c,
                &inst.joints,
                &mut sa,
                drive,
                sign,
                inst.scale,
                Level::Acceleration,
            )
            .map(|_| ()),
            Kernel::Driven(d) => crate::kernel::kinematics::solve_driven(
                g.solver,
                d,
                &inst.joints,
                &mut sa,
                drive,
                Level::Acceleration,
            ),
            Kernel::System
            | Kernel::Mesh(_)
            | Kernel::Train(_)
            | Kernel::Rolling(_)
            | Kernel::Cam(_) => {
                panic!("{text}: no screw kernel")
            }
        }
        .expect("screw route");
        crate::kernel::dyad::position(g.solver, &inst.joints, &mut sb, drive, sign)
            .expect("position");
        jacobian_rates(g, inst, &mut sb, drive);
    }
    Some((sa, sb))
}

/// The rates of group `g` from its scaled Jacobian (LU): velocities, then accelerations.
fn jacobian_rates(
    g: &crate::plan::assur::Group,
    inst: &crate::solvers::instance::Instance,
    sb: &mut [LinkState],
    drive: Drive,
) {
    let sys = GroupSystem::<6>::new(&g.bodies, &g.cons, &inst.joints, sb, inst.scale);
    // One-link groups: a 3×3 system.
    if g.bodies.len() == 1 {
        let sys =
            GroupSystem::<3>::new(&g.bodies, &g.cons, &inst.joints, sb, inst.scale).expect("lu");
        for level in [Level::Velocity, Level::Acceleration] {
            group_rates(&sys, &g.bodies, &g.cons, &inst.joints, sb, drive, level);
        }
    } else {
        let sys = sys.expect("lu");
        for level in [Level::Velocity, Level::Acceleration] {
            group_rates(&sys, &g.bodies, &g.cons, &inst.joints, sb, drive, level);
        }
    }
}

/// Reactions from arbitrary wrenches on every moving link, by both routes, agree.
fn both_reactions_agree(
    text: &str,
    inst: &crate::solvers::instance::Instance,
    groups: &[crate::plan::assur::Group],
    sa: &[LinkState],
    sb: &[LinkState],
    n_in: usize,
) {
    let n = inst.links.len();
    let w0: Vec<Wrench> = (0..n)
        .map(|l| Wrench::new(10.0 - 3.0 * l as f64, 4.0 + l as f64, 0.5 - 0.2 * l as f64))
        .collect();
    let (mut fa, mut fb) = (w0.clone(), w0);
    let nj = inst.joints.len();
    let (mut ra, mut rb) = (vec![Reaction::default(); nj], vec![Reaction::default(); nj]);
    let (mut da, mut db) = (vec![0.0; n_in], vec![0.0; n_in]);
    for g in groups.iter().rev() {
        match &g.kernel {
            Kernel::Chain(c) => crate::kernel::kinematics::chain_reactions(
                g.solver,
                c,
                &inst.joints,
                sa,
                &mut fa,
                inst.scale,
                &crate::kernel::natural::DyadSystem::None,
                &mut ra,
            )
            .expect("chain"),
            Kernel::Driven(d) => driven_reactions(d, &inst.joints, sa, &mut fa, &mut ra, &mut da),
            Kernel::System
            | Kernel::Mesh(_)
            | Kernel::Train(_)
            | Kernel::Rolling(_)
            | Kernel::Cam(_) => unreachable!(),
        }
        let lam = if g.bodies.len() == 1 {
            group_reactions::<3>(
                None,
                &g.bodies,
                &g.cons,
                &inst.joints,
                sb,
                &mut fb,
                inst.scale,
            )
            .expect("lu")
            .as_slice()
            .to_vec()
        } else {
            group_reactions::<6>(
                None,
                &g.bodies,
                &g.cons,
                &inst.joints,
                sb,
                &mut fb,
                inst.scale,
            )
            .expect("lu")
            .as_slice()
            .to_vec()
        };
        lambda_reactions(&g.cons, &inst.joints, sb, &lam, &mut rb, &mut db);
    }
    for (a, b) in ra.iter().zip(&rb) {
        for (x, y) in [
            (a.force.x, b.force.x),
            (a.force.y, b.force.y),
            (a.moment, b.moment),
        ] {
            // measured worst 3.6e-15 (be05608); 100×
            assert!(close(x, y, 2e-13), "{text}: reaction {x} vs {y}");
        }
    }
    for (x, y) in da.iter().zip(&db) {
        // measured worst 3.6e-15 (be05608); 100×. Relative beyond unity: the PRP's driver
        // torque, 1876 N·m, differs by 2 ulp (4.5e-13) since the natural route (6d93c4d).
        assert!(
            close(*x, *y, 2e-13 * y.abs().max(1.0)),
            "{text}: driver {x} vs {y}"
        );
    }
}
