//! The hand-written floor (`benches/floor/hand.rs` and the `hand_*.rs` beside it) computes
//! the same numbers as the generated solvers: every quantity of every operation timed in
//! `benches/floor.rs` (the four-bar, the slider-crank, the quick-return, the Scotch yoke, and
//! the inverted slider-crank, the geared slider-crank, the roller cam, the crank, rod and
//! wheel, the Scotch yoke with a block, the slotted crank and ram, the planetary reducer and
//! the rack and pinion of `benches/floor/machines.rs`), on a sweep of 72 input angles over
//! a full turn (three turns of the geared slider-crank's pinion: one of its crank; five of
//! the planetary's sun: more than one of its arm; the slotted crank and ram, which cannot
//! turn, over its swing `RAM_SWING`), to 1e-13 relative (`TOL`:
//! at most 100× the worst error measured over the quantities; the new machines' worst, the
//! quick-return's α, 1.4e-14), the roller cam to 1e-12 (`CAM_TOL`: its law's argument, an
//! ulp apart on the two sides, amplified in the middle of the fall).
//!
//! "Relative" is scaled by the largest entry of the quantity: for a quantity made of
//! several entries (the three link angles, the cg positions of the three links, the pin
//! forces of the four joints, ...) the largest |entry| at that q; for a single scalar
//! (driver torque, a prismatic joint's moment, I*, dI*/dq, M*, q̈), which can cross zero
//! inside the turn, the largest |value| over the sweep. Angles are compared modulo 2π (the
//! generated angles are wrapped to (−π, π], the hand-written crank angle is q itself).
//!
//! Independent checks of the hand-written side (so that a shared mistake cannot pass):
//! central finite differences of positions against velocities and of velocities against
//! accelerations, of I* against dI*/dq, and the inverse problem (the generated d'Alembert
//! driver at the hand-written q̈ gives back the applied torque). For the quick-return, the
//! Scotch yoke, the inverted slider-crank, the geared slider-crank, the roller cam, the
//! crank, rod and wheel, the Scotch yoke with a block, the slotted crank and ram, the
//! planetary and the rack and pinion, on the hand-written side alone: finite
//! differences of every point, cg and link angle (velocities, accelerations, q̈ entering
//! linearly), every link's d'Alembert balance with the hand-written reactions, the driver
//! torque by d'Alembert, by virtual power and by Zhukovski, dI*/dq against I*, M* against
//! the power of gravity and the loads on the positions, and the inverse problem; for the
//! geared slider-crank, the planetary and the rack and pinion also the meshes' data against
//! the model, Willis' relations (no slip at the pitch points) and the tooth forces on their
//! lines of action, for the roller cam the law's data against the model and the contact
//! normal against the pitch curve.

use crate::measure::{within, within_at};
use crate::mechanisms;

#[path = "../benches/floor/machines.rs"]
pub(crate) mod machines;

#[path = "../benches/floor/hand.rs"]
mod hand;

use hand::*;
use machines::*;
use mech::prelude::*;
use mechanisms::*;
use std::collections::BTreeMap;
use std::f64::consts::{PI, TAU};

// measured worst 1.9e-15 over the quantities (be05608); 100×
const TOL: f64 = 1e-13;
// The roller cam's: measured worst 5.0e-14, its follower's acceleration in the middle of
// the cycloidal fall. The two sides take the cam's turn into [0, 2π) by different routes
// (the generated from the rotation: atan2, then + 2π; the hand q − 2π), an ulp of 2π
// apart, and there s″ = (2πL/β²) sin 2πx, with sin 2πx near zero, turns that ulp into
// a few 1e-13 of s″. Every other quantity of the cam within TOL; 20×
const CAM_TOL: f64 = 1e-12;
const STEPS: usize = 72;
const QD: f64 = 12.0;
const QDD: f64 = -3.0;

fn sweep() -> impl Iterator<Item = f64> {
    sweep_turns(1)
}

/// `turns` full turns of q from 0.7, STEPS samples per turn (a geared input turns more
/// than once while its crank turns once).
fn sweep_turns(turns: usize) -> impl Iterator<Item = f64> {
    (0..STEPS * turns).map(|k| 0.7 + TAU * k as f64 / STEPS as f64)
}

/// The slotted crank and ram's working range (rad): its crank swings, it cannot turn (the
/// ram runs to infinity where the slot is parallel to the guide, q = −0.15 and 2.99 rad).
pub(crate) const RAM_SWING: (f64, f64) = (0.45, 2.4);

/// STEPS samples of q from `RAM_SWING.0` to `RAM_SWING.1`, both ends included.
fn sweep_swing() -> impl Iterator<Item = f64> {
    let (lo, hi) = RAM_SWING;
    (0..STEPS).map(move |k| lo + (hi - lo) * k as f64 / (STEPS - 1) as f64)
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
    /// [`Report::scalars`] measured against at least `scale`: for a quantity balanced from
    /// larger forces (a tooth load from the pins' forces), whose roundoff follows theirs.
    fn scalars_against(&mut self, name: &'static str, q: f64, pairs: &[(f64, f64)], scale: f64) {
        self.record(name, q, false, pairs, false);
        if let Some(row) = self.0.get_mut(name).and_then(|s| s.rows.last_mut()) {
            row.2 = row.2.max(scale);
        }
    }
    fn scalar(&mut self, name: &'static str, q: f64, g: f64, h: f64) {
        self.record(name, q, true, &[(g, h)], false);
    }
    /// Print the worst relative error of each quantity and fail on any above `TOL`.
    fn check(&self, expected: &[&str]) {
        self.check_to(expected, TOL)
    }
    /// [`Report::check`] to `tol`.
    fn check_to(&self, expected: &[&str], tol: f64) {
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
                if !within_at(name, rel, tol) {
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

        // Zhukovski (the hand code's own closed form for the batched benchmarks)
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
            "acceleration: q̈ (gravity, loads, driver)",
            q,
            m.acceleration(q, QD, 5.0, &loads).unwrap(),
            h.acceleration(q, QD, 5.0, &loads).unwrap(),
        );
    }
    r.check(&[
        "reduced: I*",
        "reduced: dI*/dq",
        "acceleration: q̈ (gravity, loads, driver)",
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

// ---------------------------------------------------------------------------------------
// The quick-return, the Scotch yoke and the inverted slider-crank: all six operations.
// ---------------------------------------------------------------------------------------

const DRIVER: f64 = 5.0;

fn quick_return_loads() -> QuickReturnLoads {
    let mut l = QuickReturnLoads::default();
    assert!(l.set_by_name("cut", &[-250.0, 30.0]));
    assert!(l.set_by_name("friction", &[-1.5]));
    l
}

fn scotch_yoke_loads() -> ScotchYokeLoads {
    let mut l = ScotchYokeLoads::default();
    assert!(l.set_by_name("resist", &[-120.0, 15.0]));
    assert!(l.set_by_name("drag", &[-1.5]));
    l
}

fn inverted_slider_crank_loads() -> InvertedSliderCrankLoads {
    let mut l = InvertedSliderCrankLoads::default();
    assert!(l.set_by_name("push", &[-300.0, 40.0]));
    assert!(l.set_by_name("resist", &[2.5]));
    l
}

fn geared_slider_crank_loads() -> GearedSliderCrankLoads {
    let mut l = GearedSliderCrankLoads::default();
    assert!(l.set_by_name("gas", &[-900.0, -90.0]));
    assert!(l.set_by_name("shaft", &[-4.0]));
    l
}

fn roller_cam_loads() -> RollerCamLoads {
    let mut l = RollerCamLoads::default();
    assert!(l.set_by_name("push", &[20.0, -250.0]));
    assert!(l.set_by_name("drag", &[-1.5]));
    l
}

fn crank_rod_wheel_loads() -> CrankRodWheelLoads {
    let mut l = CrankRodWheelLoads::default();
    assert!(l.set_by_name("pull", &[-150.0, 20.0]));
    assert!(l.set_by_name("brake", &[-0.8]));
    l
}

fn block_scotch_yoke_loads() -> BlockScotchYokeLoads {
    let mut l = BlockScotchYokeLoads::default();
    assert!(l.set_by_name("resist", &[-150.0, 20.0]));
    assert!(l.set_by_name("friction", &[-0.6]));
    l
}

fn planetary_loads() -> PlanetaryLoads {
    let mut l = PlanetaryLoads::default();
    assert!(l.set_by_name("pull", &[40.0, -60.0]));
    assert!(l.set_by_name("brake", &[-2.0]));
    l
}

fn rack_pinion_loads() -> RackPinionLoads {
    let mut l = RackPinionLoads::default();
    assert!(l.set_by_name("push", &[-250.0, 30.0]));
    assert!(l.set_by_name("resist", &[-2.0]));
    l
}

/// The rack and pinion's loads with the push on the rack reversed: the tooth force's
/// tangential part changes sign, the other flank in contact.
fn rack_pinion_loads_reversed() -> RackPinionLoads {
    let mut l = rack_pinion_loads();
    l.push = -l.push;
    l
}

fn slotted_crank_ram_loads() -> SlottedCrankRamLoads {
    let mut l = SlottedCrankRamLoads::default();
    assert!(l.set_by_name("push", &[-400.0, 60.0]));
    assert!(l.set_by_name("resist", &[1.8]));
    l
}

/// The quantities every machine of the six operations records (`record_six`), and the
/// names of its own (joint forces, prismatic moment) to add.
fn six_expected(extra: &[&'static str]) -> Vec<&'static str> {
    let mut v = vec![
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
        "driver: generated d'Alembert vs hand d'Alembert",
        "driver: generated virtual power vs hand virtual power",
        "driver: generated d'Alembert vs hand virtual power",
        "driver: generated virtual power vs hand d'Alembert",
        "reduced: I*",
        "reduced: dI*/dq",
        "reduced_moment: M*",
        "acceleration: q̈ (gravity, loads, driver)",
        "acceleration: q̈ (gravity only, no driver)",
    ];
    v.extend_from_slice(extra);
    v
}

/// Record one machine's pose and kinematics: (generated, hand) link poses, point
/// positions, link motions and point motions, matched by name in the caller.
fn record_motion(
    r: &mut Report,
    q: f64,
    pose_links: &[(LinkPose, HandLinkPose)],
    pose_points: &[(Vector2<f64>, Vector2<f64>)],
    links: &[(LinkMotion, HandLinkMotion)],
    points: &[(PointMotion, HandPointMotion)],
) {
    let angles: Vec<_> = pose_links.iter().map(|(g, h)| (g.angle, h.angle)).collect();
    r.angles("pose: link angle", q, &angles);
    let cgs: Vec<_> = pose_links.iter().map(|(g, h)| (g.cg, h.cg)).collect();
    r.vecs("pose: link cg", q, &cgs);
    r.vecs("pose: point pos", q, pose_points);
    let s = |f: fn(&LinkMotion, &HandLinkMotion) -> (f64, f64)| {
        links.iter().map(|(g, h)| f(g, h)).collect::<Vec<_>>()
    };
    r.angles("kinematics: link angle", q, &s(|g, h| (g.angle, h.angle)));
    r.scalars("kinematics: link omega", q, &s(|g, h| (g.omega, h.omega)));
    r.scalars("kinematics: link alpha", q, &s(|g, h| (g.alpha, h.alpha)));
    type V = Vector2<f64>;
    let v = |f: fn(&LinkMotion, &HandLinkMotion) -> (V, V)| {
        links.iter().map(|(g, h)| f(g, h)).collect::<Vec<_>>()
    };
    r.vecs("kinematics: link cg", q, &v(|g, h| (g.cg, h.cg)));
    r.vecs(
        "kinematics: link cg_vel",
        q,
        &v(|g, h| (g.cg_vel, h.cg_vel)),
    );
    r.vecs(
        "kinematics: link cg_acc",
        q,
        &v(|g, h| (g.cg_acc, h.cg_acc)),
    );
    let p = |f: fn(&PointMotion, &HandPointMotion) -> (V, V)| {
        points.iter().map(|(g, h)| f(g, h)).collect::<Vec<_>>()
    };
    r.vecs("kinematics: point pos", q, &p(|g, h| (g.pos, h.pos)));
    r.vecs("kinematics: point vel", q, &p(|g, h| (g.vel, h.vel)));
    r.vecs("kinematics: point acc", q, &p(|g, h| (g.acc, h.acc)));
}

/// Record the drivers by both routes on both sides, crossed.
fn record_drivers(r: &mut Report, q: f64, gen: (f64, f64), hand: (f64, f64)) {
    let ((gf, gd), (hf, hd)) = (gen, hand);
    r.scalar("driver: generated d'Alembert vs hand d'Alembert", q, gf, hf);
    r.scalar(
        "driver: generated virtual power vs hand virtual power",
        q,
        gd,
        hd,
    );
    r.scalar(
        "driver: generated d'Alembert vs hand virtual power",
        q,
        gf,
        hd,
    );
    r.scalar(
        "driver: generated virtual power vs hand d'Alembert",
        q,
        gd,
        hf,
    );
}

/// Record Zhukovski's I*, dI*/dq, M* and the direct problem's q̈ (with the loads and the
/// driver, and with gravity alone).
fn record_reduced(
    r: &mut Report,
    q: f64,
    gen: (Reduced, f64, f64, f64),
    hand: (HandReduced, f64, f64, f64),
) {
    r.scalar("reduced: I*", q, gen.0.inertia, hand.0.inertia);
    r.scalar(
        "reduced: dI*/dq",
        q,
        gen.0.inertia_derivative,
        hand.0.inertia_derivative,
    );
    r.scalar("reduced_moment: M*", q, gen.1, hand.1);
    r.scalar("acceleration: q̈ (gravity, loads, driver)", q, gen.2, hand.2);
    r.scalar(
        "acceleration: q̈ (gravity only, no driver)",
        q,
        gen.3,
        hand.3,
    );
}

/// One machine's `*_hand_matches_generated` test: the generated `$machine` against its
/// hand-written `$hand` at every q of `sweep`, with the loads `$loads` (and with none):
/// pose and kinematics of `links` and `points` (generated name, hand-written name), the
/// forces of `joints`, the drivers and the reduced quantities (`record_motion`,
/// `record_drivers`, `record_reduced`). `setup` binds what `each` and `finish` share;
/// `each` records the machine's own quantities at every q, between the joint forces and the
/// drivers, with the report, q, the generated joints and the hand-written forces named as
/// its closure's arguments; `finish` checks the report.
macro_rules! hand_matches_generated {
    (
        $(#[$attr:meta])*
        fn $name:ident {
            machine: $machine:ident, $hand:ident, $loads_ty:ident = $loads:expr;
            sweep: $sweep:expr;
            links: $($link:ident),+;
            points: $($gpt:ident $hpt:ident),+;
            joints: $($gj:ident $hj:ident),+;
            setup: $(let $pat:pat = $init:expr;)*
            each |$r:ident, $q:ident, $j:ident, $hf:ident| $each:block
            finish $finish:block
        }
    ) => {
        $(#[$attr])*
        #[test]
        fn $name() {
            let m = $machine::new();
            let h = $hand::new(m.params());
            let loads = $loads;
            let none = $loads_ty::default();
            let mut $r = Report::default();
            $(let $pat = $init;)*
            for $q in $sweep {
                let (gp, hp) = (m.pose($q).unwrap(), h.pose($q).unwrap());
                let (gm, hm) = (
                    m.kinematics($q, QD, QDD).unwrap(),
                    h.kinematics($q, QD, QDD).unwrap(),
                );
                let (gl, gpt, l, pt) = (&gp.links, &gp.points, &gm.links, &gm.points);
                record_motion(
                    &mut $r,
                    $q,
                    &[$((gl.$link, hp.$link)),+],
                    &[$((gpt.$gpt.pos, hp.$hpt)),+],
                    &[$((l.$link, hm.$link)),+],
                    &[$((pt.$gpt, hm.$hpt)),+],
                );
                let gf = m.kinetostatics(&gm, &loads).unwrap();
                let $hf = h.kinetostatics(&hm, &loads);
                let $j = &gf.joints;
                $r.vecs(
                    "kinetostatics: joint force",
                    $q,
                    &[$(($j.$gj.force, $hf.$hj)),+],
                );
                $each
                record_drivers(
                    &mut $r,
                    $q,
                    (gf.driver, m.driver_action(&gm, &loads).unwrap()),
                    ($hf.driver, h.driver_action(&hm, &loads)),
                );
                record_reduced(
                    &mut $r,
                    $q,
                    (
                        m.reduced($q).unwrap(),
                        m.reduced_moment($q, &loads).unwrap(),
                        m.acceleration($q, QD, DRIVER, &loads).unwrap(),
                        m.acceleration($q, QD, 0.0, &none).unwrap(),
                    ),
                    (
                        h.reduced($q).unwrap(),
                        h.reduced_moment($q, &loads).unwrap(),
                        h.acceleration($q, QD, DRIVER, &loads).unwrap(),
                        h.acceleration($q, QD, 0.0, &none).unwrap(),
                    ),
                );
            }
            $finish
        }
    };
}

hand_matches_generated! {
    fn quick_return_hand_matches_generated {
        machine: QuickReturn, QuickReturnHand, QuickReturnLoads = quick_return_loads();
        sweep: sweep();
        links: crank, block, lever;
        points: O2 o2, O4 o4, A a, C c;
        joints: O2 o2, A a, slot slot, O4 o4;
        setup:
        each |r, q, j, hf| {
            r.scalar("kinetostatics: slot moment", q, j.slot.moment, hf.slot_moment);
        }
        finish {
            r.check(&six_expected(&["kinetostatics: slot moment"]));
        }
    }
}

hand_matches_generated! {
    fn scotch_yoke_hand_matches_generated {
        machine: ScotchYoke, ScotchYokeHand, ScotchYokeLoads = scotch_yoke_loads();
        sweep: sweep();
        links: crank, yoke;
        points: O2 o2, A a, Y y;
        joints: O2 o2, guide guide, slot slot;
        setup:
        each |r, q, j, hf| {
            r.scalar("kinetostatics: guide moment", q, j.guide.moment, hf.guide_moment);
        }
        finish {
            r.check(&six_expected(&["kinetostatics: guide moment"]));
        }
    }
}

hand_matches_generated! {
    fn inverted_slider_crank_hand_matches_generated {
        machine: InvertedSliderCrank, InvertedSliderCrankHand, InvertedSliderCrankLoads =
            inverted_slider_crank_loads();
        sweep: sweep();
        links: crank, rod, block;
        points: O2 o2, O4 o4, A a, P p;
        joints: O2 o2, A a, slide slide, O4 o4;
        setup:
        each |r, q, j, hf| {
            r.scalar("kinetostatics: slide moment", q, j.slide.moment, hf.slide_moment);
        }
        finish {
            r.check(&six_expected(&["kinetostatics: slide moment"]));
        }
    }
}

hand_matches_generated! {
    /// The geared slider-crank over three turns of the pinion (one of the crank): every
    /// quantity as the other machines, the mesh's tooth force, tooth load and flank besides.
    fn geared_slider_crank_hand_matches_generated {
        machine: GearedSliderCrank, GearedSliderCrankHand, GearedSliderCrankLoads =
            geared_slider_crank_loads();
        sweep: sweep_turns(3);
        links: pinion, crank, rod, piston;
        points: O1 o1, O2 o2, A a, B b;
        joints: O1 o1, O2 o2, A a, B b, guide guide, mesh mesh;
        setup: let mut flanks = [0usize; 2];
        each |r, q, j, hf| {
            r.scalar("kinetostatics: guide moment", q, j.guide.moment, hf.guide_moment);
            r.scalar("kinetostatics: tooth load", q, j.mesh.tooth_load, hf.tooth_load);
            assert_eq!(j.mesh.flank, hf.flank, "flank at q = {q}");
            flanks[(hf.flank > 0.0) as usize] += 1;
        }
        finish {
            // Both flanks are in contact during the turn (the comparison covers the sign of
            // the tooth force's radial part).
            assert!(flanks[0] > 0 && flanks[1] > 0, "flanks {flanks:?}");
            r.check(&six_expected(&[
                "kinetostatics: guide moment",
                "kinetostatics: tooth load",
            ]));
        }
    }
}

hand_matches_generated! {
    /// The roller cam over a turn of the cam: every quantity as the other machines, the
    /// contact force's signed magnitude besides.
    fn roller_cam_hand_matches_generated {
        machine: RollerCam, RollerCamHand, RollerCamLoads = roller_cam_loads();
        sweep: sweep();
        links: cam, follower;
        points: O o, P p, T t;
        joints: O o, slide slide, lobe lobe;
        setup:
        each |r, q, j, hf| {
            r.scalar("kinetostatics: slide moment", q, j.slide.moment, hf.slide_moment);
            r.scalar("kinetostatics: normal force", q, j.lobe.normal_force, hf.normal_force);
        }
        finish {
            r.check_to(
                &six_expected(&["kinetostatics: slide moment", "kinetostatics: normal force"]),
                CAM_TOL,
            );
        }
    }
}

hand_matches_generated! {
    /// The crank, rod and rolling wheel over a turn: every quantity as the other machines,
    /// the contact force's normal and friction parts besides.
    fn crank_rod_wheel_hand_matches_generated {
        machine: CrankRodWheel, CrankRodWheelHand, CrankRodWheelLoads = crank_rod_wheel_loads();
        sweep: sweep();
        links: crank, rod, wheel;
        points: O2 o2, A a, C c;
        joints: O2 o2, A a, C c, roll roll;
        setup:
        each |r, q, j, hf| {
            r.scalars(
                "kinetostatics: contact normal and friction",
                q,
                &[(j.roll.normal, hf.normal), (j.roll.friction, hf.friction)],
            );
        }
        finish {
            r.check(&six_expected(&["kinetostatics: contact normal and friction"]));
        }
    }
}

hand_matches_generated! {
    /// The Scotch yoke with a block over a turn: every quantity as the other machines, the
    /// slot's and the guide's moments besides.
    fn block_scotch_yoke_hand_matches_generated {
        machine: BlockScotchYoke, BlockScotchYokeHand, BlockScotchYokeLoads =
            block_scotch_yoke_loads();
        sweep: sweep();
        links: crank, block, yoke;
        points: O2 o2, A a, Y y, T t;
        joints: O2 o2, A a, slot slot, guide guide;
        setup:
        each |r, q, j, hf| {
            r.scalar("kinetostatics: slot moment", q, j.slot.moment, hf.slot_moment);
            r.scalar("kinetostatics: guide moment", q, j.guide.moment, hf.guide_moment);
        }
        finish {
            r.check(&six_expected(&[
                "kinetostatics: slot moment",
                "kinetostatics: guide moment",
            ]));
        }
    }
}

hand_matches_generated! {
    /// The slotted crank and ram over its working swing (`RAM_SWING`: it cannot turn):
    /// every quantity as the other machines, the slot's and the guide's moments besides.
    fn slotted_crank_ram_hand_matches_generated {
        machine: SlottedCrankRam, SlottedCrankRamHand, SlottedCrankRamLoads =
            slotted_crank_ram_loads();
        sweep: sweep_swing();
        links: crank, block, ram;
        points: O2 o2, E e, B b, P p;
        joints: O2 o2, slot slot, B b, guide guide;
        setup:
        each |r, q, j, hf| {
            r.scalar("kinetostatics: slot moment", q, j.slot.moment, hf.slot_moment);
            r.scalar("kinetostatics: guide moment", q, j.guide.moment, hf.guide_moment);
        }
        finish {
            r.check(&six_expected(&[
                "kinetostatics: slot moment",
                "kinetostatics: guide moment",
            ]));
        }
    }
}

hand_matches_generated! {
    /// The planetary reducer over five turns of the sun (more than one of the arm): every
    /// quantity as the other machines, both meshes' tooth loads and flanks besides.
    fn planetary_hand_matches_generated {
        machine: Planetary, PlanetaryHand, PlanetaryLoads = planetary_loads();
        sweep: sweep_turns(5);
        links: sun, arm, planet;
        points: O o, P p, T t;
        joints: S s, O o, P p, sp sp, pr pr;
        setup: let mut flanks = [[0usize; 2]; 2];
        each |r, q, j, hf| {
            // The tooth loads (a few tenths of a newton) are balanced from the pins'
            // forces (newtons), whose roundoff they carry: measured against the largest.
            let pins = j.O.force.norm().max(j.P.force.norm()).max(j.S.force.norm());
            r.scalars_against(
                "kinetostatics: tooth loads",
                q,
                &[(j.sp.tooth_load, hf.sp_load), (j.pr.tooth_load, hf.pr_load)],
                pins,
            );
            assert_eq!((j.sp.flank, j.pr.flank), (hf.sp_flank, hf.pr_flank), "flanks at q = {q}");
            flanks[0][(hf.sp_flank > 0.0) as usize] += 1;
            flanks[1][(hf.pr_flank > 0.0) as usize] += 1;
        }
        finish {
            // Both flanks of both meshes are in contact during the sweep (the comparison
            // covers the sign of each tooth force's radial part).
            assert!(flanks.iter().flatten().all(|&n| n > 0), "flanks {flanks:?}");
            r.check(&six_expected(&["kinetostatics: tooth loads"]));
        }
    }
}

hand_matches_generated! {
    /// The rack and pinion over a turn of the pinion: every quantity as the other machines,
    /// the guide's moment (about R where it is now), the tooth load and the flank besides.
    /// The rack only translates, so at a fixed q̈ the tooth force's tangential part
    /// f_t = −(W + F_push)·u does not depend on q: one flank is in contact over the whole
    /// sweep. The kinetostatics are therefore compared again with the push reversed, where
    /// the other flank carries the load (the comparison then covers both signs of the tooth
    /// force's tangential part).
    fn rack_pinion_hand_matches_generated {
        machine: RackPinion, RackPinionHand, RackPinionLoads = rack_pinion_loads();
        sweep: sweep();
        links: pinion, rack;
        points: O o, R r, L l;
        joints: O o, guide guide, mesh mesh;
        setup:
            let gen = RackPinion::new();
            let hand = RackPinionHand::new(gen.params());
            let reversed = rack_pinion_loads_reversed();
            let mut flanks = [0usize; 2];
        each |r, q, j, hf| {
            r.scalar("kinetostatics: guide moment", q, j.guide.moment, hf.guide_moment);
            r.scalar("kinetostatics: tooth load", q, j.mesh.tooth_load, hf.tooth_load);
            assert_eq!(j.mesh.flank, hf.flank, "flank at q = {q}");
            flanks[(hf.flank > 0.0) as usize] += 1;
            let (gk, hk) = (
                gen.kinematics(q, QD, QDD).unwrap(),
                hand.kinematics(q, QD, QDD).unwrap(),
            );
            let (gb, hb) = (
                gen.kinetostatics(&gk, &reversed).unwrap(),
                hand.kinetostatics(&hk, &reversed),
            );
            let jb = &gb.joints;
            r.vecs(
                "kinetostatics (push reversed): joint force",
                q,
                &[(jb.O.force, hb.o), (jb.guide.force, hb.guide), (jb.mesh.force, hb.mesh)],
            );
            r.scalar(
                "kinetostatics (push reversed): guide moment",
                q,
                jb.guide.moment,
                hb.guide_moment,
            );
            r.scalar(
                "kinetostatics (push reversed): tooth load",
                q,
                jb.mesh.tooth_load,
                hb.tooth_load,
            );
            r.scalar("kinetostatics (push reversed): driver", q, gb.driver, hb.driver);
            assert_eq!(jb.mesh.flank, hb.flank, "flank (push reversed) at q = {q}");
            flanks[(hb.flank > 0.0) as usize] += 1;
        }
        finish {
            // Both flanks compared: one under the floor's push, the other reversed.
            assert!(flanks[0] > 0 && flanks[1] > 0, "flanks {flanks:?}");
            r.check(&six_expected(&[
                "kinetostatics: guide moment",
                "kinetostatics: tooth load",
                "kinetostatics (push reversed): joint force",
                "kinetostatics (push reversed): guide moment",
                "kinetostatics (push reversed): tooth load",
                "kinetostatics (push reversed): driver",
            ]));
        }
    }
}

/// (name, value, its rate, its second rate): a point's position, velocity and acceleration,
/// or a link's angle, ω and α.
type Track<T> = (&'static str, T, T, T);

/// What the finite-difference check follows of one hand-written motion: every moving
/// point and cg, every link.
#[derive(Default)]
struct Tracked {
    points: Vec<Track<Vector2<f64>>>,
    links: Vec<Track<f64>>,
}

impl Tracked {
    fn point(&mut self, name: &'static str, p: &HandPointMotion) {
        self.points.push((name, p.pos, p.vel, p.acc));
    }
    fn link(&mut self, name: &'static str, l: &HandLinkMotion) {
        self.links.push((name, l.angle, l.omega, l.alpha));
        self.points.push((name, l.cg, l.cg_vel, l.cg_acc));
    }
}

/// A hand-written `kinematics(q, q̇, q̈)` against itself by central differences at every q
/// of the sweep: d(position)/dq = the velocity at q̇ = 1, q̈ = 0, and d(that velocity)/dq =
/// the acceleration at q̇ = 1, q̈ = 0, for every point and cg; the same for the link
/// angles (differenced modulo 2π), ω and α; and q̈ enters linearly (the acceleration at
/// q̇ = 0, q̈ = 1 is the velocity at q̇ = 1, α there is ω).
fn check_by_finite_differences(
    machine: &str,
    turns: usize,
    motion: impl Fn(f64, f64, f64) -> Tracked,
) {
    check_by_finite_differences_over(machine, sweep_turns(turns), motion)
}

/// [`check_by_finite_differences`] at the angles `qs` (a machine that cannot turn: its
/// working range).
fn check_by_finite_differences_over(
    machine: &str,
    qs: impl Iterator<Item = f64>,
    motion: impl Fn(f64, f64, f64) -> Tracked,
) {
    let h = 1e-5;
    for q in qs {
        let (k, lin) = (motion(q, 1.0, 0.0), motion(q, 0.0, 1.0));
        let (plus, minus) = (motion(q + h, 1.0, 0.0), motion(q - h, 1.0, 0.0));
        for (i, &(name, _, v, a)) in k.points.iter().enumerate() {
            let fv = (plus.points[i].1 - minus.points[i].1) / (2.0 * h);
            let fa = (plus.points[i].2 - minus.points[i].2) / (2.0 * h);
            assert!(
                (fv - v).norm() < 1e-8 * v.norm().max(0.1),
                "{machine}: {name} velocity at {q}: fd {fv:?} vs {v:?}"
            );
            assert!(
                (fa - a).norm() < 1e-7 * a.norm().max(0.1),
                "{machine}: {name} acceleration at {q}: fd {fa:?} vs {a:?}"
            );
            let acc_at_unit_qdd = lin.points[i].3;
            assert!(
                (acc_at_unit_qdd - v).norm() <= 1e-12 * v.norm().max(0.1),
                "{machine}: {name} at q̈ = 1: {acc_at_unit_qdd:?} vs {v:?}"
            );
        }
        for (i, &(name, _, w, al)) in k.links.iter().enumerate() {
            let fw = wrap(plus.links[i].1 - minus.links[i].1) / (2.0 * h);
            let fal = (plus.links[i].2 - minus.links[i].2) / (2.0 * h);
            assert!(
                (fw - w).abs() < 1e-8 * w.abs().max(0.1),
                "{machine}: {name} ω at {q}: fd {fw} vs {w}"
            );
            assert!(
                (fal - al).abs() < 1e-7 * al.abs().max(0.1),
                "{machine}: {name} α at {q}: fd {fal} vs {al}"
            );
            assert!(
                (lin.links[i].3 - w).abs() <= 1e-12 * w.abs().max(0.1),
                "{machine}: {name} α at q̈ = 1: {} vs {w}",
                lin.links[i].3
            );
        }
    }
}

/// One q of a hand-written machine's dynamics, against itself: the driver torque by
/// d'Alembert (`kinetostatics`), by virtual power (`driver_action`) and by Zhukovski
/// (I* q̈ + ½ dI*/dq q̇² − M*) at (q, q̇, q̈) = (q, 12, −3); dI*/dq by a central difference
/// of I*; M* by the power of gravity and the loads on a central difference of the
/// positions (`moment_by_positions`); and the inverse problem: d'Alembert at the q̈ of
/// `acceleration` gives back its driver.
struct Dynamics {
    /// Driver by d'Alembert, by virtual power, at (q, q̇, q̈).
    dalembert: f64,
    virtual_power: f64,
    /// I*, dI*/dq, M* at q; I* at q ± h.
    reduced: HandReduced,
    reduced_moment: f64,
    inertia_plus: f64,
    inertia_minus: f64,
    /// M* from the positions at q ± h.
    moment_by_positions: f64,
    /// d'Alembert's driver at (q, q̇, acceleration(q, q̇, DRIVER)).
    inverse: f64,
}

const FD_STEP: f64 = 1e-5;

fn check_dynamics(machine: &str, turns: usize, at: impl Fn(f64) -> Dynamics) {
    check_dynamics_over(machine, sweep_turns(turns), at)
}

/// [`check_dynamics`] at the angles `qs` (a machine that cannot turn: its working range).
fn check_dynamics_over(machine: &str, qs: impl Iterator<Item = f64>, at: impl Fn(f64) -> Dynamics) {
    for q in qs {
        let d = at(q);
        let r = d.reduced;
        let zhukovski = r.inertia * QDD + 0.5 * r.inertia_derivative * QD * QD - d.reduced_moment;
        let scale = (r.inertia * QDD)
            .abs()
            .max((0.5 * r.inertia_derivative * QD * QD).abs())
            .max(d.reduced_moment.abs())
            .max(d.dalembert.abs());
        for (what, a, b) in [
            ("d'Alembert vs virtual power", d.dalembert, d.virtual_power),
            ("d'Alembert vs Zhukovski", d.dalembert, zhukovski),
            ("virtual power vs Zhukovski", d.virtual_power, zhukovski),
        ] {
            assert!(
                (a - b).abs() <= 1e-12 * scale,
                "{machine} at {q}: driver {what}: {a} vs {b} (scale {scale})"
            );
        }
        let fd = (d.inertia_plus - d.inertia_minus) / (2.0 * FD_STEP);
        assert!(
            (fd - r.inertia_derivative).abs() < 1e-8 * r.inertia,
            "{machine}: dI*/dq at {q}: fd {fd} vs {}",
            r.inertia_derivative
        );
        assert!(
            (d.moment_by_positions - d.reduced_moment).abs()
                < 1e-8 * d.reduced_moment.abs().max(1.0),
            "{machine}: M* at {q}: by positions {} vs {}",
            d.moment_by_positions,
            d.reduced_moment
        );
        assert!(
            (d.inverse - DRIVER).abs() < 1e-12 * scale.max(DRIVER),
            "{machine}: inverse problem at {q}: {} vs {DRIVER}",
            d.inverse
        );
    }
}

/// One link's free body with the hand-written reactions and driver, balanced by
/// d'Alembert about the global origin: Σ F + m g − m a_G = 0 and
/// Σ x × F + Σ M + G × (m g − m a_G) − I α = 0, each to 1e-12 of the sum of the
/// magnitudes of its terms. `forces` are (point of application, force), `moments` the
/// pure moments (torques, a prismatic joint's moment) on the link.
fn check_balance(
    what: &str,
    q: f64,
    (mass, inertia, gravity): (f64, f64, Vector2<f64>),
    l: &HandLinkMotion,
    forces: &[(Vector2<f64>, Vector2<f64>)],
    moments: &[f64],
) {
    let cross = |a: Vector2<f64>, b: Vector2<f64>| a.x * b.y - a.y * b.x;
    let own = (gravity - l.cg_acc) * mass;
    let mut f = own;
    let mut f_scale = own.norm();
    let mut m = cross(l.cg, own) - inertia * l.alpha;
    let mut m_scale = cross(l.cg, own).abs() + (inertia * l.alpha).abs();
    for &(x, force) in forces {
        f += force;
        f_scale += force.norm();
        m += cross(x, force);
        m_scale += cross(x, force).abs();
    }
    for &t in moments {
        m += t;
        m_scale += t.abs();
    }
    assert!(
        f.norm() <= 1e-12 * f_scale,
        "{what} at {q}: forces do not balance, {f:?} (scale {f_scale})"
    );
    assert!(
        m.abs() <= 1e-12 * m_scale,
        "{what} at {q}: moments do not balance, {m} (scale {m_scale})"
    );
}

/// The joint `joint` of the floor's machine `machine` as the run-time `Mechanism` loads it
/// from `benches/floor/machines.rs`: what its declaration says.
fn declared_joint(machine: &str, joint: &str) -> mech::model::Joint {
    let rt =
        mech::Mechanism::from_rust_source(include_str!("../benches/floor/machines.rs"), machine)
            .unwrap();
    rt.model()
        .joints
        .iter()
        .find(|j| j.name == joint)
        .unwrap()
        .clone()
}

/// Each link's balance ([`check_balance`]) at `$q`, named "`$machine` `$name`": the link
/// `$link` of the hand-written parameters `$l` and motion `$k`, under gravity `$g`, with
/// its forces (point of application, force) and pure moments.
macro_rules! check_balances {
    (
        $machine:literal, $q:ident, ($l:ident, $g:ident, $k:ident);
        $($name:literal $link:ident: [$($force:expr),*], [$($moment:expr),*];)+
    ) => {
        let body = |l: &mech::LinkParams| (l.mass, l.inertia, $g);
        $(
            check_balance(
                concat!($machine, " ", $name),
                $q,
                body(&$l.$link),
                &$k.$link,
                &[$($force),*],
                &[$($moment),*],
            );
        )+
    };
}

/// dX/dq by a central difference of `f` (step `FD_STEP`).
fn d_dq(f: impl Fn(f64) -> Vector2<f64>, q: f64) -> Vector2<f64> {
    (f(q + FD_STEP) - f(q - FD_STEP)) / (2.0 * FD_STEP)
}

/// The closure `|q, q̇, q̈| Tracked` of [`check_by_finite_differences`] for the hand-written
/// machine `$h`: its points (name, field of its kinematics) and links (field).
macro_rules! tracked {
    ($h:ident; points: $($name:ident $point:ident),+; links: $($link:ident),+) => {
        |q, qd, qdd| {
            let k = $h.kinematics(q, qd, qdd).unwrap();
            let mut t = Tracked::default();
            $(t.point(stringify!($name), &k.$point);)+
            $(t.link(stringify!($link), &k.$link);)+
            t
        }
    };
}

/// The closure `|q| Dynamics` of [`check_dynamics`] for the hand-written machine `$h` under
/// `$loads`: M* by the positions is `$moment`, with q and the hand-written pose at an angle
/// (`|q| h.pose(q).unwrap()`) named as its closure's arguments.
macro_rules! hand_dynamics {
    ($h:ident, $loads:ident, |$q:ident, $pose:ident| $moment:expr) => {
        |$q| {
            let k = $h.kinematics($q, QD, QDD).unwrap();
            let $pose = |q| $h.pose(q).unwrap();
            let qdd = $h.acceleration($q, QD, DRIVER, &$loads).unwrap();
            Dynamics {
                dalembert: $h.kinetostatics(&k, &$loads).driver,
                virtual_power: $h.driver_action(&k, &$loads),
                reduced: $h.reduced($q).unwrap(),
                reduced_moment: $h.reduced_moment($q, &$loads).unwrap(),
                inertia_plus: $h.reduced($q + FD_STEP).unwrap().inertia,
                inertia_minus: $h.reduced($q - FD_STEP).unwrap().inertia,
                moment_by_positions: $moment,
                inverse: $h
                    .kinetostatics(&$h.kinematics($q, QD, qdd).unwrap(), &$loads)
                    .driver,
            }
        }
    };
}

/// The power of gravity on the cgs of `links` at q̇ = 1: Σ m g · d(cg)/dq, each cg's rate a
/// central difference of `$pose` at `$q` (the links' parameters `$l`, gravity `$g`), summed
/// in the order given.
macro_rules! gravity_power {
    ($l:ident, $g:ident, $pose:ident, $q:ident; $first:ident $(, $link:ident)*) => {
        $l.$first.mass * $g.dot(&d_dq(|q| $pose(q).$first.cg, $q))
            $(+ $l.$link.mass * $g.dot(&d_dq(|q| $pose(q).$link.cg, $q)))*
    };
}

#[test]
fn quick_return_hand_independent_checks() {
    let m = QuickReturn::new();
    let p = m.params().clone();
    let h = QuickReturnHand::new(&p);
    check_by_finite_differences(
        "quick-return",
        1,
        tracked!(h; points: A a, C c; links: crank, block, lever),
    );
    let loads = quick_return_loads();
    let (l, g) = (&p.links, p.gravity);
    for q in sweep() {
        let k = h.kinematics(q, QD, QDD).unwrap();
        let f = h.kinetostatics(&k, &loads);
        let (o2, o4, a, c) = (k.o2.pos, k.o4.pos, k.a.pos, k.c.pos);
        check_balances!("quick-return", q, (l, g, k);
            "crank" crank: [(o2, f.o2), (a, -f.a)], [f.driver, loads.friction];
            "block" block: [(a, f.a), (a, f.slot)], [f.slot_moment];
            "lever" lever: [(o4, f.o4), (a, -f.slot), (c, loads.cut)], [-f.slot_moment];
        );
    }
    check_dynamics(
        "quick-return",
        1,
        hand_dynamics!(
            h,
            loads,
            |q, pose| gravity_power!(l, g, pose, q; crank, block, lever)
                + loads.cut.dot(&d_dq(|q| pose(q).c, q))
                + loads.friction
        ),
    );
}

#[test]
fn scotch_yoke_hand_independent_checks() {
    let m = ScotchYoke::new();
    let p = m.params().clone();
    let h = ScotchYokeHand::new(&p);
    check_by_finite_differences(
        "Scotch yoke",
        1,
        tracked!(h; points: A a, Y y; links: crank, yoke),
    );
    let loads = scotch_yoke_loads();
    let (l, g) = (&p.links, p.gravity);
    for q in sweep() {
        let k = h.kinematics(q, QD, QDD).unwrap();
        let f = h.kinetostatics(&k, &loads);
        let (o2, a, y) = (k.o2.pos, k.a.pos, k.y.pos);
        check_balances!("Scotch yoke", q, (l, g, k);
            "crank" crank: [(o2, f.o2), (a, f.slot)], [f.driver, loads.drag];
            "yoke" yoke: [(y, f.guide), (a, -f.slot), (y, loads.resist)], [f.guide_moment];
        );
    }
    check_dynamics(
        "Scotch yoke",
        1,
        hand_dynamics!(
            h,
            loads,
            |q, pose| gravity_power!(l, g, pose, q; crank, yoke)
                + loads.resist.dot(&d_dq(|q| pose(q).y, q))
                + loads.drag
        ),
    );
}

#[test]
fn inverted_slider_crank_hand_independent_checks() {
    let m = InvertedSliderCrank::new();
    let p = m.params().clone();
    let h = InvertedSliderCrankHand::new(&p);
    check_by_finite_differences(
        "inverted slider-crank",
        1,
        tracked!(h; points: A a, P p; links: crank, rod, block),
    );
    let loads = inverted_slider_crank_loads();
    let (l, g) = (&p.links, p.gravity);
    for q in sweep() {
        let k = h.kinematics(q, QD, QDD).unwrap();
        let f = h.kinetostatics(&k, &loads);
        let (o2, o4, a, pp) = (k.o2.pos, k.o4.pos, k.a.pos, k.p.pos);
        check_balances!("inverted slider-crank", q, (l, g, k);
            "crank" crank: [(o2, f.o2), (a, -f.a)], [f.driver];
            "rod" rod: [(a, f.a), (o4, -f.slide), (pp, loads.push)], [-f.slide_moment];
            "block" block: [(o4, f.o4), (o4, f.slide)], [f.slide_moment, loads.resist];
        );
    }
    check_dynamics(
        "inverted slider-crank",
        1,
        hand_dynamics!(h, loads, |q, pose| {
            let block_turn = wrap(pose(q + FD_STEP).block.angle - pose(q - FD_STEP).block.angle)
                / (2.0 * FD_STEP);
            gravity_power!(l, g, pose, q; crank, rod, block)
                + loads.push.dot(&d_dq(|q| pose(q).p, q))
                + loads.resist * block_turn
        }),
    );
}

/// The hand-written geared slider-crank against itself: the mesh's radii and pressure
/// angle are the declared ones (the loaded model's), Willis' relation (no slip at the
/// pitch point), finite differences, every link's balance (the tooth force at the pitch
/// point on the line of action, at α from the tangent and pushing the gear away from the
/// pinion), the driver by three routes, dI*/dq, M* and the inverse problem.
#[test]
fn geared_slider_crank_hand_independent_checks() {
    let mesh = declared_joint("GearedSliderCrank", "mesh").mesh.unwrap();
    assert_eq!(
        (mesh.ra, mesh.rb, mesh.internal),
        (GEARED_PINION_RADIUS, GEARED_GEAR_RADIUS, false)
    );
    assert!((mesh.pressure_angle - GEARED_PRESSURE_ANGLE).abs() < 1e-15);
    let m = GearedSliderCrank::new();
    let p = m.params().clone();
    let h = GearedSliderCrankHand::new(&p);
    let (ra, rb) = (GEARED_PINION_RADIUS, GEARED_GEAR_RADIUS);
    let w = (p.points.O2 - p.points.O1).normalize();
    let pitch = p.points.O1 + w * ra;
    let tangent = Vector2::new(-w.y, w.x);
    check_by_finite_differences(
        "geared slider-crank",
        3,
        tracked!(h; points: A a, B b; links: pinion, crank, rod, piston),
    );
    let loads = geared_slider_crank_loads();
    let (l, g) = (&p.links, p.gravity);
    for q in sweep_turns(3) {
        let k = h.kinematics(q, QD, QDD).unwrap();
        // Willis: the pitch circles roll, v_P of the pinion = v_P of the gear.
        let vp1 = k.pinion.omega * ra;
        let vp2 = -k.crank.omega * rb;
        assert!((vp1 - vp2).abs() <= 1e-15 * vp1.abs(), "Willis at {q}");
        let f = h.kinetostatics(&k, &loads);
        let (o1, o2, a, b) = (k.o1.pos, k.o2.pos, k.a.pos, k.b.pos);
        let (ft, fr) = (f.mesh.dot(&tangent), f.mesh.dot(&w));
        assert!(
            fr >= 0.0
                && (fr - ft.abs() * GEARED_PRESSURE_ANGLE.tan()).abs() <= 1e-12 * f.tooth_load,
            "line of action at {q}: tangential {ft}, radial {fr}"
        );
        assert!((f.mesh.norm() - f.tooth_load).abs() <= 1e-12 * f.tooth_load);
        assert_eq!(f.flank, ft.signum());
        check_balances!("geared slider-crank", q, (l, g, k);
            "pinion" pinion: [(o1, f.o1), (pitch, -f.mesh)], [f.driver];
            "gear" crank: [(o2, f.o2), (pitch, f.mesh), (a, -f.a)], [loads.shaft];
            "rod" rod: [(a, f.a), (b, -f.b)], [];
            "piston" piston: [(b, f.b), (b, f.guide), (b, loads.gas)], [f.guide_moment];
        );
        assert!(f.guide.dot(&p.axes.guide).abs() <= 1e-12 * f.guide.norm().max(1.0));
    }
    check_dynamics(
        "geared slider-crank",
        3,
        hand_dynamics!(h, loads, |q, pose| {
            let crank_turn = wrap(pose(q + FD_STEP).crank.angle - pose(q - FD_STEP).crank.angle)
                / (2.0 * FD_STEP);
            gravity_power!(l, g, pose, q; pinion, crank, rod, piston)
                + loads.gas.dot(&d_dq(|q| pose(q).b, q))
                + loads.shaft * crank_turn
        }),
    );
}

/// The hand-written planetary against itself: both meshes' radii, kinds and pressure
/// angles are the declared ones (the loaded model's), no slip at either pitch point (the
/// sun's and the planet's teeth move together at K₁, the planet's are at rest on the
/// ring's at K₂), finite differences, every link's balance (each tooth force at its pitch
/// point on its line of action, its radial part pushing the planet away from the sun and
/// the ring outward), the driver by three routes, dI*/dq, M* and the inverse problem.
#[test]
fn planetary_hand_independent_checks() {
    let (sp, pr) = (
        declared_joint("Planetary", "sp").mesh.unwrap(),
        declared_joint("Planetary", "pr").mesh.unwrap(),
    );
    let (rs, rp, rr) = (
        PLANETARY_SUN_RADIUS,
        PLANETARY_PLANET_RADIUS,
        PLANETARY_RING_RADIUS,
    );
    assert_eq!((sp.ra, sp.rb, sp.internal), (rs, rp, false));
    assert_eq!((pr.ra, pr.rb, pr.internal), (rp, rr, true));
    assert!((sp.pressure_angle - PLANETARY_SUN_PRESSURE_ANGLE).abs() < 1e-15);
    assert!((pr.pressure_angle - PLANETARY_RING_PRESSURE_ANGLE).abs() < 1e-15);
    let m = Planetary::new();
    let p = m.params().clone();
    let h = PlanetaryHand::new(&p);
    check_by_finite_differences(
        "planetary",
        5,
        tracked!(h; points: P p, T t; links: sun, arm, planet),
    );
    let perp = |v: Vector2<f64>| Vector2::new(-v.y, v.x);
    let loads = planetary_loads();
    let (l, g) = (&p.links, p.gravity);
    for q in sweep_turns(5) {
        let k = h.kinematics(q, QD, QDD).unwrap();
        let (o, pp) = (k.o.pos, k.p.pos);
        let e = (pp - o).normalize();
        let (k1, k2) = (o + e * rs, o + e * rr);
        // Willis: the pitch circles roll on one another.
        let scale = k.sun.omega.abs() * rs;
        let v_sun = perp(k1 - o) * k.sun.omega;
        let v_planet_k1 = k.p.vel + perp(k1 - pp) * k.planet.omega;
        let v_planet_k2 = k.p.vel + perp(k2 - pp) * k.planet.omega;
        assert!(
            (v_sun - v_planet_k1).norm() <= 1e-15 * scale,
            "sun–planet slip at {q}"
        );
        assert!(
            v_planet_k2.norm() <= 1e-15 * scale,
            "planet–ring slip at {q}"
        );
        let f = h.kinetostatics(&k, &loads);
        let t = perp(e);
        for (what, force, tangent, tan, load, flank) in [
            (
                "sun–planet",
                f.sp,
                t,
                PLANETARY_SUN_PRESSURE_ANGLE.tan(),
                f.sp_load,
                f.sp_flank,
            ),
            (
                "planet–ring",
                f.pr,
                -t,
                PLANETARY_RING_PRESSURE_ANGLE.tan(),
                f.pr_load,
                f.pr_flank,
            ),
        ] {
            let (ft, fr) = (force.dot(&tangent), force.dot(&e));
            assert!(
                fr >= 0.0 && (fr - ft.abs() * tan).abs() <= 1e-12 * load,
                "{what} line of action at {q}: tangential {ft}, radial {fr}"
            );
            assert!((force.norm() - load).abs() <= 1e-12 * load);
            assert_eq!(flank, ft.signum());
        }
        check_balances!("planetary", q, (l, g, k);
            "sun" sun: [(o, f.s), (k1, -f.sp)], [f.driver];
            "arm" arm: [(o, f.o), (pp, -f.p), (k.t.pos, loads.pull)], [loads.brake];
            "planet" planet: [(pp, f.p), (k1, f.sp), (k2, -f.pr)], [];
        );
    }
    check_dynamics(
        "planetary",
        5,
        hand_dynamics!(h, loads, |q, pose| {
            let arm_turn =
                wrap(pose(q + FD_STEP).arm.angle - pose(q - FD_STEP).arm.angle) / (2.0 * FD_STEP);
            gravity_power!(l, g, pose, q; sun, arm, planet)
                + loads.pull.dot(&d_dq(|q| pose(q).t, q))
                + loads.brake * arm_turn
        }),
    );
}

/// The rack-and-pinion's guide moment is taken about the rack's own point R where it is
/// now (the convention of every prismatic joint, `docs/conventions.md`, Reactions), not
/// about R's drawing place: the rack's balance from the generated reactions alone, the
/// tooth force at the pitch point K = O + r n (n the unit normal from O to the rack's pitch
/// line), over a turn of the pinion (at q = 0 the two points coincide, elsewhere they are
/// r q apart: the moment reported about the drawing place was off by r q (u × R_guide)).
#[test]
fn rack_pinion_guide_moment_is_about_the_racks_point() {
    let m = RackPinion::new();
    let p = m.params().clone();
    let loads = rack_pinion_loads();
    let cross = |a: Vector2<f64>, b: Vector2<f64>| a.x * b.y - a.y * b.x;
    let u = p.axes.guide.normalize();
    let (o, r0) = (p.points.O, p.points.R);
    let n = Vector2::new(-u.y, u.x) * Vector2::new(-u.y, u.x).dot(&(r0 - o)).signum();
    let pitch = o + n * declared_joint("RackPinion", "mesh").mesh.unwrap().ra;
    let mut travel = 0.0f64;
    for q in sweep() {
        let k = m.kinematics(q, QD, QDD).unwrap();
        let f = m.kinetostatics(&k, &loads).unwrap();
        let (rack, at_r, at_l) = (&k.links.rack, k.points.R.pos, k.points.L.pos);
        let (guide, mesh) = (&f.joints.guide, &f.joints.mesh);
        let w = (p.gravity - rack.cg_acc) * p.links.rack.mass;
        let force = guide.force + mesh.force + w + loads.push;
        let moment = guide.moment
            + cross(pitch - at_r, mesh.force)
            + cross(rack.cg - at_r, w)
            + cross(at_l - at_r, loads.push);
        let scale = mesh.force.norm() + w.norm() + loads.push.norm();
        assert!(
            force.norm() <= 1e-12 * scale,
            "rack's forces at {q}: {force}"
        );
        assert!(
            moment.abs() <= 1e-12 * scale * 0.2,
            "rack's moments about R at {q}: {moment} (guide moment {})",
            guide.moment
        );
        travel = travel.max((at_r - r0).norm());
    }
    assert!(travel > 0.1, "the rack travelled {travel} m");
}

/// The hand-written rack and pinion against itself: the mesh's radius, kind and pressure
/// angle are the declared ones (the loaded model's), no slip at the pitch point (the
/// pinion's teeth at K move with the rack, along its axis u), finite differences, every
/// link's balance (the tooth force at the pitch point K = O + r n on its line of action, at
/// α from u and pushing the rack away from the pinion, the guide's force normal to u and
/// its moment about R where it is now), on both flanks (the floor's push and the push
/// reversed), the driver by three routes, dI*/dq, M* and the inverse problem.
#[test]
fn rack_pinion_hand_independent_checks() {
    let mesh = declared_joint("RackPinion", "mesh").mesh.unwrap();
    assert_eq!(
        (mesh.ra, mesh.rb, mesh.internal),
        (RACK_PINION_RADIUS, 0.0, false)
    );
    assert!((mesh.pressure_angle - RACK_PRESSURE_ANGLE).abs() < 1e-15);
    let m = RackPinion::new();
    let p = m.params().clone();
    let h = RackPinionHand::new(&p);
    let r = RACK_PINION_RADIUS;
    check_by_finite_differences(
        "rack and pinion",
        1,
        tracked!(h; points: R r, L l; links: pinion, rack),
    );
    let perp = |v: Vector2<f64>| Vector2::new(-v.y, v.x);
    let u = p.axes.guide.normalize();
    let (o, r0, l0) = (p.points.O, p.points.R, p.points.L);
    // The pitch line is parallel to u at r from O, on R's side: n from O towards it.
    let n = perp(u) * perp(u).dot(&(r0 - o)).signum();
    let pitch = o + n * r;
    let (l, g) = (&p.links, p.gravity);
    let mut flanks = [0usize; 2];
    for loads in [rack_pinion_loads(), rack_pinion_loads_reversed()] {
        for q in sweep() {
            let k = h.kinematics(q, QD, QDD).unwrap();
            let (rr, ll) = (k.r.pos, k.l.pos);
            // The rack translates along its guide: R stays on the guide's line, L and the
            // cg keep their offsets from R.
            assert!(
                (rr - r0).dot(&perp(u)).abs() < 1e-15,
                "R off the guide at {q}"
            );
            assert!(
                (ll - rr - (l0 - r0)).norm() < 1e-15,
                "the rack turns at {q}"
            );
            assert!((k.rack.cg - rr - (l.rack.cg - r0)).norm() < 1e-15);
            // No slip: the pinion's point at K moves with the rack.
            let v_pinion = perp(pitch - o) * k.pinion.omega;
            let scale = k.pinion.omega.abs() * r;
            assert!(
                (v_pinion - k.r.vel).norm() <= 1e-15 * scale,
                "slip at {q}: pinion {v_pinion:?}, rack {:?}",
                k.r.vel
            );
            let f = h.kinetostatics(&k, &loads);
            let (ft, fr) = (f.mesh.dot(&u), f.mesh.dot(&n));
            assert!(
                fr >= 0.0
                    && (fr - ft.abs() * RACK_PRESSURE_ANGLE.tan()).abs() <= 1e-12 * f.tooth_load,
                "line of action at {q}: tangential {ft}, radial {fr}"
            );
            assert!((f.mesh.norm() - f.tooth_load).abs() <= 1e-12 * f.tooth_load);
            assert_eq!(f.flank, ft.signum());
            flanks[(f.flank > 0.0) as usize] += 1;
            assert!(f.guide.dot(&u).abs() <= 1e-12 * f.guide.norm().max(1.0));
            check_balances!("rack and pinion", q, (l, g, k);
                "pinion" pinion: [(o, f.o), (pitch, -f.mesh)], [f.driver, loads.resist];
                "rack" rack: [(rr, f.guide), (pitch, f.mesh), (ll, loads.push)], [f.guide_moment];
            );
        }
        check_dynamics(
            "rack and pinion",
            1,
            hand_dynamics!(h, loads, |q, pose| {
                let pinion_turn =
                    wrap(pose(q + FD_STEP).pinion.angle - pose(q - FD_STEP).pinion.angle)
                        / (2.0 * FD_STEP);
                gravity_power!(l, g, pose, q; pinion, rack)
                    + loads.push.dot(&d_dq(|q| pose(q).l, q))
                    + loads.resist * pinion_turn
            }),
        );
    }
    assert!(flanks[0] > 0 && flanks[1] > 0, "flanks {flanks:?}");
}

/// The hand-written roller cam against itself: its law, base circle and roller are the
/// declared ones (the loaded model's), the lift by finite differences, the contact normal
/// perpendicular to the pitch curve as the cam sees it (a central difference of the
/// roller's centre in the cam's frame) and pushing the follower away from the cam, every
/// link's balance with the contact force at the contact point K = P − r n, the driver by
/// three routes, dI*/dq, M* and the inverse problem.
#[test]
fn roller_cam_hand_independent_checks() {
    use mech::cam::{Face, Law};
    let spec = declared_joint("RollerCam", "lobe").cam.unwrap();
    assert_eq!(spec.base_radius, CAM_BASE_RADIUS);
    assert_eq!(spec.face, Face::Roller(CAM_ROLLER_RADIUS));
    let laws: Vec<_> = spec.segments.iter().map(|g| g.law).collect();
    assert_eq!(
        laws,
        [Law::Cycloidal, Law::Dwell, Law::Cycloidal, Law::Dwell]
    );
    let ends = [CAM_SEGMENTS[0], CAM_SEGMENTS[1], CAM_SEGMENTS[2], TAU];
    let lifts = [CAM_LIFT, CAM_LIFT, 0.0, 0.0];
    for (k, g) in spec.segments.iter().enumerate() {
        assert!(
            (g.end - ends[k]).abs() < 1e-15,
            "segment {k} ends at {}",
            g.end
        );
        assert!(
            (g.to - lifts[k]).abs() < 1e-15,
            "segment {k} lifts to {}",
            g.to
        );
    }
    let m = RollerCam::new();
    let p = m.params().clone();
    let h = RollerCamHand::new(&p);
    let r = CAM_ROLLER_RADIUS;
    check_by_finite_differences(
        "roller cam",
        1,
        tracked!(h; points: P p, T t; links: cam, follower),
    );
    let loads = roller_cam_loads();
    let (l, g) = (&p.links, p.gravity);
    let cross = |a: Vector2<f64>, b: Vector2<f64>| a.x * b.y - a.y * b.x;
    // The roller's centre seen from the cam (turned back by q), relative to O.
    let in_cam = |q: f64, v: Vector2<f64>| {
        let (sn, cs) = (-q).sin_cos();
        Vector2::new(cs * v.x - sn * v.y, sn * v.x + cs * v.y)
    };
    for q in sweep() {
        let k = h.kinematics(q, QD, QDD).unwrap();
        let f = h.kinetostatics(&k, &loads);
        let (o, pp) = (k.o.pos, k.p.pos);
        assert!(f.normal_force > 0.0, "the follower leaves the cam at {q}");
        let n = f.lobe / f.normal_force;
        assert!((n.norm() - 1.0).abs() < 1e-12, "|n| at {q}");
        let pitch = |q: f64| in_cam(q, h.pose(q).unwrap().p - o);
        let tangent = (pitch(q + FD_STEP) - pitch(q - FD_STEP)) / (2.0 * FD_STEP);
        let nc = in_cam(q, n);
        assert!(
            nc.dot(&tangent).abs() < 1e-8 * tangent.norm(),
            "normal not normal to the pitch curve at {q}"
        );
        assert!(
            cross(tangent, nc) > 0.0,
            "normal not outward at {q} (the pitch curve runs clockwise)"
        );
        let contact = pp - n * r;
        check_balances!("roller cam", q, (l, g, k);
            "cam" cam: [(o, f.o), (contact, -f.lobe)], [f.driver, loads.drag];
            "follower" follower: [(pp, f.slide), (contact, f.lobe), (k.t.pos, loads.push)],
                [f.slide_moment];
        );
        assert!(f.slide.dot(&p.axes.slide).abs() <= 1e-12 * f.slide.norm().max(1.0));
    }
    check_dynamics(
        "roller cam",
        1,
        hand_dynamics!(
            h,
            loads,
            |q, pose| gravity_power!(l, g, pose, q; cam, follower)
                + loads.push.dot(&d_dq(|q| pose(q).t, q))
                + loads.drag
        ),
    );
}

/// The hand-written crank, rod and wheel against itself: the wheel's radius is the
/// declared one (the loaded model's), rolling without slipping (the contact point's
/// velocity zero: v_C + ω₄ × (K − C) = 0), finite differences, every link's balance with
/// the contact force at K = C − r n, its normal and friction parts, the driver by three
/// routes, dI*/dq, M* and the inverse problem.
#[test]
fn crank_rod_wheel_hand_independent_checks() {
    let roll = declared_joint("CrankRodWheel", "roll");
    assert_eq!(roll.radius, WHEEL_RADIUS);
    let m = CrankRodWheel::new();
    let p = m.params().clone();
    let h = CrankRodWheelHand::new(&p);
    check_by_finite_differences(
        "crank-rod-wheel",
        1,
        tracked!(h; points: A a, C c; links: crank, rod, wheel),
    );
    let loads = crank_rod_wheel_loads();
    let (l, g) = (&p.links, p.gravity);
    let u = p.axes.roll.normalize();
    let n = Vector2::new(-u.y, u.x);
    for q in sweep() {
        let k = h.kinematics(q, QD, QDD).unwrap();
        let f = h.kinetostatics(&k, &loads);
        let (o2, a, c) = (k.o2.pos, k.a.pos, k.c.pos);
        let contact = c - n * WHEEL_RADIUS;
        let r = contact - c;
        let vk = k.c.vel + Vector2::new(-r.y, r.x) * k.wheel.omega;
        assert!(
            vk.norm() <= 1e-12 * k.c.vel.norm().max(1e-3),
            "the wheel slips at {q}: {vk:?}"
        );
        assert!(
            (f.roll - (n * f.normal + u * f.friction)).norm() <= 1e-12 * f.roll.norm(),
            "contact parts at {q}"
        );
        check_balances!("crank-rod-wheel", q, (l, g, k);
            "crank" crank: [(o2, f.o2), (a, -f.a)], [f.driver];
            "rod" rod: [(a, f.a), (c, -f.c)], [];
            "wheel" wheel: [(c, f.c), (contact, f.roll), (c, loads.pull)], [loads.brake];
        );
    }
    check_dynamics(
        "crank-rod-wheel",
        1,
        hand_dynamics!(h, loads, |q, pose| {
            let wheel_turn =
                (pose(q + FD_STEP).wheel.angle - pose(q - FD_STEP).wheel.angle) / (2.0 * FD_STEP);
            gravity_power!(l, g, pose, q; crank, rod, wheel)
                + loads.pull.dot(&d_dq(|q| pose(q).c, q))
                + loads.brake * wheel_turn
        }),
    );
}

/// The hand-written Scotch yoke with a block against itself: the block keeps the yoke's
/// orientation and the yoke the ground's, A on the slot's line through A₀ carried by the
/// yoke, Y on the guide, finite differences, every link's balance (the slot's and the
/// guide's forces normal to their axes), the driver by three routes, dI*/dq, M* and the
/// inverse problem.
#[test]
fn block_scotch_yoke_hand_independent_checks() {
    let m = BlockScotchYoke::new();
    let p = m.params().clone();
    let h = BlockScotchYokeHand::new(&p);
    check_by_finite_differences(
        "block Scotch yoke",
        1,
        tracked!(h; points: A a, Y y, T t; links: crank, block, yoke),
    );
    let loads = block_scotch_yoke_loads();
    let (l, g) = (&p.links, p.gravity);
    let cross = |a: Vector2<f64>, b: Vector2<f64>| a.x * b.y - a.y * b.x;
    let (us, ug) = (p.axes.slot.normalize(), p.axes.guide.normalize());
    let (a0, y0, t0) = (p.points.A, p.points.Y, p.points.T);
    let theta4 = (t0.y - y0.y).atan2(t0.x - y0.x);
    for q in sweep() {
        let k = h.kinematics(q, QD, QDD).unwrap();
        let f = h.kinetostatics(&k, &loads);
        let (o2, a, y, t) = (k.o2.pos, k.a.pos, k.y.pos, k.t.pos);
        // The yoke translates along the guide, the block with A, neither turns.
        let shift = y - y0;
        assert!(cross(shift, ug).abs() < 1e-15, "Y off the guide at {q}");
        assert!((t - t0 - shift).norm() < 1e-15, "the yoke turns at {q}");
        assert!(
            (k.block.cg - a - (p.links.block.cg - a0)).norm() < 1e-15,
            "the block turns at {q}"
        );
        assert!(
            cross(a - a0 - shift, us).abs() < 1e-15,
            "A off the slot at {q}"
        );
        assert_eq!((k.block.angle, k.yoke.angle), (0.0, theta4));
        assert!(f.slot.dot(&us).abs() <= 1e-12 * f.slot.norm().max(1.0));
        assert!(f.guide.dot(&ug).abs() <= 1e-12 * f.guide.norm().max(1.0));
        check_balances!("block Scotch yoke", q, (l, g, k);
            "crank" crank: [(o2, f.o2), (a, -f.a)], [f.driver];
            "block" block: [(a, f.a), (a, f.slot)], [f.slot_moment, loads.friction];
            "yoke" yoke: [(y, f.guide), (a, -f.slot), (t, loads.resist)],
                [f.guide_moment, -f.slot_moment];
        );
    }
    check_dynamics(
        "block Scotch yoke",
        1,
        hand_dynamics!(h, loads, |q, pose| {
            let block_turn = wrap(pose(q + FD_STEP).block.angle - pose(q - FD_STEP).block.angle)
                / (2.0 * FD_STEP);
            gravity_power!(l, g, pose, q; crank, block, yoke)
                + loads.resist.dot(&d_dq(|q| pose(q).t, q))
                + loads.friction * block_turn
        }),
    );
}

/// The hand-written slotted crank and ram against itself over its swing: the block turns
/// with the crank and the ram not, B on the crank's slot (the line through B₀ along the
/// slot's axis, both carried by the crank about O2) and on the ground's guide, finite
/// differences, every link's balance (the slot's and the guide's forces normal to their
/// axes), the driver by three routes, dI*/dq, M* and the inverse problem.
#[test]
fn slotted_crank_ram_hand_independent_checks() {
    let m = SlottedCrankRam::new();
    let p = m.params().clone();
    let h = SlottedCrankRamHand::new(&p);
    check_by_finite_differences_over(
        "slotted crank and ram",
        sweep_swing(),
        tracked!(h; points: E e, B b, P p; links: crank, block, ram),
    );
    let loads = slotted_crank_ram_loads();
    let (l, g) = (&p.links, p.gravity);
    let cross = |a: Vector2<f64>, b: Vector2<f64>| a.x * b.y - a.y * b.x;
    let (o20, e0, b0, p0) = (p.points.O2, p.points.E, p.points.B, p.points.P);
    let ug = p.axes.guide.normalize();
    let theta2 = (e0.y - o20.y).atan2(e0.x - o20.x);
    let turn = |phi: f64, v: Vector2<f64>| {
        let (sn, cs) = phi.sin_cos();
        Vector2::new(cs * v.x - sn * v.y, sn * v.x + cs * v.y)
    };
    for q in sweep_swing() {
        let k = h.kinematics(q, QD, QDD).unwrap();
        let f = h.kinetostatics(&k, &loads);
        let (o2, b, pp) = (k.o2.pos, k.b.pos, k.p.pos);
        // The crank turned by φ = q − θ₂(drawing) carries the slot's line and the block.
        let phi = q - theta2;
        let us = turn(phi, p.axes.slot.normalize());
        let on_slot = o2 + turn(phi, b0 - o20);
        assert!(
            (k.e.pos - o2 - turn(phi, e0 - o20)).norm() < 1e-15,
            "E at {q}"
        );
        assert!(
            cross(b - on_slot, us).abs() < 1e-15,
            "B off the slot at {q}"
        );
        assert!(cross(b - b0, ug).abs() < 1e-15, "B off the guide at {q}");
        assert!(
            (k.block.cg - b - turn(phi, l.block.cg - b0)).norm() < 1e-15,
            "the block does not turn with the crank at {q}"
        );
        assert!((pp - b - (p0 - b0)).norm() < 1e-15, "the ram turns at {q}");
        assert!(wrap(k.block.angle - phi).abs() < 1e-15);
        assert!(f.slot.dot(&us).abs() <= 1e-12 * f.slot.norm().max(1.0));
        assert!(f.guide.dot(&ug).abs() <= 1e-12 * f.guide.norm().max(1.0));
        check_balances!("slotted crank and ram", q, (l, g, k);
            "crank" crank: [(o2, f.o2), (b, -f.slot)], [f.driver, -f.slot_moment];
            "block" block: [(b, f.slot), (b, -f.b)], [f.slot_moment, loads.resist];
            "ram" ram: [(b, f.b), (b, f.guide), (pp, loads.push)], [f.guide_moment];
        );
    }
    check_dynamics_over(
        "slotted crank and ram",
        sweep_swing(),
        hand_dynamics!(h, loads, |q, pose| {
            let block_turn = wrap(pose(q + FD_STEP).block.angle - pose(q - FD_STEP).block.angle)
                / (2.0 * FD_STEP);
            gravity_power!(l, g, pose, q; crank, block, ram)
                + loads.push.dot(&d_dq(|q| pose(q).p, q))
                + loads.resist * block_turn
        }),
    );
}

/// The kinds of group the floor's machines exercise, as the macro's plan solves them
/// (`mech_core::plan::assur`, the decomposition the generated code is emitted from): what
/// each bench group measures. The Scotch yoke's yoke (a guide and a pin in a slot) is a
/// `SlottedSlider`: one closed-form slide, its rates and reactions in that coordinate. The
/// Scotch yoke with a block is an `Rpp` dyad (the block pinned to the crank, sliding in the
/// yoke, the yoke on the ground), the slotted crank and ram a `Prp` (the block sliding on
/// the crank, pinned to the ram, the ram on the ground): neither a `SlottedSlider` nor
/// Newton.
#[test]
fn floor_machines_group_kinds() {
    use mech_core::plan::assur::plan;
    use mech_oracle::GenericMechanism;
    const REFERENCE: &str = include_str!("common/mechanisms.rs");
    const FLOOR: &str = include_str!("../benches/floor/machines.rs");
    let kinds = |source: &str, name: &str| -> Vec<String> {
        let g = GenericMechanism::from_rust_source(source, name).unwrap();
        plan(g.model())
            .unwrap()
            .iter()
            .map(|group| {
                let s = format!("{:?}", group.solver);
                s.split([' ', '{']).next().unwrap().to_owned()
            })
            .collect()
    };
    for (source, name, expected) in [
        (REFERENCE, "FourBar", ["DrivenRevolute", "Rrr"]),
        (REFERENCE, "SliderCrank", ["DrivenRevolute", "Rrp"]),
        (REFERENCE, "QuickReturn", ["DrivenRevolute", "Rpr"]),
        (REFERENCE, "ScotchYoke", ["DrivenRevolute", "SlottedSlider"]),
        (FLOOR, "InvertedSliderCrank", ["DrivenRevolute", "Rpr"]),
        (FLOOR, "BlockScotchYoke", ["DrivenRevolute", "Rpp"]),
        (FLOOR, "SlottedCrankRam", ["DrivenRevolute", "Prp"]),
    ] {
        assert_eq!(kinds(source, name), expected, "{name}");
    }
    // The machines with elements, which the dense oracle refuses: their model as the
    // run-time `Mechanism` loads it.
    let element_kinds = |name: &str| -> Vec<String> {
        let m = mech::Mechanism::from_rust_source(FLOOR, name).unwrap();
        plan(m.model())
            .unwrap()
            .iter()
            .map(|group| {
                let s = format!("{:?}", group.solver);
                s.split([' ', '{']).next().unwrap().to_owned()
            })
            .collect()
    };
    for (name, expected) in [
        ("GearedSliderCrank", &["DrivenRevolute", "Mesh", "Rrp"][..]),
        ("RollerCam", &["DrivenRevolute", "Cam"][..]),
        ("CrankRodWheel", &["DrivenRevolute", "Rrl"][..]),
        ("Planetary", &["DrivenRevolute", "Train"][..]),
        ("RackPinion", &["DrivenRevolute", "Mesh"][..]),
    ] {
        assert_eq!(element_kinds(name), expected, "{name}");
    }
}

/// A load on a link that slides on the ground: the block Scotch yoke's friction couple on
/// its block (the block slides in the yoke, the yoke on the ground: it never turns). Its
/// Zhukovski term is left out, generated and at run time (a torque on a link with ω = 0
/// does no work), so M* and q̈ do not change with it; and a non-finite value of it is still
/// refused as an input, not passed over with its term.
#[test]
fn a_torque_on_a_sliding_link_does_no_work_and_is_still_checked() {
    let gen = BlockScotchYoke::new();
    let rt = mech::Mechanism::from_rust_source(
        include_str!("../benches/floor/machines.rs"),
        "BlockScotchYoke",
    )
    .unwrap();
    let with = |t: f64| {
        let mut g = block_scotch_yoke_loads();
        assert!(g.set_by_name("friction", &[t]));
        let mut r = rt.loads();
        assert!(r.set_by_name("resist", &[-150.0, 20.0]));
        assert!(r.set_by_name("friction", &[t]));
        (g, r)
    };
    for q in [0.3, 1.7, 4.0] {
        // The block does not turn: its angular velocity and acceleration are zero.
        let mo = gen.kinematics(q, 12.0, -3.0).unwrap();
        let block = mo.links.block;
        assert_eq!((block.omega, block.alpha), (0.0, 0.0), "q = {q}");
        let (g0, r0) = with(-0.6);
        let (g1, r1) = with(250.0);
        let m0 = gen.reduced_moment(q, &g0).unwrap();
        assert_eq!(gen.reduced_moment(q, &g1).unwrap(), m0, "q = {q}");
        assert_eq!(
            gen.acceleration(q, 12.0, 5.0, &g1).unwrap(),
            gen.acceleration(q, 12.0, 5.0, &g0).unwrap()
        );
        let rm0 = rt.reduced_moment(q, &r0).unwrap();
        assert_eq!(rt.reduced_moment(q, &r1).unwrap(), rm0, "q = {q}");
        assert!(
            within((rm0 - m0).abs() / m0.abs(), 1e-12),
            "run-time {rm0}, generated {m0}"
        );
        for x in [f64::NAN, f64::INFINITY] {
            let (g, r) = with(x);
            for e in [
                gen.reduced_moment(q, &g).err(),
                gen.acceleration(q, 12.0, 5.0, &g).err(),
                rt.reduced_moment(q, &r).err(),
                rt.acceleration(q, 12.0, 5.0, &r).err(),
            ] {
                assert!(
                    matches!(&e, Some(MechError::InvalidInput(m)) if m.contains("must be finite")),
                    "friction {x} at q = {q}: {e:?}"
                );
            }
        }
    }
}
