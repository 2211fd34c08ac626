//! `mech serve` (SPEC 3j), the real binary on a temporary copy of
//! examples/mech/four_bar.mech with `--port 0`, spoken to over HTTP/1.0 by a small client
//! of std::net: it listens on 127.0.0.1 only and refuses any other path; its frame's points
//! are `mech solve`'s, its charts `mech sweep`'s and `mech shaking`'s columns; an edit on
//! disk is served within a second; a broken file shows `mech check`'s message and line
//! with the last good drawing kept; it survives the file deleted, renamed and half
//! written; a drag rewrites only the point's numbers. Last, the page in headless Chromium
//! (tools/serve_check.sh).

use assert_cmd::Command as Cmd;
use serde_json::Value;
use std::io::{BufRead, BufReader, Read, Write};
use std::net::TcpStream;
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};
use std::time::{Duration, Instant};

const FOUR_BAR: &str = include_str!("../../examples/mech/four_bar.mech");

/// A running `mech serve` on a copy of the four-bar; killed when dropped.
struct Server {
    child: Child,
    port: u16,
    file: PathBuf,
    _dir: tempfile::TempDir,
}

impl Drop for Server {
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

fn mech_bin() -> PathBuf {
    assert_cmd::cargo::cargo_bin("mech")
}

impl Server {
    fn start() -> Server {
        let dir = tempfile::tempdir().unwrap();
        let file = dir.path().join("four_bar.mech");
        std::fs::write(&file, FOUR_BAR).unwrap();
        let mut child = Command::new(mech_bin())
            .args(["serve", file.to_str().unwrap(), "--port", "0"])
            .stdin(Stdio::null())
            .stdout(Stdio::null())
            .stderr(Stdio::piped())
            .spawn()
            .unwrap();
        let mut lines = BufReader::new(child.stderr.take().unwrap()).lines();
        let first = lines.next().expect("a line on stderr").unwrap();
        // Keep draining standard error so that the server never blocks on it.
        std::thread::spawn(move || for _ in lines {});
        let at = first
            .find("http://127.0.0.1:")
            .unwrap_or_else(|| panic!("no address in {first:?}"));
        let port: u16 = first[at + 17..].split('/').next().unwrap().parse().unwrap();
        Server {
            child,
            port,
            file,
            _dir: dir,
        }
    }

    /// A request; the status and the body.
    fn request(&self, method: &str, path: &str, body: &str) -> (u16, String) {
        let mut s = TcpStream::connect(("127.0.0.1", self.port)).unwrap();
        s.set_read_timeout(Some(Duration::from_secs(20))).unwrap();
        write!(
            s,
            "{method} {path} HTTP/1.0\r\nHost: 127.0.0.1\r\nContent-Type: application/json\r\nContent-Length: {}\r\n\r\n{body}",
            body.len()
        )
        .unwrap();
        let mut out = String::new();
        s.read_to_string(&mut out).unwrap();
        let status = out
            .split_whitespace()
            .nth(1)
            .and_then(|c| c.parse().ok())
            .unwrap_or_else(|| panic!("no status in {out:?}"));
        let body = out.split_once("\r\n\r\n").map_or("", |b| b.1).to_string();
        (status, body)
    }

    fn get(&self, path: &str) -> (u16, String) {
        self.request("GET", path, "")
    }

    fn json(&self, path: &str) -> Value {
        let (status, body) = self.get(path);
        assert_eq!(status, 200, "GET {path}: {body}");
        serde_json::from_str(&body).unwrap()
    }

    fn model(&self) -> Value {
        self.json("/api/model")
    }

    /// Waits (at most `limit`) for the model's version to pass `version`; the model and
    /// the time it took.
    fn next_model(&self, version: u64, limit: Duration) -> (Value, Duration) {
        let t = Instant::now();
        loop {
            let m = self.model();
            if m["version"].as_u64().unwrap() > version {
                return (m, t.elapsed());
            }
            assert!(
                t.elapsed() < limit,
                "the server did not follow the file within {limit:?}"
            );
            std::thread::sleep(Duration::from_millis(20));
        }
    }
}

/// A CSV of `mech` (header, rows) as name → column.
fn csv(text: &str) -> Vec<(String, Vec<f64>)> {
    let mut lines = text.lines();
    let names: Vec<String> = lines.next().unwrap().split(',').map(String::from).collect();
    let mut cols: Vec<(String, Vec<f64>)> = names.into_iter().map(|n| (n, vec![])).collect();
    for l in lines {
        for (c, v) in cols.iter_mut().zip(l.split(',')) {
            c.1.push(v.parse().unwrap());
        }
    }
    cols
}

fn mech(args: &[&str]) -> String {
    let out = Cmd::cargo_bin("mech").unwrap().args(args).output().unwrap();
    assert!(
        out.status.success(),
        "mech {args:?}: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8(out.stdout).unwrap()
}

#[test]
fn it_listens_on_loopback_only_and_refuses_other_paths() {
    let s = Server::start();
    // The listening socket (/proc/net/tcp, state 0A) is bound to 127.0.0.1, and nothing
    // listens on this port over IPv6.
    let port = format!(":{:04X}", s.port);
    let tcp = std::fs::read_to_string("/proc/net/tcp").unwrap();
    let listening: Vec<&str> = tcp
        .lines()
        .filter(|l| {
            let f: Vec<&str> = l.split_whitespace().collect();
            f.len() > 3 && f[1].ends_with(&port) && f[3] == "0A"
        })
        .collect();
    assert_eq!(listening.len(), 1, "{listening:?}");
    assert!(
        listening[0].split_whitespace().nth(1).unwrap() == format!("0100007F{port}"),
        "{listening:?}"
    );
    if let Ok(tcp6) = std::fs::read_to_string("/proc/net/tcp6") {
        assert!(!tcp6.lines().any(|l| {
            let f: Vec<&str> = l.split_whitespace().collect();
            f.len() > 3 && f[1].ends_with(&port) && f[3] == "0A"
        }));
    }
    // The page and its script are served, and need no network.
    let (status, page) = s.get("/");
    assert_eq!(status, 200);
    assert!(page.contains("<script src=\"/page.js\">"), "{page}");
    let (status, script) = s.get("/page.js");
    assert_eq!(status, 200);
    assert!(script.contains("EventSource"));
    for text in [&page, &script] {
        let outside = text
            .replace("http://www.w3.org/2000/svg", "")
            .contains("http");
        assert!(!outside, "the page names an address outside");
    }
    // Any other path, the file itself, a `..` or an absolute path: 404, no file read.
    for path in [
        "/four_bar.mech",
        "/etc/passwd",
        "/../four_bar.mech",
        "/%2e%2e/%2e%2e/etc/passwd",
        "/api/../../etc/passwd",
        "//etc/passwd",
        "/api/file?path=/etc/passwd",
        "/api/frames",
    ] {
        let (status, body) = s.get(path);
        assert_eq!(status, 404, "{path}: {body}");
        assert!(!body.contains("root:"), "{path}");
    }
    assert_eq!(s.request("POST", "/api/model", "").0, 405);
    // Another host name (DNS rebinding), a drag that is not JSON or from another origin.
    let raw = |head: &str, body: &str| {
        let mut c = TcpStream::connect(("127.0.0.1", s.port)).unwrap();
        write!(c, "{head}Content-Length: {}\r\n\r\n{body}", body.len()).unwrap();
        let mut out = String::new();
        c.read_to_string(&mut out).unwrap();
        out.split_whitespace()
            .nth(1)
            .unwrap()
            .parse::<u16>()
            .unwrap()
    };
    assert_eq!(
        raw("GET /api/model HTTP/1.0\r\nHost: evil.example:80\r\n", ""),
        403
    );
    assert_eq!(raw("GET /api/model HTTP/1.0\r\n", ""), 403);
    let drag = r#"{"point": "A", "x": 0.05, "y": 0.07}"#;
    let host = format!("Host: 127.0.0.1:{}\r\n", s.port);
    assert_eq!(
        raw(
            &format!("POST /api/drag HTTP/1.0\r\n{host}Content-Type: text/plain\r\n"),
            drag
        ),
        415
    );
    assert_eq!(
        raw(&format!("POST /api/drag HTTP/1.0\r\n{host}Content-Type: application/json\r\nOrigin: http://evil.example\r\n"), drag),
        403
    );
    assert_eq!(
        std::fs::read_to_string(&s.file).unwrap(),
        FOUR_BAR,
        "FILE untouched"
    );
    assert_eq!(
        raw(
            &format!("GET /api/model HTTP/1.0\r\nHost: localhost:{}\r\n", s.port),
            ""
        ),
        200
    );
}

#[test]
fn the_frame_is_mech_solve_at_the_sliders_value() {
    let s = Server::start();
    let path = s.file.to_str().unwrap();
    for q in ["0.7", "2.5", "-1"] {
        let f = s.json(&format!("/api/frame?q={q}"));
        let solved = csv(&mech(&[
            "solve", path, "--at", q, "--level", "pose", "--format", "csv",
        ]));
        let mut compared = 0;
        for (name, v) in &solved {
            if let Some((p, c)) = name.split_once('.') {
                let k = match c {
                    "x" => 0,
                    "y" => 1,
                    _ => continue,
                };
                let got = f["points"][p][k].as_f64().unwrap();
                assert_eq!(got, v[0], "{name} at q = {q}");
                compared += 1;
            }
        }
        assert_eq!(compared, 2 * 5, "every point's x and y at q = {q}");
        // Every shape has its placing attributes, and the pins are where the points are.
        assert!(f["attrs"].as_array().unwrap().len() > 10);
        let view = &s.model()["view"];
        let (k, pad) = (view["k"].as_f64().unwrap(), view["pad"].as_f64().unwrap());
        let a = &f["points"]["A"];
        let px = &f["px"]["A"];
        let x = (a[0].as_f64().unwrap() - view["x_min"].as_f64().unwrap()) * k + pad;
        assert!((px[0].as_f64().unwrap() - x).abs() < 1e-9);
    }
    // A value that is no number: a clear 400.
    let (status, body) = s.get("/api/frame?q=abc");
    assert_eq!(status, 400);
    assert!(body.contains("not a finite number"), "{body}");
}

#[test]
fn the_charts_are_mech_sweeps_columns() {
    let s = Server::start();
    let c = s.json("/api/charts?speed=12");
    let path = s.file.to_str().unwrap();
    let two_pi = format!("{:?}", std::f64::consts::TAU);
    let sweep = csv(&mech(&[
        "sweep", path, "--from", "0", "--to", &two_pi, "--steps", "360", "--speed", "12",
        "--format", "csv",
    ]));
    let x: Vec<f64> = c["x"]
        .as_array()
        .unwrap()
        .iter()
        .map(|v| v.as_f64().unwrap())
        .collect();
    assert_eq!(x, sweep.iter().find(|c| c.0 == "q").unwrap().1);
    let mut compared = Vec::new();
    for (name, values) in &sweep {
        if let Some(col) = c["columns"].get(name) {
            let got: Vec<f64> = col
                .as_array()
                .unwrap()
                .iter()
                .map(|v| v.as_f64().unwrap())
                .collect();
            assert_eq!(&got, values, "column {name}");
            compared.push(name.as_str());
        }
    }
    for name in [
        "driver",
        "virtual_power",
        "inertia",
        "moment",
        "O2.fx",
        "A.fy",
        "B.fx",
        "O4.fy",
    ] {
        assert!(
            compared.contains(&name),
            "{name} not in the charts: {compared:?}"
        );
    }
    // The shaking force is `mech shaking`'s.
    let shaking = csv(&mech(&[
        "shaking", path, "--speed", "12", "--format", "csv",
    ]));
    for name in ["shaking.fx", "shaking.fy"] {
        let got: Vec<f64> = c["columns"][name]
            .as_array()
            .unwrap()
            .iter()
            .map(|v| v.as_f64().unwrap())
            .collect();
        assert_eq!(
            got,
            shaking.iter().find(|c| c.0 == name).unwrap().1,
            "{name}"
        );
    }
    assert!(c["cam"].is_null(), "a four-bar has no cam");
}

#[test]
fn an_edit_on_disk_is_served_within_a_second() {
    let s = Server::start();
    let v0 = s.model()["version"].as_u64().unwrap();
    // The event stream says the version now, then again when the file changes.
    let mut events = TcpStream::connect(("127.0.0.1", s.port)).unwrap();
    events
        .set_read_timeout(Some(Duration::from_secs(5)))
        .unwrap();
    write!(
        events,
        "GET /api/events HTTP/1.0\r\nHost: 127.0.0.1\r\n\r\n"
    )
    .unwrap();
    let mut events = BufReader::new(events);
    let mut read_event = || loop {
        let mut line = String::new();
        events.read_line(&mut line).unwrap();
        if let Some(d) = line.strip_prefix("data:") {
            return d.trim().parse::<u64>().unwrap();
        }
    };
    assert_eq!(read_event(), v0);
    let edited = FOUR_BAR.replace("O4: (0.3, 0.04)", "O4: (0.32, 0.04)");
    assert_ne!(edited, FOUR_BAR);
    std::fs::write(&s.file, &edited).unwrap();
    let (m, took) = s.next_model(v0, Duration::from_secs(1));
    assert!(m["error"].is_null(), "{m}");
    assert!(took < Duration::from_secs(1), "{took:?}");
    assert!(read_event() > v0);
    let f = s.json("/api/frame?q=1");
    assert_eq!(f["points"]["O4"][0].as_f64(), Some(0.32));
}

/// The line (1-based) of `text` that holds `needle`.
fn line_of(text: &str, needle: &str) -> u64 {
    text.lines().position(|l| l.contains(needle)).unwrap() as u64 + 1
}

#[test]
fn a_broken_file_shows_mech_checks_message_and_line() {
    let s = Server::start();
    let good = s.model();
    let broken = FOUR_BAR.replace(
        "B: revolute(coupler, rocker)",
        "B: revolute(coupler, rockr)",
    );
    std::fs::write(&s.file, &broken).unwrap();
    let (m, _) = s.next_model(good["version"].as_u64().unwrap(), Duration::from_secs(1));
    let e = &m["error"];
    assert_eq!(e["line"].as_u64(), Some(line_of(&broken, "rockr")), "{e}");
    let check = Cmd::cargo_bin("mech")
        .unwrap()
        .args(["check", s.file.to_str().unwrap()])
        .output()
        .unwrap();
    assert_eq!(check.status.code(), Some(1));
    assert_eq!(
        e["message"].as_str().unwrap().trim_end(),
        String::from_utf8_lossy(&check.stderr).trim_end()
    );
    assert!(e["message"].as_str().unwrap().contains("rockr"));
    // The last good drawing stays, and still moves.
    assert_eq!(m["picture"], good["picture"]);
    assert_eq!(s.get("/api/frame?q=0.3").0, 200);
    // Fixed: the error goes.
    std::fs::write(&s.file, FOUR_BAR).unwrap();
    let (m, _) = s.next_model(m["version"].as_u64().unwrap(), Duration::from_secs(1));
    assert!(m["error"].is_null(), "{m}");
}

#[test]
fn it_survives_the_file_deleted_renamed_and_half_written() {
    let s = Server::start();
    let mut v = s.model()["version"].as_u64().unwrap();
    let mut step = |what: &str, change: &dyn Fn(), broken: bool| {
        change();
        let (m, _) = s.next_model(v, Duration::from_secs(1));
        v = m["version"].as_u64().unwrap();
        assert_eq!(!m["error"].is_null(), broken, "{what}: {m}");
        assert!(
            m["picture"].as_str().unwrap().contains("<svg"),
            "{what}: the last good drawing"
        );
        assert_eq!(s.get("/api/frame?q=1").0, 200, "{what}");
        m
    };
    let file = s.file.clone();
    let aside = file.with_extension("moved");
    let m = step("deleted", &|| std::fs::remove_file(&file).unwrap(), true);
    assert!(
        m["error"]["message"]
            .as_str()
            .unwrap()
            .contains("cannot read"),
        "{m}"
    );
    step("back", &|| std::fs::write(&file, FOUR_BAR).unwrap(), false);
    step(
        "renamed away",
        &|| std::fs::rename(&file, &aside).unwrap(),
        true,
    );
    step(
        "renamed back",
        &|| std::fs::rename(&aside, &file).unwrap(),
        false,
    );
    let half = &FOUR_BAR[..FOUR_BAR.len() / 2];
    let m = step(
        "half written",
        &|| std::fs::write(&file, half).unwrap(),
        true,
    );
    assert!(m["error"]["line"].as_u64().is_some(), "{m}");
    step(
        "whole again",
        &|| std::fs::write(&file, FOUR_BAR).unwrap(),
        false,
    );
    // The renamed file was never written.
    assert!(!Path::new(&aside).exists());
}

#[test]
fn a_drag_rewrites_only_the_points_numbers() {
    let s = Server::start();
    // A comment that names the point, and another layout, must stay as they are.
    let before = FOUR_BAR.replace(
        "    link crank {",
        "    // A: (1.0, 2.0) is not the point, only a comment\n    link crank {",
    );
    let v = s.model()["version"].as_u64().unwrap();
    std::fs::write(&s.file, &before).unwrap();
    let (m, _) = s.next_model(v, Duration::from_secs(1));
    assert!(m["error"].is_null());
    let (status, body) = s.request(
        "POST",
        "/api/drag",
        r#"{"point": "A", "x": 0.05, "y": 0.0712345678}"#,
    );
    assert_eq!(status, 200, "{body}");
    let after = std::fs::read_to_string(&s.file).unwrap();
    assert_eq!(
        after,
        before.replace("A: (0.04, 0.06928203230275509)", "A: (0.05, 0.07123)"),
        "only A's numbers change"
    );
    // The server follows: A is where it was dropped, in the drawing as written.
    let m = s.model();
    assert!(m["error"].is_null(), "{m}");
    let f = s.json("/api/frame");
    assert!(
        (f["points"]["A"][0].as_f64().unwrap() - 0.05).abs() < 1e-12,
        "{f}"
    );
    assert!(
        (f["points"]["A"][1].as_f64().unwrap() - 0.07123).abs() < 1e-12,
        "{f}"
    );
    // A ground point, then refusals: no such point, not JSON; the file stays.
    let (status, _) = s.request(
        "POST",
        "/api/drag",
        r#"{"point": "O4", "x": 0.31, "y": 0.05}"#,
    );
    assert_eq!(status, 200);
    let moved = std::fs::read_to_string(&s.file).unwrap();
    assert_eq!(moved, after.replace("O4: (0.3, 0.04)", "O4: (0.31, 0.05)"));
    for body in [
        r#"{"point": "Z", "x": 0, "y": 0}"#,
        "not json",
        r#"{"point": "A"}"#,
    ] {
        let (status, msg) = s.request("POST", "/api/drag", body);
        assert_eq!(status, 400, "{body}: {msg}");
    }
    assert_eq!(std::fs::read_to_string(&s.file).unwrap(), moved);
}

/// The page in a real browser (tools/serve_check.sh: headless Chromium, driven by
/// Playwright, installed when missing): the drawing moves with the slider (pins against
/// `mech solve`), a chart's value against `mech sweep`, an edit on disk shown within a
/// second, a broken file's line shown, a drag that rewrites the file's numbers only; and
/// the screenshot docs/img/serve.png.
#[test]
fn the_page_in_headless_chromium() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let out = Command::new("bash")
        .arg("tools/serve_check.sh")
        .env("MECH_BIN", mech_bin())
        .current_dir(&root)
        .output()
        .expect("bash runs tools/serve_check.sh");
    let (stdout, stderr) = (
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr),
    );
    assert!(
        out.status.success(),
        "tools/serve_check.sh failed ({}):\n{stdout}\n{stderr}",
        out.status
    );
    let summary = stdout
        .lines()
        .rev()
        .find(|l| l.starts_with("serve_check:"))
        .unwrap_or_else(|| panic!("no summary:\n{stdout}\n{stderr}"));
    assert!(
        summary.contains(" 5 passed, 0 failed"),
        "{summary}\n{stdout}"
    );
}

/// What cannot be served is refused at the start with a message and status 2: standard
/// input, a file that is missing, a directory or binary, a port already taken.
#[test]
fn what_cannot_be_served_is_refused_at_the_start() {
    let dir = tempfile::tempdir().unwrap();
    let binary = dir.path().join("binary.mech");
    std::fs::write(&binary, [0u8; 64]).unwrap();
    let missing = dir.path().join("missing.mech");
    let cases: Vec<(Vec<&str>, &str)> = vec![
        (vec!["-"], "give a file, not standard input"),
        (vec![missing.to_str().unwrap()], "cannot read"),
        (vec![dir.path().to_str().unwrap()], "is a directory"),
        (vec![binary.to_str().unwrap()], "is a binary file"),
    ];
    for (args, phrase) in cases {
        let out = Cmd::cargo_bin("mech")
            .unwrap()
            .arg("serve")
            .args(&args)
            .args(["--port", "0"])
            .timeout(Duration::from_secs(20))
            .output()
            .unwrap();
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{args:?}: {err}");
        assert!(err.contains(phrase), "{args:?}: {err}");
    }
    // A port that is taken.
    let s = Server::start();
    let out = Cmd::cargo_bin("mech")
        .unwrap()
        .args([
            "serve",
            s.file.to_str().unwrap(),
            "--port",
            &s.port.to_string(),
        ])
        .timeout(Duration::from_secs(20))
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(err.contains("cannot listen on 127.0.0.1"), "{err}");
}
