//! The grammar of a cam's motion: its law's segments or its table.

use super::comma;
use super::scope::Scope;
use crate::model::units::Dim;
use proc_macro2::Span;
use syn::parse::ParseStream;
use syn::{bracketed, parenthesized, Ident, Token};

/// A cam's table: `[(θ, s), ..]`, angles and lifts (lengths, or a rocker's angles).
pub(super) fn cam_points(
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
pub(super) fn cam_segments(
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
