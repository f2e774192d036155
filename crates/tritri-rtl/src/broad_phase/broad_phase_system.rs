//! The accelerator from triangles to pairs: the binning unit (the octree
//! broad phase), the leaf batcher, and the collision system (the narrow
//! phase) and an owner filter, in one top. The host streams each object's
//! triangles once, in grid coordinates, and reads back each intersecting
//! pair once, and each pair whose verdict has no certificate.
//!
//! ```text
//!  host triangles ─► binning unit ─► leaf stream ─► leaf batcher ─► collision system ─► owner filter ─► pairs
//!  (G-bit grid,      (octree, leaf   (header, A and  (frame offset,  (two banks, P        (each pair     (index_a,
//!   A's and B's)      lists)          B entries with   slots, end      pipelines, result    from its first index_b)
//!                                     vertices)        word per leaf)  FIFO; hits as slots) leaf)
//! ```
//!
//! Each reported pair (intersecting, or without a certificate: `out_hit`,
//! `out_certain`) comes out once, from the first leaf holding both
//! triangles: the owner filter ([`super::owner_chain_filter`]) sits on the
//! system's result stream, with tables the batcher's entries write as they
//! stream. A pair's indices are the triangles' positions in their object's
//! stream. The leaves reach the system as soon as the binning
//! unit streams them: the banks let the system test one leaf while the
//! next is written. The cycles to the system's last verdict are
//! [`broad_phase_cycles`]; the owner filter, deciding hits as they come,
//! finishes at most its clocks for the hits back to back later. A leaf larger than the system's memory depth
//! (the split rule makes one only where triangles overlap over an area)
//! comes from the binning unit as tiles, each a batch.

use super::binning_machine::BinningRun;
use super::binning_unit::BinningUnit;
use super::leaf_batcher::{LeafBatcher, LEAF_BATCHER_LATENCY};
use super::leaf_cost::COUNT_BITS;
use super::owner_chain_filter::OwnerChainFilter;
use crate::system::collision_system::CollisionSystem;
use crate::system::cycle_model::{streamed_system_cycles, BatchSizes};
use crate::system::{SystemConfig, COUNTER_BITS, ID_BITS};
use rust_hdl::prelude::*;

/// The grid and hardware widths the top is instantiated for: a `G`-bit
/// grid on `W`-bit hardware (24 on 24, and 24 on 16 with local frames).
pub const BROAD_PHASE_WIDTHS: [(usize, usize); 2] = [(24, 24), (24, 16)];

#[derive(LogicBlock)]
pub struct BroadPhaseSystem<
    const G: usize,
    const V: usize,
    const N: usize,
    const T: usize,
    const W: usize,
    const D: usize,
    const C: usize,
    const O: usize,
> {
    pub clock: Signal<In, Clock>,
    /// Synchronous, active high.
    pub reset: Signal<In, Bit>,
    /// One clock high while idle: a run begins; `root_*` and `max_leaf_*`
    /// are held from here to `done`.
    pub start: Signal<In, Bit>,
    pub root_x: Signal<In, Bits<G>>,
    pub root_y: Signal<In, Bits<G>>,
    pub root_z: Signal<In, Bits<G>>,
    pub root_level: Signal<In, Bits<6>>,
    pub max_leaf_level: Signal<In, Bits<6>>,
    pub max_leaf_enable: Signal<In, Bit>,
    // Triangles in (valid/ready), the binning unit's.
    pub in_valid: Signal<In, Bit>,
    pub in_ready: Signal<Out, Bit>,
    pub in_last: Signal<In, Bit>,
    pub in_object: Signal<In, Bit>,
    pub in_vertices: Signal<In, Bits<T>>,
    // Pairs out (valid/ready), the owner filter's.
    pub out_valid: Signal<Out, Bit>,
    pub out_ready: Signal<In, Bit>,
    pub out_index_a: Signal<Out, Bits<ID_BITS>>,
    pub out_index_b: Signal<Out, Bits<ID_BITS>>,
    /// The pair's verdict on the grid and its certificate: pairs without one
    /// come out whatever their verdict (docs/certificates.md).
    pub out_hit: Signal<Out, Bit>,
    pub out_certain: Signal<Out, Bit>,
    /// Binning is over: the leaves stream into the system.
    pub binned: Signal<Out, Bit>,
    /// Every leaf is tested and every hit decided; the last owned pair has
    /// been taken.
    pub done: Signal<Out, Bit>,
    /// A memory of the binning unit, the system's memory depth or the
    /// owner filter's record tables were too small for this run (sticky).
    pub overflow: Signal<Out, Bit>,
    pub pairs_tested: Signal<Out, Bits<COUNTER_BITS>>,
    /// Hits, each once per leaf holding both triangles (before the owner
    /// filter).
    pub hits: Signal<Out, Bits<COUNTER_BITS>>,
    binning: BinningUnit<G, V, N, T>,
    batcher: LeafBatcher<G, T, W>,
    system: CollisionSystem<W, D, C, O>,
    owner: OwnerChainFilter,
    /// The system's outputs this top does not use, folded into one bit
    /// whose name tells Verilator's lint they are unused on purpose.
    unused_outputs: Signal<Local, Bit>,
    _config: SystemConfig,
}

impl<
        const G: usize,
        const V: usize,
        const N: usize,
        const T: usize,
        const W: usize,
        const D: usize,
        const C: usize,
        const O: usize,
    > crate::unit::Unit for BroadPhaseSystem<G, V, N, T, W, D, C, O>
{
    fn sub_units(&self, units: &mut crate::unit::UnitWalk) {
        crate::sub_units!(self, units, binning, batcher, system, owner);
    }
}

impl<
        const G: usize,
        const V: usize,
        const N: usize,
        const T: usize,
        const W: usize,
        const D: usize,
        const C: usize,
        const O: usize,
    > BroadPhaseSystem<G, V, N, T, W, D, C, O>
{
    /// The top for a binning unit of `triangles` per object, `list_words`
    /// per list memory and `leaves` descriptors, feeding the system of
    /// `config` (whose width must be `W`), whose hits the owner filter
    /// decides with tables of `slots` entries per object ([`stream_slots`]);
    /// `local_frames` when `G > W`.
    pub fn new(
        triangles: usize,
        list_words: usize,
        leaves: usize,
        slots: usize,
        config: SystemConfig,
        local_frames: bool,
    ) -> Self {
        assert_eq!(
            config.coordinate_bits, W,
            "the system's width differs from the type's"
        );
        BroadPhaseSystem {
            clock: Default::default(),
            reset: Default::default(),
            start: Default::default(),
            root_x: Default::default(),
            root_y: Default::default(),
            root_z: Default::default(),
            root_level: Default::default(),
            max_leaf_level: Default::default(),
            max_leaf_enable: Default::default(),
            in_valid: Default::default(),
            in_ready: Default::default(),
            in_last: Default::default(),
            in_object: Default::default(),
            in_vertices: Default::default(),
            out_valid: Default::default(),
            out_ready: Default::default(),
            out_index_a: Default::default(),
            out_index_b: Default::default(),
            out_hit: Default::default(),
            out_certain: Default::default(),
            binned: Default::default(),
            done: Default::default(),
            overflow: Default::default(),
            pairs_tested: Default::default(),
            hits: Default::default(),
            binning: BinningUnit::new(triangles, list_words, leaves)
                .with_system(log2(config.triangles_per_bank), log2(config.pipelines)),
            batcher: LeafBatcher::new(local_frames),
            system: CollisionSystem::with_pipelines(config),
            owner: OwnerChainFilter::new(triangles, slots),
            unused_outputs: Default::default(),
            _config: config,
        }
    }

    pub fn system_config(&self) -> SystemConfig {
        self._config
    }
}

/// `n = 2^k`: `k` (the split rule is built for powers of two).
fn log2(n: usize) -> u32 {
    assert!(n.is_power_of_two(), "{n} is not a power of two");
    n.trailing_zeros()
}

// The counts of a leaf header are COUNT_BITS wide on both sides.
const _: () = assert!(COUNT_BITS == 20);

impl<
        const G: usize,
        const V: usize,
        const N: usize,
        const T: usize,
        const W: usize,
        const D: usize,
        const C: usize,
        const O: usize,
    > Logic for BroadPhaseSystem<G, V, N, T, W, D, C, O>
{
    #[hdl_gen]
    fn update(&mut self) {
        // Host → binning unit.
        clock!(self, clock, binning, batcher, system, owner);
        self.binning.reset.next = self.reset.val();
        self.binning.start.next = self.start.val();
        self.binning.root_x.next = self.root_x.val();
        self.binning.root_y.next = self.root_y.val();
        self.binning.root_z.next = self.root_z.val();
        self.binning.root_level.next = self.root_level.val();
        self.binning.max_leaf_level.next = self.max_leaf_level.val();
        self.binning.max_leaf_enable.next = self.max_leaf_enable.val();
        self.binning.in_valid.next = self.in_valid.val();
        self.in_ready.next = self.binning.in_ready.val();
        self.binning.in_last.next = self.in_last.val();
        self.binning.in_object.next = self.in_object.val();
        self.binning.in_vertices.next = self.in_vertices.val();

        // Leaf stream → batcher.
        self.batcher.reset.next = self.reset.val();
        self.batcher.in_valid.next = self.binning.out_valid.val();
        self.binning.out_ready.next = self.batcher.in_ready.val();
        self.batcher.in_header.next = self.binning.out_header.val();
        self.batcher.in_object.next = self.binning.out_object.val();
        self.batcher.in_index.next = self.binning.out_index.val();
        self.batcher.in_vertices.next = self.binning.out_vertices.val();
        self.batcher.in_x.next = self.binning.out_x.val();
        self.batcher.in_y.next = self.binning.out_y.val();
        self.batcher.in_z.next = self.binning.out_z.val();
        self.batcher.in_level.next = self.binning.out_level.val();
        self.batcher.in_count_a.next = self.binning.out_count_a.val();
        self.batcher.in_count_b.next = self.binning.out_count_b.val();
        self.batcher.in_leaf_number.next = self.binning.out_leaf_number.val();
        self.batcher.start.next = self.start.val();

        // Batches → system.
        self.system.reset.next = self.reset.val();
        self.system.in_valid.next = self.batcher.out_valid.val();
        self.batcher.out_ready.next = self.system.in_ready.val();
        self.system.in_end.next = self.batcher.out_end.val();
        self.system.in_object.next = self.batcher.out_object.val();
        self.system.in_id.next = self.batcher.out_id.val();
        self.system.in_x0.next = self.batcher.out_x0.val();
        self.system.in_y0.next = self.batcher.out_y0.val();
        self.system.in_z0.next = self.batcher.out_z0.val();
        self.system.in_x1.next = self.batcher.out_x1.val();
        self.system.in_y1.next = self.batcher.out_y1.val();
        self.system.in_z1.next = self.batcher.out_z1.val();
        self.system.in_x2.next = self.batcher.out_x2.val();
        self.system.in_y2.next = self.batcher.out_y2.val();
        self.system.in_z2.next = self.batcher.out_z2.val();

        // The owner filter: its tables written as triangles load and as
        // entries stream; the system's hits (slots) in, owned pairs out.
        self.owner.reset.next = self.reset.val();
        self.owner.start.next = self.start.val();
        self.owner.load_valid.next = self.in_valid.val() & self.binning.in_ready.val();
        self.owner.load_object.next = self.in_object.val();
        self.owner.entry_valid.next = self.batcher.entry_valid.val();
        self.owner.entry_object.next = self.batcher.entry_object.val();
        self.owner.entry_index.next = self.batcher.entry_index.val();
        self.owner.entry_slot.next = self.batcher.entry_slot.val();
        self.owner.entry_leaf.next = self.batcher.entry_leaf.val();
        self.owner.in_valid.next = self.system.out_valid.val();
        self.system.out_ready.next = self.owner.in_ready.val();
        self.owner.in_slot_a.next = self.system.out_id_a.val();
        self.owner.in_slot_b.next = self.system.out_id_b.val();
        self.owner.in_hit.next = self.system.out_hit.val();
        self.owner.in_certain.next = self.system.out_certain.val();
        self.out_valid.next = self.owner.out_valid.val();
        self.owner.out_ready.next = self.out_ready.val();
        self.out_index_a.next = self.owner.out_index_a.val();
        self.out_index_b.next = self.owner.out_index_b.val();
        self.out_hit.next = self.owner.out_hit.val();
        self.out_certain.next = self.owner.out_certain.val();
        self.pairs_tested.next = self.system.pairs_tested.val();
        self.hits.next = self.system.hits.val();

        self.binned.next = self.binning.binned.val();
        self.done.next = self.binning.done.val()
            & !self.batcher.busy.val()
            & self.system.done.val()
            & self.system.results_empty.val()
            & !self.system.out_valid.val()
            & self.owner.idle.val();
        self.overflow.next =
            self.binning.overflow.val() | self.system.overflow.val() | self.owner.overflow.val();
        self.unused_outputs.next = self.system.stall_cycles.val().any();
    }
}

/// The tiles the binning unit streams, in order, as `(leaf, A tile, B
/// tile)`: each leaf whole, or a leaf with more than `depth` triangles of
/// an object as every A tile of at most `depth` with every B tile (as the
/// host's `scene::tile` cuts it), each under a header of its own.
pub fn leaf_tiles(
    leaf_lists: &[(Vec<u32>, Vec<u32>)],
    depth: usize,
) -> impl Iterator<Item = (usize, &[u32], &[u32])> {
    leaf_lists
        .iter()
        .enumerate()
        .flat_map(move |(leaf, (a, b))| {
            a.chunks(depth)
                .flat_map(move |ta| b.chunks(depth).map(move |tb| (leaf, ta, tb)))
        })
}

/// The batches the system gets: [`leaf_tiles`]' sizes.
pub fn leaf_batches(depth: usize, run: &BinningRun) -> Vec<BatchSizes> {
    leaf_tiles(&run.leaf_lists, depth)
        .map(|(_, a, b)| BatchSizes {
            a: a.len(),
            b: b.len(),
        })
        .collect()
}

/// Entries each object streams into the system (A's repeated for every
/// B tile of a leaf, B's for every A tile): the owner filter's slots.
pub fn stream_slots(depth: usize, run: &BinningRun) -> [usize; 2] {
    slots_of_leaves(
        depth,
        run.leaves
            .iter()
            .map(|l| [l.a.count as usize, l.b.count as usize]),
    )
}

/// [`stream_slots`] of leaves given by their two counts (the DRAM top's
/// leaves too).
pub fn slots_of_leaves(depth: usize, counts: impl IntoIterator<Item = [usize; 2]>) -> [usize; 2] {
    counts.into_iter().fold([0, 0], |[a, b], [na, nb]| {
        [a + na * nb.div_ceil(depth), b + nb * na.div_ceil(depth)]
    })
}

/// Clocks from `binned` to the first leaf's header on the leaf stream: the
/// binning unit reads the leaf memory (OutLeaf, OutHeader).
pub const FIRST_HEADER_DELAY: u64 = 2;

/// The top's clocks from the first triangle in (clock 0) to the system's
/// last verdict (its `done`; the top's `done` also waits for the owner
/// filter, at most its clocks for the hits back to back), the reader
/// always ready: the binning unit's run (`run.cycles` to `binned`),
/// the first header [`FIRST_HEADER_DELAY`] later, its first entry one
/// clock after that and in the system one more ([`LEAF_BATCHER_LATENCY`]);
/// from there the system's bank recurrence
/// ([`streamed_system_cycles`]) with one idle clock between a leaf's end
/// word and the next leaf's first triangle (the header's clock).
pub fn broad_phase_cycles(config: SystemConfig, run: &BinningRun) -> u64 {
    let sizes = leaf_batches(config.triangles_per_bank, run);
    let first_header = run.cycles + FIRST_HEADER_DELAY;
    if sizes.is_empty() {
        return first_header;
    }
    let first_write = first_header + 1 + LEAF_BATCHER_LATENCY as u64;
    streamed_system_cycles(config, &sizes, first_write, 1)
}
