//! Numerical path synthesis of four-bars (SPEC §3f): the [`FourBar`] whose coupler point
//! P passes nearest to targets T₁ … Tₙ, with free timing (E = Σᵢ min_θ |P(θ) − Tᵢ|², the
//! [`error::free_timing`] of SPEC §3f) or prescribed timing (E = Σᵢ |P(φ + αᵢ) − Tᵢ|²,
//! αᵢ the crank angle O2 → A of target i measured from the frame line O2 → O4, φ that
//! line's direction: [`error::prescribed_timing`]).
//!
//! **Design variables** (ten): the crank pivot O2 = (x, y), the frame's direction φ, the
//! link lengths r₁ (frame O2O4), r₂ (crank O2A), r₃ (coupler AB), r₄ (rocker O4B), the
//! coupler point (u, v) in the coupler's frame (u along A → B, v across), and the
//! assembly branch (B on the left or the right of A → O4). With L the larger side of the
//! targets' bounding box and c its centre, the search box is O2 ∈ c ± 2.5 L,
//! φ ∈ [−π, π], r₂ ∈ [0.05 L, 2.5 L], r₁, r₃, r₄ ∈ [0.05 L, 5 L], u, v ∈ [−3 L, 3 L].
//!
//! **Constraints**, in closed form from the lengths. With μ_b the bound on the
//! transmission angle μ (the angle at B between the coupler and the rocker,
//! [`FourBar::transmission_angle`]) and d(ψ)² = r₁² + r₂² − 2 r₁ r₂ cos ψ the squared
//! distance A–O4 at crank angle ψ from the frame line, the linkage assembles with
//! μ_b ≤ μ ≤ π − μ_b exactly where
//! D_lo = r₃² + r₄² − 2 r₃ r₄ cos μ_b ≤ d(ψ)² ≤ D_hi = r₃² + r₄² + 2 r₃ r₄ cos μ_b,
//! that is where c_lo ≤ cos ψ ≤ c_hi with c_lo = (r₁² + r₂² − D_hi)/(2 r₁ r₂) and
//! c_hi = (r₁² + r₂² − D_lo)/(2 r₁ r₂): at most two arcs of the crank's circle, symmetric
//! about the frame line.
//! - *Closed path*: the crank turns fully within the transmission bound, c_lo ≤ −1 and
//!   c_hi ≥ 1 (with μ_b = 0 this is Grashof's condition with the crank or the frame the
//!   shortest link: a crank-rocker or a drag link). Violation (c_lo + 1)⁺ + (1 − c_hi)⁺.
//!   The linkage then never reaches a toggle, so it stays on its drawn assembly branch over
//!   the whole turn (what [`FourBar::pose`] follows).
//! - *Open path*: the crank rocks within one arc of the usable set, which must not be
//!   empty: violation (c_lo − 1)⁺ + (−1 − c_hi)⁺; with free timing each target's nearest
//!   point is sought on one arc (the best one); with prescribed timing every αᵢ must lie on
//!   one arc (violation: the angular distance of the others to it, over π).
//! - *Link-length ratio*: max rₖ / min rₖ ≤ R, violation (max/min / R − 1)⁺.
//!
//! The global search is [`differential_evolution`] under Deb's feasibility rules on the
//! sum of the violations, run as [`ISLANDS`] independent populations of [`POPULATION`]
//! vectors sharing the budget (seeds derived from the one given), side by side on the
//! thread pool. Its objective is E on the coupler curve sampled at [`SEARCH_SAMPLES`] crank
//! angles (free timing: each target's distance to the polyline through the samples, the
//! two segments beside its nearest sample). Why four populations: on ten targets sampled
//! from a known crank-rocker's curve (at crank angles π/2 + 0.1 + 2πk/10), a local optimum
//! on the transmission bound (E ≈ 2e-6 m² for a linkage of 0.3 m) captures many single
//! populations; four populations found the exact curve for six seeds of eight at 200 000
//! evaluations, against four of eight for one population (seeds 1–8); on the 18-point path
//! of `tests/data/synthesis`, E was within 1.2 % of the best for all eight seeds (one
//! population: within 66 %).
//!
//! The polish is [`levenberg_marquardt`] on the nine continuous variables (the branch
//! kept) from the best [`POLISH_STARTS`] distinct designs of each population, in parallel
//! (the results taken in order). Its residuals are each target's signed distance to the
//! curve, n̂ · (Tᵢ − P(θᵢ)), with θᵢ re-found at each evaluation (sampled at
//! [`error::SAMPLES`] angles, then a golden-section search) and n̂ the curve's unit normal
//! there (prescribed timing: the two components of P(φ + αᵢ) − Tᵢ); a step that breaks a
//! constraint is refused. The reported error is SPEC §3f's, computed by [`error`] on the
//! result.
//!
//! **The curve of a candidate** is [`FourBar::pose`]'s closed form with the candidate's
//! constants (the lengths, r₃², r₄², the coupler frame, O4) computed once instead of at
//! every angle: `kernel::dyad::circle_circle` for B, P = A + u e + v perp(e). The unit test
//! `the_hoisted_curve_is_the_four_bars_pose` holds it to [`FourBar::pose`] to 1e-15; it
//! takes 27–34 ns an angle where calling [`FourBar::pose`] takes 36–42 ns (1.1–1.5×,
//! three runs of 360 angles × 20 000 on the shared two-core machine, release build).
//! Nothing is allocated to evaluate a candidate: its samples live in a buffer of the
//! thread, its arcs on the stack.

use super::error;
use super::four_bar::FourBar;
use super::optimiser::{
    differential_evolution, levenberg_marquardt, DeSettings, Evaluation, LmSettings, Strategy,
};
use crate::kernel::dyad::circle_circle;
use crate::kernel::link_state::{cross, perp, V2};
use rayon::prelude::*;
use std::cell::RefCell;
use std::f64::consts::{PI, TAU};
use std::fmt;
use std::sync::atomic::{AtomicUsize, Ordering};

/// The crank angles at which the global search samples each candidate's coupler curve
/// over a full turn (an open path's arc gets a share in proportion to its length, at least
/// 32).
pub const SEARCH_SAMPLES: usize = 360;

/// The fewest targets a path takes, with free or prescribed timing.
pub const MIN_TARGETS: usize = 3;

/// The most targets a path takes (each candidate's error is a sum over them, and the
/// check for coincident targets compares every pair).
pub const MAX_TARGETS: usize = 10_000;

/// Two targets closer than this fraction of the targets' extent L are one point.
pub const COINCIDENT: f64 = 1e-9;

/// The vectors of the differential evolution's population.
pub const POPULATION: usize = 60;

/// The independent populations the global search's budget is shared among (fewer when
/// the budget gives each less than ten generations).
pub const ISLANDS: usize = 4;

/// The number of best distinct designs of each final population the polish starts from.
pub const POLISH_STARTS: usize = 3;

/// What a path synthesis is asked for: the targets (m), their crank angles when the
/// timing is prescribed (rad, from the frame line), and whether the path is closed.
#[derive(Clone, Debug, PartialEq)]
pub struct PathProblem {
    /// The targets Tᵢ, m.
    pub targets: Vec<[f64; 2]>,
    /// Prescribed timing: αᵢ, the crank angle O2 → A at target i measured
    /// counter-clockwise from the frame line O2 → O4, rad; `None`: free timing.
    pub angles: Option<Vec<f64>>,
    /// A closed path: the crank turns fully. An open one: the crank rocks within an arc.
    pub closed: bool,
}

/// How a path synthesis runs, and its constraints.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PathOptions {
    /// The seed of the random stream: one seed, one result (whatever the threads).
    pub seed: u64,
    /// The global search's budget: evaluations of a candidate (≥ [`POPULATION`]).
    pub evaluations: usize,
    /// μ_b, the smallest transmission angle allowed over the motion, rad, in [0, π/2).
    pub transmission: f64,
    /// R, the largest ratio of the longest link to the shortest (frame included), ≥ 1.
    pub ratio: f64,
}

impl Default for PathOptions {
    /// Seed 1, 200 000 evaluations, μ_b = 30°, R = 10.
    fn default() -> Self {
        PathOptions {
            seed: 1,
            evaluations: 200_000,
            transmission: 30f64.to_radians(),
            ratio: 10.0,
        }
    }
}

/// A constraint of path synthesis (the module's docs).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Constraint {
    /// A closed path: the crank turns fully (Grashof, the crank or the frame shortest).
    CrankTurns,
    /// An open path: the linkage assembles on one arc through every target.
    Assembly,
    /// The transmission angle stays within [μ_b, π − μ_b] over the motion.
    Transmission,
    /// The longest link over the shortest is at most R.
    Ratio,
}

impl fmt::Display for Constraint {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Constraint::CrankTurns => "the crank turns fully (a closed path)",
            Constraint::Assembly => "the linkage assembles on one arc through every target",
            Constraint::Transmission => "the transmission-angle bound (--transmission)",
            Constraint::Ratio => "the link-length ratio bound (--ratio)",
        })
    }
}

/// Why a path cannot be synthesised.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum PathError {
    /// Fewer targets than [`MIN_TARGETS`].
    #[error("{found} target(s): a path needs at least {MIN_TARGETS}")]
    TooFewTargets {
        /// How many were given.
        found: usize,
    },
    /// More targets than [`MAX_TARGETS`].
    #[error("{found} targets: at most {MAX_TARGETS}; thin the path out")]
    TooManyTargets {
        /// How many were given.
        found: usize,
    },
    /// A coordinate or an angle is NaN or infinite.
    #[error("target {index} (row {row}): {what} is not a finite number")]
    NotFinite {
        /// The target's index, from 0.
        index: usize,
        /// Its row in the table, the header being row 1 (index + 2).
        row: usize,
        /// `x`, `y` or `angle`.
        what: &'static str,
    },
    /// Two targets at the same point.
    #[error("targets {first} and {second} (rows {} and {}) coincide at ({x}, {y}) m: give each point once", first + 2, second + 2)]
    Coincident {
        /// The first one's index.
        first: usize,
        /// The second one's index.
        second: usize,
        /// Their x, m.
        x: f64,
        /// Their y, m.
        y: f64,
    },
    /// Prescribed timing without one angle per target.
    #[error("prescribed timing needs one crank angle per target: {angles} angle(s) for {targets} target(s)")]
    Angles {
        /// Angles given.
        angles: usize,
        /// Targets given.
        targets: usize,
    },
    /// An option outside its range.
    #[error("{0}")]
    Options(String),
    /// No design met the constraints.
    #[error("no four-bar within the search box met the constraints after {evaluations} evaluations; {binding} binds (the best design misses it by {miss}); relax it, or give more --evaluations")]
    Infeasible {
        /// The constraint the best design misses most.
        binding: Constraint,
        /// By how much, in words with the numbers.
        miss: String,
        /// The evaluations made.
        evaluations: usize,
    },
}

/// A synthesised four-bar and how it was found.
#[derive(Clone, Debug, PartialEq)]
pub struct PathSynthesis {
    /// The four-bar, drawn at its crank angle nearest the first target (free timing) or at
    /// the first target's angle (prescribed).
    pub four_bar: FourBar,
    /// E of SPEC §3f, m².
    pub error: f64,
    /// The smallest of min(μ, π − μ) over the motion, μ the transmission angle, rad.
    pub transmission: f64,
    /// The longest link over the shortest.
    pub ratio: f64,
    /// An open path's crank range: the arc [ψ_a, ψ_b] (rad, from the frame line) the crank
    /// rocks within; `None` for a closed path (a full turn).
    pub crank_range: Option<(f64, f64)>,
    /// Evaluations of the global search.
    pub evaluations: usize,
    /// Its generations.
    pub generations: usize,
    /// Residual evaluations of the polish (all starts).
    pub polish_evaluations: usize,
    /// The global search's wall time, s (for evaluations per second).
    pub search_seconds: f64,
}

/// One candidate, decoded from the design vector.
#[derive(Clone, Copy, Debug)]
struct Design {
    o2: V2,
    phi: f64,
    r: [f64; 4],
    u: f64,
    w: f64,
    branch: f64,
}

/// The number of design variables (the last one the branch's sign).
const DIM: usize = 10;

impl Design {
    fn decode(x: &[f64]) -> Design {
        Design {
            o2: V2::new(x[0], x[1]),
            phi: x[2],
            r: [x[3], x[4], x[5], x[6]],
            u: x[7],
            w: x[8],
            branch: if x.get(9).copied().unwrap_or(1.0) >= 0.0 {
                1.0
            } else {
                -1.0
            },
        }
    }

    fn o4(&self) -> V2 {
        self.o2 + V2::new(self.phi.cos(), self.phi.sin()) * self.r[0]
    }

    /// A, B and P at crank angle ψ from the frame line; `None` where it does not assemble.
    #[inline]
    fn pose(&self, o4: V2, psi: f64) -> Option<(V2, V2, V2)> {
        let t = self.phi + psi;
        let a = self.o2 + V2::new(t.cos(), t.sin()) * self.r[1];
        let b = circle_circle(
            a,
            self.r[2] * self.r[2],
            o4,
            self.r[3] * self.r[3],
            self.branch,
        )
        .ok()?;
        let e = (b - a) / self.r[2];
        Some((a, b, a + e * self.u + perp(e) * self.w))
    }

    fn point(&self, o4: V2, psi: f64) -> Option<V2> {
        self.pose(o4, psi).map(|p| p.2)
    }

    /// The usable set c_lo ≤ cos ψ ≤ c_hi (the module's docs).
    fn usable(&self, mu: f64) -> (f64, f64) {
        usable(self.r, mu)
    }

    fn ratio(&self) -> f64 {
        length_ratio(&self.r)
    }

    /// The arcs of the usable set as [ψ_a, ψ_b] with ψ_a < ψ_b (a full turn: one arc of
    /// length 2π), on the stack.
    fn arcs(&self, mu: f64) -> Arcs {
        let (c_lo, c_hi) = self.usable(mu);
        let a_lo = c_hi.clamp(-1.0, 1.0).acos();
        let a_hi = c_lo.clamp(-1.0, 1.0).acos();
        match (c_hi >= 1.0, c_lo <= -1.0) {
            (true, true) => Arcs([(0.0, TAU); 2], 1),
            (true, false) => Arcs([(-a_hi, a_hi); 2], 1),
            (false, true) => Arcs([(a_lo, TAU - a_lo); 2], 1),
            (false, false) => Arcs([(a_lo, a_hi), (-a_hi, -a_lo)], 2),
        }
    }

    fn four_bar(&self, psi0: f64) -> Option<FourBar> {
        let o4 = self.o4();
        let (a, b, p) = self.pose(o4, psi0)?;
        let arr = |v: V2| [v.x, v.y];
        Some(FourBar {
            o2: arr(self.o2),
            o4: arr(o4),
            a: arr(a),
            b: arr(b),
            p: arr(p),
        })
    }
}

/// The squared distances [D_lo, D_hi] between the free ends of a dyad of links `a` and `b`
/// (m) within which its transmission angle stays in [μ, π − μ]: a² + b² ∓ 2 a b cos μ, m².
pub(super) fn dyad_window(a: f64, b: f64, mu: f64) -> (f64, f64) {
    let (mid, k) = (a * a + b * b, 2.0 * a * b * mu.cos());
    (mid - k, mid + k)
}

/// The usable set c_lo ≤ cos ψ ≤ c_hi of a four-bar of lengths r = [r₁, r₂, r₃, r₄] with
/// the transmission bound μ (the module's docs).
pub(super) fn usable(r: [f64; 4], mu: f64) -> (f64, f64) {
    let [r1, r2, r3, r4] = r;
    let (lo, hi) = dyad_window(r3, r4, mu);
    let s = r1 * r1 + r2 * r2;
    ((s - hi) / (2.0 * r1 * r2), (s - lo) / (2.0 * r1 * r2))
}

/// The longest of the lengths `r` over the shortest.
pub(super) fn length_ratio(r: &[f64]) -> f64 {
    let max = r.iter().copied().fold(0.0, f64::max);
    let min = r.iter().copied().fold(f64::INFINITY, f64::min);
    max / min
}

/// A final population: (design vector, its evaluation), best first.
pub(super) type Population = Vec<(Vec<f64>, Evaluation)>;

/// One or two arcs of crank angles ψ (rad, from the frame line): the first `.1` of `.0`.
#[derive(Clone, Copy, Debug)]
struct Arcs([(f64, f64); 2], usize);

impl Arcs {
    fn as_slice(&self) -> &[(f64, f64)] {
        &self.0[..self.1]
    }
}

/// The validated problem with its scale.
pub(super) struct Prepared {
    pub(super) targets: Vec<V2>,
    pub(super) angles: Option<Vec<f64>>,
    pub(super) closed: bool,
    pub(super) centre: V2,
    pub(super) size: f64,
    pub(super) mu: f64,
    pub(super) ratio: f64,
}

/// The problem validated (targets, angles, options: [`PathError`]) with its scale: the
/// targets' bounding box's centre and larger side.
pub(super) fn prepare(problem: &PathProblem, options: &PathOptions) -> Result<Prepared, PathError> {
    let n = problem.targets.len();
    for (i, t) in problem.targets.iter().enumerate() {
        for (k, what) in [(0, "x"), (1, "y")] {
            if !t[k].is_finite() {
                return Err(PathError::NotFinite {
                    index: i,
                    row: i + 2,
                    what,
                });
            }
        }
    }
    if let Some(a) = &problem.angles {
        if a.len() != n {
            return Err(PathError::Angles {
                angles: a.len(),
                targets: n,
            });
        }
        if let Some(i) = a.iter().position(|v| !v.is_finite()) {
            return Err(PathError::NotFinite {
                index: i,
                row: i + 2,
                what: "angle",
            });
        }
    }
    if n < MIN_TARGETS {
        return Err(PathError::TooFewTargets { found: n });
    }
    if n > MAX_TARGETS {
        return Err(PathError::TooManyTargets { found: n });
    }
    if !(options.transmission >= 0.0 && options.transmission < 0.5 * PI) {
        return Err(PathError::Options(format!(
            "--transmission {}°: the bound on the transmission angle must be in [0°, 90°) (μ must stay within [μ_b, 180° − μ_b] while the crank moves)",
            options.transmission.to_degrees()
        )));
    }
    if !(options.ratio >= 1.0) {
        return Err(PathError::Options(format!(
            "--ratio {}: the longest link over the shortest is at least 1",
            options.ratio
        )));
    }
    if options.evaluations < POPULATION {
        return Err(PathError::Options(format!(
            "--evaluations {}: the search needs at least {POPULATION} (one population)",
            options.evaluations
        )));
    }
    let targets: Vec<V2> = problem
        .targets
        .iter()
        .map(|t| V2::new(t[0], t[1]))
        .collect();
    let (mut lo, mut hi) = (targets[0], targets[0]);
    for t in &targets {
        lo = lo.inf(t);
        hi = hi.sup(t);
    }
    let size = (hi - lo).max();
    for i in 0..n {
        for j in i + 1..n {
            if (targets[i] - targets[j]).norm() <= COINCIDENT * size {
                return Err(PathError::Coincident {
                    first: i,
                    second: j,
                    x: targets[i].x,
                    y: targets[i].y,
                });
            }
        }
    }
    Ok(Prepared {
        targets,
        angles: problem.angles.clone(),
        closed: problem.closed,
        centre: (lo + hi) * 0.5,
        size,
        mu: options.transmission,
        ratio: options.ratio,
    })
}

impl Prepared {
    /// The search box of the module's docs (the last coordinate the branch's sign).
    pub(super) fn bounds(&self) -> (Vec<f64>, Vec<f64>) {
        let (c, l) = (self.centre, self.size);
        (
            vec![
                c.x - 2.5 * l,
                c.y - 2.5 * l,
                -PI,
                0.05 * l,
                0.05 * l,
                0.05 * l,
                0.05 * l,
                -3.0 * l,
                -3.0 * l,
                -1.0,
            ],
            vec![
                c.x + 2.5 * l,
                c.y + 2.5 * l,
                PI,
                5.0 * l,
                2.5 * l,
                5.0 * l,
                5.0 * l,
                3.0 * l,
                3.0 * l,
                1.0,
            ],
        )
    }

    /// Each constraint's violation (dimensionless, ≥ 0): crank/assembly (with the
    /// transmission bound), the same without it, and the ratio.
    fn violations(&self, d: &Design) -> (f64, f64, f64) {
        if d.r.iter().any(|r| !(*r > 0.0)) {
            return (f64::INFINITY, f64::INFINITY, f64::INFINITY);
        }
        let geometric = |mu: f64| {
            let (c_lo, c_hi) = d.usable(mu);
            if self.closed {
                (c_lo + 1.0).max(0.0) + (1.0 - c_hi).max(0.0)
            } else {
                let empty = (c_lo - 1.0).max(0.0) + (-1.0 - c_hi).max(0.0);
                if empty > 0.0 {
                    return empty;
                }
                match &self.angles {
                    None => 0.0,
                    Some(a) => {
                        // Every prescribed angle on one arc: the arc holding the most.
                        let arcs = d.arcs(mu);
                        let miss = |arc: &(f64, f64), psi: f64| {
                            let p = (psi - arc.0).rem_euclid(TAU);
                            if p <= arc.1 - arc.0 {
                                0.0
                            } else {
                                (p - (arc.1 - arc.0)).min(TAU - p)
                            }
                        };
                        arcs.as_slice()
                            .iter()
                            .map(|arc| a.iter().map(|&psi| miss(arc, psi)).sum::<f64>() / PI)
                            .fold(f64::INFINITY, f64::min)
                    }
                }
            }
        };
        (
            geometric(self.mu),
            geometric(0.0),
            (d.ratio() / self.ratio - 1.0).max(0.0),
        )
    }

    fn violation(&self, d: &Design) -> f64 {
        let (g, _, r) = self.violations(d);
        g + r
    }

    /// The global search's objective of a feasible design (module docs).
    fn search_objective(&self, d: &Design, buf: &mut Vec<V2>) -> f64 {
        let o4 = d.o4();
        if let Some(angles) = &self.angles {
            return self
                .targets
                .iter()
                .zip(angles)
                .map(|(t, &a)| {
                    d.point(o4, a)
                        .map_or(f64::INFINITY, |p| (p - t).norm_squared())
                })
                .sum();
        }
        let mut best = f64::INFINITY;
        for &(a, b) in d.arcs(self.mu).as_slice() {
            let full = self.closed || b - a >= TAU;
            let n = if full {
                SEARCH_SAMPLES
            } else {
                ((SEARCH_SAMPLES as f64 * (b - a) / TAU) as usize).max(32)
            };
            buf.clear();
            for k in 0..n {
                let psi = if full {
                    a + TAU * k as f64 / n as f64
                } else {
                    a + (b - a) * k as f64 / (n - 1) as f64
                };
                match d.point(o4, psi) {
                    Some(p) => buf.push(p),
                    None => return f64::INFINITY,
                }
            }
            let e: f64 = self
                .targets
                .iter()
                .map(|t| polyline_distance2(buf, *t, full))
                .sum();
            best = best.min(e);
        }
        best
    }

    fn evaluate(&self, x: &[f64]) -> Evaluation {
        let d = Design::decode(x);
        let v = self.violation(&d);
        if v > 0.0 {
            return Evaluation::infeasible(v);
        }
        thread_local! {
            static BUF: RefCell<Vec<V2>> = RefCell::new(Vec::with_capacity(SEARCH_SAMPLES));
        }
        BUF.with(|b| Evaluation::feasible(self.search_objective(&d, &mut b.borrow_mut())))
    }

    /// The nearest point of the arc [a, b] (or the full turn) to `t`: (ψ, P).
    fn nearest(&self, d: &Design, o4: V2, (a, b): (f64, f64), t: V2) -> Option<(f64, V2)> {
        let full = self.closed || b - a >= TAU;
        let n = error::SAMPLES;
        let h = if full {
            TAU / n as f64
        } else {
            (b - a) / (n - 1) as f64
        };
        let mut best = (f64::INFINITY, 0.0);
        for k in 0..n {
            let psi = a + h * k as f64;
            let p = d.point(o4, psi)?;
            let e = (p - t).norm_squared();
            if e < best.0 {
                best = (e, psi);
            }
        }
        let f = |psi: f64| {
            d.point(o4, psi)
                .map_or(f64::INFINITY, |p| (p - t).norm_squared())
        };
        let (mut lo, mut hi) = (best.1 - h, best.1 + h);
        if !full {
            lo = lo.max(a);
            hi = hi.min(b);
        }
        let g = 0.5 * (5f64.sqrt() - 1.0);
        let (mut c, mut e) = (hi - g * (hi - lo), lo + g * (hi - lo));
        let (mut fc, mut fe) = (f(c), f(e));
        for _ in 0..100 {
            if hi - lo <= 1e-15 * (1.0 + hi.abs()) {
                break;
            }
            if fc < fe {
                (hi, e, fe) = (e, c, fc);
                c = hi - g * (hi - lo);
                fc = f(c);
            } else {
                (lo, c, fc) = (c, e, fe);
                e = lo + g * (hi - lo);
                fe = f(e);
            }
        }
        let psi = if fc.min(fe) <= best.0 {
            if fc < fe {
                c
            } else {
                e
            }
        } else {
            best.1
        };
        Some((psi, d.point(o4, psi)?))
    }

    /// The arc the targets are met on: the full turn (closed), the arc of the prescribed
    /// angles, or the arc with the smallest free-timing error.
    fn arc(&self, d: &Design) -> Option<(f64, f64)> {
        let arcs = d.arcs(self.mu);
        let arcs = arcs.as_slice();
        if self.closed || arcs.len() == 1 {
            return arcs.first().copied();
        }
        let o4 = d.o4();
        arcs.iter()
            .map(|&arc| {
                let e: f64 = match &self.angles {
                    Some(a) => a
                        .iter()
                        .map(|&psi| {
                            let p = (psi - arc.0).rem_euclid(TAU);
                            if p <= arc.1 - arc.0 {
                                0.0
                            } else {
                                1.0
                            }
                        })
                        .sum(),
                    None => self
                        .targets
                        .iter()
                        .map(|&t| {
                            self.nearest(d, o4, arc, t)
                                .map_or(f64::INFINITY, |n| (n.1 - t).norm_squared())
                        })
                        .sum(),
                };
                (arc, e)
            })
            .fold((None, f64::INFINITY), |b, (arc, e)| {
                if e < b.1 {
                    (Some(arc), e)
                } else {
                    b
                }
            })
            .0
    }

    /// The polish's residuals at x (nine variables, the branch given): false where a
    /// constraint fails or the linkage does not assemble.
    fn residuals(&self, x: &[f64], branch: f64, r: &mut [f64]) -> bool {
        let mut full = [0.0; DIM];
        full[..DIM - 1].copy_from_slice(x);
        full[DIM - 1] = branch;
        let d = Design::decode(&full);
        if self.violation(&d) > 0.0 {
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
        let Some(arc) = self.arc(&d) else {
            return false;
        };
        for (i, &t) in self.targets.iter().enumerate() {
            let Some((psi, p)) = self.nearest(&d, o4, arc, t) else {
                return false;
            };
            // The normal component of T − P (smooth through 0); at an end of an open arc,
            // where T may lie beyond the curve, the whole distance with that sign.
            let full = self.closed || arc.1 - arc.0 >= TAU;
            let dp = 1e-6;
            let (lo, hi) = if full {
                (psi - dp, psi + dp)
            } else {
                ((psi - dp).max(arc.0), (psi + dp).min(arc.1))
            };
            let (Some(p1), Some(p0)) = (d.point(o4, hi), d.point(o4, lo)) else {
                return false;
            };
            let tan = p1 - p0;
            let n = tan.norm();
            let normal = if n > 0.0 {
                cross(tan, t - p) / n
            } else {
                (t - p).norm()
            };
            let at_end = !full && (psi - arc.0 <= 1e-9 || arc.1 - psi <= 1e-9);
            r[i] = if at_end {
                (t - p).norm().copysign(normal)
            } else {
                normal
            };
        }
        true
    }
}

/// The squared distance from `t` to the polyline through `pts` (closed when `wrap`): the
/// nearest vertex, then the two segments beside it.
pub(super) fn polyline_distance2(pts: &[V2], t: V2, wrap: bool) -> f64 {
    let n = pts.len();
    let (mut k, mut best) = (0, f64::INFINITY);
    for (i, p) in pts.iter().enumerate() {
        let e = (p - t).norm_squared();
        if e < best {
            best = e;
            k = i;
        }
    }
    let seg = |a: V2, b: V2| {
        let ab = b - a;
        let l2 = ab.norm_squared();
        if l2 == 0.0 {
            return (a - t).norm_squared();
        }
        let s = ((t - a).dot(&ab) / l2).clamp(0.0, 1.0);
        (a + ab * s - t).norm_squared()
    };
    if wrap || k > 0 {
        best = best.min(seg(pts[(k + n - 1) % n], pts[k]));
    }
    if wrap || k + 1 < n {
        best = best.min(seg(pts[k], pts[(k + 1) % n]));
    }
    best
}

/// The global search's result: the final populations (best first each), the evaluations
/// and generations they took, and the wall time, s.
pub(super) struct Islands {
    pub(super) populations: Vec<Population>,
    pub(super) evaluations: usize,
    pub(super) generations: usize,
    pub(super) seconds: f64,
}

impl Islands {
    /// The best design of all the populations (Deb's rules; the first on a tie).
    pub(super) fn best(&self) -> &(Vec<f64>, Evaluation) {
        let best_of = |a: &(Vec<f64>, Evaluation), b: &(Vec<f64>, Evaluation)| {
            b.1.better(&a.1) && !a.1.better(&b.1)
        };
        let mut overall = &self.populations[0][0];
        for pop in &self.populations[1..] {
            if best_of(overall, &pop[0]) {
                overall = &pop[0];
            }
        }
        overall
    }
}

/// The global search of the module's docs over the box [lo, hi]: [`ISLANDS`] populations
/// of [`POPULATION`] vectors under Deb's rules, each on its share of the budget (at least
/// ten generations each), side by side on the pool, each depending on its own seed alone.
/// `progress(evaluations)` as for [`synthesize`].
pub(super) fn islands(
    lo: &[f64],
    hi: &[f64],
    options: &PathOptions,
    evaluate: impl Fn(&[f64]) -> Evaluation + Sync,
    progress: impl Fn(usize) + Sync,
) -> Islands {
    let start = std::time::Instant::now();
    // A basin that captures one population seldom captures them all; they run side by
    // side on the pool (each also evaluates its trials in parallel), so the threads meet
    // once per population rather than once per generation.
    let islands = ISLANDS.min(options.evaluations / (10 * POPULATION)).max(1);
    let done = AtomicUsize::new(0);
    let runs: Vec<(Population, usize, usize)> = (0..islands)
        .into_par_iter()
        .map(|i| {
            let share = options.evaluations / islands;
            let budget = if i + 1 == islands {
                options.evaluations - share * (islands - 1)
            } else {
                share
            };
            let mut last = 0;
            let de = differential_evolution(
                lo,
                hi,
                DeSettings {
                    strategy: Strategy::CurrentToPBest,
                    population: POPULATION,
                    evaluations: budget,
                    seed: options.seed ^ (i as u64).wrapping_mul(0x9E37_79B9_7F4A_7C15),
                },
                &evaluate,
                |n| {
                    let total = done.fetch_add(n - last, Ordering::Relaxed) + n - last;
                    last = n;
                    progress(total);
                },
            );
            (de.population, de.evaluations, de.generations)
        })
        .collect();
    Islands {
        evaluations: runs.iter().map(|r| r.1).sum(),
        generations: runs.iter().map(|r| r.2).sum(),
        populations: runs.into_iter().map(|r| r.0).collect(),
        seconds: start.elapsed().as_secs_f64(),
    }
}

/// The polish of the module's docs: [`levenberg_marquardt`] on the continuous variables
/// (all but the last `branches`, which are kept) from the best [`POLISH_STARTS`] distinct
/// feasible designs of each population, in parallel, `m` residuals filled by
/// `residuals(continuous, branches, r)`. The best polished design (`None` when no polish
/// has a finite cost) and the residual evaluations made.
pub(super) fn polish(
    populations: &[Population],
    m: usize,
    size: f64,
    branches: usize,
    residuals: impl Fn(&[f64], &[f64], &mut [f64]) -> bool + Sync,
) -> (Option<Vec<f64>>, usize) {
    let mut starts: Vec<&Vec<f64>> = Vec::new();
    for pop in populations {
        let mut taken = 0;
        for (x, e) in pop {
            if !e.is_feasible() || taken >= POLISH_STARTS {
                break;
            }
            if starts.iter().all(|s| {
                s.iter()
                    .zip(x)
                    .any(|(a, b)| (a - b).abs() > 1e-9 * size.max(1.0))
            }) {
                starts.push(x);
                taken += 1;
            }
        }
    }
    // The polishes in parallel, their results in the order of the starts.
    let polished: Vec<(Vec<f64>, f64, usize)> = starts
        .par_iter()
        .map(|x| {
            let split = x.len() - branches;
            let branch = &x[split..];
            let lm = levenberg_marquardt(
                &x[..split],
                m,
                LmSettings {
                    iterations: 300,
                    scale: size,
                },
                |y, r| residuals(y, branch, r),
            );
            let mut full = lm.x;
            full.extend_from_slice(branch);
            (full, lm.cost, lm.evaluations)
        })
        .collect();
    let evaluations = polished.iter().map(|c| c.2).sum();
    let mut chosen: Option<(Vec<f64>, f64)> = None;
    for (x, cost, _) in polished {
        let better = match &chosen {
            None => true,
            Some(c) => cost < c.1,
        };
        if cost.is_finite() && better {
            chosen = Some((x, cost));
        }
    }
    (chosen.map(|c| c.0), evaluations)
}

/// Synthesises a four-bar whose coupler point meets the targets (the module's docs).
/// `progress(evaluations)` is called, from the pool's threads, with the evaluations made
/// so far as the global search proceeds (at most `options.evaluations`).
pub fn synthesize(
    problem: &PathProblem,
    options: &PathOptions,
    progress: impl Fn(usize) + Sync,
) -> Result<PathSynthesis, PathError> {
    let p = prepare(problem, options)?;
    let (lo, hi) = p.bounds();
    let search = islands(&lo, &hi, options, |x| p.evaluate(x), progress);
    let (used, generations, search_seconds) =
        (search.evaluations, search.generations, search.seconds);
    let populations = &search.populations;
    let overall = search.best();
    let (best, best_eval) = overall;
    if !best_eval.is_feasible() {
        let d = Design::decode(best);
        let (g, g0, r) = p.violations(&d);
        // The constraint the best design misses most: the ratio, the full turn (or the
        // assembly) without the transmission bound, or what the bound adds to it.
        let transmission = (g - g0).max(0.0);
        let (binding, miss) = if r >= g0 && r >= transmission {
            (
                Constraint::Ratio,
                format!("a ratio of {:.3} for at most {}", d.ratio(), p.ratio),
            )
        } else if g0 >= transmission {
            (
                if p.closed {
                    Constraint::CrankTurns
                } else {
                    Constraint::Assembly
                },
                format!("{g0:.3e} in the cosine of the crank angle"),
            )
        } else {
            (
                Constraint::Transmission,
                format!(
                    "{transmission:.3e} in the cosine of the crank angle at the bound {:.1}°",
                    p.mu.to_degrees()
                ),
            )
        };
        return Err(PathError::Infeasible {
            binding,
            miss,
            evaluations: used,
        });
    }
    // The polish, from the best few distinct feasible designs.
    let m = if p.angles.is_some() {
        2 * p.targets.len()
    } else {
        p.targets.len()
    };
    let (chosen, polish_evaluations) = polish(populations, m, p.size, 1, |y, branch, r| {
        p.residuals(y, branch[0], r)
    });
    let x = chosen.unwrap_or_else(|| best.clone());
    let d = Design::decode(&x);
    let arc = p.arc(&d).unwrap_or((0.0, TAU));
    let o4 = d.o4();
    // Drawn at the first target's crank angle.
    let psi0 = match &p.angles {
        Some(a) => a[0],
        None => p.nearest(&d, o4, arc, p.targets[0]).map_or(arc.0, |n| n.0),
    };
    let four_bar = d.four_bar(psi0).ok_or_else(|| {
        PathError::Options(
            "the synthesised linkage does not assemble at its first target (please report)".into(),
        )
    })?;
    let targets: Vec<[f64; 2]> = p.targets.iter().map(|t| [t.x, t.y]).collect();
    let err = match &p.angles {
        Some(a) => error::prescribed_timing(&four_bar, &targets, a),
        None => error::free_timing(&four_bar, &targets),
    };
    let full = p.closed || arc.1 - arc.0 >= TAU;
    let transmission = (0..=720)
        .filter_map(|k| {
            let psi = arc.0 + (arc.1 - arc.0) * k as f64 / 720.0;
            four_bar.transmission_angle(error::frame_angle(&four_bar) + psi)
        })
        .map(|mu| mu.min(PI - mu))
        .fold(f64::INFINITY, f64::min);
    Ok(PathSynthesis {
        four_bar,
        error: err,
        transmission,
        ratio: d.ratio(),
        crank_range: if full { None } else { Some(arc) },
        evaluations: used,
        generations,
        polish_evaluations,
        search_seconds,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn design() -> Design {
        Design {
            o2: V2::new(0.1, -0.2),
            phi: 0.3,
            r: [0.3, 0.1, 0.27, 0.22],
            u: 0.12,
            w: 0.08,
            branch: -1.0,
        }
    }

    /// The candidate's curve is FourBar::pose's closed form: the same A, B and P at every
    /// crank angle (to 1e-15 m, the round-off of a few operations on 0.3 m).
    #[test]
    fn the_hoisted_curve_is_the_four_bars_pose() {
        let d = design();
        let fb = d.four_bar(0.4).unwrap();
        assert_eq!(fb.branch(), d.branch);
        let o4 = d.o4();
        for k in 0..72 {
            let psi = k as f64 * TAU / 72.0;
            let (a, b, p) = d.pose(o4, psi).unwrap();
            let q = fb.pose(d.phi + psi).unwrap();
            for (x, y) in [(a, q.a), (b, q.b), (p, q.p)] {
                // measured worst 1.1e-16 (this commit); 10×, round-off of a few operations
                assert!(
                    (x.x - y[0]).abs() < 1e-15 && (x.y - y[1]).abs() < 1e-15,
                    "{k}"
                );
            }
        }
    }

    /// The closed-form constraint is the sampled one: a crank-rocker whose transmission
    /// angle dips to μ_min is feasible for μ_b just below μ_min and not just above.
    #[test]
    fn the_transmission_bound_is_the_sampled_minimum() {
        let d = design();
        let fb = d.four_bar(0.0).unwrap();
        let mu_min = (0..3600)
            .filter_map(|k| fb.transmission_angle(k as f64 * TAU / 3600.0))
            .map(|m| m.min(PI - m))
            .fold(f64::INFINITY, f64::min);
        let problem = |mu: f64| Prepared {
            targets: vec![],
            angles: None,
            closed: true,
            centre: V2::zeros(),
            size: 1.0,
            mu,
            ratio: 10.0,
        };
        assert!(mu_min > 0.1, "{mu_min}");
        assert_eq!(problem(mu_min - 1e-4).violation(&d), 0.0);
        assert!(problem(mu_min + 1e-4).violation(&d) > 0.0);
    }

    /// An open path's arcs: for a triple rocker (no link turns fully), the crank angles
    /// inside the arcs are exactly those where the linkage assembles with μ_b ≤ μ ≤ π − μ_b
    /// (sampled every 0.1°, away from the arcs' ends by a step).
    #[test]
    fn the_arcs_are_where_the_linkage_assembles_within_the_bound() {
        let d = Design {
            r: [0.3, 0.25, 0.12, 0.2],
            ..design()
        };
        let mu = 20f64.to_radians();
        let arcs = d.arcs(mu);
        assert_eq!(arcs.as_slice().len(), 2, "{arcs:?}");
        let fb = d.four_bar(0.5 * (arcs.0[0].0 + arcs.0[0].1)).unwrap();
        let h = TAU / 3600.0;
        let (mut inside, mut outside) = (0, 0);
        for k in 0..3600 {
            let psi = -PI + h * k as f64;
            let near = |a: f64| ((psi - a + PI).rem_euclid(TAU) - PI).abs() < h;
            if arcs.as_slice().iter().any(|&(a, b)| near(a) || near(b)) {
                continue;
            }
            let within = arcs.as_slice().iter().any(|&(a, b)| {
                let p = (psi - a).rem_euclid(TAU);
                p <= b - a
            });
            let ok = fb
                .transmission_angle(d.phi + psi)
                .is_some_and(|m| m >= mu && m <= PI - mu);
            assert_eq!(within, ok, "ψ = {psi}");
            if within {
                inside += 1;
            } else {
                outside += 1;
            }
        }
        assert!(inside > 100 && outside > 100, "{inside} {outside}");
    }

    /// Bad input: each is refused with its own error.
    #[test]
    fn bad_targets_are_refused() {
        let o = PathOptions::default();
        let run = |targets: Vec<[f64; 2]>, angles: Option<Vec<f64>>| {
            synthesize(
                &PathProblem {
                    targets,
                    angles,
                    closed: true,
                },
                &o,
                |_| {},
            )
            .unwrap_err()
        };
        assert_eq!(
            run(vec![[0.0, 0.0], [1.0, 0.0]], None),
            PathError::TooFewTargets { found: 2 }
        );
        assert!(matches!(
            run(vec![[0.0, 0.0], [1.0, f64::NAN], [0.0, 1.0]], None),
            PathError::NotFinite {
                index: 1,
                what: "y",
                ..
            }
        ));
        assert!(matches!(
            run(vec![[0.0, 0.0], [1.0, 0.0], [0.0, 0.0]], None),
            PathError::Coincident {
                first: 0,
                second: 2,
                ..
            }
        ));
        assert!(matches!(
            run(
                vec![[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]],
                Some(vec![0.0, 1.0])
            ),
            PathError::Angles {
                angles: 2,
                targets: 3
            }
        ));
    }

    /// The 18 targets of `tests/data/synthesis/kunjur18.csv`.
    const KUNJUR18: [[f64; 2]; 18] = [
        [0.5, 1.1],
        [0.4, 1.1],
        [0.3, 1.1],
        [0.2, 1.0],
        [0.1, 0.9],
        [0.05, 0.75],
        [0.02, 0.6],
        [0.0, 0.5],
        [0.0, 0.4],
        [0.03, 0.3],
        [0.1, 0.25],
        [0.15, 0.2],
        [0.2, 0.3],
        [0.3, 0.4],
        [0.4, 0.5],
        [0.5, 0.7],
        [0.6, 0.9],
        [0.6, 1.0],
    ];

    /// The comparison in `optimiser`'s docs: the search objective (before the polish) of
    /// DE/current-to-pbest/1, DE/rand/1 and uniform random sampling on the 18-point path,
    /// seeds 1–8, 100 000 evaluations each; the median of current-to-pbest is the lowest.
    /// Long (24 runs): `cargo test --release -p mech-core de_variants -- --ignored
    /// --nocapture`.
    #[test]
    #[ignore]
    fn de_variants() {
        let p = prepare(
            &PathProblem {
                targets: KUNJUR18.to_vec(),
                angles: None,
                closed: true,
            },
            &PathOptions::default(),
        )
        .unwrap();
        let (lo, hi) = p.bounds();
        let median = |strategy| {
            let mut e: Vec<f64> = (1..=8)
                .map(|seed| {
                    let s = DeSettings {
                        strategy,
                        population: POPULATION,
                        evaluations: 100_000,
                        seed,
                    };
                    differential_evolution(&lo, &hi, s, |x| p.evaluate(x), |_| {}).population[0]
                        .1
                        .objective
                })
                .collect();
            e.sort_by(f64::total_cmp);
            println!("{strategy:?}: {e:?}");
            0.5 * (e[3] + e[4])
        };
        let (pbest, rand, random) = (
            median(Strategy::CurrentToPBest),
            median(Strategy::Rand),
            median(Strategy::Random),
        );
        println!("medians: current-to-pbest {pbest:.4e}, rand {rand:.4e}, random {random:.4e}");
        assert!(pbest < rand && pbest < random);
    }
}
