//! The numerical stress suite (not timed; runs in the test profile in seconds):
//!
//! - dead points: a non-Grashof four-bar driven to transmission angles 1e-1 … 1e-7 rad
//!   and past its toggle, against a textbook closed form and a 50-digit reference;
//! - scale: the same mechanisms in metres/kilograms and in millimetres/grams;
//! - mass ratios 1e-6 … 1e6 between neighbouring links (`from_params`, `from_model`);
//! - property-based tests over random four-bars, slider-cranks and Watt II six-bars:
//!   d'Alembert = virtual power = Zhukovski, the power balance, Newton–Euler of every link
//!   with R_ba = −R_ab, and generated = generic;
//! - bad input: the loader, `from_params`, and NaN / infinite / huge inputs.
//!
//! Stated error bounds (`mech_oracle::{position_error_bound, rate_error_bound}`), κ the
//! condition estimate of the constraint Jacobian: angles within 8 ε κ rad, positions within
//! 8 ε κ × L, and everything computed from velocities and accelerations (rates, motor
//! actions, reactions) within 16 ε κ² relative.

use crate::measure::{within, within_at};
use crate::mechanisms;
use crate::support;

use mech::model::{JointKind, Load, Model};
use mech::prelude::*;
use mech_core::solvers::instance::LinkParams;
use mech_oracle::{
    mechanism_text, position_error_bound, rate_error_bound, GenericLoads, GenericMechanism,
    LoadValue,
};
use mechanisms::*;
use proptest::prelude::*;
use support::as_vec;

type V = Vector2<f64>;
const EPS: f64 = f64::EPSILON;

/// This file and the example mechanisms, as text for the run-time loader.
const SELF: &str = include_str!("stress.rs");
const MECHANISMS: &str = include_str!("common/mechanisms.rs");

fn generic(source: &str, name: &str) -> GenericMechanism {
    GenericMechanism::from_rust_source(source, name).unwrap_or_else(|e| panic!("{name}: {e}"))
}

// =======================================================================================
// Results of one solve, in the model's order, for comparisons and balance checks
// =======================================================================================

/// Everything one solver says about one configuration, ordered like the model (moving
/// links, points, joints).
#[derive(Clone, Debug, Default)]
struct Snap {
    angle: Vec<f64>,
    omega: Vec<f64>,
    alpha: Vec<f64>,
    /// cg of every moving link, then every point.
    pos: Vec<V>,
    vel: Vec<V>,
    acc: Vec<V>,
    /// Reaction force (N) and prismatic moment (N·m, 0 for other joints) per joint.
    force: Vec<V>,
    moment: Vec<f64>,
    /// Motor actions by d'Alembert and by virtual power.
    driver: Vec<f64>,
    vp: Vec<f64>,
    /// One DOF: I*, dI*/dq, M*, and q̈ of the direct problem driven by `driver`.
    zhukovski: Option<[f64; 4]>,
}

impl Snap {
    fn push_link(&mut self, l: &LinkMotion) {
        self.angle.push(l.angle);
        self.omega.push(l.omega);
        self.alpha.push(l.alpha);
        self.push_point(&PointMotion {
            pos: l.cg,
            vel: l.cg_vel,
            acc: l.cg_acc,
        });
    }
    fn push_point(&mut self, p: &PointMotion) {
        self.pos.push(p.pos);
        self.vel.push(p.vel);
        self.acc.push(p.acc);
    }
    fn push_reaction(&mut self, force: V, moment: Option<f64>) {
        self.force.push(force);
        self.moment.push(moment.unwrap_or(0.0));
    }
}

fn snap_generic(
    g: &GenericMechanism,
    q: &[f64],
    qd: &[f64],
    qdd: &[f64],
    loads: &GenericLoads,
) -> Result<Snap, MechError> {
    let m = g.kinematics(q, qd, qdd)?;
    let f = g.kinetostatics(&m, loads)?;
    let mut s = Snap::default();
    m.links[1..].iter().for_each(|l| s.push_link(l));
    m.points.iter().for_each(|p| s.push_point(p));
    f.joints
        .iter()
        .for_each(|r| s.push_reaction(r.force, r.moment));
    s.driver = f.driver.clone();
    s.vp = g.driver_action(&m, loads)?;
    if g.dof() == 1 {
        let r = g.reduced(q[0])?;
        let ms = g.reduced_moment(q[0], loads)?;
        s.zhukovski = Some([
            r.inertia,
            r.inertia_derivative,
            ms,
            g.acceleration(q[0], qd[0], s.driver[0], loads)?,
        ]);
    }
    Ok(s)
}

/// The same snapshot from a generated struct (names taken from the equivalent model).
macro_rules! snap_generated {
    ($m:expr, $model:expr, $q:expr, $qd:expr, $qdd:expr, $loads:expr, one_dof = $one:tt) => {
        (|| -> Result<Snap, MechError> {
            let model: &Model = $model;
            let mo = $m.kinematics($q, $qd, $qdd)?;
            let f = $m.kinetostatics(&mo, &$loads)?;
            let mut s = Snap::default();
            model.links[1..].iter().for_each(|l| s.push_link(mo.link(&l.name).unwrap()));
            model.points.iter().for_each(|p| s.push_point(mo.point(&p.name).unwrap()));
            for j in &model.joints {
                let (fv, mom) = f.reaction(&j.name).unwrap();
                s.push_reaction(fv, mom);
            }
            s.driver = as_vec(&f.driver);
            s.vp = as_vec(&$m.driver_action(&mo, &$loads)?);
            snap_generated!(@zh $one, $m, s, $q, $qd, $loads);
            Ok(s)
        })()
    };
    (@zh true, $m:expr, $s:ident, $q:expr, $qd:expr, $loads:expr) => {{
        let r = $m.reduced($q)?;
        let ms = $m.reduced_moment($q, &$loads)?;
        $s.zhukovski = Some([r.inertia, r.inertia_derivative, ms, $m.acceleration($q, $qd, $s.driver[0], &$loads)?]);
    }};
    (@zh false, $($rest:tt)*) => {{}};
}

fn amax(v: &[f64]) -> f64 {
    v.iter().fold(0.0f64, |a, x| a.max(x.abs()))
}
fn vmax(v: &[V]) -> f64 {
    v.iter().fold(0.0f64, |a, x| a.max(x.amax()))
}

/// Per kind: the unit factor applied to `b` before comparing it with `a`.
#[derive(Clone, Copy)]
struct Units {
    length: f64,
    force: f64,
    torque: f64,
    /// Motor action (torque or force), I*, dI*/dq, M*, q̈ of the direct problem.
    driver: f64,
    inertia: f64,
    inertia_derivative: f64,
    qdd: f64,
}
const SAME: Units = Units {
    length: 1.0,
    force: 1.0,
    torque: 1.0,
    driver: 1.0,
    inertia: 1.0,
    inertia_derivative: 1.0,
    qdd: 1.0,
};

/// `a` and `b` (in units `u`) agree to `rel` of the largest entry of each kind.
#[track_caller]
fn agree(ctx: &str, a: &Snap, b: &Snap, u: Units, rel: f64) {
    // Measured per caller and kind (`tests/common/measure.rs`).
    let at = std::panic::Location::caller();
    let key = |what: &str| {
        format!(
            "from {}:{} {}",
            at.file(),
            at.line(),
            what.split('[').next().unwrap()
        )
    };
    let close = |what: &str, x: f64, y: f64, scale: f64| {
        assert!(
            within_at(&key(what), (x - y).abs(), rel * scale.max(1e-300)),
            "{ctx}: {what}: {x:.17e} vs {y:.17e} (scale {scale:e}, rel {rel:e})"
        );
    };
    let scalars = |what: &str, x: &[f64], y: &[f64], k: f64| {
        let scale = amax(x);
        for (i, (p, q)) in x.iter().zip(y).enumerate() {
            close(&format!("{what}[{i}]"), *p, q / k, scale);
        }
    };
    let vectors = |what: &str, x: &[V], y: &[V], k: f64| {
        let scale = vmax(x);
        for (i, (p, q)) in x.iter().zip(y).enumerate() {
            close(&format!("{what}[{i}].x"), p.x, q.x / k, scale);
            close(&format!("{what}[{i}].y"), p.y, q.y / k, scale);
        }
    };
    for (i, (p, q)) in a.angle.iter().zip(&b.angle).enumerate() {
        let d = (p - q).rem_euclid(std::f64::consts::TAU);
        assert!(
            within_at(
                &key("angle"),
                d.min(std::f64::consts::TAU - d),
                rel * std::f64::consts::PI
            ),
            "{ctx}: angle[{i}] {p} vs {q}"
        );
    }
    scalars("omega", &a.omega, &b.omega, 1.0);
    scalars("alpha", &a.alpha, &b.alpha, 1.0);
    vectors("pos", &a.pos, &b.pos, u.length);
    vectors("vel", &a.vel, &b.vel, u.length);
    vectors("acc", &a.acc, &b.acc, u.length);
    vectors("reaction", &a.force, &b.force, u.force);
    let mscale = amax(&a.moment).max(vmax(&a.force) * vmax(&a.pos[a.angle.len()..]));
    for (i, (p, q)) in a.moment.iter().zip(&b.moment).enumerate() {
        close(&format!("moment[{i}]"), *p, q / u.torque, mscale);
    }
    // A motor action is a sum of moments (a torque) or of forces: its roundoff is that of
    // the forces times their lever arms, as for the prismatic moments above.
    let dscale = amax(&a.driver).max(amax(&a.vp)).max(mscale);
    for i in 0..a.driver.len() {
        close("driver", a.driver[i], b.driver[i] / u.driver, dscale);
        close(
            "driver (virtual power)",
            a.vp[i],
            b.vp[i] / u.driver,
            dscale,
        );
    }
    if let (Some(x), Some(y)) = (a.zhukovski, b.zhukovski) {
        let iscale = x[0].abs().max(x[1].abs());
        close("I*", x[0], y[0] / u.inertia, iscale);
        close("dI*/dq", x[1], y[1] / u.inertia_derivative, iscale);
        close("M*", x[2], y[2] / u.driver, x[2].abs().max(dscale));
        close(
            "q'' (direct)",
            x[3],
            y[3] / u.qdd,
            x[3].abs().max(dscale.max(x[2].abs()) / x[0].abs()),
        );
    }
}

/// The balances every solution must satisfy, to `rel` of the largest term of each:
/// d'Alembert = virtual power (= Zhukovski I* q̈ + ½ I*′ q̇² − M* for one DOF); Newton–Euler
/// of every moving link with the reported reactions (+R on b, −R on a); the power balance
/// Σ Q q̇ + P_loads + P_gravity = dT/dt, dT/dt = Σ (m v_G·a_G + I ω α).
#[track_caller]
fn balances(
    ctx: &str,
    model: &Model,
    s: &Snap,
    loads: &[LoadValue],
    qd: &[f64],
    qdd: &[f64],
    rel: f64,
) {
    // Measured per caller and balance (`tests/common/measure.rs`).
    let at = std::panic::Location::caller();
    let key = |what: &str| format!("from {}:{} {what}", at.file(), at.line());
    let nl = model.links.len() - 1;
    let g = model
        .gravity
        .map(|g| V::new(g[0], g[1]))
        .unwrap_or_else(V::zeros);
    let point = |p: usize| s.pos[nl + p];
    // Motor actions.
    let dscale = amax(&s.driver)
        .max(vmax(&s.force) * vmax(&s.pos))
        .max(amax(&s.moment));
    for k in 0..s.driver.len() {
        assert!(
            within_at(&key("vp"), (s.driver[k] - s.vp[k]).abs(), rel * dscale),
            "{ctx}: d'Alembert {} vs virtual power {}",
            s.driver[k],
            s.vp[k]
        );
    }
    if let Some([i, di, ms, acc]) = s.zhukovski {
        let zh = i * qdd[0] + 0.5 * di * qd[0] * qd[0] - ms;
        let scale = dscale
            .max((i * qdd[0]).abs())
            .max((0.5 * di * qd[0] * qd[0]).abs())
            .max(ms.abs());
        assert!(
            within_at(&key("zhukovski"), (zh - s.driver[0]).abs(), rel * scale),
            "{ctx}: Zhukovski {zh} vs d'Alembert {}",
            s.driver[0]
        );
        assert!(
            within_at(
                &key("direct"),
                (acc - qdd[0]).abs(),
                rel * scale / i.abs().max(1e-300) + rel * qdd[0].abs()
            ),
            "{ctx}: direct q'' {acc} vs {}",
            qdd[0]
        );
    }
    // Newton–Euler of every moving link, about its cg.
    for l in 1..model.links.len() {
        let link = &model.links[l];
        let (m, inertia) = (link.mass.unwrap_or(0.0), link.inertia);
        let rg = s.pos[l - 1];
        let mut terms: Vec<(V, f64)> =
            vec![(g * m, 0.0), (-s.acc[l - 1] * m, -inertia * s.alpha[l - 1])];
        let mut at = |f: V, p: V, t: f64| terms.push((f, (p - rg).perp(&f) + t));
        for (k, ld) in model.loads.iter().enumerate() {
            match (ld, loads[k]) {
                (
                    Load::Force {
                        link: ll, point: p, ..
                    },
                    LoadValue::Force(f),
                ) if *ll == l => at(f, point(*p), 0.0),
                (Load::Torque { link: ll, .. }, LoadValue::Torque(t)) if *ll == l => {
                    at(V::zeros(), rg, t)
                }
                _ => {}
            }
        }
        for (j, jt) in model.joints.iter().enumerate() {
            let sign = if jt.b == l {
                1.0
            } else if jt.a == l {
                -1.0
            } else {
                continue;
            };
            let p = point(jt.point);
            at(s.force[j] * sign, p, s.moment[j] * sign);
            if let Some(k) = model.inputs.iter().position(|&i| i == j) {
                match jt.kind {
                    JointKind::Revolute => at(V::zeros(), p, s.driver[k] * sign),
                    _ => {
                        // The axis turns with link a.
                        let th = s.angle.get(jt.a.wrapping_sub(1)).copied();
                        let rot = match th {
                            Some(t) => t - model.reference_angle(jt.a),
                            None => 0.0,
                        };
                        let u = V::new(jt.axis[0], jt.axis[1]).normalize();
                        let u = V::new(
                            rot.cos() * u.x - rot.sin() * u.y,
                            rot.sin() * u.x + rot.cos() * u.y,
                        );
                        at(u * (s.driver[k] * sign), p, 0.0);
                    }
                }
            }
        }
        let sum_f: V = terms.iter().map(|t| t.0).sum();
        let sum_m: f64 = terms.iter().map(|t| t.1).sum();
        let fscale = terms.iter().fold(0.0f64, |a, t| a.max(t.0.amax()));
        let mscale = terms.iter().fold(0.0f64, |a, t| a.max(t.1.abs()));
        assert!(
            within_at(&key("sum F"), sum_f.amax(), rel * fscale),
            "{ctx}: link {}: ΣF = {sum_f:?} (largest term {fscale:e})",
            link.name
        );
        assert!(
            within_at(
                &key("sum M"),
                sum_m.abs(),
                rel * mscale.max(fscale * model.scale())
            ),
            "{ctx}: link {}: ΣM = {sum_m:e} (largest term {mscale:e})",
            link.name
        );
    }
    // Power balance.
    let mut terms = vec![];
    for k in 0..s.driver.len() {
        terms.push(s.driver[k] * qd[k]);
    }
    for (k, ld) in model.loads.iter().enumerate() {
        match (ld, loads[k]) {
            (Load::Force { point: p, .. }, LoadValue::Force(f)) => {
                terms.push(f.dot(&s.vel[nl + p]))
            }
            (Load::Torque { link: l, .. }, LoadValue::Torque(t)) => terms.push(t * s.omega[l - 1]),
            _ => unreachable!(),
        }
    }
    for l in 1..model.links.len() {
        let (m, i) = (model.links[l].mass.unwrap_or(0.0), model.links[l].inertia);
        terms.push(m * g.dot(&s.vel[l - 1]));
        terms.push(-m * s.vel[l - 1].dot(&s.acc[l - 1]));
        terms.push(-i * s.omega[l - 1] * s.alpha[l - 1]);
    }
    let sum: f64 = terms.iter().sum();
    assert!(
        within_at(&key("power"), sum.abs(), rel * amax(&terms)),
        "{ctx}: power balance {sum:e} (largest term {:e})",
        amax(&terms)
    );
}

// =======================================================================================
// Dead points
// =======================================================================================

mechanism! {
    /// Non-Grashof four-bar (a = 1, b = 0.5, c = 0.8, d = 1.2 m): the crank O2 is limited
    /// to q ≤ q_lim ≈ 1.25297 rad, where coupler and rocker are in line (the toggle).
    pub struct Toggle {
        gravity: (0.0, -9.81),
        ground { O2: (0.0, 0.0), O4: (1.2, 0.0) },
        link crank { points { O2, A: (0.7648421872844884, 0.644217687237691) }, mass: 2.0, inertia: 0.2, cg: (0.38, 0.32) },
        link coupler { points { A, B: (1.2402862761794526, 0.7989849910677878) }, mass: 1.0, inertia: 0.03, cg: (1.0, 0.72) },
        link rocker { points { O4, B }, mass: 1.5, inertia: 0.08, cg: (1.22, 0.4) },
        joints {
            O2: revolute(ground, crank),
            A: revolute(crank, coupler),
            B: revolute(coupler, rocker),
            O4: revolute(ground, rocker),
        },
        input: O2,
        loads { resist: torque on rocker },
    }
}

/// Transmission angle δ (rad, the deviation of coupler and rocker from the line), the crank
/// angle q (f64) there, and the 50-digit reference at exactly that q with q̇ = 1 rad/s,
/// q̈ = 0.5 rad/s², resist = −3 N·m: ω and α of the coupler, the crank torque. Computed
/// by `tools/reference.py` (mpmath, Newton with continuation from the drawing) on this
/// drawing's f64 numbers.
const TOGGLE_TRUTH: [(f64, f64, f64, f64, f64); 7] = [
    (
        1e-1,
        1.2512190399336858,
        -17.194334127089157,
        -5003.7756718130878,
        19778.892236879795,
    ),
    (
        1e-2,
        1.2529550775840586,
        -175.00230201085202,
        -4997661.2983885556,
        190354213.72657791,
    ),
    (
        1e-3,
        1.2529724474132404,
        -1753.3247722672932,
        -4997596812.1703655,
        1896302312687.5713,
    ),
    (
        1e-4,
        1.2529726211124785,
        -17536.574838394076,
        -4997597340083.5594,
        18955833771007519.0,
    ),
    (
        1e-5,
        1.2529726228494709,
        -175369.71300520342,
        -4997651748569531.0,
        1.8955389900881929e20,
    ),
    (
        1e-6,
        1.2529726228668407,
        -1754137.316598313,
        -5.0013875206646059e18,
        1.8974212623384052e24,
    ),
    (
        1e-7,
        1.2529726228670146,
        -18940244.411004323,
        -6.2958769448906318e21,
        2.5789993343654491e28,
    ),
];
/// The next f64 crank angles are past the toggle: the 50-digit Newton finds no assembly.
const PAST_TOGGLE: [f64; 4] = [1.2529726228670164, 1.25297262287, 1.2539726228670164, 2.0];

/// The drawing's lengths (from its f64 points, as the solvers compute them).
fn toggle_lengths() -> (f64, f64, f64, V) {
    let (o4, pa, pb) = (
        V::new(1.2, 0.0),
        V::new(0.7648421872844884, 0.644217687237691),
        V::new(1.2402862761794526, 0.7989849910677878),
    );
    (pa.norm(), (pb - pa).norm(), (pb - o4).norm(), o4)
}

/// Textbook four-bar (vector loop a e^{iθ2} + b e^{iθ3} = d + c e^{iθ4}, Freudenstein):
/// θ3, θ4, ω3, ω4, α3, α4 for crank angle q, ω2, α2, with B on the left of A → O4.
fn textbook(a: f64, b: f64, c: f64, o4: V, q: f64, w2: f64, a2: f64) -> [f64; 6] {
    let ex = |t: f64| V::new(t.cos(), t.sin());
    let pa = ex(q) * a;
    let dv = o4 - pa;
    let f = dv.norm();
    let e = dv / f;
    let along = (f * f + b * b - c * c) / (2.0 * f);
    let h = (b * b - along * along).max(0.0).sqrt();
    let pb = pa + e * along + V::new(-e.y, e.x) * h;
    let t3 = (pb.y - pa.y).atan2(pb.x - pa.x);
    let t4 = (pb.y - o4.y).atan2(pb.x - o4.x);
    let w3 = -a * w2 * (q - t4).sin() / (b * (t3 - t4).sin());
    let w4 = a * w2 * (q - t3).sin() / (c * (t4 - t3).sin());
    // Second derivative: b α3 e3 − c α4 e4 = −a α2 e2 − i S, S = a ω2² e2 + b ω3² e3 − c ω4² e4.
    let sv = ex(q) * (a * w2 * w2) + ex(t3) * (b * w3 * w3) - ex(t4) * (c * w4 * w4);
    let r = -ex(q) * (a * a2) + V::new(sv.y, -sv.x);
    let im = |t: f64, z: V| -t.sin() * z.x + t.cos() * z.y; // Im(e^{-it} z)
    [
        t3,
        t4,
        w3,
        w4,
        im(t4, r) / (b * (t3 - t4).sin()),
        -im(t3, r) / (c * (t4 - t3).sin()),
    ]
}

/// Driven towards its toggle, every result of the generated and the generic solver is
/// within its stated bound of the 50-digit reference (ω, α, torque by d'Alembert and by
/// virtual power: 16 ε κ² relative) and of the textbook solution (angles: twice 8 ε κ, as
/// the textbook in f64 has the same conditioning; rates: twice 16 ε κ²), or is
/// `Singular`. κ is the generic solver's condition estimate at the same q (the generated
/// API does not report it).
#[test]
fn dead_point_results_are_within_the_stated_bound_or_singular() {
    let gen = Toggle::new();
    let any = generic(SELF, "Toggle").with_max_error(f64::MAX).unwrap();
    let strict = generic(SELF, "Toggle");
    let (a, b, c, o4) = toggle_lengths();
    let loads = ToggleLoads { resist: -3.0 };
    let mut gl = any.loads();
    gl.set_by_name("resist", &[-3.0]);
    for &(delta, q, w3, a3, torque) in &TOGGLE_TRUTH {
        let ctx = format!("transmission angle {delta:e} rad, q = {q:?}");
        let tb = textbook(a, b, c, o4, q, 1.0, 0.5);
        // The permissive generic solver always answers here (κ < 1e10), within its bound.
        let m = any
            .kinematics(&[q], &[1.0], &[0.5])
            .unwrap_or_else(|e| panic!("{ctx}: {e}"));
        let kappa = m.condition;
        let (pb, rb) = (position_error_bound(kappa), rate_error_bound(kappa));
        assert_eq!(m.error_bound(), rb);
        assert!(
            kappa > 0.5 / delta && kappa < 50.0 / delta,
            "{ctx}: κ = {kappa:e}"
        );
        let check = |who: &str, th: [f64; 2], w: [f64; 2], al: [f64; 2], t: f64, vp: f64| {
            for i in 0..2 {
                assert!(
                    within((th[i] - tb[i]).abs(), 2.0 * pb + 4.0 * EPS), // measured worst 0.15 of the bound (be05608); the stated bound (8 ε κ), the claim under test
                    "{ctx}: {who}: θ{} {} vs textbook {} (bound {pb:e})",
                    i + 3,
                    th[i],
                    tb[i]
                );
                let ws = tb[2].abs().max(tb[3].abs());
                let als = tb[4].abs().max(tb[5].abs());
                assert!(
                    within((w[i] - tb[2 + i]).abs(), 2.0 * rb * ws), // measured worst 0.086 of the bound (be05608); the stated bound (16 ε κ²), the claim under test
                    "{ctx}: {who}: ω{} {} vs textbook {} (bound {rb:e})",
                    i + 3,
                    w[i],
                    tb[2 + i]
                );
                assert!(
                    within((al[i] - tb[4 + i]).abs(), 2.0 * rb * als), // measured worst 0.25 of the bound (be05608); the stated bound
                    "{ctx}: {who}: α{} {} vs textbook {}",
                    i + 3,
                    al[i],
                    tb[4 + i]
                );
            }
            assert!(
                within((w[0] - w3).abs(), rb * w3.abs()), // measured worst 0.11 of the bound (be05608); the stated bound
                "{ctx}: {who}: ω3 {} vs reference {w3} (bound {rb:e})",
                w[0]
            );
            assert!(
                within((al[0] - a3).abs(), rb * a3.abs()), // measured worst 0.32 of the bound (be05608); the stated bound
                "{ctx}: {who}: α3 {} vs reference {a3}",
                al[0]
            );
            assert!(
                within((t - torque).abs(), rb * torque.abs()), // measured worst 0.43 of the bound (be05608); the stated bound
                "{ctx}: {who}: torque {t:e} vs reference {torque:e} (bound {rb:e})"
            );
            assert!(
                within((vp - torque).abs(), rb * torque.abs()), // measured worst 0.43 of the bound (be05608); the stated bound
                "{ctx}: {who}: virtual-power torque {vp:e} vs reference {torque:e}"
            );
        };
        let (l3, l4) = (m.link("coupler").unwrap(), m.link("rocker").unwrap());
        let f = any.kinetostatics(&m, &gl).unwrap();
        let vp = any.driver_action(&m, &gl).unwrap();
        check(
            "generic",
            [l3.angle, l4.angle],
            [l3.omega, l4.omega],
            [l3.alpha, l4.alpha],
            f.driver[0],
            vp[0],
        );
        // The pose alone is within its (much smaller) bound.
        let p = any.pose(&[q]).unwrap();
        assert!(
            within(
                (p.link("coupler").unwrap().angle - tb[0]).abs(),
                2.0 * p.error_bound() + 4.0 * EPS
            ), // measured worst 0.14 of the bound (be05608); the stated bound
            "{ctx}: pose"
        );

        // The default generic solver: within its bound, or Singular once 16 ε κ² > 1e-6.
        match strict.kinematics(&[q], &[1.0], &[0.5]) {
            Ok(sm) => assert!(
                sm.error_bound() <= strict.max_error() && sm.links == m.links,
                "{ctx}"
            ),
            Err(MechError::Singular { condition }) => assert!(
                rate_error_bound(condition) > strict.max_error(),
                "{ctx}: {condition:e}"
            ),
            Err(e) => panic!("{ctx}: generic: {e}"),
        }

        // The generated solver: within the same bound, or Singular.
        match gen.kinematics(q, 1.0, 0.5) {
            Ok(gm) => {
                let (l3, l4) = (gm.links.coupler, gm.links.rocker);
                let f = gen.kinetostatics(&gm, &loads).unwrap();
                let vp = gen.driver_action(&gm, &loads).unwrap();
                check(
                    "generated",
                    [l3.angle, l4.angle],
                    [l3.omega, l4.omega],
                    [l3.alpha, l4.alpha],
                    f.driver,
                    vp,
                );
            }
            // Refused only close to the toggle (SINGULAR_CONDITION = 1e6 on the groups' κ).
            Err(MechError::Singular { .. }) => {
                assert!(kappa > 1e5, "{ctx}: generated Singular at κ = {kappa:e}")
            }
            Err(e) => panic!("{ctx}: generated: {e}"),
        }
    }

    // Past the toggle there is no assembly: an error from both, never a number.
    for q in PAST_TOGGLE {
        match gen.kinematics(q, 1.0, 0.0) {
            Err(MechError::NoAssembly | MechError::Singular { .. }) => {}
            other => panic!("generated past the toggle, q = {q}: {other:?}"),
        }
        match strict.kinematics(&[q], &[1.0], &[0.0]) {
            Err(MechError::NoAssembly | MechError::Singular { .. }) => {}
            other => panic!("generic past the toggle, q = {q}: {other:?}"),
        }
        assert!(
            matches!(
                strict.pose(&[q]),
                Err(MechError::NoAssembly | MechError::Singular { .. })
            ) || q == PAST_TOGGLE[0]
        );
    }
}

/// `docs/conventions.md#solver-requirements`: "near a dead point the result is either
/// accurate or `Singular`": every generated answer near the toggle is within 1e-3 of the
/// reference (ω, measured far inside it, within 2e-4). (Regression: with `SINGULAR_CONDITION` = 1e10 the generated four-bar
/// answered at a transmission angle of 1e-7 rad, κ ≈ 1.5e7, with ω 2.2 % and the torque
/// 9 % off and no error; rate errors grow as ε κ², and the threshold is now 1e6.)
#[test]
fn generated_toggle_is_accurate_to_a_thousandth_or_singular() {
    let gen = Toggle::new();
    let loads = ToggleLoads { resist: -3.0 };
    let mut answered = 0;
    for &(delta, q, w3, _, torque) in &TOGGLE_TRUTH {
        match gen.kinematics(q, 1.0, 0.5) {
            Ok(m) => {
                answered += 1;
                let t = gen.kinetostatics(&m, &loads).unwrap().driver;
                assert!(
                    within((m.links.coupler.omega - w3).abs(), 2e-4 * w3.abs()), // measured worst 3.9e-6 (be05608); 100× (the requirement is 1e-3)
                    "δ = {delta:e}: ω {} vs {w3}",
                    m.links.coupler.omega
                );
                assert!(
                    within((t - torque).abs(), 1e-3 * torque.abs()), // measured worst 1.6e-5 (be05608); 100×
                    "δ = {delta:e}: torque {t:e} vs {torque:e}"
                );
            }
            Err(MechError::Singular { .. }) => {}
            Err(e) => panic!("{e}"),
        }
    }
    // Refused as `Singular` only close to the toggle: 5 of the 7 answer (δ ≥ 1e-5 rad,
    // be05608); fewer would leave the claim checked on fewer angles.
    println!(
        "COUNT generated toggle: {answered} of {} answered",
        TOGGLE_TRUTH.len()
    );
    assert!(answered >= 5, "only {answered} answers near the toggle");
}

// =======================================================================================
// Scale: metres and kilograms against millimetres and grams
// =======================================================================================

mechanism! {
    /// `SliderCrank` of tests/common/mechanisms.rs in mm, g, g·mm², mm/s².
    pub struct SliderCrankMm {
        gravity: (0.0, -9810.0),
        ground { O2: (0.0, 0.0) },
        link crank {
            points { O2, A: (42.132444371543794, 35.353318532759664) },
            mass: 1100.0, inertia: 1350000.0, cg: (6.1767322404058704, 9.751819257468356),
        },
        link rod {
            points { A, B: (231.03914733547787, 15.0) },
            mass: 850.0, inertia: 3200000.0, cg: (108.1811584228632, 32.260201631147026),
        },
        link piston {
            points { B },
            mass: 620.0, inertia: 360000.0, cg: (227.03914733547786, 12.5),
        },
        joints {
            O2: revolute(ground, crank),
            A: revolute(crank, rod),
            B: revolute(rod, piston),
            guide: prismatic(ground, piston) at B along (1.0, 0.0),
        },
        input: O2,
        loads {
            gas: force on piston at B,
            shaft: torque on crank,
        },
    }
}

mechanism! {
    /// `HydraulicLever` of tests/common/mechanisms.rs (a prismatic input, solved by the
    /// Newton fallback) in mm, g, g·mm², mm/s².
    pub struct HydraulicLeverMm {
        gravity: (0.0, -9810.0),
        ground { O: (0.0, 0.0), C0: (120.0, -420.0) },
        link lever {
            points { O, L: (260.0, 40.0), E: (720.0, 150.0) },
            mass: 4800.0, inertia: 230000000.0, cg: (328.57030337443366, 89.90303521257006),
        },
        link cylinder {
            points { C0 },
            mass: 3200.0, inertia: 45000000.0, cg: (166.58585852523136, -266.9321791313827),
        },
        link rod {
            points { L },
            mass: 1300.0, inertia: 12000000.0, cg: (216.3257576325956, -103.50108206432876),
        },
        joints {
            O: revolute(ground, lever),
            C0: revolute(ground, cylinder),
            L: revolute(lever, rod),
            stroke: prismatic(cylinder, rod) at L along (0.29116161578269606, 0.9566738804288584),
        },
        input: stroke,
        loads {
            payload: force on lever at E,
            damper: torque on lever,
        },
    }
}

/// mm/g against m/kg: lengths ×1e3, forces (g·mm/s²) ×1e6, torques (g·mm²/s²) ×1e9.
const MM_G: Units = Units {
    length: 1e3,
    force: 1e6,
    torque: 1e9,
    driver: 1e9,
    inertia: 1e9,
    inertia_derivative: 1e9,
    qdd: 1.0,
};
/// The same for a prismatic input: the actuator force ×1e6, I* (g) ×1e3, dI*/dq (g/mm) ×1,
/// M* (g·mm/s²) ×1e6, q̈ (mm/s²) ×1e3.
const MM_G_PRISMATIC: Units = Units {
    driver: 1e6,
    inertia: 1e3,
    inertia_derivative: 1.0,
    qdd: 1e3,
    ..MM_G
};

/// The same machine in metres and kilograms and in millimetres and grams gives the same
/// results after unit conversion, to 2e-14 … 1e-13 relative (largest entry of each kind), with
/// the generated solvers (closed form and Newton fallback) and with the generic solver.
#[test]
fn metres_and_millimetres_agree() {
    let (m, mm) = (SliderCrank::new(), SliderCrankMm::new());
    let (g, gmm) = (
        generic(MECHANISMS, "SliderCrank"),
        generic(SELF, "SliderCrankMm"),
    );
    let loads = SliderCrankLoads {
        gas: V::new(-2500.0, 40.0),
        shaft: 12.0,
    };
    let loads_mm = SliderCrankMmLoads {
        gas: loads.gas * 1e6,
        shaft: loads.shaft * 1e9,
    };
    let (mut gl, mut glmm) = (g.loads(), gmm.loads());
    gl.set_by_name("gas", &[-2500.0, 40.0]);
    gl.set_by_name("shaft", &[12.0]);
    glmm.set_by_name("gas", &[-2500.0e6, 40.0e6]);
    glmm.set_by_name("shaft", &[12.0e9]);
    for (q, qd, qdd) in [(0.3, 150.0, -20.0), (2.0, -90.0, 300.0), (4.4, 60.0, 0.0)] {
        let ctx = format!("slider-crank q = {q}");
        let a = snap_generated!(m, g.model(), q, qd, qdd, loads, one_dof = true).unwrap();
        let b = snap_generated!(mm, gmm.model(), q, qd, qdd, loads_mm, one_dof = true).unwrap();
        // measured worst 4.2e-16 over the kinds (be05608); 100×
        agree(&ctx, &a, &b, MM_G, 2e-14);
        let c = snap_generic(&g, &[q], &[qd], &[qdd], &gl).unwrap();
        let d = snap_generic(&gmm, &[q], &[qd], &[qdd], &glmm).unwrap();
        // measured worst 4.2e-16 over the kinds (be05608); 100×
        agree(&format!("{ctx} (generic)"), &c, &d, MM_G, 2e-14);
        agree(
            &format!("{ctx} (generic vs generated)"),
            &a,
            &c,
            SAME,
            2e-14, // measured worst 2.8e-16 over the kinds (be05608); 100×
        );
    }

    let (m, mm) = (HydraulicLever::new(), HydraulicLeverMm::new());
    let (g, gmm) = (
        generic(MECHANISMS, "HydraulicLever"),
        generic(SELF, "HydraulicLeverMm"),
    );
    let loads = HydraulicLeverLoads {
        payload: V::new(300.0, -2000.0),
        damper: -40.0,
    };
    let loads_mm = HydraulicLeverMmLoads {
        payload: loads.payload * 1e6,
        damper: loads.damper * 1e9,
    };
    let (mut gl, mut glmm) = (g.loads(), gmm.loads());
    gl.set_by_name("payload", &[300.0, -2000.0]);
    gl.set_by_name("damper", &[-40.0]);
    glmm.set_by_name("payload", &[300.0e6, -2000.0e6]);
    glmm.set_by_name("damper", &[-40.0e9]);
    for (q, qd, qdd) in [(-0.08, 0.2, -1.5), (0.0, -0.35, 0.0), (0.11, 0.05, 2.5)] {
        let ctx = format!("hydraulic lever stroke = {q} m");
        let a = snap_generated!(m, g.model(), q, qd, qdd, loads, one_dof = true).unwrap();
        let b = snap_generated!(
            mm,
            gmm.model(),
            q * 1e3,
            qd * 1e3,
            qdd * 1e3,
            loads_mm,
            one_dof = true
        )
        .unwrap();
        // measured worst 1.6e-15 over the kinds (be05608); 100×
        agree(&ctx, &a, &b, MM_G_PRISMATIC, 1e-13);
        let c = snap_generic(&g, &[q], &[qd], &[qdd], &gl).unwrap();
        let d = snap_generic(&gmm, &[q * 1e3], &[qd * 1e3], &[qdd * 1e3], &glmm).unwrap();
        // measured worst 6.7e-16 over the kinds (be05608); 100×
        agree(&format!("{ctx} (generic)"), &c, &d, MM_G_PRISMATIC, 5e-14);
        agree(
            &format!("{ctx} (generic vs generated)"),
            &a,
            &c,
            SAME,
            1e-13, // measured worst 1.6e-15 over the kinds (be05608); 100×
        );
    }
}

// =======================================================================================
// Mass ratios
// =======================================================================================

/// Masses and inertias of neighbouring links of the Watt II six-bar in ratios 1e-6 … 1e6
/// (every other link scaled by r), set at run time with `from_params` (generated) and
/// `from_model` (generic): the two agree, and every balance holds, to 1e-13 relative.
#[test]
fn mass_ratios_from_1e_minus_6_to_1e6() {
    let base = generic(MECHANISMS, "Watt2");
    let t = support::truth("watt2");
    let configs: Vec<[f64; 3]> = t["configs"]
        .as_array()
        .unwrap()
        .iter()
        .step_by(3)
        .map(|c| {
            [
                c["q"].as_f64().unwrap(),
                c["qd"].as_f64().unwrap(),
                c["qdd"].as_f64().unwrap(),
            ]
        })
        .collect();
    for r in [1e-6, 1e-3, 1.0, 1e3, 1e6] {
        let mut p = Watt2Params::default();
        let mut model = base.model().clone();
        let scale = |lp: &mut LinkParams, k: usize| {
            let f = if k % 2 == 0 { r } else { 1.0 };
            lp.mass *= f;
            lp.inertia *= f;
        };
        for (k, lp) in [
            &mut p.links.crank,
            &mut p.links.coupler,
            &mut p.links.rocker,
            &mut p.links.link5,
            &mut p.links.rocker6,
        ]
        .into_iter()
        .enumerate()
        {
            scale(lp, k);
            let l = &mut model.links[k + 1];
            l.mass = Some(lp.mass);
            l.inertia = lp.inertia;
        }
        let gen = Watt2::from_params(p).unwrap();
        let g = GenericMechanism::from_model(model).unwrap();
        let loads = Watt2Loads {
            output: V::new(-30.0, 12.0),
            resist: -4.0,
        };
        let mut gl = g.loads();
        gl.set_by_name("output", &[-30.0, 12.0]);
        gl.set_by_name("resist", &[-4.0]);
        for [q, qd, qdd] in &configs {
            let ctx = format!("ratio {r:e}, q = {q}");
            let a = snap_generated!(gen, g.model(), *q, *qd, *qdd, loads, one_dof = true).unwrap();
            let b = snap_generic(&g, &[*q], &[*qd], &[*qdd], &gl).unwrap();
            // measured worst 1.9e-15 over the kinds (be05608); 100×
            agree(&ctx, &a, &b, SAME, 1e-13);
            // measured worst 8.9e-16 over the balances (be05608); 100×
            balances(&ctx, g.model(), &a, &gl.values, &[*qd], &[*qdd], 5e-14);
            balances(
                &format!("{ctx} (generic)"),
                g.model(),
                &b,
                &gl.values,
                &[*qd],
                &[*qdd],
                1e-13, // measured worst 1.4e-15 over the balances (be05608); 100×
            );
        }
    }
}

// =======================================================================================
// Property-based tests
// =======================================================================================

/// Random numbers of one mechanism: point coordinates (m), per moving link (mass kg,
/// inertia kg·m², cg m), the loads, gravity, and the motion offset from the drawing.
#[derive(Clone, Debug)]
struct Case {
    points: Vec<V>,
    links: Vec<(f64, f64, V)>,
    forces: Vec<V>,
    torques: Vec<f64>,
    gravity: V,
    /// The sliding axis of the joint `guide`, if the mechanism has one.
    axis: Option<V>,
    dq: f64,
    qd: f64,
    qdd: f64,
}

fn polar(r: f64, t: f64) -> V {
    V::new(r * t.cos(), r * t.sin())
}

/// |sin| of the angle between u and v.
fn sin_between(u: V, v: V) -> f64 {
    (u.x * v.y - u.y * v.x).abs() / (u.norm() * v.norm())
}

fn link_data(n: usize) -> impl Strategy<Value = Vec<(f64, f64, V)>> {
    prop::collection::vec((0.01f64..10.0, 1e-4f64..1.0, -0.3f64..0.3, -0.3f64..0.3), n).prop_map(
        |v| {
            v.into_iter()
                .map(|(m, i, x, y)| (m, i, V::new(x, y)))
                .collect()
        },
    )
}

fn motion_and_loads(
    forces: usize,
    torques: usize,
) -> impl Strategy<Value = (Vec<V>, Vec<f64>, V, f64, f64, f64)> {
    (
        prop::collection::vec(
            (-100.0f64..100.0, -100.0f64..100.0).prop_map(|(x, y)| V::new(x, y)),
            forces,
        ),
        prop::collection::vec(-10.0f64..10.0, torques),
        (-10.0f64..10.0, -10.0f64..10.0).prop_map(|(x, y)| V::new(x, y)),
        -0.3f64..0.3,
        -20.0f64..20.0,
        -100.0f64..100.0,
    )
}

/// Four-bar: O2 = 0, O4, A, B, coupler point P; transmission angle at B in the drawing of
/// at least 0.3 rad, links at least 5 cm.
fn four_bar_case() -> impl Strategy<Value = Case> {
    (
        (
            0.2f64..1.0,
            -0.5f64..0.5,
            0.05f64..0.5,
            0.0f64..std::f64::consts::TAU,
            0.1f64..1.0,
            0.0f64..std::f64::consts::TAU,
            0.0f64..1.0,
            -0.3f64..0.3,
        ),
        link_data(3),
        motion_and_loads(1, 1),
    )
        .prop_map(
            |((d, beta, a, t, c, phi, s, h), links, (forces, torques, gravity, dq, qd, qdd))| {
                let o4 = polar(d, beta);
                let pa = polar(a, t);
                let pb = o4 + polar(c, phi);
                let pp = pa + (pb - pa) * s + V::new(pa.y - pb.y, pb.x - pa.x) * h;
                // cgs near the middle of each link.
                let mids = [pa * 0.5, (pa + pb) * 0.5, (o4 + pb) * 0.5];
                let links = links
                    .iter()
                    .zip(mids)
                    .map(|(&(m, i, off), mid)| (m, i, mid + off * 0.3))
                    .collect();
                Case {
                    points: vec![V::zeros(), o4, pa, pb, pp],
                    links,
                    forces,
                    torques,
                    gravity,
                    axis: None,
                    dq,
                    qd,
                    qdd,
                }
            },
        )
        .prop_filter("drawing away from a dead point", |c| {
            let [_, o4, pa, pb, _] = c.points[..] else {
                return false;
            };
            (pb - pa).norm() > 0.05
                && (pb - o4).norm() > 0.05
                && sin_between(pa - pb, o4 - pb) > 0.3
        })
}

/// Slider-crank: O2 = 0, crank pin A, piston pin B on a guide along (cos γ, sin γ); the rod
/// at least 0.3 (sine) off the guide normal in the drawing.
fn slider_crank_case() -> impl Strategy<Value = Case> {
    (
        (
            0.02f64..0.3,
            0.0f64..std::f64::consts::TAU,
            2.0f64..5.0,
            -1.2f64..1.2,
            -0.5f64..0.5,
        ),
        link_data(3),
        motion_and_loads(1, 1),
    )
        .prop_map(
            |((a, t, ratio, psi, gamma), links, (forces, torques, gravity, dq, qd, qdd))| {
                let pa = polar(a, t);
                let pb = pa + polar(ratio * a, psi + gamma);
                let axis = polar(1.0, gamma);
                let mids = [pa * 0.5, (pa + pb) * 0.5, pb];
                let links = links
                    .iter()
                    .zip(mids)
                    .map(|(&(m, i, off), mid)| (m, i, mid + off * 0.2 * a))
                    .collect();
                Case {
                    points: vec![V::zeros(), pa, pb],
                    links,
                    forces,
                    torques,
                    gravity,
                    axis: Some(axis),
                    dq,
                    qd,
                    qdd,
                }
            },
        )
        .prop_filter("rod not normal to the guide", |c| {
            let u = c.axis.unwrap();
            ((c.points[2] - c.points[1]).normalize().dot(&u)).abs() > 0.3
        })
}

/// Watt II six-bar: the four-bar O2-A-B-O4 with a ternary rocker O4-B-C driving the dyad
/// C-D-O6; both transmission angles at least 0.3 rad in the drawing.
fn watt2_case() -> impl Strategy<Value = Case> {
    use std::f64::consts::TAU;
    (
        (
            0.2f64..0.6,
            -0.5f64..0.5,
            0.04f64..0.15,
            0.0f64..TAU,
            0.1f64..0.4,
            0.0f64..TAU,
            0.1f64..0.4,
            0.0f64..TAU,
        ),
        (0.2f64..0.6, 0.0f64..TAU, 0.1f64..0.5, 0.0f64..TAU),
        link_data(5),
        motion_and_loads(1, 1),
    )
        .prop_map(
            |(
                (d, beta, a, t, c, phi, e, chi),
                (f, om, g6, w6),
                links,
                (forces, torques, gravity, dq, qd, qdd),
            )| {
                let o4 = polar(d, beta);
                let pa = polar(a, t);
                let pb = o4 + polar(c, phi);
                let pc = o4 + polar(e, chi);
                let o6 = pc + polar(f, om);
                let pd = o6 + polar(g6, w6);
                let mids = [
                    pa * 0.5,
                    (pa + pb) * 0.5,
                    (o4 + pb + pc) / 3.0,
                    (pc + pd) * 0.5,
                    (o6 + pd) * 0.5,
                ];
                let links = links
                    .iter()
                    .zip(mids)
                    .map(|(&(m, i, off), mid)| (m, i, mid + off * 0.2))
                    .collect();
                Case {
                    points: vec![V::zeros(), o4, o6, pa, pb, pc, pd],
                    links,
                    forces,
                    torques,
                    gravity,
                    axis: None,
                    dq,
                    qd,
                    qdd,
                }
            },
        )
        .prop_filter("drawing away from dead points", |c| {
            let [_, o4, o6, pa, pb, pc, pd] = c.points[..] else {
                return false;
            };
            let far = |p: V, q: V| (p - q).norm() > 0.05;
            far(pa, pb)
                && far(pb, o4)
                && far(pc, o4)
                && far(pc, pb)
                && far(pc, pd)
                && far(pd, o6)
                && sin_between(pa - pb, o4 - pb) > 0.3
                && sin_between(pc - pd, o6 - pd) > 0.3
        })
}

/// Put a case's numbers into a model whose points and moving links are in the case's order.
fn apply(model: &mut Model, c: &Case, point_names: &[&str]) {
    for (name, p) in point_names.iter().zip(&c.points) {
        let i = model.point_index(name).unwrap();
        model.points[i].pos = [p.x, p.y];
    }
    for (l, &(m, i, cg)) in c.links.iter().enumerate() {
        let link = &mut model.links[l + 1];
        link.mass = Some(m);
        link.inertia = i;
        link.cg = [cg.x, cg.y];
    }
    model.gravity = Some([c.gravity.x, c.gravity.y]);
    if let Some(u) = c.axis {
        let j = model.joint_index("guide").unwrap();
        model.joints[j].axis = [u.x, u.y];
    }
}

fn generic_loads(g: &GenericMechanism, c: &Case) -> GenericLoads {
    let mut l = g.loads();
    let (mut fi, mut ti) = (0, 0);
    for v in l.values.iter_mut() {
        match v {
            LoadValue::Force(f) => {
                *f = c.forces[fi];
                fi += 1;
            }
            LoadValue::Torque(t) => {
                *t = c.torques[ti];
                ti += 1;
            }
        }
    }
    l
}

fn lp(c: &Case, k: usize) -> LinkParams {
    LinkParams {
        mass: c.links[k].0,
        inertia: c.links[k].1,
        flywheel: 0.0,
        cg: c.links[k].2,
    }
}

/// One random case through both solvers: the generic one from the run-time model, the
/// generated one through `from_params`; both accept or reject the drawing alike; when
/// both solve, they agree within twice the stated bound, every balance holds, and
/// declaring the coupler–rocker pin the other way round negates its reaction. `Ok(true)`
/// when the case was exercised, `Ok(false)` when it was skipped (refused alike by both, or
/// no number at the offset input).
macro_rules! random_case {
    ($c:expr, $base:expr, $names:expr, $swap:expr, $params:expr, $ty:ident, $loads:ident) => {{
        let c: &Case = $c;
        let mut model = $base.model().clone();
        apply(&mut model, c, $names);
        let g = GenericMechanism::from_model(model.clone());
        let gen = $ty::from_params($params);
        prop_assert_eq!(g.is_ok(), gen.is_ok(), "the generic and generated run-time checks disagree: {:?} / {:?}", g.as_ref().err(), gen.as_ref().err());
        // Refused alike by both (the drawing is checked at run time): skipped, counted.
        let (Ok(g), Ok(gen)) = (g, gen) else { return Ok(false) };
        let q = g.reference_inputs()[0] + c.dq;
        let gl = generic_loads(&g, c);
        let mut loads = $loads::default();
        for (ld, v) in g.model().loads.iter().zip(&gl.values) {
            let ok = match v {
                LoadValue::Force(f) => loads.set_by_name(ld.name(), &[f.x, f.y]),
                LoadValue::Torque(t) => loads.set_by_name(ld.name(), &[*t]),
            };
            prop_assert!(ok);
        }
        let b = match snap_generic(&g, &[q], &[c.qd], &[c.qdd], &gl) {
            Ok(b) => b,
            // Past a limit of the input's range, or too close to a dead point: no number;
            // skipped, counted.
            Err(MechError::NoAssembly | MechError::Singular { .. }) => return Ok(false),
            Err(e) => panic!("{e}"),
        };
        let kappa = g.kinematics(&[q], &[c.qd], &[c.qdd]).unwrap().condition;
        // Twice the stated bound, at least 1e-12: measured worst 0.18, 0.12, 0.035 of it
        // (Watt II, four-bar, slider-crank; 1000 cases each, be05608); the balances, a
        // tenth of it: measured worst 0.095, 0.073, 0.027 of that. 100× (6000 more cases
        // each passed).
        let tol = (2.0 * rate_error_bound(kappa)).max(1e-12);
        let tol_balance = 0.1 * tol;
        let a = snap_generated!(gen, g.model(), q, c.qd, c.qdd, loads, one_dof = true)
            .unwrap_or_else(|e| panic!("the generic solver answered but the generated one says {e} (κ = {kappa:e})"));
        agree("generated vs generic", &a, &b, SAME, tol);
        balances("generated", g.model(), &a, &gl.values, &[c.qd], &[c.qdd], tol_balance);
        balances("generic", g.model(), &b, &gl.values, &[c.qd], &[c.qdd], tol_balance);
        // R_ba = −R_ab: the same pin declared (b, a).
        let j = model.joint_index($swap).unwrap();
        let (ja, jb) = (model.joints[j].a, model.joints[j].b);
        model.joints[j].a = jb;
        model.joints[j].b = ja;
        let swapped = GenericMechanism::from_model(model).unwrap();
        let s = snap_generic(&swapped, &[q], &[c.qd], &[c.qdd], &generic_loads(&swapped, c)).unwrap();
        let fscale = vmax(&b.force);
        // Measured worst 0 (be05608, 3000 cases): exact; a few ulps.
        prop_assert!(within((s.force[j] + b.force[j]).amax(), 1e-15 * fscale), "R_ba {:?} vs R_ab {:?}", s.force[j], b.force[j]);
        Ok(true)
    }};
}

/// Run one property over `cases` random cases (a new seed each run; `MECH_PROPERTY_CASES`
/// sets another number, to re-measure the fraction exercised over many: tests/README.md,
/// "Tolerances"): `case`
/// returns `Ok(true)` for a case exercised, `Ok(false)` for one skipped. Both counts are
/// printed, and at least the fraction `min` of the cases must have been exercised: a
/// property whose cases are mostly skipped passes without checking anything.
fn property<S: Strategy>(
    name: &str,
    cases: u32,
    strategy: S,
    min: f64,
    case: impl Fn(S::Value) -> Result<bool, TestCaseError>,
) where
    S::Value: std::fmt::Debug,
{
    let cases = std::env::var("MECH_PROPERTY_CASES")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(cases);
    let mut runner = proptest::test_runner::TestRunner::new(ProptestConfig {
        cases,
        failure_persistence: None,
        ..ProptestConfig::default()
    });
    let (exercised, skipped) = (std::cell::Cell::new(0u32), std::cell::Cell::new(0u32));
    let result = runner.run(&strategy, |c| {
        let count = if case(c)? { &exercised } else { &skipped };
        count.set(count.get() + 1);
        Ok(())
    });
    if let Err(e) = result {
        panic!("{name}: {e}");
    }
    let (e, s) = (exercised.get(), skipped.get());
    println!("COUNT {name}: {e} exercised, {s} skipped of {cases}");
    assert!(
        f64::from(e) >= min * f64::from(cases),
        "{name}: {e} of {cases} cases exercised ({s} skipped), fewer than {min}"
    );
}

#[test]
fn random_four_bars() {
    let base = generic(MECHANISMS, "FourBar");
    // Exercised: 979 of 1000 and 5841 of 6000 cases (97–98 %, be05608; the others past a
    // limit of the input's range at the offset input); at least 75 % asserted (24 of 32:
    // at 3 % skipped, a false failure once in about 3·10⁶ runs).
    property("random four-bars", 32, four_bar_case(), 0.75, |c| {
        let mut p = FourBarParams::default();
        let pt = &c.points;
        (p.points.O2, p.points.O4, p.points.A, p.points.B, p.points.P) =
            (pt[0], pt[1], pt[2], pt[3], pt[4]);
        (p.links.crank, p.links.coupler, p.links.rocker) = (lp(&c, 0), lp(&c, 1), lp(&c, 2));
        p.gravity = c.gravity;
        random_case!(
            &c,
            base,
            &["O2", "O4", "A", "B", "P"],
            "B",
            p,
            FourBar,
            FourBarLoads
        )
    });
}

#[test]
fn random_slider_cranks() {
    let base = generic(MECHANISMS, "SliderCrank");
    // Exercised: 999 of 1000 and 5995 of 6000 cases (be05608); at least 75 % asserted.
    property("random slider-cranks", 32, slider_crank_case(), 0.75, |c| {
        let mut p = SliderCrankParams::default();
        let pt = &c.points;
        (p.points.O2, p.points.A, p.points.B) = (pt[0], pt[1], pt[2]);
        p.axes.guide = c.axis.unwrap();
        (p.links.crank, p.links.rod, p.links.piston) = (lp(&c, 0), lp(&c, 1), lp(&c, 2));
        p.gravity = c.gravity;
        random_case!(
            &c,
            base,
            &["O2", "A", "B"],
            "A",
            p,
            SliderCrank,
            SliderCrankLoads
        )
    });
}

#[test]
fn random_watt_six_bars() {
    let base = generic(MECHANISMS, "Watt2");
    // Exercised: 977 of 1000 and 5825 of 6000 cases (97–98 %, be05608); at least 75 %
    // asserted (24 of 32: at 3 % skipped, a false failure once in about 3·10⁶ runs).
    property("random Watt II six-bars", 32, watt2_case(), 0.75, |c| {
        let mut p = Watt2Params::default();
        let pt = &c.points;
        (
            p.points.O2,
            p.points.O4,
            p.points.O6,
            p.points.A,
            p.points.B,
            p.points.C,
            p.points.D,
        ) = (pt[0], pt[1], pt[2], pt[3], pt[4], pt[5], pt[6]);
        (
            p.links.crank,
            p.links.coupler,
            p.links.rocker,
            p.links.link5,
            p.links.rocker6,
        ) = (lp(&c, 0), lp(&c, 1), lp(&c, 2), lp(&c, 3), lp(&c, 4));
        p.gravity = c.gravity;
        random_case!(
            &c,
            base,
            &["O2", "O4", "O6", "A", "B", "C", "D"],
            "D",
            p,
            Watt2,
            Watt2Loads
        )
    });
}

// =======================================================================================
// Bad input
// =======================================================================================

/// The declaration texts of the example four-bar and slider-crank, for the loader's
/// error cases.
fn four_bar_text() -> &'static str {
    mechanism_text(MECHANISMS, "FourBar").unwrap()
}
fn slider_text() -> &'static str {
    mechanism_text(MECHANISMS, "SliderCrank").unwrap()
}

/// Every malformed description is a `MechError::Invalid` whose messages start with the
/// `line:column` of the culprit (and name it), never a panic.
#[test]
fn loader_rejects_bad_descriptions_with_locations() {
    let (four_bar, slider) = (four_bar_text(), slider_text());
    assert!(GenericMechanism::parse(four_bar).is_ok());
    assert!(GenericMechanism::parse(slider).is_ok());
    let b = "B: (0.2430191330116403, 0.23171119111114735)";
    let cases: &[(&str, &str, &str, &str)] = &[
        (
            four_bar,
            b,
            "B: (0.2430191330116403, 0.23171119111114735",
            "cannot parse",
        ),
        (
            four_bar,
            "mass: 1.45",
            "mass: NaN",
            "unknown constant `NaN`",
        ),
        (
            four_bar,
            "revolute(coupler, rocker)",
            "revolute(coupler, rockr)",
            "unknown link `rockr`",
        ),
        // P on A: two points of the coupler coincide (a zero-length link side).
        (
            four_bar,
            "P: (0.08528408845676129, 0.22077246544174978)",
            "P: (0.04, 0.06928203230275509)",
            "coincide",
        ),
        (four_bar, "O4: (0.3, 0.04)", "O4: (1e999, 0.04)", "finite"),
        (four_bar, "mass: 0.95", "mass: -0.95", "mass -0.95 kg"),
        (
            four_bar,
            "inertia: 0.0036",
            "inertia: -0.0036",
            "moment of inertia",
        ),
        (
            four_bar,
            "gravity: (0.0, -9.81)",
            "gravity: (0.0, 1e400)",
            "gravity",
        ),
        // B halfway between A and O4: coupler and rocker in line, a dead point.
        (four_bar, b, "B: (0.17, 0.054641016151377545)", "dead point"),
        (four_bar, "input: O2,", "inputs: [O2, O4],", "Grübler"),
        (four_bar, "input: O2,", "", "0 inputs were declared"),
        (
            four_bar,
            "tool: force on coupler at P",
            "tool: force on rocker at P",
            "does not have",
        ),
        (four_bar, "ground {", "grund {", "unknown item"),
        (slider, "along (1.0, 0.0)", "along (0.0, 0.0)", "zero"),
        (slider, " along (1.0, 0.0)", "", "needs its sliding axis"),
        // B on A: the rod has zero length.
        (
            slider,
            "B: (0.23103914733547787, 0.015)",
            "B: (0.042132444371543794, 0.035353318532759664)",
            "coincide",
        ),
        (slider, "input: O2,", "inputs: [O2, guide],", "Grübler"),
    ];
    for (text, from, to, expect) in cases {
        assert!(text.contains(from), "{from}");
        let bad = text.replacen(from, to, 1);
        match GenericMechanism::parse(&bad) {
            Err(MechError::Invalid(msg)) => {
                assert!(
                    msg.contains(expect),
                    "`{from}` → `{to}`: expected “{expect}” in:\n{msg}"
                );
                let first = msg.lines().next().unwrap();
                let (line, rest) = first.split_once(':').unwrap();
                let (col, _) = rest.split_once(':').unwrap();
                let (line, col): (usize, usize) = (line.parse().unwrap(), col.parse().unwrap());
                assert!(
                    line >= 1 && line <= bad.lines().count() && col >= 1,
                    "`{to}`: location {line}:{col} in\n{msg}"
                );
            }
            other => panic!(
                "`{from}` → `{to}`: expected Invalid, got {:?}",
                other.map(|_| "a mechanism")
            ),
        }
    }
    assert!(matches!(
        GenericMechanism::load("/nonexistent/dir/mechanism.mech"),
        Err(MechError::Invalid(_))
    ));
    assert!(matches!(
        GenericMechanism::from_rust_source("fn main() { let x = \"unterminated; }", "X"),
        Err(MechError::Invalid(_))
    ));
}

/// Random edits of a valid description (deleted, inserted or replaced characters):
/// the loader answers `Ok` or `Invalid`, never panics, and whatever loads can be
/// solved at its drawing without panicking. A case is exercised when the edited text still
/// loads (the solvers run on it), skipped when it is `Invalid`.
#[test]
fn loader_never_panics_on_edited_text() {
    let edits = prop::collection::vec(
        (
            0usize..10_000,
            0usize..4,
            prop::sample::select(vec![
                '{', '}', '(', ')', ',', ':', '-', '.', '0', '9', 'e', 'A', 'B', 'x', ' ', '\n',
            ]),
        ),
        1..4,
    );
    // Exercised (the edited text still loads): 148 of 1000 and 886 of 6000 cases (15 %,
    // be05608), about 14 of 96; at least 1 % asserted (1 of 96: none loading happens once
    // in about 5·10⁶ runs).
    property(
        "edited descriptions",
        96,
        (edits, any::<bool>()),
        0.01,
        |(edits, slider)| {
            let mut text: Vec<char> = if slider {
                slider_text()
            } else {
                four_bar_text()
            }
            .chars()
            .collect();
            for (at, kind, ch) in edits {
                let i = at % text.len();
                match kind {
                    0 => {
                        text.remove(i);
                    }
                    1 => text.insert(i, ch),
                    2 => text[i] = ch,
                    _ => {
                        let end = (i + 8).min(text.len());
                        text.drain(i..end);
                    }
                }
            }
            let text: String = text.into_iter().collect();
            match GenericMechanism::parse(&text) {
                Ok(g) => {
                    let q = g.reference_inputs().to_vec();
                    let _ = g
                        .kinematics(&q, &vec![1.0; q.len()], &vec![0.0; q.len()])
                        .map(|m| g.kinetostatics(&m, &g.loads()));
                    Ok(true)
                }
                Err(MechError::Invalid(_)) => Ok(false),
                Err(e) => Err(TestCaseError::fail(format!("unexpected error {e:?}"))),
            }
        },
    );
}

/// `from_params` re-runs the drawing, rank and determinacy checks: NaN and infinite
/// numbers, zero-length links, coincident points, negative masses and inertias, zero
/// axes and a drawing at a dead point are each a `MechError::Invalid`, never a panic.
#[test]
fn from_params_rejects_bad_numbers() {
    let nan = f64::NAN;
    let inf = f64::INFINITY;
    let bad: Vec<(&str, Box<dyn Fn(&mut FourBarParams)>)> = vec![
        ("NaN point", Box::new(move |p| p.points.B.x = nan)),
        ("infinite point", Box::new(move |p| p.points.O4.y = inf)),
        ("zero-length crank", Box::new(|p| p.points.A = p.points.O2)),
        (
            "coincident coupler points",
            Box::new(|p| p.points.P = p.points.A),
        ),
        ("NaN mass", Box::new(move |p| p.links.coupler.mass = nan)),
        ("negative mass", Box::new(|p| p.links.rocker.mass = -1.0)),
        (
            "negative inertia",
            Box::new(|p| p.links.crank.inertia = -1e-3),
        ),
        (
            "infinite inertia",
            Box::new(move |p| p.links.crank.inertia = inf),
        ),
        ("NaN cg", Box::new(move |p| p.links.rocker.cg.y = nan)),
        ("NaN gravity", Box::new(move |p| p.gravity.x = nan)),
        // B on the line A–O4: coupler and rocker in line, the drawing is a dead point.
        (
            "dead point",
            Box::new(|p| p.points.B = p.points.A + (p.points.O4 - p.points.A) * 0.4),
        ),
    ];
    for (what, f) in &bad {
        let mut p = FourBarParams::default();
        f(&mut p);
        assert!(
            matches!(FourBar::from_params(p), Err(MechError::Invalid(_))),
            "{what}"
        );
    }
    let mut p = SliderCrankParams::default();
    p.axes.guide = V::zeros();
    assert!(
        matches!(SliderCrank::from_params(p), Err(MechError::Invalid(_))),
        "zero axis"
    );
    let mut p = SliderCrankParams::default();
    p.axes.guide = V::new(nan, 1.0);
    assert!(
        matches!(SliderCrank::from_params(p), Err(MechError::Invalid(_))),
        "NaN axis"
    );
    // The generic solver's run-time model is checked the same way.
    let base = generic(MECHANISMS, "FourBar");
    let mut model = base.model().clone();
    model.points[2].pos = [nan, 0.0];
    assert!(matches!(
        GenericMechanism::from_model(model),
        Err(MechError::Invalid(_))
    ));
}

/// NaN and infinite inputs to every solver are `MechError::InvalidInput`, for the generated
/// solvers (one and two DOF) and the generic one.
#[test]
fn nan_and_infinite_inputs_are_errors() {
    let (nan, inf) = (f64::NAN, f64::INFINITY);
    let invalid = |r: Result<(), MechError>, what: &str| {
        assert!(
            matches!(r, Err(MechError::InvalidInput(_))),
            "{what}: {r:?}"
        )
    };
    let m = FourBar::new();
    let ok = FourBarLoads::default();
    let bad_loads = [
        FourBarLoads { resist: nan, ..ok },
        FourBarLoads {
            tool: V::new(inf, 0.0),
            ..ok
        },
    ];
    let mo = m.kinematics(1.0, 1.0, 0.0).unwrap();
    for x in [nan, inf, -inf] {
        invalid(m.pose(x).map(drop), "pose");
        invalid(m.kinematics(x, 1.0, 0.0).map(drop), "kinematics q");
        invalid(m.kinematics(1.0, x, 0.0).map(drop), "kinematics qd");
        invalid(m.kinematics(1.0, 1.0, x).map(drop), "kinematics qdd");
        invalid(m.reduced(x).map(drop), "reduced");
        invalid(m.reduced_moment(x, &ok).map(drop), "reduced_moment");
        invalid(m.acceleration(x, 1.0, 0.0, &ok).map(drop), "acceleration q");
        invalid(
            m.acceleration(1.0, x, 0.0, &ok).map(drop),
            "acceleration qd",
        );
        invalid(
            m.acceleration(1.0, 1.0, x, &ok).map(drop),
            "acceleration driver",
        );
    }
    for l in &bad_loads {
        invalid(m.kinetostatics(&mo, l).map(drop), "kinetostatics loads");
        invalid(m.driver_action(&mo, l).map(drop), "driver_action loads");
        invalid(m.reduced_moment(1.0, l).map(drop), "reduced_moment loads");
        invalid(
            m.acceleration(1.0, 1.0, 0.0, l).map(drop),
            "acceleration loads",
        );
    }
    let five = FiveBar::new();
    invalid(five.pose([nan, 1.0]).map(drop), "five-bar pose");
    invalid(
        five.kinematics([2.0, 1.0], [0.0, inf], [0.0, 0.0])
            .map(drop),
        "five-bar kinematics",
    );

    let g = generic(MECHANISMS, "FourBar");
    let gm = g.kinematics(&[1.0], &[1.0], &[0.0]).unwrap();
    for x in [nan, inf, -inf] {
        invalid(g.pose(&[x]).map(drop), "generic pose");
        invalid(
            g.kinematics(&[x], &[1.0], &[0.0]).map(drop),
            "generic kinematics q",
        );
        invalid(
            g.kinematics(&[1.0], &[x], &[0.0]).map(drop),
            "generic kinematics qd",
        );
        invalid(
            g.kinematics(&[1.0], &[1.0], &[x]).map(drop),
            "generic kinematics qdd",
        );
        invalid(g.reduced(x).map(drop), "generic reduced");
        invalid(
            g.acceleration(1.0, x, 0.0, &g.loads()).map(drop),
            "generic acceleration qd",
        );
        invalid(
            g.acceleration(1.0, 1.0, x, &g.loads()).map(drop),
            "generic acceleration driver",
        );
        let mut l = g.loads();
        assert!(l.set_by_name("resist", &[x]));
        invalid(
            g.kinetostatics(&gm, &l).map(drop),
            "generic kinetostatics loads",
        );
        invalid(
            g.driver_action(&gm, &l).map(drop),
            "generic driver_action loads",
        );
        invalid(
            g.reduced_moment(1.0, &l).map(drop),
            "generic reduced_moment loads",
        );
    }
    invalid(
        g.kinematics(&[1.0, 2.0], &[1.0], &[0.0]).map(drop),
        "generic wrong length",
    );
    let other = generic(MECHANISMS, "Watt2");
    let om = other.kinematics(&[1.0], &[1.0], &[0.0]).unwrap();
    invalid(
        g.kinetostatics(&om, &g.loads()).map(drop),
        "motion of another mechanism",
    );
    invalid(
        g.kinetostatics(&gm, &other.loads()).map(drop),
        "loads of another mechanism",
    );
}

/// Huge but finite inputs: a crank angle of 1e20 or 1e300 rad is some angle (both
/// solvers reduce it exactly and agree); an actuator stroke of 1e300 m has no assembly.
/// Nothing panics or hangs.
#[test]
fn huge_inputs_answer_quickly() {
    let m = FourBar::new();
    let g = generic(MECHANISMS, "FourBar");
    for q in [1e20, -1e20, 1e300, -1e300] {
        let a = m.pose(q).unwrap();
        let b = g.pose(&[q]).unwrap();
        for p in &g.model().points {
            let d = a.point(&p.name).unwrap().pos - b.point(&p.name).unwrap().pos;
            // measured worst 5.6e-17 (be05608); 100×
            assert!(within(d.amax(), 5e-15), "q = {q:e}: {}: {d:?}", p.name);
        }
    }
    let h = HydraulicLever::new();
    let gh = generic(MECHANISMS, "HydraulicLever");
    for q in [1e300, -1e300, 1e3] {
        assert!(h.pose(q).is_err(), "stroke {q:e}");
        assert!(gh.pose(&[q]).is_err(), "generic stroke {q:e}");
    }
}

// =======================================================================================
// Regressions: kernel bugs this suite found (fixed in de5dccc)
// =======================================================================================

mechanism! {
    /// Nine sliders on the ground, each driven by its own actuator (9 DOF).
    pub struct NineSliders {
        ground { O: (0.0, 0.0) },
        link s1 { points { P1: (0.0, 1.0) }, mass: 1.0, cg: (0.0, 1.0) },
        link s2 { points { P2: (0.0, 2.0) }, mass: 1.0, cg: (0.0, 2.0) },
        link s3 { points { P3: (0.0, 3.0) }, mass: 1.0, cg: (0.0, 3.0) },
        link s4 { points { P4: (0.0, 4.0) }, mass: 1.0, cg: (0.0, 4.0) },
        link s5 { points { P5: (0.0, 5.0) }, mass: 1.0, cg: (0.0, 5.0) },
        link s6 { points { P6: (0.0, 6.0) }, mass: 1.0, cg: (0.0, 6.0) },
        link s7 { points { P7: (0.0, 7.0) }, mass: 1.0, cg: (0.0, 7.0) },
        link s8 { points { P8: (0.0, 8.0) }, mass: 1.0, cg: (0.0, 8.0) },
        link s9 { points { P9: (0.0, 9.0) }, mass: 1.0, cg: (0.0, 9.0) },
        joints {
            j1: prismatic(ground, s1) at P1 along (1.0, 0.0),
            j2: prismatic(ground, s2) at P2 along (1.0, 0.0),
            j3: prismatic(ground, s3) at P3 along (1.0, 0.0),
            j4: prismatic(ground, s4) at P4 along (1.0, 0.0),
            j5: prismatic(ground, s5) at P5 along (1.0, 0.0),
            j6: prismatic(ground, s6) at P6 along (1.0, 0.0),
            j7: prismatic(ground, s7) at P7 along (1.0, 0.0),
            j8: prismatic(ground, s8) at P8 along (1.0, 0.0),
            j9: prismatic(ground, s9) at P9 along (1.0, 0.0),
        },
        inputs: [j1, j2, j3, j4, j5, j6, j7, j8, j9],
    }
}

/// A ninth prismatic input works. (Regression: `kinematics::eval` at `Level::Jacobian`
/// replaced the drive by an array of 8 zeros that a `DrivePrismatic(k)` still indexed with
/// k, so input 9 or later of a prismatic driver panicked in the generated `kinematics`.)
#[test]
fn ninth_prismatic_input_does_not_panic() {
    let m = NineSliders::new();
    let q = [0.1; 9];
    let mo = m.kinematics(q, [1.0; 9], [0.0; 9]).unwrap();
    // measured worst 0 (be05608); exact; a few ulps
    assert!(within((mo.links.s9.cg_vel.x - 1.0).abs(), 1e-15));
}

/// The generic solver never evaluates at `Level::Jacobian`: nine prismatic inputs work.
#[test]
fn generic_nine_prismatic_inputs() {
    let g = generic(SELF, "NineSliders");
    let q: Vec<f64> = (1..=9).map(|k| 0.1 * k as f64).collect();
    let m = g.kinematics(&q, &[1.0; 9], &[2.0; 9]).unwrap();
    for k in 1..=9 {
        let l = m.link(&format!("s{k}")).unwrap();
        assert!(
            within((l.cg - V::new(0.1 * k as f64, k as f64)).amax(), 1e-14) // measured worst 0 (be05608); exact; a few ulps of 9 m
                && within((l.cg_vel.x - 1.0).abs(), 1e-15), // measured worst 0 (be05608); exact; a few ulps
            "s{k}: {l:?}"
        );
    }
    // Each actuator pushes its own slider: F = m a = 2 N.
    let d = g.driver_action(&m, &g.loads()).unwrap();
    // measured worst 0 (be05608); exact; a few ulps
    assert!(d.iter().all(|f| within((f - 2.0).abs(), 1e-15)), "{d:?}");
}

/// `kinematics::wrap` reduces huge angles into (−π, π]. (Regression: a − 2π·round(a/2π)
/// gave wrap(−3e19) = −4089.7; it is the driver equation of a revolute input inside a
/// Newton group.)
#[test]
fn wrap_reduces_huge_angles() {
    for a in [1e17, 1e20, -3e19, 1e300] {
        let w = mech_core::kernel::kinematics::wrap(a);
        assert!(
            w > -std::f64::consts::PI && w <= std::f64::consts::PI,
            "wrap({a:e}) = {w}"
        );
    }
}
