//! The inputs, loads and force elements of [`super::resolve`]: the joints driven and
//! their zeros, where each load acts, each element's links and points and its rest state.

use super::links::Known;
use super::{list, Diagnostic};
use crate::model::*;

/// An element's end: its link, and its point for a linear element.
type End = (usize, Option<usize>);

/// Inputs: the joint of each, and its zero.
pub(super) fn inputs<S: Clone>(
    d: &Description<S>,
    errs: &mut Vec<Diagnostic<S>>,
) -> (Vec<usize>, Vec<f64>) {
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
    (inputs, input_zero)
}

/// Loads: a torque on a link, a force on a link at one of its points.
pub(super) fn loads<S: Clone>(
    d: &Description<S>,
    known: &Known,
    errs: &mut Vec<Diagnostic<S>>,
) -> Vec<Load> {
    let (links, points, point_ix) = (known.links, known.points, known.point_ix);
    let mut loads = Vec::new();
    for l in &d.loads {
        match &l.kind {
            LoadDeclKind::Torque { link } => {
                if let Some(li) = known.find_link(link, errs) {
                    loads.push(Load::Torque {
                        name: l.name.text.clone(),
                        link: li,
                    });
                }
            }
            LoadDeclKind::Force { link, point } => {
                let li = known.find_link(link, errs);
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
    loads
}

/// Force elements: their links and points (the rest state after the model is built).
pub(super) fn element_ends<'d, S: Clone>(
    d: &'d Description<S>,
    known: &Known,
    errs: &mut Vec<Diagnostic<S>>,
) -> Vec<(&'d ElementDecl<S>, End, End)> {
    let mut element_ends = Vec::new();
    for e in &d.elements {
        let (ea, eb) = (
            element_end(e, &e.a, &e.pa, known, errs),
            element_end(e, &e.b, &e.pb, known, errs),
        );
        if let (Some(ea), Some(eb)) = (ea, eb) {
            if ea.0 == eb.0 {
                errs.push(Diagnostic::at(
                    e.b.span.clone(),
                    format!(
                        "{} `{}` joins link `{}` to itself: a force element acts between two different links (one of them may be `ground`)",
                        e.kind.keyword(), e.name.text, known.links[ea.0].name
                    ),
                ));
            } else {
                element_ends.push((e, ea, eb));
            }
        }
    }
    element_ends
}

/// One end of element `e`: `link`, and `at` (a linear element's point) among its points.
fn element_end<S: Clone>(
    e: &ElementDecl<S>,
    link: &Name<S>,
    at: &Option<Name<S>>,
    known: &Known,
    errs: &mut Vec<Diagnostic<S>>,
) -> Option<End> {
    let (links, points, point_ix) = (known.links, known.points, known.point_ix);
    let li = known.find_link(link, errs)?;
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
}

/// A resolved force element; a preload becomes the free length (angle) that gives it in
/// the drawing: x₀ = x_drawing − F₀/k.
pub(super) fn element_of<S: Clone>(
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
