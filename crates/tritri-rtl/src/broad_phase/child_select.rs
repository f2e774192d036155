//! The list pass's choice of the child it writes this clock
//! ([`super::list_pass`]): the lowest octant left in the entry's mask (in
//! object B's half for a B entry), or the child being flushed, and that
//! child's slot state.
//!
//! The choice is made a clock ahead: the inputs are the pass's registers'
//! *next* values, and the outputs are registers, equal in every clock to
//! the choice on the pass's registers of that clock. The pass's decision
//! to write a beat and take the next entry so starts from registers: made
//! from the pass's registers directly, the lowest octant's carry chain,
//! the sixteen-way mux of the slot states and the FIFO pops behind them
//! were 13 levels, the top's critical path (23.3 ns on the ECP5-85).
//! A unit of its own, so that the choice is one always block that reads
//! nothing the pass's block writes (in the pass's block, whose next state
//! reads the choice, it made a false combinational loop, UNOPTFLAT).

use super::list_pass::{CHILDREN, SLOT_BITS};
use crate::axi::ADDRESS_BITS;
use rust_hdl::prelude::*;
use rust_hdl::widgets::prelude::DFF;

#[derive(LogicBlock)]
pub struct ChildSelect {
    pub clock: Signal<In, Clock>,
    // The pass's state after this clock's edge.
    /// The entry's octants not yet written (those a B entry may go to).
    pub mask_left: Signal<In, Bits<8>>,
    /// The entry is object B's: its children are 8 to 15.
    pub object: Signal<In, Bit>,
    /// After the last entry, `flush_child` is chosen instead.
    pub flushing: Signal<In, Bit>,
    pub flush_child: Signal<In, Bits<4>>,
    /// Each child's beats in its current slot.
    pub fill: [Signal<In, Bits<9>>; CHILDREN],
    /// Each child's current slot: 0 low, 1 high.
    pub half: [Signal<In, Bit>; CHILDREN],
    /// A full slot not yet read out to W.
    pub pending_low: [Signal<In, Bit>; CHILDREN],
    pub pending_high: [Signal<In, Bit>; CHILDREN],
    /// The address of each child's next burst.
    pub region: [Signal<In, Bits<ADDRESS_BITS>>; CHILDREN],
    // The choice in this clock, on the pass's registers of this clock.
    /// `mask_left`.
    pub live: Signal<Out, Bits<8>>,
    /// `live` has at most one octant: its lowest is its last.
    pub single: Signal<Out, Bit>,
    /// The lowest octant of `live`, one-hot.
    pub lowest: Signal<Out, Bits<8>>,
    /// The chosen child, one-hot (0 when none is).
    pub target: Signal<Out, Bits<CHILDREN>>,
    /// The chosen child's fill, region and slot, and whether that slot is
    /// still pending (the write waits).
    pub fill_of: Signal<Out, Bits<9>>,
    pub blocked: Signal<Out, Bit>,
    pub region_of: Signal<Out, Bits<ADDRESS_BITS>>,
    pub slot: Signal<Out, Bits<SLOT_BITS>>,
    live_q: DFF<Bits<8>>,
    single_q: DFF<Bit>,
    lowest_q: DFF<Bits<8>>,
    target_q: DFF<Bits<CHILDREN>>,
    fill_of_q: DFF<Bits<9>>,
    blocked_q: DFF<Bit>,
    region_of_q: DFF<Bits<ADDRESS_BITS>>,
    slot_q: DFF<Bits<SLOT_BITS>>,
    upper_half: Constant<Bits<4>>,
    child_bit: [Constant<Bits<CHILDREN>>; CHILDREN],
    /// Slot `2i` of child `i`.
    child_slot: [Constant<Bits<SLOT_BITS>>; CHILDREN],
    lowest_next: Signal<Local, Bits<8>>,
    fill_next: Signal<Local, Bits<9>>,
    blocked_next: Signal<Local, Bit>,
    region_next: Signal<Local, Bits<ADDRESS_BITS>>,
    slot_next: Signal<Local, Bits<SLOT_BITS>>,
    lowest_wide: Signal<Local, Bits<CHILDREN>>,
    chosen: Signal<Local, Bits<CHILDREN>>,
    /// Child `i`'s state where it is chosen, else zero.
    fill_term: [Signal<Local, Bits<9>>; CHILDREN],
    blocked_term: [Signal<Local, Bit>; CHILDREN],
    region_term: [Signal<Local, Bits<ADDRESS_BITS>>; CHILDREN],
    slot_term: [Signal<Local, Bits<SLOT_BITS>>; CHILDREN],
}

impl crate::unit::Unit for ChildSelect {
    fn sub_units(&self, units: &mut crate::unit::UnitWalk) {
        crate::sub_units!(
            self,
            units,
            live_q,
            single_q,
            lowest_q,
            target_q,
            fill_of_q,
            blocked_q,
            region_of_q,
            slot_q
        );
    }
}

impl Default for ChildSelect {
    fn default() -> Self {
        ChildSelect {
            clock: Default::default(),
            mask_left: Default::default(),
            object: Default::default(),
            flushing: Default::default(),
            flush_child: Default::default(),
            fill: Default::default(),
            half: Default::default(),
            pending_low: Default::default(),
            pending_high: Default::default(),
            region: Default::default(),
            live: Default::default(),
            single: Default::default(),
            lowest: Default::default(),
            target: Default::default(),
            fill_of: Default::default(),
            blocked: Default::default(),
            region_of: Default::default(),
            slot: Default::default(),
            live_q: Default::default(),
            single_q: Default::default(),
            lowest_q: Default::default(),
            target_q: Default::default(),
            fill_of_q: Default::default(),
            blocked_q: Default::default(),
            region_of_q: Default::default(),
            slot_q: Default::default(),
            upper_half: Constant::new(8.into()),
            child_bit: std::array::from_fn(|i| Constant::new(Bits::<CHILDREN>::from(1u64 << i))),
            child_slot: std::array::from_fn(|i| Constant::new((2 * i as u64).into())),
            lowest_next: Default::default(),
            fill_next: Default::default(),
            blocked_next: Default::default(),
            region_next: Default::default(),
            slot_next: Default::default(),
            lowest_wide: Default::default(),
            chosen: Default::default(),
            fill_term: Default::default(),
            blocked_term: Default::default(),
            region_term: Default::default(),
            slot_term: Default::default(),
        }
    }
}

impl Logic for ChildSelect {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(
            self,
            clock,
            live_q,
            single_q,
            lowest_q,
            target_q,
            fill_of_q,
            blocked_q,
            region_of_q,
            slot_q
        );
        self.live.next = self.live_q.q.val();
        self.single.next = self.single_q.q.val();
        self.lowest.next = self.lowest_q.q.val();
        self.target.next = self.target_q.q.val();
        self.fill_of.next = self.fill_of_q.q.val();
        self.blocked.next = self.blocked_q.q.val();
        self.region_of.next = self.region_of_q.q.val();
        self.slot.next = self.slot_q.q.val();
        // The next clock's choice.
        self.live_q.d.next = self.mask_left.val();
        self.single_q.d.next = (self.mask_left.val() & (self.mask_left.val() - 1)) == 0;
        self.lowest_next.next = self.mask_left.val() & (!self.mask_left.val() + 1);
        self.lowest_q.d.next = self.lowest_next.val();
        self.lowest_wide.next = bit_cast::<CHILDREN, 8>(self.lowest_next.val());
        self.chosen.next = self.lowest_wide.val();
        if self.object.val() {
            self.chosen.next = self.lowest_wide.val() << self.upper_half.val();
        }
        if self.flushing.val() {
            self.chosen.next = 0.into();
            for i in 0..16 {
                if self.flush_child.val().index() == i {
                    self.chosen.next = self.child_bit[i].val();
                }
            }
        }
        self.target_q.d.next = self.chosen.val();
        for i in 0..16 {
            self.fill_term[i].next = 0.into();
            self.blocked_term[i].next = false;
            self.region_term[i].next = 0.into();
            self.slot_term[i].next = 0.into();
            if self.chosen.val().get_bit(i) {
                self.fill_term[i].next = self.fill[i].val();
                self.blocked_term[i].next = self.pending_low[i].val();
                self.slot_term[i].next = self.child_slot[i].val();
                if self.half[i].val() {
                    self.blocked_term[i].next = self.pending_high[i].val();
                    self.slot_term[i].next = self.child_slot[i].val() + 1;
                }
                self.region_term[i].next = self.region[i].val();
            }
        }
        // Gathered in locals: a DFF's `d` reads back its settled value
        // only, not what this block wrote.
        self.fill_next.next = 0.into();
        self.blocked_next.next = false;
        self.region_next.next = 0.into();
        self.slot_next.next = 0.into();
        for i in 0..16 {
            self.fill_next.next = self.fill_next.val() | self.fill_term[i].val();
            self.blocked_next.next = self.blocked_next.val() | self.blocked_term[i].val();
            self.region_next.next = self.region_next.val() | self.region_term[i].val();
            self.slot_next.next = self.slot_next.val() | self.slot_term[i].val();
        }
        self.fill_of_q.d.next = self.fill_next.val();
        self.blocked_q.d.next = self.blocked_next.val();
        self.region_of_q.d.next = self.region_next.val();
        self.slot_q.d.next = self.slot_next.val();
    }
}
