//! Co-simulation of the shared rare-case unit ([`tritri_rtl::pipeline::
//! shared_rare_cases`]): the pairs the pipeline sends to a rare test
//! (coplanar, a segment in the other's plane, two segments) offered one
//! after another, each held until the unit takes it, through
//! the rust-hdl model and the emitted Verilog in Icarus and Verilator.
//!
//! Vectors: one job per line, `segments axis n1 n2 ends` then the 18
//! coordinates (T1's vertices, then T2's), in hex: `n1`, `n2` the normals'
//! flags (negative at bit `k`, zero at bit `3 + k`), `ends` T1's low and
//! high, T2's low and high vertex at 2 bits each. Outputs: `taken EDGE` for
//! every job the unit takes, `done EDGE HIT` for every verdict (edges
//! counted from 0, the first at which a job is offered).

use crate::simulator::{compile, run_on_vectors, Simulator, Testbench};
use anyhow::{bail, Context as _};
use rust_hdl::prelude::*;
use tritri_geom::devillers_guigue::hulls_intersect_2d;
use tritri_geom::fixed_point::{cross, dominant_axis, intersects, FixedPoint, FixedTriangle};
use tritri_geom::kernel::ExactKernel;
use tritri_rtl::arith::convert::from_i128;
use tritri_rtl::emit::dsp_mapping::MultiplierMapping;
use tritri_rtl::emit::shared_rare_cases_unit::{emit_shared_rare_cases, shared_rare_cases_name};
use tritri_rtl::pipeline::shared_rare_cases::{SharedRareCases, IN_VALID_COPIES};
use tritri_rtl::sim_drive::{clock_cycle, reset_one_clock, settle};
use tritri_rtl::system::rare_case_model::{degenerate, rare_kind, RareKind};

/// One pair for the unit, with what its ports carry.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct RareJob {
    /// Two degenerate triangles (else a coplanar pair, T1 proper).
    pub segments: bool,
    pub t1: FixedTriangle,
    pub t2: FixedTriangle,
}

impl RareJob {
    /// The job for a pair the pipeline's decision sends to a rare test
    /// (`rare_case_model::rare_kind`: coplanar, a segment in the other's
    /// plane, or two segments).
    pub fn of(t1: FixedTriangle, t2: FixedTriangle) -> Option<RareJob> {
        rare_kind(&t1, &t2).map(|kind| RareJob {
            segments: kind == RareKind::Segments,
            t1,
            t2,
        })
    }

    /// The projection's axis, as the pipeline picks it: the largest
    /// normal component of the proper triangle (T1's unless T1 is
    /// degenerate).
    pub fn axis(&self) -> usize {
        let proper = if degenerate(&self.t1) {
            &self.t2
        } else {
            &self.t1
        };
        dominant_axis(normal(proper).map(|c| c.unsigned_abs()))
    }

    /// The model's verdict: the exact test on the grid for a coplanar job
    /// (the pipeline's verdict is the coplanar test's there), the segments
    /// meeting in all three projections for two segments (the pipeline
    /// adds `[a, b, c, d] == 0` from its orient3d unit).
    pub fn expected(&self) -> bool {
        if self.segments {
            let ((a, b), (c, d)) = (lexicographic_ends(&self.t1), lexicographic_ends(&self.t2));
            (0..3).all(|axis| {
                hulls_intersect_2d::<FixedPoint>(
                    axis,
                    &[self.t1[a], self.t1[b]],
                    &[self.t2[c], self.t2[d]],
                )
            })
        } else {
            intersects(&self.t1, &self.t2)
        }
    }

    /// The normals' flags: negative at bit `k`, zero at bit `3 + k`.
    fn normal_flags(t: &FixedTriangle) -> u32 {
        let n = normal(t);
        (0..3).fold(0, |f, k| {
            f | ((n[k] < 0) as u32) << k | ((n[k] == 0) as u32) << (3 + k)
        })
    }

    /// T1's low and high, T2's low and high vertex, 2 bits each.
    fn ends(&self) -> u32 {
        let ((a, b), (c, d)) = (lexicographic_ends(&self.t1), lexicographic_ends(&self.t2));
        (a | b << 2 | c << 4 | d << 6) as u32
    }
}

fn normal(t: &FixedTriangle) -> [i128; 3] {
    let [p, q, r] = *t;
    cross(
        std::array::from_fn(|k| q[k] - p[k]),
        std::array::from_fn(|k| r[k] - p[k]),
    )
}

/// Indices of the lexicographically smallest and largest vertex, the first
/// on ties (the pipeline's segment ends).
fn lexicographic_ends(t: &FixedTriangle) -> (usize, usize) {
    let order = |i: usize, j: usize| FixedPoint::compare_lexicographic(t[i], t[j]);
    let low = (1..3).fold(0, |lo, i| if order(i, lo).is_lt() { i } else { lo });
    let high = (1..3).fold(0, |hi, i| if order(i, hi).is_gt() { i } else { hi });
    (low, high)
}

/// What a run gives: the edge at which each job was taken, and each
/// verdict with its edge.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct RareRun {
    pub taken: Vec<u64>,
    pub verdicts: Vec<(u64, bool)>,
}

/// The jobs through the rust-hdl model at W = 16, offered back to back.
pub fn run_rusthdl(jobs: &[RareJob]) -> RareRun {
    let mut uut = SharedRareCases::<16, 17, 33>::default();
    uut.connect_all();
    reset_one_clock(&mut uut, |u| &mut u.reset, |u| &mut u.clock);
    let mut run = RareRun::default();
    let (mut next, mut edge) = (0usize, 0u64);
    while run.verdicts.len() < jobs.len() {
        assert!(
            edge < 10 * jobs.len() as u64 + 100,
            "no verdicts after {edge} edges"
        );
        uut.in_valid.next = next < jobs.len();
        for copy in uut.in_valid_copies.iter_mut() {
            copy.next = next < jobs.len();
        }
        if let Some(job) = jobs.get(next) {
            uut.in_segments.next = job.segments;
            for i in 0..9 {
                uut.t1_vertices[i].next = from_i128(job.t1[i / 3][i % 3] as i128);
                uut.t2_vertices[i].next = from_i128(job.t2[i / 3][i % 3] as i128);
            }
            uut.axis.next = (job.axis() as u64).into();
            let (n1, n2) = (
                RareJob::normal_flags(&job.t1),
                RareJob::normal_flags(&job.t2),
            );
            for k in 0..3 {
                uut.t1_normal_negative[k].next = n1 >> k & 1 == 1;
                uut.t1_normal_zero[k].next = n1 >> (3 + k) & 1 == 1;
                uut.t2_normal_negative[k].next = n2 >> k & 1 == 1;
                uut.t2_normal_zero[k].next = n2 >> (3 + k) & 1 == 1;
            }
            let ends = job.ends() as u64;
            uut.t1_segment_low.next = (ends & 3).into();
            uut.t1_segment_high.next = (ends >> 2 & 3).into();
            uut.t2_segment_low.next = (ends >> 4 & 3).into();
            uut.t2_segment_high.next = (ends >> 6 & 3).into();
        }
        settle(&mut uut);
        if uut.done.val() {
            run.verdicts.push((edge, uut.hit.val()));
        }
        if uut.in_valid.val() && uut.ready.val() {
            run.taken.push(edge);
            next += 1;
        }
        clock_cycle(&mut uut, |u| &mut u.clock);
        edge += 1;
    }
    run
}

/// The jobs through the emitted unit at W = 16 in `simulator`.
pub fn run_emitted(jobs: &[RareJob], simulator: Simulator) -> anyhow::Result<RareRun> {
    let design = emit_shared_rare_cases(16, MultiplierMapping::Inferred)?;
    let mut files = vec![("tb_shared_rare_cases.sv".to_string(), testbench())];
    files.extend(
        design
            .verilog_files()
            .map(|f| (f.path.clone(), f.contents.clone())),
    );
    let bench = Testbench {
        top: "tb_shared_rare_cases".into(),
        files,
        defines: vec![],
        parameters: vec![],
        c_optimization: 2,
        trace: false,
    };
    let compiled = compile(simulator, &bench)?;
    let mut vectors = String::new();
    for job in jobs {
        vectors += &format!(
            "{:x} {:x} {:x} {:x} {:x}",
            job.segments as u8,
            job.axis(),
            RareJob::normal_flags(&job.t1),
            RareJob::normal_flags(&job.t2),
            job.ends()
        );
        for t in [&job.t1, &job.t2] {
            for v in t {
                for c in v {
                    vectors += &format!(" {:x}", (*c as u64) & 0xffff);
                }
            }
        }
        vectors += "\n";
    }
    let (text, _) = run_on_vectors(&compiled, "shared-rare-cases-run", &vectors, &[])?;
    let mut run = RareRun::default();
    for line in text.lines() {
        let number = |s: &str| {
            s.parse::<u64>()
                .with_context(|| format!("`{s}` in `{line}`"))
        };
        match line.split_whitespace().collect::<Vec<_>>().as_slice() {
            ["taken", edge] => run.taken.push(number(edge)?),
            ["done", edge, hit] => run.verdicts.push((number(edge)?, number(hit)? == 1)),
            _ => bail!(
                "shared rare-case output line `{line}` is neither `taken EDGE` nor `done EDGE HIT`"
            ),
        }
    }
    if run.verdicts.len() != jobs.len() {
        bail!(
            "the shared rare-case unit gave {} verdicts for {} jobs",
            run.verdicts.len(),
            jobs.len()
        );
    }
    Ok(run)
}

/// The testbench: each job offered until taken (the next put on at the
/// falling edge after), every verdict with its edge, until all are out.
fn testbench() -> String {
    let open_files = crate::simulator::OPEN_VECTOR_FILES;
    let top = shared_rare_cases_name(16);
    let mut ports = String::new();
    for c in 0..IN_VALID_COPIES {
        ports += &format!(".in_valid_copies_{c}(in_valid), ");
    }
    for t in ["t1", "t2"] {
        for i in 0..9 {
            ports += &format!(".{t}_vertices_{i}({t}_v[{i}]), ");
        }
        for k in 0..3 {
            ports += &format!(
                ".{t}_normal_negative_{k}({t}_n[{k}]), .{t}_normal_zero_{k}({t}_n[{}]), ",
                3 + k
            );
        }
    }
    format!(
        "\
// Generated by tritri-cosim: the shared rare-case unit, one job per vector line.
`timescale 1ns/1ps
module tb_shared_rare_cases;
    reg clock = 1'b0;
    reg reset = 1'b1;
    reg in_valid = 1'b0;
    reg segments = 1'b0;
    reg [1:0] axis = 2'd0;
    reg [5:0] t1_n = 6'd0, t2_n = 6'd0;
    reg [7:0] ends = 8'd0;
    reg [15:0] t1_v [0:8];
    reg [15:0] t2_v [0:8];
    wire ready, done, hit;
    reg [63:0] edge_count = 64'd0, base = 64'd0;
    integer vectors, outputs, r, i, taken, jobs, verdicts;
    reg [8*4096-1:0] vectors_path, outputs_path;
    {top} dut (
        .clock(clock), .reset(reset), .in_valid(in_valid), .in_segments(segments),
        {ports}.axis(axis),
        .t1_segment_low(ends[1:0]), .t1_segment_high(ends[3:2]),
        .t2_segment_low(ends[5:4]), .t2_segment_high(ends[7:6]),
        .ready(ready), .done(done), .hit(hit)
    );
    always #5 clock = ~clock;
    always @(posedge clock) edge_count <= edge_count + 64'd1;

    task next_job;
        begin
            r = $fscanf(vectors, \"%h %h %h %h %h\", segments, axis, t1_n, t2_n, ends);
            in_valid = (r == 5);
            for (i = 0; i < 9; i = i + 1) r = $fscanf(vectors, \"%h\", t1_v[i]);
            for (i = 0; i < 9; i = i + 1) r = $fscanf(vectors, \"%h\", t2_v[i]);
            if (in_valid) jobs = jobs + 1;
        end
    endtask

    initial begin
{open_files}
        jobs = 0;
        verdicts = 0;
        repeat (2) @(negedge clock);
        reset = 1'b0;
        // The next rising edge is edge 0.
        base = edge_count;
        next_job;
        while (in_valid || verdicts < jobs) begin
            if (done) begin
                $fwrite(outputs, \"done %0d %0d\\n\", edge_count - base, hit);
                verdicts = verdicts + 1;
            end
            taken = in_valid && ready;
            if (taken != 0) $fwrite(outputs, \"taken %0d\\n\", edge_count - base);
            @(negedge clock);
            if (taken != 0) next_job;
        end
        $fclose(outputs);
        $finish;
    end
endmodule
"
    )
}
