//! `mech balance FILE --speed QD [--method force|optimal] [--fraction C] [--radius R]
//! [--weights F,M,T] -o OUT.mech`: the counterweights of `mech_core::design::balance`
//! (`force_balance`, `optimal_balance`) written into the file;
//! the shaking force's RMS and peak over a turn before and after on standard output.

use crate::{quantity, source, Failure};
use mech_core::design::balance::{
    force_balance, optimal_balance, shaking_cycle, write_counterweights, BalanceWeights,
};
use mech_core::model::units::Dim;
use std::io::Write;
use std::path::PathBuf;

/// How the counterweights are chosen.
#[derive(clap::ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub enum Method {
    /// Exact force balance: a four-bar by two counterweights on its ground-pinned links
    /// (the total cg stationary); a slider-crank's crank counterweight taking the rotating
    /// masses and the fraction C of the reciprocating ones.
    Force,
    /// Counterweights on the ground-pinned links minimising the weighted RMS of shaking
    /// force, shaking moment and driver torque (`--weights`), by Nelder–Mead.
    Optimal,
}

/// `mech balance` arguments.
#[derive(clap::Args, Debug)]
pub struct BalanceArgs {
    /// The mechanism file (`-` = standard input); one revolute input.
    pub file: PathBuf,
    /// The input's constant speed q̇ (rad/s, or `3000rpm`) for the before/after figures.
    #[arg(long, allow_hyphen_values = true)]
    pub speed: String,
    /// The balancing method.
    #[arg(long, value_enum, default_value_t = Method::Force)]
    pub method: Method,
    /// The fraction C (0 to 1) of a slider-crank's reciprocating mass the crank's
    /// counterweight takes.
    #[arg(long, default_value_t = 0.5)]
    pub fraction: f64,
    /// The counterweights' distance from their pivots (m, or `400mm`); default each
    /// link's length.
    #[arg(long)]
    pub radius: Option<String>,
    /// The weights of the optimal method: shaking force, shaking moment, driver torque
    /// (each RMS relative to the unbalanced machine's).
    #[arg(long, value_delimiter = ',', default_values_t = [1.0, 1.0, 1.0])]
    pub weights: Vec<f64>,
    /// Where to write the balanced file.
    #[arg(short = 'o', long = "output")]
    pub output: PathBuf,
}

/// Run `mech balance`.
pub fn run(args: BalanceArgs, mut out: impl Write) -> Result<(), Failure> {
    let (text, origin) = source::read(&args.file)?;
    let m = source::parse(&text, &origin)?;
    if m.dof() != 1 {
        return Err(Failure::usage(
            "mech balance takes a mechanism with one input",
        ));
    }
    let qd = quantity::parse(&args.speed, Dim::SPEED, "--speed")?;
    let radius = match &args.radius {
        Some(r) => Some(quantity::parse(r, Dim::LENGTH, "--radius")?),
        None => None,
    };
    let weights = match args.method {
        Method::Force => force_balance(m.model(), args.fraction, radius),
        Method::Optimal => {
            let [f, mo, t] = args.weights[..] else {
                return Err(Failure::usage(
                    "--weights: give three numbers, force,moment,driver",
                ));
            };
            let w = BalanceWeights {
                force: f,
                moment: mo,
                driver: t,
            };
            optimal_balance(&text, qd, w, radius)
        }
    }
    .map_err(|e| Failure::usage(e.to_string()))?;
    let balanced =
        write_counterweights(&text, &weights).map_err(|e| Failure::usage(e.to_string()))?;
    let after = mech_core::Mechanism::from_dsl(&balanced)
        .map_err(|e| Failure::mechanism(format!("the balanced file: {e}")))?;
    let grid = (0.0, std::f64::consts::TAU, 360);
    let summary = |m: &mech_core::Mechanism| {
        shaking_cycle(m, grid, &[0.0], &[qd])
            .map(|c| c.summary())
            .map_err(|e| Failure::mechanism(e.to_string()))
    };
    let (b, a) = (summary(&m)?, summary(&after)?);
    std::fs::write(&args.output, &balanced)
        .map_err(|e| Failure::usage(format!("-o {}: {e}", args.output.display())))?;
    for w in &weights {
        writeln!(
            out,
            "counterweight on {}: {:.6e} kg at ({:.6e}, {:.6e}) m",
            w.name, w.mass, w.at[0], w.at[1]
        )?;
    }
    writeln!(out, "shaking force   rms [N]           peak [N]")?;
    writeln!(
        out,
        "before          {:<16.9e}  {:.9e}",
        b.rms_force, b.peak_force
    )?;
    writeln!(
        out,
        "after           {:<16.9e}  {:.9e}",
        a.rms_force, a.peak_force
    )?;
    out.flush()?;
    Ok(())
}
