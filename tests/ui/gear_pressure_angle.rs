// Mistake (gears): a pressure angle of 50° is not a gear.
use mech::prelude::*;

mechanism! {
    /// A two-stage gear reducer.
    pub struct Reducer {
        ground { O1: (0.0, 0.0), O2: (80 mm, 0.0), O4: (80 mm, 100 mm) },
        link g1 { points { O1 }, mass: 0.2, inertia: 4.0e-5, cg: (0.0, 0.0) },
        link cluster { points { O2 }, mass: 1.1, inertia: 2.2e-3, cg: (80 mm, 0.0) },
        link g4 { points { O4 }, mass: 2.0, inertia: 6.0e-3, cg: (80 mm, 100 mm) },
        joints {
            O1: revolute(ground, g1),
            O2: revolute(ground, cluster),
            O4: revolute(ground, g4),
            m12: gear(g1, cluster) radii (20 mm, 60 mm) pressure_angle 50 deg,
            m34: gear(cluster, g4) radii (25 mm, 75 mm),
        },
        input: O1,
    }
}

fn main() {}
