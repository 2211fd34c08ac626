//! The flywheel as a designer asks for it (`docs/theory.md` §7): the maximum fluctuation
//! of energy ΔE and the coefficient of fluctuation of speed of a given flywheel without
//! choosing an ε, a cycle with defaults, balancing without consuming the cycle, and a
//! flywheel set through the run-time parameters so that the direct problem of the engine
//! with its flywheel is one call. References: the engine's 25-digit table
//! (`tests/data/engine.flywheel.json`, mpmath), the energy balance, the three routes to
//! the driver torque.

use crate::engine;
use crate::measure::within;

use mech::flywheel::Cycle;
use mech::prelude::*;
use mech::Mechanism;

fn reference() -> serde_json::Value {
    serde_json::from_str(include_str!("data/engine.flywheel.json")).unwrap()
}

fn gas_cycle(eng: &engine::Engine) -> Cycle<'_, engine::Engine> {
    Cycle::builder(eng, engine::PERIOD, |q| engine::gas_loads(eng, q))
        .start(engine::Q_TDC)
        .breakpoints(&engine::breakpoints())
        .build()
        .unwrap()
}

#[track_caller]
fn close(what: &str, a: f64, b: f64, tol: f64) {
    assert!(
        within((a - b).abs(), tol * b.abs().max(1e-300)),
        "{what}: {a} against {b} ({:.2e})",
        (a - b).abs() / b.abs()
    );
}

#[test]
fn the_fluctuation_of_energy_is_the_reference_one() {
    let eng = engine::Engine::new();
    let mut cycle = gas_cycle(&eng);
    let t = cycle.balance();
    let r = &reference()["results"];
    close(
        "balancing torque",
        t,
        r["balancing_torque"].as_f64().unwrap(),
        2e-14, // measured worst 3.7e-16 (be05608); 100×
    );
    let f = cycle.fluctuation().unwrap();
    let (smax, smin) = (r["s_max"].as_f64().unwrap(), r["s_min"].as_f64().unwrap());
    // measured worst 1.3e-16 (be05608); 100×
    close("ΔE", f.energy, smax - smin, 1e-14);
    // measured worst 6.8e-16 (be05608); 100×
    close("S_max", f.s_max, smax, 5e-14);
    // An extreme's position is determined to about √ε of the flat function.
    // measured worst 1.8e-9 (be05608); 100×
    close("q(S_min)", f.q_s_min, r["q_s_min"].as_f64().unwrap(), 1e-7);
    // Balancing again adds nothing: the cycle was not consumed and stays periodic.
    let again = cycle.balance();
    // measured worst 0 (be05608); exact; a few ulps
    assert!(within(again.abs(), 1e-15 * t.abs()), "{again}");
    assert!(cycle.check_periodic().is_ok());
    close(
        "ΔE after a second balance",
        cycle.fluctuation().unwrap().energy,
        f.energy,
        1e-15, // measured worst 0 (be05608); exact; a few ulps
    );
}

#[test]
fn the_speed_fluctuation_of_a_flywheel_round_trips_wittenbauer() {
    let eng = engine::Engine::new();
    let (cycle, _) = gas_cycle(&eng).balanced();
    let w = engine::OMEGA_MEAN;
    for eps in [0.1, 0.02, 0.005] {
        let fw = cycle.wittenbauer(w, eps).unwrap();
        close(
            "δ of Wittenbauer's flywheel",
            cycle.speed_fluctuation(w, fw.inertia).unwrap(),
            eps,
            5e-13, // measured worst 5.4e-15 (be05608); 100×
        );
    }
    // A large flywheel: δ → ΔE' / (I ω_a²), with ΔE' the range of S − ½ I* ω_a² (the
    // machine's own kinetic energy varies with I*: at 3000 rpm that is 6 % of ΔE here).
    let hi = cycle
        .extreme(|s, i| s - 0.5 * i * w * w, true)
        .unwrap()
        .value;
    let lo = cycle
        .extreme(|s, i| s - 0.5 * i * w * w, false)
        .unwrap()
        .value;
    for big in [50.0, 500.0] {
        let delta = cycle.speed_fluctuation(w, big).unwrap();
        let limit = (hi - lo) / (big * w * w);
        assert!(
            within((delta / limit - 1.0).abs(), 2.0 * delta + 1e-6), // measured worst 0.90 of the bound (be05608); an asymptotic bound (first order in δ), not a tolerance
            "I = {big}: {delta} against {limit}"
        );
    }
    let de = cycle.fluctuation().unwrap().energy;
    assert!(
        ((hi - lo) / de - 1.0).abs() > 0.01,
        "ΔE' differs from ΔE at this speed"
    );
}

#[test]
fn a_cycle_with_defaults_starts_at_zero_with_no_driver() {
    let eng = engine::Engine::new();
    let a = Cycle::of(&eng, engine::PERIOD, |q| engine::gas_loads(&eng, q)).unwrap();
    let b = Cycle::new(
        &eng,
        0.0,
        engine::PERIOD,
        &[],
        |q| engine::gas_loads(&eng, q),
        |_| 0.0,
    )
    .unwrap();
    assert_eq!(a.start(), 0.0);
    assert_eq!(a.net_work(), b.net_work());
    assert_eq!(a.driver(1.0), 0.0);
}

/// The engine with a flywheel through its parameters: I* grows by exactly I_f, dI*/dq
/// does not change, the three routes to the driver torque agree, the kinetic energy
/// grows by ½ I_f q̇², and the run-time mechanism agrees.
#[test]
fn a_flywheel_through_the_parameters() {
    let plain = engine::Engine::new();
    let i_f = 0.2048;
    let mut p = plain.params().clone();
    p.links.crank.flywheel = i_f;
    let fly = engine::Engine::from_params(p).unwrap();
    let mut rt = Mechanism::from_rust_source(include_str!("common/engine.rs"), "Engine").unwrap();
    rt.set_param("links.crank.flywheel", &[i_f]).unwrap();
    for k in 0..24 {
        let q = 0.1 + 0.5 * k as f64;
        let (a, b) = (plain.reduced(q).unwrap(), fly.reduced(q).unwrap());
        // measured worst 1.3e-16 (be05608); 100×
        close("I* + I_f", b.inertia, a.inertia + i_f, 1e-14);
        assert!(
            within(
                (b.inertia_derivative - a.inertia_derivative).abs(),
                1e-15 * b.inertia
            ), // measured worst 0 (be05608); exact; a few ulps
            "dI*/dq"
        );
        close(
            "run-time I*",
            OneDof::reduced(&rt, q).unwrap().inertia,
            b.inertia,
            1e-14, // measured worst 1.3e-16 (be05608); 100×
        );
        let (qd, qdd) = (300.0, -40.0);
        let loads = engine::gas_loads(&fly, q).unwrap();
        let m = fly.kinematics(q, qd, qdd).unwrap();
        let dalembert = fly.kinetostatics(&m, &loads).unwrap().driver;
        let vp = fly.driver_action(&m, &loads).unwrap();
        // Zhukovski: driver = I* q̈ + ½ I*' q̇² − M*.
        let zh = b.inertia * qdd + 0.5 * b.inertia_derivative * qd * qd
            - fly.reduced_moment(q, &loads).unwrap();
        let scale = dalembert.abs().max(i_f * qdd.abs());
        assert!(
            within((vp - dalembert).abs(), 5e-14 * scale)
                && within((zh - dalembert).abs(), 5e-14 * scale), // measured worst 8.7e-16 and 6.5e-16 (be05608); 100×
            "{dalembert} {vp} {zh}"
        );
        // The flywheel's share of the driver torque is I_f q̈.
        let m0 = plain.kinematics(q, qd, qdd).unwrap();
        let d0 = plain.kinetostatics(&m0, &loads).unwrap().driver;
        // measured worst 1.6e-16 (be05608); 100×
        assert!(
            within((dalembert - d0 - i_f * qdd).abs(), 1e-14 * scale),
            "I_f q̈"
        );
        let t = |e: &engine::Engine, m| mech::dynamics::kinetic_energy(e, m);
        close(
            "T + ½ I_f q̇²",
            t(&fly, &m),
            t(&plain, &m0) + 0.5 * i_f * qd * qd,
            1e-14, // measured worst 1.9e-16 (be05608); 100×
        );
    }
    // The direct problem of the engine with its flywheel is one call.
    let qdd = fly
        .acceleration(1.0, 300.0, 50.0, &engine::gas_loads(&fly, 1.0).unwrap())
        .unwrap();
    let r = fly.reduced(1.0).unwrap();
    let m_star = fly
        .reduced_moment(1.0, &engine::gas_loads(&fly, 1.0).unwrap())
        .unwrap();
    close(
        "q̈",
        qdd,
        (50.0 + m_star - 0.5 * r.inertia_derivative * 300.0 * 300.0) / r.inertia,
        1e-15, // measured worst 0 (be05608); exact; a few ulps
    );
}

mechanism! {
    /// A four-bar whose rocker is declared massless.
    pub struct Bare {
        ground { O2: (0.0, 0.0), O4: (0.3, 0.0) },
        link crank { points { O2, A: (0.0, 0.1) }, mass: 0.5, inertia: 1e-3, cg: (0.0, 0.05) },
        link coupler { points { A, B: (0.25, 0.25) }, inertia: 2e-3 },
        link rocker { points { O4, B } },
        joints { O2: revolute(ground, crank), A: revolute(crank, coupler), B: revolute(coupler, rocker), O4: revolute(ground, rocker) },
        input: O2,
        loads { out: torque on rocker },
    }
}

#[test]
fn a_flywheel_on_a_massless_link_is_refused_and_a_negative_one_is_an_error() {
    let mut p = Bare::new().params().clone();
    p.links.rocker.flywheel = 0.1;
    match Bare::from_params(p) {
        Err(MechError::InvalidInput(msg)) => assert!(
            msg.contains("link `rocker`") && msg.contains("a flywheel of 0.1 kg·m²"),
            "{msg}"
        ),
        other => panic!("{other:?}"),
    }
    // On a link declared with inertia only, the flywheel is honoured.
    let mut p = Bare::new().params().clone();
    p.links.coupler.flywheel = 0.1;
    let with = Bare::from_params(p).unwrap();
    close(
        "coupler flywheel in I*",
        with.reduced(0.4).unwrap().inertia - Bare::new().reduced(0.4).unwrap().inertia,
        0.1 * {
            let m = Bare::new().kinematics(0.4, 1.0, 0.0).unwrap();
            m.links.coupler.omega * m.links.coupler.omega
        },
        1e-15, // measured worst 0 (be05608); exact; a few ulps
    );
    let mut p = Bare::new().params().clone();
    p.links.crank.flywheel = -1.0;
    assert!(matches!(
        Bare::from_params(p),
        Err(MechError::Invalid(_)) | Err(MechError::InvalidInput(_))
    ));
    let mut rt = Mechanism::from_rust_source(include_str!("flywheel_designer.rs"), "Bare").unwrap();
    assert!(rt.set_param("links.crank.flywheel", &[-1.0]).is_err());
    assert!(rt.set_param("links.crank.flywheel", &[f64::NAN]).is_err());
}
