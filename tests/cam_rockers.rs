//! Oscillating cam followers (rockers) against `tests/data/cam_rocker.json`
//! (`tools/cam_rocker_reference.py`, by routes mech does not take):
//! - the profiles of a roller rocker and a flat-faced rocker — contact points, pressure
//!   angles and radii of curvature from sympy's symbolic derivatives of the pitch curve and
//!   of the face lines' envelope seen from the cam, the common normal by Aronhold–Kennedy;
//! - the spring-loaded roller rocker at constant cam speed by its own moment equation about
//!   the pivot (mpmath): the contact force, the pressure angle, the motor torque by three
//!   routes and at run time, and the jump speed;
//! - a flat-faced rocker's three routes to the driver torque, a rocker whose law is a
//!   table of angles, and the direct problem
//!   through a rocker (the energy of a coasting machine kept over many turns);
//! - the rocker's mistakes refused at compile time (tests/ui).

use crate::measure::within;
use mech::cam::{Face, Law, MotionLaw, Profile, Rocker, Segment};
use mech::dynamics::{equation_of_motion, total_energy};
use mech::ode::{solve, Dop853};
use mech::prelude::*;
use serde_json::Value;
use std::f64::consts::TAU;

use crate::data;
use data::{close, num};

mechanism! {
    /// A cam on the ground swings a roller rocker pinned to the ground at A through 15°,
    /// against a torsion spring (3 N·m in the drawing).
    pub struct RockerCam {
        gravity: (0.0, -9.81),
        ground { O: (0.0, 0.0), A: (60 mm, 50 mm) },
        link cam { points { O }, mass: 0.5, inertia: 2.0e-4, cg: (0.0, 0.0) },
        link rocker {
            points { A, P: (0.0, 38 mm) },
            mass: 0.15, inertia: 6.0e-5, cg: (40 mm, 46 mm),
        },
        joints {
            O: revolute(ground, cam),
            A: revolute(ground, rocker),
            lobe: cam(cam, rocker) at P base_radius 30 mm roller 8 mm
                law [dwell 90 deg, cycloidal 90 deg rise 15 deg, dwell 60 deg, poly345 120 deg fall 15 deg],
        },
        input: O,
        elements {
            spring: torsion_spring(ground, rocker) stiffness 20 N_m_per_rad preload -3 N_m,
        },
    }
}

mechanism! {
    /// A flat-faced rocker pinned at (70 mm, 45 mm), its face tangent to a 30 mm base
    /// circle at P in the drawing, swung 10° against gravity and a torsion spring.
    pub struct FlatRocker {
        gravity: (0.0, -9.81),
        ground { O: (0.0, 0.0), A: (70 mm, 45 mm) },
        link cam { points { O }, mass: 0.5, inertia: 2.0e-4, cg: (5 mm, 0.0) },
        link rocker {
            points { A, P: (0.0, 30 mm) },
            mass: 0.2, inertia: 8.0e-5, cg: (35 mm, 40 mm),
        },
        joints {
            O: revolute(ground, cam),
            A: revolute(ground, rocker),
            lobe: cam(cam, rocker) at P base_radius 30 mm flat
                law [dwell 90 deg, cycloidal 90 deg rise 10 deg, dwell 60 deg, poly345 120 deg fall 10 deg],
        },
        input: O,
        elements {
            spring: torsion_spring(ground, rocker) stiffness 15 N_m_per_rad preload -2 N_m,
        },
    }
}

fn reference() -> Value {
    data::load("cam_rocker.json")
}

/// The law of both rockers: dwell 90°, cycloidal rise 90°, dwell 60°, 3-4-5 fall 120°.
fn law(lift: f64) -> MotionLaw {
    let d = std::f64::consts::PI / 180.0;
    let seg = |law, a: f64, b: f64, h0, h1| Segment {
        law,
        start: a * d,
        end: b * d,
        from: h0,
        to: h1,
    };
    MotionLaw::from_segments(vec![
        seg(Law::Dwell, 0.0, 90.0, 0.0, 0.0),
        seg(Law::Cycloidal, 90.0, 180.0, 0.0, lift),
        seg(Law::Dwell, 180.0, 240.0, lift, lift),
        seg(Law::Poly345, 240.0, 360.0, lift, 0.0),
    ])
    .unwrap()
}

fn compare_profile(what: &str, p: &Profile, rows: &Value) {
    for row in rows.as_array().unwrap() {
        let th = num(&row["theta"]);
        let at = p.at(th);
        let c = &row["contact"];
        let w = format!("{what} at {:.0}°", th.to_degrees());
        // measured worst 2.1e-17 (be05608); 100×
        close(&format!("{w}: contact x"), at.contact[0], num(&c[0]), 1e-15);
        // measured worst 1.4e-17 (be05608); 100×
        close(&format!("{w}: contact y"), at.contact[1], num(&c[1]), 1e-15);
        close(
            &format!("{w}: pressure angle"),
            at.pressure_angle,
            num(&row["pressure_angle"]),
            2e-14, // measured worst 2.8e-16 (be05608); 100×
        );
        close(
            &format!("{w}: radius of curvature"),
            at.curvature_radius,
            num(&row["curvature_radius"]),
            1e-14, // measured worst 1.1e-16 (be05608); 100×
        );
    }
}

/// The roller rocker's profile (from the generated struct's `cams()`) and a flat-faced
/// rocker's (a `Profile` built by hand) against sympy: contact points to 1e-15 m, pressure
/// angles to 2e-14 rad and radii of curvature to 1e-14 m.
#[test]
fn profiles_against_symbolic_geometry() {
    let r = reference();
    let m = RockerCam::new();
    let p = &m.cams()[0].profile;
    assert_eq!(
        p.rocker,
        Some(Rocker {
            pivot: [0.06, 0.05],
            sign: -1.0
        })
    );
    compare_profile("roller rocker", p, &r["roller_profile"]);
    let flat = Profile {
        law: law(10f64.to_radians()),
        base_radius: 0.03,
        offset: 0.0,
        face: Face::Flat,
        rocker: Some(Rocker {
            pivot: [0.07, 0.045],
            sign: -1.0,
        }),
    };
    compare_profile("flat rocker", &flat, &r["flat_profile"]);
    // The generated flat rocker's profile is that one.
    let fm = FlatRocker::new();
    let g = &fm.cams()[0].profile;
    for k in 0..72 {
        let th = TAU * k as f64 / 72.0;
        assert_eq!(g.at(th), flat.at(th));
    }
    // Both are convex and clear of undercut; the roller rocker's largest pressure angle is
    // where the reference's largest is, within the sampling.
    assert!(!p.check(720).undercut && !flat.check(720).undercut);
}

/// The rocker turns by σψ(θ) about its pivot (σ = −1: clockwise lifts it), its roller's
/// centre stays on its arm's circle; the contact force over a revolution at 60 rad/s, the
/// pressure angle it leans at, and the motor torque by d'Alembert, virtual power,
/// Zhukovski and the run-time mechanism, against the rocker's moment equation (mpmath),
/// each to at most 100× the worst error measured, of its own scale.
#[test]
fn contact_force_over_a_revolution() {
    let r = reference();
    let w = num(&r["speed"]);
    let m = RockerCam::new();
    let rt = Mechanism::from_rust_source(include_str!("cam_rockers.rs"), "RockerCam").unwrap();
    let loads = RockerCamLoads::default();
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
    let lw = law(15f64.to_radians());
    let arm0 = (-0.012f64).atan2(-0.06);
    for p in r["points"].as_array().unwrap() {
        let th = num(&p["theta"]);
        let at = format!("θ = {:.2}°", th.to_degrees());
        let mo = m.kinematics(th, w, 0.0).unwrap();
        let (pp, a) = (mo.points.P.pos, mo.points.A.pos);
        close(
            &format!("arm length at {at}"),
            (pp - a).norm(),
            0.06f64.hypot(0.012),
            1e-15, // measured worst 1.4e-17 (be05608); 100×
        );
        let [psi, psi1, ..] = lw.eval(th);
        let turn = ((pp.y - a.y).atan2(pp.x - a.x) - arm0 + 3.0 * std::f64::consts::PI)
            .rem_euclid(TAU)
            - std::f64::consts::PI;
        // measured worst 1.3e-15 (be05608); 100×
        close(&format!("rocker's turn at {at}"), turn, -psi, 1e-14);
        close(
            &format!("rocker's rate at {at}"),
            mo.links.rocker.omega,
            -psi1 * w,
            1e-15 * w, // measured worst 0 (be05608); exact; a few ulps
        );
        let f = m.kinetostatics(&mo, &loads).unwrap();
        let c = f.joints.lobe;
        close(
            // measured worst 2.1e-16 (be05608); 100×
            &format!("contact force at {at}"),
            c.normal_force,
            num(&p["normal_force"]),
            5e-14 * fscale, // measured worst 7.3e-16 (be05608); 100×
        );
        assert!(within(
            (c.force.norm() - c.normal_force.abs()).abs(),
            2e-14 * fscale
        ));
        // The pressure angle: from the roller centre's motion σ perp(P − A) to the force.
        let arm = pp - a;
        let d = Vector2::new(arm.y, -arm.x) / arm.norm();
        let n = c.force / c.normal_force;
        close(
            &format!("pressure angle at {at}"),
            (d.x * n.y - d.y * n.x).atan2(d.dot(&n)),
            num(&p["pressure_angle"]),
            2e-14, // measured worst 3.9e-16 (be05608); 100×
        );
        let t = num(&p["driver"]);
        // measured worst 7.3e-16 (be05608); 100×
        close(&format!("d'Alembert at {at}"), f.driver, t, 5e-14 * dscale);
        close(
            &format!("virtual power at {at}"),
            m.driver_action(&mo, &loads).unwrap(),
            t,
            5e-14 * dscale, // measured worst 8.4e-16 (be05608); 100×
        );
        close(
            &format!("Zhukovski at {at}"),
            m.acceleration(th, w, t, &loads).unwrap(),
            0.0,
            5e-14 * dscale / m.reduced(th).unwrap().inertia, // measured worst 8.4e-16 (be05608); 100×
        );
        let rm = rt.kinematics(&[th], &[w], &[0.0]).unwrap();
        let rf = rt.kinetostatics(&rm, &rt.loads()).unwrap();
        close(
            &format!("run-time driver at {at}"),
            rf.driver[0],
            t,
            5e-14 * dscale, // measured worst 9.0e-16 (be05608); 100×
        );
        let (force, _) = rf.reaction("lobe").unwrap();
        close(
            &format!("run-time contact at {at}"),
            force.x,
            c.force.x,
            2e-15 * fscale, // measured worst 2.6e-17 (be05608); 100×
        );
        close(
            &format!("run-time pivot at {at}"),
            rf.reaction("A").unwrap().0.y,
            f.joints.A.force.y,
            2e-14 * fscale, // measured worst 2.1e-16 (be05608); 100×
        );
    }
}

/// The contact force is (a + b ω²)/lever at each cam angle, so the speed where it first
/// reaches zero on the reference's grid of 7 200 angles is min √(−a/b) over b < 0: the
/// reference's jump speed; below it the roller stays on the cam everywhere.
#[test]
fn jump_speed() {
    let r = reference();
    let m = RockerCam::new();
    let loads = RockerCamLoads::default();
    let fnorm = |th: f64, w: f64| {
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
        let (a, b) = (fnorm(th, 0.0), fnorm(th, 1.0) - fnorm(th, 0.0));
        if b < 0.0 {
            jump = jump.min((-a / b).sqrt());
        }
    }
    // measured worst 5.4e-12 (be05608); 100×
    close("jump speed", jump, num(&r["jump_speed"]), 1e-10 * jump);
    assert!(grid.iter().all(|&th| fnorm(th, 0.99 * jump) > 0.0));
    assert!(grid.iter().any(|&th| fnorm(th, 1.01 * jump) < 0.0));
}

/// A flat-faced rocker: the driver torque by d'Alembert (through the contact point and
/// normal of the face's envelope) equals virtual power's and Zhukovski's (which never see
/// the contact), at 72 angles, accelerating.
#[test]
fn flat_rocker_three_routes() {
    let m = FlatRocker::new();
    let loads = FlatRockerLoads::default();
    for k in 0..72 {
        let th = TAU * k as f64 / 72.0 + 0.02;
        let mo = m.kinematics(th, 80.0, 300.0).unwrap();
        let f = m.kinetostatics(&mo, &loads).unwrap();
        assert!(f.joints.lobe.normal_force > 0.0, "contact lost at {th}");
        let scale = 2e-14; // N·m; measured worst 2.2e-16 (virtual power), 3.1e-16 (Zhukovski, times I*) (be05608); 100×
        close(
            "virtual power",
            m.driver_action(&mo, &loads).unwrap(),
            f.driver,
            scale,
        );
        close(
            "Zhukovski",
            m.acceleration(th, 80.0, f.driver, &loads).unwrap(),
            300.0,
            scale / m.reduced(th).unwrap().inertia,
        );
    }
}

/// The direct problem through a rocker: the roller rocker coasting with no motor torque
/// from 150 rad/s (DOP853, rtol = atol = 1e-11) over about 15 cam turns keeps its energy
/// (the cam's and the rocker's kinetic energy, the torsion spring's and gravity's
/// potential) within 1e-7 of it, while the cam's speed swings as the spring gives back what
/// the lift took. The bound is the integration's, not the model's: where the law's
/// segments meet its jerk ψ‴ jumps (cycloidal and 3-4-5 are C² only), so the right-hand
/// side is C¹ there and each of the 60 crossings costs the order-8 method accuracy, by an
/// amount that depends on where the steps fall (measured 8e-9 and 3.7e-8 J of 2.54 J for
/// two roundings of the same kernels).
#[test]
fn coasting_rocker_keeps_its_energy() {
    let m = RockerCam::new();
    let (q0, w0) = (0.0, 150.0);
    let e0 = total_energy(&m, &[q0], &[w0]).unwrap();
    let (mut worst, mut slowest, mut turns) = (0.0f64, f64::INFINITY, 0.0);
    let mut obs = |d: &mech::ode::Dop853Dense<2>| {
        use mech::ode::Dense;
        let y = d.y_end();
        worst = worst.max((total_energy(&m, &[y[0]], &[y[1]]).unwrap() - e0).abs());
        slowest = slowest.min(y[1]);
        turns = y[0] / TAU;
    };
    solve(
        &mut Dop853::new(1e-11, 1e-11),
        equation_of_motion(&m, |_, _, _| (0.0, RockerCamLoads::default())),
        0.0,
        [q0, w0],
        20.0 * TAU / w0,
        None,
        Some(&mut obs),
    )
    .unwrap();
    eprintln!("coasting rocker: {turns:.2} turns, max |ΔE| = {worst:.2e} J of {e0:.5} J, slowest {slowest:.3} rad/s");
    assert!(turns > 15.0, "{turns}");
    assert!(
        slowest < 0.99 * w0,
        "the lift should slow the cam: {slowest}"
    );
    // measured worst 1.4e-8 (be05608); the integration's error at C² joints (above), not the model's
    assert!(within(worst, 1e-7 * e0), "energy drift {worst:e} J");
}

use crate::counting;

/// Every generated solver of the two rockers allocates nothing (a counting allocator).
#[test]
fn generated_rocker_solvers_are_allocation_free() {
    let (m, f) = (RockerCam::new(), FlatRocker::new());
    let (lm, lf) = (RockerCamLoads::default(), FlatRockerLoads::default());
    let before = counting::count();
    let mut sink = 0.0;
    for k in 0..100 {
        let q = 0.063 * k as f64;
        let mo = m.kinematics(q, 50.0, 10.0).unwrap();
        sink += m.kinetostatics(&mo, &lm).unwrap().joints.lobe.normal_force;
        sink += m.driver_action(&mo, &lm).unwrap();
        sink += m.reduced_moment(q, &lm).unwrap();
        sink += m.acceleration(q, 50.0, 1.0, &lm).unwrap();
        let mo = f.kinematics(q, 50.0, 10.0).unwrap();
        sink += f.kinetostatics(&mo, &lf).unwrap().driver;
        sink += f.acceleration(q, 50.0, 1.0, &lf).unwrap();
    }
    assert_eq!(counting::count() - before, 0, "allocations");
    assert!(sink.is_finite());
}

/// `examples/mech/rocker_cam.mech` is the machine of these tests: loaded at run time, its
/// driver torque and contact force equal the generated struct's.
#[test]
fn the_mech_file_is_this_machine() {
    let file = Mechanism::load(format!(
        "{}/examples/mech/rocker_cam.mech",
        env!("CARGO_MANIFEST_DIR")
    ))
    .unwrap();
    let m = RockerCam::new();
    for k in 0..24 {
        let th = TAU * k as f64 / 24.0 + 0.1;
        let fm = file.kinematics(&[th], &[60.0], &[5.0]).unwrap();
        let ff = file.kinetostatics(&fm, &file.loads()).unwrap();
        let gm = m.kinematics(th, 60.0, 5.0).unwrap();
        let gf = m.kinetostatics(&gm, &RockerCamLoads::default()).unwrap();
        close("driver", ff.driver[0], gf.driver, 1e-14); // N·m; measured worst 2.2e-16 (be05608); 100×
        let (force, _) = ff.reaction("lobe").unwrap();
        close("contact", force.y, gf.joints.lobe.force.y, 1e-12); // N; measured worst 1.4e-14 (be05608); 100×
    }
}

mechanism! {
    /// The roller rocker driven by a cam given as a table of swings every 30° (angles).
    pub struct TableRocker {
        gravity: (0.0, -9.81),
        ground { O: (0.0, 0.0), A: (60 mm, 50 mm) },
        link cam { points { O }, mass: 0.5, inertia: 2.0e-4, cg: (0.0, 0.0) },
        link rocker {
            points { A, P: (0.0, 38 mm) },
            mass: 0.15, inertia: 6.0e-5, cg: (40 mm, 46 mm),
        },
        joints {
            O: revolute(ground, cam),
            A: revolute(ground, rocker),
            lobe: cam(cam, rocker) at P base_radius 30 mm roller 8 mm
                table [(0 deg, 0 deg), (30 deg, 1 deg), (60 deg, 3.75 deg), (90 deg, 7.5 deg),
                       (120 deg, 11.25 deg), (150 deg, 14 deg), (180 deg, 15 deg),
                       (210 deg, 14 deg), (240 deg, 11.25 deg), (270 deg, 7.5 deg),
                       (300 deg, 3.75 deg), (330 deg, 1 deg)],
        },
        input: O,
        elements {
            spring: torsion_spring(ground, rocker) stiffness 20 N_m_per_rad preload -3 N_m,
        },
    }
}

/// A rocker's law given as a table of angles: the rocker turns by minus the periodic
/// spline through the points (built apart with `mech::cam::Spline`) to 1e-14 rad, and the
/// driver torque agrees by d'Alembert, virtual power and Zhukovski.
#[test]
fn table_rocker() {
    let m = TableRocker::new();
    let th: Vec<f64> = (0..12).map(|k| (30.0 * k as f64).to_radians()).collect();
    let psi: Vec<f64> = [
        0.0, 1.0, 3.75, 7.5, 11.25, 14.0, 15.0, 14.0, 11.25, 7.5, 3.75, 1.0,
    ]
    .iter()
    .map(|x: &f64| x.to_radians())
    .collect();
    let spline = mech::cam::Spline::periodic(&th, &psi).unwrap();
    let arm0 = (-0.012f64).atan2(-0.06);
    let l = TableRockerLoads::default();
    for k in 0..36 {
        let q = TAU * k as f64 / 36.0 + 0.05;
        let mo = m.kinematics(q, 40.0, 0.0).unwrap();
        let (pp, a) = (mo.points.P.pos, mo.points.A.pos);
        let turn = ((pp.y - a.y).atan2(pp.x - a.x) - arm0 + 3.0 * std::f64::consts::PI)
            .rem_euclid(TAU)
            - std::f64::consts::PI;
        // measured worst 1.3e-15 (be05608); 100×
        close("table rocker's turn", turn, -spline.eval(q)[0], 1e-14);
        let d = m.kinetostatics(&mo, &l).unwrap().driver;
        close(
            "virtual power",
            m.driver_action(&mo, &l).unwrap(),
            d,
            1e-14, // N·m; measured worst 2.2e-16 (be05608); 100×
        );
        close(
            "Zhukovski",
            m.acceleration(q, 40.0, d, &l).unwrap(),
            0.0,
            1e-14 / m.reduced(q).unwrap().inertia, // N·m; measured worst 2.0e-16 (be05608); 100×
        );
    }
}

/// A flat-faced rocker turning exactly as fast as the cam (σψ′ = 1: a uniform fall of
/// 60° over 60° with σ = −1) has no envelope there: `Profile::check` reports where the
/// profile is missing (the macro's error), and nowhere else; the same rocker with a
/// 30° fall over those 60° (σψ′ = ½) has its profile everywhere.
#[test]
fn a_rocker_as_fast_as_the_cam_has_no_profile() {
    let d = std::f64::consts::PI / 180.0;
    let profile = |fall: f64| Profile {
        law: MotionLaw::from_segments(vec![
            Segment {
                law: Law::Uniform,
                start: 0.0,
                end: 60.0 * d,
                from: 0.0,
                to: fall * d,
            },
            Segment {
                law: Law::Uniform,
                start: 60.0 * d,
                end: 120.0 * d,
                from: fall * d,
                to: 0.0,
            },
            Segment {
                law: Law::Dwell,
                start: 120.0 * d,
                end: 360.0 * d,
                from: 0.0,
                to: 0.0,
            },
        ])
        .unwrap(),
        base_radius: 0.03,
        offset: 0.0,
        face: Face::Flat,
        rocker: Some(Rocker {
            pivot: [0.07, 0.045],
            sign: -1.0,
        }),
    };
    let at = profile(60.0).check(720).missing.expect("a missing profile");
    assert!(at >= 60.0 * d && at < 120.0 * d, "missing at {}°", at / d);
    assert_eq!(profile(30.0).check(720).missing, None);
}
