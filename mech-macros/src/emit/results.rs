//! The results of the kinematics: `<Name>Pose` and `<Name>Motion` with their by-name
//! accessors, and the methods that make them, `pose` and `kinematics`.

use super::{plan, Ctx};
use mech_core::kernel::dyad::Solver;
use mech_core::model::PointOwner;
use mech_core::plan::assur::Kernel;
use mech_core::plan::rotation::AngleRule as Angle;
use proc_macro2::TokenStream;
use quote::{format_ident, quote};
use syn::Ident;

/// The result types and `pose`, `kinematics`.
pub(crate) fn emit(cx: &Ctx) -> TokenStream {
    let n = &cx.names;
    let (types, pose_by_name, motion_by_name) = (
        types(cx),
        by_name(cx, &n.pose, "pose"),
        by_name(cx, &n.motion, "motion"),
    );
    let (pose_fn, kinematics_fn) = (pose_fn(cx), kinematics_fn(cx));
    let main = &n.main;
    quote! {
        #types
        #pose_by_name
        #motion_by_name
        impl #main {
            #pose_fn
            #kinematics_fn
        }
    }
}

/// `Pose`, `Motion` and their per-link and per-point structs.
fn types(cx: &Ctx) -> TokenStream {
    let Ctx {
        p, dof, point_ids, ..
    } = cx;
    let n = &cx.names;
    let (pose, pose_links, pose_points) = (&n.pose, &n.pose_links, &n.pose_points);
    let (motion, motion_links, motion_points) = (&n.motion, &n.motion_links, &n.motion_points);
    let moving_ids = cx.moving_ids();
    let (n_rots, n_angles) = (kept_rotations(cx).len(), kept_angles(cx).len());
    let systems = plan::systems_type(cx);
    let states = states_fn(cx);
    quote! {
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
            rots: [#p::Vector2<f64>; #n_rots],
            angles: [f64; #n_angles],
            qd: [f64; #dof],
            systems: #systems,
        }
        #states
    }
}

/// `Motion::__states`: the link states the motion was computed from, rebuilt from what it
/// publishes (each link's anchor is its first point: its position, velocity and
/// acceleration are that point's; ω and α the link's) and the rotations and angles it
/// keeps. The motion is thus no larger than its results and two small arrays.
fn states_fn(cx: &Ctx) -> TokenStream {
    let Ctx {
        p,
        n_links,
        point_ids,
        ..
    } = cx;
    let motion = &cx.names.motion;
    let (rots, angles) = (kept_rotations(cx), kept_angles(cx));
    let states = (1..cx.n_links).map(|l| {
        let lid = &cx.link_ids[l];
        let anchor = &point_ids[cx.model.links[l].points[0]];
        let rot = match rotation_of(cx, l) {
            Rotation::Identity => quote!(#p::Vector2::new(1.0, 0.0)),
            Rotation::Of(m) => {
                let k = rots.iter().position(|&r| r == m).unwrap_or_default();
                quote!(self.rots[#k])
            }
        };
        let angle = match angles.iter().position(|&a| a == l) {
            Some(k) => quote!(self.angles[#k]),
            None => quote!(0.0),
        };
        quote! {
            #p::kinematics::LinkState {
                pos: self.points.#anchor.pos,
                rot: #rot,
                vel: self.points.#anchor.vel,
                omega: self.links.#lid.omega,
                acc: self.points.#anchor.acc,
                alpha: self.links.#lid.alpha,
                angle: #angle,
            },
        }
    });
    quote! {
        impl #motion {
            /// The link states of the motion (ground first), rebuilt from its published
            /// points and links and its kept rotations.
            #[inline(always)]
            fn __states(&self) -> [#p::kinematics::LinkState; #n_links] {
                [#p::kinematics::LinkState::default(), #(#states)*]
            }
        }
    }
}

/// Where the motion finds a link's rotation (`Motion::__states`).
#[derive(Clone, Copy, PartialEq)]
enum Rotation {
    /// (1, 0): a link that slides on the ground, placed by a closed form.
    Identity,
    /// The rotation kept for this link (itself, or the link it turns with).
    Of(usize),
}

/// [`Rotation`] of moving link `l`: unrotated when it never turns and a closed form
/// places it (an RRP dyad's slider, a slotted slider, a driven slider, PRP and RPP
/// sliders: their rotation is copied from the ground's, (1, 0)); that of the link it
/// turns with ([`rotation_partner`]), whose rotation the kernels copy; else its own.
fn rotation_of(cx: &Ctx, l: usize) -> Rotation {
    let closed = cx.plan.iter().any(|g| {
        g.bodies.contains(&l)
            && matches!(
                g.solver,
                Solver::Rrp { .. }
                    | Solver::SlottedSlider { .. }
                    | Solver::DrivenPrismatic { .. }
                    | Solver::Prp { .. }
                    | Solver::Rpp { .. }
            )
    });
    match angle_of(cx, l) {
        Angle::Translating if closed => Rotation::Identity,
        Angle::With(m) => rotation_of(cx, m),
        _ => Rotation::Of(l),
    }
}

/// The links whose rotation the motion keeps (`rots`), each once.
fn kept_rotations(cx: &Ctx) -> Vec<usize> {
    let mut kept = Vec::new();
    for l in 1..cx.n_links {
        if let Rotation::Of(m) = rotation_of(cx, l) {
            if !kept.contains(&m) {
                kept.push(m);
            }
        }
    }
    kept
}

/// The links whose rotation counted over turns (`LinkState::angle`) the motion keeps
/// (`angles`): every moving link when a kernel reads it (gears, cams, rolling, a driven
/// link that tracks its turns), none otherwise (the states then carry 0).
fn kept_angles(cx: &Ctx) -> Vec<usize> {
    let read = cx.plan.iter().any(|g| match g.kernel {
        Kernel::Mesh(_) | Kernel::Train(_) | Kernel::Cam(_) | Kernel::Rolling(_) => true,
        Kernel::Driven(d) => d.track,
        _ => false,
    });
    if read {
        (1..cx.n_links).collect()
    } else {
        vec![]
    }
}

/// `link(name)` and `point(name)` of the result type `ty` (`what`: pose or motion).
fn by_name(cx: &Ctx, ty: &Ident, what: &str) -> TokenStream {
    let p = &cx.p;
    let (link_ty, point_ty) = match what {
        "pose" => (
            quote!(#p::kinematics::LinkPose),
            quote!(#p::kinematics::PointPose),
        ),
        _ => (
            quote!(#p::kinematics::LinkMotion),
            quote!(#p::kinematics::PointMotion),
        ),
    };
    let link_names = cx.model.links[1..].iter().map(|l| l.name.as_str());
    let point_names = cx.model.points.iter().map(|pt| pt.name.as_str());
    let (moving_ids, point_ids) = (cx.moving_ids(), &cx.point_ids);
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
}

/// How each point is placed: by the ground if it is a ground point (at rest); else as the
/// anchor of the moving link whose first point it is (that link's state itself, nothing
/// rotated); else by the first link that carries it.
#[derive(Clone, Copy)]
pub(crate) enum Owner {
    /// The material point of this link at the point's local vector.
    Local(usize),
    /// This link's anchor.
    Anchor(usize),
}

pub(crate) fn owners(cx: &Ctx) -> Vec<Owner> {
    (0..cx.n_points)
        .map(|pt| match cx.model.point_owner(pt) {
            PointOwner::Ground => Owner::Local(0),
            PointOwner::Anchor(l) => Owner::Anchor(l),
            PointOwner::Local(l) => Owner::Local(l),
        })
        .collect()
}

/// `let q = [q];` for one DOF (the solvers take arrays), nothing else.
pub(crate) fn to_array(cx: &Ctx, v: &str) -> TokenStream {
    let v = super::id(v);
    if cx.one_dof() {
        quote!(let #v = [#v];)
    } else {
        quote!()
    }
}

/// How the angle of moving link `l` is found: the rule the run-time mechanism follows too
/// ([`mech_core::plan::rotation::angle_rule`]).
fn angle_of(cx: &Ctx, l: usize) -> Angle {
    mech_core::plan::rotation::angle_rule(cx.model, cx.plan, l)
}

/// The name of the binding of link `l`'s angle.
fn angle_id(l: usize) -> Ident {
    format_ident!("angle{}", l)
}

/// `let angle{l} = ...;` for every moving link whose angle is published (all but those
/// sliding on the ground, unless another turns with them), in plan order so that a link
/// turning with another comes after it.
fn angle_lets(cx: &Ctx) -> TokenStream {
    let order = mech_core::plan::rotation::angle_order(cx.plan, cx.n_links);
    let needed = |l: usize| {
        !matches!(angle_of(cx, l), Angle::Translating)
            || (1..cx.n_links).any(|k| matches!(angle_of(cx, k), Angle::With(m) if m == l))
    };
    let lets = order.into_iter().filter(|&l| needed(l)).map(|l| {
        let a = angle_id(l);
        let value = match angle_of(cx, l) {
            Angle::Crank { input, sign, zero } => crank_angle(cx, input, sign, zero),
            Angle::Translating => quote!(self.links[#l].angle_ref),
            Angle::With(m) => {
                let am = angle_id(m);
                quote!(self.links[#l].angle_with(&self.links[#m], #am))
            }
            Angle::Tracked => quote!(self.links[#l].angle_tracked(&s[#l])),
            Angle::Own => quote!(self.links[#l].angle(&s[#l])),
        };
        quote!(let #a = #value;)
    });
    quote!(#(#lets)*)
}

/// `crank_angle(q[input], sign)`, or `crank_angle(q[input] + zero, sign)` for an input
/// declared `from zero`: the angle of a crank driven on the ground, no atan2.
fn crank_angle(cx: &Ctx, input: usize, sign: f64, zero: Option<f64>) -> TokenStream {
    let p = &cx.p;
    let sign = crate::emit::f64s(sign);
    match zero {
        None => quote!(#p::kinematics::crank_angle(q[#input], #sign)),
        Some(z) => {
            let z = crate::emit::f64s(z);
            quote!(#p::kinematics::crank_angle(q[#input] + #z, #sign))
        }
    }
}

/// `pose`: positions only.
fn pose_fn(cx: &Ctx) -> TokenStream {
    let Ctx {
        p,
        q_ty,
        dof,
        point_ids,
        ..
    } = cx;
    let n = &cx.names;
    let (pose, pose_links, pose_points) = (&n.pose, &n.pose_links, &n.pose_points);
    let owners = owners(cx);
    let angles = angle_lets(cx);
    let links = (1..cx.n_links).map(|l| {
        let lid = &cx.link_ids[l];
        match angle_of(cx, l) {
            Angle::Translating => quote!(#lid: self.links[#l].pose_translating(&s[#l]),),
            _ => {
                let a = angle_id(l);
                quote!(#lid: self.links[#l].pose_at(&s[#l], #a),)
            }
        }
    });
    let points = (0..cx.n_points).map(|pt| {
        let pid = &point_ids[pt];
        match owners[pt] {
            Owner::Anchor(l) => quote!(#pid: #p::kinematics::anchor_pose(&s[#l]),),
            Owner::Local(o) => quote!(#pid: #p::kinematics::point_pose(&s, #o, self.points[#pt]),),
        }
    });
    let q_arr = to_array(cx, "q");
    let inputs = &cx.inputs_doc;
    quote! {
        /// Position analysis: every link's angle and cg, every point's position.
        /// Computes no velocity or acceleration.
        ///
        #(#[doc = #inputs])*
        pub fn pose(&self, q: #q_ty) -> Result<#pose, #p::MechError> {
            #q_arr
            let zero = [0.0; #dof];
            let (s, _) = self
                .__solve(&q, &zero, &zero, #p::kinematics::Level::Position, true)
                .map_err(|e| #p::error::blame("q", &q, e))?;
            #angles
            Ok(#pose {
                links: #pose_links { #(#links)* },
                points: #pose_points { #(#points)* },
            })
        }
    }
}

/// `kinematics`: positions, velocities and accelerations.
fn kinematics_fn(cx: &Ctx) -> TokenStream {
    let Ctx {
        p, q_ty, point_ids, ..
    } = cx;
    let n = &cx.names;
    let (motion, motion_links, motion_points) = (&n.motion, &n.motion_links, &n.motion_points);
    let owners = owners(cx);
    let angles = angle_lets(cx);
    let links = (1..cx.n_links).map(|l| {
        let lid = &cx.link_ids[l];
        match angle_of(cx, l) {
            Angle::Translating => quote!(#lid: self.links[#l].motion_translating(&s[#l]),),
            _ => {
                let a = angle_id(l);
                quote!(#lid: self.links[#l].motion_at(&s[#l], #a),)
            }
        }
    });
    let points = (0..cx.n_points).map(|pt| {
        let pid = &point_ids[pt];
        match owners[pt] {
            Owner::Anchor(l) => quote!(#pid: #p::kinematics::anchor_motion(&s[#l]),),
            Owner::Local(o) => {
                quote!(#pid: #p::kinematics::point_motion(&s, #o, self.points[#pt]),)
            }
        }
    });
    // What derives from the states and is not one of them: a point away from its link's
    // anchor, each moving link's cg (checked finite, `magnitudes::finite_derived`).
    let derived_points: Vec<_> = (0..cx.n_points)
        .filter(|&pt| matches!(owners[pt], Owner::Local(o) if o != 0))
        .map(|pt| &point_ids[pt])
        .collect();
    let derived_links: Vec<_> = (1..cx.n_links).map(|l| &cx.link_ids[l]).collect();
    let (q_arr, qd_arr, qdd_arr) = (to_array(cx, "q"), to_array(cx, "qd"), to_array(cx, "qdd"));
    let inputs = &cx.inputs_doc;
    let (rots, turns) = (kept_rotations(cx), kept_angles(cx));
    let ks: Vec<usize> = (0..cx.dof).collect();
    quote! {
        /// Position, velocity and acceleration analysis at input (q, q̇, q̈).
        ///
        #(#[doc = #inputs])*
        pub fn kinematics(&self, q: #q_ty, qd: #q_ty, qdd: #q_ty) -> Result<#motion, #p::MechError> {
            #q_arr #qd_arr #qdd_arr
            let (s, systems) = self
                .__solve(&q, &qd, &qdd, #p::kinematics::Level::Acceleration, true)
                .map_err(|e| #p::error::blame("q, qd, qdd", &[#(q[#ks],)* #(qd[#ks],)* #(qdd[#ks],)*], e))?;
            #angles
            let m = #motion {
                links: #motion_links { #(#links)* },
                points: #motion_points { #(#points)* },
                rots: [#(s[#rots].rot,)*],
                angles: [#(s[#turns].angle,)*],
                qd,
                systems,
            };
            #p::magnitudes::finite_derived(&[#(&m.points.#derived_points,)*], &[#(&m.links.#derived_links,)*])?;
            Ok(m)
        }
    }
}
