//! The clock-exact model of the leaf reader ([`super::leaf_reader`]): its
//! registers, its reader and its queue of entries, clock by clock, against
//! the memory model ([`crate::axi::memory_model`]), with the stream's
//! `out_ready` from the caller.
//!
//! [`LeafReaderMachine::clock`] computes what the unit shows in a clock
//! from its registers and then what they take at the edge, in the order
//! `update` writes them; the caller clocks the memory, so that the unit can
//! share a memory with the controller's passes.

use super::list_entry::ENTRY_BYTES;
use super::list_pass_machine::ListPassConfig;
use crate::axi::memory_model::{AxiMemory, ManagerSignals, MemoryOutputs};
use crate::axi::transfer_machine::{Queue, ReaderModel};
use tritri_geom::octree::cell::Cell;

/// Words of the queue of entries ([`crate::axi::beat_fifo`]).
const ENTRY_CAPACITY: usize = (1 << super::leaf_reader::LEAF_QUEUE_ADDRESS_BITS) + 2;

/// A leaf to read: its cell and its two lists, `(address, entries)`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct LeafRequest {
    pub cell: Cell,
    pub lists: [(u64, u64); 2],
}

/// A word of the leaf stream.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum LeafWord {
    /// The leaf's cell and its lists' entries.
    Header { cell: Cell, counts: [u64; 2] },
    /// An entry of object B (`object`) or A, its 32 bytes as in memory.
    Entry { object: bool, entry: Vec<u8> },
}

/// The unit's registers.
#[derive(Clone, Debug)]
pub struct LeafReaderMachine {
    config: ListPassConfig,
    reader: ReaderModel,
    entries: Queue<(Vec<u8>, bool)>,
    running: bool,
    header_due: bool,
    read_stage: u8,
    cell: Cell,
    count_a: u64,
    base_b: u64,
    count_b: u64,
    left: u64,
    gear: Vec<u8>,
    gear_count: u64,
    entries_in: u64,
}

impl LeafReaderMachine {
    /// The reader of a unit whose port and bursts `config` gives (its grid
    /// bits are not used: the unit does not look into the entries).
    pub fn new(config: ListPassConfig) -> Self {
        LeafReaderMachine {
            config,
            reader: ReaderModel::new(config.reader()),
            entries: Queue::default(),
            running: false,
            header_due: false,
            read_stage: 0,
            cell: Cell {
                lo: [0; 3],
                level: 0,
            },
            count_a: 0,
            base_b: 0,
            count_b: 0,
            left: 0,
            gear: vec![0; ENTRY_BYTES],
            gear_count: 0,
            entries_in: 0,
        }
    }

    /// `busy`: a leaf is under way.
    pub fn busy(&self) -> bool {
        self.running
    }

    /// `reading`: the read channel is the unit's.
    pub fn reading(&self) -> bool {
        self.running && self.read_stage != 3
    }

    /// A read response was not OKAY since the last start.
    pub fn failed(&self) -> bool {
        self.reader.failed
    }

    /// The word `out_valid` offers this clock.
    pub fn out(&self) -> Option<LeafWord> {
        if self.header_due {
            Some(LeafWord::Header {
                cell: self.cell,
                counts: [self.count_a, self.count_b],
            })
        } else {
            self.entries
                .head
                .as_ref()
                .map(|(entry, object)| LeafWord::Entry {
                    object: *object,
                    entry: entry.clone(),
                })
        }
    }

    /// The AR and R signals of this clock into `m`.
    pub fn drive(&self, m: &mut ManagerSignals) {
        self.reader.drive(m);
    }

    /// One clock: the memory's outputs `mem`, `start` if given (taken only
    /// while idle) and the stream's `out_ready`. Gives the word the stream
    /// took in this clock.
    pub fn clock(
        &mut self,
        mem: &MemoryOutputs,
        start: Option<&LeafRequest>,
        out_ready: bool,
    ) -> Option<LeafWord> {
        let per_entry = self.config.beats_per_entry();
        let start = start.filter(|_| !self.running);

        // The reads.
        let mut reader_start = None;
        let mut read_stage = self.read_stage;
        if self.running && self.read_stage == 1 && !self.reader.busy() {
            reader_start = Some((self.base_b, self.count_b * per_entry));
            read_stage = 2;
        }
        if self.running && self.read_stage == 2 && !self.reader.busy() {
            read_stage = 3;
        }
        if let Some(p) = start {
            reader_start = Some((p.lists[0].0, p.lists[0].1 * per_entry));
        }

        // The gearbox.
        let room = self.entries.count() < ENTRY_CAPACITY;
        let beat_ready = self.gear_count != per_entry - 1 || room;
        let head = self.reader.out().map(|(b, _)| b.clone());
        let accepted = head.is_some() && beat_ready;
        let push = accepted && self.gear_count == per_entry - 1;
        let assembled = head.as_ref().map(|beat| {
            let mut e = self.gear[beat.len()..].to_vec();
            e.extend_from_slice(beat);
            e
        });
        let entry_in = push.then(|| (assembled.clone().unwrap(), self.entries_in >= self.count_a));

        // The stream.
        let sent = self.out().filter(|_| out_ready);
        let send_entry = !self.header_due && self.entries.head.is_some() && out_ready;

        // The edge.
        let r = mem.rvalid.then(|| (mem.rdata.clone(), mem.rlast, false));
        self.reader.edge(mem.arready, r, beat_ready, reader_start);
        self.read_stage = read_stage;
        if accepted {
            self.gear = assembled.unwrap();
            self.gear_count += 1;
        }
        if push {
            self.gear_count = 0;
            self.entries_in += 1;
        }
        if self.header_due && out_ready {
            self.header_due = false;
            if self.left == 0 {
                self.running = false;
            }
        }
        if send_entry {
            if self.left == 1 {
                self.running = false;
            }
            self.left -= 1;
        }
        if let Some(p) = start {
            self.running = true;
            self.header_due = true;
            self.cell = p.cell;
            self.count_a = p.lists[0].1;
            self.base_b = p.lists[1].0;
            self.count_b = p.lists[1].1;
            self.left = p.lists[0].1 + p.lists[1].1;
            self.read_stage = 1;
            self.gear_count = 0;
            self.entries_in = 0;
        }
        self.entries.edge(entry_in, send_entry);
        sent
    }
}

/// What reading one leaf took and gave.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct LeafReadRun {
    /// Every word of the stream with the clock it was taken in (`start`'s
    /// clock is 0).
    pub words: Vec<(u64, LeafWord)>,
    /// The first clock with `reading` low.
    pub read_cycles: u64,
    /// The first clock with `busy` low.
    pub cycles: u64,
    /// Clocks the memory stalled in that time.
    pub stalled: u64,
    pub error: bool,
}

/// Reads `leaf` with the unit built for `config` from `memory`, the
/// stream's `out_ready` in clock `t` being `ready(t)`; None if it is not
/// done within `limit` clocks.
pub fn read_leaf(
    config: ListPassConfig,
    memory: &mut AxiMemory,
    leaf: &LeafRequest,
    ready: impl Fn(u64) -> bool,
    limit: u64,
) -> Option<LeafReadRun> {
    let mut machine = LeafReaderMachine::new(config);
    let stalled_before = memory.stalled;
    let mut words = Vec::new();
    let mut read_cycles = None;
    let mut t = 0;
    loop {
        if t > 0 && !machine.reading() && read_cycles.is_none() {
            read_cycles = Some(t);
        }
        if t > 0 && !machine.busy() {
            break;
        }
        if t >= limit {
            return None;
        }
        let mem = memory.outputs();
        let mut m = ManagerSignals::default();
        machine.drive(&mut m);
        let start = (t == 0).then_some(leaf);
        if let Some(word) = machine.clock(&mem, start, ready(t)) {
            words.push((t, word));
        }
        memory.edge(&m);
        t += 1;
    }
    Some(LeafReadRun {
        words,
        read_cycles: read_cycles.unwrap_or(t),
        cycles: t,
        stalled: memory.stalled - stalled_before,
        error: machine.failed(),
    })
}
