//! The pose of a triad machine against a dyad chain of as many links (issue 35): the two
//! triad machines of `tests/common/triads.rs` — pyslvs's Stephenson III six-bar
//! (`examples/mech/stephenson_iii.mech`, mm scaled to m: a crank, then one triad, a
//! ternary link pinned to three binary links) and the Stephenson chain on the binary link
//! of its two-binary path driven by a ternary crank (`Stephenson2` there: a triad again,
//! two of its outer pins on the crank) — and the Watt II six-bar of
//! `tests/common/mechanisms.rs` (a crank and two RRR dyads). Each call is `pose` at the
//! next of 64 crank angles over a full turn, so that the count is the mean over a turn
//! (a triad's Newton starts from the drawing, and its cost grows with the distance).
//!
//! The group `triad_ratio` measures each triad machine's `pose` against the Watt II's as
//! one ratio, the two alternated in blocks within every sample (`benches/floor/interleaved.rs`,
//! as the floor's `ratio` group): `triad_ratio/<machine>`, the figure the target (at most
//! 3×) is read on, free of the drift of a shared core between two criterion functions.
//!
//! The group `triad_sweep` times a sweep of the run-time `Mechanism` over the same 64
//! angles: the rows of `mech sweep` (each triad started from the previous configuration)
//! against 64 one-configuration calls (each from the drawing).
//!
//! Count instructions per call with callgrind, as in the header of `benches/floor.rs`:
//!
//! ```text
//! cargo bench --bench triad --no-run
//! BIN=$(ls -t $CARGO_TARGET_DIR/release/deps/triad-* | grep -v '\.d$' | head -1)
//! valgrind --tool=callgrind --callgrind-out-file=cg.out $BIN --bench --profile-time 1 '^triad/pose/watt2$'
//! ```

#[path = "../tests/common/mechanisms.rs"]
#[allow(dead_code)]
mod mechanisms;

#[path = "../tests/common/triads.rs"]
mod triads;

#[path = "floor/interleaved.rs"]
mod interleaved;

use criterion::{black_box, criterion_group, criterion_main, Criterion};
use interleaved::Interleaved;
use mechanisms::Watt2;
use triads::{Stephenson2, StephensonIII};

/// 64 crank angles over a full turn.
fn angles() -> [f64; 64] {
    std::array::from_fn(|k| std::f64::consts::TAU * k as f64 / 64.0)
}

macro_rules! bench_pose {
    ($g:ident, $name:literal, $ty:ident) => {{
        let m = black_box($ty::new());
        let qs = angles();
        let mut k = 0;
        $g.bench_function($name, |b| {
            b.iter(|| {
                k = (k + 1) & 63;
                m.pose(black_box(qs[k])).unwrap()
            })
        });
    }};
}

/// A sweep of the run-time `Mechanism` over the 64 angles: the rows of `mech sweep`
/// (`Columns::rows_many` of the inputs and points: each triad starts from the previous
/// angle's configuration, `mech_core::runtime::warm`) against 64 calls of `points_into`
/// (each from the drawing): `triad_sweep/<machine>/warm` and `.../cold`, per sweep of 64
/// configurations.
fn sweep(c: &mut Criterion) {
    use mech::columns::{Columns, Part};
    const SOURCE: &str = include_str!("../tests/common/triads.rs");
    let mut g = c.benchmark_group("triad_sweep");
    for (name, ty) in [
        ("stephenson3", "StephensonIII"),
        ("stephenson2", "Stephenson2"),
    ] {
        let r = mech::Mechanism::from_rust_source(SOURCE, ty).unwrap();
        let q = angles().to_vec();
        let zero = vec![0.0; q.len()];
        let np = r.model().points.len();
        let cols = Columns::new(&r, &[Part::Inputs, Part::Points]);
        let loads = r.loads();
        let mut rows = vec![0.0; cols.names.len() * q.len()];
        g.bench_function(format!("{name}/warm"), |b| {
            b.iter(|| {
                let l = |_| std::borrow::Cow::Borrowed(&loads);
                let e = cols.rows_many(black_box(&r), black_box(&q), &zero, &zero, &l, &mut rows);
                assert!(e.is_empty());
            })
        });
        let mut out = vec![0.0; 2 * np * q.len()];
        let mut s = Vec::new();
        g.bench_function(format!("{name}/cold"), |b| {
            b.iter(|| {
                for (i, qi) in black_box(&q).iter().enumerate() {
                    let row = &mut out[2 * np * i..2 * np * (i + 1)];
                    black_box(&r).points_into(&[*qi], &mut s, row).unwrap();
                }
            })
        });
    }
    g.finish();
}

fn triad(c: &mut Criterion) {
    let mut g = c.benchmark_group("triad");
    bench_pose!(g, "pose/stephenson3", StephensonIII);
    bench_pose!(g, "pose/stephenson2", Stephenson2);
    bench_pose!(g, "pose/watt2", Watt2);
    g.finish();
}

/// `pose` at the next of the 64 angles, each call: the closure the pose entries time.
fn poses<M, R>(m: M, pose: impl Fn(&M, f64) -> R) -> impl FnMut() -> R {
    let (qs, mut k) = (angles(), 0);
    move || {
        k = (k + 1) & 63;
        pose(black_box(&m), black_box(qs[k]))
    }
}

/// `triad_ratio/<machine>`: the triad machine's `pose` over the Watt II's, interleaved.
fn triad_ratios(c: &mut Criterion<Interleaved>) {
    let mut g = c.benchmark_group("triad_ratio");
    g.bench_function("stephenson3", |b| {
        let mut triad = poses(StephensonIII::new(), |m, q| m.pose(q).unwrap());
        let mut watt = poses(Watt2::new(), |m, q| m.pose(q).unwrap());
        b.iter_custom(|n| interleaved::ratio(n, &mut triad, &mut watt))
    });
    g.bench_function("stephenson2", |b| {
        let mut triad = poses(Stephenson2::new(), |m, q| m.pose(q).unwrap());
        let mut watt = poses(Watt2::new(), |m, q| m.pose(q).unwrap());
        b.iter_custom(|n| interleaved::ratio(n, &mut triad, &mut watt))
    });
    g.finish();
}

criterion_group!(benches, triad, sweep);
criterion_group! {
    name = ratios;
    config = Criterion::default().with_measurement(Interleaved);
    targets = triad_ratios
}
criterion_main!(benches, ratios);
