//! `tritri classify --arith fixed --grid-verdicts --engine E` prints the
//! same grid verdicts from the software model, the rust-hdl pipeline and
//! the emitted Verilog in Icarus and Verilator, on pairs that include
//! touching, coplanar and degenerate ones; `--vcd FILE` writes a waveform
//! from every hardware engine.

use std::process::Command;

fn classify(file: &std::path::Path, engine: &str, extra: &[&str]) -> String {
    let out = Command::new(env!("CARGO_BIN_EXE_tritri"))
        .args([
            "classify",
            "--arith",
            "fixed",
            "--width",
            "16",
            "--grid-verdicts",
            "--engine",
            engine,
        ])
        .args(extra)
        .arg(file)
        .output()
        .expect("running tritri");
    assert!(
        out.status.success(),
        "engine {engine}: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8(out.stdout).unwrap()
}

const PAIRS: [&str; 6] = [
    "0 0 0 1 0 0 0 1 0  0 0 0 0 0 1 1 1 1", // shared vertex
    "0 0 0 2 0 0 0 2 0  1 1 0 3 1 0 1 3 0", // coplanar, touching at a vertex
    "0 0 0 2 0 0 0 2 0  3 3 0 4 3 0 3 4 0", // coplanar, apart
    "0 0 0 1 1 1 2 2 2  0 0 1 1 0 0 0 1 0", // degenerate segment through a triangle
    "0 0 0 1 0 0 0 1 0  0.2 0.2 0.5 0.3 0.2 -0.5 0.2 0.3 0.5", // crossing
    "0 0 0 1 0 0 0 1 0  0 0 0.001 1 0 0.001 0 1 0.001", // parallel near miss
];

fn pair_file(label: &str) -> std::path::PathBuf {
    let file = std::env::temp_dir().join(format!(
        "tritri-classify-{label}-{}.txt",
        std::process::id()
    ));
    std::fs::write(&file, PAIRS.join("\n")).unwrap();
    file
}

#[test]
fn every_engine_gives_the_model_verdicts() {
    let file = pair_file("engines");
    let model = classify(&file, "model", &[]);
    assert_eq!(model.lines().count(), PAIRS.len());
    assert!(
        model.contains('1') && model.contains('0'),
        "the set has both verdicts: {model}"
    );
    for engine in ["rusthdl", "icarus", "verilator"] {
        assert_eq!(classify(&file, engine, &[]), model, "engine {engine}");
    }
    std::fs::remove_file(&file).ok();
}

/// Every hardware engine writes a VCD that declares the pipeline's ports and
/// has a time step for each clock edge of the run (6 pairs: 12 input cycles,
/// plus the latency), and gives the same verdicts as without it.
#[test]
fn vcd_from_every_hardware_engine() {
    let file = pair_file("vcd");
    let model = classify(&file, "model", &[]);
    for engine in ["rusthdl", "icarus", "verilator"] {
        let vcd = std::env::temp_dir().join(format!(
            "tritri-classify-{engine}-{}.vcd",
            std::process::id()
        ));
        let verdicts = classify(&file, engine, &["--vcd", vcd.to_str().unwrap()]);
        assert_eq!(verdicts, model, "engine {engine} with --vcd");
        let text = std::fs::read_to_string(&vcd)
            .unwrap_or_else(|e| panic!("{engine}: {}: {e}", vcd.display()));
        assert!(text.contains("$enddefinitions"), "{engine}: no VCD header");
        for port in ["in_bset", "in_x0", "out_hit", "out_stream_id"] {
            assert!(
                text.contains(port),
                "{engine}: the VCD does not name {port}"
            );
        }
        let steps = text.lines().filter(|l| l.starts_with('#')).count();
        assert!(steps >= 12 + 30, "{engine}: {steps} time steps");
        std::fs::remove_file(&vcd).ok();
    }
    let out = Command::new(env!("CARGO_BIN_EXE_tritri"))
        .args(["classify", "--arith", "fixed", "--vcd", "x.vcd"])
        .arg(&file)
        .output()
        .unwrap();
    std::fs::remove_file(&file).ok();
    assert_eq!(out.status.code(), Some(2));
    assert!(
        String::from_utf8_lossy(&out.stderr).contains("--vcd x.vcd"),
        "the error names the option"
    );
}

/// A width the model takes but no pipeline is generated for is a usage
/// error (exit 2) that names the width, before any simulation runs.
#[test]
fn hardware_engines_refuse_widths_without_a_pipeline() {
    let file = pair_file("width");
    for engine in ["rusthdl", "icarus", "verilator"] {
        let out = Command::new(env!("CARGO_BIN_EXE_tritri"))
            .args([
                "classify", "--arith", "fixed", "--width", "9", "--engine", engine,
            ])
            .arg(&file)
            .output()
            .unwrap();
        assert_eq!(out.status.code(), Some(2), "engine {engine}");
        assert!(
            String::from_utf8_lossy(&out.stderr).contains("--width 9"),
            "engine {engine}: the error names the width"
        );
        assert!(out.stdout.is_empty(), "engine {engine}: no verdicts");
    }
    std::fs::remove_file(&file).ok();
}
