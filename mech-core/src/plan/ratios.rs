//! Constant velocity coefficients: a machine of gears turning on fixed axes and racks
//! sliding on fixed guides.
//!
//! When the input is on the ground and every other group is one link meshing with a
//! solved one, held by a joint to the ground and carried by the ground (a gear on a fixed
//! axis, a rack on a fixed guide), every link's rate is a constant multiple of the
//! input's: ω_l = k_l q̇ and v_l = k_l q̇ with k_l fixed by the pitch radii (Willis with a
//! fixed carrier). Zhukovski's reduced inertia is then a constant of the drawing,
//! I* = Σ (I_O,l k_l² for a gear, m_l k_l² for a rack), and dI*/dq = 0: the textbook
//! gearbox reduced to its motor shaft. The generated struct and the run-time mechanism
//! work it out once ([`constant_ratios`] tells them when).

use super::assur::{Group, Kernel};
use crate::model::Model;

/// Whether every velocity coefficient of the plan `groups` is a constant: a driven link on
/// the ground, then only meshing groups whose link is held to the ground by its joint and
/// whose carrier is the ground (see the module's docs).
pub fn constant_ratios(model: &Model, groups: &[Group]) -> bool {
    groups.iter().all(|g| match &g.kernel {
        Kernel::Driven(d) => d.from == 0,
        Kernel::Mesh(m) => {
            let pin = &model.joints[m.pin];
            m.carrier == 0 && (pin.a == 0 || pin.b == 0)
        }
        _ => false,
    })
}

#[cfg(test)]
mod tests {
    use super::constant_ratios;
    use crate::front::resolve::model_of;
    use crate::plan::assur::plan;

    fn constant(text: &str) -> bool {
        let m = model_of(text);
        constant_ratios(&m, &plan(&m).unwrap())
    }

    #[test]
    fn a_gearbox_and_a_rack_have_constant_ratios_a_linkage_and_an_epicyclic_have_not() {
        // A pinion driving a gear on a fixed axis and a rack on a fixed guide.
        assert!(constant(
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
        ));
        // The four-bar: its coupler's and rocker's coefficients change with q.
        assert!(!constant(
            "pub struct F { ground { O2: (0.0, 0.0), O4: (0.1, 0.0) },
              link crank { points { O2, A: (0.0, 0.03) } },
              link coupler { points { A, B: (0.09, 0.06) } },
              link rocker { points { O4, B } },
              joints { O2: revolute(ground, crank), A: revolute(crank, coupler),
                       B: revolute(coupler, rocker), O4: revolute(ground, rocker) },
              input: O2 }"
        ));
        // A planet on a driven arm, rolling on a fixed sun: it turns about a moving pin.
        assert!(!constant(
            "pub struct E { ground { O: (0.0, 0.0) },
              link arm { points { O, P: (0.045, 0.0) } },
              link planet { points { P } },
              joints { A: revolute(ground, arm) at O,
                       P: revolute(arm, planet),
                       sp: gear(ground, planet) radii (20 mm, 25 mm) },
              input: A }"
        ));
    }
}
