// tb_collision_system.sv — file-driven testbench of the collision system.
//
// Purpose: plays the host of the bounding-volume-aware system: writes the
//   batches of a vector file into the triangle stream (valid/ready), reads
//   the result stream with a reader that is ready one cycle in
//   READER_PERIOD, and writes every pair and the final counters to an
//   output file. It behaves cycle for cycle like the rust-hdl harness
//   (crates/tritri-cosim/src/system_harness.rs), so the two agree on pairs,
//   their order and the cycle count. Runs in Verilator 5.006
//   (`verilator --binary`, timing on) and Icarus (iverilog -g2012).
//   Formats and commands: testbenches/README.md.
//
// Parameters:
//   W         coordinate width in bits (the DUT's W)
//   ID_WIDTH  width of the triangle ids
//   TIMEOUT   cycles after the last word before giving up
// Macros:
//   TRITRI_SYSTEM  module name of the system top (default tritri_system)
//   TRITRI_VCD     define to dump every signal to the +vcd file (Verilator
//                  needs --trace for it; runs are slower, keep them short)
// Plusargs:
//   +vectors=FILE      host words (required; a named pipe will do)
//   +outputs=FILE      where pairs and counters go (required)
//   +overlap=0|1       1: write the next batch at once; 0: wait for done (default 1)
//   +reader_period=K   out_ready in cycles K-1, 2K-1, ... (default 1: always)
//   +progress=N        print "# progress CYCLE" (flushed) every N cycles (default 0: never)
//   +vcd=FILE          the waveform, with TRITRI_VCD (required then)
//
// Host: two reset cycles, then cycle 0 presents the first word; a word
// stays on the bus until accepted (in_valid & in_ready). Without overlap the
// host waits after each end-of-batch word until it sees done, and writes
// the next word in the following cycle. "# cycles N": N is the first cycle
// after the last end-of-batch word in which done is high. The run ends in
// the first cycle after that in which the result FIFO is empty and
// out_valid is low.

`timescale 1ns / 1ps
`default_nettype none

`ifndef TRITRI_SYSTEM
`define TRITRI_SYSTEM tritri_system
`endif

module tb_collision_system #(
    parameter integer W = 24,
    parameter integer ID_WIDTH = 32,
    parameter integer TIMEOUT = 10000000
);
    localparam integer RESET_CYCLES = 2;
    localparam integer FIELDS = 11;  // kind id + 9 coordinates

    reg clock = 1'b0;
    reg reset = 1'b1;
    reg in_valid = 1'b0;
    wire in_ready;
    reg in_end = 1'b0;
    reg in_object = 1'b0;
    reg [ID_WIDTH-1:0] in_id = {ID_WIDTH{1'b0}};
    reg [W-1:0] in_coordinate [0:8];
    wire out_valid;
    reg out_ready = 1'b0;
    wire [ID_WIDTH-1:0] out_id_a;
    wire [ID_WIDTH-1:0] out_id_b;
    wire out_hit;
    wire out_certain;
    wire done;
    wire results_empty;
    wire overflow;
    wire [31:0] pairs_tested;
    wire [31:0] hits;
    wire [31:0] stall_cycles;

    `TRITRI_SYSTEM dut (
        .clock(clock),
        .reset(reset),
        .in_valid(in_valid),
        .in_ready(in_ready),
        .in_end(in_end),
        .in_object(in_object),
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
        .out_ready(out_ready),
        .out_id_a(out_id_a),
        .out_id_b(out_id_b),
        .out_hit(out_hit),
        .out_certain(out_certain),
        .done(done),
        .results_empty(results_empty),
        .overflow(overflow),
        .pairs_tested(pairs_tested),
        .hits(hits),
        .stall_cycles(stall_cycles)
    );

    always #5 clock = ~clock;

    // Files and options.
    reg [8*1000-1:0] vectors_path;
    reg [8*1000-1:0] outputs_path;
    integer vectors_fd;
    integer outputs_fd;
    integer overlap = 1;
    integer reader_period = 1;
    integer fields;
    integer line_number = 0;
    integer progress = 0;

    // One parsed word.
    reg [31:0] field_kind;
    reg [ID_WIDTH-1:0] field_id;
    reg [W-1:0] field_coordinate [0:8];

    // Host state.
    reg have_word = 1'b0;        // field_* hold a word not yet accepted
    reg input_done = 1'b0;       // end of the vector file
    reg waiting_for_done = 1'b0; // no overlap: wait for done before the next batch
    reg done_seen = 1'b0;
    integer cycle = -RESET_CYCLES;
    integer done_cycle = 0;
    integer pairs_seen = 0;
    integer k;

    initial begin
        for (k = 0; k < 9; k = k + 1) in_coordinate[k] = {W{1'b0}};
        if (!$value$plusargs("vectors=%s", vectors_path)) begin
            $display("tb_collision_system: error: missing +vectors=FILE");
            $finish;
        end
        if (!$value$plusargs("outputs=%s", outputs_path)) begin
            $display("tb_collision_system: error: missing +outputs=FILE");
            $finish;
        end
        if (!$value$plusargs("overlap=%d", overlap)) overlap = 1;
        if (!$value$plusargs("reader_period=%d", reader_period)) reader_period = 1;
        if (!$value$plusargs("progress=%d", progress)) progress = 0;
        vectors_fd = $fopen(vectors_path, "r");
        if (vectors_fd == 0) begin
            $display("tb_collision_system: error: cannot open vectors %0s", vectors_path);
            $finish;
        end
        outputs_fd = $fopen(outputs_path, "w");
        if (outputs_fd == 0) begin
            $display("tb_collision_system: error: cannot open outputs %0s", outputs_path);
            $finish;
        end
    end

    // Reads the next word into field_*; sets input_done at end of file.
    // (Only $fscanf: Verilator 5.006 loses characters when $fgetc, $ungetc
    // and $fscanf are mixed on one file, so the format has no comments.)
    task read_word;
        begin
            fields = $fscanf(vectors_fd, " %h %h %h %h %h %h %h %h %h %h %h",
                field_kind, field_id,
                field_coordinate[0], field_coordinate[1], field_coordinate[2],
                field_coordinate[3], field_coordinate[4], field_coordinate[5],
                field_coordinate[6], field_coordinate[7], field_coordinate[8]);
            if (fields <= 0) begin
                input_done = 1'b1;
            end else begin
                line_number = line_number + 1;
                if (fields != FIELDS) begin
                    $display("tb_collision_system: error: vectors word %0d has %0d of %0d fields",
                        line_number, fields, FIELDS);
                    $finish;
                end
            end
        end
    endtask

    // At the edge that ends cycle `cycle`, the DUT's outputs are those of
    // that cycle; the host then sets its inputs for cycle + 1.
`ifdef TRITRI_VCD
    reg [8*1000-1:0] vcd_path;
    initial begin
        if (!$value$plusargs("vcd=%s", vcd_path)) begin
            $display("tb_collision_system: error: TRITRI_VCD is defined but +vcd=FILE is missing");
            $finish;
        end
        $dumpfile(vcd_path);
        $dumpvars(0, tb_collision_system);
    end
`endif

    always @(posedge clock) begin
        if (cycle >= 0) begin
            if (progress > 0 && cycle > 0 && cycle % progress == 0) begin
                $display("# progress %0d", cycle);
                $fflush();
            end
            if (out_valid && out_ready) begin
                $fdisplay(outputs_fd, "%0h %0h %0d %0d", out_id_a, out_id_b, out_hit, out_certain);
                pairs_seen = pairs_seen + 1;
            end
            if (input_done && !have_word && !done_seen && done) begin
                done_seen = 1'b1;
                done_cycle = cycle;
            end
            if (waiting_for_done && done) waiting_for_done = 1'b0;
            if (in_valid && in_ready) begin
                have_word = 1'b0;
                if (field_kind == 2 && overlap == 0) waiting_for_done = 1'b1;
            end
            if (done_seen && results_empty && !out_valid) begin
                $fdisplay(outputs_fd, "# cycles %0d", done_cycle);
                $fdisplay(outputs_fd, "# pairs_tested %0d", pairs_tested);
                $fdisplay(outputs_fd, "# hits %0d", hits);
                $fdisplay(outputs_fd, "# stall_cycles %0d", stall_cycles);
                $fdisplay(outputs_fd, "# overflow %0d", overflow);
                $fclose(outputs_fd);
                $finish;
            end
            if (cycle > TIMEOUT) begin
                $display("tb_collision_system: error: not done after %0d cycles", TIMEOUT);
                $fdisplay(outputs_fd, "# timeout");
                $fclose(outputs_fd);
                $finish;
            end
        end
        // Inputs of the next cycle.
        reset <= (cycle + 1 < 0);
        out_ready <= (cycle + 1 >= 0) && (reader_period <= 1 || ((cycle + 1) % reader_period) == reader_period - 1);
        // Read ahead (also while waiting for done), so that the end of the
        // file is known as soon as the last word is accepted.
        if (cycle + 1 >= 0 && !have_word) begin
            read_word();
            if (!input_done) have_word = 1'b1;
        end
        in_valid <= have_word && !waiting_for_done;
        in_end <= field_kind == 2;
        in_object <= field_kind == 1;
        in_id <= field_id;
        for (k = 0; k < 9; k = k + 1) in_coordinate[k] <= field_coordinate[k];
        cycle = cycle + 1;
    end
endmodule

`default_nettype wire
