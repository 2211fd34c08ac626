//! The `mechanism!` procedural macro: parse (mech-core's DSL grammar) → resolve and
//! validate (mech-core) → plan (mech-core's Assur groups) → emit (here, with quote).
//!
//! The macro holds no mechanics: the emitted code is a straight-line sequence of calls
//! into mech-core's kernels with the topology unrolled as constants.
#![deny(missing_docs)]

mod emit;

use mech_core::front::dsl::Parsed;
use proc_macro::TokenStream;

/// Declare a planar mechanism (or a spatial one: `space` first); see the crate `mech` and `docs/conventions.md#dsl` for the grammar.
#[proc_macro]
pub fn mechanism(input: TokenStream) -> TokenStream {
    let tokens = proc_macro2::TokenStream::from(input.clone());
    let space = |s: syn::parse::ParseStream| {
        let space = mech_core::spatial::dsl::is_space(s);
        s.parse::<proc_macro2::TokenStream>()?;
        Ok(space)
    };
    if syn::parse::Parser::parse2(space, tokens.clone()).unwrap_or(false) {
        return emit::spatial::mechanism(tokens).into();
    }
    let desc = match syn::parse::<Parsed>(input) {
        Ok(p) => p.0,
        Err(e) => return e.to_compile_error().into(),
    };
    if let Some(e) = free_dimension(&desc) {
        return e.to_compile_error().into();
    }
    match mech_core::checks::load::check(&desc) {
        Ok((model, plan)) => emit::mechanism(&desc, &model, &plan).into(),
        Err(rejected) => {
            emit::outline(&desc, rejected.model.as_ref(), &rejected.diagnostics).into()
        }
    }
}

/// A dimension written `free(LO..HI)`: `mech size` chooses it in a file; the macro needs
/// the number.
fn free_dimension(desc: &mech_core::model::Description<proc_macro2::Span>) -> Option<syn::Error> {
    desc.links.iter().find_map(|l| {
        let shape = l.shape.as_ref()?;
        let f = shape.free.iter().flatten().next()?;
        Some(syn::Error::new(
            f.span,
            format!(
                "link `{}`: a dimension written `free({} m..{} m)` is chosen by `mech size FILE --safety S -o OUT.mech`; the macro needs its number: write the sized value from OUT.mech here",
                l.name.text, f.lo, f.hi
            ),
        ))
    })
}

/// The whole pipeline on text, for the snapshot tests: parse → resolve → validate →
/// plan → emit, returning the generated code part by part or the diagnostics' messages.
#[cfg(test)]
fn expand_parts(text: &str) -> Result<Vec<(&'static str, proc_macro2::TokenStream)>, Vec<String>> {
    let desc = mech_core::front::dsl::parse_str(text).map_err(|e| vec![e.to_string()])?;
    let (model, plan) = mech_core::checks::load::check(&desc).map_err(|r| {
        r.diagnostics
            .into_iter()
            .map(|d| d.message)
            .collect::<Vec<_>>()
    })?;
    Ok(emit::parts(&desc, &model, &plan))
}

#[cfg(test)]
mod snapshots {
    //! Snapshots of the expanded code (prettyplease), one per emitted part (params, plan,
    //! results, forces, traits): a change in what the macro emits shows up as a
    //! reviewable diff of that part (`cargo insta review`, or INSTA_UPDATE=always).

    /// Each part of the expansion of `text`, pretty-printed.
    fn pretty_parts(text: &str) -> Vec<(&'static str, String)> {
        let parts = super::expand_parts(text).unwrap_or_else(|e| panic!("{e:?}"));
        let mut all = proc_macro2::TokenStream::new();
        let out = parts
            .into_iter()
            .map(|(name, tokens)| {
                all.extend(tokens.clone());
                let file = syn::parse2(tokens)
                    .unwrap_or_else(|e| panic!("the {name} part parses as items: {e}"));
                (name, prettyplease::unparse(&file))
            })
            .collect();
        syn::parse2::<syn::File>(all).expect("the whole expansion parses as a file");
        out
    }

    /// A snapshot of every part, named `<mechanism>_<part>`.
    fn snapshot_parts(mechanism: &str, text: &str) {
        for (part, code) in pretty_parts(text) {
            insta::assert_snapshot!(format!("{mechanism}_{part}"), code);
        }
    }

    /// A four-bar with a link of each kind: the crank declared with `mass` (every term),
    /// the coupler without (massless: no term, `from_params` checks it stays so), the
    /// rocker with `inertia` alone (the inertia moment only); gravity and two loads.
    const FOUR_BAR: &str = r#"
        /// Crank-rocker four-bar.
        pub struct FourBar {
            gravity: (0.0, -9.81),
            ground { O2: (0.0, 0.0), O4: (0.3, 0.0) },
            link crank { points { O2, A: (0.0, 0.1) }, mass: 0.5, inertia: 1e-3, cg: (0.0, 0.05) },
            link coupler { points { A, B: (0.25, 0.25), P: (0.1, 0.2) } },
            link rocker { points { O4, B }, inertia: 3e-3 },
            joints { O2: revolute(ground, crank), A: revolute(crank, coupler), B: revolute(coupler, rocker), O4: revolute(ground, rocker) },
            input: O2,
            loads { tool: force on coupler at P, resist: torque on rocker },
        }
    "#;

    /// An offset slider-crank (a prismatic joint) with gravity; the piston declared
    /// `mass: 0.0`, so its mass may be given at run time.
    const SLIDER_CRANK: &str = r#"
        /// Offset slider-crank.
        pub struct SliderCrank {
            gravity: (0.0, -9.81),
            ground { O2: (0.0, 0.0) },
            link crank { points { O2, A: (0.038302, 0.032139) }, mass: 1.2, inertia: 2.1e-3, cg: (0.0089, 0.0127) },
            link rod { points { A, B: (0.237285, 0.012) }, mass: 2.4, inertia: 9.5e-3, cg: (0.1030, 0.0256) },
            link piston { points { B }, mass: 0.0, cg: (0.237285, 0.012) },
            joints {
                O2: revolute(ground, crank),
                A: revolute(crank, rod),
                B: revolute(rod, piston),
                guide: prismatic(ground, piston) at B along (1.0, 0.0),
            },
            input: O2,
            loads { gas: force on piston at B, load: torque on crank },
        }
    "#;

    /// A pinion driving a gear whose crank pin pulls a spring and a damper: the meshing
    /// group, the tooth reaction, the elements in every route.
    const GEARED_SPRUNG: &str = r#"
        /// A geared crank held by a spring.
        pub struct GearedSprung {
            gravity: (0.0, -9.81),
            ground { O1: (0.0, 0.0), O2: (100 mm, 0.0), C: (100 mm, 200 mm) },
            link pinion { points { O1 }, mass: 0.3, inertia: 1.0e-4, cg: (0.0, 0.0) },
            link wheel { points { O2, A: (140 mm, 0.0) }, mass: 1.5, inertia: 3.0e-3, cg: (105 mm, 5 mm) },
            joints {
                O1: revolute(ground, pinion),
                O2: revolute(ground, wheel),
                mesh: gear(pinion, wheel) radii (25 mm, 75 mm),
            },
            input: O1,
            loads { load: torque on wheel },
            elements {
                k: spring(ground at C, wheel at A) stiffness 2 kN_per_m free_length 150 mm,
                c: damper(ground at C, wheel at A) damping 20 N_s_per_m,
            },
        }
    "#;

    /// pyslvs's Stephenson III: a crank, then a triad (the ternary L3 pinned to L2, L4
    /// and L5), whose positions go through the triad kernel, its rates through the
    /// group's linear system.
    const STEPHENSON_TRIAD: &str = r#"
        /// Stephenson III six-bar with a triad.
        pub struct StephensonIII {
            ground { P0: (0.00025, -0.000625), P4: (0.117125, 0.023375), P6: (0.138875, 0.033125) },
            link L1 { points { P0, P1: (0.015375, 0.041125) } },
            link L2 { points { P1, P2: (0.061375, 0.095125) } },
            link L3 { points { P2, P3: (0.102875, 0.084375), P5: (0.134625, 0.119875) } },
            link L4 { points { P3, P4 } },
            link L5 { points { P5, P6 } },
            joints {
                J0: revolute(ground, L1) at P0, J1: revolute(L1, L2) at P1,
                J2: revolute(L2, L3) at P2, J3: revolute(L3, L4) at P3,
                J4: revolute(ground, L4) at P4, J5: revolute(L3, L5) at P5,
                J6: revolute(ground, L5) at P6,
            },
            input: J0,
        }
    "#;

    /// A slider-crank whose crank is a steel bar and whose rod is a brass rod: the
    /// `shapes` field of `Params` and `from_params` computing their mass properties with
    /// `mech_core`'s function (`update_shape`), the bodies carried into the model.
    const SHAPED_CRANK: &str = r#"
        /// A slider-crank built from stock.
        pub struct ShapedCrank {
            ground { O: (0.0, 0.0) },
            link crank { points { O, A: (0.05, 0.0) }, shape: bar(width 20 mm, thickness 8 mm), material: steel },
            link rod { points { A, B: (0.25, 0.0) }, shape: rod(diameter 10 mm), material: brass },
            link slider { points { B }, mass: 0.2, cg: B },
            joints {
                O: revolute(ground, crank),
                A: revolute(crank, rod),
                B: revolute(rod, slider),
                guide: prismatic(ground, slider) at B along (1.0, 0.0),
            },
            input: O,
        }
    "#;

    /// The params part of a machine with links declared by their shapes: each one's
    /// mass properties computed in `from_params` by one call into `mech_core`, none by a
    /// formula written in the expansion.
    #[test]
    fn shaped_crank_params() {
        let parts = pretty_parts(SHAPED_CRANK);
        let params = &parts
            .iter()
            .find(|(name, _)| *name == "params")
            .expect("a params part")
            .1;
        insta::assert_snapshot!("shaped_crank_params", params);
        let code = flat(&parts);
        for call in [
            "instance::update_shape(\"crank\",&mutp.links.crank,&mutp.shapes.crank,&[[p.points.O.x,p.points.O.y],[p.points.A.x,p.points.A.y]],)?;",
            "instance::update_shape(\"rod\",&mutp.links.rod,&mutp.shapes.rod,&[[p.points.A.x,p.points.A.y],[p.points.B.x,p.points.B.y]],)?;",
            "body:Some((p.shapes.crank.shape,p.shapes.crank.material))",
        ] {
            assert!(code.contains(call), "{call} in {params}");
        }
        assert!(!code.contains("update_shape(\"slider\""), "{params}");
        assert!(
            !code.contains("PI") && !code.contains("3.14159"),
            "{params}"
        );
    }

    /// An epicyclic train: a planet, its cg off its pin, on an arm driven on the ground,
    /// rolling on a fixed sun.
    const EPICYCLIC: &str = r#"
        /// A planet on a driven arm.
        pub struct Epicyclic {
            gravity: (0.0, -9.81),
            ground { O: (0.0, 0.0) },
            link arm { points { O, P: (45 mm, 0.0) }, mass: 0.8, inertia: 9.0e-4, cg: (20 mm, 3 mm) },
            link planet { points { P }, mass: 0.2, inertia: 2.0e-5, cg: (46 mm, 1 mm) },
            joints {
                A: revolute(ground, arm) at O,
                P: revolute(arm, planet),
                sp: gear(ground, planet) radii (20 mm, 25 mm),
            },
            input: A,
        }
    "#;

    /// The one-DOF part of an epicyclic train: I*(q) kept as a constant and one cosine
    /// (`reduced_series`, one term: the planet's chain), the direct problem solving to the
    /// rates alone.
    #[test]
    fn epicyclic_reduced_is_a_kept_series() {
        let parts = pretty_parts(EPICYCLIC);
        let traits = &parts
            .iter()
            .find(|(name, _)| *name == "traits")
            .expect("a traits part")
            .1;
        insta::assert_snapshot!("epicyclic_traits", traits);
        let code = flat(&parts);
        assert!(code.contains("reduced_series:::mech::__private::zhukovski::Series<[::mech::__private::zhukovski::Term;1usize],>"), "{code}");
        assert!(code.contains("Ok(self.reduced_series.at(q))"), "{code}");
    }

    /// The plan part of a triad machine: its constant and the call of its kernel.
    #[test]
    fn stephenson_triad_plan() {
        let parts = pretty_parts(STEPHENSON_TRIAD);
        let plan = &parts
            .iter()
            .find(|(name, _)| *name == "plan")
            .expect("a plan part")
            .1;
        insta::assert_snapshot!("stephenson_triad_plan", plan);
        let code = flat(&parts);
        assert!(
            code.contains("triad::triad_solve::<12usize,>(&Self::__G1_TRIAD"),
            "{plan}"
        );
    }

    /// The whole expansion of a spatial RSSR (`space` first): the struct, its constants and
    /// declaration as a `SpatialModel` literal, the typed results copied from the run-time
    /// solver's answer, each point moved with its body from a constant offset.
    #[test]
    fn rssr_spatial() {
        let text = r#"
            /// An RSSR.
            pub struct Rssr {
                space,
                gravity: (0.0, 0.0, -9.81),
                ground { O: (0.0, 0.0, 0.0), C: (250 mm, 120 mm, 80 mm) },
                link crank { points { O, A: (0.0, 0.05, 0.0) }, mass: 1.0, cg: (0.01, 0.025, 0.004),
                             inertia: (1e-3, 4e-4, 9e-4, 1e-4, -2e-5, 5e-5) },
                link rod { points { A, B: (0.25, 0.02, 0.08) } },
                link rocker { points { C, B } },
                joints {
                    O: revolute(ground, crank) axis (1.0, 0.0, 0.0),
                    A: spherical(crank, rod),
                    B: spherical(rod, rocker),
                    C: revolute(ground, rocker) axis (0.0, 0.0, 1.0),
                },
                input: O,
                loads { tool: torque on rocker },
            }
        "#;
        let tokens = super::emit::spatial::mechanism(text.parse().expect("tokens"));
        let file = syn::parse2::<syn::File>(tokens).expect("the expansion parses as a file");
        let code = prettyplease::unparse(&file);
        assert!(!code.contains("compile_error"), "{code}");
        insta::assert_snapshot!("rssr_spatial", code);
    }

    #[test]
    fn geared_sprung_parts() {
        snapshot_parts("geared_sprung", GEARED_SPRUNG);
    }

    #[test]
    fn four_bar_parts() {
        snapshot_parts("four_bar", FOUR_BAR);
    }

    #[test]
    fn slider_crank_parts() {
        snapshot_parts("slider_crank", SLIDER_CRANK);
    }

    /// The whole expansion with no whitespace, to look for calls whatever the line breaks.
    fn flat(parts: &[(&'static str, String)]) -> String {
        parts
            .iter()
            .flat_map(|(_, c)| c.chars())
            .filter(|c| !c.is_whitespace())
            .collect()
    }

    #[test]
    fn every_impl_allows_the_drawings_numbers() {
        // A 90° input zero is π/2 written out: clippy's deny-by-default `approx_constant`
        // must not fail the user's build on it.
        let text = SLIDER_CRANK.replacen("input: O2", "input: O2 from 90 deg", 1);
        assert_ne!(text, SLIDER_CRANK, "the slider-crank declares `input: O2`");
        let parts = super::expand_parts(&text).unwrap_or_else(|e| panic!("{e:?}"));
        let mut impls = 0;
        for (_, part) in parts {
            let file: syn::File =
                syn::parse2(super::emit::allow_drawing_numbers(part)).expect("items");
            for item in &file.items {
                if let syn::Item::Impl(i) = item {
                    impls += 1;
                    let allowed = i
                        .attrs
                        .iter()
                        .any(|a| quote::quote!(#a).to_string().contains("approx_constant"));
                    assert!(allowed, "an impl without the allow");
                }
            }
        }
        assert!(impls >= 5, "{impls} impl blocks");
    }

    #[test]
    fn declared_terms_on_every_route() {
        let code = flat(&pretty_parts(SLIDER_CRANK));
        // `mass: 0.0` on the piston (link 3): gravity, inertia, energies and Zhukovski.
        for term in [
            "add_gravity_of(&mutf[3usize]",
            "add_inertia_of(&mutf[3usize]",
            // The piston slides on the ground: its cg moves as its anchor.
            "z.inertia_translating(&self.links[3usize]",
            "z.gravity_translating(&self.links[3usize]",
            "energy::kinetic(&self.links[3usize]",
            "energy::potential(&self.links[3usize]",
        ] {
            assert!(code.contains(term), "{term}");
        }
        assert!(
            !code.contains("LinkTerms::"),
            "every link declared with mass: nothing to check in from_params"
        );
        let code = flat(&pretty_parts(FOUR_BAR));
        // The coupler (link 2) has no term; the rocker (link 3) its inertia only.
        for absent in [
            "add_inertia_of(&mutf[2usize]",
            "add_gravity_of(&mutf[2usize]",
            "z.inertia(&self.links[2usize]",
            "z.inertia_about_pivot(&self.links[2usize]",
            "z.gravity(&self.links[2usize]",
            "energy::kinetic(&self.links[2usize]",
            "energy::potential(&self.links[2usize]",
            "add_gravity_of(&mutf[3usize]",
            "z.gravity(&self.links[3usize]",
            "energy::potential(&self.links[3usize]",
        ] {
            assert!(!code.contains(absent), "{absent}");
        }
        for present in [
            "LinkTerms::Massless.check(\"coupler\",&p.links.coupler)?",
            "LinkTerms::InertiaOnly.check(\"rocker\",&p.links.rocker)?",
            "add_inertia_of(&mutf[3usize]",
            // The rocker turns about its anchor O4, a ground pin: its inertia about O4.
            "z.inertia_about_pivot(&self.links[3usize]",
            "energy::kinetic(&self.links[3usize]",
        ] {
            assert!(code.contains(present), "{present}");
        }
    }

    #[test]
    fn massless_four_bar_without_gravity_has_no_inertia_or_gravity_terms() {
        let parts = pretty_parts(
            r#"
            pub struct Bare {
                ground { O2: (0.0, 0.0), O4: (0.3, 0.0) },
                link crank { points { O2, A: (0.0, 0.1) } },
                link coupler { points { A, B: (0.25, 0.25) } },
                link rocker { points { O4, B } },
                joints { O2: revolute(ground, crank), A: revolute(crank, coupler), B: revolute(coupler, rocker), O4: revolute(ground, rocker) },
                input: O2,
                loads { out: torque on rocker },
            }
            "#,
        );
        let code = flat(&parts);
        for absent in ["add_inertia", "z.inertia", "energy::kinetic"] {
            assert!(
                !code.contains(absent),
                "massless links must not get inertia terms: {absent}"
            );
        }
        for absent in [
            "add_gravity",
            "z.gravity",
            "energy::potential",
            "pubgravity",
        ] {
            assert!(
                !code.contains(absent),
                "no gravity declared: no gravity terms: {absent}"
            );
        }
        assert!(code.contains("add_torque"));
        for (part, code) in parts
            .into_iter()
            .filter(|(part, _)| matches!(*part, "forces" | "traits"))
        {
            insta::assert_snapshot!(format!("bare_four_bar_{part}"), code);
        }
    }
}
