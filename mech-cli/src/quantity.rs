//! Numbers on the command line: SI, or with one unit word of the DSL glued or spaced
//! (`--at 30deg`, `--at "30 deg"`, `--speed 3000rpm`), or an expression (`--period
//! "4*PI"`), evaluated by the DSL's own [`mech_core::front::expr`].

use crate::Failure;
use mech_core::front::expr::Constants;
use mech_core::model::units::Dim;
use syn::parse::{ParseStream, Parser};

/// The value (SI) of `text` where a quantity of dimension `dim` goes (`what` names it in
/// messages); a plain number is SI.
pub fn parse(text: &str, dim: Dim, what: &str) -> Result<f64, Failure> {
    let c = Constants::default();
    let word = text
        .trim()
        .trim_start_matches(['-', '+'])
        .to_ascii_lowercase();
    if ["nan", "inf", "infinity"].contains(&word.as_str()) {
        return Err(Failure::usage(format!(
            "{what} `{}`: not a finite number; give a finite value, SI or with a unit word (`30deg`, `3000rpm`)",
            text.trim()
        )));
    }
    crate::limits::nesting(text, what)?;
    // `4pi`, `2 pi`, `4π`: a multiple of π, as written on the command line.
    let trimmed = text.trim();
    let expr = match trimmed
        .strip_suffix("pi")
        .or_else(|| trimmed.strip_suffix('π'))
    {
        Some(k) if !k.trim().is_empty() && k.trim().parse::<f64>().is_ok() => {
            format!("{} * PI", k.trim())
        }
        _ => trimmed.to_string(),
    };
    let text = expr.as_str();
    let q = (|input: ParseStream| {
        let q = c.expr(input)?;
        if !input.is_empty() {
            return Err(input.error("unexpected text after the number"));
        }
        Ok(q)
    })
    .parse_str(text)
    .map_err(|e| Failure::usage(format!("{what} `{text}`: {e}")))?;
    let v = q
        .expect(dim, what)
        .map_err(|e| Failure::usage(format!("{what} `{text}`: {e}")))?;
    if !v.is_finite() {
        return Err(Failure::usage(format!(
            "{what} `{text}`: overflows to {v}; give a value within ±1.8e308"
        )));
    }
    Ok(v)
}

/// The dimension of input `k`'s coordinate and of its rate: (angle, angular speed) for a
/// revolute input, (length, none) for a prismatic one.
pub fn input_dims(model: &mech_core::model::Model, k: usize) -> (Dim, Dim) {
    match model.joints[model.inputs[k]].kind {
        mech_core::model::JointKind::Revolute => (Dim::ANGLE, Dim::SPEED),
        _ => (Dim::LENGTH, Dim::NONE),
    }
}

/// One value per input from a list of texts (`--at 30deg --at 10mm`, or `--at 30deg,10mm`);
/// `default` when the list is empty.
pub fn per_input(
    texts: &[String],
    model: &mech_core::model::Model,
    rate: usize,
    what: &str,
    default: f64,
) -> Result<Vec<f64>, Failure> {
    let g = model.inputs.len();
    if texts.is_empty() {
        return Ok(vec![default; g]);
    }
    if texts.len() != g {
        return Err(Failure::usage(format!("{what}: {} value(s) given for {g} input(s); give one per input, in the order of `inputs`", texts.len())));
    }
    texts
        .iter()
        .enumerate()
        .map(|(k, t)| {
            let (d, v) = input_dims(model, k);
            let dim = match rate {
                0 => d,
                1 => v,
                _ => Dim::NONE,
            };
            parse(t, dim, what)
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn units_glued_or_spaced() {
        assert!((parse("30deg", Dim::ANGLE, "q").unwrap() - 30f64.to_radians()).abs() < 1e-16);
        assert!((parse("30 deg", Dim::ANGLE, "q").unwrap() - 30f64.to_radians()).abs() < 1e-16);
        assert_eq!(parse("0.5", Dim::ANGLE, "q").unwrap(), 0.5);
        assert!(
            (parse("3000rpm", Dim::SPEED, "speed").unwrap() - 100.0 * std::f64::consts::PI).abs()
                < 1e-12
        );
        assert!(
            (parse("4*PI", Dim::ANGLE, "period").unwrap() - 4.0 * std::f64::consts::PI).abs()
                < 1e-15
        );
        assert_eq!(
            parse("4pi", Dim::ANGLE, "period").unwrap(),
            4.0 * std::f64::consts::PI
        );
        assert_eq!(
            parse("2 π", Dim::ANGLE, "period").unwrap(),
            2.0 * std::f64::consts::PI
        );
        let e = parse("30 mm", Dim::ANGLE, "--at").unwrap_err();
        assert!(
            e.message.contains("an angle") && e.status == 2,
            "{}",
            e.message
        );
        assert!(parse("thirty", Dim::ANGLE, "--at").is_err());
    }
}
