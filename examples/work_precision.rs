//! Work against precision of the integrators of `mech::ode` on the slider-crank.
//!
//! The run: `SliderCrank` of `tests/common/mechanisms.rs` from q0 = 0.3 rad, q̇0 = 20 rad/s
//! under a constant driver torque of 3 N·m (gravity on, no other load) for 0.5 s (about 20
//! crank revolutions, ending near 470 rad/s). The error is |q − q_ref| / |q_ref| at the end
//! against `tests/data/slider_crank.dynamics.json` (tools/dynamics_reference.py, mpmath at
//! 50 digits). For each integrator and a range of steps (RK4) or tolerances (rtol = atol,
//! Dormand–Prince 5(4) and DOP853) it prints the work — evaluations of the right-hand side,
//! accepted and rejected steps, wall time of one run (the median of repeated runs) — and the
//! error, and draws both work measures against the error as SVG into
//! `target/mech-figures/work_precision.svg`.
//!
//! Run it in release: `cargo run --release --example work_precision`.

#[path = "../tests/common/mechanisms.rs"]
mod mechanisms;

use std::error::Error;
use std::path::PathBuf;
use std::time::Instant;

use mech::dynamics::equation_of_motion;
use mech::ode::{integrate, Dop853, DormandPrince, Method, Rk4, Stats};
use mechanisms::{SliderCrank, SliderCrankLoads};
use plotters::prelude::*;

/// The run's start, end time and driver torque (N·m).
const Q0: f64 = 0.3;
const QD0: f64 = 20.0;
const T_END: f64 = 0.5;
const TORQUE: f64 = 3.0;

/// q and q̇ of the reference at `T_END`.
fn reference() -> Result<(f64, f64), Box<dyn Error>> {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/data/slider_crank.dynamics.json"
    );
    let doc: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(path)?)?;
    let case = doc["cases"]
        .as_array()
        .and_then(|c| c.iter().find(|c| c["name"] == "constant_torque"))
        .ok_or("no constant_torque case")?;
    let s = case["samples"]
        .as_array()
        .and_then(|s| s.last())
        .ok_or("no samples")?;
    if s["t"].as_f64() != Some(T_END) {
        return Err("the reference does not end at 0.5 s".into());
    }
    Ok((s["q"].as_f64().ok_or("q")?, s["qd"].as_f64().ok_or("qd")?))
}

/// One measured setting.
struct Row {
    method: &'static str,
    setting: String,
    stats: Stats,
    seconds: f64,
    error: f64,
}

/// Integrate once with a fresh `make()`, then time repeated runs (at least 0.2 s of them)
/// and keep the median.
fn measure<M: Method<2>>(
    m: &SliderCrank,
    make: impl Fn() -> M,
    q_ref: f64,
) -> Result<(Stats, f64, f64), Box<dyn Error>> {
    let zero = SliderCrankLoads::default();
    let run = || {
        integrate(
            &mut make(),
            equation_of_motion(m, |_, _, _| (TORQUE, zero)),
            0.0,
            [Q0, QD0],
            T_END,
        )
    };
    let r = run()?;
    let mut times = Vec::new();
    let begin = Instant::now();
    while times.len() < 5 || (begin.elapsed().as_secs_f64() < 0.2 && times.len() < 2000) {
        let t = Instant::now();
        std::hint::black_box(run()?);
        times.push(t.elapsed().as_secs_f64());
    }
    times.sort_by(f64::total_cmp);
    Ok((
        r.stats,
        times[times.len() / 2],
        (r.y[0] - q_ref).abs() / q_ref.abs(),
    ))
}

fn main() -> Result<(), Box<dyn Error>> {
    let (q_ref, qd_ref) = reference()?;
    let m = SliderCrank::new();
    println!("Slider-crank, q0 = {Q0} rad, q'0 = {QD0} rad/s, {TORQUE} N m for {T_END} s: reference q = {q_ref:.15} rad, q' = {qd_ref:.12} rad/s");
    let mut rows = Vec::new();
    for h in [1e-3, 5e-4, 2e-4, 1e-4, 5e-5, 2e-5, 1e-5, 5e-6, 2e-6] {
        let (stats, seconds, error) = measure(&m, || Rk4 { h }, q_ref)?;
        rows.push(Row {
            method: "RK4",
            setting: format!("h = {h:.0e} s"),
            stats,
            seconds,
            error,
        });
    }
    for k in 4..=14 {
        let tol = 10f64.powi(-k);
        let (stats, seconds, error) = measure(&m, || DormandPrince::new(tol, tol), q_ref)?;
        rows.push(Row {
            method: "DP5(4)",
            setting: format!("rtol = 1e-{k}"),
            stats,
            seconds,
            error,
        });
    }
    for k in 4..=15 {
        let tol = 10f64.powi(-k);
        let (stats, seconds, error) = measure(&m, || Dop853::new(tol, tol), q_ref)?;
        rows.push(Row {
            method: "DOP853",
            setting: format!("rtol = 1e-{k}"),
            stats,
            seconds,
            error,
        });
    }

    println!();
    println!("| method | setting | RHS evaluations | steps (rejected) | wall time of one run | s per simulated s | relative error in q(0.5 s) |");
    println!("|---|---|---:|---:|---:|---:|---:|");
    for r in &rows {
        println!(
            "| {} | {} | {} | {} ({}) | {:.1} µs | {:.2e} | {:.2e} |",
            r.method,
            r.setting,
            r.stats.rhs_evals,
            r.stats.steps,
            r.stats.rejected,
            r.seconds * 1e6,
            r.seconds / T_END,
            r.error
        );
    }

    let path = plot(&rows)?;
    println!();
    println!("work-precision diagram: {}", path.display());
    Ok(())
}

/// Two log–log panels, wall time and evaluations against the error, one line per method
/// through its settings from coarse to fine (errors below 1e-16 drawn at 1e-16).
fn plot(rows: &[Row]) -> Result<PathBuf, Box<dyn Error>> {
    let dir = PathBuf::from(concat!(env!("CARGO_MANIFEST_DIR"), "/target/mech-figures"));
    std::fs::create_dir_all(&dir)?;
    let path = dir.join("work_precision.svg");
    let floor = 1e-16;
    let methods = ["RK4", "DP5(4)", "DOP853"];
    let colors = [RED, BLUE, RGBColor(0, 140, 0)];
    let err = |r: &Row| r.error.max(floor);
    let (e0, e1) = rows.iter().fold((f64::INFINITY, 0.0f64), |(a, b), r| {
        (a.min(err(r)), b.max(err(r)))
    });
    let target = path.clone();
    let root = SVGBackend::new(&target, (1200, 520)).into_drawing_area();
    root.fill(&WHITE)?;
    let panels = root.split_evenly((1, 2));
    let measures: [(&str, &dyn Fn(&Row) -> f64); 2] = [
        ("wall time of one run (s)", &|r| r.seconds),
        ("evaluations of the right-hand side", &|r| {
            r.stats.rhs_evals as f64
        }),
    ];
    for (area, (label, work)) in panels.iter().zip(measures) {
        let (w0, w1) = rows.iter().fold((f64::INFINITY, 0.0f64), |(a, b), r| {
            (a.min(work(r)), b.max(work(r)))
        });
        let mut chart = ChartBuilder::on(area)
            .caption(
                format!("Slider-crank, 0.5 s: {label} vs error"),
                ("sans-serif", 16),
            )
            .margin(14)
            .x_label_area_size(44)
            .y_label_area_size(80)
            .build_cartesian_2d(
                (e0 / 2.0..e1 * 2.0).log_scale(),
                (w0 / 2.0..w1 * 2.0).log_scale(),
            )?;
        chart
            .configure_mesh()
            .x_desc("relative error in q at t = 0.5 s")
            .y_desc(label)
            .x_label_formatter(&|v| format!("{v:.0e}"))
            .y_label_formatter(&|v| format!("{v:.0e}"))
            .draw()?;
        for (name, color) in methods.iter().zip(colors) {
            // In the order of the settings (coarse to fine), a marker at each.
            let pts: Vec<(f64, f64)> = rows
                .iter()
                .filter(|r| r.method == *name)
                .map(|r| (err(r), work(r)))
                .collect();
            chart.draw_series(pts.iter().map(|p| Circle::new(*p, 3, color.filled())))?;
            chart
                .draw_series(LineSeries::new(pts, color.stroke_width(2)))?
                .label(*name)
                .legend(move |(x, y)| {
                    PathElement::new(vec![(x, y), (x + 20, y)], color.stroke_width(2))
                });
        }
        chart
            .configure_series_labels()
            .background_style(WHITE.mix(0.85))
            .border_style(BLACK)
            .draw()?;
    }
    root.present()?;
    Ok(path)
}
