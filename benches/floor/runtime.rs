//! The run-time side of the floor: the run-time `mech::Mechanism`, loaded from the very
//! text the macro compiled (`tests/common/mechanisms.rs`, `benches/floor/machines.rs`),
//! against the generated struct, on the floor's machines and all six operations, with
//! the floor's inputs and loads. The run-time side uses its caller-buffer forms, no
//! allocation per call: `pose_into`, `kinematics_into`, `kinetostatics_into`,
//! `Machine::driver_actions` into a slice, and Zhukovski's `reduced` and `acceleration`.
//!
//! - `runtime/<machine>/<op>`, the functions `generated` and `runtime`, timed one after the
//!   other (and the functions to count instructions on: the recipe in the header of
//!   `benches/floor.rs`, e.g. the filter `'^runtime/four_bar/kinematics/runtime$'`);
//! - `runtime_ratio/<machine>/<op>`: run-time / generated measured interleaved
//!   (`interleaved::ratio`, the run-time side in the numerator).
//!
//! ```text
//! cargo bench --bench floor -- '^runtime_ratio/'   # the interleaved ratios alone
//! ```
//!
//! `tests/floor_runtime.rs` proves that both sides compute the same numbers over a turn.

use super::interleaved::{self, Interleaved};
use super::{Case, FourBarCase, SliderCrankCase, Q, QD, QDD};
use criterion::measurement::Measurement;
use criterion::{black_box, Criterion};
use mech::prelude::*;
use mech::{Forces, Loads, Mechanism, Motion, Pose};

/// The source texts the macro compiled.
const REFERENCE: &str = include_str!("../../tests/common/mechanisms.rs");
const FLOOR: &str = include_str!("machines.rs");

/// The driver torque of `acceleration` (N·m), as the floor's.
const DRIVER: f64 = 5.0;

/// A run-time mechanism with its loads and its caller-owned buffers.
pub struct Runtime {
    m: Mechanism,
    loads: Loads,
    pose: Pose,
    motion: Motion,
    forces: Forces,
}

impl Runtime {
    /// The mechanism `name` of `source`, its loads set by name.
    fn new(source: &str, name: &str, loads: &[(&str, &[f64])]) -> Self {
        let m = Mechanism::from_rust_source(source, name).unwrap();
        let mut l = m.loads();
        for (n, v) in loads {
            assert!(l.set_by_name(n, v), "{name}: load {n}");
        }
        let pose = m.pose(&[Q]).unwrap();
        let motion = m.kinematics(&[Q], &[QD], &[QDD]).unwrap();
        let forces = m.kinetostatics(&motion, &l).unwrap();
        Runtime {
            m,
            loads: l,
            pose,
            motion,
            forces,
        }
    }
}

// The run-time side of each operation; every input through `black_box`.

fn rt_pose(r: &mut Runtime) {
    black_box(&r.m)
        .pose_into(&[black_box(Q)], &mut r.pose)
        .unwrap();
}
fn rt_kin(r: &mut Runtime) {
    black_box(&r.m)
        .kinematics_into(
            &[black_box(Q)],
            &[black_box(QD)],
            &[black_box(QDD)],
            &mut r.motion,
        )
        .unwrap();
}
fn rt_kinetostatics(r: &mut Runtime) {
    rt_kin(r);
    black_box(&r.m)
        .kinetostatics_into(&r.motion, black_box(&r.loads), None, &mut r.forces)
        .unwrap();
}
fn rt_driver(r: &mut Runtime) -> f64 {
    rt_kin(r);
    let mut d = [0.0];
    black_box(&r.m)
        .driver_actions(&r.motion, black_box(&r.loads), &mut d)
        .unwrap();
    d[0]
}
fn rt_reduced(r: &mut Runtime) -> mech::Reduced {
    black_box(&r.m).reduced(black_box(Q)).unwrap()
}
fn rt_acceleration(r: &mut Runtime) -> f64 {
    black_box(&r.m)
        .acceleration(
            black_box(Q),
            black_box(QD),
            black_box(DRIVER),
            black_box(&r.loads),
        )
        .unwrap()
}

/// The six operations of one machine: the generated side on `$case.m` and `$case.loads`
/// (every input through `black_box`), the run-time side above; the groups
/// `runtime/$name/<op>` (`pairs`) and the entries `runtime_ratio/$name/<op>` (`ratios`).
macro_rules! runtime_machine {
    ($module:ident, $name:literal, $case:expr, $source:expr, $ty:literal, loads: $loads:expr) => {
        mod $module {
            use super::*;

            fn runtime() -> Runtime {
                Runtime::new($source, $ty, $loads)
            }

            /// Calls `$f!(op name, generated closure, run-time function)` for each operation.
            macro_rules! each_op {
                ($f:ident, $c:expr, $k:expr, $r:expr) => {{
                    let k = $k;
                    $f!(
                        $c,
                        "pose",
                        || black_box(&k.m).pose(black_box(Q)).unwrap(),
                        rt_pose,
                        $r
                    );
                    $f!(
                        $c,
                        "kinematics",
                        || black_box(&k.m)
                            .kinematics(black_box(Q), black_box(QD), black_box(QDD))
                            .unwrap(),
                        rt_kin,
                        $r
                    );
                    $f!(
                        $c,
                        "kinematics+kinetostatics",
                        || {
                            let mo = black_box(&k.m)
                                .kinematics(black_box(Q), black_box(QD), black_box(QDD))
                                .unwrap();
                            black_box(&k.m)
                                .kinetostatics(&mo, black_box(&k.loads))
                                .unwrap()
                        },
                        rt_kinetostatics,
                        $r
                    );
                    $f!(
                        $c,
                        "kinematics+driver_action",
                        || {
                            let mo = black_box(&k.m)
                                .kinematics(black_box(Q), black_box(QD), black_box(QDD))
                                .unwrap();
                            black_box(&k.m)
                                .driver_action(&mo, black_box(&k.loads))
                                .unwrap()
                        },
                        rt_driver,
                        $r
                    );
                    $f!(
                        $c,
                        "reduced",
                        || black_box(&k.m).reduced(black_box(Q)).unwrap(),
                        rt_reduced,
                        $r
                    );
                    $f!(
                        $c,
                        "acceleration",
                        || black_box(&k.m)
                            .acceleration(
                                black_box(Q),
                                black_box(QD),
                                black_box(DRIVER),
                                black_box(&k.loads),
                            )
                            .unwrap(),
                        rt_acceleration,
                        $r
                    );
                }};
            }

            macro_rules! pair {
                ($c:expr, $op:literal, $gen:expr, $rt:ident, $r:expr) => {{
                    let r: &mut Runtime = $r;
                    let mut g = $c.benchmark_group(concat!("runtime/", $name, "/", $op));
                    g.bench_function("generated", |b| b.iter($gen));
                    g.bench_function("runtime", |b| b.iter(|| $rt(r)));
                    g.finish();
                }};
            }

            macro_rules! ratio {
                ($c:expr, $op:literal, $gen:expr, $rt:ident, $r:expr) => {{
                    let r: &mut Runtime = $r;
                    let mut gen = $gen;
                    $c.benchmark_group("runtime_ratio")
                        .bench_function(concat!($name, "/", $op), |b| {
                            b.iter_custom(|n| interleaved::ratio(n, || $rt(r), &mut gen))
                        });
                }};
            }

            /// The groups `runtime/$name/<op>`, generated then run-time.
            pub fn pairs(c: &mut Criterion) {
                let mut r = runtime();
                each_op!(pair, c, &$case, &mut r);
            }

            /// The entries `runtime_ratio/$name/<op>`, run-time / generated interleaved.
            pub fn ratios<M: Measurement<Value = f64>>(c: &mut Criterion<M>) {
                let mut r = runtime();
                each_op!(ratio, c, &$case, &mut r);
            }
        }
    };
}

runtime_machine!(
    four_bar,
    "four_bar",
    FourBarCase::new(),
    REFERENCE,
    "FourBar",
    loads: &[("tool", &[80.0, -60.0]), ("resist", &[2.0])]
);
runtime_machine!(
    slider_crank,
    "slider_crank",
    SliderCrankCase::new(),
    REFERENCE,
    "SliderCrank",
    loads: &[("gas", &[-1500.0, 0.0]), ("shaft", &[-4.0])]
);
runtime_machine!(
    quick_return,
    "quick_return",
    Case::quick_return(),
    REFERENCE,
    "QuickReturn",
    loads: &[("cut", &[-250.0, 30.0]), ("friction", &[-1.5])]
);
runtime_machine!(
    scotch_yoke,
    "scotch_yoke",
    Case::scotch_yoke(),
    REFERENCE,
    "ScotchYoke",
    loads: &[("resist", &[-120.0, 15.0]), ("drag", &[-1.5])]
);
runtime_machine!(
    inverted_slider_crank,
    "inverted_slider_crank",
    Case::inverted_slider_crank(),
    FLOOR,
    "InvertedSliderCrank",
    loads: &[("push", &[-300.0, 40.0]), ("resist", &[2.5])]
);
runtime_machine!(
    geared_slider_crank,
    "geared_slider_crank",
    Case::geared_slider_crank(),
    FLOOR,
    "GearedSliderCrank",
    loads: &[("gas", &[-900.0, -90.0]), ("shaft", &[-4.0])]
);
runtime_machine!(
    roller_cam,
    "roller_cam",
    Case::roller_cam(),
    FLOOR,
    "RollerCam",
    loads: &[("push", &[20.0, -250.0]), ("drag", &[-1.5])]
);
runtime_machine!(
    crank_rod_wheel,
    "crank_rod_wheel",
    Case::crank_rod_wheel(),
    FLOOR,
    "CrankRodWheel",
    loads: &[("pull", &[-150.0, 20.0]), ("brake", &[-0.8])]
);
runtime_machine!(
    block_scotch_yoke,
    "block_scotch_yoke",
    Case::block_scotch_yoke(),
    FLOOR,
    "BlockScotchYoke",
    loads: &[("resist", &[-150.0, 20.0]), ("friction", &[-0.6])]
);
runtime_machine!(
    slotted_crank_ram,
    "slotted_crank_ram",
    Case::slotted_crank_ram(),
    FLOOR,
    "SlottedCrankRam",
    loads: &[("push", &[-400.0, 60.0]), ("resist", &[1.8])]
);
runtime_machine!(
    planetary,
    "planetary",
    Case::planetary(),
    FLOOR,
    "Planetary",
    loads: &[("pull", &[40.0, -60.0]), ("brake", &[-2.0])]
);
runtime_machine!(
    rack_pinion,
    "rack_pinion",
    Case::rack_pinion(),
    FLOOR,
    "RackPinion",
    loads: &[("push", &[-250.0, 30.0]), ("resist", &[-2.0])]
);

/// The groups `runtime/<machine>/<op>`.
pub fn pairs(c: &mut Criterion) {
    four_bar::pairs(c);
    slider_crank::pairs(c);
    quick_return::pairs(c);
    scotch_yoke::pairs(c);
    inverted_slider_crank::pairs(c);
    geared_slider_crank::pairs(c);
    roller_cam::pairs(c);
    crank_rod_wheel::pairs(c);
    block_scotch_yoke::pairs(c);
    slotted_crank_ram::pairs(c);
    planetary::pairs(c);
    rack_pinion::pairs(c);
}

/// The entries `runtime_ratio/<machine>/<op>`.
pub fn ratios(c: &mut Criterion<Interleaved>) {
    four_bar::ratios(c);
    slider_crank::ratios(c);
    quick_return::ratios(c);
    scotch_yoke::ratios(c);
    inverted_slider_crank::ratios(c);
    geared_slider_crank::ratios(c);
    roller_cam::ratios(c);
    crank_rod_wheel::ratios(c);
    block_scotch_yoke::ratios(c);
    slotted_crank_ram::ratios(c);
    planetary::ratios(c);
    rack_pinion::ratios(c);
}
