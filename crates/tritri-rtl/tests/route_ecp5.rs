//! The place-and-route flow runs in CI on one small unit: the owner filter
//! with 256 slots per table (two tables of 256 x 72 bits in block RAM and
//! a small state machine), through Yosys synth_ecp5 and nextpnr-ecp5 out
//! of context. It must route, report a clock and its critical path, and
//! put the tables in EBR.

use tritri_rtl::emit::dsp_mapping::MultiplierMapping;
use tritri_rtl::emit::owner_filter_unit::emit_owner_filter;
use tritri_rtl::pipeline::pipeline_unit::emit_pipeline_with;
use tritri_rtl::route::{route_ecp5, Ecp5Options};

#[test]
fn a_small_unit_places_and_routes_on_ecp5() {
    let design = emit_owner_filter(256).unwrap();
    let dir = std::path::PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("route-ecp5-owner-filter");
    let _ = std::fs::remove_dir_all(&dir);
    design.write_to(&dir).unwrap();
    // As `tritri gen --synth ecp5` routes an emitted top: router1. (router2
    // with timing-driven rip-up goes on to its iteration limit, over a
    // thousand passes and a quarter of an hour, on a unit that misses the
    // 150 MHz target, as this one does at about 50 MHz.)
    let report = route_ecp5(&dir, &design.top, &Ecp5Options::whole_design())
        .unwrap_or_else(|e| panic!("{e}"));
    eprintln!(
        "{}",
        tritri_rtl::route::route_table(std::slice::from_ref(&report))
    );
    assert!(
        report.fmax_mhz > 10.0 && report.fmax_mhz < 500.0,
        "{report:?}"
    );
    assert!(
        report.block_rams >= 2
            && report.luts > 50
            && report.flip_flops > 50
            && report.multipliers == 0,
        "{report:?}"
    );
    let path = report.critical_path.expect("a critical path");
    assert!(path.logic_levels >= 1 && path.logic_ns > 0.0, "{path:?}");
    let netlist = dir.join("tritri_owner_filter_s256.ecp5.json");
    assert!(dir.join("route_ecp5.log").is_file() && netlist.is_file());
    // nextpnr wrote under the partial names; a finished route renames them.
    assert!(dir.join("route_ecp5.json").is_file());
    for partial in ["route_ecp5.partial.log", "route_ecp5.partial.json"] {
        assert!(!dir.join(partial).exists(), "{partial} left behind");
    }
    // The state machine's synchronous reset is data-input logic, not the
    // flip-flops' LSR (route::FLIP_FLOPS_WITHOUT_SYNC_RESET).
    let (flip_flops, with_reset) = flip_flops_and_those_with_reset(&netlist);
    assert!(
        flip_flops > 50 && with_reset == 0,
        "{with_reset} of {flip_flops} flip-flops use LSR"
    );
}

/// Yosys' ECP5 netlist: its `TRELLIS_FF` cells, and those whose LSR input
/// is a net rather than a constant.
fn flip_flops_and_those_with_reset(netlist: &std::path::Path) -> (usize, usize) {
    let text = std::fs::read_to_string(netlist).unwrap();
    let json: serde_json::Value = serde_json::from_str(&text).unwrap();
    let mut counts = (0, 0);
    for module in json["modules"].as_object().unwrap().values() {
        let Some(cells) = module["cells"].as_object() else {
            continue;
        };
        for cell in cells.values().filter(|c| c["type"] == "TRELLIS_FF") {
            counts.0 += 1;
            // A constant bit is the string "0" or "1", a net a number.
            if cell["connections"]["LSR"]
                .as_array()
                .is_some_and(|bits| bits.iter().any(|b| b.is_number()))
            {
                counts.1 += 1;
            }
        }
    }
    counts
}

/// `--dsp ecp5`: the W = 16 pipeline's wide multiplier (17 x 33 -> 50
/// bits), routed on its own, takes two MULT18X18D blocks holding its
/// operand, pipeline and output registers; the only flip-flops left in
/// fabric are the 50 of the product that adds the two halves. Inferred,
/// the same module keeps its operand and product registers in fabric.
#[test]
fn ecp5_multipliers_keep_their_registers_in_the_dsp_blocks() {
    let module = "tritri_pipeline_w16_multiplier_w50";
    let mut flip_flops = Vec::new();
    for (mapping, name) in [
        (MultiplierMapping::Ecp5, "ecp5"),
        (MultiplierMapping::Inferred, "inferred"),
    ] {
        let design = emit_pipeline_with(16, mapping).unwrap();
        assert!(
            design.modules.iter().any(|m| m == module),
            "{module} is emitted"
        );
        let dir = std::path::PathBuf::from(env!("CARGO_TARGET_TMPDIR"))
            .join(format!("route-ecp5-multiplier-{name}"));
        let _ = std::fs::remove_dir_all(&dir);
        design.write_to(&dir).unwrap();
        let report = route_ecp5(&dir, module, &Ecp5Options::default())
            .unwrap_or_else(|e| panic!("{name}: {e}"));
        eprintln!(
            "{name}: {}",
            tritri_rtl::route::route_table(std::slice::from_ref(&report))
        );
        assert_eq!(report.multipliers, 2, "{name}: {report:?}");
        flip_flops.push(report.flip_flops);
    }
    assert_eq!(
        flip_flops[0], 50,
        "ecp5: only the product register is in fabric"
    );
    assert!(
        flip_flops[1] >= 17 + 33 + 50 + 50,
        "inferred: operands, product and two more stages in fabric: {flip_flops:?}"
    );
}
