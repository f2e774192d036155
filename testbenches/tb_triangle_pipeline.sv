// tb_triangle_pipeline.sv — file-driven testbench of the triangle pipeline.
//
// Purpose: reads one input cycle per line from a vector file, drives the
//   pipeline with it (advance held high), and writes one line per verdict to
//   an output file. The same file runs in Icarus (iverilog -g2012) and,
//   built with `verilator --binary` (timing on), in Verilator 5.006.
//   Formats and commands: testbenches/README.md.
//
// Parameters:
//   W         coordinate width in bits (the DUT's W)
//   ID_WIDTH  width of the triangle ids on the bus
//   TIMEOUT   cycles to wait for an outstanding verdict before giving up
// Macros:
//   TRITRI_DUT  module name of the pipeline top (default tritri_pipeline_w24)
//   TRITRI_VCD  define to dump every signal to the +vcd file (Verilator
//               needs --trace for it; runs are slower, keep them short)
//   TRITRI_HOLD define for a pipeline with a `hold` output (the rare cases
//               on the shared unit): while it is high the input stays on
//               the bus, and the held clocks are counted (the pipeline is
//               on its own: `hold_others` is 0)
// Plusargs:
//   +vectors=FILE  input vectors (required)
//   +outputs=FILE  where verdicts go (required)
//   +vcd=FILE      the waveform, with TRITRI_VCD (required then)
//
// The run ends when every tested triangle (valid, bset = 0) has its verdict;
// the last line written is "# cycles N" with N counted from the first input
// cycle to the cycle of the last verdict, inclusive, after "# held H" (the
// clocks with `hold` high) with TRITRI_HOLD.

`timescale 1ns / 1ps
`default_nettype none

`ifndef TRITRI_DUT
`define TRITRI_DUT tritri_pipeline_w24
`endif

module tb_triangle_pipeline #(
    parameter integer W = 24,
    parameter integer ID_WIDTH = 32,
    parameter integer TIMEOUT = 1000
);
    localparam integer RESET_CYCLES = 2;
    localparam integer FIELDS = 12;  // valid bset id + 9 coordinates

    reg clock = 1'b0;
    reg reset = 1'b1;
    reg advance = 1'b1;
    reg in_valid = 1'b0;
    reg in_bset = 1'b0;
    reg [ID_WIDTH-1:0] in_id = {ID_WIDTH{1'b0}};
    reg [W-1:0] in_coordinate [0:8];
    wire out_valid;
    wire out_hit;
    wire out_certain;
    wire [ID_WIDTH-1:0] out_base_id;
    wire [ID_WIDTH-1:0] out_stream_id;
`ifdef TRITRI_HOLD
    wire hold;
    wire [3:0] hold_request;  // for pipelines in step with this one: none here
`else
    wire hold = 1'b0;
`endif
    // The edge that ended the last cycle was held: the outputs still show
    // the verdict already written.
    reg held_edge = 1'b0;
    integer held_cycles = 0;

    `TRITRI_DUT dut (
        .clock(clock),
        .reset(reset),
        .advance(advance),
        .in_valid(in_valid),
        .in_bset(in_bset),
        .in_id(in_id),
        .in_x0(in_coordinate[0]),
        .in_y0(in_coordinate[1]),
        .in_z0(in_coordinate[2]),
        .in_x1(in_coordinate[3]),
        .in_y1(in_coordinate[4]),
        .in_z1(in_coordinate[5]),
        .in_x2(in_coordinate[6]),
        .in_y2(in_coordinate[7]),
        .in_z2(in_coordinate[8]),
        .out_valid(out_valid),
        .out_hit(out_hit),
        .out_certain(out_certain),
        .out_base_id(out_base_id),
        .out_stream_id(out_stream_id)
`ifdef TRITRI_HOLD
        ,
        .hold(hold),
        .hold_request(hold_request),
        .hold_others(4'b0)
`endif
    );

    always #5 clock = ~clock;

    // File state.
    reg [8*1000-1:0] vectors_path;
    reg [8*1000-1:0] outputs_path;
    reg [8*240-1:0] line;  // at most 256 characters convert in Verilator
    integer vectors_fd;
    integer outputs_fd;
    integer fields;
    reg [7:0] first_character;
    integer line_number = 0;
    reg input_done = 1'b0;

    // One parsed line.
    reg field_valid;
    reg [31:0] field_bset;
    reg [ID_WIDTH-1:0] field_id;
    reg [W-1:0] field_coordinate [0:8];

    // Counters.
    integer edge_count = 0;
    integer cycle;
    integer tests_sent = 0;
    integer input_cycles = 0;
    integer verdicts_seen = 0;
    integer last_verdict_cycle = -1;
    integer idle_cycles = 0;
    integer k;

`ifdef TRITRI_VCD
    reg [8*1000-1:0] vcd_path;
    initial begin
        if (!$value$plusargs("vcd=%s", vcd_path)) begin
            $display("tb_triangle_pipeline: error: TRITRI_VCD is defined but +vcd=FILE is missing");
            $finish;
        end
        $dumpfile(vcd_path);
        $dumpvars(0, tb_triangle_pipeline);
    end
`endif

    initial begin
        for (k = 0; k < 9; k = k + 1) in_coordinate[k] = {W{1'b0}};
        if (!$value$plusargs("vectors=%s", vectors_path)) begin
            $display("tb_triangle_pipeline: error: missing +vectors=FILE");
            $finish;
        end
        if (!$value$plusargs("outputs=%s", outputs_path)) begin
            $display("tb_triangle_pipeline: error: missing +outputs=FILE");
            $finish;
        end
        vectors_fd = $fopen(vectors_path, "r");
        if (vectors_fd == 0) begin
            $display("tb_triangle_pipeline: error: cannot open vectors %0s", vectors_path);
            $finish;
        end
        outputs_fd = $fopen(outputs_path, "w");
        if (outputs_fd == 0) begin
            $display("tb_triangle_pipeline: error: cannot open outputs %0s", outputs_path);
            $finish;
        end
    end

    // Reads the next vector line into field_*; sets input_done at end of file.
    // Lines whose first non-blank character is '#' are comments; otherwise
    // that character is the valid digit, and $fscanf reads the other fields.
    // Portability notes (Verilator 5.006 and Icarus 11 differ): $fscanf reads
    // straight from the file because Verilator's $sscanf stops at the leading
    // NUL bytes of a wide line register; neither $ungetc nor a failed literal
    // match in a format gives a character back reliably; a $fgets whose result
    // is never read is optimized away; at end of file $fscanf may return 0, so
    // $feof decides.
    task read_vector;
        reg found;
        begin
            found = 1'b0;
            while (!found && !input_done) begin
                fields = $fscanf(vectors_fd, " %c", first_character);
                if (fields != 1 || $feof(vectors_fd) != 0) begin
                    input_done = 1'b1;
                end else if (first_character == "#") begin
                    // A comment: drop the rest of its line.
                    if ($fgets(line, vectors_fd) == 0) input_done = 1'b1;
                end else begin
                    line_number = line_number + 1;
                    fields = 1 + $fscanf(vectors_fd, "%h %h %h %h %h %h %h %h %h %h %h",
                        field_bset, field_id,
                        field_coordinate[0], field_coordinate[1], field_coordinate[2],
                        field_coordinate[3], field_coordinate[4], field_coordinate[5],
                        field_coordinate[6], field_coordinate[7], field_coordinate[8]);
                    if (fields != FIELDS || (first_character != "0" && first_character != "1")) begin
                        $display("tb_triangle_pipeline: error: vector %0d: expected %0d fields, valid 0 or 1",
                            line_number, FIELDS);
                        $finish;
                    end
                    field_valid = first_character == "1";
                    found = 1'b1;
                end
            end
        end
    endtask

    // Cycle c is the clock period that ends with edge RESET_CYCLES + c: the
    // inputs of vector line c are on the bus during it, and the outputs seen
    // at that edge (before it updates anything) are the outputs of cycle c.
    always @(posedge clock) begin
        cycle = edge_count - RESET_CYCLES;
        if (cycle >= 0 && out_valid && !held_edge) begin
            $fdisplay(outputs_fd, "%0d %0h %0h %0d %0d", cycle, out_base_id, out_stream_id, out_hit, out_certain);
            verdicts_seen = verdicts_seen + 1;
            last_verdict_cycle = cycle;
        end
        held_edge = hold;
        if (hold) begin
            // This edge does not take the input: it stays on the bus.
            held_cycles = held_cycles + 1;
        end else if (cycle + 1 >= 0) begin
            reset <= 1'b0;
            read_vector();
            if (!input_done) begin
                in_valid <= field_valid;
                in_bset <= field_bset[0];
                in_id <= field_id;
                for (k = 0; k < 9; k = k + 1) in_coordinate[k] <= field_coordinate[k];
                input_cycles = input_cycles + 1;
                if (field_valid && !field_bset[0]) tests_sent = tests_sent + 1;
            end else begin
                in_valid <= 1'b0;
                in_bset <= 1'b0;
            end
        end
        if (input_done) begin
            if (verdicts_seen == tests_sent) begin
`ifdef TRITRI_HOLD
                $fdisplay(outputs_fd, "# held %0d", held_cycles);
`endif
                $fdisplay(outputs_fd, "# cycles %0d",
                    tests_sent == 0 ? input_cycles : last_verdict_cycle + 1);
                $fclose(outputs_fd);
                $finish;
            end
            idle_cycles = idle_cycles + 1;
            if (idle_cycles > TIMEOUT) begin
                $display("tb_triangle_pipeline: error: %0d of %0d verdicts after %0d idle cycles",
                    verdicts_seen, tests_sent, TIMEOUT);
                $fdisplay(outputs_fd, "# timeout");
                $fclose(outputs_fd);
                $finish;
            end
        end
        edge_count = edge_count + 1;
    end
endmodule

`default_nettype wire
