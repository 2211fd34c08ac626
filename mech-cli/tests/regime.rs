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

/// A lone crank that is a steel disc (R = 100 mm, T = 20 mm, no gravity): a constant
/// inertia J = ρ T π R⁴ / 2 about its pivot.
const WHEEL: &str = "pub struct Wheel {
    ground { O: (0.0, 0.0) },
    link wheel { points { O, A: (0.1, 0.0) }, shape: disc(radius 100 mm, thickness 20 mm), material: steel },
    joints { O: revolute(ground, wheel) },
    input: O,
}";

/// The number after `name` in a summary.
fn summary_value(summary: &str, name: &str) -> f64 {
    let line = summary
        .lines()
        .find(|l| l.split_whitespace().next() == Some(name))
        .unwrap_or_else(|| panic!("no {name} in {summary}"));
    line.split_whitespace().nth(1).unwrap().parse().unwrap()
}

/// `mech regime --stop --brake B`: the wheel decelerates uniformly from ω₀ and stops after
/// t = J ω₀ / B having turned θ = J ω₀² / (2B), J = ρ T π R⁴ / 2 written out here; ω₀ is
/// the steady speed of a DC motor with no load (its no-load speed, 100 rad/s) or the given
/// `--speed` (rpm here); the table's rows are even in time, q̇ linear in t.
#[test]
fn a_braked_stop_of_a_disc_takes_j_omega_over_the_brake() {
    let dir = tempfile::tempdir().unwrap();
    let f = dir.path().join("wheel.mech");
    std::fs::write(&f, WHEEL).unwrap();
    let j = 7850.0 * 0.020 * std::f64::consts::PI * 0.1f64.powi(4) / 2.0;
    let (w0, brake) = (100.0, 0.5);
    let (t_stop, angle) = (j * w0 / brake, j * w0 * w0 / (2.0 * brake));
    let speed = format!("{}rpm", w0 * 30.0 / std::f64::consts::PI);
    for from in [
        [
            "--motor",
            "dc(stall_torque 2 N_m, no_load_speed 100 rad_per_s)",
        ],
        ["--speed", speed.as_str()],
    ] {
        let out = mech()
            .args([
                "regime",
                f.to_str().unwrap(),
                "--stop",
                "--brake",
                "0.5 N_m",
            ])
            .args(from)
            .args(["--points", "8", "--format", "csv"])
            .assert()
            .success()
            .get_output()
            .clone();
        let summary = String::from_utf8(out.stderr).unwrap();
        // The summary prints 13 significant digits.
        assert!(
            (summary_value(&summary, "initial_speed") - w0).abs() < 1e-11 * w0,
            "{summary}"
        );
        assert!(
            (summary_value(&summary, "stop_time") - t_stop).abs() < 1e-11 * t_stop,
            "{summary}"
        );
        assert!(
            (summary_value(&summary, "stop_angle") - angle).abs() < 1e-11 * angle,
            "{summary}"
        );
        assert!(summary.contains("braked to rest"), "{summary}");
        let (names, table) = rows(&out.stdout);
        assert_eq!(names, ["t", "q", "qd"]);
        assert_eq!(table.len(), 9);
        for (k, r) in table.iter().enumerate() {
            let t = t_stop * k as f64 / 8.0;
            assert!((r[0] - t).abs() < 1e-10 * t_stop, "{r:?}");
            assert!(
                (r[1] - (w0 * t - brake / (2.0 * j) * t * t)).abs() < 1e-10 * angle,
                "{r:?}"
            );
            assert!((r[2] - (w0 - brake / j * t)).abs() < 1e-10 * w0, "{r:?}");
        }
    }
}

/// Coasting with no loss never ends: the error names the fix; a negative brake, `--speed`
/// without `--stop` and `--stop` with neither a motor nor a speed are usage errors.
#[test]
fn stops_that_cannot_be_are_errors_that_name_the_fix() {
    let dir = tempfile::tempdir().unwrap();
    let f = dir.path().join("wheel.mech");
    std::fs::write(&f, WHEEL).unwrap();
    let f = f.to_str().unwrap();
    let err = |args: &[&str], code: i32| -> String {
        let out = mech()
            .arg("regime")
            .arg(f)
            .args(args)
            .assert()
            .code(code)
            .get_output()
            .clone();
        String::from_utf8(out.stderr).unwrap()
    };
    let e = err(&["--stop", "--speed", "100", "--t-max", "5"], 1);
    assert!(
        e.contains("still moving at t = 5 s") && e.contains("brake"),
        "{e}"
    );
    let e = err(&["--stop", "--speed", "100", "--brake", "-1"], 2);
    assert!(e.contains("--brake -1") && e.contains("≥ 0"), "{e}");
    let e = err(&["--stop", "--speed", "-3"], 2);
    assert!(e.contains("positive speed"), "{e}");
    let e = err(&["--speed", "100"], 2);
    assert!(e.contains("--stop"), "{e}");
    let e = err(&["--stop"], 2);
    assert!(e.contains("--motor"), "{e}");
}

/// `rated_power 1.5 kW`, `1500 W` and `1500` are one motor: the same output byte for byte;
/// and its steady speed under a drag D is Kloss's, written out here: the slip
/// s = s_b (T_b − √(T_b² − D²)) / D with T_b = k P / ω_r and s_b = s_r (k + √(k² − 1)).
#[test]
fn a_rated_power_in_kilowatts_is_the_same_motor_as_in_watts() {
    let dir = tempfile::tempdir().unwrap();
    let f = disc(&dir);
    let run = |power: &str| {
        let motor = format!(
            "induction(rated_power {power}, synchronous_speed 1500 rpm, rated_speed 1420 rpm, breakdown_ratio 2.5)"
        );
        mech()
            .args(["regime", f.to_str().unwrap(), "--motor", &motor])
            .args(["--load", "drag=-5", "--points", "12"])
            .assert()
            .success()
            .get_output()
            .stdout
            .clone()
    };
    let kw = run("1.5 kW");
    assert_eq!(
        String::from_utf8_lossy(&kw),
        String::from_utf8_lossy(&run("1500 W"))
    );
    assert_eq!(
        String::from_utf8_lossy(&kw),
        String::from_utf8_lossy(&run("1500"))
    );
    assert_eq!(
        String::from_utf8_lossy(&kw),
        String::from_utf8_lossy(&run("1.5kW"))
    );
    let rpm = std::f64::consts::PI / 30.0;
    let (ws, wr, k, d) = (1500.0 * rpm, 1420.0 * rpm, 2.5f64, 5.0);
    let tb = k * 1500.0 / wr;
    let sb = (ws - wr) / ws * (k + (k * k - 1.0).sqrt());
    let w = ws * (1.0 - sb * (tb - (tb * tb - d * d).sqrt()) / d);
    let text = String::from_utf8(kw).unwrap();
    let mean = summary_value(&text, "mean_speed");
    assert!((mean - w).abs() < 1e-9 * w, "{mean} vs {w}");
    // 1.5 W is another motor (too weak for the drag).
    let motor = "induction(rated_power 1.5 W, synchronous_speed 1500 rpm, rated_speed 1420 rpm, breakdown_ratio 2.5)";
    mech()
        .args([
            "regime",
            f.to_str().unwrap(),
            "--motor",
            motor,
            "--load",
            "drag=-5",
        ])
        .assert()
        .code(1);
}
