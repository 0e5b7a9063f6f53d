"""Functional coverage of the FFC stage top ``method_ffc_top`` (sampled by
``cocotb_tests/tb_ffc.py``).

The base model's stream points (idle and backpressure patterns, back-to-back frames) and
the FFC sequence's own, every bin decided from the golden run (:class:`~irnuc.cosim.stages
.FfcRun`) of a sequence that was driven and checked:

========================== =====================================================================
``ffc.frame``              what a frame did: open, first or further accumulation, the mean pass,
                           the refresh, held, a shutter frame passed to the output
``ffc.refresh_frame``      the refresh frame's own shutter: open, or closed (a new run starts)
``ffc.run``                a shutter run shorter than N (no refresh), of N, longer than N
``ffc.first_frame``        the first frame after reset is a shutter frame (nothing to hold)
``ffc.refresh_stream``     a sequence with a refresh at full rate, or with idle inputs and
                           backpressure on every output (a shutter event under backpressure)
``ffc.shutter_mid_frame``  the shutter flag changed inside a frame (the frame keeps the flag
                           of its first pixel)
``ffc.correction``         a refreshed correction at the ffc format's lowest code, highest
                           code, or between (the refresh's OVF)
``ffc.tiny_frame``         a refresh in a sequence of frames of 4 pixels or fewer (shorter
                           than the pipeline and the target's division)
========================== =====================================================================

Unreachable bins are removed with the reason (``removed``), as in the base model.
"""

from __future__ import annotations

import numpy as np

from irnuc.cosim.coverage import CoverageModel
from irnuc.cosim.stages import FfcRun
from irnuc.nuc_fixed.config import PipelineConfig

__all__ = ["FFC_POINTS", "FFC_TOPS", "FfcCoverageModel", "ffc_classes"]

#: The tops whose coverage model is :class:`FfcCoverageModel`.
FFC_TOPS = ("method_ffc_top",)

FRAME_BINS = ("open", "accumulate_first", "accumulate_add", "mean", "refresh", "held",
              "shutter_passed")
#: Coverpoint -> bins of the FFC sequence.
FFC_POINTS: dict[str, tuple[str, ...]] = {
    "ffc.frame": FRAME_BINS,
    "ffc.refresh_frame": ("open", "shutter"),
    "ffc.run": ("short", "full", "long"),
    "ffc.first_frame": ("shutter",),
    "ffc.refresh_stream": ("full_rate", "idle_backpressure"),
    "ffc.shutter_mid_frame": ("ignored",),
    "ffc.correction": ("min", "max", "between"),
    "ffc.tiny_frame": ("refresh",),
}
#: A frame this short (pixels) is shorter than the pipeline.
TINY_PIXELS = 4


def ffc_classes(run: FfcRun, cfg: PipelineConfig) -> dict[str, set[str]]:
    """The bins of ``ffc.frame``, ``ffc.refresh_frame``, ``ffc.run``, ``ffc.first_frame``,
    ``ffc.correction`` and ``ffc.tiny_frame`` one golden run hits."""
    out: dict[str, set[str]] = {k: set() for k in FFC_POINTS}
    shutter = [bool(s) for s in run.shutter]
    held = [bool(h) for h in run.held]
    refresh = [f is not None for f in run.foff_out]
    fr = out["ffc.frame"]
    for i, s in enumerate(shutter):
        if refresh[i]:
            fr.add("refresh")
            out["ffc.refresh_frame"].add("shutter" if s else "open")
        if i + 1 < len(refresh) and refresh[i + 1]:
            fr.add("mean")
        if held[i]:
            fr.add("held")
        elif s:
            fr.add("shutter_passed")
        if s and run.acc_out[i] is not None:
            fr.add("accumulate_add" if run.acc_in[i] is not None and not refresh[i]
                   else "accumulate_first")
        if not s and not refresh[i]:
            fr.add("open")
    n = int(cfg.ffc_frames or 1)
    length = 0
    for s in [*shutter, False]:
        if s:
            length += 1
        elif length:
            out["ffc.run"].add("short" if length < n else "full" if length == n else "long")
            length = 0
    if shutter and shutter[0]:
        out["ffc.first_frame"].add("shutter")
    c = cfg.format("ffc")
    lo, hi = -(1 << (c.bits - 1)), (1 << (c.bits - 1)) - 1
    for f in run.foff_out:
        if f is not None:
            v = np.asarray(f, dtype=np.int64)
            for name, hit in (("min", v == lo), ("max", v == hi), ("between", (v > lo) & (v < hi))):
                if hit.any():
                    out["ffc.correction"].add(name)
    if any(refresh) and max(f.raw.size for f in run.frames) <= TINY_PIXELS:
        out["ffc.tiny_frame"].add("refresh")
    return out


class FfcCoverageModel(CoverageModel):
    """The coverpoints of ``method_ffc_top`` on one configuration (:data:`FFC_POINTS` and
    the base model's stream points)."""

    def __init__(self, top: str, cfg: PipelineConfig, prefix: str = "irnuc") -> None:
        super().__init__(top, cfg, prefix)
        bins = dict(FFC_POINTS)
        if cfg.ffc_output != "hold":
            bins["ffc.frame"] = tuple(b for b in FRAME_BINS if b != "held")
            self.removed["ffc.frame"] = {"held": f"ffc_output = {cfg.ffc_output!r}: shutter "
                                                 "frames are passed, never held"}
        for name, b in bins.items():
            self.add_point(name, b)

    def sample_run(self, run: FfcRun, stream: str) -> None:
        """The bins of one golden run that was driven and checked; ``stream``: how
        (``full_rate`` or ``idle_backpressure``)."""
        for name, labels in ffc_classes(run, self.cfg).items():
            for b in sorted(labels):
                self.sample(name, b)
        if any(f is not None for f in run.foff_out):
            self.sample("ffc.refresh_stream", stream)
        if len(run.frames) > 1 and stream == "full_rate":
            self.sample("stream.back_to_back", "frames")
