//! The accepted magnitudes of a drawing's numbers (`docs/conventions.md#magnitudes`).
//!
//! f64 holds 1e±308, but the solvers multiply lengths, masses and squared speeds: a mass
//! of 1e308 kg or a drawing 1e200 m across overflows to an infinity and then to a NaN in a
//! result, and a drawing 1e-200 m across underflows the rank test (every Jacobian entry
//! looks like zero, and the mechanism would be called redundant). So the checks of the
//! macro, of the run-time loader and of `from_params` refuse numbers outside ranges wide
//! enough for any machine, from a MEMS device to a crane, and every solver refuses to
//! return a non-finite number ([`crate::kernel::finite`]).
//!
//! | quantity | accepted |
//! |---|---|
//! | the drawing's size (largest distance between two points) | 1e-9 m to 1e6 m |
//! | a coordinate, a cg | \|x\| ≤ 1e6 m |
//! | a mass | 0, or 1e-18 kg to 1e9 kg |
//! | a moment of inertia, a flywheel | 0, or 1e-36 kg·m² to 1e15 kg·m² |
//! | gravity | \|g\| ≤ 1e4 m/s² |

use crate::front::resolve::{Culprit, Issue};
use crate::model::Model;

/// The smallest and largest size of a drawing, m.
pub const SIZE: (f64, f64) = (1e-9, 1e6);
/// The largest |coordinate| of a point or a cg, m.
pub const COORDINATE: f64 = 1e6;
/// The smallest non-zero and the largest mass, kg.
pub const MASS: (f64, f64) = (1e-18, 1e9);
/// The smallest non-zero and the largest moment of inertia, kg·m².
pub const INERTIA: (f64, f64) = (1e-36, 1e15);
/// The largest |gravity|, m/s².
pub const GRAVITY: f64 = 1e4;

pub(crate) const WHY: &str = "products of masses, lengths and squared speeds must stay far from f64's overflow and underflow";

/// x is 0 or within [lo, hi] (a finite, non-negative number).
pub(crate) fn in_range(x: f64, (lo, hi): (f64, f64)) -> bool {
    x == 0.0 || (x >= lo && x <= hi)
}

/// The magnitude issues of a model whose numbers are finite (validate's drawing check
/// reports non-finite and negative numbers first).
pub fn check(model: &Model) -> Vec<Issue> {
    let mut out = Vec::new();
    if model.links.len() < 2 {
        out.push(Issue {
            culprits: vec![Culprit::Mechanism],
            message: "the mechanism has no moving link: declare at least one `link NAME { points { ... } }` joined to the ground, and an input".into(),
        });
    }
    let finite = model
        .points
        .iter()
        .all(|p| p.pos.iter().all(|v| v.is_finite()));
    for (i, p) in model.points.iter().enumerate() {
        if finite && p.pos.iter().any(|v| v.abs() > COORDINATE) {
            out.push(Issue {
                culprits: vec![Culprit::Point(i)],
                message: format!("point `{}` is at ({:e}, {:e}) m: coordinates must be within ±{COORDINATE:e} m ({WHY}); move the origin or check the unit", p.name, p.pos[0], p.pos[1]),
            });
        }
    }
    let size = model.scale();
    if finite && model.points.len() >= 2 && !(size >= SIZE.0 && size <= SIZE.1) {
        out.push(Issue {
            culprits: vec![Culprit::Mechanism],
            message: format!(
                "the drawing is {size:e} m across: mech takes drawings from {:e} m to {:e} m across ({WHY}, and the rank test needs lengths well above rounding); scale the drawing, or check the unit (`mm`, `m`)",
                SIZE.0, SIZE.1
            ),
        });
    }
    for (i, l) in model.links.iter().enumerate().skip(1) {
        if let Some(m) = l
            .mass
            .filter(|m| m.is_finite() && *m >= 0.0 && !in_range(*m, MASS))
        {
            out.push(Issue {
                culprits: vec![Culprit::Mass(i), Culprit::Link(i)],
                message: format!(
                    "link `{}` has mass {m:e} kg: a mass is 0 or from {:e} kg to {:e} kg ({WHY})",
                    l.name, MASS.0, MASS.1
                ),
            });
        }
        for (what, v, c) in [
            ("moment of inertia", l.inertia, Culprit::Inertia(i)),
            ("flywheel inertia", l.flywheel, Culprit::Link(i)),
        ] {
            if v.is_finite() && v >= 0.0 && !in_range(v, INERTIA) {
                out.push(Issue {
                    culprits: vec![c, Culprit::Link(i)],
                    message: format!("link `{}` has a {what} of {v:e} kg·m²: it is 0 or from {:e} to {:e} kg·m² ({WHY})", l.name, INERTIA.0, INERTIA.1),
                });
            }
        }
        if l.cg.iter().all(|v| v.is_finite()) && l.cg.iter().any(|v| v.abs() > COORDINATE) {
            out.push(Issue {
                culprits: vec![Culprit::Cg(i), Culprit::Link(i)],
                message: format!("link `{}` has its cg at ({:e}, {:e}) m: coordinates must be within ±{COORDINATE:e} m ({WHY})", l.name, l.cg[0], l.cg[1]),
            });
        }
    }
    if let Some(g) = model.gravity.filter(|g| g.iter().all(|v| v.is_finite())) {
        if g[0].hypot(g[1]) > GRAVITY {
            out.push(Issue {
                culprits: vec![Culprit::Gravity],
                message: format!("gravity ({:e}, {:e}) m/s² is larger than {GRAVITY:e} m/s² ({WHY}); on Earth it is (0, -9.81)", g[0], g[1]),
            });
        }
    }
    out
}
