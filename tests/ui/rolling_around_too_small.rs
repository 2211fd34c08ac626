// Mistake (rolling): the circle the wheel rolls around has a negative radius (|C D| < r).
use mech::prelude::*;

mechanism! {
    /// A crank pushing a wheel along the floor.
    pub struct WheelRod {
        ground { O2: (0.0, 0.0), D: (250 mm, -50 mm) },
        link crank { points { O2, A: (40 mm, 30 mm) }, mass: 0.8, inertia: 6.0e-4, cg: (20 mm, 15 mm) },
        link rod { points { A, C: (250 mm, -20 mm) }, mass: 1.1, inertia: 5.0e-3, cg: (140 mm, 10 mm) },
        link wheel { points { C }, mass: 1.6, inertia: 2.2e-3, cg: (250 mm, -20 mm) },
        joints {
            O2: revolute(ground, crank),
            A: revolute(crank, rod),
            C: revolute(rod, wheel),
            roll: rolling(ground, wheel) at C radius 50 mm around D,
        },
        input: O2,
    }
}

fn main() {}
