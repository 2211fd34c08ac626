//! Compile-fail suite of the `mechanism!` checks (`docs/conventions.md#checks`): every case under
//! `tests/ui/` is a small realistic mechanism with exactly one mistake, and its `.stderr`
//! holds the expected diagnostics (message and span).
//!
//! Regenerate the expected output after a deliberate change of a message with
//! `TRYBUILD=overwrite cargo test --test machines compile_fail::`, then read every changed `.stderr`.

#[test]
fn ui() {
    let t = trybuild::TestCases::new();
    t.compile_fail("tests/ui/*.rs");
}
