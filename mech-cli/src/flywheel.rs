//! `mech flywheel FILE --period 4pi --speed 3000rpm --irregularity 0.02`: the cycle of a
//! one-input machine with its loads (constants or tables against q), the constant torque
//! that balances it (unless `--driver` is given), the maximum fluctuation of energy
//! ΔE = S_max − S_min, the flywheel inertia by the approximate formula and by
//! Wittenbauer's exact method, and the check of the exact one by integrating a cycle in
//! time (`mech_core::dynamics::flywheel`). A spatial file (`space` first) takes its loads
//! as `--load NAME=x,y,z` or `NAME=@table.csv`.

use crate::loads::LoadSet;
use crate::output::{Format, Writer};
use crate::{limits, quantity, source, Failure};
use mech_core::dynamics::flywheel::Cycle;
use mech_core::model::units::Dim;
use mech_core::solvers::traits::OneDof;
use mech_core::spatial::JointKind as SpatialJoint;
use mech_core::MechError;
use std::io::Write;
use std::path::PathBuf;

/// `mech flywheel` arguments.
#[derive(clap::Args, Debug)]
pub struct FlywheelArgs {
    /// The mechanism file (`-` = standard input), planar or spatial; one revolute input.
    pub file: PathBuf,
    /// The cycle's period λ (rad): `2pi`, `4*PI` (a four-stroke engine), `720deg`.
    #[arg(long, default_value = "2*PI", allow_hyphen_values = true)]
    pub period: String,
    /// Where the cycle starts, q0 (rad or deg).
    #[arg(long, default_value = "0", allow_hyphen_values = true)]
    pub start: String,
    /// Mean speed ω_a (rad/s, or rpm).
    #[arg(long, allow_hyphen_values = true)]
    pub speed: String,
    /// Coefficient of fluctuation of speed ε = (ω_max − ω_min)/ω_a (1e-9 to below 2).
    #[arg(long, allow_hyphen_values = true, value_parser = limits::irregularity)]
    pub irregularity: f64,
    /// Input angles (inside the cycle) where the loads are not smooth: panels end there.
    #[arg(long, value_delimiter = ',', allow_hyphen_values = true)]
    pub breakpoints: Vec<String>,
    /// A load: NAME=VALUE or NAME=@table.csv (as `mech solve`); for a spatial file
    /// NAME=x,y,z or NAME=@table.csv (columns q, x, y, z). Repeatable.
    #[arg(long = "load", allow_hyphen_values = true)]
    pub load: Vec<String>,
    /// A constant driver torque on the input (N·m); omitted: the constant torque that
    /// balances the cycle's work.
    #[arg(long, allow_hyphen_values = true)]
    pub driver: Option<String>,
    /// Relative tolerance of the verifying time integration (DOP853; 1e-15 to 0.1).
    #[arg(long, default_value_t = 1e-10, allow_hyphen_values = true, value_parser = limits::rtol)]
    pub rtol: f64,
    /// Output format.
    #[arg(long, value_enum, default_value_t = Format::Table)]
    pub format: Format,
}

/// The results' names, units and values, in order: the file's machine, planar (loads
/// constant or tables against q) or spatial (constant 3-vector loads).
fn results(args: &FlywheelArgs) -> Result<Vec<(&'static str, &'static str, f64)>, Failure> {
    match source::load_any(&args.file)? {
        source::Any::Planar(m) => {
            let input = m.model().joints[m.model().inputs[0]].kind;
            if m.dof() != 1 || input != mech_core::model::JointKind::Revolute {
                return Err(one_revolute());
            }
            let loads = LoadSet::parse(&args.load, m.model())?;
            cycle(&m, |q| Ok(loads.at(&m, q)), args)
        }
        source::Any::Spatial(m) => {
            let input = &m.model().joints[m.model().inputs[0]].kind;
            if m.dof() != 1 || !matches!(input, SpatialJoint::Revolute { .. }) {
                return Err(one_revolute());
            }
            let loads = crate::spatial::loads(&args.load, &m)?;
            cycle(&m, |q| Ok(loads.at(q)), args)
        }
    }
}

fn one_revolute() -> Failure {
    Failure::usage("`mech flywheel` sizes the flywheel of a machine with one revolute input")
}

/// The cycle of `m` under `loads` (against q), its flywheel and the check by integration.
fn cycle<M: OneDof>(
    m: &M,
    loads: impl Fn(f64) -> Result<M::Loads, MechError>,
    args: &FlywheelArgs,
) -> Result<Vec<(&'static str, &'static str, f64)>, Failure> {
    let period = quantity::parse(&args.period, Dim::ANGLE, "--period")?;
    if period > limits::PERIOD {
        return Err(Failure::usage(format!(
            "--period {}: {:.3e} turns, more than the limit of {:.0} turns; a cycle is the shortest span after which the loads repeat",
            args.period,
            period / std::f64::consts::TAU,
            limits::PERIOD / std::f64::consts::TAU
        )));
    }
    let start = quantity::parse(&args.start, Dim::ANGLE, "--start")?;
    // Beyond this the cycle's angles lose their precision (q0 + λ rounds).
    if start.abs() * f64::EPSILON > 1e-9 * period.abs() {
        return Err(Failure::usage(format!(
            "--start {}: so large beside the period that the cycle's angles lose their precision; give a start within a few periods of 0",
            args.start
        )));
    }
    let omega = quantity::parse(&args.speed, Dim::SPEED, "--speed")?;
    let breakpoints: Vec<f64> = args
        .breakpoints
        .iter()
        .map(|b| quantity::parse(b, Dim::ANGLE, "--breakpoints"))
        .collect::<Result<_, _>>()?;
    let driver = match &args.driver {
        Some(d) => Some(quantity::parse(d, Dim::TORQUE, "--driver")?),
        None => None,
    };
    let cycle = Cycle::new(m, start, period, &breakpoints, loads, move |_| {
        driver.unwrap_or(0.0)
    })?;
    let net = cycle.net_work();
    let (cycle, torque) = if driver.is_some() {
        (cycle, 0.0)
    } else {
        cycle.balanced()
    };
    cycle.check_periodic()?;
    let fw = cycle.flywheel(omega, args.irregularity)?;
    let sim = cycle.simulate(&fw.exact.state, args.rtol)?;
    let a = &fw.approximate;
    Ok(vec![
        ("net_work", "J", net),
        ("balancing_torque", "N·m", torque),
        ("s_max", "J", a.s_max),
        ("q_s_max", "rad", a.q_s_max),
        ("s_min", "J", a.s_min),
        ("q_s_min", "rad", a.q_s_min),
        ("fluctuation", "J", a.s_max - a.s_min),
        ("inertia_approximate", "kg·m²", a.inertia),
        ("inertia_exact", "kg·m²", fw.exact.inertia),
        ("omega_max", "rad/s", sim.speeds.omega_max),
        ("omega_min", "rad/s", sim.speeds.omega_min),
        ("irregularity_simulated", "1", sim.speeds.irregularity),
    ])
}

/// Run `mech flywheel`.
pub fn run(args: FlywheelArgs, out: impl Write) -> Result<(), Failure> {
    let r = results(&args)?;
    if args.format == Format::Table {
        let mut out = out;
        for (n, u, v) in r {
            writeln!(out, "{n:<24} {v:>22.12e}  {u}")?;
        }
        out.flush()?;
        return Ok(());
    }
    let names: Vec<String> = r.iter().map(|(n, _, _)| n.to_string()).collect();
    let units: Vec<&str> = r.iter().map(|(_, u, _)| *u).collect();
    let mut w = Writer::new(out, args.format, &names, &units)?;
    w.row(&r.iter().map(|(_, _, v)| *v).collect::<Vec<_>>())?;
    w.finish()?;
    Ok(())
}
