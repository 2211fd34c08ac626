// Mistake (cams): a uniform rise between dwells: the velocity jumps (infinite acceleration).
use mech::prelude::*;

mechanism! {
    /// A cam lifting a roller follower.
    pub struct ValveTrain {
        ground { O: (0.0, 0.0) },
        link cam { points { O }, mass: 0.5, inertia: 2.0e-4, cg: (0.0, 0.0) },
        link follower { points { P: (0.0, 50 mm) }, mass: 0.08, cg: (0.0, 50 mm) },
        joints {
            O: revolute(ground, cam),
            slide: prismatic(ground, follower) at P along (0.0, 1.0),
            lobe: cam(cam, follower) base_radius 40 mm roller 10 mm
                law [dwell 90 deg, uniform 90 deg rise 10 mm, dwell 60 deg, poly345 120 deg fall 10 mm],
        },
        input: O,
    }
}

fn main() {}
