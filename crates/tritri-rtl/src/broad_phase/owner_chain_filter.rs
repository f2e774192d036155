//! Each intersecting pair once, decided inside the broad-phase top from
//! tables the hardware writes as the leaves stream (the host-built slot
//! tables of [`super::owner_filter`] need every leaf of a triangle before
//! its first slot is numbered, so they cannot be written on the fly).
//!
//! The rule is the same: a pair belongs to the first leaf, in stream
//! order, holding both triangles (`OctreeSchedule::owner`). Here each
//! object's entries are numbered as they stream (the *slot*), and each
//! slot's *record* is `{index, leaf, prev}`: the triangle, its leaf, and
//! the slot of the same triangle's previous appearance (a *chain* back
//! through the triangle's leaves; a per-object *head* table holds each
//! triangle's last slot, cleared as the triangle is loaded). The system's
//! ids are the slots, so a hit arrives as `(s_a, s_b)` from leaf `L`.
//! `L` owns the pair iff no leaf before `L` holds both triangles: walk the
//! two chains back from `s_a` and `s_b` (leaf numbers never increase
//! along a chain), skipping appearances in `L` itself (earlier tiles of
//! the same leaf), and merge: equal leaves are an earlier common leaf (a
//! duplicate, dropped); otherwise step the chain at the higher leaf; a
//! chain that ends means no earlier common leaf (the pair is emitted, as
//! its two triangles' indices).
//!
//! ```text
//! Idle ──(in_valid: read A[s_a], B[s_b])──► First
//! First: either has no previous appearance ───────────────────► Emit
//!        else read both previous slots ───────────────────────► Load
//! Load:  keep both records, read the slots before them ───────► Walk
//! Walk:  equal leaves below L (a duplicate) ──────────────────► Idle
//!        else step the chain at L or at the higher leaf:
//!        its end ─────────────────────────────────────────────► Emit
//!        else keep the record read ahead, read the one before ► Walk
//! Emit:  out_valid until out_ready ───────────────────────────► Idle
//! ```
//!
//! The walk compares records held in registers (`cur_a`, `cur_b`), while
//! each table already shows the record before its chain's (read ahead in
//! Load and at every step): a step takes the table's word and reads the
//! slot it names, so no comparison lies between a table's output and a
//! table's read enable. Comparing the tables' outputs directly put a
//! block RAM's clock-to-output, two 20-bit compares and the enable's fan-out
//! in one clock: the DRAM top's worst path at 43.6 MHz.
//!
//! A hit taken at edge `t` whose walk makes `m` steps frees the unit after
//! [`hit_clocks`]`(owned, m)` clocks: `t + 2` and one more when owned (with
//! `out_ready` high) if there is no walk, plus `1 + m` for a walk
//! ([`decide`] counts `m`). The records are written one clock after their
//! entry (the head is read, then the record and the new head written); a
//! hit reads them some pipeline latency later.

use super::list_packer::INDEX_BITS;
use crate::system::dual_port_ram::SimpleDualPortRam;
use crate::system::ID_BITS;
use rust_hdl::prelude::*;
use rust_hdl::widgets::prelude::DFF;

/// Bits of a slot number (entries of one object over a run).
pub const CHAIN_SLOT_BITS: usize = 24;
/// Bits of a leaf number.
pub const CHAIN_LEAF_BITS: usize = 20;

/// One appearance of a triangle in a leaf.
#[derive(Clone, Copy, Debug, PartialEq, Default, LogicStruct)]
pub struct ChainRecord {
    pub index: Bits<INDEX_BITS>,
    pub leaf: Bits<CHAIN_LEAF_BITS>,
    pub prev: Bits<CHAIN_SLOT_BITS>,
    pub has_prev: Bit,
}

/// A triangle's last appearance so far.
#[derive(Clone, Copy, Debug, PartialEq, Default, LogicStruct)]
pub struct ChainHead {
    pub slot: Bits<CHAIN_SLOT_BITS>,
    pub valid: Bit,
}

#[derive(Copy, Clone, PartialEq, Eq, Debug, LogicState)]
pub enum ChainState {
    Idle,
    First,
    Load,
    Walk,
    Emit,
}

#[derive(LogicBlock)]
pub struct OwnerChainFilter {
    pub clock: Signal<In, Clock>,
    /// Synchronous, active high: back to Idle (the tables keep their words).
    pub reset: Signal<In, Bit>,
    /// One clock high as a run starts: the load counters restart.
    pub start: Signal<In, Bit>,
    /// A triangle of `load_object` is loaded (its index is its position in
    /// its object's stream): its head is cleared.
    pub load_valid: Signal<In, Bit>,
    pub load_object: Signal<In, Bit>,
    /// An entry streams into the system: its object, triangle, slot and leaf.
    pub entry_valid: Signal<In, Bit>,
    pub entry_object: Signal<In, Bit>,
    pub entry_index: Signal<In, Bits<INDEX_BITS>>,
    pub entry_slot: Signal<In, Bits<CHAIN_SLOT_BITS>>,
    pub entry_leaf: Signal<In, Bits<CHAIN_LEAF_BITS>>,
    /// Hits from the system (valid/ready): the two slots.
    pub in_valid: Signal<In, Bit>,
    pub in_ready: Signal<Out, Bit>,
    pub in_slot_a: Signal<In, Bits<ID_BITS>>,
    pub in_slot_b: Signal<In, Bits<ID_BITS>>,
    /// The pair's verdict and certificate, carried to `out_hit`, `out_certain`.
    pub in_hit: Signal<In, Bit>,
    pub in_certain: Signal<In, Bit>,
    /// Owned pairs (valid/ready): the two triangles' indices.
    pub out_valid: Signal<Out, Bit>,
    pub out_ready: Signal<In, Bit>,
    pub out_index_a: Signal<Out, Bits<ID_BITS>>,
    pub out_index_b: Signal<Out, Bits<ID_BITS>>,
    pub out_hit: Signal<Out, Bit>,
    pub out_certain: Signal<Out, Bit>,
    /// No hit in progress.
    pub idle: Signal<Out, Bit>,
    /// An entry's slot was past the record tables' end (sticky until the
    /// next start): its record is lost and decisions may be wrong.
    pub overflow: Signal<Out, Bit>,
    overflow_q: DFF<Bit>,
    /// The record tables' depth, one past the last slot.
    slot_limit: Constant<Bits<{ CHAIN_SLOT_BITS + 1 }>>,
    heads: [SimpleDualPortRam<ChainHead, INDEX_BITS>; 2],
    records: [SimpleDualPortRam<ChainRecord, CHAIN_SLOT_BITS>; 2],
    loaded: [DFF<Bits<INDEX_BITS>>; 2],
    // The entry whose head is being read.
    entry_q: DFF<Bit>,
    entry_object_q: DFF<Bit>,
    entry_index_q: DFF<Bits<INDEX_BITS>>,
    entry_slot_q: DFF<Bits<CHAIN_SLOT_BITS>>,
    entry_leaf_q: DFF<Bits<CHAIN_LEAF_BITS>>,
    state: DFF<ChainState>,
    hit_leaf: DFF<Bits<CHAIN_LEAF_BITS>>,
    /// The walk's place in each chain (the tables show the records before).
    cur_a: DFF<ChainRecord>,
    cur_b: DFF<ChainRecord>,
    index_a: DFF<Bits<INDEX_BITS>>,
    index_b: DFF<Bits<INDEX_BITS>>,
    hit_q: DFF<Bit>,
    certain_q: DFF<Bit>,
    // Combinational.
    record_a: Signal<Local, ChainRecord>,
    record_b: Signal<Local, ChainRecord>,
    head: Signal<Local, ChainHead>,
    /// What the tables are written with: a cleared head, an entry's
    /// record and its new head.
    cleared: Signal<Local, ChainHead>,
    new_record: Signal<Local, ChainRecord>,
    new_head: Signal<Local, ChainHead>,
    step_a: Signal<Local, Bit>,
    step_b: Signal<Local, Bit>,
    /// The hits' slot ids above the slot bits are zero; folded here for
    /// Verilator's lint.
    unused_high_bits: Signal<Local, Bit>,
}

impl crate::unit::Unit for OwnerChainFilter {
    fn sub_units(&self, units: &mut crate::unit::UnitWalk) {
        crate::sub_units!(
            self,
            units,
            overflow_q,
            heads,
            records,
            loaded,
            entry_q,
            entry_object_q,
            entry_index_q,
            entry_slot_q,
            entry_leaf_q,
            state,
            hit_leaf,
            cur_a,
            cur_b,
            index_a,
            index_b,
            hit_q,
            certain_q
        );
    }
}

impl OwnerChainFilter {
    /// Tables for `triangles` per object and `slots` entries per object.
    pub fn new(triangles: usize, slots: usize) -> Self {
        OwnerChainFilter {
            clock: Default::default(),
            reset: Default::default(),
            start: Default::default(),
            load_valid: Default::default(),
            load_object: Default::default(),
            entry_valid: Default::default(),
            entry_object: Default::default(),
            entry_index: Default::default(),
            entry_slot: Default::default(),
            entry_leaf: Default::default(),
            in_valid: Default::default(),
            in_ready: Default::default(),
            in_slot_a: Default::default(),
            in_slot_b: Default::default(),
            in_hit: Default::default(),
            in_certain: Default::default(),
            out_valid: Default::default(),
            out_ready: Default::default(),
            out_index_a: Default::default(),
            out_index_b: Default::default(),
            out_hit: Default::default(),
            out_certain: Default::default(),
            idle: Default::default(),
            overflow: Default::default(),
            overflow_q: Default::default(),
            slot_limit: Constant::new(Bits::<{ CHAIN_SLOT_BITS + 1 }>::from(slots as u64)),
            heads: std::array::from_fn(|_| SimpleDualPortRam::new(triangles)),
            records: std::array::from_fn(|_| SimpleDualPortRam::new(slots)),
            loaded: Default::default(),
            entry_q: Default::default(),
            entry_object_q: Default::default(),
            entry_index_q: Default::default(),
            entry_slot_q: Default::default(),
            entry_leaf_q: Default::default(),
            state: Default::default(),
            hit_leaf: Default::default(),
            cur_a: Default::default(),
            cur_b: Default::default(),
            index_a: Default::default(),
            index_b: Default::default(),
            hit_q: Default::default(),
            certain_q: Default::default(),
            record_a: Default::default(),
            record_b: Default::default(),
            head: Default::default(),
            cleared: Default::default(),
            new_record: Default::default(),
            new_head: Default::default(),
            step_a: Default::default(),
            step_b: Default::default(),
            unused_high_bits: Default::default(),
        }
    }
}

impl Logic for OwnerChainFilter {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(
            self,
            clock,
            entry_q,
            entry_object_q,
            entry_index_q,
            entry_slot_q,
            entry_leaf_q,
            state,
            hit_leaf,
            cur_a,
            cur_b,
            index_a,
            index_b,
            hit_q,
            certain_q,
            overflow_q
        );
        self.overflow.next = self.overflow_q.q.val();
        if self.entry_valid.val()
            & (bit_cast::<{ CHAIN_SLOT_BITS + 1 }, CHAIN_SLOT_BITS>(self.entry_slot.val())
                >= self.slot_limit.val())
        {
            self.overflow_q.d.next = true;
        }
        self.cleared.next.slot = 0.into();
        self.cleared.next.valid = false;
        for o in 0..2 {
            self.heads[o].clock.next = self.clock.val();
            self.records[o].clock.next = self.clock.val();
            self.loaded[o].clock.next = self.clock.val();
            self.loaded[o].d.next = self.loaded[o].q.val();
            self.heads[o].write_enable.next = false;
            self.heads[o].write_address.next = self.loaded[o].q.val();
            self.heads[o].write_data.next = self.cleared.val();
            self.heads[o].read_enable.next = false;
            self.heads[o].read_address.next = self.entry_index.val();
            self.records[o].write_enable.next = false;
            self.records[o].write_address.next = self.entry_slot_q.q.val();
            self.records[o].read_enable.next = false;
        }

        // Loading: each triangle's head cleared as it comes in.
        if self.start.val() {
            self.loaded[0].d.next = 0.into();
            self.loaded[1].d.next = 0.into();
            self.overflow_q.d.next = false;
        }
        if self.load_valid.val() & !self.load_object.val() {
            self.heads[0].write_enable.next = true;
            self.loaded[0].d.next = self.loaded[0].q.val() + 1;
        }
        if self.load_valid.val() & self.load_object.val() {
            self.heads[1].write_enable.next = true;
            self.loaded[1].d.next = self.loaded[1].q.val() + 1;
        }

        // Streaming: an entry's head is read, then its record and the new
        // head are written (the stream never repeats a triangle of an
        // object on consecutive clocks).
        self.entry_q.d.next = self.entry_valid.val();
        self.entry_object_q.d.next = self.entry_object.val();
        self.entry_index_q.d.next = self.entry_index.val();
        self.entry_slot_q.d.next = self.entry_slot.val();
        self.entry_leaf_q.d.next = self.entry_leaf.val();
        self.heads[0].read_enable.next = self.entry_valid.val() & !self.entry_object.val();
        self.heads[1].read_enable.next = self.entry_valid.val() & self.entry_object.val();
        self.head.next = self.heads[0].read_data.val();
        if self.entry_object_q.q.val() {
            self.head.next = self.heads[1].read_data.val();
        }
        self.new_record.next.index = self.entry_index_q.q.val();
        self.new_record.next.leaf = self.entry_leaf_q.q.val();
        self.new_record.next.prev = self.head.val().slot;
        self.new_record.next.has_prev = self.head.val().valid;
        self.new_head.next.slot = self.entry_slot_q.q.val();
        self.new_head.next.valid = true;
        self.records[0].write_data.next = self.new_record.val();
        self.records[1].write_data.next = self.new_record.val();
        if self.entry_q.q.val() & !self.entry_object_q.q.val() {
            self.records[0].write_enable.next = true;
            self.heads[0].write_enable.next = true;
            self.heads[0].write_address.next = self.entry_index_q.q.val();
            self.heads[0].write_data.next = self.new_head.val();
        }
        if self.entry_q.q.val() & self.entry_object_q.q.val() {
            self.records[1].write_enable.next = true;
            self.heads[1].write_enable.next = true;
            self.heads[1].write_address.next = self.entry_index_q.q.val();
            self.heads[1].write_data.next = self.new_head.val();
        }

        // Hits.
        self.record_a.next = self.records[0].read_data.val();
        self.record_b.next = self.records[1].read_data.val();
        self.records[0].read_address.next = self.record_a.val().prev;
        self.records[1].read_address.next = self.record_b.val().prev;
        // In Walk: step the chain at the hit's own leaf, else the one at
        // the higher leaf; neither: equal leaves below it, a duplicate.
        // Registers only: the tables' outputs feed addresses, not this.
        self.step_a.next = (self.cur_a.q.val().leaf == self.hit_leaf.q.val())
            | ((self.cur_b.q.val().leaf != self.hit_leaf.q.val())
                & (self.cur_a.q.val().leaf > self.cur_b.q.val().leaf));
        self.step_b.next = !self.step_a.val()
            & ((self.cur_b.q.val().leaf == self.hit_leaf.q.val())
                | (self.cur_b.q.val().leaf > self.cur_a.q.val().leaf));
        self.in_ready.next = self.state.q.val() == ChainState::Idle;
        self.out_valid.next = self.state.q.val() == ChainState::Emit;
        self.out_index_a.next = bit_cast::<ID_BITS, INDEX_BITS>(self.index_a.q.val());
        self.out_index_b.next = bit_cast::<ID_BITS, INDEX_BITS>(self.index_b.q.val());
        self.out_hit.next = self.hit_q.q.val();
        self.out_certain.next = self.certain_q.q.val();
        self.idle.next = self.state.q.val() == ChainState::Idle;
        self.unused_high_bits.next = self.in_slot_a.val().get_bits::<8>(24).any()
            ^ self.in_slot_b.val().get_bits::<8>(24).any();

        match self.state.q.val() {
            ChainState::Idle => {
                self.records[0].read_address.next =
                    bit_cast::<CHAIN_SLOT_BITS, ID_BITS>(self.in_slot_a.val());
                self.records[1].read_address.next =
                    bit_cast::<CHAIN_SLOT_BITS, ID_BITS>(self.in_slot_b.val());
                if self.in_valid.val() {
                    self.records[0].read_enable.next = true;
                    self.records[1].read_enable.next = true;
                    self.hit_q.d.next = self.in_hit.val();
                    self.certain_q.d.next = self.in_certain.val();
                    self.state.d.next = ChainState::First;
                }
            }
            ChainState::First => {
                self.hit_leaf.d.next = self.record_a.val().leaf;
                self.index_a.d.next = self.record_a.val().index;
                self.index_b.d.next = self.record_b.val().index;
                if self.record_a.val().has_prev & self.record_b.val().has_prev {
                    self.records[0].read_enable.next = true;
                    self.records[1].read_enable.next = true;
                    self.state.d.next = ChainState::Load;
                } else {
                    self.state.d.next = ChainState::Emit;
                }
            }
            ChainState::Load => {
                // A record without a previous one names slot 0 (a cleared
                // head's), a word the table holds: reading it is harmless.
                self.cur_a.d.next = self.record_a.val();
                self.cur_b.d.next = self.record_b.val();
                self.records[0].read_enable.next = true;
                self.records[1].read_enable.next = true;
                self.state.d.next = ChainState::Walk;
            }
            ChainState::Walk => {
                if self.step_a.val() {
                    if self.cur_a.q.val().has_prev {
                        self.cur_a.d.next = self.record_a.val();
                        self.records[0].read_enable.next = true;
                    } else {
                        self.state.d.next = ChainState::Emit;
                    }
                } else if self.step_b.val() {
                    if self.cur_b.q.val().has_prev {
                        self.cur_b.d.next = self.record_b.val();
                        self.records[1].read_enable.next = true;
                    } else {
                        self.state.d.next = ChainState::Emit;
                    }
                } else {
                    self.state.d.next = ChainState::Idle;
                }
            }
            ChainState::Emit => {
                if self.out_ready.val() {
                    self.state.d.next = ChainState::Idle;
                }
            }
        }
        if self.reset.val() {
            self.state.d.next = ChainState::Idle;
            self.entry_q.d.next = false;
            self.overflow_q.d.next = false;
        }
    }
}

/// What the top streams for `leaf_lists` at memory depth `depth`: the
/// entries in order, `(object, index, leaf)` (tiles as
/// [`super::broad_phase_system::leaf_tiles`] cuts them), the system's hits
/// as slots (the pairs of each tile that `touches`), and each hit's leaf.
pub fn streamed(
    leaf_lists: &[(Vec<u32>, Vec<u32>)],
    depth: usize,
    touches: impl Fn(u32, u32) -> bool,
) -> Streamed {
    let mut out = Streamed::default();
    let mut slots = [0u32; 2];
    for (leaf, ta, tb) in super::broad_phase_system::leaf_tiles(leaf_lists, depth) {
        let first = slots;
        out.entries
            .extend(ta.iter().map(|&i| (false, i, leaf as u32)));
        out.entries
            .extend(tb.iter().map(|&j| (true, j, leaf as u32)));
        slots[0] += ta.len() as u32;
        slots[1] += tb.len() as u32;
        for (x, &i) in ta.iter().enumerate() {
            for (y, &j) in tb.iter().enumerate() {
                if touches(i, j) {
                    out.hits.push((first[0] + x as u32, first[1] + y as u32));
                    out.hit_leaves.push(leaf);
                }
            }
        }
    }
    out
}

/// [`streamed`]'s result.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Streamed {
    pub entries: Vec<(bool, u32, u32)>,
    pub hits: Vec<(u32, u32)>,
    pub hit_leaves: Vec<usize>,
}

/// Clocks from taking a hit to taking the next (`out_ready` high): a hit
/// decided in First takes 2 (and one in Emit when owned); a walk of
/// `steps` steps adds Load and one clock a step.
pub fn hit_clocks(owned: bool, steps: u64) -> u64 {
    2 + owned as u64 + if steps > 0 { 1 + steps } else { 0 }
}

/// The filter's decision on each hit, with the steps its walk makes: the
/// model the co-simulation checks the unit's pairs against. `entries` are
/// the stream's entries in order, `(object, index, leaf)`; `hits` the
/// system's, as slots.
pub fn decide(entries: &[(bool, u32, u32)], hits: &[(u32, u32)]) -> Vec<(Option<(u32, u32)>, u64)> {
    // Records per object: (index, leaf, prev).
    let mut records: [Vec<(u32, u32, Option<u32>)>; 2] = Default::default();
    let mut heads: [std::collections::HashMap<u32, u32>; 2] = Default::default();
    for &(object, index, leaf) in entries {
        let o = object as usize;
        let slot = records[o].len() as u32;
        records[o].push((index, leaf, heads[o].get(&index).copied()));
        heads[o].insert(index, slot);
    }
    hits.iter()
        .map(|&(sa, sb)| {
            let (ia, l, mut pa) = records[0][sa as usize];
            let (ib, _, mut pb) = records[1][sb as usize];
            let mut steps = 0;
            loop {
                let (Some(a), Some(b)) = (pa, pb) else {
                    return (Some((ia, ib)), steps);
                };
                let (ra, rb) = (records[0][a as usize], records[1][b as usize]);
                steps += 1;
                if ra.1 == l || (rb.1 != l && ra.1 > rb.1) {
                    pa = ra.2;
                } else if rb.1 == l || rb.1 > ra.1 {
                    pb = rb.2;
                } else {
                    return (None, steps);
                }
            }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::collections::BTreeSet;

    /// On random leaves, tiled as the binning unit streams them, the walk
    /// keeps each pair exactly once, and from the first leaf holding both
    /// triangles.
    #[test]
    fn each_pair_is_kept_once_from_its_first_leaf() {
        let mut state = 0x2545_f491_4f6c_dd1du64;
        let mut next = |n: u64| {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            state % n
        };
        for depth in [1usize, 3, 64] {
            let leaves: Vec<(Vec<u32>, Vec<u32>)> = (0..40)
                .map(|_| {
                    let pick = |next: &mut dyn FnMut(u64) -> u64| -> Vec<u32> {
                        (0..12).filter(|_| next(3) == 0).collect()
                    };
                    (pick(&mut next), pick(&mut next))
                })
                .filter(|(a, b): &(Vec<u32>, Vec<u32>)| !a.is_empty() && !b.is_empty())
                .collect();
            let touches = |i: u32, j: u32| (i * 7 + j * 3) % 4 == 0;
            let Streamed {
                entries,
                hits,
                hit_leaves,
            } = streamed(&leaves, depth, touches);
            let first_leaf = |i: u32, j: u32| {
                leaves
                    .iter()
                    .position(|(la, lb)| la.contains(&i) && lb.contains(&j))
                    .unwrap()
            };
            let mut kept = BTreeSet::new();
            for ((owned, _), leaf) in decide(&entries, &hits).into_iter().zip(&hit_leaves) {
                if let Some((i, j)) = owned {
                    assert!(kept.insert((i, j)), "depth {depth}: ({i}, {j}) kept twice");
                    assert_eq!(
                        *leaf,
                        first_leaf(i, j),
                        "depth {depth}: ({i}, {j}) kept from leaf {leaf}"
                    );
                }
            }
            let all: BTreeSet<(u32, u32)> = leaves
                .iter()
                .flat_map(|(la, lb)| {
                    la.iter()
                        .flat_map(move |&i| lb.iter().map(move |&j| (i, j)))
                })
                .filter(|&(i, j)| touches(i, j))
                .collect();
            assert_eq!(kept, all, "depth {depth}");
            assert!(
                hits.len() > 2 * all.len(),
                "depth {depth}: {} hits, {} pairs",
                hits.len(),
                all.len()
            );
        }
    }
}
