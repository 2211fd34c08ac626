//! The spatial joints' constraint equations, their Jacobian rows and their velocity terms.
//!
//! Each moving body i has a reference point o_i (its cg, else its first point) and a
//! rotation R_i from the drawing (R_i = 1 in the drawing, so vectors fixed in a body are
//! written with their drawing components). Its twist is (v_i, ω_i): the velocity of o_i and
//! the angular velocity, both in global axes. A constraint Φ = 0 has the row J with
//! Φ̇ = J·(v_a, ω_a, v_b, ω_b) and Φ̈ = J·(a_a, α_a, a_b, α_b) + γ, γ the terms in the
//! velocities alone. Every joint is built from five primitives, each written once:
//! - `coincide`: a point of a on a point of b, p_a − p_b = 0 (3 rows);
//! - `perpendicular`: a vector fixed in a stays at its drawing angle to one fixed in b,
//!   (R_a x)·(R_b y) = x·y (1 row);
//! - `offset`: the point of b stays at its drawing distance from a plane of a:
//!   n·(p_b − p_a) = target (1 row, n fixed in a);
//! - `angle`: b's rotation about an axis u fixed in a, θ = atan2((n_a × n_b)·u, n_a·n_b) with
//!   n ⊥ u fixed in both (1 row, θ̇ = u·(ω_b − ω_a));
//! - `spin`: an idle link keeps the drawing's spin about its axis e, the vector part of its
//!   rotation quaternion ⊥ e (1 row).

use nalgebra::{Quaternion, UnitQuaternion, Vector3};
use std::f64::consts::PI;

type V3 = Vector3<f64>;

/// A body's pose and twist during a solve (the ground: o = 0, R = 1, at rest).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BodyState {
    /// The reference point o (m).
    pub o: V3,
    /// The rotation from the drawing.
    pub rot: UnitQuaternion<f64>,
    /// The velocity of o (m/s).
    pub v: V3,
    /// The angular velocity (rad/s).
    pub w: V3,
}

impl BodyState {
    /// The body in the drawing, at rest, its reference point at `o`.
    pub fn drawing(o: V3) -> Self {
        BodyState {
            o,
            rot: UnitQuaternion::identity(),
            v: V3::zeros(),
            w: V3::zeros(),
        }
    }
}

/// One constraint row: its value Φ, its Jacobian blocks on body a's and body b's twists
/// ((v, ω) coefficients each) and γ (Φ̈ = J·accelerations + γ).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Row {
    /// Φ (m, or dimensionless, or rad).
    pub value: f64,
    /// Coefficients of (v_a, ω_a).
    pub a: [V3; 2],
    /// Coefficients of (v_b, ω_b).
    pub b: [V3; 2],
    /// The velocity terms of Φ̈.
    pub gamma: f64,
}

impl Row {
    /// self + k·other, every part.
    fn plus(self, k: f64, o: Row) -> Row {
        Row {
            value: self.value + k * o.value,
            a: [self.a[0] + o.a[0] * k, self.a[1] + o.a[1] * k],
            b: [self.b[0] + o.b[0] * k, self.b[1] + o.b[1] * k],
            gamma: self.gamma + k * o.gamma,
        }
    }
}

/// Two unit vectors completing the unit `u` to a right-handed orthonormal basis (n1, n2, u).
pub fn basis(u: V3) -> (V3, V3) {
    let t = if u.x.abs() < 0.9 { V3::x() } else { V3::y() };
    let n1 = u.cross(&t).normalize();
    (n1, u.cross(&n1))
}

/// The three rows of p_a = p_b, p = o + R s (s: the point from the body's o in the drawing).
fn coincide(a: &BodyState, sa: V3, b: &BodyState, sb: V3, out: &mut impl Extend<Row>) {
    let (ra, rb) = (a.rot * sa, b.rot * sb);
    let d = a.o + ra - b.o - rb;
    let g = a.w.cross(&a.w.cross(&ra)) - b.w.cross(&b.w.cross(&rb));
    for k in 0..3 {
        let e = V3::ith(k, 1.0);
        out.extend([Row {
            value: d[k],
            a: [e, ra.cross(&e)],
            b: [-e, -rb.cross(&e)],
            gamma: g[k],
        }]);
    }
}

/// (R_a x)·(R_b y) − x·y: Φ̇ = (x_a × y_b)·(ω_a − ω_b).
fn perpendicular(a: &BodyState, x: V3, b: &BodyState, y: V3) -> Row {
    let (xa, yb) = (a.rot * x, b.rot * y);
    let c = xa.cross(&yb);
    let dc = a.w.cross(&xa).cross(&yb) + xa.cross(&b.w.cross(&yb));
    Row {
        value: xa.dot(&yb) - x.dot(&y),
        a: [V3::zeros(), c],
        b: [V3::zeros(), -c],
        gamma: (a.w - b.w).dot(&dc),
    }
}

/// n·(p_b − p_a) − target, n = R_a n fixed in a, p_a = o_a + R_a s_a, p_b = o_b + R_b s_b.
fn offset(a: &BodyState, n: V3, sa: V3, b: &BodyState, sb: V3, target: f64) -> Row {
    let (n, ra, rb) = (a.rot * n, a.rot * sa, b.rot * sb);
    let d = b.o + rb - a.o - ra;
    let dd = b.v + b.w.cross(&rb) - a.v - a.w.cross(&ra);
    let gamma = a.w.cross(&a.w.cross(&n)).dot(&d)
        + 2.0 * a.w.cross(&n).dot(&dd)
        + n.dot(&(b.w.cross(&b.w.cross(&rb)) - a.w.cross(&a.w.cross(&ra))));
    Row {
        value: n.dot(&d) - target,
        a: [-n, n.cross(&(d + ra))],
        b: [n, rb.cross(&n)],
        gamma,
    }
}

/// θ − target, θ the rotation of b relative to a about u (fixed in a) measured by n ⊥ u
/// (fixed in both in the drawing), unwrapped to the turn nearest `target`.
fn angle(a: &BodyState, u: V3, n: V3, b: &BodyState, target: f64) -> Row {
    let (u, na, nb) = (a.rot * u, a.rot * n, b.rot * n);
    let theta = na.cross(&nb).dot(&u).atan2(na.dot(&nb));
    let turns = ((target - theta) / (2.0 * PI)).round();
    Row {
        value: theta + 2.0 * PI * turns - target,
        a: [V3::zeros(), -u],
        b: [V3::zeros(), u],
        gamma: a.w.cross(&u).dot(&(b.w - a.w)),
    }
}

/// The idle link's spin fix: e·vec(q) = 0 for its rotation quaternion q = (w, v) (e the
/// link's axis in the drawing); with q̇ = ½ (0, ω) ⊗ q, Φ̇ = ½ ω·(w e + v × e) and
/// γ = ½ ω·(ẇ e + v̇ × e). The row's ground side (a) is empty.
pub fn spin(body: &BodyState, e: V3) -> Row {
    let q = body.rot.quaternion();
    let (w, v) = (q.w, q.imag());
    let (wd, vd) = (-0.5 * body.w.dot(&v), 0.5 * (body.w * w + body.w.cross(&v)));
    Row {
        value: e.dot(&v),
        a: [V3::zeros(); 2],
        b: [V3::zeros(), 0.5 * (e * w + v.cross(&e))],
        gamma: 0.5 * body.w.dot(&(e * wd + vd.cross(&e))),
    }
}

/// The rotation the spin fix gives an idle link whose axis (from one spherical centre to the
/// other) is `e` in the drawing and `now` at present (any lengths): the shortest arc from e
/// to now, the quaternion ∝ (1 + ê·n̂, ê × n̂), its vector part ⊥ e (`spin`'s value 0; the
/// only rotation taking ê to n̂ with that property). `None` when now is opposite e.
pub fn spin_rotation(e: V3, now: V3) -> Option<UnitQuaternion<f64>> {
    let (e, n) = (e.try_normalize(0.0)?, now.try_normalize(0.0)?);
    let w = 1.0 + e.dot(&n);
    if !(w > 1e-12) {
        return None;
    }
    Some(UnitQuaternion::from_quaternion(Quaternion::from_parts(
        w,
        e.cross(&n),
    )))
}

/// A joint's geometry fixed in its bodies: the point from each body's o and its axes, all
/// in the drawing's components.
#[derive(Clone, Debug, PartialEq)]
pub struct JointGeom {
    /// The first body.
    pub a: usize,
    /// The second body.
    pub b: usize,
    /// The joint's point from o_a in the drawing (m).
    pub sa: V3,
    /// The joint's point from o_b in the drawing (m).
    pub sb: V3,
    /// The kind's axes: (u, n1, n2) (u the axis, n1, n2 from [`basis`]; the universal's
    /// second axis in n1).
    pub axes: [V3; 3],
    /// The kind.
    pub kind: Kind,
    /// A helical joint's lead (m per turn).
    pub pitch: f64,
}

/// The rows a joint contributes (its kind without its geometry).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Kind {
    /// The point (3 rows).
    Spherical,
    /// The point and the axis in line (5).
    Revolute,
    /// The point and the cross's two axes at their drawing angle (4).
    Universal,
    /// The axis in line and the point on it (4).
    Cylindrical,
    /// The cylindrical rows and no turning about the axis (5).
    Prismatic,
    /// The cylindrical rows and the lead, advance = p θ / (2π) (5).
    Helical,
}

/// The joint's 6 − k rows (k its class), appended to `out`, for bodies in states `a`, `b`.
pub fn joint_rows(g: &JointGeom, a: &BodyState, b: &BodyState, out: &mut impl Extend<Row>) {
    let [u, n1, n2] = g.axes;
    match g.kind {
        Kind::Spherical => coincide(a, g.sa, b, g.sb, out),
        Kind::Revolute => {
            coincide(a, g.sa, b, g.sb, out);
            out.extend([perpendicular(a, n1, b, u)]);
            out.extend([perpendicular(a, n2, b, u)]);
        }
        Kind::Universal => {
            coincide(a, g.sa, b, g.sb, out);
            out.extend([perpendicular(a, u, b, n1)]);
        }
        _ => {
            // cylindrical, then prismatic's no-rotation or helical's lead
            out.extend([perpendicular(a, n1, b, u)]);
            out.extend([perpendicular(a, n2, b, u)]);
            out.extend([offset(a, n1, g.sa, b, g.sb, 0.0)]);
            out.extend([offset(a, n2, g.sa, b, g.sb, 0.0)]);
            if g.kind == Kind::Prismatic {
                out.extend([perpendicular(a, n1, b, n2)]);
            } else if g.kind == Kind::Helical {
                out.extend([lead(g, a, b)]);
            }
        }
    }
}

/// A helical joint's u·d − p θ/(2π), θ unwrapped near 2π u·d / p.
fn lead(g: &JointGeom, a: &BodyState, b: &BodyState) -> Row {
    let [u, n1, _] = g.axes;
    let along = offset(a, u, g.sa, b, g.sb, 0.0);
    let near = along.value * 2.0 * PI / g.pitch;
    let mut theta = angle(a, u, n1, b, near);
    theta.value += near;
    along.plus(-g.pitch / (2.0 * PI), theta)
}

/// The driver's row at input value q: a revolute's or helical's rotation about its axis
/// θ − q (rad), a prismatic's advance along its axis u·(p_b − p_a) − q (m, 0 in the
/// drawing). Its multiplier is the motor action (N·m or N, by a on b along the axis).
pub fn driver_row(g: &JointGeom, a: &BodyState, b: &BodyState, q: f64) -> Row {
    let [u, n1, _] = g.axes;
    if g.kind == Kind::Prismatic {
        offset(a, u, g.sa, b, g.sb, q)
    } else {
        angle(a, u, n1, b, q)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Fourth-order central differences (first and second derivative) of five samples at
    /// −2h, −h, 0, h, 2h.
    fn differences(f: [f64; 5], h: f64) -> (f64, f64) {
        (
            (f[0] - 8.0 * f[1] + 8.0 * f[3] - f[4]) / (12.0 * h),
            (-f[0] + 16.0 * f[1] - 30.0 * f[2] + 16.0 * f[3] - f[4]) / (12.0 * h * h),
        )
    }

    /// Φ̇ = J·ẋ and Φ̈ = J·ẍ + γ for every row of every joint kind, its driver, and a
    /// `perpendicular` row of two generic vectors, against differences of Φ along a path:
    /// body a on o(t) = o + v t + ½ a t², R(t) = exp(ω t + ½ α t²) R0 (so its ω, α at t = 0
    /// are ω, α); body b turning with a about the joint's axis (R_b = R_a Rot(u, θ(t)) C,
    /// C about u, so the axes stay aligned: ω_b = ω_a + θ̇ R_a u,
    /// α_b = α_a + θ̈ R_a u + θ̇ ω_a × R_a u), its o on a parabola of its own.
    #[test]
    fn rows_and_velocity_terms_match_differences_of_the_equations() {
        let u = V3::new(0.3, -0.5, 0.8).normalize();
        let (n1, n2) = basis(u);
        let r0 = UnitQuaternion::from_scaled_axis(V3::new(0.4, 0.1, -0.7));
        let (oa, va, aa) = (
            V3::new(0.1, 0.2, -0.1),
            V3::new(0.5, -1.0, 0.3),
            V3::new(2.0, 1.0, -3.0),
        );
        let (wa, ala) = (V3::new(1.5, -0.5, 2.0), V3::new(-4.0, 3.0, 1.0));
        let (ob, vb, ab) = (
            V3::new(0.4, 0.1, 0.2),
            V3::new(-0.3, 0.8, 1.1),
            V3::new(1.0, -2.0, 0.5),
        );
        let (thd, thdd) = (2.5, -6.0);
        let c = UnitQuaternion::from_scaled_axis(u * 0.3);
        let at = |t: f64| {
            let ra = UnitQuaternion::from_scaled_axis(wa * t + ala * (0.5 * t * t)) * r0;
            let rb = ra * UnitQuaternion::from_scaled_axis(u * (thd * t + 0.5 * thdd * t * t)) * c;
            (
                BodyState {
                    o: oa + va * t + aa * (0.5 * t * t),
                    rot: ra,
                    v: va,
                    w: wa,
                },
                BodyState {
                    o: ob + vb * t + ab * (0.5 * t * t),
                    rot: rb,
                    v: vb,
                    w: wa,
                },
            )
        };
        let (sa, sb) = (V3::new(0.2, -0.1, 0.05), V3::new(-0.15, 0.3, 0.1));
        let h = 1e-3;
        let mut worst = 0.0f64;
        for kind in [
            Kind::Spherical,
            Kind::Revolute,
            Kind::Universal,
            Kind::Cylindrical,
            Kind::Prismatic,
            Kind::Helical,
        ] {
            let g = JointGeom {
                a: 1,
                b: 2,
                sa,
                sb,
                axes: [u, n1, n2],
                kind,
                pitch: 0.07,
            };
            let rows = |a: &BodyState, b: &BodyState| {
                let mut out = Vec::new();
                joint_rows(&g, a, b, &mut out);
                out.push(driver_row(&g, a, b, 0.2));
                out.push(perpendicular(
                    a,
                    V3::new(0.6, 0.0, 0.8),
                    b,
                    V3::new(0.0, 0.6, -0.8),
                ));
                out
            };
            let samples: Vec<Vec<Row>> = [-2.0, -1.0, 0.0, 1.0, 2.0]
                .iter()
                .map(|k| {
                    let (a, b) = at(k * h);
                    rows(&a, &b)
                })
                .collect();
            let (a, b) = at(0.0);
            let ua = a.rot * u;
            let wb = wa + ua * thd;
            let alb = ala + ua * thdd + wa.cross(&(ua * thd));
            let exact = rows(&a, &BodyState { w: wb, ..b });
            for (r, row) in exact.iter().enumerate() {
                let (d1, d2) = differences(std::array::from_fn(|k| samples[k][r].value), h);
                let j1 =
                    row.a[0].dot(&va) + row.a[1].dot(&wa) + row.b[0].dot(&vb) + row.b[1].dot(&wb);
                let j2 = row.a[0].dot(&aa)
                    + row.a[1].dot(&ala)
                    + row.b[0].dot(&ab)
                    + row.b[1].dot(&alb)
                    + row.gamma;
                worst = worst.max((d1 - j1).abs()).max((d2 - j2).abs());
                assert!(
                    (d1 - j1).abs() < 1e-8 && (d2 - j2).abs() < 1e-6,
                    "kind {kind:?} row {r}: {d1} {j1} {d2} {j2}"
                );
            }
        }
        eprintln!("rows against differences: {worst:.1e}");
    }

    /// The spin row of an idle link, along a free path of the body alone.
    #[test]
    fn the_spin_row_matches_differences() {
        let e = V3::new(0.2, 0.9, -0.3).normalize();
        let (w, al) = (V3::new(1.0, -2.0, 0.5), V3::new(3.0, 1.0, -2.0));
        let r0 = UnitQuaternion::from_scaled_axis(V3::new(0.2, -0.3, 0.1));
        let at = |t: f64| BodyState {
            o: V3::zeros(),
            rot: UnitQuaternion::from_scaled_axis(w * t + al * (0.5 * t * t)) * r0,
            v: V3::zeros(),
            w,
        };
        let h = 1e-3;
        let (d1, d2) = differences(
            std::array::from_fn(|k| spin(&at((k as f64 - 2.0) * h), e).value),
            h,
        );
        let row = spin(&at(0.0), e);
        assert!((d1 - row.b[1].dot(&w)).abs() < 1e-9, "{d1}");
        assert!((d2 - row.b[1].dot(&al) - row.gamma).abs() < 1e-6, "{d2}");
    }
}
