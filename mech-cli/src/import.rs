//! `mech import FILE --input B,D [-o out.mech]`: a mechanism from pyslvs's PMKS expression
//! ([`crate::pmks`]) written as a `.mech` file.
//!
//! Joint i of the expression becomes the point `P<i>` at its coordinates (as given: pyslvs
//! has no units; `--unit mm` writes them in millimetres) and the joints between the links
//! it lists: an R joint of links l₁ … l_k is k − 1 revolute joints `J<i>`, `J<i>b`, … of
//! l₁ with each other link (of the ground when it is listed); a P or RP joint is a
//! prismatic or pin-in-slot joint `J<i>` of its slot link (the first) with its first pin
//! link along the slot's angle, and revolute joints of that link with the other pin links.
//! A slider's point belongs to its pin links only (a guide is given by its axis). The input
//! is given as in pyslvs, a pair (base joint, driver joint) of indices: the driven link is
//! the one holding both points, turning about the base (`--input 0,1`); a pair (i, i) on a
//! slider drives the slider. No masses: a comment says so.

use crate::pmks::{self, Kind};
use crate::{limits, Failure};
use std::fmt::Write;
use std::path::PathBuf;

/// `mech import` arguments.
#[derive(clap::Args, Debug)]
pub struct ImportArgs {
    /// The file with the PMKS expression (`-` = standard input).
    pub file: PathBuf,
    /// The `.mech` file to write (standard output when omitted).
    #[arg(short = 'o', long = "output")]
    pub output: Option<PathBuf>,
    /// An input as in pyslvs: base joint and driver joint indices, `B,D`. Repeatable.
    #[arg(long = "input", value_parser = parse_pair, allow_hyphen_values = true)]
    pub input: Vec<(usize, usize)>,
    /// The struct name of the mechanism.
    #[arg(long, default_value = "Imported")]
    pub name: String,
    /// The unit word of the expression's lengths (e.g. `mm`); none = as given.
    #[arg(long)]
    pub unit: Option<String>,
}

fn parse_pair(s: &str) -> Result<(usize, usize), String> {
    let (a, b) = s
        .split_once(',')
        .ok_or_else(|| format!("`{s}`: expected two joint indices `B,D`"))?;
    let index = |t: &str| {
        t.trim().parse::<usize>().map_err(|_| {
            format!("`{}`: not a joint index; give two indices 0, 1, 2, ... of the expression's joints, `B,D`", t.trim())
        })
    };
    Ok((index(a)?, index(b)?))
}

const GROUND: &str = "ground";

/// A Rust identifier of ASCII letters, digits and `_`, not starting with a digit.
fn is_ident(s: &str) -> bool {
    s.chars()
        .next()
        .is_some_and(|c| c.is_ascii_alphabetic() || c == '_')
        && s.chars().all(|c| c.is_ascii_alphanumeric() || c == '_')
}

/// A name the DSL accepts for a link (pyslvs allows `-`).
fn ident(name: &str) -> String {
    let s: String = name
        .chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() || c == '_' {
                c
            } else {
                '_'
            }
        })
        .collect();
    if s.chars().next().is_some_and(|c| c.is_ascii_digit()) {
        format!("L_{s}")
    } else {
        s
    }
}

/// The `.mech` text of the expression's joints with the pyslvs inputs.
pub fn to_mech(
    joints: &[pmks::Joint],
    name: &str,
    inputs: &[(usize, usize)],
    unit: Option<&str>,
) -> Result<String, Failure> {
    let n = joints.len();
    for &(b, d) in inputs {
        if b >= n || d >= n {
            return Err(Failure::usage(format!(
                "--input {b},{d}: the expression has {n} joints (0 to {})",
                n.saturating_sub(1)
            )));
        }
    }
    // The links in order of appearance, and the points of each.
    let mut links: Vec<String> = Vec::new();
    let mut points: Vec<Vec<usize>> = Vec::new();
    let mut ground_points = Vec::new();
    for (i, j) in joints.iter().enumerate() {
        let holders: &[String] = if j.kind == Kind::R {
            &j.links
        } else {
            j.links.get(1..).unwrap_or(&[])
        };
        for l in holders {
            if l == GROUND {
                ground_points.push(i);
                continue;
            }
            let k = match links.iter().position(|x| x == l) {
                Some(k) => k,
                None => {
                    links.push(l.clone());
                    points.push(Vec::new());
                    links.len() - 1
                }
            };
            if !points[k].contains(&i) {
                points[k].push(i);
            }
        }
        if let Some(slot) = j.links.first().filter(|_| j.kind != Kind::R) {
            if slot != GROUND && !links.contains(slot) {
                links.push(slot.clone());
                points.push(Vec::new());
            }
        }
    }
    // A driven link lists its base point, then its driver point: its angle is pyslvs's
    // input angle.
    let mut input_joints = Vec::new();
    for &(b, d) in inputs {
        if b == d {
            if joints[b].kind == Kind::R {
                return Err(Failure::usage(format!(
                    "--input {b},{d}: joint {b} is a pin; a pair (i, i) drives a slider"
                )));
            }
            input_joints.push(format!("J{b}"));
            continue;
        }
        let k = (0..links.len())
            .find(|&k| points[k].contains(&b) && points[k].contains(&d))
            .ok_or_else(|| {
                Failure::usage(format!(
                    "--input {b},{d}: no link holds both joint {b} and joint {d}"
                ))
            })?;
        points[k].retain(|&p| p != b && p != d);
        points[k].splice(0..0, [b, d]);
        let base = &joints[b];
        if base.kind != Kind::R {
            return Err(Failure::usage(format!(
                "--input {b},{d}: the base joint {b} must be a pin (R)"
            )));
        }
        let other = if base.links.iter().any(|l| l == GROUND) {
            GROUND.to_string()
        } else {
            base.links
                .iter()
                .find(|l| **l != links[k])
                .cloned()
                .unwrap_or_default()
        };
        input_joints.push(revolute_name(base, b, &other, &links[k]));
    }
    let unit = unit.map(|u| format!(" {u}")).unwrap_or_default();
    let at = |i: usize| format!("({}{unit}, {}{unit})", joints[i].at.0, joints[i].at.1);
    let mut out = String::new();
    let _ = writeln!(out, "/// Imported from a pyslvs PMKS expression by `mech import`. No masses: the expression has none;");
    let _ = writeln!(
        out,
        "/// add `mass`, `inertia` and `cg` to the links for kinetostatics and dynamics."
    );
    let _ = writeln!(out, "pub struct {name} {{");
    let defined = |i: usize, seen: &mut Vec<usize>| -> String {
        if seen.contains(&i) {
            format!("P{i}")
        } else {
            seen.push(i);
            format!("P{i}: {}", at(i))
        }
    };
    let mut seen = Vec::new();
    let ground: Vec<String> = ground_points
        .iter()
        .map(|&i| defined(i, &mut seen))
        .collect();
    let _ = writeln!(out, "    ground {{ {} }},", ground.join(", "));
    for (k, l) in links.iter().enumerate() {
        let pts: Vec<String> = points[k].iter().map(|&i| defined(i, &mut seen)).collect();
        let _ = writeln!(
            out,
            "    link {} {{ points {{ {} }} }},",
            ident(l),
            pts.join(", ")
        );
    }
    let _ = writeln!(out, "    joints {{");
    for (i, j) in joints.iter().enumerate() {
        match j.kind {
            Kind::R => {
                let first = if j.links.iter().any(|l| l == GROUND) {
                    GROUND.to_string()
                } else {
                    j.links.first().cloned().unwrap_or_default()
                };
                for other in j.links.iter().filter(|l| **l != first) {
                    let _ = writeln!(
                        out,
                        "        {}: revolute({}, {}) at P{i},",
                        revolute_name(j, i, &first, other),
                        ident(&first),
                        ident(other)
                    );
                }
            }
            Kind::P | Kind::RP => {
                let (Some(slot), Some(pin)) = (j.links.first(), j.links.get(1)) else {
                    continue;
                };
                let kw = if j.kind == Kind::P {
                    "prismatic"
                } else {
                    "pin_in_slot"
                };
                let a = j.angle.to_radians();
                let _ = writeln!(
                    out,
                    "        J{i}: {kw}({}, {}) at P{i} along ({:.15}, {:.15}),",
                    ident(slot),
                    ident(pin),
                    a.cos(),
                    a.sin()
                );
                for (n, other) in j.links[2..].iter().enumerate() {
                    let _ = writeln!(
                        out,
                        "        J{i}p{}: revolute({}, {}) at P{i},",
                        n + 1,
                        ident(pin),
                        ident(other)
                    );
                }
            }
        }
    }
    let _ = writeln!(out, "    }},");
    match input_joints.len() {
        0 => {}
        1 => {
            let _ = writeln!(out, "    input: {},", input_joints[0]);
        }
        _ => {
            let _ = writeln!(out, "    inputs: [{}],", input_joints.join(", "));
        }
    }
    let _ = writeln!(out, "}}");
    Ok(out)
}

/// The name of the revolute joint of R joint `i` between `first` and `other`: `J<i>` for
/// the first pair, then `J<i>b`, `J<i>c`, ...
fn revolute_name(j: &pmks::Joint, i: usize, first: &str, other: &str) -> String {
    let others: Vec<&String> = j.links.iter().filter(|l| *l != first).collect();
    let k = others.iter().position(|l| *l == other).unwrap_or(0);
    if k == 0 {
        format!("J{i}")
    } else {
        format!("J{i}{}", (b'a' + k as u8) as char)
    }
}

/// Run `mech import`.
pub fn run(args: ImportArgs, mut out: impl std::io::Write) -> Result<(), Failure> {
    if !is_ident(&args.name) {
        return Err(Failure::usage(format!(
            "--name `{}`: not a struct name; give letters, digits and `_`, not starting with a digit (e.g. `Imported`)",
            args.name
        )));
    }
    if let Some(u) = &args.unit {
        let length = mech_core::model::units::Dim::LENGTH;
        if !is_ident(u) || crate::quantity::parse(&format!("1 {u}"), length, "--unit").is_err() {
            return Err(Failure::usage(format!(
                "--unit `{u}`: not a unit word of length; give one such as `mm`, `cm` or `m`"
            )));
        }
    }
    if let Some(path) = &args.output {
        limits::writable(path, "-o", "mech")?;
    }
    let text = limits::read_text(&args.file, limits::MECH_BYTES, "the PMKS file")?;
    let origin = if args.file.as_os_str() == "-" {
        "<stdin>".to_string()
    } else {
        args.file.display().to_string()
    };
    let joints =
        pmks::parse(&text).map_err(|f| Failure::mechanism(format!("{origin}:{}", f.message)))?;
    let mech = to_mech(&joints, &args.name, &args.input, args.unit.as_deref())?;
    match &args.output {
        Some(path) => limits::write_file(path, &mech, "-o", "mech")?,
        None => {
            out.write_all(mech.as_bytes())?;
            out.flush()?;
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_crank_rocker_imports_and_checks() {
        let expr = "M[J[R, color[Green], P[0.0, 0.0], L[ground, L1]], J[R, color[Green], P[12.92, 32.53], L[L1, L2]], J[R, color[Green], P[73.28, 67.97], L[L2, L3]], J[R, color[Green], P[33.3, 66.95], L[L2]], J[R, color[Green], P[90.0, 0.0], L[ground, L3]]]";
        let text = to_mech(&pmks::parse(expr).unwrap(), "CrankRocker", &[(0, 1)], None).unwrap();
        assert!(
            text.contains("J0: revolute(ground, L1) at P0") && text.contains("input: J0"),
            "{text}"
        );
        let m = mech_core::Mechanism::from_dsl(&text).unwrap();
        // The drawing's input angle is pyslvs's: the angle of P0 → P1.
        let q = 32.53f64.atan2(12.92);
        let p = m.pose(&[q]).unwrap();
        let p2 = p.point("P2").unwrap().pos;
        assert!(
            (p2.x - 73.28).abs() < 1e-9 && (p2.y - 67.97).abs() < 1e-9,
            "{p2:?}"
        );
    }
}
