//! Spatial mechanisms at run time (issue 33) against independent references: the RSSR's and
//! the RSSP's closed forms over a full turn, the planar run-time `Mechanism` on a planar
//! four-bar declared with `space`, the three routes to the driver torque, energy kept by the
//! direct problem, an mpmath Newton–Euler table of a spatial slider-crank, and the load-time
//! errors.

use mech_core::dynamics::ode::{integrate, Dop853};
use mech_core::dynamics::{equation_of_motion, total_energy};
use mech_core::spatial::{SpatialLoads, SpatialMechanism};
use mech_core::{MechError, Mechanism};
use nalgebra::Vector3;
use std::f64::consts::PI;

type V3 = Vector3<f64>;

const RSSR: &str = r#"
pub struct Rssr {
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
"#;

/// The RSSR's closed form (independent of the solver): A(q) on the crank circle about x,
/// B(φ) on the rocker circle about z through C, |B − A| = L solved as P cos φ + Q sin φ = R
/// on the drawing's branch; φ' = −f_q / f_φ for f = |B − A|² − L².
struct RssrClosed {
    a0: V3,
    c: V3,
    b: V3,
    l: f64,
    /// The assembly: φ = atan2(Q, P) + sign·acos(R / √(P² + Q²)).
    sign: f64,
}

impl RssrClosed {
    fn new() -> Self {
        let (a0, c, b0) = (
            V3::new(0.0, 0.05, 0.0),
            V3::new(0.25, 0.12, 0.08),
            V3::new(0.25, 0.02, 0.08),
        );
        RssrClosed {
            a0,
            c,
            b: b0 - c,
            l: (b0 - a0).norm(),
            sign: -1.0,
        }
    }
    fn a(&self, q: f64) -> V3 {
        V3::new(
            0.0,
            self.a0.y * q.cos() - self.a0.z * q.sin(),
            self.a0.y * q.sin() + self.a0.z * q.cos(),
        )
    }
    fn rz(v: V3, phi: f64) -> V3 {
        V3::new(
            v.x * phi.cos() - v.y * phi.sin(),
            v.x * phi.sin() + v.y * phi.cos(),
            v.z,
        )
    }
    /// (A, B, φ, φ').
    fn solve(&self, q: f64) -> (V3, V3, f64, f64) {
        let a = self.a(q);
        let (d, b) = (self.c - a, self.b);
        let p = 2.0 * (d.x * b.x + d.y * b.y);
        let qq = 2.0 * (d.y * b.x - d.x * b.y);
        let r = self.l * self.l - d.norm_squared() - b.norm_squared() - 2.0 * d.z * b.z;
        let phi = qq.atan2(p) + self.sign * (r / p.hypot(qq)).acos();
        let bb = self.c + Self::rz(b, phi);
        let a_dot = V3::x().cross(&a);
        let b_dot = V3::z().cross(&(bb - self.c));
        let phi_dot = (bb - a).dot(&a_dot) / (bb - a).dot(&b_dot);
        (a, bb, phi, phi_dot)
    }
}

fn rssr_loads(m: &SpatialMechanism) -> SpatialLoads {
    let mut loads = m.loads();
    assert!(loads.set_by_name("tool", &[0.3, -0.2, 1.7]));
    assert!(loads.set_by_name("push", &[4.0, -3.0, 2.5]));
    assert!(!loads.set_by_name("nothing", &[1.0, 2.0, 3.0]));
    loads
}

#[test]
fn rssr_matches_its_closed_form_over_a_full_turn() {
    let m = SpatialMechanism::from_dsl(RSSR).unwrap();
    assert_eq!(m.dof(), 1);
    assert_eq!(m.idle_links(), vec!["rod"]);
    let count = m.kutzbach();
    assert_eq!((count.mobility, count.idle.len()), (2, 1));
    let cf = RssrClosed::new();
    let loads = rssr_loads(&m);
    let (mut worst_pos, mut worst_torque) = (0.0f64, 0.0f64);
    for k in 0..72 {
        let q = 2.0 * PI * k as f64 / 72.0;
        let (a, b, phi, phi_dot) = cf.solve(q);
        let pose = m.pose(&[q]).unwrap();
        worst_pos = worst_pos
            .max((pose.point("A").unwrap() - a).amax())
            .max((pose.point("B").unwrap() - b).amax());
        let rocker = pose.link("rocker").unwrap();
        assert!((rocker.rotation.angle() - phi.abs()).abs() < 1e-11, "{q}");
        // Static driver torque by virtual work with the closed form's velocity coefficients:
        // τ = −(T·ω'_rocker + F·v'_B + Σ m g·v'_G), the rod's cg on AB (its velocity the
        // mean of A's and B's weighted by the position along AB).
        let va = V3::x().cross(&a);
        let vb = V3::z().cross(&(b - cf.c)) * phi_dot;
        let g = V3::new(0.0, 0.0, -9.81);
        let crank_g = V3::x().cross(&(pose.link("crank").unwrap().cg));
        let rocker_g = V3::z().cross(&(pose.link("rocker").unwrap().cg - cf.c)) * phi_dot;
        let rod_cg = pose.link("rod").unwrap().cg;
        let t = (rod_cg - a).dot(&(b - a)) / (b - a).norm_squared();
        assert!(
            ((a + (b - a) * t) - rod_cg).norm() < 1e-12,
            "the rod's cg is on AB"
        );
        let rod_g = va + (vb - va) * t;
        let power = loads.values[0].dot(&(V3::z() * phi_dot))
            + loads.values[1].dot(&vb)
            + g.dot(&(crank_g * 1.0 + rod_g * 0.5 + rocker_g * 0.8));
        let tau = -power;
        let got = m.driver_action(&pose, &loads).unwrap()[0];
        let f = m.kinetostatics(&pose, &loads).unwrap();
        worst_torque = worst_torque
            .max((got - tau).abs() / tau.abs().max(1.0))
            .max((f.driver() - tau).abs() / tau.abs().max(1.0));
    }
    eprintln!("RSSR: positions {worst_pos:.2e} m, static torque {worst_torque:.2e} relative");
    assert!(worst_pos < 1e-12, "{worst_pos}");
    assert!(worst_torque < 1e-10, "{worst_torque}");
}

const RSSP: &str = r#"
pub struct Rssp {
    space,
    gravity: (0.0, -9.81, 0.0),
    ground { O: (0.0, 0.0, 0.0) },
    link crank { points { O, A: (0.0, 0.05, 0.0) }, mass: 1.0, cg: (0.0, 0.02, 0.0), inertia: (1e-3, 4e-4, 9e-4, 0.0, 0.0, 0.0) },
    link rod { points { A, B: (0.25, 0.02, 0.08) }, mass: 0.5, cg: (0.1, 0.038, 0.032), inertia: (2e-4, 3e-3, 2.5e-3, 0.0, 0.0, 0.0) },
    link slider { points { B }, mass: 2.0, cg: (0.25, 0.02, 0.08) },
    joints {
        O: revolute(ground, crank) axis (1.0, 0.0, 0.0),
        A: spherical(crank, rod),
        B: spherical(rod, slider),
        guide: prismatic(ground, slider) at B along (1.0, 0.2, -0.1),
    },
    input: O,
    loads { gas: force on slider at B },
}
"#;

#[test]
fn rssp_matches_its_closed_form_over_a_full_turn() {
    let m = SpatialMechanism::from_dsl(RSSP).unwrap();
    assert_eq!(m.idle_links(), vec!["rod"]);
    let w = V3::new(1.0, 0.2, -0.1).normalize();
    let (a0, b0) = (V3::new(0.0, 0.05, 0.0), V3::new(0.25, 0.02, 0.08));
    let l = (b0 - a0).norm();
    let mut loads = m.loads();
    loads.set_by_name("gas", &[-30.0, 5.0, 2.0]);
    let (mut worst_pos, mut worst_torque) = (0.0f64, 0.0f64);
    for k in 0..72 {
        let q = 2.0 * PI * k as f64 / 72.0;
        let a = V3::new(0.0, 0.05 * q.cos(), 0.05 * q.sin());
        let d = b0 - a;
        let s = -w.dot(&d) + (w.dot(&d).powi(2) - d.norm_squared() + l * l).sqrt();
        let b = b0 + w * s;
        let va = V3::x().cross(&a);
        let s_dot = (b - a).dot(&va) / (b - a).dot(&w);
        let pose = m.pose(&[q]).unwrap();
        worst_pos = worst_pos
            .max((pose.point("A").unwrap() - a).amax())
            .max((pose.point("B").unwrap() - b).amax());
        let rod_cg = pose.link("rod").unwrap().cg;
        let t = (rod_cg - a).dot(&(b - a)) / (b - a).norm_squared();
        let g = V3::new(0.0, -9.81, 0.0);
        let crank_g = V3::x().cross(&pose.link("crank").unwrap().cg);
        let power = loads.values[0].dot(&(w * s_dot))
            + g.dot(&(crank_g * 1.0 + (va + (w * s_dot - va) * t) * 0.5 + w * s_dot * 2.0));
        let got = m.kinetostatics(&pose, &loads).unwrap().driver();
        worst_torque = worst_torque.max((got + power).abs() / power.abs().max(1.0));
    }
    eprintln!("RSSP: positions {worst_pos:.2e} m, static torque {worst_torque:.2e} relative");
    assert!(worst_pos < 1e-12, "{worst_pos}");
    assert!(worst_torque < 1e-10, "{worst_torque}");
}

/// d'Alembert (Newton–Euler's multiplier), virtual power and Zhukovski
/// (I* q̈ + ½ dI*/dq q̇² − M*) for the motor torque.
fn three_routes(m: &SpatialMechanism, loads: &SpatialLoads, q: f64, qd: f64, qdd: f64) -> f64 {
    let motion = m.kinematics(&[q], &[qd], &[qdd]).unwrap();
    let dalembert = m.kinetostatics(&motion, loads).unwrap().driver();
    let power = m.driver_action(&motion, loads).unwrap()[0];
    let r = m.reduced(q).unwrap();
    let zhukovski = r.inertia * qdd + 0.5 * r.inertia_derivative * qd * qd
        - m.reduced_moment(q, loads).unwrap();
    let scale = dalembert.abs().max(power.abs()).max(1e-3);
    ((dalembert - power).abs() / scale).max((dalembert - zhukovski).abs() / scale)
}

#[test]
fn the_three_routes_to_the_driver_torque_agree() {
    let m = SpatialMechanism::from_dsl(RSSR).unwrap();
    let loads = rssr_loads(&m);
    let mut worst = 0.0f64;
    for k in 0..24 {
        let q = 2.0 * PI * k as f64 / 24.0 + 0.1;
        worst = worst.max(three_routes(
            &m,
            &loads,
            q,
            12.0 - k as f64,
            40.0 * (q).sin(),
        ));
    }
    let m = SpatialMechanism::from_dsl(RSSP).unwrap();
    let loads = m.loads();
    for k in 0..24 {
        let q = 2.0 * PI * k as f64 / 24.0 + 0.1;
        worst = worst.max(three_routes(&m, &loads, q, 9.0, -25.0));
    }
    eprintln!("three routes: {worst:.2e} relative");
    assert!(worst < 1e-10, "{worst}");
}

const PLANAR: &str = r#"
pub struct FourBar {
    gravity: (0.0, -9.81),
    ground { O2: (0.0, 0.0), O4: (0.3, 0.0) },
    link crank { points { O2, A: (0.02, 0.06) }, mass: 0.4, inertia: 2e-4, cg: (0.012, 0.03) },
    link coupler { points { A, B: (0.25, 0.16) }, mass: 1.1, inertia: 6e-3, cg: (0.14, 0.13) },
    link rocker { points { B, O4 }, mass: 0.7, inertia: 2.5e-3, cg: (0.27, 0.07) },
    joints {
        O2: revolute(ground, crank),
        A: revolute(crank, coupler),
        B: revolute(coupler, rocker),
        O4: revolute(rocker, ground),
    },
    input: O2,
    loads { push: force on coupler at B, tool: torque on rocker },
}
"#;

/// The same four-bar in space: revolute axes along z at z = 0, A spherical and B universal
/// (z in the coupler, the rocker's line in the rocker) so that Kutzbach's count is 1 (four
/// revolutes in space are over-constrained: G = −2); Izz as the planar inertia, Ixx, Iyy,
/// Ixy arbitrary (Ixz = Iyz = 0 keeps the motion planar).
const PLANAR_IN_SPACE: &str = r#"
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
    loads { push: force on coupler at B, tool: torque on rocker },
}
"#;

/// A planar mechanism declared with `space` gives the planar run-time Mechanism's numbers:
/// positions, velocities, accelerations, the driver torque and every reaction force; under
/// planar loads the z force components and the x and y moment components are zero (the
/// only moments a revolute or universal joint carries here).
#[test]
fn a_planar_four_bar_declared_in_space_gives_the_planar_numbers() {
    let plane = Mechanism::from_dsl(PLANAR).unwrap();
    let space = SpatialMechanism::from_dsl(PLANAR_IN_SPACE).unwrap();
    assert!(space.idle_links().is_empty());
    let mut pl = plane.loads();
    assert!(pl.set_by_name("push", &[3.0, -2.0]) && pl.set_by_name("tool", &[1.5]));
    let mut sl = space.loads();
    assert!(sl.set_by_name("push", &[3.0, -2.0, 0.0]) && sl.set_by_name("tool", &[0.0, 0.0, 1.5]));
    let (mut kin, mut force, mut out_of_plane) = (0.0f64, 0.0f64, 0.0f64);
    for k in 0..36 {
        let q = 2.0 * PI * k as f64 / 36.0;
        let (qd, qdd) = (7.0, -20.0 + k as f64);
        // the planar q is the crank's angle θ (SPEC 2), the spatial one its rotation from
        // the drawing
        let a = plane
            .kinematics(&[q + 0.06f64.atan2(0.02)], &[qd], &[qdd])
            .unwrap();
        let b = space.kinematics(&[q], &[qd], &[qdd]).unwrap();
        for p in ["A", "B"] {
            let (pa, pb) = (a.point(p).unwrap(), b.point_motion(p).unwrap());
            for (x, y, scale) in [
                (pa.pos, pb[0], 0.3),
                (pa.vel, pb[1], 0.3 * qd),
                (pa.acc, pb[2], 0.3 * (qd * qd + qdd.abs())),
            ] {
                kin = kin.max((x - y.xy()).amax() / scale).max(y.z.abs() / scale);
            }
        }
        for l in ["crank", "coupler", "rocker"] {
            let (la, lb) = (a.link(l).unwrap(), b.link(l).unwrap());
            kin = kin
                .max((la.omega - lb.omega.z).abs() / qd)
                .max((la.alpha - lb.alpha.z).abs() / (qd * qd + qdd.abs()));
            kin = kin
                .max(lb.omega.xy().amax() / qd)
                .max(lb.alpha.xy().amax() / (qd * qd));
        }
        let (fa, fb) = (
            plane.kinetostatics(&a, &pl).unwrap(),
            space.kinetostatics(&b, &sl).unwrap(),
        );
        let scale = fa
            .joints
            .iter()
            .map(|j| j.force.amax())
            .fold(fa.driver[0].abs(), f64::max);
        force = force.max((fa.driver[0] - fb.driver()).abs() / scale);
        for j in ["O2", "A", "B", "O4"] {
            let (ra, rb) = (fa.reaction(j).unwrap().0, fb.reaction(j).unwrap());
            force = force.max((ra - rb.force.xy()).amax() / scale);
            out_of_plane = out_of_plane
                .max(rb.force.z.abs() / scale)
                .max(rb.moment.xy().amax() / (0.3 * scale));
            // a spherical joint carries no moment; a universal's only about its cross's normal
            assert!(j != "A" || rb.moment.amax() < 1e-12 * scale, "{j}");
        }
    }
    eprintln!("planar in space: kinematics {kin:.2e}, forces {force:.2e}, out of plane {out_of_plane:.2e} (relative)");
    assert!(
        kin < 1e-12 && force < 1e-12 && out_of_plane < 1e-12,
        "{kin} {force} {out_of_plane}"
    );
}

/// The direct problem keeps T + V: the RSSR coasting under gravity (driver 0, no loads)
/// integrated by DOP853 at 1e-11 for one second.
#[test]
fn the_direct_problem_keeps_the_energy() {
    let m = SpatialMechanism::from_dsl(RSSR).unwrap();
    let (q0, w0) = (0.3, 8.0);
    let e0 = total_energy(&m, &[q0], &[w0]).unwrap();
    let out = integrate(
        &mut Dop853::new(1e-11, 1e-11),
        equation_of_motion(&m, |_, _, _| (0.0, SpatialLoads::default())),
        0.0,
        [q0, w0],
        1.0,
    )
    .unwrap();
    let e1 = total_energy(&m, &[out.y[0]], &[out.y[1]]).unwrap();
    eprintln!(
        "energy: q {:.3} rad after 1 s, |ΔE| = {:.2e} J of {e0:.5} J",
        out.y[0],
        (e1 - e0).abs()
    );
    assert!((out.y[0] - q0).abs() > 1.0, "it moves: {}", out.y[0]);
    assert!((e1 - e0).abs() < 1e-8 * e0.abs().max(1.0), "{e0} {e1}");
}

fn invalid(text: &str) -> String {
    match SpatialMechanism::from_dsl(text) {
        Err(MechError::Invalid(m)) => m,
        other => panic!("expected Invalid, got {other:?}"),
    }
}

#[test]
fn bad_input_is_refused_with_the_numbers_and_the_fix() {
    // Kutzbach off: the rocker's revolute made cylindrical gives G = 6·3 − 5 − 3 − 3 − 4 = 3,
    // one idle, 2 ≠ 1 input.
    let m = invalid(&RSSR.replace(
        "C: revolute(ground, rocker)",
        "C: cylindrical(ground, rocker)",
    ));
    assert!(
        m.contains("Kutzbach")
            && m.contains("= 3, of which 1 idle")
            && m.contains("link `rod` spins idly")
            && m.contains("declare 2 input"),
        "{m}"
    );
    // Two idle links are both named.
    let m = invalid(&RSSR.replace(
        "C: revolute(ground, rocker) axis (0.0, 0.0, 1.0)",
        "C: spherical(ground, rocker)",
    ));
    assert!(
        m.contains("of which 2 idle") && m.contains("link `rocker` spins idly"),
        "{m}"
    );
    // An unknown kind.
    let m = invalid(&RSSR.replace("A: spherical(crank, rod)", "A: ball(crank, rod)"));
    assert!(
        m.contains("unknown joint kind `ball`") && m.contains("universal(a, b) axes"),
        "{m}"
    );
    // A zero axis.
    let m = invalid(&RSSR.replace("axis (1.0, 0.0, 0.0)", "axis (0.0, 0.0, 0.0)"));
    assert!(m.contains("the axis of joint `O` is (0, 0, 0)"), "{m}");
    // A universal joint whose axes are not perpendicular.
    let m = invalid(&PLANAR_IN_SPACE.replace("(0.05, -0.16, 0.0)", "(0.05, -0.16, 0.1)"));
    assert!(
        m.contains("universal joint's two axes are perpendicular"),
        "{m}"
    );
    // Four revolutes in space: Kutzbach's G = −2, and the rank names the joint that repeats.
    let m = invalid(
        &PLANAR_IN_SPACE
            .replace(
                "A: spherical(crank, coupler)",
                "A: revolute(crank, coupler) axis (0.0, 0.0, 1.0)",
            )
            .replace(
                "universal(coupler, rocker) axes (0.0, 0.0, 1.0) (0.05, -0.16, 0.0)",
                "revolute(coupler, rocker) axis (0.0, 0.0, 1.0)",
            ),
    );
    assert!(
        m.contains("= -2")
            && m.contains("rank 18 for 21 equations: 3 redundant")
            && m.contains("joint `O4` (revolute): 3 of its 5"),
        "{m}"
    );
    // Kutzbach's count can hide an over-constrained sub-chain: four revolutes (3 redundant
    // equations) beside a pendulum on a ball joint (3 free turns) count G = −2 + 3 = 1. The
    // pebble game names the four links; the rank, which would repeat it, is not run.
    let m = invalid(
        &PLANAR_IN_SPACE
            .replace("A: spherical(crank, coupler)", "A: revolute(crank, coupler) axis (0.0, 0.0, 1.0)")
            .replace("universal(coupler, rocker) axes (0.0, 0.0, 1.0) (0.05, -0.16, 0.0)", "revolute(coupler, rocker) axis (0.0, 0.0, 1.0)")
            .replace("O4: (0.3, 0.0, 0.0) },", "O4: (0.3, 0.0, 0.0), P: (0.5, 0.5, 0.5) },\n    link bob { points { P }, mass: 1.0 },")
            .replace("O4: revolute(rocker, ground) axis (0.0, 0.0, 1.0),", "O4: revolute(rocker, ground) axis (0.0, 0.0, 1.0),\n        P: spherical(ground, bob),"),
    );
    assert!(
        !m.contains("Kutzbach's count does not match")
            && m.contains("links `crank`, `coupler`, `rocker` (with the ground) form an over-constrained sub-chain")
            && m.contains("21 in all, but a rigid set of 4 links (the ground among them) can lose only 6·4 − 6 = 18 (3 redundant equations)")
            && !m.contains("bob")
            && !m.contains("constraint Jacobian"),
        "{m}"
    );
    // Units and names.
    let m = invalid(&RSSR.replace("mass: 0.5,", "mass: 0.5 mm,"));
    assert!(m.contains("a mass is"), "{m}");
    let m = invalid(&RSSR.replace("input: O,", "input: A,"));
    assert!(m.contains("input `A` is a spherical joint"), "{m}");
    let m = invalid(&RSSR.replace("space,", ""));
    assert!(m.contains("starts with the word `space`"), "{m}");
    // Not a panic, not a non-finite number: q beyond reach, NaN.
    let m = SpatialMechanism::from_dsl(RSSR).unwrap();
    assert!(matches!(
        m.pose(&[f64::NAN]),
        Err(MechError::InvalidInput(_))
    ));
    assert!(m.kinematics(&[0.1, 0.2], &[0.0], &[0.0]).is_err());
    assert!(matches!(m.pose(&[1e300]), Err(MechError::InvalidInput(_))));
    let other = SpatialMechanism::from_dsl(RSSP)
        .unwrap()
        .pose(&[0.1])
        .unwrap();
    assert!(matches!(
        m.kinetostatics(&other, &m.loads()),
        Err(MechError::InvalidInput(_))
    ));
    assert!(matches!(
        m.driver_action(&other, &m.loads()),
        Err(MechError::InvalidInput(_))
    ));
    let motion = m.kinematics(&[0.3], &[1.0], &[0.0]).unwrap();
    let mut loads = m.loads();
    loads.set_by_name("push", &[f64::NAN, 0.0, 0.0]);
    assert!(matches!(
        m.kinetostatics(&motion, &loads),
        Err(MechError::InvalidInput(_))
    ));
    assert!(m.driver_action(&motion, &loads).is_err());
    assert!(m.reduced_moment(0.3, &loads).is_err());
    assert!(m.acceleration(0.3, f64::INFINITY, 0.0, &m.loads()).is_err());
    // the RSSP pushed at its slide beyond the crank's reach (c = 2.1 in the closed form)
    let far = SpatialMechanism::from_dsl(&RSSP.replace("input: O,", "input: guide,")).unwrap();
    let e = far.pose(&[0.03]).map(|p| p.point("A"));
    assert!(
        matches!(e, Err(MechError::NoAssembly | MechError::Singular { .. })),
        "{e:?}"
    );
}

/// A spatial slider-crank (R-S-U-P: a skew crank axis, a skew slide) against
/// tools/spatial_reference.py's table: 50-digit Newton on its own loop equations (the rod's
/// rotation by the universal joint's two angles), rates by 3×3 solves, Newton–Euler of each
/// body with the 18 reaction components in the joints' own bases. Each quantity within
/// 1e-12 of its kind's scale (the largest magnitude of that kind in the table).
#[test]
fn a_spatial_slider_crank_matches_the_mpmath_newton_euler_table() {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../tests/data/spatial/slider_crank.truth.json"
    );
    let data: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap();
    let m = SpatialMechanism::from_dsl(data["dsl"].as_str().unwrap()).unwrap();
    assert!(m.idle_links().is_empty());
    let mut loads = m.loads();
    for (name, value) in data["loads"].as_object().unwrap() {
        let v: Vec<f64> = value
            .as_array()
            .unwrap()
            .iter()
            .map(|x| x.as_f64().unwrap())
            .collect();
        assert!(loads.set_by_name(name, &v), "{name}");
    }
    let num = |x: &serde_json::Value| -> f64 { x.as_str().unwrap().parse().unwrap() };
    let vec =
        |x: &serde_json::Value| -> V3 { V3::from_iterator(x.as_array().unwrap().iter().map(num)) };
    // (kind, reference, computed), scaled per kind afterwards
    let mut pairs: Vec<(&str, f64, f64)> = Vec::new();
    let mut push = |kind: &'static str, a: V3, b: V3| {
        for k in 0..3 {
            pairs.push((kind, a[k], b[k]));
        }
    };
    for c in data["cases"].as_array().unwrap() {
        let (q, qd, qdd) = (num(&c["q"]), num(&c["qd"]), num(&c["qdd"]));
        let motion = m.kinematics(&[q], &[qd], &[qdd]).unwrap();
        for (p, kinds) in [
            ("A", ["position", "velocity", "acceleration"]),
            ("B", ["position", "velocity", "acceleration"]),
        ] {
            let got = motion.point_motion(p).unwrap();
            for k in 0..3 {
                push(kinds[k], vec(&c["points"][p][k]), got[k]);
            }
        }
        for l in ["rod", "crank"] {
            let got = motion.link(l).unwrap();
            push("omega", vec(&c["links"][l]["omega"]), got.omega);
            push("alpha", vec(&c["links"][l]["alpha"]), got.alpha);
            push(
                "acceleration",
                vec(&c["links"][l]["cg_acceleration"]),
                got.cg_acceleration,
            );
        }
        let f = m.kinetostatics(&motion, &loads).unwrap();
        for j in ["O", "A", "B", "guide"] {
            let r = f.reaction(j).unwrap();
            push("force", vec(&c["reactions"][j]["force"]), r.force);
            push("moment", vec(&c["reactions"][j]["moment"]), r.moment);
        }
        let tau = num(&c["driver"]);
        push(
            "moment",
            V3::new(tau, 0.0, 0.0),
            V3::new(f.driver(), 0.0, 0.0),
        );
        let power = m.driver_action(&motion, &loads).unwrap()[0];
        push("moment", V3::new(tau, 0.0, 0.0), V3::new(power, 0.0, 0.0));
    }
    let mut report = String::new();
    let mut worst = 0.0f64;
    for kind in [
        "position",
        "velocity",
        "acceleration",
        "omega",
        "alpha",
        "force",
        "moment",
    ] {
        let these: Vec<_> = pairs.iter().filter(|p| p.0 == kind).collect();
        let scale = these.iter().map(|p| p.1.abs()).fold(0.0, f64::max);
        let err = these.iter().map(|p| (p.1 - p.2).abs()).fold(0.0, f64::max) / scale;
        report += &format!(" {kind} {err:.1e} (of {scale:.3});");
        worst = worst.max(err);
    }
    eprintln!("spatial slider-crank against mpmath:{report}");
    assert!(worst < 1e-12, "{report}");
}

/// A nut on a fixed screw (helical joint, lead 5 mm): over three turns each way the nut's
/// point rises p q / (2π) and its cg turns about z; the motor torque is the closed form
/// T = I* q̈ − M*, I* = m (r² + (p/2π)²) + Izz constant, M* = (F_z + m g_z) p / (2π).
#[test]
fn a_helical_joint_matches_its_closed_form_over_three_turns_each_way() {
    let text = r#"pub struct Nut {
        space,
        gravity: (0.0, 0.0, -9.81),
        consts { lead: 5 mm },
        ground { O: (0.0, 0.0, 0.0) },
        link nut { points { P: (0.0, 0.0, 100 mm) }, mass: 2.0, cg: (0.01, 0.02, 0.1), inertia: (3e-3, 2e-3, 4e-3, 5e-4, 0.0, 0.0) },
        joints { P: helical(ground, nut) axis (0.0, 0.0, 1.0) pitch lead },
        input: P,
        loads { thrust: force on nut at P },
    }"#;
    let m = SpatialMechanism::from_dsl(text).unwrap();
    let mut loads = m.loads();
    loads.set_by_name("thrust", &[3.0, -1.0, -100.0]);
    let k = 0.005 / (2.0 * PI);
    let (mass, r) = (2.0, V3::new(0.01, 0.02, 0.0));
    let inertia = mass * (r.norm_squared() + k * k) + 4e-3;
    let (mut pos, mut torque) = (0.0f64, 0.0f64);
    for i in -36..=36 {
        let q = 3.0 * PI * i as f64 / 36.0;
        let (qd, qdd) = (4.0, 30.0 - i as f64);
        let motion = m.kinematics(&[q], &[qd], &[qdd]).unwrap();
        let p = motion.point("P").unwrap();
        let cg = motion.link("nut").unwrap().cg;
        let turned = V3::new(
            r.x * q.cos() - r.y * q.sin(),
            r.x * q.sin() + r.y * q.cos(),
            0.1 + k * q,
        );
        pos = pos
            .max((p - V3::new(0.0, 0.0, 0.1 + k * q)).amax())
            .max((cg - turned).amax());
        let want = inertia * qdd - (-100.0 - mass * 9.81) * k;
        let got = m.kinetostatics(&motion, &loads).unwrap().driver();
        torque = torque.max((got - want).abs() / want.abs().max(1.0));
        assert!(
            (m.driver_action(&motion, &loads).unwrap()[0] - want).abs()
                < 1e-12 * want.abs().max(1.0)
        );
    }
    eprintln!("helical: positions {pos:.1e} m, torque {torque:.1e} relative");
    assert!(pos < 1e-12 && torque < 1e-12, "{pos} {torque}");
}

/// The RSSP driven at its slide (a prismatic input): the crank's angle from the closed form
/// 0.1 (B_y cos θ + B_z sin θ) = |B|² + r² − L², and the three routes agree.
#[test]
fn the_rssp_driven_at_its_slide_matches_its_closed_form() {
    let m = SpatialMechanism::from_dsl(&RSSP.replace("input: O,", "input: guide,")).unwrap();
    let w = V3::new(1.0, 0.2, -0.1).normalize();
    let (a0, b0) = (V3::new(0.0, 0.05, 0.0), V3::new(0.25, 0.02, 0.08));
    let l2 = (b0 - a0).norm_squared();
    let (mut pos, mut routes) = (0.0f64, 0.0f64);
    let mut loads = m.loads();
    loads.set_by_name("gas", &[-30.0, 5.0, 2.0]);
    // the stroke is about −0.02 m .. 0.012 m (the dead points, c = ±1)
    for i in 0..=40 {
        let s = -0.018 + 0.028 * i as f64 / 40.0;
        let b = b0 + w * s;
        let c = (b.norm_squared() + 0.0025 - l2) / (0.1 * b.y.hypot(b.z));
        let theta = b.z.atan2(b.y) - c.acos();
        let pose = m.pose(&[s]).unwrap();
        pos = pos.max(
            (pose.point("A").unwrap() - V3::new(0.0, 0.05 * theta.cos(), 0.05 * theta.sin()))
                .amax(),
        );
        pos = pos.max((pose.point("B").unwrap() - b).amax());
        routes = routes.max(three_routes(&m, &loads, s, 0.7, -3.0 + i as f64 / 4.0));
    }
    eprintln!("RSSP by its slide: positions {pos:.1e} m, routes {routes:.1e}");
    assert!(pos < 1e-12 && routes < 1e-10, "{pos} {routes}");
}

/// An RSCR: the RSSR with a cylindrical joint (axis z, fixed in the rod) between rod and
/// rocker: the rod only turns about z, so in the xy plane the crank pin, the rod and the
/// rocker are a planar dyad (|B_xy − A_xy| = the drawing's), and B's point on the rod
/// slides along z by A's rise. Three routes agree.
#[test]
fn a_cylindrical_joint_in_an_rscr_matches_its_closed_form() {
    let text = RSSR.replace(
        "B: spherical(rod, rocker)",
        "B: cylindrical(rod, rocker) axis (0.0, 0.0, 1.0)",
    );
    let m = SpatialMechanism::from_dsl(&text).unwrap();
    assert!(m.idle_links().is_empty());
    let loads = rssr_loads(&m);
    let (a0, c, b0) = (
        V3::new(0.0, 0.05, 0.0),
        V3::new(0.25, 0.12, 0.08),
        V3::new(0.25, 0.02, 0.08),
    );
    let b = b0 - c;
    let l2 = (b0 - a0).xy().norm_squared();
    let (mut pos, mut routes) = (0.0f64, 0.0f64);
    for i in 0..36 {
        let q = 2.0 * PI * i as f64 / 36.0;
        let a = V3::new(0.0, 0.05 * q.cos(), 0.05 * q.sin());
        let d = (c - a).xy();
        let (p, qq) = (2.0 * (d.x * b.x + d.y * b.y), 2.0 * (d.y * b.x - d.x * b.y));
        let r = l2 - d.norm_squared() - b.xy().norm_squared();
        let phi = qq.atan2(p) - (r / p.hypot(qq)).acos();
        let bb = c + V3::new(
            b.x * phi.cos() - b.y * phi.sin(),
            b.x * phi.sin() + b.y * phi.cos(),
            b.z,
        );
        let pose = m.pose(&[q]).unwrap();
        // `B` moves with the rod, the first link to list it: A_z above its drawing height
        pos = pos.max((pose.point("B").unwrap() - V3::new(bb.x, bb.y, b0.z + a.z)).amax());
        let rocker = pose.link("rocker").unwrap();
        let rocker_b = rocker.cg + rocker.rotation * (b0 - V3::new(0.25, 0.07, 0.09));
        pos = pos.max((rocker_b - bb).amax());
        routes = routes.max(three_routes(&m, &loads, q, 5.0, 17.0));
    }
    eprintln!("RSCR: positions {pos:.1e} m, routes {routes:.1e}");
    assert!(pos < 1e-12 && routes < 1e-10, "{pos} {routes}");
}

/// Two inputs: the RSSR's rocker pinned to a slider on a skew guide (inputs O and the
/// guide). With the slide held at 0 (s = ṡ = s̈ = 0) it is the RSSR: the same points and
/// motor torque at O, and the guide's motor force is what holds the slider against the
/// rocker and gravity, (F_C of the RSSR − m_s g)·w; virtual power gives both motor actions.
#[test]
fn two_inputs_with_one_held_give_the_rssr() {
    let text = RSSR
        .replace(
            "ground { O: (0.0, 0.0, 0.0), C: (250 mm, 120 mm, 80 mm) },",
            "ground { O: (0.0, 0.0, 0.0) },\n    link slider { points { C: (250 mm, 120 mm, 80 mm) }, mass: 3.0, cg: (0.26, 0.11, 0.07), inertia: (1e-3, 1e-3, 1e-3, 0.0, 0.0, 0.0) },",
        )
        .replace(
            "C: revolute(ground, rocker) axis (0.0, 0.0, 1.0),",
            "C: revolute(slider, rocker) axis (0.0, 0.0, 1.0),\n        guide: prismatic(ground, slider) at C along (0.3, 1.0, -0.2),",
        )
        .replace("input: O,", "inputs: [O, guide],");
    let two = SpatialMechanism::from_dsl(&text).unwrap();
    let one = SpatialMechanism::from_dsl(RSSR).unwrap();
    assert_eq!((two.dof(), two.idle_links()), (2, vec!["rod"]));
    let (l1, l2) = (rssr_loads(&one), rssr_loads(&two));
    let w = V3::new(0.3, 1.0, -0.2).normalize();
    let g = V3::new(0.0, 0.0, -9.81);
    let mut worst = 0.0f64;
    for k in 0..12 {
        let q = 2.0 * PI * k as f64 / 12.0;
        let (qd, qdd) = (6.0 - k as f64, 20.0 * q.cos());
        let a = one.kinematics(&[q], &[qd], &[qdd]).unwrap();
        let b = two.kinematics(&[q, 0.0], &[qd, 0.0], &[qdd, 0.0]).unwrap();
        for p in ["A", "B", "C"] {
            worst = worst.max((a.point(p).unwrap() - b.point(p).unwrap()).amax() / 0.3);
        }
        let (fa, fb) = (
            one.kinetostatics(&a, &l1).unwrap(),
            two.kinetostatics(&b, &l2).unwrap(),
        );
        let scale = fa.drivers[0]
            .abs()
            .max(fa.reaction("C").unwrap().force.amax());
        let push = (fa.reaction("C").unwrap().force - g * 3.0).dot(&w);
        worst = worst.max((fa.drivers[0] - fb.drivers[0]).abs() / scale);
        worst = worst.max((push - fb.drivers[1]).abs() / scale);
        let power = two.driver_action(&b, &l2).unwrap();
        worst = worst
            .max((power[0] - fb.drivers[0]).abs() / scale)
            .max((power[1] - fb.drivers[1]).abs() / scale);
        // the rocker's pin: the RSSR's ground reaction is now the slider's
        let (ra, rb) = (fa.reaction("C").unwrap(), fb.reaction("C").unwrap());
        worst = worst
            .max((ra.force - rb.force).amax() / scale)
            .max((ra.moment - rb.moment).amax() / scale);
    }
    eprintln!("two inputs, one held: {worst:.1e} relative");
    assert!(worst < 1e-12, "{worst}");
}

/// The drawing's assembly is kept: the RSSR drawn in its other assembly (B at the closed
/// form's second root at q = 0) follows that assembly's closed form over a full turn.
#[test]
fn the_rssr_drawn_in_its_other_assembly_stays_in_it() {
    let first = RssrClosed::new();
    let flipped = RssrClosed {
        sign: 1.0,
        ..RssrClosed::new()
    };
    let (_, b0, phi0, _) = flipped.solve(0.0);
    assert!(phi0.abs() > 0.5, "a distinct assembly: {phi0}");
    let a0 = first.a0;
    let other = RssrClosed {
        b: b0 - first.c,
        sign: 1.0,
        ..RssrClosed::new()
    };
    let mid = (a0 + b0) * 0.5;
    let text = RSSR
        .replace(
            "B: (0.25, 0.02, 0.08)",
            &format!("B: ({:?}, {:?}, {:?})", b0.x, b0.y, b0.z),
        )
        .replace(
            "cg: (0.125, 0.035, 0.04)",
            &format!("cg: ({:?}, {:?}, {:?})", mid.x, mid.y, mid.z),
        );
    let m = SpatialMechanism::from_dsl(&text).unwrap();
    let mut worst = 0.0f64;
    for k in 0..72 {
        let q = 2.0 * PI * k as f64 / 72.0;
        let (a, b, _, _) = other.solve(q);
        let (_, b_first, _, _) = first.solve(q);
        let pose = m.pose(&[q]).unwrap();
        worst = worst
            .max((pose.point("A").unwrap() - a).amax())
            .max((pose.point("B").unwrap() - b).amax());
        assert!(
            (b - b_first).norm() > 1e-3,
            "the assemblies stay apart at {q}"
        );
    }
    eprintln!("RSSR, other assembly: positions {worst:.1e} m");
    assert!(worst < 1e-12, "{worst}");
}

/// The idle spin is idle for a thin rod: with the rod's inertia I_t (1 − e eᵀ) (none about
/// its own axis e) and its cg on AB, the moment fixing its spin vanishes; with a general
/// tensor it does not (the spin convention then needs a moment, which does no work).
#[test]
fn a_thin_rod_needs_no_moment_to_fix_its_spin() {
    let e = (V3::new(0.25, 0.02, 0.08) - V3::new(0.0, 0.05, 0.0)).normalize();
    let it = 3e-3;
    let six = [
        it * (1.0 - e.x * e.x),
        it * (1.0 - e.y * e.y),
        it * (1.0 - e.z * e.z),
        it * e.x * e.y,
        it * e.x * e.z,
        it * e.y * e.z,
    ];
    let thin = RSSR.replace(
        "inertia: (2e-4, 3e-3, 2.5e-3, 3e-5, 1e-5, -4e-5)",
        &format!(
            "inertia: ({:?}, {:?}, {:?}, {:?}, {:?}, {:?})",
            six[0], six[1], six[2], six[3], six[4], six[5]
        ),
    );
    for (text, thin_rod) in [(thin.as_str(), true), (RSSR, false)] {
        let m = SpatialMechanism::from_dsl(text).unwrap();
        let loads = rssr_loads(&m);
        let mut largest = 0.0f64;
        for k in 0..12 {
            let q = 2.0 * PI * k as f64 / 12.0;
            let motion = m.kinematics(&[q], &[9.0], &[-30.0]).unwrap();
            let f = m.kinetostatics(&motion, &loads).unwrap();
            assert_eq!(f.spin_moments.len(), 1);
            assert_eq!(f.spin_moment("rod"), Some(f.spin_moments[0]));
            assert_eq!(f.spin_moment("crank"), None);
            largest = largest.max(f.spin_moments[0].norm() / f.driver().abs().max(1.0));
        }
        eprintln!("spin moment, thin rod {thin_rod}: {largest:.1e} relative");
        assert_eq!(largest < 1e-13, thin_rod, "{largest}");
    }
}

/// The double-wishbone suspension of tools/suspension_reference.py (mpmath, 50 digits, its
/// own formulation: four distance equations, rates by mpmath.diff, Newton–Euler with 23
/// unknowns): every point's motion, every body's cg motion, rotation, ω and α, every
/// reaction and the driver torque, each kind within 1e-12 of its scale. The tie rod's idle
/// spin is fixed by another convention there (ω normal to its axis): its ω is compared
/// without its component along the axis e, its α without the spin's terms (ṡ e + s ω × e).
#[test]
fn a_double_wishbone_matches_the_mpmath_suspension_table() {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../tests/data/spatial/double_wishbone.truth.json"
    );
    let data: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap();
    let m = SpatialMechanism::from_dsl(data["source"].as_str().unwrap()).unwrap();
    assert_eq!(m.idle_links(), vec!["tierod"]);
    let num = |x: &serde_json::Value| -> f64 { x.as_str().unwrap().parse().unwrap() };
    let vec =
        |x: &serde_json::Value| -> V3 { V3::from_iterator(x.as_array().unwrap().iter().map(num)) };
    let mut loads = m.loads();
    for name in ["wheel", "brake"] {
        let v = vec(&data["loads"][name]);
        assert!(loads.set_by_name(name, v.as_slice()));
    }
    let mut pairs: Vec<(&str, f64, f64)> = Vec::new();
    let mut push = |kind: &'static str, a: V3, b: V3| {
        for k in 0..3 {
            pairs.push((kind, a[k], b[k]));
        }
    };
    for c in data["cases"].as_array().unwrap() {
        let (q, qd, qdd) = (num(&c["q"]), num(&c["qd"]), num(&c["qdd"]));
        let motion = m.kinematics(&[q], &[qd], &[qdd]).unwrap();
        for (name, p) in c["points"].as_object().unwrap() {
            let got = motion.point_motion(name).unwrap();
            push("position", vec(&p["pos"]), got[0]);
            push("velocity", vec(&p["vel"]), got[1]);
            push("acceleration", vec(&p["acc"]), got[2]);
        }
        let tie = motion.point("Tb").unwrap() - motion.point("Ti").unwrap();
        let e = tie.normalize();
        for (name, l) in c["links"].as_object().unwrap() {
            let got = motion.link(name).unwrap();
            push("position", vec(&l["cg"]), got.cg);
            push("velocity", vec(&l["v"]), got.cg_velocity);
            push("acceleration", vec(&l["a"]), got.cg_acceleration);
            // ω = ω⊥ + s e, α = dω⊥/dt + ṡ e + s ω⊥ × e: ω⊥ = e × ė and dω⊥/dt are the
            // axis's own motion, the same in any convention for the spin s
            let tierod = name == "tierod";
            let omega = |w: V3| if tierod { w - e * e.dot(&w) } else { w };
            let alpha = |a: V3, w: V3| {
                if tierod {
                    a - e * e.dot(&a) - w.cross(&e) * e.dot(&w)
                } else {
                    a
                }
            };
            let w_ref = vec(&l["omega"]);
            push("omega", omega(w_ref), omega(got.omega));
            push(
                "alpha",
                alpha(vec(&l["alpha"]), w_ref),
                alpha(got.alpha, got.omega),
            );
            if let Some(r) = l.get("R") {
                let rm = got.rotation.to_rotation_matrix();
                for i in 0..3 {
                    push("rotation", vec(&r[i]), rm.matrix().row(i).transpose());
                }
            }
        }
        let f = m.kinetostatics(&motion, &loads).unwrap();
        for (name, r) in c["reactions"].as_object().unwrap() {
            let got = f.reaction(name).unwrap();
            push("force", vec(&r["force"]), got.force);
            push("moment", vec(&r["moment"]), got.moment);
        }
        let tau = num(&c["driver"]);
        push(
            "moment",
            V3::new(tau, 0.0, 0.0),
            V3::new(f.driver(), 0.0, 0.0),
        );
        push(
            "moment",
            V3::new(tau, 0.0, 0.0),
            V3::new(m.driver_action(&motion, &loads).unwrap()[0], 0.0, 0.0),
        );
    }
    let mut report = String::new();
    let mut worst = 0.0f64;
    for kind in [
        "position",
        "velocity",
        "acceleration",
        "rotation",
        "omega",
        "alpha",
        "force",
        "moment",
    ] {
        let these: Vec<_> = pairs.iter().filter(|p| p.0 == kind).collect();
        let scale = these.iter().map(|p| p.1.abs()).fold(0.0, f64::max);
        let err = these.iter().map(|p| (p.1 - p.2).abs()).fold(0.0, f64::max) / scale;
        report += &format!(" {kind} {err:.1e} (of {scale:.3});");
        worst = worst.max(err);
    }
    eprintln!("double wishbone against mpmath:{report}");
    assert!(worst < 1e-12, "{report}");
}

/// `#[allow(redundant)]`: four revolutes in space (Kutzbach −2, the rank's mobility 1). The
/// planar four-bar so declared gives the planar Mechanism's motion and, by virtual power,
/// its motor torque; its reactions are refused (statically indeterminate).
#[test]
fn four_revolutes_with_allow_redundant_give_the_planar_motion_and_torque() {
    let text = PLANAR_IN_SPACE
        .replace(
            "A: spherical(crank, coupler)",
            "A: revolute(crank, coupler) axis (0.0, 0.0, 1.0)",
        )
        .replace(
            "universal(coupler, rocker) axes (0.0, 0.0, 1.0) (0.05, -0.16, 0.0)",
            "revolute(coupler, rocker) axis (0.0, 0.0, 1.0)",
        );
    assert!(SpatialMechanism::from_dsl(&text).is_err());
    let space = SpatialMechanism::from_dsl(&format!("#[allow(redundant)]\n{text}")).unwrap();
    let plane = Mechanism::from_dsl(PLANAR).unwrap();
    let mut pl = plane.loads();
    assert!(pl.set_by_name("push", &[3.0, -2.0]) && pl.set_by_name("tool", &[1.5]));
    let mut sl = space.loads();
    assert!(sl.set_by_name("push", &[3.0, -2.0, 0.0]) && sl.set_by_name("tool", &[0.0, 0.0, 1.5]));
    let mut worst = 0.0f64;
    for k in 0..36 {
        let q = 2.0 * PI * k as f64 / 36.0;
        let (qd, qdd) = (7.0, -20.0 + k as f64);
        let a = plane
            .kinematics(&[q + 0.06f64.atan2(0.02)], &[qd], &[qdd])
            .unwrap();
        let b = space.kinematics(&[q], &[qd], &[qdd]).unwrap();
        for p in ["A", "B"] {
            let (pa, pb) = (a.point(p).unwrap(), b.point_motion(p).unwrap());
            worst = worst
                .max((pa.pos - pb[0].xy()).amax() / 0.3)
                .max((pa.acc - pb[2].xy()).amax() / (0.3 * qd * qd));
        }
        let torque = plane.kinetostatics(&a, &pl).unwrap().driver[0];
        worst = worst
            .max((torque - space.driver_action(&b, &sl).unwrap()[0]).abs() / torque.abs().max(1.0));
        worst = worst.max(three_routes_without_reactions(&space, &sl, q, qd, qdd));
        assert!(matches!(
            space.kinetostatics(&b, &sl),
            Err(MechError::Redundant(_))
        ));
    }
    eprintln!("four revolutes, allow(redundant): {worst:.1e} relative");
    assert!(worst < 1e-12, "{worst}");
    // a wrong count of inputs is still refused, by the rank's mobility
    let m = invalid(&format!(
        "#[allow(redundant)]\n{}",
        text.replace("input: O2,", "")
    ));
    assert!(
        m.contains("the mobility is the rank's") && m.contains("= 1 at the drawing"),
        "{m}"
    );
}

/// Virtual power against Zhukovski, for a mechanism without reactions.
fn three_routes_without_reactions(
    m: &SpatialMechanism,
    loads: &SpatialLoads,
    q: f64,
    qd: f64,
    qdd: f64,
) -> f64 {
    let motion = m.kinematics(&[q], &[qd], &[qdd]).unwrap();
    let power = m.driver_action(&motion, loads).unwrap()[0];
    let r = m.reduced(q).unwrap();
    let zhukovski = r.inertia * qdd + 0.5 * r.inertia_derivative * qd * qd
        - m.reduced_moment(q, loads).unwrap();
    (power - zhukovski).abs() / power.abs().max(1e-3)
}

/// The spherical four-bar (every axis through the centre; arcs 20°, 60°, 50°, ground 70°:
/// a crank), with `#[allow(redundant)]`: the coupler–rocker axis against the closed form of
/// two cones, c₂·g₂ = cos 50°, c₂·c₁ = cos 60°, |c₂| = 1, over a full turn; virtual power
/// and Zhukovski agree.
#[test]
fn a_spherical_four_bar_matches_its_closed_form() {
    let r = 0.1;
    let deg = |d: f64| d.to_radians();
    let g1 = V3::z();
    let g2 = V3::new(deg(70.0).sin(), 0.0, deg(70.0).cos());
    let c1_0 = V3::new(
        deg(20.0).sin() * deg(60.0).cos(),
        deg(20.0).sin() * deg(60.0).sin(),
        deg(20.0).cos(),
    );
    let (cb, cg) = (deg(50.0).cos(), deg(60.0).cos());
    // c₂ = x g₂ + y c₁ + z (g₂ × c₁), the + branch
    let cone = |c1: V3| {
        let k = g2.dot(&c1);
        let (x, y) = ((cb - k * cg) / (1.0 - k * k), (cg - k * cb) / (1.0 - k * k));
        let base = g2 * x + c1 * y;
        let n = g2.cross(&c1);
        base + n * ((1.0 - base.norm_squared()).sqrt() / n.norm())
    };
    let c2_0 = cone(c1_0);
    let p = |v: V3| format!("({:?}, {:?}, {:?})", r * v.x, r * v.y, r * v.z);
    let a = |v: V3| format!("({:?}, {:?}, {:?})", v.x, v.y, v.z);
    let text = format!(
        "#[allow(redundant)]
        pub struct Spherical {{
            space,
            gravity: (0.0, 0.0, -9.81),
            ground {{ O1: {}, O4: {} }},
            link crank {{ points {{ O1, A: {} }}, mass: 0.3, cg: {}, inertia: (1e-4, 2e-4, 1.5e-4, 1e-5, 0.0, 2e-5) }},
            link coupler {{ points {{ A, B: {} }}, mass: 0.5, cg: {}, inertia: (3e-4, 2e-4, 4e-4, 0.0, 3e-5, 0.0) }},
            link rocker {{ points {{ B, O4 }}, mass: 0.4, cg: {}, inertia: (2e-4, 2e-4, 1e-4, 0.0, 0.0, 1e-5) }},
            joints {{
                O1: revolute(ground, crank) axis {},
                A: revolute(crank, coupler) axis {},
                B: revolute(coupler, rocker) axis {},
                O4: revolute(rocker, ground) axis {},
            }},
            input: O1,
            loads {{ tool: torque on rocker }},
        }}",
        p(g1), p(g2), p(c1_0), p((g1 + c1_0) * 0.5), p(c2_0), p((c1_0 + c2_0) * 0.5), p((c2_0 + g2) * 0.5),
        a(g1), a(c1_0), a(c2_0), a(g2)
    );
    let m = SpatialMechanism::from_dsl(&text).unwrap();
    let mut loads = m.loads();
    loads.set_by_name("tool", &[0.2, -0.1, 0.5]);
    let (mut pos, mut routes) = (0.0f64, 0.0f64);
    for k in 0..72 {
        let q = 2.0 * PI * k as f64 / 72.0;
        let c1 =
            c1_0 * q.cos() + g1.cross(&c1_0) * q.sin() + g1 * (g1.dot(&c1_0) * (1.0 - q.cos()));
        let pose = m.pose(&[q]).unwrap();
        pos = pos
            .max((pose.point("A").unwrap() - c1 * r).amax())
            .max((pose.point("B").unwrap() - cone(c1) * r).amax());
        routes = routes.max(three_routes_without_reactions(&m, &loads, q, 4.0, -9.0));
    }
    eprintln!("spherical four-bar: positions {pos:.1e} m, routes {routes:.1e}");
    assert!(pos < 1e-12 && routes < 1e-10, "{pos} {routes}");
}

/// `set_param` gives the mechanism of the text with that number changed (the text edited
/// and loaded is the reference): a point (the rod's far ball), a link's mass, cg and
/// inertia, an axis, gravity — the same poses and driver torques to the bit; a refused
/// change (unknown name, a count, a magnitude, a tensor that is not positive, an axis of
/// no direction, a drawing whose constraint Jacobian loses rank) names the fix and leaves
/// the mechanism as it was.
#[test]
fn set_param_is_the_edited_text() {
    let text = include_str!("../../examples/mech/rssr.mech");
    let base = SpatialMechanism::from_dsl(text).unwrap();
    let cases: [(&str, &[f64], &str, &str); 6] = [
        (
            "points.B",
            &[0.26, 0.03, 0.07],
            "B: (0.25, 0.02, 0.08)",
            "B: (0.26, 0.03, 0.07)",
        ),
        ("links.rod.mass", &[0.7], "mass: 0.5", "mass: 0.7"),
        (
            "links.rocker.cg",
            &[0.24, 0.08, 0.1],
            "cg: (0.25, 0.07, 0.09)",
            "cg: (0.24, 0.08, 0.1)",
        ),
        (
            "links.crank.inertia",
            &[2e-3, 4e-4, 9e-4, 1e-4, -2e-5, 5e-5],
            "inertia: (1e-3, 4e-4, 9e-4, 1e-4, -2e-5, 5e-5)",
            "inertia: (2e-3, 4e-4, 9e-4, 1e-4, -2e-5, 5e-5)",
        ),
        (
            "axes.C",
            &[0.0, 0.1, 1.0],
            "axis (0.0, 0.0, 1.0)",
            "axis (0.0, 0.1, 1.0)",
        ),
        (
            "gravity",
            &[0.0, -9.81, 0.0],
            "gravity: (0.0, 0.0, -9.81)",
            "gravity: (0.0, -9.81, 0.0)",
        ),
    ];
    for (path, value, from, to) in cases {
        assert!(text.contains(from), "{from}");
        let edited = SpatialMechanism::from_dsl(&text.replacen(from, to, 1)).unwrap();
        let mut m = base.clone();
        m.set_param(path, value).unwrap();
        for q in [0.3, 2.0, -1.2] {
            let (a, b) = (
                m.kinematics(&[q], &[4.0], &[1.0]).unwrap(),
                edited.kinematics(&[q], &[4.0], &[1.0]).unwrap(),
            );
            assert_eq!(a.bodies, b.bodies, "{path} at {q}");
            let (la, lb) = (rssr_loads(&m), rssr_loads(&edited));
            assert_eq!(
                m.driver_action(&a, &la).unwrap(),
                edited.driver_action(&b, &lb).unwrap(),
                "{path} at {q}"
            );
        }
    }
    let refused: [(&str, &[f64], &str); 8] = [
        ("points.Z", &[0.0, 0.0, 0.0], "unknown point"),
        ("points.B", &[0.1, 0.2], "takes 3 number(s)"),
        ("links.ground.mass", &[1.0], "unknown moving link"),
        ("links.rod.mass", &[1e12], "a mass is 0 or within"),
        (
            "links.rod.inertia",
            &[1e-3, 1e-3, 1e-3, 5e-3, 0.0, 0.0],
            "not positive semi-definite",
        ),
        ("axes.O", &[0.0, 0.0, 0.0], "has no direction"),
        ("axes.A", &[0.0, 0.0, 1.0], "a spherical joint has no axis"),
        // the rocker's axis through B: the rocker cannot move B (a rank deficiency)
        ("axes.C", &[0.0, 1.0, 0.0], "rank"),
    ];
    for (path, value, says) in refused {
        let mut m = base.clone();
        let e = m.set_param(path, value).unwrap_err().to_string();
        assert!(e.contains(says), "{path}: {e}");
        assert_eq!(m.model(), base.model(), "{path}: unchanged on error");
    }
}
