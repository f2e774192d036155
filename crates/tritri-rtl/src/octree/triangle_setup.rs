//! The binning unit's setup: one triangle per clock in, its thirteen test
//! functions out, ready for the classifier ([`super::cell_classifier`]) at
//! the root cell. It is where the multiplications are; below the root the
//! classifier needs only adds and shifts.
//!
//! The functions are taken relative to the root's low corner `lo`:
//! `f(p) = g · (p - lo)`, so every function is zero at the root's low
//! corner and the classifier's first entry carries no values at all. In
//! fixed positions (`tritri_geom::octree::triangle_cell::root_relative_axes`
//! is the software model, which it equals bit for bit):
//!
//! * 0–2, the axes x, y, z: interval `[min, max]` of the vertices' relative
//!   coordinates;
//! * 3, the plane: `n = e0 × e1` with `e0 = p1 - p0`, `e1 = p2 - p1`; every
//!   vertex projects to the same `n · p0`, so the interval is one point;
//! * 4–12, edge `j` (`e_j` from `p_j`, `e2 = p0 - p2`) across axis `k`:
//!   `g = e_j × u_k`. Both ends of the edge project to `g · p_j` (two
//!   products), and the opposite vertex to `g · p_j - n_k` (the triple
//!   product `(e_j × u_k) · (p_opposite - p_j) = -n_k`, the same for every
//!   edge), so the interval needs no third product.
//!
//! 27 multiplications per triangle (6 for the normal, 18 for the edges, 3
//! for the plane), against 90 for evaluating every function at every
//! vertex and at the root.
//!
//! With `grow` high every interval is then grown by `|g|_1` (one grid step
//! in every direction, `tritri_geom::octree::triangle_cell::
//! BROAD_PHASE_MARGIN`), so that two triangles that touch before
//! quantization share a leaf: 1 for the axes, `|n_x| + |n_y| + |n_z|` for
//! the plane, the two non-zero components' magnitudes of the edge's `e_j`
//! for an edge function. With `grow` low the intervals are the triangle's
//! own, for exact voxelization (`tritri_geom::octree::voxelize::surface`).
//!
//! Stages: relative coordinates and edges (1); products (2); the normal and
//! the edge starts (3); the plane's products, the opposite ends and the
//! margins (4); the plane's sum, minima and maxima, grown by the margins,
//! into the output registers (5).
//! Two's complement, each register as wide as its value needs (`SetupWidths`),
//! the outputs `V = 3G + 6` bits ([`super::value_bits`]), which hold every
//! value exactly.
//!
//! **Phases.** A setup built [`TriangleSetup::with_phases`]`(R)` takes a
//! triangle at most every `R` clocks (a lane behind a memory port that
//! brings an entry every `R` clocks) and shares stage 2's 24 products over
//! `R` clocks: `⌈24 / R⌉` multipliers, each fed group `r` of the products
//! in the `r`-th clock after stage 1 took the triangle. Stage 1 then holds
//! its triangle until the next `in_valid`, and the output registers hold
//! theirs until the next triangle's, so a phased consumer can read them
//! over `R` clocks. Latency [`setup_latency`]`(R)`: `R - 1` more clocks.
//!
//! A custom-Verilog primitive with an exact i128 model evaluated only at
//! clock edges, like [`super::axis_step::AxisStep`]. The outputs are packed:
//! function `i`'s field is bits `[i V +: V]` of each bus.

use super::cell_classifier::{AXES, TAG_BITS};
use tritri_geom::octree::triangle_cell::BROAD_PHASE_MARGIN;

// The Verilog grows each interval by |g|_1 itself: one step.
const _: () = assert!(BROAD_PHASE_MARGIN == 1);
use crate::arith::convert::{to_i128, wrap_i128};
use rust_hdl::core::bitvec::BitVec;
use rust_hdl::prelude::*;

/// Clock edges from a triangle to its functions.
pub const TRIANGLE_SETUP_LATENCY: usize = 5;

/// Stage 2's products: three pairs for the normal, nine pairs for the edge
/// starts.
pub const SETUP_PRODUCTS: usize = 24;

/// Clock edges from a triangle to its functions in a setup whose products
/// are shared over `phases` clocks (module docs, "Phases").
pub const fn setup_latency(phases: usize) -> usize {
    TRIANGLE_SETUP_LATENCY + phases - 1
}

#[derive(LogicBlock)]
pub struct TriangleSetup<const G: usize, const V: usize, const N: usize> {
    pub clock: Signal<In, Clock>,
    /// Synchronous reset, active high: clears the valid bits.
    pub reset: Signal<In, Bit>,
    pub advance: Signal<In, Bit>,
    pub in_valid: Signal<In, Bit>,
    pub in_tag: Signal<In, Bits<TAG_BITS>>,
    /// The triangle's vertices, G-bit two's complement grid coordinates.
    pub in_x0: Signal<In, Bits<G>>,
    pub in_y0: Signal<In, Bits<G>>,
    pub in_z0: Signal<In, Bits<G>>,
    pub in_x1: Signal<In, Bits<G>>,
    pub in_y1: Signal<In, Bits<G>>,
    pub in_z1: Signal<In, Bits<G>>,
    pub in_x2: Signal<In, Bits<G>>,
    pub in_y2: Signal<In, Bits<G>>,
    pub in_z2: Signal<In, Bits<G>>,
    /// The root cell's low corner.
    pub in_root_x: Signal<In, Bits<G>>,
    pub in_root_y: Signal<In, Bits<G>>,
    pub in_root_z: Signal<In, Bits<G>>,
    /// Grow every interval by one grid step (the broad phase); low: the
    /// triangle's exact intervals (voxelization). Held constant.
    pub grow: Signal<In, Bit>,
    pub out_valid: Signal<Out, Bit>,
    pub out_tag: Signal<Out, Bits<TAG_BITS>>,
    /// Function `i`'s gradient, interval ends: bits `[i V +: V]`.
    pub out_gradient_x: Signal<Out, Bits<N>>,
    pub out_gradient_y: Signal<Out, Bits<N>>,
    pub out_gradient_z: Signal<Out, Bits<N>>,
    pub out_low: Signal<Out, Bits<N>>,
    pub out_high: Signal<Out, Bits<N>>,
    _stages: [Stage; TRIANGLE_SETUP_LATENCY],
    /// Stage 1's triangle in each of its product phases after the first
    /// (module docs, "Phases"): `phases - 1` records between stage 1 and
    /// stage 2.
    _waiting: Vec<Stage>,
}

impl<const G: usize, const V: usize, const N: usize> crate::unit::Unit for TriangleSetup<G, V, N> {
    const LATENCY: Option<usize> = Some(TRIANGLE_SETUP_LATENCY);
    fn latency(&self) -> Option<usize> {
        Some(setup_latency(self.phases()))
    }
    fn settings(&self) -> Vec<(&'static str, String)> {
        // A setup of one phase keeps the module name it always had.
        if self.phases() == 1 {
            Vec::new()
        } else {
            vec![("phases", self.phases().to_string())]
        }
    }
}

impl<const G: usize, const V: usize, const N: usize> TriangleSetup<G, V, N> {
    /// A setup taking a triangle at most every `phases` clocks, its products
    /// shared over them (module docs, "Phases").
    pub fn with_phases(phases: usize) -> Self {
        assert!(
            (1..=SETUP_PRODUCTS).contains(&phases),
            "a setup shares its products over 1 to {SETUP_PRODUCTS} clocks, not {phases}"
        );
        Self {
            _waiting: vec![Stage::default(); phases - 1],
            ..Self::default()
        }
    }

    /// Clocks a triangle's products are shared over.
    pub fn phases(&self) -> usize {
        self._waiting.len() + 1
    }
}

/// What one pipeline stage holds (the model keeps every stage's values in
/// one shape; each stage fills the fields it has computed).
#[derive(Clone, Copy, Default)]
struct Stage {
    valid: bool,
    tag: u64,
    /// Relative vertices, edges.
    p: [[i128; 3]; 3],
    e: [[i128; 3]; 3],
    normal: [i128; 3],
    /// Edge `j` across axis `k` at `3 j + k`: the edge's projection, the
    /// opposite vertex's.
    start: [i128; 9],
    opposite: [i128; 9],
    plane: i128,
}

impl<const G: usize, const V: usize, const N: usize> Default for TriangleSetup<G, V, N> {
    fn default() -> Self {
        assert!(
            V == super::value_bits(G) && N == AXES * V && V <= 127,
            "setup for G = {G}: V = {V}, N = {N}"
        );
        Self {
            clock: Default::default(),
            reset: Default::default(),
            advance: Default::default(),
            in_valid: Default::default(),
            in_tag: Default::default(),
            in_x0: Default::default(),
            in_y0: Default::default(),
            in_z0: Default::default(),
            in_x1: Default::default(),
            in_y1: Default::default(),
            in_z1: Default::default(),
            in_x2: Default::default(),
            in_y2: Default::default(),
            in_z2: Default::default(),
            in_root_x: Default::default(),
            in_root_y: Default::default(),
            in_root_z: Default::default(),
            grow: Default::default(),
            out_valid: Default::default(),
            out_tag: Default::default(),
            out_gradient_x: Default::default(),
            out_gradient_y: Default::default(),
            out_gradient_z: Default::default(),
            out_low: Default::default(),
            out_high: Default::default(),
            _stages: [Stage::default(); TRIANGLE_SETUP_LATENCY],
            _waiting: Vec::new(),
        }
    }
}

/// `e × u_k` for axis `k`.
pub fn edge_gradient(e: [i128; 3], k: usize) -> [i128; 3] {
    match k {
        0 => [0, e[2], -e[1]],
        1 => [-e[2], 0, e[0]],
        _ => [e[1], -e[0], 0],
    }
}

/// The thirteen `(gradient, low, high)` of a stage-4 record, each interval
/// grown by `|g|_1` when `grow`: what the output registers take.
fn functions(s: &Stage, v: usize, grow: bool) -> [([i128; 3], i128, i128); AXES] {
    let w = |x: i128| wrap_i128(x, v);
    let l1 = |g: [i128; 3]| {
        if grow {
            w(g.iter().map(|x| x.abs()).sum())
        } else {
            0
        }
    };
    let mut out = [([0i128; 3], 0i128, 0i128); AXES];
    for (k, f) in out.iter_mut().take(3).enumerate() {
        let coordinates = s.p.map(|p| p[k]);
        let unit = [0, 1, 2].map(|j| i128::from(j == k));
        *f = (
            unit,
            w(coordinates.into_iter().min().unwrap_or(0) - l1(unit)),
            w(coordinates.into_iter().max().unwrap_or(0) + l1(unit)),
        );
    }
    out[3] = (
        s.normal,
        w(s.plane - l1(s.normal)),
        w(s.plane + l1(s.normal)),
    );
    for j in 0..3 {
        for k in 0..3 {
            let (a, b) = (s.start[3 * j + k], s.opposite[3 * j + k]);
            let g = edge_gradient(s.e[j], k).map(w);
            out[4 + 3 * j + k] = (g, w(a.min(b) - l1(g)), w(a.max(b) + l1(g)));
        }
    }
    out
}

/// Packs `AXES` values of `v` bits into one bus, value `i` at `[i v +: v]`.
fn pack<const N: usize>(values: [i128; AXES], v: usize) -> Bits<N> {
    let mut bits = [false; N];
    for (i, value) in values.iter().enumerate() {
        for b in 0..v {
            bits[i * v + b] = (value >> b) & 1 == 1;
        }
    }
    Bits::Long(BitVec::from(bits))
}

impl<const G: usize, const V: usize, const N: usize> Logic for TriangleSetup<G, V, N> {
    fn update(&mut self) {
        if !self.clock.pos_edge() {
            return;
        }
        if self.advance.val() {
            let w = |x: i128| wrap_i128(x, V);
            let [s1, s2, s3, s4, _] = self._stages;
            // Stage 5: the outputs.
            let f = functions(&s4, V, self.grow.val());
            let next5 = Stage {
                plane: w(s4.plane),
                ..s4
            };
            // Stage 4: the plane's products (summed here, as the Verilog
            // sums them into the output) and the opposite ends.
            let plane = w((0..3).map(|k| w(s3.normal[k] * s3.p[0][k])).sum());
            let opposite = std::array::from_fn(|i| w(s3.start[i] - s3.normal[i % 3]));
            let next4 = Stage {
                plane,
                opposite,
                ..s3
            };
            // Stages 2 and 3: products, then differences (one step in the
            // model: the products are exact in i128).
            let e = s2.e;
            let normal = [0, 1, 2].map(|k| {
                let (a, b) = ((k + 1) % 3, (k + 2) % 3);
                w(w(e[0][a] * e[1][b]) - w(e[0][b] * e[1][a]))
            });
            let start = std::array::from_fn(|i| {
                let (j, k) = (i / 3, i % 3);
                let g = edge_gradient(e[j], k);
                w((0..3).map(|c| w(g[c] * s2.p[j][c])).sum())
            });
            let next3 = Stage {
                normal,
                start,
                ..s2
            };
            // A phased setup's triangle waits in stage 1 for its product
            // phases (the Verilog's ph_1 ...), then enters stage 2.
            self._waiting.insert(0, s1);
            let next2 = self._waiting.pop().expect("one record more than waiting");
            // Stage 1: relative coordinates and edges.
            let v = [
                [&self.in_x0, &self.in_y0, &self.in_z0].map(|x| to_i128(x.val())),
                [&self.in_x1, &self.in_y1, &self.in_z1].map(|x| to_i128(x.val())),
                [&self.in_x2, &self.in_y2, &self.in_z2].map(|x| to_i128(x.val())),
            ];
            let root =
                [&self.in_root_x, &self.in_root_y, &self.in_root_z].map(|x| to_i128(x.val()));
            let p = v.map(|q| [0, 1, 2].map(|k| w(q[k] - root[k])));
            let edge = |a: usize, b: usize| [0, 1, 2].map(|k| w(v[b][k] - v[a][k]));
            let next1 = if self.phases() > 1 && !self.in_valid.val() {
                // A phased stage 1 holds its triangle for the phases.
                Stage { valid: false, ..s1 }
            } else {
                Stage {
                    valid: self.in_valid.val(),
                    tag: self.in_tag.val().index() as u64,
                    p,
                    e: [edge(0, 1), edge(1, 2), edge(2, 0)],
                    ..Stage::default()
                }
            };
            self._stages = [next1, next2, next3, next4, next5];
            // A phased setup's outputs hold until the next triangle's.
            if self.phases() == 1 || s4.valid {
                self.out_gradient_x.next = pack(f.map(|a| a.0[0]), V);
                self.out_gradient_y.next = pack(f.map(|a| a.0[1]), V);
                self.out_gradient_z.next = pack(f.map(|a| a.0[2]), V);
                self.out_low.next = pack(f.map(|a| a.1), V);
                self.out_high.next = pack(f.map(|a| a.2), V);
                self.out_tag.next = Bits::from(s4.tag);
            }
        }
        if self.reset.val() {
            for s in self._stages.iter_mut().chain(self._waiting.iter_mut()) {
                s.valid = false;
            }
        }
        self.out_valid.next = self._stages[TRIANGLE_SETUP_LATENCY - 1].valid;
    }

    fn connect(&mut self) {
        self.out_valid.connect();
        self.out_tag.connect();
        self.out_gradient_x.connect();
        self.out_gradient_y.connect();
        self.out_gradient_z.connect();
        self.out_low.connect();
        self.out_high.connect();
    }

    fn hdl(&self) -> Verilog {
        Verilog::Custom(setup_verilog(G, V, self.phases()))
    }
}

/// Register widths per stage of the setup's Verilog, for `g`-bit signed
/// inputs, each the smallest that holds its value exactly (the bounds are
/// on magnitudes, with `2^g - 1` for a difference of two inputs). Without
/// them every register would be `V` bits wide and Yosys, which narrows a
/// multiplier only from what drives it, cannot see through a register that
/// its top bits are sign copies: the lane inside the DRAM binning
/// controller took 162 MULT18X18D; at these widths it takes 30 at G = 16
/// (docs/axi-port.md).
struct SetupWidths {
    /// `p_i`, `e_j`: a difference of two inputs, `< 2^g`.
    difference: usize,
    /// One product of two differences, `< 2^(2g)`.
    product: usize,
    /// `n_k`, the edge starts: a difference of two products, `< 2^(2g+1)`.
    normal: usize,
    /// The opposite ends `s - n_k`, `< 2^(2g+2)`.
    opposite: usize,
    /// The plane's products `n_k p0_k`, `< 2^(3g+1)`.
    plane: usize,
    /// `|n|_1 < 3 * 2^(2g+1)`.
    plane_margin: usize,
    /// `|e_a| + |e_b| < 2^(g+1)`.
    edge_margin: usize,
}

impl SetupWidths {
    fn new(g: usize) -> Self {
        Self {
            difference: g + 1,
            product: 2 * g + 1,
            normal: 2 * g + 2,
            opposite: 2 * g + 3,
            plane: 3 * g + 2,
            plane_margin: 2 * g + 4,
            edge_margin: g + 2,
        }
    }
}

/// `x`, a `from`-bit signed register, sign-extended to `to` bits, so that
/// every operand of an expression has the expression's width (Verilator's
/// WIDTH lint) and a `$unsigned` never evaluates at a narrower one.
fn sign_extend(x: &str, from: usize, to: usize) -> String {
    assert!(from <= to, "{x}: {from} bits into {to}");
    if from == to {
        x.to_string()
    } else {
        format!("$signed({{{{{}{{{x}[{}]}}}}, {x}}})", to - from, from - 1)
    }
}

/// The Verilog of the setup (module docs), for `g`-bit grids and `v`-bit
/// values, its products shared over `phases` clocks.
fn setup_verilog(g: usize, v: usize, phases: usize) -> String {
    let phased = phases > 1;
    let v1 = v - 1;
    let wd = SetupWidths::new(g);
    assert!(wd.plane + 2 < v, "the plane's sum of three products fits V");
    let mut text = String::new();
    let mut line = |s: String| {
        text.push_str(&s);
        text.push('\n');
    };
    let xyz = ["x", "y", "z"];
    let regs = |bits: usize, names: Vec<String>| {
        format!("reg signed [{}:0] {};", bits - 1, names.join(", "))
    };
    let per = |stage: usize, what: &str, n: usize| {
        (0..n)
            .map(|i| format!("{what}{i}_{stage}"))
            .collect::<Vec<_>>()
    };
    let per_from = |stage: usize, what: &str, from: usize, n: usize| {
        (from..from + n)
            .map(|i| format!("{what}{i}_{stage}"))
            .collect::<Vec<_>>()
    };
    let coords = |stage: usize, what: &str| {
        (0..3)
            .flat_map(|i| xyz.map(|c| format!("{what}{i}{c}_{stage}")))
            .collect::<Vec<_>>()
    };
    let points = |stage: usize| [coords(stage, "p"), coords(stage, "e")].concat();
    line("// Register widths per stage: the smallest that hold each value exactly.".into());
    line("// Stage 1: p_i = v_i - root, e_j = v_{j+1} - v_j.".into());
    line(regs(wd.difference, points(1)));
    line("// Stage 2: the products of the normal and of the edge starts.".into());
    line(regs(
        wd.product,
        [
            per(2, "na", 3),
            per(2, "nb", 3),
            per(2, "sa", 9),
            per(2, "sb", 9),
        ]
        .concat(),
    ));
    line(regs(wd.difference, points(2)));
    line("// Stage 3: the normal and the edge starts.".into());
    line(regs(wd.normal, [per(3, "n", 3), per(3, "s", 9)].concat()));
    line(regs(wd.difference, points(3)));
    line("// Stage 4: the plane's products, the opposite ends, the margins |g|_1.".into());
    line(regs(wd.plane, per(4, "pl", 3)));
    line(regs(wd.normal, [per(4, "n", 3), per(4, "s", 9)].concat()));
    line(regs(wd.opposite, per(4, "o", 9)));
    line(regs(wd.plane_margin, per(4, "m", 1)));
    line(regs(wd.edge_margin, per_from(4, "m", 1, 9)));
    line(regs(wd.difference, points(4)));
    line(format!(
        "reg [{}:0] tag_1, tag_2, tag_3, tag_4;",
        TAG_BITS - 1
    ));
    line("reg valid_1, valid_2, valid_3, valid_4;".into());
    // Stage 2's products, `(register, [operand, operand])`: n_k = e0_a e1_b -
    // e0_b e1_a with (a, b) = (k+1, k+2) mod 3; edge j across axis k: g =
    // e_j × u_k, start = g · p_j as two products (x: e_z p_y - e_y p_z; y:
    // e_x p_z - e_z p_x; z: e_y p_x - e_x p_y).
    let mut products = Vec::with_capacity(SETUP_PRODUCTS);
    for k in 0..3 {
        let (a, b) = (xyz[(k + 1) % 3], xyz[(k + 2) % 3]);
        products.push((format!("na{k}_2"), [format!("e0{a}_1"), format!("e1{b}_1")]));
        products.push((format!("nb{k}_2"), [format!("e0{b}_1"), format!("e1{a}_1")]));
    }
    for j in 0..3 {
        for k in 0..3 {
            let (a, b) = (xyz[(k + 2) % 3], xyz[(k + 1) % 3]);
            let i = 3 * j + k;
            products.push((
                format!("sa{i}_2"),
                [format!("e{j}{a}_1"), format!("p{j}{b}_1")],
            ));
            products.push((
                format!("sb{i}_2"),
                [format!("e{j}{b}_1"), format!("p{j}{a}_1")],
            ));
        }
    }
    assert_eq!(products.len(), SETUP_PRODUCTS);
    let difference = |x: String| sign_extend(&x, wd.difference, wd.product);
    let product = |a: &str, b: &str| {
        format!(
            "{} * {}",
            difference(a.to_string()),
            difference(b.to_string())
        )
    };
    // Phased: multiplier m computes product r M + m in phase r; ph_r is
    // high in the r-th clock after stage 1 took a triangle (phase 0 is
    // valid_1). Each operand is chosen at the differences' width and
    // widened after, so that Yosys still sees a narrow multiplier.
    let multipliers = SETUP_PRODUCTS.div_ceil(phases);
    let phase = |r: usize| {
        if r == 0 {
            "valid_1".to_string()
        } else {
            format!("ph_{r}")
        }
    };
    if phased {
        line(format!(
            "// Stage 2 shares its {SETUP_PRODUCTS} products over {phases} clocks: {multipliers} multipliers."
        ));
        line(format!(
            "reg {};",
            (1..phases).map(phase).collect::<Vec<_>>().join(", ")
        ));
        for m in 0..multipliers {
            for (pick, side) in ["a", "b"].into_iter().enumerate() {
                let operand = |r: usize| products[r * multipliers + m].1[pick].clone();
                let mut choice = operand(0);
                for r in 1..phases {
                    if r * multipliers + m < SETUP_PRODUCTS {
                        choice = format!("{} ? {} : {choice}", phase(r), operand(r));
                    }
                }
                line(format!(
                    "wire signed [{}:0] mul_{side}{m} = {choice};",
                    wd.difference - 1
                ));
            }
            line(format!(
                "wire signed [{}:0] mul{m} = {};",
                wd.product - 1,
                product(&format!("mul_a{m}"), &format!("mul_b{m}"))
            ));
        }
    }
    let last_phase = phase(phases - 1);
    line("always @(posedge clock) begin".into());
    line("    if (reset) begin".into());
    let phases_off: String = (1..phases).map(|r| format!(" ph_{r} <= 1'b0;")).collect();
    line(format!("        valid_1 <= 1'b0; valid_2 <= 1'b0; valid_3 <= 1'b0; valid_4 <= 1'b0; out_valid <= 1'b0;{phases_off}"));
    line("    end else if (advance) begin".into());
    let phases_on: String = (1..phases)
        .map(|r| format!(" ph_{r} <= {};", phase(r - 1)))
        .collect();
    line(format!("        valid_1 <= in_valid; valid_2 <= {last_phase}; valid_3 <= valid_2; valid_4 <= valid_3; out_valid <= valid_4;{phases_on}"));
    line("    end".into());
    line("    if (advance) begin".into());
    if phased {
        // Stage 1 and the outputs hold their triangle (module docs).
        line("        tag_2 <= tag_1; tag_3 <= tag_2; tag_4 <= tag_3;".into());
        line("        if (valid_4) out_tag <= tag_4;".into());
        line("        if (in_valid) begin".into());
        line("        tag_1 <= in_tag;".into());
    } else {
        line("        tag_1 <= in_tag; tag_2 <= tag_1; tag_3 <= tag_2; tag_4 <= tag_3; out_tag <= tag_4;".into());
    }
    let input = |port: String| sign_extend(&port, g, wd.difference);
    for i in 0..3 {
        for c in xyz {
            line(format!(
                "        p{i}{c}_1 <= {} - {};",
                input(format!("in_{c}{i}")),
                input(format!("in_root_{c}"))
            ));
            let next = (i + 1) % 3;
            line(format!(
                "        e{i}{c}_1 <= {} - {};",
                input(format!("in_{c}{next}")),
                input(format!("in_{c}{i}"))
            ));
        }
    }
    if phased {
        line("        end".into());
        // Stage 2: product group r from the multipliers in phase r.
        for r in 0..phases {
            line(format!("        if ({}) begin", phase(r)));
            for m in 0..multipliers {
                if let Some((register, _)) = products.get(r * multipliers + m) {
                    line(format!("            {register} <= mul{m};"));
                }
            }
            line("        end".into());
        }
    } else {
        for (register, [a, b]) in &products {
            line(format!("        {register} <= {};", product(a, b)));
        }
    }
    let pass = |line: &mut dyn FnMut(String), from: usize, to: usize| {
        for i in 0..3 {
            for c in xyz {
                line(format!("        p{i}{c}_{to} <= p{i}{c}_{from};"));
                line(format!("        e{i}{c}_{to} <= e{i}{c}_{from};"));
            }
        }
    };
    pass(&mut line, 1, 2);
    let of_products = |x: String| sign_extend(&x, wd.product, wd.normal);
    for k in 0..3 {
        line(format!(
            "        n{k}_3 <= {} - {};",
            of_products(format!("na{k}_2")),
            of_products(format!("nb{k}_2"))
        ));
    }
    for i in 0..9 {
        line(format!(
            "        s{i}_3 <= {} - {};",
            of_products(format!("sa{i}_2")),
            of_products(format!("sb{i}_2"))
        ));
    }
    pass(&mut line, 2, 3);
    for k in 0..3 {
        line(format!(
            "        pl{k}_4 <= {} * {};",
            sign_extend(&format!("n{k}_3"), wd.normal, wd.plane),
            sign_extend(&format!("p0{}_3", xyz[k]), wd.difference, wd.plane)
        ));
        line(format!("        n{k}_4 <= n{k}_3;"));
    }
    for i in 0..9 {
        line(format!("        s{i}_4 <= s{i}_3;"));
        line(format!(
            "        o{i}_4 <= {} - {};",
            sign_extend(&format!("s{i}_3"), wd.normal, wd.opposite),
            sign_extend(&format!("n{}_3", i % 3), wd.normal, wd.opposite)
        ));
    }
    // Margins: m0 = |n|_1 (the plane); m(1 + 3j + k) = |e_j| over the two
    // axes other than k (the edge function's gradient e_j x u_k). Each
    // operand is widened first, so that negating the most negative value
    // cannot overflow.
    let abs = |x: String, bits: usize| format!("(({x} < {bits}'sd0) ? -{x} : {x})");
    let plane_term = |k: usize| {
        let n = sign_extend(&format!("n{k}_3"), wd.normal, wd.plane_margin);
        abs(n, wd.plane_margin)
    };
    line(format!(
        "        m0_4 <= {} + {} + {};",
        plane_term(0),
        plane_term(1),
        plane_term(2)
    ));
    for j in 0..3 {
        for k in 0..3 {
            let (a, b) = (xyz[(k + 1) % 3], xyz[(k + 2) % 3]);
            let term = |c: &str| {
                let e = sign_extend(&format!("e{j}{c}_3"), wd.difference, wd.edge_margin);
                abs(e, wd.edge_margin)
            };
            line(format!(
                "        m{}_4 <= {} + {};",
                1 + 3 * j + k,
                term(a),
                term(b)
            ));
        }
    }
    pass(&mut line, 3, 4);
    // Stage 5: the packed outputs, function i at [i V +: V], every operand
    // widened to V. The margins apply only while `grow` is high.
    let at_v = |name: String, bits: usize| sign_extend(&name, bits, v);
    let one = format!("(grow ? {v}'sd1 : {v}'sd0)");
    let margin = |i: usize| {
        let bits = if i == 0 {
            wd.plane_margin
        } else {
            wd.edge_margin
        };
        format!("(grow ? {} : {v}'sd0)", at_v(format!("m{i}_4"), bits))
    };
    let min = |a: &str, b: &str| format!("(({a} < {b}) ? {a} : {b})");
    let max = |a: &str, b: &str| format!("(({a} < {b}) ? {b} : {a})");
    let mut gradient: [Vec<String>; 3] = Default::default();
    let (mut low, mut high) = (Vec::new(), Vec::new());
    for (k, c) in xyz.iter().enumerate() {
        for (d, g) in gradient.iter_mut().enumerate() {
            g.push(format!("{v}'sd{}", u8::from(d == k)));
        }
        let [c0, c1, c2] = [0, 1, 2].map(|i| at_v(format!("p{i}{c}_4"), wd.difference));
        low.push(format!("{} - {one}", min(&min(&c0, &c1), &c2)));
        high.push(format!("{} + {one}", max(&max(&c0, &c1), &c2)));
    }
    for (k, g) in gradient.iter_mut().enumerate() {
        g.push(at_v(format!("n{k}_4"), wd.normal));
    }
    let plane = (0..3)
        .map(|k| at_v(format!("pl{k}_4"), wd.plane))
        .collect::<Vec<_>>()
        .join(" + ");
    low.push(format!("{plane} - {}", margin(0)));
    high.push(format!("{plane} + {}", margin(0)));
    for j in 0..3 {
        for k in 0..3 {
            let e = |c: usize| at_v(format!("e{j}{}_4", xyz[c]), wd.difference);
            let zero = format!("{v}'sd0");
            let g = match k {
                0 => [zero.clone(), e(2), format!("-{}", e(1))],
                1 => [format!("-{}", e(2)), zero.clone(), e(0)],
                _ => [e(1), format!("-{}", e(0)), zero.clone()],
            };
            for (d, component) in g.into_iter().enumerate() {
                gradient[d].push(component);
            }
            let i = 3 * j + k;
            let start = at_v(format!("s{i}_4"), wd.normal);
            let opposite = at_v(format!("o{i}_4"), wd.opposite);
            low.push(format!("{} - {}", min(&start, &opposite), margin(i + 1)));
            high.push(format!("{} + {}", max(&start, &opposite), margin(i + 1)));
        }
    }
    // Each field is a V-bit signed expression written into its slice.
    if phased {
        line("        if (valid_4) begin".into());
    }
    for (name, fields) in [
        ("out_gradient_x", &gradient[0]),
        ("out_gradient_y", &gradient[1]),
        ("out_gradient_z", &gradient[2]),
        ("out_low", &low),
        ("out_high", &high),
    ] {
        for (i, f) in fields.iter().enumerate() {
            line(format!(
                "        {name}[{}:{}] <= $unsigned({f});",
                i * v + v1,
                i * v
            ));
        }
    }
    if phased {
        line("        end".into());
    }
    line("    end".into());
    line("end".into());
    text
}
