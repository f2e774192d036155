// tritri_sync_fifo: a first-word-fall-through FIFO on one clock, with
// valid/ready on both sides. Part of examples/fpga-top (hand-written, not
// generated: copy and adapt it).
//
// The head word is on out_data whenever out_valid is high; a word moves on
// a rising edge where valid and ready are both high. in_ready and out_valid
// come from registers only, so neither side sees a combinational path
// through the FIFO. The storage is read asynchronously, which maps to
// distributed (LUT) RAM on Xilinx and ECP5 parts; depths of a few dozen
// words are what it is for.
`default_nettype none

module tritri_sync_fifo #(
    parameter integer WIDTH      = 8,
    parameter integer LOG2_DEPTH = 4    // 2^LOG2_DEPTH words
) (
    input  wire             clock,
    input  wire             reset,      // synchronous, active high: empties the FIFO
    input  wire             in_valid,
    output wire             in_ready,
    input  wire [WIDTH-1:0] in_data,
    output wire             out_valid,
    input  wire             out_ready,
    output wire [WIDTH-1:0] out_data
);
    localparam integer DEPTH = 1 << LOG2_DEPTH;

    reg [WIDTH-1:0] storage [0:DEPTH-1];
    // One more bit than an address: equal pointers mean empty, pointers
    // that differ only in that bit mean full.
    reg [LOG2_DEPTH:0] write_pointer;
    reg [LOG2_DEPTH:0] read_pointer;

    wire empty = write_pointer == read_pointer;
    wire full  = (write_pointer[LOG2_DEPTH] != read_pointer[LOG2_DEPTH])
              && (write_pointer[LOG2_DEPTH-1:0] == read_pointer[LOG2_DEPTH-1:0]);

    assign in_ready  = !full;
    assign out_valid = !empty;
    assign out_data  = storage[read_pointer[LOG2_DEPTH-1:0]];

    always @(posedge clock) begin
        if (in_valid && !full)
            storage[write_pointer[LOG2_DEPTH-1:0]] <= in_data;
    end

    always @(posedge clock) begin
        if (reset) begin
            write_pointer <= {(LOG2_DEPTH + 1){1'b0}};
            read_pointer  <= {(LOG2_DEPTH + 1){1'b0}};
        end else begin
            if (in_valid && !full)
                write_pointer <= write_pointer + 1'b1;
            if (out_ready && !empty)
                read_pointer <= read_pointer + 1'b1;
        end
    end
endmodule

`default_nettype wire
