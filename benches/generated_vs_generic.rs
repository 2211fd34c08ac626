//! Generated solvers against the run-time mechanism (`mech::Mechanism`: the same plan and
//! kernels, interpreted) and the dense generic solver (`mech::generic`), in the same run: for the four-bar, the slider-crank, the Watt II six-bar and the two-DOF five-bar
//! of `tests/common/mechanisms.rs`, each of `pose`, `kinematics`,
//! `kinematics + kinetostatics` and `kinematics + driver_action`.
//!
//! Every iteration takes the next of the twelve configurations (q, q̇, q̈) of the
//! mechanism's reference table `tests/data/<name>.truth.json` (with its loads), so both
//! solvers are timed over the same spread of input values: the generated closed forms cost
//! the same at any q, the generic continuation grows with |q − q_ref|.
//!
//! Run: `cargo bench --bench generated_vs_generic` (quick: `-- --warm-up-time 1
//! --measurement-time 3`); the table of `docs/performance.md` is made from the medians.

#[path = "../tests/common/mechanisms.rs"]
mod mechanisms;

use criterion::{black_box, criterion_group, criterion_main, Criterion};
use mech::Mechanism;
use mech_oracle::GenericMechanism;
use mechanisms::*;
use serde_json::Value;

const SOURCE: &str = include_str!("../tests/common/mechanisms.rs");

/// Configurations as (q, q̇, q̈) vectors.
type States = Vec<[Vec<f64>; 3]>;
/// Loads by name, their components.
type NamedLoads = Vec<(String, Vec<f64>)>;

/// The reference table's configurations as (q, q̇, q̈) vectors, and its loads.
fn table(name: &str) -> (States, NamedLoads) {
    let path = format!(
        "{}/tests/data/{name}.truth.json",
        env!("CARGO_MANIFEST_DIR")
    );
    let t: Value =
        serde_json::from_str(&std::fs::read_to_string(&path).expect("truth file")).expect("json");
    let nums = |v: &Value| -> Vec<f64> {
        match v {
            Value::Array(a) => a.iter().map(|x| x.as_f64().unwrap()).collect(),
            x => vec![x.as_f64().unwrap()],
        }
    };
    let configs = t["configs"]
        .as_array()
        .unwrap()
        .iter()
        .map(|c| [nums(&c["q"]), nums(&c["qd"]), nums(&c["qdd"])])
        .collect();
    let loads = t["loads"]
        .as_object()
        .unwrap()
        .iter()
        .map(|(n, l)| (n.clone(), nums(&l["value"])))
        .collect();
    (configs, loads)
}

/// Three benchmarks `<op>/generated`, `<op>/runtime` and `<op>/generic` of group `$grp`,
/// each call taking the next configuration: `$gen` with the typed inputs `$typed[i]`,
/// `$rt` and `$gnc` with the slices `$configs[i]`.
macro_rules! pair {
    ($grp:ident, $op:literal, $typed:ident, $configs:ident, |$q:pat_param| $gen:expr, |$r:pat_param| $rt:expr, |$g:pat_param| $gnc:expr) => {{
        let (mut i, n) = (0, $configs.len());
        $grp.bench_function(concat!($op, "/generated"), |b| {
            b.iter(|| {
                i = (i + 1) % n;
                let $q = $typed[i];
                $gen
            })
        });
        $grp.bench_function(concat!($op, "/runtime"), |b| {
            b.iter(|| {
                i = (i + 1) % n;
                let $r = &$configs[i];
                $rt
            })
        });
        $grp.bench_function(concat!($op, "/generic"), |b| {
            b.iter(|| {
                i = (i + 1) % n;
                let $g = &$configs[i];
                $gnc
            })
        });
    }};
}

macro_rules! bench_pair {
    ($c:ident, $file:literal, $ty:ident, $loads:ident, $to_q:expr) => {{
        let (configs, load_values) = table($file);
        let m = $ty::new();
        let g = GenericMechanism::from_rust_source(SOURCE, stringify!($ty)).unwrap();
        let r = Mechanism::from_rust_source(SOURCE, stringify!($ty)).unwrap();
        let mut loads = $loads::default();
        let mut gloads = g.loads();
        let mut rloads = r.loads();
        for (n, v) in &load_values {
            assert!(
                loads.set_by_name(n, v) && gloads.set_by_name(n, v) && rloads.set_by_name(n, v)
            );
        }
        let to_q = $to_q;
        let typed: Vec<_> = configs
            .iter()
            .map(|[q, qd, qdd]| (to_q(q), to_q(qd), to_q(qdd)))
            .collect();
        let mut grp = $c.benchmark_group($file);
        pair!(
            grp,
            "pose",
            typed,
            configs,
            |(q, _, _)| m.pose(black_box(q)).unwrap(),
            |[q, _, _]| r.pose(black_box(q)).unwrap(),
            |[q, _, _]| g.pose(black_box(q)).unwrap()
        );
        pair!(
            grp,
            "kinematics",
            typed,
            configs,
            |(q, qd, qdd)| m
                .kinematics(black_box(q), black_box(qd), black_box(qdd))
                .unwrap(),
            |[q, qd, qdd]| r
                .kinematics(black_box(q), black_box(qd), black_box(qdd))
                .unwrap(),
            |[q, qd, qdd]| g
                .kinematics(black_box(q), black_box(qd), black_box(qdd))
                .unwrap()
        );
        pair!(
            grp,
            "kinematics+kinetostatics",
            typed,
            configs,
            |(q, qd, qdd)| m
                .kinetostatics(
                    &m.kinematics(black_box(q), black_box(qd), black_box(qdd))
                        .unwrap(),
                    black_box(&loads)
                )
                .unwrap(),
            |[q, qd, qdd]| r
                .kinetostatics(
                    &r.kinematics(black_box(q), black_box(qd), black_box(qdd))
                        .unwrap(),
                    black_box(&rloads)
                )
                .unwrap(),
            |[q, qd, qdd]| g
                .kinetostatics(
                    &g.kinematics(black_box(q), black_box(qd), black_box(qdd))
                        .unwrap(),
                    black_box(&gloads)
                )
                .unwrap()
        );
        // The run-time mechanism with caller-owned buffers (no allocation per call).
        {
            let [q, qd, qdd] = &configs[0];
            let mut mo = r.kinematics(q, qd, qdd).unwrap();
            let mut fo = r.kinetostatics(&mo, &rloads).unwrap();
            let (mut i, n) = (0, configs.len());
            grp.bench_function("kinematics+kinetostatics/runtime_buffers", |b| {
                b.iter(|| {
                    i = (i + 1) % n;
                    let [q, qd, qdd] = &configs[i];
                    r.kinematics_into(black_box(q), black_box(qd), black_box(qdd), &mut mo)
                        .unwrap();
                    r.kinetostatics_into(&mo, black_box(&rloads), None, &mut fo)
                        .unwrap();
                    fo.driver[0]
                })
            });
        }
        pair!(
            grp,
            "kinematics+driver_action",
            typed,
            configs,
            |(q, qd, qdd)| m
                .driver_action(
                    &m.kinematics(black_box(q), black_box(qd), black_box(qdd))
                        .unwrap(),
                    black_box(&loads)
                )
                .unwrap(),
            |[q, qd, qdd]| r
                .driver_action(
                    &r.kinematics(black_box(q), black_box(qd), black_box(qdd))
                        .unwrap(),
                    black_box(&rloads)
                )
                .unwrap(),
            |[q, qd, qdd]| g
                .driver_action(
                    &g.kinematics(black_box(q), black_box(qd), black_box(qdd))
                        .unwrap(),
                    black_box(&gloads)
                )
                .unwrap()
        );
        grp.finish();
    }};
}

fn generated_vs_generic(c: &mut Criterion) {
    bench_pair!(c, "four_bar", FourBar, FourBarLoads, |v: &Vec<f64>| v[0]);
    bench_pair!(
        c,
        "slider_crank",
        SliderCrank,
        SliderCrankLoads,
        |v: &Vec<f64>| v[0]
    );
    bench_pair!(c, "watt2", Watt2, Watt2Loads, |v: &Vec<f64>| v[0]);
    bench_pair!(c, "five_bar", FiveBar, FiveBarLoads, |v: &Vec<f64>| [
        v[0], v[1]
    ]);
}

criterion_group!(benches, generated_vs_generic);
criterion_main!(benches);
