//! The grammar of the `mechanism!` DSL (`docs/conventions.md#dsl`), parsed with `syn` into a
//! [`Description`]. The macro and the run-time loader share this parser, so a mechanism
//! means the same thing whether it is compiled or read from text.

mod cams;
mod elements;
mod joints;
mod links;
mod scope;

use crate::model::units::Dim;
use crate::model::{Description, Name};
use elements::elements;
use joints::joints;
use links::{link_body, loads};
use proc_macro2::Span;
use scope::Scope;
use syn::parse::{Parse, ParseStream};
use syn::{braced, bracketed, Ident, Token};

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
