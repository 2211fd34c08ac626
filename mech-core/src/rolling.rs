//! A wheel rolling without slipping on a straight line of a track (`docs/theory.md` §12,
//! `docs/conventions.md#rolling`). The joint `rolling(track, wheel) at C radius r along u`
//! keeps the wheel's centre C on the line through C (in the drawing) along u, fixed in the
//! track, and the contact point K = C − r perp(u) (the wheel on the left of u) at rest
//! relative to the track: with s the travel of C along u relative to the track since the
//! drawing, the wheel turns φ_w = φ_t − s/r, so
//!
//! ω_w = ω_t − ṡ/r,  α_w = α_t − s̈/r,
//!
//! ṡ = u·(v_C − v_t(C)), s̈ = u·(a_C − a_t(C)) (the Coriolis part of the rolling point's
//! acceleration is normal to u). Positions of C follow as for a slider (a driven travel,
//! or the circle–line closed form of a crank–rod–wheel dyad, [`crate::natural`]).
//!
//! **Reactions.** The track acts on the wheel at K with a normal force N (along
//! n = perp(u)) and a friction force F (along u). The wheel's moment about C fixes F:
//! M_w(C) + (K − C) × F u = M_w(C) + r F = 0, F = −M_w(C)/r; the rest is a slider's
//! balance.

use crate::constraints::{Drive, JointGeom, Level};
use crate::kinetostatics::{Reaction, Wrench};
use crate::link_state::{cross, dir_of, perp, point_of, rotate, LinkState, V2};
use crate::MechError;

/// How a rolling wheel is solved: driven by its travel, or the second link of a
/// crank–rod–wheel dyad (the rod `b1` pinned at A by `ja`, the wheel `b2` pinned to it
/// at its centre by `jc`, rolling by `jr`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum RollingGroup {
    /// The wheel `body`, its travel along the track the input `input` (rolling joint
    /// `joint`).
    Driven {
        /// The wheel.
        body: usize,
        /// The rolling joint.
        joint: usize,
        /// The input index.
        input: usize,
    },
    /// A rod and a wheel (see the type's docs).
    Dyad {
        /// The rod.
        b1: usize,
        /// The wheel.
        b2: usize,
        /// The rod's pin to a solved link.
        ja: usize,
        /// The pin between rod and wheel, at the wheel's centre.
        jc: usize,
        /// The rolling joint.
        jr: usize,
    },
}

/// The track's direction u now, the track's point at the wheel's centre in the drawing,
/// and the travel s (m) of the centre `c` along u.
#[inline(always)]
fn travel(g: &JointGeom, s: &[LinkState], c: V2) -> (V2, V2, f64) {
    let u = dir_of(s, g.a, g.axis);
    let q = point_of(s, g.a, g.da);
    (u, q, u.dot(&(c - q)))
}

/// Turn the wheel `w` (centre `c`, local vector of its centre `dc`) to the track's
/// rotation less s/r and place it by its centre.
#[inline(always)]
fn turn_wheel(g: &JointGeom, s: &mut [LinkState], w: usize, c: V2, dc: V2, travel: f64) {
    let (sn, cs) = (-travel / g.radius).sin_cos();
    let base = if g.a == 0 { V2::new(1.0, 0.0) } else { s[g.a].rot };
    let rot = rotate(base, V2::new(cs, sn));
    s[w].rot = rot;
    s[w].pos = c - rotate(rot, dc);
}

/// The wheel's spin and angular acceleration from its centre's motion (module docs), set
/// through the centre `c` (whose velocity `vc` and acceleration `ac` are known).
#[inline(always)]
fn spin(g: &JointGeom, s: &mut [LinkState], w: usize, c: V2, vc: V2, ac: V2, upto: Level) {
    let u = dir_of(s, g.a, g.axis);
    let (vt, at, wt, alt) = if g.a == 0 {
        (V2::zeros(), V2::zeros(), 0.0, 0.0)
    } else {
        let t = &s[g.a];
        let r = c - t.pos;
        (t.vel_at(r), t.acc_at(r), t.omega, t.alpha)
    };
    let sd = u.dot(&(vc - vt));
    s[w].set_velocity_through(c, vc, wt - sd / g.radius);
    if upto == Level::Acceleration {
        let sdd = u.dot(&(ac - at));
        s[w].set_acceleration_through(c, ac, alt - sdd / g.radius);
    }
}

/// Solve a rolling group up to `upto` (module docs); `sign` is the dyad's branch. With
/// `place` false the positions in `s` are kept and only the rates are solved (a velocity
/// field, whose `drive` holds rates only).
#[cfg_attr(debug_assertions, inline)]
#[cfg_attr(not(debug_assertions), inline(always))]
#[allow(clippy::too_many_arguments)]
pub fn solve_rolling(
    grp: &RollingGroup,
    joints: &[JointGeom],
    s: &mut [LinkState],
    drive: Drive,
    sign: f64,
    scale: f64,
    upto: Level,
    place: bool,
) -> Result<(), MechError> {
    match *grp {
        RollingGroup::Driven { body, joint, input } => {
            let g = &joints[joint];
            let c = if place {
                let (u, q, _) = travel(g, s, V2::zeros());
                let x = drive.0[input] - g.q_ref;
                let c = q + u * x;
                turn_wheel(g, s, body, c, g.db, x);
                c
            } else {
                s[body].point(g.db)
            };
            if upto == Level::Position {
                return Ok(());
            }
            let u = dir_of(s, g.a, g.axis);
            let (vt, at, wt) = if g.a == 0 {
                (V2::zeros(), V2::zeros(), 0.0)
            } else {
                let t = &s[g.a];
                (t.vel_at(c - t.pos), t.acc_at(c - t.pos), t.omega)
            };
            let vc = vt + u * drive.1[input];
            let ac = at + perp(u) * (2.0 * wt * drive.1[input]) + u * drive.2[input];
            spin(g, s, body, c, vc, ac, upto);
        }
        RollingGroup::Dyad { b1, b2, ja, jc, jr } => {
            let rrp = crate::dyad::Solver::Rrp {
                b1,
                b2,
                ja,
                jc,
                jp: jr,
            };
            let g = &joints[jr];
            let points = if place {
                let points = crate::dyad::position(rrp, joints, s, drive, sign)?;
                let (_, _, x) = travel(g, s, points[1]);
                turn_wheel(g, s, b2, points[1], g.db, x);
                points
            } else {
                let (gj, gc) = (&joints[ja], &joints[jc]);
                let a = s[b1].point(if gj.a == b1 { gj.da } else { gj.db });
                let c = s[b1].point(if gc.a == b1 { gc.da } else { gc.db });
                [a, c, V2::zeros()]
            };
            let c = points[1];
            if upto == Level::Position {
                return Ok(());
            }
            // The rod and the centre as an RRP dyad's, then the wheel's spin.
            crate::natural::rrp_rates(joints, s, b1, b2, ja, jr, points, scale, upto)?;
            let r = c - s[b2].pos;
            let (vc, ac) = (s[b2].vel_at(r), s[b2].acc_at(r));
            spin(g, s, b2, c, vc, ac, upto);
        }
    }
    Ok(())
}

/// The contact force of the track on the wheel `w` from the wheel's moment about its
/// centre (module docs): F u at K, F = −M_w(C)/r, added to the wheel's wrench; returns
/// (F u, K, C).
#[inline(always)]
fn friction(g: &JointGeom, s: &[LinkState], f: &mut [Wrench], w: usize) -> (V2, V2, V2) {
    let c = s[w].point(g.db);
    let u = dir_of(s, g.a, g.axis);
    let k = c - perp(u) * g.radius;
    let fw = f[w];
    let mc = fw.z + cross(s[w].pos - c, V2::new(fw.x, fw.y));
    let ft = u * (-mc / g.radius);
    f[w] += Wrench::new(ft.x, ft.y, cross(k - s[w].pos, ft));
    (ft, k, c)
}

/// d'Alembert for a rolling group: the contact force (normal and friction, by the track
/// on the wheel at the contact point) into `out[joint]`, a driven wheel's motor action
/// (the force along u at its centre) into `drivers`, the other reactions as a slider's
/// (dyad: [`crate::natural::rrp_reactions`]), and their opposites on the solved links.
#[cfg_attr(debug_assertions, inline)]
#[cfg_attr(not(debug_assertions), inline(always))]
#[allow(clippy::too_many_arguments)]
pub fn rolling_reactions(
    grp: &RollingGroup,
    joints: &[JointGeom],
    s: &[LinkState],
    f: &mut [Wrench],
    scale: f64,
    out: &mut [Reaction],
    drivers: &mut [f64],
) -> Result<(), MechError> {
    let push = |f: &mut [Wrench], l: usize, p: V2, force: V2| {
        let pos = if l == 0 { V2::zeros() } else { s[l].pos };
        f[l] += Wrench::new(force.x, force.y, cross(p - pos, force));
    };
    match *grp {
        RollingGroup::Driven { body, joint, input } => {
            let g = &joints[joint];
            let (ft, k, c) = friction(g, s, f, body);
            let u = dir_of(s, g.a, g.axis);
            let n = perp(u);
            let fw = f[body];
            let fv = V2::new(fw.x, fw.y);
            // The friction is in fw now: the motor's force along u at C and the normal.
            let q = -fv.dot(&u);
            let normal = n * (-fv.dot(&n));
            drivers[input] = q;
            out[joint] = Reaction {
                force: normal + ft,
                moment: 0.0,
            };
            push(f, g.a, k, -(normal + ft));
            push(f, g.a, c, -u * q);
        }
        RollingGroup::Dyad { b1, b2, ja, jc, jr } => {
            let g = &joints[jr];
            let (ft, k, c) = friction(g, s, f, b2);
            crate::natural::rrp_reactions(joints, s, f, b1, b2, ja, jc, jr, scale, out)?;
            // The slider's guide reaction is the normal force, through C (on the normal
            // through K); the friction acts at K.
            let normal = out[jr].force;
            out[jr] = Reaction {
                force: normal + ft,
                moment: 0.0,
            };
            let _ = c;
            push(f, g.a, k, -ft);
        }
    }
    Ok(())
}

/// A rolling joint's reaction as reported: the contact force by the track on the wheel
/// and its normal (along perp(u), > 0 when the track pushes the wheel) and friction
/// (along u) parts, N.
#[inline]
pub fn report(g: &JointGeom, s: &[LinkState], force: V2) -> crate::kinetostatics::RollingReaction {
    let u = dir_of(s, g.a, g.axis);
    crate::kinetostatics::RollingReaction {
        force,
        normal: force.dot(&perp(u)),
        friction: force.dot(&u),
    }
}
