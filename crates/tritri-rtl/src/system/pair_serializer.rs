//! The pair serializer: turns the result FIFO's head word (a `P`-bit mask
//! of the pairs it holds, their hit and certificate bits, `P` base ids, one
//! streamed id) into one `(id_a, id_b, hit, certain)` transfer per cycle on
//! a valid/ready stream.
//!
//! The serializer takes the head word into registers of its own (popping
//! it from the FIFO) when it holds none or sends its word's last pair, so
//! the FIFO's head goes into those registers and nothing else: deciding
//! the pop from the head put the FIFO's block RAM, the pending mask and
//! the FIFO's read pointer on one path, 60.8 MHz post-route for the W = 8
//! system. The head itself is the block RAM's output register (see
//! `result_fifo`).
//!
//! The pairs of a word leave highest pipeline first; `served` remembers the
//! ones already sent. With a reader that is always ready, a word of `k`
//! pairs takes `k` cycles, and the next word follows without a gap.
//!
//! Whether the pair being sent is the word's last is a register too
//! (`one_left`, set from the word as it loads and from what remains after
//! each transfer): testing `remaining == 0` put the 16-bit selection
//! before the pop and the FIFO's pointers, 89.4 MHz post-route. The masks
//! are cut to the system's `P` lanes as they load, so that synthesis
//! knows the other lanes are empty.

use super::{ID_BITS, LANE_BITS, MAX_PIPELINES};
use rust_hdl::prelude::*;
use rust_hdl::widgets::prelude::DFF;

#[derive(LogicBlock)]
pub struct PairSerializer {
    pub clock: Signal<In, Clock>,
    pub reset: Signal<In, Bit>,
    pub head_valid: Signal<In, Bit>,
    pub head_mask: Signal<In, Bits<MAX_PIPELINES>>,
    pub head_hit_mask: Signal<In, Bits<MAX_PIPELINES>>,
    pub head_certain_mask: Signal<In, Bits<MAX_PIPELINES>>,
    pub head_stream_id: Signal<In, Bits<ID_BITS>>,
    pub head_base_ids: Vec<Signal<In, Bits<ID_BITS>>>,
    pub pop: Signal<Out, Bit>,
    pub out_valid: Signal<Out, Bit>,
    pub out_ready: Signal<In, Bit>,
    pub out_id_a: Signal<Out, Bits<ID_BITS>>,
    pub out_id_b: Signal<Out, Bits<ID_BITS>>,
    pub out_hit: Signal<Out, Bit>,
    pub out_certain: Signal<Out, Bit>,
    /// A word is held, its pairs not all sent (the system's `results_empty`).
    pub holding: Signal<Out, Bit>,
    /// The held word: its valid bit, masks and ids, loaded from the head.
    word_valid: DFF<Bit>,
    word_mask: DFF<Bits<MAX_PIPELINES>>,
    word_hit_mask: DFF<Bits<MAX_PIPELINES>>,
    word_certain_mask: DFF<Bits<MAX_PIPELINES>>,
    word_stream_id: DFF<Bits<ID_BITS>>,
    word_base_ids: Vec<DFF<Bits<ID_BITS>>>,
    served: DFF<Bits<MAX_PIPELINES>>,
    /// Exactly one pair of the held word is not yet sent.
    one_left: DFF<Bit>,
    /// The `P` lanes' bits.
    lanes: Constant<Bits<MAX_PIPELINES>>,
    /// The head word moves in (and is popped) this clock.
    load: Signal<Local, Bit>,
    /// The pairs pending next clock, and of those: some lane set so far,
    /// more than one (the loop below).
    next_pending: Signal<Local, Bits<MAX_PIPELINES>>,
    seen_one: Signal<Local, Bit>,
    seen_two: Signal<Local, Bit>,
    pending: Signal<Local, Bits<MAX_PIPELINES>>,
    remaining: Signal<Local, Bits<MAX_PIPELINES>>,
    selected: Signal<Local, Bits<LANE_BITS>>,
    transfer: Signal<Local, Bit>,
}

impl crate::unit::Unit for PairSerializer {
    fn sub_units(&self, units: &mut crate::unit::UnitWalk) {
        crate::sub_units!(
            self,
            units,
            word_valid,
            word_mask,
            word_hit_mask,
            word_certain_mask,
            word_stream_id,
            word_base_ids,
            served,
            one_left
        );
    }
}

impl PairSerializer {
    pub fn new(pipelines: usize) -> Self {
        assert!((1..=MAX_PIPELINES).contains(&pipelines));
        PairSerializer {
            clock: Default::default(),
            reset: Default::default(),
            head_valid: Default::default(),
            head_mask: Default::default(),
            head_hit_mask: Default::default(),
            head_certain_mask: Default::default(),
            head_stream_id: Default::default(),
            head_base_ids: (0..pipelines).map(|_| Default::default()).collect(),
            pop: Default::default(),
            out_valid: Default::default(),
            out_ready: Default::default(),
            out_id_a: Default::default(),
            out_id_b: Default::default(),
            out_hit: Default::default(),
            out_certain: Default::default(),
            holding: Default::default(),
            word_valid: Default::default(),
            word_mask: Default::default(),
            word_hit_mask: Default::default(),
            word_certain_mask: Default::default(),
            word_stream_id: Default::default(),
            word_base_ids: (0..pipelines).map(|_| Default::default()).collect(),
            served: Default::default(),
            one_left: Default::default(),
            lanes: Constant::new(((1u64 << pipelines) - 1).to_bits()),
            load: Default::default(),
            next_pending: Default::default(),
            seen_one: Default::default(),
            seen_two: Default::default(),
            pending: Default::default(),
            remaining: Default::default(),
            selected: Default::default(),
            transfer: Default::default(),
        }
    }
}

impl Logic for PairSerializer {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(
            self,
            clock,
            word_valid,
            word_mask,
            word_hit_mask,
            word_certain_mask,
            word_stream_id,
            served,
            one_left
        );
        for i in 0..self.word_base_ids.len() {
            self.word_base_ids[i].clock.next = self.clock.val();
            self.word_base_ids[i].d.next = self.word_base_ids[i].q.val();
        }
        self.pending.next = self.word_mask.q.val() & !self.served.q.val();
        // The highest pending pipeline (later assignments win).
        self.selected.next = 0.into();
        self.remaining.next = self.pending.val();
        for i in 0..self.word_base_ids.len() {
            if self.pending.val().get_bit(i) {
                self.selected.next = i.to_bits();
                self.remaining.next = self.pending.val().replace_bit(i, false);
            }
        }
        self.out_id_a.next = self.word_base_ids[0].q.val();
        for i in 0..self.word_base_ids.len() {
            if self.selected.val().index() == i {
                self.out_id_a.next = self.word_base_ids[i].q.val();
            }
        }
        // The selected pipeline's bit is the one `remaining` cleared.
        self.out_hit.next =
            (self.word_hit_mask.q.val() & self.pending.val() & !self.remaining.val()).any();
        self.out_certain.next =
            (self.word_certain_mask.q.val() & self.pending.val() & !self.remaining.val()).any();
        self.out_id_b.next = self.word_stream_id.q.val();
        self.out_valid.next = self.word_valid.q.val();
        self.holding.next = self.word_valid.q.val();
        self.transfer.next = self.word_valid.q.val() & self.out_ready.val();
        // The next word comes in as the last pair of this one goes out.
        self.load.next = self.head_valid.val()
            & (!self.word_valid.q.val() | (self.transfer.val() & self.one_left.q.val()));
        self.pop.next = self.load.val();
        // The pairs pending next clock: the loaded word's, or what remains.
        self.next_pending.next = self.remaining.val();
        if self.load.val() {
            self.next_pending.next = self.head_mask.val() & self.lanes.val();
        }
        self.seen_one.next = false;
        self.seen_two.next = false;
        for i in 0..self.word_base_ids.len() {
            if self.next_pending.val().get_bit(i) {
                self.seen_two.next = self.seen_one.val();
                self.seen_one.next = true;
            }
        }
        if self.transfer.val() {
            self.served.d.next = self.word_mask.q.val() & !self.remaining.val();
            if self.one_left.q.val() {
                self.word_valid.d.next = false;
                self.served.d.next = 0.into();
            }
        }
        if self.transfer.val() | self.load.val() {
            self.one_left.d.next = self.seen_one.val() & !self.seen_two.val();
        }
        if self.load.val() {
            self.word_valid.d.next = true;
            self.served.d.next = 0.into();
            self.word_mask.d.next = self.next_pending.val();
            self.word_hit_mask.d.next = self.head_hit_mask.val() & self.lanes.val();
            self.word_certain_mask.d.next = self.head_certain_mask.val() & self.lanes.val();
            self.word_stream_id.d.next = self.head_stream_id.val();
            for i in 0..self.word_base_ids.len() {
                self.word_base_ids[i].d.next = self.head_base_ids[i].val();
            }
        }
        if self.reset.val() {
            self.word_valid.d.next = false;
            self.served.d.next = 0.into();
        }
    }
}
