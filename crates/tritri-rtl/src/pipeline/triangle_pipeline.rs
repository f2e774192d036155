//! The top: the Devillers–Guigue triangle-pair pipeline (thesis, chapter 3,
//! figure 3.1), one pair per clock, fixed latency [`latency`], with the
//! rare cases' tests in parallel: the general path
//! ([`super::general_path`]) and, started with its plane side, the
//! coplanar test (11 stages, 36 multipliers) and the degenerate pair's
//! segment test (9 stages, 24 multipliers), whose verdicts wait for the
//! decision. No pair ever stalls it; the other top,
//! [`super::shared_rare_pipeline`], trades those 60 multipliers for six
//! and stalls.
//!
//! Input, one triangle per clock: nine W-bit signed coordinates
//! `in_x0 in_y0 in_z0 … in_z2`, `in_valid`, `in_bset` and an id. A triangle
//! with `in_bset = 1` becomes the base polygon T1 (it is not tested); every
//! other valid triangle T2 is tested against the current base, and its
//! verdict leaves `latency()` clocks later with `out_valid = 1`, `out_hit`,
//! `out_certain` and both ids. `advance` is a global clock enable: when
//! low, the whole pipeline, base polygon included, holds (for
//! back-pressure); `reset` (synchronous, active high) clears the valid
//! bits only.
//!
//! Every verdict equals `tritri_geom::fixed_point::intersects(base, streamed)`
//! for every input, degenerate and coplanar included.

use super::coplanar_test::{CoplanarTest, COPLANAR_TEST_LATENCY};
use super::degenerate_pair::{DegeneratePair, DEGENERATE_PAIR_LATENCY};
use super::general_path::{GeneralPath, RARE_VERDICTS_STAGE};
use crate::arith::delay_line::DelayLine;
use rust_hdl::prelude::*;

pub use super::general_path::{latency, TRIANGLE_PIPELINE_LATENCY};

const _: () = assert!(
    COPLANAR_TEST_LATENCY < RARE_VERDICTS_STAGE && DEGENERATE_PAIR_LATENCY < RARE_VERDICTS_STAGE
);

crate::pipeline_ports! {
    // The ports: crate::pipeline::ports.
    #[derive(LogicBlock, Default)]
    pub struct TrianglePipeline<const W: usize, const D: usize, const C: usize, const O: usize> {
        path: GeneralPath<W, D, C, O>,
        coplanar: CoplanarTest<W, D, C>,
        degenerate_pair: DegeneratePair<W, D, C>,
        coplanar_to_decision: DelayLine<Bit, { RARE_VERDICTS_STAGE - COPLANAR_TEST_LATENCY }>,
        degenerate_pair_to_decision: DelayLine<Bit, { RARE_VERDICTS_STAGE - DEGENERATE_PAIR_LATENCY }>,
        /// The path's `sides_*` outputs and degenerate flags, which only
        /// the shared unit needs, folded into a bit whose name tells
        /// Verilator's lint they are unused on purpose.
        unused_sides: Signal<Local, Bit>,
    }
}

impl<const W: usize, const D: usize, const C: usize, const O: usize> crate::unit::Unit
    for TrianglePipeline<W, D, C, O>
{
    const LATENCY: Option<usize> = Some(TRIANGLE_PIPELINE_LATENCY);
    fn sub_units(&self, units: &mut crate::unit::UnitWalk) {
        crate::sub_units!(
            self,
            units,
            path,
            coplanar,
            degenerate_pair,
            coplanar_to_decision,
            degenerate_pair_to_decision
        );
    }
}

impl<const W: usize, const D: usize, const C: usize, const O: usize> TrianglePipeline<W, D, C, O> {
    /// A pipeline for W-bit coordinates. Panics unless `D`, `C`, `O` are the
    /// widths `tritri_geom::widths` derives from `W`.
    pub fn new() -> Self {
        GeneralPath::<W, D, C, O>::new();
        Self::default()
    }
}

impl<const W: usize, const D: usize, const C: usize, const O: usize> Logic
    for TrianglePipeline<W, D, C, O>
{
    #[hdl_gen]
    fn update(&mut self) {
        clock!(
            self,
            clock,
            path,
            coplanar,
            degenerate_pair,
            coplanar_to_decision,
            degenerate_pair_to_decision
        );
        self.path.reset.next = self.reset.val();
        self.path.advance.next = self.advance.val();
        for i in 0..12 {
            self.path.advance_copies[i].next = self.advance.val();
        }
        self.path.base_advance.next = self.advance.val();
        self.path.base_hold_if_advance.next = false;
        self.path.base_hold_if_still.next = false;
        self.coplanar.advance.next = self.advance.val();
        self.degenerate_pair.advance.next = self.advance.val();
        self.coplanar_to_decision.advance.next = self.advance.val();
        self.degenerate_pair_to_decision.advance.next = self.advance.val();

        // The ports, through to the path.
        self.path.in_valid.next = self.in_valid.val();
        self.path.in_bset.next = self.in_bset.val();
        self.path.in_id.next = self.in_id.val();
        self.path.in_x0.next = self.in_x0.val();
        self.path.in_y0.next = self.in_y0.val();
        self.path.in_z0.next = self.in_z0.val();
        self.path.in_x1.next = self.in_x1.val();
        self.path.in_y1.next = self.in_y1.val();
        self.path.in_z1.next = self.in_z1.val();
        self.path.in_x2.next = self.in_x2.val();
        self.path.in_y2.next = self.in_y2.val();
        self.path.in_z2.next = self.in_z2.val();
        self.out_valid.next = self.path.out_valid.val();
        self.out_hit.next = self.path.out_hit.val();
        self.out_certain.next = self.path.out_certain.val();
        self.out_base_id.next = self.path.out_base_id.val();
        self.out_stream_id.next = self.path.out_stream_id.val();

        // The coplanar test and the degenerate pair test, from the pair.
        self.coplanar.axis.next = self.path.pair_axis.val();
        for i in 0..9 {
            self.coplanar.t1_vertices[i].next = self.path.pair_t1_vertices[i].val();
            self.coplanar.t2_vertices[i].next = self.path.pair_t2_vertices[i].val();
            self.degenerate_pair.t1_vertices[i].next = self.path.pair_t1_vertices[i].val();
            self.degenerate_pair.t2_vertices[i].next = self.path.pair_t2_vertices[i].val();
        }
        for k in 0..3 {
            self.coplanar.t1_normal_negative[k].next = self.path.pair_t1_normal_negative[k].val();
            self.coplanar.t1_normal_zero[k].next = self.path.pair_t1_normal_zero[k].val();
            self.coplanar.t2_normal_negative[k].next = self.path.pair_t2_normal_negative[k].val();
            self.coplanar.t2_normal_zero[k].next = self.path.pair_t2_normal_zero[k].val();
        }
        self.degenerate_pair.t1_segment_low.next = self.path.pair_t1_segment_low.val();
        self.degenerate_pair.t1_segment_high.next = self.path.pair_t1_segment_high.val();
        self.degenerate_pair.t2_segment_low.next = self.path.pair_t2_segment_low.val();
        self.degenerate_pair.t2_segment_high.next = self.path.pair_t2_segment_high.val();
        self.coplanar_to_decision.d.next = self.coplanar.hit.val();
        self.degenerate_pair_to_decision.d.next = self.degenerate_pair.hit.val();
        self.path.coplanar_hit.next = self.coplanar_to_decision.q.val();
        self.path.degenerate_pair_hit.next = self.degenerate_pair_to_decision.q.val();

        self.unused_sides.next = self.path.sides_valid.val()
            || self.path.sides_t1_all_zero.val()
            || self.path.sides_t2_all_zero.val()
            || self.path.pair_t1_degenerate.val()
            || self.path.pair_t2_degenerate.val();
    }
}
