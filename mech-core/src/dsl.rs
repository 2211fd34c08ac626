//! The grammar of the `mechanism!` DSL (`docs/conventions.md#dsl`), parsed with `syn` into a
//! [`Description`]. The macro and the run-time loader share this parser, so a mechanism
//! means the same thing whether it is compiled or read from text.

use crate::model::{
    Description, JointDecl, JointKind, LinkDecl, LoadDecl, LoadDeclKind, Name, Num, Pair, PointRef,
};
use proc_macro2::Span;
use syn::parse::{Parse, ParseStream};
use syn::{braced, bracketed, parenthesized, Ident, LitFloat, LitInt, Token};

/// A parsed mechanism, spans as `proc_macro2::Span`.
pub struct Parsed(pub Description<Span>);

fn name(id: &Ident) -> Name<Span> {
    Name { text: id.to_string(), span: id.span() }
}

fn keyword(input: ParseStream, kw: &str) -> syn::Result<Ident> {
    let id: Ident = input.call(syn::ext::IdentExt::parse_any)?;
    if id != kw {
        return Err(syn::Error::new(id.span(), format!("expected `{kw}`, found `{id}`")));
    }
    Ok(id)
}

/// A number literal, negative allowed: `-0.5`, `3`, `2.1e-3`.
fn number(input: ParseStream) -> syn::Result<Num<Span>> {
    let neg: Option<Token![-]> = input.parse()?;
    let (value, span) = if input.peek(LitFloat) {
        let l: LitFloat = input.parse()?;
        (l.base10_parse::<f64>()?, l.span())
    } else if input.peek(LitInt) {
        let l: LitInt = input.parse()?;
        (l.base10_parse::<f64>()?, l.span())
    } else {
        return Err(input.error("expected a number, e.g. `0.25` or `-1.5e-3`"));
    };
    Ok(Num { value: if neg.is_some() { -value } else { value }, span })
}

/// `(x, y)`.
fn pair(input: ParseStream) -> syn::Result<Pair<Span>> {
    let content;
    let paren = parenthesized!(content in input);
    let x = number(&content)?;
    content.parse::<Token![,]>()?;
    let y = number(&content)?;
    let _: Option<Token![,]> = content.parse()?;
    if !content.is_empty() {
        return Err(content.error("expected `(x, y)`: two numbers"));
    }
    Ok(Pair { value: [x.value, y.value], span: paren.span.join() })
}

fn comma(input: ParseStream) -> syn::Result<()> {
    if !input.is_empty() {
        input.parse::<Token![,]>()?;
    }
    Ok(())
}

/// `A: (x, y), B, ...` inside braces.
fn point_list(input: ParseStream) -> syn::Result<Vec<PointRef<Span>>> {
    let mut out = Vec::new();
    while !input.is_empty() {
        let id: Ident = input.parse()?;
        let at = if input.peek(Token![:]) {
            input.parse::<Token![:]>()?;
            Some(pair(input)?)
        } else {
            None
        };
        out.push(PointRef { name: name(&id), at });
        comma(input)?;
    }
    Ok(out)
}

fn link_body(input: ParseStream, link_name: Name<Span>, ground: bool) -> syn::Result<LinkDecl<Span>> {
    let content;
    braced!(content in input);
    let mut decl = LinkDecl { name: link_name, points: Vec::new(), mass: None, inertia: None, cg: None };
    // `ground { O2: (0, 0), O4: (..) }` lists points directly.
    if ground && !content.peek2(syn::token::Brace) {
        decl.points = point_list(&content)?;
        return Ok(decl);
    }
    while !content.is_empty() {
        let key: Ident = content.parse()?;
        match key.to_string().as_str() {
            "points" => {
                let inner;
                braced!(inner in content);
                decl.points.extend(point_list(&inner)?);
            }
            "mass" if !ground => {
                content.parse::<Token![:]>()?;
                decl.mass = Some(number(&content)?);
            }
            "inertia" if !ground => {
                content.parse::<Token![:]>()?;
                decl.inertia = Some(number(&content)?);
            }
            "cg" if !ground => {
                content.parse::<Token![:]>()?;
                decl.cg = Some(pair(&content)?);
            }
            other => {
                let expected = if ground { "`points`" } else { "`points`, `mass`, `inertia` or `cg`" };
                return Err(syn::Error::new(key.span(), format!("unknown link property `{other}`: expected {expected}")));
            }
        }
        comma(&content)?;
    }
    Ok(decl)
}

fn joints(input: ParseStream) -> syn::Result<Vec<JointDecl<Span>>> {
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
            other => {
                return Err(syn::Error::new(
                    kw.span(),
                    format!("unknown joint kind `{other}`: expected `revolute`, `prismatic` or `pin_in_slot`"),
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
        while content.peek(Ident) {
            let k: Ident = content.parse()?;
            match k.to_string().as_str() {
                "at" => at = Some(name(&content.parse::<Ident>()?)),
                "along" => along = Some(pair(&content)?),
                other => {
                    return Err(syn::Error::new(k.span(), format!("unexpected `{other}`: expected `at POINT` or `along (ux, uy)`")))
                }
            }
        }
        out.push(JointDecl { name: name(&id), kind, kind_span: kw.span(), a: name(&a), b: name(&b), at, along });
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
                LoadDeclKind::Force { link: name(&link), point: name(&point) }
            }
            "torque" => {
                keyword(&content, "on")?;
                let link: Ident = content.parse()?;
                LoadDeclKind::Torque { link: name(&link) }
            }
            other => {
                return Err(syn::Error::new(
                    kw.span(),
                    format!("unknown load `{other}`: expected `force on LINK at POINT` or `torque on LINK`"),
                ))
            }
        };
        out.push(LoadDecl { name: name(&id), kind });
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
                    if let syn::Expr::Lit(syn::ExprLit { lit: syn::Lit::Str(s), .. }) = &nv.value {
                        docs.push(s.value());
                    }
                }
            } else if attr.path().is_ident("allow") {
                let arg: Ident = attr.parse_args()?;
                if arg != "redundant" {
                    return Err(syn::Error::new(arg.span(), "only `#[allow(redundant)]` is understood here"));
                }
                allow_redundant = true;
            } else {
                return Err(syn::Error::new_spanned(attr, "unsupported attribute: use doc comments or `#[allow(redundant)]`"));
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
        while !body.is_empty() {
            let key: Ident = body.call(syn::ext::IdentExt::parse_any)?;
            match key.to_string().as_str() {
                "gravity" => {
                    body.parse::<Token![:]>()?;
                    gravity = Some(pair(&body)?);
                }
                "ground" => {
                    if ground.is_some() {
                        return Err(syn::Error::new(key.span(), "duplicate `ground` block: list every ground point in one block"));
                    }
                    ground = Some(link_body(&body, name(&key), true)?);
                }
                "link" => {
                    let id: Ident = body.parse()?;
                    links.push(link_body(&body, name(&id), false)?);
                }
                "joints" => joint_list.extend(joints(&body)?),
                "input" => {
                    body.parse::<Token![:]>()?;
                    inputs_span = key.span();
                    inputs.push(name(&body.parse::<Ident>()?));
                }
                "inputs" => {
                    body.parse::<Token![:]>()?;
                    inputs_span = key.span();
                    let list;
                    bracketed!(list in body);
                    while !list.is_empty() {
                        inputs.push(name(&list.parse::<Ident>()?));
                        comma(&list)?;
                    }
                }
                "loads" => load_list.extend(loads(&body)?),
                other => {
                    return Err(syn::Error::new(
                        key.span(),
                        format!("unknown item `{other}`: expected `gravity`, `ground`, `link`, `joints`, `input`, `inputs` or `loads`"),
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
        Ok(Parsed(Description {
            docs,
            name: name(&struct_name),
            allow_redundant,
            gravity,
            ground,
            links,
            joints: joint_list,
            inputs,
            inputs_span,
            loads: load_list,
        }))
    }
}

/// Parse DSL text (the body of a `mechanism! { ... }`) at run time.
pub fn parse_str(text: &str) -> syn::Result<Description<Span>> {
    syn::parse_str::<Parsed>(text).map(|p| p.0)
}
