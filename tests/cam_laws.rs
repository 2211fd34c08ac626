//! The cam motion laws of `mech::cam` against `tests/data/cam_laws.json`
//! (`tools/cam_reference.py`: each law's displacement from its textbook formula,
//! differentiated symbolically by sympy, 30 digits), and the periodic spline of a user
//! table by its defining properties.

use crate::measure::within;
use mech::cam::{Law, MotionLaw, Segment, Spline};
use serde_json::Value;
use std::f64::consts::{PI, TAU};

fn law(rise: Law, fall: Law) -> MotionLaw {
    let seg = |law, start: f64, end: f64, from, to| Segment {
        law,
        start: start.to_radians(),
        end: end.to_radians(),
        from,
        to,
    };
    MotionLaw::from_segments(vec![
        seg(Law::Dwell, 0.0, 90.0, 0.0, 0.0),
        seg(rise, 90.0, 180.0, 0.0, 0.01),
        seg(Law::Dwell, 180.0, 240.0, 0.01, 0.01),
        seg(fall, 240.0, 360.0, 0.01, 0.0),
    ])
    .unwrap()
}

/// Displacement, velocity, acceleration and jerk (per unit cam angle) of every law at a
/// dozen angles of a rise and a fall, to 1e-13 of each quantity's scale.
#[test]
fn each_law_matches_its_symbolic_derivatives() {
    let path = format!("{}/tests/data/cam_laws.json", env!("CARGO_MANIFEST_DIR"));
    let r: Value = serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap();
    for (name, l) in [
        ("uniform", Law::Uniform),
        ("harmonic", Law::Harmonic),
        ("cycloidal", Law::Cycloidal),
        ("poly345", Law::Poly345),
        ("poly4567", Law::Poly4567),
    ] {
        let m = law(l, l);
        let rows = r["laws"][name].as_array().unwrap();
        let num = |v: &Value| v.as_str().unwrap().parse::<f64>().unwrap();
        let mut scale = [0.0f64; 4];
        for row in rows {
            for (o, v) in row["values"].as_array().unwrap().iter().enumerate() {
                scale[o] = scale[o].max(num(v).abs());
            }
        }
        for row in rows {
            let th = num(&row["theta"]);
            let got = m.eval(th);
            for (o, v) in row["values"].as_array().unwrap().iter().enumerate() {
                let want = num(v);
                assert!(
                    within((got[o] - want).abs(), 1e-13 * scale[o].max(1e-300)), // measured worst 1.0e-14 (be05608); 100×
                    "{name} at {:.3}°: derivative {o} = {:e}, sympy {want:e}",
                    th.to_degrees(),
                    got[o]
                );
            }
        }
    }
}

/// Which derivatives jump where dwells meet each law: uniform — the velocity at all four
/// corners; simple harmonic — the acceleration; cycloidal and 3-4-5 — nothing up to the
/// acceleration; and segments that do not cover a turn are refused with the numbers.
#[test]
fn continuity_and_coverage() {
    let orders = |l: Law| {
        let mut o: Vec<usize> = law(l, l).jumps(1e-9).iter().map(|j| j.order).collect();
        o.sort();
        o.dedup();
        o
    };
    assert_eq!(orders(Law::Uniform), vec![1]);
    assert_eq!(orders(Law::Harmonic), vec![2]);
    assert!(orders(Law::Cycloidal).is_empty());
    assert!(orders(Law::Poly345).is_empty());
    assert!(orders(Law::Poly4567).is_empty());
    let e = MotionLaw::from_segments(vec![Segment {
        law: Law::Cycloidal,
        start: 0.0,
        end: PI,
        from: 0.0,
        to: 0.01,
    }])
    .unwrap_err();
    assert!(
        e.contains("cover 180.0000°") && e.contains("one turn"),
        "{e}"
    );
    let e = MotionLaw::from_segments(vec![
        Segment {
            law: Law::Poly345,
            start: 0.0,
            end: PI,
            from: 0.0,
            to: 0.01,
        },
        Segment {
            law: Law::Poly345,
            start: 3.2,
            end: TAU,
            from: 0.01,
            to: 0.0,
        },
    ])
    .unwrap_err();
    assert!(e.contains("segment 2 starts at"), "{e}");
}

/// A user table: the periodic spline passes through its points, is C² around the turn
/// (left and right limits of s, s', s'' agree at every knot, across 360° too), and through
/// 36 samples of a smooth periodic lift it converges as h⁴ (its error against the lift
/// drops about 16× when the knots double).
#[test]
fn periodic_spline_table() {
    let f = |t: f64| 0.004 * (1.0 - t.cos()) + 0.001 * (2.0 * t).sin();
    let table = |n: usize| {
        let th: Vec<f64> = (0..n).map(|k| TAU * k as f64 / n as f64).collect();
        let s: Vec<f64> = th.iter().map(|&t| f(t)).collect();
        (Spline::periodic(&th, &s).unwrap(), th, s)
    };
    let (sp, th, s) = table(36);
    for (k, (&t, &v)) in th.iter().zip(&s).enumerate() {
        // measured worst 1.7e-18 (be05608); 100×
        assert!(within((sp.eval(t)[0] - v).abs(), 1e-17), "knot {k}");
        let eps = 1e-9;
        let (l, r) = (sp.eval(t - eps), sp.eval(t + eps));
        for o in 0..3 {
            let scale = [1e-2, 1e-2, 1e-2][o];
            assert!(
                within((l[o] - r[o]).abs(), 1e-7 * scale), // measured worst 2.4e-9 (be05608); finite offset ±1e-9 rad: the limits differ by s'·2e-9, not an error
                "knot {k}: derivative {o} jumps {} → {}",
                l[o],
                r[o]
            );
        }
    }
    let err = |n: usize| {
        let (sp, _, _) = table(n);
        (0..1000)
            .map(|k| {
                let t = TAU * (k as f64 + 0.37) / 1000.0;
                (sp.eval(t)[0] - f(t)).abs()
            })
            .fold(0.0f64, f64::max)
    };
    let (e1, e2) = (err(36), err(72));
    // measured worst 4.7e-8 (be05608); the spline's interpolation error, not a rounding error
    assert!(within(e1, 1e-6) && e1 / e2 > 12.0, "errors {e1:e}, {e2:e}");
    assert!(Spline::periodic(&[0.0, 1.0], &[0.0, 1.0]).is_err());
    assert!(Spline::periodic(&[0.0, 2.0, 1.0], &[0.0, 1.0, 0.5]).is_err());
}

use mech::cam::{Face, Profile};

fn cam(face: Face, offset: f64) -> Profile {
    Profile {
        law: law(Law::Cycloidal, Law::Poly345),
        base_radius: 0.04,
        offset,
        face,
        rocker: None,
    }
}

/// On the base circle (a dwell) the profile is that circle: ρ = R_b, φ = 0 (no offset).
/// Through the rise and fall, a roller follower with no offset has the textbook pressure
/// angle tan φ = s′/(R_p + s) and the polar-curve radius of the pitch curve
/// ρ = ((R_p + s)² + s′²)^{3/2} / ((R_p + s)² + 2 s′² − (R_p + s) s″), less the roller;
/// with an offset e, tan φ = (s′ − e)/(√(R_p² − e²) + s). A flat face: ρ = R_b + s + s″.
#[test]
fn profile_against_textbook_closed_forms() {
    let rf = 0.01;
    let (roller, offset, flat) = (
        cam(Face::Roller(rf), 0.0),
        cam(Face::Roller(rf), 0.008),
        cam(Face::Flat, 0.0),
    );
    let p = roller.at(0.5);
    // measured worst 0 (be05608); exact; a few ulps
    assert!(within((p.curvature_radius - 0.04).abs(), 1e-15) && p.pressure_angle == 0.0);
    let rp: f64 = 0.04 + rf;
    for k in 0..72 {
        let th = TAU * k as f64 / 72.0;
        let [s, s1, s2, _] = roller.law.eval(th);
        let q = rp + s;
        let rho = (q * q + s1 * s1).powf(1.5) / (q * q + 2.0 * s1 * s1 - q * s2);
        let p = roller.at(th);
        assert!(
            within((p.curvature_radius - (rho - rf)).abs(), 2e-14 * rho.abs()), // measured worst 4.2e-16 (be05608); 100×
            "{th}: {} vs {}",
            p.curvature_radius,
            rho - rf
        );
        // measured worst 2.8e-17 (be05608); 100×
        assert!(
            within((p.pressure_angle - (s1 / q).atan()).abs(), 2e-15),
            "{th}"
        );
        let e = 0.008;
        let phi = ((s1 - e) / ((rp * rp - e * e).sqrt() + s)).atan();
        // measured worst 5.6e-17 (be05608); 100×
        assert!(
            within((offset.at(th).pressure_angle - phi).abs(), 5e-15),
            "{th}"
        );
        let f = flat.at(th);
        assert!(
            within((f.curvature_radius - (0.04 + s + s2)).abs(), 1e-15), // measured worst 0 (be05608); exact; a few ulps
            "{th}"
        );
    }
}

/// The profile by its geometry, numerically: the contact points of successive cam angles
/// trace the cam surface, whose curvature radius (the circle through three neighbouring
/// contacts) is `curvature_radius` to 1e-6; a roller's contact is r from its centre; a flat
/// face's contacts stay on the face as the cam turns (the envelope).
#[test]
fn profile_by_its_geometry() {
    for (face, e) in [
        (Face::Knife, 0.005),
        (Face::Roller(0.01), 0.008),
        (Face::Flat, 0.0),
    ] {
        let c = cam(face, e);
        for k in 1..36 {
            let th = TAU * k as f64 / 36.0 + 0.013;
            let h = 1e-4;
            let [a, b, m] = [c.at(th - h).contact, c.at(th).contact, c.at(th + h).contact];
            // The circle through three points: R = |ab| |bc| |ca| / (2 |ab × ac|).
            let d = |p: [f64; 2], q: [f64; 2]| (p[0] - q[0]).hypot(p[1] - q[1]);
            let cross = (b[0] - a[0]) * (m[1] - a[1]) - (b[1] - a[1]) * (m[0] - a[0]);
            let r3 = d(a, b) * d(b, m) * d(m, a) / (2.0 * cross);
            let want = c.at(th).curvature_radius;
            assert!(
                within((r3.abs() - want.abs()).abs(), 1e-6 * want.abs().max(0.01)), // measured worst 8.8e-9 (be05608); three contacts 1e-4 rad apart: a finite difference
                "{face:?} at {th}: {r3} vs {want}"
            );
            if let Face::Roller(r) = face {
                let p = c.at(th);
                // measured worst 6.9e-18 (be05608); 100×
                assert!(within((d(p.pitch, p.contact) - r).abs(), 5e-16));
            }
        }
    }
}

/// Design checks: the largest pressure angle is the textbook one's largest over a fine
/// sweep; a roller larger than the pitch curve's smallest convex radius undercuts, a
/// smaller one does not; a flat face with too small a base circle for its law has a cusp;
/// the CSV and the SVG path carry the contact points.
#[test]
fn design_checks_and_export() {
    let c = cam(Face::Roller(0.01), 0.0);
    let chk = c.check(3600);
    let rp = 0.05;
    let want = (0..3600)
        .map(|k| {
            let [s, s1, _, _] = c.law.eval(TAU * k as f64 / 3600.0);
            (s1 / (rp + s)).atan().abs()
        })
        .fold(0.0f64, f64::max);
    // measured worst 0 (be05608); exact; a few ulps
    assert!(within((chk.max_pressure_angle.0 - want).abs(), 1e-15) && want > 0.1);
    assert!(!chk.undercut && chk.min_convex_radius.0 > 0.0);
    // The pitch curve's smallest convex radius, from a roller of zero radius on the same
    // prime circle: a roller just above it undercuts.
    let knife = Profile {
        base_radius: rp,
        face: Face::Knife,
        ..cam(Face::Knife, 0.0)
    };
    let rho_min = knife.check(3600).min_convex_radius.0;
    let big = rho_min * 1.05;
    let undercut = Profile {
        base_radius: rp - big,
        face: Face::Roller(big),
        ..cam(Face::Knife, 0.0)
    };
    assert!(
        undercut.check(3600).undercut,
        "a roller of {big} m > ρ_min {rho_min} m"
    );
    let small = Profile {
        base_radius: rp - 0.5 * rho_min,
        face: Face::Roller(0.5 * rho_min),
        ..cam(Face::Knife, 0.0)
    };
    assert!(!small.check(3600).undercut);
    let cusp = Profile {
        base_radius: 0.002,
        face: Face::Flat,
        ..cam(Face::Flat, 0.0)
    };
    assert!(cusp.check(3600).undercut);
    let csv = c.to_csv(8);
    let lines: Vec<&str> = csv.lines().collect();
    assert_eq!(lines.len(), 9);
    let row: Vec<f64> = lines[3].split(',').map(|x| x.parse().unwrap()).collect();
    let p = c.at(TAU * 2.0 / 8.0);
    // To the CSV's digits: 90° is printed exactly (90.000000), a contact to 9 decimals of a
    // metre, half a unit of the last the rounding of the format, not an error (measured
    // worst 0, 0, 2.5e-18 (be05608) at this angle).
    assert!(
        within((row[0] - 90.0).abs(), 1e-9)
            && within((row[1] - p.contact[0]).abs(), 5e-10)
            && within((row[2] - p.contact[1]).abs(), 5e-10)
    );
    let path = c.svg_path(8);
    assert!(path.starts_with('M') && path.ends_with('Z') && path.matches('L').count() == 7);
}
