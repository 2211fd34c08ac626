//! A spatial mechanism's `Loads` (one 3-vector per declared load), `Forces` (one reaction
//! per joint), `kinetostatics`, `driver_action`, the one-DOF methods (`reduced`,
//! `reduced_moment`, `acceleration`) and the `Machine` / `OneDof` impls, each a call of
//! mech-core's spatial `Solver` on the mechanism's stack frame.

use super::Ctx;
use crate::emit::id;
use mech_core::spatial::LoadKind;
use proc_macro2::TokenStream;
use quote::quote;

pub(super) fn emit(c: &Ctx) -> TokenStream {
    let Ctx {
        main,
        s,
        p,
        q_ty,
        dof,
        ..
    } = c;
    let (loads, forces, forces_joints, motion) = (
        c.name("Loads"),
        c.name("Forces"),
        c.name("ForcesJoints"),
        c.name("Motion"),
    );
    let model = c.model;
    let load_ids: Vec<_> = model.loads.iter().map(|l| id(&l.name)).collect();
    let load_docs = model.loads.iter().map(|l| match l.kind {
        LoadKind::Force { body, point } => format!(
            "`force on {} at {}`: N, global axes.",
            model.bodies[body].name, model.points[point].0
        ),
        LoadKind::Torque { body } => format!(
            "`torque on {}`: N·m about the global axes.",
            model.bodies[body].name
        ),
    });
    let joint_ids: Vec<_> = model.joints.iter().map(|j| id(&j.name)).collect();
    let joint_docs = model.joints.iter().map(|j| {
        format!(
            "`{}` ({}): by `{}` on `{}`, force (N) and moment about the joint's point (N·m).",
            j.name,
            j.kind.word(),
            model.bodies[j.a].name,
            model.bodies[j.b].name
        )
    });
    let k = 0..model.joints.len();
    let (n_loads, n_joints, n_idle) = (
        model.loads.len(),
        model.joints.len(),
        c.mech.idle_links().len(),
    );
    let driver = c.from_values(quote!(drivers));
    let action = c.from_values(quote!(d));
    let one_dof = (*dof == 1).then(|| {
        quote! {
            impl #main {
                /// Zhukovski's I*(q) (kg·m² or kg) and dI*/dq.
                pub fn reduced(&self, q: f64) -> Result<#p::zhukovski::Reduced, #p::MechError> {
                    self.__solver()?.reduced(q)
                }

                /// Zhukovski's M*(q) (N·m or N): the loads and gravity reduced to the input.
                pub fn reduced_moment(&self, q: f64, loads: &#loads) -> Result<f64, #p::MechError> {
                    self.__solver()?.reduced_moment(q, &Self::__loads(loads))
                }

                /// The direct problem: q̈ = (driver + M* − ½ dI*/dq q̇²) / I*.
                pub fn acceleration(
                    &self,
                    q: f64,
                    qd: f64,
                    driver: f64,
                    loads: &#loads,
                ) -> Result<f64, #p::MechError> {
                    self.__solver()?.acceleration(q, qd, driver, &Self::__loads(loads))
                }
            }

            impl #p::traits::OneDof for #main {
                fn reduced(&self, q: f64) -> Result<#p::zhukovski::Reduced, #p::MechError> {
                    #main::reduced(self, q)
                }
                fn reduced_moment(&self, q: f64, loads: &#loads) -> Result<f64, #p::MechError> {
                    #main::reduced_moment(self, q, loads)
                }
                fn acceleration(
                    &self,
                    q: f64,
                    qd: f64,
                    driver: f64,
                    loads: &#loads,
                ) -> Result<f64, #p::MechError> {
                    #main::acceleration(self, q, qd, driver, loads)
                }
            }
        }
    });
    quote! {
        /// The value of every declared load.
        #[allow(non_snake_case)]
        #[derive(Clone, Copy, Debug, Default, PartialEq)]
        pub struct #loads {
            #(#[doc = #load_docs] pub #load_ids: #s::Vector3<f64>,)*
        }
        /// Every joint's reaction.
        #[allow(non_snake_case)]
        #[derive(Clone, Copy, Debug, PartialEq)]
        pub struct #forces_joints {
            #(#[doc = #joint_docs] pub #joint_ids: #s::Reaction,)*
        }
        /// Result of `kinetostatics`: the motor actions and every reaction.
        #[derive(Clone, Copy, Debug, PartialEq)]
        pub struct #forces {
            /// The motor action of each input (N·m about its axis or N along it, by its first
            /// link on its second).
            pub driver: #q_ty,
            /// Every joint's reaction.
            pub joints: #forces_joints,
            /// The moment (N·m) the spin convention of each idle link needs, in the order of
            /// `mechanism().idle_links()`: zero for a thin rod loaded through its axis; it
            /// does no work (docs/spatial.md).
            pub spin_moments: [#s::Vector3<f64>; #n_idle],
        }

        impl #main {
            /// The loads' values in the order declared.
            fn __loads(l: &#loads) -> [#s::Vector3<f64>; #n_loads] {
                [#(l.#load_ids),*]
            }

            /// Every joint's reaction and every motor action at the motion `m` under `loads`:
            /// Newton–Euler (d'Alembert) with the full inertia tensor and the gyroscopic term.
            pub fn kinetostatics(&self, m: &#motion, loads: &#loads) -> Result<#forces, #p::MechError> {
                self.__forces(m, loads, None)
            }

            /// `kinetostatics` with Coulomb friction in the joints (`friction[j]` for joint j
            /// in the order declared: μ and the pin or ball radius, m), iterated to a fixed
            /// point; `MechError::SelfLocking` when no finite motor action moves the mechanism.
            pub fn kinetostatics_with_friction(
                &self,
                m: &#motion,
                loads: &#loads,
                friction: &[#p::friction::JointFriction; #n_joints],
            ) -> Result<#forces, #p::MechError> {
                self.__forces(m, loads, Some(friction))
            }

            fn __forces(
                &self,
                m: &#motion,
                loads: &#loads,
                friction: Option<&[#p::friction::JointFriction; #n_joints]>,
            ) -> Result<#forces, #p::MechError> {
                let mut reactions = [#s::Reaction::default(); #n_joints];
                let mut drivers = [0.0; #dof];
                let mut spins = [#s::Vector3::zeros(); #n_idle];
                let out = #s::ForcesOut {
                    reactions: &mut reactions,
                    drivers: &mut drivers,
                    spin_moments: &mut spins,
                };
                let (solver, loads) = (self.__solver()?, Self::__loads(loads));
                match friction {
                    None => solver.kinetostatics(&m.bodies, &m.q, &loads, out)?,
                    Some(f) => solver.kinetostatics_with_friction(&m.bodies, &m.q, &loads, f, out)?,
                }
                Ok(#forces {
                    driver: #driver,
                    joints: #forces_joints {
                        #(#joint_ids: reactions[#k],)*
                    },
                    spin_moments: spins,
                })
            }

            /// The motor actions by virtual power (no reaction computed).
            pub fn driver_action(&self, m: &#motion, loads: &#loads) -> Result<#q_ty, #p::MechError> {
                let mut d = [0.0; #dof];
                self.__solver()?.driver_actions(&m.bodies, &m.q, &Self::__loads(loads), &mut d)?;
                Ok(#action)
            }
        }

        impl #p::traits::Machine for #main {
            type Loads = #loads;
            type Motion = #motion;
            fn dof(&self) -> usize {
                #dof
            }
            fn links(&self) -> usize {
                #main::LINKS
            }
            fn motion(&self, q: &[f64], qd: &[f64], qdd: &[f64]) -> Result<#motion, #p::MechError> {
                let arr = |v: &[f64]| {
                    <[f64; #dof]>::try_from(v).map_err(|_| {
                        #p::MechError::InvalidInput(format!(
                            "{} value(s) given for {} input(s)",
                            v.len(),
                            #dof
                        ))
                    })
                };
                self.__kinematics(arr(q)?, arr(qd)?, arr(qdd)?)
            }
            fn driver_actions(
                &self,
                m: &#motion,
                loads: &#loads,
                out: &mut [f64],
            ) -> Result<(), #p::MechError> {
                self.__solver()?.driver_actions(&m.bodies, &m.q, &Self::__loads(loads), out)
            }
            fn link_kinetic_energies(&self, m: &#motion, out: &mut [f64]) {
                match self.__solver() {
                    Ok(s) => s.kinetic_energies(&m.bodies, out),
                    Err(_) => out.fill(f64::NAN),
                }
            }
            fn potential_energy(&self, m: &#motion) -> f64 {
                self.__solver()
                    .map(|s| s.potential_energy(&m.bodies))
                    .unwrap_or(f64::NAN)
            }
            fn shaking(&self, m: &#motion) -> #p::energy::Shaking {
                self.__solver()
                    .map(|s| s.shaking(&m.bodies))
                    .unwrap_or_default()
            }
        }

        #one_dof
    }
}
