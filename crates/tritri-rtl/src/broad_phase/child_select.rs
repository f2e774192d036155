//! The list pass's choice of the child it writes this clock
//! ([`super::list_pass`]): the lowest octant left in the entry's mask (in
//! object B's half for a B entry), or the child being flushed, and that
//! child's slot state. Combinational; a unit of its own so that the choice
//! is one always block that reads nothing the pass's block writes (in the
//! pass's block, whose next state reads the choice, it made a false
//! combinational loop, UNOPTFLAT).

use super::list_pass::{CHILDREN, SLOT_BITS};
use crate::axi::ADDRESS_BITS;
use rust_hdl::prelude::*;

#[derive(LogicBlock)]
pub struct ChildSelect {
    /// The entry's octants not yet written.
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
    /// The lowest octant of `mask_left`, one-hot.
    pub lowest: Signal<Out, Bits<8>>,
    /// The chosen child, one-hot (0 when none is).
    pub target: Signal<Out, Bits<CHILDREN>>,
    /// The chosen child's fill, region and slot, and whether that slot is
    /// still pending (the write waits).
    pub fill_of: Signal<Out, Bits<9>>,
    pub blocked: Signal<Out, Bit>,
    pub region_of: Signal<Out, Bits<ADDRESS_BITS>>,
    pub slot: Signal<Out, Bits<SLOT_BITS>>,
    upper_half: Constant<Bits<4>>,
    child_bit: [Constant<Bits<CHILDREN>>; CHILDREN],
    /// Slot `2i` of child `i`.
    child_slot: [Constant<Bits<SLOT_BITS>>; CHILDREN],
    lowest_wide: Signal<Local, Bits<CHILDREN>>,
    chosen: Signal<Local, Bits<CHILDREN>>,
    /// Child `i`'s state where it is chosen, else zero.
    fill_term: [Signal<Local, Bits<9>>; CHILDREN],
    blocked_term: [Signal<Local, Bit>; CHILDREN],
    region_term: [Signal<Local, Bits<ADDRESS_BITS>>; CHILDREN],
    slot_term: [Signal<Local, Bits<SLOT_BITS>>; CHILDREN],
}

impl crate::unit::Unit for ChildSelect {}

impl Default for ChildSelect {
    fn default() -> Self {
        ChildSelect {
            mask_left: Default::default(),
            object: Default::default(),
            flushing: Default::default(),
            flush_child: Default::default(),
            fill: Default::default(),
            half: Default::default(),
            pending_low: Default::default(),
            pending_high: Default::default(),
            region: Default::default(),
            lowest: Default::default(),
            target: Default::default(),
            fill_of: Default::default(),
            blocked: Default::default(),
            region_of: Default::default(),
            slot: Default::default(),
            upper_half: Constant::new(8.into()),
            child_bit: std::array::from_fn(|i| Constant::new(Bits::<CHILDREN>::from(1u64 << i))),
            child_slot: std::array::from_fn(|i| Constant::new((2 * i as u64).into())),
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
        self.lowest.next = self.mask_left.val() & (!self.mask_left.val() + 1);
        self.lowest_wide.next = bit_cast::<CHILDREN, 8>(self.lowest.val());
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
        self.target.next = self.chosen.val();
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
        self.fill_of.next = 0.into();
        self.blocked.next = false;
        self.region_of.next = 0.into();
        self.slot.next = 0.into();
        for i in 0..16 {
            self.fill_of.next = self.fill_of.val() | self.fill_term[i].val();
            self.blocked.next = self.blocked.val() | self.blocked_term[i].val();
            self.region_of.next = self.region_of.val() | self.region_term[i].val();
            self.slot.next = self.slot.val() | self.slot_term[i].val();
        }
    }
}
