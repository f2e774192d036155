//! The broad-phase accelerator with its scene in DRAM
//! ([`crate::broad_phase::dram_broad_phase`]): what it is built for, and the
//! dispatch from run-time widths to the type's constants.

use super::axi_copy_unit::axi_manager_ports;
use super::dsp_mapping::MultiplierMapping;
use super::{emit_with, EmitOptions, EmittedDesign, UnitDescription};
use crate::broad_phase::binning_unit::on_unit_stack;
use crate::broad_phase::dram_binning_machine::DramBinningConfig;
use crate::broad_phase::dram_binning_unit::WAITING_CAPACITY;
use crate::broad_phase::dram_broad_phase::{
    DramBroadPhase, DramBroadPhaseBuild, SharedDramBroadPhase,
};
use crate::broad_phase::owner_chain_filter::CHAIN_SLOT_BITS;
use crate::octree::value_bits;
use crate::pipeline::RareCasePath;
use crate::system::SystemConfig;
use rust_hdl::prelude::*;
use tritri_geom::widths::{cross_bits, difference_bits, orient3d_bits};

/// (grid bits, system width, port bits) the top is instantiated for: the
/// torus and sphere of the tests on a 24-bit grid, and the 16-bit grid the
/// controller routes at on the ECP5-85, on 64-, 128- and 256-bit ports. A
/// 256-bit port takes an entry a clock, where the 64-bit port takes one
/// every four: the passes, which are most of a run, go up to four times as
/// fast on a memory that keeps up. A narrower port's lane shares its
/// setup's products over an entry's beats (`classify_lane::lane_latency`):
/// the 128-bit top is the one sized to a memory of about 32 bytes a clock
/// in all, as the ECP5-5G Versa's.
pub const DRAM_BROAD_PHASE_WIDTHS: [(usize, usize, usize); 4] =
    [(24, 24, 64), (16, 16, 64), (16, 16, 128), (16, 16, 256)];

/// What the top is built for.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct DramBroadPhaseConfig {
    /// The controller: its passes' port and the split rule (whose depth
    /// and pipelines are the system's).
    pub binning: DramBinningConfig,
    pub system: SystemConfig,
    /// The owner filter's head table (indices per object) and record
    /// tables (entries streamed per object over a run).
    pub triangles: usize,
    pub slots: usize,
    pub local_frames: bool,
    /// Where the pipelines decide their rare pairs (`_shared` in the name:
    /// on one shared unit each, the choice that fits the ECP5-85).
    pub rare_cases: RareCasePath,
}

impl DramBroadPhaseConfig {
    /// `tritri_dram_broad_phase_g<G>_w<W>_d<DW>_p<P>_t<depth>_i<triangles>_s<slots>[_local][_shared]`.
    pub fn unit_name(&self) -> String {
        format!(
            "tritri_dram_broad_phase_g{}_w{}_d{}_p{}_t{}_i{}_s{}{}{}",
            self.binning.pass.grid_bits,
            self.system.coordinate_bits,
            self.binning.pass.data_bits,
            self.system.pipelines,
            self.system.triangles_per_bank,
            self.triangles,
            self.slots,
            if self.local_frames { "_local" } else { "" },
            match self.rare_cases {
                RareCasePath::Parallel => "",
                RareCasePath::Shared => "_shared",
            }
        )
    }

    /// An error naming what the top is not built for, if anything.
    pub fn check(&self) -> Result<(), String> {
        let (pass, rule) = (self.binning.pass, self.binning.rule);
        pass.check()?;
        let widths = (pass.grid_bits, self.system.coordinate_bits, pass.data_bits);
        if !DRAM_BROAD_PHASE_WIDTHS.contains(&widths) {
            return Err(format!(
                "the DRAM broad-phase top is built for (grid, width, port bits) {DRAM_BROAD_PHASE_WIDTHS:?}, not {widths:?}"
            ));
        }
        if pass.data_bits != 64 && self.rare_cases != RareCasePath::Shared {
            return Err(format!(
                "the DRAM broad-phase top's {}-bit port is built with the rare cases shared (--rare-cases shared), the design for the ECP5-85",
                pass.data_bits
            ));
        }
        if 1usize << rule.log_depth != self.system.triangles_per_bank
            || 1usize << rule.log_pipelines != self.system.pipelines
        {
            return Err(format!(
                "the split rule's depth {} and {} pipelines are not the system's {} and {}",
                1u64 << rule.log_depth,
                1u64 << rule.log_pipelines,
                self.system.triangles_per_bank,
                self.system.pipelines
            ));
        }
        if !(1..=WAITING_CAPACITY).contains(&self.binning.waiting_capacity) {
            return Err(format!(
                "a waiting memory of 1 to {WAITING_CAPACITY} leaves, not {}",
                self.binning.waiting_capacity
            ));
        }
        if self.slots == 0 || self.slots > 1 << CHAIN_SLOT_BITS {
            return Err(format!(
                "slots {}: 1 to {}",
                self.slots,
                1u64 << CHAIN_SLOT_BITS
            ));
        }
        if self.triangles == 0 || self.triangles > 1 << crate::broad_phase::list_packer::INDEX_BITS
        {
            return Err(format!(
                "triangles {}: 1 to {}",
                self.triangles,
                1u64 << crate::broad_phase::list_packer::INDEX_BITS
            ));
        }
        Ok(())
    }

    fn build(&self) -> DramBroadPhaseBuild {
        DramBroadPhaseBuild {
            max_read_burst: self.binning.pass.max_read_burst,
            outstanding: self.binning.pass.outstanding,
            max_leaf_level: self.binning.rule.max_leaf_level,
            waiting_capacity: self.binning.waiting_capacity,
            triangles: self.triangles,
            slots: self.slots,
            local_frames: self.local_frames,
        }
    }
}

/// What is done with a top of whichever widths.
pub trait DramBroadPhaseVisitor {
    type Output;
    #[allow(clippy::too_many_arguments)]
    fn visit<
        const G: usize,
        const V: usize,
        const N: usize,
        const T: usize,
        const DW: usize,
        const S: usize,
        const W: usize,
        const D: usize,
        const C: usize,
        const O: usize,
    >(
        self,
        top: DramBroadPhase<G, V, N, T, DW, S, W, D, C, O>,
    ) -> Self::Output;
    /// The same for the top whose pipelines share a rare-case unit.
    #[allow(clippy::too_many_arguments)]
    fn visit_shared<
        const G: usize,
        const V: usize,
        const N: usize,
        const T: usize,
        const DW: usize,
        const S: usize,
        const W: usize,
        const D: usize,
        const C: usize,
        const O: usize,
    >(
        self,
        top: SharedDramBroadPhase<G, V, N, T, DW, S, W, D, C, O>,
    ) -> Self::Output;
}

/// The top for `config`, handed to `f` on a stack deep enough for it.
pub fn with_dram_broad_phase<R: Send>(
    config: &DramBroadPhaseConfig,
    f: impl DramBroadPhaseVisitor<Output = R> + Send,
) -> Result<R, String> {
    config.check()?;
    const V16: usize = value_bits(16);
    const V24: usize = value_bits(24);
    let (build, system) = (config.build(), config.system);
    // One arm per (grid, kind, port); the widths are DRAM_BROAD_PHASE_WIDTHS'.
    macro_rules! top {
        ($top:ident, $visit:ident, $g:literal, $v:ident, $dw:literal) => {
            f.$visit($top::<
                $g,
                $v,
                { 13 * $v },
                { 9 * $g },
                $dw,
                { $dw / 8 },
                $g,
                { difference_bits($g) },
                { cross_bits($g) },
                { orient3d_bits($g) },
            >::new(build, system))
        };
    }
    Ok(on_unit_stack(move || {
        let port = config.binning.pass.data_bits;
        match (config.binning.pass.grid_bits, config.rare_cases) {
            (24, RareCasePath::Parallel) => top!(DramBroadPhase, visit, 24, V24, 64),
            (24, RareCasePath::Shared) => top!(SharedDramBroadPhase, visit_shared, 24, V24, 64),
            (_, RareCasePath::Parallel) => top!(DramBroadPhase, visit, 16, V16, 64),
            (_, RareCasePath::Shared) if port == 256 => {
                top!(SharedDramBroadPhase, visit_shared, 16, V16, 256)
            }
            (_, RareCasePath::Shared) if port == 128 => {
                top!(SharedDramBroadPhase, visit_shared, 16, V16, 128)
            }
            (_, RareCasePath::Shared) => top!(SharedDramBroadPhase, visit_shared, 16, V16, 64),
        }
    }))
}

struct Raw;

impl DramBroadPhaseVisitor for Raw {
    type Output = crate::unit::RawDesign;
    fn visit<
        const G: usize,
        const V: usize,
        const N: usize,
        const T: usize,
        const DW: usize,
        const S: usize,
        const W: usize,
        const D: usize,
        const C: usize,
        const O: usize,
    >(
        self,
        mut top: DramBroadPhase<G, V, N, T, DW, S, W, D, C, O>,
    ) -> crate::unit::RawDesign {
        top.connect_all();
        crate::unit::RawDesign::of(&top)
    }
    fn visit_shared<
        const G: usize,
        const V: usize,
        const N: usize,
        const T: usize,
        const DW: usize,
        const S: usize,
        const W: usize,
        const D: usize,
        const C: usize,
        const O: usize,
    >(
        self,
        mut top: SharedDramBroadPhase<G, V, N, T, DW, S, W, D, C, O>,
    ) -> crate::unit::RawDesign {
        top.connect_all();
        crate::unit::RawDesign::of(&top)
    }
}

/// The description of the top for the emitter.
pub fn dram_broad_phase(config: &DramBroadPhaseConfig) -> UnitDescription {
    let (g, w) = (config.binning.pass.grid_bits, config.system.coordinate_bits);
    let dw = config.binning.pass.data_bits;
    let mut unit = UnitDescription::new(
        &config.unit_name(),
        &format!(
            "Collision detection with the scene in external memory: the octree broad phase's binning controller \
             walks the octree in passes over DRAM ({g}-bit grid), each leaf is read back into the collision \
             system ({w}-bit pipelines, {} per bank), and each intersecting pair comes out once.",
            config.system.triangles_per_bank
        ),
    )
    .detail(&format!(
        "One AXI4 manager port of {dw}-bit beats. The host writes each object's root list (32-byte entries: \
         the triangle's vertices on the grid and its index) into the memory, gives the root cell, the lists' \
         places and the arena for the children's lists, and pulses start. The read channel is the leaf reader's \
         while a leaf is held, the controller's otherwise; the writes are the controller's. A leaf with more \
         triangles of one object than a bank holds is read as tiles, every A tile with every B tile."
    ))
    .detail(&format!(
        "On chip: the controller's frame stack and {} waiting leaves, the system's two banks, the owner filter's \
         head table of {} indices per object and record tables of {} entries per object.",
        config.binning.waiting_capacity, config.triangles, config.slots
    ))
    .detail(match config.rare_cases {
        RareCasePath::Parallel => "The pipelines test their rare pairs (coplanar, or two degenerate triangles) on units of their own: no stall.",
        RareCasePath::Shared => "The pipelines test their rare pairs (coplanar, or two degenerate triangles) on one shared unit each: the system holds while a rare pair waits for it.",
    })
    .port("clock", "Clock; every register updates on the rising edge.")
    .port("reset", "Synchronous reset, active high.")
    .port("start", "One clock high while idle or done: a run from the inputs below, which are held until done.")
    .port("corner_x", "The root cell's low corner, x (two's complement grid coordinate).")
    .port("corner_y", "The root cell's low corner, y.")
    .port("corner_z", "The root cell's low corner, z.")
    .port("level", "The root cell's level: its side is 2^level grid steps.")
    .port("list_base_0", "Byte address of A's root list, aligned to the beat.")
    .port("list_base_1", "Byte address of B's root list, aligned to the beat.")
    .port("list_count_0", "Entries of A's root list.")
    .port("list_count_1", "Entries of B's root list.")
    .port("index_count_0", "A's triangle indices are below this (the owner filter clears that many heads after start).")
    .port("index_count_1", "B's triangle indices are below this.")
    .port("arena_start", "First byte of the arena for the children's lists, aligned to a write burst.")
    .port("arena_end", "The byte after the arena.")
    .port("out_valid", "A pair is offered, once per pair: every intersecting pair and every pair whose verdict has no certificate.")
    .port("out_ready", "The reader takes it.")
    .port("out_index_a", "The pair's A triangle: the index in its list entry.")
    .port("out_index_b", "The pair's B triangle.")
    .port("out_hit", "The pair intersects on the grid (touching counts).")
    .port("out_certain", "The verdict is provably the verdict before quantization; with 0 the host decides the pair again on its own coordinates.")
    .port("binned", "The walk is over: every leaf is decided.")
    .port("tested", "Every leaf is read and tested: the system's last verdict is in.")
    .port("done", "Every pair is decided and the last one taken.")
    .port("error", "Sticky: a pass or a leaf read saw a response that was not OKAY.")
    .port("overflow", "Sticky: the system's bank or the owner filter's tables were too small for this run.")
    .port("passes", "Cells passed since start.")
    .port("leaves", "Leaves taken since start.")
    .port("arena_full", "Cells made leaves since start because their children would not fit the arena.")
    .port("waiting_commits", "Times since start a leaf found the waiting memory full and every tried split was kept.")
    .port("pairs_tested", "Triangle pairs the pipelines have tested (32 bits).")
    .port("hits", "Intersecting pairs the pipelines found, once per tile holding them, before the owner filter (32 bits).");
    for (name, meaning) in axi_manager_ports() {
        unit = unit.port(name, meaning);
    }
    unit.throughput("per leaf tile of a and b triangles: its a + b entries read at the port's rate, and the system's a + ceil(a / P) * b reads, overlapped with the next tile's")
}

/// A top that cannot be built, or could not be emitted.
#[derive(Debug, thiserror::Error)]
pub enum DramBroadPhaseEmitError {
    #[error("DRAM broad-phase top: {0}")]
    Config(String),
    #[error(transparent)]
    Emit(#[from] super::EmitError),
}

/// The emitted top built for `config`, its multipliers mapped as
/// `multipliers` says.
pub fn emit_dram_broad_phase(
    config: &DramBroadPhaseConfig,
    multipliers: MultiplierMapping,
) -> Result<EmittedDesign, DramBroadPhaseEmitError> {
    let raw = with_dram_broad_phase(config, Raw).map_err(DramBroadPhaseEmitError::Config)?;
    let options = EmitOptions {
        multipliers,
        ..EmitOptions::default()
    };
    // The passes recurse over the text's expressions, deeper here than a
    // test thread's stack allows.
    Ok(on_unit_stack(|| {
        emit_with(&raw, &dram_broad_phase(config), options)
    })?)
}
