//! The `space` form of the DSL (SPEC 3i), parsed with `syn` into a `SpatialModel`.

use super::model::{inertia_tensor, Body, Joint, JointKind, Load, LoadKind, SpatialModel};
use crate::front::expr::Constants;
use crate::model::units::Dim;
use crate::MechError;
use nalgebra::{Matrix3, Vector3};
use proc_macro2::Span;
use syn::ext::IdentExt;
use syn::parse::{Parse, ParseStream};
use syn::{braced, bracketed, parenthesized, Ident, Token};

/// A joint as written: names not yet resolved.
struct JointDecl {
    name: Ident,
    kind: Ident,
    a: Ident,
    b: Ident,
    at: Option<Ident>,
    axes: Vec<(Vector3<f64>, Span)>,
    pitch: Option<f64>,
}

/// A link as written.
struct LinkDecl {
    name: Ident,
    points: Vec<(Ident, Option<Vector3<f64>>)>,
    mass: Option<f64>,
    cg: Option<Vector3<f64>>,
    inertia: Option<[f64; 6]>,
}

/// The whole text as written.
struct Written {
    name: Ident,
    gravity: Option<Vector3<f64>>,
    links: Vec<LinkDecl>,
    joints: Vec<JointDecl>,
    inputs: Vec<Ident>,
    loads: Vec<(Ident, Ident, Ident, Option<Ident>)>,
}

fn comma(input: ParseStream) -> syn::Result<()> {
    if !input.is_empty() {
        input.parse::<Token![,]>()?;
    }
    Ok(())
}

/// `(x, y, z)`, each an expression of dimension `dim` (a plain number is SI).
fn triple(input: ParseStream, c: &Constants, dim: Dim, what: &str) -> syn::Result<Vector3<f64>> {
    let content;
    parenthesized!(content in input);
    let mut v = [0.0; 3];
    for (k, x) in v.iter_mut().enumerate() {
        if k > 0 {
            content.parse::<Token![,]>()?;
        }
        *x = c.expr(&content)?.expect(dim, what)?;
    }
    let _: Option<Token![,]> = content.parse()?;
    if !content.is_empty() {
        return Err(content.error(format!(
            "expected `(x, y, z)`: three numbers for {what} (a spatial mechanism's vectors have three components)"
        )));
    }
    Ok(Vector3::from(v))
}

fn link_body(
    input: ParseStream,
    c: &Constants,
    name: Ident,
    ground: bool,
) -> syn::Result<LinkDecl> {
    let content;
    braced!(content in input);
    let mut decl = LinkDecl {
        name,
        points: Vec::new(),
        mass: None,
        cg: None,
        inertia: None,
    };
    let point_list = |inner: ParseStream, out: &mut Vec<(Ident, Option<Vector3<f64>>)>| {
        while !inner.is_empty() {
            let id: Ident = inner.parse()?;
            let at = if inner.peek(Token![:]) {
                inner.parse::<Token![:]>()?;
                Some(triple(inner, c, Dim::LENGTH, "a point's coordinate")?)
            } else {
                None
            };
            out.push((id, at));
            comma(inner)?;
        }
        Ok::<_, syn::Error>(())
    };
    if ground && !content.peek2(syn::token::Brace) {
        point_list(&content, &mut decl.points)?;
        return Ok(decl);
    }
    while !content.is_empty() {
        let key: Ident = content.parse()?;
        match key.to_string().as_str() {
            "points" => {
                let inner;
                braced!(inner in content);
                point_list(&inner, &mut decl.points)?;
            }
            "mass" if !ground => {
                content.parse::<Token![:]>()?;
                decl.mass = Some(c.expr(&content)?.expect(Dim::MASS, "a mass")?);
            }
            "cg" if !ground => {
                content.parse::<Token![:]>()?;
                decl.cg = Some(triple(&content, c, Dim::LENGTH, "a cg's coordinate")?);
            }
            "inertia" if !ground => {
                content.parse::<Token![:]>()?;
                let inner;
                parenthesized!(inner in content);
                let mut six = [0.0; 6];
                for (k, x) in six.iter_mut().enumerate() {
                    if k > 0 {
                        inner.parse::<Token![,]>()?;
                    }
                    *x = c.expr(&inner)?.expect(Dim::INERTIA, "a moment of inertia")?;
                }
                let _: Option<Token![,]> = inner.parse()?;
                if !inner.is_empty() {
                    return Err(inner.error("expected `(Ixx, Iyy, Izz, Ixy, Ixz, Iyz)`: six numbers about the cg in the drawing's axes"));
                }
                decl.inertia = Some(six);
            }
            other => {
                return Err(syn::Error::new(
                    key.span(),
                    format!("unknown link property `{other}`: a spatial link takes `points`, `mass`, `cg` and `inertia: (Ixx, Iyy, Izz, Ixy, Ixz, Iyz)`"),
                ))
            }
        }
        comma(&content)?;
    }
    Ok(decl)
}

fn joint(input: ParseStream, c: &Constants) -> syn::Result<JointDecl> {
    let name: Ident = input.parse()?;
    input.parse::<Token![:]>()?;
    let kind: Ident = input.parse()?;
    let args;
    parenthesized!(args in input);
    let a: Ident = args.call(Ident::parse_any)?;
    args.parse::<Token![,]>()?;
    let b: Ident = args.call(Ident::parse_any)?;
    let _: Option<Token![,]> = args.parse()?;
    let mut decl = JointDecl {
        name,
        kind,
        a,
        b,
        at: None,
        axes: Vec::new(),
        pitch: None,
    };
    while input.peek(Ident) {
        let word: Ident = input.parse()?;
        match word.to_string().as_str() {
            "at" => decl.at = Some(input.parse()?),
            "axis" | "along" | "axes" => {
                while input.peek(syn::token::Paren) {
                    let span = input.span();
                    decl.axes.push((triple(input, c, Dim::NONE, "a direction")?, span));
                }
            }
            "pitch" => decl.pitch = Some(c.expr(input)?.expect(Dim::LENGTH, "a helical joint's pitch (its lead per turn)")?),
            other => {
                return Err(syn::Error::new(
                    word.span(),
                    format!("unknown joint item `{other}`: expected `at P`, `axis (..)`, `along (..)`, `axes (..) (..)` or `pitch ..`"),
                ))
            }
        }
    }
    Ok(decl)
}

impl Parse for Written {
    fn parse(input: ParseStream) -> syn::Result<Self> {
        let _ = input.call(syn::Attribute::parse_outer)?;
        input.parse::<Token![pub]>()?;
        input.parse::<Token![struct]>()?;
        let name: Ident = input.parse()?;
        let body;
        braced!(body in input);
        let first: Ident = body.call(Ident::parse_any)?;
        if first != "space" {
            return Err(syn::Error::new(first.span(), "a spatial mechanism starts with the word `space`: `pub struct Name { space, ... }`"));
        }
        comma(&body)?;
        let mut c = Constants::default();
        let mut w = Written {
            name,
            gravity: None,
            links: Vec::new(),
            joints: Vec::new(),
            inputs: Vec::new(),
            loads: Vec::new(),
        };
        while !body.is_empty() {
            let key: Ident = body.call(Ident::parse_any)?;
            match key.to_string().as_str() {
                "gravity" => {
                    body.parse::<Token![:]>()?;
                    w.gravity = Some(triple(&body, &c, Dim::ACCELERATION, "gravity")?);
                }
                "consts" => c.parse_block(&body)?,
                "ground" => w.links.insert(0, link_body(&body, &c, key, true)?),
                "link" => {
                    let id: Ident = body.parse()?;
                    w.links.push(link_body(&body, &c, id, false)?);
                }
                "joints" => {
                    let inner;
                    braced!(inner in body);
                    while !inner.is_empty() {
                        w.joints.push(joint(&inner, &c)?);
                        comma(&inner)?;
                    }
                }
                "input" => {
                    body.parse::<Token![:]>()?;
                    w.inputs.push(body.parse()?);
                }
                "inputs" => {
                    body.parse::<Token![:]>()?;
                    let list;
                    bracketed!(list in body);
                    while !list.is_empty() {
                        w.inputs.push(list.parse()?);
                        comma(&list)?;
                    }
                }
                "loads" => {
                    let inner;
                    braced!(inner in body);
                    while !inner.is_empty() {
                        let n: Ident = inner.parse()?;
                        inner.parse::<Token![:]>()?;
                        let kind: Ident = inner.parse()?;
                        let on: Ident = inner.parse()?;
                        if on != "on" {
                            return Err(syn::Error::new(on.span(), "expected `on`: `NAME: force on LINK at P` or `NAME: torque on LINK`"));
                        }
                        let link: Ident = inner.parse()?;
                        let at = if inner.peek(Ident) {
                            let kw: Ident = inner.parse()?;
                            if kw != "at" {
                                return Err(syn::Error::new(kw.span(), "expected `at P` after the link of a force"));
                            }
                            Some(inner.parse()?)
                        } else {
                            None
                        };
                        w.loads.push((n, kind, link, at));
                        comma(&inner)?;
                    }
                }
                other => {
                    return Err(syn::Error::new(
                        key.span(),
                        format!("unknown item `{other}`: a spatial mechanism takes `consts`, `gravity`, `ground`, `link`, `joints`, `input`, `inputs` and `loads`"),
                    ))
                }
            }
            comma(&body)?;
        }
        Ok(w)
    }
}

/// `line L, column C: message` of a syn error (columns from 1).
fn located(e: &syn::Error) -> String {
    let at = e.span().start();
    format!("line {}, column {}: {e}", at.line, at.column + 1)
}

/// Parse the `space` text form (the body of a `mechanism! { ... }`) into a
/// [`SpatialModel`]: names resolved, units converted to SI, axes normalised. Every naming or
/// geometry mistake found is reported at once in one [`MechError::Invalid`].
pub fn parse(text: &str) -> Result<SpatialModel, MechError> {
    let w = syn::parse_str::<Written>(text).map_err(|e| MechError::Invalid(located(&e)))?;
    resolve(w)
}

fn unit(v: Vector3<f64>, what: &str, errors: &mut Vec<String>) -> Vector3<f64> {
    let n = v.norm();
    if !(n > 1e-12) || !n.is_finite() {
        errors.push(format!("{what} is ({}, {}, {}), which has no direction: give a nonzero vector, e.g. (0.0, 0.0, 1.0)", v.x, v.y, v.z));
        return Vector3::z();
    }
    v / n
}

fn resolve(w: Written) -> Result<SpatialModel, MechError> {
    let mut errors = Vec::new();
    let mut points: Vec<(String, Vector3<f64>)> = Vec::new();
    let ground_missing = w.links.first().map_or(true, |l| l.name != "ground");
    if ground_missing {
        errors.push("missing `ground { ... }` block: every mechanism needs a frame, e.g. `ground { O: (0.0, 0.0, 0.0) }`".to_string());
    }
    // Points with coordinates first, then the references.
    for l in &w.links {
        for (id, at) in &l.points {
            if let Some(p) = at {
                if points.iter().any(|(n, _)| *n == id.to_string()) {
                    errors.push(format!("point `{id}` is given coordinates twice: define it once (`{id}: (x, y, z)`) and name it alone elsewhere"));
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
            match points.iter().position(|(n, _)| *n == id.to_string()) {
                Some(i) => idx.push(i),
                None => errors.push(format!("point `{id}` of link `{}` is never given coordinates: write `{id}: (x, y, z)` in one link", l.name)),
            }
        }
        let mass = l.mass.unwrap_or(0.0);
        if !(mass >= 0.0) || !mass.is_finite() {
            errors.push(format!(
                "the mass of link `{}` is {mass} kg: a mass is finite and ≥ 0",
                l.name
            ));
        }
        let inertia = l.inertia.map(inertia_tensor).unwrap_or_else(Matrix3::zeros);
        if l.inertia.is_some() && inertia.symmetric_eigenvalues().min() < -1e-12 * inertia.norm() {
            errors.push(format!("the inertia tensor of link `{}` is not positive semi-definite (eigenvalues {:?} kg·m²): check the signs of the products Ixy, Ixz, Iyz (Ixy = Σ m x y)", l.name, inertia.symmetric_eigenvalues().as_slice()));
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
    let body = |id: &Ident, errors: &mut Vec<String>| -> usize {
        bodies
            .iter()
            .position(|b| b.name == id.to_string())
            .unwrap_or_else(|| {
                errors.push(format!(
                    "unknown link `{id}`: the links are {}",
                    bodies
                        .iter()
                        .map(|b| format!("`{}`", b.name))
                        .collect::<Vec<_>>()
                        .join(", ")
                ));
                0
            })
    };
    let mut joints = Vec::new();
    for j in &w.joints {
        let (a, b) = (body(&j.a, &mut errors), body(&j.b, &mut errors));
        let at = j.at.as_ref().unwrap_or(&j.name);
        let point = points.iter().position(|(n, _)| *n == at.to_string()).unwrap_or_else(|| {
            errors.push(format!("joint `{}`: point `{at}` is not defined: name the joint after a point or write `at P`", j.name));
            0
        });
        let want = match j.kind.to_string().as_str() {
            "spherical" => 0,
            "revolute" | "prismatic" | "cylindrical" | "helical" => 1,
            "universal" => 2,
            other => {
                errors.push(format!("joint `{}`: unknown joint kind `{other}`: a spatial joint is `revolute(a, b) axis (..)`, `prismatic(a, b) along (..)`, `cylindrical(a, b) axis (..)`, `spherical(a, b)`, `universal(a, b) axes (..) (..)` or `helical(a, b) axis (..) pitch ..`", j.name));
                continue;
            }
        };
        if j.axes.len() != want {
            errors.push(format!(
                "joint `{}`: a {} joint takes {want} direction(s), {} given (e.g. `{}`)",
                j.name,
                j.kind,
                j.axes.len(),
                [
                    "`spherical(a, b)`",
                    "`axis (0.0, 0.0, 1.0)`",
                    "`axes (1.0, 0.0, 0.0) (0.0, 1.0, 0.0)`"
                ][want]
            ));
            continue;
        }
        let what = |k: usize| format!("the {} of joint `{}`", ["axis", "second axis"][k], j.name);
        let u: Vec<Vector3<f64>> = j
            .axes
            .iter()
            .enumerate()
            .map(|(k, (v, _))| unit(*v, &what(k), &mut errors))
            .collect();
        let kind = match (j.kind.to_string().as_str(), j.pitch) {
            ("helical", None) => {
                errors.push(format!(
                    "joint `{}`: a helical joint needs its lead: `pitch 5 mm` (m per turn)",
                    j.name
                ));
                continue;
            }
            ("helical", Some(pitch)) => JointKind::Helical { axis: u[0], pitch },
            (k, Some(_)) => {
                errors.push(format!(
                    "joint `{}`: only a helical joint takes `pitch`, not a {k} one",
                    j.name
                ));
                continue;
            }
            ("revolute", _) => JointKind::Revolute { axis: u[0] },
            ("prismatic", _) => JointKind::Prismatic { axis: u[0] },
            ("cylindrical", _) => JointKind::Cylindrical { axis: u[0] },
            ("universal", _) => {
                let cos = u[0].dot(&u[1]);
                if cos.abs() > 1e-9 {
                    errors.push(format!("joint `{}`: a universal joint's two axes are perpendicular, but these make {:.6}°: correct the second axis", j.name, cos.clamp(-1.0, 1.0).acos().to_degrees()));
                }
                JointKind::Universal {
                    first: u[0],
                    second: u[1],
                }
            }
            _ => JointKind::Spherical,
        };
        if a == b {
            errors.push(format!(
                "joint `{}` joins link `{}` to itself: name two different links",
                j.name, j.a
            ));
        }
        let owns = |x: usize| bodies[x].points.contains(&point);
        let shared = !matches!(
            kind,
            JointKind::Prismatic { .. } | JointKind::Cylindrical { .. } | JointKind::Helical { .. }
        );
        if !owns(b) || (shared && !owns(a)) {
            errors.push(format!("joint `{}`: its point `{at}` must be a point of {}: list it in the link's `points`", j.name, if shared { format!("both `{}` and `{}`", j.a, j.b) } else { format!("`{}` (the second link)", j.b) }));
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
        match joints.iter().position(|j| j.name == id.to_string()) {
            Some(k) => inputs.push(k),
            None => errors.push(format!(
                "input `{id}` is not a joint: name a revolute, prismatic or helical joint"
            )),
        }
    }
    let mut loads = Vec::new();
    for (n, kind, link, at) in &w.loads {
        let b = body(link, &mut errors);
        let kind = match (kind.to_string().as_str(), at) {
            ("torque", None) => LoadKind::Torque { body: b },
            ("force", Some(p)) => match points.iter().position(|(m, _)| *m == p.to_string()) {
                Some(point) if bodies[b].points.contains(&point) => {
                    LoadKind::Force { body: b, point }
                }
                _ => {
                    errors.push(format!("load `{n}`: `{p}` is not a point of link `{link}`: list it in the link's `points`"));
                    continue;
                }
            },
            _ => {
                errors.push(format!(
                    "load `{n}`: expected `force on LINK at P` or `torque on LINK`"
                ));
                continue;
            }
        };
        loads.push(Load {
            name: n.to_string(),
            kind,
        });
    }
    if !errors.is_empty() {
        return Err(MechError::Invalid(errors.join("\n")));
    }
    Ok(SpatialModel {
        name: w.name.to_string(),
        gravity: w.gravity,
        points,
        bodies,
        joints,
        inputs,
        loads,
    })
}
