//! Many configurations per call: `pose_many`, `points_many`, `driver_action_many` and, with
//! one input, `reduced_many` and `acceleration_many`, each a loop of mech-core's batch
//! runner (`mech::__private::batch::each`) over the one-configuration solver; the `NAN`
//! constant of the pose; `__points`, the points alone.

use super::plan::solver_const;
use super::results::{owners, Owner};
use super::Ctx;
use mech_core::plan::assur::Kernel;
use proc_macro2::TokenStream;
use quote::{format_ident, quote};

/// Whether every group has a lane kernel (`mech_core::kernel::lanes::supports`: a driven
/// crank or slider, RRR and RRP dyads) and nothing else enters the sums (no force element,
/// no redundant constraint): then `points_many`, `reduced_many` and `acceleration_many`
/// take configurations four by four (`__solve_lanes`), the other solvers one by one.
fn lanes(cx: &Ctx) -> bool {
    !cx.has_elements()
        && !cx.redundant()
        && cx.plan.iter().all(|g| {
            matches!(g.kernel, Kernel::Driven(_) | Kernel::Chain(_))
                && mech_core::kernel::lanes::supports(g.solver)
        })
}

/// `__solve_lanes`: four configurations through every group's lane kernel in plan order,
/// and the mask of the lanes the one-configuration solver must redo.
fn solve_lanes_fn(cx: &Ctx) -> TokenStream {
    let Ctx {
        p, n_links, dof, ..
    } = cx;
    let l = quote!(#p::lanes);
    let calls = cx.plan.iter().enumerate().map(|(gi, g)| {
        let solver = solver_const(gi);
        match g.kernel {
            Kernel::Driven(_) => {
                let kn = format_ident!("__G{}_DRIVEN", gi);
                quote!(mask = #l::or(mask, #l::solve_driven_lanes(Self::#solver, &Self::#kn, &joints, &mut s, q, qd, qdd, upto));)
            }
            _ => quote!(mask = #l::or(mask, #l::solve_chain_lanes(Self::#solver, &joints, &mut s, self.branches[#gi], self.scale, upto));),
        }
    });
    quote! {
        /// Four configurations at once on the lane backend `B`: every group's lane kernel
        /// in plan order (`mech::__private::lanes`), and the mask of the lanes that failed
        /// or may fail.
        #[inline(always)]
        fn __solve_lanes<B: #l::Backend>(
            &self,
            q: &[#l::L<B>; #dof],
            qd: &[#l::L<B>; #dof],
            qdd: &[#l::L<B>; #dof],
            upto: #p::kinematics::Level,
        ) -> ([#l::LinkLanes<B>; #n_links], #l::Mask) {
            let mut s = [#l::LinkLanes::<B>::default(); #n_links];
            let joints = self.__joints();
            let mut mask = #l::NONE;
            #(#calls)*
            (s, mask)
        }
    }
}

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
    let lanes = if lanes(cx) && cx.one_dof() {
        let (solve, four) = (solve_lanes_fn(cx), four_fns(cx));
        quote!(#solve #four)
    } else if lanes(cx) {
        solve_lanes_fn(cx)
    } else {
        quote!()
    };
    let tables = table_fns(cx);
    quote! {
        #nan
        impl #main {
            #points
            #lanes
            #many
            #one_dof
            #tables
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
    let points_body = if lanes(cx) && cx.one_dof() {
        points_lanes(cx)
    } else {
        quote!(#b::each(q.len(), rows, |i, r| self.__points(q[i], r.row(i))))
    };
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
            #points_body
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
    let l = quote!(#p::lanes);
    let red_one = quote!(|i, (a, d)| {
        let red = self.reduced(q[i])?;
        *a.at(i) = red.inertia;
        *d.at(i) = red.inertia_derivative;
        Ok(())
    });
    let acc_one = quote!(|i, r| {
        *r.at(i) = self.acceleration(q[i], qd[i], driver[i], loads)?;
        Ok(())
    });
    let (reduced_body, acceleration_body) = if lanes(cx) {
        (
            quote! {
                #b::each_lanes(q.len(), rows, self,
                    #[inline(always)] |copy: &Self, i, r: &mut (#b::Block<f64>, #b::Block<f64>)| copy.__reduced_four::<#l::Base>(q, i, r),
                    #[inline(always)] |copy: &Self, i, r: &mut (#b::Block<f64>, #b::Block<f64>)| copy.__reduced_four::<#l::Wide>(q, i, r),
                    #red_one)
            },
            quote! {
                let x = (q, qd, driver);
                #b::each_lanes(q.len(), rows, &(self.clone(), *loads),
                    #[inline(always)] |(copy, loads): &(Self, #loads), i, r: &mut #b::Block<f64>| copy.__acceleration_four::<#l::Base>(x, loads, i, r),
                    #[inline(always)] |(copy, loads): &(Self, #loads), i, r: &mut #b::Block<f64>| copy.__acceleration_four::<#l::Wide>(x, loads, i, r),
                    #acc_one)
            },
        )
    } else {
        (
            quote!(#b::each(q.len(), rows, #red_one)),
            quote!(#b::each(q.len(), rows, #acc_one)),
        )
    };
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
            #reduced_body
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
            #acceleration_body
        }
    }
}

/// `points_many`'s body through the lane kernels (one input): four configurations'
/// points at once (`__points_four` on both lane backends), the masked lanes and the tail by
/// `__points`.
fn points_lanes(cx: &Ctx) -> TokenStream {
    let p = &cx.p;
    let (b, l) = (quote!(#p::batch), quote!(#p::lanes));
    quote! {
        #b::each_lanes(q.len(), rows, self,
            #[inline(always)] |copy: &Self, i, r: &mut #b::Block<f64>| copy.__points_four::<#l::Base>(q, i, r),
            #[inline(always)] |copy: &Self, i, r: &mut #b::Block<f64>| copy.__points_four::<#l::Wide>(q, i, r),
            |i, r| self.__points(q[i], r.row(i)))
    }
}

/// The four-configuration bodies of `points_many`, `reduced_many` and `acceleration_many`
/// (one input, every group with a lane kernel), generic over the lane backend `B` so that
/// `each_lanes` runs them on 128-bit (`Base`) or 256-bit (`Wide`) registers.
fn four_fns(cx: &Ctx) -> TokenStream {
    let p = &cx.p;
    let (b, l) = (quote!(#p::batch), quote!(#p::lanes));
    let loads = &cx.names.loads;
    let (np, np2) = (cx.n_points, 2 * cx.n_points);
    let pts = owners(cx).into_iter().enumerate().map(|(pt, o)| match o {
        Owner::Anchor(k) => quote!([s[#k].pos.x, s[#k].pos.y]),
        Owner::Local(k) => quote!(#l::point_lanes(&s, #k, self.points[#pt])),
    });
    let (inertia, moment) = super::traits::zhukovski_terms(cx);
    let solve = quote! {
        let qv = #l::L::<B>::new([q[i], q[i + 1], q[i + 2], q[i + 3]]);
        let (s, mask) = self.__solve_lanes(&[qv], &[#l::L::splat(1.0)], &[#l::L::splat(0.0)], #p::kinematics::Level::Acceleration);
        let mut z = #l::ZhukovskiLanes::<B>::new();
        #inertia
    };
    quote! {
        /// `points_many`'s four configurations from `q[i]` on the lane backend `B`: the
        /// points of the lanes not masked into their rows, and the mask.
        #[inline(always)]
        fn __points_four<B: #l::Backend>(&self, q: &[f64], i: usize, r: &mut #b::Block<f64>) -> #l::Mask {
            let q4: [f64; #l::LANES] = q[i..i + #l::LANES].try_into().expect("four configurations");
            let zero = #l::L::splat(0.0);
            let (s, mut mask) = self.__solve_lanes(&[#l::L::<B>::new(q4)], &[zero], &[zero], #p::kinematics::Level::Position);
            let pts: [[#l::L<B>; 2]; #np] = [#(#pts),*];
            // One test for every coordinate: their sum is not finite where one is (or
            // where it overflows, a lane the scalar path then redoes).
            let mut sum = #l::L::splat(0.0);
            for xy in &pts {
                sum += xy[0] + xy[1];
            }
            mask = #l::or(mask, sum.not_finite());
            // Each point's (x, y) per configuration: pairs[j][k] for point j, lane k.
            let pairs: [[[f64; 2]; #l::LANES]; #np] = ::core::array::from_fn(|j| pts[j][0].pairs(pts[j][1]));
            if !#l::any(mask) {
                // The four rows at once, their slots known: no test per slot.
                let rows: &mut [f64; #l::LANES * #np2] = r.rows(i, #l::LANES).try_into().expect("four rows");
                for k in 0..#l::LANES {
                    for j in 0..#np {
                        let at = k * #np2 + 2 * j;
                        rows[at..at + 2].copy_from_slice(&pairs[j][k]);
                    }
                }
                return mask;
            }
            for k in 0..#l::LANES {
                if !mask[k] {
                    let row = r.row(i + k);
                    for j in 0..#np {
                        row[2 * j..2 * j + 2].copy_from_slice(&pairs[j][k]);
                    }
                }
            }
            mask
        }

        /// `reduced_many`'s four configurations from `q[i]` on the lane backend `B`.
        #[inline(always)]
        fn __reduced_four<B: #l::Backend>(&self, q: &[f64], i: usize, (a, d): &mut (#b::Block<f64>, #b::Block<f64>)) -> #l::Mask {
            #solve
            let #l::ZhukovskiLanes { inertia: ii, inertia_derivative: di, .. } = z;
            let mask = #l::or(mask, #l::or(ii.not_finite(), di.not_finite()));
            for k in 0..#l::LANES {
                if !mask[k] {
                    *a.at(i + k) = ii.0[k];
                    *d.at(i + k) = di.0[k];
                }
            }
            mask
        }

        /// `acceleration_many`'s four configurations from index `i` of (q, q̇, driver) on
        /// the lane backend `B`.
        #[inline(always)]
        fn __acceleration_four<B: #l::Backend>(&self, (q, qd, driver): (&[f64], &[f64], &[f64]), loads: &#loads, i: usize, r: &mut #b::Block<f64>) -> #l::Mask {
            #solve
            #moment
            let qdv = #l::L::new([qd[i], qd[i + 1], qd[i + 2], qd[i + 3]]);
            let dv = #l::L::new([driver[i], driver[i + 1], driver[i + 2], driver[i + 3]]);
            let (acc, failed) = #l::acceleration_lanes(&z, qdv, dv);
            let mask = #l::or(mask, failed);
            for k in 0..#l::LANES {
                if !mask[k] {
                    *r.at(i + k) = acc.0[k];
                }
            }
            mask
        }
    }
}

/// The names and units of a table's columns (`mech_core::solvers::batch::kinematics_columns`
/// or `kinetostatics_columns` on this mechanism's model).
fn columns(
    cx: &Ctx,
    of: fn(&mech_core::model::Model, &mut mech_core::solvers::batch::ColumnSink<'_>),
) -> (Vec<String>, Vec<&'static str>) {
    let (mut names, mut units) = (Vec::new(), Vec::new());
    of(cx.model, &mut |a, b, u| {
        names.push(format!("{a}{b}"));
        units.push(u);
    });
    (names, units)
}

/// `kinematics_many` and, without redundant constraints, `kinetostatics_many`: structure-of-
/// arrays tables (`mech::batch::Table`) with their column constants and constructors, each
/// configuration through the one-configuration solvers and mech-core's `put_kinematics` /
/// `put_kinetostatics`.
fn table_fns(cx: &Ctx) -> TokenStream {
    let Ctx {
        p, q_ty, point_ids, ..
    } = cx;
    let b = quote!(#p::batch);
    let loads = &cx.names.loads;
    let (kn, ku) = columns(cx, mech_core::solvers::batch::kinematics_columns);
    let moving = cx.moving_ids();
    let one = quote!(|i, r: &mut #b::Strided<'_>| {
        let m = self.kinematics(q[i], qd[i], qdd[i])?;
        #b::put_kinematics(r, i, [#(&m.points.#point_ids),*], [#(&m.links.#moving),*]);
        Ok(())
    });
    let (kinematics_body, kinematics_four) = if lanes(cx) && cx.one_dof() {
        let l = quote!(#p::lanes);
        (
            quote! {
                let x = (q, qd, qdd);
                #b::each_lanes(q.len(), rows, self,
                    #[inline(always)] |copy: &Self, i, r: &mut #b::Strided<'_>| copy.__kinematics_four::<#l::Base>(x, i, r),
                    #[inline(always)] |copy: &Self, i, r: &mut #b::Strided<'_>| copy.__kinematics_four::<#l::Wide>(x, i, r),
                    #one)
            },
            kinematics_four_fn(cx),
        )
    } else {
        (quote!(#b::each(q.len(), rows, #one)), quote!())
    };
    let kinematics = quote! {
        /// The columns of `kinematics_many`'s table, in order: every point's `<point>.x`,
        /// `.y` (m), every moving link's `<link>.angle` (rad), every point's `.vx`, `.vy`
        /// (m/s), `.ax`, `.ay` (m/s²), every moving link's `.omega` (rad/s), `.alpha`
        /// (rad/s²): the names of the `mech sweep` CSV.
        pub const KINEMATICS_COLUMNS: &'static [&'static str] = &[#(#kn),*];
        /// The SI unit of each of `KINEMATICS_COLUMNS`.
        pub const KINEMATICS_UNITS: &'static [&'static str] = &[#(#ku),*];

        /// A table for `kinematics_many` of `n` configurations (`KINEMATICS_COLUMNS`, every
        /// value NaN), made once and reused.
        pub fn kinematics_table(&self, n: usize) -> #b::Table {
            #b::Table::new(Self::KINEMATICS_COLUMNS, Self::KINEMATICS_UNITS, n)
        }

        /// `kinematics` at every configuration (q, q̇, q̈) into the table `out`
        /// (`kinematics_table(q.len())`), structure of arrays: `out.column("B.x")` holds
        /// every configuration's x of B, one after the other. A configuration that fails
        /// gets NaN in every column and its index in the returned `BatchErrors`; slices of
        /// different lengths or a table of another size or mechanism are refused, nothing
        /// written.
        pub fn kinematics_many(&self, q: &[#q_ty], qd: &[#q_ty], qdd: &[#q_ty], out: &mut #b::Table) -> #b::BatchErrors {
            let rows = match #b::same_len(&[("qd", qd.len()), ("qdd", qdd.len())], q.len()).and_then(|()| {
                out.configurations("kinematics", #b::named(Self::KINEMATICS_COLUMNS, Self::KINEMATICS_UNITS), q.len())
            }) {
                Ok(r) => r,
                Err(e) => return #b::refuse(e),
            };
            #kinematics_body
        }
        #kinematics_four
    };
    if cx.redundant() {
        return kinematics;
    }
    let (fn_, fu) = columns(cx, mech_core::solvers::batch::kinetostatics_columns);
    let joints = cx.model.joints.iter().zip(&cx.joint_ids).map(|(j, jid)| {
        if j.kind == mech_core::model::JointKind::Prismatic {
            quote!((f.joints.#jid.force, Some(f.joints.#jid.moment)))
        } else {
            quote!((f.joints.#jid.force, None))
        }
    });
    let driver = if cx.one_dof() {
        quote!(&[f.driver])
    } else {
        quote!(&f.driver)
    };
    quote! {
        #kinematics

        /// The columns of `kinetostatics_many`'s table, in order: every joint's reaction
        /// `<joint>.fx`, `.fy` (N, by its first link on its second) and, for a prismatic
        /// joint, `<joint>.moment` (N·m); then the motor actions, `driver` (one input) or
        /// `driver.<joint>` (N·m or N): the names of the `mech sweep` CSV.
        pub const KINETOSTATICS_COLUMNS: &'static [&'static str] = &[#(#fn_),*];
        /// The SI unit of each of `KINETOSTATICS_COLUMNS`.
        pub const KINETOSTATICS_UNITS: &'static [&'static str] = &[#(#fu),*];

        /// A table for `kinetostatics_many` of `n` configurations
        /// (`KINETOSTATICS_COLUMNS`, every value NaN), made once and reused.
        pub fn kinetostatics_table(&self, n: usize) -> #b::Table {
            #b::Table::new(Self::KINETOSTATICS_COLUMNS, Self::KINETOSTATICS_UNITS, n)
        }

        /// `kinetostatics` (d'Alembert) at every configuration (q, q̇, q̈) with the same
        /// loads into the table `out` (`kinetostatics_table(q.len())`), structure of
        /// arrays: every reaction and the motor actions, one column each. A configuration
        /// that fails gets NaN in every column and its index in the returned
        /// `BatchErrors`; slices of different lengths or a table of another size or
        /// mechanism are refused, nothing written.
        pub fn kinetostatics_many(&self, q: &[#q_ty], qd: &[#q_ty], qdd: &[#q_ty], loads: &#loads, out: &mut #b::Table) -> #b::BatchErrors {
            let rows = match #b::same_len(&[("qd", qd.len()), ("qdd", qdd.len())], q.len()).and_then(|()| {
                out.configurations("kinetostatics", #b::named(Self::KINETOSTATICS_COLUMNS, Self::KINETOSTATICS_UNITS), q.len())
            }) {
                Ok(r) => r,
                Err(e) => return #b::refuse(e),
            };
            #b::each(q.len(), rows, |i, r| {
                let m = self.kinematics(q[i], qd[i], qdd[i])?;
                let f = self.kinetostatics(&m, loads)?;
                #b::put_kinetostatics(r, i, [#(#joints),*], #driver);
                Ok(())
            })
        }
    }
}

/// `__kinematics_four`: `kinematics_many`'s four configurations from index `i` on the lane
/// backend `B` (one input, every group with a lane kernel): the groups' lane kernels up to
/// accelerations, every point's motion and every moving link's angle (as `kinematics`
/// finds it: ±q for a crank driven on the ground, the drawing's for a link sliding on the
/// ground, else `atan2`), ω and α, written by mech-core's `put_kinematics_lanes`.
fn kinematics_four_fn(cx: &Ctx) -> TokenStream {
    let p = &cx.p;
    let (b, l) = (quote!(#p::batch), quote!(#p::lanes));
    let np = cx.n_points;
    let nm = cx.n_links - 1;
    let points = owners(cx).into_iter().enumerate().map(|(pt, o)| match o {
        Owner::Anchor(k) => quote!([s[#k].pos.xy(), s[#k].vel.xy(), s[#k].acc.xy()]),
        Owner::Local(k) => quote!(#l::point_motion_lanes(&s, #k, self.points[#pt])),
    });
    let links = (1..cx.n_links).map(|k| {
        let angle = lane_angle(cx, k);
        quote!([#angle, s[#k].omega, s[#k].alpha])
    });
    quote! {
        /// `kinematics_many`'s four configurations from index `i` of (q, q̇, q̈) on the lane
        /// backend `B`: the lanes not masked into the table, and the mask.
        #[inline(always)]
        fn __kinematics_four<B: #l::Backend>(&self, (q, qd, qdd): (&[f64], &[f64], &[f64]), i: usize, r: &mut #b::Strided<'_>) -> #l::Mask {
            let four = |x: &[f64]| -> #l::L<B> { #l::L::new(x[i..i + #l::LANES].try_into().expect("four configurations")) };
            let qv = [four(q)];
            let (s, mask) = self.__solve_lanes(&qv, &[four(qd)], &[four(qdd)], #p::kinematics::Level::Acceleration);
            let points: [[[#l::L<B>; 2]; 3]; #np] = [#(#points),*];
            let links: [[#l::L<B>; 3]; #nm] = [#(#links),*];
            #b::put_kinematics_lanes(r, i, mask, &points, &links)
        }
    }
}

/// The angle of moving link `k` in lanes, as `kinematics` finds it (`results::crank_angle`):
/// a crank driven on the ground from its input (`crank_angle_lanes`, the same operations
/// as the scalar `crank_angle`); a link sliding on the ground, its drawing's angle; else
/// `link_angle_lanes` (atan2).
fn lane_angle(cx: &Ctx, k: usize) -> TokenStream {
    let p = &cx.p;
    let l = quote!(#p::lanes);
    let crank = cx.plan.iter().find_map(|g| match g.kernel {
        Kernel::Driven(d) if d.body == k && d.from == 0 && !d.screw.slide => {
            let sign = if cx.model.joints[d.screw.joint].b == k {
                1.0f64
            } else {
                -1.0
            };
            let (input, sign) = (d.input, super::f64s(sign));
            Some(match cx.model.input_zero[input] {
                0.0 => quote!(#l::crank_angle_lanes(qv[#input], #sign)),
                z => {
                    let z = super::f64s(z);
                    quote!(#l::crank_angle_lanes(qv[#input] + #z, #sign))
                }
            })
        }
        _ => None,
    });
    match crank {
        Some(a) => a,
        None if cx.model.translates(k) => quote!(#l::L::splat(self.links[#k].angle_ref)),
        None => quote!(#l::link_angle_lanes(&self.links[#k], &s[#k])),
    }
}
