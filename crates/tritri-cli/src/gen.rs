//! `tritri gen [--width W]... [--out DIR] [--synth] [--system [--pipelines P] [--depth N] | --classifier | --setup | --binning-unit [--triangles N] [--list-words N] [--leaves N] [--pipelines P] [--depth N] | --broad-phase [the same, --slots N] | --owner-filter [--slots N] | --plane-traversal | --set-operation | --octant-clipper | --voxel-fill]`
//!
//! Writes the synthesizable Verilog of the triangle pipeline (or, with
//! `--system`, of the whole system, see below) for each
//! coordinate width W (default 24, the thesis's): one module per file, named
//! `tritri_pipeline_w<W>*.v`, with `filelist.f`, a FuseSoC core, Yosys
//! scripts and a README with the port table, latency and throughput.
//!
//! Output directory: with one width, `--out DIR` (default `rtl-out/w<W>`,
//! relative to the current directory); with several, `<DIR>/w<W>` for each
//! (default `rtl-out/w<W>`). A directory is updated in place: files of an
//! earlier emission that this one no longer produces are removed.
//!
//! `--synth` then runs Yosys (generic `synth` and `synth_xilinx`) in each
//! directory and prints a resource table (generic cells; LUT, FF, DSP48E1,
//! CARRY4, SRL for Xilinx 7-series), also written to `resources.md` next to
//! the Verilog, with Yosys' reports `stat_generic.txt` and `stat_xilinx.txt`.
//! `--synth xilinx` or `--synth generic` runs one of the two (the generic
//! flow maps the wide multipliers to gates and takes minutes). `--synth
//! ecp5` places and routes instead (`tritri_rtl::route`: Yosys and
//! nextpnr-ecp5 from PyPI, out of context on an ECP5-85 at speed grade 6)
//! and prints the post-route Fmax, the critical path and the resources,
//! also written to `route_ecp5.md` (a whole pipeline takes tens of minutes
//! to hours; a unit on its own, seconds to minutes).
//!
//! `--synth-top MODULE` places and routes one module of the emitted design
//! instead of its top, for the critical path of one unit in minutes;
//! `--seed N` sets nextpnr's placement seed (default 1); `--seed 1,2,3`
//! routes the one netlist with each seed, side by side, and names the
//! best (`route_ecp5_seed<N>.log` and `.json` for each).
//!
//! `--dsp ecp5` (the default with `--synth ecp5`) writes each multiplier as
//! Lattice MULT18X18D blocks with their input, pipeline and output
//! registers, which Yosys does not infer, plus a simulation model of the
//! primitive (`ecp5_mult18x18d_model.v`, skipped by synthesis); `--dsp
//! inferred` (the default otherwise) leaves `a * b` to the flow.
//!
//! `--system` writes the whole bounding-volume-aware system instead (two-bank
//! triangle memories, address generator, `--pipelines P` pipelines, result
//! FIFO; `--depth N` triangles per array per bank), top
//! `tritri_system_w<W>_p<P>_d<N>`, by default into `rtl-out/<top>`.
//!
//! `--classifier` writes the octree engine's triangle classifier step (the
//! broad phase's binning unit, `docs/broad-phase.md`) for a `--width`-bit
//! grid (16, 24 or 32), top `tritri_cell_classifier_g<G>`, by default into
//! `rtl-out/<top>`. `--setup` writes the setup that feeds it (one triangle
//! per clock to its thirteen test functions at the root cell), top
//! `tritri_triangle_setup_g<G>`. `--binning-unit` writes the broad phase's
//! binning unit for a `--width`-bit grid (each object's triangles in once,
//! the leaves out; memories sized by `--triangles`, `--list-words` and
//! `--leaves`, the split rule by the system's `--depth` and `--pipelines`),
//! top `tritri_binning_g<G>_t<N>_w<N>_l<N>_d<depth>_p<P>`. `--broad-phase`
//! writes the broad-phase top: that binning unit on a 24-bit grid feeding
//! the collision system of `--width` bits (24, or 16 with each leaf in a
//! frame of its own), `--depth` and `--pipelines`, triangles in and each
//! leaf's pairs out, top `tritri_broad_phase_g24_w<W>_p<P>_d<depth>_t<N>[_local]`.
//! `--owner-filter` writes the filter that
//! reports each pair of the octree broad phase once (`--slots N` words per
//! object's slot table, default 65536), top `tritri_owner_filter_s<N>`.
//! `--owner-chain-filter` writes the broad-phase tops' own filter alone
//! (tables written as the entries stream: `--triangles N` heads and
//! `--slots N` records per object), top
//! `tritri_owner_chain_filter_t<N>_s<N>`, so that its clock is measured in
//! a route of minutes.
//! `--plane-traversal` writes the octree engine's plane classification
//! (grids up to 1024^3, one octant per clock), top `tritri_plane_traversal`;
//! `--set-operation` its set-operation unit (two voxel models, a 64-voxel
//! word per clock), top `tritri_set_operation`; `--octant-clipper` its
//! clipping unit (one octant per clock against a box), top
//! `tritri_octant_clipper`; `--voxel-fill` its memory side (cells'
//! children written into the voxel memory a word per clock), top
//! `tritri_voxel_fill`; `--triangle-voxelizer` its surface voxelization
//! (triangles in, the voxels each meets out), top
//! `tritri_triangle_voxelizer`; `--octree-builder` its voxel → octree
//! conversion (a 4x4x4 brick in per clock, the canonical tree's nodes
//! out), top `tritri_octree_builder`. `--patch-tessellator [--width 16|24] [--steps 1..4]`
//! writes the Bezier system's patch tessellation unit (forward
//! differences, one vertex per clock), top
//! `tritri_patch_tessellator_w<W>_k<K>` (with `--assemble`, its triangles
//! assembled, two a clock in the collision system's format, top
//! `tritri_patch_triangles_w<W>_k<K>`); `--cone-unit [--width 16|24]` its
//! cone-of-normals test (one patch and eye a clock), top
//! `tritri_cone_unit_w<W>`. `--shared-rare-cases [--width 8|16|24]` writes
//! the pipeline's rare cases on one shared path (the coplanar and
//! degenerate-pair tests on three orient2d lanes), top
//! `tritri_shared_rare_cases_w<W>`; `--rare-cases shared` the pipeline
//! with that unit inside (it holds, output `hold`, while a rare pair
//! waits), top `tritri_pipeline_shared_w<W>`. `--axi-copy [--width DW]`
//! writes the AXI4 port's copy unit, top `tritri_axi_copy_d<DW>_…`;
//! `--list-pass [--width 16|24] [--data-bits 64|128|256]` the broad
//! phase's pass of one cell with its lists in external memory, top
//! `tritri_list_pass_g<G>_d<DW>_r16_o4`; `--dram-binning [--width 16|24]
//! [--data-bits 64|128|256] [--pipelines P] [--depth D]` the binning over
//! such passes, the pass unit inside, top
//! `tritri_dram_binning_g<G>_d<DW>_r16_o4_t<D>_p<P>`;
//! `--dram-broad-phase [--width 16|24] [--pipelines P] [--depth D]
//! [--rare-cases shared] [--triangles N] [--slots N]` the accelerator with
//! its scene in external memory (that binning, the leaf reader, the system
//! and the owner filter on one port), top
//! `tritri_dram_broad_phase_g<G>_w<W>_d64_p<P>_t<D>_i<N>_s<N>[_shared]`.
//!
//! `--for-scene A B [--pose-b ...] [--max-uncertain RATE] [--device NAME]`
//! sizes the system for a scene and an error budget instead: it runs the
//! scene in the bit-exact model at every width, takes the cheapest width
//! (multipliers per pipeline on the device) that sends at most RATE of the
//! pairs back to the host, P and the memory depth from the cycle model
//! within the device's measured budget, and writes the system with the
//! reasons in its README (`gen/for_scene.rs`). A budget that nothing on the
//! device meets is an error (status 2) naming the best there is.
//!
//! The designs and the options each takes are one table (`gen/design.rs`):
//! an option that does not apply to the design chosen is refused, naming
//! it and what the design does take, before anything is written.
//!
//! Exit status: 0 done; 1 a tool failed; 2 a width without a pipeline (the
//! message names it and lists the supported widths) or bad usage.

mod design;
mod for_scene;

use crate::stdout::out;
use design::{Design, DesignOption};

use crate::scene_input::SceneArgs;
use anyhow::Context;
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use tritri_geom::scene::load::Pose;
use tritri_rtl::broad_phase::binning_machine::BinningParams;
use tritri_rtl::broad_phase::binning_unit::{BinningUnitConfig, LEAF_ADDRESS_BITS};
use tritri_rtl::broad_phase::dram_binning_machine::DramBinningConfig;
use tritri_rtl::broad_phase::dram_binning_unit::WAITING_CAPACITY;
use tritri_rtl::broad_phase::list_packer::{INDEX_BITS, LIST_ADDRESS_BITS};
use tritri_rtl::broad_phase::list_pass_machine::ListPassConfig;
use tritri_rtl::emit::axi_copy_unit::{emit_axi_copy, AxiCopyConfig};
use tritri_rtl::emit::binning_unit_unit::emit_binning_unit;
use tritri_rtl::emit::broad_phase_system_unit::{
    emit_broad_phase_system_with, BroadPhaseConfig, BROAD_PHASE_GRID_BITS,
};
use tritri_rtl::emit::cell_classifier_unit::{
    cell_classifier_unit_name, emit_cell_classifier, CLASSIFIER_GRID_WIDTHS,
};
use tritri_rtl::emit::cone_unit_unit::{cone_unit_name, emit_cone_unit, CONE_UNIT_WIDTHS};
use tritri_rtl::emit::dram_binning_unit_unit::{dram_binning_unit_name, emit_dram_binning};
use tritri_rtl::emit::dram_broad_phase_unit::{emit_dram_broad_phase, DramBroadPhaseConfig};
use tritri_rtl::emit::dsp_mapping::{MultiplierMapping, MAX_ECP5_DSP_WIDTH};
use tritri_rtl::emit::list_pass_unit::{
    emit_list_pass, list_pass_unit_name, LIST_PASS_GRID_WIDTHS,
};
use tritri_rtl::emit::memory_mapping::{map_delay_lines, DelayLineMapping};
use tritri_rtl::emit::octree_builder_unit::{emit_octree_builder, OCTREE_BUILDER_NAME};
use tritri_rtl::emit::owner_chain_filter_unit::{
    emit_owner_chain_filter, owner_chain_filter_unit_name,
};
use tritri_rtl::emit::owner_filter_unit::{emit_owner_filter, owner_filter_unit_name, MAX_SLOTS};
use tritri_rtl::emit::patch_tessellator_unit::{
    emit_patch_tessellator, emit_patch_triangles, patch_tessellator_unit_name,
    patch_triangles_unit_name, TESSELLATOR_CONFIGURATIONS,
};
use tritri_rtl::emit::plane_traversal_unit::{emit_plane_traversal, PLANE_TRAVERSAL_NAME};
use tritri_rtl::emit::shared_rare_cases_unit::{
    emit_shared_rare_cases, shared_rare_cases_name, SHARED_RARE_CASES_WIDTHS,
};
use tritri_rtl::emit::triangle_setup_unit::{emit_triangle_setup, triangle_setup_unit_name};
use tritri_rtl::emit::triangle_voxelizer_unit::{emit_triangle_voxelizer, TRIANGLE_VOXELIZER_NAME};
use tritri_rtl::emit::voxel_units::{
    emit_octant_clipper, emit_set_operation, emit_voxel_fill, OCTANT_CLIPPER_NAME,
    SET_OPERATION_NAME, VOXEL_FILL_NAME,
};
use tritri_rtl::emit::EmittedDesign;
use tritri_rtl::measured::{device, DEVICES};
use tritri_rtl::pipeline::pipeline_for_width::check_width;
use tritri_rtl::pipeline::pipeline_unit::{emit_pipeline_for, pipeline_unit_name_for};
use tritri_rtl::pipeline::RareCasePath;
use tritri_rtl::route::{
    best_route, route_ecp5, route_ecp5_seeds, route_table, routes_at_once, Ecp5Options, Placer,
    RouteError, RouteFiles, RouteReport, Router,
};
use tritri_rtl::synth::{resource_table, synthesize, ResourceRow, Target};
use tritri_rtl::system::system_for_width::PipelineKind;
use tritri_rtl::system::system_unit::{emit_system_with, system_unit_name};
use tritri_rtl::system::{
    SystemConfig, DEFAULT_TRIANGLES_PER_BANK, MAX_PIPELINES, MAX_TRIANGLES_PER_BANK,
};

#[derive(clap::Args)]
pub struct Args {
    /// Coordinate width in bits (the grid's for the octree units); repeat
    /// or separate with commas for several [default: 24].
    #[arg(long, value_delimiter = ',', value_parser = crate::input::whole::<usize>(tritri_geom::widths::MIN_WIDTH as usize..=tritri_geom::widths::MAX_WIDTH as usize))]
    width: Option<Vec<usize>>,
    /// Output directory (one width) or parent directory (several widths).
    #[arg(long)]
    out: Option<PathBuf>,
    /// Run Yosys and print a resource table: `all` (default when given
    /// without a value: `xilinx` and `generic`), `xilinx`, `generic`, or
    /// `ecp5`: Yosys and nextpnr-ecp5 place and route (out of context,
    /// LFE5U-85F speed 6, aiming at 150 MHz) and report the post-route
    /// Fmax, the critical path, the register inputs short of 150 MHz and
    /// LUT4 / FF / MULT18X18D / EBR.
    #[arg(long, num_args = 0..=1, default_missing_value = "all", value_parser = ["all", "xilinx", "generic", "ecp5"])]
    synth: Option<String>,
    /// How the multipliers reach the DSP blocks: `inferred` (`a * b`
    /// between registers, for any flow) or `ecp5` (Lattice MULT18X18D
    /// instances with their input, pipeline and output registers, and a
    /// simulation model of the primitive; widths up to 17; with --system,
    /// the triangle memories also as DP16KD instances with their output
    /// registers, and a model of that primitive) [default: ecp5 with
    /// --synth ecp5, inferred otherwise].
    #[arg(long, value_parser = MultiplierMapping::NAMES)]
    dsp: Option<String>,
    /// Where the delay lines keep their stages: `registers` (one per stage
    /// and bit; Xilinx maps long ones onto SRL LUTs) or `memory` (lines of
    /// six stages or more in a memory of at least N - 1 words with two
    /// counters, which Yosys puts in ECP5's distributed RAM: a quarter
    /// fewer flip-flops at W = 16, and nextpnr routes it in a quarter of
    /// the time; rtl-out/README.md) [default: memory with --synth ecp5,
    /// registers otherwise].
    #[arg(long, value_parser = DelayLineMapping::NAMES)]
    delay_lines: Option<String>,
    /// With --synth ecp5: place and route this module of the emitted
    /// design on its own instead of the top (a unit of the pipeline, such
    /// as tritri_pipeline_w16_orient3d_operands: minutes where the whole pipeline
    /// takes hours).
    #[arg(long, value_name = "MODULE")]
    synth_top: Option<String>,
    /// With --synth ecp5: nextpnr's placement seed [default: 1]. The same
    /// netlist routes some per cent faster or slower from seed to seed
    /// (13 % and more on the W = 16 pipeline); the table names the seed of
    /// each route. Several (`--seed 1,2,3`) route the one netlist with
    /// each, side by side on the machine's cores, into
    /// route_ecp5_seed<N>.log and .json, and the table has a row for each
    /// and names the best: a seed sweep, the usual last step of closing
    /// timing.
    #[arg(long, value_name = "N", value_delimiter = ',', value_parser = crate::input::whole::<u64>(0..=u64::MAX))]
    seed: Vec<u64>,
    /// With --synth ecp5: nextpnr's router [default: router1 for the
    /// emitted top, router2 with timing-driven rip-up for a --synth-top
    /// module inside it]. router1 converges on whole designs where router2 does not
    /// (the W = 16 pipeline with --rare-cases shared).
    #[arg(long, value_parser = Router::NAMES)]
    router: Option<String>,
    /// With --synth ecp5: nextpnr's placer [default: heap; static for the
    /// --dram-broad-phase top, which router1 routed only from its
    /// placement]. `static`, the electrostatic placer, also left a fifth as
    /// many paths short of 150 MHz on the whole W = 16 pipeline with
    /// --rare-cases shared.
    #[arg(long, value_parser = Placer::NAMES)]
    placer: Option<String>,
    /// With --synth ecp5: the heap placer's weight of timing against wire
    /// length [default: 30 for the emitted top, 10 (nextpnr's) for a
    /// --synth-top module inside it]. 30 left a ninth as many paths short of 150 MHz
    /// on the whole W = 16 pipeline with --rare-cases shared (router1).
    #[arg(long, value_name = "N", value_parser = crate::input::whole::<u32>(1..=1000))]
    timing_weight: Option<u32>,
    /// Emit the whole system (memories, address generator, pipelines,
    /// result FIFO) instead of the pipeline alone.
    #[arg(long)]
    system: bool,
    /// Emit the octree engine's triangle classifier step instead (the
    /// broad phase's binning unit); --width is then the grid's width (16,
    /// 24 or 32).
    #[arg(long)]
    classifier: bool,
    /// Emit the classifier's setup instead (a triangle's test functions at
    /// the root cell); --width is the grid's width (16, 24 or 32).
    #[arg(long)]
    setup: bool,
    /// Emit the octree broad phase's owner filter instead (each
    /// intersecting pair reported once, from its first leaf); --width does
    /// not apply.
    #[arg(long)]
    owner_filter: bool,
    /// Emit the broad-phase tops' owner filter alone instead (chain form:
    /// tables written as the entries stream, --triangles heads and --slots
    /// records per object); --width does not apply.
    #[arg(long)]
    owner_chain_filter: bool,
    /// Emit the octree engine's plane classification instead (the grid
    /// against a plane, one octant per clock); --width does not apply.
    #[arg(long)]
    plane_traversal: bool,
    /// Emit the octree engine's set-operation unit instead (union,
    /// intersection, difference of two voxel models, a word per clock).
    #[arg(long)]
    set_operation: bool,
    /// Emit the octree engine's clipping unit instead (one octant per clock
    /// against a box).
    #[arg(long)]
    octant_clipper: bool,
    /// Emit the Bezier system's patch tessellation unit instead (a patch
    /// on the grid, forward differences, one vertex per clock); --width is
    /// the coordinates' (16 or 24), --steps the log2 of the steps a side.
    #[arg(long)]
    patch_tessellator: bool,
    /// Emit the Bezier system's cone-of-normals unit instead (one patch and
    /// eye a clock: culled, front-facing or a possible silhouette); --width
    /// is the control points' (16 or 24).
    #[arg(long)]
    cone_unit: bool,
    /// Emit the pipeline's rare cases on one shared path instead: the
    /// coplanar and degenerate-pair tests on three orient2d lanes (six
    /// multipliers), a pair every 4 or 6 clocks; --width 8, 16 or 24.
    #[arg(long)]
    shared_rare_cases: bool,
    /// Emit the AXI4 memory port's copy unit instead: a burst reader
    /// streaming a region into a burst writer, the port every DRAM-backed
    /// unit uses; --width is the port's data width (64, 128, 256 or 512,
    /// default 64).
    #[arg(long)]
    axi_copy: bool,
    /// Emit the broad phase's pass of one cell with its lists in external
    /// memory instead: the cell's two lists read over AXI4, each entry
    /// classified against the eight children and appended to their lists;
    /// --width is the grid's (16 or 24), --data-bits the port's.
    #[arg(long)]
    list_pass: bool,
    /// Emit the broad phase's binning with every list in external memory
    /// instead: the octree walked from the root's lists, a list pass per
    /// cell split, each leaf out as it is decided; --width is the grid's
    /// (16 or 24), --data-bits the port's, --pipelines and --depth the
    /// collision system's its split rule counts for.
    #[arg(long)]
    dram_binning: bool,
    /// Emit the broad-phase accelerator with its scene in external memory
    /// instead: that binning, the leaf reader, the collision system and the
    /// owner filter on one 64-bit AXI4 port; --width is the grid's and the
    /// system's (16 or 24), --pipelines, --depth and --rare-cases the
    /// system's, --triangles and --slots the owner filter's tables.
    #[arg(long)]
    dram_broad_phase: bool,
    /// With --list-pass or --dram-binning: the AXI4 port's data width (64,
    /// 128 or 256); with --dram-broad-phase 64, or 256 with --width 16
    /// --rare-cases shared [default: 64].
    #[arg(long, value_name = "BITS", value_parser = crate::input::whole::<usize>(64..=512))]
    data_bits: Option<usize>,
    /// Where the pipeline tests its rare pairs (coplanar, or two degenerate
    /// triangles): `parallel`, their own units (60 multipliers, never a
    /// stall), or `shared`, the shared unit inside the pipeline (6
    /// multipliers; the pipeline holds, output `hold`, while a rare pair
    /// waits for it), top `tritri_pipeline_shared_w<W>`; with --system,
    /// the system's pipelines (the read side holds with them), top
    /// `tritri_system_..._shared`.
    /// [default: parallel]
    #[arg(long, value_name = "PATH", value_parser = RareCasePath::NAMES)]
    rare_cases: Option<String>,
    /// With --patch-tessellator: 2^K steps a side (1 to 4) [default: 3].
    #[arg(long, value_name = "K", value_parser = crate::input::whole::<usize>(1..=4))]
    steps: Option<usize>,
    /// With --patch-tessellator: the unit with its triangles assembled (two
    /// a clock, in the collision system's triangle format).
    #[arg(long)]
    assemble: bool,
    /// Emit the octree engine's voxel fill instead (cells' children
    /// written into the voxel memory, a word per clock).
    #[arg(long)]
    voxel_fill: bool,
    /// Emit the octree engine's surface voxelization instead (triangles
    /// in, the voxels each meets out; grids up to 1024^3).
    #[arg(long)]
    triangle_voxelizer: bool,
    /// Emit the octree engine's voxel → octree conversion instead (a
    /// 4x4x4 brick of voxels in per clock, the canonical tree's nodes out).
    #[arg(long)]
    octree_builder: bool,
    /// With --owner-filter, --owner-chain-filter, --broad-phase or --dram-broad-phase: words of each object's slot
    /// table, one per triangle per leaf (1 to 16777216) [default: 65536].
    #[arg(long, value_parser = crate::input::whole::<u64>(1..=MAX_SLOTS as u64))]
    slots: Option<u64>,
    /// With --system or --binning-unit: pipelines working in parallel (1
    /// to 16; a power of two for the binning unit's split rule) [default: 2].
    #[arg(long, value_parser = crate::input::whole::<u32>(1..=MAX_PIPELINES as u32))]
    pipelines: Option<u32>,
    /// With --system or --binning-unit: memory depth, triangles per array
    /// per bank (1 to 32767; a power of two for the binning unit) [default: 256].
    #[arg(long, value_parser = crate::input::whole::<u64>(1..=MAX_TRIANGLES_PER_BANK as u64))]
    depth: Option<u64>,
    /// Emit the octree broad phase's binning unit instead (triangles in,
    /// leaves out); --width is the grid's width (16, 24 or 32), --depth and
    /// --pipelines the system it feeds.
    #[arg(long)]
    binning_unit: bool,
    /// Emit the broad-phase top instead: the binning unit on a 24-bit grid
    /// feeding the collision system (triangles in, each leaf's pairs out);
    /// --width is the system's (24, or 16 with leaves in frames of their
    /// own), --depth and --pipelines the system's, --triangles,
    /// --list-words and --leaves the binning unit's memories.
    #[arg(long)]
    broad_phase: bool,
    /// With --binning-unit, --broad-phase, --dram-broad-phase or --owner-chain-filter: triangles per object (1 to
    /// 262144) [default: 8192].
    #[arg(long, value_parser = crate::input::whole::<u64>(1..=1 << INDEX_BITS))]
    triangles: Option<u64>,
    /// With --binning-unit or --broad-phase: words of each of the sixteen
    /// list memories, two indices a word (1 to 1048576) [default: 16384].
    #[arg(long, value_parser = crate::input::whole::<u64>(1..=1 << LIST_ADDRESS_BITS))]
    list_words: Option<u64>,
    /// With --binning-unit or --broad-phase: leaf descriptors (1 to
    /// 1048576) [default: 4096].
    #[arg(long, value_parser = crate::input::whole::<u64>(1..=1 << LEAF_ADDRESS_BITS))]
    leaves: Option<u64>,
    /// Size the system for this scene (objects A and B as `tritri sim`
    /// takes them) and an error budget: W, P, the memory depth and the
    /// grid, from measured figures, with the reasons in its README.
    #[arg(long, num_args = 2, value_names = ["A", "B"], conflicts_with_all = ["width", "system", "classifier", "setup", "owner_filter", "plane_traversal", "set_operation", "octant_clipper", "voxel_fill", "binning_unit", "broad_phase", "pipelines", "depth", "synth"])]
    for_scene: Option<Vec<String>>,
    /// With --for-scene: pose of B, tx,ty,tz[,rx,ry,rz] (as in `tritri sim`).
    #[arg(
        long,
        allow_hyphen_values = true,
        value_name = "TX,TY,TZ,RX,RY,RZ",
        requires = "for_scene"
    )]
    pose_b: Option<Pose>,
    /// With --for-scene: uniform scale of B about its origin, before the pose.
    #[arg(long, default_value_t = 1.0, value_name = "S", allow_negative_numbers = true, value_parser = crate::input::parse_scale)]
    scale_b: f64,
    /// With --for-scene: the largest share of the pairs tested that may go
    /// back to the host (verdicts without a certificate, and pairs too long
    /// for a leaf's local frame), from 0 to 1 [default: 0.001, 0.1 %].
    #[arg(long, value_name = "RATE", value_parser = parse_rate, requires = "for_scene")]
    max_uncertain: Option<f64>,
    /// With --for-scene: the device whose resources bound the design
    /// (ecp5-85: LFE5U-85F, post-route figures at W = 8 and 12, and at
    /// W = 16 with the rare cases shared, the pipeline it then emits;
    /// artix7-200t: XC7A200T, Yosys synth_xilinx figures at every width).
    #[arg(long, value_name = "NAME", default_value = "artix7-200t", value_parser = parse_device)]
    device: String,
}

/// A rate from 0 to 1.
fn parse_rate(s: &str) -> Result<f64, String> {
    match s.trim().parse::<f64>() {
        Ok(v) if (0.0..=1.0).contains(&v) => Ok(v),
        _ => Err(format!("`{s}` is not a rate from 0 to 1 (0.001 is 0.1 %)")),
    }
}

/// A device of `tritri_rtl::measured::DEVICES`.
fn parse_device(s: &str) -> Result<String, String> {
    match device(s) {
        Some(d) => Ok(d.name.to_string()),
        None => Err(format!(
            "unknown device `{s}`: known are {}",
            DEVICES
                .iter()
                .map(|d| d.name)
                .collect::<Vec<_>>()
                .join(", ")
        )),
    }
}

impl Args {
    /// The scene of `--for-scene`, as `sim` takes one.
    fn for_scene(&self) -> Option<SceneArgs> {
        let objects = self.for_scene.clone()?;
        Some(SceneArgs {
            scene: Some(objects),
            pose_b: self.pose_b,
            scale_b: self.scale_b,
            subdivide: 0,
            tessellation: 8,
            tolerance: None,
        })
    }

    fn pipelines(&self) -> u32 {
        self.pipelines.unwrap_or(2)
    }

    /// `--triangles`: per object, for the binning unit's and the owner
    /// filter's tables.
    fn triangles(&self) -> usize {
        self.triangles.unwrap_or(8192) as usize
    }

    fn slots(&self) -> usize {
        self.slots.unwrap_or(65536) as usize
    }

    fn depth(&self) -> u64 {
        self.depth.unwrap_or(DEFAULT_TRIANGLES_PER_BANK as u64)
    }

    /// The system configuration at `width` (with --system).
    fn system_config(&self, width: usize) -> SystemConfig {
        SystemConfig::new(width, self.pipelines() as usize).with_depth(self.depth() as usize)
    }

    /// The binning unit's configuration for a `grid_bits`-bit grid (with
    /// --binning-unit; `check_usage` has checked the powers of two).
    fn binning_config(&self, grid_bits: usize) -> BinningUnitConfig {
        BinningUnitConfig {
            grid_bits,
            triangles: self.triangles(),
            list_words: self.list_words.unwrap_or(16384) as usize,
            leaves: self.leaves.unwrap_or(4096) as usize,
            log_depth: self.depth().trailing_zeros(),
            log_pipelines: self.pipelines().trailing_zeros(),
        }
    }

    /// The broad-phase top's configuration for a `width`-bit system (with
    /// --broad-phase): a 24-bit grid, local frames below 24 bits.
    fn broad_phase_config(&self, width: usize) -> BroadPhaseConfig {
        BroadPhaseConfig {
            unit: self.binning_config(BROAD_PHASE_GRID_BITS),
            system: self.system_config(width),
            slots: self.slots(),
            local_frames: width < BROAD_PHASE_GRID_BITS,
        }
    }

    /// The multipliers' mapping (`--dsp`, or the device of `--synth`).
    fn multipliers(&self) -> MultiplierMapping {
        match (&self.dsp, self.synth.as_deref()) {
            (Some(name), _) => MultiplierMapping::parse(name).unwrap_or_default(),
            (None, Some("ecp5")) => MultiplierMapping::Ecp5,
            (None, _) => MultiplierMapping::Inferred,
        }
    }

    /// The delay lines' mapping (`--delay-lines`, or the device of
    /// `--synth`).
    fn delay_lines(&self) -> DelayLineMapping {
        match (&self.delay_lines, self.synth.as_deref()) {
            (Some(name), _) => DelayLineMapping::parse(name).unwrap_or_default(),
            (None, Some("ecp5")) => DelayLineMapping::Memory,
            (None, _) => DelayLineMapping::Registers,
        }
    }

    /// The design the options pick ([`design::DESIGNS`]), or an error
    /// naming the design options given together.
    fn design(&self) -> Result<Design, String> {
        design::picked(&[
            (Design::System, self.system),
            (Design::Classifier, self.classifier),
            (Design::Setup, self.setup),
            (Design::BinningUnit, self.binning_unit),
            (Design::BroadPhase, self.broad_phase),
            (Design::OwnerFilter, self.owner_filter),
            (Design::OwnerChainFilter, self.owner_chain_filter),
            (Design::PlaneTraversal, self.plane_traversal),
            (Design::SetOperation, self.set_operation),
            (Design::OctantClipper, self.octant_clipper),
            (Design::VoxelFill, self.voxel_fill),
            (Design::TriangleVoxelizer, self.triangle_voxelizer),
            (Design::OctreeBuilder, self.octree_builder),
            (Design::PatchTessellator, self.patch_tessellator),
            (Design::ConeUnit, self.cone_unit),
            (Design::SharedRareCases, self.shared_rare_cases),
            (Design::AxiCopy, self.axi_copy),
            (Design::ListPass, self.list_pass),
            (Design::DramBinning, self.dram_binning),
            (Design::DramBroadPhase, self.dram_broad_phase),
        ])
    }

    /// The design options given on the command line.
    fn design_options_given(&self) -> Vec<DesignOption> {
        [
            (self.width.is_some(), DesignOption::Width),
            (self.dsp.is_some(), DesignOption::Dsp),
            (self.rare_cases.is_some(), DesignOption::RareCases),
            (self.pipelines.is_some(), DesignOption::Pipelines),
            (self.depth.is_some(), DesignOption::Depth),
            (self.triangles.is_some(), DesignOption::Triangles),
            (self.list_words.is_some(), DesignOption::ListWords),
            (self.leaves.is_some(), DesignOption::Leaves),
            (self.slots.is_some(), DesignOption::Slots),
            (self.steps.is_some(), DesignOption::Steps),
            (self.assemble, DesignOption::Assemble),
            (self.data_bits.is_some(), DesignOption::DataBits),
        ]
        .into_iter()
        .filter_map(|(given, option)| given.then_some(option))
        .collect()
    }

    /// The widths to emit: `--width`, or 24; one pass for a design that
    /// takes none.
    fn widths(&self) -> Vec<usize> {
        let default = if self.axi_copy { 64 } else { 24 };
        self.width.clone().unwrap_or_else(|| vec![default])
    }

    /// An error for options that do not go together, naming them.
    fn check_usage(&self) -> Result<Design, String> {
        let design = self.design()?;
        if self.for_scene.is_some() {
            // --for-scene chooses the system itself.
            if design != Design::Pipeline {
                return Err(format!(
                    "--for-scene sizes the system itself; {} does not go with it",
                    design.named()
                ));
            }
            if let Some(option) = self.design_options_given().first() {
                return Err(format!(
                    "--for-scene sizes the system itself; {} does not go with it",
                    option.flag()
                ));
            }
        }
        design.refuse(&self.design_options_given())?;
        // Checked before anything is built: the design goes into a directory.
        if let Some(out) = self.out.as_ref().filter(|o| o.exists() && !o.is_dir()) {
            return Err(format!(
                "--out {}: a file is there; gen writes a directory of Verilog files",
                out.display()
            ));
        }
        if self.synth_top.is_some() && self.synth.as_deref() != Some("ecp5") {
            return Err("--synth-top applies to --synth ecp5".into());
        }
        if !self.seed.is_empty() && self.synth.as_deref() != Some("ecp5") {
            return Err("--seed applies to --synth ecp5".into());
        }
        if let Some(seed) = (1..self.seed.len()).find_map(|i| {
            self.seed[..i]
                .contains(&self.seed[i])
                .then_some(self.seed[i])
        }) {
            return Err(format!("--seed {seed} is given twice"));
        }
        if self.router.is_some() && self.synth.as_deref() != Some("ecp5") {
            return Err("--router applies to --synth ecp5".into());
        }
        if self.placer.is_some() && self.synth.as_deref() != Some("ecp5") {
            return Err("--placer applies to --synth ecp5".into());
        }
        if self.timing_weight.is_some() && self.synth.as_deref() != Some("ecp5") {
            return Err("--timing-weight applies to --synth ecp5".into());
        }
        if self.timing_weight.is_some() && self.placer.as_deref() == Some("static") {
            return Err("--timing-weight is the heap placer's (not --placer static)".into());
        }
        // The width check is the multipliers' (the octree engine's units and
        // the tessellator map none onto MULT18X18D).
        if self.multipliers() == MultiplierMapping::Ecp5 && design.has_multipliers() {
            if let Some(flow) = self.synth.as_deref().filter(|&s| s != "ecp5") {
                return Err(format!("--dsp ecp5 with --synth {flow}: the multipliers are ECP5 primitives; synthesize them with --synth ecp5"));
            }
            if let Some(&w) = self.widths().iter().find(|&&w| w > MAX_ECP5_DSP_WIDTH) {
                let how = if self.dsp.is_some() {
                    "--dsp ecp5"
                } else {
                    "--synth ecp5 (which maps onto MULT18X18D blocks)"
                };
                return Err(format!(
                    "--width {w} with {how}: MULT18X18D mapping takes widths up to {MAX_ECP5_DSP_WIDTH} (add --dsp inferred to let Yosys map the products)"
                ));
            }
        }
        if matches!(
            design,
            Design::BinningUnit | Design::BroadPhase | Design::DramBinning | Design::DramBroadPhase
        ) {
            if !self.pipelines().is_power_of_two() {
                return Err(format!(
                    "--pipelines {}: the binning unit's split rule takes a power of two",
                    self.pipelines()
                ));
            }
            if !self.depth().is_power_of_two() {
                return Err(format!(
                    "--depth {}: the binning unit's split rule takes a power of two",
                    self.depth()
                ));
            }
        }
        for w in self.widths() {
            self.check_width(design, w)?;
        }
        Ok(design)
    }

    /// An error unless `design` is built for `width` (the coordinates' for
    /// the pipeline, the system and the broad-phase top, the grid's for the
    /// octree units, a unit's own list for the others).
    fn check_width(&self, design: Design, w: usize) -> Result<(), String> {
        let flag = design.named();
        match design {
            Design::Pipeline | Design::System => {
                check_width(w).map_err(|e| format!("--width {w}: {e}"))
            }
            Design::Classifier | Design::Setup if !CLASSIFIER_GRID_WIDTHS.contains(&w) => Err(format!(
                "{flag} --width {w}: the octree engine's units are emitted for grids of {CLASSIFIER_GRID_WIDTHS:?} bits"
            )),
            Design::BinningUnit => self
                .binning_config(w)
                .check()
                .map_err(|e| format!("{flag} --width {w}: {e}")),
            Design::BroadPhase => self
                .broad_phase_config(w)
                .check()
                .map_err(|e| format!("{flag} --width {w}: {e}")),
            Design::DramBroadPhase => self
                .dram_broad_phase_config(w)
                .check()
                .map_err(|e| format!("{flag} --width {w}: {e}")),
            Design::PatchTessellator
                if !TESSELLATOR_CONFIGURATIONS.contains(&(w, self.steps())) =>
            {
                Err(format!(
                    "{flag} --width {w} --steps {}: the unit is built for (W, K) in {TESSELLATOR_CONFIGURATIONS:?}",
                    self.steps()
                ))
            }
            Design::ConeUnit if !CONE_UNIT_WIDTHS.contains(&w) => Err(format!(
                "{flag} --width {w}: the unit is built for W in {CONE_UNIT_WIDTHS:?}"
            )),
            Design::SharedRareCases if !SHARED_RARE_CASES_WIDTHS.contains(&w) => Err(format!(
                "{flag} --width {w}: the unit is emitted for W in {SHARED_RARE_CASES_WIDTHS:?}"
            )),
            Design::AxiCopy => axi_copy_config(w)
                .transfer()
                .check()
                .map_err(|e| format!("{flag} --width {w}: {e}")),
            Design::ListPass | Design::DramBinning if !LIST_PASS_GRID_WIDTHS.contains(&w) => Err(format!(
                "{flag} --width {w}: the unit is built for grids of {LIST_PASS_GRID_WIDTHS:?} bits"
            )),
            Design::ListPass | Design::DramBinning => self
                .list_pass_config(w)
                .check()
                .map_err(|e| format!("{flag} --data-bits {}: {e}", self.list_pass_config(w).data_bits)),
            _ => Ok(()),
        }
    }

    /// `--steps` of the patch tessellator (its value: 2^K steps a side).
    fn steps(&self) -> usize {
        self.steps.unwrap_or(3)
    }

    /// The design for `width`.
    fn emit(&self, design: Design, width: usize) -> anyhow::Result<EmittedDesign> {
        let name = self.unit_name(design, width);
        self.emit_unnamed(design, width)
            .with_context(|| format!("emitting {name}"))
    }

    /// [`Args::emit`] without the top's name in the error.
    fn emit_unnamed(&self, design: Design, width: usize) -> anyhow::Result<EmittedDesign> {
        Ok(match design {
            Design::Pipeline => {
                emit_pipeline_for(width, self.multipliers(), self.rare_case_path())?
            }
            Design::System => {
                let kind = PipelineKind::from(self.rare_case_path());
                emit_system_with(self.system_config(width), kind, self.multipliers())?
            }
            Design::Classifier => emit_cell_classifier(width)?,
            Design::Setup => emit_triangle_setup(width)?,
            Design::BinningUnit => emit_binning_unit(&self.binning_config(width))?,
            Design::BroadPhase => {
                emit_broad_phase_system_with(&self.broad_phase_config(width), self.multipliers())?
            }
            Design::OwnerFilter => emit_owner_filter(self.slots())?,
            Design::OwnerChainFilter => emit_owner_chain_filter(self.triangles(), self.slots())?,
            Design::PlaneTraversal => emit_plane_traversal()?,
            Design::SetOperation => emit_set_operation()?,
            Design::OctantClipper => emit_octant_clipper()?,
            Design::VoxelFill => emit_voxel_fill()?,
            Design::TriangleVoxelizer => emit_triangle_voxelizer()?,
            Design::OctreeBuilder => emit_octree_builder()?,
            Design::PatchTessellator if self.assemble => emit_patch_triangles(width, self.steps())?,
            Design::PatchTessellator => emit_patch_tessellator(width, self.steps())?,
            Design::ConeUnit => emit_cone_unit(width)?,
            Design::SharedRareCases => emit_shared_rare_cases(width, self.multipliers())?,
            Design::AxiCopy => emit_axi_copy(&axi_copy_config(width))?,
            Design::ListPass => emit_list_pass(&self.list_pass_config(width))?,
            Design::DramBinning => emit_dram_binning(&self.dram_binning_config(width))?,
            Design::DramBroadPhase => {
                emit_dram_broad_phase(&self.dram_broad_phase_config(width), self.multipliers())?
            }
        })
    }

    /// `--rare-cases` (its value parser admits only the names).
    fn rare_case_path(&self) -> RareCasePath {
        self.rare_cases
            .as_deref()
            .and_then(RareCasePath::parse)
            .unwrap_or_default()
    }

    /// The top module's name for `width`.
    fn unit_name(&self, design: Design, width: usize) -> String {
        match design {
            Design::Pipeline => pipeline_unit_name_for(width, self.rare_case_path()),
            Design::System => {
                system_unit_name(self.system_config(width), self.rare_case_path().into())
            }
            Design::Classifier => cell_classifier_unit_name(width),
            Design::Setup => triangle_setup_unit_name(width),
            Design::BinningUnit => self.binning_config(width).unit_name(),
            Design::BroadPhase => self.broad_phase_config(width).unit_name(),
            Design::OwnerFilter => owner_filter_unit_name(self.slots()),
            Design::OwnerChainFilter => {
                owner_chain_filter_unit_name(self.triangles(), self.slots())
            }
            Design::PlaneTraversal => PLANE_TRAVERSAL_NAME.to_string(),
            Design::SetOperation => SET_OPERATION_NAME.to_string(),
            Design::OctantClipper => OCTANT_CLIPPER_NAME.to_string(),
            Design::VoxelFill => VOXEL_FILL_NAME.to_string(),
            Design::TriangleVoxelizer => TRIANGLE_VOXELIZER_NAME.to_string(),
            Design::OctreeBuilder => OCTREE_BUILDER_NAME.to_string(),
            Design::PatchTessellator if self.assemble => {
                patch_triangles_unit_name(width, self.steps())
            }
            Design::PatchTessellator => patch_tessellator_unit_name(width, self.steps()),
            Design::ConeUnit => cone_unit_name(width),
            Design::SharedRareCases => shared_rare_cases_name(width),
            Design::AxiCopy => axi_copy_config(width).unit_name(),
            Design::ListPass => list_pass_unit_name(&self.list_pass_config(width)),
            Design::DramBinning => dram_binning_unit_name(&self.dram_binning_config(width)),
            Design::DramBroadPhase => self.dram_broad_phase_config(width).unit_name(),
        }
    }

    /// The accelerator `tritri gen --dram-broad-phase` writes for a
    /// `width`-bit grid and system: the controller of `--dram-binning` on
    /// its port of `--data-bits` (64, or 256 with the rare cases shared),
    /// the system of `--pipelines`, `--depth` and
    /// `--rare-cases`, the owner filter's tables of `--triangles` and
    /// `--slots`.
    fn dram_broad_phase_config(&self, width: usize) -> DramBroadPhaseConfig {
        DramBroadPhaseConfig {
            binning: self.dram_binning_config(width),
            system: self.system_config(width),
            triangles: self.triangles(),
            slots: self.slots(),
            local_frames: false,
            rare_cases: self.rare_case_path(),
        }
    }

    /// The binning controller `tritri gen --dram-binning` writes for a
    /// `grid_bits` grid: the pass unit of `--list-pass`, the split rule of
    /// `--pipelines` and `--depth` in one frame (no level forced to split;
    /// the arena is an input).
    fn dram_binning_config(&self, grid_bits: usize) -> DramBinningConfig {
        DramBinningConfig {
            pass: self.list_pass_config(grid_bits),
            rule: BinningParams {
                log_depth: self.depth().trailing_zeros(),
                log_pipelines: self.pipelines().trailing_zeros(),
                max_leaf_level: None,
            },
            arena: (0, 0),
            waiting_capacity: WAITING_CAPACITY,
        }
    }

    /// The pass unit `tritri gen --list-pass` writes for a `grid_bits`
    /// grid: `--data-bits`, reads of up to 16 beats, 4 bursts in flight each
    /// way (what `crates/tritri-cosim/tests/list_pass.rs` co-simulates).
    fn list_pass_config(&self, grid_bits: usize) -> ListPassConfig {
        ListPassConfig {
            grid_bits,
            data_bits: self.data_bits.unwrap_or(64),
            max_read_burst: 16,
            outstanding: 4,
        }
    }
}

/// The copy unit `tritri gen --axi-copy` writes: a `data_bits` port, bursts
/// of up to 16 beats, 4 in flight each way (what
/// `crates/tritri-cosim/tests/axi_copy.rs` co-simulates).
fn axi_copy_config(data_bits: usize) -> AxiCopyConfig {
    AxiCopyConfig {
        data_bits,
        max_burst: 16,
        outstanding: 4,
    }
}

/// Where width `width` of `design` goes: `--out` with one width; otherwise
/// `w<W>` for the parallel pipeline and the top's name for every other
/// design, under `--out` or `rtl-out`.
fn out_dir(args: &Args, design: Design, width: usize) -> PathBuf {
    let several = args.width.as_ref().is_some_and(|w| w.len() > 1);
    let parent = match (&args.out, several) {
        (Some(dir), false) => return dir.clone(),
        (Some(parent), true) => parent.clone(),
        (None, _) => PathBuf::from("rtl-out"),
    };
    if design == Design::Pipeline && args.rare_case_path() == RareCasePath::Parallel {
        parent.join(format!("w{width}"))
    } else {
        parent.join(args.unit_name(design, width))
    }
}

/// `--synth ecp5`: synthesis and a route of `top` in `dir` for each
/// `--seed` (seed 1 without one), writing `route_ecp5.md`; several seeds
/// route side by side ([`route_ecp5_seeds`]), each into files of its own,
/// and the table is written again as each finishes, so that what is done
/// stays when the rest is stopped. `whole` is whether `top` is the emitted
/// top rather than a unit inside it.
fn place_and_route(
    args: &Args,
    dir: &Path,
    top: &str,
    whole: bool,
) -> anyhow::Result<Vec<RouteReport>> {
    let mut options = if whole {
        Ecp5Options::whole_design()
    } else {
        Ecp5Options::default()
    };
    // clap's value_parser admits only Router::NAMES.
    options.router = args
        .router
        .as_deref()
        .and_then(Router::from_name)
        .unwrap_or(options.router);
    // And only Placer::NAMES. The DRAM top routed only from the
    // electrostatic placer's placement (router1 left it unrouted from the
    // heap placer's: docs/axi-port.md, "Where the router fails").
    let placer = if whole && args.dram_broad_phase {
        Placer::Static
    } else {
        Placer::default()
    };
    options.placer = args
        .placer
        .as_deref()
        .and_then(Placer::from_name)
        .unwrap_or(placer);
    options.timing_weight = args.timing_weight.unwrap_or(options.timing_weight);
    let table = dir.join("route_ecp5.md");
    if let [] | [_] = args.seed.as_slice() {
        options.seed = args.seed.first().copied().unwrap_or(options.seed);
        eprintln!(
            "yosys synth_ecp5 and nextpnr-ecp5 of {top} (out of context, LFE5U-85F, speed 6) in {} (progress: {}) ...",
            dir.display(),
            dir.join(RouteFiles::single().partial().log).display()
        );
        let report =
            route_ecp5(dir, top, &options).with_context(|| format!("place and route of {top}"))?;
        std::fs::write(&table, route_table(std::slice::from_ref(&report)))
            .with_context(|| format!("writing {}", table.display()))?;
        return Ok(vec![report]);
    }
    eprintln!(
        "yosys synth_ecp5, then nextpnr-ecp5 of {top} with seeds {} (out of context, LFE5U-85F, speed 6, {} at once) in {} (progress: route_ecp5_seed<N>.partial.log) ...",
        seeds_list(&args.seed),
        routes_at_once(&options, args.seed.len()),
        dir.display()
    );
    let done = std::sync::Mutex::new(Vec::new());
    let on_route = |seed: u64, outcome: &Result<RouteReport, RouteError>| {
        let Ok(mut done) = done.lock() else { return };
        match outcome {
            Ok(report) => {
                done.push(report.clone());
                done.sort_by_key(|r: &RouteReport| r.seed);
                eprintln!(
                    "seed {seed}: {:.1} MHz ({} of {} seeds routed)",
                    report.fmax_mhz,
                    done.len(),
                    args.seed.len()
                );
                if let Err(e) = std::fs::write(&table, route_table(&done)) {
                    eprintln!("error: writing {}: {e}", table.display());
                }
            }
            Err(e) => eprintln!("error: seed {seed}: place and route of {top}: {e}"),
        }
    };
    let outcomes = route_ecp5_seeds(dir, top, &options, &args.seed, &on_route)
        .with_context(|| format!("synthesis of {top}"))?;
    let mut reports = Vec::new();
    let mut failed = Vec::new();
    for (seed, outcome) in args.seed.iter().zip(outcomes) {
        match outcome {
            Ok(report) => reports.push(report),
            Err(_) => failed.push(*seed),
        }
    }
    if let Some((best, meeting)) = best_route(&reports) {
        eprintln!(
            "{top}: best {:.1} MHz (seed {}); {meeting} of {} seeds at {} MHz or more",
            best.fmax_mhz,
            best.seed,
            reports.len(),
            best.target_mhz
        );
    }
    if !failed.is_empty() {
        let others = if reports.is_empty() {
            String::new()
        } else {
            format!("; the others' routes are in {}", table.display())
        };
        anyhow::bail!(
            "place and route of {top} failed with seed(s) {} (above){others}",
            seeds_list(&failed)
        );
    }
    Ok(reports)
}

/// `1, 2, 3`.
fn seeds_list(seeds: &[u64]) -> String {
    seeds
        .iter()
        .map(u64::to_string)
        .collect::<Vec<_>>()
        .join(", ")
}

pub fn run(args: Args) -> anyhow::Result<ExitCode> {
    let design = match args.check_usage() {
        Ok(design) => design,
        Err(e) => {
            eprintln!("error: {e}");
            return Ok(ExitCode::from(2));
        }
    };
    if let Some(scene) = args.for_scene() {
        let device = device(&args.device).expect("checked by parse_device");
        let request = for_scene::Request {
            scene: &scene,
            max_uncertain: args.max_uncertain.unwrap_or(0.001),
            device,
            out: args.out.clone(),
        };
        return for_scene::run(request);
    }
    let mut rows = Vec::new();
    let mut routes = Vec::new();
    // A design without a width is written once.
    let widths = if design.takes(DesignOption::Width) {
        args.widths()
    } else {
        vec![0]
    };
    for w in widths {
        let dir = out_dir(&args, design, w);
        let mut emitted = args.emit(design, w)?;
        map_delay_lines(&mut emitted, args.delay_lines());
        emitted
            .write_to(&dir)
            .with_context(|| format!("writing {}", dir.display()))?;
        eprintln!(
            "wrote {} ({} modules, {} files) to {}",
            emitted.top,
            emitted.modules.len(),
            emitted.files.len(),
            dir.display()
        );
        if args.synth.as_deref() == Some("ecp5") {
            let top = args.synth_top.as_deref().unwrap_or(&emitted.top);
            if !emitted.modules.iter().any(|m| m == top) {
                let units: Vec<&str> = emitted
                    .modules
                    .iter()
                    .map(String::as_str)
                    .filter(|m| !m.contains("_dff_") && !m.contains("_delay"))
                    .take(12)
                    .collect();
                eprintln!(
                    "error: --synth-top {top}: {} has no such module; it has {}, ...",
                    emitted.top,
                    units.join(", ")
                );
                return Ok(ExitCode::from(2));
            }
            routes.extend(place_and_route(&args, &dir, top, top == emitted.top)?);
        } else if let Some(which) = &args.synth {
            let mut row = ResourceRow {
                unit: args.unit_name(design, w),
                generic: None,
                xilinx: None,
            };
            if which == "all" || which == "xilinx" {
                eprintln!("yosys synth_xilinx in {} ...", dir.display());
                row.xilinx = Some(synthesize(&dir, Target::Xilinx)?);
            }
            if which == "all" || which == "generic" {
                eprintln!("yosys synth (generic) in {} ...", dir.display());
                row.generic = Some(synthesize(&dir, Target::Generic)?);
            }
            std::fs::write(
                dir.join("resources.md"),
                resource_table(std::slice::from_ref(&row)),
            )?;
            rows.push(row);
        }
    }
    if !rows.is_empty() {
        out!("{}", resource_table(&rows))?;
    }
    if !routes.is_empty() {
        out!("{}", route_table(&routes))?;
    }
    Ok(ExitCode::SUCCESS)
}
