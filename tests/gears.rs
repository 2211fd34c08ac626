//! Gear pairs and racks against independent references, `tests/data/gears.json` from
//! `tools/gears_reference.py` (mpmath, 50 digits): the trains' kinetostatics as one
//! Newton–Euler linear system of all their bodies (mech goes gear by gear), their speed
//! ratios by Willis written out by hand; the geared linkages by the energy method. Every
//! number compared to at most 100× the worst error measured, of its own scale (the motor
//! torque on the motor torque's, a reaction on the largest reaction's), on the generated
//! struct and on the run-time
//! mechanism read from this file; the three routes to the driver torque; energy over many
//! turns; no allocation.

use crate::measure::within;
use mech::dynamics::{equation_of_motion, total_energy};
use mech::ode::{solve, Dop853};
use mech::prelude::*;
use serde_json::Value;

use crate::data;
use data::{close, num};

mechanism! {
    /// A compound gear train: pinion g1 (input) drives the cluster (two pitch circles on
    /// one shaft), which drives the output gear g4 carrying an unbalanced mass.
    pub struct GearTrain {
        gravity: (0.0, -9.81),
        ground { O1: (0.0, 0.0), O2: (80 mm, 0.0), O4: (80 mm, 100 mm) },
        link g1 { points { O1 }, mass: 0.2, inertia: 4.0e-5, cg: (0.0, 0.0) },
        link cluster { points { O2 }, mass: 1.1, inertia: 2.2e-3, cg: (80 mm, 0.0) },
        link g4 { points { O4 }, mass: 2.0, inertia: 6.0e-3, cg: (90 mm, 100 mm) },
        joints {
            O1: revolute(ground, g1),
            O2: revolute(ground, cluster),
            O4: revolute(ground, g4),
            m12: gear(g1, cluster) radii (20 mm, 60 mm),
            m34: gear(cluster, g4) radii (25 mm, 75 mm) pressure_angle 25 deg,
        },
        input: O1,
        loads { load: torque on g4 },
    }
}

mechanism! {
    /// An epicyclic train with a fixed ring (the ground), driven by its arm: the planet
    /// rolls inside the ring and drives the sun four times as fast as the arm.
    pub struct Epicyclic {
        ground { O: (0.0, 0.0) },
        link arm { points { O, P: (60 mm, 0.0) }, mass: 0.6, inertia: 4.0e-4, cg: (30 mm, 0.0) },
        link planet { points { P }, mass: 0.3, inertia: 1.4e-4, cg: (60 mm, 0.0) },
        link sun { points { O }, mass: 0.5, inertia: 2.3e-4, cg: (0.0, 0.0) },
        joints {
            O: revolute(ground, arm),
            P: revolute(arm, planet),
            S: revolute(ground, sun) at O,
            sp: gear(sun, planet) radii (30 mm, 30 mm),
            pr: gear(planet, ground) radii (30 mm, 90 mm) internal,
        },
        input: O,
        loads { load: torque on sun },
    }
}

mechanism! {
    /// A planetary reducer: the sun (input) drives the planet inside the fixed ring, and
    /// the arm (output) turns a quarter as fast; arm and planet form one gear-train group.
    pub struct Planetary {
        ground { O: (0.0, 0.0) },
        link arm { points { O, P: (60 mm, 0.0) }, mass: 0.6, inertia: 4.0e-4, cg: (30 mm, 0.0) },
        link planet { points { P }, mass: 0.3, inertia: 1.4e-4, cg: (60 mm, 0.0) },
        link sun { points { O }, mass: 0.5, inertia: 2.3e-4, cg: (0.0, 0.0) },
        joints {
            O: revolute(ground, arm),
            P: revolute(arm, planet),
            S: revolute(ground, sun) at O,
            sp: gear(sun, planet) radii (30 mm, 30 mm),
            pr: gear(planet, ground) radii (30 mm, 90 mm) internal,
        },
        input: S,
        loads { load: torque on arm },
    }
}

mechanism! {
    /// A slider-crank driven through a gear pair: the pinion (input, 25 mm) turns the
    /// crank gear (75 mm), whose crank pin A drives the rod and the piston.
    pub struct GearedSliderCrank {
        gravity: (0.0, -9.81),
        ground { O1: (0.0, 0.0), O2: (100 mm, 0.0) },
        link pinion { points { O1 }, mass: 0.3, inertia: 1.0e-4, cg: (0.0, 0.0) },
        link crank { points { O2, A: (140 mm, 0.0) }, mass: 1.5, inertia: 3.0e-3, cg: (105 mm, 5 mm) },
        link rod { points { A, B: (300 mm, 20 mm) }, mass: 0.9, inertia: 2.5e-3, cg: (220 mm, 12 mm) },
        link piston { points { B }, mass: 0.8, cg: (300 mm, 20 mm) },
        joints {
            O1: revolute(ground, pinion),
            O2: revolute(ground, crank),
            A: revolute(crank, rod),
            B: revolute(rod, piston),
            guide: prismatic(ground, piston) at B along (1.0, 0.0),
            mesh: gear(pinion, crank) radii (25 mm, 75 mm),
        },
        input: O1,
        loads { gas: force on piston at B },
    }
}

mechanism! {
    /// A rack-and-pinion steering: the pinion (input) moves the rack, whose ends pull the
    /// tie rods and turn the two knuckles about their kingpins.
    pub struct RackSteering {
        gravity: (0.0, -9.81),
        ground { O: (0.0, 0.0), K1o: (-300 mm, -150 mm), K2o: (300 mm, -150 mm) },
        link pinion { points { O }, mass: 0.2, inertia: 5.0e-5, cg: (0.0, 0.0) },
        link rack {
            points { R: (0.0, -20 mm), E1: (-150 mm, -100 mm), E2: (150 mm, -100 mm) },
            mass: 1.2, cg: (0.0, -20 mm),
        },
        link tie1 { points { E1, T1: (-280 mm, -100 mm) }, mass: 0.3, inertia: 4.0e-4, cg: (-215 mm, -100 mm) },
        link tie2 { points { E2, T2: (280 mm, -100 mm) }, mass: 0.3, inertia: 4.0e-4, cg: (215 mm, -100 mm) },
        link knuckle1 { points { K1o, T1 }, mass: 0.8, inertia: 2.0e-3, cg: (-290 mm, -125 mm) },
        link knuckle2 { points { K2o, T2 }, mass: 0.8, inertia: 2.0e-3, cg: (290 mm, -125 mm) },
        joints {
            O: revolute(ground, pinion),
            slide: prismatic(ground, rack) at R along (1.0, 0.0),
            E1: revolute(rack, tie1),
            E2: revolute(rack, tie2),
            T1: revolute(tie1, knuckle1),
            T2: revolute(tie2, knuckle2),
            K1o: revolute(ground, knuckle1),
            K2o: revolute(ground, knuckle2),
            drive: rack(pinion, rack) radius 20 mm,
        },
        input: O,
        loads { align1: torque on knuckle1, align2: torque on knuckle2 },
    }
}

mechanism! {
    /// A double-planet train: the sun (input, 20 mm) drives the first planet (12 mm, at P1
    /// on the arm), which drives the second (12 mm, at P2, 60° round from the line O P1),
    /// which rolls inside the fixed ring (its radius |O P2| + 12 mm): the arm and the two
    /// planets are one gear-train group of three links, three meshes. Every cg is off its
    /// centre, under gravity, and the arm is braked.
    pub struct DoublePlanet {
        gravity: (0.0, -9.81),
        ground { O: (0.0, 0.0) },
        link sun { points { O }, mass: 0.3, inertia: 6.0e-5, cg: (0.5 mm, 0.0) },
        link arm {
            points { O, P1: (32 mm, 0.0), P2: (0.044000000000000004, 0.020784609690826527) },
            mass: 0.8, inertia: 9.0e-4, cg: (25 mm, 8 mm),
        },
        link p1 { points { P1 }, mass: 0.1, inertia: 8.0e-6, cg: (32.4 mm, 0.3 mm) },
        link p2 { points { P2 }, mass: 0.1, inertia: 8.0e-6, cg: (44.2 mm, 20.5 mm) },
        joints {
            S: revolute(ground, sun) at O,
            O: revolute(ground, arm),
            P1: revolute(arm, p1),
            P2: revolute(arm, p2),
            s1: gear(sun, p1) radii (20 mm, 12 mm),
            pp: gear(p1, p2) radii (12 mm, 12 mm) pressure_angle 25 deg,
            r2: gear(p2, ground) radii (12 mm, 60.66210024238576 mm) internal,
        },
        input: S,
        loads { brake: torque on arm },
    }
}

/// A gear-train group of three links (the arm and two planets): the driver by d'Alembert
/// (from the tooth forces the group's reduced system gives) equals the driver by virtual
/// power (no reaction), and the ground's reactions (the sun's and the arm's bearings, the
/// ring's tooth force) balance the whole machine's d'Alembert forces, the brake and
/// gravity, over a turn of the arm, generated and run-time.
#[test]
fn a_three_link_train_balances_by_both_routes() {
    let m = DoublePlanet::new();
    let rt = runtime("DoublePlanet");
    let plan = mech_core::plan::assur::plan(rt.model()).unwrap();
    assert!(plan
        .iter()
        .any(|g| matches!(g.kernel, mech_core::plan::assur::Kernel::Train(t) if t.n == 3)));
    let loads = DoublePlanetLoads { brake: -1.5 };
    let mut rl = rt.loads();
    assert!(rl.set_by_name("brake", &[-1.5]));
    let p = m.params();
    let (qd, qdd) = (12.0, -3.0);
    for k in 0..48 {
        // The arm turns at 20/(20 + r_ring) of the sun: 4 turns of the sun, more than one of
        // the arm.
        let q = 0.3 + 4.0 * std::f64::consts::TAU * k as f64 / 48.0;
        let mo = m.kinematics(q, qd, qdd).unwrap();
        let f = m.kinetostatics(&mo, &loads).unwrap();
        let by_power = m.driver_action(&mo, &loads).unwrap();
        let scale = f.driver.abs().max(by_power.abs());
        assert!(
            within((f.driver - by_power).abs(), 1e-12 * scale),
            "driver at {q}: d'Alembert {}, virtual power {by_power}",
            f.driver
        );
        let rf = rt
            .kinetostatics(&rt.kinematics(&[q], &[qd], &[qdd]).unwrap(), &rl)
            .unwrap();
        assert!(
            within((rf.driver[0] - f.driver).abs(), 1e-12 * scale),
            "run-time driver at {q}: {} against {}",
            rf.driver[0],
            f.driver
        );
        let l = &mo.links;
        let inertial = [
            (p.links.sun.mass, l.sun.cg_acc),
            (p.links.arm.mass, l.arm.cg_acc),
            (p.links.p1.mass, l.p1.cg_acc),
            (p.links.p2.mass, l.p2.cg_acc),
        ]
        .iter()
        .fold(Vector2::zeros(), |sum, &(mass, acc)| {
            sum + (p.gravity - acc) * mass
        });
        let j = &f.joints;
        let ground = j.S.force + j.O.force - j.r2.force;
        let total = ground + inertial;
        assert!(
            total.norm() <= 1e-12 * (ground.norm() + inertial.norm()),
            "the machine's forces at {q}: {total}"
        );
    }
}

/// A planet on a moving arm: I*(q) is a constant and a cosine per pair of links on a chain
/// of pins (`mech_core::solvers::zhukovski_series`, worked out once), which must agree with
/// the routes that solve the motion at q: I* = 2T at q̇ = 1 (each link's kinetic energy
/// from the solved motion), ½ dI*/dq = driver(q, 1, 0) − driver(q, 0, 0) (d'Alembert's
/// kinetostatics, no load), and the direct problem returns the q̈ the kinetostatics was
/// given, generated and run-time, over four turns of the sun.
#[test]
fn an_epicyclic_s_reduced_inertia_is_a_sum_of_cosines_equal_to_the_solved_motion() {
    let m = DoublePlanet::new();
    let rt = runtime("DoublePlanet");
    let loads = DoublePlanetLoads::default();
    let rl = rt.loads();
    let mut energies = [0.0; 5];
    let mut varied = (f64::INFINITY, f64::NEG_INFINITY);
    for k in 0..48 {
        let q = -0.7 + 4.0 * std::f64::consts::TAU * k as f64 / 48.0;
        let r = m.reduced(q).unwrap();
        varied = (varied.0.min(r.inertia), varied.1.max(r.inertia));
        // I* = 2T of the motion at q̇ = 1.
        let unit = m.kinematics(q, 1.0, 0.0).unwrap();
        m.link_kinetic_energies(&unit, &mut energies);
        let by_energy = 2.0 * energies.iter().sum::<f64>();
        close("I* against 2T", r.inertia, by_energy, 1e-14 * by_energy);
        // ½ dI*/dq from d'Alembert's driver (gravity's M* cancels in the difference).
        let at_rest = m.kinematics(q, 0.0, 0.0).unwrap();
        let half = m.kinetostatics(&unit, &loads).unwrap().driver
            - m.kinetostatics(&at_rest, &loads).unwrap().driver;
        let scale = m.kinetostatics(&at_rest, &loads).unwrap().driver.abs() + r.inertia;
        close(
            "dI*/dq against d'Alembert",
            0.5 * r.inertia_derivative,
            half,
            1e-12 * scale,
        );
        // The direct problem returns the q̈ the kinetostatics was given.
        let (qd, qdd) = (9.0, -4.0);
        let driver = m
            .kinetostatics(&m.kinematics(q, qd, qdd).unwrap(), &loads)
            .unwrap()
            .driver;
        let back = m.acceleration(q, qd, driver, &loads).unwrap();
        close("q̈ by the direct problem", back, qdd, 1e-11 * qdd.abs());
        // The run-time mechanism keeps the same sum.
        let rr = OneDof::reduced(&rt, q).unwrap();
        close("run-time I*", rr.inertia, r.inertia, 1e-14 * r.inertia);
        close(
            "run-time dI*/dq",
            rr.inertia_derivative,
            r.inertia_derivative,
            1e-14 * r.inertia,
        );
        let rback = OneDof::acceleration(&rt, q, qd, driver, &rl).unwrap();
        close("run-time q̈", rback, qdd, 1e-11 * qdd.abs());
    }
    // The cgs off the planets' centres make I* vary with q: the cosines are not idle.
    assert!(
        varied.1 - varied.0 > 1e-9 * varied.1,
        "I* varies: {varied:?}"
    );
}

fn reference() -> Value {
    data::load("gears.json")
}

fn runtime(name: &str) -> Mechanism {
    Mechanism::from_rust_source(include_str!("gears.rs"), name)
        .unwrap_or_else(|e| panic!("{name}: {e}"))
}

/// The largest reaction of a configuration: the scale of the reactions' tolerance.
fn reaction_scale(c: &Value) -> f64 {
    c["reactions"]
        .as_object()
        .unwrap()
        .values()
        .flat_map(|v| v.as_array().unwrap().iter().map(num))
        .fold(1.0f64, |a, x| a.max(x.abs()))
}

/// Compare one train configuration: angles and speeds (Willis, over many turns), I*, the
/// driver by d'Alembert, virtual power and Zhukovski, every bearing reaction and tooth
/// force with its flank; then the run-time mechanism's driver and reactions.
fn check_train<M: OneDof>(
    name: &str,
    c: &Value,
    m: &M,
    kin: impl Fn(
        f64,
        f64,
        f64,
    ) -> (
        Vec<(String, f64, f64)>,
        f64,
        Vec<(String, V, Option<f64>)>,
        f64,
    ),
    loads: &M::Loads,
) where
    M::Loads: Clone,
{
    let (q, qd, qdd) = (num(&c["q"]), num(&c["qd"]), num(&c["qdd"]));
    let at = format!("{name} at q = {q}, q̇ = {qd}, q̈ = {qdd}");
    let (links, driver_va, joints, driver_ks) = kin(q, qd, qdd);
    for (link, angle, omega) in &links {
        // The link angle is reported in (−π, π]: compared modulo 2π, to 2e-14 of the
        // turned angle (a gear's angle counted wrong over the turns is off by a
        // non-multiple of 2π, the ratios not being integers).
        let want = num(&c["angles"][link]);
        let diff = (angle - want).rem_euclid(std::f64::consts::TAU);
        let diff = diff.min(std::f64::consts::TAU - diff);
        assert!(
            within(diff, 2e-14 * want.abs().max(1.0)), // measured worst 2.2e-16 (be05608); 100×
            "{at}: angle of {link} {angle} vs {want} (mod 2π)"
        );
        close(
            &format!("{at}: ω of {link}"),
            *omega,
            num(&c["omegas"][link]),
            1e-15 * qd.abs().max(1.0) * 4.0, // measured worst 1.5e-17 (be05608); 100×
        );
    }
    let i_star = num(&c["I_star"]);
    close(
        &format!("{at}: I*"),
        m.reduced(q).unwrap().inertia,
        i_star,
        2e-14 * i_star, // measured worst 3.0e-16 (be05608); 100×
    );
    let driver = num(&c["driver"]);
    // The motor torque on its own scale (issue 28; it was the largest reaction × 0.1 m,
    // 3 to 50 times the torque).
    let scale = driver.abs();
    close(
        &format!("{at}: d'Alembert"),
        driver_ks,
        driver,
        2e-14 * scale, // measured worst 4.4e-16 (be05608); the motor torque on its own scale; 100×
    );
    close(
        &format!("{at}: virtual power"),
        driver_va,
        driver,
        5e-14 * scale, // measured worst 5.3e-16 (be05608); 100×
    );
    close(
        &format!("{at}: Zhukovski q̈"),
        m.acceleration(q, qd, driver, loads).unwrap(),
        qdd,
        2e-14 * scale / i_star, // measured worst 2.7e-16 (be05608); 100×
    );
    let rs = reaction_scale(c);
    for (joint, f, flank) in &joints {
        let want = c["reactions"][joint].as_array().unwrap();
        // measured worst 2.8e-16 (be05608); 100×
        close(&format!("{at}: {joint}.x"), f.x, num(&want[0]), 2e-14 * rs);
        // measured worst 2.8e-16 (be05608); 100×
        close(&format!("{at}: {joint}.y"), f.y, num(&want[1]), 2e-14 * rs);
        if let Some(fl) = flank {
            assert_eq!(*fl, num(&c["flanks"][joint]), "{at}: flank of {joint}");
        }
    }
}

type V = mech::Vector2<f64>;

/// Gears on fixed axes have constant velocity coefficients: I* is one number, worked out
/// when the struct (or the run-time mechanism) is built, and dI*/dq is exactly 0. The
/// number is the 50-digit tables' I* at every one of their configurations (each worked
/// out there from that configuration's rates), and the direct problem with it gives the
/// tables' q̈ (`check_train`).
#[test]
fn a_gear_train_s_reduced_inertia_is_one_number() {
    let m = GearTrain::new();
    let rt = runtime("GearTrain");
    for c in reference()["gear_train"].as_array().unwrap() {
        let (q, want) = (num(&c["q"]), num(&c["I_star"]));
        for r in [m.reduced(q).unwrap(), rt.reduced(q).unwrap()] {
            assert_eq!(r.inertia_derivative, 0.0, "dI*/dq at q = {q}");
            close(&format!("I* at q = {q}"), r.inertia, want, 2e-14 * want);
        }
    }
    // Not a number at all is still refused.
    assert!(m.reduced(f64::NAN).is_err() && rt.reduced(f64::NAN).is_err());
}

/// The kept I* follows the drawing's numbers: a flywheel of 0.81 kg·m² keyed to the output
/// gear g4, which turns at (20/60)(25/75) = 1/9 of the pinion, adds 0.81/81 = 0.01 kg·m²
/// to I*, through `from_params` (generated) and `set_param` (run-time) alike.
#[test]
fn a_gear_train_s_kept_inertia_follows_its_flywheel() {
    let q = 0.3;
    let before = GearTrain::new().reduced(q).unwrap().inertia;
    let mut p = GearTrainParams::default();
    p.links.g4.flywheel = 0.81;
    let generated = GearTrain::from_params(p).unwrap().reduced(q).unwrap();
    let mut rt = runtime("GearTrain");
    rt.set_param("links.g4.flywheel", &[0.81]).unwrap();
    let run_time = rt.reduced(q).unwrap();
    for r in [generated, run_time] {
        close("I* with the flywheel", r.inertia - before, 0.01, 1e-15);
        assert_eq!(r.inertia_derivative, 0.0);
    }
}

#[test]
fn compound_gear_train_matches_newton_euler() {
    let m = GearTrain::new();
    let rt = runtime("GearTrain");
    for c in reference()["gear_train"].as_array().unwrap() {
        let loads = GearTrainLoads {
            load: num(&c["load"]),
        };
        check_train(
            "gear train",
            c,
            &m,
            |q, qd, qdd| {
                let mo = m.kinematics(q, qd, qdd).unwrap();
                let f = m.kinetostatics(&mo, &loads).unwrap();
                let j = &f.joints;
                let links = vec![
                    ("g1".into(), mo.links.g1.angle, mo.links.g1.omega),
                    (
                        "cluster".into(),
                        mo.links.cluster.angle,
                        mo.links.cluster.omega,
                    ),
                    ("g4".into(), mo.links.g4.angle, mo.links.g4.omega),
                ];
                let joints = vec![
                    ("O1".into(), j.O1.force, None),
                    ("O2".into(), j.O2.force, None),
                    ("O4".into(), j.O4.force, None),
                    ("m12".into(), j.m12.force, Some(j.m12.flank)),
                    ("m34".into(), j.m34.force, Some(j.m34.flank)),
                ];
                // measured worst 0 (be05608); exact; a few ulps
                assert!(within(
                    (j.m12.tooth_load - j.m12.force.norm()).abs(),
                    1e-15 * j.m12.tooth_load
                ));
                (
                    links,
                    m.driver_action(&mo, &loads).unwrap(),
                    joints,
                    f.driver,
                )
            },
            &loads,
        );
        // The run-time mechanism: the same driver and reactions.
        let (q, qd, qdd) = (num(&c["q"]), num(&c["qd"]), num(&c["qdd"]));
        let mut rl = rt.loads();
        assert!(rl.set_by_name("load", &[num(&c["load"])]));
        let f = rt
            .kinetostatics(&rt.kinematics(&[q], &[qd], &[qdd]).unwrap(), &rl)
            .unwrap();
        let rs = reaction_scale(c);
        close(
            "run-time driver",
            f.driver[0],
            num(&c["driver"]),
            2e-14 * num(&c["driver"]).abs(), // measured worst 2.1e-16 (be05608); 100×
        );
        for joint in ["O1", "O2", "O4", "m12", "m34"] {
            let want = c["reactions"][joint].as_array().unwrap();
            let (got, _) = f.reaction(joint).unwrap();
            close(
                &format!("run-time {joint}.x"),
                got.x,
                num(&want[0]),
                2e-14 * rs, // measured worst 2.5e-16 (be05608); 100×
            );
            close(
                &format!("run-time {joint}.y"),
                got.y,
                num(&want[1]),
                1e-14 * rs, // measured worst 1.4e-16 (be05608); 100×
            );
        }
    }
}

#[test]
fn epicyclic_train_matches_willis_and_newton_euler() {
    let m = Epicyclic::new();
    let rt = runtime("Epicyclic");
    for c in reference()["epicyclic"].as_array().unwrap() {
        let loads = EpicyclicLoads {
            load: num(&c["load"]),
        };
        check_train(
            "epicyclic",
            c,
            &m,
            |q, qd, qdd| {
                let mo = m.kinematics(q, qd, qdd).unwrap();
                let f = m.kinetostatics(&mo, &loads).unwrap();
                let j = &f.joints;
                let links = vec![
                    ("arm".into(), mo.links.arm.angle, mo.links.arm.omega),
                    (
                        "planet".into(),
                        mo.links.planet.angle,
                        mo.links.planet.omega,
                    ),
                    ("sun".into(), mo.links.sun.angle, mo.links.sun.omega),
                ];
                let joints = vec![
                    ("O".into(), j.O.force, None),
                    ("P".into(), j.P.force, None),
                    ("S".into(), j.S.force, None),
                    ("sp".into(), j.sp.force, Some(j.sp.flank)),
                    ("pr".into(), j.pr.force, Some(j.pr.flank)),
                ];
                (
                    links,
                    m.driver_action(&mo, &loads).unwrap(),
                    joints,
                    f.driver,
                )
            },
            &loads,
        );
        let (q, qd, qdd) = (num(&c["q"]), num(&c["qd"]), num(&c["qdd"]));
        let mut rl = rt.loads();
        assert!(rl.set_by_name("load", &[num(&c["load"])]));
        let mo = rt.kinematics(&[q], &[qd], &[qdd]).unwrap();
        let rs = reaction_scale(c);
        close(
            "run-time driver",
            rt.driver_action(&mo, &rl).unwrap()[0],
            num(&c["driver"]),
            1e-15 * num(&c["driver"]).abs(), // measured worst 0 (be05608); exact; a few ulps
        );
        let f = rt.kinetostatics(&mo, &rl).unwrap();
        for joint in ["O", "P", "S", "sp", "pr"] {
            let want = c["reactions"][joint].as_array().unwrap();
            let (got, _) = f.reaction(joint).unwrap();
            close(
                &format!("run-time {joint}.x"),
                got.x,
                num(&want[0]),
                2e-14 * rs, // measured worst 2.1e-16 (be05608); 100×
            );
            close(
                &format!("run-time {joint}.y"),
                got.y,
                num(&want[1]),
                2e-14 * rs, // measured worst 2.8e-16 (be05608); 100×
            );
        }
    }
}

/// The sun-driven planetary: arm and planet solved together (one gear-train group, a 2 × 2
/// Willis system for the angles, a 2 × 2 system for the tangential tooth forces, the pins'
/// forces then by sums).
#[test]
fn planetary_driven_by_its_sun_matches_newton_euler() {
    let m = Planetary::new();
    let rt = runtime("Planetary");
    let plan = mech_core::plan::assur::plan(rt.model()).unwrap();
    assert!(plan
        .iter()
        .any(|g| matches!(g.kernel, mech_core::plan::assur::Kernel::Train(_))));
    for c in reference()["planetary"].as_array().unwrap() {
        let loads = PlanetaryLoads {
            load: num(&c["load"]),
        };
        check_train(
            "planetary",
            c,
            &m,
            |q, qd, qdd| {
                let mo = m.kinematics(q, qd, qdd).unwrap();
                let f = m.kinetostatics(&mo, &loads).unwrap();
                let j = &f.joints;
                let links = vec![
                    ("arm".into(), mo.links.arm.angle, mo.links.arm.omega),
                    (
                        "planet".into(),
                        mo.links.planet.angle,
                        mo.links.planet.omega,
                    ),
                    ("sun".into(), mo.links.sun.angle, mo.links.sun.omega),
                ];
                let joints = vec![
                    ("O".into(), j.O.force, None),
                    ("P".into(), j.P.force, None),
                    ("S".into(), j.S.force, None),
                    ("sp".into(), j.sp.force, Some(j.sp.flank)),
                    ("pr".into(), j.pr.force, Some(j.pr.flank)),
                ];
                (
                    links,
                    m.driver_action(&mo, &loads).unwrap(),
                    joints,
                    f.driver,
                )
            },
            &loads,
        );
        let (q, qd, qdd) = (num(&c["q"]), num(&c["qd"]), num(&c["qdd"]));
        let mut rl = rt.loads();
        assert!(rl.set_by_name("load", &[num(&c["load"])]));
        let mo = rt.kinematics(&[q], &[qd], &[qdd]).unwrap();
        let rs = reaction_scale(c);
        let f = rt.kinetostatics(&mo, &rl).unwrap();
        close(
            "run-time driver",
            f.driver[0],
            num(&c["driver"]),
            2e-14 * num(&c["driver"]).abs(), // measured worst 4.4e-16 (be05608); 100×
        );
        for joint in ["O", "P", "S", "sp", "pr"] {
            let want = c["reactions"][joint].as_array().unwrap();
            let (got, _) = f.reaction(joint).unwrap();
            close(
                &format!("run-time {joint}.x"),
                got.x,
                num(&want[0]),
                2e-14 * rs, // measured worst 2.2e-16 (be05608); 100×
            );
            close(
                &format!("run-time {joint}.y"),
                got.y,
                num(&want[1]),
                1e-14 * rs, // measured worst 1.1e-16 (be05608); 100×
            );
        }
    }
}

/// The geared slider-crank and the rack-and-pinion steering against the energy method:
/// I*, dI*/dq, M*, and the driver by the three routes (generated) and by d'Alembert (run
/// time).
#[test]
fn geared_linkages_match_the_energy_method() {
    let r = reference();
    let g = GearedSliderCrank::new();
    let grt = runtime("GearedSliderCrank");
    for c in r["geared_slider_crank"].as_array().unwrap() {
        let loads = GearedSliderCrankLoads {
            gas: V::new(num(&c["gas"]), 0.0),
        };
        let mut rl = grt.loads();
        assert!(rl.set_by_name("gas", &[num(&c["gas"]), 0.0]));
        linkage_case("geared slider-crank", c, &g, &loads, |q, qd, qdd| {
            let mo = g.kinematics(q, qd, qdd).unwrap();
            let rmo = grt.kinematics(&[q], &[qd], &[qdd]).unwrap();
            [
                g.kinetostatics(&mo, &loads).unwrap().driver,
                g.driver_action(&mo, &loads).unwrap(),
                grt.kinetostatics(&rmo, &rl).unwrap().driver[0],
            ]
        });
    }
    let s = RackSteering::new();
    let srt = runtime("RackSteering");
    for c in r["rack_steering"].as_array().unwrap() {
        let a = num(&c["align"]);
        let loads = RackSteeringLoads {
            align1: a,
            align2: a,
        };
        let mut rl = srt.loads();
        assert!(rl.set_by_name("align1", &[a]) && rl.set_by_name("align2", &[a]));
        // The rack slides r q along x (the pinion turning counter-clockwise above it).
        let q = num(&c["q"]);
        let mo = s.kinematics(q, 0.0, 0.0).unwrap();
        close(
            "rack slide",
            mo.points.R.pos.x,
            num(&c["rack_slide"]),
            1e-15, // measured worst 0 (be05608); exact; a few ulps
        );
        linkage_case("rack steering", c, &s, &loads, |q, qd, qdd| {
            let mo = s.kinematics(q, qd, qdd).unwrap();
            let rmo = srt.kinematics(&[q], &[qd], &[qdd]).unwrap();
            [
                s.kinetostatics(&mo, &loads).unwrap().driver,
                s.driver_action(&mo, &loads).unwrap(),
                srt.kinetostatics(&rmo, &rl).unwrap().driver[0],
            ]
        });
    }
}

fn linkage_case<M: OneDof>(
    name: &str,
    c: &Value,
    m: &M,
    loads: &M::Loads,
    drivers: impl Fn(f64, f64, f64) -> [f64; 3],
) {
    let (q, qd, qdd) = (num(&c["q"]), num(&c["qd"]), num(&c["qdd"]));
    // The torques (M*, the motor torque) on their own scale (issue 28; it was a hand-set
    // 100 or 10 N·m, 2 to 100 times them).
    let scale = num(&c["driver"]).abs().max(num(&c["M_star"]).abs());
    let at = format!("{name} at q = {q}, q̇ = {qd}, q̈ = {qdd}");
    let red = m.reduced(q).unwrap();
    let i_star = num(&c["I_star"]);
    // measured worst 6.6e-15 (be05608); 100×
    close(&format!("{at}: I*"), red.inertia, i_star, 5e-13 * i_star);
    close(
        &format!("{at}: dI*/dq"),
        red.inertia_derivative,
        num(&c["dI_star_dq"]),
        1e-12 * i_star, // measured worst 9.2e-14 (be05608); 100×
    );
    close(
        &format!("{at}: M*"),
        m.reduced_moment(q, loads).unwrap(),
        num(&c["M_star"]),
        2e-13 * scale, // measured worst 3.1e-15 (be05608); 100×
    );
    let driver = num(&c["driver"]);
    for (route, d) in ["d'Alembert", "virtual power", "run-time d'Alembert"]
        .iter()
        .zip(drivers(q, qd, qdd))
    {
        // measured worst 2.9e-15 (be05608); 100×
        close(&format!("{at}: {route}"), d, driver, 2e-13 * scale);
    }
    close(
        &format!("{at}: Zhukovski q̈"),
        m.acceleration(q, qd, driver, loads).unwrap(),
        qdd,
        2e-13 * scale / i_star, // measured worst 2.8e-15 (be05608); 100×
    );
}

/// Spun up and left alone (no driver, no load, gravity on the unbalanced output gear),
/// the compound train runs through more than 10³ turns of its pinion: DOP853 (rtol =
/// atol = 1e-11) keeps T + V within 2e-10 of T, the gears' angles carried over the turns.
#[test]
fn gear_train_energy_is_conserved_over_many_turns() {
    let m = GearTrain::new();
    let y0 = [0.0, 300.0];
    let e0 = total_energy(&m, &[y0[0]], &[y0[1]]).unwrap();
    let mut worst = 0.0f64;
    let mut obs = |d: &mech::ode::Dop853Dense<2>| {
        use mech::ode::Dense;
        let y = d.y_end();
        worst = worst.max((total_energy(&m, &[y[0]], &[y[1]]).unwrap() - e0).abs());
    };
    let out = solve(
        &mut Dop853::new(1e-11, 1e-11),
        equation_of_motion(&m, |_, _, _| (0.0, GearTrainLoads::default())),
        0.0,
        y0,
        25.0,
        None,
        Some(&mut obs),
    )
    .unwrap();
    let turns = out.y[0] / std::f64::consts::TAU;
    assert!(turns > 1000.0, "{turns} turns");
    assert!(
        within(worst, 2e-10 * e0), // measured worst 2.4e-12 (be05608); 100×
        "energy drift {worst:e} J of {e0} J over {turns:.0} turns"
    );
}

use crate::counting;

/// The generated solvers of a geared machine allocate nothing.
#[test]
fn geared_solvers_are_allocation_free() {
    let m = GearedSliderCrank::new();
    let e = Epicyclic::new();
    let loads = GearedSliderCrankLoads {
        gas: V::new(-300.0, 0.0),
    };
    let before = counting::count();
    let mut sink = 0.0;
    for k in 0..100 {
        let q = 0.37 * k as f64;
        let mo = m.kinematics(q, 20.0, 3.0).unwrap();
        sink += m.kinetostatics(&mo, &loads).unwrap().joints.mesh.tooth_load;
        sink += m.driver_action(&mo, &loads).unwrap();
        sink += m.acceleration(q, 20.0, 1.0, &loads).unwrap();
        let mo = e.kinematics(q, 5.0, 1.0).unwrap();
        sink += e
            .kinetostatics(&mo, &EpicyclicLoads { load: 1.0 })
            .unwrap()
            .joints
            .pr
            .tooth_load;
    }
    assert_eq!(counting::count() - before, 0, "allocations");
    assert!(sink.is_finite());
}

#[path = "../examples/gearbox.rs"]
#[allow(dead_code)]
mod gearbox;

/// The gearbox example runs and writes its chart; over a turn of its arm at a steady speed
/// the motor torque by d'Alembert and by virtual power agree to 5e-14, the tooth loads of
/// the sun–planet and planet–ring meshes are equal (a light planet at constant speed
/// carries the same tangential force on both sides), and the mean motor torque is the
/// brake's 20 N·m divided by the 4:1 ratio (gravity and the spring are conservative: the
/// trapezoidal mean of a smooth periodic function is exact to roundoff).
#[test]
fn gearbox_example() {
    let dir = std::env::temp_dir().join(format!("mech-gearbox-{}", std::process::id()));
    let files = gearbox::run(&dir).unwrap();
    assert!(files.iter().all(|f| std::fs::metadata(f)
        .map(|m| m.len() > 1000)
        .unwrap_or(false)));
    let rows = gearbox::table(2.0).unwrap();
    let mut mean = 0.0;
    for r in &rows {
        // measured worst 5.6e-16 (be05608); 100×
        close(
            "routes",
            r.driver.1,
            r.driver.0,
            5e-14 * r.driver.0.abs().max(1.0),
        );
        assert!(
            r.sp.0 > 0.0 && within((r.sp.0 - r.pr.0).abs(), 5e-14 * r.sp.0), // measured worst 6.5e-16 (be05608); 100×
            "{} vs {}",
            r.sp.0,
            r.pr.0
        );
        mean += r.driver.0 / rows.len() as f64;
    }
    // measured worst 1.8e-15 (be05608); 100×
    close("mean motor torque", mean, 20.0 / 4.0, 1e-13);
    let _ = std::fs::remove_dir_all(&dir);
}
