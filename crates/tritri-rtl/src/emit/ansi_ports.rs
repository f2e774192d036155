//! Port declarations in the module header (Verilog-2001, "ANSI" style),
//! as lowRISC's style guide and every current linter expect:
//!
//! ```verilog
//! module tritri_pipeline_w24_decision (
//!     input  wire        clock,
//!     input  wire [73:0] value,
//!     output reg         hit
//! );
//! ```
//!
//! rust-hdl prints the Verilog-95 form instead: a header that lists the
//! names, `module m(clock,value,hit);`, then one `input wire [73:0] value;`
//! declaration per port in the body. This pass moves each declaration into
//! the header, in the header's order, columns aligned, and removes it from
//! the body. It only moves text: a module whose header is already ANSI, or
//! whose ports it cannot all find as one-line declarations, is left as it
//! is (the formal equivalence test of the emission covers it).

use super::modules::Module;
use super::tokens::tokenize;

/// Rewrites `module`'s port list in place (module docs).
pub fn ansi_ports(module: &mut Module) {
    if let Some(text) = rewrite(&module.text()) {
        module.tokens = tokenize(&text);
    }
}

/// One port declaration taken from the body.
struct Declaration {
    direction: String,
    kind: String,
    range: String,
    name: String,
}

fn rewrite(text: &str) -> Option<String> {
    let start = text.find("module ")?;
    let open = start + text[start..].find('(')?;
    let close = open + text[open..].find(')')?;
    let after = text[close + 1..].trim_start();
    if !after.starts_with(';') {
        return None;
    }
    let header_end = close + 1 + text[close + 1..].find(';')? + 1;
    let names: Vec<&str> = text[open + 1..close].split(',').map(str::trim).collect();
    if names
        .iter()
        .any(|n| n.is_empty() || !n.chars().all(|c| c.is_ascii_alphanumeric() || c == '_'))
    {
        return None; // already ANSI, or not a plain name list
    }
    let module_name = text[start + "module ".len()..open].trim();

    let body = &text[header_end..];
    let mut kept = Vec::new();
    let mut declarations: Vec<Option<Declaration>> = names.iter().map(|_| None).collect();
    for line in body.split_inclusive('\n') {
        if let Some(d) = declaration(line) {
            if let Some(k) = names.iter().position(|n| *n == d.name) {
                if declarations[k].is_none() {
                    declarations[k] = Some(d);
                    continue;
                }
            }
        }
        if line.trim() == "// Module arguments" {
            continue;
        }
        kept.push(line);
    }
    let declarations: Vec<Declaration> = declarations.into_iter().collect::<Option<_>>()?;

    let kind_width = declarations.iter().map(|d| d.kind.len()).max().unwrap_or(0);
    let range_width = declarations
        .iter()
        .map(|d| d.range.len())
        .max()
        .unwrap_or(0);
    let mut header = format!("module {module_name} (\n");
    for (k, d) in declarations.iter().enumerate() {
        let separator = if k + 1 == declarations.len() { "" } else { "," };
        let line = format!(
            "    {:<6} {:<kind_width$} {:<range_width$} {}{separator}",
            d.direction, d.kind, d.range, d.name
        );
        header.push_str(&squeeze_empty_columns(&line, kind_width, range_width));
        header.push('\n');
    }
    header.push_str(");");
    // The body's first line after the header was rust-hdl's blank line
    // before the (now removed) "// Module arguments" block; drop a second
    // blank line that the removal leaves.
    let mut body_text: String = kept.concat();
    while body_text.starts_with("\n\n\n") {
        body_text.remove(0);
    }
    Some(format!("{}{header}{body_text}", &text[..start]))
}

/// Without any ranges (or kinds) the aligned columns would leave runs of
/// blanks; keep one.
fn squeeze_empty_columns(line: &str, kind_width: usize, range_width: usize) -> String {
    if kind_width == 0 || range_width == 0 {
        let mut out = String::new();
        for (k, word) in line.split_whitespace().enumerate() {
            out.push_str(if k == 0 { "    " } else { " " });
            out.push_str(word);
        }
        out
    } else {
        line.trim_end().to_string()
    }
}

/// `input wire [23:0] in_x0;` (one line, nothing else on it).
fn declaration(line: &str) -> Option<Declaration> {
    let line = line.trim();
    let line = line.strip_suffix(';')?;
    let mut words = line.split_whitespace().peekable();
    let direction = words.next()?;
    if !matches!(direction, "input" | "output" | "inout") {
        return None;
    }
    let mut kind = String::new();
    if let Some(&w) = words.peek() {
        if matches!(w, "wire" | "reg" | "logic") {
            kind = w.to_string();
            words.next();
        }
    }
    if let Some(&"signed") = words.peek() {
        kind = if kind.is_empty() {
            "signed".into()
        } else {
            format!("{kind} signed")
        };
        words.next();
    }
    let rest: Vec<&str> = words.collect();
    let (range, name) = match rest.as_slice() {
        [name] => (String::new(), *name),
        [range @ .., name] if range.concat().starts_with('[') && range.concat().ends_with(']') => {
            (range.concat(), *name)
        }
        _ => return None,
    };
    Some(Declaration {
        direction: direction.to_string(),
        kind,
        range,
        name: name.to_string(),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn verilog_95_ports_move_into_the_header() {
        let text = "module m(clock,value,hit);\n\n    // Module arguments\n    input wire  clock;\n    input wire  [73:0] value;\n    output reg  hit;\n\n    // Update code\n    always @(posedge clock) hit <= value[73];\nendmodule";
        let out = rewrite(text).unwrap();
        assert_eq!(
            out,
            "module m (\n    input  wire        clock,\n    input  wire [73:0] value,\n    output reg         hit\n);\n\n    // Update code\n    always @(posedge clock) hit <= value[73];\nendmodule"
        );
    }

    #[test]
    fn ansi_headers_and_missing_declarations_are_left_alone() {
        assert_eq!(rewrite("module m (\n    input wire a\n);\nendmodule"), None);
        assert_eq!(
            rewrite("module m(a,b);\n    input wire a;\nendmodule"),
            None
        );
    }
}
