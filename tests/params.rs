//! Run-time parameters (`from_params`) against the terms fixed by the declaration
//! (README, "Run-time parameters"): masses, inertias, cgs and gravity changed at run time
//! are honoured alike by d'Alembert (`kinetostatics`), virtual power (`driver_action`),
//! Zhukovski (`reduced`, `reduced_moment`) and the energies, including on a link declared
//! `mass: 0.0`; a mass or inertia given to a link declared without a term for it is
//! refused with a message that names the link and the fix.

use crate::measure::within;
use mech::prelude::*;

type V = Vector2<f64>;

mechanism! {
    /// Crank-rocker four-bar; the coupler is declared `mass: 0.0` so that its mass can be
    /// given at run time.
    pub struct FourBar {
        gravity: (0.0, -9.81),
        ground { O2: (0.0, 0.0), O4: (0.3, 0.0) },
        link crank { points { O2, A: (0.0, 0.1) }, mass: 0.5, inertia: 1e-3, cg: (0.0, 0.05) },
        link coupler { points { A, B: (0.25, 0.25), P: (0.1, 0.2) }, mass: 0.0, cg: (0.12, 0.17) },
        link rocker { points { O4, B }, mass: 0.8, inertia: 3e-3, cg: (0.28, 0.12) },
        joints {
            O2: revolute(ground, crank),
            A: revolute(crank, coupler),
            B: revolute(coupler, rocker),
            O4: revolute(ground, rocker),
        },
        input: O2,
        loads { tool: force on coupler at P, resist: torque on rocker },
    }
}

mechanism! {
    /// The same four-bar without gravity, its coupler declared without `mass` (massless by
    /// structure) and its rocker with `inertia` alone.
    pub struct Bare {
        ground { O2: (0.0, 0.0), O4: (0.3, 0.0) },
        link crank { points { O2, A: (0.0, 0.1) }, mass: 0.5, inertia: 1e-3, cg: (0.0, 0.05) },
        link coupler { points { A, B: (0.25, 0.25), P: (0.1, 0.2) } },
        link rocker { points { O4, B }, inertia: 3e-3 },
        joints {
            O2: revolute(ground, crank),
            A: revolute(crank, coupler),
            B: revolute(coupler, rocker),
            O4: revolute(ground, rocker),
        },
        input: O2,
        loads { tool: force on coupler at P, resist: torque on rocker },
    }
}

mechanism! {
    /// Offset slider-crank with gravity; the piston is declared `mass: 0.0`.
    pub struct SliderCrank {
        gravity: (0.0, -9.81),
        ground { O2: (0.0, 0.0) },
        link crank { points { O2, A: (0.038302, 0.032139) }, mass: 1.2, inertia: 2.1e-3, cg: (0.0089, 0.0127) },
        link rod { points { A, B: (0.237285, 0.012) }, mass: 2.4, inertia: 9.5e-3, cg: (0.1030, 0.0256) },
        link piston { points { B }, mass: 0.0, cg: (0.237285, 0.012) },
        joints {
            O2: revolute(ground, crank),
            A: revolute(crank, rod),
            B: revolute(rod, piston),
            guide: prismatic(ground, piston) at B along (1.0, 0.0),
        },
        input: O2,
        loads { gas: force on piston at B, load: torque on crank },
    }
}

/// The routes compared at one (q, q̇, q̈).
#[derive(Debug)]
struct Routes {
    /// d'Alembert: `kinetostatics(..).driver`, N·m.
    dalembert: f64,
    /// Virtual power: `driver_action`, N·m.
    virtual_power: f64,
    /// Zhukovski: I* q̈ + ½ dI*/dq q̇² − M*, N·m.
    zhukovski: f64,
    /// Σ T of `link_kinetic_energies`, J.
    kinetic: f64,
    /// ½ I* q̇², J.
    reduced_kinetic: f64,
}

#[track_caller]
fn close(what: &str, a: f64, b: f64, scale: f64, tol: f64) {
    assert!(
        within((a - b).abs(), tol * scale),
        "{what}: {a:e} vs {b:e} (difference {:e}, scale {scale:e})",
        a - b
    );
}

/// The configurations: q over a whole turn, q̇ and q̈ of both signs and zero.
fn configurations() -> Vec<(f64, f64, f64)> {
    let mut out = Vec::new();
    for i in 0..24 {
        let q = -3.0 + 0.26 * i as f64;
        for (qd, qdd) in [
            (1.0, 0.0),
            (7.5, -40.0),
            (-3.0, 120.0),
            (0.0, 25.0),
            (12.0, 3.0),
        ] {
            out.push((q, qd, qdd));
        }
    }
    out
}

macro_rules! routes {
    ($m:expr, $loads:expr, $q:expr, $qd:expr, $qdd:expr) => {{
        let (m, loads, q, qd, qdd) = (&$m, &$loads, $q, $qd, $qdd);
        let motion = m.kinematics(q, qd, qdd).unwrap();
        let r = m.reduced(q).unwrap();
        let ms = m.reduced_moment(q, loads).unwrap();
        let mut t = [0.0; 4];
        Machine::link_kinetic_energies(m, &motion, &mut t);
        Routes {
            dalembert: m.kinetostatics(&motion, loads).unwrap().driver,
            virtual_power: m.driver_action(&motion, loads).unwrap(),
            zhukovski: r.inertia * qdd + 0.5 * r.inertia_derivative * qd * qd - ms,
            kinetic: t.iter().sum(),
            reduced_kinetic: 0.5 * r.inertia * qd * qd,
        }
    }};
}

/// The three routes agree to 5e-12 of the largest term, and Σ T = ½ I* q̇² to 5e-14.
fn check_routes(ctx: &str, r: &Routes) {
    let scale = r
        .dalembert
        .abs()
        .max(r.virtual_power.abs())
        .max(r.zhukovski.abs())
        .max(1e-9);
    close(
        &format!("{ctx}: virtual power vs d'Alembert"),
        r.virtual_power,
        r.dalembert,
        scale,
        2e-12, // measured worst 4.0e-14 (be05608); 100×
    );
    close(
        &format!("{ctx}: Zhukovski vs d'Alembert"),
        r.zhukovski,
        r.dalembert,
        scale,
        5e-12, // measured worst 7.3e-14 (be05608); 100×
    );
    close(
        &format!("{ctx}: Σ T vs ½ I* q̇²"),
        r.kinetic,
        r.reduced_kinetic,
        r.kinetic.abs().max(1e-12),
        5e-14, // measured worst 5.5e-16 (be05608); 100×
    );
}

/// Per link (mass, inertia, cg motion, ω, α): Σ (m v_G·a_G + I ω α), the exact dT/dt.
fn kinetic_rate(links: &[(f64, f64, &LinkMotion)]) -> f64 {
    links
        .iter()
        .map(|(m, i, l)| m * l.cg_vel.dot(&l.cg_acc) + i * l.omega * l.alpha)
        .sum()
}

/// Σ T along the motion through (q, q̇, q̈) at constant q̈, at time t.
fn kinetic_at<M: Machine>(m: &M, q: f64, qd: f64, qdd: f64, t: f64) -> f64 {
    let motion = m
        .motion(&[q + qd * t + 0.5 * qdd * t * t], &[qd + qdd * t], &[qdd])
        .unwrap();
    let mut e = vec![0.0; m.links()];
    m.link_kinetic_energies(&motion, &mut e);
    e.iter().sum()
}

/// The derivative at t = 0 of `f` by the five-point central difference, step 1e-4 s
/// (truncation error O(h⁴)).
fn rate(f: impl Fn(f64) -> f64) -> f64 {
    let h = 1e-4;
    (-f(2.0 * h) + 8.0 * f(h) - 8.0 * f(-h) + f(-2.0 * h)) / (12.0 * h)
}

/// The power balance driver·q̇ + P(loads) + P(gravity) = dT/dt, exactly (5e-13) and by
/// finite differences in time along the motion (2e-9); and −dV/dt = P(gravity) by finite
/// differences (1e-9).
fn check_power<M: Machine>(
    ctx: &str,
    m: &M,
    q: f64,
    qd: f64,
    qdd: f64,
    input: f64,
    loads_power: f64,
    gravity_power: f64,
    exact: f64,
) {
    let lhs = input + loads_power + gravity_power;
    let scale = input
        .abs()
        .max(loads_power.abs())
        .max(gravity_power.abs())
        .max(exact.abs())
        .max(1e-9);
    close(
        &format!("{ctx}: power balance (exact dT/dt)"),
        lhs,
        exact,
        scale,
        5e-13, // measured worst 8.2e-15 (be05608); 100×
    );
    let v = |t: f64| {
        m.potential_energy(
            &m.motion(&[q + qd * t + 0.5 * qdd * t * t], &[qd + qdd * t], &[qdd])
                .unwrap(),
        )
    };
    // The differences round off to ε |E| / h: scale them by the energies per second too.
    let fd_scale = scale.max((kinetic_at(m, q, qd, qdd, 0.0).abs() + v(0.0).abs()) / 1.0);
    close(
        &format!("{ctx}: power balance (finite-difference dT/dt)"),
        lhs,
        rate(|t| kinetic_at(m, q, qd, qdd, t)),
        fd_scale,
        2e-9, // measured worst 4.7e-11 (be05608); 100×
    );
    close(
        &format!("{ctx}: −dV/dt vs power of gravity"),
        -rate(v),
        gravity_power,
        fd_scale,
        1e-9, // measured worst 1.2e-11 (be05608); 100×
    );
}

fn four_bar_params() -> FourBarParams {
    let mut p = FourBarParams::default();
    p.links.crank.mass = 0.7;
    p.links.crank.inertia = 2e-3;
    p.links.crank.cg = V::new(0.01, 0.04);
    // Declared `mass: 0.0`: given a mass and an inertia at run time.
    p.links.coupler.mass = 1.3;
    p.links.coupler.inertia = 6e-3;
    p.links.coupler.cg = V::new(0.13, 0.18);
    p.links.rocker.mass = 0.4;
    p.links.rocker.inertia = 1e-3;
    p.links.rocker.cg = V::new(0.29, 0.1);
    p.gravity = V::new(1.5, -9.7);
    p
}

#[test]
fn four_bar_routes_and_power_use_the_run_time_numbers() {
    let p = four_bar_params();
    let m = FourBar::from_params(p.clone()).unwrap();
    assert_eq!(m.params(), &p);
    let loads = FourBarLoads {
        tool: V::new(3.0, -2.0),
        resist: -0.4,
    };
    for (q, qd, qdd) in configurations() {
        let ctx = format!("four-bar at q = {q}, q̇ = {qd}, q̈ = {qdd}");
        let r = routes!(m, loads, q, qd, qdd);
        check_routes(&ctx, &r);
        let mo = m.kinematics(q, qd, qdd).unwrap();
        let l = &mo.links;
        let masses = [
            (p.links.crank.mass, p.links.crank.inertia, &l.crank),
            (p.links.coupler.mass, p.links.coupler.inertia, &l.coupler),
            (p.links.rocker.mass, p.links.rocker.inertia, &l.rocker),
        ];
        let loads_power = loads.tool.dot(&mo.points.P.vel) + loads.resist * l.rocker.omega;
        let gravity_power: f64 = masses
            .iter()
            .map(|(mass, _, lm)| mass * p.gravity.dot(&lm.cg_vel))
            .sum();
        check_power(
            &ctx,
            &m,
            q,
            qd,
            qdd,
            r.dalembert * qd,
            loads_power,
            gravity_power,
            kinetic_rate(&masses),
        );
    }
}

#[test]
fn a_link_declared_mass_zero_counts_when_given_mass() {
    // With the coupler's run-time mass, every route moves by the same amount.
    let heavy = FourBar::from_params(four_bar_params()).unwrap();
    let mut p = four_bar_params();
    p.links.coupler.mass = 0.0;
    p.links.coupler.inertia = 0.0;
    let light = FourBar::from_params(p).unwrap();
    let loads = FourBarLoads::default();
    let (a, b) = (
        routes!(heavy, loads, 1.0, 1.0, 0.0),
        routes!(light, loads, 1.0, 1.0, 0.0),
    );
    let diff = a.dalembert - b.dalembert;
    assert!(
        diff.abs() > 1e-2 * a.dalembert.abs(),
        "the coupler's mass must change the driver: {a:?} / {b:?}"
    );
    close(
        "virtual power difference",
        a.virtual_power - b.virtual_power,
        diff,
        diff.abs(),
        2e-14, // measured worst 2.5e-16 (be05608); 100×
    );
    close(
        "Zhukovski difference",
        a.zhukovski - b.zhukovski,
        diff,
        diff.abs(),
        2e-14, // measured worst 2.5e-16 (be05608); 100×
    );
    assert!(a.kinetic > b.kinetic);
}

#[test]
fn slider_crank_with_gravity_routes_and_power_use_the_run_time_numbers() {
    let mut p = SliderCrankParams::default();
    p.links.crank.mass = 1.5;
    p.links.crank.cg = V::new(0.012, 0.01);
    p.links.rod.inertia = 1.1e-2;
    p.links.rod.cg = V::new(0.11, 0.03);
    // Declared `mass: 0.0`: given mass and inertia at run time, gravity included.
    p.links.piston.mass = 1.7;
    p.links.piston.inertia = 4e-4;
    p.gravity = V::new(-0.8, -9.81);
    let m = SliderCrank::from_params(p.clone()).unwrap();
    let loads = SliderCrankLoads {
        gas: V::new(-250.0, 15.0),
        load: 1.5,
    };
    for (q, qd, qdd) in configurations() {
        let ctx = format!("slider-crank at q = {q}, q̇ = {qd}, q̈ = {qdd}");
        let r = routes!(m, loads, q, qd, qdd);
        check_routes(&ctx, &r);
        let mo = m.kinematics(q, qd, qdd).unwrap();
        let l = &mo.links;
        let masses = [
            (p.links.crank.mass, p.links.crank.inertia, &l.crank),
            (p.links.rod.mass, p.links.rod.inertia, &l.rod),
            (p.links.piston.mass, p.links.piston.inertia, &l.piston),
        ];
        let loads_power = loads.gas.dot(&mo.points.B.vel) + loads.load * l.crank.omega;
        let gravity_power: f64 = masses
            .iter()
            .map(|(mass, _, lm)| mass * p.gravity.dot(&lm.cg_vel))
            .sum();
        check_power(
            &ctx,
            &m,
            q,
            qd,
            qdd,
            r.dalembert * qd,
            loads_power,
            gravity_power,
            kinetic_rate(&masses),
        );
    }
}

#[test]
fn inertia_only_link_varies_its_inertia_on_every_route() {
    let mut p = BareParams::default();
    p.links.rocker.inertia = 7e-3;
    p.links.crank.mass = 0.9;
    let m = Bare::from_params(p.clone()).unwrap();
    let loads = BareLoads {
        tool: V::new(-1.0, 4.0),
        resist: 0.3,
    };
    for (q, qd, qdd) in configurations() {
        let ctx = format!("bare four-bar at q = {q}, q̇ = {qd}, q̈ = {qdd}");
        let r = routes!(m, loads, q, qd, qdd);
        check_routes(&ctx, &r);
        let mo = m.kinematics(q, qd, qdd).unwrap();
        let l = &mo.links;
        let masses = [
            (p.links.crank.mass, p.links.crank.inertia, &l.crank),
            (0.0, p.links.rocker.inertia, &l.rocker),
        ];
        let loads_power = loads.tool.dot(&mo.points.P.vel) + loads.resist * l.rocker.omega;
        check_power(
            &ctx,
            &m,
            q,
            qd,
            qdd,
            r.dalembert * qd,
            loads_power,
            0.0,
            kinetic_rate(&masses),
        );
        assert_eq!(m.potential_energy(&mo), 0.0);
    }
}

fn refused(r: Result<Bare, MechError>, parts: &[&str]) {
    match r {
        Err(MechError::InvalidInput(msg)) => {
            for part in parts {
                assert!(msg.contains(part), "expected “{part}” in: {msg}");
            }
        }
        other => panic!(
            "expected InvalidInput, got {:?}",
            other.map(|_| "a mechanism")
        ),
    }
}

#[test]
fn mass_on_a_link_declared_without_mass_is_refused() {
    // The case of the report: mass 1.0 and inertia 5e-3 on a coupler declared without mass.
    let mut p = BareParams::default();
    p.links.coupler.mass = 1.0;
    p.links.coupler.inertia = 5e-3;
    refused(
        Bare::from_params(p),
        &[
            "link `coupler`",
            "without `mass`",
            "mass 1 kg",
            "inertia 0.005 kg·m²",
            "declare `mass: 0.0` on link `coupler` in `mechanism!` to vary its mass at run time",
        ],
    );
    // Inertia alone is refused too: the massless coupler has no inertia moment.
    let mut p = BareParams::default();
    p.links.coupler.inertia = 5e-3;
    refused(
        Bare::from_params(p),
        &["link `coupler`", "inertia 0.005 kg·m²"],
    );
    // A mass on the rocker, declared with `inertia` alone.
    let mut p = BareParams::default();
    p.links.rocker.mass = 0.2;
    refused(
        Bare::from_params(p),
        &[
            "link `rocker`",
            "with `inertia` but without `mass`",
            "mass 0.2 kg",
            "declare `mass: 0.0` on link `rocker`",
        ],
    );
    // A cg is free on a massless link (it is unused), and zeros are the declaration.
    let mut p = BareParams::default();
    p.links.coupler.cg = V::new(0.5, 0.5);
    p.links.rocker.inertia = 0.0;
    assert!(Bare::from_params(p).is_ok());
}
