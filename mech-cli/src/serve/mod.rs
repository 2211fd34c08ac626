//! `mech serve FILE [--port P]`: the workbench (SPEC 3j). A page on 127.0.0.1 that draws
//! the mechanism moving, with a slider for each input, play/pause and the speed; the
//! charts a designer reads against the first input (the motor action, I*, M*, each
//! reaction, the shaking force, a cam's pressure angle), with the value under the cursor;
//! the check's message with the file's line when FILE is wrong (the last good drawing
//! stays). FILE is read again within a second of changing on disk, and dragging a point of
//! the drawing writes its new coordinates into FILE (those numbers only).
//!
//! One way through the modules: `state` reads FILE and keeps the last good mechanism;
//! `watch` polls FILE; `data` computes what the page asks for (the drawing's shapes, the
//! columns of `mech sweep`); `drag` writes a point back; `routes` is the HTTP server
//! (axum on a one-thread tokio runtime) with the page (`page.html`, `page.js`, built into
//! the binary: it works offline). Outside, [`run`] serves; [`Workbench`] and [`router`]
//! are the server without its socket.

mod data;
mod drag;
mod routes;
mod state;
mod watch;

pub use routes::router;
pub use state::{Diagnostic, Good, Input, Snapshot, Workbench};

use crate::Failure;
use std::path::PathBuf;

/// `mech serve` arguments.
#[derive(clap::Args, Debug)]
pub struct ServeArgs {
    /// The mechanism file (read again whenever it changes, written when a point is dragged).
    pub file: PathBuf,
    /// The port on 127.0.0.1 (0: any free port; the address is printed on standard error).
    #[arg(long, default_value_t = 7878)]
    pub port: u16,
}

/// Run `mech serve` until interrupted.
pub fn run(args: ServeArgs) -> Result<(), Failure> {
    if args.file.as_os_str() == "-" {
        return Err(Failure::usage(
            "mech serve: give a file, not standard input: the workbench reads it again when it changes and writes dragged points into it",
        ));
    }
    let wb = Workbench::open(args.file.clone())?;
    let listener = std::net::TcpListener::bind(("127.0.0.1", args.port)).map_err(|e| {
        Failure::usage(format!(
            "--port {}: cannot listen on 127.0.0.1:{}: {e}; give another port, or 0 for any free one",
            args.port, args.port
        ))
    })?;
    listener.set_nonblocking(true)?;
    let addr = listener.local_addr()?;
    eprintln!(
        "mech serve: http://{addr}/ shows {} (Ctrl-C stops)",
        args.file.display()
    );
    watch::spawn(wb.clone())?;
    let runtime = tokio::runtime::Builder::new_current_thread()
        .enable_io()
        .enable_time()
        .build()?;
    runtime.block_on(async move {
        let listener = tokio::net::TcpListener::from_std(listener)?;
        axum::serve(listener, routes::router(wb)).await
    })?;
    Ok(())
}
