//! `mech shaking FILE --speed QD [--from A --to B --steps N] [--svg FILE]`: the shaking
//! force and moment on the frame over a cycle (SPEC 3g, `mech_core::design::balance`), one
//! row per input value (the grid of `mech sweep`), with the couples about the x and y axes
//! (`shaking.mx`, `shaking.my`) when some link is out of the plane z = 0 (`plane: z`); the
//! peaks, RMS values and the primary and secondary harmonics on standard error; a polar
//! diagram of the force as SVG.

use crate::output::{Format, Writer};
use crate::{limits, quantity, source, Failure};
use mech_core::design::balance::{shaking_cycle, ShakingCycle, ShakingSummary};
use std::io::Write;
use std::path::PathBuf;

/// `mech shaking` arguments.
#[derive(clap::Args, Debug)]
pub struct ShakingArgs {
    /// The mechanism file (`-` = standard input).
    pub file: PathBuf,
    /// Input speeds q̇, one per input (rad/s, or `3000rpm`), constant over the cycle.
    #[arg(
        long = "speed",
        required = true,
        value_delimiter = ',',
        allow_hyphen_values = true
    )]
    pub speed: Vec<String>,
    /// First value of the first input.
    #[arg(long, default_value = "0", allow_hyphen_values = true)]
    pub from: String,
    /// Last value of the first input (included); the cycle is from..to.
    #[arg(long, default_value = "2pi", allow_hyphen_values = true)]
    pub to: String,
    /// Number of steps (rows = steps + 1), at most 10⁸.
    #[arg(long, default_value_t = 360, value_parser = limits::steps)]
    pub steps: usize,
    /// Write a polar diagram of the shaking force (its tip over the cycle) to this SVG file.
    #[arg(long)]
    pub svg: Option<PathBuf>,
    /// Output format.
    #[arg(long, value_enum, default_value_t = Format::Table)]
    pub format: Format,
}

/// Run `mech shaking`.
pub fn run(args: ShakingArgs, out: impl Write) -> Result<(), Failure> {
    let m = source::load(&args.file)?;
    let model = m.model();
    let (d, _) = quantity::input_dims(model, 0);
    let from = quantity::parse(&args.from, d, "--from")?;
    let to = quantity::parse(&args.to, d, "--to")?;
    if !(to - from).is_finite() {
        return Err(Failure::usage("--from/--to: the range overflows f64"));
    }
    let qd = quantity::per_input(&args.speed, model, 1, "--speed", 0.0)?;
    let rest = vec![0.0; m.dof()];
    let cycle = shaking_cycle(&m, (from, to, args.steps), &rest, &qd)
        .map_err(|e| Failure::mechanism(e.to_string()))?;
    let summary = cycle.summary();
    eprint!("{}", summary_text(&summary));
    if let Some(path) = &args.svg {
        std::fs::write(path, polar_svg(&cycle))
            .map_err(|e| Failure::usage(format!("--svg {}: {e}", path.display())))?;
    }
    let planes = model.has_planes();
    let mut names: Vec<String> = ["q", "shaking.fx", "shaking.fy", "shaking.moment"]
        .iter()
        .map(|s| s.to_string())
        .collect();
    let unit_q = if d == mech_core::model::units::Dim::ANGLE {
        "rad"
    } else {
        "m"
    };
    let mut units = vec![unit_q, "N", "N", "N·m"];
    if planes {
        names.extend(["shaking.mx".to_string(), "shaking.my".to_string()]);
        units.extend(["N·m", "N·m"]);
    }
    let mut w = Writer::new(out, args.format, &names, &units)?;
    for (q, s) in cycle.q.iter().zip(&cycle.shaking) {
        let mut row = vec![*q, s.force.x, s.force.y, s.moment];
        if planes {
            row.extend([s.mx, s.my]);
        }
        w.row(&row)?;
    }
    w.finish()?;
    Ok(())
}

/// The summary's lines: peaks, RMS, and a, b of F_x and F_y for orders 1 and 2.
pub fn summary_text(s: &ShakingSummary) -> String {
    let mut t = format!(
        "shaking force:  peak {:.12e} N, rms {:.12e} N\nshaking moment: peak {:.12e} N·m, rms {:.12e} N·m\n",
        s.peak_force, s.rms_force, s.peak_moment, s.rms_moment
    );
    if s.peak_couple > 0.0 {
        t += &format!(
            "shaking couple about x and y: peak {:.12e} N·m\n",
            s.peak_couple
        );
    }
    for h in &s.harmonics {
        let name = if h.order == 1 { "primary" } else { "secondary" };
        t += &format!(
            "{name} (order {}): fx = {:.12e} cos + {:.12e} sin N, fy = {:.12e} cos + {:.12e} sin N\n",
            h.order, h.fx[0], h.fx[1], h.fy[0], h.fy[1]
        );
        if s.peak_couple > 0.0 {
            t += &format!(
                "{name} couple (order {}): mx = {:.12e} cos + {:.12e} sin N·m, my = {:.12e} cos + {:.12e} sin N·m\n",
                h.order, h.mx[0], h.mx[1], h.my[0], h.my[1]
            );
        }
    }
    t
}

/// A polar diagram of the shaking force: axes through the origin, circles at the peak and
/// its halves, and the path of the force's tip over the cycle, 480 px square.
pub fn polar_svg(c: &ShakingCycle) -> String {
    let peak = c
        .shaking
        .iter()
        .map(|s| s.force.norm())
        .fold(0.0, f64::max)
        .max(f64::MIN_POSITIVE);
    let (size, half) = (480.0, 240.0);
    let k = 200.0 / peak;
    let px = |x: f64, y: f64| (half + k * x, half - k * y);
    let mut s = format!(
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{size}\" height=\"{size}\" viewBox=\"0 0 {size} {size}\">\n<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n"
    );
    for f in [0.5, 1.0] {
        s += &format!(
            "<circle cx=\"{half}\" cy=\"{half}\" r=\"{:.2}\" fill=\"none\" stroke=\"#bbb\"/>\n",
            200.0 * f
        );
    }
    s += &format!(
        "<line x1=\"20\" y1=\"{half}\" x2=\"460\" y2=\"{half}\" stroke=\"#888\"/>\n<line x1=\"{half}\" y1=\"20\" x2=\"{half}\" y2=\"460\" stroke=\"#888\"/>\n"
    );
    let pts: Vec<String> = c
        .shaking
        .iter()
        .map(|sh| {
            let (x, y) = px(sh.force.x, sh.force.y);
            format!("{x:.2},{y:.2}")
        })
        .collect();
    s += &format!(
        "<polyline points=\"{}\" fill=\"none\" stroke=\"#c00\" stroke-width=\"1.5\"/>\n",
        pts.join(" ")
    );
    s += &format!(
        "<text x=\"250\" y=\"36\" font-family=\"sans-serif\" font-size=\"12\">|F| max {peak:.4e} N (outer circle)</text>\n<text x=\"444\" y=\"{}\" font-family=\"sans-serif\" font-size=\"12\">Fx</text>\n<text x=\"{}\" y=\"16\" font-family=\"sans-serif\" font-size=\"12\">Fy</text>\n</svg>\n",
        half - 6.0,
        half + 6.0
    );
    s
}
