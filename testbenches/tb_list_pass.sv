// tb_list_pass.sv — a cell's pass over lists in external memory, against
// the memory model.
//
// Purpose: loads the memory model (axi_memory.sv) from a hex file, starts
//   one pass of the list pass unit (tritri_rtl::broad_phase::list_pass), counts
//   its clocks and writes the memory back out, so the co-simulation
//   compares the children's lists, counts and cycles with the rust-hdl run
//   and the clock-exact model (tritri_rtl::broad_phase::list_pass_machine). It
//   runs in both Verilator 5.006 (`verilator --binary`) and Icarus
//   (iverilog -g2012).
//
// Parameters: GRID_BITS, the memory's (DATA_BITS, BYTES, READ_LATENCY,
//   WRITE_LATENCY, OUTSTANDING, BPC_NUM, BPC_DEN, STALL_PERCENT, SEED) and
//   LIMIT, the clocks to wait for done.
// Macros: TRITRI_DUT, the pass unit's module name (required).
// Plusargs: +memory=FILE (hex, a byte a line, required), +out=FILE (the
//   memory after the pass, required), +corner_x= +corner_y= +corner_z=
//   (the cell's low corner, as GRID_BITS-bit unsigned numbers), +level=,
//   and for k = 0, 1: +list_base_k= +list_count_k= +child_base_k=
//   +child_stride_k=.
//
// Clocks: one reset clock, then clock 0 presents start; "# cycles N": done
// is first high in clock N; "# counts" the sixteen children's entries.

`timescale 1ns / 1ps
`default_nettype none

module tb_list_pass #(
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
    reg [31:0] child_base_0 = 0, child_base_1 = 0, child_stride_0 = 0, child_stride_1 = 0;
    wire busy, done, error;
    wire [31:0] count [0:15];
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
        .child_base_0(child_base_0), .child_base_1(child_base_1),
        .child_stride_0(child_stride_0), .child_stride_1(child_stride_1),
        .busy(busy), .done(done), .error(error),
        .child_count_0(count[0]), .child_count_1(count[1]), .child_count_2(count[2]),
        .child_count_3(count[3]), .child_count_4(count[4]), .child_count_5(count[5]),
        .child_count_6(count[6]), .child_count_7(count[7]), .child_count_8(count[8]),
        .child_count_9(count[9]), .child_count_10(count[10]), .child_count_11(count[11]),
        .child_count_12(count[12]), .child_count_13(count[13]), .child_count_14(count[14]),
        .child_count_15(count[15]),
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
    wire unused = ^{busy, arcache, awcache, arprot, awprot, arid, awid};
    // verilator lint_on UNUSEDSIGNAL

    always #5 clock = ~clock;

    reg [1023:0] memory_file, out_file;
    integer cycles, i;
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
        if (!$value$plusargs("child_base_0=%d", child_base_0)) child_base_0 = 0;
        if (!$value$plusargs("child_base_1=%d", child_base_1)) child_base_1 = 0;
        if (!$value$plusargs("child_stride_0=%d", child_stride_0)) child_stride_0 = 0;
        if (!$value$plusargs("child_stride_1=%d", child_stride_1)) child_stride_1 = 0;
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
            @(negedge clock);
            cycles = cycles + 1;
        end
        $display("# cycles %0d stalled %0d faults %0d error %0d done %0d", cycles,
                 memory.stalled, memory.faults, error, done);
        $write("# counts");
        for (i = 0; i < 16; i = i + 1) $write(" %0d", count[i]);
        $write("\n");
        $writememh(out_file, memory.mem);
        $finish;
    end
endmodule
