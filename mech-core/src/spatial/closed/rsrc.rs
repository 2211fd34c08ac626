//! The RSRC group in closed form: a crank (revolute input), a coupler on a spherical joint
//! at the crank pin, pinned by a revolute to an output that turns about and slides along a
//! cylindrical joint at the ground; the pin's axis perpendicular to the cylinder's.
//!
//! The crank pin A turns about the input's axis (c₁, u₁) by ψ; the output turns by θ about
//! the cylinder's axis (C, w) and slides s along it, carrying the pin B = C + s w +
//! Rot(w, θ)(B₀ − C) and its axis v = Rot(w, θ) v₀ (v₀ ⊥ w); the coupler turns about v, so
//! A keeps its height along v above B, (A − B)·v = (A₀ − B₀)·v₀, and its distance
//! L = |A₀ − B₀|. The slide drops out of the first (v ⊥ w):
//! (A − C)·Rot(w, θ) v₀ = (A₀ − C)·v₀, a Freudenstein equation P cos θ + Q sin θ = R in the
//! rotation θ (rad, (−π, π], `dot_angle`); then |A − B| = L is a quadratic in the slide s
//! (m): s = w·m + σ₂ √((w·m)² − |m|² + L²), m = A − C − Rot(w, θ)(B₀ − C) (`travel`).
//! **Branch rule**: σ₁ (of θ) and then σ₂ (of s) are the signs whose roots are θ = 0 and
//! s = 0 at ψ = 0, fixed at construction (a drawing at a toggle of either is refused).
//! Rates: θ̇, θ̈ from (A − C)·v constant (`keep_dot`), then ṡ, s̈ from |A − B| constant
//! (`keep_length`) with Ḃ = ṡ w + θ̇ k, k = w × (B − C). With a pin axis not ⊥ the
//! cylinder's the two equations make a quartic: not taken here (Newton solves it).

use super::{circle, dot_angle, keep_dot, keep_length, travel, turn, Output};
use crate::MechError;
use nalgebra::Vector3;

type V3 = Vector3<f64>;

/// An RSRC's closed form (all points in the drawing, m; axes unit).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Rsrc {
    /// A point of the input's axis (m).
    pub centre: V3,
    /// The input's axis (unit).
    pub axis: V3,
    /// The crank pin A (the spherical joint) in the drawing (m).
    pub a0: V3,
    /// The coupler–output revolute's point B in the drawing (m).
    pub b0: V3,
    /// Its axis v₀ (unit, ⊥ `cylinder_axis`).
    pub pin_axis: V3,
    /// A point C of the cylinder's axis (m).
    pub cylinder: V3,
    /// The cylinder's axis w (unit).
    pub cylinder_axis: V3,
    /// |A₀ − B₀| (m).
    pub length: f64,
    /// The branches (σ₁ of θ, σ₂ of s).
    pub sign: [f64; 2],
}

impl Rsrc {
    /// The RSRC of the input axis (`centre`, `axis`) with pin `a0`, the revolute at `b0`
    /// about `pin_axis`, the cylinder through `cylinder` along `cylinder_axis`; axes
    /// normalised here. `None` when the pin's axis is not ⊥ the cylinder's (to 1e-12), A₀
    /// is on the pin's axis, or the drawing is at a toggle.
    pub fn new(
        centre: V3,
        axis: V3,
        a0: V3,
        b0: V3,
        pin_axis: V3,
        cylinder: V3,
        cylinder_axis: V3,
    ) -> Option<Self> {
        let (v, w) = (
            pin_axis.try_normalize(0.0)?,
            cylinder_axis.try_normalize(0.0)?,
        );
        if v.dot(&w).abs() > 1e-12 || (a0 - b0).cross(&v).norm() <= 1e-9 * (a0 - b0).norm() {
            return None;
        }
        let mut k = Rsrc {
            centre,
            axis: axis.try_normalize(0.0)?,
            a0,
            b0,
            pin_axis: v,
            cylinder,
            cylinder_axis: w,
            length: (a0 - b0).norm(),
            sign: [1.0, 1.0],
        };
        k.sign[0] = super::branch(
            |s| {
                Self {
                    sign: [s, 1.0],
                    ..k
                }
                .rotation(0.0)
            },
            1.0,
        )?;
        let s0 = k.sign[0];
        k.sign[1] = super::branch(
            |s| Self { sign: [s0, s], ..k }.points(0.0).map(|p| p.3),
            k.length,
        )?;
        Some(k)
    }

    /// The output's rotation θ about the cylinder (rad, (−π, π], 0 in the drawing) at the
    /// crank's rotation ψ (rad); `NoAssembly` where it cannot assemble.
    #[inline]
    pub fn rotation(&self, psi: f64) -> Result<f64, MechError> {
        self.rotation_at(circle(self.centre, self.axis, self.a0, [psi, 0.0, 0.0])[0])
    }

    /// θ with the crank pin at `a`.
    #[inline]
    fn rotation_at(&self, a: V3) -> Result<f64, MechError> {
        let c = (self.a0 - self.cylinder).dot(&self.pin_axis);
        dot_angle(
            a - self.cylinder,
            self.cylinder_axis,
            self.pin_axis,
            c,
            self.sign[0],
        )
    }

    /// (A, B, θ, s) at ψ: the pins (m), the rotation (rad) and the slide (m).
    #[inline]
    pub fn points(&self, psi: f64) -> Result<(V3, V3, f64, f64), MechError> {
        let a = circle(self.centre, self.axis, self.a0, [psi, 0.0, 0.0])[0];
        let theta = self.rotation_at(a)?;
        let turned = self.cylinder + turn(self.cylinder_axis, theta) * (self.b0 - self.cylinder);
        let s = travel(a - turned, self.cylinder_axis, self.length, self.sign[1])?;
        Ok((a, turned + self.cylinder_axis * s, theta, s))
    }

    /// (θ, θ̇, θ̈) and (s, ṡ, s̈) at (ψ, ψ̇, ψ̈) (rad, m and their rates); `Singular` at a dead
    /// point of either.
    #[inline]
    pub fn solve(&self, psi: f64, psid: f64, psidd: f64) -> Result<[Output; 2], MechError> {
        let (_, b, theta, s) = self.points(psi)?;
        let [a, ad, add] = circle(self.centre, self.axis, self.a0, [psi, psid, psidd]);
        let w = self.cylinder_axis;
        let v = turn(w, theta) * self.pin_axis;
        let (td, tdd) = keep_dot(a - self.cylinder, ad, add, v, w)?;
        let k = w.cross(&(b - self.cylinder));
        let (sd, sdd) = keep_length(
            a - b,
            ad - k * td,
            add - k * tdd - w.cross(&k) * (td * td),
            w,
            V3::zeros(),
        )?;
        Ok([
            Output {
                x: theta,
                xd: td,
                xdd: tdd,
            },
            Output {
                x: s,
                xd: sd,
                xdd: sdd,
            },
        ])
    }
}
