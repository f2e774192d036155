//! The emitted pipeline's Verilog in Icarus or Verilator, with
//! `testbenches/tb_triangle_pipeline.sv`, on the vector files of
//! [`crate::vectors`]: the same schedules, the same [`StreamResult`] as the
//! rust-hdl harness ([`crate::rusthdl_harness`]).

use crate::simulator::{compile, run_on_vectors, Simulator, Testbench};
use crate::stream::{StreamResult, TriangleStream};
use crate::vectors::{parse_outputs, vectors, vectors_for_schedule, TimedVerdict};
use std::path::Path;
use tritri_rtl::emit::dsp_mapping::MultiplierMapping;
use tritri_rtl::emit::EmittedDesign;
use tritri_rtl::pipeline::pipeline_for_width::PipelineInput;
use tritri_rtl::pipeline::RareCasePath;

/// The testbench, compiled into the library so runs need no checkout.
pub const TESTBENCH: &str = include_str!("../../../testbenches/tb_triangle_pipeline.sv");
/// Its top module.
pub const TESTBENCH_TOP: &str = "tb_triangle_pipeline";

/// An emitted pipeline and the facts the testbench needs about it.
#[derive(Clone, Debug)]
pub struct RtlDut {
    pub design: EmittedDesign,
    /// Coordinate width W.
    pub width: u32,
    /// Width of the ids on the bus.
    pub id_bits: u32,
    /// Pipeline latency L.
    pub latency: u64,
    /// Where the rare pairs are tested; the shared unit's pipeline has a
    /// `hold` port, which the testbench follows (`TRITRI_HOLD`).
    pub rare_cases: RareCasePath,
}

impl RtlDut {
    /// The testbench around this pipeline.
    pub fn testbench(&self, trace: bool) -> Testbench {
        let mut files = vec![(format!("{TESTBENCH_TOP}.sv"), TESTBENCH.to_string())];
        files.extend(
            self.design
                .verilog_files()
                .map(|f| (f.path.clone(), f.contents.clone())),
        );
        Testbench {
            top: TESTBENCH_TOP.into(),
            files,
            defines: std::iter::once(format!("TRITRI_DUT={}", self.design.top))
                .chain((self.rare_cases == RareCasePath::Shared).then(|| "TRITRI_HOLD".into()))
                .collect(),
            parameters: vec![
                ("W".into(), self.width.to_string()),
                ("ID_WIDTH".into(), self.id_bits.to_string()),
            ],
            c_optimization: 2,
            trace,
        }
    }
}

/// One simulation run of emitted Verilog.
#[derive(Clone, Debug)]
pub struct RtlRun {
    pub result: StreamResult,
    /// Every verdict with the cycle it appeared in.
    pub timed: Vec<TimedVerdict>,
    /// Seconds spent compiling (0 for a cached Verilator build).
    pub build_seconds: f64,
    /// Seconds spent simulating (including reading and writing the files).
    pub simulate_seconds: f64,
}

/// The emitted `width`-bit pipeline as a DUT, emitted once per process.
pub fn pipeline_dut(width: usize) -> anyhow::Result<std::sync::Arc<RtlDut>> {
    pipeline_dut_with(width, MultiplierMapping::Inferred)
}

/// [`pipeline_dut`] with its multipliers mapped as `multipliers` says
/// (with `Ecp5`, the MULT18X18D instances run on the primitive's model).
pub fn pipeline_dut_with(
    width: usize,
    multipliers: MultiplierMapping,
) -> anyhow::Result<std::sync::Arc<RtlDut>> {
    pipeline_dut_for(width, multipliers, RareCasePath::Parallel)
}

/// [`pipeline_dut_with`] with the rare cases on `rare_cases`.
pub fn pipeline_dut_for(
    width: usize,
    multipliers: MultiplierMapping,
    rare_cases: RareCasePath,
) -> anyhow::Result<std::sync::Arc<RtlDut>> {
    use std::collections::HashMap;
    use std::sync::{Arc, Mutex, OnceLock};
    type Cache = Mutex<HashMap<(usize, MultiplierMapping, RareCasePath), Arc<RtlDut>>>;
    static CACHE: OnceLock<Cache> = OnceLock::new();
    let cache = CACHE.get_or_init(Default::default);
    if let Some(d) =
        cache
            .lock()
            .unwrap_or_else(|e| e.into_inner())
            .get(&(width, multipliers, rare_cases))
    {
        return Ok(d.clone());
    }
    let design =
        tritri_rtl::pipeline::pipeline_unit::emit_pipeline_for(width, multipliers, rare_cases)?;
    let dut = Arc::new(RtlDut {
        design,
        width: width as u32,
        id_bits: tritri_rtl::pipeline::ID_BITS as u32,
        latency: tritri_rtl::pipeline::triangle_pipeline::latency() as u64,
        rare_cases,
    });
    cache
        .lock()
        .unwrap_or_else(|e| e.into_inner())
        .insert((width, multipliers, rare_cases), dut.clone());
    Ok(dut)
}

/// Runs `stream` on `dut` in `simulator`.
pub fn run_stream(
    simulator: Simulator,
    dut: &RtlDut,
    stream: &TriangleStream,
) -> anyhow::Result<RtlRun> {
    run_vectors(
        simulator,
        dut,
        &vectors(stream, dut.width, dut.id_bits),
        None,
    )
}

/// Runs an arbitrary schedule of input cycles on the emitted `width`-bit
/// pipeline (see `rusthdl_harness::run_schedule_on`); with `vcd`, writes the
/// waveform of every signal there.
pub fn run_schedule(
    simulator: Simulator,
    width: usize,
    schedule: &[PipelineInput],
    vcd: Option<&Path>,
) -> anyhow::Result<RtlRun> {
    run_schedule_on(simulator, &*pipeline_dut(width)?, schedule, vcd)
}

/// [`run_schedule`] on `dut`.
pub fn run_schedule_on(
    simulator: Simulator,
    dut: &RtlDut,
    schedule: &[PipelineInput],
    vcd: Option<&Path>,
) -> anyhow::Result<RtlRun> {
    run_vectors(
        simulator,
        dut,
        &vectors_for_schedule(schedule, dut.width, dut.id_bits),
        vcd,
    )
}

fn run_vectors(
    simulator: Simulator,
    dut: &RtlDut,
    vector_text: &str,
    vcd: Option<&Path>,
) -> anyhow::Result<RtlRun> {
    let compiled = compile(simulator, &dut.testbench(vcd.is_some()))?;
    let extra: Vec<String> = vcd
        .map(|path| format!("+vcd={}", path.display()))
        .into_iter()
        .collect();
    let (text, simulate_seconds) = run_on_vectors(&compiled, "pipeline-run", vector_text, &extra)?;
    let (result, timed) = parse_outputs(&text)?;
    Ok(RtlRun {
        result,
        timed,
        build_seconds: compiled.build_seconds,
        simulate_seconds,
    })
}
