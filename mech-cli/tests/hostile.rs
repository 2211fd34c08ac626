//! Hostile input to the `mech` tool (issue 28): for every subcommand that reads something,
//! malformed and huge CSV load tables, NaN, infinite, negative, zero and absurd values of
//! every numeric flag (`--steps 1e12` must not be attempted), unwritable output paths
//! (a folder that does not exist, a directory, a read-only file of /proc, a full disk, a
//! closed pipe), and input files that are binary, empty, not UTF-8, nested too deep, or
//! 100 MB. Each case ends within a time bound (a timeout is a failure) in a clean exit
//! status — 1 or 2, never 101 (a panic) or a signal — with a message on standard error
//! that names what is wrong (a key phrase is asserted), and prints no non-finite number
//! as a result. Bounds are `mech_cli::limits` (`docs/cli.md#limits`).

use assert_cmd::Command;
use std::io::Write;
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

/// The time a refusal may take (a debug build on a loaded 2-core machine: refusals take
/// milliseconds; the bound only separates them from a hang).
const BOUND: Duration = Duration::from_secs(60);

fn mech() -> Command {
    let mut c = Command::cargo_bin("mech").unwrap();
    c.timeout(BOUND);
    c
}

fn example(name: &str) -> String {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../examples/mech")
        .join(name)
        .to_str()
        .unwrap()
        .to_string()
}

/// The engine (one revolute input, a force load `gas`).
fn engine() -> String {
    example("engine.mech")
}

/// No result printed is NaN or infinite (nor JSON's `null` for one).
fn finite_only(stdout: &[u8], args: &[String]) {
    let text = String::from_utf8_lossy(stdout);
    for token in text.split(|c: char| c.is_whitespace() || ",:[]{}\"".contains(c)) {
        let t = token.trim_start_matches(['-', '+']).to_ascii_lowercase();
        assert!(
            !matches!(t.as_str(), "nan" | "inf" | "infinity" | "null"),
            "{args:?}: a non-finite result `{token}` in\n{}",
            &text[..text.len().min(2000)]
        );
    }
}

/// Run `args` and return (status, stdout, stderr), failing on a timeout, a signal or a
/// panic.
fn run(args: &[String], stdin: Option<Vec<u8>>) -> (i32, Vec<u8>, String) {
    let start = Instant::now();
    let mut c = mech();
    c.args(args);
    if let Some(input) = stdin {
        c.write_stdin(input);
    }
    let out = c.output().unwrap();
    let err = String::from_utf8_lossy(&out.stderr).into_owned();
    let code = out.status.code().unwrap_or_else(|| {
        panic!(
            "{args:?}: killed by a signal or the {BOUND:?} bound after {:?}: {}\n{err}",
            start.elapsed(),
            out.status
        )
    });
    assert!(
        code != 101 && !err.contains("panicked") && !err.contains("overflowed its stack"),
        "{args:?}: a panic (status {code})\n{err}"
    );
    (code, out.stdout, err)
}

/// `args` fail with `status` and `phrase` in the message, printing nothing non-finite.
fn refused(args: &[String], status: i32, phrase: &str) {
    let (code, out, err) = run(args, None);
    assert_eq!(
        code, status,
        "{args:?}: status {code}, expected {status}\n{err}"
    );
    assert!(
        err.contains(phrase),
        "{args:?}: expected “{phrase}” in\n{err}"
    );
    finite_only(&out, args);
}

/// `args` succeed and print only finite numbers.
fn accepted(args: &[String]) -> Vec<u8> {
    let (code, out, err) = run(args, None);
    assert_eq!(code, 0, "{args:?}: status {code}\n{err}");
    finite_only(&out, args);
    out
}

fn strings(args: &[&str]) -> Vec<String> {
    args.iter().map(|s| s.to_string()).collect()
}

/// Every subcommand that reads a file, with `FILE` for the file, and its usual output
/// files in `dir`.
fn readers(dir: &Path) -> Vec<Vec<String>> {
    let svg = dir.join("out.svg").to_str().unwrap().to_string();
    let html = dir.join("out.html").to_str().unwrap().to_string();
    [
        vec!["check", "FILE"],
        vec!["solve", "FILE", "--at", "0"],
        vec!["sweep", "FILE", "--from", "0", "--to", "1", "--steps", "4"],
        vec![
            "flywheel",
            "FILE",
            "--speed",
            "100",
            "--irregularity",
            "0.02",
        ],
        vec!["simulate", "FILE", "--t-end", "0.01"],
        vec!["draw", "FILE", "--at", "0", "-o", &svg],
        vec!["animate", "FILE", "-o", &svg],
        vec!["report", "FILE", "-o", &html],
        vec!["cam", "FILE"],
        vec!["import", "FILE", "--input", "0,1"],
    ]
    .iter()
    .map(|a| strings(a))
    .collect()
}

fn with_file(args: &[String], file: &Path) -> Vec<String> {
    args.iter()
        .map(|a| {
            if a == "FILE" {
                file.to_str().unwrap().to_string()
            } else {
                a.clone()
            }
        })
        .collect()
}

/// Pseudo-random bytes, none zero (xorshift; the same every run).
fn noise(n: usize) -> Vec<u8> {
    let mut x = 0x9E37_79B9_7F4A_7C15u64;
    (0..n)
        .map(|_| {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            (x % 255) as u8 + 1
        })
        .collect()
}

/// A file of `len` bytes, created sparse (no time, no disk).
fn sparse(path: &Path, len: u64) {
    std::fs::File::create(path).unwrap().set_len(len).unwrap();
}

/// Bad input files for every subcommand: random bytes, NUL bytes, text that is not
/// UTF-8, a 100 MB file, standard input beyond the limit, a directory, a file that does
/// not exist, brackets nested deeper than the parser's stack, and an empty file.
#[test]
fn bad_files_are_refused_by_every_subcommand() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let random = d.join("random.mech");
    std::fs::write(&random, noise(4096)).unwrap();
    let nul = d.join("nul.mech");
    std::fs::write(&nul, vec![0u8; 4096]).unwrap();
    let latin1 = d.join("latin1.mech");
    std::fs::write(&latin1, b"/// caf\xe9\npub struct X {}\n").unwrap();
    let huge = d.join("huge.mech");
    sparse(&huge, 100 << 20);
    let empty = d.join("empty.mech");
    std::fs::write(&empty, "").unwrap();
    let deep = d.join("deep.mech");
    let text = std::fs::read_to_string(engine()).unwrap();
    let nested = format!("{}0.086{}", "(".repeat(5000), ")".repeat(5000));
    std::fs::write(
        &deep,
        text.replace("stroke: 86 mm", &format!("stroke: {nested} m")),
    )
    .unwrap();
    let missing = d.join("missing.mech");
    for args in readers(d) {
        let is_import = args[0] == "import";
        for (file, status, phrase) in [
            (&random, 2, "is not UTF-8 text (byte 0x"),
            (
                &nul,
                2,
                "is a binary file (a NUL byte at offset 0), not text",
            ),
            (
                &latin1,
                2,
                "is not UTF-8 text (byte 0xe9 at line 1, column 8)",
            ),
            (
                &huge,
                2,
                "is 100.0 MB, more than the 4.0 MB this tool reads",
            ),
            (&d.to_path_buf(), 2, "is a directory; give a file"),
            (&missing, 2, "cannot read"),
            (
                &empty,
                1,
                if is_import {
                    "expected `M[`"
                } else {
                    "unexpected end of input"
                },
            ),
        ] {
            refused(&with_file(&args, file), status, phrase);
        }
        if !is_import {
            refused(
                &with_file(&args, &deep),
                2,
                "deep.mech:4:84: brackets nested more than 64 deep",
            );
        }
        // Standard input: at most 4 MB read, then refused.
        let (code, _, err) = run(&with_file(&args, Path::new("-")), Some(vec![b' '; 5 << 20]));
        assert_eq!(code, 2, "{args:?} < 5 MB: {err}");
        assert!(
            err.contains("<stdin> holds more than the 4.0 MB"),
            "{args:?} < 5 MB: {err}"
        );
    }
}

/// A table of a force against q: the engine's gas load.
const GOOD: &str = "q, fx, fy\n0, -100, 0\n3.2, -4000, 0\n6.3, -100, 0\n";

/// Malformed load tables through `mech solve`, each with the phrase of its message.
#[test]
fn malformed_load_tables_are_named() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let cases: Vec<(&str, Vec<u8>, &str)> = vec![
        ("two columns for a force", b"q, fx\n0, 1\n1, 2\n".to_vec(), "2 column(s) (`q, fx`), but this load needs a header `q` (or `q_deg`) and 2 value column(s), 3 in all"),
        ("four columns", b"q, fx, fy, fz\n0, 1, 0, 0\n1, 2, 0, 0\n".to_vec(), "4 column(s)"),
        ("a short row", b"q, fx, fy\n0, 1, 0\n1, 2\n".to_vec(), "line 3: 2 field(s), but the header has 3"),
        ("a long row", b"q, fx, fy\n0, 1, 0\n1, 2, 0,\n".to_vec(), "line 3: 4 field(s), but the header has 3"),
        ("a word", b"q, fx, fy\n0, abc, 0\n1, 2, 0\n".to_vec(), "line 2, column 2 (`abc`): not a number"),
        ("a hexadecimal number", b"q, fx, fy\n0x1, 1, 0\n2, 2, 0\n".to_vec(), "line 2, column 1 (`0x1`): not a number"),
        ("empty", b"".to_vec(), "empty; a table needs a header"),
        ("blank lines", b"\n\n\n".to_vec(), "empty; a table needs a header"),
        ("a header only", b"q, fx, fy\n".to_vec(), "0 row(s); a table needs at least two rows"),
        ("one row", b"q, fx, fy\n0, 1, 0\n".to_vec(), "1 row(s); a table needs at least two rows"),
        ("no header", b"0, 1, 0\n1, 2, 0\n".to_vec(), "the first column must be `q` (rad) or `q_deg` (degrees), found `0`"),
        ("duplicated headers", b"q, fx, fx\n0, 1, 0\n1, 2, 0\n".to_vec(), "the column name `fx` appears twice (columns 2 and 3)"),
        ("semicolons", b"q;fx;fy\n0;1;0\n1;2;0\n".to_vec(), "(columns are separated by commas)"),
        ("an unterminated quote", b"q, fx, fy\n0,\"1, 0\n1, 2, 0\n".to_vec(), "line 2: an unterminated quote"),
        ("a stray quote", b"q, fx, fy\n0, \"1, 0\n1, 2, 0\n".to_vec(), "not a number (an unbalanced quote"),
        ("NaN", b"q, fx, fy\n0, nan, 0\n1, 2, 0\n".to_vec(), "line 2, column 2 (`nan`): not a finite number"),
        ("inf", b"q, fx, fy\n0, 1, 0\n1, -inf, 0\n".to_vec(), "line 3, column 2 (`-inf`): not a finite number"),
        ("an overflowing number", b"q, fx, fy\n0, 1e400, 0\n1, 2, 0\n".to_vec(), "(`1e400`): not a finite number"),
        ("q decreasing", b"q, fx, fy\n1, 1, 0\n0, 2, 0\n".to_vec(), "line 3: q = 0 does not increase"),
        ("q repeated", b"q_deg, fx, fy\n0, 1, 0\n0, 2, 0\n".to_vec(), "line 3: q = 0 does not increase"),
        ("q over all of f64", b"q, fx, fy\n-1e308, 1, 0\n1e308, 2, 0\n".to_vec(), "q spans from -1e308 to 1e308: too wide"),
        ("Latin-1", b"q, fx, fy\n0, 1, 0\n1, 2\xb0, 0\n".to_vec(), "is not UTF-8 text (byte 0xb0 at line 3, column 5)"),
        ("NUL bytes", b"q, fx, fy\n0, 1, 0\n1, 2, 0\n\0\0".to_vec(), "is a binary file (a NUL byte at offset 26)"),
        ("random bytes", noise(10_000), "is not UTF-8 text"),
    ];
    for (what, bytes, phrase) in &cases {
        let path = d.join("table.csv");
        std::fs::write(&path, bytes).unwrap();
        let load = format!("gas=@{}", path.display());
        let args = strings(&["solve", &engine(), "--at", "1", "--load", &load]);
        let (code, out, err) = run(&args, None);
        assert_eq!(code, 2, "{what}: status {code}\n{err}");
        assert!(
            err.contains(phrase),
            "{what}: expected “{phrase}” in\n{err}"
        );
        finite_only(&out, &args);
    }
    // A file that does not exist, a directory, 70 MB, an endless device.
    for (file, phrase) in [
        (d.join("missing.csv"), "--load gas: cannot read"),
        (d.to_path_buf(), "is a directory; give a file"),
        (
            d.join("big.csv"),
            "is 70.0 MB, more than the 64.0 MB this tool reads",
        ),
        (PathBuf::from("/dev/zero"), "holds more than the 64.0 MB"),
    ] {
        if file.ends_with("big.csv") {
            sparse(&file, 70 << 20);
        }
        if !file.exists() && !file.ends_with("missing.csv") {
            continue;
        }
        let load = format!("gas=@{}", file.display());
        refused(
            &strings(&["solve", &engine(), "--at", "1", "--load", &load]),
            2,
            phrase,
        );
    }
}

/// A byte-order mark and CRLF line ends are read as the plain table.
#[test]
fn a_bom_and_crlf_read_as_the_plain_table() {
    let dir = tempfile::tempdir().unwrap();
    let solve = |bytes: &[u8]| {
        let path = dir.path().join("t.csv");
        std::fs::write(&path, bytes).unwrap();
        let load = format!("gas=@{}", path.display());
        accepted(&strings(&[
            "solve",
            &engine(),
            "--at",
            "1",
            "--load",
            &load,
            "--format",
            "csv",
        ]))
    };
    let plain = solve(GOOD.as_bytes());
    let bom = [b"\xef\xbb\xbf".as_slice(), GOOD.as_bytes()].concat();
    assert_eq!(solve(&bom), plain, "BOM");
    assert_eq!(solve(GOOD.replace('\n', "\r\n").as_bytes()), plain, "CRLF");
    assert_eq!(
        solve(b"q, fx, fy\n0,\"-100\",0\n3.2,\"-4000\",0\n6.3,-100,0\n"),
        plain,
        "quoted numbers"
    );
}

/// Every subcommand that takes a load table names a bad one the same way (the CSV goes
/// through one reader).
#[test]
fn every_table_reader_refuses_a_bad_table() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let bad = d.join("bad.csv");
    std::fs::write(&bad, "q, fx, fy\n0, 1, 0\n1, oops, 0\n").unwrap();
    let torque = d.join("torque.csv");
    std::fs::write(&torque, "q, t\n0, 1\n1,\"oops\n2, 3\n").unwrap();
    let huge = d.join("huge.csv");
    sparse(&huge, 100 << 20);
    let svg = d.join("out.svg").to_str().unwrap().to_string();
    let html = d.join("out.html").to_str().unwrap().to_string();
    let e = engine();
    let with = |extra: &[&str], table: &Path| {
        let load = format!("gas=@{}", table.display());
        let mut a = strings(extra);
        a.extend(strings(&["--load", &load]));
        a
    };
    let commands: Vec<Vec<&str>> = vec![
        vec!["solve", &e, "--at", "1"],
        vec!["sweep", &e, "--from", "0", "--to", "1", "--steps", "4"],
        vec!["flywheel", &e, "--speed", "100", "--irregularity", "0.02"],
        vec!["simulate", &e, "--t-end", "0.01"],
        vec!["draw", &e, "--at", "1", "-o", &svg, "--forces"],
        vec!["report", &e, "-o", &html],
    ];
    for c in &commands {
        refused(&with(c, &bad), 2, "line 3, column 2 (`oops`): not a number");
        refused(&with(c, &huge), 2, "is 100.0 MB, more than the 64.0 MB");
    }
    let driver = format!("@{}", torque.display());
    refused(
        &strings(&["simulate", &e, "--t-end", "0.01", "--driver", &driver]),
        2,
        "line 3: an unterminated quote",
    );
    let driver = format!("@{}", huge.display());
    refused(
        &strings(&["simulate", &e, "--t-end", "0.01", "--driver", &driver]),
        2,
        "--driver: ",
    );
}

/// Peak resident memory of a child process, kB, sampled from /proc while it runs, with
/// its exit status; a run past `bound` is killed and fails the test.
#[cfg(target_os = "linux")]
fn peak_kb(args: &[String], bound: Duration) -> (i32, u64, String) {
    let dir = tempfile::tempdir().unwrap();
    let err_path = dir.path().join("stderr");
    let mut child = std::process::Command::new(assert_cmd::cargo::cargo_bin("mech"))
        .args(args)
        .stdout(std::process::Stdio::null())
        .stderr(std::fs::File::create(&err_path).unwrap())
        .spawn()
        .unwrap();
    let start = Instant::now();
    let mut peak = 0u64;
    let status = loop {
        if let Ok(s) = std::fs::read_to_string(format!("/proc/{}/status", child.id())) {
            if let Some(kb) = s
                .lines()
                .find_map(|l| l.strip_prefix("VmHWM:"))
                .and_then(|v| v.trim().trim_end_matches("kB").trim().parse::<u64>().ok())
            {
                peak = peak.max(kb);
            }
        }
        if let Some(s) = child.try_wait().unwrap() {
            break s;
        }
        if start.elapsed() > bound {
            let _ = child.kill();
            let _ = child.wait();
            panic!("{args:?}: still running after {bound:?}");
        }
        std::thread::sleep(Duration::from_millis(5));
    };
    let err = std::fs::read_to_string(&err_path).unwrap_or_default();
    let code = status
        .code()
        .unwrap_or_else(|| panic!("{args:?}: {status}\n{err}"));
    (code, peak, err)
}

/// A table of 10⁶ rows (40 MB) is read in bounded time and memory: its numbers (24 MB as
/// f64) and its text, nothing per row beyond them.
#[cfg(target_os = "linux")]
#[test]
fn a_million_row_table_is_read_in_bounded_time_and_memory() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("million.csv");
    let mut f = std::io::BufWriter::new(std::fs::File::create(&path).unwrap());
    writeln!(f, "q, fx, fy").unwrap();
    let n = 1_000_000;
    for k in 0..=n {
        let q = 4.0 * std::f64::consts::PI * k as f64 / n as f64;
        writeln!(f, "{q:.17}, {:.6}, 0", -1000.0 * (1.0 + (3.0 * q).sin())).unwrap();
    }
    f.flush().unwrap();
    drop(f);
    let bytes = std::fs::metadata(&path).unwrap().len();
    let load = format!("gas=@{}", path.display());
    let args = strings(&[
        "sweep",
        &engine(),
        "--from",
        "0",
        "--to",
        "6",
        "--steps",
        "100",
        "--load",
        &load,
    ]);
    let (code, peak, err) = peak_kb(&args, Duration::from_secs(180));
    assert_eq!(code, 0, "{err}");
    // The text, the numbers and the program: well under three times the file.
    assert!(
        peak * 1024 < 3 * bytes + (64 << 20),
        "peak resident memory {peak} kB for a table of {bytes} bytes"
    );
}

/// Every numeric flag with NaN, ±inf, negative, zero and absurd values: a usage error
/// (status 2) naming the flag and the accepted range, or a mechanism error (status 1)
/// naming the quantity; `--steps 1e12` and its kind are refused before any work.
#[test]
fn absurd_numbers_are_refused_with_the_range() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let e = engine();
    let cam = example("valve_train.mech");
    let svg = d.join("out.svg").to_str().unwrap().to_string();
    let html = d.join("out.html").to_str().unwrap().to_string();
    let pmks = d.join("crank_rocker.pmks");
    std::fs::write(
        &pmks,
        "M[J[R, P[0.0, 0.0], L[ground, L1]], J[R, P[12.92, 32.53], L[L1, L2]], J[R, P[73.28, 67.97], L[L2, L3]], J[R, P[90.0, 0.0], L[ground, L3]]]",
    )
    .unwrap();
    let pmks = pmks.to_str().unwrap().to_string();
    let deep = format!("{}1{}", "(".repeat(10_000), ")".repeat(10_000));
    let signs = format!("{}1", "-".repeat(50_000));
    let sweep = ["sweep", e.as_str(), "--from", "0", "--to", "1"];
    let fly = ["flywheel", e.as_str(), "--speed", "100"];
    let sim = [
        "simulate",
        e.as_str(),
        "--q0",
        "0.3",
        "--speed",
        "20",
        "--driver",
        "3",
    ];
    let cases: Vec<(Vec<&str>, i32, &str)> = vec![
        // sweep
        ([&sweep[..], &["--steps", "1e12"]].concat(), 2, "more than the limit of 100000000 steps; use fewer, or split"),
        ([&sweep[..], &["--steps", "1000000000000"]].concat(), 2, "more than the limit of 100000000 steps"),
        ([&sweep[..], &["--steps", "18446744073709551616"]].concat(), 2, "more than the limit of 100000000 steps"),
        ([&sweep[..], &["--steps", "inf"]].concat(), 2, "more than the limit of 100000000 steps"),
        ([&sweep[..], &["--steps", "-1"]].concat(), 2, "negative; give a whole number of steps from 0 to 100000000"),
        ([&sweep[..], &["--steps", "nan"]].concat(), 2, "not a number; give a whole number of steps"),
        ([&sweep[..], &["--steps", "2.5"]].concat(), 2, "not a whole number"),
        (vec!["sweep", &e, "--from", "nan", "--to", "1", "--steps", "4"], 2, "--from `nan`: not a finite number"),
        (vec!["sweep", &e, "--from", "0", "--to", "inf", "--steps", "4"], 2, "--to `inf`: not a finite number"),
        (vec!["sweep", &e, "--from", "1e400", "--to", "1", "--steps", "4"], 2, "--from `1e400`: overflows to inf"),
        (vec!["sweep", &e, "--from", "-1e308", "--to", "1e308", "--steps", "4"], 2, "the range overflows f64"),
        ([&sweep[..], &["--steps", "4", "--speed", "-inf"]].concat(), 2, "--speed `-inf`: not a finite number"),
        ([&sweep[..], &["--steps", "4", "--speed", "1e200"]].concat(), 1, "overflow"),
        ([&sweep[..], &["--steps", "4", "--rest", "1"]].concat(), 2, "--rest: 1 value(s) for the 0 input(s)"),
        // solve
        (vec!["solve", &e, "--at", "nan"], 2, "--at `nan`: not a finite number; give a finite value"),
        (vec!["solve", &e, "--at", "-inf"], 2, "--at `-inf`: not a finite number"),
        (vec!["solve", &e, "--at", "1e400"], 2, "--at `1e400`: overflows to inf"),
        (vec!["solve", &e, "--at", "1e308*10"], 2, "evaluates to inf, not a finite number"),
        (vec!["solve", &e, "--at", "1/0"], 2, "division by zero"),
        (vec!["solve", &e, "--at", &deep], 2, "--at:1:65: brackets nested more than 64 deep"),
        (vec!["solve", &e, "--at", &signs], 2, "--at:1:65: more than 64 signs in a row"),
        (vec!["solve", &e, "--at", "0", "--speed", "NaN"], 2, "--speed `NaN`: not a finite number"),
        (vec!["solve", &e, "--at", "0", "--accel", "infinity"], 2, "--accel `infinity`: not a finite number"),
        (vec!["solve", &e, "--at", "0", "--speed", "1e200"], 1, "overflow"),
        (vec!["solve", &e, "--at", "0", "--load", "gas=nan,0"], 2, "--load gas `nan`: not a finite number"),
        (vec!["solve", &e, "--at", "0", "--load", "gas=1e400,0"], 2, "--load gas `1e400`: overflows to inf"),
        // flywheel
        ([&fly[..], &["--irregularity", "nan"]].concat(), 2, "not a finite number; give ε = (ω_max − ω_min)/ω_a from 1e-9 to 2"),
        ([&fly[..], &["--irregularity", "0"]].concat(), 2, "out of range; give ε"),
        ([&fly[..], &["--irregularity", "-0.02"]].concat(), 2, "out of range; give ε"),
        ([&fly[..], &["--irregularity", "2"]].concat(), 2, "below 2"),
        ([&fly[..], &["--irregularity", "1e-300"]].concat(), 2, "out of range; give ε"),
        ([&fly[..], &["--irregularity", "inf"]].concat(), 2, "not a finite number"),
        ([&fly[..], &["--irregularity", "0.02", "--period", "1e12"]].concat(), 2, "--period 1e12: 1.592e11 turns, more than the limit of 1000 turns"),
        ([&fly[..], &["--irregularity", "0.02", "--period", "0"]].concat(), 1, "period must be positive"),
        ([&fly[..], &["--irregularity", "0.02", "--period", "-4pi"]].concat(), 1, "period must be positive"),
        ([&fly[..], &["--irregularity", "0.02", "--period", "nan"]].concat(), 2, "--period `nan`: not a finite number"),
        ([&fly[..], &["--irregularity", "0.02", "--start", "1e300"]].concat(), 2, "lose their precision"),
        ([&fly[..], &["--irregularity", "0.02", "--rtol", "0"]].concat(), 2, "give a relative tolerance from 1e-15 to 0.1"),
        ([&fly[..], &["--irregularity", "0.02", "--rtol", "-1"]].concat(), 2, "give a relative tolerance"),
        ([&fly[..], &["--irregularity", "0.02", "--rtol", "1e-300"]].concat(), 2, "give a relative tolerance"),
        ([&fly[..], &["--irregularity", "0.02", "--rtol", "nan"]].concat(), 2, "not a finite number"),
        ([&fly[..], &["--irregularity", "0.02", "--breakpoints", "nan"]].concat(), 2, "--breakpoints `nan`: not a finite number"),
        ([&fly[..], &["--irregularity", "0.02", "--driver", "inf"]].concat(), 2, "--driver `inf`: not a finite number"),
        (vec!["flywheel", &e, "--speed", "0", "--irregularity", "0.02"], 1, "mean speed must be positive"),
        (vec!["flywheel", &e, "--speed", "-inf", "--irregularity", "0.02"], 2, "--speed `-inf`: not a finite number"),
        // simulate
        ([&sim[..], &["--t-end", "nan"]].concat(), 2, "not a finite number; give a positive number"),
        ([&sim[..], &["--t-end", "inf"]].concat(), 2, "not a finite number; give a positive number"),
        ([&sim[..], &["--t-end", "-1"]].concat(), 2, "not positive; give a positive number"),
        ([&sim[..], &["--t-end", "0"]].concat(), 2, "not positive"),
        ([&sim[..], &["--t-end", "1e12"]].concat(), 2, "more than the limit of 10000000; shorten --t-end"),
        ([&sim[..], &["--t-end", "1e12", "--method", "rk4"]].concat(), 2, "--t-end 1e12 with --step 1e-4: 1.0e16 steps, more than the limit of 10000000; take a larger --step"),
        ([&sim[..], &["--t-end", "0.1", "--method", "rk4", "--step", "1e-300"]].concat(), 2, "1.0e299 steps, more than the limit"),
        ([&sim[..], &["--t-end", "0.1", "--method", "rk4", "--step", "0"]].concat(), 2, "not positive"),
        ([&sim[..], &["--t-end", "0.1", "--method", "rk4", "--step", "-1"]].concat(), 2, "not positive"),
        ([&sim[..], &["--t-end", "0.1", "--method", "rk4", "--step", "nan"]].concat(), 2, "not a finite number"),
        ([&sim[..], &["--t-end", "0.1", "--samples", "1e12"]].concat(), 2, "more than the limit of 10000000 samples"),
        ([&sim[..], &["--t-end", "0.1", "--samples", "0"]].concat(), 2, "too few; give at least 1 samples"),
        ([&sim[..], &["--t-end", "0.1", "--samples", "-3"]].concat(), 2, "negative"),
        ([&sim[..], &["--t-end", "0.1", "--rtol", "0"]].concat(), 2, "give a relative tolerance"),
        ([&sim[..], &["--t-end", "0.1", "--atol", "-1"]].concat(), 2, "give an absolute tolerance from 0 to 1"),
        ([&sim[..], &["--t-end", "0.1", "--atol", "nan"]].concat(), 2, "not a finite number"),
        (vec!["simulate", &e, "--t-end", "0.1", "--q0", "nan"], 2, "--q0 `nan`: not a finite number"),
        (vec!["simulate", &e, "--t-end", "0.1", "--speed", "inf"], 2, "--speed `inf`: not a finite number"),
        (vec!["simulate", &e, "--t-end", "0.1", "--driver", "-inf"], 2, "--driver `-inf`: not a finite number"),
        // cam
        (vec!["cam", &cam, "--points", "1e12"], 2, "more than the limit of 1000000 points"),
        (vec!["cam", &cam, "--points", "0"], 2, "too few; give at least 3 points"),
        (vec!["cam", &cam, "--points", "-5"], 2, "negative"),
        (vec!["cam", &cam, "--points", "nan"], 2, "not a number"),
        // draw
        (vec!["draw", &e, "--at", "0", "-o", &svg, "--width", "nan"], 2, "not a finite number; give a size in px from 1 to 100000"),
        (vec!["draw", &e, "--at", "0", "-o", &svg, "--width", "0"], 2, "out of range; give a size in px"),
        (vec!["draw", &e, "--at", "0", "-o", &svg, "--width", "1e300"], 2, "out of range"),
        (vec!["draw", &e, "--at", "0", "-o", &svg, "--height", "-5"], 2, "out of range"),
        (vec!["draw", &e, "--at", "0", "-o", &svg, "--height", "inf"], 2, "not a finite number"),
        (vec!["draw", &e, "--at", "nan", "-o", &svg], 2, "--at `nan`: not a finite number"),
        (vec!["draw", &e, "--at", "0", "-o", &svg, "--forces", "--speed", "inf"], 2, "--speed `inf`: not a finite number"),
        // animate
        (vec!["animate", &e, "-o", &svg, "--frames", "1e12"], 2, "more than the limit of 10000 frames"),
        (vec!["animate", &e, "-o", &svg, "--frames", "1"], 2, "too few; give at least 2 frames"),
        (vec!["animate", &e, "-o", &svg, "--frames", "-1"], 2, "negative"),
        (vec!["animate", &e, "-o", &svg, "--seconds", "0"], 2, "out of range; give a duration in seconds from 0.001 to 86400"),
        (vec!["animate", &e, "-o", &svg, "--seconds", "inf"], 2, "not a finite number"),
        (vec!["animate", &e, "-o", &svg, "--seconds", "-1"], 2, "out of range"),
        (vec!["animate", &e, "-o", &svg, "--seconds", "1e-300"], 2, "out of range"),
        (vec!["animate", &e, "-o", &svg, "--width", "nan"], 2, "not a finite number"),
        (vec!["animate", &e, "-o", &svg, "--from", "nan"], 2, "--from `nan`: not a finite number"),
        (vec!["animate", &e, "-o", &svg, "--from", "-1e308", "--to", "1e308"], 2, "the range overflows f64"),
        // report
        (vec!["report", &e, "-o", &html, "--frames", "1e12"], 2, "more than the limit of 10000 frames"),
        (vec!["report", &e, "-o", &html, "--frames", "0"], 2, "too few"),
        (vec!["report", &e, "-o", &html, "--speed", "nan"], 2, "--speed `nan`: not a finite number"),
        (vec!["report", &e, "-o", &html, "--from", "-1e308", "--to", "1e308"], 2, "the range overflows f64"),
        // import
        (vec!["import", &pmks, "--input", "-1,1"], 2, "`-1`: not a joint index"),
        (vec!["import", &pmks, "--input", "99999999999999999999,1"], 2, "not a joint index"),
        (vec!["import", &pmks, "--input", "9,1"], 2, "the expression has 4 joints (0 to 3)"),
        (vec!["import", &pmks, "--input", "0,1", "--name", "a b"], 2, "--name `a b`: not a struct name"),
        (vec!["import", &pmks, "--input", "0,1", "--name", "X { }"], 2, "not a struct name"),
        (vec!["import", &pmks, "--input", "0,1", "--unit", "deg"], 2, "--unit `deg`: not a unit word of length"),
        (vec!["import", &pmks, "--input", "0,1", "--unit", "mm) }"], 2, "not a unit word of length"),
    ];
    for (args, status, phrase) in &cases {
        refused(&strings(args), *status, phrase);
    }
    // At the edges of the ranges: finite results.
    accepted(&strings(&[&sweep[..], &["--steps", "0"]].concat()));
    accepted(&strings(
        &[&sweep[..], &["--steps", "1e2", "--format", "json"]].concat(),
    ));
    accepted(&strings(&[
        "solve", &e, "--at", "1e308", "--format", "json",
    ]));
    accepted(&strings(&[
        "solve",
        &e,
        "--at",
        "0",
        "--load",
        "gas=1e308,1e308",
        "--format",
        "json",
    ]));
    accepted(&strings(&["cam", &cam, "--points", "3"]));
    accepted(&strings(&[
        "import", &pmks, "--input", "0,1", "--unit", "mm",
    ]));
    accepted(&strings(&[
        "draw", &e, "--at", "0", "-o", &svg, "--width", "1", "--height", "1",
    ]));
    let picture = std::fs::read_to_string(&svg).unwrap();
    assert!(
        !picture.contains("NaN") && !picture.contains("inf"),
        "{picture}"
    );
}

/// Output files that cannot be written: a folder that does not exist, a directory, a
/// read-only file of /proc. Said before any work, or when the write fails.
#[test]
fn unwritable_output_files_are_named() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let e = engine();
    let cam = example("valve_train.mech");
    let pmks = d.join("p.pmks");
    std::fs::write(&pmks, "M[J[R, P[0.0, 0.0], L[ground, L1]], J[R, P[12.92, 32.53], L[L1, L2]], J[R, P[73.28, 67.97], L[L2, L3]], J[R, P[90.0, 0.0], L[ground, L3]]]").unwrap();
    let pmks = pmks.to_str().unwrap().to_string();
    let nowhere = d.join("no/such/folder/out.x").to_str().unwrap().to_string();
    let here = d.to_str().unwrap().to_string();
    let writers: Vec<(Vec<&str>, &str, &str)> = vec![
        (vec!["draw", &e, "--at", "0", "-o"], "-o", "svg"),
        (vec!["animate", &e, "-o"], "-o", "svg"),
        (vec!["report", &e, "-o"], "-o", "html"),
        (vec!["cam", &cam, "--svg"], "--svg", "svg"),
        (vec!["import", &pmks, "--input", "0,1", "-o"], "-o", "mech"),
    ];
    for (args, flag, ext) in &writers {
        let with = |path: &str| {
            let mut a = strings(args);
            a.push(path.to_string());
            a
        };
        refused(&with(&nowhere), 2, &format!("{flag} {nowhere}: the folder"));
        refused(
            &with(&nowhere),
            2,
            "does not exist; create it first or write elsewhere",
        );
        refused(
            &with(&here),
            2,
            &format!("{flag} {here}: a directory; give a file name in it, e.g. {here}/out.{ext}"),
        );
        if Path::new("/proc/version").exists() {
            refused(
                &with("/proc/version"),
                2,
                &format!("{flag} /proc/version: cannot write it"),
            );
        }
    }
}

/// Standard output on a full disk or a closed pipe: a message and status 1, not a panic
/// (status 101) and not a silent success.
#[cfg(target_os = "linux")]
#[test]
fn a_full_disk_or_a_closed_pipe_on_standard_output_is_an_error() {
    let dir = tempfile::tempdir().unwrap();
    let pmks = dir.path().join("p.pmks");
    std::fs::write(&pmks, "M[J[R, P[0.0, 0.0], L[ground, L1]], J[R, P[12.92, 32.53], L[L1, L2]], J[R, P[73.28, 67.97], L[L2, L3]], J[R, P[90.0, 0.0], L[ground, L3]]]").unwrap();
    let e = engine();
    let cam = example("valve_train.mech");
    let spawn = |args: &[&str], stdout: std::process::Stdio, close: bool| {
        let mut child = std::process::Command::new(assert_cmd::cargo::cargo_bin("mech"))
            .args(args)
            .stdout(stdout)
            .stderr(std::process::Stdio::piped())
            .spawn()
            .unwrap();
        if close {
            drop(child.stdout.take());
        }
        let start = Instant::now();
        while child.try_wait().unwrap().is_none() {
            if start.elapsed() > BOUND {
                let _ = child.kill();
                panic!("{args:?}: still running after {BOUND:?}");
            }
            std::thread::sleep(Duration::from_millis(5));
        }
        let out = child.wait_with_output().unwrap();
        (
            out.status,
            String::from_utf8_lossy(&out.stderr).into_owned(),
        )
    };
    if Path::new("/dev/full").exists() {
        for args in [
            vec!["check", &e],
            vec!["import", pmks.to_str().unwrap(), "--input", "0,1"],
            vec!["solve", &e, "--at", "0"],
            vec!["sweep", &e, "--from", "0", "--to", "1", "--steps", "10"],
            vec!["flywheel", &e, "--speed", "100", "--irregularity", "0.02"],
            vec!["simulate", &e, "--t-end", "0.01"],
            vec!["cam", &cam],
        ] {
            let full = std::fs::OpenOptions::new()
                .write(true)
                .open("/dev/full")
                .unwrap();
            let (status, err) = spawn(&args, full.into(), false);
            assert_eq!(
                status.code(),
                Some(1),
                "{args:?} > /dev/full: {status}\n{err}"
            );
            assert!(
                err.contains("cannot write standard output: No space left on device"),
                "{args:?} > /dev/full:\n{err}"
            );
        }
    }
    let args = [
        "sweep", &e, "--from", "0", "--to", "1", "--steps", "200000", "--level", "pose",
    ];
    let (status, err) = spawn(&args, std::process::Stdio::piped(), true);
    assert_eq!(status.code(), Some(1), "closed pipe: {status}\n{err}");
    assert!(err.contains("cannot write standard output"), "{err}");
}
