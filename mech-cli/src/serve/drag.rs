//! A point dragged on the page, written back into FILE: the two numbers of its
//! coordinates (`A: (0.04, 0.069)`) are replaced, in their unit word, and nothing else of
//! the text changes (`mech_core::design::rewrite::move_point`). The page drags the
//! drawing as written (the inputs at their reference values), so the new coordinates are
//! those of the file.

use super::state::{lock, Workbench};
use crate::{source, Failure};
use mech_core::design::rewrite;

/// The rounding step of a dragged coordinate, m: a ten-thousandth of the drawing's order
/// of magnitude (0.01 mm for a drawing of 0.3 m).
pub fn step(size: f64) -> f64 {
    10f64.powf(size.max(1e-12).log10().floor() - 4.0)
}

/// Write point `name` at (`x`, `y`) (m) into FILE, then read FILE again; the new version.
/// Refused while FILE is wrong (its last good drawing is not the file's), for a point
/// the mechanism does not have, or one not written as two plain numbers.
pub fn drag(wb: &Workbench, name: &str, x: f64, y: f64) -> Result<u64, Failure> {
    let _writing = lock(&wb.writing);
    wb.refresh();
    let s = wb.snapshot();
    if let Some(e) = &s.error {
        return Err(Failure::usage(format!(
            "FILE is wrong now; fix it before dragging a point: {}",
            e.message
        )));
    }
    let Some(g) = &s.good else {
        return Err(Failure::usage("no mechanism yet"));
    };
    if g.mechanism.model().point_index(name).is_none() {
        return Err(Failure::usage(format!(
            "no point `{name}` in the mechanism"
        )));
    }
    if !(x.is_finite() && y.is_finite()) {
        return Err(Failure::usage(format!(
            "point `{name}`: ({x}, {y}) is not a finite position"
        )));
    }
    let (text, _) = source::read(&wb.path)?;
    let new = rewrite::move_point(&text, name, [x, y], step(g.size)).map_err(Failure::usage)?;
    std::fs::write(&wb.path, new)
        .map_err(|e| Failure::mechanism(format!("cannot write {}: {e}", wb.path.display())))?;
    wb.refresh();
    Ok(wb.snapshot().version)
}
