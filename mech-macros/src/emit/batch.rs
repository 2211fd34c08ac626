//! Many configurations per call: `pose_many`, `points_many`, `driver_action_many` and, with
//! one input, `reduced_many` and `acceleration_many`, each a loop of mech-core's batch
//! runner (`mech::__private::batch::each`) over the one-configuration solver; the `NAN`
//! constant of the pose; `__points`, the points alone.

use super::results::{owners, Owner};
use super::Ctx;
use proc_macro2::TokenStream;
use quote::quote;

/// The batched methods and what they need.
pub(crate) fn emit(cx: &Ctx) -> TokenStream {
    let main = &cx.names.main;
    let nan = pose_nan(cx);
    let (points, many) = (points_fn(cx), many_fns(cx));
    let one_dof = if cx.one_dof() {
        one_dof_many_fns(cx)
    } else {
        quote!()
    };
    quote! {
        #nan
        impl #main {
            #points
            #many
            #one_dof
        }
    }
}

/// `Pose::NAN` and the batch runner's `Nan` for it: the value of a failed configuration.
fn pose_nan(cx: &Ctx) -> TokenStream {
    let p = &cx.p;
    let n = &cx.names;
    let (pose, pose_links, pose_points) = (&n.pose, &n.pose_links, &n.pose_points);
    let moving = cx.moving_ids();
    let points = &cx.point_ids;
    quote! {
        impl #pose {
            /// NaN in every number: what `pose_many` writes for a configuration that fails
            /// (`vec![Self::NAN; n]` is an output buffer).
            pub const NAN: Self = #pose {
                links: #pose_links { #(#moving: #p::kinematics::LinkPose { angle: f64::NAN, cg: #p::batch::NAN2 },)* },
                points: #pose_points { #(#points: #p::kinematics::PointPose { pos: #p::batch::NAN2 },)* },
            };
        }
        impl #p::batch::Nan for #pose {
            fn set_nan(&mut self) {
                *self = Self::NAN;
            }
        }
    }
}

/// `__points`: the points alone (x, y of each, declaration order) into `out`, no link angle
/// or cg computed.
fn points_fn(cx: &Ctx) -> TokenStream {
    let Ctx { p, q_ty, dof, .. } = cx;
    let np2 = 2 * cx.n_points;
    let writes = owners(cx).into_iter().enumerate().map(|(pt, o)| {
        let (x, y) = (2 * pt, 2 * pt + 1);
        let pos = match o {
            Owner::Anchor(l) => quote!(s[#l].pos),
            Owner::Local(l) => quote!(#p::kinematics::point_pose(&s, #l, self.points[#pt]).pos),
        };
        quote!({ let v = #pos; out[#x] = v.x; out[#y] = v.y; })
    });
    let q_arr = super::results::to_array(cx, "q");
    quote! {
        /// The points alone at q: x and y (m) of each point in declaration order into
        /// `out` (2 × points values), no link angle or cg computed.
        #[inline(always)]
        fn __points(&self, q: #q_ty, out: &mut [f64]) -> Result<(), #p::MechError> {
            #q_arr
            let zero = [0.0; #dof];
            let (s, _) = self
                .__solve(&q, &zero, &zero, #p::kinematics::Level::Position, false)
                .map_err(|e| #p::error::blame("q", &q, e))?;
            let out: &mut [f64; #np2] = out.try_into().map_err(|_| #p::MechError::Internal("points row".into()))?;
            #(#writes)*
            #p::magnitudes::finite_result("point positions", out)
        }
    }
}

/// `pose_many`, `points_many`, `driver_action_many`.
fn many_fns(cx: &Ctx) -> TokenStream {
    let Ctx { p, q_ty, dof, .. } = cx;
    let n = &cx.names;
    let (pose, loads) = (&n.pose, &n.loads);
    let np2 = 2 * cx.n_points;
    let store = if cx.one_dof() {
        quote!(*r.at(i) = d;)
    } else {
        quote!(r.row(i).copy_from_slice(&d);)
    };
    let b = quote!(#p::batch);
    quote! {
        /// `pose` at every configuration of `q` into `out` (one pose each; `vec![Pose::NAN;
        /// q.len()]` is a buffer). A configuration that fails gets `Pose::NAN` and its index
        /// in the returned `BatchErrors`; the others are unaffected. On the calling thread
        /// below `mech::batch::PARALLEL_FROM` configurations, on rayon's pool above.
        pub fn pose_many(&self, q: &[#q_ty], out: &mut [#pose]) -> #b::BatchErrors {
            let rows = match #b::Block::new("out", out, 1, q.len()) {
                Ok(r) => r,
                Err(e) => return #b::refuse(e),
            };
            #b::each(q.len(), rows, |i, r| {
                *r.at(i) = self.pose(q[i])?;
                Ok(())
            })
        }

        /// The points at every configuration of `q` into `out`: x and y (m) of each point
        /// in declaration order, configuration after configuration (`2 × POINT_NAMES.len()`
        /// values per configuration). A configuration that fails gets NaN and its index in the returned
        /// `BatchErrors`.
        pub fn points_many(&self, q: &[#q_ty], out: &mut [f64]) -> #b::BatchErrors {
            let rows = match #b::Block::new("out", out, #np2, q.len()) {
                Ok(r) => r,
                Err(e) => return #b::refuse(e),
            };
            #b::each(q.len(), rows, |i, r| self.__points(q[i], r.row(i)))
        }

        /// `driver_action` (virtual power) at every configuration (q, q̇, q̈) with the same
        /// loads into `out` (G values per configuration: N·m or N). A configuration that
        /// fails gets NaN and its index in the returned `BatchErrors`.
        pub fn driver_action_many(&self, q: &[#q_ty], qd: &[#q_ty], qdd: &[#q_ty], loads: &#loads, out: &mut [f64]) -> #b::BatchErrors {
            let rows = match #b::same_len(&[("qd", qd.len()), ("qdd", qdd.len())], q.len())
                .and_then(|()| #b::Block::new("out", out, #dof, q.len()))
            {
                Ok(r) => r,
                Err(e) => return #b::refuse(e),
            };
            #b::each(q.len(), rows, |i, r| {
                let m = self.kinematics(q[i], qd[i], qdd[i])?;
                let d = self.driver_action(&m, loads)?;
                #store
                Ok(())
            })
        }
    }
}

/// `reduced_many` and `acceleration_many` (one input).
fn one_dof_many_fns(cx: &Ctx) -> TokenStream {
    let p = &cx.p;
    let loads = &cx.names.loads;
    let b = quote!(#p::batch);
    quote! {
        /// Zhukovski's I* (kg·m²) and dI*/dq (kg·m²/rad) at every q into `inertia` and
        /// `derivative` (one value each per configuration). A configuration that fails gets
        /// NaN in both and its index in the returned `BatchErrors`.
        pub fn reduced_many(&self, q: &[f64], inertia: &mut [f64], derivative: &mut [f64]) -> #b::BatchErrors {
            let rows = match #b::Block::new("inertia", inertia, 1, q.len())
                .and_then(|a| Ok((a, #b::Block::new("derivative", derivative, 1, q.len())?)))
            {
                Ok(r) => r,
                Err(e) => return #b::refuse(e),
            };
            #b::each(q.len(), rows, |i, (a, d)| {
                let red = self.reduced(q[i])?;
                *a.at(i) = red.inertia;
                *d.at(i) = red.inertia_derivative;
                Ok(())
            })
        }

        /// The direct problem's q̈ (rad/s²) at every (q, q̇, driver) with the same loads into
        /// `out`, as `acceleration`. A configuration that fails gets NaN and its index in
        /// the returned `BatchErrors`.
        pub fn acceleration_many(&self, q: &[f64], qd: &[f64], driver: &[f64], loads: &#loads, out: &mut [f64]) -> #b::BatchErrors {
            let rows = match #b::same_len(&[("qd", qd.len()), ("driver", driver.len())], q.len())
                .and_then(|()| #b::Block::new("out", out, 1, q.len()))
            {
                Ok(r) => r,
                Err(e) => return #b::refuse(e),
            };
            #b::each(q.len(), rows, |i, r| {
                *r.at(i) = self.acceleration(q[i], qd[i], driver[i], loads)?;
                Ok(())
            })
        }
    }
}
