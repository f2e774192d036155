//! The emitted broad-phase top ([`crate::broad_phase::broad_phase_system`]):
//! its name, port meanings and timing.

use super::binning_unit_unit::BinningEmitError;
use super::dsp_mapping::MultiplierMapping;
use super::{emit_with, EmitOptions, EmittedDesign, UnitDescription};
use crate::broad_phase::binning_unit::{on_unit_stack, BinningUnitConfig};
use crate::broad_phase::broad_phase_system::{
    BroadPhaseSystem, BROAD_PHASE_WIDTHS, FIRST_HEADER_DELAY,
};
use crate::broad_phase::owner_chain_filter::CHAIN_SLOT_BITS;
use crate::octree::cell_classifier::AXES;
use crate::octree::value_bits;
use crate::system::SystemConfig;
use rust_hdl::prelude::*;
use tritri_geom::widths::{cross_bits, difference_bits, orient3d_bits};

/// The binning unit's grid in the top.
pub const BROAD_PHASE_GRID_BITS: usize = 24;

/// What the top is built for: the binning unit, the system it feeds, and
/// whether leaves are sent in frames of their own.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct BroadPhaseConfig {
    pub unit: BinningUnitConfig,
    pub system: SystemConfig,
    /// The owner filter's table depth: entries streamed per object
    /// (`broad_phase_system::stream_slots`).
    pub slots: usize,
    pub local_frames: bool,
}

impl BroadPhaseConfig {
    /// `tritri_broad_phase_g<G>_w<W>_p<P>_d<depth>_t<triangles>_s<slots>[_local]`.
    pub fn unit_name(&self) -> String {
        format!(
            "tritri_broad_phase_g{}_w{}_p{}_d{}_t{}_s{}{}",
            self.unit.grid_bits,
            self.system.coordinate_bits,
            self.system.pipelines,
            self.system.triangles_per_bank,
            self.unit.triangles,
            self.slots,
            if self.local_frames { "_local" } else { "" }
        )
    }

    /// An error naming what the top is not built for, if anything.
    pub fn check(&self) -> Result<(), String> {
        self.unit.check()?;
        if self.slots == 0 || self.slots > 1 << CHAIN_SLOT_BITS {
            return Err(format!(
                "slots {}: 1 to {} ({CHAIN_SLOT_BITS} address bits)",
                self.slots,
                1u64 << CHAIN_SLOT_BITS
            ));
        }
        let widths = (self.unit.grid_bits, self.system.coordinate_bits);
        if !BROAD_PHASE_WIDTHS.contains(&widths) {
            return Err(format!("the broad-phase top is built for (grid, width) {BROAD_PHASE_WIDTHS:?}, not {widths:?}"));
        }
        if 1usize << self.unit.log_depth != self.system.triangles_per_bank
            || 1usize << self.unit.log_pipelines != self.system.pipelines
        {
            return Err(format!(
                "the binning unit's split rule (depth {}, {} pipelines) is not the system's (depth {}, {} pipelines)",
                1u64 << self.unit.log_depth,
                1u64 << self.unit.log_pipelines,
                self.system.triangles_per_bank,
                self.system.pipelines
            ));
        }
        Ok(())
    }
}

/// rust-hdl's Verilog of the top built for `config`.
pub fn raw_broad_phase_verilog(
    config: &BroadPhaseConfig,
) -> Result<crate::unit::RawDesign, BinningEmitError> {
    config.check().map_err(BinningEmitError::Config)?;
    fn raw<
        const G: usize,
        const V: usize,
        const N: usize,
        const T: usize,
        const W: usize,
        const D: usize,
        const C: usize,
        const O: usize,
    >(
        config: &BroadPhaseConfig,
    ) -> crate::unit::RawDesign {
        let unit = &config.unit;
        let mut uut = BroadPhaseSystem::<G, V, N, T, W, D, C, O>::new(
            unit.triangles,
            unit.list_words,
            unit.leaves,
            config.slots,
            config.system,
            config.local_frames,
        );
        uut.connect_all();
        crate::unit::RawDesign::of(&uut)
    }
    const V24: usize = value_bits(24);
    Ok(on_unit_stack(|| match config.system.coordinate_bits {
        24 => raw::<
            24,
            V24,
            { AXES * V24 },
            { 9 * 24 },
            24,
            { difference_bits(24) },
            { cross_bits(24) },
            { orient3d_bits(24) },
        >(config),
        _ => raw::<
            24,
            V24,
            { AXES * V24 },
            { 9 * 24 },
            16,
            { difference_bits(16) },
            { cross_bits(16) },
            { orient3d_bits(16) },
        >(config),
    }))
}

/// The description of the top for the emitter.
pub fn broad_phase_system(config: &BroadPhaseConfig) -> UnitDescription {
    let g = config.unit.grid_bits;
    let w = config.system.coordinate_bits;
    UnitDescription::new(
        &config.unit_name(),
        &format!(
            "Collision detection from triangles to pairs: the octree broad phase's binning unit on a {g}-bit grid, its \
             leaves fed straight into the collision system ({w}-bit pipelines), each intersecting pair out once."
        ),
    )
    .detail(
        "The host streams each object's triangles once. The binning unit subdivides the common box into leaves \
         holding both objects and streams each leaf as a header and its A and B entries with their vertices; the \
         leaf batcher turns a leaf into one batch of the system (its triangles, then an end-of-batch word), taking \
         the cell's centre off every coordinate when leaves have frames of their own. The system tests every pair \
         of a leaf while the next is written into its other bank. The owner filter lets each hit through only from \
         the first leaf that holds both triangles, from tables written as the triangles load and the leaves stream.",
    )
    .detail(&format!(
        "Cycles from the first triangle in to done: the binning unit's (its clock-exact model), {FIRST_HEADER_DELAY} \
         to the first header, then the system's bank recurrence fed one word per clock with one idle clock per leaf \
         (tritri_rtl::broad_phase::broad_phase_system::broad_phase_cycles, which co-simulation holds the system's part \
         to); the owner filter then takes 2 clocks per hit, plus one per step back through the triangles' earlier \
         leaves, plus one per pair out."
    ))
    .detail(&format!(
        "Memories: the binning unit's {:.2} Mbit and the system's two banks of {} triangles per object. A leaf with \
         more triangles of one object than that comes as tiles, each a batch.",
        config.unit.memory_bits() as f64 / 1e6,
        config.system.triangles_per_bank
    ))
    .port("clock", "Clock; every register updates on the rising edge.")
    .port("reset", "Synchronous reset, active high.")
    .port("start", "One clock high while idle: a run begins; root_* and max_leaf_* are held from here to done.")
    .port("root_x", "Root cell's low corner, x (grid units, two's complement).")
    .port("root_y", "Root cell's low corner, y.")
    .port("root_z", "Root cell's low corner, z.")
    .port("root_level", "Root cell's level: its side is 2^level grid units.")
    .port("max_leaf_level", "With max_leaf_enable: cells above this level are always split (local frames).")
    .port("max_leaf_enable", "Enables max_leaf_level.")
    .port("in_valid", "A triangle is offered.")
    .port("in_ready", "The top takes it (transfer = in_valid & in_ready).")
    .port("in_last", "The offered triangle is the run's last.")
    .port("in_object", "The offered triangle's object: 0 A, 1 B. Its index is its position in its object's stream.")
    .port("in_vertices", &format!("The triangle's vertices, x0 y0 z0 x1 ... z2 from bit 0 up, {g} bits each, grid coordinates."))
    .port("out_valid", "A pair is offered, once per pair: every intersecting pair and every pair whose verdict has no certificate.")
    .port("out_ready", "The reader takes it (back-pressure: the owner filter holds, the result FIFO fills, then the read side holds).")
    .port("out_index_a", "The pair's A triangle: its index in A's stream.")
    .port("out_index_b", "The pair's B triangle: its index in B's stream.")
    .port("out_hit", "The pair intersects on the grid (touching counts).")
    .port("out_certain", "The verdict is provably the verdict before quantization; with 0 the host decides the pair again on its own coordinates.")
    .port("binned", "Binning is over: the leaves are streaming into the system.")
    .port("done", "Every leaf is tested, every hit decided and the last pair taken.")
    .port("overflow", "Sticky: a memory of the binning unit, or the system's memory depth, was too small for this run.")
    .port("pairs_tested", "Triangle pairs the pipelines have tested (32 bits).")
    .port("hits", "Intersecting pairs the pipelines found, each once per leaf holding it, before the owner filter (32 bits).")
    .throughput("one triangle per clock in; per leaf of a and b triangles, a + b + 2 clocks of the leaf stream and the system's a + ceil(a / P) * b reads, overlapped.")
}

/// The emitted top built for `config`.
pub fn emit_broad_phase_system(
    config: &BroadPhaseConfig,
) -> Result<EmittedDesign, BinningEmitError> {
    emit_broad_phase_system_with(config, MultiplierMapping::Inferred)
}

/// [`emit_broad_phase_system`] with the system's multipliers mapped as
/// `multipliers` says (`tritri gen --broad-phase --dsp`).
pub fn emit_broad_phase_system_with(
    config: &BroadPhaseConfig,
    multipliers: MultiplierMapping,
) -> Result<EmittedDesign, BinningEmitError> {
    let raw = raw_broad_phase_verilog(config)?;
    let options = EmitOptions {
        multipliers,
        ..EmitOptions::default()
    };
    // The passes recurse over the text's expressions, deeper here than a
    // test thread's stack allows.
    Ok(on_unit_stack(|| {
        emit_with(&raw, &broad_phase_system(config), options)
    })?)
}
