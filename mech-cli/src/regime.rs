//! `mech regime FILE --motor MODEL [--ratio N] [--load ..]`: the periodic steady regime
//! ω(q) = ω(q + λ) of a one-input machine driven by a motor, found directly by shooting
//! (`mech_core::dynamics::regime`): the mean speed, the irregularity ε, the period in
//! time, the motor's duty, and the table `q`, `qd`, `t`, `torque` over one period.
//!
//! With `--stop [--brake T]`, the stop instead: the motor switched off at `--start` with the
//! machine at its steady speed there (or at `--speed` without a motor), coasting (`--brake
//! 0`) or braked by a constant torque T against the motion until it is at rest
//! (`Drive::stop_steps`): the time to rest, the angle turned, and the table `t`, `q`, `qd`.

use crate::loads::LoadSet;
use crate::output::{Format, Writer};
use crate::{limits, motor, quantity, source, Failure};
use mech_core::dynamics::motor::Motor;
use mech_core::dynamics::regime::Drive;
use mech_core::model::units::Dim;
use std::io::Write;
use std::path::PathBuf;

/// `mech regime` arguments.
#[derive(clap::Args, Debug)]
pub struct RegimeArgs {
    /// The mechanism file (`-` = standard input); one revolute input.
    pub file: PathBuf,
    /// The motor: dc(stall_torque T, no_load_speed W), induction(rated_power P,
    /// synchronous_speed W, rated_speed W, breakdown_ratio K), table(FILE.csv) or constant(T).
    /// A power takes `W` or `kW`, a speed `rpm`. Needed unless `--stop --speed` gives the
    /// speed the stop starts from.
    #[arg(long, required_unless_present = "speed")]
    pub motor: Option<String>,
    /// Reduction ratio n = motor speed / input speed.
    #[arg(long, default_value_t = 1.0, value_parser = limits::positive)]
    pub ratio: f64,
    /// A load: NAME=VALUE or NAME=@table.csv (as `mech solve`). Repeatable.
    #[arg(long = "load", allow_hyphen_values = true)]
    pub load: Vec<String>,
    /// A flywheel on the input shaft (kg·m², or with a unit word), the motor's rotor
    /// included (n² J_rotor).
    #[arg(long, default_value = "0")]
    pub flywheel: String,
    /// The period λ of the loads (rad): 2pi, or 4pi for a four-stroke engine.
    #[arg(long, default_value = "2pi")]
    pub period: String,
    /// Where the period starts, q0 (rad or `30deg`); with `--stop`, where the motor is
    /// switched off.
    #[arg(long, default_value = "0", allow_hyphen_values = true)]
    pub start: String,
    /// Rows of the table: the period (with `--stop`, the time to rest) in this many even
    /// steps (2 to 10⁶).
    #[arg(long, default_value_t = 360)]
    pub points: usize,
    /// The stop instead of the steady regime: the motor switched off at `--start`, from the
    /// steady speed there (or from `--speed`), until the machine is at rest. Prints the time
    /// to rest, the angle turned and the table t, q, qd.
    #[arg(long)]
    pub stop: bool,
    /// With `--stop`: a brake of constant torque against the motion (N·m, ≥ 0); 0, the
    /// default, coasts (the loads, gravity and the machine's own losses stop it).
    #[arg(
        long,
        default_value = "0",
        requires = "stop",
        allow_hyphen_values = true
    )]
    pub brake: String,
    /// With `--stop`: the input speed the stop starts from (rad/s or `1500rpm`), instead of
    /// the steady regime under `--motor`.
    #[arg(
        long,
        requires = "stop",
        conflicts_with = "motor",
        allow_hyphen_values = true
    )]
    pub speed: Option<String>,
    /// With `--stop`: the longest stop waited for, s; an error when the machine is still
    /// moving then (coasting with no loss never stops).
    #[arg(long = "t-max", default_value_t = 600.0, requires = "stop", value_parser = limits::positive)]
    pub t_max: f64,
    /// Output format. With `table` the summary comes first on standard output; with
    /// `csv` or `json` standard output holds the table only and the summary goes to
    /// standard error.
    #[arg(long, value_enum, default_value_t = Format::Table)]
    pub format: Format,
}

/// Run `mech regime`.
pub fn run(args: RegimeArgs, mut out: impl Write) -> Result<(), Failure> {
    let m = source::load(&args.file)?;
    if m.dof() != 1 || quantity::input_dims(m.model(), 0).0 != Dim::ANGLE {
        return Err(Failure::usage(
            "`mech regime` drives a machine with one revolute input (a motor's shaft)".to_string(),
        ));
    }
    if !(2..=1_000_000).contains(&args.points) {
        return Err(Failure::usage(format!(
            "--points {}: give 2 to 1000000 rows",
            args.points
        )));
    }
    let motor = match &args.motor {
        Some(text) => Some(motor::parse(text, args.ratio)?),
        None => None,
    };
    let flywheel = quantity::parse(&args.flywheel, Dim::INERTIA, "--flywheel")?;
    let period = quantity::parse(&args.period, Dim::ANGLE, "--period")?;
    if !(period > 0.0 && period <= limits::PERIOD) {
        return Err(Failure::usage(format!(
            "--period {}: give a positive period of at most {:.0} turns",
            args.period,
            limits::PERIOD / std::f64::consts::TAU
        )));
    }
    let start = quantity::parse(&args.start, Dim::ANGLE, "--start")?;
    let loads = LoadSet::parse(&args.load, m.model())?;
    if args.stop {
        return stop(&args, &m, motor, flywheel, period, start, &loads, out);
    }
    let Some(motor) = motor else {
        return Err(Failure::usage(
            "the steady regime needs `--motor MODEL`".to_string(),
        ));
    };
    let drive = Drive::new(&m, motor, |q| Ok(loads.at(&m, q))).flywheel(flywheel)?;
    let s = drive.steady(start, period, args.points)?;
    let c = &s.check;
    let mut summary = vec![
        ("mean_speed", "rad/s", s.mean_speed),
        (
            "mean_speed_rpm",
            "rpm",
            s.mean_speed * 30.0 / std::f64::consts::PI,
        ),
        ("epsilon", "1", s.epsilon),
        ("period_time", "s", s.period_time),
        (
            "omega_max",
            "rad/s",
            s.qd.iter().copied().fold(f64::NEG_INFINITY, f64::max),
        ),
        (
            "omega_min",
            "rad/s",
            s.qd.iter().copied().fold(f64::INFINITY, f64::min),
        ),
        ("motor_peak_torque", "N·m", c.peak_torque),
        ("motor_rms_torque", "N·m", c.rms_torque),
        ("motor_mean_power", "W", c.mean_power),
    ];
    if let Some(r) = c.rated_torque {
        summary.push(("motor_rated_torque", "N·m", r));
    }
    let verdict = if c.within_rating {
        "the motor's RMS torque is within its rating".to_string()
    } else {
        format!(
            "the motor is overloaded: its RMS torque {:.4} N·m exceeds its rated torque {:.4} N·m; choose a larger motor or another ratio",
            c.rms_torque,
            c.rated_torque.unwrap_or(f64::NAN)
        )
    };
    let lines: Vec<String> = summary
        .iter()
        .map(|(n, u, v)| format!("{n:<20} {v:>22.12e}  {u}"))
        .chain([verdict])
        .collect();
    write_summary(&lines, args.format, &mut out)?;
    let names = ["q", "qd", "t", "torque"].map(String::from);
    let mut w = Writer::new(out, args.format, &names, &["rad", "rad/s", "s", "N·m"])?;
    for k in 0..s.q.len() {
        w.row(&[s.q[k], s.qd[k], s.t[k], s.torque[k]])?;
    }
    w.finish()?;
    Ok(())
}

/// The summary: on standard output before the table (`table`), else on standard error.
fn write_summary(lines: &[String], format: Format, mut out: impl Write) -> Result<(), Failure> {
    if format == Format::Table {
        for l in lines {
            writeln!(out, "{l}")?;
        }
        writeln!(out)?;
    } else {
        for l in lines {
            eprintln!("{l}");
        }
    }
    Ok(())
}

/// `mech regime --stop`: the speed at q0 (`--speed`, or the steady regime's under the
/// motor), then the stop with the motor off and the brake on (`Drive::stop_steps`).
#[allow(clippy::too_many_arguments)]
fn stop(
    args: &RegimeArgs,
    m: &mech_core::Mechanism,
    motor: Option<Motor>,
    flywheel: f64,
    period: f64,
    start: f64,
    loads: &LoadSet,
    out: impl Write,
) -> Result<(), Failure> {
    let brake = quantity::parse(&args.brake, Dim::TORQUE, "--brake")?;
    if brake < 0.0 {
        return Err(Failure::usage(format!(
            "--brake {}: a brake's torque acts against the motion; give its magnitude, ≥ 0 (0 coasts)",
            args.brake
        )));
    }
    let (speed, from) =
        match (&args.speed, motor) {
            (Some(text), _) => {
                let w = quantity::parse(text, Dim::SPEED, "--speed")?;
                if !(w > 0.0) {
                    return Err(Failure::usage(format!(
                        "--speed {text}: a stop starts from a positive speed"
                    )));
                }
                (w, "the given")
            }
            (None, Some(motor)) => {
                let steady = Drive::new(m, motor, |q| Ok(loads.at(m, q)))
                    .flywheel(flywheel)?
                    .steady(start, period, args.points)?;
                (steady.qd[0], "the steady regime's")
            }
            (None, None) => return Err(Failure::usage(
                "--stop starts from the steady regime under `--motor MODEL`, or from `--speed QD`"
                    .to_string(),
            )),
        };
    // The motor is off during the stop: the drive's motor is never asked for a torque.
    let off = Motor::constant(0.0)?;
    let drive = Drive::new(m, off, |q| Ok(loads.at(m, q))).flywheel(flywheel)?;
    let s = drive.stop_steps(start, speed, brake, args.points, args.t_max)?;
    let summary = [
        ("initial_speed", "rad/s", speed),
        (
            "initial_speed_rpm",
            "rpm",
            speed * 30.0 / std::f64::consts::PI,
        ),
        ("brake_torque", "N·m", brake),
        ("stop_time", "s", s.time),
        ("stop_angle", "rad", s.travel),
        ("stop_turns", "turns", s.travel / std::f64::consts::TAU),
    ];
    let lines: Vec<String> = summary
        .iter()
        .map(|(n, u, v)| format!("{n:<20} {v:>22.12e}  {u}"))
        .chain([format!(
            "the motor switched off at q0 = {start} rad, at {from} speed; {}",
            if brake > 0.0 {
                "braked to rest"
            } else {
                "coasting to rest"
            }
        )])
        .collect();
    let mut out = out;
    write_summary(&lines, args.format, &mut out)?;
    let names = ["t", "q", "qd"].map(String::from);
    let mut w = Writer::new(out, args.format, &names, &["s", "rad", "rad/s"])?;
    for k in 0..s.run.t.len() {
        w.row(&[s.run.t[k], s.run.q[k], s.run.qd[k]])?;
    }
    w.finish()?;
    Ok(())
}
