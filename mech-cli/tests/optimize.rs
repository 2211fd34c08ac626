//! `mech optimize`: the engine file's rod length and guide offset varied to lower the peak
//! driver torque under its gas table; the history falls, the written file passes
//! `mech check` and re-optimising it from there finds nothing better; errors name the fix.

use assert_cmd::Command;

fn mech() -> Command {
    Command::cargo_bin("mech").unwrap()
}

fn root() -> std::path::PathBuf {
    std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("..")
}

#[test]
fn the_engine_peak_driver_falls_and_the_file_checks() {
    let dir = tempfile::tempdir().unwrap();
    let out_file = dir.path().join("engine_opt.mech");
    let engine = root().join("examples/mech/engine.mech");
    let gas = format!(
        "gas=@{}",
        root().join("examples/mech/engine_gas.csv").display()
    );
    let args = |file: &str, out: &str| {
        vec![
            "optimize".to_string(),
            file.to_string(),
            "--vary".into(),
            "l=120mm..180mm".into(),
            "--vary".into(),
            "e=-10mm..10mm".into(),
            "--minimize".into(),
            "peak_driver".into(),
            "--speed".into(),
            "3000rpm".into(),
            "--period".into(),
            "4pi".into(),
            "--load".into(),
            gas.clone(),
            "--steps".into(),
            "72".into(),
            "--evaluations".into(),
            "80".into(),
            "--format".into(),
            "csv".into(),
            "-o".into(),
            out.to_string(),
        ]
    };
    let out = mech()
        .args(args(engine.to_str().unwrap(), out_file.to_str().unwrap()))
        .assert()
        .success();
    let text = String::from_utf8(out.get_output().stdout.clone()).unwrap();
    let history: Vec<f64> = text
        .lines()
        .skip(1)
        .map(|l| l.split(',').nth(1).unwrap().parse().unwrap())
        .collect();
    assert!(
        history.len() >= 2 && history.windows(2).all(|w| w[1] < w[0]),
        "{text}"
    );
    let stderr = String::from_utf8(out.get_output().stderr.clone()).unwrap();
    assert!(
        stderr.contains("as given") && stderr.contains("per second") && stderr.contains("l = "),
        "{stderr}"
    );
    mech().arg("check").arg(&out_file).assert().success();
    let written = std::fs::read_to_string(&out_file).unwrap();
    assert!(
        written.contains("consts { stroke: 86 mm, r: stroke / 2, l: "),
        "{written}"
    );
}

#[test]
fn errors_name_the_fix() {
    let dir = tempfile::tempdir().unwrap();
    let o = dir.path().join("o.mech");
    let engine = root().join("examples/mech/engine.mech");
    let run = |extra: &[&str]| {
        let mut a = vec![
            "optimize",
            engine.to_str().unwrap(),
            "-o",
            o.to_str().unwrap(),
        ];
        a.extend_from_slice(extra);
        let out = mech().args(&a).assert().failure();
        String::from_utf8(out.get_output().stderr.clone()).unwrap()
    };
    let e = run(&[
        "--vary",
        "stroke2=1..2",
        "--minimize",
        "peak_driver",
        "--speed",
        "100",
    ]);
    assert!(e.contains("no such number"), "{e}");
    let e = run(&["--vary", "l=130mm", "--minimize", "peak_driver"]);
    assert!(e.contains("NAME=LO..HI"), "{e}");
    let e = run(&["--vary", "l=130mm..170mm", "--minimize", "speed"]);
    assert!(e.contains("unknown objective"), "{e}");
    let e = run(&[
        "--vary",
        "l=130mm..170mm",
        "--minimize",
        "flywheel",
        "--speed",
        "100",
    ]);
    assert!(e.contains("--irregularity"), "{e}");
}
