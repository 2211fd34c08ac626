//! The cost of the machine elements, measured in one run next to the machine without them:
//! the slider-crank driven directly at its crank (`plain`), through a 25/75 gear pair
//! (`geared`: one more link, one meshing group), and directly with a return spring and a
//! damper on the piston (`sprung`). Each: `kinematics + kinetostatics` (every reaction,
//! the tooth force included) and `acceleration` (Zhukovski's right-hand side of the
//! direct problem). Same geometry, masses and loads; q = 0.7 rad, q̇ = 12, q̈ = −3 at the
//! crank (the geared input turns 3× as fast).
//!
//! `cargo bench --bench machine_elements -- --warm-up-time 1 --measurement-time 3`

use criterion::{black_box, criterion_group, criterion_main, Criterion};
use mech::prelude::*;

mechanism! {
    /// The slider-crank driven at its crank.
    pub struct Plain {
        gravity: (0.0, -9.81),
        ground { O2: (100 mm, 0.0) },
        link crank { points { O2, A: (140 mm, 0.0) }, mass: 1.5, inertia: 3.0e-3, cg: (105 mm, 5 mm) },
        link rod { points { A, B: (300 mm, 20 mm) }, mass: 0.9, inertia: 2.5e-3, cg: (220 mm, 12 mm) },
        link piston { points { B }, mass: 0.8, cg: (300 mm, 20 mm) },
        joints {
            O2: revolute(ground, crank),
            A: revolute(crank, rod),
            B: revolute(rod, piston),
            guide: prismatic(ground, piston) at B along (1.0, 0.0),
        },
        input: O2,
        loads { gas: force on piston at B },
    }
}

mechanism! {
    /// The same slider-crank driven through a gear pair.
    pub struct Geared {
        gravity: (0.0, -9.81),
        ground { O1: (0.0, 0.0), O2: (100 mm, 0.0) },
        link pinion { points { O1 }, mass: 0.3, inertia: 1.0e-4, cg: (0.0, 0.0) },
        link crank { points { O2, A: (140 mm, 0.0) }, mass: 1.5, inertia: 3.0e-3, cg: (105 mm, 5 mm) },
        link rod { points { A, B: (300 mm, 20 mm) }, mass: 0.9, inertia: 2.5e-3, cg: (220 mm, 12 mm) },
        link piston { points { B }, mass: 0.8, cg: (300 mm, 20 mm) },
        joints {
            O1: revolute(ground, pinion),
            O2: revolute(ground, crank),
            A: revolute(crank, rod),
            B: revolute(rod, piston),
            guide: prismatic(ground, piston) at B along (1.0, 0.0),
            mesh: gear(pinion, crank) radii (25 mm, 75 mm),
        },
        input: O1,
        loads { gas: force on piston at B },
    }
}

mechanism! {
    /// The same slider-crank with a return spring and a damper on the piston.
    pub struct Sprung {
        gravity: (0.0, -9.81),
        ground { O2: (100 mm, 0.0), S: (400 mm, 20 mm) },
        link crank { points { O2, A: (140 mm, 0.0) }, mass: 1.5, inertia: 3.0e-3, cg: (105 mm, 5 mm) },
        link rod { points { A, B: (300 mm, 20 mm) }, mass: 0.9, inertia: 2.5e-3, cg: (220 mm, 12 mm) },
        link piston { points { B }, mass: 0.8, cg: (300 mm, 20 mm) },
        joints {
            O2: revolute(ground, crank),
            A: revolute(crank, rod),
            B: revolute(rod, piston),
            guide: prismatic(ground, piston) at B along (1.0, 0.0),
        },
        input: O2,
        loads { gas: force on piston at B },
        elements {
            spring: spring(ground at S, piston at B) stiffness 5 kN_per_m free_length 150 mm,
            damper: damper(ground at S, piston at B) damping 30 N_s_per_m,
        },
    }
}

macro_rules! bench {
    ($c:ident, $name:literal, $ty:ident, $loads:ident, $k:expr) => {{
        let m = $ty::new();
        let loads = $loads {
            gas: mech::Vector2::new(-300.0, 0.0),
        };
        let (q, qd, qdd) = (0.7 * $k, 12.0 * $k, -3.0 * $k);
        let mut g = $c.benchmark_group(concat!("slider_crank/", $name));
        g.bench_function("kinematics+kinetostatics", |b| {
            b.iter(|| {
                let s = black_box(&m);
                let mo = s
                    .kinematics(black_box(q), black_box(qd), black_box(qdd))
                    .unwrap();
                s.kinetostatics(&mo, black_box(&loads)).unwrap()
            })
        });
        g.bench_function("acceleration", |b| {
            b.iter(|| {
                black_box(&m)
                    .acceleration(
                        black_box(q),
                        black_box(qd),
                        black_box(5.0),
                        black_box(&loads),
                    )
                    .unwrap()
            })
        });
        g.finish();
    }};
}

fn elements(c: &mut Criterion) {
    bench!(c, "plain", Plain, PlainLoads, 1.0);
    bench!(c, "geared", Geared, GearedLoads, -3.0);
    bench!(c, "sprung", Sprung, SprungLoads, 1.0);
}

criterion_group!(benches, elements);
criterion_main!(benches);
