//! Snapshots of what a user reads (insta): `mech check`'s structure report, a check
//! error with its excerpt, and `mech --help`. A change shows up as a reviewable diff
//! (`cargo insta review`, or INSTA_UPDATE=always).

use assert_cmd::Command;
use std::path::Path;

fn run(args: &[&str]) -> (String, String) {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let out = Command::cargo_bin("mech")
        .unwrap()
        .current_dir(&root)
        .args(args)
        .output()
        .unwrap();
    (
        String::from_utf8(out.stdout).unwrap(),
        String::from_utf8(out.stderr).unwrap(),
    )
}

#[test]
fn check_reports_the_structure() {
    insta::assert_snapshot!(
        "check_watt_ii",
        run(&["check", "examples/mech/watt_ii.mech"]).0
    );
    insta::assert_snapshot!(
        "check_jansen",
        run(&["check", "examples/mech/jansen.mech"]).0
    );
}

#[test]
fn check_points_into_the_file() {
    let dir = tempfile::tempdir().unwrap();
    let text = std::fs::read_to_string(
        Path::new(env!("CARGO_MANIFEST_DIR")).join("../examples/mech/five_bar.mech"),
    )
    .unwrap();
    let bad = dir.path().join("five_bar.mech");
    std::fs::write(
        &bad,
        text.replace(
            "circle_circle(C, 230 mm, O5, 190 mm, right)",
            "circle_circle(C, 23 mm, O5, 190 mm, right)",
        ),
    )
    .unwrap();
    let err = run(&["check", bad.to_str().unwrap()])
        .1
        .replace(bad.to_str().unwrap(), "five_bar.mech");
    insta::assert_snapshot!("check_error_five_bar", err);
}

#[test]
fn help_lists_every_subcommand() {
    insta::assert_snapshot!("help", run(&["--help"]).0);
}
