//! The emitted shared rare-case unit ([`crate::pipeline::shared_rare_cases`]):
//! its name, port meanings and timing.

use super::dsp_mapping::MultiplierMapping;
use super::{emit_with, EmitError, EmitOptions, EmittedDesign, UnitDescription};
use crate::pipeline::pipeline_for_width::UnsupportedWidth;
use crate::pipeline::shared_rare_cases::{
    SharedRareCases, COPLANAR_STEPS, IN_VALID_COPIES, SEGMENTS_STEPS, SHARED_RARE_CASES_LATENCY,
};
use rust_hdl::prelude::*;

/// The coordinate widths the unit is emitted for.
pub const SHARED_RARE_CASES_WIDTHS: [usize; 3] = [8, 16, 24];

/// `tritri_shared_rare_cases_w<W>`.
pub fn shared_rare_cases_name(w: usize) -> String {
    format!("tritri_shared_rare_cases_w{w}")
}

pub fn shared_rare_cases(w: usize) -> UnitDescription {
    let mut unit = UnitDescription::new(
        &shared_rare_cases_name(w),
        "The triangle pipeline's rare cases on one shared, slower path: the coplanar test and the degenerate pair's \
         segment test with three orient2d lanes (six multipliers) over several clocks, exactly as the parallel units \
         decide them.",
    )
    .detail(&format!(
        "A job is a pair: a coplanar pair takes {COPLANAR_STEPS} clocks of the lanes, two segments \
         {SEGMENTS_STEPS}; the next job is taken in the clock of the last step, and verdicts leave in order."
    ))
    .parameter("W", &format!("{w}: bits of a coordinate, two's complement"))
    .port("clock", "Clock; every register updates on the rising edge.")
    .port("reset", "Synchronous reset, active high: no job in the unit.")
    .port("in_valid", "A job is offered; it is taken at the clock edge when ready is high.");
    for c in 0..IN_VALID_COPIES {
        unit = unit.port(
            &format!("in_valid_copies_{c}"),
            "in_valid again, for one copy of the steps left (equal to in_valid; each from a register of its own).",
        );
    }
    unit = unit.port(
        "in_segments",
        "The job is two degenerate triangles (else a coplanar pair).",
    );
    for t in ["t1", "t2"] {
        for i in 0..9 {
            unit = unit.port(
                &format!("{t}_vertices_{i}"),
                &format!(
                    "{}: coordinate {} of vertex {}.",
                    t.to_uppercase(),
                    i % 3,
                    i / 3
                ),
            );
        }
    }
    unit = unit.port("axis", "Coplanar: the axis the projection drops.");
    for t in ["t1", "t2"] {
        for k in 0..3 {
            unit = unit
                .port(
                    &format!("{t}_normal_negative_{k}"),
                    &format!("Coplanar: {t}'s normal's component {k} < 0."),
                )
                .port(
                    &format!("{t}_normal_zero_{k}"),
                    &format!("Coplanar: {t}'s normal's component {k} = 0."),
                );
        }
        unit = unit
            .port(
                &format!("{t}_segment_low"),
                &format!("Segments: {t}'s lexicographically lowest vertex."),
            )
            .port(
                &format!("{t}_segment_high"),
                &format!("Segments: {t}'s lexicographically highest vertex."),
            );
    }
    unit.port("ready", "The unit takes a job at this clock's edge.")
        .port("idle_in_three", "ready will be high three clocks from now unless a job is taken before.")
        .port("done", &format!("A job's verdict is on hit: {SHARED_RARE_CASES_LATENCY} clocks after a coplanar job was taken, {} after two segments.", SHARED_RARE_CASES_LATENCY - (COPLANAR_STEPS - SEGMENTS_STEPS)))
        .port("hit", "The pair meets.")
        .latency(SHARED_RARE_CASES_LATENCY as u64)
        .throughput(&format!("a coplanar pair every {COPLANAR_STEPS} clocks, two segments every {SEGMENTS_STEPS}."))
}

/// The unit at `w` (one of [`SHARED_RARE_CASES_WIDTHS`]), its multipliers
/// mapped as `multipliers` says.
pub fn emit_shared_rare_cases(
    w: usize,
    multipliers: MultiplierMapping,
) -> Result<EmittedDesign, EmitError> {
    fn one<const W: usize, const D: usize, const C: usize>(
        multipliers: MultiplierMapping,
    ) -> Result<EmittedDesign, EmitError> {
        let mut uut = SharedRareCases::<W, D, C>::default();
        uut.connect_all();
        let options = EmitOptions {
            multipliers,
            ..EmitOptions::default()
        };
        emit_with(
            &crate::unit::RawDesign::of(&uut),
            &shared_rare_cases(W),
            options,
        )
    }
    match w {
        8 => one::<8, 9, 17>(multipliers),
        16 => one::<16, 17, 33>(multipliers),
        24 => one::<24, 25, 49>(multipliers),
        _ => panic!("{}", UnsupportedWidth(w)),
    }
}
