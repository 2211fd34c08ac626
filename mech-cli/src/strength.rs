//! `mech strength FILE [--speed QD] [--load ..] [--steps N] [--format ..]`: the strength of
//! every member over the cycle (`Mechanism::strength`): one row per member (`<link>` or
//! `<joint>.pin`) with the criterion that governs it, the stresses over the cycle, the
//! smallest factor of safety and the input q where it is smallest; `--all` gives a row per
//! criterion.

use crate::loads::LoadSet;
use crate::output::{Cell, Format, Writer};
use crate::{limits, quantity, source, Failure};
use mech_core::model::units::Dim;
use mech_core::strength::{Check, Member, Strength};
use std::io::Write;
use std::path::PathBuf;

/// `mech strength` arguments.
#[derive(clap::Args, Debug)]
pub struct StrengthArgs {
    /// The mechanism file (`-` = standard input); one revolute input, links declared by a
    /// beam `shape:` and a `material:`, joints with a `pin`.
    pub file: PathBuf,
    /// The input's constant speed q̇ (rad/s, or with a unit: `300rpm`); 0 checks the loads
    /// and gravity alone.
    #[arg(long, default_value = "0", allow_hyphen_values = true)]
    pub speed: String,
    /// A load: NAME=VALUE or NAME=@table.csv (as `mech solve`). Repeatable.
    #[arg(long = "load", allow_hyphen_values = true)]
    pub load: Vec<String>,
    /// Instants over the cycle (2 to 10⁶).
    #[arg(long, default_value_t = 360)]
    pub steps: usize,
    /// The period of the cycle (rad): 2pi, or 4pi for a four-stroke engine's loads.
    #[arg(long, default_value = "2pi")]
    pub period: String,
    /// A row for every criterion of every member, not only the one that governs.
    #[arg(long)]
    pub all: bool,
    /// Output format. With `table` the worst member is named after the table; with `csv`
    /// or `json` standard output holds the rows only and the worst goes to standard error.
    #[arg(long, value_enum, default_value_t = Format::Table)]
    pub format: Format,
}

/// The columns of `mech strength` (SPEC §3e), and their units.
pub const COLUMNS: [(&str, &str); 7] = [
    ("member", ""),
    ("criterion", ""),
    ("stress_max", "Pa"),
    ("stress_mean", "Pa"),
    ("stress_alt", "Pa"),
    ("safety", "1"),
    ("q", "rad"),
];

/// The strength of the machine in `args` (shared with `mech size`).
pub fn analyse(
    m: &mech_core::Mechanism,
    speed: f64,
    period: f64,
    steps: usize,
    loads: &LoadSet,
) -> Result<Strength, Failure> {
    Ok(m.strength(speed, period, steps, |q| Ok(loads.at(m, q)))?)
}

/// Parse the cycle's flags shared by `mech strength` and `mech size`: the speed (rad/s),
/// the period (rad) and the steps.
pub fn cycle(speed: &str, period: &str, steps: usize) -> Result<(f64, f64), Failure> {
    let qd = quantity::parse(speed, Dim::SPEED, "--speed")?;
    let period = quantity::parse(period, Dim::ANGLE, "--period")?;
    if !(period > 0.0 && period <= limits::PERIOD) {
        return Err(Failure::usage(format!(
            "--period {period}: give a positive period of at most {:.0} turns",
            limits::PERIOD / std::f64::consts::TAU
        )));
    }
    if !(2..=1_000_000).contains(&steps) {
        return Err(Failure::usage(format!(
            "--steps {steps}: give 2 to 1000000 instants"
        )));
    }
    Ok((qd, period))
}

/// The row of one check.
fn cells<'a>(member: &'a Member, c: &'a Check) -> [Cell<'a>; 7] {
    [
        Cell::Text(&member.name),
        Cell::Text(c.criterion.name()),
        Cell::Num(c.stress_max),
        Cell::Num(c.stress_mean),
        Cell::Num(c.stress_alt),
        Cell::Num(c.safety),
        Cell::Num(c.q),
    ]
}

/// Run `mech strength`.
pub fn run(args: StrengthArgs, out: impl Write) -> Result<(), Failure> {
    let m = source::load(&args.file)?;
    let (qd, period) = cycle(&args.speed, &args.period, args.steps)?;
    let loads = LoadSet::parse(&args.load, m.model())?;
    let s = analyse(&m, qd, period, args.steps, &loads)?;
    let names: Vec<String> = COLUMNS.iter().map(|c| c.0.to_string()).collect();
    let units: Vec<&str> = COLUMNS.iter().map(|c| c.1).collect();
    let table = args.format == Format::Table;
    let mut w = Writer::new(out, args.format, &names, &units)?;
    for member in &s.members {
        if args.all {
            for c in &member.checks {
                w.cells(&cells(member, c))?;
            }
        } else if let Some(c) = member.governing() {
            w.cells(&cells(member, c))?;
        }
    }
    let worst = s.worst().map(|(m, c)| {
        format!(
            "worst: {} in {} at q = {:.4} rad, safety {:.4}",
            m.name,
            c.criterion.name(),
            c.q,
            c.safety
        )
    });
    if table {
        if let Some(line) = &worst {
            w.push(&format!("\n{line}"))?;
        }
        w.finish()?;
    } else {
        w.finish()?;
        if let Some(line) = worst {
            eprintln!("{line}");
        }
    }
    Ok(())
}
