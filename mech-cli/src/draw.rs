//! `mech draw FILE --at Q -o out.svg`: the linkage at one input as SVG (links, pins,
//! slider blocks and guides, slots, hatched ground pivots, point names), with the paths
//! of chosen points over a turn (`--path P`) and the reaction arrows (`--forces`).
//! A spatial mechanism (`space` first) is drawn in an isometric projection
//! ([`crate::spatial::frame`]).
//! `mech animate FILE -o out.svg`: the linkage moving over a range of the first input, as
//! an SVG that animates itself (SMIL) in any browser.

use crate::loads::LoadSet;
use crate::{limits, quantity, scene, source, svg, Failure};
use mech_core::Mechanism;
use std::path::PathBuf;

/// `mech draw` arguments.
#[derive(clap::Args, Debug)]
pub struct DrawArgs {
    /// The mechanism file (`-` = standard input).
    pub file: PathBuf,
    /// Input values q, one per input (rad or m; `deg`, `mm` allowed).
    #[arg(
        long = "at",
        required = true,
        value_delimiter = ',',
        allow_hyphen_values = true
    )]
    pub at: Vec<String>,
    /// The SVG file to write.
    #[arg(short = 'o', long = "output")]
    pub output: PathBuf,
    /// Draw the path of this point over a turn of the first input. Repeatable.
    #[arg(long = "path")]
    pub path: Vec<String>,
    /// Draw the reaction at every joint (force by its first link on its second) as an
    /// arrow, at --speed, --accel and --load.
    #[arg(long)]
    pub forces: bool,
    /// Input speeds for --forces (rad/s or m/s; `rpm` allowed).
    #[arg(long = "speed", value_delimiter = ',', allow_hyphen_values = true)]
    pub speed: Vec<String>,
    /// Input accelerations for --forces.
    #[arg(long = "accel", value_delimiter = ',', allow_hyphen_values = true)]
    pub accel: Vec<String>,
    /// Loads for --forces: NAME=VALUE or NAME=@table.csv. Repeatable.
    #[arg(long = "load", allow_hyphen_values = true)]
    pub load: Vec<String>,
    /// Picture width, px (1 to 100000).
    #[arg(long, default_value_t = 800.0, allow_hyphen_values = true, value_parser = limits::pixels)]
    pub width: f64,
    /// Smallest picture height, px (the drawing's aspect ratio decides above it).
    #[arg(long, default_value_t = 200.0, allow_hyphen_values = true, value_parser = limits::pixels)]
    pub height: f64,
}

/// `mech animate` arguments.
#[derive(clap::Args, Debug)]
pub struct AnimateArgs {
    /// The mechanism file (`-` = standard input).
    pub file: PathBuf,
    /// The SVG file to write.
    #[arg(short = 'o', long = "output")]
    pub output: PathBuf,
    /// First value of the first input (default 0).
    #[arg(long, allow_hyphen_values = true)]
    pub from: Option<String>,
    /// Last value of the first input (default: a full turn of a revolute input, or the
    /// drawing's size for a prismatic one).
    #[arg(long, allow_hyphen_values = true)]
    pub to: Option<String>,
    /// The other inputs' values (several DOF), in order after the first.
    #[arg(long = "rest", value_delimiter = ',', allow_hyphen_values = true)]
    pub rest: Vec<String>,
    /// Number of frames (2 to 10⁴).
    #[arg(long, default_value_t = 120, allow_hyphen_values = true, value_parser = limits::frames)]
    pub frames: usize,
    /// Duration of one loop, s (0.001 to 86400).
    #[arg(long, default_value_t = 4.0, allow_hyphen_values = true, value_parser = limits::seconds)]
    pub seconds: f64,
    /// Draw the path of this point under the animation. Repeatable.
    #[arg(long = "path")]
    pub path: Vec<String>,
    /// Picture width, px (1 to 100000).
    #[arg(long, default_value_t = 800.0, allow_hyphen_values = true, value_parser = limits::pixels)]
    pub width: f64,
    /// Smallest picture height, px.
    #[arg(long, default_value_t = 200.0, allow_hyphen_values = true, value_parser = limits::pixels)]
    pub height: f64,
}

/// `n` + 1 inputs from `from` to `to` for the first input, the rest fixed.
pub fn range(rest: &[f64], from: f64, to: f64, n: usize) -> Vec<Vec<f64>> {
    (0..=n)
        .map(|k| {
            let mut q = rest.to_vec();
            q[0] = from + (to - from) * k as f64 / n.max(1) as f64;
            q
        })
        .collect()
}

/// The default range of the first input: a turn (0 to 2π) for a revolute input, ± the
/// drawing's size around the drawing for a prismatic one.
pub fn default_range(m: &Mechanism) -> (f64, f64) {
    let model = m.model();
    if quantity::input_dims(model, 0).0 == mech_core::model::units::Dim::ANGLE {
        (0.0, 2.0 * std::f64::consts::PI)
    } else {
        let s = 0.25 * scene::size(model);
        (-s, s)
    }
}

/// The first input's range and the other inputs from the arguments.
pub fn inputs(
    m: &Mechanism,
    from: &Option<String>,
    to: &Option<String>,
    rest: &[String],
) -> Result<(f64, f64, Vec<f64>), Failure> {
    let model = m.model();
    let (d, _) = quantity::input_dims(model, 0);
    let (a0, b0) = default_range(m);
    let a = from
        .as_deref()
        .map(|t| quantity::parse(t, d, "--from"))
        .transpose()?
        .unwrap_or(a0);
    let b = to
        .as_deref()
        .map(|t| quantity::parse(t, d, "--to"))
        .transpose()?
        .unwrap_or(b0);
    if !(b - a).is_finite() {
        return Err(Failure::usage(format!(
            "--from {} --to {}: the range overflows f64; give a narrower range",
            from.as_deref().unwrap_or("(default)"),
            to.as_deref().unwrap_or("(default)")
        )));
    }
    if rest.len() + 1 != m.dof() {
        return Err(Failure::usage(format!(
            "--rest: {} value(s) for the {} input(s) after the first",
            rest.len(),
            m.dof() - 1
        )));
    }
    let mut q = vec![a];
    for (k, t) in rest.iter().enumerate() {
        q.push(quantity::parse(
            t,
            quantity::input_dims(model, k + 1).0,
            "--rest",
        )?);
    }
    Ok((a, b, q))
}

fn write(path: &std::path::Path, text: &str) -> Result<(), Failure> {
    limits::write_file(path, text, "-o", "svg")
}

/// Run `mech draw`.
pub fn draw(args: DrawArgs) -> Result<(), Failure> {
    limits::writable(&args.output, "-o", "svg")?;
    let m = match source::load_any(&args.file)? {
        source::Any::Planar(m) => m,
        source::Any::Spatial(m) => {
            return write(&args.output, &crate::spatial::draw(&m, &args)?);
        }
    };
    let model = m.model();
    let q = quantity::per_input(&args.at, model, 0, "--at", 0.0)?;
    let frame = scene::frame(&m, &q)?;
    let mut extra = Vec::new();
    let (a, b) = default_range(&m);
    let mut turn = range(&q, a, b, 360);
    for p in &args.path {
        extra.push(scene::path(&m, p, &turn)?);
    }
    turn.clear();
    if args.forces {
        let qd = quantity::per_input(&args.speed, model, 1, "--speed", 0.0)?;
        let qdd = quantity::per_input(&args.accel, model, 2, "--accel", 0.0)?;
        let loads = LoadSet::parse(&args.load, model)?.at(&m, q[0]);
        extra.extend(scene::arrows(
            &m,
            &q,
            &qd,
            &qdd,
            &loads,
            0.25 * scene::size(model),
        )?);
    }
    let (text, _) = svg::still(&frame, &extra, args.width, args.height);
    write(&args.output, &text)
}

/// Run `mech animate`.
pub fn animate(args: AnimateArgs) -> Result<(), Failure> {
    if args.frames < 2 || !(args.seconds > 0.0) {
        return Err(Failure::usage(format!(
            "--frames {} and --seconds {}: need at least 2 frames and a positive duration",
            args.frames, args.seconds
        )));
    }
    limits::writable(&args.output, "-o", "svg")?;
    let m = match source::load_any(&args.file)? {
        source::Any::Planar(m) => m,
        source::Any::Spatial(m) => {
            return write(&args.output, &crate::spatial::animate(&m, &args)?)
        }
    };
    let (a, b, q) = inputs(&m, &args.from, &args.to, &args.rest)?;
    let qs = range(&q, a, b, args.frames - 1);
    let frames = scene::frames(&m, &qs)?;
    let extra: Vec<_> = args
        .path
        .iter()
        .map(|p| scene::path(&m, p, &qs))
        .collect::<Result<_, _>>()?;
    let (text, _) = svg::animated(&frames, &extra, args.width, args.height, args.seconds);
    write(&args.output, &text)
}
