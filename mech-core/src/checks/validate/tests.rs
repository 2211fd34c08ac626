//! The checks on whole mechanisms: each check family's verdicts and messages.

use super::*;

use crate::front::resolve::model_of as model;

const SLIDER_CRANK: &str = r#"
        /// Offset slider-crank of a single-cylinder engine.
        pub struct SliderCrank {
            gravity: (0.0, -9.81),
            ground { O2: (0.0, 0.0) },
            link crank {
                points { O2, A: (0.038302, 0.032139) },
                mass: 1.2, inertia: 2.1e-3, cg: (0.0089, 0.0127),
            },
            link rod {
                points { A, B: (0.237285, 0.012) },
                mass: 2.4, inertia: 9.5e-3, cg: (0.1030, 0.0256),
            },
            link piston {
                points { B },
                mass: 1.7, cg: (0.237285, 0.012),
            },
            joints {
                O2: revolute(ground, crank),
                A: revolute(crank, rod),
                B: revolute(rod, piston),
                guide: prismatic(ground, piston) at B along (1.0, 0.0),
            },
            input: O2,
            loads {
                gas: force on piston at B,
                load: torque on crank,
            },
        }
    "#;

/// Four-bar; `B_AT` is the coupler–rocker pin.
const FOUR_BAR: &str = r#"
        pub struct FourBar {
            ground { O2: (0.0, 0.0), O4: (3.0, 0.0) },
            link crank { points { O2, A: (0.0, 1.0) } },
            link coupler { points { A, B: B_AT } },
            link rocker { points { B, O4 } },
            joints {
                O2: revolute(ground, crank),
                A: revolute(crank, coupler),
                B: revolute(coupler, rocker),
                O4: revolute(rocker, ground),
            },
            input: O2,
        }
    "#;

const DOUBLE_PARALLELOGRAM: &str = r#"
        pub struct Parallel {
            ground { O1: (0.0, 0.0), O2: (1.0, 0.0), O3: (2.0, 0.0) },
            link c1 { points { O1, A1: (0.0, 1.0) } },
            link c2 { points { O2, A2: (1.0, 1.0) } },
            link c3 { points { O3, A3: (2.0, 1.0) } },
            link coupler { points { A1, A2, A3 }, mass: 1.0, cg: (1.0, 1.0) },
            joints {
                O1: revolute(ground, c1),
                O2: revolute(ground, c2),
                O3: revolute(ground, c3),
                A1: revolute(c1, coupler),
                A2: revolute(c2, coupler),
                A3: revolute(c3, coupler),
            },
            input: O1,
        }
    "#;

fn culprit_links(i: &Issue) -> Vec<usize> {
    i.culprits
        .iter()
        .filter_map(|c| {
            if let Culprit::Link(l) = c {
                Some(*l)
            } else {
                None
            }
        })
        .collect()
}

#[test]
fn slider_crank_passes_everything() {
    let m = model(SLIDER_CRANK);
    assert_eq!(check(&m), vec![]);
    let j = jacobian(&m);
    assert_eq!(j.matrix.shape(), (9, 9));
    assert_eq!(j.driver.iter().filter(|&&d| d).count(), 1);
    // Dimensionless: every entry is of order one.
    assert!(j.matrix.amax() <= 1.0 + 1e-12);
}

#[test]
fn four_bar_and_slot_pass() {
    assert_eq!(
        check(&model(&FOUR_BAR.replace("B_AT", "(2.5, 2.0)"))),
        vec![]
    );
    let yoke = model(
        r#"pub struct Yoke {
                ground { O: (0.0, 0.0) },
                link crank { points { O, A: (0.1, 0.05) } },
                link yoke { points { C: (0.3, 0.0) }, mass: 2.0, cg: (0.3, 0.0) },
                joints {
                    O: revolute(ground, crank),
                    slot: pin_in_slot(yoke, crank) at A along (0.0, 1.0),
                    guide: prismatic(ground, yoke) at C along (1.0, 0.0),
                },
                input: O,
            }"#,
    );
    assert_eq!(check(&yoke), vec![]);
    // A prismatic driver (an actuator) on an inclined guide.
    let lever = model(
        r#"pub struct Lever {
                ground { O: (0.0, 0.0), C: (1.0, -0.5) },
                link arm { points { O, A: (1.0, 0.3) } },
                link cyl { points { C } },
                link rod { points { A, P: (1.0, -0.1) } },
                joints {
                    O: revolute(ground, arm),
                    A: revolute(arm, rod),
                    C: revolute(ground, cyl),
                    stroke: prismatic(cyl, rod) at P along (0.0, 1.0),
                },
                input: stroke,
            }"#,
    );
    assert_eq!(check(&lever), vec![]);
}

#[test]
fn grubler_mismatch_is_reported_with_numbers() {
    let m = model(
        &FOUR_BAR
            .replace("B_AT", "(2.5, 2.0)")
            .replace("input: O2", "inputs: [O2, O4]"),
    );
    let issues = check(&m);
    assert_eq!(issues.len(), 1, "{issues:#?}");
    let msg = &issues[0].message;
    assert!(
        msg.contains("N = 4") && msg.contains("P_I = 4") && msg.contains("P_II = 0"),
        "{msg}"
    );
    assert!(
        msg.contains("= 1") && msg.contains("9 equations") && msg.contains("9 unknowns"),
        "{msg}"
    );
    assert!(msg.contains("2 inputs were declared"), "{msg}");
}

#[test]
fn double_parallelogram_is_redundant() {
    let m = model(DOUBLE_PARALLELOGRAM);
    let issues = geometric(&m);
    assert_eq!(issues.len(), 1, "{issues:#?}");
    let msg = &issues[0].message;
    assert!(msg.starts_with("redundant constraints at the drawing: the joints' 12 constraint equations have rank 11, so 1 constraint is redundant"), "{msg}");
    assert!(
        msg.contains("joints `O1`, `O2`, `O3`, `A1`, `A2`, `A3` take part"),
        "{msg}"
    );
    assert!(msg.contains("#[allow(redundant)]"), "{msg}");
    assert_eq!(issues[0].culprits.len(), 6);
    // Through `check`, Grübler (G = 0 with one input) would say it cannot move; the
    // rank shows it does, so the redundancy is what is reported.
    let all = check(&m);
    assert_eq!(all.len(), 1, "{all:#?}");
    assert!(
        all[0]
            .message
            .starts_with("redundant constraints at the drawing"),
        "{}",
        all[0].message
    );
    assert!(
        all[0].message.contains("G = 0 for 1 input(s)"),
        "{}",
        all[0].message
    );
    assert!(all[0].message.contains("#[allow(redundant)]"));
    // Accepted when declared.
    let ok = model(&format!("#[allow(redundant)] {DOUBLE_PARALLELOGRAM}"));
    assert_eq!(check(&ok), vec![]);
    // ... but with #[allow(redundant)] the inputs must still match the true mobility.
    let two = model(&format!(
        "#[allow(redundant)] {}",
        DOUBLE_PARALLELOGRAM.replace("input: O1", "inputs: [O1, O2]")
    ));
    let issues = check(&two);
    assert_eq!(issues.len(), 1, "{issues:#?}");
    assert!(
        issues[0]
            .message
            .contains("leaves 1 DOF, but 2 inputs were declared: declare 1 input"),
        "{}",
        issues[0].message
    );
}

#[test]
fn dead_point_fails_determinacy() {
    // Coupler and rocker collinear: A = (0, 1), B = (1.5, 0.5), O4 = (3, 0). With the
    // crank held, B can still move normal to the line A–O4.
    let m = model(&FOUR_BAR.replace("B_AT", "(1.5, 0.5)"));
    assert!(drawing(&m).is_empty());
    assert_eq!(crate::checks::grubler::check(&m), None);
    assert!(crate::checks::pebble::check(&m).is_empty());
    let issues = check(&m);
    assert_eq!(issues.len(), 1, "{issues:#?}");
    let msg = &issues[0].message;
    assert!(
        msg.starts_with("the inputs do not determine the position at the drawing (a dead point, or a missing input): links `coupler`, `rocker` can still move"),
        "{msg}"
    );
    assert!(msg.contains("have rank 8 < 3(N−1) = 9"), "{msg}");
    assert!(
        msg.contains("redraw the mechanism away from the dead point, or add an input"),
        "{msg}"
    );
    assert_eq!(issues[0].culprits[0], Culprit::Inputs);
    assert_eq!(culprit_links(&issues[0]), vec![2, 3]);
    // Crank and coupler collinear is the crank's own dead point only when the rocker
    // drives; with the crank as input the drawing is determinate.
    let m = model(
        &FOUR_BAR
            .replace("B_AT", "(0.0, 2.5)")
            .replace("O4: (3.0, 0.0)", "O4: (2.0, 0.5)"),
    );
    assert_eq!(check(&m), vec![]);
}

#[test]
fn missing_input_fails_determinacy() {
    let m = model(
        &FOUR_BAR
            .replace("B_AT", "(2.5, 2.0)")
            .replace("input: O2,", ""),
    );
    let issues = geometric(&m);
    assert_eq!(issues.len(), 1, "{issues:#?}");
    assert_eq!(culprit_links(&issues[0]), vec![1, 2, 3]);
}

#[test]
fn drawing_errors() {
    let neg = model(&SLIDER_CRANK.replace("mass: 2.4", "mass: -2.4"));
    let issues = drawing(&neg);
    assert_eq!(issues.len(), 1, "{issues:#?}");
    assert_eq!(issues[0].culprits[0], Culprit::Mass(2));
    assert!(
        issues[0]
            .message
            .starts_with("link `rod` has mass -2.4 kg: a mass must be finite and ≥ 0"),
        "{}",
        issues[0].message
    );
    assert!(!check(&neg).is_empty());

    let neg_i = model(&SLIDER_CRANK.replace("inertia: 2.1e-3", "inertia: -2.1e-3"));
    let issues = drawing(&neg_i);
    assert_eq!(issues.len(), 1);
    assert_eq!(issues[0].culprits[0], Culprit::Inertia(1));
    assert!(
        issues[0]
            .message
            .contains("moment of inertia -0.0021 kg·m²"),
        "{}",
        issues[0].message
    );

    let zero_axis = model(&SLIDER_CRANK.replace("along (1.0, 0.0)", "along (0.0, 0.0)"));
    let issues = drawing(&zero_axis);
    assert_eq!(issues.len(), 1, "{issues:#?}");
    assert_eq!(issues[0].culprits[0], Culprit::Axis(3));
    assert!(
        issues[0]
            .message
            .starts_with("prismatic joint `guide` has sliding axis along (0, 0), which is zero"),
        "{}",
        issues[0].message
    );
    // The geometric check is not run on a bad drawing (no cascade).
    assert_eq!(check(&zero_axis).len(), 1);

    let same = model(
        &SLIDER_CRANK
            .replace("B: (0.237285, 0.012)", "B: (0.038302, 0.032139)")
            .replace("cg: (0.237285, 0.012)", "cg: (0.038302, 0.032139)"),
    );
    let issues = drawing(&same);
    assert_eq!(issues.len(), 1, "{issues:#?}");
    assert_eq!(
        issues[0].culprits,
        vec![Culprit::Point(2), Culprit::Link(2)]
    );
    assert!(
        issues[0]
            .message
            .starts_with("points `A` and `B` of link `rod` coincide"),
        "{}",
        issues[0].message
    );
    assert_eq!(check(&same).len(), 1);

    let mut nan = model(SLIDER_CRANK);
    nan.gravity = Some([0.0, f64::NAN]);
    nan.points[1].pos[0] = f64::INFINITY;
    let issues = drawing(&nan);
    assert_eq!(issues.len(), 2, "{issues:#?}");
    assert!(issues.iter().any(|i| i.culprits == vec![Culprit::Gravity]));
    assert!(issues.iter().any(|i| i.culprits == vec![Culprit::Point(1)]));
    let _ = geometric(&nan); // must neither panic nor hang
}
