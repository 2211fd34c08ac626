//! Every number of every result: [`Numbers`] walks each result type field by field (each
//! struct destructured, so that a field added to a result and not checked here fails to
//! compile where the struct has no private fields), and [`first_non_finite`] names the
//! first number that is not finite, with its path (`links[2].cg_acc.x = inf`).

use mech_core::dynamics::flywheel::{
    Approximate, CyclePoint, CycleSimulation, Extreme, Fluctuation, Flywheel, SpeedRange,
    SteadyState, Tangent, Wittenbauer,
};
use mech_core::dynamics::ode::Outcome;
use mech_core::dynamics::EnergyPoint;
use mech_core::elements::cam::{Contact, ProfileCheck, ProfilePoint};
use mech_core::kernel::link_state::{LinkMotion, LinkPose, PointMotion, PointPose, V2};
use mech_core::runtime::{Forces, JointReaction, Motion, Pose};
use mech_core::solvers::zhukovski::Reduced;

/// One step of the path to a number.
enum Step {
    Field(&'static str),
    Index(usize),
}

/// Walks a result, remembering where it is, and keeps the first non-finite number.
#[derive(Default)]
pub struct Visitor {
    path: Vec<Step>,
    /// The first non-finite number met: its path and value.
    pub bad: Option<String>,
}

impl Visitor {
    /// A number at the current path.
    pub fn leaf(&mut self, x: f64) {
        if !x.is_finite() && self.bad.is_none() {
            let mut p = String::new();
            for s in &self.path {
                match s {
                    Step::Field(f) if p.is_empty() => p.push_str(f),
                    Step::Field(f) => {
                        p.push('.');
                        p.push_str(f);
                    }
                    Step::Index(i) => p.push_str(&format!("[{i}]")),
                }
            }
            self.bad = Some(format!("{p} = {x}"));
        }
    }

    /// The field `name` of the value being walked.
    pub fn field<T: Numbers + ?Sized>(&mut self, name: &'static str, t: &T) {
        self.path.push(Step::Field(name));
        t.visit(self);
        self.path.pop();
    }
}

/// A result whose numbers can be walked.
pub trait Numbers {
    /// Visit every number of `self` ([`Visitor::leaf`]), each under its field's name.
    fn visit(&self, v: &mut Visitor);
}

/// The first non-finite number of `t`, named by its path; `None` when all are finite.
pub fn first_non_finite<T: Numbers + ?Sized>(t: &T) -> Option<String> {
    let mut v = Visitor::default();
    t.visit(&mut v);
    v.bad
}

impl Numbers for f64 {
    fn visit(&self, v: &mut Visitor) {
        v.leaf(*self);
    }
}

impl<T: Numbers> Numbers for [T] {
    fn visit(&self, v: &mut Visitor) {
        for (i, x) in self.iter().enumerate() {
            v.path.push(Step::Index(i));
            x.visit(v);
            v.path.pop();
        }
    }
}

impl<T: Numbers> Numbers for Vec<T> {
    fn visit(&self, v: &mut Visitor) {
        self.as_slice().visit(v);
    }
}

impl<T: Numbers, const N: usize> Numbers for [T; N] {
    fn visit(&self, v: &mut Visitor) {
        self.as_slice().visit(v);
    }
}

impl<T: Numbers> Numbers for Option<T> {
    fn visit(&self, v: &mut Visitor) {
        if let Some(x) = self {
            x.visit(v);
        }
    }
}

impl<A: Numbers, B: Numbers> Numbers for (A, B) {
    fn visit(&self, v: &mut Visitor) {
        v.field("0", &self.0);
        v.field("1", &self.1);
    }
}

impl<A: Numbers, B: Numbers, C: Numbers> Numbers for (A, B, C) {
    fn visit(&self, v: &mut Visitor) {
        v.field("0", &self.0);
        v.field("1", &self.1);
        v.field("2", &self.2);
    }
}

impl Numbers for V2 {
    fn visit(&self, v: &mut Visitor) {
        v.field("x", &self.x);
        v.field("y", &self.y);
    }
}

impl Numbers for LinkPose {
    fn visit(&self, v: &mut Visitor) {
        let LinkPose { angle, cg } = self;
        v.field("angle", angle);
        v.field("cg", cg);
    }
}

impl Numbers for PointPose {
    fn visit(&self, v: &mut Visitor) {
        let PointPose { pos } = self;
        v.field("pos", pos);
    }
}

impl Numbers for LinkMotion {
    fn visit(&self, v: &mut Visitor) {
        let LinkMotion {
            angle,
            omega,
            alpha,
            cg,
            cg_vel,
            cg_acc,
        } = self;
        v.field("angle", angle);
        v.field("omega", omega);
        v.field("alpha", alpha);
        v.field("cg", cg);
        v.field("cg_vel", cg_vel);
        v.field("cg_acc", cg_acc);
    }
}

impl Numbers for PointMotion {
    fn visit(&self, v: &mut Visitor) {
        let PointMotion { pos, vel, acc } = self;
        v.field("pos", pos);
        v.field("vel", vel);
        v.field("acc", acc);
    }
}

impl Numbers for Pose {
    fn visit(&self, v: &mut Visitor) {
        v.field("links", &self.links);
        v.field("points", &self.points);
    }
}

impl Numbers for Motion {
    fn visit(&self, v: &mut Visitor) {
        v.field("links", &self.links);
        v.field("points", &self.points);
        v.field("q", self.q());
        v.field("qd", self.qd());
        v.field("qdd", self.qdd());
    }
}

impl Numbers for JointReaction {
    fn visit(&self, v: &mut Visitor) {
        let JointReaction { force, moment } = self;
        v.field("force", force);
        v.field("moment", moment);
    }
}

impl Numbers for Forces {
    fn visit(&self, v: &mut Visitor) {
        v.field("driver", &self.driver);
        v.field("joints", &self.joints);
    }
}

impl Numbers for Reduced {
    fn visit(&self, v: &mut Visitor) {
        let Reduced {
            inertia,
            inertia_derivative,
        } = self;
        v.field("inertia", inertia);
        v.field("inertia_derivative", inertia_derivative);
    }
}

impl Numbers for CyclePoint {
    fn visit(&self, v: &mut Visitor) {
        let CyclePoint {
            q,
            moment,
            inertia,
            inertia_derivative,
            work,
        } = self;
        v.field("q", q);
        v.field("moment", moment);
        v.field("inertia", inertia);
        v.field("inertia_derivative", inertia_derivative);
        v.field("work", work);
    }
}

impl Numbers for Extreme {
    fn visit(&self, v: &mut Visitor) {
        let Extreme {
            q,
            work,
            inertia,
            value,
        } = self;
        v.field("q", q);
        v.field("work", work);
        v.field("inertia", inertia);
        v.field("value", value);
    }
}

impl Numbers for Fluctuation {
    fn visit(&self, v: &mut Visitor) {
        let Fluctuation {
            energy,
            s_max,
            q_s_max,
            s_min,
            q_s_min,
        } = self;
        v.field("energy", energy);
        v.field("s_max", s_max);
        v.field("q_s_max", q_s_max);
        v.field("s_min", s_min);
        v.field("q_s_min", q_s_min);
    }
}

impl Numbers for Tangent {
    fn visit(&self, v: &mut Visitor) {
        let Tangent {
            slope,
            intercept,
            q,
            reduced_inertia,
            f,
        } = self;
        v.field("slope", slope);
        v.field("intercept", intercept);
        v.field("q", q);
        v.field("reduced_inertia", reduced_inertia);
        v.field("f", f);
    }
}

impl Numbers for SpeedRange {
    fn visit(&self, v: &mut Visitor) {
        let SpeedRange {
            omega_max,
            q_max,
            omega_min,
            q_min,
            omega_mean,
            irregularity,
        } = self;
        v.field("omega_max", omega_max);
        v.field("q_max", q_max);
        v.field("omega_min", omega_min);
        v.field("q_min", q_min);
        v.field("omega_mean", omega_mean);
        v.field("irregularity", irregularity);
    }
}

impl Numbers for SteadyState {
    fn visit(&self, v: &mut Visitor) {
        let SteadyState {
            flywheel,
            energy,
            speeds,
        } = self;
        v.field("flywheel", flywheel);
        v.field("energy", energy);
        v.field("speeds", speeds);
    }
}

impl Numbers for Wittenbauer {
    fn visit(&self, v: &mut Visitor) {
        let Wittenbauer {
            inertia,
            c,
            upper,
            lower,
            state,
        } = self;
        v.field("inertia", inertia);
        v.field("c", c);
        v.field("upper", upper);
        v.field("lower", lower);
        v.field("state", state);
    }
}

impl Numbers for Approximate {
    fn visit(&self, v: &mut Visitor) {
        let Approximate {
            inertia,
            s_max,
            q_s_max,
            s_min,
            q_s_min,
        } = self;
        v.field("inertia", inertia);
        v.field("s_max", s_max);
        v.field("q_s_max", q_s_max);
        v.field("s_min", s_min);
        v.field("q_s_min", q_s_min);
    }
}

impl Numbers for Flywheel {
    fn visit(&self, v: &mut Visitor) {
        let Flywheel {
            omega_mean,
            irregularity,
            exact,
            approximate,
        } = self;
        v.field("omega_mean", omega_mean);
        v.field("irregularity", irregularity);
        v.field("exact", exact);
        v.field("approximate", approximate);
    }
}

impl Numbers for CycleSimulation {
    fn visit(&self, v: &mut Visitor) {
        // `stats` counts steps and evaluations (integers).
        let CycleSimulation {
            speeds,
            omega_start,
            omega_end,
            duration,
            stats: _,
        } = self;
        v.field("speeds", speeds);
        v.field("omega_start", omega_start);
        v.field("omega_end", omega_end);
        v.field("duration", duration);
    }
}

impl Numbers for EnergyPoint {
    fn visit(&self, v: &mut Visitor) {
        let EnergyPoint { q, omega, t, work } = self;
        v.field("q", q);
        v.field("omega", omega);
        v.field("t", t);
        v.field("work", work);
    }
}

impl<const N: usize> Numbers for Outcome<N> {
    fn visit(&self, v: &mut Visitor) {
        // `event` is a flag, `stats` integers.
        let Outcome {
            t,
            y,
            event: _,
            stats: _,
        } = self;
        v.field("t", t);
        v.field("y", y);
    }
}

impl Numbers for ProfilePoint {
    fn visit(&self, v: &mut Visitor) {
        let ProfilePoint {
            theta,
            pitch,
            contact,
            pressure_angle,
            curvature_radius,
        } = self;
        v.field("theta", theta);
        v.field("pitch", pitch);
        v.field("contact", contact);
        v.field("pressure_angle", pressure_angle);
        v.field("curvature_radius", curvature_radius);
    }
}

impl Numbers for Contact {
    fn visit(&self, v: &mut Visitor) {
        let Contact {
            law,
            pitch,
            contact,
            normal,
            pressure_angle,
            curvature_radius,
        } = self;
        v.field("law", law);
        v.field("pitch", pitch);
        v.field("contact", contact);
        v.field("normal", normal);
        v.field("pressure_angle", pressure_angle);
        v.field("curvature_radius", curvature_radius);
    }
}

impl Numbers for ProfileCheck {
    fn visit(&self, v: &mut Visitor) {
        // `undercut` is a flag. The smallest convex radius is +∞ by definition when the
        // surface is nowhere convex (its documentation): only its other values are checked.
        let ProfileCheck {
            max_pressure_angle,
            min_convex_radius,
            undercut: _,
            missing,
        } = self;
        v.field("max_pressure_angle", max_pressure_angle);
        if min_convex_radius.0 != f64::INFINITY {
            v.field("min_convex_radius", min_convex_radius);
        }
        v.field("missing", missing);
    }
}
