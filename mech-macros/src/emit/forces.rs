//! The forces: `<Name>Loads`, the wrenches on every link (`__wrenches`: loads, gravity,
//! d'Alembert's inertia), `<Name>Forces`, and the routes to the motor actions:
//! `kinetostatics` (d'Alembert, every reaction), `kinetostatics_with_friction` and
//! `driver_action` (virtual power, no reaction).

use super::{id, plan, Ctx};
use mech_core::model::{JointKind, Load};
use mech_core::plan::assur::{Group, Kernel};
use proc_macro2::TokenStream;
use quote::{format_ident, quote};

/// The loads and forces types and the force methods.
pub(crate) fn emit(cx: &Ctx) -> TokenStream {
    let main = &cx.names.main;
    let (loads, forces, wrenches) = (loads_type(cx), forces_type(cx), wrenches_fn(cx));
    let kinetostatics = if cx.redundant() {
        no_kinetostatics(cx)
    } else {
        kinetostatics_fns(cx)
    };
    let driver_action = driver_action_fn(cx);
    quote! {
        #loads
        #forces
        impl #main {
            #wrenches
            #kinetostatics
            #driver_action
        }
    }
}

/// `Loads` (one field per declared load) and `set_by_name`.
fn loads_type(cx: &Ctx) -> TokenStream {
    let Ctx { p, v2, model, .. } = cx;
    let loads = &cx.names.loads;
    let fields = model.loads.iter().map(|l| {
        let lid = id(l.name());
        match l {
            Load::Force { link, point, .. } => {
                let doc = format!(
                    "Force (N, global vector) on `{}` at `{}`.",
                    model.links[*link].name, model.points[*point].name
                );
                quote!(#[doc = #doc] pub #lid: #v2,)
            }
            Load::Torque { link, .. } => {
                let doc = format!(
                    "Torque (N·m, CCW positive) on `{}`.",
                    model.links[*link].name
                );
                quote!(#[doc = #doc] pub #lid: f64,)
            }
        }
    });
    let by_name = model.loads.iter().map(|l| {
        let (lid, n) = (id(l.name()), l.name());
        match l {
            Load::Force { .. } => quote!(#n if value.len() == 2 => { self.#lid = #p::Vector2::new(value[0], value[1]); true }),
            Load::Torque { .. } => quote!(#n if value.len() == 1 => { self.#lid = value[0]; true }),
        }
    });
    quote! {
        /// The declared loads; `Default` is all zero.
        #[allow(non_snake_case)]
        #[derive(Clone, Copy, Debug, Default, PartialEq)]
        pub struct #loads { #(#fields)* }
        impl #loads {
            /// Set the load named `name` from its components (2 for a force, 1 for a
            /// torque); false when there is no such load or the length is wrong.
            pub fn set_by_name(&mut self, name: &str, value: &[f64]) -> bool {
                match name { #(#by_name,)* _ => { let _ = value; false } }
            }
        }
    }
}

/// The components of every load, for `check_inputs`.
pub(crate) fn load_values(cx: &Ctx) -> TokenStream {
    let values = cx.model.loads.iter().map(|l| {
        let lid = id(l.name());
        match l {
            Load::Force { .. } => quote!(loads.#lid.x, loads.#lid.y,),
            Load::Torque { .. } => quote!(loads.#lid,),
        }
    });
    quote!(#(#values)*)
}

/// `Forces` with one reaction per joint and `reaction(name)`; an empty `Forces` for a
/// redundant mechanism (its reactions are indeterminate).
fn forces_type(cx: &Ctx) -> TokenStream {
    let Ctx {
        p,
        v2,
        q_ty,
        model,
        joint_ids,
        ..
    } = cx;
    let (forces, forces_joints) = (&cx.names.forces, &cx.names.forces_joints);
    if cx.redundant() {
        return quote! {
            /// Not available: the mechanism has redundant constraints, so its reactions are
            /// statically indeterminate (`#[allow(redundant)]`); use `driver_action`.
            #[derive(Clone, Copy, Debug)]
            pub struct #forces { _private: () }
        };
    }
    let fields = model.joints.iter().zip(joint_ids).map(|(jt, jid)| {
        let (ty, what) = match jt.kind {
            JointKind::Revolute => (quote!(#p::kinetostatics::RevoluteReaction), "force by"),
            JointKind::Prismatic => (
                quote!(#p::kinetostatics::PrismaticReaction),
                "force (normal to the axis) and moment by",
            ),
            JointKind::PinInSlot => (
                quote!(#p::kinetostatics::SlotReaction),
                "force (normal to the slot) by",
            ),
            JointKind::Cam => (
                quote!(#p::kinetostatics::CamReaction),
                "contact force (along the common normal, at the contact point) and its signed magnitude by",
            ),
            JointKind::Rolling => (
                quote!(#p::kinetostatics::RollingReaction),
                "contact force (at the contact point: normal and friction) by",
            ),
            JointKind::Gear | JointKind::Rack => (
                quote!(#p::kinetostatics::MeshReaction),
                "tooth force (along the line of action, at the pitch point), its magnitude and the flank in contact, by",
            ),
        };
        let doc = format!(
            "Joint `{}`: {} `{}` on `{}`.",
            jt.name, what, model.links[jt.a].name, model.links[jt.b].name
        );
        quote!(#[doc = #doc] pub #jid: #ty,)
    });
    let by_name = model.joints.iter().zip(joint_ids).map(|(jt, jid)| {
        let n = &jt.name;
        match jt.kind {
            JointKind::Prismatic => {
                quote!(#n => Some((self.joints.#jid.force, Some(self.joints.#jid.moment))),)
            }
            _ => quote!(#n => Some((self.joints.#jid.force, None)),),
        }
    });
    let inputs = &cx.inputs_doc;
    let dof = cx.dof;
    let zero = if cx.one_dof() {
        quote!(0.0)
    } else {
        quote!([0.0; #dof])
    };
    quote! {
        /// Reactions at every joint (`docs/conventions.md#reactions`).
        #[allow(non_snake_case)]
        #[derive(Clone, Copy, Debug, Default, PartialEq)]
        pub struct #forces_joints { #(#fields)* }
        /// Result of `kinetostatics`: the motor actions and every joint reaction.
        #[derive(Clone, Copy, Debug, PartialEq)]
        pub struct #forces {
            /// The motor action of each input: torque by a on b (N·m) for a revolute
            /// input, force along the axis on b (N) for a prismatic one.
            ///
            #(#[doc = #inputs])*
            pub driver: #q_ty,
            /// The reaction at every joint.
            pub joints: #forces_joints,
        }
        impl Default for #forces {
            fn default() -> Self {
                Self { driver: #zero, joints: Default::default() }
            }
        }
        impl #forces {
            /// The reaction at the joint named `name`: force by a on b (N) and, for a
            /// prismatic joint, the moment (N·m).
            pub fn reaction(&self, name: &str) -> Option<(#v2, Option<f64>)> {
                match name { #(#by_name)* _ => None }
            }
        }
    }
}

/// `__wrenches`: gravity on the links declared with `mass`, the loads, the force elements,
/// and d'Alembert's inertia wrench of the links with inertia terms; each
/// about its link's anchor, from the motion's published cg, cg acceleration and load
/// points (nothing is rotated again).
fn wrenches_fn(cx: &Ctx) -> TokenStream {
    let Ctx { p, n_links, .. } = cx;
    let (motion, loads) = (&cx.names.motion, &cx.names.loads);
    let link = |l: usize| &cx.link_ids[l];
    let weighed = cx.weighed().into_iter().map(|l| {
        let lid = link(l);
        quote!(#p::kinetostatics::add_gravity_of(&mut f[#l], s[#l].pos, &m.links.#lid, &self.links[#l], self.gravity);)
    });
    let inertial = cx.inertial().into_iter().map(|l| {
        let lid = link(l);
        quote!(#p::kinetostatics::add_inertia_of(&mut f[#l], s[#l].pos, &m.links.#lid, &self.links[#l]);)
    });
    let elements = if cx.has_elements() {
        quote!(#p::elements::add_wrenches(&self.elements, s, &mut f);)
    } else {
        quote!()
    };
    let load_terms = cx.model.loads.iter().map(|l| {
        let (lid, link) = (id(l.name()), l.link());
        match *l {
            Load::Force { point, .. } => {
                let pid = &cx.point_ids[point];
                quote!(#p::kinetostatics::add_force_at(&mut f[#link], s[#link].pos, m.points.#pid.pos, loads.#lid);)
            }
            Load::Torque { .. } => quote!(#p::kinetostatics::add_torque(&mut f[#link], loads.#lid);),
        }
    });
    quote! {
        /// Applied (loads, gravity) and d'Alembert inertia wrenches per link, for the motion
        /// `m` whose link states are `s` (`m.__states()`).
        #[inline(always)]
        fn __wrenches(
            &self,
            m: &#motion,
            s: &[#p::kinematics::LinkState; #n_links],
            loads: &#loads,
        ) -> [#p::kinetostatics::Wrench; #n_links] {
            // Started at −0, the identity of IEEE addition: each link's first term is taken
            // as it is (`kinetostatics::wrench_sum`).
            let mut f = [#p::kinetostatics::wrench_sum(); #n_links];
            #(#weighed)*
            #(#load_terms)*
            #elements
            #(#inertial)*
            f
        }
    }
}

/// The reaction call of group `gi`: its joints' reactions into `r`, its inputs' motor
/// actions into `d`, its reactions passed on to the inner links' wrenches `f`.
fn reaction_call(cx: &Ctx, gi: usize, g: &Group) -> TokenStream {
    let p = &cx.p;
    let (bn, cn) = plan::system_consts(gi);
    let n = 3 * g.bodies.len();
    let path = crate::emit::plan::system_path(cx, gi);
    match g.kernel {
        Kernel::Driven(_) => {
            let kn = format_ident!("__G{}_DRIVEN", gi);
            quote!(#p::screw::driven_reactions(&Self::#kn, &joints, s, &mut f, &mut r, &mut d);)
        }
        Kernel::Chain(_) => {
            let kn = format_ident!("__G{}_CHAIN", gi);
            let solver = plan::solver_const(gi);
            let kept = if plan::keeps_system(g) {
                quote!(&m.systems #path)
            } else {
                quote!(&#p::kinematics::DyadSystem::None)
            };
            quote!(#p::kinematics::chain_reactions(Self::#solver, &Self::#kn, &joints, s, &mut f, self.scale, #kept, &mut r)?;)
        }
        Kernel::Mesh(_) => {
            let kn = plan::mesh_const(gi);
            quote!(#p::gears::mesh_reactions(&Self::#kn, &self.meshes, &joints, s, &mut f, &mut r)?;)
        }
        Kernel::Train(_) => {
            let kn = plan::mesh_const(gi);
            quote!(#p::gears::train_reactions(&Self::#kn, &self.meshes, &joints, s, &mut f, &mut r)?;)
        }
        Kernel::Cam(_) => {
            let kn = plan::mesh_const(gi);
            quote!(#p::cam::cam_reactions(&Self::#kn, &self.cams, &joints, s, Some(&m.systems #path), &mut f, &mut r)?;)
        }
        Kernel::Rolling(_) => {
            let kn = plan::mesh_const(gi);
            quote!(#p::rolling::rolling_reactions(&Self::#kn, &joints, s, &mut f, self.scale, &mut r, &mut d)?;)
        }
        Kernel::System => quote! {
            let lam = #p::kinetostatics::group_reactions::<#n>(m.systems #path.as_ref(), &Self::#bn, &Self::#cn, &joints, s, &mut f, self.scale)?;
            #p::kinetostatics::lambda_reactions(&Self::#cn, &joints, s, lam.as_slice(), &mut r, &mut d);
        },
    }
}

/// The `kinetostatics` of a redundant mechanism: a bound no type meets, so that calling it
/// fails to compile with the explanation.
fn no_kinetostatics(cx: &Ctx) -> TokenStream {
    let p = &cx.p;
    let (loads, forces) = (&cx.names.loads, &cx.names.forces);
    quote! {
        /// Not available: with redundant constraints the reactions are statically
        /// indeterminate. Calling this fails to compile with that explanation; use
        /// `driver_action`.
        pub fn kinetostatics<M: #p::traits::DeterminateReactions>(&self, m: &M, loads: &#loads) -> Result<#forces, #p::MechError> {
            let _ = loads;
            match m.never() {}
        }
    }
}

/// `kinetostatics`, `kinetostatics_with_friction` and their helpers.
fn kinetostatics_fns(cx: &Ctx) -> TokenStream {
    let Ctx {
        p,
        n_joints,
        n_links,
        ..
    } = cx;
    let n = &cx.names;
    let (motion, loads, forces) = (&n.motion, &n.loads, &n.forces);
    let (inner, flat) = (inner_kinetostatics_fn(cx), flat_fn(cx));
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
            let s = &m.__states();
            let first = Self::__flat(&self.__kinetostatics(m, loads, None)?);
            let mut last = None;
            #p::friction::iterate(first, |prev| {
                let mut extra = [#p::kinetostatics::Wrench::zeros(); #n_links];
                #p::friction::add_joint_friction(&mut extra, &self.__joints(), &Self::__JOINT_KINDS, s, friction, Self::DOF, prev);
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

        #inner
        #flat
    }
}

/// `__kinetostatics`: the wrenches (plus the friction's `extra`), then every group's
/// reaction call from the outermost group inward.
fn inner_kinetostatics_fn(cx: &Ctx) -> TokenStream {
    let Ctx {
        p,
        n_joints,
        n_links,
        dof,
        joint_ids,
        model,
        ..
    } = cx;
    let n = &cx.names;
    let (motion, loads, forces, forces_joints) = (&n.motion, &n.loads, &n.forces, &n.forces_joints);
    let calls = cx
        .plan
        .iter()
        .enumerate()
        .rev()
        .map(|(gi, g)| reaction_call(cx, gi, g));
    let values = model.joints.iter().enumerate().map(|(j, jt)| {
        let jid = &joint_ids[j];
        match jt.kind {
            JointKind::Revolute => quote!(#jid: #p::kinetostatics::RevoluteReaction { force: r[#j].force },),
            JointKind::Prismatic => quote!(#jid: #p::kinetostatics::PrismaticReaction { force: r[#j].force, moment: r[#j].moment },),
            JointKind::PinInSlot => quote!(#jid: #p::kinetostatics::SlotReaction { force: r[#j].force },),
            JointKind::Gear | JointKind::Rack => quote!(#jid: #p::kinetostatics::MeshReaction { force: r[#j].force, tooth_load: r[#j].force.norm(), flank: r[#j].moment },),
            JointKind::Rolling => quote!(#jid: #p::rolling::report(&joints[#j], s, r[#j].force),),
            JointKind::Cam => quote!(#jid: #p::kinetostatics::CamReaction { force: r[#j].force, normal_force: r[#j].moment },),
        }
    });
    let driver = if cx.one_dof() {
        quote!(d[0])
    } else {
        quote!(d)
    };
    let load_values = load_values(cx);
    quote! {
        fn __kinetostatics(
            &self,
            m: &#motion,
            loads: &#loads,
            extra: Option<&[#p::kinetostatics::Wrench; #n_links]>,
        ) -> Result<#forces, #p::MechError> {
            let s = &m.__states();
            let joints = self.__joints();
            let mut f = self.__wrenches(m, s, loads);
            if let Some(extra) = extra {
                for (fi, ei) in f.iter_mut().zip(extra) {
                    *fi += ei;
                }
            }
            let mut r = [#p::kinetostatics::Reaction::default(); #n_joints];
            let mut d = [0.0; #dof];
            #(#calls)*
            #p::magnitudes::finite_reactions(&r, &d)
                .map_err(|e| #p::error::blame("loads", &[#load_values], e))?;
            Ok(#forces { driver: #driver, joints: #forces_joints { #(#values)* } })
        }
    }
}

/// The joints' kinds and `__flat`: the forces in the flattened layout the friction's
/// fixed point iterates on (`mech::friction::Flattener`).
fn flat_fn(cx: &Ctx) -> TokenStream {
    let Ctx {
        p,
        n_joints,
        joint_ids,
        model,
        ..
    } = cx;
    let forces = &cx.names.forces;
    let kinds = model.joints.iter().map(|jt| match jt.kind {
        JointKind::Revolute => quote!(#p::model::JointKind::Revolute),
        JointKind::Prismatic => quote!(#p::model::JointKind::Prismatic),
        JointKind::PinInSlot => quote!(#p::model::JointKind::PinInSlot),
        JointKind::Gear => quote!(#p::model::JointKind::Gear),
        JointKind::Rack => quote!(#p::model::JointKind::Rack),
        JointKind::Rolling => quote!(#p::model::JointKind::Rolling),
        JointKind::Cam => quote!(#p::model::JointKind::Cam),
    });
    let drivers = if cx.one_dof() {
        quote!(&[f.driver])
    } else {
        quote!(&f.driver)
    };
    quote! {
        /// The kind of every joint, in declaration order.
        const __JOINT_KINDS: [#p::model::JointKind; #n_joints] = [#(#kinds),*];
        /// Motor actions, then every joint's force (and prismatic moment).
        const __FLAT_LEN: usize = #p::friction::flat_len(Self::DOF, &Self::__JOINT_KINDS);

        /// Motor actions, then every joint's force (and prismatic moment), as one array.
        fn __flat(f: &#forces) -> [f64; Self::__FLAT_LEN] {
            let mut out = [0.0; Self::__FLAT_LEN];
            let mut w = #p::friction::Flattener::new(&mut out, #drivers);
            #( w.push(&f.joints.#joint_ids); )*
            out
        }
    }
}

/// `driver_action`: the motor actions by virtual power, computing no reaction.
fn driver_action_fn(cx: &Ctx) -> TokenStream {
    let Ctx { p, q_ty, .. } = cx;
    let (motion, loads) = (&cx.names.motion, &cx.names.loads);
    let out = if cx.one_dof() {
        quote!(out[0])
    } else {
        quote!(out)
    };
    let inputs = &cx.inputs_doc;
    let load_values = load_values(cx);
    // With one input, `driver_action` is the short power balance (the fields' route is a
    // call of its own, for q̇ = 0): inlined where it is called, it reads the caller's
    // motion where it lies, instead of the caller copying it out to pass it by reference.
    let inline = if cx.one_dof() {
        quote!(#[inline])
    } else {
        quote!()
    };
    // One input moving: the power balance over the motion itself (no wrench is formed).
    let by_power = if cx.one_dof() {
        let link = |l: usize| &cx.link_ids[l];
        let inertia = cx.inertial().into_iter().map(|l| {
            let lid = link(l);
            quote!(w.inertia(&self.links[#l], &m.links.#lid);)
        });
        let gravity = cx.weighed().into_iter().map(|l| {
            let lid = link(l);
            quote!(w.gravity(&self.links[#l], &m.links.#lid, self.gravity);)
        });
        let applied = cx.model.loads.iter().map(|ld| {
            let name = id(ld.name());
            match *ld {
                Load::Force { point, .. } => {
                    let pid = &cx.point_ids[point];
                    quote!(w.force(&m.points.#pid, loads.#name);)
                }
                Load::Torque { link: l, .. } => {
                    let lid = link(l);
                    quote!(w.torque(&m.links.#lid, loads.#name);)
                }
            }
        });
        let elements = if cx.has_elements() {
            quote!(w.elements(&self.elements, &m.__states());)
        } else {
            quote!()
        };
        quote! {
            if m.qd[0] != 0.0 {
                let mut w = #p::virtual_power::Power::new();
                #(#inertia)*
                #(#gravity)*
                #(#applied)*
                #elements
                return w.driver(m.qd[0]).map_err(|e| #p::error::blame("loads", &[#load_values], e));
            }
        }
    } else {
        quote!()
    };
    quote! {
        /// The motor actions by the principle of virtual power, computing no reaction:
        /// for each input, the velocity field that moves it alone at unit rate, and
        /// Q = −Σ (F·v + M·ω) over loads, gravity and inertia forces. With one input
        /// moving (q̇ ≠ 0) that field is the motion's own velocities divided by q̇, and
        /// Q = (dT/dt − P)/q̇ (the kinetic energy's rate less the power of the loads and
        /// gravity, `mech::virtual_power::Power`).
        ///
        #(#[doc = #inputs])*
        #inline
        pub fn driver_action(&self, m: &#motion, loads: &#loads) -> Result<#q_ty, #p::MechError> {
            #by_power
            self.__driver_action_by_fields(*m, loads)
        }

        /// [`Self::driver_action`] by the virtual velocity field of each input. (The
        /// motion by value: the caller's is then only read, never given an address.)
        #[inline(never)]
        fn __driver_action_by_fields(&self, m: #motion, loads: &#loads) -> Result<#q_ty, #p::MechError> {
            let m = &m;
            let s = &m.__states();
            let f = self.__wrenches(m, s, loads);
            let out = #p::virtual_power::driver_actions(&f, s, &m.qd, |qd| self.__velocity_field(m, qd))
                .map_err(|e| #p::error::blame("loads", &[#load_values], e))?;
            Ok(#out)
        }
    }
}
