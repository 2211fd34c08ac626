// Mistake (cams): a 45 mm roller on a 5 mm base circle cannot follow this law (undercut).
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
            lobe: cam(cam, follower) base_radius 5 mm roller 45 mm
                law [dwell 90 deg, cycloidal 30 deg rise 20 mm, dwell 60 deg, poly345 180 deg fall 20 mm],
        },
        input: O,
    }
}

fn main() {}
