"""cocotb protocol tests of ``nuc_core``, ``dpc_core`` and ``nuc_dpc_top`` (run through
``cocotb_tests/test_protocol.py``); one testbench for every top: its valid/ready streams
are found by prefix (``streams.stream_prefixes``), items are random over the widths read
back from the DUT, with frame markers where a stream has them.

* ``registered_outputs``: every output port is a register. Each cycle the engine drives
  the inputs (valid/ready protocol kept, random idle cycles); between the edges the output
  ready is changed and every other input is glitched to random values and restored; no
  output may move until the next rising edge (``Timer(1, unit="ns")`` steps).
* ``clean_stall``: the stall used by the violation tests, kept legal: no assertion fires.
* ``violation_*``: the protocol is broken on purpose; the RTL's assertions must stop the
  simulation (then this test fails with cocotb's SimFailure, which the pytest wrapper
  expects, together with the assertion's line in the simulator log). If the simulation
  survives, the test fails with "no assertion fired". Run each in its own simulation.
"""

from __future__ import annotations

import cocotb
import numpy as np
from cocotb.handle import SimHandleBase
from cocotb.triggers import ClockCycles, Timer

from irnuc.cocotb_tests import tb_lib
from irnuc.cocotb_tests.streams import (
    Sink,
    Source,
    StreamBus,
    ports,
    run_streams,
    start_clock_and_reset,
    stream_prefixes,
)

#: Message of a violation test whose violation went unnoticed.
NOT_FIRED = "no assertion fired"


def _size(cfg) -> tuple[int, int]:
    return min(cfg.max_width, 5), min(cfg.max_height, 3)


def _sources(dut: SimHandleBase, rng: np.random.Generator, n: int, idle: float = 0.0
             ) -> list[Source]:
    """A source of n random items on every input stream of the DUT (markers of frames of
    the test's size where the stream has sof/eol)."""
    w, h = _size(tb_lib.config_from_env())
    sof, eol = tb_lib.markers(h, w)
    reps = -(-n // (w * h))
    out = []
    for prefix in stream_prefixes(dut, "in"):
        bus = StreamBus.from_prefix(dut, prefix)
        items = {f: rng.integers(0, 1 << bus.width(f), size=n, dtype=np.int64)
                 for f in bus.names}
        for name, marks in (("sof", sof), ("eol", eol)):
            if name in items:
                items[name] = np.tile(marks, reps)[:n]
        out.append(Source(bus, items, idle, rng))
    return out


def _sink(dut: SimHandleBase, backpressure: float) -> Sink:
    (prefix,) = stream_prefixes(dut, "out")
    return Sink(StreamBus.from_prefix(dut, prefix), backpressure)


async def _start(dut: SimHandleBase) -> None:
    for p in ports(dut):
        if p.endswith("_i") and p != "clk_i":
            getattr(dut, p).value = 0
    if hasattr(dut, "frame_width_i"):
        dut.frame_width_i.value, dut.frame_height_i.value = _size(tb_lib.config_from_env())
    await start_clock_and_reset(dut)


@cocotb.test()
async def registered_outputs(dut) -> None:
    """No output moves between clock edges, whatever the inputs do there."""
    rng = np.random.default_rng(tb_lib.seed_from_env() + 10)
    await _start(dut)
    outs = [getattr(dut, p) for p in ports(dut) if p.endswith("_o")]
    sink = _sink(dut, 0.5)
    sources = _sources(dut, rng, 400, idle=0.2)
    glitched = [getattr(dut, p) for p in ports(dut)
                if p.endswith("_i") and p not in ("clk_i", sink.bus.ready._name)]
    seen_ready = {s.bus.prefix: set() for s in sources}
    checks = 0

    async def between(cycle: int) -> None:
        nonlocal checks
        await Timer(1, unit="ns")
        snap = [int(h.value) for h in outs]
        for s in sources:
            seen_ready[s.bus.prefix].add(int(s.bus.ready.value))

        def same(when: str) -> None:
            nonlocal checks
            moved = {h._name: (a, int(h.value)) for h, a in zip(outs, snap, strict=True)
                     if int(h.value) != a}
            assert not moved, f"cycle {cycle}, {when}: outputs moved between edges {moved}"
            checks += 1

        # The output side's ready changes between the edges (its final value this cycle).
        old = int(sink.bus.ready.value)
        sink.bus.ready.value = 1 - old
        await Timer(1, unit="ns")
        same(f"after {sink.bus.ready._name} {old} -> {1 - old}")
        # Every other input glitches to random values and back.
        saved = [int(h.value) for h in glitched]
        for h in glitched:
            h.value = int(rng.integers(0, 1 << len(h)))
        await Timer(1, unit="ns")
        same("while the inputs glitch")
        for h, v in zip(glitched, saved, strict=True):
            h.value = v
        await Timer(1, unit="ns")
        same("after the glitch")

    await run_streams(dut, sources, sink, stop=lambda c: c >= 300, between=between)
    taken = {s.bus.prefix: len(s.taken) for s in sources}
    cocotb.log.info(f"{checks} checks; items taken {taken}, delivered {len(sink.got)}; "
                    f"readies seen {seen_ready}")
    assert all(v == {0, 1} for v in seen_ready.values()), (
        f"the input readies never both stalled and moved: {seen_ready}")
    assert len(sink.got) > 20 and all(t > 20 for t in taken.values()), (taken, len(sink.got))


async def _stalled_first_input(dut) -> Source:
    """Offer items on the DUT's first input stream with the output blocked, until its
    ready is low at an edge; return right after that edge with the item still offered.
    (Top: only pixels come, no coefficient word, so the pixel input register fills up.)"""
    rng = np.random.default_rng(tb_lib.seed_from_env() + 11)
    await _start(dut)
    src = _sources(dut, rng, 400)[0]
    await run_streams(dut, [src], _sink(dut, 1.0), max_cycles=200,
                      stop=lambda c: src.held, release=False)
    return src


@cocotb.test()
async def clean_stall(dut) -> None:
    """Control: the stall of the violation tests, kept legal, passes without assertion."""
    s = await _stalled_first_input(dut)
    await ClockCycles(dut.clk_i, 5)  # valid held, data held
    assert int(s.bus.valid.value) == 1


@cocotb.test()
async def violation_valid_dropped(dut) -> None:
    """valid falls while the item is not taken: a_valid_held must fire."""
    s = await _stalled_first_input(dut)
    s.bus.valid.value = 0
    await ClockCycles(dut.clk_i, 5)
    raise AssertionError(NOT_FIRED)


@cocotb.test()
async def violation_data_changed(dut) -> None:
    """The data of a stalled item change: a_data_stable must fire."""
    s = await _stalled_first_input(dut)
    port = s.bus.fields["pix_data" if "pix_data" in s.bus.fields else "data"]
    port.value = int(port.value) ^ 1
    await ClockCycles(dut.clk_i, 5)
    raise AssertionError(NOT_FIRED)


@cocotb.test()
async def violation_frame_size(dut) -> None:
    """A frame starts with width 0: a_frame_size must fire (frame_err_o is set too)."""
    if not hasattr(dut, "frame_width_i"):
        raise AssertionError(f"{dut._name} has no frame size")
    rng = np.random.default_rng(tb_lib.seed_from_env() + 12)
    await _start(dut)
    dut.frame_width_i.value = 0
    await ClockCycles(dut.clk_i, 2)
    await run_streams(dut, _sources(dut, rng, 4), _sink(dut, 0.0),
                      stop=lambda c: c >= 10, release=False)
    raise AssertionError(NOT_FIRED)
