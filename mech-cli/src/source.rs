//! Reading a mechanism file (`*.mech`: the text between the braces of `mechanism! { ... }`,
//! so a file pastes into Rust code unchanged) or standard input (`-`).

use crate::limits;
use crate::Failure;
use mech_core::runtime::spatial_columns::is_spatial;
use mech_core::spatial::SpatialMechanism;
use mech_core::Mechanism;
use std::path::Path;

/// A mechanism of either kind: planar, or spatial (its first item is `space`).
#[derive(Debug)]
#[allow(clippy::large_enum_variant)] // one value per command: its size does not matter
pub enum Any {
    /// A planar mechanism.
    Planar(Mechanism),
    /// A spatial mechanism (SPEC 3i).
    Spatial(SpatialMechanism),
}

/// The mechanism of `path`, planar or spatial as its text says
/// ([`mech_core::runtime::spatial_columns::is_spatial`]); a bad file is a [`Failure`]
/// whose messages start `FILE:LINE:COLUMN:` (or `FILE:` for a whole-mechanism count).
pub fn load_any(path: &Path) -> Result<Any, Failure> {
    let (text, origin) = read(path)?;
    if is_spatial(&text) {
        crate::spatial::parse(&text, &origin).map(Any::Spatial)
    } else {
        parse_planar(&text, &origin).map(Any::Planar)
    }
}

/// The text of `path` (`-` = standard input) and the name its messages show. At most
/// [`limits::MECH_BYTES`] of UTF-8 text, nested at most [`limits::NESTING`] deep.
pub fn read(path: &Path) -> Result<(String, String), Failure> {
    let text = limits::read_text(path, limits::MECH_BYTES, "the mechanism file")?;
    let origin = if path.as_os_str() == "-" {
        "<stdin>".to_string()
    } else {
        path.display().to_string()
    };
    limits::nesting(&text, &origin)?;
    Ok((text, origin))
}

/// The mechanism of `path`, through every check of the macro; a bad file is a
/// [`Failure`] whose message starts `FILE:LINE:COLUMN:`.
pub fn load(path: &Path) -> Result<Mechanism, Failure> {
    let (text, origin) = read(path)?;
    parse(&text, &origin)
}

/// The mechanism of `text` (read from [`read`]) through every check of the macro, its
/// messages naming `origin`: what [`load`] does once the file is read.
/// A spatial text (`space` first) is refused with a message naming the commands that take it.
pub fn parse(text: &str, origin: &str) -> Result<Mechanism, Failure> {
    if is_spatial(text) {
        return Err(Failure::mechanism(format!(
            "{origin}: a spatial mechanism (its first item is `space`): `mech check`, `solve`, `sweep`, `draw`, `animate`, `flywheel` and `simulate` take it; this command takes planar mechanisms only"
        )));
    }
    parse_planar(text, origin)
}

fn parse_planar(text: &str, origin: &str) -> Result<Mechanism, Failure> {
    Mechanism::from_dsl_named(text, origin).map_err(|e| match e {
        mech_core::MechError::Invalid(rendered) => Failure::mechanism(rendered),
        other => Failure::mechanism(other.to_string()),
    })
}
