//! Balancing (SPEC 3g, `docs/theory.md` §15): the shaking force and moment over a cycle
//! and their summary (peaks, RMS, the primary and secondary harmonics).
//!
//! The shaking of one configuration is [`Machine::shaking`] (the formula is
//! [`crate::kernel::energy::Shaking::add`]); this module samples it over a grid of the
//! first input at a constant speed and sums it up.

use crate::kernel::energy::Shaking;
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

/// The Fourier coefficients of one order n of the shaking force over the cycle: with the
/// cycle's phase ψ = 2π (q − q_from)/(q_to − q_from) and N samples (the last grid value,
/// the period's repeat of the first, left out), a = (2/N) Σ F cos nψ, b = (2/N) Σ F sin nψ
/// (N), so that F ≈ Σ_n a cos nψ + b sin nψ.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Harmonic {
    /// The order n (1 primary, 2 secondary).
    pub order: usize,
    /// a and b of F_x, N.
    pub fx: [f64; 2],
    /// a and b of F_y, N.
    pub fy: [f64; 2],
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
        let n = if all.len() > 1 { all.len() - 1 } else { all.len() };
        let body = &all[..n];
        let nf = n.max(1) as f64;
        let mean2 = |f: &dyn Fn(&Shaking) -> f64| body.iter().map(|s| f(s).powi(2)).sum::<f64>() / nf;
        let (from, to) = (
            self.q.first().copied().unwrap_or(0.0),
            self.q.last().copied().unwrap_or(0.0),
        );
        let span = if to != from { to - from } else { std::f64::consts::TAU };
        let harmonic = |order: usize| {
            let mut h = Harmonic {
                order,
                ..Harmonic::default()
            };
            for (q, s) in self.q.iter().zip(body) {
                let psi = std::f64::consts::TAU * order as f64 * (q - from) / span;
                let (sn, cs) = psi.sin_cos();
                h.fx[0] += 2.0 / nf * s.force.x * cs;
                h.fx[1] += 2.0 / nf * s.force.x * sn;
                h.fy[0] += 2.0 / nf * s.force.y * cs;
                h.fy[1] += 2.0 / nf * s.force.y * sn;
            }
            h
        };
        ShakingSummary {
            peak_force: all.iter().map(|s| s.force.norm()).fold(0.0, f64::max),
            rms_force: mean2(&|s| s.force.norm()).sqrt(),
            peak_moment: all.iter().map(|s| s.moment.abs()).fold(0.0, f64::max),
            rms_moment: mean2(&|s| s.moment).sqrt(),
            harmonics: [harmonic(1), harmonic(2)],
        }
    }
}
