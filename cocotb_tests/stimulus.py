"""Constrained-random stimulus of ``nuc_dpc_top`` (pure numpy; run by ``tb_top``):

* :func:`size_walk`: a sequence of frame sizes whose consecutive pairs change size across
  every width class and every height class (1, 2, 3, small, max: ``coverage.SIZE_CLASSES``)
  and whose frames hit every width class x height class;
* :class:`DpcSchedule`: when ``dpc_ctrl`` takes each item (pixel or flush phantom) at a
  full-rate output, from the cycles the pixels were taken at the input. It tells when the
  next frame's size may be applied (the frame size is sampled in ``dpc_core``, about
  ``D`` cycles after the input: docs/rtl.md, "Frame size rule") and predicts the cycle of
  every output, which the test compares with the DUT;
* :func:`size_gate`: a pause generator for the pixel source that holds a frame of a new
  size until that is legal: at once after the previous frame's first pixel was sampled
  (by the schedule, at full rate), or, with idle and backpressure, when the previous frame
  is longer than the pipeline holds or its first output has left;
* :func:`nuc_preimage`: raw code, gain and offset codes that give chosen NUC outputs (the
  DPC's input values), checked with the golden model;
* :func:`dpc_neighbourhoods`: frames whose bad pixels have a chosen good-neighbour count,
  residue of the neighbour sum modulo that count and range of their mean.
"""

from __future__ import annotations

from collections.abc import Callable, Iterator, Sequence
from dataclasses import dataclass, field

import numpy as np

from irnuc.cosim import coverage
from irnuc.nuc_fixed import PipelineConfig, nuc_core, pack_words

# ---- size classes ------------------------------------------------------------------------


def class_value(cls: str, vmax: int, rng: np.random.Generator, avoid: int | None = None) -> int:
    """A dimension of class ``cls`` (``small``: 4 .. min(vmax - 1, 8), not ``avoid`` when
    there is another choice)."""
    if cls == "max":
        return vmax
    if cls != "small":
        return int(cls)
    choices = [v for v in range(4, min(vmax - 1, 8) + 1) if v != avoid] or [4]
    return int(rng.choice(choices))


def pair_walk(symbols: Sequence[str]) -> list[str]:
    """A sequence over ``symbols`` in which every ordered pair (a, b), a = b included,
    occurs once as consecutive elements (an Eulerian circuit of the complete directed
    graph with loops, by Hierholzer's algorithm; k^2 + 1 elements)."""
    if not symbols:
        return []
    out_edges = {a: list(symbols) for a in symbols}
    stack, walk = [symbols[0]], []
    while stack:
        v = stack[-1]
        if out_edges[v]:
            stack.append(out_edges[v].pop())
        else:
            walk.append(stack.pop())
    return walk[::-1]


def size_walk(cfg: PipelineConfig, rng: np.random.Generator,
              budget: int = coverage.SIZE_CLASS_FRAME_BUDGET) -> list[tuple[int, int]]:
    """(H, W) of consecutive frames in which every width-class change and every
    height-class change (from any class to any class, :data:`coverage.SIZE_CLASSES`) occurs
    between two consecutive frames of different sizes, and every width class x height
    class is a frame (a MaxWidth x MaxHeight frame only within ``budget`` pixels).

    Three walks, concatenated: the width classes in :func:`pair_walk` order with the
    height 1, moved to 2 (when it can) where the width class repeats so that the size
    changes; the same for the heights; then every class pair as a frame. A repeated class
    with one value (1, 2, 3, max) and the other dimension's maximum 1 cannot change the
    size: that change is left out (the coverage model removes its bin)."""
    mw, mh = cfg.max_width, cfg.max_height
    if mw * mh == 1:
        return [(1, 1), (1, 1)]
    frames: list[tuple[int, int]] = []

    def dim_walk(classes: Sequence[str], vmax: int, omax: int) -> list[tuple[int, int]]:
        """(value, other value) of one walk over the classes of one dimension."""
        out: list[tuple[int, int]] = []
        other = 1
        for cls in pair_walk(classes):
            prev = out[-1] if out else None
            v = class_value(cls, vmax, rng, prev[0] if prev else None)
            if prev is not None and v == prev[0]:
                if omax < 2:
                    continue  # cannot change the size: that bin is removed
                other = 3 - other
            out.append((v, other))
        return out

    frames += [(h, w) for w, h in dim_walk(coverage.dim_classes(mw), mw, mh)]
    frames += list(dim_walk(coverage.dim_classes(mh), mh, mw))
    for cw in coverage.dim_classes(mw):
        for ch in coverage.dim_classes(mh):
            if cw == ch == "max" and mw * mh > budget:
                continue
            hw = (class_value(ch, mh, rng), class_value(cw, mw, rng))
            if frames and hw == frames[-1]:
                frames.append((1, 1) if hw != (1, 1) else (1, 2) if mw > 1 else (2, 1))
            frames.append(hw)
    return frames


# ---- when the DPC takes each item ------------------------------------------------------------

@dataclass
class DpcSchedule:
    """When ``dpc_ctrl`` takes each item of a frame sequence, at a full-rate output.

    From the cycle ``t`` a pixel was taken at the input it reaches ``dpc_ctrl`` at ``t + D``
    (``D``: the register stages before the window, ``coverage.pipeline_stages``); the DPC
    takes it then, or one cycle after the previous pixel; a frame's first pixel waits for
    the previous frame's flush (W + 1 phantoms) unless it is of the same size and waiting
    at the tail decision (docs/rtl.md, "Frame/flush FSM"). After a flush, the first W + 1
    items emit no output and every further item emits one; an output leaves the DPC's
    output register ``after`` cycles after its item entered the window.
    """

    cfg: PipelineConfig
    sizes: Sequence[tuple[int, int]]
    d: int = 0
    after: int = 0
    frame_of: list[int] = field(default_factory=list)
    take: list[int] = field(default_factory=list)   # ctrl take cycle of every pixel
    emits: list[int] = field(default_factory=list)  # cycles of the items that emit
    phantoms: list[int] = field(default_factory=list)
    _since_idle: int = 0
    _geo_w: int = 1
    _idle_from: int = 0

    def __post_init__(self) -> None:
        stages = coverage.pipeline_stages("nuc_dpc_top", self.cfg)[:-1]
        self.d = stages.index("dpc_window")
        self.after = len(stages) - self.d
        self.frame_of = [f for f, (h, w) in enumerate(self.sizes) for _ in range(h * w)]
        self.starts = list(np.cumsum([0] + [h * w for h, w in self.sizes]))

    def _item(self, c: int) -> None:
        if self._since_idle >= self._geo_w + 1:
            self.emits.append(c)
        self._since_idle += 1

    def _flush(self, last: int, w: int) -> int:
        for k in range(w + 1):
            self.phantoms.append(last + 1 + k)
            self._item(last + 1 + k)
        self._since_idle = 0
        return last + w + 2

    def update(self, taken: Sequence[int]) -> None:
        """Extend the schedule with the pixels taken at the input since the last call."""
        while len(self.take) < len(taken):
            j = len(self.take)
            a = taken[j] + self.d
            f = self.frame_of[j]
            if j == self.starts[f]:
                if f > 0:
                    last = self.take[-1]
                    if self.sizes[f] == self.sizes[f - 1] and a <= last + 1:
                        c = last + 1
                    else:
                        self._idle_from = self._flush(last, self.sizes[f - 1][1])
                        c = max(a, self._idle_from)
                else:
                    c = max(a, self._idle_from)
                if self._since_idle == 0:
                    self._geo_w = self.sizes[f][1]
            else:
                c = max(a, self.take[-1] + 1)
            self.take.append(c)
            self._item(c)

    def finish(self) -> None:
        """The last frame's flush (no pixel follows)."""
        if self.take and len(self.take) == len(self.frame_of):
            self._flush(self.take[-1], self.sizes[-1][1])

    def first_taken(self, f: int) -> int | None:
        """Cycle the DPC took frame f's first pixel (None: not yet known)."""
        j = self.starts[f]
        return self.take[j] if j < len(self.take) else None

    def output_cycles(self) -> list[int]:
        """Predicted cycle (at the output) of every output, in order."""
        return [c + self.after for c in self.emits]


def pipeline_capacity(cfg: PipelineConfig) -> int:
    """Most items between ``nuc_dpc_top``'s input and ``dpc_ctrl``: one per register stage
    before the window and one more in each of the four spill registers' skid slots."""
    stages = coverage.pipeline_stages("nuc_dpc_top", cfg)[:-1]
    return stages.index("dpc_window") + 4


class size_gate(Iterator[bool]):  # lower case: used like pause_pattern's generators
    """Pause generator of the pixel source: pause while the next item is the first pixel of
    a frame whose size may not be applied yet.

    ``mode="schedule"`` (full-rate output only): frame b of a new size is offered from
    ``first_taken(b - 1) + delay[b]`` on, the earliest cycle the frame size rule allows plus
    a chosen delay. ``mode="observed"`` (any idle and backpressure): offered when the
    previous frame has more pixels than the pipeline holds, or once its first output has
    left. :meth:`tick` must be called after every edge (``run_streams(stop=gate.tick)``).
    """

    pattern = "gated"

    def __init__(self, cfg: PipelineConfig, sizes: Sequence[tuple[int, int]], mode: str,
                 delays: Sequence[int] = (), idle: Iterator[bool] | None = None) -> None:
        self.sizes, self.mode = list(sizes), mode
        self.schedule = DpcSchedule(cfg, sizes)
        self.delays = list(delays) or [0] * len(sizes)
        self.capacity = pipeline_capacity(cfg)
        self.idle = idle
        self.edges = 0
        self.source = None   # the pixel Source (set by the test)
        self.sink = None     # the Sink
        self.offered: list[int] = []  # cycle each frame's first pixel was first offered

    def tick(self, cycle: int) -> bool:
        self.edges = cycle
        if self.mode == "schedule" and self.source is not None:
            self.schedule.update(self.source.taken)
        return False

    def _allowed(self, f: int, now: int) -> bool:
        if f == 0 or self.sizes[f] == self.sizes[f - 1]:
            return True
        if self.mode == "schedule":
            first = self.schedule.first_taken(f - 1)
            return first is not None and now >= first + self.delays[f]
        h, w = self.sizes[f - 1]
        if h * w > self.capacity + 1:
            return True
        before = int(self.schedule.starts[f - 1])
        return self.sink is not None and len(self.sink.got) > before

    def __next__(self) -> bool:
        now = self.edges + 1
        idx = self.source.idx
        f = self.schedule.frame_of[idx] if idx < len(self.schedule.frame_of) else 0
        first = idx == self.schedule.starts[f]
        if first and not self._allowed(f, now):
            return True
        if self.idle is not None and next(self.idle):
            return True
        if first and len(self.offered) == f:
            self.offered.append(now)
        return False


# ---- NUC inputs for chosen outputs ---------------------------------------------------------

def nuc_preimage(cfg: PipelineConfig, y: np.ndarray
                 ) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Raw codes x, gain codes g and offset codes o with NUC output ``y`` (where found):
    returns x, g, o and a mask of the targets found, every one checked with the golden
    model (``nuc_fixed.nuc_core``).

    For a target y the sum s (units of 2^-F) is aimed at [y 2^F, y 2^F + 2^(F-1) - 1]
    (below one half: every rounding mode gives y), from the offset alone, or from a
    product x g (several gains tried) plus an offset; a saturated target (0, 2^B - 1) also
    from the most negative or largest inputs, a wrapped one from r = y - 2^B or y + 2^B.
    """
    y = np.asarray(y, dtype=np.int64).ravel()
    f, gf, of = cfg.frac_bits, cfg.gain_frac_bits, cfg.offset_frac_bits
    xmax, gmax = (1 << cfg.adc_bits) - 1, (1 << cfg.gain_bits) - 1
    omin, omax = -(1 << (cfg.offset_bits - 1)), (1 << (cfg.offset_bits - 1)) - 1
    full = (1 << cfg.out_bits) - 1
    n = y.size
    bx, bg, bo = np.zeros(n, np.int64), np.zeros(n, np.int64), np.zeros(n, np.int64)
    found = np.zeros(n, bool)
    gains = sorted({0, 1, gmax, min(gmax, 1 << gf), max(1, gmax >> 1), max(1, gmax // 3),
                    max(1, min(gmax, (1 << gf) >> 1))})
    targets = [y]
    if cfg.overflow == "wrap":
        targets += [y - (1 << cfg.out_bits), y + (1 << cfg.out_bits)]
    for r in targets:
        for g in gains:
            todo = ~found
            if not todo.any():
                break
            lo = r[todo] << f  # aim s at lo .. lo + half
            # Largest x whose product stays at or below the aim, and one below it.
            step = g << (f - gf)
            for dx in (0, -1, -2):
                if g == 0 and dx:
                    break
                x = np.zeros(lo.size, np.int64) if g == 0 else np.clip(
                    np.floor_divide(np.maximum(lo, 0), step) + dx, 0, xmax)
                rest = lo - x * step  # what the offset must add (units of 2^-F)
                unit = 1 << (f - of)
                o = np.clip(-np.floor_divide(-rest, unit), omin, omax)  # ceil
                idx = np.flatnonzero(todo)
                got = nuc_core(x, np.full(lo.size, g), o, cfg).astype(np.int64)
                ok = got == (r[todo] & full if cfg.overflow == "wrap" else
                             np.clip(r[todo], 0, full))
                ok &= (r[todo] == np.clip(r[todo], 0, full)) | (cfg.overflow == "wrap")
                sel = idx[ok]
                bx[sel], bg[sel], bo[sel] = x[ok], g, o[ok]
                found[sel] = True
                todo = ~found
                if not todo.any():
                    break
                lo = r[todo] << f
    if cfg.overflow == "saturate":
        for target, (xx, gg, oo) in ((0, (0, 0, omin)), (full, (xmax, gmax, omax))):
            sel = ~found & (y == target)
            if sel.any() and int(nuc_core(np.array([xx]), np.array([gg]), np.array([oo]),
                                          cfg)[0]) == target:
                bx[sel], bg[sel], bo[sel], found[sel] = xx, gg, oo, True
    if found.any():  # the reference decides
        assert (nuc_core(bx[found], bg[found], bo[found], cfg) == y[found]).all()
    return bx, bg, bo, found


# ---- DPC neighbourhoods --------------------------------------------------------------------

@dataclass
class Neighbourhoods:
    """Frames of chosen DPC neighbourhoods: raw codes and coefficient words per frame, the
    NUC outputs (the DPC's inputs) and bad maps, and the bins each frame targets."""

    raw: list[np.ndarray]
    words: list[np.ndarray]
    values: list[np.ndarray]
    bad: list[np.ndarray]
    targets: list[list[tuple[int, int, str]]]
    missing: list[tuple[int, int, str]]


def _split_sum(s: int, n: int, intervals: Sequence[tuple[int, int]],
               rng: np.random.Generator) -> list[int] | None:
    """n values, each in one of ``intervals``, summing to s (random)."""
    for _ in range(64):
        pick = [intervals[int(rng.integers(len(intervals)))] for _ in range(n)]
        lo, hi = sum(a for a, _ in pick), sum(b for _, b in pick)
        if not lo <= s <= hi:
            continue
        vals = [a for a, _ in pick]
        rest = s - lo
        for i in rng.permutation(n):
            add = int(rng.integers(0, min(rest, pick[i][1] - pick[i][0]) + 1)) \
                if rest else 0
            vals[i] += add
            rest -= add
        for i in range(n):  # what is left, wherever there is room
            add = min(rest, pick[i][1] - vals[i])
            vals[i] += add
            rest -= add
        if rest == 0:
            return vals
    return None


def dpc_neighbourhoods(cfg: PipelineConfig, rng: np.random.Generator,
                       bins: Sequence[tuple[int, int, str]],
                       intervals: Sequence[tuple[int, int]],
                       preimage: Callable[[np.ndarray], tuple] | None = None,
                       frame: tuple[int, int] = (12, 12), max_frames: int = 12
                       ) -> Neighbourhoods:
    """Frames whose bad pixels hit the bins ``(n, residue, range)``: each target is the
    centre of a 3 x 3 tile (tiles side by side, as many per frame as fit), bad, with n good
    in-frame neighbours (the others bad) whose values, drawn from ``intervals`` (the DPC's
    input codes), sum to S with S mod n = residue and S / n in the range.

    ``preimage`` maps the values to NUC inputs (:func:`nuc_preimage`; None: the values are
    driven as they are, for ``dpc_core``). A bin for which no sum or no preimage was found
    is listed in ``missing``, as are those beyond ``max_frames`` frames."""
    h, w = min(frame[0], cfg.max_height), min(frame[1], cfg.max_width)
    # Tile centres: every third row and column (a 1- or 2-wide frame: its only column).
    rows = list(range(1, h - 1, 3)) or [0] if h >= 3 else list(range(0, h, 3))
    cols = list(range(1, w - 1, 3)) or [0] if w >= 3 else list(range(0, w, 3))
    centres = [(r, c) for r in rows for c in cols]
    full = (1 << cfg.out_bits) - 1
    out = Neighbourhoods([], [], [], [], [], [])
    queue = list(bins)
    while queue:
        if len(out.raw) >= max_frames:  # a small maximum frame: the rest is missing
            out.missing.extend(queue)
            break
        vals = rng.integers(0, full + 1, size=(h, w), dtype=np.int64)
        if intervals:
            spans = np.array([b - a + 1 for a, b in intervals], dtype=float)
            k = rng.choice(len(intervals), size=(h, w), p=spans / spans.sum())
            lo = np.array([a for a, _ in intervals])[k]
            span = np.array([b - a for a, b in intervals])[k]
            vals = lo + (rng.random((h, w)) * (span + 1)).astype(np.int64).clip(0, span)
        bad = rng.random((h, w)) < 0.1
        placed, where = [], []
        for r, c in centres:
            if not queue:
                break
            n, res, rng_cls = queue.pop(0)
            nbs = [(r + dy, c + dx) for dy in (-1, 0, 1) for dx in (-1, 0, 1)
                   if (dy, dx) != (0, 0) and 0 <= r + dy < h and 0 <= c + dx < w]
            if n > len(nbs):
                out.missing.append((n, res, rng_cls))
                continue
            lo, hi = coverage._range_sums(n, cfg.out_bits, rng_cls)
            first = lo + (res - lo) % n
            count = (hi - first) // n + 1 if first <= hi else 0
            sums = [first + n * int(i) for i in rng.choice(count, size=min(8, count),
                                                            replace=False)] if count else []
            split = None
            for s in sums:
                split = _split_sum(int(s), n, intervals, rng)
                if split is not None:
                    break
            if split is None:
                out.missing.append((n, res, rng_cls))
                continue
            order = rng.permutation(len(nbs))
            good = [nbs[i] for i in order[:n]]
            for rr, cc in nbs:
                bad[rr, cc] = True
            for (rr, cc), v in zip(good, split, strict=True):
                bad[rr, cc] = False
                vals[rr, cc] = v
            bad[r, c] = True
            placed.append((n, res, rng_cls))
            where.append((r, c))
        if not placed and queue:
            continue
        if preimage is not None:
            x, g, o, ok = preimage(vals.ravel())
            if not ok.any():
                raise AssertionError("no NUC input gives any of the DPC input codes drawn")
            if not ok.all():
                # Codes inside the NUC's output range that no input gives (coarse offset
                # and product steps): take found codes there; the targets of the tiles
                # touched are listed as missing (coverage is sampled from the frame).
                src = rng.choice(np.flatnonzero(ok), size=int((~ok).sum()))
                for arr in (x, g, o):
                    arr[~ok] = arr[src]
                flat = vals.ravel()
                flat[~ok] = flat[src]
                vals = flat.reshape(h, w)
                hit = ~ok.reshape(h, w)
                for (r, c), target in zip(where, placed, strict=True):
                    if hit[max(r - 1, 0):r + 2, max(c - 1, 0):c + 2].any():
                        out.missing.append(target)
            raw = x.reshape(h, w)
            words = pack_words(g.reshape(h, w), o.reshape(h, w), bad, cfg)
        else:
            raw, words = vals, np.zeros((h, w), np.uint64)
        out.raw.append(raw)
        out.words.append(words)
        out.values.append(vals)
        out.bad.append(bad)
        out.targets.append(placed)
        if not placed:
            break
    return out


__all__ = ["DpcSchedule", "Neighbourhoods", "class_value", "dpc_neighbourhoods",
           "nuc_preimage", "pipeline_capacity", "size_gate", "size_walk"]
