//! A mechanism accepted with `#[allow(redundant)]`: coupled locomotive wheels (three equal
//! parallel cranks on one coupling rod, a double parallelogram). Its kinematics and its
//! motor torque (virtual power) are determined; its reactions are not, so it has no
//! callable `kinetostatics` (see `tests/ui/redundant_kinetostatics.rs`).

use crate::measure::within;
use mech::prelude::*;

mechanism! {
    /// Coupled wheels: three equal parallel cranks and one coupling rod.
    #[allow(redundant)]
    pub struct CoupledWheels {
        ground { O1: (0.0, 0.0), O2: (0.8, 0.0), O3: (1.6, 0.0) },
        link wheel1 { points { O1, A1: (0.05, 0.0866) }, mass: 120.0, inertia: 9.0, cg: (0.0, 0.0) },
        link wheel2 { points { O2, A2: (0.85, 0.0866) }, mass: 120.0, inertia: 9.0, cg: (0.8, 0.0) },
        link wheel3 { points { O3, A3: (1.65, 0.0866) }, mass: 120.0, inertia: 9.0, cg: (1.6, 0.0) },
        link rod { points { A1, A2, A3 }, mass: 35.0, inertia: 7.5, cg: (0.85, 0.0866) },
        joints {
            O1: revolute(ground, wheel1),
            O2: revolute(ground, wheel2),
            O3: revolute(ground, wheel3),
            A1: revolute(wheel1, rod),
            A2: revolute(wheel2, rod),
            A3: revolute(wheel3, rod),
        },
        input: O1,
        loads { traction: torque on wheel3 },
    }
}

#[test]
fn coupled_wheels_move_and_need_the_textbook_torque() {
    assert_eq!(
        (
            CoupledWheels::DOF,
            CoupledWheels::EQUATIONS,
            CoupledWheels::UNKNOWNS
        ),
        (1, 12, 13)
    );
    let m = CoupledWheels::new();
    let r = (0.05f64 * 0.05 + 0.0866 * 0.0866).sqrt();
    // Every wheel turns with the first, the rod translates on a circle of radius r.
    let i_star = 3.0 * 9.0 + 35.0 * r * r;
    let loads = CoupledWheelsLoads { traction: -50.0 };
    // At q = 0 and π the cranks lie on the line of the pivots: the parallelogram's change
    // point (it could fold into an anti-parallelogram), reported as such.
    let at_change = m.kinematics(0.0, 1.0, 0.0);
    assert!(
        matches!(
            at_change,
            Err(MechError::Singular { .. } | MechError::NoAssembly)
        ),
        "{at_change:?}"
    );
    // Away from the change points (0.3 rad or more), where the dyad is well conditioned.
    for k in 0..16 {
        let q = 0.3 + 0.4 * k as f64;
        if (q / std::f64::consts::PI - (q / std::f64::consts::PI).round()).abs()
            * std::f64::consts::PI
            < 0.3
        {
            continue;
        }
        let (qd, qdd) = (10.0, 2.0);
        let mo = m.kinematics(q, qd, qdd).unwrap();
        for w in [mo.links.wheel2, mo.links.wheel3] {
            let d = (w.angle - mo.links.wheel1.angle).rem_euclid(std::f64::consts::TAU);
            // measured worst 1.1e-14 (be05608); 100×
            assert!(within(d.min(std::f64::consts::TAU - d), 1e-12), "q={q}");
            assert!(
                within((w.omega - qd).abs(), 2e-12 * qd)
                    && within((w.alpha - qdd).abs(), 1e-11 * qd * qd), // measured worst 2.1e-14, 1.0e-13 (be05608); 100×
                "q={q}: {} {}",
                w.omega,
                w.alpha
            );
        }
        assert!(
            within(mo.links.rod.omega.abs(), 1e-13 * qd), // measured worst 1.4e-15 (be05608); 100×
            "the rod translates: ω = {}",
            mo.links.rod.omega
        );
        let torque = m.driver_action(&mo, &loads).unwrap();
        // I* is constant: T = I* q̈ − (traction on a wheel turning at the input's rate).
        let want = i_star * qdd + 50.0;
        assert!(
            within((torque - want).abs(), 1e-10 * want), // measured worst 1.3e-12 (be05608); 100×
            "q={q}: {torque} vs {want}"
        );
        // measured worst 2.1e-14, 2.7e-12 (be05608); 100×
        let z = m.reduced(q).unwrap();
        assert!(
            within((z.inertia - i_star).abs(), 1e-12 * i_star)
                && within(z.inertia_derivative.abs(), 1e-10)
        );
        // A motion at rest still gets its torque from the solved velocity field.
        let rest = m.kinematics(q, 0.0, qdd).unwrap();
        // measured worst 2.1e-14 (be05608); 100×
        assert!(within(
            (m.driver_action(&rest, &loads).unwrap() - want).abs(),
            2e-12 * want
        ));
    }
}

/// The same mechanism loaded at run time (`mech::Mechanism`, the same text): the same
/// motion, the same motor torque (virtual power) and I*, and no reactions.
#[test]
fn the_run_time_mechanism_solves_it_too() {
    let text = mech_oracle::mechanism_text(include_str!("redundant.rs"), "CoupledWheels").unwrap();
    let rt = mech::Mechanism::from_dsl(text).unwrap();
    assert!(rt.redundant());
    let m = CoupledWheels::new();
    let loads = CoupledWheelsLoads { traction: -50.0 };
    let mut rloads = rt.loads();
    assert!(rloads.set_by_name("traction", &[-50.0]));
    for k in 0..16 {
        let q = 0.3 + 0.4 * k as f64;
        if (q / std::f64::consts::PI - (q / std::f64::consts::PI).round()).abs()
            * std::f64::consts::PI
            < 0.3
        {
            continue;
        }
        let (mo, rm) = (
            m.kinematics(q, 10.0, 2.0).unwrap(),
            rt.kinematics(&[q], &[10.0], &[2.0]).unwrap(),
        );
        for name in ["wheel2", "wheel3", "rod"] {
            let (a, b) = (mo.link(name).unwrap(), rm.link(name).unwrap());
            assert!(
                within((a.omega - b.omega).abs(), 1e-15 * 10.0) // measured worst 0 (be05608); exact; a few ulps
                    && within((a.alpha - b.alpha).abs(), 1e-15 * 100.0), // measured worst 0 (be05608); exact; a few ulps
                "q={q} {name}"
            );
            // measured worst 0 (be05608); exact; a few ulps
            assert!(within((a.cg - b.cg).norm(), 1e-15), "q={q} {name}");
        }
        let (t, rtq) = (
            m.driver_action(&mo, &loads).unwrap(),
            rt.driver_action(&rm, &rloads).unwrap()[0],
        );
        // measured worst 0 (be05608); exact; a few ulps
        assert!(
            within((t - rtq).abs(), 1e-15 * t.abs()),
            "q={q}: {t} vs {rtq}"
        );
        let (z, rz) = (m.reduced(q).unwrap(), rt.reduced(q).unwrap());
        // measured worst 0 (be05608); exact; a few ulps
        assert!(within((z.inertia - rz.inertia).abs(), 1e-15 * z.inertia));
        assert!(matches!(
            rt.kinetostatics(&rm, &rloads),
            Err(MechError::Redundant(_))
        ));
    }
}
