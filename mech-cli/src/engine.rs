//! `mech engine --layout inline|v|boxer --cylinders N [--bank DEG] [--firing 1-3-4-2 |
//! --phases 0,180,180,0] [--radius R --rod L --mass M --spacing A] [--balance-couple]
//! [-o OUT.mech]`: an engine of several cylinders written as a mechanism file
//! (`mech_core::design::engine`), and its classical balance table (the primary and
//! secondary shaking forces and couples, exact and first order) on standard output.

use crate::{quantity, Failure};
use mech_core::design::engine::{
    balance_table, parse_firing, primary_couple_counterweights, table_text, Engine, Layout,
};
use mech_core::model::units::Dim;
use std::io::Write;
use std::path::PathBuf;

/// The layouts of `mech engine`.
#[derive(clap::ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub enum LayoutArg {
    /// Vertical cylinders in one line, a crank pin each.
    Inline,
    /// Two banks at ±bank/2 from the vertical, two cylinders on each crank pin.
    V,
    /// Opposed horizontal cylinders, a crank pin each.
    Boxer,
}

/// `mech engine` arguments.
#[derive(clap::Args, Debug)]
pub struct EngineArgs {
    /// The layout.
    #[arg(long, value_enum)]
    pub layout: LayoutArg,
    /// The number of cylinders (even for V and boxer).
    #[arg(long)]
    pub cylinders: usize,
    /// The angle between the banks of a V (deg, or `1.57rad`).
    #[arg(long, default_value = "90deg", allow_hyphen_values = true)]
    pub bank: String,
    /// A four-stroke firing order, cylinders numbered from 1 along the shaft (a V's left
    /// bank first on each pin): the throws that fire evenly in this order.
    #[arg(long, conflicts_with = "phases")]
    pub firing: Option<String>,
    /// The crank throws, one per crank pin (deg from cylinder 1's axis, counter-clockwise):
    /// n for in-line and boxer, n/2 for a V.
    #[arg(long, value_delimiter = ',', allow_hyphen_values = true)]
    pub phases: Option<Vec<String>>,
    /// The crank radius r (m, or `45mm`).
    #[arg(long, default_value = "45mm", allow_hyphen_values = true)]
    pub radius: String,
    /// The rod length l (m, or `150mm`).
    #[arg(long, default_value = "150mm", allow_hyphen_values = true)]
    pub rod: String,
    /// The reciprocating mass of each cylinder (kg, or `500g`).
    #[arg(long, default_value = "0.5kg", allow_hyphen_values = true)]
    pub mass: String,
    /// The distance between neighbouring crank pins along the shaft (m, or `90mm`).
    #[arg(long, default_value = "90mm", allow_hyphen_values = true)]
    pub spacing: String,
    /// Add two crankshaft counterweights at the end planes that cancel a primary couple
    /// rotating with the crank (a cross-plane V8's), at the crank radius.
    #[arg(long)]
    pub balance_couple: bool,
    /// Where to write the engine's mechanism file.
    #[arg(short = 'o', long = "output")]
    pub output: Option<PathBuf>,
}

/// Run `mech engine`.
pub fn run(args: EngineArgs, mut out: impl Write) -> Result<(), Failure> {
    let usage = |e: mech_core::MechError| Failure::usage(e.to_string());
    let layout = match args.layout {
        LayoutArg::Inline => Layout::Inline,
        LayoutArg::Boxer => Layout::Boxer,
        LayoutArg::V => Layout::Vee {
            bank: quantity::parse(&args.bank, Dim::ANGLE, "--bank")?,
        },
    };
    let mut e = Engine::new(layout, args.cylinders).map_err(usage)?;
    e.radius = quantity::parse(&args.radius, Dim::LENGTH, "--radius")?;
    e.rod = quantity::parse(&args.rod, Dim::LENGTH, "--rod")?;
    e.mass = quantity::parse(&args.mass, Dim::MASS, "--mass")?;
    e.spacing = quantity::parse(&args.spacing, Dim::LENGTH, "--spacing")?;
    if let Some(f) = &args.firing {
        let order = parse_firing(f, args.cylinders).map_err(usage)?;
        e = e.with_firing(&order).map_err(usage)?;
    }
    if let Some(p) = &args.phases {
        let throws = p
            .iter()
            .map(|t| {
                let t = t.trim();
                let with_unit = if t.chars().any(|c| c.is_alphabetic()) {
                    t.to_string()
                } else {
                    format!("{t}deg")
                };
                quantity::parse(&with_unit, Dim::ANGLE, "--phases")
            })
            .collect::<Result<Vec<f64>, Failure>>()?;
        e = e.with_throws(&throws).map_err(usage)?;
    }
    let steps = 360;
    let mut rows = vec![balance_table(&e, steps).map_err(usage)?];
    if args.balance_couple {
        let ends = (e.pins() as f64 - 1.0) / 2.0 * e.spacing;
        let w = primary_couple_counterweights(&e, &rows[0].exact[0], e.radius, (-ends, ends))
            .map_err(usage)?;
        e.counterweights = w.to_vec();
        let mut after = balance_table(&e, steps).map_err(usage)?;
        after.engine += " balanced";
        rows.push(after);
    }
    write!(out, "{}", table_text(&rows))?;
    if let Some(path) = &args.output {
        let text = e.to_mech("Engine").map_err(usage)?;
        std::fs::write(path, text)
            .map_err(|err| Failure::usage(format!("-o {}: {err}", path.display())))?;
    }
    out.flush()?;
    Ok(())
}
