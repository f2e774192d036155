"""cocotb test of the broad-phase accelerator with its scene in DRAM
(`tritri gen --dram-broad-phase`, the design that fits the ECP5-85) against
cocotbext-axi's AxiRam, a memory written by other people: the host's root
lists are written into the RAM, the top is started, and the pairs it
streams must be the ones the case lists (the exact answer on the grid,
which the Verilator co-simulation against the project's own memory model
gave), each once. The second test pauses AxiRam's channels at random.

The case (`CASE_DIR`) comes from `dram_broad_phase --write-case`
(examples/dram_broad_phase.rs): `rtl/`, `memory.bin` and `case.txt`.
Run with `bash run.sh`.
"""

import os
import random

import cocotb
from cocotb.clock import Clock
from cocotb.triggers import FallingEdge, ReadOnly, RisingEdge
from cocotbext.axi import AxiBus, AxiRam

CASE = os.environ["CASE_DIR"]
INPUTS = ("corner_x", "corner_y", "corner_z", "level", "list_base_0", "list_count_0",
          "list_base_1", "list_count_1", "index_count_0", "index_count_1",
          "arena_start", "arena_end")


def read_case():
    numbers, ids, pairs, uncertain = {}, {}, [], []
    with open(os.path.join(CASE, "case.txt")) as f:
        for line in f:
            words = line.split()
            if not words or words[0] == "unit":
                continue
            if words[0] in ("ids_0", "ids_1"):
                ids[int(words[0][-1])] = [int(w) for w in words[1:]]
            elif words[0] == "pair":
                pairs.append((int(words[1]), int(words[2])))
            elif words[0] == "uncertain":
                uncertain.append((int(words[1]), int(words[2])))
            else:
                numbers[words[0]] = int(words[1])
    return numbers, ids, pairs, uncertain


async def run(dut, pause_seed):
    numbers, ids, want_pairs, want_uncertain = read_case()
    size = 1 << (numbers["arena_end"] - 1).bit_length()
    cocotb.start_soon(Clock(dut.clock, 10, units="ns").start())
    ram = AxiRam(AxiBus.from_prefix(dut, "m_axi"), dut.clock, dut.reset, size=size)
    with open(os.path.join(CASE, "memory.bin"), "rb") as f:
        ram.write(0, f.read())
    if pause_seed is not None:
        rng = random.Random(pause_seed)

        def pauses():
            while True:
                yield rng.random() < 0.3

        for channel in (ram.read_if.ar_channel, ram.read_if.r_channel,
                        ram.write_if.aw_channel, ram.write_if.w_channel,
                        ram.write_if.b_channel):
            channel.set_pause_generator(pauses())
    # Inputs change at falling edges, away from AxiRam's rising-edge updates.
    dut.start.value = 0
    dut.out_ready.value = 1
    for name in INPUTS:
        getattr(dut, name).value = numbers[name]
    dut.reset.value = 1
    for _ in range(2):
        await FallingEdge(dut.clock)
    dut.reset.value = 0
    await FallingEdge(dut.clock)
    dut.start.value = 1
    await FallingEdge(dut.clock)
    dut.start.value = 0
    pairs, uncertain, clocks = [], [], 1
    limit = 20 * numbers["done_at"] + 100_000
    while True:
        await ReadOnly()
        if dut.out_valid.value == 1:
            pair = (ids[0][int(dut.out_index_a.value)], ids[1][int(dut.out_index_b.value)])
            if dut.out_hit.value == 1:
                pairs.append(pair)
            if dut.out_certain.value == 0:
                uncertain.append(pair)
        if dut.done.value == 1:
            break
        assert dut.error.value == 0, "an error response"
        await FallingEdge(dut.clock)
        clocks += 1
        assert clocks < limit, "the top did not end"
    assert dut.overflow.value == 0, "a table overflowed"
    for got, want, what in ((pairs, want_pairs, "intersecting"),
                            (uncertain, want_uncertain, "without a certificate")):
        assert len(set(got)) == len(got), f"{what}: a pair came out twice"
        assert set(got) == set(want), (
            f"{what}: {len(set(want) - set(got))} missing, {len(set(got) - set(want))} extra")
    await RisingEdge(dut.clock)
    return len(pairs), len(uncertain), clocks, numbers["done_at"]


@cocotb.test()
async def streams_the_exact_pairs_from_axi_ram(dut):
    pairs, uncertain, clocks, verilator = await run(dut, None)
    dut._log.info("AxiRam top: %d pairs, %d without a certificate, each once; done at clock %d "
                  "(Verilator against the project's memory model: %d)",
                  pairs, uncertain, clocks, verilator)


@cocotb.test()
async def streams_them_with_axi_ram_pausing_at_random(dut):
    pairs, uncertain, clocks, verilator = await run(dut, 5)
    dut._log.info("AxiRam top, paused: %d pairs, %d without a certificate, each once; done at "
                  "clock %d", pairs, uncertain, clocks)
