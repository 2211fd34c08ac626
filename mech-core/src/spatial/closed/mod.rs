//! Closed-form positions of the four spatial groups that have one (RSSR, RSSP, RSRC, the
//! spherical four-bar), allocation-free, on the drawing's assembly.
//!
//! Each group is driven by a revolute crank (the input) and has one output: the rocker's
//! angle φ (RSSR, spherical four-bar, rad), the slider's travel s (RSSP, m), or the output
//! cylinder's rotation θ and slide s (RSRC); the RSSP may also be driven at its slide, the
//! crank's angle its output (`RsspSlide`). Every kernel reduces to two scalar equations,
//! each written once here:
//! - `dot_angle`: x·Rot(g, φ) y₀ = c, the Freudenstein form P cos φ + Q sin φ = R with
//!   P = x·y⊥, Q = x·(g × y⊥), R = c − (x·g)(y₀·g) (y⊥ = y₀ − (y₀·g) g), solved
//!   φ = atan2(Q, P) + σ acos(R / √(P² + Q²)), wrapped to (−π, π];
//! - `travel`: |m − s w| = l, s = w·m + σ √((w·m)² − |m|² + l²).
//!
//! and their rates to two more (`keep_dot`: x·y constant with y turning about g;
//! `keep_length`: |r| constant). The branch σ = ±1 of each is chosen once, at
//! construction, as the root that reproduces the drawing (φ = 0, s = 0 at q = 0); a
//! drawing at a toggle (the two roots equal) has no such choice and is not taken (`new`
//! answers `None`, and the mechanism is solved by Newton). A position that does not
//! assemble is [`MechError::NoAssembly`] (the Newton path's error), a rate at a dead
//! point [`MechError::Singular`]; never a NaN inside `Ok`.
//!
//! `Closed` (crate-internal) recognises a loaded mechanism whose whole topology is one of
//! these groups and gives every body's pose, the idle coupler's spin fixed as
//! `constraints::spin` fixes it (`constraints::spin_rotation`).

pub mod rsrc;
pub mod rssp;
pub mod rssr;
pub mod spherical;

pub use rsrc::Rsrc;
pub use rssp::{Rssp, RsspGeometry, RsspSlide};
pub use rssr::Rssr;
pub use spherical::SphericalFourBar;

use super::constraints::{self, BodyState};
use super::kinematics::BodyMotion;
use super::model::{Joint, JointKind, SpatialModel};
use crate::MechError;
use nalgebra::{Matrix3, Rotation3, Unit, UnitQuaternion, Vector3};
use std::f64::consts::PI;

type V3 = Vector3<f64>;

/// An output variable (rad or m) and its first and second time derivatives (rad/s, rad/s²
/// or m/s, m/s²).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Output {
    /// The value, 0 in the drawing.
    pub x: f64,
    /// Its rate.
    pub xd: f64,
    /// Its acceleration.
    pub xdd: f64,
}

/// The rotation by `angle` (rad) about the unit `axis`.
#[inline]
pub(crate) fn turn(axis: V3, angle: f64) -> UnitQuaternion<f64> {
    UnitQuaternion::from_axis_angle(&Unit::new_unchecked(axis), angle)
}

/// The point `p0` (drawing) of a body turning by [ψ, ψ̇, ψ̈] about the line through
/// `centre` along the unit `axis`: its position c + Rot(u, ψ)(p₀ − c), velocity ψ̇ u × ρ and
/// acceleration ψ̈ u × ρ + ψ̇² u × (u × ρ), ρ = p − c (m, m/s, m/s²).
#[inline]
pub(crate) fn circle(centre: V3, axis: V3, p0: V3, psi: [f64; 3]) -> [V3; 3] {
    let rho = turn(axis, psi[0]) * (p0 - centre);
    let t = axis.cross(&rho);
    [
        centre + rho,
        t * psi[1],
        t * psi[2] + axis.cross(&t) * (psi[1] * psi[1]),
    ]
}

/// An angle wrapped to (−π, π].
#[inline]
fn wrap(a: f64) -> f64 {
    let w = a - 2.0 * PI * (a / (2.0 * PI)).round();
    if w <= -PI {
        w + 2.0 * PI
    } else {
        w
    }
}

/// The cosine c = R / √(P² + Q²) of a Freudenstein or quadratic root, clamped to [−1, 1]
/// when it is out by rounding only (1e-12); `NoAssembly` beyond (or NaN).
#[inline]
fn reach(r: f64, h: f64) -> Result<f64, MechError> {
    if !(r.abs() <= h * (1.0 + 1e-12)) || !(h > 0.0) {
        return Err(MechError::NoAssembly);
    }
    Ok((r / h).clamp(-1.0, 1.0))
}

/// φ (rad, (−π, π]) with x·Rot(g, φ) y₀ = c on the branch σ: P cos φ + Q sin φ = R,
/// φ = atan2(Q, P) + σ acos(R / √(P² + Q²)) (module doc).
#[inline]
pub(crate) fn dot_angle(x: V3, g: V3, y0: V3, c: f64, sign: f64) -> Result<f64, MechError> {
    let along = y0.dot(&g);
    let perp = y0 - g * along;
    let (p, q) = (x.dot(&perp), x.dot(&g.cross(&perp)));
    let r = c - x.dot(&g) * along;
    let cos = reach(r, p.hypot(q))?;
    Ok(wrap(q.atan2(p) + sign * cos.acos()))
}

/// s (m) with |m − s w| = l (w unit) on the branch σ: s = w·m + σ √((w·m)² − |m|² + l²);
/// `NoAssembly` when the discriminant is negative beyond rounding.
#[inline]
pub(crate) fn travel(m: V3, w: V3, l: f64, sign: f64) -> Result<f64, MechError> {
    let b = w.dot(&m);
    let perp2 = m.norm_squared() - b * b;
    let disc = l * l - perp2;
    if !(disc >= -1e-12 * l * l) {
        return Err(MechError::NoAssembly);
    }
    Ok(b + sign * disc.max(0.0).sqrt())
}

/// num / den, `Singular` when |den| ≤ 1e-12 · scale (a dead point of the output).
#[inline]
fn divide(num: f64, den: f64, scale: f64) -> Result<f64, MechError> {
    if !(den.abs() > 1e-12 * scale) {
        return Err(MechError::Singular {
            condition: scale / den.abs(),
        });
    }
    Ok(num / den)
}

/// The rates of φ keeping x·y constant, y turning about the unit g (ẏ = φ̇ g × y), x moving
/// with (ẋ, ẍ): with t = g × y, φ̇ = −ẋ·y / x·t and
/// φ̈ = −(ẍ·y + 2 φ̇ ẋ·t + φ̇² x·(g × t)) / x·t.
#[inline]
pub(crate) fn keep_dot(x: V3, xd: V3, xdd: V3, y: V3, g: V3) -> Result<(f64, f64), MechError> {
    let t = g.cross(&y);
    let (den, scale) = (x.dot(&t), x.norm() * t.norm());
    let rate = divide(-xd.dot(&y), den, scale)?;
    let acc = divide(
        -(xdd.dot(&y) + 2.0 * rate * xd.dot(&t) + rate * rate * x.dot(&g.cross(&t))),
        den,
        scale,
    )?;
    Ok((rate, acc))
}

/// The rates of x keeping |r| constant with ṙ = a − ẋ t and r̈ = b − ẍ t − ẋ² c (a, b the
/// parts not in x): ẋ = r·a / r·t, ẍ = (ṙ·ṙ + r·b − ẋ² r·c) / r·t.
#[inline]
pub(crate) fn keep_length(r: V3, a: V3, b: V3, t: V3, c: V3) -> Result<(f64, f64), MechError> {
    let (den, scale) = (r.dot(&t), r.norm() * t.norm());
    let rate = divide(r.dot(&a), den, scale)?;
    let rd = a - t * rate;
    let acc = divide(
        rd.norm_squared() + r.dot(&b) - rate * rate * r.dot(&c),
        den,
        scale,
    )?;
    Ok((rate, acc))
}

/// The branch σ ∈ {+1, −1} whose root `root(σ)` reproduces the drawing (|root| ≤ 1e-9 ·
/// `scale`), the other root apart from it by more than 1e-6 · `scale`; `None` at a toggle or
/// when the drawing does not satisfy the equation.
pub(crate) fn branch(root: impl Fn(f64) -> Result<f64, MechError>, scale: f64) -> Option<f64> {
    let (plus, minus) = (root(1.0).ok()?, root(-1.0).ok()?);
    let sign = if plus.abs() <= minus.abs() { 1.0 } else { -1.0 };
    let (near, far) = if sign > 0.0 {
        (plus, minus)
    } else {
        (minus, plus)
    };
    (near.abs() <= 1e-9 * scale && (far - near).abs() > 1e-6 * scale).then_some(sign)
}

/// The rotation taking the drawing's pair (x₀, y₀) (not parallel) to the current (x, y), the
/// angle between them kept: F(x, y) F(x₀, y₀)ᵀ with F(x, y) = [x̂, ŷ⊥, x̂ × ŷ⊥].
#[inline]
pub(crate) fn frame_rotation(x0: V3, y0: V3, x: V3, y: V3) -> UnitQuaternion<f64> {
    let frame = |x: V3, y: V3| {
        let e1 = x.normalize();
        let e2 = (y - e1 * e1.dot(&y)).normalize();
        Matrix3::from_columns(&[e1, e2, e1.cross(&e2)])
    };
    let m = frame(x, y) * frame(x0, y0).transpose();
    UnitQuaternion::from_rotation_matrix(&Rotation3::from_matrix_unchecked(m))
}

/// The rotation of a rod between two spherical joints, A₀B₀ in the drawing and AB now,
/// with its idle spin fixed as `constraints::spin` fixes it (`constraints::spin_rotation`);
/// `Singular` with AB opposite A₀B₀ (the spin fix is then undefined).
#[inline]
fn rod(a0: V3, b0: V3, a: V3, b: V3) -> Result<UnitQuaternion<f64>, MechError> {
    constraints::spin_rotation(b0 - a0, b - a).ok_or(MechError::Singular {
        condition: f64::INFINITY,
    })
}

/// Which group, with its kernel.
#[derive(Clone, Debug)]
pub(crate) enum Group {
    Rssr(Rssr),
    Rssp(Rssp),
    RsspSlide(RsspSlide),
    Rsrc(Rsrc),
    Spherical(SphericalFourBar),
}

impl Group {
    /// The group's name (`RSSR`, `RSSP`, `RSRC`, `spherical four-bar`).
    pub fn name(&self) -> &'static str {
        match self {
            Group::Rssr(_) => "RSSR",
            Group::Rssp(_) => "RSSP",
            Group::RsspSlide(_) => "RSSP driven at its slide",
            Group::Rsrc(_) => "RSRC",
            Group::Spherical(_) => "spherical four-bar",
        }
    }
}

/// A mechanism recognised as one closed group: its kernel, the input's sense and the
/// bodies (crank, coupler, output) with their reference points in the drawing.
#[derive(Clone, Debug)]
pub(crate) struct Closed {
    pub group: Group,
    /// +1 when the input joint is (ground, crank), −1 when (crank, ground): the crank's
    /// rotation about the axis is ψ = sign · q (a sliding input's travel along its axis
    /// likewise).
    pub sign: f64,
    /// (crank, coupler, output) body indices (the crank: the input's body, the slider of
    /// an RSSP driven at its slide).
    pub bodies: [usize; 3],
    /// Their reference points o in the drawing.
    pub o0: [V3; 3],
}

/// The other joint of `body` than `not`, when it has exactly two.
fn next(model: &SpatialModel, body: usize, not: usize) -> Option<usize> {
    let mut js = (0..model.joints.len())
        .filter(|&j| j != not && (model.joints[j].a == body || model.joints[j].b == body));
    let j = js.next()?;
    js.next().is_none().then_some(j)
}

/// The joint's other body than `body`.
fn across(j: &Joint, body: usize) -> usize {
    if j.a == body {
        j.b
    } else {
        j.a
    }
}

impl Closed {
    /// The closed group `model` is, when its whole topology is exactly one: four bodies in
    /// one loop ground–R(input)–crank–…–output–ground with one revolute input at the ground,
    /// and joints S, S, R (RSSR), S, S, P (RSSP), S, R, C with the R axis ⊥ the C axis
    /// (RSRC), or R, R, R with all four axes through one point (spherical four-bar); or
    /// ground–P(input)–slider–S–rod–S–crank–R–ground (the RSSP driven at its slide); and
    /// the drawing not at a toggle of the group. `o0`: every body's reference point.
    pub fn recognise(model: &SpatialModel, o0: &[V3]) -> Option<Closed> {
        if model.bodies.len() != 4 || model.joints.len() != 4 || model.inputs.len() != 1 {
            return None;
        }
        let k0 = model.inputs[0];
        let j0 = &model.joints[k0];
        let (JointKind::Revolute { axis: u1 } | JointKind::Prismatic { axis: u1 }) = j0.kind else {
            return None;
        };
        let (crank, sign) = match (j0.a, j0.b) {
            (0, c) if c != 0 => (c, 1.0),
            (c, 0) => (c, -1.0),
            _ => return None,
        };
        let k1 = next(model, crank, k0)?;
        let coupler = across(&model.joints[k1], crank);
        let k2 = next(model, coupler, k1)?;
        let output = across(&model.joints[k2], coupler);
        let k3 = next(model, output, k2)?;
        if across(&model.joints[k3], output) != 0
            || next(model, 0, k0) != Some(k3)
            || [crank, coupler, output].contains(&0)
            || crank == coupler
            || coupler == output
            || crank == output
        {
            return None;
        }
        let p = |k: usize| model.points[model.joints[k].point].1;
        let (o, a0, b0, c0) = (p(k0), p(k1), p(k2), p(k3));
        use JointKind::{Cylindrical, Prismatic, Revolute, Spherical};
        if let Prismatic { .. } = j0.kind {
            // the RSSP driven at its slide: slider–S–rod–S–crank–R–ground
            let group = match (
                &model.joints[k1].kind,
                &model.joints[k2].kind,
                &model.joints[k3].kind,
            ) {
                (Spherical, Spherical, Revolute { axis }) => {
                    Group::RsspSlide(RsspSlide::new(c0, *axis, b0, u1, a0)?)
                }
                _ => return None,
            };
            return Some(Closed {
                group,
                sign,
                bodies: [crank, coupler, output],
                o0: [o0[crank], o0[coupler], o0[output]],
            });
        }
        let group = match (
            &model.joints[k1].kind,
            &model.joints[k2].kind,
            &model.joints[k3].kind,
        ) {
            (Spherical, Spherical, Revolute { axis }) => {
                Group::Rssr(Rssr::new(o, u1, a0, c0, *axis, b0)?)
            }
            (Spherical, Spherical, Prismatic { axis }) => {
                Group::Rssp(Rssp::new(o, u1, a0, *axis, b0)?)
            }
            (Spherical, Revolute { axis: v }, Cylindrical { axis: w }) => {
                Group::Rsrc(Rsrc::new(o, u1, a0, b0, *v, c0, *w)?)
            }
            (Revolute { axis: c1 }, Revolute { axis: c2 }, Revolute { axis: g2 }) => {
                Group::Spherical(SphericalFourBar::from_lines([
                    (o, u1),
                    (a0, *c1),
                    (b0, *c2),
                    (c0, *g2),
                ])?)
            }
            _ => return None,
        };
        Some(Closed {
            group,
            sign,
            bodies: [crank, coupler, output],
            o0: [o0[crank], o0[coupler], o0[output]],
        })
    }

    /// Every body's pose at the input value q (rad), in the model's order (the ground
    /// first, at rest; velocities zero): the crank turned by ψ = sign · q about its axis,
    /// the output by the kernel's closed form, the coupler carried by its two joints.
    pub fn positions(&self, q: f64) -> Result<[BodyState; 4], MechError> {
        let psi = self.sign * q;
        let [crank, coupler, output] = self.bodies;
        let [oc, ok, oo] = self.o0;
        let mut s = [BodyState::drawing(V3::zeros()); 4];
        let about = |p: V3, rot: UnitQuaternion<f64>, p0: V3, o0: V3| BodyState {
            o: p + rot * (o0 - p0),
            rot,
            v: V3::zeros(),
            w: V3::zeros(),
        };
        match &self.group {
            Group::Rssr(k) => {
                let (a, b, phi) = k.points(psi)?;
                s[crank] = about(k.centre, turn(k.axis, psi), k.centre, oc);
                s[output] = about(
                    k.rocker_centre,
                    turn(k.rocker_axis, phi),
                    k.rocker_centre,
                    oo,
                );
                s[coupler] = about(a, rod(k.a0, k.b0, a, b)?, k.a0, ok);
            }
            Group::Rssp(k) => {
                let (a, b, x) = k.points(psi)?;
                let g = &k.geometry;
                s[crank] = about(g.centre, turn(g.axis, psi), g.centre, oc);
                s[output] = BodyState::drawing(oo + g.slide * x);
                s[coupler] = about(a, rod(g.a0, g.b0, a, b)?, g.a0, ok);
            }
            Group::RsspSlide(k) => {
                // the input body is the slider, the output the crank
                let (a, b, phi) = k.points(psi)?;
                let g = &k.geometry;
                s[crank] = BodyState::drawing(oc + g.slide * psi);
                s[output] = about(g.centre, turn(g.axis, phi), g.centre, oo);
                s[coupler] = about(a, rod(g.a0, g.b0, a, b)?, g.a0, ok);
            }
            Group::Rsrc(k) => {
                let (a, b, theta, x) = k.points(psi)?;
                s[crank] = about(k.centre, turn(k.axis, psi), k.centre, oc);
                let out = turn(k.cylinder_axis, theta);
                s[output] = about(k.cylinder + k.cylinder_axis * x, out, k.cylinder, oo);
                let rot = frame_rotation(k.pin_axis, k.a0 - k.b0, out * k.pin_axis, a - b);
                s[coupler] = about(b, rot, k.b0, ok);
            }
            Group::Spherical(k) => {
                let (c1, c2, phi) = k.axes(psi)?;
                s[crank] = about(k.centre, turn(k.g1, psi), k.centre, oc);
                s[output] = about(k.centre, turn(k.g2, phi), k.centre, oo);
                s[coupler] = about(k.centre, frame_rotation(k.c1, k.c2, c1, c2), k.centre, ok);
            }
        }
        Ok(s)
    }
}

impl Closed {
    /// Every body's motion at (q, q̇, q̈) from the kernel's own rates, for the groups whose
    /// coupler is a rod between two balls (RSSR, RSSP): the crank turns about its axis
    /// (ω = ψ̇ u), the output about its axis (ω = φ̇ w) or along its guide (v = ṡ w), the rod
    /// is carried by its pins A and B, ω = d × (v_B − v_A)/|d|² + λ ê and
    /// α = d × (a_B − a_A − ω × (ω × d))/|d|² + μ ê (d = B − A), its rate along itself fixed
    /// by the spin row about its drawing axis `spin` (Φ̇ = 0, Φ̈ = 0: `constraints::spin`).
    /// `None` for the other groups (their rates come from the linear solves).
    pub fn motions(
        &self,
        q: f64,
        qd: f64,
        qdd: f64,
        spin: V3,
        out: &mut [BodyMotion],
    ) -> Option<Result<(), MechError>> {
        let (psi, psid, psidd) = (self.sign * q, self.sign * qd, self.sign * qdd);
        // the pins' motions, the crank's and the output's axes (a slider: no axis point)
        type Axis = (V3, V3, Option<V3>, f64, f64);
        let solved = |o: Result<Output, MechError>| o;
        let (pa, pb, crank, output): ([V3; 3], [V3; 3], Axis, Axis) = match &self.group {
            Group::Rssr(k) => {
                let o = match solved(k.solve(psi, psid, psidd)) {
                    Ok(o) => o,
                    Err(e) => return Some(Err(e)),
                };
                (
                    circle(k.centre, k.axis, k.a0, [psi, psid, psidd]),
                    circle(k.rocker_centre, k.rocker_axis, k.b0, [o.x, o.xd, o.xdd]),
                    (k.centre, k.axis, Some(k.centre), psid, psidd),
                    (
                        k.rocker_centre,
                        k.rocker_axis,
                        Some(k.rocker_centre),
                        o.xd,
                        o.xdd,
                    ),
                )
            }
            Group::Rssp(k) => {
                let o = match solved(k.solve(psi, psid, psidd)) {
                    Ok(o) => o,
                    Err(e) => return Some(Err(e)),
                };
                let g = &k.geometry;
                (
                    circle(g.centre, g.axis, g.a0, [psi, psid, psidd]),
                    [g.b0 + g.slide * o.x, g.slide * o.xd, g.slide * o.xdd],
                    (g.centre, g.axis, Some(g.centre), psid, psidd),
                    (g.b0, g.slide, None, o.xd, o.xdd),
                )
            }
            _ => return None,
        };
        Some(self.carried(q, pa, pb, [crank, output], spin, out))
    }

    /// The bodies' motions from the pins' and the two outer bodies' motions
    /// ([`Closed::motions`]).
    fn carried(
        &self,
        q: f64,
        pa: [V3; 3],
        pb: [V3; 3],
        outer: [(V3, V3, Option<V3>, f64, f64); 2],
        spin: V3,
        out: &mut [BodyMotion],
    ) -> Result<(), MechError> {
        let s = self.positions(q)?;
        let [crank, coupler, output] = self.bodies;
        if out.len() != s.len() {
            return Err(MechError::InvalidInput(format!(
                "{} motions for {} bodies",
                out.len(),
                s.len()
            )));
        }
        for (m, &state) in out.iter_mut().zip(&s) {
            *m = BodyMotion {
                state,
                ..BodyMotion::rest()
            };
        }
        for (body, (_, u, centre, xd, xdd)) in [crank, output].into_iter().zip(outer) {
            let m = &mut out[body];
            match centre {
                Some(c) => {
                    let (w, al, r) = (u * xd, u * xdd, m.state.o - c);
                    m.state.w = w;
                    m.state.v = w.cross(&r);
                    m.alpha = al;
                    m.a = al.cross(&r) + w.cross(&w.cross(&r));
                }
                None => {
                    m.state.v = u * xd;
                    m.a = u * xdd;
                }
            }
        }
        let [a, va, aa] = pa;
        let [b, vb, ab] = pb;
        let d = b - a;
        let (dd, e) = (d.norm_squared(), d.normalize());
        let rod = out[coupler].state;
        let along = |w: V3, perp: V3, extra: f64| -> Result<V3, MechError> {
            let row = constraints::spin(&BodyState { w, ..rod }, spin);
            let den = row.b[1].dot(&e);
            if !(den.abs() > 1e-12 * row.b[1].norm()) {
                return Err(MechError::Singular {
                    condition: f64::INFINITY,
                });
            }
            Ok(perp + e * (-(row.b[1].dot(&perp) + extra * row.gamma) / den))
        };
        let w_perp = d.cross(&(vb - va)) / dd;
        let w = along(w_perp, w_perp, 0.0)?;
        let al_perp = d.cross(&(ab - aa - w.cross(&w.cross(&d)))) / dd;
        let al = along(w, al_perp, 1.0)?;
        let r = rod.o - a;
        let m = &mut out[coupler];
        m.state.w = w;
        m.state.v = va + w.cross(&r);
        m.alpha = al;
        m.a = aa + al.cross(&r) + w.cross(&w.cross(&r));
        // an overflow (rates near f64's limit) is refused as the linear solves refuse it
        let finite = out.iter().all(|m| {
            let st = &m.state;
            [st.v, st.w, m.a, m.alpha]
                .iter()
                .all(|v| v.iter().all(|x| x.is_finite()))
        });
        if finite {
            Ok(())
        } else {
            Err(MechError::Singular {
                condition: f64::INFINITY,
            })
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Both roots of `dot_angle` and `travel` satisfy their equations (1e-15), and out of
    /// reach is `NoAssembly`.
    #[test]
    fn the_two_scalar_equations_are_solved_on_both_branches() {
        let g = V3::new(0.3, -0.4, 0.8).normalize();
        let (x, y0) = (V3::new(0.5, 0.2, -0.1), V3::new(-0.2, 0.7, 0.4));
        let c = 0.1;
        for sign in [1.0, -1.0] {
            let phi = dot_angle(x, g, y0, c, sign).unwrap();
            assert!((x.dot(&(turn(g, phi) * y0)) - c).abs() < 1e-15, "{sign}");
        }
        assert!(matches!(
            dot_angle(x, g, y0, 1.0, 1.0),
            Err(MechError::NoAssembly)
        ));
        let (m, w, l) = (
            V3::new(0.2, -0.1, 0.3),
            V3::new(1.0, 2.0, -0.5).normalize(),
            0.5,
        );
        for sign in [1.0, -1.0] {
            let s = travel(m, w, l, sign).unwrap();
            assert!(((m - w * s).norm() - l).abs() < 1e-15, "{sign}");
        }
        assert!(matches!(
            travel(m, w, 0.01, 1.0),
            Err(MechError::NoAssembly)
        ));
        assert!(matches!(
            dot_angle(x, g, y0, f64::NAN, 1.0),
            Err(MechError::NoAssembly)
        ));
    }

    /// The spin fix's rotation takes e to the current axis with its vector part ⊥ e;
    /// `frame_rotation` takes both drawing vectors to the current ones.
    #[test]
    fn the_couplers_rotations_take_the_drawing_to_the_current_axes() {
        let e = V3::new(0.25, -0.03, 0.08);
        let now = V3::new(0.1, 0.2, -0.15).normalize() * e.norm();
        let r = constraints::spin_rotation(e, now).unwrap();
        assert!((r * e - now).norm() < 1e-16 && r.quaternion().imag().dot(&e).abs() < 1e-17);
        assert!(constraints::spin_rotation(e, -e).is_none());
        let turn_it = turn(V3::new(0.2, 0.5, -0.3).normalize(), 2.1);
        let (x0, y0) = (V3::new(0.3, 0.1, 0.0), V3::new(-0.1, 0.4, 0.2));
        let f = frame_rotation(x0, y0, turn_it * x0, turn_it * y0);
        assert!(f.angle_to(&turn_it) < 1e-15);
    }
}
