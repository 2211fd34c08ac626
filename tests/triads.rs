//! Triad machines (issue 35; `tests/common/triads.rs`): the generated solvers, whose triad
//! goes through `mech_core::kernel::triad` (one eliminated unknown), against the oracle's
//! dense Newton continued from the drawing and the run-time `Mechanism`, over a full turn
//! of the crank; continuity on the drawn assembly; `NoAssembly` past a dead point; and no
//! allocation.

#[path = "common/triads.rs"]
mod triads;

use crate::counting;
use crate::measure::within;
use mech::prelude::*;
use mech_oracle::GenericMechanism;
use triads::*;

/// The text the macro compiled.
const TRIADS: &str = include_str!("common/triads.rs");

/// The drawing's crank angle of a machine whose crank runs from point `o` to point `a`.
fn q0(o: Vector2<f64>, a: Vector2<f64>) -> f64 {
    let d = a - o;
    d.y.atan2(d.x)
}

/// The generated pose, the run-time `Mechanism`'s and the oracle's (dense Newton continued
/// from the drawing: the drawn assembly) agree at 72 crank angles over a full turn, to
/// 1e-12 of the drawing's size; and so do the velocities.
macro_rules! agrees {
    ($test:ident, $ty:ident, $name:literal, $o:ident, $a:ident) => {
        #[test]
        fn $test() {
            let m = $ty::new();
            let oracle = GenericMechanism::from_rust_source(TRIADS, $name).unwrap();
            let runtime = mech::Mechanism::from_rust_source(TRIADS, $name).unwrap();
            let p = m.params();
            let start = q0(p.points.$o, p.points.$a);
            let size = $ty::POINT_NAMES
                .iter()
                .map(|n| m.pose(start).unwrap().point(n).unwrap().pos.norm())
                .fold(0.0, f64::max);
            for k in 0..72 {
                let q = start + std::f64::consts::TAU * k as f64 / 72.0;
                let gen = m.pose(q).unwrap();
                let want = oracle.pose(&[q]).unwrap();
                let rt = runtime.pose(&[q]).unwrap();
                let mo = m.kinematics(q, 2.0, -1.0).unwrap();
                let wk = oracle.kinematics(&[q], &[2.0], &[-1.0]).unwrap();
                for n in $ty::POINT_NAMES {
                    let g = gen.point(n).unwrap().pos;
                    let d = (g - want.point(n).unwrap().pos).norm() / size;
                    assert!(within(d, 1e-12), "{n} at step {k}: {d:e} from the oracle");
                    let d = (g - rt.point(n).unwrap().pos).norm() / size;
                    assert!(within(d, 1e-12), "{n} at step {k}: {d:e} from the run time");
                    let (v, w) = (mo.point(n).unwrap().vel, wk.point(n).unwrap().vel);
                    let d = (v - w).norm() / (2.0 * size);
                    assert!(within(d, 1e-11), "{n} at step {k}: velocity {d:e}");
                }
            }
        }
    };
}

agrees!(
    stephenson3_agrees_with_the_oracle,
    StephensonIII,
    "StephensonIII",
    P0,
    P1
);
agrees!(
    stephenson2_agrees_with_the_oracle,
    Stephenson2,
    "Stephenson2",
    O,
    E
);

/// A whole turn in 1° steps stays on the drawn assembly: every point moves by no more than
/// its speed and acceleration allow over the step, and comes back to where it started
/// (as `kinematics::continuity` for the dyad chains).
macro_rules! continuity {
    ($test:ident, $ty:ident, $o:ident, $a:ident) => {
        #[test]
        fn $test() {
            let m = $ty::new();
            let p = m.params();
            let start = q0(p.points.$o, p.points.$a);
            let dq = std::f64::consts::TAU / 360.0;
            let mut prev = m.pose(start).unwrap();
            let mut prev_speed = m.kinematics(start, 1.0, 0.0).unwrap();
            let first = prev;
            for k in 1..=360 {
                let q = start + dq * k as f64;
                let now = m.pose(q).unwrap();
                let speed = m.kinematics(q, 1.0, 0.0).unwrap();
                for n in $ty::POINT_NAMES {
                    let step = (now.point(n).unwrap().pos - prev.point(n).unwrap().pos).norm();
                    let (s0, s1) = (prev_speed.point(n).unwrap(), speed.point(n).unwrap());
                    let v = s0.vel.norm().max(s1.vel.norm());
                    let a = s0.acc.norm().max(s1.acc.norm());
                    let bound = 1.01 * (v * dq + a * dq * dq) + 1e-12;
                    assert!(step <= bound, "{n} jumps {step} > {bound} at step {k}");
                }
                prev = now;
                prev_speed = speed;
            }
            for n in $ty::POINT_NAMES {
                let back = (prev.point(n).unwrap().pos - first.point(n).unwrap().pos).norm();
                assert!(within(back, 1e-14), "{n} back to the start: {back:e}");
            }
        }
    };
}

continuity!(continuity_stephenson3, StephensonIII, P0, P1);
continuity!(continuity_stephenson2, Stephenson2, O, E);

/// A crank too long for the triad (its pin moved out to 2.2× its length): past the dead
/// points the pose is `NoAssembly`, never a panic or a NaN; where it assembles it is the
/// oracle's (continued from the drawing, up to where the oracle stops).
#[test]
fn past_a_dead_point_no_assembly() {
    let mut p = StephensonIIIParams::default();
    p.points.P1 = p.points.P0 + (p.points.P1 - p.points.P0) * 2.2;
    let m = StephensonIII::from_params(p.clone()).unwrap();
    let start = q0(p.points.P0, p.points.P1);
    let (mut ok, mut none) = (0, 0);
    for k in 0..=360 {
        let q = start + std::f64::consts::TAU * k as f64 / 360.0;
        match m.pose(q) {
            Ok(pose) => {
                ok += 1;
                for n in StephensonIII::POINT_NAMES {
                    let x = pose.point(n).unwrap().pos;
                    assert!(x.x.is_finite() && x.y.is_finite(), "{n} at step {k}");
                }
            }
            Err(e) => {
                assert_eq!(e, MechError::NoAssembly, "step {k}");
                none += 1;
            }
        }
        assert!(
            m.kinematics(q, 1.0, 0.0).is_ok() == m.pose(q).is_ok(),
            "step {k}"
        );
    }
    assert!(ok > 0 && none > 0, "{ok} assembled, {none} not");
}

/// Zero heap allocations in every solver of the triad machines (the elimination and its
/// fallback are on the stack).
#[test]
fn triad_solvers_do_not_allocate() {
    fn count<R>(f: impl FnOnce() -> R) -> (usize, R) {
        let before = counting::count();
        let r = f();
        (counting::count() - before, r)
    }
    macro_rules! no_alloc {
        ($ty:ident, $loads:ident) => {{
            let m = $ty::new();
            let mut loads = $loads::default();
            assert!(loads.set_by_name("load", &[3.0, -2.0]));
            assert!(loads.set_by_name("resist", &[0.5]));
            for q in [0.4, 2.5, 4.0] {
                let (n, p) = count(|| m.pose(q));
                p.unwrap();
                assert_eq!(n, 0, "pose allocated");
                let (n, mo) = count(|| m.kinematics(q, 3.0, -2.0));
                let mo = mo.unwrap();
                assert_eq!(n, 0, "kinematics allocated");
                let (n, f) = count(|| m.kinetostatics(&mo, &loads));
                f.unwrap();
                assert_eq!(n, 0, "kinetostatics allocated");
                let (n, d) = count(|| m.driver_action(&mo, &loads));
                d.unwrap();
                assert_eq!(n, 0, "driver_action allocated");
                let (n, r) = count(|| m.reduced(q));
                r.unwrap();
                assert_eq!(n, 0, "reduced allocated");
            }
        }};
    }
    no_alloc!(StephensonIII, StephensonIIILoads);
    no_alloc!(Stephenson2, Stephenson2Loads);
}
