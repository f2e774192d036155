//! Emission properties on a small rust-hdl design of our own (a registered
//! adder inside a top with a state machine, a constant, arrays and casts):
//! the shapes rust-hdl prints for any design, checked without the pipeline.

use rust_hdl::prelude::*;
use tritri_rtl::emit::{emit, EmittedDesign, UnitDescription};
use tritri_rtl::tools::{run, IVERILOG};
use tritri_rtl::unit::{RawDesign, Unit, UnitWalk};

#[derive(LogicBlock, Default)]
pub struct RegisteredAdder {
    pub clock: Signal<In, Clock>,
    pub a: Signal<In, Bits<8>>,
    pub b: Signal<In, Bits<8>>,
    pub sum: Signal<Out, Bits<9>>,
    sum_q: DFF<Bits<9>>,
}

impl Logic for RegisteredAdder {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(self, clock, sum_q);
        self.sum_q.d.next = bit_cast::<9, 8>(self.a.val()) + bit_cast::<9, 8>(self.b.val());
        self.sum.next = self.sum_q.q.val();
    }
}

impl Unit for RegisteredAdder {
    fn sub_units(&self, units: &mut UnitWalk) {
        tritri_rtl::sub_units!(self, units, sum_q);
    }
}

#[derive(Copy, Clone, PartialEq, Debug, LogicState)]
pub enum Phase {
    Idle,
    Busy,
    Done,
}

#[derive(LogicBlock)]
pub struct Sample {
    pub clock: Signal<In, Clock>,
    pub reset: Signal<In, Bit>,
    pub start: Signal<In, Bit>,
    pub x: [Signal<In, Bits<8>>; 2],
    pub total: Signal<Out, Bits<9>>,
    pub high: Signal<Out, Bits<4>>,
    pub busy: Signal<Out, Bit>,
    offset: Constant<Bits<8>>,
    adder: RegisteredAdder,
    other_adder: RegisteredAdder,
    phase: DFF<Phase>,
    count: DFF<Bits<4>>,
}

impl Unit for Sample {
    fn sub_units(&self, units: &mut UnitWalk) {
        tritri_rtl::sub_units!(self, units, adder, other_adder, phase, count);
    }
}

impl Default for Sample {
    fn default() -> Self {
        Sample {
            clock: Default::default(),
            reset: Default::default(),
            start: Default::default(),
            x: Default::default(),
            total: Default::default(),
            high: Default::default(),
            busy: Default::default(),
            offset: Constant::new(Bits::<8>::from(0x5a)),
            adder: Default::default(),
            other_adder: Default::default(),
            phase: Default::default(),
            count: Default::default(),
        }
    }
}

impl Logic for Sample {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(self, clock, phase, count);
        self.adder.clock.next = self.clock.val();
        self.other_adder.clock.next = self.clock.val();
        self.adder.a.next = self.x[0].val();
        self.adder.b.next = self.x[1].val() ^ self.offset.val();
        self.other_adder.a.next = self.adder.sum.val().get_bits::<8>(0);
        self.other_adder.b.next = 3.into();
        self.total.next = self.other_adder.sum.val();
        self.high.next = self.adder.sum.val().get_bits::<4>(5);
        self.busy.next = false;
        match self.phase.q.val() {
            Phase::Idle => {
                if self.start.val() {
                    self.phase.d.next = Phase::Busy;
                    self.count.d.next = 0.into();
                }
            }
            Phase::Busy => {
                self.busy.next = true;
                self.count.d.next = self.count.q.val() + 1;
                if self.count.q.val() == 9 {
                    self.phase.d.next = Phase::Done;
                }
            }
            Phase::Done => {
                self.phase.d.next = Phase::Idle;
            }
            _ => {}
        }
        if self.reset.val() {
            self.phase.d.next = Phase::Idle;
        }
    }
}

fn sample_design() -> EmittedDesign {
    let mut uut = Sample::default();
    uut.connect_all();
    let raw = RawDesign::of(&uut);
    let unit = UnitDescription::new(
        "tritri_sample_w8",
        "A sample design: two registered adders and a counter.",
    )
    .parameter("W", "8, operand width")
    .port("clock", "clock, rising edge")
    .port("reset", "synchronous reset, active high")
    .port("start", "starts the counter")
    .port("x_0", "first operand")
    .port("x_1", "second operand")
    .port("total", "sum of the sums")
    .port("high", "high bits of the first sum")
    .port("busy", "counter running")
    .latency(2)
    .throughput("one operand pair per clock");
    emit(&raw, &unit).expect("the sample emits")
}

fn temp_dir(name: &str) -> std::path::PathBuf {
    let dir =
        std::env::temp_dir().join(format!("tritri-emit-sample-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// No `$` survives in any identifier (system tasks like `$signed` aside).
#[test]
fn no_dollar_in_names() {
    let design = sample_design();
    for f in design.verilog_files() {
        let stripped = f.contents.replace("$signed", "").replace("$unsigned", "");
        assert!(
            !stripped.contains('$'),
            "{} still has a `$`:\n{}",
            f.path,
            f.contents
        );
    }
}

/// One module per file, the file named after the module, wrapped in
/// `default_nettype none` ... `default_nettype wire`.
#[test]
fn one_module_per_file_with_nettype_guards() {
    let design = sample_design();
    for f in design.verilog_files() {
        let modules: Vec<&str> = f
            .contents
            .lines()
            .filter(|l| l.starts_with("module "))
            .collect();
        assert_eq!(modules.len(), 1, "{}", f.path);
        let name = f.path.trim_end_matches(".v");
        assert!(
            modules[0].starts_with(&format!("module {name}("))
                || modules[0].starts_with(&format!("module {name} ("))
        );
        assert_eq!(f.contents.matches("endmodule").count(), 1);
        let none = f
            .contents
            .find("`default_nettype none")
            .expect("nettype none");
        let module = f.contents.find("\nmodule ").unwrap();
        let wire = f
            .contents
            .rfind("`default_nettype wire")
            .expect("nettype wire");
        let end = f.contents.rfind("endmodule").unwrap();
        assert!(none < module && end < wire, "{}", f.path);
        assert!(
            f.contents.contains("Generated by tritri-rtl"),
            "{} has no header",
            f.path
        );
    }
}

/// The top is named after the unit, children after the unit plus their
/// Rust type (`RegisteredAdder`, whatever the fields holding it are
/// called); registers of the same shape share one module.
#[test]
fn module_names() {
    let design = sample_design();
    assert_eq!(design.modules[0], "tritri_sample_w8");
    assert!(design
        .modules
        .iter()
        .all(|m| m.starts_with("tritri_sample_w8")));
    assert!(
        design
            .modules
            .contains(&"tritri_sample_w8_dff_9".to_string()),
        "{:?}",
        design.modules
    );
    // Instances carry the u_ prefix.
    let top = &design.file("tritri_sample_w8.v").unwrap().contents;
    assert!(
        top.contains("tritri_sample_w8_registered_adder u_adder("),
        "{top}"
    );
    assert!(
        top.contains("tritri_sample_w8_registered_adder u_other_adder("),
        "{top}"
    );
    // adder and other_adder are the same circuit.
    let adders: Vec<_> = design
        .modules
        .iter()
        .filter(|m| m.contains("adder"))
        .collect();
    assert_eq!(adders.len(), 1, "{:?}", design.modules);
    let filelist = &design.file("filelist.f").unwrap().contents;
    assert_eq!(filelist.lines().count(), design.modules.len());
    assert_eq!(filelist.lines().last(), Some("tritri_sample_w8.v"));
}

/// The README lists every port with direction and width.
#[test]
fn readme_has_port_table() {
    let design = sample_design();
    let readme = &design.file("README.md").unwrap().contents;
    assert!(
        readme.contains("| `x_0` | input | 8 | first operand |"),
        "{readme}"
    );
    assert!(
        readme.contains("| `total` | output | 9 | sum of the sums |"),
        "{readme}"
    );
    assert!(readme.contains("Latency: 2 clock cycles"));
    let core = &design.file("tritri_sample_w8.core").unwrap().contents;
    assert!(core.starts_with("CAPI=2:\n") && core.contains("toplevel: tritri_sample_w8"));
}

/// `verilator --lint-only -Wall` reports nothing, Icarus compiles, Yosys
/// synthesizes with a stat report.
#[test]
fn sample_is_lint_clean_and_synthesizes() {
    let design = sample_design();
    let dir = temp_dir("lint");
    design.write_to(&dir).unwrap();
    let lint = tritri_rtl::tools::lint(&dir, "tritri_sample_w8");
    if std::env::var_os("TRITRI_SHOW").is_some() || lint.is_err() {
        for f in design.verilog_files() {
            eprintln!("==== {}\n{}", f.path, f.contents);
        }
        lint.unwrap();
    }
    run(IVERILOG.command().unwrap().current_dir(&dir).args([
        "-g2012",
        "-o",
        "/dev/null",
        "-c",
        "filelist.f",
    ]))
    .unwrap();
    let report = tritri_rtl::synth::synthesize(&dir, tritri_rtl::synth::Target::Generic).unwrap();
    assert!(report.cells > 0);
    std::fs::remove_dir_all(&dir).unwrap();
}
