//! The machines of the floor that `tests/common/mechanisms.rs` (the reference mechanisms,
//! generated from `tests/data/`) does not have, shared by `benches/floor.rs` and
//! `tests/floor.rs` through `#[path]`.

use mech::prelude::*;

mechanism! {
    /// Inverted slider-crank, the inversion of the offset slider-crank with its rod fixed
    /// (the oscillating-cylinder engine): the crank O2–A drives the rod A–P, whose slide
    /// line, 12 mm from the pin A, runs through a block (the cylinder) pivoted on the ground
    /// at O4. The guide is the link pinned to the crank, the slider the link pinned to the
    /// ground, the opposite of the quick-return's RPR group, and the slide line misses the
    /// pin (the general tangent construction). Crank 60 mm at 40°, |O2 O4| ≈ 282 mm.
    pub struct InvertedSliderCrank {
        gravity: (0.0, -9.81),
        ground { O2: (0.0, 0.0), O4: (0.28, 0.03) },
        link crank {
            points { O2, A: (0.04596266658713868, 0.03856725658119235) },
            mass: 0.9, inertia: 0.0008, cg: (0.014929915608062767, 0.014877419801031484),
        },
        link rod {
            points { A, P: (0.44547293212306205, 0.015425352350640463) },
            mass: 1.2, inertia: 0.019, cg: (0.20587205967990738, 0.030505867079227388),
        },
        link block {
            points { O4 },
            mass: 2.4, inertia: 0.011, cg: (0.24548593404553726, 0.037055441254166405),
        },
        joints {
            O2: revolute(ground, crank),
            A: revolute(crank, rod),
            slide: prismatic(rod, block) at O4 along (0.9961434918798252, -0.08773906533277448),
            O4: revolute(ground, block),
        },
        input: O2,
        loads {
            push: force on rod at P,
            resist: torque on block,
        },
    }
}
