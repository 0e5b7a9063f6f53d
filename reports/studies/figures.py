"""Figures of the sweep and the report (matplotlib, Agg backend, PNG bytes).

Every function returns PNG bytes so the report can embed them as base64 and the sweep can
write them to files; no window is ever opened.
"""

from __future__ import annotations

import io
from collections.abc import Mapping, Sequence
from typing import Any

import numpy as np


def _plt():
    import matplotlib

    matplotlib.use("Agg", force=True)
    import matplotlib.pyplot as plt

    return plt


def png(fig, dpi: int = 90) -> bytes:
    """Render a figure to PNG bytes and close it."""
    plt = _plt()
    buf = io.BytesIO()
    fig.savefig(buf, format="png", dpi=dpi, bbox_inches="tight")
    plt.close(fig)
    return buf.getvalue()


def error_vs_bits(points: Sequence[Mapping[str, Any]], metric: str = "err_max_lsb",
                  max_error: float | None = None) -> bytes:
    """Error against gain fraction bits, one line per offset fraction width (log scale)."""
    plt = _plt()
    fig, axes = plt.subplots(1, 2, figsize=(10, 3.8))
    groups: dict[tuple, list[Mapping[str, Any]]] = {}
    for p in points:
        key = (p["offset_frac_bits"], p["rounding"], p["coeff_rounding"], p["adc_bits"], p["out_bits"])
        groups.setdefault(key, []).append(p)
    for ax, m, label in ((axes[0], metric, metric.replace("_", " ")),
                         (axes[1], "residual_nu", "residual non-uniformity (std/mean)")):
        for key, pts in groups.items():
            pts = sorted(pts, key=lambda q: q["gain_frac_bits"])
            x = [q["gain_frac_bits"] for q in pts]
            y = [max(q[m], 1e-12) if q[m] is not None else np.nan for q in pts]
            name = f"Of={key[0]}"
            if len({k[1:] for k in groups}) > 1:
                name += f" {key[1]}/{key[2]} A{key[3]}->B{key[4]}"
            ax.semilogy(x, y, "o-", ms=3, label=name)
        if m == "residual_nu" and points and points[0].get("per_temp"):
            floor = max((r["float_nu"] for r in points[0]["per_temp"] if not r["calibration_point"]),
                        default=None)
            if floor:
                ax.axhline(floor, color="C2", ls=":", lw=1, label="float NUC")
        if m == metric and max_error is not None:
            ax.axhline(max_error, color="k", ls="--", lw=0.8, label=f"max error {max_error:g}")
        ax.set_xlabel("gain fraction bits")
        ax.set_ylabel(label)
        ax.grid(True, which="both", alpha=0.3)
    axes[0].legend(fontsize=7, ncol=2)
    fig.suptitle("Error of the fixed-point NUC against the float NUC (evaluation temperatures)")
    return png(fig)


def pareto(points: Sequence[Mapping[str, Any]], front: Sequence[Mapping[str, Any]],
           metric: str = "err_max_lsb", smallest: Mapping[str, Any] | None = None) -> bytes:
    """Error against coefficient memory (bits per pixel), the front and the chosen point."""
    plt = _plt()
    fig, ax = plt.subplots(figsize=(6.5, 4))
    bx = [p["bits_per_pixel"] for p in points]
    by = [max(p[metric], 1e-12) for p in points]
    ax.semilogy(bx, by, ".", color="0.6", label="sweep points")
    fx = [p["bits_per_pixel"] for p in front]
    fy = [max(p[metric], 1e-12) for p in front]
    ax.semilogy(fx, fy, "o-", color="C0", ms=4, label="Pareto front")
    if smallest:
        ax.axhline(smallest["max_error"], color="k", ls="--", lw=0.8,
                   label=f"max error {smallest['max_error']:g}")
        if smallest.get("found"):
            best = next(p for p in points if p["index"] == smallest["best"])
            ax.semilogy([best["bits_per_pixel"]], [max(best[metric], 1e-12)], "*", ms=14, color="C3",
                        label=f"smallest: {best['bits_per_pixel']} bit/pixel")
    ax.set_xlabel("coefficient memory, bits per pixel (gain + offset + bad flag)")
    ax.set_ylabel(metric.replace("_", " "))
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
    return png(fig)


def _stretch(img: np.ndarray, mask: np.ndarray | None = None) -> tuple[float, float]:
    v = img[mask] if mask is not None and mask.any() else img.ravel()
    lo, hi = np.percentile(v, [0.5, 99.5])
    if hi <= lo:
        hi = lo + 1.0
    return float(lo), float(hi)


def image_grid(images: Sequence[Sequence[np.ndarray]], row_labels: Sequence[str],
               col_labels: Sequence[str], notes: Sequence[Sequence[str]] | None = None,
               title: str = "", mask: np.ndarray | None = None, cell: float = 1.9,
               dpi: int = 80) -> bytes:
    """A grid of grey images, each stretched to its own 0.5-99.5 % range (as the paper shows
    frames: the pattern, not the level, is what matters)."""
    plt = _plt()
    nr, nc = len(images), len(images[0])
    h, w = images[0][0].shape
    fig, axes = plt.subplots(nr, nc, figsize=(cell * nc * max(w / h, 0.5), cell * nr + 0.6),
                             squeeze=False)
    for i in range(nr):
        for j in range(nc):
            ax = axes[i][j]
            img = np.asarray(images[i][j], dtype=np.float64)
            lo, hi = _stretch(img, mask)
            ax.imshow(img, cmap="gray", vmin=lo, vmax=hi, interpolation="nearest")
            ax.set_xticks([])
            ax.set_yticks([])
            if i == 0:
                ax.set_title(col_labels[j], fontsize=8)
            if j == 0:
                ax.set_ylabel(row_labels[i], fontsize=8)
            if notes is not None and notes[i][j]:
                ax.text(0.02, 0.03, notes[i][j], transform=ax.transAxes, fontsize=6,
                        color="yellow", backgroundcolor=(0, 0, 0, 0.5))
    if title:
        fig.suptitle(title, fontsize=10)
    fig.tight_layout()
    return png(fig, dpi=dpi)


def paper_comparison(bits: Sequence[int], irnuc: Sequence[float], reference: Sequence[float],
                     floor: float | None = None) -> bytes:
    """Residual non-uniformity against fraction bits: irnuc, the paper's reference, 2^-f/sqrt(12)."""
    plt = _plt()
    fig, ax = plt.subplots(figsize=(5.5, 3.6))
    b = np.asarray(bits, dtype=float)
    ax.semilogy(b, reference, "s--", label="paper reference implementation")
    ax.semilogy(b, irnuc, "o-", label="irnuc (paper preset)")
    ax.semilogy(b, 2.0**-b / np.sqrt(12.0), ":", color="k", label=r"$2^{-f}/\sqrt{12}$")
    if floor is not None and floor > 0:
        ax.axhline(floor, color="C2", lw=0.8, label="float NUC floor")
    ax.set_xlabel("coefficient fraction bits f (gain and offset)")
    ax.set_ylabel("residual non-uniformity at 350 K")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
    return png(fig)


def bad_pixel_maps(truth: np.ndarray, found: np.ndarray, raw: np.ndarray, corrected: np.ndarray) -> bytes:
    """Raw frame, NUC+DPC output, and the detection against the ground truth."""
    plt = _plt()
    fig, axes = plt.subplots(1, 3, figsize=(11, 3.2))
    for ax, img, t in ((axes[0], raw, "raw frame"), (axes[1], corrected, "golden NUC + DPC")):
        lo, hi = _stretch(np.asarray(img, dtype=float))
        ax.imshow(img, cmap="gray", vmin=lo, vmax=hi, interpolation="nearest")
        ax.set_title(t, fontsize=9)
    t, f = truth.astype(bool), found.astype(bool)
    rgb = np.ones((*t.shape, 3))
    rgb[t & f] = (0.1, 0.6, 0.1)
    rgb[t & ~f] = (0.9, 0.1, 0.1)
    rgb[~t & f] = (0.1, 0.2, 0.9)
    axes[2].imshow(rgb, interpolation="nearest")
    axes[2].set_title("detected (green), missed (red), false alarm (blue)", fontsize=9)
    for ax in axes:
        ax.set_xticks([])
        ax.set_yticks([])
    fig.tight_layout()
    return png(fig)


def phase_times(seconds: Mapping[str, float]) -> bytes:
    plt = _plt()
    fig, ax = plt.subplots(figsize=(6, 0.35 * len(seconds) + 0.8))
    names = list(seconds)
    ax.barh(names, [seconds[n] for n in names], color="C0")
    ax.invert_yaxis()
    ax.set_xlabel("seconds")
    ax.grid(True, axis="x", alpha=0.3)
    return png(fig)


def hardware_fronts(points: Sequence[Mapping[str, Any]], metric: str, max_error: float,
                    recommended: int | None, front_memory: Sequence[int],
                    front_datapath: Sequence[int]) -> bytes:
    """Error against coefficient memory (left) and against the datapath cost (right).

    Every point is a grey dot; synthesized points are black squares (the others' datapath
    cost is the cost model's); the Pareto fronts are lines; the recommendation is a star.
    """
    plt = _plt()
    fig, axes = plt.subplots(1, 2, figsize=(11, 4.2), sharey=True)
    by_index = {p["index"]: p for p in points}
    err = {p["index"]: max(p[metric], 1e-12) if p[metric] is not None else np.nan for p in points}
    for ax, key, label, front in (
            (axes[0], "bits_per_pixel", "coefficient memory, bits per pixel", front_memory),
            (axes[1], "datapath_cost", "datapath: xc7 LUT + DSP48E1 x LUT equivalent", front_datapath)):
        pts = [p for p in points if p.get(key) is not None]
        ax.semilogy([p[key] for p in pts], [err[p["index"]] for p in pts], ".", color="0.6",
                    label="sweep points")
        syn = [p for p in pts if (p.get("hw") or {}).get("source") == "synthesized"]
        if syn:
            ax.semilogy([p[key] for p in syn], [err[p["index"]] for p in syn], "s", mfc="none",
                        color="k", ms=7, label="synthesized")
        fr = [by_index[i] for i in front if by_index[i].get(key) is not None]
        fr.sort(key=lambda p: p[key])
        ax.semilogy([p[key] for p in fr], [err[p["index"]] for p in fr], "o-", color="C0", ms=4,
                    label="Pareto front")
        ax.axhline(max_error, color="k", ls="--", lw=0.8, label=f"tolerance {max_error:g}")
        if recommended is not None and by_index[recommended].get(key) is not None:
            r = by_index[recommended]
            ax.semilogy([r[key]], [err[recommended]], "*", ms=15, color="C3",
                        label=f"recommended {r['label']}")
        ax.set_xlabel(label)
        ax.grid(True, which="both", alpha=0.3)
    axes[0].set_ylabel(metric.replace("_", " "))
    axes[0].legend(fontsize=7)
    fig.suptitle("Pareto fronts: error against coefficient memory and against datapath cost")
    return png(fig)


def cost_model_check(names: Sequence[str], synthesized: Sequence[float],
                     predicted: Sequence[float], used_for_fit: Sequence[bool], what: str) -> bytes:
    """Predicted against synthesized values of one figure (the cost model's error)."""
    plt = _plt()
    fig, ax = plt.subplots(figsize=(4.8, 4))
    s = np.asarray(synthesized, float)
    p = np.asarray(predicted, float)
    fit = np.asarray(used_for_fit, bool)
    if fit.any():
        ax.plot(s[fit], p[fit], "o", color="C0", label="fit points")
    if (~fit).any():
        ax.plot(s[~fit], p[~fit], "D", color="C3", label="held out")
    if len(s):
        lo, hi = float(min(s.min(), p.min())), float(max(s.max(), p.max()))
        pad = 0.05 * (hi - lo or 1.0)
        ax.plot([lo - pad, hi + pad], [lo - pad, hi + pad], "k:", lw=0.8)
    for name, a, b in zip(names, s, p, strict=True):
        ax.annotate(name, (a, b), fontsize=6, xytext=(3, 3), textcoords="offset points")
    ax.set_xlabel(f"synthesized {what}")
    ax.set_ylabel(f"cost model {what}")
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=7)
    return png(fig)
