//! Spatial mechanisms at run time (issue 33) against independent references: the RSSR's and
//! the RSSP's closed forms over a full turn, the planar run-time `Mechanism` on a planar
//! four-bar declared with `space`, the three routes to the driver torque, energy kept by the
//! direct problem, an mpmath Newton–Euler table of a spatial slider-crank, and the load-time
//! errors.

use mech_core::solvers::traits::Machine;
use mech_core::spatial::{SpatialLoads, SpatialMechanism};
use mech_core::MechError;
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

fn sub(a: [f64; 3], b: [f64; 3]) -> V3 {
    V3::from(a) - V3::from(b)
}

/// The RSSR's closed form (independent of the solver): A(q) on the crank circle about x,
/// B(φ) on the rocker circle about z through C, |B − A| = L solved as P cos φ + Q sin φ = R
/// on the drawing's branch; φ' = −f_q / f_φ for f = |B − A|² − L².
struct RssrClosed {
    a0: V3,
    c: V3,
    b: V3,
    l: f64,
}

impl RssrClosed {
    fn new() -> Self {
        let (a0, c, b0) = (V3::new(0.0, 0.05, 0.0), V3::new(0.25, 0.12, 0.08), V3::new(0.25, 0.02, 0.08));
        RssrClosed { a0, c, b: b0 - c, l: (b0 - a0).norm() }
    }
    fn a(&self, q: f64) -> V3 {
        V3::new(0.0, self.a0.y * q.cos() - self.a0.z * q.sin(), self.a0.y * q.sin() + self.a0.z * q.cos())
    }
    fn rz(v: V3, phi: f64) -> V3 {
        V3::new(v.x * phi.cos() - v.y * phi.sin(), v.x * phi.sin() + v.y * phi.cos(), v.z)
    }
    /// (A, B, φ, φ').
    fn solve(&self, q: f64) -> (V3, V3, f64, f64) {
        let a = self.a(q);
        let (d, b) = (self.c - a, self.b);
        let p = 2.0 * (d.x * b.x + d.y * b.y);
        let qq = 2.0 * (d.y * b.x - d.x * b.y);
        let r = self.l * self.l - d.norm_squared() - b.norm_squared() - 2.0 * d.z * b.z;
        let phi = qq.atan2(p) - (r / p.hypot(qq)).acos();
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
        worst_pos = worst_pos.max((pose.point("A").unwrap() - a).amax()).max((pose.point("B").unwrap() - b).amax());
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
        assert!(((a + (b - a) * t) - rod_cg).norm() < 1e-12, "the rod's cg is on AB");
        let rod_g = va + (vb - va) * t;
        let power = loads.values[0].dot(&(V3::z() * phi_dot)) + loads.values[1].dot(&vb)
            + g.dot(&(crank_g * 1.0 + rod_g * 0.5 + rocker_g * 0.8));
        let tau = -power;
        let got = m.driver_action(&pose, &loads).unwrap()[0];
        let f = m.kinetostatics(&pose, &loads).unwrap();
        worst_torque = worst_torque.max((got - tau).abs() / tau.abs().max(1.0)).max((f.driver() - tau).abs() / tau.abs().max(1.0));
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
        worst_pos = worst_pos.max((pose.point("A").unwrap() - a).amax()).max((pose.point("B").unwrap() - b).amax());
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
    let zhukovski = r.inertia * qdd + 0.5 * r.inertia_derivative * qd * qd - m.reduced_moment(q, loads).unwrap();
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
        worst = worst.max(three_routes(&m, &loads, q, 12.0 - k as f64, 40.0 * (q).sin()));
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
