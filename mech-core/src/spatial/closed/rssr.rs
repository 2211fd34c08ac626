//! The RSSR group in closed form: a crank (revolute input) and a rocker (revolute output)
//! joined by a rod between two spherical joints.
//!
//! The crank pin A turns about the input's axis (c₁, u₁) by ψ, the rocker pin B about the
//! output's axis (c₂, u₂) by φ, and the rod keeps its length L = |B₀ − A₀| (m):
//! |B(φ) − A(ψ)|² = L². With d = c₂ − A and b = B₀ − c₂ this is the Freudenstein-type
//! equation d·Rot(u₂, φ) b = (L² − |d|² − |b|²)/2, i.e. P cos φ + Q sin φ = R with
//! P = d·b⊥, Q = d·(u₂ × b⊥), R = (L² − |d|² − |b|²)/2 − (d·u₂)(b·u₂) (`dot_angle`), solved
//! φ = atan2(Q, P) + σ acos(R / √(P² + Q²)) (rad, wrapped to (−π, π], 0 in the drawing).
//! **Branch rule**: σ is the sign whose root is φ = 0 at ψ = 0, fixed at construction (a
//! drawing at a toggle, both roots equal, is refused). Rates from |B − A| constant
//! (`keep_length`): with r = A − B and t = u₂ × (B − c₂), φ̇ = r·Ȧ / r·t,
//! φ̈ = (ṙ·ṙ + r·Ä − φ̇² r·(u₂ × t)) / r·t.

use super::{circle, dot_angle, keep_length, turn, Output};
use crate::MechError;
use nalgebra::Vector3;

type V3 = Vector3<f64>;

/// An RSSR's closed form (all points in the drawing, m; axes unit).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Rssr {
    /// A point of the input's axis (m).
    pub centre: V3,
    /// The input's axis (unit).
    pub axis: V3,
    /// The crank pin A in the drawing (m).
    pub a0: V3,
    /// A point of the output's axis (m).
    pub rocker_centre: V3,
    /// The output's axis (unit).
    pub rocker_axis: V3,
    /// The rocker pin B in the drawing (m).
    pub b0: V3,
    /// The rod's length |B₀ − A₀| (m).
    pub length: f64,
    /// The branch σ = ±1 (module doc).
    pub sign: f64,
}

impl Rssr {
    /// The RSSR of the input axis (`centre`, `axis`) with pin `a0` and the output axis
    /// (`rocker_centre`, `rocker_axis`) with pin `b0`; axes normalised here. `None` when the
    /// drawing is at a toggle (or a pin on its axis).
    pub fn new(
        centre: V3,
        axis: V3,
        a0: V3,
        rocker_centre: V3,
        rocker_axis: V3,
        b0: V3,
    ) -> Option<Self> {
        let mut k = Rssr {
            centre,
            axis: axis.try_normalize(0.0)?,
            a0,
            rocker_centre,
            rocker_axis: rocker_axis.try_normalize(0.0)?,
            b0,
            length: (b0 - a0).norm(),
            sign: 1.0,
        };
        k.sign = super::branch(|s| Self { sign: s, ..k }.angle(0.0), 1.0)?;
        Some(k)
    }

    /// The rocker's angle φ (rad, (−π, π], 0 in the drawing) at the crank's rotation ψ
    /// (rad from the drawing); `NoAssembly` where the rod cannot reach.
    #[inline]
    pub fn angle(&self, psi: f64) -> Result<f64, MechError> {
        self.angle_at(self.pin(psi))
    }

    /// The crank pin A at ψ (m).
    #[inline]
    fn pin(&self, psi: f64) -> V3 {
        circle(self.centre, self.axis, self.a0, [psi, 0.0, 0.0])[0]
    }

    /// φ with the crank pin at `a`.
    #[inline]
    fn angle_at(&self, a: V3) -> Result<f64, MechError> {
        let (d, b) = (self.rocker_centre - a, self.b0 - self.rocker_centre);
        let c = 0.5 * (self.length * self.length - d.norm_squared() - b.norm_squared());
        dot_angle(d, self.rocker_axis, b, c, self.sign)
    }

    /// (A, B, φ) at ψ: the pins (m) and the rocker's angle (rad).
    #[inline]
    pub fn points(&self, psi: f64) -> Result<(V3, V3, f64), MechError> {
        let a = self.pin(psi);
        let phi = self.angle_at(a)?;
        let b = self.rocker_centre + turn(self.rocker_axis, phi) * (self.b0 - self.rocker_centre);
        Ok((a, b, phi))
    }

    /// φ, φ̇, φ̈ at (ψ, ψ̇, ψ̈) (rad, rad/s, rad/s²); `Singular` at a dead point of the rocker
    /// (the rod ⊥ B's path).
    #[inline]
    pub fn solve(&self, psi: f64, psid: f64, psidd: f64) -> Result<Output, MechError> {
        let (_, b, phi) = self.points(psi)?;
        let [a, ad, add] = circle(self.centre, self.axis, self.a0, [psi, psid, psidd]);
        let t = self.rocker_axis.cross(&(b - self.rocker_centre));
        let (xd, xdd) = keep_length(a - b, ad, add, t, self.rocker_axis.cross(&t))?;
        Ok(Output { x: phi, xd, xdd })
    }
}
