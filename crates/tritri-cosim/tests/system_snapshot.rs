//! Snapshot of the emitted system Verilog (W = 24, P = 2, depth 64, result
//! FIFO of 8 words): the modules of the system itself (top, address
//! generator, memories and their columns, result FIFO, pair serializer),
//! and the list of all modules. The pipeline's modules are left out: the
//! pipeline has its own snapshot. Any change to the emitted system RTL
//! shows up here for review. And the emitted system is lint-clean.

use tritri_rtl::system::system_for_width::PipelineKind;
use tritri_rtl::system::system_unit::emit_system;
use tritri_rtl::system::SystemConfig;

#[test]
fn emitted_system_w24_p2_d64() {
    let config = SystemConfig::new(24, 2)
        .with_depth(64)
        .with_result_fifo_room(8);
    let design = emit_system(config, PipelineKind::Parallel).unwrap();
    assert_eq!(design.top, "tritri_system_w24_p2_d64");
    let system_module = |path: &str| {
        path == format!("{}.v", design.top)
            || [
                "address_generator",
                "memory",
                "simple_dual_port_ram",
                "result_fifo",
                "pair_serializer",
            ]
            .iter()
            .any(|part| path.contains(part))
    };
    let mut text = format!("// modules: {}\n", design.modules.join(" "));
    for f in design.verilog_files().filter(|f| system_module(&f.path)) {
        text.push_str(&format!("// ===== {} =====\n{}\n", f.path, f.contents));
    }
    insta::assert_snapshot!(text);
}

/// `verilator --lint-only -Wall` and `slang -Weverything` print nothing on
/// the emitted system with 1, 2 and 4 pipelines, with the rare cases in
/// each pipeline and on shared units (whose pipelines hold together
/// through each other's requests), and Icarus compiles it.
#[test]
fn emitted_system_is_lint_clean() {
    use tritri_rtl::tools::{lint, run, IVERILOG};
    for (kind, pipelines) in [1, 2, 4]
        .map(|p| (PipelineKind::Parallel, p))
        .into_iter()
        .chain([1, 2].map(|p| (PipelineKind::Shared, p)))
    {
        let config = SystemConfig::new(8, pipelines).with_depth(16);
        let design = emit_system(config, kind).unwrap();
        let dir = std::env::temp_dir().join(format!(
            "tritri-system-lint-{}-{kind:?}-{pipelines}",
            std::process::id()
        ));
        let _ = std::fs::remove_dir_all(&dir);
        design.write_to(&dir).unwrap();
        let messages =
            lint(&dir, &design.top).unwrap_or_else(|e| panic!("{kind:?}, P={pipelines}: {e}"));
        assert!(
            messages.trim().is_empty(),
            "{kind:?}, P={pipelines}: verilator said:\n{messages}"
        );
        let messages = tritri_rtl::tools::slang_lint(&dir, &design.top)
            .unwrap_or_else(|e| panic!("{kind:?}, P={pipelines}: {e}"));
        assert!(
            messages.is_empty(),
            "{kind:?}, P={pipelines}: slang -Weverything said:\n{messages}"
        );
        run(IVERILOG.command().unwrap().current_dir(&dir).args([
            "-g2012",
            "-o",
            "/dev/null",
            "-c",
            "filelist.f",
        ]))
        .unwrap_or_else(|e| panic!("{kind:?}, P={pipelines}: {e}"));
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
