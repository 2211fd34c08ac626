// Mistake (dimensions): B is built from P, which is defined later
use mech::prelude::*;

mechanism! {
    /// Crank-rocker four-bar by its lengths.
    pub struct FourBar {
        consts { crank: 80 mm, coupler: 260 mm, rocker: 190 mm },
        ground { O2: (0.0, 0.0), O4: (300 mm, 40 mm) },
        link crank {
            points { O2, A: O2 + polar(crank, 60 deg) },
            mass: 650 g, inertia: 5.2 g_cm2 * 1000, cg: along(25 mm),
        },
        link coupler {
            points { A, B: circle_circle(P, coupler, O4, rocker, left) },
            mass: 1.45 kg, inertia: 0.0112 kg_m2, cg: local(110 mm, 40 mm),
        },
        link rocker {
            points { O4, B },
            mass: 0.95, inertia: 0.0036, cg: along(95 mm),
        },
        joints {
            O2: revolute(ground, crank),
            A: revolute(crank, coupler),
            B: revolute(coupler, rocker),
            O4: revolute(ground, rocker),
        },
        input: O2,
        loads { resist: torque on rocker },
    }
}

fn main() {}
