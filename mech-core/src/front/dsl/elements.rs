//! The grammar of the `elements { .. }` block: springs and dampers, linear and rotary.

use super::scope::Scope;
use super::{comma, keyword, name};
use crate::model::units::Dim;
use crate::model::{ElementDecl, ElementKind, Name, RestDecl};
use proc_macro2::Span;
use syn::parse::ParseStream;
use syn::{braced, parenthesized, Ident, Token};

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
pub(super) fn elements(input: ParseStream, scope: &Scope) -> syn::Result<Vec<ElementDecl<Span>>> {
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
