//! The flywheel of a quick-return shaper: a machine driven by a motor, loaded by a cutting
//! force during the working stroke only (no gas model).
//!
//! ```text
//! cargo run --release --example shaper
//! ```
//!
//! The shaper (tests/common/shaper.rs): crank O2-A, block in the slotted lever O4-C, link
//! C-D, ram on a horizontal guide; the tool cuts with 2 kN from 10° after the start of the
//! working stroke to 10° before its end. The motor's mean torque is the one that balances
//! the cycle. The example prints a table over the revolution, sizes the flywheel on the crank
//! shaft for 60 rpm and ε = 0.05 by both methods, checks it by integrating a revolution in
//! time, and writes the diagrams into target/mech-figures/shaper/.

#[path = "common/plot.rs"]
mod plot;
#[path = "../tests/common/shaper.rs"]
mod shaper;

use std::error::Error;
use std::path::{Path, PathBuf};
use std::process::ExitCode;

use mech::flywheel::Cycle;
use shaper::*;

/// Where the figures go.
pub const FIGURES: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/target/mech-figures/shaper");

fn main() -> ExitCode {
    plot::exit("shaper", run(Path::new(FIGURES)))
}

/// The whole example: prints the report and writes the SVG diagrams into `dir`; returns
/// their paths.
pub fn run(dir: &Path) -> Result<Vec<PathBuf>, Box<dyn Error>> {
    let started = std::time::Instant::now();
    let m = Shaper::new();
    let q0 = working_start(&m);
    let unbalanced = Cycle::new(
        &m,
        q0,
        PERIOD,
        &breakpoints(&m),
        |q| cut_loads(&m, q),
        |_| 0.0,
    )?;
    println!("Quick-return shaper: working stroke {:.2} deg of crank, return {:.2} deg (ratio {:.3}); cut {CUT_FORCE} N", working_arc(&m).to_degrees(), 360.0 - working_arc(&m).to_degrees(), working_arc(&m) / (PERIOD - working_arc(&m)));
    println!("cycle: one revolution from the start of the working stroke (q0 = {:.4} deg); work of the cut and gravity W = {:.3} J", q0.to_degrees(), unbalanced.net_work());
    let (cycle, torque) = unbalanced.balanced();
    println!("  balanced by the motor's constant torque T = {torque:.4} N m on the crank (mean power {:.1} W at {:.0} rpm)", torque * OMEGA_MEAN, OMEGA_MEAN * 30.0 / std::f64::consts::PI);

    println!();
    println!("At constant speed w_a = {OMEGA_MEAN:.4} rad/s (alpha = 0):");
    println!(
        "{:>6} {:>9} {:>9} {:>7} {:>10} {:>10} {:>10} {:>9}",
        "phi", "ram x", "ram v", "cut", "T_driver", "|R_slot|", "M*", "I*"
    );
    println!(
        "{:>6} {:>9} {:>9} {:>7} {:>10} {:>10} {:>10} {:>9}",
        "deg", "mm", "m/s", "N", "N m", "N", "N m", "kg m^2"
    );
    for k in 0..=12 {
        let q = q0 + (30.0 * k as f64).to_radians();
        let motion = m.kinematics(q, OMEGA_MEAN, 0.0)?;
        let loads = cycle.loads(q)?;
        let f = m.kinetostatics(&motion, &loads)?;
        println!(
            "{:>6} {:>9.2} {:>9.4} {:>7.0} {:>10.3} {:>10.2} {:>10.3} {:>9.5}",
            30 * k,
            motion.points.D.pos.x * 1e3,
            motion.points.D.vel.x,
            loads.cut.x,
            f.driver,
            f.joints.slot.force.norm(),
            cycle.moment(q)?,
            m.reduced(q)?.inertia
        );
    }

    let paths = plot::report(&cycle, OMEGA_MEAN, IRREGULARITY, "shaper", dir)?;
    println!("(on a motor shaft geared n : 1 to the crank, the same flywheel is I / n^2)");
    println!("done in {:.2} s", started.elapsed().as_secs_f64());
    Ok(paths)
}
