// Mistake: asking a mechanism accepted with #[allow(redundant)] for its reactions. Its
// motor torque is determined (driver_action), its reactions are not.
use mech::prelude::*;

mechanism! {
    #[allow(redundant)]
    /// Coupled wheels: three equal parallel cranks and one coupling rod.
    pub struct CoupledWheels {
        ground { O1: (0.0, 0.0), O2: (0.8, 0.0), O3: (1.6, 0.0) },
        link wheel1 {
            points { O1, A1: (0.05, 0.0866) },
            mass: 120.0, inertia: 9.0, cg: (0.0, 0.0),
        },
        link wheel2 {
            points { O2, A2: (0.85, 0.0866) },
            mass: 120.0, inertia: 9.0, cg: (0.8, 0.0),
        },
        link wheel3 {
            points { O3, A3: (1.65, 0.0866) },
            mass: 120.0, inertia: 9.0, cg: (1.6, 0.0),
        },
        link rod {
            points { A1, A2, A3 },
            mass: 35.0, inertia: 7.5, cg: (0.85, 0.0866),
        },
        joints {
            O1: revolute(ground, wheel1),
            O2: revolute(ground, wheel2),
            O3: revolute(ground, wheel3),
            A1: revolute(wheel1, rod),
            A2: revolute(wheel2, rod),
            A3: revolute(wheel3, rod),
        },
        input: O1,
        loads {
            traction: torque on wheel3,
        },
    }
}

fn main() {
    let m = CoupledWheels::new();
    let motion = m.kinematics(0.3, 10.0, 0.0).unwrap();
    let loads = CoupledWheelsLoads { traction: -50.0 };
    let torque = m.driver_action(&motion, &loads).unwrap();
    let forces = m.kinetostatics(&motion, &loads);
    println!("{torque} {forces:?}");
}
