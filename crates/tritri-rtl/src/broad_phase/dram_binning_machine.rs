//! The clock-exact model of the broad phase's binning with every list in
//! external memory: a controller that walks the octree depth first and
//! runs one pass of the list pass unit ([`super::list_pass_machine`]) per
//! cell it classifies, all against one memory ([`crate::axi::memory_model`]).
//!
//! # How the controller bins
//!
//! * **The stack** (block RAM on chip) holds two kinds of entry: a cell
//!   still to visit (the cell, its two lists `(address, entries)`, the
//!   arena's top to restore, the lookahead's slack) and a split cell
//!   waiting for its children's costs (its leaf cost, its pass's cost, the
//!   sum of its children's so far). The root's lists are the ones the host
//!   wrote.
//! * **The split rule** is the planner's (`tritri_geom::scene::octree`)
//!   for a binner that streams its leaves ([`DramSplitRule`]). Popped, a
//!   cell's leaf cost is queried ([`super::leaf_cost`]); a cell that cannot
//!   be split, or whose leaf costs no more than its triangles' batch
//!   writes and an estimate of its pass ([`pass_estimate`]), is a leaf at
//!   once (the root is always passed). Otherwise its children's regions
//!   are allocated and the cell is passed; then the eight children's leaf
//!   costs, one query a clock. When they sum below the cell's own (or the
//!   level forces a split, local frames) the split *pays* and is kept;
//!   when it does not pay and the slack is 0, the cell is a leaf (its own
//!   lists, which the pass left in place); otherwise the split is *tried*:
//!   its children are visited with one level less of slack, and when the
//!   subtree cost at least the cell as a leaf, the subtree's leaves are
//!   dropped and the cell is a leaf. Each child holding both objects is
//!   pushed, octant 7 first, above its parent's entry.
//! * **Leaves** go out as they are decided, the cell and its two lists'
//!   places, except under a tried split: there they wait on chip until the
//!   outermost tried split is decided, then go out or are dropped (a leaf
//!   that finds the waiting memory full keeps every tried split on the
//!   stack instead: the waiting leaves go out, then it, and nothing is
//!   lost). A leaf goes out when what takes the leaves is ready
//!   ([`Beside::ready`]; it is held meanwhile). A leaf's lists must be
//!   read before the next pass writes (it may reuse the region): a pass
//!   starts only in a clock without [`Beside::hold`], and between passes
//!   the port's read channel may be the narrow phase's ([`Beside::drive`]).
//!   [`DramLeaf::entries`] are the lists as they are when the leaf goes
//!   out, read outside the port's clocks.
//! * **The arena.** Children's lists go above the arena's top, each child
//!   list as long as its parent's (a child holds at most every entry),
//!   rounded up to a write burst. A cell to visit remembers the top above
//!   its siblings' regions and restores it when popped, so a subtree's
//!   regions are free again when the next sibling is popped; under a tried
//!   split the top only rises, since waiting leaves' lists must survive. A
//!   cell whose children would not fit the arena is made a leaf instead
//!   and counted ([`DramBinningRun::arena_full`]): the flag is raised and
//!   no triangle is lost (the leaf is tiled by the narrow phase like any
//!   oversized leaf).
//!
//! # Clocks
//!
//! Between passes the controller asks nothing of the port (what is beside
//! it may read). Per cell popped: [`POP_CLOCKS`] to read its entry, then
//! [`DECIDE_CLOCKS`] for its leaf cost and the cannot-pay test; a leaf
//! takes [`LEAF_CLOCKS`] and every clock it is held; a pass waits while
//! it is held ([`Beside::hold`]), then takes its own clocks
//! ([`super::list_pass_machine::run_pass`]), then [`COSTS_CLOCKS`] for the
//! children's costs and the decision (then [`LEAF_CLOCKS`] if the cell is
//! a leaf after all). A split cell's entry,
//! popped after its children, takes [`POP_CLOCKS`] and [`CLOSE_CLOCKS`];
//! waiting leaves go out at [`LEAF_CLOCKS`] each.

use super::binning_machine::BinningParams;
use super::leaf_cost::{leaf_cost, LEAF_COST_LATENCY};
use super::list_entry::ENTRY_BYTES;
use super::list_pass_machine::{run_pass_beside, ListPassConfig, PassRequest};
use crate::axi::memory_model::{AxiMemory, ManagerSignals, MemoryOutputs};
use crate::system::SystemConfig;
use tritri_geom::octree::cell::Cell;
use tritri_geom::scene::octree::{BatchCost, LOOKAHEAD};

/// Clocks to read the top frame off the stack.
pub const POP_CLOCKS: u64 = 1;
/// Clocks of the popped cell's leaf cost and the cannot-pay test.
pub const DECIDE_CLOCKS: u64 = LEAF_COST_LATENCY as u64 + 1;
/// Clocks to send a leaf on.
pub const LEAF_CLOCKS: u64 = 1;
/// Clocks after a pass: the clock that sees it done, the eight children's
/// leaf costs, one query a clock (each child's list places written to the
/// children memory beside it), the last one's latency, and the decision.
/// Pushing the cell's frame takes no clock more (it is the decision's).
pub const COSTS_CLOCKS: u64 = 1 + 8 + LEAF_COST_LATENCY as u64 + 1;
/// Clocks to decide a split cell whose children are done.
pub const CLOSE_CLOCKS: u64 = 1;
/// The split rule's estimate of a pass's clocks besides its beats (the
/// reader's and the lane's latencies, the slots' flush, the last
/// responses): a pass of one entry each takes 137 clocks on a 64-bit port
/// against a memory of latency 24 (tests/list_pass.rs), 8 of them beats.
pub const PASS_FIXED_CLOCKS: u64 = 128;

/// The clocks the split rule charges a pass of `a + b` entries: one beat
/// each way per entry's beats, and the fixed cost.
pub fn pass_estimate(config: &ListPassConfig, a: u64, b: u64) -> u64 {
    PASS_FIXED_CLOCKS + (a + b) * config.beats_per_entry()
}

/// The split rule of the binning in external memory as the planner's cost
/// (`tritri_geom::scene::octree::BatchCost`): a leaf costs the system's
/// batches, a cell its pass's estimate, and leaves stream.
pub struct DramSplitRule {
    pub system: SystemConfig,
    pub pass: ListPassConfig,
}

impl BatchCost for DramSplitRule {
    fn batch_cycles(&self, a: usize, b: usize) -> u64 {
        self.system.batch_cycles(a, b)
    }

    fn classify_cycles(&self, a: usize, b: usize) -> u64 {
        pass_estimate(&self.pass, a as u64, b as u64)
    }

    fn streams_leaves(&self) -> bool {
        true
    }
}

/// How the binning is built and where its memory lies.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct DramBinningConfig {
    pub pass: ListPassConfig,
    pub rule: BinningParams,
    /// The arena for children's lists: `[start, end)` bytes of the memory,
    /// `start` on a write burst.
    pub arena: (u64, u64),
    /// Leaves that can wait under tried splits (the unit's waiting memory,
    /// at most [`super::dram_binning_unit::WAITING_CAPACITY`]).
    pub waiting_capacity: usize,
}

/// One list in the memory: `(address, entries)`.
pub type ListPlace = (u64, u64);

/// A leaf as it goes out: the cell, its lists' places, and the entries
/// read from them when it was sent.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct DramLeaf {
    pub cell: Cell,
    pub lists: [ListPlace; 2],
    /// The clock it went out on.
    pub clock: u64,
    /// Passes finished by then.
    pub after_passes: u64,
    pub entries: [Vec<[u8; ENTRY_BYTES]>; 2],
}

/// What a run took and gave.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct DramBinningRun {
    pub leaves: Vec<DramLeaf>,
    /// Clocks from the root's pop to the last leaf out, every clock.
    pub cycles: u64,
    /// Of them, the passes' own.
    pub pass_cycles: u64,
    /// Clocks the memory stalled.
    pub stalled: u64,
    /// Cells passed.
    pub passes: u64,
    /// Bytes the passes read and wrote.
    pub bytes_read: u64,
    pub bytes_written: u64,
    /// Of those written, the bytes in children no pass or leaf reads
    /// (one object absent).
    pub bytes_dropped: u64,
    /// The arena's highest top above its start.
    pub peak_arena: u64,
    /// Most frames on the stack at once.
    pub peak_frames: usize,
    /// Cells made leaves because their children would not fit the arena.
    pub arena_full: u64,
    /// Leaves decided under tried splits and dropped with them.
    pub leaves_dropped: u64,
    /// Most leaves waiting on chip at once.
    pub peak_waiting: usize,
    /// Times a leaf found the waiting memory full, and every tried split
    /// on the stack was kept instead (the leaves waiting went out).
    pub waiting_commits: u64,
    /// The largest pass (entries of both objects).
    pub largest_pass: u64,
}

/// What sits beside the controller and takes its leaves: in the AXI top,
/// the narrow phase, which reads each leaf's lists over the same port
/// between passes. Clocked in every clock of the walk.
pub trait Beside {
    /// `pass_hold` in this clock: no pass starts.
    fn hold(&self) -> bool;
    /// `leaf_ready` in this clock: a leaf offered is taken.
    fn ready(&self) -> bool;
    /// Its AR and R signals in a clock between passes (nothing when the
    /// port is not its own).
    fn drive(&self, m: &mut ManagerSignals);
    /// One clock: the memory's outputs `mem` (quiet during a pass) and the
    /// leaf the controller offers, taken if [`Beside::ready`].
    fn clock(&mut self, mem: &MemoryOutputs, leaf: Option<(Cell, [ListPlace; 2])>);
}

/// Nothing beside the controller: every leaf taken at once, no pass held.
pub struct TakesEveryLeaf;

impl Beside for TakesEveryLeaf {
    fn hold(&self) -> bool {
        false
    }
    fn ready(&self) -> bool {
        true
    }
    fn drive(&self, _m: &mut ManagerSignals) {}
    fn clock(&mut self, _mem: &MemoryOutputs, _leaf: Option<(Cell, [ListPlace; 2])>) {}
}

/// A cell still to visit.
struct Visit {
    cell: Cell,
    lists: [ListPlace; 2],
    /// The arena's top above its siblings' regions.
    top: u64,
    /// Levels of lookahead left.
    slack: u32,
}

/// A split cell waiting for its children's costs.
struct Split {
    visit: Visit,
    /// Its cost as a leaf, and its pass's (the rule's estimate).
    leaf_cost: u64,
    classify: u64,
    /// Its children's costs so far.
    subtree: u64,
    /// Tried, not paid: its subtree may still be dropped.
    tried: bool,
    /// The waiting leaves before its children's.
    waiting_mark: usize,
}

enum Entry {
    Visit(Visit),
    Split(Split),
}

/// The walk's state besides the stack.
struct Walk<'m> {
    config: DramBinningConfig,
    memory: &'m mut AxiMemory,
    beside: &'m mut dyn Beside,
    run: DramBinningRun,
    /// The arena's top.
    top: u64,
    /// Leaves decided under a tried split.
    waiting: Vec<(Cell, [ListPlace; 2])>,
    /// Tried splits on the stack, not committed.
    tried: usize,
    /// Split cells on the stack, and how many of the lowest were kept
    /// when the waiting memory filled (their tried flag no longer counts).
    splits: usize,
    committed: usize,
}

impl Walk<'_> {
    /// The controller's clocks between passes: the memory sees an idle port.
    fn idle(&mut self, clocks: u64) {
        for _ in 0..clocks {
            self.clock_beside(None);
        }
    }

    /// One clock between passes, with `leaf` offered: the port's read
    /// channel is what is beside the controller's.
    fn clock_beside(&mut self, leaf: Option<(Cell, [ListPlace; 2])>) {
        let stalled = self.memory.stalled;
        let mem = self.memory.outputs();
        let mut m = ManagerSignals::default();
        self.beside.drive(&mut m);
        self.beside.clock(&mem, leaf);
        self.memory.edge(&m);
        self.run.stalled += self.memory.stalled - stalled;
        self.run.cycles += 1;
    }

    /// A leaf decided: out at once, or waiting under a tried split. A leaf
    /// that finds the waiting memory full keeps every tried split on the
    /// stack as split: the waiting leaves go out, then this one, and
    /// nothing is lost (the splits cost what their subtrees cost).
    fn leaf(&mut self, cell: Cell, lists: [ListPlace; 2]) {
        if self.tried == 0 {
            self.send(cell, lists);
        } else if self.waiting.len() < self.config.waiting_capacity {
            self.waiting.push((cell, lists));
            self.run.peak_waiting = self.run.peak_waiting.max(self.waiting.len());
        } else {
            self.run.waiting_commits += 1;
            self.tried = 0;
            self.committed = self.splits;
            for (cell, lists) in std::mem::take(&mut self.waiting) {
                self.send(cell, lists);
            }
            self.send(cell, lists);
        }
    }

    fn send(&mut self, cell: Cell, lists: [ListPlace; 2]) {
        // Offered until taken; the clock it is taken in is its own.
        const _: () = assert!(LEAF_CLOCKS == 1);
        loop {
            let taken = self.beside.ready();
            self.clock_beside(Some((cell, lists)));
            if taken {
                break;
            }
        }
        let entries = lists.map(|place| read_list(self.memory, place));
        self.run.leaves.push(DramLeaf {
            cell,
            lists,
            clock: self.run.cycles,
            after_passes: self.run.passes,
            entries,
        });
    }

    fn cost(&self, a: u64, b: u64) -> u64 {
        leaf_cost(
            a,
            b,
            self.config.rule.log_depth,
            self.config.rule.log_pipelines,
        )
    }

    /// Visits a cell: a leaf (its cost returned), or a pass and its
    /// children pushed (`None`: the cost comes when its split closes).
    fn visit(
        &mut self,
        visit: Visit,
        root: Cell,
        stack: &mut Vec<Entry>,
    ) -> Result<Option<u64>, String> {
        let [a, b] = visit.lists.map(|(_, n)| n);
        let cell = visit.cell;
        let rule = self.config.rule;
        let pass = self.config.pass;
        self.top = if self.tried > 0 {
            self.top.max(visit.top)
        } else {
            visit.top
        };
        self.idle(POP_CLOCKS + DECIDE_CLOCKS);
        let forced = rule.max_leaf_level.is_some_and(|m| cell.level > m);
        let leaf_cost = self.cost(a, b);
        let is_root = cell == root;
        let classify = if is_root {
            pass_estimate(&pass, 0, 0)
        } else {
            pass_estimate(&pass, a, b)
        };
        let cannot_pay = !is_root && !forced && leaf_cost <= a + b + 1 + classify;
        // Each child list is as long as the parent's, on a write burst.
        let burst = pass.burst_bytes();
        let stride = |n: u64| (n * ENTRY_BYTES as u64).div_ceil(burst).max(1) * burst;
        let children_at = [self.top, self.top + 8 * stride(a)];
        let top = children_at[1] + 8 * stride(b);
        let fits = top <= self.config.arena.1;
        if !cell.splittable() || cannot_pay || !fits {
            self.run.arena_full += u64::from(cell.splittable() && !cannot_pay && !fits);
            self.leaf(cell, visit.lists);
            return Ok(Some(leaf_cost));
        }
        self.run.peak_arena = self.run.peak_arena.max(top - self.config.arena.0);
        // The shorter list goes first: the unit writes the second only to
        // children the first reached (`list_pass`).
        let swapped = b < a;
        let order = if swapped { [1, 0] } else { [0, 1] };
        let request = PassRequest {
            cell,
            lists: order.map(|k| visit.lists[k]),
            children: order.map(|k| (children_at[k], stride(visit.lists[k].1))),
        };
        let entries = a + b;
        while self.beside.hold() {
            self.idle(1);
        }
        let limit = 64 * (entries + 64) * pass.beats_per_entry();
        let beside = &mut *self.beside;
        let quiet = MemoryOutputs::default();
        let out = run_pass_beside(pass, self.memory, &request, limit, || {
            beside.clock(&quiet, None)
        })
        .ok_or_else(|| format!("the pass of cell {cell:?} did not finish in {limit} clocks"))?;
        if out.error {
            return Err(format!("the pass of cell {cell:?} raised its error"));
        }
        let mut counts = out.child_counts;
        if swapped {
            counts.rotate_left(8);
        }
        let run = &mut self.run;
        run.passes += 1;
        run.cycles += out.cycles;
        run.pass_cycles += out.cycles;
        run.stalled += out.stalled;
        run.largest_pass = run.largest_pass.max(entries);
        run.bytes_read += entries * ENTRY_BYTES as u64;
        run.bytes_written += counts.iter().sum::<u64>() * ENTRY_BYTES as u64;
        let children: [[ListPlace; 2]; 8] = std::array::from_fn(|o| {
            [0, 1].map(|k| {
                let (at, n) = (children_at[k], visit.lists[k].1);
                (at + o as u64 * stride(n), counts[8 * k + o])
            })
        });
        self.idle(COSTS_CLOCKS);
        let children_cost: u64 = children.iter().map(|[a, b]| self.cost(a.1, b.1)).sum();
        let pays = forced || children_cost < leaf_cost;
        if !pays && visit.slack == 0 {
            self.leaf(cell, visit.lists);
            return Ok(Some(leaf_cost + classify));
        }
        let slack = if pays { LOOKAHEAD } else { visit.slack - 1 };
        let tried = !pays;
        self.tried += usize::from(tried);
        self.splits += 1;
        let waiting_mark = self.waiting.len();
        stack.push(Entry::Split(Split {
            visit,
            leaf_cost,
            classify,
            subtree: 0,
            tried,
            waiting_mark,
        }));
        for (o, lists) in children.iter().enumerate().rev() {
            if lists[0].1 == 0 || lists[1].1 == 0 {
                self.run.bytes_dropped += (lists[0].1 + lists[1].1) * ENTRY_BYTES as u64;
                continue;
            }
            stack.push(Entry::Visit(Visit {
                cell: cell.child(o),
                lists: *lists,
                top,
                slack,
            }));
        }
        self.run.peak_frames = self.run.peak_frames.max(stack.len());
        Ok(None)
    }

    /// A split cell whose children are done: its cost. A tried split that
    /// cost at least the cell as a leaf drops its subtree's waiting leaves
    /// for the cell; when the outermost tried split is decided, the waiting
    /// leaves go out.
    fn close(&mut self, split: Split) -> u64 {
        self.idle(POP_CLOCKS + CLOSE_CLOCKS);
        let forced = self
            .config
            .rule
            .max_leaf_level
            .is_some_and(|m| split.visit.cell.level > m);
        let mut cost = split.subtree;
        // A split below the last commit was kept: it is tried no more.
        self.splits -= 1;
        let tried = split.tried && self.splits >= self.committed;
        self.committed = self.committed.min(self.splits);
        if tried {
            self.tried -= 1;
            if !forced && split.subtree >= split.leaf_cost {
                self.run.leaves_dropped += (self.waiting.len() - split.waiting_mark) as u64;
                self.waiting.truncate(split.waiting_mark);
                self.leaf(split.visit.cell, split.visit.lists);
                cost = split.leaf_cost;
            }
            if self.tried == 0 {
                for (cell, lists) in std::mem::take(&mut self.waiting) {
                    self.send(cell, lists);
                }
            }
        }
        cost + split.classify
    }
}

/// The entries of a list in the memory.
pub fn read_list(memory: &AxiMemory, (at, count): ListPlace) -> Vec<[u8; ENTRY_BYTES]> {
    (0..count as usize)
        .map(|i| {
            let from = at as usize + i * ENTRY_BYTES;
            memory.bytes[from..from + ENTRY_BYTES]
                .try_into()
                .expect("entry-sized slice")
        })
        .collect()
}

/// Bins from `root` with the lists `root_lists` already in `memory`; an
/// error names a pass that failed, or the arena that does not fit the
/// memory.
pub fn run_dram_binning(
    config: DramBinningConfig,
    memory: &mut AxiMemory,
    root: Cell,
    root_lists: [ListPlace; 2],
) -> Result<DramBinningRun, String> {
    run_dram_binning_beside(config, memory, root, root_lists, &mut TakesEveryLeaf)
}

/// [`run_dram_binning`] with `beside` taking the leaves, holding passes
/// and sharing the port between them.
pub fn run_dram_binning_beside(
    config: DramBinningConfig,
    memory: &mut AxiMemory,
    root: Cell,
    root_lists: [ListPlace; 2],
    beside: &mut dyn Beside,
) -> Result<DramBinningRun, String> {
    config.pass.check()?;
    let capacity = super::dram_binning_unit::WAITING_CAPACITY;
    if !(1..=capacity).contains(&config.waiting_capacity) {
        return Err(format!(
            "a waiting memory of 1 to {capacity} leaves, not {}",
            config.waiting_capacity
        ));
    }
    let (arena_start, arena_end) = config.arena;
    let burst = config.pass.burst_bytes();
    if arena_start % burst != 0 || arena_end > memory.bytes.len() as u64 {
        return Err(format!(
            "the arena {arena_start:#x}..{arena_end:#x} is not on a {burst}-byte burst or not in the {}-byte memory",
            memory.bytes.len()
        ));
    }
    let mut walk = Walk {
        config,
        memory,
        beside,
        run: DramBinningRun::default(),
        top: arena_start,
        waiting: Vec::new(),
        tried: 0,
        splits: 0,
        committed: 0,
    };
    let mut stack = Vec::new();
    // Only the root can lack an object: no child without both is pushed.
    // A root without both takes the clock that finds it so.
    if root_lists.iter().any(|&(_, n)| n == 0) {
        walk.idle(POP_CLOCKS);
    } else {
        stack.push(Entry::Visit(Visit {
            cell: root,
            lists: root_lists,
            top: arena_start,
            slack: LOOKAHEAD,
        }));
    }
    while let Some(entry) = stack.pop() {
        let cost = match entry {
            Entry::Visit(visit) => walk.visit(visit, root, &mut stack)?,
            Entry::Split(split) => Some(walk.close(split)),
        };
        // A finished cell's cost goes to its parent's split.
        if let (Some(cost), Some(Entry::Split(parent))) = (
            cost,
            stack
                .iter_mut()
                .rev()
                .find(|e| matches!(e, Entry::Split(_))),
        ) {
            parent.subtree += cost;
        }
    }
    if !walk.memory.faults().is_empty() {
        return Err(format!(
            "{} protocol faults, the first: {}",
            walk.memory.faults().len(),
            walk.memory.faults()[0]
        ));
    }
    Ok(walk.run)
}
