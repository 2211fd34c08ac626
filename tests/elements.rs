//! Force elements (springs, dampers, torsion springs, rotary dampers) against independent
//! references:
//! - `tests/data/spring_four_bar.json`, from `tools/elements_reference.py`: the
//!   spring-loaded four-bar below by the energy method (mpmath, 50 digits: positions in
//!   closed form, velocity coefficients by numerical differentiation, springs through their
//!   potential, dampers through Rayleigh's function), its equilibrium and natural frequency;
//! - exact invariants: the energy of the undamped machine over 10⁴ oscillations, and the
//!   energy the damped one loses equal to the work its dampers dissipate (integrated apart,
//!   from the points' velocities, not from `mech_core::elements`);
//! - the three routes to the driver torque and the run-time mechanism read from this file.

use crate::measure::within;
use mech::dynamics::{equation_of_motion, total_energy};
use mech::ode::{solve, Dop853};
use mech::prelude::*;
use serde_json::Value;

use crate::data;
use data::{close, num};

mechanism! {
    /// A crank-rocker four-bar held by springs and slowed by dampers: a spring from the
    /// ground to the coupler, a preloaded spring across the crank and rocker, a torsion
    /// spring on the crank's bearing, a damper on the rocker and a rotary damper on the
    /// crank's bearing.
    pub struct SpringFourBar {
        gravity: (0.0, -9.81),
        ground { O2: (0.0, 0.0), O4: (300 mm, 0.0), C: (50 mm, 250 mm), D: (400 mm, 200 mm) },
        link crank {
            points { O2, A: (0.0, 100 mm) },
            mass: 0.8, inertia: 1.0e-3, cg: (0.0, 0.05),
        },
        link coupler {
            points { A, B: (280 mm, 220 mm), P: (100 mm, 200 mm) },
            mass: 1.5, inertia: 9.0e-3, cg: (0.14, 0.17),
        },
        link rocker {
            points { B, O4 },
            mass: 1.1, inertia: 4.0e-3, cg: (0.29, 0.11),
        },
        joints {
            O2: revolute(ground, crank),
            A: revolute(crank, coupler),
            B: revolute(coupler, rocker),
            O4: revolute(rocker, ground),
        },
        input: O2,
        loads {
            resist: torque on rocker,
        },
        elements {
            k1: spring(ground at C, coupler at P) stiffness 2 kN_per_m free_length 80 mm,
            k2: spring(crank at A, rocker at O4) stiffness 500 N_per_m preload 30 N,
            kt: torsion_spring(ground, crank) stiffness 1.5 N_m_per_rad free_angle 60 deg,
            c1: damper(ground at D, rocker at B) damping 40 N_s_per_m,
            ct: rotary_damper(ground, crank) damping 0.05 N_m_s_per_rad,
        },
    }
}

fn reference() -> Value {
    data::load("spring_four_bar.json")
}

/// The same machine without its dampers (c = 0 through `from_params`).
fn undamped() -> SpringFourBar {
    let mut p = SpringFourBarParams::default();
    p.elements.c1.damping = 0.0;
    p.elements.ct.damping = 0.0;
    SpringFourBar::from_params(p).unwrap()
}

/// The declared numbers land in `Params` (units converted, the preload turned into the free
/// length L₀ = L_drawing − F₀/k), and the reference's L₀ is the same.
#[test]
fn params_hold_the_declared_elements() {
    let p = SpringFourBarParams::default();
    assert_eq!(p.elements.k1.stiffness, 2000.0);
    // measured worst 0 (be05608); exact; a few ulps
    assert!(within((p.elements.k1.free_length - 0.08).abs(), 1e-17));
    let l_drawn = (0.3f64).hypot(0.1);
    // measured worst 0 (be05608); exact; a few ulps
    assert!(within(
        (p.elements.k2.free_length - (l_drawn - 30.0 / 500.0)).abs(),
        1e-16
    ));
    close(
        "k2 free length",
        p.elements.k2.free_length,
        num(&reference()["free_length_k2"]),
        1e-16, // measured worst 0 (be05608); exact; a few ulps
    );
    // measured worst 0 (be05608); exact; a few ulps
    assert!(within(
        (p.elements.kt.free_angle - 60f64.to_radians()).abs(),
        1e-16
    ));
    assert_eq!(p.elements.c1.damping, 40.0);
    assert_eq!(p.elements.ct.damping, 0.05);
}

/// At six states (q, q̇, q̈, resisting torque): I*, dI*/dq, M*(q), the potential energy,
/// and the driver torque by d'Alembert (`kinetostatics`), by virtual power
/// (`driver_action`) and by Zhukovski (the q̈ `acceleration` gives for the reference's
/// driver) all match the energy method, to 1e-13 of the terms' scale (I*, dI*/dq, V:
/// 5e-14).
#[test]
fn three_routes_match_the_energy_method() {
    let m = SpringFourBar::new();
    let r = reference();
    for c in r["configs"].as_array().unwrap() {
        let (q, qd, qdd) = (num(&c["q"]), num(&c["qd"]), num(&c["qdd"]));
        let loads = SpringFourBarLoads {
            resist: num(&c["resist"]),
        };
        let at = format!("q = {q}, q̇ = {qd}, q̈ = {qdd}");
        let red = m.reduced(q).unwrap();
        let i_star = num(&c["I_star"]);
        // measured worst 6.4e-16 (be05608); 100×
        close(&format!("I* at {at}"), red.inertia, i_star, 5e-14 * i_star);
        let di = num(&c["dI_star_dq"]);
        close(
            &format!("dI*/dq at {at}"),
            red.inertia_derivative,
            di,
            5e-14 * i_star, // measured worst 7.7e-16 (be05608); 100×
        );
        let m_star = num(&c["M_star"]);
        // The scale of the torques: springs' and gravity's terms are O(10) N·m here.
        let scale = 10.0f64.max(m_star.abs());
        close(
            &format!("M* at {at}"),
            m.reduced_moment(q, &loads).unwrap(),
            m_star,
            1e-13 * scale, // measured worst 1.1e-15 (be05608); 100×
        );
        let motion = m.kinematics(q, qd, qdd).unwrap();
        let v = m.potential_energy(&motion);
        close(
            &format!("V at {at}"),
            v,
            num(&c["potential"]),
            5e-14 * scale, // measured worst 9.9e-16 (be05608); 100×
        );
        let driver = num(&c["driver"]);
        let d_alembert = m.kinetostatics(&motion, &loads).unwrap().driver;
        let virtual_power = m.driver_action(&motion, &loads).unwrap();
        close(
            &format!("d'Alembert at {at}"),
            d_alembert,
            driver,
            1e-13 * scale, // measured worst 1.4e-15 (be05608); 100×
        );
        close(
            &format!("virtual power at {at}"),
            virtual_power,
            driver,
            1e-13 * scale, // measured worst 1.4e-15 (be05608); 100×
        );
        let qdd_z = m.acceleration(q, qd, driver, &loads).unwrap();
        close(
            &format!("Zhukovski's q̈ at {at}"),
            qdd_z,
            qdd,
            1e-13 * scale / i_star, // measured worst 1.2e-15 (be05608); 100×
        );
    }
}

/// The run-time mechanism read from this file's own `mechanism!` gives the same numbers as
/// the generated struct (driver by both routes, every reaction, M*, q̈, energy), and
/// `set_param` reaches the elements.
#[test]
fn runtime_mechanism_is_a_peer() {
    let g = SpringFourBar::new();
    let mut rt = Mechanism::from_rust_source(include_str!("elements.rs"), "SpringFourBar").unwrap();
    let mut rl = rt.loads();
    assert!(rl.set_by_name("resist", &[2.5]));
    let gl = SpringFourBarLoads { resist: 2.5 };
    for &(q, qd, qdd) in &[(0.4, 3.0, -10.0), (2.2, -6.0, 40.0), (4.0, 1.0, 0.0)] {
        let (gm, rm) = (
            g.kinematics(q, qd, qdd).unwrap(),
            rt.kinematics(&[q], &[qd], &[qdd]).unwrap(),
        );
        let (gf, rf) = (
            g.kinetostatics(&gm, &gl).unwrap(),
            rt.kinetostatics(&rm, &rl).unwrap(),
        );
        // measured worst 1.8e-15 N·m (driver; driver_action, M*, V: 0) (be05608); 100×
        let tol = 1e-13;
        close("driver", rf.driver[0], gf.driver, tol);
        for name in SpringFourBar::JOINT_NAMES {
            let (a, b) = (gf.reaction(name).unwrap().0, rf.reaction(name).unwrap().0);
            // measured worst 2.8e-16 (of 100 N) (be05608); 100×
            close(name, b.x, a.x, 2e-14 * 100.0);
            // measured worst 2.8e-16 (of 100 N) (be05608); 100×
            close(name, b.y, a.y, 2e-14 * 100.0);
        }
        close(
            "driver_action",
            rt.driver_action(&rm, &rl).unwrap()[0],
            g.driver_action(&gm, &gl).unwrap(),
            tol,
        );
        close(
            "M*",
            rt.reduced_moment(q, &rl).unwrap(),
            g.reduced_moment(q, &gl).unwrap(),
            tol,
        );
        close(
            "q̈",
            rt.acceleration(q, qd, 1.0, &rl).unwrap(),
            g.acceleration(q, qd, 1.0, &gl).unwrap(),
            2e-11, // measured worst 4.5e-13 (be05608); 100×
        );
        close("V", rt.potential_energy(&rm), g.potential_energy(&gm), tol);
    }
    // The torsion spring's stiffness doubled at run time moves M* by its own term.
    let before = rt.reduced_moment(0.4, &rl).unwrap();
    rt.set_param("elements.kt.stiffness", &[3.0]).unwrap();
    let after = rt.reduced_moment(0.4, &rl).unwrap();
    close(
        "doubled torsion spring",
        after - before,
        -1.5 * (0.4 - 60f64.to_radians()),
        2e-14, // measured worst 4.4e-16 (be05608); 100×
    );
    let e = rt
        .set_param("elements.kt.damping", &[1.0])
        .unwrap_err()
        .to_string();
    assert!(e.contains("a spring has `stiffness`"), "{e}");
    let e = rt
        .set_param("elements.c1.stiffness", &[-1.0])
        .unwrap_err()
        .to_string();
    assert!(e.contains("a damper has `damping`"), "{e}");
}

/// A negative stiffness or damping through `from_params` is refused with the numbers.
#[test]
fn from_params_refuses_negative_coefficients() {
    let mut p = SpringFourBarParams::default();
    p.elements.k1.stiffness = -5.0;
    let e = SpringFourBar::from_params(p).unwrap_err().to_string();
    assert!(
        e.contains("spring `k1` has stiffness -5 N/m") && e.contains("≥ 0"),
        "{e}"
    );
    let mut p = SpringFourBarParams::default();
    p.elements.ct.damping = f64::NAN;
    let e = SpringFourBar::from_params(p).unwrap_err().to_string();
    assert!(e.contains("rotary_damper `ct`"), "{e}");
}

/// The equilibrium (no driver, no load, at rest) where M*(q) = 0, found by Newton on the
/// generated M*, is the energy method's q* to 1e-12; the natural frequency of small
/// oscillations about it, ω_n = √(K*/I*) with K* = −dM*/dq (an 8th-order central
/// difference of the generated M*: its truncation ~1e-16, its roundoff ~1e-13), is the
/// reference's to 1e-11.
#[test]
fn equilibrium_and_natural_frequency() {
    let m = undamped();
    let r = &reference()["equilibrium"];
    let none = SpringFourBarLoads::default();
    let moment = |q: f64| m.reduced_moment(q, &none).unwrap();
    // K* by the 8th-order central difference (h = 1e-2: truncation ~1e-17, roundoff ~1e-13).
    let stiffness = |q: f64| {
        let h = 1e-2;
        let w = [4.0 / 5.0, -1.0 / 5.0, 4.0 / 105.0, -1.0 / 280.0];
        -(1..=4)
            .map(|k| w[k - 1] * (moment(q + k as f64 * h) - moment(q - k as f64 * h)))
            .sum::<f64>()
            / h
    };
    let mut q = num(&r["q"]) + 0.05;
    for _ in 0..20 {
        q += moment(q) / stiffness(q);
    }
    // measured worst 0 (be05608); exact; a few ulps
    close("q*", q, num(&r["q"]), 1e-15);
    let k = stiffness(q);
    // measured worst 8.1e-14 (be05608); 100×
    close("K*", k, num(&r["stiffness_star"]), 5e-12 * k);
    let wn = (k / m.reduced(q).unwrap().inertia).sqrt();
    // measured worst 4.0e-14 (be05608); 100×
    close("ω_n", wn, num(&r["natural_frequency"]), 2e-12 * wn);
}

/// Released at rest 0.3 rad from its equilibrium, the undamped machine oscillates; DOP853
/// (rtol = atol = 1e-11) through 10⁴ periods (about 3.6e5 steps) keeps T + V (gravity and
/// springs, 5.3 J) within 1e-7 J of the start at every step; measured 9.5e-9 J (an
/// explicit method's energy error grows linearly with the steps).
#[test]
fn undamped_energy_is_conserved_over_ten_thousand_oscillations() {
    let m = undamped();
    let r = &reference()["equilibrium"];
    let q0 = num(&r["q"]) + 0.3;
    let period = std::f64::consts::TAU / num(&r["natural_frequency"]);
    let e0 = total_energy(&m, &[q0], &[0.0]).unwrap();
    let scale = 10.0; // J: the springs' and gravity's energies are of this order here
    let mut worst = 0.0f64;
    let mut obs = |d: &mech::ode::Dop853Dense<2>| {
        use mech::ode::Dense;
        let y = d.y_end();
        worst = worst.max((total_energy(&m, &[y[0]], &[y[1]]).unwrap() - e0).abs());
    };
    // 10⁴ oscillations take about 370 000 steps: this long run states its own step budget
    // (Tolerance::max_steps) rather than lean on the default.
    let mut method = Dop853::new(1e-11, 1e-11);
    method.tol.max_steps = 1_000_000;
    let out = solve(
        &mut method,
        equation_of_motion(&m, |_, _, _| (0.0, SpringFourBarLoads::default())),
        0.0,
        [q0, 0.0],
        1e4 * period,
        None,
        Some(&mut obs),
    )
    .unwrap();
    eprintln!(
        "10⁴ oscillations ({:.1} s): {} steps, max |ΔE| = {worst:.2e} J of E = {e0:.6} J",
        1e4 * period,
        out.stats.steps
    );
    // measured worst 9.5e-10 (be05608); an explicit integrator over 3.6e5 steps (above)
    assert!(within(worst, 1e-8 * scale), "energy drift {worst:e} J");
}

/// With its dampers the machine loses energy: integrated with the dissipated work
/// W = ∫ (c₁ L̇₁² + c_t ω₂²) dt as a third state (L̇₁ from the velocity of B seen from D,
/// ω₂ the crank's, both from `kinematics`), E(t) + W(t) stays E(0) to 2e-12 of E over 5 s.
#[test]
fn damped_energy_loss_is_the_dissipated_work() {
    let m = SpringFourBar::new();
    let p = m.params().clone();
    let (c1, ct, d) = (p.elements.c1.damping, p.elements.ct.damping, p.points.D);
    let none = SpringFourBarLoads::default();
    let rhs = |_: f64, y: &[f64; 3]| -> Result<[f64; 3], MechError> {
        let qdd = m.acceleration(y[0], y[1], 0.0, &none)?;
        let mo = m.kinematics(y[0], y[1], qdd)?;
        let b = &mo.points.B;
        let e = (b.pos - d).normalize();
        let ld = e.dot(&b.vel);
        let w2 = mo.links.crank.omega;
        Ok([y[1], qdd, c1 * ld * ld + ct * w2 * w2])
    };
    let q0 = 0.2;
    let y0 = [q0, 15.0, 0.0];
    let e0 = total_energy(&m, &[q0], &[15.0]).unwrap();
    let mut worst = 0.0f64;
    let mut obs = |dn: &mech::ode::Dop853Dense<3>| {
        use mech::ode::Dense;
        let y = dn.y_end();
        let e = total_energy(&m, &[y[0]], &[y[1]]).unwrap();
        worst = worst.max((e + y[2] - e0).abs());
    };
    let out = solve(
        &mut Dop853::new(1e-12, 1e-12),
        rhs,
        0.0,
        y0,
        5.0,
        None,
        Some(&mut obs),
    )
    .unwrap();
    let lost = out.y[2];
    assert!(
        lost > 0.5
            * (e0 - total_energy(&m, &[num(&reference()["equilibrium"]["q"])], &[0.0]).unwrap())
    );
    assert!(
        within(worst, 2e-12 * e0.abs()), // measured worst 2.5e-14 (be05608); 100×
        "E + W drifted by {worst:e} J (E0 = {e0}, dissipated {lost})"
    );
}

use crate::counting;

/// Every generated solver of a machine with force elements allocates nothing.
#[test]
fn generated_solvers_with_elements_are_allocation_free() {
    let m = SpringFourBar::new();
    let loads = SpringFourBarLoads { resist: 1.0 };
    let before = counting::count();
    let mut sink = 0.0;
    for k in 0..100 {
        let q = 0.06 * k as f64;
        let mo = m.kinematics(q, 3.0, -2.0).unwrap();
        sink += m.kinetostatics(&mo, &loads).unwrap().driver;
        sink += m.driver_action(&mo, &loads).unwrap();
        sink += m.reduced_moment(q, &loads).unwrap();
        sink += m.acceleration(q, 3.0, 1.0, &loads).unwrap();
        sink += m.potential_energy(&mo);
    }
    assert_eq!(counting::count() - before, 0, "allocations");
    assert!(sink.is_finite());
}

/// The flywheel cycle sees the springs: over a full turn of the crank (torsion spring off,
/// so that every spring's force is smooth), with no driver and no load, Wittenbauer's
/// work S(q) = ∫ M* dq (`mech::flywheel::Cycle`, by quadrature) is minus the change of the
/// potential energy (gravity and springs, `potential_energy`) to 1e-13 of its range: the
/// springs' M* is exactly −dV/dq.
#[test]
fn flywheel_cycle_sees_the_springs() {
    let mut p = SpringFourBarParams::default();
    p.elements.kt.stiffness = 0.0;
    p.elements.c1.damping = 0.0;
    p.elements.ct.damping = 0.0;
    let m = SpringFourBar::from_params(p).unwrap();
    let cycle = mech::flywheel::Cycle::builder(&m, std::f64::consts::TAU, |_| {
        Ok(SpringFourBarLoads::default())
    })
    .build()
    .unwrap();
    let v = |q: f64| m.potential_energy(&m.kinematics(q, 0.0, 0.0).unwrap());
    let (v0, mut range) = (v(0.0), 0.0f64);
    let mut worst = 0.0f64;
    for k in 0..=36 {
        let q = std::f64::consts::TAU * k as f64 / 36.0;
        let dv = v(q) - v0;
        range = range.max(dv.abs());
        worst = worst.max((cycle.work(q).unwrap() + dv).abs());
    }
    assert!(range > 1.0, "the springs' energy varies: {range} J");
    assert!(
        within(worst, 1e-13 * range), // measured worst 1.4e-15 (be05608); 100×
        "S + ΔV off by {worst:e} J (range {range} J)"
    );
}

mechanism! {
    /// A spring whose two ends coincide in the drawing (a zero-length spring on a pin):
    /// its direction is undefined there.
    pub struct DegenerateSpring {
        gravity: (0.0, -9.81),
        ground { O: (0.0, 0.0) },
        link arm { points { O, A: (0.1, 0.0) }, mass: 1.0, inertia: 1.0e-3, cg: (0.05, 0.0) },
        joints { O: revolute(ground, arm) },
        input: O,
        elements { k: spring(ground at O, arm at O) stiffness 100 N_per_m free_length 10 mm },
    }
}

/// A spring of zero length has no direction: every solver that needs its force returns a
/// `MechError` (never a NaN inside `Ok`); the potential energy, which does not need the
/// direction, stays finite.
#[test]
fn a_spring_of_zero_length_is_an_error_not_a_nan() {
    let m = DegenerateSpring::new();
    let loads = DegenerateSpringLoads::default();
    let mo = m.kinematics(0.3, 2.0, 1.0).unwrap();
    assert!(m.kinetostatics(&mo, &loads).is_err());
    assert!(m.driver_action(&mo, &loads).is_err());
    assert!(m.reduced_moment(0.3, &loads).is_err());
    assert!(m.acceleration(0.3, 2.0, 0.0, &loads).is_err());
    assert!(m.potential_energy(&mo).is_finite());
}
