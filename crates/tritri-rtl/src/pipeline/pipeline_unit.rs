//! The emitted configuration of the triangle pipeline: its name, port
//! meanings, latency and throughput, around rust-hdl's Verilog from
//! [`crate::raw_design`].

use crate::emit::dsp_mapping::MultiplierMapping;
use crate::emit::{emit_with, EmitError, EmitOptions, EmittedDesign, UnitDescription};
use crate::pipeline::pipeline_for_width::{UnsupportedWidth, SUPPORTED_WIDTHS};
use crate::pipeline::ports::port_descriptions;
use crate::pipeline::triangle_pipeline::latency;
use crate::pipeline::ID_BITS;
use tritri_geom::widths::FixedWidths;

/// Top module name of the `width`-bit pipeline: `tritri_pipeline_w<W>`.
pub fn pipeline_unit_name(width: usize) -> String {
    format!("tritri_pipeline_w{width}")
}

/// The description of the `width`-bit pipeline for the emitter.
pub fn pipeline_unit(width: usize) -> Result<UnitDescription, UnsupportedWidth> {
    if !SUPPORTED_WIDTHS.contains(&width) {
        return Err(UnsupportedWidth(width));
    }
    let w = FixedWidths::new(width as u32).map_err(|_| UnsupportedWidth(width))?;
    let l = latency() as u64;
    let mut unit = UnitDescription::new(
        &pipeline_unit_name(width),
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
    let unit = pipeline_unit(width)?;
    let raw = crate::raw_design(width)?;
    Ok(emit_with(
        &raw,
        &unit,
        EmitOptions {
            multipliers,
            ..EmitOptions::default()
        },
    )?)
}
