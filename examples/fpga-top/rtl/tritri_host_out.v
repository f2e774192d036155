// tritri_host_out: one pair (id_a, id_b) in, two 32-bit host words out.
// Part of examples/fpga-top (hand-written: copy and adapt it).
//
// Each pair leaves as id_a, then id_b with m_last high. The pair is taken
// from in_* when its second word is taken, so in_ready is high only in the
// cycle in which that happens.
`default_nettype none

module tritri_host_out (
    input  wire        clock,
    input  wire        reset,
    input  wire        in_valid,
    output wire        in_ready,
    input  wire [63:0] in_data,       // {id_a, id_b}
    output wire        m_valid,
    input  wire        m_ready,
    output wire [31:0] m_data,
    output wire        m_last
);
    reg second;                       // id_b is on m_data

    assign m_valid  = in_valid;
    assign m_data   = second ? in_data[31:0] : in_data[63:32];
    assign m_last   = second;
    assign in_ready = second && m_ready;

    always @(posedge clock) begin
        if (reset)
            second <= 1'b0;
        else if (m_valid && m_ready)
            second <= !second;
    end
endmodule

`default_nettype wire
