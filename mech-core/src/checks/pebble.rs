//! Structural redundancy (`docs/conventions.md#checks`, check 3; `docs/theory.md` §1.4)
//! by the (3,3) pebble game on the body-bar graph of the mechanism.
//!
//! Every link, the ground included, is a rigid body with 3 DOF in the plane (3 pebbles).
//! Every scalar constraint is a bar between two bodies: a revolute or a prismatic joint is
//! 2 bars, a pin in a slot 1 bar, and each input adds 1 bar between its joint's links.
//! By Tay's theorem a generic body-bar framework in the plane is independent exactly when
//! every set of k bodies spans at most 3k − 3 bars (a rigid set of k bodies keeps the 3
//! DOF of one body, so its bars can remove at most 3k − 3). The pebble game (Jacobs &
//! Hendrickson; Lee & Streinu) tests this in O(bars · bodies): a bar is independent when 4
//! pebbles can be gathered on its two ends; when they cannot, the bodies reachable from its
//! ends in the pebble-directed graph are the smallest rigid set containing both ends that
//! already has its 3k − 3 bars, so that set plus the bar is over-constrained.
//!
//! This count is topological (generic): it finds a rigid truss hidden in a mechanism whose
//! overall Grübler count looks right. Redundancy that depends on the dimensions (parallel
//! cranks) is found at the drawing by [`crate::checks::validate::geometric`].
//!
//! The game itself (`over_constrained`) takes the pebbles per body as a parameter: 3 in
//! the plane, 6 in space, where a rigid set of k bodies can take at most 6k − 6 bars (Tay's
//! theorem holds for body-bar frameworks in every dimension); the spatial check
//! (`crate::spatial::pebble`) plays it with 6.

use crate::front::resolve::{Culprit, Issue};
use crate::model::Model;

/// Pebbles of a body in the plane (its DOF), also its trivial motions: a rigid set of k
/// bodies in the plane can take at most 3k − 3 independent bars.
const K: usize = 3;

/// Where a bar comes from.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Source {
    /// A scalar constraint of joint `j`.
    Joint(usize),
    /// The driver of input `k` (at joint `model.inputs[k]`).
    Input(usize),
}

/// The directed pebble graph of the (k, k) game: free pebbles per body and the bars, each
/// oriented away from the body whose pebble covers it.
struct Game {
    /// k: the pebbles of a body (its DOF) and the trivial motions of a rigid set (a set of
    /// n bodies takes at most k·n − k bars).
    k: usize,
    pebbles: Vec<usize>,
    /// Outgoing accepted bars of each body: (bar index, head).
    out: Vec<Vec<(usize, usize)>>,
}

impl Game {
    /// `bodies` bodies with `k` pebbles each and no bar.
    fn new(bodies: usize, k: usize) -> Self {
        Game {
            k,
            pebbles: vec![k; bodies],
            out: vec![Vec::new(); bodies],
        }
    }

    /// Move one free pebble to `root` along a directed path, not taking any from (nor
    /// passing through) `hold`. Returns false when no pebble can be reached.
    fn fetch(&mut self, root: usize, hold: usize) -> bool {
        let n = self.pebbles.len();
        let mut seen = vec![false; n];
        // parent[v] = (u, position of the bar u→v in out[u]).
        let mut parent: Vec<Option<(usize, usize)>> = vec![None; n];
        seen[root] = true;
        seen[hold] = true;
        let mut stack = vec![root];
        while let Some(u) = stack.pop() {
            for (pos, &(_, v)) in self.out[u].iter().enumerate() {
                if seen[v] {
                    continue;
                }
                seen[v] = true;
                parent[v] = Some((u, pos));
                if self.pebbles[v] > 0 {
                    // Reverse the path root → … → v: the pebble of v comes to root.
                    self.pebbles[v] -= 1;
                    self.pebbles[root] += 1;
                    let mut w = v;
                    while let Some((u, pos)) = parent[w] {
                        let (bar, head) = self.out[u].swap_remove(pos);
                        debug_assert_eq!(head, w);
                        // Each body is once on the path, so `swap_remove` disturbs no
                        // position still to be used; w's own path bar is already reversed.
                        self.out[w].push((bar, u));
                        w = u;
                    }
                    return true;
                }
                stack.push(v);
            }
        }
        false
    }

    /// Gather as many pebbles as possible (up to k + 1) on the two ends of a bar.
    fn gather(&mut self, u: usize, v: usize) -> usize {
        while self.pebbles[u] + self.pebbles[v] < self.k + 1 {
            if !(self.fetch(u, v) || self.fetch(v, u)) {
                break;
            }
        }
        self.pebbles[u] + self.pebbles[v]
    }

    /// Try to insert bar `bar` between `u` and `v`; true when it is independent.
    fn insert(&mut self, bar: usize, u: usize, v: usize) -> bool {
        if self.gather(u, v) < self.k + 1 {
            return false;
        }
        let tail = if self.pebbles[u] > 0 { u } else { v };
        let head = if tail == u { v } else { u };
        self.pebbles[tail] -= 1;
        self.out[tail].push((bar, head));
        true
    }

    /// The bodies reachable from `u` or `v` along the directed bars.
    fn reach(&self, u: usize, v: usize) -> Vec<bool> {
        let mut seen = vec![false; self.pebbles.len()];
        let mut stack = vec![u, v];
        seen[u] = true;
        seen[v] = true;
        while let Some(x) = stack.pop() {
            for &(_, y) in &self.out[x] {
                if !seen[y] {
                    seen[y] = true;
                    stack.push(y);
                }
            }
        }
        seen
    }
}

/// The bars of the body-bar graph: (body a, body b, source), joints first (in joint order),
/// then the inputs.
fn bars(model: &Model) -> Vec<(usize, usize, Source)> {
    let mut out = Vec::new();
    for (j, jt) in model.joints.iter().enumerate() {
        for _ in 0..jt.kind.removed() {
            out.push((jt.a, jt.b, Source::Joint(j)));
        }
    }
    for (k, &j) in model.inputs.iter().enumerate() {
        let jt = &model.joints[j];
        out.push((jt.a, jt.b, Source::Input(k)));
    }
    out
}

/// An over-constrained set of bodies found by the game.
#[derive(Clone, Debug, PartialEq, Eq)]
pub(crate) struct Block {
    /// Membership, by body index.
    pub(crate) links: Vec<bool>,
    /// Bars among the bodies minus the k·n − k a rigid set of n bodies can take.
    pub(crate) excess: usize,
    /// The bars with both ends in the set (indices into the bars given), in order.
    pub(crate) bars: Vec<usize>,
}

/// The over-constrained sets of the body-bar graph of `bodies` bodies with k pebbles each
/// (`k` = 3 in the plane, 6 in space) and the given bars (a, b), by the (k, k) pebble game:
/// the bars are inserted in order; each one rejected (its ends cannot gather k + 1
/// pebbles) gives the smallest rigid set containing its ends in the final graph (the
/// bodies reachable from them), which with its bars exceeds k·n − k. Returns those sets,
/// deduplicated, smallest first, each kept only when its excess is more than that of the
/// smaller sets inside it. Bars with an end out of range or both ends on one body are
/// skipped (a naming mistake reported elsewhere).
pub(crate) fn over_constrained(bodies: usize, bars: &[(usize, usize)], k: usize) -> Vec<Block> {
    let n = bodies;
    if n < 2 {
        return Vec::new();
    }
    let mut game = Game::new(n, k);
    let mut rejected = Vec::new();
    for (i, &(a, b)) in bars.iter().enumerate() {
        if a == b || a >= n || b >= n {
            continue; // reported by name resolution
        }
        if !game.insert(i, a, b) {
            rejected.push(i);
        }
    }
    // Each rejected bar's block in the final graph: the smallest rigid set containing its
    // ends (rigid sets only grow as bars are accepted).
    let mut cands: Vec<Block> = Vec::new();
    for &i in &rejected {
        let (a, b) = bars[i];
        game.gather(a, b);
        let links = game.reach(a, b);
        if cands.iter().any(|c| c.links == links) {
            continue;
        }
        let size = links.iter().filter(|&&x| x).count();
        let among: Vec<usize> = (0..bars.len())
            .filter(|&i| {
                let (x, y) = bars[i];
                x < n && y < n && links[x] && links[y]
            })
            .collect();
        cands.push(Block {
            excess: among.len().saturating_sub(k * size - k),
            links,
            bars: among,
        });
    }
    cands.sort_by_key(|c| c.links.iter().filter(|&&x| x).count());
    // Keep a block unless its excess is only that of smaller blocks inside it.
    let mut kept: Vec<Block> = Vec::new();
    for c in cands {
        let inner: usize = kept
            .iter()
            .filter(|k| k.links.iter().zip(&c.links).all(|(&x, &y)| !x || y))
            .map(|k| k.excess)
            .sum();
        if c.excess > inner {
            kept.push(c);
        }
    }
    kept
}

/// The over-constrained blocks of a planar model: [`over_constrained`] with 3 pebbles on
/// the bars of [`bars`].
fn blocks(model: &Model) -> Vec<Block> {
    let pairs: Vec<(usize, usize)> = bars(model).iter().map(|&(a, b, _)| (a, b)).collect();
    over_constrained(model.n_links(), &pairs, K)
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

/// Check 3 of `docs/conventions.md#checks`: structural redundancy.
///
/// Runs the (3,3) pebble game on the body-bar graph (bodies = links with the ground, 3 DOF
/// each; bars = 2 per revolute or prismatic joint, 1 per pin in slot, 1 per input) and
/// returns one [`Issue`] per over-constrained sub-chain: a set of k links whose joints and
/// inputs remove more than the 3(k − 1) DOF the set has (3 per moving link when the ground
/// is in the set; 3k − 3 relative DOF of k links moving as one body otherwise). The issue
/// names the links and blames their declarations, then the joints among them (and the
/// inputs when they take part). Returns nothing when the model has `#[allow(redundant)]`.
pub fn check(model: &Model) -> Vec<Issue> {
    if model.allow_redundant {
        return Vec::new();
    }
    let mut out = Vec::new();
    for b in blocks(model) {
        let links: Vec<usize> = (0..model.n_links()).filter(|&l| b.links[l]).collect();
        let k = links.len();
        let with_ground = b.links[0];
        let moving: Vec<usize> = links.iter().copied().filter(|&l| l != 0).collect();
        let joints: Vec<usize> = (0..model.joints.len())
            .filter(|&j| b.links[model.joints[j].a] && b.links[model.joints[j].b])
            .collect();
        let inputs: Vec<usize> = model
            .inputs
            .iter()
            .copied()
            .filter(|j| joints.contains(j))
            .collect();
        let by_joints: usize = joints.iter().map(|&j| model.joints[j].kind.removed()).sum();
        let capacity = 3 * k - 3;
        let link_list = format!(
            "{} {}{}",
            if moving.len() == 1 { "link" } else { "links" },
            names(moving.iter().map(|&l| model.links[l].name.clone())),
            if with_ground {
                " (with the ground)"
            } else {
                ""
            }
        );
        let has = if with_ground {
            format!(
                "the {} only {}",
                plural(moving.len(), "moving link has", "moving links have"),
                capacity
            )
        } else {
            format!(
                "{k} links moving as one rigid body have only 3·{k} − 3 = {capacity} relative DOF"
            )
        };
        let joint_list = names(joints.iter().map(|&j| model.joints[j].name.clone()));
        let redundant = plural(b.excess, "redundant constraint", "redundant constraints");
        let message = if by_joints > capacity || inputs.is_empty() {
            let removed = by_joints + inputs.len();
            let inp = if inputs.is_empty() {
                String::new()
            } else {
                format!(
                    " and {} ({})",
                    plural(inputs.len(), "input", "inputs"),
                    names(inputs.iter().map(|&j| model.joints[j].name.clone()))
                )
            };
            format!(
                "{link_list} form an over-constrained sub-chain: their {} ({joint_list}){inp} remove {removed} DOF but {has} ({redundant}), so the chain is rigid and its reactions are indeterminate: remove a joint or a link, or add #[allow(redundant)] if intended",
                plural(joints.len(), "joint", "joints"),
            )
        } else {
            let free = capacity - by_joints;
            format!(
                "{link_list} are over-driven: their {} ({joint_list}) leave them {} but {} ({}) drive them: move an input to a part of the mechanism that is not yet driven, or remove it",
                plural(joints.len(), "joint", "joints"),
                plural(free, "DOF", "DOF"),
                plural(inputs.len(), "input", "inputs"),
                names(inputs.iter().map(|&j| model.joints[j].name.clone())),
            )
        };
        // Culprit first: the inputs when over-driven, else the first moving link of the set.
        let mut culprits: Vec<Culprit> = Vec::new();
        if !inputs.is_empty() && by_joints <= capacity {
            culprits.push(Culprit::Inputs);
        }
        culprits.extend(links.iter().filter(|&&l| l != 0).map(|&l| Culprit::Link(l)));
        culprits.extend(links.iter().filter(|&&l| l == 0).map(|&l| Culprit::Link(l)));
        culprits.extend(joints.iter().map(|&j| Culprit::Joint(j)));
        if !inputs.is_empty() && by_joints > capacity {
            culprits.push(Culprit::Inputs);
        }
        out.push(Issue { culprits, message });
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    use crate::front::resolve::model_of as model;

    const FOUR_BAR: &str = r#"
        pub struct FourBar {
            ground { O2: (0.0, 0.0), O4: (3.0, 0.0) },
            link crank { points { O2, A: (0.0, 1.0) } },
            link coupler { points { A, B: (2.5, 2.0) } },
            link rocker { points { B, O4 } },
            joints {
                O2: revolute(ground, crank),
                A: revolute(crank, coupler),
                B: revolute(coupler, rocker),
                O4: revolute(rocker, ground),
                EXTRA
            },
            INPUTS
        }
    "#;

    fn four_bar(extra: &str, inputs: &str) -> Model {
        model(&FOUR_BAR.replace("EXTRA", extra).replace("INPUTS", inputs))
    }

    fn named_links(issue: &Issue) -> Vec<usize> {
        issue
            .culprits
            .iter()
            .filter_map(|c| {
                if let Culprit::Link(l) = c {
                    Some(*l)
                } else {
                    None
                }
            })
            .collect()
    }

    #[test]
    fn four_bar_passes() {
        assert!(check(&four_bar("", "input: O2,")).is_empty());
    }

    #[test]
    fn slider_crank_and_slot_pass() {
        let m = model(
            r#"pub struct Yoke {
                ground { O: (0.0, 0.0) },
                link crank { points { O, A: (0.1, 0.0) } },
                link yoke { points { C: (0.3, 0.0) } },
                joints {
                    O: revolute(ground, crank),
                    slot: pin_in_slot(yoke, crank) at A along (0.0, 1.0),
                    guide: prismatic(ground, yoke) at C along (1.0, 0.0),
                },
                input: O,
            }"#,
        );
        assert!(check(&m).is_empty());
    }

    /// A four-bar, a truss (t1, t2, t3 pinned in a triangle at P, Q, R, and t1 and t2
    /// pinned to the ground: 5 joints on 3 moving links, one too many) and a link dangling from the
    /// ground: G = 3·7 − 2·10 = 1, Grübler is satisfied by the one input.
    const TRUSS: &str = r#"
        pub struct Hidden {
            ground { O2: (0.0, 0.0), O4: (3.0, 0.0), G1: (5.0, 0.0), G2: (7.0, 0.0), D: (-2.0, 0.0) },
            link crank { points { O2, A: (0.0, 1.0) } },
            link coupler { points { A, B: (2.5, 2.0) } },
            link rocker { points { B, O4 } },
            link t1 { points { G1, P: (5.5, 1.0), R: (6.0, 0.5) } },
            link t2 { points { G2, Q: (6.5, 1.0), R } },
            link t3 { points { P, Q } },
            link dangle { points { D, E: (-2.0, 1.0) } },
            joints {
                O2: revolute(ground, crank),
                A: revolute(crank, coupler),
                B: revolute(coupler, rocker),
                O4: revolute(rocker, ground),
                G1: revolute(ground, t1),
                G2: revolute(ground, t2),
                P: revolute(t1, t3),
                Q: revolute(t3, t2),
                T12: revolute(t1, t2) at R,
                D: revolute(ground, dangle),
            },
            input: O2,
        }
    "#;

    #[test]
    fn hidden_truss_is_named() {
        let m = model(TRUSS);
        assert_eq!(
            crate::checks::grubler::check(&m),
            None,
            "the overall count looks right"
        );
        let issues = check(&m);
        assert_eq!(issues.len(), 1, "{issues:#?}");
        let issue = &issues[0];
        let t = |n: &str| m.link_index(n).unwrap();
        let mut named = named_links(issue);
        named.sort();
        assert_eq!(named, vec![0, t("t1"), t("t2"), t("t3")]);
        assert_eq!(
            issue.culprits[0],
            Culprit::Link(t("t1")),
            "the truss, not the ground, is the culprit"
        );
        let msg = &issue.message;
        assert!(
            msg.starts_with(
                "links `t1`, `t2`, `t3` (with the ground) form an over-constrained sub-chain"
            ),
            "{msg}"
        );
        assert!(
            msg.contains("their 5 joints (`G1`, `G2`, `P`, `Q`, `T12`) remove 10 DOF"),
            "{msg}"
        );
        assert!(
            msg.contains("the 3 moving links have only 9 (1 redundant constraint)"),
            "{msg}"
        );
        for j in ["G1", "G2", "P", "Q", "T12"] {
            assert!(
                issue
                    .culprits
                    .contains(&Culprit::Joint(m.joint_index(j).unwrap())),
                "{j}"
            );
        }
        assert!(!issue
            .culprits
            .contains(&Culprit::Joint(m.joint_index("O2").unwrap())));
        assert!(!issue.culprits.contains(&Culprit::Inputs));
        // Accepted on request.
        let mut m2 = m.clone();
        m2.allow_redundant = true;
        assert!(check(&m2).is_empty());
    }

    #[test]
    fn doubled_joint_is_caught() {
        let m = four_bar("A2: revolute(crank, coupler) at A,", "input: O2,");
        let issues = check(&m);
        let pair = vec![
            m.link_index("crank").unwrap(),
            m.link_index("coupler").unwrap(),
        ];
        let issue = issues
            .iter()
            .find(|i| named_links(i) == pair)
            .unwrap_or_else(|| panic!("{issues:#?}"));
        assert!(
            issue.message.starts_with(
                "links `crank`, `coupler` form an over-constrained sub-chain: their 2 joints (`A`, `A2`) remove 4 DOF but 2 links moving as one rigid body have only 3·2 − 3 = 3 relative DOF (1 redundant constraint)"
            ),
            "{}",
            issue.message
        );
    }

    #[test]
    fn over_driven_part_is_caught() {
        // Two inputs on the four-bar (crank and rocker) and a free link elsewhere: the
        // overall count G = 2 matches, but the four-bar is driven twice.
        let m = model(
            &FOUR_BAR
                .replace("EXTRA", "D: revolute(ground, dangle),")
                .replace("INPUTS", "inputs: [O2, O4],")
                .replace("O4: (3.0, 0.0) }", "O4: (3.0, 0.0), D: (-1.0, 0.0) }")
                .replace(
                    "link rocker",
                    "link dangle { points { D, E: (-1.0, 1.0) } }, link rocker",
                ),
        );
        assert_eq!(crate::checks::grubler::check(&m), None);
        let issues = check(&m);
        assert_eq!(issues.len(), 1, "{issues:#?}");
        let msg = &issues[0].message;
        assert!(
            msg.starts_with("links `crank`, `coupler`, `rocker` (with the ground) are over-driven: their 4 joints (`O2`, `A`, `B`, `O4`) leave them 1 DOF but 2 inputs (`O2`, `O4`) drive them"),
            "{msg}"
        );
        assert!(issues[0].culprits.contains(&Culprit::Inputs));
    }

    #[test]
    fn independent_sets_respect_6k_minus_6_in_space() {
        // The same exhaustive check with 6 pebbles: independent iff every subset of k
        // bodies spans at most 6k − 6 accepted bars (bars of a spatial body-bar graph).
        let n = 4;
        let pairs: Vec<(usize, usize)> = (0..n)
            .flat_map(|a| (a + 1..n).map(move |b| (a, b)))
            .collect();
        let mut seed = 987654321u64;
        let mut rejected = 0;
        for _ in 0..200 {
            let mut game = Game::new(n, 6);
            let mut accepted: Vec<(usize, usize)> = Vec::new();
            for i in 0..24 {
                seed = seed
                    .wrapping_mul(6364136223846793005)
                    .wrapping_add(1442695040888963407);
                let (a, b) = pairs[(seed >> 33) as usize % pairs.len()];
                let ok = game.insert(i, a, b);
                let mut trial = accepted.clone();
                trial.push((a, b));
                let sparse = (1u32..(1 << n)).all(|mask| {
                    let k = mask.count_ones() as usize;
                    let e = trial
                        .iter()
                        .filter(|&&(x, y)| mask & (1 << x) != 0 && mask & (1 << y) != 0)
                        .count();
                    e <= 6 * k - 6
                });
                assert_eq!(ok, sparse);
                if ok {
                    accepted = trial;
                } else {
                    rejected += 1;
                }
            }
        }
        assert!(rejected > 0, "the random graphs never reached the bound");
    }

    #[test]
    fn blocks_name_their_bodies_excess_and_bars() {
        // Space (6 pebbles): bodies 0 and 1 joined by 7 bars (one too many), body 2 hung
        // from 1 by 3 bars, body 3 from 0 by 5 and to 2 by 1.
        let mut bars = vec![(0, 1); 7];
        bars.extend([(1, 2); 3]);
        bars.extend([(0, 3); 5]);
        bars.push((2, 3));
        let found = over_constrained(4, &bars, 6);
        assert_eq!(found.len(), 1, "{found:#?}");
        assert_eq!(found[0].links, vec![true, true, false, false]);
        assert_eq!(found[0].excess, 1);
        assert_eq!(found[0].bars, (0..7).collect::<Vec<_>>());
        // The same bars in the plane (3 pebbles): the pair {0, 1} is 4 bars over, {0, 3}
        // (5 bars) 2 over, and {0, 1, 2, 3} (16 bars against 9) 7 in all, more than the
        // 4 + 2 of the pairs inside it.
        let found = over_constrained(4, &bars, 3);
        assert_eq!(found.len(), 3, "{found:#?}");
        assert_eq!(
            (found[0].links.clone(), found[0].excess),
            (vec![true, true, false, false], 4)
        );
        assert_eq!(
            (found[1].links.clone(), found[1].excess),
            (vec![true, false, false, true], 2)
        );
        assert_eq!(found[1].bars, (10..15).collect::<Vec<_>>());
        assert_eq!(found[2].links, vec![true; 4]);
        assert_eq!(found[2].excess, 7);
        assert_eq!(found[2].bars.len(), bars.len());
    }

    #[test]
    fn independent_sets_respect_3k_minus_3() {
        // Exhaustive check of the game's verdict against the definition on small graphs:
        // independent iff every subset of k bodies spans at most 3k − 3 accepted bars.
        let n = 4;
        let pairs: Vec<(usize, usize)> = (0..n)
            .flat_map(|a| (a + 1..n).map(move |b| (a, b)))
            .collect();
        let mut seed = 12345u64;
        for _ in 0..300 {
            let mut game = Game::new(n, K);
            let mut accepted: Vec<(usize, usize)> = Vec::new();
            for i in 0..12 {
                seed = seed
                    .wrapping_mul(6364136223846793005)
                    .wrapping_add(1442695040888963407);
                let (a, b) = pairs[(seed >> 33) as usize % pairs.len()];
                let ok = game.insert(i, a, b);
                let mut trial = accepted.clone();
                trial.push((a, b));
                let sparse = (1u32..(1 << n)).all(|mask| {
                    let k = mask.count_ones() as usize;
                    let e = trial
                        .iter()
                        .filter(|&&(x, y)| mask & (1 << x) != 0 && mask & (1 << y) != 0)
                        .count();
                    e <= 3 * k - 3
                });
                assert_eq!(ok, sparse);
                if ok {
                    accepted = trial;
                }
            }
        }
    }
}
