//! The statement walker of rust-hdl's combinational blocks, shared by the
//! passes that rewrite them ([`super::widths`], [`super::continuous_assigns`]):
//! `begin ... end`, `if (...) ... else ...`, `case (...) label: ... endcase`
//! and `;`-terminated statements, with the spans of the expressions in them.

pub(crate) enum Span {
    /// `if (` cond `)` or `case (` subject `)`: self-determined.
    SelfDetermined(usize, usize),
    /// lhs `=` rhs `;`: lhs words, rhs words.
    Assignment((usize, usize), (usize, usize)),
    /// A case label (words) and the case subject (words).
    CaseLabel((usize, usize), (usize, usize)),
}

pub(crate) struct StatementParser<'a> {
    pub(crate) words: &'a [&'a str],
    pub(crate) position: usize,
    pub(crate) spans: Vec<Span>,
    /// The `endcase` of every `case` without a `default` label.
    pub(crate) cases_without_default: Vec<usize>,
}

impl<'a> StatementParser<'a> {
    pub(crate) fn new(words: &'a [&'a str], position: usize) -> Self {
        StatementParser {
            words,
            position,
            spans: Vec::new(),
            cases_without_default: Vec::new(),
        }
    }

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

    pub(crate) fn statement(&mut self) -> Option<()> {
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
                let mut default = false;
                while self.peek()? != "endcase" {
                    // Labels up to `:`.
                    let label = self.position;
                    while self.peek()? != ":" {
                        self.position += 1;
                    }
                    if self.words[label] == "default" {
                        default = true;
                    } else {
                        self.spans
                            .push(Span::CaseLabel((label, self.position), (open + 1, close)));
                    }
                    self.position += 1;
                    self.statement()?;
                }
                if !default {
                    self.cases_without_default.push(self.position);
                }
                self.position += 1;
            }
            ";" => self.position += 1,
            _ => {
                // An assignment, or any other statement up to its `;`.
                let start = self.position;
                let end = (start..self.words.len()).find(|&k| self.words[k] == ";")?;
                if let Some(equals) = (start..end).find(|&k| self.words[k] == "=") {
                    self.spans
                        .push(Span::Assignment((start, equals), (equals + 1, end)));
                }
                self.position = end + 1;
            }
        }
        Some(())
    }
}

/// Index just past the statement that starts at word `start`.
pub(crate) fn statement_end(words: &[&str], start: usize) -> Option<usize> {
    let mut parser = StatementParser::new(words, start);
    parser.statement()?;
    Some(parser.position)
}
