//! The regimes of a one-DOF machine driven by a [`Motor`] (`docs/theory.md` §6): the start
//! from rest, the periodic steady regime ω(q) = ω(q + λ) and the stop.
//!
//! The equation of motion is Zhukovski's, with the motor's action on the input and an
//! optional flywheel J on the input shaft (a flywheel, or a rotor of inertia J_r through a
//! ratio n: J = n² J_r):
//!
//! (I*(q) + J) q̈ + ½ dI*/dq q̇² = n T(n q̇) + M*(q),
//!
//! M* the reduced moment of the loads (functions of q) and gravity. The start and the stop
//! are integrated in time (DOP853). The steady regime is found directly: with q the
//! independent variable and ω = q̇ > 0, dω/dq = q̈/ω and dt/dq = 1/ω; the speed ω₀ at q₀
//! with ω(q₀ + λ) = ω₀ is the root of F(ω₀) = ω(q₀ + λ; ω₀) − ω₀ (shooting, secant steps),
//! started from the speed where the motor's action balances the mean of M* over the cycle
//! (the term ½ dI*/dq ω² has no mean over a period).

use super::motor::Motor;
use super::ode::{self, Dop853};
use crate::solvers::traits::OneDof;
use crate::solvers::zhukovski::{acceleration, Reduced};
use crate::MechError;

/// The loads of the machine as a function of the input position q.
type LoadsFn<'a, M> =
    Box<dyn Fn(f64) -> Result<<M as crate::solvers::traits::Machine>::Loads, MechError> + 'a>;

/// Relative tolerance of the integrations.
const RTOL: f64 = 1e-12;

/// The most rows of a stop's table.
const MAX_SAMPLES: usize = 10_000_000;

/// A one-DOF machine, its motor, its loads (functions of q) and a flywheel on the input.
pub struct Drive<'a, M: OneDof> {
    machine: &'a M,
    motor: Motor,
    loads: LoadsFn<'a, M>,
    flywheel: f64,
}

/// A run in time: samples at even times.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Run {
    /// Time, s.
    pub t: Vec<f64>,
    /// Input position, rad (m).
    pub q: Vec<f64>,
    /// Input speed, rad/s (m/s).
    pub qd: Vec<f64>,
    /// The action on the input, N·m (N): the motor's n T(n q̇), or the brake's.
    pub torque: Vec<f64>,
}

/// The periodic steady regime over one period from q₀.
#[derive(Clone, Debug, PartialEq)]
pub struct Steady {
    /// Positions of the table, rad: q₀ … q₀ + λ.
    pub q: Vec<f64>,
    /// Speed ω(q), rad/s.
    pub qd: Vec<f64>,
    /// Time from q₀, s.
    pub t: Vec<f64>,
    /// The motor's action on the input, N·m.
    pub torque: Vec<f64>,
    /// The period in time, s: ∫ dq / ω over the cycle.
    pub period_time: f64,
    /// The mean speed over time λ / period_time, rad/s.
    pub mean_speed: f64,
    /// The coefficient of irregularity ε = (ω_max − ω_min) / ω_a, ω_a = (ω_max + ω_min)/2
    /// (the flywheel design's definition), the extremes over the table.
    pub epsilon: f64,
    /// The motor check over the regime (on the motor's shaft).
    pub check: MotorCheck,
    /// Shooting iterations used.
    pub iterations: usize,
}

/// The motor's duty over the steady regime, on its own shaft.
#[derive(Clone, Debug, PartialEq)]
pub struct MotorCheck {
    /// The largest |T| over the table's points, N·m.
    pub peak_torque: f64,
    /// The root mean square of T over time, √(∫T² dt / t_period), N·m: the thermal load.
    pub rms_torque: f64,
    /// The mean power ∫ T ω dt / t_period, W.
    pub mean_power: f64,
    /// The motor's rated torque (N·m), where its curve states one ([`Motor::rating`]).
    pub rated_torque: Option<f64>,
    /// RMS torque ≤ rated torque (true when no rating is known).
    pub within_rating: bool,
}

/// Where a stop ended.
#[derive(Clone, Debug, PartialEq)]
pub struct Stop {
    /// The run until the machine is at rest.
    pub run: Run,
    /// The time to rest, s.
    pub time: f64,
    /// The input's travel to rest, rad (m).
    pub travel: f64,
}

impl<'a, M: OneDof> Drive<'a, M> {
    /// `machine` driven by `motor` under `loads(q)`, no flywheel.
    pub fn new(
        machine: &'a M,
        motor: Motor,
        loads: impl Fn(f64) -> Result<M::Loads, MechError> + 'a,
    ) -> Self {
        Drive {
            machine,
            motor,
            loads: Box::new(loads),
            flywheel: 0.0,
        }
    }

    /// With a flywheel J (kg·m²; kg on a prismatic input) on the input shaft, J ≥ 0.
    pub fn flywheel(mut self, j: f64) -> Result<Self, MechError> {
        if !(j.is_finite() && j >= 0.0) {
            return Err(MechError::InvalidInput(format!(
                "the flywheel's inertia must be a finite number ≥ 0, got {j} kg·m²"
            )));
        }
        self.flywheel = j;
        Ok(self)
    }

    /// The motor.
    pub fn motor(&self) -> &Motor {
        &self.motor
    }

    /// q̈ at (q, q̇) under the action `driver` (N·m): (driver + M* − ½ dI*/dq q̇²)/(I* + J).
    pub fn acceleration_with(&self, q: f64, qd: f64, driver: f64) -> Result<f64, MechError> {
        let loads = (self.loads)(q)?;
        if self.flywheel == 0.0 {
            return self.machine.acceleration(q, qd, driver, &loads);
        }
        let r = self.machine.reduced(q)?;
        let moment = self.machine.reduced_moment(q, &loads)?;
        let with = Reduced {
            inertia: r.inertia + self.flywheel,
            inertia_derivative: r.inertia_derivative,
        };
        acceleration(with, moment, qd, driver)
    }

    /// q̈ at (q, q̇) under the motor.
    pub fn acceleration(&self, q: f64, qd: f64) -> Result<f64, MechError> {
        self.acceleration_with(q, qd, self.motor.on_input(qd))
    }

    /// The start from rest at q₀: the state at `samples` + 1 even times over [0, t_end].
    /// An error when the motor cannot start the machine ([`Drive::check_start`]) or the
    /// machine stalls (comes back to rest) before t_end.
    pub fn start_up(&self, q0: f64, t_end: f64, samples: usize) -> Result<Run, MechError> {
        crate::error::check_finite("q0", &[q0])?;
        self.check_start(q0)?;
        self.run(q0, 0.0, t_end, samples)
    }

    /// The motion from (q₀, q̇₀ ≥ 0) under the motor: the state at `samples` + 1 even times
    /// over [0, t_end]; an error when the machine stalls (its speed turns negative).
    pub fn run(&self, q0: f64, qd0: f64, t_end: f64, samples: usize) -> Result<Run, MechError> {
        crate::error::check_finite("q0, qd0, t_end", &[q0, qd0, t_end])?;
        if !(t_end > 0.0) || samples == 0 || !(qd0 >= 0.0) {
            return Err(MechError::InvalidInput(format!(
                "a run needs q̇0 ≥ 0, t_end > 0 and at least one sample, got q̇0 = {qd0}, t_end = {t_end} s, {samples} samples"
            )));
        }
        let times: Vec<f64> = (0..=samples)
            .map(|k| t_end * k as f64 / samples as f64)
            .collect();
        let mut out = vec![[0.0; 2]; times.len()];
        let stalled = std::cell::Cell::new(None);
        let rhs = |_t: f64, y: &[f64; 2]| -> Result<[f64; 2], MechError> {
            if y[1] < 0.0 && stalled.get().is_none() {
                stalled.set(Some(y[0]));
            }
            Ok([y[1], self.acceleration(y[0], y[1])?])
        };
        let mut method = Dop853::new(RTOL, RTOL);
        ode::sample(&mut method, rhs, 0.0, [q0, qd0], &times, &mut out)?;
        if let Some(q) = stalled.get() {
            return Err(self.stall(q, "under the motor"));
        }
        Ok(self.table(times, &out, |qd| self.motor.on_input(qd)))
    }

    /// `Ok` when the motor's action at rest on the input, n T(0), exceeds the resisting
    /// moment −M*(q₀) (loads and gravity) at q₀: the machine starts from rest there.
    pub fn check_start(&self, q0: f64) -> Result<(), MechError> {
        let at_rest = self.motor.on_input(0.0);
        let resisting = self.machine.reduced_moment(q0, &(self.loads)(q0)?)?;
        if at_rest + resisting > 0.0 {
            return Ok(());
        }
        Err(MechError::InvalidInput(format!(
            "the motor cannot start the machine at q0 = {q0:.6} rad: its action at rest on the input is {at_rest:.6} N·m against a resisting moment of {:.6} N·m; choose a motor with a larger starting torque or a larger reduction ratio (now {})",
            -resisting,
            self.motor.ratio()
        )))
    }

    fn table(&self, t: Vec<f64>, y: &[[f64; 2]], action: impl Fn(f64) -> f64) -> Run {
        Run {
            q: y.iter().map(|s| s[0]).collect(),
            qd: y.iter().map(|s| s[1]).collect(),
            torque: y.iter().map(|s| action(s[1])).collect(),
            t,
        }
    }

    fn stall(&self, q: f64, when: &str) -> MechError {
        MechError::InvalidInput(format!(
            "the machine stalls {when} near q = {q:.6} rad: the motor's action (at most {:.6} N·m on the input, at rest) does not carry it through the resisting moments; choose a stronger motor, a larger reduction ratio (now {}) or a flywheel",
            self.motor.on_input(0.0),
            self.motor.ratio()
        ))
    }

    /// The mean of M*(q) over [q₀, q₀ + λ], N·m, by Gauss–Kronrod on 64 panels.
    fn mean_moment(&self, q0: f64, period: f64) -> Result<f64, MechError> {
        let panels = 64;
        let mut sum = 0.0;
        for k in 0..panels {
            let a = q0 + period * k as f64 / panels as f64;
            let b = q0 + period * (k + 1) as f64 / panels as f64;
            sum += super::gauss_kronrod(
                |q| self.machine.reduced_moment(q, &(self.loads)(q)?),
                a,
                b,
                1e-10,
                0.0,
            )?;
        }
        Ok(sum / period)
    }

    /// The speed ω (rad/s on the input) where the motor's action balances the mean resisting
    /// moment: n T(n ω) + mean M* = 0 on the falling part of the curve.
    fn balance_speed(&self, mean: f64) -> Result<f64, MechError> {
        let n = self.motor.ratio();
        let Some(free) = self.motor.free_speed() else {
            return Err(MechError::InvalidInput(
                "a steady regime needs a motor whose torque falls with speed (dc, induction, or a table that crosses zero): a constant torque sets no speed".into(),
            ));
        };
        let hi = 2.0 * free / n;
        let f = |w: f64| self.motor.on_input(w) + mean;
        let steps = 4000;
        let mut prev = (0.0, f(0.0));
        for k in 1..=steps {
            let w = hi * k as f64 / steps as f64;
            let here = (w, f(w));
            if prev.1 > 0.0 && here.1 <= 0.0 {
                let (mut a, mut b) = (prev.0, here.0);
                for _ in 0..200 {
                    let c = 0.5 * (a + b);
                    if f(c) > 0.0 {
                        a = c;
                    } else {
                        b = c;
                    }
                }
                if a > 0.0 {
                    return Ok(0.5 * (a + b));
                }
            }
            prev = here;
        }
        Err(MechError::InvalidInput(format!(
            "the motor cannot drive the machine: its action on the input never balances the mean resisting moment {:.6} N·m between rest and {hi:.3} rad/s; choose a motor with more torque or a larger reduction ratio (now {n})",
            -mean
        )))
    }

    /// The state at q₀ + λ from ω₀ at q₀, q the independent variable: y = (ω, t, ∫T_m² dt,
    /// ∫T_m ω_m dt) with dω/dq = q̈/ω, dt/dq = 1/ω, d(∫T_m² dt)/dq = T_m²/ω and
    /// d(∫T_m ω_m dt)/dq = n T_m (T_m = T(n ω) on the motor's shaft); the dense samples at
    /// `qs` when asked.
    fn shoot(
        &self,
        q0: f64,
        period: f64,
        w0: f64,
        table: Option<(&[f64], &mut [[f64; 4]])>,
    ) -> Result<[f64; 4], MechError> {
        let low = std::cell::Cell::new(None);
        let n = self.motor.ratio();
        let rhs = |q: f64, y: &[f64; 4]| -> Result<[f64; 4], MechError> {
            let w = y[0];
            if !(w > 0.0) {
                low.set(Some(q));
                return Err(MechError::NoAssembly);
            }
            let tm = self.motor.torque(n * w);
            let qdd = self.acceleration_with(q, w, n * tm)?;
            Ok([qdd / w, 1.0 / w, tm * tm / w, n * tm])
        };
        let mut method = Dop853::new(RTOL, RTOL * w0.abs().max(1e-300));
        let y0 = [w0, 0.0, 0.0, 0.0];
        let end = match table {
            Some((qs, out)) => {
                ode::sample(&mut method, rhs, q0, y0, qs, out).map(|_| out[out.len() - 1])
            }
            None => ode::integrate(&mut method, rhs, q0, y0, q0 + period).map(|o| o.y),
        };
        match (end, low.get()) {
            (_, Some(q)) => Err(self.stall(q, "in the steady regime")),
            (r, None) => r,
        }
    }

    /// The periodic steady regime over [q₀, q₀ + λ] (λ = 2π, or 4π for a four-stroke
    /// engine), tabulated at `points` + 1 even positions: ω₀ with ω(q₀ + λ) = ω₀ by
    /// shooting, then the table, ε, the mean speed and the motor check.
    pub fn steady(&self, q0: f64, period: f64, points: usize) -> Result<Steady, MechError> {
        crate::error::check_finite("q0, period", &[q0, period])?;
        if !(period > 0.0) || points < 2 {
            return Err(MechError::InvalidInput(format!(
                "the steady regime needs a positive period and at least 2 points, got {period} rad, {points}"
            )));
        }
        let mean = self.mean_moment(q0, period)?;
        let guess = self.balance_speed(mean)?;
        let residual =
            |w: f64| -> Result<f64, MechError> { Ok(self.shoot(q0, period, w, None)?[0] - w) };
        let (mut a, mut b) = (guess, guess * (1.0 + 1e-3));
        let (mut fa, mut fb) = (residual(a)?, residual(b)?);
        let mut iterations = 2;
        // Converged when a secant step moves ω₀ by less than 1e-11 of it: the residual itself
        // is the integration's noise there (about 1e-12 of ω).
        while (b - a).abs() > 1e-11 * b && fb != 0.0 {
            if iterations >= 60 || fb == fa {
                return Err(MechError::InvalidInput(format!(
                    "no periodic steady regime found from {guess:.6} rad/s after {iterations} shots (the last residual {fb:.3e} rad/s): the regime may be unstable under this motor"
                )));
            }
            let c = b - fb * (b - a) / (fb - fa);
            (a, fa) = (b, fb);
            b = if c > 0.0 { c } else { 0.5 * b };
            fb = residual(b)?;
            iterations += 1;
        }
        let qs: Vec<f64> = (0..=points)
            .map(|k| q0 + period * k as f64 / points as f64)
            .collect();
        let mut y = vec![[0.0; 4]; qs.len()];
        let end = self.shoot(q0, period, b, Some((&qs, &mut y)))?;
        let qd: Vec<f64> = y.iter().map(|s| s[0]).collect();
        let t: Vec<f64> = y.iter().map(|s| s[1]).collect();
        let period_time = t[points];
        let mean_speed = period / period_time;
        let (lo, hi) = qd
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), &w| {
                (l.min(w), h.max(w))
            });
        let average = 0.5 * (hi + lo);
        let torque: Vec<f64> = qd.iter().map(|&w| self.motor.on_input(w)).collect();
        let check = self.check(&qd, end, period_time);
        Ok(Steady {
            epsilon: (hi - lo) / average,
            q: qs,
            qd,
            t,
            torque,
            period_time,
            mean_speed,
            check,
            iterations,
        })
    }

    /// The motor's duty over the cycle on its shaft from the integrals the shooting
    /// carried (`end` = the state at q₀ + λ): RMS = √(∫T_m² dt / t_λ), mean power
    /// ∫T_m ω_m dt / t_λ; the peak over the table `qd`.
    fn check(&self, qd: &[f64], end: [f64; 4], period_time: f64) -> MotorCheck {
        let n = self.motor.ratio();
        let peak_torque = qd
            .iter()
            .fold(0.0f64, |m, &w| m.max(self.motor.torque(n * w).abs()));
        let rms_torque = (end[2] / period_time).sqrt();
        let rated_torque = self.motor.rating().map(|(t, _)| t);
        MotorCheck {
            peak_torque,
            rms_torque,
            mean_power: end[3] / period_time,
            within_rating: rated_torque.map_or(true, |r| rms_torque <= r),
            rated_torque,
        }
    }

    /// The stop from (q₀, q̇₀ > 0) with the motor off and a brake of constant torque
    /// `brake` (N·m ≥ 0, 0 to coast) against the motion, sampled every `dt` seconds until the
    /// machine is at rest (the last sample at the time to rest); an error when it is not at
    /// rest by `t_max`, or when that would be more than 10⁷ samples.
    pub fn stop(
        &self,
        q0: f64,
        qd0: f64,
        brake: f64,
        dt: f64,
        t_max: f64,
    ) -> Result<Stop, MechError> {
        crate::error::check_finite("dt", &[dt])?;
        if !(dt > 0.0 && t_max > dt) {
            return Err(MechError::InvalidInput(format!(
                "a stop sampled every dt needs 0 < dt < t_max, got dt = {dt} s, t_max = {t_max} s"
            )));
        }
        self.stop_sampled(q0, qd0, brake, t_max, |time| {
            let steps = (time / dt).floor();
            if steps >= MAX_SAMPLES as f64 {
                return Err(MechError::InvalidInput(format!(
                    "the machine comes to rest after {time} s: sampled every {dt} s, more than {MAX_SAMPLES} rows; give a larger dt"
                )));
            }
            let mut times: Vec<f64> = (0..=steps as usize).map(|k| k as f64 * dt).collect();
            if times.last() != Some(&time) {
                times.push(time);
            }
            Ok(times)
        })
    }

    /// The stop of [`Drive::stop`], sampled at `steps` + 1 even times over [0, t_s], t_s the
    /// time to rest (1 ≤ `steps` ≤ 10⁷): the table of a stop whose length is not known
    /// beforehand.
    pub fn stop_steps(
        &self,
        q0: f64,
        qd0: f64,
        brake: f64,
        steps: usize,
        t_max: f64,
    ) -> Result<Stop, MechError> {
        if !(1..=MAX_SAMPLES).contains(&steps) {
            return Err(MechError::InvalidInput(format!(
                "a stop in {steps} even steps: give 1 to {MAX_SAMPLES}"
            )));
        }
        self.stop_sampled(q0, qd0, brake, t_max, |time| {
            let mut times: Vec<f64> = (0..=steps)
                .map(|k| time * k as f64 / steps as f64)
                .collect();
            times[steps] = time;
            Ok(times)
        })
    }

    /// The stop: the time to rest t_s by the event q̇ = 0, then the state at `times(t_s)`
    /// (increasing from 0, the last t_s) by the same right-hand side.
    fn stop_sampled(
        &self,
        q0: f64,
        qd0: f64,
        brake: f64,
        t_max: f64,
        times: impl FnOnce(f64) -> Result<Vec<f64>, MechError>,
    ) -> Result<Stop, MechError> {
        crate::error::check_finite("q0, qd0, brake, t_max", &[q0, qd0, brake, t_max])?;
        if !(qd0 > 0.0 && brake >= 0.0 && t_max > 0.0) {
            return Err(MechError::InvalidInput(format!(
                "a stop needs q̇0 > 0, a brake ≥ 0 and t_max > 0, got q̇0 = {qd0}, brake = {brake} N·m, t_max = {t_max} s"
            )));
        }
        let rhs = |_t: f64, y: &[f64; 2]| -> Result<[f64; 2], MechError> {
            Ok([y[1], self.acceleration_with(y[0], y[1], -brake)?])
        };
        let mut g = |_t: f64, y: &[f64; 2]| y[1];
        let mut event = ode::Event::new(&mut g);
        event.direction = -1;
        let mut method = Dop853::new(RTOL, RTOL * qd0);
        let end = ode::solve(
            &mut method,
            rhs,
            0.0,
            [q0, qd0],
            t_max,
            Some(&mut event),
            None,
        )?;
        if !end.event {
            return Err(MechError::InvalidInput(format!(
                "the machine is still moving at t = {t_max} s (q̇ = {:.6}): give it a brake or a longer time",
                end.y[1]
            )));
        }
        let times = times(end.t)?;
        let mut out = vec![[0.0; 2]; times.len()];
        // The same right-hand side again (a closure of shared references: Copy), now sampled.
        let mut method = Dop853::new(RTOL, RTOL * qd0);
        ode::sample(&mut method, rhs, 0.0, [q0, qd0], &times, &mut out)?;
        // The last row is the event itself: at rest (q̇ = 0 there, not its located root's
        // rounding, a few ulps either side).
        let last = out.len() - 1;
        out[last] = [end.y[0], 0.0];
        let run = self.table(times, &out, |_| -brake);
        Ok(Stop {
            time: end.t,
            travel: end.y[0] - q0,
            run,
        })
    }
}
