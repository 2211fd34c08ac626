//! The `mech` binary against the generated structs of the same mechanisms: the
//! mechanisms are declared here with `mechanism!`, and the text between their braces is
//! written to `.mech` files for the tool, so both read the same declaration. `solve`,
//! `sweep`, `flywheel` and `simulate` must give the generated numbers to 1e-12 (1e-9 for
//! a time integration); `check` points into the file; bad arguments are usage errors.

use assert_cmd::Command;
use mech::flywheel::Cycle;
use mech::prelude::*;
use std::path::PathBuf;

mechanism! {
    /// Offset slider-crank by its dimensions, with a gas force and a shaft torque.
    pub struct Slider {
        consts { r: 43 mm, l: 143 mm, e: 6 mm },
        gravity: (0.0, -9.81),
        ground { O2: (0.0, 0.0) },
        link crank { points { O2, A: O2 + polar(r, 30 deg) }, mass: 3.6 kg, inertia: 6.8e-3 kg_m2, cg: along(-5 mm) },
        link rod { points { A, B: circle_line(A, l, (0.0, e), 0 deg, forward) }, mass: 580 g, inertia: 2.1e-3 kg_m2, cg: along(38 mm) },
        link piston { points { B }, mass: 520 g, cg: B },
        joints {
            O2: revolute(ground, crank),
            A: revolute(crank, rod),
            B: revolute(rod, piston),
            guide: prismatic(ground, piston) at B along (1.0, 0.0),
        },
        input: O2,
        loads { gas: force on piston at B, shaft: torque on crank },
    }
}

mechanism! {
    /// A five-bar with two cranks driven (two inputs).
    pub struct FiveBar {
        ground { O1: (0.0, 0.0), O5: (0.5, 0.0) },
        link left { points { O1, A: (0.1, 0.15) }, mass: 0.5, inertia: 2e-3, cg: along(0.08) },
        link upper { points { A, C: (0.3, 0.35) }, mass: 0.7, inertia: 4e-3, cg: along(0.14) },
        link lower { points { C, B: (0.45, 0.18) }, mass: 0.6, inertia: 3e-3, cg: along(0.1) },
        link right { points { O5, B }, mass: 0.5, inertia: 2e-3, cg: along(0.09) },
        joints {
            O1: revolute(ground, left),
            A: revolute(left, upper),
            C: revolute(upper, lower),
            B: revolute(lower, right),
            O5: revolute(ground, right),
        },
        inputs: [O1, O5],
        loads { pen: force on upper at C },
    }
}

/// The text between the braces of the `mechanism!` declaring `name` in this file,
/// written to a `.mech` file.
fn mech_file(dir: &tempfile::TempDir, name: &str) -> PathBuf {
    let source = include_str!("cli.rs");
    let at = source.find(&format!("pub struct {name} ")).unwrap();
    let start = source[..at].rfind("mechanism! {").unwrap() + "mechanism! {".len();
    let end = at + source[at..].find("\n}\n").unwrap();
    let path = dir.path().join(format!("{name}.mech"));
    std::fs::write(&path, &source[start..end]).unwrap();
    path
}

fn mech() -> Command {
    Command::cargo_bin("mech").unwrap()
}

/// The CSV output as (header, rows).
fn csv(out: &[u8]) -> (Vec<String>, Vec<Vec<f64>>) {
    let text = String::from_utf8(out.to_vec()).unwrap();
    let mut lines = text.lines();
    let header = lines.next().unwrap().split(',').map(String::from).collect();
    (
        header,
        lines
            .map(|l| l.split(',').map(|v| v.parse().unwrap()).collect())
            .collect(),
    )
}

fn close(what: &str, a: f64, b: f64, tol: f64) {
    assert!(
        (a - b).abs() <= tol * b.abs().max(1.0),
        "{what}: {a} against {b}"
    );
}

#[test]
fn check_summarises_a_good_mechanism_and_locates_a_mistake() {
    let dir = tempfile::tempdir().unwrap();
    let f = mech_file(&dir, "Slider");
    let out = mech()
        .arg("check")
        .arg(&f)
        .assert()
        .success()
        .get_output()
        .stdout
        .clone();
    let text = String::from_utf8(out).unwrap();
    for part in [
        "N = 4 links",
        "P_I = 4",
        "G = 3(N − 1) − 2 P_I − P_II = 9 − 8 − 0 = 1",
        "1. driven crank: crank (closed form)",
        "2. RRP dyad: rod, piston (closed form)",
    ] {
        assert!(text.contains(part), "{part} in\n{text}");
    }
    // A mistake on line 7, column 51 of the file: `rod` for `l`.
    let text = std::fs::read_to_string(&f).unwrap();
    let bad = text.replacen("circle_line(A, l,", "circle_line(A, rod,", 1);
    let (line, col) = bad
        .lines()
        .enumerate()
        .find_map(|(i, l)| l.find("rod,").map(|c| (i + 1, c + 1)))
        .unwrap();
    std::fs::write(&f, bad).unwrap();
    let err = mech()
        .arg("check")
        .arg(&f)
        .assert()
        .code(1)
        .get_output()
        .stderr
        .clone();
    let err = String::from_utf8(err).unwrap();
    let head = format!("{}:{line}:{col}: unknown constant `rod`", f.display());
    assert!(err.starts_with(&head), "expected `{head}` first in\n{err}");
}

#[test]
fn solve_gives_the_generated_numbers() {
    let dir = tempfile::tempdir().unwrap();
    let f = mech_file(&dir, "Slider");
    let out = mech()
        .args([
            "solve",
            f.to_str().unwrap(),
            "--at",
            "40deg",
            "--speed",
            "3000rpm",
            "--accel",
            "-50",
            "--load",
            "gas=-2.5kN,0",
            "--load",
            "shaft=-4",
            "--format",
            "csv",
        ])
        .assert()
        .success()
        .get_output()
        .stdout
        .clone();
    let (names, rows) = csv(&out);
    let row = &rows[0];
    let col = |n: &str| {
        row[names
            .iter()
            .position(|c| c == n)
            .unwrap_or_else(|| panic!("column {n} in {names:?}"))]
    };
    let m = Slider::new();
    let (q, qd, qdd) = (40f64.to_radians(), 100.0 * std::f64::consts::PI, -50.0);
    let loads = SliderLoads {
        gas: Vector2::new(-2500.0, 0.0),
        shaft: -4.0,
    };
    let mo = m.kinematics(q, qd, qdd).unwrap();
    let f = m.kinetostatics(&mo, &loads).unwrap();
    let z = m.reduced(q).unwrap();
    assert_eq!(names[0], "q");
    close("q", col("q"), q, 1e-15);
    close("B.x", col("B.x"), mo.points.B.pos.x, 1e-12);
    close("A.vy", col("A.vy"), mo.points.A.vel.y, 1e-12);
    close("rod.angle", col("rod.angle"), mo.links.rod.angle, 1e-12);
    close("rod.omega", col("rod.omega"), mo.links.rod.omega, 1e-12);
    close("rod.alpha", col("rod.alpha"), mo.links.rod.alpha, 1e-12);
    for (j, force, moment) in [
        ("O2", f.joints.O2.force, None),
        ("A", f.joints.A.force, None),
        ("B", f.joints.B.force, None),
        ("guide", f.joints.guide.force, Some(f.joints.guide.moment)),
    ] {
        close(&format!("{j}.fx"), col(&format!("{j}.fx")), force.x, 1e-12);
        close(&format!("{j}.fy"), col(&format!("{j}.fy")), force.y, 1e-12);
        if let Some(mm) = moment {
            close("guide.moment", col("guide.moment"), mm, 1e-12);
        }
    }
    close("driver", col("driver"), f.driver, 1e-12);
    close(
        "virtual_power",
        col("virtual_power"),
        m.driver_action(&mo, &loads).unwrap(),
        1e-12,
    );
    close("inertia", col("inertia"), z.inertia, 1e-12);
    close(
        "inertia_derivative",
        col("inertia_derivative"),
        z.inertia_derivative,
        1e-12,
    );
    close(
        "moment",
        col("moment"),
        m.reduced_moment(q, &loads).unwrap(),
        1e-12,
    );
}

#[test]
fn sweep_gives_the_generated_numbers_in_order_in_every_format() {
    let dir = tempfile::tempdir().unwrap();
    let f = mech_file(&dir, "FiveBar");
    let args = [
        "sweep",
        f.to_str().unwrap(),
        "--from",
        "60deg",
        "--to",
        "80deg",
        "--steps",
        "40",
        "--rest",
        "100deg",
        "--speed",
        "2,-1",
        "--load",
        "pen=10,-20",
    ];
    let out = mech()
        .args(args)
        .args(["--format", "csv"])
        .assert()
        .success()
        .get_output()
        .stdout
        .clone();
    let (names, rows) = csv(&out);
    assert_eq!(rows.len(), 41);
    assert_eq!(&names[..2], ["q.O1", "q.O5"]);
    assert!(names.contains(&"driver.O1".to_string()) && names.contains(&"driver.O5".to_string()));
    let m = FiveBar::new();
    let loads = FiveBarLoads {
        pen: Vector2::new(10.0, -20.0),
    };
    for (k, row) in rows.iter().enumerate() {
        let q = [(60.0 + 0.5 * k as f64).to_radians(), 100f64.to_radians()];
        let mo = m.kinematics(q, [2.0, -1.0], [0.0, 0.0]).unwrap();
        let f = m.kinetostatics(&mo, &loads).unwrap();
        let col = |n: &str| row[names.iter().position(|c| c == n).unwrap()];
        close("q", col("q.O1"), q[0], 1e-15);
        close("C.x", col("C.x"), mo.points.C.pos.x, 1e-12);
        close("C.y", col("C.y"), mo.points.C.pos.y, 1e-12);
        close("driver.O1", col("driver.O1"), f.driver[0], 1e-12);
        close("driver.O5", col("driver.O5"), f.driver[1], 1e-12);
        close(
            "virtual_power.O5",
            col("virtual_power.O5"),
            m.driver_action(&mo, &loads).unwrap()[1],
            1e-12,
        );
    }
    // JSON: an array of objects with the same keys and numbers.
    let out = mech()
        .args(args)
        .args(["--format", "json"])
        .assert()
        .success()
        .get_output()
        .stdout
        .clone();
    let json: serde_json::Value = serde_json::from_slice(&out).unwrap();
    let arr = json.as_array().unwrap();
    assert_eq!(arr.len(), 41);
    assert_eq!(
        arr[7]["C.y"].as_f64().unwrap(),
        rows[7][names.iter().position(|c| c == "C.y").unwrap()]
    );
    // Table: units in the header.
    let out = mech()
        .args(args)
        .assert()
        .success()
        .get_output()
        .stdout
        .clone();
    let head = String::from_utf8(out)
        .unwrap()
        .lines()
        .next()
        .unwrap()
        .to_string();
    assert!(
        head.contains("q.O1 [rad]") && head.contains("C.x [m]") && head.contains("driver.O1 [N·m]"),
        "{head}"
    );
}

/// The flywheel of the slider-crank under a gas force given as a table against the crank
/// angle: the tool's numbers against `Cycle` on the generated struct with the same
/// loads (the table interpolated here).
#[test]
fn flywheel_gives_the_generated_numbers() {
    let dir = tempfile::tempdir().unwrap();
    let f = mech_file(&dir, "Slider");
    // A gas force over 4π: a pressure peak after the TDC of the second turn.
    let table: Vec<(f64, f64)> = (0..=72)
        .map(|k| {
            let q = 10.0 * k as f64;
            let x = (q - 380.0) / 40.0;
            (q, -(100.0 + 4000.0 * (-x * x).exp()))
        })
        .collect();
    let csv_path = dir.path().join("gas.csv");
    let mut text = String::from("q_deg, fx, fy\n");
    for (q, v) in &table {
        text.push_str(&format!("{q}, {v}, 0\n"));
    }
    std::fs::write(&csv_path, text).unwrap();
    let out = mech()
        .args([
            "flywheel",
            f.to_str().unwrap(),
            "--period",
            "4pi",
            "--speed",
            "3000rpm",
            "--irregularity",
            "0.02",
            "--load",
        ])
        .arg(format!("gas=@{}", csv_path.display()))
        .args(["--format", "json"])
        .assert()
        .success()
        .get_output()
        .stdout
        .clone();
    let json: serde_json::Value = serde_json::from_slice(&out).unwrap();
    let r = &json[0];
    let m = Slider::new();
    let gas = |q: f64| {
        let deg = q.to_degrees().rem_euclid(720.0);
        let k = ((deg / 10.0).floor() as usize).min(71);
        let t = (deg - table[k].0) / 10.0;
        table[k].1 + t * (table[k + 1].1 - table[k].1)
    };
    let breaks: Vec<f64> = vec![];
    let cycle = Cycle::new(
        &m,
        0.0,
        4.0 * std::f64::consts::PI,
        &breaks,
        |q| {
            Ok(SliderLoads {
                gas: Vector2::new(gas(q), 0.0),
                shaft: 0.0,
            })
        },
        |_| 0.0,
    )
    .unwrap();
    let w = cycle.net_work();
    let (cycle, t) = cycle.balanced();
    let fw = cycle.flywheel(100.0 * std::f64::consts::PI, 0.02).unwrap();
    close("net work", r["net_work"].as_f64().unwrap(), w, 1e-12);
    close(
        "balancing torque",
        r["balancing_torque"].as_f64().unwrap(),
        t,
        1e-12,
    );
    close(
        "ΔE",
        r["fluctuation"].as_f64().unwrap(),
        fw.approximate.s_max - fw.approximate.s_min,
        1e-12,
    );
    close(
        "approximate",
        r["inertia_approximate"].as_f64().unwrap(),
        fw.approximate.inertia,
        1e-12,
    );
    close(
        "exact",
        r["inertia_exact"].as_f64().unwrap(),
        fw.exact.inertia,
        1e-12,
    );
    close(
        "simulated ε",
        r["irregularity_simulated"].as_f64().unwrap(),
        0.02,
        1e-6,
    );
}

#[test]
fn simulate_gives_the_generated_trajectory() {
    let dir = tempfile::tempdir().unwrap();
    let f = mech_file(&dir, "Slider");
    let out = mech()
        .args([
            "simulate",
            f.to_str().unwrap(),
            "--q0",
            "0.3",
            "--speed",
            "20",
            "--driver",
            "3",
            "--load",
            "gas=-200,0",
            "--t-end",
            "0.2",
            "--samples",
            "4",
            "--format",
            "csv",
        ])
        .assert()
        .success()
        .get_output()
        .stdout
        .clone();
    let (names, rows) = csv(&out);
    assert_eq!(names, ["t", "q", "qd", "qdd"]);
    assert_eq!(rows.len(), 5);
    let m = Slider::new();
    let loads = SliderLoads {
        gas: Vector2::new(-200.0, 0.0),
        shaft: 0.0,
    };
    let mut y = [0.3, 20.0];
    let mut t0 = 0.0;
    for row in &rows[1..] {
        let mut method = mech::ode::Dop853::new(1e-12, 1e-12);
        let out = mech::ode::solve(
            &mut method,
            mech::dynamics::equation_of_motion(&m, |_, _, _| (3.0, loads)),
            t0,
            y,
            row[0],
            None,
            None,
        )
        .unwrap();
        (y, t0) = (out.y, row[0]);
        close("q", row[1], y[0], 1e-8);
        close("q̇", row[2], y[1], 1e-8);
        close(
            "q̈",
            row[3],
            m.acceleration(row[1], row[2], 3.0, &loads).unwrap(),
            1e-12,
        );
    }
}

#[test]
fn bad_arguments_are_usage_errors() {
    let dir = tempfile::tempdir().unwrap();
    let f = mech_file(&dir, "Slider");
    let f = f.to_str().unwrap();
    for (args, status, part) in [
        (vec!["solve", f], 2, "--at"),
        (vec!["solve", f, "--at", "30mm"], 2, "an angle"),
        (
            vec!["solve", f, "--at", "30deg", "--load", "wind=3"],
            2,
            "no load named `wind`: the mechanism's loads are gas, shaft",
        ),
        (
            vec!["solve", f, "--at", "30deg", "--load", "gas=3"],
            2,
            "two components",
        ),
        (
            vec!["solve", f, "--at", "30deg,40deg"],
            2,
            "2 value(s) given for 1 input(s)",
        ),
        (vec!["sweep", f, "--from", "0", "--to", "1"], 2, "--steps"),
        (
            vec!["solve", "/nonexistent.mech", "--at", "1"],
            2,
            "cannot read",
        ),
        (vec!["frobnicate"], 2, "unrecognized subcommand"),
        (
            vec![
                "flywheel",
                f,
                "--speed",
                "100",
                "--irregularity",
                "0.02",
                "--period",
                "-1",
            ],
            1,
            "period must be positive",
        ),
        // The step budget of an adaptive run (issue 28: a stiff or runaway machine).
        (
            vec![
                "simulate",
                f,
                "--speed",
                "20",
                "--t-end",
                "10",
                "--max-steps",
                "5",
            ],
            1,
            "the integration took 5 steps",
        ),
    ] {
        let out = mech()
            .args(&args)
            .assert()
            .code(status)
            .get_output()
            .clone();
        let err = String::from_utf8(out.stderr).unwrap();
        assert!(err.contains(part), "{args:?}: expected “{part}” in\n{err}");
        assert!(!err.contains("panicked"), "{args:?}: {err}");
    }
}

/// Every example mechanism file passes `mech check`.
#[test]
fn the_example_files_pass_check() {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../examples/mech");
    let mut n = 0;
    for entry in std::fs::read_dir(&dir).unwrap() {
        let path = entry.unwrap().path();
        if path.extension().is_some_and(|e| e == "mech") {
            mech().arg("check").arg(&path).assert().success();
            n += 1;
        }
    }
    assert!(n >= 4, "{n} example files in {}", dir.display());
}

#[path = "../../tests/common/engine.rs"]
mod engine;

/// The engine example's flywheel from files: `examples/mech/engine.mech` and the gas
/// force tabulated every 0.1° by `tools/engine_gas_table.py`, against the 25-digit
/// reference of the engine example (`tests/data/engine.flywheel.json`, mpmath). The table's
/// linear interpolation costs a few parts in 10⁷.
#[test]
fn the_engine_flywheel_from_files() {
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let breaks: Vec<String> = engine::breakpoints()
        .iter()
        .map(|b| format!("{b:.17}"))
        .collect();
    let out = mech()
        .arg("flywheel")
        .arg(root.join("examples/mech/engine.mech"))
        .args([
            "--period",
            "4pi",
            "--start",
            &format!("{:.17}", engine::Q_TDC),
            "--speed",
            "3000rpm",
            "--irregularity",
            "0.02",
        ])
        .arg("--breakpoints")
        .arg(breaks.join(","))
        .arg(format!(
            "--load=gas=@{}",
            root.join("examples/mech/engine_gas.csv").display()
        ))
        .args(["--format", "json"])
        .assert()
        .success()
        .get_output()
        .stdout
        .clone();
    let r = &serde_json::from_slice::<serde_json::Value>(&out).unwrap()[0];
    let reference: serde_json::Value = serde_json::from_str(
        &std::fs::read_to_string(root.join("tests/data/engine.flywheel.json")).unwrap(),
    )
    .unwrap();
    let x = &reference["results"];
    for (ours, theirs) in [
        ("net_work", "net_work_gas"),
        ("balancing_torque", "balancing_torque"),
        ("s_max", "s_max"),
        ("s_min", "s_min"),
        ("inertia_approximate", "approximate_inertia"),
        ("inertia_exact", "exact_inertia"),
    ] {
        let (a, b) = (r[ours].as_f64().unwrap(), x[theirs].as_f64().unwrap());
        assert!(
            (a - b).abs() <= 1e-6 * b.abs(),
            "{ours}: {a} against the reference {b} ({:.1e})",
            (a - b).abs() / b.abs()
        );
    }
    close(
        "simulated ε",
        r["irregularity_simulated"].as_f64().unwrap(),
        0.02,
        1e-6,
    );
}

/// `mech cam` on the rocker of `examples/mech/rocker_cam.mech` (base circle 30 mm, roller
/// 8 mm, 15° cycloidal rise over 90°–180°): every contact point is one roller radius from
/// its pitch point; in the first dwell the contact is on the base circle and the pitch
/// point on the prime circle; over the rise the lift is the cycloidal law's closed form
/// written here; the largest pressure angle reported on standard error is the column's;
/// `--svg` writes a closed path through `--points` points; a file without a cam and an
/// unknown name are usage errors.
#[test]
fn cam_exports_the_profile() {
    let dir = tempfile::tempdir().unwrap();
    let file = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../examples/mech/rocker_cam.mech");
    let svg = dir.path().join("cam.svg");
    let out = mech()
        .args(["cam", "--points", "72", "--format", "csv", "--svg"])
        .arg(&svg)
        .arg(&file)
        .assert()
        .success()
        .get_output()
        .clone();
    let (head, rows) = csv(&out.stdout);
    let col = |n: &str| head.iter().position(|h| h == n).unwrap();
    assert_eq!(rows.len(), 72);
    let (lift, px, py, cx, cy, phi) = (
        col("lift"),
        col("pitch_x"),
        col("pitch_y"),
        col("contact_x"),
        col("contact_y"),
        col("pressure_angle"),
    );
    let mut largest = 0.0f64;
    for r in &rows {
        let th = r[col("theta")];
        close("roller", (r[px] - r[cx]).hypot(r[py] - r[cy]), 0.008, 1e-12);
        if th < std::f64::consts::FRAC_PI_2 {
            close("base circle", r[cx].hypot(r[cy]), 0.030, 1e-12);
            close("prime circle", r[px].hypot(r[py]), 0.038, 1e-12);
        }
        if th > std::f64::consts::FRAC_PI_2 && th < std::f64::consts::PI {
            let x = (th - std::f64::consts::FRAC_PI_2) / std::f64::consts::FRAC_PI_2;
            let want = 15f64.to_radians()
                * (x - (std::f64::consts::TAU * x).sin() / std::f64::consts::TAU);
            close("cycloidal lift", r[lift], want, 1e-14);
        }
        largest = largest.max(r[phi].abs());
    }
    let err = String::from_utf8(out.stderr).unwrap();
    assert!(
        err.contains(&format!(
            "largest pressure angle {:.2}°",
            largest.to_degrees()
        )),
        "{err}"
    );
    assert!(err.contains("not undercut"), "{err}");
    let text = std::fs::read_to_string(&svg).unwrap();
    let d = text
        .split("d=\"")
        .nth(1)
        .unwrap()
        .split('"')
        .next()
        .unwrap();
    assert_eq!(d.matches('L').count() + 1, 72);
    assert!(d.starts_with('M') && d.ends_with('Z'));
    let engine = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../examples/mech/engine.mech");
    let e = mech().arg("cam").arg(&engine).assert().code(2);
    assert!(String::from_utf8_lossy(&e.get_output().stderr).contains("has no cam"));
    let e = mech()
        .args(["cam", "--name", "nope"])
        .arg(&file)
        .assert()
        .code(2);
    assert!(String::from_utf8_lossy(&e.get_output().stderr).contains("its cams: `lobe`"));
}
