//! Rewrites of whole declarations and statements for the lint tools: enum
//! labels sized to their register, unused labels dropped, a `default` for
//! every `case`.

use super::*;
use crate::emit::statements::Span;

/// The text that replaces the `endcase` token at `endcase` of a `case`
/// without a `default`: an empty `default: ;` before it, one level in.
/// The same circuit (every signal the `case` assigns was given a value
/// before it), and a `case` that says it covers the rest, as lint tools
/// ask (slang's -Wcase-default).
pub(super) fn case_default(module: &Module, endcase: usize) -> String {
    let indent = match module.tokens.get(endcase.wrapping_sub(1)) {
        Some(t) if t.kind == Kind::Whitespace => t.text.rsplit('\n').next().unwrap_or(""),
        _ => "",
    };
    format!("    default: ;\n{indent}endcase")
}

/// rust-hdl declares enum labels as unsized `localparam Label = 2;` (32-bit
/// signed), then assigns them to and compares them with a register of the
/// enum's width. When every such use agrees on one width, the label is
/// declared with it: `localparam [1:0] Label = 2'd2;`.
pub(super) fn size_enum_labels(
    positions: &[usize],
    words: &[&str],
    spans: &[Span],
    decls: &mut Declarations,
) -> Vec<(usize, String)> {
    let mut edits = Vec::new();
    // Unsized localparams: name -> word index of `localparam`.
    let mut unsized_labels: HashMap<&str, usize> = HashMap::new();
    for i in 0..words.len().saturating_sub(3) {
        if words[i] == "localparam"
            && words[i + 2] == "="
            && words[i + 3].chars().all(|c| c.is_ascii_digit())
        {
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
        let other_ty =
            parse_expression(&words[other.0..other.1]).and_then(|e| self_type(&e, decls));
        if single.1 == single.0 + 1 {
            note(words[single.0], other_ty.map(|t| t.bits));
        } else {
            note_label_uses(&words[single.0..single.1], decls, &mut note);
        }
    }
    for span in spans {
        if let Span::SelfDetermined(a, b) = span {
            note_label_uses(&words[*a..*b], decls, &mut note);
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
        let range = if w == 1 {
            String::new()
        } else {
            format!(" [{}:0]", w - 1)
        };
        edits.push((positions[i], format!("localparam{range}")));
        edits.push((positions[i + 3], format!("{w}'d{value}")));
        decls.insert(
            name.to_string(),
            Ty {
                bits: w,
                signed: false,
            },
        );
    }
    edits
}

/// The uses of names in an expression: a name compared with `==` or `!=`
/// takes the width of the other side; any other use keeps a label as
/// rust-hdl wrote it (as does an expression the parser does not know).
pub(super) fn note_label_uses(
    words: &[&str],
    decls: &Declarations,
    note: &mut impl FnMut(&str, Option<usize>),
) {
    fn walk(e: &Expr, decls: &Declarations, note: &mut impl FnMut(&str, Option<usize>)) {
        match e {
            Expr::Binary(op, a, b) if op == "==" || op == "!=" => {
                for (x, y) in [(a, b), (b, a)] {
                    match strip_paren(x) {
                        Expr::Ident(n) => note(n, self_type(y, decls).map(|t| t.bits)),
                        other => walk(other, decls, note),
                    }
                }
            }
            Expr::Ident(n) => note(n, None),
            Expr::Number { .. } => {}
            Expr::Unary(_, a) | Expr::Paren(a) | Expr::SignCast(_, a) => walk(a, decls, note),
            Expr::Index(a, index) => {
                walk(a, decls, note);
                index
                    .split(|c: char| !(c.is_ascii_alphanumeric() || c == '_'))
                    .for_each(|w| note(w, None));
            }
            Expr::Slice(a, offset, _) => {
                walk(a, decls, note);
                offset
                    .split(|c: char| !(c.is_ascii_alphanumeric() || c == '_'))
                    .for_each(|w| note(w, None));
            }
            Expr::Range(a, ..) => walk(a, decls, note),
            Expr::Binary(_, a, b) => {
                walk(a, decls, note);
                walk(b, decls, note);
            }
            Expr::Concat(items) | Expr::Replicate(_, items) => {
                items.iter().for_each(|i| walk(i, decls, note))
            }
            Expr::Ternary(c, a, b) => [c, a, b].iter().for_each(|x| walk(x, decls, note)),
        }
    }
    match parse_expression(words) {
        Some(e) => walk(&e, decls, note),
        None => words.iter().for_each(|w| note(w, None)),
    }
}

/// Drops `localparam NAME = ...;` lines whose name is never used: rust-hdl
/// copies every label of an enum into each module that holds one.
pub(super) fn remove_unused_localparams(module: &mut Module) {
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
                    if from > 0
                        && tokens[from - 1].kind == Kind::Whitespace
                        && !tokens[from - 1].text.contains('\n')
                    {
                        from -= 1;
                    }
                    let mut to = end;
                    if tokens
                        .get(to + 1)
                        .is_some_and(|t| t.kind == Kind::Whitespace)
                    {
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
