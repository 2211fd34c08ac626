//! `mech optimize FILE --vary NAME=LO..HI ... --minimize OBJECTIVE [--subject-to ..] -o
//! OUT.mech`: named numbers of the file varied within bounds against an objective of the
//! machine's dynamics (`mech_core::design::optimize`); prints the objective's history and
//! the values, writes the file with them.

use crate::loads::LoadSet;
use crate::output::{Format, Writer};
use crate::{limits, source, strength, Failure};
use mech_core::design::optimize::{optimize, Constraint, Objective, Settings, Variable};
use mech_core::MechError;
use std::io::Write;
use std::path::PathBuf;

/// `mech optimize` arguments.
#[derive(clap::Args, Debug)]
pub struct OptimizeArgs {
    /// The mechanism file; one revolute input.
    pub file: PathBuf,
    /// A number to vary: NAME=LO..HI, NAME a constant of `consts { .. }` or
    /// `links.<l>.mass` / `links.<l>.inertia`, the bounds with a unit word as the file
    /// writes it (`l=130mm..170mm`). Repeatable.
    #[arg(long, required = true)]
    pub vary: Vec<String>,
    /// peak_driver, rms_driver, flywheel, peak_reaction(J), rms_shaking or
    /// path(TARGETS.csv, P).
    #[arg(long)]
    pub minimize: String,
    /// A constraint: assembles, grashof, "transmission >= 40 deg". Repeatable.
    #[arg(long = "subject-to")]
    pub subject_to: Vec<String>,
    /// Where to write the optimised file.
    #[arg(short = 'o', long = "output")]
    pub output: PathBuf,
    /// The input's constant speed q̇ (rad/s, or `300rpm`); the mean speed for `flywheel`.
    #[arg(long, default_value = "0", allow_hyphen_values = true)]
    pub speed: String,
    /// ε for the `flywheel` objective.
    #[arg(long, value_parser = limits::irregularity)]
    pub irregularity: Option<f64>,
    /// A load: NAME=VALUE or NAME=@table.csv (as `mech solve`). Repeatable.
    #[arg(long = "load", allow_hyphen_values = true)]
    pub load: Vec<String>,
    /// Instants over the cycle (2 to 10⁶).
    #[arg(long, default_value_t = 180)]
    pub steps: usize,
    /// The period of the cycle (rad): 2pi, or 4pi.
    #[arg(long, default_value = "2pi")]
    pub period: String,
    /// Candidates to evaluate at most.
    #[arg(long, default_value_t = 300)]
    pub evaluations: usize,
    /// The seed of the initial sampling (a run repeats exactly with the same seed).
    #[arg(long, default_value_t = 0)]
    pub seed: u64,
    /// Output format of the history.
    #[arg(long, value_enum, default_value_t = Format::Table)]
    pub format: Format,
}

/// `NAME=LO..HI` with unit words.
fn variable(text: &str) -> Result<Variable, Failure> {
    let bad = || {
        Failure::usage(format!(
            "--vary {text}: write NAME=LO..HI, e.g. `l=130mm..170mm` or `links.crank.mass=2..6`"
        ))
    };
    let (name, range) = text.split_once('=').ok_or_else(bad)?;
    let (lo, hi) = range.split_once("..").ok_or_else(bad)?;
    let number = |s: &str| {
        mech_core::design::rewrite::number(s).map_err(|why| match why.starts_with("unknown unit") {
            true => Failure::usage(format!("--vary {text}: {why}")),
            false => bad(),
        })
    };
    let ((lo, u1), (hi, u2)) = (number(lo)?, number(hi)?);
    if u1.map(|u| u.dim) != u2.map(|u| u.dim) && u1.is_some() && u2.is_some() {
        return Err(Failure::usage(format!(
            "--vary {text}: the bounds have different units"
        )));
    }
    Ok(Variable {
        name: name.trim().to_string(),
        lo,
        hi,
        unit: u1.or(u2),
    })
}

/// Path targets from a CSV file with columns `x,y` (m).
fn targets(path: &str) -> Result<Vec<[f64; 2]>, MechError> {
    let text = std::fs::read_to_string(path)
        .map_err(|e| MechError::InvalidInput(format!("path({path}, ..): cannot read it: {e}")))?;
    let mut r = csv::ReaderBuilder::new()
        .trim(csv::Trim::All)
        .from_reader(text.as_bytes());
    let mut out = Vec::new();
    for row in r.records() {
        let row = row.map_err(|e| MechError::InvalidInput(format!("{path}: {e}")))?;
        let v: Vec<f64> = row.iter().take(2).filter_map(|x| x.parse().ok()).collect();
        match v.as_slice() {
            [x, y] if x.is_finite() && y.is_finite() => out.push([*x, *y]),
            _ => {
                return Err(MechError::InvalidInput(format!(
                    "{path}: each row is x,y in metres (finite numbers)"
                )))
            }
        }
    }
    if out.is_empty() {
        return Err(MechError::InvalidInput(format!(
            "{path}: no target; give a header x,y and one row per target"
        )));
    }
    Ok(out)
}

/// Run `mech optimize`.
pub fn run(args: OptimizeArgs, out: impl Write) -> Result<(), Failure> {
    let m = source::load(&args.file)?;
    let (text, _) = source::read(&args.file)?;
    limits::writable(&args.output, "-o", "mech")?;
    let vars = args
        .vary
        .iter()
        .map(|v| variable(v))
        .collect::<Result<Vec<_>, _>>()?;
    let objective = Objective::parse(&args.minimize, args.irregularity, targets)?;
    let constraints = args
        .subject_to
        .iter()
        .map(|c| Constraint::parse(c))
        .collect::<Result<Vec<_>, _>>()?;
    let (speed, period) = strength::cycle(&args.speed, &args.period, args.steps)?;
    let loads = LoadSet::parse(&args.load, m.model())?;
    let settings = Settings {
        speed,
        period,
        steps: args.steps,
        evaluations: args.evaluations,
        seed: args.seed,
    };
    let started = std::time::Instant::now();
    let best = optimize(&text, &vars, &objective, &constraints, settings, |m, q| {
        Ok(loads.at(m, q))
    })?;
    let names = ["evaluations", "objective"].map(String::from);
    let mut w = Writer::new(out, args.format, &names, &["1", ""])?;
    for (n, f) in &best.history {
        w.row(&[*n as f64, *f])?;
    }
    w.finish()?;
    eprintln!(
        "{}: {} as given, {} optimised ({} evaluations, {:.1} s, {:.0} per second)",
        args.minimize,
        best.initial,
        best.objective,
        best.evaluations,
        started.elapsed().as_secs_f64(),
        best.evaluations as f64 / started.elapsed().as_secs_f64().max(1e-9)
    );
    for (v, x) in vars.iter().zip(&best.values) {
        let shown = v
            .unit
            .map_or(format!("{x}"), |u| format!("{} {}", x / u.factor, u.word));
        eprintln!("  {} = {shown}", v.name);
    }
    limits::write_file(&args.output, &best.text, "-o", "mech")
}
