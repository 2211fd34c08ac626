//! A spring-loaded cam follower (a valve train) against `tests/data/cam_follower.json`
//! (`tools/cam_follower_reference.py`: the follower's own equation along its axis,
//! mpmath): the contact force over a revolution at constant speed, the pressure angle, the
//! motor torque by three routes and at run time; the jump speed and the smallest preload
//! that prevents a jump; the cam mistakes refused at compile time (tests/ui).

use crate::measure::within;
use mech::prelude::*;
use serde_json::Value;
use std::f64::consts::TAU;

use crate::data;
use data::{close, num};

mechanism! {
    /// A cam on the ground lifts a roller follower against a compression spring.
    pub struct ValveTrain {
        gravity: (0.0, -9.81),
        ground { O: (0.0, 0.0), S: (0.0, 150 mm) },
        link cam { points { O }, mass: 0.5, inertia: 2.0e-4, cg: (0.0, 0.0) },
        link follower { points { P: (0.0, 50 mm) }, mass: 0.08, cg: (0.0, 50 mm) },
        joints {
            O: revolute(ground, cam),
            slide: prismatic(ground, follower) at P along (0.0, 1.0),
            lobe: cam(cam, follower) base_radius 40 mm roller 10 mm
                law [dwell 90 deg, cycloidal 90 deg rise 10 mm, dwell 60 deg, poly345 120 deg fall 10 mm],
        },
        input: O,
        elements {
            spring: spring(ground at S, follower at P) stiffness 5 kN_per_m preload -50 N,
        },
    }
}

fn reference() -> Value {
    data::load("cam_follower.json")
}

/// At 150 rad/s over a revolution: the follower's lift, the contact force (and the
/// pressure angle it leans at) and the motor torque by d'Alembert, virtual power and
/// Zhukovski, and the run-time mechanism, each to at most 100× the worst error measured,
/// of its own scale (the largest of its kind over the revolution).
#[test]
fn contact_force_over_a_revolution() {
    let r = reference();
    let w = num(&r["speed"]);
    let m = ValveTrain::new();
    let rt = Mechanism::from_rust_source(include_str!("cams.rs"), "ValveTrain").unwrap();
    let loads = ValveTrainLoads::default();
    // The motor torque on its own scale (issue 28), the contact force on its own.
    let points = r["points"].as_array().unwrap();
    let dscale = points
        .iter()
        .map(|p| num(&p["driver"]).abs())
        .fold(0.0, f64::max);
    let fscale = points
        .iter()
        .map(|p| num(&p["normal_force"]).abs())
        .fold(0.0, f64::max);
    for p in r["points"].as_array().unwrap() {
        let th = num(&p["theta"]);
        let at = format!("θ = {:.2}°", th.to_degrees());
        let mo = m.kinematics(th, w, 0.0).unwrap();
        close(
            &format!("lift at {at}"),
            mo.points.P.pos.y - 0.05,
            num(&p["s"]),
            5e-16, // measured worst 9.5e-18 (be05608); 100×
        );
        let f = m.kinetostatics(&mo, &loads).unwrap();
        let c = f.joints.lobe;
        let fnorm = num(&p["normal_force"]);
        close(
            &format!("contact force at {at}"),
            c.normal_force,
            fnorm,
            5e-14 * fscale, // measured worst 8.3e-16 (be05608); 100×
        );
        let phi = num(&p["pressure_angle"]);
        close(
            &format!("pressure angle at {at}"),
            (-c.force.x).atan2(c.force.y),
            phi,
            1e-14, // measured worst 1.8e-16 (be05608); 100×
        );
        let t = num(&p["driver"]);
        // measured worst 9.8e-16 (be05608); 100×
        close(&format!("d'Alembert at {at}"), f.driver, t, 5e-14 * dscale);
        close(
            &format!("virtual power at {at}"),
            m.driver_action(&mo, &loads).unwrap(),
            t,
            1e-13 * dscale, // measured worst 1.0e-15 (be05608); 100×
        );
        close(
            &format!("Zhukovski at {at}"),
            m.acceleration(th, w, t, &loads).unwrap(),
            0.0,
            1e-13 * dscale / m.reduced(th).unwrap().inertia, // measured worst 1.1e-15 (be05608); 100×
        );
        let rf = rt
            .kinetostatics(&rt.kinematics(&[th], &[w], &[0.0]).unwrap(), &rt.loads())
            .unwrap();
        close(
            &format!("run-time driver at {at}"),
            rf.driver[0],
            t,
            5e-14 * dscale, // measured worst 9.8e-16 (be05608); 100×
        );
        close(
            &format!("run-time contact at {at}"),
            rf.reaction("lobe").unwrap().0.y,
            c.force.y,
            1e-14 * fscale, // measured worst 1.4e-16 (be05608); 100×
        );
    }
}

/// Follower jump: the contact force is a + b ω² at each cam angle (constant speed), so
/// the speed where it first reaches zero over the 7 200 angles of the reference's grid is
/// min √(−a/b) over b < 0 — the reference's jump speed; and at 400 rad/s the smallest
/// preload that keeps contact (the force linear in the preload) is the reference's.
#[test]
fn jump_speed_and_minimum_preload() {
    let r = reference();
    let m = ValveTrain::new();
    let loads = ValveTrainLoads::default();
    let fnorm = |m: &ValveTrain, th: f64, w: f64| {
        let mo = m.kinematics(th, w, 0.0).unwrap();
        m.kinetostatics(&mo, &loads)
            .unwrap()
            .joints
            .lobe
            .normal_force
    };
    let grid: Vec<f64> = (0..7200).map(|k| TAU * k as f64 / 7200.0).collect();
    let mut jump = f64::INFINITY;
    for &th in &grid {
        let (a, b) = (fnorm(&m, th, 0.0), fnorm(&m, th, 1.0) - fnorm(&m, th, 0.0));
        if b < 0.0 {
            jump = jump.min((-a / b).sqrt());
        }
    }
    // measured worst 1.5e-12 (be05608); 100×
    close("jump speed", jump, num(&r["jump_speed"]), 1e-10 * jump);
    // Below it the follower stays on the cam, above it leaves it somewhere.
    assert!(grid.iter().all(|&th| fnorm(&m, th, 0.99 * jump) > 0.0));
    assert!(grid.iter().any(|&th| fnorm(&m, th, 1.01 * jump) < 0.0));
    let w = num(&r["preload_at"]);
    let with = |f0: f64| {
        let mut p = ValveTrainParams::default();
        // Compression F0 in the drawing: L0 = L_drawing + F0/k.
        p.elements.spring.free_length = 0.1 + f0 / 5000.0;
        ValveTrain::from_params(p).unwrap()
    };
    let (m0, m1) = (with(0.0), with(1.0));
    let mut need = f64::NEG_INFINITY;
    for &th in &grid {
        let (a, b) = (fnorm(&m0, th, w), fnorm(&m1, th, w) - fnorm(&m0, th, w));
        need = need.max(-a / b);
    }
    close(
        "minimum preload",
        need,
        num(&r["min_preload"]),
        2e-12 * need, // measured worst 2.8e-14 (be05608); 100×
    );
}

#[path = "../examples/valve_train.rs"]
#[allow(dead_code)]
mod valve_train;

/// The valve-train example runs, writes its two SVGs, and its jump speed is the
/// reference's (the same machine); its `.mech` file loads into the same machine.
#[test]
fn valve_train_example() {
    let dir = std::env::temp_dir().join(format!("mech-valve-{}", std::process::id()));
    let files = valve_train::run(&dir).unwrap();
    assert!(files
        .iter()
        .all(|f| std::fs::metadata(f).map(|m| m.len() > 500).unwrap_or(false)));
    let m = valve_train::ValveTrain::new();
    let jump = valve_train::jump_speed(&m, 7200).unwrap();
    close(
        "example's jump speed",
        jump,
        num(&reference()["jump_speed"]),
        1e-10 * jump, // measured worst 1.5e-12 (be05608); 100×
    );
    let file = Mechanism::load(format!(
        "{}/examples/mech/valve_train.mech",
        env!("CARGO_MANIFEST_DIR")
    ))
    .unwrap();
    let mo = file.kinematics(&[2.8], &[150.0], &[0.0]).unwrap();
    let f = file.kinetostatics(&mo, &file.loads()).unwrap();
    close(
        "the .mech file's contact",
        f.reaction("lobe").unwrap().0.y,
        valve_train::contact(&m, 2.8, 150.0).unwrap()
            * (f.reaction("lobe").unwrap().0.y / f.reaction("lobe").unwrap().0.norm()),
        5e-13, // measured worst 7.1e-15 N (be05608); 100×
    );
    let _ = std::fs::remove_dir_all(&dir);
}

mechanism! {
    /// The same follower driven by a cam given as a table of lifts every 30°.
    pub struct TableCam {
        gravity: (0.0, -9.81),
        ground { O: (0.0, 0.0), S: (0.0, 150 mm) },
        link cam { points { O }, mass: 0.5, inertia: 2.0e-4, cg: (0.0, 0.0) },
        link follower { points { P: (0.0, 50 mm) }, mass: 0.08, cg: (0.0, 50 mm) },
        joints {
            O: revolute(ground, cam),
            slide: prismatic(ground, follower) at P along (0.0, 1.0),
            lobe: cam(cam, follower) base_radius 40 mm roller 10 mm
                table [(0 deg, 0 mm), (30 deg, 0.669873 mm), (60 deg, 2.5 mm), (90 deg, 5 mm),
                       (120 deg, 7.5 mm), (150 deg, 9.330127 mm), (180 deg, 10 mm),
                       (210 deg, 9.330127 mm), (240 deg, 7.5 mm), (270 deg, 5 mm),
                       (300 deg, 2.5 mm), (330 deg, 0.669873 mm)],
        },
        input: O,
        elements {
            spring: spring(ground at S, follower at P) stiffness 5 kN_per_m preload -50 N,
        },
    }
}

/// A cam given by a table: the follower's lift is the periodic spline through the points
/// (built apart with `mech::cam::Spline`) to 1e-15, close to the smooth lift it samples,
/// and the driver torque agrees by d'Alembert, virtual power and Zhukovski.
#[test]
fn table_cam() {
    let m = TableCam::new();
    let th: Vec<f64> = (0..12).map(|k| (30.0 * k as f64).to_radians()).collect();
    let s: Vec<f64> = [
        0.0, 0.669873, 2.5, 5.0, 7.5, 9.330127, 10.0, 9.330127, 7.5, 5.0, 2.5, 0.669873,
    ]
    .iter()
    .map(|x| x * 1e-3)
    .collect();
    let spline = mech::cam::Spline::periodic(&th, &s).unwrap();
    for k in 0..36 {
        let q = TAU * k as f64 / 36.0 + 0.05;
        let mo = m.kinematics(q, 100.0, 0.0).unwrap();
        let lift = mo.points.P.pos.y - 0.05;
        // measured worst 3.5e-18 (be05608); 100×
        close("table lift", lift, spline.eval(q)[0], 2e-16);
        // measured worst 9.8e-7 (be05608); the spline against the lift it samples, not an error
        assert!(
            within((lift - 0.005 * (1.0 - q.cos())).abs(), 5e-5),
            "{lift}"
        );
        let l = TableCamLoads::default();
        let d = m.kinetostatics(&mo, &l).unwrap().driver;
        close(
            "virtual power",
            m.driver_action(&mo, &l).unwrap(),
            d,
            1e-14, // N·m; measured worst 1.1e-16 (be05608); 100×
        );
        close(
            "Zhukovski",
            m.acceleration(q, 100.0, d, &l).unwrap(),
            0.0,
            1e-14 / m.reduced(q).unwrap().inertia, // N·m; measured worst 1.3e-16 (be05608); 100×
        );
    }
}
