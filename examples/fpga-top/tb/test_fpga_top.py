"""cocotb test of examples/fpga-top: the accelerator kernel around the
emitted broad-phase top with its scene in DRAM, driven the way a host
drives it, with three independent models from cocotbext-axi (PyPI): an
AxiLiteMaster writes and reads the registers, an AxiRam is the DRAM, an
AxiStreamSink takes the pair words.

The case (`CASE_DIR`) comes from `dram_broad_phase --write-case`
(examples/dram_broad_phase.rs): the generated top in `rtl/`, the scene
memory as the host leaves it in `memory.bin`, and in `case.txt` the
registers' values, the lists' triangle numbers, the pairs the top must
stream (the exact answer on the grid), the host's verdict on each pair
without a certificate, and the exact answer on the f64 meshes. The test
holds the stream to the grid's answer, each pair once, and the stream with
the host's verdicts to the exact answer. Run with `bash run.sh` (the
FuseSoC `sim` target).
"""

import os
import random
import struct

import cocotb
from cocotb.clock import Clock
from cocotb.triggers import RisingEdge
from cocotbext.axi import (AxiBus, AxiLiteBus, AxiLiteMaster, AxiRam, AxiResp,
                           AxiStreamBus, AxiStreamSink)

CASE = os.environ["CASE_DIR"]

# The register map (README.md, "Registers").
CONTROL, CLOCKS, PAIRS_OUT, PASSES, LEAVES, ID = 0x00, 0x40, 0x44, 0x48, 0x4C, 0x7C
INPUTS = {"corner_x": 0x04, "corner_y": 0x08, "corner_z": 0x0C, "level": 0x10,
          "list_base_0": 0x14, "list_count_0": 0x18, "index_count_0": 0x1C,
          "list_base_1": 0x20, "list_count_1": 0x24, "index_count_1": 0x28,
          "arena_start": 0x2C, "arena_end": 0x30}
MAGIC = 0x54525452
BUSY, DONE, ERROR, OVERFLOW = 1, 2, 4, 8


def read_case():
    numbers, ids, pairs, uncertain, exact = {}, {}, set(), {}, set()
    with open(os.path.join(CASE, "case.txt")) as f:
        for line in f:
            words = line.split()
            if not words or words[0] == "unit":
                continue
            if words[0] in ("ids_0", "ids_1"):
                ids[int(words[0][-1])] = [int(w) for w in words[1:]]
            elif words[0] == "pair":
                pairs.add((int(words[1]), int(words[2])))
            elif words[0] == "uncertain":
                uncertain[(int(words[1]), int(words[2]))] = words[3] == "1"
            elif words[0] == "exact":
                exact.add((int(words[1]), int(words[2])))
            else:
                numbers[words[0]] = int(words[1])
    return numbers, ids, pairs, uncertain, exact


class Host:
    """The board's host side: registers, DRAM, the pair stream."""

    def __init__(self, dut, size):
        self.regs = AxiLiteMaster(AxiLiteBus.from_prefix(dut, "s_axil"), dut.clock, dut.reset)
        self.ram = AxiRam(AxiBus.from_prefix(dut, "m_axi"), dut.clock, dut.reset, size=size)
        self.pairs = AxiStreamSink(AxiStreamBus.from_prefix(dut, "m_axis"), dut.clock, dut.reset)

    async def write(self, address, value):
        return (await self.regs.write(address, struct.pack("<I", value))).resp

    async def read(self, address):
        answer = await self.regs.read(address, 4)
        assert answer.resp == AxiResp.OKAY, f"reading 0x{address:02x}: {answer.resp}"
        return struct.unpack("<I", answer.data)[0]


async def run(dut, pause_seed):
    numbers, ids, want_pairs, host_verdicts, exact = read_case()
    cocotb.start_soon(Clock(dut.clock, 10, units="ns").start())
    host = Host(dut, 1 << (numbers["arena_end"] - 1).bit_length())
    with open(os.path.join(CASE, "memory.bin"), "rb") as f:
        host.ram.write(0, f.read())
    if pause_seed is not None:
        rng = random.Random(pause_seed)

        def pauses():
            while True:
                yield rng.random() < 0.3

        for channel in (host.ram.read_if.ar_channel, host.ram.read_if.r_channel,
                        host.ram.write_if.aw_channel, host.ram.write_if.w_channel,
                        host.ram.write_if.b_channel):
            channel.set_pause_generator(pauses())
        host.pairs.set_pause_generator(pauses())
    dut.reset.value = 1
    for _ in range(4):
        await RisingEdge(dut.clock)
    dut.reset.value = 0
    await RisingEdge(dut.clock)

    assert await host.read(ID) == MAGIC, "ID does not read TRTR"
    for name, address in INPUTS.items():
        assert await host.write(address, numbers[name]) == AxiResp.OKAY, name
    assert await host.read(INPUTS["list_count_1"]) == numbers["list_count_1"]
    assert await host.write(0x38, 1) == AxiResp.SLVERR, "an unmapped address answered OKAY"
    assert await host.write(CONTROL, 1) == AxiResp.OKAY
    assert await host.read(CONTROL) & BUSY, "not busy after start"
    # The run's inputs hold while it runs: a write answers SLVERR, changes nothing.
    assert await host.write(INPUTS["corner_x"], 0) == AxiResp.SLVERR, "a write while busy was taken"
    assert await host.read(INPUTS["corner_x"]) == numbers["corner_x"]

    frame = await host.pairs.recv()
    words = struct.unpack(f"<{len(frame.tdata) // 8}Q", bytes(frame.tdata))
    *pair_words, last = words
    hits, uncertain = [], []
    for word in pair_words:
        pair = (ids[0][word & 0xFFFF_FFFF], ids[1][(word >> 32) & 0x3FFF_FFFF])
        if word >> 63:
            hits.append(pair)
        if not (word >> 62) & 1:
            uncertain.append(pair)
    clocks, sent = last & 0xFFFF_FFFF, last >> 32

    status = await host.read(CONTROL)
    assert status & (BUSY | DONE | ERROR | OVERFLOW) == DONE, f"status 0x{status:x} after the run"
    assert (await host.read(CLOCKS), await host.read(PAIRS_OUT)) == (clocks, sent)
    assert sent == len(pair_words), f"the last word counts {sent} pairs, the stream had {len(pair_words)}"
    for got, want, what in ((hits, want_pairs, "intersecting"),
                            (uncertain, set(host_verdicts), "without a certificate")):
        assert len(set(got)) == len(got), f"{what}: a pair came out twice"
        assert set(got) == want, (
            f"{what}: {len(want - set(got))} missing, {len(set(got) - want)} extra")
    # The host's part: the certain hits, and the uncertain pairs it decides true.
    answer = {p for p in hits if p not in host_verdicts} | {p for p, v in host_verdicts.items() if v}
    assert answer == exact, (
        f"exact answer: {len(exact - answer)} missing, {len(answer - exact)} extra")
    return (len(hits), len(uncertain), len(exact), clocks, await host.read(PASSES),
            await host.read(LEAVES), numbers["done_at"])


@cocotb.test()
async def gives_the_exact_pairs(dut):
    hits, uncertain, exact, clocks, passes, leaves, verilator = await run(dut, None)
    dut._log.info("fpga-top: %d pairs on the grid (%d without a certificate), %d exact pairs "
                  "with the host's verdicts; %d clocks, %d passes, %d leaves (Verilator "
                  "against the project's memory model: done at clock %d)",
                  hits, uncertain, exact, clocks, passes, leaves, verilator)


@cocotb.test()
async def gives_them_with_memory_and_stream_pausing(dut):
    hits, uncertain, exact, clocks, passes, leaves, _ = await run(dut, 11)
    dut._log.info("fpga-top, paused: %d pairs on the grid (%d without a certificate), %d exact "
                  "pairs; %d clocks, %d passes, %d leaves", hits, uncertain, exact, clocks,
                  passes, leaves)
