//! Direct drive of a rust-hdl simulation (docs/ARCHITECTURE.md, conventions: no `simple_sim!`
//! threads): set the inputs, toggle the clock, and call `update_all()` until
//! `has_changed()` is false.

use rust_hdl::prelude::*;
use std::sync::atomic::{AtomicU64, Ordering};

/// Delta cycles (`update_all` passes) run by [`settle`] in this process, for
/// simulation-speed diagnostics.
pub static DELTA_CYCLES: AtomicU64 = AtomicU64::new(0);

/// Upper bound on delta cycles per clock phase; more means a logic loop.
pub const MAX_DELTA_CYCLES: usize = 10_000;

/// Propagates until nothing changes. Panics on a combinational loop.
pub fn settle<B: Block>(uut: &mut B) {
    for i in 0..MAX_DELTA_CYCLES {
        uut.update_all();
        if !uut.has_changed() {
            DELTA_CYCLES.fetch_add(i as u64 + 1, Ordering::Relaxed);
            return;
        }
    }
    panic!("the circuit did not settle within {MAX_DELTA_CYCLES} delta cycles");
}

/// One full clock period, for inputs set just before the call: the clock
/// falls, then rises, and the circuit settles; outputs read afterwards are
/// those of the registers just loaded. `clock` selects the top's clock.
///
/// The falling edge gets a single delta cycle rather than a full settle:
/// nothing here acts on it, and it travels down the hierarchy one level per
/// delta cycle, one step ahead of the rising edge, exactly as it would
/// after a full settle; new inputs travel with them and reach every
/// register before its rising edge. The previous settle left everything
/// stable, so no register can see a value from the wrong cycle. This saves
/// about a third of the delta cycles.
///
/// That holds for an input's paths that only go down the hierarchy. A unit
/// reads a sub-unit's output a delta cycle after the sub-unit computes it,
/// so an input that goes into a sub-unit and comes back out to a register
/// of the unit arrives a delta cycle after that register's edge, and the
/// register takes the input's old value. Designs driven this way keep such
/// round trips off their input paths (`HoldForecast` chooses by `advance`
/// itself for this reason).
pub fn clock_cycle<B: Block>(uut: &mut B, clock: fn(&mut B) -> &mut Signal<In, Clock>) {
    clock(uut).next = Clock { clk: false };
    uut.update_all();
    clock(uut).next = Clock { clk: true };
    settle(uut);
}

/// Holds a freshly connected unit in reset for one clock (reset high, the
/// circuit settled, one clock period, reset low): the start of every
/// direct-drive run. `reset` and `clock` select the top's signals.
pub fn reset_one_clock<B: Block>(
    uut: &mut B,
    reset: fn(&mut B) -> &mut Signal<In, Bit>,
    clock: fn(&mut B) -> &mut Signal<In, Clock>,
) {
    reset(uut).next = true;
    settle(uut);
    clock_cycle(uut, clock);
    reset(uut).next = false;
}

/// Streams `vectors` through a unit, one per clock with `advance` high
/// (`set` drives a vector's inputs), and checks that the outputs `get` reads
/// `latency` clock edges later equal `model` of that vector, and that they
/// are not already there one edge earlier (so `latency` is the unit's
/// latency, not an upper bound). The unit's own test (one beside each unit)
/// calls this with the unit's latency constant.
pub fn assert_stream_matches<B: Block, V, O: PartialEq + std::fmt::Debug>(
    uut: &mut B,
    clock: fn(&mut B) -> &mut Signal<In, Clock>,
    vectors: &[V],
    latency: usize,
    set: impl Fn(&mut B, &V),
    get: impl Fn(&B) -> O,
    model: impl Fn(&V) -> O,
) where
    V: std::fmt::Debug,
{
    assert!(latency >= 1 && !vectors.is_empty());
    // outputs[k]: what the outputs show after clock edge k (0-based).
    let mut outputs = Vec::new();
    for k in 0..vectors.len() + latency {
        if let Some(v) = vectors.get(k) {
            set(uut, v);
        }
        // The inputs settle first: a unit alone may have logic between its
        // inputs and its first registers (the pipeline's top registers
        // its inputs, so `clock_cycle` alone serves it).
        settle(uut);
        clock_cycle(uut, clock);
        outputs.push(get(uut));
    }
    let expected: Vec<O> = vectors.iter().map(&model).collect();
    for (i, (v, e)) in vectors.iter().zip(&expected).enumerate() {
        assert_eq!(
            &outputs[i + latency - 1],
            e,
            "vector {i}: {v:?}, {latency} edges after it entered"
        );
    }
    if latency >= 2 {
        let early = (0..vectors.len()).all(|i| outputs[i + latency - 2] == expected[i]);
        assert!(
            !early,
            "every output is there after {} edges already: the latency is less than {latency}",
            latency - 1
        );
    }
}
