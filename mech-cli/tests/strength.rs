//! `mech strength`: a slider-crank held still (`--speed 0`) against a piston force, whose
//! rod is a two-force member: its largest stress P/(A cos φ) (sin φ = r sin θ / l) over
//! the instants, its pins' shear R/(n π d²/4), against the hand calculation; the formats
//! and the errors that name the fix.

use assert_cmd::Command;

const R: f64 = 0.05;
const L: f64 = 0.2;
const PI: f64 = std::f64::consts::PI;

const SLIDER_CRANK: &str = "pub struct SliderCrank {
    ground { O: (0.0, 0.0) },
    link crank { points { O, A: (50 mm, 0.0) }, shape: bar(width 20 mm, thickness 10 mm), material: steel },
    link rod { points { A, B: (250 mm, 0.0) }, shape: rod(diameter 16 mm), material: aluminium },
    link piston { points { B }, mass: 0.5, cg: B },
    joints {
        O: revolute(ground, crank) pin 12 mm,
        A: revolute(crank, rod) pin 10 mm double,
        B: revolute(rod, piston),
        slide: prismatic(ground, piston) at B along (1.0, 0.0),
    },
    input: O,
    loads { P: force on piston at B },
}";

fn mech() -> Command {
    Command::cargo_bin("mech").unwrap()
}

fn write(dir: &tempfile::TempDir, text: &str) -> String {
    let path = dir.path().join("m.mech");
    std::fs::write(&path, text).unwrap();
    path.to_str().unwrap().to_string()
}

/// The rows of a CSV output: (member, criterion, the five numbers).
fn rows(out: &[u8]) -> Vec<(String, String, Vec<f64>)> {
    let text = String::from_utf8(out.to_vec()).unwrap();
    let mut lines = text.lines();
    assert_eq!(
        lines.next().unwrap(),
        "member,criterion,stress_max,stress_mean,stress_alt,safety,q"
    );
    lines
        .map(|l| {
            let f: Vec<&str> = l.split(',').collect();
            (
                f[0].to_string(),
                f[1].to_string(),
                f[2..].iter().map(|v| v.parse().unwrap()).collect(),
            )
        })
        .collect()
}

#[test]
fn a_slider_crank_at_rest_against_the_hand_calculation() {
    let dir = tempfile::tempdir().unwrap();
    let f = write(&dir, SLIDER_CRANK);
    let out = mech()
        .args([
            "strength", &f, "--load", "P=-2kN,0", "--steps", "12", "--all", "--format", "csv",
        ])
        .assert()
        .success();
    let rows = rows(&out.get_output().stdout);
    let p = 2000.0;
    let rod_max = (0..12)
        .map(|k| {
            let t = 2.0 * PI * k as f64 / 12.0;
            p / (R * t.sin() / L).asin().cos()
        })
        .fold(0.0, f64::max);
    let find = |m: &str, c: &str| {
        rows.iter()
            .find(|r| r.0 == m && r.1 == c)
            .unwrap_or_else(|| panic!("no row {m} {c} in {rows:?}"))
            .2
            .clone()
    };
    let area = PI * 0.016f64.powi(2) / 4.0;
    let axial = find("rod", "axial");
    assert!(
        (axial[0] - rod_max / area).abs() < 1e-9 * axial[0],
        "{axial:?}"
    );
    assert!(
        (axial[3] - 276e6 / (rod_max / area)).abs() < 1e-9 * axial[3],
        "aluminium's S_y"
    );
    let shear = find("A.pin", "shear");
    assert!((shear[0] - rod_max / (2.0 * PI * 0.01f64.powi(2) / 4.0)).abs() < 1e-9 * shear[0]);
    // B has no pin, the piston no section: four members, each with its checks.
    assert!(rows
        .iter()
        .all(|r| ["crank", "rod", "O.pin", "A.pin"].contains(&r.0.as_str())));
    // Without --all: one row per member, the smallest factor of its checks.
    let out = mech()
        .args([
            "strength", &f, "--load", "P=-2kN,0", "--steps", "12", "--format", "csv",
        ])
        .assert()
        .success();
    let governing = self::rows(&out.get_output().stdout);
    assert_eq!(governing.len(), 4);
    for g in &governing {
        let least = rows
            .iter()
            .filter(|r| r.0 == g.0)
            .map(|r| r.2[3])
            .fold(f64::INFINITY, f64::min);
        assert_eq!(g.2[3], least, "{g:?}");
    }
    let stderr = String::from_utf8(out.get_output().stderr.clone()).unwrap();
    assert!(stderr.contains("worst: "), "{stderr}");
}

#[test]
fn json_and_table_carry_the_same_members() {
    let dir = tempfile::tempdir().unwrap();
    let f = write(&dir, SLIDER_CRANK);
    let out = mech()
        .args([
            "strength", &f, "--speed", "300rpm", "--load", "P=-2kN,0", "--steps", "36", "--format",
            "json",
        ])
        .assert()
        .success();
    let v: serde_json::Value = serde_json::from_slice(&out.get_output().stdout).unwrap();
    let names: Vec<&str> = v
        .as_array()
        .unwrap()
        .iter()
        .map(|r| r["member"].as_str().unwrap())
        .collect();
    assert_eq!(names, ["crank", "rod", "O.pin", "A.pin"]);
    let table = mech()
        .args([
            "strength", &f, "--speed", "300rpm", "--load", "P=-2kN,0", "--steps", "36",
        ])
        .assert()
        .success();
    let text = String::from_utf8(table.get_output().stdout.clone()).unwrap();
    assert!(
        text.lines().next().unwrap().contains("stress_max [Pa]"),
        "{text}"
    );
    assert!(text.contains("worst: "), "{text}");
}

#[test]
fn errors_name_the_fix() {
    let dir = tempfile::tempdir().unwrap();
    let bare = write(
        &dir,
        "pub struct Bare {
            ground { O: (0.0, 0.0) },
            link crank { points { O, A: (0.1, 0.0) }, mass: 1.0, cg: O },
            joints { O: revolute(ground, crank) },
            input: O,
        }",
    );
    let out = mech().args(["strength", &bare]).assert().failure();
    let e = String::from_utf8(out.get_output().stderr.clone()).unwrap();
    assert!(
        e.contains("no member to check") && e.contains("pin 12 mm"),
        "{e}"
    );
    let f = write(&dir, SLIDER_CRANK);
    let out = mech()
        .args(["strength", &f, "--steps", "1"])
        .assert()
        .failure();
    let e = String::from_utf8(out.get_output().stderr.clone()).unwrap();
    assert!(e.contains("--steps 1"), "{e}");
}

/// `mech size`: the crank's width free; the table of passes ends on a repeated pass, the
/// written file has the number in place of `free(..)` and re-checks with every factor ≥ S.
#[test]
fn size_writes_a_file_that_meets_the_factor() {
    let dir = tempfile::tempdir().unwrap();
    let f = write(
        &dir,
        &SLIDER_CRANK.replace("bar(width 20 mm,", "bar(width free(15 mm..60 mm),"),
    );
    let out_file = dir.path().join("sized.mech");
    let out = mech()
        .args([
            "size",
            &f,
            "--safety",
            "2.5",
            "--speed",
            "30",
            "--load",
            "P=-3kN,0",
            "--steps",
            "72",
            "--irregularity",
            "0.05",
            "--format",
            "csv",
            "-o",
            out_file.to_str().unwrap(),
        ])
        .assert()
        .success();
    let text = String::from_utf8(out.get_output().stdout.clone()).unwrap();
    let mut lines = text.lines();
    assert_eq!(
        lines.next().unwrap(),
        "iteration,total_mass,peak_torque,flywheel,worst"
    );
    let passes: Vec<Vec<f64>> = lines
        .map(|l| l.split(',').map(|v| v.parse().unwrap()).collect())
        .collect();
    assert!(passes.len() >= 2, "{text}");
    let (a, b) = (&passes[passes.len() - 2], &passes[passes.len() - 1]);
    assert_eq!(
        a[1..],
        b[1..],
        "the fixed point: the last pass changes nothing"
    );
    assert!(b[4] >= 2.5, "{b:?}");
    let stderr = String::from_utf8(out.get_output().stderr.clone()).unwrap();
    assert!(stderr.contains("crank.width = "), "{stderr}");
    let sized = std::fs::read_to_string(&out_file).unwrap();
    assert!(
        !sized.contains("free(") && sized.contains("bar(width "),
        "{sized}"
    );
    let check = mech()
        .args([
            "strength",
            out_file.to_str().unwrap(),
            "--speed",
            "30",
            "--load",
            "P=-3kN,0",
            "--steps",
            "72",
            "--format",
            "csv",
        ])
        .assert()
        .success();
    for (m, c, v) in rows(&check.get_output().stdout) {
        assert!(v[3] >= 2.5 * (1.0 - 1e-9), "{m} {c}: {v:?}");
    }
    // Nothing free: an error naming the form.
    let plain = write(&dir, SLIDER_CRANK);
    let out = mech()
        .args([
            "size",
            &plain,
            "--safety",
            "2",
            "-o",
            out_file.to_str().unwrap(),
        ])
        .assert()
        .failure();
    let e = String::from_utf8(out.get_output().stderr.clone()).unwrap();
    assert!(e.contains("free(10 mm..40 mm)"), "{e}");
}
