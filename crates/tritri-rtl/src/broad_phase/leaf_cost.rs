//! The binning unit's cost arithmetic: the cycles the collision system
//! spends on one leaf of `a` A-triangles and `b` B-triangles, its arrays
//! cut into tiles of the memory depth `D`, as the broad phase's split rule
//! counts them (`tritri_geom::scene::octree`, `Planner::leaf_cost`, with
//! the system's [`crate::system::cycle_model::overlapped_batch_cycles`]).
//!
//! A tile pair of `x >= 1` and `y >= 1` triangles costs
//! `max(x + y + 1, 1 + x + ceil(x / P) · y)`, and since `ceil(x / P) >= 1`
//! that is `f(x, y) = 1 + x + ceil(x / P) · y`. With `a = qa · D + ra` and
//! `b = qb · D + rb` the leaf costs
//! `qa qb f(D, D) + qa f(D, rb) + qb f(ra, D) + f(ra, rb)`, each term
//! present when its remainders are non-zero, and 0 when `a` or `b` is 0.
//! `D` and `P` are powers of two, so the divisions are shifts.
//!
//! Stages: split into quotients and remainders (1); the three `f` and
//! `qa · qb` (2); the products by the quotients (3); the sum (4). One query
//! per clock. A custom-Verilog primitive with an exact model evaluated at
//! clock edges, like [`crate::octree::axis_step::AxisStep`].

use rust_hdl::prelude::*;

/// Bits of a triangle count.
pub const COUNT_BITS: usize = 20;
/// Bits of a cost in cycles.
pub const COST_BITS: usize = 48;
/// Clock edges from a query to its cost.
pub const LEAF_COST_LATENCY: usize = 4;

/// The cost of a leaf with `a` and `b` triangles for memory depth
/// `2^log_depth` and `2^log_pipelines` pipelines: the closed form above.
pub fn leaf_cost(a: u64, b: u64, log_depth: u32, log_pipelines: u32) -> u64 {
    if a == 0 || b == 0 {
        return 0;
    }
    let depth = 1u64 << log_depth;
    let f = |x: u64, y: u64| 1 + x + x.div_ceil(1 << log_pipelines) * y;
    let (qa, ra, qb, rb) = (
        a >> log_depth,
        a & (depth - 1),
        b >> log_depth,
        b & (depth - 1),
    );
    let mut cost = qa * qb * f(depth, depth);
    if rb > 0 {
        cost += qa * f(depth, rb);
    }
    if ra > 0 {
        cost += qb * f(ra, depth);
    }
    if ra > 0 && rb > 0 {
        cost += f(ra, rb);
    }
    cost
}

#[derive(LogicBlock)]
pub struct LeafCost {
    pub clock: Signal<In, Clock>,
    pub a: Signal<In, Bits<COUNT_BITS>>,
    pub b: Signal<In, Bits<COUNT_BITS>>,
    /// [`leaf_cost`] of the `a`, `b` taken [`LEAF_COST_LATENCY`] edges before.
    pub cost: Signal<Out, Bits<COST_BITS>>,
    _log_depth: u32,
    _log_pipelines: u32,
    _queries: [(u64, u64); LEAF_COST_LATENCY],
}

impl crate::unit::Unit for LeafCost {
    const LATENCY: Option<usize> = Some(LEAF_COST_LATENCY);
}

impl LeafCost {
    /// For memory depth `2^log_depth` (1 to 2^16) and `2^log_pipelines`
    /// pipelines (1 to 16).
    pub fn new(log_depth: u32, log_pipelines: u32) -> Self {
        assert!(
            log_depth <= 16 && log_pipelines <= 4,
            "leaf cost for D = 2^{log_depth}, P = 2^{log_pipelines}"
        );
        LeafCost {
            clock: Default::default(),
            a: Default::default(),
            b: Default::default(),
            cost: Default::default(),
            _log_depth: log_depth,
            _log_pipelines: log_pipelines,
            _queries: [(0, 0); LEAF_COST_LATENCY],
        }
    }
}

impl Default for LeafCost {
    /// depth 256, P = 2 (the system's defaults).
    fn default() -> Self {
        LeafCost::new(8, 1)
    }
}

impl Logic for LeafCost {
    fn update(&mut self) {
        if !self.clock.pos_edge() {
            return;
        }
        // The model keeps the queries in flight and evaluates the one that
        // reaches the output register at this edge (taken three edges ago).
        self._queries.copy_within(0..LEAF_COST_LATENCY - 1, 1);
        self._queries[0] = (self.a.val().index() as u64, self.b.val().index() as u64);
        let (a, b) = self._queries[LEAF_COST_LATENCY - 1];
        self.cost.next = Bits::from(leaf_cost(a, b, self._log_depth, self._log_pipelines));
    }

    fn connect(&mut self) {
        self.cost.connect();
    }

    fn hdl(&self) -> Verilog {
        Verilog::Custom(leaf_cost_verilog(self._log_depth, self._log_pipelines))
    }
}

/// The leaf cost's Verilog body for depth `2^ld` and `2^lp` pipelines.
/// Every register is as wide as its largest value for counts below
/// 2^[`COUNT_BITS`] (worked out below), so that synthesis sees products of
/// those widths and not of the cost's 48 bits: a quotient has `COUNT_BITS
/// - ld` bits, a remainder `ld`, an `f` at most `1 + D + D^2`, so `2 ld +
/// 2` bits (given one more); the largest term, `qa qb f(D, D)`, has `2
/// (COUNT_BITS - ld) + 2 ld + 3 = 43` bits, within the cost's 48.
pub fn leaf_cost_verilog(ld: u32, lp: u32) -> String {
    let depth = 1u64 << ld;
    let per_group = depth.div_ceil(1 << lp);
    let f_dd = 1 + depth + per_group * depth;
    let c = COUNT_BITS;
    let k = COST_BITS;
    let q = COUNT_BITS - ld as usize; // quotient bits
    let r = (ld as usize).max(1); // remainder bits
    let g = r + 1; // ceil(remainder / P) bits
    let f = 2 * ld as usize + 3; // bits of an f, one spare (so g < f at D = 1)
    let qq = 2 * q; // bits of qa qb
    debug_assert!(qq + f <= k && 1u64 << f > f_dd);
    format!(
        "\
// Leaf cost for depth D = {depth}, P = {p}: f(x, y) = 1 + x + ceil(x / P) * y per tile pair.
// Each register as wide as its largest value for counts below 2^{c}.
localparam [{f1}:0] F_DD = {f}'d{f_dd};      // f(D, D)
localparam [{f1}:0] PER_GROUP = {f}'d{per_group}; // ceil(D / P)
// Stage 1: quotients, remainders, ceil(ra / P).
reg [{q1}:0] qa_1, qb_1;
reg [{r1}:0] ra_1, rb_1;
reg [{g1}:0] groups_1;
reg zero_1;
// Stage 2: qa qb and the three f.
reg [{qq1}:0] qq_2;
reg [{f1}:0] f_d_rb_2, f_ra_d_2, f_ra_rb_2;
reg [{q1}:0] qa_2, qb_2;
reg ra_2, rb_2, zero_2;
// Stage 3: the four terms.
reg [{k1}:0] t1_3, t2_3, t3_3, t4_3;
reg zero_3;
initial begin
    qa_1 = {q}'d0; qb_1 = {q}'d0; ra_1 = {r}'d0; rb_1 = {r}'d0; groups_1 = {g}'d0; zero_1 = 1'b1;
    qq_2 = {qq}'d0; f_d_rb_2 = {f}'d0; f_ra_d_2 = {f}'d0; f_ra_rb_2 = {f}'d0; qa_2 = {q}'d0; qb_2 = {q}'d0;
    ra_2 = 1'b0; rb_2 = 1'b0; zero_2 = 1'b1;
    t1_3 = {k}'d0; t2_3 = {k}'d0; t3_3 = {k}'d0; t4_3 = {k}'d0; zero_3 = 1'b1;
    cost = {k}'d0;
end
// The quotients and remainders, at the counts' width; the registers
// below take the bits their values can have, so the rest is unread.
// verilator lint_off UNUSEDSIGNAL
wire [{c1}:0] a_high = a >> {ld};
wire [{c1}:0] b_high = b >> {ld};
wire [{c1}:0] a_low = a & {c}'d{mask};
wire [{c1}:0] b_low = b & {c}'d{mask};
wire [{c1}:0] a_groups = (a_low + {c}'d{p_minus_1}) >> {lp};
// verilator lint_on UNUSEDSIGNAL
always @(posedge clock) begin
    qa_1 <= a_high[{q1}:0];
    qb_1 <= b_high[{q1}:0];
    ra_1 <= a_low[{r1}:0];
    rb_1 <= b_low[{r1}:0];
    groups_1 <= a_groups[{g1}:0];
    zero_1 <= (a == {c}'d0) || (b == {c}'d0);

    qq_2 <= {{{q}'d0, qa_1}} * {{{q}'d0, qb_1}};
    f_d_rb_2 <= {f}'d{one_plus_depth} + PER_GROUP * {{{fr}'d0, rb_1}};
    f_ra_d_2 <= {f}'d1 + {{{fr}'d0, ra_1}} + ({{{fg}'d0, groups_1}} << {ld});
    f_ra_rb_2 <= {f}'d1 + {{{fr}'d0, ra_1}} + {{{fg}'d0, groups_1}} * {{{fr}'d0, rb_1}};
    qa_2 <= qa_1;
    qb_2 <= qb_1;
    ra_2 <= ra_1 != {r}'d0;
    rb_2 <= rb_1 != {r}'d0;
    zero_2 <= zero_1;

    t1_3 <= {{{kqq}'d0, qq_2}} * {{{kf}'d0, F_DD}};
    t2_3 <= rb_2 ? {{{kq}'d0, qa_2}} * {{{kf}'d0, f_d_rb_2}} : {k}'d0;
    t3_3 <= ra_2 ? {{{kq}'d0, qb_2}} * {{{kf}'d0, f_ra_d_2}} : {k}'d0;
    t4_3 <= (ra_2 && rb_2) ? {{{kf}'d0, f_ra_rb_2}} : {k}'d0;
    zero_3 <= zero_2;

    cost <= zero_3 ? {k}'d0 : t1_3 + t2_3 + t3_3 + t4_3;
end
",
        p = 1u64 << lp,
        mask = depth - 1,
        p_minus_1 = (1u64 << lp) - 1,
        one_plus_depth = 1 + depth,
        c1 = c - 1,
        k1 = k - 1,
        q1 = q - 1,
        r1 = r - 1,
        g1 = g - 1,
        f1 = f - 1,
        qq1 = qq - 1,
        fr = f - r,
        fg = f - g,
        kqq = k - qq,
        kf = k - f,
        kq = k - q,
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::system::cycle_model::{overlapped_batch_cycles, BatchSizes};
    use crate::system::SystemConfig;

    /// The closed form equals the split rule's sum over tiles of the
    /// system's batch cost.
    #[test]
    fn closed_form_equals_the_tiled_batch_cost() {
        for (log_depth, log_pipelines) in [(2, 0), (3, 1), (4, 2), (8, 1)] {
            let depth = 1usize << log_depth;
            let mut config = SystemConfig::new(24, 1 << log_pipelines).with_pipeline_latency(30);
            config.triangles_per_bank = depth;
            let tiles = |n: usize| (0..n.div_ceil(depth)).map(move |t| (n - t * depth).min(depth));
            for a in 0..(3 * depth + 2) {
                for b in 0..(3 * depth + 2) {
                    let tiled: u64 = tiles(a)
                        .map(|ta| {
                            tiles(b)
                                .map(|tb| {
                                    overlapped_batch_cycles(config, BatchSizes { a: ta, b: tb })
                                })
                                .sum::<u64>()
                        })
                        .sum();
                    assert_eq!(
                        leaf_cost(a as u64, b as u64, log_depth, log_pipelines),
                        tiled,
                        "a {a} b {b} D {depth}"
                    );
                }
            }
        }
    }
}
