//! Loads on the command line: `--load NAME=VALUE` with a constant (`--load load=-4`,
//! `--load gas=-1500,0`, units allowed: `--load gas=-1.5kN,0`) or a table
//! (`--load gas=@gas.csv`): a CSV file whose first column is the input q (header `q`, rad,
//! or `q_deg`, degrees) and whose next one (torque, N·m) or two (force x and y, N) columns
//! are the load. A table is interpolated linearly in q and repeats with the period
//! q_last − q_first (a cycle: its last row closes on its first).

use crate::Failure;
use crate::{limits, quantity};
use mech_core::model::units::Dim;
use mech_core::model::{Load, Model};
use mech_core::Mechanism;
use std::path::Path;

/// A load's values against the input q.
#[derive(Clone, Debug, PartialEq)]
pub struct Table {
    q: Vec<f64>,
    /// Row after row, `width` values each.
    values: Vec<f64>,
    width: usize,
}

impl Table {
    /// The table of the CSV file `path` (`flag` names it in messages): at most
    /// [`limits::TABLE_BYTES`] of UTF-8 text.
    pub fn read(path: &str, width: usize, flag: &str) -> Result<Self, Failure> {
        let text = limits::read_text(Path::new(path), limits::TABLE_BYTES, flag)?;
        Table::parse(&text, width, path)
    }

    /// Read a table of `width` value columns from CSV text (`origin` for messages).
    pub fn parse(text: &str, width: usize, origin: &str) -> Result<Self, Failure> {
        let bad = |m: String| Failure::usage(format!("{origin}: {m}"));
        let shape = format!(
            "a header `q` (or `q_deg`) and {width} value column(s), {} in all",
            width + 1
        );
        let mut r = csv::ReaderBuilder::new()
            .trim(csv::Trim::All)
            .flexible(true)
            .from_reader(text.as_bytes());
        let headers = r.headers().map_err(|e| bad(e.to_string()))?.clone();
        let scale = match headers.get(0) {
            Some("q") => 1.0,
            Some("q_deg") => std::f64::consts::PI / 180.0,
            None | Some("") if headers.len() <= 1 => {
                return Err(bad(format!(
                    "empty; a table needs {shape}, then at least two rows"
                )))
            }
            Some(other) => {
                let hint = if other.contains([';', '\t']) {
                    " (columns are separated by commas)"
                } else {
                    ""
                };
                return Err(bad(format!(
                    "the first column must be `q` (rad) or `q_deg` (degrees), found `{other}`{hint}"
                )));
            }
            None => unreachable!("a record of two or more fields has a first"),
        };
        if headers.len() != width + 1 {
            let names: Vec<&str> = headers.iter().collect();
            return Err(bad(format!(
                "{} column(s) (`{}`), but this load needs {shape}",
                headers.len(),
                names.join(", ")
            )));
        }
        for (i, h) in headers.iter().enumerate() {
            if let Some(j) = headers.iter().take(i).position(|g| g == h) {
                return Err(bad(format!(
                    "the column name `{h}` appears twice (columns {} and {}); name each column once",
                    j + 1,
                    i + 1
                )));
            }
        }
        let (mut q, mut values) = (Vec::new(), Vec::new());
        let mut record = csv::StringRecord::new();
        loop {
            match r.read_record(&mut record) {
                Ok(true) => {}
                Ok(false) => break,
                Err(e) => return Err(bad(e.to_string())),
            }
            let line = record.position().map_or(0, |p| p.line());
            if let Some(field) = record.iter().find(|f| f.contains('\n')) {
                return Err(bad(format!(
                    "line {line}: an unterminated quote (`\"`) runs over {} line(s); close it or remove it",
                    field.matches('\n').count() + 1
                )));
            }
            if record.len() != width + 1 {
                return Err(bad(format!(
                    "line {line}: {} field(s), but the header has {}",
                    record.len(),
                    width + 1
                )));
            }
            for (c, field) in record.iter().enumerate() {
                let x: f64 = field.parse().map_err(|_| {
                    bad(format!(
                        "line {line}, column {} (`{}`): not a number{}",
                        c + 1,
                        field.chars().take(40).collect::<String>(),
                        if field.contains('"') {
                            " (an unbalanced quote `\"`?)"
                        } else {
                            ""
                        }
                    ))
                })?;
                if !x.is_finite() {
                    return Err(bad(format!(
                        "line {line}, column {} (`{field}`): not a finite number",
                        c + 1
                    )));
                }
                if c == 0 {
                    let x = x * scale;
                    if let Some(&last) = q.last() {
                        if !(x > last) {
                            return Err(bad(format!(
                                "line {line}: q = {field} does not increase; sort the rows by q, each q once"
                            )));
                        }
                    }
                    q.push(x);
                } else {
                    values.push(x);
                }
            }
        }
        if q.len() < 2 {
            return Err(bad(format!(
                "{} row(s); a table needs at least two rows after its header",
                q.len()
            )));
        }
        let (first, last) = (q[0], q[q.len() - 1]);
        if !(last - first).is_finite() {
            return Err(bad(format!(
                "q spans from {} to {}: too wide to interpolate in f64; give q in one cycle",
                limits::show(first),
                limits::show(last)
            )));
        }
        Ok(Table { q, values, width })
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
        let w = self.width;
        self.values[(k - 1) * w..k * w]
            .iter()
            .zip(&self.values[k * w..(k + 1) * w])
            .map(|(u, v)| {
                let d = v - u;
                // Two values of opposite signs near f64's largest: d overflows, the
                // weighted mean does not.
                if d.is_finite() {
                    u + t * d
                } else {
                    u * (1.0 - t) + v * t
                }
            })
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
                Value::Table(Table::read(path, w, &format!("--load {name}"))?)
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

    /// True when no load is a table: the loads are the same at every input.
    pub fn is_constant(&self) -> bool {
        self.given
            .iter()
            .all(|(_, v)| matches!(v, Value::Constant(_)))
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

    #[test]
    fn values_near_the_largest_f64_interpolate_finitely() {
        let t = Table::parse("q, f\n0, 1e308\n1, -1e308\n", 1, "t.csv").unwrap();
        for q in [0.0, 0.25, 0.5, 0.75, 0.999] {
            let v = t.at(q)[0];
            assert!(v.is_finite(), "at {q}: {v}");
        }
        assert_eq!(t.at(0.5)[0], 0.0);
    }
}
