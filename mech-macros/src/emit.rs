//! Emission: the generated struct and its solvers, as calls into mech-core's kernels.

use mech_core::assur::{Group, Kernel};
use mech_core::dyad::Solver;
use mech_core::screw::{Chain, Driven, JointScrew};
use mech_core::kinematics::{Con, ConKind};
use mech_core::model::{Description, JointKind, Load, Model};
use mech_core::resolve::Diagnostic;
use proc_macro2::{Span, TokenStream};
use quote::{format_ident, quote};
use syn::Ident;

fn id(s: &str) -> Ident {
    Ident::new(s, Span::call_site())
}

fn f64s(v: f64) -> TokenStream {
    let l = proc_macro2::Literal::f64_suffixed(v);
    quote!(#l)
}

fn vec2(v: [f64; 2]) -> TokenStream {
    let (x, y) = (f64s(v[0]), f64s(v[1]));
    quote!(::mech::__private::Vector2::new(#x, #y))
}

/// Every diagnostic as `compile_error!`s: the message at the culprit, a short pointer at
/// each other declaration involved.
pub fn errors(diags: &[Diagnostic<Span>]) -> TokenStream {
    let mut out = TokenStream::new();
    for d in diags {
        let first = d.message.split(':').next().unwrap_or("");
        for (i, span) in d.spans.iter().enumerate() {
            let msg = if i == 0 { d.message.clone() } else { format!("involved here: {first} (see the first error)") };
            out.extend(syn::Error::new(*span, msg).to_compile_error());
        }
    }
    out
}

struct Names {
    main: Ident,
    params: Ident,
    loads: Ident,
    pose: Ident,
    motion: Ident,
    forces: Ident,
}

fn names(desc: &Description<Span>) -> Names {
    let n = &desc.name.text;
    let span = desc.name.span;
    Names {
        main: Ident::new(n, span),
        params: format_ident!("{}Params", n),
        loads: format_ident!("{}Loads", n),
        pose: format_ident!("{}Pose", n),
        motion: format_ident!("{}Motion", n),
        forces: format_ident!("{}Forces", n),
    }
}

/// On error: the errors, and the struct's outline (empty types with the public names) so
/// that code using the mechanism does not add a cascade of unrelated errors.
pub fn outline(desc: &Description<Span>, _model: Option<&Model>, diags: &[Diagnostic<Span>]) -> TokenStream {
    let errs = errors(diags);
    let Names { main, params, loads, pose, motion, forces } = names(desc);
    quote! {
        #errs
        /// (not generated: the mechanism has errors)
        #[derive(Clone, Debug, Default)]
        pub struct #main;
        /// (not generated: the mechanism has errors)
        #[derive(Clone, Debug, Default)]
        pub struct #params;
        /// (not generated: the mechanism has errors)
        #[derive(Clone, Debug, Default)]
        pub struct #loads;
        /// (not generated: the mechanism has errors)
        #[derive(Clone, Debug, Default)]
        pub struct #pose;
        /// (not generated: the mechanism has errors)
        #[derive(Clone, Debug, Default)]
        pub struct #motion;
        /// (not generated: the mechanism has errors)
        #[derive(Clone, Debug, Default)]
        pub struct #forces;
        impl #main {
            /// (not generated: the mechanism has errors)
            pub fn new() -> Self { #main }
        }
    }
}

fn con_tokens(c: &Con) -> TokenStream {
    let j = c.joint;
    let kind = match c.kind {
        ConKind::Revolute => quote!(Revolute),
        ConKind::Prismatic => quote!(Prismatic),
        ConKind::Slot => quote!(Slot),
        ConKind::DriveRevolute(k) => quote!(DriveRevolute(#k)),
        ConKind::DrivePrismatic(k) => quote!(DrivePrismatic(#k)),
    };
    quote!(::mech::__private::kinematics::Con { joint: #j, kind: ::mech::__private::kinematics::ConKind::#kind })
}

fn solver_tokens(s: &Solver) -> TokenStream {
    let p = quote!(::mech::__private::dyad::Solver);
    match *s {
        Solver::DrivenRevolute { body, joint, input } => quote!(#p::DrivenRevolute { body: #body, joint: #joint, input: #input }),
        Solver::DrivenPrismatic { body, joint, input } => quote!(#p::DrivenPrismatic { body: #body, joint: #joint, input: #input }),
        Solver::Rrr { b1, b2, ja, jc, jb } => quote!(#p::Rrr { b1: #b1, b2: #b2, ja: #ja, jc: #jc, jb: #jb }),
        Solver::Rrp { b1, b2, ja, jc, jp } => quote!(#p::Rrp { b1: #b1, b2: #b2, ja: #ja, jc: #jc, jp: #jp }),
        Solver::Rpr { b1, b2, ja, jp, jb } => quote!(#p::Rpr { b1: #b1, b2: #b2, ja: #ja, jp: #jp, jb: #jb }),
        Solver::Prp { b1, b2, jp1, jc, jp2 } => quote!(#p::Prp { b1: #b1, b2: #b2, jp1: #jp1, jc: #jc, jp2: #jp2 }),
        Solver::Rpp { b1, b2, ja, jp, jq } => quote!(#p::Rpp { b1: #b1, b2: #b2, ja: #ja, jp: #jp, jq: #jq }),
        Solver::PinInFixedSlot { body, ja, js } => quote!(#p::PinInFixedSlot { body: #body, ja: #ja, js: #js }),
        Solver::SlottedLever { body, ja, js } => quote!(#p::SlottedLever { body: #body, ja: #ja, js: #js }),
        Solver::Newton => quote!(#p::Newton),
    }
}

fn screw_tokens(s: &JointScrew) -> TokenStream {
    let (j, slide) = (s.joint, s.slide);
    quote!(::mech::__private::screw::JointScrew { joint: #j, slide: #slide })
}

fn link_tokens(l: usize) -> TokenStream {
    if l == mech_core::screw::VIRTUAL {
        quote!(::mech::__private::screw::VIRTUAL)
    } else {
        quote!(#l)
    }
}

fn chain_tokens(c: &Chain) -> TokenStream {
    let (from, to, pivot) = (c.from, c.to, c.pivot);
    let screws = c.screws.iter().map(screw_tokens);
    let links = c.links.iter().map(|&l| link_tokens(l));
    quote!(::mech::__private::screw::Chain { from: #from, to: #to, screws: [#(#screws),*], links: [#(#links),*], pivot: #pivot })
}

fn driven_tokens(d: &Driven) -> TokenStream {
    let (from, body, input) = (d.from, d.body, d.input);
    let screw = screw_tokens(&d.screw);
    quote!(::mech::__private::screw::Driven { from: #from, body: #body, screw: #screw, input: #input })
}

/// The whole generated code of a valid mechanism.
pub fn mechanism(desc: &Description<Span>, model: &Model, plan: &[Group]) -> TokenStream {
    let nm = names(desc);
    let Names { main, params, loads, pose, motion, forces } = &nm;
    let p = quote!(::mech::__private);
    let v2 = quote!(#p::Vector2<f64>);
    let n_links = model.links.len();
    let n_joints = model.joints.len();
    let n_points = model.points.len();
    let n_loads = model.loads.len();
    let dof = model.inputs.len();
    let n_groups = plan.len();
    let lower = model.lower_pairs();
    let higher = model.higher_pairs();
    let equations = 3 * (n_links - 1);
    let unknowns = dof + 2 * lower + higher;
    let redundant = model.allow_redundant;
    let one_dof = dof == 1;
    let q_ty = if one_dof { quote!(f64) } else { quote!([f64; #dof]) };
    let to_arr = |v: &Ident| if one_dof { quote!(let #v = [#v];) } else { quote!() };
    let from_arr = |v: TokenStream| if one_dof { quote!(#v[0]) } else { v };
    let docs = desc.docs.iter().map(|d| quote!(#[doc = #d]));
    let doc_struct = format!(" Generated by `mechanism!`: {} links (ground included), {} lower pairs, {} higher pairs, {} input(s).", n_links, lower, higher, dof);

    let link_ids: Vec<Ident> = model.links.iter().map(|l| id(&l.name)).collect();
    let point_ids: Vec<Ident> = model.points.iter().map(|pt| id(&pt.name)).collect();
    let joint_ids: Vec<Ident> = model.joints.iter().map(|j| id(&j.name)).collect();
    let moving = 1..n_links;
    let moving_ids: Vec<&Ident> = link_ids[1..].iter().collect();
    let sliding: Vec<usize> = (0..n_joints).filter(|&j| model.joints[j].kind != JointKind::Revolute).collect();
    let sliding_ids: Vec<&Ident> = sliding.iter().map(|&j| &joint_ids[j]).collect();

    // ---- Params ------------------------------------------------------------------------
    let params_points = format_ident!("{}ParamsPoints", desc.name.text);
    let params_links = format_ident!("{}ParamsLinks", desc.name.text);
    let params_axes = format_ident!("{}ParamsAxes", desc.name.text);
    let point_defaults = model.points.iter().map(|pt| vec2(pt.pos));
    let link_defaults = moving.clone().map(|l| {
        let lk = &model.links[l];
        let (m, i, cg) = (f64s(lk.mass.unwrap_or(0.0)), f64s(lk.inertia), vec2(lk.cg));
        quote!(#p::instance::LinkParams { mass: #m, inertia: #i, cg: #cg })
    });
    let axis_defaults = sliding.iter().map(|&j| vec2(model.joints[j].axis));
    let (gravity_field, gravity_default, gravity_model) = match model.gravity {
        Some(g) => {
            let gv = vec2(g);
            (
                quote!(/// Gravity, m/s².
                       pub gravity: #v2,),
                quote!(gravity: #gv,),
                quote!(Some([p.gravity.x, p.gravity.y])),
            )
        }
        None => (quote!(), quote!(), quote!(None)),
    };

    // ---- The model rebuilt from params (for from_params' run-time checks) -------------
    let m_points = model.points.iter().zip(&point_ids).map(|(pt, pid)| {
        let n = &pt.name;
        quote!(#p::model::Point { name: #n.into(), pos: [p.points.#pid.x, p.points.#pid.y] })
    });
    let m_links = model.links.iter().enumerate().map(|(l, lk)| {
        let n = &lk.name;
        let pts = &lk.points;
        if l == 0 {
            quote!(#p::model::Link { name: #n.into(), points: vec![#(#pts),*], mass: None, inertia: 0.0, cg: [0.0, 0.0] })
        } else {
            let lid = &link_ids[l];
            let mass = if lk.mass.is_some() { quote!(Some(p.links.#lid.mass)) } else { quote!(None) };
            quote!(#p::model::Link { name: #n.into(), points: vec![#(#pts),*], mass: #mass, inertia: p.links.#lid.inertia, cg: [p.links.#lid.cg.x, p.links.#lid.cg.y] })
        }
    });
    let m_joints = model.joints.iter().enumerate().map(|(j, jt)| {
        let n = &jt.name;
        let (a, b, pt) = (jt.a, jt.b, jt.point);
        let kind = match jt.kind {
            JointKind::Revolute => quote!(Revolute),
            JointKind::Prismatic => quote!(Prismatic),
            JointKind::PinInSlot => quote!(PinInSlot),
        };
        let axis = if jt.kind == JointKind::Revolute {
            quote!([0.0, 0.0])
        } else {
            let jid = &joint_ids[j];
            quote!([p.axes.#jid.x, p.axes.#jid.y])
        };
        quote!(#p::model::Joint { name: #n.into(), kind: #p::model::JointKind::#kind, a: #a, b: #b, point: #pt, axis: #axis })
    });
    let m_inputs = &model.inputs;
    let m_loads = model.loads.iter().map(|l| match l {
        Load::Force { name, link, point } => quote!(#p::model::Load::Force { name: #name.into(), link: #link, point: #point }),
        Load::Torque { name, link } => quote!(#p::model::Load::Torque { name: #name.into(), link: #link }),
    });
    let model_name = &model.name;

    // ---- Loads ---------------------------------------------------------------------------
    let load_fields = model.loads.iter().map(|l| {
        let lid = id(l.name());
        match l {
            Load::Force { link, point, .. } => {
                let doc = format!("Force (N, global vector) on `{}` at `{}`.", model.links[*link].name, model.points[*point].name);
                quote!(#[doc = #doc] pub #lid: #v2,)
            }
            Load::Torque { link, .. } => {
                let doc = format!("Torque (N·m, CCW positive) on `{}`.", model.links[*link].name);
                quote!(#[doc = #doc] pub #lid: f64,)
            }
        }
    });
    let load_checks = model.loads.iter().map(|l| {
        let lid = id(l.name());
        match l {
            Load::Force { .. } => quote!(loads.#lid.x, loads.#lid.y,),
            Load::Torque { .. } => quote!(loads.#lid,),
        }
    }).collect::<Vec<TokenStream>>();
    let load_terms = model.loads.iter().enumerate().map(|(k, l)| {
        let lid = id(l.name());
        let link = l.link();
        match l {
            Load::Force { .. } => quote!(#p::kinetostatics::add_force(&mut f[#link], &s[#link], self.loads[#k], loads.#lid);),
            Load::Torque { .. } => quote!(#p::kinetostatics::add_torque(&mut f[#link], loads.#lid);),
        }
    });
    let massive: Vec<usize> = (1..n_links).filter(|&l| model.links[l].has_inertia()).collect();
    let gravity_terms = if model.gravity.is_some() {
        let with_mass: Vec<usize> = (1..n_links).filter(|&l| model.links[l].mass.is_some_and(|m| m != 0.0)).collect();
        quote!(#( #p::kinetostatics::add_gravity(&mut f[#with_mass], &s[#with_mass], &self.links[#with_mass], self.gravity); )*)
    } else {
        quote!()
    };
    let inertia_terms = quote!(#( #p::kinetostatics::add_inertia(&mut f[#massive], &s[#massive], &self.links[#massive]); )*);

    // ---- Groups ----------------------------------------------------------------------------
    let group_consts = plan.iter().enumerate().map(|(gi, g)| {
        let bn = format_ident!("__G{}_BODIES", gi);
        let cn = format_ident!("__G{}_CONS", gi);
        let nb = g.bodies.len();
        let nc = g.cons.len();
        let bodies = &g.bodies;
        let cons = g.cons.iter().map(con_tokens);
        let doc = format!(
            "Assur group {gi}: links {} ({:?}).",
            g.bodies.iter().map(|&b| model.links[b].name.as_str()).collect::<Vec<_>>().join(", "),
            g.solver
        );
        let kernel = match &g.kernel {
            Kernel::Driven(d) => {
                let kn = format_ident!("__G{}_DRIVEN", gi);
                let t = driven_tokens(d);
                quote!(const #kn: #p::screw::Driven = #t;)
            }
            Kernel::Chain(c) => {
                let kn = format_ident!("__G{}_CHAIN", gi);
                let t = chain_tokens(c);
                quote!(const #kn: #p::screw::Chain = #t;)
            }
            Kernel::System => quote!(
                const #bn: [usize; #nb] = [#(#bodies),*];
                const #cn: [#p::kinematics::Con; #nc] = [#(#cons),*];
            ),
        };
        quote! {
            #[doc = #doc]
            #kernel
        }
    });
    let solvers: Vec<TokenStream> = plan.iter().map(|g| solver_tokens(&g.solver)).collect();
    let solve_calls = plan.iter().enumerate().map(|(gi, g)| {
        let bn = format_ident!("__G{}_BODIES", gi);
        let cn = format_ident!("__G{}_CONS", gi);
        let n = 3 * g.bodies.len();
        let solver = &solvers[gi];
        let sys = format_ident!("sys{}", gi);
        match g.kernel {
            Kernel::Driven(_) => {
                let kn = format_ident!("__G{}_DRIVEN", gi);
                quote!(#p::kinematics::solve_driven(#solver, &Self::#kn, &self.joints, &mut s, drive, upto)?; let #sys = ();)
            }
            Kernel::Chain(_) => {
                let kn = format_ident!("__G{}_CHAIN", gi);
                quote!(#p::kinematics::solve_chain(#solver, &Self::#kn, &self.joints, &mut s, drive, branches[#gi], self.scale, upto)?; let #sys = ();)
            }
            Kernel::System if g.redundant() => {
                let m = g.rows();
                quote!(let #sys = #p::group::group_solve_ls::<#n, #m>(&Self::#bn, &Self::#cn, &self.joints, &mut s, drive, self.scale, upto)?;)
            }
            Kernel::System => quote!(let #sys = #p::group::group_solve::<#n>(&Self::#bn, &Self::#cn, &self.joints, &mut s, drive, self.scale, upto)?;),
        }
    });
    // Newton starts from the drawing; closed forms overwrite every state they use.
    let initial = if plan.iter().any(|g| g.kernel == Kernel::System) {
        quote!(self.drawing)
    } else {
        quote!([#p::kinematics::LinkState::default(); #n_links])
    };
    let sys_ids: Vec<Ident> = (0..n_groups).map(|g| format_ident!("sys{}", g)).collect();
    let sys_types: Vec<TokenStream> = plan.iter().map(|g| {
        let n = 3 * g.bodies.len();
        if g.kernel != Kernel::System {
            quote!(())
        } else if g.redundant() {
            let m = g.rows();
            quote!(Option<#p::group::LsSystem<#n, #m>>)
        } else {
            quote!(Option<#p::group::GroupSystem<#n>>)
        }
    }).collect();
    let systems_ty = quote!((#(#sys_types,)*));
    // With redundant constraints the closed forms' drawing branches may be the wrong ones
    // past a change point (a parallelogram folding): the redundant group then finds its
    // equations inconsistent, and the other branches are tried.
    let solve_entry = if plan.iter().any(|g| g.redundant()) {
        quote! {
            let mut result = self.__solve_on(&self.branches, q, qd, qdd, upto);
            let mut flips = 1u32;
            while matches!(result, Err(#p::MechError::NoAssembly)) && flips < (1u32 << #n_groups.min(8)) {
                let mut b = self.branches;
                for (k, x) in b.iter_mut().enumerate() {
                    if flips & (1 << k) != 0 {
                        *x = -*x;
                    }
                }
                result = self.__solve_on(&b, q, qd, qdd, upto);
                flips += 1;
            }
            result
        }
    } else {
        quote!(self.__solve_on(&self.branches, q, qd, qdd, upto))
    };
    let velocity_calls = plan.iter().enumerate().map(|(gi, g)| {
        let bn = format_ident!("__G{}_BODIES", gi);
        let cn = format_ident!("__G{}_CONS", gi);
        let n = 3 * g.bodies.len();
        let idx = syn::Index::from(gi);
        let level = quote!(#p::kinematics::Level::Velocity);
        match g.kernel {
            Kernel::Driven(_) => {
                let kn = format_ident!("__G{}_DRIVEN", gi);
                quote!(#p::screw::driven_rates(&Self::#kn, &self.joints, &mut v, drive, #level)?;)
            }
            Kernel::Chain(_) => {
                let kn = format_ident!("__G{}_CHAIN", gi);
                quote!(#p::screw::chain_rates(&Self::#kn, &self.joints, &mut v, self.scale, #level)?;)
            }
            Kernel::System if g.redundant() => {
                let m = g.rows();
                quote!(#p::group::group_velocity_field_ls::<#n, #m>(m.systems.#idx.as_ref(), &Self::#bn, &Self::#cn, &self.joints, &mut v, drive, self.scale)?;)
            }
            Kernel::System => quote!(#p::group::group_velocity_field::<#n>(m.systems.#idx.as_ref(), &Self::#bn, &Self::#cn, &self.joints, &mut v, drive, self.scale)?;),
        }
    });

    // ---- Pose and motion ------------------------------------------------------------------
    let pose_links = format_ident!("{}PoseLinks", desc.name.text);
    let pose_points = format_ident!("{}PosePoints", desc.name.text);
    let motion_links = format_ident!("{}MotionLinks", desc.name.text);
    let motion_points = format_ident!("{}MotionPoints", desc.name.text);
    let owners: Vec<usize> =
        (0..n_points).map(|pt| (0..n_links).find(|&l| model.links[l].points.contains(&pt)).unwrap_or(0)).collect();
    let pose_link_vals = moving.clone().map(|l| {
        let lid = &link_ids[l];
        quote!(#lid: self.links[#l].pose(&s[#l]),)
    });
    let pose_point_vals = (0..n_points).map(|pt| {
        let pid = &point_ids[pt];
        let o = owners[pt];
        quote!(#pid: #p::kinematics::point_pose(&s[#o], self.points[#pt]),)
    });
    let motion_link_vals = moving.clone().map(|l| {
        let lid = &link_ids[l];
        quote!(#lid: self.links[#l].motion(&s[#l]),)
    });
    let motion_point_vals = (0..n_points).map(|pt| {
        let pid = &point_ids[pt];
        let o = owners[pt];
        quote!(#pid: #p::kinematics::point_motion(&s[#o], self.points[#pt]),)
    });

    // ---- Forces ---------------------------------------------------------------------------
    let forces_joints = format_ident!("{}ForcesJoints", desc.name.text);
    let reaction_fields = model.joints.iter().enumerate().map(|(j, jt)| {
        let jid = &joint_ids[j];
        let (ty, what) = match jt.kind {
            JointKind::Revolute => (quote!(#p::kinetostatics::RevoluteReaction), "force by"),
            JointKind::Prismatic => (quote!(#p::kinetostatics::PrismaticReaction), "force (normal to the axis) and moment by"),
            JointKind::PinInSlot => (quote!(#p::kinetostatics::SlotReaction), "force (normal to the slot) by"),
        };
        let doc = format!("Joint `{}`: {} `{}` on `{}`.", jt.name, what, model.links[jt.a].name, model.links[jt.b].name);
        quote!(#[doc = #doc] pub #jid: #ty,)
    });
    let reaction_calls = plan.iter().enumerate().rev().map(|(gi, g)| {
        let bn = format_ident!("__G{}_BODIES", gi);
        let cn = format_ident!("__G{}_CONS", gi);
        let n = 3 * g.bodies.len();
        let idx = syn::Index::from(gi);
        match g.kernel {
            Kernel::Driven(_) => {
                let kn = format_ident!("__G{}_DRIVEN", gi);
                quote!(#p::screw::driven_reactions(&Self::#kn, &self.joints, s, &mut f, &mut r, &mut d);)
            }
            Kernel::Chain(_) => {
                let kn = format_ident!("__G{}_CHAIN", gi);
                quote!(#p::screw::chain_reactions(&Self::#kn, &self.joints, s, &mut f, self.scale, &mut r)?;)
            }
            Kernel::System => quote! {
                let lam = #p::kinetostatics::group_reactions::<#n>(m.systems.#idx.as_ref(), &Self::#bn, &Self::#cn, &self.joints, s, &mut f, self.scale)?;
                #p::kinetostatics::lambda_reactions(&Self::#cn, &self.joints, s, lam.as_slice(), &mut r, &mut d);
            },
        }
    });
    let reaction_vals = model.joints.iter().enumerate().map(|(j, jt)| {
        let jid = &joint_ids[j];
        match jt.kind {
            JointKind::Revolute => quote!(#jid: #p::kinetostatics::RevoluteReaction { force: r[#j].force },),
            JointKind::Prismatic => quote!(#jid: #p::kinetostatics::PrismaticReaction { force: r[#j].force, moment: r[#j].moment },),
            JointKind::PinInSlot => quote!(#jid: #p::kinetostatics::SlotReaction { force: r[#j].force },),
        }
    });
    let driver_value = if one_dof { quote!(d[0]) } else { quote!(d) };

    let link_names: Vec<&str> = model.links[1..].iter().map(|l| l.name.as_str()).collect();
    let point_names: Vec<&str> = model.points.iter().map(|pt| pt.name.as_str()).collect();
    let joint_names: Vec<&str> = model.joints.iter().map(|j| j.name.as_str()).collect();
    let n_moving = n_links - 1;
    let by_name = |ty: &Ident, what: &str, link_ty: TokenStream, point_ty: TokenStream| {
        let doc_l = format!("The {what} of the link named `name`, if any.");
        let doc_p = format!("The {what} of the point named `name`, if any.");
        quote! {
            impl #ty {
                #[doc = #doc_l]
                pub fn link(&self, name: &str) -> Option<&#link_ty> {
                    match name { #(#link_names => Some(&self.links.#moving_ids),)* _ => None }
                }
                #[doc = #doc_p]
                pub fn point(&self, name: &str) -> Option<&#point_ty> {
                    match name { #(#point_names => Some(&self.points.#point_ids),)* _ => None }
                }
            }
        }
    };
    let pose_by_name = by_name(pose, "pose", quote!(#p::kinematics::LinkPose), quote!(#p::kinematics::PointPose));
    let motion_by_name = by_name(motion, "motion", quote!(#p::kinematics::LinkMotion), quote!(#p::kinematics::PointMotion));
    let reaction_by_name = model.joints.iter().enumerate().map(|(j, jt)| {
        let jid = &joint_ids[j];
        let n = &jt.name;
        match jt.kind {
            JointKind::Prismatic => quote!(#n => Some((self.joints.#jid.force, Some(self.joints.#jid.moment))),),
            _ => quote!(#n => Some((self.joints.#jid.force, None)),),
        }
    });
    let loads_by_name = model.loads.iter().map(|l| {
        let lid = id(l.name());
        let n = l.name();
        match l {
            Load::Force { .. } => quote!(#n if value.len() == 2 => { self.#lid = #p::Vector2::new(value[0], value[1]); true }),
            Load::Torque { .. } => quote!(#n if value.len() == 1 => { self.#lid = value[0]; true }),
        }
    });
    let loads_impl = quote! {
        impl #loads {
            /// Set the load named `name` from its components (2 for a force, 1 for a
            /// torque); false when there is no such load or the length is wrong.
            pub fn set_by_name(&mut self, name: &str, value: &[f64]) -> bool {
                match name { #(#loads_by_name,)* _ => { let _ = value; false } }
            }
        }
    };
    let forces_by_name = if redundant {
        quote!()
    } else {
        quote! {
            impl #forces {
                /// The reaction at the joint named `name`: force by a on b (N) and, for a
                /// prismatic joint, the moment (N·m).
                pub fn reaction(&self, name: &str) -> Option<(#v2, Option<f64>)> {
                    match name { #(#reaction_by_name)* _ => None }
                }
            }
        }
    };

    // Flattened forces: drivers first, then per joint (fx, fy[, moment]).
    let mut offsets = Vec::new();
    let mut flat_len = dof;
    for jt in &model.joints {
        offsets.push(flat_len);
        flat_len += if jt.kind == JointKind::Prismatic { 3 } else { 2 };
    }
    let flat_driver = if one_dof { quote!(out[0] = f.driver;) } else { quote!(out[..#dof].copy_from_slice(&f.driver);) };
    let flat_joints: Vec<TokenStream> = model.joints.iter().enumerate().map(|(j, jt)| {
        let jid = &joint_ids[j];
        let o = offsets[j];
        let (o1, o2) = (o + 1, o + 2);
        if jt.kind == JointKind::Prismatic {
            quote!(out[#o] = f.joints.#jid.force.x; out[#o1] = f.joints.#jid.force.y; out[#o2] = f.joints.#jid.moment;)
        } else {
            quote!(out[#o] = f.joints.#jid.force.x; out[#o1] = f.joints.#jid.force.y;)
        }
    }).collect();
    let friction_calls: Vec<TokenStream> = model.joints.iter().enumerate().map(|(j, jt)| {
        let o = offsets[j];
        let o1 = o + 1;
        let kernel = if jt.kind == JointKind::Revolute { quote!(revolute) } else { quote!(sliding) };
        quote!(#p::friction::#kernel(&mut extra, &self.joints[#j], s, &friction[#j], #p::Vector2::new(prev[#o], prev[#o1]));)
    }).collect();

    let kinetostatics = if redundant {
        quote! {
            /// Not available: with redundant constraints the reactions are statically
            /// indeterminate. Calling this fails to compile with that explanation; use
            /// `driver_action`.
            pub fn kinetostatics<M: #p::traits::DeterminateReactions>(&self, m: &M, loads: &#loads) -> Result<#forces, #p::MechError> {
                let _ = loads;
                match m.never() {}
            }
        }
    } else {
        quote! {
            /// Kinetostatics by d'Alembert (`docs/theory.md` §4): the motor action of every input
            /// and the reaction at every joint, solved group by group from the outermost
            /// Assur group inward. Reactions are forces BY the joint's first link ON its
            /// second (N), prismatic joints add a moment (N·m, CCW on the second link).
            pub fn kinetostatics(&self, m: &#motion, loads: &#loads) -> Result<#forces, #p::MechError> {
                self.__kinetostatics(m, loads, None)
            }

            /// Kinetostatics with Coulomb friction in the joints (`friction[j]` for joint j
            /// in declaration order, see `mech::friction`): d'Alembert iterated to a fixed
            /// point, friction from the reactions of the previous iterate;
            /// `MechError::SelfLocking` when no finite motor action moves the mechanism.
            pub fn kinetostatics_with_friction(
                &self,
                m: &#motion,
                loads: &#loads,
                friction: &[#p::friction::JointFriction; #n_joints],
            ) -> Result<#forces, #p::MechError> {
                let s = &m.states;
                let first = Self::__flat(&self.__kinetostatics(m, loads, None)?);
                let mut last = None;
                #p::friction::iterate(first, |prev| {
                    let mut extra = [#p::kinetostatics::Wrench::zeros(); #n_links];
                    #(#friction_calls)*
                    let f = self.__kinetostatics(m, loads, Some(&extra))?;
                    let flat = Self::__flat(&f);
                    last = Some(f);
                    Ok(flat)
                })?;
                match last {
                    Some(f) => Ok(f),
                    None => self.__kinetostatics(m, loads, None),
                }
            }

            fn __kinetostatics(
                &self,
                m: &#motion,
                loads: &#loads,
                extra: Option<&[#p::kinetostatics::Wrench; #n_links]>,
            ) -> Result<#forces, #p::MechError> {
                let s = &m.states;
                let mut f = self.__wrenches(s, loads, true)?;
                if let Some(extra) = extra {
                    for (fi, ei) in f.iter_mut().zip(extra) {
                        *fi += ei;
                    }
                }
                let mut r = [#p::kinetostatics::Reaction::default(); #n_joints];
                let mut d = [0.0; #dof];
                #(#reaction_calls)*
                Ok(#forces { driver: #driver_value, joints: #forces_joints { #(#reaction_vals)* } })
            }

            /// Motor actions, then every joint's force (and prismatic moment), as one array.
            fn __flat(f: &#forces) -> [f64; #flat_len] {
                let mut out = [0.0; #flat_len];
                #flat_driver
                #(#flat_joints)*
                out
            }
        }
    };
    let forces_struct = if redundant {
        quote! {
            /// Not available: the mechanism has redundant constraints, so its reactions are
            /// statically indeterminate (`#[allow(redundant)]`); use `driver_action`.
            #[derive(Clone, Copy, Debug)]
            pub struct #forces { _private: () }
        }
    } else {
        quote! {
            /// Reactions at every joint (`docs/conventions.md#reactions`).
            #[allow(non_snake_case)]
            #[derive(Clone, Copy, Debug, Default, PartialEq)]
            pub struct #forces_joints { #(#reaction_fields)* }
            /// Result of `kinetostatics`: the motor actions and every joint reaction.
            #[derive(Clone, Copy, Debug, Default, PartialEq)]
            pub struct #forces {
                /// The motor action of each input: torque by a on b (N·m) for a revolute
                /// input, force along the axis on b (N) for a prismatic one.
                pub driver: #q_ty,
                /// The reaction at every joint.
                pub joints: #forces_joints,
            }
        }
    };

    let zhuk_inertia = quote!(#( z.inertia(&self.links[#massive], &s[#massive]); )*);
    let zhuk_gravity: Vec<TokenStream> = if model.gravity.is_some() {
        (1..n_links)
            .filter(|&l| model.links[l].mass.is_some_and(|m| m != 0.0))
            .map(|l| quote!(z.gravity(&self.links[#l], &s[#l], self.gravity);))
            .collect()
    } else {
        vec![]
    };
    let zhuk_loads = model.loads.iter().enumerate().map(|(k, l)| {
        let lid = id(l.name());
        let link = l.link();
        match l {
            Load::Force { .. } => quote!(z.force(&s[#link], self.loads[#k], loads.#lid);),
            Load::Torque { .. } => quote!(z.torque(&s[#link], loads.#lid);),
        }
    });
    let zhuk_moment = quote!(#(#zhuk_gravity)* #(#zhuk_loads)*);
    let one_dof_api = if one_dof {
        quote! {
            /// Zhukovski's reduced inertia I*(q) (kg·m²) and dI*/dq (kg·m²/rad), in closed
            /// form from the velocity coefficients and their derivatives.
            pub fn reduced(&self, q: f64) -> Result<#p::zhukovski::Reduced, #p::MechError> {
                #p::error::check_finite("q", &[q])?;
                let (s, _) = self.__solve(&[q], &[1.0], &[0.0], #p::kinematics::Level::Acceleration)?;
                let mut z = #p::zhukovski::Reduction::default();
                #zhuk_inertia
                Ok(z.reduced)
            }
            /// Zhukovski's reduced moment M*(q) (N·m): the power of the loads and gravity
            /// per unit input rate, M* = Σ F·g + Σ M·g.
            pub fn reduced_moment(&self, q: f64, loads: &#loads) -> Result<f64, #p::MechError> {
                #p::error::check_finite("q", &[q])?;
                #p::error::check_finite("loads", &[#(#load_checks)*])?;
                let (s, _) = self.__solve(&[q], &[1.0], &[0.0], #p::kinematics::Level::Velocity)?;
                let mut z = #p::zhukovski::Reduction::default();
                #zhuk_moment
                Ok(z.moment)
            }
            /// The direct problem: q̈ (rad/s²) from I* q̈ + ½ dI*/dq q̇² = driver + M*.
            pub fn acceleration(&self, q: f64, qd: f64, driver: f64, loads: &#loads) -> Result<f64, #p::MechError> {
                #p::error::check_finite("q, qd, driver", &[q, qd, driver])?;
                #p::error::check_finite("loads", &[#(#load_checks)*])?;
                let (s, _) = self.__solve(&[q], &[1.0], &[0.0], #p::kinematics::Level::Acceleration)?;
                let mut z = #p::zhukovski::Reduction::default();
                #zhuk_inertia
                #zhuk_moment
                #p::zhukovski::acceleration(z.reduced, z.moment, qd, driver)
            }
        }
    } else {
        quote!()
    };

    let ke_terms = massive.iter().map(|&l| {
        let lid = &link_ids[l];
        quote!(out[#l] = 0.5 * (self.links[#l].mass * m.links.#lid.cg_vel.norm_squared() + self.links[#l].inertia * m.links.#lid.omega * m.links.#lid.omega);)
    });
    let pe_terms: Vec<TokenStream> = if model.gravity.is_some() {
        massive.iter().map(|&l| {
            let lid = &link_ids[l];
            quote!(v -= self.links[#l].mass * self.gravity.dot(&m.links.#lid.cg);)
        }).collect()
    } else {
        vec![]
    };
    let slice_to_q = |v: Ident| -> TokenStream {
        if one_dof {
            quote!(#v[0])
        } else {
            let idx = 0..dof;
            quote!([#(#v[#idx]),*])
        }
    };
    let (sq, sqd, sqdd) = (slice_to_q(id("q")), slice_to_q(id("qd")), slice_to_q(id("qdd")));
    let drv_store = if one_dof { quote!(out[0] = d;) } else { quote!(out.copy_from_slice(&d);) };
    let machine_impl = quote! {
        impl #p::traits::Machine for #main {
            const DOF: usize = #dof;
            const LINKS: usize = #n_links;
            type Loads = #loads;
            type Motion = #motion;
            fn motion(&self, q: &[f64], qd: &[f64], qdd: &[f64]) -> Result<#motion, #p::MechError> {
                if q.len() != #dof || qd.len() != #dof || qdd.len() != #dof {
                    return Err(#p::MechError::InvalidInput(format!("expected {} input values", #dof)));
                }
                self.kinematics(#sq, #sqd, #sqdd)
            }
            fn driver_actions(&self, m: &#motion, loads: &#loads, out: &mut [f64]) -> Result<(), #p::MechError> {
                let d = self.driver_action(m, loads)?;
                #drv_store
                Ok(())
            }
            fn link_kinetic_energies(&self, m: &#motion, out: &mut [f64]) {
                for o in out.iter_mut() {
                    *o = 0.0;
                }
                #(#ke_terms)*
            }
            fn potential_energy(&self, m: &#motion) -> f64 {
                let mut v = 0.0;
                #(#pe_terms)*
                let _ = m;
                v
            }
        }
    };
    let one_dof_impl = if one_dof {
        quote! {
            impl #p::traits::OneDof for #main {
                fn reduced(&self, q: f64) -> Result<#p::zhukovski::Reduced, #p::MechError> {
                    #main::reduced(self, q)
                }
                fn reduced_moment(&self, q: f64, loads: &#loads) -> Result<f64, #p::MechError> {
                    #main::reduced_moment(self, q, loads)
                }
                fn acceleration(&self, q: f64, qd: f64, driver: f64, loads: &#loads) -> Result<f64, #p::MechError> {
                    #main::acceleration(self, q, qd, driver, loads)
                }
            }
        }
    } else {
        quote!()
    };
    let q_arr = to_arr(&id("q"));
    let qd_arr = to_arr(&id("qd"));
    let qdd_arr = to_arr(&id("qdd"));
    let driver_out = from_arr(quote!(out));
    let mut joints_copy = quote!();
    for j in 0..n_joints {
        joints_copy.extend(quote!(inst.joints[#j],));
    }
    let links_copy = (0..n_links).map(|l| quote!(inst.links[#l],));
    let drawing_copy = (0..n_links).map(|l| quote!(inst.drawing[#l],));
    let points_copy = (0..n_points).map(|pt| quote!(inst.points[#pt].1,));
    let loads_copy = (0..n_loads).map(|k| quote!(inst.loads[#k],));
    let branches_copy = (0..n_groups).map(|g| quote!(branches[#g],));

    quote! {
        #(#docs)*
        #[doc = #doc_struct]
        #[derive(Clone, Debug)]
        pub struct #main {
            params: #params,
            joints: [#p::kinematics::JointGeom; #n_joints],
            links: [#p::kinematics::LinkGeom; #n_links],
            drawing: [#p::kinematics::LinkState; #n_links],
            points: [#v2; #n_points],
            loads: [#v2; #n_loads],
            branches: [f64; #n_groups],
            scale: f64,
            gravity: #v2,
        }

        /// Reference coordinates of every point (m).
        #[allow(non_snake_case)]
        #[derive(Clone, Debug, PartialEq)]
        pub struct #params_points { #(pub #point_ids: #v2,)* }
        /// Mass data of every moving link.
        #[allow(non_snake_case)]
        #[derive(Clone, Debug, PartialEq)]
        pub struct #params_links { #(pub #moving_ids: #p::instance::LinkParams,)* }
        /// Sliding axes (reference global coordinates) of the prismatic and slot joints.
        #[allow(non_snake_case)]
        #[derive(Clone, Debug, PartialEq)]
        pub struct #params_axes { #(pub #sliding_ids: #v2,)* }
        /// Every number of the drawing; `Default` is the drawing as declared.
        #[derive(Clone, Debug, PartialEq)]
        pub struct #params {
            /// Points, m.
            pub points: #params_points,
            /// Links' mass, inertia and cg.
            pub links: #params_links,
            /// Sliding axes.
            pub axes: #params_axes,
            #gravity_field
        }
        impl Default for #params {
            fn default() -> Self {
                #params {
                    points: #params_points { #(#point_ids: #point_defaults,)* },
                    links: #params_links { #(#moving_ids: #link_defaults,)* },
                    axes: #params_axes { #(#sliding_ids: #axis_defaults,)* },
                    #gravity_default
                }
            }
        }

        /// The declared loads; `Default` is all zero.
        #[allow(non_snake_case)]
        #[derive(Clone, Copy, Debug, Default, PartialEq)]
        pub struct #loads { #(#load_fields)* }

        /// Pose of every moving link.
        #[allow(non_snake_case)]
        #[derive(Clone, Copy, Debug, PartialEq)]
        pub struct #pose_links { #(pub #moving_ids: #p::kinematics::LinkPose,)* }
        /// Position of every point.
        #[allow(non_snake_case)]
        #[derive(Clone, Copy, Debug, PartialEq)]
        pub struct #pose_points { #(pub #point_ids: #p::kinematics::PointPose,)* }
        /// Result of `pose`: positions only.
        #[derive(Clone, Copy, Debug, PartialEq)]
        pub struct #pose {
            /// Links: angle (rad), cg (m).
            pub links: #pose_links,
            /// Points: pos (m).
            pub points: #pose_points,
        }

        /// Motion of every moving link.
        #[allow(non_snake_case)]
        #[derive(Clone, Copy, Debug, PartialEq)]
        pub struct #motion_links { #(pub #moving_ids: #p::kinematics::LinkMotion,)* }
        /// Motion of every point.
        #[allow(non_snake_case)]
        #[derive(Clone, Copy, Debug, PartialEq)]
        pub struct #motion_points { #(pub #point_ids: #p::kinematics::PointMotion,)* }
        /// Result of `kinematics`: positions, velocities, accelerations.
        #[derive(Clone, Copy, Debug, PartialEq)]
        pub struct #motion {
            /// Links: angle, omega, alpha, cg, cg_vel, cg_acc.
            pub links: #motion_links,
            /// Points: pos, vel, acc.
            pub points: #motion_points,
            states: [#p::kinematics::LinkState; #n_links],
            qd: [f64; #dof],
            systems: #systems_ty,
        }

        #forces_struct
        #forces_by_name
        #pose_by_name
        #motion_by_name
        #loads_impl

        #machine_impl
        #one_dof_impl

        impl Default for #main {
            fn default() -> Self {
                Self::new()
            }
        }

        impl #main {
            /// G: the number of inputs (degrees of freedom).
            pub const DOF: usize = #dof;
            /// N: links, ground included.
            pub const LINKS: usize = #n_links;
            /// P_I: lower pairs (revolute, prismatic).
            pub const LOWER_PAIRS: usize = #lower;
            /// P_II: higher pairs (pins in slots).
            pub const HIGHER_PAIRS: usize = #higher;
            /// Equations of motion: 3(N − 1).
            pub const EQUATIONS: usize = #equations;
            /// Unknowns: G + 2 P_I + P_II.
            pub const UNKNOWNS: usize = #unknowns;
            /// The moving links' names, in declaration order.
            pub const LINK_NAMES: [&'static str; #n_moving] = [#(#link_names),*];
            /// The points' names, in order of definition.
            pub const POINT_NAMES: [&'static str; #n_points] = [#(#point_names),*];
            /// The joints' names, in declaration order.
            pub const JOINT_NAMES: [&'static str; #n_joints] = [#(#joint_names),*];

            #(#group_consts)*

            /// The mechanism as drawn.
            pub fn new() -> Self {
                match Self::from_params(#params::default()) {
                    Ok(m) => m,
                    Err(e) => panic!("the drawing was checked at compile time: {e}"),
                }
            }

            /// The mechanism with other numbers; re-runs the drawing, rank and determinacy
            /// checks of the macro at run time.
            pub fn from_params(p: #params) -> Result<Self, #p::MechError> {
                let model = Self::__model(&p);
                let inst = #p::instance::instance(&model)?;
                let branches = inst.branches(&[#(#solvers),*]);
                Ok(#main {
                    joints: [#joints_copy],
                    links: [#(#links_copy)*],
                    drawing: [#(#drawing_copy)*],
                    points: [#(#points_copy)*],
                    loads: [#(#loads_copy)*],
                    branches: [#(#branches_copy)*],
                    scale: inst.scale,
                    gravity: inst.gravity,
                    params: p,
                })
            }

            /// The numbers of the drawing in use.
            pub fn params(&self) -> &#params {
                &self.params
            }

            fn __model(p: &#params) -> #p::model::Model {
                #p::model::Model {
                    name: #model_name.into(),
                    gravity: #gravity_model,
                    allow_redundant: #redundant,
                    points: vec![#(#m_points),*],
                    links: vec![#(#m_links),*],
                    joints: vec![#(#m_joints),*],
                    inputs: vec![#(#m_inputs),*],
                    loads: vec![#(#m_loads),*],
                }
            }

            #[inline(always)]
            #[inline(always)]
            fn __solve(
                &self,
                q: &[f64; #dof],
                qd: &[f64; #dof],
                qdd: &[f64; #dof],
                upto: #p::kinematics::Level,
            ) -> Result<([#p::kinematics::LinkState; #n_links], #systems_ty), #p::MechError> {
                #solve_entry
            }

            #[inline(always)]
            fn __solve_on(
                &self,
                branches: &[f64; #n_groups],
                q: &[f64; #dof],
                qd: &[f64; #dof],
                qdd: &[f64; #dof],
                upto: #p::kinematics::Level,
            ) -> Result<([#p::kinematics::LinkState; #n_links], #systems_ty), #p::MechError> {
                let mut s = #initial;
                let drive = (&q[..], &qd[..], &qdd[..]);
                #(#solve_calls)*
                Ok((s, (#(#sys_ids,)*)))
            }

            #[inline(always)]
            fn __velocity_field(
                &self,
                m: &#motion,
                qd: &[f64; #dof],
            ) -> Result<[#p::kinematics::LinkState; #n_links], #p::MechError> {
                let mut v = m.states;
                for st in v.iter_mut() {
                    st.vel = #p::Vector2::zeros();
                    st.omega = 0.0;
                }
                let zero = [0.0; #dof];
                let drive = (&zero[..], &qd[..], &zero[..]);
                #(#velocity_calls)*
                Ok(v)
            }

            /// Applied (loads, gravity) and, when `inertia`, d'Alembert inertia wrenches per link.
            #[inline(always)]
            fn __wrenches(
                &self,
                s: &[#p::kinematics::LinkState; #n_links],
                loads: &#loads,
                inertia: bool,
            ) -> Result<[#p::kinetostatics::Wrench; #n_links], #p::MechError> {
                #p::error::check_finite("loads", &[#(#load_checks)*])?;
                let mut f = [#p::kinetostatics::Wrench::zeros(); #n_links];
                #gravity_terms
                #(#load_terms)*
                if inertia {
                    #inertia_terms
                }
                Ok(f)
            }

            /// Position analysis: every link's angle and cg, every point's position.
            /// Computes no velocity or acceleration.
            pub fn pose(&self, q: #q_ty) -> Result<#pose, #p::MechError> {
                #q_arr
                #p::error::check_finite("q", &q)?;
                let zero = [0.0; #dof];
                let (s, _) = self.__solve(&q, &zero, &zero, #p::kinematics::Level::Position)?;
                Ok(#pose {
                    links: #pose_links { #(#pose_link_vals)* },
                    points: #pose_points { #(#pose_point_vals)* },
                })
            }

            /// Position, velocity and acceleration analysis at input (q, q̇, q̈).
            pub fn kinematics(&self, q: #q_ty, qd: #q_ty, qdd: #q_ty) -> Result<#motion, #p::MechError> {
                #q_arr #qd_arr #qdd_arr
                #p::error::check_finite("q, qd, qdd", &q)?;
                #p::error::check_finite("q, qd, qdd", &qd)?;
                #p::error::check_finite("q, qd, qdd", &qdd)?;
                let (s, systems) = self.__solve(&q, &qd, &qdd, #p::kinematics::Level::Acceleration)?;
                Ok(#motion {
                    links: #motion_links { #(#motion_link_vals)* },
                    points: #motion_points { #(#motion_point_vals)* },
                    states: s,
                    qd,
                    systems,
                })
            }

            #kinetostatics

            /// The motor actions by the principle of virtual power, computing no reaction:
            /// for each input, the velocity field that moves it alone at unit rate, and
            /// Q = −Σ (F·v + M·ω) over loads, gravity and inertia forces. With one input
            /// moving (q̇ ≠ 0) that field is the motion's own velocities divided by q̇.
            pub fn driver_action(&self, m: &#motion, loads: &#loads) -> Result<#q_ty, #p::MechError> {
                let s = &m.states;
                let f = self.__wrenches(s, loads, true)?;
                let mut out = [0.0; #dof];
                // One input moving at q̇ ≠ 0: the motion's own velocities are q̇ times the
                // virtual field, so no velocity system needs solving.
                if #dof == 1 && m.qd[0] != 0.0 {
                    out[0] = -#p::kinetostatics::virtual_power(&f, s) / m.qd[0];
                    return Ok(#driver_out);
                }
                for k in 0..#dof {
                    let mut qd = [0.0; #dof];
                    qd[k] = 1.0;
                    let v = self.__velocity_field(m, &qd)?;
                    out[k] = -#p::kinetostatics::virtual_power(&f, &v);
                }
                Ok(#driver_out)
            }

            #one_dof_api
        }
    }
}
