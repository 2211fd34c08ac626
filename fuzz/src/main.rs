//! `mech-fuzz`: mutated mechanism texts through the run-time loader
//! (`mech_core::Mechanism::from_dsl`) and every solver on what loads, checking the
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
//! `target/fuzz/` and the run exits with status 1.

use mech_core::solvers::traits::OneDof;
use mech_core::{MechError, Mechanism};
use std::panic::{catch_unwind, AssertUnwindSafe};
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

/// xorshift64*: a small deterministic generator.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        self.0.wrapping_mul(0x2545_F491_4F6C_DD1D)
    }
    fn below(&mut self, n: usize) -> usize {
        (self.next() % n.max(1) as u64) as usize
    }
}

/// Every mechanism body under the repository's tests and examples.
fn seeds(root: &Path) -> Vec<String> {
    let mut out = Vec::new();
    let mut files = Vec::new();
    for dir in ["tests", "tests/common", "examples", "examples/mech"] {
        if let Ok(rd) = std::fs::read_dir(root.join(dir)) {
            files.extend(rd.flatten().map(|e| e.path()));
        }
    }
    files.sort();
    for f in files {
        let Ok(text) = std::fs::read_to_string(&f) else {
            continue;
        };
        if f.extension().is_some_and(|e| e == "mech") {
            out.push(text);
            continue;
        }
        let mut at = 0;
        while let Some(i) = text[at..].find("mechanism! {\n") {
            let start = at + i + "mechanism! {\n".len();
            let Some(end) = text[start..].find("\n}\n") else {
                break;
            };
            out.push(text[start..start + end].to_string());
            at = start + end;
        }
    }
    out
}

const NUMBERS: [&str; 16] = [
    "0",
    "-0.0",
    "1e308",
    "-1.7976931348623157e308",
    "1e-308",
    "5e-324",
    "1e999",
    "1e16",
    "-1e-300",
    "0.5",
    "3",
    "1e200",
    "1e-200",
    "4294967296",
    "-2",
    "1e6",
];
const TOKENS: [&str; 12] = [
    ",", "(", ")", "{", "}", "[", "]", ":", "-", "r#x", "0.0", "ground",
];

/// One mutation of `text`.
fn mutate(text: &str, rng: &mut Rng) -> String {
    let bytes: Vec<(usize, char)> = text.char_indices().collect();
    if bytes.is_empty() {
        return text.to_string();
    }
    let pick = |rng: &mut Rng| bytes[rng.below(bytes.len())].0;
    match rng.below(6) {
        0 => {
            // A number replaced by a hostile one.
            let starts: Vec<usize> = bytes
                .windows(2)
                .filter(|w| {
                    w[1].1.is_ascii_digit() && !w[0].1.is_ascii_alphanumeric() && w[0].1 != '.'
                })
                .map(|w| w[1].0)
                .collect();
            if starts.is_empty() {
                return text.to_string();
            }
            let s = starts[rng.below(starts.len())];
            let e = s + text[s..]
                .find(|c: char| !(c.is_ascii_alphanumeric() || c == '.' || c == '-'))
                .unwrap_or(text.len() - s);
            format!(
                "{}{}{}",
                &text[..s],
                NUMBERS[rng.below(NUMBERS.len())],
                &text[e..]
            )
        }
        1 => {
            // A span deleted.
            let (a, b) = (pick(rng), pick(rng));
            let (a, mut b) = (a.min(b), a.max(b).min(a.min(b) + 40));
            while !text.is_char_boundary(b) {
                b -= 1;
            }
            format!("{}{}", &text[..a], &text[b..])
        }
        2 => {
            // A line duplicated.
            let lines: Vec<&str> = text.lines().collect();
            let k = rng.below(lines.len());
            let mut out: Vec<&str> = lines.clone();
            out.insert(k, lines[k]);
            out.join("\n")
        }
        3 => {
            // A name replaced by another name of the text.
            let words: Vec<&str> = text
                .split(|c: char| !(c.is_alphanumeric() || c == '_'))
                .filter(|w| w.chars().next().is_some_and(|c| c.is_alphabetic()))
                .collect();
            if words.len() < 2 {
                return text.to_string();
            }
            let (a, b) = (words[rng.below(words.len())], words[rng.below(words.len())]);
            text.replacen(a, b, 1 + rng.below(2))
        }
        4 => {
            let a = pick(rng);
            format!(
                "{}{}{}",
                &text[..a],
                TOKENS[rng.below(TOKENS.len())],
                &text[a..]
            )
        }
        _ => {
            // A point or a whole number tweaked slightly (a near-dead point, a near-tangency).
            text.replacen("0.", "0.00000000001", 1)
        }
    }
}

/// What went wrong in one case (written out with `Debug`).
#[derive(Debug)]
#[allow(dead_code)]
enum Finding {
    Panic(String),
    NonFinite(String),
    Slow(Duration, &'static str),
}

fn all_finite(v: &[f64]) -> bool {
    v.iter().all(|x| x.is_finite())
}

/// Load `text` and call every solver on what loads: the findings, and whether it loaded.
fn run(text: &str) -> (Vec<Finding>, bool) {
    let mut found = Vec::new();
    let mut timed = |what: &'static str, f: &mut dyn FnMut() -> Option<String>| {
        let t = Instant::now();
        let r = catch_unwind(AssertUnwindSafe(&mut *f));
        let dt = t.elapsed();
        if dt > Duration::from_secs(1) {
            found.push(Finding::Slow(dt, what));
        }
        match r {
            Err(p) => found.push(Finding::Panic(format!(
                "{what}: {}",
                p.downcast_ref::<String>()
                    .cloned()
                    .or_else(|| p.downcast_ref::<&str>().map(|s| s.to_string()))
                    .unwrap_or_default()
            ))),
            Ok(Some(msg)) => found.push(Finding::NonFinite(format!("{what}: {msg}"))),
            Ok(None) => {}
        }
    };
    let mut loaded = None;
    timed("load", &mut || match Mechanism::from_dsl(text) {
        Ok(m) => {
            loaded = Some(m);
            None
        }
        // The loader catches a panic of its own thread: a defect, counted as a panic.
        Err(e @ MechError::Internal(_)) => std::panic::panic_any(e.to_string()),
        Err(_) => None,
    });
    let Some(m) = loaded else {
        return (found, false);
    };
    let g = m.dof();
    let zero = vec![0.0; g];
    for (k, q0) in [0.0, 0.7, 2.0, -1.3, 1e6].iter().enumerate() {
        let q: Vec<f64> = (0..g).map(|i| q0 + 0.1 * i as f64).collect();
        let qd: Vec<f64> = (0..g)
            .map(|i| [1.0, 100.0, 1e20, 0.0, 3.0][k] * (1.0 + i as f64))
            .collect();
        timed("pose", &mut || match m.pose(&q) {
            Ok(p) => (!p.points.iter().all(|p| p.pos.iter().all(|x| x.is_finite()))
                || !p.links.iter().all(|l| l.angle.is_finite()))
            .then(|| format!("pose at {q:?}")),
            Err(_) => None,
        });
        timed("kinematics and forces", &mut || {
            let mo = m.kinematics(&q, &qd, &zero).ok()?;
            if !mo.links.iter().all(|l| {
                all_finite(&[
                    l.angle, l.omega, l.alpha, l.cg.x, l.cg.y, l.cg_acc.x, l.cg_acc.y,
                ])
            }) {
                return Some(format!("kinematics at {q:?}, {qd:?}"));
            }
            let mut loads = m.loads();
            for l in &m.model().loads {
                let v = [1e3, -2e3];
                let n = if matches!(l, mech_core::model::Load::Force { .. }) {
                    2
                } else {
                    1
                };
                loads.set_by_name(l.name(), &v[..n]);
            }
            if let Ok(f) = m.kinetostatics(&mo, &loads) {
                if !all_finite(&f.driver)
                    || !f.joints.iter().all(|r| {
                        r.force.iter().all(|x| x.is_finite())
                            && r.moment.filter(|m| !m.is_finite()).is_none()
                    })
                {
                    return Some(format!("kinetostatics at {q:?}, {qd:?}"));
                }
            }
            if let Ok(d) = m.driver_action(&mo, &loads) {
                if !all_finite(&d) {
                    return Some(format!("driver_action at {q:?}, {qd:?}"));
                }
            }
            if g == 1 {
                if let Ok(r) = OneDof::reduced(&m, q[0]) {
                    if !all_finite(&[r.inertia, r.inertia_derivative]) {
                        return Some(format!("reduced at {q:?}"));
                    }
                }
                if let Ok(a) = OneDof::acceleration(&m, q[0], qd[0], 1e3, &loads) {
                    if !a.is_finite() {
                        return Some(format!("acceleration at {q:?}, {qd:?}"));
                    }
                }
            }
            None
        });
    }
    (found, true)
}

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
    /// Calls over 1 s.
    slow: u64,
}

/// Mutate the seed mechanisms and run each through the loader and every solver until
/// `seconds` have passed or `cases` were tried (10 000 when neither is given).
fn fuzz(seconds: Option<f64>, cases: Option<u64>, seed: u64) -> Summary {
    let root = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("..");
    let mut rng = Rng(seed);
    let seeds = seeds(&root);
    assert!(
        !seeds.is_empty(),
        "no seed mechanisms under {}",
        root.display()
    );
    let out = root.join("target/fuzz");
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
        let (findings, ok) = run(&text);
        loaded += u64::from(ok);
        for f in &findings {
            match f {
                Finding::Slow(..) => slow += 1,
                _ => bad += 1,
            }
            let _ = std::fs::create_dir_all(&out);
            let _ = std::fs::write(
                out.join(format!("case-{n}.txt")),
                format!("// {f:?}\n{text}"),
            );
            eprintln!("case {n}: {f:?}");
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
    let s = fuzz(seconds, cases, seed);
    println!(
        "{} cases from {} seeds in {:.1} s: {} loaded and solved, {} panics or non-finite results, {} calls over 1 s",
        s.cases, s.seeds, s.seconds, s.loaded, s.bad, s.slow
    );
    if s.bad > 0 {
        std::process::exit(1);
    }
}

#[cfg(test)]
mod tests {
    /// The minute of fuzzing that `cargo test --workspace` (the README's test command,
    /// which CI runs) includes: mutated mechanisms through the run-time loader and every
    /// solver, no panic and no non-finite number inside `Ok`. (An unoptimised test build
    /// tries fewer cases in the minute than the release run of `cargo run --release -p
    /// mech-fuzz -- --seconds 60`; a finding is written under target/fuzz.)
    #[test]
    fn a_minute_of_mutations_finds_no_panic_and_no_non_finite_result() {
        let s = super::fuzz(Some(60.0), None, 0x9E37_79B9_7F4A_7C15);
        assert_eq!(s.bad, 0, "{s:?}: see target/fuzz");
        assert!(
            s.cases >= 200 && s.loaded > 0,
            "{s:?}: too few cases to mean anything"
        );
    }
}
