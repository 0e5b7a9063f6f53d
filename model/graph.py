"""The stage graph's machinery: a stage, what it may read, and the planner that runs only
the stages a request needs, each once (:mod:`model.pipeline` builds the graph,
:mod:`model.stages` holds the stages)."""


from __future__ import annotations

from collections import Counter
from collections.abc import Callable, Iterable, Iterator, Mapping, Sequence
from contextlib import contextmanager
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from irnuc.model import noise as _noise
from irnuc.model.fpa import ArrayLayout
from irnuc.model.scenes import Scene
from irnuc.model.validate import ConfigError

#: Per-frame environment a run may vary (arrays of one value per frame): substrate and
#: housing temperature (K), shutter closed (bool), the shutter's temperature (K) and the
#: lens's (K; absent: at the housing).
ENV_FIELDS = ("T_substrate", "T_cam", "shutter", "T_shutter", "T_lens")


@dataclass(frozen=True)
class Stage:
    """One node of the graph: ``fn(ctx, inputs) -> outputs`` (dicts keyed by product)."""

    name: str
    inputs: tuple[str, ...]
    outputs: tuple[str, ...]
    per_chunk: bool
    fn: Callable[[RunContext, dict[str, Any]], dict[str, Any]]


@dataclass
class RunContext:
    """What a stage may read besides its inputs."""

    cfg: Mapping[str, Any]
    layout: ArrayLayout
    scene: Scene
    seed: int
    temps: np.ndarray = field(default_factory=lambda: np.empty(0))
    first_frame: int = 0
    counts: Counter = field(default_factory=Counter)
    flicker: _noise.VossState | None = None
    #: ``demand(product)`` computes (once) and returns a product no stage input declared:
    #: for results needed only on a rare path, like the skimming fallback voltage.
    demand: Callable[[str], Any] | None = None
    #: This chunk's per-frame environment (keys of :data:`ENV_FIELDS`), or None: the
    #: configuration's, constant.
    env: Mapping[str, np.ndarray] | None = None
    #: State carried from chunk to chunk of one run (thermal memory, transient state).
    state: dict[str, Any] = field(default_factory=dict)
    #: Time between frames, s (the lagged and transient thermal modes).
    frame_period: float | None = None
    #: Settings of the transient thermal mode (:class:`model.transient.TransientSettings`).
    transient: Any = None

    def frames(self) -> int:
        return len(self.temps)

    def substrate(self, n: int) -> np.ndarray:
        """(n,) substrate temperature of this chunk's frames, K."""
        if self.env is not None and "T_substrate" in self.env:
            return np.asarray(self.env["T_substrate"], dtype=np.float64)
        return np.full(n, float(self.cfg["environment"]["T_substrate"]))


#: Pixel-frames below which a kernel runs on one thread. A pass over one VGA frame takes
#: about a millisecond; splitting it saves little, and on a busy machine the wait for the
#: second thread's core costs several times more (measured: 13 ms for a VGA frame on one
#: thread, 28 ms on two, with the machine's other jobs running). Chunks of many frames
#: are split.
PARALLEL_MIN_WORK = 1_000_000


@contextmanager
def threads_for(work: int) -> Iterator[None]:
    """Run the numba kernels inside on one thread when ``work`` (pixel-frames) is small."""
    import numba

    if work >= PARALLEL_MIN_WORK:
        yield
        return
    before = numba.get_num_threads()
    numba.set_num_threads(1)
    try:
        yield
    finally:
        numba.set_num_threads(before)


def plan(stages: Sequence[Stage], products: Iterable[str],
         have: Iterable[str] = ()) -> list[Stage]:
    """The stages needed for ``products``, each once, in dependency order; products in
    ``have`` are already known and need no stage."""
    producer = {out: s for s in stages for out in s.outputs}
    order: list[Stage] = []
    seen: set[str] = set()
    known = set(have)

    def visit(product: str) -> None:
        if product in known:
            return
        if product not in producer:
            raise ConfigError(f"no stage produces {product!r}")
        stage = producer[product]
        if stage.name in seen:
            return
        for dep in stage.inputs:
            visit(dep)
        seen.add(stage.name)
        order.append(stage)

    for p in products:
        visit(p)
    return order


def run_planned(stages: Sequence[Stage], ctx: RunContext, values: dict[str, Any],
                products: Sequence[str]) -> None:
    """Run the stages that ``products`` need beyond the products already in ``values``,
    counting each in ``ctx.counts``; results are added to ``values``. Stages asking for a
    product on demand get it computed into ``values`` the same way."""
    if ctx.demand is None:
        def demand(product: str) -> Any:
            run_planned(stages, ctx, values, [product])
            return values[product]

        ctx.demand = demand
    for stage in plan(stages, products, values):
        ctx.counts[stage.name] += 1
        values.update(stage.fn(ctx, {k: values[k] for k in stage.inputs}))
