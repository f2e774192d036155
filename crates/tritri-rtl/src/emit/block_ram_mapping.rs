//! Memories with an output register onto ECP5 block RAMs with theirs.
//!
//! A [`SimpleDualPortRam`](crate::system::dual_port_ram::SimpleDualPortRam)
//! built `with_output_register` reads in two registered stages. Yosys maps
//! the first into an ECP5 DP16KD and leaves the second in fabric, so the
//! block RAM runs without its output register (`REGMODE = "NOREG"`): 5.83 ns
//! from clock to data, which no route after it can fit into 150 MHz (a
//! DP16KD with a flip-flop straight after it routes at 145.9 MHz; with
//! `"OUTREG"`, 293.1 MHz; rtl-out/README.md). With the ECP5 primitives
//! (`tritri gen --dsp ecp5`, the default with `--synth ecp5`), [`map_ecp5`]
//! swaps such a module's body for DP16KD instances in their 1,024 x 18
//! mode with both registers: the same ports, latency and words, and both
//! stages enabled by `read_enable` (`CEB` and `OCEB`). Memories of more than
//! 1,024 words stay inferred. The emitted directory then also holds
//! [`ECP5_DP16KD_MODEL_FILE`], a simulation model of the primitive that
//! Yosys skips.

use super::dsp_mapping::indented_body;
use super::modules::Module;
use super::tokens::tokenize;
use crate::system::dual_port_ram::OUTPUT_REGISTER_SHAPE;

/// Words of a DP16KD in its 18-bit mode, and its data bits there.
const WORDS: usize = 1024;
const DATA_BITS: usize = 18;

/// The file that holds [`ECP5_DP16KD_MODEL`] in an emitted directory.
pub const ECP5_DP16KD_MODEL_FILE: &str = "ecp5_dp16kd_model.v";

/// `(words, bits)` of a RAM with an output register, from the comment its
/// body starts with.
fn ram_shape(text: &str) -> Option<(usize, usize)> {
    let rest = text.split(OUTPUT_REGISTER_SHAPE).nth(1)?;
    let mut words = rest.lines().next()?.split_whitespace();
    let n = words.next()?.parse().ok()?;
    let _words = words.next()?;
    let _of = words.next()?;
    let bits = words.next()?.parse().ok()?;
    Some((n, bits))
}

/// The width of a module's `name` port, from its header (`[15:0] name`,
/// or 1 without a range).
fn port_bits(text: &str, name: &str) -> Option<usize> {
    let line = text.lines().find(|l| {
        l.trim_end()
            .trim_end_matches(',')
            .ends_with(&format!(" {name}"))
    })?;
    match line.split('[').nth(1) {
        Some(range) => Some(range.split(':').next()?.trim().parse::<usize>().ok()? + 1),
        None => Some(1),
    }
}

/// Swaps `module`'s body for DP16KD instances when it is a RAM with an
/// output register of at most 1,024 words; returns whether it did.
pub fn map_ecp5(module: &mut Module) -> bool {
    let text = module.text();
    let Some((words, bits)) = ram_shape(&text) else {
        return false;
    };
    let Some(address_bits) = port_bits(&text, "read_address") else {
        return false;
    };
    if words > WORDS {
        return false;
    }
    let marker = "// Update code (custom)";
    let (Some(start), Some(end)) = (text.find(marker), text.rfind("endmodule")) else {
        return false;
    };
    let head = &text[..start + marker.len()];
    let body = indented_body(&ecp5_verilog(words, bits, address_bits));
    module.tokens = tokenize(&format!("{head}\n{body}{}", &text[end..]));
    true
}

/// The body of a `words` x `bits` RAM with an output register on DP16KD
/// blocks, its addresses `address_bits` wide (the bits above the depth are
/// always zero, as in the inferred body).
pub fn ecp5_verilog(words: usize, bits: usize, address_bits: usize) -> String {
    let index_bits = (usize::BITS - (words.max(2) - 1).leading_zeros()) as usize;
    let blocks = bits.div_ceil(DATA_BITS);
    let mut v = format!(
        "{OUTPUT_REGISTER_SHAPE}{words} words of {bits} bit(s), on ECP5\n\
         // DP16KD blocks (1,024 x 18) with their read and output registers.\n"
    );
    // Port A writes (its two low address bits are the byte enables of the
    // 18-bit mode), port B reads; the word address is bits 13:4.
    let pad = 10 - index_bits;
    let zeros = |n: usize| {
        if n == 0 {
            String::new()
        } else {
            format!("{n}'b0, ")
        }
    };
    v.push_str(&format!(
        "wire [13:0] write_port = {{{}write_address[{}:0], 4'b0011}};\n",
        zeros(pad),
        index_bits - 1
    ));
    v.push_str(&format!(
        "wire [13:0] read_port = {{{}read_address[{}:0], 4'b0000}};\n",
        zeros(pad),
        index_bits - 1
    ));
    v.push_str("// verilator lint_off UNUSED\n");
    if index_bits < address_bits {
        v.push_str(&format!(
            "wire unused_address_bits = ^{{write_address[{hi}:{index_bits}], read_address[{hi}:{index_bits}]}};\n",
            hi = address_bits - 1
        ));
    }
    for b in 0..blocks {
        v.push_str(&format!("wire [17:0] port_a_{b};\nwire [17:0] data_{b};\n"));
    }
    v.push_str("// verilator lint_on UNUSED\n");
    for b in 0..blocks {
        let lo = b * DATA_BITS;
        let hi = bits.min(lo + DATA_BITS) - 1;
        let width = hi - lo + 1;
        let input = if width == DATA_BITS {
            format!("write_data[{hi}:{lo}]")
        } else if bits == 1 {
            format!("{{{}'b0, write_data}}", DATA_BITS - 1)
        } else {
            format!("{{{}'b0, write_data[{hi}:{lo}]}}", DATA_BITS - width)
        };
        v.push_str(&format!("wire [17:0] write_{b} = {input};\n"));
        v.push_str(&instance(b));
    }
    let parts: Vec<String> = (0..blocks)
        .rev()
        .map(|b| {
            let width = bits.min((b + 1) * DATA_BITS) - b * DATA_BITS;
            format!("data_{b}[{}:0]", width - 1)
        })
        .collect();
    v.push_str(&format!(
        "always @(*) begin\n    read_data = {{{}}};\nend\n",
        parts.join(", ")
    ));
    v
}

/// The DP16KD of block `b`: port A writes `write_<b>`, port B reads into
/// `data_<b>`, through its output register.
fn instance(b: usize) -> String {
    let pins = |prefix: &str, n: usize, bus: &str| -> String {
        (0..n)
            .map(|i| format!(".{prefix}{i}({bus}[{i}])"))
            .collect::<Vec<_>>()
            .join(", ")
    };
    format!(
        "DP16KD #(\n\
         \x20   .DATA_WIDTH_A(18), .DATA_WIDTH_B(18), .REGMODE_A(\"NOREG\"), .REGMODE_B(\"OUTREG\"),\n\
         \x20   .CSDECODE_A(\"0b000\"), .CSDECODE_B(\"0b000\"), .WRITEMODE_A(\"READBEFOREWRITE\"),\n\
         \x20   .WRITEMODE_B(\"READBEFOREWRITE\"), .RESETMODE(\"SYNC\"), .GSR(\"DISABLED\")\n\
         ) u_block_{b} (\n\
         \x20   .CLKA(clock), .CEA(1'b1), .OCEA(1'b1), .WEA(write_enable), .RSTA(1'b0),\n\
         \x20   .CSA0(1'b0), .CSA1(1'b0), .CSA2(1'b0),\n\
         \x20   {},\n\
         \x20   {},\n\
         \x20   {},\n\
         \x20   .CLKB(clock), .CEB(read_enable), .OCEB(read_enable), .WEB(1'b0), .RSTB(1'b0),\n\
         \x20   .CSB0(1'b0), .CSB1(1'b0), .CSB2(1'b0),\n\
         \x20   {},\n\
         \x20   {},\n\
         \x20   {}\n\
         );\n",
        pins("ADA", 14, "write_port"),
        pins("DIA", 18, &format!("write_{b}")),
        pins("DOA", 18, &format!("port_a_{b}")),
        pins("ADB", 14, "read_port"),
        (0..18)
            .map(|i| format!(".DIB{i}(1'b0)"))
            .collect::<Vec<_>>()
            .join(", "),
        pins("DOB", 18, &format!("data_{b}")),
    )
}

/// A simulation model of the Lattice ECP5 DP16KD for Icarus and Verilator,
/// for the subset [`ecp5_verilog`] instantiates: both ports 18 bits wide,
/// port A writing (byte enables on `ADA1:0`) and port B reading, `CSDECODE`
/// 0b000 with the chip selects low, no reset; each port's read register on
/// `CE`, and with `REGMODE "OUTREG"` its output register on `OCE`, as
/// Lattice's memory usage guide (TN1264) describes them. The words start at
/// zero (no `INITVAL`), and so do the registers. A read of a word written on
/// the same edge gives the word before the write. Any other setting stops
/// the simulation. It sits inside `` `ifndef SYNTHESIS `` so that Yosys takes
/// the primitive from its own cell library.
pub const ECP5_DP16KD_MODEL: &str = r#"`ifndef SYNTHESIS
/* verilator lint_off UNUSED */
/* verilator lint_off DECLFILENAME */
/* verilator lint_off WIDTH */
module DP16KD #(
    parameter DATA_WIDTH_A = 18,
    parameter DATA_WIDTH_B = 18,
    parameter REGMODE_A = "NOREG",
    parameter REGMODE_B = "NOREG",
    parameter CSDECODE_A = "0b000",
    parameter CSDECODE_B = "0b000",
    parameter WRITEMODE_A = "NORMAL",
    parameter WRITEMODE_B = "NORMAL",
    parameter RESETMODE = "SYNC",
    parameter GSR = "ENABLED"
) (
    input  wire CLKA, CEA, OCEA, WEA, RSTA, CSA0, CSA1, CSA2,
    input  wire ADA0, ADA1, ADA2, ADA3, ADA4, ADA5, ADA6, ADA7, ADA8, ADA9, ADA10, ADA11, ADA12, ADA13,
    input  wire DIA0, DIA1, DIA2, DIA3, DIA4, DIA5, DIA6, DIA7, DIA8, DIA9, DIA10, DIA11, DIA12, DIA13, DIA14, DIA15, DIA16, DIA17,
    output wire DOA0, DOA1, DOA2, DOA3, DOA4, DOA5, DOA6, DOA7, DOA8, DOA9, DOA10, DOA11, DOA12, DOA13, DOA14, DOA15, DOA16, DOA17,
    input  wire CLKB, CEB, OCEB, WEB, RSTB, CSB0, CSB1, CSB2,
    input  wire ADB0, ADB1, ADB2, ADB3, ADB4, ADB5, ADB6, ADB7, ADB8, ADB9, ADB10, ADB11, ADB12, ADB13,
    input  wire DIB0, DIB1, DIB2, DIB3, DIB4, DIB5, DIB6, DIB7, DIB8, DIB9, DIB10, DIB11, DIB12, DIB13, DIB14, DIB15, DIB16, DIB17,
    output wire DOB0, DOB1, DOB2, DOB3, DOB4, DOB5, DOB6, DOB7, DOB8, DOB9, DOB10, DOB11, DOB12, DOB13, DOB14, DOB15, DOB16, DOB17
);
    wire [13:0] ada = {ADA13, ADA12, ADA11, ADA10, ADA9, ADA8, ADA7, ADA6, ADA5, ADA4, ADA3, ADA2, ADA1, ADA0};
    wire [13:0] adb = {ADB13, ADB12, ADB11, ADB10, ADB9, ADB8, ADB7, ADB6, ADB5, ADB4, ADB3, ADB2, ADB1, ADB0};
    wire [17:0] dia = {DIA17, DIA16, DIA15, DIA14, DIA13, DIA12, DIA11, DIA10, DIA9, DIA8, DIA7, DIA6, DIA5, DIA4, DIA3, DIA2, DIA1, DIA0};
    initial begin
        if (DATA_WIDTH_A != 18 || DATA_WIDTH_B != 18 || CSDECODE_A != "0b000" || CSDECODE_B != "0b000"
            || (REGMODE_A != "NOREG" && REGMODE_A != "OUTREG") || (REGMODE_B != "NOREG" && REGMODE_B != "OUTREG")) begin
            $display("DP16KD model: only 18-bit ports, CSDECODE 0b000 and REGMODE NOREG or OUTREG are modelled");
            $finish;
        end
    end
    reg [17:0] words [0:1023];
    integer i;
    initial for (i = 0; i < 1024; i = i + 1) words[i] = 18'd0;
    reg [17:0] a_read = 18'd0;
    reg [17:0] a_out = 18'd0;
    reg [17:0] b_read = 18'd0;
    reg [17:0] b_out = 18'd0;
    always @(posedge CLKA) begin
        if (RSTA || CSA0 || CSA1 || CSA2) begin
            $display("DP16KD model: port A's reset and chip selects are not modelled");
            $finish;
        end
        if (CEA) begin
            a_read <= words[ada[13:4]];
            if (WEA && ada[0]) words[ada[13:4]][8:0] <= dia[8:0];
            if (WEA && ada[1]) words[ada[13:4]][17:9] <= dia[17:9];
        end
        if (OCEA) a_out <= a_read;
    end
    always @(posedge CLKB) begin
        if (RSTB || CSB0 || CSB1 || CSB2 || WEB) begin
            $display("DP16KD model: port B reads only, without reset or chip selects");
            $finish;
        end
        if (CEB) b_read <= words[adb[13:4]];
        if (OCEB) b_out <= b_read;
    end
    wire [17:0] doa = REGMODE_A == "OUTREG" ? a_out : a_read;
    wire [17:0] dob = REGMODE_B == "OUTREG" ? b_out : b_read;
    assign {DOA17, DOA16, DOA15, DOA14, DOA13, DOA12, DOA11, DOA10, DOA9, DOA8, DOA7, DOA6, DOA5, DOA4, DOA3, DOA2, DOA1, DOA0} = doa;
    assign {DOB17, DOB16, DOB15, DOB14, DOB13, DOB12, DOB11, DOB10, DOB9, DOB8, DOB7, DOB6, DOB5, DOB4, DOB3, DOB2, DOB1, DOB0} = dob;
endmodule
/* verilator lint_on WIDTH */
/* verilator lint_on DECLFILENAME */
/* verilator lint_on UNUSED */
`endif
"#;

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn shape_and_address_width_are_read_from_the_module() {
        let text = format!(
            "module m (\n    input  wire [15:0] read_address,\n    output reg  [31:0] read_data\n);\n    // Update code (custom)\n    {OUTPUT_REGISTER_SHAPE}512 words of 32 bit(s), read-first,\nendmodule\n"
        );
        assert_eq!(ram_shape(&text), Some((512, 32)));
        assert_eq!(port_bits(&text, "read_address"), Some(16));
        assert_eq!(
            ram_shape(
                "module m ();\n    // Simple dual-port RAM: 512 words of 32 bit(s)\nendmodule"
            ),
            None
        );
    }

    #[test]
    fn words_split_over_blocks_of_18_bits() {
        let v = ecp5_verilog(512, 32, 16);
        assert_eq!(v.matches("DP16KD #(").count(), 2, "{v}");
        assert!(
            v.contains("read_data = {data_1[13:0], data_0[17:0]};"),
            "{v}"
        );
        assert!(
            v.contains("wire [17:0] write_1 = {4'b0, write_data[31:18]};"),
            "{v}"
        );
        assert!(
            v.contains("wire [13:0] write_port = {1'b0, write_address[8:0], 4'b0011};"),
            "{v}"
        );
        assert!(v.contains("read_address[15:9]"), "{v}");
        let v = ecp5_verilog(1024, 16, 10);
        assert_eq!(v.matches("DP16KD #(").count(), 1);
        assert!(!v.contains("unused_address_bits"), "{v}");
        assert!(v.contains("{read_address[9:0], 4'b0000}"), "{v}");
    }
}
