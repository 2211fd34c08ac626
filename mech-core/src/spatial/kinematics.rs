//! Spatial kinematics by Newton on the loop equations from the drawing, rates by linear solves.
//!
//! The unknowns are the moving bodies' twists (v, ω) at their reference points, 6 per
//! body; the rows are the joints' (`constraints::joint_rows`), one per input (the driver)
//! and one per idle freedom (`constraints::spin`), 6(N − 1) in all when Kutzbach's count
//! holds. Positions: Newton, o += δv, R ← exp(δω) R, continued from the drawing to q in
//! steps of at most 0.25 rad (or a tenth of the drawing's size for a sliding input), so the
//! result depends on q alone and stays on the drawing's assembly. Velocities: J ẋ = q̇ on
//! the driver rows, 0 elsewhere; accelerations: J ẍ = q̈ − γ. A mechanism that is one
//! closed group (RSSR, RSSP, RSRC, the spherical four-bar: `closed`) takes its positions
//! from the closed form instead, on the same assembly; an RSSR or RSSP its rates too
//! (`Closed::motions`), the others the same linear solves.

use super::closed::Closed;
use super::constraints::{self, BodyState, JointGeom, Kind, Row};
use super::frame::{Dense, Frame, RowBuffer};
use super::model::{Finding, JointKind, Site, SpatialModel};
use crate::MechError;
use nalgebra::{DMatrix, DVector, Matrix3, UnitQuaternion, Vector3};
use std::cell::Cell;
use std::sync::Arc;

type V3 = Vector3<f64>;

/// A spatial mechanism prepared for solving: the model, each body's reference point, each
/// joint's geometry in its bodies, the idle links' axes.
#[derive(Clone, Debug)]
pub(crate) struct Layout {
    pub model: SpatialModel,
    /// Each body's reference point in the drawing: its cg when declared, else its first
    /// point, else the origin (the ground's is the origin).
    pub o0: Vec<V3>,
    pub joints: Vec<JointGeom>,
    /// (body, its axis from one spherical centre to the other in the drawing, unit).
    pub spins: Vec<(usize, V3)>,
    /// The drawing's size (m): the largest distance of a point from the origin, at least 1e-3.
    pub scale: f64,
    /// The closed group the whole mechanism is, when it is one (`closed`): its positions
    /// then come from the closed form, not from Newton.
    pub closed: Option<Closed>,
}

impl Layout {
    /// Prepare `model` (checked for the input kinds and a degenerate idle link: each
    /// finding at its joint or link).
    pub fn new(model: SpatialModel) -> Result<Self, Vec<Finding>> {
        let o0: Vec<V3> = model
            .bodies
            .iter()
            .enumerate()
            .map(|(i, b)| match (i, b.cg, b.points.first()) {
                (0, _, _) => V3::zeros(),
                (_, Some(g), _) => g,
                (_, None, Some(&p)) => model.points[p].1,
                _ => V3::zeros(),
            })
            .collect();
        let joints = model
            .joints
            .iter()
            .map(|j| {
                let p = model.points[j.point].1;
                let (u, kind, pitch, second) = match j.kind {
                    JointKind::Spherical => (V3::z(), Kind::Spherical, 0.0, None),
                    JointKind::Revolute { axis } => (axis, Kind::Revolute, 0.0, None),
                    JointKind::Universal { first, second } => {
                        (first, Kind::Universal, 0.0, Some(second))
                    }
                    JointKind::Cylindrical { axis } => (axis, Kind::Cylindrical, 0.0, None),
                    JointKind::Prismatic { axis } => (axis, Kind::Prismatic, 0.0, None),
                    JointKind::Helical { axis, pitch } => (axis, Kind::Helical, pitch, None),
                };
                let (n1, n2) = match second {
                    Some(s) => (s, u.cross(&s)),
                    None => constraints::basis(u),
                };
                JointGeom {
                    a: j.a,
                    b: j.b,
                    sa: p - o0[j.a],
                    sb: p - o0[j.b],
                    axes: [u, n1, n2],
                    kind,
                    pitch,
                }
            })
            .collect();
        let mut errors = Vec::new();
        for &k in &model.inputs {
            let j = &model.joints[k];
            if !matches!(
                j.kind,
                JointKind::Revolute { .. }
                    | JointKind::Prismatic { .. }
                    | JointKind::Helical { .. }
            ) {
                errors.push(Finding {
                    site: Site::Joint(k),
                    message: format!("input `{}` is a {} joint, which leaves more than one freedom: an input is a revolute, prismatic or helical joint", j.name, j.kind.word()),
                    involved: Vec::new(),
                });
            }
        }
        let mut spins = Vec::new();
        for (b, j1, j2) in super::kutzbach::idle_freedoms(&model) {
            let e = model.points[model.joints[j2].point].1 - model.points[model.joints[j1].point].1;
            if !(e.norm() > 0.0) {
                errors.push(Finding {
                    site: Site::Body(b),
                    message: format!("link `{}` has its two spherical joints at one point: it can turn freely about it; give its joints distinct points", model.bodies[b].name),
                    involved: Vec::new(),
                });
                continue;
            }
            spins.push((b, e.normalize()));
        }
        if !errors.is_empty() {
            return Err(errors);
        }
        let scale = model
            .points
            .iter()
            .map(|(_, p)| p.norm())
            .fold(1e-3, f64::max);
        let closed = Closed::recognise(&model, &o0);
        Ok(Layout {
            model,
            o0,
            joints,
            spins,
            scale,
            closed,
        })
    }

    /// The moving bodies (N − 1).
    pub fn moving(&self) -> usize {
        self.o0.len() - 1
    }

    /// The rows of J: the joints' Σ (6 − class), one per input, one per idle spin.
    pub fn row_count(&self) -> usize {
        let joints: usize = self.model.joints.iter().map(|j| 6 - j.kind.class()).sum();
        joints + self.model.inputs.len() + self.spins.len()
    }

    /// The heap frame of this mechanism (the run-time solvers').
    pub fn dense(&self) -> Dense {
        Dense {
            bodies: self.o0.len(),
            rows: self.row_count(),
        }
    }

    /// Every row at `states` and input values `frac · q`, appended to `out` with each
    /// row's two bodies: the joints' (in order), the drivers', the spins'.
    pub fn rows_into(&self, s: &[BodyState], q: &[f64], frac: f64, out: &mut impl RowBuffer) {
        for g in &self.joints {
            constraints::joint_rows(g, &s[g.a], &s[g.b], &mut Owned(&mut *out, (g.a, g.b)));
        }
        for (&k, &qk) in self.model.inputs.iter().zip(q) {
            let g = &self.joints[k];
            out.push(
                constraints::driver_row(g, &s[g.a], &s[g.b], qk * frac),
                (g.a, g.b),
            );
        }
        for &(b, e) in &self.spins {
            out.push(constraints::spin(&s[b], e), (0, b));
        }
    }

    /// Every row at `states` and input values `q` ([`Layout::rows_into`]), on the heap.
    pub fn rows(&self, s: &[BodyState], q: &[f64]) -> (Vec<Row>, Vec<(usize, usize)>) {
        let mut out = self.dense().rows();
        self.rows_into(s, q, 1.0, &mut out);
        out
    }

    /// The Jacobian (rows × 6(N − 1)), body i's (v, ω) in columns 6(i − 1)..6i.
    pub fn jacobian(&self, rows: &[Row], owners: &[(usize, usize)]) -> DMatrix<f64> {
        let mut j = DMatrix::zeros(rows.len(), 6 * self.moving());
        super::frame::assemble(rows, owners, |r, c, v| j[(r, c)] += v);
        j
    }

    /// Positions at `q` into `s` (one state per body): the closed form when the mechanism
    /// is a closed group (unless `newton_only` asks otherwise), else Newton continued from
    /// the drawing.
    pub fn positions_into<F: Frame>(
        &self,
        f: F,
        q: &[f64],
        s: &mut [BodyState],
    ) -> Result<(), MechError> {
        let steps = self.steps(q)?;
        if let (Some(c), [q], 4) = (&self.closed, q, s.len()) {
            if !NEWTON_ONLY.with(|n| n.get()) {
                s.copy_from_slice(&c.positions(*q)?);
                return Ok(());
            }
        }
        for (st, &o) in s.iter_mut().zip(&self.o0) {
            *st = BodyState::drawing(o);
        }
        let mut rows = f.rows();
        for i in 1..=steps {
            self.newton(f, s, q, i as f64 / steps as f64, &mut rows)?;
        }
        Ok(())
    }

    /// The continuation steps from the drawing to `q` (0.25 rad, or a tenth of the
    /// drawing's size for a sliding input, each); `InvalidInput` beyond `MAX_STEPS` (the
    /// closed forms refuse the same q, so both paths answer the same inputs).
    fn steps(&self, q: &[f64]) -> Result<usize, MechError> {
        let step = |k: usize| match self.model.joints[self.model.inputs[k]].kind {
            JointKind::Prismatic { .. } => 0.1 * self.scale,
            _ => 0.25,
        };
        let steps = (0..q.len())
            .map(|k| (q[k].abs() / step(k)).ceil())
            .fold(1.0, f64::max);
        if !(steps <= MAX_STEPS) {
            return Err(MechError::InvalidInput(format!(
                "q = {q:?} is more than {MAX_STEPS} continuation steps from the drawing (0.25 rad, or a tenth of the drawing's size, each): give q within about {:.0} turns of the drawing",
                MAX_STEPS * 0.25 / (2.0 * std::f64::consts::PI)
            )));
        }
        Ok(steps as usize)
    }

    /// Newton on the rows at input values `frac · q`, from `s`: o += δv, R ← exp(δω) R.
    fn newton<F: Frame>(
        &self,
        f: F,
        s: &mut [BodyState],
        q: &[f64],
        frac: f64,
        rows: &mut F::Rows,
    ) -> Result<(), MechError> {
        let tol = 1e-15 * (1.0 + self.scale);
        let mut last = f64::INFINITY;
        for it in 0..60 {
            rows.clear();
            self.rows_into(s, q, frac, rows);
            let r = residual(rows.rows());
            if r <= tol || (it > 4 && r >= 0.5 * last) {
                break;
            }
            last = r;
            let mut rhs = f.rhs();
            for (x, row) in rhs.as_mut().iter_mut().zip(rows.rows()) {
                *x = -row.value;
            }
            let dx = f.solve(&f.factor(rows)?, &rhs)?;
            let dx = dx.as_ref();
            for (b, st) in s.iter_mut().enumerate().skip(1) {
                let c = 6 * (b - 1);
                st.o += V3::from_column_slice(&dx[c..c + 3]);
                st.rot = UnitQuaternion::from_scaled_axis(V3::from_column_slice(&dx[c + 3..c + 6]))
                    * st.rot;
            }
        }
        rows.clear();
        self.rows_into(s, q, frac, rows);
        let r = residual(rows.rows());
        if !(r <= 1e-9 * (1.0 + self.scale)) {
            return Err(MechError::NoAssembly);
        }
        Ok(())
    }

    /// `InvalidInput` unless q, q̇, q̈ hold one value per input each and `out` one motion
    /// per body; `InvalidInput` naming the first that is not finite.
    fn check_inputs(
        &self,
        q: &[f64],
        qd: &[f64],
        qdd: &[f64],
        out: usize,
    ) -> Result<(), MechError> {
        let g = self.model.inputs.len();
        if q.len() != g || qd.len() != g || qdd.len() != g {
            return Err(MechError::InvalidInput(format!(
                "q, q̇ and q̈ must each have {g} value(s) (one per input), got {}, {} and {}",
                q.len(),
                qd.len(),
                qdd.len()
            )));
        }
        bodies_len(self, out)?;
        crate::error::check_finite("q", q)?;
        crate::error::check_finite("q̇", qd)?;
        crate::error::check_finite("q̈", qdd)
    }

    /// Positions alone at q into `out` (one motion per body, every rate zero; no linear
    /// solve).
    pub fn pose_into<F: Frame>(
        &self,
        f: F,
        q: &[f64],
        out: &mut [BodyMotion],
    ) -> Result<(), MechError> {
        let g = self.model.inputs.len();
        if q.len() != g {
            return Err(MechError::InvalidInput(format!(
                "q must have {g} value(s) (one per input), got {}",
                q.len()
            )));
        }
        bodies_len(self, out.len())?;
        crate::error::check_finite("q", q)?;
        let mut s = f.states(&self.o0);
        self.positions_into(f, q, s.as_mut())?;
        for (m, &state) in out.iter_mut().zip(s.as_ref()) {
            *m = BodyMotion {
                state,
                ..BodyMotion::rest()
            };
        }
        Ok(())
    }

    /// Kinematics at (q, q̇, q̈) into `out`: an RSSR or RSSP entirely from its kernel
    /// (`Closed::motions`: no linear solve); otherwise positions
    /// ([`Layout::positions_into`]), then J ẋ = (q̇ on the driver rows) and
    /// J ẍ = (q̈ on the driver rows) − γ, J factored once.
    pub fn kinematics_into<F: Frame>(
        &self,
        f: F,
        q: &[f64],
        qd: &[f64],
        qdd: &[f64],
        out: &mut [BodyMotion],
    ) -> Result<(), MechError> {
        self.check_inputs(q, qd, qdd, out.len())?;
        if let (Some(c), [q1], [qd1], [qdd1], [(_, e)]) =
            (&self.closed, q, qd, qdd, &self.spins[..])
        {
            if !NEWTON_ONLY.with(|n| n.get()) {
                self.steps(q)?;
                if let Some(done) = c.motions(*q1, *qd1, *qdd1, *e, out) {
                    return done;
                }
            }
        }
        let mut states = f.states(&self.o0);
        let s = states.as_mut();
        self.positions_into(f, q, s)?;
        let mut rows = f.rows();
        self.rows_into(s, q, 1.0, &mut rows);
        let first_driver = rows.rows().len() - q.len() - self.spins.len();
        let j = f.factor(&rows)?;
        let mut b = f.rhs();
        b.as_mut()[first_driver..first_driver + q.len()].copy_from_slice(qd);
        let xd = f.solve(&j, &b)?;
        for (k, st) in s.iter_mut().enumerate().skip(1) {
            let c = 6 * (k - 1);
            st.v = V3::from_column_slice(&xd.as_ref()[c..c + 3]);
            st.w = V3::from_column_slice(&xd.as_ref()[c + 3..c + 6]);
        }
        rows.clear();
        self.rows_into(s, q, 1.0, &mut rows);
        let mut b = f.rhs();
        for (x, row) in b.as_mut().iter_mut().zip(rows.rows()) {
            *x = -row.gamma;
        }
        for (x, v) in b.as_mut()[first_driver..].iter_mut().zip(qdd) {
            *x += v;
        }
        let xdd = f.solve(&j, &b)?;
        for (k, (m, &state)) in out.iter_mut().zip(s.iter()).enumerate() {
            *m = match k {
                0 => BodyMotion {
                    state,
                    ..BodyMotion::rest()
                },
                _ => {
                    let c = 6 * (k - 1);
                    BodyMotion {
                        state,
                        a: V3::from_column_slice(&xdd.as_ref()[c..c + 3]),
                        alpha: V3::from_column_slice(&xdd.as_ref()[c + 3..c + 6]),
                    }
                }
            };
        }
        Ok(())
    }
}

/// `InvalidInput` unless `n` is the layout's body count.
fn bodies_len(layout: &Layout, n: usize) -> Result<(), MechError> {
    if n == layout.o0.len() {
        Ok(())
    } else {
        Err(MechError::InvalidInput(format!(
            "`{}` has {} bodies (the ground included); a buffer of {n} motions was given",
            layout.model.name,
            layout.o0.len()
        )))
    }
}

/// A row buffer that appends every row with one owner (a joint's rows).
struct Owned<'a, B>(&'a mut B, (usize, usize));

impl<B: RowBuffer> Extend<Row> for Owned<'_, B> {
    fn extend<I: IntoIterator<Item = Row>>(&mut self, rows: I) {
        for r in rows {
            self.0.push(r, self.1);
        }
    }
}

thread_local! {
    /// Set by `newton_only`: this thread's positions by Newton even for a closed group.
    static NEWTON_ONLY: Cell<bool> = const { Cell::new(false) };
}

/// Run `f` with every position on this thread solved by Newton continued from the
/// drawing, the closed forms (`closed`) set aside: for comparing the two paths (tests,
/// benches). Restored on return, and on a panic.
#[doc(hidden)]
pub fn newton_only<R>(f: impl FnOnce() -> R) -> R {
    struct Restore(bool);
    impl Drop for Restore {
        fn drop(&mut self) {
            NEWTON_ONLY.with(|n| n.set(self.0));
        }
    }
    let _restore = Restore(NEWTON_ONLY.with(|n| n.replace(true)));
    f()
}

/// The largest |Φ| of the rows, +∞ when one is not finite.
fn residual(rows: &[Row]) -> f64 {
    rows.iter().fold(0.0, |m, r| {
        if r.value.is_finite() {
            m.max(r.value.abs())
        } else {
            f64::INFINITY
        }
    })
}

/// The most continuation steps from the drawing to q (2500 rad of a crank).
const MAX_STEPS: f64 = 10_000.0;

/// Solve the square system a x = b by LU; `Singular` (condition estimate max|U_ii| /
/// min|U_ii|) when it is singular to working accuracy. A system with more rows than
/// columns (redundant constraints, consistent) by least squares through the SVD.
pub(crate) fn solve(a: DMatrix<f64>, b: DVector<f64>) -> Result<DVector<f64>, MechError> {
    if a.nrows() > a.ncols() && a.nrows() == b.len() && a.ncols() > 0 {
        // redundant constraints (#[allow(redundant)]): the consistent system by least squares
        let svd = a.svd(true, true);
        let s = &svd.singular_values;
        let (lo, hi) = (s.min(), s.max());
        if !(lo > 1e-13 * hi) {
            return Err(MechError::Singular { condition: hi / lo });
        }
        return match svd.solve(&b, 0.0) {
            Ok(x) if x.iter().all(|v| v.is_finite()) => Ok(x),
            _ => Err(MechError::Singular {
                condition: f64::INFINITY,
            }),
        };
    }
    if a.nrows() != a.ncols() || a.nrows() != b.len() || a.nrows() == 0 {
        return Err(MechError::InvalidInput(format!(
            "the constraint system is {}×{}: the count of equations does not match the unknowns",
            a.nrows(),
            a.ncols()
        )));
    }
    let lu = a.lu();
    let d = lu.u().diagonal().map(f64::abs);
    let (lo, hi) = (d.min(), d.max());
    if !(lo > 1e-13 * hi) {
        return Err(MechError::Singular { condition: hi / lo });
    }
    let x = lu.solve(&b).ok_or(MechError::Singular {
        condition: f64::INFINITY,
    })?;
    if x.iter().all(|v| v.is_finite()) {
        Ok(x)
    } else {
        Err(MechError::Singular {
            condition: f64::INFINITY,
        })
    }
}

/// One body's motion: its reference point's position, velocity, acceleration and its
/// rotation, angular velocity and acceleration (SI, global axes).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BodyMotion {
    /// The body's pose and twist.
    pub state: BodyState,
    /// The reference point's acceleration (m/s²).
    pub a: V3,
    /// The angular acceleration (rad/s²).
    pub alpha: V3,
}

impl BodyMotion {
    /// A body at the drawing's origin, unturned, at rest.
    pub fn rest() -> Self {
        BodyMotion {
            state: BodyState::drawing(V3::zeros()),
            a: V3::zeros(),
            alpha: V3::zeros(),
        }
    }

    /// The position, velocity and acceleration of the point at `s` from o in the drawing:
    /// r = o + R s, v = v_o + ω × ρ, a = a_o + α × ρ + ω × (ω × ρ) with ρ = R s.
    pub fn point(&self, s: V3) -> [V3; 3] {
        let st = &self.state;
        let rho = st.rot * s;
        [
            st.o + rho,
            st.v + st.w.cross(&rho),
            self.a + self.alpha.cross(&rho) + st.w.cross(&st.w.cross(&rho)),
        ]
    }

    /// The inertia tensor about the cg turned to the current pose, R I Rᵀ (kg·m²).
    pub fn inertia(&self, drawing: &Matrix3<f64>) -> Matrix3<f64> {
        let r = self.state.rot.to_rotation_matrix();
        r.matrix() * drawing * r.matrix().transpose()
    }
}

/// The kinematics of a spatial mechanism at (q, q̇, q̈): every body's motion.
#[derive(Clone, Debug)]
pub struct SpatialMotion {
    pub(crate) layout: Arc<Layout>,
    /// The input values (rad or m).
    pub q: Vec<f64>,
    /// Their rates.
    pub qd: Vec<f64>,
    /// Their accelerations.
    pub qdd: Vec<f64>,
    /// Each body's motion, the ground first.
    pub bodies: Vec<BodyMotion>,
}

impl SpatialMotion {
    /// The closed group whose closed form this motion's mechanism takes its positions from
    /// (`RSSR`, `RSSP`, `RSRC`, `spherical four-bar`), `None` when it is solved by Newton.
    #[doc(hidden)]
    pub fn closed_group(&self) -> Option<&'static str> {
        self.layout.closed.as_ref().map(|c| c.group.name())
    }
}

/// Positions alone at q ([`Layout::pose_into`] on the heap frame).
pub(crate) fn pose(layout: &Arc<Layout>, q: &[f64]) -> Result<SpatialMotion, MechError> {
    let f = layout.dense();
    let mut bodies = f.motions();
    layout.pose_into(f, q, &mut bodies)?;
    let zero = vec![0.0; q.len()];
    Ok(SpatialMotion {
        layout: layout.clone(),
        q: q.to_vec(),
        qd: zero.clone(),
        qdd: zero,
        bodies,
    })
}

/// Kinematics at (q, q̇, q̈) ([`Layout::kinematics_into`] on the heap frame).
pub(crate) fn kinematics(
    layout: &Arc<Layout>,
    q: &[f64],
    qd: &[f64],
    qdd: &[f64],
) -> Result<SpatialMotion, MechError> {
    let f = layout.dense();
    let mut bodies = f.motions();
    layout.kinematics_into(f, q, qd, qdd, &mut bodies)?;
    Ok(SpatialMotion {
        layout: layout.clone(),
        q: q.to_vec(),
        qd: qd.to_vec(),
        qdd: qdd.to_vec(),
        bodies,
    })
}
