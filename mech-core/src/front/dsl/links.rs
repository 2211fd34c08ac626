//! The grammar of a link's body (`ground { .. }`, `link NAME { .. }`) and of the
//! `loads { .. }` block.

use super::scope::Scope;
use super::{comma, keyword, name};
use crate::model::shape::{material_named, material_names, Material, Shape};
use crate::model::units::Dim;
use crate::model::{FreeDecl, LinkDecl, LoadDecl, LoadDeclKind, MaterialDecl, Name, ShapeDecl};
use proc_macro2::Span;
use syn::ext::IdentExt;
use syn::parse::ParseStream;
use syn::{braced, parenthesized, Ident, Token};

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
        shape: None,
        material: None,
        counterweights: Vec::new(),
        plane: None,
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
            "shape" if !ground => {
                content.parse::<Token![:]>()?;
                decl.shape = Some(shape(&content, scope)?);
            }
            "counterweight" if ground => {
                return Err(syn::Error::new(
                    key.span(),
                    "a counterweight on the ground balances nothing: the ground does not move; put it on a moving link (`link crank { .., counterweight: (MASS, at (x, y)) }`)",
                ));
            }
            "counterweight" => {
                content.parse::<Token![:]>()?;
                let inner;
                parenthesized!(inner in content);
                let mass = scope.scalar(&inner, Dim::MASS, "a counterweight's mass")?;
                inner.parse::<Token![,]>()?;
                let at: Ident = inner.parse()?;
                if at != "at" {
                    return Err(syn::Error::new(
                        at.span(),
                        "expected `at`: write `counterweight: (MASS, at (x, y))`",
                    ));
                }
                let pos = scope.point_expr(&inner)?;
                let _: Option<Token![,]> = inner.parse()?;
                let mut plane = None;
                if inner.peek(Ident) {
                    let kw: Ident = inner.parse()?;
                    if kw != "plane" {
                        return Err(syn::Error::new(
                            kw.span(),
                            format!("unknown counterweight item `{kw}`: expected `plane: Z`, as in `counterweight: (MASS, at (x, y), plane: Z)`"),
                        ));
                    }
                    inner.parse::<Token![:]>()?;
                    plane = Some(scope.scalar(&inner, Dim::LENGTH, "a counterweight's plane")?);
                    let _: Option<Token![,]> = inner.parse()?;
                }
                if !inner.is_empty() {
                    return Err(inner
                        .error("expected `(MASS, at (x, y))` or `(MASS, at (x, y), plane: Z)`"));
                }
                decl.counterweights.push((mass, pos, plane, key.span()));
            }
            "plane" if !ground => {
                content.parse::<Token![:]>()?;
                decl.plane = Some(scope.scalar(&content, Dim::LENGTH, "a link's plane")?);
            }
            "material" if !ground => {
                decl.material = Some(material(&content, scope, key.span())?);
            }
            other => {
                let expected = if ground {
                    "`points`"
                } else {
                    "`points`, `mass`, `inertia`, `cg`, `shape`, `material`, `counterweight` or `plane`"
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

/// `KIND(name value, ..)`: each of the shape's dimensions once, a length.
fn shape(input: ParseStream, scope: &Scope) -> syn::Result<ShapeDecl<Span>> {
    let kw: Ident = input.parse()?;
    let keyword = kw.to_string();
    let Some(names) = Shape::dimension_names(&keyword) else {
        return Err(syn::Error::new(
            kw.span(),
            format!("unknown shape `{keyword}`: expected {}", Shape::FORMS),
        ));
    };
    let inner;
    parenthesized!(inner in input);
    let mut dims: Vec<Option<f64>> = vec![None; names.len()];
    let mut free = vec![None; names.len()];
    while !inner.is_empty() {
        let key = Ident::parse_any(&inner)?;
        let Some(k) = names.iter().position(|n| key == n) else {
            return Err(syn::Error::new(
                key.span(),
                format!(
                    "a `{keyword}` has no dimension `{key}`: it takes {}",
                    names.join(", ")
                ),
            ));
        };
        if dims[k].is_some() {
            return Err(syn::Error::new(
                key.span(),
                format!("`{key}` is given twice"),
            ));
        }
        let what = format!("the {keyword}'s {key}");
        let free_kw = inner.fork().parse::<Ident>().is_ok_and(|i| i == "free");
        dims[k] = Some(if free_kw && inner.peek2(syn::token::Paren) {
            let f = free_range(&inner, scope, &what)?;
            let lo = f.lo;
            free[k] = Some(f);
            lo
        } else {
            scope.scalar(&inner, Dim::LENGTH, &what)?.value
        });
        comma(&inner)?;
    }
    let dims = names
        .iter()
        .zip(&dims)
        .map(|(n, d)| {
            d.ok_or_else(|| {
                syn::Error::new(
                    kw.span(),
                    format!(
                        "a `{keyword}` needs its `{n}`: write {keyword}({})",
                        names
                            .iter()
                            .map(|n| format!("{n} .."))
                            .collect::<Vec<_>>()
                            .join(", ")
                    ),
                )
            })
        })
        .collect::<syn::Result<Vec<f64>>>()?;
    Ok(ShapeDecl {
        keyword,
        dims,
        free,
        span: kw.span(),
    })
}

/// `free(LO..HI)`: a dimension `mech size` chooses, 0 < LO < HI, lengths.
fn free_range(input: ParseStream, scope: &Scope, what: &str) -> syn::Result<FreeDecl<Span>> {
    let kw: Ident = input.parse()?;
    let range;
    let paren = parenthesized!(range in input);
    let lo = scope.scalar(&range, Dim::LENGTH, what)?;
    range.parse::<Token![..]>().map_err(|e| {
        syn::Error::new(
            e.span(),
            format!("{what}: write its range as `free(LO..HI)`, e.g. `free(10 mm..40 mm)`"),
        )
    })?;
    let hi = scope.scalar(&range, Dim::LENGTH, what)?;
    if !(lo.value > 0.0 && hi.value > lo.value && hi.value.is_finite()) {
        return Err(syn::Error::new(
            lo.span,
            format!(
                "{what}: `free(LO..HI)` needs 0 < LO < HI, got LO = {} m, HI = {} m",
                lo.value, hi.value
            ),
        ));
    }
    Ok(FreeDecl {
        lo: lo.value,
        hi: hi.value,
        span: kw.span(),
        end: paren.span.close(),
    })
}

/// `material: NAME` (a named material) or `material { density .., youngs .., yield ..,
/// ultimate .., endurance .. }`.
fn material(input: ParseStream, scope: &Scope, at: Span) -> syn::Result<MaterialDecl<Span>> {
    if input.peek(Token![:]) {
        input.parse::<Token![:]>()?;
        let id: Ident = input.parse()?;
        return match material_named(&id.to_string()) {
            Some(material) => Ok(MaterialDecl {
                material,
                span: id.span(),
            }),
            None => Err(syn::Error::new(
                id.span(),
                format!(
                    "unknown material `{id}`: the named materials are {}, or give its properties: `material {{ density 7850 kg_per_m3, youngs 205 GPa, yield 310 MPa, ultimate 565 MPa, endurance 282 MPa }}`",
                    material_names()
                ),
            )),
        };
    }
    let content;
    braced!(content in input);
    const KEYS: [(&str, Dim); 5] = [
        ("density", Dim::DENSITY),
        ("youngs", Dim::PRESSURE),
        ("yield", Dim::PRESSURE),
        ("ultimate", Dim::PRESSURE),
        ("endurance", Dim::PRESSURE),
    ];
    let mut v: [Option<f64>; 5] = [None; 5];
    while !content.is_empty() {
        let key = Ident::parse_any(&content)?;
        let Some(k) = KEYS.iter().position(|(n, _)| key == n) else {
            return Err(syn::Error::new(
                key.span(),
                format!("a material has no property `{key}`: give density, youngs, yield, ultimate and endurance"),
            ));
        };
        if v[k].is_some() {
            return Err(syn::Error::new(
                key.span(),
                format!("`{key}` is given twice"),
            ));
        }
        let value = scope.scalar(&content, KEYS[k].1, &format!("the material's {key}"))?;
        if !(value.value > 0.0) {
            return Err(syn::Error::new(
                value.span,
                format!("the material's {key} must be positive, got {}", value.value),
            ));
        }
        v[k] = Some(value.value);
        comma(&content)?;
    }
    let missing: Vec<&str> = KEYS
        .iter()
        .zip(&v)
        .filter(|(_, x)| x.is_none())
        .map(|((n, _), _)| *n)
        .collect();
    if !missing.is_empty() {
        return Err(syn::Error::new(
            at,
            format!("the material needs its {}: a block gives density, youngs, yield, ultimate and endurance", missing.join(", ")),
        ));
    }
    let [density, youngs, yield_strength, ultimate, endurance] = v.map(|x| x.unwrap_or(0.0));
    Ok(MaterialDecl {
        material: Material {
            name: "custom",
            density,
            youngs,
            yield_strength,
            ultimate,
            endurance,
        },
        span: at,
    })
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
