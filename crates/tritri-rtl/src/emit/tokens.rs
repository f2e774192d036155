//! A small Verilog lexer: enough to split rust-hdl's output into modules,
//! rename identifiers and re-print everything else byte for byte.
//!
//! Concatenating the texts of the tokens gives back the input exactly, so
//! every pass edits only the tokens it understands.

#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Kind {
    /// A simple identifier or keyword; may contain `$` after the first
    /// character (rust-hdl's hierarchy separator).
    Identifier,
    /// `$signed`, `$display`, ...
    SystemIdentifier,
    /// `\escaped.name ` (the terminating blank is part of the token).
    EscapedIdentifier,
    /// `12`, `9'h1ff`, `1'b0`, `'0`, and rust-hdl's negative `10'h-5`.
    Number,
    String,
    Comment,
    Whitespace,
    /// `` `default_nettype `` and other compiler directives.
    Directive,
    /// Operators and punctuation, longest match (`<=`, `+:`, `>>>`, ...).
    Punctuation,
}

#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Token {
    pub kind: Kind,
    pub text: String,
}

impl Token {
    pub fn new(kind: Kind, text: impl Into<String>) -> Self {
        Token {
            kind,
            text: text.into(),
        }
    }
    pub fn is(&self, text: &str) -> bool {
        self.text == text && !matches!(self.kind, Kind::Comment | Kind::String)
    }
    pub fn is_trivia(&self) -> bool {
        matches!(self.kind, Kind::Whitespace | Kind::Comment)
    }
}

// Attribute brackets `(*` `*)` are left as two tokens each, so that
// `@(*)` reads as `@ ( * )`.
const PUNCTUATION: [&str; 29] = [
    "<<<", ">>>", "===", "!==", "<=", ">=", "==", "!=", "&&", "||", "<<", ">>", "+:", "-:", "**",
    "~&", "~|", "~^", "^~", "->", "::", "++", "--", "+=", "-=", "|=", "&=", "^=", "'{",
];

fn is_identifier_start(c: char) -> bool {
    c.is_ascii_alphabetic() || c == '_'
}

fn is_identifier_char(c: char) -> bool {
    c.is_ascii_alphanumeric() || c == '_' || c == '$'
}

/// Splits `text` into tokens; never fails (unknown characters become
/// one-character punctuation).
pub fn tokenize(text: &str) -> Vec<Token> {
    let chars: Vec<char> = text.chars().collect();
    let mut tokens = Vec::new();
    let mut i = 0;
    let take = |from: usize, to: usize| chars[from..to].iter().collect::<String>();
    while i < chars.len() {
        let c = chars[i];
        let start = i;
        let kind;
        if c.is_whitespace() {
            while i < chars.len() && chars[i].is_whitespace() {
                i += 1;
            }
            kind = Kind::Whitespace;
        } else if c == '/' && chars.get(i + 1) == Some(&'/') {
            while i < chars.len() && chars[i] != '\n' {
                i += 1;
            }
            kind = Kind::Comment;
        } else if c == '/' && chars.get(i + 1) == Some(&'*') {
            i += 2;
            while i < chars.len() && !(chars[i] == '*' && chars.get(i + 1) == Some(&'/')) {
                i += 1;
            }
            i = (i + 2).min(chars.len());
            kind = Kind::Comment;
        } else if c == '"' {
            i += 1;
            while i < chars.len() && chars[i] != '"' {
                if chars[i] == '\\' {
                    i += 1;
                }
                i += 1;
            }
            i = (i + 1).min(chars.len());
            kind = Kind::String;
        } else if is_identifier_start(c) {
            while i < chars.len() && is_identifier_char(chars[i]) {
                i += 1;
            }
            kind = Kind::Identifier;
        } else if c == '$' && chars.get(i + 1).is_some_and(|&d| is_identifier_start(d)) {
            i += 1;
            while i < chars.len() && is_identifier_char(chars[i]) {
                i += 1;
            }
            kind = Kind::SystemIdentifier;
        } else if c == '\\' {
            while i < chars.len() && !chars[i].is_whitespace() {
                i += 1;
            }
            i = (i + 1).min(chars.len());
            kind = Kind::EscapedIdentifier;
        } else if c == '`' {
            i += 1;
            while i < chars.len() && is_identifier_char(chars[i]) {
                i += 1;
            }
            kind = Kind::Directive;
        } else if c.is_ascii_digit()
            || (c == '\''
                && chars
                    .get(i + 1)
                    .is_some_and(|d| "sSbBoOdDhH01xXzZ".contains(*d)))
        {
            while i < chars.len() && (chars[i].is_ascii_digit() || chars[i] == '_') {
                i += 1;
            }
            if i < chars.len() && chars[i] == '\'' {
                i += 1;
                if i < chars.len() && (chars[i] == 's' || chars[i] == 'S') {
                    i += 1;
                }
                if i < chars.len() && "bBoOdDhH".contains(chars[i]) {
                    i += 1;
                    // rust-hdl prints negative signed literals as `10'h-5`.
                    if i < chars.len() && chars[i] == '-' {
                        i += 1;
                    }
                }
                while i < chars.len()
                    && (chars[i].is_ascii_hexdigit() || "xXzZ_?".contains(chars[i]))
                {
                    i += 1;
                }
            }
            kind = Kind::Number;
        } else {
            let rest: String = chars[i..(i + 3).min(chars.len())].iter().collect();
            let len = PUNCTUATION
                .iter()
                .find(|p| rest.starts_with(*p))
                .map_or(1, |p| p.len());
            i += len;
            kind = Kind::Punctuation;
        }
        tokens.push(Token {
            kind,
            text: take(start, i),
        });
    }
    tokens
}

/// The text of `tokens`, concatenated.
pub fn untokenize(tokens: &[Token]) -> String {
    tokens.iter().map(|t| t.text.as_str()).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Tokenizing and concatenating gives back the input, byte for byte.
    #[test]
    fn round_trip_is_exact() {
        let text = "module top$a(x,y);\n  // c$omment\n  always @(*) y = $signed(x$q) + 9'h1ff /* b */ + \"s$\";\nendmodule // top$a\n";
        assert_eq!(untokenize(&tokenize(text)), text);
    }

    /// `$` inside an identifier stays in the identifier; `$signed` is a system name.
    #[test]
    fn dollar_names() {
        let kinds: Vec<_> = tokenize("a$b $signed 10'h-5 <= x")
            .into_iter()
            .filter(|t| t.kind != Kind::Whitespace)
            .map(|t| (t.kind, t.text))
            .collect();
        assert_eq!(
            kinds,
            vec![
                (Kind::Identifier, "a$b".to_string()),
                (Kind::SystemIdentifier, "$signed".to_string()),
                (Kind::Number, "10'h-5".to_string()),
                (Kind::Punctuation, "<=".to_string()),
                (Kind::Identifier, "x".to_string()),
            ]
        );
    }
}
