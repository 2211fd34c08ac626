// Mistake (dimensions): the rod (143 mm) cannot reach a guide 200 mm away
use mech::prelude::*;

mechanism! {
    /// Offset slider-crank by its lengths.
    pub struct Engine {
        consts { r: 43 mm, l: 143 mm, e: 6 mm },
        ground { O2: (0.0, 0.0) },
        link crank {
            points { O2, A: O2 + polar(r, 30 deg) },
            mass: 3.6 kg, inertia: 6.8e-3 kg_m2, cg: along(-5 mm),
        },
        link rod {
            points { A, B: circle_line(A, l, (0.0, 200 mm), 0 deg, forward) },
            mass: 580 g, inertia: 2.1e-3 kg_m2, cg: along(38 mm),
        },
        link piston {
            points { B },
            mass: 520 g, cg: B,
        },
        joints {
            O2: revolute(ground, crank),
            A: revolute(crank, rod),
            B: revolute(rod, piston),
            guide: prismatic(ground, piston) at B along (1.0, 0.0),
        },
        input: O2,
        loads { gas: force on piston at B },
    }
}

fn main() {}
