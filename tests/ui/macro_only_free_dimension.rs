// Mistake (shapes): `free(LO..HI)` in the macro; `mech size` chooses it in a file, the macro needs the number.
use mech::prelude::*;

mechanism! {
    /// A four-bar whose links are declared by their shapes and materials.
    pub struct Shaped {
        ground { O2: (0.0, 0.0), O4: (0.3, 0.0) },
        link crank {
            points { O2, A: (0.0, 0.1) },
            shape: bar(width free(10 mm..40 mm), thickness 8 mm), material: steel,
        },
        link coupler {
            points { A, B: (0.25, 0.2) },
            shape: bar(width 16 mm, thickness 6 mm), material: steel,
        },
        link rocker {
            points { O4, B },
            shape: rod(diameter 12 mm), material: aluminium,
        },
        joints {
            O2: revolute(ground, crank),
            A: revolute(crank, coupler),
            B: revolute(coupler, rocker),
            O4: revolute(ground, rocker),
        },
        input: O2,
    }
}

fn main() {}
