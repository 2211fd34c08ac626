//! `mech shaking` and `mech balance`: a centred slider-crank whose only mass is the piston,
//! its primary and secondary harmonics against the Fourier coefficients of the exact
//! slider motion computed here by quadrature; the polar SVG; the balanced files.

use assert_cmd::Command;

fn mech() -> Command {
    Command::cargo_bin("mech").unwrap()
}

/// r = 50 mm, l = 200 mm, the piston 1.5 kg, crank and rod massless.
const PISTON_ONLY: &str = "pub struct Piston {
    ground { O: (0.0, 0.0) },
    link crank { points { O, A: (0.05, 0.0) } },
    link rod { points { A, B: (0.25, 0.0) } },
    link piston { points { B }, mass: 1.5, cg: B },
    joints {
        O: revolute(ground, crank),
        A: revolute(crank, rod),
        B: revolute(rod, piston),
        guide: prismatic(ground, piston) at B along (1.0, 0.0),
    },
    input: O,
}";

/// The summary's numbers after `label` (the first two: a and b of F_x).
fn numbers_after(text: &str, label: &str) -> Vec<f64> {
    let line = text.lines().find(|l| l.starts_with(label)).unwrap();
    line.split([' ', ','])
        .filter_map(|w| w.parse::<f64>().ok())
        .collect()
}

/// F_x = −m ẍ: its order-n coefficient is m n² ω² c_n with c_n = (1/π)∫ x cos nθ dθ of
/// x = r cos θ + √(l² − r² sin² θ) (c_1 = r exactly; c_2 by the trapezoid rule, exact to
/// rounding for a smooth periodic integrand).
#[test]
fn shaking_harmonics_of_a_piston_against_the_exact_slider_motion() {
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("piston.mech");
    std::fs::write(&file, PISTON_ONLY).unwrap();
    let svg = dir.path().join("polar.svg");
    let out = mech()
        .args([
            "shaking",
            file.to_str().unwrap(),
            "--speed",
            "100",
            "--steps",
            "360",
        ])
        .args(["--format", "csv", "--svg", svg.to_str().unwrap()])
        .assert()
        .success();
    let stdout = String::from_utf8(out.get_output().stdout.clone()).unwrap();
    let stderr = String::from_utf8(out.get_output().stderr.clone()).unwrap();
    assert!(
        stdout.starts_with("q,shaking.fx,shaking.fy,shaking.moment"),
        "{stdout}"
    );
    assert_eq!(stdout.lines().count(), 362);
    let (r, l, m, w) = (0.05f64, 0.2f64, 1.5, 100.0);
    let n = 4096;
    let c2: f64 = (0..n)
        .map(|k| {
            let t = std::f64::consts::TAU * k as f64 / n as f64;
            (r * t.cos() + (l * l - r * r * t.sin().powi(2)).sqrt()) * (2.0 * t).cos()
        })
        .sum::<f64>()
        * 2.0
        / n as f64;
    let peak = m * w * w * (r + r * r / l);
    let primary = numbers_after(&stderr, "primary");
    let secondary = numbers_after(&stderr, "secondary");
    // [a_x, b_x, a_y, b_y]
    assert!((primary[0] - m * w * w * r).abs() < 1e-9 * peak, "{stderr}");
    assert!(
        (secondary[0] - 4.0 * m * w * w * c2).abs() < 1e-9 * peak,
        "{stderr}"
    );
    // The textbook's first order: the secondary m r ω² (r/l), within (r/l)² of it.
    assert!((secondary[0] / (m * r * w * w * r / l) - 1.0).abs() < 0.1);
    for v in [
        primary[1],
        primary[2],
        primary[3],
        secondary[1],
        secondary[2],
        secondary[3],
    ] {
        assert!(v.abs() < 1e-9 * peak, "{stderr}");
    }
    let picture = std::fs::read_to_string(&svg).unwrap();
    assert!(picture.starts_with("<svg") && picture.contains("<polyline"));
    // The peak, at θ = 0: m ω² (r + r²/l).
    let peak_line = numbers_after(&stderr, "shaking force:");
    assert!((peak_line[0] - peak).abs() < 1e-4 * peak, "{stderr}");
}

#[test]
fn shaking_refuses_a_file_that_does_not_load() {
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("bad.mech");
    std::fs::write(&file, "pub struct Bad { ground { O: (0.0, 0.0) } }").unwrap();
    mech()
        .args(["shaking", file.to_str().unwrap(), "--speed", "10"])
        .assert()
        .failure();
}

/// The four-bar of `tests/balancing.rs` balanced by `mech balance`: the written file has two
/// counterweights, checks, and `mech shaking` of it gives a force below 1e-9 of the
/// unbalanced one's peak at every row.
#[test]
fn balance_writes_a_four_bar_that_no_longer_shakes() {
    let text = "pub struct Linkage {
    ground { O2: (0.0, 0.0), O4: (0.3, 0.0) },
    link crank { points { O2, A: (0.0, 0.1) }, mass: 0.5, inertia: 4e-4, cg: (0.01, 0.05) },
    link coupler { points { A, B: (0.25, 0.2) }, mass: 1.0, inertia: 6e-3, cg: (0.12, 0.22) },
    link rocker { points { O4, B }, mass: 0.8, inertia: 3e-3, cg: (0.28, 0.1) },
    joints {
        O2: revolute(ground, crank),
        A: revolute(crank, coupler),
        B: revolute(coupler, rocker),
        O4: revolute(ground, rocker),
    },
    input: O2,
}";
    let dir = tempfile::tempdir().unwrap();
    let (file, out_file) = (dir.path().join("fb.mech"), dir.path().join("fb_bal.mech"));
    std::fs::write(&file, text).unwrap();
    let out = mech()
        .args(["balance", file.to_str().unwrap(), "--speed", "300rpm", "-o"])
        .arg(&out_file)
        .assert()
        .success();
    let stdout = String::from_utf8(out.get_output().stdout.clone()).unwrap();
    assert_eq!(stdout.matches("counterweight on").count(), 2, "{stdout}");
    let written = std::fs::read_to_string(&out_file).unwrap();
    assert_eq!(written.matches("counterweight:").count(), 2);
    mech().arg("check").arg(&out_file).assert().success();
    let rows = |f: &std::path::Path| -> Vec<f64> {
        let o = mech()
            .args([
                "shaking",
                f.to_str().unwrap(),
                "--speed",
                "300rpm",
                "--steps",
                "72",
                "--format",
                "csv",
            ])
            .assert()
            .success();
        String::from_utf8(o.get_output().stdout.clone())
            .unwrap()
            .lines()
            .skip(1)
            .map(|l| {
                let v: Vec<f64> = l.split(',').map(|x| x.parse().unwrap()).collect();
                v[1].hypot(v[2])
            })
            .collect()
    };
    let peak = rows(&file).into_iter().fold(0.0, f64::max);
    assert!(peak > 1.0);
    for f in rows(&out_file) {
        assert!(f < 1e-9 * peak, "{f} against {peak}");
    }
    // A fraction outside 0..1 is refused.
    mech()
        .args([
            "balance",
            file.to_str().unwrap(),
            "--speed",
            "10",
            "--fraction",
            "1.5",
            "-o",
        ])
        .arg(&out_file)
        .assert()
        .failure();
}

/// `--method optimal` with the shaking force alone on the four-bar: its exact balance is
/// the optimum (RMS 0), so the written file's RMS is far below the unbalanced one.
#[test]
fn optimal_balance_of_the_four_bar_finds_the_force_balance() {
    let text = "pub struct Linkage {
    ground { O2: (0.0, 0.0), O4: (0.3, 0.0) },
    link crank { points { O2, A: (0.0, 0.1) }, mass: 0.5, inertia: 4e-4, cg: (0.01, 0.05) },
    link coupler { points { A, B: (0.25, 0.2) }, mass: 1.0, inertia: 6e-3, cg: (0.12, 0.22) },
    link rocker { points { O4, B }, mass: 0.8, inertia: 3e-3, cg: (0.28, 0.1) },
    joints {
        O2: revolute(ground, crank),
        A: revolute(crank, coupler),
        B: revolute(coupler, rocker),
        O4: revolute(ground, rocker),
    },
    input: O2,
}";
    let dir = tempfile::tempdir().unwrap();
    let (file, out_file) = (dir.path().join("fb.mech"), dir.path().join("fb_opt.mech"));
    std::fs::write(&file, text).unwrap();
    let out = mech()
        .args([
            "balance",
            file.to_str().unwrap(),
            "--speed",
            "30",
            "--method",
            "optimal",
        ])
        .args(["--weights", "1,0,0", "-o"])
        .arg(&out_file)
        .assert()
        .success();
    let stdout = String::from_utf8(out.get_output().stdout.clone()).unwrap();
    let rms = |label: &str| -> f64 {
        let line = stdout.lines().find(|l| l.starts_with(label)).unwrap();
        line.split_whitespace().nth(1).unwrap().parse().unwrap()
    };
    assert!(rms("after") < 1e-6 * rms("before"), "{stdout}");
}
