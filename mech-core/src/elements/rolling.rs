//! A wheel rolling without slipping on a straight line or a circle of a track (`docs/theory.md` §12,
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
//! or the circle–line closed form of a crank–rod–wheel dyad, [`crate::kernel::natural`]).
//!
//! **A circular track** (`around D`, centred at the track's point D): C stays at the
//! drawing's distance ρ = |C − D| from D, the contact K = C − r n on the line of centres
//! (n, the contact normal towards the wheel: (C − D)/ρ outside, (D − C)/ρ inside); with ψ
//! the turn of C about D relative to the track since the drawing, the wheel turns
//! φ_w − φ_t = k ψ, k = ±ρ/r (+ outside, − inside). A crank–rod–wheel is then an RRR
//! dyad whose second link is the virtual one from D to C; the driven form is not offered.
//!
//! **Reactions.** The track acts on the wheel at K with a normal force N (along the
//! contact normal n, perp(u) on a straight track) and a friction force F (along
//! u = −perp(n)). The wheel's moment about C fixes F:
//! M_w(C) + (K − C) × F u = M_w(C) + r F = 0, F = −M_w(C)/r; the rest is a slider's
//! balance.

use crate::kernel::constraints::{Drive, JointGeom, Level};
use crate::kernel::kinetostatics::{Reaction, Wrench};
use crate::kernel::link_state::{cross, dir_of, perp, point_of, rotate, LinkState, V2};
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
/// rotation less s/r and place it by its centre. On a track of the ground its turn since
/// the drawing, −s/r, is exact over turns: it is kept as the wheel's
/// [`LinkState::angle`] (which its published angle reads, no `atan2`).
#[inline(always)]
fn turn_wheel(g: &JointGeom, s: &mut [LinkState], w: usize, c: V2, dc: V2, travel: f64) {
    let turn = -travel / g.radius;
    let (sn, cs) = turn.sin_cos();
    // On the ground the track's rotation is the identity: no rotation by it.
    let rot = if g.a == 0 {
        s[w].angle = turn;
        V2::new(cs, sn)
    } else {
        rotate(s[g.a].rot, V2::new(cs, sn))
    };
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

/// The contact normal n (towards the wheel) and the track's direction u = −perp(n) at
/// the wheel's centre `c` (module docs).
#[inline(always)]
fn contact_frame(g: &JointGeom, s: &[LinkState], c: V2) -> (V2, V2) {
    if g.around == 0.0 {
        let u = dir_of(s, g.a, g.axis);
        (perp(u), u)
    } else {
        let d = point_of(s, g.a, g.da);
        let n = (c - d) * (g.around / (c - d).norm());
        (n, -perp(n))
    }
}

/// The rod's local vectors of A (its pin `ja`) and of C (the pin `jc`), and the wheel's of C.
#[inline(always)]
fn rod_points(joints: &[JointGeom], b1: usize, ja: usize, jc: usize) -> (V2, V2, V2) {
    let (gj, gc) = (&joints[ja], &joints[jc]);
    let da = if gj.a == b1 { gj.da } else { gj.db };
    let (dc1, dc2) = if gc.a == b1 {
        (gc.da, gc.db)
    } else {
        (gc.db, gc.da)
    };
    (da, dc1, dc2)
}

/// A crank–rod–wheel around a circle (module docs): C from the circles about A and D, the
/// rod by A and C, the wheel turned k ψ; then the rates from the RRR system of the rod and
/// the virtual link D–C. Returns nothing; `place` as in [`solve_rolling`].
#[allow(clippy::too_many_arguments)]
#[inline(always)]
fn around_dyad(
    joints: &[JointGeom],
    s: &mut [LinkState],
    (b1, b2, ja, jc, jr): (usize, usize, usize, usize, usize),
    sign: f64,
    upto: Level,
    place: bool,
) -> Result<(), MechError> {
    let g = &joints[jr];
    let (da, dc1, dc2) = rod_points(joints, b1, ja, jc);
    let (a, _) = crate::kernel::dyad::pin(&joints[ja], s, b1);
    let d = point_of(s, g.a, g.da);
    let rho = g.axis.norm();
    let k = g.around * rho / g.radius;
    let (rot_t, w_t, al_t) = if g.a == 0 {
        (V2::new(1.0, 0.0), 0.0, 0.0)
    } else {
        (s[g.a].rot, s[g.a].omega, s[g.a].alpha)
    };
    let c = if place {
        let c =
            crate::kernel::dyad::circle_circle(a, (dc1 - da).norm_squared(), d, rho * rho, sign)?;
        crate::kernel::dyad::place_by_two_points(&mut s[b1], da, dc1, a, c);
        // On the ground the track's rotation is the identity: no rotation by it.
        let turned = |v: V2| if g.a == 0 { v } else { rotate(rot_t, v) };
        let d0 = turned(g.axis);
        let psi = cross(d0, c - d).atan2(d0.dot(&(c - d)));
        let (sn, cs) = (k * psi).sin_cos();
        let rot = turned(V2::new(cs, sn));
        s[b2].rot = rot;
        s[b2].pos = c - rotate(rot, dc2);
        c
    } else {
        s[b1].point(dc1)
    };
    if upto == Level::Position {
        return Ok(());
    }
    let (e1, e2) = (c - a, c - d);
    let m = crate::kernel::linalg::Inverse2::new([[-e1.y, e2.y], [e1.x, -e2.x]])?;
    let rates = |s: &[LinkState], l: usize, p: V2| {
        if l == 0 {
            (V2::zeros(), V2::zeros())
        } else {
            let r = p - s[l].pos;
            (s[l].vel_at(r), s[l].acc_at(r))
        }
    };
    let ga = &joints[ja];
    let la = if ga.a == b1 { ga.b } else { ga.a };
    let ((va, aa), (vd, ad)) = (rates(s, la, a), rates(s, g.a, d));
    let dv = vd - va;
    let [w1, wv] = m.solve([dv.x, dv.y]);
    s[b1].set_velocity_through(a, va, w1);
    let vc = va + perp(e1) * w1;
    s[b2].set_velocity_through(c, vc, w_t + k * (wv - w_t));
    if upto == Level::Acceleration {
        let rhs = ad - aa + e1 * (w1 * w1) - e2 * (wv * wv);
        let [al1, alv] = m.solve([rhs.x, rhs.y]);
        s[b1].set_acceleration_through(a, aa, al1);
        let ac = aa + perp(e1) * al1 - e1 * (w1 * w1);
        s[b2].set_acceleration_through(c, ac, al_t + k * (alv - al_t));
    }
    Ok(())
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
        RollingGroup::Dyad { b1, b2, ja, jc, jr } if joints[jr].around != 0.0 => {
            around_dyad(joints, s, (b1, b2, ja, jc, jr), sign, upto, place)?;
        }
        RollingGroup::Dyad { b1, b2, ja, jc, jr } => {
            let rrp = crate::kernel::dyad::Solver::Rrp {
                b1,
                b2,
                ja,
                jc,
                jp: jr,
            };
            let g = &joints[jr];
            let points = if place {
                let points = crate::kernel::dyad::position(rrp, joints, s, drive, sign)?;
                let (_, _, x) = travel(g, s, points[1]);
                turn_wheel(g, s, b2, points[1], g.db, x);
                points
            } else {
                let (gj, gc) = (&joints[ja], &joints[jc]);
                let a = s[b1].point(if gj.a == b1 { gj.da } else { gj.db });
                let c = s[b1].point(if gc.a == b1 { gc.da } else { gc.db });
                let u =
                    crate::kernel::link_state::dir_of(s, if g.b == b2 { g.a } else { g.b }, g.axis);
                [
                    a,
                    c,
                    V2::new((c - a).dot(&u), crate::kernel::link_state::cross(u, c - a)),
                ]
            };
            let c = points[1];
            if upto == Level::Position {
                return Ok(());
            }
            // The rod and the centre as an RRP dyad's, then the wheel's spin.
            crate::kernel::natural::rrp_rates(joints, s, b1, b2, ja, jc, jr, points, scale, upto)?;
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
    let (n, u) = contact_frame(g, s, c);
    let k = c - n * g.radius;
    let fw = f[w];
    let mc = fw.z + cross(s[w].pos - c, V2::new(fw.x, fw.y));
    let ft = u * (-mc / g.radius);
    f[w] += Wrench::new(ft.x, ft.y, cross(k - s[w].pos, ft));
    (ft, k, c)
}

/// d'Alembert for a rolling group: the contact force (normal and friction, by the track
/// on the wheel at the contact point) into `out[joint]`, a driven wheel's motor action
/// (the force along u at its centre) into `drivers`, the other reactions as a slider's
/// (dyad: [`crate::kernel::natural::rrp_reactions`]), and their opposites on the solved links.
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
        RollingGroup::Dyad { b1, b2, ja, jc, jr } if joints[jr].around != 0.0 => {
            // X, the rod's force on the wheel at C: the rod's moment about A, and the
            // wheel's balance along u (the normal takes the rest): [perp(e₁); u] X =
            // (M₁(A), −u·F₂); then the contact force −X − F₂ (friction included in F₂).
            let g = &joints[jr];
            let f2_before = f[b2];
            let (_, k, c) = friction(g, s, f, b2);
            let (n, u) = contact_frame(g, s, c);
            let _ = n;
            let (da, _, _) = rod_points(joints, b1, ja, jc);
            let a = s[b1].point(da);
            let e1 = c - a;
            let w1 = f[b1];
            let f1 = V2::new(w1.x, w1.y);
            let m1 = w1.z + cross(s[b1].pos - a, f1);
            let w2 = f[b2];
            let f2 = V2::new(w2.x, w2.y);
            let m = crate::kernel::linalg::Inverse2::new([[-e1.y, e1.x], [u.x, u.y]])?;
            let [x, y] = m.solve([m1, -u.dot(&f2)]);
            let x = V2::new(x, y);
            let contact = -x - V2::new(f2_before.x, f2_before.y);
            let ra = x - f1;
            let (ga, gc) = (&joints[ja], &joints[jc]);
            let la = if ga.a == b1 { ga.b } else { ga.a };
            out[ja] = if ga.b == b1 {
                Reaction {
                    force: ra,
                    moment: 0.0,
                }
            } else {
                Reaction {
                    force: -ra,
                    moment: 0.0,
                }
            };
            out[jc] = if gc.b == b2 {
                Reaction {
                    force: x,
                    moment: 0.0,
                }
            } else {
                Reaction {
                    force: -x,
                    moment: 0.0,
                }
            };
            out[jr] = Reaction {
                force: contact,
                moment: 0.0,
            };
            push(f, la, a, -ra);
            push(f, g.a, k, -contact);
        }
        RollingGroup::Dyad { b1, b2, ja, jc, jr } => {
            let g = &joints[jr];
            let (ft, k, c) = friction(g, s, f, b2);
            crate::kernel::natural::rrp_reactions(
                joints,
                s,
                f,
                b1,
                b2,
                ja,
                jc,
                jr,
                scale,
                &crate::kernel::natural::DyadSystem::None,
                out,
            )?;
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
pub fn report(
    g: &JointGeom,
    s: &[LinkState],
    force: V2,
) -> crate::kernel::kinetostatics::RollingReaction {
    let (n, u) = contact_frame(g, s, s[g.b].point(g.db));
    crate::kernel::kinetostatics::RollingReaction {
        force,
        normal: force.dot(&n),
        friction: force.dot(&u),
    }
}
