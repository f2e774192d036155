//! Re-printing an expression with explicit widths: every operand at the
//! width its context gives it.

use super::*;

/// The evaluation context of a context-determined expression.
#[derive(Clone, Copy, Debug)]
pub(super) struct Context {
    pub(super) width: usize,
    pub(super) signed: bool,
}

pub(super) fn literal(bits: usize, signed: bool, value: &BigUint) -> String {
    let v = value % (one() << bits);
    format!(
        "{bits}'{}h{}",
        if signed { "s" } else { "" },
        v.to_str_radix(16)
    )
}

pub(super) fn zeros(bits: usize) -> String {
    format!("{bits}'h0")
}

pub(super) fn signed_wrap(text: String, signed: bool) -> String {
    if signed {
        format!("$signed({text})")
    } else {
        text
    }
}

pub(super) struct Printer<'a> {
    pub(super) decls: &'a Declarations,
    /// Values of the module's numeric localparams.
    pub(super) constants: &'a Constants,
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
    pub(super) fn emit(&self, e: &Expr, k: usize, ctx: Context) -> Option<String> {
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
                Some(if is_atomic_text(&inner) {
                    inner
                } else {
                    format!("({inner})")
                })
            }
            Expr::Ident(name) => self.fit_leaf(name, own, k, ctx),
            Expr::Number {
                bits,
                signed,
                value,
            } => {
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
                        return Some(if k == wa {
                            inner
                        } else {
                            format!("{{{}, {inner}}}", zeros(k - wa))
                        });
                    }
                    if k <= n {
                        self.emit(a, k, ctx)
                    } else {
                        let low = self.emit(a, n, ctx)?;
                        Some(format!(
                            "{{{}, {}}}",
                            zeros(k - n),
                            parenthesize_compound(a, low)
                        ))
                    }
                }
                "+" | "-" | "*" | "&" | "|" | "^" | "^~" | "~^" => {
                    let (left, right) = (self.emit(a, k, ctx)?, self.emit(b, k, ctx)?);
                    Some(format!(
                        "{} {op} {}",
                        mixed_bitwise(op, a, left),
                        mixed_bitwise(op, b, right)
                    ))
                }
                "<<" | "<<<" => {
                    // Its low k bits are zero when it shifts by k or more.
                    if let Expr::Number { value, .. } = strip_paren(b) {
                        if *value >= BigUint::from(k) {
                            return Some(zeros(k));
                        }
                    }
                    Some(format!(
                        "{} {op} {}",
                        self.emit(a, k, ctx)?,
                        self.emit_self(b)?
                    ))
                }
                ">>" | ">>>" | "/" | "%" | "**" => {
                    if k != ctx.width {
                        return None;
                    }
                    // A logical right shift by its operand's whole width or
                    // more is zero (rust-hdl writes one for some widths of a
                    // unit; slang warns about the shift count).
                    let logical = op == ">>" || (op == ">>>" && !ctx.signed);
                    if let (true, Expr::Number { value, .. }) = (logical, strip_paren(b)) {
                        if *value >= BigUint::from(k) {
                            return Some(zeros(k));
                        }
                    }
                    let right = if op == "/" || op == "%" {
                        self.emit(b, k, ctx)?
                    } else {
                        self.emit_self(b)?
                    };
                    Some(format!("{} {op} {}", self.emit(a, k, ctx)?, right))
                }
                "&&" | "||" => {
                    let (left, right) = (self.emit_self(a)?, self.emit_self(b)?);
                    let inner = format!(
                        "{} {op} {}",
                        mixed_bitwise(op, a, left),
                        mixed_bitwise(op, b, right)
                    );
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
                            if !signed
                                && width_stable(other, decls)
                                && value.bits() as usize <= t_other.bits
                            {
                                width = t_other.bits;
                            }
                        }
                    }
                    let inner_ctx = Context { width, signed };
                    let inner = format!(
                        "{} {op} {}",
                        self.emit(a, width, inner_ctx)?,
                        self.emit(b, width, inner_ctx)?
                    );
                    self.fit_unsigned_compound(inner, 1, k)
                }
            },
            Expr::SignCast(signed, a) => {
                // The operand of $signed / $unsigned is self-determined.
                let inner_ty = self_type(a, decls)?;
                if k == inner_ty.bits {
                    let inner = self.emit_self(a)?;
                    return Some(if *signed {
                        format!("$signed({inner})")
                    } else {
                        format!("$unsigned({inner})")
                    });
                }
                match strip_paren(a) {
                    Expr::Ident(name) => self.fit_leaf(
                        name,
                        Ty {
                            bits: inner_ty.bits,
                            signed: *signed,
                        },
                        k,
                        ctx,
                    ),
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
                    let select = if keep == 1 {
                        format!("{base}[{lsb}]")
                    } else {
                        format!("{base}[{}:{lsb}]", lsb + keep - 1)
                    };
                    return if k <= *w {
                        Some(signed_wrap(select, ctx.signed))
                    } else {
                        self.fit_unsigned_compound(select, *w, k)
                    };
                }
                if k <= *w {
                    Some(signed_wrap(
                        format!("{base}[({offset})+:({k})]"),
                        ctx.signed,
                    ))
                } else {
                    self.fit_unsigned_compound(format!("{base}[({offset})+:({w})]"), *w, k)
                }
            }
            Expr::Range(base, m, l) => {
                let base = self.emit_self(base)?;
                let w = m.abs_diff(*l) + 1;
                if k <= w && m >= l {
                    Some(signed_wrap(
                        format!("{base}[{}:{l}]", l + k - 1),
                        ctx.signed,
                    ))
                } else {
                    self.fit_unsigned_compound(format!("{base}[{m}:{l}]"), w, k)
                }
            }
            Expr::Concat(items) => {
                let parts = items
                    .iter()
                    .map(|i| self.emit_self(i))
                    .collect::<Option<Vec<_>>>()?;
                if k == own.bits {
                    Some(signed_wrap(format!("{{{}}}", parts.join(", ")), ctx.signed))
                } else if k > own.bits && !ctx.signed {
                    Some(format!("{{{}, {}}}", zeros(k - own.bits), parts.join(", ")))
                } else {
                    None
                }
            }
            Expr::Replicate(n, items) => {
                let parts = items
                    .iter()
                    .map(|i| self.emit_self(i))
                    .collect::<Option<Vec<_>>>()?;
                let text = format!("{{{n}{{{}}}}}", parts.join(", "));
                if k == own.bits {
                    Some(signed_wrap(text, ctx.signed))
                } else {
                    self.fit_unsigned_compound(text, own.bits, k)
                }
            }
            Expr::Ternary(c, a, b) => Some(format!(
                "{} ? {} : {}",
                self.emit_self(c)?,
                self.emit(a, k, ctx)?,
                self.emit(b, k, ctx)?
            )),
        }
    }

    /// `e` at its own width, in its own context.
    pub(super) fn emit_self(&self, e: &Expr) -> Option<String> {
        let t = self_type(e, self.decls)?;
        self.emit(
            e,
            t.bits,
            Context {
                width: t.bits,
                signed: t.signed,
            },
        )
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
            let msb = if w == 1 {
                name.to_string()
            } else {
                format!("{name}[{}]", w - 1)
            };
            format!("{{{{{}{{{msb}}}}}, {name}}}", k - w)
        } else {
            format!("{{{}, {name}}}", zeros(k - w))
        };
        // Keep the signedness the context had (a select or a concatenation is unsigned).
        Some(if ctx.signed && (k != w || !own.signed) {
            format!("$signed({text})")
        } else {
            text
        })
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
pub(super) fn is_atomic_text(text: &str) -> bool {
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
    let name_end = t
        .find(|c: char| !(c.is_ascii_alphanumeric() || c == '_' || c == '$' || c == '\''))
        .unwrap_or(t.len());
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

/// `text` (the printed `operand` of `op`) in parentheses when it is itself
/// an unparenthesized `&` under `|` or `^`, or `&&` under `||`: the same
/// value (`&` binds tighter), written as lint tools ask (slang's
/// -Wbitwise-op-parentheses; rust-hdl's `replace_bit` prints `x & ~m | v`).
pub(super) fn mixed_bitwise(op: &str, operand: &Expr, text: String) -> String {
    let inner = match operand {
        Expr::Binary(inner, ..) => inner.as_str(),
        _ => return text,
    };
    let mixed = matches!((op, inner), ("|" | "^", "&") | ("||", "&&"));
    if mixed && !text.starts_with('(') {
        format!("({text})")
    } else {
        text
    }
}

pub(super) fn strip_paren(e: &Expr) -> &Expr {
    match e {
        Expr::Paren(a) => strip_paren(a),
        _ => e,
    }
}

pub(super) fn parenthesize_compound(e: &Expr, text: String) -> String {
    match e {
        Expr::Binary(..) | Expr::Ternary(..) => format!("({text})"),
        _ => text,
    }
}

/// `Some(n)` when `e` is a sized literal of `n` bits, all ones.
pub(super) fn is_all_ones_mask(e: &Expr) -> Option<usize> {
    match strip_paren(e) {
        Expr::Number {
            bits: Some(n),
            signed: false,
            value,
        } if *value == (one() << *n) - one() => Some(*n),
        _ => None,
    }
}
