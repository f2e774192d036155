//! A bicubic patch tessellated in hardware by forward differences: adds
//! and shifts only, one vertex per clock, bit for bit the exact fixed-point
//! model `tritri_geom::bezier::fixed::fixed_grid`.
//!
//! With `n = 2^K` steps a side, `n^3 C(i/n)` of a cubic `C` with integer
//! control values `p` is an integer cubic in `i` whose forward
//! differences at 0 are, with `a1 = 3 (p1 - p0)`, `a2 = 3 (p0 - 2 p1 +
//! p2)`, `a3 = p3 - 3 p2 + 3 p1 - p0`:
//!
//! `F = p0 << 3K`, `D1 = (a1 << 2K) + (a2 << K) + a3`,
//! `D2 = (a2 << (K + 1)) + 6 a3`, `D3 = 6 a3`
//!
//! (multiplications by 3 and 6 are shifts and adds). The four column
//! curves (fixed column of the net, along the first parameter) are set up
//! once per patch; each row's values `F_c(i)` are the control values of
//! the row curve, scaled by `n^3`, whose own differences give `n^6 S(i/n,
//! j/n)`; marching along the row is three adds per coordinate per vertex,
//! and each vertex is that value rounded half up (bits `6K` up, plus bit
//! `6K - 1`). The next row's setup is taken from the advanced column values with
//! the last vertex of a row, so vertices leave back to back.
//!
//! Coordinates are offset binary inside (`x + 2^(W - 1)`, the sign bit
//! flipped): every coefficient but `p0`'s sums to zero, so the offset
//! passes through to the vertex unchanged, and all arithmetic is modulo
//! `2^V` with `V = 6K + W` bits, enough for the vertex's bits since the
//! surface lies in the net's hull. No sign extension anywhere.
//!
//! Timing: `start` (while idle) takes the net; the clock after, the first
//! row's setup; then one vertex per clock while `out_ready` is high, rows
//! `i` outer and columns `j` inner, `out_last` on the last. `busy` falls
//! with the clock that takes it: [`tessellation_clocks`] clocks from
//! `start` with the reader always ready.

use crate::arith::convert::{from_i128, to_i128, wrap_i128};
use rust_hdl::prelude::*;

/// Clock edges from the `start` edge through the edge that takes the last
/// vertex, the reader always ready: the start edge (the column setup), the
/// first row's setup, then a vertex per clock (`(2^k + 1)^2`).
pub fn tessellation_clocks(k: u32) -> u64 {
    let side = (1u64 << k) + 1;
    2 + side * side
}

/// Bits of the values: `6K + W`.
pub const fn value_bits(w: usize, k: usize) -> usize {
    6 * k + w
}

/// (W, K) the unit is built for: coordinate bits and `log2` of the steps
/// a side. [`with_patch_tessellator!`] dispatches on the same list.
pub const TESSELLATOR_CONFIGURATIONS: [(usize, usize); 8] = [
    (16, 1),
    (16, 2),
    (16, 3),
    (16, 4),
    (24, 1),
    (24, 2),
    (24, 3),
    (24, 4),
];

/// `$run::<W, K, V, N>($args...)` for the unit built for `($w, $k)`, as
/// `Some`, or `None` for a configuration it is not built for: the one
/// place that turns [`TESSELLATOR_CONFIGURATIONS`] into const parameters.
#[macro_export]
macro_rules! with_patch_tessellator {
    ($w:expr, $k:expr, $run:ident($($arg:expr),*)) => {{
        use $crate::bezier::patch_tessellator::{net_bits, value_bits};
        match ($w, $k) {
            (16, 1) => Some($run::<16, 1, { value_bits(16, 1) }, { net_bits(16) }>($($arg),*)),
            (16, 2) => Some($run::<16, 2, { value_bits(16, 2) }, { net_bits(16) }>($($arg),*)),
            (16, 3) => Some($run::<16, 3, { value_bits(16, 3) }, { net_bits(16) }>($($arg),*)),
            (16, 4) => Some($run::<16, 4, { value_bits(16, 4) }, { net_bits(16) }>($($arg),*)),
            (24, 1) => Some($run::<24, 1, { value_bits(24, 1) }, { net_bits(24) }>($($arg),*)),
            (24, 2) => Some($run::<24, 2, { value_bits(24, 2) }, { net_bits(24) }>($($arg),*)),
            (24, 3) => Some($run::<24, 3, { value_bits(24, 3) }, { net_bits(24) }>($($arg),*)),
            (24, 4) => Some($run::<24, 4, { value_bits(24, 4) }, { net_bits(24) }>($($arg),*)),
            _ => None,
        }
    }};
}

/// Coordinates of a net: 16 control points, 3 each.
pub const NET_COORDINATES: usize = 48;

/// The bits of the `net` port: `48 W`.
pub const fn net_bits(w: usize) -> usize {
    NET_COORDINATES * w
}

#[derive(LogicBlock)]
pub struct PatchTessellator<const W: usize, const K: usize, const V: usize, const N: usize> {
    pub clock: Signal<In, Clock>,
    /// Synchronous, active high: idle.
    pub reset: Signal<In, Bit>,
    /// One clock high while idle: tessellate the patch on `net`.
    pub start: Signal<In, Bit>,
    /// The control points, W-bit two's complement, read with `start`:
    /// coordinate `axis` of the point in row `r` (along the first
    /// parameter) and column `c` at bits `[(3 (4 r + c) + axis) W +: W]`.
    pub net: Signal<In, Bits<N>>,
    pub busy: Signal<Out, Bit>,
    pub out_valid: Signal<Out, Bit>,
    pub out_ready: Signal<In, Bit>,
    pub out_x: Signal<Out, Bits<W>>,
    pub out_y: Signal<Out, Bits<W>>,
    pub out_z: Signal<Out, Bits<W>>,
    /// The vertex's row `i` and column `j` (0 to 2^K).
    pub out_i: Signal<Out, Bits<8>>,
    pub out_j: Signal<Out, Bits<8>>,
    /// The patch's last vertex.
    pub out_last: Signal<Out, Bit>,
    _state: State,
}

/// The registers, as the Verilog body has them.
#[derive(Clone, Copy, Default)]
struct State {
    busy: bool,
    /// The first row's setup is next.
    load: bool,
    valid: bool,
    i: u64,
    j: u64,
    /// Column tables `[axis][column]`.
    f: [[i128; 4]; 3],
    d1: [[i128; 4]; 3],
    d2: [[i128; 4]; 3],
    d3: [[i128; 4]; 3],
    /// The row being marched, per axis.
    g: [i128; 3],
    e1: [i128; 3],
    e2: [i128; 3],
    e3: [i128; 3],
}

impl<const W: usize, const K: usize, const V: usize, const N: usize> crate::unit::Unit
    for PatchTessellator<W, K, V, N>
{
}

impl<const W: usize, const K: usize, const V: usize, const N: usize> Default
    for PatchTessellator<W, K, V, N>
{
    fn default() -> Self {
        assert_eq!(V, value_bits(W, K), "V = 6K + W");
        assert_eq!(N, net_bits(W), "N = 48 W");
        assert!(
            (1..=7).contains(&K) && V <= 127,
            "K = {K}, V = {V}: out of range"
        );
        Self {
            clock: Default::default(),
            reset: Default::default(),
            start: Default::default(),
            net: Default::default(),
            busy: Default::default(),
            out_valid: Default::default(),
            out_ready: Default::default(),
            out_x: Default::default(),
            out_y: Default::default(),
            out_z: Default::default(),
            out_i: Default::default(),
            out_j: Default::default(),
            out_last: Default::default(),
            _state: State::default(),
        }
    }
}

/// The forward-difference table `(F, D1, D2, D3)` of the cubic with
/// control values `p`, for steps of `2^-k`, modulo `2^bits`.
fn differences(p: [i128; 4], k: u32, bits: usize) -> [i128; 4] {
    let w = |x: i128| wrap_i128(x, bits);
    let a1 = w(3 * (p[1] - p[0]));
    let a2 = w(3 * (p[0] - 2 * p[1] + p[2]));
    let a3 = w(p[3] - 3 * p[2] + 3 * p[1] - p[0]);
    [
        w(p[0] << (3 * k)),
        w((a1 << (2 * k)) + (a2 << k) + a3),
        w((a2 << (k + 1)) + 6 * a3),
        w(6 * a3),
    ]
}

impl<const W: usize, const K: usize, const V: usize, const N: usize> PatchTessellator<W, K, V, N> {
    fn n() -> u64 {
        1 << K
    }

    /// The vertex coordinate of a row value, as the Verilog forms it:
    /// rounded half up (the bits from 6K up, plus bit 6K - 1), back to
    /// two's complement.
    fn vertex(g: i128) -> Bits<W> {
        let bits = g as u128 & ((1u128 << V) - 1);
        let rounded = (bits >> (6 * K)) + (bits >> (6 * K - 1) & 1);
        from_i128::<W>((rounded as i128) ^ (1i128 << (W - 1)))
    }

    /// Loads the row setup from the column values, then advances them.
    fn next_row(s: &mut State) {
        for axis in 0..3 {
            let t = differences(s.f[axis], K as u32, V);
            (s.g[axis], s.e1[axis], s.e2[axis], s.e3[axis]) = (t[0], t[1], t[2], t[3]);
            for c in 0..4 {
                s.f[axis][c] = wrap_i128(s.f[axis][c] + s.d1[axis][c], V);
                s.d1[axis][c] = wrap_i128(s.d1[axis][c] + s.d2[axis][c], V);
                s.d2[axis][c] = wrap_i128(s.d2[axis][c] + s.d3[axis][c], V);
            }
        }
    }
}

impl<const W: usize, const K: usize, const V: usize, const N: usize> Logic
    for PatchTessellator<W, K, V, N>
{
    fn update(&mut self) {
        if !self.clock.pos_edge() {
            return;
        }
        let mut s = self._state;
        let n = Self::n();
        if self.reset.val() {
            s.busy = false;
            s.load = false;
            s.valid = false;
        } else if !s.busy {
            if self.start.val() {
                let flip = 1i128 << (W - 1);
                for axis in 0..3 {
                    for c in 0..4 {
                        // Offset binary, zero-extended.
                        let p = [0, 1, 2, 3].map(|r| {
                            (to_i128(self.net.val().get_bits::<W>((3 * (4 * r + c) + axis) * W))
                                ^ -flip)
                                & ((1i128 << W) - 1)
                        });
                        let t = differences(p, K as u32, V);
                        (s.f[axis][c], s.d1[axis][c], s.d2[axis][c], s.d3[axis][c]) =
                            (t[0], t[1], t[2], t[3]);
                    }
                }
                s.busy = true;
                s.load = true;
                s.valid = false;
            }
        } else if s.load {
            Self::next_row(&mut s);
            s.load = false;
            s.valid = true;
            s.i = 0;
            s.j = 0;
        } else if s.valid && self.out_ready.val() {
            if s.j == n {
                if s.i == n {
                    s.busy = false;
                    s.valid = false;
                } else {
                    Self::next_row(&mut s);
                    s.i += 1;
                    s.j = 0;
                }
            } else {
                for axis in 0..3 {
                    s.g[axis] = wrap_i128(s.g[axis] + s.e1[axis], V);
                    s.e1[axis] = wrap_i128(s.e1[axis] + s.e2[axis], V);
                    s.e2[axis] = wrap_i128(s.e2[axis] + s.e3[axis], V);
                }
                s.j += 1;
            }
        }
        self._state = s;
        self.busy.next = s.busy;
        self.out_valid.next = s.valid;
        self.out_x.next = Self::vertex(s.g[0]);
        self.out_y.next = Self::vertex(s.g[1]);
        self.out_z.next = Self::vertex(s.g[2]);
        self.out_i.next = Bits::from(s.i);
        self.out_j.next = Bits::from(s.j);
        self.out_last.next = s.i == n && s.j == n;
    }

    fn connect(&mut self) {
        self.busy.connect();
        self.out_valid.connect();
        self.out_x.connect();
        self.out_y.connect();
        self.out_z.connect();
        self.out_i.connect();
        self.out_j.connect();
        self.out_last.connect();
    }

    fn hdl(&self) -> Verilog {
        Verilog::Custom(verilog_body(W, K, V))
    }
}

/// The Verilog of the unit's body (the Rust `update` above, register for
/// register).
fn verilog_body(w: usize, k: usize, v: usize) -> String {
    let v1 = v - 1;
    let n = 1u64 << k;
    let mut decl = String::new();
    let mut wires = String::new();
    let mut start_block = String::new();
    let mut row_block = String::new();
    let mut march_block = String::new();
    let mut init = String::new();
    // The difference table of four V-bit values named by `p(r)`, into wires `{t}_f, {t}_d1, {t}_d2, {t}_d3`.
    let table = |t: &str, p: &dyn Fn(usize) -> String| -> String {
        format!(
            "wire [{v1}:0] {t}_x1 = {p1} - {p0};\n\
             wire [{v1}:0] {t}_a1 = ({t}_x1 << 1) + {t}_x1;\n\
             wire [{v1}:0] {t}_x2 = {p0} - ({p1} << 1) + {p2};\n\
             wire [{v1}:0] {t}_a2 = ({t}_x2 << 1) + {t}_x2;\n\
             wire [{v1}:0] {t}_a3 = {p3} - ({p2} << 1) - {p2} + ({p1} << 1) + {p1} - {p0};\n\
             wire [{v1}:0] {t}_f = {p0} << {k3};\n\
             wire [{v1}:0] {t}_d1 = ({t}_a1 << {k2}) + ({t}_a2 << {k}) + {t}_a3;\n\
             wire [{v1}:0] {t}_d3 = ({t}_a3 << 2) + ({t}_a3 << 1);\n\
             wire [{v1}:0] {t}_d2 = ({t}_a2 << {k1}) + {t}_d3;\n",
            p0 = p(0),
            p1 = p(1),
            p2 = p(2),
            p3 = p(3),
            k3 = 3 * k,
            k2 = 2 * k,
            k1 = k + 1,
        )
    };
    for (axis, name) in ["x", "y", "z"].iter().enumerate() {
        decl.push_str(&format!(
            "reg [{v1}:0] g_{name}, e1_{name}, e2_{name}, e3_{name};\n"
        ));
        init.push_str(&format!(
            "    g_{name} = {v}'d0; e1_{name} = {v}'d0; e2_{name} = {v}'d0; e3_{name} = {v}'d0;\n"
        ));
        for c in 0..4 {
            let col = format!("{name}{c}");
            decl.push_str(&format!(
                "reg [{v1}:0] f_{col}, d1_{col}, d2_{col}, d3_{col};\n"
            ));
            init.push_str(&format!(
                "    f_{col} = {v}'d0; d1_{col} = {v}'d0; d2_{col} = {v}'d0; d3_{col} = {v}'d0;\n"
            ));
            // The column's control values, offset binary, zero-extended.
            wires.push_str(&table(&format!("col_{col}"), &|r| {
                format!(
                    "{{{pad}'d0, net[{lo} +: {w}] ^ {w}'d{flip}}}",
                    pad = v - w,
                    lo = (3 * (4 * r + c) + axis) * w,
                    flip = 1u64 << (w - 1)
                )
            }));
            start_block.push_str(&format!(
                "            f_{col} <= col_{col}_f; d1_{col} <= col_{col}_d1; d2_{col} <= col_{col}_d2; d3_{col} <= col_{col}_d3;\n"
            ));
            row_block.push_str(&format!("        f_{col} <= f_{col} + d1_{col}; d1_{col} <= d1_{col} + d2_{col}; d2_{col} <= d2_{col} + d3_{col};\n"));
        }
        wires.push_str(&table(&format!("row_{name}"), &|c| format!("f_{name}{c}")));
        row_block.push_str(&format!("        g_{name} <= row_{name}_f; e1_{name} <= row_{name}_d1; e2_{name} <= row_{name}_d2; e3_{name} <= row_{name}_d3;\n"));
        march_block.push_str(&format!("                g_{name} <= g_{name} + e1_{name}; e1_{name} <= e1_{name} + e2_{name}; e2_{name} <= e2_{name} + e3_{name};\n"));
        // Rounded half up: the bits from 6K up, plus bit 6K - 1.
        wires.push_str(&format!(
            "assign out_{name} = (g_{name}[{v1}:{low}] + {{{{{w1}{{1'b0}}}}, g_{name}[{half_bit}]}}) ^ {w}'d{flip};\n",
            low = 6 * k,
            w1 = w - 1,
            half_bit = 6 * k - 1,
            flip = 1u64 << (w - 1)
        ));
    }
    let row_block_inner: String = row_block
        .lines()
        .map(|l| format!("        {l}\n"))
        .collect();
    format!(
        "\
// Registers: the column tables f, d1, d2, d3 per axis and column; the row
// being marched g, e1, e2, e3 per axis; control (module header).
{decl}reg load_q, valid_q, busy_q;
reg [7:0] i_q, j_q;
// The difference tables: of the net's columns (at start) and of the row
// curve whose control values are the columns' current values.
{wires}initial begin
{init}    load_q = 1'b0; valid_q = 1'b0; busy_q = 1'b0; i_q = 8'd0; j_q = 8'd0;
end
assign busy = busy_q;
assign out_valid = valid_q;
assign out_i = i_q;
assign out_j = j_q;
assign out_last = (i_q == 8'd{n}) && (j_q == 8'd{n});
always @(posedge clock) begin
    if (reset) begin
        busy_q <= 1'b0; load_q <= 1'b0; valid_q <= 1'b0;
    end else if (!busy_q) begin
        if (start) begin
{start_block}            busy_q <= 1'b1; load_q <= 1'b1; valid_q <= 1'b0;
        end
    end else if (load_q) begin
        // The first row's setup; the columns advance to the next row.
{row_block}        load_q <= 1'b0; valid_q <= 1'b1; i_q <= 8'd0; j_q <= 8'd0;
    end else if (valid_q && out_ready) begin
        if (j_q == 8'd{n}) begin
            if (i_q == 8'd{n}) begin
                busy_q <= 1'b0; valid_q <= 1'b0;
            end else begin
                // The next row's setup, with the last vertex of this one
                // (the first row's statements, written out again).
{row_block_inner}                i_q <= i_q + 8'd1; j_q <= 8'd0;
            end
        end else begin
{march_block}            j_q <= j_q + 8'd1;
        end
    end
end
"
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    fn parameters<const W: usize, const K: usize, const V: usize, const N: usize>() -> (usize, usize)
    {
        (W, K)
    }

    /// The dispatch builds exactly the listed configurations, each with its
    /// own parameters.
    #[test]
    fn dispatch_is_the_configuration_list() {
        for w in 8..=32 {
            for k in 0..=8 {
                let built = crate::with_patch_tessellator!(w, k, parameters());
                assert_eq!(
                    built.is_some(),
                    TESSELLATOR_CONFIGURATIONS.contains(&(w, k)),
                    "W = {w}, K = {k}"
                );
                assert!(built.is_none_or(|p| p == (w, k)));
            }
        }
    }
}
