// tb_dram_broad_phase.sv — the broad-phase accelerator with its scene in
// external memory, against the memory model.
//
// Purpose: loads the memory model (axi_memory.sv) from a hex file (the
//   root lists as the host writes them), starts the top
//   (tritri_rtl::broad_phase::dram_broad_phase) and prints every pair it
//   streams and the clocks at which it is binned, tested and done, so the
//   co-simulation compares them with the rust-hdl run, the exact answer on
//   the grid and the cycle model. It runs in Verilator 5.006
//   (`verilator --binary`) and Icarus (iverilog -g2012).
//
// Parameters: GRID_BITS, the memory's (DATA_BITS, BYTES, READ_LATENCY,
//   WRITE_LATENCY, OUTSTANDING, BPC_NUM, BPC_DEN, STALL_PERCENT, SEED) and
//   LIMIT, the clocks to wait for done.
// Macros: TRITRI_DUT, the top's module name (required).
// Plusargs: +memory=FILE (hex, a byte a line, required), +corner_x=
//   +corner_y= +corner_z= (the root's low corner, as GRID_BITS-bit unsigned
//   numbers), +level=, +list_base_k= +list_count_k= +index_count_k= for
//   k = 0, 1, +arena_start= +arena_end=.
//
// Clocks: one reset clock, then clock 0 presents start. "# pair C A B H K":
// a pair taken in clock C (out_ready is always high), its indices, out_hit
// and out_certain; "# binned N" and "# tested N": the first clock from 1
// with that output high; "# cycles N ...": done is first high in clock N;
// "# counts ...": the top's counters at done; "# memory ...": the beats
// the memory read and wrote.

`timescale 1ns / 1ps
`default_nettype none

module tb_dram_broad_phase #(
    parameter integer GRID_BITS = 24,
    parameter integer DATA_BITS = 64,
    parameter integer BYTES = 65536,
    parameter integer READ_LATENCY = 20,
    parameter integer WRITE_LATENCY = 20,
    parameter integer OUTSTANDING = 64,
    parameter integer BPC_NUM = 16,
    parameter integer BPC_DEN = 1,
    parameter integer STALL_PERCENT = 0,
    parameter integer SEED = 1,
    parameter integer LIMIT = 10000000
);
    reg clock = 0;
    reg reset = 1;
    reg enable = 0;
    reg start = 0;
    reg [GRID_BITS-1:0] corner_x = 0, corner_y = 0, corner_z = 0;
    reg [5:0] level = 1;
    reg [31:0] list_base_0 = 0, list_base_1 = 0, list_count_0 = 0, list_count_1 = 0;
    reg [31:0] index_count_0 = 0, index_count_1 = 0;
    reg [31:0] arena_start = 0, arena_end = 0;
    wire out_valid, out_hit, out_certain;
    wire [31:0] out_index_a, out_index_b;
    wire binned, tested, done, error, overflow;
    wire [31:0] passes, arena_full, waiting_commits, pairs_tested, hits;
    wire [19:0] leaves;
    integer cycles = 0;
    reg finished = 0;
    integer binned_at = -1, tested_at = -1;
    wire [31:0] araddr, awaddr;
    wire [7:0] arlen, awlen;
    wire [2:0] arsize, awsize, arprot, awprot;
    wire [1:0] arburst, awburst, rresp, bresp;
    wire [3:0] arcache, awcache;
    wire arid, awid;
    wire arvalid, arready, rlast, rvalid, rready, awvalid, awready;
    wire wlast, wvalid, wready, bvalid, bready;
    wire [DATA_BITS-1:0] rdata, wdata;
    wire [DATA_BITS/8-1:0] wstrb;

    `TRITRI_DUT dut (
        .clock(clock), .reset(reset), .start(start),
        .corner_x(corner_x), .corner_y(corner_y), .corner_z(corner_z), .level(level),
        .list_base_0(list_base_0), .list_base_1(list_base_1),
        .list_count_0(list_count_0), .list_count_1(list_count_1),
        .index_count_0(index_count_0), .index_count_1(index_count_1),
        .arena_start(arena_start), .arena_end(arena_end),
        .out_valid(out_valid), .out_ready(1'b1), .out_index_a(out_index_a),
        .out_index_b(out_index_b), .out_hit(out_hit), .out_certain(out_certain),
        .binned(binned), .tested(tested), .done(done), .error(error), .overflow(overflow),
        .passes(passes), .leaves(leaves), .arena_full(arena_full),
        .waiting_commits(waiting_commits), .pairs_tested(pairs_tested), .hits(hits),
        .m_axi_arid(arid), .m_axi_rid(1'b0), .m_axi_awid(awid), .m_axi_bid(1'b0),
        .m_axi_araddr(araddr), .m_axi_arlen(arlen), .m_axi_arsize(arsize),
        .m_axi_arburst(arburst), .m_axi_arcache(arcache), .m_axi_arprot(arprot),
        .m_axi_arvalid(arvalid), .m_axi_arready(arready), .m_axi_rdata(rdata),
        .m_axi_rresp(rresp), .m_axi_rlast(rlast), .m_axi_rvalid(rvalid),
        .m_axi_rready(rready), .m_axi_awaddr(awaddr), .m_axi_awlen(awlen),
        .m_axi_awsize(awsize), .m_axi_awburst(awburst), .m_axi_awcache(awcache),
        .m_axi_awprot(awprot), .m_axi_awvalid(awvalid), .m_axi_awready(awready),
        .m_axi_wdata(wdata), .m_axi_wstrb(wstrb), .m_axi_wlast(wlast),
        .m_axi_wvalid(wvalid), .m_axi_wready(wready), .m_axi_bresp(bresp),
        .m_axi_bvalid(bvalid), .m_axi_bready(bready)
    );

    tritri_axi_memory #(
        .DATA_BITS(DATA_BITS), .BYTES(BYTES), .READ_LATENCY(READ_LATENCY),
        .WRITE_LATENCY(WRITE_LATENCY), .OUTSTANDING(OUTSTANDING), .BPC_NUM(BPC_NUM),
        .BPC_DEN(BPC_DEN), .STALL_PERCENT(STALL_PERCENT), .SEED(SEED)
    ) memory (
        .clock(clock), .enable(enable),
        .araddr(araddr), .arlen(arlen), .arsize(arsize), .arburst(arburst),
        .arvalid(arvalid), .arready(arready), .rdata(rdata), .rresp(rresp),
        .rlast(rlast), .rvalid(rvalid), .rready(rready), .awaddr(awaddr),
        .awlen(awlen), .awsize(awsize), .awburst(awburst), .awvalid(awvalid),
        .awready(awready), .wdata(wdata), .wstrb(wstrb), .wlast(wlast),
        .wvalid(wvalid), .wready(wready), .bresp(bresp), .bvalid(bvalid),
        .bready(bready)
    );

    // The unused manager signals, folded into one bit on purpose.
    // verilator lint_off UNUSEDSIGNAL
    wire unused = ^{arcache, awcache, arprot, awprot, arid, awid};
    // verilator lint_on UNUSEDSIGNAL

    always #5 clock = ~clock;

    reg [1023:0] memory_file;
    initial begin
        if (!$value$plusargs("memory=%s", memory_file)) begin
            $display("error: +memory=FILE is required");
            $finish;
        end
        if (!$value$plusargs("corner_x=%d", corner_x)) corner_x = 0;
        if (!$value$plusargs("corner_y=%d", corner_y)) corner_y = 0;
        if (!$value$plusargs("corner_z=%d", corner_z)) corner_z = 0;
        if (!$value$plusargs("level=%d", level)) level = 1;
        if (!$value$plusargs("list_base_0=%d", list_base_0)) list_base_0 = 0;
        if (!$value$plusargs("list_base_1=%d", list_base_1)) list_base_1 = 0;
        if (!$value$plusargs("list_count_0=%d", list_count_0)) list_count_0 = 0;
        if (!$value$plusargs("list_count_1=%d", list_count_1)) list_count_1 = 0;
        if (!$value$plusargs("index_count_0=%d", index_count_0)) index_count_0 = 0;
        if (!$value$plusargs("index_count_1=%d", index_count_1)) index_count_1 = 0;
        if (!$value$plusargs("arena_start=%d", arena_start)) arena_start = 0;
        if (!$value$plusargs("arena_end=%d", arena_end)) arena_end = 0;
        $readmemh(memory_file, memory.mem);
        @(negedge clock);
        reset = 0;
        enable = 1;
        // The loop of cosim::dram_broad_phase::run_top_rusthdl: a pair is
        // taken in any clock, the flags looked at from clock 1. It ends in
        // the clock `done` rises, which `cycles` then counts (a flag, not
        // `break`, which Icarus does not take).
        cycles = 0;
        while (cycles < LIMIT && !finished) begin
            start = cycles == 0;
            #1;
            if (out_valid)
                $display("# pair %0d %0d %0d %0d %0d", cycles, out_index_a, out_index_b,
                         out_hit, out_certain);
            if (cycles > 0) begin
                if (binned && binned_at < 0) binned_at = cycles;
                if (tested && tested_at < 0) tested_at = cycles;
                if (done) finished = 1;
            end
            if (!finished) begin
                @(negedge clock);
                cycles = cycles + 1;
            end
        end
        $display("# binned %0d", binned_at);
        $display("# tested %0d", tested_at);
        $display("# cycles %0d stalled %0d faults %0d error %0d done %0d", cycles,
                 memory.stalled, memory.faults, error, done);
        $display("# counts leaves %0d passes %0d pairs_tested %0d hits %0d overflow %0d",
                 leaves, passes, pairs_tested, hits, overflow);
        $display("# memory beats_read %0d beats_written %0d", memory.beats_read,
                 memory.beats_written);
        $finish;
    end
endmodule
