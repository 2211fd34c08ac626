//! Accuracy against run time, for every solver path:
//!
//! - generated closed form (most of the example mechanisms),
//! - generated Newton fallback (the Assur groups with no closed form: the hydraulic
//!   lever's three-link group, the scotch yoke's yoke),
//! - generic run-time solver (one global system, Newton with continuation),
//!
//! each against the 50-digit reference tables of `tests/data/*.truth.json`, with the time
//! per call of `kinematics + kinetostatics`; then, for the generic position analysis, the
//! Newton tolerance against the error and the time per `pose` call.
//!
//! Errors are relative to the largest entry of the same kind in the configuration
//! (`docs/conventions.md#solver-requirements`): "kinematics" is the worst of positions,
//! velocities, accelerations, ω, α (angles absolute, rad); "forces" the worst of
//! reactions, motor actions (d'Alembert and virtual power) and, for one DOF, I*, dI*/dq,
//! M*. The worst over the twelve reference configurations is shown.
//!
//! Run: `cargo run --release --example accuracy_report` (a markdown report on stdout).

#[path = "../tests/common/mechanisms.rs"]
mod mechanisms;
#[path = "../tests/support/mod.rs"]
mod support;
// `support`'s comparisons go through the tests' tolerance check.
#[path = "../tests/common/measure.rs"]
mod measure;

use mech::prelude::*;
use mech_core::kernel::dyad::Solver;
use mech_core::plan::assur::plan;
use mech_oracle::{GenericMechanism, GenericMotion};
use mechanisms::*;
use serde_json::Value;
use std::hint::black_box;
use std::time::Instant;
use support::{as_vec, nums, truth};

const SOURCE: &str = include_str!("../tests/common/mechanisms.rs");

/// One solver's answer at one configuration, by name.
struct Answer {
    links: Vec<(String, LinkMotion)>,
    points: Vec<(String, PointMotion)>,
    reactions: Vec<(String, Vector2<f64>, Option<f64>)>,
    drivers: Vec<f64>,
    virtual_power: Vec<f64>,
    /// I*, dI*/dq, M* (one DOF).
    zhukovski: Option<[f64; 3]>,
}

fn generic_answer(
    g: &GenericMechanism,
    m: &GenericMotion,
    loads: &mech_oracle::GenericLoads,
) -> Answer {
    let model = g.model();
    let f = g.kinetostatics(m, loads).unwrap();
    Answer {
        links: model
            .links
            .iter()
            .zip(&m.links)
            .skip(1)
            .map(|(l, lm)| (l.name.clone(), *lm))
            .collect(),
        points: model
            .points
            .iter()
            .zip(&m.points)
            .map(|(p, pm)| (p.name.clone(), *pm))
            .collect(),
        reactions: model
            .joints
            .iter()
            .zip(&f.joints)
            .map(|(j, r)| (j.name.clone(), r.force, r.moment))
            .collect(),
        drivers: f.driver.clone(),
        virtual_power: g.driver_action(m, loads).unwrap(),
        zhukovski: (g.dof() == 1).then(|| {
            let r = g.reduced(m.q[0]).unwrap();
            [
                r.inertia,
                r.inertia_derivative,
                g.reduced_moment(m.q[0], loads).unwrap(),
            ]
        }),
    }
}

/// Worst relative errors (kinematics, forces) of an answer against one truth configuration.
fn errors(a: &Answer, c: &Value) -> (f64, f64) {
    let max_of = |f: &dyn Fn(&Value) -> Vec<f64>| {
        let mut m = 0.0f64;
        for (_, l) in c["links"].as_object().unwrap() {
            for v in f(l) {
                m = m.max(v.abs());
            }
        }
        m
    };
    let vecs = |l: &Value, key: &str| -> Vec<f64> {
        let mut v = nums(&l["cg"][key]);
        for (_, p) in l["points"].as_object().unwrap() {
            v.extend(nums(&p[key]));
        }
        v
    };
    let (pos, vel, acc) = (
        max_of(&|l| vecs(l, "pos")),
        max_of(&|l| vecs(l, "vel")),
        max_of(&|l| vecs(l, "acc")),
    );
    let (om, al) = (
        max_of(&|l| nums(&l["omega"])),
        max_of(&|l| nums(&l["alpha"])),
    );
    let rel = |got: f64, want: f64, scale: f64| (got - want).abs() / scale.max(1e-300);
    let relv = |got: Vector2<f64>, want: &Value, scale: f64| {
        let w = nums(want);
        rel(got.x, w[0], scale).max(rel(got.y, w[1], scale))
    };
    let mut kin = 0.0f64;
    for (name, lm) in &a.links {
        let t = &c["links"][name];
        let d = (lm.angle - t["theta"].as_f64().unwrap()).rem_euclid(std::f64::consts::TAU);
        kin = kin.max(d.min(std::f64::consts::TAU - d));
        kin = kin
            .max(rel(lm.omega, t["omega"].as_f64().unwrap(), om))
            .max(rel(lm.alpha, t["alpha"].as_f64().unwrap(), al));
        kin = kin
            .max(relv(lm.cg, &t["cg"]["pos"], pos))
            .max(relv(lm.cg_vel, &t["cg"]["vel"], vel))
            .max(relv(lm.cg_acc, &t["cg"]["acc"], acc));
        for (pname, pt) in t["points"].as_object().unwrap() {
            let pm = a.points.iter().find(|(n, _)| n == pname).unwrap().1;
            kin = kin
                .max(relv(pm.pos, &pt["pos"], pos))
                .max(relv(pm.vel, &pt["vel"], vel))
                .max(relv(pm.acc, &pt["acc"], acc));
        }
    }
    let drivers: Vec<f64> = c["drivers"]
        .as_array()
        .unwrap()
        .iter()
        .map(|d| d["value"].as_f64().unwrap())
        .collect();
    let mut fscale = drivers.iter().fold(0.0f64, |m, d| m.max(d.abs()));
    for (_, r) in c["reactions"].as_object().unwrap() {
        fscale = fscale.max(nums(&r["force"]).iter().fold(0.0f64, |m, x| m.max(x.abs())));
    }
    let mut force = 0.0f64;
    for (i, d) in drivers.iter().enumerate() {
        force = force
            .max(rel(a.drivers[i], *d, fscale))
            .max(rel(a.virtual_power[i], *d, fscale));
    }
    for (name, f, m) in &a.reactions {
        let t = &c["reactions"][name];
        force = force.max(relv(*f, &t["force"], fscale));
        if let (Some(m), Some(w)) = (m, t.get("moment")) {
            force = force.max(rel(*m, w.as_f64().unwrap(), fscale * pos));
        }
    }
    if let Some([i, di, ms]) = a.zhukovski {
        let z = &c["zhukovski"];
        let (ti, tdi, tms) = (
            z["I_star"].as_f64().unwrap(),
            z["dI_star_dq"].as_f64().unwrap(),
            z["M_star"].as_f64().unwrap(),
        );
        force = force
            .max(rel(i, ti, ti.abs()))
            .max(rel(di, tdi, ti.abs().max(tdi.abs())));
        force = force.max(rel(ms, tms, tms.abs().max(drivers[0].abs())));
    }
    (kin, force)
}

/// Median time per call (ns) of `f`, over batches of at least 50 ms.
fn ns_per_call(mut f: impl FnMut()) -> f64 {
    f();
    let mut n = 1u64;
    loop {
        let t = Instant::now();
        for _ in 0..n {
            f();
        }
        if t.elapsed().as_secs_f64() > 0.05 {
            break;
        }
        n *= 2;
    }
    let mut times: Vec<f64> = (0..5)
        .map(|_| {
            let t = Instant::now();
            for _ in 0..n {
                f();
            }
            t.elapsed().as_secs_f64() * 1e9 / n as f64
        })
        .collect();
    times.sort_by(f64::total_cmp);
    times[2]
}

struct Row {
    name: &'static str,
    path: &'static str,
    generated: (f64, f64),
    generic: (f64, f64),
    generated_ns: f64,
    generic_ns: f64,
}

macro_rules! report {
    ($file:literal, $ty:ident, $loads:ident, $to_q:expr) => {{
        let t = truth($file);
        let gen = $ty::new();
        let g = GenericMechanism::from_rust_source(SOURCE, stringify!($ty)).unwrap();
        let newton = plan(g.model())
            .unwrap()
            .iter()
            .any(|grp| grp.solver == Solver::Newton);
        let mut loads = $loads::default();
        let mut gl = g.loads();
        for (n, l) in t["loads"].as_object().unwrap() {
            assert!(
                loads.set_by_name(n, &nums(&l["value"])) && gl.set_by_name(n, &nums(&l["value"]))
            );
        }
        let to_q = $to_q;
        let configs: Vec<[Vec<f64>; 3]> = t["configs"]
            .as_array()
            .unwrap()
            .iter()
            .map(|c| [nums(&c["q"]), nums(&c["qd"]), nums(&c["qdd"])])
            .collect();
        let (mut e_gen, mut e_gnc) = ((0.0f64, 0.0f64), (0.0f64, 0.0f64));
        for (c, [q, qd, qdd]) in t["configs"].as_array().unwrap().iter().zip(&configs) {
            let mo = gen.kinematics(to_q(q), to_q(qd), to_q(qdd)).unwrap();
            let fs = gen.kinetostatics(&mo, &loads).unwrap();
            let a = Answer {
                links: g.model().links[1..]
                    .iter()
                    .map(|l| (l.name.clone(), *mo.link(&l.name).unwrap()))
                    .collect(),
                points: g
                    .model()
                    .points
                    .iter()
                    .map(|p| (p.name.clone(), *mo.point(&p.name).unwrap()))
                    .collect(),
                reactions: g
                    .model()
                    .joints
                    .iter()
                    .map(|j| {
                        let (f, m) = fs.reaction(&j.name).unwrap();
                        (j.name.clone(), f, m)
                    })
                    .collect(),
                drivers: as_vec(&fs.driver),
                virtual_power: as_vec(&gen.driver_action(&mo, &loads).unwrap()),
                zhukovski: gen.zhukovski(q[0], &loads),
            };
            let e = errors(&a, c);
            e_gen = (e_gen.0.max(e.0), e_gen.1.max(e.1));
            let gm = g.kinematics(q, qd, qdd).unwrap();
            let e = errors(&generic_answer(&g, &gm, &gl), c);
            e_gnc = (e_gnc.0.max(e.0), e_gnc.1.max(e.1));
        }
        let n = configs.len();
        let mut i = 0;
        let generated_ns = ns_per_call(|| {
            i = (i + 1) % n;
            let [q, qd, qdd] = &configs[i];
            let mo = gen
                .kinematics(
                    black_box(to_q(q)),
                    black_box(to_q(qd)),
                    black_box(to_q(qdd)),
                )
                .unwrap();
            black_box(gen.kinetostatics(&mo, &loads).unwrap());
        });
        let generic_ns = ns_per_call(|| {
            i = (i + 1) % n;
            let [q, qd, qdd] = &configs[i];
            let mo = g
                .kinematics(black_box(q), black_box(qd), black_box(qdd))
                .unwrap();
            black_box(g.kinetostatics(&mo, &gl).unwrap());
        });
        Row {
            name: $file,
            path: if newton {
                "Newton fallback"
            } else {
                "closed form"
            },
            generated: e_gen,
            generic: e_gnc,
            generated_ns,
            generic_ns,
        }
    }};
}

/// I*, dI*/dq, M* of a generated mechanism at q; `None` for several DOF.
trait ZhukovskiOrNot {
    type L;
    fn zhukovski(&self, q: f64, loads: &Self::L) -> Option<[f64; 3]>;
}
macro_rules! one_dof {
    ($($ty:ident: $loads:ident),*) => {$(
        impl ZhukovskiOrNot for $ty {
            type L = $loads;
            fn zhukovski(&self, q: f64, loads: &$loads) -> Option<[f64; 3]> {
                let r = self.reduced(q).unwrap();
                Some([r.inertia, r.inertia_derivative, self.reduced_moment(q, loads).unwrap()])
            }
        }
    )*};
}
one_dof!(
    PublicSliderCrank: PublicSliderCrankLoads, PublicFourBar: PublicFourBarLoads, FourBar: FourBarLoads,
    SliderCrank: SliderCrankLoads, QuickReturn: QuickReturnLoads, Watt2: Watt2Loads, Stephenson3: Stephenson3Loads,
    ScotchYoke: ScotchYokeLoads, HydraulicLever: HydraulicLeverLoads
);
impl ZhukovskiOrNot for FiveBar {
    type L = FiveBarLoads;
    fn zhukovski(&self, _: f64, _: &FiveBarLoads) -> Option<[f64; 3]> {
        None
    }
}

/// Newton tolerance against error and time of the generic position analysis.
fn tolerance_study(file: &str, ty: &str) {
    let t = truth(file);
    let configs: Vec<Vec<f64>> = t["configs"]
        .as_array()
        .unwrap()
        .iter()
        .map(|c| nums(&c["q"]))
        .collect();
    println!(
        "\n**{file}** (generic `pose`; L = {:.3} m)\n",
        GenericMechanism::from_rust_source(SOURCE, ty)
            .unwrap()
            .model()
            .scale()
    );
    println!("| Newton tolerance (× L) | worst position error (× L) | worst angle error (rad) | ns per `pose` |");
    println!("|---:|---:|---:|---:|");
    for tol in [1e-2, 1e-4, 1e-6, 1e-8, 1e-10, 1e-12, 1e-14, 1e-16] {
        let g = GenericMechanism::from_rust_source(SOURCE, ty)
            .unwrap()
            .with_tolerance(tol)
            .unwrap();
        let scale = g.model().scale();
        let (mut pos, mut ang) = (0.0f64, 0.0f64);
        for (q, c) in configs.iter().zip(t["configs"].as_array().unwrap()) {
            let p = g.pose(q).unwrap();
            for (lname, lt) in c["links"].as_object().unwrap() {
                let d = (p.link(lname).unwrap().angle - lt["theta"].as_f64().unwrap())
                    .rem_euclid(std::f64::consts::TAU);
                ang = ang.max(d.min(std::f64::consts::TAU - d));
                for (pname, pt) in lt["points"].as_object().unwrap() {
                    let w = nums(&pt["pos"]);
                    let got = p.point(pname).unwrap().pos;
                    pos = pos.max((got.x - w[0]).abs().max((got.y - w[1]).abs()) / scale);
                }
            }
        }
        let n = configs.len();
        let mut i = 0;
        let ns = ns_per_call(|| {
            i = (i + 1) % n;
            black_box(g.pose(black_box(&configs[i])).unwrap());
        });
        println!("| {tol:.0e} | {pos:.1e} | {ang:.1e} | {ns:.0} |");
    }
}

fn main() {
    let rows = vec![
        report!("four_bar", FourBar, FourBarLoads, |v: &Vec<f64>| v[0]),
        report!(
            "public_four_bar",
            PublicFourBar,
            PublicFourBarLoads,
            |v: &Vec<f64>| v[0]
        ),
        report!("slider_crank", SliderCrank, SliderCrankLoads, |v: &Vec<
            f64,
        >| v
            [0]),
        report!(
            "public_slider_crank",
            PublicSliderCrank,
            PublicSliderCrankLoads,
            |v: &Vec<f64>| v[0]
        ),
        report!("quick_return", QuickReturn, QuickReturnLoads, |v: &Vec<
            f64,
        >| v
            [0]),
        report!("watt2", Watt2, Watt2Loads, |v: &Vec<f64>| v[0]),
        report!("stephenson3", Stephenson3, Stephenson3Loads, |v: &Vec<
            f64,
        >| v
            [0]),
        report!("five_bar", FiveBar, FiveBarLoads, |v: &Vec<f64>| [
            v[0], v[1]
        ]),
        report!("scotch_yoke", ScotchYoke, ScotchYokeLoads, |v: &Vec<
            f64,
        >| v[0]),
        report!(
            "hydraulic_lever",
            HydraulicLever,
            HydraulicLeverLoads,
            |v: &Vec<f64>| v[0]
        ),
    ];
    println!("## Accuracy against the 50-digit reference, and time per call\n");
    println!("Worst relative error over the 12 reference configurations; time per `kinematics + kinetostatics` call (median of 5 batches).\n");
    println!("| mechanism | generated path | generated: kinematics | generated: forces | generic: kinematics | generic: forces | generated ns | generic ns | generic / generated |");
    println!("|---|---|---:|---:|---:|---:|---:|---:|---:|");
    for r in &rows {
        println!(
            "| {} | {} | {:.1e} | {:.1e} | {:.1e} | {:.1e} | {:.0} | {:.0} | {:.0}× |",
            r.name,
            r.path,
            r.generated.0,
            r.generated.1,
            r.generic.0,
            r.generic.1,
            r.generated_ns,
            r.generic_ns,
            r.generic_ns / r.generated_ns
        );
    }
    println!("\n## Generic position analysis: Newton tolerance against error and time");
    tolerance_study("four_bar", "FourBar");
    tolerance_study("watt2", "Watt2");
    tolerance_study("hydraulic_lever", "HydraulicLever");
}
