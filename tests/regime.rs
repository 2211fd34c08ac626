//! Motors and the regimes they drive (`mech::motor`, `mech::regime`): the start from rest
//! against its closed form, the engine's periodic steady regime against a long direct
//! integration and against the flywheel design, the stop, and the errors.

use crate::engine::{self, Engine, OMEGA_MEAN, PERIOD, Q_TDC};
use mech::flywheel::Cycle;
use mech::motor::Motor;
use mech::ode::{self, Dop853};
use mech::prelude::*;
use mech::regime::Drive;

/// A disc on a fixed pivot (cg on the axis, no gravity): I* is its I_G, M* = 0.
fn disc(inertia: f64) -> mech::Mechanism {
    mech::Mechanism::from_dsl(&format!(
        "pub struct Disc {{
            ground {{ O: (0.0, 0.0) }},
            link disc {{
                points {{ O, A: (0.1, 0.0) }},
                mass: 2.0, inertia: {inertia}, cg: (0.0, 0.0),
            }},
            joints {{ O: revolute(ground, disc) }},
            input: O,
        }}"
    ))
    .unwrap()
}

/// A DC motor through a reduction n starts a constant inertia I (disc + flywheel) on the
/// first-order law ω = ω∞ (1 − e^{−t/τ}), ω∞ = ω₀/n, τ = I ω₀ / (n² T_s); and
/// q = ω∞ (t − τ (1 − e^{−t/τ})). Both to 1e-8 of ω∞ (of ω∞ τ for q).
#[test]
fn a_dc_motor_starts_a_constant_inertia_on_its_exponential() {
    let m = disc(0.01);
    for (ratio, flywheel) in [(1.0, 0.0), (10.0, 0.02)] {
        let (ts, w0) = (2.0, 300.0);
        let motor = Motor::dc(ts, w0).unwrap().through(ratio).unwrap();
        let drive = Drive::new(&m, motor, |_| Ok(m.loads()))
            .flywheel(flywheel)
            .unwrap();
        let inertia = 0.01 + flywheel;
        let (w_inf, tau) = (w0 / ratio, inertia * w0 / (ratio * ratio * ts));
        let run = drive.start_up(0.3, 8.0 * tau, 200).unwrap();
        for k in 0..run.t.len() {
            let t = run.t[k];
            let w = w_inf * (1.0 - (-t / tau).exp());
            let q = 0.3 + w_inf * (t - tau * (1.0 - (-t / tau).exp()));
            assert!(
                (run.qd[k] - w).abs() < 1e-8 * w_inf,
                "n {ratio}, t {t}: {} vs {w}",
                run.qd[k]
            );
            assert!((run.q[k] - q).abs() < 1e-8 * w_inf * tau, "t {t}");
            let action = ratio * ts * (1.0 - ratio * run.qd[k] / w0);
            assert!((run.torque[k] - action).abs() < 1e-12 * ratio * ts);
        }
    }
}

/// The engine (gas force from its indicator cycle) driving an induction generator (Kloss;
/// above its synchronous speed its torque is negative) through a flywheel: the periodic
/// steady regime found by shooting equals the last cycle of a direct integration in time
/// started away from it and run until the transient has died (40 cycles), to 1e-8.
#[test]
fn the_engine_steady_regime_is_the_end_of_a_long_direct_integration() {
    let eng = Engine::new();
    let generator = generator();
    let drive = Drive::new(&eng, generator, |q| engine::gas_loads(&eng, q))
        .flywheel(0.15)
        .unwrap();
    let steady = drive.steady(Q_TDC, PERIOD, 720).unwrap();
    assert!(
        steady.mean_speed > OMEGA_MEAN,
        "a generator runs above synchronous speed"
    );
    // Periodic: the table ends where it starts.
    let last = steady.qd.len() - 1;
    assert!((steady.qd[last] - steady.qd[0]).abs() < 1e-10 * steady.qd[0]);
    // The direct integration in time, from 5 % below the regime's speed at the TDC.
    let rhs = |_t: f64, y: &[f64; 2]| -> Result<[f64; 2], MechError> {
        Ok([y[1], drive.acceleration(y[0], y[1])?])
    };
    let cycles = 40.0;
    let mut g = |_t: f64, y: &[f64; 2]| y[0] - (Q_TDC + cycles * PERIOD);
    let mut event = ode::Event::new(&mut g);
    let mut method = Dop853::new(1e-13, 1e-13 * OMEGA_MEAN);
    let end = ode::solve(
        &mut method,
        rhs,
        0.0,
        [Q_TDC, 0.95 * steady.qd[0]],
        100.0,
        Some(&mut event),
        None,
    )
    .unwrap();
    assert!(end.event);
    let err = (end.y[1] - steady.qd[0]).abs() / steady.qd[0];
    assert!(
        err < 1e-8,
        "ω at the TDC: direct {} vs regime {} ({err:.2e})",
        end.y[1],
        steady.qd[0]
    );
    // The motor check: the mean power is the gas work per cycle over the period in time.
    let cycle = Cycle::builder(&eng, PERIOD, |q| engine::gas_loads(&eng, q))
        .start(Q_TDC)
        .breakpoints(&engine::breakpoints())
        .build()
        .unwrap();
    let power = cycle.net_work() / steady.period_time;
    assert!(
        (steady.check.mean_power + power).abs() < 1e-8 * power,
        "generator power {} vs gas power {power}",
        steady.check.mean_power
    );
    assert!(steady.check.rms_torque >= steady.check.mean_power.abs() / (steady.mean_speed * 1.0));
}

/// 7.5 kW, 3000 rpm synchronous, 2940 rpm rated, breakdown 2.5 T_r.
fn generator() -> Motor {
    let rpm = std::f64::consts::PI / 30.0;
    Motor::induction(7500.0, 3000.0 * rpm, 2940.0 * rpm, 2.5).unwrap()
}

/// The flywheel designed by Wittenbauer's method for δ = 2 % at the regime's mean speed
/// (constant resisting torque) keeps the regime under the induction generator within
/// that design: the generator's torque falls as the speed rises, which only damps the
/// fluctuation. Stated bound: 0.97 δ ≤ ε ≤ 1.005 δ (measured: ε = 0.990 δ; the 0.5 % above δ
/// allows for the extremes read off a table of 1440 points).
#[test]
fn the_regime_irregularity_is_within_the_flywheel_design() {
    let eng = Engine::new();
    let (cycle, _) = Cycle::builder(&eng, PERIOD, |q| engine::gas_loads(&eng, q))
        .start(Q_TDC)
        .breakpoints(&engine::breakpoints())
        .build()
        .unwrap()
        .balanced();
    let delta = 0.02;
    // The regime's speed first (any flywheel), then the design at that speed.
    let probe = Drive::new(&eng, generator(), |q| engine::gas_loads(&eng, q))
        .flywheel(0.2)
        .unwrap()
        .steady(Q_TDC, PERIOD, 720)
        .unwrap();
    let design = cycle.wittenbauer(probe.mean_speed, delta).unwrap();
    let steady = Drive::new(&eng, generator(), |q| engine::gas_loads(&eng, q))
        .flywheel(design.inertia)
        .unwrap()
        .steady(Q_TDC, PERIOD, 1440)
        .unwrap();
    let ratio = steady.epsilon / delta;
    assert!(
        (0.97..=1.005).contains(&ratio),
        "ε = {} against the design's δ = {delta} (flywheel {} kg·m²)",
        steady.epsilon,
        design.inertia
    );
}

/// Coasting with a brake: a constant inertia under a brake torque B stops after
/// t = I ω₀ / B having turned I ω₀² / (2B) (to 1e-10); without a brake or losses it never
/// stops, an error naming the fix.
#[test]
fn a_braked_stop_and_a_coast_that_never_ends() {
    let m = disc(0.05);
    let drive = Drive::new(&m, Motor::dc(1.0, 10.0).unwrap(), |_| Ok(m.loads()));
    let stop = drive.stop(0.0, 40.0, 0.5, 0.1, 100.0).unwrap();
    assert!(
        (stop.time - 0.05 * 40.0 / 0.5).abs() < 1e-10 * 4.0,
        "{}",
        stop.time
    );
    assert!(
        (stop.travel - 0.05 * 1600.0 / 1.0).abs() < 1e-10 * 80.0,
        "{}",
        stop.travel
    );
    assert!(stop.run.qd.last().unwrap().abs() < 1e-9);
    let e = drive
        .stop(0.0, 40.0, 0.0, 0.1, 5.0)
        .unwrap_err()
        .to_string();
    assert!(e.contains("still moving") && e.contains("brake"), "{e}");
}

/// The stop in even steps of its own length (`Drive::stop_steps`, what `mech regime --stop`
/// and Python's `Mechanism.stop` tabulate): under a brake B a constant inertia I decelerates
/// uniformly, q̇ = ω₀ − (B/I) t and q = ω₀ t − (B/(2I)) t², at every row (to 1e-10 of ω₀ and
/// of the travel); the motor is off, whichever it is.
#[test]
fn a_stop_in_even_steps_follows_the_uniform_deceleration() {
    let m = disc(0.05);
    let (w0, brake, inertia) = (40.0, 0.5, 0.05);
    let drive = Drive::new(&m, Motor::constant(0.0).unwrap(), |_| Ok(m.loads()));
    let stop = drive.stop_steps(0.3, w0, brake, 8, 100.0).unwrap();
    let ts = inertia * w0 / brake;
    assert!((stop.time - ts).abs() < 1e-10 * ts, "{}", stop.time);
    assert_eq!(stop.run.t.len(), 9);
    for k in 0..=8 {
        let t = ts * k as f64 / 8.0;
        assert!(
            (stop.run.t[k] - t).abs() < 1e-10 * ts,
            "t[{k}] = {}",
            stop.run.t[k]
        );
        let (qd, q) = (
            w0 - brake / inertia * t,
            w0 * t - brake / (2.0 * inertia) * t * t,
        );
        assert!(
            (stop.run.qd[k] - qd).abs() < 1e-10 * w0,
            "q̇ at {t}: {} vs {qd}",
            stop.run.qd[k]
        );
        assert!(
            (stop.run.q[k] - 0.3 - q).abs() < 1e-10 * 80.0,
            "q at {t}: {} vs {q}",
            stop.run.q[k]
        );
        assert_eq!(stop.run.torque[k], -brake);
    }
    // A DC motor in the drive changes nothing: it is off.
    let dc = Drive::new(&m, Motor::dc(1.0, 10.0).unwrap(), |_| Ok(m.loads()));
    assert_eq!(dc.stop_steps(0.3, w0, brake, 8, 100.0).unwrap(), stop);
    for (steps, t_max, says) in [(0, 100.0, "1 to"), (8, -1.0, "t_max > 0")] {
        let e = drive
            .stop_steps(0.3, w0, brake, steps, t_max)
            .unwrap_err()
            .to_string();
        assert!(e.contains(says), "{e}");
    }
    let e = drive
        .stop(0.0, w0, brake, 1e-9, 100.0)
        .unwrap_err()
        .to_string();
    assert!(e.contains("give a larger dt"), "{e}");
}

/// A motor too weak to start a machine is an error that names the numbers and the fix; a
/// constant torque has no steady regime.
#[test]
fn a_motor_that_cannot_start_the_machine_is_an_error() {
    let eng = Engine::new();
    // A gas force on the piston; the motor starts where it resists most.
    let weak = Motor::dc(1e-3, 100.0).unwrap();
    let loads = |_q: f64| {
        Ok(engine::EngineLoads {
            gas: Vector2::new(-500.0, 0.0),
        })
    };
    let drive = Drive::new(&eng, weak, loads);
    let moment = |q: f64| eng.reduced_moment(q, &loads(q).unwrap()).unwrap();
    let q0 = (0..72)
        .map(|k| k as f64 * std::f64::consts::TAU / 72.0)
        .min_by(|&a, &b| moment(a).total_cmp(&moment(b)))
        .unwrap();
    assert!(moment(q0) < -1.0, "{}", moment(q0));
    let e = drive.start_up(q0, 1.0, 10).unwrap_err().to_string();
    assert!(
        e.contains("cannot start") && e.contains("reduction ratio"),
        "{e}"
    );
    let constant = Drive::new(&eng, Motor::constant(5.0).unwrap(), loads);
    let e = constant.steady(0.0, PERIOD, 10).unwrap_err().to_string();
    assert!(e.contains("falls with speed"), "{e}");
}
