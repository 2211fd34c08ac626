//! The checks of one member accumulated over the cycle, one instant after the other.
//!
//! A link ([`LinkTrack`]) is watched at fixed sections (the ends of its span, 32 even steps
//! between, and each side of every point action), at both extreme fibres, σ± = N/A ± M/Z:
//! their largest and smallest values over the cycle give the fatigue check (Goodman, the
//! endurance corrected as [`fatigue`] states, in bending, or axial loading for a
//! two-force member). The static checks take at each instant the worst of those sections
//! and of the exact extremes of M (where V = 0): the normal stress against S_y (`axial`
//! for a link that never bends, `bending` otherwise), the transverse shear k V/A against
//! S_sy = S_y/√3, and a compressive N against the critical stress of the link pinned at
//! both ends over the length L between its first two points (Euler / Johnson).
//!
//! A pin ([`PinTrack`]) carries its joint's reaction R: in shear τ = R/(n π d²/4) against
//! S_sy of steel (`model::shape::MATERIALS[0]`; pins are steel), in bearing p = R/(d t) on
//! the thinner of its links' sections against that link's S_y, and in fatigue: the
//! component of R along each of twelve directions fixed in the joint's first link (a pin
//! whose load turns relative to it sees each fibre reversed), in shear (k_c = 0.59,
//! S_su = 0.67 S_u).

use super::diagram::Diagram;
use super::report::{Check, Criterion, Member};
use super::section::Section;
use super::{buckling, fatigue, pin};
use crate::kernel::link_state::V2;
use crate::model::shape::Material;
use crate::model::Pin;

/// S_sy / S_y by the distortion-energy theory: 1/√3.
pub const SHEAR_YIELD: f64 = 0.577_350_269_189_625_8;
/// S_su / S_u, the ultimate strength in shear.
pub const SHEAR_ULTIMATE: f64 = 0.67;
/// The even steps between the ends of a link's span at which it is watched.
const GRID: usize = 32;

/// The largest and smallest value of a stress over the cycle and where.
#[derive(Clone, Copy, Debug)]
struct Range {
    max: f64,
    q_max: f64,
    min: f64,
    q_min: f64,
}

impl Range {
    const EMPTY: Range = Range {
        max: f64::NEG_INFINITY,
        q_max: 0.0,
        min: f64::INFINITY,
        q_min: 0.0,
    };

    fn add(&mut self, v: f64, q: f64) {
        if v > self.max {
            (self.max, self.q_max) = (v, q);
        }
        if v < self.min {
            (self.min, self.q_min) = (v, q);
        }
    }

    /// The largest magnitude and where it is.
    fn peak(&self) -> (f64, f64) {
        if self.max.abs() >= self.min.abs() {
            (self.max.abs(), self.q_max)
        } else {
            (self.min.abs(), self.q_min)
        }
    }
}

/// The worst value of a static check so far: (stress, q, station).
#[derive(Clone, Copy, Debug, Default)]
struct Peak {
    stress: f64,
    q: f64,
    at: f64,
}

impl Peak {
    fn add(&mut self, stress: f64, q: f64, at: f64) {
        if stress > self.stress {
            *self = Peak { stress, q, at };
        }
    }
}

/// A link's checks over the cycle.
#[derive(Clone, Debug)]
pub struct LinkTrack {
    name: String,
    section: Section,
    material: Material,
    length: f64,
    /// The watched sections: station (m) and which side of a point action.
    stations: Vec<(f64, bool)>,
    /// Per watched section, the fibres σ+ and σ−.
    fibres: Vec<[Range; 2]>,
    normal: Peak,
    bending: f64,
    direct: f64,
    shear: Peak,
    /// The smallest buckling factor: (factor, compressive stress, q, station).
    buckling: Option<(f64, f64, f64, f64)>,
}

impl LinkTrack {
    /// A link named `name` of section `section` and material `material`, L (m) between
    /// its first two points.
    pub fn new(name: &str, section: Section, material: Material, length: f64) -> LinkTrack {
        LinkTrack {
            name: name.to_string(),
            section,
            material,
            length,
            stations: Vec::new(),
            fibres: Vec::new(),
            normal: Peak::default(),
            bending: 0.0,
            direct: 0.0,
            shear: Peak::default(),
            buckling: None,
        }
    }

    fn watch(&mut self, d: &Diagram) {
        let (lo, hi) = d.span();
        let points = d.stations();
        let mut s: Vec<(f64, bool)> = (0..=GRID)
            .map(|k| (lo + (hi - lo) * k as f64 / GRID as f64, false))
            .filter(|(x, _)| !points.iter().any(|p| (p - x).abs() <= 1e-12 * (hi - lo)))
            .collect();
        for &p in &points {
            s.push((p, false));
            s.push((p, true));
        }
        s.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
        self.fibres = vec![[Range::EMPTY; 2]; s.len()];
        self.stations = s;
    }

    /// The instant q (rad) whose actions on the link are `d`.
    pub fn add(&mut self, q: f64, d: &Diagram) {
        if self.stations.is_empty() {
            self.watch(d);
        }
        let (area, z) = (self.section.area, self.section.modulus());
        let mut stations = std::mem::take(&mut self.stations);
        for (k, &(s, past)) in stations.iter().enumerate() {
            let f = d.at(s, past);
            let (direct, bend) = (f.axial / area, f.moment / z);
            self.fibres[k][0].add(direct + bend, q);
            self.fibres[k][1].add(direct - bend, q);
            self.static_at(q, s, f);
        }
        for s in d.shear_zeros() {
            self.static_at(q, s, d.at(s, false));
        }
        self.stations = std::mem::take(&mut stations);
    }

    fn static_at(&mut self, q: f64, s: f64, f: super::diagram::Internal) {
        let sec = &self.section;
        let sigma = sec.normal_stress(f.axial, f.moment).abs();
        self.normal.add(sigma, q, s);
        self.bending = self.bending.max(f.moment.abs() / sec.modulus());
        self.direct = self.direct.max(f.axial.abs() / sec.area);
        self.shear
            .add(sec.shear_factor * f.shear.abs() / sec.area, q, s);
        if f.axial < 0.0 {
            let m = &self.material;
            let slender = self.length / sec.radius_of_gyration();
            let critical = buckling::critical_stress(slender, m.youngs, m.yield_strength);
            let stress = -f.axial / sec.area;
            let factor = critical / stress;
            if self.buckling.is_none_or(|b| factor < b.0) {
                self.buckling = Some((factor, stress, q, s));
            }
        }
    }

    /// Whether the link bends: its largest bending stress is above 10⁻⁹ of its largest
    /// direct one (a two-force member's is round-off).
    fn bends(&self) -> bool {
        self.bending > 1e-9 * self.direct.max(f64::MIN_POSITIVE)
    }

    /// The member's checks.
    pub fn finish(&self) -> Member {
        let m = &self.material;
        let mut checks = Vec::new();
        // The fibre with the largest stress, and the one with the smallest fatigue factor.
        let loading = if self.bends() {
            fatigue::Loading::Bending
        } else {
            fatigue::Loading::Axial
        };
        let se = fatigue::endurance_limit(m.endurance, m.ultimate, self.section.size, loading);
        let mut widest: Option<(f64, Range)> = None;
        let mut fatigue: Option<Check> = None;
        for (&(s, _), pair) in self.stations.iter().zip(&self.fibres) {
            for r in pair {
                if r.max < r.min {
                    continue;
                }
                if widest.is_none_or(|w| r.peak().0 > w.1.peak().0) {
                    widest = Some((s, *r));
                }
                let (mean, alt) = fatigue::mean_and_alternating(r.max, r.min);
                let n = fatigue::goodman(mean, alt, se, m.ultimate);
                if fatigue.is_none_or(|f| n < f.safety) {
                    let (peak, q) = r.peak();
                    fatigue = Some(Check {
                        criterion: Criterion::Fatigue,
                        stress_max: peak,
                        stress_mean: mean,
                        stress_alt: alt,
                        safety: n,
                        q,
                        at: s,
                    });
                }
            }
        }
        let (mean, alt) = widest.map_or((0.0, 0.0), |(_, r)| {
            fatigue::mean_and_alternating(r.max, r.min)
        });
        checks.push(Check {
            criterion: if self.bends() {
                Criterion::Bending
            } else {
                Criterion::Axial
            },
            stress_max: self.normal.stress,
            stress_mean: mean,
            stress_alt: alt,
            safety: m.yield_strength / self.normal.stress,
            q: self.normal.q,
            at: self.normal.at,
        });
        checks.push(Check {
            criterion: Criterion::Shear,
            stress_max: self.shear.stress,
            stress_mean: 0.0,
            stress_alt: 0.0,
            safety: SHEAR_YIELD * m.yield_strength / self.shear.stress,
            q: self.shear.q,
            at: self.shear.at,
        });
        if let Some((factor, stress, q, at)) = self.buckling {
            checks.push(Check {
                criterion: Criterion::Buckling,
                stress_max: stress,
                stress_mean: 0.0,
                stress_alt: 0.0,
                safety: factor,
                q,
                at,
            });
        }
        checks.extend(fatigue);
        checks.sort_by_key(|c| c.criterion);
        Member {
            name: self.name.clone(),
            checks,
        }
    }
}

/// A pin's checks over the cycle.
#[derive(Clone, Debug)]
pub struct PinTrack {
    name: String,
    pin: Pin,
    /// The bore it bears on: its length t (m) and the link's S_y (Pa).
    bore: Option<(f64, f64)>,
    force: Peak,
    /// The reaction's component along twelve directions fixed in the joint's first link.
    along: [Range; 12],
}

impl PinTrack {
    /// The pin of the joint named `joint`, bearing on a bore of length t (m) in a link of
    /// yield strength S_y (Pa), when known.
    pub fn new(joint: &str, pin: Pin, bore: Option<(f64, f64)>) -> PinTrack {
        PinTrack {
            name: format!("{joint}.pin"),
            pin,
            bore,
            force: Peak::default(),
            along: [Range::EMPTY; 12],
        }
    }

    /// The instant q (rad): the reaction R (N) and the angle (rad) of the joint's first link.
    pub fn add(&mut self, q: f64, r: V2, angle: f64) {
        self.force.add(r.norm(), q, 0.0);
        for (k, range) in self.along.iter_mut().enumerate() {
            let phi = angle + std::f64::consts::PI * k as f64 / 12.0;
            range.add(r.x * phi.cos() + r.y * phi.sin(), q);
        }
    }

    /// The member's checks.
    pub fn finish(&self) -> Member {
        let steel = crate::model::shape::MATERIALS[0];
        let (r, q) = (self.force.stress, self.force.q);
        let tau = pin::shear_stress(&self.pin, r);
        let mut checks = vec![Check {
            criterion: Criterion::Shear,
            stress_max: tau,
            stress_mean: 0.0,
            stress_alt: 0.0,
            safety: SHEAR_YIELD * steel.yield_strength / tau,
            q,
            at: 0.0,
        }];
        if let Some((t, yield_strength)) = self.bore {
            let p = pin::bearing_pressure(&self.pin, r, t);
            checks.push(Check {
                criterion: Criterion::Bearing,
                stress_max: p,
                stress_mean: 0.0,
                stress_alt: 0.0,
                safety: yield_strength / p,
                q,
                at: 0.0,
            });
        }
        let se = fatigue::endurance_limit(
            steel.endurance,
            steel.ultimate,
            self.pin.diameter,
            fatigue::Loading::Shear,
        );
        let per_newton = pin::shear_stress(&self.pin, 1.0);
        let fatigue = self
            .along
            .iter()
            .filter(|r| r.max >= r.min)
            .map(|r| {
                let (mean, alt) =
                    fatigue::mean_and_alternating(r.max * per_newton, r.min * per_newton);
                // A shear stress's sign is a convention: its mean counts by magnitude.
                let n = fatigue::goodman(mean.abs(), alt, se, SHEAR_ULTIMATE * steel.ultimate);
                let (peak, q) = r.peak();
                Check {
                    criterion: Criterion::Fatigue,
                    stress_max: peak * per_newton,
                    stress_mean: mean,
                    stress_alt: alt,
                    safety: n,
                    q,
                    at: 0.0,
                }
            })
            .min_by(|a, b| a.safety.total_cmp(&b.safety));
        checks.extend(fatigue);
        Member {
            name: self.name.clone(),
            checks,
        }
    }
}
