//! The owner filter: each intersecting pair reported once, decided in
//! hardware. It sits on the system's result stream when the octree broad
//! phase sends leaves whose arrays carry *slots* instead of triangle ids
//! (`tritri_geom::scene::owner_slots`, where the rule and its proof are):
//! a hit arrives as two slots `(s_a, s_b)` of the leaf that found it, and
//! leaves as the two triangle ids only if that leaf is the first to hold
//! both triangles.
//!
//! Each object has a slot table, one [`SimpleDualPortRam`] word per slot,
//! `{id, leaf, first}`: the triangle's id, the slot's leaf, and the slot of
//! the triangle's first leaf. The host (or the binning unit) writes the
//! tables through the write ports before the hits arrive.
//!
//! ```text
//! Idle ──(in_valid: read A[s_a], B[s_b])──► Head
//! Head:  a slot is its triangle's first ──────────────────────► Emit
//!        else read A[first_a], B[first_b] ────────────────────► Merge
//! Merge: leaves equal: the leaf of the hit ───────────────────► Emit
//!                      an earlier leaf (a duplicate) ─────────► Idle
//!        A's leaf lower: read A's next slot, else B's next ───► Merge
//! Emit:  out_valid; with out_ready: the next hit (as in Idle) ► Head
//!                                   or none ──────────────────► Idle
//! ```
//!
//! Timing (the cycle model [`pair_cycles`] counts it): a hit accepted at a
//! rising edge `t` whose test makes `m` comparisons in Merge leaves at
//! edge `t + 2 + m` if owned (with `out_ready` high), and the next hit can
//! be accepted at that same edge; a duplicate frees the unit at `t + 2 + m`
//! too. Most hits need no comparison (a triangle in one leaf only): 2
//! cycles. `in_ready` depends on `out_ready` (in Emit) but on no data.

use crate::system::dual_port_ram::SimpleDualPortRam;
use crate::system::ID_BITS;
use rust_hdl::prelude::*;
use rust_hdl::widgets::prelude::DFF;

/// Bits of a slot number: up to 2^24 slots per object.
pub const SLOT_BITS: usize = 24;
/// Bits of a leaf index: up to 65,536 leaves.
pub const LEAF_BITS: usize = 16;
/// A slot table word: `{id, leaf, first}`, id in the top bits.
pub const SLOT_WORD_BITS: usize = ID_BITS + LEAF_BITS + SLOT_BITS;

// The slices in `update` spell these widths as literals (`#[hdl_gen]` reads
// a named constant as a signal): `first` [23:0], `leaf` [39:24], `id` [71:40].
const _: () = assert!(SLOT_BITS == 24 && LEAF_BITS == 16 && ID_BITS == 32);

/// The filter's states.
#[derive(Copy, Clone, PartialEq, Eq, Debug, LogicState)]
pub enum OwnerState {
    Idle,
    Head,
    Merge,
    Emit,
}

#[derive(LogicBlock)]
pub struct OwnerFilter {
    pub clock: Signal<In, Clock>,
    /// Synchronous, active high: back to Idle (the tables keep their words).
    pub reset: Signal<In, Bit>,
    // Slot table writes, one port per object.
    pub write_a_enable: Signal<In, Bit>,
    pub write_a_slot: Signal<In, Bits<SLOT_BITS>>,
    pub write_a_word: Signal<In, Bits<SLOT_WORD_BITS>>,
    pub write_b_enable: Signal<In, Bit>,
    pub write_b_slot: Signal<In, Bits<SLOT_BITS>>,
    pub write_b_word: Signal<In, Bits<SLOT_WORD_BITS>>,
    // Hits in, as slots (valid/ready).
    pub in_valid: Signal<In, Bit>,
    pub in_ready: Signal<Out, Bit>,
    pub in_slot_a: Signal<In, Bits<SLOT_BITS>>,
    pub in_slot_b: Signal<In, Bits<SLOT_BITS>>,
    // Owned pairs out, as triangle ids (valid/ready).
    pub out_valid: Signal<Out, Bit>,
    pub out_ready: Signal<In, Bit>,
    pub out_id_a: Signal<Out, Bits<ID_BITS>>,
    pub out_id_b: Signal<Out, Bits<ID_BITS>>,
    table_a: SimpleDualPortRam<Bits<SLOT_WORD_BITS>, SLOT_BITS>,
    table_b: SimpleDualPortRam<Bits<SLOT_WORD_BITS>, SLOT_BITS>,
    state: DFF<OwnerState>,
    /// The slots being read (the hit's, then the merge's).
    slot_a: DFF<Bits<SLOT_BITS>>,
    slot_b: DFF<Bits<SLOT_BITS>>,
    /// The hit's leaf and ids, kept from Head to Emit.
    leaf: DFF<Bits<LEAF_BITS>>,
    id_a: DFF<Bits<ID_BITS>>,
    id_b: DFF<Bits<ID_BITS>>,
    // The words the tables show, taken apart.
    word_a_leaf: Signal<Local, Bits<LEAF_BITS>>,
    word_b_leaf: Signal<Local, Bits<LEAF_BITS>>,
    word_a_first: Signal<Local, Bits<SLOT_BITS>>,
    word_b_first: Signal<Local, Bits<SLOT_BITS>>,
    /// A hit moves in this cycle.
    take: Signal<Local, Bit>,
}

impl crate::unit::Unit for OwnerFilter {
    fn sub_units(&self, units: &mut crate::unit::UnitWalk) {
        crate::sub_units!(self, units, table_a, table_b, state, slot_a, slot_b, leaf, id_a, id_b);
    }
}

impl OwnerFilter {
    /// A filter whose tables hold `slots_a` and `slots_b` words.
    pub fn new(slots_a: usize, slots_b: usize) -> Self {
        OwnerFilter {
            clock: Default::default(),
            reset: Default::default(),
            write_a_enable: Default::default(),
            write_a_slot: Default::default(),
            write_a_word: Default::default(),
            write_b_enable: Default::default(),
            write_b_slot: Default::default(),
            write_b_word: Default::default(),
            in_valid: Default::default(),
            in_ready: Default::default(),
            in_slot_a: Default::default(),
            in_slot_b: Default::default(),
            out_valid: Default::default(),
            out_ready: Default::default(),
            out_id_a: Default::default(),
            out_id_b: Default::default(),
            table_a: SimpleDualPortRam::new(slots_a),
            table_b: SimpleDualPortRam::new(slots_b),
            state: Default::default(),
            slot_a: Default::default(),
            slot_b: Default::default(),
            leaf: Default::default(),
            id_a: Default::default(),
            id_b: Default::default(),
            word_a_leaf: Default::default(),
            word_b_leaf: Default::default(),
            word_a_first: Default::default(),
            word_b_first: Default::default(),
            take: Default::default(),
        }
    }
}

/// A slot table word.
pub fn slot_word(id: u32, leaf: u32, first: u32) -> Bits<SLOT_WORD_BITS> {
    let mut word = Bits::<SLOT_WORD_BITS>::default();
    word.set_bits::<SLOT_BITS>(0, (first as u64).into());
    word.set_bits::<LEAF_BITS>(SLOT_BITS, (leaf as u64).into());
    word.set_bits::<ID_BITS>(SLOT_BITS + LEAF_BITS, (id as u64).into());
    word
}

impl Logic for OwnerFilter {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(self, clock, state, slot_a, slot_b, leaf, id_a, id_b);
        clock!(self, clock, table_a, table_b);
        self.table_a.write_enable.next = self.write_a_enable.val();
        self.table_a.write_address.next = self.write_a_slot.val();
        self.table_a.write_data.next = self.write_a_word.val();
        self.table_b.write_enable.next = self.write_b_enable.val();
        self.table_b.write_address.next = self.write_b_slot.val();
        self.table_b.write_data.next = self.write_b_word.val();
        self.word_a_leaf.next = self.table_a.read_data.val().get_bits::<16>(24);
        self.word_b_leaf.next = self.table_b.read_data.val().get_bits::<16>(24);
        self.word_a_first.next = self.table_a.read_data.val().get_bits::<24>(0);
        self.word_b_first.next = self.table_b.read_data.val().get_bits::<24>(0);
        // No read unless a state asks for one (a table not read holds its word).
        self.table_a.read_enable.next = false;
        self.table_b.read_enable.next = false;
        self.table_a.read_address.next = self.slot_a.q.val();
        self.table_b.read_address.next = self.slot_b.q.val();
        self.in_ready.next = (self.state.q.val() == OwnerState::Idle)
            | ((self.state.q.val() == OwnerState::Emit) & self.out_ready.val());
        self.take.next = self.in_valid.val() & self.in_ready.val();
        self.out_valid.next = self.state.q.val() == OwnerState::Emit;
        self.out_id_a.next = self.id_a.q.val();
        self.out_id_b.next = self.id_b.q.val();
        match self.state.q.val() {
            OwnerState::Idle => {}
            OwnerState::Head => {
                self.id_a.d.next = self.table_a.read_data.val().get_bits::<32>(40);
                self.id_b.d.next = self.table_b.read_data.val().get_bits::<32>(40);
                self.leaf.d.next = self.word_a_leaf.val();
                if (self.word_a_first.val() == self.slot_a.q.val())
                    | (self.word_b_first.val() == self.slot_b.q.val())
                {
                    self.state.d.next = OwnerState::Emit;
                } else {
                    self.table_a.read_enable.next = true;
                    self.table_b.read_enable.next = true;
                    self.table_a.read_address.next = self.word_a_first.val();
                    self.table_b.read_address.next = self.word_b_first.val();
                    self.slot_a.d.next = self.word_a_first.val();
                    self.slot_b.d.next = self.word_b_first.val();
                    self.state.d.next = OwnerState::Merge;
                }
            }
            OwnerState::Merge => {
                if self.word_a_leaf.val() == self.word_b_leaf.val() {
                    if self.word_a_leaf.val() == self.leaf.q.val() {
                        self.state.d.next = OwnerState::Emit;
                    } else {
                        self.state.d.next = OwnerState::Idle;
                    }
                } else if self.word_a_leaf.val() < self.word_b_leaf.val() {
                    self.table_a.read_enable.next = true;
                    self.table_a.read_address.next = self.slot_a.q.val() + 1;
                    self.slot_a.d.next = self.slot_a.q.val() + 1;
                } else {
                    self.table_b.read_enable.next = true;
                    self.table_b.read_address.next = self.slot_b.q.val() + 1;
                    self.slot_b.d.next = self.slot_b.q.val() + 1;
                }
            }
            OwnerState::Emit => {
                if self.out_ready.val() {
                    self.state.d.next = OwnerState::Idle;
                }
            }
        }
        // A hit is taken in Idle, or as an owned pair leaves (in_ready).
        if self.take.val() {
            self.table_a.read_enable.next = true;
            self.table_b.read_enable.next = true;
            self.table_a.read_address.next = self.in_slot_a.val();
            self.table_b.read_address.next = self.in_slot_b.val();
            self.slot_a.d.next = self.in_slot_a.val();
            self.slot_b.d.next = self.in_slot_b.val();
            self.state.d.next = OwnerState::Head;
        }
        if self.reset.val() {
            self.state.d.next = OwnerState::Idle;
        }
    }
}

/// The cycle model: the rising edges (counted from 0, the edge at which
/// the first hit is accepted) at which each owned pair leaves, for hits
/// offered back to back and `out_ready` always high; each item is a hit's
/// verdict and its Merge comparisons
/// (`tritri_geom::scene::owner_slots::OwnerDecision`). Also returns the
/// edge at which the filter has finished the last hit.
pub fn pair_cycles(decisions: impl IntoIterator<Item = (bool, u32)>) -> (Vec<u64>, u64) {
    let mut edge = 0u64;
    let mut out = Vec::new();
    for (owned, comparisons) in decisions {
        edge += 2 + comparisons as u64;
        if owned {
            out.push(edge);
        }
    }
    (out, edge)
}
