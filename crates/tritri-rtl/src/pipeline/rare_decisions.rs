//! The last stages of the two rare-case tests, from signs and coordinate
//! comparisons to the verdict: shared by the parallel units
//! ([`super::coplanar_test::CoplanarTest`],
//! [`super::degenerate_pair::DegeneratePair`]) and the time-multiplexed one
//! ([`super::shared_rare_cases::SharedRareCases`]), which differ only in
//! how they compute the orient2d signs.
//!
//! * [`CoplanarContacts`] and [`CoplanarDecision`]: `hulls_intersect_2d` in
//!   devillers_guigue.rs on one projection. The eighteen orient2d values
//!   are `[A_e, A_e+1, B_v]` at `3 e + v` and `-[B_f, B_f+1, A_u]` at
//!   `9 + 3 f + u`; the comparisons, projected coordinate `c` of `A_u`
//!   against `B_v`, at `9 c + 3 u + v`.
//! * [`SegmentContacts`] and [`SegmentsDecision`]: `degenerate_pair`'s
//!   three-projection segment test. The twelve orient2d values are
//!   component `k` of `[a, b, c]`, `[a, b, d]`, `[c, d, a]`, `[c, d, b]` at
//!   `3 i + k`; the comparisons, coordinate `k` of the pairs (a, c),
//!   (a, d), (b, c), (b, d), at `3 pair + k`.

use rust_hdl::prelude::*;
use rust_hdl::widgets::prelude::DFF;

/// Clock edges from signs to [`CoplanarDecision::hit`]: the eleven terms,
/// then their OR (in one stage, eighteen signs fanned into one register
/// through five LUT levels, 129 MHz on ECP5).
pub const COPLANAR_DECISION_LATENCY: usize = 2;
/// Clock edges from signs to [`SegmentsDecision::hit`].
pub const SEGMENTS_DECISION_LATENCY: usize = 1;
/// Terms of the coplanar decision: a crossing or touching per pair of
/// edges (`3 e + f`), B_0 inside A, A_0 inside B.
const TERMS: usize = 11;

/// Collinear touching in the coplanar test (`on_segment_2d`): a vertex
/// within an edge's bounding box on both projected coordinates. No clock.
#[derive(LogicBlock, Default)]
pub struct CoplanarContacts {
    /// `A_u < B_v` and `A_u == B_v` on projected coordinate `c`, at
    /// `9 c + 3 u + v`.
    pub less: [Signal<In, Bit>; 18],
    pub equal: [Signal<In, Bit>; 18],
    /// `B_v` on the projected edge `e` of A (`3 e + v`), when collinear.
    pub on_edge_a: [Signal<Out, Bit>; 9],
    /// `A_u` on the projected edge `f` of B (`3 f + u`), when collinear.
    pub on_edge_b: [Signal<Out, Bit>; 9],
}

impl crate::unit::Unit for CoplanarContacts {
    const LATENCY: Option<usize> = Some(0);
}

impl Logic for CoplanarContacts {
    #[hdl_gen]
    fn update(&mut self) {
        // A_u <= B_v is less || equal.
        for e in 0..3 {
            for v in 0..3 {
                // B_v on [A_e, A_e+1].
                self.on_edge_a[3 * e + v].next = (self.less[3 * e + v].val()
                    || self.equal[3 * e + v].val()
                    || self.less[3 * ((e + 1) % 3) + v].val()
                    || self.equal[3 * ((e + 1) % 3) + v].val())
                    && (!self.less[3 * e + v].val() || !self.less[3 * ((e + 1) % 3) + v].val())
                    && (self.less[9 + 3 * e + v].val()
                        || self.equal[9 + 3 * e + v].val()
                        || self.less[9 + 3 * ((e + 1) % 3) + v].val()
                        || self.equal[9 + 3 * ((e + 1) % 3) + v].val())
                    && (!self.less[9 + 3 * e + v].val()
                        || !self.less[9 + 3 * ((e + 1) % 3) + v].val());
                // f = e, u = v: A_u on [B_f, B_f+1].
                self.on_edge_b[3 * e + v].next = (!self.less[3 * v + e].val()
                    || !self.less[3 * v + (e + 1) % 3].val())
                    && (self.less[3 * v + e].val()
                        || self.equal[3 * v + e].val()
                        || self.less[3 * v + (e + 1) % 3].val()
                        || self.equal[3 * v + (e + 1) % 3].val())
                    && (!self.less[9 + 3 * v + e].val()
                        || !self.less[9 + 3 * v + (e + 1) % 3].val())
                    && (self.less[9 + 3 * v + e].val()
                        || self.equal[9 + 3 * v + e].val()
                        || self.less[9 + 3 * v + (e + 1) % 3].val()
                        || self.equal[9 + 3 * v + (e + 1) % 3].val());
            }
        }
    }
}

/// The coplanar test's verdict from its eighteen orient2d signs, the
/// collinear contacts and the two projected triangles' orientations.
#[derive(LogicBlock, Default)]
pub struct CoplanarDecision {
    pub clock: Signal<In, Clock>,
    pub advance: Signal<In, Bit>,
    pub negative: [Signal<In, Bit>; 18],
    pub zero: [Signal<In, Bit>; 18],
    /// From [`CoplanarContacts`].
    pub on_edge_a: [Signal<In, Bit>; 9],
    pub on_edge_b: [Signal<In, Bit>; 9],
    /// Orientation of A in the projection (negative, zero), then of B.
    pub orientation: [Signal<In, Bit>; 4],
    /// The closed projected hulls meet, `COPLANAR_DECISION_LATENCY` later.
    pub hit: Signal<Out, Bit>,
    positive: [Signal<Local, Bit>; 18],
    term_q: [DFF<Bit>; TERMS],
    hit_q: DFF<Bit>,
}

impl crate::unit::Unit for CoplanarDecision {
    const LATENCY: Option<usize> = Some(COPLANAR_DECISION_LATENCY);
    fn sub_units(&self, units: &mut crate::unit::UnitWalk) {
        crate::sub_units!(self, units, term_q, hit_q);
    }
}

impl Logic for CoplanarDecision {
    #[hdl_gen]
    fn update(&mut self) {
        for i in 0..18 {
            self.positive[i].next = !self.negative[i].val() && !self.zero[i].val();
        }
        // Stage 1: the terms of hulls_intersect_2d.
        for i in 0..TERMS {
            self.term_q[i].clock.next = self.clock.val();
            self.term_q[i].d.next = self.term_q[i].q.val();
        }
        if self.advance.val() {
            for e in 0..3 {
                for f in 0..3 {
                    // Proper crossing: o1, o2 strictly opposite and o3, o4
                    // strictly opposite (o3, o4 are both negated: same test);
                    // or touching: an end collinear with the other edge and
                    // on it.
                    self.term_q[3 * e + f].d.next = (((self.negative[3 * e + f].val()
                        && self.positive[3 * e + (f + 1) % 3].val())
                        || (self.positive[3 * e + f].val()
                            && self.negative[3 * e + (f + 1) % 3].val()))
                        && ((self.negative[9 + 3 * f + e].val()
                            && self.positive[9 + 3 * f + (e + 1) % 3].val())
                            || (self.positive[9 + 3 * f + e].val()
                                && self.negative[9 + 3 * f + (e + 1) % 3].val())))
                        || (self.zero[3 * e + f].val() && self.on_edge_a[3 * e + f].val())
                        || (self.zero[3 * e + (f + 1) % 3].val()
                            && self.on_edge_a[3 * e + (f + 1) % 3].val())
                        || (self.zero[9 + 3 * f + e].val() && self.on_edge_b[3 * f + e].val())
                        || (self.zero[9 + 3 * f + (e + 1) % 3].val()
                            && self.on_edge_b[3 * f + (e + 1) % 3].val());
                }
            }
            // B_0 inside A: A proper here, and B_0 on the inner side of (or
            // on) every edge.
            self.term_q[9].d.next = !self.orientation[1].val()
                && (self.zero[0].val() || (self.negative[0].val() == self.orientation[0].val()))
                && (self.zero[3].val() || (self.negative[3].val() == self.orientation[0].val()))
                && (self.zero[6].val() || (self.negative[6].val() == self.orientation[0].val()));
            // A_0 inside B (its orient2d values are negated: positive here
            // means negative there).
            self.term_q[10].d.next = !self.orientation[3].val()
                && (self.zero[9].val() || (self.positive[9].val() == self.orientation[2].val()))
                && (self.zero[12].val() || (self.positive[12].val() == self.orientation[2].val()))
                && (self.zero[15].val() || (self.positive[15].val() == self.orientation[2].val()));
        }
        // Stage 2: any term.
        dff_setup!(self, clock, hit_q);
        if self.advance.val() {
            self.hit_q.d.next = self.term_q[0].q.val()
                || self.term_q[1].q.val()
                || self.term_q[2].q.val()
                || self.term_q[3].q.val()
                || self.term_q[4].q.val()
                || self.term_q[5].q.val()
                || self.term_q[6].q.val()
                || self.term_q[7].q.val()
                || self.term_q[8].q.val()
                || self.term_q[9].q.val()
                || self.term_q[10].q.val();
        }
        self.hit.next = self.hit_q.q.val();
    }
}

/// `on_segment_2d` of the degenerate pair along one coordinate: an end
/// within the other segment's range. No clock.
#[derive(LogicBlock, Default)]
pub struct SegmentContacts {
    /// Coordinate `k` of the pairs (a, c), (a, d), (b, c), (b, d) at
    /// `3 pair + k`: first `<` second, first `==` second.
    pub less: [Signal<In, Bit>; 12],
    pub equal: [Signal<In, Bit>; 12],
    /// Along coordinate `m` (`3 i + m`): c within [a, b], d within [a, b],
    /// a within [c, d], b within [c, d].
    pub within: [Signal<Out, Bit>; 12],
}

impl crate::unit::Unit for SegmentContacts {
    const LATENCY: Option<usize> = Some(0);
}

impl Logic for SegmentContacts {
    #[hdl_gen]
    fn update(&mut self) {
        // For "c within [a, b]" with pairs (a,c) and (b,c): (a <= c or
        // b <= c) and (a >= c or b >= c).
        for m in 0..3 {
            self.within[m].next = (self.less[m].val()
                || self.equal[m].val()
                || self.less[6 + m].val()
                || self.equal[6 + m].val())
                && (!self.less[m].val() || !self.less[6 + m].val());
            self.within[3 + m].next = (self.less[3 + m].val()
                || self.equal[3 + m].val()
                || self.less[9 + m].val()
                || self.equal[9 + m].val())
                && (!self.less[3 + m].val() || !self.less[9 + m].val());
            // a within [c, d]: pairs (a,c), (a,d); c <= a is !(a < c).
            self.within[6 + m].next = (!self.less[m].val() || !self.less[3 + m].val())
                && (self.less[m].val()
                    || self.equal[m].val()
                    || self.less[3 + m].val()
                    || self.equal[3 + m].val());
            self.within[9 + m].next = (!self.less[6 + m].val() || !self.less[9 + m].val())
                && (self.less[6 + m].val()
                    || self.equal[6 + m].val()
                    || self.less[9 + m].val()
                    || self.equal[9 + m].val());
        }
    }
}

/// The degenerate pair's 2D tests in all three projections, from the
/// twelve orient2d signs and the contacts.
#[derive(LogicBlock, Default)]
pub struct SegmentsDecision {
    pub clock: Signal<In, Clock>,
    pub advance: Signal<In, Bit>,
    pub negative: [Signal<In, Bit>; 12],
    pub zero: [Signal<In, Bit>; 12],
    /// From [`SegmentContacts`].
    pub within: [Signal<In, Bit>; 12],
    /// The projections of `[a, b]` and `[c, d]` meet along all three axes,
    /// `SEGMENTS_DECISION_LATENCY` later.
    pub hit: Signal<Out, Bit>,
    positive: [Signal<Local, Bit>; 12],
    /// The 2D test per dropped axis.
    meets: [Signal<Local, Bit>; 3],
    hit_q: DFF<Bit>,
}

impl crate::unit::Unit for SegmentsDecision {
    const LATENCY: Option<usize> = Some(SEGMENTS_DECISION_LATENCY);
    fn sub_units(&self, units: &mut crate::unit::UnitWalk) {
        crate::sub_units!(self, units, hit_q);
    }
}

impl Logic for SegmentsDecision {
    #[hdl_gen]
    fn update(&mut self) {
        for i in 0..12 {
            self.positive[i].next = !self.negative[i].val() && !self.zero[i].val();
        }
        // segments_intersect_2d for each dropped axis k, whose projection
        // keeps the coordinates (k+1) % 3 and (k+2) % 3.
        for k in 0..3 {
            // The proper crossing in parentheses of its own, so that no
            // reader (or linter) has to recall that && binds tighter.
            self.meets[k].next = (((self.negative[k].val() && self.positive[3 + k].val())
                || (self.positive[k].val() && self.negative[3 + k].val()))
                && ((self.negative[6 + k].val() && self.positive[9 + k].val())
                    || (self.positive[6 + k].val() && self.negative[9 + k].val())))
                || (self.zero[k].val()
                    && self.within[(k + 1) % 3].val()
                    && self.within[(k + 2) % 3].val())
                || (self.zero[3 + k].val()
                    && self.within[3 + (k + 1) % 3].val()
                    && self.within[3 + (k + 2) % 3].val())
                || (self.zero[6 + k].val()
                    && self.within[6 + (k + 1) % 3].val()
                    && self.within[6 + (k + 2) % 3].val())
                || (self.zero[9 + k].val()
                    && self.within[9 + (k + 1) % 3].val()
                    && self.within[9 + (k + 2) % 3].val());
        }
        dff_setup!(self, clock, hit_q);
        if self.advance.val() {
            self.hit_q.d.next = self.meets[0].val() && self.meets[1].val() && self.meets[2].val();
        }
        self.hit.next = self.hit_q.q.val();
    }
}
