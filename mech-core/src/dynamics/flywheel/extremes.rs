//! Samples and extremes over the cycle: [`Cycle::sample`] ([`CyclePoint`]),
//! [`Cycle::extreme`] of any function of (S, I*) by golden-section search ([`Extreme`]),
//! and the maximum fluctuation of energy ([`Fluctuation`]).

use super::cycle::Cycle;
use crate::solvers::traits::OneDof;
use crate::MechError;

/// One sample of a cycle ([`Cycle::sample`]).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct CyclePoint {
    /// Input position q, rad.
    pub q: f64,
    /// Reduced moment M*(q) of every action, driver included, N·m.
    pub moment: f64,
    /// Reduced inertia I*(q), kg·m².
    pub inertia: f64,
    /// dI*/dq, kg·m²/rad.
    pub inertia_derivative: f64,
    /// Accumulated work S(q) = ∫_{q0}^{q} M* dq, J.
    pub work: f64,
}

/// An extreme of a function of (S, I*) over the cycle.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Extreme {
    /// Where, rad (in [q0, q0 + λ)).
    pub q: f64,
    /// S(q), J.
    pub work: f64,
    /// I*(q), kg·m².
    pub inertia: f64,
    /// The function's value there.
    pub value: f64,
}

/// The maximum fluctuation of energy of a cycle ([`Cycle::fluctuation`]).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Fluctuation {
    /// ΔE = S_max − S_min, J.
    pub energy: f64,
    /// The largest accumulated work S_max, J.
    pub s_max: f64,
    /// Where S_max is reached, rad.
    pub q_s_max: f64,
    /// The smallest accumulated work S_min, J.
    pub s_min: f64,
    /// Where S_min is reached, rad.
    pub q_s_min: f64,
}

impl<'a, M: OneDof> Cycle<'a, M> {
    /// The maximum fluctuation of energy over the cycle, ΔE = S_max − S_min (J), with
    /// where S reaches its extremes: the energy the flywheel must store and give back
    /// (`docs/theory.md` §7). Needs a periodic cycle ([`MechError::NotPeriodic`]).
    pub fn fluctuation(&self) -> Result<Fluctuation, MechError> {
        self.check_periodic()?;
        let hi = self.extreme(|s, _| s, true)?;
        let lo = self.extreme(|s, _| s, false)?;
        Ok(Fluctuation {
            energy: hi.value - lo.value,
            s_max: hi.value,
            q_s_max: hi.q,
            s_min: lo.value,
            q_s_min: lo.q,
        })
    }

    /// n + 1 evenly spaced samples q0 + k λ / n, k = 0..=n, of M*, I*, dI*/dq and S.
    pub fn sample(&self, n: usize) -> Result<Vec<CyclePoint>, MechError> {
        if n == 0 {
            return Err(MechError::InvalidInput(
                "sample needs at least one interval".into(),
            ));
        }
        (0..=n)
            .map(|k| {
                let q = self.start + self.period * k as f64 / n as f64;
                let r = self.reduced(q)?;
                Ok(CyclePoint {
                    q,
                    moment: self.moment(q)?,
                    inertia: r.inertia,
                    inertia_derivative: r.inertia_derivative,
                    work: self.work(q)?,
                })
            })
            .collect()
    }

    /// The largest (`maximize`) or smallest value over the cycle of f(S(q), I*(q)):
    /// bracketed on the panel ends, refined by golden-section search.
    pub fn extreme(
        &self,
        f: impl Fn(f64, f64) -> f64,
        maximize: bool,
    ) -> Result<Extreme, MechError> {
        let sign = if maximize { 1.0 } else { -1.0 };
        let h = |q: f64| -> Result<f64, MechError> {
            Ok(sign * f(self.work(q)?, self.reduced(q)?.inertia))
        };
        // Panel ends without the last (it is the first again, one period on).
        let m = self.nodes.len() - 1;
        let vals: Vec<f64> = self.nodes[..m]
            .iter()
            .map(|n| sign * f(n.work, n.inertia))
            .collect();
        if let Some(k) = vals.iter().position(|v| !v.is_finite()) {
            return Err(MechError::InvalidInput(format!(
                "non-finite value at q = {}",
                self.nodes[k].q
            )));
        }
        let (lo, hi) = vals
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &v| {
                (a.min(v), b.max(v))
            });
        let margin = 0.05 * (hi - lo);
        let q_at = |i: isize| -> f64 {
            let (k, shift) = if i < 0 {
                ((i + m as isize) as usize, -self.period)
            } else {
                (i as usize, 0.0)
            };
            self.nodes[k].q + shift
        };
        // The candidates: panel ends at least as high as their neighbours and within the
        // margin of the highest, the highest first.
        let neighbours = |k: usize| (vals[(k + m - 1) % m], vals[(k + 1) % m]);
        let mut candidates: Vec<usize> = (0..m)
            .filter(|&k| {
                let (prev, next) = neighbours(k);
                vals[k] >= prev && vals[k] >= next && vals[k] >= hi - margin
            })
            .collect();
        candidates.sort_by(|&a, &b| vals[b].total_cmp(&vals[a]));
        let mut best: Option<(f64, f64)> = None;
        for k in candidates {
            // A parabola through the three panel ends peaks at most (v_k − min(v_k−1,
            // v_k+1))/8 above the middle one: a candidate that cannot beat the best found
            // so far even by twice its drop is not refined (on a plateau, flat or flat up
            // to rounding, every panel end is a candidate, and each search costs some
            // sixty quadratures).
            let (prev, next) = neighbours(k);
            if best.is_some_and(|(_, b)| vals[k] + 2.0 * (vals[k] - prev.min(next)) <= b) {
                continue;
            }
            let (x, v) = golden_max(h, q_at(k as isize - 1), q_at(k as isize + 1))?;
            let (x, v) = if v >= vals[k] {
                (x, v)
            } else {
                (self.nodes[k].q, vals[k])
            };
            if best.is_none_or(|(_, b)| v > b) {
                best = Some((x, v));
            }
            if margin == 0.0 {
                break;
            }
        }
        let (mut q, _) =
            best.ok_or_else(|| MechError::InvalidInput("no extreme found over the cycle".into()))?;
        if q < self.start {
            q += self.period;
        }
        let (work, inertia) = (self.work(q)?, self.reduced(q)?.inertia);
        Ok(Extreme {
            q,
            work,
            inertia,
            value: f(work, inertia),
        })
    }

    /// The smallest I* over the cycle, kg·m².
    pub(super) fn min_inertia(&self) -> Result<f64, MechError> {
        Ok(self.extreme(|_, i| i, false)?.value)
    }
}

/// The maximum of h on [a, b] (h unimodal there) by golden-section search to
/// |b − a| ≤ 1e-13 max(1, |x|): (x, h(x)).
pub(super) fn golden_max(
    mut h: impl FnMut(f64) -> Result<f64, MechError>,
    mut a: f64,
    mut b: f64,
) -> Result<(f64, f64), MechError> {
    const R: f64 = 0.618_033_988_749_894_9; // (√5 − 1)/2
    let (mut x1, mut x2) = (b - R * (b - a), a + R * (b - a));
    let (mut h1, mut h2) = (h(x1)?, h(x2)?);
    while (b - a).abs() > 1e-13 * a.abs().max(b.abs()).max(1.0) {
        if h1 >= h2 {
            b = x2;
            (x2, h2) = (x1, h1);
            x1 = b - R * (b - a);
            h1 = h(x1)?;
        } else {
            a = x1;
            (x1, h1) = (x2, h2);
            x2 = a + R * (b - a);
            h2 = h(x2)?;
        }
        if x1 == x2 {
            break;
        }
    }
    Ok(if h1 >= h2 { (x1, h1) } else { (x2, h2) })
}
