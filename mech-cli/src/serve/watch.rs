//! Polling FILE: every [`PERIOD`], its text is read again and, when it differs from the
//! last reading (or the file went or came back), the workbench reloads
//! ([`Workbench::refresh`]). Polling needs nothing of the platform and catches a file
//! replaced by a rename as well as one written in place.

use super::state::Workbench;
use std::sync::Arc;
use std::time::Duration;

/// How often FILE is read.
pub const PERIOD: Duration = Duration::from_millis(200);

/// Start the polling thread (it runs as long as the process).
pub fn spawn(wb: Arc<Workbench>) -> std::io::Result<()> {
    std::thread::Builder::new()
        .name("mech-serve-watch".into())
        .spawn(move || loop {
            std::thread::sleep(PERIOD);
            wb.refresh();
        })
        .map(|_| ())
}
