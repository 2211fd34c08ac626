//! The cam pair: a cam pinned to a carrier drives a follower sliding on it (a translating
//! follower) or turning about its pivot (a rocker) — the kernel the generated solvers and
//! the run-time `Mechanism` call to place the follower ([`solve_cam`]) and to find the
//! contact force ([`cam_reactions`]).

use crate::elements::cam::profile::Profile;
use crate::kernel::constraints::{JointGeom, Level};
use crate::kernel::kinetostatics::{Reaction, Wrench};
use crate::kernel::link_state::{cross, perp, point_of, rotate, LinkState, V2};
use crate::MechError;

/// A cam pair's geometry in its links' frames (`docs/conventions.md#cams`).
#[derive(Clone, Debug, PartialEq)]
pub struct CamGeom {
    /// The profile: law, base circle, the follower (offset e, or a rocker's pivot), face.
    pub profile: Profile,
    /// The profile's axis frame: its unit +y (û) in the carrier's frame — a translating
    /// follower's axis, from the cam's centre towards the follower; for a rocker, from
    /// the cam's centre towards the pitch point of the drawing. x̂ = (û_y, −û_x).
    pub axis: V2,
    /// The cam's centre: its local vector in the cam.
    pub centre: V2,
}

/// The group of a follower driven by a cam ([`solve_cam`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct CamGroup {
    /// The follower.
    pub follower: usize,
    /// Its joint on the carrier: a prismatic joint (translating) or its pin (a rocker).
    pub slide: usize,
    /// The cam joint.
    pub joint: usize,
    /// The cam.
    pub cam: usize,
    /// The carrier.
    pub carrier: usize,
    /// Index into the mechanism's cams.
    pub index: usize,
    /// The cam's [`LinkState::angle`] is exact over turns (a cam driven from the ground):
    /// its turn θ is read from it instead of an `atan2` of its rotation.
    pub cam_tracked: bool,
    /// The carrier's angle is exact over turns (the ground, or a tracked driven link).
    pub carrier_tracked: bool,
}

impl CamGroup {
    /// The cam's turn θ relative to the carrier since the drawing, its rate and
    /// acceleration; the carrier's rotation, ω, α. θ is the difference of the two links'
    /// tracked angles when both are tracked (exact over turns, no `atan2`), else the angle
    /// of the relative rotation, in (−π, π].
    #[inline(always)]
    fn turn(&self, s: &[LinkState]) -> ([f64; 3], V2, f64, f64) {
        let (rc, wc, ac) = if self.carrier == 0 {
            (V2::new(1.0, 0.0), 0.0, 0.0)
        } else {
            let c = &s[self.carrier];
            (c.rot, c.omega, c.alpha)
        };
        let k = &s[self.cam];
        let theta = if self.cam_tracked && self.carrier_tracked {
            if self.carrier == 0 {
                k.angle
            } else {
                k.angle - s[self.carrier].angle
            }
        } else {
            let rel = V2::new(rc.dot(&k.rot), cross(rc, k.rot));
            rel.y.atan2(rel.x)
        };
        ([theta, k.omega - wc, k.alpha - ac], rc, wc, ac)
    }

    /// The follower's frame: û (world), the carrier's point of the follower's joint (the
    /// slide's start, or the rocker's pivot), the follower's local vector of that point.
    #[inline(always)]
    fn frame(&self, g: &JointGeom, geom: &CamGeom, s: &[LinkState], rc: V2) -> (V2, V2, V2) {
        let u = rotate(rc, geom.axis);
        let (q, df) = if g.a == self.carrier {
            (point_of(s, g.a, g.da), g.db)
        } else {
            (point_of(s, g.b, g.db), g.da)
        };
        (u, q, df)
    }
}

/// The law's (s, s′, s″, s‴) at the cam's turn, as [`solve_cam`] evaluated it: what a
/// motion keeps of a cam group, so that [`cam_reactions`] finds the contact without
/// evaluating the law again.
pub type CamLaw = [f64; 4];

/// Solve a cam-driven follower up to `upto` from the cam's turn θ relative to the carrier
/// (the law is periodic: any θ is taken modulo the turn). Translating: its slide along û
/// is s(θ), ṡ = s′ θ̇, s̈ = s″ θ̇² + s′ θ̈. A rocker turns about its pivot by σψ(θ)
/// relative to the carrier: ω = ω_c + σψ′ θ̇, α = α_c + σ(ψ″ θ̇² + ψ′ θ̈). Returns the
/// law's values at θ ([`CamLaw`]).
#[cfg_attr(debug_assertions, inline)]
#[cfg_attr(not(debug_assertions), inline(always))]
pub fn solve_cam(
    grp: &CamGroup,
    cams: &[CamGeom],
    joints: &[JointGeom],
    s: &mut [LinkState],
    upto: Level,
) -> Result<CamLaw, MechError> {
    let geom = &cams[grp.index];
    let g = &joints[grp.slide];
    let (th, rc, wc, ac) = grp.turn(s);
    let law = geom.profile.law.eval(th[0]);
    let [x, x1, x2, _] = law;
    let (u, q, df) = grp.frame(g, geom, s, rc);
    let fl = grp.follower;
    let carrier_angle = if grp.carrier == 0 {
        0.0
    } else {
        s[grp.carrier].angle
    };
    // The follower's point p (on its axis, or its pivot) and the rotation it turns by.
    let (p, turn, rate, accel) = match geom.profile.rocker {
        None => (q + u * x, 0.0, 0.0, 0.0),
        Some(k) => (
            q,
            k.sign * x,
            k.sign * x1 * th[1],
            k.sign * (x2 * th[1] * th[1] + x1 * th[2]),
        ),
    };
    let rot = if turn == 0.0 {
        rc
    } else {
        let (sn, cs) = turn.sin_cos();
        rotate(rc, V2::new(cs, sn))
    };
    s[fl].rot = rot;
    s[fl].angle = carrier_angle + turn;
    s[fl].pos = p - rotate(rot, df);
    if upto == Level::Position {
        return Ok(law);
    }
    let (vq, aq) = if grp.carrier == 0 {
        (V2::zeros(), V2::zeros())
    } else {
        let c = &s[grp.carrier];
        (c.vel_at(p - c.pos), c.acc_at(p - c.pos))
    };
    if geom.profile.rocker.is_some() {
        s[fl].set_velocity_through(p, vq, wc + rate);
        if upto == Level::Acceleration {
            s[fl].set_acceleration_through(p, aq, ac + accel);
        }
        return Ok(law);
    }
    let xd = x1 * th[1];
    s[fl].set_velocity_through(p, vq + u * xd, wc);
    if upto == Level::Acceleration {
        let xdd = x2 * th[1] * th[1] + x1 * th[2];
        s[fl].set_acceleration_through(p, aq + perp(u) * (2.0 * wc * xd) + u * xdd, ac);
    }
    Ok(law)
}

/// d'Alembert for a cam-driven follower: the contact force F_n n at the contact point K
/// from the follower's balance — along its axis for a translating follower,
/// F_n = −(F·û)/(n·û) (the slide takes the rest: a force normal to û and a moment); about
/// its pivot A for a rocker, F_n = −M_A/((K − A) × n) (the pin takes the rest). `out[joint]`
/// holds the force by the cam on the follower and, as its `moment`, F_n (N, > 0 while the
/// cam pushes: a negative value is the follower leaving the cam, a jump). `law`: the
/// law's values the motion kept ([`solve_cam`]'s), else the law is evaluated again.
#[cfg_attr(debug_assertions, inline)]
#[cfg_attr(not(debug_assertions), inline(always))]
#[allow(clippy::too_many_arguments)]
pub fn cam_reactions(
    grp: &CamGroup,
    cams: &[CamGeom],
    joints: &[JointGeom],
    s: &[LinkState],
    law: Option<&CamLaw>,
    f: &mut [Wrench],
    out: &mut [Reaction],
) -> Result<(), MechError> {
    let geom = &cams[grp.index];
    let g = &joints[grp.slide];
    let (th, rc, _, _) = grp.turn(s);
    let (u, _, df) = grp.frame(g, geom, s, rc);
    let xh = V2::new(u.y, -u.x);
    let o = point_of(s, grp.cam, geom.centre);
    let law = match law {
        Some(l) => *l,
        None => geom.profile.law.eval(th[0]),
    };
    let (kc, nc) = geom.profile.contact_normal_of(th[0], law);
    let kw = o + xh * kc.x + u * kc.y;
    let nw = xh * nc.x + u * nc.y;
    let fl = grp.follower;
    let wf = f[fl];
    let ff = V2::new(wf.x, wf.y);
    let p = s[fl].point(df);
    // The follower's moment about p of everything but the cam and its joint.
    let mf = wf.z + cross(s[fl].pos - p, ff);
    let (fnorm, lever) = if geom.profile.rocker.is_some() {
        let arm = kw - p;
        let lever = cross(arm, nw);
        (-mf / lever, lever / arm.norm())
    } else {
        let nu = nw.dot(&u);
        (-ff.dot(&u) / nu, nu)
    };
    if !(lever.abs() >= 1e-12 && fnorm.is_finite()) {
        return Err(MechError::Singular {
            condition: f64::INFINITY,
        });
    }
    let force = nw * fnorm;
    let r = -(ff + force);
    let mp = if geom.profile.rocker.is_some() {
        0.0
    } else {
        -(mf + cross(kw - p, force))
    };
    out[grp.joint] = Reaction {
        force,
        moment: fnorm,
    };
    out[grp.slide] = if g.b == fl {
        Reaction {
            force: r,
            moment: mp,
        }
    } else {
        Reaction {
            force: -r,
            moment: -mp,
        }
    };
    let push = |f: &mut [Wrench], l: usize, at: V2, force: V2, couple: f64| {
        let pos = if l == 0 { V2::zeros() } else { s[l].pos };
        f[l] += Wrench::new(force.x, force.y, couple + cross(at - pos, force));
    };
    push(f, grp.cam, kw, -force, 0.0);
    push(f, grp.carrier, p, -r, -mp);
    Ok(())
}
