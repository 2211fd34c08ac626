//! A crank press sized from scratch: its links' sections, its flywheel and its motor.
//!
//! ```text
//! cargo run --release --example press
//! ```
//!
//! The press is `examples/mech/press.mech` (printed below), its sections written
//! `free(LO..HI)`; the work resists the ram with 20 kN over the last 30° before the bottom
//! dead centre (`examples/mech/press_load.csv`). At 60 rpm the example
//! 1. sizes the sections so that every member has a factor of safety ≥ 2 (`mech::design::sizing`:
//!    lightest first, the dynamics re-run until the sizes stop changing) and prints the
//!    passes and the sized press's strength (`mech::strength`);
//! 2. takes the flywheel for ε = 0.05 (Wittenbauer) and the mean power of the cycle, and
//!    picks the smallest induction motor (1440 rpm, through a 24:1 reduction) whose RMS
//!    torque in the periodic steady regime stays within its rating (`mech::regime`);
//! 3. starts the press from rest with it, and writes the steady regime's speed to
//!    `target/mech-figures/press/steady_regime.svg`.

#[path = "common/plot.rs"]
mod plot;

use std::error::Error;
use std::path::{Path, PathBuf};
use std::process::ExitCode;

use mech::design::sizing::{free_dimensions, size, write_sized, Requirement};
use mech::flywheel::Cycle;
use mech::motor::Motor;
use mech::regime::Drive;
use mech::{Loads, MechError, Mechanism};

/// Where the figures go.
pub const FIGURES: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/target/mech-figures/press");
const RPM: f64 = std::f64::consts::PI / 30.0;
const TAU: f64 = std::f64::consts::TAU;
/// The crank's mean speed, rad/s.
const SPEED: f64 = 60.0 * RPM;
/// The required factor of safety.
const SAFETY: f64 = 2.0;
/// The flywheel's coefficient of fluctuation of speed.
const IRREGULARITY: f64 = 0.05;
/// The reduction from the motor (1440 rpm rated) to the crank (60 rpm).
const RATIO: f64 = 24.0;
/// Induction motors' standard rated powers, W.
const SIZES: [f64; 12] = [
    370.0, 550.0, 750.0, 1100.0, 1500.0, 2200.0, 3000.0, 4000.0, 5500.0, 7500.0, 11000.0, 15000.0,
];

fn main() -> ExitCode {
    plot::exit("press", run(Path::new(FIGURES)))
}

/// The work's force on the ram at crank angle q: the table (q in degrees, fx, fy in N),
/// linear between rows, periodic over a turn.
fn work(table: &[[f64; 3]], m: &Mechanism, q: f64) -> Result<Loads, MechError> {
    let deg = q.to_degrees().rem_euclid(360.0);
    let k = table.windows(2).position(|w| deg <= w[1][0]).unwrap_or(0);
    let (a, b) = (table[k], table[k + 1]);
    let s = (deg - a[0]) / (b[0] - a[0]);
    let mut loads = m.loads();
    loads.set_by_name(
        "work",
        &[a[1] + s * (b[1] - a[1]), a[2] + s * (b[2] - a[2])],
    );
    Ok(loads)
}

/// The whole example: prints the report and writes the SVG into `dir`.
pub fn run(dir: &Path) -> Result<Vec<PathBuf>, Box<dyn Error>> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/mech");
    let text = std::fs::read_to_string(root.join("press.mech"))?;
    let table: Vec<[f64; 3]> = std::fs::read_to_string(root.join("press_load.csv"))?
        .lines()
        .skip(1)
        .map(|l| {
            let v: Vec<f64> = l
                .split(',')
                .map(|x| x.trim().parse().unwrap_or(f64::NAN))
                .collect();
            [v[0], v[1], v[2]]
        })
        .collect();
    println!("The press to size (examples/mech/press.mech):\n{text}");
    let press = Mechanism::from_dsl(&text)?;
    let free = free_dimensions(&text, None)?;

    // 1. The sections.
    let req = Requirement {
        safety: SAFETY,
        speed: SPEED,
        period: TAU,
        steps: 180,
        irregularity: Some(IRREGULARITY),
    };
    let sized = size(&press, &free, req, |q| work(&table, &press, q))?;
    println!(
        "Sizing for a factor of safety {SAFETY} at 60 rpm, flywheel for eps = {IRREGULARITY}:"
    );
    println!(
        "{:>5} {:>10} {:>12} {:>12} {:>7}",
        "pass", "mass kg", "peak T N m", "flywheel", "worst"
    );
    for (k, it) in sized.iterations.iter().enumerate() {
        println!(
            "{:>5} {:>10.4} {:>12.2} {:>12.3} {:>7.3}",
            k + 1,
            it.total_mass,
            it.peak_torque,
            it.flywheel.unwrap_or(f64::NAN),
            it.worst
        );
    }
    for (f, v) in free.iter().zip(&sized.dims) {
        println!(
            "  {}.{} = {:.1} mm (free {:.0}..{:.0} mm)",
            f.link,
            f.name,
            v * 1e3,
            f.lo * 1e3,
            f.hi * 1e3
        );
    }
    if !sized.unmet.is_empty() {
        return Err(format!("not met: {:?}", sized.unmet).into());
    }
    let sized_text = write_sized(&text, &free, &sized.dims);
    let m = Mechanism::from_dsl(&sized_text)?;
    let strength = m.strength(SPEED, TAU, 360, |q| work(&table, &m, q))?;
    println!("\nThe sized press's members over the cycle (the governing check of each):");
    println!(
        "{:>7} {:>9} {:>11} {:>11} {:>7} {:>7}",
        "member", "criterion", "max MPa", "alt MPa", "safety", "at deg"
    );
    for member in &strength.members {
        let c = member.governing().ok_or("a member with no check")?;
        println!(
            "{:>7} {:>9} {:>11.2} {:>11.2} {:>7.3} {:>7.1}",
            member.name,
            c.criterion.name(),
            c.stress_max / 1e6,
            c.stress_alt / 1e6,
            c.safety,
            c.q.to_degrees()
        );
    }

    // 2. The flywheel and the motor.
    let cycle = Cycle::new(&m, 0.0, TAU, &[], |q| work(&table, &m, q), |_| 0.0)?;
    let (cycle, torque) = cycle.balanced();
    let flywheel = cycle.wittenbauer(SPEED, IRREGULARITY)?.inertia;
    let power = torque * SPEED;
    println!(
        "\nThe cycle's mean torque {torque:.2} N m on the crank, mean power {power:.1} W; flywheel {flywheel:.3} kg m^2 on the crank ({:.4} kg m^2 on the motor's shaft)",
        flywheel / (RATIO * RATIO)
    );
    let mut chosen = None;
    for rated in SIZES.iter().filter(|&&p| p >= power) {
        let motor = Motor::induction(*rated, 1500.0 * RPM, 1440.0 * RPM, 2.5)?.through(RATIO)?;
        let drive = Drive::new(&m, motor, |q| work(&table, &m, q)).flywheel(flywheel)?;
        let steady = match drive.steady(0.0, TAU, 720) {
            Ok(s) => s,
            Err(e) => {
                println!("  {:.2} kW: no steady regime ({e})", rated / 1e3);
                continue;
            }
        };
        let c = &steady.check;
        println!(
            "  {:>5.2} kW: steady mean {:.2} rpm, eps {:.4}; RMS torque {:.2} N m against rated {:.2} N m: {}",
            rated / 1e3,
            steady.mean_speed / RPM,
            steady.epsilon,
            c.rms_torque,
            c.rated_torque.unwrap_or(f64::NAN),
            if c.within_rating { "within its rating" } else { "overloaded" }
        );
        if c.within_rating {
            chosen = Some((*rated, drive, steady));
            break;
        }
    }
    let (rated, drive, steady) = chosen.ok_or("no motor of the table carries the press")?;

    // 3. The start and the steady regime.
    let start = drive.start_up(0.0, 40.0, 8)?;
    println!(
        "\nThe start from rest with the {:.2} kW motor:",
        rated / 1e3
    );
    println!("{:>6} {:>9} {:>12}", "t s", "rpm", "motor N m");
    for k in 0..start.t.len() {
        println!(
            "{:>6.2} {:>9.2} {:>12.2}",
            start.t[k],
            start.qd[k] / RPM,
            start.torque[k]
        );
    }
    std::fs::create_dir_all(dir)?;
    let path = dir.join("steady_regime.svg");
    let points = steady
        .q
        .iter()
        .zip(&steady.qd)
        .map(|(q, w)| (q.to_degrees(), w / RPM))
        .collect();
    plot::line_chart(
        &path,
        "the sized press with its motor and flywheel: the steady regime",
        "crank angle (deg)",
        "crank speed (rpm)",
        &[plot::Series {
            label: format!("{:.2} kW, eps = {:.4}", rated / 1e3, steady.epsilon),
            points,
        }],
    )?;
    println!("\nthe steady regime's speed: {}", path.display());
    Ok(vec![path])
}
