//! The grammar of the `joints { .. }` block: `NAME: KIND(a, b)` and the options of each
//! kind (`at`, `along`, a gear's radii, a rolling wheel's track, a cam's law).

use super::cams::{cam_points, cam_segments};
use super::scope::Scope;
use super::{comma, name};
use crate::elements::cam::{Face, Segment};
use crate::model::units::Dim;
use crate::model::{CamDecl, JointDecl, JointKind, MeshDecl, Name, Num, Pair};
use proc_macro2::Span;
use syn::parse::ParseStream;
use syn::{braced, parenthesized, Ident, Token};

pub(super) fn joints(input: ParseStream, scope: &Scope) -> syn::Result<Vec<JointDecl<Span>>> {
    let content;
    braced!(content in input);
    let mut out = Vec::new();
    while !content.is_empty() {
        out.push(joint(&content, scope)?);
        comma(&content)?;
    }
    Ok(out)
}

/// The options written after a joint's links, as parsed so far.
struct Options {
    at: Option<Name<Span>>,
    along: Option<Pair<Span>>,
    mesh: Option<MeshDecl<Span>>,
    around: Option<(Name<Span>, bool)>,
    cam_base: Option<Num<Span>>,
    cam_face: Face,
    cam_law: Option<(Vec<(Segment, Span)>, Span)>,
    cam_table: Vec<[f64; 2]>,
    cam_lift: Option<(bool, Span)>,
    pin: Option<(Num<Span>, bool)>,
}

/// One joint: `NAME: KIND(a, b) OPTIONS`.
fn joint(content: ParseStream, scope: &Scope) -> syn::Result<JointDecl<Span>> {
    let id: Ident = content.parse()?;
    content.parse::<Token![:]>()?;
    let kw: Ident = content.parse()?;
    let kind = joint_kind(&kw)?;
    let args;
    parenthesized!(args in content);
    let a: Ident = args.call(syn::ext::IdentExt::parse_any)?;
    args.parse::<Token![,]>()?;
    let b: Ident = args.call(syn::ext::IdentExt::parse_any)?;
    let _: Option<Token![,]> = args.parse()?;
    let mut o = Options {
        at: None,
        along: None,
        mesh: None,
        around: None,
        cam_base: None,
        cam_face: Face::Knife,
        cam_law: None,
        cam_table: Vec::new(),
        cam_lift: None,
        pin: None,
    };
    while content.peek(Ident) {
        let k: Ident = content.parse()?;
        option(content, scope, kind, &k, &mut o)?;
    }
    let Options {
        at,
        along,
        mesh,
        around,
        cam_base,
        cam_face,
        cam_law,
        cam_table,
        cam_lift,
        pin,
    } = o;
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
    radii_given(kind, &kw, &id, &a, &b, &mesh)?;
    Ok(JointDecl {
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
        pin,
    })
}

/// The kind of joint `kw` names.
fn joint_kind(kw: &Ident) -> syn::Result<JointKind> {
    Ok(match kw.to_string().as_str() {
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
    })
}

/// One option `k` of a joint of kind `kind`, and its value.
fn option(
    content: ParseStream,
    scope: &Scope,
    kind: JointKind,
    k: &Ident,
    o: &mut Options,
) -> syn::Result<()> {
    match k.to_string().as_str() {
        "radii" if kind == JointKind::Gear && o.mesh.is_none() => {
            o.mesh = Some(MeshDecl {
                radii: scope.pair(content, Dim::LENGTH, "a pitch radius")?,
                internal: false,
                pressure_angle: None,
            });
        }
        "radius" if matches!(kind, JointKind::Rack | JointKind::Rolling) && o.mesh.is_none() => {
            let what = if kind == JointKind::Rack {
                "the pinion's pitch radius"
            } else {
                "the wheel's radius"
            };
            let r = scope.scalar(content, Dim::LENGTH, what)?;
            o.mesh = Some(MeshDecl {
                radii: Pair {
                    value: [r.value, 0.0],
                    span: r.span,
                },
                internal: false,
                pressure_angle: None,
            });
        }
        "base_radius" if kind == JointKind::Cam && o.cam_base.is_none() => {
            o.cam_base = Some(scope.scalar(content, Dim::LENGTH, "a cam's base radius")?);
        }
        "roller" if kind == JointKind::Cam => {
            let r = scope.scalar(content, Dim::LENGTH, "the roller's radius")?;
            o.cam_face = Face::Roller(r.value);
        }
        "flat" if kind == JointKind::Cam => o.cam_face = Face::Flat,
        "knife" if kind == JointKind::Cam => o.cam_face = Face::Knife,
        "law" if kind == JointKind::Cam && o.cam_law.is_none() => {
            o.cam_law = Some((cam_segments(content, scope, &mut o.cam_lift)?, k.span()));
        }
        "table" if kind == JointKind::Cam && o.cam_law.is_none() => {
            o.cam_table = cam_points(content, scope, &mut o.cam_lift)?;
            o.cam_law = Some((Vec::new(), k.span()));
        }
        "around" if kind == JointKind::Rolling && o.around.is_none() => {
            o.around = Some((name(&content.parse::<Ident>()?)?, false));
        }
        "inside" if kind == JointKind::Rolling && o.around.is_some() => {
            if let Some(a) = o.around.as_mut() {
                a.1 = true;
            }
        }
        "internal" if kind == JointKind::Gear && o.mesh.is_some() => {
            if let Some(m) = o.mesh.as_mut() {
                m.internal = true;
            }
        }
        "pressure_angle" if kind.mesh() && o.mesh.is_some() => {
            let a = scope.scalar(content, Dim::ANGLE, "a pressure angle")?;
            if let Some(m) = o.mesh.as_mut() {
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
        "pin" if kind == JointKind::Revolute && o.pin.is_none() => {
            let d = scope.scalar(content, Dim::LENGTH, "a pin's diameter")?;
            let double = content.peek(Ident) && content.fork().parse::<Ident>()? == "double";
            if double {
                content.parse::<Ident>()?;
            }
            o.pin = Some((d, double));
        }
        "at" => o.at = Some(name(&content.parse::<Ident>()?)?),
        "along" => {
            let (u, span) = scope.vector(content)?;
            o.along = Some(Pair {
                value: [u.x, u.y],
                span,
            });
        }
        other => {
            return Err(syn::Error::new(
                k.span(),
                format!("unexpected `{other}`: expected `at POINT`, `along (ux, uy)` or, on a revolute joint, `pin D [double]`"),
            ))
        }
    }
    Ok(())
}

/// A rolling joint has its wheel's radius, a gear pair its pitch radii, a rack its
/// pinion's.
fn radii_given(
    kind: JointKind,
    kw: &Ident,
    id: &Ident,
    a: &Ident,
    b: &Ident,
    mesh: &Option<MeshDecl<Span>>,
) -> syn::Result<()> {
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
    Ok(())
}
