//! Verilog's width and signedness rules (IEEE 1364, table 5-22) on the
//! expression tree.

use super::*;

pub type Declarations = HashMap<String, Ty>;

pub(super) fn number_ty(bits: Option<usize>, signed: bool) -> Ty {
    Ty {
        bits: bits.unwrap_or(32),
        signed,
    }
}

/// The self-determined width and signedness of `e` (IEEE 1364 table 5-22).
pub fn self_type(e: &Expr, decls: &Declarations) -> Option<Ty> {
    let unsigned = |bits| {
        Some(Ty {
            bits,
            signed: false,
        })
    };
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
                "+" | "-" | "*" | "/" | "%" | "&" | "|" | "^" | "^~" | "~^" => Some(Ty {
                    bits: ta.bits.max(tb.bits),
                    signed: ta.signed && tb.signed,
                }),
                "<<" | ">>" | "<<<" | ">>>" | "**" => Some(ta),
                _ => unsigned(1),
            }
        }
        Expr::Paren(a) => self_type(a, decls),
        Expr::SignCast(signed, a) => Some(Ty {
            bits: self_type(a, decls)?.bits,
            signed: *signed,
        }),
        Expr::Index(..) => unsigned(1),
        Expr::Slice(_, _, w) => unsigned(*w),
        Expr::Range(_, m, l) => unsigned(m.abs_diff(*l) + 1),
        Expr::Concat(items) => unsigned(
            items
                .iter()
                .map(|i| self_type(i, decls).map(|t| t.bits))
                .sum::<Option<usize>>()?,
        ),
        Expr::Replicate(n, items) => unsigned(
            n * items
                .iter()
                .map(|i| self_type(i, decls).map(|t| t.bits))
                .sum::<Option<usize>>()?,
        ),
        Expr::Ternary(_, a, b) => {
            let (ta, tb) = (self_type(a, decls)?, self_type(b, decls)?);
            Some(Ty {
                bits: ta.bits.max(tb.bits),
                signed: ta.signed && tb.signed,
            })
        }
    }
}

/// True when `e`'s value at a larger width is its zero-extension, so a
/// comparison against it may be done at its own width.
pub(super) fn width_stable(e: &Expr, decls: &Declarations) -> bool {
    match e {
        Expr::Ident(n) => decls.get(n).is_some_and(|t| !t.signed),
        Expr::Index(..)
        | Expr::Slice(..)
        | Expr::Range(..)
        | Expr::Concat(..)
        | Expr::Replicate(..) => true,
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
