//! Mechanisms described the way a designer does (`docs/conventions.md#dimensions`):
//! lengths and angles with units, named constants and expressions, points assembled from
//! lengths (`polar`, `circle_circle`, `circle_line`, each branch), cgs in the link's frame,
//! and the input's zero where the designer puts it. Every check is against numbers
//! computed here by other formulas (law of cosines, the slider-crank's closed form,
//! hand-converted SI literals), never against the DSL's own evaluation.

use crate::measure::within;
use mech::prelude::*;
use mech::Mechanism;

mechanism! {
    /// Crank-rocker four-bar by its lengths, the coupler above the frame (B on the left of A → O4).
    pub struct FourBarLeft {
        consts { crank: 80 mm, coupler: 260 mm, rocker: 190 mm },
        gravity: (0.0, -9.81),
        ground { O2: (0.0, 0.0), O4: (300 mm, 40 mm) },
        link crank {
            points { O2, A: O2 + polar(crank, 60 deg) },
            mass: 650 g, inertia: 5.2 g_cm2 * 1000, cg: along(25 mm),
        },
        link coupler {
            points { A, B: circle_circle(A, coupler, O4, rocker, left) },
            mass: 1.45 kg, inertia: 0.0112 kg_m2, cg: local(110 mm, 40 mm),
        },
        link rocker {
            points { O4, B },
            mass: 0.95, inertia: 0.0036, cg: along(95 mm),
        },
        joints {
            O2: revolute(ground, crank),
            A: revolute(crank, coupler),
            B: revolute(coupler, rocker),
            O4: revolute(ground, rocker),
        },
        input: O2,
        loads { resist: torque on rocker },
    }
}

mechanism! {
    /// The same four-bar crossed: B on the right of A → O4.
    pub struct FourBarRight {
        consts { crank: 80 mm, coupler: 260 mm, rocker: 190 mm },
        gravity: (0.0, -9.81),
        ground { O2: (0.0, 0.0), O4: (300 mm, 40 mm) },
        link crank {
            points { O2, A: O2 + polar(crank, 60 deg) },
            mass: 650 g, inertia: 5.2 g_cm2 * 1000, cg: along(25 mm),
        },
        link coupler {
            points { A, B: circle_circle(A, coupler, O4, rocker, right) },
            mass: 1.45 kg, inertia: 0.0112 kg_m2, cg: local(110 mm, 40 mm),
        },
        link rocker {
            points { O4, B },
            mass: 0.95, inertia: 0.0036, cg: along(95 mm),
        },
        joints {
            O2: revolute(ground, crank),
            A: revolute(crank, coupler),
            B: revolute(coupler, rocker),
            O4: revolute(ground, rocker),
        },
        input: O2,
        loads { resist: torque on rocker },
    }
}

/// B by the law of cosines: the angle at A between A → O4 and A → B is
/// acos((d² + c² − r²)/(2 d c)), turned counter-clockwise for `left`.
fn four_bar_b(left: bool) -> (Vector2<f64>, Vector2<f64>) {
    let (crank, coupler, rocker) = (0.08, 0.26, 0.19);
    let a = Vector2::new(
        crank * 60f64.to_radians().cos(),
        crank * 60f64.to_radians().sin(),
    );
    let o4 = Vector2::new(0.3, 0.04);
    let d = (o4 - a).norm();
    let base = (o4.y - a.y).atan2(o4.x - a.x);
    let gamma = ((d * d + coupler * coupler - rocker * rocker) / (2.0 * d * coupler)).acos();
    let t = if left { base + gamma } else { base - gamma };
    (a, a + coupler * Vector2::new(t.cos(), t.sin()))
}

#[track_caller]
fn near(what: &str, x: Vector2<f64>, y: Vector2<f64>, tol: f64) {
    assert!(
        within((x - y).norm(), tol),
        "{what}: {x:?} against {y:?} ({:.2e} > {tol:.0e})",
        (x - y).norm()
    );
}

#[test]
fn a_four_bar_from_its_lengths_on_both_branches() {
    let (l, r) = (FourBarLeft::new(), FourBarRight::new());
    let (pl, pr) = (l.params(), r.params());
    let drawn = |p: &FourBarLeftParams| {
        [
            p.points.A,
            p.points.B,
            p.points.O4,
            p.links.crank.cg,
            p.links.coupler.cg,
            p.links.rocker.cg,
        ]
    };
    let right = FourBarLeftParams {
        points: FourBarLeftParamsPoints {
            O2: pr.points.O2,
            O4: pr.points.O4,
            A: pr.points.A,
            B: pr.points.B,
        },
        ..pl.clone()
    };
    let mut right = right;
    right.links.crank.cg = pr.links.crank.cg;
    right.links.coupler.cg = pr.links.coupler.cg;
    right.links.rocker.cg = pr.links.rocker.cg;
    for (left, [pa, pb, po4, g2, g3, g4]) in [(true, drawn(pl)), (false, drawn(&right))] {
        let (a, b) = four_bar_b(left);
        // measured worst 0 (be05608); exact; a few ulps
        near("A", pa, a, 1e-15);
        // measured worst 2.8e-17 (be05608); 100×
        near("B", pb, b, 2e-15);
        assert!(
            within(((pb - pa).norm() - 0.26).abs(), 1e-15)
                && within(((pb - po4).norm() - 0.19).abs(), 1e-15) // measured worst 5.6e-17, 5.6e-17 (be05608); 100×
        );
        // cgs in each link's frame: along(25 mm) on O2 → A, local(110, 40) mm on A → B.
        let e = (b - a) / 0.26;
        // measured worst 1.7e-18 (be05608); 100×
        near("crank cg", g2, a * (0.025 / 0.08), 1e-16);
        near(
            "coupler cg",
            g3,
            a + e * 0.110 + Vector2::new(-e.y, e.x) * 0.040,
            1e-15, // measured worst 2.8e-17 (be05608); 100×
        );
        // measured worst 6.2e-17 (be05608); 100×
        near("rocker cg", g4, po4 + (b - po4) * (0.095 / 0.19), 1e-15);
    }
    assert_eq!(pl.links.crank.inertia, 5.2e-4);
    // Each branch is kept over a turn: B stays on its side of A → O4.
    for k in 0..12 {
        let q = (30.0 * k as f64).to_radians();
        let (pl, pr) = (l.pose(q).unwrap(), r.pose(q).unwrap());
        let side = |a: Vector2<f64>, b: Vector2<f64>, o4: Vector2<f64>| (o4 - a).perp(&(b - a));
        assert!(
            side(pl.points.A.pos, pl.points.B.pos, pl.points.O4.pos) > 0.0,
            "left at q = {q}"
        );
        assert!(
            side(pr.points.A.pos, pr.points.B.pos, pr.points.O4.pos) < 0.0,
            "right at q = {q}"
        );
    }
}

mechanism! {
    /// Offset slider-crank by its lengths; the piston on the far side of the crank.
    pub struct SliderForward {
        consts { r: 43 mm, l: 143 mm, e: 6 mm },
        ground { O2: (0.0, 0.0) },
        link crank { points { O2, A: O2 + polar(r, 30 deg) }, mass: 3.6 kg, inertia: 6.8e-3 kg_m2, cg: along(-5 mm) },
        link rod { points { A, B: circle_line(A, l, (0.0, e), 0 deg, forward) }, mass: 580 g, inertia: 2.1e-3 kg_m2, cg: along(38 mm) },
        link piston { points { B }, mass: 520 g, cg: B },
        joints {
            O2: revolute(ground, crank),
            A: revolute(crank, rod),
            B: revolute(rod, piston),
            guide: prismatic(ground, piston) at B along (1.0, 0.0),
        },
        input: O2,
        loads { gas: force on piston at B },
    }
}

mechanism! {
    /// The same slider-crank with the piston on the other side (B back along the guide).
    pub struct SliderBackward {
        consts { r: 43 mm, l: 143 mm, e: 6 mm },
        ground { O2: (0.0, 0.0) },
        link crank { points { O2, A: O2 + polar(r, 30 deg) }, mass: 3.6 kg, inertia: 6.8e-3 kg_m2, cg: along(-5 mm) },
        link rod { points { A, B: circle_line(A, l, (0.0, e), 0 deg, backward) }, mass: 580 g, inertia: 2.1e-3 kg_m2, cg: along(38 mm) },
        link piston { points { B }, mass: 520 g, cg: B },
        joints {
            O2: revolute(ground, crank),
            A: revolute(crank, rod),
            B: revolute(rod, piston),
            guide: prismatic(ground, piston) at B along (1.0, 0.0),
        },
        input: O2,
        loads { gas: force on piston at B },
    }
}

#[test]
fn a_slider_crank_from_its_lengths_on_both_branches() {
    let (r, l, e) = (0.043, 0.143, 0.006);
    for q in [0.3f64, 1.2, 2.5, 4.0, 5.5] {
        let (a, s) = (
            r * Vector2::new(q.cos(), q.sin()),
            (l * l - (e - r * q.sin()).powi(2)).sqrt(),
        );
        let (f, b) = (
            SliderForward::new().pose(q).unwrap(),
            SliderBackward::new().pose(q).unwrap(),
        );
        // measured worst 1.6e-17 (be05608); 100×
        near("A", f.points.A.pos, a, 1e-15);
        // measured worst 5.6e-17 (be05608); 100×
        near("B forward", f.points.B.pos, Vector2::new(a.x + s, e), 5e-15);
        near(
            "B backward",
            b.points.B.pos,
            Vector2::new(a.x - s, e),
            5e-15, // measured worst 5.6e-17 (be05608); 100×
        );
    }
    let p = SliderForward::new();
    assert_eq!(
        p.params().links.piston.cg,
        p.params().points.B,
        "`cg: B` is the point B"
    );
    assert_eq!(p.params().links.rod.mass, 0.58);
}

mechanism! {
    /// A four-bar in the designer's units and expressions.
    pub struct InUnits {
        consts { side: 40 mm, h: sqrt(3) * side, frame: 300 mm },
        gravity: (0, -9.81),
        ground { O2: (0 mm, 0 mm), O4: (frame, 4 cm) },
        link crank {
            points { O2, A: (side, h) },
            mass: 650 g, inertia: 5200 g_cm2, cg: (11.803847577293369 mm, 32.44486372867091 mm),
        },
        link coupler {
            points { A, B: (243.0191330116403 mm, 231.71119111114735 mm), P: (85.28408845676129 mm, 220.77246544174978 mm) },
            mass: 1.45 kg, inertia: 11200000 g_mm2, cg: (118.23879885921107 mm, 171.57910143510077 mm),
        },
        link rocker {
            points { O4, B },
            mass: 0.95 kg, inertia: 3.6e-3 kg_m2, cg: (280.88744015991685 mm, 132.38349450177364 mm),
        },
        joints {
            O2: revolute(ground, crank),
            A: revolute(crank, coupler),
            B: revolute(coupler, rocker),
            O4: revolute(ground, rocker),
        },
        input: O2,
        loads { tool: force on coupler at P, resist: torque on rocker },
    }
}

mechanism! {
    /// The same four-bar converted to SI by hand.
    pub struct InSi {
        gravity: (0.0, -9.81),
        ground { O2: (0.0, 0.0), O4: (0.3, 0.04) },
        link crank {
            points { O2, A: (0.04, 0.06928203230275509) },
            mass: 0.65, inertia: 0.00052, cg: (0.011803847577293369, 0.03244486372867091),
        },
        link coupler {
            points { A, B: (0.2430191330116403, 0.23171119111114735), P: (0.08528408845676129, 0.22077246544174978) },
            mass: 1.45, inertia: 0.0112, cg: (0.11823879885921107, 0.17157910143510077),
        },
        link rocker {
            points { O4, B },
            mass: 0.95, inertia: 0.0036, cg: (0.28088744015991685, 0.13238349450177364),
        },
        joints {
            O2: revolute(ground, crank),
            A: revolute(crank, coupler),
            B: revolute(coupler, rocker),
            O4: revolute(ground, rocker),
        },
        input: O2,
        loads { tool: force on coupler at P, resist: torque on rocker },
    }
}

/// x and y equal to within the rounding of one unit conversion (one ulp of each factor).
fn same(what: &str, x: f64, y: f64) {
    assert!(
        within((x - y).abs(), 2.0 * f64::EPSILON * y.abs()), // measured worst 0.45 of the bound (be05608); one rounding per unit factor: a bound, not a measurement
        "{what}: {x:e} against {y:e}"
    );
}

#[test]
fn units_and_expressions_give_the_hand_converted_params() {
    let (u, s) = (InUnits::new(), InSi::new());
    let (u, s) = (u.params(), s.params());
    for (what, x, y) in [
        ("O2", u.points.O2, s.points.O2),
        ("O4", u.points.O4, s.points.O4),
        ("A", u.points.A, s.points.A),
        ("B", u.points.B, s.points.B),
        ("P", u.points.P, s.points.P),
        ("crank cg", u.links.crank.cg, s.links.crank.cg),
        ("coupler cg", u.links.coupler.cg, s.links.coupler.cg),
        ("rocker cg", u.links.rocker.cg, s.links.rocker.cg),
        ("gravity", u.gravity, s.gravity),
    ] {
        same(what, x.x, y.x);
        same(what, x.y, y.y);
    }
    for (what, x, y) in [
        ("crank", &u.links.crank, &s.links.crank),
        ("coupler", &u.links.coupler, &s.links.coupler),
        ("rocker", &u.links.rocker, &s.links.rocker),
    ] {
        same(what, x.mass, y.mass);
        same(what, x.inertia, y.inertia);
    }
}

mechanism! {
    /// A vertical engine whose input counts from the top dead centre: q = θ_crank − 90°.
    pub struct Vertical {
        consts { r: 50 mm, l: 200 mm },
        gravity: (0.0, -9.81),
        ground { O2: (0.0, 0.0) },
        link crank { points { O2, A: O2 + polar(r, 90 deg) }, mass: 2 kg, inertia: 4e-3 kg_m2, cg: along(10 mm) },
        link rod { points { A, B: circle_line(A, l, O2, 90 deg, forward) }, mass: 1 kg, inertia: 5e-3 kg_m2, cg: along(60 mm) },
        link piston { points { B }, mass: 0.8 kg, cg: B },
        joints {
            O2: revolute(ground, crank),
            A: revolute(crank, rod),
            B: revolute(rod, piston),
            guide: prismatic(ground, piston) at B along (0.0, 1.0),
        },
        input: O2 from 90 deg,
        loads { gas: force on piston at B },
    }
}

mechanism! {
    /// The same engine with the input the crank's absolute angle.
    pub struct VerticalAbsolute {
        consts { r: 50 mm, l: 200 mm },
        gravity: (0.0, -9.81),
        ground { O2: (0.0, 0.0) },
        link crank { points { O2, A: O2 + polar(r, 90 deg) }, mass: 2 kg, inertia: 4e-3 kg_m2, cg: along(10 mm) },
        link rod { points { A, B: circle_line(A, l, O2, 90 deg, forward) }, mass: 1 kg, inertia: 5e-3 kg_m2, cg: along(60 mm) },
        link piston { points { B }, mass: 0.8 kg, cg: B },
        joints {
            O2: revolute(ground, crank),
            A: revolute(crank, rod),
            B: revolute(rod, piston),
            guide: prismatic(ground, piston) at B along (0.0, 1.0),
        },
        input: O2,
        loads { gas: force on piston at B },
    }
}

#[test]
fn a_vertical_engine_at_45_degrees_after_top_dead_centre() {
    let (r, l) = (0.05, 0.2);
    let (m, abs) = (Vertical::new(), VerticalAbsolute::new());
    let top = m.pose(0.0).unwrap();
    // measured worst 1.5e-17 (be05608); 100×
    near("TDC", top.points.B.pos, Vector2::new(0.0, r + l), 1e-15);
    let q = 45f64.to_radians();
    let p = m.pose(q).unwrap();
    assert!(
        within((p.links.crank.angle - 135f64.to_radians()).abs(), 1e-15), // measured worst 0 (be05608); exact; a few ulps
        "{}",
        p.links.crank.angle
    );
    // The piston's height in closed form: r cos φ + √(l² − r² sin² φ), φ from TDC.
    let y = r * q.cos() + (l * l - (r * q.sin()).powi(2)).sqrt();
    near(
        "piston at 45° after TDC",
        p.points.B.pos,
        Vector2::new(0.0, y),
        1e-15, // measured worst 1.5e-17 (be05608); 100×
    );
    // The motor action's sign is the joint's, whatever the zero: the same torque as the
    // absolute input at θ = q + 90°.
    let loads = VerticalLoads {
        gas: Vector2::new(0.0, -2500.0),
    };
    let abs_loads = VerticalAbsoluteLoads { gas: loads.gas };
    for k in 0..8 {
        let q = 0.1 + 0.8 * k as f64;
        let (mo, ma) = (
            m.kinematics(q, 150.0, 30.0).unwrap(),
            abs.kinematics(q + 90f64.to_radians(), 150.0, 30.0).unwrap(),
        );
        let (t, ta) = (
            m.driver_action(&mo, &loads).unwrap(),
            abs.driver_action(&ma, &abs_loads).unwrap(),
        );
        assert!(
            within((t - ta).abs(), 2e-13 * ta.abs().max(1.0)), // measured worst 2.8e-15 (be05608); 100×
            "q = {q}: {t} against {ta}"
        );
        let z = m.acceleration(q, 150.0, 40.0, &loads).unwrap();
        let za = abs
            .acceleration(q + 90f64.to_radians(), 150.0, 40.0, &abs_loads)
            .unwrap();
        assert!(
            within((z - za).abs(), 2e-13 * za.abs().max(1.0)), // measured worst 3.1e-15 (be05608); 100×
            "q̈ at q = {q}: {z} against {za}"
        );
    }
}

mechanism! {
    /// The slider-crank driven by its piston, the stroke counted from 10 mm past the drawing.
    pub struct PistonDriven {
        consts { r: 43 mm, l: 143 mm, e: 6 mm },
        ground { O2: (0.0, 0.0) },
        link crank { points { O2, A: O2 + polar(r, 60 deg) }, mass: 3.6 kg, inertia: 6.8e-3 kg_m2, cg: along(-5 mm) },
        link rod { points { A, B: circle_line(A, l, (0.0, e), 0 deg, forward) }, mass: 580 g, inertia: 2.1e-3 kg_m2, cg: along(38 mm) },
        link piston { points { B }, mass: 520 g, cg: B },
        joints {
            O2: revolute(ground, crank),
            A: revolute(crank, rod),
            B: revolute(rod, piston),
            guide: prismatic(ground, piston) at B along (1.0, 0.0),
        },
        input: guide from 10 mm,
        loads { shaft: torque on crank },
    }
}

#[test]
fn a_prismatic_input_counts_from_its_zero() {
    let m = PistonDriven::new();
    let b0 = m.params().points.B;
    for q in [-0.03, -0.01, 0.0, 0.005] {
        near(
            "piston",
            m.pose(q).unwrap().points.B.pos,
            b0 + Vector2::new(0.01 + q, 0.0),
            1e-15, // measured worst 0 (be05608); exact; a few ulps
        );
    }
}

#[test]
fn the_run_time_loader_reads_the_same_grammar() {
    let source = include_str!("dimensions.rs");
    for (name, q) in [
        ("Vertical", 0.7),
        ("FourBarRight", 1.1),
        ("SliderBackward", 2.0),
        ("InUnits", 0.4),
    ] {
        let rt =
            Mechanism::from_rust_source(source, name).unwrap_or_else(|e| panic!("{name}: {e}"));
        let reduced = match name {
            "Vertical" => Vertical::new().reduced(q).unwrap(),
            "FourBarRight" => FourBarRight::new().reduced(q).unwrap(),
            "SliderBackward" => SliderBackward::new().reduced(q).unwrap(),
            _ => InUnits::new().reduced(q).unwrap(),
        };
        let i = OneDof::reduced(&rt, q).unwrap().inertia;
        assert!(
            within((i - reduced.inertia).abs(), 1e-15 * reduced.inertia), // measured worst 0 (be05608); exact; a few ulps
            "{name}: I* {i} against {}",
            reduced.inertia
        );
    }
}

#[test]
fn the_run_time_loader_explains_a_missing_branch_word() {
    let text = include_str!("dimensions.rs");
    let start = text.find("pub struct FourBarLeft").unwrap();
    let body = &text[start..text[start..].find("\n}\n").unwrap() + start];
    let bad = body.replace(
        "circle_circle(A, coupler, O4, rocker, left)",
        "circle_circle(A, coupler, O4, rocker)",
    );
    match Mechanism::from_dsl(&bad) {
        Err(MechError::Invalid(msg)) => {
            assert!(
                msg.contains("two points satisfy these lengths")
                    && msg.contains("add `left` or `right`"),
                "{msg}"
            );
            assert!(
                msg.lines().next().unwrap().contains(':'),
                "a location first: {msg}"
            );
        }
        other => panic!("{other:?}"),
    }
}

/// The README's example mechanism, read by the run-time loader: valid, and its piston
/// where the slider-crank's closed form puts it.
#[test]
fn the_readme_mechanism_is_valid() {
    let readme = include_str!("../README.md");
    let at = readme.find("pub struct SliderCrank").unwrap();
    let (start, end) = (
        readme[..at].rfind("```rust").unwrap() + 7,
        at + readme[at..].find("```").unwrap(),
    );
    let m = Mechanism::from_rust_source(&readme[start..end], "SliderCrank").unwrap();
    let (r, l, e) = (0.05, 0.225, 0.012);
    let q = 0.7f64;
    let s = (l * l - (e - r * q.sin()).powi(2)).sqrt();
    let pose = m.pose(&[q]).unwrap();
    let b = pose.point("B").unwrap().pos;
    // measured worst 0 (be05608); exact; a few ulps
    near("B", b, Vector2::new(r * q.cos() + s, e), 1e-15);
}
