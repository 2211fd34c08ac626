//! The constraint equations of the joints and their Jacobian, in the links' absolute
//! coordinates (x, y, φ) (see [`crate::kernel::link_state`]):
//! - revolute (a, b) at P: `P_b − P_a = 0` (2 rows),
//! - sliding normal (prismatic and slot) along u fixed in a: `n·(P_b − Q_a) = 0` with
//!   n = R(φ_a)·perp(u), Q_a the material point of a at P in the drawing (1 row),
//! - prismatic rotation lock: `φ_b − φ_a = 0` (1 row),
//! - revolute driver: `φ_b − φ_a − (q − q_ref) = 0`; prismatic driver: `u·(P_b − Q_a) − (q − q_ref) = 0`;
//! - gear pair or rack: no slip along the tangent t at the pitch point P,
//!   `t·(v_b(P) − v_a(P)) = 0` (a velocity constraint: Jacobian and rates only).
//!
//! The reaction convention follows from these signs: the multiplier λ of a joint's rows
//! is the force (and moment) exerted BY a ON b (`docs/conventions.md`, Reactions).
//!
//! Scaling (one rule, [`ConKind::angle_row`]): columns (x, y, φ·L), angle rows × L, L the
//! drawing's length scale; every entry of the scaled Jacobian is then dimensionless and of
//! order one. [`scaled_rows`] writes it; the group systems, the validation's rank test and
//! the generic solver all assemble through it.

use crate::kernel::link_state::{cross, perp, wrap, LinkState, V2};
use nalgebra::{SMatrix, SVector, Vector3};

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
    /// The input q in the drawing (`Model::reference_input`): for a revolute driver
    /// θ_b − θ_a there less the input's zero (rad), so that φ_b − φ_a = q − q_ref; for a
    /// prismatic driver minus its zero (m), so that the slide from the drawing is q − q_ref.
    pub q_ref: f64,
    /// A rolling wheel's radius r (m; 0 for the other joints): the contact point is
    /// r·perp(u) behind the wheel's centre, K = C − r perp(u).
    pub radius: f64,
    /// A rolling wheel's circular track (`crate::elements::rolling`): +1 rolling outside the circle
    /// centred at `da` (then the local vector of its centre D in the track), −1 inside;
    /// 0 for a straight track and for the other joints.
    pub around: f64,
}

impl JointGeom {
    /// This joint's geometry with its links given as `a` and `b`, and its local vectors
    /// as literal zeros where `at_anchor` says the point is the link's anchor
    /// ([`crate::model::Model::at_anchor`]: they are zero there for any drawing). The
    /// generated code rebuilds its joints with the topology as literal constants (the
    /// same values as the stored ones), so that every `a`/`b` test of a kernel (which
    /// side is solved, is it the ground) and every "is this point the anchor" test folds
    /// at compile time; only the other vectors are read at run time.
    #[inline(always)]
    pub fn with_links(&self, a: usize, b: usize, at_anchor: [bool; 2]) -> JointGeom {
        JointGeom {
            a,
            b,
            da: if at_anchor[0] { V2::zeros() } else { self.da },
            db: if at_anchor[1] { V2::zeros() } else { self.db },
            ..*self
        }
    }
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
    /// Gear pair or rack (`crate::elements::gears`): no slip at the pitch point along the common
    /// tangent t, `t·(v_b(P) − v_a(P)) = 0` (1 row; the joint's `da`, `db` are P in a and
    /// b, its `axis` is t in the drawing). Its rows serve the rank test at the drawing;
    /// meshing links are solved by [`crate::elements::gears`], not by a group system.
    Mesh,
    /// Rolling (`crate::elements::rolling`): the wheel's and the track's material points at the
    /// contact K = C − r perp(u) have the same velocity (2 rows, a revolute's at K). For
    /// the rank test; rolling links are solved by [`crate::elements::rolling`].
    Rolling,
}

impl ConKind {
    /// Number of scalar equations.
    pub const fn rows(self) -> usize {
        match self {
            ConKind::Revolute | ConKind::Prismatic | ConKind::Rolling => 2,
            _ => 1,
        }
    }
    /// Rows whose unit is an angle (scaled by the length scale in group systems).
    pub const fn angle_row(self, k: usize) -> bool {
        matches!(
            (self, k),
            (ConKind::Prismatic, 1) | (ConKind::DriveRevolute(_), 0)
        )
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
    let z = Row {
        a: Vector3::zeros(),
        b: Vector3::zeros(),
    };
    let mut out = ConEval {
        rows: [z, z],
        val: [0.0, 0.0],
    };
    match c.kind {
        ConKind::Revolute => {
            out.rows[0] = Row {
                a: Vector3::new(-1.0, 0.0, ra.y),
                b: Vector3::new(1.0, 0.0, -rb.y),
            };
            out.rows[1] = Row {
                a: Vector3::new(0.0, -1.0, -ra.x),
                b: Vector3::new(0.0, 1.0, rb.x),
            };
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
                ConKind::DrivePrismatic(k) => (u, [drive.0[k] - g.q_ref, drive.1[k], drive.2[k]]),
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
                out.rows[1] = Row {
                    a: Vector3::new(0.0, 0.0, -1.0),
                    b: Vector3::new(0.0, 0.0, 1.0),
                };
                out.val[1] = match level {
                    Level::Jacobian => 0.0,
                    Level::Position => cross(sa.rot, sb.rot).atan2(sa.rot.dot(&sb.rot)),
                    Level::Velocity => sb.omega - sa.omega,
                    Level::Acceleration => sb.alpha - sa.alpha,
                };
            }
        }
        ConKind::Rolling => {
            let c = sb.pos + rb;
            let k = if g.around == 0.0 {
                c - perp(sa.r(g.axis)) * g.radius
            } else {
                // The contact is on the line of centres, r from C towards the track.
                let d = sa.pos + ra;
                let n = (c - d) * (g.around / (c - d).norm());
                c - n * g.radius
            };
            let (ka, kb) = (k - sa.pos, k - sb.pos);
            out.rows[0] = Row {
                a: Vector3::new(-1.0, 0.0, ka.y),
                b: Vector3::new(1.0, 0.0, -kb.y),
            };
            out.rows[1] = Row {
                a: Vector3::new(0.0, -1.0, -ka.x),
                b: Vector3::new(0.0, 1.0, kb.x),
            };
            if level == Level::Velocity {
                let v = sb.vel_at(kb) - sa.vel_at(ka);
                out.val = [v.x, v.y];
            }
        }
        ConKind::Mesh => {
            let t = sa.r(g.axis);
            out.rows[0] = Row {
                a: Vector3::new(-t.x, -t.y, -cross(ra, t)),
                b: Vector3::new(t.x, t.y, cross(rb, t)),
            };
            out.val[0] = match level {
                Level::Velocity => t.dot(&(sb.vel_at(rb) - sa.vel_at(ra))),
                _ => 0.0,
            };
        }
        ConKind::DriveRevolute(k) => {
            out.rows[0] = Row {
                a: Vector3::new(0.0, 0.0, -1.0),
                b: Vector3::new(0.0, 0.0, 1.0),
            };
            out.val[0] = match level {
                Level::Jacobian => 0.0,
                Level::Position => {
                    wrap(cross(sa.rot, sb.rot).atan2(sa.rot.dot(&sb.rot)) - (drive.0[k] - g.q_ref))
                }
                Level::Velocity => sb.omega - sa.omega - drive.1[k],
                Level::Acceleration => sb.alpha - sa.alpha - drive.2[k],
            };
        }
    }
    out
}

/// Which column block (0, 1, ...) of the group a link occupies, if any.
#[inline(always)]
fn block(bodies: &[usize], link: usize) -> Option<usize> {
    bodies.iter().position(|&b| b == link)
}

/// The row scale of row `k` of a constraint of kind `kind`: L for an angle row, 1 otherwise.
#[inline(always)]
pub fn row_scale(kind: ConKind, k: usize, scale: f64) -> f64 {
    if kind.angle_row(k) {
        scale
    } else {
        1.0
    }
}

/// The scaled Jacobian rows of constraint `c` at the states `s`: for each of its rows k
/// and each of its two links, `put(k, link, [∂C/∂x, ∂C/∂y, ∂C/∂(φL)] × row scale)`, all
/// dimensionless (module docs). The one place the scaling rule is applied.
#[inline(always)]
pub fn scaled_rows(
    c: Con,
    g: &JointGeom,
    s: &[LinkState],
    scale: f64,
    mut put: impl FnMut(usize, usize, [f64; 3]),
) {
    // The input index only selects a drive value, which the Jacobian does not use.
    let kind = match c.kind {
        ConKind::DriveRevolute(_) => ConKind::DriveRevolute(0),
        ConKind::DrivePrismatic(_) => ConKind::DrivePrismatic(0),
        k => k,
    };
    let zero = [0.0];
    let e = eval(
        Con {
            joint: c.joint,
            kind,
        },
        g,
        s,
        (&zero, &zero, &zero),
        Level::Jacobian,
    );
    for k in 0..c.kind.rows() {
        let rs = row_scale(c.kind, k, scale);
        for (link, r) in [(g.a, &e.rows[k].a), (g.b, &e.rows[k].b)] {
            put(k, link, [rs * r.x, rs * r.y, rs * r.z / scale]);
        }
    }
}

/// The scaled Jacobian (M rows, N = 3 × links columns) of a group's constraints at the
/// current positions, and the row scales (L for angle rows, 1 otherwise).
#[inline(always)]
pub fn assemble<const M: usize, const N: usize>(
    bodies: &[usize],
    cons: &[Con],
    joints: &[JointGeom],
    s: &[LinkState],
    scale: f64,
) -> (SMatrix<f64, M, N>, SVector<f64, M>) {
    let mut j = SMatrix::<f64, M, N>::zeros();
    let mut rows = SVector::<f64, M>::repeat(1.0);
    let mut row = 0;
    for c in cons {
        scaled_rows(*c, &joints[c.joint], s, scale, |k, link, e| {
            if let Some(b) = block(bodies, link) {
                for (i, x) in e.iter().enumerate() {
                    j[(row + k, 3 * b + i)] += x;
                }
            }
        });
        for k in 0..c.kind.rows() {
            rows[row + k] = row_scale(c.kind, k, scale);
        }
        row += c.kind.rows();
    }
    (j, rows)
}

/// Minus the constraint values of a group at `level` (unknown rates must be zero in `s`).
#[inline(always)]
pub fn group_rhs<const N: usize>(
    cons: &[Con],
    joints: &[JointGeom],
    s: &[LinkState],
    drive: Drive,
    level: Level,
) -> SVector<f64, N> {
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
