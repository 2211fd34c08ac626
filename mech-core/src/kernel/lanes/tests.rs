//! The lane kernels against the scalar ones: the vector math in ulps over many arguments,
//! and whole mechanisms (cranks, sliders, RRR and RRP dyads) solved in lanes and one
//! configuration at a time on random inputs, positions, rates, points, angles, Zhukovski's
//! sums and the masks compared.

#![allow(clippy::needless_range_loop)]

use super::*;
use crate::front::resolve::model_of;
use crate::kernel::constraints::Level;
use crate::kernel::kinematics::{crank_angle, point_pose, solve_chain, solve_driven};
use crate::kernel::measure::within;
use crate::plan::assur::{plan, Group, Kernel};
use crate::solvers::instance::{instance, Instance};
use crate::solvers::zhukovski::{acceleration, Reduced, ZhukovskiSums};
use crate::MechError;

/// The lane backend of this instance of the tests: this file is compiled twice
/// (`lanes/mod.rs`), as `tests` on [`Base`] and as `tests_wide` on [`Wide`].
type TB = <Pick<{ is_wide(module_path!()) }> as Backend2>::T;
type L = super::L<TB>;
type LinkLanes = super::LinkLanes<TB>;
type ZhukovskiLanes = super::ZhukovskiLanes<TB>;

/// Whether the module path ends in `tests_wide`.
const fn is_wide(path: &str) -> bool {
    let (p, w) = (path.as_bytes(), b"tests_wide".as_slice());
    if p.len() < w.len() {
        return false;
    }
    let mut k = 0;
    while k < w.len() {
        if p[p.len() - w.len() + k] != w[k] {
            return false;
        }
        k += 1;
    }
    true
}

/// The backend for a module: [`Wide`] where `W`.
pub(super) struct Pick<const W: bool>;
pub(super) trait Backend2 {
    type T: Backend;
}
impl Backend2 for Pick<false> {
    type T = Base;
}
impl Backend2 for Pick<true> {
    type T = Wide;
}

/// True when this instance cannot run: the 256-bit one on a processor without AVX2 and
/// FMA (or with `MECH_SIMD=0`).
fn skip() -> bool {
    is_wide(module_path!()) && !simd_allowed()
}

/// `f` where this instance's backend runs: in [`with_simd`]'s AVX2 path for [`Wide`], plainly
/// for [`Base`].
fn run<R>(f: impl FnOnce() -> R) -> R {
    if is_wide(module_path!()) {
        with_simd(
            (),
            |()| unreachable!("the 256-bit backend without AVX2"),
            |()| f(),
        )
    } else {
        f()
    }
}

/// splitmix64: a small seeded generator (no dependency).
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }
    /// Uniform in [lo, hi).
    fn uniform(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * ((self.next() >> 11) as f64 / (1u64 << 53) as f64)
    }
}

/// The distance from `a` to the reference `b` in units of b's last place.
fn ulps(a: f64, b: f64) -> f64 {
    if a == b {
        return 0.0;
    }
    let m = b.abs();
    let ulp = if m < f64::MIN_POSITIVE {
        f64::from_bits(1)
    } else {
        f64::from_bits(m.to_bits() + 1) - m
    };
    (a - b).abs() / ulp
}

/// The worst ulps of `sin_cos` against `f64::sin_cos` over `n` arguments drawn by `draw`.
fn sin_cos_worst(rng: &mut Rng, n: usize, mut draw: impl FnMut(&mut Rng) -> f64) -> (f64, f64) {
    let (mut ws, mut wc) = (0.0f64, 0.0f64);
    for _ in 0..n / LANES {
        let x = L::from_fn(|_| draw(rng));
        let (s, c) = sin_cos(x);
        for i in 0..LANES {
            let (rs, rc) = x.0[i].sin_cos();
            ws = ws.max(ulps(s.0[i], rs));
            wc = wc.max(ulps(c.0[i], rc));
        }
    }
    (ws, wc)
}

#[test]
fn sin_cos_and_atan2_are_within_their_stated_ulps() {
    if skip() {
        return;
    }
    let mut rng = Rng(0x5EED);
    let big = 1e4 * std::f64::consts::PI;
    let mut n = 0;
    let mut worst = [0.0f64; 2];
    for (count, lo, hi) in [
        (1_000_000, -big, big),
        (100_000, -1.0, 1.0),
        (100_000, -SIN_COS_RANGE, SIN_COS_RANGE),
    ] {
        let (s, c) = sin_cos_worst(&mut rng, count, |r| r.uniform(lo, hi));
        worst = [worst[0].max(s), worst[1].max(c)];
        n += count;
    }
    // Tiny arguments, and beyond the range (the scalar fallback).
    let (s, c) = sin_cos_worst(&mut rng, 40_000, |r| {
        r.uniform(-1.0, 1.0) * 10f64.powf(r.uniform(-300.0, 0.0))
    });
    worst = [worst[0].max(s), worst[1].max(c)];
    let (s, c) = sin_cos_worst(&mut rng, 4_000, |r| r.uniform(-1e12, 1e12));
    assert!(s == 0.0 && c == 0.0, "the fallback is f64::sin_cos");
    n += 44_000;
    println!(
        "sin_cos over {n} arguments: worst {:.3} ulp (sin), {:.3} ulp (cos)",
        worst[0], worst[1]
    );
    // The documented bound (sin_cos's doc): measured worst 1.000 ulp, asserted exactly.
    assert!(worst[0] <= 1.0 && worst[1] <= 1.0, "sin_cos: {worst:?} ulp");
    for x in [f64::NAN, f64::INFINITY, -f64::INFINITY] {
        let (s, c) = sin_cos(L::splat(x));
        assert!(s.0[0].is_nan() && c.0[0].is_nan());
    }

    let mut wa = 0.0f64;
    let m = 1_000_000;
    for _ in 0..m / LANES {
        let (y, x): (L, L) = {
            let t = L::from_fn(|_| rng.uniform(-4.0, 4.0));
            let r = L::from_fn(|_| 10f64.powf(rng.uniform(-3.0, 3.0)));
            (r * t.map(f64::sin), r * t.map(f64::cos))
        };
        let a = atan2(y, x);
        for i in 0..LANES {
            wa = wa.max(ulps(a.0[i], y.0[i].atan2(x.0[i])));
        }
    }
    println!("atan2 over {m} arguments: worst {wa:.3} ulp");
    // The documented bound (atan2's doc): measured worst 2.000 ulp, asserted exactly.
    assert!(wa <= 2.0, "atan2: {wa} ulp");
    // Axes, zeros and non-finite lanes.
    for (y, x) in [
        (0.0, 1.0),
        (0.0, -1.0),
        (-0.0, -1.0),
        (1.0, 0.0),
        (-1.0, 0.0),
        (1.0, -0.0),
        (0.0, 0.0),
        (-0.0, -0.0),
        (1.0, 1.0),
        (-1.0, -1.0),
        (f64::INFINITY, 1.0),
        (f64::NAN, 1.0),
        (1.0, f64::NEG_INFINITY),
    ] {
        let a = atan2(L::splat(y), L::splat(x)).0[0];
        let b = y.atan2(x);
        assert!(
            a == b || (a.is_nan() && b.is_nan()),
            "atan2({y}, {x}) = {a}, not {b}"
        );
    }
    // wrap: the same operations as the scalar one.
    for _ in 0..10_000 {
        let a = L::from_fn(|_| rng.uniform(-1e3, 1e3));
        let w = wrap(a);
        for i in 0..LANES {
            assert_eq!(w.0[i], crate::kernel::link_state::wrap(a.0[i]));
        }
    }
    let far = L::new([1e9, -3e12, 2.5e300, 0.5]);
    for i in 0..LANES {
        assert_eq!(wrap(far).0[i], crate::kernel::link_state::wrap(far.0[i]));
    }
}

/// A mechanism, its numbers and its plan.
pub(super) struct Rig {
    text: &'static str,
    inst: Instance,
    groups: Vec<Group>,
    branches: Vec<f64>,
    /// Per input: a revolute (true) or a prismatic driver.
    revolute: Vec<bool>,
}

pub(super) fn rig(text: &'static str) -> Rig {
    let model = model_of(text);
    let inst = instance(&model).expect("instance");
    let groups = plan(&model).expect("plan");
    let solvers: Vec<_> = groups.iter().map(|g| g.solver).collect();
    let branches = inst.branches(&solvers);
    for g in &groups {
        assert!(
            supports(g.solver),
            "{text}: {:?} has no lane kernel",
            g.solver
        );
    }
    let revolute = model
        .inputs
        .iter()
        .map(|&j| model.joints[j].kind == crate::model::JointKind::Revolute)
        .collect();
    Rig {
        text,
        inst,
        groups,
        branches,
        revolute,
    }
}

/// Inputs (q, q̇, q̈) of one configuration.
type Config = (Vec<f64>, Vec<f64>, Vec<f64>);

impl Rig {
    /// A random configuration: revolute inputs all around, sliders ±`travel` m from the
    /// drawing, rates and accelerations of a few units.
    fn random(&self, rng: &mut Rng, travel: f64) -> Config {
        let mut q = Vec::new();
        for (i, &rev) in self.revolute.iter().enumerate() {
            let j = self.input_joint(i);
            let q_ref = self.inst.joints[j].q_ref;
            q.push(if rev {
                q_ref + rng.uniform(-std::f64::consts::PI, std::f64::consts::PI)
            } else {
                q_ref + rng.uniform(-travel, travel)
            });
        }
        let qd = (0..q.len()).map(|_| rng.uniform(-5.0, 5.0)).collect();
        let qdd = (0..q.len()).map(|_| rng.uniform(-50.0, 50.0)).collect();
        (q, qd, qdd)
    }
    /// The joint of input `i`.
    fn input_joint(&self, i: usize) -> usize {
        self.groups
            .iter()
            .find_map(|g| match g.solver {
                Solver::DrivenRevolute { joint, input, .. }
                | Solver::DrivenPrismatic { joint, input, .. }
                    if input == i =>
                {
                    Some(joint)
                }
                _ => None,
            })
            .expect("the input's driver")
    }
    /// The scalar route: every group in plan order.
    fn scalar(&self, c: &Config, upto: Level) -> Result<Vec<LinkState>, MechError> {
        let mut s = self.inst.drawing.clone();
        let drive = (&c.0[..], &c.1[..], &c.2[..]);
        for (g, &sign) in self.groups.iter().zip(&self.branches) {
            match &g.kernel {
                Kernel::Driven(d) => {
                    solve_driven(g.solver, d, &self.inst.joints, &mut s, drive, upto)?
                }
                Kernel::Chain(ch) => {
                    solve_chain(
                        g.solver,
                        ch,
                        &self.inst.joints,
                        &mut s,
                        drive,
                        sign,
                        self.inst.scale,
                        upto,
                    )?;
                }
                k => panic!("no lane kernel for {k:?}"),
            }
        }
        Ok(s)
    }
    /// The lane route for four configurations: the states and the union of the masks.
    pub(super) fn lanes(&self, c: &[Config; LANES], upto: Level) -> (Vec<LinkLanes>, Mask) {
        let mut s: Vec<LinkLanes> = self
            .inst
            .drawing
            .iter()
            .map(LinkLanes::from_state)
            .collect();
        let n_in = c[0].0.len();
        let pick = |k: usize| -> Vec<L> {
            (0..n_in)
                .map(|i| {
                    L::from_fn(|l| match k {
                        0 => c[l].0[i],
                        1 => c[l].1[i],
                        _ => c[l].2[i],
                    })
                })
                .collect()
        };
        let (q, qd, qdd) = (pick(0), pick(1), pick(2));
        let mut mask = NONE;
        for (g, &sign) in self.groups.iter().zip(&self.branches) {
            let m = match &g.kernel {
                Kernel::Driven(d) => {
                    solve_driven_lanes(g.solver, d, &self.inst.joints, &mut s, &q, &qd, &qdd, upto)
                }
                Kernel::Chain(_) => solve_chain_lanes(
                    g.solver,
                    &self.inst.joints,
                    &mut s,
                    sign,
                    self.inst.scale,
                    upto,
                ),
                k => panic!("no lane kernel for {k:?}"),
            };
            mask = or(mask, m);
        }
        (s, mask)
    }
}

/// The worst error relative to its magnitude over a run, and how many checks went in.
#[derive(Default, Debug)]
struct Worst {
    pos: f64,
    rate: f64,
    zhukovski: f64,
    angle: f64,
    compared: usize,
    masked: usize,
    failed: usize,
}

/// Compare lane `i` of the lane states with the scalar states `sa` (moving links 1..),
/// each kind of quantity relative to its largest magnitude in the configuration (m with
/// the length scale L, m/s with |ω| L, m/s² with |α| L and ω² L).
fn compare(rig: &Rig, sa: &[LinkState], sl: &[LinkLanes], i: usize, upto: Level, w: &mut Worst) {
    let len = rig.inst.scale;
    let n = sa.len();
    let lanes: Vec<LinkState> = sl.iter().map(|x| x.lane(i)).collect();
    let mut refs = [len, f64::MIN_POSITIVE, f64::MIN_POSITIVE];
    for s in &sa[1..] {
        refs[0] = refs[0].max(s.pos.norm());
        refs[1] = refs[1].max(s.vel.norm()).max(s.omega.abs() * len);
        refs[2] = refs[2]
            .max(s.acc.norm())
            .max(s.alpha.abs() * len)
            .max(s.omega * s.omega * len);
    }
    for (a, b) in sa[1..].iter().zip(&lanes[1..]) {
        w.pos = w.pos.max((a.pos - b.pos).norm() / refs[0]);
        w.pos = w.pos.max((a.rot - b.rot).norm());
        if upto != Level::Position {
            w.rate = w.rate.max((a.vel - b.vel).norm() / refs[1]);
            w.rate = w.rate.max((a.omega - b.omega).abs() * len / refs[1]);
            w.rate = w.rate.max((a.acc - b.acc).norm() / refs[2]);
            w.rate = w.rate.max((a.alpha - b.alpha).abs() * len / refs[2]);
        }
        w.angle = w
            .angle
            .max((a.angle - b.angle).abs() / a.angle.abs().max(1.0));
    }
    // Points, poses and angles.
    for (l, geom) in rig.inst.links.iter().enumerate().skip(1) {
        let d = geom.dcg + V2::new(0.013, -0.021);
        let p = point_lanes(sl, l, d);
        let ps = point_pose(sa, l, d).pos;
        w.pos = w
            .pos
            .max((ps - V2::new(p[0].0[i], p[1].0[i])).norm() / refs[0]);
        let cg = cg_lanes(geom, &sl[l]);
        let cgs = geom.pose(&sa[l]).cg;
        w.pos = w
            .pos
            .max((cgs - V2::new(cg[0].0[i], cg[1].0[i])).norm() / refs[0]);
        let (al, asc) = (link_angle_lanes(geom, &sl[l]).0[i], geom.angle(&sa[l]));
        w.angle = w.angle.max((al - asc).abs() / asc.abs().max(1.0));
        if upto == Level::Acceleration {
            let [pl, vl, al_] = point_motion_lanes(sl, l, d);
            let m = crate::kernel::link_state::point_motion(sa, l, d);
            for (k, (x, y)) in [(pl, m.pos), (vl, m.vel), (al_, m.acc)]
                .into_iter()
                .enumerate()
            {
                let err = (y - V2::new(x[0].0[i], x[1].0[i])).norm() / refs[k];
                let worst = if k == 0 { &mut w.pos } else { &mut w.rate };
                *worst = worst.max(err);
            }
        }
    }
    if upto != Level::Acceleration {
        return;
    }
    // Zhukovski's sums, method by method, link by link.
    let g = V2::new(0.3, -9.81);
    let f = V2::new(12.0, -7.0);
    for l in 1..n {
        let geom = &rig.inst.links[l];
        let next = l % (n - 1) + 1;
        type Scalar = fn(
            &mut ZhukovskiSums,
            &crate::kernel::link_state::LinkGeom,
            &LinkState,
            &LinkState,
            V2,
            V2,
        );
        type Lanes = fn(
            &mut ZhukovskiLanes,
            &crate::kernel::link_state::LinkGeom,
            &LinkLanes,
            &LinkLanes,
            V2,
            V2,
        );
        let methods: [(Scalar, Lanes); 11] = [
            (
                |z, l, s, _, _, _| z.inertia(l, s),
                |z, l, s, _, _, _| z.inertia(l, s),
            ),
            (
                |z, l, s, n, _, _| z.inertia_spanned(l, s, n),
                |z, l, s, n, _, _| z.inertia_spanned(l, s, n),
            ),
            (
                |z, l, s, _, _, _| z.inertia_about_pivot(l, s),
                |z, l, s, _, _, _| z.inertia_about_pivot(l, s),
            ),
            (
                |z, l, s, _, _, _| z.inertia_translating(l, s),
                |z, l, s, _, _, _| z.inertia_translating(l, s),
            ),
            (
                |z, l, s, _, g, _| z.gravity(l, s, g),
                |z, l, s, _, g, _| z.gravity(l, s, g),
            ),
            (
                |z, l, s, n, g, _| z.gravity_spanned(l, s, n, g),
                |z, l, s, n, g, _| z.gravity_spanned(l, s, n, g),
            ),
            (
                |z, l, s, _, g, _| z.gravity_translating(l, s, g),
                |z, l, s, _, g, _| z.gravity_translating(l, s, g),
            ),
            (
                |z, _, s, _, _, f| z.force(s, V2::new(0.02, 0.01), f),
                |z, _, s, _, _, f| z.force(s, V2::new(0.02, 0.01), f),
            ),
            (
                |z, _, s, _, _, f| z.force(s, V2::zeros(), f),
                |z, _, s, _, _, f| z.force_lanes(s, V2::zeros(), [L::splat(f.x), L::splat(f.y)]),
            ),
            (
                |z, _, s, _, _, _| z.torque(s, 3.5),
                |z, _, s, _, _, _| z.torque(s, 3.5),
            ),
            (
                |z, _, s, _, _, _| z.torque(s, -1.5),
                |z, _, s, _, _, _| z.torque_lanes(s, L::splat(-1.5)),
            ),
        ];
        for (ms, ml) in methods {
            let mut zs = ZhukovskiSums::new();
            ms(&mut zs, geom, &sa[l], &sa[next], g, f);
            let mut zl = ZhukovskiLanes::new();
            ml(&mut zl, geom, &sl[l], &sl[next], g, f);
            // Magnitudes: m v², I ω², m v a, m g v, F v, T ω.
            let mass = geom.mass.max(geom.inertia / (len * len));
            let scale_i = mass * refs[1] * refs[1];
            let scale_d = mass * refs[1] * refs[2];
            let scale_m = (mass * g.norm() + f.norm()) * refs[1] + 3.5 * refs[1] / len;
            for (a, b, r) in [
                (zs.reduced.inertia, zl.inertia.0[i], scale_i),
                (
                    zs.reduced.inertia_derivative,
                    zl.inertia_derivative.0[i],
                    scale_d,
                ),
                (zs.moment, zl.moment.0[i], scale_m),
            ] {
                w.zhukovski = w.zhukovski.max((a - b).abs() / r.max(f64::MIN_POSITIVE));
            }
        }
    }
}

/// Run `batches` batches of four random configurations of `rig` (plus the `extra` ones) at
/// each level; check the masks and collect the errors of the lanes not masked.
fn exercise(
    rig: &Rig,
    rng: &mut Rng,
    batches: usize,
    extra: &[Config],
    travel: f64,
    w: &mut Worst,
) {
    let mut configs: Vec<Config> = (0..batches * LANES)
        .map(|_| rig.random(rng, travel))
        .collect();
    configs.extend_from_slice(extra);
    while !configs.len().is_multiple_of(LANES) {
        configs.push(rig.random(rng, travel));
    }
    for upto in [Level::Position, Level::Velocity, Level::Acceleration] {
        for chunk in configs.chunks(LANES) {
            let batch: [Config; LANES] = std::array::from_fn(|i| chunk[i].clone());
            let (sl, mask) = rig.lanes(&batch, upto);
            for (i, c) in batch.iter().enumerate() {
                match rig.scalar(c, upto) {
                    Err(e) => {
                        w.failed += 1;
                        assert!(
                            mask[i],
                            "{}: scalar {e:?} at {c:?} ({upto:?}) not masked",
                            rig.text
                        );
                    }
                    Ok(sa) if !mask[i] => {
                        compare(rig, &sa, &sl, i, upto, w);
                        w.compared += 1;
                    }
                    Ok(_) => w.masked += 1,
                }
            }
        }
    }
}

/// The input angle between `ok` and `bad` (one revolute input, the others fixed) where the
/// scalar route changes from Ok to Err, by bisection.
fn change_point(rig: &Rig, base: &Config, mut ok: f64, mut bad: f64, upto: Level) -> f64 {
    for _ in 0..200 {
        let mid = 0.5 * (ok + bad);
        if mid == ok || mid == bad {
            break;
        }
        let mut c = base.clone();
        c.0[0] = mid;
        if rig.scalar(&c, upto).is_ok() {
            ok = mid;
        } else {
            bad = mid;
        }
    }
    ok
}

/// Configurations around every change point of input 0 found on a sweep: the last Ok and
/// the first Err angle at each level, and their neighbours a few ulps to 10⁻⁶ rad away.
fn near_change_points(rig: &Rig) -> Vec<Config> {
    let mut out = Vec::new();
    let q_ref = rig.inst.joints[rig.input_joint(0)].q_ref;
    let n_in = rig.revolute.len();
    let base: Config = (vec![q_ref; n_in], vec![1.3; n_in], vec![-0.7; n_in]);
    for upto in [Level::Position, Level::Velocity] {
        let at = |q: f64| {
            let mut c = base.clone();
            c.0[0] = q;
            rig.scalar(&c, upto).is_ok()
        };
        let steps = 720;
        for k in 0..steps {
            let (q0, q1) = (
                q_ref + std::f64::consts::TAU * k as f64 / steps as f64,
                q_ref + std::f64::consts::TAU * (k + 1) as f64 / steps as f64,
            );
            let (a, b) = (at(q0), at(q1));
            if a == b {
                continue;
            }
            let (ok, bad) = if a { (q0, q1) } else { (q1, q0) };
            let q = change_point(rig, &base, ok, bad, upto);
            let dir = if bad > ok { 1.0 } else { -1.0 };
            for off in [
                0.0, 1e-16, 4e-16, 1e-15, 1e-14, 1e-13, 1e-12, 1e-10, 1e-8, 1e-6,
            ] {
                for sgn in [-1.0, 1.0] {
                    let mut c = base.clone();
                    c.0[0] = q + dir * sgn * off * q.abs().max(1.0);
                    out.push(c);
                }
            }
        }
    }
    out
}

/// A crank-rocker four-bar (crank + RRR), with masses.
const FOUR_BAR: &str = "pub struct FourBar {
    gravity: (0.0, -9.81),
    ground { O2: (0.0, 0.0), O4: (0.3, 0.04) },
    link crank { points { O2, A: (0.04, 0.06928203230275509) },
        mass: 0.65, inertia: 0.00052, cg: (0.011803847577293369, 0.03244486372867091) },
    link coupler { points { A, B: (0.2430191330116403, 0.23171119111114735), P: (0.085, 0.22) },
        mass: 1.45, inertia: 0.0112, cg: (0.11823879885921107, 0.17157910143510077) },
    link rocker { points { O4, B }, mass: 0.9, inertia: 0.0031, cg: (0.27, 0.13) },
    joints { O2: revolute(ground, crank), A: revolute(crank, coupler),
             B: revolute(coupler, rocker), O4: revolute(ground, rocker) },
    input: O2 }";

/// A four-bar that does not assemble over part of the crank's turn (non-Grashof), its
/// crank's anchor not its pin, off the origin.
const FOUR_BAR_LIMITED: &str = "pub struct Limited {
    ground { O2: (0.1, 0.2), O4: (0.4, 0.2) },
    link crank { points { A: (0.1, 0.3), O2 }, mass: 0.3, inertia: 0.0002, cg: (0.1, 0.26) },
    link coupler { points { A, B: (0.35, 0.32) }, mass: 0.8, inertia: 0.004, cg: (0.2, 0.33) },
    link rocker { points { B, O4 }, mass: 0.5, inertia: 0.001, cg: (0.37, 0.25) },
    joints { O2: revolute(ground, crank), A: revolute(crank, coupler),
             B: revolute(coupler, rocker), O4: revolute(rocker, ground) },
    input: O2 }";

/// An offset slider-crank (crank + RRP), the guide inclined.
const SLIDER_CRANK: &str = "pub struct SliderCrank {
    gravity: (0.0, -9.81),
    ground { O2: (0.0, 0.0) },
    link crank { points { O2, A: (0.04, 0.03) }, mass: 0.4, inertia: 0.0003, cg: (0.015, 0.01) },
    link rod { points { A, B: (0.24, 0.012) }, mass: 0.9, inertia: 0.004, cg: (0.14, 0.02) },
    link piston { points { B }, mass: 0.7, inertia: 0.0001, cg: (0.25, 0.012) },
    joints { O2: revolute(ground, crank), A: revolute(crank, rod), B: revolute(rod, piston),
             guide: prismatic(ground, piston) at B along (1.0, 0.1) },
    input: O2 }";

/// A slider-crank whose rod is too short for part of the turn (NoAssembly and change
/// points).
const SLIDER_CRANK_SHORT: &str = "pub struct Short {
    ground { O2: (0.0, 0.0) },
    link crank { points { O2, A: (0.0, 0.1) }, mass: 0.4, inertia: 0.0003, cg: (0.0, 0.05) },
    link rod { points { A, B: (0.03, 0.02) }, mass: 0.9, inertia: 0.004, cg: (0.02, 0.06) },
    link piston { points { B }, mass: 0.7, inertia: 0.0001, cg: (0.03, 0.02) },
    joints { O2: revolute(ground, crank), A: revolute(crank, rod), B: revolute(rod, piston),
             guide: prismatic(ground, piston) at B along (1.0, 0.0) },
    input: O2 }";

/// Two cranks, the second guiding an RRP slider (the guide moves: Coriolis).
const MOVING_GUIDE: &str = "pub struct MovingGuide {
    ground { O2: (0.0, 0.0), O4: (0.4, 0.0) },
    link crank { points { O2, A: (0.05, 0.05) }, mass: 0.3, inertia: 0.0002, cg: (0.02, 0.03) },
    link arm { points { O4, E: (0.4, 0.3) }, mass: 0.6, inertia: 0.002, cg: (0.41, 0.15) },
    link rod { points { A, B: (0.3, 0.2) }, mass: 0.5, inertia: 0.001, cg: (0.15, 0.12) },
    link block { points { B }, mass: 0.2, inertia: 0.00005, cg: (0.3, 0.2) },
    joints { O2: revolute(ground, crank), O4: revolute(ground, arm), A: revolute(crank, rod),
             B: revolute(rod, block), slide: prismatic(arm, block) at B along (-0.1, 0.3) },
    inputs: [O2, O4] }";

/// A driven slider and an RRR dyad.
const DRIVEN_SLIDER: &str = "pub struct DrivenSlider {
    ground { O4: (0.3, 0.0) },
    link slider { points { P: (0.0, 0.05) }, mass: 0.5, inertia: 0.0001, cg: (0.0, 0.05) },
    link rod { points { P, B: (0.25, 0.2) }, mass: 0.7, inertia: 0.003, cg: (0.12, 0.12) },
    link rocker { points { O4, B }, mass: 0.4, inertia: 0.001, cg: (0.28, 0.1) },
    joints { drive: prismatic(ground, slider) at P along (1.0, 0.2), P: revolute(slider, rod),
             B: revolute(rod, rocker), O4: revolute(ground, rocker) },
    input: drive }";

/// A crank driven on a crank (a revolute driver between two moving links: the general
/// joint screw) and an RRP dyad on the ground guide.
const CRANK_ON_CRANK: &str = "pub struct CrankOnCrank {
    ground { O2: (0.0, 0.0) },
    link crank { points { O2, A: (0.05, 0.02) }, mass: 0.3, inertia: 0.0002, cg: (0.02, 0.01) },
    link arm { points { E: (0.09, 0.06), A }, mass: 0.3, inertia: 0.0002, cg: (0.07, 0.04) },
    link rod { points { E, B: (0.35, 0.01) }, mass: 0.5, inertia: 0.001, cg: (0.2, 0.03) },
    link block { points { B }, mass: 0.2, inertia: 0.00005, cg: (0.35, 0.01) },
    joints { O2: revolute(ground, crank), A: revolute(crank, arm), E: revolute(arm, rod),
             B: revolute(rod, block), guide: prismatic(ground, block) at B along (1.0, -0.05) },
    inputs: [O2, A] }";

#[test]
fn lanes_match_the_scalar_kernels_and_mask_every_failure() {
    if skip() {
        return;
    }
    let mut rng = Rng(0xC0FFEE);
    let mut total = Worst::default();
    let mut kinds = std::collections::BTreeSet::new();
    for (text, batches, travel) in [
        (FOUR_BAR, 2000, 0.0),
        (FOUR_BAR_LIMITED, 2000, 0.0),
        (SLIDER_CRANK, 2000, 0.0),
        (SLIDER_CRANK_SHORT, 2000, 0.0),
        (MOVING_GUIDE, 2000, 0.0),
        (DRIVEN_SLIDER, 2000, 0.15),
        (CRANK_ON_CRANK, 2000, 0.0),
    ] {
        let rig = rig(text);
        for g in &rig.groups {
            kinds.insert(
                format!("{:?}", g.solver)
                    .split([' ', '{'])
                    .next()
                    .unwrap_or_default()
                    .to_string(),
            );
            if let Kernel::Driven(d) = g.kernel {
                kinds.insert(format!("pinned {}, from ground {}", d.pinned, d.from == 0));
            }
        }
        let extra = if rig.revolute[0] {
            near_change_points(&rig)
        } else {
            Vec::new()
        };
        let mut w = Worst::default();
        exercise(&rig, &mut rng, batches, &extra, travel, &mut w);
        println!(
            "{}: {w:?} ({} near change points)",
            text.split_whitespace().nth(2).unwrap_or(""),
            extra.len()
        );
        total.pos = total.pos.max(w.pos);
        total.rate = total.rate.max(w.rate);
        total.zhukovski = total.zhukovski.max(w.zhukovski);
        total.angle = total.angle.max(w.angle);
        total.compared += w.compared;
        total.masked += w.masked;
        total.failed += w.failed;
    }
    println!("all: {total:?}, kinds {kinds:?}");
    assert!(total.compared >= 140_000, "{total:?}");
    assert!(total.failed >= 20_000, "{total:?}");
    for k in ["DrivenRevolute", "DrivenPrismatic", "Rrr", "Rrp"] {
        assert!(kinds.contains(k), "{kinds:?}");
    }
    // Relative to each quantity's magnitude in its configuration (`compare`), over the
    // lanes not masked (κ < PRECISE_CONDITION).
    // measured worst 7.6e-15 (positions, near a tangency of SLIDER_CRANK_SHORT); 13×
    assert!(within(total.pos, 1e-13), "positions {total:?}");
    // measured worst 5.8e-14 (MOVING_GUIDE); 17×
    assert!(within(total.rate, 1e-12), "rates {total:?}");
    // measured worst 1.0e-13 (SLIDER_CRANK_SHORT); 10×
    assert!(within(total.zhukovski, 1e-12), "Zhukovski {total:?}");
    // measured worst 5.0e-15; 20×
    assert!(within(total.angle, 1e-13), "angles {total:?}");
}

#[test]
fn crank_angles_and_the_direct_problem_match_the_scalar_ones() {
    if skip() {
        return;
    }
    let mut rng = Rng(7);
    for _ in 0..10_000 {
        let q = L::from_fn(|_| rng.uniform(-40.0, 40.0));
        for sign in [1.0, -1.0] {
            let a = crank_angle_lanes(q, sign);
            for i in 0..LANES {
                assert_eq!(a.0[i], crank_angle(q.0[i], sign));
            }
        }
    }
    // acceleration_lanes against zhukovski::acceleration, Err lanes masked.
    let mut checked = 0;
    let mut worst = 0.0f64;
    for k in 0..20_000 {
        let pick = |rng: &mut Rng| match rng.next() % 16 {
            0 => 0.0,
            1 => -rng.uniform(0.0, 2.0),
            2 => f64::NAN,
            3 => f64::INFINITY,
            4 => 1e300,
            _ => rng.uniform(1e-3, 2.0),
        };
        let z = ZhukovskiLanes {
            inertia: L::from_fn(|_| pick(&mut rng)),
            inertia_derivative: L::from_fn(|_| {
                if k % 7 == 0 {
                    pick(&mut rng)
                } else {
                    rng.uniform(-3.0, 3.0)
                }
            }),
            moment: L::from_fn(|_| rng.uniform(-30.0, 30.0)),
        };
        let qd = L::from_fn(|_| rng.uniform(-100.0, 100.0));
        let driver = L::from_fn(|_| rng.uniform(-50.0, 50.0));
        let (qdd, mask) = acceleration_lanes(&z, qd, driver);
        for i in 0..LANES {
            let r = Reduced {
                inertia: z.inertia.0[i],
                inertia_derivative: z.inertia_derivative.0[i],
            };
            match acceleration(r, z.moment.0[i], qd.0[i], driver.0[i]) {
                Err(_) => assert!(mask[i], "{r:?} not masked"),
                Ok(a) => {
                    assert!(!mask[i], "{r:?} masked, scalar Ok");
                    worst = worst.max((a - qdd.0[i]).abs() / a.abs().max(1.0));
                    checked += 1;
                }
            }
        }
    }
    assert!(checked > 40_000);
    assert_eq!(worst, 0.0, "the same operations");
}

/// The two backends give the same bits: this instance's lanes plainly and within
/// [`with_simd`] (the AVX2 path's encoding) on [`Base`]; on [`Wide`], the same as the
/// [`Base`] instance's (`tests`), lane by lane, state by state.
#[test]
fn with_simd_gives_the_same_bits() {
    if skip() {
        return;
    }
    let rig = rig(FOUR_BAR);
    let mut rng = Rng(11);
    for _ in 0..200 {
        let batch: [Config; LANES] = std::array::from_fn(|_| rig.random(&mut rng, 0.0));
        let (a, ma) = run(|| rig.lanes(&batch, Level::Acceleration));
        if is_wide(module_path!()) {
            let base = super::tests::rig(FOUR_BAR);
            let (b, mb) = base.lanes(&batch, Level::Acceleration);
            assert_eq!(ma, mb);
            for (x, y) in a.iter().zip(&b) {
                for k in 0..LANES {
                    assert_eq!(x.lane(k), y.lane(k));
                }
            }
        } else {
            let lanes = || rig.lanes(&batch, Level::Acceleration);
            let (b, mb) = with_simd((), |()| lanes(), |()| lanes());
            assert_eq!(ma, mb);
            assert_eq!(a, b);
        }
    }
}

/// The four-bar `FOUR_BAR` as the generated code solves it: its plan's kernels with the
/// topology as constants (the joints rebuilt with their links as literals, as
/// `JointGeom::with_links` in the generated code).
mod four_bar {
    use super::super::*;
    use crate::kernel::constraints::{JointGeom, Level};
    use crate::kernel::kinematics::{solve_chain, solve_driven};
    use crate::kernel::screw::{Chain, Driven, JointScrew};
    use crate::solvers::zhukovski::ZhukovskiSums;
    use crate::MechError;

    const S0: Solver = Solver::DrivenRevolute {
        body: 1,
        joint: 0,
        input: 0,
    };
    const D0: Driven = Driven {
        from: 0,
        body: 1,
        screw: JointScrew {
            joint: 0,
            slide: false,
        },
        input: 0,
        pinned: true,
        track: false,
    };
    const S1: Solver = Solver::Rrr {
        b1: 2,
        b2: 3,
        ja: 1,
        jc: 2,
        jb: 3,
    };
    const C1: Chain = Chain {
        from: 1,
        to: 0,
        screws: [
            JointScrew {
                joint: 1,
                slide: false,
            },
            JointScrew {
                joint: 2,
                slide: false,
            },
            JointScrew {
                joint: 3,
                slide: false,
            },
        ],
        links: [2, 3],
        pivot: 1,
    };

    /// The numbers of the mechanism.
    pub struct Numbers {
        pub joints: [JointGeom; 4],
        pub links: [LinkGeom; 4],
        pub drawing: [LinkState; 4],
        pub scale: f64,
        pub sign: f64,
    }

    #[inline(always)]
    fn topology(j: &[JointGeom; 4]) -> [JointGeom; 4] {
        [
            j[0].with_links(0, 1, [false, true]),
            j[1].with_links(1, 2, [false, true]),
            j[2].with_links(2, 3, [false, false]),
            j[3].with_links(0, 3, [false, true]),
        ]
    }

    /// `reduced(q)`: the kinematics at q̇ = 1, q̈ = 0 and the sums, one configuration.
    #[inline(never)]
    pub fn scalar(n: &Numbers, q: f64) -> Result<(f64, f64), MechError> {
        let j = topology(&n.joints);
        let mut s = n.drawing;
        let drive = (&[q][..], &[1.0][..], &[0.0][..]);
        solve_driven(S0, &D0, &j, &mut s, drive, Level::Acceleration)?;
        solve_chain(
            S1,
            &C1,
            &j,
            &mut s,
            drive,
            n.sign,
            n.scale,
            Level::Acceleration,
        )?;
        let mut z = ZhukovskiSums::new();
        z.inertia_about_pivot(&n.links[1], &s[1]);
        z.inertia(&n.links[2], &s[2]);
        z.inertia_about_pivot(&n.links[3], &s[3]);
        Ok((z.reduced.inertia, z.reduced.inertia_derivative))
    }

    /// `reduced` of four configurations in lanes.
    #[inline(always)]
    fn lanes<B: Backend>(n: &Numbers, q: L<B>) -> (L<B>, L<B>, Mask) {
        let j = topology(&n.joints);
        let d = &n.drawing;
        let mut s = [
            LinkLanes::from_state(&d[0]),
            LinkLanes::from_state(&d[1]),
            LinkLanes::from_state(&d[2]),
            LinkLanes::from_state(&d[3]),
        ];
        let (qd, qdd) = (L::splat(1.0), L::splat(0.0));
        let m0 = solve_driven_lanes(
            S0,
            &D0,
            &j,
            &mut s,
            &[q],
            &[qd],
            &[qdd],
            Level::Acceleration,
        );
        let m1 = solve_chain_lanes(S1, &j, &mut s, n.sign, n.scale, Level::Acceleration);
        let mut z = ZhukovskiLanes::new();
        z.inertia_about_pivot(&n.links[1], &s[1]);
        z.inertia(&n.links[2], &s[2]);
        z.inertia_about_pivot(&n.links[3], &s[3]);
        (z.inertia, z.inertia_derivative, or(m0, m1))
    }

    /// The batch in lanes, masked lanes by the scalar route.
    #[inline(always)]
    fn batch_body<B: Backend>(n: &Numbers, q: &[f64], out: &mut [(f64, f64)]) {
        for (qc, oc) in q.chunks_exact(LANES).zip(out.chunks_exact_mut(LANES)) {
            let (i, d, m) = lanes(n, L::<B>::new([qc[0], qc[1], qc[2], qc[3]]));
            for k in 0..LANES {
                oc[k] = if m[k] {
                    scalar(n, qc[k]).unwrap_or((f64::NAN, f64::NAN))
                } else {
                    (i.0[k], d.0[k])
                };
            }
        }
    }

    /// [`batch_body`] compiled for the baseline.
    #[inline(never)]
    pub fn batch(n: &Numbers, q: &[f64], out: &mut [(f64, f64)]) {
        batch_body::<Base>(n, q, out)
    }

    /// [`batch_body`] with [`with_simd`].
    #[inline(never)]
    pub fn batch_simd(n: &Numbers, q: &[f64], out: &mut [(f64, f64)]) {
        with_simd(
            out,
            #[inline(always)]
            |out| batch_body::<Base>(n, q, out),
            #[inline(always)]
            |out| batch_body::<Wide>(n, q, out),
        )
    }

    /// A lane function alone, for the disassembly (`vsqrtpd`, `vmulpd` on ymm registers).
    #[inline(never)]
    pub fn probe_simd(x: &mut [f64; 2]) {
        with_simd(
            x,
            |_| unreachable!("run where the processor has AVX2"),
            #[inline(always)]
            |x| {
                let (a, b) = (L::<Wide>::splat(x[0]), L::<Wide>::splat(x[1]));
                x[0] = (a * b + a).sqrt().0[0];
                x[1] = sin_cos(a).0 .0[0];
            },
        )
    }
}

/// Nanoseconds per configuration of `reduced` (kinematics at q̇ = 1, q̈ = 0 and the inertia
/// sums) of the four-bar over 1024 configurations: scalar kernels in a loop, lanes on the
/// baseline, lanes with [`with_simd`]. Run with
/// `cargo test --release -p mech-core --lib lanes -- --ignored --nocapture`.
#[test]
#[ignore]
fn speed_of_the_four_bar_reduced() {
    if skip() {
        return;
    }
    use std::hint::black_box;
    use std::time::Instant;
    let r = rig(FOUR_BAR);
    let n = four_bar::Numbers {
        joints: std::array::from_fn(|k| r.inst.joints[k]),
        links: std::array::from_fn(|k| r.inst.links[k]),
        drawing: std::array::from_fn(|k| r.inst.drawing[k]),
        scale: r.inst.scale,
        sign: r.branches[1],
    };
    let count = 1024;
    let mut rng = Rng(3);
    let q: Vec<f64> = (0..count)
        .map(|_| rng.uniform(-std::f64::consts::PI, std::f64::consts::PI))
        .collect();
    let mut out = vec![(0.0, 0.0); count];
    let mut x = [0.3, 0.7];
    if simd_allowed() {
        four_bar::probe_simd(black_box(&mut x));
    }
    // The same results by every route.
    let reference: Vec<_> = q
        .iter()
        .map(|&q| four_bar::scalar(&n, q).unwrap())
        .collect();
    four_bar::batch(&n, &q, &mut out);
    let mut worst = 0.0f64;
    for (a, b) in out.iter().zip(&reference) {
        worst = worst
            .max((a.0 - b.0).abs() / b.0.abs())
            .max((a.1 - b.1).abs() / b.0.abs());
    }
    println!("lanes against scalar: worst relative {worst:.2e}");
    let time = |f: &mut dyn FnMut()| {
        let mut best = f64::INFINITY;
        for _ in 0..30 {
            let t = Instant::now();
            for _ in 0..50 {
                f();
            }
            best = best.min(t.elapsed().as_secs_f64() / (50 * count) as f64 * 1e9);
        }
        best
    };
    let scalar = time(&mut || {
        for (o, &q) in out.iter_mut().zip(&q) {
            *o = four_bar::scalar(black_box(&n), q).unwrap();
        }
        black_box(&out);
    });
    let lanes = time(&mut || {
        four_bar::batch(black_box(&n), &q, &mut out);
        black_box(&out);
    });
    let simd = time(&mut || {
        four_bar::batch_simd(black_box(&n), &q, &mut out);
        black_box(&out);
    });
    println!(
        "four-bar reduced, ns per configuration: scalar {scalar:.2}, lanes {lanes:.2} ({:.2}x), lanes with_simd {simd:.2} ({:.2}x)",
        scalar / lanes,
        scalar / simd
    );
}
