//! The checks of `docs/conventions.md#checks` on a resolved [`Model`] (name resolution, check 1, is
//! [`crate::front::resolve`]): the drawing's consistency (check 5, [`drawing`]), Grübler's count
//! (check 2, [`crate::checks::grubler::check`]), structural redundancy (check 3,
//! [`crate::checks::pebble::check`]) and the rank of the constraint Jacobian at the drawing
//! (check 4, [`geometric`]). [`check`] runs them all and collects every [`Issue`].

mod drawing;
mod meshes;
mod rank;

pub use drawing::drawing;
pub use meshes::meshes_solvable;
pub use rank::{geometric, jacobian, Jacobian};

use crate::front::resolve::{Culprit, Issue};
use crate::model::Model;

/// Relative tolerance of the rank decisions of [`geometric`]: a singular value counts as
/// zero when it is at most `RANK_TOL` × the largest one (the Jacobian is dimensionless,
/// see [`jacobian`]).
pub const RANK_TOL: f64 = 1e-9;

/// Relative tolerance below which two points of one link are coincident: `COINCIDENT_TOL`
/// × [`Model::scale`] (m).
pub const COINCIDENT_TOL: f64 = 1e-12;

/// A sliding axis `along (ux, uy)` shorter than this (dimensionless, the axis is a
/// direction) is taken as zero.
pub const AXIS_TOL: f64 = 1e-12;

/// A component of a null vector is significant when it exceeds this fraction of the
/// vector's largest component.
const SIGNIFICANT: f64 = 1e-6;

fn names(items: impl Iterator<Item = String>) -> String {
    items
        .map(|n| format!("`{n}`"))
        .collect::<Vec<_>>()
        .join(", ")
}

fn plural(n: usize, one: &str, many: &str) -> String {
    format!("{n} {}", if n == 1 { one } else { many })
}

/// How closely a gear pair's centre distance must match its pitch radii, relative to the
/// drawing's scale.
pub const MESH_TOL: f64 = 1e-9;

/// Every check of `docs/conventions.md#checks` on a resolved model (check 1, names, is done by
/// [`crate::front::resolve::resolve`]): [`drawing`] (5), [`crate::checks::grubler::check`] (2),
/// [`crate::checks::pebble::check`] (3), and [`geometric`] (4) only when the drawing and the counts
/// passed, to avoid cascades. A structural issue that covers the whole mechanism is
/// dropped when Grübler's count already failed (it restates the count). Returns every
/// issue found, in that order; empty when the mechanism is accepted.
pub fn check(model: &Model) -> Vec<Issue> {
    let mut out = drawing(model);
    let drawing_ok = out.is_empty();
    let grubler = crate::checks::grubler::check(model);
    let mut pebble = crate::checks::pebble::check(model);
    if grubler.is_some() {
        let n = model.n_links();
        pebble.retain(|i| {
            i.culprits
                .iter()
                .filter(|c| matches!(c, Culprit::Link(_)))
                .count()
                < n
        });
    }
    // Grübler below the inputs with a drawing that really moves (parallel cranks): the
    // rank check tells the true story — redundant constraints — so report that instead.
    if drawing_ok && !model.allow_redundant && grubler.is_some() {
        let g = crate::checks::grubler::count(model).grubler;
        if g < model.inputs.len() as i64 {
            let relaxed = Model {
                allow_redundant: true,
                ..model.clone()
            };
            if geometric(&relaxed).is_empty() {
                let strict = geometric(model);
                if !strict.is_empty() {
                    out.extend(strict.into_iter().map(|mut i| {
                            i.message = format!(
                                "{} (Grübler's count gives G = {g} for {} input(s), but the drawing moves: the count is fooled by the redundant constraints)",
                                i.message,
                                model.inputs.len()
                            );
                            i
                        }));
                    return out;
                }
            }
        }
    }
    let counts_ok = grubler.is_none() && pebble.is_empty();
    out.extend(grubler);
    out.extend(pebble);
    if drawing_ok && counts_ok {
        out.extend(geometric(model));
        if out.is_empty() {
            out.extend(meshes_solvable(model));
        }
    }
    out
}

/// The checks that depend on the numbers rather than the topology, for a model whose
/// topology already passed [`check`] (e.g. at compile time) and whose parameters changed
/// at run time: [`drawing`] (check 5), then [`geometric`] (check 4, redundancy and
/// determinacy at the new drawing) when the drawing passed. Empty when accepted.
pub fn runtime(model: &Model) -> Vec<Issue> {
    let out = drawing(model);
    if !out.is_empty() {
        return out;
    }
    geometric(model)
}

#[cfg(test)]
mod tests;
