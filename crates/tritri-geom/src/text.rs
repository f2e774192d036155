//! Text files as the readers take them.

/// `bytes` as UTF-8 text, or the 1-based line of the first byte that is
/// not, so that the error points into the file like any other.
pub(crate) fn utf8_text(bytes: &[u8]) -> Result<&str, usize> {
    std::str::from_utf8(bytes).map_err(|e| {
        1 + bytes[..e.valid_up_to()]
            .iter()
            .filter(|&&b| b == b'\n')
            .count()
    })
}
