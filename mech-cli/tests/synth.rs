//! `mech synth path`: targets sampled from a crank-rocker's coupler curve give a file that
//! `mech check`, `solve` and `draw` take, with the printed error E < 1e-10 m² and every
//! target within reach of the file's coupler point P; the same seed writes the same file;
//! prescribed timing reads the `angle` column; and bad input (too few, coincident or
//! non-finite targets, a missing angle column, an open path for a six-bar, bounds out of
//! range, constraints no four-bar meets) is refused with a message that names it; targets
//! on a Stephenson III six-bar's curve give a six-bar file whose tracer meets them.

use assert_cmd::Command;

fn mech() -> Command {
    Command::cargo_bin("mech").unwrap()
}

/// The crank-rocker O2 (0, 0), O4 (0.3, 0), crank 0.1, coupler 0.269, rocker 0.206 m,
/// drawn with A (0, 0.1), B (0.25, 0.2), P (0.1, 0.3).
const KNOWN: &str = "pub struct Known {
    ground { O2: (0.0, 0.0), O4: (0.3, 0.0) },
    link crank { points { O2, A: (0.0, 0.1) } },
    link coupler { points { A, B: (0.25, 0.2), P: (0.1, 0.3) } },
    link rocker { points { O4, B } },
    joints {
        O2: revolute(ground, crank),
        A: revolute(crank, coupler),
        B: revolute(coupler, rocker),
        O4: revolute(ground, rocker),
    },
    input: O2,
}";

/// P of `file` at `steps` + 1 inputs from `from` to `to` (rad), by `mech sweep`.
fn p_of(file: &str, from: f64, to: f64, steps: usize) -> Vec<[f64; 2]> {
    let out = mech()
        .args([
            "sweep",
            file,
            "--from",
            &from.to_string(),
            "--to",
            &to.to_string(),
        ])
        .args([
            "--steps",
            &steps.to_string(),
            "--level",
            "pose",
            "--format",
            "csv",
        ])
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let text = String::from_utf8(out.stdout).unwrap();
    let mut lines = text.lines();
    let head: Vec<&str> = lines.next().unwrap().split(',').collect();
    let (ix, iy) = (
        head.iter().position(|h| *h == "P.x").unwrap(),
        head.iter().position(|h| *h == "P.y").unwrap(),
    );
    lines
        .map(|l| {
            let f: Vec<f64> = l.split(',').map(|v| v.parse().unwrap()).collect();
            [f[ix], f[iy]]
        })
        .collect()
}

/// Writes `name` in `dir` with `text`; its path.
fn write(dir: &tempfile::TempDir, name: &str, text: &str) -> String {
    let path = dir.path().join(name);
    std::fs::write(&path, text).unwrap();
    path.to_str().unwrap().to_string()
}

/// Ten targets on the known curve at crank angles θ = 0.1 + 2πk/10 (the input q of a
/// file whose input has no `from` is θ itself, and the frame line is along x, so the
/// `angle` column is θ too).
fn targets(dir: &tempfile::TempDir) -> (String, Vec<[f64; 2]>) {
    let known = write(dir, "known.mech", KNOWN);
    let thetas: Vec<f64> = (0..10)
        .map(|k| 0.1 + std::f64::consts::TAU * k as f64 / 10.0)
        .collect();
    let pts: Vec<[f64; 2]> = thetas.iter().map(|&q| p_of(&known, q, q, 0)[0]).collect();
    let mut csv = String::from("# ten points of a crank-rocker's coupler curve\nx,y,angle\n");
    for (p, q) in pts.iter().zip(&thetas) {
        csv += &format!("{:?},{:?},{:?}\n", p[0], p[1], q);
    }
    (write(dir, "targets.csv", &csv), pts)
}

/// The value of the `error` column of a CSV output.
fn error_of(stdout: &[u8]) -> f64 {
    let text = String::from_utf8(stdout.to_vec()).unwrap();
    let mut lines = text.lines();
    assert_eq!(lines.next().unwrap(), "error,rms,transmission,ratio");
    lines
        .next()
        .unwrap()
        .split(',')
        .next()
        .unwrap()
        .parse()
        .unwrap()
}

#[test]
fn a_path_on_a_four_bars_curve_gives_a_file_check_solve_and_draw_take() {
    let dir = tempfile::tempdir().unwrap();
    let (csv, pts) = targets(&dir);
    let out_file = dir.path().join("synth.mech");
    let out = mech()
        .args([
            "synth",
            "path",
            &csv,
            "--evaluations",
            "60000",
            "--format",
            "csv",
            "-o",
        ])
        .arg(&out_file)
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr).to_string();
    assert!(out.status.success(), "{stderr}");
    let e = error_of(&out.stdout);
    assert!(e < 1e-10, "E = {e}");
    assert!(stderr.contains("evaluations/s"), "{stderr}");
    assert!(stderr.contains("the angle column is not used"), "{stderr}");
    let file = out_file.to_str().unwrap();
    let check = mech().args(["check", file]).output().unwrap();
    assert!(
        check.status.success(),
        "{}",
        String::from_utf8_lossy(&check.stdout)
    );
    let text = std::fs::read_to_string(file).unwrap();
    for name in ["O2:", "O4:", "A:", "B:", "P:", "input: O2"] {
        assert!(text.contains(name), "{name} in {text}");
    }
    assert!(mech()
        .args(["solve", file, "--at", "0.3"])
        .output()
        .unwrap()
        .status
        .success());
    let svg = dir.path().join("synth.svg");
    let draw = mech()
        .args(["draw", file, "--at", "0", "--path", "P", "-o"])
        .arg(&svg)
        .output()
        .unwrap();
    assert!(
        draw.status.success(),
        "{}",
        String::from_utf8_lossy(&draw.stderr)
    );
    // Every target within reach of the file's coupler curve (sampled every 0.1°: half a
    // step of this curve is under 2e-4 m).
    let curve = p_of(file, 0.0, std::f64::consts::TAU, 3600);
    for t in &pts {
        let d = curve
            .iter()
            .map(|c| ((c[0] - t[0]).powi(2) + (c[1] - t[1]).powi(2)).sqrt())
            .fold(f64::INFINITY, f64::min);
        assert!(d < 5e-4, "{t:?}: {d}");
    }
}

/// A Stephenson III six-bar: `KNOWN`'s four-bar with C at its coupler point driving the
/// dyad C D O6, the tracer P on C D (it assembles over the whole turn).
const KNOWN6: &str = "pub struct Known6 {
    ground { O2: (0.0, 0.0), O4: (0.3, 0.0), O6: (0.1, 0.6) },
    link crank { points { O2, A: (0.0, 0.1) } },
    link coupler { points { A, B: (0.25, 0.2), C: (0.1, 0.3) } },
    link rocker { points { O4, B } },
    link tracer { points { C, D: (0.35, 0.55), P: (0.3, 0.4) } },
    link rocker6 { points { O6, D } },
    joints {
        O2: revolute(ground, crank),
        A: revolute(crank, coupler),
        B: revolute(coupler, rocker),
        O4: revolute(ground, rocker),
        C: revolute(coupler, tracer),
        D: revolute(tracer, rocker6),
        O6: revolute(ground, rocker6),
    },
    input: O2,
}";

/// Twelve targets on the six-bar's tracer curve: `--topology six-bar` writes a six-bar
/// (the SPEC names and C, D, O6) that `mech check` takes, with E below 1e-4 of the path's
/// size squared, and the printed E is the file's own: recomputed from `mech sweep`'s P
/// over a turn at 3600 inputs, the root of the sum of the squared nearest distances
/// differs from √E by at most √12 half-steps of the sampled curve.
#[test]
fn a_path_on_a_six_bars_curve_gives_a_six_bar_file() {
    let dir = tempfile::tempdir().unwrap();
    let known = write(&dir, "known6.mech", KNOWN6);
    let pts: Vec<[f64; 2]> = (0..12)
        .map(|k| {
            let q = 0.2 + std::f64::consts::TAU * k as f64 / 12.0;
            p_of(&known, q, q, 0)[0]
        })
        .collect();
    let mut csv = String::from("x,y\n");
    for p in &pts {
        csv += &format!("{:?},{:?}\n", p[0], p[1]);
    }
    let csv = write(&dir, "six.csv", &csv);
    let out_file = dir.path().join("six.mech");
    let out = mech()
        .args(["synth", "path", &csv, "--topology", "six-bar"])
        .args(["--evaluations", "40000", "--transmission", "10", "--ratio", "20"])
        .args(["--format", "csv", "-o"])
        .arg(&out_file)
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr).to_string();
    assert!(out.status.success(), "{stderr}");
    assert!(stderr.contains("six-bar (Stephenson III)"), "{stderr}");
    let e = error_of(&out.stdout);
    let size = 0.4;
    assert!(e < 1e-4 * size * size, "E = {e}");
    let file = out_file.to_str().unwrap();
    let check = mech().args(["check", file]).output().unwrap();
    let report = String::from_utf8_lossy(&check.stdout).to_string();
    assert!(check.status.success(), "{report}");
    assert_eq!(report.matches("RRR dyad").count(), 2, "{report}");
    let text = std::fs::read_to_string(file).unwrap();
    for name in ["O2:", "O4:", "O6:", "A:", "B:", "C:", "D:", "P:", "input: O2", "--topology six-bar"] {
        assert!(text.contains(name), "{name} in {text}");
    }
    let curve = p_of(file, 0.0, std::f64::consts::TAU, 3600);
    let dense: f64 = pts
        .iter()
        .map(|t| {
            curve
                .iter()
                .map(|c| (c[0] - t[0]).powi(2) + (c[1] - t[1]).powi(2))
                .fold(f64::INFINITY, f64::min)
        })
        .sum();
    let step = curve
        .windows(2)
        .map(|w| ((w[1][0] - w[0][0]).powi(2) + (w[1][1] - w[0][1]).powi(2)).sqrt())
        .fold(0.0, f64::max);
    assert!(
        dense >= e * (1.0 - 1e-9) - 1e-18 && dense.sqrt() - e.sqrt() <= 12f64.sqrt() * 0.5 * step,
        "E = {e}, sampled {dense}, step {step}"
    );
}

#[test]
fn the_same_seed_writes_the_same_file() {
    let dir = tempfile::tempdir().unwrap();
    let (csv, _) = targets(&dir);
    let run = |seed: &str, name: &str| {
        let f = dir.path().join(name);
        let out = mech()
            .args([
                "synth",
                "path",
                &csv,
                "--evaluations",
                "2000",
                "--seed",
                seed,
                "-o",
            ])
            .arg(&f)
            .output()
            .unwrap();
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
        std::fs::read_to_string(f).unwrap()
    };
    let (a, b, c) = (run("5", "a.mech"), run("5", "b.mech"), run("6", "c.mech"));
    assert_eq!(a, b);
    assert_ne!(a, c);
}

#[test]
fn prescribed_timing_reads_the_angle_column() {
    let dir = tempfile::tempdir().unwrap();
    let (csv, _) = targets(&dir);
    let out = mech()
        .args([
            "synth",
            "path",
            &csv,
            "--timing",
            "prescribed",
            "--evaluations",
            "60000",
        ])
        .args(["--format", "csv", "-o"])
        .arg(dir.path().join("p.mech"))
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let e = error_of(&out.stdout);
    assert!(e < 1e-10, "E = {e}");
}

/// Runs `mech synth path` on a targets text with extra arguments; (status, stderr).
fn refused(text: &str, extra: &[&str]) -> (i32, String) {
    let dir = tempfile::tempdir().unwrap();
    let csv = write(&dir, "t.csv", text);
    let out = mech()
        .args(["synth", "path", &csv, "--evaluations", "2000"])
        .args(extra)
        .arg("-o")
        .arg(dir.path().join("o.mech"))
        .output()
        .unwrap();
    assert!(!dir.path().join("o.mech").exists());
    (
        out.status.code().unwrap(),
        String::from_utf8_lossy(&out.stderr).to_string(),
    )
}

#[test]
fn bad_input_is_refused_with_what_to_change() {
    let three = "x,y\n0,0\n1,0\n0,1\n";
    for (text, extra, status, says) in [
        (
            "x,y\n0,0\n1,0\n",
            &[][..],
            2,
            "2 target(s): a path needs at least 3",
        ),
        ("x,y\n0,0\n1,0\n0,0\n", &[], 2, "coincide at (0, 0) m"),
        ("x,y\n0,0\n1,nan\n0,1\n", &[], 2, "not a finite number"),
        ("x,y\n0,0\n1,zero\n0,1\n", &[], 2, "not a number"),
        ("a,b\n0,0\n1,0\n0,1\n", &[], 2, "the columns `x` and `y`"),
        (
            three,
            &["--timing", "prescribed"],
            2,
            "needs the crank angle of each target",
        ),
        (three, &["--topology", "six-bar", "--open"], 2, "closed paths"),
        (three, &["--transmission", "95"], 2, "out of range"),
        (three, &["--ratio", "0.5"], 2, "out of range"),
        (three, &["--ratio", "1"], 1, "binds"),
    ] {
        let (code, stderr) = refused(text, extra);
        assert_eq!(code, status, "{extra:?}: {stderr}");
        assert!(
            stderr.contains(says),
            "{extra:?}: `{says}` not in: {stderr}"
        );
    }
}

#[test]
fn hostile_target_files_are_refused() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let bytes = |name: &str, b: &[u8]| {
        let p = d.join(name);
        std::fs::write(&p, b).unwrap();
        p.to_str().unwrap().to_string()
    };
    let many = {
        let mut t = String::from("x,y\n");
        for k in 0..10_001 {
            t += &format!("{k},{}\n", k % 7);
        }
        t
    };
    for (file, says) in [
        (
            bytes("latin1.csv", b"x,y\n0,0\ncaf\xe9,1\n"),
            "is not UTF-8 text",
        ),
        (bytes("nul.csv", &[0u8; 64]), "is a binary file"),
        (bytes("empty.csv", b""), "the columns `x` and `y`"),
        (
            bytes("many.csv", many.as_bytes()),
            "more than 10000 targets",
        ),
        (d.to_str().unwrap().to_string(), "is a directory"),
        (
            d.join("missing.csv").to_str().unwrap().to_string(),
            "cannot read",
        ),
    ] {
        let out = mech()
            .args(["synth", "path", &file, "-o"])
            .arg(d.join("o.mech"))
            .output()
            .unwrap();
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{file}: {stderr}");
        assert!(stderr.contains(says), "{file}: `{says}` not in {stderr}");
    }
}
