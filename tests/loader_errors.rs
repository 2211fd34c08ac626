//! A mistake in a mechanism loaded from text gets the macro's message, at the macro's line
//! and column, with the offending excerpt: every compile-fail case of `tests/ui` (the
//! checks of `docs/conventions.md#checks`) is loaded as text with
//! `GenericMechanism::from_rust_source` (the loader behind `mech::Mechanism`) and compared
//! with its `.stderr`.

use mech::prelude::*;
use mech_oracle::GenericMechanism;

/// (message's first line, line, column) of each `error: ...` the macro reports, from a
/// trybuild `.stderr` (pointers "involved here" and type errors `error[E...]` skipped).
fn macro_errors(stderr: &str) -> Vec<(String, usize, usize)> {
    let lines: Vec<&str> = stderr.lines().collect();
    let mut out = Vec::new();
    for (i, l) in lines.iter().enumerate() {
        let Some(msg) = l.strip_prefix("error: ") else {
            continue;
        };
        if msg.starts_with("involved here") {
            continue;
        }
        let Some(at) = lines[i + 1..]
            .iter()
            .find_map(|l| l.trim_start().strip_prefix("--> "))
        else {
            continue;
        };
        let mut parts = at.rsplitn(3, ':');
        let (col, line) = (
            parts.next().unwrap().parse().unwrap(),
            parts.next().unwrap().parse().unwrap(),
        );
        out.push((msg.to_string(), line, col));
    }
    out
}

#[test]
fn every_ui_mistake_loaded_as_text_gets_the_same_message_and_place() {
    let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/ui");
    let mut covered = 0;
    let mut entries: Vec<_> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .collect();
    entries.sort();
    for path in entries
        .iter()
        .filter(|p| p.extension().is_some_and(|e| e == "rs"))
    {
        let stderr = std::fs::read_to_string(path.with_extension("stderr")).unwrap();
        let expected = macro_errors(&stderr);
        if expected.is_empty() {
            continue; // not a check of the mechanism (a type error in the user's code)
        }
        if path
            .file_name()
            .unwrap()
            .to_string_lossy()
            .starts_with("macro_only_")
        {
            continue; // what the loader takes on purpose (`free(LO..HI)`: `mech size`'s input)
        }
        let source = std::fs::read_to_string(path).unwrap();
        let name = source
            .split("pub struct ")
            .nth(1)
            .and_then(|r| r.split(|c: char| !c.is_alphanumeric() && c != '_').next())
            .unwrap();
        let file = path.file_name().unwrap().to_string_lossy();
        if source.contains("        space,\n") {
            spatial_case(&file, &source, &expected);
            covered += 1;
            continue;
        }
        let msg = match GenericMechanism::from_rust_source(&source, name) {
            Err(MechError::Invalid(msg)) => msg,
            other => panic!(
                "{file}: expected Invalid, got {:?}",
                other.map(|_| "a mechanism")
            ),
        };
        for (text, line, col) in expected {
            assert!(
                msg.contains(&text),
                "{file}: the macro's message\n  {text}\nis not in\n{msg}"
            );
            assert!(
                msg.contains(&format!("{line}:{col}: ")),
                "{file}: no {line}:{col} in\n{msg}"
            );
            let excerpt = source.lines().nth(line - 1).unwrap().trim();
            assert!(
                msg.contains(excerpt),
                "{file}: the excerpt `{excerpt}` is not in\n{msg}"
            );
        }
        covered += 1;
    }
    eprintln!("{covered} cases of tests/ui loaded as text");
    assert!(covered >= 25, "only {covered} cases covered");
}

/// A spatial case (`space` first): the run-time spatial loader, given the macro's body,
/// reports each of the macro's messages; one the loader places (a naming, unit or geometry
/// mistake: `line L, column C: ` of the body) is at the macro's place. The counts (Kutzbach,
/// the rank) name the mechanism as a whole at run time.
fn spatial_case(file: &str, source: &str, expected: &[(String, usize, usize)]) {
    let open = source.find("mechanism! {\n").unwrap() + "mechanism! {\n".len();
    let close = source.rfind("\n}\n").unwrap();
    let offset = source[..open].lines().count();
    let msg = match mech::spatial::SpatialMechanism::from_dsl(&source[open..close]) {
        Err(MechError::Invalid(msg)) => msg,
        other => panic!("{file}: expected Invalid, got {other:?}"),
    };
    for (text, line, col) in expected {
        let found = msg.lines().find(|l| l.contains(text.as_str()));
        let found = found
            .unwrap_or_else(|| panic!("{file}: the macro's message\n  {text}\nis not in\n{msg}"));
        if found.starts_with("line ") {
            let at = format!("line {}, column {col}: {text}", line - offset);
            assert_eq!(found, at, "{file}: not at the macro's place");
        }
    }
}

/// The rendering: the location line, then the excerpt with the culprit underlined.
#[test]
fn a_rendered_error_shows_the_line_and_the_culprit() {
    let text = "pub struct X {\n    ground { O: (0.0, 0.0) },\n    link crank { points { O, A: (1.0, 0.0) }, mass: -2.0, cg: (0.5, 0.0) },\n    joints { O: revolute(ground, crank) },\n    input: O,\n}\n";
    let Err(MechError::Invalid(msg)) = Mechanism::from_dsl(text) else {
        panic!("accepted")
    };
    eprintln!("{msg}");
    let first = msg.lines().next().unwrap();
    assert!(first.starts_with("3:"), "{msg}");
    assert!(
        msg.contains("link crank { points { O, A: (1.0, 0.0) }, mass: -2.0"),
        "{msg}"
    );
    assert!(msg.lines().any(|l| l.contains('^')), "no underline:\n{msg}");
}
