//! The four-bar every synthesis method returns: ground pivots O2 and O4, the crank pin A,
//! the coupler–rocker pin B and the coupler point P, drawn at the crank's angle θ₀; the
//! input is the crank O2 → A. It moves by the closed form of its RRR dyad
//! (`kernel::dyad::circle_circle`): at crank angle θ, A = O2 + r₂ (cos θ, sin θ), B on the
//! circles (A, r₃) and (O4, r₄) on the drawing's side of the line A → O4 (the assembly
//! branch, kept over the cycle), and P = A + u e + v perp(e), e = (B − A)/r₃, with (u, v)
//! the coupler point in the coupler's frame.
//!
//! It writes itself as an ordinary mechanism file ([`FourBar::to_mech`]) with the names of
//! SPEC §3f: `O2`, `O4`, `A`, `B`, `P`, input `O2`.

use crate::kernel::dyad::circle_circle;
use crate::kernel::link_state::{cross, perp, V2};

/// A four-bar with a coupler point, in the drawing, m.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FourBar {
    /// The crank's ground pivot.
    pub o2: [f64; 2],
    /// The rocker's ground pivot.
    pub o4: [f64; 2],
    /// The crank pin.
    pub a: [f64; 2],
    /// The coupler–rocker pin.
    pub b: [f64; 2],
    /// The coupler point.
    pub p: [f64; 2],
}

/// The positions of the moving points at one crank angle, m.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FourBarPose {
    /// A.
    pub a: [f64; 2],
    /// B.
    pub b: [f64; 2],
    /// P.
    pub p: [f64; 2],
}

fn v(p: [f64; 2]) -> V2 {
    V2::new(p[0], p[1])
}

fn arr(x: V2) -> [f64; 2] {
    [x.x, x.y]
}

impl FourBar {
    /// The link lengths (r₁ frame O2O4, r₂ crank O2A, r₃ coupler AB, r₄ rocker O4B), m.
    pub fn lengths(&self) -> [f64; 4] {
        let d = |a: [f64; 2], b: [f64; 2]| (v(b) - v(a)).norm();
        [
            d(self.o2, self.o4),
            d(self.o2, self.a),
            d(self.a, self.b),
            d(self.o4, self.b),
        ]
    }

    /// Grashof's condition s + l ≤ p + q: some link turns fully relative to the others.
    pub fn grashof(&self) -> bool {
        let mut r = self.lengths();
        r.sort_by(f64::total_cmp);
        r[0] + r[3] <= r[1] + r[2]
    }

    /// Whether the crank turns fully: Grashof with the crank (or the frame) the shortest
    /// link.
    pub fn crank_turns(&self) -> bool {
        let r = self.lengths();
        let shortest = r.iter().copied().fold(f64::INFINITY, f64::min);
        self.grashof() && (r[1] == shortest || r[0] == shortest)
    }

    /// The crank's drawn angle θ₀ (rad): the direction of O2 → A.
    pub fn drawn_angle(&self) -> f64 {
        let d = v(self.a) - v(self.o2);
        d.y.atan2(d.x)
    }

    /// The side of B from the line A → O4 in the drawing (±1): the assembly branch.
    pub fn branch(&self) -> f64 {
        let s = cross(v(self.o4) - v(self.a), v(self.b) - v(self.a));
        if s >= 0.0 {
            1.0
        } else {
            -1.0
        }
    }

    /// The coupler point in the coupler's frame (u along A → B, v across), m.
    pub fn coupler_frame(&self) -> [f64; 2] {
        let e = (v(self.b) - v(self.a)).normalize();
        let d = v(self.p) - v(self.a);
        [d.dot(&e), d.dot(&perp(e))]
    }

    /// The pose at crank angle θ (rad, the direction of O2 → A) on the drawing's branch;
    /// `None` where it does not assemble.
    pub fn pose(&self, theta: f64) -> Option<FourBarPose> {
        let [_, r2, r3, r4] = self.lengths();
        let [u, w] = self.coupler_frame();
        let a = v(self.o2) + V2::new(theta.cos(), theta.sin()) * r2;
        // circle_circle's side is that of the line c1 → c2 = A → O4.
        let b = circle_circle(a, r3 * r3, v(self.o4), r4 * r4, self.branch()).ok()?;
        let e = (b - a) / r3;
        Some(FourBarPose {
            a: arr(a),
            b: arr(b),
            p: arr(a + e * u + perp(e) * w),
        })
    }

    /// P at `n` even crank angles over a turn from the drawn one (`None` where it does not
    /// assemble).
    pub fn coupler_curve(&self, n: usize) -> Vec<Option<[f64; 2]>> {
        let t0 = self.drawn_angle();
        (0..n)
            .map(|k| {
                self.pose(t0 + std::f64::consts::TAU * k as f64 / n as f64)
                    .map(|p| p.p)
            })
            .collect()
    }

    /// The transmission angle μ at crank angle θ (rad, in [0, π]): the angle between the
    /// coupler B − A and the rocker B − O4; `None` where it does not assemble.
    pub fn transmission_angle(&self, theta: f64) -> Option<f64> {
        let p = self.pose(theta)?;
        let (c, r) = (v(p.b) - v(p.a), v(p.b) - v(self.o4));
        Some(cross(c, r).abs().atan2(c.dot(&r)))
    }

    /// The four-bar as a mechanism file (the names of SPEC §3f), `name` the struct's,
    /// `doc` its doc line. Coordinates in metres, written to round-trip.
    pub fn to_mech(&self, name: &str, doc: &str) -> String {
        let p = |x: [f64; 2]| format!("({:?}, {:?})", x[0], x[1]);
        format!(
            "/// {doc}\npub struct {name} {{\n    ground {{ O2: {}, O4: {} }},\n    link crank {{ points {{ O2, A: {} }} }},\n    link coupler {{ points {{ A, B: {}, P: {} }} }},\n    link rocker {{ points {{ O4, B }} }},\n    joints {{\n        O2: revolute(ground, crank),\n        A: revolute(crank, coupler),\n        B: revolute(coupler, rocker),\n        O4: revolute(ground, rocker),\n    }},\n    input: O2,\n}}\n",
            p(self.o2),
            p(self.o4),
            p(self.a),
            p(self.b),
            p(self.p)
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A crank-rocker: the drawn pose comes back at θ₀; every pose keeps the lengths; the
    /// file loads with the same coupler curve at the run-time mechanism's input angles.
    #[test]
    fn the_closed_form_keeps_the_links_and_the_branch() {
        let fb = FourBar {
            o2: [0.0, 0.0],
            o4: [0.3, 0.0],
            a: [0.0, 0.1],
            b: [0.25, 0.2],
            p: [0.1, 0.3],
        };
        assert!(fb.grashof() && fb.crank_turns());
        let p0 = fb.pose(fb.drawn_angle()).unwrap();
        for (x, y) in [(p0.b, fb.b), (p0.p, fb.p)] {
            assert!((x[0] - y[0]).abs() < 1e-15 && (x[1] - y[1]).abs() < 1e-15);
        }
        let r = fb.lengths();
        for k in 0..36 {
            let t = k as f64 * 10f64.to_radians();
            let p = fb.pose(t).unwrap();
            let d = |a: [f64; 2], b: [f64; 2]| (v(b) - v(a)).norm();
            assert!((d(p.a, p.b) - r[2]).abs() < 1e-14 && (d(fb.o4, p.b) - r[3]).abs() < 1e-14);
            assert!((d(p.a, p.p) - d(fb.a, fb.p)).abs() < 1e-14);
        }
        let m = crate::Mechanism::from_dsl(&fb.to_mech("Synth", "A four-bar")).unwrap();
        // The input q is the crank's angle itself (no `from`): θ = q.
        let c0 = fb.coupler_curve(12)[0].unwrap();
        assert!((c0[0] - fb.p[0]).abs() < 1e-15 && (c0[1] - fb.p[1]).abs() < 1e-15);
        for k in 0..12 {
            let q = std::f64::consts::TAU * k as f64 / 12.0;
            let pose = m.pose(&[q]).unwrap();
            let pp = pose.point("P").unwrap().pos;
            let c = fb.pose(q).unwrap().p;
            assert!(
                (pp.x - c[0]).abs() < 1e-12 && (pp.y - c[1]).abs() < 1e-12,
                "{k}: {pp:?} vs {c:?}"
            );
        }
    }
}
