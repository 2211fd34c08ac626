//! The spherical four-bar in closed form: four revolutes whose axes meet at one point O.
//!
//! Every link turns about O, so each joint is its unit axis: the ground's g₁ (the input)
//! and g₂ (the output), the crank–coupler axis c₁ = Rot(g₁, ψ) c₁₀ and the coupler–rocker
//! axis c₂ = Rot(g₂, φ) c₂₀. The coupler keeps the angle between its two axes, the
//! spherical Freudenstein equation c₁·Rot(g₂, φ) c₂₀ = c₁₀·c₂₀ (= cos of the coupler's
//! arc), P cos φ + Q sin φ = R with P = c₁·c₂⊥, Q = c₁·(g₂ × c₂⊥),
//! R = c₁₀·c₂₀ − (c₁·g₂)(c₂₀·g₂) (`dot_angle`), solved for the rocker's angle φ (rad,
//! (−π, π], 0 in the drawing; the axes dimensionless). **Branch rule**: σ is the sign whose
//! root is φ = 0 at ψ = 0, fixed at construction (a drawing at a toggle is refused).
//! Rates from c₁·c₂ constant (`keep_dot`): φ̇ = −ċ₁·c₂ / c₁·t,
//! φ̈ = −(c̈₁·c₂ + 2 φ̇ ċ₁·t + φ̇² c₁·(g₂ × t)) / c₁·t, t = g₂ × c₂.
//!
//! Four revolutes in space count G = −2 by Kutzbach's formula (three of their equations
//! repeat the others'), so the mechanism is loaded with `#[allow(redundant)]`.

use super::{circle, dot_angle, keep_dot, turn, Output};
use crate::MechError;
use nalgebra::Vector3;

type V3 = Vector3<f64>;

/// A spherical four-bar's closed form (the centre in m, the axes unit).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SphericalFourBar {
    /// The point O where the four axes meet (m).
    pub centre: V3,
    /// The input's axis g₁ (ground–crank).
    pub g1: V3,
    /// The crank–coupler axis c₁₀ in the drawing.
    pub c1: V3,
    /// The coupler–rocker axis c₂₀ in the drawing.
    pub c2: V3,
    /// The output's axis g₂ (rocker–ground).
    pub g2: V3,
    /// The branch σ = ±1 (module doc).
    pub sign: f64,
}

impl SphericalFourBar {
    /// The four-bar of the axes g₁, c₁₀, c₂₀, g₂ through `centre` (normalised here). `None`
    /// when an axis is zero, two neighbours are parallel or the drawing is at a toggle.
    pub fn new(centre: V3, g1: V3, c1: V3, c2: V3, g2: V3) -> Option<Self> {
        let [g1, c1, c2, g2] = [g1, c1, c2, g2].map(|v| v.try_normalize(0.0));
        let mut k = SphericalFourBar {
            centre,
            g1: g1?,
            c1: c1?,
            c2: c2?,
            g2: g2?,
            sign: 1.0,
        };
        let pairs = [(k.g1, k.c1), (k.c1, k.c2), (k.c2, k.g2), (k.g2, k.g1)];
        if pairs.iter().any(|(x, y)| x.cross(y).norm() < 1e-9) {
            return None;
        }
        k.sign = super::branch(|s| Self { sign: s, ..k }.angle(0.0), 1.0)?;
        Some(k)
    }

    /// The four-bar of four joint lines (a point, an axis) in the loop's order
    /// (ground–crank, crank–coupler, coupler–rocker, rocker–ground), when the four lines
    /// meet at one point (each within 1e-9 of the drawing's size of the point where the
    /// first and the last meet).
    pub fn from_lines(lines: [(V3, V3); 4]) -> Option<Self> {
        let [(p1, u1), _, _, (p4, u4)] = lines;
        let (u1, u4) = (u1.try_normalize(0.0)?, u4.try_normalize(0.0)?);
        // the point of line 1 nearest line 4: p₁ + t u₁ with (p₁ + t u₁ − p₄) ⊥ u₄ × (u₁ × u₄)
        let n = u1.cross(&u4);
        if n.norm() < 1e-9 {
            return None;
        }
        let m = u4.cross(&n);
        let centre = p1 + u1 * ((p4 - p1).dot(&m) / u1.dot(&m));
        let scale = lines.iter().map(|(p, _)| p.norm()).fold(1e-3, f64::max);
        for (p, u) in lines {
            let u = u.try_normalize(0.0)?;
            let off = centre - p;
            if (off - u * off.dot(&u)).norm() > 1e-9 * scale {
                return None;
            }
        }
        Self::new(centre, u1, lines[1].1, lines[2].1, u4)
    }

    /// The rocker's angle φ (rad, (−π, π], 0 in the drawing) at the crank's rotation ψ
    /// (rad); `NoAssembly` where it cannot assemble.
    #[inline]
    pub fn angle(&self, psi: f64) -> Result<f64, MechError> {
        Ok(self.axes(psi)?.2)
    }

    /// (c₁, c₂, φ) at ψ: the moving axes (unit) and the rocker's angle (rad).
    #[inline]
    pub fn axes(&self, psi: f64) -> Result<(V3, V3, f64), MechError> {
        let c1 = turn(self.g1, psi) * self.c1;
        let phi = dot_angle(c1, self.g2, self.c2, self.c1.dot(&self.c2), self.sign)?;
        Ok((c1, turn(self.g2, phi) * self.c2, phi))
    }

    /// φ, φ̇, φ̈ at (ψ, ψ̇, ψ̈) (rad, rad/s, rad/s²); `Singular` at a dead point of the rocker.
    #[inline]
    pub fn solve(&self, psi: f64, psid: f64, psidd: f64) -> Result<Output, MechError> {
        let (_, c2, phi) = self.axes(psi)?;
        let [c1, c1d, c1dd] = circle(V3::zeros(), self.g1, self.c1, [psi, psid, psidd]);
        let (xd, xdd) = keep_dot(c1, c1d, c1dd, c2, self.g2)?;
        Ok(Output { x: phi, xd, xdd })
    }
}
