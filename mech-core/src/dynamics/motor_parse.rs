//! A motor written as text (the `--motor MODEL` of `mech simulate` and `mech regime`, the
//! Python package's `motor=`): `dc(stall_torque T, no_load_speed W)`,
//! `induction(rated_power P, synchronous_speed W, rated_speed W, breakdown_ratio K)`,
//! `table(FILE.csv)`, `constant(T)`. Values are numbers in SI or with a unit word of the
//! DSL (`3000 rpm`, `12 N_m`), or expressions of them.

use super::motor::Motor;
use crate::front::expr::Constants;
use crate::model::units::Dim;
use crate::MechError;
use syn::parse::{ParseStream, Parser};

/// The forms, for messages.
const FORMS: &str = "dc(stall_torque T, no_load_speed W), induction(rated_power P, synchronous_speed W, rated_speed W, breakdown_ratio K), table(FILE.csv) or constant(T)";

fn bad(text: &str, why: impl std::fmt::Display) -> MechError {
    MechError::InvalidInput(format!("motor `{text}`: {why}; write one of {FORMS}"))
}

/// The value of `text` where a quantity of dimension `dim` goes.
fn quantity(text: &str, dim: Dim, what: &str) -> Result<f64, MechError> {
    let c = Constants::default();
    let parse = |input: ParseStream| {
        let q = c.expr(input)?;
        if !input.is_empty() {
            return Err(input.error("unexpected text after the value"));
        }
        q.expect(dim, what)
    };
    let v = parse
        .parse_str(text)
        .map_err(|e| MechError::InvalidInput(format!("{what} `{}`: {e}", text.trim())))?;
    crate::error::check_finite(what, &[v])?;
    Ok(v)
}

impl Motor {
    /// The motor written `text` (see the module documentation); `table(PATH)` is read by
    /// `table(path)` (the caller's file access: columns `speed` (rad/s), `torque` (N·m)).
    pub fn parse(
        text: &str,
        table: &dyn Fn(&str) -> Result<Motor, MechError>,
    ) -> Result<Motor, MechError> {
        let t = text.trim();
        let (name, args) = t
            .split_once('(')
            .and_then(|(n, rest)| Some((n.trim(), rest.strip_suffix(')')?)))
            .ok_or_else(|| bad(t, "expected NAME(ARGUMENTS)"))?;
        if name == "table" {
            return table(args.trim());
        }
        let want: &[(&str, Dim)] = match name {
            "constant" => &[("torque", Dim::TORQUE)],
            "dc" => &[("stall_torque", Dim::TORQUE), ("no_load_speed", Dim::SPEED)],
            "induction" => &[
                ("rated_power", Dim::POWER),
                ("synchronous_speed", Dim::SPEED),
                ("rated_speed", Dim::SPEED),
                ("breakdown_ratio", Dim::NONE),
            ],
            other => return Err(bad(t, format!("unknown motor `{other}`"))),
        };
        let mut given: Vec<(&str, &str)> = Vec::new();
        for arg in args.split(',').map(str::trim).filter(|a| !a.is_empty()) {
            let (key, value) = match arg.split_once(char::is_whitespace) {
                // `constant(T)`: the value alone, spaced unit word and all (`2 N_m`).
                Some((k, _)) if name == "constant" && k != "torque" => ("torque", arg),
                Some((k, v)) => (k, v.trim()),
                None if name == "constant" => ("torque", arg),
                None => return Err(bad(t, format!("`{arg}` has no value: write `name value`"))),
            };
            given.push((key, value));
        }
        if let Some((k, _)) = given
            .iter()
            .find(|(k, _)| !want.iter().any(|(w, _)| w == k))
        {
            let names: Vec<&str> = want.iter().map(|(w, _)| *w).collect();
            return Err(bad(
                t,
                format!(
                    "`{name}` has no parameter `{k}` (it takes {})",
                    names.join(", ")
                ),
            ));
        }
        let mut v = Vec::with_capacity(want.len());
        for &(key, dim) in want {
            let mut found = given.iter().filter(|(k, _)| *k == key);
            let (Some((_, value)), None) = (found.next(), found.next()) else {
                return Err(bad(t, format!("`{name}` needs `{key}` exactly once")));
            };
            v.push(quantity(value, dim, &format!("the motor's {key}"))?);
        }
        match name {
            "constant" => Motor::constant(v[0]),
            "dc" => Motor::dc(v[0], v[1]),
            _ => Motor::induction(v[0], v[1], v[2], v[3]),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn no_table(_: &str) -> Result<Motor, MechError> {
        Err(MechError::InvalidInput("no tables here".into()))
    }

    #[test]
    fn the_forms_parse_with_units() {
        let rpm = std::f64::consts::PI / 30.0;
        let m = Motor::parse("dc(stall_torque 12 N_m, no_load_speed 3000 rpm)", &no_table).unwrap();
        assert_eq!(m, Motor::dc(12.0, 3000.0 * rpm).unwrap());
        let m = Motor::parse(
            "induction(rated_power 7500, synchronous_speed 1500 rpm, rated_speed 1440 rpm, breakdown_ratio 2.5)",
            &no_table,
        )
        .unwrap();
        assert_eq!(
            m,
            Motor::induction(7500.0, 1500.0 * rpm, 1440.0 * rpm, 2.5).unwrap()
        );
        assert_eq!(
            Motor::parse("constant(-4)", &no_table).unwrap(),
            Motor::constant(-4.0).unwrap()
        );
        for t in [
            "constant(3 N_m)",
            "constant(3N_m)",
            "constant(torque 3 N_m)",
            "constant(1.5 * 2)",
        ] {
            assert_eq!(
                Motor::parse(t, &no_table).unwrap(),
                Motor::constant(3.0).unwrap(),
                "{t}"
            );
        }
        let e = Motor::parse("table(x.csv)", &no_table)
            .unwrap_err()
            .to_string();
        assert!(e.contains("no tables here"));
    }

    /// A rated power in `kW` or `W` (`model::units`): `1.5 kW`, `1.5kW`, `(1 + 0.5) kW` and
    /// `1500 W` are the motor of 1500 (SI); a power where a torque goes, or a torque where
    /// the power goes, is refused naming the dimensions and the words.
    #[test]
    fn rated_power_in_watts_and_kilowatts() {
        let rpm = std::f64::consts::PI / 30.0;
        let si = Motor::induction(1500.0, 1500.0 * rpm, 1420.0 * rpm, 2.5).unwrap();
        for p in [
            "1.5 kW",
            "1.5kW",
            "(1 + 0.5) kW",
            "1500 W",
            "1500W",
            "0.5 kW * 3",
            "1500",
        ] {
            let text = format!(
                "induction(rated_power {p}, synchronous_speed 1500 rpm, rated_speed 1420 rpm, breakdown_ratio 2.5)"
            );
            assert_eq!(Motor::parse(&text, &no_table).unwrap(), si, "{p}");
        }
        let e = Motor::parse("constant(2 kW)", &no_table)
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("a torque (N·m)") && e.contains("a power (W)"),
            "{e}"
        );
        let e = Motor::parse(
            "induction(rated_power 12 N_m, synchronous_speed 1500 rpm, rated_speed 1420 rpm, breakdown_ratio 2.5)",
            &no_table,
        )
        .unwrap_err()
        .to_string();
        assert!(
            e.contains("rated_power") && e.contains("`W` or `kW`"),
            "{e}"
        );
    }

    #[test]
    fn bad_text_names_the_forms() {
        for (text, says) in [
            ("stepper(1)", "unknown motor `stepper`"),
            ("dc(stall_torque 1)", "needs `no_load_speed`"),
            ("dc(stall_torque 1 rpm, no_load_speed 3)", "stall_torque"),
            (
                "dc(stall_torque 1, no_load_speed 3, colour 2)",
                "no parameter `colour`",
            ),
            ("dc", "expected NAME(ARGUMENTS)"),
        ] {
            let e = Motor::parse(text, &no_table).unwrap_err().to_string();
            assert!(e.contains(says), "{text}: {e}");
        }
    }
}
