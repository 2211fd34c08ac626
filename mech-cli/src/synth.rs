//! `mech synth path TARGETS.csv [--closed|--open] [--timing free|prescribed]
//! [--topology four-bar|six-bar] [--seed N] [--evaluations N] [--transmission DEG]
//! [--ratio R] -o OUT.mech` (SPEC §3f, `docs/cli.md#synth-path`): the four-bar whose
//! coupler point P passes nearest to the targets, by `mech_core::design::synthesis::path`
//! (differential evolution, then a Levenberg–Marquardt polish), or the Stephenson III
//! six-bar of `mech_core::design::synthesis::six_bar`. Prints one row (`error`, `rms`,
//! `transmission`, `ratio`), writes OUT.mech (the SPEC names O2, O4, A, B, P, input O2;
//! a six-bar adds C, D and O6), and reports the search's evaluations per second on
//! standard error.

use crate::output::{Format, Writer};
use crate::{limits, Failure};
use mech_core::design::synthesis::path::{self, PathOptions, PathProblem};
use mech_core::design::synthesis::six_bar;
use std::io::Write;
use std::path::{Path, PathBuf};

/// The largest budget of `--evaluations`.
pub const MAX_EVALUATIONS: usize = 1_000_000_000;

/// How the targets are timed.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, clap::ValueEnum)]
pub enum Timing {
    /// Each target meets the nearest point of the coupler curve (SPEC §3f).
    #[default]
    Free,
    /// Target i meets P at the crank angle of its `angle` column.
    Prescribed,
}

/// The linkage synthesised.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, clap::ValueEnum)]
pub enum Topology {
    /// A four-bar with a coupler point.
    #[default]
    FourBar,
    /// A Stephenson III six-bar: the four-bar's coupler point C drives a second dyad
    /// C D O6, the tracer P on the link C D (closed paths).
    SixBar,
}

/// `mech synth path` arguments.
#[derive(clap::Args, Debug)]
pub struct PathArgs {
    /// The targets: a CSV file with columns `x`, `y` (m) and, with prescribed timing,
    /// `angle` (rad) or `angle_deg`: the crank angle O2 → A from the frame line O2 → O4.
    /// Lines starting with `#` are comments.
    pub targets: PathBuf,
    /// Where to write the four-bar (a `.mech` file).
    #[arg(short = 'o', long = "output")]
    pub output: PathBuf,
    /// A closed path: the crank turns fully (the default).
    #[arg(long, conflicts_with = "open")]
    pub closed: bool,
    /// An open path: the crank rocks within one arc of its circle.
    #[arg(long)]
    pub open: bool,
    /// Free timing (each target meets the curve anywhere) or prescribed (the `angle`
    /// column).
    #[arg(long, value_enum, default_value_t = Timing::Free)]
    pub timing: Timing,
    /// The linkage: a four-bar, or a Stephenson III six-bar (closed paths).
    #[arg(long, value_enum, default_value_t = Topology::FourBar)]
    pub topology: Topology,
    /// The seed of the search: one seed, one result, whatever the number of threads.
    #[arg(long, default_value_t = 1)]
    pub seed: u64,
    /// The global search's budget, evaluations of a candidate linkage.
    #[arg(long, default_value = "200000", value_parser = evaluations)]
    pub evaluations: usize,
    /// The smallest transmission angle allowed over the motion, degrees, from 0 to 89.
    #[arg(long, default_value = "30", value_parser = transmission)]
    pub transmission: f64,
    /// The largest ratio of the longest link to the shortest (frame included), ≥ 1.
    #[arg(long, default_value = "10", value_parser = ratio)]
    pub ratio: f64,
    /// Output format of the result row.
    #[arg(long, value_enum, default_value_t = Format::Table)]
    pub format: Format,
}

fn evaluations(text: &str) -> Result<usize, String> {
    limits::count(text, path::POPULATION, MAX_EVALUATIONS, "evaluations")
}

fn transmission(text: &str) -> Result<f64, String> {
    limits::number(text, 0.0, 89.0, "the bound in degrees")
}

fn ratio(text: &str) -> Result<f64, String> {
    limits::number(text, 1.0, 1e6, "the ratio")
}

/// The targets of a file: (x, y) in m, and their crank angles in rad if it has them.
pub type Targets = (Vec<[f64; 2]>, Option<Vec<f64>>);

/// The targets of a CSV text (`origin` names it in messages): (x, y) in m, and the
/// angles in rad when the file has an `angle` (rad) or `angle_deg` column.
pub fn read_targets(text: &str, origin: &str) -> Result<Targets, Failure> {
    let bad = |m: String| Failure::usage(format!("{origin}: {m}"));
    let mut r = csv::ReaderBuilder::new()
        .trim(csv::Trim::All)
        .comment(Some(b'#'))
        .flexible(true)
        .from_reader(text.as_bytes());
    let headers = r.headers().map_err(|e| bad(e.to_string()))?.clone();
    let find = |name: &str| headers.iter().position(|h| h == name);
    let (Some(ix), Some(iy)) = (find("x"), find("y")) else {
        let names: Vec<&str> = headers.iter().collect();
        return Err(bad(format!(
            "the header must name the columns `x` and `y` (m){}; found `{}`",
            ", and `angle` (rad) or `angle_deg` for prescribed timing",
            names.join(", ")
        )));
    };
    let angle = match (find("angle"), find("angle_deg")) {
        (Some(_), Some(_)) => {
            return Err(bad(
                "both `angle` and `angle_deg`: give the crank angles once".into(),
            ))
        }
        (Some(i), None) => Some((i, 1.0)),
        (None, Some(i)) => Some((i, std::f64::consts::PI / 180.0)),
        (None, None) => None,
    };
    let (mut targets, mut angles) = (Vec::new(), Vec::new());
    let mut record = csv::StringRecord::new();
    loop {
        match r.read_record(&mut record) {
            Ok(true) => {}
            Ok(false) => break,
            Err(e) => return Err(bad(e.to_string())),
        }
        let line = record.position().map_or(0, |p| p.line());
        if record.len() != headers.len() {
            return Err(bad(format!(
                "line {line}: {} field(s), but the header has {}",
                record.len(),
                headers.len()
            )));
        }
        if targets.len() >= path::MAX_TARGETS {
            return Err(bad(format!(
                "more than {} targets; thin the path out",
                path::MAX_TARGETS
            )));
        }
        let num = |i: usize| -> Result<f64, Failure> {
            let field = &record[i];
            let x: f64 = field.parse().map_err(|_| {
                bad(format!(
                    "line {line}, column `{}` (`{}`): not a number",
                    &headers[i],
                    field.chars().take(40).collect::<String>()
                ))
            })?;
            if !x.is_finite() {
                return Err(bad(format!(
                    "line {line}, column `{}` (`{field}`): not a finite number",
                    &headers[i]
                )));
            }
            Ok(x)
        };
        targets.push([num(ix)?, num(iy)?]);
        if let Some((i, scale)) = angle {
            angles.push(num(i)? * scale);
        }
    }
    Ok((targets, angle.map(|_| angles)))
}

/// Run `mech synth path`.
pub fn run_path(args: PathArgs, out: impl Write) -> Result<(), Failure> {
    limits::writable(&args.output, "-o", "mech")?;
    let origin = args.targets.display().to_string();
    let text = limits::read_text(&args.targets, limits::TABLE_BYTES, "the targets file")?;
    let (targets, angles) = read_targets(&text, &origin)?;
    let angles = match (args.timing, angles) {
        (Timing::Prescribed, None) => {
            return Err(Failure::usage(format!(
                "{origin}: --timing prescribed needs the crank angle of each target: a column \
                 `angle` (rad) or `angle_deg`, measured from the frame line O2 → O4"
            )))
        }
        (Timing::Prescribed, Some(a)) => Some(a),
        (Timing::Free, Some(_)) => {
            eprintln!("{origin}: the angle column is not used with free timing (--timing prescribed uses it)");
            None
        }
        (Timing::Free, None) => None,
    };
    let problem = PathProblem {
        targets,
        angles,
        closed: !args.open,
    };
    let options = PathOptions {
        seed: args.seed,
        evaluations: args.evaluations,
        transmission: args.transmission.to_radians(),
        ratio: args.ratio,
    };
    let bar = indicatif::ProgressBar::new(args.evaluations as u64);
    bar.set_style(
        indicatif::ProgressStyle::with_template(
            "{bar:40} {pos}/{len} evaluations, {per_sec}, eta {eta}",
        )
        .expect("template"),
    );
    let start = std::time::Instant::now();
    let progress = |n: usize| bar.set_position(n as u64);
    let result = match args.topology {
        Topology::FourBar => path::synthesize(&problem, &options, progress).map(Found::Four),
        Topology::SixBar => six_bar::synthesize(&problem, &options, progress).map(Found::Six),
    };
    bar.finish_and_clear();
    let found = result.map_err(|e| match e {
        path::PathError::Infeasible { .. } => Failure::mechanism(format!("{origin}: {e}")),
        _ => Failure::usage(format!("{origin}: {e}")),
    })?;
    let s = found.summary();
    let wall = start.elapsed().as_secs_f64();
    let n = problem.targets.len();
    let names: Vec<String> = ["error", "rms", "transmission", "ratio"]
        .iter()
        .map(|s| s.to_string())
        .collect();
    let mut w = Writer::new(out, args.format, &names, &["m²", "m", "rad", "1"])?;
    w.row(&[
        s.error,
        (s.error / n as f64).sqrt(),
        s.transmission,
        s.ratio,
    ])?;
    w.finish()?;
    let [r1, r2, r3, r4] = s.lengths[..4] else {
        unreachable!("a four-bar's lengths come first")
    };
    eprintln!(
        "{}: frame {} m, crank {} m, coupler {} m, rocker {} m{}; {}",
        found.name(),
        limits::show(r1),
        limits::show(r2),
        limits::show(r3),
        limits::show(r4),
        match s.lengths[4..] {
            [r5, r6] => format!(
                ", C to D {} m, second rocker O6 to D {} m",
                limits::show(r5),
                limits::show(r6)
            ),
            _ => String::new(),
        },
        match s.crank_range {
            None => "the crank turns fully".to_string(),
            Some((a, b)) => format!(
                "the crank rocks from {:.2}° to {:.2}° (from the frame line O2 → O4)",
                a.to_degrees(),
                b.to_degrees()
            ),
        }
    );
    eprintln!(
        "search: {} evaluations in {:.2} s, {:.0} evaluations/s on {} thread(s); polish: {} residual evaluations; {:.2} s in all",
        s.evaluations,
        s.search_seconds,
        s.evaluations as f64 / s.search_seconds,
        rayon::current_num_threads(),
        s.polish_evaluations,
        wall
    );
    let doc = format!(
        "{} from `mech synth path {}{} --seed {}`: E = {:e} m² over {n} targets ({} timing, {} path).",
        found.title(),
        Path::new(&args.targets)
            .file_name()
            .map_or(origin.clone(), |f| f.to_string_lossy().into_owned()),
        if args.topology == Topology::SixBar {
            " --topology six-bar"
        } else {
            ""
        },
        args.seed,
        s.error,
        if problem.angles.is_some() { "prescribed" } else { "free" },
        if problem.closed { "closed" } else { "open" },
    );
    limits::write_file(&args.output, &found.to_mech(&doc), "-o", "mech")
}

/// What a path synthesis found: a four-bar or a six-bar.
enum Found {
    Four(path::PathSynthesis),
    Six(six_bar::SixBarSynthesis),
}

/// The figures `mech synth path` prints, whatever the linkage.
struct Summary {
    error: f64,
    transmission: f64,
    ratio: f64,
    lengths: Vec<f64>,
    crank_range: Option<(f64, f64)>,
    evaluations: usize,
    search_seconds: f64,
    polish_evaluations: usize,
}

impl Found {
    fn summary(&self) -> Summary {
        match self {
            Found::Four(s) => Summary {
                error: s.error,
                transmission: s.transmission,
                ratio: s.ratio,
                lengths: s.four_bar.lengths().to_vec(),
                crank_range: s.crank_range,
                evaluations: s.evaluations,
                search_seconds: s.search_seconds,
                polish_evaluations: s.polish_evaluations,
            },
            Found::Six(s) => Summary {
                error: s.error,
                transmission: s.transmission,
                ratio: s.ratio,
                lengths: s.six_bar.lengths().to_vec(),
                crank_range: None,
                evaluations: s.evaluations,
                search_seconds: s.search_seconds,
                polish_evaluations: s.polish_evaluations,
            },
        }
    }

    fn name(&self) -> &'static str {
        match self {
            Found::Four(_) => "four-bar",
            Found::Six(_) => "six-bar (Stephenson III)",
        }
    }

    fn title(&self) -> &'static str {
        match self {
            Found::Four(_) => "Four-bar",
            Found::Six(_) => "Stephenson III six-bar",
        }
    }

    fn to_mech(&self, doc: &str) -> String {
        match self {
            Found::Four(s) => s.four_bar.to_mech("PathGenerator", doc),
            Found::Six(s) => s.six_bar.to_mech("PathGenerator", doc),
        }
    }
}
