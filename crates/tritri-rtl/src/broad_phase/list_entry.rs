//! A list entry in external memory: one triangle of a cell's list, with
//! its vertices, so a pass reads a list front to back and never fetches a
//! triangle by its index (a random 27-byte read per entry).
//!
//! 32 bytes, little-endian, the host's format as well as the passes':
//!
//! | bits | field |
//! |---|---|
//! | `0 .. 9G` | `x0 y0 z0 x1 y1 z1 x2 y2 z2`, `G`-bit two's complement grid coordinates, from bit 0 up |
//! | `9G .. 224` | zero |
//! | `224 .. 256` | the triangle's index in its object's array (32 bits) |
//!
//! So `G` is at most [`MAX_GRID_BITS`], and an object has at most `2^32`
//! triangles.

use tritri_geom::fixed_point::FixedTriangle;

/// Bits of an entry.
pub const ENTRY_BITS: usize = 256;
/// Bytes of an entry.
pub const ENTRY_BYTES: usize = ENTRY_BITS / 8;
/// Where the index begins.
pub const INDEX_OFFSET: usize = 224;
/// The widest grid whose vertices fit below the index.
pub const MAX_GRID_BITS: usize = INDEX_OFFSET / 9;

/// The entry of triangle `index` on a `grid_bits`-bit grid. The host packs
/// one for every triangle it sends, so the coordinates go in as whole
/// fields into four 64-bit words, not bit by bit.
pub fn pack(index: u32, triangle: &FixedTriangle, grid_bits: usize) -> [u8; ENTRY_BYTES] {
    assert!(
        (1..=MAX_GRID_BITS).contains(&grid_bits),
        "an entry holds 1- to {MAX_GRID_BITS}-bit coordinates, not {grid_bits}"
    );
    let mut words = [0u64; ENTRY_BITS / 64];
    let mask = (1u64 << grid_bits) - 1;
    for (k, v) in triangle.iter().flatten().enumerate() {
        let raw = (*v as u64) & mask;
        let (word, offset) = (k * grid_bits / 64, k * grid_bits % 64);
        words[word] |= raw << offset;
        // A field across two words (G <= 24 < 64: never more than two).
        if offset + grid_bits > 64 {
            words[word + 1] |= raw >> (64 - offset);
        }
    }
    words[INDEX_OFFSET / 64] |= u64::from(index) << (INDEX_OFFSET % 64);
    let mut bytes = [0u8; ENTRY_BYTES];
    for (chunk, word) in bytes.chunks_exact_mut(8).zip(words) {
        chunk.copy_from_slice(&word.to_le_bytes());
    }
    bytes
}

/// The index and vertices of an entry on a `grid_bits`-bit grid.
pub fn unpack(bytes: &[u8], grid_bits: usize) -> (u32, FixedTriangle) {
    let bit = |at: usize| bytes[at / 8] >> (at % 8) & 1;
    let mut triangle = [[0i64; 3]; 3];
    for k in 0..9 {
        let raw = (0..grid_bits).fold(0u64, |v, b| v | u64::from(bit(k * grid_bits + b)) << b);
        // Sign-extend from bit G - 1.
        let shift = 64 - grid_bits;
        triangle[k / 3][k % 3] = ((raw << shift) as i64) >> shift;
    }
    let mut index = [0u8; 4];
    index.copy_from_slice(&bytes[INDEX_OFFSET / 8..INDEX_OFFSET / 8 + 4]);
    (u32::from_le_bytes(index), triangle)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_entry_keeps_its_index_and_signed_vertices() {
        let t = [[-1, 0, 5], [8_388_607, -8_388_608, 3], [-2, 7, -9]];
        for g in [24, 20] {
            let t = t.map(|v| v.map(|c: i64| c.clamp(-(1 << (g - 1)), (1 << (g - 1)) - 1)));
            let bytes = pack(4_000_000_007, &t, g);
            assert_eq!(unpack(&bytes, g), (4_000_000_007, t));
        }
        // Nothing between the vertices and the index.
        let bytes = pack(0, &[[-1; 3]; 3], 16);
        assert!(bytes[18..28].iter().all(|&b| b == 0));
        assert_eq!(bytes[17], 0xff);
    }

    /// The format written out bit by bit, as the table above reads.
    fn pack_bit_by_bit(index: u32, triangle: &FixedTriangle, g: usize) -> [u8; ENTRY_BYTES] {
        let mut bytes = [0u8; ENTRY_BYTES];
        for (k, v) in triangle.iter().flatten().enumerate() {
            for bit in 0..g {
                if (*v as u64) >> bit & 1 == 1 {
                    bytes[(k * g + bit) / 8] |= 1 << ((k * g + bit) % 8);
                }
            }
        }
        bytes[INDEX_OFFSET / 8..].copy_from_slice(&index.to_le_bytes());
        bytes
    }

    #[test]
    fn fields_packed_word_by_word_are_the_bit_by_bit_format() {
        // Every grid width an entry holds, fields across word boundaries included.
        let mut x: u64 = 0x9e37_79b9_7f4a_7c15;
        for g in 1..=MAX_GRID_BITS {
            for _ in 0..50 {
                let triangle: FixedTriangle = std::array::from_fn(|_| {
                    std::array::from_fn(|_| {
                        x = x
                            .wrapping_mul(6364136223846793005)
                            .wrapping_add(1442695040888963407);
                        ((x >> 20) as i64 & ((1 << g) - 1)) - (1 << (g - 1))
                    })
                });
                let index = (x >> 7) as u32;
                assert_eq!(
                    pack(index, &triangle, g),
                    pack_bit_by_bit(index, &triangle, g),
                    "G = {g}"
                );
                assert_eq!(unpack(&pack(index, &triangle, g), g), (index, triangle));
            }
        }
    }
}
