//! The emitted owner filter of the broad-phase tops
//! ([`crate::broad_phase::owner_chain_filter`]), alone: its name, port
//! meanings and timing. Inside the tops it is routed with everything else;
//! alone it routes in minutes, which is how its clock is measured.

use super::{emit, EmitError, EmittedDesign, UnitDescription};
use crate::broad_phase::list_packer::INDEX_BITS;
use crate::broad_phase::owner_chain_filter::{OwnerChainFilter, CHAIN_LEAF_BITS, CHAIN_SLOT_BITS};
use rust_hdl::prelude::*;

/// Top module name for `triangles` heads and `slots` records per object:
/// `tritri_owner_chain_filter_t<triangles>_s<slots>`.
pub fn owner_chain_filter_unit_name(triangles: usize, slots: usize) -> String {
    format!("tritri_owner_chain_filter_t{triangles}_s{slots}")
}

/// rust-hdl's Verilog of the filter.
pub fn raw_owner_chain_filter_verilog(triangles: usize, slots: usize) -> crate::unit::RawDesign {
    let mut uut = OwnerChainFilter::new(triangles, slots);
    uut.connect_all();
    crate::unit::RawDesign::of(&uut)
}

/// The description of the filter for the emitter.
pub fn owner_chain_filter_unit(triangles: usize, slots: usize) -> UnitDescription {
    UnitDescription::new(
        &owner_chain_filter_unit_name(triangles, slots),
        "Owner filter of the broad-phase tops: hits in as slots of the entry stream, each reported pair out once, \
         as its triangles' indices, from the first leaf (in stream order) that holds both triangles.",
    )
    .detail(
        "Each object's entries are numbered as they stream (the slot); each slot's record is {index, leaf, prev}, \
         prev the slot of the same triangle's previous appearance, from a head table per object cleared as the \
         triangles load. A hit walks the two chains back from its slots, skipping its own leaf, and merges them: \
         equal leaves are an earlier common leaf (a duplicate, dropped); a chain's end means the pair is owned.",
    )
    .detail(
        "The walk compares records held in registers while the tables read one record ahead, so no comparison \
         lies between a block RAM's output and a read enable.",
    )
    .detail(
        "Cycles from taking a hit to taking the next (out_ready high): 2, plus 1 when owned, plus 1 + m for a walk \
         of m steps (tritri_rtl::broad_phase::owner_chain_filter::hit_clocks).",
    )
    .parameter("TRIANGLES", &format!("{triangles}: head table words (triangles per object)"))
    .parameter("SLOTS", &format!("{slots}: record table words (entries per object in a run)"))
    .parameter("INDEX_BITS", &format!("{INDEX_BITS}: bits of a triangle's index"))
    .parameter("CHAIN_SLOT_BITS", &format!("{CHAIN_SLOT_BITS}: bits of a slot number"))
    .parameter("CHAIN_LEAF_BITS", &format!("{CHAIN_LEAF_BITS}: bits of a leaf number"))
    .port("clock", "Clock; every register updates on the rising edge.")
    .port("reset", "Synchronous reset, active high: back to Idle (the tables keep their words).")
    .port("start", "One clock high as a run starts: the load counters restart, overflow clears.")
    .port("load_valid", "A triangle of load_object is loaded (its index is its place in its object's stream): its head is cleared.")
    .port("load_object", "0 for object A, 1 for B.")
    .port("entry_valid", "An entry streams into the system: its record is written (one clock later).")
    .port("entry_object", "The entry's object.")
    .port("entry_index", "The entry's triangle index.")
    .port("entry_slot", "The entry's slot: its place among its object's entries of the run.")
    .port("entry_leaf", "The entry's leaf number (never decreasing along the stream).")
    .port("in_valid", "A hit is offered: the slots of its two entries.")
    .port("in_ready", "The filter takes the hit (in Idle).")
    .port("in_slot_a", "Slot of the hit's A entry (bits above CHAIN_SLOT_BITS zero).")
    .port("in_slot_b", "Slot of the hit's B entry.")
    .port("in_hit", "The pair's verdict, carried to out_hit.")
    .port("in_certain", "The verdict's certificate, carried to out_certain.")
    .port("out_valid", "An owned pair is offered.")
    .port("out_ready", "The reader takes it.")
    .port("out_index_a", "Index of the pair's A triangle.")
    .port("out_index_b", "Index of the pair's B triangle.")
    .port("out_hit", "The pair's verdict.")
    .port("out_certain", "The verdict's certificate.")
    .port("idle", "No hit in progress.")
    .port("overflow", "An entry's slot was past the record tables' end (sticky until start): decisions may be wrong.")
    .throughput("one hit per 2 clocks (3 when owned) without a walk; 1 + m more for a walk of m steps.")
}

/// The emitted filter.
pub fn emit_owner_chain_filter(triangles: usize, slots: usize) -> Result<EmittedDesign, EmitError> {
    emit(
        &raw_owner_chain_filter_verilog(triangles, slots),
        &owner_chain_filter_unit(triangles, slots),
    )
}
