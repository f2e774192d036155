//! The emitted octree classifier step, its setup, the binning unit, the
//! broad-phase top, the owner filter, the plane traversal, the triangle voxelizer and the
//! octree builder, the AXI4 port's copy unit and the pass over lists in
//! external memory:
//! lint-clean under `verilator --lint-only -Wall` and compiled by Icarus
//! at every grid width (table size for the filter), following the
//! emitter's naming conventions. (Their behaviour is co-simulated in
//! tritri-cosim's tests/cell_classifier.rs, tests/triangle_setup.rs and
//! tests/binning_unit.rs, tests/owner_filter.rs, tests/plane_traversal.rs,
//! tests/triangle_voxelizer.rs and tests/octree_builder.rs.)

use tritri_rtl::axi::DATA_WIDTHS;
use tritri_rtl::broad_phase::binning_machine::BinningParams;
use tritri_rtl::broad_phase::binning_unit::{BinningUnitConfig, BINNING_GRID_WIDTHS};
use tritri_rtl::broad_phase::dram_binning_machine::DramBinningConfig;
use tritri_rtl::broad_phase::dram_binning_unit::WAITING_CAPACITY;
use tritri_rtl::broad_phase::list_pass_machine::ListPassConfig;
use tritri_rtl::emit::axi_copy_unit::{emit_axi_copy, AxiCopyConfig};
use tritri_rtl::emit::binning_unit_unit::emit_binning_unit;
use tritri_rtl::emit::broad_phase_system_unit::{emit_broad_phase_system, BroadPhaseConfig};
use tritri_rtl::emit::cell_classifier_unit::{emit_cell_classifier, CLASSIFIER_GRID_WIDTHS};
use tritri_rtl::emit::dram_binning_unit_unit::emit_dram_binning;
use tritri_rtl::emit::leaf_reader_unit::emit_leaf_reader;
use tritri_rtl::emit::list_pass_unit::{emit_list_pass, LIST_PASS_GRID_WIDTHS};
use tritri_rtl::emit::octree_builder_unit::emit_octree_builder;
use tritri_rtl::emit::owner_filter_unit::emit_owner_filter;
use tritri_rtl::emit::plane_traversal_unit::emit_plane_traversal;
use tritri_rtl::emit::triangle_setup_unit::emit_triangle_setup;
use tritri_rtl::emit::triangle_voxelizer_unit::emit_triangle_voxelizer;
use tritri_rtl::emit::voxel_units::{emit_octant_clipper, emit_set_operation, emit_voxel_fill};
use tritri_rtl::emit::EmittedDesign;
use tritri_rtl::system::SystemConfig;
use tritri_rtl::tools::{run, IVERILOG};

#[test]
fn every_grid_width_is_lint_clean() {
    for &g in &CLASSIFIER_GRID_WIDTHS {
        check(g, emit_cell_classifier(g).unwrap());
        check(g, emit_triangle_setup(g).unwrap());
    }
}

#[test]
fn the_binning_unit_is_lint_clean_at_every_grid() {
    for &g in &BINNING_GRID_WIDTHS {
        // Memories that fill their address bits and memories that do not.
        let config = BinningUnitConfig {
            grid_bits: g,
            triangles: 1000,
            list_words: 4096,
            leaves: 300,
            log_depth: 8,
            log_pipelines: 1,
        };
        check(g, emit_binning_unit(&config).unwrap());
    }
}

#[test]
fn the_broad_phase_top_is_lint_clean_at_both_widths() {
    for w in [24, 16] {
        let unit = BinningUnitConfig {
            grid_bits: 24,
            triangles: 1000,
            list_words: 4096,
            leaves: 300,
            log_depth: 6,
            log_pipelines: 1,
        };
        let system = SystemConfig::new(w, 2).with_depth(64);
        check(
            w,
            emit_broad_phase_system(&BroadPhaseConfig {
                unit,
                system,
                slots: 5000,
                local_frames: w < 24,
            })
            .unwrap(),
        );
    }
}

#[test]
fn the_owner_filter_is_lint_clean() {
    // A table that fills its address bits, and one that does not.
    for slots in [1000, 65536] {
        check(slots, emit_owner_filter(slots).unwrap());
    }
}

#[test]
fn the_octree_engines_units_are_lint_clean() {
    check(0, emit_plane_traversal().unwrap());
    check(0, emit_set_operation().unwrap());
    check(0, emit_octant_clipper().unwrap());
    check(0, emit_voxel_fill().unwrap());
    check(0, emit_triangle_voxelizer().unwrap());
    check(0, emit_octree_builder().unwrap());
}

/// The emitted patch tessellator at W = 16, K = 3, for review: any change
/// to its Verilog shows up here.
#[test]
fn patch_tessellator_snapshot() {
    let design = tritri_rtl::emit::patch_tessellator_unit::emit_patch_tessellator(16, 3).unwrap();
    assert_eq!(
        design.modules,
        vec!["tritri_patch_tessellator_w16_k3".to_string()]
    );
    insta::assert_snapshot!(design.verilog_files().next().unwrap().contents.clone());
}

/// The emitted cone unit at W = 16, for review.
#[test]
fn cone_unit_snapshot() {
    let design = tritri_rtl::emit::cone_unit_unit::emit_cone_unit(16).unwrap();
    assert_eq!(design.modules, vec!["tritri_cone_unit_w16".to_string()]);
    insta::assert_snapshot!(design.verilog_files().next().unwrap().contents.clone());
}

/// The Bezier system's cone unit, at every W it is built for.
#[test]
fn the_cone_unit_is_lint_clean() {
    use tritri_rtl::emit::cone_unit_unit::{emit_cone_unit, CONE_UNIT_WIDTHS};
    for w in CONE_UNIT_WIDTHS {
        check(w, emit_cone_unit(w).unwrap());
    }
}

/// The Bezier system's patch tessellator, alone and with its triangles
/// assembled, at every (W, K) it is built for.
#[test]
fn the_patch_tessellator_is_lint_clean() {
    use tritri_rtl::emit::patch_tessellator_unit::emit_patch_triangles;
    use tritri_rtl::emit::patch_tessellator_unit::{
        emit_patch_tessellator, TESSELLATOR_CONFIGURATIONS,
    };
    for (w, k) in TESSELLATOR_CONFIGURATIONS {
        check(w, emit_patch_tessellator(w, k).unwrap());
        check(w, emit_patch_triangles(w, k).unwrap());
    }
}

#[test]
fn the_axi_copy_unit_is_lint_clean_at_every_data_width() {
    for &data_bits in &DATA_WIDTHS {
        let config = AxiCopyConfig {
            data_bits,
            max_burst: 256,
            outstanding: 8,
        };
        check(data_bits, emit_axi_copy(&config).unwrap());
    }
}

#[test]
fn the_list_pass_unit_is_lint_clean_at_every_grid_and_data_width() {
    for &grid_bits in &LIST_PASS_GRID_WIDTHS {
        for data_bits in [64, 128, 256] {
            let config = ListPassConfig {
                grid_bits,
                data_bits,
                max_read_burst: 16,
                outstanding: 4,
            };
            check(grid_bits, emit_list_pass(&config).unwrap());
        }
    }
}

#[test]
fn the_leaf_reader_is_lint_clean_at_every_grid_and_data_width() {
    for &grid_bits in &LIST_PASS_GRID_WIDTHS {
        for data_bits in [64, 128, 256] {
            let config = ListPassConfig {
                grid_bits,
                data_bits,
                max_read_burst: 16,
                outstanding: 4,
            };
            check(grid_bits, emit_leaf_reader(&config).unwrap());
        }
    }
}

#[test]
fn the_dram_binning_controller_is_lint_clean_at_both_grids() {
    for (grid_bits, data_bits, max_leaf_level) in [(24, 64, None), (16, 256, Some(20))] {
        let config = DramBinningConfig {
            pass: ListPassConfig {
                grid_bits,
                data_bits,
                max_read_burst: 16,
                outstanding: 4,
            },
            rule: BinningParams {
                log_depth: 8,
                log_pipelines: 1,
                max_leaf_level,
            },
            arena: (0, 1 << 24),
            waiting_capacity: WAITING_CAPACITY,
        };
        check(grid_bits, emit_dram_binning(&config).unwrap());
    }
}

fn check(g: usize, design: EmittedDesign) {
    {
        let dir =
            std::env::temp_dir().join(format!("tritri-emit-{}-{}", design.top, std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        design.write_to(&dir).unwrap();
        let messages =
            tritri_rtl::tools::lint(&dir, &design.top).unwrap_or_else(|e| panic!("G={g}: {e}"));
        assert!(
            messages.trim().is_empty(),
            "G={g}: verilator said:\n{messages}"
        );
        let messages = tritri_rtl::tools::slang_lint(&dir, &design.top)
            .unwrap_or_else(|e| panic!("G={g}: {e}"));
        assert!(messages.is_empty(), "G={g}: slang said:\n{messages}");
        run(IVERILOG.command().unwrap().current_dir(&dir).args([
            "-g2012",
            "-o",
            "/dev/null",
            "-c",
            "filelist.f",
        ]))
        .unwrap_or_else(|e| panic!("G={g}: {e}"));
        for f in design.verilog_files() {
            assert!(f.path.starts_with(&design.top), "{}", f.path);
            assert!(
                !f.contents
                    .replace("$signed", "")
                    .replace("$unsigned", "")
                    .contains('$'),
                "{}: a `$` is left",
                f.path
            );
        }
        std::fs::remove_dir_all(&dir).unwrap();
    }
}

/// The pipeline's shared rare-case unit, at W = 8, 16 and 24.
#[test]
fn the_shared_rare_case_unit_is_lint_clean() {
    use tritri_rtl::emit::dsp_mapping::MultiplierMapping;
    use tritri_rtl::emit::shared_rare_cases_unit::{
        emit_shared_rare_cases, SHARED_RARE_CASES_WIDTHS,
    };
    for w in SHARED_RARE_CASES_WIDTHS {
        check(
            w,
            emit_shared_rare_cases(w, MultiplierMapping::Inferred).unwrap(),
        );
    }
}
