//! Reading a mechanism file (`*.mech`: the text between the braces of `mechanism! { ... }`,
//! so a file pastes into Rust code unchanged) or standard input (`-`).

use crate::Failure;
use mech_core::Mechanism;
use std::io::Read;
use std::path::Path;

/// The text of `path` (`-` = standard input) and the name its messages show.
pub fn read(path: &Path) -> Result<(String, String), Failure> {
    if path.as_os_str() == "-" {
        let mut text = String::new();
        std::io::stdin().read_to_string(&mut text)?;
        return Ok((text, "<stdin>".to_string()));
    }
    let text = std::fs::read_to_string(path)
        .map_err(|e| Failure::usage(format!("cannot read {}: {e}", path.display())))?;
    Ok((text, path.display().to_string()))
}

/// The mechanism of `path`, through every check of the macro; a bad file is a
/// [`Failure`] whose message starts `FILE:LINE:COLUMN:`.
pub fn load(path: &Path) -> Result<Mechanism, Failure> {
    let (text, origin) = read(path)?;
    Mechanism::from_dsl_named(&text, &origin).map_err(|e| match e {
        mech_core::MechError::Invalid(rendered) => Failure::mechanism(rendered),
        other => Failure::mechanism(other.to_string()),
    })
}
