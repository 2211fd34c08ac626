//! What the parser knows so far ([`Scope`]) and the grammar of what refers to it:
//! quantities and constant expressions, points and their constructions, a link's cg, an
//! input.

use super::{comma, keyword, name};
use crate::front::construction::{self, Branch, CIRCLE_CIRCLE_WORDS, CIRCLE_LINE_WORDS};
use crate::front::expr::{Constants, Quantity};
use crate::kernel::link_state::V2;
use crate::model::units::Dim;
use crate::model::{InputDecl, LinkDecl, Measure, Num, Pair, PointRef};
use proc_macro2::Span;
use syn::parse::ParseStream;
use syn::{parenthesized, Ident, Token};

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
pub(super) struct Scope {
    pub(super) consts: Constants,
    points: Vec<(String, V2)>,
    local_cgs: Vec<LocalCg>,
}

impl Scope {
    /// An expression where a quantity of dimension `dim` goes.
    pub(super) fn scalar(
        &self,
        input: ParseStream,
        dim: Dim,
        what: &str,
    ) -> syn::Result<Num<Span>> {
        let q = self.consts.expr(input)?;
        Ok(Num {
            value: q.expect(dim, what)?,
            span: q.span,
        })
    }

    /// A cam's lift: a length (a translating follower) or an angle (an oscillating one), or
    /// a plain number (SI: m or rad). `kind` keeps the first lift written with a unit (true
    /// for an angle) and where: every lift of a cam must be of the same kind.
    pub(super) fn lift(
        &self,
        input: ParseStream,
        kind: &mut Option<(bool, Span)>,
    ) -> syn::Result<f64> {
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
    pub(super) fn pair(&self, input: ParseStream, dim: Dim, what: &str) -> syn::Result<Pair<Span>> {
        let content;
        let paren = parenthesized!(content in input);
        let x = self.scalar(&content, dim, what)?;
        content.parse::<Token![,]>()?;
        let y = self.scalar(&content, dim, what)?;
        let _: Option<Token![,]> = content.parse()?;
        if !content.is_empty() {
            return Err(content.error("expected `(x, y)`: two numbers (a planar mechanism; a spatial one, with points `(x, y, z)`, starts with the word `space`: `pub struct Name { space, ... }`)"));
        }
        Ok(Pair {
            value: [x.value, y.value],
            span: paren.span.join(),
        })
    }

    /// The position of a point defined earlier.
    pub(super) fn point(&self, id: &Ident) -> syn::Result<V2> {
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
    pub(super) fn vector(&self, input: ParseStream) -> syn::Result<(V2, Span)> {
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
    pub(super) fn point_expr(&self, input: ParseStream) -> syn::Result<Pair<Span>> {
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
    pub(super) fn label(input: ParseStream) -> String {
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
    pub(super) fn construction(&self, id: &Ident, input: ParseStream) -> syn::Result<V2> {
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
    pub(super) fn branch(input: ParseStream, words: (&str, &str)) -> syn::Result<Branch> {
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
    pub(super) fn point_list(&mut self, input: ParseStream) -> syn::Result<Vec<PointRef<Span>>> {
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
    pub(super) fn cg(
        &mut self,
        input: ParseStream,
        link: usize,
    ) -> syn::Result<Option<Pair<Span>>> {
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
    pub(super) fn place_local_cgs(&self, links: &mut [LinkDecl<Span>]) -> syn::Result<()> {
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
    pub(super) fn input(&self, input: ParseStream) -> syn::Result<InputDecl<Span>> {
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
