//! Strength over the cycle (`Mechanism::strength`, `mech_core::strength`) against hand
//! calculations: a slider-crank held still against a piston force, whose rod is a
//! two-force member (N = P / cos φ, sin φ = r sin θ / l), whose crank bends at its root
//! under the driver torque T = P r sin(θ + φ)/cos φ, whose pins shear under the rod force,
//! and whose rod buckles by Euler's formula; and, the same machine running with gravity,
//! every link's diagram closing (N = V = M = 0 past its far end: the kinetostatics'
//! reactions balance the link's loads, weight and inertia).

use mech::strength::Criterion;
use mech::{Loads, Mechanism};

const PI: f64 = std::f64::consts::PI;
const R: f64 = 0.05;
const L: f64 = 0.2;

/// A slider-crank of steel bars, a steel rod and pins, the piston loaded by `P`.
fn machine(gravity: bool) -> Mechanism {
    let g = if gravity {
        "gravity: (0.0, -9.81), "
    } else {
        ""
    };
    Mechanism::from_dsl(&format!(
        "pub struct SliderCrank {{
            {g}ground {{ O: (0.0, 0.0) }},
            link crank {{
                points {{ O, A: ({R}, 0.0) }},
                shape: bar(width 20 mm, thickness 10 mm), material: steel,
            }},
            link rod {{
                points {{ A, B: ({x}, 0.0) }},
                shape: rod(diameter 16 mm), material: steel,
            }},
            link piston {{ points {{ B }}, mass: 0.5, cg: B }},
            joints {{
                O: revolute(ground, crank) pin 12 mm,
                A: revolute(crank, rod) pin 10 mm double,
                B: revolute(rod, piston) pin 8 mm,
                slide: prismatic(ground, piston) at B along (1.0, 0.0),
            }},
            input: O,
            loads {{ P: force on piston at B }},
        }}",
        x = R + L
    ))
    .expect("the slider-crank loads")
}

fn piston_force(m: &Mechanism, p: f64) -> Loads {
    let mut loads = m.loads();
    assert!(loads.set_by_name("P", &[-p, 0.0]));
    loads
}

fn rel(a: f64, b: f64) -> f64 {
    (a - b).abs() / b.abs()
}

/// At rest (q̇ = 0, so no inertia) against a piston force P at eight crank angles: the
/// largest rod stress is max P/(A cos φ), axial; the crank's largest normal stress is
/// max T/Z + N_crank/A at its root; each pin's shear max R/(n π d²/4).
#[test]
fn a_slider_crank_at_rest_against_hand_calculations() {
    let m = machine(false);
    let p = 2000.0;
    let steps = 8;
    let s = m
        .strength(0.0, 2.0 * PI, steps, |_| Ok(piston_force(&m, p)))
        .unwrap();
    let angles: Vec<f64> = (0..steps)
        .map(|k| 2.0 * PI * k as f64 / steps as f64)
        .collect();
    // The rod force N (compression for a push) at crank angle θ.
    let rod = |t: f64| {
        let phi = (R * t.sin() / L).asin();
        (phi, p / phi.cos())
    };
    let rod_area = PI * 0.016f64.powi(2) / 4.0;
    let rod_max = angles.iter().map(|&t| rod(t).1).fold(0.0, f64::max);
    let c = s.member("rod").unwrap().governing().unwrap();
    let axial = s
        .member("rod")
        .unwrap()
        .checks
        .iter()
        .find(|c| matches!(c.criterion, Criterion::Axial));
    let axial = axial.expect("the rod is a two-force member: its normal-stress check is `axial`");
    assert!(
        rel(axial.stress_max, rod_max / rod_area) < 1e-9,
        "{axial:?} vs {}",
        rod_max / rod_area
    );
    assert!(rel(axial.safety, 310e6 / (rod_max / rod_area)) < 1e-9);
    // Buckling: the rod pushed, λ = L/(d/4) = 50, below the transition √(2π²E/S_y) = 114:
    // Johnson's parabola.
    let lambda: f64 = L / (0.016 / 4.0);
    let transition = (2.0 * PI * PI * 205e9 / 310e6).sqrt();
    let critical = if lambda >= transition {
        PI * PI * 205e9 / lambda.powi(2)
    } else {
        310e6 - (310e6 * lambda / (2.0 * PI)).powi(2) / 205e9
    };
    let b = s
        .member("rod")
        .unwrap()
        .check(Criterion::Buckling)
        .expect("pushed: buckling");
    assert!(
        rel(b.safety, critical / (rod_max / rod_area)) < 1e-9,
        "{b:?}"
    );
    assert!(c.safety <= b.safety && c.safety <= axial.safety);
    // The crank at its root: M = T (the driver's torque), N = the rod force along it.
    let (w, t) = (0.02, 0.01);
    let (area, z) = (w * t, t * w * w / 6.0);
    let crank_max = angles
        .iter()
        .map(|&th| {
            let (phi, n) = rod(th);
            let torque = p * R * (th + phi).sin() / phi.cos();
            // The rod pushes the crank pin along the rod: its component along the crank.
            let along = -n * (th + phi).cos();
            (torque.abs() / z + along.abs() / area).max(along.abs() / area)
        })
        .fold(0.0, f64::max);
    let bend = s
        .member("crank")
        .unwrap()
        .check(Criterion::Bending)
        .expect("the crank bends");
    assert!(
        rel(bend.stress_max, crank_max) < 1e-9,
        "{} vs {crank_max}",
        bend.stress_max
    );
    // Pins: O carries the rod force (the crank is massless here: at rest), A in double shear.
    for (pin, d, n) in [
        ("O.pin", 0.012, 1.0),
        ("A.pin", 0.010, 2.0),
        ("B.pin", 0.008, 1.0),
    ] {
        let shear = s.member(pin).unwrap().check(Criterion::Shear).unwrap();
        let tau = rod_max / (n * PI * d * d / 4.0);
        assert!(
            rel(shear.stress_max, tau) < 1e-9,
            "{pin}: {} vs {tau}",
            shear.stress_max
        );
    }
    // Bearing of A's pin on the thinner bore: the crank's 10 mm (the rod's is its 16 mm).
    let bearing = s
        .member("A.pin")
        .unwrap()
        .check(Criterion::Bearing)
        .unwrap();
    assert!(
        rel(bearing.stress_max, rod_max / (0.010 * 0.010)) < 1e-9,
        "{bearing:?}"
    );
}

/// Running at 300 rad/s with gravity and a piston force: every link's diagram closes at
/// its far end to round-off against its largest internal force, at every instant.
#[test]
fn every_diagram_closes_over_a_running_cycle() {
    let m = machine(true);
    let loads = piston_force(&m, 1500.0);
    for k in 0..24 {
        let q = 2.0 * PI * k as f64 / 24.0;
        let d = m.strength_diagrams(q, 300.0, &loads).unwrap();
        for (name, d) in d {
            let (lo, hi) = d.span();
            let scale = (0..=32)
                .map(|i| {
                    let f = d.at(lo + (hi - lo) * i as f64 / 32.0, false);
                    f.axial
                        .abs()
                        .max(f.shear.abs())
                        .max(f.moment.abs() / d.length())
                })
                .fold(0.0, f64::max);
            assert!(scale > 1.0, "{name} at q = {q}: loaded");
            let end = d.at(hi, true);
            let worst = end
                .axial
                .abs()
                .max(end.shear.abs())
                .max(end.moment.abs() / d.length());
            assert!(
                worst < 1e-9 * scale,
                "{name} at q = {q}: {end:?} against {scale}"
            );
        }
    }
}

/// Bad input: a machine with no member, a speed that is not finite, too few steps.
#[test]
fn bad_input_is_an_error_naming_the_fix() {
    let bare = Mechanism::from_dsl(
        "pub struct Bare {
            ground { O: (0.0, 0.0) },
            link crank { points { O, A: (0.1, 0.0) }, mass: 1.0, cg: O },
            joints { O: revolute(ground, crank) },
            input: O,
        }",
    )
    .unwrap();
    let e = bare
        .strength(10.0, 2.0 * PI, 36, |_| Ok(Loads::default()))
        .unwrap_err();
    assert!(
        e.to_string().contains("shape:") && e.to_string().contains("pin"),
        "{e}"
    );
    let m = machine(false);
    let e = m
        .strength(f64::NAN, 2.0 * PI, 36, |_| Ok(Loads::default()))
        .unwrap_err();
    assert!(e.to_string().contains("finite speed"), "{e}");
    let e = m
        .strength(1.0, 2.0 * PI, 1, |_| Ok(Loads::default()))
        .unwrap_err();
    assert!(e.to_string().contains("steps"), "{e}");
}

/// Sizing (`mech::design::sizing`): the free dimensions of a running slider-crank and of a
/// four-bar reach a fixed point; the sized text re-loads and re-checks with every factor
/// ≥ S; and each single free dimension is the lightest on its grid (one step less fails).
mod sizing {
    use super::*;
    use mech::design::sizing::{free_dimensions, grid_step, size, write_sized, Requirement};

    const SLIDER_CRANK: &str = "pub struct Press {
        gravity: (0.0, -9.81),
        ground { O: (0.0, 0.0) },
        link crank { points { O, A: (60 mm, 0.0) }, shape: bar(width free(30 mm..80 mm), thickness 20 mm), material: steel },
        link rod { points { A, B: (0.0, -800 mm) }, shape: rod(diameter free(12 mm..60 mm)), material: steel },
        link ram { points { B }, mass: 12.0, cg: B },
        joints {
            O: revolute(ground, crank) pin 25 mm,
            A: revolute(crank, rod) pin 11 mm double,
            B: revolute(rod, ram) pin 11 mm double,
            guide: prismatic(ground, ram) at B along (0.0, 1.0),
        },
        input: O,
        loads { work: force on ram at B },
    }";

    const FOUR_BAR: &str = "pub struct Linkage {
        ground { O2: (0.0, 0.0), O4: (0.3, 0.0) },
        link crank { points { O2, A: (0.0, 0.1) }, shape: bar(width free(20 mm..60 mm), thickness 10 mm), material: steel },
        link coupler { points { A, B: (0.25, 0.2) }, shape: bar(width free(20 mm..60 mm), thickness 8 mm), material: aluminium },
        link rocker { points { O4, B }, shape: tube(outer free(20 mm..60 mm), inner 14 mm), material: steel },
        joints {
            O2: revolute(ground, crank) pin 12 mm,
            A: revolute(crank, coupler) pin 10 mm double,
            B: revolute(coupler, rocker) pin 10 mm,
            O4: revolute(ground, rocker) pin 12 mm,
        },
        input: O2,
        loads { tool: torque on rocker },
    }";

    /// Size `text` under the load `load` = value; check the fixed point, the re-check and
    /// the minimality; return the number of passes.
    fn sized(text: &str, load: (&str, &[f64]), speed: f64, s: f64) -> usize {
        let m = Mechanism::from_dsl(text).unwrap();
        let free = free_dimensions(text, None).unwrap();
        let loads_of = |m: &Mechanism| {
            let mut l = m.loads();
            assert!(l.set_by_name(load.0, load.1));
            l
        };
        let req = Requirement {
            safety: s,
            speed,
            period: 2.0 * PI,
            steps: 90,
            irregularity: Some(0.05),
        };
        let out = size(&m, &free, req, |_| Ok(loads_of(&m))).unwrap();
        assert!(out.converged, "{:?}", out.iterations);
        assert!(out.unmet.is_empty(), "{:?}", out.unmet);
        let n = out.iterations.len();
        assert!(
            n >= 2,
            "the last pass repeats the one before: {:?}",
            out.iterations
        );
        let lows: Vec<f64> = free.iter().map(|f| f.lo).collect();
        assert!(
            out.dims.iter().zip(&lows).filter(|(d, lo)| d > lo).count() >= 2,
            "sized: {:?}",
            out.dims
        );
        assert_eq!(out.iterations[n - 1].dims, out.iterations[n - 2].dims);
        let it = &out.iterations[n - 1];
        assert!(it.total_mass > 0.0 && it.peak_torque > 0.0 && it.flywheel.unwrap() > 0.0);
        assert!(it.worst >= s, "{it:?}");
        // The sized file re-loads, and every member meets S.
        let written = write_sized(text, &free, &out.dims);
        assert!(!written.contains("free("), "{written}");
        let again = Mechanism::from_dsl(&written).unwrap();
        let check = again
            .strength(speed, 2.0 * PI, 90, |_| Ok(loads_of(&again)))
            .unwrap();
        for member in &check.members {
            let c = member.governing().unwrap();
            // The written value is the sized one to its grid: the same machine.
            assert!(c.safety >= s * (1.0 - 1e-9), "{}: {c:?}", member.name);
        }
        // Lightest on the grid: one step less of a link's only free dimension fails S.
        for (k, f) in free.iter().enumerate() {
            let alone = free.iter().filter(|g| g.link == f.link).count() == 1;
            let step = grid_step(f.lo, f.hi);
            if !alone || out.dims[k] - step < f.lo {
                continue;
            }
            let mut less = out.mechanism.clone();
            less.set_param(
                &format!("links.{}.shape.{}", f.link, f.name),
                &[out.dims[k] - step],
            )
            .unwrap();
            let weak = less
                .strength(speed, 2.0 * PI, 90, |_| Ok(loads_of(&less)))
                .unwrap();
            let own = weak.member(&f.link).unwrap().governing().unwrap().safety;
            let bearing = weak
                .members
                .iter()
                .filter(|m| m.name.ends_with(".pin"))
                .filter_map(|m| m.check(Criterion::Bearing))
                .map(|c| c.safety)
                .fold(f64::INFINITY, f64::min);
            assert!(
                own.min(bearing) < s,
                "{}.{}: one step less still meets S",
                f.link,
                f.name
            );
        }
        n
    }

    #[test]
    fn a_slider_crank_press_reaches_a_fixed_point() {
        sized(SLIDER_CRANK, ("work", &[0.0, 8e3]), 2.0 * PI, 2.0);
    }

    #[test]
    fn a_four_bar_reaches_a_fixed_point() {
        sized(FOUR_BAR, ("tool", &[-400.0]), 40.0, 2.0);
    }

    /// Nothing free, or S ≤ 0: an error naming the fix.
    #[test]
    fn nothing_to_size_is_an_error() {
        let text = SLIDER_CRANK
            .replace("free(30 mm..80 mm)", "40 mm")
            .replace("free(12 mm..60 mm)", "30 mm");
        let m = Mechanism::from_dsl(&text).unwrap();
        let req = Requirement {
            safety: 2.0,
            speed: 1.0,
            period: 2.0 * PI,
            steps: 10,
            irregularity: None,
        };
        let e = size(&m, &[], req, |_| Ok(m.loads()))
            .unwrap_err()
            .to_string();
        assert!(e.contains("free(10 mm..40 mm)"), "{e}");
        let free = free_dimensions(SLIDER_CRANK, None).unwrap();
        let e = size(&m, &free, Requirement { safety: 0.0, ..req }, |_| {
            Ok(m.loads())
        })
        .unwrap_err();
        assert!(e.to_string().contains("above 0"), "{e}");
    }
}
