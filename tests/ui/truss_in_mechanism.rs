// Mistake: the crusher's frame bracket is modelled as a triangle of three bars (t1, t2, t3)
// with t1 and t2 both pinned to the ground: five pins on three bars, one too many, so the
// bracket is an over-constrained truss. The overall count still looks right (G = 1 for one
// input) only because the idle tensioner arm is free.
use mech::prelude::*;

mechanism! {
    /// Jaw crusher: crank-rocker drive, a frame bracket and a tensioner arm.
    pub struct Crusher {
        ground {
            O2: (0.0, 0.0), O4: (0.30, 0.04),
            G1: (0.50, 0.0), G2: (0.70, 0.0), T: (-0.20, 0.0),
        },
        link crank {
            points { O2, A: (0.04, 0.0693) },
            mass: 0.65, inertia: 5.2e-4, cg: (0.0118, 0.0324),
        },
        link jaw {
            points { A, B: (0.243, 0.2317) },
            mass: 6.5, inertia: 0.05, cg: (0.1182, 0.1716),
        },
        link rocker {
            points { O4, B },
            mass: 0.95, inertia: 0.0036, cg: (0.2809, 0.1324),
        },
        link t1 { points { G1, P: (0.55, 0.10), R: (0.60, 0.05) } },
        link t2 { points { G2, Q: (0.65, 0.10), R } },
        link t3 { points { P, Q } },
        link tensioner {
            points { T, E: (-0.20, 0.12) },
            mass: 0.4, inertia: 5.0e-4, cg: (-0.20, 0.06),
        },
        joints {
            O2: revolute(ground, crank),
            A: revolute(crank, jaw),
            B: revolute(jaw, rocker),
            O4: revolute(ground, rocker),
            G1: revolute(ground, t1),
            G2: revolute(ground, t2),
            P: revolute(t1, t3),
            Q: revolute(t3, t2),
            R: revolute(t1, t2),
            T: revolute(ground, tensioner),
        },
        input: O2,
    }
}

fn main() {}
