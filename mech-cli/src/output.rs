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

/// Writes rows in one format, streaming (rows may come in chunks). A row is first
/// rendered to text ([`Renderer::render`], pure: chunks render in parallel), then written in
/// order ([`Writer::push`]).
pub struct Writer<W: Write> {
    out: W,
    renderer: Renderer,
    rows: usize,
}

/// How a row becomes text (shared by the threads of a sweep).
#[derive(Clone, Debug)]
pub struct Renderer {
    format: Format,
    names: Vec<String>,
}

/// The width of a table column.
const WIDTH: usize = 16;

impl<W: Write> Writer<W> {
    /// A writer of rows with these column names and units; writes the header.
    pub fn new(mut out: W, format: Format, names: &[String], units: &[&str]) -> io::Result<Self> {
        match format {
            Format::Table => {
                let head: Vec<String> = names
                    .iter()
                    .zip(units)
                    .map(|(n, u)| match u.is_empty() {
                        true => format!("{n:>WIDTH$}"),
                        false => format!("{:>WIDTH$}", format!("{n} [{u}]")),
                    })
                    .collect();
                writeln!(out, "{}", head.join(" "))?;
            }
            Format::Csv => {
                let mut c = csv::Writer::from_writer(&mut out);
                c.write_record(names)?;
                c.flush()?;
            }
            Format::Json => write!(out, "[")?,
        }
        Ok(Writer {
            out,
            renderer: Renderer {
                format,
                names: names.to_vec(),
            },
            rows: 0,
        })
    }

    /// The renderer of this writer's rows.
    pub fn renderer(&self) -> &Renderer {
        &self.renderer
    }

    /// Write a rendered row.
    pub fn push(&mut self, rendered: &str) -> io::Result<()> {
        match self.renderer.format {
            Format::Json => write!(
                self.out,
                "{}  {rendered}",
                if self.rows == 0 { "\n" } else { ",\n" }
            )?,
            _ => writeln!(self.out, "{rendered}")?,
        }
        self.rows += 1;
        Ok(())
    }

    /// Render and write one row.
    pub fn row(&mut self, values: &[f64]) -> io::Result<()> {
        let r = self.renderer.render(values);
        self.push(&r)
    }

    /// Render and write one row of text and numbers.
    pub fn cells(&mut self, cells: &[Cell]) -> io::Result<()> {
        let r = self.renderer.render_cells(cells);
        self.push(&r)
    }

    /// Close the output (the JSON array's bracket) and flush.
    pub fn finish(mut self) -> io::Result<()> {
        if self.renderer.format == Format::Json {
            writeln!(self.out, "\n]")?;
        }
        self.out.flush()
    }
}

/// One value of a row that has text columns (`mech strength`'s member and criterion).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Cell<'a> {
    /// A name.
    Text(&'a str),
    /// A number.
    Num(f64),
}

impl Renderer {
    /// One row of text and numbers as text: numbers in shortest round-trip form for CSV
    /// and JSON, 10 significant digits in the table; text as is (quoted in CSV when it
    /// holds a comma, a quote or a line break).
    pub fn render_cells(&self, cells: &[Cell]) -> String {
        match self.format {
            Format::Csv => cells
                .iter()
                .map(|c| match c {
                    Cell::Text(t) if t.contains([',', '"', '\n', '\r']) => {
                        format!("\"{}\"", t.replace('"', "\"\""))
                    }
                    Cell::Text(t) => t.to_string(),
                    Cell::Num(v) => v.to_string(),
                })
                .collect::<Vec<_>>()
                .join(","),
            Format::Table => cells
                .iter()
                .map(|c| match c {
                    Cell::Text(t) => format!("{t:>WIDTH$}"),
                    Cell::Num(v) => format!("{:>WIDTH$}", format!("{v:.9e}")),
                })
                .collect::<Vec<_>>()
                .join(" "),
            Format::Json => {
                let obj: serde_json::Map<String, serde_json::Value> = self
                    .names
                    .iter()
                    .zip(cells)
                    .map(|(n, c)| {
                        let v = match c {
                            Cell::Text(t) => serde_json::Value::String(t.to_string()),
                            Cell::Num(v) => serde_json::Number::from_f64(*v)
                                .map_or(serde_json::Value::Null, serde_json::Value::Number),
                        };
                        (n.clone(), v)
                    })
                    .collect();
                serde_json::Value::Object(obj).to_string()
            }
        }
    }

    /// One row as text (as many values as names): numbers in shortest round-trip form
    /// for CSV and JSON, 10 significant digits in the table.
    pub fn render(&self, values: &[f64]) -> String {
        let cells: Vec<Cell> = values.iter().map(|&v| Cell::Num(v)).collect();
        self.render_cells(&cells)
    }
}
