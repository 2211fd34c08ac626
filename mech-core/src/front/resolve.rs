//! Name resolution (check 1 of `docs/conventions.md#checks`): turns a [`Description`]
//! into a [`Model`], collecting every naming mistake at once.

use crate::model::*;
use std::collections::HashMap;

/// A message located at one or more places of the source. The first span is the culprit;
/// the others are the declarations involved.
#[derive(Clone, Debug, PartialEq)]
pub struct Diagnostic<S> {
    /// Where to point.
    pub spans: Vec<S>,
    /// What is wrong, the numbers, and how to fix it.
    pub message: String,
}

impl<S> Diagnostic<S> {
    /// A diagnostic at one place.
    pub fn at(span: S, message: impl Into<String>) -> Self {
        Diagnostic {
            spans: vec![span],
            message: message.into(),
        }
    }
}

/// A model item a check blames; mapped back to a span by [`Description::locate`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Culprit {
    /// The struct as a whole.
    Mechanism,
    /// Link `i` of the model (0 = ground).
    Link(usize),
    /// The `mass` of link `i`.
    Mass(usize),
    /// The `inertia` of link `i`.
    Inertia(usize),
    /// The `cg` of link `i`.
    Cg(usize),
    /// Joint `i`.
    Joint(usize),
    /// The `along` axis of joint `i`.
    Axis(usize),
    /// Point `i` (its definition).
    Point(usize),
    /// The `input`/`inputs` declaration.
    Inputs,
    /// The gravity vector.
    Gravity,
    /// Force element `i` (its coefficient).
    Element(usize),
}

/// A problem found by a check on a resolved [`Model`].
#[derive(Clone, Debug, PartialEq)]
pub struct Issue {
    /// The items involved, culprit first.
    pub culprits: Vec<Culprit>,
    /// The message.
    pub message: String,
}

impl<S: Clone> Description<S> {
    fn link_decl(&self, i: usize) -> &LinkDecl<S> {
        if i == 0 {
            &self.ground
        } else {
            &self.links[i - 1]
        }
    }

    /// The source location of a model item.
    pub fn locate(&self, model: &Model, c: Culprit) -> S {
        match c {
            Culprit::Mechanism => self.name.span.clone(),
            Culprit::Link(i) => self.link_decl(i).name.span.clone(),
            Culprit::Mass(i) => {
                let l = self.link_decl(i);
                l.mass
                    .as_ref()
                    .map(|m| m.span.clone())
                    .unwrap_or_else(|| l.name.span.clone())
            }
            Culprit::Inertia(i) => {
                let l = self.link_decl(i);
                l.inertia
                    .as_ref()
                    .map(|m| m.span.clone())
                    .unwrap_or_else(|| l.name.span.clone())
            }
            Culprit::Cg(i) => {
                let l = self.link_decl(i);
                l.cg.as_ref()
                    .map(|m| m.span.clone())
                    .unwrap_or_else(|| l.name.span.clone())
            }
            Culprit::Joint(i) => self.joints[i].name.span.clone(),
            Culprit::Axis(i) => {
                let j = &self.joints[i];
                j.along
                    .as_ref()
                    .map(|a| a.span.clone())
                    .unwrap_or_else(|| j.kind_span.clone())
            }
            Culprit::Point(i) => {
                let n = &model.points[i].name;
                std::iter::once(&self.ground)
                    .chain(self.links.iter())
                    .flat_map(|l| l.points.iter())
                    .find(|p| &p.name.text == n && p.at.is_some())
                    .map(|p| p.name.span.clone())
                    .unwrap_or_else(|| self.name.span.clone())
            }
            Culprit::Inputs => self.inputs_span.clone(),
            Culprit::Element(i) => self.elements[i].coefficient.span.clone(),
            Culprit::Gravity => self
                .gravity
                .as_ref()
                .map(|g| g.span.clone())
                .unwrap_or_else(|| self.name.span.clone()),
        }
    }

    /// An [`Issue`] located in this description.
    pub fn diagnostic(&self, model: &Model, issue: &Issue) -> Diagnostic<S> {
        let mut spans: Vec<S> = issue
            .culprits
            .iter()
            .map(|&c| self.locate(model, c))
            .collect();
        if spans.is_empty() {
            spans.push(self.name.span.clone());
        }
        Diagnostic {
            spans,
            message: issue.message.clone(),
        }
    }
}

fn dup_check<'a, S: Clone + 'a>(
    what: &str,
    names: impl Iterator<Item = &'a Name<S>>,
    errs: &mut Vec<Diagnostic<S>>,
) {
    let mut seen: HashMap<&str, ()> = HashMap::new();
    for n in names {
        if seen.insert(n.text.as_str(), ()).is_some() {
            errs.push(Diagnostic::at(
                n.span.clone(),
                format!(
                    "duplicate {what} `{}`: every {what} needs its own name",
                    n.text
                ),
            ));
        }
    }
}

fn list(names: &[&str]) -> String {
    if names.is_empty() {
        return "(none)".into();
    }
    names
        .iter()
        .map(|n| format!("`{n}`"))
        .collect::<Vec<_>>()
        .join(", ")
}

/// Resolve names; on success the model's links, joints and loads are in declaration
/// order (ground first), points in order of definition.
pub fn resolve<S: Clone>(d: &Description<S>) -> Result<Model, Vec<Diagnostic<S>>> {
    let mut errs = Vec::new();
    let decls: Vec<&LinkDecl<S>> = std::iter::once(&d.ground).chain(d.links.iter()).collect();

    dup_check("link", decls.iter().map(|l| &l.name), &mut errs);
    dup_check("joint", d.joints.iter().map(|j| &j.name), &mut errs);
    dup_check("load", d.loads.iter().map(|l| &l.name), &mut errs);
    dup_check("input", d.inputs.iter().map(|i| &i.name), &mut errs);
    dup_check("element", d.elements.iter().map(|e| &e.name), &mut errs);

    // Points: defined once, reused by name.
    let mut points: Vec<Point> = Vec::new();
    let mut point_ix: HashMap<String, usize> = HashMap::new();
    for l in &decls {
        for p in &l.points {
            if let Some(at) = &p.at {
                if point_ix.contains_key(&p.name.text) {
                    errs.push(Diagnostic::at(
                        p.name.span.clone(),
                        format!(
                            "point `{}` is defined twice: give its coordinates once and reuse it by name elsewhere (`{}` alone)",
                            p.name.text, p.name.text
                        ),
                    ));
                } else {
                    point_ix.insert(p.name.text.clone(), points.len());
                    points.push(Point {
                        name: p.name.text.clone(),
                        pos: at.value,
                    });
                }
            }
        }
    }
    let mut links = Vec::new();
    for l in &decls {
        let mut pts = Vec::new();
        for p in &l.points {
            match point_ix.get(&p.name.text) {
                Some(&i) => {
                    if pts.contains(&i) {
                        errs.push(Diagnostic::at(
                            p.name.span.clone(),
                            format!("point `{}` is listed twice in link `{}`", p.name.text, l.name.text),
                        ));
                    } else {
                        pts.push(i)
                    }
                }
                None => errs.push(Diagnostic::at(
                    p.name.span.clone(),
                    format!(
                        "unknown point `{}`: no link defines it; define it once with its coordinates, e.g. `{}: (0.1, 0.2)`",
                        p.name.text, p.name.text
                    ),
                )),
            }
        }
        if let (Some(m), None) = (&l.mass, &l.cg) {
            errs.push(Diagnostic::at(
                m.span.clone(),
                format!("link `{}` has a mass but no `cg`: add `cg: (x, y)`, its centre of gravity in the drawing", l.name.text),
            ));
        }
        links.push(Link {
            name: l.name.text.clone(),
            points: pts,
            mass: l.mass.as_ref().map(|m| m.value),
            inertia: l.inertia.as_ref().map(|m| m.value).unwrap_or(0.0),
            flywheel: 0.0,
            cg: l.cg.as_ref().map(|c| c.value).unwrap_or_else(|| {
                l.points
                    .iter()
                    .find_map(|p| point_ix.get(&p.name.text))
                    .map(|&i| points[i].pos)
                    .unwrap_or([0.0, 0.0])
            }),
        });
    }
    let link_names: Vec<&str> = links.iter().map(|l| l.name.as_str()).collect();
    let find_link = |n: &Name<S>, errs: &mut Vec<Diagnostic<S>>| -> Option<usize> {
        let r = links.iter().position(|l| l.name == n.text);
        if r.is_none() {
            errs.push(Diagnostic::at(
                n.span.clone(),
                format!(
                    "unknown link `{}`: the links are {}",
                    n.text,
                    list(&link_names)
                ),
            ));
        }
        r
    };

    // Joints.
    let mut joints = Vec::new();
    let mut reached = vec![false; links.len()];
    reached[0] = true;
    for j in &d.joints {
        let a = find_link(&j.a, &mut errs);
        let b = find_link(&j.b, &mut errs);
        let pname = j.at.as_ref().unwrap_or(&j.name);
        let point = if j.kind == JointKind::Cam {
            // A rocker's pitch point is written (`at P`); a translating follower's is its
            // slide's point, found with the carrier below.
            match &j.at {
                Some(at) => point_ix.get(&at.text).copied(),
                None => Some(0),
            }
        } else if j.kind.mesh() {
            // A mesh is placed by its gears' centres, found once every joint is known.
            if let Some(at) = &j.at {
                errs.push(Diagnostic::at(
                    at.span.clone(),
                    format!("{} `{}` takes no `at`: its pitch point follows from the centres of its gears and their radii", j.kind.keyword(), j.name.text),
                ));
            }
            Some(0)
        } else {
            point_ix.get(&pname.text).copied()
        };
        if point.is_none() {
            let how = if j.at.is_none() {
                format!("joint `{}` has no `at POINT`, so it is placed at the point of the same name, and there is no point `{}`; add `at P`", j.name.text, pname.text)
            } else {
                format!("unknown point `{}` in joint `{}`", pname.text, j.name.text)
            };
            errs.push(Diagnostic::at(pname.span.clone(), how));
        }
        if let (Some(a), Some(b)) = (a, b) {
            if a == b {
                errs.push(Diagnostic::at(
                    j.b.span.clone(),
                    format!(
                        "joint `{}` joins link `{}` with itself: a joint needs two different links",
                        j.name.text, links[a].name
                    ),
                ));
            } else {
                reached[a] = true;
                reached[b] = true;
            }
        }
        let around = match (&j.around, j.kind) {
            (Some((d, inside)), JointKind::Rolling) => {
                match point_ix.get(&d.text).copied() {
                    Some(di) => Some((di, *inside)),
                    _ => {
                        errs.push(Diagnostic::at(
                        d.span.clone(),
                        format!("unknown point `{}`: the centre of rolling joint `{}`'s circular track", d.text, j.name.text),
                    ));
                        None
                    }
                }
            }
            _ => None,
        };
        let axis = match (j.kind, &j.along) {
            (JointKind::Revolute, Some(al)) => {
                errs.push(Diagnostic::at(
                    al.span.clone(),
                    format!("revolute joint `{}` takes no `along` axis", j.name.text),
                ));
                [0.0, 0.0]
            }
            (JointKind::Revolute, None) => [0.0, 0.0],
            (k, Some(al)) if k.mesh() => {
                errs.push(Diagnostic::at(
                    al.span.clone(),
                    format!("{} `{}` takes no `along` axis (a rack slides along its prismatic joint's axis)", k.keyword(), j.name.text),
                ));
                [0.0, 0.0]
            }
            (k, None) if k.mesh() || k == JointKind::Cam => [0.0, 0.0],
            (JointKind::Rolling, None) if around.is_some() => [0.0, 0.0],
            (JointKind::Rolling, Some(al)) if around.is_some() => {
                errs.push(Diagnostic::at(
                    al.span.clone(),
                    format!("rolling joint `{}` rolls around a circle: it takes `around D` or `along (ux, uy)`, not both", j.name.text),
                ));
                [0.0, 0.0]
            }
            (_, Some(al)) => al.value,
            (k, None) => {
                errs.push(Diagnostic::at(
                    j.kind_span.clone(),
                    format!(
                        "{} joint `{}` needs its sliding axis: add `along (ux, uy)`",
                        k.keyword(),
                        j.name.text
                    ),
                ));
                [1.0, 0.0]
            }
        };
        if let (Some(a), Some(b), Some(p)) = (a, b, point) {
            let pn = &points[p].name;
            match j.kind {
                JointKind::Revolute => {
                    for (l, side) in [(a, &j.a), (b, &j.b)] {
                        if !links[l].points.contains(&p) {
                            errs.push(Diagnostic::at(
                                side.span.clone(),
                                format!(
                                    "revolute joint `{}` is at point `{pn}`, which link `{}` does not have; list `{pn}` among the points of `{}`",
                                    j.name.text, links[l].name, links[l].name
                                ),
                            ));
                        }
                    }
                }
                JointKind::Gear | JointKind::Rack | JointKind::Cam => {}
                JointKind::Prismatic | JointKind::PinInSlot | JointKind::Rolling => {
                    if let (Some((di, _)), Some((dn, _))) = (around, &j.around) {
                        if !links[a].points.contains(&di) {
                            errs.push(Diagnostic::at(
                                dn.span.clone(),
                                format!("rolling joint `{}` rolls around `{}`, which must be a point of the track `{}`; list it among `{}`'s points", j.name.text, dn.text, links[a].name, links[a].name),
                            ));
                        }
                    }
                    if !links[b].points.contains(&p) {
                        errs.push(Diagnostic::at(
                            j.b.span.clone(),
                            format!(
                                "{} joint `{}` is at point `{pn}`, which must be a point of `{}` ({}); list it among `{}`'s points",
                                j.kind.keyword(), j.name.text, links[b].name,
                                if j.kind == JointKind::Rolling { "the wheel's centre" } else { "the slider or pin" },
                                links[b].name
                            ),
                        ));
                    }
                    if links[a].points.contains(&p) {
                        errs.push(Diagnostic::at(
                            j.a.span.clone(),
                            format!(
                                "{} joint `{}`: point `{pn}` belongs to the slider `{}` and must not be listed among the points of the guide `{}` (the guide is given by the axis alone)",
                                j.kind.keyword(), j.name.text, links[b].name, links[a].name
                            ),
                        ));
                    }
                }
            }
        }
        joints.push(Joint {
            name: j.name.text.clone(),
            kind: j.kind,
            a: a.unwrap_or(0),
            b: b.unwrap_or(0),
            point: point.unwrap_or(0),
            axis,
            mesh: None,
            radius: if j.kind == JointKind::Rolling {
                j.mesh.as_ref().map(|m| m.radii.value[0]).unwrap_or(0.0)
            } else {
                0.0
            },
            around,
            cam: None,
        });
    }
    // Cams: the carrier the cam is pinned to and the follower slides on (or is pinned to).
    for (k, j) in d.joints.iter().enumerate() {
        let Some(decl) = &j.cam else { continue };
        let (a, b) = (joints[k].a, joints[k].b);
        if a == b {
            continue;
        }
        let found = [JointKind::Prismatic, JointKind::Revolute]
            .iter()
            .find_map(|&kind| {
                joints.iter().enumerate().find_map(|(i, sl)| {
                    if sl.kind != kind || !(sl.a == b || sl.b == b) {
                        return None;
                    }
                    let c = if sl.a == b { sl.b } else { sl.a };
                    let pin = joints.iter().find(|r| {
                        c != a
                            && r.kind == JointKind::Revolute
                            && ((r.a == c && r.b == a) || (r.b == c && r.a == a))
                    })?;
                    Some((c, pin.point, i))
                })
            });
        let Some((carrier, centre, slide)) = found else {
            errs.push(Diagnostic::at(
                j.kind_span.clone(),
                format!(
                    "cam `{}`: the follower `{}` must slide (a prismatic joint) on the link the cam `{}` is pinned to (a revolute joint at the cam's centre), or be pinned to it (an oscillating follower); no link carries both",
                    j.name.text, links[b].name, links[a].name
                ),
            ));
            continue;
        };
        let rocker = joints[slide].kind == JointKind::Revolute;
        let lifts = decl.angular.unwrap_or(rocker);
        if lifts != rocker {
            let (how, why) = if rocker {
                ("angles (`rise 15 deg`)", "turns about its pin")
            } else {
                ("lengths (`rise 10 mm`)", "slides on its prismatic joint")
            };
            errs.push(Diagnostic::at(
                decl.law_span.clone(),
                format!(
                    "cam `{}`: its follower `{}` {why} `{}` on `{}`, so its lifts are {how}, but they are written as {}",
                    j.name.text,
                    links[b].name,
                    d.joints[slide].name.text,
                    links[carrier].name,
                    if lifts { "angles" } else { "lengths" }
                ),
            ));
            continue;
        }
        match (&j.at, rocker) {
            (Some(at), false) => {
                errs.push(Diagnostic::at(
                    at.span.clone(),
                    format!("cam `{}` takes no `at`: its follower `{}` slides, and its pitch point is its prismatic joint's point", j.name.text, links[b].name),
                ));
                continue;
            }
            (None, true) => {
                errs.push(Diagnostic::at(
                    j.kind_span.clone(),
                    format!("cam `{}`: its follower `{}` is pinned to `{}` (an oscillating follower), so the cam needs its pitch point: write `cam({}, {}) at P ..`, P the roller's centre (the knife's edge, the flat face's point on the base circle) in the drawing", j.name.text, links[b].name, links[carrier].name, links[a].name, links[b].name),
                ));
                continue;
            }
            (None, false) => joints[k].point = joints[slide].point,
            (Some(_), true) => {}
        }
        joints[k].cam = Some(Box::new(CamSpec {
            base_radius: decl.base_radius.value,
            face: decl.face,
            segments: decl.segments.iter().map(|(g, _)| *g).collect(),
            table: decl.table.clone(),
            carrier,
            centre,
            slide,
            angular: rocker,
        }));
    }
    // Gear pairs and racks: their carrier and centres, now that every joint is known.
    for (k, j) in d.joints.iter().enumerate() {
        if let (Some(decl), true) = (&j.mesh, j.kind.mesh()) {
            if joints[k].a == joints[k].b {
                continue;
            }
            match mesh_of(&joints, &links, &points, k, decl) {
                Ok(m) => {
                    joints[k].point = m.centres[0];
                    joints[k].mesh = Some(m);
                }
                Err(msg) => errs.push(Diagnostic::at(j.kind_span.clone(), msg)),
            }
        }
    }
    for (i, l) in decls.iter().enumerate() {
        let first_of_its_name = decls[..i].iter().all(|d| d.name.text != l.name.text);
        if !reached[i] && first_of_its_name {
            errs.push(Diagnostic::at(
                l.name.span.clone(),
                format!(
                    "link `{}` is not reached by any joint: connect it with a joint or remove it",
                    l.name.text
                ),
            ));
        }
    }

    // Shared points must be pinned by a revolute joint (only once the names are right:
    // a misspelt link in a joint would otherwise look like a missing pin).
    let names_ok = errs.is_empty();
    for (pi, p) in points.iter().enumerate().filter(|_| names_ok) {
        let owners: Vec<usize> = (0..links.len())
            .filter(|&l| links[l].points.contains(&pi))
            .collect();
        for w in 1..owners.len() {
            for v in 0..w {
                let (l1, l2) = (owners[v], owners[w]);
                let pinned = joints.iter().any(|j| {
                    j.kind == JointKind::Revolute
                        && j.point == pi
                        && ((j.a == l1 && j.b == l2) || (j.a == l2 && j.b == l1))
                });
                // Links pinned through a third at the same point (a ternary pin) are fine.
                let via_third = owners.iter().any(|&l3| {
                    l3 != l1
                        && l3 != l2
                        && [l1, l2].iter().all(|&lx| {
                            joints.iter().any(|j| {
                                j.kind == JointKind::Revolute
                                    && j.point == pi
                                    && ((j.a == lx && j.b == l3) || (j.a == l3 && j.b == lx))
                            })
                        })
                });
                if !pinned && !via_third {
                    let span = decls[l2]
                        .points
                        .iter()
                        .find(|r| r.name.text == p.name)
                        .map(|r| r.name.span.clone())
                        .unwrap_or_else(|| decls[l2].name.span.clone());
                    errs.push(Diagnostic::at(
                        span,
                        format!(
                            "point `{}` is shared by links `{}` and `{}` but no revolute joint pins them there; a shared point is a pin: add `{}: revolute({}, {})`, or give one link its own point",
                            p.name, links[l1].name, links[l2].name, p.name, links[l1].name, links[l2].name
                        ),
                    ));
                }
            }
        }
    }

    // Inputs.
    let joint_names: Vec<&str> = d.joints.iter().map(|j| j.name.text.as_str()).collect();
    let mut inputs = Vec::new();
    let mut input_zero = Vec::new();
    for decl in &d.inputs {
        let i = &decl.name;
        if let Some(k) = d.joints.iter().position(|j| j.name.text == i.text) {
            match input_zero_of(decl, d.joints[k].kind) {
                Ok(z) => input_zero.push(z),
                Err(e) => errs.push(e),
            }
        }
        match d.joints.iter().position(|j| j.name.text == i.text) {
            None => errs.push(Diagnostic::at(
                i.span.clone(),
                format!(
                    "unknown joint `{}` as input: the joints are {}",
                    i.text,
                    list(&joint_names)
                ),
            )),
            Some(k) => {
                if d.joints[k].kind == JointKind::PinInSlot {
                    errs.push(Diagnostic::at(
                        i.span.clone(),
                        format!(
                            "input `{}` is a pin_in_slot joint, which cannot be driven: an input must be a revolute joint (a motor torque) or a prismatic joint (an actuator force)",
                            i.text
                        ),
                    ));
                }
                inputs.push(k);
            }
        }
    }

    // Loads.
    let mut loads = Vec::new();
    for l in &d.loads {
        match &l.kind {
            LoadDeclKind::Torque { link } => {
                if let Some(li) = find_link(link, &mut errs) {
                    loads.push(Load::Torque {
                        name: l.name.text.clone(),
                        link: li,
                    });
                }
            }
            LoadDeclKind::Force { link, point } => {
                let li = find_link(link, &mut errs);
                let pi = point_ix.get(&point.text).copied();
                match (li, pi) {
                    (Some(li), Some(pi)) if links[li].points.contains(&pi) => {
                        loads.push(Load::Force {
                            name: l.name.text.clone(),
                            link: li,
                            point: pi,
                        })
                    }
                    (Some(li), _) => {
                        let names: Vec<&str> = links[li]
                            .points
                            .iter()
                            .map(|&p| points[p].name.as_str())
                            .collect();
                        errs.push(Diagnostic::at(
                            point.span.clone(),
                            format!(
                                "load `{}` acts at point `{}`, which link `{}` does not have; its points are {}",
                                l.name.text, point.text, links[li].name, list(&names)
                            ),
                        ))
                    }
                    _ => {}
                }
            }
        }
    }

    // Force elements: their links and points (the rest state after the model is built).
    let mut element_ends = Vec::new();
    for e in &d.elements {
        let end = |link: &Name<S>, at: &Option<Name<S>>, errs: &mut Vec<Diagnostic<S>>| {
            let li = find_link(link, errs)?;
            let Some(pt) = at else {
                return Some((li, None));
            };
            match point_ix.get(&pt.text).copied() {
                Some(pi) if links[li].points.contains(&pi) => Some((li, Some(pi))),
                _ => {
                    let names: Vec<&str> = links[li]
                        .points
                        .iter()
                        .map(|&p| points[p].name.as_str())
                        .collect();
                    errs.push(Diagnostic::at(
                        pt.span.clone(),
                        format!(
                            "{} `{}` is attached at point `{}`, which link `{}` does not have; its points are {}",
                            e.kind.keyword(), e.name.text, pt.text, links[li].name, list(&names)
                        ),
                    ));
                    None
                }
            }
        };
        let (ea, eb) = (end(&e.a, &e.pa, &mut errs), end(&e.b, &e.pb, &mut errs));
        if let (Some(ea), Some(eb)) = (ea, eb) {
            if ea.0 == eb.0 {
                errs.push(Diagnostic::at(
                    e.b.span.clone(),
                    format!(
                        "{} `{}` joins link `{}` to itself: a force element acts between two different links (one of them may be `ground`)",
                        e.kind.keyword(), e.name.text, links[ea.0].name
                    ),
                ));
            } else {
                element_ends.push((e, ea, eb));
            }
        }
    }

    if !errs.is_empty() {
        return Err(errs);
    }
    let mut model = Model {
        name: d.name.text.clone(),
        gravity: d.gravity.as_ref().map(|g| g.value),
        allow_redundant: d.allow_redundant,
        points,
        links,
        joints,
        inputs,
        input_zero,
        loads,
        elements: Vec::new(),
    };
    for (e, (a, pa), (b, pb)) in element_ends {
        match element_of(&model, e, a, b, pa.zip(pb).map(|(p, q)| [p, q])) {
            Ok(el) => model.elements.push(el),
            Err(diag) => errs.push(diag),
        }
    }
    if !errs.is_empty() {
        return Err(errs);
    }
    Ok(model)
}

/// The carrier and centres of the gear pair or rack `k` (`docs/conventions.md#gears`): a
/// gear's centre is the point of one of its revolute joints; a gear pair's carrier is a
/// link (not one of the gears) that has both centres among its points, so that their
/// distance is fixed; a rack's carrier is the link its prismatic joint slides on, which
/// must have the pinion's centre. Among several candidates, the centres whose distance is
/// nearest the pitch radii's sum (difference when internal) are taken.
fn mesh_of<S>(
    joints: &[Joint],
    links: &[Link],
    points: &[Point],
    k: usize,
    decl: &MeshDecl<S>,
) -> Result<Mesh, String> {
    let jt = &joints[k];
    let (a, b) = (jt.a, jt.b);
    let [ra, rb] = decl.radii.value;
    let pressure_angle = decl
        .pressure_angle
        .as_ref()
        .map(|p| p.value)
        .unwrap_or(20f64.to_radians());
    let centres_of = |l: usize| -> Vec<usize> {
        joints
            .iter()
            .filter(|o| o.kind == JointKind::Revolute && (o.a == l || o.b == l))
            .map(|o| o.point)
            .collect()
    };
    let dist = |p: usize, q: usize| {
        let (p, q) = (points[p].pos, points[q].pos);
        (q[0] - p[0]).hypot(q[1] - p[1])
    };
    let name = |l: usize| links[l].name.as_str();
    if jt.kind == JointKind::Rack {
        let slide = joints.iter().find(|o| {
            o.kind == JointKind::Prismatic && (o.b == b || o.a == b) && (o.a != a && o.b != a)
        });
        let Some(slide) = slide else {
            return Err(format!("rack `{}`: the rack `{}` must slide (a prismatic joint) on the link that carries the pinion `{}`; it has no prismatic joint", jt.name, name(b), name(a)));
        };
        let carrier = if slide.a == b { slide.b } else { slide.a };
        let Some(&centre) = centres_of(a)
            .iter()
            .find(|&&p| links[carrier].points.contains(&p))
        else {
            return Err(format!("rack `{}`: the pinion `{}` must be pinned (a revolute joint) at its centre to `{}`, the link the rack slides on", jt.name, name(a), name(carrier)));
        };
        return Ok(Mesh {
            ra,
            rb: 0.0,
            internal: false,
            pressure_angle,
            carrier,
            centres: [centre, slide.point],
        });
    }
    let want = if decl.internal {
        (rb - ra).abs()
    } else {
        ra + rb
    };
    let mut best: Option<(f64, Mesh)> = None;
    for &pa in &centres_of(a) {
        for &pb in &centres_of(b) {
            if pa == pb {
                continue;
            }
            for (c, l) in links.iter().enumerate() {
                if c == a || c == b || !l.points.contains(&pa) || !l.points.contains(&pb) {
                    continue;
                }
                let miss = (dist(pa, pb) - want).abs();
                if best.as_ref().is_none_or(|(m, _)| miss < *m) {
                    best = Some((
                        miss,
                        Mesh {
                            ra,
                            rb,
                            internal: decl.internal,
                            pressure_angle,
                            carrier: c,
                            centres: [pa, pb],
                        },
                    ));
                }
            }
        }
    }
    best.map(|(_, m)| m).ok_or_else(|| {
        format!(
            "gear pair `{}`: `{}` and `{}` must each be pinned (a revolute joint) at its centre, and one carrier link (the ground or an arm) must hold both centres among its points; no link holds a centre of each",
            jt.name,
            name(a),
            name(b)
        )
    })
}

/// A resolved force element; a preload becomes the free length (angle) that gives it in
/// the drawing: x₀ = x_drawing − F₀/k.
fn element_of<S: Clone>(
    model: &Model,
    e: &ElementDecl<S>,
    a: usize,
    b: usize,
    points: Option<[usize; 2]>,
) -> Result<Element, Diagnostic<S>> {
    let k = e.coefficient.value;
    let drawn = match points {
        Some([p, q]) => {
            let (p, q) = (model.points[p].pos, model.points[q].pos);
            (q[0] - p[0]).hypot(q[1] - p[1])
        }
        None => model.reference_angle(b) - model.reference_angle(a),
    };
    let free = match &e.rest {
        None => 0.0,
        Some(RestDecl::Free(x)) => x.value,
        Some(RestDecl::Preload(f)) => {
            if !(k > 0.0) {
                return Err(Diagnostic::at(
                    f.span.clone(),
                    format!(
                        "{} `{}` has a preload but stiffness {k}: a preload needs a positive stiffness (free length = drawn length − preload / stiffness)",
                        e.kind.keyword(), e.name.text
                    ),
                ));
            }
            drawn - f.value / k
        }
    };
    let spring = e.kind.spring();
    Ok(Element {
        name: e.name.text.clone(),
        kind: e.kind,
        a,
        b,
        points,
        stiffness: if spring { k } else { 0.0 },
        damping: if spring { 0.0 } else { k },
        free,
    })
}

/// The zero of an input (`from z`): an angle on a revolute joint, a length on a
/// prismatic one (a plain number is SI: rad or m).
fn input_zero_of<S: Clone>(decl: &InputDecl<S>, kind: JointKind) -> Result<f64, Diagnostic<S>> {
    let Some(z) = &decl.from else { return Ok(0.0) };
    let want = if kind == JointKind::Revolute {
        crate::model::units::Dim::ANGLE
    } else {
        crate::model::units::Dim::LENGTH
    };
    match z.dim.filter(|d| *d != crate::model::units::Dim::NONE) {
        Some(d) if d != want => Err(Diagnostic::at(
            z.span.clone(),
            format!(
                "the zero of input `{}`, a {} joint, is {}, but this value is {}: write it with {}, or as a plain number in SI",
                decl.name.text,
                kind.keyword(),
                want.describe(),
                d.describe(),
                want.words()
            ),
        )),
        _ => Ok(z.value),
    }
}

/// Parse and resolve DSL text, for the unit tests of the checks.
#[cfg(test)]
pub(crate) fn model_of(text: &str) -> Model {
    resolve(&crate::front::dsl::parse_str(text).expect("parse")).expect("resolve")
}
