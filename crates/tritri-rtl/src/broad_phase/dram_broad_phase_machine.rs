//! The clock-exact model of the DRAM top ([`super::dram_broad_phase`]) up to
//! the system's last verdict (`binned` and `tested`): the controller's model
//! ([`super::dram_binning_machine`]) with what sits beside it in the top,
//! clocked in every clock of the walk and after it:
//!
//! * the owner filter's heads, cleared one index a clock after `start`;
//! * the sequencer, which takes a leaf and starts the reader
//!   ([`super::leaf_reader_machine`]) on each of its tiles;
//! * the leaf batcher's one register stage ([`super::leaf_batcher`]);
//! * the collision system's address generator
//!   ([`crate::system::address_generator`]): its two banks, written as the
//!   batcher offers words, read as nested loops, the last verdict counted
//!   `read_to_counted_cycles` after the last read.
//!
//! What it leaves out: the result FIFO's back-pressure (the read side runs
//! on while the FIFO has room, which a pair reader always ready and the
//! owner filter keep) and the shared rare-case unit's holds (the model is
//! of the system with parallel rare-case units). The owner filter after the
//! last verdict adds its clocks for the hits left; `done` is not modelled.
//! The co-simulation (`tritri-cosim/tests/dram_broad_phase.rs`) holds
//! rust-hdl to it.

use super::dram_binning_machine::{
    run_dram_binning_beside, Beside, DramBinningConfig, DramBinningRun, ListPlace,
};
use super::leaf_reader_machine::{LeafReaderMachine, LeafRequest, LeafWord};
use crate::axi::memory_model::{AxiMemory, ManagerSignals, MemoryOutputs};
use crate::system::SystemConfig;
use tritri_geom::octree::cell::Cell;

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Sequence {
    Idle,
    Issue,
    Read,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum ReadState {
    Idle,
    LoadBases,
    StreamB,
}

/// The system's address generator: the registers its cycles depend on.
#[derive(Clone, Debug)]
struct Banks {
    write_bank: usize,
    full: [bool; 2],
    counts: [(u64, u64); 2],
    written: (u64, u64),
    read_bank: usize,
    state: ReadState,
    a_left: u64,
    a_left_one: bool,
    a_left_none: bool,
    b_count: u64,
    b_left: u64,
    b_left_one: bool,
    lane: u64,
    flight: u64,
    last_lane: u64,
    flight_cycles: u64,
}

impl Banks {
    fn new(system: SystemConfig) -> Self {
        Banks {
            write_bank: 0,
            full: [false; 2],
            counts: [(0, 0); 2],
            written: (0, 0),
            read_bank: 0,
            state: ReadState::Idle,
            a_left: 0,
            a_left_one: false,
            a_left_none: false,
            b_count: 0,
            b_left: 0,
            b_left_one: false,
            lane: 0,
            flight: 0,
            last_lane: system.pipelines as u64 - 1,
            flight_cycles: system.read_to_counted_cycles() as u64,
        }
    }

    fn in_ready(&self) -> bool {
        !self.full[self.write_bank]
    }

    fn done(&self) -> bool {
        !self.full[0] && !self.full[1] && self.state == ReadState::Idle && self.flight == 0
    }

    /// One clock: `word` is the batcher's offered word (`Some(end,
    /// object)`), taken if [`Banks::in_ready`].
    fn clock(&mut self, word: Option<(bool, bool)>) {
        let mut full = self.full;
        if let Some((end, object)) = word.filter(|_| self.in_ready()) {
            if end {
                let (a, b) = self.written;
                full[self.write_bank] = true;
                self.counts[self.write_bank] = (a, b);
                self.write_bank ^= 1;
                self.written = (0, 0);
            } else if object {
                self.written.1 += 1;
            } else {
                self.written.0 += 1;
            }
        }
        let mut release = false;
        let mut stream_issue = false;
        match self.state {
            ReadState::Idle => {
                if self.full[self.read_bank] {
                    let (a, b) = self.counts[self.read_bank];
                    self.a_left = a;
                    self.a_left_one = a == 1;
                    self.a_left_none = a == 0;
                    self.b_count = b;
                    self.lane = 0;
                    if a == 0 || b == 0 {
                        release = true;
                    } else {
                        self.state = ReadState::LoadBases;
                    }
                }
            }
            ReadState::LoadBases => {
                let (left, one, lane) = (self.a_left, self.a_left_one, self.lane);
                self.a_left = left - 1;
                self.a_left_one = left == 2;
                self.a_left_none = one;
                self.lane = lane + 1;
                if lane == self.last_lane || one {
                    self.state = ReadState::StreamB;
                    self.b_left = self.b_count;
                    self.b_left_one = self.b_count == 1;
                }
            }
            ReadState::StreamB => {
                stream_issue = true;
                let (left, one) = (self.b_left, self.b_left_one);
                self.b_left = left - 1;
                self.b_left_one = left == 2;
                if one {
                    if self.a_left_none {
                        release = true;
                        self.state = ReadState::Idle;
                    } else {
                        self.state = ReadState::LoadBases;
                        self.lane = 0;
                    }
                }
            }
        }
        if stream_issue {
            self.flight = self.flight_cycles;
        } else if self.flight != 0 {
            self.flight -= 1;
        }
        if release {
            full[self.read_bank] = false;
            self.read_bank ^= 1;
        }
        self.full = full;
    }
}

/// The leaf batcher's registers.
#[derive(Clone, Debug, Default)]
struct Batcher {
    valid: bool,
    end: bool,
    object: bool,
    end_due: bool,
    remaining: u64,
}

/// Everything beside the controller in the top.
struct NarrowSide {
    depth: u64,
    index_count: [u64; 2],
    started: bool,
    clear: [u64; 2],
    seq: Sequence,
    cell: Cell,
    lists: [ListPlace; 2],
    a_at: u64,
    a_rest: u64,
    b_at: u64,
    b_rest: u64,
    leaves: u64,
    reader: LeafReaderMachine,
    batcher: Batcher,
    banks: Banks,
}

impl NarrowSide {
    fn cleared(&self) -> bool {
        self.clear == [0, 0]
    }

    /// `tested` but for the controller's `done`.
    fn quiet(&self) -> bool {
        self.cleared()
            && self.seq == Sequence::Idle
            && !self.reader.busy()
            && !(self.batcher.valid || self.batcher.end_due)
            && self.banks.done()
    }
}

impl Beside for NarrowSide {
    fn hold(&self) -> bool {
        self.seq != Sequence::Idle || self.reader.reading() || !self.cleared()
    }

    fn ready(&self) -> bool {
        self.seq == Sequence::Idle && self.cleared()
    }

    fn drive(&self, m: &mut ManagerSignals) {
        if self.seq != Sequence::Idle {
            self.reader.drive(m);
        }
    }

    fn clock(&mut self, mem: &MemoryOutputs, leaf: Option<(Cell, [ListPlace; 2])>) {
        let take = self.ready();
        let (busy, reading) = (self.reader.busy(), self.reader.reading());
        // The read channel is the reader's while a leaf is held.
        let mut own = mem.clone();
        if self.seq == Sequence::Idle {
            own.arready = false;
            own.rvalid = false;
        }
        let start = (self.seq == Sequence::Issue && !busy).then(|| LeafRequest {
            cell: self.cell,
            lists: [
                (self.a_at, self.a_rest.min(self.depth)),
                (self.b_at, self.b_rest.min(self.depth)),
            ],
        });
        let advance = !self.batcher.valid || self.banks.in_ready();
        let in_ready = advance && !self.batcher.end_due;
        let word = self.reader.clock(&own, start.as_ref(), in_ready);
        let offered = self
            .batcher
            .valid
            .then_some((self.batcher.end, self.batcher.object));
        self.banks.clock(offered);

        // The batcher's edge.
        if advance {
            let b = &mut self.batcher;
            b.valid = false;
            if b.end_due {
                b.valid = true;
                b.end = true;
                b.end_due = false;
            } else {
                match word {
                    Some(LeafWord::Header { counts, .. }) => b.remaining = counts[0] + counts[1],
                    Some(LeafWord::Entry { object, .. }) => {
                        b.valid = true;
                        b.end = false;
                        b.object = object;
                        b.end_due = b.remaining == 1;
                        b.remaining -= 1;
                    }
                    None => {}
                }
            }
        }

        // The sequencer's edge.
        match self.seq {
            Sequence::Idle => {
                if let Some((cell, lists)) = leaf.filter(|_| take) {
                    self.cell = cell;
                    self.lists = lists;
                    (self.a_at, self.a_rest) = lists[0];
                    (self.b_at, self.b_rest) = lists[1];
                    self.leaves += 1;
                    if lists[0].1 != 0 && lists[1].1 != 0 {
                        self.seq = Sequence::Issue;
                    }
                }
            }
            Sequence::Issue => {
                if !busy {
                    self.seq = Sequence::Read;
                }
            }
            Sequence::Read => {
                if !reading {
                    let tile_bytes = self.depth * super::list_entry::ENTRY_BYTES as u64;
                    self.seq = Sequence::Issue;
                    if self.b_rest > self.depth {
                        self.b_at += tile_bytes;
                        self.b_rest -= self.depth;
                    } else if self.a_rest > self.depth {
                        self.a_at += tile_bytes;
                        self.a_rest -= self.depth;
                        (self.b_at, self.b_rest) = self.lists[1];
                    } else {
                        self.seq = Sequence::Idle;
                    }
                }
            }
        }

        // The owner filter's heads: set at `start` (the first clock),
        // counted down after.
        if !self.started {
            self.started = true;
            self.clear = self.index_count;
        } else if self.clear[0] != 0 {
            self.clear[0] -= 1;
        } else if self.clear[1] != 0 {
            self.clear[1] -= 1;
        }
    }
}

/// What the model gives: the clocks from `start` (clock 0) at which
/// `binned` and `tested` are first high, and the walk's run.
#[derive(Clone, Debug)]
pub struct DramBroadPhaseTimes {
    pub binned_at: u64,
    pub tested_at: u64,
    pub leaves: u64,
    pub walk: DramBinningRun,
}

/// The top of `config` (its controller) around the system of `system`, on
/// `memory` holding the root lists `root_lists` (entries numbered below
/// `index_count`), from `root`; an error names a pass that failed or a top
/// that did not finish in `limit` clocks.
pub fn run_dram_broad_phase(
    config: DramBinningConfig,
    system: SystemConfig,
    memory: &mut AxiMemory,
    root: Cell,
    root_lists: [ListPlace; 2],
    index_count: [u64; 2],
    limit: u64,
) -> Result<DramBroadPhaseTimes, String> {
    let mut side = NarrowSide {
        depth: system.triangles_per_bank as u64,
        index_count,
        started: false,
        clear: [0, 0],
        seq: Sequence::Idle,
        cell: root,
        lists: [(0, 0); 2],
        a_at: 0,
        a_rest: 0,
        b_at: 0,
        b_rest: 0,
        leaves: 0,
        reader: LeafReaderMachine::new(config.pass),
        batcher: Batcher::default(),
        banks: Banks::new(system),
    };
    let walk = run_dram_binning_beside(config, memory, root, root_lists, &mut side)?;
    let binned_at = walk.cycles;
    let mut t = binned_at;
    while !side.quiet() {
        if t >= limit {
            return Err(format!(
                "the top was not done testing within {limit} clocks"
            ));
        }
        let mem = memory.outputs();
        let mut m = ManagerSignals::default();
        side.drive(&mut m);
        side.clock(&mem, None);
        memory.edge(&m);
        t += 1;
    }
    Ok(DramBroadPhaseTimes {
        binned_at,
        tested_at: t,
        leaves: side.leaves,
        walk,
    })
}
