//! Name resolution (check 1 of `docs/conventions.md#checks`): turns a [`Description`]
//! into a [`Model`], collecting every naming mistake at once.

mod cams;
mod joints;
mod links;
mod loads;
mod meshes;

use crate::model::*;
use links::Known;
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
///
/// One function per section of the description, in this order, each adding its
/// diagnostics to one list: duplicate names, points, links, joints, cams, gear pairs and
/// racks, links no joint reaches, shared points no pin holds, inputs, loads, force
/// elements; then the elements' rest states once the model is built.
pub fn resolve<S: Clone>(d: &Description<S>) -> Result<Model, Vec<Diagnostic<S>>> {
    let mut errs = Vec::new();
    let decls: Vec<&LinkDecl<S>> = std::iter::once(&d.ground).chain(d.links.iter()).collect();
    duplicates(d, &decls, &mut errs);
    let (points, point_ix) = links::points(&decls, &mut errs);
    let links = links::links(&decls, &points, &point_ix, &mut errs);
    let known = Known::new(&points, &point_ix, &links);
    let (mut joints, reached) = joints::joints(d, &known, &mut errs);
    cams::cams(d, &mut joints, &links, &mut errs);
    meshes::meshes(d, &mut joints, &links, &points, &mut errs);
    joints::unreached(&decls, &reached, &mut errs);
    joints::shared_points(&decls, &known, &joints, &mut errs);
    let (inputs, input_zero) = loads::inputs(d, &mut errs);
    let loads = loads::loads(d, &known, &mut errs);
    let element_ends = loads::element_ends(d, &known, &mut errs);

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
        match loads::element_of(&model, e, a, b, pa.zip(pb).map(|(p, q)| [p, q])) {
            Ok(el) => model.elements.push(el),
            Err(diag) => errs.push(diag),
        }
    }
    if !errs.is_empty() {
        return Err(errs);
    }
    Ok(model)
}

/// Every link, joint, load, input and element needs its own name.
fn duplicates<S: Clone>(d: &Description<S>, decls: &[&LinkDecl<S>], errs: &mut Vec<Diagnostic<S>>) {
    dup_check("link", decls.iter().map(|l| &l.name), errs);
    dup_check("joint", d.joints.iter().map(|j| &j.name), errs);
    dup_check("load", d.loads.iter().map(|l| &l.name), errs);
    dup_check("input", d.inputs.iter().map(|i| &i.name), errs);
    dup_check("element", d.elements.iter().map(|e| &e.name), errs);
}

/// Parse and resolve DSL text, for the unit tests of the checks.
#[cfg(test)]
pub(crate) fn model_of(text: &str) -> Model {
    resolve(&crate::front::dsl::parse_str(text).expect("parse")).expect("resolve")
}
