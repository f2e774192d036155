//! The pipeline's general path: everything of the Devillers–Guigue
//! triangle-pair pipeline (thesis, chapter 3, figure 3.1) but the tests of
//! the rare cases, the coplanar test and the degenerate pair's segment
//! test. The two tops put those around it: in parallel
//! ([`super::triangle_pipeline::TrianglePipeline`], 60 multipliers, never
//! a stall) or on one shared, slower unit
//! ([`super::shared_rare_pipeline::SharedRarePipeline`], 6 multipliers,
//! stalling while a rare pair waits for it). The path hands them the pair
//! as it forms (`pair_*`, stage 0) and its plane-side signs' zeros
//! (`sides_*`, [`SIDES_STAGE`]), and takes their verdicts in the decision's
//! last stage (`coplanar_hit`, `degenerate_pair_hit`,
//! [`RARE_VERDICTS_STAGE`]).
//!
//! Input, one triangle per clock: nine W-bit signed coordinates
//! `in_x0 in_y0 in_z0 … in_z2`, `in_valid`, `in_bset` and an id. A triangle
//! with `in_bset = 1` becomes the base polygon T1 (it is not tested); every
//! other valid triangle T2 is tested against the current base, and its
//! verdict leaves `latency()` clocks later with `out_valid = 1`, `out_hit`,
//! `out_certain` (the verdict is provably the verdict on the coordinates
//! before quantization, `tritri_geom::certificate`) and both ids. `advance`
//! is a global clock enable: when low, the whole path, base polygon
//! included, holds (for back-pressure); `reset` (synchronous, active high)
//! clears the valid bits only.
//!
//! Flow, with the stage counts of each unit:
//!
//! ```text
//! input registers (1)
//!   -> triangle front end: normal, signs, degenerate, axis, segment ends (9)
//!   -> base polygon registers (on bset) | pair = (base, streamed)
//!   -> plane side T1 vs plane 2 || plane side T2 vs plane 1   (7)   steps 1-4
//!   -> align T1 (1) -> align T2 (1) -> interval overlap (1)         steps 5-7
//!   -> orient3d operands (3) -> 2 x orient3d (11 to the values)
//!   -> the segment-triangle case's third determinant, from the two
//!      determinants' values and the segment ends' plane-side values (2;
//!      units 0 and 1's signs, a clock after their values, wait a clock)
//!   -> decision (3), with the rare tests' verdicts
//! ```
//!
//! With the rare tests' verdicts, every verdict equals
//! `tritri_geom::fixed_point::intersects(base, streamed)` for every input,
//! degenerate and coplanar included.

use super::align_t1::{AlignT1, ALIGN_T1_LATENCY};
use super::align_t2::{AlignT2, ALIGN_T2_LATENCY};
use super::base_polygon::BasePolygon;
use super::certified_orient3d::{
    CertifiedOrient3d, CERTIFIED_ORIENT3D_LATENCY, ORIENT3D_VALUE_LATENCY,
};
use super::decision::{Decision, DECISION_LATENCY};
use super::interval_overlap::{IntervalOverlap, INTERVAL_OVERLAP_LATENCY};
use super::orient3d_operands::{Orient3dOperands, ORIENT3D_OPERANDS_LATENCY};
use super::plane_side::{PlaneSide, PLANE_SIDE_LATENCY};
use super::third_determinant::{
    EndsDifference, ThirdDeterminant, ENDS_DIFFERENCE_LATENCY, THIRD_DETERMINANT_LATENCY,
};
use super::triangle_front_end::{TriangleFrontEnd, FRONT_END_LATENCY};
use super::ID_BITS;
use crate::arith::certificate::{CERTAIN_SIGN_LATENCY, CERTIFICATE_LATENCY};
use crate::arith::delay_line::DelayLine;
use crate::arith::valid_line::ValidLine;
use rust_hdl::prelude::*;

/// Input registers.
const INPUT_LATENCY: usize = 1;
/// From the input ports to the triangle's record.
const RECORD_STAGE: usize = INPUT_LATENCY + FRONT_END_LATENCY;
// Stages below count from the pair's formation.
/// The plane-side signs, and the pair beside them (`sides_*`).
pub const SIDES_STAGE: usize = PLANE_SIDE_LATENCY;
const OPERANDS_STAGE: usize =
    PLANE_SIDE_LATENCY + ALIGN_T1_LATENCY + ALIGN_T2_LATENCY + INTERVAL_OVERLAP_LATENCY;
/// The determinants' values, and a stage later their signs.
const VALUES_STAGE: usize = OPERANDS_STAGE + ORIENT3D_OPERANDS_LATENCY + ORIENT3D_VALUE_LATENCY;
const ORIENT_SIGNS_STAGE: usize =
    OPERANDS_STAGE + ORIENT3D_OPERANDS_LATENCY + CERTIFIED_ORIENT3D_LATENCY;
/// The plane-side values a stage before their signs, and `s_b - s_a`.
const DISTANCES_STAGE: usize = PLANE_SIDE_LATENCY - CERTAIN_SIGN_LATENCY;
const ENDS_DIFFERENCE_STAGE: usize = DISTANCES_STAGE + ENDS_DIFFERENCE_LATENCY;
/// The third determinant's sign comes last.
pub const DECISION_STAGE: usize = VALUES_STAGE + THIRD_DETERMINANT_LATENCY;
/// The rare tests' verdicts go into the decision's last stage.
pub const RARE_VERDICTS_STAGE: usize = DECISION_STAGE + DECISION_LATENCY - 1;
const _: () = assert!(DECISION_LATENCY == 3);
const _: () = assert!(DECISION_STAGE > ORIENT_SIGNS_STAGE && ENDS_DIFFERENCE_STAGE < VALUES_STAGE);
/// The certificates come two clocks after their signs (`CertainSign`):
/// the plane side's wait for the decision in lines two stages shorter
/// than the signs', and units 0 and 1's reach it as the third
/// determinant's sign does, wired straight to it.
const SIDE_CERTIFICATES_STAGE: usize =
    PLANE_SIDE_LATENCY + CERTIFICATE_LATENCY - CERTAIN_SIGN_LATENCY;
const _: () = assert!(
    DECISION_STAGE > SIDE_CERTIFICATES_STAGE
        && ORIENT_SIGNS_STAGE + CERTIFICATE_LATENCY - CERTAIN_SIGN_LATENCY == DECISION_STAGE
);
/// From the pair's formation to the output ports.
const PAIR_LATENCY: usize = DECISION_STAGE + DECISION_LATENCY;

/// The groups of units with an enable of their own (`advance_copies`):
/// each plane side, alignment and the interval overlap, orient3d's
/// operands, each orient3d, the decision, the front end, the input
/// vertices, T1's and T2's vertices to the operands, and the ids' delay
/// lines (the update's literal 12). The base polygon forms its groups'
/// enables itself (`base_advance`).
pub const ADVANCE_COPIES: usize = 12;

/// Clock edges (with `advance` high) from a triangle on the input ports to
/// its verdict on the output ports.
pub const TRIANGLE_PIPELINE_LATENCY: usize = RECORD_STAGE + PAIR_LATENCY;

/// The pipeline's latency `L`: a run of `N1` bases against `N2` streamed
/// triangles takes `N1 + N1 N2 + L` clocks (thesis, equation 3.2).
pub const fn latency() -> usize {
    TRIANGLE_PIPELINE_LATENCY
}

crate::pipeline_ports! {
    // The ports: crate::pipeline::ports.
    #[derive(LogicBlock, Default)]
    pub struct GeneralPath<const W: usize, const D: usize, const C: usize, const O: usize> {
        /// The pair as it forms (stage 0), for tests that start with the
        /// plane side: both triangles' vertices, the coplanar test's axis,
        /// the normals' signs, the degenerate flags and segment ends.
        pub pair_t1_vertices: [Signal<Out, Bits<W>>; 9],
        pub pair_t2_vertices: [Signal<Out, Bits<W>>; 9],
        pub pair_axis: Signal<Out, Bits<2>>,
        pub pair_t1_normal_negative: [Signal<Out, Bit>; 3],
        pub pair_t1_normal_zero: [Signal<Out, Bit>; 3],
        pub pair_t2_normal_negative: [Signal<Out, Bit>; 3],
        pub pair_t2_normal_zero: [Signal<Out, Bit>; 3],
        pub pair_t1_degenerate: Signal<Out, Bit>,
        pub pair_t2_degenerate: Signal<Out, Bit>,
        pub pair_t1_segment_low: Signal<Out, Bits<2>>,
        pub pair_t1_segment_high: Signal<Out, Bits<2>>,
        pub pair_t2_segment_low: Signal<Out, Bits<2>>,
        pub pair_t2_segment_high: Signal<Out, Bits<2>>,
        /// Beside the plane-side signs ([`SIDES_STAGE`]): whether a pair
        /// is there, and whether all of a triangle's vertices lie on the
        /// other plane.
        pub sides_valid: Signal<Out, Bit>,
        pub sides_t1_all_zero: Signal<Out, Bit>,
        pub sides_t2_all_zero: Signal<Out, Bit>,
        /// The rare tests' verdicts for the pair at [`RARE_VERDICTS_STAGE`]
        /// (each is read only when the pair's case needs it).
        pub coplanar_hit: Signal<In, Bit>,
        pub degenerate_pair_hit: Signal<In, Bit>,
        /// Copies of `advance`, each the enable of one group of units
        /// ([`ADVANCE_COPIES`]); `advance` itself enables the input records
        /// and the valid bits. A top ties them all to `advance`, or drives
        /// each from a register of its own, so that no one net reaches
        /// every register ([`super::hold_register`]).
        pub advance_copies: [Signal<In, Bit>; 12],
        /// The base polygon's enables, from their parts: `advance` before
        /// `hold`, and `hold` next clock if `advance` is high this clock
        /// and if it is low (a top that never holds ties these two low).
        pub base_advance: Signal<In, Bit>,
        pub base_hold_if_advance: Signal<In, Bit>,
        pub base_hold_if_still: Signal<In, Bit>,
        input_vertices: [DelayLine<Bits<W>, INPUT_LATENCY>; 9],
        record_valid: ValidLine<RECORD_STAGE>,
        record_bset: DelayLine<Bit, RECORD_STAGE>,
        /// `valid && bset` a stage before the record: the base polygon's
        /// load, an enabled edge ahead.
        record_load: ValidLine<{ RECORD_STAGE - 1 }>,
        record_id: DelayLine<Bits<ID_BITS>, RECORD_STAGE>,
        front_end: TriangleFrontEnd<W, D, C>,
        base: BasePolygon<W, D, C>,
        pair_valid_to_sides: ValidLine<SIDES_STAGE>,
        pair_valid_to_out: ValidLine<{ PAIR_LATENCY - SIDES_STAGE }>,
        base_id: DelayLine<Bits<ID_BITS>, PAIR_LATENCY>,
        stream_id: DelayLine<Bits<ID_BITS>, PAIR_LATENCY>,
        /// Steps (1)-(2): T1 (base) against the plane of T2 (streamed).
        plane_side_t1: PlaneSide<W, D, C, O>,
        /// Steps (3)-(4): T2 against the plane of T1, in parallel.
        plane_side_t2: PlaneSide<W, D, C, O>,
        align_t1: AlignT1,
        align_t2: AlignT2,
        interval_overlap: IntervalOverlap,
        operands: Orient3dOperands<W>,
        /// Step (7)'s determinants, with certificates.
        orient3d_0: CertifiedOrient3d<W, D, C, O>,
        orient3d_1: CertifiedOrient3d<W, D, C, O>,
        /// The segment-triangle case's third determinant, from the segment
        /// ends' plane-side values and units 0 and 1.
        ends_difference: EndsDifference<O>,
        ends_difference_to_values: DelayLine<Bits<O>, { VALUES_STAGE - ENDS_DIFFERENCE_STAGE }>,
        third_determinant: ThirdDeterminant<O>,
        /// The degenerate flag of T1 and the four segment ends, to the
        /// plane-side values.
        degenerate_to_distances: DelayLine<Bit, DISTANCES_STAGE>,
        segment_ends_to_distances: [DelayLine<Bits<2>, DISTANCES_STAGE>; 4],
        /// Units 0 and 1's negative and zero bits, to the third's sign.
        orient_signs_to_decision: [DelayLine<Bit, { DECISION_STAGE - ORIENT_SIGNS_STAGE }>; 4],
        decision: Decision,
        // Alignment of the operands of later stages:
        t1_vertices_to_operands: [DelayLine<Bits<W>, OPERANDS_STAGE>; 9],
        t2_vertices_to_operands: [DelayLine<Bits<W>, OPERANDS_STAGE>; 9],
        /// t1 degenerate, t2 degenerate: to the operands a clock before the
        /// overlap indices (the operands register the case).
        degenerate_to_operands: [DelayLine<Bit, { OPERANDS_STAGE - 1 }>; 2],
        /// t1 low, t1 high, t2 low, t2 high, likewise.
        segment_ends_to_operands: [DelayLine<Bits<2>, { OPERANDS_STAGE - 1 }>; 4],
        degenerate_to_decision: [DelayLine<Bit, { DECISION_STAGE - OPERANDS_STAGE + 1 }>; 2],
        segment_ends_to_decision: [DelayLine<Bits<2>, { DECISION_STAGE - OPERANDS_STAGE + 1 }>; 4],
        /// t1 negative, t1 zero, t2 negative, t2 zero at `3 j + vertex`.
        sides_to_decision: [DelayLine<Bit, { DECISION_STAGE - PLANE_SIDE_LATENCY }>; 12],
        /// t1 certain, t2 certain at `3 j + vertex`.
        side_certificates_to_decision:
            [DelayLine<Bit, { DECISION_STAGE - SIDE_CERTIFICATES_STAGE }>; 6],
    }
}

impl<const W: usize, const D: usize, const C: usize, const O: usize> crate::unit::Unit
    for GeneralPath<W, D, C, O>
{
    const LATENCY: Option<usize> = Some(TRIANGLE_PIPELINE_LATENCY);
    fn sub_units(&self, units: &mut crate::unit::UnitWalk) {
        crate::sub_units!(
            self,
            units,
            input_vertices,
            record_valid,
            record_bset,
            record_load,
            record_id,
            front_end,
            base,
            pair_valid_to_sides,
            pair_valid_to_out,
            base_id,
            stream_id,
            plane_side_t1,
            plane_side_t2,
            align_t1,
            align_t2,
            interval_overlap,
            operands,
            orient3d_0,
            orient3d_1,
            ends_difference,
            ends_difference_to_values,
            third_determinant,
            degenerate_to_distances,
            segment_ends_to_distances,
            orient_signs_to_decision,
            decision,
            t1_vertices_to_operands,
            t2_vertices_to_operands,
            degenerate_to_operands,
            segment_ends_to_operands,
            degenerate_to_decision,
            segment_ends_to_decision,
            sides_to_decision,
            side_certificates_to_decision
        );
    }
}

impl<const W: usize, const D: usize, const C: usize, const O: usize> GeneralPath<W, D, C, O> {
    /// A path for W-bit coordinates. Panics unless `D`, `C`, `O` are the
    /// widths `tritri_geom::widths` derives from `W`.
    pub fn new() -> Self {
        use tritri_geom::widths::{cross_bits, difference_bits, orient3d_bits};
        assert_eq!(D, difference_bits(W), "difference width for W = {W}");
        assert_eq!(C, cross_bits(W), "cross-product width for W = {W}");
        assert_eq!(O, orient3d_bits(W), "orient3d width for W = {W}");
        Self::default()
    }
}

impl<const W: usize, const D: usize, const C: usize, const O: usize> Logic
    for GeneralPath<W, D, C, O>
{
    #[hdl_gen]
    fn update(&mut self) {
        // Clock and clock enable to every unit.
        clock!(
            self,
            clock,
            record_valid,
            record_bset,
            record_load,
            record_id,
            front_end,
            base,
            pair_valid_to_sides,
            pair_valid_to_out,
            base_id,
            stream_id,
            plane_side_t1,
            plane_side_t2,
            align_t1,
            align_t2,
            interval_overlap,
            operands,
            orient3d_0,
            orient3d_1,
            ends_difference,
            ends_difference_to_values,
            third_determinant,
            degenerate_to_distances,
            decision
        );
        self.record_valid.reset.next = self.reset.val();
        self.record_valid.advance.next = self.advance.val();
        self.record_bset.advance.next = self.advance.val();
        self.record_load.reset.next = self.reset.val();
        self.record_load.advance.next = self.advance.val();
        self.record_id.advance.next = self.advance.val();
        self.front_end.advance.next = self.advance_copies[7].val();
        self.pair_valid_to_sides.reset.next = self.reset.val();
        self.pair_valid_to_sides.advance.next = self.advance.val();
        self.pair_valid_to_out.reset.next = self.reset.val();
        self.pair_valid_to_out.advance.next = self.advance.val();
        self.base_id.advance.next = self.advance_copies[11].val();
        self.stream_id.advance.next = self.advance_copies[11].val();
        self.plane_side_t1.advance.next = self.advance_copies[0].val();
        self.plane_side_t2.advance.next = self.advance_copies[1].val();
        self.align_t1.advance.next = self.advance_copies[2].val();
        self.align_t2.advance.next = self.advance_copies[2].val();
        self.interval_overlap.advance.next = self.advance_copies[2].val();
        self.operands.advance.next = self.advance_copies[3].val();
        self.orient3d_0.advance.next = self.advance_copies[4].val();
        self.orient3d_1.advance.next = self.advance_copies[5].val();
        self.ends_difference.advance.next = self.advance_copies[2].val();
        self.ends_difference_to_values.advance.next = self.advance_copies[2].val();
        self.third_determinant.advance.next = self.advance_copies[5].val();
        self.degenerate_to_distances.advance.next = self.advance_copies[2].val();
        self.decision.advance.next = self.advance_copies[6].val();
        for i in 0..9 {
            self.input_vertices[i].clock.next = self.clock.val();
            self.input_vertices[i].advance.next = self.advance_copies[8].val();
            self.t1_vertices_to_operands[i].clock.next = self.clock.val();
            self.t1_vertices_to_operands[i].advance.next = self.advance_copies[9].val();
            self.t2_vertices_to_operands[i].clock.next = self.clock.val();
            self.t2_vertices_to_operands[i].advance.next = self.advance_copies[10].val();
        }
        for i in 0..2 {
            self.degenerate_to_operands[i].clock.next = self.clock.val();
            self.degenerate_to_operands[i].advance.next = self.advance_copies[3].val();
            self.degenerate_to_decision[i].clock.next = self.clock.val();
            self.degenerate_to_decision[i].advance.next = self.advance_copies[6].val();
        }
        for i in 0..4 {
            self.segment_ends_to_operands[i].clock.next = self.clock.val();
            self.segment_ends_to_operands[i].advance.next = self.advance_copies[3].val();
            self.segment_ends_to_decision[i].clock.next = self.clock.val();
            self.segment_ends_to_decision[i].advance.next = self.advance_copies[6].val();
        }
        for i in 0..4 {
            self.orient_signs_to_decision[i].clock.next = self.clock.val();
            self.orient_signs_to_decision[i].advance.next = self.advance_copies[6].val();
        }
        for i in 0..12 {
            self.sides_to_decision[i].clock.next = self.clock.val();
            self.sides_to_decision[i].advance.next = self.advance_copies[6].val();
        }
        for i in 0..6 {
            self.side_certificates_to_decision[i].clock.next = self.clock.val();
            self.side_certificates_to_decision[i].advance.next = self.advance_copies[6].val();
        }

        // Input registers and the per-triangle front end.
        self.record_valid.d.next = self.in_valid.val();
        self.record_bset.d.next = self.in_bset.val();
        self.record_load.d.next = self.in_valid.val() && self.in_bset.val();
        self.record_id.d.next = self.in_id.val();
        self.input_vertices[0].d.next = self.in_x0.val();
        self.input_vertices[1].d.next = self.in_y0.val();
        self.input_vertices[2].d.next = self.in_z0.val();
        self.input_vertices[3].d.next = self.in_x1.val();
        self.input_vertices[4].d.next = self.in_y1.val();
        self.input_vertices[5].d.next = self.in_z1.val();
        self.input_vertices[6].d.next = self.in_x2.val();
        self.input_vertices[7].d.next = self.in_y2.val();
        self.input_vertices[8].d.next = self.in_z2.val();
        for i in 0..9 {
            self.front_end.vertices_in[i].next = self.input_vertices[i].q.val();
        }

        // Base polygon (thesis: BSET latches the record into its registers).
        self.base.reset.next = self.reset.val();
        self.base.advance.next = self.base_advance.val();
        self.base.hold_if_advance.next = self.base_hold_if_advance.val();
        self.base.hold_if_still.next = self.base_hold_if_still.val();
        self.base.load_ahead.next = self.record_load.q.val();
        self.base.id_in.next = self.record_id.q.val();
        self.base.degenerate_in.next = self.front_end.degenerate.val();
        self.base.dominant_axis_in.next = self.front_end.dominant_axis.val();
        self.base.segment_low_in.next = self.front_end.segment_low.val();
        self.base.segment_high_in.next = self.front_end.segment_high.val();
        self.base.edges_bits_in.next = self.front_end.edges_bits.val();
        for i in 0..9 {
            self.base.vertices_in[i].next = self.front_end.vertices[i].val();
        }
        for k in 0..3 {
            self.base.normal_in[k].next = self.front_end.normal[k].val();
            self.base.normal_negative_in[k].next = self.front_end.normal_negative[k].val();
            self.base.normal_zero_in[k].next = self.front_end.normal_zero[k].val();
        }

        // The pair: T1 = base, T2 = the streamed triangle's record.
        self.pair_valid_to_sides.d.next = self.record_valid.q.val() && !self.record_bset.q.val();
        self.pair_valid_to_out.d.next = self.pair_valid_to_sides.q.val();
        self.base_id.d.next = self.base.id.val();
        self.stream_id.d.next = self.record_id.q.val();

        // Steps (1)-(4), both sides in parallel.
        for i in 0..9 {
            self.plane_side_t1.vertices[i].next = self.base.vertices[i].val();
            self.plane_side_t2.vertices[i].next = self.front_end.vertices[i].val();
        }
        self.plane_side_t1.plane_edges_bits.next = self.front_end.edges_bits.val();
        self.plane_side_t2.plane_edges_bits.next = self.base.edges_bits.val();
        for k in 0..3 {
            self.plane_side_t1.plane_point[k].next = self.front_end.vertices[k].val();
            self.plane_side_t1.plane_normal[k].next = self.front_end.normal[k].val();
            self.plane_side_t2.plane_point[k].next = self.base.vertices[k].val();
            self.plane_side_t2.plane_normal[k].next = self.base.normal[k].val();
        }

        // Steps (5)-(7).
        for v in 0..3 {
            self.align_t1.t1_negative[v].next = self.plane_side_t1.negative[v].val();
            self.align_t1.t1_zero[v].next = self.plane_side_t1.zero[v].val();
            self.align_t1.t2_negative[v].next = self.plane_side_t2.negative[v].val();
            self.align_t1.t2_zero[v].next = self.plane_side_t2.zero[v].val();
            self.align_t2.t2_aligned_negative[v].next = self.align_t1.t2_aligned_negative[v].val();
            self.align_t2.t2_aligned_zero[v].next = self.align_t1.t2_aligned_zero[v].val();
        }
        self.align_t2.t1_rotation_in.next = self.align_t1.t1_rotation.val();
        self.align_t2.t2_swap_in.next = self.align_t1.t2_swap.val();
        self.interval_overlap.t1_rotation.next = self.align_t2.t1_rotation.val();
        self.interval_overlap.t2_swap.next = self.align_t2.t2_swap.val();
        self.interval_overlap.t2_rotation.next = self.align_t2.t2_rotation.val();
        self.interval_overlap.t1_swap.next = self.align_t2.t1_swap.val();

        // The operands of the shared orient3d units.
        for i in 0..9 {
            self.t1_vertices_to_operands[i].d.next = self.base.vertices[i].val();
            self.t2_vertices_to_operands[i].d.next = self.front_end.vertices[i].val();
            self.operands.t1_vertices[i].next = self.t1_vertices_to_operands[i].q.val();
            self.operands.t2_vertices[i].next = self.t2_vertices_to_operands[i].q.val();
        }
        self.degenerate_to_operands[0].d.next = self.base.degenerate.val();
        self.degenerate_to_operands[1].d.next = self.front_end.degenerate.val();
        self.segment_ends_to_operands[0].d.next = self.base.segment_low.val();
        self.segment_ends_to_operands[1].d.next = self.base.segment_high.val();
        self.segment_ends_to_operands[2].d.next = self.front_end.segment_low.val();
        self.segment_ends_to_operands[3].d.next = self.front_end.segment_high.val();
        self.operands.t1_degenerate.next = self.degenerate_to_operands[0].q.val();
        self.operands.t2_degenerate.next = self.degenerate_to_operands[1].q.val();
        self.operands.t1_segment_low.next = self.segment_ends_to_operands[0].q.val();
        self.operands.t1_segment_high.next = self.segment_ends_to_operands[1].q.val();
        self.operands.t2_segment_low.next = self.segment_ends_to_operands[2].q.val();
        self.operands.t2_segment_high.next = self.segment_ends_to_operands[3].q.val();
        for j in 0..4 {
            self.operands.overlap_first[j].next = self.interval_overlap.first[j].val();
            self.operands.overlap_second[j].next = self.interval_overlap.second[j].val();
        }
        for k in 0..3 {
            self.orient3d_0.a[k].next = self.operands.operands[k].val();
            self.orient3d_0.b[k].next = self.operands.operands[3 + k].val();
            self.orient3d_0.c[k].next = self.operands.operands[6 + k].val();
            self.orient3d_0.d[k].next = self.operands.operands[9 + k].val();
            self.orient3d_1.a[k].next = self.operands.operands[12 + k].val();
            self.orient3d_1.b[k].next = self.operands.operands[15 + k].val();
            self.orient3d_1.c[k].next = self.operands.operands[18 + k].val();
            self.orient3d_1.d[k].next = self.operands.operands[21 + k].val();
        }

        // The segment-triangle case's third determinant: s_b - s_a of the
        // degenerate triangle's ends beside the plane side, then that less
        // units 0 and 1's values.
        self.degenerate_to_distances.d.next = self.base.degenerate.val();
        self.segment_ends_to_distances[0].d.next = self.base.segment_low.val();
        self.segment_ends_to_distances[1].d.next = self.base.segment_high.val();
        self.segment_ends_to_distances[2].d.next = self.front_end.segment_low.val();
        self.segment_ends_to_distances[3].d.next = self.front_end.segment_high.val();
        for i in 0..4 {
            self.segment_ends_to_distances[i].clock.next = self.clock.val();
            self.segment_ends_to_distances[i].advance.next = self.advance_copies[2].val();
        }
        self.ends_difference.t1_degenerate.next = self.degenerate_to_distances.q.val();
        self.ends_difference.t1_segment_low.next = self.segment_ends_to_distances[0].q.val();
        self.ends_difference.t1_segment_high.next = self.segment_ends_to_distances[1].q.val();
        self.ends_difference.t2_segment_low.next = self.segment_ends_to_distances[2].q.val();
        self.ends_difference.t2_segment_high.next = self.segment_ends_to_distances[3].q.val();
        for v in 0..3 {
            self.ends_difference.t1_distance[v].next = self.plane_side_t1.distance[v].val();
            self.ends_difference.t2_distance[v].next = self.plane_side_t2.distance[v].val();
        }
        self.ends_difference_to_values.d.next = self.ends_difference.difference.val();
        self.third_determinant.ends_difference.next = self.ends_difference_to_values.q.val();
        self.third_determinant.first.next = self.orient3d_0.value.val();
        self.third_determinant.second.next = self.orient3d_1.value.val();

        // The pair, for the rare cases' tests: the coplanar test projects
        // along the proper triangle's axis (T1's unless T1 is degenerate).
        if self.base.degenerate.val() {
            self.pair_axis.next = self.front_end.dominant_axis.val();
        } else {
            self.pair_axis.next = self.base.dominant_axis.val();
        }
        for i in 0..9 {
            self.pair_t1_vertices[i].next = self.base.vertices[i].val();
            self.pair_t2_vertices[i].next = self.front_end.vertices[i].val();
        }
        for k in 0..3 {
            self.pair_t1_normal_negative[k].next = self.base.normal_negative[k].val();
            self.pair_t1_normal_zero[k].next = self.base.normal_zero[k].val();
            self.pair_t2_normal_negative[k].next = self.front_end.normal_negative[k].val();
            self.pair_t2_normal_zero[k].next = self.front_end.normal_zero[k].val();
        }
        self.pair_t1_degenerate.next = self.base.degenerate.val();
        self.pair_t2_degenerate.next = self.front_end.degenerate.val();
        self.pair_t1_segment_low.next = self.base.segment_low.val();
        self.pair_t1_segment_high.next = self.base.segment_high.val();
        self.pair_t2_segment_low.next = self.front_end.segment_low.val();
        self.pair_t2_segment_high.next = self.front_end.segment_high.val();
        self.sides_valid.next = self.pair_valid_to_sides.q.val();
        self.sides_t1_all_zero.next = self.plane_side_t1.all_zero.val();
        self.sides_t2_all_zero.next = self.plane_side_t2.all_zero.val();

        // The decision.
        for i in 0..2 {
            self.degenerate_to_decision[i].d.next = self.degenerate_to_operands[i].q.val();
        }
        for i in 0..4 {
            self.segment_ends_to_decision[i].d.next = self.segment_ends_to_operands[i].q.val();
        }
        for v in 0..3 {
            self.sides_to_decision[v].d.next = self.plane_side_t1.negative[v].val();
            self.sides_to_decision[3 + v].d.next = self.plane_side_t1.zero[v].val();
            self.sides_to_decision[6 + v].d.next = self.plane_side_t2.negative[v].val();
            self.sides_to_decision[9 + v].d.next = self.plane_side_t2.zero[v].val();
            self.side_certificates_to_decision[v].d.next = self.plane_side_t1.certain[v].val();
            self.side_certificates_to_decision[3 + v].d.next = self.plane_side_t2.certain[v].val();
            self.decision.t1_side_negative[v].next = self.sides_to_decision[v].q.val();
            self.decision.t1_side_zero[v].next = self.sides_to_decision[3 + v].q.val();
            self.decision.t2_side_negative[v].next = self.sides_to_decision[6 + v].q.val();
            self.decision.t2_side_zero[v].next = self.sides_to_decision[9 + v].q.val();
            self.decision.t1_side_certain[v].next = self.side_certificates_to_decision[v].q.val();
            self.decision.t2_side_certain[v].next =
                self.side_certificates_to_decision[3 + v].q.val();
        }
        self.decision.t1_degenerate.next = self.degenerate_to_decision[0].q.val();
        self.decision.t2_degenerate.next = self.degenerate_to_decision[1].q.val();
        self.decision.t1_segment_low.next = self.segment_ends_to_decision[0].q.val();
        self.decision.t1_segment_high.next = self.segment_ends_to_decision[1].q.val();
        self.decision.t2_segment_low.next = self.segment_ends_to_decision[2].q.val();
        self.decision.t2_segment_high.next = self.segment_ends_to_decision[3].q.val();
        self.orient_signs_to_decision[0].d.next = self.orient3d_0.negative.val();
        self.orient_signs_to_decision[1].d.next = self.orient3d_0.zero.val();
        self.orient_signs_to_decision[2].d.next = self.orient3d_1.negative.val();
        self.orient_signs_to_decision[3].d.next = self.orient3d_1.zero.val();
        for u in 0..2 {
            self.decision.orient_negative[u].next = self.orient_signs_to_decision[2 * u].q.val();
            self.decision.orient_zero[u].next = self.orient_signs_to_decision[2 * u + 1].q.val();
        }
        self.decision.orient_certain[0].next = self.orient3d_0.certain.val();
        self.decision.orient_certain[1].next = self.orient3d_1.certain.val();
        self.decision.orient_negative[2].next = self.third_determinant.negative.val();
        self.decision.orient_zero[2].next = self.third_determinant.zero.val();
        self.decision.coplanar_hit.next = self.coplanar_hit.val();
        self.decision.degenerate_pair_hit.next = self.degenerate_pair_hit.val();

        // Outputs.
        self.out_valid.next = self.pair_valid_to_out.q.val();
        self.out_hit.next = self.decision.hit.val();
        self.out_certain.next = self.decision.certain.val();
        self.out_base_id.next = self.base_id.q.val();
        self.out_stream_id.next = self.stream_id.q.val();
    }
}
