//! The clock-exact model of the AXI units ([`super::burst_reader`],
//! [`super::burst_writer`], [`super::axi_copy`]): their registers, clock by
//! clock, against the memory model ([`super::memory_model`]), so a run's
//! cycles are known without simulating the circuit and the co-simulations
//! hold the circuit to them.
//!
//! Each model has the unit's registers under the unit's names; `outputs`
//! is what the unit shows in a clock and `edge` what its registers take at
//! the clock's end, in the order the unit's `update` writes them.

use super::memory_model::{AxiMemory, ManagerSignals, MemoryParams};
use super::{burst_beats, TransferConfig};
use std::collections::VecDeque;

/// A beat's bytes, lowest address first.
pub type Beat = Vec<u8>;

/// [`super::beat_fifo`]: the RAM's words, the stage, the head and the
/// spare behind it.
#[derive(Clone, Debug)]
pub(crate) struct Queue<T> {
    stored: VecDeque<T>,
    stage: Option<T>,
    pub(crate) head: Option<T>,
    spare: Option<T>,
}

impl<T> Default for Queue<T> {
    fn default() -> Self {
        Queue {
            stored: VecDeque::new(),
            stage: None,
            head: None,
            spare: None,
        }
    }
}

impl<T> Queue<T> {
    pub(crate) fn count(&self) -> usize {
        self.stored.len()
            + self.stage.is_some() as usize
            + self.head.is_some() as usize
            + self.spare.is_some() as usize
    }

    pub(crate) fn edge(&mut self, push: Option<T>, pop: bool) {
        let popped = pop && self.head.is_some();
        let head_free = self.head.is_none() || popped;
        let fetch = !(self.stage.is_some() && self.head.is_some() && self.spare.is_some())
            && !self.stored.is_empty();
        if head_free {
            if self.spare.is_some() {
                self.head = self.spare.take();
                self.spare = self.stage.take();
            } else {
                self.head = self.stage.take();
            }
        } else if self.spare.is_none() {
            self.spare = self.stage.take();
        }
        if fetch {
            debug_assert!(self.stage.is_none(), "a full stage fetched");
            self.stage = self.stored.pop_front();
        }
        if let Some(beat) = push {
            self.stored.push_back(beat);
        }
    }
}

/// [`super::burst_rule`]: the next burst's beats at `address` with `left`
/// beats to go.
fn next_burst(config: &TransferConfig, address: u64, left: u64) -> u64 {
    burst_beats(address, config.beat_bytes(), config.max_burst as u64).min(left)
}

/// [`super::burst_reader::BurstReader`]'s registers.
#[derive(Clone, Debug)]
pub struct ReaderModel {
    config: TransferConfig,
    queue: Queue<Beat>,
    running: bool,
    pub failed: bool,
    next_address: u64,
    to_request: u64,
    to_deliver: u64,
    in_flight: usize,
    committed: u64,
    ar: Option<(u64, u64)>,
    burst_q: u64,
    burst_ok: bool,
}

impl ReaderModel {
    pub fn new(config: TransferConfig) -> Self {
        ReaderModel {
            config,
            queue: Queue::default(),
            running: false,
            failed: false,
            next_address: 0,
            to_request: 0,
            to_deliver: 0,
            in_flight: 0,
            committed: 0,
            ar: None,
            burst_q: 0,
            burst_ok: false,
        }
    }

    pub fn busy(&self) -> bool {
        self.running
    }

    /// `out_valid`, `out_last` and the head beat.
    pub fn out(&self) -> Option<(&Beat, bool)> {
        self.queue.head.as_ref().map(|b| (b, self.to_deliver == 1))
    }

    /// The AR and R signals of this clock into `m`.
    pub fn drive(&self, m: &mut ManagerSignals) {
        m.arvalid = self.ar.is_some();
        let (address, length) = self.ar.unwrap_or((0, 0));
        m.araddr = address;
        m.arlen = length;
        m.arsize = u64::from(self.config.beat_bytes().trailing_zeros());
        m.arburst = 1;
        m.rready = true;
    }

    /// The edge: `arready` and the R beat (`rvalid`: data, `rlast`, an
    /// error response) from the memory, `out_ready` from the reader of
    /// the stream, and `start` with its base and beats.
    pub fn edge(
        &mut self,
        arready: bool,
        r: Option<(Beat, bool, bool)>,
        out_ready: bool,
        start: Option<(u64, u64)>,
    ) {
        // Every decision reads the registers as they were before the edge.
        let finish = self.running && self.to_deliver == 0;
        let delivered = self.queue.head.is_some() && out_ready;
        let burst_done = r.as_ref().is_some_and(|&(_, last, _)| last);
        if r.as_ref().is_some_and(|&(_, _, error)| error) {
            self.failed = true;
        }
        if delivered {
            self.to_deliver -= 1;
        }
        let burst = self.burst_q;
        let next_burst_q = next_burst(&self.config, self.next_address, self.to_request);
        let issue = self.running
            && self.ar.is_none()
            && self.burst_ok
            && self.to_request != 0
            && self.in_flight < self.config.outstanding
            && self.committed + burst <= self.config.queue_beats as u64;
        if self.ar.is_some() && arready {
            self.ar = None;
        }
        if issue {
            self.ar = Some((self.next_address, burst - 1));
            self.next_address += burst * self.config.beat_bytes();
            self.to_request -= burst;
            self.committed += burst;
            self.in_flight += 1;
        }
        if burst_done {
            self.in_flight -= 1;
        }
        if delivered {
            self.committed -= 1;
        }
        if finish {
            self.running = false;
        }
        self.burst_q = next_burst_q;
        self.burst_ok = !issue;
        if let Some((base, beats)) = start.filter(|_| !self.running) {
            self.burst_ok = false;
            self.running = true;
            self.failed = false;
            self.next_address = base;
            self.to_request = beats;
            self.to_deliver = beats;
        }
        self.queue.edge(r.map(|(beat, _, _)| beat), delivered);
    }
}

/// [`super::burst_writer::BurstWriter`]'s registers.
#[derive(Clone, Debug)]
pub struct WriterModel {
    config: TransferConfig,
    queue: Queue<Beat>,
    /// The lengths of bursts issued on AW and not yet begun on W.
    lengths: Queue<u64>,
    running: bool,
    pub failed: bool,
    ended: bool,
    received: u64,
    issued: u64,
    sent: u64,
    aw_next: u64,
    w_left: u64,
    unanswered: usize,
    aw: Option<(u64, u64)>,
    aw_full: u64,
    aw_full_ok: bool,
}

impl WriterModel {
    pub fn new(config: TransferConfig) -> Self {
        WriterModel {
            config,
            queue: Queue::default(),
            lengths: Queue::default(),
            running: false,
            failed: false,
            ended: false,
            received: 0,
            issued: 0,
            sent: 0,
            aw_next: 0,
            w_left: 0,
            unanswered: 0,
            aw: None,
            aw_full: 0,
            aw_full_ok: false,
        }
    }

    pub fn busy(&self) -> bool {
        self.running
    }

    pub fn in_ready(&self) -> bool {
        self.running && !self.ended && self.queue.count() < self.config.queue_beats
    }

    fn wvalid(&self) -> bool {
        self.queue.head.is_some() && (self.w_left != 0 || self.lengths.head.is_some())
    }

    /// The length at the head of the queue of lengths (0 when empty).
    fn next_length(&self) -> u64 {
        self.lengths.head.unwrap_or(0)
    }

    /// The AW, W and B signals of this clock into `m`.
    pub fn drive(&self, m: &mut ManagerSignals) {
        m.awvalid = self.aw.is_some();
        let (address, length) = self.aw.unwrap_or((0, 0));
        m.awaddr = address;
        m.awlen = length;
        m.awsize = u64::from(self.config.beat_bytes().trailing_zeros());
        m.awburst = 1;
        m.wvalid = self.wvalid();
        m.wdata = self.queue.head.clone().unwrap_or_default();
        m.wlast = if self.w_left == 0 {
            self.next_length() == 1
        } else {
            self.w_left == 1
        };
        m.bready = true;
    }

    /// The edge: the beat offered (`in_valid` with its data and `in_last`),
    /// `flush`, the memory's `awready`, `wready`, `bvalid` (with an error
    /// response), and `start` with its base.
    #[allow(clippy::too_many_arguments)]
    pub fn edge(
        &mut self,
        offered: Option<(Beat, bool)>,
        flush: bool,
        awready: bool,
        wready: bool,
        b: Option<bool>,
        start: Option<u64>,
    ) {
        // Every decision reads the registers as they were before the edge.
        let finish = self.running
            && self.ended
            && self.sent == self.received
            && self.unanswered == 0
            && self.aw.is_none();
        let taken = offered.filter(|_| self.in_ready());
        let pending = self.received - self.issued;
        let full = self.aw_full;
        let next_full = next_burst(&self.config, self.aw_next, u64::MAX);
        let issue = self.running
            && self.aw.is_none()
            && self.aw_full_ok
            && self.unanswered < self.config.outstanding
            && (pending >= full || (self.ended && pending != 0));
        let beat_out = self.wvalid() && wready;
        let starts_burst = beat_out && self.w_left == 0;
        let length = self.next_length();
        let mut issued_length = None;
        if taken.as_ref().is_some_and(|&(_, last)| last) || (self.running && flush) {
            self.ended = true;
        }
        if taken.is_some() {
            self.received += 1;
        }
        if self.aw.is_some() && awready {
            self.aw = None;
        }
        if issue {
            let burst = full.min(pending);
            issued_length = Some(burst);
            self.aw = Some((self.aw_next, burst - 1));
            self.aw_next += burst * self.config.beat_bytes();
            self.issued += burst;
            self.unanswered += 1;
        }
        if beat_out {
            self.sent += 1;
            self.w_left = if self.w_left == 0 {
                length - 1
            } else {
                self.w_left - 1
            };
        }
        if let Some(error) = b {
            self.failed |= error;
            self.unanswered -= 1;
        }
        if finish {
            self.running = false;
        }
        self.aw_full = next_full;
        self.aw_full_ok = !issue;
        if let Some(base) = start.filter(|_| !self.running) {
            self.aw_full_ok = false;
            self.running = true;
            self.failed = false;
            self.ended = flush;
            self.received = 0;
            self.issued = 0;
            self.sent = 0;
            self.aw_next = base;
            self.w_left = 0;
        }
        self.queue.edge(taken.map(|(beat, _)| beat), beat_out);
        self.lengths.edge(issued_length, starts_burst);
    }
}

/// What a copy took.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct CopyRun {
    /// Clocks from `start` (clock 0) to the first clock with `done`.
    pub cycles: u64,
    /// Clocks the memory stalled in that time.
    pub stalled: u64,
    pub error: bool,
}

/// [`super::axi_copy::AxiCopy`] with its two units, and the memory.
#[derive(Clone, Debug)]
pub struct CopyModel {
    pub reader: ReaderModel,
    pub writer: WriterModel,
    active: bool,
    finished: bool,
    pub memory: AxiMemory,
}

impl CopyModel {
    pub fn new(config: TransferConfig, memory: AxiMemory) -> Self {
        CopyModel {
            reader: ReaderModel::new(config),
            writer: WriterModel::new(config),
            active: false,
            finished: false,
            memory,
        }
    }

    /// One clock: `start` with source, destination and beats, if given.
    fn clock(&mut self, start: Option<(u64, u64, u64)>) {
        let start = start.filter(|_| !self.active);
        let mem = self.memory.outputs();
        let mut m = ManagerSignals::default();
        self.reader.drive(&mut m);
        self.writer.drive(&mut m);
        let in_ready = self.writer.in_ready();
        let offered = self.reader.out().map(|(b, last)| (b.clone(), last));
        let r = mem.rvalid.then(|| (mem.rdata.clone(), mem.rlast, false));
        let b = mem.bvalid.then_some(false);
        let wready = mem.wready;
        let units_idle = !self.reader.busy() && !self.writer.busy();
        self.reader
            .edge(mem.arready, r, in_ready, start.map(|(s, _, n)| (s, n)));
        let flush = start.is_some_and(|(_, _, n)| n == 0);
        self.writer.edge(
            offered,
            flush,
            mem.awready,
            wready,
            b,
            start.map(|(_, d, _)| d),
        );
        if self.active && units_idle {
            self.active = false;
            self.finished = true;
        }
        if start.is_some() {
            self.active = true;
            self.finished = false;
        }
        self.memory.edge(&m);
    }

    /// Copies `beats` beats from `source` to `destination`: the clocks to
    /// `done`, at most `limit` (None past it).
    pub fn copy(
        &mut self,
        source: u64,
        destination: u64,
        beats: u64,
        limit: u64,
    ) -> Option<CopyRun> {
        let stalled_before = self.memory.stalled;
        self.clock(Some((source, destination, beats)));
        let mut cycles = 1;
        while !self.finished {
            if cycles >= limit {
                return None;
            }
            self.clock(None);
            cycles += 1;
        }
        Some(CopyRun {
            cycles,
            stalled: self.memory.stalled - stalled_before,
            error: self.reader.failed || self.writer.failed,
        })
    }
}

/// The clocks of a copy of `beats` beats on the units built for `config`
/// against a memory of `params`, and the memory afterwards (or None if it
/// ran past `limit` clocks).
pub fn copy_cycles(
    config: TransferConfig,
    params: MemoryParams,
    bytes: Vec<u8>,
    (source, destination, beats): (u64, u64, u64),
    limit: u64,
) -> Option<(CopyRun, AxiMemory)> {
    let mut model = CopyModel::new(config, AxiMemory::new(params, bytes));
    let run = model.copy(source, destination, beats, limit)?;
    Some((run, model.memory))
}

#[cfg(test)]
mod tests {
    use super::Queue;
    use std::collections::VecDeque;

    /// The queue before the spare: the stage fetched whenever the head was
    /// free, so a pop reached the RAM's read enable. The spare must not
    /// change a clock of what the queue shows.
    #[derive(Default)]
    struct StageOnly {
        stored: VecDeque<u32>,
        stage: Option<u32>,
        head: Option<u32>,
    }

    impl StageOnly {
        fn count(&self) -> usize {
            self.stored.len() + self.stage.is_some() as usize + self.head.is_some() as usize
        }

        fn edge(&mut self, push: Option<u32>, pop: bool) {
            let popped = pop && self.head.is_some();
            let head_free = self.head.is_none() || popped;
            let fetch = (self.stage.is_none() || head_free) && !self.stored.is_empty();
            if head_free {
                self.head = self.stage.take();
            }
            if fetch {
                self.stage = self.stored.pop_front();
            }
            if let Some(word) = push {
                self.stored.push_back(word);
            }
        }
    }

    #[test]
    fn the_spare_changes_no_clock_of_the_head_or_the_count() {
        // Bursts of pushes and pops at several densities, from a fixed LCG.
        let mut state = 0x2545_f491_4f6c_dd1du64;
        let mut next = move || {
            state = state
                .wrapping_mul(6_364_136_223_846_793_005)
                .wrapping_add(1_442_695_040_888_963_407);
            (state >> 33) as u32
        };
        let mut stalls = 0;
        for density in [10, 30, 50, 70, 90, 100] {
            let mut queue = Queue::<u32>::default();
            let mut reference = StageOnly::default();
            for clock in 0..20_000u32 {
                assert_eq!(queue.head, reference.head, "head, clock {clock}");
                assert_eq!(queue.count(), reference.count(), "count, clock {clock}");
                let push = (next() % 100 < density && queue.count() < 34).then_some(clock);
                let pop = next() % 100 < 100 - density / 2;
                stalls += (pop && queue.head.is_none() && queue.count() > 0) as usize;
                queue.edge(push, pop);
                reference.edge(push, pop);
            }
        }
        // The sequences did reach a head that was still on its way.
        assert!(stalls > 0);
    }
}
