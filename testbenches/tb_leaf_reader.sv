// tb_leaf_reader.sv — a leaf's lists read back from external memory, against
// the memory model.
//
// Purpose: loads the memory model (axi_memory.sv) from a hex file, starts
//   the leaf reader (tritri_rtl::broad_phase::leaf_reader) on one leaf, takes its
//   stream with a fixed pattern of out_ready and prints every word taken and
//   the clocks, so the co-simulation compares them with the rust-hdl run and
//   the clock-exact model (tritri_rtl::broad_phase::leaf_reader_machine). It runs
//   in both Verilator 5.006 (`verilator --binary`) and Icarus (iverilog
//   -g2012).
//
// Parameters: GRID_BITS, the memory's (DATA_BITS, BYTES, READ_LATENCY,
//   WRITE_LATENCY, OUTSTANDING, BPC_NUM, BPC_DEN, STALL_PERCENT, SEED),
//   READY_TENTHS (out_ready in clock t is ((7 t + 3) mod 10) < READY_TENTHS:
//   10 always) and LIMIT, the clocks to wait for busy to fall.
// Macros: TRITRI_DUT, the leaf reader's module name (required).
// Plusargs: +memory=FILE (hex, a byte a line, required), +corner_x=
//   +corner_y= +corner_z= (the leaf's low corner, as GRID_BITS-bit unsigned
//   numbers), +level=, and for k = 0, 1: +list_base_k= +list_count_k=.
//
// Clocks: one reset clock, then clock 0 presents start. "# header T X Y Z
//   LEVEL A B" and "# entry T OBJECT INDEX VERTICES" (hex) for each word
//   taken in clock T; "# read N": reading is first low in clock N; "# cycles
//   N": busy is first low in clock N (done is 1 then).

`timescale 1ns / 1ps
`default_nettype none

module tb_leaf_reader #(
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
    parameter integer READY_TENTHS = 10,
    parameter integer LIMIT = 10000000
);
    reg clock = 0;
    reg reset = 1;
    reg enable = 0;
    reg start = 0;
    reg out_ready = 0;
    reg [GRID_BITS-1:0] corner_x = 0, corner_y = 0, corner_z = 0;
    reg [5:0] level = 1;
    reg [31:0] list_base_0 = 0, list_base_1 = 0, list_count_0 = 0, list_count_1 = 0;
    wire busy, reading, error;
    wire out_valid, out_header, out_object;
    wire [31:0] out_index, out_count_a, out_count_b;
    wire [9*GRID_BITS-1:0] out_vertices;
    wire [GRID_BITS-1:0] out_x, out_y, out_z;
    wire [5:0] out_level;
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
        .busy(busy), .reading(reading), .error(error),
        .out_valid(out_valid), .out_ready(out_ready), .out_header(out_header),
        .out_object(out_object), .out_index(out_index), .out_vertices(out_vertices),
        .out_x(out_x), .out_y(out_y), .out_z(out_z), .out_level(out_level),
        .out_count_a(out_count_a), .out_count_b(out_count_b),
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

    function automatic ready_in(input integer t);
        ready_in = ((7 * t + 3) % 10) < READY_TENTHS;
    endfunction

    reg [1023:0] memory_file;
    integer cycles, read_cycles;
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
        $readmemh(memory_file, memory.mem);
        @(negedge clock);
        reset = 0;
        enable = 1;
        start = 1;
        cycles = 0;
        read_cycles = -1;
        // Each clock: the inputs set after the falling edge, the word taken
        // at the rising edge logged here, before it.
        while ((cycles == 0 || busy) && cycles < LIMIT) begin
            if (cycles > 0 && !reading && read_cycles < 0) read_cycles = cycles;
            out_ready = ready_in(cycles);
            #1;
            if (out_valid && out_ready) begin
                if (out_header)
                    $display("# header %0d %0d %0d %0d %0d %0d %0d", cycles, out_x, out_y, out_z,
                             out_level, out_count_a, out_count_b);
                else
                    $display("# entry %0d %0d %0d %h", cycles, out_object, out_index, out_vertices);
            end
            @(negedge clock);
            start = 0;
            cycles = cycles + 1;
        end
        if (cycles > 0 && !reading && read_cycles < 0) read_cycles = cycles;
        $display("# read %0d", read_cycles);
        $display("# cycles %0d stalled %0d faults %0d error %0d done %0d", cycles,
                 memory.stalled, memory.faults, error, !busy);
        $finish;
    end
endmodule
