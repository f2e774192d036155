//! The bounding-volume-aware collision system (thesis, chapter 4): the host
//! streams, per common bounding volume, the triangles of object A and of
//! object B that touch it; the hardware tests every pair of the two arrays
//! and returns the intersecting pairs by their original triangle ids.
//!
//! ```text
//!  host triangles ──► write FSM ──► triangle memory A (bank 0 | bank 1)
//!  (valid/ready,       │  end        triangle memory B (bank 0 | bank 1)
//!   object, id, xyz,   │  addresses        │ read address, read enable
//!   end-of-batch)      ▼                   ▼
//!                   address generator (read FSM) ── bset / lane valid ──►
//!                   P pipelines: base polygon per pipeline, B broadcast
//!                         │ out_valid, out_hit, ids (aligned)
//!                         ▼
//!                   hit mask (P bits) + ids ──► result FIFO ──► pair
//!                   serializer ──► (id_a, id_b), valid/ready
//! ```
//!
//! * [`triangle_memory`]: per object, one simple dual-port memory of
//!   `2 · depth` triangles; bank `k` is the address range
//!   `[k · depth, (k + 1) · depth)`. The host writes one bank while the
//!   pipelines read the other (the banks alternate batch by batch).
//! * [`address_generator`]: the write state machine (fills the write bank,
//!   records each array's end address at the end-of-batch word, hands the
//!   bank over) and the read state machine (idle → load up to `P` bases, one
//!   per cycle, each with `bset` to its own pipeline → stream all of B to
//!   every pipeline → next group of bases … → release the bank).
//! * [`result_fifo`] and [`pair_serializer`]: one FIFO word per cycle in
//!   which some pipeline reported a hit (`P`-bit hit mask, the `P` base ids,
//!   the streamed id), serialized to one `(id_a, id_b)` per transfer. While
//!   the FIFO holds more than `depth - L` words, `advance` is low: the read
//!   side holds and sends nothing, the pipelines run on, and the pairs in
//!   flight fill the `L` words kept in reserve, so nothing is dropped.
//! * [`collision_system`]: the top, generated for a pipeline type by
//!   [`collision_system!`](crate::collision_system): `CollisionSystem` with
//!   the real [`TrianglePipeline`](crate::pipeline::triangle_pipeline::TrianglePipeline),
//!   `StubCollisionSystem` with [`stub_pipeline`], a stand-in with the
//!   pipeline's ports; [`system_for_width`] picks one at run time;
//!   [`host_ports`] drives any of them; [`cycle_model`]: the exact cycle
//!   count of the state machines.
//!
//! Every size that the generator chooses lives in [`SystemConfig`]: the
//! coordinate width `W`, the number of pipelines `P`, the memory depth
//! (triangles per array per bank), the result FIFO depth and the pipeline
//! latency `L`.

pub mod address_generator;
pub mod collision_system;
pub mod cycle_model;
pub mod dual_port_ram;
pub mod host_ports;
pub mod pair_serializer;
pub mod rare_case_model;
pub mod result_fifo;
pub mod stub_pipeline;
pub mod system_for_width;
pub mod system_unit;
pub mod triangle_memory;

/// Width of every memory address and array pointer (bank bit included).
pub const ADDRESS_BITS: usize = 16;
/// The most triangles a bank holds per object: an array's end pointer,
/// `ADDRESS_BITS - 1` bits within its bank, must hold the count itself.
pub const MAX_TRIANGLES_PER_BANK: usize = (1 << (ADDRESS_BITS - 1)) - 1;
/// Clocks from a memory read address to its triangle on the pipelines'
/// bus: the block RAM's registered read, then an output register in fabric
/// ([`triangle_memory`]).
pub const MEMORY_READ_LATENCY: usize = 2;
/// Clocks from a verdict on the pipelines' outputs to the counters
/// (`pairs_tested`, `hits`): they add increments registered a clock
/// before ([`collision_system`]).
pub const COUNT_LATENCY: usize = 1;
/// Width of the result FIFO's pointers and fill count.
pub const FIFO_POINTER_BITS: usize = 16;
/// Width of the triangle ids carried through memories and pipelines (the
/// pipeline's, defined in one place).
pub const ID_BITS: usize = crate::pipeline::ID_BITS;
/// Width of the hit mask and of the pipeline index: at most 16 pipelines.
pub const MAX_PIPELINES: usize = 16;
/// Width of a pipeline index.
pub const LANE_BITS: usize = 5;
/// Width of the performance counters (they wrap).
pub const COUNTER_BITS: usize = 32;
/// The default memory depth: triangles per array per bank.
pub const DEFAULT_TRIANGLES_PER_BANK: usize = 256;
/// The default result FIFO depth (words; a word holds up to `P` pairs):
/// more than the pipeline's latency, which the FIFO keeps in reserve
/// ([`result_fifo`]), and the same block RAMs as 32 words.
pub const DEFAULT_RESULT_FIFO_DEPTH: usize = 64;

/// The generator parameters of the system, in one place.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct SystemConfig {
    /// Coordinate width `W` (signed bits).
    pub coordinate_bits: usize,
    /// Number of pipelines `P` working in parallel (1..=16).
    pub pipelines: usize,
    /// Memory depth: triangles per array (object) per bank.
    pub triangles_per_bank: usize,
    /// Result FIFO depth in words (>= 2).
    pub result_fifo_depth: usize,
    /// Pipeline latency `L`: an input in cycle `c` gives its verdict in
    /// cycle `c + L`.
    pub pipeline_latency: usize,
}

impl SystemConfig {
    /// The system of `pipelines` Devillers–Guigue pipelines on `W`-bit
    /// coordinates; its pipeline latency is theirs
    /// ([`crate::pipeline::triangle_pipeline::latency`]), the memories and
    /// the result FIFO of the default depths.
    pub fn new(coordinate_bits: usize, pipelines: usize) -> Self {
        SystemConfig {
            coordinate_bits,
            pipelines,
            triangles_per_bank: DEFAULT_TRIANGLES_PER_BANK,
            result_fifo_depth: DEFAULT_RESULT_FIFO_DEPTH,
            pipeline_latency: crate::pipeline::triangle_pipeline::latency(),
        }
    }
    /// Another pipeline latency: for systems of stub pipelines
    /// ([`stub_pipeline`]) and for the cycle model's tests; a system of
    /// Devillers–Guigue pipelines refuses any latency but theirs.
    pub fn with_pipeline_latency(mut self, latency: usize) -> Self {
        self.pipeline_latency = latency;
        self
    }
    pub fn with_depth(mut self, triangles_per_bank: usize) -> Self {
        self.triangles_per_bank = triangles_per_bank;
        self
    }
    pub fn with_result_fifo_depth(mut self, words: usize) -> Self {
        self.result_fifo_depth = words;
        self
    }
    /// A result FIFO with `words` words below its mark, above the reserve
    /// of `L` words ([`Self::smallest_result_fifo_depth`]): how full it may
    /// get before the read side holds.
    pub fn with_result_fifo_room(self, words: usize) -> Self {
        let depth = self.result_fifo_reserve() + words;
        self.with_result_fifo_depth(depth)
    }

    /// Panics with the reason when a parameter is out of the generator's range.
    pub fn validate(&self) {
        assert!(
            (1..=MAX_PIPELINES).contains(&self.pipelines),
            "pipelines must be in 1..={MAX_PIPELINES}, got {}",
            self.pipelines
        );
        assert!(
            (1..=MAX_TRIANGLES_PER_BANK).contains(&self.triangles_per_bank),
            "triangles per bank must be in 1..={}, got {}",
            MAX_TRIANGLES_PER_BANK,
            self.triangles_per_bank
        );
        assert!(
            self.pipeline_latency >= 1 && self.pipeline_latency < 200,
            "pipeline latency out of range"
        );
        assert!(
            (self.smallest_result_fifo_depth()..1 << (FIFO_POINTER_BITS - 1))
                .contains(&self.result_fifo_depth),
            "result FIFO depth must be in {}..{} (more than the pipeline latency {}), got {}",
            self.smallest_result_fifo_depth(),
            1 << (FIFO_POINTER_BITS - 1),
            self.pipeline_latency,
            self.result_fifo_depth
        );
    }

    /// The words the result FIFO keeps above its mark: the pipelines never
    /// stop, so when the read side stops, the `L` pairs in flight still
    /// arrive ([`result_fifo`]), and one more: the read side's enable is a
    /// register, so it sees `room` fall a clock late ([`collision_system`]).
    pub fn result_fifo_reserve(&self) -> usize {
        self.pipeline_latency + 1
    }

    /// The smallest result FIFO: the reserve, plus one word to write at all.
    pub fn smallest_result_fifo_depth(&self) -> usize {
        self.result_fifo_reserve() + 1
    }

    /// Clocks from a streamed triangle's read address until its verdict is
    /// counted: the memories' read latency, `L`, and the counters'; `done`
    /// rises the clock after (the address generator's `flight_cycles`).
    pub fn read_to_counted_cycles(&self) -> usize {
        MEMORY_READ_LATENCY + self.pipeline_latency + COUNT_LATENCY
    }

    /// The unit name of the emitted top: `tritri_system_w24_p2_d256`.
    pub fn unit_name(&self) -> String {
        format!(
            "tritri_system_w{}_p{}_d{}",
            self.coordinate_bits, self.pipelines, self.triangles_per_bank
        )
    }

    /// One line per parameter, as the generator reports them.
    pub fn report(&self) -> String {
        format!(
            "coordinate width W = {} bits\npipelines P = {}\nmemory depth = {} triangles per array per bank \
             (2 banks x 2 objects)\nresult FIFO depth = {} words ({} pairs per word at most)\n\
             pipeline latency L = {} cycles\n",
            self.coordinate_bits,
            self.pipelines,
            self.triangles_per_bank,
            self.result_fifo_depth,
            self.pipelines,
            self.pipeline_latency
        )
    }
}
