//! What the tool accepts (`docs/cli.md#limits`): the size of the files it reads, the
//! counts it is asked for (`--steps`, `--samples`, `--points`, `--frames`), the numbers of
//! its plain flags, the nesting of a text, and where it may write. Each is refused beyond
//! its bound by a message with the value, the bound and the fix, before any work is done:
//! hostile input ends in a clean exit status 2, never a panic, a hang or an allocation
//! of the size it names (`mech-cli/tests/hostile.rs`).

use crate::Failure;
use std::io::{self, Read, Write};
use std::path::Path;

/// The largest mechanism or PMKS file, bytes (the largest example is a few kB).
pub const MECH_BYTES: u64 = 4 << 20;
/// The largest load table, bytes (a million rows at full precision are about 40 MB).
pub const TABLE_BYTES: u64 = 64 << 20;
/// The most steps of a sweep (rows = steps + 1).
pub const STEPS: usize = 100_000_000;
/// The most output rows of `mech simulate` (`--samples`).
pub const SAMPLES: usize = 10_000_000;
/// The most steps a time integration of `mech simulate` may take.
pub const INTEGRATION_STEPS: u64 = 10_000_000;
/// The longest cycle of `mech flywheel`, rad (1000 turns).
pub const PERIOD: f64 = 2000.0 * std::f64::consts::PI;
/// The most points of a cam profile (`--points`).
pub const POINTS: usize = 1_000_000;
/// The most frames of an animation or a report (`--frames`).
pub const FRAMES: usize = 10_000;
/// The deepest nesting of brackets, or the longest run of signs, in a text.
pub const NESTING: usize = mech_core::checks::load::MAX_NESTING;
/// The largest picture side, px (`--width`, `--height`).
pub const PICTURE: f64 = 100_000.0;

/// `n` bytes for a message: `512 bytes`, `4.0 MB`.
fn size(n: u64) -> String {
    if n < 1 << 20 {
        format!("{n} bytes")
    } else {
        format!("{:.1} MB", n as f64 / (1u64 << 20) as f64)
    }
}

/// The UTF-8 text of `path` (`-` = standard input), at most `limit` bytes; `what` names
/// the file in messages (`the mechanism file`, `--load gas: the table`). A file too large,
/// a binary file (a NUL byte), text that is not UTF-8, a directory or a device that never
/// ends are refused with a message that says which.
pub fn read_text(path: &Path, limit: u64, what: &str) -> Result<String, Failure> {
    let shown = if path.as_os_str() == "-" {
        "<stdin>".to_string()
    } else {
        path.display().to_string()
    };
    let cannot = |e: io::Error| Failure::usage(format!("{what}: cannot read {shown}: {e}"));
    let mut bytes = Vec::new();
    if path.as_os_str() == "-" {
        io::stdin()
            .lock()
            .take(limit + 1)
            .read_to_end(&mut bytes)
            .map_err(cannot)?;
    } else {
        let meta = std::fs::metadata(path).map_err(cannot)?;
        if meta.is_dir() {
            return Err(Failure::usage(format!(
                "{what}: {shown} is a directory; give a file"
            )));
        }
        if meta.len() > limit {
            return Err(too_large(what, &shown, Some(meta.len()), limit));
        }
        std::fs::File::open(path)
            .and_then(|f| f.take(limit + 1).read_to_end(&mut bytes))
            .map_err(cannot)?;
    }
    if bytes.len() as u64 > limit {
        return Err(too_large(what, &shown, None, limit));
    }
    if let Some(at) = bytes.iter().position(|&b| b == 0) {
        return Err(Failure::usage(format!(
            "{what}: {shown} is a binary file (a NUL byte at offset {at}), not text"
        )));
    }
    String::from_utf8(bytes).map_err(|e| {
        let at = e.utf8_error().valid_up_to();
        let (line, col) = line_col(&e.as_bytes()[..at]);
        Failure::usage(format!(
            "{what}: {shown} is not UTF-8 text (byte 0x{:02x} at line {line}, column {col}); save it as UTF-8",
            e.as_bytes()[at]
        ))
    })
}

fn too_large(what: &str, shown: &str, n: Option<u64>, limit: u64) -> Failure {
    let held = match n {
        Some(n) => format!("is {}, more than", size(n)),
        None => "holds more than".to_string(),
    };
    Failure::usage(format!(
        "{what}: {shown} {held} the {} this tool reads; is it the right file?",
        size(limit)
    ))
}

/// A number for a message: plain when moderate, else in exponent form (`1e-300`).
pub fn show(x: f64) -> String {
    if x == 0.0 || (1e-3..1e6).contains(&x.abs()) {
        format!("{x}")
    } else {
        format!("{x:e}")
    }
}

/// The 1-based line and column just after `prefix`.
fn line_col(prefix: &[u8]) -> (usize, usize) {
    let line = prefix.iter().filter(|&&b| b == b'\n').count() + 1;
    let start = prefix
        .iter()
        .rposition(|&b| b == b'\n')
        .map_or(0, |p| p + 1);
    let col = String::from_utf8_lossy(&prefix[start..]).chars().count() + 1;
    (line, col)
}

/// Refuse a text nested deeper than [`NESTING`] brackets, or with a longer run of signs
/// (`- - - 1`): the parser is recursive, and such a text would overflow its stack.
/// Comments (`//` to the end of the line) are skipped. `origin` names the text. The rule
/// is the loader's own (`mech_core::checks::load::check_text`), said here before any work.
pub fn nesting(text: &str, origin: &str) -> Result<(), Failure> {
    mech_core::checks::load::check_text(text, Some(origin)).map_err(|e| match e {
        mech_core::MechError::Invalid(m) => Failure::usage(m),
        other => Failure::usage(other.to_string()),
    })
}

/// Why `path` cannot be written, said before the work: a directory, or a parent folder
/// that does not exist. `flag` names the option, `ext` the file's kind (`svg`).
pub fn writable(path: &Path, flag: &str, ext: &str) -> Result<(), Failure> {
    if path.is_dir() {
        return Err(Failure::usage(format!(
            "{flag} {}: a directory; give a file name in it, e.g. {}",
            path.display(),
            path.join(format!("out.{ext}")).display()
        )));
    }
    if let Some(parent) = path.parent().filter(|p| !p.as_os_str().is_empty()) {
        if !parent.is_dir() {
            return Err(Failure::usage(format!(
                "{flag} {}: the folder {} does not exist; create it first or write elsewhere",
                path.display(),
                parent.display()
            )));
        }
    }
    Ok(())
}

/// Write `text` to `path` (an output file of `flag`), saying so on standard error.
pub fn write_file(path: &Path, text: &str, flag: &str, ext: &str) -> Result<(), Failure> {
    writable(path, flag, ext)?;
    std::fs::write(path, text).map_err(|e| {
        Failure::usage(format!(
            "{flag} {}: cannot write it: {e}{}",
            path.display(),
            match e.kind() {
                io::ErrorKind::PermissionDenied => "; choose a file you may write",
                _ => "",
            }
        ))
    })?;
    eprintln!("wrote {}", path.display());
    Ok(())
}

/// Standard output whose errors say so (`cannot write standard output: ...`): a full disk
/// or a closed pipe ends the run with a message, not a panic and not a silent success.
pub struct Stdout<W: Write>(pub W);

impl<W: Write> Write for Stdout<W> {
    fn write(&mut self, buf: &[u8]) -> io::Result<usize> {
        self.0.write(buf).map_err(tag)
    }
    fn flush(&mut self) -> io::Result<()> {
        self.0.flush().map_err(tag)
    }
}

fn tag(e: io::Error) -> io::Error {
    io::Error::new(e.kind(), format!("cannot write standard output: {e}"))
}

/// A count flag (`--steps`, `--points`, ...): a whole number from `min` to `max`, written
/// as digits or as a whole float (`1e6`).
pub fn count(text: &str, min: usize, max: usize, what: &str) -> Result<usize, String> {
    let t = text.trim();
    let n = match t.parse::<u128>() {
        Ok(n) => n as f64,
        Err(_) => match t.parse::<f64>() {
            Ok(x) if x.is_nan() => {
                return Err(format!(
                    "not a number; give a whole number of {what} from {min} to {max}"
                ))
            }
            Ok(x) if x.fract() != 0.0 && x.is_finite() => {
                return Err(format!(
                    "not a whole number; give a whole number of {what} from {min} to {max}"
                ))
            }
            Ok(x) => x,
            Err(_) => {
                return Err(format!(
                    "not a number; give a whole number of {what} from {min} to {max}"
                ))
            }
        },
    };
    if n < 0.0 {
        return Err(format!(
            "negative; give a whole number of {what} from {min} to {max}"
        ));
    }
    if n < min as f64 {
        return Err(format!(
            "too few; give at least {min} {what} (a whole number up to {max})"
        ));
    }
    if n > max as f64 {
        return Err(format!(
            "more than the limit of {max} {what}; use fewer, or split the work into several runs"
        ));
    }
    Ok(n as usize)
}

/// A plain number flag: finite and within [`lo`, `hi`] (`what` says what the number is).
pub fn number(text: &str, lo: f64, hi: f64, what: &str) -> Result<f64, String> {
    let range = format!("give {what} from {} to {}", show(lo), show(hi));
    let x: f64 = text
        .trim()
        .parse()
        .map_err(|_| format!("not a number; {range}"))?;
    if !x.is_finite() {
        return Err(format!("not a finite number; {range}"));
    }
    if !(x >= lo && x <= hi) {
        return Err(format!("out of range; {range}"));
    }
    Ok(x)
}

/// `--steps` of a sweep: 0 to [`STEPS`].
pub fn steps(text: &str) -> Result<usize, String> {
    count(text, 0, STEPS, "steps")
}

/// `--samples` of `mech simulate`: 1 to [`SAMPLES`].
pub fn samples(text: &str) -> Result<usize, String> {
    count(text, 1, SAMPLES, "samples")
}

/// `--points` of `mech cam`: 3 to [`POINTS`].
pub fn points(text: &str) -> Result<usize, String> {
    count(text, 3, POINTS, "points")
}

/// `--frames` of `mech animate` and `mech report`: 2 to [`FRAMES`].
pub fn frames(text: &str) -> Result<usize, String> {
    count(text, 2, FRAMES, "frames")
}

/// A positive finite number (`--t-end`, `--step`).
pub fn positive(text: &str) -> Result<f64, String> {
    let x: f64 = text
        .trim()
        .parse()
        .map_err(|_| "not a number; give a positive number".to_string())?;
    if !x.is_finite() {
        return Err("not a finite number; give a positive number".into());
    }
    if !(x > 0.0) {
        return Err("not positive; give a positive number".into());
    }
    Ok(x)
}

/// A relative tolerance `--rtol`: 1e-15 (what f64 resolves) to 0.1.
pub fn rtol(text: &str) -> Result<f64, String> {
    number(text, 1e-15, 0.1, "a relative tolerance")
}

/// An absolute tolerance `--atol`: 0 to 1.
pub fn atol(text: &str) -> Result<f64, String> {
    number(text, 0.0, 1.0, "an absolute tolerance")
}

/// `--irregularity` ε = (ω_max − ω_min)/ω_a: from 1e-9 to less than 2.
pub fn irregularity(text: &str) -> Result<f64, String> {
    let x = number(text, 1e-9, 2.0, "ε = (ω_max − ω_min)/ω_a")?;
    if x == 2.0 {
        return Err(
            "out of range; give ε = (ω_max − ω_min)/ω_a below 2, typically 0.002 to 0.2".into(),
        );
    }
    Ok(x)
}

/// `--seconds` of an animation's loop: 0.001 to 86400 (a day).
pub fn seconds(text: &str) -> Result<f64, String> {
    number(text, 0.001, 86_400.0, "a duration in seconds")
}

/// `--width` or `--height` of a picture, px: 1 to [`PICTURE`].
pub fn pixels(text: &str) -> Result<f64, String> {
    number(text, 1.0, PICTURE, "a size in px")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn counts_and_numbers() {
        assert_eq!(count("1e3", 0, STEPS, "steps"), Ok(1000));
        assert_eq!(count("12", 0, STEPS, "steps"), Ok(12));
        assert!(count("1e12", 0, STEPS, "steps")
            .unwrap_err()
            .contains("limit of 100000000"));
        assert!(count("-1", 0, STEPS, "steps")
            .unwrap_err()
            .contains("negative"));
        assert!(count("nan", 0, STEPS, "steps")
            .unwrap_err()
            .contains("not a number"));
        assert!(count("inf", 0, STEPS, "steps")
            .unwrap_err()
            .contains("limit"));
        assert!(count("2.5", 0, STEPS, "steps")
            .unwrap_err()
            .contains("whole"));
        assert!(number("nan", 0.0, 1.0, "x").unwrap_err().contains("finite"));
        assert!(number("2", 0.0, 1.0, "x")
            .unwrap_err()
            .contains("out of range"));
    }

    #[test]
    fn nesting_is_bounded() {
        assert!(nesting("(((1)))", "t").is_ok());
        assert!(nesting(&format!("{}1", "(".repeat(65)), "t").is_err());
        assert!(nesting(&format!("{}1", "- ".repeat(65)), "t").is_err());
        assert!(nesting(&format!("// {}\n1", "(".repeat(100)), "t").is_ok());
    }
}
