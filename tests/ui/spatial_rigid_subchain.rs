// Mistake: a bracket of two links, each pinned to the frame by a revolute and joined to the
// other by a ball joint, is rigid with one equation too many (13 for the 12 DOF of two
// links); a hinged flap that no input drives makes up the freedom, so Kutzbach's count
// (G = 2, one of them the rod's idle spin) matches the one input.
use mech::prelude::*;

mechanism! {
    /// An RSSR (a crank turning about x drives a rocker turning about z through a rod with
    /// a ball joint at each end) on a frame carrying a two-piece bracket and a flap.
    pub struct Rssr {
        space,
        ground { O: (0.0, 0.0, 0.0), C: (250 mm, 120 mm, 80 mm), G1: (0.5, 0.0, 0.0),
                 G2: (0.7, 0.0, 0.0), D: (-0.3, 0.0, 0.0) },
        link crank { points { O, A: (0.0, 0.05, 0.0) }, mass: 1.0, cg: (0.01, 0.025, 0.004),
                     inertia: (1e-3, 4e-4, 9e-4, 1e-4, -2e-5, 5e-5) },
        link rod { points { A, B: (0.25, 0.02, 0.08) }, mass: 0.5, cg: (0.125, 0.035, 0.04),
                   inertia: (2e-4, 3e-3, 2.5e-3, 3e-5, 1e-5, -4e-5) },
        link rocker { points { C, B }, mass: 0.8, cg: (0.25, 0.07, 0.09),
                      inertia: (1.2e-3, 6e-4, 1.1e-3, 0.0, 2e-5, 0.0) },
        link bracket1 { points { G1, S: (0.6, 0.1, 0.05) }, mass: 0.3, cg: (0.55, 0.05, 0.025) },
        link bracket2 { points { G2, S }, mass: 0.3, cg: (0.65, 0.05, 0.025) },
        link flap { points { D, E: (-0.3, 0.0, -0.2) }, mass: 0.2, cg: (-0.3, 0.0, -0.1) },
        joints {
            O: revolute(ground, crank) axis (1.0, 0.0, 0.0),
            A: spherical(crank, rod),
            B: spherical(rod, rocker),
            C: revolute(ground, rocker) axis (0.0, 0.0, 1.0),
            G1: revolute(ground, bracket1) axis (0.0, 1.0, 0.0),
            G2: revolute(ground, bracket2) axis (0.0, 0.0, 1.0),
            S: spherical(bracket1, bracket2),
            D: revolute(ground, flap) axis (1.0, 0.0, 0.0),
        },
        input: O,
    }
}

fn main() {}
