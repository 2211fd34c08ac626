//! `mech size FILE --safety S [--speed ..] [--load ..] [--irregularity EPS] -o OUT.mech`:
//! the dimensions written `free(LO..HI)` chosen so that every member's factor is ≥ S
//! (`mech_core::design::sizing`), the dynamics re-run with each change until a fixed
//! point. Prints the table of passes (`iteration`, `total_mass`, `peak_torque`,
//! `flywheel`, `worst`), then each sized dimension; writes OUT.mech, the same file with
//! the numbers written in.

use crate::loads::LoadSet;
use crate::output::{Format, Writer};
use crate::{limits, source, strength, Failure};
use mech_core::checks::load::free_dimensions;
use mech_core::design::sizing::{self, Requirement};
use std::io::Write;
use std::path::PathBuf;

/// `mech size` arguments.
#[derive(clap::Args, Debug)]
pub struct SizeArgs {
    /// The mechanism file, with dimensions written `free(LO..HI)`; one revolute input.
    pub file: PathBuf,
    /// S: the smallest factor of safety every member must have.
    #[arg(long)]
    pub safety: f64,
    /// Where to write the sized file.
    #[arg(short = 'o', long = "output")]
    pub output: PathBuf,
    /// The input's constant speed q̇ (rad/s, or `300rpm`).
    #[arg(long, default_value = "0", allow_hyphen_values = true)]
    pub speed: String,
    /// A load: NAME=VALUE or NAME=@table.csv (as `mech solve`). Repeatable.
    #[arg(long = "load", allow_hyphen_values = true)]
    pub load: Vec<String>,
    /// Instants of each strength analysis (2 to 10⁶).
    #[arg(long, default_value_t = 180)]
    pub steps: usize,
    /// The period of the cycle (rad): 2pi, or 4pi.
    #[arg(long, default_value = "2pi")]
    pub period: String,
    /// The coefficient of fluctuation of speed ε the flywheel column is designed for (with
    /// a mean speed `--speed` > 0); omitted, no flywheel column.
    #[arg(long, value_parser = limits::irregularity)]
    pub irregularity: Option<f64>,
    /// Output format of the table of passes.
    #[arg(long, value_enum, default_value_t = Format::Table)]
    pub format: Format,
}

/// Run `mech size`.
pub fn run(args: SizeArgs, out: impl Write) -> Result<(), Failure> {
    let m = source::load(&args.file)?;
    let (text, origin) = source::read(&args.file)?;
    let free = free_dimensions(&text, Some(&origin))?;
    limits::writable(&args.output, "-o", "mech")?;
    let (speed, period) = strength::cycle(&args.speed, &args.period, args.steps)?;
    if args.irregularity.is_some() && !(speed > 0.0) {
        return Err(Failure::usage(format!(
            "--irregularity needs the mean speed it is for: give --speed > 0 (got {speed} rad/s)"
        )));
    }
    let loads = LoadSet::parse(&args.load, m.model())?;
    let req = Requirement {
        safety: args.safety,
        speed,
        period,
        steps: args.steps,
        irregularity: args.irregularity,
    };
    let sized = sizing::size(&m, &free, req, |q| Ok(loads.at(&m, q)))?;
    let mut names = vec!["iteration", "total_mass", "peak_torque"];
    let mut units = vec!["1", "kg", "N·m"];
    if args.irregularity.is_some() {
        names.push("flywheel");
        units.push("kg·m²");
    }
    names.push("worst");
    units.push("1");
    let names: Vec<String> = names.into_iter().map(String::from).collect();
    let mut w = Writer::new(out, args.format, &names, &units)?;
    for (k, it) in sized.iterations.iter().enumerate() {
        let mut row = vec![(k + 1) as f64, it.total_mass, it.peak_torque];
        row.extend(it.flywheel);
        row.push(it.worst);
        w.row(&row)?;
    }
    w.finish()?;
    let mut summary: Vec<String> = free
        .iter()
        .zip(&sized.dims)
        .map(|(f, v)| {
            format!(
                "{}.{} = {:.4} mm (free {:.4}..{:.4} mm)",
                f.link,
                f.name,
                v * 1e3,
                f.lo * 1e3,
                f.hi * 1e3
            )
        })
        .collect();
    if !sized.converged {
        summary.push(format!(
            "no fixed point after {} passes: the sizes still change; the last pass is written",
            sizing::MAX_PASSES
        ));
    }
    for u in &sized.unmet {
        summary.push(format!("not met: {u}"));
    }
    for line in &summary {
        eprintln!("{line}");
    }
    limits::write_file(
        &args.output,
        &sizing::write_sized(&text, &free, &sized.dims),
        "-o",
        "mech",
    )?;
    if sized.unmet.is_empty() {
        Ok(())
    } else {
        Err(Failure::usage(format!(
            "{} member(s) do not meet the factor {}: {}",
            sized.unmet.len(),
            args.safety,
            sized.unmet.join("; ")
        )))
    }
}
