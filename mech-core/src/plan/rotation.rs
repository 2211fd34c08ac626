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

/// How a moving link's published angle θ (rad) is found: the one rule the generated code
/// (`pose`, `kinematics`, the columns) and the run-time mechanism both follow, so that they
/// publish the same bits. Chosen in this order by [`angle_rule`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum AngleRule {
    /// A crank driven on the ground by input `input`:
    /// θ = `crank_angle(q[input] + zero, sign)` ([`crate::kernel::kinematics::crank_angle`]),
    /// no `atan2`; `sign` = +1 when the crank is its joint's second link, −1 otherwise;
    /// `zero` the input's declared zero (`None` for none: then q itself).
    Crank {
        /// The input that turns the crank.
        input: usize,
        /// ±1, the side of the crank on its joint.
        sign: f64,
        /// The input's zero (rad), if declared.
        zero: Option<f64>,
    },
    /// A link that never turns ([`Model::translates`]): the drawing's angle, its cg not
    /// rotated (`LinkGeom::pose_translating`, `motion_translating`).
    Translating,
    /// A link whose turn the plan keeps exact over turns ([`tracked`]):
    /// `LinkGeom::angle_tracked`, no `atan2`.
    Tracked,
    /// A link that turns with link `m` ([`rotation_partner`]), published before it in
    /// [`angle_order`]: m's angle plus the drawing's difference (`LinkGeom::angle_with`),
    /// no `atan2`.
    With(usize),
    /// Any other link: the `atan2` of its turned reference direction (`LinkGeom::angle`).
    Own,
}

/// The rule of moving link `l`'s published angle ([`AngleRule`]): a crank driven on the
/// ground first, then a link that never turns, a link whose turn is tracked, a link turning
/// with a partner published before it, else its own rotation.
pub fn angle_rule(model: &Model, plan: &[Group], l: usize) -> AngleRule {
    let crank = plan.iter().find_map(|g| match g.kernel {
        Kernel::Driven(d) if d.body == l && d.from == 0 && !d.screw.slide => {
            Some(AngleRule::Crank {
                input: d.input,
                sign: if model.joints[d.screw.joint].b == l {
                    1.0
                } else {
                    -1.0
                },
                zero: match model.input_zero.get(d.input).copied().unwrap_or(0.0) {
                    0.0 => None,
                    z => Some(z),
                },
            })
        }
        _ => None,
    });
    if let Some(c) = crank {
        return c;
    }
    if model.translates(l) {
        return AngleRule::Translating;
    }
    if tracked(model, plan, l) {
        return AngleRule::Tracked;
    }
    let order = angle_order(plan, model.links.len());
    let at = |k: usize| order.iter().position(|&x| x == k);
    match rotation_partner(model, plan, l) {
        Some(m) if at(m) < at(l) => AngleRule::With(m),
        _ => AngleRule::Own,
    }
}

/// The moving links (1..`n_links`) in the order their angles are published: the plan's
/// order, each group's links by number, then any link no group solves. A link turning with
/// a partner ([`AngleRule::With`]) comes after it.
pub fn angle_order(plan: &[Group], n_links: usize) -> Vec<usize> {
    let mut order: Vec<usize> = Vec::with_capacity(n_links);
    for g in plan {
        let mut bodies = g.bodies.clone();
        bodies.sort_unstable();
        order.extend(bodies);
    }
    order.extend(1..n_links);
    let mut seen = vec![false; n_links];
    order.retain(|&l| l != 0 && l < n_links && !std::mem::replace(&mut seen[l], true));
    order
}

#[cfg(test)]
mod tests {
    use super::{angle_order, angle_rule, rotation_partner, AngleRule};
    use crate::front::resolve::model_of;
    use crate::model::Model;
    use crate::plan::assur::plan;

    /// A slotted crank and ram: the block slides in the crank's slot and is pinned to the
    /// ram, which slides on the ground (a PRP dyad).
    fn slotted_crank_and_ram() -> Model {
        model_of(
            "pub struct S { ground { O2: (0.0, 0.0) },
              link crank { points { O2, E: (0.03, 0.08) } },
              link block { points { B: (0.05, 0.09) } },
              link ram { points { B, P: (0.2, 0.1) } },
              joints { O2: revolute(ground, crank),
                       slot: prismatic(crank, block) at B along (1.0, 3.0),
                       B: revolute(block, ram),
                       guide: prismatic(ground, ram) at P along (1.0, -0.1) },
              input: O2 }",
        )
    }

    /// The slotted crank and ram: the block turns with the crank (a PRP dyad's first
    /// slider), the ram slides on the ground (no partner); the crank has none.
    #[test]
    fn a_prp_slider_turns_with_its_guide() {
        let m = slotted_crank_and_ram();
        let p = plan(&m).unwrap();
        let l = |name: &str| m.link_index(name).unwrap();
        assert_eq!(rotation_partner(&m, &p, l("block")), Some(l("crank")));
        assert_eq!(rotation_partner(&m, &p, l("ram")), None);
        assert_eq!(rotation_partner(&m, &p, l("crank")), None);
    }

    /// Each rule of the slotted crank and ram: the crank's from its input (its joint's
    /// second link: sign +1), the block with the crank, the ram never turns.
    #[test]
    fn the_slotted_crank_and_ram_publish_by_three_rules() {
        let m = slotted_crank_and_ram();
        let p = plan(&m).unwrap();
        let l = |name: &str| m.link_index(name).unwrap();
        let crank = AngleRule::Crank {
            input: 0,
            sign: 1.0,
            zero: None,
        };
        assert_eq!(angle_rule(&m, &p, l("crank")), crank);
        assert_eq!(angle_rule(&m, &p, l("block")), AngleRule::With(l("crank")));
        assert_eq!(angle_rule(&m, &p, l("ram")), AngleRule::Translating);
    }

    /// A slider declared before the crank it slides on: its partner has the higher number,
    /// is published first (the crank's group comes first in the plan), and the slider turns
    /// with it; the rod pinned to the ground turns by its own rotation.
    #[test]
    fn a_partner_numbered_after_its_link_is_published_before_it() {
        let m = model_of(
            "pub struct S { ground { O: (0.0, 0.0), A: (0.1, -0.05) },
              link block { points { C: (0.06, 0.02) } },
              link rod { points { A, C } },
              link crank { points { O, E: (0.12, 0.04) } },
              joints { O: revolute(ground, crank),
                       A: revolute(ground, rod),
                       C: revolute(rod, block),
                       slide: prismatic(crank, block) at C along (3.0, 1.0) },
              input: O }",
        );
        let p = plan(&m).unwrap();
        let l = |name: &str| m.link_index(name).unwrap();
        let (block, rod, crank) = (l("block"), l("rod"), l("crank"));
        assert!(crank > block);
        let order = angle_order(&p, m.links.len());
        let at = |k: usize| order.iter().position(|&x| x == k).unwrap();
        assert!(at(crank) < at(block), "order {order:?}");
        assert_eq!(order.len(), 3);
        assert_eq!(angle_rule(&m, &p, block), AngleRule::With(crank));
        assert_eq!(angle_rule(&m, &p, rod), AngleRule::Own);
        assert!(matches!(
            angle_rule(&m, &p, crank),
            AngleRule::Crank { input: 0, .. }
        ));
    }
}
