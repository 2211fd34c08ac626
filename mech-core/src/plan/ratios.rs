//! Constant ratios: machines of gears, where every link's angular velocity is a constant
//! multiple of the input's.
//!
//! When the input is on the ground and every other group is a gear meshing with solved
//! ones (one link, or a train solved together) held by a revolute pin (or a rack sliding
//! on the ground), Willis' relations are linear with constant coefficients: every link's
//! angular rate is ω_l = k_l q̇ with k_l fixed by the pitch radii, so its angle is
//! φ_l = k_l (q − q₀) from a reference q₀. Each link then hangs from the ground through a
//! chain of pins ([`Pin`]), and the velocity coefficient of any of its points is a sum of
//! vectors turning at the chain's rates, g(q) = Σ_i R(k_i (q − q₀)) a_i: Zhukovski's I* is
//! a short trigonometric sum of q (`crate::solvers::zhukovski_series`), one term per pair
//! of links on a chain. Gears on fixed axes and racks on fixed guides (every chain one
//! link long) leave no term: I* is a constant of the drawing, the textbook gearbox reduced
//! to its motor shaft. The generated struct and the run-time mechanism work the sum out
//! once ([`pins`] tells them when, [`series_len`] its length).

use super::assur::{Group, Kernel};
use crate::model::{JointKind, Model};

/// How a moving link hangs from the links solved before it in a machine of constant
/// ratios: held by `joint` to `parent` (0 the ground), about whose point it turns, or
/// along which it slides (`slides`: a slider or a rack on the ground, which does not turn).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Pin {
    /// The link it is held by (0: the ground).
    pub parent: usize,
    /// The joint that holds it.
    pub joint: usize,
    /// It slides on the ground instead of turning about the joint.
    pub slides: bool,
}

/// Every link's [`Pin`] (index by link; the ground's entry unused) when every angular
/// velocity coefficient of the plan `groups` is a constant: a driven link on the ground
/// (or pinned to a link of constant ratio), then only gear groups whose links are held by
/// revolute pins, or slide on the ground (see the module's docs); `None` for any other
/// machine.
pub fn pins(model: &Model, groups: &[Group]) -> Option<Vec<Pin>> {
    let ground = Pin {
        parent: 0,
        joint: usize::MAX,
        slides: false,
    };
    let mut out = vec![ground; model.links.len()];
    let mut hold = |body: usize, joint: usize, slides: bool| -> Option<()> {
        let j = model.joints.get(joint)?;
        let parent = if j.b == body { j.a } else { j.b };
        let kind_fits = if slides {
            j.kind == JointKind::Prismatic && parent == 0
        } else {
            j.kind == JointKind::Revolute
        };
        kind_fits.then(|| {
            out[body] = Pin {
                parent,
                joint,
                slides,
            }
        })
    };
    for g in groups {
        match &g.kernel {
            Kernel::Driven(d) => hold(d.body, d.screw.joint, d.screw.slide)?,
            Kernel::Mesh(m) => hold(m.body, m.pin, m.body_slides)?,
            Kernel::Train(t) => {
                for k in 0..t.n {
                    hold(t.bodies[k], t.pins[k], false)?;
                }
            }
            _ => return None,
        }
    }
    Some(out)
}

/// The links from `l` down to the one held by the ground, `l` first (`pins` of
/// [`pins`]; at most as many as the links, so that a malformed table cannot loop).
pub(crate) fn chain(pins: &[Pin], l: usize) -> impl Iterator<Item = usize> + '_ {
    let mut next = (l != 0).then_some(l);
    (0..pins.len()).map_while(move |_| {
        let here = next?;
        let up = pins[here].parent;
        next = (up != 0).then_some(up);
        Some(here)
    })
}

/// The number of oscillating terms of I* (`crate::solvers::zhukovski_series`): one per
/// pair of links on each moving link's chain, Σ_l n_l (n_l − 1)/2; 0 when every gear
/// turns on a fixed axis.
pub fn series_len(pins: &[Pin]) -> usize {
    (1..pins.len())
        .map(|l| {
            let n = chain(pins, l).count();
            n * n.saturating_sub(1) / 2
        })
        .sum()
}

#[cfg(test)]
mod tests {
    use super::{chain, pins, series_len};
    use crate::front::resolve::model_of;
    use crate::plan::assur::plan;

    /// A planet on a driven arm, rolling on a fixed sun: it turns about a moving pin.
    const EPICYCLIC: &str = "pub struct E { ground { O: (0.0, 0.0) },
          link arm { points { O, P: (0.045, 0.0) } },
          link planet { points { P } },
          joints { A: revolute(ground, arm) at O,
                   P: revolute(arm, planet),
                   sp: gear(ground, planet) radii (20 mm, 25 mm) },
          input: A }";

    /// The number of terms of I* of `text`, `None` when it is not a machine of gears.
    fn terms(text: &str) -> Option<usize> {
        let m = model_of(text);
        pins(&m, &plan(&m).unwrap()).map(|p| series_len(&p))
    }

    #[test]
    fn a_gearbox_and_a_rack_leave_no_term_an_epicyclic_one_a_linkage_no_series() {
        // A pinion driving a gear on a fixed axis and a rack on a fixed guide: I* constant.
        assert_eq!(
            terms(
                "pub struct G { ground { O: (0.0, 0.0), C: (0.05, 0.0) },
                  link pinion { points { O } },
                  link gear { points { C } },
                  link rack { points { R: (0.0, -0.02) } },
                  joints { O: revolute(ground, pinion),
                           C: revolute(ground, gear),
                           pg: gear(pinion, gear) radii (20 mm, 30 mm),
                           guide: prismatic(ground, rack) at R along (1.0, 0.0),
                           pr: rack(pinion, rack) radius 20 mm },
                  input: O }"
            ),
            Some(0)
        );
        // The planet's chain (planet, arm) is one pair; the arm's a single link.
        assert_eq!(terms(EPICYCLIC), Some(1));
        // The four-bar and the slider-crank: their coefficients are not sums of turns.
        assert_eq!(
            terms(
                "pub struct F { ground { O2: (0.0, 0.0), O4: (0.1, 0.0) },
                  link crank { points { O2, A: (0.0, 0.03) } },
                  link coupler { points { A, B: (0.09, 0.06) } },
                  link rocker { points { O4, B } },
                  joints { O2: revolute(ground, crank), A: revolute(crank, coupler),
                           B: revolute(coupler, rocker), O4: revolute(ground, rocker) },
                  input: O2 }"
            ),
            None
        );
        assert_eq!(
            terms(
                "pub struct S { ground { O: (0.0, 0.0) },
                  link crank { points { O, A: (0.03, 0.0) } },
                  link rod { points { A, B: (0.12, 0.0) } },
                  link piston { points { B } },
                  joints { O: revolute(ground, crank), A: revolute(crank, rod),
                           B: revolute(rod, piston),
                           guide: prismatic(ground, piston) at B along (1.0, 0.0) },
                  input: O }"
            ),
            None
        );
    }

    #[test]
    fn an_epicyclic_hangs_its_planet_from_the_arm() {
        let m = model_of(EPICYCLIC);
        let p = pins(&m, &plan(&m).unwrap()).expect("a gear train");
        let (arm, planet) = (
            m.link_index("arm").unwrap(),
            m.link_index("planet").unwrap(),
        );
        assert_eq!((p[arm].parent, p[planet].parent), (0, arm));
        assert!(!p[arm].slides && !p[planet].slides);
        assert_eq!(chain(&p, planet).collect::<Vec<_>>(), vec![planet, arm]);
        assert_eq!(chain(&p, 0).count(), 0);
    }
}
