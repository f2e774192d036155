//! The emitted pipeline: lint-clean under `verilator --lint-only -Wall` at
//! every supported width (with either rare-case path), compiled by Icarus, synthesized by Yosys, and
//! snapshot-checked at W = 24 (rung 5 of the verification ladder: any
//! change to the emitted RTL shows up as a snapshot diff to review).
//!
//! A missing tool fails the test with the package to install.

use tritri_rtl::emit::dsp_mapping::MultiplierMapping;
use tritri_rtl::emit::{emit_pipeline, EmittedDesign};
use tritri_rtl::pipeline::pipeline_for_width::SUPPORTED_WIDTHS;
use tritri_rtl::pipeline::pipeline_unit::emit_pipeline_for;
use tritri_rtl::pipeline::RareCasePath;
use tritri_rtl::synth::{synthesize, Target};
use tritri_rtl::tools::{run, IVERILOG};

fn temp_dir(name: &str) -> std::path::PathBuf {
    let dir = std::env::temp_dir().join(format!(
        "tritri-emit-pipeline-{}-{name}",
        std::process::id()
    ));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn write(design: &EmittedDesign, name: &str) -> std::path::PathBuf {
    let dir = temp_dir(name);
    design.write_to(&dir).unwrap();
    dir
}

/// `verilator --lint-only -Wall` and `slang -Weverything` print nothing and
/// Icarus compiles, at every width, with the rare cases in parallel and on
/// the shared unit; the emitted files never contain a lint_off pragma.
#[test]
fn every_width_is_lint_clean() {
    for &width in SUPPORTED_WIDTHS {
        for rare_cases in [RareCasePath::Parallel, RareCasePath::Shared] {
            let design = emit_pipeline_for(width, MultiplierMapping::Inferred, rare_cases).unwrap();
            let what = format!("W={width}, {rare_cases:?}");
            let dir = write(&design, &format!("lint-w{width}-{rare_cases:?}"));
            let messages = tritri_rtl::tools::lint(&dir, &design.top)
                .unwrap_or_else(|e| panic!("{what}: {e}"));
            assert!(
                messages.trim().is_empty(),
                "{what}: verilator said:\n{messages}"
            );
            let messages = tritri_rtl::tools::slang_lint(&dir, &design.top)
                .unwrap_or_else(|e| panic!("{what}: {e}"));
            assert!(
                messages.is_empty(),
                "{what}: slang -Weverything said:\n{messages}"
            );
            run(IVERILOG.command().unwrap().current_dir(&dir).args([
                "-g2012",
                "-o",
                "/dev/null",
                "-c",
                "filelist.f",
            ]))
            .unwrap_or_else(|e| panic!("{what}: {e}"));
            for f in design.verilog_files() {
                assert!(
                    !f.contents.contains("lint_off"),
                    "{}: no lint_off pragma is needed",
                    f.path
                );
            }
            std::fs::remove_dir_all(&dir).unwrap();
        }
    }
}

/// Emission properties on the real design: no `$` in any name, one module
/// per file named after it, `default_nettype` guards, all names prefixed
/// with the unit, the README's port table complete.
#[test]
fn emitted_files_follow_the_conventions() {
    let design = emit_pipeline(24).unwrap();
    assert_eq!(design.top, "tritri_pipeline_w24");
    for f in design.verilog_files() {
        let name = f.path.trim_end_matches(".v");
        assert!(name.starts_with("tritri_pipeline_w24"), "{name}");
        let stripped = f.contents.replace("$signed", "").replace("$unsigned", "");
        assert!(!stripped.contains('$'), "{}: a `$` is left", f.path);
        assert_eq!(
            f.contents
                .lines()
                .filter(|l| l.starts_with("module "))
                .count(),
            1,
            "{}",
            f.path
        );
        assert!(
            f.contents.contains(&format!("\nmodule {name}")),
            "{}",
            f.path
        );
        assert!(
            f.contents.contains("`default_nettype none")
                && f.contents.trim_end().ends_with("`default_nettype wire")
        );
    }
    let readme = &design.file("README.md").unwrap().contents;
    for p in &design.ports {
        assert!(
            readme.contains(&format!("| `{}` | {} | {} |", p.name, p.direction, p.bits)),
            "{}",
            p.name
        );
    }
    assert!(readme.contains(&format!(
        "Latency: {} clock cycles",
        tritri_rtl::pipeline::triangle_pipeline::latency()
    )));
}

/// The row of `unit` in the resource table of rtl-out/README.md, split
/// into its cells (unit, generic cells, LUT, FF, DSP48E1, CARRY4, SRL).
fn published_row(unit: &str) -> Vec<String> {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../rtl-out/README.md");
    let text = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let row = text
        .lines()
        .find(|l| l.starts_with(&format!("| {unit} |")))
        .unwrap_or_else(|| panic!("{}: no resource-table row for {unit}", path.display()));
    row.split('|')
        .map(|c| c.trim().to_string())
        .filter(|c| !c.is_empty())
        .collect()
}

/// rtl-out/measurements.json (what `tritri report` reads) says what
/// rtl-out/README.md's tables say, row for row, and holds every row of
/// them: one set of measurements in two forms.
#[test]
fn measurements_file_is_the_readme_tables() {
    let kept = tritri_rtl::measured::Measurements::committed();
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../rtl-out/README.md");
    let text = std::fs::read_to_string(&path).unwrap();
    let rows: Vec<Vec<String>> = text
        .lines()
        .filter(|l| l.starts_with("| tritri_"))
        .map(|l| {
            l.split('|')
                .map(|c| c.trim().to_string())
                .filter(|c| !c.is_empty())
                .collect()
        })
        .collect();
    let (mut xilinx, mut ecp5) = (0, 0);
    for row in &rows {
        let n = |i: usize| {
            row[i]
                .parse::<u64>()
                .unwrap_or_else(|_| panic!("{row:?}: column {i}"))
        };
        if row.len() == 10 && row[7].starts_with('`') {
            let r = kept
                .ecp5(&row[0])
                .unwrap_or_else(|| panic!("measurements.json has no ECP5 row for {}", row[0]));
            assert_eq!(
                (
                    format!("{:.1}", r.fmax_mhz),
                    r.seed,
                    r.lut4,
                    r.ff,
                    r.mult18x18d,
                    r.ebr
                ),
                (row[1].clone(), n(2), n(3), n(4), n(5), n(6)),
                "{}",
                row[0]
            );
            ecp5 += 1;
        } else if row.len() == 7 {
            let r = kept
                .xilinx(&row[0])
                .unwrap_or_else(|| panic!("measurements.json has no Xilinx row for {}", row[0]));
            assert_eq!(
                (r.generic_cells, r.lut, r.ff, r.dsp48e1, r.carry4, r.srl),
                (Some(n(1)), n(2), n(3), n(4), n(5), n(6)),
                "{}",
                row[0]
            );
            xilinx += 1;
        } else if row.len() == 8 && row[6].contains('+') {
            let r = kept
                .xilinx(&row[0])
                .unwrap_or_else(|| panic!("measurements.json has no Xilinx row for {}", row[0]));
            let ram = format!("{} + {}", r.ramb36.unwrap_or(0), r.ramb18.unwrap_or(0));
            assert_eq!(
                (
                    r.lut,
                    r.ff,
                    r.dsp48e1,
                    r.carry4,
                    r.srl,
                    ram,
                    r.distributed_ram
                ),
                (n(1), n(2), n(3), n(4), n(5), row[6].clone(), Some(n(7))),
                "{}",
                row[0]
            );
            xilinx += 1;
        }
    }
    assert_eq!(
        (xilinx, ecp5),
        (kept.xilinx.len(), kept.ecp5.len()),
        "every measured row is in the README, and no other"
    );
}

/// Yosys: `synth_xilinx` at W = 24 and generic `synth` at W = 8 both finish
/// with a `stat` report, and their counts are the ones published in
/// rtl-out/README.md's resource table (so the table is what its command
/// produces; the generic flow at W = 24 takes about 6 minutes, so it is
/// checked at W = 8).
/// `TRITRI_LONG=1` (scripts/test-long.sh): the W = 24 cases as well,
/// which take minutes in Yosys where W = 8 takes seconds.
fn long_run() -> bool {
    std::env::var_os("TRITRI_LONG").is_some()
}

/// synth_xilinx gives rtl-out's published row, and measurements.json's,
/// at W = 8 (and W = 24 in the long run); generic synthesis W = 8's cells.
#[test]
fn yosys_synthesizes_to_the_published_resources() {
    let widths: &[usize] = if long_run() { &[8, 24] } else { &[8] };
    for &width in widths {
        let design = emit_pipeline(width).unwrap();
        let dir = write(&design, &format!("synth-xilinx-w{width}"));
        let xilinx = synthesize(&dir, Target::Xilinx).unwrap();
        assert!(xilinx.luts() > 0 && xilinx.flip_flops() > 0 && xilinx.dsps() > 0);
        let row = published_row(&design.top);
        let measured = [
            xilinx.luts(),
            xilinx.flip_flops(),
            xilinx.dsps(),
            xilinx.carry_chains(),
            xilinx.shift_registers(),
        ];
        assert_eq!(
            row[2..7],
            measured.map(|n| n.to_string()),
            "W={width} synth_xilinx: LUT FF DSP48E1 CARRY4 SRL; regenerate the table in rtl-out/README.md"
        );
        let kept = tritri_rtl::measured::Measurements::committed();
        let kept = kept
            .xilinx(&design.top)
            .unwrap_or_else(|| panic!("rtl-out/measurements.json has the W = {width} pipeline"));
        assert_eq!(
            [kept.lut, kept.ff, kept.dsp48e1, kept.carry4, kept.srl],
            measured,
            "W={width} synth_xilinx against rtl-out/measurements.json"
        );
        std::fs::remove_dir_all(&dir).unwrap();
    }

    let design = emit_pipeline(8).unwrap();
    let dir = write(&design, "synth-w8");
    let generic = synthesize(&dir, Target::Generic).unwrap();
    assert!(generic.cells > 0 && generic.flip_flops() > 0);
    assert_eq!(
        published_row(&design.top)[1],
        generic.cells.to_string(),
        "W=8 generic cells"
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

/// Every emitted W = 24 file equals its reviewed snapshot
/// (tests/snapshots/; update with `INSTA_UPDATE=always` and review the diff).
#[test]
fn w24_snapshots() {
    let design = emit_pipeline(24).unwrap();
    for f in &design.files {
        insta::assert_snapshot!(f.path.clone(), &f.contents);
    }
}

/// The rewriting passes (explicit widths, continuous assigns, ANSI ports) change no
/// behaviour: module by module, Yosys proves the design emitted with them
/// equivalent to the same emission without them (same names, so every
/// signal and register pairs up; children are black boxes with the same
/// ports; memories mapped to registers; `equiv_simple` then
/// `equiv_induct`). Checked on the pipeline at
/// W = 8 (and 24 in the long run) and on a two-pipeline system (its top has the valid/ready
/// paths the continuous-assigns pass is for).
#[test]
fn emission_passes_are_formally_equivalent() {
    use tritri_rtl::emit::{emit_with, pipeline_unit, EmitOptions};
    use tritri_rtl::system::system_for_width::{system_for_config, PipelineKind};
    use tritri_rtl::system::system_unit::system_unit;
    use tritri_rtl::system::SystemConfig;
    let system = SystemConfig::new(8, 2).with_depth(16);
    let raw_system = {
        let mut s = system_for_config(system, PipelineKind::Parallel).unwrap();
        s.connect_all();
        s.raw_design()
    };
    let mut cases = vec![
        (
            "w8".to_string(),
            tritri_rtl::raw_design(8).unwrap(),
            pipeline_unit(8).unwrap(),
        ),
        (
            "system".to_string(),
            raw_system,
            system_unit(system, PipelineKind::Parallel),
        ),
    ];
    // The same passes on wider operands: minutes more in Yosys.
    if long_run() {
        cases.push((
            "w24".to_string(),
            tritri_rtl::raw_design(24).unwrap(),
            pipeline_unit(24).unwrap(),
        ));
    }
    for (width, raw, unit) in cases {
        let gold = emit_with(&raw, &unit, EmitOptions::no_rewrites()).unwrap();
        let gate = emit_with(&raw, &unit, EmitOptions::default()).unwrap();
        assert_eq!(gold.modules, gate.modules);
        let dir = temp_dir(&format!("equiv-w{width}"));
        for (design, sub) in [(&gold, "gold"), (&gate, "gate")] {
            std::fs::create_dir_all(dir.join(sub)).unwrap();
            design.write_to(&dir.join(sub)).unwrap();
        }
        let mut changed = 0;
        for module in &gate.modules {
            let file = format!("{module}.v");
            if gold.file(&file).unwrap().contents == gate.file(&file).unwrap().contents {
                continue;
            }
            changed += 1;
            let others: Vec<String> = gate
                .modules
                .iter()
                .filter(|m| *m != module)
                .map(|m| format!("gate/{m}.v"))
                .collect();
            let script = format!(
                "read_verilog -lib {}\nread_verilog gold/{file}\nproc\nmemory\nrename {module} gold\n\
                 read_verilog gate/{file}\nproc\nmemory\nrename {module} gate\nequiv_make gold gate equiv\n\
                 hierarchy -top equiv\nequiv_simple\nequiv_induct\nequiv_status -assert\n",
                others.join(" ")
            );
            std::fs::write(dir.join("equiv.ys"), script).unwrap();
            tritri_rtl::tools::run(
                tritri_rtl::tools::YOSYS
                    .command()
                    .unwrap()
                    .current_dir(&dir)
                    .args(["-q", "equiv.ys"]),
            )
            .unwrap_or_else(|e| panic!("{width}, module {module}: {e}"));
        }
        eprintln!("{width}: {changed} rewritten modules proven equivalent");
        assert!(changed > 0);
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
