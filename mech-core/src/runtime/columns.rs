//! The columns of one configuration, named as in `docs/cli.md` (the `mech` tool's CSV and
//! JSON, the Python package's dictionaries):
//! `q` first (`q.<joint>` for several inputs), then `<point>.x`, `<point>.y`, the links'
//! `<link>.angle`, and, as the parts ask ([`Part`]), velocities and accelerations
//! (`<point>.vx`, `<point>.vy`, `<point>.ax`, `<point>.ay`, `<link>.omega`, `<link>.alpha`),
//! the reactions `<joint>.fx`, `<joint>.fy` (`<joint>.moment` for a prismatic joint), the
//! motor actions by d'Alembert `driver` (`driver.<joint>`) and by virtual power
//! `virtual_power` (`virtual_power.<joint>`), and for one input Zhukovski's `inertia` (I*),
//! `inertia_derivative` (dI*/dq) and `moment` (M*). SI units throughout.

use super::warm::Warm;
use crate::kernel::link_state::LinkState;
use crate::model::JointKind;
use crate::runtime::mechanism::{Loads, Motion};
use crate::solvers::batch::{each_with, refuse, BatchErrors, Block};
use crate::solvers::traits::OneDof;
use crate::{MechError, Mechanism};

/// A part of the solution, each a group of columns.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Part {
    /// `q` (`q.<joint>`).
    Inputs,
    /// `<point>.x`, `<point>.y`, `<link>.angle`.
    Positions,
    /// `<point>.x`, `<point>.y` alone (no link angle, no `atan2`); implied by `Positions`.
    Points,
    /// `<point>.vx`, `.vy`, `.ax`, `.ay`, `<link>.omega`, `<link>.alpha`.
    Rates,
    /// `<joint>.fx`, `<joint>.fy` (`<joint>.moment`): d'Alembert's reactions.
    Reactions,
    /// `driver` (`driver.<joint>`): the motor actions by d'Alembert.
    Driver,
    /// `virtual_power` (`virtual_power.<joint>`): the motor actions by virtual power.
    VirtualPower,
    /// `inertia`, `inertia_derivative`, `moment`: Zhukovski's I*, dI*/dq, M* (one input).
    Zhukovski,
    /// `shaking.fx`, `shaking.fy` (N), `shaking.moment` (N·m): the shaking force and moment
    /// on the frame ([`crate::solvers::traits::Machine::shaking`]), and with links in
    /// several planes ([`crate::model::Model::has_planes`]) `shaking.mx`, `shaking.my`
    /// (N·m), the couples about the x and y axes; not in [`Part::ALL`].
    Shaking,
}

impl Part {
    /// Positions only.
    pub const POSE: &'static [Part] = &[Part::Inputs, Part::Positions];
    /// Positions, velocities, accelerations.
    pub const KINEMATICS: &'static [Part] = &[Part::Inputs, Part::Positions, Part::Rates];
    /// Everything.
    pub const ALL: &'static [Part] = &[
        Part::Inputs,
        Part::Positions,
        Part::Rates,
        Part::Reactions,
        Part::Driver,
        Part::VirtualPower,
        Part::Zhukovski,
    ];
}

/// Buffers reused from row to row ([`Columns::row_into`]).
#[derive(Debug, Default)]
pub struct RowScratch {
    states: Vec<LinkState>,
    motion: Option<Motion>,
    /// The chunk's last solved configuration: the triads' warm start (`super::warm`).
    warm: Option<Warm>,
}

/// The names and units of a row's columns.
#[derive(Clone, Debug)]
pub struct Columns {
    /// The parts computed.
    pub parts: Vec<Part>,
    /// Column names.
    pub names: Vec<String>,
    /// Their SI units.
    pub units: Vec<&'static str>,
    /// `parts` as bits (1 << part), for [`Columns::has`] at every row.
    mask: u16,
    /// The shaking has the couples about x and y (links in several planes).
    planes: bool,
}

impl Columns {
    /// The columns of mechanism `m` for `parts` (in the order of [`Part`]; a redundant
    /// mechanism has no reactions and no d'Alembert driver, a mechanism with several
    /// inputs no Zhukovski columns).
    pub fn new(m: &Mechanism, parts: &[Part]) -> Self {
        let model = m.model();
        let g = m.dof();
        let has = |p: Part| parts.contains(&p);
        let mut parts: Vec<Part> = Part::ALL
            .iter()
            .copied()
            .chain([Part::Points, Part::Shaking])
            .filter(|&p| has(p))
            .collect();
        if parts.contains(&Part::Positions) {
            parts.retain(|&p| p != Part::Points);
        }
        // A redundant mechanism has no reactions; several inputs have no Zhukovski reduction.
        let dropped = |p: Part| {
            (m.redundant() && matches!(p, Part::Reactions | Part::Driver))
                || (g != 1 && p == Part::Zhukovski)
        };
        parts.retain(|&p| !dropped(p));
        let mask = parts.iter().fold(0u16, |m, &p| m | 1 << p as u16);
        let mut c = Columns {
            parts,
            names: Vec::new(),
            units: Vec::new(),
            mask,
            planes: model.has_planes(),
        };
        let has = |p: Part| c.parts.contains(&p);
        let (inputs, positions, rates, reactions, driver, vp, zhukovski) = (
            has(Part::Inputs),
            has(Part::Positions),
            has(Part::Rates),
            has(Part::Reactions),
            has(Part::Driver),
            has(Part::VirtualPower),
            has(Part::Zhukovski),
        );
        let points = has(Part::Points);
        let shaking = has(Part::Shaking);
        let input_unit = |k: usize| {
            if model.joints[model.inputs[k]].kind == JointKind::Revolute {
                ("rad", "N·m")
            } else {
                ("m", "N")
            }
        };
        let per_input = |base: &str, k: usize| {
            if g == 1 {
                base.to_string()
            } else {
                format!("{base}.{}", model.joints[model.inputs[k]].name)
            }
        };
        if inputs {
            for k in 0..g {
                c.push(per_input("q", k), input_unit(k).0);
            }
        }
        if positions || points {
            for p in &model.points {
                c.push(format!("{}.x", p.name), "m");
                c.push(format!("{}.y", p.name), "m");
            }
        }
        if positions {
            for l in &model.links[1..] {
                c.push(format!("{}.angle", l.name), "rad");
            }
        }
        if rates {
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
        if reactions {
            for j in &model.joints {
                c.push(format!("{}.fx", j.name), "N");
                c.push(format!("{}.fy", j.name), "N");
                if j.kind == JointKind::Prismatic {
                    c.push(format!("{}.moment", j.name), "N·m");
                }
            }
        }
        if driver {
            for k in 0..g {
                c.push(per_input("driver", k), input_unit(k).1);
            }
        }
        if vp {
            for k in 0..g {
                c.push(per_input("virtual_power", k), input_unit(k).1);
            }
        }
        if zhukovski {
            let (m_unit, i_unit, d_unit) =
                if model.joints[model.inputs[0]].kind == JointKind::Revolute {
                    ("N·m", "kg·m²", "kg·m²/rad")
                } else {
                    ("N", "kg", "kg/m")
                };
            c.push("inertia".into(), i_unit);
            c.push("inertia_derivative".into(), d_unit);
            c.push("moment".into(), m_unit);
        }
        if shaking {
            c.push("shaking.fx".into(), "N");
            c.push("shaking.fy".into(), "N");
            c.push("shaking.moment".into(), "N·m");
            if c.planes {
                c.push("shaking.mx".into(), "N·m");
                c.push("shaking.my".into(), "N·m");
            }
        }
        c
    }

    fn push(&mut self, name: String, unit: &'static str) {
        self.names.push(name);
        self.units.push(unit);
    }

    /// True when the columns include `p`.
    pub fn has(&self, p: Part) -> bool {
        self.mask & (1 << p as u16) != 0
    }

    /// The row at inputs (q, q̇, q̈) with `loads`, in the order of [`Columns::names`]:
    /// computes what the parts need and nothing else (positions alone for [`Part::POSE`],
    /// no reaction for the virtual-power driver or Zhukovski's columns).
    pub fn row(
        &self,
        m: &Mechanism,
        q: &[f64],
        qd: &[f64],
        qdd: &[f64],
        loads: &Loads,
    ) -> Result<Vec<f64>, MechError> {
        let mut row = vec![0.0; self.names.len()];
        self.row_into(m, q, qd, qdd, loads, &mut RowScratch::default(), &mut row)?;
        Ok(row)
    }

    /// [`Columns::row`] into `out` (as many values as names), reusing `scratch`: rows of
    /// positions allocate nothing once the scratch has grown (a batch keeps one scratch
    /// per thread).
    #[allow(clippy::too_many_arguments)]
    pub fn row_into(
        &self,
        m: &Mechanism,
        q: &[f64],
        qd: &[f64],
        qdd: &[f64],
        loads: &Loads,
        scratch: &mut RowScratch,
        out: &mut [f64],
    ) -> Result<(), MechError> {
        let needs_motion = self.has(Part::Rates)
            || self.has(Part::Reactions)
            || self.has(Part::Driver)
            || self.has(Part::VirtualPower)
            || self.has(Part::Shaking);
        if !needs_motion && !self.has(Part::Zhukovski) {
            let mut at = 0;
            if self.has(Part::Inputs) {
                out[..q.len()].copy_from_slice(q);
                at = q.len();
            }
            let warm = scratch.warm.get_or_insert_with(|| Warm::new(m));
            let s = &mut scratch.states;
            if self.has(Part::Positions) {
                let n = 2 * m.model().points.len() + m.model().links.len() - 1;
                warm.run(q, |start| {
                    m.positions_from(q, s, &mut out[at..at + n], start)?;
                    Ok(((), &s[..]))
                })?;
            } else if self.has(Part::Points) {
                let n = 2 * m.model().points.len();
                warm.run(q, |start| {
                    m.points_from(q, s, &mut out[at..at + n], start)?;
                    Ok(((), &s[..]))
                })?;
            }
            return Ok(());
        }
        let row = self.full_row(m, q, qd, qdd, loads, scratch)?;
        out.copy_from_slice(&row);
        Ok(())
    }

    /// The rows of many configurations (`docs/batch.md`): configuration i's inputs are
    /// `q[i·G..(i+1)·G]`, its rates `qd[i·G..(i+1)·G]` and `qdd[i·G..(i+1)·G]`, its loads
    /// `loads(i)`; its row goes to `out[i·W..(i+1)·W]` (W = the number of names). One
    /// [`RowScratch`] per chunk; a configuration that fails gets NaN and its index in the
    /// returned [`BatchErrors`]; on rayon's pool from
    /// [`PARALLEL_FROM`](crate::solvers::batch::PARALLEL_FROM) rows on.
    pub fn rows_many<'l>(
        &self,
        m: &Mechanism,
        q: &[f64],
        qd: &[f64],
        qdd: &[f64],
        loads: &(dyn Fn(usize) -> std::borrow::Cow<'l, Loads> + Sync),
        out: &mut [f64],
    ) -> BatchErrors {
        let g = m.dof();
        let n = if g == 0 { 0 } else { q.len() / g };
        let shape = if g == 0 || q.len() % g != 0 || qd.len() != q.len() || qdd.len() != q.len() {
            Err(MechError::InvalidInput(format!(
                "`q` has {} values, `qd` {} and `qdd` {}: give {g} values (the inputs) per configuration in each",
                q.len(),
                qd.len(),
                qdd.len()
            )))
        } else {
            Ok(())
        };
        if shape.is_ok() && self.parts == [Part::Points] {
            // The points alone: the mechanism's own batched form (four configurations at
            // once where its groups have lane kernels).
            return m.points_many(q, out);
        }
        let rows = match shape.and_then(|()| Block::new("out", out, self.names.len(), n)) {
            Ok(r) => r,
            Err(e) => return refuse(e),
        };
        each_with(
            n,
            rows,
            RowScratch::default,
            |i, r: &mut Block<f64>, scratch| {
                let k = i * g..(i + 1) * g;
                let (qi, qdi, qddi) = (&q[k.clone()], &qd[k.clone()], &qdd[k]);
                self.row_into(m, qi, qdi, qddi, &loads(i), scratch, r.row(i))
            },
        )
    }

    /// Every part but positions-only: through the motion (reused from `scratch`).
    fn full_row(
        &self,
        m: &Mechanism,
        q: &[f64],
        qd: &[f64],
        qdd: &[f64],
        loads: &Loads,
        scratch: &mut RowScratch,
    ) -> Result<Vec<f64>, MechError> {
        let mut row = Vec::with_capacity(self.names.len());
        if self.has(Part::Inputs) {
            row.extend_from_slice(q);
        }
        let needs_motion = self.has(Part::Rates)
            || self.has(Part::Reactions)
            || self.has(Part::Driver)
            || self.has(Part::VirtualPower)
            || self.has(Part::Shaking);
        if !needs_motion {
            if self.has(Part::Positions) || self.has(Part::Points) {
                let p = m.pose(q)?;
                row.extend(p.points.iter().flat_map(|p| [p.pos.x, p.pos.y]));
                if self.has(Part::Positions) {
                    row.extend(p.links[1..].iter().map(|l| l.angle));
                }
            }
        } else {
            let warm = scratch.warm.get_or_insert_with(|| Warm::new(m));
            let mo = scratch.motion.get_or_insert_with(|| m.empty_motion());
            warm.run(q, |start| {
                m.kinematics_from(q, qd, qdd, mo, start)?;
                Ok(((), &mo.states[..]))
            })?;
            if self.has(Part::Positions) || self.has(Part::Points) {
                row.extend(mo.points.iter().flat_map(|p| [p.pos.x, p.pos.y]));
                if self.has(Part::Positions) {
                    row.extend(mo.links[1..].iter().map(|l| l.angle));
                }
            }
            if self.has(Part::Rates) {
                row.extend(
                    mo.points
                        .iter()
                        .flat_map(|p| [p.vel.x, p.vel.y, p.acc.x, p.acc.y]),
                );
                row.extend(mo.links[1..].iter().flat_map(|l| [l.omega, l.alpha]));
            }
            if self.has(Part::Reactions) || self.has(Part::Driver) {
                let f = m.kinetostatics(mo, loads)?;
                if self.has(Part::Reactions) {
                    for r in &f.joints {
                        row.extend([r.force.x, r.force.y]);
                        row.extend(r.moment);
                    }
                }
                if self.has(Part::Driver) {
                    row.extend_from_slice(&f.driver);
                }
            }
            if self.has(Part::VirtualPower) {
                row.extend(m.driver_action(mo, loads)?);
            }
        }
        let shaking = scratch
            .motion
            .as_ref()
            .filter(|_| self.has(Part::Shaking))
            .map(|mo| crate::solvers::traits::Machine::shaking(m, mo));
        if self.has(Part::Zhukovski) {
            let z = OneDof::reduced(m, q[0])?;
            row.extend([
                z.inertia,
                z.inertia_derivative,
                OneDof::reduced_moment(m, q[0], loads)?,
            ]);
        }
        if let Some(sh) = shaking {
            row.extend([sh.force.x, sh.force.y, sh.moment]);
            if self.planes {
                row.extend([sh.mx, sh.my]);
            }
        }
        debug_assert_eq!(row.len(), self.names.len());
        Ok(row)
    }
}
