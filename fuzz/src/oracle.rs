//! `--oracle`: the same cases through the dense test oracle `mech-oracle`
//! ([`GenericMechanism`], the tests' independent cross-check) instead of the run-time
//! `Mechanism`: its loader, pose, kinematics, kinetostatics, motor actions by virtual
//! power and Zhukovski's I*, M* and q̈, at the inputs of [`crate::exercise`], with the
//! same findings.

use crate::check::{Numbers, Visitor};
use crate::exercise::{Case, Finding, INPUTS};
use crate::watchdog::Watchdog;
use mech_core::model::Load;
use mech_oracle::{GenericForces, GenericLoads, GenericMechanism, GenericMotion, GenericPose};

impl Numbers for GenericPose {
    fn visit(&self, v: &mut Visitor) {
        v.field("links", &self.links);
        v.field("points", &self.points);
        v.field("condition", &self.condition);
    }
}

impl Numbers for GenericMotion {
    fn visit(&self, v: &mut Visitor) {
        v.field("links", &self.links);
        v.field("points", &self.points);
        v.field("q", &self.q);
        v.field("qd", &self.qd);
        v.field("qdd", &self.qdd);
        v.field("condition", &self.condition);
    }
}

impl Numbers for GenericForces {
    fn visit(&self, v: &mut Visitor) {
        v.field("driver", &self.driver);
        v.field("joints", &self.joints);
        v.field("condition", &self.condition);
    }
}

/// Every load of `m` of size `size`: a force (size, −2 size) N, a torque size N·m.
fn loads(m: &GenericMechanism, size: f64) -> GenericLoads {
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

/// Load `text` with the oracle and call each of its solvers at every input of
/// [`INPUTS`], and with a NaN: the findings, and whether it loaded.
pub fn run(text: &str, dog: &Watchdog) -> (Vec<Finding>, bool) {
    let mut c = Case::new(dog);
    let Some(m) = c.attempt("oracle load", || GenericMechanism::parse(text)) else {
        return (c.found, false);
    };
    let g = m.dof();
    for &(q0, qd0, qdd0, size) in &INPUTS {
        let q: Vec<f64> = (0..g).map(|i| q0 + 0.1 * i as f64).collect();
        let qd: Vec<f64> = (0..g).map(|i| qd0 * (1.0 + i as f64)).collect();
        let qdd: Vec<f64> = (0..g).map(|i| qdd0 * (1.0 - 0.5 * i as f64)).collect();
        c.at = format!(" at q = {q:?}, qd = {qd:?}, qdd = {qdd:?}, loads {size:e}");
        let l = loads(&m, size);
        c.solve("oracle pose", || m.pose(&q));
        if let Some(mo) = c.solve("oracle kinematics", || m.kinematics(&q, &qd, &qdd)) {
            c.solve("oracle kinetostatics", || m.kinetostatics(&mo, &l));
            c.solve("oracle driver_action", || m.driver_action(&mo, &l));
        }
        if g == 1 {
            c.solve("oracle reduced", || m.reduced(q[0]));
            c.solve("oracle reduced_moment", || m.reduced_moment(q[0], &l));
            c.solve("oracle acceleration", || {
                m.acceleration(q[0], qd[0], 1e3, &l)
            });
        }
    }
    c.at.clear();
    let nan = vec![f64::NAN; g];
    c.refuse("oracle pose (NaN q)", || m.pose(&nan));
    c.refuse("oracle kinematics (NaN qd)", || {
        m.kinematics(&vec![0.5; g], &nan, &vec![0.0; g])
    });
    if g == 1 {
        c.refuse("oracle acceleration (NaN qd)", || {
            m.acceleration(0.5, f64::NAN, 0.0, &m.loads())
        });
    }
    (c.found, true)
}
