//! The clock-exact model of a cell's pass over lists in external memory
//! ([`super::list_pass`]): the unit's registers and queues, clock by
//! clock, against the memory model ([`crate::axi::memory_model`]), with
//! the classifier's masks from the software test
//! ([`TriangleCellTest::children_of_cell`], which the lane equals).
//!
//! `clock` computes what the unit shows in a clock from its registers and
//! then what they take at the edge, in the order `update` writes them, so
//! the model and the circuit can be compared a clock at a time.

use super::classify_lane::lane_latency;
use super::list_entry::{unpack, ENTRY_BYTES};
use super::list_pass::{
    CHILDREN, ENTRY_QUEUE_ADDRESS_BITS, READ_QUEUE_ADDRESS_BITS, WRITE_BURST_BEATS,
};
use crate::axi::memory_model::{AxiMemory, ManagerSignals};
use crate::axi::transfer_machine::{Beat, Queue, ReaderModel};
use crate::axi::TransferConfig;
use std::collections::VecDeque;
use tritri_geom::octree::cell::Cell;
use tritri_geom::octree::triangle_cell::{TriangleCellTest, BROAD_PHASE_MARGIN};

/// Words of the queues of entries and masks ([`crate::axi::beat_fifo`]).
const ENTRY_CAPACITY: usize = (1 << ENTRY_QUEUE_ADDRESS_BITS) + 2;
/// Beats of the W side's queue.
const W_CAPACITY: usize = (1 << 4) + 2;

/// The port widths a pass unit (and the leaf reader) is built for: an
/// entry is one to four beats.
pub const PASS_DATA_BITS: [usize; 3] = [64, 128, 256];

/// How a pass unit is built.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ListPassConfig {
    /// Grid bits of the coordinates.
    pub grid_bits: usize,
    /// Data bits of the port: 64, 128 or 256.
    pub data_bits: usize,
    /// The longest read burst.
    pub max_read_burst: usize,
    /// Bursts in flight, per direction.
    pub outstanding: usize,
}

impl ListPassConfig {
    pub fn beat_bytes(&self) -> u64 {
        self.data_bits as u64 / 8
    }

    pub fn beats_per_entry(&self) -> u64 {
        ENTRY_BYTES as u64 / self.beat_bytes()
    }

    /// Bytes of a write burst: the alignment of every child list.
    pub fn burst_bytes(&self) -> u64 {
        WRITE_BURST_BEATS as u64 * self.beat_bytes()
    }

    /// The reader's configuration.
    pub fn reader(&self) -> TransferConfig {
        TransferConfig {
            data_bits: self.data_bits,
            max_burst: self.max_read_burst,
            outstanding: self.outstanding,
            queue_beats: (1 << READ_QUEUE_ADDRESS_BITS) + 2,
        }
    }

    /// An error naming the parameter the unit is not built for, if any.
    pub fn check(&self) -> Result<(), String> {
        if !PASS_DATA_BITS.contains(&self.data_bits) {
            return Err(format!(
                "a pass's port is 64, 128 or 256 bits wide, not {}",
                self.data_bits
            ));
        }
        if !(1..=super::list_entry::MAX_GRID_BITS).contains(&self.grid_bits) {
            return Err(format!(
                "an entry holds 1- to {}-bit coordinates, not {}",
                super::list_entry::MAX_GRID_BITS,
                self.grid_bits
            ));
        }
        self.reader().check()
    }
}

/// One pass: the cell, its two lists and where the children's go.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct PassRequest {
    /// At least level 1.
    pub cell: Cell,
    /// Object `k`'s list: `(address, entries)`.
    pub lists: [(u64, u64); 2],
    /// Object `k`'s children: `(address of child 0, bytes between children)`.
    pub children: [(u64, u64); 2],
}

/// What a pass took and gave.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct PassRun {
    /// Clocks from `start` (clock 0) to the first clock with `done`.
    pub cycles: u64,
    /// Clocks the memory stalled in that time.
    pub stalled: u64,
    pub error: bool,
    /// Entries written to child `8k + o`.
    pub child_counts: [u64; CHILDREN],
}

/// A write command: the burst's address, its beats, its slot.
type Command = (u64, u64, usize);

/// The unit's registers and queues.
struct Machine {
    config: ListPassConfig,
    reader: ReaderModel,
    entries: Queue<(Vec<u8>, bool)>,
    masks: Queue<u8>,
    /// The lane: the mask shown at its output is the front.
    lane: VecDeque<Option<u8>>,
    buffer: Vec<Beat>,
    read_data: Beat,
    commands: Queue<Command>,
    bursts: Queue<(u64, usize)>,
    w_data: Queue<Beat>,
    w_last: Queue<bool>,
    running: bool,
    finished: bool,
    failed: bool,
    cell: Cell,
    count_a: u64,
    base_b: u64,
    count_b: u64,
    stride: [u64; 2],
    read_stage: u8,
    setup_left: u8,
    gear: Vec<u8>,
    gear_count: u64,
    entries_in: u64,
    entry: Vec<u8>,
    object: bool,
    mask_left: u8,
    /// The children an A entry has been written to in this pass.
    reached: u8,
    beat: u64,
    flushing: bool,
    flushed: bool,
    flush_child: usize,
    fill: [u64; CHILDREN],
    half: [bool; CHILDREN],
    pending: [[bool; 2]; CHILDREN],
    count: [u64; CHILDREN],
    region: [u64; CHILDREN],
    aw: Option<(u64, u64)>,
    unanswered: usize,
    feed_left: u64,
    feed_slot: usize,
    feed_address: usize,
    read_valid: bool,
    read_last: bool,
}

impl Machine {
    fn new(config: ListPassConfig) -> Self {
        Machine {
            config,
            reader: ReaderModel::new(config.reader()),
            entries: Queue::default(),
            masks: Queue::default(),
            // The lane shares its products over an entry's beats.
            lane: std::iter::repeat_n(None, lane_latency(config.beats_per_entry() as usize))
                .collect(),
            buffer: vec![vec![0; config.beat_bytes() as usize]; 2 * CHILDREN * WRITE_BURST_BEATS],
            read_data: vec![0; config.beat_bytes() as usize],
            commands: Queue::default(),
            bursts: Queue::default(),
            w_data: Queue::default(),
            w_last: Queue::default(),
            running: false,
            finished: false,
            failed: false,
            cell: Cell {
                lo: [0; 3],
                level: 1,
            },
            count_a: 0,
            base_b: 0,
            count_b: 0,
            stride: [0; 2],
            read_stage: 0,
            setup_left: 0,
            gear: vec![0; ENTRY_BYTES],
            gear_count: 0,
            entries_in: 0,
            entry: vec![0; ENTRY_BYTES],
            object: false,
            mask_left: 0,
            reached: 0,
            beat: 0,
            flushing: false,
            flushed: false,
            flush_child: 0,
            fill: [0; CHILDREN],
            half: [false; CHILDREN],
            pending: [[false; 2]; CHILDREN],
            count: [0; CHILDREN],
            region: [0; CHILDREN],
            aw: None,
            unanswered: 0,
            feed_left: 0,
            feed_slot: 0,
            feed_address: 0,
            read_valid: false,
            read_last: false,
        }
    }

    /// The classifier's mask of an entry in the pass's cell.
    fn mask(&self, entry: &[u8]) -> u8 {
        let (_, triangle) = unpack(entry, self.config.grid_bits);
        TriangleCellTest::widened(&triangle, BROAD_PHASE_MARGIN).children_of_cell(&self.cell)
    }

    /// The AW, W and B signals of this clock into `m`.
    fn drive(&self, m: &mut ManagerSignals) {
        self.reader.drive(m);
        m.awvalid = self.aw.is_some();
        let (address, length) = self.aw.unwrap_or((0, 0));
        m.awaddr = address;
        m.awlen = length;
        m.awsize = u64::from(self.config.beat_bytes().trailing_zeros());
        m.awburst = 1;
        m.wvalid = self.w_data.head.is_some();
        m.wdata = self.w_data.head.clone().unwrap_or_default();
        m.wlast = self.w_last.head.unwrap_or(false);
        m.bready = true;
    }

    /// One clock against `memory`, with `start` if given.
    fn clock(&mut self, memory: &mut AxiMemory, start: Option<&PassRequest>) {
        let c = self.config;
        let per_entry = c.beats_per_entry();
        let burst = WRITE_BURST_BEATS as u64;
        let mem = memory.outputs();
        let mut m = ManagerSignals::default();
        self.drive(&mut m);
        let start = start.filter(|_| !self.running);

        // The reads.
        let mut reader_start = None;
        if self.running && self.read_stage == 1 && !self.reader.busy() {
            reader_start = Some((self.base_b, self.count_b * per_entry));
        }
        let mut read_stage = self.read_stage;
        if self.running && self.read_stage == 1 && !self.reader.busy() {
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
        let out_ready = self.gear_count != per_entry - 1 || room;
        let head = self.reader.out().map(|(b, _)| b.clone());
        let accepted = head.is_some() && out_ready;
        let push = accepted && self.gear_count == per_entry - 1;
        let assembled = head.as_ref().map(|beat| {
            let mut e = self.gear[beat.len()..].to_vec();
            e.extend_from_slice(beat);
            e
        });
        let object_in = self.entries_in >= self.count_a;
        let lane_in = push.then(|| self.mask(assembled.as_ref().unwrap()));
        let entry_in = push.then(|| (assembled.clone().unwrap(), object_in));
        let mask_out = self.lane.front().copied().flatten();

        // The distributor: a B entry only to the children A reached.
        let live = if self.object {
            self.mask_left & self.reached
        } else {
            self.mask_left
        };
        let target = if self.flushing {
            Some(self.flush_child)
        } else if live != 0 {
            Some(usize::from(self.object) * 8 + live.trailing_zeros() as usize)
        } else {
            None
        };
        let (sel_fill, sel_half, sel_blocked, sel_region, sel_slot) = match target {
            Some(i) => (
                self.fill[i],
                self.half[i],
                self.pending[i][usize::from(self.half[i])],
                self.region[i],
                2 * i + usize::from(self.half[i]),
            ),
            None => (0, false, false, 0, 0),
        };
        let _ = sel_half;
        let write = live != 0 && !sel_blocked && !self.flushing;
        let entry_done = write && self.beat == per_entry - 1;
        let last_child = live & live.wrapping_sub(1) == 0;
        let slot_full = write && sel_fill == burst - 1;
        let flush_out = self.flushing && sel_fill != 0;
        let load = self.masks.head.is_some()
            && self.entries.head.is_some()
            && (live == 0 || (entry_done && last_child));
        let flush_begins = self.running
            && self.read_stage == 3
            && self.entries.count() == 0
            && live == 0
            && !self.flushing
            && !self.flushed;
        let command = (slot_full || flush_out).then(|| {
            let beats = if slot_full { sel_fill + 1 } else { sel_fill };
            (sel_region, beats, sel_slot)
        });

        // AW, the feeder, W, B.
        let issue =
            self.commands.head.is_some() && self.aw.is_none() && self.unanswered < c.outstanding;
        let issued = issue.then(|| self.commands.head.unwrap());
        let start_feed = self.feed_left == 0 && self.bursts.head.is_some();
        let w_held = self.w_data.count() + usize::from(self.read_valid);
        let feed = self.feed_left != 0 && w_held < W_CAPACITY;
        let freed = feed && self.feed_left == 1;
        let beat_out = self.w_data.head.is_some() && mem.wready;
        let answered = mem.bvalid;
        let finish = self.running
            && self.flushed
            && self.commands.count() == 0
            && self.aw.is_none()
            && self.bursts.count() == 0
            && self.feed_left == 0
            && !self.read_valid
            && self.w_data.count() == 0
            && self.unanswered == 0;

        // The edge: the reader first (it reads its own registers).
        let r = mem.rvalid.then(|| (mem.rdata.clone(), mem.rlast, false));
        self.reader.edge(mem.arready, r, out_ready, reader_start);
        self.read_stage = read_stage;
        if accepted {
            self.gear = assembled.clone().unwrap();
            self.gear_count += 1;
        }
        if push {
            self.gear_count = 0;
            self.entries_in += 1;
        }
        // The buffer: read first, then written.
        let read_word = feed.then(|| self.buffer[self.feed_address].clone());
        if write {
            let at = (sel_slot * WRITE_BURST_BEATS + sel_fill as usize) % self.buffer.len();
            let bytes = c.beat_bytes() as usize;
            let offset = self.beat as usize * bytes;
            self.buffer[at] = self.entry[offset..offset + bytes].to_vec();
            if entry_done {
                self.beat = 0;
                self.mask_left = live & !(live & live.wrapping_neg());
            } else {
                self.beat += 1;
            }
        }
        if let Some(i) = target {
            if write {
                self.fill[i] += 1;
                if i < 8 {
                    self.reached |= 1 << i;
                }
            }
            if entry_done {
                self.count[i] += 1;
            }
            if slot_full || flush_out {
                self.fill[i] = 0;
                self.pending[i][usize::from(self.half[i])] = true;
                self.half[i] = !self.half[i];
                self.region[i] += c.burst_bytes();
            }
        }
        let popped_entry = load.then(|| self.entries.head.clone().unwrap());
        let popped_mask = load.then(|| self.masks.head.unwrap());
        if let (Some((entry, object)), Some(mask)) = (&popped_entry, popped_mask) {
            self.entry = entry.clone();
            self.object = *object;
            self.mask_left = mask;
            self.beat = 0;
        }
        if flush_begins {
            self.flushing = true;
            self.flush_child = 0;
        }
        if self.flushing && !flush_begins {
            if self.flush_child == CHILDREN - 1 {
                self.flushing = false;
                self.flushed = true;
            }
            self.flush_child += 1;
        }
        if self.aw.is_some() && mem.awready {
            self.aw = None;
        }
        if let Some((address, beats, _)) = issued {
            self.aw = Some((address, beats - 1));
        }
        if start_feed {
            let (beats, slot) = self.bursts.head.unwrap();
            self.feed_left = beats;
            self.feed_slot = slot;
            self.feed_address = slot * WRITE_BURST_BEATS;
        }
        let read_last = feed && self.feed_left == 1;
        if feed {
            self.feed_left -= 1;
            self.feed_address += 1;
        }
        if freed {
            let slot = self.feed_slot;
            self.pending[slot / 2][slot % 2] = false;
        }
        let w_in = self.read_valid.then(|| self.read_data.clone());
        let w_last_in = self.read_valid.then_some(self.read_last);
        if let Some(word) = read_word {
            self.read_data = word;
        }
        self.read_valid = feed;
        self.read_last = read_last;
        if issue && !answered {
            self.unanswered += 1;
        } else if !issue && answered {
            self.unanswered -= 1;
        }
        if finish {
            self.running = false;
            self.finished = true;
        }
        if self.setup_left != 0 {
            self.setup_left -= 1;
            for base in [0, 8] {
                for i in (base + 1..base + 8).rev() {
                    self.region[i] = self.region[i - 1] + self.stride[base / 8];
                }
            }
        }
        if let Some(p) = start {
            self.running = true;
            self.finished = false;
            self.failed = false;
            self.cell = p.cell;
            self.count_a = p.lists[0].1;
            self.base_b = p.lists[1].0;
            self.count_b = p.lists[1].1;
            self.stride = [p.children[0].1, p.children[1].1];
            self.read_stage = 1;
            self.setup_left = super::list_pass::ADDRESS_SETUP_CLOCKS as u8;
            self.gear_count = 0;
            self.entries_in = 0;
            self.flushing = false;
            self.flushed = false;
            self.reached = 0;
            self.fill = [0; CHILDREN];
            self.half = [false; CHILDREN];
            self.pending = [[false; 2]; CHILDREN];
            self.count = [0; CHILDREN];
            for i in 0..CHILDREN {
                self.region[i] = p.children[i / 8].0;
            }
        }
        self.entries.edge(entry_in, load);
        self.masks.edge(mask_out, load);
        self.lane.pop_front();
        self.lane.push_back(lane_in);
        self.commands.edge(command, issue);
        self.bursts
            .edge(issued.map(|(_, beats, slot)| (beats, slot)), start_feed);
        self.w_data.edge(w_in, beat_out);
        self.w_last.edge(w_last_in, beat_out);
        memory.edge(&m);
    }
}

/// Runs one pass of the unit built for `config` against `memory`: the
/// clocks to `done`, at most `limit` (None past it).
pub fn run_pass(
    config: ListPassConfig,
    memory: &mut AxiMemory,
    request: &PassRequest,
    limit: u64,
) -> Option<PassRun> {
    run_pass_beside(config, memory, request, limit, || {})
}

/// [`run_pass`], calling `beside` once in every clock of the pass (what
/// shares the clock but not the port: the AXI top's narrow phase).
pub fn run_pass_beside(
    config: ListPassConfig,
    memory: &mut AxiMemory,
    request: &PassRequest,
    limit: u64,
    mut beside: impl FnMut(),
) -> Option<PassRun> {
    let mut machine = Machine::new(config);
    let stalled_before = memory.stalled;
    beside();
    machine.clock(memory, Some(request));
    let mut cycles = 1;
    while !machine.finished {
        if cycles >= limit {
            return None;
        }
        beside();
        machine.clock(memory, None);
        cycles += 1;
    }
    Some(PassRun {
        cycles,
        stalled: memory.stalled - stalled_before,
        error: machine.failed || machine.reader.failed,
        child_counts: machine.count,
    })
}

/// The pass's answer without clocks: each child's list, in the order the
/// entries are read (what the unit writes, checked against in the tests).
/// A's entries go to every child they meet, B's only to children that
/// hold an A entry.
pub fn child_lists(
    grid_bits: usize,
    cell: &Cell,
    lists: [&[Vec<u8>]; 2],
) -> [Vec<Vec<u8>>; CHILDREN] {
    let mut children: [Vec<Vec<u8>>; CHILDREN] = Default::default();
    for (k, list) in lists.iter().enumerate() {
        for entry in list.iter() {
            let (_, triangle) = unpack(entry, grid_bits);
            let mask =
                TriangleCellTest::widened(&triangle, BROAD_PHASE_MARGIN).children_of_cell(cell);
            for o in 0..8 {
                let reached = k == 0 || !children[o].is_empty();
                if mask >> o & 1 == 1 && reached {
                    children[8 * k + o].push(entry.clone());
                }
            }
        }
    }
    children
}
