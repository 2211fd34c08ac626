// Mistake (gears): the two gears' centres are on no common link (g2 is pinned to the
// arm, g1 to the ground, and the arm does not hold O1).
use mech::prelude::*;

mechanism! {
    /// A gear on a swinging arm.
    pub struct Swing {
        ground { O1: (0.0, 0.0), OA: (0.0, -50 mm) },
        link g1 { points { O1 }, mass: 0.2, inertia: 4.0e-5, cg: (0.0, 0.0) },
        link arm { points { OA, O2: (80 mm, 0.0) }, mass: 0.5, inertia: 1.0e-3, cg: (40 mm, -25 mm) },
        link g2 { points { O2 }, mass: 1.1, inertia: 2.2e-3, cg: (80 mm, 0.0) },
        joints {
            O1: revolute(ground, g1),
            OA: revolute(ground, arm),
            O2: revolute(arm, g2),
            m12: gear(g1, g2) radii (20 mm, 60 mm),
        },
        inputs: [O1, OA],
    }
}

fn main() {}
