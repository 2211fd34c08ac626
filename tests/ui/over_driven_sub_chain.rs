// Mistake: the second motor, meant for the free pendulum arm, was put on the four-bar's
// rocker pivot: the count G = 2 matches the two inputs, but the four-bar is driven twice.
use mech::prelude::*;

mechanism! {
    /// Flap drive (crank-rocker) and an independently driven pendulum arm.
    pub struct TwinDrive {
        ground { O2: (0.0, 0.0), O4: (0.30, 0.04), P0: (-0.25, 0.0) },
        link crank {
            points { O2, A: (0.04, 0.0693) },
            mass: 0.65, inertia: 5.2e-4, cg: (0.0118, 0.0324),
        },
        link coupler {
            points { A, B: (0.243, 0.2317) },
            mass: 1.45, inertia: 0.0112, cg: (0.1182, 0.1716),
        },
        link rocker {
            points { O4, B },
            mass: 0.95, inertia: 0.0036, cg: (0.2809, 0.1324),
        },
        link arm {
            points { P0, P1: (-0.25, -0.15) },
            mass: 0.3, inertia: 6.0e-4, cg: (-0.25, -0.075),
        },
        joints {
            O2: revolute(ground, crank),
            A: revolute(crank, coupler),
            B: revolute(coupler, rocker),
            O4: revolute(ground, rocker),
            P0: revolute(ground, arm),
        },
        inputs: [O2, O4],
    }
}

fn main() {}
