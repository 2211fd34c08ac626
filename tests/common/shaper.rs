//! The quick-return shaper of `examples/shaper.rs` and `tests/flywheel.rs`: a crank-shaper
//! (crank O2-A, block A sliding in the slotted lever O4-C, link C-D, ram D on a horizontal
//! guide) with a cutting force on the ram during the working stroke only.
//!
//! O4 is directly below O2, so the lever's limit positions are where the crank is
//! perpendicular to it: crank angles −π/2 ± acos(r/d) (r = O2A, d = O2O4). With the crank
//! turning counter-clockwise, the working stroke is the long arc through the top, of
//! π + 2 asin(r/d), during which the ram moves in −x; the tool cuts from `OVERRUN` after
//! its start to `OVERRUN` before its end, against the motion: a force (+CUT_FORCE, 0) on
//! the ram at D.
#![allow(dead_code)]

use mech::prelude::*;

mechanism! {
    /// Crank-shaper quick-return: crank 100 mm, centres 350 mm, lever 700 mm, link 200 mm, ram 370 mm above O2.
    pub struct Shaper {
        gravity: (0.0, -9.81),
        ground { O2: (0.0, 0.0), O4: (0.0, -0.35) },
        link crank {
            points { O2, A: (0.0, 0.1) },
            mass: 4.0, inertia: 0.02, cg: (0.0, -0.01),
        },
        link block {
            points { A },
            mass: 0.6, inertia: 0.0004, cg: (0.0, 0.1),
        },
        link lever {
            points { O4, C: (0.0, 0.35) },
            mass: 7.5, inertia: 0.35, cg: (0.0, -0.02),
        },
        link rod {
            points { C, D: (0.198997487421324, 0.37) },
            mass: 1.6, inertia: 0.006, cg: (0.099498743710662, 0.36),
        },
        link ram {
            points { D },
            mass: 22.0, cg: (-0.05, 0.43),
        },
        joints {
            O2: revolute(ground, crank),
            A: revolute(crank, block),
            slot: prismatic(lever, block) at A along (0.0, 1.0),
            O4: revolute(ground, lever),
            C: revolute(lever, rod),
            D: revolute(rod, ram),
            guide: prismatic(ground, ram) at D along (1.0, 0.0),
        },
        input: O2,
        loads {
            cut: force on ram at D,
        },
    }
}

/// The cutting force on the ram while the tool cuts, N (it acts along +x, against the
/// ram's motion in −x).
pub const CUT_FORCE: f64 = 2000.0;

/// Crank angle between the start of the working stroke and the start of the cut (and
/// between the end of the cut and the end of the stroke), rad (10°).
pub const OVERRUN: f64 = 10.0 * std::f64::consts::PI / 180.0;

/// Mean crank speed ω_a, rad/s (60 strokes a minute).
pub const OMEGA_MEAN: f64 = 2.0 * std::f64::consts::PI;

/// Requested irregularity ε.
pub const IRREGULARITY: f64 = 0.05;

/// Period of the cycle: one crank revolution, rad.
pub const PERIOD: f64 = 2.0 * std::f64::consts::PI;

/// (r, d) = (|O2A|, |O2O4|) of the shaper's drawing, m.
fn crank_and_centres(m: &Shaper) -> (f64, f64) {
    let p = &m.params().points;
    ((p.A - p.O2).norm(), (p.O4 - p.O2).norm())
}

/// Crank angle of the start of the working stroke, −π/2 + acos(r/d), rad: the cycle's start.
pub fn working_start(m: &Shaper) -> f64 {
    let (r, d) = crank_and_centres(m);
    -std::f64::consts::FRAC_PI_2 + (r / d).acos()
}

/// Crank angle swept by the working stroke, π + 2 asin(r/d), rad.
pub fn working_arc(m: &Shaper) -> f64 {
    let (r, d) = crank_and_centres(m);
    std::f64::consts::PI + 2.0 * (r / d).asin()
}

/// The start and the end of the cut, crank angles in (start, start + 2π), rad.
pub fn breakpoints(m: &Shaper) -> [f64; 2] {
    let s = working_start(m);
    [s + OVERRUN, s + working_arc(m) - OVERRUN]
}

/// The loads at crank angle q (rad): (CUT_FORCE, 0) N on the ram while the tool cuts.
pub fn cut_loads(m: &Shaper, q: f64) -> Result<ShaperLoads, MechError> {
    mech_core::error::check_finite("q", &[q])?;
    let phi = (q - working_start(m)).rem_euclid(PERIOD);
    let cutting = phi > OVERRUN && phi < working_arc(m) - OVERRUN;
    Ok(ShaperLoads {
        cut: Vector2::new(if cutting { CUT_FORCE } else { 0.0 }, 0.0),
    })
}
