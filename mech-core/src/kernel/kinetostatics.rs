//! Kinetostatics (`docs/theory.md` §4, §5): the motor actions and every joint reaction by
//! d'Alembert, group by group from the outermost Assur group inward, and the motor
//! actions alone by virtual power.
//!
//! Forces on a link are kept as generalised forces (F_x, F_y, M) with the moment about
//! the link's anchor. The multipliers λ of a group's constraints solve Jᵀ λ = −f, f the
//! sum of the applied, gravity and inertia forces on the group's links and the
//! reactions of the groups solved before (outer groups); with the signs of
//! [`crate::kernel::kinematics`], λ is the action BY joint link a ON link b.

use crate::kernel::constraints::{eval, Con, ConKind, JointGeom, Level};
use crate::kernel::group::GroupSystem;
use crate::kernel::link_state::{cross, perp, LinkGeom, LinkMotion, LinkState, V2};
use crate::MechError;
use nalgebra::{SVector, Vector3};

/// A generalised force on a link: (F_x, F_y, M about the anchor), N and N·m.
pub type Wrench = Vector3<f64>;

/// The start of a sum of wrenches (N, N·m): (−0, −0, −0), the identity of IEEE addition
/// (−0 + x = x for every x, where 0 + x is not x when x = −0), so that a link's first term
/// is taken as it is and the compiler drops the addition.
#[inline(always)]
pub fn wrench_sum() -> Wrench {
    Wrench::new(-0.0, -0.0, -0.0)
}

/// Add a force `force` (N) at the offset `r` (m) from the link's anchor: (F, r × F).
#[inline(always)]
fn add_force_arm(w: &mut Wrench, r: V2, force: V2) {
    *w += Vector3::new(force.x, force.y, cross(r, force));
}

/// Add a force `force` (N) applied at the material point of local vector `d`.
#[inline(always)]
pub fn add_force(w: &mut Wrench, s: &LinkState, d: V2, force: V2) {
    add_force_arm(w, s.r(d), force);
}

/// Add a force `force` (N) applied at the point now at `p` (m) of the link anchored at
/// `anchor`: r = p − anchor.
#[inline(always)]
pub fn add_force_at(w: &mut Wrench, anchor: V2, p: V2, force: V2) {
    add_force_arm(w, p - anchor, force);
}

/// Add a pure torque (N·m, CCW).
#[inline(always)]
pub fn add_torque(w: &mut Wrench, torque: f64) {
    w.z += torque;
}

/// Add gravity m·g at the cg.
#[inline(always)]
pub fn add_gravity(w: &mut Wrench, s: &LinkState, l: &LinkGeom, g: V2) {
    add_force(w, s, l.dcg, g * l.mass);
}

/// Add gravity m·g at the cg of the link motion `m` (its anchor at `anchor`).
#[inline(always)]
pub fn add_gravity_of(w: &mut Wrench, anchor: V2, m: &LinkMotion, l: &LinkGeom, g: V2) {
    add_force_at(w, anchor, m.cg, g * l.mass);
}

/// Add d'Alembert's inertia wrench of a link whose cg is at the offset `r` (m) from its
/// anchor and accelerates at `acc` (m/s²), the link at α (rad/s²): the force −m·a_G at
/// the cg and the moment −I_G·α.
#[inline(always)]
fn add_inertia_arm(w: &mut Wrench, r: V2, acc: V2, alpha: f64, l: &LinkGeom) {
    let force = -acc * l.mass;
    *w += Vector3::new(force.x, force.y, cross(r, force) - l.inertia * alpha);
}

/// Add d'Alembert's inertia force −m·a_G at the cg and inertia moment −I_G·α.
#[inline(always)]
pub fn add_inertia(w: &mut Wrench, s: &LinkState, l: &LinkGeom) {
    let r = s.r(l.dcg);
    add_inertia_arm(w, r, s.acc_at(r), s.alpha, l);
}

/// [`add_inertia`] from the link motion `m` (its anchor at `anchor`), whose cg and cg
/// acceleration are already known: nothing is rotated again.
#[inline(always)]
pub fn add_inertia_of(w: &mut Wrench, anchor: V2, m: &LinkMotion, l: &LinkGeom) {
    add_inertia_arm(w, m.cg - anchor, m.cg_acc, m.alpha, l);
}

/// The multipliers of one group (row order of its constraints): solve Jᵀ λ = −f for
/// the group's links, then pass each constraint's reaction on to the solved links it
/// touches (`f[other] += rowᵀ λ`). Called from the outermost group inward. `sys` is the
/// group's factored system from the kinematics, if kept; else it is rebuilt.
#[inline]
pub fn group_reactions<const N: usize>(
    sys: Option<&GroupSystem<N>>,
    bodies: &[usize],
    cons: &[Con],
    joints: &[JointGeom],
    s: &[LinkState],
    f: &mut [Wrench],
    scale: f64,
) -> Result<SVector<f64, N>, MechError> {
    let sys = match sys {
        Some(sys) => *sys,
        None => GroupSystem::<N>::new(bodies, cons, joints, s, scale)?,
    };
    let mut rhs = SVector::<f64, N>::zeros();
    for (k, &b) in bodies.iter().enumerate() {
        rhs.fixed_rows_mut::<3>(3 * k).copy_from(&(-f[b]));
    }
    let lam = sys.solve_transpose(&rhs);
    let none: &[f64] = &[];
    let mut row = 0;
    for c in cons {
        let g = &joints[c.joint];
        let e = eval(*c, g, s, (none, none, none), Level::Jacobian);
        for k in 0..c.kind.rows() {
            for (link, r) in [(g.a, e.rows[k].a), (g.b, e.rows[k].b)] {
                if !bodies.contains(&link) {
                    f[link] += r * lam[row];
                }
            }
            row += 1;
        }
    }
    Ok(lam)
}

/// The reaction force (N, global) of a sliding joint from its normal multiplier.
#[inline]
pub fn slide_force(g: &JointGeom, s: &[LinkState], lambda: f64) -> V2 {
    perp(s[g.a].r(g.axis)) * lambda
}

/// Virtual power of the applied and inertia wrenches `f` in the velocity field of `s`:
/// Σ (F·v_anchor + M·ω) (W per unit input rate). The motor action of the input that
/// moves alone in `s` at unit rate is minus this.
#[inline]
pub fn virtual_power(f: &[Wrench], s: &[LinkState]) -> f64 {
    f.iter()
        .zip(s)
        .map(|(w, st)| w.x * st.vel.x + w.y * st.vel.y + w.z * st.omega)
        .sum()
}

/// The reaction at one joint as the kernels produce it: the force BY a ON b (N, global)
/// and the moment on b about the joint's current point (N·m, CCW; zero but for a
/// prismatic joint). The generated `Forces` copy it into the joint's own reaction type.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Reaction {
    /// Force by a on b, N.
    pub force: V2,
    /// Moment by a on b about the joint point, N·m.
    pub moment: f64,
}

/// The reactions of a group solved through its multipliers λ (row order of `cons`, from
/// [`group_reactions`]): each joint's into `out`, each driver row's motor action into
/// `drivers` (by a on b: torque, or axial force).
#[inline]
pub fn lambda_reactions(
    cons: &[Con],
    joints: &[JointGeom],
    s: &[LinkState],
    lam: &[f64],
    out: &mut [Reaction],
    drivers: &mut [f64],
) {
    let mut row = 0;
    for c in cons {
        let g = &joints[c.joint];
        match c.kind {
            ConKind::Revolute => {
                out[c.joint] = Reaction {
                    force: V2::new(lam[row], lam[row + 1]),
                    moment: 0.0,
                }
            }
            ConKind::Prismatic => {
                out[c.joint] = Reaction {
                    force: slide_force(g, s, lam[row]),
                    moment: lam[row + 1],
                }
            }
            ConKind::Slot => {
                out[c.joint] = Reaction {
                    force: slide_force(g, s, lam[row]),
                    moment: 0.0,
                }
            }
            ConKind::DriveRevolute(k) | ConKind::DrivePrismatic(k) => drivers[k] = lam[row],
            ConKind::Rolling => {
                out[c.joint] = Reaction {
                    force: V2::new(lam[row], lam[row + 1]),
                    moment: 0.0,
                }
            }
            // A mesh's tangential force (meshing links are solved by `crate::elements::gears`).
            ConKind::Mesh => {
                out[c.joint] = Reaction {
                    force: g.axis * lam[row],
                    moment: 0.0,
                }
            }
        }
        row += c.kind.rows();
    }
}

/// Reaction at a revolute joint: the force BY a ON b (N, global).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct RevoluteReaction {
    /// Force by a on b, N.
    pub force: V2,
}

/// Reaction at a gear pair or rack (`crate::elements::gears`): the tooth force BY a ON b at the
/// pitch point, along the line of action (N, global).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct MeshReaction {
    /// The tooth force by a on b, N.
    pub force: V2,
    /// Its magnitude, N (≥ 0).
    pub tooth_load: f64,
    /// The flank in contact: +1 when the force on b pushes along the common tangent t
    /// (gear pair: t = perp of the line of centres from a's centre to b's, the
    /// counter-clockwise tangent of a at the pitch point; rack: the rack's axis), −1 when
    /// against it.
    pub flank: f64,
}

/// Reaction at a rolling joint (`crate::elements::rolling`): the contact force BY the track ON the
/// wheel at the contact point (N, global), and its parts: `normal` along perp(u) (> 0 while
/// the track pushes the wheel; < 0 would mean the wheel lifts off), `friction` along u.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct RollingReaction {
    /// The contact force by the track on the wheel, N.
    pub force: V2,
    /// Its normal part, N.
    pub normal: f64,
    /// Its part along the track's direction u (the friction the contact needs), N.
    pub friction: f64,
}

/// Reaction at a cam (`crate::elements::cam`): the contact force BY the cam ON the follower (N,
/// global, along the common normal at the contact point) and its signed magnitude
/// `normal_force` (> 0 while the cam pushes; < 0 means the follower would leave the cam:
/// a jump).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct CamReaction {
    /// The contact force by the cam on the follower, N.
    pub force: V2,
    /// F_n, N.
    pub normal_force: f64,
}

/// Reaction at a prismatic joint: the force BY a ON b normal to the axis (N, global) and
/// the moment on b about the joint point's current position (N·m, CCW).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct PrismaticReaction {
    /// Force by a on b, N.
    pub force: V2,
    /// Moment by a on b about the joint point, N·m.
    pub moment: f64,
}

/// Reaction at a pin in a slot: the force BY a ON b, normal to the slot (N, global).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct SlotReaction {
    /// Force by a on b, N.
    pub force: V2,
}
