// tritri_fpga_top: a board-independent top level around the emitted
// collision system. Part of examples/fpga-top (hand-written: copy it into
// your design and connect the two streams to your host link: a UART, a
// PCIe or Ethernet DMA, an AXI4-Stream interconnect).
//
//   s_* host words ──► tritri_host_in ──► triangle FIFO ──► system
//                                                             │ pairs
//   m_* host words ◄── tritri_host_out ◄── pair FIFO ◄────────┘
//
// Both streams follow the valid/ready rules of README.md ("Streams"); the
// word formats are in README.md ("Host words") and in tritri_host_in.v.
//
// The system module's name carries its configuration (tritri gen --system
// --width W --pipelines P --depth D writes tritri_system_w<W>_p<P>_d<D>):
// define TRITRI_SYSTEM to the one you generated and set W to its width.
`default_nettype none

`ifndef TRITRI_SYSTEM
`define TRITRI_SYSTEM tritri_system_w16_p1_d64
`endif

module tritri_fpga_top #(
    parameter integer W                   = 16,  // the generated system's coordinate width
    parameter integer LOG2_TRIANGLE_FIFO  = 4,   // 16 triangles between the host and the system
    parameter integer LOG2_PAIR_FIFO      = 5    // 32 pairs between the system and the host
) (
    input  wire        clock,
    input  wire        reset,            // synchronous, active high, at least 2 cycles

    // Host words in: triangles and end-of-batch words.
    input  wire        s_valid,
    output wire        s_ready,
    input  wire [31:0] s_data,

    // Host words out: each reported pair as id_a, id_b, then its flags
    // (m_last; bit 0 hit, bit 1 certain). Pairs without a certificate come
    // out whatever their verdict: the host decides them again.
    output wire        m_valid,
    input  wire        m_ready,
    output wire [31:0] m_data,
    output wire        m_last,

    // Status.
    output wire        idle,             // every word taken is processed and every pair has left
    output wire        overflow,         // sticky: a batch had more triangles per object than the depth
    output wire [15:0] bad_words,        // headers that name no kind (skipped)
    output wire [15:0] range_errors,     // coordinates outside the W-bit range (low W bits used)
    output wire [31:0] pairs_tested,     // since reset; see the system's README
    output wire [31:0] hits,
    output wire [31:0] stall_cycles
);
    localparam integer TRIANGLE_BITS = 2 + 32 + 9 * W;

    // Host words to triangle words.
    wire                     words_valid, words_ready, host_in_busy;
    wire [TRIANGLE_BITS-1:0] words_data;
    tritri_host_in #(.W(W)) host_in (
        .clock(clock), .reset(reset),
        .s_valid(s_valid), .s_ready(s_ready), .s_data(s_data),
        .out_valid(words_valid), .out_ready(words_ready), .out_data(words_data),
        .busy(host_in_busy), .bad_words(bad_words), .range_errors(range_errors)
    );

    // Triangle FIFO: the host keeps writing while the system's write bank
    // is busy.
    wire                     triangle_valid, triangle_ready;
    wire [TRIANGLE_BITS-1:0] triangle;
    tritri_sync_fifo #(.WIDTH(TRIANGLE_BITS), .LOG2_DEPTH(LOG2_TRIANGLE_FIFO)) triangle_fifo (
        .clock(clock), .reset(reset),
        .in_valid(words_valid), .in_ready(words_ready), .in_data(words_data),
        .out_valid(triangle_valid), .out_ready(triangle_ready), .out_data(triangle)
    );

    // The emitted system. Its triangle word: {end, object, id, x0 .. z2}.
    wire        pair_valid, pair_ready, pair_hit, pair_certain;
    wire [31:0] pair_id_a, pair_id_b;
    wire        system_done, results_empty;
    `TRITRI_SYSTEM system (
        .clock(clock),
        .reset(reset),
        .in_valid(triangle_valid),
        .in_ready(triangle_ready),
        .in_end(triangle[TRIANGLE_BITS-1]),
        .in_object(triangle[TRIANGLE_BITS-2]),
        .in_id(triangle[9*W +: 32]),
        .in_x0(triangle[8*W +: W]), .in_y0(triangle[7*W +: W]), .in_z0(triangle[6*W +: W]),
        .in_x1(triangle[5*W +: W]), .in_y1(triangle[4*W +: W]), .in_z1(triangle[3*W +: W]),
        .in_x2(triangle[2*W +: W]), .in_y2(triangle[1*W +: W]), .in_z2(triangle[0*W +: W]),
        .out_valid(pair_valid),
        .out_ready(pair_ready),
        .out_id_a(pair_id_a),
        .out_id_b(pair_id_b),
        .out_hit(pair_hit),
        .out_certain(pair_certain),
        .done(system_done),
        .results_empty(results_empty),
        .overflow(overflow),
        .pairs_tested(pairs_tested),
        .hits(hits),
        .stall_cycles(stall_cycles)
    );

    // Pair FIFO: a slow host link does not stall the pipelines until both
    // this FIFO and the system's own result FIFO are full.
    wire        queued_valid, queued_ready;
    wire [65:0] queued_pair;
    tritri_sync_fifo #(.WIDTH(66), .LOG2_DEPTH(LOG2_PAIR_FIFO)) pair_fifo (
        .clock(clock), .reset(reset),
        .in_valid(pair_valid), .in_ready(pair_ready), .in_data({pair_certain, pair_hit, pair_id_a, pair_id_b}),
        .out_valid(queued_valid), .out_ready(queued_ready), .out_data(queued_pair)
    );

    tritri_host_out host_out (
        .clock(clock), .reset(reset),
        .in_valid(queued_valid), .in_ready(queued_ready), .in_data(queued_pair),
        .m_valid(m_valid), .m_ready(m_ready), .m_data(m_data), .m_last(m_last)
    );

    assign idle = !host_in_busy && !triangle_valid && system_done && results_empty && !queued_valid;
endmodule

`default_nettype wire
