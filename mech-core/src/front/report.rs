//! Diagnostics of a mechanism loaded from text, rendered the way the compiler renders the
//! macro's: each check's message with its line and column in the text, the offending line
//! with the culprit underlined, and the other declarations involved (`annotate-snippets`).
//!
//! Each rendered error starts with a line `LINE:COLUMN: message` (1-based), or
//! `FILE:LINE:COLUMN: message` when the text came from a named file, so a program (or an
//! editor) can find the location.

use crate::front::resolve::Diagnostic;
use annotate_snippets::{Level, Renderer, Snippet};
use proc_macro2::{LineColumn, Span};
use std::ops::Range;

/// The byte offset in `source` of a line and column (1-based line, 0-based column in chars).
pub(crate) fn offset(source: &str, lc: LineColumn) -> usize {
    let mut at = 0;
    for (i, line) in source.split_inclusive('\n').enumerate() {
        if i + 1 == lc.line {
            return at
                + line
                    .char_indices()
                    .nth(lc.column)
                    .map_or(line.trim_end_matches('\n').len(), |(b, _)| b);
        }
        at += line.len();
    }
    source.len()
}

/// The byte range of `span` in `source`, at least one character wide.
fn range(source: &str, span: &Span) -> Range<usize> {
    let (a, b) = (offset(source, span.start()), offset(source, span.end()));
    if b > a {
        a..b
    } else {
        let end = source[a..].chars().next().map_or(a, |c| a + c.len_utf8());
        a..end
    }
}

/// `line:column` (1-based) of a span.
pub fn location(span: &Span) -> String {
    let lc = span.start();
    format!("{}:{}", lc.line, lc.column + 1)
}

/// One error: `LINE:COL: message`, then the excerpt with the culprit (`spans[0]`) and the
/// other declarations involved (`spans[1..]`) underlined.
fn render_one(source: &str, origin: Option<&str>, message: &str, spans: &[Span]) -> String {
    let Some(first) = spans.first() else {
        return message.to_string();
    };
    let head = match origin {
        Some(o) => format!("{o}:{}: {message}", location(first)),
        None => format!("{}: {message}", location(first)),
    };
    let mut snippet = Snippet::source(source).line_start(1).fold(true);
    if let Some(o) = origin {
        snippet = snippet.origin(o);
    }
    for (i, s) in spans.iter().enumerate() {
        let r = range(source, s);
        snippet = snippet.annotation(if i == 0 {
            Level::Error.span(r).label("here")
        } else {
            Level::Info.span(r).label("involved")
        });
    }
    let title = message.split(':').next().unwrap_or(message);
    let rendered = Renderer::plain()
        .render(Level::Error.title(title).snippet(snippet))
        .to_string();
    format!("{head}\n{rendered}")
}

/// Every diagnostic of the checks, rendered against the text they were found in
/// (`origin`: a file name shown in the excerpt's `-->` line, if any), blank-line separated.
pub fn render(source: &str, origin: Option<&str>, diags: &[Diagnostic<Span>]) -> String {
    diags
        .iter()
        .map(|d| render_one(source, origin, &d.message, &d.spans))
        .collect::<Vec<_>>()
        .join("\n\n")
}

/// A syntax error (every message of it), rendered as [`render`] does.
pub fn render_syntax(source: &str, origin: Option<&str>, e: &syn::Error) -> String {
    e.clone()
        .into_iter()
        .map(|e| render_one(source, origin, &e.to_string(), &[e.span()]))
        .collect::<Vec<_>>()
        .join("\n\n")
}
