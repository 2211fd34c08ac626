//! A spatial mechanism's `Pose` and `Motion` (one field per moving link and per point),
//! `pose` and `kinematics`: the solver's bodies (on the mechanism's stack frame) copied into
//! them, each point moved with its body from a constant offset.

use super::{vec3, Ctx};
use crate::emit::id;
use proc_macro2::TokenStream;
use quote::quote;
use syn::Ident;

/// The points: (field identifier, its body, its offset from the body's reference point).
fn points(c: &Ctx) -> Vec<(Ident, usize, TokenStream)> {
    c.model
        .points
        .iter()
        .enumerate()
        .filter_map(|(p, (name, _))| {
            let (b, offset) = c.mech.point_anchor(p)?;
            Some((id(name), b, vec3(&offset)))
        })
        .collect()
}

pub(super) fn emit(c: &Ctx) -> TokenStream {
    let Ctx {
        main,
        s,
        p,
        q_ty,
        dof,
        ..
    } = c;
    let (pose, pose_links, pose_points) =
        (c.name("Pose"), c.name("PoseLinks"), c.name("PosePoints"));
    let (motion, motion_links, motion_points) = (
        c.name("Motion"),
        c.name("MotionLinks"),
        c.name("MotionPoints"),
    );
    let (bodies, link_ids): (Vec<usize>, Vec<Ident>) = c.links().into_iter().unzip();
    let pts = points(c);
    let point_ids: Vec<&Ident> = pts.iter().map(|(i, _, _)| i).collect();
    let point_at: Vec<TokenStream> = pts
        .iter()
        .map(|(_, b, offset)| quote!(m[#b].point(#offset)))
        .collect();
    let n = c.model.bodies.len();
    let all = 0..n;
    let q = id("q");
    let (qa, qda, qdda) = (
        c.to_array(&q),
        c.to_array(&id("qd")),
        c.to_array(&id("qdd")),
    );
    quote! {
        /// Pose of every moving link.
        #[allow(non_snake_case)]
        #[derive(Clone, Copy, Debug, PartialEq)]
        pub struct #pose_links {
            #(pub #link_ids: #s::LinkPose,)*
        }
        /// Position of every point.
        #[allow(non_snake_case)]
        #[derive(Clone, Copy, Debug, PartialEq)]
        pub struct #pose_points {
            #(pub #point_ids: #s::PointPose,)*
        }
        /// Result of `pose`: positions only.
        #[derive(Clone, Copy, Debug, PartialEq)]
        pub struct #pose {
            /// Links: rotation from the drawing, cg (m).
            pub links: #pose_links,
            /// Points: pos (m).
            pub points: #pose_points,
        }
        /// Motion of every moving link.
        #[allow(non_snake_case)]
        #[derive(Clone, Copy, Debug, PartialEq)]
        pub struct #motion_links {
            #(pub #link_ids: #s::LinkMotion,)*
        }
        /// Motion of every point.
        #[allow(non_snake_case)]
        #[derive(Clone, Copy, Debug, PartialEq)]
        pub struct #motion_points {
            #(pub #point_ids: #s::PointMotion,)*
        }
        /// Result of `kinematics`: positions, velocities, accelerations.
        #[derive(Clone, Copy, Debug, PartialEq)]
        pub struct #motion {
            /// Links: rotation, omega, alpha (rad/s, rad/s²), cg, cg_velocity, cg_acceleration.
            pub links: #motion_links,
            /// Points: pos, vel, acc.
            pub points: #motion_points,
            q: [f64; #dof],
            qd: [f64; #dof],
            qdd: [f64; #dof],
            bodies: [#s::BodyMotion; #n],
        }

        impl #main {
            /// Position analysis: every link's rotation and cg, every point's position
            /// (Newton in absolute coordinates, continued from the drawing to q).
            pub fn pose(&self, q: #q_ty) -> Result<#pose, #p::MechError> {
                use #s::{LinkMotion, LinkPose, PointPose, Vector3};
                let m = self.__solver()?.pose(&#qa)?;
                Ok(#pose {
                    links: #pose_links {
                        #(#link_ids: LinkPose::from(LinkMotion::from(&m[#bodies])),)*
                    },
                    points: #pose_points {
                        #(#point_ids: PointPose { pos: #point_at[0] },)*
                    },
                })
            }

            /// Positions, velocities and accelerations at (q, q̇, q̈): positions as in `pose`,
            /// rates by linear solves of the constraint Jacobian.
            pub fn kinematics(&self, q: #q_ty, qd: #q_ty, qdd: #q_ty) -> Result<#motion, #p::MechError> {
                self.__kinematics(#qa, #qda, #qdda)
            }

            fn __kinematics(
                &self,
                q: [f64; #dof],
                qd: [f64; #dof],
                qdd: [f64; #dof],
            ) -> Result<#motion, #p::MechError> {
                use #s::{LinkMotion, PointMotion, Vector3};
                let m = self.__solver()?.kinematics(&q, &qd, &qdd)?;
                Ok(#motion {
                    links: #motion_links {
                        #(#link_ids: LinkMotion::from(&m[#bodies]),)*
                    },
                    points: #motion_points {
                        #(#point_ids: PointMotion::from(#point_at),)*
                    },
                    q,
                    qd,
                    qdd,
                    bodies: [#(m[#all]),*],
                })
            }
        }
    }
}
