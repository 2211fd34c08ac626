//! `mech report FILE -o out.html`: one self-contained HTML page. (In progress.)

use crate::Failure;
use std::path::PathBuf;

/// `mech report FILE -o out.html`.
#[derive(clap::Args, Debug)]
pub struct ReportArgs {
    /// The mechanism file (`-` = standard input).
    pub file: PathBuf,
    /// The HTML file to write.
    #[arg(short = 'o', long = "output")]
    pub output: PathBuf,
}

/// Run `mech report`.
pub fn run(_args: ReportArgs) -> Result<(), Failure> {
    Err(Failure::usage("`mech report` is not available in this build yet"))
}
