//! The numbers a generated struct (or the generic solver) works with, derived from a
//! resolved [`Model`]: local joint geometry, link data, the drawing's states.

use crate::elements::springs::ElementGeom;
use crate::kernel::constraints::JointGeom;
use crate::kernel::dyad::{branch, branch_quantity, Solver};
use crate::kernel::link_state::{quotient, LinkGeom, LinkState, V2};
use crate::model::shape::{MassProperties, Material, Shape};
use crate::model::{Load, Model};
use crate::plan::geometry::{anchor, drawing_states, joint_geoms, local};
use crate::MechError;

/// A mechanism's numbers, ready for the solvers.
#[derive(Clone, Debug, PartialEq)]
pub struct Instance {
    /// Joint geometry, joint order.
    pub joints: Vec<JointGeom>,
    /// Link data, link order (ground first).
    pub links: Vec<LinkGeom>,
    /// The drawing's states.
    pub drawing: Vec<LinkState>,
    /// Per point: (owner link, local vector in it).
    pub points: Vec<(usize, V2)>,
    /// Per load: local vector of its point in its link (zero for torques).
    pub loads: Vec<V2>,
    /// The force elements with their points in their links' frames.
    pub elements: Vec<ElementGeom>,
    /// The gear pairs and racks, in joint order.
    pub meshes: Vec<crate::elements::gears::MeshGeom>,
    /// The cams, in joint order.
    pub cams: Vec<crate::elements::cam::CamGeom>,
    /// The drawing's length scale, m.
    pub scale: f64,
    /// Gravity, m/s² (zero when not declared).
    pub gravity: V2,
}

/// Derive the numbers of `model`. Runs the drawing and rank checks (`docs/conventions.md#checks`)
/// (the same code the macro runs), so a run-time change of parameters is checked too.
pub fn instance(model: &Model) -> Result<Instance, MechError> {
    let issues = crate::checks::validate::runtime(model);
    if !issues.is_empty() {
        let msg = issues
            .iter()
            .map(|i| i.message.as_str())
            .collect::<Vec<_>>()
            .join("\n");
        return Err(MechError::Invalid(msg));
    }
    let links = (0..model.links.len())
        .map(|l| {
            let link = &model.links[l];
            let th = model.reference_angle(l);
            let (dcg, mass, inertia) = (
                local(model, l, link.cg),
                link.mass.unwrap_or(0.0),
                link.rotational_inertia(),
            );
            let dir_ref = V2::new(th.cos(), th.sin());
            LinkGeom {
                anchor: anchor(model, l),
                dir_ref,
                angle_ref: dir_ref.y.atan2(dir_ref.x),
                dcg,
                mass,
                inertia,
                inertia_pivot: inertia
                    + mass
                        * match model.ground_pivot(l) {
                            Some(o) => {
                                let (g, o) = (link.cg, model.points[o].pos);
                                (g[0] - o[0]).powi(2) + (g[1] - o[1]).powi(2)
                            }
                            None => dcg.norm_squared(),
                        },
                cg_span: match link.points.get(1) {
                    Some(&p2) => {
                        let a = local(model, l, model.points[p2].pos);
                        if a.norm_squared() > 0.0 {
                            quotient(dcg, a)
                        } else {
                            V2::zeros()
                        }
                    }
                    None => V2::zeros(),
                },
                plane: link.axial.plane,
                product: V2::new(link.axial.product[0], link.axial.product[1]),
            }
        })
        .collect();
    let points = (0..model.points.len())
        .map(|p| {
            let owner = (0..model.links.len())
                .find(|&l| model.links[l].points.contains(&p))
                .unwrap_or(0);
            (owner, local(model, owner, model.points[p].pos))
        })
        .collect();
    let loads = model
        .loads
        .iter()
        .map(|l| match l {
            Load::Force { link, point, .. } => local(model, *link, model.points[*point].pos),
            Load::Torque { .. } => V2::zeros(),
        })
        .collect();
    let elements = model
        .elements
        .iter()
        .map(|e| {
            let (da, db) = match e.points {
                Some([p, q]) => (
                    local(model, e.a, model.points[p].pos),
                    local(model, e.b, model.points[q].pos),
                ),
                None => (V2::zeros(), V2::zeros()),
            };
            ElementGeom {
                a: e.a,
                b: e.b,
                rotary: !e.kind.linear(),
                da,
                db,
                stiffness: e.stiffness,
                damping: e.damping,
                free: e.free,
                reference: model.reference_angle(e.b) - model.reference_angle(e.a),
            }
        })
        .collect();
    let meshes = model
        .joints
        .iter()
        .enumerate()
        .filter_map(|(j, jt)| {
            let m = jt.mesh.as_ref()?;
            let pos = |p: usize| model.points[p].pos;
            let (oa, ob) = (pos(m.centres[0]), pos(m.centres[1]));
            let sign = if jt.kind == crate::model::JointKind::Rack {
                let (p, t) = crate::plan::geometry::pitch_point(model, j)?;
                let n = crate::kernel::link_state::perp(t);
                if n.dot(&(p - V2::new(oa[0], oa[1]))) >= 0.0 {
                    1.0
                } else {
                    -1.0
                }
            } else if m.internal {
                -1.0
            } else {
                1.0
            };
            let rack = jt.kind == crate::model::JointKind::Rack;
            Some(crate::elements::gears::MeshGeom {
                rack,
                ra: m.ra,
                rb: m.rb,
                ratios: crate::elements::gears::MeshGeom::ratios(rack, m.ra, m.rb),
                sign,
                tan_pressure: m.pressure_angle.tan(),
                ca: local(model, jt.a, oa),
                cb: local(model, jt.b, ob),
                carrier: m.carrier,
                inv_centre: if rack {
                    0.0
                } else {
                    1.0 / (V2::new(ob[0], ob[1]) - V2::new(oa[0], oa[1])).norm()
                },
            })
        })
        .collect();
    let cams = model
        .joints
        .iter()
        .filter_map(|jt| crate::plan::geometry::cam_geom(model, jt))
        .collect();
    Ok(Instance {
        elements,
        meshes,
        cams,
        joints: joint_geoms(model),
        links,
        drawing: drawing_states(model),
        points,
        loads,
        scale: model.scale(),
        gravity: model
            .gravity
            .map(|g| V2::new(g[0], g[1]))
            .unwrap_or_else(V2::zeros),
    })
}

impl Instance {
    /// The branch sign of each group's closed form in the drawing.
    pub fn branches(&self, solvers: &[Solver]) -> Vec<f64> {
        solvers
            .iter()
            .map(|&s| branch(branch_quantity(s, &self.joints, &self.drawing)))
            .collect()
    }

    /// The error of a result of `model` that is not finite in the states `s`: when a
    /// linear spring or damper has its two ends at the same place there
    /// ([`crate::elements::springs::undirected`]), its force has no direction and is the
    /// cause: `InvalidInput` naming it, where, its numbers and the fix; otherwise `e`
    /// (an overflow). Called on the error path only.
    #[cold]
    #[inline(never)]
    pub fn blame_elements(&self, model: &Model, s: &[LinkState], e: MechError) -> MechError {
        let Some((k, at)) = crate::elements::springs::undirected(&self.elements, s) else {
            return e;
        };
        let el = &model.elements[k];
        let kind = el.kind.keyword();
        let ends = match el.points {
            Some([p, q]) => format!(
                "{} at {}, {} at {}",
                model.links[el.a].name,
                model.points[p].name,
                model.links[el.b].name,
                model.points[q].name
            ),
            None => String::new(),
        };
        let numbers = if el.kind.spring() {
            format!("stiffness {} N/m, free length {} m", el.stiffness, el.free)
        } else {
            format!("damping {} N·s/m", el.damping)
        };
        MechError::InvalidInput(format!(
            "{kind} `{}` ({ends}) has its two ends at the same place, ({}, {}) m, in this configuration: a {kind} of zero length has no direction, so its force ({numbers}) is undefined there; keep its ends apart over the motion (move one of its points), or give a spring zero free length and no damper (its force k (Q − P) is then zero there)",
            el.name, at.x, at.y
        ))
    }
}

/// Mass data of a link as a run-time parameter.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct LinkParams {
    /// Mass, kg (0 = massless).
    pub mass: f64,
    /// Moment of inertia about the cg, kg·m².
    pub inertia: f64,
    /// A flywheel keyed to the link (kg·m², 0 = none): a pure rotor whose inertia adds to
    /// the link's on every route (d'Alembert, virtual power, Zhukovski's I*, the kinetic
    /// energy), so that the direct problem of a machine with its flywheel is one call.
    pub flywheel: f64,
    /// Centre of gravity in the drawing, m.
    pub cg: V2,
}

/// A linear spring's run-time parameters (`spring(a at P, b at Q)`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SpringParams {
    /// k, N/m, ≥ 0.
    pub stiffness: f64,
    /// L₀, the unloaded length, m, ≥ 0 (a declared `preload` F₀ is L_drawing − F₀/k).
    pub free_length: f64,
}

/// A linear damper's run-time parameter (`damper(a at P, b at Q)`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DamperParams {
    /// c, N·s/m, ≥ 0.
    pub damping: f64,
}

/// A torsion spring's run-time parameters (`torsion_spring(a, b)`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TorsionSpringParams {
    /// k, N·m/rad, ≥ 0.
    pub stiffness: f64,
    /// φ₀, the relative angle θ_b − θ_a at which it is unloaded, rad.
    pub free_angle: f64,
}

/// A rotary damper's run-time parameter (`rotary_damper(a, b)`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RotaryDamperParams {
    /// c, N·m·s/rad, ≥ 0.
    pub damping: f64,
}

/// A link declared by its shape and material (`shape:`, `material:`) as a run-time
/// parameter: the `shapes.<link>` field of a generated `<Name>Params`.
///
/// Its mass m (kg), I_G (kg·m²) and cg (m) are not parameters of their own: `from_params`
/// computes them from the shape's dimensions, the material's density ρ and the link's
/// points ([`Shape::mass_properties`], the formulas of [`crate::model::shape`]; the same
/// function as the loader's and `Mechanism::set_param("links.<l>.shape.<dimension>", ..)`)
/// and writes them into the link's [`LinkParams`], where `params()` shows them.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ShapeParams {
    /// The section and its dimensions, m (a change of kind, a `bar` made a `rod`, is
    /// allowed when the link's points can carry the new kind).
    pub shape: Shape,
    /// The material; its density ρ (kg/m³, > 0) gives the mass.
    pub material: Material,
    /// The mass properties the link's `LinkParams` hold from the last computation, to tell
    /// them from numbers written there by hand.
    held: Option<MassProperties>,
}

impl ShapeParams {
    /// `shape` of `material`. `held`: the mass, I_G and cg the link's [`LinkParams`] hold
    /// now, as last computed from a shape (`Default` and `from_params` keep them so), so
    /// that `from_params` refuses other numbers written there; `None` lets `from_params`
    /// replace whatever they hold.
    pub fn new(shape: Shape, material: Material, held: Option<MassProperties>) -> Self {
        ShapeParams {
            shape,
            material,
            held,
        }
    }

    /// Set the dimension `name` (`width`, `thickness`, `diameter`, `outer`, `inner`,
    /// `radius`: the names of [`Shape::dimensions`] and of
    /// `Mechanism::set_param("links.<l>.shape.<name>", ..)`) to `value`, m; an
    /// `InvalidInput` naming the shape's dimensions, or the bound broken (a positive
    /// length, a tube's bore inside its outer diameter), leaves the shape unchanged.
    pub fn set_dimension(&mut self, name: &str, value: f64) -> Result<(), MechError> {
        self.shape = self
            .shape
            .with_dimension(name, value)
            .map_err(MechError::InvalidInput)?;
        Ok(())
    }

    /// The mass properties last computed from the shape (what the link's `LinkParams`
    /// should hold), if any.
    pub fn held(&self) -> Option<MassProperties> {
        self.held
    }
}

/// Compute the mass m, I_G and cg of the link `name`, declared by `shape`, over its points
/// `points` (the drawing's coordinates, m, in the link's order) with
/// [`Shape::mass_properties`] at the material's density, and write them into `link`
/// (`from_params` calls this once per link declared by a shape). `InvalidInput`, naming
/// the link and the fix: a mass, inertia or cg written into `link` by hand (they differ
/// from what `shape` last held), a density that is not a positive number, a bad
/// dimension, points that cannot carry the shape.
pub fn update_shape(
    name: &str,
    link: &mut LinkParams,
    shape: &mut ShapeParams,
    points: &[[f64; 2]],
) -> Result<(), MechError> {
    if let Some(h) = shape.held {
        if link.mass != h.mass || link.inertia != h.inertia || [link.cg.x, link.cg.y] != h.cg {
            return Err(MechError::InvalidInput(format!(
                "link `{name}` is declared by its shape and material, which give its mass ({} kg), inertia ({} kg·m²) and cg ({}, {}) m, \
                 but the parameters give it mass {} kg, inertia {} kg·m² and cg ({}, {}) m: change its dimensions or material \
                 (`shapes.{name}`, e.g. `shapes.{name}.set_dimension(..)`) instead, and leave `links.{name}.mass`, `.inertia` and `.cg` as `params()` gave them",
                h.mass, h.inertia, h.cg[0], h.cg[1], link.mass, link.inertia, link.cg.x, link.cg.y
            )));
        }
    }
    let density = shape.material.density;
    if !(density.is_finite() && density > 0.0) {
        return Err(MechError::InvalidInput(format!(
            "link `{name}`: the density of its material `{}` must be a positive number of kg/m³, got {density}: set `shapes.{name}.material.density`",
            shape.material.name
        )));
    }
    let p = shape
        .shape
        .mass_properties(density, points)
        .map_err(|why| MechError::InvalidInput(format!("link `{name}`: {why}")))?;
    link.mass = p.mass;
    link.inertia = p.inertia;
    link.cg = V2::new(p.cg[0], p.cg[1]);
    shape.held = Some(p);
    Ok(())
}
