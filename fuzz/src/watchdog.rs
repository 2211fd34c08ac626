//! The watchdog: every solver call of a case runs under it. The fuzzing thread records
//! which call it is in and since when ([`Watchdog::enter`], [`Watchdog::leave`]); a thread
//! of its own looks at that record every 50 ms, and when one call has run longer than the
//! hang limit it writes the case (its text, the call) under `target/fuzz/` and ends the
//! process with status 1 and a message, so that a hang never stalls a run. A call that
//! merely runs over [`SLOW`] is reported by the fuzzing thread itself when it returns (a
//! finding like a panic).

use std::collections::HashMap;
use std::path::PathBuf;
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

/// A call longer than this is a finding (`docs/conventions.md#magnitudes`: no call over a
/// second).
pub const SLOW: Duration = Duration::from_secs(1);

/// A call longer than this is a hang: the watchdog writes the case and ends the process.
pub const HANG: Duration = Duration::from_secs(20);

/// What the fuzzing thread is doing, as the watchdog sees it.
#[derive(Default)]
struct Current {
    /// The case number and its text.
    case: u64,
    text: String,
    /// The call under way and when it started; `None` between calls.
    call: Option<(&'static str, Instant)>,
    /// Per kind of call: the time spent in it and how many were made.
    spent: HashMap<&'static str, (Duration, u64)>,
    /// The longest call so far and its kind.
    slowest: (Duration, &'static str),
}

/// The shared record of the call under way, and the thread that watches it.
#[derive(Clone)]
pub struct Watchdog {
    current: Arc<Mutex<Current>>,
}

impl Watchdog {
    /// Start the watching thread: a call over `hang` makes it write the case into `out`
    /// (`hang-<case>.txt`) and end the process with status 1.
    pub fn start(out: PathBuf, hang: Duration) -> Self {
        let me = Watchdog {
            current: Arc::new(Mutex::new(Current::default())),
        };
        // The thread ends when the last handle is dropped.
        let watched = Arc::downgrade(&me.current);
        std::thread::Builder::new()
            .name("watchdog".into())
            .spawn(move || loop {
                std::thread::sleep(Duration::from_millis(50));
                let Some(watched) = watched.upgrade() else {
                    return;
                };
                // A poisoned lock still holds the record (a panic is caught outside it).
                let cur = watched.lock().unwrap_or_else(|p| p.into_inner());
                if let Some((what, since)) = cur.call {
                    let dt = since.elapsed();
                    if dt > hang {
                        let file = out.join(format!("hang-{}.txt", cur.case));
                        let _ = std::fs::create_dir_all(&out);
                        let _ = std::fs::write(
                            &file,
                            format!("// Hang: {what} still running after {dt:?}\n{}", cur.text),
                        );
                        eprintln!(
                            "mech-fuzz: case {}: `{what}` has run for {dt:?} (limit {hang:?}): a hang; the case is in {}; stopping",
                            cur.case,
                            file.display()
                        );
                        std::process::exit(1);
                    }
                }
            })
            .expect("cannot start the watchdog thread");
        me
    }

    fn lock(&self) -> std::sync::MutexGuard<'_, Current> {
        self.current.lock().unwrap_or_else(|p| p.into_inner())
    }

    /// A new case: its number and text, written out if one of its calls hangs.
    pub fn case(&self, n: u64, text: &str) {
        let mut cur = self.lock();
        cur.case = n;
        cur.text.clear();
        cur.text.push_str(text);
        cur.call = None;
    }

    /// The call `what` starts now.
    pub fn enter(&self, what: &'static str) -> Instant {
        let now = Instant::now();
        self.lock().call = Some((what, now));
        now
    }

    /// The call under way has returned.
    pub fn leave(&self) {
        let mut cur = self.lock();
        if let Some((what, since)) = cur.call.take() {
            let dt = since.elapsed();
            let e = cur.spent.entry(what).or_default();
            e.0 += dt;
            e.1 += 1;
            if dt > cur.slowest.0 {
                cur.slowest = (dt, what);
            }
        }
    }

    /// The longest call so far and its kind.
    pub fn slowest(&self) -> (Duration, &'static str) {
        self.lock().slowest
    }

    /// The time spent per kind of call and how many were made, the costliest first.
    pub fn spent(&self) -> Vec<(&'static str, Duration, u64)> {
        let mut v: Vec<_> = self
            .lock()
            .spent
            .iter()
            .map(|(k, (d, n))| (*k, *d, *n))
            .collect();
        v.sort_by_key(|e| std::cmp::Reverse(e.1));
        v
    }
}
