// The AXI4 memory the co-simulations run the AXI units against: a byte
// array behind a subordinate port with a read latency, a write response
// latency, a limit on the bursts it holds per direction, a bandwidth and
// random stalls. It is tritri_rtl::axi::memory_model written again, clock
// for clock (the module docs there give the rules); the co-simulations hold
// the two to the same cycles. State moves only while `enable` is high, so
// the clocks of a reset do not count.
module tritri_axi_memory #(
    parameter integer DATA_BITS = 64,
    parameter integer BYTES = 65536,
    parameter integer READ_LATENCY = 20,
    parameter integer WRITE_LATENCY = 20,
    parameter integer OUTSTANDING = 64,
    parameter integer BPC_NUM = 16,
    parameter integer BPC_DEN = 1,
    parameter integer STALL_PERCENT = 0,
    parameter integer SEED = 1
) (
    input wire clock,
    input wire enable,
    input wire [31:0] araddr,
    input wire [7:0] arlen,
    input wire [2:0] arsize,
    input wire [1:0] arburst,
    input wire arvalid,
    output wire arready,
    output wire [DATA_BITS-1:0] rdata,
    output wire [1:0] rresp,
    output wire rlast,
    output wire rvalid,
    input wire rready,
    input wire [31:0] awaddr,
    input wire [7:0] awlen,
    input wire [2:0] awsize,
    input wire [1:0] awburst,
    input wire awvalid,
    output wire awready,
    input wire [DATA_BITS-1:0] wdata,
    input wire [DATA_BITS/8-1:0] wstrb,
    input wire wlast,
    input wire wvalid,
    output wire wready,
    output wire [1:0] bresp,
    output wire bvalid,
    input wire bready
);
    localparam integer BEAT = DATA_BITS / 8;
    localparam integer COST = BEAT * BPC_DEN;
    localparam integer QUEUE = 256;

    reg [7:0] mem [0:BYTES-1];

    reg [63:0] now = 0;
    reg [31:0] random = SEED;
    reg [63:0] bucket = 2 * COST;
    reg r_held = 0;
    reg [63:0] stalled = 0;
    reg [63:0] beats_read = 0;
    reg [63:0] beats_written = 0;
    reg [31:0] faults = 0;

    // Read bursts, write bursts and write responses: queues of QUEUE.
    reg [31:0] r_address [0:QUEUE-1];
    reg [31:0] r_left [0:QUEUE-1];
    reg [63:0] r_due [0:QUEUE-1];
    reg [7:0] r_head = 0, r_tail = 0;
    reg [8:0] r_count = 0;
    reg [31:0] w_address [0:QUEUE-1];
    reg [31:0] w_left [0:QUEUE-1];
    reg [7:0] w_head = 0, w_tail = 0;
    reg [8:0] w_count = 0;
    reg [63:0] b_due [0:QUEUE-1];
    reg [7:0] b_head = 0, b_tail = 0;
    reg [8:0] b_count = 0;

    wire stall = (random % 100) < STALL_PERCENT;
    wire read_due = (r_count != 0) && (now >= r_due[r_head]);
    assign rvalid = r_held || (read_due && bucket >= COST && !stall);
    assign rlast = rvalid && r_left[r_head] == 1;
    assign rresp = 2'b00;
    assign arready = (r_count < OUTSTANDING) && !stall;
    assign awready = (w_count < OUTSTANDING) && !stall;
    assign wready = (w_count != 0) && (bucket >= (rvalid ? 2 * COST : COST)) && !stall;
    assign bvalid = (b_count != 0) && (now >= b_due[b_head]);
    assign bresp = 2'b00;
    genvar i;
    generate
        for (i = 0; i < BEAT; i = i + 1) begin : beat_bytes
            assign rdata[8*i +: 8] = mem[r_address[r_head] + i];
        end
    endgenerate

    // A burst's fault: not INCR of full beats, unaligned, across 4 KB, or
    // past the end.
    function automatic integer burst_faults(input [31:0] address, input [7:0] length,
                                            input [2:0] size, input [1:0] burst);
        integer bytes, n;
        begin
            bytes = (length + 1) * BEAT;
            n = 0;
            if ((1 << size) != BEAT || burst != 2'b01) n = n + 1;
            if (address % BEAT != 0) n = n + 1;
            if (address / 4096 != (address + bytes - 1) / 4096) n = n + 1;
            if (address + bytes > BYTES) n = n + 1;
            burst_faults = n;
        end
    endfunction

    integer k;
    reg [63:0] level;
    reg [8:0] r_count_n, w_count_n, b_count_n;
    reg [31:0] x;
    reg [31:0] f;
    always @(posedge clock) if (enable) begin
        level = bucket;
        f = faults;
        r_count_n = r_count;
        w_count_n = w_count;
        b_count_n = b_count;
        if (arvalid && arready) begin
            f = f + burst_faults(araddr, arlen, arsize, arburst);
            r_address[r_tail] <= araddr;
            r_left[r_tail] <= arlen + 1;
            r_due[r_tail] <= now + READ_LATENCY;
            r_tail <= r_tail + 1;
            r_count_n = r_count_n + 1;
        end
        r_held <= rvalid && !rready;
        if (rvalid && rready) begin
            level = (level >= COST) ? level - COST : 0;
            beats_read <= beats_read + 1;
            r_address[r_head] <= r_address[r_head] + BEAT;
            r_left[r_head] <= r_left[r_head] - 1;
            if (r_left[r_head] == 1) begin
                r_head <= r_head + 1;
                r_count_n = r_count_n - 1;
            end
        end
        if (wvalid && wready) begin
            level = (level >= COST) ? level - COST : 0;
            beats_written <= beats_written + 1;
            for (k = 0; k < BEAT; k = k + 1)
                if (w_address[w_head] + k < BYTES) mem[w_address[w_head] + k] <= wdata[8*k +: 8];
            w_address[w_head] <= w_address[w_head] + BEAT;
            w_left[w_head] <= w_left[w_head] - 1;
            if ((w_left[w_head] == 1) != wlast) f = f + 1;
            if (w_left[w_head] == 1) begin
                w_head <= w_head + 1;
                w_count_n = w_count_n - 1;
                b_due[b_tail] <= now + WRITE_LATENCY;
                b_tail <= b_tail + 1;
                b_count_n = b_count_n + 1;
            end
        end
        if (awvalid && awready) begin
            f = f + burst_faults(awaddr, awlen, awsize, awburst);
            w_address[w_tail] <= awaddr;
            w_left[w_tail] <= awlen + 1;
            w_tail <= w_tail + 1;
            w_count_n = w_count_n + 1;
        end
        if (bvalid && bready) begin
            b_head <= b_head + 1;
            b_count_n = b_count_n - 1;
        end
        faults <= f;
        r_count <= r_count_n;
        w_count <= w_count_n;
        b_count <= b_count_n;
        if (stall) stalled <= stalled + 1;
        bucket <= (level + BPC_NUM < 2 * COST) ? level + BPC_NUM : 2 * COST;
        x = random;
        x = x ^ (x << 13);
        x = x ^ (x >> 17);
        x = x ^ (x << 5);
        random <= x;
        now <= now + 1;
    end
endmodule
