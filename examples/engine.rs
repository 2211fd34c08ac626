//! A single-cylinder four-stroke engine and its flywheel, end to end:
//!
//! ```text
//! cargo run --release --example engine
//! ```
//!
//! The engine: an offset slider-crank, 86 mm bore × 86 mm stroke, 143 mm rod, declared
//! below by its dimensions (no coordinate computed by hand), with an explicit gas-pressure
//! model over the 4π cycle (intake, polytropic compression, Wiebe-shaped combustion,
//! polytropic expansion, exhaust; `tests/common/engine.rs`) acting on the piston.
//! The consumer's constant resisting torque is the one that balances the cycle. The example
//! prints the turning-moment table, sizes the flywheel for ω_a = 3000 rpm and ε = 1/50 by
//! Wittenbauer's exact method and by the approximate one, checks the exact one by
//! integrating a cycle in time, runs the engine on the grid through an induction machine
//! (`mech::motor`, `mech::regime`: the run-up and the periodic steady regime found
//! directly, against the flywheel design), and writes the diagrams into
//! target/mech-figures/engine/.

#[path = "../tests/common/engine.rs"]
mod engine;
#[path = "common/plot.rs"]
mod plot;

use std::error::Error;
use std::path::{Path, PathBuf};
use std::process::ExitCode;

use engine::{
    breakpoints, pressure, BORE, COMPRESSION_RATIO, IRREGULARITY, OMEGA_MEAN, PERIOD, PISTON_AREA,
    P_CRANKCASE, Q_TDC, X_BDC, X_TDC,
};
use mech::flywheel::Cycle;
use mech::motor::Motor;
use mech::prelude::*;
use mech::regime::Drive;

mechanism! {
    /// Single-cylinder four-stroke engine: offset slider-crank, 86 mm stroke, 143 mm rod,
    /// the piston's guide 6 mm above the crank centre, drawn with the crank at 30°.
    pub struct Engine {
        consts { stroke: 86 mm, r: stroke / 2, l: 143 mm, e: 6 mm },
        gravity: (0.0, -9.81),
        ground { O2: (0.0, 0.0) },
        link crank {
            points { O2, A: O2 + polar(r, 30 deg) },
            // crankshaft with counterweights: the cg 5 mm behind the pivot
            mass: 3.6 kg, inertia: 6.8e-3 kg_m2, cg: along(-5 mm),
        },
        link rod {
            // B on the guide line y = e, on the far side of the crank: the rod's length closes it
            points { A, B: circle_line(A, l, (0.0, e), 0 deg, forward) },
            mass: 580 g, inertia: 2.1e-3 kg_m2, cg: along(38 mm),
        },
        link piston {
            points { B },
            mass: 520 g, cg: B,
        },
        joints {
            O2: revolute(ground, crank),
            A: revolute(crank, rod),
            B: revolute(rod, piston),
            guide: prismatic(ground, piston) at B along (1.0, 0.0),
        },
        input: O2,
        loads {
            gas: force on piston at B,
        },
    }
}

/// The gas force on the piston pin at crank angle q (N): (−(p − p_crankcase) A, 0), the
/// cylinder head on the +x side.
pub fn gas_loads(engine: &Engine, q: f64) -> Result<EngineLoads, MechError> {
    let x_b = engine.pose(q)?.points.B.pos.x;
    Ok(EngineLoads {
        gas: Vector2::new(-(pressure(q, x_b) - P_CRANKCASE) * PISTON_AREA, 0.0),
    })
}

/// The engine on the grid through an induction machine (11 kW, 3000 rpm synchronous,
/// 2940 rpm rated, breakdown 2.5 T_r; Kloss's curve) and Wittenbauer's flywheel for ε = 1/50:
/// from 600 rpm (the starter's work done) the machine, a motor below its synchronous speed,
/// and the firing engine bring the shaft up until the engine drives the machine above
/// synchronous speed, a generator; the periodic steady regime it settles in, found
/// directly, against the flywheel design.
fn regimes(eng: &Engine, cycle: &Cycle<Engine>, dir: &Path) -> Result<PathBuf, Box<dyn Error>> {
    let rpm = std::f64::consts::PI / 30.0;
    let machine = Motor::induction(11000.0, 3000.0 * rpm, 2940.0 * rpm, 2.5)?;
    let flywheel = cycle.wittenbauer(OMEGA_MEAN, IRREGULARITY)?.inertia;
    let drive = Drive::new(eng, machine, |q| gas_loads(eng, q)).flywheel(flywheel)?;
    println!();
    println!("On the grid through an 11 kW induction machine (3000 rpm synchronous), flywheel {flywheel:.4} kg m^2:");
    // Compression resists up to ~140 N·m, more than the machine's torque at rest: the
    // starter brings the engine to 600 rpm, the ignition is on, and the run begins there.
    println!("  the start, from 600 rpm (after the starter) at the TDC of intake:");
    let start = drive.run(Q_TDC, 600.0 * rpm, 1.5, 6)?;
    println!("{:>8} {:>10} {:>12}", "t s", "rpm", "machine N m");
    for k in 0..start.t.len() {
        println!(
            "{:>8.2} {:>10.1} {:>12.2}",
            start.t[k],
            start.qd[k] / rpm,
            start.torque[k]
        );
    }
    let steady = drive.steady(Q_TDC, PERIOD, 1440)?;
    let c = &steady.check;
    println!(
        "  steady regime (shooting, {} shots): mean {:.2} rpm, eps = {:.5} (flywheel design {IRREGULARITY}), cycle {:.2} ms",
        steady.iterations,
        steady.mean_speed / rpm,
        steady.epsilon,
        steady.period_time * 1e3
    );
    println!(
        "  the machine as generator: mean power {:.2} kW, torque peak {:.2} N m, RMS {:.2} N m (rated {:.2} N m): {}",
        -c.mean_power / 1e3,
        c.peak_torque,
        c.rms_torque,
        c.rated_torque.unwrap_or(f64::NAN),
        if c.within_rating { "within its rating" } else { "overloaded" }
    );
    let speed: Vec<(f64, f64)> = steady
        .q
        .iter()
        .zip(&steady.qd)
        .map(|(q, w)| ((q - Q_TDC).to_degrees(), w / rpm))
        .collect();
    std::fs::create_dir_all(dir)?;
    let path = dir.join("steady_regime.svg");
    plot::line_chart(
        &path,
        "engine on the grid: the steady regime's crank speed",
        "crank angle from the cycle start (deg)",
        "speed (rpm)",
        &[plot::Series {
            label: format!("eps = {:.4}", steady.epsilon),
            points: speed,
        }],
    )?;
    println!(
        "  the steady regime's speed over the cycle: {}",
        path.display()
    );
    Ok(path)
}

/// Where the figures go.
pub const FIGURES: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/target/mech-figures/engine");

fn main() -> ExitCode {
    plot::exit("engine", run(Path::new(FIGURES)))
}

/// The whole example: prints the report and writes the SVG diagrams into `dir`; returns
/// their paths.
pub fn run(dir: &Path) -> Result<Vec<PathBuf>, Box<dyn Error>> {
    let started = std::time::Instant::now();
    let eng = Engine::new();
    let mut cycle = Cycle::builder(&eng, PERIOD, |q| gas_loads(&eng, q))
        .start(Q_TDC)
        .breakpoints(&breakpoints())
        .build()?;
    let gas_only = &cycle;
    println!("Single-cylinder four-stroke engine: bore {:.0} mm, stroke {:.2} mm, rod 143 mm, offset 6 mm, compression ratio {}", BORE * 1e3, (X_TDC - X_BDC) * 1e3, COMPRESSION_RATIO);
    println!("cycle: lambda = 4 pi from the TDC of intake (q0 = {:.4} deg); gas work per cycle W = {:.3} J", Q_TDC.to_degrees(), gas_only.net_work());
    if let Err(e) = gas_only.check_periodic() {
        println!("  gas loads alone: {e}");
    }
    let torque = cycle.balance();
    println!("  balanced by a constant resisting torque T = {torque:.4} N m on the crank (mean power {:.2} kW at {:.0} rpm)", -torque * OMEGA_MEAN / 1e3, OMEGA_MEAN * 30.0 / std::f64::consts::PI);
    let de = cycle.fluctuation()?;
    println!("  maximum fluctuation of energy dE = S_max - S_min = {:.3} J (S_max at {:.1} deg, S_min at {:.1} deg of the cycle)", de.energy, (de.q_s_max - Q_TDC).to_degrees(), (de.q_s_min - Q_TDC).to_degrees());
    for flywheel in [0.1, 0.2, 0.4] {
        println!("  a flywheel of {flywheel} kg m^2 keeps the speed within delta = (w_max - w_min)/w_a = {:.5} at {:.0} rpm", cycle.speed_fluctuation(OMEGA_MEAN, flywheel)?, OMEGA_MEAN * 30.0 / std::f64::consts::PI);
    }

    println!();
    println!("Turning moment at constant speed w_a = {OMEGA_MEAN:.2} rad/s (alpha = 0); reactions in kN (force by the first link on the second):");
    println!(
        "{:>6} {:>8} {:>10} {:>9} {:>9} {:>9} {:>10} {:>9}",
        "phi", "p", "T_driver", "|R_A|", "|R_B|", "|R_O2|", "M*", "I*"
    );
    println!(
        "{:>6} {:>8} {:>10} {:>9} {:>9} {:>9} {:>10} {:>9}",
        "deg", "bar", "N m", "crankpin", "gudgeon", "main", "N m", "kg m^2"
    );
    for k in 0..=24 {
        let q = Q_TDC + (30.0 * k as f64).to_radians();
        let motion = eng.kinematics(q, OMEGA_MEAN, 0.0)?;
        let loads = cycle.loads(q)?;
        let f = eng.kinetostatics(&motion, &loads)?;
        let p = pressure(q, motion.points.B.pos.x);
        println!(
            "{:>6} {:>8.2} {:>10.2} {:>9.3} {:>9.3} {:>9.3} {:>10.2} {:>9.6}",
            30 * k,
            p / 1e5,
            f.driver,
            f.joints.A.force.norm() / 1e3,
            f.joints.B.force.norm() / 1e3,
            f.joints.O2.force.norm() / 1e3,
            cycle.moment(q)?,
            eng.reduced(q)?.inertia
        );
    }
    println!("(the mean of T_driver over the cycle is T; M* = gas and gravity moment + T)");

    let regime = regimes(&eng, &cycle, dir)?;

    let mut paths = plot::report(&cycle, OMEGA_MEAN, IRREGULARITY, "engine", dir)?;
    paths.push(regime);
    println!("done in {:.2} s", started.elapsed().as_secs_f64());
    Ok(paths)
}
