//! `mech draw` and `mech animate`: the linkage itself as SVG. (In progress.)

use crate::Failure;
use std::path::PathBuf;

/// `mech draw FILE --at Q -o out.svg`.
#[derive(clap::Args, Debug)]
pub struct DrawArgs {
    /// The mechanism file (`-` = standard input).
    pub file: PathBuf,
    /// Input values q, one per input (rad or m; `deg`, `mm` allowed).
    #[arg(long = "at", required = true, value_delimiter = ',', allow_hyphen_values = true)]
    pub at: Vec<String>,
    /// The SVG file to write.
    #[arg(short = 'o', long = "output")]
    pub output: PathBuf,
}

/// `mech animate FILE -o out.svg`.
#[derive(clap::Args, Debug)]
pub struct AnimateArgs {
    /// The mechanism file (`-` = standard input).
    pub file: PathBuf,
    /// The SVG file to write.
    #[arg(short = 'o', long = "output")]
    pub output: PathBuf,
}

/// Run `mech draw`.
pub fn draw(_args: DrawArgs) -> Result<(), Failure> {
    Err(Failure::usage("`mech draw` is not available in this build yet"))
}

/// Run `mech animate`.
pub fn animate(_args: AnimateArgs) -> Result<(), Failure> {
    Err(Failure::usage("`mech animate` is not available in this build yet"))
}
