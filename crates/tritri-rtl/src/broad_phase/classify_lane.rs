//! One lane of the binning unit ([`super::binning_unit`]): a triangle's
//! vertices and a cell in, the children of the cell the triangle meets out,
//! one triangle per clock. The setup ([`crate::octree::triangle_setup`]) takes the
//! cell's low corner as its root, so the classifier
//! ([`crate::octree::corner_classifier`]) starts every triangle at the cell
//! itself with zero values there; an index rides alongside.
//!
//! A lane built [`ClassifyLane::with_phases`]`(R)` takes a triangle at most
//! every `R` clocks and shares its setup's products over them
//! ([`crate::octree::triangle_setup`], "Phases"): the lane of a list pass
//! behind a port that brings an entry every `R` beats. Its latency is
//! [`lane_latency`]`(R)`.

use super::list_packer::INDEX_BITS;
use crate::arith::delay_line::DelayLine;
use crate::octree::cell_classifier::AXES;
use crate::octree::corner_classifier::{CornerClassifier, CORNER_CLASSIFIER_LATENCY};
use crate::octree::triangle_setup::{setup_latency, TriangleSetup};
use rust_hdl::prelude::*;
use rust_hdl::widgets::prelude::DFF;

/// Clocks from a triangle in to its mask out in a lane whose setup shares
/// its products over `phases` clocks: setup and classifier.
pub const fn lane_latency(phases: usize) -> usize {
    setup_latency(phases) + CORNER_CLASSIFIER_LATENCY
}

/// Clocks from a triangle in to its mask out: a lane taking a triangle
/// every clock.
pub const LANE_LATENCY: usize = lane_latency(1);

#[derive(LogicBlock)]
pub struct ClassifyLane<const G: usize, const V: usize, const N: usize, const T: usize> {
    pub clock: Signal<In, Clock>,
    pub reset: Signal<In, Bit>,
    pub in_valid: Signal<In, Bit>,
    /// The triangle's index, carried to `out_index`.
    pub in_index: Signal<In, Bits<INDEX_BITS>>,
    /// `x0 y0 z0 x1 … z2` from bit 0 up, G bits each.
    pub in_vertices: Signal<In, Bits<T>>,
    /// The cell: its low corner and level (held for the triangle's
    /// [`LANE_LATENCY`] clocks: the corner for setup's first stages, the
    /// level until the classifier's).
    pub in_corner_x: Signal<In, Bits<G>>,
    pub in_corner_y: Signal<In, Bits<G>>,
    pub in_corner_z: Signal<In, Bits<G>>,
    pub in_level: Signal<In, Bits<6>>,
    pub out_valid: Signal<Out, Bit>,
    pub out_index: Signal<Out, Bits<INDEX_BITS>>,
    /// Bit `o`: the triangle meets child `o` of the cell.
    pub out_mask: Signal<Out, Bits<8>>,
    setup: TriangleSetup<G, V, N>,
    classifier: CornerClassifier<V>,
    /// The index, taken with `in_valid` and held until the next triangle:
    /// at the end of the line it shows the triangle's index from
    /// `LANE_LATENCY` clocks after the triangle to `R - 1` clocks later,
    /// so a lane of any phases `R` reads it there.
    index_q: DFF<Bits<INDEX_BITS>>,
    index_line: DelayLine<Bits<INDEX_BITS>, { LANE_LATENCY - 1 }>,
    // Where each vertex coordinate sits in `in_vertices`, each test
    // function in the setup's packed outputs.
    vertex_offset: [Constant<Bits<16>>; 9],
    field_offset: [Constant<Bits<16>>; AXES],
    /// The parts' outputs a lane does not use, folded into one bit whose
    /// name tells Verilator's lint they are unused on purpose.
    unused_outputs: Signal<Local, Bit>,
}

impl<const G: usize, const V: usize, const N: usize, const T: usize> crate::unit::Unit
    for ClassifyLane<G, V, N, T>
{
    const LATENCY: Option<usize> = Some(LANE_LATENCY);
    fn latency(&self) -> Option<usize> {
        Some(lane_latency(self.setup.phases()))
    }
    fn sub_units(&self, units: &mut crate::unit::UnitWalk) {
        crate::sub_units!(self, units, setup, classifier, index_q, index_line);
    }
}

impl<const G: usize, const V: usize, const N: usize, const T: usize> ClassifyLane<G, V, N, T> {
    /// A lane taking a triangle at most every `phases` clocks (module docs).
    pub fn with_phases(phases: usize) -> Self {
        Self {
            setup: TriangleSetup::with_phases(phases),
            ..Self::default()
        }
    }
}

impl<const G: usize, const V: usize, const N: usize, const T: usize> Default
    for ClassifyLane<G, V, N, T>
{
    fn default() -> Self {
        assert!(
            V == crate::octree::value_bits(G) && N == AXES * V && T == 9 * G,
            "classify lane for G = {G}"
        );
        ClassifyLane {
            clock: Default::default(),
            reset: Default::default(),
            in_valid: Default::default(),
            in_index: Default::default(),
            in_vertices: Default::default(),
            in_corner_x: Default::default(),
            in_corner_y: Default::default(),
            in_corner_z: Default::default(),
            in_level: Default::default(),
            out_valid: Default::default(),
            out_index: Default::default(),
            out_mask: Default::default(),
            setup: Default::default(),
            classifier: Default::default(),
            index_q: Default::default(),
            index_line: Default::default(),
            vertex_offset: std::array::from_fn(|k| Constant::new(Bits::<16>::from((k * G) as u64))),
            field_offset: std::array::from_fn(|i| Constant::new(Bits::<16>::from((i * V) as u64))),
            unused_outputs: Default::default(),
        }
    }
}

impl<const G: usize, const V: usize, const N: usize, const T: usize> Logic
    for ClassifyLane<G, V, N, T>
{
    #[hdl_gen]
    fn update(&mut self) {
        clock!(self, clock, setup, classifier, index_line);
        dff_setup!(self, clock, index_q);
        self.setup.reset.next = self.reset.val();
        self.setup.advance.next = true;
        self.setup.in_valid.next = self.in_valid.val();
        self.setup.in_tag.next = 0.into();
        self.setup.in_x0.next = self
            .in_vertices
            .val()
            .get_bits::<G>(self.vertex_offset[0].val().index());
        self.setup.in_y0.next = self
            .in_vertices
            .val()
            .get_bits::<G>(self.vertex_offset[1].val().index());
        self.setup.in_z0.next = self
            .in_vertices
            .val()
            .get_bits::<G>(self.vertex_offset[2].val().index());
        self.setup.in_x1.next = self
            .in_vertices
            .val()
            .get_bits::<G>(self.vertex_offset[3].val().index());
        self.setup.in_y1.next = self
            .in_vertices
            .val()
            .get_bits::<G>(self.vertex_offset[4].val().index());
        self.setup.in_z1.next = self
            .in_vertices
            .val()
            .get_bits::<G>(self.vertex_offset[5].val().index());
        self.setup.in_x2.next = self
            .in_vertices
            .val()
            .get_bits::<G>(self.vertex_offset[6].val().index());
        self.setup.in_y2.next = self
            .in_vertices
            .val()
            .get_bits::<G>(self.vertex_offset[7].val().index());
        self.setup.in_z2.next = self
            .in_vertices
            .val()
            .get_bits::<G>(self.vertex_offset[8].val().index());
        self.setup.in_root_x.next = self.in_corner_x.val();
        self.setup.in_root_y.next = self.in_corner_y.val();
        self.setup.in_root_z.next = self.in_corner_z.val();
        // The broad phase grows every triangle by a step (certificates).
        self.setup.grow.next = true;
        self.classifier.reset.next = self.reset.val();
        self.classifier.advance.next = true;
        self.classifier.in_valid.next = self.setup.out_valid.val();
        self.classifier.in_tag.next = 0.into();
        self.classifier.in_level.next = self.in_level.val();
        // The setup's functions, relative to the cell's corner.
        for i in 0..13 {
            self.classifier.in_gradient_x[i].next = self
                .setup
                .out_gradient_x
                .val()
                .get_bits::<V>(self.field_offset[i].val().index());
            self.classifier.in_gradient_y[i].next = self
                .setup
                .out_gradient_y
                .val()
                .get_bits::<V>(self.field_offset[i].val().index());
            self.classifier.in_gradient_z[i].next = self
                .setup
                .out_gradient_z
                .val()
                .get_bits::<V>(self.field_offset[i].val().index());
            self.classifier.in_low[i].next = self
                .setup
                .out_low
                .val()
                .get_bits::<V>(self.field_offset[i].val().index());
            self.classifier.in_high[i].next = self
                .setup
                .out_high
                .val()
                .get_bits::<V>(self.field_offset[i].val().index());
        }
        if self.in_valid.val() {
            self.index_q.d.next = self.in_index.val();
        }
        self.index_line.advance.next = true;
        self.index_line.d.next = self.index_q.q.val();
        self.out_valid.next = self.classifier.out_valid.val();
        self.out_index.next = self.index_line.q.val();
        self.out_mask.next = self.classifier.out_mask.val();
        self.unused_outputs.next =
            self.setup.out_tag.val().any() ^ self.classifier.out_tag.val().any();
    }
}

// The loop over the test functions is written with a literal.
const _: () = assert!(AXES == 13);
