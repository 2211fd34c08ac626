//! The direct dynamic problem (mech-core `dynamics` and `ode`) against independent
//! references:
//! - `tests/data/slider_crank.dynamics.json`: trajectories of the slider-crank computed by
//!   `tools/dynamics_reference.py` (mpmath, 50 digits, absolute coordinates, extrapolated
//!   modified-midpoint integration of order 20) — nothing of this crate;
//! - `tests/data/*.truth.json`: the configurations of `tools/reference.py`, for Quinn's
//!   coefficients (link energies from the truth's cg velocities and ω) and for the mass
//!   matrix and velocity terms of Lagrange's equations (truth driver actions);
//! - exact invariants: the energy of conservative machines.

use crate::measure::{within, within_at};
use crate::mechanisms;
use crate::support;

use mech::dynamics::{
    equation_of_motion, lagrange_acceleration, lagrange_equations, mass_matrix, quinn_coefficients,
    total_energy, velocity_terms, EnergyMethod,
};
use mech::ode::{integrate, sample, solve, Dop853, DormandPrince, Event, Rk4, Stats};
use mech::prelude::*;
use mechanisms::*;
use serde_json::Value;
use std::f64::consts::TAU;
use support::*;

// ---------------------------------------------------------------------------------------
// A counting allocator: stepping must not allocate.

use crate::counting;

// ---------------------------------------------------------------------------------------
// The reference trajectories

fn dynamics_reference() -> Value {
    let path = format!(
        "{}/tests/data/slider_crank.dynamics.json",
        env!("CARGO_MANIFEST_DIR")
    );
    serde_json::from_str(&std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{path}: {e}")))
        .unwrap()
}

fn case<'a>(doc: &'a Value, name: &str) -> &'a Value {
    doc["cases"]
        .as_array()
        .unwrap()
        .iter()
        .find(|c| c["name"] == name)
        .unwrap_or_else(|| panic!("no case {name}"))
}

/// (t, q, q̇, q̈) of every sample of a case.
fn samples(c: &Value) -> Vec<[f64; 4]> {
    c["samples"]
        .as_array()
        .unwrap()
        .iter()
        .map(|s| ["t", "q", "qd", "qdd"].map(|k| s[k].as_f64().unwrap()))
        .collect()
}

/// The actions of the reference cases (tools/dynamics_reference.py, `case_actions`).
fn actions(name: &str) -> impl Fn(f64, f64, f64) -> (f64, SliderCrankLoads) {
    let time_and_speed = match name {
        "constant_torque" => false,
        "time_and_speed" => true,
        other => panic!("unknown case {other}"),
    };
    move |t, q, qd| {
        let mut l = SliderCrankLoads::default();
        if time_and_speed {
            l.gas = Vector2::new(-(10.0 + 8.0 * q.cos()), 0.0);
            l.shaft = -0.002 * qd;
            (3.0 + 2.0 * (8.0 * t).sin(), l)
        } else {
            (3.0, l)
        }
    }
}

/// Both relative errors of (q, q̇) against a sample, relative to |q| and |q̇|.
fn rel_err(y: &[f64; 2], s: &[f64; 4]) -> (f64, f64) {
    (
        (y[0] - s[1]).abs() / s[1].abs(),
        (y[1] - s[2]).abs() / s[2].abs(),
    )
}

const CASES: [&str; 2] = ["constant_torque", "time_and_speed"];

/// The equation of motion at the reference states reproduces the reference q̈ (2e-12
/// relative): the right-hand side itself, with these loads, before any integration.
#[test]
fn slider_crank_right_hand_side_matches_reference() {
    let doc = dynamics_reference();
    let m = SliderCrank::new();
    for name in CASES {
        let mut f = equation_of_motion(&m, actions(name));
        for s in samples(case(&doc, name)) {
            let dy = f(s[0], &[s[1], s[2]]).unwrap();
            assert_eq!(dy[0], s[2]);
            assert!(
                within((dy[1] - s[3]).abs(), 2e-12 * s[3].abs().max(1.0)), // measured worst 4.0e-14 (be05608); 100×
                "{name} t = {}: q'' {} vs {}",
                s[0],
                dy[1],
                s[3]
            );
        }
    }
}

/// Time integration of the slider-crank from the reference's start (q0 = 0.3 rad,
/// q̇0 = 20 rad/s) agrees with the 50-digit reference at every sample time (dense output):
/// DOP853 (rtol 1e-13) and Dormand–Prince 5(4) (rtol 1e-12) to 2e-11 relative in q and
/// 1e-9 in q̇; fixed-step RK4 (h = 2e-5 s) to 1e-9 and 2e-8.
#[test]
fn slider_crank_time_integration_matches_reference() {
    let doc = dynamics_reference();
    let m = SliderCrank::new();
    for name in CASES {
        let c = case(&doc, name);
        let s = samples(c);
        let times: Vec<f64> = s.iter().map(|s| s[0]).collect();
        let y0 = [c["q0"].as_f64().unwrap(), c["qd0"].as_f64().unwrap()];
        let mut out = vec![[0.0; 2]; s.len()];
        // (method, tolerance on q, on q̇): measured worst 3.8e-13, 1.3e-11 (DOP853), 2.2e-13, 1.2e-11 (DP5), 1.1e-11, 3.5e-10 (RK4) (be05608); 100×
        for (label, tol, tol_d) in [
            ("dop853", 2e-11, 1e-9),
            ("dp5", 2e-11, 1e-9),
            ("rk4", 1e-9, 2e-8),
        ] {
            let f = equation_of_motion(&m, actions(name));
            let stats = match label {
                "dop853" => sample(&mut Dop853::new(1e-13, 1e-13), f, 0.0, y0, &times, &mut out),
                "dp5" => sample(
                    &mut DormandPrince::new(1e-12, 1e-12),
                    f,
                    0.0,
                    y0,
                    &times,
                    &mut out,
                ),
                _ => sample(&mut Rk4 { h: 2e-5 }, f, 0.0, y0, &times, &mut out),
            }
            .unwrap();
            for (y, s) in out.iter().zip(&s) {
                let (eq, eqd) = rel_err(y, s);
                assert!(
                    within_at(label, eq, tol) && within_at(label, eqd, tol_d),
                    "{name} {label} t = {}: rel. error q {eq:.2e}, q' {eqd:.2e} ({stats:?})",
                    s[0]
                );
            }
        }
    }
}

/// Lagrange's equations of the general G-DOF route, used with G = 1 on the slider-crank,
/// give the same trajectory as Zhukovski's equation of motion (5e-13 relative at the end).
#[test]
fn lagrange_route_equals_zhukovski_route_for_one_dof() {
    let m = SliderCrank::new();
    let act = actions("time_and_speed");
    let zh = integrate(
        &mut Dop853::new(1e-12, 1e-12),
        equation_of_motion(&m, &act),
        0.0,
        [0.3, 20.0],
        0.1,
    )
    .unwrap();
    let lg = integrate(
        &mut Dop853::new(1e-12, 1e-12),
        lagrange_equations(&m, |t, q: &[f64; 1], qd: &[f64; 1]| {
            let (d, l) = act(t, q[0], qd[0]);
            ([d], l)
        }),
        0.0,
        [0.3, 20.0],
        0.1,
    )
    .unwrap();
    for i in 0..2 {
        assert!(
            within((zh.y[i] - lg.y[i]).abs(), 5e-13 * zh.y[i].abs()), // measured worst 5.2e-15 (be05608); 100×
            "{i}: {} vs {}",
            zh.y[i],
            lg.y[i]
        );
    }
}

// ---------------------------------------------------------------------------------------
// The energy method

/// ω(q) and t(q) by the energy theorem (position-only actions: the constant 3 N·m) agree
/// with the reference trajectory at every sample (2e-13 relative in ω, 2e-14 s·(1 + t) in
/// t), and with the time integration stopped by an event at q0 + 2πk (5e-11 relative in
/// ω, 1e-11 in t).
#[test]
fn energy_method_agrees_with_reference_and_time_integration() {
    let doc = dynamics_reference();
    let m = SliderCrank::new();
    let c = case(&doc, "constant_torque");
    let zero = SliderCrankLoads::default();
    let mut em = EnergyMethod::new(&m, 0.0, 0.3, 20.0, |_| (3.0, zero), 1e-12).unwrap();
    for s in samples(c).iter().skip(1) {
        let p = em.advance_to(s[1]).unwrap();
        assert!(
            within((p.omega - s[2]).abs(), 2e-13 * s[2]), // measured worst 2.5e-15 (be05608); 100×
            "omega at q = {}: {} vs {}",
            s[1],
            p.omega,
            s[2]
        );
        assert!(
            within((p.t - s[0]).abs(), 2e-14 * (1.0 + s[0])), // measured worst 2.3e-16 (be05608); 100×
            "t at q = {}: {} vs {}",
            s[1],
            p.t,
            s[0]
        );
    }

    let mut em = EnergyMethod::new(&m, 0.0, 0.3, 20.0, |_| (3.0, zero), 1e-12).unwrap();
    for k in [1.0, 5.0, 12.0] {
        let target = 0.3 + TAU * k;
        let mut g = |_: f64, y: &[f64; 2]| y[0] - target;
        let mut ev = Event {
            g: &mut g,
            direction: 1,
            t_tol: 1e-15,
        };
        let r = solve(
            &mut Dop853::new(1e-13, 1e-13),
            equation_of_motion(&m, actions("constant_torque")),
            0.0,
            [0.3, 20.0],
            10.0,
            Some(&mut ev),
            None,
        )
        .unwrap();
        assert!(r.event);
        let p = em.advance_to(target).unwrap();
        assert!(
            within((p.omega - r.y[1]).abs(), 5e-11 * r.y[1]), // measured worst 6.0e-13 (be05608); 100×
            "k = {k}: omega {} vs {}",
            p.omega,
            r.y[1]
        );
        assert!(
            within((p.t - r.t).abs(), 1e-11 * r.t), // measured worst 1.1e-13 (be05608); 100×
            "k = {k}: t {} vs {}",
            p.t,
            r.t
        );
        // Work of the constant torque plus the (conservative) gravity: W = 3·2πk − ΔV.
        let dv = total_energy(&m, &[target], &[0.0]).unwrap()
            - total_energy(&m, &[0.3], &[0.0]).unwrap();
        assert!(
            within((p.work - (3.0 * TAU * k - dv)).abs(), 2e-14 * p.work.abs()), // measured worst 2.5e-16 (be05608); 100×
            "work {} vs {}",
            p.work,
            3.0 * TAU * k - dv
        );
    }
}

/// Against a constant resisting torque the machine stops: the energy method reports
/// `Stall` where ω reaches 0, at the position where the time integration's q̇ crosses
/// zero (2e-11 rad).
#[test]
fn energy_method_reports_the_stall() {
    let m = SliderCrank::new();
    let zero = SliderCrankLoads::default();
    let mut em = EnergyMethod::new(&m, 0.0, 0.3, 20.0, |_| (-1.0, zero), 1e-12).unwrap();
    let stall = match em.advance_to(5.0) {
        Err(MechError::Stall { q }) => q,
        other => panic!("expected a stall, got {other:?}"),
    };
    let mut g = |_: f64, y: &[f64; 2]| y[1];
    let mut ev = Event {
        g: &mut g,
        direction: -1,
        t_tol: 1e-14,
    };
    let r = solve(
        &mut Dop853::new(1e-13, 1e-13),
        equation_of_motion(&m, |_, _, _| (-1.0, zero)),
        0.0,
        [0.3, 20.0],
        10.0,
        Some(&mut ev),
        None,
    )
    .unwrap();
    assert!(r.event && r.y[0] < 5.0);
    assert!(
        within((stall - r.y[0]).abs(), 2e-11), // measured worst 3.5e-13 (be05608); 100×
        "stall at {stall}, time integration stops at {}",
        r.y[0]
    );
}

/// From rest (ω0 = 0) the energy method moves in the direction of the moment and its
/// t(q), ω(q) agree with the time integration from rest (2e-11 relative in t, 1e-12 in ω).
#[test]
fn energy_method_from_rest() {
    let m = SliderCrank::new();
    let zero = SliderCrankLoads::default();
    let mut em = EnergyMethod::new(&m, 0.0, 0.3, 0.0, |_| (3.0, zero), 1e-12).unwrap();
    for target in [0.31, 0.8, 4.0] {
        let p = em.advance_to(target).unwrap();
        let mut g = |_: f64, y: &[f64; 2]| y[0] - target;
        let mut ev = Event {
            g: &mut g,
            direction: 1,
            t_tol: 1e-15,
        };
        let r = solve(
            &mut Dop853::new(1e-13, 1e-13),
            equation_of_motion(&m, |_, _, _| (3.0, zero)),
            0.0,
            [0.3, 0.0],
            10.0,
            Some(&mut ev),
            None,
        )
        .unwrap();
        assert!(
            within((p.omega - r.y[1]).abs(), 1e-12 * r.y[1]), // measured worst 1.8e-14 (be05608); 100×
            "q = {target}: omega {} vs {}",
            p.omega,
            r.y[1]
        );
        assert!(
            within((p.t - r.t).abs(), 2e-11 * r.t), // measured worst 4.6e-13 (be05608); 100×
            "q = {target}: t {} vs {}",
            p.t,
            r.t
        );
    }
}

// ---------------------------------------------------------------------------------------
// Quinn

fn link_data(file: &str) -> Vec<(String, f64, f64)> {
    let path = format!(
        "{}/tests/data/{file}.mechanism.json",
        env!("CARGO_MANIFEST_DIR")
    );
    let d: Value = serde_json::from_str(&std::fs::read_to_string(&path).unwrap()).unwrap();
    let num = |v: &Value| v.get("float").and_then(|f| f.as_f64()).unwrap_or(0.0);
    d["links"]
        .as_array()
        .unwrap()
        .iter()
        .map(|l| {
            (
                l["name"].as_str().unwrap().to_string(),
                l.get("mass").map_or(0.0, num),
                l.get("inertia").map_or(0.0, num),
            )
        })
        .collect()
}

macro_rules! quinn_check {
    ($ty:ident, $file:literal) => {{
        let m = $ty::new();
        let links = link_data($file);
        let t = truth($file);
        let mut eps = vec![0.0; m.links()];
        for c in t["configs"].as_array().unwrap() {
            let q = c["q"].as_f64().unwrap();
            quinn_coefficients(&m, q, &mut eps).unwrap();
            // T_j from the truth's velocities: ½ m |v_G|² + ½ I ω².
            let tj: Vec<f64> = $ty::LINK_NAMES
                .iter()
                .map(|name| {
                    let (_, mass, inertia) = links.iter().find(|l| l.0 == *name).unwrap();
                    let l = &c["links"][*name];
                    let v = nums(&l["cg"]["vel"]);
                    let w = l["omega"].as_f64().unwrap();
                    0.5 * mass * (v[0] * v[0] + v[1] * v[1]) + 0.5 * inertia * w * w
                })
                .collect();
            let total: f64 = tj.iter().sum();
            // The same ratio from Zhukovski's I*: T = ½ I* q̇².
            let qd = c["qd"].as_f64().unwrap();
            let i_star = c["zhukovski"]["I_star"].as_f64().unwrap();
            assert!(
                within_at("T", (total - 0.5 * i_star * qd * qd).abs(), 2e-14 * total), // measured worst 4.0e-16 (be05608); 100×
                "{}: T vs ½ I* q̇²",
                $file
            );
            assert_eq!(eps[0], 0.0);
            for (j, name) in $ty::LINK_NAMES.iter().enumerate() {
                assert!(
                    within_at("eps_j", (eps[j + 1] - tj[j] / total).abs(), 2e-14), // measured worst 2.8e-16 (be05608); 100×
                    "{} q = {q}: eps[{name}] = {} vs {}",
                    $file,
                    eps[j + 1],
                    tj[j] / total
                );
            }
            assert!(
                within_at("sum", (eps.iter().sum::<f64>() - 1.0).abs(), 1e-14), // measured worst 3.3e-16 (be05608); 100×
                "{}: sum {}",
                $file,
                eps.iter().sum::<f64>()
            );
        }
    }};
}

/// Quinn's coefficients ε_j = T_j / T sum to 1 and equal I*_j / I* computed from the
/// truth tables' cg velocities and angular velocities (2e-14) for every one-DOF drawing.
#[test]
fn quinn_coefficients_match_truth() {
    quinn_check!(SliderCrank, "slider_crank");
    quinn_check!(FourBar, "four_bar");
    quinn_check!(QuickReturn, "quick_return");
    quinn_check!(Watt2, "watt2");
    quinn_check!(Stephenson3, "stephenson3");
    quinn_check!(ScotchYoke, "scotch_yoke");
    quinn_check!(HydraulicLever, "hydraulic_lever");
    quinn_check!(PublicSliderCrank, "public_slider_crank");
    quinn_check!(PublicFourBar, "public_four_bar");
}

// ---------------------------------------------------------------------------------------
// Several DOF

/// The five-bar's mass matrix and velocity terms reproduce the truth table's driver
/// torques: M(q) q̈ + b(q, q̇) = τ (1e-13 relative to the largest torque); M is symmetric
/// positive definite; and q̈ = M⁻¹(τ − b) recovers the truth's q̈ (5e-12). For the
/// one-DOF slider-crank, M = [I*] and b = ½ dI*/dq q̇² − M*.
#[test]
fn mass_matrix_and_velocity_terms_match_truth() {
    let m = FiveBar::new();
    let t = truth("five_bar");
    let mut loads = FiveBarLoads::default();
    for (name, l) in t["loads"].as_object().unwrap() {
        assert!(loads.set_by_name(name, &nums(&l["value"])));
    }
    for c in t["configs"].as_array().unwrap() {
        let (q, qd, qdd) = (nums(&c["q"]), nums(&c["qd"]), nums(&c["qdd"]));
        let (q, qd, qdd) = ([q[0], q[1]], [qd[0], qd[1]], [qdd[0], qdd[1]]);
        let tau: Vec<f64> = c["drivers"]
            .as_array()
            .unwrap()
            .iter()
            .map(|d| d["value"].as_f64().unwrap())
            .collect();
        let mm = mass_matrix(&m, &q).unwrap();
        let b = velocity_terms(&m, &q, &qd, &loads).unwrap();
        let scale = tau.iter().fold(1.0f64, |a, x| a.max(x.abs()));
        for i in 0..2 {
            let got = mm[i][0] * qdd[0] + mm[i][1] * qdd[1] + b[i];
            assert!(
                within((got - tau[i]).abs(), 1e-13 * scale), // measured worst 1.9e-15 (be05608); 100×
                "M q'' + b = {got}, truth {}",
                tau[i]
            );
        }
        // measured worst 1.9e-14 (be05608); 100×
        assert!(within(
            (mm[0][1] - mm[1][0]).abs(),
            1e-13 * mm[0][0].abs().max(mm[1][1].abs())
        ));
        assert!(mm[0][0] > 0.0 && mm[0][0] * mm[1][1] - mm[0][1] * mm[1][0] > 0.0);
        let acc = lagrange_acceleration(&m, &q, &qd, &[tau[0], tau[1]], &loads).unwrap();
        for i in 0..2 {
            assert!(
                within((acc[i] - qdd[i]).abs(), 5e-12 * qdd[i].abs().max(1.0)), // measured worst 7.3e-14 (be05608); 100×
                "q''[{i}] = {} vs {}",
                acc[i],
                qdd[i]
            );
        }
    }

    let m = SliderCrank::new();
    let t = truth("slider_crank");
    let mut loads = SliderCrankLoads::default();
    for (name, l) in t["loads"].as_object().unwrap() {
        assert!(loads.set_by_name(name, &nums(&l["value"])));
    }
    for c in t["configs"].as_array().unwrap() {
        let (q, qd) = (c["q"].as_f64().unwrap(), c["qd"].as_f64().unwrap());
        let z = &c["zhukovski"];
        let (i_star, di, m_star) = (
            z["I_star"].as_f64().unwrap(),
            z["dI_star_dq"].as_f64().unwrap(),
            z["M_star"].as_f64().unwrap(),
        );
        let mm = mass_matrix(&m, &[q]).unwrap();
        // measured worst 2.6e-14 (be05608); 100×
        assert!(within((mm[0][0] - i_star).abs(), 1e-12 * i_star));
        let b = velocity_terms(&m, &[q], &[qd], &loads).unwrap()[0];
        let want = 0.5 * di * qd * qd - m_star;
        assert!(
            within((b - want).abs(), 5e-14 * m_star.abs().max(want.abs())), // measured worst 6.9e-16 (be05608); 100×
            "b = {b}, want {want}"
        );
    }
}

/// The five-bar held near its drawing by two torsion springs τ = −k (q − q_ref)
/// (k = 20 N·m/rad), gravity on, no other load: Lagrange's equations integrated for 2 s
/// keep E = T + V_gravity + ½ k |q − q_ref|² to 2e-12 relative (DOP853, rtol 1e-12), and
/// DP5, DOP853 and RK4 (h = 1e-4 s) end at the same state (DP5: 5e-10 rad, 5e-8 rad/s;
/// RK4: 1e-9 rad, 2e-8 rad/s).
#[test]
fn five_bar_lagrange_integration_conserves_energy() {
    let m = FiveBar::new();
    let q_ref = [2.0299, 1.0645];
    let k = 20.0;
    let springs = move |_: f64, q: &[f64; 2], _: &[f64; 2]| {
        (
            [-k * (q[0] - q_ref[0]), -k * (q[1] - q_ref[1])],
            FiveBarLoads::default(),
        )
    };
    let energy = |y: &[f64; 4]| {
        let spring = 0.5 * k * ((y[0] - q_ref[0]).powi(2) + (y[1] - q_ref[1]).powi(2));
        total_energy(&m, &y[..2], &y[2..]).unwrap() + spring
    };
    let y0 = [q_ref[0], q_ref[1], 2.0, -1.5];
    let e0 = energy(&y0);
    let mut worst = 0.0f64;
    let mut obs = |d: &mech::ode::Dop853Dense<4>| {
        use mech::ode::Dense;
        worst = worst.max((energy(&d.y_end()) - e0).abs());
    };
    let r8 = solve(
        &mut Dop853::new(1e-12, 1e-12),
        lagrange_equations(&m, springs),
        0.0,
        y0,
        2.0,
        None,
        Some(&mut obs),
    )
    .unwrap();
    // measured worst 3.0e-14 (be05608); 100×
    assert!(
        within(worst, 2e-12 * e0.abs()),
        "energy drift {worst:e} of {e0}"
    );
    let r5 = integrate(
        &mut DormandPrince::new(1e-11, 1e-12),
        lagrange_equations(&m, springs),
        0.0,
        y0,
        2.0,
    )
    .unwrap();
    let r4 = integrate(
        &mut Rk4 { h: 1e-4 },
        lagrange_equations(&m, springs),
        0.0,
        y0,
        2.0,
    )
    .unwrap();
    // (method, state, tolerance on q, on q̇): measured worst 7.3e-12, 7.5e-10 (DP5),
    // 1.4e-11, 2.2e-10 (RK4) (be05608); 100×
    for (method, r, tol_q, tol_qd) in [("dp5", r5, 5e-10, 5e-8), ("rk4", r4, 1e-9, 2e-8)] {
        for i in 0..4 {
            let (what, tol) = if i < 2 { ("q", tol_q) } else { ("q'", tol_qd) };
            assert!(
                within_at(&format!("{method} {what}"), (r.y[i] - r8.y[i]).abs(), tol),
                "component {i}: {} vs {}",
                r.y[i],
                r8.y[i]
            );
        }
    }
}

// ---------------------------------------------------------------------------------------
// Long run

/// The four-bar (gravity, no driver, no load, no friction) launched at q̇0 = 100 rad/s
/// keeps revolving; integrated by DOP853 (rtol = atol = RTOL) through 10,000 crank
/// revolutions, in 1,000 runs of 10 revolutions each stopped by an event (q is then
/// reduced by 20π, exact physics for a fully rotating crank, so that the relative
/// tolerance on q stays meaningful), its total energy T + V stays within BOUND = 1e-6
/// relative of the start at the end of every run. The measured drift is −5.3e-7: an
/// explicit method's energy error accumulates linearly over the ~570,000 steps (8 million
/// evaluations; rtol 1e-11 gives −9.5e-8 for 25 % more work, 1e-12 gives −7e-9 for 70 %
/// more). About 15 s in the test profile, 2 s in release.
#[test]
fn conservative_four_bar_keeps_its_energy_for_10000_revolutions() {
    const RTOL: f64 = 1e-10;
    // measured worst 5.3e-7 (be05608); 100×
    const BOUND: f64 = 1e-6;
    let m = FourBar::new();
    let q0 = 1.0;
    let mut y = [q0, 100.0];
    let mut t = 0.0;
    let e0 = total_energy(&m, &[q0], &[y[1]]).unwrap();
    let mut worst = 0.0f64;
    let mut work = Stats::default();
    let start = std::time::Instant::now();
    for run in 0..1000 {
        let target = q0 + TAU * 10.0;
        let mut g = |_: f64, y: &[f64; 2]| y[0] - target;
        let mut ev = Event {
            g: &mut g,
            direction: 1,
            t_tol: 1e-13,
        };
        let r = solve(
            &mut Dop853::new(RTOL, RTOL),
            equation_of_motion(&m, |_, _, _| (0.0, FourBarLoads::default())),
            t,
            y,
            t + 1e4,
            Some(&mut ev),
            None,
        )
        .unwrap();
        assert!(
            r.event && r.y[1] > 0.0,
            "the crank stopped revolving in run {run}"
        );
        (t, y) = (r.t, [r.y[0] - TAU * 10.0, r.y[1]]);
        work.steps += r.stats.steps;
        work.rhs_evals += r.stats.rhs_evals;
        worst = worst.max((total_energy(&m, &[y[0]], &[y[1]]).unwrap() - e0).abs() / e0);
    }
    eprintln!(
        "10,000 revolutions in {t:.3} s simulated: {} steps, {} evaluations, max |ΔE|/E = {worst:.2e}; wall {:.1?}",
        work.steps,
        work.rhs_evals,
        start.elapsed()
    );
    assert!(within(worst, BOUND), "energy drift {worst:e} > {BOUND:e}");
}

// ---------------------------------------------------------------------------------------
// Allocation and errors

/// One-DOF stepping allocates nothing: a whole run of each integrator (with an event
/// for DOP853) on the slider-crank's equation of motion makes zero heap allocations.
#[test]
fn one_dof_stepping_is_allocation_free() {
    let m = SliderCrank::new();
    let act = actions("time_and_speed");
    let _ = integrate(
        &mut Rk4 { h: 1e-3 },
        equation_of_motion(&m, &act),
        0.0,
        [0.3, 20.0],
        0.01,
    )
    .unwrap();
    let before = counting::count();
    let a = integrate(
        &mut Rk4 { h: 1e-4 },
        equation_of_motion(&m, &act),
        0.0,
        [0.3, 20.0],
        0.05,
    )
    .unwrap();
    let b = integrate(
        &mut DormandPrince::new(1e-10, 1e-10),
        equation_of_motion(&m, &act),
        0.0,
        [0.3, 20.0],
        0.05,
    )
    .unwrap();
    let mut g = |_: f64, y: &[f64; 2]| y[0] - 2.0;
    let mut ev = Event::new(&mut g);
    let c = solve(
        &mut Dop853::new(1e-10, 1e-10),
        equation_of_motion(&m, &act),
        0.0,
        [0.3, 20.0],
        0.05,
        Some(&mut ev),
        None,
    )
    .unwrap();
    let after = counting::count();
    assert!(a.stats.steps > 0 && b.stats.steps > 0 && c.event);
    assert_eq!(
        after - before,
        0,
        "{} allocations while stepping",
        after - before
    );
}

mechanism! {
    /// A massless crank: I* = 0.
    pub struct Massless {
        ground { O: (0.0, 0.0) },
        link crank { points { O, A: (0.1, 0.0) } },
        joints { O: revolute(ground, crank) },
        input: O,
    }
}

/// Bad input gives an error, never a panic: a massless machine (I* = 0) in every
/// algorithm, non-finite states, wrong slice lengths, a state of the wrong size.
#[test]
fn bad_input_is_an_error() {
    let z = Massless::new();
    let none = MasslessLoads::default();
    let mut eps = [0.0; 2];
    assert!(matches!(
        quinn_coefficients(&z, 0.1, &mut eps),
        Err(MechError::NonPositiveInertia(_))
    ));
    assert!(matches!(
        EnergyMethod::new(&z, 0.0, 0.1, 1.0, |_| (1.0, none), 1e-9).err(),
        Some(MechError::NonPositiveInertia(_))
    ));
    assert!(matches!(
        integrate(
            &mut Rk4 { h: 0.1 },
            equation_of_motion(&z, |_, _, _| (1.0, none)),
            0.0,
            [0.0, 1.0],
            1.0
        ),
        Err(MechError::NonPositiveInertia(_))
    ));
    assert!(matches!(
        lagrange_acceleration(&z, &[0.0], &[1.0], &[1.0], &none),
        Err(MechError::NonPositiveInertia(_))
    ));

    let m = SliderCrank::new();
    let zero = SliderCrankLoads::default();
    assert!(matches!(
        quinn_coefficients(&m, 0.1, &mut eps),
        Err(MechError::InvalidInput(_))
    ));
    assert!(matches!(
        quinn_coefficients(&m, f64::NAN, &mut [0.0; 4]),
        Err(MechError::InvalidInput(_))
    ));
    assert!(matches!(
        EnergyMethod::new(&m, 0.0, 0.3, 20.0, |_| (3.0, zero), 0.0).err(),
        Some(MechError::InvalidInput(_))
    ));
    assert!(matches!(
        EnergyMethod::new(&m, 0.0, f64::NAN, 20.0, |_| (3.0, zero), 1e-9).err(),
        Some(MechError::InvalidInput(_))
    ));
    let mut em = EnergyMethod::new(&m, 0.0, 0.3, 20.0, |_| (3.0, zero), 1e-9).unwrap();
    assert!(
        matches!(em.advance_to(0.2), Err(MechError::InvalidInput(_))),
        "backwards"
    );
    assert!(matches!(
        em.advance_to(f64::INFINITY),
        Err(MechError::InvalidInput(_))
    ));
    assert!(matches!(
        integrate(
            &mut Dop853::new(1e-9, 1e-9),
            equation_of_motion(&m, |_, _, _| (3.0, zero)),
            0.0,
            [f64::NAN, 1.0],
            1.0
        ),
        Err(MechError::InvalidInput(_))
    ));
    assert!(matches!(
        integrate(
            &mut Dop853::new(1e-9, 1e-9),
            equation_of_motion(&m, |_, _, _| (f64::NAN, zero)),
            0.0,
            [0.3, 1.0],
            1.0
        ),
        Err(MechError::InvalidInput(_))
    ));
    assert!(matches!(
        mass_matrix(&m, &[0.1, 0.2]),
        Err(MechError::InvalidInput(_))
    ));
    assert!(matches!(
        total_energy(&m, &[0.1, 0.2], &[0.0, 0.0]),
        Err(MechError::InvalidInput(_))
    ));
    let mut wrong = lagrange_equations(&m, |_, _: &[f64; 1], _: &[f64; 1]| ([0.0], zero));
    assert!(matches!(
        wrong(0.0, &[0.1, 0.2, 0.3]),
        Err(MechError::InvalidInput(_))
    ));
    let _: Stats = Stats::default();
}
