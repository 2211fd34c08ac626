//! Spatial mechanisms (SPEC 3i) on the command line: `mech solve` and `mech sweep` against
//! `SpatialMechanism` called directly (the RSSR of mech-core/tests/spatial.rs, written to a
//! `.mech` file), against the 50-digit mpmath table of the double-wishbone suspension, and
//! a load's effect on the driver against virtual work; `mech check`'s count and its
//! messages; `mech draw`'s isometric picture, its paths and reaction arrows, `mech animate`'s
//! paths; the errors for planar-style arguments.

use assert_cmd::Command;
use mech_core::spatial::{SpatialLoads, SpatialMechanism};
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

fn mech() -> Command {
    Command::cargo_bin("mech").unwrap()
}

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("..")
}

/// The RSSR of mech-core/tests/spatial.rs (its `const RSSR`).
fn rssr_text() -> String {
    let source = include_str!("../../mech-core/tests/spatial.rs");
    let start = source.find("const RSSR: &str = r#\"").unwrap() + "const RSSR: &str = r#\"".len();
    let end = start + source[start..].find("\"#;").unwrap();
    source[start..end].to_string()
}

/// The RSSR written to a `.mech` file in `dir`.
fn rssr_file(dir: &tempfile::TempDir, text: &str) -> PathBuf {
    let path = dir.path().join("rssr.mech");
    std::fs::write(&path, text).unwrap();
    path
}

/// The rows of a CSV output as (header, rows).
fn csv_rows(out: &[u8]) -> (Vec<String>, Vec<Vec<f64>>) {
    let text = String::from_utf8(out.to_vec()).unwrap();
    let mut lines = text.lines();
    let head: Vec<String> = lines
        .next()
        .unwrap()
        .split(',')
        .map(str::to_string)
        .collect();
    let rows = lines
        .map(|l| l.split(',').map(|v| v.parse().unwrap()).collect())
        .collect();
    (head, rows)
}

/// One CSV row as a map of column name to value.
fn csv_map(out: &[u8]) -> BTreeMap<String, f64> {
    let (head, rows) = csv_rows(out);
    assert_eq!(rows.len(), 1);
    head.into_iter().zip(rows[0].iter().copied()).collect()
}

/// The columns the library gives directly at (q, q̇, q̈) under `loads`: every column of
/// docs/cli.md's spatial table, computed without the columns module.
fn library_row(
    m: &SpatialMechanism,
    q: f64,
    qd: f64,
    qdd: f64,
    loads: &SpatialLoads,
) -> BTreeMap<String, f64> {
    let model = m.model();
    let mo = m.kinematics(&[q], &[qd], &[qdd]).unwrap();
    let f = m.kinetostatics(&mo, loads).unwrap();
    let mut r = BTreeMap::new();
    r.insert("q".to_string(), q);
    for (p, _) in &model.points {
        let [pos, vel, acc] = mo.point_motion(p).unwrap();
        for (k, s) in ["x", "y", "z"].iter().enumerate() {
            r.insert(format!("{p}.{s}"), pos[k]);
            r.insert(format!("{p}.v{s}"), vel[k]);
            r.insert(format!("{p}.a{s}"), acc[k]);
        }
    }
    for b in &model.bodies[1..] {
        let l = mo.link(&b.name).unwrap();
        let qn = l.rotation.quaternion();
        for (s, v) in [("qw", qn.w), ("qx", qn.i), ("qy", qn.j), ("qz", qn.k)] {
            r.insert(format!("{}.{s}", b.name), v);
        }
        for (k, s) in ["x", "y", "z"].iter().enumerate() {
            r.insert(format!("{}.omega_{s}", b.name), l.omega[k]);
            r.insert(format!("{}.alpha_{s}", b.name), l.alpha[k]);
        }
    }
    for j in &model.joints {
        let re = f.reaction(&j.name).unwrap();
        for (k, s) in ["x", "y", "z"].iter().enumerate() {
            r.insert(format!("{}.f{s}", j.name), re.force[k]);
            r.insert(format!("{}.m{s}", j.name), re.moment[k]);
        }
    }
    r.insert("driver".into(), f.driver());
    r.insert(
        "virtual_power".into(),
        m.driver_action(&mo, loads).unwrap()[0],
    );
    let z = m.reduced(q).unwrap();
    r.insert("inertia".into(), z.inertia);
    r.insert("inertia_derivative".into(), z.inertia_derivative);
    r.insert("moment".into(), m.reduced_moment(q, loads).unwrap());
    r
}

/// Every column of `got` equals the library's to 1e-12 of its kind's scale, and the
/// columns are exactly the library's.
fn assert_same(got: &BTreeMap<String, f64>, want: &BTreeMap<String, f64>, what: &str) {
    assert_eq!(
        got.keys().collect::<Vec<_>>(),
        want.keys().collect::<Vec<_>>(),
        "{what}: the columns"
    );
    let scale = want.values().fold(1e-3f64, |s, v| s.max(v.abs()));
    for (k, w) in want {
        let g = got[k];
        assert!(
            (g - w).abs() <= 1e-12 * scale.max(w.abs()),
            "{what}: {k} = {g}, the library gives {w}"
        );
    }
}

const LOADS: [&str; 2] = ["tool=0.5,-1.0,2.0", "push=4,-3,2.5"];

fn library_loads(m: &SpatialMechanism) -> SpatialLoads {
    let mut l = m.loads();
    assert!(l.set_by_name("tool", &[0.5, -1.0, 2.0]));
    assert!(l.set_by_name("push", &[4.0, -3.0, 2.5]));
    l
}

#[test]
fn the_example_rssr_is_the_core_tests_rssr() {
    let example = std::fs::read_to_string(root().join("examples/mech/rssr.mech")).unwrap();
    let body: String = example
        .lines()
        .filter(|l| !l.starts_with("///"))
        .map(|l| format!("{l}\n"))
        .collect();
    assert_eq!(body.trim(), rssr_text().trim());
}

#[test]
fn solve_gives_the_librarys_numbers() {
    let dir = tempfile::tempdir().unwrap();
    let file = rssr_file(&dir, &rssr_text());
    let out = mech()
        .arg("solve")
        .arg(&file)
        .args([
            "--at", "0.7", "--speed", "3", "--accel", "-2", "--format", "csv",
        ])
        .args(LOADS.iter().flat_map(|l| ["--load", l]))
        .assert()
        .success()
        .get_output()
        .stdout
        .clone();
    let got = csv_map(&out);
    let m = SpatialMechanism::from_dsl(&rssr_text()).unwrap();
    let want = library_row(&m, 0.7, 3.0, -2.0, &library_loads(&m));
    assert_same(&got, &want, "solve");
    // SPEC 3i's columns are there, and the two routes to the torque agree.
    for c in ["B.z", "A.fz", "A.mx", "A.my", "A.mz", "driver"] {
        assert!(got.contains_key(c), "{c}");
    }
    assert!((got["driver"] - got["virtual_power"]).abs() < 1e-9 * got["driver"].abs());
    // A spherical joint carries no moment; a revolute's is normal to its axis (x at O).
    assert_eq!((got["A.mx"], got["A.my"], got["A.mz"]), (0.0, 0.0, 0.0));
    assert!(got["O.mx"].abs() < 1e-9 * (got["O.my"].abs() + got["O.mz"].abs()));

    // JSON has the same keys and numbers; the table one quantity a line with its unit.
    let json = mech()
        .arg("solve")
        .arg(&file)
        .args([
            "--at", "0.7", "--speed", "3", "--accel", "-2", "--format", "json",
        ])
        .args(LOADS.iter().flat_map(|l| ["--load", l]))
        .assert()
        .success()
        .get_output()
        .stdout
        .clone();
    let v: serde_json::Value = serde_json::from_slice(&json).unwrap();
    let obj = v[0].as_object().unwrap();
    assert_eq!(obj.len(), got.len());
    for (k, x) in obj {
        assert_eq!(x.as_f64().unwrap(), got[k], "{k}");
    }
    let table = mech()
        .arg("solve")
        .arg(&file)
        .args(["--at", "40deg", "--level", "kinematics"])
        .assert()
        .success()
        .get_output()
        .stdout
        .clone();
    let table = String::from_utf8(table).unwrap();
    let line = |name: &str| {
        table
            .lines()
            .find(|l| l.split_whitespace().next() == Some(name))
            .unwrap_or_else(|| panic!("{name} in\n{table}"))
            .to_string()
    };
    assert!(line("B.az").ends_with("m/s²"), "{}", line("B.az"));
    assert!(line("rod.qw").ends_with(" 1"), "{}", line("rod.qw"));
    assert!(line("rocker.omega_z").ends_with("rad/s"));
    assert!(!table.contains("driver"), "no forces at level kinematics");
    let b = m.pose(&[40f64.to_radians()]).unwrap().point("B").unwrap();
    let printed: f64 = line("B.y")
        .split_whitespace()
        .nth(1)
        .unwrap()
        .parse()
        .unwrap();
    assert!(
        (printed - b.y).abs() <= 1e-11 * b.y.abs(),
        "{printed} vs {}",
        b.y
    );
}

#[test]
fn sweep_rows_are_the_librarys() {
    let dir = tempfile::tempdir().unwrap();
    let file = rssr_file(&dir, &rssr_text());
    let out = mech()
        .arg("sweep")
        .arg(&file)
        .args(["--from", "-30deg", "--to", "330deg", "--steps", "12"])
        .args(["--speed", "2", "--accel", "1.5", "--format", "csv"])
        .args(LOADS.iter().flat_map(|l| ["--load", l]))
        .assert()
        .success()
        .get_output()
        .stdout
        .clone();
    let (head, rows) = csv_rows(&out);
    assert_eq!(rows.len(), 13);
    let m = SpatialMechanism::from_dsl(&rssr_text()).unwrap();
    let loads = library_loads(&m);
    for (k, row) in rows.iter().enumerate() {
        let q = (-30.0 + 30.0 * k as f64).to_radians();
        let got: BTreeMap<String, f64> = head.iter().cloned().zip(row.iter().copied()).collect();
        assert!((got["q"] - q).abs() < 1e-15, "row {k}: q = {}", got["q"]);
        assert_same(
            &got,
            &library_row(&m, got["q"], 2.0, 1.5, &loads),
            &format!("row {k}"),
        );
    }
    // --level pose: positions and rotations only.
    let out = mech()
        .arg("sweep")
        .arg(&file)
        .args([
            "--from", "0", "--to", "1", "--steps", "2", "--level", "pose",
        ])
        .args(["--format", "csv"])
        .assert()
        .success()
        .get_output()
        .stdout
        .clone();
    let (head, rows) = csv_rows(&out);
    assert_eq!(head.len(), 1 + 3 * 4 + 4 * 3, "{head:?}");
    let pose = m.pose(&[0.5]).unwrap();
    let i = head.iter().position(|h| h == "B.z").unwrap();
    assert_eq!(rows[1][i], pose.point("B").unwrap().z);
}

#[test]
fn a_load_changes_the_driver_by_its_virtual_work() {
    let dir = tempfile::tempdir().unwrap();
    let file = rssr_file(&dir, &rssr_text());
    let solve = |extra: &[&str]| {
        csv_map(
            &mech()
                .arg("solve")
                .arg(&file)
                .args(["--at", "1.1", "--format", "csv"])
                .args(extra)
                .assert()
                .success()
                .get_output()
                .stdout
                .clone(),
        )
    };
    let without = solve(&[]);
    let with = solve(&["--load", "push=40N,-30N,25N"]);
    // Virtual work at rest: driver + F·v_B(q̇ = 1) = 0 for the load's share.
    let rates = solve(&["--speed", "1", "--level", "kinematics"]);
    let work = 40.0 * rates["B.vx"] - 30.0 * rates["B.vy"] + 25.0 * rates["B.vz"];
    let change = with["driver"] - without["driver"];
    assert!(work.abs() > 0.1, "the load does work: {work}");
    assert!(
        (change + work).abs() < 1e-10 * work.abs(),
        "driver change {change}, virtual work −{work}"
    );
    // ... and as the library says.
    let m = SpatialMechanism::from_dsl(&rssr_text()).unwrap();
    let mut loads = m.loads();
    loads.set_by_name("push", &[40.0, -30.0, 25.0]);
    let mo = m.pose(&[1.1]).unwrap();
    let lib = m.kinetostatics(&mo, &loads).unwrap().driver();
    assert!((with["driver"] - lib).abs() < 1e-12 * lib.abs());
}

#[test]
fn planar_arguments_on_a_spatial_file_name_the_fix() {
    let dir = tempfile::tempdir().unwrap();
    let file = rssr_file(&dir, &rssr_text());
    let err = |args: &[&str]| {
        let o = mech()
            .arg("solve")
            .arg(&file)
            .args(args)
            .assert()
            .failure()
            .code(2)
            .get_output()
            .stderr
            .clone();
        String::from_utf8(o).unwrap()
    };
    let e = err(&["--at", "0", "--load", "push=4,-3"]);
    assert!(
        e.contains("`4,-3` has 2 component(s)")
            && e.contains("a force on `rod` at `B`")
            && e.contains("three components `fx,fy,fz` (N)")
            && e.contains("--load push=4,-3,0"),
        "{e}"
    );
    let e = err(&["--at", "0", "--load", "tool=2"]);
    assert!(
        e.contains("`mx,my,mz` (N·m)") && e.contains("tool=2,0,0"),
        "{e}"
    );
    let e = err(&["--at", "0", "--load", "gas=1,2,3"]);
    assert!(
        e.contains("no load named `gas`") && e.contains("tool, push"),
        "{e}"
    );
    let e = err(&["--at", "0", "--load", "push=@table.csv"]);
    assert!(e.contains("table.csv"), "{e}");
    let e = err(&["--at", "0,1"]);
    assert!(e.contains("2 value(s) given for 1 input(s)"), "{e}");
    let e = err(&["--at", "30mm"]);
    assert!(e.contains("--at"), "{e}");
    // A command for planar mechanisms says so.
    let o = mech()
        .arg("balance")
        .arg(&file)
        .args(["--speed", "100", "-o"])
        .arg(dir.path().join("balanced.mech"))
        .assert()
        .failure()
        .code(1)
        .get_output()
        .stderr
        .clone();
    let e = String::from_utf8(o).unwrap();
    assert!(
        e.contains("a spatial mechanism") && e.contains("planar mechanisms only"),
        "{e}"
    );
}

#[test]
fn check_prints_kutzbachs_count_or_the_error_with_its_line() {
    let dir = tempfile::tempdir().unwrap();
    let file = rssr_file(&dir, &rssr_text());
    let o = mech()
        .arg("check")
        .arg(&file)
        .assert()
        .success()
        .get_output()
        .stdout
        .clone();
    let s = String::from_utf8(o).unwrap();
    assert!(s.contains("mechanism `Rssr`: valid (spatial)"), "{s}");
    // N = 4, P_I = 2 (the revolutes), P_III = 2 (the ball joints): G = 18 − 10 − 6 = 2.
    assert!(
        s.contains("P_I = 2, P_II = 0, P_III = 2")
            && s.contains("= 18 − 10 − 0 − 6 − 0 − 0 = 2")
            && s.contains(
                "link `rod` spins about the line through its spherical joints `A` and `B`"
            )
            && s.contains("G − idle = 1 = inputs declared: 1 (`O` (revolute))"),
        "{s}"
    );
    // The count off (no input): the numbers and the fix, status 1.
    let bad = rssr_file(&dir, &rssr_text().replace("input: O,", ""));
    let o = mech()
        .arg("check")
        .arg(&bad)
        .assert()
        .failure()
        .code(1)
        .get_output()
        .stderr
        .clone();
    let e = String::from_utf8(o).unwrap();
    assert!(
        e.starts_with(&format!(
            "{}: Kutzbach's count does not match the inputs",
            bad.display()
        )) && e.contains("of which 1 idle")
            && e.contains("declare 1 input(s)"),
        "{e}"
    );
    // A misspelt link: FILE:LINE:COLUMN, the line and a caret under the name.
    let text = rssr_text().replace("revolute(ground, rocker)", "revolute(ground, rocket)");
    let line = text.lines().position(|l| l.contains("rocket")).unwrap() + 1;
    let column = text.lines().nth(line - 1).unwrap().find("rocket").unwrap() + 1;
    let bad = rssr_file(&dir, &text);
    let o = mech()
        .arg("check")
        .arg(&bad)
        .assert()
        .failure()
        .code(1)
        .get_output()
        .stderr
        .clone();
    let e = String::from_utf8(o).unwrap();
    assert!(
        e.starts_with(&format!(
            "{}:{line}:{column}: unknown link `rocket`",
            bad.display()
        )),
        "{e}"
    );
    let caret = e.lines().find(|l| l.ends_with("^ here")).unwrap();
    let excerpt = e.lines().find(|l| l.contains("rocket)")).unwrap();
    assert_eq!(
        caret.find('^').unwrap() - caret.find('|').unwrap(),
        excerpt.find("rocket)").unwrap() - excerpt.find('|').unwrap(),
        "{e}"
    );
}

/// The numbers of the truth table (strings of 30 digits).
fn num(v: &serde_json::Value) -> f64 {
    v.as_str().unwrap().parse().unwrap()
}

#[test]
fn the_double_wishbone_example_matches_the_mpmath_table() {
    let truth: serde_json::Value = serde_json::from_str(
        &std::fs::read_to_string(root().join("tests/data/spatial/double_wishbone.truth.json"))
            .unwrap(),
    )
    .unwrap();
    let file = root().join("examples/mech/double_wishbone.mech");
    let example = std::fs::read_to_string(&file).unwrap();
    assert!(example.contains(truth["source"].as_str().unwrap().trim()));
    let load = |name: &str| {
        let v: Vec<String> = truth["loads"][name]
            .as_array()
            .unwrap()
            .iter()
            .map(|x| num(x).to_string())
            .collect();
        format!("{name}={}", v.join(","))
    };
    let (mut worst_pos, mut worst_force) = (0f64, 0f64);
    for case in truth["cases"].as_array().unwrap() {
        let out = mech()
            .arg("solve")
            .arg(&file)
            .arg(format!("--at={}", num(&case["q"])))
            .arg(format!("--speed={}", num(&case["qd"])))
            .arg(format!("--accel={}", num(&case["qdd"])))
            .args(["--load", &load("wheel"), "--load", &load("brake")])
            .args(["--format", "csv"])
            .assert()
            .success()
            .get_output()
            .stdout
            .clone();
        let got = csv_map(&out);
        for (p, v) in case["points"].as_object().unwrap() {
            for (k, s) in ["x", "y", "z"].iter().enumerate() {
                worst_pos = worst_pos.max((got[&format!("{p}.{s}")] - num(&v["pos"][k])).abs());
                let scale_v = 1.0 + num(&case["qd"]).abs();
                let scale_a = 1.0 + num(&case["qd"]).powi(2) + num(&case["qdd"]).abs();
                worst_pos =
                    worst_pos.max((got[&format!("{p}.v{s}")] - num(&v["vel"][k])).abs() / scale_v);
                worst_pos =
                    worst_pos.max((got[&format!("{p}.a{s}")] - num(&v["acc"][k])).abs() / scale_a);
            }
        }
        let driver = num(&case["driver"]);
        let scale = driver.abs().max(1e3);
        worst_force = worst_force.max((got["driver"] - driver).abs() / scale);
        for (j, r) in case["reactions"].as_object().unwrap() {
            for (k, s) in ["x", "y", "z"].iter().enumerate() {
                worst_force = worst_force
                    .max((got[&format!("{j}.f{s}")] - num(&r["force"][k])).abs() / scale);
                worst_force = worst_force
                    .max((got[&format!("{j}.m{s}")] - num(&r["moment"][k])).abs() / scale);
            }
        }
    }
    assert!(worst_pos < 1e-12, "positions, rates: {worst_pos:e} m");
    assert!(
        worst_force < 1e-12,
        "forces: {worst_force:e} of the driver's scale"
    );
}

/// The isometric projection the picture promises (docs/cli.md): X = (y − x)/√2,
/// Y = (2z − x − y)/√6, the picture's y pointing down.
fn iso(p: nalgebra::Vector3<f64>) -> (f64, f64) {
    (
        (p.y - p.x) / 2f64.sqrt(),
        -(2.0 * p.z - p.x - p.y) / 6f64.sqrt(),
    )
}

#[test]
fn draw_shows_each_link_once_and_the_joints_where_the_solver_puts_them() {
    let dir = tempfile::tempdir().unwrap();
    for (file, q) in [
        (root().join("examples/mech/rssr.mech"), 0.9),
        (root().join("examples/mech/double_wishbone.mech"), -0.08),
    ] {
        let out = dir.path().join("d.svg");
        mech()
            .arg("draw")
            .arg(&file)
            .arg(format!("--at={q}"))
            .arg("-o")
            .arg(&out)
            .assert()
            .success();
        let text = std::fs::read_to_string(&out).unwrap();
        let doc = roxmltree::Document::parse(&text).unwrap();
        let m = SpatialMechanism::from_dsl(&std::fs::read_to_string(&file).unwrap()).unwrap();
        let model = m.model();
        for b in &model.bodies[1..] {
            let n = doc
                .descendants()
                .filter(|e| {
                    matches!(e.attribute("class"), Some("bar") | Some("plate"))
                        && e.attribute("data-name") == Some(b.name.as_str())
                })
                .count();
            assert_eq!(n, 1, "{}: link `{}`", file.display(), b.name);
        }
        let links = doc
            .descendants()
            .filter(|e| matches!(e.attribute("class"), Some("bar") | Some("plate")))
            .count();
        assert_eq!(links, model.bodies.len() - 1);
        // The pins: the projection of the library's points, up to the view's scale and shift.
        let pose = m.pose(&[q]).unwrap();
        let pins: Vec<((f64, f64), (f64, f64))> = model
            .joints
            .iter()
            .map(|j| {
                let e = doc
                    .descendants()
                    .find(|e| {
                        e.attribute("class") == Some("pin")
                            && e.attribute("data-name") == Some(j.name.as_str())
                    })
                    .unwrap();
                let px = (
                    e.attribute("cx").unwrap().parse::<f64>().unwrap(),
                    e.attribute("cy").unwrap().parse::<f64>().unwrap(),
                );
                (px, iso(pose.point(&model.points[j.point].0).unwrap()))
            })
            .collect();
        let (p0, w0) = pins[0];
        let far = pins
            .iter()
            .max_by(|a, b| {
                let d = |p: &((f64, f64), (f64, f64))| (p.1 .0 - w0.0).hypot(p.1 .1 - w0.1);
                d(a).total_cmp(&d(b))
            })
            .unwrap();
        let k = (far.0 .0 - p0.0).hypot(far.0 .1 - p0.1) / (far.1 .0 - w0.0).hypot(far.1 .1 - w0.1);
        for ((x, y), (u, v)) in &pins {
            let (ex, ey) = (p0.0 + k * (u - w0.0), p0.1 + k * (v - w0.1));
            assert!(
                (x - ex).abs() < 0.05 && (y - ey).abs() < 0.05,
                "{}: pin at ({x}, {y}), the projection puts it at ({ex}, {ey})",
                file.display()
            );
        }
    }
}

/// The RSSP of mech-core/tests/spatial.rs (its `const RSSP`), driven at its slide.
fn rssp_slide_text() -> String {
    let source = include_str!("../../mech-core/tests/spatial.rs");
    let start = source.find("const RSSP: &str = r#\"").unwrap() + "const RSSP: &str = r#\"".len();
    let end = start + source[start..].find("\"#;").unwrap();
    source[start..end].replace("input: O,", "input: guide,")
}

#[test]
fn a_sliding_input_is_in_metres_and_its_driver_in_newtons() {
    let dir = tempfile::tempdir().unwrap();
    let text = rssp_slide_text();
    let file = rssr_file(&dir, &text);
    let m = SpatialMechanism::from_dsl(&text).unwrap();
    let mut loads = m.loads();
    loads.set_by_name("gas", &[-50.0, 10.0, 5.0]);
    let run = |format: &str| {
        mech()
            .arg("solve")
            .arg(&file)
            .args(["--at", "12mm", "--speed", "0.3", "--accel", "-0.5"])
            .args(["--load", "gas=-50N,10N,5N", "--format", format])
            .assert()
            .success()
            .get_output()
            .stdout
            .clone()
    };
    let got = csv_map(&run("csv"));
    assert_same(&got, &library_row(&m, 0.012, 0.3, -0.5, &loads), "RSSP");
    let table = String::from_utf8(run("table")).unwrap();
    for (name, unit) in [
        ("q", "m"),
        ("driver", "N"),
        ("virtual_power", "N"),
        ("inertia", "kg"),
        ("inertia_derivative", "kg/m"),
        ("moment", "N"),
        ("guide.fz", "N"),
        ("guide.my", "N·m"),
    ] {
        let line = table
            .lines()
            .find(|l| l.split_whitespace().next() == Some(name))
            .unwrap_or_else(|| panic!("{name} in\n{table}"));
        assert_eq!(line.split_whitespace().last(), Some(unit), "{line}");
    }
    // An angle where a length goes is a usage error naming the flag.
    let o = mech()
        .arg("solve")
        .arg(&file)
        .args(["--at", "30deg"])
        .assert()
        .failure()
        .code(2)
        .get_output()
        .stderr
        .clone();
    let e = String::from_utf8(o).unwrap();
    assert!(e.contains("--at") && e.contains("length"), "{e}");
}

#[test]
fn two_inputs_name_their_columns_and_sweep_with_rest() {
    let dir = tempfile::tempdir().unwrap();
    let text = rssr_text()
        .replace(
            "ground { O: (0.0, 0.0, 0.0), C: (250 mm, 120 mm, 80 mm) },",
            "ground { O: (0.0, 0.0, 0.0) },\n    link slider { points { C: (250 mm, 120 mm, 80 mm) }, mass: 3.0, cg: (0.26, 0.11, 0.07), inertia: (1e-3, 1e-3, 1e-3, 0.0, 0.0, 0.0) },",
        )
        .replace(
            "C: revolute(ground, rocker) axis (0.0, 0.0, 1.0),",
            "C: revolute(slider, rocker) axis (0.0, 0.0, 1.0),\n        guide: prismatic(ground, slider) at C along (0.3, 1.0, -0.2),",
        )
        .replace("input: O,", "inputs: [O, guide],");
    let file = rssr_file(&dir, &text);
    let m = SpatialMechanism::from_dsl(&text).unwrap();
    let out = mech()
        .arg("sweep")
        .arg(&file)
        .args(["--from", "0", "--to", "1", "--steps", "4", "--rest", "5mm"])
        .args(["--speed", "1,0.2", "--format", "csv"])
        .assert()
        .success()
        .get_output()
        .stdout
        .clone();
    let (head, rows) = csv_rows(&out);
    assert_eq!(rows.len(), 5);
    for c in [
        "q.O",
        "q.guide",
        "driver.O",
        "driver.guide",
        "virtual_power.guide",
    ] {
        assert!(head.iter().any(|h| h == c), "{c} in {head:?}");
    }
    assert!(
        !head.iter().any(|h| h == "inertia"),
        "no Zhukovski for two inputs"
    );
    let col = |n: &str| head.iter().position(|h| h == n).unwrap();
    let loads = m.loads();
    for (k, row) in rows.iter().enumerate() {
        let q = [0.25 * k as f64, 0.005];
        assert_eq!((row[col("q.O")], row[col("q.guide")]), (q[0], q[1]));
        let mo = m.kinematics(&q, &[1.0, 0.2], &[0.0, 0.0]).unwrap();
        let f = m.kinetostatics(&mo, &loads).unwrap();
        for (j, name) in ["driver.O", "driver.guide"].iter().enumerate() {
            let (got, want) = (row[col(name)], f.drivers[j]);
            assert!(
                (got - want).abs() <= 1e-12 * want.abs().max(1.0),
                "{name}: {got} vs {want}"
            );
        }
        let b = mo.point("B").unwrap();
        assert!((row[col("B.z")] - b.z).abs() < 1e-15);
    }
}

/// `mech simulate` on a spatial file: every printed row keeps the RSSR's energy (the
/// library's T + V at its (q, q̇): coasting under gravity, no loads) and its q̈ is the
/// library's direct problem at that state.
#[test]
fn simulate_keeps_the_energy_of_a_spatial_machine() {
    let dir = tempfile::tempdir().unwrap();
    let text = rssr_text();
    let file = rssr_file(&dir, &text);
    let m = SpatialMechanism::from_dsl(&text).unwrap();
    let out = mech()
        .arg("simulate")
        .arg(&file)
        .args([
            "--q0",
            "0.3",
            "--speed",
            "8",
            "--t-end",
            "1",
            "--samples",
            "20",
        ])
        .args(["--rtol", "1e-11", "--atol", "1e-11", "--format", "csv"])
        .assert()
        .success()
        .get_output()
        .stdout
        .clone();
    let (head, rows) = csv_rows(&out);
    assert_eq!(head, ["t", "q", "qd", "qdd"]);
    assert_eq!(rows.len(), 21);
    let energy = |q: f64, qd: f64| mech_core::dynamics::total_energy(&m, &[q], &[qd]).unwrap();
    let e0 = energy(0.3, 8.0);
    let (mut drift, mut qdd) = (0.0f64, 0.0f64);
    for r in &rows {
        drift = drift.max((energy(r[1], r[2]) - e0).abs());
        let want = m.acceleration(r[1], r[2], 0.0, &m.loads()).unwrap();
        qdd = qdd.max((r[3] - want).abs() / want.abs().max(1.0));
    }
    assert!((rows[20][1] - 0.3).abs() > 1.0, "it moves");
    assert!(drift < 1e-8 * e0, "energy drift {drift:e} J of {e0} J");
    assert!(qdd < 1e-12, "{qdd:e}");
}

/// `mech flywheel` on a spatial file: the fluctuation of energy is the trapezoid rule's
/// max − min of ∫ M* dq over the turn (M* from the library at 4000 points: a turning moment
/// on the rocker and gravity, zero net work), and the exact flywheel's simulated
/// irregularity is the one asked for.
#[test]
fn flywheel_sizes_a_spatial_machine() {
    let dir = tempfile::tempdir().unwrap();
    let text = rssr_text();
    let file = rssr_file(&dir, &text);
    let m = SpatialMechanism::from_dsl(&text).unwrap();
    let out = mech()
        .arg("flywheel")
        .arg(&file)
        .args(["--speed", "60rpm", "--irregularity", "0.05"])
        .args(["--load", "tool=0,0,-1.5", "--format", "csv"])
        .assert()
        .success()
        .get_output()
        .stdout
        .clone();
    let r = csv_map(&out);
    let mut loads = m.loads();
    assert!(loads.set_by_name("tool", &[0.0, 0.0, -1.5]));
    let n = 4000;
    let h = std::f64::consts::TAU / n as f64;
    let moment = |k: usize| m.reduced_moment(k as f64 * h, &loads).unwrap();
    let (mut s, mut lo, mut hi) = (0.0f64, 0.0f64, 0.0f64);
    for k in 0..n {
        s += 0.5 * h * (moment(k) + moment(k + 1));
        lo = lo.min(s);
        hi = hi.max(s);
    }
    assert!(s.abs() < 1e-9, "a conservative cycle: net work {s:e}");
    assert!(r["net_work"].abs() < 1e-9, "{r:?}");
    let fluctuation = r["fluctuation"];
    assert!(
        (fluctuation - (hi - lo)).abs() < 1e-6 * fluctuation,
        "{fluctuation} against the trapezoid's {}",
        hi - lo
    );
    assert!((r["irregularity_simulated"] - 0.05).abs() < 1e-6, "{r:?}");
    assert!(r["inertia_exact"] > 0.0 && r["inertia_approximate"] > 0.0);
}

/// `mech animate` on a spatial file: one frame per input value, each the isometric picture
/// of `mech draw` at that value (the SMIL frames hold the projected points where the
/// library puts them).
#[test]
fn animate_moves_the_isometric_picture() {
    let dir = tempfile::tempdir().unwrap();
    let text = rssr_text();
    let file = rssr_file(&dir, &text);
    let out = dir.path().join("rssr.svg");
    mech()
        .arg("animate")
        .arg(&file)
        .args(["-o"])
        .arg(&out)
        .args(["--frames", "8", "--seconds", "2"])
        .assert()
        .success();
    let svg = std::fs::read_to_string(&out).unwrap();
    // Eight frames: the axes stay put, the crank pin's marker moves (its x in the picture
    // takes as many values as the library's projected A over the eight inputs).
    let m = SpatialMechanism::from_dsl(&text).unwrap();
    let xs: Vec<f64> = (0..8)
        .map(|k| {
            iso(m
                .pose(&[std::f64::consts::TAU * k as f64 / 7.0])
                .unwrap()
                .point("A")
                .unwrap())
            .0
        })
        .collect();
    let distinct = |v: &[f64]| {
        let mut v = v.to_vec();
        v.sort_by(f64::total_cmp);
        v.dedup_by(|a, b| (*a - *b).abs() < 1e-9);
        v.len()
    };
    let axis = svg.split("data-name=\"axis x\"").nth(1).unwrap();
    let axis = &axis[..axis
        .find("/>")
        .unwrap()
        .min(axis.find("</line>").unwrap_or(usize::MAX))];
    let axis_x1 = axis.split("attributeName=\"x1\" values=\"").nth(1);
    assert!(
        axis_x1.is_none_or(|v| {
            let vals: Vec<&str> = v.split('"').next().unwrap().split(';').collect();
            vals.iter().all(|x| *x == vals[0])
        }),
        "the axes stay put"
    );
    let pin = svg
        .split("data-name=\"A\"")
        .nth(1)
        .expect("the pin A is drawn");
    let cx: Vec<f64> = pin
        .split("values=\"")
        .nth(1)
        .unwrap()
        .split('"')
        .next()
        .unwrap()
        .split(';')
        .map(|v| v.parse().unwrap())
        .collect();
    assert_eq!(cx.len(), 8, "{pin:.300}");
    assert_eq!(distinct(&cx), distinct(&xs), "{cx:?} against {xs:?}");
}

/// `--load NAME=@table.csv` on a spatial file: columns q, x, y, z, linear between rows. A
/// sweep under a table whose force grows with q gives, row by row, the library's columns
/// under that row's force (the table's nodes and the points between them).
#[test]
fn a_load_table_gives_each_row_its_load() {
    let dir = tempfile::tempdir().unwrap();
    let text = rssr_text();
    let file = rssr_file(&dir, &text);
    let table = dir.path().join("push.csv");
    // push = (10 q, −5, 2 q²) at q = 0, 0.5, …, 2π (sampled: linear between the rows)
    let mut csv = String::from("q,fx,fy,fz\n");
    let nodes: Vec<f64> = (0..=12)
        .map(|k| 0.5 * k as f64)
        .chain([std::f64::consts::TAU])
        .collect();
    for &q in &nodes {
        csv.push_str(&format!("{q},{},{},{}\n", 10.0 * q, -5.0, 2.0 * q * q));
    }
    std::fs::write(&table, csv).unwrap();
    let out = mech()
        .arg("sweep")
        .arg(&file)
        .args([
            "--from", "0", "--to", "6", "--steps", "24", "--speed", "3", "--format", "csv",
        ])
        .arg("--load")
        .arg(format!("push=@{}", table.display()))
        .assert()
        .success()
        .get_output()
        .stdout
        .clone();
    let (head, rows) = csv_rows(&out);
    let m = SpatialMechanism::from_dsl(&text).unwrap();
    let driver = head.iter().position(|h| h == "driver").unwrap();
    for r in &rows {
        let q = r[0];
        // the table's linear interpolation at q
        let k = nodes
            .iter()
            .rposition(|&x| x <= q)
            .unwrap()
            .min(nodes.len() - 2);
        let t = (q - nodes[k]) / (nodes[k + 1] - nodes[k]);
        let lerp = |f: &dyn Fn(f64) -> f64| f(nodes[k]) + t * (f(nodes[k + 1]) - f(nodes[k]));
        let push = [lerp(&|x| 10.0 * x), -5.0, lerp(&|x| 2.0 * x * x)];
        let mut loads = m.loads();
        assert!(loads.set_by_name("push", &push));
        let motion = m.kinematics(&[q], &[3.0], &[0.0]).unwrap();
        let want = m.kinetostatics(&motion, &loads).unwrap().driver();
        assert!(
            (r[driver] - want).abs() < 1e-9 * want.abs().max(1.0),
            "q = {q}: {} against {want}",
            r[driver]
        );
    }
}

/// The map from the projection of [`iso`] to the picture of `doc`: px = k·iso + o, read from
/// the pins (their `cx`, `cy`: the first frame of an animation) against the library's joint
/// points at `q`, and checked on every pin (the view is a scale and a shift).
fn pin_map(doc: &roxmltree::Document, m: &SpatialMechanism, q: &[f64]) -> (f64, (f64, f64)) {
    let model = m.model();
    let pose = m.pose(q).unwrap();
    let pins: Vec<((f64, f64), (f64, f64))> = model
        .joints
        .iter()
        .map(|j| {
            let e = doc
                .descendants()
                .find(|e| {
                    e.attribute("class") == Some("pin")
                        && e.attribute("data-name") == Some(j.name.as_str())
                })
                .unwrap();
            let px = (
                e.attribute("cx").unwrap().parse::<f64>().unwrap(),
                e.attribute("cy").unwrap().parse::<f64>().unwrap(),
            );
            (px, iso(pose.point(&model.points[j.point].0).unwrap()))
        })
        .collect();
    let mut best = (0.0, 0, 0);
    for a in 0..pins.len() {
        for b in 0..a {
            let d = (pins[a].1 .0 - pins[b].1 .0).hypot(pins[a].1 .1 - pins[b].1 .1);
            if d > best.0 {
                best = (d, a, b);
            }
        }
    }
    let ((pa, wa), (pb, wb)) = (pins[best.1], pins[best.2]);
    let k = (pa.0 - pb.0).hypot(pa.1 - pb.1) / (wa.0 - wb.0).hypot(wa.1 - wb.1);
    let o = (pa.0 - k * wa.0, pa.1 - k * wa.1);
    for ((x, y), (u, v)) in &pins {
        assert!(
            (x - (o.0 + k * u)).abs() < 0.05 && (y - (o.1 + k * v)).abs() < 0.05,
            "pin at ({x}, {y}), the projection puts it at ({}, {})",
            o.0 + k * u,
            o.1 + k * v
        );
    }
    (k, o)
}

/// The vertices of the `polyline` of class `path` named `name` in `doc`, px.
fn path_points(doc: &roxmltree::Document, name: &str) -> Vec<(f64, f64)> {
    let e = doc
        .descendants()
        .find(|e| e.attribute("class") == Some("path") && e.attribute("data-name") == Some(name))
        .unwrap_or_else(|| panic!("no path of `{name}` drawn"));
    e.attribute("points")
        .unwrap()
        .split_whitespace()
        .map(|xy| {
            let (x, y) = xy.split_once(',').unwrap();
            (x.parse().unwrap(), y.parse().unwrap())
        })
        .collect()
}

/// The size of the drawing as the tool takes it: the largest distance between two points.
fn drawing_size(m: &SpatialMechanism) -> f64 {
    let points = &m.model().points;
    points
        .iter()
        .flat_map(|(_, a)| points.iter().map(move |(_, b)| (a - b).norm()))
        .fold(0.0, f64::max)
}

/// `mech draw --path B` on a spatial file: 361 vertices over a turn of the crank (the other
/// inputs at `--at`), each the isometric projection of the library's B at that input,
/// through the picture's own scale and shift (read from the pins).
#[test]
fn draw_path_is_the_projection_of_the_librarys_point_over_a_turn() {
    let dir = tempfile::tempdir().unwrap();
    let text = rssr_text();
    let file = rssr_file(&dir, &text);
    let out = dir.path().join("path.svg");
    mech()
        .arg("draw")
        .arg(&file)
        .args(["--at=0.9", "--path", "B", "-o"])
        .arg(&out)
        .assert()
        .success();
    let svg = std::fs::read_to_string(&out).unwrap();
    let doc = roxmltree::Document::parse(&svg).unwrap();
    let m = SpatialMechanism::from_dsl(&text).unwrap();
    let (k, o) = pin_map(&doc, &m, &[0.9]);
    let pts = path_points(&doc, "B");
    assert_eq!(pts.len(), 361, "one vertex per degree of the turn");
    let mut spread: f64 = 0.0;
    for i in [0, 1, 45, 90, 137, 180, 225, 271, 333, 360] {
        let q = std::f64::consts::TAU * i as f64 / 360.0;
        let (u, v) = iso(m.pose(&[q]).unwrap().point("B").unwrap());
        let (x, y) = pts[i];
        let (ex, ey) = (o.0 + k * u, o.1 + k * v);
        assert!(
            (x - ex).abs() < 0.05 && (y - ey).abs() < 0.05,
            "vertex {i}: ({x}, {y}), the library's B projects to ({ex}, {ey})"
        );
        spread = spread.max((x - pts[0].0).hypot(y - pts[0].1));
    }
    assert!(spread > 20.0, "B moves over the turn: {spread} px");
}

/// `mech draw --forces --speed 10 --load tool=0,0,2` on a spatial file: one arrow per joint,
/// from the joint's pin along the projection of the library's reaction (by the first link
/// on the second) at that joint, the largest force a quarter of the drawing's size long in
/// space. In the SVG (coordinates to 0.01 px) the directions hold to the rounding; the
/// shapes of `mech_cli::spatial::arrows` to 1e-6 rad.
#[test]
fn draw_forces_are_the_librarys_reactions_projected() {
    let dir = tempfile::tempdir().unwrap();
    let text = rssr_text();
    let file = rssr_file(&dir, &text);
    let out = dir.path().join("forces.svg");
    mech()
        .arg("draw")
        .arg(&file)
        .args([
            "--at=0.9",
            "--forces",
            "--speed",
            "10",
            "--load",
            "tool=0,0,2",
            "-o",
        ])
        .arg(&out)
        .assert()
        .success();
    let svg = std::fs::read_to_string(&out).unwrap();
    let doc = roxmltree::Document::parse(&svg).unwrap();
    let m = SpatialMechanism::from_dsl(&text).unwrap();
    let model = m.model();
    let (k, o) = pin_map(&doc, &m, &[0.9]);
    let motion = m.kinematics(&[0.9], &[10.0], &[0.0]).unwrap();
    let mut loads = m.loads();
    loads.set_by_name("tool", &[0.0, 0.0, 2.0]);
    let forces = m.kinetostatics(&motion, &loads).unwrap();
    let largest = forces
        .reactions
        .iter()
        .map(|r| r.force.norm())
        .fold(0.0, f64::max);
    assert!(largest > 0.0);
    let scale = 0.25 * drawing_size(&m) / largest;
    let arrows: Vec<_> = doc
        .descendants()
        .filter(|e| e.attribute("class") == Some("arrow"))
        .collect();
    assert_eq!(arrows.len(), model.joints.len(), "one arrow per joint");
    let angle = |a: (f64, f64), b: (f64, f64)| (a.0 * b.1 - a.1 * b.0).atan2(a.0 * b.0 + a.1 * b.1);
    for (j, r) in model.joints.iter().zip(&forces.reactions) {
        let e = arrows
            .iter()
            .find(|e| e.attribute("data-name") == Some(j.name.as_str()))
            .unwrap_or_else(|| panic!("no arrow at joint `{}`", j.name));
        let c = |a: &str| e.attribute(a).unwrap().parse::<f64>().unwrap();
        let (x1, y1, x2, y2) = (c("x1"), c("y1"), c("x2"), c("y2"));
        let (u, v) = iso(motion.point_motion_at(j.point).unwrap()[0]);
        assert!(
            (x1 - (o.0 + k * u)).abs() < 0.05 && (y1 - (o.1 + k * v)).abs() < 0.05,
            "arrow `{}` starts at ({x1}, {y1}), its joint is at ({}, {})",
            j.name,
            o.0 + k * u,
            o.1 + k * v
        );
        let f = iso(r.force);
        let want = (k * scale * f.0, k * scale * f.1);
        let got = (x2 - x1, y2 - y1);
        let len = got.0.hypot(got.1);
        let want_len = want.0.hypot(want.1);
        // Each end rounded to 0.005 px: the direction within 0.015/len rad, the length
        // within 0.015 px (with the scale's own error read from the pins).
        assert!(
            (len - want_len).abs() < 0.015 + 1e-4 * want_len,
            "arrow `{}`: {len} px, the projected reaction {want_len} px",
            j.name
        );
        if want_len > 1.0 {
            let a = angle(got, want).abs();
            assert!(
                a < 0.015 / len,
                "arrow `{}`: {a} rad from the projected reaction",
                j.name
            );
        }
    }
    // The shapes themselves (drawing units, y up), against the library to 1e-6 rad and in
    // the ratio of the projected forces.
    let shapes = mech_cli::spatial::arrows(&m, &[0.9], &[10.0], &[0.0], &loads, 1.0).unwrap();
    assert_eq!(shapes.len(), model.joints.len());
    for ((s, j), r) in shapes.iter().zip(&model.joints).zip(&forces.reactions) {
        assert_eq!(s.name, j.name);
        let d = s.points[1] - s.points[0];
        let f = iso(r.force);
        let f = (f.0, -f.1);
        let a = angle((d.x, d.y), f).abs();
        assert!(
            a < 1e-6,
            "arrow `{}`: {a} rad from the projected reaction",
            j.name
        );
        let ratio = d.norm() / f.0.hypot(f.1);
        assert!(
            (ratio - 1.0 / largest).abs() < 1e-9 / largest,
            "arrow `{}`: {ratio} m per N, want 1/{largest}",
            j.name
        );
    }
}

/// `mech animate --path A --frames 8` on a spatial file: the path of A under the animation,
/// one vertex per frame, each the projection of the library's A at that frame's input.
#[test]
fn animate_draws_the_path_over_the_animated_inputs() {
    let dir = tempfile::tempdir().unwrap();
    let text = rssr_text();
    let file = rssr_file(&dir, &text);
    let out = dir.path().join("anim.svg");
    mech()
        .arg("animate")
        .arg(&file)
        .args(["--path", "A", "--frames", "8", "-o"])
        .arg(&out)
        .assert()
        .success();
    let svg = std::fs::read_to_string(&out).unwrap();
    let doc = roxmltree::Document::parse(&svg).unwrap();
    let m = SpatialMechanism::from_dsl(&text).unwrap();
    let (k, o) = pin_map(&doc, &m, &[0.0]);
    let pts = path_points(&doc, "A");
    assert_eq!(pts.len(), 8, "one vertex per frame");
    for (i, (x, y)) in pts.iter().enumerate() {
        let q = std::f64::consts::TAU * i as f64 / 7.0;
        let (u, v) = iso(m.pose(&[q]).unwrap().point("A").unwrap());
        let (ex, ey) = (o.0 + k * u, o.1 + k * v);
        assert!(
            (x - ex).abs() < 0.05 && (y - ey).abs() < 0.05,
            "frame {i}: ({x}, {y}), the library's A projects to ({ex}, {ey})"
        );
    }
}

/// `--path` of a point the spatial mechanism does not have: a usage error (status 2) that
/// names the point and lists the mechanism's points, from `draw` and from `animate`.
#[test]
fn an_unknown_path_point_lists_the_points() {
    let dir = tempfile::tempdir().unwrap();
    let text = rssr_text();
    let file = rssr_file(&dir, &text);
    let m = SpatialMechanism::from_dsl(&text).unwrap();
    let names: Vec<&str> = m.model().points.iter().map(|(p, _)| p.as_str()).collect();
    for command in ["draw", "animate"] {
        let mut c = mech();
        c.arg(command).arg(&file);
        if command == "draw" {
            c.arg("--at=0.3");
        }
        let o = c
            .args(["--path", "Z", "-o"])
            .arg(dir.path().join("z.svg"))
            .assert()
            .code(2)
            .get_output()
            .stderr
            .clone();
        let err = String::from_utf8(o).unwrap();
        assert!(
            err.contains(&format!(
                "--path Z: no such point; the points are {}",
                names.join(", ")
            )),
            "{command}: {err}"
        );
    }
}
