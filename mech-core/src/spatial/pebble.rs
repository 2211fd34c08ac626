//! Over-constrained sub-chains of a spatial mechanism (check 3) by the (6,6) pebble game.
//!
//! Every link, the ground included, is a rigid body with 6 DOF (6 pebbles); every scalar
//! equation is a bar between two bodies: a joint of class k is 6 − k bars between its
//! links, an input 1 bar between its joint's links, and the spin fix of an idle link (a
//! link between two spherical joints, [`super::kutzbach::idle_freedoms`]) 1 bar between
//! the ground and that link (the solvers and the rank check hold its spin by one row
//! between them). A rigid set of k bodies keeps the 6 DOF of one body, so its bars can
//! remove at most 6k − 6; by Tay's theorem a generic body-bar framework is independent
//! exactly when no set of bodies spans more. The game is the planar one
//! ([`crate::checks::pebble`]) with 6 pebbles per body: a set it finds spans more bars than
//! 6k − 6, whatever the dimensions, so the check finds a rigid truss hidden beside a
//! freedom that makes Kutzbach's overall count look right, and names its links (the rank
//! at the drawing names only a joint whose equations repeat). Redundancy that depends on
//! the dimensions (parallel axes) is left to the rank at the drawing.

use super::kutzbach::idle_freedoms;
use super::model::{Finding, Site, SpatialModel};
use crate::checks::pebble::over_constrained;

/// Pebbles of a body in space (its DOF), also the trivial motions of a rigid set: a set of
/// k bodies can lose at most 6k − 6 DOF.
const K: usize = 6;

/// Where a bar comes from.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Source {
    /// An equation of joint `j`.
    Joint(usize),
    /// The driver of the input at joint `j`.
    Input(usize),
    /// The spin fix of the idle link `b` (a bar between the ground and `b`).
    Spin(usize),
}

/// The bars of the body-bar graph: (body a, body b, source), the joints' 6 − class each in
/// joint order, then one per input, then one per idle spin (between the ground and the
/// link).
fn bars(model: &SpatialModel) -> Vec<(usize, usize, Source)> {
    let mut out = Vec::new();
    for (j, jt) in model.joints.iter().enumerate() {
        for _ in 0..6 - jt.kind.class() {
            out.push((jt.a, jt.b, Source::Joint(j)));
        }
    }
    for &j in &model.inputs {
        let jt = &model.joints[j];
        out.push((jt.a, jt.b, Source::Input(j)));
    }
    for (b, _, _) in idle_freedoms(model) {
        out.push((0, b, Source::Spin(b)));
    }
    out
}

fn names(items: impl Iterator<Item = String>) -> String {
    items
        .map(|n| format!("`{n}`"))
        .collect::<Vec<_>>()
        .join(", ")
}

fn plural(n: usize, one: &str, many: &str) -> String {
    format!("{n} {}", if n == 1 { one } else { many })
}

/// Check 3 of `docs/conventions.md#checks` in space: one [`Finding`] per over-constrained
/// sub-chain, a set of k links whose joints (with the inputs and the idle links' spin fixes
/// among them) impose more equations than the 6k − 6 DOF a rigid set of k links can lose,
/// found by the (6,6) pebble game on the body-bar graph (6 − class bars per joint, 1 per
/// input, 1 between the ground and each idle link). The finding is at the set's first
/// moving link; the other links (the ground last) and the joints among them are involved
/// (and the inputs when they over-drive the set). The message names the links, the
/// equations against 6k − 6, the excess and the fix. Returns nothing with
/// `#[allow(redundant)]`.
pub(crate) fn check(model: &SpatialModel) -> Vec<Finding> {
    if model.allow_redundant {
        return Vec::new();
    }
    let bars = bars(model);
    let pairs: Vec<(usize, usize)> = bars.iter().map(|&(a, b, _)| (a, b)).collect();
    let mut out = Vec::new();
    for block in over_constrained(model.bodies.len(), &pairs, K) {
        let links: Vec<usize> = (0..model.bodies.len())
            .filter(|&l| block.links[l])
            .collect();
        let k = links.len();
        let with_ground = block.links[0];
        let moving: Vec<usize> = links.iter().copied().filter(|&l| l != 0).collect();
        let joints: Vec<usize> = (0..model.joints.len())
            .filter(|&j| block.links[model.joints[j].a] && block.links[model.joints[j].b])
            .collect();
        let mut inputs: Vec<usize> = Vec::new();
        let mut spins: Vec<usize> = Vec::new();
        for &i in &block.bars {
            match bars[i].2 {
                Source::Input(j) if !inputs.contains(&j) => inputs.push(j),
                Source::Spin(b) => spins.push(b),
                _ => {}
            }
        }
        let by_joints: usize = joints
            .iter()
            .map(|&j| 6 - model.joints[j].kind.class())
            .sum();
        let fixed = by_joints + spins.len();
        let total = fixed + inputs.len();
        let capacity = 6 * k - 6;
        let link_names = |ls: &[usize]| names(ls.iter().map(|&l| model.bodies[l].name.clone()));
        let joint_names = |js: &[usize]| names(js.iter().map(|&j| model.joints[j].name.clone()));
        let link_list = format!(
            "{} {}{}",
            if moving.len() == 1 { "link" } else { "links" },
            link_names(&moving),
            if with_ground {
                " (with the ground)"
            } else {
                ""
            }
        );
        let joint_list = format!(
            "their {} ({})",
            plural(joints.len(), "joint", "joints"),
            joint_names(&joints)
        );
        let spin_list = format!(
            "the spin {} of {} {}",
            if spins.len() == 1 { "fix" } else { "fixes" },
            if spins.len() == 1 { "link" } else { "links" },
            link_names(&spins)
        );
        let rigid_set = format!(
            "a rigid set of {k} links{}",
            if with_ground {
                " (the ground among them)"
            } else {
                ""
            }
        );
        let over_driven = !inputs.is_empty() && fixed <= capacity;
        let message = if over_driven {
            let spin_text = if spins.is_empty() {
                String::new()
            } else {
                format!(" and {spin_list}")
            };
            format!(
                "{link_list} are over-driven: {joint_list}{spin_text} impose {fixed} of the 6·{k} − 6 = {capacity} equations {rigid_set} can take, leaving them {}, but {} ({}) drive them ({}): move an input to a part of the mechanism that is not yet driven, or remove it",
                plural(capacity - fixed, "freedom", "freedoms"),
                plural(inputs.len(), "input", "inputs"),
                joint_names(&inputs),
                plural(block.excess, "redundant equation", "redundant equations"),
            )
        } else {
            let mut extra: Vec<String> = Vec::new();
            if !inputs.is_empty() {
                extra.push(format!(
                    "{} ({})",
                    plural(inputs.len(), "input", "inputs"),
                    joint_names(&inputs)
                ));
            }
            if !spins.is_empty() {
                extra.push(spin_list);
            }
            let extra = if extra.is_empty() {
                String::new()
            } else {
                format!(
                    " and {} {}, {total} in all,",
                    extra.join(" and "),
                    if inputs.len() + spins.len() == 1 {
                        "1 more"
                    } else {
                        "1 each"
                    }
                )
            };
            format!(
                "{link_list} form an over-constrained sub-chain: {joint_list} impose {by_joints} equations{extra} but {rigid_set} can lose only 6·{k} − 6 = {capacity} ({}): the sub-chain is rigid and its reactions are statically indeterminate. Replace a joint by one that leaves more freedom (e.g. a revolute (5 equations) by a universal (4) or a spherical (3) joint), or remove a link or a joint; add #[allow(redundant)] if the redundancy is intended",
                plural(block.excess, "redundant equation", "redundant equations"),
            )
        };
        let mut involved: Vec<Site> = moving[1..].iter().map(|&l| Site::Body(l)).collect();
        if with_ground {
            involved.push(Site::Body(0));
        }
        involved.extend(joints.iter().map(|&j| Site::Joint(j)));
        if over_driven {
            involved.push(Site::Inputs);
        }
        out.push(Finding {
            site: Site::Body(moving[0]),
            message,
            involved,
        });
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::spatial::dsl::parse;

    fn rssr() -> String {
        std::fs::read_to_string(concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/../examples/mech/rssr.mech"
        ))
        .unwrap()
    }

    /// The links of a finding (its site first), sorted.
    fn links(f: &Finding) -> Vec<usize> {
        let mut out: Vec<usize> = std::iter::once(&f.site)
            .chain(&f.involved)
            .filter_map(|s| match s {
                Site::Body(b) => Some(*b),
                _ => None,
            })
            .collect();
        out.sort();
        out
    }

    /// The joints a finding involves, sorted.
    fn joints(f: &Finding) -> Vec<usize> {
        let mut out: Vec<usize> = f
            .involved
            .iter()
            .filter_map(|s| match s {
                Site::Joint(j) => Some(*j),
                _ => None,
            })
            .collect();
        out.sort();
        out
    }

    #[test]
    fn the_rssr_passes() {
        let m = parse(&rssr()).unwrap();
        assert_eq!(idle_freedoms(&m).len(), 1, "the rod's spin fix is a bar");
        assert!(check(&m).is_empty(), "{:#?}", check(&m));
    }

    #[test]
    fn the_double_wishbone_passes() {
        let text = std::fs::read_to_string(concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/../examples/mech/double_wishbone.mech"
        ))
        .unwrap();
        let m = parse(&text).unwrap();
        assert!(check(&m).is_empty(), "{:#?}", check(&m));
    }

    #[test]
    fn a_planar_four_bar_in_space_r_s_u_r_passes() {
        let m = parse(
            r#"pub struct Rsur {
                space,
                ground { O2: (0.0, 0.0, 0.0), O4: (0.3, 0.0, 0.0) },
                link crank { points { O2, A: (0.02, 0.06, 0.0) } },
                link coupler { points { A, B: (0.25, 0.16, 0.0) } },
                link rocker { points { B, O4 } },
                joints {
                    O2: revolute(ground, crank) axis (0.0, 0.0, 1.0),
                    A: spherical(crank, coupler),
                    B: universal(coupler, rocker) axes (0.0, 0.0, 1.0) (1.0, 0.0, 0.0),
                    O4: revolute(rocker, ground) axis (0.0, 0.0, 1.0),
                },
                input: O2,
            }"#,
        )
        .unwrap();
        assert!(check(&m).is_empty(), "{:#?}", check(&m));
    }

    #[test]
    fn four_revolutes_in_a_loop_are_named_with_their_four_links() {
        let m = parse(
            r#"pub struct FourR {
                space,
                ground { O2: (0.0, 0.0, 0.0), O4: (0.3, 0.0, 0.0) },
                link crank { points { O2, A: (0.02, 0.06, 0.0) } },
                link coupler { points { A, B: (0.25, 0.16, 0.0) } },
                link rocker { points { B, O4 } },
                joints {
                    O2: revolute(ground, crank) axis (0.0, 0.0, 1.0),
                    A: revolute(crank, coupler) axis (0.0, 0.0, 1.0),
                    B: revolute(coupler, rocker) axis (0.0, 0.0, 1.0),
                    O4: revolute(rocker, ground) axis (0.0, 0.0, 1.0),
                },
                input: O2,
            }"#,
        )
        .unwrap();
        assert_eq!(crate::spatial::kutzbach::count(&m).mobility, -2);
        let found = check(&m);
        assert_eq!(found.len(), 1, "{found:#?}");
        let f = &found[0];
        assert_eq!(f.site, Site::Body(1), "at the first moving link");
        assert_eq!(links(f), vec![0, 1, 2, 3]);
        assert_eq!(joints(f), vec![0, 1, 2, 3]);
        let msg = &f.message;
        assert!(
            msg.starts_with(
                "links `crank`, `coupler`, `rocker` (with the ground) form an over-constrained sub-chain: their 4 joints (`O2`, `A`, `B`, `O4`) impose 20 equations and 1 input (`O2`) 1 more, 21 in all, but a rigid set of 4 links (the ground among them) can lose only 6·4 − 6 = 18 (3 redundant equations)"
            ),
            "{msg}"
        );
        assert!(
            msg.contains("a revolute (5 equations) by a universal (4)"),
            "{msg}"
        );
        assert!(msg.contains("#[allow(redundant)]"), "{msg}");
        // accepted on request
        let mut m = m;
        m.allow_redundant = true;
        assert!(check(&m).is_empty());
    }

    /// The RSSR of rssr.mech beside a rigid truss (t1 and t2 pinned to the ground by
    /// revolutes and to each other by a ball joint: 13 equations on 2 links, one too many)
    /// and a pendulum on a revolute that no input drives: G = 2 − 1 + 1 = 2, of which one
    /// is the rod's idle spin, so Kutzbach's count matches the one input.
    fn with_truss() -> SpatialModel {
        let text = rssr()
            .replace(
                "ground { O: (0.0, 0.0, 0.0),",
                "ground { O: (0.0, 0.0, 0.0), G1: (1.0, 0.0, 0.0), G2: (1.5, 0.0, 0.0), D: (-1.0, 0.0, 0.0),",
            )
            .replace(
                "    joints {\n",
                "    link t1 { points { G1, S: (1.2, 0.3, 0.1) } },
    link t2 { points { G2, S } },
    link pendulum { points { D, E: (-1.0, 0.0, -0.5) } },
    joints {
        G1: revolute(ground, t1) axis (0.0, 1.0, 0.0),
        G2: revolute(ground, t2) axis (0.0, 0.0, 1.0),
        S: spherical(t1, t2),
        D: revolute(ground, pendulum) axis (1.0, 0.0, 0.0),
",
            );
        parse(&text).unwrap()
    }

    #[test]
    fn a_rigid_truss_beside_a_free_pendulum_is_named_by_exactly_its_links() {
        let m = with_truss();
        assert_eq!(
            crate::spatial::kutzbach::check(&m),
            None,
            "the overall count looks right"
        );
        let found = check(&m);
        assert_eq!(found.len(), 1, "{found:#?}");
        let f = &found[0];
        let b = |n: &str| m.body_index(n).unwrap();
        let j = |n: &str| m.joint_index(n).unwrap();
        assert_eq!(f.site, Site::Body(b("t1")));
        assert_eq!(links(f), vec![0, b("t1"), b("t2")]);
        let mut expected = vec![j("G1"), j("G2"), j("S")];
        expected.sort();
        assert_eq!(joints(f), expected);
        assert!(!f.involved.contains(&Site::Inputs));
        assert!(
            f.message.starts_with(
                "links `t1`, `t2` (with the ground) form an over-constrained sub-chain: their 3 joints (`G1`, `G2`, `S`) impose 13 equations but a rigid set of 3 links (the ground among them) can lose only 6·3 − 6 = 12 (1 redundant equation)"
            ),
            "{}",
            f.message
        );
    }

    #[test]
    fn an_over_driven_part_is_named_with_its_inputs() {
        // The RSSR driven at both revolutes, a pendulum on a revolute elsewhere: G = 2 − 1
        // + 1 = 2 matches the two inputs, but the RSSR has one freedom for two drivers.
        let text = rssr()
            .replace(
                "ground { O: (0.0, 0.0, 0.0),",
                "ground { O: (0.0, 0.0, 0.0), D: (-1.0, 0.0, 0.0),",
            )
            .replace(
                "    joints {\n",
                "    link pendulum { points { D, E: (-1.0, 0.0, -0.5) } },
    joints {
        D: revolute(ground, pendulum) axis (1.0, 0.0, 0.0),
",
            )
            .replace("input: O,", "inputs: [O, C],");
        let m = parse(&text).unwrap();
        assert_eq!(crate::spatial::kutzbach::check(&m), None);
        let found = check(&m);
        assert_eq!(found.len(), 1, "{found:#?}");
        let f = &found[0];
        assert!(f.involved.contains(&Site::Inputs));
        assert!(
            f.message.starts_with(
                "links `crank`, `rod`, `rocker` (with the ground) are over-driven: their 4 joints (`O`, `A`, `B`, `C`) and the spin fix of link `rod` impose 17 of the 6·4 − 6 = 18 equations a rigid set of 4 links (the ground among them) can take, leaving them 1 freedom, but 2 inputs (`O`, `C`) drive them (1 redundant equation)"
            ),
            "{}",
            f.message
        );
    }
}
