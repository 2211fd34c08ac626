//! Numerical path synthesis of Stephenson III six-bars (`mech synth path --topology
//! six-bar`): a four-bar O2 A B O4 whose coupler point C drives a second RRR dyad C D O6,
//! the tracer point P on the link C D. The linkage has one more dyad than the four-bar of
//! [`super::path`], so its coupler curve is the four-bar's curve C(ψ) carried through a
//! second circle intersection — a sixth-order family of curves with cusps, crunodes and
//! straight stretches a four-bar's cannot have.
//!
//! **Design variables** (seventeen): the four-bar's ten of [`super::path`] (O2, the frame's
//! direction φ, r₁ … r₄, C = A + u e + v perp(e) in the coupler's frame), the second
//! ground pivot O6 = (x, y), r₅ = |CD|, r₆ = |O6 D|, P = C + u′ e′ + v′ perp(e′) with
//! e′ = (D − C)/r₅, and the two assembly branches (B on its side of A → O4, D on its side
//! of C → O6, each kept over the cycle). The box is the four-bar's, with O6 ∈ c ± 2.5 L,
//! r₅, r₆ ∈ [0.05 L, 5 L] and u′, v′ ∈ [−3 L, 3 L].
//!
//! **Constraints** (closed paths: the crank turns fully):
//! - the four-bar's crank turns fully within the transmission bound μ_b, in closed form
//!   ([`super::path`]'s c_lo ≤ −1, c_hi ≥ 1);
//! - the second dyad assembles with its transmission angle (at D, between D − C and
//!   D − O6) within [μ_b, π − μ_b] at every sampled crank angle: with d² = |C − O6|²,
//!   r₅² + r₆² − 2 r₅ r₆ cos μ_b ≤ d² ≤ r₅² + r₆² + 2 r₅ r₆ cos μ_b, violation the largest
//!   excess over 2 r₅ r₆ (a cosine, as the four-bar's); the bound keeps D away from its
//!   toggle, so the branch holds between the samples;
//! - the longest of the six lengths over the shortest at most R.
//!
//! The search and the polish are [`super::path`]'s (its `islands` and `polish`) with this
//! linkage's curve; the reported error is SPEC §3f's on
//! the result ([`super::error::nearest_on`]: free timing, each target's nearest point over
//! a full turn; prescribed: P at the crank angle φ + αᵢ).

use super::error;
use super::four_bar::FourBar;
use super::optimiser::Evaluation;
use super::path::{
    dyad_window, islands, length_ratio, polish, polyline_distance2, prepare, usable, Constraint,
    PathError, PathOptions, PathProblem, Prepared, SEARCH_SAMPLES,
};
use crate::kernel::dyad::circle_circle;
use crate::kernel::link_state::{cross, perp, V2};
use std::cell::RefCell;
use std::f64::consts::{PI, TAU};

/// A Stephenson III six-bar with its tracer point, in the drawing, m: the four-bar O2 A B
/// O4 with C on its coupler, the dyad C D O6, P on the link C D.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SixBar {
    /// The crank's ground pivot.
    pub o2: [f64; 2],
    /// The rocker's ground pivot.
    pub o4: [f64; 2],
    /// The second rocker's ground pivot.
    pub o6: [f64; 2],
    /// The crank pin.
    pub a: [f64; 2],
    /// The coupler–rocker pin.
    pub b: [f64; 2],
    /// The coupler's point that drives the second dyad.
    pub c: [f64; 2],
    /// The pin of the link C D and the second rocker O6 D.
    pub d: [f64; 2],
    /// The tracer point, on the link C D.
    pub p: [f64; 2],
}

/// The moving points of a [`SixBar`] at one crank angle, m.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SixBarPose {
    /// A.
    pub a: [f64; 2],
    /// B.
    pub b: [f64; 2],
    /// C.
    pub c: [f64; 2],
    /// D.
    pub d: [f64; 2],
    /// P.
    pub p: [f64; 2],
}

fn v(p: [f64; 2]) -> V2 {
    V2::new(p[0], p[1])
}

fn arr(x: V2) -> [f64; 2] {
    [x.x, x.y]
}

impl SixBar {
    /// Its four-bar O2 A B O4 with C as the coupler point.
    pub fn four_bar(&self) -> FourBar {
        FourBar {
            o2: self.o2,
            o4: self.o4,
            a: self.a,
            b: self.b,
            p: self.c,
        }
    }

    /// The six lengths: the four-bar's (frame O2O4, crank O2A, coupler AB, rocker O4B),
    /// then r₅ = |CD| and r₆ = |O6 D|, m.
    pub fn lengths(&self) -> [f64; 6] {
        let [r1, r2, r3, r4] = self.four_bar().lengths();
        let d = |a: [f64; 2], b: [f64; 2]| (v(b) - v(a)).norm();
        [r1, r2, r3, r4, d(self.c, self.d), d(self.o6, self.d)]
    }

    /// The side of D from the line C → O6 in the drawing (±1): the second dyad's branch.
    pub fn branch(&self) -> f64 {
        if cross(v(self.o6) - v(self.c), v(self.d) - v(self.c)) >= 0.0 {
            1.0
        } else {
            -1.0
        }
    }

    /// The pose at crank angle θ (rad, the direction of O2 → A) on the drawing's branches;
    /// `None` where it does not assemble.
    pub fn pose(&self, theta: f64) -> Option<SixBarPose> {
        let first = self.four_bar().pose(theta)?;
        let [.., r5, r6] = self.lengths();
        let (c0, d0) = (v(self.c), v(self.d));
        let e0 = (d0 - c0) / r5;
        let rel = v(self.p) - c0;
        let (u, w) = (rel.dot(&e0), rel.dot(&perp(e0)));
        let c = v(first.p);
        let d = circle_circle(c, r5 * r5, v(self.o6), r6 * r6, self.branch()).ok()?;
        let e = (d - c) / r5;
        Some(SixBarPose {
            a: first.a,
            b: first.b,
            c: first.p,
            d: arr(d),
            p: arr(c + e * u + perp(e) * w),
        })
    }

    /// The two transmission angles at θ (rad, in [0, π]): the four-bar's at B and the
    /// second dyad's at D (between D − C and D − O6); `None` where it does not assemble.
    pub fn transmission_angles(&self, theta: f64) -> Option<(f64, f64)> {
        let p = self.pose(theta)?;
        let angle = |x: V2, y: V2| cross(x, y).abs().atan2(x.dot(&y));
        Some((
            angle(v(p.b) - v(p.a), v(p.b) - v(self.o4)),
            angle(v(p.d) - v(p.c), v(p.d) - v(self.o6)),
        ))
    }

    /// The six-bar as a mechanism file, `name` the struct's, `doc` its doc line: the
    /// four-bar's names of SPEC §3f (`O2`, `O4`, `A`, `B`, input `O2`) with `C` on the
    /// coupler, the second dyad's `D` and `O6`, and the tracer `P` on the link `CD`.
    /// Coordinates in metres, written to round-trip.
    pub fn to_mech(&self, name: &str, doc: &str) -> String {
        let p = |x: [f64; 2]| format!("({:?}, {:?})", x[0], x[1]);
        format!(
            "/// {doc}\npub struct {name} {{\n    ground {{ O2: {}, O4: {}, O6: {} }},\n    link crank {{ points {{ O2, A: {} }} }},\n    link coupler {{ points {{ A, B: {}, C: {} }} }},\n    link rocker {{ points {{ O4, B }} }},\n    link tracer {{ points {{ C, D: {}, P: {} }} }},\n    link rocker6 {{ points {{ O6, D }} }},\n    joints {{\n        O2: revolute(ground, crank),\n        A: revolute(crank, coupler),\n        B: revolute(coupler, rocker),\n        O4: revolute(ground, rocker),\n        C: revolute(coupler, tracer),\n        D: revolute(tracer, rocker6),\n        O6: revolute(ground, rocker6),\n    }},\n    input: O2,\n}}\n",
            p(self.o2),
            p(self.o4),
            p(self.o6),
            p(self.a),
            p(self.b),
            p(self.c),
            p(self.d),
            p(self.p)
        )
    }

    /// The frame line's direction O2 → O4 (rad): prescribed angles are measured from it.
    pub fn frame_angle(&self) -> f64 {
        error::frame_angle(&self.four_bar())
    }

    /// E of SPEC §3f with free timing (each target's nearest point of P's curve over a
    /// full turn), m².
    pub fn free_timing(&self, targets: &[[f64; 2]]) -> f64 {
        let t0 = self.four_bar().drawn_angle();
        targets
            .iter()
            .map(|&t| error::nearest_on(|th| self.pose(th).map(|p| p.p), t0, t).0)
            .sum()
    }

    /// E of SPEC §3f with prescribed timing: P at the crank angles `angles` (rad, from the
    /// frame line), m².
    pub fn prescribed_timing(&self, targets: &[[f64; 2]], angles: &[f64]) -> f64 {
        let f = self.frame_angle();
        targets
            .iter()
            .zip(angles)
            .map(|(t, &a)| {
                self.pose(f + a).map_or(f64::INFINITY, |p| {
                    (p.p[0] - t[0]).powi(2) + (p.p[1] - t[1]).powi(2)
                })
            })
            .sum()
    }
}

/// A synthesised six-bar and how it was found.
#[derive(Clone, Debug, PartialEq)]
pub struct SixBarSynthesis {
    /// The six-bar, drawn at its crank angle nearest the first target (free timing) or at
    /// the first target's angle (prescribed).
    pub six_bar: SixBar,
    /// E of SPEC §3f, m².
    pub error: f64,
    /// The smallest of min(μ, π − μ) over a turn of both dyads' transmission angles, rad.
    pub transmission: f64,
    /// The longest link over the shortest (six lengths).
    pub ratio: f64,
    /// Evaluations of the global search.
    pub evaluations: usize,
    /// Its generations.
    pub generations: usize,
    /// Residual evaluations of the polish.
    pub polish_evaluations: usize,
    /// The global search's wall time, s.
    pub search_seconds: f64,
}

/// The number of design variables (the last two the branches' signs).
const DIM: usize = 17;

/// One candidate, decoded from the design vector, with what depends on it alone.
#[derive(Clone, Copy, Debug)]
struct Design {
    o2: V2,
    phi: f64,
    r: [f64; 6],
    u: f64,
    w: f64,
    o6: V2,
    u2: f64,
    w2: f64,
    branch: [f64; 2],
}

fn sign(x: f64) -> f64 {
    if x >= 0.0 {
        1.0
    } else {
        -1.0
    }
}

impl Design {
    fn decode(x: &[f64]) -> Design {
        Design {
            o2: V2::new(x[0], x[1]),
            phi: x[2],
            r: [x[3], x[4], x[5], x[6], x[11], x[12]],
            u: x[7],
            w: x[8],
            o6: V2::new(x[9], x[10]),
            u2: x[13],
            w2: x[14],
            branch: [sign(x[15]), sign(x[16])],
        }
    }

    fn o4(&self) -> V2 {
        self.o2 + V2::new(self.phi.cos(), self.phi.sin()) * self.r[0]
    }

    /// A, B and C at crank angle ψ from the frame line (the four-bar's closed form).
    #[inline]
    fn first(&self, o4: V2, psi: f64) -> Option<(V2, V2, V2)> {
        let t = self.phi + psi;
        let a = self.o2 + V2::new(t.cos(), t.sin()) * self.r[1];
        let b = circle_circle(
            a,
            self.r[2] * self.r[2],
            o4,
            self.r[3] * self.r[3],
            self.branch[0],
        )
        .ok()?;
        let e = (b - a) / self.r[2];
        Some((a, b, a + e * self.u + perp(e) * self.w))
    }

    /// D and P from C (the second dyad's closed form).
    #[inline]
    fn second(&self, c: V2) -> Option<(V2, V2)> {
        let d = circle_circle(
            c,
            self.r[4] * self.r[4],
            self.o6,
            self.r[5] * self.r[5],
            self.branch[1],
        )
        .ok()?;
        let e = (d - c) / self.r[4];
        Some((d, c + e * self.u2 + perp(e) * self.w2))
    }

    fn point(&self, o4: V2, psi: f64) -> Option<V2> {
        let (_, _, c) = self.first(o4, psi)?;
        self.second(c).map(|x| x.1)
    }

    fn ratio(&self) -> f64 {
        length_ratio(&self.r)
    }

    /// The four-bar's violation of a full turn within the bound μ (a cosine; the module's
    /// docs).
    fn crank(&self, mu: f64) -> f64 {
        let [r1, r2, r3, r4, ..] = self.r;
        let (c_lo, c_hi) = usable([r1, r2, r3, r4], mu);
        (c_lo + 1.0).max(0.0) + (1.0 - c_hi).max(0.0)
    }

    /// The second dyad's violation at C within the bound μ (the module's docs).
    fn dyad(&self, c: V2, mu: f64) -> f64 {
        let [.., r5, r6] = self.r;
        let d2 = (c - self.o6).norm_squared();
        let (lo, hi) = dyad_window(r5, r6, mu);
        (lo - d2).max(d2 - hi).max(0.0) / (2.0 * r5 * r6)
    }

    fn six_bar(&self, psi0: f64) -> Option<SixBar> {
        let o4 = self.o4();
        let (a, b, c) = self.first(o4, psi0)?;
        let (d, p) = self.second(c)?;
        Some(SixBar {
            o2: arr(self.o2),
            o4: arr(o4),
            o6: arr(self.o6),
            a: arr(a),
            b: arr(b),
            c: arr(c),
            d: arr(d),
            p: arr(p),
        })
    }
}

impl Prepared {
    /// The four-bar's box of [`super::path`] without its branch, then O6, r₅, r₆, u′, v′
    /// and the two branches (the module's docs).
    fn six_bar_bounds(&self) -> (Vec<f64>, Vec<f64>) {
        let (c, l) = (self.centre, self.size);
        let (mut lo, mut hi) = self.bounds();
        lo.pop();
        hi.pop();
        lo.extend([
            c.x - 2.5 * l,
            c.y - 2.5 * l,
            0.05 * l,
            0.05 * l,
            -3.0 * l,
            -3.0 * l,
            -1.0,
            -1.0,
        ]);
        hi.extend([
            c.x + 2.5 * l,
            c.y + 2.5 * l,
            5.0 * l,
            5.0 * l,
            3.0 * l,
            3.0 * l,
            1.0,
            1.0,
        ]);
        debug_assert_eq!(lo.len(), DIM);
        (lo, hi)
    }

    /// The violations (crank, second dyad, ratio) of a design with the bound μ; C's curve
    /// at [`SEARCH_SAMPLES`] angles left in `buf` when the crank turns.
    fn six_bar_violations(&self, d: &Design, mu: f64, buf: &mut Vec<V2>) -> (f64, f64, f64) {
        if d.r.iter().any(|r| !(*r > 0.0)) {
            return (f64::INFINITY, f64::INFINITY, f64::INFINITY);
        }
        let ratio = (d.ratio() / self.ratio - 1.0).max(0.0);
        let crank = d.crank(mu);
        if crank > 0.0 {
            // The second dyad is not looked at until the crank turns: its worst case.
            return (crank, 1.0, ratio);
        }
        let o4 = d.o4();
        buf.clear();
        let mut dyad = 0.0f64;
        for k in 0..SEARCH_SAMPLES {
            let Some((_, _, c)) = d.first(o4, TAU * k as f64 / SEARCH_SAMPLES as f64) else {
                return (f64::INFINITY, 1.0, ratio);
            };
            dyad = dyad.max(d.dyad(c, mu));
            buf.push(c);
        }
        (0.0, dyad, ratio)
    }

    fn six_bar_evaluate(&self, x: &[f64]) -> Evaluation {
        thread_local! {
            static BUF: RefCell<Vec<V2>> = RefCell::new(Vec::with_capacity(SEARCH_SAMPLES));
        }
        let d = Design::decode(x);
        BUF.with(|b| {
            let buf = &mut *b.borrow_mut();
            let (crank, dyad, ratio) = self.six_bar_violations(&d, self.mu, buf);
            let v = crank + dyad + ratio;
            if v > 0.0 {
                return Evaluation::infeasible(v);
            }
            if let Some(angles) = &self.angles {
                let o4 = d.o4();
                return Evaluation::feasible(
                    self.targets
                        .iter()
                        .zip(angles)
                        .map(|(t, &a)| {
                            d.point(o4, a)
                                .map_or(f64::INFINITY, |p| (p - t).norm_squared())
                        })
                        .sum(),
                );
            }
            // P's curve from C's, in place.
            for c in buf.iter_mut() {
                match d.second(*c) {
                    Some((_, p)) => *c = p,
                    None => return Evaluation::feasible(f64::INFINITY),
                }
            }
            Evaluation::feasible(
                self.targets
                    .iter()
                    .map(|t| polyline_distance2(buf, *t, true))
                    .sum(),
            )
        })
    }

    /// The polish's residuals (fifteen continuous variables, the branches given): each
    /// target's signed normal distance to P's curve (free timing) or the two components
    /// of P(φ + αᵢ) − Tᵢ (prescribed); false where a constraint fails.
    fn six_bar_residuals(&self, x: &[f64], branches: &[f64], r: &mut [f64]) -> bool {
        let mut full = [0.0; DIM];
        full[..DIM - 2].copy_from_slice(x);
        full[DIM - 2..].copy_from_slice(branches);
        let d = Design::decode(&full);
        let mut buf = Vec::new();
        let (crank, dyad, ratio) = self.six_bar_violations(&d, self.mu, &mut buf);
        if crank + dyad + ratio > 0.0 {
            return false;
        }
        let o4 = d.o4();
        if let Some(angles) = &self.angles {
            for (i, (t, &a)) in self.targets.iter().zip(angles).enumerate() {
                let Some(p) = d.point(o4, a) else {
                    return false;
                };
                r[2 * i] = p.x - t.x;
                r[2 * i + 1] = p.y - t.y;
            }
            return true;
        }
        let curve = |psi: f64| d.point(o4, psi).map(arr);
        for (i, &t) in self.targets.iter().enumerate() {
            let (e, psi) = error::nearest_on(curve, 0.0, arr(t));
            if !e.is_finite() {
                return false;
            }
            let dp = 1e-6;
            let (Some(p), Some(p1), Some(p0)) = (
                d.point(o4, psi),
                d.point(o4, psi + dp),
                d.point(o4, psi - dp),
            ) else {
                return false;
            };
            let tan = p1 - p0;
            let n = tan.norm();
            r[i] = if n > 0.0 {
                cross(tan, t - p) / n
            } else {
                (t - p).norm()
            };
        }
        true
    }
}

/// Synthesises a Stephenson III six-bar whose tracer point meets the targets of a closed
/// path (the module's docs), on [`PathOptions`]' budget and bounds. `progress` as for
/// [`super::path::synthesize`]. Errors: those of [`super::path::synthesize`]; an open path
/// (the six-bar's crank turns fully here).
pub fn synthesize(
    problem: &PathProblem,
    options: &PathOptions,
    progress: impl Fn(usize) + Sync,
) -> Result<SixBarSynthesis, PathError> {
    let p = prepare(problem, options)?;
    if !p.closed {
        return Err(PathError::Options(
            "a six-bar is synthesised for closed paths (its crank turns fully); for an open \
             path use the four-bar (--topology four-bar --open)"
                .into(),
        ));
    }
    let (lo, hi) = p.six_bar_bounds();
    let search = islands(&lo, &hi, options, |x| p.six_bar_evaluate(x), progress);
    let (best, best_eval) = search.best();
    if !best_eval.is_feasible() {
        let d = Design::decode(best);
        let mut buf = Vec::new();
        let (crank, dyad, ratio) = p.six_bar_violations(&d, p.mu, &mut buf);
        let (crank0, dyad0, _) = p.six_bar_violations(&d, 0.0, &mut buf);
        let transmission = (crank + dyad - crank0 - dyad0).max(0.0);
        let (binding, miss) = if ratio >= crank0.max(dyad0) && ratio >= transmission {
            (
                Constraint::Ratio,
                format!("a ratio of {:.3} for at most {}", d.ratio(), p.ratio),
            )
        } else if crank0.max(dyad0) >= transmission {
            (
                Constraint::CrankTurns,
                if crank0 >= dyad0 {
                    format!("{crank0:.3e} in the cosine of the crank angle")
                } else {
                    format!("{dyad0:.3e} in the cosine of the second dyad's angle at D")
                },
            )
        } else {
            (
                Constraint::Transmission,
                format!(
                    "{transmission:.3e} in the cosine of an angle at the bound {:.1}°",
                    p.mu.to_degrees()
                ),
            )
        };
        return Err(PathError::Infeasible {
            binding,
            miss,
            evaluations: search.evaluations,
        });
    }
    let m = if p.angles.is_some() {
        2 * p.targets.len()
    } else {
        p.targets.len()
    };
    let (chosen, polish_evaluations) = polish(&search.populations, m, p.size, 2, |y, b, r| {
        p.six_bar_residuals(y, b, r)
    });
    let x = chosen.unwrap_or_else(|| best.clone());
    let d = Design::decode(&x);
    let o4 = d.o4();
    let t0 = arr(p.targets[0]);
    let psi0 = match &p.angles {
        Some(a) => a[0],
        None => error::nearest_on(|psi| d.point(o4, psi).map(arr), 0.0, t0).1,
    };
    let six_bar = d.six_bar(psi0).ok_or_else(|| {
        PathError::Options(
            "the synthesised six-bar does not assemble at its first target (please report)".into(),
        )
    })?;
    let targets: Vec<[f64; 2]> = p.targets.iter().map(|t| arr(*t)).collect();
    let err = match &p.angles {
        Some(a) => six_bar.prescribed_timing(&targets, a),
        None => six_bar.free_timing(&targets),
    };
    let theta0 = six_bar.four_bar().drawn_angle();
    let transmission = (0..720)
        .filter_map(|k| six_bar.transmission_angles(theta0 + TAU * k as f64 / 720.0))
        .map(|(m1, m2)| m1.min(PI - m1).min(m2.min(PI - m2)))
        .fold(f64::INFINITY, f64::min);
    Ok(SixBarSynthesis {
        six_bar,
        error: err,
        transmission,
        ratio: d.ratio(),
        evaluations: search.evaluations,
        generations: search.generations,
        polish_evaluations,
        search_seconds: search.seconds,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn design() -> Design {
        Design::decode(&[
            0.0, 0.0, 0.1, 0.3, 0.08, 0.28, 0.22, 0.1, 0.06, 0.35, 0.35, 0.3, 0.25, 0.12, -0.05,
            1.0, -1.0,
        ])
    }

    /// The candidate's closed forms are the SixBar's: the same A, B, C, D, P at every
    /// crank angle of a turn, every link keeping its length, and the written file loads
    /// into a run-time mechanism whose P follows the same curve.
    #[test]
    fn the_candidate_the_six_bar_and_its_file_agree() {
        let d = design();
        let mut buf = Vec::new();
        let (crank, dyad, ratio) = Prepared {
            targets: vec![],
            angles: None,
            closed: true,
            centre: V2::zeros(),
            size: 1.0,
            mu: 0.0,
            ratio: 10.0,
        }
        .six_bar_violations(&d, 0.0, &mut buf);
        assert_eq!(
            (crank, dyad, ratio),
            (0.0, 0.0, 0.0),
            "the test design must assemble"
        );
        let sb = d.six_bar(0.4).unwrap();
        assert_eq!(sb.branch(), d.branch[1]);
        assert_eq!(sb.four_bar().branch(), d.branch[0]);
        let o4 = d.o4();
        let r = sb.lengths();
        let dist = |a: [f64; 2], b: [f64; 2]| (v(b) - v(a)).norm();
        for k in 0..72 {
            let psi = k as f64 * TAU / 72.0;
            let (a, b, c) = d.first(o4, psi).unwrap();
            let (dd, p) = d.second(c).unwrap();
            let q = sb.pose(d.phi + psi).unwrap();
            for (x, y) in [(a, q.a), (b, q.b), (c, q.c), (dd, q.d), (p, q.p)] {
                assert!(
                    (x.x - y[0]).abs() < 1e-14 && (x.y - y[1]).abs() < 1e-14,
                    "{k}"
                );
            }
            assert!((dist(q.c, q.d) - r[4]).abs() < 1e-14);
            assert!((dist(sb.o6, q.d) - r[5]).abs() < 1e-14);
            assert!((dist(q.c, q.p) - dist(sb.c, sb.p)).abs() < 1e-14);
        }
        let m = crate::Mechanism::from_dsl(&sb.to_mech("Six", "A six-bar")).unwrap();
        for k in 0..12 {
            let q = TAU * k as f64 / 12.0;
            let pose = m.pose(&[q]).unwrap();
            let pp = pose.point("P").unwrap().pos;
            let c = sb.pose(q).unwrap().p;
            assert!(
                (pp.x - c[0]).abs() < 1e-12 && (pp.y - c[1]).abs() < 1e-12,
                "{k}: {pp:?} vs {c:?}"
            );
        }
    }

    /// Ten targets on a known six-bar's curve: the synthesis finds a six-bar through them
    /// (E below 1e-6 of the path's size squared), meeting its constraints.
    #[test]
    fn a_six_bar_curve_is_found_again() {
        let d = design();
        let sb = d.six_bar(0.0).unwrap();
        let targets: Vec<[f64; 2]> = (0..10)
            .map(|k| sb.pose(0.3 + TAU * k as f64 / 10.0).unwrap().p)
            .collect();
        let options = PathOptions {
            seed: 3,
            evaluations: 60_000,
            transmission: 0.0,
            ratio: 20.0,
        };
        let problem = PathProblem {
            targets: targets.clone(),
            angles: None,
            closed: true,
        };
        let s = synthesize(&problem, &options, |_| {}).unwrap();
        let size = 0.3;
        assert!(s.error < 1e-4 * size * size, "E = {}", s.error);
        assert!((s.six_bar.free_timing(&targets) - s.error).abs() <= 1e-12);
        assert!(s.ratio <= 20.0 + 1e-9);
        let open = PathProblem {
            closed: false,
            ..problem
        };
        assert!(matches!(
            synthesize(&open, &options, |_| {}),
            Err(PathError::Options(_))
        ));
    }
}
