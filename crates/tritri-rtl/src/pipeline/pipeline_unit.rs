//! The emitted configuration of the triangle pipeline: its name, port
//! meanings, latency and throughput, around rust-hdl's Verilog from
//! [`crate::raw_design`].

use crate::emit::dsp_mapping::MultiplierMapping;
use crate::emit::{emit_with, EmitError, EmitOptions, EmittedDesign, UnitDescription};
use crate::pipeline::pipeline_for_width::{pipeline_with, UnsupportedWidth, SUPPORTED_WIDTHS};
use crate::pipeline::ports::port_descriptions;
use crate::pipeline::shared_rare_cases::{COPLANAR_STEPS, SEGMENTS_STEPS};
use crate::pipeline::triangle_pipeline::latency;
use crate::pipeline::RareCasePath;
use crate::pipeline::ID_BITS;
use tritri_geom::widths::FixedWidths;

/// Top module name of the `width`-bit pipeline: `tritri_pipeline_w<W>`.
pub fn pipeline_unit_name(width: usize) -> String {
    pipeline_unit_name_for(width, RareCasePath::Parallel)
}

/// Top module name of the `width`-bit pipeline with its rare cases on
/// `rare_cases`: `tritri_pipeline_w<W>`, or `tritri_pipeline_shared_w<W>`.
pub fn pipeline_unit_name_for(width: usize, rare_cases: RareCasePath) -> String {
    match rare_cases {
        RareCasePath::Parallel => format!("tritri_pipeline_w{width}"),
        RareCasePath::Shared => format!("tritri_pipeline_shared_w{width}"),
    }
}

/// The description of the `width`-bit pipeline for the emitter.
pub fn pipeline_unit(width: usize) -> Result<UnitDescription, UnsupportedWidth> {
    pipeline_unit_for(width, RareCasePath::Parallel)
}

/// The description of the `width`-bit pipeline with its rare cases on
/// `rare_cases`.
pub fn pipeline_unit_for(
    width: usize,
    rare_cases: RareCasePath,
) -> Result<UnitDescription, UnsupportedWidth> {
    if !SUPPORTED_WIDTHS.contains(&width) {
        return Err(UnsupportedWidth(width));
    }
    let w = FixedWidths::new(width as u32).map_err(|_| UnsupportedWidth(width))?;
    let l = latency() as u64;
    let mut unit = UnitDescription::new(
        &pipeline_unit_name_for(width, rare_cases),
        &format!(
            "Devillers-Guigue triangle-triangle overlap test for {width}-bit signed coordinates, pipelined: \
             one triangle pair per clock, verdict after {l} clocks."
        ),
    )
    .detail(
        "Protocol (thesis, chapter 3): a valid triangle with `in_bset = 1` is loaded into the base-polygon \
         registers and is not tested; every other valid triangle is tested against the current base and its \
         verdict leaves the pipeline a fixed number of clocks later with `out_valid = 1` and both ids. For N1 base \
         triangles against N2 streamed triangles, send per base one `in_bset` cycle followed by the N2 triangles.",
    )
    .detail(
        "The arithmetic is exact integer arithmetic on the quantized coordinates (differences, cross products and \
         orient3d determinants in their tight widths), so every verdict equals the exact test on the grid, \
         touching, coplanar and degenerate triangles included.",
    )
    .parameter("W", &format!("{width}: coordinate width in bits (two's complement)"))
    .parameter("D", &format!("{}: coordinate difference width, W + 1", w.difference))
    .parameter("C", &format!("{}: cross-product and orient2d width, 2W + 1", w.cross))
    .parameter("O", &format!("{}: orient3d width, 3W + 2", w.orient3d))
    .parameter("ID", &format!("{ID_BITS}: triangle id width"))
    .latency(l)
    .throughput(&format!(
        "one triangle pair per clock while `advance` is high; N1 bases against N2 streamed triangles take \
         N1 + N1*N2 + {l} clocks (thesis, equation 3.2)."
    ));
    for (name, meaning) in port_descriptions(latency()) {
        unit = unit.port(&name, &meaning);
    }
    if rare_cases == RareCasePath::Shared {
        unit = unit
            .detail(&format!(
                "The rare pairs (coplanar, or two degenerate triangles) are tested on one shared unit with six \
                 multipliers instead of 60: it takes a coplanar pair every {COPLANAR_STEPS} clocks and two segments \
                 every {SEGMENTS_STEPS}. While a rare pair waits for it, `hold` is high and the pipeline holds as if \
                 `advance` were low; verdicts keep their order and their latency in advancing clocks."
            ))
            .port(
                "hold",
                "A rare pair waits for the shared unit: this clock does not take the input bus (keep the \
                 triangle on it) and moves nothing. A register's output.",
            )
            .port(
                "hold_request",
                "Four registers: this pipeline's rare pair will wait for its unit three clocks from now if \
                 `advance` is `a` next clock and the pipeline moves (`m`, `advance` high and `hold` low) two \
                 clocks from now, at index `2a + m`. For pipelines that move in step with this one (a \
                 system's), which take the OR of all their requests, index by index, as `hold_others`.",
            )
            .port(
                "hold_others",
                "Four inputs: the OR of the `hold_request`s of the pipelines moving in step with this one, \
                 this one's may be included; `hold` rises with them. Tie to 0 for a pipeline on its own.",
            );
    }
    Ok(unit)
}

#[derive(Debug, thiserror::Error)]
pub enum PipelineEmitError {
    #[error("{0}")]
    Width(#[from] UnsupportedWidth),
    #[error(transparent)]
    Emit(#[from] EmitError),
}

/// The emitted `width`-bit pipeline (what `tritri gen --width <W>` writes).
pub fn emit_pipeline(width: usize) -> Result<EmittedDesign, PipelineEmitError> {
    emit_pipeline_with(width, MultiplierMapping::Inferred)
}

/// [`emit_pipeline`] with its multipliers mapped as `multipliers` says
/// (`tritri gen --dsp`).
pub fn emit_pipeline_with(
    width: usize,
    multipliers: MultiplierMapping,
) -> Result<EmittedDesign, PipelineEmitError> {
    emit_pipeline_for(width, multipliers, RareCasePath::Parallel)
}

/// [`emit_pipeline_with`] with the rare cases on `rare_cases`
/// (`tritri gen --rare-cases`).
pub fn emit_pipeline_for(
    width: usize,
    multipliers: MultiplierMapping,
    rare_cases: RareCasePath,
) -> Result<EmittedDesign, PipelineEmitError> {
    let unit = pipeline_unit_for(width, rare_cases)?;
    let raw = pipeline_with(width, rare_cases)?.raw_design();
    Ok(emit_with(
        &raw,
        &unit,
        EmitOptions {
            multipliers,
            ..EmitOptions::default()
        },
    )?)
}
