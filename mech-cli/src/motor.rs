//! `--motor MODEL [--ratio N]`: the motor of `mech simulate` and `mech regime`
//! (`mech_core::dynamics::motor`), written `dc(stall_torque .., no_load_speed ..)`,
//! `induction(rated_power .., synchronous_speed .., rated_speed .., breakdown_ratio ..)`,
//! `table(FILE.csv)` (columns `speed`, rad/s, or `speed_rpm`, and `torque`, N·m) or
//! `constant(T)`.

use crate::{limits, Failure};
use mech_core::dynamics::motor::Motor;
use mech_core::MechError;
use std::path::Path;

/// The motor `text` through the reduction `ratio` (motor speed / input speed).
pub fn parse(text: &str, ratio: f64) -> Result<Motor, Failure> {
    crate::limits::nesting(text, "--motor")?;
    let motor =
        Motor::parse(text, &read_table).map_err(|e| Failure::usage(format!("--motor: {e}")))?;
    motor
        .through(ratio)
        .map_err(|e| Failure::usage(format!("--ratio: {e}")))
}

/// A torque–speed table from a CSV file.
fn read_table(path: &str) -> Result<Motor, MechError> {
    let text = limits::read_text(Path::new(path), limits::TABLE_BYTES, "--motor table(..)")
        .map_err(|e| MechError::InvalidInput(e.message))?;
    let bad = |m: String| MechError::InvalidInput(format!("{path}: {m}"));
    let mut r = csv::ReaderBuilder::new()
        .trim(csv::Trim::All)
        .from_reader(text.as_bytes());
    let headers = r.headers().map_err(|e| bad(e.to_string()))?.clone();
    let scale = match headers.get(0) {
        Some("speed") => 1.0,
        Some("speed_rpm") => std::f64::consts::PI / 30.0,
        other => {
            return Err(bad(format!(
                "the first column must be `speed` (rad/s) or `speed_rpm`, found `{}`; the second `torque` (N·m)",
                other.unwrap_or("")
            )))
        }
    };
    if headers.get(1) != Some("torque") || headers.len() != 2 {
        return Err(bad(
            "a motor table has two columns: `speed` (or `speed_rpm`) and `torque` (N·m)".into(),
        ));
    }
    let (mut speed, mut torque) = (Vec::new(), Vec::new());
    for (k, row) in r.records().enumerate() {
        let row = row.map_err(|e| bad(e.to_string()))?;
        let num = |i: usize| -> Result<f64, MechError> {
            row.get(i)
                .and_then(|s| s.parse::<f64>().ok())
                .ok_or_else(|| {
                    bad(format!(
                        "row {}: `{}` is not a number",
                        k + 2,
                        row.get(i).unwrap_or("")
                    ))
                })
        };
        speed.push(num(0)? * scale);
        torque.push(num(1)?);
    }
    Motor::table(speed, torque).map_err(|e| bad(e.to_string()))
}
