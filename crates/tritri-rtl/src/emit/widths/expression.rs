//! The expressions of rust-hdl's combinational code: their tree, and a
//! parser for the words of one expression.

use super::*;

pub(super) fn one() -> BigUint {
    BigUint::from(1u32)
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Ty {
    pub bits: usize,
    pub signed: bool,
}

#[derive(Clone, Debug, PartialEq)]
pub enum Expr {
    Ident(String),
    /// A literal; `bits: None` for an unsized one (32 bits).
    Number {
        bits: Option<usize>,
        signed: bool,
        value: BigUint,
    },
    Unary(String, Box<Expr>),
    Binary(String, Box<Expr>, Box<Expr>),
    Paren(Box<Expr>),
    /// `$signed(e)` / `$unsigned(e)`.
    SignCast(bool, Box<Expr>),
    /// `x[index]`, index kept as text.
    Index(Box<Expr>, String),
    /// `x[(offset)+:(width)]`, offset kept as text.
    Slice(Box<Expr>, String, usize),
    /// `x[msb:lsb]`.
    Range(Box<Expr>, usize, usize),
    Concat(Vec<Expr>),
    Replicate(usize, Vec<Expr>),
    Ternary(Box<Expr>, Box<Expr>, Box<Expr>),
}

// ---------------------------------------------------------------- parsing

pub(super) fn binary_precedence(op: &str) -> Option<u8> {
    Some(match op {
        "||" => 1,
        "&&" => 2,
        "|" => 3,
        "^" | "^~" | "~^" => 4,
        "&" => 5,
        "==" | "!=" | "===" | "!==" => 6,
        "<" | "<=" | ">" | ">=" => 7,
        "<<" | ">>" | "<<<" | ">>>" => 8,
        "+" | "-" => 9,
        "*" | "/" | "%" => 10,
        "**" => 11,
        _ => return None,
    })
}

/// Parses a literal's text; `None` for x/z digits and other forms we leave alone.
pub fn parse_number(text: &str) -> Option<Expr> {
    let text = text.replace('_', "");
    let Some(tick) = text.find('\'') else {
        let value = text.parse::<BigUint>().ok()?;
        return Some(Expr::Number {
            bits: None,
            signed: true,
            value,
        });
    };
    let bits = if tick == 0 {
        None
    } else {
        Some(text[..tick].parse::<usize>().ok()?)
    };
    let mut rest = &text[tick + 1..];
    let signed = rest.starts_with(['s', 'S']);
    if signed {
        rest = &rest[1..];
    }
    let radix = match rest.chars().next()?.to_ascii_lowercase() {
        'h' => 16,
        'd' => 10,
        'o' => 8,
        'b' => 2,
        _ => return None,
    };
    rest = &rest[1..];
    // rust-hdl prints a negative Signed<N> constant as `N'h-X`.
    let negative = rest.starts_with('-');
    if negative {
        rest = &rest[1..];
    }
    let magnitude = BigUint::parse_bytes(rest.as_bytes(), radix)?;
    let value = if negative {
        let n = bits?;
        let modulus = one() << n;
        (&modulus - (magnitude % &modulus)) % &modulus
    } else {
        magnitude
    };
    Some(Expr::Number {
        bits,
        signed: signed || negative,
        value,
    })
}

pub(super) struct Parser<'a> {
    pub(super) words: &'a [&'a str],
    pub(super) position: usize,
}

impl<'a> Parser<'a> {
    fn peek(&self) -> Option<&'a str> {
        self.words.get(self.position).copied()
    }
    fn next(&mut self) -> Option<&'a str> {
        let w = self.peek();
        self.position += 1;
        w
    }
    fn expect(&mut self, w: &str) -> Option<()> {
        (self.next()? == w).then_some(())
    }

    fn expression(&mut self) -> Option<Expr> {
        let condition = self.binary(1)?;
        if self.peek() == Some("?") {
            self.next();
            let a = self.expression()?;
            self.expect(":")?;
            let b = self.expression()?;
            return Some(Expr::Ternary(Box::new(condition), Box::new(a), Box::new(b)));
        }
        Some(condition)
    }

    fn binary(&mut self, min: u8) -> Option<Expr> {
        let mut left = self.unary()?;
        while let Some(op) = self.peek() {
            let Some(p) = binary_precedence(op) else {
                break;
            };
            if p < min {
                break;
            }
            self.next();
            let right = self.binary(p + 1)?;
            left = Expr::Binary(op.to_string(), Box::new(left), Box::new(right));
        }
        Some(left)
    }

    fn unary(&mut self) -> Option<Expr> {
        match self.peek()? {
            op @ ("~" | "-" | "+" | "!" | "&" | "|" | "^" | "~&" | "~|" | "~^" | "^~") => {
                self.next();
                Some(Expr::Unary(op.to_string(), Box::new(self.unary()?)))
            }
            _ => self.postfix(),
        }
    }

    fn postfix(&mut self) -> Option<Expr> {
        let mut e = self.primary()?;
        while self.peek() == Some("[") {
            // Only identifiers (and their selects) take selects in rust-hdl output.
            self.next();
            let start = self.position;
            let mut depth = 0;
            let mut colon = None;
            let mut plus_colon = None;
            while let Some(w) = self.peek() {
                match w {
                    "[" | "(" | "{" => depth += 1,
                    ")" | "}" => depth -= 1,
                    "]" if depth == 0 => break,
                    "]" => depth -= 1,
                    ":" if depth == 0 => colon = Some(self.position),
                    "+:" if depth == 0 => plus_colon = Some(self.position),
                    _ => {}
                }
                self.next();
            }
            let end = self.position;
            self.expect("]")?;
            let inner = &self.words[start..end];
            e = if let Some(pc) = plus_colon {
                let width_text: String = self.words[pc + 1..end].concat();
                let width = width_text
                    .trim_matches(|c| c == '(' || c == ')')
                    .parse()
                    .ok()?;
                Expr::Slice(Box::new(e), self.words[start..pc].concat(), width)
            } else if let Some(c) = colon {
                let msb = self.words[start..c].concat().parse().ok()?;
                let lsb = self.words[c + 1..end].concat().parse().ok()?;
                Expr::Range(Box::new(e), msb, lsb)
            } else {
                Expr::Index(Box::new(e), inner.concat())
            };
        }
        Some(e)
    }

    fn primary(&mut self) -> Option<Expr> {
        let w = self.next()?;
        match w {
            "(" => {
                let e = self.expression()?;
                self.expect(")")?;
                Some(Expr::Paren(Box::new(e)))
            }
            "$signed" | "$unsigned" => {
                self.expect("(")?;
                let e = self.expression()?;
                self.expect(")")?;
                Some(Expr::SignCast(w == "$signed", Box::new(e)))
            }
            "{" => {
                let first = self.expression()?;
                if self.peek() == Some("{") {
                    // Replication {n{a, b}}.
                    let Expr::Number { value, .. } = first else {
                        return None;
                    };
                    self.next();
                    let items = self.list("}")?;
                    self.expect("}")?;
                    let count = value.to_string().parse().ok()?;
                    return Some(Expr::Replicate(count, items));
                }
                let mut items = vec![first];
                while self.peek() == Some(",") {
                    self.next();
                    items.push(self.expression()?);
                }
                self.expect("}")?;
                Some(Expr::Concat(items))
            }
            _ if w.starts_with(|c: char| c.is_ascii_digit() || c == '\'') => parse_number(w),
            _ if w.starts_with(|c: char| c.is_ascii_alphabetic() || c == '_') => {
                if is_keyword(w) {
                    None
                } else {
                    Some(Expr::Ident(w.to_string()))
                }
            }
            _ => None,
        }
    }

    fn list(&mut self, close: &str) -> Option<Vec<Expr>> {
        let mut items = vec![self.expression()?];
        while self.peek() == Some(",") {
            self.next();
            items.push(self.expression()?);
        }
        (self.peek() == Some(close)).then_some(items)
    }
}

pub(super) fn is_keyword(w: &str) -> bool {
    matches!(
        w,
        "begin"
            | "end"
            | "if"
            | "else"
            | "case"
            | "endcase"
            | "default"
            | "always"
            | "assign"
            | "module"
            | "endmodule"
    )
}

/// Parses a whole expression; `None` unless every word is consumed.
pub fn parse_expression(words: &[&str]) -> Option<Expr> {
    let mut p = Parser { words, position: 0 };
    let e = p.expression()?;
    (p.position == words.len()).then_some(e)
}
