//! Verilog emission of the system top through [`crate::emit`]: the unit
//! description (name, parameters, ports) and the emitted design.
//!
//! ```no_run
//! use tritri_rtl::system::system_unit::emit_system;
//! use tritri_rtl::system::system_for_width::PipelineKind;
//! use tritri_rtl::system::SystemConfig;
//! let config = SystemConfig::new(24, 2).with_depth(64);
//! let design = emit_system(config, PipelineKind::Parallel).unwrap();
//! assert_eq!(design.top, "tritri_system_w24_p2_d64");
//! ```

use super::system_for_width::{system_for_config, PipelineKind, UnsupportedWidth};
use super::{SystemConfig, MEMORY_READ_LATENCY};
use crate::emit::dsp_mapping::MultiplierMapping;
use crate::emit::{emit_with, EmitError, EmitOptions, EmittedDesign, UnitDescription};

/// The top's name: [`SystemConfig::unit_name`], with `_stub` for stub
/// pipelines and `_shared` for pipelines with the shared rare-case unit.
pub fn system_unit_name(config: SystemConfig, kind: PipelineKind) -> String {
    match kind {
        PipelineKind::Parallel => config.unit_name(),
        PipelineKind::Stub => format!("{}_stub", config.unit_name()),
        PipelineKind::Shared => format!("{}_shared", config.unit_name()),
    }
}

/// What the emitter writes about the system (header, README, port table).
pub fn system_unit(config: SystemConfig, kind: PipelineKind) -> UnitDescription {
    let w = config.coordinate_bits;
    let mut unit = UnitDescription::new(
        &system_unit_name(config, kind),
        "Bounding-volume-aware triangle-triangle intersection system: two-bank triangle memories, \
         address generator, parallel Devillers-Guigue pipelines, result FIFO.",
    )
    .detail(
        "The host writes a batch (the triangles of objects A and B inside one common bounding volume) \
         as triangle words followed by one end-of-batch word, and may write the next batch at once into \
         the other memory bank. Every pair (a, b) of the batch is tested; the intersecting pairs leave \
         on the result stream as (id_a, id_b). When the result FIFO holds more than FIFO_DEPTH - L words \
         the read side stalls; the pipelines run on and their pairs in flight fill the L words kept in \
         reserve, so no result is dropped.",
    )
    .detail(&format!(
        "Cycles of one batch of N1 A- and N2 B-triangles, from its first word to done: \
         (N1 + N2 + 1) + 1 + N1 + ceil(N1 / P) * N2 + {MEMORY_READ_LATENCY} + L ({MEMORY_READ_LATENCY}: the \
         memories' read latency), plus stall cycles (tritri_rtl::system::cycle_model).",
    ))
    .detail(if kind == PipelineKind::Shared {
        "Each pipeline tests its rare pairs (coplanar, or two degenerate triangles) on one shared unit \
         with six multipliers; while a rare pair waits for its pipeline's unit, every pipeline and the read \
         side hold, and `stall_cycles` counts those clocks too (tritri_rtl::system::rare_case_model)."
    } else {
        "Each pipeline tests its rare pairs (coplanar, or two degenerate triangles) on units of their own, \
         beside the general path: they never stall it."
    })
    .parameter("W", &format!("{w}: coordinate width (signed bits)"))
    .parameter("P", &format!("{}: pipelines in parallel", config.pipelines))
    .parameter(
        "DEPTH",
        &format!("{}: triangles per array (object) per bank; 2 banks per object", config.triangles_per_bank),
    )
    .parameter("FIFO_DEPTH", &format!("{}: result FIFO words (up to P pairs each)", config.result_fifo_depth))
    .parameter(
        "L",
        &format!(
            "{}: pipeline latency{}",
            config.pipeline_latency,
            if kind == PipelineKind::Stub { " (stub pipelines: trivial verdict)" } else { "" }
        ),
    )
    .throughput(&format!(
        "{} triangle pair{} per clock while B streams",
        config.pipelines,
        if config.pipelines == 1 { "" } else { "s" }
    ));
    let ports: [(&str, String); 28] = [
        ("clock", "clock".into()),
        ("reset", "synchronous active-high reset".into()),
        ("in_valid", "host triangle stream: a word is offered".into()),
        ("in_ready", "host triangle stream: the write bank is free (transfer = in_valid & in_ready)".into()),
        ("in_end", "the word is the end-of-batch (commit) word; its triangle fields are ignored".into()),
        ("in_object", "0: the triangle belongs to object A (bases), 1: to object B (streamed)".into()),
        ("in_id", "the triangle's original id".into()),
        ("in_x0", format!("vertex 0 x, signed {w}-bit")),
        ("in_y0", format!("vertex 0 y, signed {w}-bit")),
        ("in_z0", format!("vertex 0 z, signed {w}-bit")),
        ("in_x1", format!("vertex 1 x, signed {w}-bit")),
        ("in_y1", format!("vertex 1 y, signed {w}-bit")),
        ("in_z1", format!("vertex 1 z, signed {w}-bit")),
        ("in_x2", format!("vertex 2 x, signed {w}-bit")),
        ("in_y2", format!("vertex 2 y, signed {w}-bit")),
        ("in_z2", format!("vertex 2 z, signed {w}-bit")),
        ("out_valid", "result stream: a pair is offered (every hit, and every pair whose verdict has no certificate)".into()),
        ("out_ready", "result stream: the reader takes it".into()),
        ("out_id_a", "id of the pair's A triangle".into()),
        ("out_id_b", "id of the pair's B triangle".into()),
        ("out_hit", "the pair intersects on the grid (touching counts)".into()),
        ("out_certain", "the verdict is provably the verdict before quantization; with 0 the host decides the pair again on its own coordinates (docs/certificates.md)".into()),
        ("done", "every committed batch is tested and its hits are in the result FIFO (busy = !done)".into()),
        ("results_empty", "no pair waits: the result FIFO and the pair serializer hold nothing".into()),
        ("overflow", "sticky: an array of a batch exceeded DEPTH (the excess was not stored)".into()),
        ("pairs_tested", "counter: pairs tested since reset (wraps at 2^32)".into()),
        ("hits", "counter: intersecting pairs found since reset".into()),
        ("stall_cycles", "counter: cycles the read side was held, with work to do, by the result FIFO above its mark (or by a shared rare-case unit)".into()),
    ];
    for (name, meaning) in ports.iter() {
        unit = unit.port(name, meaning);
    }
    unit
}

/// Why the system could not be emitted.
#[derive(Debug, thiserror::Error)]
pub enum SystemEmitError {
    #[error("{0}")]
    Width(UnsupportedWidth),
    #[error(transparent)]
    Emit(#[from] EmitError),
}

/// The emitted Verilog directory of the system for `config`.
pub fn emit_system(
    config: SystemConfig,
    kind: PipelineKind,
) -> Result<EmittedDesign, SystemEmitError> {
    emit_system_with(config, kind, MultiplierMapping::Inferred)
}

/// [`emit_system`] with its multipliers mapped as `multipliers` says
/// (`tritri gen --system --dsp`).
pub fn emit_system_with(
    config: SystemConfig,
    kind: PipelineKind,
    multipliers: MultiplierMapping,
) -> Result<EmittedDesign, SystemEmitError> {
    let mut system = system_for_config(config, kind).map_err(SystemEmitError::Width)?;
    system.connect_all();
    Ok(emit_with(
        &system.raw_design(),
        &system_unit(config, kind),
        EmitOptions {
            multipliers,
            ..EmitOptions::default()
        },
    )?)
}
