"""cocotb test of the emitted AXI copy unit (`tritri gen --axi-copy`)
against cocotbext-axi's AxiRam, a memory written by other people: a region
is copied, the destination must hold the source's bytes and nothing else
may change. The second test pauses AxiRam's channels at random.

Run with `make SIM=icarus`, or `bash run.sh`. (Under Verilator 5.006 and
cocotb 1.8.1 the unit never sees its inputs once AxiRam is attached, so the
copy never starts; the Verilator co-simulation of this unit runs against
the project's own memory model, crates/tritri-cosim/tests/axi_copy.rs.)
"""

import random

import cocotb
from cocotb.clock import Clock
from cocotb.triggers import FallingEdge, ReadOnly, RisingEdge
from cocotbext.axi import AxiBus, AxiRam

SIZE = 1 << 17
SOURCE = 0x0140
DESTINATION = 0x1_0C00


def pattern(size, seed):
    rng = random.Random(seed)
    return bytes(rng.getrandbits(8) for _ in range(size))


async def copy(dut, ram, beats):
    """One copy from SOURCE to DESTINATION; returns its clocks to `done`.
    The inputs change at falling edges, away from AxiRam's rising-edge
    updates."""
    await FallingEdge(dut.clock)
    dut.source.value = SOURCE
    dut.destination.value = DESTINATION
    dut.beats.value = beats
    dut.start.value = 1
    await FallingEdge(dut.clock)
    dut.start.value = 0
    clocks = 1
    while True:
        await ReadOnly()
        if dut.done.value == 1:
            break
        await FallingEdge(dut.clock)
        clocks += 1
        assert clocks < 1_000_000, "the copy did not end"
    assert dut.error.value == 0, "an error response"
    await RisingEdge(dut.clock)
    return clocks


async def setup(dut, seed):
    cocotb.start_soon(Clock(dut.clock, 10, units="ns").start())
    ram = AxiRam(AxiBus.from_prefix(dut, "m_axi"), dut.clock, dut.reset, size=SIZE)
    before = pattern(SIZE, seed)
    ram.write(0, before)
    dut.start.value = 0
    dut.reset.value = 1
    for _ in range(2):
        await FallingEdge(dut.clock)
    dut.reset.value = 0
    return ram, before


def check(dut, ram, before, beats):
    n = beats * len(dut.m_axi_wdata) // 8
    after = ram.read(0, SIZE)
    assert after[DESTINATION:DESTINATION + n] == before[SOURCE:SOURCE + n], "the destination"
    assert after[:DESTINATION] == before[:DESTINATION], "below the destination"
    assert after[DESTINATION + n:] == before[DESTINATION + n:], "above the destination"


@cocotb.test()
async def copies_a_region_into_axi_ram(dut):
    ram, before = await setup(dut, 1)
    beats = 1500
    clocks = await copy(dut, ram, beats)
    check(dut, ram, before, beats)
    dut._log.info("AxiRam copy: %d beats in %d clocks, bytes equal", beats, clocks)


@cocotb.test()
async def copies_with_axi_ram_pausing_at_random(dut):
    ram, before = await setup(dut, 2)
    rng = random.Random(3)

    def pauses():
        while True:
            yield rng.random() < 0.3

    for channel in (ram.read_if.ar_channel, ram.read_if.r_channel,
                    ram.write_if.aw_channel, ram.write_if.w_channel,
                    ram.write_if.b_channel):
        channel.set_pause_generator(pauses())
    beats = 700
    clocks = await copy(dut, ram, beats)
    check(dut, ram, before, beats)
    dut._log.info("AxiRam copy, paused: %d beats in %d clocks, bytes equal", beats, clocks)
