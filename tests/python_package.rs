//! The Python package's pytest suite (`mech-py/tests`) as part of `cargo test --workspace`,
//! the README's test command: `tools/python_tests.sh` builds the package from this
//! repository (maturin) into a virtual environment under `target/` and runs pytest there.
//! Needs python3 with venv and pip, and pip's network access for maturin, numpy, pytest,
//! dask and pandas.

use std::process::Command;

#[test]
fn the_python_package_passes_its_pytest_suite() {
    let root = env!("CARGO_MANIFEST_DIR");
    let out = Command::new("bash")
        .arg("tools/python_tests.sh")
        .current_dir(root)
        .output()
        .expect("bash runs tools/python_tests.sh");
    let (stdout, stderr) = (
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr),
    );
    assert!(
        out.status.success(),
        "tools/python_tests.sh failed ({}):\n{stdout}\n{stderr}",
        out.status
    );
    // pytest -q ends with "N passed in T s": the suite ran, and nothing failed or errored.
    let summary = stdout
        .lines()
        .rev()
        .find(|l| l.contains(" passed"))
        .unwrap_or_else(|| panic!("no pytest summary:\n{stdout}"));
    let passed: usize = summary
        .split_whitespace()
        .next()
        .and_then(|n| n.parse().ok())
        .unwrap_or(0);
    assert!(passed >= 18, "{summary}");
    assert!(
        !summary.contains("failed") && !summary.contains("error"),
        "{summary}"
    );
}
