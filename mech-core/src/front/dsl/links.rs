//! The grammar of a link's body (`ground { .. }`, `link NAME { .. }`) and of the
//! `loads { .. }` block.

use super::scope::Scope;
use super::{comma, keyword, name};
use crate::model::units::Dim;
use crate::model::{LinkDecl, LoadDecl, LoadDeclKind, Name};
use proc_macro2::Span;
use syn::parse::ParseStream;
use syn::{braced, Ident, Token};

pub(super) fn link_body(
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

pub(super) fn loads(input: ParseStream) -> syn::Result<Vec<LoadDecl<Span>>> {
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
