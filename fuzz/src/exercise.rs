//! One case: the text through the run-time loader, then every solver of the run-time
//! [`Mechanism`] (the path of the `mech` tool and of Python) on what loads, at moderate
//! and at hostile inputs, each call under the [`Watchdog`]. A finding is a panic (or
//! `MechError::Internal`, a panic the loader caught), a non-finite number inside an `Ok`
//! (every field of every result, [`crate::check`]), an `Ok` for a NaN or infinite input,
//! or a call over [`SLOW`].

use crate::check::{first_non_finite, Numbers};
use crate::watchdog::{Watchdog, SLOW};
use mech_core::dynamics::flywheel::Cycle;
use mech_core::dynamics::ode::{self, Dop853, DormandPrince, Rk4, Tolerance};
use mech_core::dynamics::{
    equation_of_motion, kinetic_energy, lagrange_acceleration, mass_matrix, quinn_coefficients,
    total_energy, velocity_terms, EnergyMethod,
};
use mech_core::model::{JointKind, Load};
use mech_core::runtime::columns::{Columns, Part};
use mech_core::runtime::Loads;
use mech_core::solvers::friction::JointFriction;
use mech_core::solvers::traits::{Machine, OneDof};
use mech_core::{MechError, Mechanism};
use std::f64::consts::TAU;
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

/// One loaded one-input mechanism in this many gets [`dynamics`] (chosen at random).
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
    fn call<T>(&mut self, what: &'static str, f: impl FnOnce() -> T) -> Option<T> {
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
    fn numbers<T: Numbers + ?Sized>(&mut self, what: &'static str, t: &T) -> bool {
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
fn loads(m: &Mechanism, size: f64) -> Loads {
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
/// parameter changed by `set_param` and whether the costly [`dynamics`] run. The findings,
/// and whether it loaded.
pub fn run(text: &str, pick: u64, dog: &Watchdog) -> (Vec<Finding>, bool) {
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
        dynamics(&mut c, &m);
    }
    cams(&mut c, &m);
    equivalent_masses(&mut c, &m);
    parameter(&mut c, &m, pick);
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
    match m.dof() {
        1 => lagrange::<1>(c, m, q, qd, loads),
        2 => lagrange::<2>(c, m, q, qd, loads),
        3 => lagrange::<3>(c, m, q, qd, loads),
        _ => {}
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

/// The one-input dynamics: the direct problem by three integrators and by the energy
/// method, and (on a revolute input) the flywheel of a cycle, Wittenbauer's and the
/// approximate, its steady state and the check by time integration.
fn dynamics(c: &mut Case, m: &Mechanism) {
    let l = loads(m, 1e3);
    for (k, (q0, w0)) in [(0.3, 1.0f64), (0.3, 1e6)].into_iter().enumerate() {
        c.at = format!(" from q = {q0}, qd = {w0}");
        let rhs = || equation_of_motion(m, |_, _, _| (1e3, l.clone()));
        // A step budget of 20 000 bounds each run (a stiff or runaway machine ends in
        // the budget's error) to well under the second a call may take.
        let tol = Tolerance {
            max_steps: 20_000,
            ..Tolerance::new(1e-8, 1e-10)
        };
        // About half a turn: the integrators' work grows with the turns simulated.
        let t_end = (0.5 / w0).min(0.05);
        c.solve("simulate (DOP853)", || {
            ode::solve(
                &mut Dop853::with(tol),
                rhs(),
                0.0,
                [q0, w0],
                t_end,
                None,
                None,
            )
        });
        if k == 0 {
            c.solve("simulate (Dormand-Prince)", || {
                ode::solve(
                    &mut DormandPrince::with(tol),
                    rhs(),
                    0.0,
                    [q0, w0],
                    t_end,
                    None,
                    None,
                )
            });
            c.solve("simulate (RK4)", || {
                ode::solve(
                    &mut Rk4 { h: 1e-3 },
                    rhs(),
                    0.0,
                    [q0, w0],
                    t_end,
                    None,
                    None,
                )
            });
            if let Some(mut e) = c.attempt("energy method", || {
                EnergyMethod::new(m, 0.0, q0, 10.0, |_| (0.0, l.clone()), 1e-8)
            }) {
                c.solve("energy method advance", || e.advance_to(q0 + 0.5));
            }
        }
    }
    c.at.clear();
    let model = m.model();
    if model.joints[model.inputs[0]].kind != JointKind::Revolute {
        return;
    }
    // The `mech flywheel` path: the cycle, balanced, sized, simulated.
    let Some(cycle) = c.attempt("flywheel cycle", || {
        Cycle::new(m, 0.0, TAU, &[], |_| Ok(l.clone()), |_| 0.0)
    }) else {
        return;
    };
    c.numbers(
        "cycle works",
        &[
            cycle.net_work(),
            cycle.gross_work(),
            cycle.balancing_torque(),
        ],
    );
    let Some((cycle, torque)) = c.call("balance", || cycle.balanced()) else {
        return;
    };
    c.numbers("balancing torque", &torque);
    c.attempt("check_periodic", || cycle.check_periodic());
    c.solve("cycle sample", || cycle.sample(8));
    c.solve("fluctuation", || cycle.fluctuation());
    if let Some(fw) = c.solve("flywheel", || cycle.flywheel(10.0, 0.05)) {
        c.solve("flywheel simulate", || {
            cycle.simulate(&fw.exact.state, 1e-8)
        });
        c.solve("speed", || cycle.speed(&fw.exact.state, 1.0));
    }
    c.solve("steady_state", || cycle.steady_state(10.0, 1.0));
    c.solve("speed_fluctuation (hostile speed)", || {
        cycle.speed_fluctuation(1e200, 1.0)
    });
    c.solve("flywheel (hostile speed)", || cycle.flywheel(1e200, 0.05));
    c.solve("flywheel (hostile irregularity)", || {
        cycle.flywheel(10.0, 1e-300)
    });
    c.refuse("flywheel (NaN speed)", || cycle.flywheel(f64::NAN, 0.05));
    c.refuse("steady_state (NaN flywheel)", || {
        cycle.steady_state(10.0, f64::NAN)
    });
    c.refuse("flywheel cycle (NaN period)", || {
        Cycle::new(m, 0.0, f64::NAN, &[], |_| Ok(l.clone()), |_| 0.0)
    });
}

/// Every cam's profile (the `mech cam` path): its table, its design figures, its points
/// and its law far from the drawing. Where the profile exists (`missing` is `None`)
/// every number is finite.
fn cams(c: &mut Case, m: &Mechanism) {
    for (_, geom) in m.cams() {
        let p = &geom.profile;
        c.numbers("cam frame", &[geom.axis, geom.centre]);
        c.numbers(
            "cam profile numbers",
            &[p.base_radius, p.offset, p.roller()],
        );
        let Some(check) = c.call("cam check", || p.check(36)) else {
            continue;
        };
        c.numbers("cam check", &check);
        for theta in [1e6, -1e15, 1e300] {
            if let Some(s) = c.call("cam law", || p.law.eval(theta)) {
                c.numbers("cam law far from the drawing", &s);
            }
        }
        if let Some(j) = c.call("cam jumps", || p.law.jumps(1e-9)) {
            let numbers: Vec<[f64; 3]> = j.iter().map(|j| [j.at, j.before, j.after]).collect();
            c.numbers("cam jumps", &numbers);
        }
        if check.missing.is_some() {
            continue;
        }
        if let Some(t) = c.call("cam table", || p.table(36)) {
            c.numbers("cam table", &t);
        }
        if let Some(pts) = c.call("cam points", || p.points(12)) {
            c.numbers("cam points", &pts);
        }
    }
}

/// The equivalent mass systems of every moving link with a mass: its mass and inertia
/// shared between its cg and its first two points.
fn equivalent_masses(c: &mut Case, m: &Mechanism) {
    use mech_core::dynamics::equivalent_mass as eq;
    let model = m.model();
    for link in model.links.iter().skip(1) {
        let (Some(mass), [a, b, ..]) = (link.mass, link.points.as_slice()) else {
            continue;
        };
        let r = |p: usize| {
            let [x, y] = model.points[p].pos;
            (x - link.cg[0]).hypot(y - link.cg[1])
        };
        let i_g = link.inertia;
        if let Some(e) = c.attempt("bar_three_masses", || {
            eq::bar_three_masses(mass, i_g, r(*a), r(*b))
        }) {
            c.numbers("bar_three_masses", &[e.at_a, e.at_b, e.at_g]);
        }
        c.solve("bar_two_masses_static", || {
            eq::bar_two_masses_static(mass, r(*a), r(*b))
        });
        c.solve("bar_two_masses_complete", || {
            eq::bar_two_masses_complete(mass, i_g, r(*a))
        });
        let pts = [model.points[*a].pos, model.points[*b].pos, link.cg];
        c.solve("planar_four_masses", || {
            eq::planar_four_masses(mass, i_g, pts)
        });
    }
}

/// One parameter of the drawing changed by `set_param` (the run-time `from_params`) to
/// a hostile number chosen by `pick`; when it is accepted, the new mechanism's pose and
/// kinematics.
fn parameter(c: &mut Case, m: &Mechanism, pick: u64) {
    let model = m.model();
    let mut paths: Vec<(String, usize)> = vec![("gravity".into(), 2)];
    paths.extend(
        model
            .points
            .iter()
            .map(|p| (format!("points.{}", p.name), 2)),
    );
    for l in model.links.iter().skip(1) {
        paths.push((format!("links.{}.cg", l.name), 2));
        for what in ["mass", "inertia", "flywheel"] {
            paths.push((format!("links.{}.{what}", l.name), 1));
        }
    }
    for j in &model.joints {
        if j.kind != JointKind::Revolute {
            paths.push((format!("axes.{}", j.name), 2));
        }
    }
    for e in &model.elements {
        for what in ["stiffness", "free_length", "free_angle", "damping"] {
            paths.push((format!("elements.{}.{what}", e.name), 1));
        }
    }
    let (path, n) = &paths[(pick % paths.len() as u64) as usize];
    let x = PARAMS[((pick >> 16) % PARAMS.len() as u64) as usize];
    let value = [x, 0.25 * x + 0.1][..*n].to_vec();
    c.at = format!(" after set_param({path}, {value:?})");
    let mut changed = m.clone();
    let Some(r) = c.call("set_param", || changed.set_param(path, &value)) else {
        return;
    };
    match r {
        Ok(()) if !x.is_finite() => c.found.push(Finding::NonFinite(format!(
            "set_param{}: Ok for a non-finite value",
            c.at
        ))),
        Ok(()) => {
            let g = changed.dof();
            c.solve("pose", || changed.pose(&vec![0.3; g]));
            if let Some(mo) = c.solve("kinematics", || {
                changed.kinematics(&vec![0.3; g], &vec![2.0; g], &vec![0.0; g])
            }) {
                c.solve("driver_action", || {
                    changed.driver_action(&mo, &loads(&changed, 1e3))
                });
            }
        }
        Err(MechError::Internal(e)) => c
            .found
            .push(Finding::Panic(format!("set_param{}: {e}", c.at))),
        Err(_) => {}
    }
}
