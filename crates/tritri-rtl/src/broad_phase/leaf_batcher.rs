//! Between the binning unit and the collision system: the binning unit's
//! leaf stream (a header, the leaf's A entries, its B entries, each entry
//! with its vertices) becomes the system's batches (the leaf's triangles,
//! then one end-of-batch word).
//!
//! * A header sets the leaf's frame: with local frames, the cell's centre
//!   (`corner + side / 2`, the route's `Leaf::offset`) is taken off every
//!   coordinate, which then fits `W` bits (the split rule keeps cells at
//!   most a quarter of the window, and long triangles are not binned);
//!   without, the grid's coordinates already fit `W` bits and nothing is
//!   taken off.
//!   The header itself gives the system no word.
//! * An entry becomes a triangle word: its object, its *slot* as the id
//!   (the entry's number among its object's entries this run), its
//!   vertices in the leaf's frame; `entry_*` tells the owner filter
//!   ([`super::owner_chain_filter`]) the slot's triangle and leaf.
//! * After the leaf's last entry (the header's counts say which) the end
//!   word follows, and the leaf stream waits meanwhile.
//!
//! One register stage: a word taken at one clock is offered to the system
//! at the next, and held while the system is not ready (the leaf stream
//! holds too). A leaf of `a + b` entries thus costs the system `a + b + 1`
//! words in `a + b + 2` clocks of the leaf stream (the header's clock is
//! the gap), which is all the top's cycle model needs to know of it.

use super::binning_unit::LEAF_ADDRESS_BITS;
use super::leaf_cost::COUNT_BITS;
use super::list_packer::INDEX_BITS;
use super::owner_chain_filter::{CHAIN_LEAF_BITS, CHAIN_SLOT_BITS};
use crate::system::ID_BITS;
use rust_hdl::prelude::*;
use rust_hdl::widgets::prelude::DFF;

/// Clocks from an entry taken from the leaf stream to its word offered to
/// the system.
pub const LEAF_BATCHER_LATENCY: usize = 1;

#[derive(LogicBlock)]
pub struct LeafBatcher<const G: usize, const T: usize, const W: usize> {
    pub clock: Signal<In, Clock>,
    pub reset: Signal<In, Bit>,
    /// One clock high as a run starts: slots count from 0 again.
    pub start: Signal<In, Bit>,
    // The binning unit's leaf stream (its `out_*` ports).
    pub in_valid: Signal<In, Bit>,
    pub in_ready: Signal<Out, Bit>,
    pub in_header: Signal<In, Bit>,
    pub in_object: Signal<In, Bit>,
    pub in_index: Signal<In, Bits<INDEX_BITS>>,
    pub in_vertices: Signal<In, Bits<T>>,
    pub in_x: Signal<In, Bits<G>>,
    pub in_y: Signal<In, Bits<G>>,
    pub in_z: Signal<In, Bits<G>>,
    pub in_level: Signal<In, Bits<6>>,
    pub in_count_a: Signal<In, Bits<COUNT_BITS>>,
    pub in_count_b: Signal<In, Bits<COUNT_BITS>>,
    pub in_leaf_number: Signal<In, Bits<LEAF_ADDRESS_BITS>>,
    // The system's host stream (its `in_*` ports).
    pub out_valid: Signal<Out, Bit>,
    pub out_ready: Signal<In, Bit>,
    pub out_end: Signal<Out, Bit>,
    pub out_object: Signal<Out, Bit>,
    pub out_id: Signal<Out, Bits<ID_BITS>>,
    pub out_x0: Signal<Out, Bits<W>>,
    pub out_y0: Signal<Out, Bits<W>>,
    pub out_z0: Signal<Out, Bits<W>>,
    pub out_x1: Signal<Out, Bits<W>>,
    pub out_y1: Signal<Out, Bits<W>>,
    pub out_z1: Signal<Out, Bits<W>>,
    pub out_x2: Signal<Out, Bits<W>>,
    pub out_y2: Signal<Out, Bits<W>>,
    pub out_z2: Signal<Out, Bits<W>>,
    /// A word is held or an end word is due.
    pub busy: Signal<Out, Bit>,
    /// An entry goes to the system this clock (into the register): its
    /// object, triangle, slot and leaf, for the owner filter's tables.
    pub entry_valid: Signal<Out, Bit>,
    pub entry_object: Signal<Out, Bit>,
    pub entry_index: Signal<Out, Bits<INDEX_BITS>>,
    pub entry_slot: Signal<Out, Bits<CHAIN_SLOT_BITS>>,
    pub entry_leaf: Signal<Out, Bits<CHAIN_LEAF_BITS>>,
    /// Each object's next slot, and the current leaf's number.
    slot_q: [DFF<Bits<CHAIN_SLOT_BITS>>; 2],
    leaf_q: DFF<Bits<CHAIN_LEAF_BITS>>,
    valid_q: DFF<Bit>,
    end_q: DFF<Bit>,
    object_q: DFF<Bit>,
    id_q: DFF<Bits<ID_BITS>>,
    coordinate_q: [DFF<Bits<W>>; 9],
    offset_q: [DFF<Bits<G>>; 3],
    /// Entries of the current leaf still to come.
    remaining_q: DFF<Bits<COUNT_BITS>>,
    end_due_q: DFF<Bit>,
    /// Generator parameter: take the cell's centre off (local frames).
    local_frames: Constant<Bit>,
    /// Where each vertex coordinate sits in `in_vertices`.
    vertex_offset: [Constant<Bits<16>>; 9],
    advance: Signal<Local, Bit>,
    /// An entry moves into the register this clock.
    take_entry: Signal<Local, Bit>,
    side: Signal<Local, Bits<G>>,
    half: Signal<Local, Bits<G>>,
    difference: [Signal<Local, Bits<G>>; 9],
    /// The coordinates' bits above `W` are dropped on purpose (sign copies:
    /// a leaf's triangles fit its window); folded here for Verilator's lint.
    unused_high_bits: Signal<Local, Bit>,
    high_bits: Constant<Bits<G>>,
}

impl<const G: usize, const T: usize, const W: usize> crate::unit::Unit for LeafBatcher<G, T, W> {
    const LATENCY: Option<usize> = Some(LEAF_BATCHER_LATENCY);
    fn sub_units(&self, units: &mut crate::unit::UnitWalk) {
        crate::sub_units!(
            self,
            units,
            slot_q,
            leaf_q,
            valid_q,
            end_q,
            object_q,
            id_q,
            coordinate_q,
            offset_q,
            remaining_q,
            end_due_q
        );
    }
}

impl<const G: usize, const T: usize, const W: usize> LeafBatcher<G, T, W> {
    /// A batcher from a `G`-bit grid to `W`-bit hardware. Without
    /// `local_frames` the grid's coordinates must fit `W` bits (the host
    /// quantizes them so); the batcher keeps their low `W` bits.
    pub fn new(local_frames: bool) -> Self {
        assert!(
            T == 9 * G && W <= G && G <= 32,
            "leaf batcher for G = {G}, W = {W}"
        );
        LeafBatcher {
            clock: Default::default(),
            reset: Default::default(),
            in_valid: Default::default(),
            in_ready: Default::default(),
            in_header: Default::default(),
            in_object: Default::default(),
            in_index: Default::default(),
            in_vertices: Default::default(),
            in_x: Default::default(),
            in_y: Default::default(),
            in_z: Default::default(),
            in_level: Default::default(),
            in_count_a: Default::default(),
            in_count_b: Default::default(),
            out_valid: Default::default(),
            out_ready: Default::default(),
            out_end: Default::default(),
            out_object: Default::default(),
            out_id: Default::default(),
            out_x0: Default::default(),
            out_y0: Default::default(),
            out_z0: Default::default(),
            out_x1: Default::default(),
            out_y1: Default::default(),
            out_z1: Default::default(),
            out_x2: Default::default(),
            out_y2: Default::default(),
            out_z2: Default::default(),
            busy: Default::default(),
            start: Default::default(),
            in_leaf_number: Default::default(),
            entry_valid: Default::default(),
            entry_object: Default::default(),
            entry_index: Default::default(),
            entry_slot: Default::default(),
            entry_leaf: Default::default(),
            slot_q: Default::default(),
            leaf_q: Default::default(),
            valid_q: Default::default(),
            end_q: Default::default(),
            object_q: Default::default(),
            id_q: Default::default(),
            coordinate_q: Default::default(),
            offset_q: Default::default(),
            remaining_q: Default::default(),
            end_due_q: Default::default(),
            local_frames: Constant::new(local_frames),
            vertex_offset: std::array::from_fn(|k| Constant::new(Bits::<16>::from((k * G) as u64))),
            advance: Default::default(),
            take_entry: Default::default(),
            side: Default::default(),
            half: Default::default(),
            difference: Default::default(),
            unused_high_bits: Default::default(),
            high_bits: Constant::new(Bits::<G>::from(((1u64 << G) - 1) & !((1u64 << W) - 1))),
        }
    }
}

impl<const G: usize, const T: usize, const W: usize> Logic for LeafBatcher<G, T, W> {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(
            self,
            clock,
            valid_q,
            end_q,
            object_q,
            id_q,
            remaining_q,
            end_due_q,
            leaf_q
        );
        for o in 0..2 {
            self.slot_q[o].clock.next = self.clock.val();
            self.slot_q[o].d.next = self.slot_q[o].q.val();
        }
        for k in 0..9 {
            self.coordinate_q[k].clock.next = self.clock.val();
            self.coordinate_q[k].d.next = self.coordinate_q[k].q.val();
        }
        for k in 0..3 {
            self.offset_q[k].clock.next = self.clock.val();
            self.offset_q[k].d.next = self.offset_q[k].q.val();
        }

        // The word in the register moves on when the system takes it or
        // when there is none; an end word due keeps the leaf stream waiting.
        self.advance.next = !self.valid_q.q.val() | self.out_ready.val();
        self.in_ready.next = self.advance.val() & !self.end_due_q.q.val();
        self.busy.next = self.valid_q.q.val() | self.end_due_q.q.val();

        // The frame's offset from a header: the cell's centre.
        self.side.next = bits::<G>(1) << self.in_level.val();
        self.half.next = self.side.val() >> 1;
        // Vertex coordinate k is along axis k mod 3.
        for v in 0..3 {
            self.difference[3 * v].next = self
                .in_vertices
                .val()
                .get_bits::<G>(self.vertex_offset[3 * v].val().index())
                - self.offset_q[0].q.val();
            self.difference[3 * v + 1].next = self
                .in_vertices
                .val()
                .get_bits::<G>(self.vertex_offset[3 * v + 1].val().index())
                - self.offset_q[1].q.val();
            self.difference[3 * v + 2].next = self
                .in_vertices
                .val()
                .get_bits::<G>(self.vertex_offset[3 * v + 2].val().index())
                - self.offset_q[2].q.val();
        }

        self.take_entry.next = self.advance.val()
            & !self.end_due_q.q.val()
            & self.in_valid.val()
            & !self.in_header.val();
        // Slots: the entry's number among its object's entries.
        self.entry_valid.next = self.take_entry.val();
        self.entry_object.next = self.in_object.val();
        self.entry_index.next = self.in_index.val();
        self.entry_slot.next = self.slot_q[0].q.val();
        if self.in_object.val() {
            self.entry_slot.next = self.slot_q[1].q.val();
        }
        self.entry_leaf.next = self.leaf_q.q.val();
        if self.take_entry.val() & !self.in_object.val() {
            self.slot_q[0].d.next = self.slot_q[0].q.val() + 1;
        }
        if self.take_entry.val() & self.in_object.val() {
            self.slot_q[1].d.next = self.slot_q[1].q.val() + 1;
        }
        if self.start.val() {
            self.slot_q[0].d.next = 0.into();
            self.slot_q[1].d.next = 0.into();
        }

        // (Written out: `bit_cast` takes no loop index inside `hdl_gen`.)
        if self.take_entry.val() {
            self.coordinate_q[0].d.next = bit_cast::<W, G>(self.difference[0].val());
            self.coordinate_q[1].d.next = bit_cast::<W, G>(self.difference[1].val());
            self.coordinate_q[2].d.next = bit_cast::<W, G>(self.difference[2].val());
            self.coordinate_q[3].d.next = bit_cast::<W, G>(self.difference[3].val());
            self.coordinate_q[4].d.next = bit_cast::<W, G>(self.difference[4].val());
            self.coordinate_q[5].d.next = bit_cast::<W, G>(self.difference[5].val());
            self.coordinate_q[6].d.next = bit_cast::<W, G>(self.difference[6].val());
            self.coordinate_q[7].d.next = bit_cast::<W, G>(self.difference[7].val());
            self.coordinate_q[8].d.next = bit_cast::<W, G>(self.difference[8].val());
        }
        if self.advance.val() {
            self.valid_q.d.next = false;
            if self.end_due_q.q.val() {
                self.valid_q.d.next = true;
                self.end_q.d.next = true;
                self.end_due_q.d.next = false;
            } else if self.in_valid.val() {
                if self.in_header.val() {
                    self.leaf_q.d.next =
                        bit_cast::<CHAIN_LEAF_BITS, LEAF_ADDRESS_BITS>(self.in_leaf_number.val());
                    self.remaining_q.d.next = self.in_count_a.val() + self.in_count_b.val();
                    self.offset_q[0].d.next = 0.into();
                    self.offset_q[1].d.next = 0.into();
                    self.offset_q[2].d.next = 0.into();
                    if self.local_frames.val() {
                        self.offset_q[0].d.next = self.in_x.val() + self.half.val();
                        self.offset_q[1].d.next = self.in_y.val() + self.half.val();
                        self.offset_q[2].d.next = self.in_z.val() + self.half.val();
                    }
                } else {
                    self.valid_q.d.next = true;
                    self.end_q.d.next = false;
                    self.object_q.d.next = self.in_object.val();
                    self.id_q.d.next = bit_cast::<ID_BITS, CHAIN_SLOT_BITS>(self.entry_slot.val());
                    self.remaining_q.d.next = self.remaining_q.q.val() - 1;
                    if self.remaining_q.q.val() == 1 {
                        self.end_due_q.d.next = true;
                    }
                }
            }
        }

        self.out_valid.next = self.valid_q.q.val();
        self.out_end.next = self.end_q.q.val();
        self.out_object.next = self.object_q.q.val();
        self.out_id.next = self.id_q.q.val();
        self.out_x0.next = self.coordinate_q[0].q.val();
        self.out_y0.next = self.coordinate_q[1].q.val();
        self.out_z0.next = self.coordinate_q[2].q.val();
        self.out_x1.next = self.coordinate_q[3].q.val();
        self.out_y1.next = self.coordinate_q[4].q.val();
        self.out_z1.next = self.coordinate_q[5].q.val();
        self.out_x2.next = self.coordinate_q[6].q.val();
        self.out_y2.next = self.coordinate_q[7].q.val();
        self.out_z2.next = self.coordinate_q[8].q.val();
        self.unused_high_bits.next = (self.difference[0].val() & self.high_bits.val()).any()
            ^ (self.difference[1].val() & self.high_bits.val()).any()
            ^ (self.difference[2].val() & self.high_bits.val()).any()
            ^ (self.difference[3].val() & self.high_bits.val()).any()
            ^ (self.difference[4].val() & self.high_bits.val()).any()
            ^ (self.difference[5].val() & self.high_bits.val()).any()
            ^ (self.difference[6].val() & self.high_bits.val()).any()
            ^ (self.difference[7].val() & self.high_bits.val()).any()
            ^ (self.difference[8].val() & self.high_bits.val()).any();

        if self.reset.val() {
            self.valid_q.d.next = false;
            self.end_due_q.d.next = false;
            self.remaining_q.d.next = 0.into();
        }
    }
}
