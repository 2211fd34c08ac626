//! `mech regime` and `mech simulate --motor`: a disc on a fixed pivot (constant I*, no
//! gravity) under a DC motor through a reduction and a constant drag, against the closed
//! forms: the steady speed where n T_s (1 − n ω/ω₀) balances the drag, and the start
//! ω = ω∞ (1 − e^{−t/τ}). Bad motors are usage errors; a motor that cannot start or carry
//! the machine is an error naming the fix.

use assert_cmd::Command;
use std::path::PathBuf;

const DISC: &str = "pub struct Disc {
    ground { O: (0.0, 0.0) },
    link disc { points { O, A: (0.1, 0.0) }, mass: 2.0, inertia: 0.03, cg: (0.0, 0.0) },
    joints { O: revolute(ground, disc) },
    input: O,
    loads { drag: torque on disc },
}";

const MOTOR: &str = "dc(stall_torque 2 N_m, no_load_speed 3000 rpm)";

fn disc(dir: &tempfile::TempDir) -> PathBuf {
    let path = dir.path().join("disc.mech");
    std::fs::write(&path, DISC).unwrap();
    path
}

fn mech() -> Command {
    Command::cargo_bin("mech").unwrap()
}

fn rows(out: &[u8]) -> (Vec<String>, Vec<Vec<f64>>) {
    let text = String::from_utf8(out.to_vec()).unwrap();
    let mut lines = text.lines();
    let header = lines.next().unwrap().split(',').map(String::from).collect();
    let rows = lines
        .map(|l| l.split(',').map(|v| v.parse().unwrap()).collect())
        .collect();
    (header, rows)
}

/// ω = (ω₀/n)(1 − D/(n T_s)) with the drag D; ε = 0; the motor's mean power D ω / ... on
/// its shaft T(nω)·nω.
#[test]
fn the_steady_regime_of_a_disc_is_the_balance_of_motor_and_drag() {
    let dir = tempfile::tempdir().unwrap();
    let f = disc(&dir);
    let out = mech()
        .args([
            "regime",
            f.to_str().unwrap(),
            "--motor",
            MOTOR,
            "--ratio",
            "10",
        ])
        .args(["--load", "drag=-0.5", "--points", "12", "--format", "csv"])
        .assert()
        .success()
        .get_output()
        .clone();
    let (names, table) = rows(&out.stdout);
    assert_eq!(names, ["q", "qd", "t", "torque"]);
    assert_eq!(table.len(), 13);
    let w0 = 3000.0 * std::f64::consts::PI / 30.0;
    let w = w0 / 10.0 * (1.0 - 0.5 / 20.0);
    for r in &table {
        assert!((r[1] - w).abs() < 1e-9 * w, "{r:?} vs {w}");
        assert!(
            (r[3] - 0.5).abs() < 1e-9,
            "the motor's action balances the drag: {r:?}"
        );
        assert!((r[2] - (r[0] / w)).abs() < 1e-9 * r[0].max(1.0) / w);
    }
    let summary = String::from_utf8(out.stderr).unwrap();
    let value = |name: &str| -> f64 {
        let line = summary.lines().find(|l| l.starts_with(name)).unwrap();
        line.split_whitespace().nth(1).unwrap().parse().unwrap()
    };
    assert!((value("mean_speed ") - w).abs() < 1e-9 * w, "{summary}");
    assert!(value("epsilon") < 1e-9, "{summary}");
    assert!(
        (value("motor_mean_power") - 0.5 * w).abs() < 1e-6,
        "{summary}"
    );
    assert!(summary.contains("within its rating"), "{summary}");
}

/// From rest: ω∞ = ω₀/n, τ = I ω₀ / (n² T_s), to 1e-8 of ω∞.
#[test]
fn simulate_with_a_motor_from_rest_is_the_exponential_start() {
    let dir = tempfile::tempdir().unwrap();
    let f = disc(&dir);
    let out = mech()
        .args([
            "simulate",
            f.to_str().unwrap(),
            "--motor",
            MOTOR,
            "--ratio",
            "10",
        ])
        .args([
            "--from-rest",
            "--t-end",
            "0.05",
            "--samples",
            "10",
            "--format",
            "csv",
        ])
        .assert()
        .success()
        .get_output()
        .stdout
        .clone();
    let (_, table) = rows(&out);
    let w0 = 3000.0 * std::f64::consts::PI / 30.0;
    let (w_inf, tau) = (w0 / 10.0, 0.03 * w0 / (100.0 * 2.0));
    for r in &table {
        let w = w_inf * (1.0 - (-r[0] / tau).exp());
        assert!((r[2] - w).abs() < 1e-8 * w_inf, "{r:?} vs {w}");
    }
}

/// Too weak a motor: the start is refused with the numbers and the fix; the regime finds
/// no balance; an unknown model is a usage error listing the forms.
#[test]
fn motors_that_cannot_do_it_are_errors_that_name_the_fix() {
    let dir = tempfile::tempdir().unwrap();
    let f = disc(&dir);
    let out = mech()
        .args([
            "simulate",
            f.to_str().unwrap(),
            "--motor",
            MOTOR,
            "--ratio",
            "10",
        ])
        .args(["--load", "drag=-30", "--from-rest", "--t-end", "1"])
        .assert()
        .code(1)
        .get_output()
        .stderr
        .clone();
    let e = String::from_utf8(out).unwrap();
    assert!(
        e.contains("cannot start") && e.contains("reduction ratio"),
        "{e}"
    );
    let out = mech()
        .args([
            "regime",
            f.to_str().unwrap(),
            "--motor",
            MOTOR,
            "--load",
            "drag=-30",
        ])
        .assert()
        .code(1)
        .get_output()
        .stderr
        .clone();
    let e = String::from_utf8(out).unwrap();
    assert!(e.contains("never balances"), "{e}");
    let out = mech()
        .args(["regime", f.to_str().unwrap(), "--motor", "stepper(3)"])
        .assert()
        .code(2)
        .get_output()
        .stderr
        .clone();
    let e = String::from_utf8(out).unwrap();
    assert!(
        e.contains("unknown motor") && e.contains("induction("),
        "{e}"
    );
}
