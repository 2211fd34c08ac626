//! The pose of a triad machine against a dyad chain of as many links (issue 35): pyslvs's
//! Stephenson III six-bar (`examples/mech/stephenson_iii.mech`, mm scaled to m: a crank,
//! then one triad — a ternary link pinned to three binary links), the Stephenson chain
//! on the binary link of its two-binary path driven by a ternary crank (`Stephenson2`
//! here: a triad again, two of its outer pins on the crank), and the Watt II six-bar of
//! `tests/common/mechanisms.rs` (a crank and two RRR dyads). Each call is `pose` at the
//! next of 64 crank angles over a full turn, so that the count is the mean over a turn
//! (a triad's Newton starts from the drawing, and its cost grows with the distance).
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

use criterion::{black_box, criterion_group, criterion_main, Criterion};
use mech::mechanism;
use mechanisms::Watt2;

mechanism! {
    /// pyslvs's Stephenson III (examples/mech/stephenson_iii.mech), mm scaled to m.
    pub struct StephensonIII {
        ground { P0: (0.00025, -0.000625), P4: (0.117125, 0.023375), P6: (0.138875, 0.033125) },
        link L1 { points { P0, P1: (0.015375, 0.041125) } },
        link L2 { points { P1, P2: (0.061375, 0.095125) } },
        link L3 { points { P2, P3: (0.102875, 0.084375), P5: (0.134625, 0.119875) } },
        link L4 { points { P3, P4 } },
        link L5 { points { P5, P6 } },
        joints {
            J0: revolute(ground, L1) at P0,
            J1: revolute(L1, L2) at P1,
            J2: revolute(L2, L3) at P2,
            J3: revolute(L3, L4) at P3,
            J4: revolute(ground, L4) at P4,
            J5: revolute(L3, L5) at P5,
            J6: revolute(ground, L5) at P6,
        },
        input: J0,
    }
}

mechanism! {
    /// The Stephenson chain on the binary link of its two-binary path (O–G), driven by a
    /// ternary crank: the triad `tri` with l3 and l4 pinned to the crank, l2 to the ground.
    pub struct Stephenson2 {
        ground { O: (0.0, 0.0), G: (0.3, -0.05) },
        link crank { points { O, E: (0.03, 0.0), F: (-0.01, 0.03) } },
        link l3 { points { E, K: (0.15, 0.15) } },
        link l4 { points { F, M: (0.1, 0.22) } },
        link tri { points { K, M, H: (0.27, 0.2) } },
        link l2 { points { G, H } },
        joints {
            O: revolute(ground, crank),
            E: revolute(crank, l3),
            K: revolute(l3, tri),
            F: revolute(crank, l4),
            M: revolute(l4, tri),
            H: revolute(tri, l2),
            G: revolute(ground, l2),
        },
        input: O,
    }
}

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

fn triad(c: &mut Criterion) {
    let mut g = c.benchmark_group("triad");
    bench_pose!(g, "pose/stephenson3", StephensonIII);
    bench_pose!(g, "pose/stephenson2", Stephenson2);
    bench_pose!(g, "pose/watt2", Watt2);
    g.finish();
}

criterion_group!(benches, triad);
criterion_main!(benches);
