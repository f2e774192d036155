//! The vectors reach the simulators through a named pipe that a thread
//! fills as they read (`simulator::run_on_vector_stream`): every line
//! arrives, the testbench's lines are seen as it prints them, and a
//! testbench that stops early, or never opens the pipe, ends the run with
//! an error instead of a hang.

use std::sync::atomic::{AtomicU64, Ordering};
use std::time::Instant;
use tritri_cosim::simulator::{compile, run_on_vector_stream, Simulator, Testbench};

/// Counts the vector lines (one hex number each) and their sum; prints
/// `# progress N` every 1000 lines. `+stop=K` stops after K lines, and
/// `+never` ends without opening the vectors.
const COUNTER: &str = r##"
module tb_counter;
    integer vectors, outputs, lines = 0, stop = 0;
    reg [31:0] value;
    reg [63:0] sum = 64'd0;
    reg [8*4096-1:0] vectors_path, outputs_path;
    // (Verilator goes on after $finish to the end of the block: so else.)
    initial begin
        if ($test$plusargs("never")) begin
            $finish;
        end else if (!$value$plusargs("vectors=%s", vectors_path) || !$value$plusargs("outputs=%s", outputs_path)) begin
            $display("usage: +vectors=FILE +outputs=FILE");
            $finish;
        end else begin
            if (!$value$plusargs("stop=%d", stop)) stop = 0;
            vectors = $fopen(vectors_path, "r");
            outputs = $fopen(outputs_path, "w");
            while ($fscanf(vectors, "%h", value) == 1 && (stop == 0 || lines < stop)) begin
                lines = lines + 1;
                sum = sum + value;
                if (lines % 1000 == 0) begin
                    $display("# progress %0d", lines);
                    $fflush();
                end
            end
            $fwrite(outputs, "%0d %0d\n", lines, sum);
            $fclose(outputs);
            $finish;
        end
    end
endmodule
"##;

fn bench() -> Testbench {
    Testbench {
        top: "tb_counter".into(),
        files: vec![("tb_counter.v".into(), COUNTER.into())],
        defines: vec![],
        parameters: vec![],
        c_optimization: 1,
        trace: false,
    }
}

#[test]
fn every_line_arrives_and_progress_is_seen_as_it_is_printed() {
    for simulator in [Simulator::Icarus, Simulator::Verilator] {
        let compiled = compile(simulator, &bench()).unwrap();
        // 300,000 lines: more than a pipe holds many times over.
        let n = 300_000u64;
        let mut write =
            |out: &mut dyn std::io::Write| (0..n).try_for_each(|k| writeln!(out, "{k:x}"));
        let reports = AtomicU64::new(0);
        let mut on_line = |line: &str| {
            if line.starts_with("# progress ") {
                reports.fetch_add(1, Ordering::Relaxed);
            }
        };
        let (text, _) =
            run_on_vector_stream(&compiled, "stream-test", &mut write, &[], &mut on_line).unwrap();
        assert_eq!(
            text.trim(),
            format!("{n} {}", n * (n - 1) / 2),
            "{simulator:?}"
        );
        assert_eq!(reports.load(Ordering::Relaxed), n / 1000, "{simulator:?}");
    }
}

#[test]
fn a_testbench_that_stops_early_or_never_reads_ends_the_run() {
    for simulator in [Simulator::Icarus, Simulator::Verilator] {
        let compiled = compile(simulator, &bench()).unwrap();
        for plusarg in ["+stop=10", "+never"] {
            let started = Instant::now();
            let mut write = |out: &mut dyn std::io::Write| {
                (0..1_000_000u64).try_for_each(|k| writeln!(out, "{k:x}"))
            };
            let result = run_on_vector_stream(
                &compiled,
                "stream-test",
                &mut write,
                &[plusarg.to_string()],
                &mut |_| {},
            );
            assert!(
                result.is_err(),
                "{simulator:?} {plusarg}: the vectors were not all read, yet {result:?}"
            );
            assert!(
                started.elapsed().as_secs() < 60,
                "{simulator:?} {plusarg}: took {:?}",
                started.elapsed()
            );
        }
    }
}
