// Mistake (names): a raw identifier as a link's name.
use mech::prelude::*;

mechanism! {
    /// Offset slider-crank of a single-cylinder engine.
    pub struct Engine {
        gravity: (0.0, -9.81),
        ground { O2: (0.0, 0.0) },
        link crank {
            points { O2, A: (0.038302, 0.032139) },
            mass: 1.2, inertia: 2.1e-3, cg: (0.0089, 0.0127),
        },
        link r#rod {
            points { A, B: (0.237285, 0.012) },
            mass: 2.4, inertia: 9.5e-3, cg: (0.1030, 0.0256),
        },
        link piston {
            points { B },
            mass: 1.7, cg: (0.237285, 0.012),
        },
        joints {
            O2: revolute(ground, crank),
            A: revolute(crank, r#rod),
            B: revolute(r#rod, piston),
            guide: prismatic(ground, piston) at B along (1.0, 0.0),
        },
        input: O2,
        loads {
            gas: force on piston at B,
            load: torque on crank,
        },
    }
}

fn main() {}
