//! A stand-in for the triangle pipeline with identical ports and a
//! configurable latency `L`, computing a trivial verdict, so that the
//! memories, the address generator and the result path can be tested (and
//! their cycle counts checked) without the cost of the real arithmetic.
//!
//! Ports: the real pipeline's ([`crate::pipeline::ports`]); `out_valid`
//! comes `L` cycles after its input.
//!
//! Verdict: [`stub_hit`] and [`stub_certain`], which read both ids and one
//! coordinate of each triangle, so the id and coordinate paths from the
//! memories are checked, and some pairs are uncertain (reported to the host
//! whatever their verdict).

use super::ID_BITS;
use rust_hdl::prelude::*;

/// The stub's verdict for base `(id, x0)` against streamed `(id, z2)`: the
/// low two bits of `base_id ^ stream_id ^ base_x0 ^ stream_z2` are zero.
pub fn stub_hit(base_id: u32, base_x0: i64, stream_id: u32, stream_z2: i64) -> bool {
    stub_bits(base_id, base_x0, stream_id, stream_z2) & 3 == 0
}

/// The stub's certificate: bits 2 and 3 of the same value are not both one
/// (a quarter of the pairs are uncertain).
pub fn stub_certain(base_id: u32, base_x0: i64, stream_id: u32, stream_z2: i64) -> bool {
    stub_bits(base_id, base_x0, stream_id, stream_z2) & 12 != 12
}

fn stub_bits(base_id: u32, base_x0: i64, stream_id: u32, stream_z2: i64) -> u64 {
    base_id as u64 ^ stream_id as u64 ^ base_x0 as u64 ^ stream_z2 as u64
}

#[derive(Clone, Copy, Default, Debug)]
struct Stage {
    valid: bool,
    hit: bool,
    certain: bool,
    base_id: u64,
    stream_id: u64,
}

crate::pipeline_ports! {
    #[derive(LogicBlock, Default)]
    pub struct StubPipeline<const W: usize> {
        _base_id: u64,
        _base_x0: u64,
        _stages: Vec<Stage>,
    }
}

impl<const W: usize> crate::unit::Unit for StubPipeline<W> {}

impl<const W: usize> StubPipeline<W> {
    pub fn new(latency: usize) -> Self {
        assert!(latency >= 1);
        StubPipeline {
            _stages: vec![Stage::default(); latency],
            ..Default::default()
        }
    }

    pub fn latency(&self) -> usize {
        self._stages.len()
    }
}

impl<const W: usize> Logic for StubPipeline<W> {
    fn update(&mut self) {
        if self.clock.pos_edge() {
            if self.advance.val() {
                let in_id = self.in_id.val().to_u64();
                let in_z2 = self.in_z2.val().to_u64();
                let bits = self._base_id ^ in_id ^ self._base_x0 ^ in_z2;
                let entering = Stage {
                    valid: self.in_valid.val() && !self.in_bset.val(),
                    hit: bits & 3 == 0,
                    certain: bits & 12 != 12,
                    base_id: self._base_id,
                    stream_id: in_id,
                };
                if self.in_valid.val() && self.in_bset.val() {
                    self._base_id = in_id;
                    self._base_x0 = self.in_x0.val().to_u64();
                }
                self._stages.rotate_right(1);
                self._stages[0] = entering;
            }
            if self.reset.val() {
                self._stages.iter_mut().for_each(|s| s.valid = false);
            }
            let last = *self._stages.last().unwrap();
            self.out_valid.next = last.valid;
            self.out_hit.next = last.hit;
            self.out_certain.next = last.certain;
            self.out_base_id.next = last.base_id.to_bits();
            self.out_stream_id.next = last.stream_id.to_bits();
        }
    }

    fn connect(&mut self) {
        self.out_valid.connect();
        self.out_hit.connect();
        self.out_certain.connect();
        self.out_base_id.connect();
        self.out_stream_id.connect();
    }

    fn hdl(&self) -> Verilog {
        let l = self._stages.len();
        Verilog::Custom(format!(
            "\
// Stub pipeline: latency {l}, verdict = low two bits of
// base_id ^ stream_id ^ base_x0 ^ stream_z2 are zero, certain = bits 2
// and 3 of it are not both one.
reg [{id}:0] base_id_q;
reg [{w}:0] base_x0_q;
reg valid_q [0:{last}];
reg hit_q [0:{last}];
reg certain_q [0:{last}];
reg [{id}:0] base_id_stage_q [0:{last}];
reg [{id}:0] stream_id_stage_q [0:{last}];
wire [3:0] verdict_bits = base_id_q[3:0] ^ in_id[3:0] ^ base_x0_q[3:0] ^ in_z2[3:0];
integer stage;

always @(posedge clock) begin
    if (advance) begin
        if (in_valid && in_bset) begin
            base_id_q <= in_id;
            base_x0_q <= in_x0;
        end
        valid_q[0] <= in_valid && !in_bset;
        hit_q[0] <= verdict_bits[1:0] == 2'b00;
        certain_q[0] <= verdict_bits[3:2] != 2'b11;
        base_id_stage_q[0] <= base_id_q;
        stream_id_stage_q[0] <= in_id;
        for (stage = 1; stage < {l}; stage = stage + 1) begin
            valid_q[stage] <= valid_q[stage - 1];
            hit_q[stage] <= hit_q[stage - 1];
            certain_q[stage] <= certain_q[stage - 1];
            base_id_stage_q[stage] <= base_id_stage_q[stage - 1];
            stream_id_stage_q[stage] <= stream_id_stage_q[stage - 1];
        end
    end
    if (reset) begin
        for (stage = 0; stage < {l}; stage = stage + 1) begin
            valid_q[stage] <= 1'b0;
        end
    end
end

always @(*) begin
    out_valid = valid_q[{last}];
    out_hit = hit_q[{last}];
    out_certain = certain_q[{last}];
    out_base_id = base_id_stage_q[{last}];
    out_stream_id = stream_id_stage_q[{last}];
end
",
            id = ID_BITS - 1,
            w = W - 1,
            last = l - 1,
        ))
    }
}
