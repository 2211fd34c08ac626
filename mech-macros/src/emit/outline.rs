//! What the macro emits for a mechanism with errors: every diagnostic as a
//! `compile_error!`, and the outline of the generated types.

use super::names::Names;
use mech_core::front::resolve::Diagnostic;
use mech_core::model::{Description, Model};
use proc_macro2::{Span, TokenStream};
use quote::quote;

/// Every diagnostic as `compile_error!`s: the message at the culprit, a short pointer at
/// each other declaration involved.
pub fn errors(diags: &[Diagnostic<Span>]) -> TokenStream {
    let mut out = TokenStream::new();
    for d in diags {
        let first = d.message.split(':').next().unwrap_or("");
        for (i, span) in d.spans.iter().enumerate() {
            let msg = if i == 0 {
                d.message.clone()
            } else {
                format!("involved here: {first} (see the first error)")
            };
            out.extend(syn::Error::new(*span, msg).to_compile_error());
        }
    }
    out
}

/// On error: the errors, and the struct's outline (empty types with the public names) so
/// that code using the mechanism does not add a cascade of unrelated errors.
pub fn outline(
    desc: &Description<Span>,
    _model: Option<&Model>,
    diags: &[Diagnostic<Span>],
) -> TokenStream {
    let errs = errors(diags);
    let Names {
        main,
        params,
        loads,
        pose,
        motion,
        forces,
        ..
    } = Names::new(desc);
    quote! {
        #errs
        /// (not generated: the mechanism has errors)
        #[derive(Clone, Debug, Default)]
        pub struct #main;
        /// (not generated: the mechanism has errors)
        #[derive(Clone, Debug, Default)]
        pub struct #params;
        /// (not generated: the mechanism has errors)
        #[derive(Clone, Debug, Default)]
        pub struct #loads;
        /// (not generated: the mechanism has errors)
        #[derive(Clone, Debug, Default)]
        pub struct #pose;
        /// (not generated: the mechanism has errors)
        #[derive(Clone, Debug, Default)]
        pub struct #motion;
        /// (not generated: the mechanism has errors)
        #[derive(Clone, Debug, Default)]
        pub struct #forces;
        impl #main {
            /// (not generated: the mechanism has errors)
            pub fn new() -> Self { #main }
        }
    }
}
