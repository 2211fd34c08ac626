//! Whether each gear pair, rack and rolling joint can be solved in closed form.

use super::names;
use crate::front::resolve::{Culprit, Issue};
use crate::kernel::constraints::ConKind;
use crate::model::Model;

/// A gear pair or rack must be solved by Willis' relation (`crate::elements::gears`): the meshing
/// link alone, held by its pin (or slide) and the mesh, after its partner and carrier, or
/// a gear-train group of up to three links pinned at their centres. A mesh inside another
/// group (a gear that closes a loop of a linkage) is refused.
pub fn meshes_solvable(model: &Model) -> Vec<Issue> {
    let Ok(plan) = crate::plan::assur::plan(model) else {
        return Vec::new();
    };
    let mut out = Vec::new();
    for g in &plan {
        if matches!(
            g.kernel,
            crate::plan::assur::Kernel::Mesh(_)
                | crate::plan::assur::Kernel::Train(_)
                | crate::plan::assur::Kernel::Rolling(_)
                | crate::plan::assur::Kernel::Cam(_)
        ) {
            continue;
        }
        for c in g.cons.iter().filter(|c| c.kind == ConKind::Rolling) {
            let jt = &model.joints[c.joint];
            out.push(Issue {
                culprits: vec![Culprit::Joint(c.joint)],
                message: format!(
                    "rolling joint `{}` is not solvable in closed form: its links {} form one group with other joints; a rolling wheel must be driven by its travel (the joint as an input) or be pinned at its centre to a rod pinned to a solved link (a crank–rod–wheel)",
                    jt.name,
                    names(g.bodies.iter().map(|&b| model.links[b].name.clone()))
                ),
            });
        }
        for c in g.cons.iter().filter(|c| c.kind == ConKind::Mesh) {
            let jt = &model.joints[c.joint];
            out.push(Issue {
                culprits: vec![Culprit::Joint(c.joint)],
                message: format!(
                    "{} `{}` is not solvable gear by gear: its links {} form one group with other joints; a meshing link must be held by one pin at its centre (or, for a rack, one slide) and be driven by the mesh alone after its partner and its carrier, or be one of at most three gears pinned at their centres that mesh with one another; closing a linkage's loop through a mesh is not supported",
                    jt.kind.keyword(),
                    jt.name,
                    names(g.bodies.iter().map(|&b| model.links[b].name.clone()))
                ),
            });
        }
    }
    out
}
