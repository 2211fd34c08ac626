//! `mech solve` (one configuration) and `mech sweep` (a range of inputs, in parallel, one
//! row per input, streamed in chunks so that a million rows need no more memory than a
//! chunk, with a progress bar on standard error when the sweep is long).

use crate::columns::Level;
use crate::loads::LoadSet;
use crate::output::{Format, Writer};
use crate::Failure;
use mech_core::Mechanism;
use rayon::prelude::*;
use std::io::Write;

/// Rows per chunk of a sweep: solved in parallel (the batch runner cuts it for the
/// threads), then written in order.
const CHUNK: usize = 16384;

/// Sweeps longer than this show a progress bar (on a terminal).
const PROGRESS_FROM: usize = 20_000;

/// One configuration in `format`. The table format lists one quantity per line with its
/// unit; CSV and JSON give the one row.
#[allow(clippy::too_many_arguments)]
pub fn solve(
    m: &Mechanism,
    q: &[f64],
    qd: &[f64],
    qdd: &[f64],
    loads: &LoadSet,
    level: Level,
    format: Format,
    out: impl Write,
) -> Result<(), Failure> {
    let cols = level.columns(m);
    let row = cols.row(m, q, qd, qdd, &loads.at(m, q[0]))?;
    if format == Format::Table {
        let mut out = out;
        let w = cols.names.iter().map(String::len).max().unwrap_or(1);
        for ((n, u), v) in cols.names.iter().zip(&cols.units).zip(&row) {
            writeln!(out, "{n:<w$}  {v:>20.12e}  {u}")?;
        }
        out.flush()?;
        return Ok(());
    }
    let mut w = Writer::new(out, format, &cols.names, &cols.units)?;
    w.row(&row)?;
    w.finish()?;
    Ok(())
}

/// The inputs of a sweep: `steps` + 1 values from `from` to `to` (both included) for the
/// first input; the other inputs (several DOF) stay at `rest`.
pub fn inputs(from: f64, to: f64, steps: usize, k: usize) -> f64 {
    if steps == 0 {
        from
    } else {
        from + (to - from) * k as f64 / steps as f64
    }
}

/// A sweep of the first input from `from` to `to` in `steps` steps; the other inputs at
/// `rest`; a row per input, in order.
#[allow(clippy::too_many_arguments)]
pub fn sweep(
    m: &Mechanism,
    (from, to, steps): (f64, f64, usize),
    rest: &[f64],
    qd: &[f64],
    qdd: &[f64],
    loads: &LoadSet,
    level: Level,
    format: Format,
    out: impl Write,
) -> Result<(), Failure> {
    let cols = level.columns(m);
    let mut w = Writer::new(out, format, &cols.names, &cols.units)?;
    let total = steps + 1;
    let renderer = w.renderer().clone();
    let bar = if total >= PROGRESS_FROM {
        let b = indicatif::ProgressBar::new(total as u64);
        b.set_style(
            indicatif::ProgressStyle::with_template(
                "{bar:40} {pos}/{len} configurations, {per_sec}, eta {eta}",
            )
            .expect("template"),
        );
        Some(b)
    } else {
        None
    };
    // One chunk of rows at a time through the batch runner (`Columns::rows_many`, on rayon's
    // pool), then rendered in parallel and written in order.
    let g = m.dof();
    let width = cols.names.len();
    let constant = loads.is_constant().then(|| loads.at(m, from));
    let (mut q, mut buf) = (Vec::new(), Vec::new());
    let (qds, qdds) = (qd.repeat(CHUNK), qdd.repeat(CHUNK));
    for start in (0..total).step_by(CHUNK) {
        let end = (start + CHUNK).min(total);
        q.clear();
        for k in start..end {
            q.push(inputs(from, to, steps, k));
            q.extend_from_slice(&rest[1..]);
        }
        let (qd, qdd) = (&qds[..q.len()], &qdds[..q.len()]);
        buf.resize((end - start) * width, 0.0);
        let at = |i: usize| match &constant {
            Some(c) => std::borrow::Cow::Borrowed(c),
            None => std::borrow::Cow::Owned(loads.at(m, q[i * g])),
        };
        let errors = cols.rows_many(m, &q, qd, qdd, &at, &mut buf);
        if let Some(e) = errors.refusal() {
            return Err(Failure::mechanism(e.to_string()));
        }
        let good = errors.indices().first().copied().unwrap_or(end - start);
        let rows: Vec<String> = buf[..good * width]
            .par_chunks(width)
            .map(|row| renderer.render(row))
            .collect();
        for r in &rows {
            w.push(r)?;
        }
        if let Some((i, e)) = errors.iter().next() {
            return Err(Failure::mechanism(format!("at q = {}: {}", q[i * g], e)));
        }
        if let Some(b) = &bar {
            b.set_position(end as u64);
        }
    }
    if let Some(b) = bar {
        b.finish_and_clear();
    }
    w.finish()?;
    Ok(())
}
