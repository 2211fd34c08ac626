//! One spatial case (a text whose first item is `space`): the spatial loader
//! (`SpatialMechanism::from_dsl`), then every spatial solver and a row of every column on
//! what loads, at the planar cases' inputs ([`crate::exercise::INPUTS`]), and the refusal of
//! non-finite inputs: no panic, no non-finite number inside an `Ok`, no call over a second.

use crate::check::{Numbers, Visitor};
use crate::exercise::{Case, Finding, INPUTS};
use crate::watchdog::Watchdog;
use mech_core::runtime::columns::Part;
use mech_core::runtime::spatial_columns::SpatialColumns;
use mech_core::solvers::traits::OneDof;
use mech_core::spatial::{
    BodyMotion, Reaction, SpatialForces, SpatialLoads, SpatialMechanism, SpatialMotion,
};
use mech_core::{UnitQuaternion, Vector3};

impl Numbers for Vector3<f64> {
    fn visit(&self, v: &mut Visitor) {
        v.field("x", &self.x);
        v.field("y", &self.y);
        v.field("z", &self.z);
    }
}

impl Numbers for UnitQuaternion<f64> {
    fn visit(&self, v: &mut Visitor) {
        v.field("w", &self.w);
        v.field("i", &self.i);
        v.field("j", &self.j);
        v.field("k", &self.k);
    }
}

impl Numbers for BodyMotion {
    fn visit(&self, v: &mut Visitor) {
        v.field("o", &self.state.o);
        v.field("rot", &self.state.rot);
        v.field("v", &self.state.v);
        v.field("w", &self.state.w);
        v.field("a", &self.a);
        v.field("alpha", &self.alpha);
    }
}

impl Numbers for SpatialMotion {
    fn visit(&self, v: &mut Visitor) {
        v.field("q", &self.q);
        v.field("qd", &self.qd);
        v.field("qdd", &self.qdd);
        v.field("bodies", &self.bodies);
    }
}

impl Numbers for Reaction {
    fn visit(&self, v: &mut Visitor) {
        v.field("force", &self.force);
        v.field("moment", &self.moment);
    }
}

impl Numbers for SpatialForces {
    fn visit(&self, v: &mut Visitor) {
        v.field("reactions", &self.reactions);
        v.field("drivers", &self.drivers);
        v.field("spin_moments", &self.spin_moments);
    }
}

/// Every load of `m` of size `size`: (size, −2 size, size / 2), N or N·m.
fn loads(m: &SpatialMechanism, size: f64) -> SpatialLoads {
    let mut l = m.loads();
    for name in l.names.clone() {
        l.set_by_name(&name, &[size, -2.0 * size, 0.5 * size]);
    }
    l
}

/// Load the spatial `text` and call every solver on what loads. The findings, and whether
/// it loaded.
pub fn run(text: &str, dog: &Watchdog) -> (Vec<Finding>, bool) {
    let mut c = Case::new(dog);
    let Some(m) = c.attempt("spatial load", || SpatialMechanism::from_dsl(text)) else {
        return (c.found, false);
    };
    let g = m.dof();
    let columns = SpatialColumns::new(&m, Part::ALL);
    for &(q0, qd0, qdd0, size) in &INPUTS {
        let q: Vec<f64> = (0..g).map(|i| q0 + 0.1 * i as f64).collect();
        let qd: Vec<f64> = (0..g).map(|i| qd0 * (1.0 + i as f64)).collect();
        let qdd: Vec<f64> = (0..g).map(|i| qdd0 * (1.0 - 0.5 * i as f64)).collect();
        c.at = format!(" at q = {q:?}, qd = {qd:?}, qdd = {qdd:?}, loads {size:e}");
        let loads = loads(&m, size);
        c.solve("spatial pose", || m.pose(&q));
        if let Some(mo) = c.solve("spatial kinematics", || m.kinematics(&q, &qd, &qdd)) {
            c.solve("spatial kinetostatics", || m.kinetostatics(&mo, &loads));
            c.solve("spatial driver_action", || m.driver_action(&mo, &loads));
        }
        c.solve("spatial columns row", || {
            columns.row(&m, &q, &qd, &qdd, &loads)
        });
        if g == 1 {
            c.solve("spatial reduced", || OneDof::reduced(&m, q[0]));
            c.solve("spatial reduced_moment", || m.reduced_moment(q[0], &loads));
            c.solve("spatial acceleration", || {
                m.acceleration(q[0], qd[0], 1e3, &loads)
            });
        }
    }
    c.at.clear();
    let zero = vec![0.0; g];
    for bad in [f64::NAN, f64::INFINITY] {
        let mut q = zero.clone();
        if let Some(x) = q.first_mut() {
            *x = bad;
        }
        c.refuse("spatial pose of a non-finite q", || m.pose(&q));
        c.refuse("spatial kinematics of a non-finite q", || {
            m.kinematics(&zero, &q, &zero)
        });
        if g == 1 {
            c.refuse("spatial reduced of a non-finite q", || m.reduced(bad));
            c.refuse("spatial acceleration of a non-finite q̇", || {
                m.acceleration(0.0, bad, 0.0, &m.loads())
            });
        }
    }
    (c.found, true)
}
