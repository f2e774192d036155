// tb_dram_binning.sv — the broad phase's binning with every list in
// external memory, against the memory model.
//
// Purpose: loads the memory model (axi_memory.sv) from a hex file, starts
//   the binning controller (tritri_rtl::broad_phase::dram_binning_unit) on the
//   root's lists, prints every leaf as it goes out, counts the clocks and
//   writes the memory back out, so the co-simulation compares the leaves,
//   clocks and memory with the rust-hdl run and the clock-exact model
//   (tritri_rtl::broad_phase::dram_binning_machine). It runs in both Verilator
//   5.006 (`verilator --binary`) and Icarus (iverilog -g2012).
//
// Parameters: GRID_BITS, the memory's (DATA_BITS, BYTES, READ_LATENCY,
//   WRITE_LATENCY, OUTSTANDING, BPC_NUM, BPC_DEN, STALL_PERCENT, SEED) and
//   LIMIT, the clocks to wait for done.
// Macros: TRITRI_DUT, the controller's module name (required).
// Plusargs: +memory=FILE (hex, a byte a line, required), +out=FILE (the
//   memory after the walk, required), +corner_x= +corner_y= +corner_z=
//   (the root's low corner, as GRID_BITS-bit unsigned numbers), +level=,
//   +list_base_k= +list_count_k= for k = 0, 1, +arena_start= +arena_end=.
//
// Clocks: one reset clock, then clock 0 presents start; "# leaf C X Y Z L
// B0 N0 B1 N1": a leaf out in clock C - 1 (C counts the clocks up to and
// including it, as the model's leaf clock does); "# cycles N": done is
// first high in clock N; "# passes P arena_full F commits C".

`timescale 1ns / 1ps
`default_nettype none

module tb_dram_binning #(
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
    parameter integer LIMIT = 10000000,
    // 1: push back on the controller with cosim::dram_binning::pushed_back's
    // pattern (a leaf refused one clock in three, a pass held three in seven).
    parameter integer PUSHBACK = 0
);
    reg clock = 0;
    reg reset = 1;
    reg enable = 0;
    reg start = 0;
    reg [GRID_BITS-1:0] corner_x = 0, corner_y = 0, corner_z = 0;
    reg [5:0] level = 1;
    reg [31:0] list_base_0 = 0, list_base_1 = 0, list_count_0 = 0, list_count_1 = 0;
    reg [31:0] arena_start = 0, arena_end = 0;
    wire done, error, leaf_valid;
    integer cycles = 0;
    // Functions of the clock, not wires read in the loop below: a wire
    // read just after `cycles` changes still shows the old clock's value.
    function automatic ready_at(input integer t);
        ready_at = (PUSHBACK == 0) || (t % 3 != 1);
    endfunction
    function automatic hold_at(input integer t);
        hold_at = (PUSHBACK != 0) && (t % 7 < 3);
    endfunction
    wire leaf_ready = ready_at(cycles);
    wire pass_hold = hold_at(cycles);
    wire [GRID_BITS-1:0] leaf_x, leaf_y, leaf_z;
    wire [5:0] leaf_level;
    wire [31:0] leaf_base_0, leaf_base_1, leaf_count_0, leaf_count_1, passes, arena_full;
    wire [31:0] waiting_commits;
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
        .arena_start(arena_start), .arena_end(arena_end),
        .done(done), .error(error), .waiting_commits(waiting_commits),
        .leaf_valid(leaf_valid), .leaf_ready(leaf_ready), .pass_hold(pass_hold), .leaf_x(leaf_x), .leaf_y(leaf_y), .leaf_z(leaf_z),
        .leaf_level(leaf_level), .leaf_base_0(leaf_base_0), .leaf_base_1(leaf_base_1),
        .leaf_count_0(leaf_count_0), .leaf_count_1(leaf_count_1),
        .passes(passes), .arena_full(arena_full),
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

    reg [1023:0] memory_file, out_file;
    initial begin
        if (!$value$plusargs("memory=%s", memory_file)) begin
            $display("error: +memory=FILE is required");
            $finish;
        end
        if (!$value$plusargs("out=%s", out_file)) begin
            $display("error: +out=FILE is required");
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
        if (!$value$plusargs("arena_start=%d", arena_start)) arena_start = 0;
        if (!$value$plusargs("arena_end=%d", arena_end)) arena_end = 0;
        $readmemh(memory_file, memory.mem);
        @(negedge clock);
        reset = 0;
        enable = 1;
        start = 1;
        cycles = 0;
        @(negedge clock);
        start = 0;
        cycles = 1;
        while (!done && cycles < LIMIT) begin
            if (leaf_valid && ready_at(cycles))
                $display("# leaf %0d %0d %0d %0d %0d %0d %0d %0d %0d", cycles + 1, leaf_x,
                         leaf_y, leaf_z, leaf_level, leaf_base_0, leaf_count_0, leaf_base_1,
                         leaf_count_1);
            @(negedge clock);
            cycles = cycles + 1;
        end
        $display("# cycles %0d stalled %0d faults %0d error %0d done %0d", cycles,
                 memory.stalled, memory.faults, error, done);
        $display("# passes %0d arena_full %0d commits %0d", passes, arena_full,
                 waiting_commits);
        $writememh(out_file, memory.mem);
        $finish;
    end
endmodule
