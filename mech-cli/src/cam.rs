//! `mech cam FILE [--name lobe] [--points 360] [--svg profile.svg]`: a cam's profile for
//! drawing and manufacturing (`mech_core::elements::cam::Profile`, `docs/conventions.md#cams`): one
//! row per cam angle θ over a turn with the law's lift and its derivatives, the pitch and
//! contact points in the cam's own frame, the pressure angle and the cam surface's radius
//! of curvature; then, on standard error, the design figures (the largest pressure angle,
//! the smallest convex radius, undercut). `--svg` writes the cam surface as a closed path.

use crate::output::{Format, Writer};
use crate::{limits, source, Failure};
use mech_core::elements::cam::Profile;
use std::io::Write;
use std::path::PathBuf;

/// `mech cam` arguments.
#[derive(clap::Args, Debug)]
pub struct CamArgs {
    /// The mechanism file (`-` = standard input).
    pub file: PathBuf,
    /// The cam joint (omitted: the mechanism's only cam).
    #[arg(long)]
    pub name: Option<String>,
    /// Cam angles over the turn, evenly from θ = 0 (3 to 10⁶).
    #[arg(long, default_value_t = 360, allow_hyphen_values = true, value_parser = limits::points)]
    pub points: usize,
    /// Write the cam surface (contact points, mm, y up) as an SVG path to this file.
    #[arg(long)]
    pub svg: Option<PathBuf>,
    /// Output format.
    #[arg(long, value_enum, default_value_t = Format::Table)]
    pub format: Format,
}

/// The units of [`Profile::COLUMNS`] (the lift's depend on the follower).
fn units(rocker: bool) -> [&'static str; 10] {
    let (s, s1, s2) = if rocker {
        ("rad", "rad/rad", "rad/rad²")
    } else {
        ("m", "m/rad", "m/rad²")
    };
    ["rad", s, s1, s2, "m", "m", "m", "m", "rad", "m"]
}

/// Run `mech cam`.
pub fn run(args: CamArgs, out: impl Write) -> Result<(), Failure> {
    if args.points < 3 {
        return Err(Failure::usage(format!(
            "--points {}: a profile needs at least 3 points",
            args.points
        )));
    }
    if let Some(path) = &args.svg {
        limits::writable(path, "--svg", "svg")?;
    }
    let m = source::load(&args.file)?;
    let (name, g) = m
        .cam(args.name.as_deref())
        .map_err(|e| Failure::usage(format!("mech cam: {e}")))?;
    let p = &g.profile;
    let names: Vec<String> = Profile::COLUMNS.iter().map(|c| c.to_string()).collect();
    let mut w = Writer::new(out, args.format, &names, &units(p.rocker.is_some()))?;
    for row in p.table(args.points) {
        w.row(&row)?;
    }
    w.finish()?;
    let c = p.check(args.points);
    eprintln!("cam `{name}`: {c}");
    if let Some(path) = &args.svg {
        let r = p
            .points(args.points)
            .iter()
            .map(|q| q.contact[0].hypot(q.contact[1]))
            .fold(0.0f64, f64::max)
            * 1e3
            * 1.1;
        let svg = format!(
            "<svg xmlns=\"http://www.w3.org/2000/svg\" viewBox=\"{:.3} {:.3} {:.3} {:.3}\" width=\"400\" height=\"400\">\n<!-- cam `{name}`: its surface in its own frame, mm (y up); the centre at the origin -->\n<path d=\"{}\" fill=\"#dde6f0\" stroke=\"#3b6ea8\" stroke-width=\"{:.3}\"/>\n<circle cx=\"0\" cy=\"0\" r=\"{:.3}\" fill=\"#3b6ea8\"/>\n</svg>\n",
            -r,
            -r,
            2.0 * r,
            2.0 * r,
            p.svg_path(args.points),
            r / 200.0,
            r / 60.0
        );
        limits::write_file(path, &svg, "--svg", "svg")?;
    }
    Ok(())
}
