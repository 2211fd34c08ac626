//! `mech synth function` and `mech synth motion`: the hand-worked cases of
//! `mech_core::design::synthesis` from a terminal — the written file passes `mech check`,
//! and `mech solve` at the crank angle of each target puts B (function) or P and the
//! coupler (motion) where the targets say; bad files are usage errors that name the fix.

use assert_cmd::Command;
use std::f64::consts::{FRAC_PI_2, PI};

fn mech() -> Command {
    Command::cargo_bin("mech").unwrap()
}

fn write(dir: &tempfile::TempDir, name: &str, text: &str) -> String {
    let path = dir.path().join(name);
    std::fs::write(&path, text).unwrap();
    path.to_str().unwrap().to_string()
}

/// The CSV rows of standard output, as numbers, after the header `head`.
fn rows(out: &[u8], head: &str) -> Vec<Vec<f64>> {
    let text = String::from_utf8(out.to_vec()).unwrap();
    let mut lines = text.lines();
    assert_eq!(lines.next().unwrap(), head);
    lines
        .map(|l| l.split(',').map(|v| v.parse().unwrap()).collect())
        .collect()
}

/// `mech solve FILE --at Q --format csv --level positions`: the columns by name.
fn solve(file: &str, q: f64) -> std::collections::HashMap<String, f64> {
    let out = mech()
        .args([
            "solve",
            file,
            "--at",
            &format!("{q:?}"),
            "--format",
            "csv",
            "--level",
            "pose",
        ])
        .assert()
        .success();
    let text = String::from_utf8(out.get_output().stdout.clone()).unwrap();
    let mut lines = text.lines();
    let names: Vec<String> = lines.next().unwrap().split(',').map(String::from).collect();
    let values = lines.next().unwrap().split(',').map(|v| v.parse().unwrap());
    names.into_iter().zip(values).collect()
}

fn wrap(a: f64) -> f64 {
    (a.sin()).atan2(a.cos())
}

/// The crank-rocker a = 1, b = 3, c = 2, d = 3 by hand (mech-core's freudenstein tests):
/// its outputs at θ₂ = 0, π/2, π give K = (3, 3/2, 5/4); with `--frame 3` the file is that
/// linkage, and `mech solve` at q = θ₂ puts B at the output angle.
#[test]
fn function_from_three_hand_worked_pairs() {
    let dir = tempfile::tempdir().unwrap();
    let x2 = (45.0 + 135f64.sqrt()) / 20.0;
    let y2 = 3.0 * x2 - 6.5;
    let pairs = [
        [0.0, (63f64.sqrt() / 4.0).atan2(13.0 / 4.0 - 3.0)],
        [FRAC_PI_2, y2.atan2(x2 - 3.0)],
        [PI, (135f64.sqrt() / 8.0).atan2(13.0 / 8.0 - 3.0)],
    ];
    let csv: String = std::iter::once("input,output".to_string())
        .chain(pairs.iter().map(|p| format!("{:?},{:?}", p[0], p[1])))
        .collect::<Vec<_>>()
        .join("\n");
    let f = write(&dir, "pairs.csv", &csv);
    let out_file = dir.path().join("fg.mech");
    let o = out_file.to_str().unwrap();
    let run = mech()
        .args([
            "synth", "function", &f, "-o", o, "--frame", "3", "--format", "csv",
        ])
        .assert()
        .success();
    let stderr = String::from_utf8(run.get_output().stderr.clone()).unwrap();
    assert!(stderr.contains("(exact)"), "{stderr}");
    let k = |name: &str| -> f64 {
        let tail = &stderr[stderr.find(&format!("{name} = ")).unwrap() + name.len() + 3..];
        tail[..tail.find([',', '\n']).unwrap()].parse().unwrap()
    };
    for (name, want) in [("K1", 3.0), ("K2", 1.5), ("K3", 1.25)] {
        assert!((k(name) - want).abs() < 1e-12, "{name}: {stderr}");
    }
    assert!(stderr.contains("error = "), "{stderr}");
    let table = rows(&run.get_output().stdout, "input,output,achieved,residual");
    assert_eq!(table.len(), 3);
    for r in &table {
        assert!(r[3].abs() < 1e-12, "{r:?}");
    }
    mech().args(["check", o]).assert().success();
    for p in &pairs {
        let c = solve(o, p[0]);
        let psi = (c["B.y"] - c["O4.y"]).atan2(c["B.x"] - c["O4.x"]);
        assert!(wrap(psi - p[1]).abs() < 1e-12, "{psi} vs {}", p[1]);
        assert!((c["O4.x"] - 3.0).abs() < 1e-12);
    }
}

/// Degrees are accepted (`input_deg`, `output_deg`), and more pairs go to least squares.
#[test]
fn function_in_degrees_and_by_least_squares() {
    let dir = tempfile::tempdir().unwrap();
    let rows_deg: Vec<String> = (0..7)
        .map(|k| {
            let x = 1.0 + k as f64 / 6.0;
            format!(
                "{},{}",
                30.0 + 60.0 * (x - 1.0),
                60.0 + 90.0 * x.log10() / 2f64.log10()
            )
        })
        .collect();
    let f = write(
        &dir,
        "log.csv",
        &format!(
            "output_deg,input_deg\n{}",
            rows_deg
                .iter()
                .map(|r| {
                    let (a, b) = r.split_once(',').unwrap();
                    format!("{b},{a}")
                })
                .collect::<Vec<_>>()
                .join("\n")
        ),
    );
    let o = dir.path().join("log.mech");
    let run = mech()
        .args(["synth", "function", &f, "-o", o.to_str().unwrap()])
        .assert()
        .success();
    let stderr = String::from_utf8(run.get_output().stderr.clone()).unwrap();
    assert!(stderr.contains("(least squares)"), "{stderr}");
    mech()
        .args(["check", o.to_str().unwrap()])
        .assert()
        .success();
}

/// The three poses worked by hand in mech-core's burmester tests, with circle points
/// A (−1, 2) and B (1, 2): O2 (2, 1), O4 (0, 0); `mech solve` at each pose's q puts P at
/// (x, y) and the coupler along the angle.
#[test]
fn motion_through_three_hand_worked_poses() {
    let dir = tempfile::tempdir().unwrap();
    let poses = [[0.0, 0.0, 0.0], [1.0, 1.0, FRAC_PI_2], [2.0, 0.0, PI]];
    let csv = format!(
        "x,y,angle\n{}",
        poses
            .iter()
            .map(|p| format!("{:?},{:?},{:?}", p[0], p[1], p[2]))
            .collect::<Vec<_>>()
            .join("\n")
    );
    let f = write(&dir, "poses.csv", &csv);
    let o = dir.path().join("mg.mech");
    let o = o.to_str().unwrap();
    let run = mech()
        .args([
            "synth",
            "motion",
            &f,
            "-o",
            o,
            "--circle-points",
            "-1,2,1,2",
            "--format",
            "csv",
        ])
        .assert()
        .success();
    let table = rows(
        &run.get_output().stdout,
        "q,x,y,angle,P.x,P.y,coupler.angle",
    );
    mech().args(["check", o]).assert().success();
    let text = std::fs::read_to_string(o).unwrap();
    assert!(
        text.contains("O2: (2.0") || text.contains("O2: (1.99999"),
        "{text}"
    );
    for (r, p) in table.iter().zip(&poses) {
        assert!(
            (r[4] - p[0]).abs() < 1e-12 && (r[5] - p[1]).abs() < 1e-12,
            "{r:?}"
        );
        let c = solve(o, r[0]);
        assert!(
            (c["P.x"] - p[0]).abs() < 1e-12 && (c["P.y"] - p[1]).abs() < 1e-12,
            "{c:?}"
        );
        assert!(wrap(c["coupler.angle"] - p[2]).abs() < 1e-12, "{c:?}");
    }
}

/// Five poses of a four-bar: the Burmester points give it back; the default three-pose
/// choice needs no flag.
#[test]
fn motion_through_five_poses_and_three_by_default() {
    let dir = tempfile::tempdir().unwrap();
    // Poses of the four-bar O2 (0, 0), A (0, 0.1), B (0.25, 0.2), O4 (0.3, 0),
    // P (0.1, 0.3), from mech-core: written out by `mech solve` here.
    let fb = "pub struct Known {
        ground { O2: (0.0, 0.0), O4: (0.3, 0.0) },
        link crank { points { O2, A: (0.0, 0.1) } },
        link coupler { points { A, B: (0.25, 0.2), P: (0.1, 0.3) } },
        link rocker { points { O4, B } },
        joints { O2: revolute(ground, crank), A: revolute(crank, coupler), B: revolute(coupler, rocker), O4: revolute(ground, rocker) },
        input: O2,
    }";
    let k = write(&dir, "known.mech", fb);
    let poses: Vec<[f64; 3]> = [0.0, 0.7, 1.3, 2.0, 2.8]
        .iter()
        .map(|&q| {
            let c = solve(&k, q);
            [c["P.x"], c["P.y"], c["coupler.angle"]]
        })
        .collect();
    let csv = |ps: &[[f64; 3]]| {
        format!(
            "angle,x,y\n{}",
            ps.iter()
                .map(|p| format!("{:?},{:?},{:?}", p[2], p[0], p[1]))
                .collect::<Vec<_>>()
                .join("\n")
        )
    };
    for n in [5, 3] {
        let f = write(&dir, "p.csv", &csv(&poses[..n]));
        let o = dir.path().join("out.mech");
        let o = o.to_str().unwrap();
        let run = mech()
            .args(["synth", "motion", &f, "-o", o, "--format", "csv"])
            .assert()
            .success();
        let table = rows(
            &run.get_output().stdout,
            "q,x,y,angle,P.x,P.y,coupler.angle",
        );
        mech().args(["check", o]).assert().success();
        for (r, p) in table.iter().zip(&poses) {
            let c = solve(o, r[0]);
            assert!(
                (c["P.x"] - p[0]).abs() < 1e-11 && (c["P.y"] - p[1]).abs() < 1e-11,
                "{n}: {c:?} vs {p:?}"
            );
        }
    }
}

/// Bad input is a usage error (status 2) that names the fix.
#[test]
fn bad_targets_are_usage_errors() {
    let dir = tempfile::tempdir().unwrap();
    let o = dir.path().join("x.mech");
    let o = o.to_str().unwrap();
    let cases: [(&str, &str, &[&str], &str); 8] = [
        (
            "function",
            "input,output\n0.1,0.2\n0.3,0.4\n",
            &[],
            "at least 3",
        ),
        (
            "function",
            "input,output\n0.1,0.2\n0.3,nan\n0.5,0.6\n",
            &[],
            "not a finite number",
        ),
        (
            "function",
            "input,output\n0.1,0.7\n0.3,0.7\n0.5,0.7\n",
            &[],
            "singular",
        ),
        ("function", "in,out\n0.1,0.2\n", &[], "no column `input`"),
        (
            "function",
            "input,output\n0.1,0.2\n0.3,0.4\n0.1,0.6\n",
            &["--frame", "-2"],
            "--frame",
        ),
        (
            "motion",
            "x,y,angle\n0,0,0\n1,1,0.5\n0,0,0\n",
            &[],
            "coincide",
        ),
        (
            "motion",
            "x,y,angle\n0,0,0\n1,1,0.5\n2,0,1\n",
            &["--circle-points", "1,2,3"],
            "four",
        ),
        ("motion", "x,y\n0,0\n", &[], "no column `angle`"),
    ];
    for (cmd, text, extra, want) in cases {
        let f = write(&dir, "t.csv", text);
        let out = mech()
            .args(["synth", cmd, &f, "-o", o])
            .args(extra)
            .assert()
            .code(2);
        let err = String::from_utf8(out.get_output().stderr.clone()).unwrap();
        assert!(err.contains(want), "{cmd} {text:?}: {err}");
        assert!(
            !std::path::Path::new(o).exists(),
            "written despite the error"
        );
    }
}
