//! Many configurations per call (docs/batch.md): a crank-rocker's Zhukovski reduction, its
//! direct problem and its points at a thousand crank angles, three calls in all.
//!
//! ```text
//! cargo run --release --example batch
//! ```
//!
//! One of the thousand angles is given as NaN on purpose: its slots come back NaN and its
//! index is in the `BatchErrors` of each call, the other 999 are unaffected. The example
//! prints every 125th configuration (the 500th is the NaN one): the crank angle, I* and
//! dI*/dq, q̈ under a 2 N·m driver at 10 rad/s, and the coupler point P.

use mech::prelude::*;

mechanism! {
    /// A crank-rocker four-bar with a coupler point P (the reference four-bar of the tests).
    pub struct FourBar {
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
        loads {
            tool: force on coupler at P,
            resist: torque on rocker,
        },
    }
}

/// The configurations of the example.
pub const N: usize = 1000;

/// The index given NaN on purpose.
pub const BROKEN: usize = 500;

/// What the three batched calls return: per configuration q, I*, dI*/dq, q̈, and the
/// points (x, y of O2, O4, A, B, P), with the failed indices of each call.
pub struct Batch {
    pub q: Vec<f64>,
    pub inertia: Vec<f64>,
    pub derivative: Vec<f64>,
    pub acceleration: Vec<f64>,
    pub points: Vec<f64>,
    pub failed: [Vec<usize>; 3],
}

/// The three calls on `m` at N crank angles over a turn (one NaN), q̇ = 10 rad/s, a 2 N·m
/// driver, the tool force (80, −60) N and a 2 N·m resisting torque.
pub fn run(m: &FourBar) -> Batch {
    let mut q: Vec<f64> = (0..N)
        .map(|i| i as f64 * std::f64::consts::TAU / N as f64)
        .collect();
    q[BROKEN] = f64::NAN;
    let (qd, driver) = (vec![10.0; N], vec![2.0; N]);
    let mut loads = FourBarLoads::default();
    loads.tool = Vector2::new(80.0, -60.0);
    loads.resist = 2.0;

    let (mut inertia, mut derivative) = (vec![0.0; N], vec![0.0; N]);
    let e1 = m.reduced_many(&q, &mut inertia, &mut derivative);
    let mut acceleration = vec![0.0; N];
    let e2 = m.acceleration_many(&q, &qd, &driver, &loads, &mut acceleration);
    let mut points = vec![0.0; 2 * FourBar::POINT_NAMES.len() * N];
    let e3 = m.points_many(&q, &mut points);
    Batch {
        q,
        inertia,
        derivative,
        acceleration,
        points,
        failed: [e1, e2, e3].map(|e| e.indices().to_vec()),
    }
}

fn main() {
    let m = FourBar::new();
    let b = run(&m);
    println!("{} configurations, failed: {:?}", N, b.failed);
    println!("   q (deg)   I* (kg·m²)  dI*/dq (kg·m²/rad)  q̈ (rad/s²)     P x (m)     P y (m)");
    let np = FourBar::POINT_NAMES.len();
    for i in (0..N).step_by(125) {
        let p = &b.points[2 * np * i + 8..2 * np * i + 10];
        println!(
            "{:>10.2} {:>12.6} {:>19.6} {:>12.3} {:>11.5} {:>11.5}",
            b.q[i].to_degrees(),
            b.inertia[i],
            b.derivative[i],
            b.acceleration[i],
            p[0],
            p[1]
        );
    }
}
