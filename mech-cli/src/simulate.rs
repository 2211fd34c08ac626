//! `mech simulate FILE --q0 .. --speed .. --t-end ..`: the direct problem of a one-input
//! machine over time, I*(q) q̈ + ½ dI*/dq q̇² = driver + M*(q) (Zhukovski), with the driver
//! and the loads as constants or tables against q, integrated by DOP853 (default),
//! Dormand–Prince 5(4) or fixed-step RK4 (`mech_core::dynamics::ode`), sampled at even times on the
//! integrator's dense output. A spatial file (`space` first) takes its loads as
//! `--load NAME=x,y,z` or `NAME=@table.csv`.

use crate::loads::{LoadSet, Table};
use crate::output::{Format, Writer};
use crate::{limits, motor, quantity, source, Failure};
use mech_core::dynamics::equation_of_motion;
use mech_core::dynamics::motor::Motor;
use mech_core::dynamics::ode::{self, Dense, Dop853, DormandPrince, Method, Rk4, Tolerance};
use mech_core::dynamics::regime::Drive;
use mech_core::model::units::Dim;
use mech_core::solvers::traits::OneDof;
use std::cell::Cell;
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
    /// End time, s (positive).
    #[arg(long = "t-end", allow_hyphen_values = true, value_parser = limits::positive)]
    pub t_end: f64,
    /// Driver action on the input: a constant (N·m or N) or @table.csv against q.
    #[arg(
        long,
        default_value = "0",
        allow_hyphen_values = true,
        conflicts_with = "motor"
    )]
    pub driver: String,
    /// A motor drives the input instead (torque from speed): dc(stall_torque T,
    /// no_load_speed W), induction(rated_power P, synchronous_speed W, rated_speed W,
    /// breakdown_ratio K), table(FILE.csv) or constant(T).
    #[arg(long)]
    pub motor: Option<String>,
    /// The motor's reduction ratio n = motor speed / input speed.
    #[arg(long, default_value_t = 1.0, value_parser = limits::positive, requires = "motor")]
    pub ratio: f64,
    /// Start from rest (q̇0 = 0); with a motor, an error when it cannot start the machine
    /// at q0.
    #[arg(long = "from-rest", conflicts_with = "speed")]
    pub from_rest: bool,
    /// A load: NAME=VALUE or NAME=@table.csv (as `mech solve`). Repeatable.
    #[arg(long = "load", allow_hyphen_values = true)]
    pub load: Vec<String>,
    /// The integrator.
    #[arg(long, value_enum, default_value_t = Integrator::Dop853)]
    pub method: Integrator,
    /// Relative tolerance of an adaptive integrator (1e-15 to 0.1).
    #[arg(long, default_value_t = 1e-10, allow_hyphen_values = true, value_parser = limits::rtol)]
    pub rtol: f64,
    /// Absolute tolerance of an adaptive integrator (0 to 1).
    #[arg(long, default_value_t = 1e-10, allow_hyphen_values = true, value_parser = limits::atol)]
    pub atol: f64,
    /// Step of RK4, s.
    #[arg(long, default_value_t = 1e-4, allow_hyphen_values = true, value_parser = limits::positive)]
    pub step: f64,
    /// The most steps an adaptive integrator may take (accepted and rejected): past it
    /// the run stops with an error (a stiff or runaway machine).
    #[arg(long = "max-steps", default_value_t = ode::DEFAULT_MAX_STEPS)]
    pub max_steps: usize,
    /// Output rows: the state at this many even intervals of [0, t_end] (plus t = 0), at
    /// most 10⁷.
    #[arg(long, default_value_t = 100, allow_hyphen_values = true, value_parser = limits::samples)]
    pub samples: usize,
    /// Output format.
    #[arg(long, value_enum, default_value_t = Format::Table)]
    pub format: Format,
}

/// The driver: a constant, a table against q, or a motor (against q̇).
enum Driver {
    Constant(f64),
    Table(Table),
    Motor(Motor),
}

impl Driver {
    fn at(&self, q: f64, qd: f64) -> f64 {
        match self {
            Driver::Constant(c) => *c,
            Driver::Table(t) => t.at(q)[0],
            Driver::Motor(m) => m.on_input(qd),
        }
    }
}

/// Integrate with `method` and write (t, q, q̇, q̈) at the sample times, row by row as
/// the integrator passes them (no memory in the number of samples). The run stops with a
/// message when it would take more than [`limits::INTEGRATION_STEPS`] steps: at once for
/// RK4 (t_end / step), by the rate so far for an adaptive method.
fn integrate<Mt: Method<2>, M: OneDof>(
    mut method: Mt,
    m: &M,
    args: &SimulateArgs,
    y0: [f64; 2],
    driver: &Driver,
    loads: &impl Fn(f64) -> M::Loads,
    w: &mut Writer<impl Write>,
) -> Result<(), Failure> {
    let limit = limits::INTEGRATION_STEPS;
    let n = args.samples.max(1);
    let time = |k: usize| args.t_end * k as f64 / n as f64;
    let qdd = |y: [f64; 2]| -> Result<f64, Failure> {
        Ok(m.acceleration(y[0], y[1], driver.at(y[0], y[1]), &loads(y[0]))?)
    };
    w.row(&[0.0, y0[0], y0[1], qdd(y0)?])?;
    // Accepted steps and the time they reached; the budget's verdict.
    let (steps, reached) = (Cell::new(0u64), Cell::new(0.0f64));
    let over: Cell<Option<(u64, f64, f64)>> = Cell::new(None);
    let mut eom = equation_of_motion(m, |_, q, qd| (driver.at(q, qd), loads(q)));
    let f = |t: f64, y: &[f64; 2]| {
        let (k, at) = (steps.get(), reached.get());
        // After 10³ steps, the rate so far predicts the whole run's.
        let whole = if at > 0.0 {
            k as f64 * args.t_end / at
        } else {
            0.0
        };
        if k >= limit || (k >= 1000 && whole > 10.0 * limit as f64) {
            over.set(Some((k, at, whole)));
            return Err(mech_core::MechError::InvalidInput("step budget".into()));
        }
        eom(t, y)
    };
    let mut next = 1;
    let mut failure: Option<Failure> = None;
    let out = {
        let mut observe = |d: &Mt::Dense| {
            steps.set(steps.get() + 1);
            reached.set(d.t_end());
            while next <= n && time(next) <= d.t_end() {
                if failure.is_none() {
                    let y = d.eval(time(next));
                    if let Err(e) = qdd(y).and_then(|a| Ok(w.row(&[time(next), y[0], y[1], a])?)) {
                        failure = Some(e);
                    }
                }
                next += 1;
            }
        };
        ode::solve(
            &mut method,
            f,
            0.0,
            y0,
            args.t_end,
            None,
            Some(&mut observe),
        )
    };
    if let Some((k, at, whole)) = over.get() {
        return Err(Failure::usage(format!(
            "--t-end {}: after {k} steps the integration has reached t = {at:.3e} s; the whole run would take about {whole:.1e} steps, more than the limit of {limit}; shorten --t-end, or loosen --rtol and --atol",
            limits::show(args.t_end)
        )));
    }
    let out = out?;
    if let Some(f) = failure {
        return Err(f);
    }
    while next <= n {
        w.row(&[time(next), out.y[0], out.y[1], qdd(out.y)?])?;
        next += 1;
    }
    eprintln!(
        "{} steps, {} evaluations of q̈",
        out.stats.steps, out.stats.rhs_evals
    );
    Ok(())
}

/// Run `mech simulate` on the file's machine, planar (loads constant or tables against q)
/// or spatial (constant 3-vector loads).
pub fn run(args: SimulateArgs, out: impl Write) -> Result<(), Failure> {
    let one_input = |g: usize| {
        if g == 1 {
            Ok(())
        } else {
            Err(Failure::usage(format!(
                "`mech simulate` integrates a machine with one input; this one has {g}"
            )))
        }
    };
    match source::load_any(&args.file)? {
        source::Any::Planar(m) => {
            one_input(m.dof())?;
            let loads = LoadSet::parse(&args.load, m.model())?;
            let dims = quantity::input_dims(m.model(), 0);
            simulate(&m, dims, |q| loads.at(&m, q), &args, out)
        }
        source::Any::Spatial(m) => {
            one_input(m.dof())?;
            let loads = crate::spatial::loads(&args.load, &m)?;
            let dims = crate::spatial::input_dims(&m, 0);
            simulate(&m, dims, |q| loads.at(q), &args, out)
        }
    }
}

/// The run on a one-input machine `m` whose input has the dimensions `(dq, dv)` (its value's
/// and its rate's) under `loads` against q.
fn simulate<M: OneDof>(
    m: &M,
    (dq, dv): (Dim, Dim),
    loads: impl Fn(f64) -> M::Loads,
    args: &SimulateArgs,
    out: impl Write,
) -> Result<(), Failure> {
    let y0 = [
        quantity::parse(&args.q0, dq, "--q0")?,
        quantity::parse(&args.speed, dv, "--speed")?,
    ];
    let y0 = if args.from_rest { [y0[0], 0.0] } else { y0 };
    let driver = match &args.motor {
        Some(text) => {
            let motor = motor::parse(text, args.ratio)?;
            if args.from_rest {
                Drive::new(m, motor.clone(), |q| Ok(loads(q))).check_start(y0[0])?;
            }
            Driver::Motor(motor)
        }
        None => match args.driver.strip_prefix('@') {
            Some(path) => Driver::Table(Table::read(path, 1, "--driver")?),
            None => Driver::Constant(quantity::parse(
                &args.driver,
                if dq == Dim::ANGLE {
                    Dim::TORQUE
                } else {
                    Dim::FORCE
                },
                "--driver",
            )?),
        },
    };
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
        Integrator::Dop853 => integrate(Dop853::with(tol), m, args, y0, &driver, &loads, &mut w)?,
        Integrator::Dopri5 => integrate(
            DormandPrince::with(tol),
            m,
            args,
            y0,
            &driver,
            &loads,
            &mut w,
        )?,
        Integrator::Rk4 => {
            let steps = (args.t_end / args.step).ceil();
            if steps > limits::INTEGRATION_STEPS as f64 {
                return Err(Failure::usage(format!(
                    "--t-end {} with --step {}: {steps:.1e} steps, more than the limit of {}; take a larger --step or a shorter --t-end",
                    limits::show(args.t_end),
                    limits::show(args.step),
                    limits::INTEGRATION_STEPS
                )));
            }
            integrate(Rk4 { h: args.step }, m, args, y0, &driver, &loads, &mut w)?
        }
    }
    w.finish()?;
    Ok(())
}
