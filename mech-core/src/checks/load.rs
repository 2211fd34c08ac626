//! Loading: DSL text, or the tokens of a `mechanism! { ... }`, through the whole front end
//! and every check — parse → resolve → validate → plan — written once and called by the
//! macro (on its tokens, [`check`]) and by the run-time `Mechanism` (on text,
//! [`parse_model`], [`rust_source_model`]). A rejected mechanism gives every problem at
//! once, each located in the text.

use crate::checks::validate;
use crate::front::dsl::parse_str;
use crate::front::report::location;
use crate::front::resolve::{resolve, Culprit, Diagnostic};
use crate::model::{Description, Model};
use crate::plan::assur::{self, Group};
use crate::MechError;
use proc_macro2::Span;

/// A description the checks refused: the resolved model when resolution got that far
/// (`None` when a name did not resolve), and every diagnostic, each with its spans.
#[derive(Debug)]
pub struct Rejected {
    /// The model, when names resolved (the checks after resolution need it to locate).
    pub model: Option<Model>,
    /// Every problem found, with the spans of its culprits and the message.
    pub diagnostics: Vec<Diagnostic<Span>>,
}

/// Resolve, validate and plan a parsed description: the model and its Assur plan (groups
/// in solving order), or every problem found. The macro's pipeline after parsing, and the
/// run-time loader's.
pub fn check(desc: &Description<Span>) -> Result<(Model, Vec<Group>), Rejected> {
    let model = resolve(desc).map_err(|diagnostics| Rejected {
        model: None,
        diagnostics,
    })?;
    let issues = validate::check(&model);
    if !issues.is_empty() {
        let diagnostics = issues.iter().map(|i| desc.diagnostic(&model, i)).collect();
        return Err(Rejected {
            model: Some(model),
            diagnostics,
        });
    }
    match assur::plan(&model) {
        Ok(plan) => Ok((model, plan)),
        Err(links) => {
            let names: Vec<String> = links
                .iter()
                .map(|&l| format!("`{}`", model.links[l].name))
                .collect();
            let spans = links
                .iter()
                .map(|&l| desc.locate(&model, Culprit::Link(l)))
                .collect();
            let message = format!(
                "links {} cannot be solved group by group from the inputs: no Assur group of them has as many equations as unknowns; check the joints and inputs",
                names.join(", ")
            );
            Err(Rejected {
                model: Some(model),
                diagnostics: vec![Diagnostic { spans, message }],
            })
        }
    }
}

/// [`check`] of a parsed description, its problems rendered against `source` (`origin`
/// naming the file) as one [`MechError::Invalid`]: the checked model.
fn checked_model(
    desc: &Description<Span>,
    source: &str,
    origin: Option<&str>,
) -> Result<Model, MechError> {
    check(desc)
        .map(|(model, _)| model)
        .map_err(|r| invalid(source, origin, &r.diagnostics))
}

/// A syntax error as [`MechError::Invalid`], rendered against `source` ([`crate::front::report`]).
fn syntax(source: &str, origin: Option<&str>, e: syn::Error) -> MechError {
    MechError::Invalid(crate::front::report::render_syntax(source, origin, &e))
}

/// The checks' diagnostics as [`MechError::Invalid`], rendered against `source`.
fn invalid(source: &str, origin: Option<&str>, diags: &[Diagnostic<Span>]) -> MechError {
    MechError::Invalid(crate::front::report::render(source, origin, diags))
}

/// The `mechanism! { ... }` invocation declaring `pub struct name` in Rust source text:
/// its braced group of tokens and the parsed description (spans located in `source`).
fn find_declaration(
    source: &str,
    name: &str,
) -> Result<(proc_macro2::Group, Description<Span>), MechError> {
    use proc_macro2::TokenTree;
    let tokens: proc_macro2::TokenStream = source.parse().map_err(|e: proc_macro2::LexError| {
        MechError::Invalid(format!("{}: {e}", location(&e.span())))
    })?;
    let mut found = Vec::new();
    let mut stack = vec![tokens];
    while let Some(ts) = stack.pop() {
        let tt: Vec<TokenTree> = ts.into_iter().collect();
        for (i, t) in tt.iter().enumerate() {
            let TokenTree::Group(g) = t else { continue };
            let invoked = i >= 2
                && matches!(&tt[i - 2], TokenTree::Ident(id) if id == "mechanism")
                && matches!(&tt[i - 1], TokenTree::Punct(p) if p.as_char() == '!');
            if !invoked {
                stack.push(g.stream());
                continue;
            }
            match syn::parse2::<crate::front::dsl::Parsed>(g.stream()) {
                Ok(p) if p.0.name.text == name => return Ok((g.clone(), p.0)),
                Ok(p) => found.push(p.0.name.text),
                Err(e) if g.stream().to_string().contains(&format!("struct {name} ")) => {
                    return Err(syntax(source, None, e))
                }
                Err(_) => {}
            }
        }
    }
    Err(MechError::Invalid(format!(
        "no `mechanism!` declares `{name}` here; found: {}",
        found.join(", ")
    )))
}

/// The DSL text of the mechanism `name` declared with `mechanism! { ... }` in Rust source
/// `source`: the text between the invocation's braces, as written (for
/// `Mechanism::from_dsl`, a `.mech` file, or editing). [`MechError::Invalid`] when the
/// source does not tokenize or declares no such mechanism.
pub fn mechanism_text<'a>(source: &'a str, name: &str) -> Result<&'a str, MechError> {
    let (group, _) = find_declaration(source, name)?;
    Ok(&source[group.span_open().byte_range().end..group.span_close().byte_range().start])
}

/// The largest text the loader reads, bytes (the largest example is a few kB).
pub const MAX_TEXT: usize = 4 << 20;

/// The deepest nesting of brackets, and the longest run of signs (`- - - 1`), in a text
/// the loader reads: the parser is recursive, and a deeper text would overflow its stack.
pub const MAX_NESTING: usize = 64;

/// Refuse, before any parsing, a text the parser must not be given: over [`MAX_TEXT`]
/// bytes, holding a NUL (binary data), or nested deeper than [`MAX_NESTING`] brackets or
/// signs (comments `//` skipped). [`MechError::Invalid`] locates it as `origin:line:col`.
pub fn check_text(text: &str, origin: Option<&str>) -> Result<(), MechError> {
    let origin = origin.unwrap_or("the text");
    if text.len() > MAX_TEXT {
        return Err(MechError::Invalid(format!(
            "{origin}: {:.1} MB of text, more than the {} MB a mechanism may have; is it the right text?",
            text.len() as f64 / (1 << 20) as f64,
            MAX_TEXT >> 20
        )));
    }
    if let Some(at) = text.find('\0') {
        return Err(MechError::Invalid(format!(
            "{origin}: a NUL character at offset {at}: binary data, not a mechanism's text"
        )));
    }
    let (mut depth, mut run, mut line, mut col) = (0usize, 0usize, 1usize, 0usize);
    let mut chars = text.chars().peekable();
    while let Some(c) = chars.next() {
        col += 1;
        match c {
            '\n' => {
                line += 1;
                col = 0;
                continue;
            }
            '/' if chars.peek() == Some(&'/') => {
                for c in chars.by_ref() {
                    if c == '\n' {
                        line += 1;
                        col = 0;
                        break;
                    }
                }
                run = 0;
                continue;
            }
            '(' | '[' | '{' => {
                depth += 1;
                run = 0;
            }
            ')' | ']' | '}' => {
                depth = depth.saturating_sub(1);
                run = 0;
            }
            '-' | '+' | '!' => run += 1,
            c if c.is_whitespace() => {}
            _ => run = 0,
        }
        if depth > MAX_NESTING || run > MAX_NESTING {
            let what = if depth > MAX_NESTING {
                format!("brackets nested more than {MAX_NESTING} deep")
            } else {
                format!("more than {MAX_NESTING} signs in a row")
            };
            return Err(MechError::Invalid(format!(
                "{origin}:{line}:{col}: {what}; write the expression flatter"
            )));
        }
    }
    Ok(())
}

/// The checked model of DSL text (every check of the macro; messages located in the
/// text, `origin` naming it): what both run-time solvers are built from. The text is
/// first held to [`check_text`].
pub fn parse_model(text: &str, origin: Option<&str>) -> Result<Model, MechError> {
    check_text(text, origin)?;
    on_own_thread(|| {
        let desc = parse_str(text).map_err(|e| syntax(text, origin, e))?;
        checked_model(&desc, text, origin)
    })
}

/// A dimension written `free(LO..HI)` in a mechanism's text (`mech size` chooses it).
#[derive(Clone, Debug, PartialEq)]
pub struct FreeDimension {
    /// The link whose shape it is a dimension of.
    pub link: String,
    /// The dimension's name (`width`, `thickness`, `diameter`, `outer`, `inner`, `radius`).
    pub name: String,
    /// LO, m.
    pub lo: f64,
    /// HI, m.
    pub hi: f64,
    /// The bytes of `free(LO..HI)` in the text.
    pub range: std::ops::Range<usize>,
}

/// The dimensions written `free(LO..HI)` in DSL text, in the order written; a syntax
/// error as [`parse_model`]'s.
pub fn free_dimensions(text: &str, origin: Option<&str>) -> Result<Vec<FreeDimension>, MechError> {
    check_text(text, origin)?;
    on_own_thread(|| {
        let desc = parse_str(text).map_err(|e| syntax(text, origin, e))?;
        let mut out = Vec::new();
        for link in &desc.links {
            let Some(shape) = &link.shape else { continue };
            let names =
                crate::model::shape::Shape::dimension_names(&shape.keyword).unwrap_or_default();
            for (free, name) in shape.free.iter().zip(names) {
                if let Some(f) = free {
                    let start = crate::front::report::offset(text, f.span.start());
                    let end = crate::front::report::offset(text, f.end.end());
                    out.push(FreeDimension {
                        link: link.name.text.clone(),
                        name: name.to_string(),
                        lo: f.lo,
                        hi: f.hi,
                        range: start..end,
                    });
                }
            }
        }
        Ok(out)
    })
}

/// The checked model of the mechanism `name` declared in Rust source text.
pub fn rust_source_model(source: &str, name: &str) -> Result<Model, MechError> {
    check_text(source, None)?;
    on_own_thread(|| checked_model(&find_declaration(source, name)?.1, source, None))
}

/// Run `f` (a parse and its checks) on a thread of its own: proc-macro2 keeps every parsed
/// text in a table of its thread for the spans' locations, so parsing on the caller's
/// thread would keep every text alive (and past 4 GiB on one thread wrap the locations);
/// the table goes with the thread. The model and the messages come back as plain data.
fn on_own_thread<T: Send>(f: impl FnOnce() -> Result<T, MechError> + Send) -> Result<T, MechError> {
    std::thread::scope(|s| {
        s.spawn(f).join().unwrap_or_else(|p| {
            let what = p
                .downcast_ref::<String>()
                .cloned()
                .or_else(|| p.downcast_ref::<&str>().map(|s| s.to_string()))
                .unwrap_or_default();
            Err(MechError::Internal(format!(
                "the loader panicked while reading the mechanism's text: {what}"
            )))
        })
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Deep nesting and long sign runs are refused with where they are, before the
    /// recursive parser could overflow its thread's stack (it did on 10⁵ brackets).
    #[test]
    fn texts_the_parser_must_not_see_are_refused_with_their_place() {
        let deep = format!(
            "consts {{ a: {}1{} }}",
            "(".repeat(100_000),
            ")".repeat(100_000)
        );
        let e = parse_model(&deep, Some("deep.mech"))
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("deep.mech:1:") && e.contains("nested more than 64 deep"),
            "{e}"
        );
        let signs = format!("consts {{ a: {}1 }}", "- ".repeat(100_000));
        let e = parse_model(&signs, None).unwrap_err().to_string();
        assert!(e.contains("more than 64 signs in a row"), "{e}");
        let e = parse_model("ground { O: (0.0, 0.0) }\0", None)
            .unwrap_err()
            .to_string();
        assert!(e.contains("NUL character at offset 24"), "{e}");
        let big = "// x\n".repeat(MAX_TEXT / 5 + 1);
        assert!(parse_model(&big, None)
            .unwrap_err()
            .to_string()
            .contains("MB of text"));
        let e = rust_source_model(&format!("fn f() {{ {} }}", "[".repeat(1000)), "M")
            .unwrap_err()
            .to_string();
        assert!(e.contains("nested more than 64 deep"), "{e}");
        // Comments do not count, and 64 levels still parse as far as the grammar goes.
        assert!(check_text(&format!("// {}\n", "(".repeat(1000)), None).is_ok());
        assert!(check_text(&format!("{}1{}", "(".repeat(64), ")".repeat(64)), None).is_ok());
    }
}
