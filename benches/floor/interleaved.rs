//! The ratio generated / hand measured *interleaved*: a criterion [`Measurement`] whose
//! value is a ratio, not a time.
//!
//! On a shared machine the speed of one core drifts over seconds (other tenants, frequency
//! changes), and criterion times the two functions of a group one after the other, seconds
//! apart, so the ratio of their medians carries that drift (on this project's 2-core
//! machines the same code gave 0.9× to 2.0× for one operation over three runs). Here one
//! iteration is one call of each; every sample alternates blocks of [`BLOCK`] calls of the
//! generated and of the hand-written code (which one goes first alternates too), timing
//! each block, and reports
//!
//! value(sample) = (Σ t_generated / Σ t_hand) · iterations,
//!
//! so that criterion's per-iteration estimate (its median over the samples, its slope) is
//! the ratio itself, both sides of each sample having run under the same conditions.
//! Criterion plans the iteration counts from the wall time of its warm-up, not from these
//! values, so the run takes about the configured measurement time.

use criterion::measurement::{Measurement, ValueFormatter};
use criterion::{black_box, Throughput};
use std::time::Instant;

/// Calls per timed block: enough that the two clock readings per block (≈ 25 ns each)
/// are below 0.5 % of the block, few enough that the blocks of the two sides interleave
/// many times per sample.
pub const BLOCK: u64 = 256;

/// The measurement: its value is a ratio (dimensionless) times the iteration count.
pub struct Interleaved;

impl Measurement for Interleaved {
    type Intermediate = ();
    type Value = f64;
    fn start(&self) {}
    fn end(&self, _: ()) -> f64 {
        // Only `iter_custom` is meaningful for this measurement (`ratio` below).
        0.0
    }
    fn add(&self, a: &f64, b: &f64) -> f64 {
        a + b
    }
    fn zero(&self) -> f64 {
        0.0
    }
    fn to_f64(&self, v: &f64) -> f64 {
        *v
    }
    fn formatter(&self) -> &dyn ValueFormatter {
        &RatioFormat
    }
}

/// Shows a value as a ratio, `1.23×`.
struct RatioFormat;

impl ValueFormatter for RatioFormat {
    fn format_value(&self, value: f64) -> String {
        format!("{value:.3}×")
    }
    fn format_throughput(&self, _: &Throughput, value: f64) -> String {
        self.format_value(value)
    }
    fn scale_values(&self, _: f64, _: &mut [f64]) -> &'static str {
        "×"
    }
    fn scale_throughputs(&self, _: f64, _: &Throughput, _: &mut [f64]) -> &'static str {
        "×"
    }
    fn scale_for_machines(&self, _: &mut [f64]) -> &'static str {
        "ratio"
    }
}

/// `n` calls of `f` (m, s): the block [`ratio`] times.
#[inline(always)]
fn block<R>(n: u64, f: &mut impl FnMut() -> R) -> f64 {
    let t0 = Instant::now();
    for _ in 0..n {
        black_box(f());
    }
    t0.elapsed().as_secs_f64()
}

/// One sample of `iters` iterations: blocks of `generated` and `hand` alternated, then
/// (Σ t_generated / Σ t_hand) · iters.
pub fn ratio<RA, RB>(
    iters: u64,
    mut generated: impl FnMut() -> RA,
    mut hand: impl FnMut() -> RB,
) -> f64 {
    let (mut tg, mut th) = (0.0, 0.0);
    let mut left = iters;
    let mut generated_first = true;
    while left > 0 {
        let n = left.min(BLOCK);
        if generated_first {
            tg += block(n, &mut generated);
            th += block(n, &mut hand);
        } else {
            th += block(n, &mut hand);
            tg += block(n, &mut generated);
        }
        generated_first = !generated_first;
        left -= n;
    }
    tg / th * iters as f64
}
