// Mistake (cams): the rocker's roller centre off the prime circle in the drawing.
use mech::prelude::*;

mechanism! {
    /// A cam swinging a roller rocker pinned to the ground at A.
    pub struct RockerCam {
        ground { O: (0.0, 0.0), A: (60 mm, 50 mm) },
        link cam { points { O }, mass: 0.5, inertia: 2.0e-4, cg: (0.0, 0.0) },
        link rocker { points { A, P: (0.0, 38 mm) }, mass: 0.15, inertia: 6.0e-5, cg: (40 mm, 46 mm) },
        joints {
            O: revolute(ground, cam),
            A: revolute(ground, rocker),
            lobe: cam(cam, rocker) at P base_radius 32 mm roller 8 mm
                law [dwell 90 deg, cycloidal 90 deg rise 15 deg, dwell 60 deg, poly345 120 deg fall 15 deg],
        },
        input: O,
    }
}

fn main() {}
