"""Hardware cost of sweep points: coefficient memory and the datapath from ``irnuc synth``.

* :func:`coefficient_memory`: the coefficient store of one frame: bits per pixel, block RAMs
  (xc7 RAMB36E1, ECP5 DP16KD, at the best aspect ratio), whether that fits the block RAM of
  a reference device, else the external memory it needs (bytes per frame, bandwidth).
* :func:`fit_indices`: the few sweep points worth synthesizing (the corners of the swept
  gain and offset word widths).
* :class:`CostModel`: a linear model of each synthesized figure (LUT, FF, DSP, BRAM, Fmax;
  xc7 and ECP5) in the gain and offset word widths, least squares on the synthesized
  points; its error is stated by leave-one-out over the fit points and against every
  synthesized point that was not used to fit it.
* :func:`recommend`: the cheapest point meeting the error tolerance (memory first, then
  the datapath), :func:`recommend_synthesized`: the same with the chosen point always
  synthesized, and :func:`grid_edges`: on which edge of the swept grid it lies.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Container, Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np

#: Block RAM shapes (depth, width) of one xc7 RAMB36E1 and one ECP5 DP16KD.
XC7_BRAM36_SHAPES = ((32768, 1), (16384, 2), (8192, 4), (4096, 9), (2048, 18), (1024, 36), (512, 72))
ECP5_DP16KD_SHAPES = ((16384, 1), (8192, 2), (4096, 4), (2048, 9), (1024, 18), (512, 36))
#: Reference devices for "fits on chip": XC7A100T (135 RAMB36E1), LFE5U-85F (208 DP16KD).
XC7_DEVICE, XC7_BRAM36_AVAILABLE = "XC7A100T", 135
ECP5_DEVICE, ECP5_DP16KD_AVAILABLE = "LFE5U-85F", 208

#: The synthesized figures the cost model predicts (dotted: family.resource).
COST_KEYS = ("xc7.lut", "xc7.ff", "xc7.dsp", "xc7.bram36", "xc7.bram18", "ecp5.lut4", "ecp5.ff",
             "ecp5.mult18", "ecp5.dp16kd", "fmax_mhz")


def bram_blocks(width: int, depth: int, shapes: Sequence[tuple[int, int]]) -> int:
    """Fewest blocks holding ``depth`` words of ``width`` bits (one aspect ratio for all)."""
    return min(math.ceil(width / w) * math.ceil(depth / d) for d, w in shapes)


#: Frame rate of the memory bandwidth figures unless the caller gives one.
FRAME_RATE_HZ = 60.0


def coefficient_memory(bits_per_pixel: int, rows: int, cols: int,
                       frame_rate_hz: float = FRAME_RATE_HZ) -> dict[str, Any]:
    """The coefficient store of one ``rows`` x ``cols`` frame at ``bits_per_pixel``."""
    n = int(rows) * int(cols)
    xc7 = bram_blocks(bits_per_pixel, n, XC7_BRAM36_SHAPES)
    ecp5 = bram_blocks(bits_per_pixel, n, ECP5_DP16KD_SHAPES)
    bus_bytes = 2 ** max(0, math.ceil(math.log2(math.ceil(bits_per_pixel / 8))))  # 1, 2, 4, 8 B
    return {
        "bits_per_pixel": int(bits_per_pixel), "pixels": n,
        "bits_per_frame": int(bits_per_pixel) * n,
        "xc7_bram36": xc7, "xc7_fits": xc7 <= XC7_BRAM36_AVAILABLE,
        "xc7_device": XC7_DEVICE, "xc7_bram36_available": XC7_BRAM36_AVAILABLE,
        "ecp5_dp16kd": ecp5, "ecp5_fits": ecp5 <= ECP5_DP16KD_AVAILABLE,
        "ecp5_device": ECP5_DEVICE, "ecp5_dp16kd_available": ECP5_DP16KD_AVAILABLE,
        "external_bytes_per_pixel": bus_bytes,
        "external_bytes_per_frame": bus_bytes * n,
        "external_mbyte_per_s": round(bus_bytes * n * frame_rate_hz / 1e6, 3),
        "frame_rate_hz": float(frame_rate_hz),
    }


def widths(p: Mapping[str, Any]) -> tuple[int, int]:
    """(gain word bits, offset word bits) of a sweep point (its configuration's)."""
    return int(p["gain_bits"]), int(p["offset_bits"])


def fit_indices(points: Sequence[Mapping[str, Any]], n: int = 4) -> list[int]:
    """Indices of up to ``n`` points spread over the swept (gain bits, offset bits): the four
    corners first (nearest point to each), then the points farthest from those chosen."""
    xy = np.array([widths(p) for p in points], dtype=float)
    if len(xy) == 0:
        return []
    lo, hi = xy.min(axis=0), xy.max(axis=0)
    span = np.where(hi > lo, hi - lo, 1.0)
    z = (xy - lo) / span
    chosen: list[int] = []
    for corner in ((0, 0), (1, 1), (0, 1), (1, 0)):
        d = np.abs(z - np.array(corner)).sum(axis=1)
        i = int(np.argmin(d))
        if i not in chosen:
            chosen.append(i)
        if len(chosen) == n:
            return sorted(chosen)
    while len(chosen) < min(n, len(points)):
        d = np.min([np.abs(z - z[c]).sum(axis=1) for c in chosen], axis=0)
        d[chosen] = -1
        if d.max() <= 0:
            break
        chosen.append(int(np.argmax(d)))
    return sorted(chosen)


def synth_figures(s: Mapping[str, Any]) -> dict[str, float]:
    """The :data:`COST_KEYS` of one ``synth_config`` result, flat."""
    out = {}
    for key in COST_KEYS:
        fam, _, res = key.partition(".")
        out[key] = float(s[fam][res] if res else s[fam])
    return out


def datapath_cost(fig: Mapping[str, float], dsp_lut_equivalent: float) -> float:
    """The datapath axis of the second front: xc7 LUTs + DSP48E1 x ``dsp_lut_equivalent``."""
    return float(fig["xc7.lut"]) + dsp_lut_equivalent * float(fig["xc7.dsp"])


@dataclass
class CostModel:
    """Per figure, ``value = a + b * gain_bits + c * offset_bits`` (least squares).

    With fewer distinct widths than coefficients the minimum-norm solution is used (a
    width that did not vary among the fit points then has no effect).
    """

    coef: dict[str, list[float]]
    fit_widths: list[tuple[int, int]]
    loo: dict[str, dict[str, float]] = field(default_factory=dict)

    @staticmethod
    def _design(ws: Sequence[tuple[int, int]]) -> np.ndarray:
        a = np.asarray(ws, dtype=float).reshape(-1, 2)
        return np.column_stack([np.ones(len(a)), a])

    @classmethod
    def fit(cls, ws: Sequence[tuple[int, int]], figs: Sequence[Mapping[str, float]]) -> CostModel:
        x = cls._design(ws)
        coef = {}
        for key in COST_KEYS:
            y = np.array([f[key] for f in figs], dtype=float)
            coef[key] = np.linalg.lstsq(x, y, rcond=None)[0].tolist()
        model = cls(coef=coef, fit_widths=[tuple(map(int, w)) for w in ws])
        model.loo = _leave_one_out(ws, figs)
        return model

    def predict(self, w: tuple[int, int]) -> dict[str, float]:
        x = self._design([w])[0]
        out = {}
        for key, c in self.coef.items():
            v = float(x @ np.asarray(c))
            out[key] = v if key == "fmax_mhz" else max(0.0, v)
        return out

    def errors(self, ws: Sequence[tuple[int, int]], figs: Sequence[Mapping[str, float]]
               ) -> dict[str, dict[str, float]]:
        """Largest absolute and relative error of the predictions at synthesized points."""
        return _errors([self.predict(w) for w in ws], figs)

    def to_dict(self) -> dict[str, Any]:
        return {"form": "value = a + b * gain_bits + c * offset_bits (least squares)",
                "coefficients": self.coef, "fit_widths": [list(w) for w in self.fit_widths],
                "leave_one_out": self.loo}


def _errors(pred: Sequence[Mapping[str, float]], figs: Sequence[Mapping[str, float]]
            ) -> dict[str, dict[str, float]]:
    out = {}
    for key in COST_KEYS:
        ab = [abs(p[key] - f[key]) for p, f in zip(pred, figs, strict=True)]
        rel = [a / abs(f[key]) if f[key] else (0.0 if a == 0 else math.inf)
               for a, f in zip(ab, figs, strict=True)]
        out[key] = {"max_abs": max(ab, default=0.0),
                    "max_rel": max(rel, default=0.0) if all(map(math.isfinite, rel)) else None,
                    "points": len(ab)}
    return out


def _leave_one_out(ws: Sequence[tuple[int, int]], figs: Sequence[Mapping[str, float]]
                   ) -> dict[str, dict[str, float]]:
    if len(ws) < 4:  # three coefficients: fewer than four points leave nothing to check
        return {}
    pred = []
    for i in range(len(ws)):
        rest = [j for j in range(len(ws)) if j != i]
        x = CostModel._design([ws[j] for j in rest])
        xi = CostModel._design([ws[i]])[0]
        p = {}
        for key in COST_KEYS:
            y = np.array([figs[j][key] for j in rest], dtype=float)
            p[key] = float(xi @ np.linalg.lstsq(x, y, rcond=None)[0])
        pred.append(p)
    return _errors(pred, figs)


def recommend(points: Sequence[Mapping[str, Any]], max_error: float, metric: str,
              datapath: Mapping[int, float] | None = None) -> dict[str, Any]:
    """The cheapest point whose ``metric`` is at most ``max_error``.

    Cheapest: fewest coefficient bits per pixel (the coefficient store of a frame dwarfs
    the datapath), then the lowest datapath cost (``datapath``: index -> cost, synthesized
    or predicted), then the lowest error. Returns ``{found, index, candidates}``
    (candidates: every point meeting the tolerance at that memory).
    """
    from irnuc.reports.studies.sweep import smallest_meeting

    least = smallest_meeting(points, max_error, metric)  # in order of error, then index
    if not least["found"]:
        return {"found": False, "index": None, "candidates": []}
    err = {p["index"]: p[metric] for p in points}
    dp = datapath or {}
    best = min(least["points"], key=lambda i: (dp.get(i, 0.0), err[i], i))
    return {"found": True, "index": best, "candidates": list(least["points"])}


def recommend_synthesized(points: Sequence[Mapping[str, Any]], max_error: float, metric: str,
                          costs: Callable[[], Mapping[int, float]],
                          synthesized: Container[int],
                          synthesize: Callable[[int], None]) -> dict[str, Any]:
    """:func:`recommend` on datapath costs that are synthesized where it matters.

    ``costs()`` gives every point's datapath cost (synthesized, else the cost model's);
    when the chosen point is not in ``synthesized``, ``synthesize(index)`` adds it and the
    choice is made again on the new costs (a predicted cost can be too low). Ends with a
    synthesized recommendation: each round synthesizes one more of the finitely many
    candidates.
    """
    while True:
        rec = recommend(points, max_error, metric, costs())
        if not rec["found"] or rec["index"] in synthesized:
            return rec
        synthesize(rec["index"])


def grid_edges(point: Mapping[str, Any], axes: Mapping[str, Sequence[Any]]) -> list[dict[str, str]]:
    """The swept axes on whose edge ``point`` lies, and which way to widen each.

    ``axes``: name -> the swept values (only numeric ones count; an axis of one value is
    an edge on both sides). A point at the largest value of an axis may be cheaper with a
    larger value there and a smaller one elsewhere; at the smallest, a smaller value may
    still meet the tolerance.
    """
    out = []
    for name, values in axes.items():
        nums = sorted({v for v in values if isinstance(v, int) and not isinstance(v, bool)})
        if not nums or name not in point:
            continue
        v = point[name]
        if v == nums[-1]:
            out.append({"axis": name, "edge": "top", "widen": f"add {name} above {v}"})
        if v == nums[0]:
            out.append({"axis": name, "edge": "bottom", "widen": f"add {name} below {v}"
                        if v > 0 else f"{name} is already 0 (nothing below)"})
    return [e for e in out if not e["widen"].endswith("(nothing below)")]
