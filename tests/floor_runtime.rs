//! The run-time `mech::Mechanism`, loaded from the text the macro compiled, gives the
//! generated struct's answers on the floor's machines (`benches/floor/runtime.rs`
//! times the two): every quantity of every operation the floor times — pose, kinematics,
//! kinetostatics (every reaction and the driver), the driver by virtual power, Zhukovski's
//! I*, dI*/dq and M*, the direct problem's q̈ — with the floor's loads, on a sweep of 72
//! crank angles over a full turn (the slotted crank and ram, which cannot turn, over its
//! swing `floor::RAM_SWING`), through the run-time caller-buffer forms
//! (`pose_into`, `kinematics_into`, `kinetostatics_into`, `Machine::driver_actions`).
//!
//! Relative to the largest entry of the same kind at that q (angles absolute, rad; the
//! scalars on their largest value over the sweep), as `tests/floor.rs`.

use crate::floor::machines::*;
use crate::measure::within_at;
use crate::mechanisms;

use mech::prelude::*;
use mech::Mechanism;
use mechanisms::*;
use std::collections::BTreeMap;
use std::f64::consts::{PI, TAU};

// measured 0 on every quantity of every machine: the same kernels on the same numbers in
// the same order, every link's angle by the same rule (`Mechanism::link_angle`), every
// point from its owner (an anchor is its link's state); bit for bit, so no tolerance
const TOL: f64 = 0.0;
const STEPS: usize = 72;
const QD: f64 = 12.0;
const QDD: f64 = -3.0;
const DRIVER: f64 = 5.0;

const REFERENCE: &str = include_str!("common/mechanisms.rs");
const FLOOR: &str = include_str!("../benches/floor/machines.rs");

fn wrap(a: f64) -> f64 {
    let r = a - TAU * (a / TAU).round();
    if r <= -PI {
        r + TAU
    } else {
        r
    }
}

/// Per quantity: (largest |run-time − generated|, largest |entry|) at each q.
#[derive(Default)]
struct Report(BTreeMap<String, (bool, Vec<(f64, f64, f64)>)>);

impl Report {
    fn record(&mut self, name: &str, q: f64, scalar: bool, pairs: &[(f64, f64)], angle: bool) {
        let (mut diff, mut big) = (0.0f64, 0.0f64);
        for &(r, g) in pairs {
            assert!(
                r.is_finite() && g.is_finite(),
                "{name} at q = {q}: run-time {r}, generated {g}"
            );
            let d = if angle { wrap(r - g) } else { r - g };
            diff = diff.max(d.abs());
            big = big.max(r.abs()).max(g.abs());
        }
        let e = self.0.entry(name.to_string()).or_default();
        e.0 = scalar;
        e.1.push((q, diff, if angle { big.max(1.0) } else { big }));
    }
    fn vecs(&mut self, name: &str, q: f64, pairs: &[(Vector2<f64>, Vector2<f64>)]) {
        let flat: Vec<(f64, f64)> = pairs
            .iter()
            .flat_map(|(r, g)| [(r.x, g.x), (r.y, g.y)])
            .collect();
        self.record(name, q, false, &flat, false);
    }
    fn check(&self, machine: &str) {
        let mut failures = Vec::new();
        for (name, (scalar, rows)) in &self.0 {
            assert!(
                rows.len() == STEPS,
                "{machine} {name}: {} samples",
                rows.len()
            );
            let sweep_big = rows.iter().fold(0.0f64, |m, r| m.max(r.2));
            let mut worst = 0.0f64;
            for &(q, diff, big) in rows {
                let scale = if *scalar { sweep_big } else { big };
                let rel = if scale > 0.0 { diff / scale } else { diff };
                worst = worst.max(rel);
                if !within_at(name, rel, TOL) {
                    failures.push(format!(
                        "{machine} {name} at q = {q:.6}: |run-time − generated| = {diff:.3e}, relative {rel:.3e}"
                    ));
                }
            }
            println!("{machine:<24} {name:<40} worst relative {worst:.2e}");
        }
        assert!(
            failures.is_empty(),
            "run-time and generated disagree:\n{}",
            failures.join("\n")
        );
    }
}

/// One machine: the generated `$ty` with `$loads` set by name, the run-time mechanism of
/// the same name from `$source` with the same loads, compared over the sweep: a full turn
/// from 0.7, or the angles `$q(k)`, k < STEPS (a machine that cannot turn).
macro_rules! floor_runtime {
    ($test:ident, $source:expr, $ty:ident, $loads_ty:ident, [$(($ln:literal, $lv:expr)),*]) => {
        floor_runtime!(
            $test, $source, $ty, $loads_ty, [$(($ln, $lv)),*],
            |k: usize| 0.7 + TAU * k as f64 / STEPS as f64
        );
    };
    (
        $test:ident, $source:expr, $ty:ident, $loads_ty:ident, [$(($ln:literal, $lv:expr)),*],
        $q:expr
    ) => {
        #[test]
        fn $test() {
            let gen = $ty::new();
            let rt = Mechanism::from_rust_source($source, stringify!($ty)).unwrap();
            let mut gl = $loads_ty::default();
            let mut rl = rt.loads();
            $(
                assert!(gl.set_by_name($ln, &$lv));
                assert!(rl.set_by_name($ln, &$lv));
            )*
            let model = rt.model().clone();
            let links: Vec<String> = model.links[1..].iter().map(|l| l.name.clone()).collect();
            let points: Vec<String> = model.points.iter().map(|p| p.name.clone()).collect();
            let joints: Vec<String> = model.joints.iter().map(|j| j.name.clone()).collect();
            let mut pose = rt.pose(&[0.7]).unwrap();
            let mut motion = rt.kinematics(&[0.7], &[QD], &[QDD]).unwrap();
            let mut forces = rt.kinetostatics(&motion, &rl).unwrap();
            let mut states = Vec::new();
            let mut r = Report::default();
            let q_of = $q;
            for k in 0..STEPS {
                let q: f64 = q_of(k);
                let gp = gen.pose(q).unwrap();
                rt.pose_into(&[q], &mut pose).unwrap();
                let angles: Vec<_> = links
                    .iter()
                    .map(|n| (pose.link(n).unwrap().angle, gp.link(n).unwrap().angle))
                    .collect();
                r.record("pose: link angle", q, false, &angles, true);
                let cgs: Vec<_> = links
                    .iter()
                    .map(|n| (pose.link(n).unwrap().cg, gp.link(n).unwrap().cg))
                    .collect();
                r.vecs("pose: link cg", q, &cgs);
                let pts: Vec<_> = points
                    .iter()
                    .map(|n| (pose.point(n).unwrap().pos, gp.point(n).unwrap().pos))
                    .collect();
                r.vecs("pose: point pos", q, &pts);

                let gm = gen.kinematics(q, QD, QDD).unwrap();
                rt.kinematics_into(&[q], &[QD], &[QDD], &mut motion).unwrap();
                let l = |f: fn(&LinkMotion) -> f64| -> Vec<(f64, f64)> {
                    links
                        .iter()
                        .map(|n| (f(motion.link(n).unwrap()), f(gm.link(n).unwrap())))
                        .collect()
                };
                r.record("kinematics: link angle", q, false, &l(|m| m.angle), true);
                r.record("kinematics: link omega", q, false, &l(|m| m.omega), false);
                r.record("kinematics: link alpha", q, false, &l(|m| m.alpha), false);
                type V = Vector2<f64>;
                let lv = |f: fn(&LinkMotion) -> V| -> Vec<(V, V)> {
                    links
                        .iter()
                        .map(|n| (f(motion.link(n).unwrap()), f(gm.link(n).unwrap())))
                        .collect()
                };
                r.vecs("kinematics: link cg", q, &lv(|m| m.cg));
                r.vecs("kinematics: link cg_vel", q, &lv(|m| m.cg_vel));
                r.vecs("kinematics: link cg_acc", q, &lv(|m| m.cg_acc));
                let pv = |f: fn(&PointMotion) -> V| -> Vec<(V, V)> {
                    points
                        .iter()
                        .map(|n| (f(motion.point(n).unwrap()), f(gm.point(n).unwrap())))
                        .collect()
                };
                r.vecs("kinematics: point pos", q, &pv(|m| m.pos));
                r.vecs("kinematics: point vel", q, &pv(|m| m.vel));
                r.vecs("kinematics: point acc", q, &pv(|m| m.acc));
                // One rule for a link's angle whichever route asks (`Mechanism::link_angle`):
                // the pose's, the motion's and the positions row's are the same number.
                let np = points.len();
                let mut row = vec![0.0; 2 * np + links.len()];
                rt.positions_into(&[q], &mut states, &mut row).unwrap();
                for (k, n) in links.iter().enumerate() {
                    let (a, b) = (pose.link(n).unwrap().angle, motion.link(n).unwrap().angle);
                    assert_eq!(a.to_bits(), b.to_bits(), "{n} at q = {q}: pose {a}, motion {b}");
                    let c = row[2 * np + k];
                    assert_eq!(a.to_bits(), c.to_bits(), "{n} at q = {q}: pose {a}, row {c}");
                }

                let gf = gen.kinetostatics(&gm, &gl).unwrap();
                rt.kinetostatics_into(&motion, &rl, None, &mut forces).unwrap();
                r.record("kinetostatics: driver", q, true, &[(forces.driver[0], gf.driver)], false);
                let mut jf = Vec::new();
                for n in &joints {
                    let (rf, rm) = forces.reaction(n).unwrap();
                    let (gff, gm_) = gf.reaction(n).unwrap();
                    jf.push((rf, gff));
                    assert_eq!(rm.is_some(), gm_.is_some(), "{n}");
                    if let (Some(a), Some(b)) = (rm, gm_) {
                        // One quantity per prismatic joint (the dyads of two sliders
                        // have two).
                        let name = format!("kinetostatics: prismatic moment ({n})");
                        r.record(&name, q, true, &[(a, b)], false);
                    }
                }
                r.vecs("kinetostatics: joint force", q, &jf);

                let mut d = [0.0];
                rt.driver_actions(&motion, &rl, &mut d).unwrap();
                let gd = gen.driver_action(&gm, &gl).unwrap();
                r.record("driver_action: virtual power", q, true, &[(d[0], gd)], false);

                let (rr, gr) = (rt.reduced(q).unwrap(), gen.reduced(q).unwrap());
                r.record("reduced: I*", q, true, &[(rr.inertia, gr.inertia)], false);
                r.record(
                    "reduced: dI*/dq",
                    q,
                    true,
                    &[(rr.inertia_derivative, gr.inertia_derivative)],
                    false,
                );
                let (rm, gmm) = (rt.reduced_moment(q, &rl).unwrap(), gen.reduced_moment(q, &gl).unwrap());
                r.record("reduced_moment: M*", q, true, &[(rm, gmm)], false);
                let ra = rt.acceleration(q, QD, DRIVER, &rl).unwrap();
                let ga = gen.acceleration(q, QD, DRIVER, &gl).unwrap();
                r.record("acceleration: q̈", q, true, &[(ra, ga)], false);
            }
            r.check(stringify!($ty));
        }
    };
}

floor_runtime!(
    four_bar,
    REFERENCE,
    FourBar,
    FourBarLoads,
    [("tool", [80.0, -60.0]), ("resist", [2.0])]
);
floor_runtime!(
    slider_crank,
    REFERENCE,
    SliderCrank,
    SliderCrankLoads,
    [("gas", [-1500.0, 0.0]), ("shaft", [-4.0])]
);
floor_runtime!(
    quick_return,
    REFERENCE,
    QuickReturn,
    QuickReturnLoads,
    [("cut", [-250.0, 30.0]), ("friction", [-1.5])]
);
floor_runtime!(
    scotch_yoke,
    REFERENCE,
    ScotchYoke,
    ScotchYokeLoads,
    [("resist", [-120.0, 15.0]), ("drag", [-1.5])]
);
floor_runtime!(
    inverted_slider_crank,
    FLOOR,
    InvertedSliderCrank,
    InvertedSliderCrankLoads,
    [("push", [-300.0, 40.0]), ("resist", [2.5])]
);
floor_runtime!(
    geared_slider_crank,
    FLOOR,
    GearedSliderCrank,
    GearedSliderCrankLoads,
    [("gas", [-900.0, -90.0]), ("shaft", [-4.0])]
);
floor_runtime!(
    roller_cam,
    FLOOR,
    RollerCam,
    RollerCamLoads,
    [("push", [20.0, -250.0]), ("drag", [-1.5])]
);
floor_runtime!(
    crank_rod_wheel,
    FLOOR,
    CrankRodWheel,
    CrankRodWheelLoads,
    [("pull", [-150.0, 20.0]), ("brake", [-0.8])]
);
floor_runtime!(
    block_scotch_yoke,
    FLOOR,
    BlockScotchYoke,
    BlockScotchYokeLoads,
    [("resist", [-150.0, 20.0]), ("friction", [-0.6])]
);
floor_runtime!(
    planetary,
    FLOOR,
    Planetary,
    PlanetaryLoads,
    [("pull", [40.0, -60.0]), ("brake", [-2.0])]
);
floor_runtime!(
    rack_pinion,
    FLOOR,
    RackPinion,
    RackPinionLoads,
    [("push", [-250.0, 30.0]), ("resist", [-2.0])]
);
floor_runtime!(
    slotted_crank_ram,
    FLOOR,
    SlottedCrankRam,
    SlottedCrankRamLoads,
    [("push", [-400.0, 60.0]), ("resist", [1.8])],
    |k: usize| {
        let (lo, hi) = crate::floor::RAM_SWING;
        lo + (hi - lo) * k as f64 / (STEPS - 1) as f64
    }
);
