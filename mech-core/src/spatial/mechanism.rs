//! `SpatialMechanism`, a spatial mechanism loaded at run time, its checks and its solvers.

use super::kinematics::{kinematics, Layout, SpatialMotion};
use super::kinetostatics::{kinetostatics, SpatialForces, SpatialLoads};
use super::kutzbach::{self, Kutzbach};
use super::model::{Finding, Site, SpatialModel};
use crate::solvers::friction::JointFriction;
use crate::solvers::zhukovski::Reduced;
use crate::MechError;
use std::sync::Arc;

/// A spatial mechanism (SPEC 3i), checked at load time: Kutzbach's count against the
/// inputs (an idle spin of a link between two spherical joints named and not counted), the
/// constraint Jacobian's rank at the drawing (redundant joints named). Its solvers work in
/// absolute coordinates (`docs/spatial.md`).
#[derive(Clone, Debug)]
pub struct SpatialMechanism {
    layout: Arc<Layout>,
}

impl SpatialMechanism {
    /// Parse the `space` text form and check it ([`SpatialMechanism::from_model`]).
    pub fn from_dsl(text: &str) -> Result<Self, MechError> {
        Self::from_model(super::dsl::parse(text)?)
    }

    /// A mechanism from a [`SpatialModel`]: [`MechError::Invalid`] with every message
    /// (Kutzbach's count, the rank at the drawing, the input kinds) when a check fails.
    pub fn from_model(model: SpatialModel) -> Result<Self, MechError> {
        Self::checked(model).map_err(|found| {
            MechError::Invalid(
                found
                    .into_iter()
                    .map(|f| f.message)
                    .collect::<Vec<_>>()
                    .join("\n"),
            )
        })
    }

    /// [`SpatialMechanism::from_model`] with each finding placed ([`Finding`]): Kutzbach's
    /// count at the inputs (every link and joint involved), an over-constrained sub-chain
    /// found by the (6,6) pebble game at its first moving link (its other links and joints
    /// involved; a set of every link is left out when Kutzbach's count already failed, as it
    /// restates the count), the rank at the drawing at the first joint whose equations
    /// repeat (the others involved; not run when the game found a sub-chain, whose
    /// redundancy it would repeat), an input of the wrong kind at its joint, a degenerate
    /// idle link at the link. With `#[allow(redundant)]` neither Kutzbach's count nor the
    /// game is run, and the rank gives the mobility. The `mechanism!` macro turns the
    /// findings into spanned errors.
    pub fn checked(model: SpatialModel) -> Result<Self, Vec<Finding>> {
        let everything = || -> Vec<Site> {
            (0..model.bodies.len())
                .map(Site::Body)
                .chain((0..model.joints.len()).map(Site::Joint))
                .collect()
        };
        let mut found: Vec<Finding> = (!model.allow_redundant)
            .then(|| kutzbach::check(&model))
            .flatten()
            .map(|message| Finding {
                site: Site::Inputs,
                message,
                involved: everything(),
            })
            .into_iter()
            .collect();
        let mut structural = super::pebble::check(&model);
        if !found.is_empty() {
            let n = model.bodies.len();
            structural.retain(|f| {
                std::iter::once(&f.site)
                    .chain(&f.involved)
                    .filter(|s| matches!(s, Site::Body(_)))
                    .count()
                    < n
            });
        }
        let structural_ok = structural.is_empty();
        found.extend(structural);
        let layout = match Layout::new(model) {
            Ok(layout) => layout,
            Err(more) => {
                found.extend(more);
                return Err(found);
            }
        };
        let rank = if layout.model.allow_redundant {
            super::rank::redundant(&layout).map(|m| (vec![Site::Inputs], m))
        } else if structural_ok {
            super::rank::check(&layout)
        } else {
            None
        };
        if let Some((sites, message)) = rank {
            let mut sites = sites.into_iter();
            found.push(Finding {
                site: sites.next().unwrap_or(Site::Whole),
                message,
                involved: sites.collect(),
            });
        }
        if !found.is_empty() {
            return Err(found);
        }
        Ok(SpatialMechanism {
            layout: Arc::new(layout),
        })
    }

    /// The prepared layout the solvers work on.
    pub(crate) fn layout(&self) -> &Layout {
        &self.layout
    }

    /// `InvalidInput` unless `m` was computed by this mechanism (or a clone of it).
    fn owns(&self, m: &SpatialMotion) -> Result<(), MechError> {
        if Arc::ptr_eq(&self.layout, &m.layout) {
            Ok(())
        } else {
            Err(MechError::InvalidInput(format!(
                "this motion was computed by another mechanism (`{}`), not by `{}`: compute it with this mechanism's `kinematics`",
                m.layout.model.name, self.layout.model.name
            )))
        }
    }

    /// The body the point with index `p` moves with and the point's offset from that
    /// body's reference point (its cg when declared, else its first point) in the drawing, m:
    /// the point is at o + R s.
    pub fn point_anchor(&self, p: usize) -> Option<(usize, nalgebra::Vector3<f64>)> {
        super::results::anchor(&self.layout, p)
    }

    /// The model as loaded.
    pub fn model(&self) -> &SpatialModel {
        &self.layout.model
    }

    /// The rows of the constraint Jacobian: the joints' Σ (6 − class), one per input, one
    /// per idle spin (6(N − 1) unless constraints are redundant).
    pub fn row_count(&self) -> usize {
        self.layout.row_count()
    }

    /// G, the number of inputs.
    pub fn dof(&self) -> usize {
        self.layout.model.inputs.len()
    }

    /// Kutzbach's count of the mechanism, its idle freedoms included.
    pub fn kutzbach(&self) -> Kutzbach {
        kutzbach::count(&self.layout.model)
    }

    /// The names of the links with an idle spin (between two spherical joints).
    pub fn idle_links(&self) -> Vec<&str> {
        self.layout
            .spins
            .iter()
            .map(|&(b, _)| self.layout.model.bodies[b].name.as_str())
            .collect()
    }

    /// The loads, every value zero.
    pub fn loads(&self) -> SpatialLoads {
        let names: Vec<String> = self
            .layout
            .model
            .loads
            .iter()
            .map(|l| l.name.clone())
            .collect();
        SpatialLoads {
            values: vec![Default::default(); names.len()],
            names,
        }
    }

    /// The positions at q (velocities and accelerations zero; no rate is solved for).
    pub fn pose(&self, q: &[f64]) -> Result<SpatialMotion, MechError> {
        super::kinematics::pose(&self.layout, q)
    }

    /// Positions, velocities and accelerations at (q, q̇, q̈) (one value per input each).
    pub fn kinematics(
        &self,
        q: &[f64],
        qd: &[f64],
        qdd: &[f64],
    ) -> Result<SpatialMotion, MechError> {
        kinematics(&self.layout, q, qd, qdd)
    }

    /// Every joint's reaction and every motor action at the motion `m` under `loads`
    /// (Newton–Euler with the full inertia tensor and the gyroscopic term).
    /// [`MechError::Redundant`] for a mechanism accepted with `#[allow(redundant)]`.
    pub fn kinetostatics(
        &self,
        m: &SpatialMotion,
        loads: &SpatialLoads,
    ) -> Result<SpatialForces, MechError> {
        self.owns(m)?;
        if self.layout.model.allow_redundant {
            return Err(indeterminate(&self.layout));
        }
        kinetostatics(&self.layout, m, loads, None)
    }

    /// [`SpatialMechanism::kinetostatics`] with Coulomb friction in the joints
    /// (`friction[j]` for joint j in the order written: μ and the pin or ball radius, m):
    /// Newton–Euler iterated to a fixed point from the frictionless reactions;
    /// `SelfLocking` when no finite motor action moves the mechanism. The laws of each
    /// joint kind are in `docs/spatial.md` ("Friction").
    pub fn kinetostatics_with_friction(
        &self,
        m: &SpatialMotion,
        loads: &SpatialLoads,
        friction: &[JointFriction],
    ) -> Result<SpatialForces, MechError> {
        self.owns(m)?;
        if self.layout.model.allow_redundant {
            return Err(indeterminate(&self.layout));
        }
        kinetostatics(&self.layout, m, loads, Some(friction))
    }

    /// The motor actions by virtual power (N·m or N per input), no reactions computed.
    pub fn driver_action(
        &self,
        m: &SpatialMotion,
        loads: &SpatialLoads,
    ) -> Result<Vec<f64>, MechError> {
        self.owns(m)?;
        let mut out = vec![0.0; m.q.len()];
        super::virtual_power::driver_actions_into(
            &self.layout,
            self.layout.dense(),
            &m.bodies,
            &m.q,
            &loads.values,
            &mut out,
        )?;
        Ok(out)
    }

    /// Zhukovski's I*(q) (kg·m² or kg) and dI*/dq; one input only.
    pub fn reduced(&self, q: f64) -> Result<Reduced, MechError> {
        super::zhukovski::reduced(&self.layout, self.layout.dense(), q)
    }

    /// Zhukovski's M*(q) (N·m or N), loads and gravity; one input only.
    pub fn reduced_moment(&self, q: f64, loads: &SpatialLoads) -> Result<f64, MechError> {
        super::zhukovski::reduced_moment(&self.layout, self.layout.dense(), q, &loads.values)
    }

    /// q̈ = (driver + M* − ½ dI*/dq q̇²) / I* (rad/s² or m/s²); one input only.
    pub fn acceleration(
        &self,
        q: f64,
        qd: f64,
        driver: f64,
        loads: &SpatialLoads,
    ) -> Result<f64, MechError> {
        super::zhukovski::acceleration(
            &self.layout,
            self.layout.dense(),
            q,
            qd,
            driver,
            &loads.values,
        )
    }
}

/// The `Redundant` error of a mechanism accepted with `#[allow(redundant)]` asked for its
/// reactions.
pub(crate) fn indeterminate(layout: &Layout) -> MechError {
    MechError::Redundant(format!(
        "`{}` has redundant constraints (#[allow(redundant)]): its reactions are statically indeterminate; `driver_action` gives the motor actions by virtual power",
        layout.model.name
    ))
}
