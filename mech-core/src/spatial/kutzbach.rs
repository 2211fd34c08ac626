//! Kutzbach's count of a spatial mechanism and its idle freedoms.
//!
//! G = 6(N − 1) − (5 P_I + 4 P_II + 3 P_III + 2 P_IV + P_V)
//! ([`crate::checks::grubler::spatial_mobility`]), N the links with the ground, P_k the
//! pairs of class k. A binary link whose two joints are both spherical can spin about the
//! line through their centres without moving anything else: an idle freedom, counted by G
//! but not a freedom of the machine. The solver fixes it (the link keeps the drawing's
//! spin: see `constraints::spin`), so the mechanism's mobility is G − (idle freedoms), and
//! that must equal the number of inputs.

use super::model::{JointKind, SpatialModel};
use crate::checks::grubler::spatial_mobility;

/// The counts of Kutzbach's formula for one spatial mechanism (all dimensionless).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Kutzbach {
    /// N: links, ground included.
    pub n: usize,
    /// P_k, pairs of class k (k = 1..5), at index k − 1.
    pub pairs_by_class: [usize; 5],
    /// G = 6(N − 1) − Σ (6 − k) P_k.
    pub mobility: i64,
    /// The idle freedoms: (link, its two spherical joints), indices into the model's bodies
    /// and joints.
    pub idle: Vec<(usize, usize, usize)>,
    /// The declared inputs.
    pub inputs: usize,
}

impl Kutzbach {
    /// The equations of the kinetostatic problem, 6(N − 1).
    pub fn equations(&self) -> usize {
        6 * self.n.saturating_sub(1)
    }

    /// The reaction components Σ (6 − k) P_k, with one moment per idle freedom (the fix of
    /// its spin).
    pub fn reactions(&self) -> usize {
        let pairs: usize = (0..5).map(|k| (5 - k) * self.pairs_by_class[k]).sum();
        pairs + self.idle.len()
    }
}

/// The links whose only two joints are both spherical: (link, first joint, second joint).
pub fn idle_freedoms(model: &SpatialModel) -> Vec<(usize, usize, usize)> {
    (1..model.bodies.len())
        .filter_map(|b| {
            let js: Vec<usize> = (0..model.joints.len())
                .filter(|&j| model.joints[j].a == b || model.joints[j].b == b)
                .collect();
            let spherical = |j: usize| model.joints[j].kind == JointKind::Spherical;
            (js.len() == 2 && spherical(js[0]) && spherical(js[1])).then(|| (b, js[0], js[1]))
        })
        .collect()
}

/// Count the links and pairs of `model` ([`Kutzbach`]).
pub fn count(model: &SpatialModel) -> Kutzbach {
    let mut pairs_by_class = [0; 5];
    for j in &model.joints {
        pairs_by_class[j.kind.class() - 1] += 1;
    }
    Kutzbach {
        n: model.bodies.len(),
        pairs_by_class,
        mobility: spatial_mobility(model.bodies.len(), pairs_by_class),
        idle: idle_freedoms(model),
        inputs: model.inputs.len(),
    }
}

/// The message when G − (idle freedoms) differs from the declared inputs: the numbers of
/// the count and the fix; `None` when they agree.
pub fn check(model: &SpatialModel) -> Option<String> {
    let c = count(model);
    let idle = c.idle.len() as i64;
    let g = c.mobility - idle;
    let inputs = c.inputs as i64;
    if g == inputs {
        return None;
    }
    let p = c.pairs_by_class;
    let idle_text = if c.idle.is_empty() {
        String::new()
    } else {
        let names: Vec<String> = c
            .idle
            .iter()
            .map(|&(b, j1, j2)| {
                format!(
                    "link `{}` spins idly about the line through its spherical joints `{}` and `{}`",
                    model.bodies[b].name, model.joints[j1].name, model.joints[j2].name
                )
            })
            .collect();
        format!(
            ", of which {idle} idle ({}; the solver fixes each such spin), leaving {g}",
            names.join("; ")
        )
    };
    let fix = if g > 0 {
        format!("declare {g} input(s) (`input: J` or `inputs: [J1, J2, ...]`), or add or change joints so that G = {inputs}")
    } else {
        format!("the chain cannot move: remove constraints (e.g. a revolute → a universal or spherical joint, 5 → 4 or 3 equations) or add links so that G = {inputs}")
    };
    Some(format!(
        "Kutzbach's count does not match the inputs: N = {} links (ground included), P_I = {}, P_II = {}, P_III = {}, P_IV = {}, P_V = {} pairs give G = 6(N−1) − 5·P_I − 4·P_II − 3·P_III − 2·P_IV − P_V = 6·{} − 5·{} − 4·{} − 3·{} − 2·{} − {} = {}{idle_text}; the 6(N−1) = {} equations face G + {} reaction components, but {} input(s) were declared: {fix}",
        c.n, p[0], p[1], p[2], p[3], p[4], c.n.saturating_sub(1), p[0], p[1], p[2], p[3], p[4], c.mobility,
        c.equations(), c.reactions(), inputs
    ))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::spatial::dsl::parse;

    const RSSR: &str = r#"pub struct Rssr {
        space,
        ground { O: (0.0, 0.0, 0.0), C: (0.3, 0.1, 0.05) },
        link crank { points { O, A: (0.0, 0.08, 0.0) } },
        link rod { points { A, B: (0.3, 0.15, 0.1) } },
        link rocker { points { C, B } },
        joints {
            O: revolute(ground, crank) axis (1.0, 0.0, 0.0),
            A: spherical(crank, rod),
            B: spherical(rod, rocker),
            C: revolute(ground, rocker) axis (0.0, 0.0, 1.0),
        },
        input: O,
    }"#;

    #[test]
    fn the_rssr_counts_two_of_which_one_is_idle() {
        let m = parse(RSSR).unwrap();
        let c = count(&m);
        assert_eq!(c.pairs_by_class, [2, 0, 2, 0, 0]);
        assert_eq!(c.mobility, 6 * 3 - 5 * 2 - 3 * 2);
        assert_eq!(c.idle, vec![(2, 1, 2)]);
        assert_eq!((c.equations(), c.reactions()), (18, 17));
        assert_eq!(check(&m), None);
        // a universal joint at B (class II) holds the spin: G = 18 − 10 − 3 − 4 = 1, no idle
        let m = parse(&RSSR.replace(
            "B: spherical(rod, rocker)",
            "B: universal(rod, rocker) axes (0.0, 0.0, 1.0) (1.0, 0.0, 0.0)",
        ))
        .unwrap();
        let c = count(&m);
        assert_eq!((c.mobility, c.idle.len()), (1, 0));
        assert_eq!(check(&m), None);
        // without the input: the numbers and the fix
        let m = parse(&RSSR.replace("input: O,", "")).unwrap();
        let msg = check(&m).unwrap();
        assert!(msg.contains("= 2, of which 1 idle (link `rod` spins idly about the line through its spherical joints `A` and `B`") && msg.contains("declare 1 input(s)"), "{msg}");
    }
}
