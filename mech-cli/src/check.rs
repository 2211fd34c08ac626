//! `mech check FILE`: the macro's checks, the messages pointing into the file, then the
//! structure: N, P_I, P_II, G by Grübler, equations against unknowns, and the Assur groups
//! in solve order with their kinds, saying which are closed-form.

use mech_core::kernel::dyad::Solver;
use mech_core::plan::assur::{self, Group};
use mech_core::Mechanism;
use std::fmt::Write;

/// The kind of a group's position solution, in words, and whether it is closed-form.
pub fn group_kind(g: &Group) -> (&'static str, bool) {
    match g.solver {
        Solver::DrivenRevolute { .. } => ("driven crank", true),
        Solver::DrivenPrismatic { .. } => ("driven slider", true),
        Solver::Rrr { .. } => ("RRR dyad", true),
        Solver::Rrp { .. } => ("RRP dyad", true),
        Solver::Rpr { .. } => ("RPR dyad", true),
        Solver::Prp { .. } => ("PRP dyad", true),
        Solver::Rpp { .. } => ("RPP dyad", true),
        Solver::PinInFixedSlot { .. } => ("link with a pin in a slot", true),
        Solver::Newton => ("group without a closed form (Newton)", false),
        Solver::SlottedLever { .. } => ("slotted lever on a pin", true),
        Solver::SlottedSlider { .. } => ("slider with a slot and a pin (Scotch yoke)", true),
        Solver::Mesh { .. } => ("meshing gear or rack (Willis)", true),
        Solver::Train => ("gear train (Willis, one linear system)", true),
        Solver::DrivenRolling { .. } => ("wheel driven along its track", true),
        Solver::Rrl { .. } => ("rod and rolling wheel", true),
        Solver::Cam { .. } => ("cam-driven follower", true),
    }
}

/// The summary of a valid mechanism, as `mech check` prints it.
pub fn summary(m: &Mechanism) -> String {
    let model = m.model();
    let n = model.n_links();
    let (pi, pii) = (model.lower_pairs(), model.higher_pairs());
    let g = m.dof();
    let eqs = 3 * (n - 1);
    let unknowns = g + 2 * pi + pii;
    let mut s = String::new();
    let _ = writeln!(s, "mechanism `{}`: valid", model.name);
    let _ = writeln!(
        s,
        "  N = {n} links (ground included), P_I = {pi} lower pairs, P_II = {pii} higher pairs"
    );
    let _ = writeln!(
        s,
        "  Grübler: G = 3(N − 1) − 2 P_I − P_II = {} − {} − {pii} = {}; inputs declared: {g}",
        eqs,
        2 * pi,
        eqs as i64 - 2 * pi as i64 - pii as i64
    );
    let _ = writeln!(
        s,
        "  equations 3(N − 1) = {eqs}, unknowns G + 2 P_I + P_II = {unknowns}{}",
        if m.redundant() {
            " (redundant constraints accepted: motor actions only, no reactions)"
        } else {
            ""
        }
    );
    match assur::plan(model) {
        Ok(plan) => {
            let _ = writeln!(s, "  Assur groups in solve order:");
            for (i, grp) in plan.iter().enumerate() {
                let (kind, closed) = group_kind(grp);
                let links: Vec<&str> = grp
                    .bodies
                    .iter()
                    .map(|&b| model.links[b].name.as_str())
                    .collect();
                let _ = writeln!(
                    s,
                    "    {}. {kind}: {} ({})",
                    i + 1,
                    links.join(", "),
                    if closed { "closed form" } else { "iterative" }
                );
            }
        }
        Err(_) => {
            let _ = writeln!(s, "  (no plan)");
        }
    }
    s
}
