// Mistake (cams): the follower slides on an arm, not on the ground the cam is pinned to.
use mech::prelude::*;

mechanism! {
    /// A cam lifting a follower guided by a swinging arm.
    pub struct ValveTrain {
        ground { O: (0.0, 0.0), A: (100 mm, 0.0) },
        link cam { points { O }, mass: 0.5, inertia: 2.0e-4, cg: (0.0, 0.0) },
        link arm { points { A, G: (0.0, 80 mm) }, mass: 0.1, inertia: 1.0e-4, cg: (50 mm, 40 mm) },
        link follower { points { P: (0.0, 50 mm) }, mass: 0.08, cg: (0.0, 50 mm) },
        joints {
            O: revolute(ground, cam),
            A: revolute(ground, arm),
            slide: prismatic(arm, follower) at P along (0.0, 1.0),
            lobe: cam(cam, follower) base_radius 40 mm roller 10 mm
                law [dwell 90 deg, cycloidal 90 deg rise 10 mm, dwell 60 deg, poly345 120 deg fall 10 mm],
        },
        inputs: [O, A],
    }
}

fn main() {}
