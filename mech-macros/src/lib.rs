//! The `mechanism!` procedural macro: parse (mech-core's DSL grammar) → resolve and
//! validate (mech-core) → plan (mech-core's Assur groups) → emit (here, with quote).
//!
//! The macro holds no mechanics: the emitted code is a straight-line sequence of calls
//! into mech-core's kernels with the topology unrolled as constants.

mod emit;

use mech_core::dsl::Parsed;
use mech_core::resolve::{resolve, Diagnostic};
use proc_macro::TokenStream;
use proc_macro2::Span;

/// Declare a planar mechanism; see the crate `mech` and `docs/conventions.md#dsl` for the grammar.
#[proc_macro]
pub fn mechanism(input: TokenStream) -> TokenStream {
    let desc = match syn::parse::<Parsed>(input) {
        Ok(p) => p.0,
        Err(e) => return e.to_compile_error().into(),
    };
    let model = match resolve(&desc) {
        Ok(m) => m,
        Err(diags) => return emit::outline(&desc, None, &diags).into(),
    };
    let issues = mech_core::validate::check(&model);
    if !issues.is_empty() {
        let diags: Vec<Diagnostic<Span>> = issues.iter().map(|i| desc.diagnostic(&model, i)).collect();
        return emit::outline(&desc, Some(&model), &diags).into();
    }
    match mech_core::assur::plan(&model) {
        Ok(plan) => emit::mechanism(&desc, &model, &plan).into(),
        Err(links) => {
            let names: Vec<String> = links.iter().map(|&l| format!("`{}`", model.links[l].name)).collect();
            let diag = Diagnostic {
                spans: links.iter().map(|&l| desc.locate(&model, mech_core::resolve::Culprit::Link(l))).collect(),
                message: format!(
                    "links {} cannot be solved group by group from the inputs: no Assur group of them has as many equations as unknowns; check the joints and inputs",
                    names.join(", ")
                ),
            };
            emit::outline(&desc, Some(&model), &[diag]).into()
        }
    }
}

/// The whole pipeline on text, for the snapshot tests: parse → resolve → validate →
/// plan → emit, returning the generated code or the diagnostics' messages.
#[cfg(test)]
fn expand_str(text: &str) -> Result<proc_macro2::TokenStream, Vec<String>> {
    let desc = mech_core::dsl::parse_str(text).map_err(|e| vec![e.to_string()])?;
    let model = resolve(&desc).map_err(|d| d.into_iter().map(|d| d.message).collect::<Vec<_>>())?;
    let issues = mech_core::validate::check(&model);
    if !issues.is_empty() {
        return Err(issues.into_iter().map(|i| i.message).collect());
    }
    let plan = mech_core::assur::plan(&model).map_err(|_| vec!["no plan".to_string()])?;
    Ok(emit::mechanism(&desc, &model, &plan))
}

#[cfg(test)]
mod snapshots {
    //! Snapshots of the expanded code (prettyplease): a change in what the macro emits
    //! shows up as a reviewable diff (`cargo insta review`, or INSTA_UPDATE=always).

    fn pretty(text: &str) -> String {
        let tokens = super::expand_str(text).unwrap_or_else(|e| panic!("{e:?}"));
        prettyplease::unparse(&syn::parse2(tokens).expect("the generated code parses as a file"))
    }

    #[test]
    fn slider_crank_expansion() {
        insta::assert_snapshot!(pretty(
            r#"
            /// Offset slider-crank.
            pub struct SliderCrank {
                gravity: (0.0, -9.81),
                ground { O2: (0.0, 0.0) },
                link crank { points { O2, A: (0.038302, 0.032139) }, mass: 1.2, inertia: 2.1e-3, cg: (0.0089, 0.0127) },
                link rod { points { A, B: (0.237285, 0.012) }, mass: 2.4, inertia: 9.5e-3, cg: (0.1030, 0.0256) },
                link piston { points { B }, mass: 1.7, cg: (0.237285, 0.012) },
                joints {
                    O2: revolute(ground, crank),
                    A: revolute(crank, rod),
                    B: revolute(rod, piston),
                    guide: prismatic(ground, piston) at B along (1.0, 0.0),
                },
                input: O2,
                loads { gas: force on piston at B, load: torque on crank },
            }
            "#
        ));
    }

    #[test]
    fn massless_four_bar_without_gravity_has_no_inertia_or_gravity_terms() {
        let code = pretty(
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
        assert!(!code.contains("add_inertia"), "massless links must not get inertia terms");
        assert!(!code.contains("add_gravity"), "no gravity declared: no gravity terms");
        assert!(code.contains("add_torque"));
        insta::assert_snapshot!(code);
    }
}
