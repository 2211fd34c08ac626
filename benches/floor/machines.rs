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

mechanism! {
    /// Geared slider-crank: the pinion (pitch radius 25 mm, centre O1) is the input; it
    /// drives the gear (75 mm, centre O2) that carries the crank O2–A, 3:1 down, through a
    /// 20° external gear pair whose line of centres O1→O2 is slanted (100 mm, at 36.87°);
    /// the rod A–B drives the piston B along a guide tilted by 5.7° (`along (1.0, 0.1)`),
    /// 10.9 mm off O2. A meshing group of one link (the gear, `mesh` and its pin O2) then
    /// an RRP dyad; the mesh's radii and pressure angle are those of the hand-written
    /// `GearedSliderCrankHand` (`benches/floor/hand_geared_slider_crank.rs`).
    pub struct GearedSliderCrank {
        gravity: (0.0, -9.81),
        ground { O1: (0.0, 0.0), O2: (0.08, 0.06) },
        link pinion {
            points { O1 },
            mass: 0.3, inertia: 0.0001, cg: (0.0, 0.0),
        },
        link crank {
            points { O2, A: (0.11897114317029974, 0.0825) },
            mass: 1.5, inertia: 0.003, cg: (0.09, 0.064),
        },
        link rod {
            points { A, B: (0.27, 0.09) },
            mass: 0.9, inertia: 0.0025, cg: (0.2, 0.087),
        },
        link piston {
            points { B },
            mass: 0.8, cg: (0.275, 0.088),
        },
        joints {
            O1: revolute(ground, pinion),
            O2: revolute(ground, crank),
            A: revolute(crank, rod),
            B: revolute(rod, piston),
            guide: prismatic(ground, piston) at B along (1.0, 0.1),
            mesh: gear(pinion, crank) radii (25 mm, 75 mm) pressure_angle 20 deg,
        },
        input: O1,
        loads {
            gas: force on piston at B,
            shaft: torque on crank,
        },
    }
}

mechanism! {
    /// Disc cam with an offset translating roller follower: the cam (the input, turning
    /// about O, its cg off the centre) lifts the follower 15 mm by a cycloidal rise over
    /// 120°, holds it 60°, lets it down by a cycloidal fall over 90° and rests 90° (the
    /// floor's q = 0.7 rad is in the rise);
    /// base circle 40 mm, roller 10 mm, the follower's axis (vertical) 10 mm off O, its cg
    /// and its top T, where it is loaded, off the axis. A cam group of one link (the follower, its slide and the cam pair); the
    /// law, base circle and roller are those of the hand-written `RollerCamHand`
    /// (`benches/floor/hand_roller_cam.rs`).
    pub struct RollerCam {
        gravity: (0.0, -9.81),
        ground { O: (0.0, 0.0) },
        link cam {
            points { O },
            mass: 1.2, inertia: 0.0008, cg: (0.002, -0.001),
        },
        link follower {
            points { P: (0.01, 0.04898979485566356), T: (0.025, 0.11) },
            mass: 0.35, inertia: 0.0002, cg: (0.012, 0.09),
        },
        joints {
            O: revolute(ground, cam),
            slide: prismatic(ground, follower) at P along (0.0, 1.0),
            lobe: cam(cam, follower) base_radius 40 mm roller 10 mm
                law [cycloidal 120 deg rise 15 mm, dwell 60 deg, cycloidal 90 deg fall 15 mm,
                     dwell 90 deg],
        },
        input: O,
        loads {
            push: force on follower at T,
            drag: torque on cam,
        },
    }
}

mechanism! {
    /// Crank, rod and a wheel rolling on the ground: the crank O2–A drives the rod A–C,
    /// pinned at C to the centre of a 30 mm wheel that rolls without slipping on a straight
    /// track tilted by 4.6° (`along (1.0, 0.08)`, the track under the wheel), its cg 2 mm
    /// off the centre (an unbalanced wheel), pulled at C and braked. A rolling group: the
    /// rod and the wheel as a crank–rod–wheel dyad (an RRP dyad whose slider turns by
    /// −s/r as it travels s).
    pub struct CrankRodWheel {
        gravity: (0.0, -9.81),
        ground { O2: (0.0, 0.0) },
        link crank {
            points { O2, A: (0.025711504387461575, 0.030641777724759120) },
            mass: 0.6, inertia: 0.0004, cg: (0.012, 0.01),
        },
        link rod {
            points { A, C: (0.2, 0.05) },
            mass: 0.7, inertia: 0.002, cg: (0.11, 0.042),
        },
        link wheel {
            points { C },
            mass: 1.1, inertia: 0.0006, cg: (0.202, 0.0505),
        },
        joints {
            O2: revolute(ground, crank),
            A: revolute(crank, rod),
            C: revolute(rod, wheel),
            roll: rolling(ground, wheel) at C radius 30 mm along (1.0, 0.08),
        },
        input: O2,
        loads {
            pull: force on wheel at C,
            brake: torque on wheel,
        },
    }
}

mechanism! {
    /// Scotch yoke with an explicit block: the crank O2–A (50 mm at 35°) carries the block
    /// pinned at A, which slides in the yoke's slot (slanted 5.7° off the vertical,
    /// `along (0.1, 1.0)`); the yoke slides on a horizontal ground guide at Y, 12 mm above
    /// O2, and is loaded at its end T. The block and the yoke are an RPP dyad (the pin A,
    /// the slot, the guide): neither turns, the yoke's place is where the slot's line
    /// through A meets the guide's. The block's cg is off A and it carries a friction couple
    /// of the slot (the torque load), which only the slot's and the guide's moments take.
    pub struct BlockScotchYoke {
        gravity: (0.0, -9.81),
        ground { O2: (0.0, 0.0) },
        link crank {
            points { O2, A: (0.041, 0.029) },
            mass: 0.7, inertia: 0.00031, cg: (0.012, 0.016),
        },
        link block {
            points { A },
            mass: 0.2, inertia: 0.00002, cg: (0.044, 0.027),
        },
        link yoke {
            points { Y: (0.16, 0.012), T: (0.26, 0.02) },
            mass: 1.7, inertia: 0.0075, cg: (0.12, 0.018),
        },
        joints {
            O2: revolute(ground, crank),
            A: revolute(crank, block),
            slot: prismatic(yoke, block) at A along (0.1, 1.0),
            guide: prismatic(ground, yoke) at Y along (1.0, 0.0),
        },
        input: O2,
        loads {
            resist: force on yoke at T,
            friction: torque on block,
        },
    }
}

mechanism! {
    /// Slotted crank driving a ram: the crank O2–E (θ₂ = 68.7° in the drawing) has a slot
    /// along (1.0, 3.0), 2.8° off its line O2→E and 7.9 mm off O2, in which the block
    /// slides; the block is pinned at B to the ram, which slides on a ground guide tilted by
    /// −5.7° (`along (1.0, -0.1)`), 89 mm off O2, and is loaded at its tool point P. The
    /// block and the ram are a PRP dyad (the slot, the pin B, the guide): the block turns
    /// with the crank, the ram does not, B is where the slot's line meets the guide's. The
    /// crank swings, it cannot turn: the ram runs to infinity where the slot is parallel to
    /// the guide (q = −0.15 and 2.99 rad); q = 0.45…2.4 rad is a working stroke of 0.26 m.
    pub struct SlottedCrankRam {
        gravity: (0.0, -9.81),
        ground { O2: (0.0, 0.0) },
        link crank {
            points { O2, E: (0.058, 0.149) },
            mass: 1.1, inertia: 0.0035, cg: (0.03, 0.06),
        },
        link block {
            points { B: (0.037, 0.086) },
            mass: 0.3, inertia: 0.00006, cg: (0.039, 0.0885),
        },
        link ram {
            points { B, P: (0.21, 0.095) },
            mass: 2.2, inertia: 0.018, cg: (0.13, 0.085),
        },
        joints {
            O2: revolute(ground, crank),
            slot: prismatic(crank, block) at B along (1.0, 3.0),
            B: revolute(block, ram),
            guide: prismatic(ground, ram) at B along (1.0, -0.1),
        },
        input: O2,
        loads {
            push: force on ram at P,
            resist: torque on block,
        },
    }
}

mechanism! {
    /// Planetary reducer driven by its sun: the sun (pitch radius 20 mm, the input) turns
    /// about O and meshes with the planet (25 mm), pinned at P to the arm 45 mm out (at 30°
    /// in the drawing), which rolls inside the fixed ring (70 mm, internal teeth, the
    /// ground): the arm turns at r_s/(r_s + r_r) = 2/9 of the sun, the planet at −2/5. The
    /// sun–planet mesh has the default 20° pressure angle, the planet–ring mesh 25°. The arm
    /// and the planet are one gear-train group (Willis' relations of both meshes solved
    /// together); every cg is off its centre (the sun's and the planet's by a fraction of a
    /// millimetre), the arm carries a lever end T, pulled, and a brake. The radii and the
    /// pressure angles are those of the hand-written `PlanetaryHand`
    /// (`benches/floor/hand_planetary.rs`).
    pub struct Planetary {
        gravity: (0.0, -9.81),
        ground { O: (0.0, 0.0) },
        link sun {
            points { O },
            mass: 0.35, inertia: 0.00006, cg: (0.0005, -0.0003),
        },
        link arm {
            points { O, P: (0.03897114317029974, 0.0225), T: (-0.03, 0.05) },
            mass: 1.1, inertia: 0.0015, cg: (0.012, 0.009),
        },
        link planet {
            points { P },
            mass: 0.3, inertia: 0.00009, cg: (0.0400, 0.0230),
        },
        joints {
            S: revolute(ground, sun) at O,
            O: revolute(ground, arm),
            P: revolute(arm, planet),
            sp: gear(sun, planet) radii (20 mm, 25 mm),
            pr: gear(planet, ground) radii (25 mm, 70 mm) internal pressure_angle 25 deg,
        },
        input: S,
        loads {
            pull: force on arm at T,
            brake: torque on arm,
        },
    }
}

mechanism! {
    /// Rack and pinion: the pinion (the input, pitch radius 30 mm, 20° teeth, centre O, its
    /// cg 3.2 mm off O) turns on the ground and drives the rack, which slides on a ground
    /// guide tilted by 4.0° (`along (1.0, 0.07)`); the rack's pitch line runs 30 mm below O
    /// through its sliding point R (the foot of the perpendicular from O), so the pinion
    /// turning q moves it r q along the guide. The rack is loaded at L, 120.4 mm along the
    /// guide from R and 25 mm below its pitch line, its cg off the line too. A meshing
    /// group of one link (the rack, its slide and `mesh`). The pitch radius and the
    /// pressure angle are those of the hand-written `RackPinionHand`
    /// (`benches/floor/hand_rack_pinion.rs`).
    pub struct RackPinion {
        gravity: (0.0, -9.81),
        ground { O: (0.0, 0.0) },
        link pinion {
            points { O },
            mass: 0.4, inertia: 0.00012, cg: (0.003, 0.001),
        },
        link rack {
            points { R: (0.002094873830997416, -0.0299267690142488), L: (0.124, -0.0465) },
            mass: 1.4, cg: (0.063, -0.038),
        },
        joints {
            O: revolute(ground, pinion),
            guide: prismatic(ground, rack) at R along (1.0, 0.07),
            mesh: rack(pinion, rack) radius 30 mm pressure_angle 20 deg,
        },
        input: O,
        loads {
            push: force on rack at L,
            resist: torque on pinion,
        },
    }
}
