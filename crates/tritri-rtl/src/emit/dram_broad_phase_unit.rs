//! The broad-phase accelerator with its scene in DRAM
//! ([`crate::octree::dram_broad_phase`]): what it is built for, and the
//! dispatch from run-time widths to the type's constants.

use crate::octree::binning_unit::on_unit_stack;
use crate::octree::dram_binning_machine::DramBinningConfig;
use crate::octree::dram_binning_unit::WAITING_CAPACITY;
use crate::octree::dram_broad_phase::{DramBroadPhase, DramBroadPhaseBuild};
use crate::octree::owner_chain_filter::CHAIN_SLOT_BITS;
use crate::octree::value_bits;
use crate::system::SystemConfig;
use tritri_geom::widths::{cross_bits, difference_bits, orient3d_bits};

/// (grid bits, system width, port bits) the top is instantiated for: the
/// torus and sphere of the tests on a 24-bit grid, and the 16-bit grid the
/// controller routes at on the ECP5-85.
pub const DRAM_BROAD_PHASE_WIDTHS: [(usize, usize, usize); 2] = [(24, 24, 64), (16, 16, 64)];

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
}

impl DramBroadPhaseConfig {
    /// `tritri_dram_broad_phase_g<G>_w<W>_d<DW>_p<P>_t<depth>_i<triangles>_s<slots>[_local]`.
    pub fn unit_name(&self) -> String {
        format!(
            "tritri_dram_broad_phase_g{}_w{}_d{}_p{}_t{}_i{}_s{}{}",
            self.binning.pass.grid_bits,
            self.system.coordinate_bits,
            self.binning.pass.data_bits,
            self.system.pipelines,
            self.system.triangles_per_bank,
            self.triangles,
            self.slots,
            if self.local_frames { "_local" } else { "" }
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
        if self.triangles == 0 || self.triangles > 1 << crate::octree::list_packer::INDEX_BITS {
            return Err(format!(
                "triangles {}: 1 to {}",
                self.triangles,
                1u64 << crate::octree::list_packer::INDEX_BITS
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
    Ok(on_unit_stack(move || match config.binning.pass.grid_bits {
        24 => f.visit(DramBroadPhase::<
            24,
            V24,
            { 13 * V24 },
            216,
            64,
            8,
            24,
            { difference_bits(24) },
            { cross_bits(24) },
            { orient3d_bits(24) },
        >::new(build, system)),
        _ => f.visit(DramBroadPhase::<
            16,
            V16,
            { 13 * V16 },
            144,
            64,
            8,
            16,
            { difference_bits(16) },
            { cross_bits(16) },
            { orient3d_bits(16) },
        >::new(build, system)),
    }))
}
