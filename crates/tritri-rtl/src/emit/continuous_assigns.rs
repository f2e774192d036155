//! Moves the unconditional assignments out of rust-hdl's combinational
//! block into continuous `assign` statements.
//!
//! rust-hdl prints a module's combinational logic as one
//! `always @(*) begin ... end` block. Verilator schedules a block as one
//! unit, so a block that drives one child's input and reads another child's
//! output that depends on it combinationally (the valid/ready handshakes
//! between the system's result FIFO and its pair serializer) looks like a
//! combinational loop: `verilator -Wall` reports UNOPTFLAT and evaluates
//! the block repeatedly. The loop is false: each signal depends on others
//! only in one direction.
//!
//! This pass takes every statement `x = e;` at the top level of such a
//! block (not under an `if` or `case`) whose target `x` is a plain
//! identifier assigned nowhere else in the module and not read by `e`,
//! writes it as `assign x = e;` before the block, and declares `x` a
//! `wire`. The statements left (conditional assignments, multiplexers,
//! next-state logic) stay in the block; a block left empty is removed.
//! Semantics are unchanged: the block's statements were already evaluated
//! whenever an operand changed, and a single unconditional assignment is
//! exactly a continuous one.

use super::modules::Module;
use super::statements::statement_end;
use super::tokens::{tokenize, Kind, Token};

/// Words (non-trivia tokens) of a module with their token positions.
struct Words {
    positions: Vec<usize>,
    texts: Vec<String>,
}

impl Words {
    fn texts(&self) -> Vec<&str> {
        self.texts.iter().map(String::as_str).collect()
    }
    fn of(module: &Module) -> Self {
        let positions: Vec<usize> = module
            .tokens
            .iter()
            .enumerate()
            .filter(|(_, t)| !t.is_trivia())
            .map(|(i, _)| i)
            .collect();
        let texts = positions
            .iter()
            .map(|&i| module.tokens[i].text.clone())
            .collect();
        Words { positions, texts }
    }
    fn get(&self, k: usize) -> Option<&str> {
        self.texts.get(k).map(String::as_str)
    }
    fn len(&self) -> usize {
        self.texts.len()
    }
}

/// Word indices at which `name` is the target of an assignment: the name
/// at the start of a statement, followed by `=`, `<=` or a select `[`.
fn assignment_targets(words: &Words, name: &str) -> usize {
    (0..words.len())
        .filter(|&k| {
            words.get(k) == Some(name)
                && matches!(words.get(k + 1), Some("=" | "<=" | "["))
                && k > 0
                && matches!(
                    words.get(k - 1),
                    Some(";" | "begin" | "else" | ")" | ":" | "end")
                )
        })
        .count()
}

/// The `reg` keyword of `name`'s declaration, if it is declared alone
/// (`reg [7:0] name;` or `output reg name;`).
fn declaration_reg(words: &Words, name: &str, before: usize) -> Option<usize> {
    (0..before).find_map(|k| {
        if words.get(k) != Some(name) || words.get(k + 1) != Some(";") {
            return None;
        }
        let start = (0..k).rev().find(|&j| words.get(j) == Some(";")).map_or(0, |j| j + 1);
        let statement: Vec<&str> = (start..k).filter_map(|j| words.get(j)).collect();
        let declares_reg = matches!(statement.first(), Some(&"reg"))
            || matches!(statement.as_slice(), [first, "reg", ..] if matches!(*first, "output" | "input"));
        (declares_reg && !statement.contains(&",")).then(|| start + statement.iter().position(|w| *w == "reg").unwrap())
    })
}

/// Applies the pass to a module (see the module docs).
pub fn continuous_assigns(module: &mut Module) {
    let words = Words::of(module);
    let texts = words.texts();
    // (word of `always`, first moved statement word, end of statement) and
    // the `reg` keywords to turn into `wire`.
    let mut moved: Vec<(usize, usize, usize)> = Vec::new();
    let mut regs: Vec<usize> = Vec::new();
    let mut empty_blocks: Vec<(usize, usize)> = Vec::new();
    let mut k = 0;
    while k < words.len() {
        let is_combinational = words.get(k) == Some("always")
            && (1..=5)
                .map(|d| words.get(k + d))
                .eq(["@", "(", "*", ")", "begin"].map(Some));
        if !is_combinational {
            k += 1;
            continue;
        }
        let always = k;
        // The block's `end`: its `begin ... end` is one statement.
        let Some(end) = statement_end(&texts, k + 5).map(|after| after - 1) else {
            return;
        };
        let mut statement = k + 6;
        let mut kept = 0;
        while statement < end {
            let Some(next) = statement_end(&texts, statement) else {
                return;
            };
            let target = words.get(statement).unwrap_or_default();
            let simple = words
                .positions
                .get(statement)
                .is_some_and(|&p| module.tokens[p].kind == Kind::Identifier)
                && words.get(statement + 1) == Some("=");
            let reads_itself = (statement + 2..next).any(|j| words.get(j) == Some(target));
            let reg = if simple && !reads_itself && assignment_targets(&words, target) == 1 {
                declaration_reg(&words, target, always)
            } else {
                None
            };
            match reg {
                Some(r) => {
                    moved.push((always, statement, next));
                    regs.push(r);
                }
                None => kept += 1,
            }
            statement = next;
        }
        if kept == 0 {
            empty_blocks.push((always, end));
        }
        k = end + 1;
    }
    if moved.is_empty() {
        return;
    }

    // Rebuild the token list: declarations, assigns before their block,
    // the block without the moved statements.
    let text_of = |from: usize, to: usize| -> String {
        module.tokens[words.positions[from]..=words.positions[to - 1]]
            .iter()
            .map(|t| t.text.as_str())
            .collect()
    };
    let mut out: Vec<Token> = Vec::with_capacity(module.tokens.len());
    let mut skip_until = 0usize; // token index up to which tokens are dropped
    let reg_tokens: Vec<usize> = regs.iter().map(|&r| words.positions[r]).collect();
    for (i, token) in module.tokens.iter().enumerate() {
        if i < skip_until {
            continue;
        }
        let word = words.positions.binary_search(&i).ok();
        if let Some(w) = word {
            if let Some(&(_, end)) = empty_blocks.iter().find(|(a, _)| *a == w) {
                // The assigns of an emptied block, then nothing of the block.
                for &(_, from, to) in moved.iter().filter(|(a, _, _)| *a == w) {
                    out.push(Token::new(
                        Kind::Punctuation,
                        format!("assign {}", text_of(from, to)),
                    ));
                    out.push(Token::new(Kind::Whitespace, "\n    "));
                }
                strip_trailing_indent(&mut out);
                skip_until = words.positions[end] + 1;
                continue;
            }
            if words.get(w) == Some("always") && moved.iter().any(|(a, _, _)| *a == w) {
                for &(_, from, to) in moved.iter().filter(|(a, _, _)| *a == w) {
                    out.push(Token::new(
                        Kind::Punctuation,
                        format!("assign {}", text_of(from, to)),
                    ));
                    out.push(Token::new(Kind::Whitespace, "\n    "));
                }
            }
            if let Some(&(_, _, to)) = moved.iter().find(|(_, from, _)| *from == w) {
                // Drop the statement and the indentation before it.
                strip_trailing_indent(&mut out);
                skip_until = words.positions[to - 1] + 1;
                continue;
            }
            if reg_tokens.contains(&i) {
                out.push(Token::new(Kind::Identifier, "wire"));
                continue;
            }
        }
        out.push(token.clone());
    }
    module.tokens = tokenize(&out.iter().map(|t| t.text.as_str()).collect::<String>());
}

/// Removes the blanks at the end of `out` back to (not including) the last
/// newline, so a dropped statement leaves no blank line behind.
fn strip_trailing_indent(out: &mut Vec<Token>) {
    if let Some(last) = out.last_mut() {
        if last.kind == Kind::Whitespace {
            match last.text.rfind('\n') {
                Some(n) => last.text.truncate(n),
                None => {
                    out.pop();
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::emit::modules::split_modules;

    fn run(text: &str) -> String {
        let mut m = split_modules(text).unwrap().remove(0);
        continuous_assigns(&mut m);
        m.text()
    }

    #[test]
    fn unconditional_assignments_become_assigns() {
        let out = run("module top(a,b,y,z);\n    input wire  a;\n    input wire  b;\n    output reg  y;\n    output reg  z;\n    reg  t;\n\n    // Update code\n    always @(*) begin\n        t = a & b;\n        y = t;\n        z = 1'b0;\n        if (a) z = b;\n    end\nendmodule\n");
        assert!(
            out.contains("output wire  y;") && out.contains("wire  t;"),
            "{out}"
        );
        assert!(out.contains("output reg  z;"), "z is assigned twice: {out}");
        assert!(
            out.contains(
                "assign t = a & b;\n    assign y = t;\n    always @(*) begin\n        z = 1'b0;"
            ),
            "{out}"
        );
    }

    #[test]
    fn an_emptied_block_is_removed() {
        let out = run("module top(a,y);\n    input wire  a;\n    output reg  y;\n\n    // Update code\n    always @(*) begin\n        y = ~a;\n    end\nendmodule\n");
        assert!(!out.contains("always"), "{out}");
        assert!(
            out.contains("output wire  y;") && out.contains("assign y = ~a;"),
            "{out}"
        );
    }

    #[test]
    fn registers_and_selects_stay() {
        let text = "module top(clock,a,y);\n    input wire  clock;\n    input wire  [1:0] a;\n    output reg  [1:0] y;\n    reg  [1:0] q;\n\n    // Update code\n    always @(*) begin\n        y[0] = a[1];\n        y[1] = q[0];\n    end\n    always @(posedge clock) begin\n        q <= a;\n    end\nendmodule\n";
        assert_eq!(run(text), split_modules(text).unwrap()[0].text());
    }
}
