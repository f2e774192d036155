//! The emitted binning unit ([`crate::broad_phase::binning_unit`]): its name,
//! port meanings and timing.

use super::{emit, EmitError, EmittedDesign, UnitDescription};
use crate::broad_phase::binning_machine::PASS_DRAIN;
use crate::broad_phase::binning_unit::{on_unit_stack, BinningUnit, BinningUnitConfig};
use crate::broad_phase::leaf_cost::COUNT_BITS;
use crate::broad_phase::list_packer::INDEX_BITS;
use crate::octree::cell_classifier::AXES;
use crate::octree::value_bits;
use rust_hdl::prelude::*;

#[derive(Debug, thiserror::Error)]
pub enum BinningEmitError {
    #[error("binning unit: {0}")]
    Config(String),
    #[error(transparent)]
    Emit(#[from] EmitError),
}

/// rust-hdl's Verilog of the unit built for `config`.
pub fn raw_binning_unit_verilog(
    config: &BinningUnitConfig,
) -> Result<crate::unit::RawDesign, BinningEmitError> {
    config.check().map_err(BinningEmitError::Config)?;
    fn raw<const G: usize, const V: usize, const N: usize, const T: usize>(
        config: &BinningUnitConfig,
    ) -> crate::unit::RawDesign {
        let mut uut =
            BinningUnit::<G, V, N, T>::new(config.triangles, config.list_words, config.leaves)
                .with_system(config.log_depth, config.log_pipelines);
        uut.connect_all();
        crate::unit::RawDesign::of(&uut)
    }
    Ok(on_unit_stack(|| match config.grid_bits {
        16 => raw::<16, { value_bits(16) }, { AXES * value_bits(16) }, { 9 * 16 }>(config),
        24 => raw::<24, { value_bits(24) }, { AXES * value_bits(24) }, { 9 * 24 }>(config),
        _ => raw::<32, { value_bits(32) }, { AXES * value_bits(32) }, { 9 * 32 }>(config),
    }))
}

/// The description of the unit for the emitter.
pub fn binning_unit(config: &BinningUnitConfig) -> UnitDescription {
    let g = config.grid_bits;
    let depth = 1u64 << config.log_depth;
    let pipelines = 1u64 << config.log_pipelines;
    UnitDescription::new(
        &config.unit_name(),
        &format!(
            "Binning unit of the octree broad phase on a {g}-bit grid: each object's triangles streamed in once, the \
             common box subdivided depth first into leaves that hold triangles of both objects, the leaves streamed \
             out as a cell and two index lists."
        ),
    )
    .detail(
        "Each cell is decided by one pass over its two lists: two triangles per object and clock go through a setup \
         at the cell's low corner and a classifier step, whose children masks append each triangle's index to the \
         lists of the children it meets (eight list memories per object, two indices a word, append only). The \
         root's pass is the input stream itself. A cell is split when its children's leaf costs (the system's batch \
         cycles, in closed form) plus their passes undercut its own leaf cost; a split that does not pay off after \
         all is rolled back, its leaves dropped. The rule is the broad phase planner's \
         (tritri_geom::scene::octree), and the unit gives its leaves cell for cell and index for index.",
    )
    .detail(&format!(
        "Cycles: a pass over a cell of a and b entries takes ceil(max(a, b) / 2) + {PASS_DRAIN} clocks; the clock \
         count from the first triangle in to `binned` is the cycle-exact model's \
         (tritri_rtl::broad_phase::binning_machine::run_binning), which co-simulation holds the unit to."
    ))
    .detail(&format!(
        "Memories: {:.2} Mbit in all (four triangle memories of {} words x {} bits, sixteen list memories of {} words \
         x 36 bits, {} leaf descriptors, a frame stack of 64 levels). A scene that overflows one raises `overflow`; \
         `tritri sim` sizes them for a scene.",
        config.memory_bits() as f64 / 1e6,
        config.triangles,
        9 * g,
        config.list_words,
        config.leaves
    ))
    .parameter("G", &format!("{g}: bits of a grid coordinate (two's complement)"))
    .parameter("TRIANGLES", &format!("{}: triangles per object", config.triangles))
    .parameter("LIST_WORDS", &format!("{}: words per list memory (two indices a word)", config.list_words))
    .parameter("LEAVES", &format!("{}: leaf descriptors", config.leaves))
    .parameter("DEPTH", &format!("{depth}: the system's triangles per array, for the split rule's leaf cost"))
    .parameter("PIPELINES", &format!("{pipelines}: the system's pipelines, for the split rule's leaf cost"))
    .port("clock", "Clock; every register updates on the rising edge.")
    .port("reset", "Synchronous reset, active high: back to Idle (the memories keep their words).")
    .port("start", "One clock high while idle: a run begins; the triangles follow. root_* and max_leaf_* are held from here to done.")
    .port("root_x", "Root cell's low corner, x (grid units, two's complement).")
    .port("root_y", "Root cell's low corner, y.")
    .port("root_z", "Root cell's low corner, z.")
    .port("root_level", "Root cell's level: its edge is 2^level grid units.")
    .port("max_leaf_level", "With max_leaf_enable: cells above this level are always split (local frames of at most 2^level).")
    .port("max_leaf_enable", "Enables max_leaf_level.")
    .port("in_valid", "A triangle is offered (both objects' triangles, in any order).")
    .port("in_ready", "The unit takes it (transfer = in_valid & in_ready): high while loading.")
    .port("in_last", "The offered triangle is the run's last.")
    .port("in_object", "The offered triangle's object: 0 A, 1 B. Its index is its position in its object's stream.")
    .port("in_vertices", &format!("The triangle's vertices, x0 y0 z0 x1 ... z2 from bit 0 up, {g} bits each, grid coordinates (the unit takes each cell's corner off itself)."))
    .port("out_valid", "A leaf word is offered: a header, then the leaf's A indices, then its B indices.")
    .port("out_ready", "The reader takes it (back-pressure: the stream holds while low).")
    .port("out_header", "The word is a leaf's header: out_x/y/z, out_level and the two counts are valid. A leaf with more triangles of one object than the system's depth comes as tiles (every A tile with every B tile), each under a header of its own.")
    .port("out_object", "An index word's object: 0 A, 1 B.")
    .port("out_index", &format!("An index word's triangle: its position in its object's input stream ({INDEX_BITS} bits)."))
    .port("out_vertices", "An entry: the triangle's vertices as streamed in (in_vertices' layout), from the object's first triangle memory.")
    .port("out_x", "Header: the leaf cell's low corner, x.")
    .port("out_y", "Header: low corner, y.")
    .port("out_z", "Header: low corner, z.")
    .port("out_level", "Header: the leaf cell's level.")
    .port("out_count_a", &format!("Header: the A indices that follow ({COUNT_BITS} bits)."))
    .port("out_count_b", "Header: the B indices that follow them.")
    .port("out_leaf_number", "Header: the leaf's number in stream order, from 0 (the tiles of one leaf share it).")
    .port("binned", "Binning is over: the leaves are streaming out or are out.")
    .port("done", "Every leaf is out; the unit waits for reset.")
    .port("overflow", "A memory was too small for this run (sticky until the next start): a triangle, list word or leaf past its memory's end was dropped; no leaf is streamed and done follows binned at once.")
    .throughput("one leaf word per clock out; two triangles per object and clock through a cell's pass.")
}

/// The emitted unit built for `config`.
pub fn emit_binning_unit(config: &BinningUnitConfig) -> Result<EmittedDesign, BinningEmitError> {
    Ok(emit(
        &raw_binning_unit_verilog(config)?,
        &binning_unit(config),
    )?)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_grid_without_a_unit_is_an_error_naming_it() {
        let config = BinningUnitConfig {
            grid_bits: 20,
            triangles: 16,
            list_words: 16,
            leaves: 16,
            log_depth: 4,
            log_pipelines: 1,
        };
        let error = raw_binning_unit_verilog(&config).unwrap_err().to_string();
        assert!(error.contains("not 20"), "{error}");
        let config = BinningUnitConfig {
            grid_bits: 16,
            triangles: 1 << 19,
            ..config
        };
        let error = raw_binning_unit_verilog(&config).unwrap_err().to_string();
        assert!(error.contains("triangles per object 524288"), "{error}");
    }
}
