//! The RSSP group in closed form: a crank (revolute input) and a slider (prismatic output)
//! joined by a rod between two spherical joints.
//!
//! The crank pin A turns about the input's axis (c₁, u₁) by ψ, the slider's pin moves along
//! the guide, B = B₀ + s w (w unit), and the rod keeps its length L = |B₀ − A₀|:
//! |A − B₀ − s w| = L, a quadratic in the travel s (m, 0 in the drawing):
//! s² − 2 s w·m + |m|² − L² = 0 with m = A − B₀, s = w·m + σ √((w·m)² − |m|² + L²)
//! (`travel`). **Branch rule**: σ is the sign whose root is s = 0 at ψ = 0, fixed at
//! construction (σ = sign of w·(A₀ − B₀); a drawing with the rod ⊥ the guide, both roots
//! equal, is refused). Rates from |B − A| constant (`keep_length`): with r = A − B,
//! ṡ = r·Ȧ / r·w, s̈ = (ṙ·ṙ + r·Ä) / r·w.
//!
//! Driven at its slide (`RsspSlide`), the same length gives the crank's rotation ψ (rad,
//! (−π, π], 0 in the drawing) at the travel s: with B = B₀ + s w, d = B − c₁ and
//! a = A₀ − c₁, the Freudenstein-type equation d·Rot(u₁, ψ) a = (|d|² + |a|² − L²)/2
//! (`dot_angle`). **Branch rule**: its σ is the sign whose root is ψ = 0 at s = 0, fixed at
//! construction (a drawing with the rod ⊥ the pin's path is refused). Rates
//! (`keep_length`): with r = A − B and t = u₁ × (A − c₁), ṙ = ψ̇ t − ṡ w.

use super::{circle, dot_angle, keep_length, travel, turn, Output};
use crate::MechError;
use nalgebra::Vector3;

type V3 = Vector3<f64>;

/// The geometry both RSSP kernels share (all points in the drawing, m; axes unit).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RsspGeometry {
    /// A point of the crank's axis (m).
    pub centre: V3,
    /// The crank's axis (unit).
    pub axis: V3,
    /// The crank pin A in the drawing (m).
    pub a0: V3,
    /// The guide's direction w (unit).
    pub slide: V3,
    /// The slider's pin B in the drawing (m).
    pub b0: V3,
    /// The rod's length |B₀ − A₀| (m).
    pub length: f64,
}

impl RsspGeometry {
    /// The crank's axis (`centre`, `axis`) with pin `a0`, the guide `slide` and the
    /// slider's pin `b0`; directions normalised here (`None` for a zero one).
    pub fn new(centre: V3, axis: V3, a0: V3, slide: V3, b0: V3) -> Option<Self> {
        Some(RsspGeometry {
            centre,
            axis: axis.try_normalize(0.0)?,
            a0,
            slide: slide.try_normalize(0.0)?,
            b0,
            length: (b0 - a0).norm(),
        })
    }
}

/// An RSSP's closed form, driven at its crank.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Rssp {
    /// The crank, the guide and the rod.
    pub geometry: RsspGeometry,
    /// The branch σ = ±1 (module doc).
    pub sign: f64,
}

impl Rssp {
    /// The RSSP of the input axis (`centre`, `axis`) with pin `a0`, the guide `slide` and
    /// the slider's pin `b0`; directions normalised here. `None` when the drawing is at a
    /// toggle (the rod ⊥ the guide).
    pub fn new(centre: V3, axis: V3, a0: V3, slide: V3, b0: V3) -> Option<Self> {
        let geometry = RsspGeometry::new(centre, axis, a0, slide, b0)?;
        let k = Rssp {
            geometry,
            sign: 1.0,
        };
        let sign = super::branch(|s| Self { sign: s, ..k }.travel(0.0), geometry.length)?;
        Some(Rssp { sign, ..k })
    }

    /// The slider's travel s along w (m, 0 in the drawing) at the crank's rotation ψ (rad);
    /// `NoAssembly` where the rod cannot reach the guide.
    #[inline]
    pub fn travel(&self, psi: f64) -> Result<f64, MechError> {
        Ok(self.points(psi)?.2)
    }

    /// (A, B, s) at ψ: the pins (m) and the travel (m).
    #[inline]
    pub fn points(&self, psi: f64) -> Result<(V3, V3, f64), MechError> {
        let a = circle(
            self.geometry.centre,
            self.geometry.axis,
            self.geometry.a0,
            [psi, 0.0, 0.0],
        )[0];
        let s = travel(
            a - self.geometry.b0,
            self.geometry.slide,
            self.geometry.length,
            self.sign,
        )?;
        Ok((a, self.geometry.b0 + self.geometry.slide * s, s))
    }

    /// s, ṡ, s̈ at (ψ, ψ̇, ψ̈) (m, m/s, m/s²); `Singular` with the rod ⊥ the guide.
    #[inline]
    pub fn solve(&self, psi: f64, psid: f64, psidd: f64) -> Result<Output, MechError> {
        let (_, b, s) = self.points(psi)?;
        let [a, ad, add] = circle(
            self.geometry.centre,
            self.geometry.axis,
            self.geometry.a0,
            [psi, psid, psidd],
        );
        let (xd, xdd) = keep_length(a - b, ad, add, self.geometry.slide, V3::zeros())?;
        Ok(Output { x: s, xd, xdd })
    }
}

/// An RSSP driven at its slide, in closed form: the crank's rotation from the slider's
/// travel (module doc).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RsspSlide {
    /// The crank, the guide (the input's axis) and the rod.
    pub geometry: RsspGeometry,
    /// The branch σ = ±1 (module doc).
    pub sign: f64,
}

impl RsspSlide {
    /// The RSSP of the crank's axis (`centre`, `axis`) with pin `a0`, driven along `slide`
    /// at the slider's pin `b0`; directions normalised here. `None` when the drawing is at
    /// a toggle (the rod ⊥ the pin's path).
    pub fn new(centre: V3, axis: V3, a0: V3, slide: V3, b0: V3) -> Option<Self> {
        let k = RsspSlide {
            geometry: RsspGeometry::new(centre, axis, a0, slide, b0)?,
            sign: 1.0,
        };
        let sign = super::branch(|s| Self { sign: s, ..k }.angle(0.0), 1.0)?;
        Some(RsspSlide { sign, ..k })
    }

    /// The crank's rotation ψ (rad, (−π, π], 0 in the drawing) at the travel s (m);
    /// `NoAssembly` where the rod cannot reach the crank's circle.
    #[inline]
    pub fn angle(&self, s: f64) -> Result<f64, MechError> {
        Ok(self.points(s)?.2)
    }

    /// (A, B, ψ) at s: the pins (m) and the crank's rotation (rad).
    #[inline]
    pub fn points(&self, s: f64) -> Result<(V3, V3, f64), MechError> {
        let b = self.geometry.b0 + self.geometry.slide * s;
        let (d, a) = (
            b - self.geometry.centre,
            self.geometry.a0 - self.geometry.centre,
        );
        let c = 0.5
            * (d.norm_squared() + a.norm_squared() - self.geometry.length * self.geometry.length);
        let psi = dot_angle(d, self.geometry.axis, a, c, self.sign)?;
        Ok((
            self.geometry.centre + turn(self.geometry.axis, psi) * a,
            b,
            psi,
        ))
    }

    /// ψ, ψ̇, ψ̈ at (s, ṡ, s̈) (rad, rad/s, rad/s²); `Singular` with the rod ⊥ the pin's
    /// path (the crank at a dead point).
    #[inline]
    pub fn solve(&self, s: f64, sd: f64, sdd: f64) -> Result<Output, MechError> {
        let (a, b, psi) = self.points(s)?;
        let t = self.geometry.axis.cross(&(a - self.geometry.centre));
        // r = A − B: ṙ = −ṡ w − ψ̇ (−t), r̈ = −s̈ w − ψ̈ (−t) − ψ̇² (−u₁ × t)
        let (xd, xdd) = keep_length(
            a - b,
            -self.geometry.slide * sd,
            -self.geometry.slide * sdd,
            -t,
            -self.geometry.axis.cross(&t),
        )?;
        Ok(Output { x: psi, xd, xdd })
    }
}
