//! [`Mechanism::strength`]: the members' checks over a cycle at a constant input speed,
//! from the kinetostatics at each instant (`strength` has the formulas and the checks).

use super::results::{LoadValue, Loads, Motion};
use super::{Forces, Mechanism};
use crate::error::MechError;
use crate::kernel::link_state::V2;
use crate::model::shape::Material;
use crate::model::{JointKind, Load};
use crate::strength::diagram::Diagram;
use crate::strength::section::Section;
use crate::strength::track::{LinkTrack, PinTrack};
use crate::strength::Strength;

/// The largest number of instants of a strength analysis.
pub(crate) const MAX_STEPS: usize = 1_000_000;

impl Mechanism {
    /// The strength of every member over one period of a one-input machine turning at the
    /// constant input speed `qd` (rad/s; q̈ = 0): `steps` instants q = period·k/steps,
    /// k = 0 … steps − 1, each solved by d'Alembert's kinetostatics with the loads
    /// `loads(q)` and gravity. The members are the links declared by a beam `shape:`
    /// (`bar`, `rod`, `tube`) with a `material:`, and the joints declared with a `pin`
    /// (`strength::track` states every check and its strength).
    ///
    /// Errors: a machine that is not one revolute input, a speed or period that is not
    /// finite (period > 0), steps outside 2 … 10⁶, no member to check, or the
    /// kinematics' and kinetostatics' own errors at some instant.
    pub fn strength(
        &self,
        qd: f64,
        period: f64,
        steps: usize,
        mut loads: impl FnMut(f64) -> Result<Loads, MechError>,
    ) -> Result<Strength, MechError> {
        let model = &self.model;
        let revolute = |j: usize| model.joints[j].kind == JointKind::Revolute;
        if model.inputs.len() != 1 || !revolute(model.inputs[0]) {
            return Err(MechError::InvalidInput(
                "a strength analysis turns one revolute input through its cycle; this machine has another kind of input".into(),
            ));
        }
        if !qd.is_finite()
            || !(period.is_finite() && period > 0.0)
            || !(2..=MAX_STEPS).contains(&steps)
        {
            return Err(MechError::InvalidInput(format!(
                "a strength analysis needs a finite speed, a finite period > 0 and 2 to {MAX_STEPS} steps; got q̇ = {qd} rad/s, period = {period} rad, {steps} steps"
            )));
        }
        let mut links: Vec<(usize, LinkTrack)> = self
            .beams()
            .into_iter()
            .map(|(l, section, material, length)| {
                (
                    l,
                    LinkTrack::new(&model.links[l].name, section, material, length),
                )
            })
            .collect();
        let mut pins: Vec<(usize, PinTrack)> = Vec::new();
        for (j, joint) in model.joints.iter().enumerate() {
            let Some(pin) = joint.pin else { continue };
            let bore = [joint.a, joint.b]
                .iter()
                .filter_map(|&l| model.links[l].body)
                .filter_map(|(shape, m)| {
                    Section::of(&shape).map(|s| (s.bearing_length, m.yield_strength))
                })
                .min_by(|x, y| x.0.total_cmp(&y.0));
            pins.push((j, PinTrack::new(&joint.name, pin, bore)));
        }
        if links.is_empty() && pins.is_empty() {
            return Err(MechError::InvalidInput(
                "no member to check: give a link a `shape: bar(..)`, `rod(..)` or `tube(..)` with a `material:`, or a revolute joint a `pin 12 mm`".into(),
            ));
        }
        let mut driver_peak = 0.0f64;
        for k in 0..steps {
            let q = period * k as f64 / steps as f64;
            let motion = self.kinematics(&[q], &[qd], &[0.0])?;
            let loads = loads(q)?;
            let forces = self.kinetostatics(&motion, &loads)?;
            driver_peak = driver_peak.max(forces.driver[0].abs());
            for (l, track) in &mut links {
                track.add(q, &self.diagram(*l, &motion, &forces, &loads));
            }
            for (j, track) in &mut pins {
                let joint = &model.joints[*j];
                track.add(q, forces.joints[*j].force, motion.links[joint.a].angle);
            }
        }
        let members = links
            .iter()
            .map(|(_, t)| t.finish())
            .chain(pins.iter().map(|(_, t)| t.finish()))
            .collect();
        Ok(Strength {
            members,
            driver_peak,
        })
    }

    /// The diagram (N, V, M along the link) of every link with a beam section at the
    /// instant q (rad) of the input turning at `qd` (rad/s, q̈ = 0) under `loads`: the
    /// instants [`Mechanism::strength`] goes through, one at a time, to draw or inspect.
    pub fn strength_diagrams(
        &self,
        q: f64,
        qd: f64,
        loads: &Loads,
    ) -> Result<Vec<(String, Diagram)>, MechError> {
        let motion = self.kinematics(&[q], &[qd], &[0.0])?;
        let forces = self.kinetostatics(&motion, loads)?;
        Ok(self
            .beams()
            .into_iter()
            .map(|(l, ..)| {
                let name = self.model.links[l].name.clone();
                (name, self.diagram(l, &motion, &forces, loads))
            })
            .collect())
    }

    /// The links the strength analysis treats as beams: declared by a `bar`, `rod` or
    /// `tube` with a material, on at least two points; with their section, material and
    /// the length L (m) between their first two points.
    fn beams(&self) -> Vec<(usize, Section, Material, f64)> {
        let model = &self.model;
        let mut out = Vec::new();
        for (l, link) in model.links.iter().enumerate().skip(1) {
            let Some((shape, material)) = link.body else {
                continue;
            };
            let (Some(section), [p, q, ..]) = (Section::of(&shape), link.points.as_slice()) else {
                continue;
            };
            let d = V2::from(model.points[*q].pos) - V2::from(model.points[*p].pos);
            out.push((l, section, material, d.norm()));
        }
        out
    }

    /// Every action on link `l` at one instant: the joints' reactions (and the motor's
    /// torque on the input), the loads, the force elements, its weight and inertia.
    fn diagram(&self, l: usize, m: &Motion, f: &Forces, loads: &Loads) -> Diagram {
        let model = &self.model;
        let link = &model.links[l];
        let at = |p: usize| m.points[p].pos;
        let mut d = Diagram::new(at(link.points[0]), at(link.points[1]));
        for (j, joint) in model.joints.iter().enumerate() {
            let sign = match (joint.a == l, joint.b == l) {
                (false, true) => 1.0,
                (true, false) => -1.0,
                _ => continue,
            };
            let r = &f.joints[j];
            d.add(
                at(joint.point),
                r.force * sign,
                r.moment.unwrap_or(0.0) * sign,
            );
            if let Some(i) = model.inputs.iter().position(|&k| k == j) {
                d.add(at(joint.point), V2::zeros(), f.driver[i] * sign);
            }
        }
        for (load, value) in model.loads.iter().zip(&loads.values) {
            match (load, *value) {
                (&Load::Force { link, point, .. }, LoadValue::Force(v)) if link == l => {
                    d.add(at(point), v, 0.0)
                }
                (load, LoadValue::Torque(t)) if load.link() == l => {
                    d.add(at(link.points[0]), V2::zeros(), t)
                }
                _ => {}
            }
        }
        for el in &self.inst.elements {
            if el.a != l && el.b != l {
                continue;
            }
            let st = el.stretch(&m.states);
            let t = el.tension(&st, st.rate);
            let s = &m.states;
            if el.rotary {
                let c = if el.b == l { -t } else { t };
                d.add(at(link.points[0]), V2::zeros(), c);
            } else if el.b == l {
                d.add(s[l].pos + st.rb, -st.e * t, 0.0);
            } else {
                d.add(s[l].pos + st.ra, st.e * t, 0.0);
            }
        }
        let (geom, lm) = (&self.inst.links[l], &m.links[l]);
        if geom.mass != 0.0 || geom.inertia != 0.0 {
            d.add_body(
                geom.mass,
                geom.inertia,
                lm.cg,
                lm.omega,
                lm.alpha,
                lm.cg_acc,
                self.inst.gravity,
            );
        }
        d
    }
}
