// Mistake (syntax): `hinge` is not a joint kind (it is `revolute`).
use mech::prelude::*;

mechanism! {
    /// Crank-rocker four-bar driving a packaging flap.
    pub struct FlapDrive {
        ground { O2: (0.0, 0.0), O4: (0.30, 0.04) },
        link crank { points { O2, A: (0.04, 0.0693) }, mass: 0.65, inertia: 5.2e-4, cg: (0.0118, 0.0324) },
        link coupler { points { A, B: (0.243, 0.2317) }, mass: 1.45, inertia: 0.0112, cg: (0.1182, 0.1716) },
        link rocker { points { O4, B }, mass: 0.95, inertia: 0.0036, cg: (0.2809, 0.1324) },
        joints {
            O2: revolute(ground, crank),
            A: revolute(crank, coupler),
            B: hinge(coupler, rocker),
            O4: revolute(ground, rocker),
        },
        input: O2,
    }
}

fn main() {}
