//! The tolerance check of the tests, and how a tolerance is measured (issue 28; the
//! rule is in `tests/README.md`, "Tolerances"): every comparison with a tolerance goes
//! through [`within`] (or [`within_at`]), which returns `err <= tol`. With the environment
//! variable `MECH_MEASURE` set, it also keeps, for each call site, the worst `err / tol`
//! seen, and prints a line whenever a site's worst grows:
//!
//! ```text
//! MEASURE tests/flywheel.rs:81:9 ratio 1.23e-2 err 1.23e-16 tol 1.0e-14
//! ```
//!
//! so the last line of a site is its worst over the run; `tests/README.md` has the
//! one-liner that reduces a run to one line per site. A tolerance at most 100× the error
//! measured is a ratio of at least 0.01.
//!
//! A module of both root binaries (`tests/suite.rs`, `tests/machines.rs`): use it with
//! `use crate::measure::within;`.

#![allow(dead_code)]

use std::collections::HashMap;
use std::panic::Location;
use std::sync::atomic::{AtomicU8, Ordering};
use std::sync::Mutex;

/// 0: not looked up yet; 1: off; 2: on.
static STATE: AtomicU8 = AtomicU8::new(0);
static WORST: Mutex<Option<HashMap<String, f64>>> = Mutex::new(None);

fn measuring() -> bool {
    match STATE.load(Ordering::Relaxed) {
        0 => {
            let on = std::env::var_os("MECH_MEASURE").is_some();
            STATE.store(if on { 2 } else { 1 }, Ordering::Relaxed);
            on
        }
        s => s == 2,
    }
}

/// Record `err / tol` under `key` when measuring.
fn record(key: String, err: f64, tol: f64) {
    // An exact comparison (tol 0) that holds measures 0.
    let ratio = if err == 0.0 { 0.0 } else { err / tol };
    let mut w = WORST.lock().unwrap_or_else(|e| e.into_inner());
    let map = w.get_or_insert_with(HashMap::new);
    // A signed excess (a bound checked one way) may measure below 0.
    let worst = map.entry(key.clone()).or_insert(f64::NEG_INFINITY);
    if ratio > *worst || (ratio.is_nan() && !worst.is_nan()) {
        *worst = ratio;
        println!("MEASURE {key} ratio {ratio:.2e} err {err:.2e} tol {tol:.1e}");
    }
}

/// The fixed part of a check's description, naming a measurement: `what` up to its first
/// formatted part (" at ", ": ", " q", " (", "=" or a digit).
pub fn label(what: &str) -> &str {
    let mut end = what.len();
    for cut in [" at ", ": ", " q", " (", "="] {
        if let Some(i) = what.find(cut) {
            end = end.min(i);
        }
    }
    if let Some(i) = what.find(|c: char| c.is_ascii_digit()) {
        end = end.min(i);
    }
    what[..end].trim_end()
}

/// `err <= tol` (false for a NaN), the caller's file and line naming the measurement.
#[track_caller]
pub fn within(err: f64, tol: f64) -> bool {
    if measuring() {
        let l = Location::caller();
        record(
            format!("{}:{}:{}", l.file(), l.line(), l.column()),
            err,
            tol,
        );
    }
    err <= tol
}

/// [`within`] for a check inside a macro or a shared helper, where the caller's line is
/// not the check's: `key` (with the caller's file and line) names it.
#[track_caller]
pub fn within_at(key: &str, err: f64, tol: f64) -> bool {
    if measuring() {
        let l = Location::caller();
        record(
            format!("{}:{}:{} {key}", l.file(), l.line(), l.column()),
            err,
            tol,
        );
    }
    err <= tol
}
