//! The one-input dynamics of a case ([`dynamics`]): the direct problem by three
//! integrators and by the energy method, and the `mech flywheel` path (a cycle balanced,
//! its flywheel by Wittenbauer and approximately, its steady state, the check by time
//! integration), at moderate and hostile settings. They cost tens of milliseconds, a
//! hundred times the rest of a case: one loaded mechanism in
//! [`crate::exercise::DYNAMICS_EVERY`] gets them.

use crate::exercise::{loads, Case};
use mech_core::dynamics::flywheel::Cycle;
use mech_core::dynamics::ode::{self, Dop853, DormandPrince, Rk4, Tolerance};
use mech_core::dynamics::{equation_of_motion, EnergyMethod};
use mech_core::model::JointKind;
use mech_core::Mechanism;
use std::f64::consts::TAU;

/// The one-input dynamics: the direct problem by three integrators and by the energy
/// method, and (on a revolute input) the flywheel of a cycle, Wittenbauer's and the
/// approximate, its steady state and the check by time integration.
pub fn dynamics(c: &mut Case, m: &Mechanism) {
    let l = loads(m, 1e3);
    for (k, (q0, w0)) in [(0.3, 1.0f64), (0.3, 1e6)].into_iter().enumerate() {
        c.at = format!(" from q = {q0}, qd = {w0}");
        let rhs = || equation_of_motion(m, |_, _, _| (1e3, l.clone()));
        // A step budget of 20 000 bounds each run (a stiff or runaway machine ends in
        // the budget's error) to well under the second a call may take.
        let tol = Tolerance {
            max_steps: 20_000,
            ..Tolerance::new(1e-8, 1e-10)
        };
        // About half a turn: the integrators' work grows with the turns simulated.
        let t_end = (0.5 / w0).min(0.05);
        c.solve("simulate (DOP853)", || {
            ode::solve(
                &mut Dop853::with(tol),
                rhs(),
                0.0,
                [q0, w0],
                t_end,
                None,
                None,
            )
        });
        if k == 0 {
            c.solve("simulate (Dormand-Prince)", || {
                ode::solve(
                    &mut DormandPrince::with(tol),
                    rhs(),
                    0.0,
                    [q0, w0],
                    t_end,
                    None,
                    None,
                )
            });
            c.solve("simulate (RK4)", || {
                ode::solve(
                    &mut Rk4 { h: 1e-3 },
                    rhs(),
                    0.0,
                    [q0, w0],
                    t_end,
                    None,
                    None,
                )
            });
            if let Some(mut e) = c.attempt("energy method", || {
                EnergyMethod::new(m, 0.0, q0, 10.0, |_| (0.0, l.clone()), 1e-8)
            }) {
                c.solve("energy method advance", || e.advance_to(q0 + 0.5));
            }
        }
    }
    c.at.clear();
    let model = m.model();
    if model.joints[model.inputs[0]].kind != JointKind::Revolute {
        return;
    }
    // The `mech flywheel` path: the cycle, balanced, sized, simulated.
    let Some(cycle) = c.attempt("flywheel cycle", || {
        Cycle::new(m, 0.0, TAU, &[], |_| Ok(l.clone()), |_| 0.0)
    }) else {
        return;
    };
    c.numbers(
        "cycle works",
        &[
            cycle.net_work(),
            cycle.gross_work(),
            cycle.balancing_torque(),
        ],
    );
    let Some((cycle, torque)) = c.call("balance", || cycle.balanced()) else {
        return;
    };
    c.numbers("balancing torque", &torque);
    c.attempt("check_periodic", || cycle.check_periodic());
    c.solve("cycle sample", || cycle.sample(8));
    c.solve("fluctuation", || cycle.fluctuation());
    if let Some(fw) = c.solve("flywheel", || cycle.flywheel(10.0, 0.05)) {
        c.solve("flywheel simulate", || {
            cycle.simulate(&fw.exact.state, 1e-8)
        });
        c.solve("speed", || cycle.speed(&fw.exact.state, 1.0));
    }
    c.solve("steady_state", || cycle.steady_state(10.0, 1.0));
    c.solve("speed_fluctuation (hostile speed)", || {
        cycle.speed_fluctuation(1e200, 1.0)
    });
    c.solve("flywheel (hostile speed)", || cycle.flywheel(1e200, 0.05));
    c.solve("flywheel (hostile irregularity)", || {
        cycle.flywheel(10.0, 1e-300)
    });
    c.refuse("flywheel (NaN speed)", || cycle.flywheel(f64::NAN, 0.05));
    c.refuse("steady_state (NaN flywheel)", || {
        cycle.steady_state(10.0, f64::NAN)
    });
    c.refuse("flywheel cycle (NaN period)", || {
        Cycle::new(m, 0.0, f64::NAN, &[], |_| Ok(l.clone()), |_| 0.0)
    });
}
