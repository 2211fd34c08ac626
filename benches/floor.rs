//! The floor: the generated solvers against expert hand-written closed-form code of the
//! same machines (`benches/floor/hand.rs`), timed in the same run so that the ratio
//! generated / hand is meaningful. `tests/floor.rs` proves that both compute the same
//! numbers (1e-12 relative on a sweep of a full turn).
//!
//! Groups (each with the functions `generated` and `hand`):
//! `four_bar/pose`, `four_bar/kinematics`, `four_bar/kinematics+kinetostatics`,
//! `four_bar/kinematics+driver_action`, `slider_crank/reduced`,
//! `slider_crank/acceleration`. Inputs as in `benches/solvers.rs`: q = 0.7, q̇ = 12,
//! q̈ = −3; the four-bar carries the tool force (80, −60) N at P and a 2 N·m resisting
//! torque on the rocker; the slider-crank a −1500 N gas force on the piston at B, a
//! −4 N·m shaft torque and a 5 N·m driver (acceleration). All inputs, and the
//! solver struct itself, go through `black_box` (no constant folding of the drawing).
//!
//! Run and tabulate:
//!
//! ```text
//! export CARGO_TARGET_DIR=...                     # the same for both commands
//! cargo bench --bench floor -- --warm-up-time 1 --measurement-time 3
//! python3 tools/floor_ratios.py                   # markdown table of medians and ratios
//! ```
//!
//! Counting instructions per call (deterministic, insensitive to the load of a shared
//! machine) with callgrind: run one benchmark in criterion's profiling mode (no analysis,
//! no output files) under valgrind, then divide the instructions spent under criterion's
//! timing loop by the number of iterations.
//!
//! ```text
//! cargo bench --bench floor --no-run        # prints "Executable ... (target/release/deps/floor-<hash>)"
//! BIN=$(ls -t $CARGO_TARGET_DIR/release/deps/floor-* | grep -v '\.d$' | head -1)
//! valgrind --tool=callgrind --callgrind-out-file=cg.out \
//!     $BIN --bench --profile-time 1 '^four_bar/kinematics/hand$'
//! callgrind_annotate --inclusive=yes --tree=caller cg.out | grep -A1 'Bencher<M>::iter'
//! ```
//!
//! The filter is a regex on `group/function` (escape the `+` of `kinematics\+kinetostatics`).
//! In the `--tree=caller` listing, the line `N (..%) * ...Bencher<M>::iter` is the
//! inclusive count of the timing loop, and the solver it calls appears with
//! `< ...Bencher<M>::iter (Kx)`, K = the number of iterations: instructions per call
//! = N / K (criterion's loop and `black_box` add a handful). One awk line does it:
//!
//! ```text
//! callgrind_annotate --inclusive=yes --tree=caller cg.out | awk \
//!   '/\* .*Bencher<M>::iter/{gsub(",","",$1); n=$1}
//!    /< .*Bencher<M>::iter \(/{c=$0; sub(/.*\(/,"",c); sub(/x\).*/,"",c); gsub(",","",c); k=c}
//!    END{printf "%.0f instructions per call\n", n/k}'
//! ```
//!
//! Valgrind runs the code ~50× slower, so `--profile-time 1` is a few hundred thousand
//! iterations, plenty for a stable count.

#[path = "../tests/common/mechanisms.rs"]
#[allow(dead_code)]
mod mechanisms;

#[path = "floor/hand.rs"]
mod hand;

use criterion::{black_box, criterion_group, criterion_main, Criterion};
use hand::{FourBarHand, SliderCrankHand};
use mechanisms::*;

const Q: f64 = 0.7;
const QD: f64 = 12.0;
const QDD: f64 = -3.0;

fn four_bar(c: &mut Criterion) {
    let m = FourBar::new();
    let h = FourBarHand::new(m.params());
    let mut loads = FourBarLoads::default();
    assert!(loads.set_by_name("tool", &[80.0, -60.0]));
    assert!(loads.set_by_name("resist", &[2.0]));

    let mut g = c.benchmark_group("four_bar/pose");
    g.bench_function("generated", |b| {
        b.iter(|| black_box(&m).pose(black_box(Q)).unwrap())
    });
    g.bench_function("hand", |b| {
        b.iter(|| black_box(&h).pose(black_box(Q)).unwrap())
    });
    g.finish();

    let mut g = c.benchmark_group("four_bar/kinematics");
    g.bench_function("generated", |b| {
        b.iter(|| {
            black_box(&m)
                .kinematics(black_box(Q), black_box(QD), black_box(QDD))
                .unwrap()
        })
    });
    g.bench_function("hand", |b| {
        b.iter(|| {
            black_box(&h)
                .kinematics(black_box(Q), black_box(QD), black_box(QDD))
                .unwrap()
        })
    });
    g.finish();

    let mut g = c.benchmark_group("four_bar/kinematics+kinetostatics");
    g.bench_function("generated", |b| {
        b.iter(|| {
            let s = black_box(&m);
            let mo = s
                .kinematics(black_box(Q), black_box(QD), black_box(QDD))
                .unwrap();
            s.kinetostatics(&mo, black_box(&loads)).unwrap()
        })
    });
    g.bench_function("hand", |b| {
        b.iter(|| {
            let s = black_box(&h);
            let mo = s
                .kinematics(black_box(Q), black_box(QD), black_box(QDD))
                .unwrap();
            s.kinetostatics(&mo, black_box(&loads))
        })
    });
    g.finish();

    let mut g = c.benchmark_group("four_bar/kinematics+driver_action");
    g.bench_function("generated", |b| {
        b.iter(|| {
            let s = black_box(&m);
            let mo = s
                .kinematics(black_box(Q), black_box(QD), black_box(QDD))
                .unwrap();
            s.driver_action(&mo, black_box(&loads)).unwrap()
        })
    });
    g.bench_function("hand", |b| {
        b.iter(|| {
            let s = black_box(&h);
            let mo = s
                .kinematics(black_box(Q), black_box(QD), black_box(QDD))
                .unwrap();
            s.driver_action(&mo, black_box(&loads))
        })
    });
    g.finish();
}

fn slider_crank(c: &mut Criterion) {
    let m = SliderCrank::new();
    let h = SliderCrankHand::new(m.params());
    let mut loads = SliderCrankLoads::default();
    assert!(loads.set_by_name("gas", &[-1500.0, 0.0]));
    assert!(loads.set_by_name("shaft", &[-4.0]));
    let driver = 5.0;

    let mut g = c.benchmark_group("slider_crank/reduced");
    g.bench_function("generated", |b| {
        b.iter(|| black_box(&m).reduced(black_box(Q)).unwrap())
    });
    g.bench_function("hand", |b| {
        b.iter(|| black_box(&h).reduced(black_box(Q)).unwrap())
    });
    g.finish();

    let mut g = c.benchmark_group("slider_crank/acceleration");
    g.bench_function("generated", |b| {
        b.iter(|| {
            black_box(&m)
                .acceleration(
                    black_box(Q),
                    black_box(QD),
                    black_box(driver),
                    black_box(&loads),
                )
                .unwrap()
        })
    });
    g.bench_function("hand", |b| {
        b.iter(|| {
            black_box(&h)
                .acceleration(
                    black_box(Q),
                    black_box(QD),
                    black_box(driver),
                    black_box(&loads),
                )
                .unwrap()
        })
    });
    g.finish();
}

criterion_group!(benches, four_bar, slider_crank);
criterion_main!(benches);
