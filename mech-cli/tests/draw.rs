//! `mech draw`, `animate` and `report`: well-formed SVG and HTML, pins where the solver
//! puts the points (read back from the picture through its view), an animation whose
//! crank pin traces the crank's circle, and errors for bad arguments.

use assert_cmd::Command;
use mech_core::Mechanism;
use std::path::{Path, PathBuf};

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("..")
}

fn mech() -> Command {
    Command::cargo_bin("mech").unwrap()
}

fn engine() -> PathBuf {
    root().join("examples/mech/engine.mech")
}

/// The pins (name, cx, cy) of an SVG document.
fn pins(doc: &roxmltree::Document) -> Vec<(String, f64, f64)> {
    doc.descendants()
        .filter(|n| n.has_tag_name("circle") && n.attribute("class") == Some("pin"))
        .map(|n| {
            (
                n.attribute("data-name").unwrap().to_string(),
                n.attribute("cx").unwrap().parse().unwrap(),
                n.attribute("cy").unwrap().parse().unwrap(),
            )
        })
        .collect()
}

#[test]
fn draw_puts_every_pin_where_the_solver_puts_its_point() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("engine.svg");
    mech()
        .arg("draw")
        .arg(engine())
        .args([
            "--at",
            "40deg",
            "--path",
            "A",
            "--forces",
            "--speed",
            "3000rpm",
            "--load",
            "gas=-5kN,0",
            "-o",
        ])
        .arg(&out)
        .assert()
        .success();
    let text = std::fs::read_to_string(&out).unwrap();
    let doc = roxmltree::Document::parse(&text).unwrap();
    let m = Mechanism::from_dsl(&std::fs::read_to_string(engine()).unwrap()).unwrap();
    let pose = m.pose(&[40f64.to_radians()]).unwrap();
    // Two pins fix the view (scale and offset); every pin must then agree with the pose.
    let p = pins(&doc);
    let model = m.model();
    let world = |name: &str| pose.points[model.joints[model.joint_index(name).unwrap()].point].pos;
    let (a, b) = (&p[0], &p[1]);
    let (wa, wb) = (world(&a.0), world(&b.0));
    let k = ((b.1 - a.1).hypot(b.2 - a.2)) / (wb - wa).norm();
    for (name, cx, cy) in &p {
        let w = world(name);
        let (x, y) = (a.1 + (w.x - wa.x) * k, a.2 - (w.y - wa.y) * k);
        assert!(
            (x - cx).abs() < 0.01 && (y - cy).abs() < 0.01,
            "pin {name}: ({cx}, {cy}) against ({x}, {y})"
        );
    }
    assert_eq!(p.len(), 3, "O2, A, B");
    // The path of A is the crank's circle: its points are all at |O2 A| from O2.
    let path = doc
        .descendants()
        .find(|n| n.attribute("class") == Some("path"))
        .unwrap();
    let o2 = p.iter().find(|x| x.0 == "O2").unwrap();
    let r = 0.043 * k;
    for xy in path.attribute("points").unwrap().split(' ') {
        let (x, y) = xy.split_once(',').unwrap();
        let d = (x.parse::<f64>().unwrap() - o2.1).hypot(y.parse::<f64>().unwrap() - o2.2);
        assert!((d - r).abs() < 0.02, "{d} against {r}");
    }
    assert_eq!(
        doc.descendants()
            .filter(|n| n.attribute("class") == Some("arrow"))
            .count(),
        4,
        "one reaction arrow per joint"
    );
    assert!(
        doc.descendants()
            .any(|n| n.attribute("class") == Some("block"))
            && doc
                .descendants()
                .any(|n| n.attribute("class") == Some("guide"))
    );
    assert!(doc
        .descendants()
        .any(|n| n.attribute("class") == Some("pivot")));
}

#[test]
fn animate_traces_the_crank_circle_frame_by_frame() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("watt.svg");
    mech()
        .arg("animate")
        .arg(root().join("examples/mech/watt_ii.mech"))
        .args(["--frames", "48", "-o"])
        .arg(&out)
        .assert()
        .success();
    let text = std::fs::read_to_string(&out).unwrap();
    let doc = roxmltree::Document::parse(&text).unwrap();
    let pin = |name: &str| {
        doc.descendants()
            .find(|n| n.attribute("class") == Some("pin") && n.attribute("data-name") == Some(name))
            .unwrap()
    };
    let values = |n: roxmltree::Node, attr: &str| -> Vec<f64> {
        n.children()
            .find(|c| c.has_tag_name("animate") && c.attribute("attributeName") == Some(attr))
            .map(|c| {
                c.attribute("values")
                    .unwrap()
                    .split(';')
                    .map(|v| v.parse().unwrap())
                    .collect()
            })
            .unwrap_or_default()
    };
    let (ax, ay) = (values(pin("A"), "cx"), values(pin("A"), "cy"));
    assert_eq!(ax.len(), 48);
    assert_eq!(ay.len(), 48);
    let o2 = pin("O2");
    assert!(values(o2, "cx").is_empty(), "a ground pivot does not move");
    let (cx, cy): (f64, f64) = (
        o2.attribute("cx").unwrap().parse().unwrap(),
        o2.attribute("cy").unwrap().parse().unwrap(),
    );
    let r: Vec<f64> = ax
        .iter()
        .zip(&ay)
        .map(|(x, y)| (x - cx).hypot(y - cy))
        .collect();
    let mean = r.iter().sum::<f64>() / r.len() as f64;
    assert!(
        r.iter().all(|d| (d - mean).abs() < 0.02),
        "A stays on a circle about O2: {r:?}"
    );
    // One turn: the first and the last frame are the same place.
    assert!((ax[0] - ax[47]).abs() < 0.02 && (ay[0] - ay[47]).abs() < 0.02);
    assert!(doc
        .descendants()
        .filter(|n| n.has_tag_name("animate"))
        .all(|n| n.attribute("repeatCount") == Some("indefinite")));
}

#[test]
fn report_is_one_self_contained_page() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("engine.html");
    mech()
        .arg("report")
        .arg(engine())
        .args([
            "--speed",
            "3000rpm",
            "--load",
            "gas=-2kN,0",
            "--point",
            "B",
            "--frames",
            "40",
            "-o",
        ])
        .arg(&out)
        .assert()
        .success();
    let html = std::fs::read_to_string(&out).unwrap();
    for needed in [
        "<svg",
        "id=\"slider\"",
        "id=\"play\"",
        "cursor-driver",
        "cursor-reactions",
        "cursor-inertia",
        "cursor-moment",
        "cursor-speed",
        "|v B|",
        "frame=",
        // 3000 rpm stated with its unit, not as a Rust vector.
        "input speed 314.159",
        " rad/s (constant)",
    ] {
        assert!(html.contains(needed), "{needed}");
    }
    assert!(
        !html.contains("input speed ["),
        "the speed printed as a vector"
    );
    let without_ns = html.replace("http://www.w3.org/2000/svg", "");
    assert!(
        !without_ns.contains("http://") && !without_ns.contains("https://"),
        "no network resource"
    );
    // The embedded frames: as many as asked, the crank pin moving.
    let open = "<script type=\"application/json\" id=\"data\">";
    let start = html.find(open).unwrap() + open.len();
    let end = start + html[start..].find("</script>").unwrap();
    let data: serde_json::Value = serde_json::from_str(&html[start..end]).unwrap();
    assert_eq!(data["q"].as_array().unwrap().len(), 40);
    let moving = data["shapes"].as_array().unwrap().iter().filter(|s| {
        let v = s["values"].as_array().unwrap();
        v.first() != v.last() || v[0] != v[10]
    });
    assert!(moving.count() >= 3, "the links move");
    // The plots are drawn: a polyline of ≥ 40 points per series.
    let polylines = html.matches("class=\"series\"").count();
    assert!(polylines > 2 + 4 + 1 + 1, "{polylines} series (at least 9)");
}

#[test]
fn bad_arguments_are_errors_not_panics() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("x.svg");
    for (args, part) in [
        (
            vec![
                "draw",
                engine().to_str().unwrap(),
                "-o",
                out.to_str().unwrap(),
            ],
            "--at",
        ),
        (
            vec![
                "draw",
                engine().to_str().unwrap(),
                "--at",
                "1",
                "--path",
                "Z",
                "-o",
                out.to_str().unwrap(),
            ],
            "no such point",
        ),
        (
            vec![
                "animate",
                engine().to_str().unwrap(),
                "--frames",
                "1",
                "-o",
                out.to_str().unwrap(),
            ],
            "at least 2 frames",
        ),
        (
            vec!["report", "/nonexistent.mech", "-o", out.to_str().unwrap()],
            "cannot read",
        ),
    ] {
        let o = mech().args(&args).assert().failure().get_output().clone();
        let err = String::from_utf8(o.stderr).unwrap();
        assert!(
            err.contains(part) && !err.contains("panicked"),
            "{args:?}: {err}"
        );
    }
}

/// `mech draw` of a rocker cam: the cam's profile (turned with the cam) and the roller
/// (its circle about the pitch point P, radius 8 mm) touch — the profile's nearest point is
/// one roller radius from P, to the profile's sampling (180 points) — and the roller's
/// centre is where the solver puts P, read through the view the pins O and A fix.
#[test]
fn draw_puts_the_roller_on_the_cam() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("rocker.svg");
    let file = root().join("examples/mech/rocker_cam.mech");
    for at in ["20deg", "135deg", "300deg"] {
        mech()
            .arg("draw")
            .arg(&file)
            .args(["--at", at, "-o"])
            .arg(&out)
            .assert()
            .success();
        let text = std::fs::read_to_string(&out).unwrap();
        let doc = roxmltree::Document::parse(&text).unwrap();
        let shapes: Vec<Vec<(f64, f64)>> = doc
            .descendants()
            .filter(|n| n.attribute("data-name") == Some("lobe") && n.has_attribute("points"))
            .map(|n| {
                n.attribute("points")
                    .unwrap()
                    .split(' ')
                    .map(|xy| {
                        let (x, y) = xy.split_once(',').unwrap();
                        (x.parse().unwrap(), y.parse().unwrap())
                    })
                    .collect()
            })
            .collect();
        assert_eq!(shapes.len(), 2, "the profile and the roller at {at}");
        let (profile, roller) = (&shapes[0], &shapes[1]);
        let n = roller.len() as f64;
        let c = (
            roller.iter().map(|p| p.0).sum::<f64>() / n,
            roller.iter().map(|p| p.1).sum::<f64>() / n,
        );
        let r = roller
            .iter()
            .map(|p| (p.0 - c.0).hypot(p.1 - c.1))
            .sum::<f64>()
            / n;
        let gap = profile
            .iter()
            .map(|p| (p.0 - c.0).hypot(p.1 - c.1))
            .fold(f64::INFINITY, f64::min);
        // 180 points around a ~40 mm cam are ~1.4 mm apart: the nearest is within
        // (1.4/2)²/(2·8) mm ≈ 0.03 mm of the circle, 1 % of r here.
        assert!(
            (gap - r).abs() < 0.01 * r,
            "at {at}: gap {gap} against roller {r}"
        );
        // The view from the pins O and A; P where the solver puts it.
        let p = pins(&doc);
        let m = Mechanism::from_dsl(&std::fs::read_to_string(&file).unwrap()).unwrap();
        let deg: f64 = at.trim_end_matches("deg").parse().unwrap();
        let pose = m.pose(&[deg.to_radians()]).unwrap();
        let model = m.model();
        let world = |point: &str| pose.points[model.point_index(point).unwrap()].pos;
        let pin = |name: &str| p.iter().find(|x| x.0 == name).unwrap();
        let (o, a) = (pin("O"), pin("A"));
        let k = (a.1 - o.1).hypot(a.2 - o.2) / (world("A") - world("O")).norm();
        let wp = world("P") - world("O");
        let (x, y) = (o.1 + wp.x * k, o.2 - wp.y * k);
        assert!(
            (x - c.0).abs() < 0.01 && (y - c.1).abs() < 0.01,
            "at {at}: roller centre ({}, {}) against P ({x}, {y})",
            c.0,
            c.1
        );
        assert!(
            (r - 0.008 * k).abs() < 0.01,
            "roller radius {r} against {}",
            0.008 * k
        );
    }
}
