//! `mech engine` and the couples of `mech shaking`: a boxer twin's file, whose couple about
//! the vertical axis is a m ẍ of cylinder 1 (x = r cos θ + √(l² − r² sin² θ) differentiated
//! here), the cross-plane V8's primary couple and its counterweights, and bad input.

use assert_cmd::Command;

fn mech() -> Command {
    Command::cargo_bin("mech").unwrap()
}

fn stdout(c: &mut Command) -> String {
    let out = c.assert().success();
    String::from_utf8(out.get_output().stdout.clone()).unwrap()
}

/// The table line of `engine` and its eight numbers: exact and first order of the primary
/// and secondary forces and couples.
fn row(table: &str, engine: &str) -> Vec<f64> {
    let line = table.lines().find(|l| l.starts_with(engine)).unwrap();
    line.split([' ', '(', ')'])
        .filter_map(|w| w.parse::<f64>().ok())
        .collect::<Vec<_>>()
        .into_iter()
        .rev()
        .take(8)
        .rev()
        .collect()
}

#[test]
fn boxer_twin_file_and_its_couple() {
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("boxer.mech");
    let table = stdout(mech().args([
        "engine",
        "--layout",
        "boxer",
        "--cylinders",
        "2",
        "-o",
        file.to_str().unwrap(),
    ]));
    let r = row(&table, "boxer 2");
    assert_eq!(r[..6], [0.0, 0.0, 0.0, 0.0, 1.0, 1.0], "{table}");
    let csv = stdout(mech().args([
        "shaking",
        file.to_str().unwrap(),
        "--speed",
        "100",
        "--steps",
        "36",
        "--format",
        "csv",
    ]));
    let mut lines = csv.lines();
    assert_eq!(
        lines.next().unwrap(),
        "q,shaking.fx,shaking.fy,shaking.moment,shaking.mx,shaking.my"
    );
    let (rr, l, m, a, w) = (0.045, 0.150, 0.5, 0.090, 100.0f64);
    let mut rows = 0;
    for line in lines {
        let v: Vec<f64> = line.split(',').map(|x| x.parse().unwrap()).collect();
        let (s, c) = v[0].sin_cos();
        let d = (l * l - rr * rr * s * s).sqrt();
        let xdd =
            (-rr * c - rr * rr * (c * c - s * s) / d - rr.powi(4) * s * s * c * c / d.powi(3))
                * w
                * w;
        let want = a * m * xdd;
        let unit = m * rr * w * w;
        assert!((v[5] - want).abs() <= 1e-9 * unit * a, "{line}: {want}");
        assert!(
            v[1].abs() + v[2].abs() + v[4].abs() <= 1e-9 * unit,
            "{line}"
        );
        rows += 1;
    }
    assert_eq!(rows, 37);
}

#[test]
fn cross_plane_v8_and_its_couple_counterweights() {
    let table = stdout(mech().args([
        "engine",
        "--layout",
        "v",
        "--cylinders",
        "8",
        "--balance-couple",
    ]));
    let before = row(&table, "90° V8 ");
    assert!((before[4] - 10f64.sqrt()).abs() < 1e-4, "{table}");
    let after = row(&table, "90° V8 balanced");
    assert_eq!(after[4], 0.0, "{table}");
    assert!((after[5] - 10f64.sqrt()).abs() < 1e-4, "{table}");
}

#[test]
fn engine_bad_input_is_a_clear_error() {
    let fails = |args: &[&str], what: &str| {
        let out = mech().arg("engine").args(args).assert().failure();
        let err = String::from_utf8(out.get_output().stderr.clone()).unwrap();
        assert!(err.contains(what), "{args:?}: {err}");
    };
    fails(
        &[
            "--layout",
            "inline",
            "--cylinders",
            "4",
            "--phases",
            "0,180",
        ],
        "2 phase angles for 4 crank pins",
    );
    fails(
        &[
            "--layout",
            "inline",
            "--cylinders",
            "4",
            "--firing",
            "1-2-2-4",
        ],
        "once",
    );
    fails(&["--layout", "v", "--cylinders", "3"], "odd");
    fails(
        &["--layout", "boxer", "--cylinders", "2", "--balance-couple"],
        "cannot cancel",
    );
    fails(
        &["--layout", "inline", "--cylinders", "2", "--mass", "-1kg"],
        "positive",
    );
}
