//! Kinematics beyond the reference tables: velocities and accelerations against central
//! differences of `pose`, the input-rate scaling law, and continuity on the drawing's
//! assembly branch over a whole crank revolution.

use crate::measure::{within, within_at};
use crate::mechanisms;

use mechanisms::*;

/// v = dP/dq at q̇ = 1 and a = d²P/dq² at q̇ = 1, q̈ = 0 against central differences of
/// `pose` (truncation O(h²), rounding O(ε/h) and O(ε/h²)); and, for any (q̇, q̈),
/// v = v₁ q̇ and a = a₁ q̇² + v₁ q̈ (exact up to rounding).
macro_rules! differences {
    ($test:ident, $ty:ident, $q:expr, $min:expr) => {
        #[test]
        fn $test() {
            let m = $ty::new();
            let (h1, h2) = (1e-6, 1e-4);
            let mut solved = 0;
            for k in 0..12 {
                let q = $q + 0.37 * k as f64;
                // Past a limit of the input's range there is no assembly: skipped, counted.
                let Ok(unit) = m.kinematics(q, 1.0, 0.0) else {
                    continue;
                };
                solved += 1;
                let (pp, pm) = (m.pose(q + h1).unwrap(), m.pose(q - h1).unwrap());
                let (app, amm, a0) = (
                    m.pose(q + h2).unwrap(),
                    m.pose(q - h2).unwrap(),
                    m.pose(q).unwrap(),
                );
                let scale = $ty::POINT_NAMES
                    .iter()
                    .fold(1e-3f64, |s, n| s.max(unit.point(n).unwrap().pos.norm()));
                let general = m.kinematics(q, 2.5, -4.0).unwrap();
                for n in $ty::POINT_NAMES {
                    let u = unit.point(n).unwrap();
                    let fd_v = (pp.point(n).unwrap().pos - pm.point(n).unwrap().pos) / (2.0 * h1);
                    let fd_a = (app.point(n).unwrap().pos - 2.0 * a0.point(n).unwrap().pos
                        + amm.point(n).unwrap().pos)
                        / (h2 * h2);
                    assert!(
                        within_at("vel by differences", (u.vel - fd_v).norm(), 1e-8 * scale), // measured worst 2.8e-10 (be05608); 100×
                        "{} {n} q={q}: vel {:?} vs {:?}",
                        stringify!($ty),
                        u.vel,
                        fd_v
                    );
                    assert!(
                        within_at("acc by differences", (u.acc - fd_a).norm(), 1e-5 * scale), // measured worst 1.2e-7 (be05608); 100×
                        "{} {n} q={q}: acc {:?} vs {:?}",
                        stringify!($ty),
                        u.acc,
                        fd_a
                    );
                    let g = general.point(n).unwrap();
                    // measured worst 9.3e-17 (be05608); 100×
                    assert!(within_at(
                        "vel scaling",
                        (g.vel - u.vel * 2.5).norm(),
                        5e-15 * scale * 2.5
                    ));
                    // measured worst 1.6e-16 (be05608); 100×
                    assert!(within_at(
                        "acc scaling",
                        (g.acc - (u.acc * 6.25 - u.vel * 4.0)).norm(),
                        1e-14 * scale * 10.0
                    ));
                }
                for n in $ty::LINK_NAMES {
                    let fd_w = angle_diff(pp.link(n).unwrap().angle, pm.link(n).unwrap().angle)
                        / (2.0 * h1);
                    assert!(
                        within_at(
                            "omega by differences",
                            (unit.link(n).unwrap().omega - fd_w).abs(),
                            5e-8 * unit.link(n).unwrap().omega.abs().max(1.0)
                        ) // measured worst 6.7e-10 (be05608); 100×
                    );
                }
            }
            // All 12 assemble for every example (be05608): a configuration lost to a wrong
            // `NoAssembly` fails here rather than going unchecked.
            println!(
                "COUNT {}: {solved} of 12 configurations assemble",
                stringify!($ty)
            );
            assert!(
                solved >= $min,
                "{}: only {solved} of 12 configurations assemble",
                stringify!($ty)
            );
        }
    };
}

fn angle_diff(a: f64, b: f64) -> f64 {
    let d = (a - b).rem_euclid(std::f64::consts::TAU);
    if d > std::f64::consts::PI {
        d - std::f64::consts::TAU
    } else {
        d
    }
}

differences!(differences_four_bar, FourBar, 0.1, 12);
differences!(differences_slider_crank, SliderCrank, 0.1, 12);
differences!(differences_quick_return, QuickReturn, 0.1, 12);
differences!(differences_watt2, Watt2, 0.1, 12);
differences!(differences_stephenson3, Stephenson3, 0.1, 12);
differences!(differences_scotch_yoke, ScotchYoke, 0.1, 12);

#[test]
fn differences_hydraulic_lever() {
    let m = HydraulicLever::new();
    let h = 1e-6;
    for k in 0..9 {
        let q = -0.08 + 0.02 * k as f64;
        let u = m.kinematics(q, 1.0, 0.0).unwrap();
        let (pp, pm) = (m.pose(q + h).unwrap(), m.pose(q - h).unwrap());
        for n in HydraulicLever::POINT_NAMES {
            let fd = (pp.point(n).unwrap().pos - pm.point(n).unwrap().pos) / (2.0 * h);
            // measured worst 1.5e-10 (be05608); 100×
            assert!(
                within((u.point(n).unwrap().vel - fd).norm(), 1e-8),
                "{n} at q={q}"
            );
        }
    }
}

/// A whole revolution of the crank in 1° steps stays on the drawing's branch: every
/// point moves by no more than its speed and acceleration allow over the step (a jump
/// to the other assembly branch would move the coupler's points by centimetres), and
/// the mechanism comes back to where it started.
macro_rules! continuity {
    ($test:ident, $ty:ident) => {
        #[test]
        fn $test() {
            let m = $ty::new();
            let q0 = {
                let p = m.params();
                let a = p.points.A - p.points.O2;
                a.y.atan2(a.x)
            };
            let dq = std::f64::consts::TAU / 360.0;
            let mut prev = m.pose(q0).unwrap();
            let mut prev_speed = m.kinematics(q0, 1.0, 0.0).unwrap();
            let first = prev;
            for k in 1..=360 {
                let q = q0 + dq * k as f64;
                let now = m.pose(q).unwrap();
                let speed = m.kinematics(q, 1.0, 0.0).unwrap();
                for n in $ty::POINT_NAMES {
                    let step = (now.point(n).unwrap().pos - prev.point(n).unwrap().pos).norm();
                    let (s0, s1) = (prev_speed.point(n).unwrap(), speed.point(n).unwrap());
                    let v = s0.vel.norm().max(s1.vel.norm());
                    let a = s0.acc.norm().max(s1.acc.norm());
                    let bound = 1.01 * (v * dq + a * dq * dq) + 1e-12;
                    assert!(
                        step <= bound,
                        "{} {n} jumps {step} > {bound} at step {k}",
                        stringify!($ty)
                    );
                }
                prev = now;
                prev_speed = speed;
            }
            for n in $ty::POINT_NAMES {
                // measured worst 2.8e-17 (be05608); 100×
                assert!(within_at(
                    "back to the start",
                    (prev.point(n).unwrap().pos - first.point(n).unwrap().pos).norm(),
                    2e-15
                ));
            }
        }
    };
}

continuity!(continuity_crank_rocker, FourBar);
continuity!(continuity_watt2, Watt2);

/// Errors instead of panics or NaN: a non-finite input, and a four-bar driven where it
/// cannot be assembled.
#[test]
fn bad_inputs_are_errors() {
    use mech::prelude::MechError;
    let m = FourBar::new();
    assert!(matches!(m.pose(f64::NAN), Err(MechError::InvalidInput(_))));
    assert!(matches!(
        m.kinematics(0.0, f64::INFINITY, 0.0),
        Err(MechError::InvalidInput(_))
    ));
    // A crank four times as long: the loop cannot close for some crank angles.
    let mut p = m.params().clone();
    p.points.A = p.points.O2 + (p.points.A - p.points.O2) * 4.0;
    let long = FourBar::from_params(p).unwrap();
    let failures = (0..36)
        .filter(|k| matches!(long.pose(0.1745 * *k as f64), Err(MechError::NoAssembly)))
        .count();
    assert!(
        failures > 0,
        "a non-Grashof four-bar must fail to assemble somewhere"
    );
    for k in 0..36 {
        if let Ok(p) = long.pose(0.1745 * k as f64) {
            assert!(p.points.B.pos.iter().all(|x| x.is_finite()));
        }
    }
}
