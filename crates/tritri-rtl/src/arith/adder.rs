//! Registered wide additions: `a - b` and `a + b + c` modulo `2^N`.
//!
//! The last stage of the cross-product unit (a difference of two products)
//! and of the dot-product unit (a sum of three products), thesis figures
//! 3.9, 3.10, 3.12 and 3.13 (adder, subtractor); the segment-triangle
//! case's third determinant from the other two (two differences, one a
//! stage). Results wrap modulo `2^N`, exact whenever the true value fits in
//! `N` signed bits, which the widths of `tritri_geom::widths` guarantee.
//!
//! Like [`super::multiplier::Multiplier`], these are primitives with custom
//! Verilog and an exact i128 simulation model evaluated only at clock edges:
//! rust-hdl simulates values wider than 32 bits as bit arrays, and doing the
//! arithmetic there on every delta cycle dominated the simulation time.

use super::convert::{from_i128, to_i128, wrap_i128};
use rust_hdl::prelude::*;

/// Clock edges from operands to result.
pub const ADDER_LATENCY: usize = 1;

/// `difference = a - b` (mod `2^N`), registered.
#[derive(LogicBlock, Default)]
pub struct RegisteredDifference<const N: usize> {
    pub clock: Signal<In, Clock>,
    pub advance: Signal<In, Bit>,
    pub a: Signal<In, Bits<N>>,
    pub b: Signal<In, Bits<N>>,
    pub difference: Signal<Out, Bits<N>>,
}

impl<const N: usize> crate::unit::Unit for RegisteredDifference<N> {
    const LATENCY: Option<usize> = Some(ADDER_LATENCY);
}

impl<const N: usize> Logic for RegisteredDifference<N> {
    fn update(&mut self) {
        if self.clock.pos_edge() && self.advance.val() {
            let v = wrap_i128(to_i128(self.a.val()) - to_i128(self.b.val()), N);
            self.difference.next = from_i128::<N>(v);
        }
    }

    fn connect(&mut self) {
        self.difference.connect();
    }

    fn hdl(&self) -> Verilog {
        Verilog::Custom(format!(
            "\
// Registered {N}-bit difference (modulo 2^{N}).
initial difference = {N}'d0;
always @(posedge clock) begin
    if (advance) begin
        difference <= a - b;
    end
end
"
        ))
    }
}

/// The sign of `a - b` (mod `2^N`) and whether it is 0 (`a == b`) in
/// parts, registered: a subtraction whose value nobody reads.
///
/// The sign is `a`'s top bit `^ b`'s `^` the borrow out of the bits below,
/// which is their comparison: one carry chain. The test for 0 compares
/// the operands beside it, [`EQUAL_PART_BITS`] bits to a part (one LUT4
/// from the operands' registers); the reader ANDs the parts a stage
/// later. (As one `a == b` of 50 bits, four levels behind the far
/// operand's register: 6.79 ns, the worst register input of the W = 16
/// shared pipeline on ECP5 at 147.2 MHz, seed 1.)
#[derive(LogicBlock, Default)]
pub struct RegisteredDifferenceSign<const N: usize> {
    pub clock: Signal<In, Clock>,
    pub advance: Signal<In, Bit>,
    pub a: Signal<In, Bits<N>>,
    pub b: Signal<In, Bits<N>>,
    /// `a - b < 0`, `ADDER_LATENCY` enabled edges later.
    pub negative: Signal<Out, Bit>,
    /// Bit `j` below `N / EQUAL_PART_BITS` (rounded up): `a` and `b` are
    /// equal in bits `[j, j + 1) * EQUAL_PART_BITS`; the bits above are 1.
    /// All are 1 exactly when `a - b == 0`, in the same clock as
    /// `negative`.
    pub equal_parts: Signal<Out, Bits<N>>,
}

/// Bits of [`RegisteredDifferenceSign::equal_parts`]' comparison in one
/// part: two bits of each operand, the four inputs of one LUT4.
pub const EQUAL_PART_BITS: usize = 2;

/// The model of a test in parts: bit `j` of the result is 1 when the
/// per-bit test `holds` holds in all of part `j`'s `part_bits` bits, and
/// the bits above the part count are 1, as [`parts_verilog`] writes it.
fn parts_model<const N: usize>(holds: u128, part_bits: usize) -> Bits<N> {
    let mask = if N == 128 {
        u128::MAX
    } else {
        (1u128 << N) - 1
    };
    let mut parts = mask;
    for j in 0..N.div_ceil(part_bits) {
        let group = ((1u128 << part_bits) - 1) << (part_bits * j) & mask;
        if holds & group != group {
            parts &= !(1u128 << j);
        }
    }
    from_i128::<N>(parts as i128)
}

impl<const N: usize> crate::unit::Unit for RegisteredDifferenceSign<N> {
    const LATENCY: Option<usize> = Some(ADDER_LATENCY);
}

impl<const N: usize> Logic for RegisteredDifferenceSign<N> {
    fn update(&mut self) {
        if self.clock.pos_edge() && self.advance.val() {
            let (a, b) = (to_i128(self.a.val()), to_i128(self.b.val()));
            self.negative.next = wrap_i128(a - b, N) < 0;
            self.equal_parts.next = parts_model::<N>(!(a ^ b) as u128, EQUAL_PART_BITS);
        }
    }

    fn connect(&mut self) {
        self.negative.connect();
        self.equal_parts.connect();
    }

    fn hdl(&self) -> Verilog {
        Verilog::Custom(format!(
            "\
// The sign of the {N}-bit difference a - b (modulo 2^{N}), and whether it
// is 0 in parts of {EQUAL_PART_BITS} bits, registered. The top bit of a - b
// is a's top bit ^ b's ^ the borrow out of the bits below, which is their
// comparison.
initial begin
    negative = 1'b0;
    equal_parts = {{{N}{{1'b1}}}};
end
always @(posedge clock) begin
    if (advance) begin
        negative <= a[{n1}] ^ b[{n1}] ^ (a[{n2}:0] < b[{n2}:0]);
        equal_parts <= {{{parts}}};
    end
end
",
            n1 = N - 1,
            n2 = N - 2,
            parts = parts_verilog(N, EQUAL_PART_BITS, |high, low| format!(
                "a[{high}:{low}] == b[{high}:{low}]"
            )),
        ))
    }
}

/// Verilog: the concatenation of a test in parts of `part_bits` bits, top
/// bit first: 1s above the part count, then each part's `test(high, low)`.
fn parts_verilog(n: usize, part_bits: usize, test: impl Fn(usize, usize) -> String) -> String {
    let count = n.div_ceil(part_bits);
    let mut fields = Vec::new();
    if n > count {
        fields.push(format!("{}'b{}", n - count, "1".repeat(n - count)));
    }
    for j in (0..count).rev() {
        let low = part_bits * j;
        let high = (low + part_bits - 1).min(n - 1);
        fields.push(test(high, low));
    }
    fields.join(", ")
}

/// Bits of [`RegisteredSum3::zero_parts`]'s test in one part: one LUT
/// level for the four bits' tests, one for their AND.
pub const ZERO_PART_BITS: usize = 4;

/// The model of [`RegisteredSum3::zero_parts`] for the stage's registers
/// `x` and `y`.
fn zero_parts<const N: usize>(x: i128, y: i128) -> Bits<N> {
    let (x, y) = (x as u128, y as u128);
    parts_model::<N>(!((x ^ y) ^ ((x | y) << 1)), ZERO_PART_BITS)
}

/// Clock edges from operands to [`RegisteredSum3::sum`].
pub const SUM3_LATENCY: usize = 2;

/// `sum = a + b + c` (mod `2^N`), in two register stages: `a + b` and `c`,
/// then their sum, one carry chain each. (In one stage, two carry chains
/// in series behind the multipliers' long wires; the sum then fans out to
/// the sign, its certificate's comparisons and the third determinant:
/// W = 16 on ECP5, 6.7 ns of 6.67 at the plane sides' distances.)
///
/// Whether the sum is 0 is found beside it without its carry chain:
/// `x + y` is 0 modulo `2^N` exactly when `x ^ y` equals `(x | y) << 1`
/// (below the lowest bit of the sum that is not 0, every bit's carry out
/// is `x_i | y_i`, and each sum bit is `x_i ^ y_i` of it). `zero_parts`
/// registers that test in parts of [`ZERO_PART_BITS`] bits with the sum,
/// and the sign that reads the sum ANDs them as it registers its own
/// `zero`: two levels of logic on each side. (Formed from the sum's
/// register a stage later, the OR of its N bits was a long route from the
/// far value register and three levels, up to 7.63 ns; in the sum's stage
/// as one bit, six levels, 7.59 ns: ECP5, W = 16 shared, the plane sides'
/// signs.)
#[derive(LogicBlock, Default)]
pub struct RegisteredSum3<const N: usize> {
    pub clock: Signal<In, Clock>,
    pub advance: Signal<In, Bit>,
    pub a: Signal<In, Bits<N>>,
    pub b: Signal<In, Bits<N>>,
    pub c: Signal<In, Bits<N>>,
    pub sum: Signal<Out, Bits<N>>,
    /// Bit `j` below `N / ZERO_PART_BITS` (rounded up): the test above
    /// holds in bits `[j, j + 1) * ZERO_PART_BITS`; the bits above are 1.
    /// All are 1 exactly when `sum == 0`, in the same clock as `sum`.
    pub zero_parts: Signal<Out, Bits<N>>,
    // Simulation model state: the first stage's registers.
    _ab: i128,
    _c: i128,
}

impl<const N: usize> crate::unit::Unit for RegisteredSum3<N> {
    const LATENCY: Option<usize> = Some(SUM3_LATENCY);
}

impl<const N: usize> Logic for RegisteredSum3<N> {
    fn update(&mut self) {
        if self.clock.pos_edge() && self.advance.val() {
            self.sum.next = from_i128::<N>(wrap_i128(self._ab + self._c, N));
            self.zero_parts.next = zero_parts::<N>(self._ab, self._c);
            self._ab = wrap_i128(to_i128(self.a.val()) + to_i128(self.b.val()), N);
            self._c = to_i128(self.c.val());
        }
    }

    fn connect(&mut self) {
        self.sum.connect();
        self.zero_parts.connect();
    }

    fn hdl(&self) -> Verilog {
        Verilog::Custom(format!(
            "\
// {N}-bit sum of three (modulo 2^{N}) in two register stages, and whether
// it is 0 in parts of {ZERO_PART_BITS} bits: ab_q + c_q is 0 exactly when
// ab_q ^ c_q is (ab_q | c_q) << 1.
reg [{n1}:0] ab_q;
reg [{n1}:0] c_q;
wire [{n1}:0] zero_bits = ~((ab_q ^ c_q) ^ {{ab_q[{n2}:0] | c_q[{n2}:0], 1'b0}});
initial begin
    ab_q = {N}'d0;
    c_q = {N}'d0;
    sum = {N}'d0;
    zero_parts = {{{N}{{1'b1}}}};
end
always @(posedge clock) begin
    if (advance) begin
        ab_q <= a + b;
        c_q <= c;
        sum <= ab_q + c_q;
        zero_parts <= {{{parts}}};
    end
end
",
            n1 = N - 1,
            n2 = N - 2,
            parts = parts_verilog(N, ZERO_PART_BITS, |high, low| format!(
                "&zero_bits[{high}:{low}]"
            )),
        ))
    }
}

#[cfg(test)]
mod tests {
    use crate::arith::adder::{
        RegisteredDifference, RegisteredDifferenceSign, RegisteredSum3, ADDER_LATENCY, SUM3_LATENCY,
    };
    use crate::arith::convert::{from_i128, to_i128, wrap_i128};
    use crate::arith::unit_vectors::tuples;
    use crate::sim_drive::assert_stream_matches;
    use rust_hdl::prelude::*;

    #[test]
    fn adders_wrap_modulo_their_width() {
        let mut uut = RegisteredSum3::<50>::default();
        uut.connect_all();
        uut.advance.next = true;
        // Random sums, and sums of 0: `c = -(a + b)`, with and without a wrap.
        let mut sums = tuples::<3>(11, 50);
        let zeros: Vec<[i128; 3]> = sums
            .iter()
            .map(|[a, b, _]| [*a, *b, wrap_i128(-(a + b), 50)])
            .collect();
        assert!(zeros.iter().any(|[a, b, _]| wrap_i128(a + b, 50) != a + b));
        sums.extend(zeros.iter().step_by(3));
        sums.extend([
            [0, 0, 0],
            [1, -1, 0],
            [0, 1, -1],
            [-(1 << 49), -(1 << 49), 0],
        ]);
        assert_stream_matches(
            &mut uut,
            |u| &mut u.clock,
            &sums,
            SUM3_LATENCY,
            |u, [a, b, c]| {
                u.a.next = from_i128(*a);
                u.b.next = from_i128(*b);
                u.c.next = from_i128(*c);
            },
            |u| (to_i128(u.sum.val()), u.zero_parts.val().all()),
            |[a, b, c]| {
                let sum = wrap_i128(a + b + c, 50);
                (sum, sum == 0)
            },
        );
        let mut uut = RegisteredDifference::<50>::default();
        uut.connect_all();
        uut.advance.next = true;
        assert_stream_matches(
            &mut uut,
            |u| &mut u.clock,
            &tuples::<2>(12, 50),
            ADDER_LATENCY,
            |u, [a, b]| {
                u.a.next = from_i128(*a);
                u.b.next = from_i128(*b);
            },
            |u| to_i128(u.difference.val()),
            |[a, b]| wrap_i128(a - b, 50),
        );
        // The sign and the equality in parts: random pairs, equal pairs, and
        // pairs that differ in one bit, every bit (each part's test, the sign's
        // borrow from each bit).
        let mut uut = RegisteredDifferenceSign::<50>::default();
        uut.connect_all();
        uut.advance.next = true;
        let mut pairs = tuples::<2>(13, 50);
        let equal: Vec<[i128; 2]> = pairs.iter().map(|[a, _]| [*a, *a]).collect();
        pairs.extend(equal.iter().step_by(4));
        for bit in 0..50 {
            let [a, _] = pairs[bit];
            pairs.push([a, wrap_i128(a ^ (1 << bit), 50)]);
        }
        pairs.extend([
            [0, 0],
            [-(1 << 49), (1 << 49) - 1],
            [(1 << 49) - 1, -(1 << 49)],
        ]);
        assert_stream_matches(
            &mut uut,
            |u| &mut u.clock,
            &pairs,
            ADDER_LATENCY,
            |u, [a, b]| {
                u.a.next = from_i128(*a);
                u.b.next = from_i128(*b);
            },
            |u| (u.negative.val(), u.equal_parts.val().all()),
            |[a, b]| (wrap_i128(a - b, 50) < 0, a == b),
        );
    }
}
