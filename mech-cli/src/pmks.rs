//! pyslvs's "PMKS expression", the text pyslvs and Pyslvs-UI save and share:
//!
//! ```text
//! mechanism := "M[" [joint ("," joint)* [","]] "]"
//! joint     := "J[" type ["," "A[" number "]"] ["," "color[" (NAME | "(" r "," g "," b ")") "]"]
//!              "," "P[" number "," number "]" "," "L[" [name ("," name)* [","]] "]" "]"
//! type      := "R" | "P" | "RP"
//! ```
//!
//! (pyslvs's `expression_parser.py`; `#` starts a comment to the end of the line). A
//! joint is a point of every link it lists. R: a pin of those links. P and RP: a slider
//! whose first link is the slot (the guide, at angle A, degrees) and whose other links
//! hold the pin; P translates, RP also turns.

use crate::Failure;

/// A joint's kind.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Kind {
    /// A pin (revolute).
    R,
    /// A slider that translates along the slot (prismatic).
    P,
    /// A pin sliding in the slot and turning (pin in a slot).
    RP,
}

/// One joint of the expression.
#[derive(Clone, Debug, PartialEq)]
pub struct Joint {
    /// R, P or RP.
    pub kind: Kind,
    /// The slot's angle, degrees (sliders).
    pub angle: f64,
    /// Its coordinates (units as given).
    pub at: (f64, f64),
    /// The links it joins; for a slider the first is the slot.
    pub links: Vec<String>,
}

/// A cursor over the text with its line and column, for messages.
struct Cursor<'a> {
    text: &'a str,
    at: usize,
}

impl<'a> Cursor<'a> {
    fn position(&self) -> (usize, usize) {
        let before = &self.text[..self.at];
        let line = before.matches('\n').count() + 1;
        let col = before.rsplit('\n').next().map_or(0, |l| l.chars().count()) + 1;
        (line, col)
    }

    fn error(&self, what: &str) -> Failure {
        let (l, c) = self.position();
        let found: String = self.text[self.at..].chars().take(12).collect();
        Failure::mechanism(format!("{l}:{c}: {what}, found `{found}`"))
    }

    /// Skip white space and `#` comments.
    fn skip(&mut self) {
        loop {
            let rest = &self.text[self.at..];
            let trimmed = rest.trim_start();
            self.at += rest.len() - trimmed.len();
            if trimmed.starts_with('#') {
                self.at += trimmed.find('\n').unwrap_or(trimmed.len());
            } else {
                return;
            }
        }
    }

    fn eat(&mut self, s: &str) -> bool {
        self.skip();
        if self.text[self.at..].starts_with(s) {
            self.at += s.len();
            true
        } else {
            false
        }
    }

    fn expect(&mut self, s: &str) -> Result<(), Failure> {
        if self.eat(s) {
            Ok(())
        } else {
            Err(self.error(&format!("expected `{s}`")))
        }
    }

    fn word(&mut self) -> Result<String, Failure> {
        self.skip();
        let rest = &self.text[self.at..];
        let n = rest
            .find(|c: char| !(c.is_ascii_alphanumeric() || c == '_' || c == '-'))
            .unwrap_or(rest.len());
        if n == 0 {
            return Err(self.error("expected a name"));
        }
        self.at += n;
        Ok(rest[..n].to_string())
    }

    fn number(&mut self) -> Result<f64, Failure> {
        self.skip();
        let rest = &self.text[self.at..];
        let n = rest
            .find(|c: char| !(c.is_ascii_digit() || matches!(c, '.' | '-' | '+' | 'e' | 'E')))
            .unwrap_or(rest.len());
        match rest[..n].parse::<f64>() {
            Ok(v) if v.is_finite() => {
                self.at += n;
                Ok(v)
            }
            _ => Err(self.error("expected a number")),
        }
    }
}

/// Parse a PMKS expression; errors give `line:column`.
pub fn parse(text: &str) -> Result<Vec<Joint>, Failure> {
    let mut c = Cursor { text, at: 0 };
    c.expect("M[")?;
    let mut joints = Vec::new();
    while !c.eat("]") {
        if !joints.is_empty() {
            c.expect(",")?;
            if c.eat("]") {
                break;
            }
        }
        c.expect("J[")?;
        let kind = if c.eat("RP") {
            Kind::RP
        } else if c.eat("R") {
            Kind::R
        } else if c.eat("P") {
            Kind::P
        } else {
            return Err(c.error("expected a joint type `R`, `P` or `RP`"));
        };
        c.expect(",")?;
        let mut angle = 0.0;
        if c.eat("A[") {
            angle = c.number()?;
            c.expect("]")?;
            c.expect(",")?;
        }
        if c.eat("color[") {
            if c.eat("(") {
                for k in 0..3 {
                    if k > 0 {
                        c.expect(",")?;
                    }
                    c.number()?;
                }
                c.expect(")")?;
            } else {
                c.word()?;
            }
            c.expect("]")?;
            c.expect(",")?;
        }
        c.expect("P[")?;
        let x = c.number()?;
        c.expect(",")?;
        let y = c.number()?;
        c.expect("]")?;
        c.expect(",")?;
        c.expect("L[")?;
        let mut links = Vec::new();
        while !c.eat("]") {
            if !links.is_empty() {
                c.expect(",")?;
                if c.eat("]") {
                    break;
                }
            }
            links.push(c.word()?);
        }
        c.expect("]")?;
        joints.push(Joint {
            kind,
            angle,
            at: (x, y),
            links,
        });
    }
    c.skip();
    if c.at != text.len() {
        return Err(c.error("unexpected text after the mechanism"));
    }
    Ok(joints)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parses_every_form() {
        let j = parse("M[J[R, color[Green], P[0.0, 0.0], L[ground, L1]], J[RP, A[30.5], color[(1, 2, 3)], P[1e1, -2], L[L2, ground, ]],\n # note\n J[P, P[3, 4], L[]]]").unwrap();
        assert_eq!(j.len(), 3);
        assert_eq!(
            j[1],
            Joint {
                kind: Kind::RP,
                angle: 30.5,
                at: (10.0, -2.0),
                links: vec!["L2".into(), "ground".into()]
            }
        );
        assert_eq!(j[2].kind, Kind::P);
        assert!(j[2].links.is_empty());
    }

    #[test]
    fn mistakes_give_line_and_column() {
        let e = parse("M[\n  J[R, P[0.0, zero], L[ground]]]").unwrap_err();
        assert!(
            e.message.starts_with("2:15: expected a number"),
            "{}",
            e.message
        );
        let e = parse("M[J[Q, P[0, 0], L[a]]]").unwrap_err();
        assert!(
            e.message.starts_with("1:5: expected a joint type"),
            "{}",
            e.message
        );
        assert!(parse("M[J[R, P[0, 0], L[a]]] tail").is_err());
    }
}
