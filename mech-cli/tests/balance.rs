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
    line.split(|c: char| c == ' ' || c == ',')
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
        .args(["shaking", file.to_str().unwrap(), "--speed", "100", "--steps", "360"])
        .args(["--format", "csv", "--svg", svg.to_str().unwrap()])
        .assert()
        .success();
    let stdout = String::from_utf8(out.get_output().stdout.clone()).unwrap();
    let stderr = String::from_utf8(out.get_output().stderr.clone()).unwrap();
    assert!(stdout.starts_with("q,shaking.fx,shaking.fy,shaking.moment"), "{stdout}");
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
    assert!((secondary[0] - 4.0 * m * w * w * c2).abs() < 1e-9 * peak, "{stderr}");
    // The textbook's first order: the secondary m r ω² (r/l), within (r/l)² of it.
    assert!((secondary[0] / (m * r * w * w * r / l) - 1.0).abs() < 0.1);
    for v in [primary[1], primary[2], primary[3], secondary[1], secondary[2], secondary[3]] {
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
