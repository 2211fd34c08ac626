//! Spatial kinetostatics by Newton–Euler with the full inertia tensor, and the joints' reactions.
//!
//! For each moving body, at its reference point o (its cg when declared): the inertia
//! wrench (m a_G, I α + ω × (I ω)), I = R I_drawing Rᵀ the tensor turned to the pose, and
//! the applied wrench Q (gravity m g at G, each force F at P with its moment (P − o) × F,
//! each torque). With one multiplier λ_r per constraint row, Newton–Euler of all the bodies
//! is Jᵀ λ = (inertia wrenches) − Q, one square solve. Row r acts on body b with the
//! wrench λ_r (J_r,v_b, J_r,ω_b) about o_b, so a joint's reaction BY a ON b is the sum over
//! its rows, its moment moved to the joint's point P: M_P = M_o − (P − o_b) × F. A driver
//! row's multiplier is the motor action (N·m about the axis, or N along it, by a on b).

use super::constraints::{BodyState, Row};
use super::frame::{Frame, RowBuffer};
use super::kinematics::{BodyMotion, Layout, SpatialMotion};
use super::model::LoadKind;
use crate::solvers::friction::JointFriction;
use crate::MechError;
use nalgebra::Vector3;

type V3 = Vector3<f64>;

/// The values of a spatial mechanism's loads, in the order written: a force (N) or a
/// torque (N·m), a global 3-vector each. Missing values count as zero.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct SpatialLoads {
    /// The loads' names.
    pub names: Vec<String>,
    /// Their values.
    pub values: Vec<V3>,
}

impl SpatialLoads {
    /// Set the load `name` to (x, y, z); false when there is no such load or `v` does not
    /// hold three numbers.
    pub fn set_by_name(&mut self, name: &str, v: &[f64]) -> bool {
        match (self.names.iter().position(|n| n == name), v) {
            (Some(k), [x, y, z]) => {
                if self.values.len() <= k {
                    self.values.resize(k + 1, V3::zeros());
                }
                self.values[k] = V3::new(*x, *y, *z);
                true
            }
            _ => false,
        }
    }
}

/// The reaction at a joint: the force (N) and moment (N·m, about the joint's point at its
/// current position) exerted BY its first link ON its second, global axes.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Reaction {
    /// The force, N.
    pub force: V3,
    /// The moment about the joint's point, N·m.
    pub moment: V3,
}

/// The kinetostatics of a spatial mechanism: every joint's reaction, every motor action,
/// the moment fixing each idle spin.
#[derive(Clone, Debug, PartialEq)]
pub struct SpatialForces {
    pub(crate) names: Vec<String>,
    /// The reaction of each joint, in the order written.
    pub reactions: Vec<Reaction>,
    /// The motor action of each input (N·m about its axis, or N along it, by its first link
    /// on its second).
    pub drivers: Vec<f64>,
    /// The pure moment (N·m) the ground would have to apply to keep each idle link to the
    /// spin convention (`docs/spatial.md`), in the order of
    /// [`crate::spatial::SpatialMechanism::idle_links`]: zero when the link has no inertia
    /// about its own axis (a thin rod) and its loads pass through the axis, which makes the
    /// idle spin truly idle; it does no work.
    pub spin_moments: Vec<V3>,
    pub(crate) idle: Vec<String>,
}

impl SpatialForces {
    /// The reaction at the joint `name`.
    pub fn reaction(&self, name: &str) -> Option<Reaction> {
        self.names
            .iter()
            .position(|n| n == name)
            .map(|k| self.reactions[k])
    }

    /// The moment fixing the spin of the idle link `name` ([`SpatialForces::spin_moments`]).
    pub fn spin_moment(&self, name: &str) -> Option<V3> {
        self.idle
            .iter()
            .position(|n| n == name)
            .map(|k| self.spin_moments[k])
    }

    /// The first input's motor action (N·m or N); 0 without inputs.
    pub fn driver(&self) -> f64 {
        self.drivers.first().copied().unwrap_or(0.0)
    }
}

/// Each body's applied wrench (force, moment about o) minus its inertia wrench, when
/// `inertia`; the applied alone otherwise: Q − (m a_G, I α + ω × I ω). 6(N − 1) values.
/// `loads` in the model's order, a missing one zero.
pub(crate) fn wrenches<F: Frame>(
    layout: &Layout,
    f: F,
    bodies: &[BodyMotion],
    loads: &[V3],
    inertia: bool,
) -> Result<F::Vector, MechError> {
    for v in loads {
        crate::error::check_finite("the loads", v.as_slice())?;
    }
    let model = &layout.model;
    let mut out = f.unknowns();
    let q = out.as_mut();
    let mut add = |b: usize, f: V3, mo: V3| {
        if b > 0 {
            for c in 0..3 {
                q[6 * (b - 1) + c] += f[c];
                q[6 * (b - 1) + 3 + c] += mo[c];
            }
        }
    };
    for (b, body) in model.bodies.iter().enumerate().skip(1) {
        if let Some(g) = model.gravity {
            add(b, g * body.mass, V3::zeros());
        }
        if inertia {
            let bm = &bodies[b];
            let i = bm.inertia(&body.inertia);
            let w = bm.state.w;
            add(b, -bm.a * body.mass, -(i * bm.alpha + w.cross(&(i * w))));
        }
    }
    for (k, load) in model.loads.iter().enumerate() {
        let v = loads.get(k).copied().unwrap_or_default();
        match load.kind {
            LoadKind::Torque { body } => add(body, V3::zeros(), v),
            LoadKind::Force { body, point } => {
                let rho = bodies[body].state.rot * (model.points[point].1 - layout.o0[body]);
                add(body, v, rho.cross(&v));
            }
        }
    }
    Ok(out)
}

/// The bodies' states of `bodies`, in a frame's buffer.
pub(crate) fn states<F: Frame>(layout: &Layout, f: F, bodies: &[BodyMotion]) -> F::States {
    let mut s = f.states(&layout.o0);
    for (st, b) in s.as_mut().iter_mut().zip(bodies) {
        *st = b.state;
    }
    s
}

/// The reaction of joint `k` from its rows' multipliers in `lambda` (module docs): force
/// and moment about the joint's point, by its first body on its second.
fn reaction(layout: &Layout, s: &[BodyState], rows: &[Row], lambda: &[f64], k: usize) -> Reaction {
    let class = |j: &super::model::Joint| 6 - j.kind.class();
    let start: usize = layout.model.joints[..k].iter().map(class).sum();
    let count = class(&layout.model.joints[k]);
    let (mut f, mut mo) = (V3::zeros(), V3::zeros());
    for (row, l) in rows[start..start + count].iter().zip(&lambda[start..]) {
        f += row.b[0] * *l;
        mo += row.b[1] * *l;
    }
    let g = &layout.joints[k];
    let rho = s[g.b].rot * g.sb;
    Reaction {
        force: f,
        moment: mo - rho.cross(&f),
    }
}

/// Where the kinetostatics of a spatial [`Solver`](super::Solver) writes: one reaction per
/// joint, one motor action per input, one moment per idle spin.
#[derive(Debug)]
pub struct ForcesOut<'a> {
    /// Each joint's reaction, in the order written (N, N·m).
    pub reactions: &'a mut [Reaction],
    /// Each input's motor action (N·m or N).
    pub drivers: &'a mut [f64],
    /// Each idle spin's moment (N·m).
    pub spin_moments: &'a mut [V3],
}

/// Newton–Euler of every moving body at the motion (`bodies`, inputs `q`): Jᵀ λ =
/// −(Q − inertia wrenches), then each joint's reaction from its rows' multipliers (module
/// docs) into `reactions`, the drivers' multipliers into `drivers`, the spins' moments into
/// `spin_moments`. With `friction` (one per joint), the joints' Coulomb friction as applied
/// wrenches, iterated to a fixed point (`super::friction`). `InvalidInput` when a buffer's
/// length is not the mechanism's.
pub(crate) fn reactions_into<F: Frame>(
    layout: &Layout,
    f: F,
    bodies: &[BodyMotion],
    q: &[f64],
    loads: &[V3],
    friction: Option<&[JointFriction]>,
    out: ForcesOut<'_>,
) -> Result<(), MechError> {
    let ForcesOut {
        reactions,
        drivers,
        spin_moments,
    } = out;
    let lens = [
        bodies.len(),
        q.len(),
        reactions.len(),
        drivers.len(),
        spin_moments.len(),
    ];
    let want = [
        layout.o0.len(),
        layout.model.inputs.len(),
        layout.joints.len(),
        layout.model.inputs.len(),
        layout.spins.len(),
    ];
    if lens != want {
        return Err(MechError::InvalidInput(format!(
            "the kinetostatics of `{}` takes {want:?} bodies, inputs, reactions, drivers and idle spins; given {lens:?}",
            layout.model.name
        )));
    }
    if let Some(fr) = friction {
        super::friction::check(layout, fr)?;
    }
    let w = wrenches(layout, f, bodies, loads, true)?;
    let s = states(layout, f, bodies);
    let s = s.as_ref();
    let mut rows = f.rows();
    layout.rows_into(s, q, 1.0, &mut rows);
    let mut rhs = f.unknowns();
    for (x, w) in rhs.as_mut().iter_mut().zip(w.as_ref()) {
        *x = -w;
    }
    let j = f.factor(&rows)?;
    let mut lambda = f.solve_transpose(&j, &rhs)?;
    if let Some(fr) = friction {
        lambda = crate::solvers::friction::iterate(lambda, |prev| {
            // the friction is applied: b = −(Q + friction − inertia wrenches)
            let mut e = f.unknowns();
            let reaction = |k| reaction(layout, s, rows.rows(), prev.as_ref(), k);
            super::friction::add_wrenches(layout, s, fr, reaction, e.as_mut());
            let mut b = rhs.clone();
            for (x, e) in b.as_mut().iter_mut().zip(e.as_ref()) {
                *x -= e;
            }
            f.solve_transpose(&j, &b)
        })?;
    }
    let (rows, lambda) = (rows.rows(), lambda.as_ref());
    for (k, out) in reactions.iter_mut().enumerate() {
        *out = reaction(layout, s, rows, lambda, k);
    }
    let r = layout.row_count() - q.len() - layout.spins.len();
    drivers.copy_from_slice(&lambda[r..r + q.len()]);
    let r = r + q.len();
    for ((out, row), l) in spin_moments.iter_mut().zip(&rows[r..]).zip(&lambda[r..]) {
        *out = row.b[1] * *l;
    }
    let finite = reactions
        .iter()
        .all(|x| x.force.iter().chain(x.moment.iter()).all(|v| v.is_finite()))
        && drivers.iter().all(|v| v.is_finite())
        && spin_moments.iter().all(|v| v.iter().all(|x| x.is_finite()));
    if finite {
        Ok(())
    } else {
        Err(crate::error::blame(
            "loads",
            &loads
                .iter()
                .flat_map(|v| v.iter().copied())
                .collect::<Vec<_>>(),
            MechError::Singular {
                condition: f64::INFINITY,
            },
        ))
    }
}

/// [`reactions_into`] on the heap frame, as a [`SpatialForces`].
pub(crate) fn kinetostatics(
    layout: &Layout,
    m: &SpatialMotion,
    loads: &SpatialLoads,
    friction: Option<&[JointFriction]>,
) -> Result<SpatialForces, MechError> {
    let mut out = SpatialForces {
        names: layout.model.joints.iter().map(|j| j.name.clone()).collect(),
        reactions: vec![Reaction::default(); layout.joints.len()],
        drivers: vec![0.0; m.q.len()],
        spin_moments: vec![V3::zeros(); layout.spins.len()],
        idle: layout
            .spins
            .iter()
            .map(|&(b, _)| layout.model.bodies[b].name.clone())
            .collect(),
    };
    reactions_into(
        layout,
        layout.dense(),
        &m.bodies,
        &m.q,
        &loads.values,
        friction,
        ForcesOut {
            reactions: &mut out.reactions,
            drivers: &mut out.drivers,
            spin_moments: &mut out.spin_moments,
        },
    )?;
    Ok(out)
}
