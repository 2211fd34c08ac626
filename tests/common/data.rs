//! Reading the committed high-precision references of `tests/data` (written by the
//! scripts under `tools/`): a file as JSON, a number stored as a string of many digits
//! (or as a plain JSON number), and the comparison that names what differs. A module of the
//! `machines` test binary (`tests/machines.rs`): use it with `use crate::data;`.

#![allow(dead_code)]

use serde_json::Value;

/// `tests/data/<file>` as JSON.
pub fn load(file: &str) -> Value {
    let path = format!("{}/tests/data/{file}", env!("CARGO_MANIFEST_DIR"));
    let text = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{path}: {e}"));
    serde_json::from_str(&text).unwrap_or_else(|e| panic!("{path}: {e}"))
}

/// A reference number: a decimal string (mpmath's digits, rounded once to f64 here) or a
/// JSON number.
pub fn num(v: &Value) -> f64 {
    match v {
        Value::String(s) => s.parse().unwrap_or_else(|e| panic!("{s}: {e}")),
        _ => v.as_f64().unwrap_or_else(|| panic!("not a number: {v}")),
    }
}

/// Assert |got − want| ≤ tol (absolute: the caller scales it), naming `what`; measured
/// at the caller's line (`tests/common/measure.rs`).
#[track_caller]
pub fn close(what: &str, got: f64, want: f64, tol: f64) {
    assert!(
        crate::measure::within_at(crate::measure::label(what), (got - want).abs(), tol),
        "{what}: {got:.17e} vs reference {want:.17e} (|diff| {:.2e} > {tol:.2e})",
        (got - want).abs()
    );
}
