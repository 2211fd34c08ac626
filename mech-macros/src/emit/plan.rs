//! The plan: each Assur group's position solver and kernel data as constants, and the
//! solvers that call the group kernels in plan order (`__solve`, `__solve_on`,
//! `__velocity_field`).
//!
//! The call of each group kernel is emitted by one small function ([`solve_call`],
//! [`velocity_call`], and [`super::forces::reaction_call`] for the reactions), so that a
//! change of the mech-core kernels changes those functions only.

use super::Ctx;
use mech_core::kernel::dyad::Solver;
use mech_core::kernel::kinematics::{Con, ConKind};
use mech_core::kernel::screw::{Chain, Driven, JointScrew};
use mech_core::plan::assur::{Group, Kernel};
use proc_macro2::TokenStream;
use quote::{format_ident, quote};
use syn::Ident;

/// The group constants and the solvers.
pub(crate) fn emit(cx: &Ctx) -> TokenStream {
    let main = &cx.names.main;
    let consts = cx
        .plan
        .iter()
        .enumerate()
        .map(|(gi, g)| group_consts(cx, gi, g));
    let (solve, solve_on, velocity_field) = (solve(cx), solve_on(cx), velocity_field(cx));
    quote! {
        impl #main {
            #(#consts)*
            #solve
            #solve_on
            #velocity_field
        }
    }
}

/// The constant of group `gi` its kernel reads: the driven joint's screw, the chain of
/// joint screws of a closed form, or the bodies and constraints of a Newton group.
fn group_consts(cx: &Ctx, gi: usize, g: &Group) -> TokenStream {
    let p = &cx.p;
    let doc = format!(
        "Assur group {gi}: links {} ({:?}).",
        g.bodies
            .iter()
            .map(|&b| cx.model.links[b].name.as_str())
            .collect::<Vec<_>>()
            .join(", "),
        g.solver
    );
    let kernel = match &g.kernel {
        Kernel::Driven(d) => {
            let (kn, t) = (format_ident!("__G{}_DRIVEN", gi), driven_tokens(d));
            quote!(const #kn: #p::screw::Driven = #t;)
        }
        Kernel::Chain(c) => {
            let (kn, t) = (format_ident!("__G{}_CHAIN", gi), chain_tokens(c));
            quote!(const #kn: #p::screw::Chain = #t;)
        }
        Kernel::Mesh(m) => {
            let (kn, t) = (mesh_const(gi), mesh_tokens(m));
            quote!(const #kn: #p::gears::MeshGroup = #t;)
        }
        Kernel::Train(t) => {
            let (kn, t) = (mesh_const(gi), train_tokens(t));
            quote!(const #kn: #p::gears::TrainGroup = #t;)
        }
        Kernel::Rolling(r) => {
            let (kn, t) = (mesh_const(gi), rolling_tokens(r));
            quote!(const #kn: #p::rolling::RollingGroup = #t;)
        }
        Kernel::Cam(c) => {
            let kn = mesh_const(gi);
            let mech_core::elements::cam::CamGroup {
                follower,
                slide,
                joint,
                cam,
                carrier,
                index,
                cam_tracked,
                carrier_tracked,
            } = *c;
            quote!(const #kn: #p::cam::CamGroup = #p::cam::CamGroup { follower: #follower, slide: #slide, joint: #joint, cam: #cam, carrier: #carrier, index: #index, cam_tracked: #cam_tracked, carrier_tracked: #carrier_tracked };)
        }
        Kernel::System => {
            let (bn, cn) = system_consts(gi);
            let (nb, nc, bodies) = (g.bodies.len(), g.cons.len(), &g.bodies);
            let cons = g.cons.iter().map(con_tokens);
            let triad = g.triad.map(|t| {
                let (tn, mid) = (triad_const(gi), t.mid);
                let (links, outer, inner) = (t.links, t.outer, t.inner);
                quote!(const #tn: #p::triad::Triad = #p::triad::Triad { mid: #mid, links: [#(#links),*], outer: [#(#outer),*], inner: [#(#inner),*] };)
            });
            quote!(
                const #bn: [usize; #nb] = [#(#bodies),*];
                const #cn: [#p::kinematics::Con; #nc] = [#(#cons),*];
                #triad
            )
        }
    };
    let (sn, solver) = (solver_const(gi), solver_tokens(&g.solver));
    quote! {
        #[doc = #doc]
        const #sn: #p::dyad::Solver = #solver;
        #kernel
    }
}

/// The name of a meshing group's kernel constant.
pub(crate) fn mesh_const(gi: usize) -> Ident {
    format_ident!("__G{}_MESH", gi)
}

fn rolling_tokens(r: &mech_core::elements::rolling::RollingGroup) -> TokenStream {
    use mech_core::elements::rolling::RollingGroup;
    let p = quote!(::mech::__private::rolling::RollingGroup);
    match *r {
        RollingGroup::Driven { body, joint, input } => {
            quote!(#p::Driven { body: #body, joint: #joint, input: #input })
        }
        RollingGroup::Dyad { b1, b2, ja, jc, jr } => {
            quote!(#p::Dyad { b1: #b1, b2: #b2, ja: #ja, jc: #jc, jr: #jr })
        }
    }
}

fn train_tokens(t: &mech_core::elements::gears::TrainGroup) -> TokenStream {
    let (n, bodies, pins, order, tracked) = (t.n, t.bodies, t.pins, t.order, t.tracked);
    let (outer, pin_b) = (t.outer, t.pin_b);
    let meshes = t.meshes.iter().map(|&(j, m)| quote!((#j, #m)));
    let ends = t.ends.iter().map(|[a, b, c]| quote!([#a, #b, #c]));
    quote!(::mech::__private::gears::TrainGroup {
        n: #n, bodies: [#(#bodies),*], pins: [#(#pins),*], meshes: [#(#meshes),*], order: [#(#order),*], tracked: #tracked,
        outer: [#(#outer),*], pin_b: [#(#pin_b),*], ends: [#(#ends),*],
    })
}

fn mesh_tokens(m: &mech_core::elements::gears::MeshGroup) -> TokenStream {
    let mech_core::elements::gears::MeshGroup {
        body,
        pin,
        joint,
        mesh,
        partner,
        carrier,
        slide,
        body_slides,
        partner_slides,
        partner_tracked,
        carrier_tracked,
    } = *m;
    quote!(::mech::__private::gears::MeshGroup { body: #body, pin: #pin, joint: #joint, mesh: #mesh, partner: #partner, carrier: #carrier, slide: #slide, body_slides: #body_slides, partner_slides: #partner_slides, partner_tracked: #partner_tracked, carrier_tracked: #carrier_tracked })
}

/// The name of group `gi`'s position solver constant.
pub(crate) fn solver_const(gi: usize) -> Ident {
    format_ident!("__G{}_SOLVER", gi)
}

/// The names of a Newton group's bodies and constraints constants.
pub(crate) fn system_consts(gi: usize) -> (Ident, Ident) {
    (
        format_ident!("__G{}_BODIES", gi),
        format_ident!("__G{}_CONS", gi),
    )
}

/// The name of a triad's constant ([`mech_core::kernel::triad::Triad`]).
fn triad_const(gi: usize) -> Ident {
    format_ident!("__G{}_TRIAD", gi)
}

/// The position solver constant of every group, in plan order (`from_params` reads the
/// drawing's branch of each).
pub(crate) fn solvers(cx: &Ctx) -> Vec<TokenStream> {
    (0..cx.n_groups)
        .map(|gi| {
            let sn = solver_const(gi);
            quote!(Self::#sn)
        })
        .collect()
}

/// The solve call of group `gi`, which binds `sys{gi}` to the group's kept system (`()`
/// for a closed form).
fn solve_call(cx: &Ctx, gi: usize, g: &Group) -> TokenStream {
    let p = &cx.p;
    let (bn, cn) = system_consts(gi);
    let n = 3 * g.bodies.len();
    let solver = solver_const(gi);
    let sys = format_ident!("sys{}", gi);
    match g.kernel {
        Kernel::Driven(_) => {
            let kn = format_ident!("__G{}_DRIVEN", gi);
            quote!(#p::kinematics::solve_driven(Self::#solver, &Self::#kn, &joints, &mut s, drive, upto)?; let #sys = ();)
        }
        Kernel::Chain(_) => {
            let kn = format_ident!("__G{}_CHAIN", gi);
            let call = quote!(#p::kinematics::solve_chain(Self::#solver, &Self::#kn, &joints, &mut s, drive, branches[#gi], self.scale, upto)?);
            if keeps_system(g) {
                quote!(let #sys = #call;)
            } else {
                quote!(#call; let #sys = ();)
            }
        }
        Kernel::Mesh(_) => {
            let kn = mesh_const(gi);
            quote!(#p::gears::solve_mesh(&Self::#kn, &self.meshes, &joints, &mut s, upto)?; let #sys = ();)
        }
        Kernel::Train(_) => {
            let (kn, t) = (mesh_const(gi), cx.train_slot(gi));
            quote!(#p::gears::solve_train(&Self::#kn, &self.willis[#t], &self.meshes, &joints, &mut s, upto)?; let #sys = ();)
        }
        Kernel::Rolling(_) => {
            let kn = mesh_const(gi);
            quote!(#p::rolling::solve_rolling(&Self::#kn, &joints, &mut s, drive, branches[#gi], self.scale, upto, true)?; let #sys = ();)
        }
        Kernel::Cam(_) => {
            let kn = mesh_const(gi);
            quote!(let #sys = #p::cam::solve_cam(&Self::#kn, &self.cams, &joints, &mut s, upto)?;)
        }
        Kernel::System if g.redundant() => {
            let m = g.rows();
            quote!(let #sys = #p::group::group_solve_ls::<#n, #m>(&Self::#bn, &Self::#cn, &joints, &mut s, drive, self.scale, upto)?;)
        }
        Kernel::System if g.triad.is_some() => {
            let tn = triad_const(gi);
            quote!(let #sys = #p::triad::triad_solve::<#n>(&Self::#tn, &Self::#bn, &Self::#cn, &joints, &mut s, drive, self.scale, upto, &self.drawing, None)?;)
        }
        Kernel::System => {
            quote!(let #sys = #p::group::group_solve::<#n>(&Self::#bn, &Self::#cn, &joints, &mut s, drive, self.scale, upto)?;)
        }
    }
}

/// `[self.joints[k].with_links(a, b, at_anchor), ..]`: the joints with their links and
/// their zero local vectors as literal constants, so that the kernels' tests on the
/// topology fold.
pub(crate) fn joints_with_topology(cx: &Ctx) -> TokenStream {
    let items = cx.model.joints.iter().enumerate().map(|(k, j)| {
        let (a, b) = (j.a, j.b);
        let [za, zb] = cx.model.at_anchor(k);
        quote!(self.joints[#k].with_links(#a, #b, [#za, #zb]))
    });
    quote!([#(#items),*])
}

/// The velocity-field call of group `gi` (positions known, velocities of the inputs'
/// rates `drive`), into the states `v`.
fn velocity_call(cx: &Ctx, gi: usize, g: &Group) -> TokenStream {
    let p = &cx.p;
    let (bn, cn) = system_consts(gi);
    let n = 3 * g.bodies.len();
    let idx = syn::Index::from(gi);
    let level = quote!(#p::kinematics::Level::Velocity);
    match g.kernel {
        Kernel::Driven(_) => {
            let kn = format_ident!("__G{}_DRIVEN", gi);
            quote!(#p::screw::driven_rates(&Self::#kn, &joints, &mut v, drive, #level)?;)
        }
        Kernel::Chain(_) => {
            let kn = format_ident!("__G{}_CHAIN", gi);
            quote!(#p::screw::chain_rates(&Self::#kn, &joints, &mut v, self.scale, #level)?;)
        }
        Kernel::Mesh(_) => {
            let kn = mesh_const(gi);
            quote!(#p::gears::solve_mesh(&Self::#kn, &self.meshes, &joints, &mut v, #level)?;)
        }
        Kernel::Train(_) => {
            let (kn, t) = (mesh_const(gi), cx.train_slot(gi));
            quote!(#p::gears::solve_train(&Self::#kn, &self.willis[#t], &self.meshes, &joints, &mut v, #level)?;)
        }
        Kernel::Rolling(_) => {
            let kn = mesh_const(gi);
            quote!(#p::rolling::solve_rolling(&Self::#kn, &joints, &mut v, drive, 1.0, self.scale, #level, false)?;)
        }
        Kernel::Cam(_) => {
            let kn = mesh_const(gi);
            quote!(#p::cam::solve_cam(&Self::#kn, &self.cams, &joints, &mut v, #level)?;)
        }
        Kernel::System if g.redundant() => {
            let m = g.rows();
            quote!(#p::group::group_velocity_field::<#n, #p::group::LsSystem<#n, #m>>(m.systems.#idx.as_ref(), &Self::#bn, &Self::#cn, &joints, &mut v, drive, self.scale)?;)
        }
        Kernel::System => {
            quote!(#p::group::group_velocity_field::<#n, #p::group::GroupSystem<#n>>(m.systems.#idx.as_ref(), &Self::#bn, &Self::#cn, &joints, &mut v, drive, self.scale)?;)
        }
    }
}

/// The type of what group `g` keeps in the motion for the reactions and velocity fields:
/// its factored system (Newton groups), a dyad's 2×2 system (closed-form chains), a cam
/// group's law values at the cam's turn (`mech_core::elements::cam::CamLaw`), nothing for
/// the others.
fn system_type(cx: &Ctx, g: &Group) -> TokenStream {
    let p = &cx.p;
    let n = 3 * g.bodies.len();
    if keeps_system(g) {
        quote!(#p::kinematics::DyadSystem)
    } else if let Kernel::Cam(_) = g.kernel {
        quote!(#p::cam::CamLaw)
    } else if let Kernel::Chain(_) = g.kernel {
        quote!(())
    } else if g.kernel != Kernel::System {
        quote!(())
    } else if g.redundant() {
        let m = g.rows();
        quote!(Option<#p::group::LsSystem<#n, #m>>)
    } else {
        quote!(Option<#p::group::GroupSystem<#n>>)
    }
}

/// Whether closed-form group `g` keeps its 2×2 system in the motion (`DyadSystem`): the
/// RRR, RRP and RPR dyads, solved in natural coordinates; the other closed forms keep
/// nothing (their reactions are given `DyadSystem::None`), so the motion does not carry it.
pub(crate) fn keeps_system(g: &Group) -> bool {
    matches!(g.kernel, Kernel::Chain(_))
        && matches!(
            g.solver,
            Solver::Rrr { .. } | Solver::Rrp { .. } | Solver::Rpr { .. }
        )
}

/// The tuple of every group's [`system_type`] (the `systems` field of the motion).
pub(crate) fn systems_type(cx: &Ctx) -> TokenStream {
    nest(cx.plan.iter().map(|g| system_type(cx, g)).collect())
}

/// Tuples longer than 12 have no `Debug` or `PartialEq`: more groups than that are kept
/// as a tuple of tuples of at most 12.
const TUPLE: usize = 12;

/// The tuple of `items`, nested in tuples of at most [`TUPLE`] when longer.
fn nest(items: Vec<TokenStream>) -> TokenStream {
    if items.len() <= TUPLE {
        return quote!((#(#items,)*));
    }
    let chunks = items.chunks(TUPLE).map(|c| quote!((#(#c,)*)));
    quote!((#(#chunks,)*))
}

/// The field path of group `g`'s system in the (possibly nested) tuple: `.3` or `.1.3`.
pub(crate) fn system_path(cx: &Ctx, g: usize) -> TokenStream {
    if cx.n_groups <= TUPLE {
        let i = syn::Index::from(g);
        quote!(.#i)
    } else {
        let (a, b) = (syn::Index::from(g / TUPLE), syn::Index::from(g % TUPLE));
        quote!(.#a.#b)
    }
}

/// `__solve`: the states (and kept systems) at the inputs, on the drawing's branches;
/// with redundant constraints, other branches past a change point.
fn solve(cx: &Ctx) -> TokenStream {
    let Ctx {
        p, n_links, dof, ..
    } = cx;
    let systems = systems_type(cx);
    // With redundant constraints the closed forms' drawing branches may be the wrong ones
    // past a change point (a parallelogram folding): the redundant group then finds its
    // equations inconsistent, and the other branches are tried.
    let body = if cx.plan.iter().any(|g| g.redundant()) {
        quote!(#p::branches::search(&self.branches, |b| self.__solve_on(b, q, qd, qdd, upto, check)))
    } else {
        quote!(self.__solve_on(&self.branches, q, qd, qdd, upto, check))
    };
    quote! {
        /// Every group solved up to `upto`; with `check`, the states checked finite
        /// (`magnitudes::finite_states`). Zhukovski's route checks its sums instead.
        #[inline(always)]
        fn __solve(
            &self,
            q: &[f64; #dof],
            qd: &[f64; #dof],
            qdd: &[f64; #dof],
            upto: #p::kinematics::Level,
            check: bool,
        ) -> Result<([#p::kinematics::LinkState; #n_links], #systems), #p::MechError> {
            #body
        }
    }
}

/// `__solve_on`: every group's solve call in plan order, on the given branch signs.
fn solve_on(cx: &Ctx) -> TokenStream {
    let Ctx {
        p,
        n_links,
        n_groups,
        dof,
        ..
    } = cx;
    let systems = systems_type(cx);
    let calls = cx
        .plan
        .iter()
        .enumerate()
        .map(|(gi, g)| solve_call(cx, gi, g));
    let joints = joints_with_topology(cx);
    let n_joints = cx.n_joints;
    let systems_value = nest(
        (0..cx.n_groups)
            .map(|g| {
                let id = format_ident!("sys{}", g);
                quote!(#id)
            })
            .collect(),
    );
    // Newton starts from the drawing; closed forms and triads (which read the drawing
    // from `self.drawing`) overwrite every state they use.
    let initial = if cx
        .plan
        .iter()
        .any(|g| g.kernel == Kernel::System && g.triad.is_none())
    {
        quote!(self.drawing)
    } else {
        quote!([#p::kinematics::LinkState::default(); #n_links])
    };
    quote! {
        /// The joints with their links as literal constants (`JointGeom::with_links`).
        #[inline(always)]
        fn __joints(&self) -> [#p::kinematics::JointGeom; #n_joints] {
            #joints
        }
        /// [`Self::__solve`] on the given branch signs.
        #[inline(always)]
        fn __solve_on(
            &self,
            branches: &[f64; #n_groups],
            q: &[f64; #dof],
            qd: &[f64; #dof],
            qdd: &[f64; #dof],
            upto: #p::kinematics::Level,
            check: bool,
        ) -> Result<([#p::kinematics::LinkState; #n_links], #systems), #p::MechError> {
            let mut s = #initial;
            let joints = self.__joints();
            let drive = (&q[..], &qd[..], &qdd[..]);
            #(#calls)*
            if check {
                #p::magnitudes::finite_states(&s, upto)?;
            }
            Ok((s, #systems_value))
        }
    }
}

/// `__velocity_field`: the velocities of input rates `qd` at the motion's positions.
fn velocity_field(cx: &Ctx) -> TokenStream {
    let Ctx {
        p, n_links, dof, ..
    } = cx;
    let motion = &cx.names.motion;
    let calls = cx
        .plan
        .iter()
        .enumerate()
        .map(|(gi, g)| velocity_call(cx, gi, g));
    quote! {
        #[inline(always)]
        fn __velocity_field(
            &self,
            m: &#motion,
            qd: &[f64; #dof],
        ) -> Result<[#p::kinematics::LinkState; #n_links], #p::MechError> {
            let mut v = m.__states();
            for st in v.iter_mut() {
                st.vel = #p::Vector2::zeros();
                st.omega = 0.0;
            }
            let zero = [0.0; #dof];
            let drive = (&zero[..], &qd[..], &zero[..]);
            let joints = self.__joints();
            #(#calls)*
            Ok(v)
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
        ConKind::Mesh => quote!(Mesh),
        ConKind::Rolling => quote!(Rolling),
    };
    quote!(::mech::__private::kinematics::Con { joint: #j, kind: ::mech::__private::kinematics::ConKind::#kind })
}

fn solver_tokens(s: &Solver) -> TokenStream {
    let p = quote!(::mech::__private::dyad::Solver);
    match *s {
        Solver::DrivenRevolute { body, joint, input } => {
            quote!(#p::DrivenRevolute { body: #body, joint: #joint, input: #input })
        }
        Solver::DrivenPrismatic { body, joint, input } => {
            quote!(#p::DrivenPrismatic { body: #body, joint: #joint, input: #input })
        }
        Solver::Rrr { b1, b2, ja, jc, jb } => {
            quote!(#p::Rrr { b1: #b1, b2: #b2, ja: #ja, jc: #jc, jb: #jb })
        }
        Solver::Rrp { b1, b2, ja, jc, jp } => {
            quote!(#p::Rrp { b1: #b1, b2: #b2, ja: #ja, jc: #jc, jp: #jp })
        }
        Solver::Rpr { b1, b2, ja, jp, jb } => {
            quote!(#p::Rpr { b1: #b1, b2: #b2, ja: #ja, jp: #jp, jb: #jb })
        }
        Solver::Prp {
            b1,
            b2,
            jp1,
            jc,
            jp2,
        } => quote!(#p::Prp { b1: #b1, b2: #b2, jp1: #jp1, jc: #jc, jp2: #jp2 }),
        Solver::Rpp { b1, b2, ja, jp, jq } => {
            quote!(#p::Rpp { b1: #b1, b2: #b2, ja: #ja, jp: #jp, jq: #jq })
        }
        Solver::PinInFixedSlot { body, ja, js } => {
            quote!(#p::PinInFixedSlot { body: #body, ja: #ja, js: #js })
        }
        Solver::SlottedLever { body, ja, js } => {
            quote!(#p::SlottedLever { body: #body, ja: #ja, js: #js })
        }
        Solver::SlottedSlider { body, jq, js } => {
            quote!(#p::SlottedSlider { body: #body, jq: #jq, js: #js })
        }
        Solver::Mesh { body, joint } => quote!(#p::Mesh { body: #body, joint: #joint }),
        Solver::Train => quote!(#p::Train),
        Solver::DrivenRolling { body, joint, input } => {
            quote!(#p::DrivenRolling { body: #body, joint: #joint, input: #input })
        }
        Solver::Cam { body, joint } => quote!(#p::Cam { body: #body, joint: #joint }),
        Solver::Rrl { b1, b2, ja, jc, jr } => {
            quote!(#p::Rrl { b1: #b1, b2: #b2, ja: #ja, jc: #jc, jr: #jr })
        }
        Solver::Newton => quote!(#p::Newton),
    }
}

fn screw_tokens(s: &JointScrew) -> TokenStream {
    let (j, slide) = (s.joint, s.slide);
    quote!(::mech::__private::screw::JointScrew { joint: #j, slide: #slide })
}

fn link_tokens(l: usize) -> TokenStream {
    if l == mech_core::kernel::screw::VIRTUAL {
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
    let (from, body, input, pinned, track) = (d.from, d.body, d.input, d.pinned, d.track);
    let screw = screw_tokens(&d.screw);
    quote!(::mech::__private::screw::Driven { from: #from, body: #body, screw: #screw, input: #input, pinned: #pinned, track: #track })
}
