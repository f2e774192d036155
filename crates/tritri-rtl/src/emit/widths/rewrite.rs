//! The declarations of a module, and the re-printing of one statement span
//! of rust-hdl's `always @(*)` blocks (the spans come from
//! [`crate::emit::statements`]).

use super::*;
use crate::emit::statements::Span;

/// The declared width of every net, variable, port and localparam of a module.
pub fn declarations(words: &[&str]) -> Declarations {
    let mut decls = Declarations::new();
    let mut i = 0;
    while i < words.len() {
        let w = words[i];
        if matches!(
            w,
            "input" | "output" | "inout" | "reg" | "wire" | "logic" | "integer"
        ) {
            let mut k = i;
            while k < words.len()
                && matches!(
                    words[k],
                    "input" | "output" | "inout" | "reg" | "wire" | "logic"
                )
            {
                k += 1;
            }
            let mut ty = Ty {
                bits: 1,
                signed: false,
            };
            if words.get(k) == Some(&"integer") {
                ty = Ty {
                    bits: 32,
                    signed: true,
                };
                k += 1;
            }
            if words.get(k) == Some(&"signed") {
                ty.signed = true;
                k += 1;
            }
            if words.get(k) == Some(&"[") {
                let msb: Option<usize> = words.get(k + 1).and_then(|x| x.parse().ok());
                let lsb: Option<usize> = words.get(k + 3).and_then(|x| x.parse().ok());
                if let (Some(m), Some(l), Some(&":"), Some(&"]")) =
                    (msb, lsb, words.get(k + 2), words.get(k + 4))
                {
                    ty.bits = m.abs_diff(l) + 1;
                    k += 5;
                } else {
                    i = k;
                    continue;
                }
            }
            // Names up to `;`, `)` or `=` (ANSI lists end at `,` + direction).
            while let Some(&name) = words.get(k) {
                if name.starts_with(|c: char| c.is_ascii_alphabetic() || c == '_')
                    && !is_keyword(name)
                {
                    decls.insert(name.to_string(), ty);
                }
                match words.get(k + 1) {
                    Some(&",")
                        if words
                            .get(k + 2)
                            .is_some_and(|n| !matches!(*n, "input" | "output" | "inout")) =>
                    {
                        k += 2
                    }
                    _ => break,
                }
            }
            i = k + 1;
        } else if w == "localparam" || w == "parameter" {
            // localparam NAME = literal;  (rust-hdl's constants and enum labels)
            if let (Some(&name), Some(&"="), Some(&value)) =
                (words.get(i + 1), words.get(i + 2), words.get(i + 3))
            {
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

/// Rewrites the expressions of one statement span; `None` leaves it as is.
pub(super) fn rewrite_span(
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
            let ctx = Context {
                width: target.bits.max(own.bits),
                signed: own.signed,
            };
            let text = printer.emit(&rhs, target.bits, ctx)?;
            Some(vec![(*ra, *rb, text)])
        }
    }
}
