//! Links that turn together: a prismatic joint keeps its two links' relative rotation, so a
//! slider turns with its guide. The published angle of such a link is its partner's plus
//! the drawing's difference ([`crate::kernel::link_state::LinkGeom::angle_with`]), no
//! `atan2`; the generated code and the run-time mechanism both read it from here, and
//! which links keep their turn exact over turns ([`tracked`]).

use crate::elements::rolling::RollingGroup;
use crate::kernel::dyad::Solver;
use crate::model::Model;
use crate::plan::assur::{Group, Kernel};

/// The moving link that link `l` turns with and whose angle is found before `l`'s, from the
/// plan: the lower-numbered link of an RPR dyad for the other, the moving guide of an RRP
/// dyad's slider, of a slotted slider or of a driven slider, each slider's guide in a PRP
/// dyad, and for both links of an RPP dyad the outer slider's guide. `None` when the
/// partner is the ground (the link never turns: [`Model::translates`]) or there is none.
pub fn rotation_partner(model: &Model, plan: &[Group], l: usize) -> Option<usize> {
    let other = |j: usize, b: usize| model.joints[j].across(b);
    plan.iter().find_map(|g| {
        let m = match g.solver {
            Solver::Rpr { b1, b2, .. } if l == b1.max(b2) => b1.min(b2),
            Solver::Rrp { b2, jp, .. } if b2 == l => other(jp, l),
            Solver::SlottedSlider { body, jq, .. } if body == l => other(jq, l),
            Solver::Prp { b1, jp1, .. } if b1 == l => other(jp1, l),
            Solver::Prp { b2, jp2, .. } if b2 == l => other(jp2, l),
            Solver::Rpp { b1, b2, jq, .. } if b1 == l || b2 == l => other(jq, b2),
            Solver::DrivenPrismatic { body, joint, .. } if body == l => other(joint, l),
            _ => return None,
        };
        (m != 0).then_some(m)
    })
}

/// Whether the plan keeps link `l`'s turn since the drawing exact over turns
/// ([`crate::kernel::link_state::LinkState::angle`]): a meshing link, whose turn is
/// Willis' from its partner's (`plan::assur`'s `track_angles`), and a wheel rolling on a
/// straight track of the ground, whose turn is −s/r (`crate::elements::rolling`). Such a
/// link publishes its angle from that turn
/// ([`crate::kernel::link_state::LinkGeom::angle_tracked`]), no `atan2`.
pub fn tracked(model: &Model, plan: &[Group], l: usize) -> bool {
    let on_ground_line = |j: usize| {
        let jt = &model.joints[j];
        jt.a == 0 && jt.around.is_none()
    };
    plan.iter().any(|g| match &g.kernel {
        Kernel::Mesh(m) => m.body == l,
        Kernel::Train(t) => t.bodies[..t.n].contains(&l),
        Kernel::Rolling(RollingGroup::Driven { body, joint, .. }) => {
            *body == l && on_ground_line(*joint)
        }
        Kernel::Rolling(RollingGroup::Dyad { b2, jr, .. }) => *b2 == l && on_ground_line(*jr),
        _ => false,
    })
}

#[cfg(test)]
mod tests {
    use super::rotation_partner;
    use crate::front::resolve::model_of;
    use crate::plan::assur::plan;

    /// The slotted crank and ram: the block turns with the crank (a PRP dyad's first
    /// slider), the ram slides on the ground (no partner); the crank has none.
    #[test]
    fn a_prp_slider_turns_with_its_guide() {
        let m = model_of(
            "pub struct S { ground { O2: (0.0, 0.0) },
              link crank { points { O2, E: (0.03, 0.08) } },
              link block { points { B: (0.05, 0.09) } },
              link ram { points { B, P: (0.2, 0.1) } },
              joints { O2: revolute(ground, crank),
                       slot: prismatic(crank, block) at B along (1.0, 3.0),
                       B: revolute(block, ram),
                       guide: prismatic(ground, ram) at P along (1.0, -0.1) },
              input: O2 }",
        );
        let p = plan(&m).unwrap();
        let l = |name: &str| m.link_index(name).unwrap();
        assert_eq!(rotation_partner(&m, &p, l("block")), Some(l("crank")));
        assert_eq!(rotation_partner(&m, &p, l("ram")), None);
        assert_eq!(rotation_partner(&m, &p, l("crank")), None);
    }
}
