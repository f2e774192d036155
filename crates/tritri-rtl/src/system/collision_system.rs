//! The system top (thesis, chapter 4, figure 4.5): host stream → write
//! state machine → two-bank triangle memories → read state machine → `P`
//! pipelines → result FIFO → pair serializer → host result stream.
//!
//! # Ports
//!
//! | port | dir | meaning |
//! |---|---|---|
//! | `clock`, `reset` | in | clock; synchronous active-high reset |
//! | `in_valid`, `in_ready` | in, out | host triangle stream handshake |
//! | `in_end` | in | the transfer is the end-of-batch (commit) word, no triangle |
//! | `in_object` | in | 0: the triangle belongs to object A (bases), 1: to B (streamed) |
//! | `in_id` | in | the triangle's original id (32 bits) |
//! | `in_x0 … in_z2` | in | its vertices, signed `W`-bit |
//! | `out_valid`, `out_ready` | out, in | result stream handshake |
//! | `out_id_a`, `out_id_b` | out | one reported pair per transfer: a hit, or a verdict without a certificate |
//! | `out_hit`, `out_certain` | out | its verdict on the grid, and whether that is provably the verdict before quantization |
//! | `done` | out | every committed batch is tested and its hits are in the FIFO |
//! | `results_empty` | out | no pair waits: the result FIFO and the serializer hold nothing |
//! | `overflow` | out | sticky: an array of a batch exceeded the memory depth |
//! | `pairs_tested`, `hits`, `stall_cycles` | out | 32-bit counters |
//!
//! The host writes a batch as its triangles of A and B in any order,
//! followed by one end-of-batch word; it may write the next batch at once
//! (into the other bank, `in_ready` tells when that bank is free) and reads
//! the pairs as they come. `busy` is `!done`.
//!
//! Every pair whose verdict has no certificate (`out_certain = 0`, see
//! docs/certificates.md) is reported too, intersecting or not, so that the
//! host can decide it again on its own coordinates; with `out_certain = 1`
//! only hits are reported.
//!
//! The top is generated for a pipeline type by [`collision_system!`](crate::collision_system)
//! (rust-hdl cannot reach fields of a generic type): [`CollisionSystem`]
//! uses the real [`TrianglePipeline`], [`StubCollisionSystem`] the
//! [`StubPipeline`].

use super::stub_pipeline::StubPipeline;
use crate::pipeline::shared_rare_pipeline::SharedRarePipeline;
use crate::pipeline::triangle_pipeline::{latency, TrianglePipeline};
use rust_hdl::prelude::*;

/// Defines a system top `$name` whose pipelines are `$pipeline`, a type with
/// the triangle pipeline's ports (`clock reset advance in_valid in_bset
/// in_id in_x0 … in_z2 out_valid out_hit out_certain out_base_id
/// out_stream_id`) and
/// `W`-bit coordinates. The caller must have `rust_hdl::prelude::*` in scope.
/// Pipelines that hold for a shared unit name their three ports for it
/// (`hold: hold, hold_request: hold_request, hold_others: hold_others`):
/// the output that says they hold, their requests three clocks ahead
/// (four bits, registers), and the input that makes them hold with the
/// others (the requests' OR, [`HoldNext`](crate::pipeline::hold_next::HoldNext)).
///
/// ```text
/// collision_system!(pub struct StubCollisionSystem<const W: usize> { coordinate_bits: W, pipeline: StubPipeline<W> });
/// ```
#[macro_export]
macro_rules! collision_system {
    ($(#[$meta:meta])* $vis:vis struct $name:ident < $(const $param:ident : usize),* > {
        coordinate_bits: $w:expr, pipeline: $pipeline:ty
        $(, hold: $hold:ident, hold_request: $hold_request:ident, hold_others: $hold_others:ident)? $(,)?
    }) => {
        $(#[$meta])*
        #[derive(LogicBlock)]
        $vis struct $name<$(const $param: usize),*> {
            pub clock: Signal<In, Clock>,
            pub reset: Signal<In, Bit>,
            pub in_valid: Signal<In, Bit>,
            pub in_ready: Signal<Out, Bit>,
            pub in_end: Signal<In, Bit>,
            pub in_object: Signal<In, Bit>,
            pub in_id: Signal<In, Bits<{ $crate::system::ID_BITS }>>,
            pub in_x0: Signal<In, Bits<$w>>,
            pub in_y0: Signal<In, Bits<$w>>,
            pub in_z0: Signal<In, Bits<$w>>,
            pub in_x1: Signal<In, Bits<$w>>,
            pub in_y1: Signal<In, Bits<$w>>,
            pub in_z1: Signal<In, Bits<$w>>,
            pub in_x2: Signal<In, Bits<$w>>,
            pub in_y2: Signal<In, Bits<$w>>,
            pub in_z2: Signal<In, Bits<$w>>,
            pub out_valid: Signal<Out, Bit>,
            pub out_ready: Signal<In, Bit>,
            pub out_id_a: Signal<Out, Bits<{ $crate::system::ID_BITS }>>,
            pub out_id_b: Signal<Out, Bits<{ $crate::system::ID_BITS }>>,
            pub out_hit: Signal<Out, Bit>,
            pub out_certain: Signal<Out, Bit>,
            pub done: Signal<Out, Bit>,
            pub results_empty: Signal<Out, Bit>,
            pub overflow: Signal<Out, Bit>,
            pub pairs_tested: Signal<Out, Bits<{ $crate::system::COUNTER_BITS }>>,
            pub hits: Signal<Out, Bits<{ $crate::system::COUNTER_BITS }>>,
            pub stall_cycles: Signal<Out, Bits<{ $crate::system::COUNTER_BITS }>>,
            address_generator: $crate::system::address_generator::AddressGenerator,
            memory_a: $crate::system::triangle_memory::TriangleMemory<$w>,
            memory_b: $crate::system::triangle_memory::TriangleMemory<$w>,
            pipelines: Vec<$pipeline>,
            result_fifo: $crate::system::result_fifo::ResultFifo,
            pair_serializer: $crate::system::pair_serializer::PairSerializer,
            pairs_tested_q: rust_hdl::widgets::prelude::DFF<Bits<{ $crate::system::COUNTER_BITS }>>,
            hits_q: rust_hdl::widgets::prelude::DFF<Bits<{ $crate::system::COUNTER_BITS }>>,
            /// The verdicts of the last clock the pipelines moved, and how
            /// many were hits: the counters add them a clock late
            /// ([`COUNT_LATENCY`](crate::system::COUNT_LATENCY)), so that
            /// the pipelines' output registers reach a register, not a
            /// 32-bit carry chain (W = 16, P = 1, seed 2: the decision's
            /// `hit_q`, 2.7 ns of routing, then 33 levels into `hits`, 7.16
            /// ns). `done` rises a clock later for it, so the counts are
            /// complete when it is seen.
            tested_increment: rust_hdl::widgets::prelude::DFF<Bits<{ $crate::system::LANE_BITS }>>,
            hit_increment: rust_hdl::widgets::prelude::DFF<Bits<{ $crate::system::LANE_BITS }>>,
            stall_cycles_q: rust_hdl::widgets::prelude::DFF<Bits<{ $crate::system::COUNTER_BITS }>>,
            /// The last clock was a stall: counted a clock late, so that
            /// `advance` and `done` reach a flip-flop, not a 32-bit carry
            /// chain (7.1 ns post-route). A stall is never the clock before
            /// `done` rises (nothing that ends a batch moves while the read
            /// side holds), so the count is complete when `done` is seen.
            stalled: rust_hdl::widgets::prelude::DFF<Bit>,
            /// The read side's clock enable, a register in copies:
            /// `advance_q` for the address generator, the pipelines' inputs
            /// and the stall count, `read_enable_a` and `read_enable_b` for
            /// the memories of A and B. High
            /// when the FIFO had room a clock ago and no pipeline holds
            /// (`hold_next` a clock ahead). Combinational from `room` and a
            /// `hold` copy, placed apart, into the address generator's next
            /// state, it crossed the chip (3.7 and 3.9 ns of routing, 125.7
            /// and 102.8 MHz post-route, W = 16, P = 1). Seeing `room` a
            /// clock late costs the FIFO one more word of reserve
            /// ([`SystemConfig::result_fifo_reserve`](crate::system::SystemConfig::result_fifo_reserve)).
            /// Register copies ([`RegisterCopy`](crate::arith::register_copy::RegisterCopy)),
            /// so that synthesis keeps them apart.
            advance_q: $crate::arith::register_copy::RegisterCopy<Bit>,
            read_enable_a: $crate::arith::register_copy::RegisterCopy<Bit>,
            read_enable_b: $crate::arith::register_copy::RegisterCopy<Bit>,
            /// What the copies take: the FIFO has room and no pipeline
            /// holds next clock.
            advance_next: Signal<Local, Bit>,
            /// `advance_q`'s register.
            advance: Signal<Local, Bit>,
            /// The pipelines move this clock: no pipeline holds (constant 1
            /// without shared rare-case units). Their `advance` is tied
            /// high (the FIFO does not stop them, and shared-unit pipelines
            /// hold together by themselves); this enables what leaves them
            /// for the FIFO and the counters.
            pipelines_move: Signal<Local, Bit>,
            bus_id: Signal<Local, Bits<{ $crate::system::ID_BITS }>>,
            bus_coordinates: [Signal<Local, Bits<$w>>; 9],
            /// Per lane: a verdict to report (a hit or uncertain), a hit, certain.
            report_mask_chain: Vec<Signal<Local, Bits<{ $crate::system::MAX_PIPELINES }>>>,
            hit_mask_chain: Vec<Signal<Local, Bits<{ $crate::system::MAX_PIPELINES }>>>,
            certain_mask_chain: Vec<Signal<Local, Bits<{ $crate::system::MAX_PIPELINES }>>>,
            tested_chain: Vec<Signal<Local, Bits<{ $crate::system::LANE_BITS }>>>,
            hit_count_chain: Vec<Signal<Local, Bits<{ $crate::system::LANE_BITS }>>>,
            report_mask: Signal<Local, Bits<{ $crate::system::MAX_PIPELINES }>>,
            hit_mask: Signal<Local, Bits<{ $crate::system::MAX_PIPELINES }>>,
            certain_mask: Signal<Local, Bits<{ $crate::system::MAX_PIPELINES }>>,
            tested_count: Signal<Local, Bits<{ $crate::system::LANE_BITS }>>,
            hit_count: Signal<Local, Bits<{ $crate::system::LANE_BITS }>>,
            any_report: Signal<Local, Bit>,
            /// Some pipeline holds (a rare pair waits for its shared unit):
            /// the chain ORs the pipelines' `hold` ports, if they have one
            /// (the macro's `hold:`); otherwise it is constant 0 and
            /// synthesis removes it.
            hold_chain: Vec<Signal<Local, Bit>>,
            any_hold: Signal<Local, Bit>,
            /// With shared rare-case units: the chain ORs the pipelines'
            /// requests (`hold_request`), and `any_request`, the OR, goes
            /// back to every pipeline's `hold_others`, so that they hold
            /// together and each decides its enables from registers of its
            /// own. Both empty without shared units.
            hold_request_chain: Vec<Signal<Local, Bits<{ $crate::pipeline::hold_next::HOLD_REQUESTS }>>>,
            any_request: Vec<Signal<Local, Bits<{ $crate::pipeline::hold_next::HOLD_REQUESTS }>>>,
            /// With shared rare-case units: the read side's own copy of the
            /// pipelines' `hold` two clocks ahead, made as each pipeline
            /// makes its own from `any_request` (their `advance` is tied
            /// high). Empty without shared units.
            hold_forecast: Vec<$crate::pipeline::hold_next::HoldNext>,
            /// The pipelines hold next clock: `hold_forecast`'s register for
            /// `advance` high, or 0 without shared units.
            hold_next: Signal<Local, Bit>,
            /// Its register for `advance` low: the pipelines' `advance` is
            /// tied high (unused on purpose, for Verilator's lint). Empty
            /// without shared units.
            unused_hold_if_still: Vec<Signal<Local, Bit>>,
            /// Every lane tests the same streamed triangle, so only lane 0's
            /// stream id is stored; the others are folded into this chain,
            /// whose name tells Verilator's lint (`--unused-regexp`, default
            /// `*unused*`) that they are unused on purpose. Synthesis removes it.
            unused_stream_ids: Vec<Signal<Local, Bit>>,
            _config: $crate::system::SystemConfig,
        }

        impl<$(const $param: usize),*> $name<$($param),*> {
            /// The pipelines have shared rare-case units (the macro's `hold:`).
            const SHARED_UNITS: bool = false $(|| { let _ = stringify!($hold); true })?;

            /// The system for `config`, its `P` pipelines made by `make_pipeline`.
            pub fn new(config: $crate::system::SystemConfig, mut make_pipeline: impl FnMut() -> $pipeline) -> Self {
                config.validate();
                assert_eq!(config.coordinate_bits, $w, "the configuration's width differs from the type's");
                let p = config.pipelines;
                $name {
                    clock: Default::default(),
                    reset: Default::default(),
                    in_valid: Default::default(),
                    in_ready: Default::default(),
                    in_end: Default::default(),
                    in_object: Default::default(),
                    in_id: Default::default(),
                    in_x0: Default::default(),
                    in_y0: Default::default(),
                    in_z0: Default::default(),
                    in_x1: Default::default(),
                    in_y1: Default::default(),
                    in_z1: Default::default(),
                    in_x2: Default::default(),
                    in_y2: Default::default(),
                    in_z2: Default::default(),
                    out_valid: Default::default(),
                    out_ready: Default::default(),
                    out_id_a: Default::default(),
                    out_id_b: Default::default(),
                    out_hit: Default::default(),
                    out_certain: Default::default(),
                    done: Default::default(),
                    results_empty: Default::default(),
                    overflow: Default::default(),
                    pairs_tested: Default::default(),
                    hits: Default::default(),
                    stall_cycles: Default::default(),
                    address_generator: $crate::system::address_generator::AddressGenerator::new(
                        p,
                        config.triangles_per_bank,
                        config.read_to_counted_cycles(),
                    ),
                    memory_a: $crate::system::triangle_memory::TriangleMemory::new(config.triangles_per_bank),
                    memory_b: $crate::system::triangle_memory::TriangleMemory::new(config.triangles_per_bank),
                    pipelines: (0..p).map(|_| make_pipeline()).collect(),
                    result_fifo: $crate::system::result_fifo::ResultFifo::new(
                        p,
                        config.result_fifo_depth,
                        config.result_fifo_reserve(),
                    ),
                    pair_serializer: $crate::system::pair_serializer::PairSerializer::new(p),
                    pairs_tested_q: Default::default(),
                    hits_q: Default::default(),
                    tested_increment: Default::default(),
                    hit_increment: Default::default(),
                    stall_cycles_q: Default::default(),
                    stalled: Default::default(),
                    advance_q: Default::default(),
                    read_enable_a: Default::default(),
                    read_enable_b: Default::default(),
                    advance_next: Default::default(),
                    advance: Default::default(),
                    pipelines_move: Default::default(),
                    bus_id: Default::default(),
                    bus_coordinates: Default::default(),
                    report_mask_chain: (0..=p).map(|_| Default::default()).collect(),
                    hit_mask_chain: (0..=p).map(|_| Default::default()).collect(),
                    certain_mask_chain: (0..=p).map(|_| Default::default()).collect(),
                    tested_chain: (0..=p).map(|_| Default::default()).collect(),
                    hit_count_chain: (0..=p).map(|_| Default::default()).collect(),
                    report_mask: Default::default(),
                    hit_mask: Default::default(),
                    certain_mask: Default::default(),
                    tested_count: Default::default(),
                    hit_count: Default::default(),
                    any_report: Default::default(),
                    hold_chain: (0..=p).map(|_| Default::default()).collect(),
                    any_hold: Default::default(),
                    hold_request_chain: (0..=p).filter(|_| Self::SHARED_UNITS).map(|_| Default::default()).collect(),
                    any_request: (0..1).filter(|_| Self::SHARED_UNITS).map(|_| Default::default()).collect(),
                    hold_forecast: (0..1).filter(|_| Self::SHARED_UNITS).map(|_| Default::default()).collect(),
                    hold_next: Default::default(),
                    unused_hold_if_still: (0..1).filter(|_| Self::SHARED_UNITS).map(|_| Default::default()).collect(),
                    unused_stream_ids: (0..=p).map(|_| Default::default()).collect(),
                    _config: config,
                }
            }

            pub fn config(&self) -> $crate::system::SystemConfig {
                self._config
            }
        }

        impl<$(const $param: usize),*> $crate::unit::Unit for $name<$($param),*> {
            fn sub_units(&self, units: &mut $crate::unit::UnitWalk) {
                $crate::sub_units!(
                    self,
                    units,
                    address_generator,
                    memory_a,
                    memory_b,
                    pipelines,
                    result_fifo,
                    pair_serializer,
                    pairs_tested_q,
                    hits_q,
                    tested_increment,
                    hit_increment,
                    stall_cycles_q,
                    stalled,
                    advance_q,
                    read_enable_a,
                    read_enable_b,
                    hold_forecast
                );
            }
        }

        impl<$(const $param: usize),*> $crate::system::host_ports::HostPorts for $name<$($param),*> {
            fn clock_signal(&mut self) -> &mut Signal<In, Clock> {
                &mut self.clock
            }
            fn set_inputs(&mut self, inputs: &$crate::system::host_ports::HostInputs) {
                use $crate::system::host_ports::signed_bits;
                let c = &inputs.in_coordinates;
                self.reset.next = inputs.reset;
                self.in_valid.next = inputs.in_valid;
                self.in_end.next = inputs.in_end;
                self.in_object.next = inputs.in_object;
                self.in_id.next = (inputs.in_id as u64).to_bits();
                self.in_x0.next = signed_bits(c[0]);
                self.in_y0.next = signed_bits(c[1]);
                self.in_z0.next = signed_bits(c[2]);
                self.in_x1.next = signed_bits(c[3]);
                self.in_y1.next = signed_bits(c[4]);
                self.in_z1.next = signed_bits(c[5]);
                self.in_x2.next = signed_bits(c[6]);
                self.in_y2.next = signed_bits(c[7]);
                self.in_z2.next = signed_bits(c[8]);
                self.out_ready.next = inputs.out_ready;
            }
            fn outputs(&self) -> $crate::system::host_ports::HostOutputs {
                $crate::system::host_ports::HostOutputs {
                    in_ready: self.in_ready.val(),
                    out_valid: self.out_valid.val(),
                    out_id_a: self.out_id_a.val().to_u64() as u32,
                    out_id_b: self.out_id_b.val().to_u64() as u32,
                    out_hit: self.out_hit.val(),
                    out_certain: self.out_certain.val(),
                    done: self.done.val(),
                    results_empty: self.results_empty.val(),
                    overflow: self.overflow.val(),
                    pairs_tested: self.pairs_tested.val().to_u64() as u32,
                    hits: self.hits.val().to_u64() as u32,
                    stall_cycles: self.stall_cycles.val().to_u64() as u32,
                }
            }
            fn system_config(&self) -> $crate::system::SystemConfig {
                self._config
            }
            fn raw_design(&self) -> $crate::unit::RawDesign {
                $crate::unit::RawDesign::of(self)
            }
        }

        impl<$(const $param: usize),*> Logic for $name<$($param),*> {
            #[hdl_gen]
            fn update(&mut self) {
                dff_setup!(
                    self,
                    clock,
                    pairs_tested_q,
                    hits_q,
                    tested_increment,
                    hit_increment,
                    stall_cycles_q,
                    stalled
                );

                // The pipelines' outputs (registers) first: the masks and the
                // counts of this cycle's verdicts, then the enables.
                self.report_mask_chain[0].next = 0.into();
                self.hit_mask_chain[0].next = 0.into();
                self.certain_mask_chain[0].next = 0.into();
                self.tested_chain[0].next = 0.into();
                self.hit_count_chain[0].next = 0.into();
                self.report_mask.next = 0.into();
                self.hit_mask.next = 0.into();
                self.certain_mask.next = 0.into();
                self.tested_count.next = 0.into();
                self.hit_count.next = 0.into();
                for i in 0..self.pipelines.len() {
                    self.report_mask_chain[i + 1].next = self.report_mask_chain[i].val().replace_bit(
                        i,
                        self.pipelines[i].out_valid.val()
                            & (self.pipelines[i].out_hit.val() | !self.pipelines[i].out_certain.val()),
                    );
                    self.hit_mask_chain[i + 1].next = self.hit_mask_chain[i]
                        .val()
                        .replace_bit(i, self.pipelines[i].out_valid.val() & self.pipelines[i].out_hit.val());
                    self.certain_mask_chain[i + 1].next =
                        self.certain_mask_chain[i].val().replace_bit(i, self.pipelines[i].out_certain.val());
                    self.tested_chain[i + 1].next = self.tested_chain[i].val();
                    if self.pipelines[i].out_valid.val() {
                        self.tested_chain[i + 1].next = self.tested_chain[i].val() + 1;
                    }
                    self.hit_count_chain[i + 1].next = self.hit_count_chain[i].val();
                    if self.pipelines[i].out_valid.val() & self.pipelines[i].out_hit.val() {
                        self.hit_count_chain[i + 1].next = self.hit_count_chain[i].val() + 1;
                    }
                    self.report_mask.next = self.report_mask_chain[i + 1].val();
                    self.hit_mask.next = self.hit_mask_chain[i + 1].val();
                    self.certain_mask.next = self.certain_mask_chain[i + 1].val();
                    self.tested_count.next = self.tested_chain[i + 1].val();
                    self.hit_count.next = self.hit_count_chain[i + 1].val();
                }
                self.any_report.next = self.report_mask.val().any();
                self.unused_stream_ids[0].next = false;
                for i in 0..self.pipelines.len() {
                    self.unused_stream_ids[i + 1].next =
                        self.unused_stream_ids[i].val() ^ self.pipelines[i].out_stream_id.val().any();
                }
                self.hold_chain[0].next = false;
                self.any_hold.next = false;
                for i in 0..self.pipelines.len() {
                    self.hold_chain[i + 1].next = self.hold_chain[i].val() $(| self.pipelines[i].$hold.val())?;
                    self.any_hold.next = self.hold_chain[i + 1].val();
                }
                self.hold_next.next = false;
                $(
                    self.hold_request_chain[0].next = 0.into();
                    for i in 0..self.pipelines.len() {
                        self.hold_request_chain[i + 1].next =
                            self.hold_request_chain[i].val() | self.pipelines[i].$hold_request.val();
                        self.any_request[0].next = self.hold_request_chain[i + 1].val();
                    }
                    for i in 0..self.pipelines.len() {
                        self.pipelines[i].$hold_others.next = self.any_request[0].val();
                    }
                    for i in 0..self.hold_forecast.len() {
                        self.hold_forecast[i].clock.next = self.clock.val();
                        self.hold_forecast[i].reset.next = self.reset.val();
                        self.hold_forecast[i].advance.next = true;
                        self.hold_forecast[i].requests.next = self.any_request[0].val();
                    }
                    self.hold_next.next = self.hold_forecast[0].if_advance.val() & !self.reset.val();
                    self.unused_hold_if_still[0].next = self.hold_forecast[0].if_still.val();
                )?
                // Back-pressure: the read side holds while the FIFO is above
                // its mark (`room`, seen a clock late through the registered
                // copies of `advance`) and sends nothing; the
                // pipelines run on, and their pairs in flight go into the
                // FIFO's reserve (see `result_fifo`), so an enable need not
                // reach every pipeline register. Shared rare-case units hold
                // the pipelines (by themselves, `hold_others` above) and the
                // read side together.
                clock!(self, clock, advance_q, read_enable_a, read_enable_b);
                self.advance_next.next = self.result_fifo.room.val() & !self.hold_next.val();
                self.advance_q.d.next = self.advance_next.val();
                self.read_enable_a.d.next = self.advance_next.val();
                self.read_enable_b.d.next = self.advance_next.val();
                self.advance.next = self.advance_q.q.val();
                self.pipelines_move.next = !self.any_hold.val();

                // Host stream → write side of the address generator and memories.
                clock!(self, clock, address_generator, memory_a, memory_b, result_fifo, pair_serializer);
                self.address_generator.reset.next = self.reset.val();
                self.address_generator.advance.next = self.advance.val();
                self.address_generator.in_valid.next = self.in_valid.val();
                self.address_generator.in_end.next = self.in_end.val();
                self.address_generator.in_object.next = self.in_object.val();
                self.in_ready.next = self.address_generator.in_ready.val();
                self.memory_a.write_enable.next = self.address_generator.a_write_enable.val();
                self.memory_a.write_address.next = self.address_generator.a_write_address.val();
                self.memory_a.write_id.next = self.in_id.val();
                self.memory_a.read_enable.next = self.read_enable_a.q.val();
                self.memory_a.read_address.next = self.address_generator.a_read_address.val();
                self.memory_b.write_enable.next = self.address_generator.b_write_enable.val();
                self.memory_b.write_address.next = self.address_generator.b_write_address.val();
                self.memory_b.write_id.next = self.in_id.val();
                self.memory_b.read_enable.next = self.read_enable_b.q.val();
                self.memory_b.read_address.next = self.address_generator.b_read_address.val();
                self.memory_a.write_coordinates[0].next = self.in_x0.val();
                self.memory_a.write_coordinates[1].next = self.in_y0.val();
                self.memory_a.write_coordinates[2].next = self.in_z0.val();
                self.memory_a.write_coordinates[3].next = self.in_x1.val();
                self.memory_a.write_coordinates[4].next = self.in_y1.val();
                self.memory_a.write_coordinates[5].next = self.in_z1.val();
                self.memory_a.write_coordinates[6].next = self.in_x2.val();
                self.memory_a.write_coordinates[7].next = self.in_y2.val();
                self.memory_a.write_coordinates[8].next = self.in_z2.val();
                self.memory_b.write_coordinates[0].next = self.in_x0.val();
                self.memory_b.write_coordinates[1].next = self.in_y0.val();
                self.memory_b.write_coordinates[2].next = self.in_z0.val();
                self.memory_b.write_coordinates[3].next = self.in_x1.val();
                self.memory_b.write_coordinates[4].next = self.in_y1.val();
                self.memory_b.write_coordinates[5].next = self.in_z1.val();
                self.memory_b.write_coordinates[6].next = self.in_x2.val();
                self.memory_b.write_coordinates[7].next = self.in_y2.val();
                self.memory_b.write_coordinates[8].next = self.in_z2.val();

                // The shared triangle bus: bases come from A, streamed triangles from B.
                self.bus_id.next = self.memory_b.read_id.val();
                for k in 0..9 {
                    self.bus_coordinates[k].next = self.memory_b.read_coordinates[k].val();
                }
                if self.address_generator.bset.val() {
                    self.bus_id.next = self.memory_a.read_id.val();
                    for k in 0..9 {
                        self.bus_coordinates[k].next = self.memory_a.read_coordinates[k].val();
                    }
                }

                // P pipelines: own bset/valid each, the same bus; a lane takes
                // the bus's triangle in a clock the read side advances.
                for i in 0..self.pipelines.len() {
                    self.pipelines[i].clock.next = self.clock.val();
                    self.pipelines[i].reset.next = self.reset.val();
                    self.pipelines[i].advance.next = true;
                    self.pipelines[i].in_valid.next =
                        self.address_generator.lane_valid[i].val() & self.advance.val();
                    self.pipelines[i].in_bset.next = self.address_generator.bset.val();
                    self.pipelines[i].in_id.next = self.bus_id.val();
                    self.pipelines[i].in_x0.next = self.bus_coordinates[0].val();
                    self.pipelines[i].in_y0.next = self.bus_coordinates[1].val();
                    self.pipelines[i].in_z0.next = self.bus_coordinates[2].val();
                    self.pipelines[i].in_x1.next = self.bus_coordinates[3].val();
                    self.pipelines[i].in_y1.next = self.bus_coordinates[4].val();
                    self.pipelines[i].in_z1.next = self.bus_coordinates[5].val();
                    self.pipelines[i].in_x2.next = self.bus_coordinates[6].val();
                    self.pipelines[i].in_y2.next = self.bus_coordinates[7].val();
                    self.pipelines[i].in_z2.next = self.bus_coordinates[8].val();
                    self.result_fifo.write_base_ids[i].next = self.pipelines[i].out_base_id.val();
                    self.pair_serializer.head_base_ids[i].next = self.result_fifo.head_base_ids[i].val();
                }

                self.result_fifo.reset.next = self.reset.val();
                self.result_fifo.write.next = self.pipelines_move.val() & self.any_report.val();
                self.result_fifo.write_mask.next = self.report_mask.val();
                self.result_fifo.write_hit_mask.next = self.hit_mask.val();
                self.result_fifo.write_certain_mask.next = self.certain_mask.val();
                self.result_fifo.write_stream_id.next = self.pipelines[0].out_stream_id.val();
                self.result_fifo.pop.next = self.pair_serializer.pop.val();
                self.pair_serializer.reset.next = self.reset.val();
                self.pair_serializer.head_valid.next = self.result_fifo.head_valid.val();
                self.pair_serializer.head_mask.next = self.result_fifo.head_mask.val();
                self.pair_serializer.head_hit_mask.next = self.result_fifo.head_hit_mask.val();
                self.pair_serializer.head_certain_mask.next = self.result_fifo.head_certain_mask.val();
                self.pair_serializer.head_stream_id.next = self.result_fifo.head_stream_id.val();
                self.pair_serializer.out_ready.next = self.out_ready.val();
                self.out_valid.next = self.pair_serializer.out_valid.val();
                self.out_id_a.next = self.pair_serializer.out_id_a.val();
                self.out_id_b.next = self.pair_serializer.out_id_b.val();
                self.out_hit.next = self.pair_serializer.out_hit.val();
                self.out_certain.next = self.pair_serializer.out_certain.val();

                // Status and counters.
                self.done.next = self.address_generator.done.val();
                self.results_empty.next = self.result_fifo.empty.val() & !self.pair_serializer.holding.val();
                self.overflow.next = self.address_generator.overflow.val();
                self.tested_increment.d.next = 0.into();
                self.hit_increment.d.next = 0.into();
                if self.pipelines_move.val() {
                    self.tested_increment.d.next = self.tested_count.val();
                    self.hit_increment.d.next = self.hit_count.val();
                }
                self.pairs_tested_q.d.next = self.pairs_tested_q.q.val()
                    + bit_cast::<{ $crate::system::COUNTER_BITS }, { $crate::system::LANE_BITS }>(
                        self.tested_increment.q.val(),
                    );
                self.hits_q.d.next = self.hits_q.q.val()
                    + bit_cast::<{ $crate::system::COUNTER_BITS }, { $crate::system::LANE_BITS }>(
                        self.hit_increment.q.val(),
                    );
                // Held with work to do: a clock the batch takes longer.
                self.stalled.d.next = !self.advance.val() & !self.address_generator.done.val();
                if self.stalled.q.val() {
                    self.stall_cycles_q.d.next = self.stall_cycles_q.q.val() + 1;
                }
                if self.reset.val() {
                    self.pairs_tested_q.d.next = 0.into();
                    self.hits_q.d.next = 0.into();
                    self.tested_increment.d.next = 0.into();
                    self.hit_increment.d.next = 0.into();
                    self.stall_cycles_q.d.next = 0.into();
                    self.stalled.d.next = false;
                }
                self.pairs_tested.next = self.pairs_tested_q.q.val();
                self.hits.next = self.hits_q.q.val();
                self.stall_cycles.next = self.stall_cycles_q.q.val();
            }
        }
    };
}

collision_system!(
    /// The system with stub pipelines (see [`StubPipeline`]).
    pub struct StubCollisionSystem<const W: usize> {
        coordinate_bits: W,
        pipeline: StubPipeline<W>,
    }
);

impl<const W: usize> StubCollisionSystem<W> {
    /// The system with stub pipelines of latency `config.pipeline_latency`.
    pub fn with_stub_pipelines(config: crate::system::SystemConfig) -> Self {
        let latency = config.pipeline_latency;
        Self::new(config, || StubPipeline::new(latency))
    }
}

collision_system!(
    /// The system with the Devillers–Guigue pipelines (concrete widths:
    /// [`super::system_for_width`]).
    pub struct CollisionSystem<const W: usize, const D: usize, const C: usize, const O: usize> {
        coordinate_bits: W,
        pipeline: TrianglePipeline<W, D, C, O>,
    }
);

collision_system!(
    /// The system with Devillers–Guigue pipelines that test their rare
    /// pairs on a shared unit ([`SharedRarePipeline`]): every pipeline
    /// holds, and the read side with them, while one of them waits for its
    /// unit.
    pub struct SharedCollisionSystem<const W: usize, const D: usize, const C: usize, const O: usize> {
        coordinate_bits: W,
        pipeline: SharedRarePipeline<W, D, C, O>,
        hold: hold,
        hold_request: hold_request,
        hold_others: hold_others,
    }
);

impl<const W: usize, const D: usize, const C: usize, const O: usize>
    SharedCollisionSystem<W, D, C, O>
{
    /// The system with shared-unit pipelines; `config.pipeline_latency`
    /// must be the pipeline's latency.
    pub fn with_pipelines(config: crate::system::SystemConfig) -> Self {
        assert_eq!(
            config.pipeline_latency,
            latency(),
            "the pipeline's latency is {}",
            latency()
        );
        Self::new(config, SharedRarePipeline::new)
    }
}

impl<const W: usize, const D: usize, const C: usize, const O: usize> CollisionSystem<W, D, C, O> {
    /// The system with real pipelines; `config.pipeline_latency` must be the
    /// pipeline's latency.
    pub fn with_pipelines(config: crate::system::SystemConfig) -> Self {
        assert_eq!(
            config.pipeline_latency,
            latency(),
            "the pipeline's latency is {}",
            latency()
        );
        Self::new(config, TrianglePipeline::new)
    }
}
