//! The RSSR's pose by its closed form against the Newton path (issue 33): the mechanism of
//! `examples/mech/rssr.mech` loaded at run time, each call `pose` at the next of 64 crank
//! angles over a full turn (the Newton path is continued from the drawing, so its cost
//! grows with the distance: the count is the mean over a turn).
//!
//! - `spatial_rssr/closed`: `SpatialMechanism::pose`, the closed form recognised at load
//!   time (`mech_core::spatial::closed`) giving every body's pose;
//! - `spatial_rssr/newton`: the same call with the positions by Newton
//!   (`mech_core::spatial::kinematics::newton_only`);
//! - `spatial_rssr/kernel`: the kernel alone, `Rssr::points` (the pins and the rocker's
//!   angle, no allocation).
//!
//! ```text
//! cargo bench --bench spatial
//! ```

use criterion::{black_box, criterion_group, criterion_main, Criterion};
use mech_core::spatial::closed::Rssr;
use mech_core::spatial::kinematics::newton_only;
use mech_core::spatial::{JointKind, SpatialMechanism};

/// 64 crank angles over a full turn.
fn angles() -> [f64; 64] {
    std::array::from_fn(|k| std::f64::consts::TAU * k as f64 / 64.0)
}

fn rssr(c: &mut Criterion) {
    let m = SpatialMechanism::from_dsl(include_str!("../examples/mech/rssr.mech")).unwrap();
    assert_eq!(m.pose(&[0.5]).unwrap().closed_group(), Some("RSSR"));
    // the example's geometry: the crank about its axis through O, pin A; the rocker about
    // its axis through C, pin B
    let model = m.model();
    let point = |n: &str| model.points[model.point_index(n).unwrap()].1;
    let axis = |n: &str| match model.joints[model.joint_index(n).unwrap()].kind {
        JointKind::Revolute { axis } => axis,
        _ => unreachable!("the example's O and C are revolutes"),
    };
    let kernel = Rssr::new(
        point("O"),
        axis("O"),
        point("A"),
        point("C"),
        axis("C"),
        point("B"),
    )
    .unwrap();
    let qs = angles();
    let mut g = c.benchmark_group("spatial_rssr");
    let mut k = 0;
    g.bench_function("closed", |b| {
        b.iter(|| {
            k = (k + 1) & 63;
            m.pose(black_box(&[qs[k]])).unwrap()
        })
    });
    g.bench_function("newton", |b| {
        b.iter(|| {
            k = (k + 1) & 63;
            newton_only(|| m.pose(black_box(&[qs[k]])).unwrap())
        })
    });
    g.bench_function("kernel", |b| {
        b.iter(|| {
            k = (k + 1) & 63;
            black_box(&kernel).points(black_box(qs[k])).unwrap()
        })
    });
    g.finish();
}

criterion_group!(benches, rssr);
criterion_main!(benches);
