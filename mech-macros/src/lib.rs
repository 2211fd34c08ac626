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

/// Declare a planar mechanism; see the crate `mech` and SPEC section 3 for the grammar.
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
