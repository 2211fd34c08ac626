//! `mech synth function PAIRS.csv -o OUT.mech [--frame D]` and `mech synth motion
//! POSES.csv -o OUT.mech [--circle-points XA,YA,XB,YB]` (SPEC §3f): four-bars by the exact
//! methods of `mech_core::design::synthesis` — Freudenstein's equation for three pairs of
//! input and output angles (least squares beyond), Burmester theory for three to five
//! poses of the coupler (least squares beyond). OUT.mech is an ordinary mechanism file
//! with the SPEC names (`O2`, `O4`, `A`, `B`, `P`, input `O2`, whose q is the crank's
//! absolute angle).
//!
//! Standard output: one row per target with what the four-bar does there; standard error:
//! the method, the numbers it chose, the link lengths and `error`.

use crate::output::{Format, Writer};
use crate::{limits, quantity, Failure};
use mech_core::design::synthesis::burmester::{self, MotionSynthesis};
use mech_core::design::synthesis::freudenstein::{self, output_angle};
use mech_core::design::synthesis::FourBar;
use mech_core::model::units::Dim;
use std::io::Write;
use std::path::{Path, PathBuf};

/// The most rows a targets file may have (least squares beyond is no better for more).
pub const ROWS: usize = 10_000;

/// `mech synth function` arguments.
#[derive(clap::Args, Debug)]
pub struct FunctionArgs {
    /// The pairs: a CSV file with the columns `input` and `output` (rad; `input_deg`,
    /// `output_deg` in degrees), the angles of O2 → A and of O4 → B counter-clockwise from
    /// the frame line O2 → O4. Three pairs are met exactly, more by least squares.
    pub pairs: PathBuf,
    /// Where to write the four-bar (`.mech`).
    #[arg(short = 'o', long = "output")]
    pub output: PathBuf,
    /// The frame length |O2O4| (m, or with a unit: `200mm`); O2 at the origin, O4 on +x.
    #[arg(long, default_value = "1", allow_hyphen_values = true)]
    pub frame: String,
    /// Output format of the table of pairs.
    #[arg(long, value_enum, default_value_t = Format::Table)]
    pub format: Format,
}

/// `mech synth motion` arguments.
#[derive(clap::Args, Debug)]
pub struct MotionArgs {
    /// The poses: a CSV file with the columns `x`, `y` (m: P's position) and `angle` (rad;
    /// `angle_deg` in degrees: the direction of A → B). Three to five are met exactly
    /// (Burmester), more by least squares.
    pub poses: PathBuf,
    /// Where to write the four-bar (`.mech`).
    #[arg(short = 'o', long = "output")]
    pub output: PathBuf,
    /// Three poses only: the circle points of A and B in the moving frame (m; origin P, x
    /// along the pose's angle), `XA,YA,XB,YB`. Default: the best pair on one line along the
    /// pose's angle (so that A → B points along it).
    #[arg(
        long = "circle-points",
        value_delimiter = ',',
        allow_hyphen_values = true
    )]
    pub circle_points: Vec<String>,
    /// Output format of the table of poses.
    #[arg(long, value_enum, default_value_t = Format::Table)]
    pub format: Format,
}

/// The rows of a CSV file of targets with the named columns (in any order); an angle
/// column may be given in degrees as `<name>_deg`. Every other shape is a usage error that
/// names the fix.
pub fn read_targets(
    path: &Path,
    names: &[&str],
    angles: &[&str],
) -> Result<Vec<Vec<f64>>, Failure> {
    let text = limits::read_text(path, limits::TABLE_BYTES, "the targets file")?;
    parse_targets(&text, names, angles, &path.display().to_string())
}

/// [`read_targets`] on text (`origin` names it in messages).
pub fn parse_targets(
    text: &str,
    names: &[&str],
    angles: &[&str],
    origin: &str,
) -> Result<Vec<Vec<f64>>, Failure> {
    let bad = |m: String| Failure::usage(format!("{origin}: {m}"));
    let want = names.join(", ");
    let mut r = csv::ReaderBuilder::new()
        .trim(csv::Trim::All)
        .flexible(true)
        .from_reader(text.as_bytes());
    let headers = r.headers().map_err(|e| bad(e.to_string()))?.clone();
    // For each wanted name: its column and its scale.
    let mut cols = Vec::new();
    for name in names {
        let deg = format!("{name}_deg");
        let found: Vec<(usize, f64)> = headers
            .iter()
            .enumerate()
            .filter_map(|(i, h)| {
                if h == *name {
                    Some((i, 1.0))
                } else if angles.contains(name) && h == deg {
                    Some((i, std::f64::consts::PI / 180.0))
                } else {
                    None
                }
            })
            .collect();
        match found.as_slice() {
            [one] => cols.push(*one),
            [] => {
                let have: Vec<&str> = headers.iter().collect();
                let hint = if have.iter().any(|h| h.contains([';', '\t'])) {
                    " (columns are separated by commas)"
                } else {
                    ""
                };
                return Err(bad(format!(
                    "no column `{name}`{}: the header must name the columns {want}, found `{}`{hint}",
                    if angles.contains(name) {
                        format!(" (or `{deg}`)")
                    } else {
                        String::new()
                    },
                    have.join(", ")
                )));
            }
            _ => {
                return Err(bad(format!(
                    "the column `{name}` is given twice; name each column once"
                )))
            }
        }
    }
    if headers.len() != names.len() {
        return Err(bad(format!(
            "{} columns (`{}`), but a targets file has exactly the columns {want}",
            headers.len(),
            headers.iter().collect::<Vec<_>>().join(", ")
        )));
    }
    let mut rows = Vec::new();
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
        if rows.len() == ROWS {
            return Err(bad(format!(
                "more than {ROWS} rows; synthesis needs three to a few dozen targets: thin the file"
            )));
        }
        let mut row = Vec::with_capacity(names.len());
        for (name, &(c, scale)) in names.iter().zip(&cols) {
            let field = &record[c];
            let x: f64 = field.parse().map_err(|_| {
                bad(format!(
                    "line {line}, column `{name}` (`{}`): not a number",
                    field.chars().take(40).collect::<String>()
                ))
            })?;
            if !x.is_finite() {
                return Err(bad(format!(
                    "line {line}, column `{name}` (`{field}`): not a finite number"
                )));
            }
            row.push(x * scale);
        }
        rows.push(row);
    }
    Ok(rows)
}

/// The link lengths as a message: frame, crank, coupler, rocker.
fn lengths(fb: &FourBar) -> String {
    let r = fb.lengths();
    format!(
        "links: frame {} m, crank {} m, coupler {} m, rocker {} m ({})",
        limits::show(r[0]),
        limits::show(r[1]),
        limits::show(r[2]),
        limits::show(r[3]),
        if fb.crank_turns() {
            "the crank turns fully"
        } else if fb.grashof() {
            "Grashof, the crank does not turn fully"
        } else {
            "not Grashof: the crank rocks"
        }
    )
}

fn usage(e: mech_core::MechError) -> Failure {
    Failure::usage(e.to_string())
}

/// Write the four-bar's file once it passes the loader's checks (a drawing at a dead
/// point, say, would not): status 1 with the check's message otherwise.
fn write(path: &Path, text: &str) -> Result<(), Failure> {
    if let Err(e) = mech_core::Mechanism::from_dsl(text) {
        return Err(Failure::mechanism(format!(
            "the four-bar found does not pass the checks of a mechanism file, not written: {e}"
        )));
    }
    limits::write_file(path, text, "-o", "mech")
}

/// Run `mech synth function`.
pub fn function(args: FunctionArgs, out: impl Write) -> Result<(), Failure> {
    limits::writable(&args.output, "-o", "mech")?;
    let frame = quantity::parse(&args.frame, Dim::LENGTH, "--frame")?;
    if !(frame > 0.0) {
        return Err(Failure::usage(format!(
            "--frame {}: the frame length must be > 0 m",
            args.frame
        )));
    }
    let rows = read_targets(&args.pairs, &["input", "output"], &["input", "output"])?;
    let pairs: Vec<[f64; 2]> = rows.iter().map(|r| [r[0], r[1]]).collect();
    let s = freudenstein::function(&pairs, frame).map_err(usage)?;
    let names: Vec<String> = ["input", "output", "achieved", "residual"]
        .map(String::from)
        .to_vec();
    let mut w = Writer::new(out, args.format, &names, &["rad", "rad", "rad", "rad"])?;
    for &[i, o] in &pairs {
        let a = output_angle(&s.four_bar, i).unwrap_or(f64::NAN);
        w.row(&[i, o, a, mech_core::kernel::link_state::wrap(a - o)])?;
    }
    w.finish()?;
    eprintln!(
        "Freudenstein, {} pairs{}: K1 = {}, K2 = {}, K3 = {}",
        pairs.len(),
        if s.exact {
            " (exact)"
        } else {
            " (least squares)"
        },
        limits::show(s.k[0]),
        limits::show(s.k[1]),
        limits::show(s.k[2])
    );
    eprintln!("{}", lengths(&s.four_bar));
    eprintln!("error = {:e} rad²", s.error);
    let doc = format!(
        "Function generator through {} (input, output) pairs: Freudenstein's equation{} (mech synth function).",
        pairs.len(),
        if s.exact { "" } else { ", least squares" }
    );
    write(&args.output, &s.four_bar.to_mech("FunctionGenerator", &doc))
}

/// The four numbers of `--circle-points`, m.
fn circle_points(args: &[String]) -> Result<Option<[[f64; 2]; 2]>, Failure> {
    if args.is_empty() {
        return Ok(None);
    }
    if args.len() != 4 {
        return Err(Failure::usage(format!(
            "--circle-points: {} value(s); give four, XA,YA,XB,YB (m, the moving frame: origin P, x along the pose's angle)",
            args.len()
        )));
    }
    let v = args
        .iter()
        .map(|a| quantity::parse(a, Dim::LENGTH, "--circle-points"))
        .collect::<Result<Vec<f64>, Failure>>()?;
    Ok(Some([[v[0], v[1]], [v[2], v[3]]]))
}

/// The method as a message.
fn method(s: &MotionSynthesis, n: usize) -> String {
    let how = match n {
        3 => "three poses: centre points by circumcentres".to_string(),
        4 => "four poses: two points of the circle-point curve".to_string(),
        5 => "five poses: two Burmester points".to_string(),
        _ => format!("{n} poses: least squares"),
    };
    let p = |x: [f64; 2]| format!("({}, {})", limits::show(x[0]), limits::show(x[1]));
    format!(
        "Burmester, {how}: A {} → O2 {}, B {} → O4 {} (circle points in the moving frame → centre points)",
        p(s.crank.circle),
        p(s.crank.centre),
        p(s.rocker.circle),
        p(s.rocker.centre)
    )
}

/// Run `mech synth motion`.
pub fn motion(args: MotionArgs, out: impl Write) -> Result<(), Failure> {
    limits::writable(&args.output, "-o", "mech")?;
    let cp = circle_points(&args.circle_points)?;
    let rows = read_targets(&args.poses, &["x", "y", "angle"], &["angle"])?;
    let poses: Vec<[f64; 3]> = rows.iter().map(|r| [r[0], r[1], r[2]]).collect();
    let s = burmester::motion(&poses, cp).map_err(usage)?;
    let names: Vec<String> = ["q", "x", "y", "angle", "P.x", "P.y", "coupler.angle"]
        .map(String::from)
        .to_vec();
    let units = ["rad", "m", "m", "rad", "m", "m", "rad"];
    let mut w = Writer::new(out, args.format, &names, &units)?;
    for (p, &q) in poses.iter().zip(&s.crank_angles) {
        let (px, py, dir) = s
            .four_bar
            .pose(q)
            .map_or((f64::NAN, f64::NAN, f64::NAN), |x| {
                (x.p[0], x.p[1], (x.b[1] - x.a[1]).atan2(x.b[0] - x.a[0]))
            });
        w.row(&[q, p[0], p[1], p[2], px, py, dir])?;
    }
    w.finish()?;
    eprintln!("{}", method(&s, poses.len()));
    eprintln!("{}", lengths(&s.four_bar));
    if s.offset != 0.0 {
        eprintln!(
            "offset = {} rad: A → B points at each pose's angle + offset (the poses' turns are met; their angles along A → B are not: Burmester points off one line along the pose)",
            limits::show(s.offset)
        );
    }
    eprintln!("error = {:e} m²", s.error);
    let doc = format!(
        "Motion generator through {} poses: Burmester theory{} (mech synth motion).",
        poses.len(),
        if s.exact { "" } else { ", least squares" }
    );
    write(&args.output, &s.four_bar.to_mech("MotionGenerator", &doc))
}
