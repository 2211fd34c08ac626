//! One case: the text through the run-time loader, then every solver of the run-time
//! [`Mechanism`] (the path of the `mech` tool and of Python) on what loads, at moderate
//! and at hostile inputs, each call under the [`Watchdog`]. A finding is a panic (or
//! `MechError::Internal`, a panic the loader caught), a non-finite number inside an `Ok`
//! (every field of every result, [`crate::check`]), an `Ok` for a NaN or infinite input,
//! or a call over [`SLOW`]. The solvers of any mechanism and the refusals of non-finite
//! input are here; the one-input dynamics in [`crate::dynamics`], the cams, equivalent
//! masses and parameters in [`crate::design`].

use crate::check::{first_non_finite, Numbers};
use crate::watchdog::{Watchdog, SLOW};
use mech_core::dynamics::{
    kinetic_energy, lagrange_acceleration, mass_matrix, quinn_coefficients, total_energy,
    velocity_terms,
};
use mech_core::model::Load;
use mech_core::runtime::columns::{Columns, Part};
use mech_core::runtime::Loads;
use mech_core::solvers::friction::JointFriction;
use mech_core::solvers::traits::{Machine, OneDof};
use mech_core::{MechError, Mechanism};
use std::panic::{catch_unwind, AssertUnwindSafe};
use std::time::Duration;

/// What went wrong in one call (written out with `Debug`).
#[derive(Debug)]
#[allow(dead_code)] // Read through `Debug`.
pub enum Finding {
    /// A panic, or `MechError::Internal` (a panic caught inside mech): the call and the message.
    Panic(String),
    /// A non-finite number inside `Ok`, or `Ok` for a NaN or infinite input.
    NonFinite(String),
    /// A call over [`SLOW`]: how long, which call.
    Slow(Duration, &'static str),
}

/// The inputs each mechanism is solved at: q, q̇, q̈ of the first input (the others
/// shifted and scaled from them) and the size of every load (N, N·m); moderate first,
/// then hostile (far turns, speeds of 1e20 and 1e300, loads of 1e300).
pub const INPUTS: [(f64, f64, f64, f64); 8] = [
    (0.0, 1.0, 0.0, 1e3),
    (0.7, 100.0, 1e3, -2e3),
    (2.0, 1e20, 0.0, 1e3),
    (-1.3, 0.0, 0.0, 0.0),
    (1e6, 3.0, -5.0, 1e3),
    (0.3, 1e300, 1e300, 1e300),
    (1.1, -1e-300, -1e300, -1e300),
    (1e15, 1e10, 1e20, 1e150),
];

/// One loaded one-input mechanism in this many gets [`crate::dynamics`] (chosen at random).
pub const DYNAMICS_EVERY: u64 = 16;

/// The numbers a parameter is set to by [`Mechanism::set_param`] (the last two must be
/// refused).
pub const PARAMS: [f64; 14] = [
    0.0,
    -0.0,
    1e308,
    -1e308,
    5e-324,
    1e16,
    -1e-300,
    0.5,
    3.0,
    1e200,
    -2.0,
    1e6,
    f64::NAN,
    f64::INFINITY,
];

/// The calls of one case and what they found.
pub struct Case<'a> {
    dog: &'a Watchdog,
    /// The inputs of the calls under way, for the findings' messages.
    pub at: String,
    /// What was found.
    pub found: Vec<Finding>,
}

impl<'a> Case<'a> {
    /// A case whose calls run under `dog`.
    pub fn new(dog: &'a Watchdog) -> Self {
        Case {
            dog,
            at: String::new(),
            found: Vec::new(),
        }
    }

    /// Run `f` as the call `what` under the watchdog: a panic or a run over [`SLOW`] is a
    /// finding; `None` after a panic.
    pub fn call<T>(&mut self, what: &'static str, f: impl FnOnce() -> T) -> Option<T> {
        let start = self.dog.enter(what);
        let r = catch_unwind(AssertUnwindSafe(f));
        let dt = start.elapsed();
        self.dog.leave();
        if dt > SLOW {
            self.found.push(Finding::Slow(dt, what));
        }
        match r {
            Ok(v) => Some(v),
            Err(p) => {
                let msg = p
                    .downcast_ref::<String>()
                    .cloned()
                    .or_else(|| p.downcast_ref::<&str>().map(|s| s.to_string()))
                    .unwrap_or_default();
                self.found
                    .push(Finding::Panic(format!("{what}{}: {msg}", self.at)));
                None
            }
        }
    }

    /// [`Case::call`] of a fallible call: its value when `Ok`; `MechError::Internal` is a
    /// panic.
    pub fn attempt<T>(
        &mut self,
        what: &'static str,
        f: impl FnOnce() -> Result<T, MechError>,
    ) -> Option<T> {
        match self.call(what, f)? {
            Ok(v) => Some(v),
            Err(MechError::Internal(e)) => {
                self.found
                    .push(Finding::Panic(format!("{what}{}: {e}", self.at)));
                None
            }
            Err(_) => None,
        }
    }

    /// Every number of `t` is finite, or a finding.
    pub fn numbers<T: Numbers + ?Sized>(&mut self, what: &'static str, t: &T) -> bool {
        match first_non_finite(t) {
            None => true,
            Some(bad) => {
                self.found
                    .push(Finding::NonFinite(format!("{what}{}: {bad}", self.at)));
                false
            }
        }
    }

    /// [`Case::attempt`], and every number of the value finite: the value then.
    pub fn solve<T: Numbers>(
        &mut self,
        what: &'static str,
        f: impl FnOnce() -> Result<T, MechError>,
    ) -> Option<T> {
        let v = self.attempt(what, f)?;
        self.numbers(what, &v).then_some(v)
    }

    /// A call given a NaN or an infinity must return an error.
    pub fn refuse<T>(&mut self, what: &'static str, f: impl FnOnce() -> Result<T, MechError>) {
        if let Some(Ok(_)) = self.call(what, f) {
            self.found.push(Finding::NonFinite(format!(
                "{what}{}: Ok for a NaN or infinite input",
                self.at
            )));
        }
    }
}

/// Every load of `m` of size `size`: a force (size, −2 size) N, a torque size N·m.
pub fn loads(m: &Mechanism, size: f64) -> Loads {
    let mut l = m.loads();
    for load in &m.model().loads {
        let v = [size, -2.0 * size];
        let n = if matches!(load, Load::Force { .. }) {
            2
        } else {
            1
        };
        l.set_by_name(load.name(), &v[..n]);
    }
    l
}

/// Load `text` and call every solver on what loads; `pick` (random bits) chooses the
/// parameter changed by `set_param` and whether the costly [`crate::dynamics`] run. The findings,
/// and whether it loaded.
pub fn run(text: &str, pick: u64, dog: &Watchdog) -> (Vec<Finding>, bool) {
    if mech_core::runtime::spatial_columns::is_spatial(text) {
        return crate::spatial::run(text, dog);
    }
    let mut c = Case::new(dog);
    // The loader catches a panic of its own thread: `Internal`, counted as a panic.
    let Some(m) = c.attempt("load", || Mechanism::from_dsl(text)) else {
        return (c.found, false);
    };
    let g = m.dof();
    for &(q0, qd0, qdd0, size) in &INPUTS {
        let q: Vec<f64> = (0..g).map(|i| q0 + 0.1 * i as f64).collect();
        let qd: Vec<f64> = (0..g).map(|i| qd0 * (1.0 + i as f64)).collect();
        let qdd: Vec<f64> = (0..g).map(|i| qdd0 * (1.0 - 0.5 * i as f64)).collect();
        c.at = format!(" at q = {q:?}, qd = {qd:?}, qdd = {qdd:?}, loads {size:e}");
        solvers(&mut c, &m, &q, &qd, &qdd, &loads(&m, size));
    }
    c.at.clear();
    refusals(&mut c, &m);
    // The direct problem and the flywheel cost tens of milliseconds, a hundred times the
    // rest: one loaded mechanism in DYNAMICS_EVERY gets them.
    if g == 1 && (pick >> 40).checked_rem(DYNAMICS_EVERY) == Some(0) {
        crate::dynamics::dynamics(&mut c, &m);
    }
    crate::design::cams(&mut c, &m);
    crate::design::equivalent_masses(&mut c, &m);
    crate::design::parameter(&mut c, &m, pick);
    (c.found, true)
}

/// Every solver at (q, q̇, q̈) with `loads`: pose, kinematics, kinetostatics (with and
/// without friction), the motor actions by virtual power, the energies, a row of every
/// column, Zhukovski's I*, M* and q̈, Quinn's coefficients, and Lagrange's M, b and q̈.
fn solvers(c: &mut Case, m: &Mechanism, q: &[f64], qd: &[f64], qdd: &[f64], loads: &Loads) {
    c.solve("pose", || m.pose(q));
    if let Some(mo) = c.solve("kinematics", || m.kinematics(q, qd, qdd)) {
        c.solve("kinetostatics", || m.kinetostatics(&mo, loads));
        // Friction of a real joint, then a hostile one (finite, or self-locking).
        for (what, mu, pin_radius) in [
            ("kinetostatics with friction", 0.15, 0.01),
            ("kinetostatics with friction (hostile)", 1e6, 1e3),
        ] {
            let friction = vec![JointFriction { mu, pin_radius }; m.model().joints.len()];
            c.solve(what, || {
                m.kinetostatics_with_friction(&mo, loads, &friction)
            });
        }
        c.solve("driver_action", || m.driver_action(&mo, loads));
        if c.solve("total_energy", || total_energy(m, q, qd)).is_some() {
            // The parts of a finite total: each finite too.
            if let Some(e) = c.call("energies", || {
                let mut links = vec![0.0; Machine::links(m)];
                m.link_kinetic_energies(&mo, &mut links);
                (links, kinetic_energy(m, &mo), m.potential_energy(&mo))
            }) {
                c.numbers("energies", &e);
            }
        }
    }
    // Every part; positions alone and points alone (their own, allocation-free path).
    for (what, parts) in [
        ("columns row", Part::ALL),
        ("columns row (pose)", Part::POSE),
        ("columns row (points)", &[Part::Inputs, Part::Points][..]),
    ] {
        let columns = Columns::new(m, parts);
        c.solve(what, || columns.row(m, q, qd, qdd, loads));
    }
    if m.dof() == 1 {
        c.solve("reduced", || OneDof::reduced(m, q[0]));
        c.solve("reduced_moment", || OneDof::reduced_moment(m, q[0], loads));
        c.solve("acceleration", || {
            OneDof::acceleration(m, q[0], qd[0], 1e3, loads)
        });
        c.solve("quinn_coefficients", || {
            let mut out = vec![0.0; Machine::links(m)];
            quinn_coefficients(m, q[0], &mut out).map(|_| out)
        });
    }
    batch(c, m, q, qd, qdd, loads);
    match m.dof() {
        1 => lagrange::<1>(c, m, q, qd, loads),
        2 => lagrange::<2>(c, m, q, qd, loads),
        3 => lagrange::<3>(c, m, q, qd, loads),
        _ => {}
    }
}

/// The batched forms (docs/batch.md) at seven configurations around q (the fourth NaN):
/// a slot not listed in the returned `BatchErrors` is finite, a listed one is NaN, and each
/// configuration fails exactly where the one-configuration solver fails. The values are
/// compared (to 1e-9 of the batch's largest magnitude: the lane kernels order their
/// operations differently) where they are well conditioned — the points, the motor
/// actions, I* (a sum of positive terms) — not dI*/dq and q̈, whose sums can cancel on a
/// hostile drawing (a 10⁶ m rod on a 5 cm crank at q̇ = 10²⁰ differed by 6e-3 relative,
/// each route within that sum's conditioning).
fn batch(c: &mut Case, m: &Mechanism, q: &[f64], qd: &[f64], qdd: &[f64], loads: &Loads) {
    let g = m.dof();
    let n = 7;
    let shift = |x: &[f64], i: usize| -> Vec<f64> {
        x.iter()
            .map(|v| {
                if i == 3 {
                    f64::NAN
                } else {
                    v + 0.37 * i as f64
                }
            })
            .collect()
    };
    let qs: Vec<f64> = (0..n).flat_map(|i| shift(q, i)).collect();
    let (qds, qdds): (Vec<f64>, Vec<f64>) = (qd.repeat(n), qdd.repeat(n));
    let np = m.model().points.len();
    let mut points = vec![0.0; 2 * np * n];
    if let Some(errors) = c.call("points_many", || m.points_many(&qs, &mut points)) {
        check_rows(c, "points_many", &errors, &points, 2 * np, 2 * np, |i| {
            let mut row = vec![0.0; 2 * np];
            m.points_into(&qs[i * g..(i + 1) * g], &mut Vec::new(), &mut row)
                .map(|()| row)
        });
    }
    let mut actions = vec![0.0; g * n];
    if let Some(errors) = c.call("driver_action_many", || {
        m.driver_action_many(&qs, &qds, &qdds, loads, &mut actions)
    }) {
        check_rows(c, "driver_action_many", &errors, &actions, g, g, |i| {
            let k = i * g..(i + 1) * g;
            let mo = m.kinematics(&qs[k.clone()], &qds[k.clone()], &qdds[k])?;
            m.driver_action(&mo, loads)
        });
    }
    if g != 1 {
        return;
    }
    let (mut a, mut b) = (vec![0.0; n], vec![0.0; n]);
    if let Some(errors) = c.call("reduced_many", || m.reduced_many(&qs, &mut a, &mut b)) {
        let both: Vec<f64> = a.iter().zip(&b).flat_map(|(x, y)| [*x, *y]).collect();
        check_rows(c, "reduced_many", &errors, &both, 2, 1, |i| {
            OneDof::reduced(m, qs[i]).map(|r| vec![r.inertia, r.inertia_derivative])
        });
    }
    let driver = vec![1e3; n];
    let mut acc = vec![0.0; n];
    if let Some(errors) = c.call("acceleration_many", || {
        m.acceleration_many(&qs, &qds, &driver, loads, &mut acc)
    }) {
        check_rows(c, "acceleration_many", &errors, &acc, 1, 0, |i| {
            OneDof::acceleration(m, qs[i], qds[i], 1e3, loads).map(|v| vec![v])
        });
    }
}

/// One batched call's rows (`width` values each) against `one(i)`, the one-configuration
/// solver's answer, its first `compared` values by value; a disagreement is a finding.
fn check_rows(
    c: &mut Case,
    what: &'static str,
    errors: &mech_core::solvers::batch::BatchErrors,
    out: &[f64],
    width: usize,
    compared: usize,
    one: impl Fn(usize) -> Result<Vec<f64>, MechError>,
) {
    if let Some(e) = errors.refusal() {
        c.found
            .push(Finding::NonFinite(format!("{what}{}: refused: {e}", c.at)));
        return;
    }
    let scale = out
        .iter()
        .filter(|v| v.is_finite())
        .fold(1.0f64, |s, v| s.max(v.abs()));
    for (i, row) in out.chunks(width.max(1)).enumerate() {
        let listed = errors.get(i).is_some();
        let bad = match one(i) {
            Ok(v) => {
                listed
                    || row.iter().any(|y| !y.is_finite())
                    || v.iter()
                        .zip(row)
                        .take(compared)
                        .any(|(x, y)| !((x - y).abs() <= 1e-9 * scale))
            }
            Err(_) => !listed || !row.iter().all(|v| v.is_nan()),
        };
        if bad {
            c.found.push(Finding::NonFinite(format!(
                "{what}{}: configuration {i} disagrees with the one-configuration solver",
                c.at
            )));
            return;
        }
    }
}

/// Lagrange's mass matrix, velocity terms and accelerations for a mechanism of G inputs.
fn lagrange<const G: usize>(c: &mut Case, m: &Mechanism, q: &[f64], qd: &[f64], loads: &Loads) {
    let (Ok(q), Ok(qd)) = (<[f64; G]>::try_from(q), <[f64; G]>::try_from(qd)) else {
        return;
    };
    c.solve("mass_matrix", || mass_matrix::<_, G>(m, &q));
    c.solve("velocity_terms", || {
        velocity_terms::<_, G>(m, &q, &qd, loads)
    });
    c.solve("lagrange_acceleration", || {
        lagrange_acceleration::<_, G>(m, &q, &qd, &[1e3; G], loads)
    });
}

/// NaN and infinite inputs, loads and settings: every solver must refuse them.
fn refusals(c: &mut Case, m: &Mechanism) {
    let g = m.dof();
    let ok = vec![0.5; g];
    for bad in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
        let v = vec![bad; g];
        c.refuse("pose (NaN q)", || m.pose(&v));
        c.refuse("kinematics (NaN q)", || m.kinematics(&v, &ok, &ok));
        c.refuse("kinematics (NaN qd)", || m.kinematics(&ok, &v, &ok));
        c.refuse("kinematics (NaN qdd)", || m.kinematics(&ok, &ok, &v));
        c.refuse("total_energy (NaN qd)", || total_energy(m, &ok, &v));
        for parts in [Part::ALL, Part::POSE, &[Part::Inputs, Part::Points][..]] {
            let columns = Columns::new(m, parts);
            c.refuse("columns row (NaN q)", || {
                columns.row(m, &v, &ok, &ok, &m.loads())
            });
        }
        if !m.model().loads.is_empty() {
            let nan = loads(m, bad);
            if let Some(mo) = c.attempt("kinematics", || m.kinematics(&ok, &ok, &ok)) {
                c.refuse("kinetostatics (NaN loads)", || m.kinetostatics(&mo, &nan));
                c.refuse("driver_action (NaN loads)", || m.driver_action(&mo, &nan));
            }
            if g == 1 {
                c.refuse("reduced_moment (NaN loads)", || {
                    OneDof::reduced_moment(m, 0.5, &nan)
                });
            }
        }
        // A NaN or infinite friction coefficient.
        if let Some(mo) = c.attempt("kinematics", || m.kinematics(&ok, &ok, &ok)) {
            let friction = vec![
                JointFriction {
                    mu: bad,
                    pin_radius: 0.01,
                };
                m.model().joints.len()
            ];
            let l = loads(m, 1e3);
            c.refuse("kinetostatics with friction (NaN mu)", || {
                m.kinetostatics_with_friction(&mo, &l, &friction)
            });
        }
        if g == 1 {
            let l = m.loads();
            c.refuse("reduced (NaN q)", || OneDof::reduced(m, bad));
            c.refuse("reduced_moment (NaN q)", || {
                OneDof::reduced_moment(m, bad, &l)
            });
            c.refuse("acceleration (NaN q)", || {
                OneDof::acceleration(m, bad, 1.0, 0.0, &l)
            });
            c.refuse("acceleration (NaN qd)", || {
                OneDof::acceleration(m, 0.5, bad, 0.0, &l)
            });
            c.refuse("acceleration (NaN driver)", || {
                OneDof::acceleration(m, 0.5, 1.0, bad, &l)
            });
        }
    }
}
