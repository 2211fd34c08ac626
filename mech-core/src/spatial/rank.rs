//! The constraint Jacobian's rank at the drawing, naming the joints whose equations repeat.
//!
//! The rows (joints in order, then the drivers, then the idle spins) are each scaled to
//! unit length and added group by group; a group whose rows raise the rank (singular
//! values above 1e-9 of the largest) by fewer than their number repeats equations already
//! imposed: redundant constraints (their reactions are statically indeterminate), or an
//! input that cannot move the drawing (a dead point).

use super::constraints::BodyState;
use super::kinematics::Layout;
use super::model::Site;
use nalgebra::DMatrix;

fn rank(m: &DMatrix<f64>) -> usize {
    if m.nrows() == 0 || m.ncols() == 0 {
        return 0;
    }
    let s = m.clone().singular_values();
    let top = s.max();
    s.iter().filter(|&&v| v > 1e-9 * top).count()
}

/// The rows at the drawing and their Jacobian, each row scaled to unit length.
fn drawing(layout: &Layout) -> (Vec<super::constraints::Row>, DMatrix<f64>) {
    let s: Vec<BodyState> = layout.o0.iter().map(|&o| BodyState::drawing(o)).collect();
    let q = vec![0.0; layout.model.inputs.len()];
    let (rows, owners) = layout.rows(&s, &q);
    let mut j = layout.jacobian(&rows, &owners);
    for mut r in j.row_iter_mut() {
        let n = r.norm();
        if n > 0.0 {
            r /= n;
        }
    }
    (rows, j)
}

/// With `#[allow(redundant)]`: the mobility is the rank's, 6(N − 1) − rank of the joints'
/// (and idle spins') rows at the drawing, and must equal the inputs; with the drivers' rows
/// the rank must be 6(N − 1) (the inputs determine the drawing). The message, or `None`.
pub(crate) fn redundant(layout: &Layout) -> Option<String> {
    let (rows, j) = drawing(layout);
    let g = layout.model.inputs.len();
    let first = rows.len() - g - layout.spins.len();
    let cols = j.ncols();
    let mobility = cols - rank(&j.clone().remove_rows(first, g));
    if mobility != g {
        return Some(format!(
            "with #[allow(redundant)] the mobility is the rank's: 6(N−1) − rank = {cols} − {} = {mobility} at the drawing, but {g} input(s) were declared: declare {mobility} input(s)",
            cols - mobility
        ));
    }
    let all = rank(&j);
    (all < cols).then(|| format!(
        "the inputs do not determine the drawing (rank {all} of {cols} with their equations): an input is at a dead point; draw the mechanism elsewhere or choose another input"
    ))
}

/// The message naming the redundant joints (or the locked inputs) when the Jacobian at the
/// drawing has fewer independent rows than rows, with the places named (joints, inputs'
/// joints, idle links); `None` when its rows are independent.
pub(crate) fn check(layout: &Layout) -> Option<(Vec<Site>, String)> {
    let (rows, j) = drawing(layout);
    let total = rank(&j);
    if total == rows.len() {
        return None;
    }
    let model = &layout.model;
    let mut groups: Vec<(String, usize, Site)> = model
        .joints
        .iter()
        .enumerate()
        .map(|(k, x)| {
            (
                format!("joint `{}` ({})", x.name, x.kind.word()),
                6 - x.kind.class(),
                Site::Joint(k),
            )
        })
        .collect();
    groups.extend(model.inputs.iter().map(|&k| {
        (
            format!("input `{}`", model.joints[k].name),
            1,
            Site::Joint(k),
        )
    }));
    groups.extend(layout.spins.iter().map(|&(b, _)| {
        (
            format!("the spin fix of link `{}`", model.bodies[b].name),
            1,
            Site::Body(b),
        )
    }));
    let (mut start, mut before, mut found, mut sites) = (0, 0, Vec::new(), Vec::new());
    for (name, count, site) in groups {
        let now = rank(&j.rows(0, start + count).into_owned());
        if now < before + count {
            sites.push(site);
            found.push(format!(
                "{name}: {} of its {count} equation(s) repeat those before it",
                before + count - now
            ));
        }
        before = now;
        start += count;
    }
    let hidden = if rows.len() == j.ncols() {
        format!(" Kutzbach's count matches the inputs only because as many freedoms are left to no input elsewhere (a link free to turn or slide): {} of the 6(N − 1) = {} body coordinates are not determined.", rows.len() - total, j.ncols())
    } else {
        String::new()
    };
    Some((sites, format!(
        "the constraint Jacobian at the drawing has rank {total} for {} equations: {} redundant. {}.{hidden} Redundant joint equations make the reactions statically indeterminate: replace a joint by one that leaves more freedom (e.g. a revolute (5 equations) by a universal (4) or a spherical (3) joint) until Kutzbach's count and the rank agree; an input whose equation repeats the others is at a dead point in the drawing: draw the mechanism elsewhere or choose another input",
        rows.len(),
        rows.len() - total,
        found.join("; ")
    )))
}
