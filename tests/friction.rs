//! Coulomb friction in the joints against closed-form textbook answers, the power balance,
//! and self-locking.

use crate::measure::within;
use mech::friction::JointFriction;
use mech::prelude::*;

mechanism! {
    /// A crank alone on its bearing: the pin reaction is m (a_G − g) whatever the moments.
    pub struct Crank {
        gravity: (0.0, -9.81),
        ground { O: (0.0, 0.0) },
        link crank { points { O, A: (0.12, 0.05) }, mass: 2.0, inertia: 0.01, cg: (0.04, 0.01) },
        joints { O: revolute(ground, crank) },
        input: O,
        loads { work: torque on crank },
    }
}

mechanism! {
    /// A block pushed up a 30° incline by an actuator along the incline.
    pub struct Incline {
        gravity: (0.0, -9.81),
        ground { O: (0.0, 0.0) },
        link block { points { P: (0.8660254037844386, 0.5) }, mass: 12.0, inertia: 0.05, cg: (0.8660254037844386, 0.5) },
        joints { stroke: prismatic(ground, block) at P along (0.8660254037844386, 0.5) },
        input: stroke,
    }
}

mechanism! {
    /// A slider-crank driven from its piston (an actuator on the guide), the crank
    /// braked; a large pin radius at the main bearing.
    pub struct PistonDriven {
        ground { O2: (0.0, 0.0) },
        link crank { points { O2, A: (0.025, 0.04330127018922193) }, mass: 1.0, inertia: 2e-3, cg: (0.01, 0.017320508075688773) },
        link rod { points { A, B: (0.2202562418976664, 0.0) }, mass: 1.5, inertia: 8e-3, cg: (0.14, 0.02) },
        link piston { points { B }, mass: 1.0, cg: (0.2202562418976664, 0.0) },
        joints {
            O2: revolute(ground, crank),
            A: revolute(crank, rod),
            B: revolute(rod, piston),
            guide: prismatic(ground, piston) at B along (1.0, 0.0),
        },
        input: guide,
        loads { brake: torque on crank },
    }
}

#[test]
fn crank_bearing_friction_adds_mu_r_r() {
    let m = Crank::new();
    let (mu, r) = (0.15, 0.02);
    let fr = [JointFriction { mu, pin_radius: r }];
    let loads = CrankLoads { work: -3.0 };
    for &(q, qd, qdd) in &[(0.3, 12.0, 4.0), (2.0, -7.0, 30.0), (4.0, 25.0, -10.0)] {
        let mo = m.kinematics(q, qd, qdd).unwrap();
        // Textbook: cg at radius ρ, angle θ0 + q; R = m (a_G − g); T = I_O q̈ − load ± μ r |R|.
        let (gx, gy) = (0.04f64, 0.01f64);
        let rho = (gx * gx + gy * gy).sqrt();
        // The cg turns with the crank: its angle is its drawing angle plus q − θ_ref.
        let phi = gy.atan2(gx) + (q - 0.05f64.atan2(0.12));
        let a_g = Vector2::new(
            -rho * qdd * phi.sin() - rho * qd * qd * phi.cos(),
            rho * qdd * phi.cos() - rho * qd * qd * phi.sin(),
        );
        let pin = (a_g - Vector2::new(0.0, -9.81)) * 2.0;
        let i_o = 0.01 + 2.0 * rho * rho;
        // Gravity's moment about O: r_G × m g.
        let r_g = Vector2::new(rho * phi.cos(), rho * phi.sin());
        let grav = r_g.x * (2.0 * -9.81);
        let t0 = i_o * qdd + 3.0 - grav;
        let want = t0 + qd.signum() * mu * r * pin.norm();
        let f = m.kinetostatics_with_friction(&mo, &loads, &fr).unwrap();
        assert!(
            within((f.joints.O.force - pin).norm(), 2e-14 * pin.norm()), // measured worst 2.1e-16 (be05608); 100×
            "q={q}: R {:?} vs {pin:?}",
            f.joints.O.force
        );
        assert!(
            within((f.driver - want).abs(), 1e-15 * want.abs().max(1.0)), // measured worst 0 (be05608); exact; a few ulps
            "q={q}: {} vs {want}",
            f.driver
        );
    }
}

#[test]
fn block_on_incline_needs_mg_sin_plus_mu_mg_cos() {
    let m = Incline::new();
    let (mu, th) = (0.3f64, std::f64::consts::FRAC_PI_6);
    let fr = [JointFriction {
        mu,
        pin_radius: 0.0,
    }];
    for &(v, a) in &[(0.5, 2.0), (-0.5, 2.0), (1.0, -1.0)] {
        let mo = m.kinematics(0.1, v, a).unwrap();
        let f = m
            .kinetostatics_with_friction(&mo, &InclineLoads::default(), &fr)
            .unwrap();
        let want = 12.0 * a + 12.0 * 9.81 * th.sin() + v.signum() * mu * 12.0 * 9.81 * th.cos();
        assert!(
            within((f.driver - want).abs(), 2e-14 * want.abs()), // measured worst 3.7e-16 (be05608); 100×
            "v={v}: {} vs {want}",
            f.driver
        );
        // measured worst 1.4e-14 (be05608); 100×
        assert!(within(
            (f.joints.stroke.force.norm() - 12.0 * 9.81 * th.cos()).abs(),
            1e-12
        ));
    }
}

/// The friction route against the power balance: the motor's power with friction equals
/// the frictionless motor's power plus the power the friction dissipates, computed here
/// from the returned reactions and the relative motions.
/// The actuator's stroke (from the drawing, 60° of crank) that puts the crank at angle θ.
fn stroke_at(theta: f64) -> f64 {
    let (r, l) = (0.05f64, 0.2f64);
    let x = |t: f64| r * t.cos() + (l * l - (r * t.sin()).powi(2)).sqrt();
    x(theta) - x(std::f64::consts::FRAC_PI_3)
}

#[test]
fn friction_dissipation_closes_the_power_balance() {
    let m = PistonDriven::new();
    let mut fr = [JointFriction {
        mu: 0.1,
        pin_radius: 0.01,
    }; 4];
    fr[3].pin_radius = 0.0;
    let loads = PistonDrivenLoads { brake: -4.0 };
    for &theta in &[0.4, 0.7, 1.3, 2.0] {
        let q = stroke_at(theta);
        let (qd, qdd) = (-0.8, 1.5);
        let mo = m.kinematics(q, qd, qdd).unwrap();
        let f0 = m.kinetostatics(&mo, &loads).unwrap();
        let f = m.kinetostatics_with_friction(&mo, &loads, &fr).unwrap();
        let l = &mo.links;
        let rel = [
            l.crank.omega,
            l.rod.omega - l.crank.omega,
            l.piston.omega - l.rod.omega,
        ];
        let pins = [f.joints.O2.force, f.joints.A.force, f.joints.B.force];
        let mut dissipated = 0.0;
        for k in 0..3 {
            dissipated += 0.1 * 0.01 * pins[k].norm() * rel[k].abs();
        }
        dissipated += 0.1 * f.joints.guide.force.norm() * mo.points.B.vel.x.abs();
        let balance = f.driver * qd - (f0.driver * qd + dissipated);
        assert!(
            within(balance.abs(), 5e-12 * dissipated.max(1e-3)), // measured worst 5.9e-14 (be05608); 100×
            "q={q}: {balance:e} (dissipated {dissipated})"
        );
    }
}

/// Near the dead centre, a piston cannot turn a crank whose bearing has friction: the
/// friction moment μ r |R| grows with |R| faster than the rod's lever arm gives torque.
#[test]
fn piston_driven_crank_self_locks_at_the_dead_centre() {
    let m = PistonDriven::new();
    let fr = [
        JointFriction {
            mu: 0.3,
            pin_radius: 0.03,
        },
        JointFriction::default(),
        JointFriction::default(),
        JointFriction::default(),
    ];
    let loads = PistonDrivenLoads { brake: -4.0 };
    // Lever arm of the rod about O2 ≈ r sin θ against μ r_pin = 9 mm: locked below θ ≈ 0.18.
    let mo = m.kinematics(stroke_at(0.05), -0.1, 0.0).unwrap();
    // measured worst 7.3e-15 (be05608); 100×
    assert!(within((mo.links.crank.angle - 0.05).abs(), 5e-13));
    let locked = m.kinetostatics_with_friction(&mo, &loads, &fr);
    assert!(
        matches!(locked, Err(MechError::SelfLocking(_))),
        "{locked:?}"
    );
    // Well away from it, the same friction is overcome.
    let mo = m.kinematics(stroke_at(1.0), -0.8, 0.0).unwrap();
    assert!(m.kinetostatics_with_friction(&mo, &loads, &fr).is_ok());
}

/// A friction coefficient or pin radius that is NaN, infinite or negative is refused by
/// the run-time mechanism with the joint's name (issue 28: `mech-fuzz`; it was reported
/// as an overflow of the reactions, or, where no joint slid, not at all).
#[test]
fn a_non_finite_or_negative_friction_is_named() {
    let m = mech::Mechanism::from_dsl(
        "pub struct Crank {
            gravity: (0.0, -9.81),
            ground { O: (0.0, 0.0) },
            link crank { points { O, A: (0.12, 0.05) }, mass: 2.0, inertia: 0.01, cg: (0.04, 0.01) },
            joints { O: revolute(ground, crank) },
            input: O,
        }",
    )
    .unwrap();
    for (mu, pin_radius) in [
        (f64::NAN, 0.01),
        (f64::INFINITY, 0.01),
        (-0.1, 0.01),
        (0.1, f64::NAN),
        (0.1, -1.0),
    ] {
        // At rest too, where a NaN coefficient met no sliding and was silently ignored.
        for qd in [0.0, 2.0] {
            let mo = m.kinematics(&[0.3], &[qd], &[0.0]).unwrap();
            match m.kinetostatics_with_friction(
                &mo,
                &m.loads(),
                &[JointFriction { mu, pin_radius }],
            ) {
                Err(MechError::InvalidInput(e)) => {
                    assert!(
                        e.contains("joint `O`") && e.contains("finite and ≥ 0"),
                        "{e}"
                    )
                }
                other => panic!("μ = {mu}, r = {pin_radius}: expected an error, got {other:?}"),
            }
        }
    }
}
