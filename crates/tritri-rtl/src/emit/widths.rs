//! Explicit widths in rust-hdl's combinational code.
//!
//! rust-hdl prints expressions that lean on Verilog's context-determined
//! widths: every Rust integer literal becomes `32'h..`, `bit_cast::<N, M>`
//! becomes `((x) & N'h1f..f)`, `signed_bit_cast` becomes a bare `$signed(x)`.
//! The circuits are right, but `verilator -Wall` reports a WIDTH warning on
//! each, and a reader has to redo Verilog's width rules to check them.
//!
//! This pass re-prints every expression of rust-hdl's generated
//! `always @(*)` blocks so that each operand already has the width Verilog
//! would extend or truncate it to: literals are sized to their context,
//! narrower operands are zero- (unsigned context) or sign-extended (signed
//! context) with a concatenation, wider identifiers are part-selected, and
//! rust-hdl's mask casts become concatenations or part-selects. The value of
//! every expression is unchanged: the rewrite computes, for each
//! sub-expression, the low `k` bits of its value in its Verilog context,
//! which for `+ - * & | ^ ~` and left shifts depend on the low `k` bits of
//! the operands only. Where that is not so (right shifts, division,
//! truncating a compound expression) and in any construct it does not know,
//! the pass leaves the statement as rust-hdl wrote it, and the lint test
//! shows what is left.
//!
//! Custom Verilog (`// Update code (custom)`) is left alone: its author
//! writes it lint-clean.

use super::modules::Module;
use super::tokens::{tokenize, Kind, Token};
use num_bigint::BigUint;
use std::collections::HashMap;

fn one() -> BigUint {
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
    Number { bits: Option<usize>, signed: bool, value: BigUint },
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

fn binary_precedence(op: &str) -> Option<u8> {
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
        return Some(Expr::Number { bits: None, signed: true, value });
    };
    let bits = if tick == 0 { None } else { Some(text[..tick].parse::<usize>().ok()?) };
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
    Some(Expr::Number { bits, signed: signed || negative, value })
}

struct Parser<'a> {
    words: &'a [&'a str],
    position: usize,
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
            let Some(p) = binary_precedence(op) else { break };
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
                let width = width_text.trim_matches(|c| c == '(' || c == ')').parse().ok()?;
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
                    let Expr::Number { value, .. } = first else { return None };
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

fn is_keyword(w: &str) -> bool {
    matches!(
        w,
        "begin" | "end" | "if" | "else" | "case" | "endcase" | "default" | "always" | "assign" | "module" | "endmodule"
    )
}

/// Parses a whole expression; `None` unless every word is consumed.
pub fn parse_expression(words: &[&str]) -> Option<Expr> {
    let mut p = Parser { words, position: 0 };
    let e = p.expression()?;
    (p.position == words.len()).then_some(e)
}

// ---------------------------------------------------------------- typing

pub type Declarations = HashMap<String, Ty>;

fn number_ty(bits: Option<usize>, signed: bool) -> Ty {
    Ty { bits: bits.unwrap_or(32), signed }
}

/// The self-determined width and signedness of `e` (IEEE 1364 table 5-22).
pub fn self_type(e: &Expr, decls: &Declarations) -> Option<Ty> {
    let unsigned = |bits| Some(Ty { bits, signed: false });
    match e {
        Expr::Ident(n) => decls.get(n).copied(),
        Expr::Number { bits, signed, .. } => Some(number_ty(*bits, *signed)),
        Expr::Unary(op, a) => match op.as_str() {
            "~" | "-" | "+" => self_type(a, decls),
            _ => unsigned(1),
        },
        Expr::Binary(op, a, b) => {
            let (ta, tb) = (self_type(a, decls)?, self_type(b, decls)?);
            match op.as_str() {
                "+" | "-" | "*" | "/" | "%" | "&" | "|" | "^" | "^~" | "~^" => {
                    Some(Ty { bits: ta.bits.max(tb.bits), signed: ta.signed && tb.signed })
                }
                "<<" | ">>" | "<<<" | ">>>" | "**" => Some(ta),
                _ => unsigned(1),
            }
        }
        Expr::Paren(a) => self_type(a, decls),
        Expr::SignCast(signed, a) => Some(Ty { bits: self_type(a, decls)?.bits, signed: *signed }),
        Expr::Index(..) => unsigned(1),
        Expr::Slice(_, _, w) => unsigned(*w),
        Expr::Range(_, m, l) => unsigned(m.abs_diff(*l) + 1),
        Expr::Concat(items) => unsigned(items.iter().map(|i| self_type(i, decls).map(|t| t.bits)).sum::<Option<usize>>()?),
        Expr::Replicate(n, items) => {
            unsigned(n * items.iter().map(|i| self_type(i, decls).map(|t| t.bits)).sum::<Option<usize>>()?)
        }
        Expr::Ternary(_, a, b) => {
            let (ta, tb) = (self_type(a, decls)?, self_type(b, decls)?);
            Some(Ty { bits: ta.bits.max(tb.bits), signed: ta.signed && tb.signed })
        }
    }
}

/// True when `e`'s value at a larger width is its zero-extension, so a
/// comparison against it may be done at its own width.
fn width_stable(e: &Expr, decls: &Declarations) -> bool {
    match e {
        Expr::Ident(n) => decls.get(n).is_some_and(|t| !t.signed),
        Expr::Index(..) | Expr::Slice(..) | Expr::Range(..) | Expr::Concat(..) | Expr::Replicate(..) => true,
        Expr::Unary(op, _) => !matches!(op.as_str(), "~" | "-" | "+"),
        Expr::Binary(op, a, b) => match op.as_str() {
            "&" | "|" | "^" => width_stable(a, decls) && width_stable(b, decls),
            "+" | "-" | "*" | "/" | "%" | "<<" | ">>" | "<<<" | ">>>" | "**" | "^~" | "~^" => false,
            _ => true,
        },
        Expr::Paren(a) => width_stable(a, decls),
        Expr::SignCast(signed, a) => !signed && width_stable(a, decls),
        Expr::Number { .. } => true,
        Expr::Ternary(_, a, b) => width_stable(a, decls) && width_stable(b, decls),
    }
}

// ---------------------------------------------------------------- printing

/// The evaluation context of a context-determined expression.
#[derive(Clone, Copy, Debug)]
struct Context {
    width: usize,
    signed: bool,
}

fn literal(bits: usize, signed: bool, value: &BigUint) -> String {
    let v = value % (one() << bits);
    format!("{bits}'{}h{}", if signed { "s" } else { "" }, v.to_str_radix(16))
}

fn zeros(bits: usize) -> String {
    format!("{bits}'h0")
}

fn signed_wrap(text: String, signed: bool) -> String {
    if signed {
        format!("$signed({text})")
    } else {
        text
    }
}

struct Printer<'a> {
    decls: &'a Declarations,
    /// Values of the module's numeric localparams.
    constants: &'a Constants,
}

/// localparam name -> value.
pub type Constants = HashMap<String, BigUint>;

/// The values of `localparam NAME = <number>;`.
pub fn constants(words: &[&str]) -> Constants {
    let mut c = Constants::new();
    for i in 0..words.len().saturating_sub(3) {
        if words[i] == "localparam" && words[i + 2] == "=" && words.get(i + 4) == Some(&";") {
            if let Some(Expr::Number { value, .. }) = parse_number(words[i + 3]) {
                c.insert(words[i + 1].to_string(), value);
            }
        }
    }
    c
}

impl Printer<'_> {
    /// An expression of self-determined width exactly `k` whose value is the
    /// low `k` bits of `e` evaluated in context `ctx` (`k <= ctx.width`).
    fn emit(&self, e: &Expr, k: usize, ctx: Context) -> Option<String> {
        let decls = self.decls;
        let own = self_type(e, decls)?;
        // A compound unsigned value that a wider context only zero-extends
        // reads best as its own value, zero-extended: `{1'h0, a ^ b}`.
        let compound = matches!(strip_paren(e), Expr::Binary(op, ..) if matches!(op.as_str(), "&" | "|" | "^"));
        if compound && !ctx.signed && k > own.bits && width_stable(e, decls) {
            let inner = self.emit_self(strip_paren(e))?;
            return Some(format!("{{{}, {inner}}}", zeros(k - own.bits)));
        }
        match e {
            Expr::Paren(a) => {
                let inner = self.emit(a, k, ctx)?;
                Some(if is_atomic_text(&inner) { inner } else { format!("({inner})") })
            }
            Expr::Ident(name) => self.fit_leaf(name, own, k, ctx),
            Expr::Number { bits, signed, value } => {
                // Extend to the context (sign-extend a negative literal in a
                // signed context), then keep k bits.
                let b = bits.unwrap_or(32);
                let v = value % (one() << b);
                let negative = ctx.signed && *signed && v.bit(b as u64 - 1);
                let extended = if negative && ctx.width > b {
                    v + ((one() << ctx.width) - (one() << b))
                } else {
                    v
                };
                Some(literal(k, ctx.signed, &extended))
            }
            Expr::Unary(op, a) => match op.as_str() {
                "~" | "-" | "+" => Some(format!("{op}{}", self.emit(a, k, ctx)?)),
                _ => {
                    let inner = format!("{op}{}", self.emit_self(a)?);
                    self.fit_unsigned_compound(inner, 1, k)
                }
            },
            Expr::Binary(op, a, b) => match op.as_str() {
                "&" if k <= ctx.width && is_all_ones_mask(b).is_some() => {
                    // rust-hdl's bit_cast: `(x) & N'h1..1` keeps the low N bits.
                    let n = is_all_ones_mask(b)?;
                    let a = strip_paren(a);
                    let wa = self_type(a, decls)?.bits;
                    if width_stable(a, decls) && wa <= n.min(k) {
                        // Widening: x's own value, zero-extended.
                        let inner = self.emit_self(a)?;
                        return Some(if k == wa { inner } else { format!("{{{}, {inner}}}", zeros(k - wa)) });
                    }
                    if k <= n {
                        self.emit(a, k, ctx)
                    } else {
                        let low = self.emit(a, n, ctx)?;
                        Some(format!("{{{}, {}}}", zeros(k - n), parenthesize_compound(a, low)))
                    }
                }
                "+" | "-" | "*" | "&" | "|" | "^" | "^~" | "~^" => {
                    Some(format!("{} {op} {}", self.emit(a, k, ctx)?, self.emit(b, k, ctx)?))
                }
                "<<" | "<<<" => Some(format!("{} {op} {}", self.emit(a, k, ctx)?, self.emit_self(b)?)),
                ">>" | ">>>" | "/" | "%" | "**" => {
                    if k != ctx.width {
                        return None;
                    }
                    let right = if op == "/" || op == "%" { self.emit(b, k, ctx)? } else { self.emit_self(b)? };
                    Some(format!("{} {op} {}", self.emit(a, k, ctx)?, right))
                }
                "&&" | "||" => {
                    let inner = format!("{} {op} {}", self.emit_self(a)?, self.emit_self(b)?);
                    self.fit_unsigned_compound(inner, 1, k)
                }
                _ => {
                    // Comparison: its operands form their own context.
                    let (ta, tb) = (self_type(a, decls)?, self_type(b, decls)?);
                    let mut width = ta.bits.max(tb.bits);
                    let signed = ta.signed && tb.signed;
                    // A literal compared with a width-stable operand may take
                    // that operand's width when its value fits.
                    for (lit, other, t_other) in [(a, b, tb), (b, a, ta)] {
                        if let Expr::Number { value, .. } = strip_paren(lit) {
                            if !signed && width_stable(other, decls) && value.bits() as usize <= t_other.bits {
                                width = t_other.bits;
                            }
                        }
                    }
                    let inner_ctx = Context { width, signed };
                    let inner =
                        format!("{} {op} {}", self.emit(a, width, inner_ctx)?, self.emit(b, width, inner_ctx)?);
                    self.fit_unsigned_compound(inner, 1, k)
                }
            },
            Expr::SignCast(signed, a) => {
                // The operand of $signed / $unsigned is self-determined.
                let inner_ty = self_type(a, decls)?;
                if k == inner_ty.bits {
                    let inner = self.emit_self(a)?;
                    return Some(if *signed { format!("$signed({inner})") } else { format!("$unsigned({inner})") });
                }
                match strip_paren(a) {
                    Expr::Ident(name) => {
                        self.fit_leaf(name, Ty { bits: inner_ty.bits, signed: *signed }, k, ctx)
                    }
                    _ => None,
                }
            }
            Expr::Index(base, index) => {
                // A constant index in plain decimal: Verilator wants an index
                // exactly as wide as the address of the vector, and an unsized
                // decimal constant is exempt.
                let constant = match parse_expression(&[index.as_str()]) {
                    Some(Expr::Number { value, .. }) => Some(value),
                    Some(Expr::Ident(name)) => self.constants.get(&name).cloned(),
                    _ => None,
                };
                let index = constant.map_or(index.clone(), |v| v.to_string());
                let inner = format!("{}[{index}]", self.emit_self(base)?);
                self.fit_unsigned_compound(inner, 1, k)
            }
            Expr::Slice(base, offset, w) => {
                let base = self.emit_self(base)?;
                let constant = parse_expression(&[offset.trim_matches(|c| c == '(' || c == ')')])
                    .and_then(|e| match e {
                        Expr::Number { value, .. } => value.to_string().parse::<usize>().ok(),
                        _ => None,
                    });
                if let Some(lsb) = constant {
                    // `x[(32'h5)+:(4)]` is `x[8:5]`.
                    let keep = k.min(*w);
                    let select =
                        if keep == 1 { format!("{base}[{lsb}]") } else { format!("{base}[{}:{lsb}]", lsb + keep - 1) };
                    return if k <= *w {
                        Some(signed_wrap(select, ctx.signed))
                    } else {
                        self.fit_unsigned_compound(select, *w, k)
                    };
                }
                if k <= *w {
                    Some(signed_wrap(format!("{base}[({offset})+:({k})]"), ctx.signed))
                } else {
                    self.fit_unsigned_compound(format!("{base}[({offset})+:({w})]"), *w, k)
                }
            }
            Expr::Range(base, m, l) => {
                let base = self.emit_self(base)?;
                let w = m.abs_diff(*l) + 1;
                if k <= w && m >= l {
                    Some(signed_wrap(format!("{base}[{}:{l}]", l + k - 1), ctx.signed))
                } else {
                    self.fit_unsigned_compound(format!("{base}[{m}:{l}]"), w, k)
                }
            }
            Expr::Concat(items) => {
                let parts = items.iter().map(|i| self.emit_self(i)).collect::<Option<Vec<_>>>()?;
                if k == own.bits {
                    Some(signed_wrap(format!("{{{}}}", parts.join(", ")), ctx.signed))
                } else if k > own.bits && !ctx.signed {
                    Some(format!("{{{}, {}}}", zeros(k - own.bits), parts.join(", ")))
                } else {
                    None
                }
            }
            Expr::Replicate(n, items) => {
                let parts = items.iter().map(|i| self.emit_self(i)).collect::<Option<Vec<_>>>()?;
                let text = format!("{{{n}{{{}}}}}", parts.join(", "));
                if k == own.bits {
                    Some(signed_wrap(text, ctx.signed))
                } else {
                    self.fit_unsigned_compound(text, own.bits, k)
                }
            }
            Expr::Ternary(c, a, b) => {
                Some(format!("{} ? {} : {}", self.emit_self(c)?, self.emit(a, k, ctx)?, self.emit(b, k, ctx)?))
            }
        }
    }

    /// `e` at its own width, in its own context.
    fn emit_self(&self, e: &Expr) -> Option<String> {
        let t = self_type(e, self.decls)?;
        self.emit(e, t.bits, Context { width: t.bits, signed: t.signed })
    }

    /// An identifier of type `own` as `k` bits of its value in `ctx`.
    fn fit_leaf(&self, name: &str, own: Ty, k: usize, ctx: Context) -> Option<String> {
        let w = own.bits;
        let sign_extend = ctx.signed && own.signed;
        let text = if k == w {
            name.to_string()
        } else if k < w {
            if k == 1 {
                format!("{name}[0]")
            } else {
                format!("{name}[{}:0]", k - 1)
            }
        } else if sign_extend {
            let msb = if w == 1 { name.to_string() } else { format!("{name}[{}]", w - 1) };
            format!("{{{{{}{{{msb}}}}}, {name}}}", k - w)
        } else {
            format!("{{{}, {name}}}", zeros(k - w))
        };
        // Keep the signedness the context had (a select or a concatenation is unsigned).
        Some(if ctx.signed && (k != w || !own.signed) { format!("$signed({text})") } else { text })
    }

    /// A `w`-bit unsigned expression (never truncated) as `k` bits.
    fn fit_unsigned_compound(&self, text: String, w: usize, k: usize) -> Option<String> {
        if k == w {
            Some(text)
        } else if k > w {
            Some(format!("{{{}, {text}}}", zeros(k - w)))
        } else {
            None
        }
    }
}

/// True when `text` needs no parentheses as an operand: a name, a number,
/// a select of a name, a concatenation, or a `$signed(...)`-like call.
fn is_atomic_text(text: &str) -> bool {
    let t = text.trim();
    let closing = |open: char, close: char, from: usize| -> Option<usize> {
        let mut depth = 0;
        for (i, c) in t.char_indices().skip(from) {
            if c == open {
                depth += 1;
            } else if c == close {
                depth -= 1;
                if depth == 0 {
                    return Some(i);
                }
            }
        }
        None
    };
    if t.starts_with('{') {
        return closing('{', '}', 0) == Some(t.len() - 1);
    }
    let name_end = t.find(|c: char| !(c.is_ascii_alphanumeric() || c == '_' || c == '$' || c == '\'')).unwrap_or(t.len());
    if name_end == 0 {
        return false;
    }
    match t[name_end..].chars().next() {
        None => true,
        Some('[') => closing('[', ']', name_end) == Some(t.len() - 1),
        Some('(') if t.starts_with('$') => closing('(', ')', name_end) == Some(t.len() - 1),
        _ => false,
    }
}

fn strip_paren(e: &Expr) -> &Expr {
    match e {
        Expr::Paren(a) => strip_paren(a),
        _ => e,
    }
}

fn parenthesize_compound(e: &Expr, text: String) -> String {
    match e {
        Expr::Binary(..) | Expr::Ternary(..) => format!("({text})"),
        _ => text,
    }
}

/// `Some(n)` when `e` is a sized literal of `n` bits, all ones.
fn is_all_ones_mask(e: &Expr) -> Option<usize> {
    match strip_paren(e) {
        Expr::Number { bits: Some(n), signed: false, value } if *value == (one() << *n) - one() => {
            Some(*n)
        }
        _ => None,
    }
}

// ---------------------------------------------------------------- statements

/// The declared width of every net, variable, port and localparam of a module.
pub fn declarations(words: &[&str]) -> Declarations {
    let mut decls = Declarations::new();
    let mut i = 0;
    while i < words.len() {
        let w = words[i];
        if matches!(w, "input" | "output" | "inout" | "reg" | "wire" | "logic" | "integer") {
            let mut k = i;
            while k < words.len() && matches!(words[k], "input" | "output" | "inout" | "reg" | "wire" | "logic") {
                k += 1;
            }
            let mut ty = Ty { bits: 1, signed: false };
            if words.get(k) == Some(&"integer") {
                ty = Ty { bits: 32, signed: true };
                k += 1;
            }
            if words.get(k) == Some(&"signed") {
                ty.signed = true;
                k += 1;
            }
            if words.get(k) == Some(&"[") {
                let msb: Option<usize> = words.get(k + 1).and_then(|x| x.parse().ok());
                let lsb: Option<usize> = words.get(k + 3).and_then(|x| x.parse().ok());
                if let (Some(m), Some(l), Some(&":"), Some(&"]")) = (msb, lsb, words.get(k + 2), words.get(k + 4)) {
                    ty.bits = m.abs_diff(l) + 1;
                    k += 5;
                } else {
                    i = k;
                    continue;
                }
            }
            // Names up to `;`, `)` or `=` (ANSI lists end at `,` + direction).
            while let Some(&name) = words.get(k) {
                if name.starts_with(|c: char| c.is_ascii_alphabetic() || c == '_') && !is_keyword(name) {
                    decls.insert(name.to_string(), ty);
                }
                match words.get(k + 1) {
                    Some(&",") if words.get(k + 2).is_some_and(|n| !matches!(*n, "input" | "output" | "inout")) => {
                        k += 2
                    }
                    _ => break,
                }
            }
            i = k + 1;
        } else if w == "localparam" || w == "parameter" {
            // localparam NAME = literal;  (rust-hdl's constants and enum labels)
            if let (Some(&name), Some(&"="), Some(&value)) = (words.get(i + 1), words.get(i + 2), words.get(i + 3)) {
                if let Some(Expr::Number { bits, signed, .. }) = parse_number(value) {
                    decls.insert(name.to_string(), number_ty(bits, signed));
                }
            }
            i += 1;
        } else {
            i += 1;
        }
    }
    decls
}

enum Span {
    /// `if (` cond `)` or `case (` subject `)`: self-determined.
    SelfDetermined(usize, usize),
    /// lhs `=` rhs `;`: lhs words, rhs words.
    Assignment((usize, usize), (usize, usize)),
    /// A case label (words) and the case subject (words).
    CaseLabel((usize, usize), (usize, usize)),
}

struct StatementParser<'a> {
    words: &'a [&'a str],
    position: usize,
    spans: Vec<Span>,
}

impl StatementParser<'_> {
    fn peek(&self) -> Option<&str> {
        self.words.get(self.position).copied()
    }

    /// Index of the `)` matching the `(` at `open`.
    fn matching(&self, open: usize) -> Option<usize> {
        let mut depth = 0;
        for k in open..self.words.len() {
            match self.words[k] {
                "(" => depth += 1,
                ")" => {
                    depth -= 1;
                    if depth == 0 {
                        return Some(k);
                    }
                }
                _ => {}
            }
        }
        None
    }

    fn statement(&mut self) -> Option<()> {
        match self.peek()? {
            "begin" => {
                self.position += 1;
                while self.peek()? != "end" {
                    self.statement()?;
                }
                self.position += 1;
            }
            "if" => {
                let open = self.position + 1;
                (self.words.get(open) == Some(&"(")).then_some(())?;
                let close = self.matching(open)?;
                self.spans.push(Span::SelfDetermined(open + 1, close));
                self.position = close + 1;
                self.statement()?;
                if self.peek() == Some("else") {
                    self.position += 1;
                    self.statement()?;
                }
            }
            "case" => {
                let open = self.position + 1;
                (self.words.get(open) == Some(&"(")).then_some(())?;
                let close = self.matching(open)?;
                self.spans.push(Span::SelfDetermined(open + 1, close));
                self.position = close + 1;
                while self.peek()? != "endcase" {
                    // Labels up to `:`.
                    let label = self.position;
                    while self.peek()? != ":" {
                        self.position += 1;
                    }
                    if self.words[label] != "default" {
                        self.spans.push(Span::CaseLabel((label, self.position), (open + 1, close)));
                    }
                    self.position += 1;
                    self.statement()?;
                }
                self.position += 1;
            }
            ";" => self.position += 1,
            _ => {
                let start = self.position;
                let equals = (start..self.words.len()).find(|&k| self.words[k] == "=" || self.words[k] == ";")?;
                (self.words[equals] == "=").then_some(())?;
                let end = (equals..self.words.len()).find(|&k| self.words[k] == ";")?;
                self.spans.push(Span::Assignment((start, equals), (equals + 1, end)));
                self.position = end + 1;
            }
        }
        Some(())
    }
}

/// Rewrites the expressions of one statement span; `None` leaves it as is.
fn rewrite_span(
    words: &[&str],
    span: &Span,
    decls: &Declarations,
    constants: &Constants,
) -> Option<Vec<(usize, usize, String)>> {
    let printer = Printer { decls, constants };
    match span {
        Span::CaseLabel(..) => None,
        Span::SelfDetermined(a, b) => {
            let e = parse_expression(&words[*a..*b])?;
            Some(vec![(*a, *b, printer.emit_self(&e)?)])
        }
        Span::Assignment((la, lb), (ra, rb)) => {
            let lhs = parse_expression(&words[*la..*lb])?;
            let rhs = parse_expression(&words[*ra..*rb])?;
            let target = self_type(&lhs, decls)?;
            let own = self_type(&rhs, decls)?;
            let ctx = Context { width: target.bits.max(own.bits), signed: own.signed };
            let text = printer.emit(&rhs, target.bits, ctx)?;
            Some(vec![(*ra, *rb, text)])
        }
    }
}

/// Applies the pass to a module (see the module docs).
pub fn fix_module(module: &mut Module) {
    // Positions of the non-trivia tokens.
    let positions: Vec<usize> =
        module.tokens.iter().enumerate().filter(|(_, t)| !t.is_trivia()).map(|(i, _)| i).collect();
    let owned: Vec<String> = positions.iter().map(|&i| module.tokens[i].text.clone()).collect();
    let words: Vec<&str> = owned.iter().map(String::as_str).collect();
    let decls = declarations(&words);
    let constants = constants(&words);
    // rust-hdl's generated block follows the comment `// Update code`.
    let Some(generated) = module.tokens.iter().position(|t| t.kind == Kind::Comment && t.text.trim() == "// Update code")
    else {
        return;
    };
    let first = positions.iter().position(|&p| p > generated).unwrap_or(words.len());
    let mut decls = decls;
    let mut parser = StatementParser { words: &words, position: first, spans: Vec::new() };
    let mut replacements: Vec<(usize, usize, String)> = Vec::new();
    while parser.position < words.len() {
        if words[parser.position] == "always"
            && words.get(parser.position + 1) == Some(&"@")
            && words.get(parser.position + 2) == Some(&"(")
            && words.get(parser.position + 3) == Some(&"*")
            && words.get(parser.position + 4) == Some(&")")
        {
            parser.position += 5;
            let before = parser.spans.len();
            if parser.statement().is_none() {
                parser.spans.truncate(before);
                break;
            }
        } else {
            parser.position += 1;
        }
    }
    for (token, text) in size_enum_labels(&positions, &words, &parser.spans, &mut decls) {
        module.tokens[token].text = text;
    }
    for span in &parser.spans {
        if let Some(r) = rewrite_span(&words, span, &decls, &constants) {
            replacements.extend(r);
        }
    }
    // Apply from the end so earlier token positions stay valid.
    replacements.sort_by_key(|r| std::cmp::Reverse(r.0));
    for (a, b, text) in replacements {
        if a >= b {
            continue;
        }
        let (from, to) = (positions[a], positions[b - 1]);
        let original: String = module.tokens[from..=to].iter().map(|t| t.text.as_str()).collect();
        if original == text {
            continue;
        }
        module.tokens.splice(from..=to, std::iter::once(Token::new(Kind::Punctuation, text)));
    }
    // Re-lex so that the rewritten text is tokens again, then drop labels
    // nothing uses.
    let text = module.text();
    module.tokens = tokenize(&text);
    remove_unused_localparams(module);
}

/// rust-hdl declares enum labels as unsized `localparam Label = 2;` (32-bit
/// signed), then assigns them to and compares them with a register of the
/// enum's width. When every such use agrees on one width, the label is
/// declared with it: `localparam [1:0] Label = 2'd2;`.
fn size_enum_labels(
    positions: &[usize],
    words: &[&str],
    spans: &[Span],
    decls: &mut Declarations,
) -> Vec<(usize, String)> {
    let mut edits = Vec::new();
    // Unsized localparams: name -> word index of `localparam`.
    let mut unsized_labels: HashMap<&str, usize> = HashMap::new();
    for i in 0..words.len().saturating_sub(3) {
        if words[i] == "localparam" && words[i + 2] == "=" && words[i + 3].chars().all(|c| c.is_ascii_digit()) {
            unsized_labels.insert(words[i + 1], i);
        }
    }
    if unsized_labels.is_empty() {
        return edits;
    }
    let mut width: HashMap<&str, Option<usize>> = HashMap::new();
    let mut note = |name: &str, w: Option<usize>| {
        if let Some((&key, _)) = unsized_labels.get_key_value(name) {
            let entry = width.entry(key).or_insert(w);
            if *entry != w {
                *entry = None;
            }
        }
    };
    for span in spans {
        let (single, other) = match span {
            Span::Assignment((la, lb), (ra, rb)) => ((*ra, *rb), (*la, *lb)),
            Span::CaseLabel(label, subject) => (*label, *subject),
            Span::SelfDetermined(..) => continue,
        };
        let other_ty = parse_expression(&words[other.0..other.1]).and_then(|e| self_type(&e, decls));
        if single.1 == single.0 + 1 {
            note(words[single.0], other_ty.map(|t| t.bits));
        } else {
            // Any other use of a label keeps it as rust-hdl wrote it.
            for w in &words[single.0..single.1] {
                note(w, None);
            }
        }
    }
    // Uses elsewhere (comparisons, ...) also keep the label unsized_labels.
    for span in spans {
        if let Span::SelfDetermined(a, b) = span {
            for w in &words[*a..*b] {
                note(w, None);
            }
        }
    }
    for (name, w) in width {
        let Some(w) = w else { continue };
        let i = unsized_labels[name];
        let value: u128 = match words[i + 3].parse() {
            Ok(v) => v,
            Err(_) => continue,
        };
        if w == 0 || w > 127 || value >> w != 0 {
            continue;
        }
        let range = if w == 1 { String::new() } else { format!(" [{}:0]", w - 1) };
        edits.push((positions[i], format!("localparam{range}")));
        edits.push((positions[i + 3], format!("{w}'d{value}")));
        decls.insert(name.to_string(), Ty { bits: w, signed: false });
    }
    edits
}

/// Drops `localparam NAME = ...;` lines whose name is never used: rust-hdl
/// copies every label of an enum into each module that holds one.
fn remove_unused_localparams(module: &mut Module) {
    let tokens = &module.tokens;
    let mut uses: HashMap<&str, usize> = HashMap::new();
    for t in tokens.iter().filter(|t| t.kind == Kind::Identifier) {
        *uses.entry(t.text.as_str()).or_default() += 1;
    }
    let mut remove = Vec::new();
    let mut i = 0;
    while i < tokens.len() {
        if tokens[i].is("localparam") {
            let end = (i..tokens.len()).find(|&k| tokens[k].is(";"));
            let name = tokens[i + 1..].iter().find(|t| !t.is_trivia());
            if let (Some(end), Some(name)) = (end, name) {
                if uses.get(name.text.as_str()) == Some(&1) {
                    // Take the line's indentation and newline with it.
                    let mut from = i;
                    if from > 0 && tokens[from - 1].kind == Kind::Whitespace && !tokens[from - 1].text.contains('\n') {
                        from -= 1;
                    }
                    let mut to = end;
                    if tokens.get(to + 1).is_some_and(|t| t.kind == Kind::Whitespace) {
                        to += 1;
                    }
                    remove.push((from, to));
                }
                i = end;
            }
        }
        i += 1;
    }
    for (from, to) in remove.into_iter().rev() {
        module.tokens.drain(from..=to);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn decls() -> Declarations {
        let mut d = Declarations::new();
        for (n, bits, signed) in [("a", 8, false), ("b", 8, false), ("y", 9, false), ("s", 10, true), ("x", 8, true)] {
            d.insert(n.into(), Ty { bits, signed });
        }
        d
    }

    fn rewrite(lhs: &str, rhs: &str) -> String {
        let words_l: Vec<String> =
            tokenize(lhs).into_iter().filter(|t| !t.is_trivia()).map(|t| t.text).collect();
        let words_r: Vec<String> =
            tokenize(rhs).into_iter().filter(|t| !t.is_trivia()).map(|t| t.text).collect();
        let mut words: Vec<&str> = words_l.iter().map(String::as_str).collect();
        let eq = words.len();
        words.push("=");
        words.extend(words_r.iter().map(String::as_str));
        let span = Span::Assignment((0, eq), (eq + 1, words.len()));
        rewrite_span(&words, &span, &decls(), &Constants::new()).unwrap().remove(0).2
    }

    /// rust-hdl's widening bit_cast becomes an explicit zero-extension.
    #[test]
    fn bit_cast_becomes_concatenation() {
        assert_eq!(rewrite("y", "((a) & 9'h1ff) + ((b) & 9'h1ff)"), "{1'h0, a} + {1'h0, b}");
    }

    /// Literals take the width of their context.
    #[test]
    fn literals_are_sized() {
        assert_eq!(rewrite("a", "32'h3"), "8'h3");
        assert_eq!(rewrite("a", "a + 32'h1"), "a + 8'h1");
    }

    /// A bare $signed in a wider signed context is sign-extended.
    #[test]
    fn signed_operands_are_sign_extended() {
        assert_eq!(rewrite("s", "$signed(x) + $signed(x)"), "$signed({{2{x[7]}}, x}) + $signed({{2{x[7]}}, x})");
    }

    /// A comparison against a literal is done at the operand's width.
    #[test]
    fn comparisons_shrink_literals() {
        assert_eq!(rewrite("y[0]", "a == 32'h5"), "a == 8'h5");
        // A sum is not width-stable: its carry would be lost.
        assert_eq!(rewrite("y[0]", "a + b == 32'h5"), "{24'h0, a} + {24'h0, b} == 32'h5");
    }

    /// Truncating a compound expression with a right shift is left alone.
    #[test]
    fn unknown_shapes_are_left() {
        let words = ["a", "=", "(", "y", ">>", "1", ")"];
        let span = Span::Assignment((0, 1), (2, 7));
        assert!(rewrite_span(&words, &span, &decls(), &Constants::new()).is_none());
    }

    #[test]
    fn numbers_parse() {
        assert_eq!(parse_number("9'h1ff"), Some(Expr::Number { bits: Some(9), signed: false, value: 511u32.into() }));
        assert_eq!(parse_number("4'h-1"), Some(Expr::Number { bits: Some(4), signed: true, value: 15u32.into() }));
        assert_eq!(parse_number("12"), Some(Expr::Number { bits: None, signed: true, value: 12u32.into() }));
    }
}
