//! Conversions between rust-hdl bit vectors and two's-complement integers,
//! for the exact simulation models of the arithmetic primitives and for test
//! benches. Values are kept as plain [`Bits`] (two's complement, no sign
//! attached), which sidesteps the `Signed` pitfalls of rust-hdl 0.46
//! (docs/ARCHITECTURE.md, conventions): `Signed::from(i64)` overflows the stack on `-2^(N-1)`.

use rust_hdl::core::bitvec::BitVec;
use rust_hdl::prelude::*;

/// The two's-complement value of an `N`-bit vector (`N <= 127`).
#[inline]
pub fn to_i128<const N: usize>(x: Bits<N>) -> i128 {
    let u = x.to_u128() as i128;
    if N < 128 && (u >> (N - 1)) & 1 == 1 {
        u - (1i128 << N)
    } else {
        u
    }
}

/// The low `N` bits of `v` (two's complement, so any value wraps modulo `2^N`).
#[inline]
pub fn from_i128<const N: usize>(v: i128) -> Bits<N> {
    let u = v as u128;
    if N <= 32 {
        Bits::from((u & ((1u128 << N) - 1)) as u64)
    } else {
        let mut b = [false; N];
        for (i, bit) in b.iter_mut().enumerate() {
            *bit = i < 128 && (u >> i) & 1 == 1;
        }
        Bits::Long(BitVec::from(b))
    }
}

/// `v` wrapped to an `n`-bit two's-complement value.
#[inline]
pub fn wrap_i128(v: i128, n: usize) -> i128 {
    if n >= 128 {
        v
    } else {
        let shift = 128 - n as u32;
        (v << shift) >> shift
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Round trips through Bits are the identity on in-range values,
    /// including the most negative one (the rust-hdl `Signed` pitfall).
    #[test]
    fn round_trip_including_extremes() {
        for v in [0i128, 1, -1, 12345, -(1 << 24), (1 << 24) - 1] {
            assert_eq!(to_i128(from_i128::<25>(v)), v);
        }
        for v in [
            0i128,
            -1,
            -(1i128 << 73),
            (1i128 << 73) - 1,
            987654321987654321,
        ] {
            assert_eq!(to_i128(from_i128::<74>(v)), v);
        }
        assert_eq!(to_i128(from_i128::<98>(-(1i128 << 97))), -(1i128 << 97));
        assert_eq!(to_i128(from_i128::<8>(255)), -1);
        assert_eq!(wrap_i128(255, 8), -1);
        assert_eq!(wrap_i128(-129, 8), 127);
    }
}
