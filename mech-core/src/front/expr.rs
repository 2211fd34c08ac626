//! Expressions of the DSL (`docs/conventions.md#dimensions`), parsed and evaluated to SI
//! at once, in the order they are written, so that the macro's checks see numbers.
//!
//! ```text
//! expr    := term (('+' | '-') term)*
//! term    := unary (('*' | '/') unary)*
//! unary   := '-' unary | atom
//! atom    := literal [unit] | '(' expr ')' [unit] | PI | CONST | FUNC '(' expr, ... ')'
//! FUNC    := sqrt | sin | cos | tan | atan2 | hypot | to_radians
//! ```
//!
//! Each value is a [`Quantity`]: its SI value and, when a unit word was involved, its
//! dimension ([`crate::model::units::Dim`]). A plain number has no dimension (it is SI of what
//! goes there); a sum of two different dimensions, a unit on what already has one, a
//! length where an angle goes, a division by zero, an unknown name: each is a
//! `syn::Error` at the culprit's span, with the numbers and the fix.

use crate::model::units::{self, Dim};
use proc_macro2::Span;
use syn::parse::ParseStream;
use syn::{parenthesized, Ident, LitFloat, LitInt, Token};

/// A number of the DSL evaluated to SI.
#[derive(Clone, Copy, Debug)]
pub struct Quantity {
    /// The value in SI units (m, kg, kg·m², rad, N, N·m, ...).
    pub value: f64,
    /// Its dimension when a unit word fixed one; `None` for a plain number.
    pub dim: Option<Dim>,
    /// Where it was written (its first token).
    pub span: Span,
}

impl Quantity {
    fn plain(value: f64, span: Span) -> Self {
        Quantity {
            value,
            dim: None,
            span,
        }
    }

    /// The dimension, a plain number and a dimensionless ratio alike giving `None`.
    fn physical(self) -> Option<Dim> {
        self.dim.filter(|d| *d != Dim::NONE)
    }

    /// The value where a quantity of dimension `want` goes: a plain number is taken as
    /// SI; a number with a unit must have that dimension. `what` names the slot
    /// ("a point's x coordinate").
    pub fn expect(self, want: Dim, what: &str) -> syn::Result<f64> {
        match self.physical() {
            Some(d) if d != want => Err(syn::Error::new(
                self.span,
                format!(
                    "{what} is {}, but this value is {}: write it with {}, or as a plain number in {}",
                    want.describe(),
                    d.describe(),
                    want.words(),
                    si_unit(want)
                ),
            )),
            _ => Ok(self.value),
        }
    }
}

/// The words that name the next property of a force element
/// (`stiffness 2 kN_per_m free_length 80 mm`) or a cam segment's lift (`90 deg rise
/// 10 mm`): an expression ends before them.
pub const PROPERTY_WORDS: [&str; 7] = [
    "stiffness",
    "damping",
    "free_length",
    "free_angle",
    "preload",
    "rise",
    "fall",
];

fn si_unit(d: Dim) -> String {
    d.describe()
        .rsplit_once('(')
        .map(|(_, u)| u.trim_end_matches(')').to_string())
        .unwrap_or_else(|| d.to_string())
}

/// The named constants declared so far (`consts { r: 200 mm, l: 4.5 * r }`).
#[derive(Clone, Debug, Default)]
pub struct Constants {
    items: Vec<(String, Quantity)>,
}

/// The functions of the DSL and their number of arguments.
const FUNCTIONS: [(&str, usize); 7] = [
    ("sqrt", 1),
    ("sin", 1),
    ("cos", 1),
    ("tan", 1),
    ("atan2", 2),
    ("hypot", 2),
    ("to_radians", 1),
];

/// Names that cannot be constants.
const RESERVED: [&str; 6] = [
    "PI",
    "polar",
    "circle_circle",
    "circle_line",
    "along",
    "local",
];

impl Constants {
    /// The constant `name`, if declared.
    pub fn get(&self, name: &str) -> Option<Quantity> {
        self.items.iter().find(|(n, _)| n == name).map(|(_, q)| *q)
    }

    /// Declare `name` = `q`; an error at `id` when the name is taken or reserved.
    pub fn declare(&mut self, id: &Ident, q: Quantity) -> syn::Result<()> {
        let name = id.to_string();
        if name.starts_with("r#") {
            return Err(syn::Error::new(id.span(), format!("`{name}` is a raw identifier, which the DSL does not take as a name: rename it")));
        }
        if self.get(&name).is_some() {
            return Err(syn::Error::new(
                id.span(),
                format!("constant `{name}` is declared twice: give the second another name"),
            ));
        }
        if RESERVED.contains(&name.as_str())
            || FUNCTIONS.iter().any(|(f, _)| *f == name)
            || units::lookup(&name).is_some()
        {
            return Err(syn::Error::new(id.span(), format!("`{name}` is a reserved word of the DSL (a function, a unit or `PI`): name the constant otherwise")));
        }
        self.items.push((name, q));
        Ok(())
    }

    /// `consts { name: expr, ... }`: each constant may use those declared before it.
    pub fn parse_block(&mut self, input: ParseStream) -> syn::Result<()> {
        let content;
        syn::braced!(content in input);
        while !content.is_empty() {
            let id: Ident = content.parse()?;
            content.parse::<Token![:]>()?;
            let q = self.expr(&content)?;
            self.declare(&id, q)?;
            if !content.is_empty() {
                content.parse::<Token![,]>()?;
            }
        }
        Ok(())
    }

    /// A whole expression.
    pub fn expr(&self, input: ParseStream) -> syn::Result<Quantity> {
        let mut acc = self.term(input)?;
        loop {
            let minus = if input.peek(Token![+]) {
                input.parse::<Token![+]>()?;
                false
            } else if input.peek(Token![-]) {
                input.parse::<Token![-]>()?;
                true
            } else {
                return Ok(acc);
            };
            let rhs = self.term(input)?;
            let dim = same_dim(acc, rhs, if minus { "subtract" } else { "add" })?;
            let value = if minus {
                acc.value - rhs.value
            } else {
                acc.value + rhs.value
            };
            acc = finite(Quantity {
                value,
                dim,
                span: acc.span,
            })?;
        }
    }

    fn term(&self, input: ParseStream) -> syn::Result<Quantity> {
        let mut acc = self.unary(input)?;
        loop {
            let (div, op_span) = if input.peek(Token![*]) {
                (false, input.parse::<Token![*]>()?.span)
            } else if input.peek(Token![/]) {
                (true, input.parse::<Token![/]>()?.span)
            } else {
                return Ok(acc);
            };
            let rhs = self.unary(input)?;
            let dim = match (acc.dim, rhs.dim) {
                (None, None) => None,
                (a, b) => {
                    let (a, b) = (a.unwrap_or(Dim::NONE), b.unwrap_or(Dim::NONE));
                    Some(if div { a.per(b) } else { a.times(b) })
                }
            };
            if div && rhs.value == 0.0 {
                return Err(syn::Error::new(
                    op_span,
                    format!("division by zero: the divisor evaluates to {}", rhs.value),
                ));
            }
            let value = if div {
                acc.value / rhs.value
            } else {
                acc.value * rhs.value
            };
            acc = finite(Quantity {
                value,
                dim,
                span: acc.span,
            })?;
        }
    }

    fn unary(&self, input: ParseStream) -> syn::Result<Quantity> {
        if input.peek(Token![-]) {
            input.parse::<Token![-]>()?;
            let q = self.unary(input)?;
            return Ok(Quantity {
                value: -q.value,
                ..q
            });
        }
        self.atom(input)
    }

    fn atom(&self, input: ParseStream) -> syn::Result<Quantity> {
        let span = input.span();
        if input.peek(LitFloat) || input.peek(LitInt) {
            let (value, suffix) = if input.peek(LitFloat) {
                let l: LitFloat = input.parse()?;
                (l.base10_parse::<f64>()?, l.suffix().to_string())
            } else {
                let l: LitInt = input.parse()?;
                (l.base10_parse::<f64>()?, l.suffix().to_string())
            };
            let q = Quantity::plain(value, span);
            let q = if suffix.is_empty() {
                q
            } else {
                with_unit(q, &suffix, span)?
            };
            return self.unit(input, q);
        }
        if input.peek(syn::token::Paren) {
            let content;
            parenthesized!(content in input);
            let q = self.expr(&content)?;
            if !content.is_empty() {
                return Err(content.error("expected `)`: a pair `(x, y)` is not a number here"));
            }
            return self.unit(input, Quantity { span, ..q });
        }
        if input.peek(Ident) {
            let id: Ident = input.parse()?;
            let name = id.to_string();
            if input.peek(syn::token::Paren) {
                return self.call(&id, input);
            }
            if name == "PI" {
                return Ok(Quantity::plain(std::f64::consts::PI, span));
            }
            return match self.get(&name) {
                Some(q) => Ok(Quantity { span, ..q }),
                None => Err(syn::Error::new(span, self.unknown(&name))),
            };
        }
        Err(input.error("expected a number: a literal (`0.25`, `200 mm`), a constant, `PI`, a function call or `( ... )`"))
    }

    fn unknown(&self, name: &str) -> String {
        let known: Vec<&str> = self.items.iter().map(|(n, _)| n.as_str()).collect();
        let listed = if known.is_empty() {
            "none is declared yet".to_string()
        } else {
            format!("declared so far: {}", known.join(", "))
        };
        format!("unknown constant `{name}`: declare it in `consts {{ {name}: ... }}` before the section that uses it ({listed})")
    }

    /// An optional unit word after a literal or a parenthesised expression (not one of
    /// [`PROPERTY_WORDS`], which start the next property of a force element).
    fn unit(&self, input: ParseStream, q: Quantity) -> syn::Result<Quantity> {
        if !input.peek(Ident) {
            return Ok(q);
        }
        let id: Ident = input.fork().parse()?;
        let word = id.to_string();
        if units::lookup(&word).is_none()
            && (input.peek2(Token![:])
                || self.get(&word).is_some()
                || PROPERTY_WORDS.contains(&word.as_str()))
        {
            return Ok(q); // the next item or property, or a constant after a missing operator: reported by the caller
        }
        input.parse::<Ident>()?;
        with_unit(q, &word, id.span())
    }

    fn call(&self, id: &Ident, input: ParseStream) -> syn::Result<Quantity> {
        let name = id.to_string();
        let span = id.span();
        let Some(&(_, arity)) = FUNCTIONS.iter().find(|(f, _)| *f == name) else {
            let list: Vec<&str> = FUNCTIONS.iter().map(|(f, _)| *f).collect();
            return Err(syn::Error::new(
                span,
                format!(
                    "unknown function `{name}`: the functions are {}",
                    list.join(", ")
                ),
            ));
        };
        let content;
        parenthesized!(content in input);
        let mut args = Vec::new();
        while !content.is_empty() {
            args.push(self.expr(&content)?);
            if !content.is_empty() {
                content.parse::<Token![,]>()?;
            }
        }
        if args.len() != arity {
            return Err(syn::Error::new(
                span,
                format!("`{name}` takes {arity} argument(s), got {}", args.len()),
            ));
        }
        let x = args[0];
        let angle_arg = |x: Quantity| -> syn::Result<f64> {
            match x.physical() {
                Some(d) if d != Dim::ANGLE => Err(syn::Error::new(
                    x.span,
                    format!("`{name}` takes an angle, but its argument is {}: write it in `deg` or `rad`", d.describe()),
                )),
                _ => Ok(x.value),
            }
        };
        let q = match name.as_str() {
            "sqrt" => {
                if x.value < 0.0 {
                    return Err(syn::Error::new(
                        x.span,
                        format!(
                            "`sqrt` of a negative number: its argument evaluates to {}",
                            x.value
                        ),
                    ));
                }
                let dim = match x.dim {
                    None => None,
                    Some(d) => Some(d.sqrt().ok_or_else(|| {
                        syn::Error::new(
                            x.span,
                            format!("`sqrt` of {}: the result has no unit", d.describe()),
                        )
                    })?),
                };
                Quantity {
                    value: x.value.sqrt(),
                    dim,
                    span,
                }
            }
            "sin" => Quantity::plain(angle_arg(x)?.sin(), span),
            "cos" => Quantity::plain(angle_arg(x)?.cos(), span),
            "tan" => Quantity::plain(angle_arg(x)?.tan(), span),
            "atan2" => {
                same_dim(x, args[1], "compare")?;
                Quantity {
                    value: x.value.atan2(args[1].value),
                    dim: Some(Dim::ANGLE),
                    span,
                }
            }
            "hypot" => Quantity {
                value: x.value.hypot(args[1].value),
                dim: same_dim(x, args[1], "combine")?,
                span,
            },
            _ => {
                if let Some(d) = x.physical() {
                    return Err(syn::Error::new(
                        x.span,
                        format!("`to_radians` takes a plain number of degrees, but its argument is {}: write `{} deg` or drop `to_radians`", d.describe(), x.value),
                    ));
                }
                Quantity {
                    value: x.value.to_radians(),
                    dim: Some(Dim::ANGLE),
                    span,
                }
            }
        };
        finite(q)
    }
}

/// `q` with the unit `word` applied; an error when `word` is not a unit or `q` has one.
fn with_unit(q: Quantity, word: &str, span: Span) -> syn::Result<Quantity> {
    let Some(u) = units::lookup(word) else {
        return Err(syn::Error::new(
            span,
            format!(
                "unknown unit `{word}`: the unit words are {}",
                units::all_words()
            ),
        ));
    };
    if u.dim == Dim::NONE {
        return Ok(q);
    }
    if let Some(d) = q.physical() {
        return Err(syn::Error::new(
            span,
            format!(
                "`{word}` on a value that is already {}: a unit word applies to a plain number",
                d.describe()
            ),
        ));
    }
    finite(Quantity {
        value: q.value * u.factor,
        dim: Some(u.dim),
        span: q.span,
    })
}

/// The dimension of a sum (or of the two arguments of atan2, hypot): both the same, a
/// plain number taking the other's.
fn same_dim(a: Quantity, b: Quantity, verb: &str) -> syn::Result<Option<Dim>> {
    match (a.physical(), b.physical()) {
        (Some(x), Some(y)) if x != y => Err(syn::Error::new(
            b.span,
            format!(
                "cannot {verb} {} and {}: give both the same kind of unit",
                x.describe(),
                y.describe()
            ),
        )),
        (x, y) => Ok(x.or(y).or(a.dim).or(b.dim)),
    }
}

fn finite(q: Quantity) -> syn::Result<Quantity> {
    if q.value.is_finite() {
        Ok(q)
    } else {
        Err(syn::Error::new(
            q.span,
            format!(
                "this expression evaluates to {}, not a finite number",
                q.value
            ),
        ))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::kernel::measure::within;
    use syn::parse::Parser;

    fn eval_with(consts: &str, text: &str) -> Result<Quantity, String> {
        let mut c = Constants::default();
        if !consts.is_empty() {
            (|input: ParseStream| c.parse_block(input))
                .parse_str(&format!("{{ {consts} }}"))
                .map_err(|e| e.to_string())?;
        }
        (|input: ParseStream| {
            let q = c.expr(input)?;
            if !input.is_empty() {
                return Err(input.error("trailing tokens"));
            }
            Ok(q)
        })
        .parse_str(text)
        .map_err(|e| e.to_string())
    }

    fn eval(text: &str) -> Result<Quantity, String> {
        eval_with("", text)
    }

    #[test]
    fn arithmetic_and_units_to_si() {
        let q = eval("200 mm").unwrap();
        assert_eq!((q.value, q.dim), (0.2, Some(Dim::LENGTH)));
        assert_eq!(eval("200mm").unwrap().value, 0.2);
        assert_eq!(eval("2.1e-3 kg_m2").unwrap().value, 2.1e-3);
        // measured worst 0 (be05608); exact
        assert!(within(
            (eval("(90 - 35) deg").unwrap().value - 55f64.to_radians()).abs(),
            1e-16
        ));
        assert_eq!(eval("-(1 + 2) * 3 / 4").unwrap().value, -2.25);
        assert_eq!(eval("2 - 3 - 4").unwrap().value, -5.0);
        assert_eq!(eval("hypot(3 mm, 4 mm)").unwrap().value, 5e-3);
        assert_eq!(
            eval("atan2(1, 1)").unwrap().value,
            std::f64::consts::FRAC_PI_4
        );
        assert_eq!(eval("to_radians(180)").unwrap().value, std::f64::consts::PI);
        assert_eq!(eval("sin(PI / 2)").unwrap().value, 1.0);
        // measured worst 1.1e-16 (be05608); 100×
        assert!(within(
            (eval("cos(60 deg)").unwrap().value - 0.5).abs(),
            1e-15
        ));
        assert_eq!(eval("sqrt(16 mm * 1 mm)").unwrap().dim, Some(Dim::LENGTH));
        // measured worst 0 (be05608); exact; a few ulps of 314
        assert!(within(
            (eval("3000 rpm").unwrap().value - 100.0 * std::f64::consts::PI).abs(),
            2e-13
        ));
        let q = eval_with("r: 200 mm, l: 4.5 * r, e: 6 mm", "l + e").unwrap();
        // measured worst 0 (be05608); exact; a few ulps
        assert!(within((q.value - 0.906).abs(), 1e-15) && q.dim == Some(Dim::LENGTH));
    }

    #[test]
    fn mistakes_are_explained() {
        let e = eval_with("r: 200 mm", "r + 10 deg").unwrap_err();
        assert!(
            e.contains("cannot add a length (m) and an angle (rad)"),
            "{e}"
        );
        let e = eval_with("r: 200 mm", "2 * s").unwrap_err();
        assert!(
            e.contains("unknown constant `s`") && e.contains("declared so far: r"),
            "{e}"
        );
        let e = eval("1 / (2 - 2)").unwrap_err();
        assert!(e.contains("division by zero"), "{e}");
        let e = eval("3 furlong").unwrap_err();
        assert!(e.contains("unknown unit `furlong`"), "{e}");
        let e = eval("(3 mm) mm").unwrap_err();
        assert!(e.contains("already a length"), "{e}");
        let e = eval("sin(30 mm)").unwrap_err();
        assert!(e.contains("`sin` takes an angle"), "{e}");
        let e = eval("sqrt(-1)").unwrap_err();
        assert!(e.contains("negative"), "{e}");
        let e = eval("to_radians(30 deg)").unwrap_err();
        assert!(e.contains("plain number of degrees"), "{e}");
        let e = eval("frobnicate(1)").unwrap_err();
        assert!(e.contains("unknown function"), "{e}");
        let e = eval_with("r: 1, r: 2", "r").unwrap_err();
        assert!(e.contains("declared twice"), "{e}");
        let e = eval_with("mm: 1", "1").unwrap_err();
        assert!(e.contains("reserved"), "{e}");
        let e = eval("45 mm")
            .unwrap()
            .expect(Dim::ANGLE, "a polar angle")
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("a polar angle is an angle (rad), but this value is a length (m)")
                && e.contains("`deg` or `rad`"),
            "{e}"
        );
        assert_eq!(eval("0.5").unwrap().expect(Dim::ANGLE, "x").unwrap(), 0.5);
    }
}
