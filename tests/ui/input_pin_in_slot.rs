// Mistake: the input is the pin-in-slot joint, which cannot be driven.
use mech::prelude::*;

mechanism! {
    /// Scotch yoke of a reciprocating pump.
    pub struct PumpYoke {
        ground { O2: (0.0, 0.0) },
        link crank {
            points { O2, A: (0.0386, 0.0460) },
            mass: 0.7, inertia: 3.1e-4, cg: (0.0111, 0.0194),
        },
        link yoke {
            points { Y: (0.2, 0.0) },
            mass: 1.9, inertia: 6.8e-3, cg: (0.13, 0.004),
        },
        joints {
            O2: revolute(ground, crank),
            guide: prismatic(ground, yoke) at Y along (1.0, 0.0),
            slot: pin_in_slot(yoke, crank) at A along (0.0, 1.0),
        },
        input: slot,
        loads {
            pressure: force on yoke at Y,
        },
    }
}

fn main() {}
