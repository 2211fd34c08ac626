// Mistake (magnitudes): a drawing in light-years (coordinates of 1e16 m).
use mech::prelude::*;

mechanism! {
    /// Offset slider-crank of a single-cylinder engine.
    pub struct Engine {
        gravity: (0.0, -9.81),
        ground { O2: (0.0, 0.0) },
        link crank {
            points { O2, A: (0.038302e18, 0.032139e18) },
            mass: 1.2, inertia: 2.1e-3, cg: (0.0089e18, 0.0127e18),
        },
        link rod {
            points { A, B: (0.237285e18, 0.012e18) },
            mass: 2.4, inertia: 9.5e-3, cg: (0.1030e18, 0.0256e18),
        },
        link piston {
            points { B },
            mass: 1.7, cg: (0.237285e18, 0.012e18),
        },
        joints {
            O2: revolute(ground, crank),
            A: revolute(crank, rod),
            B: revolute(rod, piston),
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
