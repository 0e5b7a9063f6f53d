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
toggle coverage per module, summed over every instance and every run.
"""

from __future__ import annotations

import json
import os
from collections.abc import Iterable, Mapping, Sequence
from pathlib import Path
from typing import Any

import numpy as np

from irnuc.nuc_fixed import PipelineConfig, nuc_core, rtl_spec
from irnuc.nuc_fixed.dpc import neighbour_counts

#: Environment variable naming the JSON file a testbench exports its coverage to.
COVERAGE_ENV = "IRNUC_TB_COVERAGE"
#: Schema version of the exported and merged coverage files.
FORMAT_VERSION = 1

ROUND_BINS = ("below_half", "tie_even", "tie_odd", "above_half")
RANGE_BINS = ("below_zero", "in_range", "above_max")
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


def pipeline_stages(top: str, cfg: PipelineConfig) -> list[str]:
    """The register stages an item passes in ``top``, in order (one name per register;
    docs/rtl.md, "Architecture"), ending with ``flush`` for the DPC's flush state: the
    stage model of :func:`irnuc.nuc_fixed.rtl_spec.pipeline_stages` for ``cfg``'s widths."""
    return rtl_spec.pipeline_stages(top, cfg.adc_bits, cfg.gain_bits, cfg.out_bits)


class CoverageModel:
    """The coverpoints of one DUT, registered in cocotb-coverage's ``coverage_db``.

    One model per simulator process (cocotb-coverage keeps one global database); every
    coverpoint name starts with ``<prefix>.``.
    """

    def __init__(self, top: str, cfg: PipelineConfig, prefix: str = "irnuc") -> None:
        from cocotb_coverage.coverage import CoverCross, CoverPoint

        self.top, self.cfg, self.prefix = top, cfg, prefix
        self.removed: dict[str, dict[str, str]] = {}
        self._samplers: dict[str, Any] = {}
        nuc = top in ("nuc_core", "nuc_dpc_top")
        dpc = top in ("dpc_core", "nuc_dpc_top")

        def point(name: str, bins: Sequence[Any]) -> None:
            full = f"{prefix}.{name}"

            @CoverPoint(full, xf=lambda v: v, bins=list(bins))
            def sample(v: Any) -> None:
                pass

            self._samplers[name] = sample

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
            point("dpc.neighbours", range(9))
            point("dpc.position", POSITIONS)
            point("dpc.bad_shape", BAD_SHAPES)
            sizes = list(FRAME_SIZES)
            point("frame.size", sizes)
            point("frame.transition", TRANSITIONS)
            point("frame.error", FRAME_ERRORS)
            ign = [(n, p) for p in POSITIONS for n in range(MAX_NEIGHBOURS[p] + 1, 9)]
            cross = f"{prefix}.dpc.n_x_position"

            @CoverCross(cross, items=[f"{prefix}.dpc.neighbours", f"{prefix}.dpc.position"],
                        ign_bins=ign)
            def sample_cross(n: int, pos: str) -> None:
                pass

            self._cross = sample_cross
            self.removed["dpc.n_x_position"] = {
                str((n, p)): f"a {p} pixel has at most {MAX_NEIGHBOURS[p]} in-frame "
                             "neighbours" for n, p in ign}
        point("stream.idle", IDLE_PATTERNS)
        point("stream.backpressure", BACKPRESSURE_PATTERNS)
        point("stream.back_to_back", ("frames",))
        if top in ("nuc_core", "dpc_core", "nuc_dpc_top"):
            point("reset.stage", pipeline_stages(top, cfg))

    # ---- helpers -----------------------------------------------------------------------
    def _above_max_reachable(self) -> bool:
        """The golden model at the largest code, gain and offset rounds above 2^B - 1."""
        c = self.cfg
        big = np.array([(1 << c.adc_bits) - 1])
        it = nuc_core(big, np.array([(1 << c.gain_bits) - 1]),
                      np.array([(1 << (c.offset_bits - 1)) - 1]), c, intermediates=True)
        return int(it.r[0]) > (1 << c.out_bits) - 1

    def has(self, name: str) -> bool:
        return name in self._samplers

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


# ---- files: export, merge, summary -----------------------------------------------------------

_MODELS: dict[tuple[str, str], CoverageModel] = {}


def enabled() -> bool:
    """Whether this simulation exports coverage (``$IRNUC_TB_COVERAGE`` is set): testbenches
    skip the sampling work otherwise (mutation runs, plain pytest runs without export)."""
    return bool(os.environ.get(COVERAGE_ENV))


def model(top: str, cfg: PipelineConfig) -> CoverageModel:
    """The process's coverage model of ``top`` on ``cfg`` (made once)."""
    key = (top, cfg.digest())
    if key not in _MODELS:
        from irnuc.cosim.axis_coverage import AXIS_TOPS, AxisCoverageModel
        from irnuc.cosim.method_coverage import METHOD_TOPS, MethodCoverageModel

        cls = (MethodCoverageModel if top in METHOD_TOPS else
               AxisCoverageModel if top in AXIS_TOPS else CoverageModel)
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


def merge_data(datas: Iterable[Mapping[str, Any]], add_hits: bool = True) -> dict[str, Any]:
    """Merge coverage dicts: per configuration, per coverpoint, hits added per bin (or
    the maximum with ``add_hits=False``, for snapshots of one database)."""
    out: dict[str, Any] = {"version": FORMAT_VERSION, "configurations": {}}
    for data in datas:
        for cname, cdata in data.get("configurations", {}).items():
            dst = out["configurations"].setdefault(
                cname, {"config_digest": cdata.get("config_digest"), "tops": [],
                        "coverpoints": {}})
            dst["tops"] = sorted(set(dst["tops"]) | set(cdata.get("tops", [])))
            for pname, p in cdata.get("coverpoints", {}).items():
                d = dst["coverpoints"].setdefault(
                    pname, {"kind": p.get("kind", "point"), "bins": {}, "removed": {}})
                for b, hits in p.get("bins", {}).items():
                    old = d["bins"].get(b, 0)
                    d["bins"][b] = old + int(hits) if add_hits else max(old, int(hits))
                d["removed"].update(p.get("removed", {}))
    return out


def merge(paths: Iterable[str | Path]) -> dict[str, Any]:
    """Merge exported coverage files (missing files are skipped)."""
    datas = []
    for p in paths:
        p = Path(p)
        if p.is_file():
            datas.append(json.loads(p.read_text()))
    return merge_data(datas)


def summarize(data: Mapping[str, Any]) -> dict[str, Any]:
    """hit/total, percent and uncovered bins per coverpoint, per configuration and over
    everything (a JSON-ready dict)."""
    out: dict[str, Any] = {"configurations": {}}
    all_hit = all_total = 0
    for cname, cdata in sorted(data.get("configurations", {}).items()):
        points = {}
        c_hit = c_total = 0
        uncovered: list[str] = []
        for pname, p in sorted(cdata.get("coverpoints", {}).items()):
            bins = p.get("bins", {})
            hit = sum(1 for v in bins.values() if v > 0)
            miss = [b for b, v in bins.items() if v <= 0]
            points[pname] = {"kind": p.get("kind", "point"), "hit": hit, "total": len(bins),
                             "percent": _pct(hit, len(bins)), "bins": dict(bins),
                             "uncovered": miss, "removed": dict(p.get("removed", {}))}
            c_hit += hit
            c_total += len(bins)
            uncovered += [f"{pname}:{b}" for b in miss]
        out["configurations"][cname] = {"hit": c_hit, "total": c_total,
                                        "percent": _pct(c_hit, c_total),
                                        "tops": cdata.get("tops", []),
                                        "uncovered": uncovered, "coverpoints": points}
        all_hit += c_hit
        all_total += c_total
    out.update(hit=all_hit, total=all_total, percent=_pct(all_hit, all_total))
    return out


def _pct(hit: int, total: int) -> float:
    return round(100.0 * hit / total, 2) if total else 100.0


# ---- code coverage (Verilator coverage.dat) -------------------------------------------------

def read_coverage_dat(path: str | Path) -> dict[tuple[str, ...], int]:
    """Points of a Verilator ``coverage.dat``: (type, module, file, line, column, comment)
    -> count, summed over instances."""
    out: dict[tuple[str, ...], int] = {}
    for line in Path(path).read_text(errors="replace").splitlines():
        if not line.startswith("C '"):
            continue
        body, _, count = line[3:].rpartition("' ")
        fields = {}
        for kv in body.split("\x01"):
            if "\x02" in kv:
                k, v = kv.split("\x02", 1)
                fields[k] = v
        page = fields.get("page", "")
        kind, _, module = page.partition("/")
        key = (kind, module, Path(fields.get("f", "")).name, fields.get("l", ""),
               fields.get("n", ""), fields.get("o", ""))
        out[key] = out.get(key, 0) + int(count or 0)
    return out


def merge_points(points: Iterable[Mapping[tuple[str, ...], int]]) -> dict[tuple[str, ...], int]:
    out: dict[tuple[str, ...], int] = {}
    for p in points:
        for k, v in p.items():
            out[k] = out.get(k, 0) + v
    return out


def code_coverage(points: Mapping[tuple[str, ...], int]) -> dict[str, Any]:
    """Per module: line coverage (Verilator's line and branch points) and toggle coverage,
    hit/total/percent, and the source lines never reached."""
    mods: dict[str, dict[str, Any]] = {}
    for (kind, module, file, line, _col, _comment), count in points.items():
        group = {"v_line": "line", "v_branch": "line", "v_toggle": "toggle"}.get(kind)
        if group is None or not module:
            continue
        m = mods.setdefault(module.split("__")[0],
                            {"line": [0, 0], "toggle": [0, 0], "missed_lines": set()})
        m[group][1] += 1
        if count > 0:
            m[group][0] += 1
        elif group == "line":
            m["missed_lines"].add(f"{file}:{line}")
    return {mod: {"line": {"hit": v["line"][0], "total": v["line"][1],
                           "percent": _pct(*v["line"])},
                  "toggle": {"hit": v["toggle"][0], "total": v["toggle"][1],
                             "percent": _pct(*v["toggle"])},
                  "missed_lines": sorted(v["missed_lines"])}
            for mod, v in sorted(mods.items())}


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
