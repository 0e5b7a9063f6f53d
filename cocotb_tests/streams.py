"""The one drive engine of the testbenches: valid/ready streams found by name prefix,
sources and sinks with pause patterns, and :func:`run_streams`.

A stream is found on the DUT by its prefix, as cocotbext-axi's ``from_prefix``:
``<prefix>_valid_i``, ``<prefix>_ready_o`` and every other ``<prefix>_<field>_i`` port of an
input stream (``_o`` and ``_i`` the other way round for an output stream); ports outside
the prefix that travel with each item (the frame size of ``nuc_dpc_top``) are named as
``extra``. A new top with other streams (a coefficient stream, a write-back stream) needs
no change here: ``StreamBus.from_prefix(dut, "s_coef")``, a :class:`Source` or
:class:`Sink` on it, and the scoreboard of its outputs.

Timing convention (measured on Verilator 5 + cocotb 2): at ``RisingEdge(clk)`` a read
returns the value sampled by that edge, and a write is seen by the next edge. So one await
per cycle is enough: read the transfers that just happened, then drive the next cycle.
Widths are read back from the DUT (``len(handle)``), never restated. Only public cocotb
API: handles, ``handle.value``, ``len(handle)``, iteration over the DUT and ``_name``
(cocotb's documented public name attribute, underscored so that it cannot clash with an
HDL name).
"""

from __future__ import annotations

import itertools
import json
import os
import re
from collections.abc import Awaitable, Callable, Iterator, Mapping, Sequence

import numpy as np
from cocotb.clock import Clock
from cocotb.handle import SimHandleBase
from cocotb.triggers import ClockCycles, RisingEdge, Timer

from irnuc.cosim import coverage
from irnuc.nuc_fixed import PipelineConfig

CLK_PERIOD_NS = 10


async def start_clock_and_reset(dut: SimHandleBase, cycles: int = 3) -> None:
    """Start ``clk_i``, idle the input streams (:func:`idle_inputs`) and pulse the
    asynchronous active-low reset ``rst_ni``."""
    Clock(dut.clk_i, CLK_PERIOD_NS, unit="ns").start()
    idle_inputs(dut)
    await reset(dut, cycles)


#: AXI names of the valid flags a master drives into the DUT (its slave ports).
_AXI_INPUT_VALIDS = re.compile(r"s_axis_\w+_tvalid|s_axil_(aw|w|ar)valid")


def input_valid_names(names: Sequence[str]) -> list[str]:
    """Of the DUT's signal ``names``, the valid flags of its inputs: ``<prefix>_valid_i``
    and the slave ports' AXI ``s_axis_*_tvalid``, ``s_axil_awvalid`` / ``wvalid`` /
    ``arvalid``."""
    return sorted(n for n in names
                  if n.endswith("_valid_i") or _AXI_INPUT_VALIDS.fullmatch(n))


def idle_inputs(dut: SimHandleBase) -> None:
    """Drive every input valid flag to 0. A cocotb test starts on the signals the one
    before it left: a driver that stopped with an item offered (a test that failed
    mid-stream) leaves its valid high, and at the first edge after the next test's reset
    the DUT would take that stale item (AXI: a master holds VALID low in reset and raises
    it only after the first edge after it; ``irnuc_axis_assert`` checks that edge)."""
    for name in input_valid_names([h._name for h in dut]):
        getattr(dut, name).value = 0


async def reset(dut: SimHandleBase, cycles: int = 3) -> None:
    """Assert ``rst_ni`` between clock edges (it is asynchronous), release it likewise."""
    await Timer(CLK_PERIOD_NS // 4, unit="ns")
    dut.rst_ni.value = 0
    await ClockCycles(dut.clk_i, cycles)
    await Timer(CLK_PERIOD_NS // 4, unit="ns")
    dut.rst_ni.value = 1
    await RisingEdge(dut.clk_i)


def ports(dut: SimHandleBase) -> list[str]:
    """The names of the DUT's ports (``*_i``, ``*_o``, ``*_ni``), sorted."""
    return sorted(h._name for h in dut if h._name.endswith(("_i", "_o", "_ni")))


def stream_prefixes(dut: SimHandleBase, direction: str) -> list[str]:
    """Prefixes of the DUT's input (``"in"``) or output (``"out"``) valid/ready streams."""
    suffix = "_valid_i" if direction == "in" else "_valid_o"
    return [p.removesuffix(suffix) for p in ports(dut) if p.endswith(suffix)]


class StreamBus:
    """The ports of one valid/ready stream: ``valid``, ``ready`` and the data fields.

    ``fields`` maps a field name to its handle: ``<prefix>_<field>_i`` becomes ``field``,
    an extra port ``frame_width_i`` becomes ``frame_width``. :attr:`is_input` tells the
    direction (the DUT takes the stream).
    """

    def __init__(self, prefix: str, valid: SimHandleBase, ready: SimHandleBase,
                 fields: Mapping[str, SimHandleBase], is_input: bool) -> None:
        self.prefix, self.valid, self.ready, self.is_input = prefix, valid, ready, is_input
        self.fields = dict(fields)
        self.names = tuple(self.fields)
        self.handles = tuple(self.fields.values())

    @classmethod
    def from_prefix(cls, dut: SimHandleBase, prefix: str, extra: Sequence[str] = ()
                    ) -> StreamBus:
        """The stream ``prefix`` of ``dut`` (input or output, told by its valid port)."""
        names = ports(dut)
        if f"{prefix}_valid_i" in names:
            d, r = "_i", "_o"
        elif f"{prefix}_valid_o" in names:
            d, r = "_o", "_i"
        else:
            raise AttributeError(f"no stream {prefix!r} on the DUT: no {prefix}_valid_i or "
                                 f"{prefix}_valid_o among {names}")
        if f"{prefix}_ready{r}" not in names:
            raise AttributeError(f"stream {prefix!r} has no {prefix}_ready{r}")
        fields = {n[len(prefix) + 1:-len(d)]: getattr(dut, n) for n in names
                  if n.startswith(f"{prefix}_") and n.endswith(d)
                  and n not in (f"{prefix}_valid{d}", f"{prefix}_ready{r}")}
        for e in extra:
            if e not in names:
                raise AttributeError(f"stream {prefix!r}: no extra port {e!r}")
            fields[e.removesuffix(d)] = getattr(dut, e)
        return cls(prefix, getattr(dut, f"{prefix}_valid{d}"),
                   getattr(dut, f"{prefix}_ready{r}"), fields, d == "_i")

    def index(self, field: str) -> int:
        """Position of ``field`` in an item (a row of :attr:`Source.values`)."""
        return self.names.index(field)

    def width(self, field: str) -> int:
        return len(self.fields[field])


# ---- pause patterns --------------------------------------------------------------------

def pause_pattern(name: str, rng: np.random.Generator) -> Iterator[bool]:
    """An endless pause generator (True = pause this cycle), as cocotbext-axi's
    ``set_pause_generator``: ``none``, ``random`` (30 % of the cycles), ``bursty`` (runs of
    4-24 active cycles and 1-12 pauses) or ``alternate`` (every other cycle)."""
    if name == "none":
        return itertools.repeat(False)
    if name == "alternate":
        return itertools.cycle((False, True))
    if name == "random":
        return _random_pauses(0.3, rng)
    if name == "bursty":
        def bursts() -> Iterator[bool]:
            while True:
                yield from itertools.repeat(False, int(rng.integers(4, 25)))
                yield from itertools.repeat(True, int(rng.integers(1, 13)))
        return bursts()
    raise ValueError(f"unknown pause pattern {name!r}; known: {coverage.IDLE_PATTERNS}")


def _random_pauses(p: float, rng: np.random.Generator) -> Iterator[bool]:
    while True:
        yield from (rng.random(4096) < p).tolist()


def _pause(value: float | str, rng: np.random.Generator) -> tuple[str, Iterator[bool] | None]:
    """A pattern name or a pause probability -> (coverage name, generator; None = never)."""
    if isinstance(value, str):
        return value, (None if value == "none" else pause_pattern(value, rng))
    if value == 0.0:
        return "none", None
    return "random", _random_pauses(float(value), rng)


# ---- sources and sinks -----------------------------------------------------------------

class Source:
    """Drives items onto an input :class:`StreamBus`.

    ``items`` gives one array per field of the bus (every field, equal lengths); ``idle``
    is a pause pattern name (:func:`pause_pattern`) or a pause probability. An item once
    offered stays offered, with its data, until it is taken (AXI-Stream rule; the RTL's
    assertions check it). The input monitor: :attr:`taken` holds the cycle of every
    transfer.
    """

    def __init__(self, bus: StreamBus, items: Mapping[str, np.ndarray | Sequence[int]],
                 idle: float | str = 0.0, rng: np.random.Generator | None = None) -> None:
        if not bus.is_input:
            raise ValueError(f"stream {bus.prefix!r} is an output of the DUT")
        missing = set(bus.names) - set(items)
        unknown = set(items) - set(bus.names)
        if missing or unknown:
            raise ValueError(f"stream {bus.prefix!r} has fields {list(bus.names)}; items "
                             f"lack {sorted(missing)} and have unknown {sorted(unknown)}")
        cols = [np.asarray(items[n]).ravel() for n in bus.names]
        if len({c.size for c in cols}) > 1:
            raise ValueError(f"stream {bus.prefix!r}: fields of different lengths")
        self.bus = bus
        self.values = np.stack(cols, axis=1).tolist() if cols and cols[0].size else []
        self.pattern, self.pause = _pause(idle, rng or np.random.default_rng(0))
        self.idx = 0          # next item to send
        self.driving = False  # valid is high this cycle
        self.held = False     # valid was high at the last edge and the item was not taken
        self.last: list[int] = [-1] * len(bus.names)
        self.taken: list[int] = []
        bus.valid.value = 0

    @property
    def done(self) -> bool:
        return self.idx >= len(self.values)

    def toggle(self, item: int, field: str) -> None:
        """Flip bit 0 of one field of one item (a deliberately broken marker)."""
        self.values[item][self.bus.index(field)] ^= 1


class Sink:
    """Takes items from an output :class:`StreamBus`, with a pause pattern (backpressure).

    ``expect`` outputs make :func:`run_streams` wait for them (None: collect what comes).
    ``first_cycle``/``last_cycle`` bracket the outputs; ``stalls`` counts the cycles from
    the first output to the last one in which the sink's ready was low.
    """

    def __init__(self, bus: StreamBus, backpressure: float | str = 0.0,
                 rng: np.random.Generator | None = None, expect: int | None = None) -> None:
        if bus.is_input:
            raise ValueError(f"stream {bus.prefix!r} is an input of the DUT")
        self.bus = bus
        self.expect = expect
        self.pattern, self.pause = _pause(backpressure, rng or np.random.default_rng(1))
        self.got: list[tuple[int, ...]] = []
        self.ready_now = False
        self.first_cycle = -1
        self.last_cycle = -1
        self.stalls = 0
        self._stalls_running = 0
        bus.ready.value = 0

    @property
    def satisfied(self) -> bool:
        return self.expect is None or len(self.got) >= self.expect

    def outputs(self) -> dict[str, np.ndarray]:
        """Field -> int64 array of the outputs taken, in order (for a scoreboard)."""
        arr = np.asarray(self.got, dtype=np.int64).reshape(len(self.got), len(self.bus.names))
        return {n: arr[:, i] for i, n in enumerate(self.bus.names)}

    def check_throughput(self) -> None:
        """No cycle lost inside the DUT: from the first output to the last, every cycle
        delivered an output or the sink stalled (``AssertionError`` otherwise)."""
        n = len(self.got)
        span = self.last_cycle - self.first_cycle + 1
        assert span == n + self.stalls, (
            f"{n} outputs took {span} cycles with {self.stalls} stalled cycles of the sink "
            f"({self.pattern}): {span - n - self.stalls} cycle(s) lost inside the DUT")


def config_from_env(var: str = "IRNUC_CONFIG_JSON") -> PipelineConfig:
    """The configuration the DUT was built with (set by ``irnuc.cosim.run``)."""
    return PipelineConfig(**json.loads(os.environ[var]))


def coverage_sample(name: str, value: object) -> None:
    """Sample a coverpoint of the DUT's model (``$IRNUC_CONFIG_JSON``, ``$COCOTB_TOPLEVEL``);
    nothing when the run exports no coverage."""
    top = os.environ.get("COCOTB_TOPLEVEL", "")
    if coverage.enabled() and top in ("nuc_core", "dpc_core", "nuc_dpc_top"):
        coverage.model(top, config_from_env()).sample(name, value)


# ---- the engine ------------------------------------------------------------------------

async def run_streams(dut: SimHandleBase, sources: Sequence[Source],
                      sinks: Sink | Sequence[Sink], *, max_cycles: int | None = None,
                      stop: Callable[[int], bool] | None = None,
                      between: Callable[[int], Awaitable[None]] | None = None,
                      release: bool = True) -> int:
    """Drive ``sources`` and collect into ``sinks`` until every sink has its ``expect``
    outputs (or ``stop(cycle)``, asked after every edge, says stop); return the cycles.

    One ``await RisingEdge(clk_i)`` per cycle: each source drives its next item unless its
    pause generator says pause (an item already offered stays offered), each sink's ready
    follows its own pause generator; transfers are read after the edge. ``between(cycle)``,
    awaited after the drive and before the edge, may act between the edges (it must leave
    the sources' valid and data as they were; it may change a sink's ready, which is read
    back). With ``release`` the valids and readies go low at the end; without, the bus is
    left as it is (an offered item stays offered). Raises AssertionError if the expected
    outputs do not arrive within ``max_cycles``.
    """
    sinks = [sinks] if isinstance(sinks, Sink) else list(sinks)
    waiting = [s for s in sinks if s.expect is not None]
    if stop is None and not waiting:
        raise ValueError("run_streams needs a sink with expect or a stop condition")
    limit = max_cycles if max_cycles is not None else (
        20 * (sum(s.expect for s in waiting) + 100) + 50_000)
    for src in sources:
        coverage_sample("stream.idle", src.pattern)
    for snk in sinks:
        coverage_sample("stream.backpressure", snk.pattern)
    edge = RisingEdge(dut.clk_i)
    cycle = 0
    while not (waiting and all(s.satisfied for s in waiting)):
        if cycle >= limit:
            got = ", ".join(f"{s.bus.prefix} {len(s.got)} of {s.expect}" for s in sinks)
            raise AssertionError(f"timeout after {cycle} cycles: outputs {got}")
        # Drive this cycle; pauses only between items.
        for src in sources:
            want = src.idx < len(src.values) and (
                src.held or src.pause is None or not next(src.pause))
            if want:
                row = src.values[src.idx]
                if row is not src.last:
                    for h, v, old in zip(src.bus.handles, row, src.last, strict=True):
                        if v != old:
                            h.value = v
                    src.last = row
            if want != src.driving:
                src.bus.valid.value = int(want)
                src.driving = want
        for snk in sinks:
            rdy = snk.pause is None or not next(snk.pause)
            if rdy != snk.ready_now:
                snk.bus.ready.value = int(rdy)
                snk.ready_now = rdy
        if between is not None:
            await between(cycle)
            for snk in sinks:
                snk.ready_now = bool(snk.bus.ready.value)
        await edge
        cycle += 1
        for src in sources:
            fired = src.driving and bool(src.bus.ready.value)
            if fired:
                src.idx += 1
                src.taken.append(cycle)
            src.held = src.driving and not fired
        for snk in sinks:
            if snk.ready_now:
                if snk.bus.valid.value:
                    snk.got.append(tuple(int(h.value) for h in snk.bus.handles))
                    if snk.first_cycle < 0:
                        snk.first_cycle = cycle
                    snk.last_cycle = cycle
                    snk.stalls = snk._stalls_running
            elif snk.first_cycle >= 0:
                snk._stalls_running += 1
        if stop is not None and stop(cycle):
            break
    if release:
        for src in sources:
            if src.driving:
                src.bus.valid.value = 0
                src.driving = False
                src.held = False
        for snk in sinks:
            snk.bus.ready.value = 0
            snk.ready_now = False
    return cycle
