//! The cases: the seed mechanisms of the repository and the mutations that turn them into
//! hostile texts, from a small deterministic generator.

use std::path::Path;

/// xorshift64*: a small deterministic generator.
pub struct Rng(pub u64);

impl Rng {
    /// The next 64 random bits.
    pub fn next(&mut self) -> u64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        self.0.wrapping_mul(0x2545_F491_4F6C_DD1D)
    }
    /// A number in 0..n (0 when n = 0).
    pub fn below(&mut self, n: usize) -> usize {
        (self.next() % n.max(1) as u64) as usize
    }
}

/// Every mechanism body under the repository's tests and examples.
pub fn seeds(root: &Path) -> Vec<String> {
    let mut out = Vec::new();
    let mut files = Vec::new();
    for dir in ["tests", "tests/common", "examples", "examples/mech"] {
        if let Ok(rd) = std::fs::read_dir(root.join(dir)) {
            files.extend(rd.flatten().map(|e| e.path()));
        }
    }
    files.sort();
    for f in files {
        let Ok(text) = std::fs::read_to_string(&f) else {
            continue;
        };
        if f.extension().is_some_and(|e| e == "mech") {
            out.push(text);
            continue;
        }
        let mut at = 0;
        while let Some(i) = text[at..].find("mechanism! {\n") {
            let start = at + i + "mechanism! {\n".len();
            let Some(end) = text[start..].find("\n}\n") else {
                break;
            };
            out.push(text[start..start + end].to_string());
            at = start + end;
        }
    }
    out
}

/// The hostile numbers a mutation writes in place of a number of the text.
const NUMBERS: [&str; 16] = [
    "0",
    "-0.0",
    "1e308",
    "-1.7976931348623157e308",
    "1e-308",
    "5e-324",
    "1e999",
    "1e16",
    "-1e-300",
    "0.5",
    "3",
    "1e200",
    "1e-200",
    "4294967296",
    "-2",
    "1e6",
];
/// The tokens a mutation inserts.
const TOKENS: [&str; 12] = [
    ",", "(", ")", "{", "}", "[", "]", ":", "-", "r#x", "0.0", "ground",
];

/// One mutation of `text`.
pub fn mutate(text: &str, rng: &mut Rng) -> String {
    let bytes: Vec<(usize, char)> = text.char_indices().collect();
    if bytes.is_empty() {
        return text.to_string();
    }
    let pick = |rng: &mut Rng| bytes[rng.below(bytes.len())].0;
    match rng.below(6) {
        0 => {
            // A number replaced by a hostile one.
            let starts: Vec<usize> = bytes
                .windows(2)
                .filter(|w| {
                    w[1].1.is_ascii_digit() && !w[0].1.is_ascii_alphanumeric() && w[0].1 != '.'
                })
                .map(|w| w[1].0)
                .collect();
            if starts.is_empty() {
                return text.to_string();
            }
            let s = starts[rng.below(starts.len())];
            let e = s + text[s..]
                .find(|c: char| !(c.is_ascii_alphanumeric() || c == '.' || c == '-'))
                .unwrap_or(text.len() - s);
            format!(
                "{}{}{}",
                &text[..s],
                NUMBERS[rng.below(NUMBERS.len())],
                &text[e..]
            )
        }
        1 => {
            // A span deleted.
            let (a, b) = (pick(rng), pick(rng));
            let (a, mut b) = (a.min(b), a.max(b).min(a.min(b) + 40));
            while !text.is_char_boundary(b) {
                b -= 1;
            }
            format!("{}{}", &text[..a], &text[b..])
        }
        2 => {
            // A line duplicated.
            let lines: Vec<&str> = text.lines().collect();
            let k = rng.below(lines.len());
            let mut out: Vec<&str> = lines.clone();
            out.insert(k, lines[k]);
            out.join("\n")
        }
        3 => {
            // A name replaced by another name of the text.
            let words: Vec<&str> = text
                .split(|c: char| !(c.is_alphanumeric() || c == '_'))
                .filter(|w| w.chars().next().is_some_and(|c| c.is_alphabetic()))
                .collect();
            if words.len() < 2 {
                return text.to_string();
            }
            let (a, b) = (words[rng.below(words.len())], words[rng.below(words.len())]);
            text.replacen(a, b, 1 + rng.below(2))
        }
        4 => {
            let a = pick(rng);
            format!(
                "{}{}{}",
                &text[..a],
                TOKENS[rng.below(TOKENS.len())],
                &text[a..]
            )
        }
        _ => {
            // A point or a whole number tweaked slightly (a near-dead point, a near-tangency).
            text.replacen("0.", "0.00000000001", 1)
        }
    }
}
