//! Loads on the command line: `--load NAME=VALUE` with a constant (`--load load=-4`,
//! `--load gas=-1500,0`, units allowed: `--load gas=-1.5kN,0`) or a table
//! (`--load gas=@gas.csv`): a CSV file whose first column is the input q (header `q`, rad,
//! or `q_deg`, degrees) and whose next one (torque, N·m) or two (force x and y, N) columns
//! are the load. A table is interpolated linearly in q and repeats with the period
//! q_last − q_first (a cycle: its last row closes on its first).

use crate::quantity;
use crate::Failure;
use mech_core::model::units::Dim;
use mech_core::model::{Load, Model};
use mech_core::Mechanism;
use std::path::Path;

/// A load's values against the input q.
#[derive(Clone, Debug, PartialEq)]
pub struct Table {
    q: Vec<f64>,
    values: Vec<Vec<f64>>,
}

impl Table {
    /// Read a table of `width` value columns from CSV text (`origin` for messages).
    pub fn parse(text: &str, width: usize, origin: &str) -> Result<Self, Failure> {
        let mut r = csv::ReaderBuilder::new()
            .trim(csv::Trim::All)
            .from_reader(text.as_bytes());
        let headers = r
            .headers()
            .map_err(|e| Failure::usage(format!("{origin}: {e}")))?
            .clone();
        let scale = match headers.get(0) {
            Some("q") => 1.0,
            Some("q_deg") => std::f64::consts::PI / 180.0,
            other => return Err(Failure::usage(format!("{origin}: the first column must be `q` (rad) or `q_deg` (degrees), found {other:?}"))),
        };
        let (mut q, mut values) = (Vec::new(), Vec::new());
        for (i, rec) in r.records().enumerate() {
            let rec = rec.map_err(|e| Failure::usage(format!("{origin}: {e}")))?;
            let nums: Result<Vec<f64>, _> = rec.iter().map(str::parse::<f64>).collect();
            let nums = nums.map_err(|e| Failure::usage(format!("{origin}: row {}: {e}", i + 2)))?;
            if nums.len() != width + 1 || nums.iter().any(|x| !x.is_finite()) {
                return Err(Failure::usage(format!(
                    "{origin}: row {}: expected q and {width} finite value(s), found {:?}",
                    i + 2,
                    nums
                )));
            }
            if let Some(&last) = q.last() {
                if !(nums[0] * scale > last) {
                    return Err(Failure::usage(format!(
                        "{origin}: row {}: q must increase",
                        i + 2
                    )));
                }
            }
            q.push(nums[0] * scale);
            values.push(nums[1..].to_vec());
        }
        if q.len() < 2 {
            return Err(Failure::usage(format!(
                "{origin}: a table needs at least two rows"
            )));
        }
        Ok(Table { q, values })
    }

    /// The load at q: linear interpolation, the table repeating with its span.
    pub fn at(&self, q: f64) -> Vec<f64> {
        let (q0, qn) = (self.q[0], *self.q.last().unwrap());
        let span = qn - q0;
        let x = q0 + (q - q0).rem_euclid(span);
        let k = self
            .q
            .partition_point(|&t| t <= x)
            .clamp(1, self.q.len() - 1);
        let (a, b) = (self.q[k - 1], self.q[k]);
        let t = (x - a) / (b - a);
        self.values[k - 1]
            .iter()
            .zip(&self.values[k])
            .map(|(u, v)| u + t * (v - u))
            .collect()
    }
}

/// How one load is given.
#[derive(Clone, Debug, PartialEq)]
pub enum Value {
    /// The same at every input.
    Constant(Vec<f64>),
    /// Against the (first) input.
    Table(Table),
}

/// The loads of a run: a value per declared load that was given.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct LoadSet {
    given: Vec<(String, Value)>,
}

fn width(model: &Model, name: &str) -> Result<usize, Failure> {
    match model.loads.iter().find(|l| l.name() == name) {
        Some(Load::Force { .. }) => Ok(2),
        Some(Load::Torque { .. }) => Ok(1),
        None => {
            let names: Vec<&str> = model.loads.iter().map(|l| l.name()).collect();
            Err(Failure::usage(format!(
                "no load named `{name}`: the mechanism's loads are {}",
                if names.is_empty() {
                    "none".into()
                } else {
                    names.join(", ")
                }
            )))
        }
    }
}

impl LoadSet {
    /// From `--load NAME=VALUE` arguments.
    pub fn parse(args: &[String], model: &Model) -> Result<Self, Failure> {
        let mut given = Vec::new();
        for a in args {
            let Some((name, value)) = a.split_once('=') else {
                return Err(Failure::usage(format!(
                    "--load `{a}`: expected NAME=VALUE, e.g. `gas=-1500,0` or `gas=@gas.csv`"
                )));
            };
            let name = name.trim();
            let w = width(model, name)?;
            let value = if let Some(path) = value.strip_prefix('@') {
                let text = std::fs::read_to_string(Path::new(path)).map_err(|e| {
                    Failure::usage(format!("--load {name}: cannot read {path}: {e}"))
                })?;
                Value::Table(Table::parse(&text, w, path)?)
            } else {
                let dim = if w == 2 { Dim::FORCE } else { Dim::TORQUE };
                let parts: Vec<&str> = value.split(',').collect();
                if parts.len() != w {
                    let shape = if w == 2 {
                        "a force: two components `fx,fy` (N)"
                    } else {
                        "a torque: one value (N·m)"
                    };
                    return Err(Failure::usage(format!(
                        "--load {name}: `{value}` has {} component(s), but `{name}` is {shape}",
                        parts.len()
                    )));
                }
                Value::Constant(
                    parts
                        .iter()
                        .map(|p| quantity::parse(p, dim, &format!("--load {name}")))
                        .collect::<Result<_, _>>()?,
                )
            };
            given.push((name.to_string(), value));
        }
        Ok(LoadSet { given })
    }

    /// The loads at input q (the first input's value for the tables).
    pub fn at(&self, m: &Mechanism, q: f64) -> mech_core::runtime::mechanism::Loads {
        let mut loads = m.loads();
        for (name, v) in &self.given {
            let value = match v {
                Value::Constant(c) => c.clone(),
                Value::Table(t) => t.at(q),
            };
            loads.set_by_name(name, &value);
        }
        loads
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tables_interpolate_and_repeat() {
        let t = Table::parse("q_deg, f\n0, 0\n90, 10\n360, 0\n", 1, "t.csv").unwrap();
        let quarter = std::f64::consts::FRAC_PI_2;
        assert!((t.at(quarter / 2.0)[0] - 5.0).abs() < 1e-12);
        assert!((t.at(quarter / 2.0 + 2.0 * std::f64::consts::PI)[0] - 5.0).abs() < 1e-12);
        assert!((t.at(-1.5 * quarter)[0] - t.at(4.0 * quarter - 1.5 * quarter)[0]).abs() < 1e-12);
        assert!(
            (t.at(-1.5 * quarter)[0] - 5.0).abs() < 1e-12,
            "at 225° = −135°: 10 (1 − 135/270)"
        );
        assert!(Table::parse("x, f\n0, 1\n1, 2\n", 1, "t.csv").is_err());
        assert!(Table::parse("q, f\n0, 1\n0, 2\n", 1, "t.csv").is_err());
        assert!(Table::parse("q, fx\n0, 1\n1, 2\n", 2, "t.csv").is_err());
    }
}
