"""Functional coverage (cocotb-coverage) and code coverage (Verilator) of the co-simulation.

Functional coverage
-------------------
:class:`CoverageModel` defines the coverpoints and crosses of one DUT (top module and
configuration) with ``cocotb_coverage.coverage`` (``CoverPoint``, ``CoverCross`` and its
``coverage_db``), and samples them from what the testbench really drove and checked:

===================== ==========================================================================
``nuc.round.<mode>``  fraction of s below / at / above one half, ties with an even and an odd
                      integer part (every rounding mode is a configuration: one coverpoint each)
``nuc.range.<mode>``  r below 0, in range, above 2^B - 1 (saturate or wrap)
``dpc.neighbours``    n = 0..8 good in-frame neighbours of a bad pixel
``dpc.position``      corner, edge, interior, thin (a pixel of a 1-pixel-wide frame)
``dpc.n_x_position``  the cross (a corner has 3 in-frame neighbours, an edge 5, a thin
                      pixel at most 2: the bins beyond are removed with that reason)
``dpc.bad_shape``     isolated, cluster, uncorrectable, whole row, whole column, all bad
``frame.size``        1x1, 1xN, Nx1, small, width = MaxWidth, height = MaxHeight
``frame.transition``  next frame back to back with the same size, width only changed,
                      height only changed, both changed, after an idle gap
``frame.error``       every cause of ``frame_err_o``: sof missing, sof unexpected, eol
                      missing, eol unexpected, width 0, height 0, width > MaxWidth,
                      height > MaxHeight (each alone)
``stream.idle``       the input pause patterns used ...
``stream.backpressure`` ... and the output ones
``stream.back_to_back`` consecutive frames without a bubble at full rate
``reset.stage``       reset while the oldest item is in each pipeline stage of the top, and
                      during the DPC's flush
``reset.window``      reset at every cycle of a window around a frame's end, the DPC's flush
                      and the next frame's start (offsets from the frame's last pixel)
``frame.size_class``  frames of every width class x height class (1, 2, 3, small, max)
``frame.change_width`` back-to-back size changes with the previous frame still in the
``frame.change_height`` pipeline, from every width (height) class to every width (height) class
``dpc.arith``         bad pixels with every good-neighbour count n x residue of the
                      neighbour sum mod n x range of their mean (low, middle, near full scale)
===================== ==========================================================================

A testbench samples through the model and calls :func:`export` (the whole database as
JSON to ``$IRNUC_TB_COVERAGE``); :func:`merge` adds such files up (hits per bin),
:func:`summarize` gives hit/total and the uncovered bins per coverpoint and per
configuration. Bins that cannot be reached are not in the model: they are listed under
``removed`` with the reason.

Code coverage
-------------
A build with ``coverage=True`` (``cosim.build``) writes Verilator's ``coverage.dat`` after
every run; :func:`read_coverage_dat` reads it and :func:`code_coverage` gives line and
toggle coverage per module, summed over every instance and every run. Merging, the summary
and the code-coverage reader live in :mod:`irnuc.cosim.coverage_data` (re-exported here).
"""

from __future__ import annotations

import json
import os
from collections.abc import Callable, Sequence
from pathlib import Path
from typing import Any

import numpy as np

from irnuc.cosim.coverage_data import (
    FORMAT_VERSION,
    code_coverage,
    merge,
    merge_data,
    merge_points,
    read_coverage_dat,
    summarize,
)
from irnuc.nuc_fixed import PipelineConfig, nuc_core, rtl_spec
from irnuc.nuc_fixed.dpc import neighbour_counts
from irnuc.nuc_fixed.methods.bins import RANGE_BINS, ROUND_BINS

#: Environment variable naming the JSON file a testbench exports its coverage to.
COVERAGE_ENV = "IRNUC_TB_COVERAGE"

POSITIONS = ("corner", "edge", "interior", "thin")
#: In-frame neighbours a pixel of each position class has at most.
MAX_NEIGHBOURS = {"corner": 3, "edge": 5, "interior": 8, "thin": 2}
BAD_SHAPES = ("isolated", "cluster", "uncorrectable", "whole_row", "whole_column", "all_bad")
FRAME_SIZES = ("1x1", "1xN", "Nx1", "small", "width_max", "height_max")
TRANSITIONS = ("same_size", "width_only", "height_only", "both", "after_idle")
FRAME_ERRORS = ("sof_missing", "sof_unexpected", "eol_missing", "eol_unexpected",
                "width_zero", "height_zero", "width_over_max", "height_over_max")
#: Pause patterns of the stream sources and sinks (cocotb_tests.streams.pause_pattern).
IDLE_PATTERNS = ("none", "random", "bursty", "alternate")
BACKPRESSURE_PATTERNS = ("none", "random", "bursty", "alternate")
#: Size classes of a frame dimension: 1, 2, 3 (the counters' special paths), small (4 up
#: to the maximum, exclusive) and max (the maximum, when it is at least 4).
SIZE_CLASSES = ("1", "2", "3", "small", "max")
#: Largest frame (pixels) the size-class stimulus drives: a MaxWidth x MaxHeight frame
#: above it is not driven (its bin is removed with that reason).
SIZE_CLASS_FRAME_BUDGET = 4096
#: Range of the mean of a bad pixel's good neighbours: low (at most a quarter of full
#: scale), near full scale (at least seven eighths), middle (in between).
DPC_RANGES = ("low", "mid", "high")
#: Frames of the reset window (``tb_top.reset_window``): frame A, then frame B of another
#: size back to back (each dimension clipped to the maximum), and cycles of the window
#: before A's last pixel is taken at the input.
RESET_WINDOW_FRAMES = ((2, 4), (3, 3))
RESET_WINDOW_BEFORE = 2


def pipeline_stages(top: str, cfg: PipelineConfig) -> list[str]:
    """The register stages an item passes in ``top``, in order (one name per register;
    docs/rtl.md, "Architecture"), ending with ``flush`` for the DPC's flush state: the
    stage model of :func:`irnuc.nuc_fixed.rtl_spec.pipeline_stages` for ``cfg``'s widths."""
    return rtl_spec.pipeline_stages(top, cfg.adc_bits, cfg.gain_bits, cfg.out_bits)


def dim_class(v: int, vmax: int) -> str:
    """Size class of a frame dimension ``v`` of at most ``vmax`` (:data:`SIZE_CLASSES`)."""
    if v == vmax and vmax >= 4:
        return "max"
    return str(v) if v <= 3 else "small"


def dim_classes(vmax: int) -> tuple[str, ...]:
    """The size classes a dimension of maximum ``vmax`` has."""
    return tuple(c for c in SIZE_CLASSES if {"1": True, "2": vmax >= 2, "3": vmax >= 3,
                                             "small": vmax >= 5, "max": vmax >= 4}[c])


def size_class_budget(cfg: PipelineConfig) -> bool:
    """Whether the size-class stimulus drives a MaxWidth x MaxHeight frame."""
    return cfg.max_width * cfg.max_height <= SIZE_CLASS_FRAME_BUDGET


def dpc_range(s: int, n: int, out_bits: int) -> str:
    """Range class of the mean S / n of a bad pixel's n good neighbours (sum S)."""
    full = n * ((1 << out_bits) - 1)
    if 4 * s <= full:
        return "low"
    return "high" if 8 * s >= 7 * full else "mid"


def _range_sums(n: int, out_bits: int, rng: str) -> tuple[int, int]:
    """The sums S of n neighbours whose mean is in range class ``rng`` (an interval)."""
    full = n * ((1 << out_bits) - 1)
    low_hi, high_lo = full // 4, -(-7 * full // 8)
    return {"low": (0, low_hi), "mid": (low_hi + 1, high_lo - 1), "high": (high_lo, full)}[rng]


def max_neighbours(max_width: int, max_height: int) -> int:
    """Most good in-frame neighbours a pixel of a frame of at most this size can have."""
    w, h = min(max_width, 3), min(max_height, 3)
    return w * h - 1


def sum_intervals(values: Sequence[tuple[int, int]], n: int) -> list[tuple[int, int]]:
    """The sums of n values, each from one of the intervals ``values`` (inclusive), as
    intervals (a sum of intervals is the interval of the sums)."""
    out: set[tuple[int, int]] = set()

    def rec(k: int, start: int, lo: int, hi: int) -> None:
        if k == n:
            out.add((lo, hi))
            return
        for i in range(start, len(values)):
            rec(k + 1, i, lo + values[i][0], hi + values[i][1])

    rec(0, 0, 0, 0)
    return sorted(out)


def dpc_arith_unreachable(n: int, r: int, rng: str, out_bits: int,
                          values: Sequence[tuple[int, int]]) -> bool:
    """Whether no sum of n neighbour values from the intervals ``values`` lies in range
    class ``rng`` with residue r mod n."""
    lo, hi = _range_sums(n, out_bits, rng)
    for a, b in sum_intervals(values, n):
        a, b = max(a, lo), min(b, hi)
        if a <= b and a + (r - a) % n <= b:
            return False
    return True


def nuc_output_intervals(cfg: PipelineConfig) -> list[tuple[int, int]]:
    """The NUC output codes of ``cfg`` (the DPC's input values) as intervals: OUT of every
    r between the smallest (x = 0, g = 0, the most negative offset) and the largest
    (largest code, gain and offset) sum, saturated or wrapped. The r between are all
    reachable when the offset spans more than one step of the product (always for the
    configurations drawn here; ``tb_top.dpc_arithmetic`` finds a preimage of every value
    it uses and fails if one is missing)."""
    it = nuc_core(np.array([0, (1 << cfg.adc_bits) - 1]),
                  np.array([0, (1 << cfg.gain_bits) - 1]),
                  np.array([-(1 << (cfg.offset_bits - 1)), (1 << (cfg.offset_bits - 1)) - 1]),
                  cfg, intermediates=True)
    lo, hi = int(it.r[0]), int(it.r[1])
    full = (1 << cfg.out_bits) - 1
    if cfg.overflow == "saturate":
        return [(min(max(lo, 0), full), min(max(hi, 0), full))]
    if hi - lo >= full:
        return [(0, full)]
    a, b = lo & full, hi & full
    return [(a, b)] if a <= b else [(0, b), (a, full)]


def small_maximum_removals(cfg: PipelineConfig) -> dict[str, dict[Any, str]]:
    """Bins of the frame and DPC coverpoints that a configuration with a small maximum
    frame (MaxWidth or MaxHeight below 3) cannot reach, with the reason."""
    mw, mh = cfg.max_width, cfg.max_height
    size = f"MaxWidth = {mw}, MaxHeight = {mh}"
    out: dict[str, dict[Any, str]] = {k: {} for k in (
        "dpc.neighbours", "dpc.position", "dpc.bad_shape", "frame.size", "frame.transition",
        "frame.error", "dpc.n_x_position")}
    # Most neighbours of each position class in a frame of at most mh x mw.
    reach = {"thin": min(2, max(mw, mh) - 1),
             "corner": 3 if mw >= 2 and mh >= 2 else -1,
             "edge": 5 if (mw >= 3 and mh >= 2) or (mh >= 3 and mw >= 2) else -1,
             "interior": 8 if mw >= 3 and mh >= 3 else -1}
    for pos, most in reach.items():
        if most < 0:
            out["dpc.position"][pos] = f"{size}: no {pos} pixel"
        for n in range(max(most, 0) + (most >= 0), MAX_NEIGHBOURS[pos] + 1):
            out["dpc.n_x_position"][(n, pos)] = f"{size}: a {pos} pixel has at most {most} " \
                                               "in-frame neighbours"
    nmax = max(reach.values())
    for n in range(nmax + 1, 9):
        out["dpc.neighbours"][n] = f"{size}: a pixel has at most {nmax} in-frame neighbours"
    if mw * mh == 1:
        for shape in ("cluster", "uncorrectable", "whole_row", "whole_column", "all_bad"):
            out["dpc.bad_shape"][shape] = f"{size}: every frame is one pixel"
        out["frame.error"]["sof_unexpected"] = f"{size}: every pixel starts a frame"
    if mw == 1:
        out["dpc.bad_shape"]["whole_row"] = f"{size}: a row is one pixel"
        out["frame.error"]["eol_unexpected"] = f"{size}: every pixel ends a line"
    if mh == 1:
        out["dpc.bad_shape"]["whole_column"] = f"{size}: a column is one pixel"
    for cls, need in (("1xN", mw >= 3), ("Nx1", mh >= 3), ("small", mw >= 3 and mh >= 3),
                      ("width_max", mw >= 2), ("height_max", mh >= 2)):
        if not need:
            out["frame.size"][cls] = f"{size}: no frame of this class"
    for tr, need in (("width_only", mw >= 2), ("height_only", mh >= 2),
                     ("both", mw >= 2 and mh >= 2)):
        if not need:
            out["frame.transition"][tr] = f"{size}: the size cannot change this way"
    for cause, port, vmax in (("width_over_max", "width", mw), ("height_over_max", "height",
                                                                   mh)):
        if vmax == (1 << rtl_spec.clog2(vmax + 1)) - 1:
            out["frame.error"][cause] = (f"Max{port.title()} = {vmax}: the {port} port is "
                                         "all ones at the maximum")
    return out


def dpc_arith_bins(cfg: PipelineConfig, top: str
                   ) -> tuple[list[tuple[int, int, str]], dict[tuple[int, int, str], str]]:
    """The bins (good-neighbour count n, residue of the sum mod n, range of the mean) of
    ``dpc.arith`` that ``top`` on ``cfg`` can reach, and those it cannot with the reason
    (more neighbours than the maximum frame gives; no sum of n DPC input codes with that
    residue and range: for ``nuc_dpc_top`` the codes are the NUC's outputs)."""
    c = cfg
    nmax = max_neighbours(c.max_width, c.max_height)
    values = (nuc_output_intervals(c) if top == "nuc_dpc_top"
              else [(0, (1 << c.out_bits) - 1)])
    bins, why = [], {}
    for n in range(1, 9):
        for r in range(n):
            for rng in DPC_RANGES:
                key = (n, r, rng)
                if n > nmax:
                    why[key] = (f"a frame of at most {c.max_height} x {c.max_width} "
                                f"gives a pixel at most {nmax} in-frame neighbours")
                elif dpc_arith_unreachable(n, r, rng, c.out_bits, values):
                    why[key] = (f"no sum of {n} values of {values} (the DPC's input "
                                f"codes here) has residue {r} and a {rng} mean")
                else:
                    bins.append(key)
    return bins, why


def reset_window(cfg: PipelineConfig) -> tuple[tuple[int, int], tuple[int, int], list[int]]:
    """Frames A and B of the reset window and its offsets: cycles from A's last pixel
    taken at the input (``-RESET_WINDOW_BEFORE``) until B's first output can leave (A's
    last pixel through the pipeline to the window, A's flush of W_A + 1 phantoms, B's
    first W_B + 1 items and the stages after the window, and one more)."""
    (ha, wa), (hb, wb) = ((min(h, cfg.max_height), min(w, cfg.max_width))
                          for h, w in RESET_WINDOW_FRAMES)
    if (hb, wb) == (ha, wa):  # a 1 x N or N x 1 maximum: make B another size if possible
        hb, wb = (ha, 1) if wa > 1 else (1, wa) if ha > 1 else (hb, wb)
    stages = pipeline_stages("nuc_dpc_top", cfg)[:-1]
    end = len(stages) + (wa + 1) + (wb + 1) + 1
    return (ha, wa), (hb, wb), list(range(-RESET_WINDOW_BEFORE, end + 1))


class CoverageModel:
    """The coverpoints of one DUT, registered in cocotb-coverage's ``coverage_db``.

    One model per simulator process (cocotb-coverage keeps one global database); every
    coverpoint name starts with ``<prefix>.``.
    """

    def __init__(self, top: str, cfg: PipelineConfig, prefix: str = "irnuc") -> None:
        from cocotb_coverage.coverage import CoverCross

        self.top, self.cfg, self.prefix = top, cfg, prefix
        self.removed: dict[str, dict[str, str]] = {}
        self._samplers: dict[str, Any] = {}
        nuc = top in ("nuc_core", "nuc_dpc_top")
        dpc = top in ("dpc_core", "nuc_dpc_top")

        point = self.add_point

        if nuc:
            f = cfg.frac_bits
            if f == 0:
                self.removed[f"nuc.round.{cfg.rounding}"] = {
                    b: "F = 0: the sum has no fraction bits, nothing is rounded"
                    for b in ROUND_BINS}
            else:
                point(f"nuc.round.{cfg.rounding}", ROUND_BINS)
            bins = list(RANGE_BINS)
            if not self._above_max_reachable():
                bins.remove("above_max")
                self.removed[f"nuc.range.{cfg.overflow}"] = {
                    "above_max": "the largest x * g + o stays below 2^B"}
            point(f"nuc.range.{cfg.overflow}", bins)
        if dpc:
            small = small_maximum_removals(cfg)
            for name, bins in (("dpc.neighbours", range(9)), ("dpc.position", POSITIONS),
                               ("dpc.bad_shape", BAD_SHAPES), ("frame.size", FRAME_SIZES),
                               ("frame.transition", TRANSITIONS),
                               ("frame.error", FRAME_ERRORS)):
                point(name, self._remove(name, list(bins), small.get(name, {})))
            ign = [(n, p) for p in POSITIONS for n in range(MAX_NEIGHBOURS[p] + 1, 9)]
            reasons = {str((n, p)): f"a {p} pixel has at most {MAX_NEIGHBOURS[p]} in-frame "
                                    "neighbours" for n, p in ign}
            for (n, p), why in small.get("dpc.n_x_position", {}).items():
                if (n, p) not in ign:
                    ign.append((n, p))
                    reasons[str((n, p))] = why
            cross = f"{prefix}.dpc.n_x_position"

            @CoverCross(cross, items=[f"{prefix}.dpc.neighbours", f"{prefix}.dpc.position"],
                        ign_bins=ign)
            def sample_cross(n: int, pos: str) -> None:
                pass

            self._cross = sample_cross
            self.removed["dpc.n_x_position"] = reasons
            self._frame_removals(point)
            self._dpc_arith(point, top)
        point("stream.idle", IDLE_PATTERNS)
        point("stream.backpressure", BACKPRESSURE_PATTERNS)
        point("stream.back_to_back", ("frames",))
        if top in ("nuc_core", "dpc_core", "nuc_dpc_top"):
            point("reset.stage", pipeline_stages(top, cfg))
        if top == "nuc_dpc_top":
            point("reset.window", reset_window(cfg)[2])

    # ---- helpers -----------------------------------------------------------------------
    def _remove(self, name: str, bins: list, why: dict) -> list:
        """Drop the bins ``why`` names from ``bins`` and record them as removed."""
        for b, reason in why.items():
            if b in bins:
                bins.remove(b)
                self.removed.setdefault(name, {})[str(b)] = reason
        return bins

    def _frame_removals(self, point: Callable[[str, Sequence[Any]], None]) -> None:
        """Frame size classes and size changes (the bins a small maximum cannot reach are
        removed with the reason); the frame sizes and transitions of small maxima."""
        c = self.cfg
        wc, hc = dim_classes(c.max_width), dim_classes(c.max_height)
        bins = [f"{w}x{h}" for w in SIZE_CLASSES for h in SIZE_CLASSES]
        why = {f"{w}x{h}": f"MaxWidth = {c.max_width}, MaxHeight = {c.max_height}: no frame "
               f"of width class {w} and height class {h}"
               for w in SIZE_CLASSES for h in SIZE_CLASSES if w not in wc or h not in hc}
        if not size_class_budget(c) and "max" in wc and "max" in hc:
            why["maxxmax"] = (f"a MaxWidth x MaxHeight frame ({c.max_width * c.max_height} "
                              f"pixels) exceeds the size-class budget of "
                              f"{SIZE_CLASS_FRAME_BUDGET}; random configurations with small "
                              "maxima drive it")
        point("frame.size_class", self._remove("frame.size_class", bins, why))
        for dim, have, vmax in (("width", wc, c.max_width), ("height", hc, c.max_height)):
            bins = [f"{a}->{b}" for a in SIZE_CLASSES for b in SIZE_CLASSES]
            why = {f"{a}->{b}": f"Max{dim.title()} = {vmax}: no {dim} of class "
                   f"{a if a not in have else b}"
                   for a in SIZE_CLASSES for b in SIZE_CLASSES if a not in have or b not in have}
            if c.max_width * c.max_height == 1:
                why.update({f"{a}->{b}": "a 1 x 1 maximum: the frame size never changes"
                            for a in have for b in have})
            elif (c.max_height if dim == "width" else c.max_width) == 1:
                # The other dimension is always 1: a class keeps the size unless it has
                # two values (small: 4 .. min(max - 1, 8)).
                why.update({f"{a}->{a}": f"Max{'Height' if dim == 'width' else 'Width'} = 1 "
                            f"and one {dim} of class {a}: the size cannot change"
                            for a in have if a != "small" or vmax < 6})
            point(f"frame.change_{dim}", self._remove(f"frame.change_{dim}", bins, why))

    def _dpc_arith(self, point: Callable[[str, Sequence[Any]], None], top: str) -> None:
        bins, why = dpc_arith_bins(self.cfg, top)
        point("dpc.arith", self._remove("dpc.arith", bins + list(why), why))

    def _above_max_reachable(self) -> bool:
        """The golden model at the largest code, gain and offset rounds above 2^B - 1."""
        c = self.cfg
        big = np.array([(1 << c.adc_bits) - 1])
        it = nuc_core(big, np.array([(1 << c.gain_bits) - 1]),
                      np.array([(1 << (c.offset_bits - 1)) - 1]), c, intermediates=True)
        return int(it.r[0]) > (1 << c.out_bits) - 1

    def has(self, name: str) -> bool:
        return name in self._samplers

    def add_point(self, name: str, bins: Sequence[Any]) -> None:
        """Register coverpoint ``<prefix>.<name>`` with ``bins`` (none: every bin was
        removed with its reason, so no coverpoint; sampling it is then ignored)."""
        if not bins:
            return
        from cocotb_coverage.coverage import CoverPoint

        @CoverPoint(f"{self.prefix}.{name}", xf=lambda v: v, bins=list(bins))
        def sample(v: Any) -> None:
            pass

        self._samplers[name] = sample

    def sample(self, name: str, value: Any, times: int = 1) -> None:
        """One hit (or ``times``) of ``value`` on coverpoint ``name``; unknown names of
        another DUT are ignored."""
        fn = self._samplers.get(name)
        if fn is not None:
            for _ in range(max(1, int(times))):
                fn(value)

    # ---- sampling from stimulus that was driven and checked -----------------------------
    def sample_nuc(self, x: np.ndarray, g: np.ndarray, o: np.ndarray) -> None:
        """Rounding and range classes of NUC inputs (one hit per class and call)."""
        c = self.cfg
        if x.size == 0:
            return
        it = nuc_core(np.asarray(x).ravel(), np.asarray(g).ravel(), np.asarray(o).ravel(),
                      c, intermediates=True)
        f = c.frac_bits
        if f > 0:
            frac = it.s & ((1 << f) - 1)
            half = 1 << (f - 1)
            odd = (it.s >> f) & 1
            classes = np.where(frac < half, 0, np.where(frac > half, 3, 1 + odd))
            for k in np.unique(classes):
                self.sample(f"nuc.round.{c.rounding}", ROUND_BINS[int(k)])
        r = it.r
        rng = np.where(r < 0, 0, np.where(r > (1 << c.out_bits) - 1, 2, 1))
        for k in np.unique(rng):
            self.sample(f"nuc.range.{c.overflow}", RANGE_BINS[int(k)])

    def sample_dpc(self, bad: np.ndarray) -> None:
        """Neighbour count x position of every bad pixel, and the bad-pixel shapes, of one
        (H, W) frame."""
        bad = np.asarray(bad, dtype=bool)
        h, w = bad.shape
        self.sample("frame.size", frame_size_class(h, w, self.cfg))
        if not bad.any():
            return
        n = neighbour_counts(bad)
        pos = position_classes(h, w)
        seen: set[tuple[int, str]] = set()
        for r, cc in zip(*np.nonzero(bad), strict=True):
            seen.add((int(n[r, cc]), str(pos[r, cc])))
        for k, p in sorted(seen):
            self.sample("dpc.neighbours", k)
            self.sample("dpc.position", p)
            if hasattr(self, "_cross"):
                self._cross(k, p)
        for shape in bad_shapes(bad):
            self.sample("dpc.bad_shape", shape)

    def sample_dpc_arith(self, y: np.ndarray, bad: np.ndarray) -> None:
        """Good-neighbour count x sum residue x range of every bad pixel with good
        neighbours, from the DPC's input codes ``y`` (H, W) of one checked frame."""
        bad = np.asarray(bad, dtype=bool)
        if not bad.any():
            return
        y = np.asarray(y, dtype=np.int64)
        h, w = bad.shape
        good = np.pad(~bad, 1)
        vals = np.pad(np.where(bad, 0, y), 1)
        s = sum(vals[1 + dy:1 + dy + h, 1 + dx:1 + dx + w] for dy in (-1, 0, 1)
                for dx in (-1, 0, 1) if (dy, dx) != (0, 0))
        n = sum(good[1 + dy:1 + dy + h, 1 + dx:1 + dx + w].astype(np.int64)
                for dy in (-1, 0, 1) for dx in (-1, 0, 1) if (dy, dx) != (0, 0))
        seen = {(int(k), int(ss) % int(k), dpc_range(int(ss), int(k), self.cfg.out_bits))
                for k, ss in zip(n[bad], s[bad], strict=True) if k > 0}
        for key in sorted(seen):
            self.sample("dpc.arith", key)

    def sample_size_changes(self, sizes: Sequence[tuple[int, int]],
                            full: Sequence[bool]) -> None:
        """Size classes of frames driven and checked, and their size changes: ``full[i]``
        tells whether frame i + 1 started with frame i still in the pipeline."""
        c = self.cfg
        for h, w in sizes:
            self.sample("frame.size_class",
                        f"{dim_class(w, c.max_width)}x{dim_class(h, c.max_height)}")
        for (h0, w0), (h1, w1), f in zip(sizes, sizes[1:], full, strict=False):
            if f and (h0, w0) != (h1, w1):
                self.sample("frame.change_width", f"{dim_class(w0, c.max_width)}->"
                            f"{dim_class(w1, c.max_width)}")
                self.sample("frame.change_height", f"{dim_class(h0, c.max_height)}->"
                            f"{dim_class(h1, c.max_height)}")

    def sample_frames(self, sizes: Sequence[tuple[int, int]], gaps: Sequence[int]) -> None:
        """Frame transitions: ``sizes`` of consecutive frames, ``gaps[i]`` idle cycles of the
        input before frame i + 1's first pixel (0: back to back)."""
        for (h0, w0), (h1, w1), gap in zip(sizes, sizes[1:], gaps, strict=False):
            if gap > 0:
                self.sample("frame.transition", "after_idle")
            elif (h0, w0) == (h1, w1):
                self.sample("frame.transition", "same_size")
            elif h0 == h1:
                self.sample("frame.transition", "width_only")
            elif w0 == w1:
                self.sample("frame.transition", "height_only")
            else:
                self.sample("frame.transition", "both")

    # ---- export -------------------------------------------------------------------------
    def snapshot(self) -> dict[str, Any]:
        """This model's coverpoints and crosses as a JSON-ready dict (hits per bin)."""
        from cocotb_coverage.coverage import coverage_db

        points: dict[str, Any] = {}
        pre = f"{self.prefix}."
        for name in sorted(coverage_db):
            item = coverage_db[name]
            if not name.startswith(pre) or not hasattr(item, "detailed_coverage"):
                continue
            if type(item).__name__ not in ("CoverPoint", "CoverCross"):
                continue
            short = name[len(pre):]
            bins = {_bin_key(k): int(v) for k, v in item.detailed_coverage.items()}
            points[short] = {"kind": "cross" if type(item).__name__ == "CoverCross"
                             else "point", "bins": bins,
                             "removed": dict(self.removed.get(short, {}))}
        for short, rem in self.removed.items():
            points.setdefault(short, {"kind": "point", "bins": {}, "removed": dict(rem)})
        return {"version": FORMAT_VERSION, "configurations": {config_label(self.cfg): {
            "config_digest": self.cfg.digest(), "tops": [self.top], "coverpoints": points}}}


def config_label(cfg: PipelineConfig) -> str:
    """The configuration's name, with its modes when they differ from the named one
    (``minimal+truncate+wrap``): coverage is kept per such label."""
    from irnuc.nuc_fixed import load_pipeline, pipeline_names

    if cfg.name in pipeline_names() and load_pipeline(cfg.name) == cfg:
        return cfg.name
    return f"{cfg.name}+{cfg.rounding}+{cfg.overflow}"


def _bin_key(k: Any) -> str:
    return str(tuple(k)) if isinstance(k, tuple) else str(k)


def frame_size_class(h: int, w: int, cfg: PipelineConfig) -> str:
    if w == cfg.max_width and w > 1:
        return "width_max"
    if h == cfg.max_height and h > 1:
        return "height_max"
    if h == 1 and w == 1:
        return "1x1"
    if h == 1:
        return "1xN"
    if w == 1:
        return "Nx1"
    return "small"


def position_classes(h: int, w: int) -> np.ndarray:
    """corner / edge / interior / thin for every pixel of an (H, W) frame."""
    ys, xs = np.mgrid[0:h, 0:w]
    borders = ((ys == 0).astype(int) + (ys == h - 1) + (xs == 0) + (xs == w - 1))
    out = np.where(borders == 0, "interior", np.where(borders == 1, "edge", "corner"))
    if h == 1 or w == 1:
        out[:] = "thin"
    return out.astype(object)


def bad_shapes(bad: np.ndarray) -> set[str]:
    """The shapes a bad map holds (see :data:`BAD_SHAPES`)."""
    h, w = bad.shape
    out: set[str] = set()
    if bad.all() and bad.size > 1:
        out.add("all_bad")
    if w > 1 and bad.all(axis=1).any():
        out.add("whole_row")
    if h > 1 and bad.all(axis=0).any():
        out.add("whole_column")
    p = np.pad(bad, 1)
    nb = sum(p[1 + dy:1 + dy + h, 1 + dx:1 + dx + w] for dy in (-1, 0, 1)
             for dx in (-1, 0, 1) if (dy, dx) != (0, 0))
    if (bad & (nb == 0)).any():
        out.add("isolated")
    if (bad & (nb > 0)).any():
        out.add("cluster")
    if (bad & (neighbour_counts(bad) == 0) & (nb > 0)).any():
        out.add("uncorrectable")
    return out


# ---- export --------------------------------------------------------------------------------------

_MODELS: dict[tuple[str, str], CoverageModel] = {}


def enabled() -> bool:
    """Whether this simulation exports coverage (``$IRNUC_TB_COVERAGE`` is set): testbenches
    skip the sampling work otherwise (mutation runs, plain pytest runs without export)."""
    return bool(os.environ.get(COVERAGE_ENV))


def model(top: str, cfg: PipelineConfig) -> CoverageModel:
    """The process's coverage model of ``top`` on ``cfg`` (made once)."""
    key = (top, cfg.digest())
    if key not in _MODELS:
        from irnuc.cosim.axis_coverage import (
            AXIS_TOPS,
            TRAFFIC_TOP,
            AxisCoverageModel,
            TrafficCoverageModel,
        )
        from irnuc.cosim.method_coverage import METHOD_TOPS, MethodCoverageModel
        from irnuc.cosim.stage_coverage import (
            DRIFT_TOPS,
            FFC_TOPS,
            DriftCoverageModel,
            FfcCoverageModel,
        )

        cls = (TrafficCoverageModel if top == TRAFFIC_TOP else
               MethodCoverageModel if top in METHOD_TOPS else
               AxisCoverageModel if top in AXIS_TOPS else
               FfcCoverageModel if top in FFC_TOPS else
               DriftCoverageModel if top in DRIFT_TOPS else CoverageModel)
        _MODELS[key] = cls(top, cfg)
    return _MODELS[key]


def export(path: str | Path | None = None) -> Path | None:
    """Write every model of this process as one JSON file (``$IRNUC_TB_COVERAGE`` when no
    path is given; nothing when neither is set)."""
    path = path or os.environ.get(COVERAGE_ENV)
    if not path or not _MODELS:
        return None
    data = merge_data([m.snapshot() for m in _MODELS.values()], add_hits=False)
    p = Path(path)
    p.parent.mkdir(parents=True, exist_ok=True)
    tmp = p.with_suffix(".tmp")
    tmp.write_text(json.dumps(data, indent=1, sort_keys=True))
    os.replace(tmp, p)
    return p


__all__ = [
    "BACKPRESSURE_PATTERNS",
    "COVERAGE_ENV",
    "FRAME_ERRORS",
    "IDLE_PATTERNS",
    "CoverageModel",
    "code_coverage",
    "enabled",
    "export",
    "merge",
    "merge_data",
    "merge_points",
    "model",
    "pipeline_stages",
    "read_coverage_dat",
    "summarize",
]
