//! Balancing (SPEC 3g, issue 31): the shaking force and moment of a single-cylinder engine
//! against a closed form written here and against −Σ of the ground's reactions from the
//! kinetostatics; counterweights and `design::balance`.

use crate::measure::within;
use mech::prelude::*;

const PI: f64 = std::f64::consts::PI;

// A centred slider-crank drawn at θ = 0 (q = θ): crank r, rod l, the crank's cg at a along
// the crank, the rod's at b from A along AB, the piston's at B.
const R: f64 = 0.05;
const L: f64 = 0.18;
const A_CG: f64 = 0.012;
const B_CG: f64 = 0.055;
const M2: f64 = 1.4;
const I2: f64 = 3.1e-3;
const M3: f64 = 0.9;
const I3: f64 = 4.4e-3;
const M4: f64 = 0.7;

mechanism! {
    /// The slider-crank of the closed form (constants above, written out).
    pub struct Single {
        ground { O: (0.0, 0.0) },
        link crank { points { O, A: (0.05, 0.0) }, mass: 1.4, inertia: 3.1e-3, cg: (0.012, 0.0) },
        link rod { points { A, B: (0.23, 0.0) }, mass: 0.9, inertia: 4.4e-3, cg: (0.105, 0.0) },
        link piston { points { B }, mass: 0.7, cg: (0.23, 0.0) },
        joints {
            O: revolute(ground, crank),
            A: revolute(crank, rod),
            B: revolute(rod, piston),
            guide: prismatic(ground, piston) at B along (1.0, 0.0),
        },
        input: O,
    }
}

/// The same text for the run-time mechanism.
const SINGLE: &str = "pub struct Single {
    ground { O: (0.0, 0.0) },
    link crank { points { O, A: (0.05, 0.0) }, mass: 1.4, inertia: 3.1e-3, cg: (0.012, 0.0) },
    link rod { points { A, B: (0.23, 0.0) }, mass: 0.9, inertia: 4.4e-3, cg: (0.105, 0.0) },
    link piston { points { B }, mass: 0.7, cg: (0.23, 0.0) },
    joints {
        O: revolute(ground, crank),
        A: revolute(crank, rod),
        B: revolute(rod, piston),
        guide: prismatic(ground, piston) at B along (1.0, 0.0),
    },
    input: O,
}";

/// The closed form at crank angle θ, rate ω, acceleration α: (Fx, Fy, M).
/// x_B = r cos θ + D, D = √(l² − r² sin² θ), differentiated twice by hand:
/// x' = −r s − r² s c / D, x'' = −r c − r² (c² − s²)/D − r⁴ s² c²/D³; the rod's angle
/// sin φ = −(r/l) sin θ: φ' = −r c/D, φ'' = r s/D − r³ s c²/D³.
fn closed_form(th: f64, w: f64, al: f64) -> [f64; 3] {
    let (s, c) = th.sin_cos();
    let d = (L * L - R * R * s * s).sqrt();
    let x1 = -R * s - R * R * s * c / d;
    let x2 = -R * c - R * R * (c * c - s * s) / d - R.powi(4) * s * s * c * c / d.powi(3);
    let xdd = x2 * w * w + x1 * al;
    let p1 = -R * c / d;
    let p2 = R * s / d - R.powi(3) * s * c * c / d.powi(3);
    let phidd = p2 * w * w + p1 * al;
    // Accelerations of a point at radius ρ on the crank.
    let on_crank = |rho: f64| [rho * (-s * al - c * w * w), rho * (c * al - s * w * w)];
    let a_a = on_crank(R);
    let a2 = on_crank(A_CG);
    let k = B_CG / L;
    let a3 = [(1.0 - k) * a_a[0] + k * xdd, (1.0 - k) * a_a[1]];
    let a4 = [xdd, 0.0];
    let g2 = [A_CG * c, A_CG * s];
    let (ax, ay) = (R * c, R * s);
    let xb = R * c + d;
    let g3 = [(1.0 - k) * ax + k * xb, (1.0 - k) * ay];
    let g4 = [xb, 0.0];
    let fx = -(M2 * a2[0] + M3 * a3[0] + M4 * a4[0]);
    let fy = -(M2 * a2[1] + M3 * a3[1] + M4 * a4[1]);
    let cr = |g: [f64; 2], m: f64, a: [f64; 2]| m * (g[0] * a[1] - g[1] * a[0]);
    let mo = -(cr(g2, M2, a2) + cr(g3, M3, a3) + cr(g4, M4, a4) + I2 * al + I3 * phidd);
    [fx, fy, mo]
}

/// The generated `shaking` and the run-time one against the closed form over a turn, at
/// a steady speed and while accelerating, to 1e-9 of the peaks.
#[test]
fn single_cylinder_shaking_against_its_closed_form() {
    let g = Single::new();
    let rt = mech::Mechanism::from_dsl(SINGLE).unwrap();
    for (w, al) in [(300.0, 0.0), (120.0, 2500.0)] {
        let rows: Vec<([f64; 3], [f64; 3], [f64; 3])> = (0..72)
            .map(|k| {
                let th = 2.0 * PI * k as f64 / 72.0;
                let mg = g.motion(&[th], &[w], &[al]).unwrap();
                let sg = g.shaking(&mg);
                let mr = rt.motion(&[th], &[w], &[al]).unwrap();
                let sr = rt.shaking(&mr);
                (
                    closed_form(th, w, al),
                    [sg.force.x, sg.force.y, sg.moment],
                    [sr.force.x, sr.force.y, sr.moment],
                )
            })
            .collect();
        for i in 0..3 {
            let peak = rows.iter().map(|r| r.0[i].abs()).fold(0.0, f64::max);
            assert!(peak > 1.0);
            for (want, gen, run) in &rows {
                assert!(
                    within((gen[i] - want[i]).abs(), 1e-9 * peak),
                    "{i}: {gen:?} vs {want:?}"
                );
                assert!(
                    within((run[i] - want[i]).abs(), 1e-9 * peak),
                    "{i}: {run:?} vs {want:?}"
                );
            }
        }
    }
}

/// F = −Σ of the forces the ground puts on the links (the reactions at its joints, by the
/// ground on the crank and on the piston), M = −(their moments about the origin + the
/// guide's moment + the driver's torque, whose reaction is on the stator): the
/// kinetostatics with no loads and no gravity, for the engine of `examples/mech` too.
#[test]
fn shaking_is_minus_the_ground_reactions() {
    let engine = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/examples/mech/engine.mech"
    ))
    .unwrap()
    .replace("gravity: (0.0, -9.81),", "");
    for text in [SINGLE, engine.as_str()] {
        let m = mech::Mechanism::from_dsl(text).unwrap();
        let model = m.model();
        let loads = m.loads();
        for k in 0..36 {
            let q = 2.0 * PI * k as f64 / 36.0;
            let motion = m.motion(&[q], &[250.0], &[-800.0]).unwrap();
            let s = m.shaking(&motion);
            let f = m.kinetostatics(&motion, &loads).unwrap();
            let (mut force, mut moment) = (Vector2::zeros(), f.driver[0]);
            for (j, joint) in model.joints.iter().enumerate() {
                let r = f.joints[j];
                // By the ground on the link: the reaction itself when the ground is a,
                // its negative when it is b.
                let sign = match (joint.a, joint.b) {
                    (0, _) => 1.0,
                    (_, 0) => -1.0,
                    _ => continue,
                };
                let at = motion.points[joint.point].pos;
                force += r.force * sign;
                moment += sign * (at.x * r.force.y - at.y * r.force.x + r.moment.unwrap_or(0.0));
            }
            let scale = 1.0 + s.force.norm();
            assert!(
                within((s.force + force).norm(), 1e-9 * scale),
                "{q}: {:?} vs {force:?}",
                s.force
            );
            assert!(
                within((s.moment + moment).abs(), 1e-9 * scale),
                "{q}: {} vs {moment}",
                s.moment
            );
        }
    }
}

const FOUR_BAR: &str = "pub struct Linkage {
    ground { O2: (0.0, 0.0), O4: (0.3, 0.0) },
    link crank { points { O2, A: (0.0, 0.1) }, mass: 0.5, inertia: 4e-4, cg: (0.01, 0.05) },
    link coupler { points { A, B: (0.25, 0.2), P: (0.1, 0.3) }, mass: 1.0, inertia: 6e-3, cg: (0.12, 0.22) },
    link rocker { points { O4, B }, mass: 0.8, inertia: 3e-3, cg: (0.28, 0.1) },
    joints {
        O2: revolute(ground, crank),
        A: revolute(crank, coupler),
        B: revolute(coupler, rocker),
        O4: revolute(ground, rocker),
    },
    input: O2,
}";

/// The four-bar with the two counterweights of `force_balance` written into its file: its
/// shaking force over a turn (at a speed and an acceleration) stays below 1e-9 of the
/// unbalanced one's peak, sample by sample.
#[test]
fn a_force_balanced_four_bar_shakes_no_more() {
    use mech::design::balance::{force_balance, write_counterweights};
    let before = mech::Mechanism::from_dsl(FOUR_BAR).unwrap();
    let weights = force_balance(before.model(), 0.0, None).unwrap();
    assert_eq!(weights.len(), 2);
    assert!(weights.iter().all(|w| w.mass > 0.0));
    let text = write_counterweights(FOUR_BAR, &weights).unwrap();
    assert_eq!(text.matches("counterweight:").count(), 2);
    let after = mech::Mechanism::from_dsl(&text).unwrap();
    let force = |m: &mech::Mechanism, q: f64| {
        let motion = m.motion(&[q], &[40.0], &[300.0]).unwrap();
        m.shaking(&motion).force.norm()
    };
    let qs: Vec<f64> = (0..90).map(|k| 2.0 * PI * k as f64 / 90.0).collect();
    let peak = qs.iter().map(|&q| force(&before, q)).fold(0.0, f64::max);
    assert!(peak > 10.0, "{peak}");
    for &q in &qs {
        let f = force(&after, q);
        assert!(
            within(f, 1e-9 * peak),
            "at {q}: {f} N against {peak} N unbalanced"
        );
    }
}

/// A counterweight is a point mass fixed to the link: the resolved link's mass, cg and I_G
/// are the two bodies combined, by the parallel-axis theorem written out here.
#[test]
fn a_counterweight_adds_a_point_mass_to_its_link() {
    let text = SINGLE.replace(
        "cg: (0.012, 0.0) },",
        "cg: (0.012, 0.0), counterweight: (2.0 kg, at (-0.03, 0.01)) },",
    );
    let m = mech::Mechanism::from_dsl(&text).unwrap();
    let crank = &m.model().links[1];
    let (m1, g1, m2, g2) = (M2, [A_CG, 0.0], 2.0, [-0.03, 0.01]);
    let mt = m1 + m2;
    let g = [
        (m1 * g1[0] + m2 * g2[0]) / mt,
        (m1 * g1[1] + m2 * g2[1]) / mt,
    ];
    let d2 = |p: [f64; 2]| (p[0] - g[0]).powi(2) + (p[1] - g[1]).powi(2);
    let i = I2 + m1 * d2(g1) + m2 * d2(g2);
    assert!(within((crank.mass.unwrap() - mt).abs(), 1e-15 * mt));
    assert!(within(
        (crank.cg[0] - g[0]).abs() + (crank.cg[1] - g[1]).abs(),
        1e-15
    ));
    assert!(within((crank.inertia - i).abs(), 1e-15 * i));
    // A massless link with a counterweight: its mass and cg are the counterweight's.
    let rod = SINGLE.replace(
        "mass: 0.9, inertia: 4.4e-3, cg: (0.105, 0.0) },",
        "counterweight: (0.3, at (0.1, 0.02)) },",
    );
    let m = mech::Mechanism::from_dsl(&rod).unwrap();
    let l = &m.model().links[2];
    assert_eq!((l.mass, l.cg, l.inertia), (Some(0.3), [0.1, 0.02], 0.0));
}

/// Khurmi & Gupta, *Theory of Machines*, Example 22.1: a single-cylinder engine at 240 rpm,
/// stroke 300 mm (r = 150 mm), reciprocating parts 50 kg, revolving parts 37 kg at the crank
/// radius; all the revolving and two thirds of the reciprocating parts balanced by a mass at
/// 400 mm: B = (37 + ⅔·50)·0.15/0.4 = 26.375 kg ("26.38 kg"); the residual unbalanced force
/// 60° from top dead centre m ω² r √((1 − c)² cos² θ + c² sin² θ) = 2.847 kN ("2.85 kN") at
/// tan⁻¹(c sin θ/((1 − c) cos θ)) = 73.9° to the line of stroke. Here the revolving parts
/// are the crank's mass at the pin, the reciprocating the piston's, the rod (600 mm) massless:
/// the exact motion's primary harmonic is the textbook's force (the piston's order-1 term is
/// exactly −r ω² cos θ, a massless rod adds none).
#[test]
fn the_textbook_single_cylinder_counterweight() {
    use mech::design::balance::{force_balance, shaking_cycle, write_counterweights};
    let text = KHURMI;
    let m = mech::Mechanism::from_dsl(text).unwrap();
    let w = force_balance(m.model(), 2.0 / 3.0, Some(0.4)).unwrap();
    assert_eq!(w.len(), 1);
    // The hand number, and the book's rounding of it.
    assert!(within((w[0].mass - 26.375).abs(), 1e-12 * 26.375), "{w:?}");
    assert!((w[0].mass - 26.38).abs() < 0.0051);
    assert!(
        within((w[0].at[0] + 0.4).abs() + w[0].at[1].abs(), 1e-15),
        "{w:?}"
    );
    let balanced = mech::Mechanism::from_dsl(&write_counterweights(text, &w).unwrap()).unwrap();
    let omega = 240.0 * 2.0 * PI / 60.0;
    let cycle = shaking_cycle(&balanced, (0.0, 2.0 * PI, 360), &[0.0], &[omega]).unwrap();
    let h = cycle.summary().harmonics[0];
    let th = 60f64.to_radians();
    let (s, c) = th.sin_cos();
    let primary = Vector2::new(h.fx[0] * c + h.fx[1] * s, h.fy[0] * c + h.fy[1] * s);
    let hand = 50.0
        * omega
        * omega
        * 0.15
        * (((1.0f64 / 3.0) * c).powi(2) + ((2.0f64 / 3.0) * s).powi(2)).sqrt();
    assert!(
        within((primary.norm() - hand).abs(), 1e-9 * hand),
        "{primary:?} vs {hand}"
    );
    assert!((primary.norm() - 2847.0).abs() < 1.0, "{}", primary.norm());
    let angle = primary.y.abs().atan2(primary.x.abs()).to_degrees();
    assert!((angle - 73.9).abs() < 0.05, "{angle}");
}

/// Khurmi's engine of the test above (a massless 600 mm rod).
const KHURMI: &str = "pub struct Khurmi {
        ground { O: (0.0, 0.0) },
        link crank { points { O, A: (150 mm, 0.0) }, mass: 37 kg, cg: A },
        link rod { points { A, B: (750 mm, 0.0) } },
        link piston { points { B }, mass: 50 kg, cg: B },
        joints {
            O: revolute(ground, crank),
            A: revolute(crank, rod),
            B: revolute(rod, piston),
            guide: prismatic(ground, piston) at B along (1.0, 0.0),
        },
        input: O,
    }";

/// `optimal_balance` with the shaking force's RMS alone: the primary residual's mean square
/// is m² r² ω⁴ ((1 − C)² + C²)/2 (the secondary, orthogonal over the cycle, untouched), least
/// at C = ½ — the counterweight (37 + ½·50) kg · 0.15 m / 0.4 m = 23.25 kg opposite the
/// crank.
#[test]
fn optimal_counterweight_of_the_textbook_engine() {
    use mech::design::balance::{optimal_balance, BalanceWeights};
    let omega = 240.0 * 2.0 * PI / 60.0;
    let force_only = BalanceWeights {
        force: 1.0,
        moment: 0.0,
        driver: 0.0,
    };
    let w = optimal_balance(KHURMI, omega, force_only, Some(0.4)).unwrap();
    assert_eq!(w.len(), 1, "{w:?}");
    assert!((w[0].mass - 23.25).abs() < 1e-6 * 23.25, "{w:?}");
    assert!((w[0].at[0] + 0.4).abs() + w[0].at[1].abs() < 1e-6, "{w:?}");
}
