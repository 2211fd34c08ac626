//! `mech simulate FILE --q0 .. --speed .. --t-end ..`: the direct problem of a one-input
//! machine over time, I*(q) q̈ + ½ dI*/dq q̇² = driver + M*(q) (Zhukovski), with the driver
//! and the loads as constants or tables against q, integrated by DOP853 (default),
//! Dormand–Prince 5(4) or fixed-step RK4 (`mech_core::dynamics::ode`), sampled at even times on the
//! integrator's dense output.

use crate::loads::{LoadSet, Table};
use crate::output::{Format, Writer};
use crate::{quantity, source, Failure};
use mech_core::dynamics::equation_of_motion;
use mech_core::dynamics::ode::{self, Dense, Dop853, DormandPrince, Method, Rk4, Tolerance};
use mech_core::model::units::Dim;
use mech_core::Mechanism;
use std::io::Write;
use std::path::PathBuf;

/// The integrator.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum Integrator {
    /// Dormand–Prince 8(5,3), adaptive.
    Dop853,
    /// Dormand–Prince 5(4), adaptive.
    Dopri5,
    /// Classical Runge–Kutta, fixed step `--step`.
    Rk4,
}

/// `mech simulate` arguments.
#[derive(clap::Args, Debug)]
pub struct SimulateArgs {
    /// The mechanism file (`-` = standard input); one input.
    pub file: PathBuf,
    /// Initial input value q0 (rad or m).
    #[arg(long, default_value = "0", allow_hyphen_values = true)]
    pub q0: String,
    /// Initial speed q̇0 (rad/s, rpm, or m/s).
    #[arg(long, default_value = "0", allow_hyphen_values = true)]
    pub speed: String,
    /// End time, s.
    #[arg(long = "t-end")]
    pub t_end: f64,
    /// Driver action on the input: a constant (N·m or N) or @table.csv against q.
    #[arg(long, default_value = "0", allow_hyphen_values = true)]
    pub driver: String,
    /// A load: NAME=VALUE or NAME=@table.csv (as `mech solve`). Repeatable.
    #[arg(long = "load", allow_hyphen_values = true)]
    pub load: Vec<String>,
    /// The integrator.
    #[arg(long, value_enum, default_value_t = Integrator::Dop853)]
    pub method: Integrator,
    /// Relative and absolute tolerance of an adaptive integrator.
    #[arg(long, default_value_t = 1e-10)]
    pub rtol: f64,
    /// Absolute tolerance of an adaptive integrator.
    #[arg(long, default_value_t = 1e-10)]
    pub atol: f64,
    /// Step of RK4, s.
    #[arg(long, default_value_t = 1e-4)]
    pub step: f64,
    /// The most steps an adaptive integrator may take (accepted and rejected): past it
    /// the run stops with an error (a stiff or runaway machine).
    #[arg(long = "max-steps", default_value_t = ode::DEFAULT_MAX_STEPS)]
    pub max_steps: usize,
    /// Output rows: the state at this many even intervals of [0, t_end] (plus t = 0).
    #[arg(long, default_value_t = 100)]
    pub samples: usize,
    /// Output format.
    #[arg(long, value_enum, default_value_t = Format::Table)]
    pub format: Format,
}

/// The driver: a constant or a table against q.
enum Driver {
    Constant(f64),
    Table(Table),
}

impl Driver {
    fn at(&self, q: f64) -> f64 {
        match self {
            Driver::Constant(c) => *c,
            Driver::Table(t) => t.at(q)[0],
        }
    }
}

/// Integrate with `method` and write (t, q, q̇, q̈) at the sample times.
fn integrate<Mt: Method<2>>(
    mut method: Mt,
    m: &Mechanism,
    args: &SimulateArgs,
    y0: [f64; 2],
    driver: &Driver,
    loads: &LoadSet,
    w: &mut Writer<impl Write>,
) -> Result<(), Failure> {
    let n = args.samples.max(1);
    let times: Vec<f64> = (0..=n).map(|k| args.t_end * k as f64 / n as f64).collect();
    let mut rows: Vec<[f64; 2]> = vec![y0];
    let mut next = 1;
    let f = equation_of_motion(m, |_, q, _| (driver.at(q), loads.at(m, q)));
    let mut observe = |d: &Mt::Dense| {
        while next < times.len() && times[next] <= d.t_end() {
            rows.push(d.eval(times[next]));
            next += 1;
        }
    };
    let out = ode::solve(
        &mut method,
        f,
        0.0,
        y0,
        args.t_end,
        None,
        Some(&mut observe),
    )?;
    while rows.len() < times.len() {
        rows.push(out.y);
    }
    for (t, y) in times.iter().zip(rows) {
        let qdd = m.acceleration_at(y[0], y[1], driver.at(y[0]), &loads.at(m, y[0]))?;
        w.row(&[*t, y[0], y[1], qdd])?;
    }
    eprintln!(
        "{} steps, {} evaluations of q̈",
        out.stats.steps, out.stats.rhs_evals
    );
    Ok(())
}

/// q̈ of the run-time mechanism (Zhukovski), as the equation of motion computes it.
trait Acceleration {
    fn acceleration_at(
        &self,
        q: f64,
        qd: f64,
        driver: f64,
        loads: &mech_core::runtime::mechanism::Loads,
    ) -> Result<f64, Failure>;
}

impl Acceleration for Mechanism {
    fn acceleration_at(
        &self,
        q: f64,
        qd: f64,
        driver: f64,
        loads: &mech_core::runtime::mechanism::Loads,
    ) -> Result<f64, Failure> {
        Ok(mech_core::solvers::traits::OneDof::acceleration(
            self, q, qd, driver, loads,
        )?)
    }
}

/// Run `mech simulate`.
pub fn run(args: SimulateArgs, out: impl Write) -> Result<(), Failure> {
    let m = source::load(&args.file)?;
    if m.dof() != 1 {
        return Err(Failure::usage(format!(
            "`mech simulate` integrates a machine with one input; this one has {}",
            m.dof()
        )));
    }
    let (dq, dv) = quantity::input_dims(m.model(), 0);
    let y0 = [
        quantity::parse(&args.q0, dq, "--q0")?,
        quantity::parse(&args.speed, dv, "--speed")?,
    ];
    let driver = match args.driver.strip_prefix('@') {
        Some(path) => {
            let text = std::fs::read_to_string(path)
                .map_err(|e| Failure::usage(format!("--driver: cannot read {path}: {e}")))?;
            Driver::Table(Table::parse(&text, 1, path)?)
        }
        None => Driver::Constant(quantity::parse(
            &args.driver,
            if dq == Dim::ANGLE {
                Dim::TORQUE
            } else {
                Dim::FORCE
            },
            "--driver",
        )?),
    };
    let loads = LoadSet::parse(&args.load, m.model())?;
    let unit = if dq == Dim::ANGLE {
        ["s", "rad", "rad/s", "rad/s²"]
    } else {
        ["s", "m", "m/s", "m/s²"]
    };
    let names = ["t", "q", "qd", "qdd"].map(String::from);
    let mut w = Writer::new(out, args.format, &names, &unit)?;
    let tol = Tolerance {
        max_steps: args.max_steps,
        ..Tolerance::new(args.rtol, args.atol)
    };
    match args.method {
        Integrator::Dop853 => integrate(Dop853::with(tol), &m, &args, y0, &driver, &loads, &mut w)?,
        Integrator::Dopri5 => integrate(
            DormandPrince::with(tol),
            &m,
            &args,
            y0,
            &driver,
            &loads,
            &mut w,
        )?,
        Integrator::Rk4 => integrate(Rk4 { h: args.step }, &m, &args, y0, &driver, &loads, &mut w)?,
    }
    w.finish()?;
    Ok(())
}
