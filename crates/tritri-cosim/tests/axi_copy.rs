//! The AXI4 port proven on the copy unit: the clock-exact model, the
//! rust-hdl unit and the emitted Verilog in Icarus and Verilator copy the
//! same bytes in the same clocks, against an ideal memory, a memory with
//! random stalls and a memory slower than the port; no burst breaks the
//! protocol's rules.

use tritri_cosim::axi_copy::{run_model, run_rusthdl, run_simulator, CopyCase, CopyOutcome};
use tritri_cosim::simulator::Simulator;
use tritri_rtl::axi::memory_model::MemoryParams;
use tritri_rtl::emit::axi_copy_unit::AxiCopyConfig;

/// A memory of `size` bytes of a fixed pseudo-random pattern.
fn pattern(size: usize) -> Vec<u8> {
    let mut x = 0x1234_5678u32;
    (0..size)
        .map(|_| {
            x ^= x << 13;
            x ^= x >> 17;
            x ^= x << 5;
            x as u8
        })
        .collect()
}

fn case(data_bits: usize, params: MemoryParams, beats: u64) -> CopyCase {
    let bytes = pattern(1 << 17);
    CopyCase {
        config: AxiCopyConfig {
            data_bits,
            max_burst: 16,
            outstanding: 4,
        },
        params,
        bytes,
        // Neither region starts on a 4 KB boundary, so bursts are cut.
        source: 0x0140,
        destination: 0x1_0000 + 0x0c00,
        beats,
        limit: 1_000_000,
    }
}

/// The copy's checks against the bytes it started from.
fn assert_copied(case: &CopyCase, out: &CopyOutcome, engine: &str) {
    let n = (case.beats * case.params.beat_bytes) as usize;
    let (s, d) = (case.source as usize, case.destination as usize);
    assert_eq!(out.faults, 0, "{engine}: protocol faults");
    assert!(!out.error, "{engine}: error response");
    assert!(
        out.bytes[d..d + n] == case.bytes[s..s + n],
        "{engine}: the destination"
    );
    assert!(
        out.bytes[..d] == case.bytes[..d],
        "{engine}: below the destination"
    );
    assert!(
        out.bytes[d + n..] == case.bytes[d + n..],
        "{engine}: above it"
    );
}

/// Every engine on `case`: equal outcomes, and the model's returned.
fn all_engines(case: &CopyCase, simulators: &[Simulator]) -> CopyOutcome {
    let model = run_model(case).unwrap();
    assert_copied(case, &model, "model");
    assert_same(&run_rusthdl(case).unwrap(), &model, "rust-hdl");
    for &sim in simulators {
        assert_same(
            &run_simulator(sim, case).unwrap(),
            &model,
            &format!("{sim:?}"),
        );
    }
    eprintln!(
        "{} beats of {} bits: {} clocks ({} stalled), model = rust-hdl = {simulators:?}",
        case.beats, case.config.data_bits, model.cycles, model.stalled
    );
    model
}

/// `out` equals the model's outcome; the first differing byte is named.
fn assert_same(out: &CopyOutcome, model: &CopyOutcome, engine: &str) {
    let counts = |o: &CopyOutcome| (o.cycles, o.stalled, o.error, o.faults);
    assert_eq!(
        counts(out),
        counts(model),
        "{engine} against the model: (cycles, stalled, error, faults)"
    );
    if let Some(i) = (0..model.bytes.len()).find(|&i| out.bytes.get(i) != model.bytes.get(i)) {
        panic!("{engine}: byte {i:#x} differs from the model's");
    }
    assert_eq!(out.bytes.len(), model.bytes.len(), "{engine}: memory size");
}

#[test]
fn an_ideal_memory_copies_at_a_beat_per_clock_after_its_latency() {
    let latency = 24;
    let beats = 1500;
    let c = case(64, MemoryParams::ideal(8, latency), beats);
    let out = all_engines(&c, &[Simulator::Verilator, Simulator::Icarus]);
    // A beat per clock each way, overlapped: the read latency, the beats,
    // the write response, and a few clocks of queues and issue.
    let floor = latency + beats + latency;
    assert!(out.cycles >= floor, "{} cycles, under {floor}", out.cycles);
    assert!(
        out.cycles <= floor + 40,
        "{} cycles, over {floor} + 40",
        out.cycles
    );
}

#[test]
fn random_stalls_change_the_clocks_but_not_the_bytes() {
    let ideal = case(64, MemoryParams::ideal(8, 24), 1500);
    let base = run_model(&ideal).unwrap().cycles;
    let stalls = CopyCase {
        params: ideal.params.with_stalls(20, 7),
        ..ideal.clone()
    };
    let out = all_engines(&stalls, &[Simulator::Verilator]);
    assert!(out.stalled > 0);
    assert!(
        out.cycles > base,
        "stalls cost nothing: {} against {base}",
        out.cycles
    );
    // A stalled clock moves nothing on either channel, so it delays the
    // copy by at most itself.
    assert!(
        out.cycles <= base + out.stalled,
        "{} cycles: more than the ideal {base} and the {} stalled clocks",
        out.cycles,
        out.stalled
    );
}

#[test]
fn a_memory_slower_than_the_port_sets_the_pace() {
    // 3 bytes a clock for reads and writes together, against 8-byte beats.
    let params = MemoryParams {
        bytes_per_clock: (3, 1),
        ..MemoryParams::ideal(8, 24)
    };
    let beats = 600;
    let c = case(64, params, beats);
    let out = all_engines(&c, &[Simulator::Icarus]);
    let bound = 2 * beats * 8 / 3;
    assert!(
        out.cycles >= bound,
        "{} cycles beat the memory's {bound}",
        out.cycles
    );
    assert!(
        out.cycles <= bound + 100,
        "{} cycles, far past the memory's {bound}",
        out.cycles
    );
}

#[test]
fn a_wide_port_and_a_copy_of_nothing() {
    let wide = case(256, MemoryParams::ideal(32, 16), 300);
    all_engines(&wide, &[Simulator::Icarus]);
    let nothing = case(64, MemoryParams::ideal(8, 16), 0);
    let out = all_engines(&nothing, &[Simulator::Icarus]);
    assert!(
        out.cycles <= 4,
        "a copy of nothing took {} clocks",
        out.cycles
    );
}
