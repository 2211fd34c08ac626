//! Spatial mechanisms through `mechanism!` (issue 33, SPEC 3i): the generated struct of a
//! `space` declaration against independent references — a planar four-bar declared with
//! `space` against the planar generated struct (reactions included), the RSSR's loop
//! equations and the three routes to its driver torque, energy kept by the direct problem
//! through the `Machine` / `OneDof` traits — and its declaration written out by the macro
//! equal to the run-time loader's. The compile-time errors are trybuild cases
//! (`tests/ui/spatial_*.rs`).

use mech::dynamics::ode::{integrate, Dop853};
use mech::dynamics::{equation_of_motion, total_energy};
use mech::prelude::*;
use mech::spatial::SpatialMechanism;
use std::f64::consts::PI;

mechanism! {
    /// A spatial four-bar, RSSR: a crank turning about x drives, through a rod with a ball
    /// joint at each end, a rocker turning about z (examples/mech/rssr.mech).
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
}

mechanism! {
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
}

mechanism! {
    /// The same four-bar in space: revolute axes along z at z = 0, A spherical and B
    /// universal (z in the coupler, the rocker's line in the rocker) so that Kutzbach's count
    /// is 1 (four revolutes in space are over-constrained: G = −2); Izz as the planar
    /// inertia, Ixx, Iyy, Ixy arbitrary (Ixz = Iyz = 0 keeps the motion planar).
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
}

mechanism! {
    /// The RSSR with its rocker's pivot on a slider along a skew guide: two inputs, so `Q`
    /// is `[f64; 2]`.
    pub struct RssrOnSlider {
        space,
        gravity: (0.0, 0.0, -9.81),
        ground { O: (0.0, 0.0, 0.0) },
        link slider { points { C: (250 mm, 120 mm, 80 mm) }, mass: 3.0, cg: (0.26, 0.11, 0.07),
                      inertia: (1e-3, 1e-3, 1e-3, 0.0, 0.0, 0.0) },
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
            C: revolute(slider, rocker) axis (0.0, 0.0, 1.0),
            guide: prismatic(ground, slider) at C along (0.3, 1.0, -0.2),
        },
        inputs: [O, guide],
        loads { tool: torque on rocker, push: force on rod at B },
    }
}

fn rssr_loads() -> RssrLoads {
    RssrLoads {
        tool: Vector3::new(0.3, -0.2, 1.7),
        push: Vector3::new(4.0, -3.0, 2.5),
    }
}

/// The macro writes out the declaration the run-time loader reads from the same text
/// (`examples/mech/rssr.mech`): every number to the bit, the inertia tensor's products
/// with their sign; and the counts of Kutzbach's formula as constants.
#[test]
fn the_generated_declaration_is_the_loaders() {
    let text = include_str!("../examples/mech/rssr.mech");
    let loaded = SpatialMechanism::from_dsl(text).unwrap();
    assert_eq!(&Rssr::model(), loaded.model());
    assert_eq!(Rssr::new().mechanism().model(), loaded.model());
    // N = 4; P_I = 2 revolutes (5 equations each), P_III = 2 spherical (3 each):
    // G = 6·3 − 10 − 6 = 2, one of them the rod's idle spin.
    assert_eq!(
        (Rssr::DOF, Rssr::LINKS, Rssr::EQUATIONS, Rssr::IDLE),
        (1, 4, 18, 1)
    );
    assert_eq!(Rssr::UNKNOWNS, 1 + 2 * 5 + 2 * 3 + 1);
    assert_eq!(Rssr::EQUATIONS, Rssr::UNKNOWNS);
    let b = &Rssr::model().bodies[1];
    assert_eq!(
        b.inertia[(0, 1)],
        -1e-4,
        "Ixy = Σ m x y enters the tensor negated"
    );
}

/// The RSSR's loop equations hold at every position over a full turn (A on the crank's
/// circle about x, B on the rocker's circle about z through C, |AB| kept), velocities and
/// accelerations are the central differences of the positions, and the generated struct's
/// answers are the run-time mechanism's to rounding.
#[test]
fn the_generated_rssr_closes_its_loop_over_a_full_turn() {
    let m = Rssr::new();
    let (a0, b0, c): (Vector3<f64>, Vector3<f64>, Vector3<f64>) = (
        Vector3::new(0.0, 0.05, 0.0),
        Vector3::new(0.25, 0.02, 0.08),
        Vector3::new(0.25, 0.12, 0.08),
    );
    let (mut loop_err, mut rate_err, mut same) = (0.0f64, 0.0f64, 0.0f64);
    let h = 1e-5;
    for k in 0..72 {
        let q = 2.0 * PI * k as f64 / 72.0;
        let (qd, qdd) = (5.0, -3.0);
        let mo = m.kinematics(q, qd, qdd).unwrap();
        let (a, b) = (mo.points.A.pos, mo.points.B.pos);
        loop_err = loop_err
            .max((a.x).abs())
            .max((a.yz().norm() - a0.yz().norm()).abs())
            .max((b.z - c.z).abs())
            .max(((b - c).xy().norm() - (b0 - c).xy().norm()).abs())
            .max(((b - a).norm() - (b0 - a0).norm()).abs());
        assert_eq!(mo.points.C.pos, c);
        let p = |x: f64| m.pose(x).unwrap().points.B.pos;
        let v = (p(q + h) - p(q - h)) / (2.0 * h) * qd;
        let acc_q = (p(q + h) - 2.0 * p(q) + p(q - h)) / (h * h);
        let dv = (p(q + h) - p(q - h)) / (2.0 * h);
        rate_err = rate_err
            .max((v - mo.points.B.vel).amax() / 0.3 / qd)
            .max((acc_q * qd * qd + dv * qdd - mo.points.B.acc).amax() / 0.3 / (qd * qd));
        // the same equations solved on the heap (nalgebra's LU) and on the stack (the
        // fixed-size LU): equal to rounding
        let rt = m.mechanism().kinematics(&[q], &[qd], &[qdd]).unwrap();
        let (acc, rocker) = (rt.point_motion("B").unwrap()[2], rt.link("rocker").unwrap());
        same = same
            .max((acc - mo.points.B.acc).amax() / acc.amax())
            .max((rocker.alpha - mo.links.rocker.alpha).amax() / rocker.alpha.amax())
            .max(rocker.rotation.angle_to(&mo.links.rocker.rotation));
    }
    // measured 0 since both take the RSSR's rates from its kernel (4.1e-14 when the two
    // frames' LUs solved them)
    assert!(same < 1e-12, "generated against run-time: {same}");
    eprintln!("generated RSSR: loop {loop_err:.1e} m, rates {rate_err:.1e} relative, against the run-time {same:.1e}");
    assert!(loop_err < 1e-12, "{loop_err}");
    assert!(rate_err < 1e-5, "{rate_err}");
}

/// d'Alembert (`kinetostatics`), virtual power (`driver_action`) and Zhukovski
/// (I* q̈ + ½ dI*/dq q̇² − M*) give one driver torque.
#[test]
fn the_three_routes_agree_on_the_generated_rssr() {
    let m = Rssr::new();
    let loads = rssr_loads();
    let mut worst = 0.0f64;
    for k in 0..24 {
        let q = 2.0 * PI * k as f64 / 24.0 + 0.1;
        let (qd, qdd) = (12.0 - k as f64, 40.0 * q.sin());
        let mo = m.kinematics(q, qd, qdd).unwrap();
        let dalembert = m.kinetostatics(&mo, &loads).unwrap().driver;
        let power = m.driver_action(&mo, &loads).unwrap();
        let r = m.reduced(q).unwrap();
        let zhukovski = r.inertia * qdd + 0.5 * r.inertia_derivative * qd * qd
            - m.reduced_moment(q, &loads).unwrap();
        let scale = dalembert.abs().max(1e-3);
        worst = worst
            .max((dalembert - power).abs() / scale)
            .max((dalembert - zhukovski).abs() / scale);
    }
    eprintln!("generated RSSR, three routes: {worst:.1e} relative");
    assert!(worst < 1e-10, "{worst}");
}

/// The planar four-bar declared with `space` gives the planar generated struct's numbers:
/// points, link rates, the driver torque and every reaction force; the out-of-plane
/// components are zero.
#[test]
fn a_planar_four_bar_declared_in_space_gives_the_planar_structs_numbers() {
    let (plane, space) = (FourBar::new(), FourBar3::new());
    let pl = FourBarLoads {
        push: Vector2::new(3.0, -2.0),
        tool: 1.5,
    };
    let sl = FourBar3Loads {
        push: Vector3::new(3.0, -2.0, 0.0),
        tool: Vector3::new(0.0, 0.0, 1.5),
    };
    let (mut kin, mut force, mut out_of_plane) = (0.0f64, 0.0f64, 0.0f64);
    for k in 0..36 {
        let q = 2.0 * PI * k as f64 / 36.0;
        let (qd, qdd) = (7.0, -20.0 + k as f64);
        // the planar q is the crank's angle (SPEC 2), the spatial one its turn from the drawing
        let a = plane.kinematics(q + 0.06f64.atan2(0.02), qd, qdd).unwrap();
        let b = space.kinematics(q, qd, qdd).unwrap();
        for (pa, pb) in [(a.points.A, b.points.A), (a.points.B, b.points.B)] {
            let acc = 0.3 * (qd * qd + qdd.abs());
            kin = kin
                .max((pa.pos - pb.pos.xy()).amax() / 0.3)
                .max((pa.vel - pb.vel.xy()).amax() / (0.3 * qd))
                .max((pa.acc - pb.acc.xy()).amax() / acc)
                .max(
                    pb.pos
                        .z
                        .abs()
                        .max(pb.vel.z.abs() / qd)
                        .max(pb.acc.z.abs() / acc)
                        / 0.3,
                );
        }
        for (la, lb) in [
            (a.links.crank, b.links.crank),
            (a.links.coupler, b.links.coupler),
            (a.links.rocker, b.links.rocker),
        ] {
            kin = kin
                .max((la.omega - lb.omega.z).abs() / qd)
                .max((la.alpha - lb.alpha.z).abs() / (qd * qd + qdd.abs()))
                .max(lb.omega.xy().amax() / qd);
        }
        let (fa, fb) = (
            plane.kinetostatics(&a, &pl).unwrap(),
            space.kinetostatics(&b, &sl).unwrap(),
        );
        let pairs = [
            (fa.joints.O2.force, fb.joints.O2),
            (fa.joints.A.force, fb.joints.A),
            (fa.joints.B.force, fb.joints.B),
            (fa.joints.O4.force, fb.joints.O4),
        ];
        let scale = pairs
            .iter()
            .map(|p| p.0.amax())
            .fold(fa.driver.abs(), f64::max);
        force = force.max((fa.driver - fb.driver).abs() / scale);
        for (ra, rb) in pairs {
            force = force.max((ra - rb.force.xy()).amax() / scale);
            out_of_plane = out_of_plane
                .max(rb.force.z.abs() / scale)
                .max(rb.moment.xy().amax() / (0.3 * scale));
        }
        assert!(
            fb.joints.A.moment.amax() < 1e-12 * scale,
            "a ball joint carries no moment"
        );
    }
    eprintln!("planar in space (macro): kinematics {kin:.1e}, forces {force:.1e}, out of plane {out_of_plane:.1e}");
    assert!(
        kin < 1e-12 && force < 1e-12 && out_of_plane < 1e-12,
        "{kin} {force} {out_of_plane}"
    );
}

/// The idle rod's spin moment (`Forces::spin_moments`) is what the rod's own axis needs:
/// about the line AB through its two balls (whose forces pass through it), the moment
/// balance about A gives M_s·ê = (I α + ω × I ω + (G − A) × m a_G − (G − A) × m g)·ê, I the
/// declared tensor turned to the pose; and the generated value is the run-time one.
#[test]
fn the_idle_rods_spin_moment_balances_its_axis() {
    let m = Rssr::new();
    let rod = &Rssr::model().bodies[2];
    let l = rssr_loads();
    let mut rl = m.mechanism().loads();
    rl.values = vec![l.tool, l.push];
    let g = Vector3::new(0.0, 0.0, -9.81);
    let mut worst = 0.0f64;
    for k in 0..24 {
        let q = 2.0 * PI * k as f64 / 24.0;
        let mo = m.kinematics(q, 6.0, -4.0).unwrap();
        let f = m.kinetostatics(&mo, &l).unwrap();
        let r = mo.links.rod;
        let (a, b) = (mo.points.A.pos, mo.points.B.pos);
        let e = (b - a).normalize();
        let rot = r.rotation.to_rotation_matrix();
        let i = rot.matrix() * rod.inertia * rot.matrix().transpose();
        let ga = r.cg - a;
        let need =
            i * r.alpha + r.omega.cross(&(i * r.omega)) + ga.cross(&(r.cg_acceleration * rod.mass))
                - ga.cross(&(g * rod.mass));
        let scale = need.norm().max(1e-9);
        worst = worst.max((f.spin_moments[0].dot(&e) - need.dot(&e)).abs() / scale);
        let rt = m.mechanism().kinematics(&[q], &[6.0], &[-4.0]).unwrap();
        let rf = m.mechanism().kinetostatics(&rt, &rl).unwrap();
        worst = worst.max((rf.spin_moment("rod").unwrap() - f.spin_moments[0]).amax() / scale);
    }
    eprintln!("the idle rod's spin moment: {worst:.1e} relative");
    assert!(worst < 1e-12, "{worst}");
}

/// Coulomb friction: the four-bar declared in space with friction in every joint gives the
/// planar generated struct's `kinetostatics_with_friction` (pins about z: the spatial
/// revolute's radial load, the ball joint's and the cross's moments reduce to the planar
/// pin's μ r |R|), over a turn in both senses of motion.
#[test]
fn friction_in_the_four_bar_in_space_is_the_planar_structs() {
    use mech::friction::JointFriction;
    let (plane, space) = (FourBar::new(), FourBar3::new());
    let pl = FourBarLoads {
        push: Vector2::new(3.0, -2.0),
        tool: 1.5,
    };
    let sl = FourBar3Loads {
        push: Vector3::new(3.0, -2.0, 0.0),
        tool: Vector3::new(0.0, 0.0, 1.5),
    };
    let fr = [0.15, 0.1, 0.2, 0.12].map(|mu| JointFriction {
        mu,
        pin_radius: 0.01,
    });
    let (mut worst, mut changed) = (0.0f64, 0.0f64);
    for k in 0..36 {
        let q = 2.0 * PI * k as f64 / 36.0;
        let (qd, qdd) = (if k % 2 == 0 { 7.0 } else { -5.0 }, 3.0 - k as f64);
        let a = plane.kinematics(q + 0.06f64.atan2(0.02), qd, qdd).unwrap();
        let b = space.kinematics(q, qd, qdd).unwrap();
        let fa = plane.kinetostatics_with_friction(&a, &pl, &fr).unwrap();
        let fb = space.kinetostatics_with_friction(&b, &sl, &fr).unwrap();
        let f0 = space.kinetostatics(&b, &sl).unwrap();
        let pairs = [
            (fa.joints.O2.force, fb.joints.O2),
            (fa.joints.A.force, fb.joints.A),
            (fa.joints.B.force, fb.joints.B),
            (fa.joints.O4.force, fb.joints.O4),
        ];
        let scale = pairs
            .iter()
            .map(|p| p.0.amax())
            .fold(fa.driver.abs(), f64::max);
        worst = worst.max((fa.driver - fb.driver).abs() / scale);
        for (ra, rb) in pairs {
            worst = worst.max((ra - rb.force.xy()).amax() / scale);
        }
        changed = changed.max((fb.driver - f0.driver).abs() / scale);
    }
    eprintln!("friction, planar in space: {worst:.1e} relative (friction moves the torque by up to {changed:.1e} of the forces)");
    assert!(worst < 1e-10, "{worst}");
    assert!(
        changed > 1e-3,
        "the friction changes the driver torque: {changed}"
    );
}

/// Friction in a truly spatial mechanism: the power the motor adds with friction is what
/// the joints dissipate, (τ_f − τ_0) q̇ = Σ_joints (|M_f·ω_r| + |F_f·v_r|), each joint's
/// friction written here from its law (the revolutes' radial load, the balls' whole force)
/// and the reactions the solver returns, the relative motions from the links' ω; and a
/// joint without relative motion (the crank at rest) gets none.
#[test]
fn friction_in_the_rssr_dissipates_what_the_motor_adds() {
    use mech::friction::JointFriction;
    let (m, l) = (Rssr::new(), rssr_loads());
    let (mu, r) = ([0.12, 0.2, 0.15, 0.1], [0.008, 0.005, 0.006, 0.01]);
    let fr: [JointFriction; 4] = std::array::from_fn(|j| JointFriction {
        mu: mu[j],
        pin_radius: r[j],
    });
    let (x, z) = (Vector3::x(), Vector3::z());
    let mut worst = 0.0f64;
    for k in 0..24 {
        let q = 2.0 * PI * k as f64 / 24.0 + 0.1;
        let qd = if k % 3 == 0 { -6.0 } else { 9.0 };
        let mo = m.kinematics(q, qd, 2.0).unwrap();
        let f = m.kinetostatics_with_friction(&mo, &l, &fr).unwrap();
        let f0 = m.kinetostatics(&mo, &l).unwrap();
        let (crank, rod, rocker) = (
            mo.links.crank.omega,
            mo.links.rod.omega,
            mo.links.rocker.omega,
        );
        let radial = |f: Vector3<f64>, u: Vector3<f64>| (f - u * f.dot(&u)).norm();
        let d = mu[0] * r[0] * radial(f.joints.O.force, x) * crank.dot(&x).abs()
            + mu[1] * r[1] * f.joints.A.force.norm() * (rod - crank).norm()
            + mu[2] * r[2] * f.joints.B.force.norm() * (rocker - rod).norm()
            + mu[3] * r[3] * radial(f.joints.C.force, z) * rocker.dot(&z).abs();
        let added = (f.driver - f0.driver) * qd;
        worst = worst.max((added - d).abs() / d);
        assert!(d > 0.0);
    }
    eprintln!("friction in the RSSR: motor power against dissipation {worst:.1e} relative");
    assert!(worst < 1e-9, "{worst}");
    let rest = m.kinematics(0.5, 0.0, 4.0).unwrap();
    let (a, b) = (
        m.kinetostatics_with_friction(&rest, &l, &fr).unwrap(),
        m.kinetostatics(&rest, &l).unwrap(),
    );
    assert_eq!(a.driver, b.driver, "no relative motion, no friction");
    let bad = [JointFriction {
        mu: -0.1,
        pin_radius: 0.01,
    }; 4];
    assert!(matches!(
        m.kinetostatics_with_friction(&rest, &l, &bad),
        Err(MechError::InvalidInput(_))
    ));
}

/// Two inputs: `Q` is `[f64; 2]`; with the slider held the machine is the RSSR, its
/// rocker's pivot reaction along the guide is the slider's motor force (gravity on the
/// slider added).
#[test]
fn two_inputs_take_arrays_and_one_held_gives_the_rssr() {
    let (two, one) = (RssrOnSlider::new(), Rssr::new());
    assert_eq!((RssrOnSlider::DOF, RssrOnSlider::IDLE), (2, 1));
    let l1 = rssr_loads();
    let l2 = RssrOnSliderLoads {
        tool: l1.tool,
        push: l1.push,
    };
    let w = Vector3::new(0.3, 1.0, -0.2).normalize();
    let g = Vector3::new(0.0, 0.0, -9.81);
    let mut worst = 0.0f64;
    for k in 0..12 {
        let q = 2.0 * PI * k as f64 / 12.0;
        let (qd, qdd) = (6.0 - k as f64, 20.0 * q.cos());
        let a = one.kinematics(q, qd, qdd).unwrap();
        let b = two.kinematics([q, 0.0], [qd, 0.0], [qdd, 0.0]).unwrap();
        worst = worst.max((a.points.B.pos - b.points.B.pos).amax() / 0.3);
        let (fa, fb) = (
            one.kinetostatics(&a, &l1).unwrap(),
            two.kinetostatics(&b, &l2).unwrap(),
        );
        let scale = fa.driver.abs().max(fa.joints.C.force.amax());
        let push = (fa.joints.C.force - g * 3.0).dot(&w);
        let power = two.driver_action(&b, &l2).unwrap();
        worst = worst
            .max((fa.driver - fb.driver[0]).abs() / scale)
            .max((push - fb.driver[1]).abs() / scale)
            .max((power[0] - fb.driver[0]).abs() / scale)
            .max((power[1] - fb.driver[1]).abs() / scale);
    }
    eprintln!("generated, two inputs: {worst:.1e} relative");
    assert!(worst < 1e-12, "{worst}");
}

/// The generated struct is a `Machine` and a `OneDof`: mech's dynamics integrate it, and
/// the RSSR coasting under gravity keeps T + V over three seconds, many turns (DOP853 at
/// 1e-11).
#[test]
fn the_direct_problem_keeps_the_energy_of_the_generated_rssr() {
    let m = Rssr::new();
    let (q0, w0) = (0.3, 20.0);
    let e0 = total_energy(&m, &[q0], &[w0]).unwrap();
    let out = integrate(
        &mut Dop853::new(1e-11, 1e-11),
        equation_of_motion(&m, |_, _, _| (0.0, RssrLoads::default())),
        0.0,
        [q0, w0],
        3.0,
    )
    .unwrap();
    let e1 = total_energy(&m, &[out.y[0]], &[out.y[1]]).unwrap();
    let turns = (out.y[0] - q0) / (2.0 * PI);
    eprintln!(
        "generated RSSR energy: |ΔE| = {:.1e} J of {e0:.4} J over {turns:.1} turns",
        (e1 - e0).abs()
    );
    assert!(turns > 8.0, "it turns many times: {turns}");
    assert!((e1 - e0).abs() < 1e-8 * e0.abs().max(1.0), "{e0} {e1}");
}

/// Allocations made on this thread by `f` (`tests/common/counting.rs`, the global allocator
/// of this binary).
fn allocations<R>(f: impl FnOnce() -> R) -> (usize, R) {
    let before = crate::counting::count();
    let r = f();
    (crate::counting::count() - before, r)
}

/// Every generated spatial solver allocates nothing (its buffers on the stack, J factored
/// by the fixed-size LU): the RSSR (positions by its closed form), the four-bar in space
/// (positions by Newton from the drawing, past several continuation steps) and the RSSR on
/// a slider (two inputs); the `Machine` methods the dynamics call included.
#[test]
fn the_generated_spatial_solvers_do_not_allocate() {
    use mech::{Machine, OneDof};
    macro_rules! none {
        ($what:expr, $e:expr) => {{
            let (n, r) = allocations(|| $e);
            assert_eq!(n, 0, "{} allocated {n} time(s)", $what);
            r
        }};
    }
    let (r, l) = (Rssr::new(), rssr_loads());
    let f = FourBar3::new();
    let fl = FourBar3Loads {
        push: Vector3::new(3.0, -2.0, 0.0),
        tool: Vector3::new(0.0, 0.0, 0.7),
    };
    for q in [0.4, 2.9, -5.5] {
        none!("RSSR pose", r.pose(q)).unwrap();
        let m = none!("RSSR kinematics", r.kinematics(q, 3.0, -2.0)).unwrap();
        none!("RSSR kinetostatics", r.kinetostatics(&m, &l)).unwrap();
        let fr = [mech::friction::JointFriction {
            mu: 0.1,
            pin_radius: 0.01,
        }; 4];
        none!("RSSR friction", r.kinetostatics_with_friction(&m, &l, &fr)).unwrap();
        none!("RSSR driver_action", r.driver_action(&m, &l)).unwrap();
        none!("RSSR reduced", r.reduced(q)).unwrap();
        none!("RSSR reduced_moment", r.reduced_moment(q, &l)).unwrap();
        none!("RSSR acceleration", r.acceleration(q, 3.0, 1.0, &l)).unwrap();
        let mut out = [0.0; 1];
        none!(
            "RSSR Machine::driver_actions",
            Machine::driver_actions(&r, &m, &l, &mut out)
        )
        .unwrap();
        let mut e = [0.0; 4];
        none!(
            "RSSR energies",
            Machine::link_kinetic_energies(&r, &m, &mut e)
        );
        none!("RSSR potential", Machine::potential_energy(&r, &m));
        none!("RSSR shaking", Machine::shaking(&r, &m));
        none!(
            "RSSR OneDof::acceleration",
            OneDof::acceleration(&r, q, 3.0, 1.0, &l)
        )
        .unwrap();

        none!("four-bar pose", f.pose(q)).unwrap();
        let m = none!("four-bar kinematics", f.kinematics(q, 3.0, -2.0)).unwrap();
        none!("four-bar kinetostatics", f.kinetostatics(&m, &fl)).unwrap();
        none!("four-bar driver_action", f.driver_action(&m, &fl)).unwrap();
        none!("four-bar reduced", f.reduced(q)).unwrap();
        none!("four-bar acceleration", f.acceleration(q, 3.0, 1.0, &fl)).unwrap();
    }
    let s = RssrOnSlider::new();
    let sl = RssrOnSliderLoads::default();
    let m = none!(
        "two inputs kinematics",
        s.kinematics([0.4, 0.02], [3.0, 0.1], [-2.0, 0.0])
    )
    .unwrap();
    none!("two inputs kinetostatics", s.kinetostatics(&m, &sl)).unwrap();
    none!("two inputs driver_action", s.driver_action(&m, &sl)).unwrap();
    // a failure allocates its message only
    assert!(matches!(r.pose(f64::NAN), Err(MechError::InvalidInput(_))));
}
