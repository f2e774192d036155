//! rust-hdl writes an assignment to a field of a packed struct
//! (`LogicStruct`) as an indexed part-select with a 64-bit constant base,
//! `entry[(64'h28)+:(11)] = x;`, which Verilator's lint rejects as a width
//! mismatch (the base needs only the vector's index bits). A constant base
//! makes it a plain slice: this pass writes `entry[50:40]`, the same bits.

/// `text` with every `[(64'hB)+:(W)]` replaced by `[B+W-1:B]`.
pub fn constant_part_selects(text: &str) -> String {
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
        assert_eq!(constant_part_selects("pushed[(64'h28)+:(11)] = x;"), "pushed[50:40] = x;");
        assert_eq!(constant_part_selects("a[(64'h0)+:(40)] = b; c[(64'hz)+:(3)]"), "a[39:0] = b; c[(64'hz)+:(3)]");
        assert_eq!(constant_part_selects("plain[3:0]"), "plain[3:0]");
    }
}
