//! `tritri classify --arith fixed --engine E` prints the same verdicts from
//! the software model, the rust-hdl pipeline and the emitted Verilog in
//! Icarus, on pairs that include touching, coplanar and degenerate ones.

use std::process::Command;

fn classify(file: &std::path::Path, engine: &str) -> String {
    let out = Command::new(env!("CARGO_BIN_EXE_tritri"))
        .args(["classify", "--arith", "fixed", "--width", "16", "--engine", engine])
        .arg(file)
        .output()
        .expect("running tritri");
    assert!(out.status.success(), "engine {engine}: {}", String::from_utf8_lossy(&out.stderr));
    String::from_utf8(out.stdout).unwrap()
}

#[test]
fn every_engine_gives_the_model_verdicts() {
    let pairs = [
        "0 0 0 1 0 0 0 1 0  0 0 0 0 0 1 1 1 1",       // shared vertex
        "0 0 0 2 0 0 0 2 0  1 1 0 3 1 0 1 3 0",       // coplanar, touching at a vertex
        "0 0 0 2 0 0 0 2 0  3 3 0 4 3 0 3 4 0",       // coplanar, apart
        "0 0 0 1 1 1 2 2 2  0 0 1 1 0 0 0 1 0",       // degenerate segment through a triangle
        "0 0 0 1 0 0 0 1 0  0.2 0.2 0.5 0.3 0.2 -0.5 0.2 0.3 0.5", // crossing
        "0 0 0 1 0 0 0 1 0  0 0 0.001 1 0 0.001 0 1 0.001",       // parallel near miss
    ];
    let file = std::env::temp_dir().join(format!("tritri-classify-engines-{}.txt", std::process::id()));
    std::fs::write(&file, pairs.join("\n")).unwrap();
    let model = classify(&file, "model");
    assert_eq!(model.lines().count(), pairs.len());
    assert!(model.contains('1') && model.contains('0'), "the set has both verdicts: {model}");
    for engine in ["rusthdl", "icarus"] {
        assert_eq!(classify(&file, engine), model, "engine {engine}");
    }
    std::fs::remove_file(&file).ok();
}
