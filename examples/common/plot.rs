//! The flywheel report of the examples and its diagrams as SVG (plotters): M*(q), I*(q),
//! Wittenbauer's F–I* diagram with its two tangents, and ω(q) with and without the flywheel.
//! Shared by `examples/engine.rs`, `examples/shaper.rs` and `tests/flywheel.rs`.
#![allow(dead_code)]

use std::error::Error;
use std::path::{Path, PathBuf};
use std::process::ExitCode;

use mech::flywheel::{Cycle, CyclePoint, Flywheel, SteadyState};
use mech::prelude::*;
use plotters::prelude::*;

/// The exit code of an example's `run`, with its error on stderr.
pub fn exit(name: &str, result: Result<Vec<PathBuf>, Box<dyn Error>>) -> ExitCode {
    match result {
        Ok(_) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("{name} example failed: {e}");
            ExitCode::FAILURE
        }
    }
}

/// Size the flywheel of `cycle` for (ω_a, ε) by both methods and print them, check the
/// exact one by integrating a cycle in time (and show what the approximate one gives),
/// then write the four diagrams into `dir`. Angles are printed from the cycle start.
pub fn report<M: OneDof>(
    cycle: &Cycle<'_, M>,
    omega_mean: f64,
    eps: f64,
    name: &str,
    dir: &Path,
) -> Result<Vec<PathBuf>, Box<dyn Error>> {
    let fw = cycle.flywheel(omega_mean, eps)?;
    let (w, a) = (&fw.exact, &fw.approximate);
    let deg = |q: f64| (q - cycle.start()).to_degrees();
    println!();
    println!("Flywheel on the input shaft for w_a = {omega_mean:.4} rad/s, eps = {eps}:");
    println!(
        "  accumulated work: S_max = {:.4} J at {:.2} deg, S_min = {:.4} J at {:.2} deg",
        a.s_max,
        deg(a.q_s_max),
        a.s_min,
        deg(a.q_s_min)
    );
    println!(
        "  approximate  I = (S_max - S_min)/(eps w_a^2)       = {:.10} kg m^2",
        a.inertia
    );
    println!(
        "  Wittenbauer  I (exact, tangents (1 +/- eps/2)^2)   = {:.10} kg m^2",
        w.inertia
    );
    println!(
        "  difference approximate - exact = {:.6} kg m^2 ({:+.3} % of the exact)",
        a.inertia - w.inertia,
        100.0 * (a.inertia / w.inertia - 1.0)
    );
    println!(
        "  tangent points: w_max at {:.3} deg (I* = {:.6}), w_min at {:.3} deg (I* = {:.6}); P = (-I, -C) = ({:.6}, {:.6})",
        deg(w.upper.q),
        w.upper.reduced_inertia,
        deg(w.lower.q),
        w.lower.reduced_inertia,
        -w.inertia,
        -w.c
    );

    let sim = cycle.simulate(&w.state, 1e-12)?;
    let s = &sim.speeds;
    println!();
    println!(
        "Verification: one cycle integrated in time (DOP853, rtol 1e-12) with the exact flywheel:"
    );
    // Eight decimals: the integration (rtol 1e-12) is within about 1e-8 rad/s of the exact
    // speeds (tests/flywheel.rs), so a ninth would print a digit that is not right.
    println!(
        "  w_max = {:.8} rad/s, w_min = {:.8} rad/s, w_mean = {:.8} rad/s",
        s.omega_max, s.omega_min, s.omega_mean
    );
    println!(
        "  eps = {:.10} (requested {eps}; relative error {:.2e}); cycle time {:.6} s, {} steps; w back at the start {:.3e} rad/s off",
        s.irregularity,
        s.irregularity / eps - 1.0,
        sim.duration,
        sim.stats.steps,
        sim.omega_end - sim.omega_start
    );
    let approx_state = cycle.steady_state(omega_mean, a.inertia)?;
    println!(
        "  with the approximate flywheel instead: eps = {:.6}",
        cycle.simulate(&approx_state, 1e-12)?.speeds.irregularity
    );

    let figures = FlywheelFigures::collect(cycle, &fw)?;
    match &figures.without {
        Ok((s, _)) => println!("  without a flywheel at the same mean speed: eps = {:.4} (w from {:.2} to {:.2} rad/s)", s.speeds.irregularity, s.speeds.omega_min, s.speeds.omega_max),
        Err(e) => println!("  without a flywheel there is no steady state at this mean speed: {e}"),
    }
    let paths = figures.write(dir, name)?;
    println!();
    println!("Diagrams (SVG) in {}:", dir.display());
    for p in &paths {
        println!("  {}", p.file_name().unwrap_or_default().to_string_lossy());
    }
    Ok(paths)
}

/// Samples per cycle of the diagrams.
pub const SAMPLES: usize = 720;

/// One curve of a chart: its legend and its points (x, y).
pub struct Series {
    /// Legend text.
    pub label: String,
    /// The points, in drawing order.
    pub points: Vec<(f64, f64)>,
}

/// Everything the four diagrams show, sampled from a cycle and its flywheel.
pub struct FlywheelFigures {
    /// Samples of M*, I*, dI*/dq and S at q0 + k λ / SAMPLES.
    pub samples: Vec<CyclePoint>,
    /// The cycle start q0, rad (the abscissa of the diagrams is (q − q0) in degrees).
    pub start: f64,
    /// The flywheel by both methods.
    pub flywheel: Flywheel,
    /// ω at the samples with the exact flywheel, rad/s.
    pub omega_with: Vec<f64>,
    /// The steady state at the same mean speed without a flywheel, and ω at the samples;
    /// or why there is none (e.g. the machine stalls).
    pub without: Result<(SteadyState, Vec<f64>), MechError>,
}

impl FlywheelFigures {
    /// Sample `cycle` and the speeds of the motion with `flywheel.exact` and with no flywheel.
    pub fn collect<M: OneDof>(
        cycle: &Cycle<'_, M>,
        flywheel: &Flywheel,
    ) -> Result<Self, MechError> {
        let samples = cycle.sample(SAMPLES)?;
        let state = flywheel.exact.state;
        let omega_with = samples
            .iter()
            .map(|p| cycle.speed(&state, p.q))
            .collect::<Result<Vec<_>, _>>()?;
        let without = cycle.steady_state(flywheel.omega_mean, 0.0).and_then(|s| {
            let w = samples
                .iter()
                .map(|p| cycle.speed(&s, p.q))
                .collect::<Result<Vec<_>, _>>()?;
            Ok((s, w))
        });
        Ok(FlywheelFigures {
            samples,
            start: cycle.start(),
            flywheel: *flywheel,
            omega_with,
            without,
        })
    }

    fn angle(&self, q: f64) -> f64 {
        (q - self.start).to_degrees()
    }

    fn against_angle(&self, y: impl Fn(&CyclePoint) -> f64) -> Vec<(f64, f64)> {
        self.samples
            .iter()
            .map(|p| (self.angle(p.q), y(p)))
            .collect()
    }

    /// Write `moment.svg`, `inertia.svg`, `wittenbauer.svg` and `speed.svg` into `dir`
    /// (created if needed); `name` heads the titles. Returns the paths.
    pub fn write(&self, dir: &Path, name: &str) -> Result<Vec<PathBuf>, Box<dyn Error>> {
        std::fs::create_dir_all(dir)?;
        let x_label = "crank angle from the cycle start (deg)";
        let moment = dir.join("moment.svg");
        line_chart(
            &moment,
            &format!("{name}: reduced moment M*(q)"),
            x_label,
            "M* (N m)",
            &[Series {
                label: "M* (driver included)".into(),
                points: self.against_angle(|p| p.moment),
            }],
        )?;
        let inertia = dir.join("inertia.svg");
        line_chart(
            &inertia,
            &format!("{name}: reduced inertia I*(q)"),
            x_label,
            "I* (kg m^2)",
            &[Series {
                label: "I* (no flywheel)".into(),
                points: self.against_angle(|p| p.inertia),
            }],
        )?;
        let witt = dir.join("wittenbauer.svg");
        self.wittenbauer(&witt, name)?;
        let speed = dir.join("speed.svg");
        let w = &self.flywheel.exact;
        let mut series = vec![Series {
            label: format!(
                "flywheel I = {:.4} kg m^2 (eps = {})",
                w.inertia, self.flywheel.irregularity
            ),
            points: self
                .samples
                .iter()
                .zip(&self.omega_with)
                .map(|(p, o)| (self.angle(p.q), *o))
                .collect(),
        }];
        if let Ok((s, omega)) = &self.without {
            series.push(Series {
                label: format!("no flywheel (eps = {:.3})", s.speeds.irregularity),
                points: self
                    .samples
                    .iter()
                    .zip(omega)
                    .map(|(p, o)| (self.angle(p.q), *o))
                    .collect(),
            });
        }
        line_chart(
            &speed,
            &format!(
                "{name}: speed w(q), mean {:.2} rad/s",
                self.flywheel.omega_mean
            ),
            x_label,
            "w (rad/s)",
            &series,
        )?;
        Ok(vec![moment, inertia, witt, speed])
    }

    /// The F–I* curve and the two tangents through P = (−I, −C): the whole diagram on the
    /// left, the curve enlarged on the right.
    fn wittenbauer(&self, path: &Path, name: &str) -> Result<(), Box<dyn Error>> {
        let k = 2.0 / (self.flywheel.omega_mean * self.flywheel.omega_mean);
        let curve: Vec<(f64, f64)> = self
            .samples
            .iter()
            .map(|p| (p.inertia, k * p.work))
            .collect();
        let w = &self.flywheel.exact;
        let p = (-w.inertia, -w.c);
        let (x_lo, x_hi) = bounds(curve.iter().map(|c| c.0));
        let (y_lo, y_hi) = bounds(curve.iter().map(|c| c.1));
        let line = |t: &mech::flywheel::Tangent, x0: f64, x1: f64| {
            vec![
                (x0, t.slope * x0 + t.intercept),
                (x1, t.slope * x1 + t.intercept),
            ]
        };
        let labels = [
            format!("tan = (1 + eps/2)^2 = {:.5}", w.upper.slope),
            format!("tan = (1 - eps/2)^2 = {:.5}", w.lower.slope),
        ];

        let root = SVGBackend::new(path, (1200, 560)).into_drawing_area();
        root.fill(&WHITE)?;
        let root = root.titled(&format!("{name}: Wittenbauer diagram F = (2/w_a^2) int M* dq against I*; P = (-I, -C) = ({:.5}, {:.5})", p.0, p.1), ("sans-serif", 18))?;
        let (left, right) = root.split_horizontally(600);
        let pad = |lo: f64, hi: f64| 0.08 * (hi - lo).max(1e-12);

        // Whole diagram: from P to the curve.
        let (ax0, ax1) = (p.0.min(x_lo), x_hi.max(0.0));
        let (ay0, ay1) = (
            p.1.min(y_lo),
            y_hi.max(0.0).max(w.upper.slope * ax1 + w.upper.intercept),
        );
        let series = [
            Series {
                label: "F(I*) over the cycle".into(),
                points: curve.clone(),
            },
            Series {
                label: labels[0].clone(),
                points: line(&w.upper, p.0, x_hi),
            },
            Series {
                label: labels[1].clone(),
                points: line(&w.lower, p.0, x_hi),
            },
        ];
        draw(
            &left,
            "whole diagram",
            "I* (kg m^2)",
            "F (kg m^2)",
            (ax0 - pad(ax0, ax1), ax1 + pad(ax0, ax1)),
            (ay0 - pad(ay0, ay1), ay1 + pad(ay0, ay1)),
            &series,
        )?;

        // The curve enlarged, with the tangents where they touch it.
        let (zx0, zx1) = (x_lo - pad(x_lo, x_hi), x_hi + pad(x_lo, x_hi));
        let series = [
            Series {
                label: "F(I*) over the cycle".into(),
                points: curve,
            },
            Series {
                label: labels[0].clone(),
                points: line(&w.upper, zx0, zx1),
            },
            Series {
                label: labels[1].clone(),
                points: line(&w.lower, zx0, zx1),
            },
        ];
        draw(
            &right,
            "the curve and the tangent points",
            "I* (kg m^2)",
            "F (kg m^2)",
            (zx0, zx1),
            (y_lo - pad(y_lo, y_hi), y_hi + pad(y_lo, y_hi)),
            &series,
        )?;
        root.present()?;
        Ok(())
    }
}

/// (min, max) of the values.
fn bounds(v: impl Iterator<Item = f64>) -> (f64, f64) {
    v.fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), x| {
        (a.min(x), b.max(x))
    })
}

const COLORS: [RGBColor; 4] = [BLUE, RED, RGBColor(0, 140, 0), BLACK];

/// One chart of `series` into the drawing area, with a legend: one polyline per series and
/// one per legend entry.
fn draw<DB: DrawingBackend>(
    area: &DrawingArea<DB, plotters::coord::Shift>,
    title: &str,
    x_label: &str,
    y_label: &str,
    x: (f64, f64),
    y: (f64, f64),
    series: &[Series],
) -> Result<(), Box<dyn Error>>
where
    DB::ErrorType: 'static,
{
    let mut chart = ChartBuilder::on(area)
        .caption(title, ("sans-serif", 16))
        .margin(12)
        .x_label_area_size(40)
        .y_label_area_size(70)
        .build_cartesian_2d(x.0..x.1, y.0..y.1)?;
    chart
        .configure_mesh()
        .x_desc(x_label)
        .y_desc(y_label)
        .draw()?;
    for (i, s) in series.iter().enumerate() {
        let color = COLORS[i % COLORS.len()];
        chart
            .draw_series(LineSeries::new(
                s.points.iter().copied(),
                color.stroke_width(2),
            ))?
            .label(s.label.as_str())
            .legend(move |(x, y)| {
                PathElement::new(vec![(x, y), (x + 20, y)], color.stroke_width(2))
            });
    }
    chart
        .configure_series_labels()
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK)
        .draw()?;
    Ok(())
}

/// A chart of `series` against a common abscissa, written to `path` as SVG (900 × 500).
pub fn line_chart(
    path: &Path,
    title: &str,
    x_label: &str,
    y_label: &str,
    series: &[Series],
) -> Result<(), Box<dyn Error>> {
    let (x0, x1) = bounds(series.iter().flat_map(|s| s.points.iter().map(|p| p.0)));
    let (y0, y1) = bounds(series.iter().flat_map(|s| s.points.iter().map(|p| p.1)));
    let pad = 0.06 * (y1 - y0).max(1e-12 * y1.abs().max(1.0));
    let root = SVGBackend::new(path, (900, 500)).into_drawing_area();
    root.fill(&WHITE)?;
    draw(
        &root,
        title,
        x_label,
        y_label,
        (x0, x1),
        (y0 - pad, y1 + pad),
        series,
    )?;
    root.present()?;
    Ok(())
}
