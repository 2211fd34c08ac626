//! The columns of one configuration, named as in `docs/cli.md` (and the Python package):
//! `q` first (`q.<joint>` for several inputs), then `<point>.x`, `<point>.y`, the links'
//! `<link>.angle`, and, as the level asks, velocities and accelerations
//! (`<point>.vx`, `<point>.vy`, `<point>.ax`, `<point>.ay`, `<link>.omega`, `<link>.alpha`),
//! the reactions `<joint>.fx`, `<joint>.fy` (`<joint>.moment` for a prismatic joint), the
//! motor actions by d'Alembert `driver` (`driver.<joint>`) and by virtual power
//! `virtual_power` (`virtual_power.<joint>`), and for one input Zhukovski's `inertia` (I*),
//! `inertia_derivative` (dI*/dq) and `moment` (M*). SI units throughout.

use crate::Failure;
use mech_core::mechanism::Loads;
use mech_core::model::JointKind;
use mech_core::Mechanism;

/// How much of the solution a row holds; nothing beyond it is computed.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, clap::ValueEnum)]
pub enum Level {
    /// Positions only.
    Pose,
    /// Positions, velocities, accelerations.
    Kinematics,
    /// Kinematics, reactions, motor actions (both routes), I* and M*.
    Forces,
}

/// The names and units of a row's columns.
#[derive(Clone, Debug)]
pub struct Columns {
    /// The level computed.
    pub level: Level,
    /// Column names.
    pub names: Vec<String>,
    /// Their SI units.
    pub units: Vec<&'static str>,
}

impl Columns {
    /// The columns of mechanism `m` at `level`.
    pub fn new(m: &Mechanism, level: Level) -> Self {
        let model = m.model();
        let g = m.dof();
        let mut c = Columns { level, names: Vec::new(), units: Vec::new() };
        let input_unit = |k: usize| if model.joints[model.inputs[k]].kind == JointKind::Revolute { ("rad", "N·m") } else { ("m", "N") };
        let per_input = |base: &str, k: usize| if g == 1 { base.to_string() } else { format!("{base}.{}", model.joints[model.inputs[k]].name) };
        for k in 0..g {
            c.push(per_input("q", k), input_unit(k).0);
        }
        for p in &model.points {
            c.push(format!("{}.x", p.name), "m");
            c.push(format!("{}.y", p.name), "m");
        }
        for l in &model.links[1..] {
            c.push(format!("{}.angle", l.name), "rad");
        }
        if level >= Level::Kinematics {
            for p in &model.points {
                for (s, u) in [("vx", "m/s"), ("vy", "m/s"), ("ax", "m/s²"), ("ay", "m/s²")] {
                    c.push(format!("{}.{s}", p.name), u);
                }
            }
            for l in &model.links[1..] {
                c.push(format!("{}.omega", l.name), "rad/s");
                c.push(format!("{}.alpha", l.name), "rad/s²");
            }
        }
        if level == Level::Forces {
            if !m.redundant() {
                for j in &model.joints {
                    c.push(format!("{}.fx", j.name), "N");
                    c.push(format!("{}.fy", j.name), "N");
                    if j.kind == JointKind::Prismatic {
                        c.push(format!("{}.moment", j.name), "N·m");
                    }
                }
                for k in 0..g {
                    c.push(per_input("driver", k), input_unit(k).1);
                }
            }
            for k in 0..g {
                c.push(per_input("virtual_power", k), input_unit(k).1);
            }
            if g == 1 {
                let (m_unit, i_unit, d_unit) = if model.joints[model.inputs[0]].kind == JointKind::Revolute { ("N·m", "kg·m²", "kg·m²/rad") } else { ("N", "kg", "kg/m") };
                c.push("inertia".into(), i_unit);
                c.push("inertia_derivative".into(), d_unit);
                c.push("moment".into(), m_unit);
            }
        }
        c
    }

    fn push(&mut self, name: String, unit: &'static str) {
        self.names.push(name);
        self.units.push(unit);
    }

    /// The row at inputs (q, q̇, q̈) with `loads`, in the order of [`Columns::names`].
    pub fn row(&self, m: &Mechanism, q: &[f64], qd: &[f64], qdd: &[f64], loads: &Loads) -> Result<Vec<f64>, Failure> {
        let mut row = Vec::with_capacity(self.names.len());
        row.extend_from_slice(q);
        if self.level == Level::Pose {
            let p = m.pose(q)?;
            row.extend(p.points.iter().flat_map(|p| [p.pos.x, p.pos.y]));
            row.extend(p.links[1..].iter().map(|l| l.angle));
            return Ok(row);
        }
        let mo = m.kinematics(q, qd, qdd)?;
        row.extend(mo.points.iter().flat_map(|p| [p.pos.x, p.pos.y]));
        row.extend(mo.links[1..].iter().map(|l| l.angle));
        row.extend(mo.points.iter().flat_map(|p| [p.vel.x, p.vel.y, p.acc.x, p.acc.y]));
        row.extend(mo.links[1..].iter().flat_map(|l| [l.omega, l.alpha]));
        if self.level == Level::Forces {
            if !m.redundant() {
                let f = m.kinetostatics(&mo, loads)?;
                for r in &f.joints {
                    row.extend([r.force.x, r.force.y]);
                    row.extend(r.moment);
                }
                row.extend_from_slice(&f.driver);
            }
            row.extend(m.driver_action(&mo, loads)?);
            if m.dof() == 1 {
                let z = mech_core::traits::OneDof::reduced(m, q[0])?;
                row.extend([z.inertia, z.inertia_derivative, mech_core::traits::OneDof::reduced_moment(m, q[0], loads)?]);
            }
        }
        debug_assert_eq!(row.len(), self.names.len());
        Ok(row)
    }
}
