//! The warm start of a sweep: the rows of `mech sweep` and of Python's tables
//! (`super::columns::Columns::rows_many`), solved one after the other within a chunk, hand
//! each triad (`crate::kernel::triad`) the previous configuration's link states as its
//! Newton's start, instead of the drawing. The batched forms (`pose_many`, ...) do not:
//! each of their configurations is the one-configuration solver's answer exactly.
//!
//! A triad's pose is one eliminated unknown solved by Newton; started from the drawing its
//! cost grows with the distance from it, and a triad whose dyad changes side over the turn
//! finds no root from the drawing with the plan's lead and tries the others. Started from
//! a neighbour a few degrees away it converges in two or three steps. The root is accepted
//! on the drawn assembly only (the sign of the group's Jacobian determinant, checked by the
//! kernel whatever the start). On a mechanism as drawn the warm start changes the cost,
//! not the answer (`tests/triads.rs`); where the turn passes dead points, one call from the
//! drawing can miss a root or land on another assembly of the same sign, and a sweep
//! follows the assembly from row to row instead.
//!
//! The previous configuration is used when it was solved and every input moved by at most
//! [`WARM_STEP`] since (rad, or that fraction of the mechanism's size for a prismatic
//! input); otherwise the drawing, as for a single call. Mechanisms without a triad ignore
//! it (no copy, no test).

use super::mechanism::Mechanism;
use crate::kernel::link_state::LinkState;
use crate::model::JointKind;

/// The largest change of an input (rad; for a prismatic input, this fraction of the
/// mechanism's size) across which a triad starts from the previous configuration.
pub(crate) const WARM_STEP: f64 = 0.5;

/// A chunk's last solved configuration (inputs and link states), for the warm start.
#[derive(Clone, Debug, Default)]
pub(crate) struct Warm {
    /// The mechanism has a triad (the warm start applies).
    on: bool,
    /// The largest change of each input across which the start is warm.
    step: Vec<f64>,
    /// The last solved configuration's inputs, and its states (when `solved`).
    q: Vec<f64>,
    states: Vec<LinkState>,
    solved: bool,
}

impl Warm {
    /// No configuration solved yet, for mechanism `m`.
    pub(crate) fn new(m: &Mechanism) -> Warm {
        let on = m.plan.iter().any(|g| g.triad.is_some());
        let step = if on {
            m.model
                .inputs
                .iter()
                .map(|&j| match m.model.joints[j].kind {
                    JointKind::Prismatic => WARM_STEP * m.inst.scale,
                    _ => WARM_STEP,
                })
                .collect()
        } else {
            Vec::new()
        };
        Warm {
            on,
            step,
            ..Warm::default()
        }
    }

    /// The start for the configuration at inputs `q`: the last solved configuration's
    /// states when every input moved by at most its step since, else `None` (the drawing).
    #[inline]
    pub(crate) fn start(&self, q: &[f64]) -> Option<&[LinkState]> {
        let near = self.on
            && self.solved
            && q.len() == self.q.len()
            && q.iter()
                .zip(&self.q)
                .zip(&self.step)
                .all(|((a, b), &h)| (a - b).abs() <= h);
        near.then_some(&self.states[..])
    }

    /// Remember the configuration at inputs `q` with the states `s` when `solved`, or
    /// forget the last one.
    #[inline]
    pub(crate) fn keep(&mut self, q: &[f64], s: &[LinkState], solved: bool) {
        if !self.on {
            return;
        }
        self.solved = solved;
        if solved {
            self.q.clear();
            self.q.extend_from_slice(q);
            self.states.clear();
            self.states.extend_from_slice(s);
        }
    }
}

use crate::MechError;

impl Warm {
    /// Solve the configuration at inputs `q` by `solve`, given the start for it
    /// ([`Warm::start`]) and returning its answer and the states it solved into; remember
    /// them when it succeeds, forget the last configuration when it fails.
    #[inline]
    pub(crate) fn run<'s, T>(
        &mut self,
        q: &[f64],
        solve: impl FnOnce(Option<&[LinkState]>) -> Result<(T, &'s [LinkState]), MechError>,
    ) -> Result<T, MechError> {
        match solve(self.start(q)) {
            Ok((t, s)) => {
                self.keep(q, s, true);
                Ok(t)
            }
            Err(e) => {
                self.keep(q, &[], false);
                Err(e)
            }
        }
    }
}

#[cfg(test)]
mod tests {
    //! When the warm start is given: after a solved configuration, within the step, on a
    //! mechanism with a triad; never on one without.
    use super::*;
    use crate::kernel::constraints::Level;

    const TRIAD: &str = "pub struct S {
        ground { P0: (0.0, 0.0), P4: (0.117, 0.023), P6: (0.139, 0.033) },
        link crank { points { P0, P1: (0.015, 0.041) } },
        link a { points { P1, P2: (0.061, 0.095) } },
        link mid { points { P2, P3: (0.103, 0.084), P5: (0.135, 0.120) } },
        link b { points { P3, P4 } },
        link c { points { P5, P6 } },
        joints {
            P0: revolute(ground, crank), P1: revolute(crank, a), P2: revolute(a, mid),
            P3: revolute(mid, b), P4: revolute(ground, b), P5: revolute(mid, c),
            P6: revolute(ground, c),
        },
        input: P0,
    }";

    #[test]
    fn the_start_is_the_last_solved_configuration_within_the_step() {
        let m = Mechanism::from_dsl(TRIAD).unwrap();
        let mut w = Warm::new(&m);
        let mut s = Vec::new();
        assert!(w.start(&[1.2]).is_none(), "nothing solved yet");
        m.solve_into(&[1.2], &[0.0], &[0.0], Level::Position, &mut s)
            .unwrap();
        w.keep(&[1.2], &s, true);
        assert_eq!(w.start(&[1.2 + 0.9 * WARM_STEP]), Some(&s[..]));
        assert!(w.start(&[1.2 - 1.1 * WARM_STEP]).is_none(), "too far");
        assert!(w.start(&[f64::NAN]).is_none());
        assert!(w.start(&[1.2, 0.0]).is_none(), "another number of inputs");
        w.keep(&[1.3], &s, false);
        assert!(w.start(&[1.3]).is_none(), "the last one failed");
        // A warm sweep solves as `solve_into` does.
        let (mut warm, mut cold) = (Vec::new(), Vec::new());
        let mut w = Warm::new(&m);
        for k in 0..40 {
            let q = [1.2 + 0.05 * k as f64];
            w.run(&q, |start| {
                m.solve_into_from(&q, &[0.0], &[0.0], Level::Position, &mut warm, start)?;
                Ok(((), &warm[..]))
            })
            .unwrap();
            m.solve_into(&q, &[0.0], &[0.0], Level::Position, &mut cold)
                .unwrap();
            for (a, b) in warm.iter().zip(&cold) {
                assert!((a.pos - b.pos).norm() < 1e-14 && (a.rot - b.rot).norm() < 1e-13);
            }
        }
    }

    #[test]
    fn a_mechanism_without_a_triad_has_no_warm_start() {
        let m = Mechanism::from_dsl(
            "pub struct F {
                ground { O: (0.0, 0.0), C: (0.3, 0.0) },
                link crank { points { O, A: (0.0, 0.1) } },
                link coupler { points { A, B: (0.25, 0.2) } },
                link rocker { points { C, B } },
                joints { O: revolute(ground, crank), A: revolute(crank, coupler),
                         B: revolute(coupler, rocker), C: revolute(ground, rocker) },
                input: O,
            }",
        )
        .unwrap();
        let mut w = Warm::new(&m);
        let mut s = Vec::new();
        m.solve_into(&[1.0], &[0.0], &[0.0], Level::Position, &mut s)
            .unwrap();
        w.keep(&[1.0], &s, true);
        assert!(w.start(&[1.0]).is_none());
    }
}
