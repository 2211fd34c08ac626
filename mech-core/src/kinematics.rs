//! Kinematic kernels: the state of a link, the constraint equations of every joint, and
//! the small fixed-size systems of one Assur group (velocities, accelerations, Newton).
//!
//! A link's state is its frame: `pos`, the global position of its anchor (its first
//! point, or its cg when it has no point; the ground's anchor is the origin), and `rot`
//! = (cos φ, sin φ), its rotation since the drawing. Every point of a link is stored as
//! a *local vector* `d` = (reference position − reference anchor), so its current
//! position is `pos + R(φ) d`. The link angle of SPEC section 2 is θ = θ_ref + φ.
//!
//! Generalised coordinates of a link are (x, y, φ); the constraint equations Φ = 0 of
//! the joints are written in them:
//! - revolute (a, b) at P: `P_b − P_a = 0` (2 rows),
//! - sliding normal (prismatic and slot) along u fixed in a: `n·(P_b − Q_a) = 0` with
//!   n = R(φ_a)·perp(u), Q_a the material point of a at P in the drawing (1 row),
//! - prismatic rotation lock: `φ_b − φ_a = 0` (1 row),
//! - revolute driver: `φ_b − φ_a − (q − q_ref) = 0`; prismatic driver: `u·(P_b − Q_a) − q = 0`.
//!
//! The reaction convention follows from these signs: the multiplier λ of a joint's rows
//! is the force (and moment) exerted BY a ON b.

use crate::MechError;
use nalgebra::{SMatrix, SVector, Vector2, Vector3};

/// A plane vector, m (or m/s, m/s², N).
pub type V2 = Vector2<f64>;

/// The vector turned +90°: perp(x, y) = (−y, x).
#[inline(always)]
pub fn perp(v: V2) -> V2 {
    V2::new(-v.y, v.x)
}

/// The scalar cross product a × b = a_x b_y − a_y b_x.
#[inline(always)]
pub fn cross(a: V2, b: V2) -> f64 {
    a.x * b.y - a.y * b.x
}

/// Rotate `d` by the unit complex `rot` = (cos φ, sin φ).
#[inline(always)]
pub fn rotate(rot: V2, d: V2) -> V2 {
    V2::new(rot.x * d.x - rot.y * d.y, rot.y * d.x + rot.x * d.y)
}

/// Position, velocity and acceleration of a link's frame (see the module docs).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LinkState {
    /// Anchor position, m.
    pub pos: V2,
    /// (cos φ, sin φ), φ the rotation since the drawing.
    pub rot: V2,
    /// Anchor velocity, m/s.
    pub vel: V2,
    /// Angular velocity ω, rad/s.
    pub omega: f64,
    /// Anchor acceleration, m/s².
    pub acc: V2,
    /// Angular acceleration α, rad/s².
    pub alpha: f64,
}

impl Default for LinkState {
    fn default() -> Self {
        LinkState::at(V2::zeros())
    }
}

impl LinkState {
    /// At rest, unrotated, anchor at `pos` (the drawing's pose when `pos` is the reference anchor).
    pub const fn at(pos: V2) -> Self {
        LinkState {
            pos,
            rot: V2::new(1.0, 0.0),
            vel: V2::new(0.0, 0.0),
            omega: 0.0,
            acc: V2::new(0.0, 0.0),
            alpha: 0.0,
        }
    }
    /// The current vector from the anchor to the material point of local vector `d`.
    #[inline(always)]
    pub fn r(&self, d: V2) -> V2 {
        rotate(self.rot, d)
    }
    /// Position of the material point with local vector `d`.
    #[inline(always)]
    pub fn point(&self, d: V2) -> V2 {
        self.pos + self.r(d)
    }
    /// Velocity of the material point at current offset `r` from the anchor: v + ω perp(r).
    #[inline(always)]
    pub fn vel_at(&self, r: V2) -> V2 {
        self.vel + perp(r) * self.omega
    }
    /// Acceleration of the material point at offset `r`: a + α perp(r) − ω² r.
    #[inline(always)]
    pub fn acc_at(&self, r: V2) -> V2 {
        self.acc + perp(r) * self.alpha - r * (self.omega * self.omega)
    }
}

/// Geometry of one joint in the local frames of its two links.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct JointGeom {
    /// First link (guide / slot).
    pub a: usize,
    /// Second link (slider / pin).
    pub b: usize,
    /// Local vector in `a` of the joint point (for sliding joints: of the material point
    /// of `a` that coincides with P in the drawing).
    pub da: V2,
    /// Local vector in `b` of the joint point.
    pub db: V2,
    /// Unit sliding axis in `a`'s local (reference) orientation; zero for a revolute.
    pub axis: V2,
    /// For a revolute driver: θ_b − θ_a in the drawing (rad), so that φ_b − φ_a = q − q_ref.
    pub q_ref: f64,
}

/// The kind of a constraint contributed by one joint to a group.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ConKind {
    /// Revolute: 2 rows.
    Revolute,
    /// Prismatic: sliding normal + rotation lock, 2 rows.
    Prismatic,
    /// Pin in slot: sliding normal, 1 row.
    Slot,
    /// Revolute driver (input `k`): 1 row (the pin itself is a separate `Revolute`).
    DriveRevolute(usize),
    /// Prismatic driver (input `k`): 1 row (the guide itself is a separate `Prismatic`).
    DrivePrismatic(usize),
}

impl ConKind {
    /// Number of scalar equations.
    pub const fn rows(self) -> usize {
        match self {
            ConKind::Revolute | ConKind::Prismatic => 2,
            _ => 1,
        }
    }
    /// Rows whose unit is an angle (scaled by the length scale in group systems).
    const fn angle_row(self, k: usize) -> bool {
        matches!((self, k), (ConKind::Prismatic, 1) | (ConKind::DriveRevolute(_), 0))
    }
}

/// One constraint of a group: a joint (index into the joint geometry) and what it imposes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Con {
    /// Joint index.
    pub joint: usize,
    /// What it imposes.
    pub kind: ConKind,
}

/// The partial derivatives of one scalar constraint with respect to (x, y, φ) of `a` and `b`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Row {
    /// ∂C/∂(x_a, y_a, φ_a).
    pub a: Vector3<f64>,
    /// ∂C/∂(x_b, y_b, φ_b).
    pub b: Vector3<f64>,
}

/// Angle difference wrapped to (−π, π] (rad). Beyond |a| = 1e9 the reduction goes
/// through (sin a, cos a), which is exact for any finite a.
#[inline]
pub fn wrap(a: f64) -> f64 {
    if !(a.abs() < 1e9) {
        let (s, c) = a.sin_cos();
        let r = s.atan2(c);
        return if r <= -std::f64::consts::PI { std::f64::consts::PI } else { r };
    }
    let t = std::f64::consts::TAU;
    let r = a - t * (a / t).round();
    if r <= -std::f64::consts::PI {
        r + t
    } else {
        r
    }
}

/// The value, rate or second rate of one constraint's rows, and its Jacobian rows.
#[derive(Clone, Copy, Debug)]
pub struct ConEval {
    /// Up to two Jacobian rows.
    pub rows: [Row; 2],
    /// Up to two values (position residual, or the rate / second rate with the group's
    /// own unknowns set to zero).
    pub val: [f64; 2],
}

/// What to evaluate.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Level {
    /// The Jacobian rows only (values left zero).
    Jacobian,
    /// Φ.
    Position,
    /// dΦ/dt.
    Velocity,
    /// d²Φ/dt².
    Acceleration,
}

/// Input values: (q, q̇, q̈) per input.
pub type Drive<'a> = (&'a [f64], &'a [f64], &'a [f64]);

/// Evaluate constraint `c` on the states `s` at `level`: its Jacobian rows and values.
///
/// Velocity/acceleration values are the full time derivatives evaluated at the current
/// states; with the unknown links' velocities (accelerations) set to zero they are the
/// right-hand sides of the group's linear systems, negated.
#[inline(always)]
pub fn eval(c: Con, g: &JointGeom, s: &[LinkState], drive: Drive, level: Level) -> ConEval {
    let (sa, sb) = (&s[g.a], &s[g.b]);
    let ra = sa.r(g.da);
    let rb = sb.r(g.db);
    let z = Row { a: Vector3::zeros(), b: Vector3::zeros() };
    let mut out = ConEval { rows: [z, z], val: [0.0, 0.0] };
    match c.kind {
        ConKind::Revolute => {
            out.rows[0] = Row { a: Vector3::new(-1.0, 0.0, ra.y), b: Vector3::new(1.0, 0.0, -rb.y) };
            out.rows[1] = Row { a: Vector3::new(0.0, -1.0, -ra.x), b: Vector3::new(0.0, 1.0, rb.x) };
            let v = match level {
                Level::Jacobian => V2::zeros(),
                Level::Position => (sb.pos + rb) - (sa.pos + ra),
                Level::Velocity => sb.vel_at(rb) - sa.vel_at(ra),
                Level::Acceleration => sb.acc_at(rb) - sa.acc_at(ra),
            };
            out.val = [v.x, v.y];
        }
        ConKind::Prismatic | ConKind::Slot | ConKind::DrivePrismatic(_) => {
            let u = sa.r(g.axis);
            // The sliding normal for guides; the axis itself for an actuator's stroke.
            let (n, target) = match c.kind {
                ConKind::DrivePrismatic(_) if level == Level::Jacobian => (u, [0.0; 3]),
                ConKind::DrivePrismatic(k) => (u, [drive.0[k], drive.1[k], drive.2[k]]),
                _ => (perp(u), [0.0; 3]),
            };
            let pb = sb.pos + rb;
            let e = pb - (sa.pos + ra);
            out.rows[0] = Row {
                a: Vector3::new(-n.x, -n.y, cross(n, pb - sa.pos)),
                b: Vector3::new(n.x, n.y, cross(rb, n)),
            };
            let nd = perp(n) * sa.omega;
            let ed = sb.vel_at(rb) - sa.vel_at(ra);
            out.val[0] = match level {
                Level::Jacobian => 0.0,
                Level::Position => n.dot(&e) - target[0],
                Level::Velocity => nd.dot(&e) + n.dot(&ed) - target[1],
                Level::Acceleration => {
                    let ndd = perp(n) * sa.alpha - n * (sa.omega * sa.omega);
                    let edd = sb.acc_at(rb) - sa.acc_at(ra);
                    ndd.dot(&e) + 2.0 * nd.dot(&ed) + n.dot(&edd) - target[2]
                }
            };
            if c.kind == ConKind::Prismatic {
                out.rows[1] = Row { a: Vector3::new(0.0, 0.0, -1.0), b: Vector3::new(0.0, 0.0, 1.0) };
                out.val[1] = match level {
                    Level::Jacobian => 0.0,
                    Level::Position => cross(sa.rot, sb.rot).atan2(sa.rot.dot(&sb.rot)),
                    Level::Velocity => sb.omega - sa.omega,
                    Level::Acceleration => sb.alpha - sa.alpha,
                };
            }
        }
        ConKind::DriveRevolute(k) => {
            out.rows[0] = Row { a: Vector3::new(0.0, 0.0, -1.0), b: Vector3::new(0.0, 0.0, 1.0) };
            out.val[0] = match level {
                Level::Jacobian => 0.0,
                Level::Position => wrap(cross(sa.rot, sb.rot).atan2(sa.rot.dot(&sb.rot)) - (drive.0[k] - g.q_ref)),
                Level::Velocity => sb.omega - sa.omega - drive.1[k],
                Level::Acceleration => sb.alpha - sa.alpha - drive.2[k],
            };
        }
    }
    out
}

/// Threshold on the condition estimate κ (the pivot ratio of a group's scaled system)
/// beyond which it is reported `Singular` (a dead point or toggle position). Near a
/// toggle, rates carry a relative error of order ε·κ², so 1e6 bounds it by about 1e-4.
pub const SINGULAR_CONDITION: f64 = 1e6;

/// The square system of one Assur group with `N` = 3 × (its links) unknowns.
///
/// Columns are (x, y, φ·L) of each link of the group in order, rows the scalar
/// equations of its constraints in order, angle rows multiplied by L (the drawing's
/// length scale): all entries are then dimensionless and of order one, so the pivot
/// ratio of the LU factorisation is a meaningful condition estimate.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GroupSystem<const N: usize> {
    lu: Lu<N>,
    row_scale: SVector<f64, N>,
    scale: f64,
}

/// Which column block (0, 1, ...) of the group a link occupies, if any.
#[inline(always)]
fn block(bodies: &[usize], link: usize) -> Option<usize> {
    bodies.iter().position(|&b| b == link)
}

/// The scaled Jacobian (M rows, N = 3 × links columns) of a group's constraints at the
/// current positions, and the row scales (L for angle rows, 1 otherwise); see
/// [`GroupSystem`] for the scaling.
#[inline(always)]
pub fn assemble<const M: usize, const N: usize>(
    bodies: &[usize],
    cons: &[Con],
    joints: &[JointGeom],
    s: &[LinkState],
    scale: f64,
) -> (SMatrix<f64, M, N>, SVector<f64, M>) {
    let mut j = SMatrix::<f64, M, N>::zeros();
    let mut row_scale = SVector::<f64, M>::repeat(1.0);
    let none: &[f64] = &[];
    let mut row = 0;
    for c in cons {
        let g = &joints[c.joint];
        let e = eval(*c, g, s, (none, none, none), Level::Jacobian);
        let (ba, bb) = (block(bodies, g.a), block(bodies, g.b));
        for k in 0..c.kind.rows() {
            let rs = if c.kind.angle_row(k) { scale } else { 1.0 };
            row_scale[row] = rs;
            for (bk, r) in [(ba, &e.rows[k].a), (bb, &e.rows[k].b)] {
                if let Some(bk) = bk {
                    j[(row, 3 * bk)] += rs * r.x;
                    j[(row, 3 * bk + 1)] += rs * r.y;
                    j[(row, 3 * bk + 2)] += rs * r.z / scale;
                }
            }
            row += 1;
        }
    }
    (j, row_scale)
}

/// The over-determined system of a redundant group (M > N rows, accepted with
/// `#[allow(redundant)]`): the equations are consistent, so the least-squares solution of
/// the normal equations JᵀJ x = Jᵀb is the exact one. Its condition is κ(J)², which is
/// what the threshold is applied to.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LsSystem<const N: usize, const M: usize> {
    j: SMatrix<f64, M, N>,
    lu: Lu<N>,
    row_scale: SVector<f64, M>,
    scale: f64,
}

impl<const N: usize, const M: usize> LsSystem<N, M> {
    /// Assemble J and factor JᵀJ at the current positions.
    #[inline(always)]
    pub fn new(bodies: &[usize], cons: &[Con], joints: &[JointGeom], s: &[LinkState], scale: f64) -> Result<Self, MechError> {
        let (j, row_scale) = assemble::<M, N>(bodies, cons, joints, s, scale);
        let lu = Lu::new(j.transpose() * j);
        let cond = lu.condition();
        if !(cond < SINGULAR_CONDITION * SINGULAR_CONDITION) {
            return Err(MechError::Singular { condition: cond.sqrt() });
        }
        Ok(LsSystem { j, lu, row_scale, scale })
    }

    /// Solve J x = b (consistent, M ≥ N) through the normal equations.
    #[inline(always)]
    pub fn solve(&self, b: &SVector<f64, M>) -> SVector<f64, N> {
        let rhs = self.j.transpose() * b.component_mul(&self.row_scale);
        let mut x = self.lu.solve(&rhs);
        for i in 0..N / 3 {
            x[3 * i + 2] /= self.scale;
        }
        x
    }
}

/// Write the solved rates `x` (x, y, φ per link) of a group into its links' velocities
/// (`acc` false) or accelerations (`acc` true).
#[inline(always)]
fn store_rates<const N: usize>(bodies: &[usize], s: &mut [LinkState], x: &SVector<f64, N>, acc: bool) {
    for (k, &b) in bodies.iter().enumerate() {
        if acc {
            s[b].acc = V2::new(x[3 * k], x[3 * k + 1]);
            s[b].alpha = x[3 * k + 2];
        } else {
            s[b].vel = V2::new(x[3 * k], x[3 * k + 1]);
            s[b].omega = x[3 * k + 2];
        }
    }
}

/// Move a group's links by the coordinate step `dx`; the largest component (m, φ×L).
#[inline(always)]
fn apply_step<const N: usize>(bodies: &[usize], s: &mut [LinkState], dx: &SVector<f64, N>, scale: f64) -> f64 {
    let mut step: f64 = 0.0;
    for (k, &b) in bodies.iter().enumerate() {
        s[b].pos += V2::new(dx[3 * k], dx[3 * k + 1]);
        let (sn, cs) = dx[3 * k + 2].sin_cos();
        s[b].rot = rotate(s[b].rot, V2::new(cs, sn)).normalize();
        step = step.max(dx[3 * k].abs()).max(dx[3 * k + 1].abs()).max((dx[3 * k + 2] * scale).abs());
    }
    step
}

/// A redundant group solved up to `upto`: positions by Gauss–Newton from the current
/// states (the drawing), then velocities and accelerations, all through [`LsSystem`].
#[inline]
#[allow(clippy::too_many_arguments)]
pub fn group_solve_ls<const N: usize, const M: usize>(
    bodies: &[usize],
    cons: &[Con],
    joints: &[JointGeom],
    s: &mut [LinkState],
    drive: Drive,
    scale: f64,
    upto: Level,
) -> Result<Option<LsSystem<N, M>>, MechError> {
    newton(bodies, s, scale, |s| {
        let sys = LsSystem::<N, M>::new(bodies, cons, joints, s, scale)?;
        Ok(sys.solve(&group_rhs::<M>(cons, joints, s, drive, Level::Position)))
    })?;
    // Consistent equations have a zero residual; a non-zero one means the links solved
    // before took the other branch at a change point (see the generated `__solve`).
    let r = group_rhs::<M>(cons, joints, s, drive, Level::Position);
    if !(r.amax() < 1e-9 * scale) {
        return Err(MechError::NoAssembly);
    }
    if !matches!(upto, Level::Velocity | Level::Acceleration) {
        return Ok(None);
    }
    let sys = LsSystem::<N, M>::new(bodies, cons, joints, s, scale)?;
    store_rates(bodies, s, &sys.solve(&group_rhs::<M>(cons, joints, s, drive, Level::Velocity)), false);
    if upto == Level::Acceleration {
        store_rates(bodies, s, &sys.solve(&group_rhs::<M>(cons, joints, s, drive, Level::Acceleration)), true);
    }
    Ok(Some(sys))
}

/// The velocity field of a redundant group only (see [`group_velocity_field`]).
#[inline(always)]
pub fn group_velocity_field_ls<const N: usize, const M: usize>(
    sys: Option<&LsSystem<N, M>>,
    bodies: &[usize],
    cons: &[Con],
    joints: &[JointGeom],
    s: &mut [LinkState],
    drive: Drive,
    scale: f64,
) -> Result<(), MechError> {
    let sys = match sys {
        Some(sys) => *sys,
        None => LsSystem::<N, M>::new(bodies, cons, joints, s, scale)?,
    };
    store_rates(bodies, s, &sys.solve(&group_rhs::<M>(cons, joints, s, drive, Level::Velocity)), false);
    Ok(())
}

impl<const N: usize> GroupSystem<N> {
    /// Assemble and factor the Jacobian of the group's constraints with respect to its
    /// links' coordinates at the current positions. `scale` is the drawing's length (m).
    #[inline(always)]
    pub fn new(bodies: &[usize], cons: &[Con], joints: &[JointGeom], s: &[LinkState], scale: f64) -> Result<Self, MechError> {
        let (j, row_scale) = assemble::<N, N>(bodies, cons, joints, s, scale);
        let lu = Lu::new(j);
        let cond = lu.condition();
        if !(cond < SINGULAR_CONDITION) {
            return Err(MechError::Singular { condition: cond });
        }
        Ok(GroupSystem { lu, row_scale, scale })
    }

    /// Solve J x = b for the links' coordinates rates (x, y, φ per link).
    #[inline(always)]
    pub fn solve(&self, b: &SVector<f64, N>) -> SVector<f64, N> {
        let rhs = b.component_mul(&self.row_scale);
        let mut x = self.lu.solve(&rhs);
        for i in 0..N / 3 {
            x[3 * i + 2] /= self.scale;
        }
        x
    }

    /// Solve Jᵀ λ = f for the multipliers (f = generalised forces (Fx, Fy, M) per link).
    #[inline(always)]
    pub fn solve_transpose(&self, f: &SVector<f64, N>) -> SVector<f64, N> {
        let mut rhs = *f;
        for i in 0..N / 3 {
            rhs[3 * i + 2] /= self.scale;
        }
        self.lu.solve_transpose(&rhs).component_mul(&self.row_scale)
    }
}

/// LU factorisation with partial pivoting of a small fixed-size matrix, on the stack.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Lu<const N: usize> {
    m: SMatrix<f64, N, N>,
    perm: [usize; N],
}

impl<const N: usize> Lu<N> {
    /// Factor P A = L U (L unit lower, U upper, stored together).
    #[inline(always)]
    pub fn new(mut m: SMatrix<f64, N, N>) -> Self {
        let mut perm = [0usize; N];
        for (i, p) in perm.iter_mut().enumerate() {
            *p = i;
        }
        for k in 0..N {
            let mut piv = k;
            for i in k + 1..N {
                if m[(i, k)].abs() > m[(piv, k)].abs() {
                    piv = i;
                }
            }
            if piv != k {
                m.swap_rows(k, piv);
                perm.swap(k, piv);
            }
            let d = m[(k, k)];
            if d == 0.0 {
                continue;
            }
            for i in k + 1..N {
                let f = m[(i, k)] / d;
                m[(i, k)] = f;
                for c in k + 1..N {
                    m[(i, c)] -= f * m[(k, c)];
                }
            }
        }
        Lu { m, perm }
    }
    /// Pivot ratio max|U_ii| / min|U_ii|: a cheap condition estimate (∞ when singular).
    #[inline(always)]
    pub fn condition(&self) -> f64 {
        let (mut lo, mut hi) = (f64::INFINITY, 0.0f64);
        for i in 0..N {
            let d = self.m[(i, i)].abs();
            lo = lo.min(d);
            hi = hi.max(d);
        }
        if lo > 0.0 {
            hi / lo
        } else {
            f64::INFINITY
        }
    }
    /// Solve A x = b.
    #[inline]
    pub fn solve(&self, b: &SVector<f64, N>) -> SVector<f64, N> {
        let mut x = SVector::<f64, N>::zeros();
        for i in 0..N {
            let mut v = b[self.perm[i]];
            for k in 0..i {
                v -= self.m[(i, k)] * x[k];
            }
            x[i] = v;
        }
        for i in (0..N).rev() {
            let mut v = x[i];
            for k in i + 1..N {
                v -= self.m[(i, k)] * x[k];
            }
            x[i] = v / self.m[(i, i)];
        }
        x
    }
    /// Solve Aᵀ x = b.
    #[inline]
    pub fn solve_transpose(&self, b: &SVector<f64, N>) -> SVector<f64, N> {
        // Aᵀ = Uᵀ Lᵀ P: solve Uᵀ y = b, Lᵀ z = y, x = Pᵀ z.
        let mut y = SVector::<f64, N>::zeros();
        for i in 0..N {
            let mut v = b[i];
            for k in 0..i {
                v -= self.m[(k, i)] * y[k];
            }
            y[i] = v / self.m[(i, i)];
        }
        for i in (0..N).rev() {
            let mut v = y[i];
            for k in i + 1..N {
                v -= self.m[(k, i)] * y[k];
            }
            y[i] = v;
        }
        let mut x = SVector::<f64, N>::zeros();
        for i in 0..N {
            x[self.perm[i]] = y[i];
        }
        x
    }
}

/// Minus the constraint values of a group at `level` (unknown rates must be zero in `s`).
#[inline(always)]
pub fn group_rhs<const N: usize>(cons: &[Con], joints: &[JointGeom], s: &[LinkState], drive: Drive, level: Level) -> SVector<f64, N> {
    let mut b = SVector::<f64, N>::zeros();
    let mut row = 0;
    for c in cons {
        let e = eval(*c, &joints[c.joint], s, drive, level);
        for k in 0..c.kind.rows() {
            b[row] = -e.val[k];
            row += 1;
        }
    }
    b
}

/// Velocities of a group's links from those of the links already solved:
/// J ẋ = −Φ̇(known). The group's velocities in `s` must be zero on entry.
#[inline(always)]
pub fn group_velocity<const N: usize>(
    sys: &GroupSystem<N>,
    bodies: &[usize],
    cons: &[Con],
    joints: &[JointGeom],
    s: &mut [LinkState],
    drive: Drive,
) {
    let x = sys.solve(&group_rhs::<N>(cons, joints, s, drive, Level::Velocity));
    store_rates(bodies, s, &x, false);
}

/// Accelerations of a group's links: J ẍ = −(Φ̈ with the group's accelerations zero).
#[inline(always)]
pub fn group_acceleration<const N: usize>(
    sys: &GroupSystem<N>,
    bodies: &[usize],
    cons: &[Con],
    joints: &[JointGeom],
    s: &mut [LinkState],
    drive: Drive,
) {
    let x = sys.solve(&group_rhs::<N>(cons, joints, s, drive, Level::Acceleration));
    store_rates(bodies, s, &x, true);
}

/// Positions of a group with no closed form: Newton–Raphson on the group's equations,
/// started from the links' current states (the drawing's pose unless the caller passes
/// a better guess). Converges to |Δ| < 1e-14 L or fails with `NoAssembly`.
pub fn group_newton<const N: usize>(
    bodies: &[usize],
    cons: &[Con],
    joints: &[JointGeom],
    s: &mut [LinkState],
    drive: Drive,
    scale: f64,
) -> Result<(), MechError> {
    newton(bodies, s, scale, |s| {
        let sys = GroupSystem::<N>::new(bodies, cons, joints, s, scale)?;
        Ok(sys.solve(&group_rhs::<N>(cons, joints, s, drive, Level::Position)))
    })
}

/// The Newton iteration of a group: apply the steps `step(s)` until the largest is below
/// 1e-14 L (at most 50); `NoAssembly` when a system is singular, a step is not finite,
/// or it does not converge.
#[inline]
fn newton<const N: usize>(
    bodies: &[usize],
    s: &mut [LinkState],
    scale: f64,
    mut step: impl FnMut(&[LinkState]) -> Result<SVector<f64, N>, MechError>,
) -> Result<(), MechError> {
    for _ in 0..50 {
        let dx = step(s).map_err(|_| MechError::NoAssembly)?;
        let size = apply_step(bodies, s, &dx, scale);
        if !size.is_finite() {
            return Err(MechError::NoAssembly);
        }
        if size < 1e-14 * scale {
            return Ok(());
        }
    }
    Err(MechError::NoAssembly)
}

// ---------------------------------------------------------------------------------------
// Closed-form position kernels of the common groups
// ---------------------------------------------------------------------------------------

/// Relative tolerance within which a negative discriminant is taken as a tangency.
const TANGENT_TOL: f64 = 1e-12;

/// Intersection of the circle (c1, r1) with the circle (c2, r2) on the side `sign` of the
/// line c1 → c2 (sign of (c2 − c1) × (X − c1)). `NoAssembly` when they do not meet.
#[inline]
pub fn circle_circle(c1: V2, r1: f64, c2: V2, r2: f64, sign: f64) -> Result<V2, MechError> {
    let d = c2 - c1;
    let l2 = d.norm_squared();
    let l = l2.sqrt();
    if !(l > 0.0) {
        return Err(MechError::NoAssembly);
    }
    let a = (l2 + r1 * r1 - r2 * r2) / (2.0 * l);
    let mut h2 = r1 * r1 - a * a;
    if h2 < 0.0 {
        if h2 < -TANGENT_TOL * r1.max(r2).powi(2) {
            return Err(MechError::NoAssembly);
        }
        h2 = 0.0;
    }
    let e = d / l;
    Ok(c1 + e * a + perp(e) * (sign * h2.sqrt()))
}

/// Intersection of the circle (c, r) with the line through `p` along unit `u`, on the
/// side `sign` along u of the foot of the perpendicular from c.
#[inline]
pub fn circle_line(c: V2, r: f64, p: V2, u: V2, sign: f64) -> Result<V2, MechError> {
    let t0 = (c - p).dot(&u);
    let foot = p + u * t0;
    let h = (c - foot).norm_squared();
    let mut w2 = r * r - h;
    if w2 < 0.0 {
        if w2 < -TANGENT_TOL * r * r {
            return Err(MechError::NoAssembly);
        }
        w2 = 0.0;
    }
    Ok(foot + u * (sign * w2.sqrt()))
}

/// Intersection of the lines (p1, u1) and (p2, u2); `Singular` when parallel.
#[inline]
pub fn line_line(p1: V2, u1: V2, p2: V2, u2: V2) -> Result<V2, MechError> {
    let den = cross(u1, u2);
    if den.abs() < 1e-12 {
        return Err(MechError::Singular { condition: 1.0 / den.abs().max(f64::MIN_POSITIVE) });
    }
    Ok(p1 + u1 * (cross(p2 - p1, u2) / den))
}

/// Place a link from its rotation and one of its points: pos = P − R d.
#[inline]
pub fn place_by_point(s: &mut LinkState, rot: V2, d: V2, p: V2) {
    s.rot = rot;
    s.pos = p - rotate(rot, d);
}

/// Place a link from two of its points (local vectors d1, d2) at global positions p1, p2.
#[inline]
pub fn place_by_two_points(s: &mut LinkState, d1: V2, d2: V2, p1: V2, p2: V2) {
    let a = d2 - d1;
    let b = p2 - p1;
    let rot = V2::new(a.dot(&b), cross(a, b)).normalize();
    place_by_point(s, rot, d1, p1);
}

/// The side of a closed form's solution in the drawing (±1), given the kernel's signed
/// quantity there; a zero (a change point) counts as +1.
#[inline]
pub fn branch(x: f64) -> f64 {
    if x < 0.0 {
        -1.0
    } else {
        1.0
    }
}

/// Solve one group up to `upto`: positions by its kernel ([`crate::assur::position`]),
/// then, when asked, velocities and accelerations from its linear system. The group's
/// links in `s` must be at the drawing (rest) on entry. Returns the factored system when
/// it was built (velocity level and beyond), so that kinetostatics can reuse it.
#[inline(always)]
#[allow(clippy::too_many_arguments)]
pub fn group_solve<const N: usize>(
    solver: crate::assur::Solver,
    bodies: &[usize],
    cons: &[Con],
    joints: &[JointGeom],
    s: &mut [LinkState],
    drive: Drive,
    scale: f64,
    sign: f64,
    upto: Level,
) -> Result<Option<GroupSystem<N>>, MechError> {
    crate::assur::position::<N>(solver, bodies, cons, joints, s, drive, scale, sign)?;
    if matches!(upto, Level::Velocity | Level::Acceleration) {
        let sys = GroupSystem::<N>::new(bodies, cons, joints, s, scale)?;
        group_velocity(&sys, bodies, cons, joints, s, drive);
        if upto == Level::Acceleration {
            group_acceleration(&sys, bodies, cons, joints, s, drive);
        }
        return Ok(Some(sys));
    }
    Ok(None)
}

/// The reference data of one link the solvers need: anchor, reference direction,
/// cg and inertia.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LinkGeom {
    /// Reference anchor (m), see the module docs.
    pub anchor: V2,
    /// (cos θ_ref, sin θ_ref): the link angle in the drawing.
    pub dir_ref: V2,
    /// Local vector of the cg (m).
    pub dcg: V2,
    /// Mass (kg), 0 for massless.
    pub mass: f64,
    /// Moment of inertia about the cg (kg·m²).
    pub inertia: f64,
}

/// Position, velocity and acceleration of a point (SPEC section 5), m, m/s, m/s².
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct PointMotion {
    /// Position, m.
    pub pos: V2,
    /// Velocity, m/s.
    pub vel: V2,
    /// Acceleration, m/s².
    pub acc: V2,
}

/// Position of a point, m.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct PointPose {
    /// Position, m.
    pub pos: V2,
}

/// Motion of a link (SPEC section 5): θ (rad, wrapped to (−π, π]), ω, α, and its cg's motion.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct LinkMotion {
    /// Link angle θ, rad.
    pub angle: f64,
    /// ω, rad/s.
    pub omega: f64,
    /// α, rad/s².
    pub alpha: f64,
    /// cg position, m.
    pub cg: V2,
    /// cg velocity, m/s.
    pub cg_vel: V2,
    /// cg acceleration, m/s².
    pub cg_acc: V2,
}

/// Pose of a link: θ (rad, wrapped to (−π, π]) and cg position (m).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct LinkPose {
    /// Link angle θ, rad.
    pub angle: f64,
    /// cg position, m.
    pub cg: V2,
}

impl LinkGeom {
    /// The link angle θ = θ_ref + φ, wrapped to (−π, π].
    #[inline]
    pub fn angle(&self, s: &LinkState) -> f64 {
        let d = rotate(s.rot, self.dir_ref);
        d.y.atan2(d.x)
    }
    /// The link's pose.
    #[inline]
    pub fn pose(&self, s: &LinkState) -> LinkPose {
        LinkPose { angle: self.angle(s), cg: s.point(self.dcg) }
    }
    /// The link's motion.
    #[inline]
    pub fn motion(&self, s: &LinkState) -> LinkMotion {
        let r = s.r(self.dcg);
        LinkMotion {
            angle: self.angle(s),
            omega: s.omega,
            alpha: s.alpha,
            cg: s.pos + r,
            cg_vel: s.vel_at(r),
            cg_acc: s.acc_at(r),
        }
    }
}

/// The motion of the material point of local vector `d` on a link.
#[inline]
pub fn point_motion(s: &LinkState, d: V2) -> PointMotion {
    let r = s.r(d);
    PointMotion { pos: s.pos + r, vel: s.vel_at(r), acc: s.acc_at(r) }
}

/// The position of the material point of local vector `d` on a link.
#[inline]
pub fn point_pose(s: &LinkState, d: V2) -> PointPose {
    PointPose { pos: s.point(d) }
}

/// The velocity field of a group only (positions already in `s`, its velocities zero),
/// with the group's factored system `sys` when the kinematics kept it.
#[inline(always)]
pub fn group_velocity_field<const N: usize>(
    sys: Option<&GroupSystem<N>>,
    bodies: &[usize],
    cons: &[Con],
    joints: &[JointGeom],
    s: &mut [LinkState],
    drive: Drive,
    scale: f64,
) -> Result<(), MechError> {
    let sys = match sys {
        Some(sys) => *sys,
        None => GroupSystem::<N>::new(bodies, cons, joints, s, scale)?,
    };
    group_velocity(&sys, bodies, cons, joints, s, drive);
    Ok(())
}
