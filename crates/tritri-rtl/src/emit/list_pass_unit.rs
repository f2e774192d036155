//! The emitted pass over lists in external memory
//! ([`crate::broad_phase::list_pass`]): its name, ports and the widths it is
//! built for.

use super::axi_copy_unit::axi_manager_ports;
use super::{emit, EmitError, EmittedDesign, UnitDescription};
use crate::broad_phase::list_pass::{ListPass, WRITE_BURST_BEATS};
use crate::broad_phase::list_pass_machine::ListPassConfig;
use crate::octree::value_bits;
use rust_hdl::prelude::*;

/// Grid widths a pass unit is emitted for.
pub const LIST_PASS_GRID_WIDTHS: [usize; 2] = [16, 24];

/// `tritri_list_pass_g<G>_d<DW>_r<read burst>_o<outstanding>`.
pub fn list_pass_unit_name(config: &ListPassConfig) -> String {
    format!(
        "tritri_list_pass_g{}_d{}_r{}_o{}",
        config.grid_bits, config.data_bits, config.max_read_burst, config.outstanding
    )
}

/// A pass unit that cannot be built, or could not be emitted.
#[derive(Debug, thiserror::Error)]
pub enum ListPassEmitError {
    #[error("list pass unit: {0}")]
    Config(String),
    #[error(transparent)]
    Emit(#[from] EmitError),
}

/// The unit for `config`, handed to `f` (the dispatch from run-time
/// widths to the type's constants, written once).
pub fn with_list_pass<R>(
    config: &ListPassConfig,
    f: impl ListPassVisitor<Output = R>,
) -> Result<R, String> {
    config.check()?;
    if !LIST_PASS_GRID_WIDTHS.contains(&config.grid_bits) {
        return Err(format!(
            "a pass unit is built for {LIST_PASS_GRID_WIDTHS:?}-bit grids, not {}",
            config.grid_bits
        ));
    }
    const V16: usize = value_bits(16);
    const V24: usize = value_bits(24);
    let (r, o) = (config.max_read_burst, config.outstanding);
    Ok(match (config.grid_bits, config.data_bits) {
        (16, 64) => f.visit(ListPass::<16, V16, { 13 * V16 }, 144, 64, 8>::new(r, o)),
        (16, 128) => f.visit(ListPass::<16, V16, { 13 * V16 }, 144, 128, 16>::new(r, o)),
        (16, _) => f.visit(ListPass::<16, V16, { 13 * V16 }, 144, 256, 32>::new(r, o)),
        (_, 64) => f.visit(ListPass::<24, V24, { 13 * V24 }, 216, 64, 8>::new(r, o)),
        (_, 128) => f.visit(ListPass::<24, V24, { 13 * V24 }, 216, 128, 16>::new(r, o)),
        _ => f.visit(ListPass::<24, V24, { 13 * V24 }, 216, 256, 32>::new(r, o)),
    })
}

/// What is done with a pass unit of whichever widths.
pub trait ListPassVisitor {
    type Output;
    fn visit<
        const G: usize,
        const V: usize,
        const N: usize,
        const T: usize,
        const DW: usize,
        const S: usize,
    >(
        self,
        unit: ListPass<G, V, N, T, DW, S>,
    ) -> Self::Output;
}

struct Raw;

impl ListPassVisitor for Raw {
    type Output = crate::unit::RawDesign;
    fn visit<
        const G: usize,
        const V: usize,
        const N: usize,
        const T: usize,
        const DW: usize,
        const S: usize,
    >(
        self,
        mut unit: ListPass<G, V, N, T, DW, S>,
    ) -> crate::unit::RawDesign {
        unit.connect_all();
        crate::unit::RawDesign::of(&unit)
    }
}

/// The description of the unit for the emitter.
pub fn list_pass_unit(config: &ListPassConfig) -> UnitDescription {
    let (g, dw) = (config.grid_bits, config.data_bits);
    let mut unit = UnitDescription::new(
        &list_pass_unit_name(config),
        &format!(
            "One cell's pass of the octree broad phase with its lists in external memory: the cell's A and B \
             lists (32-byte entries: {g}-bit vertices and an index) read over one AXI4 manager port, each entry \
             classified against the cell's eight children, and appended to the list of every child it meets."
        ),
    )
    .detail(&format!(
        "Reads: INCR bursts of {dw}-bit beats, at most {} beats, never across 4 KB, at most {} in flight. \
         Writes: a burst of {WRITE_BURST_BEATS} beats per full child slot (two slots per child), the \
         rest after the last entry; at most {} unanswered.",
        config.max_read_burst, config.outstanding, config.outstanding
    ))
    .detail(
        "Cycles: tritri_rtl::broad_phase::list_pass_machine, clock-exact against the memory model \
         tritri_rtl::axi::memory_model.",
    )
    .parameter("GRID_BITS", &format!("{g}: bits of a vertex coordinate"))
    .parameter("DATA_BITS", &format!("{dw}: bits of a beat"))
    .port("clock", "Clock; every register updates on the rising edge.")
    .port("reset", "Synchronous reset, active high.")
    .port("start", "One clock high while not busy: a pass over the cell and lists on the inputs, read in that clock.")
    .port("corner_x", "The cell's low corner, x (two's complement grid coordinate).")
    .port("corner_y", "The cell's low corner, y.")
    .port("corner_z", "The cell's low corner, z.")
    .port("level", "The cell's level: its side is 2^level grid steps; at least 1.")
    .port("list_base_0", "Byte address of A's list, aligned to the beat.")
    .port("list_base_1", "Byte address of B's list, aligned to the beat.")
    .port("list_count_0", "Entries of A's list.")
    .port("list_count_1", "Entries of B's list.")
    .port("child_base_0", "Byte address of A's child 0 list, aligned to a write burst; child o at child_base_0 + o * child_stride_0.")
    .port("child_base_1", "The same for B.")
    .port("child_stride_0", "Bytes between A's child lists: a multiple of a write burst, at least A's list.")
    .port("child_stride_1", "The same for B.")
    .port("busy", "From the clock after `start` until `done`.")
    .port("done", "High from the end of a pass (every write response in) until the next `start`.")
    .port("error", "A read or write response of the pass was not OKAY, or not for ID 0.");
    for i in 0..16 {
        let (object, octant) = (["A", "B"][i / 8], i % 8);
        unit = unit.port(
            &format!("child_count_{i}"),
            &format!("Entries written to {object}'s child {octant} (valid with `done`)."),
        );
    }
    for (name, meaning) in axi_manager_ports() {
        unit = unit.port(name, meaning);
    }
    unit.throughput(&format!(
        "an entry per {} clocks read, a beat per clock written to the children",
        config.beats_per_entry()
    ))
}

/// The emitted pass unit.
pub fn emit_list_pass(config: &ListPassConfig) -> Result<EmittedDesign, ListPassEmitError> {
    let raw = with_list_pass(config, Raw).map_err(ListPassEmitError::Config)?;
    Ok(emit(&raw, &list_pass_unit(config))?)
}
