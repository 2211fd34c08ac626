//! The mech-core traits every generated struct implements (`Machine`, and `OneDof` for one
//! input), with the energies, and the one-DOF methods of Zhukovski's reduction:
//! `reduced`, `reduced_moment`, `acceleration`.

use super::{forces, id, Ctx};
use mech_core::model::Load;
use proc_macro2::TokenStream;
use quote::quote;

/// The trait impls and the one-DOF methods.
pub(crate) fn emit(cx: &Ctx) -> TokenStream {
    let machine = machine_impl(cx);
    if !cx.one_dof() {
        return machine;
    }
    let (one_dof, zhukovski) = (one_dof_impl(cx), zhukovski_fns(cx));
    let main = &cx.names.main;
    quote! {
        #machine
        #one_dof
        impl #main {
            #zhukovski
        }
    }
}

/// `Machine`: slices in, the kinematics and virtual power out, and the energies of the
/// links that have the terms (`mech::energy`).
fn machine_impl(cx: &Ctx) -> TokenStream {
    let Ctx {
        p, n_links, dof, ..
    } = cx;
    let n = &cx.names;
    let (main, loads, motion) = (&n.main, &n.loads, &n.motion);
    let slice_to_q = |v: &str| {
        let v = id(v);
        if cx.one_dof() {
            quote!(#v[0])
        } else {
            let idx = 0..cx.dof;
            quote!([#(#v[#idx]),*])
        }
    };
    let (q, qd, qdd) = (slice_to_q("q"), slice_to_q("qd"), slice_to_q("qdd"));
    let store = if cx.one_dof() {
        quote!(out[0] = d;)
    } else {
        quote!(out.copy_from_slice(&d);)
    };
    let kinetic = cx.inertial().into_iter().map(|l| {
        let lid = &cx.link_ids[l];
        quote!(out[#l] = #p::energy::kinetic(&self.links[#l], &m.links.#lid);)
    });
    let potential = cx.weighed().into_iter().map(|l| {
        let lid = &cx.link_ids[l];
        quote!(+ #p::energy::potential(&self.links[#l], &m.links.#lid, self.gravity))
    });
    let shaking = cx.inertial().into_iter().map(|l| {
        let lid = &cx.link_ids[l];
        quote!(s.add(&self.links[#l], &m.links.#lid);)
    });
    let springs = if cx.has_elements() {
        quote!(+ #p::elements::potential(&self.elements, &m.__states()))
    } else {
        quote!()
    };
    quote! {
        impl #p::traits::Machine for #main {
            type Loads = #loads;
            fn dof(&self) -> usize {
                #dof
            }
            fn links(&self) -> usize {
                #n_links
            }
            type Motion = #motion;
            fn motion(&self, q: &[f64], qd: &[f64], qdd: &[f64]) -> Result<#motion, #p::MechError> {
                if q.len() != #dof || qd.len() != #dof || qdd.len() != #dof {
                    return Err(#p::MechError::InvalidInput(format!("expected {} input values", #dof)));
                }
                self.kinematics(#q, #qd, #qdd)
            }
            fn driver_actions(&self, m: &#motion, loads: &#loads, out: &mut [f64]) -> Result<(), #p::MechError> {
                let d = self.driver_action(m, loads)?;
                #store
                Ok(())
            }
            fn link_kinetic_energies(&self, m: &#motion, out: &mut [f64]) {
                for o in out.iter_mut() {
                    *o = 0.0;
                }
                #(#kinetic)*
            }
            fn potential_energy(&self, m: &#motion) -> f64 {
                let _ = m;
                0.0 #(#potential)* #springs
            }
            fn shaking(&self, m: &#motion) -> #p::energy::Shaking {
                let _ = m;
                #[allow(unused_mut)]
                let mut s = #p::energy::Shaking::default();
                #(#shaking)*
                s
            }
        }
    }
}

/// `OneDof`: the inherent one-DOF methods.
fn one_dof_impl(cx: &Ctx) -> TokenStream {
    let p = &cx.p;
    let (main, loads) = (&cx.names.main, &cx.names.loads);
    quote! {
        impl #p::traits::OneDof for #main {
            fn reduced(&self, q: f64) -> Result<#p::zhukovski::Reduced, #p::MechError> {
                #main::reduced(self, q)
            }
            fn reduced_many(&self, q: &[f64], inertia: &mut [f64], derivative: &mut [f64]) -> #p::batch::BatchErrors {
                #main::reduced_many(self, q, inertia, derivative)
            }
            fn reduced_moment(&self, q: f64, loads: &#loads) -> Result<f64, #p::MechError> {
                #main::reduced_moment(self, q, loads)
            }
            fn acceleration(&self, q: f64, qd: f64, driver: f64, loads: &#loads) -> Result<f64, #p::MechError> {
                #main::acceleration(self, q, qd, driver, loads)
            }
        }
    }
}

/// Zhukovski's sums term by term (`mech::zhukovski::ZhukovskiSums`): the inertia of the links
/// with inertia terms, and the moment of gravity and of every load.
pub(crate) fn zhukovski_terms(cx: &Ctx) -> (TokenStream, TokenStream) {
    let p = &cx.p;
    let inertial = cx.inertial();
    let weighed = cx.weighed();
    let inertia = inertial.iter().map(|&l| {
        if cx.model.ground_pivot(l).is_some() {
            quote!(z.inertia_about_pivot(&self.links[#l], &s[#l]);)
        } else if cx.model.translates(l) {
            quote!(z.inertia_translating(&self.links[#l], &s[#l]);)
        } else if let Some(m) = cx.model.span_partner(l) {
            quote!(z.inertia_spanned(&self.links[#l], &s[#l], &s[#m]);)
        } else {
            quote!(z.inertia(&self.links[#l], &s[#l]);)
        }
    });
    let inertia = quote!(#(#inertia)*);
    let loads = cx.model.loads.iter().enumerate().map(|(k, l)| {
        let (lid, link) = (id(l.name()), l.link());
        match l {
            // A link that slides on the ground moves every point alike, and a torque on
            // it does no work (ω = 0: its term would add a zero).
            Load::Force { .. } if cx.model.translates(link) => {
                quote!(z.force_translating(&s[#link], loads.#lid);)
            }
            Load::Torque { .. } if cx.model.translates(link) => quote!(),
            // At the link's first point the load's local vector is zero for any drawing:
            // written as a literal, the kernel's "at the anchor" test folds.
            Load::Force { point, .. } if cx.model.links[link].points.first() == Some(point) => {
                quote!(z.force(&s[#link], #p::Vector2::zeros(), loads.#lid);)
            }
            Load::Force { .. } => quote!(z.force(&s[#link], self.loads[#k], loads.#lid);),
            Load::Torque { .. } => quote!(z.torque(&s[#link], loads.#lid);),
        }
    });
    let gravity = weighed.iter().map(|&l| {
        if cx.model.translates(l) {
            quote!(z.gravity_translating(&self.links[#l], &s[#l], self.gravity);)
        } else if let Some(m) = cx.model.span_partner(l) {
            quote!(z.gravity_spanned(&self.links[#l], &s[#l], &s[#m], self.gravity);)
        } else {
            quote!(z.gravity(&self.links[#l], &s[#l], self.gravity);)
        }
    });
    let moment = quote! {
        #(#gravity)*
        #(#loads)*
    };
    (inertia, moment)
}

/// `reduced`, `reduced_moment`, `acceleration`. These check their inputs first
/// (`error::check_inputs`), where `kinematics` and `kinetostatics` look at theirs only
/// when a solve fails (`error::blame`): measured, the short Zhukovski routes lost time to
/// the deferred form (interleaved against the hand-written floor, `reduced` 1.22× with
/// the check first, 1.36–1.39× deferred), the long ones gained.
fn zhukovski_fns(cx: &Ctx) -> TokenStream {
    let p = &cx.p;
    let loads = &cx.names.loads;
    let values = forces::load_values(cx);
    let (inertia, moment) = zhukovski_terms(cx);
    let inputs = &cx.inputs_doc;
    // The force elements at q̇ = 0 (M*(q): no damper force) and at the given q̇.
    let (elements_at_rest, elements_moving) = if cx.has_elements() {
        (
            quote!(z.elements(&self.elements, &s, 0.0);),
            quote!(z.elements(&self.elements, &s, qd);),
        )
    } else {
        (quote!(), quote!())
    };
    let solved = quote! {
        let (s, _) = self.__solve(&[q], &[1.0], &[0.0], #p::kinematics::Level::Acceleration, false)?;
        let mut z = #p::zhukovski::ZhukovskiSums::new();
        #inertia
        #p::magnitudes::finite_few("reduced inertia", &[z.reduced.inertia, z.reduced.inertia_derivative])?;
        Ok(z.reduced)
    };
    // Constant ratios (`mech_core::plan::ratios`): I*(q) is kept in the struct as a
    // constant and a few cosines, and the direct problem needs the rates alone (for M*).
    let (reduced, series_items, acceleration_solve) = match cx.ratio_pins() {
        Some(pins) => {
            let n_links = cx.n_links;
            let pins = pins.iter().map(|pin| {
                let (parent, slides) = (pin.parent, pin.slides);
                // The ground hangs from nothing: its entry's joint is never read.
                let joint = match pin.joint {
                    usize::MAX => quote!(usize::MAX),
                    j => quote!(#j),
                };
                quote!(#p::zhukovski::Pin { parent: #parent, joint: #joint, slides: #slides })
            });
            (
                quote! {
                    #p::error::check_inputs("q", [q])?;
                    Ok(self.reduced_series.at(q))
                },
                quote! {
                    /// Each link's pin in the machine of constant ratios (the ground's unused).
                    const __PINS: [#p::zhukovski::Pin; #n_links] = [#(#pins),*];
                },
                quote! {
                    let (s, _) = self.__solve(&[q], &[1.0], &[0.0], #p::kinematics::Level::Velocity, false)?;
                    let mut z = #p::zhukovski::ZhukovskiSums::new();
                    z.reduced = self.reduced_series.at(q);
                },
            )
        }
        None => (
            quote! { #p::error::check_inputs("q", [q])?; #solved },
            quote!(),
            quote! {
                let (s, _) = self.__solve(&[q], &[1.0], &[0.0], #p::kinematics::Level::Acceleration, false)?;
                let mut z = #p::zhukovski::ZhukovskiSums::new();
                #inertia
            },
        ),
    };
    let reduced_doc: &[&str] = match cx.series_len() {
        Some(0) => &[
            " Zhukovski's reduced inertia I* (kg·m²) and dI*/dq (kg·m²/rad): every velocity",
            " coefficient of this machine is a constant (gears on fixed axes, racks on fixed",
            " guides), so I* is a constant of the drawing, worked out by `from_params`, and",
            " dI*/dq = 0.",
        ],
        Some(_) => &[
            " Zhukovski's reduced inertia I*(q) (kg·m²) and dI*/dq (kg·m²/rad): every link of",
            " this machine of gears turns at a constant ratio to the input, so I* is a",
            " constant and a few cosines of q, I* = C + Σ (A cos Δ(q − q₀) + B sin Δ(q − q₀)),",
            " one per pair of links on a chain of pins, worked out by `from_params`.",
        ],
        None => &[
            " Zhukovski's reduced inertia I*(q) (kg·m²) and dI*/dq (kg·m²/rad), in closed",
            " form from the velocity coefficients and their derivatives.",
        ],
    };
    quote! {
        #(#[doc = #reduced_doc])*
        pub fn reduced(&self, q: f64) -> Result<#p::zhukovski::Reduced, #p::MechError> {
            #reduced
        }
        #series_items
        /// Zhukovski's reduced moment M*(q) (N·m): the power of the loads, gravity and
        /// springs per unit input rate, M* = Σ F·g + Σ M·g − Σ T x' (a damper's part,
        /// −c x'² q̇, depends on q̇: `acceleration` adds it, M*(q) is at q̇ = 0).
        pub fn reduced_moment(&self, q: f64, loads: &#loads) -> Result<f64, #p::MechError> {
            #p::error::check_inputs("q and the loads", [q, #values])?;
            let (s, _) = self.__solve(&[q], &[1.0], &[0.0], #p::kinematics::Level::Velocity, false)?;
            let mut z = #p::zhukovski::ZhukovskiSums::new();
            #moment
            #elements_at_rest
            #p::magnitudes::finite_few("reduced moment", &[z.moment])?;
            Ok(z.moment)
        }
        /// The direct problem: q̈ (rad/s²) from I* q̈ + ½ dI*/dq q̇² = driver + M*, the
        /// driver's torque applied by the motor (the sign of `kinetostatics`' `driver`).
        ///
        #(#[doc = #inputs])*
        pub fn acceleration(&self, q: f64, qd: f64, driver: f64, loads: &#loads) -> Result<f64, #p::MechError> {
            #p::error::check_inputs("q, qd, driver and the loads", [q, qd, driver, #values])?;
            #acceleration_solve
            #moment
            #elements_moving
            #p::zhukovski::acceleration(z.reduced, z.moment, qd, driver)
        }
    }
}
