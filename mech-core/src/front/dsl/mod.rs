//! The grammar of the `mechanism!` DSL (`docs/conventions.md#dsl`), parsed with `syn` into a
//! [`Description`]. The macro and the run-time loader share this parser, so a mechanism
//! means the same thing whether it is compiled or read from text.

use crate::front::construction::{self, Branch, CIRCLE_CIRCLE_WORDS, CIRCLE_LINE_WORDS};
use crate::front::expr::{Constants, Quantity};
use crate::kernel::link_state::V2;
use crate::model::units::Dim;
use crate::model::{
    CamDecl, Description, ElementDecl, ElementKind, InputDecl, JointDecl, JointKind, LinkDecl,
    LoadDecl, LoadDeclKind, Measure, MeshDecl, Name, Num, Pair, PointRef, RestDecl,
};
use proc_macro2::Span;
use syn::parse::{Parse, ParseStream};
use syn::{braced, bracketed, parenthesized, Ident, Token};

/// A parsed mechanism, spans as `proc_macro2::Span`.
pub struct Parsed(pub Description<Span>);

/// A name of the mechanism (struct, link, point, joint, load). Raw identifiers (`r#fn`)
/// are refused: the generated code names its fields after these, and both readers (the
/// macro and the run-time loader) must agree on the name.
fn name(id: &Ident) -> syn::Result<Name<Span>> {
    let text = id.to_string();
    if let Some(bare) = text.strip_prefix("r#") {
        return Err(syn::Error::new(
            id.span(),
            format!("`{text}` is a raw identifier, which the DSL does not take as a name: rename it (e.g. `{bare}_`)"),
        ));
    }
    Ok(Name {
        text,
        span: id.span(),
    })
}

fn keyword(input: ParseStream, kw: &str) -> syn::Result<Ident> {
    let id: Ident = input.call(syn::ext::IdentExt::parse_any)?;
    if id != kw {
        return Err(syn::Error::new(
            id.span(),
            format!("expected `{kw}`, found `{id}`"),
        ));
    }
    Ok(id)
}

fn comma(input: ParseStream) -> syn::Result<()> {
    if !input.is_empty() {
        input.parse::<Token![,]>()?;
    }
    Ok(())
}

/// A `cg` in a link's own frame, placed once every point is known.
struct LocalCg {
    /// Index into `Description::links`.
    link: usize,
    /// (u, v) in the link's frame, m.
    at: (f64, f64),
    span: Span,
}

/// What the parser knows so far, in the order of the text: the named constants and the
/// points defined (ground first, then each link).
#[derive(Default)]
struct Scope {
    consts: Constants,
    points: Vec<(String, V2)>,
    local_cgs: Vec<LocalCg>,
}

impl Scope {
    /// An expression where a quantity of dimension `dim` goes.
    fn scalar(&self, input: ParseStream, dim: Dim, what: &str) -> syn::Result<Num<Span>> {
        let q = self.consts.expr(input)?;
        Ok(Num {
            value: q.expect(dim, what)?,
            span: q.span,
        })
    }

    /// A cam's lift: a length (a translating follower) or an angle (an oscillating one), or
    /// a plain number (SI: m or rad). `kind` keeps the first lift written with a unit (true
    /// for an angle) and where: every lift of a cam must be of the same kind.
    fn lift(&self, input: ParseStream, kind: &mut Option<(bool, Span)>) -> syn::Result<f64> {
        let q = self.consts.expr(input)?;
        let angular = match q.dim.filter(|d| *d != Dim::NONE) {
            None => return Ok(q.value),
            Some(Dim::ANGLE) => true,
            Some(Dim::LENGTH) => false,
            Some(d) => {
                return Err(syn::Error::new(
                    q.span,
                    format!("a cam's lift is a length (a translating follower: `rise 10 mm`) or an angle (an oscillating one: `rise 15 deg`), but this value is {}", d.describe()),
                ))
            }
        };
        match kind {
            Some((first, _)) if *first != angular => {
                let word = |a: bool| if a { "an angle" } else { "a length" };
                Err(syn::Error::new(
                    q.span,
                    format!("this lift is {}, but the cam's first lift is {}: a cam's lifts are all lengths (a translating follower) or all angles (an oscillating one)", word(angular), word(*first)),
                ))
            }
            Some(_) => Ok(q.value),
            None => {
                *kind = Some((angular, q.span));
                Ok(q.value)
            }
        }
    }

    /// `(x, y)`, each an expression of dimension `dim`.
    fn pair(&self, input: ParseStream, dim: Dim, what: &str) -> syn::Result<Pair<Span>> {
        let content;
        let paren = parenthesized!(content in input);
        let x = self.scalar(&content, dim, what)?;
        content.parse::<Token![,]>()?;
        let y = self.scalar(&content, dim, what)?;
        let _: Option<Token![,]> = content.parse()?;
        if !content.is_empty() {
            return Err(content.error("expected `(x, y)`: two numbers"));
        }
        Ok(Pair {
            value: [x.value, y.value],
            span: paren.span.join(),
        })
    }

    /// The position of a point defined earlier.
    fn point(&self, id: &Ident) -> syn::Result<V2> {
        let n = id.to_string();
        if let Some((_, p)) = self.points.iter().find(|(m, _)| *m == n) {
            return Ok(*p);
        }
        let hint = if self.consts.get(&n).is_some() {
            format!("`{n}` is a constant, not a point")
        } else {
            format!("point `{n}` is not defined yet")
        };
        Err(syn::Error::new(
            id.span(),
            format!("{hint}: a point built from others may use the ground's points and those defined above it (points are read in order: `ground`, then each link)"),
        ))
    }

    /// A vector: `(dx, dy)` or `polar(r, θ)`, m, with where it was written.
    fn vector(&self, input: ParseStream) -> syn::Result<(V2, Span)> {
        if input.peek(Ident) && input.peek2(syn::token::Paren) {
            let id: Ident = input.parse()?;
            if id != "polar" {
                return Err(syn::Error::new(
                    id.span(),
                    format!(
                        "expected a vector, `(dx, dy)` or `polar(length, angle)`, found `{id}(..)`"
                    ),
                ));
            }
            let content;
            parenthesized!(content in input);
            let r = self.scalar(&content, Dim::LENGTH, "the length of `polar`")?;
            content.parse::<Token![,]>()?;
            let t = self.scalar(&content, Dim::ANGLE, "the direction of `polar`")?;
            let _: Option<Token![,]> = content.parse()?;
            return Ok((construction::polar(r.value, t.value), id.span()));
        }
        let p = self.pair(input, Dim::LENGTH, "a vector component")?;
        Ok((V2::new(p.value[0], p.value[1]), p.span))
    }

    /// A point: coordinates `(x, y)`, a point defined earlier, `circle_circle(..)` or
    /// `circle_line(..)`, each followed by any number of `+ vector` / `- vector`.
    fn point_expr(&self, input: ParseStream) -> syn::Result<Pair<Span>> {
        let span = input.span();
        let mut p = if input.peek(syn::token::Paren) {
            let p = self.pair(input, Dim::LENGTH, "a point's coordinate")?;
            V2::new(p.value[0], p.value[1])
        } else {
            let id: Ident = input.parse()?;
            if input.peek(syn::token::Paren) {
                self.construction(&id, input)?
            } else {
                self.point(&id)?
            }
        };
        loop {
            if input.peek(Token![+]) {
                input.parse::<Token![+]>()?;
                p += self.vector(input)?.0;
            } else if input.peek(Token![-]) {
                input.parse::<Token![-]>()?;
                p -= self.vector(input)?.0;
            } else {
                return Ok(Pair {
                    value: [p.x, p.y],
                    span,
                });
            }
        }
    }

    /// The name a point argument is shown with in messages.
    fn label(input: ParseStream) -> String {
        if input.peek(Ident) && !input.peek2(syn::token::Paren) {
            input
                .fork()
                .parse::<Ident>()
                .map(|i| i.to_string())
                .unwrap_or_default()
        } else {
            "the point".to_string()
        }
    }

    /// `circle_circle(c1, r1, c2, r2, left|right)`, `circle_line(c, r, p, θ, forward|backward)`.
    fn construction(&self, id: &Ident, input: ParseStream) -> syn::Result<V2> {
        let content;
        parenthesized!(content in input);
        let kind = id.to_string();
        let words = match kind.as_str() {
            "circle_circle" => CIRCLE_CIRCLE_WORDS,
            "circle_line" => CIRCLE_LINE_WORDS,
            _ => {
                return Err(syn::Error::new(
                    id.span(),
                    format!("unknown construction `{kind}`: a point is `(x, y)`, a point name, `P + polar(r, angle)`, `P + (dx, dy)`, `circle_circle(..)` or `circle_line(..)`"),
                ))
            }
        };
        let c_name = Self::label(&content);
        let c = self.point_expr(&content)?;
        content.parse::<Token![,]>()?;
        let r = self.scalar(&content, Dim::LENGTH, "a radius")?;
        content.parse::<Token![,]>()?;
        let other_name = Self::label(&content);
        let other = self.point_expr(&content)?;
        content.parse::<Token![,]>()?;
        let x = if kind == "circle_circle" {
            self.scalar(&content, Dim::LENGTH, "a radius")?
        } else {
            self.scalar(&content, Dim::ANGLE, "the direction of the line")?
        };
        let branch = Self::branch(&content, words)?;
        if !content.is_empty() {
            return Err(content.error(format!(
                "expected `)` after the branch word `{}` or `{}`",
                words.0, words.1
            )));
        }
        let (c, o) = (
            V2::new(c.value[0], c.value[1]),
            V2::new(other.value[0], other.value[1]),
        );
        let result = if kind == "circle_circle" {
            construction::circle_circle(c, r.value, o, x.value, branch, (&c_name, &other_name))
        } else {
            construction::circle_line(c, r.value, o, x.value, branch, &c_name)
        };
        result.map_err(|m| syn::Error::new(id.span(), format!("`{kind}`: {m}")))
    }

    /// `, left` / `, right` (or forward / backward), or nothing.
    fn branch(input: ParseStream, words: (&str, &str)) -> syn::Result<Branch> {
        if input.is_empty() {
            return Ok(None);
        }
        input.parse::<Token![,]>()?;
        if input.is_empty() {
            return Ok(None);
        }
        let w: Ident = input.parse()?;
        match w.to_string() {
            s if s == words.0 => Ok(Some(1.0)),
            s if s == words.1 => Ok(Some(-1.0)),
            s => Err(syn::Error::new(
                w.span(),
                format!(
                    "unknown branch word `{s}`: expected `{}` or `{}`",
                    words.0, words.1
                ),
            )),
        }
    }

    /// `A: point, B, ...` inside braces; each defined point is known from here on.
    fn point_list(&mut self, input: ParseStream) -> syn::Result<Vec<PointRef<Span>>> {
        let mut out = Vec::new();
        while !input.is_empty() {
            let id: Ident = input.parse()?;
            let at = if input.peek(Token![:]) {
                input.parse::<Token![:]>()?;
                let at = self.point_expr(input)?;
                let n = id.to_string();
                if !self.points.iter().any(|(m, _)| *m == n) {
                    self.points.push((n, V2::new(at.value[0], at.value[1])));
                }
                Some(at)
            } else {
                None
            };
            out.push(PointRef {
                name: name(&id)?,
                at,
            });
            comma(input)?;
        }
        Ok(out)
    }

    /// `cg: (x, y)` (or any point), `cg: along(d)`, `cg: local(u, v)`; the last two are
    /// placed at the end ([`Scope::place_local_cgs`]), when every point is known.
    fn cg(&mut self, input: ParseStream, link: usize) -> syn::Result<Option<Pair<Span>>> {
        let span = input.span();
        if input.peek(Ident) && input.peek2(syn::token::Paren) {
            let id: Ident = input.fork().parse()?;
            if id == "along" || id == "local" {
                input.parse::<Ident>()?;
                let content;
                parenthesized!(content in input);
                let u = self.scalar(&content, Dim::LENGTH, "a distance along the link")?;
                let v = if id == "local" {
                    content.parse::<Token![,]>()?;
                    self.scalar(&content, Dim::LENGTH, "a distance across the link")?
                        .value
                } else {
                    0.0
                };
                let _: Option<Token![,]> = content.parse()?;
                if !content.is_empty() {
                    return Err(content.error(format!(
                        "expected `)`: `{id}` takes {} number(s)",
                        if id == "local" { 2 } else { 1 }
                    )));
                }
                self.local_cgs.push(LocalCg {
                    link,
                    at: (u.value, v),
                    span,
                });
                return Ok(None);
            }
        }
        self.point_expr(input).map(Some)
    }

    /// Place the cgs given in a link's own frame, from its first two points.
    fn place_local_cgs(&self, links: &mut [LinkDecl<Span>]) -> syn::Result<()> {
        for c in &self.local_cgs {
            let l = &mut links[c.link];
            let at = |k: usize| -> syn::Result<V2> {
                let Some(p) = l.points.get(k) else {
                    return Err(syn::Error::new(c.span, format!("`along` and `local` place the cg on the line from the link's first to its second point, but link `{}` has {} point(s)", l.name.text, l.points.len())));
                };
                let n = &p.name.text;
                self.points
                    .iter()
                    .find(|(m, _)| m == n)
                    .map(|(_, v)| *v)
                    .ok_or_else(|| {
                        syn::Error::new(
                            c.span,
                            format!(
                                "point `{n}` of link `{}` is never given coordinates",
                                l.name.text
                            ),
                        )
                    })
            };
            let (p0, p1) = (at(0)?, at(1)?);
            let g = construction::local(p0, p1, c.at.0, c.at.1).map_err(|m| {
                syn::Error::new(c.span, format!("the cg of link `{}`: {m}", l.name.text))
            })?;
            l.cg = Some(Pair {
                value: [g.x, g.y],
                span: c.span,
            });
        }
        Ok(())
    }

    /// `O2` or `O2 from z` (z an angle or a length, checked against the joint's kind
    /// when names are resolved).
    fn input(&self, input: ParseStream) -> syn::Result<InputDecl<Span>> {
        let id: Ident = input.parse()?;
        let from = if input.peek(Ident) {
            keyword(input, "from")?;
            let q: Quantity = self.consts.expr(input)?;
            Some(Measure {
                value: q.value,
                dim: q.dim,
                span: q.span,
            })
        } else {
            None
        };
        Ok(InputDecl {
            name: name(&id)?,
            from,
        })
    }
}

fn link_body(
    input: ParseStream,
    scope: &mut Scope,
    link_name: Name<Span>,
    ground: bool,
    index: usize,
) -> syn::Result<LinkDecl<Span>> {
    let content;
    braced!(content in input);
    let mut decl = LinkDecl {
        name: link_name,
        points: Vec::new(),
        mass: None,
        inertia: None,
        cg: None,
    };
    // `ground { O2: (0, 0), O4: (..) }` lists points directly.
    if ground && !content.peek2(syn::token::Brace) {
        decl.points = scope.point_list(&content)?;
        return Ok(decl);
    }
    while !content.is_empty() {
        let key: Ident = content.parse()?;
        match key.to_string().as_str() {
            "points" => {
                let inner;
                braced!(inner in content);
                decl.points.extend(scope.point_list(&inner)?);
            }
            "mass" if !ground => {
                content.parse::<Token![:]>()?;
                decl.mass = Some(scope.scalar(&content, Dim::MASS, "a mass")?);
            }
            "inertia" if !ground => {
                content.parse::<Token![:]>()?;
                decl.inertia = Some(scope.scalar(&content, Dim::INERTIA, "an inertia")?);
            }
            "cg" if !ground => {
                content.parse::<Token![:]>()?;
                decl.cg = scope.cg(&content, index)?;
            }
            other => {
                let expected = if ground {
                    "`points`"
                } else {
                    "`points`, `mass`, `inertia` or `cg`"
                };
                return Err(syn::Error::new(
                    key.span(),
                    format!("unknown link property `{other}`: expected {expected}"),
                ));
            }
        }
        comma(&content)?;
    }
    Ok(decl)
}

fn joints(input: ParseStream, scope: &Scope) -> syn::Result<Vec<JointDecl<Span>>> {
    let content;
    braced!(content in input);
    let mut out = Vec::new();
    while !content.is_empty() {
        let id: Ident = content.parse()?;
        content.parse::<Token![:]>()?;
        let kw: Ident = content.parse()?;
        let kind = match kw.to_string().as_str() {
            "revolute" => JointKind::Revolute,
            "prismatic" => JointKind::Prismatic,
            "pin_in_slot" => JointKind::PinInSlot,
            "gear" => JointKind::Gear,
            "rack" => JointKind::Rack,
            "rolling" => JointKind::Rolling,
            "cam" => JointKind::Cam,
            other => {
                return Err(syn::Error::new(
                    kw.span(),
                    format!("unknown joint kind `{other}`: expected `revolute`, `prismatic`, `pin_in_slot`, `gear`, `rack`, `rolling` or `cam`"),
                ))
            }
        };
        let args;
        parenthesized!(args in content);
        let a: Ident = args.call(syn::ext::IdentExt::parse_any)?;
        args.parse::<Token![,]>()?;
        let b: Ident = args.call(syn::ext::IdentExt::parse_any)?;
        let _: Option<Token![,]> = args.parse()?;
        let mut at = None;
        let mut along = None;
        let mut mesh: Option<MeshDecl<Span>> = None;
        let mut around = None;
        let mut cam_base: Option<Num<Span>> = None;
        let mut cam_face = crate::elements::cam::Face::Knife;
        let mut cam_law: Option<(Vec<(crate::elements::cam::Segment, Span)>, Span)> = None;
        let mut cam_table: Vec<[f64; 2]> = Vec::new();
        let mut cam_lift: Option<(bool, Span)> = None;
        while content.peek(Ident) {
            let k: Ident = content.parse()?;
            match k.to_string().as_str() {
                "radii" if kind == JointKind::Gear && mesh.is_none() => {
                    mesh = Some(MeshDecl {
                        radii: scope.pair(&content, Dim::LENGTH, "a pitch radius")?,
                        internal: false,
                        pressure_angle: None,
                    });
                }
                "radius"
                    if matches!(kind, JointKind::Rack | JointKind::Rolling) && mesh.is_none() =>
                {
                    let what = if kind == JointKind::Rack {
                        "the pinion's pitch radius"
                    } else {
                        "the wheel's radius"
                    };
                    let r = scope.scalar(&content, Dim::LENGTH, what)?;
                    mesh = Some(MeshDecl {
                        radii: Pair {
                            value: [r.value, 0.0],
                            span: r.span,
                        },
                        internal: false,
                        pressure_angle: None,
                    });
                }
                "base_radius" if kind == JointKind::Cam && cam_base.is_none() => {
                    cam_base = Some(scope.scalar(&content, Dim::LENGTH, "a cam's base radius")?);
                }
                "roller" if kind == JointKind::Cam => {
                    let r = scope.scalar(&content, Dim::LENGTH, "the roller's radius")?;
                    cam_face = crate::elements::cam::Face::Roller(r.value);
                }
                "flat" if kind == JointKind::Cam => cam_face = crate::elements::cam::Face::Flat,
                "knife" if kind == JointKind::Cam => cam_face = crate::elements::cam::Face::Knife,
                "law" if kind == JointKind::Cam && cam_law.is_none() => {
                    cam_law = Some((cam_segments(&content, scope, &mut cam_lift)?, k.span()));
                }
                "table" if kind == JointKind::Cam && cam_law.is_none() => {
                    cam_table = cam_points(&content, scope, &mut cam_lift)?;
                    cam_law = Some((Vec::new(), k.span()));
                }
                "around" if kind == JointKind::Rolling && around.is_none() => {
                    around = Some((name(&content.parse::<Ident>()?)?, false));
                }
                "inside" if kind == JointKind::Rolling && around.is_some() => {
                    if let Some(a) = around.as_mut() {
                        a.1 = true;
                    }
                }
                "internal" if kind == JointKind::Gear && mesh.is_some() => {
                    if let Some(m) = mesh.as_mut() {
                        m.internal = true;
                    }
                }
                "pressure_angle" if kind.mesh() && mesh.is_some() => {
                    let a = scope.scalar(&content, Dim::ANGLE, "a pressure angle")?;
                    if let Some(m) = mesh.as_mut() {
                        m.pressure_angle = Some(a);
                    }
                }
                _ if kind.mesh() => {
                    let form = if kind == JointKind::Gear {
                        "`gear(a, b) radii (r_a, r_b)`, then optionally `internal` and `pressure_angle α` (20° when omitted)"
                    } else {
                        "`rack(pinion, bar) radius r`, then optionally `pressure_angle α` (20° when omitted)"
                    };
                    return Err(syn::Error::new(
                        k.span(),
                        format!("unexpected `{k}` in a {}: write {form}", kind.keyword()),
                    ));
                }
                "at" => at = Some(name(&content.parse::<Ident>()?)?),
                "along" => {
                    let (u, span) = scope.vector(&content)?;
                    along = Some(Pair {
                        value: [u.x, u.y],
                        span,
                    });
                }
                other => {
                    return Err(syn::Error::new(
                        k.span(),
                        format!("unexpected `{other}`: expected `at POINT` or `along (ux, uy)`"),
                    ))
                }
            }
        }
        let cam = if kind == JointKind::Cam {
            let (Some(base_radius), Some((segments, law_span))) = (cam_base, cam_law) else {
                return Err(syn::Error::new(
                    kw.span(),
                    format!("cam `{id}` needs `base_radius R_b` and `law [..]` (or `table [(θ, s), ..]`): write e.g. `cam({a}, {b}) base_radius 40 mm roller 10 mm law [dwell 90 deg, cycloidal 90 deg rise 10 mm, dwell 60 deg, poly345 120 deg fall 10 mm]`"),
                ));
            };
            Some(CamDecl {
                base_radius,
                face: cam_face,
                segments,
                table: cam_table,
                law_span,
                angular: cam_lift.map(|k| k.0),
            })
        } else {
            None
        };
        if kind == JointKind::Rolling && mesh.is_none() {
            return Err(syn::Error::new(
                kw.span(),
                format!("rolling joint `{id}` has no wheel radius: write `rolling({a}, {b}) at C radius r along (ux, uy)` (a straight track) or `rolling({a}, {b}) at C radius r around D` (a circle centred at D), C the wheel's centre, e.g. `radius 50 mm`"),
            ));
        }
        if kind.mesh() && mesh.is_none() {
            return Err(syn::Error::new(
                kw.span(),
                if kind == JointKind::Gear {
                    format!("gear pair `{id}` has no pitch radii: write `gear({a}, {b}) radii (r_a, r_b)`, e.g. `radii (40 mm, 120 mm)`")
                } else {
                    format!("rack `{id}` has no pinion radius: write `rack({a}, {b}) radius r`, e.g. `radius 30 mm`")
                },
            ));
        }
        out.push(JointDecl {
            name: name(&id)?,
            kind,
            kind_span: kw.span(),
            a: name(&a)?,
            b: name(&b)?,
            at,
            along,
            mesh,
            around,
            cam,
        });
        comma(&content)?;
    }
    Ok(out)
}

fn loads(input: ParseStream) -> syn::Result<Vec<LoadDecl<Span>>> {
    let content;
    braced!(content in input);
    let mut out = Vec::new();
    while !content.is_empty() {
        let id: Ident = content.parse()?;
        content.parse::<Token![:]>()?;
        let kw: Ident = content.parse()?;
        let kind = match kw.to_string().as_str() {
            "force" => {
                keyword(&content, "on")?;
                let link: Ident = content.parse()?;
                keyword(&content, "at")?;
                let point: Ident = content.parse()?;
                LoadDeclKind::Force {
                    link: name(&link)?,
                    point: name(&point)?,
                }
            }
            "torque" => {
                keyword(&content, "on")?;
                let link: Ident = content.parse()?;
                LoadDeclKind::Torque { link: name(&link)? }
            }
            other => {
                return Err(syn::Error::new(
                    kw.span(),
                    format!(
                    "unknown load `{other}`: expected `force on LINK at POINT` or `torque on LINK`"
                ),
                ))
            }
        };
        out.push(LoadDecl {
            name: name(&id)?,
            kind,
        });
        comma(&content)?;
    }
    Ok(out)
}

/// A cam's table: `[(θ, s), ..]`, angles and lifts (lengths, or a rocker's angles).
fn cam_points(
    input: ParseStream,
    scope: &Scope,
    kind: &mut Option<(bool, Span)>,
) -> syn::Result<Vec<[f64; 2]>> {
    let list;
    bracketed!(list in input);
    let mut out = Vec::new();
    while !list.is_empty() {
        let pt;
        parenthesized!(pt in list);
        let th = scope.scalar(&pt, Dim::ANGLE, "a table's cam angle")?;
        pt.parse::<Token![,]>()?;
        let s = scope.lift(&pt, kind)?;
        out.push([th.value, s]);
        comma(&list)?;
    }
    Ok(out)
}

/// A cam's law: `[LAW SPAN (rise | fall) LIFT, ..]`, LAW one of `dwell` (no lift),
/// `uniform`, `harmonic`, `cycloidal`, `poly345`, `poly4567`; SPAN an angle, LIFT a
/// length (or an angle, for an oscillating follower); the segments follow each other from
/// the cam's angle 0.
fn cam_segments(
    input: ParseStream,
    scope: &Scope,
    kind: &mut Option<(bool, Span)>,
) -> syn::Result<Vec<(crate::elements::cam::Segment, Span)>> {
    use crate::elements::cam::{Law, Segment};
    let list;
    bracketed!(list in input);
    let (mut at, mut lift) = (0.0, 0.0);
    let mut out = Vec::new();
    while !list.is_empty() {
        let w: Ident = list.parse()?;
        let law = match w.to_string().as_str() {
            "dwell" => Law::Dwell,
            "uniform" => Law::Uniform,
            "harmonic" => Law::Harmonic,
            "cycloidal" => Law::Cycloidal,
            "poly345" => Law::Poly345,
            "poly4567" => Law::Poly4567,
            other => {
                return Err(syn::Error::new(
                    w.span(),
                    format!("unknown motion law `{other}`: expected `dwell`, `uniform`, `harmonic`, `cycloidal`, `poly345` or `poly4567`"),
                ))
            }
        };
        let span = scope.scalar(&list, Dim::ANGLE, "a segment's span")?;
        let rise = if law == Law::Dwell {
            0.0
        } else {
            let dir: Ident = list.parse()?;
            let sign = match dir.to_string().as_str() {
                "rise" => 1.0,
                "fall" => -1.0,
                other => {
                    return Err(syn::Error::new(
                        dir.span(),
                        format!("expected `rise` or `fall` and a lift after the segment's span, found `{other}`: e.g. `cycloidal 90 deg rise 10 mm`"),
                    ))
                }
            };
            sign * scope.lift(&list, kind)?
        };
        out.push((
            Segment {
                law,
                start: at,
                end: at + span.value,
                from: lift,
                to: lift + rise,
            },
            w.span(),
        ));
        at += span.value;
        lift += rise;
        comma(&list)?;
    }
    // A velocity jump where two segments meet is an infinite acceleration: refused at the
    // segment after it (an acceleration jump, an infinite jerk, is a designer's choice).
    let segs: Vec<Segment> = out.iter().map(|(g, _)| *g).collect();
    if let Ok(law) = crate::elements::cam::MotionLaw::from_segments(segs) {
        if let Some(j) = law.jumps(1e-9).into_iter().find(|j| j.order == 1) {
            let k = out
                .iter()
                .position(|(g, _)| (g.start - j.at).abs() < 1e-9)
                .unwrap_or(0);
            let (scale, unit) = if kind.is_some_and(|k| k.0) {
                (180.0 / std::f64::consts::PI, "°/rad")
            } else {
                (1e3, " mm/rad")
            };
            return Err(syn::Error::new(
                out[k].1,
                format!(
                    "the follower's velocity jumps from {:.4} to {:.4}{unit} at {:.2}°, where this segment starts: an infinite acceleration (the cam would hammer the follower); use laws that start and end at rest next to a dwell (harmonic, cycloidal, poly345, poly4567)",
                    j.before * scale,
                    j.after * scale,
                    j.at.to_degrees()
                ),
            ));
        }
    }
    Ok(out)
}

/// `LINK at POINT` (a linear element's end) or `LINK` (a rotary element's link).
fn element_end(args: ParseStream, linear: bool) -> syn::Result<(Name<Span>, Option<Name<Span>>)> {
    let link: Ident = args.call(syn::ext::IdentExt::parse_any)?;
    let at = if linear {
        keyword(args, "at")?;
        Some(name(&args.parse::<Ident>()?)?)
    } else {
        None
    };
    Ok((name(&link)?, at))
}

/// `elements { k1: spring(a at P, b at Q) stiffness 2 kN_per_m free_length 80 mm, ... }`
/// (`docs/conventions.md#elements`).
fn elements(input: ParseStream, scope: &Scope) -> syn::Result<Vec<ElementDecl<Span>>> {
    let content;
    braced!(content in input);
    let mut out = Vec::new();
    while !content.is_empty() {
        let id: Ident = content.parse()?;
        content.parse::<Token![:]>()?;
        let kw: Ident = content.parse()?;
        let kind = match kw.to_string().as_str() {
            "spring" => ElementKind::Spring,
            "damper" => ElementKind::Damper,
            "torsion_spring" => ElementKind::TorsionSpring,
            "rotary_damper" => ElementKind::RotaryDamper,
            other => {
                return Err(syn::Error::new(
                    kw.span(),
                    format!("unknown force element `{other}`: expected `spring(a at P, b at Q)`, `damper(a at P, b at Q)`, `torsion_spring(a, b)` or `rotary_damper(a, b)`"),
                ))
            }
        };
        let args;
        parenthesized!(args in content);
        let (a, pa) = element_end(&args, kind.linear())?;
        args.parse::<Token![,]>()?;
        let (b, pb) = element_end(&args, kind.linear())?;
        let _: Option<Token![,]> = args.parse()?;
        if !args.is_empty() {
            return Err(args.error("expected `)` after the element's two ends"));
        }
        let (coef_word, coef_dim, free_word, free_dim) = match kind {
            ElementKind::Spring => ("stiffness", Dim::STIFFNESS, "free_length", Dim::LENGTH),
            ElementKind::Damper => ("damping", Dim::DAMPING, "", Dim::NONE),
            ElementKind::TorsionSpring => (
                "stiffness",
                Dim::TORSIONAL_STIFFNESS,
                "free_angle",
                Dim::ANGLE,
            ),
            ElementKind::RotaryDamper => ("damping", Dim::TORSIONAL_DAMPING, "", Dim::NONE),
        };
        let preload_dim = if kind.linear() {
            Dim::FORCE
        } else {
            Dim::TORQUE
        };
        let mut coefficient = None;
        let mut rest = None;
        while content.peek(Ident) {
            let k: Ident = content.parse()?;
            let word = k.to_string();
            if word == coef_word && coefficient.is_none() {
                let what = format!("a {}'s {coef_word}", kind.keyword().replace('_', " "));
                coefficient = Some(scope.scalar(&content, coef_dim, &what)?);
            } else if kind.spring() && word == free_word && rest.is_none() {
                let what = format!(
                    "a {}'s {}",
                    kind.keyword().replace('_', " "),
                    free_word.replace('_', " ")
                );
                rest = Some(RestDecl::Free(scope.scalar(&content, free_dim, &what)?));
            } else if kind.spring() && word == "preload" && rest.is_none() {
                rest = Some(RestDecl::Preload(scope.scalar(
                    &content,
                    preload_dim,
                    "a preload",
                )?));
            } else {
                let expected = if kind.spring() {
                    format!("`{coef_word}` and one of `{free_word}` or `preload`")
                } else {
                    format!("`{coef_word}`")
                };
                return Err(syn::Error::new(
                    k.span(),
                    format!(
                        "unexpected `{word}` in {} `{id}`: a {} takes {expected}, each once",
                        kind.keyword(),
                        kind.keyword()
                    ),
                ));
            }
        }
        let Some(coefficient) = coefficient else {
            return Err(syn::Error::new(
                kw.span(),
                format!(
                    "{} `{id}` has no `{coef_word}`: write e.g. `{}`",
                    kind.keyword(),
                    match kind {
                        ElementKind::Spring =>
                            "spring(a at P, b at Q) stiffness 2 kN_per_m free_length 80 mm",
                        ElementKind::Damper => "damper(a at P, b at Q) damping 50 N_s_per_m",
                        ElementKind::TorsionSpring =>
                            "torsion_spring(a, b) stiffness 5 N_m_per_rad free_angle 0 deg",
                        ElementKind::RotaryDamper =>
                            "rotary_damper(a, b) damping 0.1 N_m_s_per_rad",
                    }
                ),
            ));
        };
        if kind.spring() && rest.is_none() {
            return Err(syn::Error::new(
                kw.span(),
                format!("{} `{id}` has no `{free_word}` and no `preload`: give its unloaded {} (`{free_word} ..`) or the tension it has in the drawing (`preload ..`, negative when compressed)", kind.keyword(), if kind.linear() { "length" } else { "angle" }),
            ));
        }
        out.push(ElementDecl {
            name: name(&id)?,
            kind,
            kind_span: kw.span(),
            a,
            pa,
            b,
            pb,
            coefficient,
            rest,
        });
        comma(&content)?;
    }
    Ok(out)
}

impl Parse for Parsed {
    fn parse(input: ParseStream) -> syn::Result<Self> {
        let mut docs = Vec::new();
        let mut allow_redundant = false;
        for attr in input.call(syn::Attribute::parse_outer)? {
            if attr.path().is_ident("doc") {
                if let syn::Meta::NameValue(nv) = &attr.meta {
                    if let syn::Expr::Lit(syn::ExprLit {
                        lit: syn::Lit::Str(s),
                        ..
                    }) = &nv.value
                    {
                        docs.push(s.value());
                    }
                }
            } else if attr.path().is_ident("allow") {
                let arg: Ident = attr.parse_args()?;
                if arg != "redundant" {
                    return Err(syn::Error::new(
                        arg.span(),
                        "only `#[allow(redundant)]` is understood here",
                    ));
                }
                allow_redundant = true;
            } else {
                return Err(syn::Error::new_spanned(
                    attr,
                    "unsupported attribute: use doc comments or `#[allow(redundant)]`",
                ));
            }
        }
        input.parse::<Token![pub]>()?;
        input.parse::<Token![struct]>()?;
        let struct_name: Ident = input.parse()?;
        let body;
        braced!(body in input);
        let mut gravity = None;
        let mut ground = None;
        let mut links = Vec::new();
        let mut joint_list = Vec::new();
        let mut inputs = Vec::new();
        let mut inputs_span = struct_name.span();
        let mut load_list = Vec::new();
        let mut element_list = Vec::new();
        let mut scope = Scope::default();
        while !body.is_empty() {
            let key: Ident = body.call(syn::ext::IdentExt::parse_any)?;
            match key.to_string().as_str() {
                "gravity" => {
                    body.parse::<Token![:]>()?;
                    gravity = Some(scope.pair(&body, Dim::ACCELERATION, "gravity")?);
                }
                "ground" => {
                    if ground.is_some() {
                        return Err(syn::Error::new(key.span(), "duplicate `ground` block: list every ground point in one block"));
                    }
                    ground = Some(link_body(&body, &mut scope, name(&key)?, true, usize::MAX)?);
                }
                "link" => {
                    let id: Ident = body.parse()?;
                    let index = links.len();
                    links.push(link_body(&body, &mut scope, name(&id)?, false, index)?);
                }
                "consts" => scope.consts.parse_block(&body)?,
                "joints" => joint_list.extend(joints(&body, &scope)?),
                "input" => {
                    body.parse::<Token![:]>()?;
                    inputs_span = key.span();
                    inputs.push(scope.input(&body)?);
                }
                "inputs" => {
                    body.parse::<Token![:]>()?;
                    inputs_span = key.span();
                    let list;
                    bracketed!(list in body);
                    while !list.is_empty() {
                        inputs.push(scope.input(&list)?);
                        comma(&list)?;
                    }
                }
                "loads" => load_list.extend(loads(&body)?),
                "elements" => element_list.extend(elements(&body, &scope)?),
                other => {
                    return Err(syn::Error::new(
                        key.span(),
                        format!("unknown item `{other}`: expected `consts`, `gravity`, `ground`, `link`, `joints`, `input`, `inputs`, `loads` or `elements`"),
                    ))
                }
            }
            comma(&body)?;
        }
        let ground = ground.ok_or_else(|| {
            syn::Error::new(struct_name.span(), "missing `ground { ... }` block: every mechanism needs a frame, e.g. `ground { O: (0.0, 0.0) }`")
        })?;
        if inputs.is_empty() {
            inputs_span = struct_name.span();
        }
        scope.place_local_cgs(&mut links)?;
        Ok(Parsed(Description {
            docs,
            name: name(&struct_name)?,
            allow_redundant,
            gravity,
            ground,
            links,
            joints: joint_list,
            inputs,
            inputs_span,
            loads: load_list,
            elements: element_list,
        }))
    }
}

/// Parse DSL text (the body of a `mechanism! { ... }`) at run time.
pub fn parse_str(text: &str) -> syn::Result<Description<Span>> {
    syn::parse_str::<Parsed>(text).map(|p| p.0)
}
