// tb_fpga_top: a self-checking test of tritri_fpga_top in Icarus Verilog 11
// (iverilog -g2012) and Verilator 5 (--binary). Part of examples/fpga-top.
//
// It plays a host that offers a word in about three cycles of four and a
// reader that is ready in about one cycle of two, sends two batches (the
// second written while the first is tested), and checks:
//   - the pairs that come out with hit = 1 are exactly the five the exact
//     model gives for these triangles (tritri classify --arith exact,
//     README.md), each once; a pair with hit = 0 has certain = 0 (the
//     system reports a non-intersecting pair only for the host to decide
//     again); every pair is id_a, id_b, then the flags with m_last;
//   - the counters: 2 x 6 + 1 x 2 = 14 pairs tested, 5 hits, no overflow;
//   - a header of kind 3 and a coordinate outside 16 bits are counted, and
//     they change no pair.
// It ends with "PASS" or with $fatal.
`timescale 1ns / 1ps
`default_nettype none

module tb_fpga_top;
    localparam integer W = 16;
    localparam integer MAX_WORDS = 256;
    localparam integer TIMEOUT = 20000;

    reg clock = 1'b0;
    always #5 clock = !clock;
    reg reset = 1'b1;

    reg         s_valid = 1'b0;
    wire        s_ready;
    reg  [31:0] s_data = 32'd0;
    wire        m_valid, m_last;
    reg         m_ready = 1'b0;
    wire [31:0] m_data;
    wire        idle, overflow;
    wire [15:0] bad_words, range_errors;
    wire [31:0] pairs_tested, hits, stall_cycles;

    tritri_fpga_top #(.W(W)) dut (
        .clock(clock), .reset(reset),
        .s_valid(s_valid), .s_ready(s_ready), .s_data(s_data),
        .m_valid(m_valid), .m_ready(m_ready), .m_data(m_data), .m_last(m_last),
        .idle(idle), .overflow(overflow), .bad_words(bad_words), .range_errors(range_errors),
        .pairs_tested(pairs_tested), .hits(hits), .stall_cycles(stall_cycles)
    );

    // The host's words, filled by the tasks below.
    reg [31:0] words [0:MAX_WORDS-1];
    integer word_count = 0;

    task put(input [31:0] word);
        begin
            words[word_count] = word;
            word_count = word_count + 1;
        end
    endtask

    // kind 0: a triangle of A, 1: of B.
    task triangle(input integer kind, input integer id,
                  input integer x0, input integer y0, input integer z0,
                  input integer x1, input integer y1, input integer z1,
                  input integer x2, input integer y2, input integer z2);
        begin
            put(kind); put(id);
            put(x0); put(y0); put(z0); put(x1); put(y1); put(z1); put(x2); put(y2); put(z2);
        end
    endtask

    task end_of_batch;
        put(32'd2);
    endtask

    // Ids: A triangles 100 + k, B triangles 200 + k.
    // Batch 1, in the plane z = 0 and around it.
    // Batch 2, at the ends of the 16-bit range.
    // Expected pairs (the exact model): (100, 200) crossing, (100, 201)
    // coplanar and touching at one point, (101, 202) touching at a shared
    // vertex, (101, 204) a point-triangle on an edge, (110, 210) crossing
    // near the corner of the range.
    localparam integer EXPECTED = 5;
    reg [31:0] expected_a [0:EXPECTED-1];
    reg [31:0] expected_b [0:EXPECTED-1];
    reg        seen       [0:EXPECTED-1];

    integer sent = 0;            // words accepted by the DUT
    integer pairs = 0;
    integer cycle = 0;
    reg [31:0] first_id, second_id;
    integer    word_of_pair = 0;  // the next word: 0 id_a, 1 id_b, 2 flags
    integer    uncertain = 0;     // pairs with certain = 0
    integer k;
    reg found;

    // The host: offers the next word in about 3 cycles of 4 and, once it
    // offers a word, holds it until it is taken (rule 2 of README.md).
    always @(posedge clock) begin
        cycle <= cycle + 1;
        if (!reset) begin
            if (s_valid && s_ready)
                sent = sent + 1;
            if (!(s_valid && !s_ready)) begin
                if (sent < word_count && ($random & 3) != 0) begin
                    s_valid <= 1'b1;
                    s_data  <= words[sent];
                end else
                    s_valid <= 1'b0;
            end
            m_ready <= $random & 1;
        end
    end

    // The reader: pairs are id_a, id_b, flags (m_last); each expected pair
    // once with hit = 1.
    always @(posedge clock) begin
        if (!reset && m_valid && m_ready) begin
            if (m_last != (word_of_pair == 2)) $fatal(1, "m_last on word %0d of a pair", word_of_pair);
            if (word_of_pair == 0) first_id = m_data;
            if (word_of_pair == 1) second_id = m_data;
            if (word_of_pair == 2) begin
                if (m_data[31:2] != 0) $fatal(1, "flags word %h", m_data);
                if (!m_data[1]) uncertain = uncertain + 1;
                if (m_data[0]) begin
                    found = 1'b0;
                    for (k = 0; k < EXPECTED; k = k + 1)
                        if (expected_a[k] == first_id && expected_b[k] == second_id) begin
                            if (seen[k]) $fatal(1, "pair (%0d, %0d) reported twice", first_id, second_id);
                            seen[k] = 1'b1;
                            found = 1'b1;
                        end
                    if (!found) $fatal(1, "pair (%0d, %0d) is not an intersecting pair", first_id, second_id);
                    pairs = pairs + 1;
                end else if (m_data[1])
                    $fatal(1, "pair (%0d, %0d) reported with hit = 0 and certain = 1", first_id, second_id);
                $display("pair %0d %0d hit %0d certain %0d (cycle %0d)", first_id, second_id, m_data[0], m_data[1], cycle);
            end
            word_of_pair = (word_of_pair + 1) % 3;
        end
    end

    task wait_idle;
        integer waited;
        begin
            waited = 0;
            // idle is checked once every word is taken; it needs the
            // system to have tested every batch and the host to have read
            // every pair.
            while (!(sent == word_count && !s_valid && idle)) begin
                @(posedge clock);
                waited = waited + 1;
                if (waited > TIMEOUT) $fatal(1, "not idle after %0d cycles", TIMEOUT);
            end
        end
    endtask

    initial begin
        triangle(0, 100,    0,   0,   0,  100,   0,   0,    0, 100,   0);
        triangle(0, 101,  200, 200,   0,  300, 200,   0,  200, 300,   0);
        triangle(1, 200,   10,  10, -50,   10,  10,  50,   60,  20,   0);
        triangle(1, 201,   50,  50,   0,  150,  50,   0,   50, 150,   0);
        triangle(1, 202,  300, 200,   0,  350, 250,  40,  320, 180,  60);
        triangle(1, 203,  500, 500, 500,  600, 500, 500,  500, 600, 500);
        triangle(1, 204,  250, 200,   0,  250, 200,   0,  250, 200,   0);
        triangle(1, 205,  -10, -10,  -5,  -10, -10,   5,  -10, -10,   0);
        end_of_batch;
        triangle(0, 110, -32768, -32768, 0,  32767, -32768, 0,  -32768, 32767, 0);
        triangle(1, 210,  -1, -1, -32768,  -1, -1, 32767,  0, 0, 0);
        triangle(1, 211,   0,  0, -32768,   0,  0, 32767,  1, 1, 0);
        end_of_batch;
        expected_a[0] = 100; expected_b[0] = 200;
        expected_a[1] = 100; expected_b[1] = 201;
        expected_a[2] = 101; expected_b[2] = 202;
        expected_a[3] = 101; expected_b[3] = 204;
        expected_a[4] = 110; expected_b[4] = 210;
        for (k = 0; k < EXPECTED; k = k + 1) seen[k] = 1'b0;

        repeat (2) @(posedge clock);
        reset <= 1'b0;
        wait_idle;
        if (pairs != EXPECTED) $fatal(1, "%0d pairs, expected %0d", pairs, EXPECTED);
        if (pairs_tested != 14) $fatal(1, "pairs_tested %0d, expected 14", pairs_tested);
        if (hits != EXPECTED) $fatal(1, "hits %0d, expected %0d", hits, EXPECTED);
        if (overflow || bad_words != 0 || range_errors != 0)
            $fatal(1, "overflow %0d, bad_words %0d, range_errors %0d", overflow, bad_words, range_errors);
        $display("two batches: %0d pairs, %0d without a certificate, %0d pairs tested, %0d stall cycles, idle at cycle %0d",
                 pairs, uncertain, pairs_tested, stall_cycles, cycle);

        // Mistakes a host can make: a header of no kind, a coordinate
        // outside the W-bit range (the batch has no B, so no pair).
        put(32'd3);
        triangle(0, 120,  40000, 0, 0,  0, 0, 0,  0, 1, 0);
        end_of_batch;
        wait_idle;
        if (bad_words != 1 || range_errors != 1)
            $fatal(1, "bad_words %0d, range_errors %0d, expected 1 and 1", bad_words, range_errors);
        if (pairs != EXPECTED || pairs_tested != 14)
            $fatal(1, "a bad word changed the pairs: %0d pairs, %0d tested", pairs, pairs_tested);
        $display("PASS");
        $finish;
    end
endmodule

`default_nettype wire
