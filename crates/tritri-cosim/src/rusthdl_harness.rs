//! Direct-drive co-simulation of the rust-hdl triangle pipeline: set the
//! input ports, toggle the clock, call `update_all()` until nothing changes
//! (docs/ARCHITECTURE.md, conventions; no `simple_sim!` threads), and collect one verdict per
//! tested pair.
//!
//! Schedule (thesis, chapter 3, and [`crate::stream`]): per base triangle,
//! one cycle with `bset = 1`, then the streamed triangles one per cycle.
//! The cycle count is measured, not assumed: from the cycle in which the
//! first triangle is on the input bus (cycle 1) to the cycle in which the
//! last verdict is on the output ports, inclusive. The thesis's formula
//! says it is `N1 + N1 N2 + L`.
//!
//! ```no_run
//! use tritri_cosim::rusthdl_harness::run_pairs;
//! let t = [[0, 0, 0], [100, 0, 0], [0, 100, 0]];
//! let s = [[10, 10, -5], [10, 10, 5], [20, 30, 5]];
//! let r = run_pairs(24, &[(7, t)], &[(9, s)]).unwrap();
//! assert_eq!(r.pairs, vec![(7, 9, true)]);
//! ```

use crate::stream::{PairVerdict, StreamResult, TriangleStream};
use anyhow::{bail, Context, Result};
use std::path::{Path, PathBuf};
use tritri_geom::fixed_point::FixedTriangle;
use tritri_rtl::pipeline::pipeline_for_width::{
    pipeline_for_width, PipelineInput, PipelineSimulation,
};

/// Options of a run.
#[derive(Clone, Debug, Default)]
pub struct HarnessOptions {
    /// Write a VCD trace of every signal to this file (large: use on small runs).
    pub vcd: Option<PathBuf>,
}

/// The verdicts as `(base_id, stream_id, hit)` in output order, and the
/// measured cycle count.
#[derive(Clone, Debug, PartialEq, Eq, Default)]
pub struct RunResult {
    pub pairs: Vec<(u32, u32, bool)>,
    pub cycles: u64,
}

impl From<StreamResult> for RunResult {
    fn from(r: StreamResult) -> Self {
        RunResult {
            pairs: r
                .verdicts
                .iter()
                .map(|v| (v.base_id, v.stream_id, v.hit))
                .collect(),
            cycles: r.cycles,
        }
    }
}

/// Runs `bases` (each loaded once with `bset`) against `streamed` on the
/// `width`-bit pipeline.
pub fn run_pairs(
    width: usize,
    bases: &[(u32, FixedTriangle)],
    streamed: &[(u32, FixedTriangle)],
) -> Result<RunResult> {
    Ok(run_stream(
        width,
        &TriangleStream::from_tagged(bases, streamed),
        &HarnessOptions::default(),
    )?
    .into())
}

/// Runs `stream` on a fresh `width`-bit pipeline.
pub fn run_stream(
    width: usize,
    stream: &TriangleStream,
    options: &HarnessOptions,
) -> Result<StreamResult> {
    let mut pipeline = pipeline_for_width(width)?;
    run_stream_on(pipeline.as_mut(), stream, options)
}

/// A VCD writer that follows the simulation half-cycle by half-cycle.
struct Trace {
    probe: Option<rust_hdl::core::vcd_probe::VCDProbe<std::io::BufWriter<std::fs::File>>>,
    time: u64,
}

impl Trace {
    fn open(path: Option<&Path>, pipeline: &dyn PipelineSimulation) -> Result<Self> {
        let probe = match path {
            None => None,
            Some(p) => {
                let file = std::fs::File::create(p)
                    .with_context(|| format!("creating VCD file {}", p.display()))?;
                let probe = rust_hdl::prelude::write_vcd_header(
                    std::io::BufWriter::new(file),
                    pipeline.block(),
                );
                Some(rust_hdl::prelude::write_vcd_dump(probe, pipeline.block()))
            }
        };
        Ok(Trace { probe, time: 0 })
    }

    /// Records the state after a half cycle (timestamps in ps, 10 ns clock).
    fn sample(&mut self, pipeline: &dyn PipelineSimulation) -> Result<()> {
        if let Some(probe) = self.probe.take() {
            self.time += 5_000;
            let mut probe = probe;
            probe.timestamp(self.time)?;
            self.probe = Some(rust_hdl::prelude::write_vcd_change(probe, pipeline.block()));
        }
        Ok(())
    }

    fn finish(self) -> Result<()> {
        if let Some(probe) = self.probe {
            drop(probe);
        }
        Ok(())
    }
}

/// Runs `stream` on `pipeline` (which may have run before: it is reset
/// first). Errors if a verdict is missing, extra, or carries unexpected ids.
pub fn run_stream_on(
    pipeline: &mut dyn PipelineSimulation,
    stream: &TriangleStream,
    options: &HarnessOptions,
) -> Result<StreamResult> {
    let schedule: Vec<PipelineInput> = stream.schedule().collect();
    run_schedule_on(pipeline, &schedule, options)
}

/// Runs an arbitrary schedule of input cycles: each valid cycle with `bset`
/// loads a base, each other valid cycle tests its triangle against the
/// latest base, and invalid cycles are bubbles. The verdicts come in the
/// order of the tested cycles; the cycle count runs from the first input
/// cycle to the cycle of the last verdict, inclusive.
pub fn run_schedule_on(
    pipeline: &mut dyn PipelineSimulation,
    schedule: &[PipelineInput],
    options: &HarnessOptions,
) -> Result<StreamResult> {
    let mut trace = Trace::open(options.vcd.as_deref(), pipeline)?;
    let clock = |p: &mut dyn PipelineSimulation, t: &mut Trace| -> Result<()> {
        if t.probe.is_some() {
            p.half_cycle(false);
            t.sample(p)?;
            p.half_cycle(true);
            t.sample(p)
        } else {
            p.clock_cycle();
            Ok(())
        }
    };

    // The pairs the schedule asks for, in order.
    let mut expected_ids = Vec::new();
    let mut base: Option<u32> = None;
    for c in schedule.iter().filter(|c| c.valid) {
        if c.bset {
            base = Some(c.id);
        } else {
            match base {
                Some(b) => expected_ids.push((b, c.id)),
                None => bail!("streamed triangle {} before any base", c.id),
            }
        }
    }

    // Reset: one cycle with reset high and an idle bus (not counted).
    pipeline.set_advance(true);
    pipeline.set_input(&PipelineInput::default());
    pipeline.set_reset(true);
    clock(pipeline, &mut trace)?;
    pipeline.set_reset(false);

    let mut verdicts = Vec::with_capacity(expected_ids.len());
    let mut last_output_cycle = 0u64;
    let latency = pipeline.latency() as u64;
    let input_cycles = schedule.len() as u64;
    // Cycle c: the input `next` is on the bus; the edge at its end loads
    // it unless the pipeline holds (a rare pair waits for the shared unit),
    // and then it stays on the bus; the outputs then visible belong to
    // cycle c + 1.
    let mut cycle = 0u64;
    let mut next = 0usize;
    let mut held = 0u64;
    while verdicts.len() < expected_ids.len() || next < schedule.len() {
        cycle += 1;
        if cycle > input_cycles + latency + 16 + held {
            bail!(
                "{} of {} verdicts after {} cycles (inputs {}, latency {}, held {})",
                verdicts.len(),
                expected_ids.len(),
                cycle - 1,
                input_cycles,
                latency,
                held
            );
        }
        let input = schedule.get(next).copied().unwrap_or_default();
        pipeline.set_input(&input);
        let hold = pipeline.hold();
        if hold {
            held += 1;
        } else {
            next += 1;
        }
        clock(pipeline, &mut trace)?;
        // A held edge leaves the outputs as they were.
        let out = pipeline.output();
        if out.valid && !hold {
            verdicts.push(PairVerdict {
                base_id: out.base_id,
                stream_id: out.stream_id,
                hit: out.hit,
                certain: out.certain,
            });
            last_output_cycle = cycle + 1;
        }
    }
    trace.finish()?;
    if verdicts.len() != expected_ids.len() {
        bail!(
            "{} verdicts, expected {}",
            verdicts.len(),
            expected_ids.len()
        );
    }
    for (i, (&(b, s), v)) in expected_ids.iter().zip(&verdicts).enumerate() {
        if (v.base_id, v.stream_id) != (b, s) {
            bail!(
                "verdict {i} carries ids ({}, {}), expected ({b}, {s})",
                v.base_id,
                v.stream_id
            );
        }
    }
    let cycles = if expected_ids.is_empty() {
        input_cycles + held
    } else {
        last_output_cycle
    };
    Ok(StreamResult {
        verdicts,
        cycles,
        held,
    })
}
