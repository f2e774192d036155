// tritri_control_regs: the accelerator's registers behind an AXI4-Lite
// subordinate port (32-bit data, byte addresses). Part of examples/fpga-top
// (hand-written; the register map is README.md's "Registers").
//
// One transaction at a time on each side: a write is taken when its address
// and its data are both valid and no response is waiting, a read when no
// read data is waiting. Addresses outside the map answer SLVERR (writes are
// dropped, reads give 0); the run's inputs are written only while the
// accelerator is not busy (a write while busy answers SLVERR and changes
// nothing), so that they hold still for the whole run as the emitted top
// requires.
`default_nettype none

module tritri_control_regs #(
    parameter integer G = 16  // the grid's width: the corner registers keep G bits
) (
    input  wire        clock,
    input  wire        reset,

    input  wire [7:0]  s_axil_awaddr,
    input  wire        s_axil_awvalid,
    output wire        s_axil_awready,
    input  wire [31:0] s_axil_wdata,
    input  wire [3:0]  s_axil_wstrb,
    input  wire        s_axil_wvalid,
    output wire        s_axil_wready,
    output reg  [1:0]  s_axil_bresp,
    output reg         s_axil_bvalid,
    input  wire        s_axil_bready,
    input  wire [7:0]  s_axil_araddr,
    input  wire        s_axil_arvalid,
    output wire        s_axil_arready,
    output reg  [31:0] s_axil_rdata,
    output reg  [1:0]  s_axil_rresp,
    output reg         s_axil_rvalid,
    input  wire        s_axil_rready,

    // The run's inputs, held while busy.
    output reg  [G-1:0] corner_x,
    output reg  [G-1:0] corner_y,
    output reg  [G-1:0] corner_z,
    output reg  [5:0]   level,
    output reg  [31:0]  list_base_0,
    output reg  [31:0]  list_count_0,
    output reg  [31:0]  index_count_0,
    output reg  [31:0]  list_base_1,
    output reg  [31:0]  list_count_1,
    output reg  [31:0]  index_count_1,
    output reg  [31:0]  arena_start,
    output reg  [31:0]  arena_end,
    // One clock high: CONTROL was written with bit 0 set while not busy.
    output reg          start,

    // What the registers read back.
    input  wire [31:0]  status,
    input  wire [31:0]  clocks,
    input  wire [31:0]  pairs_out,
    input  wire [31:0]  passes,
    input  wire [31:0]  leaves,
    input  wire [31:0]  pairs_tested,
    input  wire [31:0]  hits,
    input  wire [31:0]  arena_full,
    input  wire [31:0]  waiting_commits,
    input  wire         busy
);
    localparam [1:0] OKAY = 2'b00, SLVERR = 2'b10;
    // "TRTR": a read of ID tells the host it found the accelerator.
    localparam [31:0] MAGIC = 32'h5452_5452;

    // The run's inputs, as the host wrote them: word k at address 4 k
    // (k = 1 to 12, README.md's "Registers"); the outputs take their low bits.
    localparam integer INPUTS = 12;
    reg [31:0] inputs [1:INPUTS];
    always @* begin
        corner_x      = inputs[1][G-1:0];
        corner_y      = inputs[2][G-1:0];
        corner_z      = inputs[3][G-1:0];
        level         = inputs[4][5:0];
        list_base_0   = inputs[5];
        list_count_0  = inputs[6];
        index_count_0 = inputs[7];
        list_base_1   = inputs[8];
        list_count_1  = inputs[9];
        index_count_1 = inputs[10];
        arena_start   = inputs[11];
        arena_end     = inputs[12];
    end

    localparam [7:0] A_CONTROL = 8'h00, A_LAST_INPUT = 8'h30, A_CLOCKS = 8'h40,
                     A_PAIRS_OUT = 8'h44, A_PASSES = 8'h48, A_LEAVES = 8'h4c,
                     A_PAIRS_TESTED = 8'h50, A_HITS = 8'h54, A_ARENA_FULL = 8'h58,
                     A_WAITING_COMMITS = 8'h5c, A_ID = 8'h7c;

    // The input register an address names (0: none; unaligned addresses name none).
    function [3:0] input_at(input [7:0] address);
        input_at = (address[1:0] == 2'b00 && address != A_CONTROL && address <= A_LAST_INPUT)
                   ? address[5:2] : 4'd0;
    endfunction

    // A write: address and data together, no response waiting. CONTROL is
    // always writable, the inputs only while not busy.
    wire       write = s_axil_awvalid && s_axil_wvalid && !s_axil_bvalid;
    wire [3:0] written = input_at(s_axil_awaddr);
    wire       control = s_axil_awaddr == A_CONTROL;
    wire       taken = control || (written != 4'd0 && !busy);
    assign s_axil_awready = write;
    assign s_axil_wready  = write;

    // The written word merged into the old one, byte by byte (WSTRB).
    function [31:0] merged(input [31:0] old, input [31:0] data, input [3:0] strobe);
        integer k;
        begin
            for (k = 0; k < 4; k = k + 1)
                merged[8*k +: 8] = strobe[k] ? data[8*k +: 8] : old[8*k +: 8];
        end
    endfunction

    integer i;
    always @(posedge clock) begin
        start <= 1'b0;
        if (reset) begin
            s_axil_bvalid <= 1'b0;
            s_axil_bresp  <= OKAY;
            for (i = 1; i <= INPUTS; i = i + 1)
                inputs[i] <= 32'd0;
        end else begin
            if (s_axil_bvalid && s_axil_bready)
                s_axil_bvalid <= 1'b0;
            if (write) begin
                s_axil_bvalid <= 1'b1;
                s_axil_bresp  <= taken ? OKAY : SLVERR;
                if (control)
                    start <= s_axil_wstrb[0] && s_axil_wdata[0] && !busy;
                else if (taken)
                    inputs[written] <= merged(inputs[written], s_axil_wdata, s_axil_wstrb);
            end
        end
    end

    // A read: taken when no read data waits, answered the next clock.
    assign s_axil_arready = !s_axil_rvalid;
    wire [3:0] read = input_at(s_axil_araddr);

    always @(posedge clock) begin
        if (reset) begin
            s_axil_rvalid <= 1'b0;
            s_axil_rdata  <= 32'd0;
            s_axil_rresp  <= OKAY;
        end else begin
            if (s_axil_rvalid && s_axil_rready)
                s_axil_rvalid <= 1'b0;
            if (s_axil_arvalid && s_axil_arready) begin
                s_axil_rvalid <= 1'b1;
                s_axil_rresp  <= OKAY;
                if (read != 4'd0)
                    s_axil_rdata <= inputs[read];
                else
                    case (s_axil_araddr)
                        A_CONTROL:         s_axil_rdata <= status;
                        A_CLOCKS:          s_axil_rdata <= clocks;
                        A_PAIRS_OUT:       s_axil_rdata <= pairs_out;
                        A_PASSES:          s_axil_rdata <= passes;
                        A_LEAVES:          s_axil_rdata <= leaves;
                        A_PAIRS_TESTED:    s_axil_rdata <= pairs_tested;
                        A_HITS:            s_axil_rdata <= hits;
                        A_ARENA_FULL:      s_axil_rdata <= arena_full;
                        A_WAITING_COMMITS: s_axil_rdata <= waiting_commits;
                        A_ID:              s_axil_rdata <= MAGIC;
                        default: begin
                            s_axil_rdata <= 32'd0;
                            s_axil_rresp <= SLVERR;
                        end
                    endcase
            end
        end
    end
endmodule

`default_nettype wire
