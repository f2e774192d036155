// tritri_host_out: one pair (id_a, id_b, hit, certain) in, three 32-bit
// host words out. Part of examples/fpga-top (hand-written: copy and adapt
// it).
//
// Each pair leaves as id_a, id_b, then its flags with m_last high (bit 0
// hit, bit 1 certain: the system's out_hit and out_certain). The pair is
// taken from in_* when its last word is taken, so in_ready is high only
// in the cycle in which that happens.
`default_nettype none

module tritri_host_out (
    input  wire        clock,
    input  wire        reset,
    input  wire        in_valid,
    output wire        in_ready,
    input  wire [65:0] in_data,       // {certain, hit, id_a, id_b}
    output wire        m_valid,
    input  wire        m_ready,
    output wire [31:0] m_data,
    output wire        m_last
);
    reg [1:0] word;                   // 0: id_a, 1: id_b, 2: the flags

    assign m_valid  = in_valid;
    assign m_data   = word == 2'd0 ? in_data[63:32]
                    : word == 2'd1 ? in_data[31:0]
                    : {30'd0, in_data[65:64]};
    assign m_last   = word == 2'd2;
    assign in_ready = m_last && m_ready;

    always @(posedge clock) begin
        if (reset)
            word <= 2'd0;
        else if (m_valid && m_ready)
            word <= m_last ? 2'd0 : word + 2'd1;
    end
endmodule

`default_nettype wire
