//! Normal vector of a triangle, `N = (q - p) × (r - p)`, exact in 2W+1 bits.
//!
//! Thesis, steps (1) and (3) and figure 3.2 (the normal-vector unit: two
//! vector subtractions, then the cross-product unit). One unit serves both
//! triangles: every triangle's normal is computed once as it enters, and the
//! base polygon keeps its own (thesis, "setting the base polygon").
//! Software model: `tritri_geom::fixed_point::cross`.

use crate::arith::certificate::{EdgesBitLength, EDGES_BIT_LENGTH_LATENCY};
use crate::arith::cross_product::{TwoWayCrossProduct, CROSS_PRODUCT_LATENCY};
use crate::arith::subtractor::{TwoWaySubtractor, SUBTRACTOR_LATENCY};
use rust_hdl::prelude::*;

/// Clock edges from vertices to normal.
pub const NORMAL_LATENCY: usize = SUBTRACTOR_LATENCY + CROSS_PRODUCT_LATENCY;

/// Clock edges from vertices to the edges' `ke`.
pub const EDGES_BITS_LATENCY: usize = SUBTRACTOR_LATENCY + EDGES_BIT_LENGTH_LATENCY;

#[derive(LogicBlock, Default)]
pub struct NormalUnit<const W: usize, const D: usize, const C: usize> {
    pub clock: Signal<In, Clock>,
    pub advance: Signal<In, Bit>,
    /// `x0 y0 z0 x1 y1 z1 x2 y2 z2` of `p, q, r`.
    pub vertices: [Signal<In, Bits<W>>; 9],
    /// `(q - p) × (r - p)`, `NORMAL_LATENCY` enabled edges later.
    pub normal: [Signal<Out, Bits<C>>; 3],
    /// `-normal`, with it: the dominant axis takes magnitudes from the two.
    pub negated_normal: [Signal<Out, Bits<C>>; 3],
    /// `ke = bitlen(|q - p|_1 + |r - p|_1)`, the certificates' (see
    /// `arith::certificate`), `EDGES_BITS_LATENCY` enabled edges later.
    pub edges_bits: Signal<Out, Bits<8>>,
    /// The edges, each also negated for its magnitudes in `edge_bits`.
    edge_pq: TwoWaySubtractor<W, D>,
    edge_pr: TwoWaySubtractor<W, D>,
    edge_cross: TwoWayCrossProduct<D, C>,
    edge_bits: EdgesBitLength<D>,
}

impl<const W: usize, const D: usize, const C: usize> crate::unit::Unit for NormalUnit<W, D, C> {
    const LATENCY: Option<usize> = Some(NORMAL_LATENCY);
    fn sub_units(&self, units: &mut crate::unit::UnitWalk) {
        crate::sub_units!(self, units, edge_pq, edge_pr, edge_cross, edge_bits);
    }
}

impl<const W: usize, const D: usize, const C: usize> Logic for NormalUnit<W, D, C> {
    #[hdl_gen]
    fn update(&mut self) {
        clock!(self, clock, edge_pq, edge_pr, edge_cross, edge_bits);
        self.edge_pq.advance.next = self.advance.val();
        self.edge_pr.advance.next = self.advance.val();
        self.edge_cross.advance.next = self.advance.val();
        self.edge_bits.advance.next = self.advance.val();
        for k in 0..3 {
            self.edge_pq.a[k].next = self.vertices[3 + k].val();
            self.edge_pq.b[k].next = self.vertices[k].val();
            self.edge_pr.a[k].next = self.vertices[6 + k].val();
            self.edge_pr.b[k].next = self.vertices[k].val();
            self.edge_cross.u[k].next = self.edge_pq.difference[k].val();
            self.edge_cross.v[k].next = self.edge_pr.difference[k].val();
            self.normal[k].next = self.edge_cross.product[k].val();
            self.negated_normal[k].next = self.edge_cross.negated[k].val();
            self.edge_bits.a[k].next = self.edge_pq.difference[k].val();
            self.edge_bits.b[k].next = self.edge_pr.difference[k].val();
            self.edge_bits.a_negated[k].next = self.edge_pq.negated[k].val();
            self.edge_bits.b_negated[k].next = self.edge_pr.negated[k].val();
        }
        self.edges_bits.next = self.edge_bits.bits.val();
    }
}

#[cfg(test)]
mod tests {
    use crate::arith::convert::to_i128;
    use crate::pipeline::normal::{NormalUnit, EDGES_BITS_LATENCY, NORMAL_LATENCY};
    use crate::pipeline::unit_vectors::{edges_bits, normal, set_vertices, triangles};
    use crate::sim_drive::assert_stream_matches;
    use rust_hdl::prelude::*;

    #[test]
    fn normal_unit_gives_the_cross_product_its_negation_and_its_edges_bit_length() {
        let vectors = triangles(1);
        let mut uut = NormalUnit::<24, 25, 49>::default();
        uut.connect_all();
        uut.advance.next = true;
        assert_stream_matches(
            &mut uut,
            |u| &mut u.clock,
            &vectors,
            NORMAL_LATENCY,
            |u, t| set_vertices(&mut u.vertices, t),
            |u| {
                (
                    u.normal.each_ref().map(|n| to_i128(n.val())),
                    u.negated_normal.each_ref().map(|n| to_i128(n.val())),
                )
            },
            |t| {
                let n = normal(t);
                (n, n.map(|c| -c))
            },
        );
        let mut uut = NormalUnit::<24, 25, 49>::default();
        uut.connect_all();
        uut.advance.next = true;
        assert_stream_matches(
            &mut uut,
            |u| &mut u.clock,
            &vectors,
            EDGES_BITS_LATENCY,
            |u, t| set_vertices(&mut u.vertices, t),
            |u| u.edges_bits.val().to_u64(),
            edges_bits,
        );
    }
}
