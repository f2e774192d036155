//! The place-and-route flow runs in CI on one small unit: the owner filter
//! with 256 slots per table (two tables of 256 x 72 bits in block RAM and
//! a small state machine), through Yosys synth_ecp5 and nextpnr-ecp5 out
//! of context. It must route, report a clock and its critical path, and
//! put the tables in EBR.

use tritri_rtl::emit::owner_filter_unit::emit_owner_filter;
use tritri_rtl::route::{route_ecp5, Ecp5Options};

#[test]
fn a_small_unit_places_and_routes_on_ecp5() {
    let design = emit_owner_filter(256).unwrap();
    let dir = std::path::PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("route-ecp5-owner-filter");
    let _ = std::fs::remove_dir_all(&dir);
    design.write_to(&dir).unwrap();
    let report = route_ecp5(&dir, &design.top, &Ecp5Options::default()).unwrap_or_else(|e| panic!("{e}"));
    eprintln!("{}", tritri_rtl::route::route_table(std::slice::from_ref(&report)));
    assert!(report.fmax_mhz > 10.0 && report.fmax_mhz < 500.0, "{report:?}");
    assert!(report.block_rams >= 2 && report.luts > 50 && report.flip_flops > 50 && report.multipliers == 0, "{report:?}");
    let path = report.critical_path.expect("a critical path");
    assert!(path.logic_levels >= 1 && path.logic_ns > 0.0, "{path:?}");
    assert!(dir.join("route_ecp5.log").is_file() && dir.join("tritri_owner_filter_s256.ecp5.json").is_file());
}
