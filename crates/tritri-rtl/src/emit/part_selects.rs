//! rust-hdl writes an assignment to a field of a packed struct
//! (`LogicStruct`) as an indexed part-select with a 64-bit constant base,
//! `entry[(64'h28)+:(11)] = x;`, which Verilator's lint rejects as a width
//! mismatch (the base needs only the vector's index bits). A constant base
//! makes it a plain slice: this pass writes `entry[50:40]`, the same bits.

/// `text` with every `[(64'hB)+:(W)]` replaced by `[B+W-1:B]`, and every
/// `[(NAME)+:(W)]` whose base is a sized localparam of its module
/// (`localparam  NAME = 16'hB;`, a rust-hdl `Constant` used as an offset)
/// the same way.
pub fn constant_part_selects(text: &str) -> String {
    let text = localparam_part_selects(text);
    bits_of_slices(&literal_part_selects(&text))
}

/// `x[H:L][K]` (a bit of a struct field: rust-hdl's `field.get_bit(K)`,
/// K a number or rust-hdl's `32'hK`), which Icarus rejects, written `x[L+K]`.
fn bits_of_slices(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    let mut rest = text;
    while let Some(at) = rest.find("][") {
        let (before, after) = (&rest[..at], &rest[at + 2..]);
        let slice = before.rfind('[').and_then(|open| {
            let (high, low) = before[open + 1..].split_once(':')?;
            let (high, low): (u64, u64) = (high.parse().ok()?, low.parse().ok()?);
            let close = after.find(']')?;
            let index = &after[..close];
            let bit = match index.strip_prefix("32'h") {
                Some(hex) => u64::from_str_radix(hex, 16).ok()?,
                None => index.parse().ok()?,
            };
            (low + bit <= high).then_some((open, low + bit, close))
        });
        match slice {
            Some((open, bit, close)) => {
                out.push_str(&before[..open]);
                out.push_str(&format!("[{bit}]"));
                rest = &after[close + 1..];
            }
            None => {
                out.push_str(&rest[..at + 2]);
                rest = after;
            }
        }
    }
    out.push_str(rest);
    out
}

/// `[(NAME)+:(W)]` with NAME a localparam of the enclosing module
/// replaced by `[(64'hB)+:(W)]`, module by module (names repeat across
/// modules with other values).
fn localparam_part_selects(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    for module in text.split_inclusive("endmodule") {
        let mut module = module.to_string();
        let values: Vec<(String, u64)> = module
            .lines()
            .filter_map(|line| {
                let rest = line.trim().strip_prefix("localparam")?;
                let (name, value) = rest.trim_end_matches(';').split_once('=')?;
                let (_, hex) = value.trim().split_once("'h")?;
                Some((name.trim().to_string(), u64::from_str_radix(hex, 16).ok()?))
            })
            .collect();
        for (name, value) in values {
            module = module.replace(&format!("[({name})+:("), &format!("[(64'h{value:x})+:("));
        }
        out.push_str(&module);
    }
    out
}

/// `text` with every `[(64'hB)+:(W)]` replaced by `[B+W-1:B]`.
fn literal_part_selects(text: &str) -> String {
    const OPEN: &str = "[(64'h";
    let mut out = String::with_capacity(text.len());
    let mut rest = text;
    while let Some(at) = rest.find(OPEN) {
        out.push_str(&rest[..at]);
        let after = &rest[at + OPEN.len()..];
        match parse_select(after) {
            Some((base, width, used)) => {
                out.push_str(&format!("[{}:{}]", base + width - 1, base));
                rest = &after[used..];
            }
            None => {
                out.push_str(OPEN);
                rest = after;
            }
        }
    }
    out.push_str(rest);
    out
}

/// `B)+:(W)]` at the start of `s`: the base, the width and the bytes used.
fn parse_select(s: &str) -> Option<(u64, u64, usize)> {
    let close = s.find(")+:(")?;
    let base = u64::from_str_radix(&s[..close], 16).ok()?;
    let width_text = &s[close + 4..];
    let end = width_text.find(")]")?;
    let width: u64 = width_text[..end].parse().ok()?;
    (width >= 1).then_some((base, width, close + 4 + end + 2))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn constant_bases_become_slices() {
        assert_eq!(
            constant_part_selects("pushed[(64'h28)+:(11)] = x;"),
            "pushed[50:40] = x;"
        );
        assert_eq!(
            constant_part_selects("a[(64'h0)+:(40)] = b; c[(64'hz)+:(3)]"),
            "a[39:0] = b; c[(64'hz)+:(3)]"
        );
        assert_eq!(constant_part_selects("plain[3:0]"), "plain[3:0]");
    }

    #[test]
    fn a_bit_of_a_slice_is_one_bit_select() {
        assert_eq!(
            constant_part_selects("if (top_q[360:357][2]) x = m[3:0][1:0];"),
            "if (top_q[359]) x = m[3:0][1:0];"
        );
        assert_eq!(constant_part_selects("a[(64'h8)+:(4)][3]"), "a[11]");
        assert_eq!(
            constant_part_selects("a[(64'h8)+:(4)][32'ha]"),
            "a[(64'h8)+:(4)][32'ha]".replace("(64'h8)+:(4)", "11:8")
        );
    }

    #[test]
    fn localparam_bases_become_slices_with_their_modules_values() {
        let text = "module a;\n    localparam  off$1 = 16'h10;\n    assign x = v[(off$1)+:(16)];\nendmodule\n\
                    module b;\n    localparam  off$1 = 16'h20;\n    assign y = v[(off$1)+:(4)]; assign z = v[(other)+:(4)];\nendmodule\n";
        let out = constant_part_selects(text);
        assert!(out.contains("assign x = v[31:16];"), "{out}");
        assert!(out.contains("assign y = v[35:32];"), "{out}");
        assert!(out.contains("v[(other)+:(4)]"), "{out}");
    }
}
