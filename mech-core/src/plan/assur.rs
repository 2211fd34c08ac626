//! Assur groups: the decomposition of a chain, with its inputs fixed, into the smallest
//! sub-chains that can be solved one after the other (`docs/theory.md` §2), and their
//! position kernels — closed forms for the common groups, Newton for the rest.
//!
//! A group is a set of links whose constraints towards already-solved links and among
//! themselves are exactly 3 × (its links) scalar equations. The plan is found at compile
//! time by the macro (and at run time by the generic solver) with [`plan`]; the
//! generated code then calls [`crate::kernel::kinematics`] once per group with constant arguments.

use crate::elements::gears::{MeshGroup, TrainGroup, TRAIN_MAX};
use crate::kernel::constraints::{Con, ConKind};
use crate::kernel::dyad::Solver;
use crate::kernel::screw::{Chain, Driven, JointScrew, VIRTUAL};
use crate::kernel::triad::Triad;
use crate::model::{JointKind, Model};
use crate::plan::geometry::joint_cons;

/// One group of the plan.
#[derive(Clone, Debug, PartialEq)]
pub struct Group {
    /// Its links, in column order.
    pub bodies: Vec<usize>,
    /// Its constraints, in row order.
    pub cons: Vec<Con>,
    /// The position kernel.
    pub solver: Solver,
    /// The rates and reactions kernel.
    pub kernel: Kernel,
    /// A triad of revolute joints among the Newton groups: its positions by one
    /// eliminated unknown ([`crate::kernel::triad`]); `None` for the other groups.
    pub triad: Option<Triad>,
}

/// How a group's rates and reactions are solved.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Kernel {
    /// A driven crank or slider: one joint screw with a known rate.
    Driven(Driven),
    /// A closed-form dyad or slot group: a chain of three joint screws.
    Chain(Chain),
    /// One link meshing with a solved gear or rack: Willis' relation ([`crate::elements::gears`]).
    Mesh(MeshGroup),
    /// Links meshing with one another: Willis' relations as one small linear system.
    Train(TrainGroup),
    /// A follower driven by a cam ([`crate::elements::cam`]).
    Cam(crate::elements::cam::CamGroup),
    /// A rolling wheel, driven or at the end of a rod ([`crate::elements::rolling`]).
    Rolling(crate::elements::rolling::RollingGroup),
    /// No closed form: the group's scaled Jacobian, LU-factored.
    System,
}

/// The pivot of a chain (see [`Chain::pivot`]): its middle screw when that is a rotation,
/// else its first rotation (every closed-form chain has one).
fn pivot(screws: &[JointScrew; 3]) -> usize {
    if !screws[1].slide {
        1
    } else if !screws[0].slide {
        0
    } else {
        2
    }
}

/// The screw kernel of a closed-form solver ([`crate::kernel::screw`] docs): the chain of joint
/// screws from a solved link through the group's links to a solved link.
pub fn kernel(model: &Model, solver: Solver) -> Kernel {
    let other = |j: usize, body: usize| model.joints[j].across(body);
    let rot = |joint| JointScrew {
        joint,
        slide: false,
    };
    let slide = |joint| JointScrew { joint, slide: true };
    let sc = |j: usize| {
        if model.joints[j].kind == JointKind::Revolute {
            rot(j)
        } else {
            slide(j)
        }
    };
    let dyad = |b1, b2, j1: usize, j2: usize, j3: usize| {
        let screws = [sc(j1), sc(j2), sc(j3)];
        Kernel::Chain(Chain {
            from: other(j1, b1),
            to: other(j3, b2),
            screws,
            links: [b1, b2],
            pivot: pivot(&screws),
        })
    };
    match solver {
        Solver::DrivenRevolute { body, joint, input } => Kernel::Driven(Driven {
            from: other(joint, body),
            body,
            screw: rot(joint),
            input,
            pinned: other(joint, body) == 0 && model.pinned_at_anchor(body),
            track: false,
        }),
        Solver::DrivenPrismatic { body, joint, input } => Kernel::Driven(Driven {
            from: other(joint, body),
            body,
            screw: slide(joint),
            input,
            pinned: false,
            track: false,
        }),
        Solver::Rrr { b1, b2, ja, jc, jb } => dyad(b1, b2, ja, jc, jb),
        Solver::Rrp { b1, b2, ja, jc, jp } => dyad(b1, b2, ja, jc, jp),
        Solver::Rpr { b1, b2, ja, jp, jb } => dyad(b1, b2, ja, jp, jb),
        Solver::Prp {
            b1,
            b2,
            jp1,
            jc,
            jp2,
        } => dyad(b1, b2, jp1, jc, jp2),
        Solver::Rpp { b1, b2, ja, jp, jq } => dyad(b1, b2, ja, jp, jq),
        // Pin of `body` in a slot of a solved link: rotation about the pin, then the slide.
        Solver::PinInFixedSlot { body, ja, js } => Kernel::Chain(Chain {
            from: other(ja, body),
            to: model.joints[js].a,
            screws: [rot(ja), rot(js), slide(js)],
            links: [body, VIRTUAL],
            pivot: 1,
        }),
        // Slot in `body`, pin of a solved link: the slide, then the rotation about the pin.
        Solver::SlottedLever { body, ja, js } => Kernel::Chain(Chain {
            from: other(ja, body),
            to: model.joints[js].b,
            screws: [rot(ja), slide(js), rot(js)],
            links: [body, VIRTUAL],
            pivot: 0,
        }),
        // A guide and a slot: the slide on the guide, then the slot's two screws in chain
        // order (slot in `body`: its slide, then the rotation about the solved link's pin;
        // `body`'s pin in a solved link's slot: the rotation, then the slide). Their pivot
        // is the rotation; the 2×2 block left is [u w].
        Solver::SlottedSlider { body, jq, js } => {
            let screws = if model.joints[js].a == body {
                [slide(jq), slide(js), rot(js)]
            } else {
                [slide(jq), rot(js), slide(js)]
            };
            Kernel::Chain(Chain {
                from: other(jq, body),
                to: other(js, body),
                screws,
                links: [body, VIRTUAL],
                pivot: pivot(&screws),
            })
        }
        Solver::Mesh { body, joint } => mesh_kernel(model, body, joint),
        // Built from the group's constraints by `plan` (`train_kernel`).
        Solver::Train => Kernel::System,
        Solver::Cam { body, joint } => cam_kernel(model, body, joint),
        Solver::DrivenRolling { body, joint, input } => {
            Kernel::Rolling(crate::elements::rolling::RollingGroup::Driven { body, joint, input })
        }
        Solver::Rrl { b1, b2, ja, jc, jr } => {
            Kernel::Rolling(crate::elements::rolling::RollingGroup::Dyad { b1, b2, ja, jc, jr })
        }
        Solver::Newton => Kernel::System,
    }
}

/// The kernel of a link meshing with a solved one: its mesh joint, the joint that holds
/// it (a revolute at its centre, or a rack's slide), the partner and the carrier. The
/// mesh index counts the mesh joints in declaration order; `*_tracked` are set by [`plan`].
fn mesh_kernel(model: &Model, body: usize, joint: usize) -> Kernel {
    let touches = |j: usize| model.joints[j].a == body || model.joints[j].b == body;
    let mesh = (0..joint).filter(|&j| model.joints[j].kind.mesh()).count();
    let jt = &model.joints[joint];
    let Some(m) = jt.mesh.as_ref() else {
        return Kernel::System;
    };
    let partner = jt.across(body);
    let rack_link = (jt.kind == JointKind::Rack).then_some(jt.b);
    let slide = rack_link.and_then(|r| {
        (0..model.joints.len()).find(|&j| {
            let o = &model.joints[j];
            o.kind == JointKind::Prismatic
                && ((o.a == r && o.b == m.carrier) || (o.b == r && o.a == m.carrier))
        })
    });
    let body_slides = rack_link == Some(body);
    let pin = if body_slides {
        slide
    } else {
        let centre = if jt.a == body {
            m.centres[0]
        } else {
            m.centres[1]
        };
        (0..model.joints.len()).find(|&j| {
            let o = &model.joints[j];
            o.kind == JointKind::Revolute && touches(j) && o.point == centre
        })
    };
    let Some(pin) = pin else {
        return Kernel::System;
    };
    Kernel::Mesh(MeshGroup {
        body,
        pin,
        joint,
        mesh,
        partner,
        carrier: m.carrier,
        slide: slide.unwrap_or(pin),
        body_slides,
        partner_slides: rack_link == Some(partner),
        partner_tracked: false,
        carrier_tracked: false,
    })
}

/// The kernel of a follower driven by a cam: its slide, the cam, the carrier, and the cam's
/// index among the mechanism's cams.
fn cam_kernel(model: &Model, body: usize, joint: usize) -> Kernel {
    let jt = &model.joints[joint];
    let Some(c) = jt.cam.as_ref() else {
        return Kernel::System;
    };
    Kernel::Cam(crate::elements::cam::CamGroup {
        follower: body,
        slide: c.slide,
        joint,
        cam: jt.a,
        carrier: c.carrier,
        index: (0..joint)
            .filter(|&j| model.joints[j].kind == JointKind::Cam)
            .count(),
        cam_tracked: false,
        carrier_tracked: false,
    })
}

/// The kernel of a gear-train group ([`TrainGroup`]): each link's pin at its centre, the
/// meshes, and an order in which each link's pin partner is solved or placed before it.
fn train_kernel(model: &Model, bodies: &[usize], cons: &[Con]) -> Kernel {
    let n = bodies.len();
    let mut grp = TrainGroup {
        n,
        bodies: [0; TRAIN_MAX],
        pins: [0; TRAIN_MAX],
        meshes: [(0, 0); TRAIN_MAX],
        order: [0; TRAIN_MAX],
        tracked: 0,
        outer: [0; TRAIN_MAX],
        pin_b: [false; TRAIN_MAX],
        ends: [[0; 3]; TRAIN_MAX],
    };
    grp.bodies[..n].copy_from_slice(bodies);
    let mut k_mesh = 0;
    let mut has_pin = [false; TRAIN_MAX];
    let inside = |l: usize| bodies.iter().position(|&b| b == l);
    // Pins to solved links first, then pins between two links of the group (each given
    // to the end that has none yet).
    for pass in 0..2 {
        for c in cons.iter().filter(|c| c.kind == ConKind::Revolute) {
            let jt = &model.joints[c.joint];
            let ends = [inside(jt.a), inside(jt.b)];
            let k = match (pass, ends) {
                (0, [Some(k), None]) | (0, [None, Some(k)]) => k,
                (1, [Some(x), Some(y)]) => {
                    if !has_pin[y] {
                        y
                    } else {
                        x
                    }
                }
                _ => continue,
            };
            if has_pin[k] {
                return Kernel::System;
            }
            has_pin[k] = true;
            grp.pins[k] = c.joint;
        }
    }
    for c in cons.iter().filter(|c| c.kind == ConKind::Mesh) {
        let index = (0..c.joint)
            .filter(|&j| model.joints[j].kind.mesh())
            .count();
        grp.meshes[k_mesh] = (c.joint, index);
        // Each meshing link of the group turns about its pin: the pin is at its centre.
        let jt = &model.joints[c.joint];
        let Some(m) = jt.mesh.as_ref() else {
            return Kernel::System;
        };
        grp.ends[k_mesh] = [jt.a, jt.b, m.carrier];
        k_mesh += 1;
        for (l, centre) in [(jt.a, m.centres[0]), (jt.b, m.centres[1])] {
            if let Some(k) = inside(l) {
                if model.joints[grp.pins[k]].point != centre {
                    return Kernel::System;
                }
            }
        }
    }
    if has_pin[..n].iter().any(|h| !h) {
        return Kernel::System;
    }
    for k in 0..n {
        let jt = &model.joints[grp.pins[k]];
        grp.pin_b[k] = jt.b == bodies[k];
        grp.outer[k] = if grp.pin_b[k] { jt.a } else { jt.b };
    }
    let mut placed = vec![false; n];
    for slot in 0..n {
        let next = (0..n).find(|&k| {
            let jt = &model.joints[grp.pins[k]];
            let other = if jt.b == bodies[k] { jt.a } else { jt.b };
            !placed[k]
                && bodies
                    .iter()
                    .position(|&b| b == other)
                    .is_none_or(|o| placed[o])
        });
        let Some(k) = next else {
            return Kernel::System;
        };
        placed[k] = true;
        grp.order[slot] = k;
    }
    Kernel::Train(grp)
}

/// Which links' [`crate::kernel::link_state::LinkState::angle`] the plan keeps over turns: the
/// ground, a driven link whose base has it, a link sliding on one that has it, and a
/// meshing link (Willis from its partner and carrier); then each mesh group told whether
/// its partner's and carrier's are kept, and each cam group whether its cam's and
/// carrier's are (the cam's turn is then their difference, not an `atan2`).
fn track_angles(n: usize, groups: &mut [Group]) {
    let meshes = groups.iter().any(|g| {
        matches!(
            g.kernel,
            Kernel::Mesh(_) | Kernel::Train(_) | Kernel::Cam(_)
        )
    });
    let mut tracked = vec![false; n];
    tracked[0] = true;
    for g in groups.iter_mut() {
        match &mut g.kernel {
            Kernel::Driven(d) => {
                d.track = meshes;
                tracked[d.body] = meshes && tracked[d.from];
            }
            Kernel::Mesh(m) => {
                m.partner_tracked = tracked[m.partner];
                m.carrier_tracked = tracked[m.carrier];
                tracked[m.body] = true;
            }
            Kernel::Cam(c) => {
                c.cam_tracked = tracked[c.cam];
                c.carrier_tracked = tracked[c.carrier];
            }
            Kernel::Train(t) => {
                t.tracked = (0..n.min(64))
                    .filter(|&l| tracked[l])
                    .fold(0, |m, l| m | 1 << l);
                for &b in &t.bodies[..t.n] {
                    tracked[b] = true;
                }
            }
            _ => {}
        }
    }
}

impl Group {
    /// The number of scalar equations.
    pub fn rows(&self) -> usize {
        self.cons.iter().map(|c| c.kind.rows()).sum()
    }
    /// More equations than unknowns (accepted with `#[allow(redundant)]` only).
    pub fn redundant(&self) -> bool {
        self.rows() > 3 * self.bodies.len()
    }
}

/// Decompose the mechanism into groups, in solve order. `Err` names the links that no
/// group reaches (the chain is not determined by its inputs).
pub fn plan(model: &Model) -> Result<Vec<Group>, Vec<usize>> {
    let n = model.links.len();
    let mut known = vec![false; n];
    known[0] = true;
    let mut groups = Vec::new();
    let joints_between = |known: &[bool], set: &[usize]| -> Vec<usize> {
        let inside = |l: usize| known[l] || set.contains(&l);
        (0..model.joints.len())
            .filter(|&j| {
                let jt = &model.joints[j];
                inside(jt.a) && inside(jt.b) && (set.contains(&jt.a) || set.contains(&jt.b))
            })
            .collect()
    };
    while known.iter().any(|k| !k) {
        let unknown: Vec<usize> = (0..n).filter(|&l| !known[l]).collect();
        let mut found = None;
        'size: for size in 1..=unknown.len() {
            for set in subsets(&unknown, size) {
                let js = joints_between(&known, &set);
                let cons: Vec<Con> = js.iter().flat_map(|&j| joint_cons(model, j)).collect();
                let rows: usize = cons.iter().map(|c| c.kind.rows()).sum();
                let fits = rows == 3 * size || (model.allow_redundant && rows > 3 * size);
                if fits {
                    found = Some((set, cons));
                    break 'size;
                }
            }
        }
        let Some((bodies, cons)) = found else {
            return Err(unknown);
        };
        for &b in &bodies {
            known[b] = true;
        }
        // A redundant group (more rows than unknowns) is solved in the least-squares
        // sense by `kinematics::group_solve_ls`; its solver is Newton's.
        let solver = if cons.iter().map(|c| c.kind.rows()).sum::<usize>() == 3 * bodies.len() {
            classify(model, &bodies, &cons)
        } else {
            Solver::Newton
        };
        let kernel = match solver {
            Solver::Train => train_kernel(model, &bodies, &cons),
            _ => kernel(model, solver),
        };
        let triad = (solver == Solver::Newton)
            .then(|| triad(model, &bodies, &cons))
            .flatten();
        groups.push(Group {
            bodies,
            cons,
            solver,
            kernel,
            triad,
        });
    }
    track_angles(n, &mut groups);
    Ok(groups)
}

/// A triad of revolute joints ([`Triad`]): four links, six revolute joints, one link (the
/// ternary) pinned to the three others, each of which is pinned to a solved link. Of the
/// six orders of its binary links (lead, dyad, close), the one best conditioned in the
/// drawing: the largest product of the dyad's |sin| (between its two sides at the middle
/// pin) and the residual's |cos| (between the close link and its pin's velocity when the
/// lead turns), so that neither the dyad nor the residual's slope is near zero there.
fn triad(model: &Model, bodies: &[usize], cons: &[Con]) -> Option<Triad> {
    use crate::kernel::link_state::{cross, perp, V2};
    if bodies.len() != 4 || cons.len() != 6 || cons.iter().any(|c| c.kind != ConKind::Revolute) {
        return None;
    }
    let ends = |c: &Con| (model.joints[c.joint].a, model.joints[c.joint].b);
    let inside = |l: usize| bodies.contains(&l);
    let mid = *bodies.iter().find(|&&b| {
        cons.iter()
            .filter(|c| {
                let (a, o) = ends(c);
                (a == b && inside(o)) || (o == b && inside(a))
            })
            .count()
            == 3
    })?;
    let mut links = [0; 3];
    let (mut outer, mut inner) = ([0; 3], [0; 3]);
    for (k, &l) in bodies.iter().filter(|&&b| b != mid).enumerate() {
        let mine: Vec<&Con> = cons
            .iter()
            .filter(|c| ends(c).0 == l || ends(c).1 == l)
            .collect();
        let to_mid = mine
            .iter()
            .find(|c| ends(c) == (l, mid) || ends(c) == (mid, l))?;
        let out = mine.iter().find(|c| {
            let (a, b) = ends(c);
            let other = if a == l { b } else { a };
            !inside(other)
        })?;
        if mine.len() != 2 {
            return None;
        }
        (links[k], inner[k], outer[k]) = (l, to_mid.joint, out.joint);
    }
    let at = |j: usize| {
        let p = model.points[model.joints[j].point].pos;
        V2::new(p[0], p[1])
    };
    let score = |[i, j, k]: [usize; 3]| {
        let (a1, o1) = (at(inner[i]), at(outer[i]));
        let (b, o2) = (at(inner[j]), at(outer[j]));
        let (a3, o3) = (at(inner[k]), at(outer[k]));
        let (p, q) = (b - a1, b - o2);
        let c = cross(p, q);
        let da1 = perp(a1 - o1);
        let da3 = da1 + perp(a3 - a1) * (-da1.dot(&q) / c);
        let w = a3 - o3;
        let s = (c / (p.norm() * q.norm())).abs() * (w.dot(&da3) / (w.norm() * da3.norm())).abs();
        if s.is_finite() {
            s
        } else {
            0.0
        }
    };
    let orders = [
        [0, 1, 2],
        [0, 2, 1],
        [1, 0, 2],
        [1, 2, 0],
        [2, 0, 1],
        [2, 1, 0],
    ];
    let best = orders
        .into_iter()
        .fold((orders[0], -1.0), |(o, s), n| {
            let sn = score(n);
            if sn > s {
                (n, sn)
            } else {
                (o, s)
            }
        })
        .0;
    Some(Triad {
        mid,
        links: best.map(|k| links[k]),
        outer: best.map(|k| outer[k]),
        inner: best.map(|k| inner[k]),
    })
}

fn subsets(items: &[usize], k: usize) -> Vec<Vec<usize>> {
    if k == 0 {
        return vec![vec![]];
    }
    let mut out = Vec::new();
    for i in 0..items.len() {
        for mut rest in subsets(&items[i + 1..], k - 1) {
            rest.insert(0, items[i]);
            out.push(rest);
        }
    }
    out
}

/// Recognise a closed-form group.
fn classify(model: &Model, bodies: &[usize], cons: &[Con]) -> Solver {
    match *bodies {
        [body] => classify_single(model, body, cons),
        [x, y] if cons.len() == 3 => classify_dyad(model, x, y, cons),
        _ if is_train(model, bodies, cons) => Solver::Train,
        _ => Solver::Newton,
    }
}

/// A one-link group: driven by an input, held by a pin (or slide) and a mesh or cam, or
/// by a pin or a guide and a slot.
fn classify_single(model: &Model, body: usize, cons: &[Con]) -> Solver {
    let drive = cons.iter().find(|c| {
        matches!(
            c.kind,
            ConKind::DriveRevolute(_) | ConKind::DrivePrismatic(_)
        )
    });
    if let Some(d) = drive {
        return classify_driven(model, body, d);
    }
    let mesh = cons.iter().find(|c| c.kind == ConKind::Mesh);
    let held = cons
        .iter()
        .any(|c| matches!(c.kind, ConKind::Revolute | ConKind::Prismatic));
    if let (Some(m), true, 2) = (mesh, held, cons.len()) {
        if model.joints[m.joint].kind == JointKind::Cam {
            return if model.joints[m.joint].b == body {
                Solver::Cam {
                    body,
                    joint: m.joint,
                }
            } else {
                Solver::Newton
            };
        }
        return Solver::Mesh {
            body,
            joint: m.joint,
        };
    }
    let rev = cons.iter().find(|c| c.kind == ConKind::Revolute);
    let slot = cons.iter().find(|c| c.kind == ConKind::Slot);
    if let (Some(r), Some(s), 2) = (rev, slot, cons.len()) {
        return if model.joints[s.joint].b == body {
            Solver::PinInFixedSlot {
                body,
                ja: r.joint,
                js: s.joint,
            }
        } else {
            Solver::SlottedLever {
                body,
                ja: r.joint,
                js: s.joint,
            }
        };
    }
    let prismatic = cons.iter().find(|c| c.kind == ConKind::Prismatic);
    if let (Some(p), Some(s), 2) = (prismatic, slot, cons.len()) {
        return Solver::SlottedSlider {
            body,
            jq: p.joint,
            js: s.joint,
        };
    }
    Solver::Newton
}

/// A one-link group driven by the input of its driver row `d`.
fn classify_driven(model: &Model, body: usize, d: &Con) -> Solver {
    if let (ConKind::DrivePrismatic(k), JointKind::Rolling, None) = (
        d.kind,
        model.joints[d.joint].kind,
        model.joints[d.joint].around,
    ) {
        return Solver::DrivenRolling {
            body,
            joint: d.joint,
            input: k,
        };
    }
    match d.kind {
        ConKind::DriveRevolute(k) => Solver::DrivenRevolute {
            body,
            joint: d.joint,
            input: k,
        },
        ConKind::DrivePrismatic(k) => Solver::DrivenPrismatic {
            body,
            joint: d.joint,
            input: k,
        },
        _ => unreachable!(),
    }
}

/// A two-link group of three joints: the joint between the two links, and one joint from
/// each to solved links, in either order of the links.
fn classify_dyad(model: &Model, x: usize, y: usize, cons: &[Con]) -> Solver {
    let touches = |c: &Con, b: usize| model.joints[c.joint].a == b || model.joints[c.joint].b == b;
    // The joint between the two links, and one joint from each to solved links.
    let Some(mid) = cons.iter().find(|c| touches(c, x) && touches(c, y)) else {
        return Solver::Newton;
    };
    for (b1, b2) in [(x, y), (y, x)] {
        let outer1 = cons.iter().find(|c| touches(c, b1) && !touches(c, b2));
        let outer2 = cons.iter().find(|c| touches(c, b2) && !touches(c, b1));
        let (Some(o1), Some(o2)) = (outer1, outer2) else {
            return Solver::Newton;
        };
        if let Some(solver) = dyad_kind(model, b1, b2, o1, mid, o2) {
            return solver;
        }
    }
    Solver::Newton
}

/// The dyad of links `b1`, `b2` with joints `o1` (b₁ to a solved link), `mid` (between
/// them) and `o2` (b₂ to a solved link), when its kinds have a closed form.
fn dyad_kind(model: &Model, b1: usize, b2: usize, o1: &Con, mid: &Con, o2: &Con) -> Option<Solver> {
    let kind = |c: &Con| model.joints[c.joint].kind;
    match (kind(o1), kind(mid), kind(o2)) {
        (JointKind::Revolute, JointKind::Revolute, JointKind::Revolute) => Some(Solver::Rrr {
            b1,
            b2,
            ja: o1.joint,
            jc: mid.joint,
            jb: o2.joint,
        }),
        (JointKind::Revolute, JointKind::Revolute, JointKind::Rolling)
            if model.joints[o2.joint].b == b2
                && model.joints[mid.joint].point == model.joints[o2.joint].point =>
        {
            Some(Solver::Rrl {
                b1,
                b2,
                ja: o1.joint,
                jc: mid.joint,
                jr: o2.joint,
            })
        }
        (JointKind::Revolute, JointKind::Revolute, JointKind::Prismatic) => Some(Solver::Rrp {
            b1,
            b2,
            ja: o1.joint,
            jc: mid.joint,
            jp: o2.joint,
        }),
        (JointKind::Revolute, JointKind::Prismatic, JointKind::Revolute) => Some(Solver::Rpr {
            b1,
            b2,
            ja: o1.joint,
            jp: mid.joint,
            jb: o2.joint,
        }),
        (JointKind::Prismatic, JointKind::Revolute, JointKind::Prismatic) => Some(Solver::Prp {
            b1,
            b2,
            jp1: o1.joint,
            jc: mid.joint,
            jp2: o2.joint,
        }),
        (JointKind::Revolute, JointKind::Prismatic, JointKind::Prismatic) => Some(Solver::Rpp {
            b1,
            b2,
            ja: o1.joint,
            jp: mid.joint,
            jq: o2.joint,
        }),
        _ => None,
    }
}

/// A gear-train group ([`TrainGroup`]): up to [`TRAIN_MAX`] links, no driver, only
/// revolute joints and gear pairs, one revolute per link at its centre, as many gear pairs
/// as links.
fn is_train(model: &Model, bodies: &[usize], cons: &[Con]) -> bool {
    let n = bodies.len();
    if !(2..=TRAIN_MAX).contains(&n) {
        return false;
    }
    let meshes = cons.iter().filter(|c| c.kind == ConKind::Mesh).count();
    let revolutes = cons.iter().filter(|c| c.kind == ConKind::Revolute).count();
    let gears_only = cons
        .iter()
        .all(|c| c.kind != ConKind::Mesh || model.joints[c.joint].kind == JointKind::Gear);
    meshes == n && revolutes == n && meshes + revolutes == cons.len() && gears_only
}
