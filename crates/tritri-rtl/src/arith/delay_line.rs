//! An `N`-stage delay line with clock enable: `q` is `d` delayed by `N`
//! enabled clock edges. It carries vertex coordinates, normals, flags and
//! ids alongside the arithmetic so that every unit sees the operands of the
//! same pair (thesis, chapter 3: the base-polygon values "are passed on to
//! the registers of the next pipeline stage").
//!
//! Datapath only: no reset (docs/ARCHITECTURE.md, conventions). Valid bits use
//! [`super::valid_line::ValidLine`], which has one.
//! Verilog: one register per stage, `stage_<i>_q`, the last being `q`;
//! FPGA tools map long ones onto shift-register LUTs. ECP5 has none, so
//! `tritri gen --delay-lines memory` swaps long lines' bodies for
//! [`delay_line_memory_verilog`] (`crate::emit::memory_mapping`).

use rust_hdl::prelude::*;

#[derive(LogicBlock)]
pub struct DelayLine<T: Synth, const N: usize> {
    pub clock: Signal<In, Clock>,
    pub advance: Signal<In, Bit>,
    pub d: Signal<In, T>,
    pub q: Signal<Out, T>,
    _stages: [T; N],
}

impl<T: Synth, const N: usize> crate::unit::Unit for DelayLine<T, N> {
    const LATENCY: Option<usize> = Some(N);
}

impl<T: Synth, const N: usize> Default for DelayLine<T, N> {
    fn default() -> Self {
        assert!(N >= 1, "a delay line has at least one stage");
        Self {
            clock: Default::default(),
            advance: Default::default(),
            d: Default::default(),
            q: Default::default(),
            _stages: [T::default(); N],
        }
    }
}

impl<T: Synth, const N: usize> Logic for DelayLine<T, N> {
    fn update(&mut self) {
        if self.clock.pos_edge() && self.advance.val() {
            self._stages.copy_within(0..N - 1, 1);
            self._stages[0] = self.d.val();
            self.q.next = self._stages[N - 1];
        }
    }

    fn connect(&mut self) {
        self.q.connect();
    }

    fn hdl(&self) -> Verilog {
        Verilog::Custom(delay_line_verilog(T::BITS, N, None))
    }
}

/// Verilog of an `n`-stage, `bits`-wide enabled shift register ending in `q`;
/// with `reset = Some(signal)`, a synchronous active-high reset clears it.
pub(crate) fn delay_line_verilog(bits: usize, n: usize, reset: Option<&str>) -> String {
    let range = declared_range(bits);
    let name = |i: usize| {
        if i + 1 == n {
            "q".to_string()
        } else {
            format!("stage_{i}_q")
        }
    };
    let mut v = format!("// Delay line: {n} stage(s) of {bits} bit(s).\n");
    for i in 0..n - 1 {
        v += &format!("reg {range}{};\n", name(i));
    }
    v += "initial begin\n";
    for i in 0..n {
        v += &format!("    {} = {bits}'d0;\n", name(i));
    }
    v += "end\nalways @(posedge clock) begin\n";
    let shifts = |indent: &str| {
        let mut s = String::new();
        for i in 0..n {
            let src = if i == 0 { "d".to_string() } else { name(i - 1) };
            s += &format!("{indent}{} <= {src};\n", name(i));
        }
        s
    };
    match reset {
        Some(r) => {
            v += &format!("    if ({r}) begin\n");
            for i in 0..n {
                v += &format!("        {} <= {bits}'d0;\n", name(i));
            }
            v += "    end else if (advance) begin\n";
            v += &shifts("        ");
            v += "    end\n";
        }
        None => {
            v += "    if (advance) begin\n";
            v += &shifts("        ");
            v += "    end\n";
        }
    }
    v += "end\n";
    v
}

/// A register's range in a declaration, `[bits-1:0] ` (nothing for one bit).
fn declared_range(bits: usize) -> String {
    if bits == 1 {
        String::new()
    } else {
        format!("[{}:0] ", bits - 1)
    }
}

/// The fewest stages [`delay_line_memory_verilog`] is used for
/// (`emit::memory_mapping`): below it, the two pointers and two output
/// registers cost about what the stages do.
pub const MEMORY_MIN_STAGES: usize = 6;

/// Verilog of the same `n`-stage, `bits`-wide enabled delay line as
/// [`delay_line_verilog`] without reset, in a memory and two registers:
/// each enabled edge writes `d` at `write_at`, reads the word written
/// `n - 2` edges before (at `read_at`, `n - 2` slots behind) into `read_q`,
/// and moves `read_q` on to `q`. The word read at edge `k` holds `d` of
/// edge `k - n + 2`; through `read_q` and `q` it is `d` of edge `k - n + 1`
/// after edge `k`, as the stages give it. Every word and register starts at
/// zero, as the stages do, and a word is read before its first write only
/// while it is zero, so the two agree from the first clock.
///
/// The memory has a power of two words, at least `n - 1`, so that both
/// pointers are plain counters enabled by `advance`. (With `n - 1` words
/// each pointer wrapped through a synchronous reset, which ECP5 drives as
/// `advance` and the wrap through a LUT into the registers' LSR: W = 16
/// with the rare cases shared, that was the critical path, a copy of
/// `hold` → 8.4 ns of routing → a pointer's LSR, 98.2 MHz.)
///
/// The word at `write_at` is written in every clock, not only on enabled
/// edges: `read_at` comes to a word `n - 2` enabled edges after it is
/// written and left the word at `write_at` `words - (n - 2) >= 1` enabled
/// edges ago, so what a held clock writes there is overwritten by the next
/// enabled edge before any read, and never seen. The memory's write
/// enable is then free of `advance`. ECP5 drove it as `advance` and the
/// bank through a LUT into every RAM's `WRE`: on the W = 16 pipeline with
/// the rare cases shared, the stream id's memory held 64 of the 323
/// register inputs short of 150 MHz.
///
/// Synthesis maps the words onto distributed RAM (ECP5: `TRELLIS_DPR16X4`,
/// 16 words of 4 bits in a slice pair) with an asynchronous read, so
/// `read_q` and `q` are fabric registers and the memory's read has a whole
/// clock. The `ram_style` attribute says so: Yosys's own choice put lines
/// of 64 words of 32 bits into block RAM, whose read came 6.1 ns after the
/// clock (the ids' lines at 35 stages, in a W = 16 system at a latency of
/// 45 tried on 2026-11-30: 53 of the 65 register inputs short of
/// 150 MHz, ECP5, seed 3).
pub(crate) fn delay_line_memory_verilog(bits: usize, n: usize) -> String {
    assert!(
        n >= 3,
        "a memory delay line reads and writes two distinct words"
    );
    let words = (n - 1).next_power_of_two();
    let pointer_bits = words.trailing_zeros() as usize;
    let range = declared_range(bits);
    let behind = words - (n - 2);
    format!(
        "\
// Delay line: {n} stage(s) of {bits} bit(s), in a memory of {words} words:
// d is written at write_at, the word written {lag} edges before is read
// (at read_at) into read_q, and read_q moves on to q.
(* ram_style = \"distributed\" *)
reg {range}words [0:{last}];
reg [{pb}:0] write_at;
reg [{pb}:0] read_at;
reg {range}read_q;
integer i;
initial begin
    for (i = 0; i < {words}; i = i + 1) words[i] = {bits}'d0;
    write_at = {pointer_bits}'d0;
    read_at = {pointer_bits}'d{behind};
    read_q = {bits}'d0;
    q = {bits}'d0;
end
always @(posedge clock) begin
    // Written in every clock: the write enable is free of advance.
    words[write_at] <= d;
    if (advance) begin
        read_q <= words[read_at];
        q <= read_q;
        write_at <= write_at + {pointer_bits}'d1;
        read_at <= read_at + {pointer_bits}'d1;
    end
end
",
        lag = n - 2,
        last = words - 1,
        pb = pointer_bits - 1,
    )
}

#[cfg(test)]
mod tests {
    use crate::arith::convert::{from_i128, to_i128};
    use crate::arith::delay_line::DelayLine;
    use crate::arith::unit_vectors::{tuples, VECTORS};
    use crate::arith::valid_line::ValidLine;
    use crate::sim_drive::{assert_stream_matches, clock_cycle};
    use rust_hdl::prelude::*;

    /// A delay line of N stages delays by N enabled edges, and holds while
    /// `advance` is low; a valid line does the same for one bit and clears on
    /// reset.
    #[test]
    fn delay_lines_delay_by_their_length_and_hold() {
        let mut uut = DelayLine::<Bits<24>, 5>::default();
        uut.connect_all();
        uut.advance.next = true;
        let words = tuples::<1>(13, 24);
        assert_stream_matches(
            &mut uut,
            |u| &mut u.clock,
            &words,
            5,
            |u, [w]| u.d.next = from_i128(*w),
            |u| to_i128(u.q.val()),
            |[w]| *w,
        );
        // Held: with `advance` low, the output and the line do not move.
        let before = uut.q.val();
        uut.advance.next = false;
        for k in 0..7 {
            uut.d.next = from_i128::<24>(k);
            clock_cycle(&mut uut, |u| &mut u.clock);
            assert_eq!(uut.q.val(), before);
        }

        let mut uut = ValidLine::<5>::default();
        uut.connect_all();
        uut.advance.next = true;
        let bits: Vec<bool> = (0..VECTORS).map(|k| (k * 7 + k / 3) % 5 < 2).collect();
        assert_stream_matches(
            &mut uut,
            |u| &mut u.clock,
            &bits,
            5,
            |u, b| u.d.next = *b,
            |u| u.q.val(),
            |b| *b,
        );
        for _ in 0..5 {
            uut.d.next = true;
            clock_cycle(&mut uut, |u| &mut u.clock);
        }
        uut.reset.next = true;
        clock_cycle(&mut uut, |u| &mut u.clock);
        uut.reset.next = false;
        uut.d.next = false;
        for _ in 0..6 {
            assert!(!uut.q.val(), "a valid bit survived the reset");
            clock_cycle(&mut uut, |u| &mut u.clock);
        }
    }
}
