//! A number of a mechanism's text found by name and written anew, so that a design tool
//! (`mech optimize`) can hand back an ordinary mechanism file.
//!
//! Names: a constant of the `consts { .. }` block (`l`, or `consts.l`), and a link's
//! `mass` or `inertia` (`links.crank.mass`). The value's text runs from after its `:` to
//! the next `,` or closing brace at the same depth (brackets and parentheses nest;
//! comments are skipped).
//!
//! A point's coordinates are found the same way ([`point`]: `A: (0.04, 0.069)` in the
//! `ground` block or a link's `points` block) and written anew in their unit words
//! ([`move_point`]), for a point dragged on `mech serve`'s page.

use crate::model::units::{all_words, lookup, Unit};
use std::ops::Range;

/// Calls `f` with each byte offset and character of `text[range]` outside `//` comments
/// and the nesting depth there relative to the range's start (an opening bracket counts
/// at the outer depth, a closing one at the outer depth too); stops when `f` says false.
fn scan(text: &str, range: Range<usize>, mut f: impl FnMut(usize, char, i32) -> bool) {
    let bytes = &text[range.clone()];
    let mut depth = 0;
    let mut it = bytes.char_indices().peekable();
    while let Some((i, c)) = it.next() {
        if c == '/' && it.peek().is_some_and(|&(_, n)| n == '/') {
            for (_, n) in it.by_ref() {
                if n == '\n' {
                    break;
                }
            }
            continue;
        }
        let before = depth;
        match c {
            '(' | '[' | '{' => depth += 1,
            ')' | ']' | '}' => depth -= 1,
            _ => {}
        }
        if !f(range.start + i, c, before.min(depth)) {
            return;
        }
    }
}

/// Whether `text[at..]` starts the word `word` (not inside a longer identifier).
fn word_at(text: &str, at: usize, word: &str) -> bool {
    let ident = |c: char| c.is_alphanumeric() || c == '_';
    text[at..].starts_with(word)
        && !text[..at].chars().next_back().is_some_and(ident)
        && !text[at + word.len()..].chars().next().is_some_and(ident)
}

/// The body (inside the braces) of the first block of `range` that follows the words
/// `head` (`consts`, `link crank`), outside comments.
fn block(text: &str, range: Range<usize>, head: &[&str]) -> Option<Range<usize>> {
    let mut found = None;
    scan(text, range.clone(), |i, _, _| {
        if word_at(text, i, head[0]) {
            // The remaining words, then `{`.
            let mut at = i + head[0].len();
            for w in &head[1..] {
                let skip = text[at..].len() - text[at..].trim_start().len();
                at += skip;
                if !word_at(text, at, w) {
                    return true;
                }
                at += w.len();
            }
            let skip = text[at..].len() - text[at..].trim_start().len();
            if text[at + skip..].starts_with('{') {
                found = Some(at + skip + 1);
                return false;
            }
        }
        true
    });
    let start = found?;
    let mut end = None;
    scan(text, start..range.end, |i, c, depth| {
        if c == '}' && depth < 0 {
            end = Some(i);
            return false;
        }
        true
    });
    Some(start..end?)
}

/// The value of the entry `key:` at depth 0 of the block body `body`.
fn entry(text: &str, body: Range<usize>, key: &str) -> Option<Range<usize>> {
    let mut start = None;
    scan(text, body.clone(), |i, _, depth| {
        if depth == 0 && word_at(text, i, key) {
            let after = i + key.len();
            let skip = text[after..].len() - text[after..].trim_start().len();
            if text[after + skip..].starts_with(':') {
                start = Some(after + skip + 1);
                return false;
            }
        }
        true
    });
    let start = start?;
    let mut end = body.end;
    scan(text, start..body.end, |i, c, depth| {
        if depth == 0 && c == ',' {
            end = i;
            return false;
        }
        true
    });
    // Trim the value's own surrounding white space.
    let value = &text[start..end];
    let lead = value.len() - value.trim_start().len();
    Some(start + lead..start + value.trim_end().len())
}

/// The bytes of the value named `name` in `text` (a constant, or `links.<l>.mass` /
/// `links.<l>.inertia`), if it is written there.
pub fn find(text: &str, name: &str) -> Option<Range<usize>> {
    let whole = 0..text.len();
    let parts: Vec<&str> = name.split('.').collect();
    match parts.as_slice() {
        ["links", link, key @ ("mass" | "inertia")] => {
            let body = block(text, whole, &["link", link])?;
            entry(text, body, key)
        }
        ["consts", c] | [c] => {
            let body = block(text, whole, &["consts"])?;
            entry(text, body, c)
        }
        _ => None,
    }
}

/// A number as a mechanism's text writes it, with an optional unit word (`143 mm`, `0.5`,
/// `6.8e-3 kg_m2`): its value in SI and the unit word. Errors: not a number (an
/// expression, say), or a word that is no unit (naming the words).
pub fn number(written: &str) -> Result<(f64, Option<&'static Unit>), String> {
    let w = written.trim();
    let split = w
        .find(|c: char| c.is_alphabetic() && c != 'e' && c != 'E')
        .unwrap_or(w.len());
    let x: f64 = w[..split]
        .trim()
        .parse()
        .map_err(|_| format!("`{w}` is not a number with an optional unit word"))?;
    match w[split..].trim() {
        "" => Ok((x, None)),
        word => lookup(word)
            .map(|u| (x * u.factor, Some(u)))
            .ok_or_else(|| format!("unknown unit `{word}`; the words are {}", all_words())),
    }
}

/// The bytes of the two coordinates of point `name` where `text` first places it: in the
/// `ground { .. }` block (`O2: (0.0, 0.0)`, or its `points { .. }`) or a link's
/// `points { .. }` block (`A: (0.04, 0.069)`), the first text of each coordinate in the
/// parentheses (white space trimmed). None when the point is not written there with a
/// parenthesized pair (a point given as an expression, `A: O2 + polar(r, 30 deg)`).
pub fn point(text: &str, name: &str) -> Option<[Range<usize>; 2]> {
    let whole = 0..text.len();
    let mut lists = Vec::new();
    if let Some(g) = block(text, whole.clone(), &["ground"]) {
        lists.push(g);
    }
    let mut from = 0;
    while let Some(b) = block(text, from..text.len(), &["points"]) {
        from = b.end;
        lists.push(b);
    }
    lists.sort_by_key(|r| r.start);
    lists
        .iter()
        .find_map(|body| pair(text, entry(text, body.clone(), name)?))
}

/// The two coordinates' bytes of a value `(x, y)` at `value` (nothing else around it).
fn pair(text: &str, value: Range<usize>) -> Option<[Range<usize>; 2]> {
    let v = &text[value.clone()];
    if !v.starts_with('(') || !v.ends_with(')') {
        return None;
    }
    let inner = value.start + 1..value.end - 1;
    let mut comma = None;
    let mut whole = true;
    scan(text, inner.clone(), |i, c, depth| {
        if depth < 0 {
            whole = false;
            return false;
        }
        if depth == 0 && c == ',' {
            if comma.is_some() {
                whole = false;
                return false;
            }
            comma = Some(i);
        }
        true
    });
    let comma = comma.filter(|_| whole)?;
    let trim = |r: Range<usize>| {
        let t = &text[r.clone()];
        let lead = t.len() - t.trim_start().len();
        r.start + lead..r.start + t.trim_end().len()
    };
    let (x, y) = (trim(inner.start..comma), trim(comma + 1..inner.end));
    (!x.is_empty() && !y.is_empty()).then_some([x, y])
}

/// `text` with point `name`'s coordinates written as `xy` (m), each in the unit word its
/// old number had (`40 mm` stays in mm), rounded to `step` (m; 0 for none); nothing else
/// of the text changes. Errors: the point is not written as `(x, y)`, or a coordinate is
/// not a plain number (an expression, a constant's name).
pub fn move_point(text: &str, name: &str, xy: [f64; 2], step: f64) -> Result<String, String> {
    let ranges = point(text, name).ok_or_else(|| {
        format!("point `{name}` is not written as `{name}: (x, y)` in a `ground` or `points` block")
    })?;
    let mut edits = Vec::new();
    for (r, v) in ranges.into_iter().zip(xy) {
        let old = &text[r.clone()];
        let (_, unit) = number(old).map_err(|_| {
            format!("point `{name}`: `{old}` is not a plain number (an expression or a name): edit it in the file")
        })?;
        if !v.is_finite() {
            return Err(format!(
                "point `{name}`: the new coordinate {v} is not finite"
            ));
        }
        let factor = unit.map_or(1.0, |u| u.factor);
        let x = v / factor;
        let s = if step > 0.0 {
            let digits = (-(step / factor).log10().floor()).clamp(0.0, 15.0) as usize;
            let t = format!("{x:.digits$}");
            let t = if t.contains('.') {
                t.trim_end_matches('0').trim_end_matches('.').to_string()
            } else {
                t
            };
            if t == "-0" || t.is_empty() {
                "0".to_string()
            } else {
                t
            }
        } else {
            format!("{x:?}")
        };
        // Keep a written decimal point where the old number had one (`0.0` stays a float).
        let s = if old.contains('.') && !s.contains('.') && !s.contains('e') {
            format!("{s}.0")
        } else {
            s
        };
        edits.push((
            r,
            match unit {
                Some(u) => format!("{s} {}", u.word),
                None => s,
            },
        ));
    }
    Ok(replace(text, &edits))
}

/// `text` with each (range, replacement) written in (ranges from [`find`], disjoint).
pub fn replace(text: &str, edits: &[(Range<usize>, String)]) -> String {
    let mut order: Vec<&(Range<usize>, String)> = edits.iter().collect();
    order.sort_by_key(|e| std::cmp::Reverse(e.0.start));
    let mut out = text.to_string();
    for (r, s) in order {
        out.replace_range(r.clone(), s);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    const TEXT: &str = "pub struct E {
    consts { stroke: 86 mm, r: stroke / 2, l: 143 mm, e: 6 mm },
    ground { O2: (0.0, 0.0) },
    link crank {
        points { O2, A: O2 + polar(r, 30 deg) },
        // the cg 5 mm behind: mass: 9
        mass: 3.6 kg, inertia: 6.8e-3 kg_m2, cg: along(-5 mm),
    },
    link crank2 { points { A }, mass: 1.0 },
}";

    #[test]
    fn points_are_found_and_moved_keeping_the_rest() {
        let text = "pub struct F {
    ground { O2: (0.0, 0.0), O4: (300 mm, 40 mm) }, // O4: (9, 9)
    link crank { points { O2, A: ( 0.04 , 0.06928 ) }, mass: 1 },
    link rod { points { A, B: (l, 0.1) } },
}";
        let at = |n: &str| point(text, n).map(|[x, y]| (&text[x], &text[y]));
        assert_eq!(at("O2"), Some(("0.0", "0.0")));
        assert_eq!(at("O4"), Some(("300 mm", "40 mm")));
        assert_eq!(at("A"), Some(("0.04", "0.06928")));
        assert_eq!(at("B"), Some(("l", "0.1")));
        assert_eq!(at("C"), None);
        let moved = move_point(text, "A", [0.05, -0.0712345], 1e-5).unwrap();
        assert_eq!(
            moved,
            text.replace("( 0.04 , 0.06928 )", "( 0.05 , -0.07123 )")
        );
        let moved = move_point(text, "O4", [0.31, 0.0], 1e-5).unwrap();
        assert_eq!(moved, text.replacen("(300 mm, 40 mm)", "(310 mm, 0 mm)", 1));
        let moved = move_point(text, "O2", [0.1, 0.2], 1e-5).unwrap();
        assert!(moved.contains("O2: (0.1, 0.2)"), "{moved}");
        assert!(move_point(text, "B", [0.0, 0.0], 1e-5)
            .unwrap_err()
            .contains("not a plain number"));
        assert!(move_point(text, "C", [0.0, 0.0], 1e-5).is_err());
    }

    #[test]
    fn constants_and_link_values_are_found_by_name() {
        let at = |n: &str| find(TEXT, n).map(|r| &TEXT[r]);
        assert_eq!(at("l"), Some("143 mm"));
        assert_eq!(at("consts.r"), Some("stroke / 2"));
        assert_eq!(at("e"), Some("6 mm"));
        assert_eq!(at("links.crank.mass"), Some("3.6 kg"));
        assert_eq!(at("links.crank.inertia"), Some("6.8e-3 kg_m2"));
        assert_eq!(at("links.crank2.mass"), Some("1.0"));
        assert_eq!(at("links.rod.mass"), None);
        assert_eq!(at("stroke2"), None);
        let out = replace(
            TEXT,
            &[
                (find(TEXT, "l").unwrap(), "150 mm".into()),
                (find(TEXT, "links.crank.mass").unwrap(), "4 kg".into()),
            ],
        );
        assert!(
            out.contains("l: 150 mm, e: 6 mm") && out.contains("mass: 4 kg, inertia"),
            "{out}"
        );
    }
}
