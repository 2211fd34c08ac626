//! `mech report FILE -o out.html`: one self-contained HTML page (no network: the SVG, the
//! data, the style and the script are inline) with the linkage moving over a cycle, a
//! slider for the input and a play/pause button, and the plots over the cycle: the motor
//! action by both routes, the reaction at every joint, I* and M* (one input), the speed of
//! chosen points. Opening the page with `#frame=K` shows frame K, paused.

use crate::columns::{Columns, Part};
use crate::draw::{inputs, range};
use crate::loads::LoadSet;
use crate::{limits, quantity, scene, source, svg, Failure};
use std::fmt::Write;
use std::path::PathBuf;

/// `mech report` arguments.
#[derive(clap::Args, Debug)]
pub struct ReportArgs {
    /// The mechanism file (`-` = standard input).
    pub file: PathBuf,
    /// The HTML file to write.
    #[arg(short = 'o', long = "output")]
    pub output: PathBuf,
    /// First value of the first input (default 0).
    #[arg(long, allow_hyphen_values = true)]
    pub from: Option<String>,
    /// Last value of the first input (default: a full turn, or ± the drawing's size).
    #[arg(long, allow_hyphen_values = true)]
    pub to: Option<String>,
    /// The other inputs' values (several DOF).
    #[arg(long = "rest", value_delimiter = ',', allow_hyphen_values = true)]
    pub rest: Vec<String>,
    /// Input speeds, constant over the cycle (rad/s or m/s; `rpm` allowed); default 1,
    /// so that velocities are the velocity coefficients.
    #[arg(long = "speed", value_delimiter = ',', allow_hyphen_values = true)]
    pub speed: Vec<String>,
    /// Loads: NAME=VALUE or NAME=@table.csv. Repeatable.
    #[arg(long = "load", allow_hyphen_values = true)]
    pub load: Vec<String>,
    /// Plot the speed of this point. Repeatable (default: the last point).
    #[arg(long = "point")]
    pub point: Vec<String>,
    /// Number of frames over the range (2 to 10⁴).
    #[arg(long, default_value_t = 120, allow_hyphen_values = true, value_parser = limits::frames)]
    pub frames: usize,
}

/// One column's values over the frames (NaN where the row failed).
fn column(names: &[String], rows: &[Option<Vec<f64>>], name: &str) -> Vec<f64> {
    match names.iter().position(|n| n == name) {
        Some(i) => rows
            .iter()
            .map(|r| r.as_ref().map_or(f64::NAN, |r| r[i]))
            .collect(),
        None => vec![f64::NAN; rows.len()],
    }
}

/// The page's script: frames of shape attributes, the slider, play/pause, the cursors.
const SCRIPT: &str = r#"
const D = JSON.parse(document.getElementById('data').textContent);
const slider = document.getElementById('slider'), readout = document.getElementById('q'), button = document.getElementById('play');
let frame = 0, timer = null;
function show(k) {
  frame = k; slider.value = k;
  D.shapes.forEach((s, i) => { const el = document.getElementById('s' + i); s.attrs.forEach((a, j) => el.setAttribute(a, s.values[k][j])); });
  D.cursors.forEach(c => { const el = document.getElementById('cursor-' + c); if (el) { el.setAttribute('x1', D.cx[c][k]); el.setAttribute('x2', D.cx[c][k]); } });
  readout.textContent = D.q[k];
}
function play() { timer = setInterval(() => show((frame + 1) % D.q.length), D.ms); button.textContent = 'pause'; }
function pause() { clearInterval(timer); timer = null; button.textContent = 'play'; }
button.onclick = () => timer ? pause() : play();
slider.oninput = () => { pause(); show(+slider.value); };
const m = /frame=(\d+)/.exec(location.hash);
if (m) { show(Math.min(+m[1], D.q.length - 1)); button.textContent = 'play'; } else { show(0); play(); }
"#;

/// Run `mech report`.
pub fn run(args: ReportArgs) -> Result<(), Failure> {
    if args.frames < 2 {
        return Err(Failure::usage("--frames: at least 2"));
    }
    limits::writable(&args.output, "-o", "html")?;
    let m = source::load(&args.file)?;
    let model = m.model();
    let (a, b, q0) = inputs(&m, &args.from, &args.to, &args.rest)?;
    let qs = range(&q0, a, b, args.frames - 1);
    let frames = scene::frames(&m, &qs)?;
    let qd = quantity::per_input(&args.speed, model, 1, "--speed", 1.0)?;
    let qdd = vec![0.0; m.dof()];
    let loads = LoadSet::parse(&args.load, model)?;
    let cols = Columns::new(&m, Part::ALL);
    let rows: Vec<Option<Vec<f64>>> = qs
        .iter()
        .map(|q| cols.row(&m, q, &qd, &qdd, &loads.at(&m, q[0])).ok())
        .collect();
    let x: Vec<f64> = qs.iter().map(|q| q[0]).collect();
    let names = &cols.names;
    let g = m.dof();
    let per_input = |base: &str, k: usize| {
        if g == 1 {
            base.to_string()
        } else {
            format!("{base}.{}", model.joints[model.inputs[k]].name)
        }
    };

    // The plots.
    let (w, h) = (560.0, 220.0);
    let mut plots: Vec<(String, String)> = Vec::new();
    let torque_unit = if quantity::input_dims(model, 0).0 == mech_core::model::units::Dim::ANGLE {
        "N·m"
    } else {
        "N"
    };
    let mut drivers = Vec::new();
    for k in 0..g {
        for (label, base) in [("d'Alembert", "driver"), ("virtual power", "virtual_power")] {
            let name = per_input(base, k);
            if names.contains(&name) {
                drivers.push((
                    format!("{} {label}", per_input("driver", k)),
                    column(names, &rows, &name),
                ));
            }
        }
    }
    plots.push((
        "driver".into(),
        svg::plot(
            "driver",
            "motor action (applied by the motor)",
            torque_unit,
            &x,
            &drivers,
            w,
            h,
        ),
    ));
    if !m.redundant() {
        let reactions: Vec<(String, Vec<f64>)> = model
            .joints
            .iter()
            .map(|j| {
                let (fx, fy) = (
                    column(names, &rows, &format!("{}.fx", j.name)),
                    column(names, &rows, &format!("{}.fy", j.name)),
                );
                (
                    format!("|R {}|", j.name),
                    fx.iter().zip(&fy).map(|(a, b)| a.hypot(*b)).collect(),
                )
            })
            .collect();
        plots.push((
            "reactions".into(),
            svg::plot("reactions", "reactions", "N", &x, &reactions, w, h),
        ));
    }
    if g == 1 {
        plots.push((
            "inertia".into(),
            svg::plot(
                "inertia",
                "reduced inertia I*",
                "kg·m²",
                &x,
                &[("I*".into(), column(names, &rows, "inertia"))],
                w,
                h,
            ),
        ));
        plots.push((
            "moment".into(),
            svg::plot(
                "moment",
                "reduced moment M*",
                torque_unit,
                &x,
                &[("M*".into(), column(names, &rows, "moment"))],
                w,
                h,
            ),
        ));
    }
    let points: Vec<String> = if args.point.is_empty() {
        model
            .points
            .last()
            .map(|p| vec![p.name.clone()])
            .unwrap_or_default()
    } else {
        args.point.clone()
    };
    let mut speeds = Vec::new();
    for p in &points {
        if model.point_index(p).is_none() {
            return Err(Failure::usage(format!("--point {p}: no such point")));
        }
        let (vx, vy) = (
            column(names, &rows, &format!("{p}.vx")),
            column(names, &rows, &format!("{p}.vy")),
        );
        speeds.push((
            format!("|v {p}|"),
            vx.iter().zip(&vy).map(|(a, b)| a.hypot(*b)).collect(),
        ));
    }
    plots.push((
        "speed".into(),
        svg::plot("speed", "speed of points", "m/s", &x, &speeds, w, h),
    ));

    // The linkage and its frames.
    let view = svg::View::fit(frames.iter().flat_map(|f| f.shapes.iter()), 640.0, 320.0);
    let mut shapes_json = Vec::new();
    for i in 0..frames[0].shapes.len() {
        let per: Vec<Vec<(&str, String)>> = frames
            .iter()
            .map(|f| svg::attributes(&view, &f.shapes[i]))
            .collect();
        let attrs: Vec<&str> = per[0].iter().map(|(a, _)| *a).collect();
        let values: Vec<Vec<&str>> = per
            .iter()
            .map(|p| p.iter().map(|(_, v)| v.as_str()).collect())
            .collect();
        shapes_json.push(serde_json::json!({ "attrs": attrs, "values": values }));
    }
    let (l, r) = (56.0, 12.0);
    let (x0, x1) = (x[0], *x.last().unwrap());
    let cx: Vec<f64> = x
        .iter()
        .map(|&v| l + (v - x0) / (x1 - x0).max(1e-300) * (w - l - r))
        .collect();
    let cursors: Vec<&str> = plots.iter().map(|(id, _)| id.as_str()).collect();
    let cx_map: serde_json::Map<String, serde_json::Value> = cursors
        .iter()
        .map(|c| (c.to_string(), serde_json::json!(cx)))
        .collect();
    let data = serde_json::json!({
        "q": x.iter().map(|v| format!("{v:.4}")).collect::<Vec<_>>(),
        "shapes": shapes_json,
        "cursors": cursors,
        "cx": cx_map,
        "ms": (4000.0 / args.frames as f64).round(),
    });
    let unit = if torque_unit == "N·m" { "rad" } else { "m" };
    let mut page = String::new();
    let _ = write!(
        page,
        "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\"><title>{name}</title>\n<style>body{{font-family:sans-serif;margin:16px;color:#222}}.row{{display:flex;flex-wrap:wrap;gap:12px}}#controls{{margin:8px 0}}#slider{{width:420px}}</style></head><body>\n<h1>{name}</h1>\n<p>{doc}</p>\n<p>Input from {a:.4} to {b:.4} {unit} in {n} frames; input speed {speeds} (constant), loads as given. Motor action: the torque or force the motor applies (the engine textbooks' turning moment on the crankshaft is its negative). SI units.</p>\n<div id=\"controls\"><button id=\"play\">pause</button> <input id=\"slider\" type=\"range\" min=\"0\" max=\"{last}\" value=\"0\"> q = <span id=\"q\"></span> {unit}</div>\n",
        name = html(&model.name),
        doc = html(&m_doc(&args.file)),
        n = args.frames,
        last = args.frames - 1,
        speeds = (0..g)
            .map(|k| {
                let u = if quantity::input_dims(model, k).0 == mech_core::model::units::Dim::ANGLE { "rad/s" } else { "m/s" };
                format!("{} {u}", qd[k])
            })
            .collect::<Vec<_>>()
            .join(", "),
    );
    page.push_str("<div id=\"linkage\">");
    page.push_str(&svg::open_picture(&view));
    page.push_str(&svg::elements_with_ids(&frames[0], &view));
    page.push_str("</svg></div>\n<div class=\"row\">\n");
    for (_, p) in &plots {
        page.push_str(p);
    }
    let _ = write!(page, "</div>\n<script type=\"application/json\" id=\"data\">{}</script>\n<script>{SCRIPT}</script>\n</body></html>\n", data);
    limits::write_file(&args.output, &page, "-o", "html")
}

fn html(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
}

/// The doc comment of the mechanism file (its `///` lines), for the page's heading.
fn m_doc(path: &std::path::Path) -> String {
    limits::read_text(path, limits::MECH_BYTES, "the mechanism file")
        .unwrap_or_default()
        .lines()
        .filter_map(|l| l.trim().strip_prefix("///"))
        .map(str::trim)
        .collect::<Vec<_>>()
        .join(" ")
}
