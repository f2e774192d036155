//! The emitted octree classifier step: lint-clean under
//! `verilator --lint-only -Wall` and compiled by Icarus at every grid
//! width, following the emitter's naming conventions. (Its behaviour is
//! co-simulated in tritri-cosim's tests/cell_classifier.rs.)

use tritri_rtl::emit::cell_classifier_unit::{emit_cell_classifier, CLASSIFIER_GRID_WIDTHS};
use tritri_rtl::tools::{run, IVERILOG};

#[test]
fn every_grid_width_is_lint_clean() {
    for &g in &CLASSIFIER_GRID_WIDTHS {
        let design = emit_cell_classifier(g).unwrap();
        let dir = std::env::temp_dir().join(format!("tritri-emit-classifier-{}-g{g}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        design.write_to(&dir).unwrap();
        let messages = tritri_rtl::tools::lint(&dir, &design.top).unwrap_or_else(|e| panic!("G={g}: {e}"));
        assert!(messages.trim().is_empty(), "G={g}: verilator said:\n{messages}");
        run(IVERILOG.command().unwrap().current_dir(&dir).args(["-g2012", "-o", "/dev/null", "-c", "filelist.f"]))
            .unwrap_or_else(|e| panic!("G={g}: {e}"));
        for f in design.verilog_files() {
            assert!(f.path.starts_with(&design.top), "{}", f.path);
            assert!(!f.contents.replace("$signed", "").contains('$'), "{}: a `$` is left", f.path);
        }
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
