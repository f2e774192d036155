//! The cone-of-normals test in hardware: one patch and eye point a clock,
//! the answer culled (back-facing), front-facing, or possibly holding a
//! silhouette, bit for bit the exact fixed-point model
//! `tritri_geom::bezier::cone_fixed::facing` (its module docs give the test
//! and why it is conservative).
//!
//! Stages, all sixteen control points side by side, every value `L = 2W +
//! 68`-bit two's complement (enough for every product, so nothing wraps):
//! `d = c - e` and `|a|²` (1); `p = a · d`, `|d|²` and `S |a|²` (2);
//! `p² 2^F` against `S |a|² |d|²`, and the sign of `p` (3); the sixteen
//! answers ANDed into the class (4). Eight multiplications per control
//! point and four for the cone: 132 in all, one patch a clock.
//!
//! A custom-Verilog primitive whose Rust model evaluates the fixed-point
//! model at the clock edge and delays the answer, like
//! [`crate::octree::triangle_setup::TriangleSetup`].

use crate::arith::convert::to_i128;
use rust_hdl::prelude::*;
use tritri_geom::bezier::cone_fixed::{
    facing, FixedCone, AXIS_BITS, EYE_EXTRA_BITS, THRESHOLD_BITS, THRESHOLD_FRACTION_BITS,
};
use tritri_geom::bezier::fixed::FixedNet;

/// Clock edges from a patch to its class.
pub const CONE_UNIT_LATENCY: usize = 4;

/// Bits of the tag carried alongside.
pub const CONE_TAG_BITS: usize = 16;

/// Coordinate widths `W` the unit is built for (the tessellator's).
pub const CONE_UNIT_WIDTHS: [usize; 2] = [16, 24];

/// The bits of the `in_eye` port: three coordinates of `W + 4` bits.
pub const fn eye_bits(w: usize) -> usize {
    3 * (w + EYE_EXTRA_BITS)
}

/// `$run::<W, NET, EYE>($args...)` for the unit built for `$w`, as `Some`,
/// or `None`: the one place that turns [`CONE_UNIT_WIDTHS`] into const
/// parameters.
#[macro_export]
macro_rules! with_cone_unit {
    ($w:expr, $run:ident($($arg:expr),*)) => {{
        use $crate::bezier::cone_unit::eye_bits;
        use $crate::bezier::patch_tessellator::net_bits;
        match $w {
            16 => Some($run::<16, { net_bits(16) }, { eye_bits(16) }>($($arg),*)),
            24 => Some($run::<24, { net_bits(24) }, { eye_bits(24) }>($($arg),*)),
            _ => None,
        }
    }};
}

#[derive(LogicBlock)]
pub struct ConeUnit<const W: usize, const NET: usize, const EYE: usize> {
    pub clock: Signal<In, Clock>,
    /// Synchronous reset, active high: clears the valid bits.
    pub reset: Signal<In, Bit>,
    pub advance: Signal<In, Bit>,
    pub in_valid: Signal<In, Bit>,
    pub in_tag: Signal<In, Bits<CONE_TAG_BITS>>,
    /// The control points, W-bit two's complement: coordinate `axis` of the
    /// point in row `r` and column `c` at bits `[(3 (4 r + c) + axis) W +:
    /// W]` (the tessellator's layout).
    pub in_net: Signal<In, Bits<NET>>,
    /// The eye, `W + 4`-bit two's complement per coordinate, on the net's
    /// grid: coordinate `k` at bits `[k (W + 4) +: W + 4]`.
    pub in_eye: Signal<In, Bits<EYE>>,
    /// The cone's axis, 16-bit two's complement per component.
    pub in_axis: Signal<In, Bits<48>>,
    /// The cone's threshold `S`, unsigned.
    pub in_threshold: Signal<In, Bits<THRESHOLD_BITS>>,
    pub out_valid: Signal<Out, Bit>,
    pub out_tag: Signal<Out, Bits<CONE_TAG_BITS>>,
    /// 0: front-facing, 1: back-facing (culled), 2: may hold a silhouette.
    pub out_class: Signal<Out, Bits<2>>,
    _stages: [(bool, u64, u64); CONE_UNIT_LATENCY],
}

impl<const W: usize, const NET: usize, const EYE: usize> crate::unit::Unit
    for ConeUnit<W, NET, EYE>
{
    const LATENCY: Option<usize> = Some(CONE_UNIT_LATENCY);
}

impl<const W: usize, const NET: usize, const EYE: usize> Default for ConeUnit<W, NET, EYE> {
    fn default() -> Self {
        assert!(
            NET == 48 * W && EYE == eye_bits(W) && AXIS_BITS == 16,
            "cone unit for W = {W}"
        );
        ConeUnit {
            clock: Default::default(),
            reset: Default::default(),
            advance: Default::default(),
            in_valid: Default::default(),
            in_tag: Default::default(),
            in_net: Default::default(),
            in_eye: Default::default(),
            in_axis: Default::default(),
            in_threshold: Default::default(),
            out_valid: Default::default(),
            out_tag: Default::default(),
            out_class: Default::default(),
            _stages: [(false, 0, 0); CONE_UNIT_LATENCY],
        }
    }
}

impl<const W: usize, const NET: usize, const EYE: usize> ConeUnit<W, NET, EYE> {
    /// The inputs as the fixed-point model's.
    fn inputs(&self) -> (FixedNet, [i64; 3], FixedCone) {
        let net_bits = self.in_net.val();
        let eye_bits = self.in_eye.val();
        let axis_bits = self.in_axis.val();
        let net = std::array::from_fn(|r| {
            std::array::from_fn(|c| {
                std::array::from_fn(|k| {
                    to_i128(net_bits.get_bits::<W>((3 * (4 * r + c) + k) * W)) as i64
                })
            })
        });
        let e = W + EYE_EXTRA_BITS;
        let eye = std::array::from_fn(|k| {
            let raw = (0..e)
                .filter(|&b| eye_bits.get_bit(k * e + b))
                .fold(0u64, |v, b| v | 1 << b);
            // Sign-extend the W + 4 bits.
            ((raw << (64 - e)) as i64) >> (64 - e)
        });
        let axis = std::array::from_fn(|k| to_i128(axis_bits.get_bits::<16>(16 * k)) as i64);
        let threshold = self.in_threshold.val().index() as i64;
        (net, eye, FixedCone { axis, threshold })
    }
}

impl<const W: usize, const NET: usize, const EYE: usize> Logic for ConeUnit<W, NET, EYE> {
    fn update(&mut self) {
        if !self.clock.pos_edge() {
            return;
        }
        if self.advance.val() {
            let (net, eye, cone) = self.inputs();
            let class = facing(&net, eye, &cone) as u64;
            let entered = (self.in_valid.val(), self.in_tag.val().index() as u64, class);
            let [s1, s2, s3, _] = self._stages;
            self._stages = [entered, s1, s2, s3];
            self.out_tag.next = Bits::from(s3.1);
            self.out_class.next = Bits::from(s3.2);
        }
        if self.reset.val() {
            for s in self._stages.iter_mut() {
                s.0 = false;
            }
        }
        self.out_valid.next = self._stages[CONE_UNIT_LATENCY - 1].0;
    }

    fn connect(&mut self) {
        self.out_valid.connect();
        self.out_tag.connect();
        self.out_class.connect();
    }

    fn hdl(&self) -> Verilog {
        Verilog::Custom(cone_verilog(W))
    }
}

/// Bits of every value inside the unit for `w`-bit nets.
pub const fn cone_value_bits(w: usize) -> usize {
    2 * w + 68
}

/// The Verilog of the unit (module docs).
fn cone_verilog(w: usize) -> String {
    let l = cone_value_bits(w);
    let l1 = l - 1;
    let e = w + EYE_EXTRA_BITS;
    let f = THRESHOLD_FRACTION_BITS;
    let mut text = String::new();
    let mut line = |s: String| {
        text.push_str(&s);
        text.push('\n');
    };
    let xyz = ["x", "y", "z"];
    // A `bits`-wide slice of a port at `at`, sign-extended to L bits.
    let signed = |port: &str, at: usize, bits: usize| {
        format!(
            "$signed({{{{{}{{{port}[{}]}}}}, {port}[{}:{at}]}})",
            l - bits,
            at + bits - 1,
            at + bits - 1
        )
    };
    let regs = |names: Vec<String>| format!("reg signed [{l1}:0] {};", names.join(", "));
    let per_point = |what: &str, stage: usize| {
        (0..16)
            .map(|i| format!("{what}{i}_{stage}"))
            .collect::<Vec<_>>()
    };
    line("// Stage 1: d = c - e for the sixteen control points, |a|^2, the axis and S.".into());
    line(regs(
        (0..16)
            .flat_map(|i| xyz.map(|c| format!("d{i}{c}_1")))
            .collect(),
    ));
    line(regs(vec![
        "aa_1".into(),
        "ax_1".into(),
        "ay_1".into(),
        "az_1".into(),
        "s_1".into(),
    ]));
    line("// Stage 2: p = a . d, |d|^2, S |a|^2.".into());
    line(regs(
        [
            per_point("p", 2),
            per_point("dd", 2),
            vec!["bound_2".into()],
        ]
        .concat(),
    ));
    line("// Stage 3: the sign of p, and p^2 2^F against S |a|^2 |d|^2.".into());
    line(regs([per_point("lhs", 3), per_point("rhs", 3)].concat()));
    line("reg [15:0] pos_3, neg_3;".into());
    line(format!(
        "reg [{}:0] tag_1, tag_2, tag_3;",
        CONE_TAG_BITS - 1
    ));
    line("reg valid_1, valid_2, valid_3;".into());
    line(
        "wire [15:0] narrow = {".to_string()
            + &(0..16)
                .rev()
                .map(|i| format!("lhs{i}_3 > rhs{i}_3"))
                .collect::<Vec<_>>()
                .join(", ")
            + "};",
    );
    line("always @(posedge clock) begin".into());
    line("    if (reset) begin".into());
    line("        valid_1 <= 1'b0; valid_2 <= 1'b0; valid_3 <= 1'b0; out_valid <= 1'b0;".into());
    line("    end else if (advance) begin".into());
    line("        valid_1 <= in_valid; valid_2 <= valid_1; valid_3 <= valid_2; out_valid <= valid_3;".into());
    line("    end".into());
    line("    if (advance) begin".into());
    line("        tag_1 <= in_tag; tag_2 <= tag_1; tag_3 <= tag_2; out_tag <= tag_3;".into());
    for i in 0..16 {
        for (k, c) in xyz.iter().enumerate() {
            line(format!(
                "        d{i}{c}_1 <= {} - {};",
                signed("in_net", (3 * i + k) * w, w),
                signed("in_eye", k * e, e)
            ));
        }
    }
    for (k, c) in xyz.iter().enumerate() {
        line(format!(
            "        a{c}_1 <= {};",
            signed("in_axis", 16 * k, 16)
        ));
    }
    let a = |k: usize| signed("in_axis", 16 * k, 16);
    line(format!(
        "        aa_1 <= {} * {} + {} * {} + {} * {};",
        a(0),
        a(0),
        a(1),
        a(1),
        a(2),
        a(2)
    ));
    line(format!(
        "        s_1 <= $signed({{{}'d0, in_threshold}});",
        l - THRESHOLD_BITS
    ));
    for i in 0..16 {
        line(format!(
            "        p{i}_2 <= ax_1 * d{i}x_1 + ay_1 * d{i}y_1 + az_1 * d{i}z_1;"
        ));
        line(format!(
            "        dd{i}_2 <= d{i}x_1 * d{i}x_1 + d{i}y_1 * d{i}y_1 + d{i}z_1 * d{i}z_1;"
        ));
    }
    line("        bound_2 <= s_1 * aa_1;".into());
    for i in 0..16 {
        line(format!("        lhs{i}_3 <= (p{i}_2 * p{i}_2) <<< {f};"));
        line(format!("        rhs{i}_3 <= bound_2 * dd{i}_2;"));
        line(format!("        pos_3[{i}] <= p{i}_2 > {l}'sd0;"));
        line(format!("        neg_3[{i}] <= p{i}_2 < {l}'sd0;"));
    }
    line("        // Back-facing: every control point seen from behind within the".into());
    line("        // cone; front-facing: the mirror; else a possible silhouette.".into());
    line("        if (&(pos_3 & narrow)) out_class <= 2'd1;".into());
    line("        else if (&(neg_3 & narrow)) out_class <= 2'd0;".into());
    line("        else out_class <= 2'd2;".into());
    line("    end".into());
    line("end".into());
    text
}
