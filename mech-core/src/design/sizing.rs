//! Sizing, the design cycle closed: the dimensions written `free(LO..HI)` chosen so that
//! every member meets a required factor of safety, the dynamics re-run with each change.
//!
//! The links with free dimensions are sized one after the other, in declaration order.
//! A link's requirement is its own checks and the bearing of the pins in its joints
//! (`strength::track`), each factor ≥ S. With the other links as they are, each free
//! dimension of the link is tried alone, the others held: the smallest value in [LO, HI]
//! that meets the requirement (bisection, the factor taken to grow with the dimension;
//! every trial a whole strength analysis, so the link's own mass and inertia load change
//! with it), rounded up to a step of 1/100 of the range's decade (0.1 mm on a range of
//! 10 mm to 40 mm); the lightest of those is kept ("lightest first"). When no dimension
//! alone is enough, the one with the best factor at HI is set to HI and the others are
//! tried again. A pass sizes every link; the passes repeat, each with the masses and the
//! reactions the previous one left, until no dimension changes (a fixed point: the sizes
//! are on a grid, so the test is exact) or [`MAX_PASSES`].
//!
//! Each pass is a row of [`Sized::iterations`]: the total mass, the peak driver torque,
//! the flywheel for the requested irregularity (Wittenbauer's exact method at the mean
//! speed, `dynamics::flywheel`), and the worst factor.

pub use crate::checks::load::{free_dimensions, FreeDimension};
use crate::dynamics::flywheel::Cycle;
use crate::error::MechError;
use crate::runtime::{Loads, Mechanism};
use crate::strength::Strength;

/// The largest number of passes over the links.
pub const MAX_PASSES: usize = 30;

/// What the sizing must meet, and the cycle it is checked over.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Requirement {
    /// S, the smallest factor of safety every member must have.
    pub safety: f64,
    /// The input's constant speed q̇ (rad/s).
    pub speed: f64,
    /// The period of the cycle (rad).
    pub period: f64,
    /// The instants of each strength analysis.
    pub steps: usize,
    /// The coefficient of fluctuation of speed ε the flywheel column is designed for
    /// (`None`: no flywheel column).
    pub irregularity: Option<f64>,
}

/// One pass of the sizing.
#[derive(Clone, Debug, PartialEq)]
pub struct Iteration {
    /// The free dimensions after the pass, m, in the order of the free list.
    pub dims: Vec<f64>,
    /// The mass of every moving link, kg.
    pub total_mass: f64,
    /// The largest magnitude of the driver's torque over the cycle, N·m.
    pub peak_torque: f64,
    /// The flywheel inertia for the requested irregularity, kg·m².
    pub flywheel: Option<f64>,
    /// The smallest factor of any member, and the member.
    pub worst: f64,
    /// The member with the smallest factor.
    pub worst_member: String,
}

/// The result of a sizing.
#[derive(Clone, Debug)]
pub struct Sized {
    /// The machine with its sized dimensions.
    pub mechanism: Mechanism,
    /// The chosen value of each free dimension, m.
    pub dims: Vec<f64>,
    /// The passes, the last one the fixed point.
    pub iterations: Vec<Iteration>,
    /// The strength of the sized machine.
    pub strength: Strength,
    /// Whether the passes reached a fixed point.
    pub converged: bool,
    /// The members that do not meet S, each with why (a link whose dimensions are all at
    /// HI, a pin or a link with no free dimension).
    pub unmet: Vec<String>,
}

/// The step the dimensions of [LO, HI] are rounded up to: 1/100 of the range's decade.
pub fn grid_step(lo: f64, hi: f64) -> f64 {
    10f64.powf((hi - lo).log10().floor()) / 100.0
}

/// `value` rounded up to the grid of `step` from 0, within [lo, hi].
fn on_grid(value: f64, step: f64, lo: f64, hi: f64) -> f64 {
    let k = (value / step - 1e-9).ceil();
    (k * step).clamp(lo, hi)
}

struct Sizer<'a, F> {
    m: Mechanism,
    free: &'a [FreeDimension],
    req: Requirement,
    loads: F,
}

impl<F: Fn(f64) -> Result<Loads, MechError>> Sizer<'_, F> {
    fn analyse(&mut self) -> Result<Strength, MechError> {
        self.m
            .strength(self.req.speed, self.req.period, self.req.steps, &self.loads)
    }

    fn set(&mut self, k: usize, value: f64) -> Result<(), MechError> {
        let f = &self.free[k];
        self.m
            .set_param(&format!("links.{}.shape.{}", f.link, f.name), &[value])
    }

    /// The smallest factor of the members a link's dimensions act on: its own checks and
    /// the bearing of the pins of its joints.
    fn factor(&mut self, link: &str) -> Result<f64, MechError> {
        let s = self.analyse()?;
        let pins: Vec<String> = self
            .m
            .model()
            .joints
            .iter()
            .filter(|j| {
                let model = self.m.model();
                j.pin.is_some() && (model.links[j.a].name == link || model.links[j.b].name == link)
            })
            .map(|j| format!("{}.pin", j.name))
            .collect();
        let own = s
            .member(link)
            .and_then(|m| m.governing())
            .map_or(f64::INFINITY, |c| c.safety);
        let bearing = pins
            .iter()
            .filter_map(|p| s.member(p)?.check(crate::strength::Criterion::Bearing))
            .map(|c| c.safety)
            .fold(f64::INFINITY, f64::min);
        Ok(own.min(bearing))
    }

    fn mass_of(&self, link: &str) -> f64 {
        let model = self.m.model();
        model
            .links
            .iter()
            .find(|l| l.name == link)
            .and_then(|l| l.mass)
            .unwrap_or(0.0)
    }

    /// The smallest value of free dimension `k` (others held) that meets S, on the grid;
    /// `None` when HI does not.
    fn smallest(&mut self, k: usize) -> Result<Option<f64>, MechError> {
        let (lo, hi, link) = (self.free[k].lo, self.free[k].hi, self.free[k].link.clone());
        let step = grid_step(lo, hi);
        let s = self.req.safety;
        self.set(k, lo)?;
        if self.factor(&link)? >= s {
            return Ok(Some(lo));
        }
        self.set(k, hi)?;
        if self.factor(&link)? < s {
            return Ok(None);
        }
        let (mut a, mut b) = (lo, hi);
        while b - a > step / 2.0 {
            let mid = 0.5 * (a + b);
            self.set(k, mid)?;
            if self.factor(&link)? >= s {
                b = mid;
            } else {
                a = mid;
            }
        }
        let mut v = on_grid(b, step, lo, hi);
        // The grid point below may already meet S (the bisection stops within half a step).
        let below = on_grid(v - step, step, lo, hi);
        if below < v {
            self.set(k, below)?;
            if self.factor(&link)? >= s {
                v = below;
            }
        }
        Ok(Some(v))
    }

    /// Size one link's free dimensions (indices `ks`) with the rest of the machine as it is.
    fn size_link(&mut self, ks: &[usize], dims: &mut [f64]) -> Result<(), MechError> {
        let link = self.free[ks[0]].link.clone();
        let mut open: Vec<usize> = ks.to_vec();
        while !open.is_empty() {
            let mut best: Option<(f64, usize, f64)> = None;
            for &k in &open {
                let held = dims[k];
                if let Some(v) = self.smallest(k)? {
                    self.set(k, v)?;
                    let mass = self.mass_of(&link);
                    if best.is_none_or(|b| mass < b.0) {
                        best = Some((mass, k, v));
                    }
                }
                self.set(k, held)?;
            }
            if let Some((_, k, v)) = best {
                dims[k] = v;
                return self.set(k, v);
            }
            // No dimension alone is enough: the one with the best factor at HI goes there.
            let mut strongest: Option<(f64, usize)> = None;
            for &k in &open {
                let held = dims[k];
                self.set(k, self.free[k].hi)?;
                let f = self.factor(&link)?;
                if strongest.is_none_or(|b| f > b.0) {
                    strongest = Some((f, k));
                }
                self.set(k, held)?;
            }
            let (_, k) = strongest.expect("open is not empty");
            dims[k] = self.free[k].hi;
            self.set(k, dims[k])?;
            open.retain(|&x| x != k);
        }
        Ok(())
    }

    fn row(&mut self, dims: &[f64], s: &Strength) -> Result<Iteration, MechError> {
        let model = self.m.model();
        let total_mass = model.links.iter().skip(1).filter_map(|l| l.mass).sum();
        let (worst_member, worst) = s.worst().map_or((String::new(), f64::INFINITY), |(m, c)| {
            (m.name.clone(), c.safety)
        });
        let flywheel = match self.req.irregularity {
            Some(eps) => {
                let cycle = Cycle::new(&self.m, 0.0, self.req.period, &[], &self.loads, |_| 0.0)?;
                let (cycle, _) = cycle.balanced();
                Some(cycle.flywheel(self.req.speed, eps)?.exact.inertia)
            }
            None => None,
        };
        Ok(Iteration {
            dims: dims.to_vec(),
            total_mass,
            peak_torque: s.driver_peak,
            flywheel,
            worst,
            worst_member,
        })
    }
}

/// Size the free dimensions `free` (from [`crate::checks::load::free_dimensions`] of the
/// machine's text) of `m` to meet `req` under `loads(q)`.
///
/// Errors: S not above 0, a free dimension that `m` does not have, the strength
/// analysis's and the flywheel's own errors.
pub fn size(
    m: &Mechanism,
    free: &[FreeDimension],
    req: Requirement,
    loads: impl Fn(f64) -> Result<Loads, MechError>,
) -> Result<Sized, MechError> {
    if !(req.safety.is_finite() && req.safety > 0.0) {
        return Err(MechError::InvalidInput(format!(
            "the required factor of safety must be a finite number above 0, got {}",
            req.safety
        )));
    }
    if free.is_empty() {
        return Err(MechError::InvalidInput(
            "nothing to size: write a shape's dimension as `free(LO..HI)`, e.g. `shape: bar(width free(10 mm..40 mm), thickness 8 mm)`".into(),
        ));
    }
    let mut z = Sizer {
        m: m.clone(),
        free,
        req,
        loads,
    };
    let mut dims: Vec<f64> = free.iter().map(|f| f.lo).collect();
    for k in 0..free.len() {
        z.set(k, dims[k])?;
    }
    let mut links: Vec<Vec<usize>> = Vec::new();
    for (k, f) in free.iter().enumerate() {
        match links.iter_mut().find(|ks| free[ks[0]].link == f.link) {
            Some(ks) => ks.push(k),
            None => links.push(vec![k]),
        }
    }
    let mut iterations = Vec::new();
    let mut converged = false;
    for _ in 0..MAX_PASSES {
        let before = dims.clone();
        for ks in &links {
            z.size_link(ks, &mut dims)?;
        }
        let s = z.analyse()?;
        iterations.push(z.row(&dims, &s)?);
        if dims == before {
            converged = true;
            break;
        }
    }
    let strength = z.analyse()?;
    let unmet = strength
        .members
        .iter()
        .filter_map(|member| {
            let c = member.governing()?;
            (c.safety < req.safety).then(|| {
                let free_here = free.iter().any(|f| f.link == member.name);
                format!(
                    "{} ({}): safety {:.4} < {}{}",
                    member.name,
                    c.criterion.name(),
                    c.safety,
                    req.safety,
                    if free_here {
                        ": its free dimensions are at HI; widen their ranges or choose a stronger material"
                    } else {
                        ": it has no free dimension; make it larger (a pin's diameter, a section written `free(..)`)"
                    }
                )
            })
        })
        .collect();
    Ok(Sized {
        mechanism: z.m,
        dims,
        iterations,
        strength,
        converged,
        unmet,
    })
}

/// The machine's text with each free dimension written as its sized value (mm, to the
/// decimals of its grid step).
pub fn write_sized(text: &str, free: &[FreeDimension], dims: &[f64]) -> String {
    let mut order: Vec<usize> = (0..free.len()).collect();
    order.sort_by_key(|&k| std::cmp::Reverse(free[k].range.start));
    let mut out = text.to_string();
    for k in order {
        let f = &free[k];
        let step_mm = grid_step(f.lo, f.hi) * 1e3;
        let decimals = (-step_mm.log10()).ceil().max(0.0) as usize;
        out.replace_range(
            f.range.clone(),
            &format!("{:.*} mm", decimals, dims[k] * 1e3),
        );
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_grid_is_a_hundredth_of_the_decade() {
        assert!((grid_step(0.010, 0.040) - 1e-4).abs() < 1e-18);
        assert!((grid_step(0.002, 0.005) - 1e-5).abs() < 1e-18);
        assert!((on_grid(0.02341, 1e-4, 0.01, 0.04) - 0.0235).abs() < 1e-15);
        assert!(
            (on_grid(0.0235, 1e-4, 0.01, 0.04) - 0.0235).abs() < 1e-15,
            "on the grid: kept"
        );
        assert_eq!(on_grid(0.05, 1e-4, 0.01, 0.04), 0.04);
    }
}
