// Mistake (force elements): a damper from the coupler to itself.
use mech::prelude::*;

mechanism! {
    /// A four-bar with a return spring.
    pub struct Sprung {
        ground { O2: (0.0, 0.0), O4: (0.3, 0.0), C: (0.05, 0.25) },
        link crank { points { O2, A: (0.0, 0.1) }, mass: 0.8, inertia: 1e-3, cg: (0.0, 0.05) },
        link coupler { points { A, B: (0.28, 0.22), P: (0.1, 0.2) }, mass: 1.5, inertia: 9e-3, cg: (0.14, 0.17) },
        link rocker { points { B, O4 }, mass: 1.1, inertia: 4e-3, cg: (0.29, 0.11) },
        joints {
            O2: revolute(ground, crank),
            A: revolute(crank, coupler),
            B: revolute(coupler, rocker),
            O4: revolute(rocker, ground),
        },
        input: O2,
        elements {
            c1: damper(coupler at A, coupler at P) damping 40 N_s_per_m,
        },
    }
}

fn main() {}
