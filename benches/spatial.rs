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
//! And the generated struct against the run-time mechanism of the same declaration (one
//! run, interleaved): `spatial_generated/{kinematics,kinetostatics}_{generated,runtime}`
//! for the RSSR (closed-form positions) and `spatial_generated/fourbar_kinematics_*` for
//! the four-bar declared in space (R-S-U-R, positions by Newton): the generated struct
//! solves on its stack frame (`Fixed<N, 6(N − 1)>`, the fixed-size LU, no allocation), the
//! run-time one on the heap frame (nalgebra's LU, its `SpatialMotion`).
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

mech::mechanism! {
    /// examples/mech/rssr.mech
    pub struct Rssr3 {
        space,
        gravity: (0.0, 0.0, -9.81),
        ground { O: (0.0, 0.0, 0.0), C: (250 mm, 120 mm, 80 mm) },
        link crank { points { O, A: (0.0, 0.05, 0.0) }, mass: 1.0, cg: (0.01, 0.025, 0.004),
                     inertia: (1e-3, 4e-4, 9e-4, 1e-4, -2e-5, 5e-5) },
        link rod { points { A, B: (0.25, 0.02, 0.08) }, mass: 0.5, cg: (0.125, 0.035, 0.04),
                   inertia: (2e-4, 3e-3, 2.5e-3, 3e-5, 1e-5, -4e-5) },
        link rocker { points { C, B }, mass: 0.8, cg: (0.25, 0.07, 0.09),
                      inertia: (1.2e-3, 6e-4, 1.1e-3, 0.0, 2e-5, 0.0) },
        joints {
            O: revolute(ground, crank) axis (1.0, 0.0, 0.0),
            A: spherical(crank, rod),
            B: spherical(rod, rocker),
            C: revolute(ground, rocker) axis (0.0, 0.0, 1.0),
        },
        input: O,
        loads { tool: torque on rocker, push: force on rod at B },
    }
}

mech::mechanism! {
    /// A planar four-bar declared in space, R-S-U-R (positions by Newton).
    pub struct FourBar3 {
        space,
        gravity: (0.0, -9.81, 0.0),
        ground { O2: (0.0, 0.0, 0.0), O4: (0.3, 0.0, 0.0) },
        link crank { points { O2, A: (0.02, 0.06, 0.0) }, mass: 0.4, cg: (0.012, 0.03, 0.0), inertia: (1e-4, 3e-4, 2e-4, 5e-5, 0.0, 0.0) },
        link coupler { points { A, B: (0.25, 0.16, 0.0) }, mass: 1.1, cg: (0.14, 0.13, 0.0), inertia: (2e-3, 5e-3, 6e-3, -1e-3, 0.0, 0.0) },
        link rocker { points { B, O4 }, mass: 0.7, cg: (0.27, 0.07, 0.0), inertia: (2e-3, 4e-4, 2.5e-3, 3e-4, 0.0, 0.0) },
        joints {
            O2: revolute(ground, crank) axis (0.0, 0.0, 1.0),
            A: spherical(crank, coupler),
            B: universal(coupler, rocker) axes (0.0, 0.0, 1.0) (0.05, -0.16, 0.0),
            O4: revolute(rocker, ground) axis (0.0, 0.0, 1.0),
        },
        input: O2,
    }
}

fn generated(c: &mut Criterion) {
    use mech::Vector3;
    let (g, f) = (Rssr3::new(), FourBar3::new());
    let (rt, frt) = (g.mechanism().clone(), f.mechanism().clone());
    let loads = Rssr3Loads {
        tool: Vector3::new(0.3, -0.2, 1.7),
        push: Vector3::new(4.0, -3.0, 2.5),
    };
    let mut rl = rt.loads();
    rl.values = vec![loads.tool, loads.push];
    let qs = angles();
    let mut grp = c.benchmark_group("spatial_generated");
    let mut k = 0;
    grp.bench_function("kinematics_generated", |b| {
        b.iter(|| {
            k = (k + 1) & 63;
            g.kinematics(black_box(qs[k]), 3.0, -2.0).unwrap()
        })
    });
    grp.bench_function("kinematics_runtime", |b| {
        b.iter(|| {
            k = (k + 1) & 63;
            rt.kinematics(black_box(&[qs[k]]), &[3.0], &[-2.0]).unwrap()
        })
    });
    let gm: Vec<_> = qs
        .iter()
        .map(|&q| g.kinematics(q, 3.0, -2.0).unwrap())
        .collect();
    let rm: Vec<_> = qs
        .iter()
        .map(|&q| rt.kinematics(&[q], &[3.0], &[-2.0]).unwrap())
        .collect();
    grp.bench_function("kinetostatics_generated", |b| {
        b.iter(|| {
            k = (k + 1) & 63;
            g.kinetostatics(black_box(&gm[k]), &loads).unwrap()
        })
    });
    grp.bench_function("kinetostatics_runtime", |b| {
        b.iter(|| {
            k = (k + 1) & 63;
            rt.kinetostatics(black_box(&rm[k]), &rl).unwrap()
        })
    });
    // the four-bar near its drawing (one continuation step: the cost of Newton, not of the
    // distance from the drawing)
    grp.bench_function("fourbar_kinematics_generated", |b| {
        b.iter(|| {
            k = (k + 1) & 63;
            f.kinematics(black_box(0.2 * qs[k] / 6.3), 3.0, -2.0)
                .unwrap()
        })
    });
    grp.bench_function("fourbar_kinematics_runtime", |b| {
        b.iter(|| {
            k = (k + 1) & 63;
            frt.kinematics(black_box(&[0.2 * qs[k] / 6.3]), &[3.0], &[-2.0])
                .unwrap()
        })
    });
    grp.finish();
}

criterion_group!(benches, rssr, generated);
criterion_main!(benches);
