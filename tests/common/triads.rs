// Triad machines (issue 35): a crank, then one class III group — a ternary link pinned to
// three binary links, each pinned to a solved link — solved by the triad kernel
// (`mech_core::kernel::triad`). Shared by `tests/triads.rs` and `benches/triad.rs`; read as
// text by the run-time `Mechanism` and the oracle there.

use mech::prelude::*;

mechanism! {
    /// pyslvs's Stephenson III (examples/mech/stephenson_iii.mech), mm scaled to m: the crank L1, then the triad L2, L3 (ternary), L4, L5
    pub struct StephensonIII {
        gravity: (0.0, -9.81),
        ground { P0: (0.00025, -0.000625), P4: (0.117125, 0.023375), P6: (0.138875, 0.033125) },
        link L1 {
            points { P0, P1: (0.015375, 0.041125) },
            mass: 0.1, inertia: 2.0e-5, cg: (0.0078, 0.02),
        },
        link L2 {
            points { P1, P2: (0.061375, 0.095125) },
            mass: 0.2, inertia: 1.0e-4, cg: (0.038375, 0.068125),
        },
        link L3 {
            points { P2, P3: (0.102875, 0.084375), P5: (0.134625, 0.119875) },
            mass: 0.4, inertia: 4.0e-4, cg: (0.1, 0.1),
        },
        link L4 {
            points { P3, P4 },
            mass: 0.15, inertia: 6.0e-5, cg: (0.11, 0.054),
        },
        link L5 {
            points { P5, P6 },
            mass: 0.2, inertia: 1.3e-4, cg: (0.13675, 0.0765),
        },
        joints {
            J0: revolute(ground, L1) at P0,
            J1: revolute(L1, L2) at P1,
            J2: revolute(L2, L3) at P2,
            J3: revolute(L3, L4) at P3,
            J4: revolute(ground, L4) at P4,
            J5: revolute(L3, L5) at P5,
            J6: revolute(ground, L5) at P6,
        },
        input: J0,
        loads {
            load: force on L3 at P5,
            resist: torque on L4,
        },
    }
}

mechanism! {
    /// The Stephenson chain on the binary link of its two-binary path (O–G), driven by a ternary crank: the triad tri with l3 and l4 pinned to the crank, l2 to the ground
    pub struct Stephenson2 {
        gravity: (0.0, -9.81),
        ground { O: (0.0, 0.0), G: (0.3, -0.05) },
        link crank {
            points { O, E: (0.03, 0.0), F: (-0.01, 0.03) },
            mass: 0.3, inertia: 1.0e-4, cg: (0.007, 0.01),
        },
        link l3 {
            points { E, K: (0.15, 0.15) },
            mass: 0.2, inertia: 4.0e-4, cg: (0.09, 0.075),
        },
        link l4 {
            points { F, M: (0.1, 0.22) },
            mass: 0.2, inertia: 4.0e-4, cg: (0.045, 0.125),
        },
        link tri {
            points { K, M, H: (0.27, 0.2) },
            mass: 0.5, inertia: 1.0e-3, cg: (0.17, 0.19),
        },
        link l2 {
            points { G, H },
            mass: 0.25, inertia: 6.0e-4, cg: (0.285, 0.075),
        },
        joints {
            O: revolute(ground, crank),
            E: revolute(crank, l3),
            K: revolute(l3, tri),
            F: revolute(crank, l4),
            M: revolute(l4, tri),
            H: revolute(tri, l2),
            G: revolute(ground, l2),
        },
        input: O,
        loads {
            load: force on tri at H,
            resist: torque on l2,
        },
    }
}
