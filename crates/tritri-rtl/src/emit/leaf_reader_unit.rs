//! The emitted leaf reader ([`crate::broad_phase::leaf_reader`]): its name,
//! ports and the widths it is built for.

use super::axi_copy_unit::axi_manager_ports;
use super::list_pass_unit::LIST_PASS_GRID_WIDTHS;
use super::{emit, EmitError, EmittedDesign, UnitDescription};
use crate::broad_phase::leaf_reader::LeafReader;
use crate::broad_phase::list_pass_machine::ListPassConfig;
use rust_hdl::prelude::*;

/// `tritri_leaf_reader_g<G>_d<DW>_r<read burst>_o<outstanding>`.
pub fn leaf_reader_unit_name(config: &ListPassConfig) -> String {
    format!(
        "tritri_leaf_reader_g{}_d{}_r{}_o{}",
        config.grid_bits, config.data_bits, config.max_read_burst, config.outstanding
    )
}

/// A leaf reader that cannot be built, or could not be emitted.
#[derive(Debug, thiserror::Error)]
pub enum LeafReaderEmitError {
    #[error("leaf reader: {0}")]
    Config(String),
    #[error(transparent)]
    Emit(#[from] EmitError),
}

/// The unit for `config` (its grid, port and bursts), handed to `f`.
pub fn with_leaf_reader<R>(
    config: &ListPassConfig,
    f: impl LeafReaderVisitor<Output = R>,
) -> Result<R, String> {
    config.check()?;
    if !LIST_PASS_GRID_WIDTHS.contains(&config.grid_bits) {
        return Err(format!(
            "a leaf reader is built for {LIST_PASS_GRID_WIDTHS:?}-bit grids, not {}",
            config.grid_bits
        ));
    }
    let (r, o) = (config.max_read_burst, config.outstanding);
    Ok(match (config.grid_bits, config.data_bits) {
        (16, 64) => f.visit(LeafReader::<16, 144, 64, 8>::new(r, o)),
        (16, 128) => f.visit(LeafReader::<16, 144, 128, 16>::new(r, o)),
        (16, _) => f.visit(LeafReader::<16, 144, 256, 32>::new(r, o)),
        (_, 64) => f.visit(LeafReader::<24, 216, 64, 8>::new(r, o)),
        (_, 128) => f.visit(LeafReader::<24, 216, 128, 16>::new(r, o)),
        _ => f.visit(LeafReader::<24, 216, 256, 32>::new(r, o)),
    })
}

/// What is done with a leaf reader of whichever widths.
pub trait LeafReaderVisitor {
    type Output;
    fn visit<const G: usize, const T: usize, const DW: usize, const S: usize>(
        self,
        unit: LeafReader<G, T, DW, S>,
    ) -> Self::Output;
}

struct Raw;

impl LeafReaderVisitor for Raw {
    type Output = crate::unit::RawDesign;
    fn visit<const G: usize, const T: usize, const DW: usize, const S: usize>(
        self,
        mut unit: LeafReader<G, T, DW, S>,
    ) -> crate::unit::RawDesign {
        unit.connect_all();
        crate::unit::RawDesign::of(&unit)
    }
}

/// The description of the unit for the emitter.
pub fn leaf_reader_unit(config: &ListPassConfig) -> UnitDescription {
    let (g, dw) = (config.grid_bits, config.data_bits);
    let mut unit = UnitDescription::new(
        &leaf_reader_unit_name(config),
        &format!(
            "A leaf of the octree broad phase read back from external memory for the narrow phase: the \
             leaf's A list, then its B list (32-byte entries: {g}-bit vertices and an index), read over one \
             AXI4 manager port and streamed as a header and the entries, valid/ready."
        ),
    )
    .detail(&format!(
        "Reads: INCR bursts of {dw}-bit beats, at most {} beats, never across 4 KB, at most {} in flight. \
         The write channels are idle.",
        config.max_read_burst, config.outstanding
    ))
    .detail(
        "Cycles: tritri_rtl::broad_phase::leaf_reader_machine, clock-exact against the memory model \
         tritri_rtl::axi::memory_model.",
    )
    .parameter("GRID_BITS", &format!("{g}: bits of a vertex coordinate"))
    .parameter("DATA_BITS", &format!("{dw}: bits of a beat"))
    .port("clock", "Clock; every register updates on the rising edge.")
    .port("reset", "Synchronous reset, active high.")
    .port("start", "One clock high while not busy: read the leaf on the inputs, read in that clock.")
    .port("corner_x", "The leaf's low corner, x (two's complement grid coordinate).")
    .port("corner_y", "The leaf's low corner, y.")
    .port("corner_z", "The leaf's low corner, z.")
    .port("level", "The leaf's level: its side is 2^level grid steps.")
    .port("list_base_0", "Byte address of A's list, aligned to the beat.")
    .port("list_base_1", "Byte address of B's list, aligned to the beat.")
    .port("list_count_0", "Entries of A's list.")
    .port("list_count_1", "Entries of B's list.")
    .port("busy", "From the clock after `start` until the last entry has gone.")
    .port("reading", "From the clock after `start` until the last beat has left the reader: the lists must stay unwritten.")
    .port("error", "A read response was not OKAY, or not for ID 0, since `start`.")
    .port("out_valid", "A word of the leaf stream is offered.")
    .port("out_ready", "The word is taken at this clock's edge.")
    .port("out_header", "The word is the leaf's header (out_x .. out_count_b); otherwise an entry.")
    .port("out_object", "An entry's object: 0 for A, 1 for B.")
    .port("out_index", "An entry's triangle index in its object.")
    .port("out_vertices", &format!("An entry's vertices: x0 y0 z0 x1 y1 z1 x2 y2 z2, {g} bits each from bit 0 up."))
    .port("out_x", "The leaf's low corner, x, from the clock after `start`.")
    .port("out_y", "The leaf's low corner, y.")
    .port("out_z", "The leaf's low corner, z.")
    .port("out_level", "The leaf's level.")
    .port("out_count_a", "Entries of A's list.")
    .port("out_count_b", "Entries of B's list.");
    for (name, meaning) in axi_manager_ports() {
        unit = unit.port(name, meaning);
    }
    unit.throughput(&format!(
        "an entry per {} clocks, at the port's rate",
        config.beats_per_entry()
    ))
}

/// The emitted leaf reader.
pub fn emit_leaf_reader(config: &ListPassConfig) -> Result<EmittedDesign, LeafReaderEmitError> {
    let raw = with_leaf_reader(config, Raw).map_err(LeafReaderEmitError::Config)?;
    Ok(emit(&raw, &leaf_reader_unit(config))?)
}
