//! Frames of the linkage ([`crate::scene`]) as SVG: one frame as a still drawing, a
//! sequence as an animated SVG (SMIL `<animate>` on each changing attribute, looping; no
//! script, so it plays in any browser and in an `<img>`), and the plots of the report.
//! The SVG y axis points down: a point (x, y) of the drawing (m) is at
//! ((x − x_min) k + pad, (y_max − y) k + pad) px ([`View`]).

use crate::scene::{Frame, Role, Shape};
use mech_core::kernel::link_state::V2;
use std::fmt::Write;

/// The map from the drawing (m, y up) to the picture (px, y down).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct View {
    /// Smallest x and largest y of what is drawn, m.
    pub x_min: f64,
    /// Largest y, m.
    pub y_max: f64,
    /// Pixels per metre.
    pub k: f64,
    /// Margin, px.
    pub pad: f64,
    /// Picture size, px.
    pub width: f64,
    /// Picture height, px.
    pub height: f64,
}

impl View {
    /// The view that fits every point of `shapes` into `width` px (the height follows the
    /// aspect ratio, at least `min_height`), with a margin of 6 %.
    pub fn fit<'a>(shapes: impl Iterator<Item = &'a Shape>, width: f64, min_height: f64) -> Self {
        let (mut lo, mut hi) = (
            V2::new(f64::INFINITY, f64::INFINITY),
            V2::new(f64::NEG_INFINITY, f64::NEG_INFINITY),
        );
        for s in shapes {
            for p in &s.points {
                lo = lo.inf(p);
                hi = hi.sup(p);
            }
        }
        let span = (hi - lo).max().max(1e-9);
        let pad = 0.06 * width;
        let k = (width - 2.0 * pad) / (hi.x - lo.x).max(1e-3 * span);
        let height = ((hi.y - lo.y) * k + 2.0 * pad).max(min_height);
        // Centre vertically when the height was raised.
        let extra = (height - ((hi.y - lo.y) * k + 2.0 * pad)) / 2.0;
        View {
            x_min: lo.x,
            y_max: hi.y + extra / k,
            k,
            pad,
            width,
            height,
        }
    }

    /// A point of the drawing in the picture, px.
    pub fn px(&self, p: V2) -> (f64, f64) {
        (
            (p.x - self.x_min) * self.k + self.pad,
            (self.y_max - p.y) * self.k + self.pad,
        )
    }

    /// A picture point back in the drawing, m (the inverse of [`View::px`]).
    pub fn world(&self, x: f64, y: f64) -> V2 {
        V2::new(
            (x - self.pad) / self.k + self.x_min,
            self.y_max - (y - self.pad) / self.k,
        )
    }
}

/// The style sheet and the definitions (hatching, arrow head) of every picture.
const STYLE: &str = r##"<defs><pattern id="hatch" width="6" height="6" patternUnits="userSpaceOnUse" patternTransform="rotate(45)"><rect width="6" height="6" fill="#eee"/><line x1="0" y1="0" x2="0" y2="6" stroke="#555" stroke-width="1.5"/></pattern><marker id="head" viewBox="0 0 10 10" refX="9" refY="5" markerWidth="7" markerHeight="7" orient="auto-start-reverse"><path d="M0,0L10,5L0,10z" fill="#d2691e"/></marker></defs>
<style>.bar{stroke:#3b6ea8;stroke-width:10;stroke-linecap:round;stroke-opacity:.8}.plate{fill:#3b6ea8;fill-opacity:.35;stroke:#3b6ea8;stroke-width:3;stroke-linejoin:round}.block{fill:#c0504d;fill-opacity:.7;stroke:#7a2a28;stroke-width:2}.guide{stroke:#555;stroke-width:2;stroke-dasharray:8 4}.pin{fill:#fff;stroke:#000;stroke-width:2}.pivot{fill:url(#hatch);stroke:#333;stroke-width:1.5}.label{font:13px sans-serif;fill:#222}.path{fill:none;stroke:#2a9d3a;stroke-width:1.5}.arrow{stroke:#d2691e;stroke-width:2.5;marker-end:url(#head)}.gear{fill:#e8d9b5;fill-opacity:.5;stroke:#8a6d3b;stroke-width:2}.spring{fill:none;stroke:#2e7d32;stroke-width:2}.damper{stroke:#6d4c41;stroke-width:4}</style>
"##;

/// The radius of a pin, px.
pub const PIN_RADIUS: f64 = 5.0;

fn class(r: Role) -> &'static str {
    match r {
        Role::Bar => "bar",
        Role::Plate => "plate",
        Role::Block => "block",
        Role::Guide => "guide",
        Role::Pin => "pin",
        Role::Pivot => "pivot",
        Role::Label => "label",
        Role::Path => "path",
        Role::Arrow => "arrow",
        Role::Gear => "gear",
        Role::Spring => "spring",
        Role::Damper => "damper",
    }
}

fn num(x: f64) -> String {
    format!("{x:.2}")
}

fn points_attr(view: &View, pts: &[V2]) -> String {
    pts.iter()
        .map(|&p| {
            let (x, y) = view.px(p);
            format!("{},{}", num(x), num(y))
        })
        .collect::<Vec<_>>()
        .join(" ")
}

/// The attributes (name, value) that place a shape.
pub fn attributes(view: &View, s: &Shape) -> Vec<(&'static str, String)> {
    match s.role {
        Role::Bar | Role::Guide | Role::Arrow | Role::Damper => {
            let ((x1, y1), (x2, y2)) = (view.px(s.points[0]), view.px(s.points[1]));
            vec![
                ("x1", num(x1)),
                ("y1", num(y1)),
                ("x2", num(x2)),
                ("y2", num(y2)),
            ]
        }
        Role::Pin => {
            let (x, y) = view.px(s.points[0]);
            vec![("cx", num(x)), ("cy", num(y))]
        }
        Role::Label => {
            let (x, y) = view.px(s.points[0]);
            vec![("x", num(x)), ("y", num(y))]
        }
        Role::Plate | Role::Block | Role::Pivot | Role::Path | Role::Gear | Role::Spring => {
            vec![("points", points_attr(view, &s.points))]
        }
    }
}

fn tag(r: Role) -> &'static str {
    match r {
        Role::Bar | Role::Guide | Role::Arrow | Role::Damper => "line",
        Role::Pin => "circle",
        Role::Label => "text",
        Role::Path | Role::Spring => "polyline",
        Role::Plate | Role::Block | Role::Pivot | Role::Gear => "polygon",
    }
}

fn escape(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

/// One element; `animation` holds its `<animate>` children.
fn element(
    out: &mut String,
    s: &Shape,
    attrs: &[(&'static str, String)],
    animation: &str,
    id: Option<usize>,
) {
    let _ = write!(
        out,
        "<{} class=\"{}\" data-name=\"{}\"",
        tag(s.role),
        class(s.role),
        escape(&s.name)
    );
    if let Some(i) = id {
        let _ = write!(out, " id=\"s{i}\"");
    }
    for (k, v) in attrs {
        let _ = write!(out, " {k}=\"{v}\"");
    }
    if s.role == Role::Pin {
        let _ = write!(out, " r=\"{PIN_RADIUS}\"");
    }
    match (s.role, animation.is_empty()) {
        (Role::Label, _) => {
            let _ = write!(out, ">{animation}{}</text>", escape(&s.name));
        }
        (_, true) => out.push_str("/>"),
        (r, false) => {
            let _ = write!(out, ">{animation}</{}>", tag(r));
        }
    }
    out.push('\n');
}

/// The opening of a picture of `view`'s size.
fn open(view: &View) -> String {
    format!(
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{w}\" height=\"{h}\" viewBox=\"0 0 {w} {h}\">\n{STYLE}<rect width=\"100%\" height=\"100%\" fill=\"#fff\"/>\n",
        w = num(view.width),
        h = num(view.height)
    )
}

/// A still drawing: the frame, then `extra` shapes (paths, arrows) over it.
pub fn still(frame: &Frame, extra: &[Shape], width: f64, height: f64) -> (String, View) {
    let view = View::fit(frame.shapes.iter().chain(extra), width, height);
    let mut out = open(&view);
    for s in extra
        .iter()
        .filter(|s| s.role == Role::Path)
        .chain(&frame.shapes)
        .chain(extra.iter().filter(|s| s.role != Role::Path))
    {
        element(&mut out, s, &attributes(&view, s), "", None);
    }
    out.push_str("</svg>\n");
    (out, view)
}

/// An animated drawing of `frames` (the same shapes in each), looping every `seconds`,
/// with `extra` still shapes (paths) under it.
pub fn animated(
    frames: &[Frame],
    extra: &[Shape],
    width: f64,
    height: f64,
    seconds: f64,
) -> (String, View) {
    let view = View::fit(
        frames.iter().flat_map(|f| f.shapes.iter()).chain(extra),
        width,
        height,
    );
    let mut out = open(&view);
    for s in extra {
        element(&mut out, s, &attributes(&view, s), "", None);
    }
    let first = &frames[0];
    for (i, s) in first.shapes.iter().enumerate() {
        let per_frame: Vec<Vec<(&'static str, String)>> = frames
            .iter()
            .map(|f| attributes(&view, &f.shapes[i]))
            .collect();
        let mut animation = String::new();
        for (a, (name, v0)) in per_frame[0].iter().enumerate() {
            if per_frame.iter().all(|attrs| &attrs[a].1 == v0) {
                continue;
            }
            let values: Vec<&str> = per_frame.iter().map(|attrs| attrs[a].1.as_str()).collect();
            let _ = write!(animation, "<animate attributeName=\"{name}\" values=\"{}\" dur=\"{seconds}s\" repeatCount=\"indefinite\"/>", values.join(";"));
        }
        element(&mut out, s, &per_frame[0], &animation, None);
    }
    out.push_str("</svg>\n");
    (out, view)
}

/// The elements of `frame` with ids `s0`, `s1`, ... (for the report's script), in `view`.
pub fn elements_with_ids(frame: &Frame, view: &View) -> String {
    let mut out = String::new();
    for (i, s) in frame.shapes.iter().enumerate() {
        element(&mut out, s, &attributes(view, s), "", Some(i));
    }
    out
}

/// The opening tag and style of a picture (for the report, which adds its own content).
pub fn open_picture(view: &View) -> String {
    open(view)
}

/// A line plot of series (label, values) against `x`, `width` × `height` px, with its
/// title, axes, the range of y, a legend, and a cursor line `id="cursor-<id>"` at `x[0]`.
pub fn plot(
    id: &str,
    title: &str,
    unit: &str,
    x: &[f64],
    series: &[(String, Vec<f64>)],
    width: f64,
    height: f64,
) -> String {
    const COLORS: [&str; 6] = [
        "#3b6ea8", "#c0504d", "#2a9d3a", "#8064a2", "#d2691e", "#4bacc6",
    ];
    let (l, r, t, b) = (56.0, 12.0, 26.0, 28.0);
    let (x0, x1) = (
        x.first().copied().unwrap_or(0.0),
        x.last().copied().unwrap_or(1.0),
    );
    let finite = series
        .iter()
        .flat_map(|(_, v)| v.iter().copied())
        .filter(|v| v.is_finite());
    let (mut lo, mut hi) = finite.fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), v| {
        (a.min(v), b.max(v))
    });
    if !(lo.is_finite() && hi.is_finite()) {
        (lo, hi) = (0.0, 1.0);
    }
    if hi - lo < 1e-12 * hi.abs().max(1.0) {
        (lo, hi) = (lo - 1.0, hi + 1.0);
    }
    let sx = |v: f64| l + (v - x0) / (x1 - x0).max(1e-300) * (width - l - r);
    let sy = |v: f64| t + (hi - v) / (hi - lo) * (height - t - b);
    let mut out = format!("<svg xmlns=\"http://www.w3.org/2000/svg\" class=\"plot\" width=\"{width}\" height=\"{height}\" viewBox=\"0 0 {width} {height}\">\n");
    let _ = writeln!(out, "<rect width=\"100%\" height=\"100%\" fill=\"#fff\"/><text x=\"{l}\" y=\"16\" font-family=\"sans-serif\" font-size=\"13\" font-weight=\"bold\">{} [{}]</text>", escape(title), escape(unit));
    let _ = writeln!(
        out,
        "<rect x=\"{l}\" y=\"{t}\" width=\"{}\" height=\"{}\" fill=\"none\" stroke=\"#999\"/>",
        width - l - r,
        height - t - b
    );
    for v in [lo, 0.5 * (lo + hi), hi] {
        let _ = writeln!(out, "<text x=\"{}\" y=\"{}\" font-family=\"sans-serif\" font-size=\"10\" text-anchor=\"end\">{:.4}</text>", l - 4.0, sy(v) + 3.0, v);
    }
    if lo < 0.0 && hi > 0.0 {
        let _ = writeln!(
            out,
            "<line x1=\"{l}\" x2=\"{}\" y1=\"{y}\" y2=\"{y}\" stroke=\"#ccc\"/>",
            width - r,
            y = sy(0.0)
        );
    }
    let _ = writeln!(out, "<text x=\"{}\" y=\"{}\" font-family=\"sans-serif\" font-size=\"10\" text-anchor=\"end\">input {:.3} … {:.3}</text>", width - r, height - 8.0, x0, x1);
    for (k, (label, v)) in series.iter().enumerate() {
        let color = COLORS[k % COLORS.len()];
        let pts: Vec<String> = x
            .iter()
            .zip(v)
            .filter(|(_, y)| y.is_finite())
            .map(|(&xx, &yy)| format!("{:.1},{:.1}", sx(xx), sy(yy)))
            .collect();
        let _ = writeln!(out, "<polyline class=\"series\" data-label=\"{}\" fill=\"none\" stroke=\"{color}\" stroke-width=\"1.6\" points=\"{}\"/>", escape(label), pts.join(" "));
        let _ = writeln!(out, "<text x=\"{}\" y=\"{}\" font-family=\"sans-serif\" font-size=\"10\" fill=\"{color}\">{}</text>", l + 6.0 + 110.0 * (k % 4) as f64, t + 12.0 + 12.0 * (k / 4) as f64, escape(label));
    }
    let _ = write!(out, "<line id=\"cursor-{id}\" x1=\"{c}\" x2=\"{c}\" y1=\"{t}\" y2=\"{}\" stroke=\"#000\" stroke-dasharray=\"3 3\"/>\n</svg>\n", height - b, c = sx(x0));
    out
}
