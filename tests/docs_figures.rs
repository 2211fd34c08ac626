//! Every measured figure of README.md and docs/*.md comes from a committed command:
//! `python3 tools/report.py NAME` prints it between the markers `<!-- report NAME -->` and
//! `<!-- /report NAME -->`, with the commit, the code's hash and the machine (the script's
//! header explains the blocks).
//!
//! - every block names a figure of `tools/report.py` and says how, where and on what code it
//!   was measured;
//! - outside the blocks (and outside code fences), no line of README.md or docs/*.md holds a
//!   measured-looking number: a ratio `1.2×`, a time `40 ns` / `3 µs` / `2 ms`, a rate `…/s`
//!   — a target stated as such (`≤ 1.3×`, `within 1.5×`, `at most`, `target`) excepted;
//! - a block of the README whose code changed since it was measured (the FNV-1a hash of the
//!   files it names, recomputed here exactly as the script computes it) fails: the README's
//!   tables are the command's output on the code they describe.

use std::collections::HashSet;
use std::path::{Path, PathBuf};

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// README.md and docs/*.md, with their text.
fn documents() -> Vec<(String, String)> {
    let mut out = vec![("README.md".to_string(), read(&root().join("README.md")))];
    let mut docs: Vec<_> = std::fs::read_dir(root().join("docs"))
        .expect("docs/")
        .map(|e| e.expect("entry").path())
        .filter(|p| p.extension().is_some_and(|e| e == "md"))
        .collect();
    docs.sort();
    for p in docs {
        let name = format!("docs/{}", p.file_name().unwrap().to_string_lossy());
        out.push((name, read(&p)));
    }
    out
}

fn read(p: &Path) -> String {
    std::fs::read_to_string(p).unwrap_or_else(|e| panic!("{}: {e}", p.display()))
}

/// The figure names of tools/report.py: the keys of its `FIGURES` table.
fn figures() -> Vec<String> {
    let src = read(&root().join("tools/report.py"));
    let table = src
        .split("FIGURES = {")
        .nth(1)
        .expect("tools/report.py has a FIGURES table");
    let table = &table[..table.find("\n}").expect("the FIGURES table ends")];
    table
        .lines()
        .filter_map(|l| {
            let l = l.trim_start();
            let rest = l.strip_prefix('"')?;
            let (name, after) = rest.split_once('"')?;
            after.starts_with(": Figure(").then(|| name.to_string())
        })
        .collect()
}

/// One report block of a document.
struct Block {
    doc: String,
    name: String,
    /// The line the block starts on (1-based).
    line: usize,
    body: String,
}

/// The blocks of a document, and its lines outside them (with their numbers).
fn split(doc: &str, text: &str) -> (Vec<Block>, Vec<(usize, String)>) {
    let (mut blocks, mut outside) = (Vec::new(), Vec::new());
    let mut open: Option<Block> = None;
    for (i, line) in text.lines().enumerate() {
        let t = line.trim();
        if let Some(name) = t
            .strip_prefix("<!-- report ")
            .and_then(|r| r.strip_suffix(" -->"))
        {
            assert!(
                open.is_none(),
                "{doc}:{}: a report block opens inside another",
                i + 1
            );
            open = Some(Block {
                doc: doc.to_string(),
                name: name.to_string(),
                line: i + 1,
                body: String::new(),
            });
        } else if let Some(name) = t
            .strip_prefix("<!-- /report ")
            .and_then(|r| r.strip_suffix(" -->"))
        {
            let b = open
                .take()
                .unwrap_or_else(|| panic!("{doc}:{}: `/report {name}` closes nothing", i + 1));
            assert_eq!(
                b.name,
                name,
                "{doc}:{}: block `{}` closed as `{name}`",
                i + 1,
                b.name
            );
            blocks.push(b);
        } else if let Some(b) = open.as_mut() {
            b.body.push_str(line);
            b.body.push('\n');
        } else {
            outside.push((i + 1, line.to_string()));
        }
    }
    assert!(open.is_none(), "{doc}: a report block is never closed");
    (blocks, outside)
}

/// The provenance line of a block: (commit, hash, paths).
fn provenance(b: &Block) -> (String, String, Vec<String>) {
    let where_ = format!("{}:{} (block `{}`)", b.doc, b.line, b.name);
    let sub = b
        .body
        .lines()
        .find(|l| l.starts_with("<sub>Printed by `python3 tools/report.py "))
        .unwrap_or_else(|| panic!("{where_}: no `<sub>Printed by ...` line: write it with `python3 tools/report.py {} --write`", b.name));
    assert!(
        sub.contains(&format!("tools/report.py {}`", b.name)),
        "{where_}: the line names another figure: {sub}"
    );
    let after = |key: &str| {
        sub.split_once(key)
            .unwrap_or_else(|| panic!("{where_}: no `{key}` in {sub}"))
            .1
    };
    let commit: String = after("on the code of ")
        .chars()
        .take_while(|c| c.is_ascii_hexdigit())
        .collect();
    assert!(
        commit.len() >= 7,
        "{where_}: no commit after `on the code of`"
    );
    let rest = after("(tree FNV-1a ");
    let (hash, rest) = rest.split_once(" of ").expect("hash, then `of`");
    let paths = rest
        .split_once("), ")
        .expect("the paths end with `), `")
        .0
        .split(", ")
        .map(str::to_string)
        .collect();
    assert!(
        after("), ").contains("cores"),
        "{where_}: the machine (processor and cores) is not stated"
    );
    (commit, hash.to_string(), paths)
}

/// The files under `paths` that git ignores (an insta `.snap.new` left by a failed run,
/// say), as repository-relative '/' paths: `git ls-files --others --ignored
/// --exclude-standard -- paths`, as `code_hash` of tools/report.py leaves them out. None
/// where git is missing or this is not a checkout (then every file counts).
fn ignored(paths: &[String]) -> HashSet<String> {
    let out = std::process::Command::new("git")
        .args([
            "ls-files",
            "-z",
            "--others",
            "--ignored",
            "--exclude-standard",
            "--",
        ])
        .args(paths)
        .current_dir(root())
        .output();
    match out {
        Ok(o) if o.status.success() => String::from_utf8_lossy(&o.stdout)
            .split('\0')
            .filter(|f| !f.is_empty())
            .map(str::to_string)
            .collect(),
        _ => HashSet::new(),
    }
}

/// FNV-1a 64 over every file under `paths` but those git ignores ([`ignored`]), sorted by
/// repository-relative '/' path: path bytes, NUL, content, NUL — `code_hash` of
/// tools/report.py.
fn code_hash(paths: &[String]) -> String {
    fn walk(dir: &Path, out: &mut Vec<PathBuf>) {
        for e in std::fs::read_dir(dir).unwrap_or_else(|e| panic!("{}: {e}", dir.display())) {
            let p = e.expect("entry").path();
            if p.is_dir() {
                walk(&p, out);
            } else if p.is_file() {
                out.push(p);
            }
        }
    }
    let mut files = Vec::new();
    for p in paths {
        let full = root().join(p);
        if full.is_file() {
            files.push(full);
        } else {
            walk(&full, &mut files);
        }
    }
    let mut rel: Vec<(String, PathBuf)> = files
        .into_iter()
        .map(|f| {
            let r = f.strip_prefix(root()).unwrap();
            let s = r
                .components()
                .map(|c| c.as_os_str().to_string_lossy().into_owned())
                .collect::<Vec<_>>()
                .join("/");
            (s, f)
        })
        .collect();
    let ignored = ignored(paths);
    rel.retain(|(r, _)| !ignored.contains(r));
    rel.sort();
    rel.dedup_by(|a, b| a.0 == b.0);
    let mut h: u64 = 0xCBF2_9CE4_8422_2325;
    let mut eat = |bytes: &[u8]| {
        for &b in bytes {
            h ^= u64::from(b);
            h = h.wrapping_mul(0x0100_0000_01B3);
        }
    };
    for (r, f) in rel {
        eat(r.as_bytes());
        eat(&[0]);
        eat(&std::fs::read(&f).expect("file"));
        eat(&[0]);
    }
    format!("{h:016x}")
}

/// A measured-looking number on a line: a ratio, a time or a rate (None: none).
fn measured(line: &str) -> Option<String> {
    let chars: Vec<char> = line.chars().collect();
    for (i, _) in chars.iter().enumerate().filter(|(_, c)| c.is_ascii_digit()) {
        // Only at the start of a number.
        if i > 0
            && (chars[i - 1].is_ascii_digit()
                || chars[i - 1] == '.'
                || chars[i - 1].is_alphabetic())
        {
            continue;
        }
        let mut j = i;
        while j < chars.len()
            && (chars[j].is_ascii_digit() || chars[j] == '.' || chars[j] == '\u{202f}')
        {
            j += 1;
        }
        let number: String = chars[i..j].iter().collect();
        let after: String = chars[j..].iter().collect();
        let unit = after.trim_start_matches(' ');
        let spaced = unit.len() < after.len();
        let ratio = !spaced
            && unit.starts_with('×')
            && !unit[('×'.len_utf8())..]
                .trim_start()
                .starts_with(|c: char| c.is_ascii_digit());
        let time = ["ns", "µs", "ms"].iter().any(|u| {
            unit.strip_prefix(u)
                .is_some_and(|r| !r.starts_with(|c: char| c.is_alphanumeric()))
        });
        let rate = unit.starts_with("/s") || unit.starts_with("configurations/s");
        if !(ratio || time || rate) {
            continue;
        }
        // A target, not a measurement.
        let before: String = chars[..i].iter().collect();
        let lead = before.trim_end();
        let tail: String = lead
            .chars()
            .rev()
            .take(24)
            .collect::<Vec<_>>()
            .into_iter()
            .rev()
            .collect();
        if ["≤", "<", "within", "at most", "below", "target", "under"]
            .iter()
            .any(|t| tail.ends_with(t) || tail.ends_with(&format!("{t} ~")))
        {
            continue;
        }
        return Some(format!("{number}{}", &after[..after.len().min(14)]));
    }
    None
}

#[test]
fn every_block_names_a_figure_and_its_provenance() {
    let names = figures();
    assert!(names.len() >= 5, "tools/report.py lists {names:?}");
    let mut seen = 0;
    for (doc, text) in documents() {
        for b in split(&doc, &text).0 {
            assert!(
                names.contains(&b.name),
                "{doc}:{}: `{}` is not a figure of tools/report.py ({names:?})",
                b.line,
                b.name
            );
            let (_, hash, paths) = provenance(&b);
            assert_eq!(hash.len(), 16, "{doc}:{}: hash {hash}", b.line);
            for p in &paths {
                assert!(
                    root().join(p).exists(),
                    "{doc}:{}: {p} does not exist",
                    b.line
                );
            }
            seen += 1;
        }
    }
    assert!(
        seen >= 5,
        "only {seen} report blocks in README.md and docs/"
    );
}

#[test]
fn no_measured_number_outside_a_block() {
    let mut bad = Vec::new();
    for (doc, text) in documents() {
        let mut fence = false;
        for (n, line) in split(&doc, &text).1 {
            if line.trim_start().starts_with("```") {
                fence = !fence;
                continue;
            }
            if fence {
                continue;
            }
            if let Some(m) = measured(&line) {
                bad.push(format!("{doc}:{n}: `{m}` in: {}", line.trim()));
            }
        }
    }
    assert!(
        bad.is_empty(),
        "measured figures outside a `<!-- report NAME -->` block (print them with \
         `python3 tools/report.py NAME --write`, or remove them):\n{}",
        bad.join("\n")
    );
}

#[test]
fn the_readme_figures_describe_this_code() {
    let text = read(&root().join("README.md"));
    let blocks = split("README.md", &text).0;
    assert!(!blocks.is_empty(), "the README shows no measured figure");
    for b in blocks {
        let (commit, hash, paths) = provenance(&b);
        let now = code_hash(&paths);
        assert_eq!(
            now, hash,
            "README.md:{}: the code under the figure `{}` (measured on {commit}) has changed \
             since: measure it again with `python3 tools/report.py {} --write`",
            b.line, b.name, b.name
        );
    }
}

#[test]
fn the_number_detector_sees_what_it_should() {
    assert!(measured("the ratio is 1.23× here").is_some());
    assert!(measured("| 40 ns | 0.98 ms |").is_some());
    assert!(measured("790 000 configurations/s").is_some());
    assert!(measured("at 430000/s").is_some());
    assert!(measured("each operation ≤ 1.3× its hand code").is_none());
    assert!(measured("within 1.5× of").is_none());
    assert!(measured("a 2×2 system, 3 × 3 matrices").is_none());
    assert!(measured("q̇ = 150 rad/s, 1e-3 s, 2 mm").is_none());
}
