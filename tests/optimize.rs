//! Optimisation (`mech::design::optimize`): a four-bar's crank length recovered from its own
//! coupler path; the engine's peak driver torque lowered, the written file re-loaded and its
//! objective recomputed here from the kinetostatics; the `flywheel` objective under a load
//! table with a kink every degree against the cycle at the full quadrature tolerance; the
//! same seed, the same run; bad input and a constraint that cannot be met named.

use mech::design::optimize::{optimize, Constraint, Objective, Settings, Variable};
use mech::Mechanism;

const PI: f64 = std::f64::consts::PI;

const FOUR_BAR: &str = "pub struct Linkage {
    consts { r: 0.1 },
    ground { O2: (0.0, 0.0), O4: (0.3, 0.0) },
    link crank { points { O2, A: (0.0, r) }, mass: 0.5, cg: (0.0, 0.05) },
    link coupler { points { A, B: (0.25, 0.2), P: (0.1, 0.3) }, mass: 1.0, cg: (0.12, 0.2) },
    link rocker { points { O4, B }, mass: 0.8, cg: (0.28, 0.1) },
    joints {
        O2: revolute(ground, crank),
        A: revolute(crank, coupler),
        B: revolute(coupler, rocker),
        O4: revolute(ground, rocker),
    },
    input: O2,
}";

fn settings(evaluations: usize) -> Settings {
    Settings {
        speed: 10.0,
        period: 2.0 * PI,
        steps: 36,
        evaluations,
        seed: 0,
    }
}

/// P's positions at the 36 instants of the drawn four-bar are the targets: the search,
/// started from r = 0.14, finds r = 0.1 again (the path objective 0 there).
#[test]
fn a_crank_length_is_recovered_from_its_own_path() {
    let m = Mechanism::from_dsl(FOUR_BAR).unwrap();
    let targets: Vec<[f64; 2]> = (0..36)
        .step_by(3)
        .map(|k| {
            let p = m.pose(&[2.0 * PI * k as f64 / 36.0]).unwrap();
            let p = p.point("P").unwrap().pos;
            [p.x, p.y]
        })
        .collect();
    let text = FOUR_BAR.replace("r: 0.1", "r: 0.14");
    let vars = [Variable {
        name: "r".into(),
        lo: 0.06,
        hi: 0.16,
        unit: None,
    }];
    let goal = Objective::Path {
        targets,
        point: "P".into(),
    };
    let best = optimize(
        &text,
        &vars,
        &goal,
        &[Constraint::Grashof],
        settings(120),
        |m, _| Ok(m.loads()),
    )
    .unwrap();
    assert!(best.initial > 1e-4, "{}", best.initial);
    assert!(best.objective < 1e-12, "{best:?}");
    assert!((best.values[0] - 0.1).abs() < 1e-6, "{:?}", best.values);
    assert!(
        best.history.windows(2).all(|w| w[1].1 < w[0].1),
        "the history improves: {:?}",
        best.history
    );
    // The same seed, the same run.
    let again = optimize(
        &text,
        &vars,
        &goal,
        &[Constraint::Grashof],
        settings(120),
        |m, _| Ok(m.loads()),
    )
    .unwrap();
    assert_eq!(again, best);
}

/// The engine at 3000 rpm (inertia only): its rod length and offset varied to lower the
/// peak driver torque; the written file loads, and its peak recomputed here equals the
/// reported optimum.
#[test]
fn the_engines_peak_driver_torque_is_lowered() {
    let text = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/examples/mech/engine.mech"
    ))
    .unwrap();
    let mm = mech::units::lookup("mm");
    let vars = [
        Variable {
            name: "l".into(),
            lo: 0.12,
            hi: 0.18,
            unit: mm,
        },
        Variable {
            name: "e".into(),
            lo: -0.01,
            hi: 0.01,
            unit: mm,
        },
    ];
    let s = Settings {
        speed: 3000.0 * PI / 30.0,
        period: 4.0 * PI,
        steps: 72,
        evaluations: 80,
        seed: 3,
    };
    let best = optimize(&text, &vars, &Objective::PeakDriver, &[], s, |m, _| {
        Ok(m.loads())
    })
    .unwrap();
    assert!(
        best.objective < 0.99 * best.initial,
        "{} → {}",
        best.initial,
        best.objective
    );
    let m = Mechanism::from_dsl(&best.text).unwrap();
    let peak = (0..72)
        .map(|k| {
            let q = 4.0 * PI * k as f64 / 72.0;
            let motion = m.kinematics(&[q], &[s.speed], &[0.0]).unwrap();
            m.kinetostatics(&motion, &m.loads()).unwrap().driver[0].abs()
        })
        .fold(0.0, f64::max);
    assert!(
        (peak - best.objective).abs() < 1e-9 * peak,
        "{peak} vs {}",
        best.objective
    );
    assert!(
        best.text.contains("l: ") && best.text.contains(" mm,"),
        "written with the unit"
    );
}

/// The `flywheel` objective of the engine under a gas force interpolated linearly in a
/// table with a row every degree of its 4π cycle (a kink at each row): its value for the
/// file as given equals Wittenbauer's inertia of a cycle tabulated at the default 1e-13
/// tolerance to 1e-6 of itself (the objective's quadratures run at `FLYWHEEL_RTOL`), and
/// the search does not end above it.
#[test]
fn the_flywheel_objective_is_the_cycles_inertia() {
    use mech::design::optimize::FLYWHEEL_RTOL;
    use mech::dynamics::flywheel::Cycle;
    let text = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/examples/mech/engine.mech"
    ))
    .unwrap();
    // A compression-then-expansion pressure shape, sampled every degree.
    let rows: Vec<f64> = (0..=720)
        .map(|k| {
            let t = k as f64 * PI / 180.0;
            -4000.0 * (-((t - 2.0 * PI) / 0.6).powi(2)).exp() - 300.0 * (t / 2.0).cos()
        })
        .collect();
    let gas = move |q: f64| {
        let x = q.rem_euclid(4.0 * PI) * 180.0 / PI;
        let k = (x.floor() as usize).min(719);
        let f = x - k as f64;
        rows[k] * (1.0 - f) + rows[k + 1] * f
    };
    let loads = |m: &Mechanism, q: f64| {
        let mut l = m.loads();
        assert!(
            l.set_by_name("gas", &[gas(q), 0.0]),
            "the engine has a load `gas`"
        );
        Ok(l)
    };
    let speed = 3000.0 * PI / 30.0;
    let vars = [Variable {
        name: "l".into(),
        lo: 0.12,
        hi: 0.18,
        unit: mech::units::lookup("mm"),
    }];
    let s = Settings {
        speed,
        period: 4.0 * PI,
        steps: 72,
        evaluations: 20,
        seed: 1,
    };
    let goal = Objective::Flywheel { irregularity: 0.02 };
    let best = optimize(&text, &vars, &goal, &[], s, loads).unwrap();
    let m = Mechanism::from_dsl(&text).unwrap();
    let (cycle, _) = Cycle::of(&m, 4.0 * PI, |q| loads(&m, q))
        .unwrap()
        .balanced();
    let exact = cycle.wittenbauer(speed, 0.02).unwrap().inertia;
    assert!(FLYWHEEL_RTOL > 1e-13);
    assert!(
        (best.initial - exact).abs() < 1e-6 * exact,
        "{} vs {exact}",
        best.initial
    );
    assert!(
        best.objective <= best.initial,
        "{} → {}",
        best.initial,
        best.objective
    );
}

#[test]
fn bad_input_and_a_binding_constraint_are_named() {
    let vars = |name: &str, lo: f64, hi: f64| {
        vec![Variable {
            name: name.into(),
            lo,
            hi,
            unit: None,
        }]
    };
    let run = |v: &[Variable], c: &[Constraint]| {
        optimize(
            FOUR_BAR,
            v,
            &Objective::RmsShaking,
            c,
            settings(40),
            |m, _| Ok(m.loads()),
        )
    };
    let e = run(&vars("q", 0.0, 1.0), &[]).unwrap_err().to_string();
    assert!(e.contains("--vary q: no such number"), "{e}");
    let e = run(&vars("r", 0.2, 0.1), &[]).unwrap_err().to_string();
    assert!(e.contains("LO < HI"), "{e}");
    let e = run(
        &vars("r", 0.06, 0.12),
        &[Constraint::Transmission(89.9f64.to_radians())],
    )
    .unwrap_err()
    .to_string();
    assert!(e.contains("transmission >= 89.9"), "{e}");
    let ok = run(&vars("links.coupler.mass", 0.2, 2.0), &[]).unwrap();
    assert!(
        (ok.values[0] - 0.2).abs() < 1e-6,
        "the lightest coupler shakes least: {:?}",
        ok.values
    );
}
