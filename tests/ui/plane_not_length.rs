// Mistake (engines): a plane that is not a length.
use mech::prelude::*;

mechanism! {
    /// A slider-crank.
    pub struct Engine {
        ground { O2: (0.0, 0.0) },
        link crank {
            points { O2, A: (0.05, 0.0) },
            mass: 1.2, inertia: 2.1e-3, cg: (0.01, 0.0),
            counterweight: (0.5 kg, at (-0.02, 0.0), plane: 40 deg),
        },
        link rod {
            points { A, B: (0.25, 0.0) },
            mass: 0.9, inertia: 4.4e-3, cg: (0.1, 0.0),
        },
        link piston {
            points { B },
            mass: 0.7, cg: B,
        },
        joints {
            O2: revolute(ground, crank),
            A: revolute(crank, rod),
            B: revolute(rod, piston),
            guide: prismatic(ground, piston) at B along (1.0, 0.0),
        },
        input: O2,
    }
}

fn main() {}
