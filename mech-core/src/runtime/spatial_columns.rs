//! The columns of one configuration of a spatial mechanism (SPEC 3i), named as in
//! `docs/cli.md` ("Spatial mechanisms"): the planar columns ([`super::columns`]) with the
//! third components. `q` first (`q.<joint>` for several inputs), then `<point>.x`, `.y`,
//! `.z` and each link's rotation from the drawing as a unit quaternion `<link>.qw`, `.qx`,
//! `.qy`, `.qz`; as the parts ask ([`Part`]), `<point>.vx`, `.vy`, `.vz`, `.ax`, `.ay`,
//! `.az`, `<link>.omega_x`, `_y`, `_z`, `<link>.alpha_x`, `_y`, `_z`; the reactions
//! `<joint>.fx`, `.fy`, `.fz`, `.mx`, `.my`, `.mz` (by the joint's first link on its second,
//! the moment about the joint's point); `driver` (`driver.<joint>`), `virtual_power`
//! (`virtual_power.<joint>`), and for one input Zhukovski's `inertia`, `inertia_derivative`
//! and `moment`. SI units throughout, global axes.

use super::columns::Part;
use crate::spatial::{JointKind, SpatialLoads, SpatialMechanism};
use crate::MechError;

/// True when `text` (the body of a `mechanism! { ... }`) declares a spatial mechanism: the
/// first item between the struct's braces is the word `space`.
pub fn is_spatial(text: &str) -> bool {
    use proc_macro2::{Delimiter, TokenStream, TokenTree};
    let Ok(tokens) = text.parse::<TokenStream>() else {
        // Unbalanced text: look at the words (the spatial parser then says what is wrong).
        return text.split("struct").nth(1).is_some_and(|rest| {
            rest.split_once('{').is_some_and(|(_, body)| {
                let body = body.trim_start();
                body.strip_prefix("space")
                    .is_some_and(|r| !r.starts_with(|c: char| c.is_alphanumeric() || c == '_'))
            })
        });
    };
    let mut it = tokens.into_iter();
    while let Some(t) = it.next() {
        if matches!(&t, TokenTree::Ident(i) if i == "struct") {
            let _name = it.next();
            return match it.next() {
                Some(TokenTree::Group(g)) if g.delimiter() == Delimiter::Brace => matches!(
                    g.stream().into_iter().next(),
                    Some(TokenTree::Ident(i)) if i == "space"
                ),
                _ => false,
            };
        }
    }
    false
}

/// The names and units of a spatial mechanism's row.
#[derive(Clone, Debug)]
pub struct SpatialColumns {
    /// The parts computed (in the order of [`Part`]; no [`Part::Shaking`]).
    pub parts: Vec<Part>,
    /// Column names.
    pub names: Vec<String>,
    /// Their SI units (`1` for a quaternion's components).
    pub units: Vec<&'static str>,
}

/// The units (coordinate, motor action) of input `k` of `m`: (rad, N·m) for a revolute or
/// helical input, (m, N) for a prismatic one.
pub fn input_units(m: &SpatialMechanism, k: usize) -> (&'static str, &'static str) {
    let model = m.model();
    match model.joints[model.inputs[k]].kind {
        JointKind::Prismatic { .. } => ("m", "N"),
        _ => ("rad", "N·m"),
    }
}

impl SpatialColumns {
    /// The columns of `m` for `parts` (a mechanism with several inputs has no Zhukovski
    /// columns; [`Part::Shaking`] is not computed for a spatial mechanism).
    pub fn new(m: &SpatialMechanism, parts: &[Part]) -> Self {
        let model = m.model();
        let g = m.dof();
        let mut parts: Vec<Part> = Part::ALL
            .iter()
            .copied()
            .chain([Part::Points])
            .filter(|p| parts.contains(p))
            .filter(|&p| !(g != 1 && p == Part::Zhukovski))
            .collect();
        if parts.contains(&Part::Positions) {
            parts.retain(|&p| p != Part::Points);
        }
        let mut c = SpatialColumns {
            parts,
            names: Vec::new(),
            units: Vec::new(),
        };
        let per_input = |base: &str, k: usize| {
            if g == 1 {
                base.to_string()
            } else {
                format!("{base}.{}", model.joints[model.inputs[k]].name)
            }
        };
        let links = &model.bodies[1..];
        if c.has(Part::Inputs) {
            for k in 0..g {
                c.push(per_input("q", k), input_units(m, k).0);
            }
        }
        if c.has(Part::Positions) || c.has(Part::Points) {
            for (p, _) in &model.points {
                for s in ["x", "y", "z"] {
                    c.push(format!("{p}.{s}"), "m");
                }
            }
        }
        if c.has(Part::Positions) {
            for l in links {
                for s in ["qw", "qx", "qy", "qz"] {
                    c.push(format!("{}.{s}", l.name), "1");
                }
            }
        }
        if c.has(Part::Rates) {
            for (p, _) in &model.points {
                for s in ["vx", "vy", "vz"] {
                    c.push(format!("{p}.{s}"), "m/s");
                }
                for s in ["ax", "ay", "az"] {
                    c.push(format!("{p}.{s}"), "m/s²");
                }
            }
            for l in links {
                for s in ["omega_x", "omega_y", "omega_z"] {
                    c.push(format!("{}.{s}", l.name), "rad/s");
                }
                for s in ["alpha_x", "alpha_y", "alpha_z"] {
                    c.push(format!("{}.{s}", l.name), "rad/s²");
                }
            }
        }
        if c.has(Part::Reactions) {
            for j in &model.joints {
                for s in ["fx", "fy", "fz"] {
                    c.push(format!("{}.{s}", j.name), "N");
                }
                for s in ["mx", "my", "mz"] {
                    c.push(format!("{}.{s}", j.name), "N·m");
                }
            }
        }
        if c.has(Part::Driver) {
            for k in 0..g {
                c.push(per_input("driver", k), input_units(m, k).1);
            }
        }
        if c.has(Part::VirtualPower) {
            for k in 0..g {
                c.push(per_input("virtual_power", k), input_units(m, k).1);
            }
        }
        if c.has(Part::Zhukovski) {
            let (i, d, f) = if input_units(m, 0).0 == "m" {
                ("kg", "kg/m", "N")
            } else {
                ("kg·m²", "kg·m²/rad", "N·m")
            };
            c.push("inertia".into(), i);
            c.push("inertia_derivative".into(), d);
            c.push("moment".into(), f);
        }
        c
    }

    fn push(&mut self, name: String, unit: &'static str) {
        self.names.push(name);
        self.units.push(unit);
    }

    /// True when the columns include `p`.
    pub fn has(&self, p: Part) -> bool {
        self.parts.contains(&p)
    }

    /// The row at inputs (q, q̇, q̈) under `loads`, in the order of
    /// [`SpatialColumns::names`]: the kinematics, then what the parts ask (the
    /// kinetostatics for the reactions and `driver`, the virtual power for
    /// `virtual_power`, Zhukovski's reduction at `q[0]`).
    pub fn row(
        &self,
        m: &SpatialMechanism,
        q: &[f64],
        qd: &[f64],
        qdd: &[f64],
        loads: &SpatialLoads,
    ) -> Result<Vec<f64>, MechError> {
        let model = m.model();
        let mut row = Vec::with_capacity(self.names.len());
        if self.has(Part::Inputs) {
            row.extend_from_slice(q);
        }
        let rates = self.has(Part::Rates)
            || self.has(Part::Reactions)
            || self.has(Part::Driver)
            || self.has(Part::VirtualPower);
        let needs_motion = rates || self.has(Part::Positions) || self.has(Part::Points);
        let motion = if !needs_motion {
            None
        } else if rates {
            Some(m.kinematics(q, qd, qdd)?)
        } else {
            Some(m.pose(q)?)
        };
        if let Some(mo) = &motion {
            let points: Vec<[nalgebra::Vector3<f64>; 3]> = model
                .points
                .iter()
                .map(|(p, _)| {
                    mo.point_motion(p).ok_or_else(|| {
                        MechError::Invalid(format!("the point `{p}` belongs to no link"))
                    })
                })
                .collect::<Result<_, _>>()?;
            let links: Vec<crate::spatial::LinkMotion> = model.bodies[1..]
                .iter()
                .map(|b| mo.link(&b.name).expect("a body of the model"))
                .collect();
            if self.has(Part::Positions) || self.has(Part::Points) {
                row.extend(points.iter().flat_map(|p| p[0].iter().copied()));
            }
            if self.has(Part::Positions) {
                for l in &links {
                    let r = l.rotation.quaternion();
                    row.extend([r.w, r.i, r.j, r.k]);
                }
            }
            if self.has(Part::Rates) {
                for p in &points {
                    row.extend(p[1].iter().chain(p[2].iter()).copied());
                }
                for l in &links {
                    row.extend(l.omega.iter().chain(l.alpha.iter()).copied());
                }
            }
            if self.has(Part::Reactions) || self.has(Part::Driver) {
                let f = m.kinetostatics(mo, loads)?;
                if self.has(Part::Reactions) {
                    for r in &f.reactions {
                        row.extend(r.force.iter().chain(r.moment.iter()).copied());
                    }
                }
                if self.has(Part::Driver) {
                    row.extend_from_slice(&f.drivers);
                }
            }
            if self.has(Part::VirtualPower) {
                row.extend(m.driver_action(mo, loads)?);
            }
        }
        if self.has(Part::Zhukovski) {
            let z = m.reduced(q[0])?;
            row.extend([
                z.inertia,
                z.inertia_derivative,
                m.reduced_moment(q[0], loads)?,
            ]);
        }
        debug_assert_eq!(row.len(), self.names.len());
        Ok(row)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_first_item_decides() {
        assert!(is_spatial(
            "/// doc\npub struct R { space, ground { O: (0.0, 0.0, 0.0) } }"
        ));
        assert!(is_spatial("pub struct R {\n  // a comment\n  space }"));
        assert!(is_spatial("pub struct R { space, ground { O: (0.0, 0.0"));
        assert!(!is_spatial(
            "pub struct R { ground { O: (0.0, 0.0) }, space_x: 1 }"
        ));
        assert!(!is_spatial("pub struct R { spacer, }"));
        assert!(!is_spatial(""));
    }
}
