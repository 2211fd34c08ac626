//! The `space` form of the DSL (SPEC 3i), parsed with `syn` into a `SpatialModel`.

use super::model::SpatialModel;
use crate::front::expr::Constants;
use crate::model::units::Dim;
use crate::MechError;
use nalgebra::Vector3;
use proc_macro2::Span;
use syn::ext::IdentExt;
use syn::parse::{Parse, ParseStream};
use syn::{braced, bracketed, parenthesized, Ident, Token};

/// A joint as written: names not yet resolved.
pub(super) struct JointDecl {
    pub(super) name: Ident,
    pub(super) kind: Ident,
    pub(super) a: Ident,
    pub(super) b: Ident,
    pub(super) at: Option<Ident>,
    pub(super) axes: Vec<(Vector3<f64>, Span)>,
    pub(super) pitch: Option<f64>,
}

/// A link as written.
pub(super) struct LinkDecl {
    pub(super) name: Ident,
    pub(super) points: Vec<(Ident, Option<Vector3<f64>>)>,
    pub(super) mass: Option<f64>,
    pub(super) cg: Option<Vector3<f64>>,
    pub(super) inertia: Option<[f64; 6]>,
}

/// The whole text as written.
pub(super) struct Written {
    pub(super) name: Ident,
    /// The word `space`.
    pub(super) space: Ident,
    /// The word `input` or `inputs`, when written.
    pub(super) input_key: Option<Ident>,
    pub(super) gravity: Option<Vector3<f64>>,
    pub(super) links: Vec<LinkDecl>,
    pub(super) joints: Vec<JointDecl>,
    pub(super) inputs: Vec<Ident>,
    pub(super) loads: Vec<(Ident, Ident, Ident, Option<Ident>)>,
    pub(super) allow_redundant: bool,
    /// The doc comment lines written on the struct.
    pub(super) docs: Vec<String>,
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
        let (mut allow_redundant, mut docs) = (false, Vec::new());
        for attr in input.call(syn::Attribute::parse_outer)? {
            if let syn::Meta::NameValue(syn::MetaNameValue {
                value:
                    syn::Expr::Lit(syn::ExprLit {
                        lit: syn::Lit::Str(line),
                        ..
                    }),
                ..
            }) = &attr.meta
            {
                if attr.path().is_ident("doc") {
                    docs.push(line.value());
                    continue;
                }
            }
            if attr.path().is_ident("allow") {
                let arg: Ident = attr.parse_args()?;
                if arg != "redundant" {
                    return Err(syn::Error::new(
                        arg.span(),
                        "only `#[allow(redundant)]` is understood here",
                    ));
                }
                allow_redundant = true;
            } else if !attr.path().is_ident("doc") {
                return Err(syn::Error::new_spanned(
                    attr,
                    "unsupported attribute: use doc comments or `#[allow(redundant)]`",
                ));
            }
        }
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
            space: first,
            input_key: None,
            gravity: None,
            links: Vec::new(),
            joints: Vec::new(),
            inputs: Vec::new(),
            loads: Vec::new(),
            allow_redundant,
            docs,
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
                    w.input_key = Some(key.clone());
                    body.parse::<Token![:]>()?;
                    w.inputs.push(body.parse()?);
                }
                "inputs" => {
                    w.input_key = Some(key.clone());
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
/// geometry mistake found is reported at once in one [`MechError::Invalid`], each line
/// starting with where it was written.
pub fn parse(text: &str) -> Result<SpatialModel, MechError> {
    let w = syn::parse_str::<Written>(text).map_err(|e| MechError::Invalid(located(&e)))?;
    super::resolve::resolve(w)
        .map(|(m, _)| m)
        .map_err(|errors| {
            MechError::Invalid(errors.iter().map(located).collect::<Vec<_>>().join("\n"))
        })
}

/// Where the parts of a `space` declaration were written, for the macro's spanned errors.
#[derive(Clone, Debug)]
pub struct Spans {
    /// The struct's name.
    pub name: Span,
    /// The word `space`.
    pub space: Span,
    /// The word `input` / `inputs` (the word `space` when none is written).
    pub input: Span,
    /// Each body's name, in the model's order (the ground first).
    pub bodies: Vec<Span>,
    /// Each joint's name, in the model's order.
    pub joints: Vec<Span>,
    /// The doc comment lines written on the struct.
    pub docs: Vec<String>,
}

/// The `space` form parsed from the tokens of a `mechanism!` call: the model and where its
/// parts were written. Every mistake is one `syn::Error` at its place (combined).
pub struct Declared {
    /// The resolved model (SI).
    pub model: SpatialModel,
    /// Where its parts were written.
    pub spans: Spans,
}

impl Parse for Declared {
    fn parse(input: ParseStream) -> syn::Result<Self> {
        let w: Written = input.parse()?;
        super::resolve::resolve(w)
            .map(|(model, spans)| Declared { model, spans })
            .map_err(|errors| {
                let mut all = errors.into_iter();
                let mut first = all.next().expect("an error");
                first.extend(all);
                first
            })
    }
}

/// Whether the tokens of a `mechanism!` call declare a spatial mechanism: attributes, then
/// `pub struct Name { space ...`.
pub fn is_space(input: ParseStream) -> bool {
    let fork = input.fork();
    let head = || -> syn::Result<bool> {
        fork.call(syn::Attribute::parse_outer)?;
        fork.parse::<Token![pub]>()?;
        fork.parse::<Token![struct]>()?;
        fork.parse::<Ident>()?;
        let body;
        braced!(body in fork);
        Ok(body.call(Ident::parse_any).is_ok_and(|w| w == "space"))
    };
    head().unwrap_or(false)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::spatial::model::{JointKind, LoadKind};
    use nalgebra::Matrix3;

    const TEXT: &str = r#"
        /// A doc comment is accepted.
        pub struct Crank {
            space,
            consts { r: 50 mm, h: 2 * r },
            gravity: (0.0, 0.0, -9.81),
            ground { O: (0.0, 0.0, 0.0), G: (1 m, 0.0, h) },
            link crank { points { O, A: (0.0, r, 0.0) }, mass: 500 g, cg: (0.0, 20 mm, 0.0),
                         inertia: (1.0, 2.0, 3.0, 0.1, 0.2, 0.3) },
            link arm { points { A, B: (0.0, r, h) } },
            joints {
                O: revolute(ground, crank) axis (0.0, 0.0, 2.0),
                A: universal(crank, arm) axes (1.0, 0.0, 0.0) (0.0, 3.0, 0.0),
                slide: helical(ground, arm) at B axis (0.0, 0.0, 1.0) pitch 4 mm,
            },
            input: O,
            loads { t: torque on crank, f: force on arm at B },
        }
    "#;

    #[test]
    fn units_constants_axes_and_the_inertia_convention() {
        let m = parse(TEXT).unwrap();
        assert_eq!(m.name, "Crank");
        let p = |n: &str| m.points[m.point_index(n).unwrap()].1;
        assert_eq!(p("G"), Vector3::new(1.0, 0.0, 0.1));
        assert_eq!(p("A"), Vector3::new(0.0, 0.05, 0.0));
        assert_eq!(p("B"), Vector3::new(0.0, 0.05, 0.1));
        let crank = &m.bodies[m.body_index("crank").unwrap()];
        assert_eq!(crank.mass, 0.5);
        assert_eq!(crank.cg, Some(Vector3::new(0.0, 0.02, 0.0)));
        // products of inertia Ixy = Σ m x y enter the tensor with a minus sign
        assert_eq!(
            crank.inertia,
            Matrix3::new(1.0, -0.1, -0.2, -0.1, 2.0, -0.3, -0.2, -0.3, 3.0)
        );
        assert_eq!(m.joints[0].kind, JointKind::Revolute { axis: Vector3::z() });
        assert_eq!(
            m.joints[1].kind,
            JointKind::Universal {
                first: Vector3::x(),
                second: Vector3::y()
            }
        );
        assert_eq!(
            m.joints[2].kind,
            JointKind::Helical {
                axis: Vector3::z(),
                pitch: 0.004
            }
        );
        assert_eq!(m.joints[2].point, m.point_index("B").unwrap());
        assert_eq!(m.inputs, vec![0]);
        assert_eq!(
            m.loads[1].kind,
            LoadKind::Force {
                body: 2,
                point: m.point_index("B").unwrap()
            }
        );
        assert_eq!(m.gravity, Some(Vector3::new(0.0, 0.0, -9.81)));
    }

    fn message(text: &str) -> String {
        match parse(text) {
            Err(MechError::Invalid(m)) => m,
            other => panic!("{other:?}"),
        }
    }

    #[test]
    fn mistakes_are_named_and_located() {
        let m = message(&TEXT.replace("mass: 500 g", "mass: 500 mm"));
        assert!(m.starts_with("line 8, column 64: a mass is"), "{m}");
        let m = message(&TEXT.replace("(0.0, r, h)", "(0.0, r)"));
        assert!(
            m.contains("expected `(x, y, z)`") || m.contains("expected `,`"),
            "{m}"
        );
        let m = message(&TEXT.replace("revolute(ground, crank)", "revolute(ground, crunk)"));
        assert_eq!(
            m,
            "line 12, column 37: unknown link `crunk`: the links are `ground`, `crank`, `arm`"
        );
        let m = message(&TEXT.replace("at B axis", "at Q axis"));
        assert!(m.contains("point `Q` is not defined"), "{m}");
        let m = message(&TEXT.replace(" pitch 4 mm", ""));
        assert!(m.contains("needs its lead"), "{m}");
        let m = message(&TEXT.replace("f: force on arm at B", "f: force on crank at B"));
        assert!(m.contains("`B` is not a point of link `crank`"), "{m}");
        let m = message(&TEXT.replace(
            "inertia: (1.0, 2.0, 3.0, 0.1, 0.2, 0.3)",
            "inertia: (1.0, 2.0, 3.0, 5.0, 0.0, 0.0)",
        ));
        assert!(m.contains("not positive semi-definite"), "{m}");
        // magnitudes (docs/conventions.md#magnitudes): an infinity never reaches the solvers
        let m = message(&TEXT.replace("G: (1 m, 0.0, h)", "G: (1 m, 0.0, 1e999)"));
        assert!(
            m.contains(
                "point `G` is at (1e0, 0e0, inf) m: coordinates must be finite and within ±1e6 m"
            ),
            "{m}"
        );
        let m = message(&TEXT.replace("mass: 500 g", "mass: 1e12"));
        assert!(m.contains("a mass is 0 or within 1e-18 to 1e9 kg"), "{m}");
        let m = message(&TEXT.replace(
            "(1.0, 2.0, 3.0, 0.1, 0.2, 0.3)",
            "(1.0, 2.0, 3.0, 1e300, 0.2, 0.3)",
        ));
        assert!(m.contains("products within ±1e15"), "{m}");
        let m = message(&TEXT.replace("(0.0, 0.0, -9.81)", "(0.0, 0.0, -1e5)"));
        assert!(m.contains("gravity is (0e0, 0e0, -1e5) m/s²"), "{m}");
        let m = message(&TEXT.replace("pitch 4 mm", "pitch 1e999"));
        assert!(m.contains("the pitch inf m must be finite"), "{m}");
        let m = message(&TEXT.replace("A: universal", "B: universal"));
        assert!(
            m.contains("must be a point of both `crank` and `arm`"),
            "{m}"
        );
    }
}
