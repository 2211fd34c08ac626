//! Counting formulas (`docs/theory.md` §1; check 2 of `docs/conventions.md#checks`).
//!
//! Plane (Grübler): a free link has 3 DOF, a lower pair (revolute, prismatic; class I in
//! the plane) removes 2, a higher pair (pin in slot; class II) removes 1, and the ground
//! is fixed:
//!
//! G = 3(N − 1) − 2·P_I − P_II,
//!
//! N the number of links with the ground. The kinetostatic problem has 3(N − 1)
//! equations (3 per moving link) and G + 2·P_I + P_II unknowns (G driver actions, and the
//! reaction components: 2 per lower pair, 1 per higher pair): it is determinate exactly
//! when G equals the number of declared inputs.
//!
//! Space (Kutzbach): see [`spatial_mobility`].

use crate::front::resolve::{Culprit, Issue};
use crate::model::Model;

/// The counts of `docs/theory.md` §1.2–§1.3 for one plane mechanism (all dimensionless).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Count {
    /// N: links, ground included.
    pub n: usize,
    /// P_I: lower pairs (revolute and prismatic joints), each removes 2 DOF.
    pub lower_pairs: usize,
    /// P_II: higher pairs (pins in slots), each removes 1 DOF.
    pub higher_pairs: usize,
    /// Grübler's mobility G = 3(N − 1) − 2·P_I − P_II (may be ≤ 0 for a structure).
    pub grubler: i64,
    /// Equations of the kinetostatic problem: 3(N − 1), three per moving link.
    pub equations: usize,
    /// Unknowns of the kinetostatic problem: DOF + 2·P_I + P_II (driver actions plus
    /// reaction components), with DOF = the number of declared inputs (which equals G
    /// when [`check`] passes; with `#[allow(redundant)]` the inputs are the true DOF and
    /// the reactions are indeterminate, so `unknowns` > `equations`).
    pub unknowns: usize,
    /// The number of declared inputs (drivers).
    pub inputs: usize,
}

/// Count the links, pairs and inputs of `model` and evaluate Grübler's formula
/// G = 3(N − 1) − 2·P_I − P_II, the equations 3(N − 1) and the unknowns
/// inputs + 2·P_I + P_II (see [`Count`]).
pub fn count(model: &Model) -> Count {
    let n = model.n_links();
    let p1 = model.lower_pairs();
    let p2 = model.higher_pairs();
    let inputs = model.inputs.len();
    let equations = 3 * n.saturating_sub(1);
    Count {
        n,
        lower_pairs: p1,
        higher_pairs: p2,
        grubler: equations as i64 - 2 * p1 as i64 - p2 as i64,
        equations,
        unknowns: inputs + 2 * p1 + p2,
        inputs,
    }
}

fn plural(n: i64, one: &str, many: &str) -> String {
    format!("{n} {}", if n == 1 { one } else { many })
}

/// Check 2 of `docs/conventions.md#checks`: Grübler's G = 3(N − 1) − 2·P_I − P_II must
/// equal the number of declared inputs, so that the 3(N − 1) equations match the
/// G + 2·P_I + P_II unknowns.
///
/// Skipped (returns `None`) when the model has `#[allow(redundant)]` and G < inputs:
/// redundant constraints make G undercount the mobility, and the geometric check
/// ([`crate::checks::validate::geometric`]) decides. The issue blames the inputs declaration first,
/// then every link (ground included) and every joint.
pub fn check(model: &Model) -> Option<Issue> {
    let c = count(model);
    let g = c.grubler;
    let inputs = c.inputs as i64;
    if g == inputs || (model.allow_redundant && g < inputs) {
        return None;
    }
    let nm1 = c.n as i64 - 1;
    let reactions = 2 * c.lower_pairs as i64 + c.higher_pairs as i64;
    let what = if g < 0 {
        " (negative: the chain is an over-constrained structure)"
    } else if g == 0 {
        " (zero: the chain is a structure and cannot move)"
    } else {
        ""
    };
    let fix = if g > 0 && inputs == 0 {
        format!(
            "declare {} (`input: J` or `inputs: [J1, J2, ...]`)",
            plural(g, "input", "inputs")
        )
    } else if g > 0 {
        format!(
            "declare {} (`input: J` or `inputs: [J1, J2, ...]`), or add/remove links or joints so that G = {}",
            plural(g, "input", "inputs"),
            inputs
        )
    } else {
        format!(
            "a mechanism needs G ≥ 1: remove joints or add links so that G = {inputs} (2 DOF per lower pair removed, 1 per higher pair); if the drawing really moves (e.g. parallel cranks), its constraints are redundant: add #[allow(redundant)]"
        )
    };
    let message = format!(
        "Grübler's count does not match the inputs: N = {} links (ground included), P_I = {} lower pairs, P_II = {} higher pairs give G = 3(N−1) − 2·P_I − P_II = 3·{} − 2·{} − {} = {}{}; the 3(N−1) = {} equations face G + 2·P_I + P_II = {} + {} = {} unknowns (G driver actions and {} reaction components), but {} declared: {}",
        c.n,
        c.lower_pairs,
        c.higher_pairs,
        nm1,
        c.lower_pairs,
        c.higher_pairs,
        g,
        what,
        c.equations,
        g,
        reactions,
        g + reactions,
        reactions,
        if inputs == 1 { "1 input was".to_string() } else { format!("{inputs} inputs were") },
        fix
    );
    let mut culprits = vec![Culprit::Inputs];
    culprits.extend((0..c.n).map(Culprit::Link));
    culprits.extend((0..model.joints.len()).map(Culprit::Joint));
    Some(Issue { culprits, message })
}

/// Mobility of a spatial mechanism by the Kutzbach (Chebyshev–Grübler–Kutzbach) formula of
/// `docs/theory.md` §1.5 (dimensionless):
///
/// G = 6(N − 1) − (5·P_I + 4·P_II + 3·P_III + 2·P_IV + P_V),
///
/// `n_links` = N, ground included; `pairs_by_class[k − 1]` = P_k, the number of pairs of
/// class k, where a class-k pair removes 6 − k DOF (so has 6 − k reaction components) and
/// leaves k (class I: revolute, prismatic, screw; II: cylindrical; III: spherical, planar;
/// IV, V: higher pairs). 6(N − 1) is the number of equations, the sum the number of
/// reaction components.
pub fn spatial_mobility(n_links: usize, pairs_by_class: [usize; 5]) -> i64 {
    let reactions: i64 = pairs_by_class
        .iter()
        .enumerate()
        .map(|(k, &p)| (5 - k as i64) * p as i64)
        .sum();
    6 * (n_links as i64 - 1) - reactions
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
            },
            INPUTS
        }
    "#;

    #[test]
    fn four_bar_counts() {
        let m = model(&FOUR_BAR.replace("INPUTS", "input: O2,"));
        let c = count(&m);
        assert_eq!(
            c,
            Count {
                n: 4,
                lower_pairs: 4,
                higher_pairs: 0,
                grubler: 1,
                equations: 9,
                unknowns: 9,
                inputs: 1
            }
        );
        assert_eq!(check(&m), None);
    }

    #[test]
    fn slot_counts_as_higher_pair() {
        // Scotch-yoke like: crank, pin in the slot of a yoke guided by the ground.
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
        let c = count(&m);
        assert_eq!(
            (
                c.n,
                c.lower_pairs,
                c.higher_pairs,
                c.grubler,
                c.equations,
                c.unknowns
            ),
            (3, 2, 1, 1, 6, 6)
        );
        assert_eq!(check(&m), None);
    }

    #[test]
    fn mismatch_states_the_numbers() {
        let m = model(&FOUR_BAR.replace("INPUTS", "inputs: [O2, O4],"));
        let issue = check(&m).expect("two inputs on a one-DOF four-bar");
        let msg = &issue.message;
        for needle in [
            "N = 4 links",
            "P_I = 4 lower pairs",
            "P_II = 0 higher pairs",
            "= 3·3 − 2·4 − 0 = 1",
            "3(N−1) = 9 equations",
            "G + 2·P_I + P_II = 1 + 8 = 9 unknowns",
            "2 inputs were declared",
            "declare 1 input",
        ] {
            assert!(msg.contains(needle), "missing {needle:?} in {msg}");
        }
        assert_eq!(issue.culprits[0], Culprit::Inputs);
        assert!(issue.culprits.contains(&Culprit::Link(0)));
        assert!(issue.culprits.contains(&Culprit::Link(3)));
        assert!(issue.culprits.contains(&Culprit::Joint(3)));
        assert_eq!(issue.culprits.len(), 1 + 4 + 4);
        // No input at all: the fix is to declare one.
        let m = model(&FOUR_BAR.replace("INPUTS", ""));
        let msg = check(&m).expect("no input").message;
        assert!(
            msg.contains("but 0 inputs were declared: declare 1 input (`input: J`"),
            "{msg}"
        );
        assert!(!msg.contains("so that G = 0"), "{msg}");
    }

    #[test]
    fn structure_and_allow_redundant() {
        // A triangle with the ground: G = 3·2 − 2·3 = 0, but one input declared.
        let text = r#"pub struct Tri {
                ground { O: (0.0, 0.0), P: (1.0, 0.0) },
                link a { points { O, C: (0.5, 1.0) } },
                link b { points { C, P } },
                joints { O: revolute(ground, a), C: revolute(a, b), P: revolute(b, ground) },
                input: O,
            }"#;
        let issue = check(&model(text)).expect("a structure with an input");
        assert!(
            issue
                .message
                .contains("= 0 (zero: the chain is a structure"),
            "{}",
            issue.message
        );
        // With #[allow(redundant)], G < inputs is left to the geometric check.
        let m = model(&format!("#[allow(redundant)] {text}"));
        assert!(m.allow_redundant);
        assert_eq!(check(&m), None);
        assert_eq!(count(&m).unknowns, 1 + 6);
    }

    #[test]
    fn kutzbach() {
        // RSSR spatial four-bar: 2 revolutes (class I), 2 spherical (class III):
        // 6·3 − (2·5 + 2·3) = 2 (the useful DOF plus the coupler's idle spin).
        assert_eq!(spatial_mobility(4, [2, 0, 2, 0, 0]), 2);
        // A plane four-bar counted in space is over-constrained: 18 − 4·5 = −2.
        assert_eq!(spatial_mobility(4, [4, 0, 0, 0, 0]), -2);
        // One link on a cylindrical pair (class II) keeps 2 DOF.
        assert_eq!(spatial_mobility(2, [0, 1, 0, 0, 0]), 2);
        // Class V: a point contact leaves 5 DOF.
        assert_eq!(spatial_mobility(2, [0, 0, 0, 0, 1]), 5);
        assert_eq!(spatial_mobility(1, [0; 5]), 0);
    }
}
