use proc_macro::TokenStream;
#[proc_macro]
pub fn mechanism(t: TokenStream) -> TokenStream { t }
