// tritri_host_in: 32-bit host words in, one system word per triangle out.
// Part of examples/fpga-top (hand-written: copy and adapt it).
//
// Host words (see README.md, "Host words"):
//   header   bits [1:0] kind: 0 = triangle of A, 1 = triangle of B,
//            2 = end of batch, 3 = not a kind (counted in bad_words,
//            skipped); bits [31:2] must be 0 (else also a bad word)
//   then, after a header of kind 0 or 1, ten words:
//   id       the triangle's id, returned with each of its pairs
//   x0 y0 z0 x1 y1 z1 x2 y2 z2
//            32-bit two's complement, each within the W-bit range;
//            a value outside it is counted in range_errors and its low
//            W bits are used
//
// A complete triangle (or an end-of-batch header) becomes one word
// {end, object, id, x0 .. z2} on the out stream. s_ready is high while no
// finished word is waiting or the consumer takes it in this cycle, so a
// full-rate host loses no cycle between triangles.
`default_nettype none

module tritri_host_in #(
    parameter integer W = 16                       // coordinate width of the system
) (
    input  wire                  clock,
    input  wire                  reset,
    input  wire                  s_valid,
    output wire                  s_ready,
    input  wire [31:0]           s_data,
    output wire                  out_valid,
    input  wire                  out_ready,
    output wire [2+32+9*W-1:0]   out_data,
    output wire                  busy,           // a word is waiting or a triangle is half read
    output reg  [15:0]           bad_words,      // saturating counters
    output reg  [15:0]           range_errors
);
    localparam [1:0] KIND_B = 2'd1, KIND_END = 2'd2;   // kind 0 (A) is the default

    reg         pending;            // out_data holds a finished word
    reg  [3:0]  words_left;         // words of the current triangle still to come (0: expect a header)
    reg         end_flag;
    reg         object_flag;
    reg  [31:0] id;
    reg  [9*W-1:0] coordinates;     // x0 in the top W bits, z2 in the lowest

    assign out_valid = pending;
    assign out_data  = {end_flag, object_flag, id, coordinates};
    assign s_ready   = !pending || out_ready;
    assign busy      = pending || words_left != 4'd0;

    wire take = s_valid && s_ready;
    // A coordinate is in range when its bits above W - 1 repeat its sign bit.
    wire in_range = (W >= 32) ? 1'b1
                  : (s_data[31:W-1] == {(33 - W){1'b0}}) || (s_data[31:W-1] == {(33 - W){1'b1}});
    wire bad_header = (s_data[31:2] != 30'd0) || (s_data[1:0] == 2'd3);

    always @(posedge clock) begin
        if (reset) begin
            pending      <= 1'b0;
            words_left   <= 4'd0;
            bad_words    <= 16'd0;
            range_errors <= 16'd0;
        end else begin
            if (pending && out_ready)
                pending <= 1'b0;
            if (take) begin
                if (words_left == 4'd0) begin
                    if (bad_header) begin
                        if (bad_words != 16'hffff) bad_words <= bad_words + 16'd1;
                    end else if (s_data[1:0] == KIND_END) begin
                        end_flag    <= 1'b1;
                        object_flag <= 1'b0;
                        pending     <= 1'b1;
                    end else begin
                        end_flag    <= 1'b0;
                        object_flag <= s_data[1:0] == KIND_B;
                        words_left  <= 4'd10;
                    end
                end else begin
                    if (words_left == 4'd10)
                        id <= s_data;
                    else begin
                        coordinates <= {coordinates[8*W-1:0], s_data[W-1:0]};
                        if (!in_range && range_errors != 16'hffff)
                            range_errors <= range_errors + 16'd1;
                    end
                    words_left <= words_left - 4'd1;
                    if (words_left == 4'd1)
                        pending <= 1'b1;
                end
            end
        end
    end
endmodule

`default_nettype wire
