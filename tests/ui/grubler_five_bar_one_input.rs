// Mistake: a five-bar (two DOF) with one input: the second crank is left free.
use mech::prelude::*;

mechanism! {
    /// Two-crank five-bar of a plotter.
    pub struct Plotter {
        ground { O1: (0.0, 0.0), O5: (0.2, 0.0) },
        link crank1 {
            points { O1, A: (-0.0342, 0.0940) },
            mass: 0.55, inertia: 6.0e-4, cg: (-0.0201, 0.0406),
        },
        link link2 {
            points { A, C: (0.1188, 0.2789) },
            mass: 0.8, inertia: 4.2e-3, cg: (0.0406, 0.1749),
        },
        link link3 {
            points { B: (0.2465, 0.0997), C },
            mass: 0.75, inertia: 3.4e-3, cg: (0.1844, 0.1782),
        },
        link crank4 {
            points { O5, B },
            mass: 0.6, inertia: 7.0e-4, cg: (0.2248, 0.0436),
        },
        joints {
            O1: revolute(ground, crank1),
            A: revolute(crank1, link2),
            C: revolute(link2, link3),
            B: revolute(link3, crank4),
            O5: revolute(ground, crank4),
        },
        input: O1,
        loads {
            pen: force on link2 at C,
        },
    }
}

fn main() {}
