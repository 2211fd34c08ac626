//! The generated solvers of the crank-rocker four-bar and the Watt II six-bar: `pose`,
//! `kinematics`, and the two routes to the motor torque — `kinematics + kinetostatics`
//! (d'Alembert, every reaction) against `kinematics + driver_action` (virtual power, no
//! reaction) — measured in one run so their ratio is meaningful.

#[path = "../tests/common/mechanisms.rs"]
mod mechanisms;

use criterion::{black_box, criterion_group, criterion_main, Criterion};
use mechanisms::*;

macro_rules! bench_mechanism {
    ($c:ident, $name:literal, $ty:ident, $loads:ident, $force:literal, $torque:literal) => {{
        let m = $ty::new();
        let mut loads = $loads::default();
        assert!(
            loads.set_by_name($force, &[80.0, -60.0]),
            "no force load {}",
            $force
        );
        assert!(
            loads.set_by_name($torque, &[2.0]),
            "no torque load {}",
            $torque
        );
        let mut g = $c.benchmark_group($name);
        g.bench_function("pose", |b| b.iter(|| m.pose(black_box(0.7)).unwrap()));
        g.bench_function("kinematics", |b| {
            b.iter(|| {
                m.kinematics(black_box(0.7), black_box(12.0), black_box(-3.0))
                    .unwrap()
            })
        });
        g.bench_function("kinematics+kinetostatics", |b| {
            b.iter(|| {
                let mo = m
                    .kinematics(black_box(0.7), black_box(12.0), black_box(-3.0))
                    .unwrap();
                m.kinetostatics(&mo, black_box(&loads)).unwrap()
            })
        });
        g.bench_function("kinematics+driver_action", |b| {
            b.iter(|| {
                let mo = m
                    .kinematics(black_box(0.7), black_box(12.0), black_box(-3.0))
                    .unwrap();
                m.driver_action(&mo, black_box(&loads)).unwrap()
            })
        });
        g.finish();
    }};
}

fn solvers(c: &mut Criterion) {
    bench_mechanism!(c, "four_bar", FourBar, FourBarLoads, "tool", "resist");
    bench_mechanism!(c, "watt2", Watt2, Watt2Loads, "output", "resist");
}

criterion_group!(benches, solvers);
criterion_main!(benches);
