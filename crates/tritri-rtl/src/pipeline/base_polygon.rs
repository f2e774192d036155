//! The base-polygon registers (thesis, chapter 3, figures 3.3 and 3.4):
//! with `BSET = 1` the triangle's record (vertices, normal and the rest of
//! the front end's output) and its id are latched here instead of being
//! tested, and held until the next `BSET`. Every streamed triangle is then
//! paired with this record, so one pair costs one clock and the input bus
//! carries one triangle (`9 W` bits) per clock.
//!
//! `load_ahead` is the load decision an enabled clock edge early (the
//! record arriving next is valid and has `BSET`). The registers of each
//! group below (each of T1's three vertices, its normal with the rest, and
//! its id) load when `advance` is high and a [`LoadEnable`] of their own
//! says so: one load register drove some 150 enables across the chip (the
//! W = 8 pipeline's critical path with nextpnr's seed 2, 6.7 of 7.5 ns
//! routing), and with a copy of the load per group, one copy of `hold`
//! still reached every group (W = 16 shared, seed 2: 7.4 ns of routing).

use crate::pipeline::load_enable::LoadEnable;
use crate::pipeline::ID_BITS;
use rust_hdl::prelude::*;
use rust_hdl::widgets::prelude::DFF;

#[derive(LogicBlock, Default)]
pub struct BasePolygon<const W: usize, const D: usize, const C: usize> {
    pub clock: Signal<In, Clock>,
    /// Synchronous, active high: no load pending.
    pub reset: Signal<In, Bit>,
    /// `advance` before `hold`, and `hold` next clock if `advance` is high
    /// this clock and if it is low (the hold forecast's registers; a top
    /// that never holds ties both low).
    pub advance: Signal<In, Bit>,
    pub hold_if_advance: Signal<In, Bit>,
    pub hold_if_still: Signal<In, Bit>,
    /// The next edge where the pipeline moves brings a record to load
    /// (module doc).
    pub load_ahead: Signal<In, Bit>,
    pub id_in: Signal<In, Bits<ID_BITS>>,
    pub vertices_in: [Signal<In, Bits<W>>; 9],
    pub normal_in: [Signal<In, Bits<C>>; 3],
    pub normal_negative_in: [Signal<In, Bit>; 3],
    pub normal_zero_in: [Signal<In, Bit>; 3],
    pub degenerate_in: Signal<In, Bit>,
    pub dominant_axis_in: Signal<In, Bits<2>>,
    pub segment_low_in: Signal<In, Bits<2>>,
    pub segment_high_in: Signal<In, Bits<2>>,
    /// The bit length of the edges' sum of magnitudes (the certificates'
    /// `ke`).
    pub edges_bits_in: Signal<In, Bits<8>>,
    pub id: Signal<Out, Bits<ID_BITS>>,
    pub vertices: [Signal<Out, Bits<W>>; 9],
    pub normal: [Signal<Out, Bits<C>>; 3],
    pub normal_negative: [Signal<Out, Bit>; 3],
    pub normal_zero: [Signal<Out, Bit>; 3],
    pub degenerate: Signal<Out, Bit>,
    pub dominant_axis: Signal<Out, Bits<2>>,
    pub segment_low: Signal<Out, Bits<2>>,
    pub segment_high: Signal<Out, Bits<2>>,
    pub edges_bits: Signal<Out, Bits<8>>,
    id_q: DFF<Bits<ID_BITS>>,
    vertices_q: [DFF<Bits<W>>; 9],
    normal_q: [DFF<Bits<C>>; 3],
    normal_negative_q: [DFF<Bit>; 3],
    normal_zero_q: [DFF<Bit>; 3],
    degenerate_q: DFF<Bit>,
    dominant_axis_q: DFF<Bits<2>>,
    segment_low_q: DFF<Bits<2>>,
    segment_high_q: DFF<Bits<2>>,
    edges_bits_q: DFF<Bits<8>>,
    /// Whether to load at the next edge where `advance` is high: for
    /// vertex `j` (`j < 3`), then for the normal, its flags and the rest,
    /// then for the id.
    loads: [LoadEnable; 5],
}

impl<const W: usize, const D: usize, const C: usize> crate::unit::Unit for BasePolygon<W, D, C> {
    fn sub_units(&self, units: &mut crate::unit::UnitWalk) {
        crate::sub_units!(
            self,
            units,
            id_q,
            vertices_q,
            normal_q,
            normal_negative_q,
            normal_zero_q,
            degenerate_q,
            dominant_axis_q,
            segment_low_q,
            segment_high_q,
            edges_bits_q,
            loads
        );
    }
}

impl<const W: usize, const D: usize, const C: usize> Logic for BasePolygon<W, D, C> {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(
            self,
            clock,
            id_q,
            degenerate_q,
            dominant_axis_q,
            segment_low_q,
            segment_high_q,
            edges_bits_q
        );
        for i in 0..9 {
            self.vertices_q[i].clock.next = self.clock.val();
            self.vertices_q[i].d.next = self.vertices_q[i].q.val();
        }
        for k in 0..3 {
            self.normal_q[k].clock.next = self.clock.val();
            self.normal_q[k].d.next = self.normal_q[k].q.val();
            self.normal_negative_q[k].clock.next = self.clock.val();
            self.normal_negative_q[k].d.next = self.normal_negative_q[k].q.val();
            self.normal_zero_q[k].clock.next = self.clock.val();
            self.normal_zero_q[k].d.next = self.normal_zero_q[k].q.val();
        }
        for g in 0..5 {
            self.loads[g].clock.next = self.clock.val();
            self.loads[g].reset.next = self.reset.val();
            self.loads[g].advance.next = self.advance.val();
            self.loads[g].load_ahead.next = self.load_ahead.val();
            self.loads[g].hold_if_advance.next = self.hold_if_advance.val();
            self.loads[g].hold_if_still.next = self.hold_if_still.val();
        }
        // rust-hdl's hdl_gen takes no computed index: one block per vertex.
        if self.advance.val() && self.loads[0].load.val() {
            for i in 0..3 {
                self.vertices_q[i].d.next = self.vertices_in[i].val();
            }
        }
        if self.advance.val() && self.loads[1].load.val() {
            for i in 3..6 {
                self.vertices_q[i].d.next = self.vertices_in[i].val();
            }
        }
        if self.advance.val() && self.loads[2].load.val() {
            for i in 6..9 {
                self.vertices_q[i].d.next = self.vertices_in[i].val();
            }
        }
        if self.advance.val() && self.loads[3].load.val() {
            self.degenerate_q.d.next = self.degenerate_in.val();
            self.dominant_axis_q.d.next = self.dominant_axis_in.val();
            self.segment_low_q.d.next = self.segment_low_in.val();
            self.segment_high_q.d.next = self.segment_high_in.val();
            self.edges_bits_q.d.next = self.edges_bits_in.val();
            for k in 0..3 {
                self.normal_q[k].d.next = self.normal_in[k].val();
                self.normal_negative_q[k].d.next = self.normal_negative_in[k].val();
                self.normal_zero_q[k].d.next = self.normal_zero_in[k].val();
            }
        }
        if self.advance.val() && self.loads[4].load.val() {
            self.id_q.d.next = self.id_in.val();
        }
        self.id.next = self.id_q.q.val();
        self.degenerate.next = self.degenerate_q.q.val();
        self.dominant_axis.next = self.dominant_axis_q.q.val();
        self.segment_low.next = self.segment_low_q.q.val();
        self.segment_high.next = self.segment_high_q.q.val();
        self.edges_bits.next = self.edges_bits_q.q.val();
        for i in 0..9 {
            self.vertices[i].next = self.vertices_q[i].q.val();
        }
        for k in 0..3 {
            self.normal[k].next = self.normal_q[k].q.val();
            self.normal_negative[k].next = self.normal_negative_q[k].q.val();
            self.normal_zero[k].next = self.normal_zero_q[k].q.val();
        }
    }
}

#[cfg(test)]
mod tests {
    use crate::arith::convert::{from_i128, to_i128};
    use crate::pipeline::base_polygon::BasePolygon;
    use crate::pipeline::unit_vectors::{edges_bits, normal, set_vertices, triangles};
    use crate::sim_drive::{assert_stream_matches, clock_cycle};
    use rand::{Rng, SeedableRng};
    use rand_chacha::ChaCha8Rng;
    use rust_hdl::prelude::*;
    use tritri_geom::fixed_point::FixedTriangle;

    /// The base polygon latches a record when `load_ahead` was high at the
    /// enabled edge before, and holds it otherwise.
    #[test]
    fn base_polygon_holds_the_last_loaded_record() {
        let mut rng = ChaCha8Rng::seed_from_u64(12);
        let records: Vec<(u32, FixedTriangle)> =
            triangles(13).into_iter().map(|t| (rng.gen(), t)).collect();
        let loads: Vec<bool> = (0..records.len())
            .map(|k| k == 0 || rng.gen_bool(0.2))
            .collect();
        // (the next record's load, offered record, the record held after the clock)
        let mut held = records[0];
        let vectors: Vec<(bool, (u32, FixedTriangle), (u32, FixedTriangle))> = records
            .iter()
            .enumerate()
            .map(|(k, r)| {
                if loads[k] {
                    held = *r;
                }
                (loads.get(k + 1).copied().unwrap_or(false), *r, held)
            })
            .collect();
        let mut uut = BasePolygon::<24, 25, 49>::default();
        uut.connect_all();
        // The first record's load, an edge ahead.
        uut.advance.next = true;
        uut.load_ahead.next = loads[0];
        clock_cycle(&mut uut, |u| &mut u.clock);
        assert_stream_matches(
            &mut uut,
            |u| &mut u.clock,
            &vectors,
            1,
            |u, (load_next, (id, t), _)| {
                u.advance.next = true;
                u.load_ahead.next = *load_next;
                u.id_in.next = (*id as u64).into();
                set_vertices(&mut u.vertices_in, t);
                for (k, c) in normal(t).iter().enumerate() {
                    u.normal_in[k].next = from_i128(*c);
                }
                u.edges_bits_in.next = edges_bits(t).into();
            },
            |u| {
                let t: FixedTriangle = std::array::from_fn(|v| {
                    std::array::from_fn(|i| to_i128(u.vertices[3 * v + i].val()) as i64)
                });
                (
                    u.id.val().to_u64() as u32,
                    t,
                    u.normal.each_ref().map(|n| to_i128(n.val())),
                    u.edges_bits.val().to_u64(),
                )
            },
            |(_, _, (id, t))| (*id, *t, normal(t), edges_bits(t)),
        );
    }
}
