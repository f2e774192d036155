//! The memory the AXI units are co-simulated against, clock by clock: a
//! byte array behind an AXI4 subordinate port with a read latency, a write
//! response latency, a limit on the bursts it takes per direction, a
//! bandwidth and, optionally, random stalls. It is written twice, here in
//! Rust (for the rust-hdl simulation and for the clock-exact model,
//! [`super::transfer_machine`]) and in Verilog for Icarus and Verilator
//! (`tritri-cosim`'s `axi_memory.v`); the co-simulations hold the two to
//! the same cycles.
//!
//! # One clock
//!
//! Every output is a function of the state at the start of the clock; at
//! the edge the memory takes what the manager's signals and its own
//! outputs say was transferred.
//!
//! * `arready` (`awready`): fewer than `outstanding` read (write) bursts
//!   are held, and the clock is not stalled.
//! * `rvalid`: the oldest read burst was taken at least `read_latency`
//!   clocks ago, the bandwidth allows a beat and the clock is not stalled;
//!   once shown, a beat stays until it is taken (AXI's rule for VALID).
//! * `wready`: a write burst is held whose beats have not all come, the
//!   bandwidth allows a beat (a second one, when a read beat is shown in
//!   the same clock), and the clock is not stalled. W beats wait for their
//!   burst's AW.
//! * `bvalid`: the oldest finished write burst's last beat came at least
//!   `write_latency` clocks ago.
//! * Bandwidth is a bucket of `bytes_per_clock` (a fraction) that fills
//!   every clock up to two beats and empties by a beat per beat moved.
//! * A stall is drawn every clock from xorshift32 (`x ^= x << 13; x ^= x
//!   >> 17; x ^= x << 5`, from `seed`): the clock is stalled when `x mod
//!   100 < stall_percent`.
//!
//! A burst that crosses a 4 KB boundary, runs past the memory's end, is
//! not INCR of full-width beats, or a `wlast` out of place is a protocol
//! fault the model records ([`AxiMemory::faults`]).

use std::collections::VecDeque;

/// What a memory is like.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct MemoryParams {
    /// Bytes of a beat (the port's data width / 8).
    pub beat_bytes: u64,
    /// Clocks from a read burst's AR to its first beat, at least 1.
    pub read_latency: u64,
    /// Clocks from a write burst's last beat to its response, at least 1.
    pub write_latency: u64,
    /// Bursts held per direction, at least 1.
    pub outstanding: usize,
    /// Bytes the memory moves per clock, read and write together, as
    /// `(numerator, denominator)`.
    pub bytes_per_clock: (u64, u64),
    /// Percent of clocks stalled, 0 to 100.
    pub stall_percent: u32,
    /// Seed of the stalls (not 0).
    pub seed: u32,
}

impl MemoryParams {
    /// A memory that never holds the port back once its latency is paid:
    /// two beats a clock, as many bursts as the manager sends, no stalls.
    pub fn ideal(beat_bytes: u64, read_latency: u64) -> Self {
        MemoryParams {
            beat_bytes,
            read_latency,
            write_latency: read_latency,
            outstanding: 64,
            bytes_per_clock: (2 * beat_bytes, 1),
            stall_percent: 0,
            seed: 1,
        }
    }

    /// The same memory with `percent` of its clocks stalled at random.
    pub fn with_stalls(self, percent: u32, seed: u32) -> Self {
        MemoryParams {
            stall_percent: percent,
            seed: seed.max(1),
            ..self
        }
    }

    /// This memory moving `gbytes` GB/s in all (reads and writes together)
    /// for a port clocked at `mhz`: bytes a clock as the fraction
    /// `gbytes * 1000 / mhz`, both rounded to whole numbers.
    pub fn at_bandwidth(self, gbytes: f64, mhz: f64) -> Self {
        MemoryParams {
            bytes_per_clock: (
                ((gbytes * 1000.0).round() as u64).max(1),
                (mhz.round() as u64).max(1),
            ),
            ..self
        }
    }

    /// GB/s at a port clocked at `mhz`.
    pub fn gbytes_at(&self, mhz: f64) -> f64 {
        let (num, den) = self.bytes_per_clock;
        num as f64 / den as f64 * mhz * 1e6 / 1e9
    }

    /// The bucket's units per beat and its size: bytes are counted in
    /// `1 / denominator`.
    fn beat_cost(&self) -> u64 {
        self.beat_bytes * self.bytes_per_clock.1
    }
}

/// The manager's side of the port in one clock.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct ManagerSignals {
    pub arvalid: bool,
    pub araddr: u64,
    pub arlen: u64,
    pub arsize: u64,
    pub arburst: u64,
    pub rready: bool,
    pub awvalid: bool,
    pub awaddr: u64,
    pub awlen: u64,
    pub awsize: u64,
    pub awburst: u64,
    pub wvalid: bool,
    /// The beat's bytes, lowest address first.
    pub wdata: Vec<u8>,
    pub wlast: bool,
    pub bready: bool,
}

/// The memory's side of the port in one clock.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct MemoryOutputs {
    pub arready: bool,
    pub rvalid: bool,
    /// The beat's bytes, lowest address first (empty without `rvalid`).
    pub rdata: Vec<u8>,
    pub rlast: bool,
    pub awready: bool,
    pub wready: bool,
    pub bvalid: bool,
}

#[derive(Clone, Copy, Debug)]
struct Burst {
    address: u64,
    beats_left: u64,
    /// The first clock its first beat (read) or its response (write) may go.
    due: u64,
}

/// The memory: its bytes and its port's state.
#[derive(Clone, Debug)]
pub struct AxiMemory {
    pub params: MemoryParams,
    pub bytes: Vec<u8>,
    clock: u64,
    reads: VecDeque<Burst>,
    writes: VecDeque<Burst>,
    responses: VecDeque<u64>,
    bucket: u64,
    random: u32,
    /// A beat shown in the last clock and not taken: shown again.
    r_held: bool,
    /// Clocks stalled so far.
    pub stalled: u64,
    /// Beats read and written so far.
    pub beats_read: u64,
    pub beats_written: u64,
    faults: Vec<String>,
}

impl AxiMemory {
    /// A memory of `bytes` (its size is their length).
    pub fn new(params: MemoryParams, bytes: Vec<u8>) -> Self {
        assert!(params.read_latency >= 1 && params.write_latency >= 1);
        assert!(params.outstanding >= 1 && params.bytes_per_clock.1 >= 1);
        AxiMemory {
            params,
            bytes,
            clock: 0,
            reads: VecDeque::new(),
            writes: VecDeque::new(),
            responses: VecDeque::new(),
            bucket: 2 * params.beat_cost(),
            random: params.seed.max(1),
            r_held: false,
            stalled: 0,
            beats_read: 0,
            beats_written: 0,
            faults: Vec::new(),
        }
    }

    /// Protocol faults seen so far, each naming the clock and the burst.
    pub fn faults(&self) -> &[String] {
        &self.faults
    }

    fn stall(&self) -> bool {
        self.random % 100 < self.params.stall_percent
    }

    /// The outputs of this clock.
    pub fn outputs(&self) -> MemoryOutputs {
        let stall = self.stall();
        let cost = self.params.beat_cost();
        let room = self.params.outstanding;
        let read_due = self.reads.front().is_some_and(|b| self.clock >= b.due);
        let rvalid = self.r_held || (read_due && self.bucket >= cost && !stall);
        let write_cost = if rvalid { 2 * cost } else { cost };
        let (rdata, rlast) = match self.reads.front() {
            Some(b) if rvalid => (self.beat(b.address), b.beats_left == 1),
            _ => (Vec::new(), false),
        };
        MemoryOutputs {
            arready: self.reads.len() < room && !stall,
            rvalid,
            rdata,
            rlast,
            awready: self.writes.len() < room && !stall,
            wready: !self.writes.is_empty() && self.bucket >= write_cost && !stall,
            bvalid: self.responses.front().is_some_and(|&due| self.clock >= due),
        }
    }

    fn beat(&self, address: u64) -> Vec<u8> {
        let n = self.params.beat_bytes as usize;
        let a = address as usize;
        self.bytes
            .get(a..a + n)
            .map(<[u8]>::to_vec)
            .unwrap_or_else(|| vec![0; n])
    }

    fn check_burst(&mut self, what: &str, address: u64, length: u64, size: u64, burst: u64) {
        let beat = self.params.beat_bytes;
        let bytes = (length + 1) * beat;
        let mut fault = |f: String| {
            self.faults
                .push(format!("clock {}: {what} at {address:#x}: {f}", self.clock))
        };
        if size != u64::from(beat.trailing_zeros()) || burst != 1 {
            fault(format!(
                "not an INCR burst of full beats (size {size}, burst {burst})"
            ));
        }
        if address % beat != 0 {
            fault("not aligned to the beat".into());
        }
        if address / 4096 != (address + bytes - 1) / 4096 {
            fault(format!("{} beats cross a 4 KB boundary", length + 1));
        }
        if address + bytes > self.bytes.len() as u64 {
            fault(format!("runs past the memory's {} bytes", self.bytes.len()));
        }
    }

    /// The edge at the end of this clock: what moved, given the manager's
    /// signals and this clock's outputs.
    pub fn edge(&mut self, manager: &ManagerSignals) {
        let out = self.outputs();
        let cost = self.params.beat_cost();
        let beat = self.params.beat_bytes;
        if manager.arvalid && out.arready {
            let (a, l) = (manager.araddr, manager.arlen);
            self.check_burst("read", a, l, manager.arsize, manager.arburst);
            self.reads.push_back(Burst {
                address: a,
                beats_left: l + 1,
                due: self.clock + self.params.read_latency,
            });
        }
        self.r_held = out.rvalid && !manager.rready;
        if out.rvalid && manager.rready {
            self.bucket = self.bucket.saturating_sub(cost);
            self.beats_read += 1;
            let b = self.reads.front_mut().expect("a beat shown has its burst");
            b.address += beat;
            b.beats_left -= 1;
            if b.beats_left == 0 {
                self.reads.pop_front();
            }
        }
        if manager.wvalid && out.wready {
            self.bucket = self.bucket.saturating_sub(cost);
            self.beats_written += 1;
            let clock = self.clock;
            let latency = self.params.write_latency;
            let b = self.writes.front_mut().expect("wready only with a burst");
            let a = b.address as usize;
            if let Some(slot) = self.bytes.get_mut(a..a + beat as usize) {
                slot.copy_from_slice(&manager.wdata[..beat as usize]);
            }
            b.address += beat;
            b.beats_left -= 1;
            let last = b.beats_left == 0;
            if last != manager.wlast {
                let f = format!(
                    "clock {clock}: wlast {} on a beat with {} left",
                    manager.wlast, b.beats_left
                );
                self.faults.push(f);
            }
            if last {
                self.writes.pop_front();
                self.responses.push_back(clock + latency);
            }
        }
        if manager.awvalid && out.awready {
            let (a, l) = (manager.awaddr, manager.awlen);
            self.check_burst("write", a, l, manager.awsize, manager.awburst);
            self.writes.push_back(Burst {
                address: a,
                beats_left: l + 1,
                due: 0,
            });
        }
        if out.bvalid && manager.bready {
            self.responses.pop_front();
        }
        if self.stall() {
            self.stalled += 1;
        }
        let (num, _) = self.params.bytes_per_clock;
        self.bucket = (self.bucket + num).min(2 * cost);
        self.random ^= self.random << 13;
        self.random ^= self.random >> 17;
        self.random ^= self.random << 5;
        self.clock += 1;
    }
}
