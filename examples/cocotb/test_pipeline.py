"""cocotb test of the emitted triangle pipeline (rtl-out/w24, or any
`tritri gen` output): Python drives the ports cycle by cycle and checks
every verdict against exact integer arithmetic (exact.py).

Run with `make SIM=icarus` or `make SIM=verilator` (README.md).
"""

import os
import random
import re

import cocotb
from cocotb.clock import Clock
from cocotb.triggers import ReadOnly, RisingEdge

from exact import intersects


def readme_latency(rtl_dir):
    """The latency the emitted pipeline's README states ("verdict after N clocks")."""
    path = os.path.join(rtl_dir, "README.md")
    with open(path, encoding="utf-8") as f:
        found = re.search(r"verdict after (\d+) clocks", f.read())
    if not found:
        raise ValueError(f"{path}: no 'verdict after N clocks' line")
    return int(found.group(1))


LATENCY = readme_latency(os.environ["RTL_DIR"])


class PipelineDriver:
    """The pipeline's input protocol (thesis, chapter 3), one call a clock.

    - `load_base(id, t)`: `in_valid = 1, in_bset = 1`: the triangle becomes
      the base polygon T1 of the following tests; it is not tested itself.
    - `test(id, t)`: `in_valid = 1, in_bset = 0`: the triangle is tested
      against the current base; its verdict leaves `LATENCY` clocks later
      with `out_valid = 1`, `out_hit`, `out_base_id`, `out_stream_id`.
    - `idle()`: `in_valid = 0`.
    - `advance` is a clock enable for the whole pipeline, base registers
      included: while it is low nothing moves, so a cycle's inputs count
      only when `advance` is high at its rising edge. `hold_probability`
      lowers it at random to show that no verdict is lost or doubled.
    """

    def __init__(self, dut, hold_probability=0.0, rng=None):
        self.dut = dut
        self.width = len(dut.in_x0)
        self.hold_probability = hold_probability
        self.rng = rng or random.Random(1)

    async def reset(self):
        dut = self.dut
        dut.reset.value = 1
        dut.advance.value = 1
        dut.in_valid.value = 0
        dut.in_bset.value = 0
        for _ in range(2):
            await RisingEdge(dut.clock)
        dut.reset.value = 0

    def _put(self, valid, bset, triangle_id, triangle):
        dut = self.dut
        mask = (1 << self.width) - 1
        dut.in_valid.value = valid
        dut.in_bset.value = bset
        dut.in_id.value = triangle_id
        for v, vertex in enumerate(triangle):
            for axis, value in zip("xyz", vertex):
                # Two's complement in W bits.
                getattr(dut, f"in_{axis}{v}").value = value & mask

    async def _cycle(self):
        # Hold cycles first: inputs stay on the bus, advance low.
        while self.rng.random() < self.hold_probability:
            self.dut.advance.value = 0
            await RisingEdge(self.dut.clock)
        self.dut.advance.value = 1
        await RisingEdge(self.dut.clock)

    async def load_base(self, triangle_id, triangle):
        self._put(1, 1, triangle_id, triangle)
        await self._cycle()

    async def test(self, triangle_id, triangle):
        self._put(1, 0, triangle_id, triangle)
        await self._cycle()

    async def idle(self):
        self._put(0, 0, 0, ((0, 0, 0),) * 3)
        await self._cycle()


async def collect_verdicts(dut, verdicts):
    """Record (base_id, stream_id, hit) once per verdict: an output counts
    at a rising edge with `advance` high (with it low, the same verdict
    stays on the outputs)."""
    while True:
        await RisingEdge(dut.clock)
        await ReadOnly()
        if dut.reset.value == 0 and dut.advance.value == 1 and dut.out_valid.value == 1:
            verdicts.append((int(dut.out_base_id.value), int(dut.out_stream_id.value), int(dut.out_hit.value)))


async def run_schedule(dut, bases, streamed, hold_probability=0.0):
    """Every base against every streamed triangle; returns the verdicts in
    the order they left the pipeline."""
    cocotb.start_soon(Clock(dut.clock, 10, units="ns").start())
    driver = PipelineDriver(dut, hold_probability)
    await driver.reset()
    verdicts = []
    cocotb.start_soon(collect_verdicts(dut, verdicts))
    for b, base in enumerate(bases):
        await driver.load_base(b, base)
        for s, triangle in enumerate(streamed):
            await driver.test(s, triangle)
    for _ in range(LATENCY + 2):
        await driver.idle()
    return verdicts


def check(dut, bases, streamed, verdicts):
    expected = [(b, s, int(intersects(base, t))) for b, base in enumerate(bases) for s, t in enumerate(streamed)]
    assert len(verdicts) == len(expected), f"{len(verdicts)} verdicts, expected {len(expected)}"
    for got, want in zip(verdicts, expected):
        assert got == want, f"verdict {got} (base, stream, hit), exact arithmetic says {want}"
    hits = sum(v[2] for v in verdicts)
    dut._log.info(f"{len(verdicts)} verdicts equal exact arithmetic ({hits} hits)")


def random_triangles(rng, count, radius):
    return [tuple(tuple(rng.randint(-radius, radius) for _ in range(3)) for _ in range(3)) for _ in range(count)]


def small_grid_scene():
    # On a 7 x 7 x 7 grid, a third of the pairs touch, many are coplanar,
    # and many triangles are segments or points: the hard cases.
    rng = random.Random(2026)
    return random_triangles(rng, 8, 3), random_triangles(rng, 60, 3)


@cocotb.test()
async def small_grid_every_verdict_exact(dut):
    """8 bases x 60 triangles on a 7^3 grid: every verdict = exact."""
    bases, streamed = small_grid_scene()
    check(dut, bases, streamed, await run_schedule(dut, bases, streamed))


@cocotb.test()
async def range_ends_every_verdict_exact(dut):
    """Coordinates drawn from the ends of the W-bit range (products at
    their widest): every verdict = exact."""
    width = len(dut.in_x0)
    lo, hi = -(1 << (width - 1)), (1 << (width - 1)) - 1
    values = [lo, lo + 1, -1, 0, 1, hi - 1, hi]
    rng = random.Random(24)

    def triangle():
        return tuple(tuple(rng.choice(values) for _ in range(3)) for _ in range(3))

    bases = [triangle() for _ in range(4)]
    streamed = [triangle() for _ in range(60)]
    check(dut, bases, streamed, await run_schedule(dut, bases, streamed))


@cocotb.test()
async def advance_low_loses_and_doubles_nothing(dut):
    """The small-grid scene with `advance` low in about a third of the
    cycles: the same verdicts, in the same order."""
    bases, streamed = small_grid_scene()
    check(dut, bases, streamed, await run_schedule(dut, bases, streamed, hold_probability=0.35))
