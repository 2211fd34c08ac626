//! Gear pairs and racks (`docs/theory.md` §11, `docs/conventions.md#gears`): the pitch
//! circles (a circle and the rack's pitch line) roll on each other without slipping.
//!
//! **Kinematics (Willis).** Relative to the carrier c, the link that holds both centres,
//! a gear pair with pitch radii r_a, r_b keeps r_a (φ_a − φ_c) + σ r_b (φ_b − φ_c) = 0
//! (σ = +1 external, −1 internal), φ the rotations since the drawing; a rack sliding s
//! (along its axis u, relative to the carrier, since the drawing) on a pinion of radius r
//! keeps s + κ r (φ_a − φ_c) = 0, κ = ±1 the side of the pitch line (left of u from the
//! pinion's centre: +1). Either way the meshing link's coordinate relative to the carrier
//! is x_body = −ρ x_partner, with the same ρ for positions, rates and accelerations:
//! ρ = σ r_a/r_b (gear b from gear a), σ r_b/r_a (a from b), κ r (the rack from the
//! pinion), κ/r (the pinion from the rack). So a gear train is solved in closed form, one
//! gear after the other, exactly over any number of turns (the angles φ are carried
//! unwrapped, [`LinkState::angle`]); links that mesh with one another (the arm and planet
//! of an epicyclic train driven by its sun) are a [`TrainGroup`], their relations one
//! small linear system.
//!
//! **Kinetostatics.** The tooth force acts at the pitch point P along the line of action,
//! at the pressure angle α from the common tangent t: F = f_t t + |f_t| tan α s, s the
//! separating direction (away from the partner's centre for an external pair, outward on
//! a ring, inward on a pinion inside a ring, away from the pinion on a rack). For a gear
//! pinned at its centre O, its moment about O fixes f_t = −M_O / ((P − O) × t) (the
//! separating part passes through O); for a rack, its force along u fixes f_t = −F_rack·u.
//! The pin (or slide) takes the rest. The flank in contact is the side the tangential
//! part pushes: reported as the sign of F·t.

use crate::kernel::constraints::{JointGeom, Level};
use crate::kernel::kinetostatics::{Reaction, Wrench};
use crate::kernel::link_state::{cross, perp, point_of, rotate, LinkState, V2};
use crate::MechError;

/// The teeth of one gear pair or rack, in the local frames of its links.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MeshGeom {
    /// A rack and pinion (a is the pinion, b the rack).
    pub rack: bool,
    /// r_a, the pitch radius of a (m).
    pub ra: f64,
    /// r_b, the pitch radius of b (m); 0 for a rack.
    pub rb: f64,
    /// σ = +1 external, −1 internal; for a rack κ, the side of its pitch line (±1).
    pub sign: f64,
    /// tan α, α the pressure angle.
    pub tan_pressure: f64,
    /// Local vector of a's centre in a (m).
    pub ca: V2,
    /// Local vector of b's centre in b (for a rack: of its sliding joint's point), m.
    pub cb: V2,
    /// The carrier link.
    pub carrier: usize,
    /// The ratios of Willis' relation, worked out once ([`MeshGeom::ratios`]):
    /// [r_b/r_a, r_a/r_b] for a gear pair, [r_a, 1/r_a] for a rack.
    pub ratios: [f64; 2],
    /// 1/|O_b − O_a|, the centres' distance in the drawing inverted (1/m; 0 for a rack):
    /// both centres ride the carrier, so the distance never changes and the line of
    /// centres is normalised by a product, not a square root and a division.
    pub inv_centre: f64,
}

/// The pitch point of a mesh and its tangent in the states `s`: P (m), t (unit) and the
/// separating direction on b (unit; the force of a on b pushes b along it).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Pitch {
    /// The pitch point P.
    pub p: V2,
    /// The common tangent t (gear pair: perp of the line of centres a → b; rack: u).
    pub t: V2,
    /// The direction the separating force pushes b.
    pub sep_b: V2,
}

impl MeshGeom {
    /// [`MeshGeom::ratios`] of a pair of pitch radii r_a, r_b (m; a rack's r_b unused).
    pub fn ratios(rack: bool, ra: f64, rb: f64) -> [f64; 2] {
        if rack {
            [ra, 1.0 / ra]
        } else {
            [rb / ra, ra / rb]
        }
    }

    /// The pitch point, tangent and separating direction (module docs) in the states `s`;
    /// `u` is the rack's axis (unused for a gear pair).
    #[inline(always)]
    pub fn pitch(&self, s: &[LinkState], a: usize, b: usize, u: V2) -> Pitch {
        let oa = point_of(s, a, self.ca);
        if self.rack {
            let n = perp(u) * self.sign;
            return Pitch {
                p: oa + n * self.ra,
                t: u,
                sep_b: n,
            };
        }
        let ob = point_of(s, b, self.cb);
        let w = (ob - oa) * self.inv_centre;
        let (p, sep_b) = if self.sign > 0.0 {
            (oa + w * self.ra, w)
        } else if self.ra < self.rb {
            // b is the ring around a: P beyond a's centre, the ring pushed outward.
            (oa - w * self.ra, -w)
        } else {
            // a is the ring around b: P beyond b's centre, b (inside) pushed inward.
            (ob + w * self.rb, -w)
        };
        Pitch {
            p,
            t: perp(w),
            sep_b,
        }
    }
}

/// A group of one link that meshes (module docs): `body`, held by the joint `pin` (a
/// revolute at its centre for a gear or pinion, the prismatic slide for a rack) to a
/// solved link, meshing through joint `joint` (tooth data `mesh`) with the solved link
/// `partner`, on the solved carrier `carrier`. `*_tracked`: the partner's and carrier's
/// [`LinkState::angle`] is exact over turns (ground, driven and meshing links); else it
/// is taken from the rotation, in (−π, π].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct MeshGroup {
    /// The link solved.
    pub body: usize,
    /// The joint that holds it.
    pub pin: usize,
    /// The mesh joint.
    pub joint: usize,
    /// Index into the mechanism's meshes.
    pub mesh: usize,
    /// The meshing link already solved.
    pub partner: usize,
    /// The carrier.
    pub carrier: usize,
    /// The rack's prismatic joint (a rack and pinion only; the body's `pin` when the body
    /// is the rack).
    pub slide: usize,
    /// The body is a rack (it slides on the carrier).
    pub body_slides: bool,
    /// The partner is a rack.
    pub partner_slides: bool,
    /// The partner's angle is tracked.
    pub partner_tracked: bool,
    /// The carrier's angle is tracked.
    pub carrier_tracked: bool,
}

/// A link's rotation since the drawing (rad): its tracked angle, or from its rotation.
#[inline(always)]
fn turned(s: &[LinkState], l: usize, tracked: bool) -> f64 {
    if l == 0 {
        0.0
    } else if tracked {
        s[l].angle
    } else {
        s[l].rot.y.atan2(s[l].rot.x)
    }
}

impl MeshGroup {
    /// ρ of the module docs: the body's relative coordinate is −ρ × the partner's.
    #[inline(always)]
    fn ratio(&self, m: &MeshGeom, joints: &[JointGeom]) -> f64 {
        let body_is_a = joints[self.joint].a == self.body;
        match (m.rack, self.body_slides, body_is_a) {
            (true, true, _) | (false, _, true) => m.sign * m.ratios[0],
            (true, false, _) | (false, _, false) => m.sign * m.ratios[1],
        }
    }

    /// The rack's axis u (global) and its slide's guide point on the carrier: the
    /// prismatic joint `g` with the carrier on one side.
    #[inline(always)]
    fn slide_frame(&self, g: &JointGeom, s: &[LinkState], rack: usize) -> (V2, V2, V2, f64) {
        // The axis is fixed in the joint's first link; the rack is on one side, the
        // carrier on the other. Returns (u, the carrier's guide point now, the rack's
        // point now, s).
        let (guide, dg, dr) = if g.b == rack {
            (g.a, g.da, g.db)
        } else {
            (g.b, g.db, g.da)
        };
        let u0 = if g.a == guide { g.axis } else { -g.axis };
        let u = if guide == 0 {
            u0
        } else {
            rotate(s[guide].rot, u0)
        };
        let q = point_of(s, guide, dg);
        let b = point_of(s, rack, dr);
        (u, q, b, u.dot(&(b - q)))
    }

    /// The partner's relative coordinate (angle or slide), rate and acceleration, and the
    /// carrier's φ, ω, α.
    #[inline(always)]
    fn partner_rel(
        &self,
        joints: &[JointGeom],
        s: &[LinkState],
        upto: Level,
    ) -> ([f64; 3], [f64; 3]) {
        let c = self.carrier;
        let car = if c == 0 {
            [0.0; 3]
        } else {
            [turned(s, c, self.carrier_tracked), s[c].omega, s[c].alpha]
        };
        let p = self.partner;
        let rel = if self.partner_slides {
            let (u, _, b, x) = self.slide_frame(&joints[self.slide], s, p);
            let (mut xd, mut xdd) = (0.0, 0.0);
            if upto != Level::Position {
                let vc = if c == 0 {
                    V2::zeros()
                } else {
                    s[c].vel_at(b - s[c].pos)
                };
                xd = u.dot(&(s[p].vel_at(b - s[p].pos) - vc));
                if upto == Level::Acceleration {
                    let ac = if c == 0 {
                        V2::zeros()
                    } else {
                        s[c].acc_at(b - s[c].pos)
                    };
                    xdd = u.dot(&(s[p].acc_at(b - s[p].pos) - ac));
                }
            }
            [x, xd, xdd]
        } else {
            [
                turned(s, p, self.partner_tracked) - car[0],
                s[p].omega - car[1],
                s[p].alpha - car[2],
            ]
        };
        (rel, car)
    }
}

/// Solve a meshing link up to `upto` (module docs): its relative coordinate from its
/// partner's by Willis' relation, then its pose, velocity and acceleration.
#[cfg_attr(debug_assertions, inline)]
#[cfg_attr(not(debug_assertions), inline(always))]
pub fn solve_mesh(
    grp: &MeshGroup,
    meshes: &[MeshGeom],
    joints: &[JointGeom],
    s: &mut [LinkState],
    upto: Level,
) -> Result<(), MechError> {
    let m = &meshes[grp.mesh];
    let rho = grp.ratio(m, joints);
    let (rel, car) = grp.partner_rel(joints, s, upto);
    let x = [-rho * rel[0], -rho * rel[1], -rho * rel[2]];
    let g = joints[grp.pin];
    let body = grp.body;
    let c = grp.carrier;
    let (ca_rot, ca_omega, ca_alpha) = if c == 0 {
        (V2::new(1.0, 0.0), 0.0, 0.0)
    } else {
        (s[c].rot, s[c].omega, s[c].alpha)
    };
    if grp.body_slides {
        // The rack: the carrier's rotation, its slide point at s along u.
        let (u, q, _, _) = grp.slide_frame(&g, s, body);
        let dr = if g.b == body { g.db } else { g.da };
        let b = q + u * x[0];
        let st = &mut s[body];
        st.rot = ca_rot;
        st.angle = car[0];
        // On the ground the carrier's rotation is the identity: no rotation by it.
        st.pos = b - if c == 0 { dr } else { rotate(ca_rot, dr) };
        if upto == Level::Position {
            return Ok(());
        }
        let (vq, aq) = if c == 0 {
            (V2::zeros(), V2::zeros())
        } else {
            let r = b - s[c].pos;
            (s[c].vel_at(r), s[c].acc_at(r))
        };
        s[body].set_velocity_through(b, vq + u * x[1], ca_omega);
        if upto == Level::Acceleration {
            let coriolis = perp(u) * (2.0 * ca_omega * x[1]);
            s[body].set_acceleration_through(b, aq + coriolis + u * x[2], ca_alpha);
        }
        return Ok(());
    }
    // A gear or pinion pinned at its centre to a solved link.
    let (other, d_other, d_body) = if g.b == body {
        (g.a, g.da, g.db)
    } else {
        (g.b, g.db, g.da)
    };
    let o = point_of(s, other, d_other);
    let phi = car[0] + x[0];
    let (sn, cs) = phi.sin_cos();
    let rot = V2::new(cs, sn);
    let st = &mut s[body];
    st.rot = rot;
    st.angle = phi;
    st.pos = o - rotate(rot, d_body);
    if upto == Level::Position {
        return Ok(());
    }
    let (vo, ao) = if other == 0 {
        (V2::zeros(), V2::zeros())
    } else {
        let r = o - s[other].pos;
        (s[other].vel_at(r), s[other].acc_at(r))
    };
    s[body].set_velocity_through(o, vo, ca_omega + x[1]);
    if upto == Level::Acceleration {
        s[body].set_acceleration_through(o, ao, ca_alpha + x[2]);
    }
    Ok(())
}

/// d'Alembert for a meshing link (module docs): the tooth force from the body's moment
/// about its centre (a gear) or its force along the slide (a rack), the pin or slide
/// takes the rest; reactions into `out` (joint order: the mesh's as
/// [`Reaction::force`] by a on b, its tangential sign in [`Reaction::moment`]) and passed
/// on to the partner and the pin's other link in `f`.
#[cfg_attr(debug_assertions, inline)]
#[cfg_attr(not(debug_assertions), inline(always))]
pub fn mesh_reactions(
    grp: &MeshGroup,
    meshes: &[MeshGeom],
    joints: &[JointGeom],
    s: &[LinkState],
    f: &mut [Wrench],
    out: &mut [Reaction],
) -> Result<(), MechError> {
    let m = &meshes[grp.mesh];
    let gm = &joints[grp.joint];
    let g = &joints[grp.pin];
    let body = grp.body;
    let body_is_b = gm.b == body;
    let u = if m.rack {
        let rack = if grp.body_slides { body } else { grp.partner };
        grp.slide_frame(&joints[grp.slide], s, rack).0
    } else {
        V2::zeros()
    };
    let pitch = m.pitch(s, gm.a, gm.b, u);
    let sep = if body_is_b { pitch.sep_b } else { -pitch.sep_b };
    let wb = f[body];
    let (fb, anchor) = (V2::new(wb.x, wb.y), s[body].pos);
    let (other, d_other) = if g.b == body {
        (g.a, g.da)
    } else {
        (g.b, g.db)
    };
    let joint_point = point_of(s, other, d_other);
    let ft = if grp.body_slides {
        -fb.dot(&pitch.t)
    } else {
        let mo = wb.z + cross(anchor - joint_point, fb);
        let lever = cross(pitch.p - joint_point, pitch.t);
        if lever == 0.0 {
            return Err(MechError::Singular {
                condition: f64::INFINITY,
            });
        }
        -mo / lever
    };
    // The force of the partner on the body, and the pin's (or slide's) reaction: a
    // slide's at the joint point as its second link carries it now, the moment about it
    // (docs/conventions.md, Reactions), not about the point the slide's other link holds.
    let force = pitch.t * ft + sep * (ft.abs() * m.tan_pressure);
    let r = -(fb + force);
    let (joint_point, moment) = if grp.body_slides {
        let p = point_of(s, g.b, g.db);
        (
            p,
            -(wb.z + cross(anchor - p, fb) + cross(pitch.p - p, force)),
        )
    } else {
        (joint_point, 0.0)
    };
    let on_b = if body_is_b { force } else { -force };
    out[grp.joint] = Reaction {
        force: on_b,
        moment: if on_b.dot(&pitch.t) >= 0.0 { 1.0 } else { -1.0 },
    };
    out[grp.pin] = if g.b == body {
        Reaction { force: r, moment }
    } else {
        Reaction {
            force: -r,
            moment: -moment,
        }
    };
    let push = |f: &mut [Wrench], l: usize, p: V2, force: V2, couple: f64| {
        let pos = if l == 0 { V2::zeros() } else { s[l].pos };
        f[l] += Wrench::new(force.x, force.y, couple + cross(p - pos, force));
    };
    push(f, grp.partner, pitch.p, -force, 0.0);
    push(f, other, joint_point, -r, -moment);
    Ok(())
}

/// The most links a gear-train group may have ([`TrainGroup`]).
pub const TRAIN_MAX: usize = 3;

/// `$f::<N>($args)` with N the gear-train group's size `$n` as a constant (1, 2, else
/// [`TRAIN_MAX`]): each size its own instance, the choice folded where `$n` is a constant.
macro_rules! by_train_size {
    ($n:expr, $($f:ident)::+ ($($arg:expr),* $(,)?)) => {
        match $n {
            1 => $($f)::+::<1>($($arg),*),
            2 => $($f)::+::<2>($($arg),*),
            _ => $($f)::+::<TRAIN_MAX>($($arg),*),
        }
    };
}

/// A group of up to [`TRAIN_MAX`] links turning about their centres and meshing with one
/// another and with solved links, as many meshes as links (for instance the arm and the
/// planet of an epicyclic train driven by its sun against a fixed ring): Willis' relation
/// of every mesh is linear in the links' rotations, one n × n system for the angles, the
/// same matrix for their rates and accelerations. Each link is held by one revolute at
/// its centre (`pins[k]`), to a solved link or to a link of the group placed before it
/// (`order`). Only gear pairs (no rack) form such a group.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct TrainGroup {
    /// The number of links n.
    pub n: usize,
    /// Its links.
    pub bodies: [usize; TRAIN_MAX],
    /// The revolute joint at each link's centre.
    pub pins: [usize; TRAIN_MAX],
    /// The mesh joints and their indices into the mechanism's meshes.
    pub meshes: [(usize, usize); TRAIN_MAX],
    /// The order the links are placed in (indices into `bodies`): each pinned to a solved
    /// link or to one placed before it.
    pub order: [usize; TRAIN_MAX],
    /// Per link of the mechanism up to the 64th: its [`LinkState::angle`] is tracked
    /// (bit l), for the solved links the meshes reach.
    pub tracked: u64,
    /// The link each link's pin holds it to (solved, or of the group), read from the model
    /// with the plan like every field here, so that the generated code's choices of side
    /// and column are constants.
    pub outer: [usize; TRAIN_MAX],
    /// Each link is its pin's second link (`b`).
    pub pin_b: [bool; TRAIN_MAX],
    /// Each mesh's links a and b and its carrier.
    pub ends: [[usize; 3]; TRAIN_MAX],
}

impl TrainGroup {
    /// The column of link `l` in the group's unknowns, if it is one of them.
    #[inline(always)]
    fn col(&self, l: usize) -> Option<usize> {
        self.bodies[..self.n].iter().position(|&b| b == l)
    }

    /// Willis' matrix A: row r is mesh r's relation r_a x_a + σ r_b x_b − (r_a + σ r_b) x_c
    /// = 0 in the group's links' columns; it depends on the pitch radii alone (`N` =
    /// `self.n`).
    #[inline(always)]
    fn willis_matrix<const N: usize>(&self, meshes: &[MeshGeom]) -> nalgebra::SMatrix<f64, N, N> {
        let mut a = nalgebra::SMatrix::<f64, N, N>::zeros();
        for (r, &(_, mi)) in self.meshes[..N].iter().enumerate() {
            for (l, k) in willis_terms(self.ends[r], &meshes[mi]) {
                if let Some(c) = self.col(l) {
                    a[(r, c)] += k;
                }
            }
        }
        a
    }

    /// The right-hand side of Willis' relations A x = rhs for the links' angle (`level`
    /// 0), rate (1) or acceleration (2): minus the terms of the solved links, their values
    /// from `s` (`N` = `self.n`).
    #[inline(always)]
    fn willis_rhs<const N: usize>(
        &self,
        meshes: &[MeshGeom],
        s: &[LinkState],
        level: usize,
    ) -> nalgebra::SVector<f64, N> {
        let mut rhs = nalgebra::SVector::<f64, N>::zeros();
        let value = |l: usize| -> f64 {
            if l == 0 {
                return 0.0;
            }
            match level {
                0 => turned(s, l, self.tracked >> l.min(63) & 1 == 1),
                1 => s[l].omega,
                _ => s[l].alpha,
            }
        };
        for (r, &(_, mi)) in self.meshes[..N].iter().enumerate() {
            for (l, k) in willis_terms(self.ends[r], &meshes[mi]) {
                if self.col(l).is_none() {
                    rhs[r] -= k * value(l);
                }
            }
        }
        rhs
    }
}

/// The three terms of a mesh's Willis relation r_a x_a + σ r_b x_b − (r_a + σ r_b) x_c = 0:
/// (link, coefficient) for a, b and the carrier c (`ends`, [`TrainGroup::ends`]).
#[inline(always)]
fn willis_terms(ends: [usize; 3], m: &MeshGeom) -> [(usize, f64); 3] {
    [
        (ends[0], m.ra),
        (ends[1], m.sign * m.rb),
        (ends[2], -(m.ra + m.sign * m.rb)),
    ]
}

/// Willis' relations of a gear-train group worked out once ([`TrainGroup`]): their
/// matrix A depends on the pitch radii alone, so its inverse and its condition estimate
/// are constants of the drawing, kept beside the meshes (the generated struct holds one
/// per gear-train group, built with the struct). Each solve is then x = A⁻¹ rhs.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Willis {
    /// A⁻¹, its first n rows and columns.
    inverse: [[f64; TRAIN_MAX]; TRAIN_MAX],
    /// The pivot ratio of A's LU factors ([`crate::kernel::linalg::Lu::condition`]).
    condition: f64,
}

impl Willis {
    /// The inverse of the group's Willis matrix and its condition estimate, from the
    /// meshes' pitch radii.
    pub fn new(grp: &TrainGroup, meshes: &[MeshGeom]) -> Self {
        by_train_size!(grp.n, Self::sized(grp, meshes))
    }

    /// [`Willis::new`] for a group of `N` = `grp.n` links: A⁻¹ column by column from its
    /// LU factors.
    fn sized<const N: usize>(grp: &TrainGroup, meshes: &[MeshGeom]) -> Self {
        let lu = crate::kernel::linalg::Lu::new(grp.willis_matrix::<N>(meshes));
        let mut inverse = [[0.0; TRAIN_MAX]; TRAIN_MAX];
        for c in 0..N {
            let x = lu.solve(&nalgebra::SVector::<f64, N>::from_fn(|r, _| {
                if r == c {
                    1.0
                } else {
                    0.0
                }
            }));
            for r in 0..N {
                inverse[r][c] = x[r];
            }
        }
        Willis {
            inverse,
            condition: lu.condition(),
        }
    }

    /// x = A⁻¹ rhs.
    #[inline(always)]
    fn apply<const N: usize>(&self, rhs: &nalgebra::SVector<f64, N>) -> nalgebra::SVector<f64, N> {
        nalgebra::SVector::<f64, N>::from_fn(|r, _| {
            let mut x = 0.0;
            for c in 0..N {
                x += self.inverse[r][c] * rhs[c];
            }
            x
        })
    }
}

/// Solve a gear-train group up to `upto` ([`TrainGroup`]): the angles from Willis'
/// relations, the links placed about their centres in `order`, then the rates and
/// accelerations, each x = A⁻¹ rhs with the inverse worked out once (`willis`, of this
/// group and these meshes). `Singular` when the relations do not fix the angles.
///
/// The systems are exactly n × n (one instance per size, chosen by `grp.n`: a constant in
/// the generated code, so the choice folds away).
#[cfg_attr(debug_assertions, inline)]
#[cfg_attr(not(debug_assertions), inline(always))]
pub fn solve_train(
    grp: &TrainGroup,
    willis: &Willis,
    meshes: &[MeshGeom],
    joints: &[JointGeom],
    s: &mut [LinkState],
    upto: Level,
) -> Result<(), MechError> {
    by_train_size!(
        grp.n,
        solve_train_sized(grp, willis, meshes, joints, s, upto)
    )
}

/// [`solve_train`] for a group of `N` = `grp.n` links.
#[cfg_attr(debug_assertions, inline)]
#[cfg_attr(not(debug_assertions), inline(always))]
fn solve_train_sized<const N: usize>(
    grp: &TrainGroup,
    willis: &Willis,
    meshes: &[MeshGeom],
    joints: &[JointGeom],
    s: &mut [LinkState],
    upto: Level,
) -> Result<(), MechError> {
    let cond = willis.condition;
    if !(cond < crate::kernel::linalg::SINGULAR_CONDITION) {
        return Err(MechError::Singular { condition: cond });
    }
    let phi = willis.apply(&grp.willis_rhs::<N>(meshes, s, 0));
    let centre = |s: &[LinkState], k: usize| {
        let g = &joints[grp.pins[k]];
        let other = grp.outer[k];
        let (d_other, d_body) = if grp.pin_b[k] {
            (g.da, g.db)
        } else {
            (g.db, g.da)
        };
        (other, point_of(s, other, d_other), d_body)
    };
    for &k in &grp.order[..grp.n] {
        let (_, o, d_body) = centre(s, k);
        let (sn, cs) = phi[k].sin_cos();
        let st = &mut s[grp.bodies[k]];
        st.rot = V2::new(cs, sn);
        st.angle = phi[k];
        st.pos = o - rotate(st.rot, d_body);
    }
    if upto == Level::Position {
        return Ok(());
    }
    let w = willis.apply(&grp.willis_rhs::<N>(meshes, s, 1));
    for &k in &grp.order[..grp.n] {
        let (other, o, _) = centre(s, k);
        let vo = if other == 0 {
            V2::zeros()
        } else {
            s[other].vel_at(o - s[other].pos)
        };
        s[grp.bodies[k]].set_velocity_through(o, vo, w[k]);
    }
    if upto == Level::Acceleration {
        let al = willis.apply(&grp.willis_rhs::<N>(meshes, s, 2));
        for &k in &grp.order[..grp.n] {
            let (other, o, _) = centre(s, k);
            let ao = if other == 0 {
                V2::zeros()
            } else {
                s[other].acc_at(o - s[other].pos)
            };
            s[grp.bodies[k]].set_acceleration_through(o, ao, al[k]);
        }
    }
    Ok(())
}

/// d'Alembert for a gear-train group, reduced to its tooth forces: every pin passes a
/// force alone, so the moments about each link's pin of the link and of everything pinned
/// to it, further out in the group (each load carried to the pin through which it enters),
/// are n equations in the n tangential tooth forces alone, an n × n system; each pin's
/// force is then minus the sum of the forces on the links it carries. The tooth forces'
/// radial parts follow the flanks, which are settled by solving again until every flank
/// agrees with the sign of its tangential force.
///
/// One instance per size, as [`solve_train`].
#[cfg_attr(debug_assertions, inline)]
#[cfg_attr(not(debug_assertions), inline(always))]
pub fn train_reactions(
    grp: &TrainGroup,
    meshes: &[MeshGeom],
    joints: &[JointGeom],
    s: &[LinkState],
    f: &mut [Wrench],
    out: &mut [Reaction],
) -> Result<(), MechError> {
    by_train_size!(grp.n, train_reactions_sized(grp, meshes, joints, s, f, out))
}

/// [`train_reactions`] for a group of `N` = `grp.n` links.
#[cfg_attr(debug_assertions, inline)]
#[cfg_attr(not(debug_assertions), inline(always))]
fn train_reactions_sized<const N: usize>(
    grp: &TrainGroup,
    meshes: &[MeshGeom],
    joints: &[JointGeom],
    s: &[LinkState],
    f: &mut [Wrench],
    out: &mut [Reaction],
) -> Result<(), MechError> {
    let n = N;
    // (Arrays filled by loops, not `core::array::from_fn`, whose closures were measured
    // to stay calls, with the group's constants read as data.)
    let mut pitch = [Pitch {
        p: V2::zeros(),
        t: V2::zeros(),
        sep_b: V2::zeros(),
    }; N];
    let mut pin_point = [V2::zeros(); N];
    // The group link each link is pinned to, if any.
    let mut parent: [Option<usize>; N] = [None; N];
    for r in 0..n {
        let [a, b, _] = grp.ends[r];
        pitch[r] = meshes[grp.meshes[r].1].pitch(s, a, b, V2::zeros());
    }
    for k in 0..n {
        let g = &joints[grp.pins[k]];
        pin_point[k] = point_of(s, grp.outer[k], if grp.pin_b[k] { g.da } else { g.db });
        parent[k] = grp.col(grp.outer[k]);
    }
    // Where a force on group link `j` at `p` enters link `k`'s moments: at `p` itself when
    // j = k, at the pin of k's child that carries j when j is further out, nowhere else.
    let enters = |j: usize, k: usize, p: V2| -> Option<V2> {
        if j == k {
            return Some(p);
        }
        let mut c = j;
        for _ in 0..N {
            match parent[c] {
                Some(up) if up == k => return Some(pin_point[c]),
                Some(up) => c = up,
                None => return None,
            }
        }
        None
    };
    // The links a group link carries (itself included).
    let carries = |k: usize, j: usize| enters(j, k, V2::zeros()).is_some();
    // The tooth force on b of mesh r per unit tangential force, for the flanks `fl`.
    let unit = |r: usize, fl: f64| {
        pitch[r].t + pitch[r].sep_b * (fl * meshes[grp.meshes[r].1].tan_pressure)
    };
    // The right-hand side: minus the loads' moments (each link's wrench `f`) about each
    // pin, the flanks aside.
    let rhs = nalgebra::SVector::<f64, N>::from_fn(|k, _| {
        let mut m = 0.0;
        for j in 0..n {
            let w = f[grp.bodies[j]];
            let pos = s[grp.bodies[j]].pos;
            if let Some(p) = enters(j, k, pos) {
                m += cross(p - pin_point[k], V2::new(w.x, w.y)) + if j == k { w.z } else { 0.0 };
            }
        }
        -m
    });
    let mut flanks = [1.0; N];
    let mut ft = nalgebra::SVector::<f64, N>::zeros();
    for _ in 0..=(1 << N) {
        let mut a = nalgebra::SMatrix::<f64, N, N>::zeros();
        for r in 0..n {
            let [ea, eb, _] = grp.ends[r];
            let d = unit(r, flanks[r]);
            for (l, dir) in [(eb, d), (ea, -d)] {
                if let Some(j) = grp.col(l) {
                    for k in 0..n {
                        if let Some(p) = enters(j, k, pitch[r].p) {
                            a[(k, r)] += cross(p - pin_point[k], dir);
                        }
                    }
                }
            }
        }
        ft = crate::kernel::linalg::Lu::new(a).solve(&rhs);
        let mut settled = [1.0; N];
        for r in 0..n {
            if ft[r] < 0.0 {
                settled[r] = -1.0;
            }
        }
        if settled == flanks {
            break;
        }
        flanks = settled;
    }
    // Each pin's force on its link: minus every force on the links it carries.
    let pin_force = |k: usize| -> V2 {
        let mut sum = V2::zeros();
        for j in 0..n {
            if carries(k, j) {
                let w = f[grp.bodies[j]];
                sum += V2::new(w.x, w.y);
            }
        }
        for r in 0..n {
            let [ea, eb, _] = grp.ends[r];
            let d = unit(r, flanks[r]) * ft[r];
            for (l, force) in [(eb, d), (ea, -d)] {
                if grp.col(l).is_some_and(|j| carries(k, j)) {
                    sum += force;
                }
            }
        }
        -sum
    };
    let mut pin_forces = [V2::zeros(); N];
    for (k, force) in pin_forces.iter_mut().enumerate() {
        *force = pin_force(k);
    }
    for k in 0..n {
        let r = pin_forces[k];
        let other = grp.outer[k];
        out[grp.pins[k]] = Reaction {
            force: if grp.pin_b[k] { r } else { -r },
            moment: 0.0,
        };
        if grp.col(other).is_none() {
            let pos = if other == 0 {
                V2::zeros()
            } else {
                s[other].pos
            };
            f[other] += Wrench::new(-r.x, -r.y, cross(pin_point[k] - pos, -r));
        }
    }
    for r in 0..n {
        let (j, _) = grp.meshes[r];
        let [ea, eb, _] = grp.ends[r];
        let force = unit(r, flanks[r]) * ft[r];
        out[j] = Reaction {
            force,
            moment: if force.dot(&pitch[r].t) >= 0.0 {
                1.0
            } else {
                -1.0
            },
        };
        for (l, fl) in [(ea, -force), (eb, force)] {
            if grp.col(l).is_none() {
                let pos = if l == 0 { V2::zeros() } else { s[l].pos };
                f[l] += Wrench::new(fl.x, fl.y, cross(pitch[r].p - pos, fl));
            }
        }
    }
    Ok(())
}
