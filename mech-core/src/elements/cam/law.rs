//! Cam motion laws (`docs/theory.md` §13): the follower's displacement s(θ) as a function of
//! the cam angle θ, segment by segment over one revolution, with its derivatives per unit
//! cam angle — s' (velocity), s'' (acceleration), s''' (jerk); multiplied by ω, ω², ω³ for
//! a cam turning at constant ω they are the follower's velocity, acceleration and jerk.
//!
//! A segment rises (or falls) from h₀ to h₁ over [θ₀, θ₁], β = θ₁ − θ₀, L = h₁ − h₀,
//! x = (θ − θ₀)/β ∈ [0, 1]:
//!
//! | law | s − h₀ | end conditions |
//! |---|---|---|
//! | dwell | 0 (h₁ = h₀) | — |
//! | uniform | L x | s continuous; s' jumps |
//! | simple harmonic | L (1 − cos πx)/2 | s' = 0 at the ends; s'' jumps |
//! | cycloidal | L (x − sin 2πx / 2π) | s', s'' = 0 at the ends |
//! | 3-4-5 polynomial | L (10x³ − 15x⁴ + 6x⁵) | s', s'' = 0 at the ends |
//! | 4-5-6-7 polynomial | L (35x⁴ − 84x⁵ + 70x⁶ − 20x⁷) | s', s'', s''' = 0 at the ends |
//!
//! and the derivatives follow by d/dθ = (1/β) d/dx. A user table is a periodic cubic
//! spline through (θᵢ, sᵢ) over the revolution: C² everywhere (s''' is piecewise constant).

use std::f64::consts::{PI, TAU};

/// The shape of one segment of a motion law (module docs).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Law {
    /// No motion.
    Dwell,
    /// Constant velocity.
    Uniform,
    /// Simple harmonic motion.
    Harmonic,
    /// Cycloidal motion.
    Cycloidal,
    /// The 3-4-5 polynomial.
    Poly345,
    /// The 4-5-6-7 polynomial.
    Poly4567,
}

impl Law {
    /// The law's name in the DSL.
    pub fn keyword(self) -> &'static str {
        match self {
            Law::Dwell => "dwell",
            Law::Uniform => "uniform",
            Law::Harmonic => "harmonic",
            Law::Cycloidal => "cycloidal",
            Law::Poly345 => "poly345",
            Law::Poly4567 => "poly4567",
        }
    }

    /// (s, ds/dx, d²s/dx², d³s/dx³) of the unit rise (L = 1) at x ∈ [0, 1].
    #[inline]
    pub fn unit(self, x: f64) -> [f64; 4] {
        match self {
            Law::Dwell => [0.0; 4],
            Law::Uniform => [x, 1.0, 0.0, 0.0],
            Law::Harmonic => {
                let (sn, cs) = (PI * x).sin_cos();
                [
                    0.5 * (1.0 - cs),
                    0.5 * PI * sn,
                    0.5 * PI * PI * cs,
                    -0.5 * PI * PI * PI * sn,
                ]
            }
            Law::Cycloidal => {
                let (sn, cs) = (TAU * x).sin_cos();
                [x - sn / TAU, 1.0 - cs, TAU * sn, TAU * TAU * cs]
            }
            Law::Poly345 => {
                let (x2, x3) = (x * x, x * x * x);
                [
                    x3 * (10.0 - 15.0 * x + 6.0 * x2),
                    30.0 * x2 * (1.0 - 2.0 * x + x2),
                    60.0 * x * (1.0 - 3.0 * x + 2.0 * x2),
                    60.0 * (1.0 - 6.0 * x + 6.0 * x2),
                ]
            }
            Law::Poly4567 => {
                let (x2, x3) = (x * x, x * x * x);
                [
                    x2 * x2 * (35.0 - 84.0 * x + 70.0 * x2 - 20.0 * x3),
                    140.0 * x3 * (1.0 - 3.0 * x + 3.0 * x2 - x3),
                    420.0 * x2 * (1.0 - 4.0 * x + 5.0 * x2 - 2.0 * x3),
                    840.0 * x * (1.0 - 6.0 * x + 10.0 * x2 - 5.0 * x3),
                ]
            }
        }
    }
}

/// One segment: `law` from (θ₀, h₀) to (θ₁, h₁), angles in rad, lifts in m (or rad for an
/// oscillating follower).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Segment {
    /// Its shape.
    pub law: Law,
    /// θ₀, rad.
    pub start: f64,
    /// θ₁ > θ₀, rad.
    pub end: f64,
    /// h₀, the lift at θ₀.
    pub from: f64,
    /// h₁, the lift at θ₁ (= h₀ for a dwell).
    pub to: f64,
}

/// x taken in [0, 2π): `x.rem_euclid(2π)` bit for bit, without its division (a call of
/// `fmod`) when x is within a turn either side of 0, as the kernels' cam angles, from an
/// `atan2`, always are: x itself on [0, 2π), x + 2π on (−2π, 0) (where `fmod` returns x;
/// at −2π it returns −0).
#[inline(always)]
fn within_turn(x: f64) -> f64 {
    if (0.0..TAU).contains(&x) {
        x
    } else if x > -TAU && x < 0.0 {
        x + TAU
    } else {
        x.rem_euclid(TAU)
    }
}

/// A periodic cubic spline through (θᵢ, sᵢ), i = 0..n, θ over one revolution (module docs).
#[derive(Clone, Debug, PartialEq)]
pub struct Spline {
    /// The knots θᵢ (rad, increasing, within one turn of θ₀).
    theta: Vec<f64>,
    /// sᵢ.
    s: Vec<f64>,
    /// The second derivatives Mᵢ = s''(θᵢ).
    m: Vec<f64>,
}

impl Spline {
    /// The periodic spline through the points (θᵢ, sᵢ) (θ increasing, spanning less than a
    /// turn; the point θ₀ + 2π closes the period): s, s', s'' continuous around the turn.
    /// Solves the cyclic tridiagonal system of the knots' second derivatives. Errors: fewer
    /// than 3 points, θ not increasing, or spanning a turn or more.
    pub fn periodic(theta: &[f64], s: &[f64]) -> Result<Self, String> {
        let n = theta.len();
        if n < 3 || s.len() != n {
            return Err(format!(
                "a cam table needs at least 3 points (θ, s), got {n}"
            ));
        }
        for k in 1..n {
            if !(theta[k] > theta[k - 1]) {
                return Err(format!(
                    "the table's angles must increase: {:.4}° after {:.4}°",
                    theta[k].to_degrees(),
                    theta[k - 1].to_degrees()
                ));
            }
        }
        if !(theta[n - 1] - theta[0] < TAU) {
            return Err("the table's angles must span less than one turn (the first point closes the period)".into());
        }
        let h = |k: usize| {
            if k + 1 < n {
                theta[k + 1] - theta[k]
            } else {
                theta[0] + TAU - theta[n - 1]
            }
        };
        let sv = |k: usize| s[k % n];
        // For each knot i: h_{i−1} M_{i−1} + 2 (h_{i−1} + h_i) M_i + h_i M_{i+1}
        //                  = 6 ((s_{i+1} − s_i)/h_i − (s_i − s_{i−1})/h_{i−1}), cyclic.
        let mut a = nalgebra::DMatrix::<f64>::zeros(n, n);
        let mut b = nalgebra::DVector::<f64>::zeros(n);
        for i in 0..n {
            let (hp, hi) = (h((i + n - 1) % n), h(i));
            a[(i, (i + n - 1) % n)] += hp;
            a[(i, i)] += 2.0 * (hp + hi);
            a[(i, (i + 1) % n)] += hi;
            b[i] = 6.0 * ((sv(i + 1) - s[i]) / hi - (s[i] - sv(i + n - 1)) / hp);
        }
        let m = a
            .lu()
            .solve(&b)
            .ok_or_else(|| "the cam table's spline system is singular".to_string())?;
        Ok(Spline {
            theta: theta.to_vec(),
            s: s.to_vec(),
            m: m.iter().copied().collect(),
        })
    }

    /// (s, s', s'', s''') at θ (any angle: taken modulo the turn).
    pub fn eval(&self, theta: f64) -> [f64; 4] {
        let n = self.theta.len();
        let t0 = self.theta[0];
        let t = t0 + within_turn(theta - t0);
        let k = self.theta.partition_point(|&x| x <= t).max(1) - 1;
        let (ta, tb) = (
            self.theta[k],
            if k + 1 < n {
                self.theta[k + 1]
            } else {
                t0 + TAU
            },
        );
        let (sa, sb) = (self.s[k], self.s[(k + 1) % n]);
        let (ma, mb) = (self.m[k], self.m[(k + 1) % n]);
        let h = tb - ta;
        let (u, w) = (tb - t, t - ta);
        [
            (ma * u * u * u + mb * w * w * w) / (6.0 * h)
                + (sa / h - ma * h / 6.0) * u
                + (sb / h - mb * h / 6.0) * w,
            (-ma * u * u + mb * w * w) / (2.0 * h) + (sb - sa) / h - (mb - ma) * h / 6.0,
            (ma * u + mb * w) / h,
            (mb - ma) / h,
        ]
    }
}

/// A discontinuity of a motion law where two segments meet.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Jump {
    /// Where, rad.
    pub at: f64,
    /// Which derivative jumps: 0 = s, 1 = s', 2 = s''.
    pub order: usize,
    /// The values before and after.
    pub before: f64,
    /// See `before`.
    pub after: f64,
}

/// A follower's motion law over one revolution: segments covering [θ₀, θ₀ + 2π) end to
/// end, or a periodic spline.
#[derive(Clone, Debug, PartialEq)]
pub enum MotionLaw {
    /// Segments, sorted, covering one turn.
    Segments(SegmentLaw),
    /// A user table.
    Table(Spline),
}

/// Segments covering one turn end to end ([`MotionLaw::from_segments`]), each kept with
/// the constants its evaluation needs, worked out once: 1/β, L/β, L/β², L/β³.
#[derive(Clone, Debug, PartialEq)]
pub struct SegmentLaw {
    /// The segments as declared.
    segments: Vec<Segment>,
    /// The same, ready to evaluate.
    pieces: Vec<Piece>,
}

impl SegmentLaw {
    /// The segments, sorted, as declared.
    pub fn segments(&self) -> &[Segment] {
        &self.segments
    }
}

/// A [`Segment`] ready to evaluate: s − h₀ = L u(x), x = (θ − θ₀)/β, and the derivatives
/// (L/βᵏ) u⁽ᵏ⁾(x).
#[derive(Clone, Copy, Debug, PartialEq)]
struct Piece {
    law: Law,
    /// θ₀, 1/β, h₀, L, L/β, L/β², L/β³.
    start: f64,
    inv_beta: f64,
    from: f64,
    rise: f64,
    k1: f64,
    k2: f64,
    k3: f64,
}

impl Piece {
    fn new(g: &Segment) -> Self {
        let inv_beta = 1.0 / (g.end - g.start);
        let rise = g.to - g.from;
        let k1 = rise * inv_beta;
        let k2 = k1 * inv_beta;
        Piece {
            law: g.law,
            start: g.start,
            inv_beta,
            from: g.from,
            rise,
            k1,
            k2,
            k3: k2 * inv_beta,
        }
    }

    /// (s, s', s'', s''') at t in the segment (module docs).
    #[inline(always)]
    fn eval(&self, t: f64) -> [f64; 4] {
        let u = self
            .law
            .unit(((t - self.start) * self.inv_beta).clamp(0.0, 1.0));
        [
            self.from + self.rise * u[0],
            self.k1 * u[1],
            self.k2 * u[2],
            self.k3 * u[3],
        ]
    }
}

/// How closely segments must meet, rad.
pub const ANGLE_TOL: f64 = 1e-9;

impl MotionLaw {
    /// A law from segments that must cover exactly one turn end to end (each starting
    /// where the previous ended, the last ending a turn after the first starts), each with
    /// θ₁ > θ₀ and a dwell with h₁ = h₀; the lift must return to its start. The error says
    /// which segment and the numbers.
    pub fn from_segments(segments: Vec<Segment>) -> Result<Self, String> {
        let Some(first) = segments.first() else {
            return Err("a motion law needs at least one segment".into());
        };
        for (k, g) in segments.iter().enumerate() {
            if !(g.end > g.start) {
                return Err(format!(
                    "segment {} ({}) ends at {:.4}°, not after its start {:.4}°",
                    k + 1,
                    g.law.keyword(),
                    g.end.to_degrees(),
                    g.start.to_degrees()
                ));
            }
            if g.law == Law::Dwell && g.to != g.from {
                return Err(format!(
                    "segment {} is a dwell but goes from {} to {}: a dwell keeps its lift",
                    k + 1,
                    g.from,
                    g.to
                ));
            }
            if k > 0 && (g.start - segments[k - 1].end).abs() > ANGLE_TOL {
                return Err(format!(
                    "segment {} starts at {:.4}° but segment {} ends at {:.4}°: the segments must follow each other end to end",
                    k + 1,
                    g.start.to_degrees(),
                    k,
                    segments[k - 1].end.to_degrees()
                ));
            }
        }
        let last = segments[segments.len() - 1];
        let span = last.end - first.start;
        if (span - TAU).abs() > ANGLE_TOL {
            return Err(format!(
                "the segments cover {:.4}° from {:.4}° to {:.4}°, not one turn (360°): add or stretch a segment",
                span.to_degrees(),
                first.start.to_degrees(),
                last.end.to_degrees()
            ));
        }
        let pieces = segments.iter().map(Piece::new).collect();
        Ok(MotionLaw::Segments(SegmentLaw { segments, pieces }))
    }

    /// (s, s', s'', s''') at cam angle θ (rad, any: taken modulo the turn); derivatives
    /// per unit cam angle (m/rad, m/rad², m/rad³ for a translating follower). At a joint
    /// of two segments the later one's values are taken. (Inline: the cam pair's kernels
    /// call it in the generated solvers, another crate.)
    #[inline(always)]
    pub fn eval(&self, theta: f64) -> [f64; 4] {
        match self {
            MotionLaw::Table(sp) => sp.eval(theta),
            MotionLaw::Segments(law) => {
                let pieces = &law.pieces[..];
                let t0 = pieces[0].start;
                let t = t0 + within_turn(theta - t0);
                let g = pieces
                    .iter()
                    .rev()
                    .find(|g| g.start <= t)
                    .unwrap_or(&pieces[0]);
                g.eval(t)
            }
        }
    }

    /// Where s, s' or s'' jumps between consecutive segments (the last to the first
    /// included), by more than `tol` × the law's largest value of that derivative: a jump
    /// in s is an error in a law, one in s' an infinite acceleration (a uniform segment's
    /// corner), one in s'' an infinite jerk (simple harmonic motion between dwells), which
    /// a designer may accept knowingly.
    pub fn jumps(&self, tol: f64) -> Vec<Jump> {
        let MotionLaw::Segments(law) = self else {
            return Vec::new();
        };
        let (segs, pieces) = (&law.segments, &law.pieces);
        let n = segs.len();
        let mut scale = [0.0f64; 3];
        for (g, p) in segs.iter().zip(pieces) {
            for k in 0..=20 {
                let v = p.eval(g.start + (g.end - g.start) * k as f64 / 20.0);
                for o in 0..3 {
                    scale[o] = scale[o].max(v[o].abs());
                }
            }
        }
        let mut out = Vec::new();
        for k in 0..n {
            let (g, h) = (&segs[k], &segs[(k + 1) % n]);
            let (a, b) = (pieces[k].eval(g.end), pieces[(k + 1) % n].eval(h.start));
            for o in 0..3 {
                if (a[o] - b[o]).abs() > tol * scale[o].max(f64::MIN_POSITIVE) {
                    out.push(Jump {
                        at: g.end,
                        order: o,
                        before: a[o],
                        after: b[o],
                    });
                }
            }
        }
        out
    }
}

/// A lift written with its unit for a message: mm for a translating follower, degrees for
/// an oscillating one (`angular`).
pub fn lift_text(v: f64, angular: bool) -> String {
    if angular {
        format!("{:.4}°", v.to_degrees())
    } else {
        format!("{:.4} mm", v * 1e3)
    }
}

/// A cam's law from its declaration: the periodic spline through `table` when it is not
/// empty (its first point at 0° and lift 0, the follower's place in the drawing), else the
/// segments, which must cover a turn and return to their start. `angular`: the lifts are
/// angles (an oscillating follower), for the messages.
pub fn law_of(
    segments: &[Segment],
    table: &[[f64; 2]],
    angular: bool,
) -> Result<MotionLaw, String> {
    if let Some(first) = table.first() {
        if first[0] != 0.0 || first[1] != 0.0 {
            return Err(format!(
                "the table's first point is ({:.4}°, {}): it must be (0 deg, 0 {}), the follower's place in the drawing",
                first[0].to_degrees(),
                lift_text(first[1], angular),
                if angular { "deg" } else { "mm" }
            ));
        }
        let (th, s): (Vec<f64>, Vec<f64>) = table.iter().map(|p| (p[0], p[1])).unzip();
        return Spline::periodic(&th, &s).map(MotionLaw::Table);
    }
    let law = MotionLaw::from_segments(segments.to_vec())?;
    let net = segments.last().map(|g| g.to).unwrap_or(0.0);
    if net.abs() > 1e-12 {
        return Err(format!(
            "it ends {} from where it starts: the rises and falls over a turn must add to zero",
            lift_text(net, angular)
        ));
    }
    Ok(law)
}

#[cfg(test)]
mod tests {
    /// `within_turn` is `rem_euclid(2π)` bit for bit, on and off its fast ranges.
    #[test]
    fn within_turn_is_rem_euclid() {
        for x in [
            0.0,
            -0.0,
            1e-300,
            -1e-300,
            1.0,
            -1.0,
            3.0,
            -3.0,
            6.283185307179586,
            -6.283185307179586,
            6.283185307179585,
            -6.283185307179585,
            7.0,
            -7.0,
            40.0,
            -40.0,
            -1e-17,
            f64::MIN_POSITIVE,
        ] {
            assert_eq!(
                super::within_turn(x).to_bits(),
                x.rem_euclid(super::TAU).to_bits(),
                "{x}"
            );
        }
    }
}
