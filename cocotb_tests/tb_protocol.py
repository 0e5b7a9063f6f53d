"""cocotb protocol tests of ``nuc_core``, ``dpc_core`` and ``nuc_dpc_top`` (run through
``cocotb_tests/test_protocol.py``).

* ``registered_outputs``: every output port is a register. In each clock cycle the inputs
  are driven (valid/ready protocol kept), then between the edges the output ready is
  changed and every other input is glitched to random values and restored; no output may
  move until the next rising edge (``Timer(1, unit="ns")`` steps).
* ``clean_stall``: the stall used by the violation tests, kept legal: no assertion fires.
* ``violation_*``: the protocol is broken on purpose; the RTL's assertions must stop the
  simulation (then this test fails with cocotb's SimFailure, which the pytest wrapper
  expects, together with the assertion's line in the simulator log). If the simulation
  survives, the test fails with "no assertion fired". Run each in its own simulation.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import cocotb
import numpy as np
from cocotb.handle import SimHandleBase
from cocotb.triggers import ClockCycles, RisingEdge, Timer

from irnuc.cocotb_tests import tb_lib

#: Message of a violation test whose violation went unnoticed.
NOT_FIRED = "no assertion fired"


@dataclass
class Stream:
    """An input stream of the DUT and the items driven on it."""

    valid: str
    ready: str
    data: list[str]
    items: list[list[int]] = field(default_factory=list)
    idx: int = 0
    pending: bool = False  # valid is high and the item was not taken yet


def _streams(dut: SimHandleBase, rng: np.random.Generator, n: int, w: int, h: int
             ) -> tuple[list[Stream], tuple[str, str]]:
    """The DUT's input streams with n items each, and its output (valid, ready) pair."""
    name = dut._name
    pos = np.arange(n) % (w * h)
    sof, eol = (pos == 0).astype(int), (pos % w == w - 1).astype(int)

    def rand(port: str) -> np.ndarray:
        return rng.integers(0, 1 << len(getattr(dut, port)), size=n, dtype=np.int64)

    if name == "nuc_dpc_top":
        pix = Stream("s_pix_valid_i", "s_pix_ready_o", ["s_pix_data_i", "s_pix_sof_i",
                                                        "s_pix_eol_i"])
        pix.items = [[int(a), int(b), int(c)] for a, b, c in zip(rand("s_pix_data_i"), sof, eol,
                                                                 strict=True)]
        coef = Stream("s_coef_valid_i", "s_coef_ready_o", ["s_coef_data_i"])
        coef.items = [[int(a)] for a in rand("s_coef_data_i")]
        return [pix, coef], ("m_pix_valid_o", "m_pix_ready_i")
    if name == "dpc_core":
        s = Stream("s_valid_i", "s_ready_o", ["s_pix_data_i", "s_bad_i", "s_sof_i", "s_eol_i"])
        s.items = [[int(a), int(b), int(c), int(d)] for a, b, c, d in
                   zip(rand("s_pix_data_i"), rand("s_bad_i"), sof, eol, strict=True)]
        return [s], ("m_valid_o", "m_ready_i")
    if name == "nuc_core":
        s = Stream("s_valid_i", "s_ready_o", ["s_pix_data_i", "s_gain_i", "s_offset_i",
                                              "s_user_i"])
        cols = [rand(p) for p in s.data]
        s.items = [[int(c[i]) for c in cols] for i in range(n)]
        return [s], ("m_valid_o", "m_ready_i")
    raise AssertionError(f"tb_protocol does not know the DUT {name!r}")


def _ports(dut: SimHandleBase) -> tuple[list[str], list[str]]:
    """Input ports (clock and reset excluded) and output ports of the DUT."""
    names = sorted(h._name for h in dut if h._name.endswith(("_i", "_o")))
    ins = [n for n in names if n.endswith("_i") and n not in ("clk_i", "rst_ni")]
    outs = [n for n in names if n.endswith("_o")]
    return ins, outs


async def _start(dut: SimHandleBase, w: int, h: int) -> None:
    for p in _ports(dut)[0]:
        getattr(dut, p).value = 0
    if hasattr(dut, "frame_width_i"):
        dut.frame_width_i.value = w
        dut.frame_height_i.value = h
    await tb_lib.start_clock_and_reset(dut)


def _size(cfg) -> tuple[int, int]:
    return min(cfg.max_width, 5), min(cfg.max_height, 3)


@cocotb.test()
async def registered_outputs(dut) -> None:
    """No output moves between clock edges, whatever the inputs do there."""
    cfg = tb_lib.config_from_env()
    rng = np.random.default_rng(tb_lib.seed_from_env() + 10)
    w, h = _size(cfg)
    await _start(dut, w, h)
    ins, outs = _ports(dut)
    streams, (m_valid, m_ready) = _streams(dut, rng, 400, w, h)
    edge = RisingEdge(dut.clk_i)
    seen_ready = {s.ready: set() for s in streams}
    taken = {s.valid: 0 for s in streams}
    delivered = checks = 0
    for cycle in range(300):
        await Timer(1, unit="ns")
        snap = {o: int(getattr(dut, o).value) for o in outs}

        def same(when: str, snap=snap, cycle=cycle) -> int:
            now = {o: int(getattr(dut, o).value) for o in outs}
            moved = {o: (snap[o], now[o]) for o in outs if now[o] != snap[o]}
            assert not moved, f"cycle {cycle}, {when}: outputs moved between edges {moved}"
            return 1

        # Drive this cycle: an offered item stays offered until taken; gaps between items.
        for s in streams:
            if not s.pending and s.idx < len(s.items) and rng.random() < 0.8:
                for port, v in zip(s.data, s.items[s.idx], strict=True):
                    getattr(dut, port).value = v
                s.pending = True
            getattr(dut, s.valid).value = int(s.pending)
        ready0 = int(rng.random() < 0.5)
        getattr(dut, m_ready).value = ready0
        await Timer(1, unit="ns")
        checks += same("after driving the inputs")
        # The output side's ready changes between the edges (its final value this cycle).
        ready1 = 1 - ready0
        getattr(dut, m_ready).value = ready1
        await Timer(1, unit="ns")
        checks += same(f"after {m_ready} {ready0} -> {ready1}")
        # Every other input glitches to random values and back.
        saved = {p: int(getattr(dut, p).value) for p in ins if p != m_ready}
        for p in saved:
            getattr(dut, p).value = int(rng.integers(0, 1 << len(getattr(dut, p))))
        await Timer(1, unit="ns")
        checks += same("while the inputs glitch")
        for p, v in saved.items():
            getattr(dut, p).value = v
        await Timer(1, unit="ns")
        checks += same("after the glitch")
        # Transfers at the coming edge (the readies are the snapshot's: registered).
        for s in streams:
            seen_ready[s.ready].add(snap[s.ready])
            if s.pending and snap[s.ready]:
                s.idx += 1
                s.pending = False
                taken[s.valid] += 1
        delivered += int(snap[m_valid] and ready1)
        await edge
    for s in streams:
        getattr(dut, s.valid).value = 0
    dut._log.info(f"{checks} checks; items taken {taken}, delivered {delivered}; "
                  f"readies seen {seen_ready}")
    assert all(v == {0, 1} for v in seen_ready.values()), (
        f"the input readies never both stalled and moved: {seen_ready}")
    assert delivered > 20 and all(t > 20 for t in taken.values()), (taken, delivered)


async def _stall(dut: SimHandleBase, stream: Stream, cycles: int = 200) -> None:
    """Offer items on ``stream`` with the output blocked until its ready is low at an edge.

    Returns right after that edge, valid still high (the item pending).
    """
    edge = RisingEdge(dut.clk_i)
    for _ in range(cycles):
        if not stream.pending:
            for port, v in zip(stream.data, stream.items[stream.idx], strict=True):
                getattr(dut, port).value = v
            getattr(dut, stream.valid).value = 1
            stream.pending = True
        await edge
        if int(getattr(dut, stream.ready).value):
            stream.idx += 1
            stream.pending = False
        else:
            return
    raise AssertionError(f"{stream.ready} never went low with the output blocked")


async def _stalled_first_input(dut) -> Stream:
    cfg = tb_lib.config_from_env()
    rng = np.random.default_rng(tb_lib.seed_from_env() + 11)
    w, h = _size(cfg)
    await _start(dut, w, h)
    streams, (_, m_ready) = _streams(dut, rng, 400, w, h)
    getattr(dut, m_ready).value = 0
    # Top: only pixels come, no coefficient word: the pixel input register fills up.
    await _stall(dut, streams[0])
    return streams[0]


@cocotb.test()
async def clean_stall(dut) -> None:
    """Control: the stall of the violation tests, kept legal, passes without assertion."""
    s = await _stalled_first_input(dut)
    await ClockCycles(dut.clk_i, 5)  # valid held, data held
    assert int(getattr(dut, s.valid).value) == 1


@cocotb.test()
async def violation_valid_dropped(dut) -> None:
    """valid falls while the item is not taken: a_valid_held must fire."""
    s = await _stalled_first_input(dut)
    getattr(dut, s.valid).value = 0
    await ClockCycles(dut.clk_i, 5)
    raise AssertionError(NOT_FIRED)


@cocotb.test()
async def violation_data_changed(dut) -> None:
    """The data of a stalled item change: a_data_stable must fire."""
    s = await _stalled_first_input(dut)
    port = getattr(dut, s.data[0])
    port.value = int(port.value) ^ 1
    await ClockCycles(dut.clk_i, 5)
    raise AssertionError(NOT_FIRED)


@cocotb.test()
async def violation_frame_size(dut) -> None:
    """A frame starts with width 0: a_frame_size must fire (frame_err_o is set too)."""
    if not hasattr(dut, "frame_width_i"):
        raise AssertionError(f"{dut._name} has no frame size")
    cfg = tb_lib.config_from_env()
    rng = np.random.default_rng(tb_lib.seed_from_env() + 12)
    w, h = _size(cfg)
    await _start(dut, w, h)
    streams, (_, m_ready) = _streams(dut, rng, 4, w, h)
    getattr(dut, m_ready).value = 1
    dut.frame_width_i.value = 0
    await ClockCycles(dut.clk_i, 2)
    for s in streams:
        for port, v in zip(s.data, s.items[0], strict=True):
            getattr(dut, port).value = v
        getattr(dut, s.valid).value = 1
    await ClockCycles(dut.clk_i, 10)
    raise AssertionError(NOT_FIRED)
