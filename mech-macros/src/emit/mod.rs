//! Emission: the generated struct and its solvers, as calls into mech-core's kernels.
//!
//! A small pipeline. [`Ctx`] gathers once the names, ids, counts and the declared terms
//! of one mechanism; each part emits the items it is named after, and [`mechanism`]
//! concatenates them:
//! - [`params`]: the struct and its constants, `Params`, `new`, `from_params`, `params`;
//! - [`plan`]: the Assur groups as constants, `__solve`, `__solve_on`, `__velocity_field`;
//! - [`results`]: `Pose`, `Motion`, their by-name accessors, `pose`, `kinematics`;
//! - [`forces`]: `Loads`, `__wrenches`, `Forces`, `kinetostatics`,
//!   `kinetostatics_with_friction`, `driver_action`;
//! - [`traits`]: the `Machine` and `OneDof` impls and the one-DOF methods `reduced`,
//!   `reduced_moment`, `acceleration`;
//! - [`batch`]: many configurations per call, `pose_many`, `points_many`,
//!   `driver_action_many`, `reduced_many`, `acceleration_many`.
//!
//! [`outline()`] is what is emitted instead when the mechanism has errors.

mod batch;
mod forces;
mod names;
mod outline;
mod params;
pub(crate) mod plan;
mod results;
pub(crate) mod spatial;
mod traits;

pub use outline::outline;

use mech_core::model::{Description, JointKind, Model};
use mech_core::plan::assur::{Group, Kernel};
use mech_core::solvers::params::LinkTerms;
use names::Names;
use proc_macro2::{Span, TokenStream};
use quote::quote;
use syn::Ident;

/// An identifier of the user's (a link, point, joint or load name).
pub(crate) fn id(s: &str) -> Ident {
    Ident::new(s, Span::call_site())
}

/// An `f64` literal.
pub(crate) fn f64s(v: f64) -> TokenStream {
    let l = proc_macro2::Literal::f64_suffixed(v);
    quote!(#l)
}

/// A `Vector2<f64>` literal.
pub(crate) fn vec2(v: [f64; 2]) -> TokenStream {
    let (x, y) = (f64s(v[0]), f64s(v[1]));
    quote!(::mech::__private::Vector2::new(#x, #y))
}

/// What every part needs to know about the mechanism being emitted.
pub(crate) struct Ctx<'a> {
    /// The resolved mechanism.
    pub model: &'a Model,
    /// Its Assur groups in solve order.
    pub plan: &'a [Group],
    /// The doc comment lines written on the struct.
    pub docs: &'a [String],
    /// The generated type names.
    pub names: Names,
    /// `::mech::__private`, the path of every kernel.
    pub p: TokenStream,
    /// `Vector2<f64>`.
    pub v2: TokenStream,
    /// One identifier per link (ground first), point and joint.
    pub link_ids: Vec<Ident>,
    pub point_ids: Vec<Ident>,
    pub joint_ids: Vec<Ident>,
    /// N (ground included), joints, points, loads, G and groups.
    pub n_links: usize,
    pub n_joints: usize,
    pub n_points: usize,
    pub n_loads: usize,
    pub dof: usize,
    pub n_groups: usize,
    /// The type of an input value: `f64` for one DOF, `[f64; G]` else.
    pub q_ty: TokenStream,
    /// The inertia and gravity terms of each link, from its declaration (ground first).
    pub terms: Vec<LinkTerms>,
    /// What q of each input is and which sign its motor action follows (doc lines).
    pub inputs_doc: Vec<String>,
}

impl<'a> Ctx<'a> {
    fn new(desc: &'a Description<Span>, model: &'a Model, plan: &'a [Group]) -> Self {
        let p = quote!(::mech::__private);
        let dof = model.inputs.len();
        Ctx {
            model,
            plan,
            docs: &desc.docs,
            names: Names::new(desc),
            v2: quote!(#p::Vector2<f64>),
            p,
            link_ids: model.links.iter().map(|l| id(&l.name)).collect(),
            point_ids: model.points.iter().map(|pt| id(&pt.name)).collect(),
            joint_ids: model.joints.iter().map(|j| id(&j.name)).collect(),
            n_links: model.links.len(),
            n_joints: model.joints.len(),
            n_points: model.points.len(),
            n_loads: model.loads.len(),
            dof,
            n_groups: plan.len(),
            q_ty: if dof == 1 {
                quote!(f64)
            } else {
                quote!([f64; #dof])
            },
            terms: model.links.iter().map(LinkTerms::of).collect(),
            inputs_doc: inputs_doc(model),
        }
    }

    /// One input: `Q` is `f64`, the one-DOF methods and `OneDof` are emitted.
    pub fn one_dof(&self) -> bool {
        self.dof == 1
    }

    /// `#[allow(redundant)]`: no reactions.
    pub fn redundant(&self) -> bool {
        self.model.allow_redundant
    }

    /// The mechanism has force elements (`elements { }`): the struct keeps their geometry
    /// and every route adds their forces.
    pub fn has_elements(&self) -> bool {
        !self.model.elements.is_empty()
    }

    /// The number of cams (the struct keeps their laws and profiles).
    pub fn n_cams(&self) -> usize {
        self.model
            .joints
            .iter()
            .filter(|j| j.kind == JointKind::Cam)
            .count()
    }

    /// The number of gear pairs and racks (the struct keeps their tooth data).
    pub fn n_meshes(&self) -> usize {
        self.model.joints.iter().filter(|j| j.kind.mesh()).count()
    }

    /// The gear-train groups (their indices in the plan), in solve order: the struct
    /// keeps each one's Willis inverse (`willis[t]` for the t-th).
    pub fn trains(&self) -> Vec<usize> {
        (0..self.n_groups)
            .filter(|&gi| matches!(self.plan[gi].kernel, Kernel::Train(_)))
            .collect()
    }

    /// Every angular velocity coefficient is a constant (a machine of gears:
    /// `mech_core::plan::ratios`), one input: each link's pin, from which the struct works
    /// out I*(q) as a constant and a few cosines (`reduced_series`).
    pub fn ratio_pins(&self) -> Option<Vec<mech_core::plan::ratios::Pin>> {
        if self.one_dof() {
            mech_core::plan::ratios::pins(self.model, self.plan)
        } else {
            None
        }
    }

    /// The number of cosines of I*(q) when [`Ctx::ratio_pins`] (0: gears on fixed axes,
    /// racks on fixed guides, I* a constant).
    pub fn series_len(&self) -> Option<usize> {
        self.ratio_pins()
            .map(|p| mech_core::plan::ratios::series_len(&p))
    }

    /// The slot of gear-train group `gi` in the struct's `willis`.
    pub fn train_slot(&self, gi: usize) -> usize {
        self.trains().iter().position(|&t| t == gi).unwrap_or(0)
    }

    /// The moving links declared by their shape and material (`shape:`), in order.
    pub fn shaped(&self) -> impl Iterator<Item = usize> + '_ {
        (1..self.n_links).filter(|&l| self.model.links[l].body.is_some())
    }

    /// The moving links' identifiers.
    pub fn moving_ids(&self) -> &[Ident] {
        &self.link_ids[1..]
    }

    /// The prismatic and slot joints (those with an axis).
    pub fn sliding(&self) -> Vec<usize> {
        (0..self.n_joints)
            .filter(|&j| {
                let jt = &self.model.joints[j];
                !matches!(
                    jt.kind,
                    JointKind::Revolute | JointKind::Gear | JointKind::Rack
                ) && jt.around.is_none()
            })
            .collect()
    }

    /// The links with inertia terms (−m·a_G, −I_G·α, T, their share of I*).
    pub fn inertial(&self) -> Vec<usize> {
        (1..self.n_links)
            .filter(|&l| self.terms[l].inertia())
            .collect()
    }

    /// The links with gravity terms (m·g, V, their share of M*): none without gravity.
    pub fn weighed(&self) -> Vec<usize> {
        if self.model.gravity.is_none() {
            return vec![];
        }
        (1..self.n_links)
            .filter(|&l| self.terms[l].gravity())
            .collect()
    }
}

/// The generated code of a valid mechanism, part by part, each with its name (the
/// snapshot tests show them one by one).
pub(crate) fn parts(
    desc: &Description<Span>,
    model: &Model,
    plan: &[Group],
) -> Vec<(&'static str, TokenStream)> {
    let cx = Ctx::new(desc, model, plan);
    vec![
        ("params", params::emit(&cx)),
        ("plan", plan::emit(&cx)),
        ("results", results::emit(&cx)),
        ("forces", forces::emit(&cx)),
        ("traits", traits::emit(&cx)),
        ("batch", batch::emit(&cx)),
    ]
}

/// The whole generated code of a valid mechanism.
pub fn mechanism(desc: &Description<Span>, model: &Model, plan: &[Group]) -> TokenStream {
    parts(desc, model, plan)
        .into_iter()
        .map(|(_, part)| allow_drawing_numbers(part))
        .collect()
}

/// The drawing's numbers are written as literals, and one may be close to π/2 or another
/// constant by design (an input's zero of 90°): clippy's `approx_constant` (deny by default)
/// would fail the user's build on the generated code. Every `impl` block of `part` gets
/// `#[allow(clippy::approx_constant)]`.
pub(crate) fn allow_drawing_numbers(part: TokenStream) -> TokenStream {
    match syn::parse2::<syn::File>(part.clone()) {
        Ok(mut file) => {
            for item in &mut file.items {
                if let syn::Item::Impl(i) = item {
                    i.attrs
                        .push(syn::parse_quote!(#[allow(clippy::approx_constant)]));
                }
            }
            quote!(#file)
        }
        Err(_) => part,
    }
}

/// A number without trailing zeros (for doc comments).
fn short(x: f64) -> String {
    let s = format!("{x:.9}");
    s.trim_end_matches('0').trim_end_matches('.').to_string()
}

/// For each input: what q is (the joint coordinate less the declared zero) and the sign
/// of its motor action, in words, for the doc comments of the solvers that take q or
/// report the motor action.
fn inputs_doc(model: &Model) -> Vec<String> {
    let mut lines = vec![" Inputs and signs:".to_string()];
    for (k, (&j, &zero)) in model.inputs.iter().zip(&model.input_zero).enumerate() {
        let jt = &model.joints[j];
        let (a, b) = (&model.links[jt.a].name, &model.links[jt.b].name);
        let q = if model.inputs.len() == 1 {
            "q".to_string()
        } else {
            format!("q[{k}]")
        };
        let line = match jt.kind {
            JointKind::Revolute => {
                let zero = if zero == 0.0 {
                    String::new()
                } else {
                    format!(" − {}°", short(zero.to_degrees()))
                };
                let relative = if jt.a == 0 {
                    String::new()
                } else {
                    format!(" − θ_{a}")
                };
                format!(
                    " - {q}, joint `{}` (revolute, `{a}` → `{b}`): q = θ_{b}{relative}{zero} (rad, counter-clockwise); \
                     its motor action is the torque applied by `{a}` on `{b}` (N·m, counter-clockwise positive): \
                     the torque the motor applies. The \"turning moment on the crankshaft\" of engine \
                     textbooks (the torque the loads give the crank) is its negative.",
                    jt.name
                )
            }
            _ => {
                let zero = if zero == 0.0 {
                    String::new()
                } else {
                    format!(" − {} m", short(zero))
                };
                format!(
                    " - {q}, joint `{}` (prismatic, `{b}` on `{a}`): q = the slide of `{}` along the axis from the drawing{zero} (m); \
                     its motor action is the force applied by `{a}` on `{b}` along the axis (N).",
                    jt.name, model.points[jt.point].name
                )
            }
        };
        lines.push(line);
    }
    lines
}
