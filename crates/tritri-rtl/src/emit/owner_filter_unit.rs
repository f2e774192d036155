//! The emitted owner filter ([`crate::broad_phase::owner_filter`]): its name,
//! port meanings and timing.

use super::{emit, EmitError, EmittedDesign, UnitDescription};
use crate::broad_phase::owner_filter::{OwnerFilter, LEAF_BITS, SLOT_BITS, SLOT_WORD_BITS};
use crate::system::ID_BITS;
use rust_hdl::prelude::*;

/// Top module name for tables of `slots` words per object: `tritri_owner_filter_s<slots>`.
pub fn owner_filter_unit_name(slots: usize) -> String {
    format!("tritri_owner_filter_s{slots}")
}

/// The most slots per object the slot numbers address.
pub const MAX_SLOTS: usize = 1 << SLOT_BITS;

/// rust-hdl's Verilog of the filter with `slots` words per table.
pub fn raw_owner_filter_verilog(slots: usize) -> crate::unit::RawDesign {
    let mut uut = OwnerFilter::new(slots, slots);
    uut.connect_all();
    crate::unit::RawDesign::of(&uut)
}

/// The description of the filter for the emitter.
pub fn owner_filter_unit(slots: usize) -> UnitDescription {
    let word = format!(
        "Slot table word {{id[{}:{}], leaf[{}:{}], first[{}:0]}}: the triangle's id, the slot's leaf, the slot of the triangle's first leaf.",
        SLOT_WORD_BITS - 1,
        LEAF_BITS + SLOT_BITS,
        LEAF_BITS + SLOT_BITS - 1,
        SLOT_BITS,
        SLOT_BITS - 1
    );
    UnitDescription::new(
        &owner_filter_unit_name(slots),
        "Owner filter of the octree broad phase: hits in as slots, each intersecting pair out once as triangle ids, \
         from the first leaf (in schedule order) that holds both triangles.",
    )
    .detail(
        "A leaf's arrays carry slots instead of triangle ids: one slot per triangle per leaf, a triangle's slots \
         consecutive in leaf order. A hit (s_a, s_b) is owned by its leaf when either slot is its triangle's first; \
         otherwise the two triangles' lists of leaves are merged from their first slots, and the first leaf found in \
         both is the owner. The rule and its proof: tritri_geom::scene::owner_slots.",
    )
    .detail(
        "Cycles: a hit accepted at edge t whose merge makes m comparisons leaves at edge t + 2 + m if owned \
         (out_ready high), and the next hit can be accepted at that edge; a duplicate frees the filter at t + 2 + m \
         too (tritri_rtl::broad_phase::owner_filter::pair_cycles). A hit whose triangles are in one leaf each takes 2 cycles.",
    )
    .parameter("SLOTS", &format!("{slots}: words per slot table (one table per object)"))
    .parameter("SLOT_BITS", &format!("{SLOT_BITS}: bits of a slot number"))
    .parameter("LEAF_BITS", &format!("{LEAF_BITS}: bits of a leaf index"))
    .parameter("ID_BITS", &format!("{ID_BITS}: bits of a triangle id"))
    .port("clock", "Clock; every register updates on the rising edge.")
    .port("reset", "Synchronous reset, active high: back to Idle (the tables keep their words).")
    .port("write_a_enable", "Write `write_a_word` into A's slot table at `write_a_slot` at this edge.")
    .port("write_a_slot", "Slot of A's table to write.")
    .port("write_a_word", &word)
    .port("write_b_enable", "Write `write_b_word` into B's slot table at `write_b_slot` at this edge.")
    .port("write_b_slot", "Slot of B's table to write.")
    .port("write_b_word", &word)
    .port("in_valid", "A hit is offered: the slots of its A and B triangles in the leaf that found it.")
    .port("in_ready", "The filter takes the hit (transfer = in_valid & in_ready): in Idle, and as an owned pair leaves.")
    .port("in_slot_a", "Slot of the hit's A triangle.")
    .port("in_slot_b", "Slot of the hit's B triangle.")
    .port("out_valid", "An owned pair is offered.")
    .port("out_ready", "The reader takes it.")
    .port("out_id_a", "Id of the pair's A triangle.")
    .port("out_id_b", "Id of the pair's B triangle.")
    .throughput("one hit per 2 cycles when its triangles are in one leaf each; 1 more per comparison of the merge.")
}

/// The emitted filter with `slots` words per table.
pub fn emit_owner_filter(slots: usize) -> Result<EmittedDesign, EmitError> {
    emit(&raw_owner_filter_verilog(slots), &owner_filter_unit(slots))
}
