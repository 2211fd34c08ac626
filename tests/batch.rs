//! Many configurations per call (`docs/batch.md`): on every reference mechanism, the
//! generated `*_many` and the run-time `Mechanism`'s equal their one-configuration solvers
//! configuration by configuration — the same numbers (to 1e-12 relative), NaN where the
//! solver fails, and the failed index with the solver's own error in `BatchErrors` — over
//! random configurations that include NaN inputs and ones that do not assemble; on the
//! calling thread and on rayon's pool; and slices of the wrong length are refused.

use crate::measure::within;
use crate::mechanisms::*;
use mech::batch::PARALLEL_FROM;
use mech::prelude::*;

const MECHANISMS: &str = include_str!("common/mechanisms.rs");

/// A small deterministic generator (xorshift64*), so that a failure names its inputs.
struct Rng(u64);
impl Rng {
    fn next(&mut self) -> f64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        (self.0.wrapping_mul(0x2545_F491_4F6C_DD1D) >> 11) as f64 / (1u64 << 53) as f64
    }
    /// Uniform in [lo, hi); one value in 23 is NaN (a configuration the batch must mask).
    fn input(&mut self, lo: f64, hi: f64) -> f64 {
        if self.next() < 1.0 / 23.0 {
            f64::NAN
        } else {
            lo + (hi - lo) * self.next()
        }
    }
}

/// `a` equals `b` to 1e-13 of `scale` (the largest magnitude of the quantity over the
/// batch, [`top`]: a coordinate or a rate that crosses zero is compared at its own scale),
/// NaN for NaN: within the 1e-12 relative the batched forms promise. The lane kernels order
/// their operations differently (measured worst 1.3e-15 of the scale, `MECH_MEASURE=1`);
/// the one-by-one route gives the same bits.
#[track_caller]
fn same(what: &str, i: usize, a: f64, b: f64, scale: f64) {
    let ok = (a.is_nan() && b.is_nan()) || within((a - b).abs(), 1e-13 * scale);
    assert!(
        ok,
        "{what}, configuration {i}: batched {a:e}, one by one {b:e} (scale {scale:e})"
    );
}

/// The largest finite magnitude of `v` (1 when there is none).
fn top(v: &[f64]) -> f64 {
    let m = v
        .iter()
        .filter(|x| x.is_finite())
        .fold(0.0f64, |m, x| m.max(x.abs()));
    if m > 0.0 {
        m
    } else {
        1.0
    }
}

/// What every one-input check needs: configurations q (with NaN and wide angles), rates and
/// driver torques.
struct Inputs {
    q: Vec<f64>,
    qd: Vec<f64>,
    qdd: Vec<f64>,
    driver: Vec<f64>,
}

fn inputs(n: usize, seed: u64) -> Inputs {
    let mut r = Rng(seed);
    let q = (0..n).map(|_| r.input(-20.0, 20.0)).collect();
    let qd = (0..n).map(|_| r.input(-50.0, 50.0)).collect();
    let qdd = (0..n).map(|_| r.input(-500.0, 500.0)).collect();
    let driver = (0..n).map(|_| r.input(-100.0, 100.0)).collect();
    Inputs { q, qd, qdd, driver }
}

/// The one-input checks of a generated struct `$ty` against its own scalar solvers and
/// against the run-time `Mechanism` of the same text. Returns (configurations, failures).
macro_rules! one_input_batch {
    ($ty:ident, $n:expr, $seed:expr) => {{
        let m = $ty::new();
        let rt = Mechanism::from_rust_source(MECHANISMS, stringify!($ty)).unwrap();
        let x = inputs($n, $seed);
        let n = x.q.len();
        let loads = Default::default();
        let mut failed = 0;

        let mut poses = vec![<$ty as HasPose>::nan(); n];
        let errs = m.pose_many(&x.q, &mut poses);
        let np = rt.model().points.len();
        let mut points = vec![0.0; 2 * np * n];
        let perrs = m.points_many(&x.q, &mut points);
        let mut rt_points = vec![0.0; 2 * np * n];
        let rerrs = rt.points_many(&x.q, &mut rt_points);
        for i in 0..n {
            match m.pose(x.q[i]) {
                Ok(p) => {
                    assert_eq!(poses[i], p, "pose, configuration {i}");
                    assert!(errs.get(i).is_none() && perrs.get(i).is_none());
                    for k in 0..2 * np {
                        same(
                            "points",
                            i,
                            points[2 * np * i + k],
                            rt_points[2 * np * i + k],
                            top(&points),
                        );
                    }
                }
                Err(e) => {
                    failed += 1;
                    assert_eq!(errs.get(i), Some(&e), "pose error, configuration {i}");
                    assert!(perrs.get(i).is_some() && rerrs.get(i).is_some());
                    assert!(points[2 * np * i..2 * np * (i + 1)]
                        .iter()
                        .all(|v| v.is_nan()));
                    assert!(rt_points[2 * np * i..2 * np * (i + 1)]
                        .iter()
                        .all(|v| v.is_nan()));
                }
            }
        }
        // The points are the pose's points, in declaration order.
        for i in (0..n).filter(|&i| errs.get(i).is_none()) {
            let by_name = rt.pose(&[x.q[i]]).unwrap();
            for (k, pt) in rt.model().points.iter().enumerate() {
                let pos = by_name.point(&pt.name).unwrap().pos;
                same(
                    "point x",
                    i,
                    points[2 * np * i + 2 * k],
                    pos.x,
                    top(&points),
                );
                same(
                    "point y",
                    i,
                    points[2 * np * i + 2 * k + 1],
                    pos.y,
                    top(&points),
                );
            }
        }

        let (mut ii, mut di) = (vec![0.0; n], vec![0.0; n]);
        let errs = m.reduced_many(&x.q, &mut ii, &mut di);
        let (mut rii, mut rdi) = (vec![0.0; n], vec![0.0; n]);
        let rerrs = rt.reduced_many(&x.q, &mut rii, &mut rdi);
        for i in 0..n {
            match m.reduced(x.q[i]) {
                Ok(z) => {
                    same("I*", i, ii[i], z.inertia, top(&ii));
                    same("dI*/dq", i, di[i], z.inertia_derivative, top(&di));
                    same("run-time I*", i, rii[i], z.inertia, top(&ii));
                    same("run-time dI*/dq", i, rdi[i], z.inertia_derivative, top(&di));
                }
                Err(e) => {
                    assert_eq!(errs.get(i), Some(&e), "reduced error, configuration {i}");
                    assert!(rerrs.get(i).is_some());
                    assert!(ii[i].is_nan() && di[i].is_nan() && rii[i].is_nan() && rdi[i].is_nan());
                }
            }
        }

        let mut acc = vec![0.0; n];
        let errs = m.acceleration_many(&x.q, &x.qd, &x.driver, &loads, &mut acc);
        let mut racc = vec![0.0; n];
        let rerrs = rt.acceleration_many(&x.q, &x.qd, &x.driver, &rt.loads(), &mut racc);
        for i in 0..n {
            match m.acceleration(x.q[i], x.qd[i], x.driver[i], &loads) {
                Ok(a) => {
                    same("q̈", i, acc[i], a, top(&acc));
                    same("run-time q̈", i, racc[i], a, top(&acc));
                }
                Err(e) => {
                    assert_eq!(
                        errs.get(i),
                        Some(&e),
                        "acceleration error, configuration {i}"
                    );
                    assert!(rerrs.get(i).is_some());
                    assert!(acc[i].is_nan() && racc[i].is_nan());
                }
            }
        }

        let mut d = vec![0.0; n];
        let errs = m.driver_action_many(&x.q, &x.qd, &x.qdd, &loads, &mut d);
        let mut rd = vec![0.0; n];
        let rerrs = rt.driver_action_many(&x.q, &x.qd, &x.qdd, &rt.loads(), &mut rd);
        for i in 0..n {
            let one = m
                .kinematics(x.q[i], x.qd[i], x.qdd[i])
                .and_then(|k| m.driver_action(&k, &loads));
            match one {
                Ok(t) => {
                    same("driver action", i, d[i], t, top(&d));
                    same("run-time driver action", i, rd[i], t, top(&d));
                }
                Err(e) => {
                    assert_eq!(
                        errs.get(i),
                        Some(&e),
                        "driver action error, configuration {i}"
                    );
                    assert!(rerrs.get(i).is_some());
                    assert!(d[i].is_nan() && rd[i].is_nan());
                }
            }
        }
        (n, failed)
    }};
}

/// `Pose::NAN` through a trait, so that the macro can name it for any struct.
trait HasPose {
    type P: Clone;
    fn nan() -> Self::P;
}
macro_rules! has_pose {
    ($($ty:ident => $pose:ident),*) => {$(
        impl HasPose for $ty {
            type P = $pose;
            fn nan() -> $pose { $pose::NAN }
        }
    )*};
}
has_pose!(
    FourBar => FourBarPose, SliderCrank => SliderCrankPose, PublicFourBar => PublicFourBarPose,
    PublicSliderCrank => PublicSliderCrankPose, QuickReturn => QuickReturnPose,
    Watt2 => Watt2Pose, Stephenson3 => Stephenson3Pose, ScotchYoke => ScotchYokePose,
    HydraulicLever => HydraulicLeverPose
);

#[test]
fn every_one_input_reference_mechanism_batched_equals_one_by_one() {
    let mut total = (0, 0);
    for (n, f) in [
        one_input_batch!(FourBar, 400, 1),
        one_input_batch!(SliderCrank, 400, 2),
        one_input_batch!(PublicFourBar, 400, 3),
        one_input_batch!(PublicSliderCrank, 400, 4),
        one_input_batch!(QuickReturn, 400, 5),
        one_input_batch!(Watt2, 400, 6),
        one_input_batch!(Stephenson3, 400, 7),
        one_input_batch!(ScotchYoke, 400, 8),
        one_input_batch!(HydraulicLever, 400, 9),
    ] {
        total = (total.0 + n, total.1 + f);
    }
    // Every mechanism ran its 400 configurations; about one in 23 inputs is NaN and some
    // angles do not assemble, so both kinds of failure are exercised (measured: 502 of the
    // 3600 poses failed).
    assert_eq!(total.0, 3600);
    assert!(
        total.1 >= 100,
        "only {} failed configurations exercised",
        total.1
    );
}

/// The two-input five-bar: q laid out as `[f64; 2]` per configuration (generated) and as G
/// values per configuration (run time); the motor actions two per configuration.
#[test]
fn two_inputs_batched_equals_one_by_one() {
    let m = FiveBar::new();
    let rt = Mechanism::from_rust_source(MECHANISMS, "FiveBar").unwrap();
    let mut r = Rng(11);
    let n = 300;
    let q: Vec<[f64; 2]> = (0..n)
        .map(|_| [r.input(-7.0, 7.0), r.input(-7.0, 7.0)])
        .collect();
    let qd: Vec<[f64; 2]> = (0..n)
        .map(|_| [r.input(-9.0, 9.0), r.input(-9.0, 9.0)])
        .collect();
    let qdd: Vec<[f64; 2]> = (0..n)
        .map(|_| [r.input(-9.0, 9.0), r.input(-9.0, 9.0)])
        .collect();
    let flat = |v: &[[f64; 2]]| v.iter().flatten().copied().collect::<Vec<f64>>();
    let loads = Default::default();
    let mut d = vec![0.0; 2 * n];
    let errs = m.driver_action_many(&q, &qd, &qdd, &loads, &mut d);
    let mut rd = vec![0.0; 2 * n];
    let rerrs = rt.driver_action_many(&flat(&q), &flat(&qd), &flat(&qdd), &rt.loads(), &mut rd);
    let mut rt_poses = vec![rt.nan_pose(); n];
    let perrs = rt.pose_many(&flat(&q), &mut rt_poses);
    let (mut ok, mut failed) = (0, 0);
    for i in 0..n {
        match m
            .kinematics(q[i], qd[i], qdd[i])
            .and_then(|k| m.driver_action(&k, &loads))
        {
            Ok(t) => {
                ok += 1;
                for k in 0..2 {
                    same("driver action", i, d[2 * i + k], t[k], top(&d));
                    same("run-time driver action", i, rd[2 * i + k], t[k], top(&d));
                }
            }
            Err(e) => {
                failed += 1;
                assert_eq!(errs.get(i), Some(&e));
                assert!(rerrs.get(i).is_some());
                assert!(d[2 * i..2 * i + 2]
                    .iter()
                    .chain(&rd[2 * i..2 * i + 2])
                    .all(|v| v.is_nan()));
            }
        }
        match rt.pose(&q[i]) {
            Ok(p) => assert_eq!(rt_poses[i].points, p.points),
            Err(e) => {
                assert_eq!(perrs.get(i), Some(&e));
                assert!(rt_poses[i].points.iter().all(|p| p.pos.x.is_nan()));
            }
        }
    }
    assert!(ok >= 150 && failed >= 20, "{ok} solved, {failed} failed");
    // Zhukovski's reduction needs one input: refused, nothing written.
    let mut a = vec![7.0; n];
    let mut b = vec![7.0; n];
    let e = rt.reduced_many(&flat(&q)[..n], &mut a, &mut b);
    assert!(e
        .refusal()
        .unwrap()
        .to_string()
        .contains("needs one input, the mechanism has 2"));
    assert!(a.iter().all(|&v| v == 7.0));
}

/// From `PARALLEL_FROM` configurations on the batch runs on rayon's pool: the same numbers
/// and the same failures, in order, as one by one.
#[test]
fn a_batch_on_the_pool_equals_one_by_one() {
    let m = FourBar::new();
    let x = inputs(2 * PARALLEL_FROM + 3, 21);
    let n = x.q.len();
    let (mut ii, mut di) = (vec![0.0; n], vec![0.0; n]);
    let errs = m.reduced_many(&x.q, &mut ii, &mut di);
    let mut expected = Vec::new();
    for i in 0..n {
        match m.reduced(x.q[i]) {
            Ok(z) => {
                same("I*", i, ii[i], z.inertia, top(&ii));
                same("dI*/dq", i, di[i], z.inertia_derivative, top(&di));
            }
            Err(_) => expected.push(i),
        }
    }
    assert_eq!(errs.indices(), &expected[..]);
    assert!(expected.len() > 100, "{} NaN inputs", expected.len());
}

/// Slices of the wrong length: the whole batch is refused with the numbers, nothing
/// written; the refusal is not a configuration's failure.
#[test]
fn wrong_lengths_are_refused() {
    let m = SliderCrank::new();
    let q = [0.1, 0.2, 0.3];
    let mut out = vec![5.0; 2];
    let e = m.acceleration_many(&q, &[1.0; 3], &[0.0; 3], &Default::default(), &mut out);
    assert_eq!(
        e.refusal().unwrap().to_string(),
        "invalid input: `out` has 2 slots for 3 configurations of 1 each: give it 3 (= 3 × 1)"
    );
    assert_eq!(e.len(), 0);
    assert_eq!(out, [5.0, 5.0]);
    let e = m.acceleration_many(&q, &[1.0; 2], &[0.0; 3], &Default::default(), &mut [0.0; 3]);
    assert!(
        e.refusal().unwrap().to_string().contains("`qd` has 2"),
        "{e}"
    );
    let rt = Mechanism::from_rust_source(MECHANISMS, "SliderCrank").unwrap();
    let e = rt.points_many(&q, &mut [0.0; 5]);
    assert!(
        e.to_string()
            .starts_with("batch refused: invalid input: `out` has 5 slots"),
        "{e}"
    );
}

/// Below `PARALLEL_FROM` configurations a batch with no failure allocates nothing (the
/// counting allocator of the suite, `tests/common/counting.rs`, counts this thread's).
#[test]
fn a_batch_on_the_calling_thread_does_not_allocate() {
    let m = FourBar::new();
    let n = 1000;
    let q: Vec<f64> = (0..n).map(|i| 0.0063 * i as f64).collect();
    let (qd, driver) = (vec![3.0; n], vec![1.5; n]);
    let loads = FourBarLoads::default();
    let mut poses = vec![FourBarPose::NAN; n];
    let np = FourBar::POINT_NAMES.len();
    let (mut a, mut b, mut c) = (vec![0.0; 2 * np * n], vec![0.0; n], vec![0.0; n]);
    let count = |f: &mut dyn FnMut() -> bool| {
        let before = crate::counting::count();
        assert!(f(), "a configuration failed");
        crate::counting::count() - before
    };
    // The first lane batch of the process looks `MECH_SIMD` up once (a string where it is
    // set): done before counting.
    assert!(m.points_many(&q[..4], &mut a[..2 * np * 4]).is_empty());
    assert_eq!(
        count(&mut || m.pose_many(&q, &mut poses).is_empty()),
        0,
        "pose_many"
    );
    assert_eq!(
        count(&mut || m.points_many(&q, &mut a).is_empty()),
        0,
        "points_many"
    );
    assert_eq!(
        count(&mut || m.reduced_many(&q, &mut b, &mut c).is_empty()),
        0,
        "reduced_many"
    );
    assert_eq!(
        count(&mut || m
            .acceleration_many(&q, &qd, &driver, &loads, &mut b)
            .is_empty()),
        0,
        "acceleration_many"
    );
    assert_eq!(
        count(&mut || m
            .driver_action_many(&q, &qd, &driver, &loads, &mut b)
            .is_empty()),
        0,
        "driver_action_many"
    );
    let (mut kin, mut kst) = (m.kinematics_table(n), m.kinetostatics_table(n));
    assert_eq!(
        count(&mut || m.kinematics_many(&q, &qd, &driver, &mut kin).is_empty()),
        0,
        "kinematics_many"
    );
    assert_eq!(
        count(&mut || m
            .kinetostatics_many(&q, &qd, &driver, &loads, &mut kst)
            .is_empty()),
        0,
        "kinetostatics_many"
    );
    assert!(kin
        .values()
        .iter()
        .chain(kst.values())
        .all(|v| v.is_finite()));
    // The run-time twins allocate a motion (and forces) per chunk, not per configuration:
    // as many allocations for 1000 configurations as for 10.
    let rt = Mechanism::from_rust_source(MECHANISMS, "FourBar").unwrap();
    let rt_loads = rt.loads();
    let runtime = |k: usize| {
        let (mut kin, mut kst) = (rt.kinematics_table(k), rt.kinetostatics_table(k));
        let (q, qd, qdd) = (&q[..k], &qd[..k], &driver[..k]);
        (
            count(&mut || rt.kinematics_many(q, qd, qdd, &mut kin).is_empty()),
            count(&mut || {
                rt.kinetostatics_many(q, qd, qdd, &rt_loads, &mut kst)
                    .is_empty()
            }),
        )
    };
    let (few, many) = (runtime(10), runtime(n));
    assert_eq!(
        few, many,
        "run-time allocations for 10 and {n} configurations"
    );
}

/// Loads set on a generated struct's and a run-time mechanism's loads alike, by name: a
/// force (10 + k, −5) N, a torque 1.5 N·m.
macro_rules! some_loads {
    ($ty:ident, $rt:expr) => {{
        let mut loads = <$ty as HasLoads>::Loads::default();
        let mut rt_loads = $rt.loads();
        for (k, l) in $rt.model().loads.iter().enumerate() {
            let v: &[f64] = match l {
                mech::model::Load::Force { .. } => &[10.0 + k as f64, -5.0],
                mech::model::Load::Torque { .. } => &[1.5],
            };
            assert!(loads.set_by_name(l.name(), v) && rt_loads.set_by_name(l.name(), v));
        }
        (loads, rt_loads)
    }};
}

trait HasLoads {
    type Loads: Default;
}
macro_rules! has_loads {
    ($($ty:ident => $loads:ident),*) => {$(
        impl HasLoads for $ty { type Loads = $loads; }
    )*};
}
has_loads!(
    FourBar => FourBarLoads, SliderCrank => SliderCrankLoads,
    PublicFourBar => PublicFourBarLoads, PublicSliderCrank => PublicSliderCrankLoads,
    QuickReturn => QuickReturnLoads, Watt2 => Watt2Loads, Stephenson3 => Stephenson3Loads,
    ScotchYoke => ScotchYokeLoads, HydraulicLever => HydraulicLeverLoads,
    FiveBar => FiveBarLoads
);

/// The tables of `kinematics_many` and `kinetostatics_many` of a generated struct `$ty` and
/// of its run-time twin, at the configurations `$q`, `$qd`, `$qdd` (the generated struct's
/// input type; `$flat` lays them out for the run time), checked configuration by
/// configuration against the one-configuration solvers read by name (`Motion::point`,
/// `link`, `Forces::reaction`, `driver`); the column names against the `mech sweep`
/// columns. Returns (configurations solved, failed).
macro_rules! tables_batch {
    ($ty:ident, $q:expr, $qd:expr, $qdd:expr, $flat:expr, $drivers:expr) => {{
        let m = $ty::new();
        let rt = Mechanism::from_rust_source(MECHANISMS, stringify!($ty)).unwrap();
        let (q, qd, qdd) = ($q, $qd, $qdd);
        let n = q.len();
        let (loads, rt_loads) = some_loads!($ty, rt);
        let g = rt.dof();

        // The column names are the CSV's, less the inputs (`q`), in the same order.
        let csv = mech::columns::Columns::new(&rt, mech::columns::Part::KINEMATICS);
        assert_eq!($ty::KINEMATICS_COLUMNS, &csv.names[g..]);
        assert_eq!($ty::KINEMATICS_UNITS, &csv.units[g..]);
        let csv = mech::columns::Columns::new(
            &rt,
            &[mech::columns::Part::Reactions, mech::columns::Part::Driver],
        );
        assert_eq!($ty::KINETOSTATICS_COLUMNS, &csv.names[..]);
        assert_eq!($ty::KINETOSTATICS_UNITS, &csv.units[..]);

        let mut kin = m.kinematics_table(n);
        let kerrs = m.kinematics_many(&q, &qd, &qdd, &mut kin);
        let mut rt_kin = rt.kinematics_table(n);
        let rt_kerrs = rt.kinematics_many(&$flat(&q), &$flat(&qd), &$flat(&qdd), &mut rt_kin);
        assert_eq!(rt_kin.names(), kin.names());
        assert_eq!(rt_kin.units(), kin.units());
        let mut kst = m.kinetostatics_table(n);
        let ferrs = m.kinetostatics_many(&q, &qd, &qdd, &loads, &mut kst);
        let mut rt_kst = rt.kinetostatics_table(n);
        let rt_ferrs = rt.kinetostatics_many(
            &$flat(&q),
            &$flat(&qd),
            &$flat(&qdd),
            &rt_loads,
            &mut rt_kst,
        );
        assert_eq!(rt_kst.names(), kst.names());
        // Every column once, contiguous: configuration i of column c at values[c·n + i].
        assert_eq!(kin.values().len(), n * kin.width());
        let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<u64>>();
        assert_eq!(bits(kin.column_at(1)), bits(&kin.values()[n..2 * n]));

        let col = |t: &mech::batch::Table, name: &str| t.column(name).unwrap().to_vec();
        let (mut ok, mut failed) = (0, 0);
        for i in 0..n {
            let one = m.kinematics(q[i], qd[i], qdd[i]);
            match &one {
                Ok(mo) => {
                    assert!(kerrs.get(i).is_none() && rt_kerrs.get(i).is_none(), "{i}");
                    for pt in rt.model().points.iter() {
                        let pm = mo.point(&pt.name).unwrap();
                        let p = &pt.name;
                        for (c, v) in [
                            ("x", pm.pos.x),
                            ("y", pm.pos.y),
                            ("vx", pm.vel.x),
                            ("vy", pm.vel.y),
                            ("ax", pm.acc.x),
                            ("ay", pm.acc.y),
                        ] {
                            let name = format!("{p}.{c}");
                            let (a, b) = (col(&kin, &name), col(&rt_kin, &name));
                            same(&name, i, a[i], v, top(&a));
                            same(&format!("run-time {name}"), i, b[i], v, top(&a));
                        }
                    }
                    for l in rt.model().links[1..].iter() {
                        let lm = mo.link(&l.name).unwrap();
                        for (c, v) in [
                            ("angle", lm.angle),
                            ("omega", lm.omega),
                            ("alpha", lm.alpha),
                        ] {
                            let name = format!("{}.{c}", l.name);
                            let (a, b) = (col(&kin, &name), col(&rt_kin, &name));
                            same(&name, i, a[i], v, top(&a));
                            same(&format!("run-time {name}"), i, b[i], v, top(&a));
                        }
                    }
                }
                Err(e) => {
                    failed += 1;
                    assert_eq!(kerrs.get(i), Some(e), "kinematics error, configuration {i}");
                    assert!(rt_kerrs.get(i).is_some(), "{i}");
                    for c in 0..kin.width() {
                        assert!(kin.column_at(c)[i].is_nan() && rt_kin.column_at(c)[i].is_nan());
                    }
                }
            }
            match one.and_then(|mo| m.kinetostatics(&mo, &loads)) {
                Ok(f) => {
                    ok += 1;
                    assert!(ferrs.get(i).is_none() && rt_ferrs.get(i).is_none(), "{i}");
                    for j in rt.model().joints.iter() {
                        let (force, moment) = f.reaction(&j.name).unwrap();
                        let mut expected = vec![("fx", force.x), ("fy", force.y)];
                        expected.extend(moment.map(|v| ("moment", v)));
                        for (c, v) in expected {
                            let name = format!("{}.{c}", j.name);
                            let (a, b) = (col(&kst, &name), col(&rt_kst, &name));
                            same(&name, i, a[i], v, top(&a));
                            same(&format!("run-time {name}"), i, b[i], v, top(&a));
                        }
                    }
                    for (name, v) in $drivers(&rt, &f.driver) {
                        let (a, b) = (col(&kst, &name), col(&rt_kst, &name));
                        same(&name, i, a[i], v, top(&a));
                        same(&format!("run-time {name}"), i, b[i], v, top(&a));
                    }
                }
                Err(e) => {
                    assert_eq!(
                        ferrs.get(i),
                        Some(&e),
                        "kinetostatics error, configuration {i}"
                    );
                    assert!(rt_ferrs.get(i).is_some(), "{i}");
                    for c in 0..kst.width() {
                        assert!(kst.column_at(c)[i].is_nan() && rt_kst.column_at(c)[i].is_nan());
                    }
                }
            }
        }
        assert_eq!((kerrs.len(), ok + ferrs.len()), (failed, n));
        (ok, failed)
    }};
}

/// The motor action of the one input, named `driver`.
fn one_driver(_: &Mechanism, d: &f64) -> Vec<(String, f64)> {
    vec![("driver".to_string(), *d)]
}

/// Configuration i's inputs as a run-time slice (one input).
fn same_f64(v: &[f64]) -> Vec<f64> {
    v.to_vec()
}

/// `kinematics_many` and `kinetostatics_many` of every reference mechanism (the generated
/// struct and the run-time twin) equal the one-configuration solvers, NaN and the error
/// where they fail.
#[test]
fn kinematics_and_kinetostatics_tables_equal_one_by_one() {
    let mut total = (0, 0);
    macro_rules! one {
        ($ty:ident, $seed:expr) => {{
            let x = inputs(300, $seed);
            tables_batch!($ty, x.q, x.qd, x.qdd, same_f64, one_driver)
        }};
    }
    for (ok, failed) in [
        one!(FourBar, 31),
        one!(SliderCrank, 32),
        one!(PublicFourBar, 33),
        one!(PublicSliderCrank, 34),
        one!(QuickReturn, 35),
        one!(Watt2, 36),
        one!(Stephenson3, 37),
        one!(ScotchYoke, 38),
        one!(HydraulicLever, 39),
    ] {
        total = (total.0 + ok, total.1 + failed);
    }
    // The five-bar's two inputs: `driver.<joint>` columns.
    let mut r = Rng(41);
    let mut two = |lo: f64, hi: f64| -> Vec<[f64; 2]> {
        (0..300)
            .map(|_| [r.input(lo, hi), r.input(lo, hi)])
            .collect()
    };
    let (q, qd, qdd) = (two(-7.0, 7.0), two(-9.0, 9.0), two(-9.0, 9.0));
    let flat = |v: &[[f64; 2]]| v.iter().flatten().copied().collect::<Vec<f64>>();
    let drivers = |rt: &Mechanism, d: &[f64; 2]| {
        rt.model()
            .inputs
            .iter()
            .zip(d)
            .map(|(&j, &v)| (format!("driver.{}", rt.model().joints[j].name), v))
            .collect::<Vec<_>>()
    };
    let (ok, failed) = tables_batch!(FiveBar, q, qd, qdd, flat, drivers);
    assert!(
        ok >= 100 && failed >= 20,
        "five-bar: {ok} solved, {failed} failed"
    );
    total = (total.0 + ok, total.1 + failed);
    assert!(total.0 >= 2000 && total.1 >= 100, "{total:?}");
}

/// A table of the wrong size, of the other kind, or slices of different lengths: refused
/// with the numbers and the fix, nothing written; a table resized is accepted.
#[test]
fn tables_of_the_wrong_shape_are_refused() {
    let m = FourBar::new();
    let q = [0.1, 0.2, 0.3];
    let mut t = m.kinematics_table(3);
    assert!(m
        .kinematics_many(&q, &[1.0; 3], &[0.0; 3], &mut t)
        .is_empty());
    let before = t.clone();
    let e = m.kinematics_many(&q, &[1.0; 2], &[0.0; 3], &mut t);
    assert!(
        e.refusal()
            .unwrap()
            .to_string()
            .contains("`qd` has 2 configurations where `q` has 3"),
        "{e}"
    );
    let e = m.kinematics_many(&q[..2], &[1.0; 2], &[0.0; 2], &mut t);
    assert_eq!(
        e.refusal().unwrap().to_string(),
        "invalid input: `out` holds 3 configurations where `q` has 2: call `out.resize(2)` or make it with `kinematics_table(2)`"
    );
    let mut f = m.kinetostatics_table(3);
    let e = m.kinematics_many(&q, &[1.0; 3], &[0.0; 3], &mut f);
    assert!(
        e.refusal()
            .unwrap()
            .to_string()
            .contains("not a table of this mechanism's kinematics"),
        "{e}"
    );
    // A kinematics table of another mechanism (the slider-crank's) is refused too.
    let mut other = SliderCrank::new().kinematics_table(3);
    assert!(m
        .kinematics_many(&q, &[1.0; 3], &[0.0; 3], &mut other)
        .refusal()
        .is_some());
    assert_eq!(t, before);
    assert!(f.values().iter().all(|v| v.is_nan()));
    let rt = Mechanism::from_rust_source(MECHANISMS, "FourBar").unwrap();
    let e = rt.kinetostatics_many(
        &q,
        &[1.0; 3],
        &[0.0; 3],
        &rt.loads(),
        &mut m.kinetostatics_table(4),
    );
    assert!(
        e.to_string()
            .starts_with("batch refused: invalid input: `out` holds 4 configurations"),
        "{e}"
    );
    // Resized, the table takes the batch.
    t.resize(2);
    assert!(m
        .kinematics_many(&q[..2], &[1.0; 2], &[0.0; 2], &mut t)
        .is_empty());
    assert_eq!(t.len(), 2);
    assert_eq!(
        t.get("B.x", 1),
        Some(m.kinematics(0.2, 1.0, 0.0).unwrap().points.B.pos.x)
    );
}

/// On rayon's pool (from `PARALLEL_FROM` configurations) the tables are the same as one by
/// one: the parts of the split write their own configurations of every column.
#[test]
fn tables_on_the_pool_equal_one_by_one() {
    let m = SliderCrank::new();
    let x = inputs(PARALLEL_FROM + 1031, 43);
    let n = x.q.len();
    let mut t = m.kinematics_table(n);
    let errs = m.kinematics_many(&x.q, &x.qd, &x.qdd, &mut t);
    let mut f = m.kinetostatics_table(n);
    let loads = SliderCrankLoads::default();
    let ferrs = m.kinetostatics_many(&x.q, &x.qd, &x.qdd, &loads, &mut f);
    let mut expected = Vec::new();
    for i in 0..n {
        match m.kinematics(x.q[i], x.qd[i], x.qdd[i]) {
            Ok(mo) => {
                let c = t.column("B.vx").unwrap();
                same("B.vx", i, c[i], mo.points.B.vel.x, top(c));
                let d = f.column("driver").unwrap();
                same(
                    "driver",
                    i,
                    d[i],
                    m.kinetostatics(&mo, &loads).unwrap().driver,
                    top(d),
                );
            }
            Err(_) => expected.push(i),
        }
    }
    assert_eq!(errs.indices(), &expected[..]);
    assert_eq!(ferrs.indices(), &expected[..]);
    assert!(expected.len() > 100);
}

#[path = "../examples/batch.rs"]
#[allow(dead_code)]
mod example;

/// The example runs: only the configuration given NaN fails, in each of its three calls,
/// and every other value is its one-configuration solver's.
#[test]
fn the_batch_example_equals_one_by_one() {
    let m = example::FourBar::new();
    let b = example::run(&m);
    assert_eq!(
        b.failed,
        [
            vec![example::BROKEN],
            vec![example::BROKEN],
            vec![example::BROKEN]
        ]
    );
    let mut loads = example::FourBarLoads::default();
    loads.tool = Vector2::new(80.0, -60.0);
    loads.resist = 2.0;
    let np = example::FourBar::POINT_NAMES.len();
    for i in (0..example::N).filter(|&i| i != example::BROKEN) {
        let r = m.reduced(b.q[i]).unwrap();
        same("I*", i, b.inertia[i], r.inertia, top(&b.inertia));
        same(
            "dI*/dq",
            i,
            b.derivative[i],
            r.inertia_derivative,
            top(&b.derivative),
        );
        let a = m.acceleration(b.q[i], 10.0, 2.0, &loads).unwrap();
        same("q̈", i, b.acceleration[i], a, top(&b.acceleration));
        let p = m.pose(b.q[i]).unwrap().points.P.pos;
        same("P x", i, b.points[2 * np * i + 8], p.x, top(&b.points));
        same("P y", i, b.points[2 * np * i + 9], p.y, top(&b.points));
    }
}

/// Loads on a link that slides on the ground (the slider-crank's gas force on its piston)
/// in the run-time lanes: `acceleration_many` takes them by the anchor's velocity
/// (`ZhukovskiLanes::force_translating`), as the scalar `acceleration` and the generated
/// struct do, and equals both configuration by configuration (the reference tests above
/// run with zero loads, which every term takes alike).
#[test]
fn loads_on_a_sliding_link_in_the_lanes_equal_one_by_one() {
    let m = SliderCrank::new();
    let mut loads = SliderCrankLoads::default();
    assert!(loads.set_by_name("gas", &[-1500.0, 35.0]));
    assert!(loads.set_by_name("shaft", &[-4.0]));
    let rt = Mechanism::from_rust_source(MECHANISMS, "SliderCrank").unwrap();
    let mut rl = rt.loads();
    assert!(rl.set_by_name("gas", &[-1500.0, 35.0]));
    assert!(rl.set_by_name("shaft", &[-4.0]));
    let x = inputs(64, 41);
    let mut racc = vec![0.0; x.q.len()];
    let _ = rt.acceleration_many(&x.q, &x.qd, &x.driver, &rl, &mut racc);
    let mut compared = 0;
    for i in 0..x.q.len() {
        let one = rt.acceleration(x.q[i], x.qd[i], x.driver[i], &rl);
        let generated = m.acceleration(x.q[i], x.qd[i], x.driver[i], &loads);
        match (one, generated) {
            (Ok(a), Ok(g)) => {
                same(
                    "run-time acceleration_many",
                    i,
                    racc[i],
                    a,
                    a.abs().max(1.0),
                );
                same("generated acceleration", i, g, a, a.abs().max(1.0));
                compared += 1;
            }
            (Err(_), Err(_)) => assert!(racc[i].is_nan(), "configuration {i}: {}", racc[i]),
            (a, g) => panic!("configuration {i}: run time {a:?}, generated {g:?}"),
        }
    }
    assert!(compared >= 32, "only {compared} configurations solved");
}
