//! Co-simulation of the cone-of-normals unit ([`tritri_rtl::bezier::
//! cone_unit`]): patches and eyes through the fixed-point model
//! (`tritri_geom::bezier::cone_fixed::facing`), the rust-hdl model and the
//! emitted Verilog in Icarus and Verilator, one a clock.
//!
//! Vectors: one patch per line, `tag`, the 48 net coordinates (W-bit two's
//! complement, row by row, point by point, x y z), the eye's three
//! (W + 4 bits), the axis's three (16 bits) and the threshold, all hex.
//! Outputs: one line per patch, `tag class`.

use crate::simulator::{
    compile, run_on_vectors, vector_testbench, Simulator, Testbench, VectorTestbench,
};
use anyhow::{bail, Context as _};
use nalgebra::Point3;
use rust_hdl::prelude::*;
use tritri_geom::bezier::cone::NormalCone;
use tritri_geom::bezier::cone_fixed::{facing, Facing, FixedCone, EYE_EXTRA_BITS};
use tritri_geom::bezier::fixed::{FixedNet, PatchFrame};
use tritri_geom::bezier::BezierPatch;
use tritri_rtl::bezier::cone_unit::{ConeUnit, CONE_UNIT_LATENCY, CONE_UNIT_WIDTHS};
use tritri_rtl::emit::cone_unit_unit::emit_cone_unit;
use tritri_rtl::sim_drive::{clock_cycle, reset_one_clock};

/// One patch and eye, as the unit takes them.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ConeInput {
    pub net: FixedNet,
    pub eye: [i64; 3],
    pub cone: FixedCone,
}

/// Why the unit cannot take an input: a coordinate outside its widths.
pub fn check_input(w: usize, input: &ConeInput) -> anyhow::Result<()> {
    anyhow::ensure!(
        CONE_UNIT_WIDTHS.contains(&w),
        "the cone unit is built for W in {CONE_UNIT_WIDTHS:?}, not {w}"
    );
    let fits = |x: i64, bits: usize| -(1i64 << (bits - 1)) <= x && x < 1i64 << (bits - 1);
    if let Some(c) = input.net.iter().flatten().flatten().find(|&&c| !fits(c, w)) {
        bail!("a control point's coordinate {c} does not fit {w} bits");
    }
    if let Some(e) = input.eye.iter().find(|&&e| !fits(e, w + EYE_EXTRA_BITS)) {
        bail!("the eye's coordinate {e} does not fit the unit's {} bits (the eye is too far from the patches' grid)", w + EYE_EXTRA_BITS);
    }
    Ok(())
}

/// The unit's inputs for `patches` seen from `eyes` on a `w`-bit grid fit
/// to the patches: patch by patch, eye by eye within a patch.
pub fn inputs_for(
    patches: &[BezierPatch],
    eyes: &[Point3<f64>],
    w: usize,
) -> anyhow::Result<Vec<ConeInput>> {
    let frame = PatchFrame::fit(patches, w as u32);
    let mut out = Vec::with_capacity(patches.len() * eyes.len());
    for patch in patches {
        let cone = FixedCone::of(NormalCone::of(patch).as_ref());
        let net = frame.quantize(patch);
        for eye in eyes {
            let q = [0, 1, 2].map(|k| ((eye[k] - frame.origin[k]) / frame.step).round() as i64);
            let input = ConeInput { net, eye: q, cone };
            check_input(w, &input)?;
            out.push(input);
        }
    }
    Ok(out)
}

/// What the model says for each input.
pub fn expected(inputs: &[ConeInput]) -> Vec<Facing> {
    inputs
        .iter()
        .map(|i| facing(&i.net, i.eye, &i.cone))
        .collect()
}

/// The inputs through the rust-hdl model of the `w`-bit unit, one a clock.
pub fn run_rusthdl(w: usize, inputs: &[ConeInput]) -> anyhow::Result<Vec<Facing>> {
    fn run<const W: usize, const NET: usize, const EYE: usize>(
        inputs: &[ConeInput],
    ) -> anyhow::Result<Vec<Facing>> {
        let mut uut = ConeUnit::<W, NET, EYE>::default();
        uut.connect_all();
        uut.advance.next = true;
        reset_one_clock(&mut uut, |u| &mut u.reset, |u| &mut u.clock);
        let mut out = Vec::new();
        let idle = std::iter::repeat_n(None, CONE_UNIT_LATENCY + 1);
        for (tag, input) in inputs.iter().map(Some).chain(idle).enumerate() {
            uut.in_valid.next = input.is_some();
            uut.in_tag.next = (tag as u64 & 0xffff).into();
            if let Some(i) = input {
                uut.in_net.next = crate::patch_tessellator::pack_net::<W, NET>(&i.net);
                let mut eye = Bits::<EYE>::default();
                let e = W + EYE_EXTRA_BITS;
                for (k, &x) in i.eye.iter().enumerate() {
                    for b in 0..e {
                        eye = eye.replace_bit(k * e + b, x >> b & 1 == 1);
                    }
                }
                uut.in_eye.next = eye;
                let mut axis = Bits::<48>::default();
                for k in 0..3 {
                    axis.set_bits::<16>(16 * k, (i.cone.axis[k] as u64 & 0xffff).into());
                }
                uut.in_axis.next = axis;
                uut.in_threshold.next = (i.cone.threshold as u64).into();
            }
            clock_cycle(&mut uut, |u| &mut u.clock);
            if uut.out_valid.val() {
                // The patch given `CONE_UNIT_LATENCY` edges ago, exactly.
                let (want, got) = (
                    (tag + 1).checked_sub(CONE_UNIT_LATENCY),
                    uut.out_tag.val().index(),
                );
                anyhow::ensure!(want == Some(got) && got == out.len(), "the class of patch {got} left at edge {tag}, not {CONE_UNIT_LATENCY} edges after it");
                let code = uut.out_class.val().index() as u64;
                out.push(Facing::from_code(code).with_context(|| format!("class code {code}"))?);
            }
        }
        Ok(out)
    }
    tritri_rtl::with_cone_unit!(w, run(inputs))
        .with_context(|| format!("no cone unit at W = {w}"))?
}

/// The inputs through the emitted `w`-bit unit in `simulator`.
pub fn run_emitted(
    w: usize,
    inputs: &[ConeInput],
    simulator: Simulator,
) -> anyhow::Result<Vec<Facing>> {
    let design = emit_cone_unit(w)?;
    let mut files = vec![("tb_cone_unit.sv".to_string(), testbench(&design.top, w))];
    files.extend(
        design
            .verilog_files()
            .map(|f| (f.path.clone(), f.contents.clone())),
    );
    let bench = Testbench {
        top: "tb_cone_unit".into(),
        files,
        defines: vec![],
        parameters: vec![],
        c_optimization: 2,
        trace: false,
    };
    let compiled = compile(simulator, &bench)?;
    let hex = |x: i64, bits: usize| format!("{:x}", (x as u64) & ((1u64 << bits) - 1));
    let mut vectors = String::new();
    for (tag, i) in inputs.iter().enumerate() {
        let mut fields = vec![format!("{:x}", tag & 0xffff)];
        fields.extend(i.net.iter().flatten().flatten().map(|&c| hex(c, w)));
        fields.extend(i.eye.iter().map(|&e| hex(e, w + EYE_EXTRA_BITS)));
        fields.extend(i.cone.axis.iter().map(|&a| hex(a, 16)));
        fields.push(hex(i.cone.threshold, 20));
        vectors += &fields.join(" ");
        vectors.push('\n');
    }
    let (text, _) = run_on_vectors(&compiled, "cone-unit-run", &vectors, &[])?;
    text.lines()
        .enumerate()
        .map(|(n, line)| {
            let fields: Vec<&str> = line.split_whitespace().collect();
            let [tag, class] = fields.as_slice() else {
                bail!("cone unit output line `{line}` is not `tag class`")
            };
            // One class a patch, in order.
            anyhow::ensure!(
                u64::from_str_radix(tag, 16).ok() == Some(n as u64 & 0xffff),
                "`{line}`: out of order (patch {n} expected)"
            );
            let code = u64::from_str_radix(class, 16).with_context(|| format!("`{line}`"))?;
            Facing::from_code(code).with_context(|| format!("class code {code} in `{line}`"))
        })
        .collect()
}

/// The testbench: one patch a line, driven for one clock; every valid
/// output's tag and class.
fn testbench(top: &str, w: usize) -> String {
    let (w1, e1, n1, y1) = (
        w - 1,
        w + EYE_EXTRA_BITS - 1,
        48 * w - 1,
        3 * (w + EYE_EXTRA_BITS) - 1,
    );
    let (n, y) = (48 * w, 3 * (w + EYE_EXTRA_BITS));
    let net = (0..48)
        .rev()
        .map(|i| format!("c[{i}]"))
        .collect::<Vec<_>>()
        .join(", ");
    let body = format!(
        "\
    reg [15:0] tag = 16'd0;
    reg [{w1}:0] c [0:47];
    reg [{e1}:0] e [0:2];
    reg [15:0] a [0:2];
    reg [17:0] threshold = 18'd0;
    reg [31:0] field;
    // Packed by the reading loop: Verilator 5.006 does not propagate
    // writes into an unpacked array through a continuous concatenation.
    reg [{n1}:0] net = {n}'d0;
    reg [{y1}:0] eye = {y}'d0;
    reg [47:0] axis = 48'd0;
    wire out_valid;
    wire [15:0] out_tag;
    wire [1:0] out_class;
    {top} dut (
        .clock(clock), .reset(reset), .advance(advance), .in_valid(in_valid), .in_tag(tag),
        .in_net(net), .in_eye(eye), .in_axis(axis), .in_threshold(threshold),
        .out_valid(out_valid), .out_tag(out_tag), .out_class(out_class)
    );

    // Registered outputs are stable at the falling edge.
    always @(negedge clock) begin
        if (!reset && out_valid) begin
            $fwrite(outputs, \"%h %h\\n\", out_tag, out_class);
        end
    end
"
    );
    vector_testbench(&VectorTestbench {
        name: "tb_cone_unit",
        body,
        start: "        for (i = 0; i < 48; i = i + 1) c[i] = 0;\n        for (i = 0; i < 3; i = i + 1) begin e[i] = 0; a[i] = 0; end".into(),
        read: "$fscanf(vectors, \"%h\", tag) == 1".into(),
        fill: format!(
            "            for (i = 0; i < 48; i = i + 1) begin r = $fscanf(vectors, \"%h\", field); c[i] = field; end
            for (i = 0; i < 3; i = i + 1) begin r = $fscanf(vectors, \"%h\", field); e[i] = field; end
            for (i = 0; i < 3; i = i + 1) begin r = $fscanf(vectors, \"%h\", field); a[i] = field; end
            r = $fscanf(vectors, \"%h\", field); threshold = field;
            net = {{{net}}};
            eye = {{e[2], e[1], e[0]}};
            axis = {{a[2], a[1], a[0]}};"
        ),
        drain: CONE_UNIT_LATENCY + 2,
    })
}
