//! `mech-fuzz`: mutated mechanism texts through the run-time loader
//! (`mech_core::Mechanism::from_dsl`, or `SpatialMechanism::from_dsl` for a text whose first
//! item is `space`) and every solver on what loads, checking the
//! promise of `docs/conventions.md#magnitudes`: no panic, no non-finite number inside an
//! `Ok`, no call over a second.
//!
//! ```text
//! cargo run --release -p mech-fuzz -- --seconds 60            # the CI run
//! cargo run --release -p mech-fuzz -- --cases 1000000         # the long run
//! ```
//!
//! Seeds: every `mechanism! { ... }` body in `tests/`, `examples/` and every
//! `examples/mech/*.mech`. A case is a seed with one to three mutations (a number replaced
//! by a hostile one, a span deleted or duplicated, a name swapped for another, a token
//! inserted), from a deterministic generator (`--seed`). A failing case is written to
//! `target/fuzz/` and the run exits with status 1; `--replay FILE` runs one case again
//! (every choice of the parameter changed) and prints what it finds; `--profile` prints
//! the time spent per kind of call; `--oracle` runs the cases through the dense test
//! oracle `mech-oracle` instead of the run-time `Mechanism`.

mod check;
mod design;
mod dynamics;
mod exercise;
mod mutate;
mod oracle;
mod spatial;
mod watchdog;

use exercise::Finding;
use mutate::{mutate, seeds, Rng};
use std::path::PathBuf;
use std::time::Instant;
use watchdog::Watchdog;

/// The value after the command-line flag `name`, if any.
fn arg(name: &str) -> Option<String> {
    let args: Vec<String> = std::env::args().collect();
    args.iter()
        .position(|a| a == name)
        .and_then(|i| args.get(i + 1).cloned())
}

/// What a fuzzing run found.
#[derive(Debug)]
struct Summary {
    /// Mutated texts tried.
    cases: u64,
    /// Seed mechanisms they came from.
    seeds: usize,
    /// Wall time, s.
    seconds: f64,
    /// Of them, loaded and solved.
    loaded: u64,
    /// Panics or non-finite results (written under target/fuzz).
    bad: u64,
    /// Calls over 1 s (written under target/fuzz).
    slow: u64,
    /// The longest call and its kind.
    slowest: (std::time::Duration, &'static str),
    /// Per kind of call: the time spent in it and how many were made, the costliest first.
    spent: Vec<(&'static str, std::time::Duration, u64)>,
}

/// Mutate the seed mechanisms and run each through the loader and every solver until
/// `seconds` have passed or `cases` were tried (10 000 when neither is given), every call
/// under a [`Watchdog`] (a call over [`watchdog::HANG`] ends the process).
fn fuzz(seconds: Option<f64>, cases: Option<u64>, seed: u64, dense: bool) -> Summary {
    let root = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("..");
    let mut rng = Rng(seed);
    let seeds = seeds(&root);
    assert!(
        !seeds.is_empty(),
        "no seed mechanisms under {}",
        root.display()
    );
    let out = root.join("target/fuzz");
    let dog = Watchdog::start(out.clone(), watchdog::HANG);
    let start = Instant::now();
    let (mut n, mut loaded, mut bad, mut slow) = (0u64, 0u64, 0u64, 0u64);
    loop {
        if cases.is_some_and(|c| n >= c)
            || seconds.is_some_and(|s| start.elapsed().as_secs_f64() >= s)
            || (cases.is_none() && seconds.is_none() && n >= 10_000)
        {
            break;
        }
        let mut text = seeds[rng.below(seeds.len())].clone();
        for _ in 0..1 + rng.below(3) {
            text = mutate(&text, &mut rng);
        }
        let pick = rng.next();
        dog.case(n, &text);
        let (findings, ok) = if dense {
            oracle::run(&text, &dog)
        } else {
            exercise::run(&text, pick, &dog)
        };
        loaded += u64::from(ok);
        for f in &findings {
            match f {
                Finding::Slow(..) => slow += 1,
                _ => bad += 1,
            }
            eprintln!("case {n}: {f:?}");
        }
        if !findings.is_empty() {
            let head: String = findings.iter().map(|f| format!("// {f:?}\n")).collect();
            let _ = std::fs::create_dir_all(&out);
            let _ = std::fs::write(out.join(format!("case-{seed:x}-{n}.txt")), head + &text);
        }
        n += 1;
        if n % 100_000 == 0 {
            eprintln!(
                "{n} cases, {loaded} loaded, {bad} failures, {slow} slow, {:.0} s",
                start.elapsed().as_secs_f64()
            );
        }
    }
    Summary {
        cases: n,
        seeds: seeds.len(),
        seconds: start.elapsed().as_secs_f64(),
        loaded,
        bad,
        slow,
        slowest: dog.slowest(),
        spent: dog.spent(),
    }
}

/// Run the case in `file` (a case file of `target/fuzz/`, or any mechanism text) through
/// the loader and every solver (the oracle's when `dense`), with every choice `pick`
/// makes, and print what is found: the exit status (1 when something is found).
fn replay(file: &str, dense: bool) -> i32 {
    let text = match std::fs::read_to_string(file) {
        Ok(t) => t,
        Err(e) => {
            eprintln!("cannot read {file}: {e}");
            return 2;
        }
    };
    let dog = Watchdog::start(std::env::temp_dir(), watchdog::HANG);
    dog.case(0, &text);
    let mut found = 0;
    // Every parameter path (up to 64) with every value; the costly dynamics once (they
    // run when pick's bits 40 and up are 0 modulo DYNAMICS_EVERY).
    let picks = if dense {
        1
    } else {
        64 * exercise::PARAMS.len() as u64
    };
    for k in 0..picks {
        let pick = (k % 64) | (k / 64) << 16 | u64::from(k > 0) << 40;
        let (findings, ok) = if dense {
            oracle::run(&text, &dog)
        } else {
            exercise::run(&text, pick, &dog)
        };
        if !ok {
            if let Err(e) = mech_core::Mechanism::from_dsl(&text) {
                println!("{file}: does not load: {e}");
            }
            return i32::from(!findings.is_empty());
        }
        for f in findings {
            println!("{f:?}");
            found += 1;
        }
    }
    if std::env::args().any(|a| a == "--profile") {
        print_spent(&dog.spent());
    }
    i32::from(found > 0)
}

/// The time spent per kind of call, the costliest first (`--profile`).
fn print_spent(spent: &[(&'static str, std::time::Duration, u64)]) {
    for (what, t, n) in spent {
        println!(
            "{what:<36} {:>9.3} s {n:>10} calls {:>10.1} µs/call",
            t.as_secs_f64(),
            t.as_secs_f64() * 1e6 / *n as f64
        );
    }
}

/// Panics inside the solvers are findings (caught and written out): keep them quiet.
fn quiet_panics() {
    let default_hook = std::panic::take_hook();
    std::panic::set_hook(Box::new(move |info| {
        if std::thread::current().name() != Some("main") {
            default_hook(info);
        }
    }));
}

fn main() {
    let seconds: Option<f64> = arg("--seconds").and_then(|s| s.parse().ok());
    let cases: Option<u64> = arg("--cases").and_then(|s| s.parse().ok());
    let seed = arg("--seed")
        .and_then(|s| s.parse().ok())
        .unwrap_or(0x9E37_79B9_7F4A_7C15);
    quiet_panics();
    let dense = std::env::args().any(|a| a == "--oracle");
    if let Some(file) = arg("--replay") {
        std::process::exit(replay(&file, dense));
    }
    let s = fuzz(seconds, cases, seed, dense);
    println!(
        "{} cases from {} seeds in {:.1} s ({:.0} cases/s): {} loaded and solved, {} panics or non-finite results, {} calls over 1 s (the longest {:.3} s, {})",
        s.cases,
        s.seeds,
        s.seconds,
        s.cases as f64 / s.seconds,
        s.loaded,
        s.bad,
        s.slow,
        s.slowest.0.as_secs_f64(),
        s.slowest.1
    );
    if std::env::args().any(|a| a == "--profile") {
        print_spent(&s.spent);
    }
    if s.bad > 0 || s.slow > 0 {
        std::process::exit(1);
    }
}

#[cfg(test)]
mod tests {
    /// The minute of fuzzing that `cargo test --workspace` (the README's test command,
    /// which CI runs) includes, as two streams of mutations of 30 s side by side (one per
    /// core of a CI machine, each from its own seed): mutated mechanisms through the
    /// run-time loader and every solver, no panic, no non-finite number inside `Ok` and no
    /// call over 1 s. (An unoptimised test build tries fewer cases in the minute than the
    /// release run of `cargo run --release -p mech-fuzz -- --seconds 60`; a finding is
    /// written under target/fuzz.)
    #[test]
    fn a_minute_of_mutations_finds_no_panic_no_non_finite_result_and_no_slow_call() {
        const SEEDS: [u64; 2] = [0x9E37_79B9_7F4A_7C15, 0xD1B5_4A32_D192_ED03];
        let runs: Vec<super::Summary> = std::thread::scope(|scope| {
            let streams: Vec<_> = SEEDS
                .iter()
                .map(|&seed| scope.spawn(move || super::fuzz(Some(30.0), None, seed, false)))
                .collect();
            streams
                .into_iter()
                .map(|h| h.join().expect("a fuzzing stream panicked"))
                .collect()
        });
        for (s, seed) in runs.iter().zip(SEEDS) {
            eprintln!(
                "seed {seed:#x}: {} cases, {} loaded, the longest call {:?} ({})",
                s.cases, s.loaded, s.slowest.0, s.slowest.1
            );
            assert_eq!(s.bad, 0, "{s:?}: see target/fuzz");
            assert_eq!(s.slow, 0, "{s:?}: see target/fuzz");
            assert!(
                s.cases >= 100 && s.loaded > 0,
                "{s:?}: too few cases to mean anything"
            );
        }
    }
}
