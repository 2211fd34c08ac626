//! Output formats of the tabular commands: `table` (aligned, units in the header), `csv`
//! (a header of column names, SI), `json` (an array of objects keyed by column name).
//! Data go to standard output; messages and progress to standard error.

use std::io::{self, Write};

/// The output format.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, clap::ValueEnum)]
pub enum Format {
    /// Aligned columns, a header with the units.
    #[default]
    Table,
    /// Comma-separated values, a header of column names.
    Csv,
    /// A JSON array of objects, one per row.
    Json,
}

/// Where rows go: the plain stream, or a CSV writer over it.
enum Sink<W: Write> {
    Plain(W),
    Csv(csv::Writer<W>),
}

/// Writes rows in one format, streaming (rows may come in chunks).
pub struct Writer<W: Write> {
    sink: Sink<W>,
    format: Format,
    names: Vec<String>,
    rows: usize,
}

/// The width of a table column.
const WIDTH: usize = 16;

impl<W: Write> Writer<W> {
    /// A writer of rows with these column names and units; writes the header.
    pub fn new(mut out: W, format: Format, names: &[String], units: &[&str]) -> io::Result<Self> {
        let sink = match format {
            Format::Table => {
                let head: Vec<String> = names.iter().zip(units).map(|(n, u)| format!("{:>WIDTH$}", format!("{n} [{u}]"))).collect();
                writeln!(out, "{}", head.join(" "))?;
                Sink::Plain(out)
            }
            Format::Csv => {
                let mut c = csv::Writer::from_writer(out);
                c.write_record(names)?;
                Sink::Csv(c)
            }
            Format::Json => {
                write!(out, "[")?;
                Sink::Plain(out)
            }
        };
        Ok(Writer { sink, format, names: names.to_vec(), rows: 0 })
    }

    /// One row (as many values as names).
    pub fn row(&mut self, values: &[f64]) -> io::Result<()> {
        match (&mut self.sink, self.format) {
            (Sink::Csv(c), _) => c.write_record(values.iter().map(|v| v.to_string()))?,
            (Sink::Plain(out), Format::Table) => {
                let cells: Vec<String> = values.iter().map(|v| format!("{:>WIDTH$}", format!("{v:.9e}"))).collect();
                writeln!(out, "{}", cells.join(" "))?;
            }
            (Sink::Plain(out), _) => {
                let obj: serde_json::Map<String, serde_json::Value> = self
                    .names
                    .iter()
                    .zip(values)
                    .map(|(n, v)| (n.clone(), serde_json::Number::from_f64(*v).map_or(serde_json::Value::Null, serde_json::Value::Number)))
                    .collect();
                let sep = if self.rows == 0 { "\n" } else { ",\n" };
                write!(out, "{sep}  {}", serde_json::Value::Object(obj))?;
            }
        }
        self.rows += 1;
        Ok(())
    }

    /// Close the output (the JSON array's bracket, the CSV writer's buffer).
    pub fn finish(self) -> io::Result<()> {
        match self.sink {
            Sink::Csv(mut c) => c.flush(),
            Sink::Plain(mut out) => {
                if self.format == Format::Json {
                    writeln!(out, "\n]")?;
                }
                out.flush()
            }
        }
    }
}
