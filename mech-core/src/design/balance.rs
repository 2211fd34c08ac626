//! Balancing (SPEC 3g, `docs/theory.md` §14): the shaking force and moment over a cycle
//! and their summary (peaks, RMS, the primary and secondary harmonics).
//!
//! The shaking of one configuration is [`Machine::shaking`] (the formula is
//! [`crate::kernel::energy::Shaking::add`]); this module samples it over a grid of the
//! first input at a constant speed and sums it up.

use super::nelder_mead::nelder_mead;
use crate::kernel::energy::Shaking;
use crate::model::Model;
use crate::runtime::mechanism::Mechanism;
use crate::solvers::traits::Machine;
use crate::MechError;

/// The shaking over a grid of the first input at a constant speed (the other inputs at
/// rest, q̈ = 0): one entry per grid value.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct ShakingCycle {
    /// The first input q at each sample, rad (or m).
    pub q: Vec<f64>,
    /// The shaking at each sample: force (N) and moment about the origin (N·m).
    pub shaking: Vec<Shaking>,
}

/// The Fourier coefficients of one order n of the shaking over the cycle: with the
/// cycle's phase ψ = 2π (q − q_from)/(q_to − q_from) and N samples (the last grid value,
/// the period's repeat of the first, left out), a = (2/N) Σ F cos nψ, b = (2/N) Σ F sin nψ
/// for each component F, so that F ≈ F₀ + Σ_n a cos nψ + b sin nψ (exact for n < N/2 when
/// F has no harmonics above N/2 − 1).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Harmonic {
    /// The order n (1 primary, 2 secondary).
    pub order: usize,
    /// a and b of F_x, N.
    pub fx: [f64; 2],
    /// a and b of F_y, N.
    pub fy: [f64; 2],
    /// a and b of the moment about the z axis, N·m.
    pub moment: [f64; 2],
    /// a and b of the couple about the x axis, N·m.
    pub mx: [f64; 2],
    /// a and b of the couple about the y axis, N·m.
    pub my: [f64; 2],
}

impl Harmonic {
    /// The amplitude of the order's force, the largest |F| of the ellipse
    /// F(ψ) = a cos nψ + b sin nψ traced by (F_x, F_y): its semi-major axis
    /// √((|a|² + |b|²)/2 + √(((|a|² − |b|²)/2)² + (a·b)²)), with a = (a_x, a_y) and
    /// b = (b_x, b_y) (N). For a force along a line, A of A cos(nψ + φ).
    pub fn force_amplitude(&self) -> f64 {
        semi_major([self.fx[0], self.fy[0]], [self.fx[1], self.fy[1]])
    }
    /// The amplitude of the order's couple about the transverse axes (Mx, My), as
    /// [`Harmonic::force_amplitude`] (N·m).
    pub fn couple_amplitude(&self) -> f64 {
        semi_major([self.mx[0], self.my[0]], [self.mx[1], self.my[1]])
    }
}

/// The semi-major axis of the ellipse a cos t + b sin t (a, b vectors of the plane):
/// √((|a|² + |b|²)/2 + √(((|a|² − |b|²)/2)² + (a·b)²)).
fn semi_major(a: [f64; 2], b: [f64; 2]) -> f64 {
    let (aa, bb, ab) = (
        a[0] * a[0] + a[1] * a[1],
        b[0] * b[0] + b[1] * b[1],
        a[0] * b[0] + a[1] * b[1],
    );
    (0.5 * (aa + bb) + (0.25 * (aa - bb).powi(2) + ab * ab).sqrt()).sqrt()
}

/// Peak and RMS values of a [`ShakingCycle`] and its harmonics of orders 1 and 2.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct ShakingSummary {
    /// max |F| over the samples, N.
    pub peak_force: f64,
    /// √(mean |F|²), N.
    pub rms_force: f64,
    /// max |M| over the samples, N·m.
    pub peak_moment: f64,
    /// √(mean M²), N·m.
    pub rms_moment: f64,
    /// max √(Mx² + My²) over the samples, N·m: the couple about the transverse axes.
    pub peak_couple: f64,
    /// The primary (order 1) and secondary (order 2) harmonics of F.
    pub harmonics: [Harmonic; 2],
}

/// The shaking of `m` at `steps` + 1 values of the first input from `from` to `to` (both
/// included, the grid of `mech sweep`), at the constant input speeds `qd` (one per input,
/// rad/s or m/s), the other inputs at `rest` (`rest[0]` is ignored). Fails where the
/// mechanism does not assemble.
pub fn shaking_cycle(
    m: &Mechanism,
    (from, to, steps): (f64, f64, usize),
    rest: &[f64],
    qd: &[f64],
) -> Result<ShakingCycle, MechError> {
    let g = m.dof();
    if rest.len() != g || qd.len() != g {
        return Err(MechError::InvalidInput(format!(
            "expected {g} input values and {g} speeds"
        )));
    }
    let mut q = rest.to_vec();
    let qdd = vec![0.0; g];
    let mut out = ShakingCycle::default();
    for k in 0..=steps {
        q[0] = if steps == 0 {
            from
        } else {
            from + (to - from) * k as f64 / steps as f64
        };
        let motion = m.motion(&q, qd, &qdd)?;
        out.q.push(q[0]);
        out.shaking.push(m.shaking(&motion));
    }
    Ok(out)
}

impl ShakingCycle {
    /// Peaks, RMS and the harmonics of orders 1 and 2 (see [`Harmonic`]). The RMS and the
    /// harmonics take the samples but the last (the period's repeat of the first) when
    /// there are at least two; the peaks take them all.
    pub fn summary(&self) -> ShakingSummary {
        let all = &self.shaking;
        let n = if all.len() > 1 {
            all.len() - 1
        } else {
            all.len()
        };
        let body = &all[..n];
        let nf = n.max(1) as f64;
        let mean2 =
            |f: &dyn Fn(&Shaking) -> f64| body.iter().map(|s| f(s).powi(2)).sum::<f64>() / nf;
        ShakingSummary {
            peak_force: all.iter().map(|s| s.force.norm()).fold(0.0, f64::max),
            rms_force: mean2(&|s| s.force.norm()).sqrt(),
            peak_moment: all.iter().map(|s| s.moment.abs()).fold(0.0, f64::max),
            rms_moment: mean2(&|s| s.moment).sqrt(),
            peak_couple: all.iter().map(|s| s.mx.hypot(s.my)).fold(0.0, f64::max),
            harmonics: [self.harmonic(1), self.harmonic(2)],
        }
    }

    /// The harmonic of order `order` (see [`Harmonic`]) of every component of the
    /// shaking, over the samples but the last when there are at least two.
    pub fn harmonic(&self, order: usize) -> Harmonic {
        let all = &self.shaking;
        let n = if all.len() > 1 {
            all.len() - 1
        } else {
            all.len()
        };
        let nf = n.max(1) as f64;
        let (from, to) = (
            self.q.first().copied().unwrap_or(0.0),
            self.q.last().copied().unwrap_or(0.0),
        );
        let span = if to != from {
            to - from
        } else {
            std::f64::consts::TAU
        };
        let mut h = Harmonic {
            order,
            ..Harmonic::default()
        };
        for (q, s) in self.q.iter().zip(&all[..n]) {
            let psi = std::f64::consts::TAU * order as f64 * (q - from) / span;
            let (sn, cs) = psi.sin_cos();
            for (c, v) in [
                (&mut h.fx, s.force.x),
                (&mut h.fy, s.force.y),
                (&mut h.moment, s.moment),
                (&mut h.mx, s.mx),
                (&mut h.my, s.my),
            ] {
                c[0] += 2.0 / nf * v * cs;
                c[1] += 2.0 / nf * v * sn;
            }
        }
        h
    }
}

/// A counterweight to add: a point mass (kg) fixed to link `link` (an index into
/// [`crate::model::Model::links`]) at `at`, a point of the drawing (m).
#[derive(Clone, Debug, PartialEq)]
pub struct Counterweight {
    /// The link's index.
    pub link: usize,
    /// The link's name.
    pub name: String,
    /// Mass, kg.
    pub mass: f64,
    /// Where, in the drawing, m.
    pub at: [f64; 2],
}

/// Complex numbers of the plane as `[re, im]`: the product and the quotient.
fn cmul(a: [f64; 2], b: [f64; 2]) -> [f64; 2] {
    [a[0] * b[0] - a[1] * b[1], a[0] * b[1] + a[1] * b[0]]
}
fn cdiv(a: [f64; 2], b: [f64; 2]) -> [f64; 2] {
    let n = b[0] * b[0] + b[1] * b[1];
    [
        (a[0] * b[0] + a[1] * b[1]) / n,
        (a[1] * b[0] - a[0] * b[1]) / n,
    ]
}
fn sub(a: [f64; 2], b: [f64; 2]) -> [f64; 2] {
    [a[0] - b[0], a[1] - b[1]]
}

/// The mechanisms [`force_balance`] knows, with their links and points.
enum Topology {
    /// Ground pivots O2, O4; crank O2–A, coupler A–B, rocker O4–B.
    FourBar {
        crank: usize,
        coupler: usize,
        rocker: usize,
        o2: [f64; 2],
        a: [f64; 2],
        b: [f64; 2],
        o4: [f64; 2],
    },
    /// Crank O2–A, rod A–B, piston at B on a ground guide.
    SliderCrank {
        crank: usize,
        rod: usize,
        piston: usize,
        o2: [f64; 2],
        a: [f64; 2],
        b: [f64; 2],
    },
}

/// Recognise a four-bar (four links, four revolute joints) or a single slider-crank (three
/// revolutes and a prismatic joint of the ground and the piston).
fn topology(model: &Model) -> Result<Topology, MechError> {
    use crate::model::JointKind::{Prismatic, Revolute};
    let refuse = || {
        MechError::InvalidInput(
            "force balance knows a four-bar (four revolute joints) and a single slider-crank (crank, rod, piston on a ground guide); use the optimal method for this mechanism".into(),
        )
    };
    if model.links.len() != 4 || model.joints.len() != 4 {
        return Err(refuse());
    }
    let pos = |j: &crate::model::Joint| model.points[j.point].pos;
    let other = |j: &crate::model::Joint, l: usize| if j.a == l { j.b } else { j.a };
    let grounded: Vec<&crate::model::Joint> = model
        .joints
        .iter()
        .filter(|j| j.a == 0 || j.b == 0)
        .collect();
    let revolutes = model.joints.iter().filter(|j| j.kind == Revolute).count();
    let prismatic = model.joints.iter().filter(|j| j.kind == Prismatic).count();
    let between = |l1: usize, l2: usize| {
        model
            .joints
            .iter()
            .find(|j| (j.a == l1 && j.b == l2) || (j.a == l2 && j.b == l1))
    };
    match (revolutes, prismatic, grounded.as_slice()) {
        (4, 0, [g1, g2]) => {
            let (crank, rocker) = (other(g1, 0), other(g2, 0));
            let coupler = (1..4)
                .find(|&l| l != crank && l != rocker)
                .ok_or_else(refuse)?;
            let (ja, jb) = (
                between(crank, coupler).ok_or_else(refuse)?,
                between(rocker, coupler).ok_or_else(refuse)?,
            );
            Ok(Topology::FourBar {
                crank,
                coupler,
                rocker,
                o2: pos(g1),
                a: pos(ja),
                b: pos(jb),
                o4: pos(g2),
            })
        }
        (3, 1, [g1, g2]) => {
            let (rev, pri) = if g1.kind == Revolute {
                (g1, g2)
            } else {
                (g2, g1)
            };
            if rev.kind != Revolute || pri.kind != Prismatic {
                return Err(refuse());
            }
            let (crank, piston) = (other(rev, 0), other(pri, 0));
            let rod = (1..4)
                .find(|&l| l != crank && l != piston)
                .ok_or_else(refuse)?;
            let (ja, jb) = (
                between(crank, rod).ok_or_else(refuse)?,
                between(rod, piston).ok_or_else(refuse)?,
            );
            if ja.kind != Revolute || jb.kind != Revolute {
                return Err(refuse());
            }
            Ok(Topology::SliderCrank {
                crank,
                rod,
                piston,
                o2: pos(rev),
                a: pos(ja),
                b: pos(jb),
            })
        }
        _ => Err(refuse()),
    }
}

/// The counterweight of first moment `need` (kg·m, a vector) about the pivot `o` on link
/// `link`, at distance `radius` (m) from it, opposite to `need`: mass |need|/radius.
fn opposite(model: &Model, link: usize, o: [f64; 2], need: [f64; 2], radius: f64) -> Counterweight {
    let n = need[0].hypot(need[1]);
    let at = if n > 0.0 {
        [o[0] - radius * need[0] / n, o[1] - radius * need[1] / n]
    } else {
        o
    };
    Counterweight {
        link,
        name: model.links[link].name.clone(),
        mass: n / radius,
        at,
    }
}

/// Force balance (SPEC 3g, `docs/theory.md` §14).
///
/// A four-bar O2–A–B–O4 by the method of linearly independent vectors: with the coupler's
/// cg G3 = A + k (B − A), k the complex ratio (G3 − A)/(B − A), the total cg is
/// stationary when the first moments about the pivots vanish,
/// m₂(G₂ − O₂) + m₃(1 − k)(A − O₂) + m_c2 (P₂ − O₂) = 0 and
/// m₄(G₄ − O₄) + m₃ k (B − O₄) + m_c4 (P₄ − O₄) = 0 (complex products); the counterweights
/// m_c2 at P₂, m_c4 at P₄ are placed at `radius` from their pivots (default: the link's
/// length O₂A, O₄B).
///
/// A single slider-crank: the rod replaced by masses m₃(1 − k) at A (rotating) and m₃ k at
/// B (reciprocating, with the piston's m₄; k the projection of G₃ − A on B − A over
/// |B − A|²); the crank's counterweight takes the crank's own unbalance, the rotating mass
/// and the fraction C = `fraction` of the reciprocating one at A:
/// m_c (P − O₂) = −[m₂(G₂ − O₂) + (m₃(1 − k) + C (m₄ + m₃ k))(A − O₂)], at `radius` from O₂
/// (default |O₂A|). Masses in kg, lengths in m.
pub fn force_balance(
    model: &Model,
    fraction: f64,
    radius: Option<f64>,
) -> Result<Vec<Counterweight>, MechError> {
    if !(0.0..=1.0).contains(&fraction) {
        return Err(MechError::InvalidInput(format!(
            "fraction {fraction}: give the share of the reciprocating mass to balance, 0 to 1"
        )));
    }
    if let Some(r) = radius {
        if !(r > 0.0 && r.is_finite()) {
            return Err(MechError::InvalidInput(format!(
                "radius {r}: give a positive distance from the pivot, m"
            )));
        }
    }
    let first = |l: usize, o: [f64; 2]| {
        let link = &model.links[l];
        let m = link.mass.unwrap_or(0.0);
        [m * (link.cg[0] - o[0]), m * (link.cg[1] - o[1])]
    };
    let mass = |l: usize| model.links[l].mass.unwrap_or(0.0);
    let dist = |p: [f64; 2], q: [f64; 2]| (p[0] - q[0]).hypot(p[1] - q[1]);
    Ok(match topology(model)? {
        Topology::FourBar {
            crank,
            coupler,
            rocker,
            o2,
            a,
            b,
            o4,
        } => {
            let k = cdiv(sub(model.links[coupler].cg, a), sub(b, a));
            let m3 = mass(coupler);
            let s2 = first(crank, o2);
            let t2 = cmul([m3 * (1.0 - k[0]), -m3 * k[1]], sub(a, o2));
            let s4 = first(rocker, o4);
            let t4 = cmul([m3 * k[0], m3 * k[1]], sub(b, o4));
            vec![
                opposite(
                    model,
                    crank,
                    o2,
                    [s2[0] + t2[0], s2[1] + t2[1]],
                    radius.unwrap_or(dist(a, o2)),
                ),
                opposite(
                    model,
                    rocker,
                    o4,
                    [s4[0] + t4[0], s4[1] + t4[1]],
                    radius.unwrap_or(dist(b, o4)),
                ),
            ]
        }
        Topology::SliderCrank {
            crank,
            rod,
            piston,
            o2,
            a,
            b,
        } => {
            let ab = sub(b, a);
            let g3 = sub(model.links[rod].cg, a);
            let k = (g3[0] * ab[0] + g3[1] * ab[1]) / (ab[0] * ab[0] + ab[1] * ab[1]);
            let m3 = mass(rod);
            let at_a = m3 * (1.0 - k) + fraction * (mass(piston) + m3 * k);
            let s2 = first(crank, o2);
            let need = [s2[0] + at_a * (a[0] - o2[0]), s2[1] + at_a * (a[1] - o2[1])];
            vec![opposite(
                model,
                crank,
                o2,
                need,
                radius.unwrap_or(dist(a, o2)),
            )]
        }
    })
}

/// `text` (a mechanism file) with a `counterweight: (MASS kg, at (x, y))` line written at
/// the start of each counterweight's `link NAME {` block; an error when a link's block is
/// not found.
pub fn write_counterweights(text: &str, weights: &[Counterweight]) -> Result<String, MechError> {
    let mut out = text.to_string();
    for w in weights {
        let start = find_link_block(&out, &w.name).ok_or_else(|| {
            MechError::InvalidInput(format!("no `link {} {{` block in the file", w.name))
        })?;
        let line = format!(
            "\n        counterweight: ({:.12e} kg, at ({:.12e}, {:.12e})),",
            w.mass, w.at[0], w.at[1]
        );
        out.insert_str(start, &line);
    }
    Ok(out)
}

/// The byte index just after the `{` of `link NAME {`.
fn find_link_block(text: &str, name: &str) -> Option<usize> {
    let mut from = 0;
    while let Some(i) = text[from..].find("link") {
        let at = from + i;
        from = at + 4;
        let before_ok = at == 0 || !text[..at].ends_with(|c: char| c.is_alphanumeric() || c == '_');
        let rest = &text[from..];
        let trimmed = rest.trim_start();
        if before_ok && rest.len() > trimmed.len() && trimmed.starts_with(name) {
            let after = trimmed[name.len()..].trim_start();
            if after.starts_with('{') {
                return Some(text.len() - after.len() + 1);
            }
        }
    }
    None
}

/// The weights of [`optimal_balance`]'s objective: each RMS over the cycle divided by the
/// unbalanced machine's (a zero RMS counts as 1), times its weight, summed.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BalanceWeights {
    /// Weight of the shaking force's RMS √(mean |F|²).
    pub force: f64,
    /// Weight of the shaking moment's RMS.
    pub moment: f64,
    /// Weight of the driver torque's RMS (no loads, no gravity: the inertia torque).
    pub driver: f64,
}

/// The RMS of |F|, M and the driver action of `m` over a turn of its one input at `speed`
/// (rad/s), `steps` instants, no loads.
fn rms_triple(m: &Mechanism, speed: f64, steps: usize) -> Result<[f64; 3], MechError> {
    let loads = m.loads();
    let mut s = [0.0; 3];
    for k in 0..steps {
        let q = std::f64::consts::TAU * k as f64 / steps as f64;
        let motion = m.motion(&[q], &[speed], &[0.0])?;
        let sh = m.shaking(&motion);
        let d = m.driver_action(&motion, &loads)?[0];
        s[0] += sh.force.norm_squared();
        s[1] += sh.moment * sh.moment;
        s[2] += d * d;
    }
    Ok(s.map(|v| (v / steps as f64).sqrt()))
}

/// Optimal counterweights (SPEC 3g): one on each link pinned to the ground by a revolute
/// joint, at `radius` from its pivot (default the link's first two points' distance), its
/// first moment (kg·m, two components each) chosen to minimise
/// w_F rms(F)/rms₀(F) + w_M rms(M)/rms₀(M) + w_T rms(T)/rms₀(T) over a turn at `speed`
/// (rad/s, 72 instants), rms₀ the machine's without counterweights. The search is
/// Nelder–Mead (`design::nelder_mead`, shared with [`super::optimize`]) over each first
/// moment's components within ±4 S (S = Σ m |cg − first point| of the moving links, plus
/// 1 mm per kg), from no counterweight and a simplex of a tenth of that range per axis,
/// 300 evaluations per variable.
/// `text` is the file the counterweights are written into for each evaluation.
pub fn optimal_balance(
    text: &str,
    speed: f64,
    weights: BalanceWeights,
    radius: Option<f64>,
) -> Result<Vec<Counterweight>, MechError> {
    let m0 = Mechanism::from_dsl(text)?;
    let model = m0.model().clone();
    if m0.dof() != 1 {
        return Err(MechError::InvalidInput(
            "optimal balance takes one input".into(),
        ));
    }
    let pivots: Vec<(usize, [f64; 2], f64)> = model
        .joints
        .iter()
        .filter(|j| j.kind == crate::model::JointKind::Revolute && (j.a == 0 || j.b == 0))
        .map(|j| {
            let l = if j.a == 0 { j.b } else { j.a };
            let o = model.points[j.point].pos;
            let len = model.links[l]
                .points
                .iter()
                .map(|&p| {
                    let q = model.points[p].pos;
                    (q[0] - o[0]).hypot(q[1] - o[1])
                })
                .fold(0.0, f64::max);
            (l, o, radius.unwrap_or(len))
        })
        .filter(|&(_, _, r)| r > 0.0)
        .collect();
    if pivots.is_empty() {
        return Err(MechError::InvalidInput(
            "no link pinned to the ground to carry a counterweight".into(),
        ));
    }
    let steps = 72;
    let base = rms_triple(&m0, speed, steps)?.map(|v| if v > 0.0 { v } else { 1.0 });
    let w = [weights.force, weights.moment, weights.driver];
    let weights_of = |x: &[f64]| -> Vec<Counterweight> {
        pivots
            .iter()
            .enumerate()
            .map(|(i, &(l, o, r))| opposite(&model, l, o, [-x[2 * i], -x[2 * i + 1]], r))
            .collect()
    };
    let cost = |x: &[f64]| -> f64 {
        let eval = || -> Result<f64, MechError> {
            let t = write_counterweights(text, &weights_of(x))?;
            let r = rms_triple(&Mechanism::from_dsl(&t)?, speed, steps)?;
            Ok((0..3).map(|i| w[i] * r[i] / base[i]).sum())
        };
        eval().unwrap_or(f64::INFINITY)
    };
    let scale: f64 = model.links[1..]
        .iter()
        .map(|l| {
            let o = l
                .points
                .first()
                .map(|&p| model.points[p].pos)
                .unwrap_or(l.cg);
            l.mass.unwrap_or(0.0) * (1e-3 + (l.cg[0] - o[0]).hypot(l.cg[1] - o[1]))
        })
        .sum::<f64>()
        .max(1e-12);
    // The unit cube's u ↦ x = 4 S (2u − 1): no counterweight at u = ½.
    let n = 2 * pivots.len();
    let to_x =
        |u: &[f64]| -> Vec<f64> { u.iter().map(|t| 4.0 * scale * (2.0 * t - 1.0)).collect() };
    let cost_u = |u: &[f64]| cost(&to_x(u));
    let centre = vec![0.5; n];
    let mut simplex = vec![(centre.clone(), cost_u(&centre))];
    for i in 0..n {
        let mut u = centre.clone();
        u[i] += 0.1;
        let c = cost_u(&u);
        simplex.push((u, c));
    }
    let (u, _, _) = nelder_mead(
        simplex,
        std::iter::empty(),
        n + 1,
        300 * n,
        cost_u,
        |_, _| {},
    );
    let x = to_x(&u);
    Ok(weights_of(&x)
        .into_iter()
        .filter(|c| c.mass > 0.0)
        .collect())
}
