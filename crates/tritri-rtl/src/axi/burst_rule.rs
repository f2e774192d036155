//! [`super::burst_beats`] in hardware: the beats of the next burst at
//! `address`, at most `max_burst`, to the 4 KB page's end, and at most
//! `left`. Combinational; a unit of its own so that the minimum is one
//! always block that reads nothing its caller's block writes (in the
//! caller's block it made a false combinational loop that Verilator
//! refuses to order, UNOPTFLAT).

use super::burst_reader::BEAT_BITS;
use super::ADDRESS_BITS;
use rust_hdl::prelude::*;

#[derive(LogicBlock)]
pub struct BurstRule {
    pub address: Signal<In, Bits<ADDRESS_BITS>>,
    pub left: Signal<In, Bits<BEAT_BITS>>,
    pub beats: Signal<Out, Bits<BEAT_BITS>>,
    max_burst: Constant<Bits<BEAT_BITS>>,
    size: Constant<Bits<3>>,
    page_beats: Constant<Bits<BEAT_BITS>>,
    page_left: Signal<Local, Bits<BEAT_BITS>>,
}

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
            page_left: Default::default(),
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
        self.page_left.next = self.page_beats.val()
            - ((self.address.val() >> self.size.val()) & (self.page_beats.val() - 1));
        self.beats.next = self.max_burst.val();
        if self.page_left.val() < self.beats.val() {
            self.beats.next = self.page_left.val();
        }
        if self.left.val() < self.beats.val() {
            self.beats.next = self.left.val();
        }
    }
}
