//! `SpatialMechanism::set_param`: one number of the drawing changed by name, the changed
//! model re-checked (the magnitudes and shapes the text's resolution checks, then every
//! load-time check) — for parameter sweeps and optimisation of spatial linkages.

use super::mechanism::SpatialMechanism;
use super::model::{inertia_tensor, JointKind};
use crate::checks::magnitudes::{in_range, COORDINATE, GRAVITY, INERTIA, MASS, WHY};
use crate::MechError;
use nalgebra::Vector3;

type V3 = Vector3<f64>;

impl SpatialMechanism {
    /// Change one number of the drawing by name, re-checked by every check of the loading
    /// (the mechanism is unchanged on error):
    /// - `points.<P>` = `[x, y, z]` (m), `links.<l>.cg` = `[x, y, z]` (m),
    /// - `links.<l>.mass` = `[m]` (kg), `links.<l>.inertia` = `[Ixx, Iyy, Izz, Ixy, Ixz,
    ///   Iyz]` (kg·m² about the cg in the drawing's axes, the products as the text writes
    ///   them: Ixy = Σ m x y),
    /// - `axes.<joint>` = `[ux, uy, uz]` (a revolute, prismatic, cylindrical or helical
    ///   joint's axis; normalised), six numbers for a universal joint's two axes,
    /// - `pitch.<joint>` = `[p]` (a helical joint's lead, m per turn),
    /// - `gravity` = `[gx, gy, gz]` (m/s²; `[]` removes it).
    pub fn set_param(&mut self, path: &str, value: &[f64]) -> Result<(), MechError> {
        crate::error::check_finite(path, value)?;
        let mut model = self.model().clone();
        let bad = |what: &str| MechError::InvalidInput(format!("no parameter `{path}`: {what}"));
        let count = |n: usize| -> Result<(), MechError> {
            if value.len() == n {
                Ok(())
            } else {
                Err(MechError::InvalidInput(format!(
                    "`{path}` takes {n} number(s), got {}",
                    value.len()
                )))
            }
        };
        let out_of_range =
            |what: String| MechError::InvalidInput(format!("`{path}`: {what} ({WHY})"));
        let vec3 = |v: &[f64]| V3::new(v[0], v[1], v[2]);
        let place = |v: &[f64]| -> Result<V3, MechError> {
            count(3)?;
            if v.iter().all(|x| x.abs() <= COORDINATE) {
                Ok(vec3(v))
            } else {
                Err(out_of_range(format!(
                    "coordinates must be within ±{COORDINATE:e} m"
                )))
            }
        };
        let unit = |v: &[f64]| -> Result<V3, MechError> {
            let u = vec3(v);
            let n = u.norm();
            if n > 1e-12 && n.is_finite() {
                Ok(u / n)
            } else {
                Err(MechError::InvalidInput(format!(
                    "`{path}` = {v:?} has no direction: give a nonzero vector"
                )))
            }
        };
        let parts: Vec<&str> = path.split('.').collect();
        match parts.as_slice() {
            ["points", p] => {
                let i = model.point_index(p).ok_or_else(|| bad("unknown point"))?;
                model.points[i].1 = place(value)?;
            }
            ["links", l, what] => {
                let i = model
                    .body_index(l)
                    .filter(|&i| i > 0)
                    .ok_or_else(|| bad("unknown moving link"))?;
                let body = &mut model.bodies[i];
                match *what {
                    "cg" => body.cg = Some(place(value)?),
                    "mass" => {
                        count(1)?;
                        if !in_range(value[0], MASS) {
                            return Err(out_of_range(format!(
                                "a mass is 0 or within {:e} to {:e} kg",
                                MASS.0, MASS.1
                            )));
                        }
                        body.mass = value[0];
                    }
                    "inertia" => {
                        count(6)?;
                        let sized = value[..3].iter().all(|&x| in_range(x, INERTIA))
                            && value[3..].iter().all(|&x| x.abs() <= INERTIA.1);
                        if !sized {
                            return Err(out_of_range(format!(
                                "moments are 0 or within {:e} to {:e} kg·m², products within ±{:e}",
                                INERTIA.0, INERTIA.1, INERTIA.1
                            )));
                        }
                        let t = inertia_tensor(std::array::from_fn(|k| value[k]));
                        if t.symmetric_eigenvalues().min() < -1e-12 * t.norm() {
                            return Err(MechError::InvalidInput(format!(
                                "`{path}`: the inertia tensor is not positive semi-definite: check the signs of the products Ixy, Ixz, Iyz (Ixy = Σ m x y)"
                            )));
                        }
                        body.inertia = t;
                    }
                    _ => return Err(bad("a link has `cg`, `mass` and `inertia`")),
                }
            }
            ["axes", j] => {
                let i = model.joint_index(j).ok_or_else(|| bad("unknown joint"))?;
                let kind = &mut model.joints[i].kind;
                match kind {
                    JointKind::Revolute { axis }
                    | JointKind::Prismatic { axis }
                    | JointKind::Cylindrical { axis }
                    | JointKind::Helical { axis, .. } => {
                        count(3)?;
                        *axis = unit(value)?;
                    }
                    JointKind::Universal { first, second } => {
                        count(6)?;
                        let (u, w) = (unit(&value[..3])?, unit(&value[3..])?);
                        if u.dot(&w).abs() > 1e-9 {
                            return Err(MechError::InvalidInput(format!(
                                "`{path}`: a universal joint's two axes are perpendicular, but these make {:.6}°",
                                u.dot(&w).clamp(-1.0, 1.0).acos().to_degrees()
                            )));
                        }
                        (*first, *second) = (u, w);
                    }
                    JointKind::Spherical => return Err(bad("a spherical joint has no axis")),
                }
            }
            ["pitch", j] => {
                let i = model.joint_index(j).ok_or_else(|| bad("unknown joint"))?;
                let JointKind::Helical { pitch, .. } = &mut model.joints[i].kind else {
                    return Err(bad("only a helical joint has a pitch"));
                };
                count(1)?;
                if !(value[0].abs() <= COORDINATE) {
                    return Err(out_of_range(format!(
                        "the pitch must be within ±{COORDINATE:e} m"
                    )));
                }
                *pitch = value[0];
            }
            ["gravity"] => {
                model.gravity = if value.is_empty() {
                    None
                } else {
                    count(3)?;
                    if !(vec3(value).norm() <= GRAVITY) {
                        return Err(out_of_range(format!(
                            "gravity must be at most {GRAVITY:e} m/s²; on Earth it is (0, 0, -9.81)"
                        )));
                    }
                    Some(vec3(value))
                }
            }
            _ => {
                return Err(bad(
                    "the parameters are `points.<P>`, `links.<l>.{cg, mass, inertia}`, `axes.<joint>`, `pitch.<joint>` and `gravity`",
                ))
            }
        }
        *self = SpatialMechanism::from_model(model)?;
        Ok(())
    }
}
