//! The points and links of [`super::resolve`]: points defined once and reused by name,
//! each link's points, mass and cg; and [`Known`], what the later sections look names up in.

use super::{list, Diagnostic};
use crate::model::shape::{Axial, MassProperties};
use crate::model::*;
use std::collections::HashMap;

/// Points: defined once, reused by name. The points in order of definition, and the
/// index of each name.
pub(super) fn points<S: Clone>(
    decls: &[&LinkDecl<S>],
    errs: &mut Vec<Diagnostic<S>>,
) -> (Vec<Point>, HashMap<String, usize>) {
    let mut points: Vec<Point> = Vec::new();
    let mut point_ix: HashMap<String, usize> = HashMap::new();
    for l in decls {
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
    (points, point_ix)
}

/// The links in declaration order (ground first): their points by index, mass, inertia
/// and cg (the first known point's position when no `cg` is given).
pub(super) fn links<S: Clone>(
    decls: &[&LinkDecl<S>],
    points: &[Point],
    point_ix: &HashMap<String, usize>,
    errs: &mut Vec<Diagnostic<S>>,
) -> Vec<Link> {
    let mut links = Vec::new();
    for l in decls {
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
        if let (Some(m), None, None) = (&l.mass, &l.cg, &l.shape) {
            errs.push(Diagnostic::at(
                m.span.clone(),
                format!("link `{}` has a mass but no `cg`: add `cg: (x, y)`, its centre of gravity in the drawing", l.name.text),
            ));
        }
        let mut link = Link {
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
            body: None,
            axial: Axial {
                plane: l.plane.as_ref().map(|z| z.value).unwrap_or(0.0),
                product: [0.0, 0.0],
            },
        };
        body(l, &mut link, points, errs);
        counterweights(l, &mut link, errs);
        links.push(link);
    }
    links
}

/// A link declared by `shape:` and `material:`: its mass, cg and inertia from them
/// ([`crate::model::shape`]); `mass:`, `inertia:` or `cg:` beside a shape, a shape without
/// a material (or the reverse) and a shape the link's points cannot carry are errors.
fn body<S: Clone>(
    l: &LinkDecl<S>,
    link: &mut Link,
    points: &[Point],
    errs: &mut Vec<Diagnostic<S>>,
) {
    let name = &l.name.text;
    let (shape, material) = match (&l.shape, &l.material) {
        (None, None) => return,
        (Some(s), None) => {
            return errs.push(Diagnostic::at(
                s.span.clone(),
                format!("link `{name}` has a shape but no material: add `material: NAME` (one of {}), or a `material {{ density .., youngs .., yield .., ultimate .., endurance .. }}` block", crate::model::shape::material_names()),
            ))
        }
        (None, Some(m)) => {
            return errs.push(Diagnostic::at(
                m.span.clone(),
                format!("link `{name}` has a material but no shape: add `shape: {}`, or remove the material and give `mass:`, `inertia:` and `cg:`", "bar(width W, thickness T)"),
            ))
        }
        (Some(s), Some(m)) => (s, m),
    };
    let mut beside = |what: &str, span: Option<S>| {
        if let Some(span) = span {
            errs.push(Diagnostic::at(
                span,
                format!("`{what}:` beside `shape:` in link `{name}`: the shape and the material give its mass, cg and inertia; remove `{what}:`, or the shape and the material"),
            ));
        }
    };
    beside("mass", l.mass.as_ref().map(|m| m.span.clone()));
    beside("inertia", l.inertia.as_ref().map(|m| m.span.clone()));
    beside("cg", l.cg.as_ref().map(|c| c.span.clone()));
    let at: Vec<[f64; 2]> = link.points.iter().map(|&i| points[i].pos).collect();
    let props =
        crate::model::shape::Shape::from_dimensions(&shape.keyword, &shape.dims).and_then(|s| {
            let p = s.mass_properties(material.material.density, &at)?;
            Ok((s, p))
        });
    match props {
        Ok((s, p)) => {
            link.mass = Some(p.mass);
            link.inertia = p.inertia;
            link.cg = p.cg;
            link.body = Some((s, material.material));
        }
        Err(why) => errs.push(Diagnostic::at(
            shape.span.clone(),
            format!("link `{name}`: {why}"),
        )),
    }
}

/// Each `counterweight: (MASS, at (x, y))` (or `.., plane: Z)`) of `l` added to `link` as
/// a point mass fixed to it ([`MassProperties::combine`], and along the axis
/// [`Axial::combine`]: in the plane Z, the link's own when not given); a negative mass, and
/// a counterweight beside `shape:`, are errors.
fn counterweights<S: Clone>(l: &LinkDecl<S>, link: &mut Link, errs: &mut Vec<Diagnostic<S>>) {
    for (mass, at, plane, span) in &l.counterweights {
        if !(mass.value >= 0.0) {
            errs.push(Diagnostic::at(
                mass.span.clone(),
                format!(
                    "a counterweight of negative mass ({} kg) on link `{}`: give its mass, 0 or more, and put it on the side opposite to the unbalance",
                    mass.value, l.name.text
                ),
            ));
            continue;
        }
        if l.shape.is_some() {
            errs.push(Diagnostic::at(
                span.clone(),
                format!("a counterweight beside `shape:` on link `{}`: declare the link by `mass:`, `inertia:` and `cg:` to add counterweights", l.name.text),
            ));
            continue;
        }
        let own = MassProperties {
            mass: link.mass.unwrap_or(0.0),
            cg: link.cg,
            inertia: link.inertia,
        };
        let weight = MassProperties {
            mass: mass.value,
            cg: at.value,
            inertia: 0.0,
        };
        let both = own.combine(weight);
        let in_plane = Axial {
            plane: plane.as_ref().or(l.plane.as_ref()).map_or(0.0, |z| z.value),
            product: [0.0, 0.0],
        };
        link.axial = link.axial.combine(&own, in_plane, &weight, both.cg);
        link.mass = Some(both.mass);
        link.cg = both.cg;
        link.inertia = both.inertia;
    }
}

/// The points and links resolved so far, which the later sections refer to by name.
pub(super) struct Known<'a> {
    pub(super) points: &'a [Point],
    pub(super) point_ix: &'a HashMap<String, usize>,
    pub(super) links: &'a [Link],
    link_names: Vec<&'a str>,
}

impl<'a> Known<'a> {
    pub(super) fn new(
        points: &'a [Point],
        point_ix: &'a HashMap<String, usize>,
        links: &'a [Link],
    ) -> Self {
        let link_names: Vec<&str> = links.iter().map(|l| l.name.as_str()).collect();
        Known {
            points,
            point_ix,
            links,
            link_names,
        }
    }

    /// The index of link `n`, or a diagnostic that lists the links.
    pub(super) fn find_link<S: Clone>(
        &self,
        n: &Name<S>,
        errs: &mut Vec<Diagnostic<S>>,
    ) -> Option<usize> {
        let r = self.links.iter().position(|l| l.name == n.text);
        if r.is_none() {
            errs.push(Diagnostic::at(
                n.span.clone(),
                format!(
                    "unknown link `{}`: the links are {}",
                    n.text,
                    list(&self.link_names)
                ),
            ));
        }
        r
    }
}
