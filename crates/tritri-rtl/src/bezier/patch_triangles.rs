//! The patch tessellation unit with its triangles assembled: the
//! tessellator's vertices in ([`super::patch_tessellator`]), two triangles
//! out for each grid cell, in the collision system's triangle format (nine
//! W-bit coordinates `x0 y0 z0 x1 … z2` from bit 0 up, as the broad
//! phase's `in_vertices`).
//!
//! Vertices come row by row, `(i, j)` with `j` inner. When `(i, j)` with
//! `i, j >= 1` arrives, the cell below and left of it is complete: its
//! corners are `(i - 1, j - 1)`, `(i, j - 1)`, `(i, j)` and `(i - 1, j)`,
//! the vertices that came `2^K + 2`, 1, 0 and `2^K + 1` vertices before.
//! A shift register of `2^K + 2` vertices holds them; the cell's two
//! triangles, `[(i-1, j-1), (i, j-1), (i, j)]` and `[(i-1, j-1), (i, j),
//! (i-1, j)]` (the order of `tritri_geom::bezier::fixed::fixed_triangles`),
//! leave together a clock after the vertex, `out_last` with the patch's
//! last cell.

use super::patch_tessellator::PatchTessellator;
use crate::arith::delay_line::DelayLine;
use rust_hdl::prelude::*;
use rust_hdl::widgets::prelude::DFF;

/// `$run::<W, K, V, N, C, T, S>($args...)` for the unit built for `($w,
/// $k)`, as `Some`, or `None`: the tessellator's configurations
/// (`TESSELLATOR_CONFIGURATIONS`) with the assembler's widths.
#[macro_export]
macro_rules! with_patch_triangles {
    ($w:expr, $k:expr, $run:ident($($arg:expr),*)) => {{
        use $crate::bezier::patch_tessellator::{net_bits, value_bits};
        match ($w, $k) {
            (16, 1) => Some($run::<16, 1, { value_bits(16, 1) }, { net_bits(16) }, 48, 144, 2>($($arg),*)),
            (16, 2) => Some($run::<16, 2, { value_bits(16, 2) }, { net_bits(16) }, 48, 144, 4>($($arg),*)),
            (16, 3) => Some($run::<16, 3, { value_bits(16, 3) }, { net_bits(16) }, 48, 144, 8>($($arg),*)),
            (16, 4) => Some($run::<16, 4, { value_bits(16, 4) }, { net_bits(16) }, 48, 144, 16>($($arg),*)),
            (24, 1) => Some($run::<24, 1, { value_bits(24, 1) }, { net_bits(24) }, 72, 216, 2>($($arg),*)),
            (24, 2) => Some($run::<24, 2, { value_bits(24, 2) }, { net_bits(24) }, 72, 216, 4>($($arg),*)),
            (24, 3) => Some($run::<24, 3, { value_bits(24, 3) }, { net_bits(24) }, 72, 216, 8>($($arg),*)),
            (24, 4) => Some($run::<24, 4, { value_bits(24, 4) }, { net_bits(24) }, 72, 216, 16>($($arg),*)),
            _ => None,
        }
    }};
}

#[derive(LogicBlock)]
pub struct PatchTriangles<
    const W: usize,
    const K: usize,
    const V: usize,
    const N: usize,
    const C: usize,
    const T: usize,
    const S: usize,
> {
    pub clock: Signal<In, Clock>,
    /// Synchronous, active high: idle.
    pub reset: Signal<In, Bit>,
    /// One clock high while idle: tessellate the patch on `net`.
    pub start: Signal<In, Bit>,
    /// The control points, as the tessellator takes them.
    pub net: Signal<In, Bits<N>>,
    pub busy: Signal<Out, Bit>,
    // Triangle pairs out (valid/ready).
    pub out_valid: Signal<Out, Bit>,
    pub out_ready: Signal<In, Bit>,
    /// The cell's first triangle, `x0 y0 z0 x1 … z2` from bit 0 up.
    pub out_first: Signal<Out, Bits<T>>,
    /// Its second triangle.
    pub out_second: Signal<Out, Bits<T>>,
    /// The patch's last cell.
    pub out_last: Signal<Out, Bit>,
    tessellator: PatchTessellator<W, K, V, N>,
    /// The vertex 1 before the current one, then `S` more, then 1 more.
    previous: DelayLine<Bits<C>, 1>,
    row: DelayLine<Bits<C>, S>,
    diagonal: DelayLine<Bits<C>, 1>,
    out_valid_q: DFF<Bit>,
    out_first_q: DFF<Bits<T>>,
    out_second_q: DFF<Bits<T>>,
    out_last_q: DFF<Bit>,
    /// Bit offsets: a coordinate's `W`, `2W`; a vertex's `C`, `2C`.
    offset_w: Constant<Bits<16>>,
    offset_2w: Constant<Bits<16>>,
    offset_c: Constant<Bits<16>>,
    offset_2c: Constant<Bits<16>>,
    // Combinational.
    advance: Signal<Local, Bit>,
    accept: Signal<Local, Bit>,
    vertex: Signal<Local, Bits<C>>,
    corner: Signal<Local, Bit>,
    first: Signal<Local, Bits<T>>,
    second: Signal<Local, Bits<T>>,
}

impl<
        const W: usize,
        const K: usize,
        const V: usize,
        const N: usize,
        const C: usize,
        const T: usize,
        const S: usize,
    > crate::unit::Unit for PatchTriangles<W, K, V, N, C, T, S>
{
    fn sub_units(&self, units: &mut crate::unit::UnitWalk) {
        crate::sub_units!(
            self,
            units,
            tessellator,
            previous,
            row,
            diagonal,
            out_valid_q,
            out_first_q,
            out_second_q,
            out_last_q
        );
    }
}

impl<
        const W: usize,
        const K: usize,
        const V: usize,
        const N: usize,
        const C: usize,
        const T: usize,
        const S: usize,
    > Default for PatchTriangles<W, K, V, N, C, T, S>
{
    fn default() -> Self {
        assert!(
            C == 3 * W && T == 9 * W && S == 1 << K,
            "patch triangles for W = {W}, K = {K}"
        );
        let constant = |x: usize| Constant::new(Bits::<16>::from(x as u64));
        PatchTriangles {
            clock: Default::default(),
            reset: Default::default(),
            start: Default::default(),
            net: Default::default(),
            busy: Default::default(),
            out_valid: Default::default(),
            out_ready: Default::default(),
            out_first: Default::default(),
            out_second: Default::default(),
            out_last: Default::default(),
            tessellator: Default::default(),
            previous: Default::default(),
            row: Default::default(),
            diagonal: Default::default(),
            out_valid_q: Default::default(),
            out_first_q: Default::default(),
            out_second_q: Default::default(),
            out_last_q: Default::default(),
            offset_w: constant(W),
            offset_2w: constant(2 * W),
            offset_c: constant(C),
            offset_2c: constant(2 * C),
            advance: Default::default(),
            accept: Default::default(),
            vertex: Default::default(),
            corner: Default::default(),
            first: Default::default(),
            second: Default::default(),
        }
    }
}

impl<
        const W: usize,
        const K: usize,
        const V: usize,
        const N: usize,
        const C: usize,
        const T: usize,
        const S: usize,
    > Logic for PatchTriangles<W, K, V, N, C, T, S>
{
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(
            self,
            clock,
            out_valid_q,
            out_first_q,
            out_second_q,
            out_last_q
        );
        clock!(self, clock, tessellator, previous, row, diagonal);
        self.tessellator.reset.next = self.reset.val();
        self.tessellator.start.next = self.start.val();
        self.tessellator.net.next = self.net.val();
        // A vertex is taken when the pair register is free or being read.
        self.advance.next = !self.out_valid_q.q.val() | self.out_ready.val();
        self.tessellator.out_ready.next = self.advance.val();
        self.accept.next = self.tessellator.out_valid.val() & self.advance.val();
        self.vertex.next = bit_cast::<C, W>(self.tessellator.out_x.val())
            | (bit_cast::<C, W>(self.tessellator.out_y.val()) << self.offset_w.val())
            | (bit_cast::<C, W>(self.tessellator.out_z.val()) << self.offset_2w.val());
        self.previous.advance.next = self.accept.val();
        self.previous.d.next = self.vertex.val();
        self.row.advance.next = self.accept.val();
        self.row.d.next = self.previous.q.val();
        self.diagonal.advance.next = self.accept.val();
        self.diagonal.d.next = self.row.q.val();
        // (i - 1, j - 1), (i, j - 1), (i, j); (i - 1, j - 1), (i, j), (i - 1, j).
        self.corner.next =
            (self.tessellator.out_i.val() != 0) & (self.tessellator.out_j.val() != 0);
        self.first.next = bit_cast::<T, C>(self.diagonal.q.val())
            | (bit_cast::<T, C>(self.previous.q.val()) << self.offset_c.val())
            | (bit_cast::<T, C>(self.vertex.val()) << self.offset_2c.val());
        self.second.next = bit_cast::<T, C>(self.diagonal.q.val())
            | (bit_cast::<T, C>(self.vertex.val()) << self.offset_c.val())
            | (bit_cast::<T, C>(self.row.q.val()) << self.offset_2c.val());
        if self.advance.val() {
            self.out_valid_q.d.next = self.accept.val() & self.corner.val();
            self.out_first_q.d.next = self.first.val();
            self.out_second_q.d.next = self.second.val();
            self.out_last_q.d.next = self.tessellator.out_last.val();
        }
        if self.reset.val() {
            self.out_valid_q.d.next = false;
        }
        self.out_valid.next = self.out_valid_q.q.val();
        self.out_first.next = self.out_first_q.q.val();
        self.out_second.next = self.out_second_q.q.val();
        self.out_last.next = self.out_last_q.q.val();
        self.busy.next = self.tessellator.busy.val() | self.out_valid_q.q.val();
    }
}
