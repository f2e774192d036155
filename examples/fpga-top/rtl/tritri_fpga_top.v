// tritri_fpga_top: a board-independent top level around the broad-phase
// accelerator with its scene in DRAM (tritri gen --dram-broad-phase). Part
// of examples/fpga-top (hand-written: copy it into your design).
//
// It has the shape of an accelerator kernel in a Xilinx, Intel or LiteX SoC:
//
//   host (CPU, PCIe) ── AXI4-Lite ──► tritri_control_regs ──► the run's inputs, start
//                                                               │
//   DRAM controller ◄──── AXI4 (m_axi_*, DATA_BITS) ──── emitted accelerator
//   (MIG, LiteDRAM, EMIF)                                       │ pairs
//   host (DMA S2MM) ◄── AXI4-Stream (m_axis_*, 64 bits) ◄────────┘
//
// * The host writes the scene (each object's root list, README.md "Scene
//   memory") into DRAM by its own path, writes the registers, and writes 1
//   to CONTROL.
// * Each intersecting pair, and each pair without a certificate, leaves
//   once on the stream as one 64-bit word: index_a in bits 31:0, index_b in
//   61:32, certain in 62, hit in 63 (the indices are the triangles'
//   places in the root lists). After the last pair, one word with TLAST:
//   the run's clocks in bits 31:0 and its pair words in 63:32. A DMA that
//   ends its transfer at TLAST gets one packet per run.
// * Status and the run's counters read back over AXI4-Lite.
//
// The accelerator's module name carries its configuration; define
// TRITRI_DRAM_TOP to the one you generated, and set G and DATA_BITS to its
// grid width and port width.
`default_nettype none

`ifndef TRITRI_DRAM_TOP
`define TRITRI_DRAM_TOP tritri_dram_broad_phase_g16_w16_d256_p1_t256_i8192_s8192_shared
`endif

module tritri_fpga_top #(
    parameter integer G         = 16,   // the grid's width (tritri gen --width)
    parameter integer DATA_BITS = 256   // the AXI4 port's data width (--data-bits)
) (
    input  wire                   clock,
    input  wire                   reset,          // synchronous, active high

    // Registers (AXI4-Lite subordinate, 32-bit data, byte addresses).
    input  wire [7:0]             s_axil_awaddr,
    input  wire [2:0]             s_axil_awprot,
    input  wire                   s_axil_awvalid,
    output wire                   s_axil_awready,
    input  wire [31:0]            s_axil_wdata,
    input  wire [3:0]             s_axil_wstrb,
    input  wire                   s_axil_wvalid,
    output wire                   s_axil_wready,
    output wire [1:0]             s_axil_bresp,
    output wire                   s_axil_bvalid,
    input  wire                   s_axil_bready,
    input  wire [7:0]             s_axil_araddr,
    input  wire [2:0]             s_axil_arprot,
    input  wire                   s_axil_arvalid,
    output wire                   s_axil_arready,
    output wire [31:0]            s_axil_rdata,
    output wire [1:0]             s_axil_rresp,
    output wire                   s_axil_rvalid,
    input  wire                   s_axil_rready,

    // Pairs (AXI4-Stream manager).
    output reg  [63:0]            m_axis_tdata,
    output reg                    m_axis_tlast,
    output reg                    m_axis_tvalid,
    input  wire                   m_axis_tready,

    // Scene memory (AXI4 manager, to the DRAM controller).
    output wire                   m_axi_arid,
    output wire [31:0]            m_axi_araddr,
    output wire [7:0]             m_axi_arlen,
    output wire [2:0]             m_axi_arsize,
    output wire [1:0]             m_axi_arburst,
    output wire [3:0]             m_axi_arcache,
    output wire [2:0]             m_axi_arprot,
    output wire                   m_axi_arvalid,
    input  wire                   m_axi_arready,
    input  wire                   m_axi_rid,
    input  wire [DATA_BITS-1:0]   m_axi_rdata,
    input  wire [1:0]             m_axi_rresp,
    input  wire                   m_axi_rlast,
    input  wire                   m_axi_rvalid,
    output wire                   m_axi_rready,
    output wire                   m_axi_awid,
    output wire [31:0]            m_axi_awaddr,
    output wire [7:0]             m_axi_awlen,
    output wire [2:0]             m_axi_awsize,
    output wire [1:0]             m_axi_awburst,
    output wire [3:0]             m_axi_awcache,
    output wire [2:0]             m_axi_awprot,
    output wire                   m_axi_awvalid,
    input  wire                   m_axi_awready,
    output wire [DATA_BITS-1:0]   m_axi_wdata,
    output wire [DATA_BITS/8-1:0] m_axi_wstrb,
    output wire                   m_axi_wlast,
    output wire                   m_axi_wvalid,
    input  wire                   m_axi_wready,
    input  wire                   m_axi_bid,
    input  wire [1:0]             m_axi_bresp,
    input  wire                   m_axi_bvalid,
    output wire                   m_axi_bready,

    // For LEDs: a run is under way; the last run ended with an error
    // response or an overflow (README.md, "Status").
    output wire                   busy,
    output wire                   fault
);
    // ---- Registers.
    wire [G-1:0] corner_x, corner_y, corner_z;
    wire [5:0]   level;
    wire [31:0]  list_base_0, list_count_0, index_count_0;
    wire [31:0]  list_base_1, list_count_1, index_count_1;
    wire [31:0]  arena_start, arena_end;
    wire         start;
    wire [31:0]  status;
    reg  [31:0]  clocks, pairs_out;
    wire [31:0]  passes, arena_full, waiting_commits, pairs_tested, hits;
    wire [19:0]  leaves;

    tritri_control_regs #(.G(G)) regs (
        .clock(clock), .reset(reset),
        .s_axil_awaddr(s_axil_awaddr), .s_axil_awvalid(s_axil_awvalid),
        .s_axil_awready(s_axil_awready), .s_axil_wdata(s_axil_wdata),
        .s_axil_wstrb(s_axil_wstrb), .s_axil_wvalid(s_axil_wvalid),
        .s_axil_wready(s_axil_wready), .s_axil_bresp(s_axil_bresp),
        .s_axil_bvalid(s_axil_bvalid), .s_axil_bready(s_axil_bready),
        .s_axil_araddr(s_axil_araddr), .s_axil_arvalid(s_axil_arvalid),
        .s_axil_arready(s_axil_arready), .s_axil_rdata(s_axil_rdata),
        .s_axil_rresp(s_axil_rresp), .s_axil_rvalid(s_axil_rvalid),
        .s_axil_rready(s_axil_rready),
        .corner_x(corner_x), .corner_y(corner_y), .corner_z(corner_z), .level(level),
        .list_base_0(list_base_0), .list_count_0(list_count_0), .index_count_0(index_count_0),
        .list_base_1(list_base_1), .list_count_1(list_count_1), .index_count_1(index_count_1),
        .arena_start(arena_start), .arena_end(arena_end), .start(start),
        .status(status), .clocks(clocks), .pairs_out(pairs_out), .passes(passes),
        .leaves({12'd0, leaves}), .pairs_tested(pairs_tested), .hits(hits),
        .arena_full(arena_full), .waiting_commits(waiting_commits), .busy(busy)
    );

    // ---- The emitted accelerator.
    wire        out_valid, out_ready, out_hit, out_certain;
    wire [31:0] out_index_a, out_index_b;
    wire        binned, tested, done, error, overflow;

    `TRITRI_DRAM_TOP accelerator (
        .clock(clock), .reset(reset), .start(start),
        .corner_x(corner_x), .corner_y(corner_y), .corner_z(corner_z), .level(level),
        .list_base_0(list_base_0), .list_base_1(list_base_1),
        .list_count_0(list_count_0), .list_count_1(list_count_1),
        .index_count_0(index_count_0), .index_count_1(index_count_1),
        .arena_start(arena_start), .arena_end(arena_end),
        .out_valid(out_valid), .out_ready(out_ready),
        .out_index_a(out_index_a), .out_index_b(out_index_b),
        .out_hit(out_hit), .out_certain(out_certain),
        .binned(binned), .tested(tested), .done(done), .error(error), .overflow(overflow),
        .passes(passes), .leaves(leaves), .arena_full(arena_full),
        .waiting_commits(waiting_commits), .pairs_tested(pairs_tested), .hits(hits),
        .m_axi_arid(m_axi_arid), .m_axi_araddr(m_axi_araddr), .m_axi_arlen(m_axi_arlen),
        .m_axi_arsize(m_axi_arsize), .m_axi_arburst(m_axi_arburst),
        .m_axi_arcache(m_axi_arcache), .m_axi_arprot(m_axi_arprot),
        .m_axi_arvalid(m_axi_arvalid), .m_axi_arready(m_axi_arready),
        .m_axi_rid(m_axi_rid), .m_axi_rdata(m_axi_rdata), .m_axi_rresp(m_axi_rresp),
        .m_axi_rlast(m_axi_rlast), .m_axi_rvalid(m_axi_rvalid), .m_axi_rready(m_axi_rready),
        .m_axi_awid(m_axi_awid), .m_axi_awaddr(m_axi_awaddr), .m_axi_awlen(m_axi_awlen),
        .m_axi_awsize(m_axi_awsize), .m_axi_awburst(m_axi_awburst),
        .m_axi_awcache(m_axi_awcache), .m_axi_awprot(m_axi_awprot),
        .m_axi_awvalid(m_axi_awvalid), .m_axi_awready(m_axi_awready),
        .m_axi_wdata(m_axi_wdata), .m_axi_wstrb(m_axi_wstrb), .m_axi_wlast(m_axi_wlast),
        .m_axi_wvalid(m_axi_wvalid), .m_axi_wready(m_axi_wready),
        .m_axi_bid(m_axi_bid), .m_axi_bresp(m_axi_bresp), .m_axi_bvalid(m_axi_bvalid),
        .m_axi_bready(m_axi_bready)
    );

    // ---- The run: from start until its last word has left on the stream.
    // `running` until the accelerator's done (it falls the clock after
    // start, so it is read from the next clock on), then `closing` until
    // the TLAST word is taken.
    reg running, closing, ended_badly;
    assign busy   = running || closing;
    assign fault  = ended_badly;
    // CONTROL reads: bit 0 busy, 1 done (the last run ended), 2 error,
    // 3 overflow, 4 binned, 5 tested.
    assign status = {26'd0, tested, binned, overflow, error, done && !busy, busy};

    // The stream's register: the accelerator's pair moves in when the
    // register is empty or its word is being taken.
    wire stage_free = !m_axis_tvalid || m_axis_tready;
    assign out_ready = stage_free;
    wire take_pair = out_valid && stage_free;
    wire take_end  = closing && !out_valid && stage_free && !(m_axis_tvalid && m_axis_tlast);

    always @(posedge clock) begin
        if (reset) begin
            running       <= 1'b0;
            closing       <= 1'b0;
            ended_badly   <= 1'b0;
            clocks        <= 32'd0;
            pairs_out     <= 32'd0;
            m_axis_tvalid <= 1'b0;
            m_axis_tlast  <= 1'b0;
            m_axis_tdata  <= 64'd0;
        end else begin
            if (start) begin
                running     <= 1'b1;
                ended_badly <= 1'b0;
                clocks      <= 32'd0;
                pairs_out   <= 32'd0;
            end else if (running) begin
                clocks <= clocks + 32'd1;
                if (done) begin
                    running     <= 1'b0;
                    closing     <= 1'b1;
                    ended_badly <= error || overflow;
                end
            end
            if (m_axis_tvalid && m_axis_tready) begin
                m_axis_tvalid <= 1'b0;
                if (m_axis_tlast)
                    closing <= 1'b0;
            end
            if (take_pair) begin
                m_axis_tvalid <= 1'b1;
                m_axis_tlast  <= 1'b0;
                m_axis_tdata  <= {out_hit, out_certain, out_index_b[29:0], out_index_a};
                pairs_out     <= pairs_out + 32'd1;
            end else if (take_end) begin
                m_axis_tvalid <= 1'b1;
                m_axis_tlast  <= 1'b1;
                m_axis_tdata  <= {pairs_out, clocks};
            end
        end
    end

    // AXI4-Lite's protection bits are accepted and ignored, as the unused
    // high bits of index_b: the lists' indices stay below 2^30.
    wire unused = &{1'b0, s_axil_awprot, s_axil_arprot, out_index_b[31:30]};
endmodule

`default_nettype wire
