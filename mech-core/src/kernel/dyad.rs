//! Closed-form positions of the common groups: the driven crank and slider, the dyads
//! RRR (two circles), RRP (circle and line), RPR (a tangent construction), PRP (two
//! lines), RPP, and the single-link slot groups. Each keeps the assembly branch of the
//! drawing: [`branch_quantity`] is evaluated once at the drawing and its sign passed to
//! [`position`] at every input value.
//!
//! The slotted slider (a link on a guide with a slot joint, the Scotch yoke's yoke) has
//! one unknown, its slide, with no branch: [`crate::kernel::slotted`], with its rates and
//! reactions in that one coordinate.

use crate::kernel::constraints::{Drive, JointGeom};
use crate::kernel::link_state::{cross, dir_of, perp, point_of, quotient, rotate, LinkState, V2};
use crate::MechError;

/// How a group's positions are solved.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Solver {
    /// One link, pinned by `joint` to a solved link and driven there by input `input`
    /// (a crank): φ from q, position from the pin.
    DrivenRevolute {
        /// The link.
        body: usize,
        /// The revolute driver.
        joint: usize,
        /// The input index.
        input: usize,
    },
    /// One link sliding along `joint` on a solved link, driven by input `input`.
    DrivenPrismatic {
        /// The link.
        body: usize,
        /// The prismatic driver.
        joint: usize,
        /// The input index.
        input: usize,
    },
    /// RRR dyad: `b1` pinned to a solved link by `ja`, `b2` by `jb`, pinned together by
    /// `jc`: intersection of two circles.
    Rrr {
        /// First link.
        b1: usize,
        /// Second link.
        b2: usize,
        /// Pin of b1 to a solved link.
        ja: usize,
        /// Pin between b1 and b2.
        jc: usize,
        /// Pin of b2 to a solved link.
        jb: usize,
    },
    /// RRP dyad: `b1` pinned by `ja`, pinned to `b2` by `jc`, `b2` sliding on a solved link
    /// by the prismatic `jp`: intersection of a circle and a line.
    Rrp {
        /// The pinned link.
        b1: usize,
        /// The slider.
        b2: usize,
        /// Pin of b1 to a solved link.
        ja: usize,
        /// Pin between b1 and b2.
        jc: usize,
        /// Prismatic of b2 on a solved link.
        jp: usize,
    },
    /// RPR dyad: `b1` pinned by `ja`, `b2` pinned by `jb`, sliding on each other by the
    /// prismatic `jp`: a tangent construction.
    Rpr {
        /// First link.
        b1: usize,
        /// Second link.
        b2: usize,
        /// Pin of b1 to a solved link.
        ja: usize,
        /// Prismatic between b1 and b2.
        jp: usize,
        /// Pin of b2 to a solved link.
        jb: usize,
    },
    /// PRP dyad: `b1` sliding on a solved link by `jp1`, `b2` by `jp2`, pinned together
    /// by `jc`: both rotations are known, the pin is where two lines cross.
    Prp {
        /// First slider.
        b1: usize,
        /// Second slider.
        b2: usize,
        /// Prismatic of b1 on a solved link.
        jp1: usize,
        /// Pin between b1 and b2.
        jc: usize,
        /// Prismatic of b2 on a solved link.
        jp2: usize,
    },
    /// RPP dyad: `b1` pinned to a solved link by `ja`, sliding on `b2` by `jp`, `b2`
    /// sliding on a solved link by `jq`: both rotations are those of the last solved link;
    /// b1 is placed by its pin, b2 where two lines cross.
    Rpp {
        /// The pinned link.
        b1: usize,
        /// The outer slider.
        b2: usize,
        /// Pin of b1.
        ja: usize,
        /// Prismatic between b1 and b2.
        jp: usize,
        /// Prismatic of b2 on a solved link.
        jq: usize,
    },
    /// One link pinned by `ja` whose point slides in a slot of a solved link (`js`):
    /// circle and line.
    PinInFixedSlot {
        /// The link.
        body: usize,
        /// Its pin to a solved link.
        ja: usize,
        /// The slot joint (slot in the solved link, pin of `body`).
        js: usize,
    },
    /// One slotted link pinned by `ja`, with a solved link's pin in its slot (`js`): a
    /// tangent construction.
    SlottedLever {
        /// The link.
        body: usize,
        /// Its pin to a solved link.
        ja: usize,
        /// The slot joint (slot in `body`, pin of a solved link).
        js: usize,
    },
    /// One link sliding by the prismatic `jq` on a solved link G (so it turns with G),
    /// with a slot joint `js` to a solved link K — a slot in `body` receiving K's pin (the
    /// Scotch yoke), or `body`'s pin in a slot of K: only the slide s along the guide's
    /// axis is unknown, and the slot joint's point of `body` is where the slide line
    /// crosses the slot's line ([`slotted_slider`](crate::kernel::slotted::slotted_slider)).
    SlottedSlider {
        /// The link.
        body: usize,
        /// Its prismatic joint on a solved link.
        jq: usize,
        /// The slot joint (slot in `body` and pin of a solved link, or the other way).
        js: usize,
    },
    /// One link meshing with a solved gear or rack (`crate::elements::gears`): placed by Willis'
    /// relation, not here.
    Mesh {
        /// The link.
        body: usize,
        /// The mesh joint that drives it.
        joint: usize,
    },
    /// Links turning about their centres, meshing with one another (`crate::elements::gears`,
    /// a gear-train group): placed by Willis' relations, not here.
    Train,
    /// A follower driven by a cam (`crate::elements::cam`), placed there.
    Cam {
        /// The follower.
        body: usize,
        /// The cam joint.
        joint: usize,
    },
    /// A wheel driven by its travel on a track (`crate::elements::rolling`), placed there.
    DrivenRolling {
        /// The wheel.
        body: usize,
        /// The rolling joint.
        joint: usize,
        /// The input index.
        input: usize,
    },
    /// A rod and a rolling wheel (`crate::elements::rolling`): the wheel's centre as an RRP
    /// dyad's slider (`Rrp` with the rolling joint as the guide), then its turn.
    Rrl {
        /// The rod.
        b1: usize,
        /// The wheel.
        b2: usize,
        /// The rod's pin to a solved link.
        ja: usize,
        /// The pin between rod and wheel (at the wheel's centre).
        jc: usize,
        /// The rolling joint.
        jr: usize,
    },
    /// No closed form: Newton–Raphson on the group's equations from the drawing.
    Newton,
}

/// Relative tolerance within which a negative discriminant is taken as a tangency.
const TANGENT_TOL: f64 = 1e-12;

/// Intersection of the circle (c1, r1) with the circle (c2, r2), given the squared radii
/// r1², r2² (m²), on the side `sign` of the line c1 → c2 (sign of (c2 − c1) × (X − c1)).
/// With d = c2 − c1, k = ½(|d|² + r1² − r2²) and H = r1² |d|² − k² (= h² |d|⁴, h the
/// distance of X from the line over |d|): X = c1 + (k d + sign·√H·perp(d)) / |d|².
/// `NoAssembly` when they do not meet (H < 0 beyond a relative tolerance, a tangency
/// within it). The square root is taken before the division, so that the two run side by
/// side rather than one after the other.
#[inline]
pub fn circle_circle(c1: V2, r1sq: f64, c2: V2, r2sq: f64, sign: f64) -> Result<V2, MechError> {
    let d = c2 - c1;
    let l2 = d.norm_squared();
    if !(l2 > 0.0) {
        return Err(MechError::NoAssembly);
    }
    let inv = 1.0 / l2;
    let k = 0.5 * (l2 + r1sq - r2sq);
    let mut h2 = r1sq * l2 - k * k;
    if h2 < 0.0 {
        if h2 < -TANGENT_TOL * r1sq.max(r2sq) * l2 {
            return Err(MechError::NoAssembly);
        }
        h2 = 0.0;
    }
    Ok(c1 + (d * k + perp(d) * (sign * h2.sqrt())) * inv)
}

/// Intersection of the circle (c, r), given r² (m²), with the line through `p` along unit
/// `u`, on the side `sign` along u of the foot of the perpendicular from c
/// ([`circle_line_along`]).
#[inline]
pub fn circle_line(c: V2, rsq: f64, p: V2, u: V2, sign: f64) -> Result<V2, MechError> {
    circle_line_along(c, rsq, p, u, sign).map(|(x, _, _)| x)
}

/// [`circle_line`]'s point X, its signed distance x = (X − c)·u along the line from the
/// foot of the perpendicular from c, and y = (X − c)·perp(u). With d = c − p, the foot is
/// at t₀ = d·u along the line and c is h = u × d from it, so x = ±√(r² − h²),
/// X = p + u (t₀ + x) and y = −h. (h from the cross product: no cancellation in
/// c − foot, and t₀ and h are computed side by side; x comes straight from the square
/// root, which an RRP dyad's rates take as their determinant, y before it.)
#[inline]
pub fn circle_line_along(
    c: V2,
    rsq: f64,
    p: V2,
    u: V2,
    sign: f64,
) -> Result<(V2, f64, f64), MechError> {
    let d = c - p;
    let t0 = d.dot(&u);
    let h = cross(u, d);
    let mut w2 = rsq - h * h;
    if w2 < 0.0 {
        if w2 < -TANGENT_TOL * rsq {
            return Err(MechError::NoAssembly);
        }
        w2 = 0.0;
    }
    let x = sign * w2.sqrt();
    Ok((p + u * (t0 + x), x, -h))
}

/// Intersection of the lines (p1, u1) and (p2, u2); `Singular` when parallel.
#[inline]
pub fn line_line(p1: V2, u1: V2, p2: V2, u2: V2) -> Result<V2, MechError> {
    let den = cross(u1, u2);
    if den.abs() < 1e-12 {
        return Err(MechError::Singular {
            condition: 1.0 / den.abs().max(f64::MIN_POSITIVE),
        });
    }
    Ok(p1 + u1 * (cross(p2 - p1, u2) / den))
}

/// Place a link from its rotation and one of its points: pos = P − R d.
#[inline]
pub fn place_by_point(s: &mut LinkState, rot: V2, d: V2, p: V2) {
    s.rot = rot;
    // The point is often the link's anchor (its first point): then d = 0, no rotation.
    s.pos = if d.x == 0.0 && d.y == 0.0 {
        p
    } else {
        p - rotate(rot, d)
    };
}

/// Place a link from two of its points (local vectors d1, d2) at global positions p1, p2
/// the same distance apart (|p2 − p1| = |d2 − d1|, as a closed form places them): the
/// rotation from a = d2 − d1 to b = p2 − p1 is (a·b, a × b)/(|a| |b|) = (a·b, a × b)/|a|²,
/// unit to roundoff, with no square root (the division depends on the drawing alone, so
/// it runs beside the solve, not in its chain).
#[inline]
pub fn place_by_two_points(s: &mut LinkState, d1: V2, d2: V2, p1: V2, p2: V2) {
    place_by_point(s, quotient(p2 - p1, d2 - d1), d1, p1);
}

/// The side of a closed form's solution in the drawing (±1), given the kernel's signed
/// quantity there; a zero (a change point) counts as +1.
#[inline]
pub fn branch(x: f64) -> f64 {
    if x < 0.0 {
        -1.0
    } else {
        1.0
    }
}

/// For a joint `g` with link `body` on one side and a solved link on the other: the
/// joint point's current position from the solved side, and its local vector in `body`.
#[inline(always)]
pub fn pin(g: &JointGeom, s: &[LinkState], body: usize) -> (V2, V2) {
    if g.b == body {
        (point_of(s, g.a, g.da), g.db)
    } else {
        (point_of(s, g.b, g.db), g.da)
    }
}

/// The line along which a point (local `d` in `body`) moves when `body` slides by the
/// prismatic `g` on the solved link `l` (its other side), `body` turned as `l`: (a point of
/// it, unit direction). Unturned on the ground ([`dir_of`]: no rotation by the identity).
#[inline(always)]
fn slide_line(g: &JointGeom, s: &[LinkState], body: usize, l: usize, d: V2) -> (V2, V2) {
    let u = dir_of(s, l, g.axis);
    if g.b == body {
        (point_of(s, g.a, g.da) + dir_of(s, l, d - g.db), u)
    } else {
        (point_of(s, g.b, g.db) + dir_of(s, l, d - g.da), u)
    }
}

/// Place `body`, turned as link `l` (the identity on the ground, a literal), with its point
/// of local vector `d` at `p`: [`place_by_point`] with no rotation by the ground's identity.
#[inline(always)]
fn place_as(s: &mut [LinkState], body: usize, l: usize, d: V2, p: V2) {
    if l == 0 {
        place_by_point(&mut s[body], V2::new(1.0, 0.0), V2::zeros(), p - d);
    } else {
        let rot = s[l].rot;
        place_by_point(&mut s[body], rot, d, p);
    }
}

const TANGENT_TOL_REL: f64 = 1e-12;

/// RPR / slotted lever: the unit rotation of the guide such that the slide line (unit
/// `axis` in the guide) passes through the slider's point, and the
/// coordinates (x, y) of `dvec` = slider pin − guide pin (current) in the guide's frame
/// (u, n = perp(u)) of the turned axis u. `w` = the local vector from the guide pin to
/// the slide point minus that from the slider's pin to its slide point; `sign` picks the
/// side (see [`tangent_side`]).
///
/// The slide condition n·(D − R w) = 0 reads y = D·n = n₀·w (n₀ = perp(axis)): a
/// constant offset, so x = D·u = ±√(|D|² − y²) straight from the square root. As complex
/// numbers D = u (x + i y), so u = D (x − i y)/|D|² and the rotation is u·conj(axis):
/// one square root and one division.
#[inline(always)]
fn tangent_rotation(axis: V2, dvec: V2, w: V2, sign: f64) -> Result<(V2, f64, f64), MechError> {
    let l2 = dvec.norm_squared();
    if !(l2 > 0.0) {
        return Err(MechError::NoAssembly);
    }
    let y = perp(axis).dot(&w);
    let mut x2 = l2 - y * y;
    if x2 < 0.0 {
        if x2 < -TANGENT_TOL_REL * l2 {
            return Err(MechError::NoAssembly);
        }
        x2 = 0.0;
    }
    let x = sign * x2.sqrt();
    // (x − i y)·conj(axis), then D times it over |D|² (the division waits only for D, so
    // it runs beside the square root).
    let k = V2::new(x * axis.x - y * axis.y, -(x * axis.y + y * axis.x));
    Ok((rotate(dvec, k) * (1.0 / l2), x, y))
}

/// The side of a tangent construction: with the guide's current normal `m` and `dvec`
/// as in [`tangent_rotation`], −m × dvec has the sign of that kernel's `sign`.
#[inline(always)]
fn tangent_side(guide: &LinkState, axis: V2, dvec: V2) -> f64 {
    -cross(rotate(guide.rot, perp(axis)), dvec)
}

/// The guide/slider data of an RPR or slotted-lever group: (D, w).
#[inline(always)]
fn rpr_data(gp: &JointGeom, pin_a: (V2, V2), pin_b: (V2, V2), b_moves: bool) -> (V2, V2) {
    // Slide condition n·(P_b − Q_a) = 0 with P_b = pin_b + R(ψ)(db − dpin_b) when the
    // slider rotates with the guide, or P_b = pin_b (a solved link's pin).
    let dvec = pin_b.0 - pin_a.0;
    let wb = if b_moves {
        gp.db - pin_b.1
    } else {
        V2::zeros()
    };
    let w = -(wb - (gp.da - pin_a.1));
    (dvec, w)
}

/// An RPR group's prismatic joint, guide and slider, and the pins of the guide and the
/// slider to solved links (current position, local vector).
#[inline(always)]
#[allow(clippy::type_complexity)]
fn rpr_pins<'a>(
    joints: &'a [JointGeom],
    s: &[LinkState],
    b1: usize,
    ja: usize,
    jp: usize,
    jb: usize,
) -> (&'a JointGeom, usize, usize, (V2, V2), (V2, V2)) {
    let gp = &joints[jp];
    let (ga, gb) = if gp.a == b1 { (ja, jb) } else { (jb, ja) };
    let (guide, slider) = (gp.a, gp.b);
    (
        gp,
        guide,
        slider,
        pin(&joints[ga], s, guide),
        pin(&joints[gb], s, slider),
    )
}

/// The signed quantity whose sign is the group's assembly branch, at the current states.
/// Evaluated once at the drawing (construction) and kept for every input value.
pub fn branch_quantity(solver: Solver, joints: &[JointGeom], s: &[LinkState]) -> f64 {
    match solver {
        Solver::Rrr { b1, b2, ja, jc, jb } => {
            let (a, _) = pin(&joints[ja], s, b1);
            let (b, _) = pin(&joints[jb], s, b2);
            let gc = &joints[jc];
            let c = s[gc.b].point(gc.db);
            cross(b - a, c - a)
        }
        Solver::Rrl { b1, ja, jc, jr, .. } if joints[jr].around != 0.0 => {
            // A wheel around a circle: the side of C from the line A → D, as an RRR's.
            let (a, _) = pin(&joints[ja], s, b1);
            let gr = &joints[jr];
            let d = point_of(s, gr.a, gr.da);
            let gc = &joints[jc];
            let c = s[gc.b].point(gc.db);
            cross(d - a, c - a)
        }
        Solver::Rrp { b1, b2, ja, jc, jp }
        | Solver::Rrl {
            b1,
            b2,
            ja,
            jc,
            jr: jp,
        } => {
            // Side along the line of C relative to the foot of the perpendicular from A.
            let (a, _) = pin(&joints[ja], s, b1);
            let gc = &joints[jc];
            let c = s[gc.b].point(gc.db);
            let u = s[b2].r(joints[jp].axis);
            (c - a).dot(&u)
        }
        Solver::Rpr { b1, ja, jp, jb, .. } => {
            let (gp, guide, _, pa, pb) = rpr_pins(joints, s, b1, ja, jp, jb);
            tangent_side(&s[guide], gp.axis, pb.0 - pa.0)
        }
        Solver::PinInFixedSlot { body, ja, js } => {
            let (a, _) = pin(&joints[ja], s, body);
            let g = &joints[js];
            let p = s[body].point(g.db);
            let u = dir_of(s, g.a, g.axis);
            (p - a).dot(&u)
        }
        Solver::SlottedLever { body, ja, js } => {
            let g = &joints[js];
            let (a, _) = pin(&joints[ja], s, body);
            let p = point_of(s, g.b, g.db);
            tangent_side(&s[body], g.axis, p - a)
        }
        _ => 1.0,
    }
}

/// Place the links of a closed-form group. `sign` is the branch of the drawing (from
/// [`branch_quantity`]); `s` holds the solved links' states. [`Solver::Newton`] has no
/// closed form (it is solved by [`crate::kernel::group::group_solve`]) and gives `NoAssembly` here.
///
/// Returns the group's joint points found on the way, for the rates that follow
/// ([`crate::kernel::natural`]): an RRR dyad's [A, B, C] (b₁'s pin, the middle pin, b₂'s pin),
/// an RRP dyad's [A, C, (x, y)] (b₁'s pin, the slider's pin, and C − A = x u + y perp(u)
/// in the guide's frame, x straight from the square root), an RPR dyad's [A, B, (x, y)]
/// (the guide's pin, the slider's pin, and B − A = x u + y perp(u) in the frame of the
/// guide's turned axis u, x straight from the square root), a PRP dyad's [C, 0, 0] (the
/// sliders' pin), an RPP dyad's [A, 0, 0] (b₁'s pin), a slotted slider's
/// [(1/(u × w), 0), 0, 0] ([`slotted_slider`](crate::kernel::slotted::slotted_slider)); zeros for the other kinds.
#[cfg_attr(debug_assertions, inline)]
#[cfg_attr(not(debug_assertions), inline(always))]
pub fn position(
    solver: Solver,
    joints: &[JointGeom],
    s: &mut [LinkState],
    drive: Drive,
    sign: f64,
) -> Result<[V2; 3], MechError> {
    let mut points = [V2::zeros(); 3];
    match solver {
        Solver::DrivenRevolute { body, joint, input } => {
            driven_revolute(&joints[joint], s, body, drive.0[input])
        }
        Solver::DrivenPrismatic { body, joint, input } => {
            driven_prismatic(&joints[joint], s, body, drive.0[input])
        }
        Solver::Rrr { b1, b2, ja, jc, jb } => {
            points = rrr(joints, s, b1, b2, [ja, jc, jb], sign)?;
        }
        Solver::Rrp { b1, b2, ja, jc, jp } => {
            points = rrp(joints, s, b1, b2, [ja, jc, jp], sign)?;
        }
        Solver::Rpr { b1, b2, ja, jp, jb } => {
            // Branched once on the orientation, so that every index is a constant.
            points = if joints[jp].a == b1 {
                rpr(joints, s, [b1, b2], [ja, jp, jb], sign)?
            } else {
                rpr(joints, s, [b2, b1], [jb, jp, ja], sign)?
            };
        }
        Solver::Prp {
            b1,
            b2,
            jp1,
            jc,
            jp2,
        } => points[0] = prp(joints, s, b1, b2, [jp1, jc, jp2])?,
        Solver::Rpp { b1, b2, ja, jp, jq } => points[0] = rpp(joints, s, b1, b2, [ja, jp, jq])?,
        Solver::PinInFixedSlot { body, ja, js } => {
            let (a, da) = pin(&joints[ja], s, body);
            let g = &joints[js];
            let u = dir_of(s, g.a, g.axis);
            let q = point_of(s, g.a, g.da);
            let p = circle_line(a, (g.db - da).norm_squared(), q, u, sign)?;
            place_by_two_points(&mut s[body], da, g.db, a, p);
        }
        Solver::SlottedLever { body, ja, js } => {
            let g = &joints[js];
            let pa = pin(&joints[ja], s, body);
            let pb = (point_of(s, g.b, g.db), g.db);
            let (dvec, w) = rpr_data(g, pa, pb, false);
            let (rot, ..) = tangent_rotation(g.axis, dvec, w, sign)?;
            place_by_point(&mut s[body], rot, pa.1, pa.0);
        }
        Solver::SlottedSlider { body, jq, js } => {
            points[0].x =
                crate::kernel::slotted::slotted_slider(&joints[jq], &joints[js], s, body)?;
        }
        Solver::Newton
        | Solver::Mesh { .. }
        | Solver::Train
        | Solver::DrivenRolling { .. }
        | Solver::Cam { .. }
        | Solver::Rrl { .. } => return Err(MechError::NoAssembly),
    }
    Ok(points)
}

/// [`position`] of a link driven by its revolute joint `g` at the input's angle `q`.
#[inline(always)]
fn driven_revolute(g: &JointGeom, s: &mut [LinkState], body: usize, q: f64) {
    let (sn, cs) = (q - g.q_ref).sin_cos();
    let (other, rel) = if g.b == body {
        (g.a, V2::new(cs, sn))
    } else {
        (g.b, V2::new(cs, -sn))
    };
    let rot = if other == 0 {
        rel
    } else {
        rotate(s[other].rot, rel)
    };
    let (p, d) = pin(g, s, body);
    place_by_point(&mut s[body], rot, d, p);
}

/// [`position`] of a link driven by its prismatic joint `g` at the input's length `q`.
#[inline(always)]
fn driven_prismatic(g: &JointGeom, s: &mut [LinkState], body: usize, q: f64) {
    let q = q - g.q_ref;
    if g.b == body {
        let p = point_of(s, g.a, g.da) + dir_of(s, g.a, g.axis) * q;
        place_as(s, body, g.a, g.db, p);
    } else {
        let p = point_of(s, g.b, g.db) - dir_of(s, g.b, g.axis) * q;
        place_as(s, body, g.b, g.da, p);
    }
}

/// [`position`] of an RRR dyad, joints [ja, jc, jb]; its points [A, C, B].
#[inline(always)]
fn rrr(
    joints: &[JointGeom],
    s: &mut [LinkState],
    b1: usize,
    b2: usize,
    [ja, jc, jb]: [usize; 3],
    sign: f64,
) -> Result<[V2; 3], MechError> {
    let (a, da) = pin(&joints[ja], s, b1);
    let (b, db) = pin(&joints[jb], s, b2);
    let gc = &joints[jc];
    let (dc1, dc2) = if gc.a == b1 {
        (gc.da, gc.db)
    } else {
        (gc.db, gc.da)
    };
    let c = circle_circle(
        a,
        (dc1 - da).norm_squared(),
        b,
        (dc2 - db).norm_squared(),
        sign,
    )?;
    place_by_two_points(&mut s[b1], da, dc1, a, c);
    place_by_two_points(&mut s[b2], db, dc2, b, c);
    Ok([a, c, b])
}

/// [`position`] of an RRP dyad, joints [ja, jc, jp]; its points [A, C, (x, y)].
#[inline(always)]
fn rrp(
    joints: &[JointGeom],
    s: &mut [LinkState],
    b1: usize,
    b2: usize,
    [ja, jc, jp]: [usize; 3],
    sign: f64,
) -> Result<[V2; 3], MechError> {
    let (a, da) = pin(&joints[ja], s, b1);
    let gp = &joints[jp];
    // The slider turns with the guide: its vectors are the guide's rotation of its
    // local ones (none on the ground).
    let guide = if gp.b == b2 { gp.a } else { gp.b };
    let gc = &joints[jc];
    let (dc1, dc2) = if gc.a == b1 {
        (gc.da, gc.db)
    } else {
        (gc.db, gc.da)
    };
    let (q, dq) = if gp.b == b2 {
        (point_of(s, gp.a, gp.da), gp.db)
    } else {
        (point_of(s, gp.b, gp.db), gp.da)
    };
    let p = q + dir_of(s, guide, dc2 - dq);
    let u = dir_of(s, guide, gp.axis);
    let (c, x, y) = circle_line_along(a, (dc1 - da).norm_squared(), p, u, sign)?;
    place_by_two_points(&mut s[b1], da, dc1, a, c);
    s[b2].rot = if guide == 0 {
        V2::new(1.0, 0.0)
    } else {
        s[guide].rot
    };
    s[b2].pos = c - dir_of(s, guide, dc2);
    Ok([a, c, V2::new(x, y)])
}

/// [`position`] of an RPR dyad, its guide and slider `[guide, slider]` pinned by
/// `[jg, jp, js]` (the guide's pin, the prismatic, the slider's pin); its points
/// [A, B, (x, y)] ([`tangent_rotation`]).
#[inline(always)]
fn rpr(
    joints: &[JointGeom],
    s: &mut [LinkState],
    [guide, slider]: [usize; 2],
    [jg, jp, js]: [usize; 3],
    sign: f64,
) -> Result<[V2; 3], MechError> {
    let gp = &joints[jp];
    let (pa, pb) = (pin(&joints[jg], s, guide), pin(&joints[js], s, slider));
    let (dvec, w) = rpr_data(gp, pa, pb, true);
    let (rot, x, y) = tangent_rotation(gp.axis, dvec, w, sign)?;
    place_by_point(&mut s[guide], rot, pa.1, pa.0);
    place_by_point(&mut s[slider], rot, pb.1, pb.0);
    Ok([pa.0, pb.0, V2::new(x, y)])
}

/// [`position`] of a PRP dyad, joints [jp1, jc, jp2]; its pin C.
#[inline(always)]
fn prp(
    joints: &[JointGeom],
    s: &mut [LinkState],
    b1: usize,
    b2: usize,
    [jp1, jc, jp2]: [usize; 3],
) -> Result<V2, MechError> {
    let (g1, g2) = (&joints[jp1], &joints[jp2]);
    // Each slider turns with the link it slides on.
    let l1 = if g1.b == b1 { g1.a } else { g1.b };
    let l2 = if g2.b == b2 { g2.a } else { g2.b };
    let gc = &joints[jc];
    let (dc1, dc2) = if gc.a == b1 {
        (gc.da, gc.db)
    } else {
        (gc.db, gc.da)
    };
    let (p1, u1) = slide_line(g1, s, b1, l1, dc1);
    let (p2, u2) = slide_line(g2, s, b2, l2, dc2);
    let c = line_line(p1, u1, p2, u2)?;
    place_as(s, b1, l1, dc1, c);
    place_as(s, b2, l2, dc2, c);
    Ok(c)
}

/// [`position`] of an RPP dyad, joints [ja, jp, jq]; b₁'s pin A.
#[inline(always)]
fn rpp(
    joints: &[JointGeom],
    s: &mut [LinkState],
    b1: usize,
    b2: usize,
    [ja, jp, jq]: [usize; 3],
) -> Result<V2, MechError> {
    let gq = &joints[jq];
    // Both links turn with the one b₂ slides on.
    let l = if gq.b == b2 { gq.a } else { gq.b };
    let (a, da) = pin(&joints[ja], s, b1);
    place_as(s, b1, l, da, a);
    // The sliding point of b2 on the solved link, on both lines.
    let dq = if gq.b == b2 { gq.db } else { gq.da };
    let (p1, u1) = slide_line(gq, s, b2, l, dq);
    let (p2, u2) = slide_line(&joints[jp], s, b2, l, dq);
    let c = line_line(p1, u1, p2, u2)?;
    place_as(s, b2, l, dq, c);
    Ok(a)
}
