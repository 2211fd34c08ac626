// Mistake: Kutzbach's count hides an over-constrained sub-chain: four parallel revolutes
// (3 repeated equations) beside a pendulum on a ball joint (3 free turns) count G = -2 + 3
// = 1.
use mech::prelude::*;

mechanism! {
    /// A four-bar in space: its pins along z, A a ball joint, B a universal joint.
    pub struct FourBar3 {
        space,
        ground { O2: (0.0, 0.0, 0.0), O4: (0.3, 0.0, 0.0), P: (0.5, 0.5, 0.5) },
        link bob { points { P }, mass: 1.0 },
        link crank { points { O2, A: (0.02, 0.06, 0.0) }, mass: 0.4, cg: (0.012, 0.03, 0.0) },
        link coupler { points { A, B: (0.25, 0.16, 0.0) }, mass: 1.1, cg: (0.14, 0.13, 0.0) },
        link rocker { points { B, O4 }, mass: 0.7, cg: (0.27, 0.07, 0.0) },
        joints {
            O2: revolute(ground, crank) axis (0.0, 0.0, 1.0),
            A: revolute(crank, coupler) axis (0.0, 0.0, 1.0),
            B: revolute(coupler, rocker) axis (0.0, 0.0, 1.0),
            O4: revolute(rocker, ground) axis (0.0, 0.0, 1.0),
            P: spherical(ground, bob),
        },
        input: O2,
    }
}

fn main() {}
