//! The hand-written floor (`benches/floor/hand.rs`) computes the same numbers as the
//! generated solvers: every quantity of every operation timed in `benches/floor.rs`, on a
//! sweep of 72 crank angles over a full turn, to 1e-13 relative (`TOL`: at most 100× the
//! worst error measured over the quantities).
//!
//! "Relative" is scaled by the largest entry of the quantity: for a quantity made of
//! several entries (the three link angles, the cg positions of the three links, the pin
//! forces of the four joints, ...) the largest |entry| at that q; for a single scalar
//! (driver torque, I*, dI*/dq, M*, q̈), which can cross zero inside the turn, the largest
//! |value| over the sweep. Angles are compared modulo 2π (the generated angles are
//! wrapped to (−π, π], the hand-written crank angle is q itself).
//!
//! Independent checks of the hand-written side (so that a shared mistake cannot pass):
//! central finite differences of positions against velocities and of velocities against
//! accelerations, of I* against dI*/dq, and the inverse problem (the generated d'Alembert
//! driver at the hand-written q̈ gives back the applied torque).

use crate::measure::{within, within_at};
use crate::mechanisms;

#[path = "../benches/floor/hand.rs"]
mod hand;

use hand::*;
use mech::prelude::*;
use mechanisms::*;
use std::collections::BTreeMap;
use std::f64::consts::{PI, TAU};

// measured worst 1.9e-15 over the quantities (be05608); 100×
const TOL: f64 = 1e-13;
const STEPS: usize = 72;
const QD: f64 = 12.0;
const QDD: f64 = -3.0;

fn sweep() -> impl Iterator<Item = f64> {
    (0..STEPS).map(|k| 0.7 + TAU * k as f64 / STEPS as f64)
}

fn wrap(a: f64) -> f64 {
    let r = a - TAU * (a / TAU).round();
    if r <= -PI {
        r + TAU
    } else {
        r
    }
}

/// One sample of a quantity: largest |generated − hand| and largest |entry| at one q.
#[derive(Default)]
struct Samples {
    scalar: bool,
    rows: Vec<(f64, f64, f64)>, // (q, diff, largest entry)
}

/// Every compared quantity, by name.
#[derive(Default)]
struct Report(BTreeMap<&'static str, Samples>);

impl Report {
    fn record(
        &mut self,
        name: &'static str,
        q: f64,
        scalar: bool,
        pairs: &[(f64, f64)],
        angle: bool,
    ) {
        let mut diff: f64 = 0.0;
        let mut big: f64 = 0.0;
        for &(g, h) in pairs {
            assert!(
                g.is_finite() && h.is_finite(),
                "{name} at q = {q}: generated {g}, hand {h}"
            );
            let d = if angle { wrap(g - h) } else { g - h };
            diff = diff.max(d.abs());
            big = big.max(g.abs()).max(h.abs());
        }
        let s = self.0.entry(name).or_default();
        s.scalar = scalar;
        s.rows.push((q, diff, big));
    }
    fn vecs(&mut self, name: &'static str, q: f64, pairs: &[(Vector2<f64>, Vector2<f64>)]) {
        let flat: Vec<(f64, f64)> = pairs
            .iter()
            .flat_map(|(g, h)| [(g.x, h.x), (g.y, h.y)])
            .collect();
        self.record(name, q, false, &flat, false);
    }
    fn scalars(&mut self, name: &'static str, q: f64, pairs: &[(f64, f64)]) {
        self.record(name, q, false, pairs, false);
    }
    fn angles(&mut self, name: &'static str, q: f64, pairs: &[(f64, f64)]) {
        self.record(name, q, false, pairs, true);
    }
    fn scalar(&mut self, name: &'static str, q: f64, g: f64, h: f64) {
        self.record(name, q, true, &[(g, h)], false);
    }
    /// Print the worst relative error of each quantity and fail on any above `TOL`.
    fn check(&self, expected: &[&str]) {
        for name in expected {
            assert!(
                self.0.contains_key(name),
                "quantity {name} was not compared"
            );
        }
        let mut failures = Vec::new();
        for (name, s) in &self.0 {
            assert!(s.rows.len() >= 50, "{name}: only {} samples", s.rows.len());
            let sweep_big = s.rows.iter().fold(0.0f64, |m, r| m.max(r.2));
            let mut worst = (0.0f64, 0.0);
            for &(q, diff, big) in &s.rows {
                let scale = if s.scalar {
                    sweep_big
                } else {
                    big.max(if name.contains("angle") { 1.0 } else { 0.0 })
                };
                let rel = if scale > 0.0 {
                    diff / scale
                } else if diff == 0.0 {
                    0.0
                } else {
                    f64::INFINITY
                };
                if rel > worst.0 {
                    worst = (rel, q);
                }
                if !within_at(name, rel, TOL) {
                    failures.push(format!("{name} at q = {q:.6}: |generated − hand| = {diff:.3e}, scale {scale:.3e}, relative {rel:.3e}"));
                }
            }
            println!(
                "{name:<40} worst relative {:.2e} (q = {:.4})",
                worst.0, worst.1
            );
        }
        assert!(
            failures.is_empty(),
            "hand-written and generated disagree:\n{}",
            failures.join("\n")
        );
    }
}

fn four_bar_loads() -> FourBarLoads {
    let mut l = FourBarLoads::default();
    assert!(l.set_by_name("tool", &[80.0, -60.0]));
    assert!(l.set_by_name("resist", &[2.0]));
    l
}

fn slider_crank_loads() -> SliderCrankLoads {
    let mut l = SliderCrankLoads::default();
    assert!(l.set_by_name("gas", &[-1500.0, 0.0]));
    assert!(l.set_by_name("shaft", &[-4.0]));
    l
}

#[test]
fn four_bar_hand_matches_generated() {
    let m = FourBar::new();
    let h = FourBarHand::new(m.params());
    let loads = four_bar_loads();
    let mut r = Report::default();
    for q in sweep() {
        // pose
        let gp = m.pose(q).unwrap();
        let hp = h.pose(q).unwrap();
        r.angles(
            "pose: link angle",
            q,
            &[
                (gp.links.crank.angle, hp.crank.angle),
                (gp.links.coupler.angle, hp.coupler.angle),
                (gp.links.rocker.angle, hp.rocker.angle),
            ],
        );
        r.vecs(
            "pose: link cg",
            q,
            &[
                (gp.links.crank.cg, hp.crank.cg),
                (gp.links.coupler.cg, hp.coupler.cg),
                (gp.links.rocker.cg, hp.rocker.cg),
            ],
        );
        r.vecs(
            "pose: point pos",
            q,
            &[
                (gp.points.O2.pos, hp.o2),
                (gp.points.O4.pos, hp.o4),
                (gp.points.A.pos, hp.a),
                (gp.points.B.pos, hp.b),
                (gp.points.P.pos, hp.p),
            ],
        );

        // kinematics
        let gm = m.kinematics(q, QD, QDD).unwrap();
        let hm = h.kinematics(q, QD, QDD).unwrap();
        let links = [
            (&gm.links.crank, &hm.crank),
            (&gm.links.coupler, &hm.coupler),
            (&gm.links.rocker, &hm.rocker),
        ];
        r.angles(
            "kinematics: link angle",
            q,
            &links.map(|(g, h)| (g.angle, h.angle)),
        );
        r.scalars(
            "kinematics: link omega",
            q,
            &links.map(|(g, h)| (g.omega, h.omega)),
        );
        r.scalars(
            "kinematics: link alpha",
            q,
            &links.map(|(g, h)| (g.alpha, h.alpha)),
        );
        r.vecs("kinematics: link cg", q, &links.map(|(g, h)| (g.cg, h.cg)));
        r.vecs(
            "kinematics: link cg_vel",
            q,
            &links.map(|(g, h)| (g.cg_vel, h.cg_vel)),
        );
        r.vecs(
            "kinematics: link cg_acc",
            q,
            &links.map(|(g, h)| (g.cg_acc, h.cg_acc)),
        );
        let points = [
            (&gm.points.O2, &hm.o2),
            (&gm.points.O4, &hm.o4),
            (&gm.points.A, &hm.a),
            (&gm.points.B, &hm.b),
            (&gm.points.P, &hm.p),
        ];
        r.vecs(
            "kinematics: point pos",
            q,
            &points.map(|(g, h)| (g.pos, h.pos)),
        );
        r.vecs(
            "kinematics: point vel",
            q,
            &points.map(|(g, h)| (g.vel, h.vel)),
        );
        r.vecs(
            "kinematics: point acc",
            q,
            &points.map(|(g, h)| (g.acc, h.acc)),
        );

        // kinetostatics and driver_action
        let gf = m.kinetostatics(&gm, &loads).unwrap();
        let hf = h.kinetostatics(&hm, &loads);
        r.vecs(
            "kinetostatics: joint force",
            q,
            &[
                (gf.joints.O2.force, hf.o2),
                (gf.joints.A.force, hf.a),
                (gf.joints.B.force, hf.b),
                (gf.joints.O4.force, hf.o4),
            ],
        );
        let gd = m.driver_action(&gm, &loads).unwrap();
        let hd = h.driver_action(&hm, &loads);
        r.scalar(
            "driver: generated d'Alembert vs hand d'Alembert",
            q,
            gf.driver,
            hf.driver,
        );
        r.scalar(
            "driver: generated virtual power vs hand virtual power",
            q,
            gd,
            hd,
        );
        r.scalar(
            "driver: generated d'Alembert vs hand virtual power",
            q,
            gf.driver,
            hd,
        );
        r.scalar(
            "driver: generated virtual power vs hand d'Alembert",
            q,
            gd,
            hf.driver,
        );
    }
    r.check(&[
        "pose: link angle",
        "pose: link cg",
        "pose: point pos",
        "kinematics: link angle",
        "kinematics: link omega",
        "kinematics: link alpha",
        "kinematics: link cg",
        "kinematics: link cg_vel",
        "kinematics: link cg_acc",
        "kinematics: point pos",
        "kinematics: point vel",
        "kinematics: point acc",
        "kinetostatics: joint force",
    ]);
}

#[test]
fn slider_crank_hand_matches_generated() {
    let m = SliderCrank::new();
    let h = SliderCrankHand::new(m.params());
    let loads = slider_crank_loads();
    let driver = 5.0;
    let mut r = Report::default();
    for q in sweep() {
        let g = m.reduced(q).unwrap();
        let hr = h.reduced(q).unwrap();
        r.scalar("reduced: I*", q, g.inertia, hr.inertia);
        r.scalar(
            "reduced: dI*/dq",
            q,
            g.inertia_derivative,
            hr.inertia_derivative,
        );
        r.scalar(
            "reduced_moment: M*",
            q,
            m.reduced_moment(q, &loads).unwrap(),
            h.reduced_moment(q, &loads).unwrap(),
        );
        r.scalar(
            "acceleration: q̈ (gravity, loads, driver)",
            q,
            m.acceleration(q, QD, driver, &loads).unwrap(),
            h.acceleration(q, QD, driver, &loads).unwrap(),
        );
        r.scalar(
            "acceleration: q̈ (gravity only, no driver)",
            q,
            m.acceleration(q, QD, 0.0, &SliderCrankLoads::default())
                .unwrap(),
            h.acceleration(q, QD, 0.0, &SliderCrankLoads::default())
                .unwrap(),
        );
    }
    r.check(&["reduced: I*", "reduced: dI*/dq", "reduced_moment: M*"]);
}

/// Central difference of `f` at `q` with step `h`.
fn diff<T, F: Fn(f64) -> T>(
    f: F,
    q: f64,
    h: f64,
    get: impl Fn(&T) -> Vector2<f64>,
) -> Vector2<f64> {
    (get(&f(q + h)) - get(&f(q - h))) / (2.0 * h)
}

/// The hand-written four-bar against itself by finite differences: d(position)/dq = the
/// velocity at q̇ = 1, q̈ = 0; d(velocity at q̇ = 1)/dq = the acceleration at q̇ = 1, q̈ = 0;
/// and q̈ enters linearly (acceleration at q̇ = 0, q̈ = 1 is the velocity at q̇ = 1).
#[test]
fn four_bar_hand_by_finite_differences() {
    let h = FourBarHand::new(FourBar::new().params());
    let step = 1e-5;
    for q in sweep() {
        let k = h.kinematics(q, 1.0, 0.0).unwrap();
        let pos = |q| h.kinematics(q, 1.0, 0.0).unwrap();
        let checks: [(
            &str,
            fn(&FourBarHandMotion) -> (Vector2<f64>, Vector2<f64>, Vector2<f64>),
        ); 6] = [
            ("A", |m| (m.a.pos, m.a.vel, m.a.acc)),
            ("B", |m| (m.b.pos, m.b.vel, m.b.acc)),
            ("P", |m| (m.p.pos, m.p.vel, m.p.acc)),
            ("crank cg", |m| (m.crank.cg, m.crank.cg_vel, m.crank.cg_acc)),
            ("coupler cg", |m| {
                (m.coupler.cg, m.coupler.cg_vel, m.coupler.cg_acc)
            }),
            ("rocker cg", |m| {
                (m.rocker.cg, m.rocker.cg_vel, m.rocker.cg_acc)
            }),
        ];
        for (name, get) in checks {
            let (_, v, a) = get(&k);
            let fv = diff(pos, q, step, |m| get(m).0);
            let fa = diff(pos, q, step, |m| get(m).1);
            assert!(
                within((fv - v).norm(), 5e-9 * v.norm().max(0.1)), // measured worst 9.2e-11 (be05608); 100×
                "{name} velocity at {q}: fd {fv:?} vs {v:?}"
            );
            assert!(
                within((fa - a).norm(), 1e-8 * a.norm().max(0.1)), // measured worst 1.2e-10 (be05608); 100×
                "{name} acceleration at {q}: fd {fa:?} vs {a:?}"
            );
        }
        let ang = |m: &FourBarHandMotion| Vector2::new(m.coupler.angle, m.rocker.angle);
        let fw = diff(pos, q, step, |m| ang(m));
        let fw = Vector2::new(
            wrap(fw.x * 2.0 * step) / (2.0 * step),
            wrap(fw.y * 2.0 * step) / (2.0 * step),
        );
        let w = Vector2::new(k.coupler.omega, k.rocker.omega);
        assert!(
            within((fw - w).norm(), 1e-8 * w.norm()), // measured worst 1.3e-10 (be05608); 100×
            "omega at {q}: fd {fw:?} vs {w:?}"
        );
        let fal = diff(pos, q, step, |m| {
            Vector2::new(m.coupler.omega, m.rocker.omega)
        });
        let al = Vector2::new(k.coupler.alpha, k.rocker.alpha);
        assert!(
            within((fal - al).norm(), 1e-8 * al.norm().max(0.1)), // measured worst 1.1e-10 (be05608); 100×
            "alpha at {q}: fd {fal:?} vs {al:?}"
        );
        let lin = h.kinematics(q, 0.0, 1.0).unwrap();
        assert!(
            within(
                (lin.coupler.alpha - k.coupler.omega).abs(),
                1e-15 * k.coupler.omega.abs().max(1.0)
            ) // measured worst 0 (be05608); exact; a few ulps
        );
        // measured worst 0 (be05608); exact; a few ulps
        assert!(within((lin.p.acc - k.p.vel).norm(), 1e-15 * k.p.vel.norm()));
    }
}

/// The hand-written slider-crank against itself and against the generated d'Alembert:
/// dI*/dq by finite differences of I*, M* by the power of the loads computed from finite
/// differences of the generated positions, and the inverse problem at the hand-written q̈.
#[test]
fn slider_crank_hand_independent_checks() {
    let m = SliderCrank::new();
    let h = SliderCrankHand::new(m.params());
    let loads = slider_crank_loads();
    let p = m.params().clone();
    let step = 1e-5;
    let (driver, qd) = (5.0, QD);
    for q in sweep() {
        let r = h.reduced(q).unwrap();
        let fd = (h.reduced(q + step).unwrap().inertia - h.reduced(q - step).unwrap().inertia)
            / (2.0 * step);
        assert!(
            within(
                (fd - r.inertia_derivative).abs(),
                1e-8 * r.inertia.max(1e-6)
            ), // measured worst 1.4e-10 (be05608); 100×
            "dI*/dq at {q}: fd {fd} vs {}",
            r.inertia_derivative
        );

        // M* = Σ m g·dG/dq + F_gas·dB/dq + T_shaft·1, with positions from the generated pose.
        let gcg = |q: f64| m.pose(q).unwrap();
        let d = |get: &dyn Fn(&SliderCrankPose) -> Vector2<f64>| {
            (get(&gcg(q + step)) - get(&gcg(q - step))) / (2.0 * step)
        };
        let mstar = p.links.crank.mass * p.gravity.dot(&d(&|s| s.links.crank.cg))
            + p.links.rod.mass * p.gravity.dot(&d(&|s| s.links.rod.cg))
            + p.links.piston.mass * p.gravity.dot(&d(&|s| s.links.piston.cg))
            + loads.gas.dot(&d(&|s| s.points.B.pos))
            + loads.shaft;
        let hm = h.reduced_moment(q, &loads).unwrap();
        assert!(
            within((mstar - hm).abs(), 5e-8 * hm.abs().max(1.0)), // measured worst 9.8e-10 (be05608); 100×
            "M* at {q}: fd {mstar} vs {hm}"
        );

        // Inverse problem: the generated d'Alembert at the hand-written q̈ needs the applied torque.
        let qdd = h.acceleration(q, qd, driver, &loads).unwrap();
        let motion = m.kinematics(q, qd, qdd).unwrap();
        let t = m.kinetostatics(&motion, &loads).unwrap().driver;
        assert!(
            within((t - driver).abs(), 2e-14 * (1.0 + loads.gas.norm() * 0.1)), // measured worst 2.1e-16 (be05608); 100×
            "inverse problem at {q}: {t} vs {driver}"
        );
    }
}
