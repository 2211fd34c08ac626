//! Optimisation of any mechanism: named numbers of its text varied within bounds to
//! minimise an objective of its motion or dynamics, subject to constraints; the result an
//! ordinary mechanism file.
//!
//! The variables are constants of the `consts { .. }` block or a link's `mass` / `inertia`
//! ([`super::rewrite`]); each candidate is the text with the values written in, loaded by
//! every check of the loader (one that does not load, or does not assemble over the whole
//! cycle, is infeasible). The objectives, over one period of a one-input machine turning at
//! the constant speed q̇ at `steps` instants (q̈ = 0):
//! - `peak_driver`: max |Q| of the motor's action; `rms_driver`: √(mean Q²);
//! - `flywheel`: the inertia for the coefficient of fluctuation ε at mean speed q̇
//!   (Wittenbauer's exact method on the cycle balanced by a constant torque, its work
//!   integrals to the relative tolerance [`FLYWHEEL_RTOL`]: `mech flywheel` on the written
//!   file gives the inertia to the last digits);
//! - `peak_reaction(J)`: max |R_J| at joint J;
//! - `rms_shaking`: √(mean |F|²) of the shaking force F = −Σ m a_G (SPEC §3g: no loads,
//!   no gravity in it);
//! - `path(TARGETS, P)`: Σᵢ min_k |P(q_k) − Tᵢ|² over the instants (the SPEC §3f error
//!   on the sampled curve).
//!
//! The constraints: `assembles` (always: every instant solves), `grashof` (a four-bar:
//! s + l ≤ p + q of its joint distances), `transmission >= μ` (at every revolute joint that
//! pins a moving link to a link pinned to the ground other than the input's, the angle
//! between the two links' lines, folded into [0°, 90°], stays ≥ μ).
//!
//! The search, in the unit cube of the bounds: the file's own values and a Halton sequence
//! (starting at index `seed`) of 8 + 4d points, then Nelder–Mead from the best feasible
//! one, its points clamped to the cube; when its simplex collapses below 10⁻⁹ of the range
//! it restarts from the next best sample (then from the best point so far, a simplex of a
//! tenth of the range), until the evaluation budget is spent. Deterministic: the same seed gives the same run. Infeasible
//! candidates rank last; when no candidate is feasible, the error names the constraint
//! that failed most often.

use super::nelder_mead::nelder_mead;
use super::rewrite;
use crate::dynamics::flywheel::Cycle;
use crate::error::MechError;
use crate::kernel::link_state::V2;
use crate::model::units::Unit;
use crate::model::JointKind;
use crate::runtime::{Loads, Mechanism};

/// A number of the text to vary.
#[derive(Clone, Debug, PartialEq)]
pub struct Variable {
    /// Its name: a constant (`l`) or `links.<l>.mass` / `links.<l>.inertia`.
    pub name: String,
    /// The bounds, SI.
    pub lo: f64,
    /// The upper bound, SI.
    pub hi: f64,
    /// The unit word it is written with (`None`: a plain number, SI).
    pub unit: Option<&'static Unit>,
}

/// What to minimise.
#[derive(Clone, Debug, PartialEq)]
pub enum Objective {
    /// max |Q| of the motor's action, N·m.
    PeakDriver,
    /// √(mean Q²), N·m.
    RmsDriver,
    /// The flywheel inertia for ε (kg·m²).
    Flywheel {
        /// ε = (ω_max − ω_min)/ω_a.
        irregularity: f64,
    },
    /// max |R| at the joint, N.
    PeakReaction(String),
    /// √(mean |F|²) of the shaking force, N.
    RmsShaking,
    /// Σ min |P − T|² of the point over the cycle to the targets, m².
    Path {
        /// The targets, m.
        targets: Vec<[f64; 2]>,
        /// The point's name.
        point: String,
    },
}

impl Objective {
    /// The objective written `text` (`peak_driver`, `rms_driver`, `flywheel`,
    /// `peak_reaction(J)`, `rms_shaking`, `path(TARGETS.csv, P)`); `read` gives a path's
    /// targets from its file name; `irregularity` is the flywheel's ε.
    pub fn parse(
        text: &str,
        irregularity: Option<f64>,
        read: impl Fn(&str) -> Result<Vec<[f64; 2]>, MechError>,
    ) -> Result<Objective, MechError> {
        let t = text.trim();
        let args = |head: &str| {
            t.strip_prefix(head)
                .and_then(|r| r.trim().strip_prefix('('))
                .and_then(|r| r.strip_suffix(')'))
                .map(|r| r.split(',').map(str::trim).collect::<Vec<_>>())
        };
        Ok(match t {
            "peak_driver" => Objective::PeakDriver,
            "rms_driver" => Objective::RmsDriver,
            "rms_shaking" => Objective::RmsShaking,
            "flywheel" => Objective::Flywheel {
                irregularity: irregularity.ok_or_else(|| {
                    MechError::InvalidInput("the `flywheel` objective needs the irregularity ε it is designed for (`--irregularity 0.02`)".into())
                })?,
            },
            _ => {
                if let Some([j]) = args("peak_reaction").as_deref() {
                    Objective::PeakReaction(j.to_string())
                } else if let Some([file, p]) = args("path").as_deref() {
                    Objective::Path {
                        targets: read(file)?,
                        point: p.to_string(),
                    }
                } else {
                    return Err(MechError::InvalidInput(format!(
                        "unknown objective `{t}`: give peak_driver, rms_driver, flywheel, peak_reaction(J), rms_shaking or path(TARGETS.csv, P)"
                    )));
                }
            }
        })
    }
}

/// A constraint every candidate must meet.
#[derive(Clone, Debug, PartialEq)]
pub enum Constraint {
    /// Every instant of the cycle solves (always checked).
    Assembles,
    /// A four-bar's s + l ≤ p + q.
    Grashof,
    /// The transmission angle stays ≥ this (rad).
    Transmission(f64),
}

impl Constraint {
    /// The constraint written `text`: `assembles`, `grashof`, `transmission >= ANGLE`
    /// (`ANGLE` in degrees with `deg`, or radians).
    pub fn parse(text: &str) -> Result<Constraint, MechError> {
        let t = text.trim();
        match t {
            "assembles" => return Ok(Constraint::Assembles),
            "grashof" => return Ok(Constraint::Grashof),
            _ => {}
        }
        if let Some(rest) = t
            .strip_prefix("transmission")
            .and_then(|r| r.trim().strip_prefix(">="))
        {
            let r = rest.trim();
            let (num, scale) = match r.strip_suffix("deg") {
                Some(n) => (n.trim(), std::f64::consts::PI / 180.0),
                None => (r, 1.0),
            };
            if let Ok(v) = num.parse::<f64>() {
                if (0.0..=std::f64::consts::FRAC_PI_2).contains(&(v * scale)) {
                    return Ok(Constraint::Transmission(v * scale));
                }
            }
        }
        Err(MechError::InvalidInput(format!(
            "unknown constraint `{t}`: give assembles, grashof or `transmission >= 40 deg` (0 to 90 deg)"
        )))
    }

    fn name(&self) -> String {
        match self {
            Constraint::Assembles => "assembles".into(),
            Constraint::Grashof => "grashof".into(),
            Constraint::Transmission(a) => format!("transmission >= {:.4} deg", a.to_degrees()),
        }
    }
}

/// The cycle the objective is taken over and the search's budget.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Settings {
    /// The input's constant speed q̇ (rad/s).
    pub speed: f64,
    /// The period (rad).
    pub period: f64,
    /// Instants over the period.
    pub steps: usize,
    /// Candidates to evaluate at most.
    pub evaluations: usize,
    /// The Halton sequence's first index.
    pub seed: u64,
}

/// The result of an optimisation.
#[derive(Clone, Debug, PartialEq)]
pub struct Optimum {
    /// The variables' values, SI.
    pub values: Vec<f64>,
    /// The objective there.
    pub objective: f64,
    /// The objective of the file as given (infinite when it is infeasible).
    pub initial: f64,
    /// (evaluations so far, best objective) at each improvement.
    pub history: Vec<(usize, f64)>,
    /// The text with the values written in.
    pub text: String,
    /// The candidates evaluated.
    pub evaluations: usize,
}

struct Problem<'a, F> {
    text: &'a str,
    vars: &'a [Variable],
    ranges: Vec<std::ops::Range<usize>>,
    objective: &'a Objective,
    constraints: &'a [Constraint],
    settings: Settings,
    loads: F,
    evaluations: usize,
    failures: Vec<(String, usize)>,
}

/// A value as written in the text: in its unit word, to round-trip.
fn written(v: &Variable, x: f64) -> String {
    match v.unit {
        Some(u) => format!("{:?} {}", x / u.factor, u.word),
        None => format!("{x:?}"),
    }
}

impl<F: Fn(&Mechanism, f64) -> Result<Loads, MechError>> Problem<'_, F> {
    fn text_at(&self, x: &[f64]) -> String {
        let edits: Vec<_> = self
            .ranges
            .iter()
            .zip(self.vars)
            .zip(x)
            .map(|((r, v), &x)| (r.clone(), written(v, x)))
            .collect();
        rewrite::replace(self.text, &edits)
    }

    fn fail(&mut self, why: String) -> f64 {
        match self.failures.iter_mut().find(|f| f.0 == why) {
            Some(f) => f.1 += 1,
            None => self.failures.push((why, 1)),
        }
        f64::INFINITY
    }

    /// The objective at the values `x` (SI); infinite when infeasible.
    fn value(&mut self, x: &[f64]) -> f64 {
        self.evaluations += 1;
        let m = match Mechanism::from_dsl(&self.text_at(x)) {
            Ok(m) => m,
            Err(_) => return self.fail("the file loads (every check of the loader)".into()),
        };
        match self.evaluate(&m) {
            Ok(v) => v,
            Err(why) => self.fail(why),
        }
    }

    fn evaluate(&self, m: &Mechanism) -> Result<f64, String> {
        let s = self.settings;
        let model = m.model();
        for c in self.constraints {
            if *c == Constraint::Grashof {
                let d = four_bar_lengths(m)
                    .ok_or("grashof applies to a four-bar (four links, four revolute joints)")?;
                let mut r = d;
                r.sort_by(f64::total_cmp);
                if r[0] + r[3] > r[1] + r[2] {
                    return Err(c.name());
                }
            }
        }
        let transmission = self.constraints.iter().find_map(|c| match c {
            Constraint::Transmission(a) => Some(*a),
            _ => None,
        });
        let outputs = transmission.map(|_| output_joints(m));
        if outputs.as_ref().is_some_and(|o| o.is_empty()) {
            return Err("transmission: no revolute joint pins a moving link to a rocker pinned to the ground".into());
        }
        let joint = match self.objective {
            Objective::PeakReaction(j) => Some(
                model
                    .joint_index(j)
                    .ok_or_else(|| format!("peak_reaction: no joint `{j}`"))?,
            ),
            _ => None,
        };
        let point = match self.objective {
            Objective::Path { point, .. } => Some(
                model
                    .point_index(point)
                    .ok_or_else(|| format!("path: no point `{point}`"))?,
            ),
            _ => None,
        };
        let (mut peak, mut sum2, mut curve) = (0.0f64, 0.0f64, Vec::new());
        for k in 0..s.steps {
            let q = s.period * k as f64 / s.steps as f64;
            let motion = m
                .kinematics(&[q], &[s.speed], &[0.0])
                .map_err(|_| "assembles".to_string())?;
            if let (Some(min), Some(outs)) = (transmission, &outputs) {
                for &(j, l1, l2) in outs {
                    let mu = line_angle(m, &motion, j, l1, l2);
                    if mu < min {
                        return Err(Constraint::Transmission(min).name());
                    }
                }
            }
            match self.objective {
                Objective::PeakDriver | Objective::RmsDriver | Objective::PeakReaction(_) => {
                    let loads = (self.loads)(m, q).map_err(|e| e.to_string())?;
                    let f = m
                        .kinetostatics(&motion, &loads)
                        .map_err(|e| e.to_string())?;
                    let v = match joint {
                        Some(j) => f.joints[j].force.norm(),
                        None => f.driver[0],
                    };
                    peak = peak.max(v.abs());
                    sum2 += v * v;
                }
                Objective::RmsShaking => {
                    let f = crate::solvers::traits::Machine::shaking(m, &motion).force;
                    sum2 += f.norm_squared();
                }
                Objective::Path { .. } => curve.push(motion.points[point.unwrap_or(0)].pos),
                Objective::Flywheel { .. } => {}
            }
        }
        Ok(match self.objective {
            Objective::PeakDriver | Objective::PeakReaction(_) => peak,
            Objective::RmsDriver | Objective::RmsShaking => (sum2 / s.steps as f64).sqrt(),
            Objective::Path { targets, .. } => targets
                .iter()
                .map(|t| {
                    curve
                        .iter()
                        .map(|p| (p.x - t[0]).powi(2) + (p.y - t[1]).powi(2))
                        .fold(f64::INFINITY, f64::min)
                })
                .sum(),
            Objective::Flywheel { irregularity } => {
                let cycle = Cycle::builder(m, s.period, |q| (self.loads)(m, q))
                    .tolerance(FLYWHEEL_RTOL)
                    .build()
                    .map_err(|e| e.to_string())?;
                let (cycle, _) = cycle.balanced();
                cycle
                    .wittenbauer(s.speed, *irregularity)
                    .map_err(|e| e.to_string())?
                    .inertia
            }
        })
    }
}

/// A four-bar's joint distances (frame, crank, coupler, rocker), `None` for another machine.
fn four_bar_lengths(m: &Mechanism) -> Option<[f64; 4]> {
    let model = m.model();
    if model.links.len() != 4
        || model.joints.len() != 4
        || model.joints.iter().any(|j| j.kind != JointKind::Revolute)
    {
        return None;
    }
    let at = |j: usize| V2::from(model.points[model.joints[j].point].pos);
    let link_len = |l: usize| {
        let js: Vec<usize> = (0..4)
            .filter(|&j| model.joints[j].a == l || model.joints[j].b == l)
            .collect();
        (js.len() == 2).then(|| (at(js[0]) - at(js[1])).norm())
    };
    Some([link_len(0)?, link_len(1)?, link_len(2)?, link_len(3)?])
}

/// The revolute joints (j, the moving link, the rocker) that pin a moving link to a link
/// pinned to the ground other than the input's.
fn output_joints(m: &Mechanism) -> Vec<(usize, usize, usize)> {
    let model = m.model();
    let input_link = model.joints[model.inputs[0]].b;
    let grounded = |l: usize| {
        l != 0
            && l != input_link
            && model.joints.iter().any(|j| {
                j.kind == JointKind::Revolute && (j.a == 0 || j.b == 0) && (j.a == l || j.b == l)
            })
    };
    model
        .joints
        .iter()
        .enumerate()
        .filter(|(_, j)| j.kind == JointKind::Revolute && j.a != 0 && j.b != 0)
        .filter_map(|(k, j)| match (grounded(j.a), grounded(j.b)) {
            (false, true) => Some((k, j.a, j.b)),
            (true, false) => Some((k, j.b, j.a)),
            _ => None,
        })
        .collect()
}

/// The angle (rad, folded into [0, π/2]) at joint `j` between the lines of links `l1`
/// and `l2`: each from the joint to the link's other joint.
fn line_angle(
    m: &Mechanism,
    motion: &crate::runtime::Motion,
    j: usize,
    l1: usize,
    l2: usize,
) -> f64 {
    let model = m.model();
    let p = motion.points[model.joints[j].point].pos;
    let other = |l: usize| {
        model
            .joints
            .iter()
            .enumerate()
            .find(|(k, x)| *k != j && (x.a == l || x.b == l))
            .map(|(_, x)| motion.points[x.point].pos - p)
            .unwrap_or_else(V2::zeros)
    };
    let (u, w) = (other(l1), other(l2));
    let mu = crate::kernel::link_state::cross(u, w)
        .abs()
        .atan2(u.dot(&w));
    mu.min(std::f64::consts::PI - mu)
}

/// The relative tolerance of the work quadratures of the `flywheel` objective: 1e-8, where
/// `mech flywheel` uses 1e-13. A gas-pressure table has a kink at every row, where the
/// adaptive quadrature refines; on the engine of `examples/mech/engine.mech` with its
/// 7 205-row table the tighter tolerance costs about twenty times the time of this one
/// for an inertia equal to about 1e-7 of itself.
pub const FLYWHEEL_RTOL: f64 = 1e-8;

/// Minimise `objective` over `vars` of the mechanism text `text` under `constraints`
/// (module docs), `loads(m, q)` the loads of a candidate `m` at q.
///
/// Errors: a variable not written in the text or with LO ≥ HI, a machine without one
/// revolute input, a budget below the initial sampling, no feasible candidate (naming the
/// constraint that failed most often).
pub fn optimize(
    text: &str,
    vars: &[Variable],
    objective: &Objective,
    constraints: &[Constraint],
    settings: Settings,
    loads: impl Fn(&Mechanism, f64) -> Result<Loads, MechError>,
) -> Result<Optimum, MechError> {
    if vars.is_empty() {
        return Err(MechError::InvalidInput("nothing to vary: give --vary NAME=LO..HI (a constant of `consts { .. }` or links.<l>.mass)".into()));
    }
    let mut ranges = Vec::new();
    for v in vars {
        if !(v.lo.is_finite() && v.hi.is_finite() && v.lo < v.hi) {
            return Err(MechError::InvalidInput(format!(
                "--vary {}: give finite bounds LO < HI, got {}..{}",
                v.name, v.lo, v.hi
            )));
        }
        ranges.push(rewrite::find(text, &v.name).ok_or_else(|| {
            MechError::InvalidInput(format!(
                "--vary {}: no such number in the file; vary a constant of the `consts {{ .. }}` block (`l`) or a link's `links.<l>.mass` / `links.<l>.inertia`",
                v.name
            ))
        })?);
    }
    let m0 = Mechanism::from_dsl(text)?;
    let model = m0.model();
    if model.inputs.len() != 1 || model.joints[model.inputs[0]].kind != JointKind::Revolute {
        return Err(MechError::InvalidInput(
            "optimisation turns one revolute input through its cycle".into(),
        ));
    }
    let d = vars.len();
    let initial_samples = 8 + 4 * d;
    if settings.evaluations < initial_samples + d + 1
        || settings.steps < 2
        || !(settings.period > 0.0)
        || !settings.speed.is_finite()
    {
        return Err(MechError::InvalidInput(format!(
            "an optimisation of {d} variable(s) needs at least {} evaluations, 2 steps, a period > 0 and a finite speed",
            initial_samples + d + 1
        )));
    }
    let mut p = Problem {
        text,
        vars,
        ranges,
        objective,
        constraints,
        settings,
        loads,
        evaluations: 0,
        failures: Vec::new(),
    };
    let scale = |u: &[f64]| -> Vec<f64> {
        u.iter()
            .zip(vars)
            .map(|(t, v)| v.lo + t * (v.hi - v.lo))
            .collect()
    };
    // The file's own values (clamped into the bounds; the middle for an expression) first.
    let own: Vec<f64> = p
        .ranges
        .iter()
        .zip(vars)
        .map(|(r, v)| {
            let si = rewrite::number(&text[r.clone()]).map_or(0.5 * (v.lo + v.hi), |n| n.0);
            ((si - v.lo) / (v.hi - v.lo)).clamp(0.0, 1.0)
        })
        .collect();
    let initial = {
        let x = scale(&own);
        p.value(&x)
    };
    let mut history = Vec::new();
    let mut pool: Vec<(Vec<f64>, f64)> = vec![(own.clone(), initial)];
    if initial.is_finite() {
        history.push((p.evaluations, initial));
    }
    let primes = [
        2u64, 3, 5, 7, 11, 13, 17, 19, 23, 29, 31, 37, 41, 43, 47, 53,
    ];
    for k in 0..initial_samples {
        let idx = settings.seed + 1 + k as u64;
        let u: Vec<f64> = (0..d)
            .map(|i| halton(idx, primes[i % primes.len()]))
            .collect();
        let f = p.value(&scale(&u));
        if f < history.last().map_or(f64::INFINITY, |h: &(usize, f64)| h.1) {
            history.push((p.evaluations, f));
        }
        pool.push((u, f));
    }
    pool.sort_by(|a, b| a.1.total_cmp(&b.1));
    if !pool[0].1.is_finite() {
        let (why, n) = p
            .failures
            .iter()
            .max_by_key(|f| f.1)
            .cloned()
            .unwrap_or_default();
        return Err(MechError::InvalidInput(format!(
            "no candidate of {} meets the constraints: `{why}` failed {n} times; widen the bounds or relax the constraint",
            p.evaluations
        )));
    }
    // Nelder–Mead from the best point, a simplex of the d + 1 best points; when it
    // collapses with budget left, again from the next start (the next best sample not yet
    // used, then the best so far with a simplex of a tenth of the range).
    let simplex: Vec<(Vec<f64>, f64)> = pool.iter().take(d + 1).cloned().collect();
    let starts = pool.iter().skip(1).filter(|s| s.1.is_finite()).cloned();
    let used = p.evaluations;
    let (u, f, _) = nelder_mead(
        simplex,
        starts,
        used,
        settings.evaluations,
        |u| p.value(&scale(u)),
        |n, now| {
            if now < history.last().map_or(f64::INFINITY, |h| h.1) {
                history.push((n, now));
            }
        },
    );
    let values = scale(&u);
    Ok(Optimum {
        text: p.text_at(&values),
        values,
        objective: f,
        initial,
        history,
        evaluations: p.evaluations,
    })
}

/// The i-th element of the van der Corput sequence in base `b`, in (0, 1).
fn halton(mut i: u64, b: u64) -> f64 {
    let (mut f, mut r) = (1.0, 0.0);
    while i > 0 {
        f /= b as f64;
        r += f * (i % b) as f64;
        i /= b;
    }
    r
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn written_numbers_and_the_sequence() {
        let n = |w: &str| rewrite::number(w).map(|x| x.0);
        assert!((n("143 mm").unwrap() - 0.143).abs() < 1e-16);
        assert_eq!(n("6.8e-3 kg_m2"), Ok(6.8e-3));
        assert!(n("stroke / 2").is_err());
        assert!(n("3 furlongs")
            .unwrap_err()
            .contains("unknown unit `furlongs`"));
        assert_eq!(halton(1, 2), 0.5);
        assert_eq!(halton(3, 2), 0.75);
        assert!((halton(4, 3) - 4.0 / 9.0).abs() < 1e-15);
        assert!(
            matches!(Constraint::parse("transmission >= 40 deg"), Ok(Constraint::Transmission(a)) if (a - 40f64.to_radians()).abs() < 1e-15)
        );
        assert!(Constraint::parse("transmission >= 100 deg").is_err());
        let no_file = |_: &str| -> Result<Vec<[f64; 2]>, MechError> {
            Err(MechError::InvalidInput("no".into()))
        };
        assert_eq!(
            Objective::parse("peak_reaction(O4)", None, no_file).unwrap(),
            Objective::PeakReaction("O4".into())
        );
        assert!(Objective::parse("flywheel", None, no_file).is_err());
        assert!(Objective::parse("speed", None, no_file)
            .unwrap_err()
            .to_string()
            .contains("unknown objective"));
    }
}
