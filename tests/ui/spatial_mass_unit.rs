// Mistake: a mass written in millimetres.
use mech::prelude::*;

mechanism! {
    /// An RSSR: a crank turning about x drives a rocker turning about z through a rod with
    /// a ball joint at each end.
    pub struct Rssr {
        space,
        ground { O: (0.0, 0.0, 0.0), C: (250 mm, 120 mm, 80 mm) },
        link crank { points { O, A: (0.0, 0.05, 0.0) }, mass: 1.0, cg: (0.01, 0.025, 0.004),
                     inertia: (1e-3, 4e-4, 9e-4, 1e-4, -2e-5, 5e-5) },
        link rod { points { A, B: (0.25, 0.02, 0.08) }, mass: 0.5 mm, cg: (0.125, 0.035, 0.04),
                   inertia: (2e-4, 3e-3, 2.5e-3, 3e-5, 1e-5, -4e-5) },
        link rocker { points { C, B }, mass: 0.8, cg: (0.25, 0.07, 0.09),
                      inertia: (1.2e-3, 6e-4, 1.1e-3, 0.0, 2e-5, 0.0) },
        joints {
            O: revolute(ground, crank) axis (1.0, 0.0, 0.0),
            A: spherical(crank, rod),
            B: spherical(rod, rocker),
            C: revolute(ground, rocker) axis (0.0, 0.0, 1.0),
        },
        input: O,
    }
}

fn main() {}
