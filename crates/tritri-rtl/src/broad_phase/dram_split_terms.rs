//! The binning controller's split-rule terms for its current cell
//! ([`super::dram_binning_unit`]): what the cell's pass is charged, whether
//! the cell cannot pay for a split, where its children's lists would go in
//! the arena and whether they fit. The terms are the clock-exact model's
//! ([`super::dram_binning_machine`]): a pass is charged
//! [`PASS_FIXED_CLOCKS`] and its entries' beats; each child's list is as
//! long as its parent's, rounded up to a write burst.
//!
//! Registered: the outputs are the terms of the inputs one clock earlier.
//! The controller reads them at its query's last counter, three clocks
//! after the cell's counts settled, so the register costs no clock; it
//! cuts the chain of 48-bit carries (sums, strides, the arena's new top,
//! the compare) that was the controller's critical path. Only `cannot_pay`
//! reads an input of its own clock, the leaf cost, which arrives at that
//! last counter: it compares the cost with a registered bound.
//!
//! A block of its own: in the controller's one combinational block, a term
//! read back through a continuous assignment looks like a loop to Verilator
//! (UNOPTFLAT).

use super::dram_binning_machine::PASS_FIXED_CLOCKS;
use super::list_entry::ENTRY_BYTES;
use super::list_pass::WRITE_BURST_BEATS;
use rust_hdl::prelude::*;
use rust_hdl::widgets::prelude::DFF;

#[derive(LogicBlock)]
pub struct SplitTerms {
    pub clock: Signal<In, Clock>,
    /// The cell's entries of each object, its level, and whether it is the
    /// root (whose pass is charged as empty and which is always passed).
    pub count_a: Signal<In, Bits<32>>,
    pub count_b: Signal<In, Bits<32>>,
    pub level: Signal<In, Bits<6>>,
    pub at_root: Signal<In, Bit>,
    /// The cell's cost as a leaf (read in its own clock).
    pub leaf_cost: Signal<In, Bits<48>>,
    /// The arena's top and end.
    pub arena_top: Signal<In, Bits<32>>,
    pub arena_end: Signal<In, Bits<32>>,
    /// What the cell's pass is charged.
    pub classify: Signal<Out, Bits<48>>,
    /// The level forces a split (local frames).
    pub forced: Signal<Out, Bit>,
    /// Its leaf costs no more than its triangles' batch writes and its pass.
    pub cannot_pay: Signal<Out, Bit>,
    /// Bytes between the children's lists of each object.
    pub stride_a: Signal<Out, Bits<32>>,
    pub stride_b: Signal<Out, Bits<32>>,
    /// Where B's children's lists begin (A's at the arena's top), and the
    /// top above them: 32-bit addresses, meant only when they fit (the
    /// sums are taken in 48 bits, so none wraps before the test).
    pub children_b: Signal<Out, Bits<32>>,
    pub new_top: Signal<Out, Bits<32>>,
    pub fits: Signal<Out, Bit>,
    pass_fixed: Constant<Bits<48>>,
    log_beats_per_entry: Constant<Bits<48>>,
    entries_per_burst_less_one: Constant<Bits<48>>,
    log_entries_per_burst: Constant<Bits<48>>,
    log_burst_bytes: Constant<Bits<48>>,
    max_leaf_enable: Constant<Bit>,
    max_leaf_level: Constant<Bits<6>>,
    classify_q: DFF<Bits<48>>,
    forced_q: DFF<Bit>,
    /// A leaf cost at most this cannot pay for a split, where `payable`.
    bound_q: DFF<Bits<48>>,
    payable_q: DFF<Bit>,
    stride_a_q: DFF<Bits<32>>,
    stride_b_q: DFF<Bits<32>>,
    children_b_q: DFF<Bits<32>>,
    new_top_q: DFF<Bits<32>>,
    fits_q: DFF<Bit>,
    classify_now: Signal<Local, Bits<48>>,
    forced_now: Signal<Local, Bit>,
    sum: Signal<Local, Bits<48>>,
    wide_a: Signal<Local, Bits<48>>,
    wide_b: Signal<Local, Bits<48>>,
    bursts_a: Signal<Local, Bits<48>>,
    bursts_b: Signal<Local, Bits<48>>,
    wide_stride_a: Signal<Local, Bits<48>>,
    wide_stride_b: Signal<Local, Bits<48>>,
    wide_children_b: Signal<Local, Bits<48>>,
    wide_new_top: Signal<Local, Bits<48>>,
}

impl crate::unit::Unit for SplitTerms {
    fn sub_units(&self, units: &mut crate::unit::UnitWalk) {
        crate::sub_units!(
            self,
            units,
            classify_q,
            forced_q,
            bound_q,
            payable_q,
            stride_a_q,
            stride_b_q,
            children_b_q,
            new_top_q,
            fits_q
        );
    }
}

impl SplitTerms {
    /// For a port of `data_bits`-bit beats; cells above `max_leaf_level`
    /// always split.
    pub fn new(data_bits: usize, max_leaf_level: Option<u32>) -> Self {
        let beat_bytes = (data_bits / 8) as u64;
        let beats_per_entry = ENTRY_BYTES as u64 / beat_bytes;
        let burst_bytes = WRITE_BURST_BEATS as u64 * beat_bytes;
        let entries_per_burst = burst_bytes / ENTRY_BYTES as u64;
        SplitTerms {
            clock: Default::default(),
            count_a: Default::default(),
            count_b: Default::default(),
            level: Default::default(),
            at_root: Default::default(),
            leaf_cost: Default::default(),
            arena_top: Default::default(),
            arena_end: Default::default(),
            classify: Default::default(),
            forced: Default::default(),
            cannot_pay: Default::default(),
            stride_a: Default::default(),
            stride_b: Default::default(),
            children_b: Default::default(),
            new_top: Default::default(),
            fits: Default::default(),
            pass_fixed: Constant::new(PASS_FIXED_CLOCKS.into()),
            log_beats_per_entry: Constant::new(u64::from(beats_per_entry.ilog2()).into()),
            entries_per_burst_less_one: Constant::new((entries_per_burst - 1).into()),
            log_entries_per_burst: Constant::new(u64::from(entries_per_burst.ilog2()).into()),
            log_burst_bytes: Constant::new(u64::from(burst_bytes.ilog2()).into()),
            max_leaf_enable: Constant::new(max_leaf_level.is_some()),
            max_leaf_level: Constant::new(u64::from(max_leaf_level.unwrap_or(0)).into()),
            classify_q: Default::default(),
            forced_q: Default::default(),
            bound_q: Default::default(),
            payable_q: Default::default(),
            stride_a_q: Default::default(),
            stride_b_q: Default::default(),
            children_b_q: Default::default(),
            new_top_q: Default::default(),
            fits_q: Default::default(),
            classify_now: Default::default(),
            forced_now: Default::default(),
            sum: Default::default(),
            wide_a: Default::default(),
            wide_b: Default::default(),
            bursts_a: Default::default(),
            bursts_b: Default::default(),
            wide_stride_a: Default::default(),
            wide_stride_b: Default::default(),
            wide_children_b: Default::default(),
            wide_new_top: Default::default(),
        }
    }
}

impl Logic for SplitTerms {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(
            self,
            clock,
            classify_q,
            forced_q,
            bound_q,
            payable_q,
            stride_a_q,
            stride_b_q,
            children_b_q,
            new_top_q,
            fits_q
        );
        self.wide_a.next = bit_cast::<48, 32>(self.count_a.val());
        self.wide_b.next = bit_cast::<48, 32>(self.count_b.val());
        self.sum.next = self.wide_a.val() + self.wide_b.val();
        self.classify_now.next =
            self.pass_fixed.val() + (self.sum.val() << self.log_beats_per_entry.val());
        if self.at_root.val() {
            self.classify_now.next = self.pass_fixed.val();
        }
        self.forced_now.next =
            self.max_leaf_enable.val() & (self.level.val() > self.max_leaf_level.val());
        self.classify_q.d.next = self.classify_now.val();
        self.forced_q.d.next = self.forced_now.val();
        self.bound_q.d.next = self.sum.val() + 1 + self.classify_now.val();
        self.payable_q.d.next = !self.at_root.val() & !self.forced_now.val();
        self.classify.next = self.classify_q.q.val();
        self.forced.next = self.forced_q.q.val();
        self.cannot_pay.next =
            self.payable_q.q.val() & (self.leaf_cost.val() <= self.bound_q.q.val());
        // Each child list as long as its parent's, on a write burst; an
        // empty one still takes a burst.
        self.bursts_a.next = (self.wide_a.val() + self.entries_per_burst_less_one.val())
            >> self.log_entries_per_burst.val();
        self.bursts_b.next = (self.wide_b.val() + self.entries_per_burst_less_one.val())
            >> self.log_entries_per_burst.val();
        self.wide_stride_a.next = self.bursts_a.val() << self.log_burst_bytes.val();
        if self.bursts_a.val() == 0 {
            self.wide_stride_a.next = bits::<48>(1) << self.log_burst_bytes.val();
        }
        self.wide_stride_b.next = self.bursts_b.val() << self.log_burst_bytes.val();
        if self.bursts_b.val() == 0 {
            self.wide_stride_b.next = bits::<48>(1) << self.log_burst_bytes.val();
        }
        self.wide_children_b.next =
            bit_cast::<48, 32>(self.arena_top.val()) + (self.wide_stride_a.val() << 3);
        self.wide_new_top.next = self.wide_children_b.val() + (self.wide_stride_b.val() << 3);
        self.fits_q.d.next = self.wide_new_top.val() <= bit_cast::<48, 32>(self.arena_end.val());
        self.stride_a_q.d.next = self.wide_stride_a.val().get_bits::<32>(0);
        self.stride_b_q.d.next = self.wide_stride_b.val().get_bits::<32>(0);
        self.children_b_q.d.next = self.wide_children_b.val().get_bits::<32>(0);
        self.new_top_q.d.next = self.wide_new_top.val().get_bits::<32>(0);
        self.fits.next = self.fits_q.q.val();
        self.stride_a.next = self.stride_a_q.q.val();
        self.stride_b.next = self.stride_b_q.q.val();
        self.children_b.next = self.children_b_q.q.val();
        self.new_top.next = self.new_top_q.q.val();
    }
}
