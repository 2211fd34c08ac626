//! The names and geometry of a parsed `space` text resolved into a `SpatialModel`.
//!
//! Points get their coordinates from the one link that gives them; links, points and joints
//! are looked up by name; axes are normalised (a zero axis refused), a universal joint's
//! axes checked perpendicular, each joint's point checked to belong to its links, the
//! inertia tensor checked positive semi-definite. Every mistake is collected and reported at
//! once.

use super::dsl::Spans;
use super::dsl::Written;
use super::model::{inertia_tensor, Body, Joint, JointKind, Load, LoadKind, SpatialModel};
use crate::checks::magnitudes::{in_range, COORDINATE, GRAVITY, INERTIA, MASS, SIZE, WHY};
use nalgebra::{Matrix3, Vector3};
use proc_macro2::Span;
use syn::Ident;

/// The message `m` at where `id` was written.
fn err(id: &Ident, m: String) -> syn::Error {
    syn::Error::new(id.span(), m)
}

/// Every coordinate finite and within ±[`COORDINATE`].
fn within(p: &Vector3<f64>) -> bool {
    p.iter().all(|x| x.abs() <= COORDINATE)
}

fn unit(v: Vector3<f64>, at: Span, what: &str, errors: &mut Vec<syn::Error>) -> Vector3<f64> {
    let n = v.norm();
    if !(n > 1e-12) || !n.is_finite() {
        errors.push(syn::Error::new(at, format!("{what} is ({}, {}, {}), which has no direction: give a nonzero vector, e.g. (0.0, 0.0, 1.0)", v.x, v.y, v.z)));
        return Vector3::z();
    }
    v / n
}

/// The model of `w` and where its parts were written, or every mistake at its place.
pub(super) fn resolve(w: Written) -> Result<(SpatialModel, Spans), Vec<syn::Error>> {
    let mut errors = Vec::new();
    let mut points: Vec<(String, Vector3<f64>)> = Vec::new();
    let ground_missing = !matches!(w.links.first(), Some(l) if l.name == "ground");
    if ground_missing {
        errors.push(err(&w.name, "missing `ground { ... }` block: every mechanism needs a frame, e.g. `ground { O: (0.0, 0.0, 0.0) }`".to_string()));
    }
    // Points with coordinates first, then the references.
    for l in &w.links {
        for (id, at) in &l.points {
            if let Some(p) = at {
                if !within(p) {
                    errors.push(err(id, format!("point `{id}` is at ({:e}, {:e}, {:e}) m: coordinates must be finite and within ±{COORDINATE:e} m ({WHY}); move the origin or check the unit", p.x, p.y, p.z)));
                } else if points.iter().any(|(n, _)| *id == *n) {
                    errors.push(err(id, format!("point `{id}` is given coordinates twice: define it once (`{id}: (x, y, z)`) and name it alone elsewhere")));
                } else {
                    points.push((id.to_string(), *p));
                }
            }
        }
    }
    let mut bodies = Vec::new();
    for l in &w.links {
        let mut idx = Vec::new();
        for (id, _) in &l.points {
            match points.iter().position(|(n, _)| *id == *n) {
                Some(i) => idx.push(i),
                None => errors.push(err(id, format!("point `{id}` of link `{}` is never given coordinates: write `{id}: (x, y, z)` in one link", l.name))),
            }
        }
        let mass = l.mass.unwrap_or(0.0);
        if !in_range(mass, MASS) {
            errors.push(err(&l.name, format!("the mass of link `{}` is {mass:e} kg: a mass is 0 or within {:e} to {:e} kg ({WHY})", l.name, MASS.0, MASS.1)));
        }
        if let Some(g) = l.cg.filter(|g| !within(g)) {
            errors.push(err(&l.name, format!("the cg of link `{}` is at ({:e}, {:e}, {:e}) m: coordinates must be finite and within ±{COORDINATE:e} m ({WHY})", l.name, g.x, g.y, g.z)));
        }
        let six = l.inertia.unwrap_or_default();
        let sized = six[..3].iter().all(|&x| in_range(x, INERTIA))
            && six[3..]
                .iter()
                .all(|&x| x.is_finite() && x.abs() <= INERTIA.1);
        if !sized {
            errors.push(err(&l.name, format!("the inertia of link `{}` is {six:?} kg·m²: moments are 0 or within {:e} to {:e} kg·m², products within ±{:e} ({WHY})", l.name, INERTIA.0, INERTIA.1, INERTIA.1)));
        }
        let inertia = l.inertia.map(inertia_tensor).unwrap_or_else(Matrix3::zeros);
        if sized
            && l.inertia.is_some()
            && inertia.symmetric_eigenvalues().min() < -1e-12 * inertia.norm()
        {
            errors.push(err(&l.name, format!("the inertia tensor of link `{}` is not positive semi-definite (eigenvalues {:?} kg·m²): check the signs of the products Ixy, Ixz, Iyz (Ixy = Σ m x y)", l.name, inertia.symmetric_eigenvalues().as_slice())));
        }
        bodies.push(Body {
            name: l.name.to_string(),
            points: idx,
            mass,
            cg: l.cg,
            inertia,
        });
    }
    if ground_missing {
        bodies.insert(
            0,
            Body {
                name: "ground".into(),
                points: Vec::new(),
                mass: 0.0,
                cg: None,
                inertia: Matrix3::zeros(),
            },
        );
    }
    let body = |id: &Ident, errors: &mut Vec<syn::Error>| -> usize {
        bodies
            .iter()
            .position(|b| *id == b.name)
            .unwrap_or_else(|| {
                errors.push(err(
                    id,
                    format!(
                        "unknown link `{id}`: the links are {}",
                        bodies
                            .iter()
                            .map(|b| format!("`{}`", b.name))
                            .collect::<Vec<_>>()
                            .join(", ")
                    ),
                ));
                0
            })
    };
    let mut joints = Vec::new();
    for j in &w.joints {
        let named = errors.len();
        let (a, b) = (body(&j.a, &mut errors), body(&j.b, &mut errors));
        let named = errors.len() == named;
        let at = j.at.as_ref().unwrap_or(&j.name);
        let point = points.iter().position(|(n, _)| *at == *n).unwrap_or_else(|| {
            errors.push(err(at, format!("joint `{}`: point `{at}` is not defined: name the joint after a point or write `at P`", j.name)));
            0
        });
        let want = match j.kind.to_string().as_str() {
            "spherical" => 0,
            "revolute" | "prismatic" | "cylindrical" | "helical" => 1,
            "universal" => 2,
            other => {
                errors.push(err(&j.kind, format!("joint `{}`: unknown joint kind `{other}`: a spatial joint is `revolute(a, b) axis (..)`, `prismatic(a, b) along (..)`, `cylindrical(a, b) axis (..)`, `spherical(a, b)`, `universal(a, b) axes (..) (..)` or `helical(a, b) axis (..) pitch ..`", j.name)));
                continue;
            }
        };
        if j.axes.len() != want {
            errors.push(err(
                &j.name,
                format!(
                    "joint `{}`: a {} joint takes {want} direction(s), {} given (e.g. `{}`)",
                    j.name,
                    j.kind,
                    j.axes.len(),
                    [
                        "`spherical(a, b)`",
                        "`axis (0.0, 0.0, 1.0)`",
                        "`axes (1.0, 0.0, 0.0) (0.0, 1.0, 0.0)`"
                    ][want]
                ),
            ));
            continue;
        }
        let what = |k: usize| format!("the {} of joint `{}`", ["axis", "second axis"][k], j.name);
        let u: Vec<Vector3<f64>> = j
            .axes
            .iter()
            .enumerate()
            .map(|(k, (v, at))| unit(*v, *at, &what(k), &mut errors))
            .collect();
        let kind = match (j.kind.to_string().as_str(), j.pitch) {
            ("helical", None) => {
                errors.push(err(
                    &j.name,
                    format!(
                        "joint `{}`: a helical joint needs its lead: `pitch 5 mm` (m per turn)",
                        j.name
                    ),
                ));
                continue;
            }
            ("helical", Some(pitch)) if !(pitch.abs() <= COORDINATE) => {
                errors.push(err(&j.name, format!("joint `{}`: the pitch {pitch:e} m must be finite and within ±{COORDINATE:e} m ({WHY})", j.name)));
                continue;
            }
            ("helical", Some(pitch)) => JointKind::Helical { axis: u[0], pitch },
            (k, Some(_)) => {
                errors.push(err(
                    &j.name,
                    format!(
                        "joint `{}`: only a helical joint takes `pitch`, not a {k} one",
                        j.name
                    ),
                ));
                continue;
            }
            ("revolute", _) => JointKind::Revolute { axis: u[0] },
            ("prismatic", _) => JointKind::Prismatic { axis: u[0] },
            ("cylindrical", _) => JointKind::Cylindrical { axis: u[0] },
            ("universal", _) => {
                let cos = u[0].dot(&u[1]);
                if cos.abs() > 1e-9 {
                    errors.push(err(&j.name, format!("joint `{}`: a universal joint's two axes are perpendicular, but these make {:.6}°: correct the second axis", j.name, cos.clamp(-1.0, 1.0).acos().to_degrees())));
                }
                JointKind::Universal {
                    first: u[0],
                    second: u[1],
                }
            }
            _ => JointKind::Spherical,
        };
        if named && a == b {
            errors.push(err(
                &j.name,
                format!(
                    "joint `{}` joins link `{}` to itself: name two different links",
                    j.name, j.a
                ),
            ));
        }
        let owns = |x: usize| bodies[x].points.contains(&point);
        let shared = !matches!(
            kind,
            JointKind::Prismatic { .. } | JointKind::Cylindrical { .. } | JointKind::Helical { .. }
        );
        if named && (!owns(b) || (shared && !owns(a))) {
            errors.push(err(&j.name, format!("joint `{}`: its point `{at}` must be a point of {}: list it in the link's `points`", j.name, if shared { format!("both `{}` and `{}`", j.a, j.b) } else { format!("`{}` (the second link)", j.b) })));
        }
        joints.push(Joint {
            name: j.name.to_string(),
            kind,
            a,
            b,
            point,
        });
    }
    let mut inputs = Vec::new();
    for id in &w.inputs {
        match joints.iter().position(|j| *id == j.name) {
            Some(k) => inputs.push(k),
            None => errors.push(err(
                id,
                format!("input `{id}` is not a joint: name a revolute, prismatic or helical joint"),
            )),
        }
    }
    let mut loads = Vec::new();
    for (n, kind, link, at) in &w.loads {
        let b = body(link, &mut errors);
        let kind = match (kind.to_string().as_str(), at) {
            ("torque", None) => LoadKind::Torque { body: b },
            ("force", Some(p)) => match points.iter().position(|(m, _)| *p == *m) {
                Some(point) if bodies[b].points.contains(&point) => {
                    LoadKind::Force { body: b, point }
                }
                _ => {
                    errors.push(err(p, format!("load `{n}`: `{p}` is not a point of link `{link}`: list it in the link's `points`")));
                    continue;
                }
            },
            _ => {
                errors.push(err(
                    n,
                    format!("load `{n}`: expected `force on LINK at P` or `torque on LINK`"),
                ));
                continue;
            }
        };
        loads.push(Load {
            name: n.to_string(),
            kind,
        });
    }
    if let Some(g) = w.gravity.filter(|g| !(g.norm() <= GRAVITY)) {
        errors.push(err(&w.name, format!("gravity is ({:e}, {:e}, {:e}) m/s²: its size must be at most {GRAVITY:e} m/s² ({WHY})", g.x, g.y, g.z)));
    }
    let size = points
        .iter()
        .flat_map(|(_, a)| points.iter().map(move |(_, b)| (a - b).norm()))
        .fold(0.0, f64::max);
    if points.len() > 1 && size < SIZE.0 {
        errors.push(err(&w.name, format!("the drawing is {size:e} m across: its points must be at least {:e} m apart somewhere ({WHY}); check the unit", SIZE.0)));
    }
    if !errors.is_empty() {
        return Err(errors);
    }
    let mut body_spans: Vec<Span> = w.links.iter().map(|l| l.name.span()).collect();
    if ground_missing {
        body_spans.insert(0, w.name.span());
    }
    let spans = Spans {
        name: w.name.span(),
        space: w.space.span(),
        input: w.input_key.as_ref().unwrap_or(&w.space).span(),
        bodies: body_spans,
        joints: w.joints.iter().map(|j| j.name.span()).collect(),
        docs: w.docs.clone(),
    };
    let model = SpatialModel {
        name: w.name.to_string(),
        gravity: w.gravity,
        points,
        bodies,
        joints,
        inputs,
        loads,
        allow_redundant: w.allow_redundant,
    };
    Ok((model, spans))
}
