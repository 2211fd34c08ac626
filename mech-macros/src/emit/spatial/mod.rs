//! Emission of a spatial mechanism (`mechanism! { pub struct Name { space, ... } }`, SPEC
//! 3i): the same pipeline as the planar one, on mech-core's spatial layer.
//!
//! Parse and resolve (`mech_core::spatial::dsl::Declared`: names, units, axes, each mistake
//! at its place) → check (`SpatialMechanism::checked`: Kutzbach's count with the idle
//! spins, the constraint Jacobian's rank at the drawing, each finding at its place) → emit:
//! - here: the struct, its constants and its declaration written out as a
//!   `SpatialModel` literal (`model()`), from which `new()` builds the run-time solver;
//! - [`results`]: `Pose`, `Motion` with one field per link and point, `pose`, `kinematics`;
//! - [`forces`]: `Loads`, `Forces` with one field per joint, `kinetostatics`,
//!   `driver_action`, the one-DOF methods and the `Machine` / `OneDof` impls.
//!
//! The solvers are mech-core's (`mech::spatial::Solver`), called on a frame of the
//! mechanism's sizes as constants (`Fixed<N, 6(N − 1)>`: every buffer on the stack, no
//! allocation; a mechanism with redundant constraints on the heap); the typed results are
//! copied out of its answers.

mod forces;
mod results;

use mech_core::spatial::dsl::{Declared, Spans};
use mech_core::spatial::{Finding, JointKind, LoadKind, Site, SpatialMechanism, SpatialModel};
use mech_core::Vector3;
use proc_macro2::TokenStream;
use quote::{format_ident, quote};
use syn::Ident;

use super::{f64s, id};

/// What every part needs to know about the spatial mechanism being emitted.
pub(crate) struct Ctx<'a> {
    /// The resolved declaration.
    pub model: &'a SpatialModel,
    /// The checked run-time mechanism (its Kutzbach count, the points' anchors).
    pub mech: &'a SpatialMechanism,
    /// The doc comment lines written on the struct.
    pub docs: &'a [String],
    /// `Name` and the result types' names.
    pub main: Ident,
    /// `::mech::__private::spatial`, the path of every item used.
    pub s: TokenStream,
    /// `::mech::__private`.
    pub p: TokenStream,
    /// G.
    pub dof: usize,
    /// `f64` for one input, `[f64; G]` else.
    pub q_ty: TokenStream,
}

impl Ctx<'_> {
    /// `<Name><suffix>`.
    pub fn name(&self, suffix: &str) -> Ident {
        format_ident!("{}{}", self.main, suffix)
    }

    /// The moving links: (body index, field identifier).
    pub fn links(&self) -> Vec<(usize, Ident)> {
        self.model
            .bodies
            .iter()
            .enumerate()
            .skip(1)
            .map(|(b, body)| (b, id(&body.name)))
            .collect()
    }

    /// The expression turning an input value `x` of type `Q` into `[f64; G]`.
    pub fn to_array(&self, x: &Ident) -> TokenStream {
        if self.dof == 1 {
            quote!([#x])
        } else {
            quote!(#x)
        }
    }

    /// The expression turning `[f64; G]` (a slice or array `v`) into `Q`.
    pub fn from_values(&self, v: TokenStream) -> TokenStream {
        if self.dof == 1 {
            quote!(#v[0])
        } else {
            let k = 0..self.dof;
            quote!([#(#v[#k]),*])
        }
    }
}

/// Everything emitted for the tokens of a `space` declaration: the struct and its solvers,
/// or every mistake as a spanned `compile_error!`.
pub(crate) fn mechanism(tokens: TokenStream) -> TokenStream {
    let Declared { model, spans } = match syn::parse2::<Declared>(tokens) {
        Ok(d) => d,
        Err(e) => return e.to_compile_error(),
    };
    let mech = match SpatialMechanism::checked(model.clone()) {
        Ok(m) => m,
        Err(found) => return errors(&found, &spans),
    };
    let dof = model.inputs.len();
    let c = Ctx {
        model: &model,
        mech: &mech,
        docs: &spans.docs,
        main: Ident::new(&model.name, spans.name),
        s: quote!(::mech::__private::spatial),
        p: quote!(::mech::__private),
        dof,
        q_ty: if dof == 1 {
            quote!(f64)
        } else {
            quote!([f64; #dof])
        },
    };
    let mut out = main(&c);
    out.extend(results::emit(&c));
    out.extend(forces::emit(&c));
    out
}

/// Each finding as `compile_error!`s: its message at its place, a short pointer at each
/// other place involved.
fn errors(found: &[Finding], spans: &Spans) -> TokenStream {
    let at = |site: Site| match site {
        Site::Whole => spans.name,
        Site::Inputs => spans.input,
        Site::Body(b) => spans.bodies.get(b).copied().unwrap_or(spans.name),
        Site::Joint(j) => spans.joints.get(j).copied().unwrap_or(spans.name),
    };
    let mut out = TokenStream::new();
    for f in found {
        out.extend(syn::Error::new(at(f.site), &f.message).to_compile_error());
        let first = f.message.split(':').next().unwrap_or("");
        for &site in &f.involved {
            let m = format!("involved here: {first} (see the first error)");
            out.extend(syn::Error::new(at(site), m).to_compile_error());
        }
    }
    out
}

/// A `Vector3<f64>` literal (`Vector3` imported where it is used).
fn vec3(v: &Vector3<f64>) -> TokenStream {
    let (x, y, z) = (f64s(v.x), f64s(v.y), f64s(v.z));
    quote!(Vector3::new(#x, #y, #z))
}

/// `Some(v)` or `None`.
fn some_vec3(v: &Option<Vector3<f64>>) -> TokenStream {
    match v {
        Some(v) => {
            let v = vec3(v);
            quote!(Some(#v))
        }
        None => quote!(None),
    }
}

/// The declaration as a `SpatialModel` literal (SI, the drawing's coordinates), the body of
/// the generated `model()`.
fn model_literal(m: &SpatialModel, s: &TokenStream) -> TokenStream {
    let name = &m.name;
    let gravity = some_vec3(&m.gravity);
    let points = m.points.iter().map(|(n, p)| {
        let p = vec3(p);
        quote!((#n.to_string(), #p))
    });
    let bodies = m.bodies.iter().map(|b| {
        let (name, pts, mass, cg) = (&b.name, &b.points, f64s(b.mass), some_vec3(&b.cg));
        // the DSL's six numbers (Ixx, Iyy, Izz, Ixy, Ixz, Iyz), products Ixy = Σ m x y
        let t = &b.inertia;
        let six = [
            t[(0, 0)],
            t[(1, 1)],
            t[(2, 2)],
            -t[(0, 1)],
            -t[(0, 2)],
            -t[(1, 2)],
        ];
        let i = six.iter().map(|&x| f64s(x + 0.0));
        quote!(Body {
            name: #name.to_string(),
            points: Vec::from([#(#pts),*]),
            mass: #mass,
            cg: #cg,
            inertia: inertia_tensor([#(#i),*]),
        })
    });
    let joints = m.joints.iter().map(|j| {
        let (name, a, b, point) = (&j.name, j.a, j.b, j.point);
        let kind = match &j.kind {
            JointKind::Revolute { axis } => {
                let u = vec3(axis);
                quote!(JointKind::Revolute { axis: #u })
            }
            JointKind::Prismatic { axis } => {
                let u = vec3(axis);
                quote!(JointKind::Prismatic { axis: #u })
            }
            JointKind::Cylindrical { axis } => {
                let u = vec3(axis);
                quote!(JointKind::Cylindrical { axis: #u })
            }
            JointKind::Spherical => quote!(JointKind::Spherical),
            JointKind::Universal { first, second } => {
                let (u, v) = (vec3(first), vec3(second));
                quote!(JointKind::Universal { first: #u, second: #v })
            }
            JointKind::Helical { axis, pitch } => {
                let (u, p) = (vec3(axis), f64s(*pitch));
                quote!(JointKind::Helical { axis: #u, pitch: #p })
            }
        };
        quote!(Joint { name: #name.to_string(), kind: #kind, a: #a, b: #b, point: #point })
    });
    let inputs = &m.inputs;
    let loads = m.loads.iter().map(|l| {
        let name = &l.name;
        let kind = match l.kind {
            LoadKind::Force { body, point } => {
                quote!(LoadKind::Force { body: #body, point: #point })
            }
            LoadKind::Torque { body } => quote!(LoadKind::Torque { body: #body }),
        };
        quote!(Load { name: #name.to_string(), kind: #kind })
    });
    let redundant = m.allow_redundant;
    quote! {
        use #s::{inertia_tensor, Body, Joint, JointKind, Load, LoadKind, SpatialModel, Vector3};
        SpatialModel {
            name: #name.to_string(),
            gravity: #gravity,
            points: Vec::from([#(#points),*]),
            bodies: Vec::from([#(#bodies),*]),
            joints: Vec::from([#(#joints),*]),
            inputs: Vec::from([#(#inputs),*]),
            loads: Vec::from([#(#loads),*]),
            allow_redundant: #redundant,
        }
    }
}

/// The struct, its constants, `new`, `model`, `mechanism` and `Default`.
fn main(c: &Ctx) -> TokenStream {
    let Ctx {
        main, s, docs, dof, ..
    } = c;
    let k = c.mech.kutzbach();
    let n = k.n;
    let equations = k.equations();
    let unknowns = dof + k.reactions();
    let idle = k.idle.len();
    let model = model_literal(c.model, s);
    let rows = c.mech.row_count();
    let (frame_ty, frame, frame_doc) = if c.model.allow_redundant {
        (
            quote!(#s::Dense),
            quote!(#s::Dense { bodies: #n, rows: #rows }),
            format!(
                " The solvers on the heap ({rows} rows for {equations} unknowns: least squares)."
            ),
        )
    } else {
        (
            quote!(#s::Fixed<#n, #rows>),
            quote!(#s::Fixed),
            format!(" The solvers on the stack: {n} bodies, {rows} rows (allocation-free)."),
        )
    };
    let summary = format!(
        " A spatial mechanism (generated by `mechanism!` from a `space` declaration): N = {n} links, {} joints; Kutzbach's G = {}{}; {equations} equations against {unknowns} unknowns. Solved in absolute coordinates by `mech::spatial::SpatialMechanism` (see docs/spatial.md).",
        c.model.joints.len(),
        k.mobility,
        if idle > 0 { format!(" of which {idle} idle spin(s)") } else { String::new() },
    );
    let docs = docs.iter().chain(docs.is_empty().then_some(&summary));
    let extra = (!c.docs.is_empty()).then(|| quote!(#[doc = ""] #[doc = #summary]));
    quote! {
        #(#[doc = #docs])*
        #extra
        #[derive(Clone, Debug)]
        pub struct #main {
            inner: #s::SpatialMechanism,
        }

        impl #main {
            /// G: the inputs.
            pub const DOF: usize = #dof;
            /// N: the links, ground included.
            pub const LINKS: usize = #n;
            /// 6(N − 1): the equations of the kinetostatic problem.
            pub const EQUATIONS: usize = #equations;
            /// G + Σ (6 − k) P_k, with one moment per idle spin: the unknowns.
            pub const UNKNOWNS: usize = #unknowns;
            /// The idle spins (links turning about the line through their two spherical joints).
            pub const IDLE: usize = #idle;

            /// The mechanism as declared (checked at compile time by the same checks).
            pub fn new() -> Self {
                #main {
                    inner: #s::SpatialMechanism::from_model(Self::model())
                        .expect("checked by `mechanism!` at compile time"),
                }
            }

            /// The declaration as plain data: SI units, the drawing's global coordinates.
            pub fn model() -> #s::SpatialModel {
                #model
            }

            /// The run-time spatial mechanism the solvers call (`mech::spatial`).
            pub fn mechanism(&self) -> &#s::SpatialMechanism {
                &self.inner
            }

            #[doc = #frame_doc]
            fn __solver(&self) -> Result<#s::Solver<'_, #frame_ty>, ::mech::__private::MechError> {
                self.inner.solver(#frame)
            }
        }

        impl ::core::default::Default for #main {
            fn default() -> Self {
                Self::new()
            }
        }
    }
}
