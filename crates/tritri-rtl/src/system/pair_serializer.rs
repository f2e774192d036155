//! The pair serializer: turns the result FIFO's head word (a `P`-bit mask
//! of the pairs it holds, their hit and certificate bits, `P` base ids, one
//! streamed id) into one `(id_a, id_b, hit, certain)` transfer per cycle on
//! a valid/ready stream.
//!
//! The pairs of a word leave highest pipeline first; `served` remembers the
//! ones already sent, and the word is popped with its last pair. With a
//! reader that is always ready, a word of `k` hits takes `k` cycles.

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
    served: DFF<Bits<MAX_PIPELINES>>,
    pending: Signal<Local, Bits<MAX_PIPELINES>>,
    remaining: Signal<Local, Bits<MAX_PIPELINES>>,
    selected: Signal<Local, Bits<LANE_BITS>>,
    transfer: Signal<Local, Bit>,
}

impl crate::unit::Unit for PairSerializer {
    fn sub_units(&self, units: &mut crate::unit::UnitWalk) {
        crate::sub_units!(self, units, served);
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
            served: Default::default(),
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
        dff_setup!(self, clock, served);
        self.pending.next = self.head_mask.val() & !self.served.q.val();
        // The highest pending pipeline (later assignments win).
        self.selected.next = 0.into();
        self.remaining.next = self.pending.val();
        for i in 0..self.head_base_ids.len() {
            if self.pending.val().get_bit(i) {
                self.selected.next = i.to_bits();
                self.remaining.next = self.pending.val().replace_bit(i, false);
            }
        }
        self.out_id_a.next = self.head_base_ids[0].val();
        for i in 0..self.head_base_ids.len() {
            if self.selected.val().index() == i {
                self.out_id_a.next = self.head_base_ids[i].val();
            }
        }
        // The selected pipeline's bit is the one `remaining` cleared.
        self.out_hit.next =
            (self.head_hit_mask.val() & self.pending.val() & !self.remaining.val()).any();
        self.out_certain.next =
            (self.head_certain_mask.val() & self.pending.val() & !self.remaining.val()).any();
        self.out_id_b.next = self.head_stream_id.val();
        self.out_valid.next = self.head_valid.val();
        self.transfer.next = self.head_valid.val() & self.out_ready.val();
        self.pop.next = self.transfer.val() & (self.remaining.val() == 0);
        if self.transfer.val() {
            if self.remaining.val() == 0 {
                self.served.d.next = 0.into();
            } else {
                self.served.d.next = self.head_mask.val() & !self.remaining.val();
            }
        }
        if self.reset.val() {
            self.served.d.next = 0.into();
        }
    }
}
