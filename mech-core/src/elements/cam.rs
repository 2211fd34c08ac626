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

use crate::kernel::constraints::{JointGeom, Level};
use crate::kernel::kinetostatics::{Reaction, Wrench};
use crate::kernel::link_state::{cross, perp, point_of, rotate, LinkState, V2};
use crate::MechError;

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
        let t = t0 + (theta - t0).rem_euclid(TAU);
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
    Segments(Vec<Segment>),
    /// A user table.
    Table(Spline),
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
        Ok(MotionLaw::Segments(segments))
    }

    /// (s, s', s'', s''') at cam angle θ (rad, any: taken modulo the turn); derivatives
    /// per unit cam angle (m/rad, m/rad², m/rad³ for a translating follower). At a joint
    /// of two segments the later one's values are taken.
    pub fn eval(&self, theta: f64) -> [f64; 4] {
        match self {
            MotionLaw::Table(sp) => sp.eval(theta),
            MotionLaw::Segments(segs) => {
                let t0 = segs[0].start;
                let t = t0 + (theta - t0).rem_euclid(TAU);
                let g = segs.iter().rev().find(|g| g.start <= t).unwrap_or(&segs[0]);
                Self::segment(g, t)
            }
        }
    }

    fn segment(g: &Segment, t: f64) -> [f64; 4] {
        let beta = g.end - g.start;
        let rise = g.to - g.from;
        let u = g.law.unit(((t - g.start) / beta).clamp(0.0, 1.0));
        [
            g.from + rise * u[0],
            rise * u[1] / beta,
            rise * u[2] / (beta * beta),
            rise * u[3] / (beta * beta * beta),
        ]
    }

    /// Where s, s' or s'' jumps between consecutive segments (the last to the first
    /// included), by more than `tol` × the law's largest value of that derivative: a jump
    /// in s is an error in a law, one in s' an infinite acceleration (a uniform segment's
    /// corner), one in s'' an infinite jerk (simple harmonic motion between dwells), which
    /// a designer may accept knowingly.
    pub fn jumps(&self, tol: f64) -> Vec<Jump> {
        let MotionLaw::Segments(segs) = self else {
            return Vec::new();
        };
        let n = segs.len();
        let mut scale = [0.0f64; 3];
        for g in segs {
            for k in 0..=20 {
                let v = Self::segment(g, g.start + (g.end - g.start) * k as f64 / 20.0);
                for o in 0..3 {
                    scale[o] = scale[o].max(v[o].abs());
                }
            }
        }
        let mut out = Vec::new();
        for k in 0..n {
            let (g, h) = (&segs[k], &segs[(k + 1) % n]);
            let (a, b) = (Self::segment(g, g.end), Self::segment(h, h.start));
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

/// The follower's contact face ([`Profile`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Face {
    /// A knife edge: the profile is the pitch curve.
    Knife,
    /// A roller of this radius (m): the profile is the pitch curve offset inward by it.
    Roller(f64),
    /// A flat face perpendicular to the follower's axis.
    Flat,
}

/// One point of a cam's profile (`docs/theory.md` §13), in the cam's own frame (the cam
/// turning counter-clockwise by θ; at θ = 0 the frame is the profile's axis frame: the
/// follower's axis (translating) or the cam's centre to the pitch point (oscillating) along
/// +y, a translating follower's axis offset by e along +x).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ProfilePoint {
    /// The cam angle θ, rad.
    pub theta: f64,
    /// The pitch point (the roller's centre, the knife's edge; for a flat face the
    /// face's foot on the axis, or for a rocker the face's point that touched the base
    /// circle in the drawing), cam frame, m.
    pub pitch: [f64; 2],
    /// The cam surface's contact point, cam frame, m.
    pub contact: [f64; 2],
    /// The pressure angle φ (rad): between the direction the follower's pitch point
    /// moves (along the axis; a rocker's: perpendicular to its arm) and the common normal
    /// at the contact; zero for a translating flat face.
    pub pressure_angle: f64,
    /// The radius of curvature of the cam surface at the contact (m, > 0 convex,
    /// < 0 concave); for a roller the pitch curve's less the roller's radius.
    pub curvature_radius: f64,
}

/// An oscillating follower (a rocker) of a [`Profile`]: pinned to the cam's carrier at its
/// pivot A and turned by the law's lift ψ(θ), an angle, from the drawing.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Rocker {
    /// The pivot A in the profile's axis frame (the cam's centre O at the origin, +y
    /// towards the pitch point P of the drawing), m.
    pub pivot: [f64; 2],
    /// σ = ±1: the rocker turns by σψ (counter-clockwise positive), the sense that moves
    /// its pitch point away from the cam's centre: σ = −sign(A_x).
    pub sign: f64,
}

/// A cam's profile (`docs/theory.md` §13): base circle R_b (to the cam surface), the
/// follower (translating with offset e, or a [`Rocker`]), its face, and the motion law
/// s(θ) (a length; a rocker's an angle ψ(θ)).
#[derive(Clone, Debug, PartialEq)]
pub struct Profile {
    /// The motion law.
    pub law: MotionLaw,
    /// R_b, the base circle's radius (m).
    pub base_radius: f64,
    /// e, the offset of a translating follower's axis from the cam's centre (m; 0 for a
    /// flat face and for a rocker).
    pub offset: f64,
    /// The follower's face.
    pub face: Face,
    /// An oscillating follower's pivot; `None` for a translating one.
    pub rocker: Option<Rocker>,
}

/// The follower against the cam at one cam angle ([`Profile::contact`]), in the profile's
/// axis frame (fixed to the carrier: not turned with the cam).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Contact {
    /// The law's (s, s′, s″, s‴) at θ (m or rad, per radian of cam angle).
    pub law: [f64; 4],
    /// The pitch point, m.
    pub pitch: V2,
    /// The contact point K, m.
    pub contact: V2,
    /// The common normal n at K (unit, from the cam towards the follower).
    pub normal: V2,
    /// The pressure angle φ, rad ([`ProfilePoint::pressure_angle`]).
    pub pressure_angle: f64,
    /// The cam surface's radius of curvature at K, m ([`ProfilePoint::curvature_radius`]).
    pub curvature_radius: f64,
}

impl Profile {
    /// The roller's radius (0 for a knife or a flat face), m.
    pub fn roller(&self) -> f64 {
        match self.face {
            Face::Roller(r) => r,
            _ => 0.0,
        }
    }

    /// The pitch point F(θ) of a knife or roller follower in the axis frame, its
    /// derivatives F′, F″ per unit cam angle, and the unit direction d̂ a lift moves it in.
    /// Translating: F = (e, d + s), d = √(R_p² − e²), R_p = R_b + r, F′ = (0, s′),
    /// F″ = (0, s″), d̂ = (0, 1). A rocker with pivot A: w = R(σψ)(P₀ − A), P₀ = (0, R_p),
    /// F = A + w, F′ = σψ′ perp(w), F″ = σψ″ perp(w) − ψ′² w, d̂ = σ perp(w)/|w|.
    #[inline]
    fn pitch_motion(&self, law: [f64; 4]) -> [V2; 4] {
        let [s, s1, s2, _] = law;
        let rp = self.base_radius + self.roller();
        match self.rocker {
            None => {
                let e = self.offset;
                [
                    V2::new(e, (rp * rp - e * e).sqrt() + s),
                    V2::new(0.0, s1),
                    V2::new(0.0, s2),
                    V2::new(0.0, 1.0),
                ]
            }
            Some(k) => {
                let a = V2::new(k.pivot[0], k.pivot[1]);
                let (sn, cs) = (k.sign * s).sin_cos();
                let w = rotate(V2::new(cs, sn), V2::new(0.0, rp) - a);
                let jw = perp(w) * k.sign;
                [a + w, jw * s1, jw * s2 - w * (s1 * s1), jw / w.norm()]
            }
        }
    }

    /// The follower against the cam at cam angle θ ([`Contact`]).
    ///
    /// Knife and roller: seen from the cam (turned back by θ) the pitch point is
    /// P(θ) = R(−θ) F(θ), so P′ = R(−θ) v and P″ = R(−θ) a with v = F′ − perp(F),
    /// a = F″ − 2 perp(F′) − F (`Profile::pitch_motion` gives F, F′, F″). The pitch curve,
    /// traversed clockwise, has the radius of curvature ρ = −|v|³ / (v × a) (> 0 where
    /// convex); its outward normal n = perp(v)/|v| is the common normal, the contact is
    /// K = F − r n and the pressure angle is the angle from d̂ to n. A translating flat face
    /// (e = 0) touches the cam where the face's points move along it: K = (s′, R_b + s),
    /// ρ = R_b + s + s″. A rocker's flat face (tangent to the base circle at P₀ = (0, R_b)
    /// in the drawing) is the line m·x = p with m = R(σψ)(0, 1), p = m·A + R_b − A_y;
    /// seen from the cam its normal turns by β′ = σψ′ − 1 per unit cam angle, so the
    /// envelope (the cam surface) touches it at K = p m + p_β perp(m) with
    /// p_β = g w, g = σψ′/(σψ′ − 1), w = perp(m)·A, and ρ = p + p_ββ,
    /// p_ββ = (g′ w + g w′)/β′, g′ = −σψ″/β′², w′ = −σψ′ (m·A) (K is the foot of the
    /// perpendicular from the relative instant centre g A: Aronhold–Kennedy).
    pub fn contact(&self, theta: f64) -> Contact {
        let law = self.law.eval(theta);
        let [s, s1, s2, _] = law;
        match (self.face, self.rocker) {
            (Face::Flat, None) => {
                let y = self.base_radius + s;
                Contact {
                    law,
                    pitch: V2::new(0.0, y),
                    contact: V2::new(s1, y),
                    normal: V2::new(0.0, 1.0),
                    pressure_angle: 0.0,
                    curvature_radius: y + s2,
                }
            }
            (Face::Flat, Some(k)) => {
                let sg = k.sign;
                let a = V2::new(k.pivot[0], k.pivot[1]);
                let (sn, cs) = (sg * s).sin_cos();
                let rot = V2::new(cs, sn);
                let m = V2::new(-sn, cs);
                let jm = perp(m);
                let p = m.dot(&a) + self.base_radius - a.y;
                let w = jm.dot(&a);
                let beta1 = sg * s1 - 1.0;
                let g = sg * s1 / beta1;
                let g1 = -sg * s2 / (beta1 * beta1);
                let w1 = -sg * s1 * m.dot(&a);
                let contact = m * p + jm * (g * w);
                let arm = contact - a;
                let dir = perp(arm) * (sg / arm.norm());
                Contact {
                    law,
                    pitch: a + rotate(rot, V2::new(0.0, self.base_radius) - a),
                    contact,
                    normal: m,
                    pressure_angle: cross(dir, m).atan2(dir.dot(&m)),
                    curvature_radius: p + (g1 * w + g * w1) / beta1,
                }
            }
            _ => {
                let r = self.roller();
                let [f, f1, f2, dir] = self.pitch_motion(law);
                let v = f1 - perp(f);
                let acc = f2 - perp(f1) * 2.0 - f;
                let speed = v.norm();
                let n = perp(v) / speed;
                Contact {
                    law,
                    pitch: f,
                    contact: f - n * r,
                    normal: n,
                    pressure_angle: cross(dir, n).atan2(dir.dot(&n)),
                    curvature_radius: -speed * speed * speed / cross(v, acc) - r,
                }
            }
        }
    }

    /// The profile at cam angle θ, in the cam's frame: [`Profile::contact`] turned back
    /// by θ.
    pub fn at(&self, theta: f64) -> ProfilePoint {
        let c = self.contact(theta);
        let (sn, cs) = (-theta).sin_cos();
        let back = |v: V2| {
            let r = rotate(V2::new(cs, sn), v);
            [r.x, r.y]
        };
        ProfilePoint {
            theta,
            pitch: back(c.pitch),
            contact: back(c.contact),
            pressure_angle: c.pressure_angle,
            curvature_radius: c.curvature_radius,
        }
    }
}

/// The design figures of a cam over a revolution ([`Profile::check`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ProfileCheck {
    /// The largest |pressure angle| (rad) and the cam angle where it occurs (rad).
    pub max_pressure_angle: (f64, f64),
    /// The smallest radius of curvature of the cam surface where it is convex (m), and
    /// where; a concave cam has no limit there (∞ when the surface is nowhere convex).
    pub min_convex_radius: (f64, f64),
    /// True when the profile is undercut: the pitch curve's convex radius is smaller than
    /// the roller's (the cam surface's radius ≤ 0 somewhere it should be convex), or a flat
    /// face's R_b + s + s″ ≤ 0 (a cusp).
    pub undercut: bool,
    /// The first sampled cam angle (rad) where the profile does not exist (a contact
    /// point or radius that is not finite: a flat-faced rocker turning as fast as the
    /// cam, σψ′ = 1, has no envelope there); `None` when it exists at every sample.
    pub missing: Option<f64>,
}

/// The design figures in one line: the largest pressure angle and where, the smallest
/// convex radius of the surface (mm) and where, undercut or not, and where the profile
/// does not exist if it does not somewhere.
impl std::fmt::Display for ProfileCheck {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "largest pressure angle {:.2}° at θ = {:.1}°; smallest convex radius of the surface {:.3} mm at θ = {:.1}°; {}",
            self.max_pressure_angle.0.to_degrees(),
            self.max_pressure_angle.1.to_degrees(),
            self.min_convex_radius.0 * 1e3,
            self.min_convex_radius.1.to_degrees(),
            if self.undercut { "UNDERCUT (a cusp)" } else { "not undercut" }
        )?;
        match self.missing {
            Some(t) => write!(f, "; no profile at θ = {:.1}°", t.to_degrees()),
            None => Ok(()),
        }
    }
}

impl Profile {
    /// The profile at `n` cam angles evenly over the revolution, from θ = 0.
    pub fn points(&self, n: usize) -> Vec<ProfilePoint> {
        (0..n).map(|k| self.at(TAU * k as f64 / n as f64)).collect()
    }

    /// The maximum pressure angle, the minimum convex radius of curvature, whether the
    /// profile is undercut and where it is missing, sampled at `n` cam angles
    /// ([`ProfileCheck`]).
    pub fn check(&self, n: usize) -> ProfileCheck {
        let r = self.roller();
        let mut out = ProfileCheck {
            max_pressure_angle: (0.0, 0.0),
            min_convex_radius: (f64::INFINITY, 0.0),
            undercut: false,
            missing: None,
        };
        for p in self.points(n) {
            if !(p.contact.iter().all(|x| x.is_finite()) && p.curvature_radius.is_finite()) {
                out.missing = out.missing.or(Some(p.theta));
            }
            if p.pressure_angle.abs() > out.max_pressure_angle.0 {
                out.max_pressure_angle = (p.pressure_angle.abs(), p.theta);
            }
            // The pitch curve's radius: convex where > 0.
            let pitch = p.curvature_radius + r;
            if pitch > 0.0 && p.curvature_radius < out.min_convex_radius.0 {
                out.min_convex_radius = (p.curvature_radius, p.theta);
            }
            let cusp = match self.face {
                Face::Flat => p.curvature_radius <= 0.0,
                Face::Roller(_) => pitch > 0.0 && p.curvature_radius <= 0.0,
                Face::Knife => false,
            };
            out.undercut |= cusp;
        }
        out
    }

    /// The names of [`Profile::row`]'s columns (SI: rad, m; the lift and its derivatives
    /// per radian of cam angle, in m or, for a rocker, rad).
    pub const COLUMNS: [&'static str; 10] = [
        "theta",
        "lift",
        "lift_velocity",
        "lift_acceleration",
        "pitch_x",
        "pitch_y",
        "contact_x",
        "contact_y",
        "pressure_angle",
        "curvature_radius",
    ];

    /// One row of the profile's table at cam angle θ ([`Profile::COLUMNS`]): θ, the law's
    /// s, s′, s″, the pitch and contact points in the cam's frame, the pressure angle and
    /// the surface's radius of curvature.
    pub fn row(&self, theta: f64) -> [f64; 10] {
        let p = self.at(theta);
        let [s, s1, s2, _] = self.law.eval(theta);
        [
            theta,
            s,
            s1,
            s2,
            p.pitch[0],
            p.pitch[1],
            p.contact[0],
            p.contact[1],
            p.pressure_angle,
            p.curvature_radius,
        ]
    }

    /// [`Profile::row`] at `n` cam angles evenly over the revolution, from θ = 0.
    pub fn table(&self, n: usize) -> Vec<[f64; 10]> {
        (0..n)
            .map(|k| self.row(TAU * k as f64 / n as f64))
            .collect()
    }

    /// The cam surface as CSV, one contact point per row: `theta_deg,x_m,y_m`
    /// (the cam's frame), `n` points over the revolution.
    pub fn to_csv(&self, n: usize) -> String {
        let mut out = String::from("theta_deg,x_m,y_m\n");
        for p in self.points(n) {
            out.push_str(&format!(
                "{:.6},{:.9},{:.9}\n",
                p.theta.to_degrees(),
                p.contact[0],
                p.contact[1]
            ));
        }
        out
    }

    /// The cam surface as the `d` attribute of an SVG path (a closed polygon through `n`
    /// contact points), in mm with y up turned to SVG's y down.
    pub fn svg_path(&self, n: usize) -> String {
        let mut d = String::new();
        for (k, p) in self.points(n).iter().enumerate() {
            d.push_str(&format!(
                "{}{:.4},{:.4} ",
                if k == 0 { "M" } else { "L" },
                p.contact[0] * 1e3,
                -p.contact[1] * 1e3
            ));
        }
        d.push('Z');
        d
    }
}

// ---------------------------------------------------------------------------------------
// The cam pair: a cam pinned to a carrier drives a follower sliding on it.

/// A cam pair's geometry in its links' frames (`docs/conventions.md#cams`).
#[derive(Clone, Debug, PartialEq)]
pub struct CamGeom {
    /// The profile: law, base circle, the follower (offset e, or a rocker's pivot), face.
    pub profile: Profile,
    /// The profile's axis frame: its unit +y (û) in the carrier's frame — a translating
    /// follower's axis, from the cam's centre towards the follower; for a rocker, from
    /// the cam's centre towards the pitch point of the drawing. x̂ = (û_y, −û_x).
    pub axis: V2,
    /// The cam's centre: its local vector in the cam.
    pub centre: V2,
}

/// The group of a follower driven by a cam ([`solve_cam`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct CamGroup {
    /// The follower.
    pub follower: usize,
    /// Its joint on the carrier: a prismatic joint (translating) or its pin (a rocker).
    pub slide: usize,
    /// The cam joint.
    pub joint: usize,
    /// The cam.
    pub cam: usize,
    /// The carrier.
    pub carrier: usize,
    /// Index into the mechanism's cams.
    pub index: usize,
}

impl CamGroup {
    /// The cam's turn θ relative to the carrier since the drawing, its rate and
    /// acceleration; the carrier's rotation, ω, α.
    #[inline(always)]
    fn turn(&self, s: &[LinkState]) -> ([f64; 3], V2, f64, f64) {
        let (rc, wc, ac) = if self.carrier == 0 {
            (V2::new(1.0, 0.0), 0.0, 0.0)
        } else {
            let c = &s[self.carrier];
            (c.rot, c.omega, c.alpha)
        };
        let k = &s[self.cam];
        let rel = V2::new(rc.dot(&k.rot), cross(rc, k.rot));
        ([rel.y.atan2(rel.x), k.omega - wc, k.alpha - ac], rc, wc, ac)
    }

    /// The follower's frame: û (world), the carrier's point of the follower's joint (the
    /// slide's start, or the rocker's pivot), the follower's local vector of that point.
    #[inline(always)]
    fn frame(&self, g: &JointGeom, geom: &CamGeom, s: &[LinkState], rc: V2) -> (V2, V2, V2) {
        let u = rotate(rc, geom.axis);
        let (q, df) = if g.a == self.carrier {
            (point_of(s, g.a, g.da), g.db)
        } else {
            (point_of(s, g.b, g.db), g.da)
        };
        (u, q, df)
    }
}

/// Solve a cam-driven follower up to `upto` from the cam's turn θ relative to the carrier
/// (the law is periodic: θ is taken in (−π, π]). Translating: its slide along û is s(θ),
/// ṡ = s′ θ̇, s̈ = s″ θ̇² + s′ θ̈. A rocker turns about its pivot by σψ(θ) relative to the
/// carrier: ω = ω_c + σψ′ θ̇, α = α_c + σ(ψ″ θ̇² + ψ′ θ̈).
#[cfg_attr(debug_assertions, inline)]
#[cfg_attr(not(debug_assertions), inline(always))]
pub fn solve_cam(
    grp: &CamGroup,
    cams: &[CamGeom],
    joints: &[JointGeom],
    s: &mut [LinkState],
    upto: Level,
) -> Result<(), MechError> {
    let geom = &cams[grp.index];
    let g = &joints[grp.slide];
    let (th, rc, wc, ac) = grp.turn(s);
    let [x, x1, x2, _] = geom.profile.law.eval(th[0]);
    let (u, q, df) = grp.frame(g, geom, s, rc);
    let fl = grp.follower;
    let carrier_angle = if grp.carrier == 0 {
        0.0
    } else {
        s[grp.carrier].angle
    };
    // The follower's point p (on its axis, or its pivot) and the rotation it turns by.
    let (p, turn, rate, accel) = match geom.profile.rocker {
        None => (q + u * x, 0.0, 0.0, 0.0),
        Some(k) => (
            q,
            k.sign * x,
            k.sign * x1 * th[1],
            k.sign * (x2 * th[1] * th[1] + x1 * th[2]),
        ),
    };
    let rot = if turn == 0.0 {
        rc
    } else {
        let (sn, cs) = turn.sin_cos();
        rotate(rc, V2::new(cs, sn))
    };
    s[fl].rot = rot;
    s[fl].angle = carrier_angle + turn;
    s[fl].pos = p - rotate(rot, df);
    if upto == Level::Position {
        return Ok(());
    }
    let (vq, aq) = if grp.carrier == 0 {
        (V2::zeros(), V2::zeros())
    } else {
        let c = &s[grp.carrier];
        (c.vel_at(p - c.pos), c.acc_at(p - c.pos))
    };
    if geom.profile.rocker.is_some() {
        s[fl].set_velocity_through(p, vq, wc + rate);
        if upto == Level::Acceleration {
            s[fl].set_acceleration_through(p, aq, ac + accel);
        }
        return Ok(());
    }
    let xd = x1 * th[1];
    s[fl].set_velocity_through(p, vq + u * xd, wc);
    if upto == Level::Acceleration {
        let xdd = x2 * th[1] * th[1] + x1 * th[2];
        s[fl].set_acceleration_through(p, aq + perp(u) * (2.0 * wc * xd) + u * xdd, ac);
    }
    Ok(())
}

/// d'Alembert for a cam-driven follower: the contact force F_n n at the contact point K
/// from the follower's balance — along its axis for a translating follower,
/// F_n = −(F·û)/(n·û) (the slide takes the rest: a force normal to û and a moment); about
/// its pivot A for a rocker, F_n = −M_A/((K − A) × n) (the pin takes the rest). `out[joint]`
/// holds the force by the cam on the follower and, as its `moment`, F_n (N, > 0 while the
/// cam pushes: a negative value is the follower leaving the cam, a jump).
#[cfg_attr(debug_assertions, inline)]
#[cfg_attr(not(debug_assertions), inline(always))]
pub fn cam_reactions(
    grp: &CamGroup,
    cams: &[CamGeom],
    joints: &[JointGeom],
    s: &[LinkState],
    f: &mut [Wrench],
    out: &mut [Reaction],
) -> Result<(), MechError> {
    let geom = &cams[grp.index];
    let g = &joints[grp.slide];
    let (th, rc, _, _) = grp.turn(s);
    let (u, _, df) = grp.frame(g, geom, s, rc);
    let xh = V2::new(u.y, -u.x);
    let o = point_of(s, grp.cam, geom.centre);
    let c = geom.profile.contact(th[0]);
    let kw = o + xh * c.contact.x + u * c.contact.y;
    let nw = xh * c.normal.x + u * c.normal.y;
    let fl = grp.follower;
    let wf = f[fl];
    let ff = V2::new(wf.x, wf.y);
    let p = s[fl].point(df);
    // The follower's moment about p of everything but the cam and its joint.
    let mf = wf.z + cross(s[fl].pos - p, ff);
    let (fnorm, lever) = if geom.profile.rocker.is_some() {
        let arm = kw - p;
        let lever = cross(arm, nw);
        (-mf / lever, lever / arm.norm())
    } else {
        let nu = nw.dot(&u);
        (-ff.dot(&u) / nu, nu)
    };
    if !(lever.abs() >= 1e-12 && fnorm.is_finite()) {
        return Err(MechError::Singular {
            condition: f64::INFINITY,
        });
    }
    let force = nw * fnorm;
    let r = -(ff + force);
    let mp = if geom.profile.rocker.is_some() {
        0.0
    } else {
        -(mf + cross(kw - p, force))
    };
    out[grp.joint] = Reaction {
        force,
        moment: fnorm,
    };
    out[grp.slide] = if g.b == fl {
        Reaction {
            force: r,
            moment: mp,
        }
    } else {
        Reaction {
            force: -r,
            moment: -mp,
        }
    };
    let push = |f: &mut [Wrench], l: usize, at: V2, force: V2, couple: f64| {
        let pos = if l == 0 { V2::zeros() } else { s[l].pos };
        f[l] += Wrench::new(force.x, force.y, couple + cross(at - pos, force));
    };
    push(f, grp.cam, kw, -force, 0.0);
    push(f, grp.carrier, p, -r, -mp);
    Ok(())
}
