//! [`super::burst_beats`] in hardware: the beats of the next burst at
//! `address`, at most `max_burst`, to the 4 KB page's end, and at most
//! `left`. Combinational; a unit of its own so that the minimum is one
//! always block that reads nothing its caller's block writes (in the
//! caller's block it made a false combinational loop that Verilator
//! refuses to order, UNOPTFLAT).

use super::burst_reader::BEAT_BITS;
use rust_hdl::prelude::*;

#[derive(LogicBlock)]
pub struct BurstRule {
    /// The low bits of the burst's address (a page is 4 KB).
    pub address: Signal<In, Bits<RULE_BITS>>,
    pub left: Signal<In, Bits<BEAT_BITS>>,
    /// At most 256: [`RULE_BITS`] wide.
    pub beats: Signal<Out, Bits<RULE_BITS>>,
    max_burst: Constant<Bits<RULE_BITS>>,
    size: Constant<Bits<3>>,
    page_beats: Constant<Bits<RULE_BITS>>,
    page_mask: Constant<Bits<RULE_BITS>>,
    index: Signal<Local, Bits<RULE_BITS>>,
    page_left: Signal<Local, Bits<RULE_BITS>>,
    short: Signal<Local, Bits<RULE_BITS>>,
    left_short: Signal<Local, Bits<RULE_BITS>>,
}

/// Bits the rule computes in: a page holds at most 512 beats (64-bit
/// beats), a burst at most 256, so 16 bits leave the carry chains short.
pub const RULE_BITS: usize = 16;

impl crate::unit::Unit for BurstRule {}

impl BurstRule {
    /// The rule for beats of `beat_bytes` and bursts of at most `max_burst`.
    pub fn new(beat_bytes: u64, max_burst: usize) -> Self {
        BurstRule {
            address: Default::default(),
            left: Default::default(),
            beats: Default::default(),
            max_burst: Constant::new((max_burst as u64).into()),
            size: Constant::new(u64::from(beat_bytes.trailing_zeros()).into()),
            page_beats: Constant::new((super::PAGE_BYTES / beat_bytes).into()),
            page_mask: Constant::new((super::PAGE_BYTES / beat_bytes - 1).into()),
            index: Default::default(),
            page_left: Default::default(),
            short: Default::default(),
            left_short: Default::default(),
        }
    }
}

impl BurstRule {
    /// The longest burst it allows.
    pub fn max_burst(&self) -> u64 {
        self.max_burst.val().to_u64()
    }
}

impl Logic for BurstRule {
    #[hdl_gen]
    fn update(&mut self) {
        // The beat's index in its page.
        self.index.next = (self.address.val() >> self.size.val()) & self.page_mask.val();
        self.page_left.next = self.page_beats.val() - self.index.val();
        self.short.next = self.max_burst.val();
        if self.page_left.val() < self.short.val() {
            self.short.next = self.page_left.val();
        }
        self.left_short.next = bit_cast::<RULE_BITS, BEAT_BITS>(self.left.val());
        if ((self.left.val() >> 16) == 0) & (self.left_short.val() < self.short.val()) {
            self.short.next = self.left_short.val();
        }
        self.beats.next = self.short.val();
    }
}
