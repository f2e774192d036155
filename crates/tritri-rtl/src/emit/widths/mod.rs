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

mod expression;
mod lint_fixes;
mod printer;
mod rewrite;
mod typing;

use crate::emit::statements::StatementParser;
use expression::*;
use lint_fixes::*;
use printer::*;
use rewrite::*;
use typing::*;

/// Applies the pass to a module (see the module docs).
pub fn fix_module(module: &mut Module) {
    // Positions of the non-trivia tokens.
    let positions: Vec<usize> = module
        .tokens
        .iter()
        .enumerate()
        .filter(|(_, t)| !t.is_trivia())
        .map(|(i, _)| i)
        .collect();
    let owned: Vec<String> = positions
        .iter()
        .map(|&i| module.tokens[i].text.clone())
        .collect();
    let words: Vec<&str> = owned.iter().map(String::as_str).collect();
    let decls = declarations(&words);
    let constants = constants(&words);
    // rust-hdl's generated block follows the comment `// Update code`.
    let Some(generated) = module
        .tokens
        .iter()
        .position(|t| t.kind == Kind::Comment && t.text.trim() == "// Update code")
    else {
        return;
    };
    let first = positions
        .iter()
        .position(|&p| p > generated)
        .unwrap_or(words.len());
    let mut decls = decls;
    let mut parser = StatementParser::new(&words, first);
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
    for &endcase in &parser.cases_without_default {
        replacements.push((
            endcase,
            endcase + 1,
            case_default(module, positions[endcase]),
        ));
    }
    // Apply from the end so earlier token positions stay valid.
    replacements.sort_by_key(|r| std::cmp::Reverse(r.0));
    for (a, b, text) in replacements {
        if a >= b {
            continue;
        }
        let (from, to) = (positions[a], positions[b - 1]);
        let original: String = module.tokens[from..=to]
            .iter()
            .map(|t| t.text.as_str())
            .collect();
        if original == text {
            continue;
        }
        module.tokens.splice(
            from..=to,
            std::iter::once(Token::new(Kind::Punctuation, text)),
        );
    }
    // Re-lex so that the rewritten text is tokens again, then drop labels
    // nothing uses.
    let text = module.text();
    module.tokens = tokenize(&text);
    remove_unused_localparams(module);
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::emit::statements::Span;

    fn decls() -> Declarations {
        let mut d = Declarations::new();
        for (n, bits, signed) in [
            ("a", 8, false),
            ("b", 8, false),
            ("y", 9, false),
            ("s", 10, true),
            ("x", 8, true),
        ] {
            d.insert(n.into(), Ty { bits, signed });
        }
        d
    }

    fn rewrite(lhs: &str, rhs: &str) -> String {
        let words_l: Vec<String> = tokenize(lhs)
            .into_iter()
            .filter(|t| !t.is_trivia())
            .map(|t| t.text)
            .collect();
        let words_r: Vec<String> = tokenize(rhs)
            .into_iter()
            .filter(|t| !t.is_trivia())
            .map(|t| t.text)
            .collect();
        let mut words: Vec<&str> = words_l.iter().map(String::as_str).collect();
        let eq = words.len();
        words.push("=");
        words.extend(words_r.iter().map(String::as_str));
        let span = Span::Assignment((0, eq), (eq + 1, words.len()));
        rewrite_span(&words, &span, &decls(), &Constants::new())
            .unwrap()
            .remove(0)
            .2
    }

    /// rust-hdl's widening bit_cast becomes an explicit zero-extension.
    #[test]
    fn bit_cast_becomes_concatenation() {
        assert_eq!(
            rewrite("y", "((a) & 9'h1ff) + ((b) & 9'h1ff)"),
            "{1'h0, a} + {1'h0, b}"
        );
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
        assert_eq!(
            rewrite("s", "$signed(x) + $signed(x)"),
            "$signed({{2{x[7]}}, x}) + $signed({{2{x[7]}}, x})"
        );
    }

    /// A comparison against a literal is done at the operand's width.
    #[test]
    fn comparisons_shrink_literals() {
        assert_eq!(rewrite("y[0]", "a == 32'h5"), "a == 8'h5");
        // A sum is not width-stable: its carry would be lost.
        assert_eq!(
            rewrite("y[0]", "a + b == 32'h5"),
            "{24'h0, a} + {24'h0, b} == 32'h5"
        );
    }

    /// Truncating a compound expression with a right shift is left alone.
    #[test]
    fn unknown_shapes_are_left() {
        let words = ["a", "=", "(", "y", ">>", "1", ")"];
        let span = Span::Assignment((0, 1), (2, 7));
        assert!(rewrite_span(&words, &span, &decls(), &Constants::new()).is_none());
    }

    /// `&` under `|` gets parentheses; a right shift by the operand's width
    /// or more is zero.
    #[test]
    fn lint_shapes() {
        assert_eq!(rewrite("a", "a & b | a ^ b"), "(a & b) | a ^ b");
        assert_eq!(rewrite("a", "a | (a >> 32'h8)"), "a | 8'h0");
        assert_eq!(rewrite("a", "a | (a >> 32'h7)"), "a | (a >> 32'h7)");
    }

    #[test]
    fn numbers_parse() {
        assert_eq!(
            parse_number("9'h1ff"),
            Some(Expr::Number {
                bits: Some(9),
                signed: false,
                value: 511u32.into()
            })
        );
        assert_eq!(
            parse_number("4'h-1"),
            Some(Expr::Number {
                bits: Some(4),
                signed: true,
                value: 15u32.into()
            })
        );
        assert_eq!(
            parse_number("12"),
            Some(Expr::Number {
                bits: None,
                signed: true,
                value: 12u32.into()
            })
        );
    }
}
