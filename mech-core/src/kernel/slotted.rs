//! The slotted slider ([`Solver::SlottedSlider`]): a link on a guide with a slot joint,
//! the Scotch yoke's yoke. One unknown, its slide, with no branch: its position
//! ([`slotted_slider`]), its rates ([`slotted_slider_rates`]) and its reactions
//! ([`slotted_slider_reactions`]) in that one coordinate.
//!
//! [`Solver::SlottedSlider`]: crate::kernel::dyad::Solver::SlottedSlider

use crate::kernel::constraints::{JointGeom, Level};
use crate::kernel::kinetostatics::{Reaction, Wrench};
use crate::kernel::link_state::{cross, dir_of, perp, point_of, zero, LinkState, V2};
use crate::MechError;

/// The lines of a [`Solver::SlottedSlider`] group, the body's rotation being G's:
/// (G, K, u, w) with G the guide's solved link, K the slot joint's solved link, u the
/// guide's unit axis and w the slot's, both current. (The guide's axis is in the frame of
/// the prismatic's first link, G's or the body's: the same rotation.)
///
/// [`Solver::SlottedSlider`]: crate::kernel::dyad::Solver::SlottedSlider
#[inline(always)]
fn slider_axes(
    gq: &JointGeom,
    gs: &JointGeom,
    s: &[LinkState],
    body: usize,
) -> (usize, usize, V2, V2) {
    let guide = if gq.b == body { gq.a } else { gq.b };
    let (k, w) = if gs.a == body {
        (gs.b, dir_of(s, guide, gs.axis))
    } else {
        (gs.a, dir_of(s, gs.a, gs.axis))
    };
    (guide, k, dir_of(s, guide, gq.axis), w)
}

/// [`position`] of a [`Solver::SlottedSlider`] group: `body` slides by the prismatic `gq`
/// on the solved link G and has the slot joint `gs` with the solved link K. Its rotation
/// is G's (φ_b = φ_G), so the point X of `body` at the slot joint (local d) runs along
/// the line X(s) = Q₀ + s u, u = R(φ_G) axis_q, Q₀ its place at zero slide; the slot's
/// line passes through a known point P along the unit w (a slot in `body`: P is K's pin,
/// w = R(φ_G) axis_s; a slot in K: P is the slot's point of K, w = R(φ_K) axis_s). X on
/// the slot's line, (X − P) × w = 0, gives the slide (m)
///
/// s = ((P − Q₀) × w) / (u × w),
///
/// the body at pos = X − R(φ_G) d. `Singular` when u ∥ w: the condition estimate of the
/// 2×2 system [u w] (unit columns, dimensionless: no length scale enters),
/// κ_F = 2/|u × w| ≥ [`crate::kernel::linalg::SINGULAR_CONDITION`], the test the joint-screw
/// chain applies to the same matrix. Otherwise it always assembles. Returns 1/(u × w),
/// which the rates reuse ([`slotted_slider_rates`]).
///
/// [`Solver::SlottedSlider`]: crate::kernel::dyad::Solver::SlottedSlider
/// [`position`]: crate::kernel::dyad::position
#[inline(always)]
pub fn slotted_slider(
    gq: &JointGeom,
    gs: &JointGeom,
    s: &mut [LinkState],
    body: usize,
) -> Result<f64, MechError> {
    let (guide, _, u, w) = slider_axes(gq, gs, s, body);
    // The local vectors of the guide's point in G (dg) and in the body (db).
    let (dg, db) = if gq.b == body {
        (gq.da, gq.db)
    } else {
        (gq.db, gq.da)
    };
    let (d, p) = if gs.a == body {
        (gs.da, point_of(s, gs.b, gs.db))
    } else {
        (gs.db, point_of(s, gs.a, gs.da))
    };
    let den = cross(u, w);
    crate::kernel::linalg::check_condition(2.0, den.abs())?;
    let inv = 1.0 / den;
    // The body's anchor at zero slide, and X's place then.
    let b0 = point_of(s, guide, dg) - dir_of(s, guide, db);
    let q0 = b0 + dir_of(s, guide, d);
    let slide = cross(p - q0, w) * inv;
    s[body].rot = if guide == 0 {
        V2::new(1.0, 0.0)
    } else {
        s[guide].rot
    };
    s[body].pos = b0 + u * slide;
    Ok(inv)
}

/// The velocity of the material point of link `l` now at `p` (m/s); zero on the ground.
#[inline(always)]
fn point_vel(s: &[LinkState], l: usize, p: V2) -> V2 {
    if l == 0 {
        zero()
    } else {
        s[l].vel_at(p - s[l].pos)
    }
}

/// The acceleration of the material point of link `l` now at `p` (m/s²); zero on the ground.
#[inline(always)]
fn point_acc(s: &[LinkState], l: usize, p: V2) -> V2 {
    if l == 0 {
        zero()
    } else {
        s[l].acc_at(p - s[l].pos)
    }
}

/// Velocity (and acceleration when `upto` is [`Level::Acceleration`]) of a
/// [`Solver::SlottedSlider`] group's link, in its one natural coordinate, the slide s
/// along the guide's axis u; positions placed, `inv_den` = 1/(u × w) from
/// [`slotted_slider`]. The body turns with G (ω_b = ω_G, α_b = α_G) and its points move as
/// G's plus the slide: v_b(X) = v_G(X) + ṡ u, a_b(X) = a_G(X) + s̈ u + 2 ω_G ṡ perp(u).
/// At the pin C (the slot joint's point), with n = perp(w) the slot's normal, the
/// relative velocity of pin and slot runs along the slot, n·(v_K − v_b)(C) = 0, and its
/// derivative carries the slot's turn ω_S (the slotted link's ω):
/// n·(a_K − a_b)(C) = 2 ω_S w·(v_K − v_b)(C) with the sign of the pin's side. Hence, in
/// m/s and m/s²,
///
/// ṡ = n·(v_K − v_G)(C) / (n·u),
/// s̈ = [n·(a_K − a_G)(C) − 2 ω_G ṡ (w·u) − 2 ω_S w·(v_K − v_b)(C)] / (n·u),
///
/// n·u = −(u × w). Every term of a ground G or K folds away (the Scotch yoke:
/// ṡ = n·v_C/(n·u), s̈ = n·a_C/(n·u)).
///
/// [`Solver::SlottedSlider`]: crate::kernel::dyad::Solver::SlottedSlider
#[inline(always)]
pub fn slotted_slider_rates(
    gq: &JointGeom,
    gs: &JointGeom,
    s: &mut [LinkState],
    body: usize,
    inv_den: f64,
    upto: Level,
) -> Result<(), MechError> {
    if !matches!(upto, Level::Velocity | Level::Acceleration) {
        return Ok(());
    }
    let (guide, k, u, w) = slider_axes(gq, gs, s, body);
    let n = perp(w);
    let inv_nu = -inv_den;
    let c = point_of(s, gs.b, gs.db);
    let pos = s[body].pos;
    let vk = point_vel(s, k, c);
    let rel = if guide == 0 {
        vk
    } else {
        vk - point_vel(s, guide, c)
    };
    let sd = n.dot(&rel) * inv_nu;
    if guide == 0 {
        s[body].omega = 0.0;
        s[body].vel = u * sd;
    } else {
        let g = s[guide];
        s[body].omega = g.omega;
        s[body].vel = g.vel_at(pos - g.pos) + u * sd;
    }
    if upto != Level::Acceleration {
        return Ok(());
    }
    let ak = point_acc(s, k, c);
    let mut rhs = if guide == 0 {
        n.dot(&ak)
    } else {
        n.dot(&(ak - point_acc(s, guide, c))) - 2.0 * s[guide].omega * sd * w.dot(&u)
    };
    // The slot's turn: that of the body (G's) when the slot is in it, else K's.
    let slotted = if gs.a == body { guide } else { k };
    if slotted != 0 {
        let vb = s[body].vel_at(c - pos);
        rhs -= 2.0 * s[slotted].omega * w.dot(&(vk - vb));
    }
    let sdd = rhs * inv_nu;
    if guide == 0 {
        s[body].alpha = 0.0;
        s[body].acc = u * sdd;
    } else {
        let g = s[guide];
        s[body].alpha = g.alpha;
        s[body].acc = g.acc_at(pos - g.pos) + u * sdd + perp(u) * (2.0 * g.omega * sd);
    }
    Ok(())
}

/// d'Alembert on a [`Solver::SlottedSlider`] group's link: the reactions at its guide `jq`
/// and slot `js` into `out` (by each joint's first link on its second,
/// `docs/conventions.md#reactions`), and their opposites added to the wrenches in `f` of
/// the solved links G and K (`f` holds every link's applied and inertia wrench about its
/// anchor, plus the reactions of the groups solved before). With the body's wrench
/// (F, M about its anchor B), the slot's force S n at the pin C and the guide's force R
/// (⊥ u) and moment M_J about the guide's point J (on the joint's second link):
///
/// along u: F·u + S (n·u) = 0, so S = (F·u)/(u × w) (N);
/// R = −F − S n (N); M_J = −M − (B − J) × F − (C − J) × S n (N·m).
///
/// `Singular` as [`slotted_slider`].
///
/// [`Solver::SlottedSlider`]: crate::kernel::dyad::Solver::SlottedSlider
#[inline(always)]
pub fn slotted_slider_reactions(
    joints: &[JointGeom],
    s: &[LinkState],
    f: &mut [Wrench],
    body: usize,
    jq: usize,
    js: usize,
    out: &mut [Reaction],
) -> Result<(), MechError> {
    let (gq, gs) = (&joints[jq], &joints[js]);
    let (guide, k, u, w) = slider_axes(gq, gs, s, body);
    let den = cross(u, w);
    crate::kernel::linalg::check_condition(2.0, den.abs())?;
    let fb = f[body];
    let force = V2::new(fb.x, fb.y);
    let sn = perp(w) * (force.dot(&u) / den);
    let c = point_of(s, gs.b, gs.db);
    let j = point_of(s, gq.b, gq.db);
    let r = -force - sn;
    let mj = -fb.z - cross(s[body].pos - j, force) - cross(c - j, sn);
    let sigma = if gq.b == body { 1.0 } else { -1.0 };
    out[jq] = Reaction {
        force: r * sigma,
        moment: mj * sigma,
    };
    out[js] = Reaction {
        force: if gs.b == body { sn } else { -sn },
        moment: 0.0,
    };
    f[guide] += Wrench::new(-r.x, -r.y, -mj - cross(j - s[guide].pos, r));
    f[k] += Wrench::new(-sn.x, -sn.y, -cross(c - s[k].pos, sn));
    Ok(())
}

#[cfg(test)]
mod tests {
    //! [`Solver::SlottedSlider`] against the Newton route it replaces: positions by
    //! Newton from the drawing, rates from the group's scaled Jacobian (LU), reactions
    //! from its transpose; and its `Singular` near u ∥ w.
    //!
    //! [`Solver::SlottedSlider`]: crate::kernel::dyad::Solver::SlottedSlider

    use super::*;
    use crate::front::resolve::model_of;
    use crate::kernel::dyad::*;
    use crate::kernel::group::group_solve;
    use crate::kernel::kinematics::{chain_reactions, solve_chain, solve_driven};
    use crate::kernel::kinetostatics::{group_reactions, lambda_reactions};
    use crate::kernel::measure::within;
    use crate::kernel::natural::DyadSystem;
    use crate::plan::assur::{plan, Group, Kernel};
    use crate::solvers::instance::{instance, Instance};

    /// The Scotch yoke of `tests/common/mechanisms.rs`, one with a tilted guide on a
    /// turning arm (the axis in the yoke's frame), and the slider's pin in the crank's
    /// slot, the slider on the ground and on a turning arm.
    const YOKES: [&str; 4] = [
        "pub struct ScotchYoke { ground { O2: (0.0, 0.0) },
          link crank { points { O2, A: (0.03856725658119236, 0.045962666587138684) } },
          link yoke { points { Y: (0.2, 0.0) } },
          joints { O2: revolute(ground, crank), guide: prismatic(ground, yoke) at Y along (1.0, 0.0),
                   slot: pin_in_slot(yoke, crank) at A along (0.0, 1.0) },
          input: O2 }",
        "pub struct Turning { ground { O2: (0.0, 0.0), O4: (0.3, -0.1) },
          link crank { points { O2, A: (0.04, 0.05) } }, link arm { points { O4, Y: (0.2, 0.02) } },
          link yoke { points { C: (0.25, 0.1) } },
          joints { O2: revolute(ground, crank), O4: revolute(ground, arm),
                   guide: prismatic(yoke, arm) at Y along (1.0, -0.2),
                   slot: pin_in_slot(yoke, crank) at A along (0.3, 1.0) },
          inputs: [O2, O4] }",
        "pub struct Mirror { ground { O: (0.0, 0.0) },
          link crank { points { O, T: (0.1, 0.1) } }, link slider { points { S: (0.08, 0.06) } },
          joints { O: revolute(ground, crank), radial: pin_in_slot(crank, slider) at S along (1.0, 0.75),
                   rail: prismatic(ground, slider) at S along (1.0, 0.0) },
          input: O }",
        "pub struct MirrorTurning { ground { O: (0.0, 0.0), O4: (0.25, -0.15) },
          link crank { points { O, T: (0.1, 0.1) } }, link arm { points { O4, E: (0.1, 0.2) } },
          link slider { points { S: (0.08, 0.06) } },
          joints { O: revolute(ground, crank), O4: revolute(ground, arm),
                   radial: pin_in_slot(crank, slider) at S along (1.0, 0.75),
                   rail: prismatic(arm, slider) at S along (1.0, 0.3) },
          inputs: [O, O4] }",
    ];

    /// The inputs' ranges about the drawing (rad) for [`YOKES`]: a full turn of the crank
    /// where the slot keeps its angle to the guide, else short of the crank angles where
    /// the slot runs along the guide (−0.64 rad for `Mirror`, −0.35 rad less the arm's
    /// turn for `MirrorTurning`), where the group is singular.
    const RANGES: [[(f64, f64); 2]; 4] = [
        [(-3.2, 3.2), (0.0, 0.0)],
        [(-3.2, 3.2), (-0.3, 0.3)],
        [(-0.4, 2.2), (0.0, 0.0)],
        [(-0.1, 1.0), (-0.1, 0.1)],
    ];

    /// How [`solve`] takes the slotted-slider group.
    #[derive(Clone, Copy, PartialEq)]
    enum Route {
        /// The plan's kernels (`solve_chain`, `chain_reactions`): its natural coordinate.
        Natural,
        /// Newton from the drawing, rates and reactions from its Jacobian.
        Newton,
        /// The closed-form position, rates and reactions by its chain of joint screws (the
        /// velocity field's route).
        Screw,
    }

    /// A small linear congruential generator: uniform in [0, 1).
    fn uniform(seed: &mut u64) -> f64 {
        *seed = seed
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (*seed >> 11) as f64 / (1u64 << 53) as f64
    }

    /// The states up to accelerations and the reactions of every joint from the same
    /// link wrenches, the slotted-slider group by `route`.
    fn solve(
        inst: &Instance,
        groups: &[Group],
        branches: &[f64],
        drive: crate::kernel::constraints::Drive,
        route: Route,
    ) -> (Vec<LinkState>, Vec<Reaction>) {
        let mut s = inst.drawing.clone();
        for (g, &sign) in groups.iter().zip(branches) {
            match (&g.kernel, route) {
                (Kernel::Driven(d), _) => {
                    solve_driven(
                        g.solver,
                        d,
                        &inst.joints,
                        &mut s,
                        drive,
                        Level::Acceleration,
                    )
                    .unwrap();
                }
                (Kernel::Chain(c), Route::Screw) => {
                    position(g.solver, &inst.joints, &mut s, drive, sign).unwrap();
                    let (sc, acc) = (inst.scale, Level::Acceleration);
                    crate::kernel::screw::chain_rates(c, &inst.joints, &mut s, sc, acc).unwrap();
                }
                (Kernel::Chain(_), Route::Newton) => {
                    group_solve::<3>(
                        &g.bodies,
                        &g.cons,
                        &inst.joints,
                        &mut s,
                        drive,
                        inst.scale,
                        Level::Acceleration,
                    )
                    .unwrap();
                }
                (Kernel::Chain(c), Route::Natural) => {
                    let sc = inst.scale;
                    solve_chain(
                        g.solver,
                        c,
                        &inst.joints,
                        &mut s,
                        drive,
                        sign,
                        sc,
                        Level::Acceleration,
                    )
                    .unwrap();
                }
                _ => unreachable!(),
            }
        }
        let n = inst.links.len();
        let mut f: Vec<Wrench> = (0..n)
            .map(|l| Wrench::new(10.0 - 3.0 * l as f64, 4.0 + l as f64, 0.5 - 0.2 * l as f64))
            .collect();
        let mut out = vec![Reaction::default(); inst.joints.len()];
        let mut drivers = vec![0.0; drive.0.len()];
        for g in groups.iter().rev() {
            match (&g.kernel, route) {
                (Kernel::Driven(d), _) => crate::kernel::screw::driven_reactions(
                    d,
                    &inst.joints,
                    &s,
                    &mut f,
                    &mut out,
                    &mut drivers,
                ),
                (Kernel::Chain(c), Route::Screw) => {
                    let (j, sc) = (&inst.joints, inst.scale);
                    crate::kernel::screw::chain_reactions(c, j, &s, &mut f, sc, &mut out).unwrap();
                }
                (Kernel::Chain(_), Route::Newton) => {
                    let lam = group_reactions::<3>(
                        None,
                        &g.bodies,
                        &g.cons,
                        &inst.joints,
                        &s,
                        &mut f,
                        inst.scale,
                    )
                    .unwrap();
                    lambda_reactions(
                        &g.cons,
                        &inst.joints,
                        &s,
                        lam.as_slice(),
                        &mut out,
                        &mut drivers,
                    );
                }
                (Kernel::Chain(c), Route::Natural) => {
                    let kept = DyadSystem::None;
                    let sc = inst.scale;
                    chain_reactions(g.solver, c, &inst.joints, &s, &mut f, sc, &kept, &mut out)
                        .unwrap();
                }
                _ => unreachable!(),
            }
        }
        (s, out)
    }

    /// |a − b| ≤ tol (|b| + reference), per component.
    #[track_caller]
    fn close(what: &str, a: &[f64], b: &[f64], reference: f64, tol: f64) {
        let size = b.iter().map(|x| x * x).sum::<f64>().sqrt() + reference;
        for (x, y) in a.iter().zip(b) {
            assert!(within((x - y).abs() / size, tol), "{what}: {x} vs {y}");
        }
    }

    #[test]
    fn slotted_slider_matches_newton() {
        let mut seed = 7;
        for (text, ranges) in YOKES.iter().zip(RANGES) {
            let model = model_of(text);
            let inst = instance(&model).unwrap();
            let groups = plan(&model).unwrap();
            let slider = groups
                .iter()
                .filter(|g| matches!(g.solver, Solver::SlottedSlider { .. }))
                .count();
            assert_eq!(slider, 1, "{text}: {groups:?}");
            let solvers: Vec<_> = groups.iter().map(|g| g.solver).collect();
            let branches = inst.branches(&solvers);
            let n_in = model.inputs.len();
            let l = inst.scale;
            for _ in 0..200 {
                let q: Vec<f64> = (0..n_in)
                    .map(|i| {
                        let (lo, hi) = ranges[i];
                        inst.joints[model.inputs[i]].q_ref + lo + (hi - lo) * uniform(&mut seed)
                    })
                    .collect();
                let qd: Vec<f64> = (0..n_in)
                    .map(|_| 20.0 * uniform(&mut seed) - 10.0)
                    .collect();
                let qdd: Vec<f64> = (0..n_in)
                    .map(|_| 200.0 * uniform(&mut seed) - 100.0)
                    .collect();
                let drive = (&q[..], &qd[..], &qdd[..]);
                let (sa, ra) = solve(&inst, &groups, &branches, drive, Route::Natural);
                let (sb, rb) = solve(&inst, &groups, &branches, drive, Route::Newton);
                let (sc, rc) = solve(&inst, &groups, &branches, drive, Route::Screw);
                let w = qd.iter().map(|x| x.abs()).fold(0.0, f64::max);
                let a = qdd.iter().map(|x| x.abs()).fold(0.0, f64::max) + w * w;
                for (x, y) in sa.iter().zip(&sb) {
                    let pose = |s: &LinkState| [s.pos.x, s.pos.y, s.rot.x * l, s.rot.y * l];
                    // measured worst 1.5e-16 (yoke); 100×
                    close("position", &pose(x), &pose(y), l, 1.5e-14);
                    let vel = |s: &LinkState| [s.vel.x, s.vel.y, s.omega * l];
                    // measured worst 3.8e-16 (yoke); 100×
                    close("velocity", &vel(x), &vel(y), l * w, 3e-14);
                    let acc = |s: &LinkState| [s.acc.x, s.acc.y, s.alpha * l];
                    // measured worst 8.2e-16 (yoke); 100×
                    close("acceleration", &acc(x), &acc(y), l * a, 8e-14);
                }
                for (x, y) in ra.iter().zip(&rb) {
                    let r = |r: &Reaction| [r.force.x, r.force.y, r.moment / l];
                    // measured worst 4.6e-16 (yoke); 100×
                    close("reaction", &r(x), &r(y), 1.0, 4e-14);
                }
                // The velocity field's route (joint screws) agrees with both.
                for (x, y) in sc.iter().zip(&sb) {
                    let vel = |s: &LinkState| [s.vel.x, s.vel.y, s.omega * l];
                    // measured worst 3.8e-16 (yoke); 100×
                    close("screw velocity", &vel(x), &vel(y), l * w, 3e-14);
                    let acc = |s: &LinkState| [s.acc.x, s.acc.y, s.alpha * l];
                    // measured worst 8.2e-16 (yoke); 100×
                    close("screw acceleration", &acc(x), &acc(y), l * a, 8e-14);
                }
                for (x, y) in rc.iter().zip(&rb) {
                    let r = |r: &Reaction| [r.force.x, r.force.y, r.moment / l];
                    // measured worst 1.8e-15 (yoke); 100×
                    close("screw reaction", &r(x), &r(y), 1.0, 1.5e-13);
                }
            }
        }
    }

    #[test]
    fn slotted_slider_is_singular_when_the_slot_runs_along_the_guide() {
        let model = model_of(YOKES[0]);
        let inst = instance(&model).unwrap();
        let groups = plan(&model).unwrap();
        let Solver::SlottedSlider { body, jq, js } = groups[1].solver else {
            panic!("{:?}", groups[1].solver)
        };
        // The guide runs along x: the slot turned to the angle t from it has
        // |u × w| = |sin t|, κ_F = 2/|sin t|, Singular from |sin t| ≤ 2e-6 on.
        for (t, singular) in [
            (0.0, true),
            (1e-6, true),
            (-1.9e-6, true),
            (2.1e-6, false),
            (0.3, false),
        ] {
            let mut joints = inst.joints.clone();
            joints[js].axis = V2::new(f64::cos(t), f64::sin(t));
            let mut s = inst.drawing.clone();
            match slotted_slider(&joints[jq], &joints[js], &mut s, body) {
                Err(MechError::Singular { condition }) => {
                    assert!(singular, "t {t}: condition {condition}");
                    assert!(condition >= 1e6, "t {t}: condition {condition}");
                }
                Ok(inv) => {
                    assert!(!singular, "t {t}: assembled");
                    assert!(inv.is_finite() && s[body].pos.iter().all(|c| c.is_finite()));
                }
                Err(e) => panic!("t {t}: {e:?}"),
            }
        }
    }
}
