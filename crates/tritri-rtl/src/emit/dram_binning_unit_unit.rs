//! The emitted binning controller over DRAM passes
//! ([`crate::broad_phase::dram_binning_unit`]): its name, ports and the widths it
//! is built for.

use super::axi_copy_unit::axi_manager_ports;
use super::list_pass_unit::LIST_PASS_GRID_WIDTHS;
use super::{emit, EmitError, EmittedDesign, UnitDescription};
use crate::broad_phase::dram_binning_machine::DramBinningConfig;
use crate::broad_phase::dram_binning_unit::{DramBinningUnit, WAITING_CAPACITY};
use crate::octree::value_bits;
use rust_hdl::prelude::*;

/// `tritri_dram_binning_g<G>_d<DW>_r<read burst>_o<outstanding>_t<depth>_p<pipelines>`,
/// with `_m<level>` when cells above a level are always split.
pub fn dram_binning_unit_name(config: &DramBinningConfig) -> String {
    let (pass, rule) = (config.pass, config.rule);
    let mut name = format!(
        "tritri_dram_binning_g{}_d{}_r{}_o{}_t{}_p{}",
        pass.grid_bits,
        pass.data_bits,
        pass.max_read_burst,
        pass.outstanding,
        1u64 << rule.log_depth,
        1u64 << rule.log_pipelines
    );
    if let Some(level) = rule.max_leaf_level {
        name.push_str(&format!("_m{level}"));
    }
    name
}

/// A controller that cannot be built, or could not be emitted.
#[derive(Debug, thiserror::Error)]
pub enum DramBinningEmitError {
    #[error("DRAM binning unit: {0}")]
    Config(String),
    #[error(transparent)]
    Emit(#[from] EmitError),
}

/// The unit for `config`, handed to `f` (the dispatch from run-time widths
/// to the type's constants, written once).
pub fn with_dram_binning<R>(
    config: &DramBinningConfig,
    f: impl DramBinningVisitor<Output = R>,
) -> Result<R, String> {
    let (pass, rule) = (config.pass, config.rule);
    pass.check()?;
    if !LIST_PASS_GRID_WIDTHS.contains(&pass.grid_bits) {
        return Err(format!(
            "a binning controller is built for {LIST_PASS_GRID_WIDTHS:?}-bit grids, not {}",
            pass.grid_bits
        ));
    }
    if rule.log_depth > 16 || rule.log_pipelines > 4 {
        return Err(format!(
            "the leaf cost is built for a depth of at most 2^16 and at most 16 pipelines, not 2^{} and 2^{}",
            rule.log_depth, rule.log_pipelines
        ));
    }
    if rule.max_leaf_level.is_some_and(|l| l >= 64) {
        return Err(format!(
            "a leaf level is 6 bits, not {:?}",
            rule.max_leaf_level
        ));
    }
    const V16: usize = value_bits(16);
    const V24: usize = value_bits(24);
    let (r, o) = (pass.max_read_burst, pass.outstanding);
    let (d, p, m, w) = (
        rule.log_depth,
        rule.log_pipelines,
        rule.max_leaf_level,
        config.waiting_capacity,
    );
    if !(1..=WAITING_CAPACITY).contains(&w) {
        return Err(format!(
            "a waiting memory of 1 to {WAITING_CAPACITY} leaves, not {w}"
        ));
    }
    Ok(match (pass.grid_bits, pass.data_bits) {
        (16, 64) => f.visit(DramBinningUnit::<16, V16, { 13 * V16 }, 144, 64, 8>::new(
            r, o, d, p, m, w,
        )),
        (16, 128) => f.visit(DramBinningUnit::<16, V16, { 13 * V16 }, 144, 128, 16>::new(
            r, o, d, p, m, w,
        )),
        (16, _) => f.visit(DramBinningUnit::<16, V16, { 13 * V16 }, 144, 256, 32>::new(
            r, o, d, p, m, w,
        )),
        (_, 64) => f.visit(DramBinningUnit::<24, V24, { 13 * V24 }, 216, 64, 8>::new(
            r, o, d, p, m, w,
        )),
        (_, 128) => f.visit(DramBinningUnit::<24, V24, { 13 * V24 }, 216, 128, 16>::new(
            r, o, d, p, m, w,
        )),
        _ => f.visit(DramBinningUnit::<24, V24, { 13 * V24 }, 216, 256, 32>::new(
            r, o, d, p, m, w,
        )),
    })
}

/// What is done with a controller of whichever widths.
pub trait DramBinningVisitor {
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
        unit: DramBinningUnit<G, V, N, T, DW, S>,
    ) -> Self::Output;
}

struct Raw;

impl DramBinningVisitor for Raw {
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
        mut unit: DramBinningUnit<G, V, N, T, DW, S>,
    ) -> crate::unit::RawDesign {
        unit.connect_all();
        crate::unit::RawDesign::of(&unit)
    }
}

/// The description of the unit for the emitter.
pub fn dram_binning_unit(config: &DramBinningConfig) -> UnitDescription {
    let (g, dw) = (config.pass.grid_bits, config.pass.data_bits);
    let mut unit = UnitDescription::new(
        &dram_binning_unit_name(config),
        &format!(
            "The octree broad phase's binning with every list in external memory: from the root cell and \
             its two lists (32-byte entries: {g}-bit vertices and an index), the octree walked depth first, \
             one list pass per cell split, the split rule decided from the children's counts, each leaf \
             sent on as it is decided."
        ),
    )
    .detail(&format!(
        "One AXI4 manager port of {dw}-bit beats (the list pass unit's). Children's lists go to the arena \
         [arena_start, arena_end); a cell whose children would not fit is made a leaf and counted in \
         arena_full. Up to {} leaves wait on chip under a tried split; one more keeps every tried split \
         on the stack (the waiting leaves go out, nothing is lost) and counts in waiting_commits.",
        config.waiting_capacity
    ))
    .detail(
        "Cycles: tritri_rtl::broad_phase::dram_binning_machine, clock-exact against the memory model \
         tritri_rtl::axi::memory_model.",
    )
    .port("clock", "Clock; every register updates on the rising edge.")
    .port("reset", "Synchronous reset, active high.")
    .port("start", "One clock high while idle or done: bin from the root on the inputs, read in that clock.")
    .port("corner_x", "The root cell's low corner, x (two's complement grid coordinate).")
    .port("corner_y", "The root cell's low corner, y.")
    .port("corner_z", "The root cell's low corner, z.")
    .port("level", "The root cell's level: its side is 2^level grid steps.")
    .port("list_base_0", "Byte address of A's root list, aligned to the beat.")
    .port("list_base_1", "Byte address of B's root list, aligned to the beat.")
    .port("list_count_0", "Entries of A's root list.")
    .port("list_count_1", "Entries of B's root list.")
    .port("arena_start", "First byte of the arena for the children's lists, aligned to a write burst.")
    .port("arena_end", "The byte after the arena.")
    .port("done", "High from the clock the walk ends until the next `start`.")
    .port("error", "A pass raised its error (the walk stopped).")
    .port("waiting_commits", "Times since `start` a leaf found the waiting memory full and every tried split on the stack was kept.")
    .port("leaf_valid", "A leaf is offered in this clock; it goes out in a clock with leaf_ready high and is held until then.")
    .port("leaf_ready", "The leaf offered is taken in this clock (tie high when nothing pushes back).")
    .port("pass_hold", "While high no pass starts: the narrow phase still reads lists a pass may overwrite (tie low when leaves are read at once).")
    .port("leaf_x", "The leaf's low corner, x.")
    .port("leaf_y", "The leaf's low corner, y.")
    .port("leaf_z", "The leaf's low corner, z.")
    .port("leaf_level", "The leaf's level.")
    .port("leaf_base_0", "Byte address of the leaf's A list.")
    .port("leaf_base_1", "Byte address of the leaf's B list.")
    .port("leaf_count_0", "Entries of the leaf's A list.")
    .port("leaf_count_1", "Entries of the leaf's B list.")
    .port("passes", "Cells passed since `start`.")
    .port("arena_full", "Cells made leaves since `start` because their children would not fit the arena.");
    for (name, meaning) in axi_manager_ports() {
        unit = unit.port(name, meaning);
    }
    unit.throughput("a leaf per clock at most; a pass per cell split")
}

/// The emitted controller.
pub fn emit_dram_binning(
    config: &DramBinningConfig,
) -> Result<EmittedDesign, DramBinningEmitError> {
    let raw = with_dram_binning(config, Raw).map_err(DramBinningEmitError::Config)?;
    Ok(emit(&raw, &dram_binning_unit(config))?)
}
