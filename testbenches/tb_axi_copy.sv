// tb_axi_copy.sv — the AXI copy unit against the memory model.
//
// Purpose: loads the memory model (axi_memory.sv) from a hex file, starts
//   one copy, counts its clocks and writes the memory back out, so the
//   co-simulation compares bytes and cycles with the rust-hdl run and the
//   clock-exact model (tritri_rtl::axi::transfer_machine). It runs in
//   both Verilator 5.006 (`verilator --binary`) and Icarus (iverilog -g2012).
//
// Parameters: the memory's (DATA_BITS, BYTES, READ_LATENCY, WRITE_LATENCY,
//   OUTSTANDING, BPC_NUM, BPC_DEN, STALL_PERCENT, SEED) and LIMIT, the
//   clocks to wait for done.
// Macros: TRITRI_DUT, the copy unit's module name (required).
// Plusargs: +memory=FILE (hex, a byte a line, required), +out=FILE (the
//   memory after the copy, required), +source=, +destination=, +beats=.
//
// Clocks: one reset clock, then clock 0 presents start; "# cycles N": done
// is first high in clock N.

`timescale 1ns / 1ps
`default_nettype none

module tb_axi_copy #(
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
    reg [31:0] source = 0, destination = 0, beats = 0;
    wire busy, done, error;
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
        .clock(clock), .reset(reset), .start(start), .source(source),
        .destination(destination), .beats(beats), .busy(busy), .done(done), .error(error),
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
    integer cycles;
    initial begin
        if (!$value$plusargs("memory=%s", memory_file)) begin
            $display("error: +memory=FILE is required");
            $finish;
        end
        if (!$value$plusargs("out=%s", out_file)) begin
            $display("error: +out=FILE is required");
            $finish;
        end
        if (!$value$plusargs("source=%d", source)) source = 0;
        if (!$value$plusargs("destination=%d", destination)) destination = 0;
        if (!$value$plusargs("beats=%d", beats)) beats = 0;
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
        $writememh(out_file, memory.mem);
        $finish;
    end
endmodule
