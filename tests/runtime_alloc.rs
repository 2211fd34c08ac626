//! The run-time mechanism makes no heap allocation per call once its buffers have grown:
//! `solve_into`, `pose_into`, `kinematics_into`, `kinetostatics_into` and
//! `Machine::driver_actions` with caller-owned buffers, and
//! Zhukovski's route (`reduced`, `reduced_moment`, `acceleration`, the right-hand side of
//! the direct problem), for mechanisms of up to 8 links and joints. Proved with a counting
//! global allocator (one test in this file: the harness runs tests in threads).

use crate::counting;
use mech::prelude::*;
use mech_core::kernel::kinematics::{Level, LinkState};

// This thread's allocations are counted (`tests/common/counting.rs`, the global allocator
// of the `machines` test binary, installed in `tests/machines.rs`): the harness's own
// threads, and the other tests running in them, which may allocate meanwhile, do not count.

fn count<R>(f: impl FnOnce() -> R) -> (usize, R) {
    let before = counting::count();
    let r = f();
    (counting::count() - before, r)
}

const MECHANISMS: &str = include_str!("common/mechanisms.rs");

#[test]
fn no_allocation_per_call_with_caller_buffers() {
    // The counter works: a Vec allocates on this thread.
    let (n, _v) = count(|| vec![1.0f64; 4]);
    assert!(
        n >= 1,
        "the counting allocator saw {n} allocations for a Vec"
    );
    // A closed-form chain, a slider-crank, and a group solved by Newton (hydraulic lever).
    for name in ["FourBar", "SliderCrank", "HydraulicLever", "Watt2"] {
        let m = Mechanism::from_rust_source(MECHANISMS, name).unwrap();
        let q0 = m.model().reference_input(0);
        let mut loads = m.loads();
        for (k, l) in m.model().loads.iter().enumerate() {
            let v: &[f64] = match l {
                mech::model::Load::Force { .. } => &[10.0 + k as f64, -5.0],
                mech::model::Load::Torque { .. } => &[1.5],
            };
            assert!(loads.set_by_name(l.name(), v));
        }
        let mut states: Vec<LinkState> = Vec::new();
        let mut motion = m.kinematics(&[q0], &[1.0], &[0.0]).unwrap();
        let mut forces = m.kinetostatics(&motion, &loads).unwrap();
        let mut pose = m.pose(&[q0]).unwrap();
        let mut driver = [0.0];
        m.solve_into(&[q0], &[1.0], &[0.0], Level::Acceleration, &mut states)
            .unwrap();
        for k in 0..8 {
            let q = [q0 + 0.01 * k as f64];
            let (n, r) =
                count(|| m.solve_into(&q, &[2.0], &[-1.0], Level::Acceleration, &mut states));
            r.unwrap();
            assert_eq!(n, 0, "{name}: solve_into allocated");
            let (n, r) = count(|| m.kinematics_into(&q, &[2.0], &[-1.0], &mut motion));
            r.unwrap();
            assert_eq!(n, 0, "{name}: kinematics_into allocated");
            let (n, r) = count(|| m.kinetostatics_into(&motion, &loads, None, &mut forces));
            r.unwrap();
            assert_eq!(n, 0, "{name}: kinetostatics_into allocated");
            assert!(forces.driver[0].is_finite());
            let (n, r) = count(|| m.pose_into(&q, &mut pose));
            r.unwrap();
            assert_eq!(n, 0, "{name}: pose_into allocated");
            let (n, r) = count(|| m.driver_actions(&motion, &loads, &mut driver));
            r.unwrap();
            assert_eq!(n, 0, "{name}: driver_actions allocated");
            let (n, r) = count(|| {
                (
                    m.reduced(q[0]),
                    m.reduced_moment(q[0], &loads),
                    m.acceleration(q[0], 2.0, 0.5, &loads),
                )
            });
            let (a, b, c) = r;
            assert!(a.is_ok() && b.is_ok() && c.is_ok());
            assert_eq!(n, 0, "{name}: Zhukovski's route allocated");
        }
    }
}
