"""Functional coverage of the stage tops: ``method_ffc_top`` (sampled by
``cocotb_tests/tb_ffc.py``) and ``method_drift_top`` (sampled by ``cocotb_tests/tb_stage.py``).

FFC
---

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
``ffc.target``             a refresh towards the mean of its mean frame's good pixels, or
                           one whose mean frame had none (no target: the corrections kept)
========================== =====================================================================

Unreachable bins are removed with the reason (``removed``), as in the base model.

Blind drift
-----------
The base model's stream points and the drift stage's own (:data:`DRIFT_POINTS`), every bin
decided by :func:`drift_classes` from the golden model's values (``nuc_fixed.drift
.blind_drift``, ``cores.drift_sub`` and the base core on x') of frames that were driven
and checked:

===================== ==========================================================================
``drift.items``       the frame's blind sum came as one item (a register) or several
``drift.gain``        the drift gain m negative, 0, positive
``drift.bd``          the blind sum below or above ``blind_ref`` (the reference's change)
``drift.delta``       delta = OVF_D(ROUND((sum - blind_ref) * m)) saturated low, negative, 0,
                      positive, saturated high (both ends of the drift format)
``drift.x``           x' = (x << Df) - delta below 0, in the raw range, above (2^A - 1) << Df
``drift.range``       the core's r on x' below 0, in range, above 2^B - 1 (OUT saturates)
``drift.update``      at a frame boundary delta changed, changed with a frame of 4 pixels or
                      fewer (shorter than the drift multiply), stayed
``drift.size``        at a frame boundary the frame size stayed or changed (back to back)
``reset.mid_frame``   a reset in the middle of a frame
===================== ==========================================================================
"""

from __future__ import annotations

import itertools
from collections.abc import Sequence

import numpy as np

from irnuc.cosim.coverage import RANGE_BINS, CoverageModel
from irnuc.cosim.stages import DriftFrame, FfcRun
from irnuc.nuc_fixed.config import PipelineConfig
from irnuc.nuc_fixed.cores import code_range, drift_sub
from irnuc.nuc_fixed.fixed import round_shift
from irnuc.nuc_fixed.method_top import MethodCoefficients, base_core, frame_coefficients

__all__ = ["DRIFT_POINTS", "DRIFT_TOPS", "FFC_POINTS", "FFC_TOPS", "DriftCoverageModel",
           "FfcCoverageModel", "drift_classes", "ffc_classes"]

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
    "ffc.target": ("mean", "no_good_pixel"),
}
#: A frame this short (pixels) is shorter than the pipeline.
TINY_PIXELS = 4


def ffc_classes(run: FfcRun, cfg: PipelineConfig) -> dict[str, set[str]]:
    """The bins of ``ffc.frame``, ``ffc.refresh_frame``, ``ffc.run``, ``ffc.first_frame``,
    ``ffc.correction``, ``ffc.tiny_frame`` and ``ffc.target`` one golden run hits."""
    out: dict[str, set[str]] = {k: set() for k in FFC_POINTS}
    shutter = [bool(s) for s in run.shutter]
    held = [bool(h) for h in run.held]
    refresh = [f is not None for f in run.foff_out]
    fr = out["ffc.frame"]
    for i, s in enumerate(shutter):
        if refresh[i]:
            fr.add("refresh")
            out["ffc.refresh_frame"].add("shutter" if s else "open")
            out["ffc.target"].add("no_good_pixel" if i - 1 in run.kept else "mean")
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


# ---- blind_drift (method_drift_top) ----------------------------------------------------------

#: The tops whose coverage model is :class:`DriftCoverageModel`.
DRIFT_TOPS = ("method_drift_top",)

#: Coverpoint -> bins of the drift stage.
DRIFT_POINTS: dict[str, tuple[str, ...]] = {
    "drift.items": ("one", "several"),
    "drift.gain": ("negative", "zero", "positive"),
    "drift.bd": ("negative", "positive"),
    "drift.delta": ("sat_low", "negative", "zero", "positive", "sat_high"),
    "drift.x": ("negative", "in_range", "above_max"),
    "drift.range": RANGE_BINS,
    "drift.update": ("changed", "changed_tiny", "same"),
    "drift.size": ("same", "changed"),
    "reset.mid_frame": ("reset",),
}


def _sign(v: int, labels: tuple[str, str, str]) -> str:
    return labels[(v > 0) - (v < 0) + 1]


def drift_classes(frames: Sequence[DriftFrame], golden: PipelineConfig | None = None
                  ) -> dict[str, set[str]]:
    """The bins of :data:`DRIFT_POINTS` (but the reset) one run of frames hits: each
    frame's values and each boundary between two frames of the run (streamed back to back,
    no reset between). ``golden``: the configuration checked against (default the
    frames')."""
    out: dict[str, set[str]] = {k: set() for k in DRIFT_POINTS if k != "reset.mid_frame"}
    for f in frames:
        cfg = golden or f.coeffs.cfg
        regs = f.coeffs.registers
        ref, m = int(regs["blind_ref"]), int(regs["drift_gain"])
        out["drift.items"].add("one" if np.size(f.blind) == 1 else "several")
        out["drift.gain"].add(_sign(m, ("negative", "zero", "positive")))
        bd = int(np.sum(f.blind_codes)) - ref
        if bd:
            out["drift.bd"].add("negative" if bd < 0 else "positive")
        df, mf = cfg.format("drift"), cfg.format("drift_gain")
        r = int(np.asarray(round_shift(np.array([bd * m], np.int64),
                                       mf.frac_bits - df.frac_bits, df.rounding))[0])
        lo, hi = code_range(cfg, "drift")
        out["drift.delta"].add("sat_low" if r < lo else "sat_high" if r > hi else
                               _sign(r, ("negative", "zero", "positive")))
        xd = np.asarray(drift_sub(f.raw, f.delta, cfg), np.int64)
        top = ((1 << cfg.adc_bits) - 1) << df.frac_bits
        for name, hit in (("negative", xd < 0), ("in_range", (xd >= 0) & (xd <= top)),
                          ("above_max", xd > top)):
            if hit.any():
                out["drift.x"].add(name)
        c = MethodCoefficients(cfg, f.coeffs.fields, f.coeffs.registers)
        res = base_core(c, frame_coefficients(c, None), xd, xfrac=df.frac_bits, signed_x=True)
        rr = np.asarray(res.r)
        for name, hit in zip(RANGE_BINS, (rr < 0, (rr >= 0) & (rr < 1 << cfg.out_bits),
                                          rr >= 1 << cfg.out_bits), strict=True):
            if hit.any():
                out["drift.range"].add(name)
    for a, b in itertools.pairwise(frames):
        out["drift.size"].add("same" if a.raw.shape == b.raw.shape else "changed")
        out["drift.update"].add("same" if a.delta == b.delta else
                                "changed_tiny" if b.raw.size <= TINY_PIXELS else "changed")
    return out


class DriftCoverageModel(CoverageModel):
    """The coverpoints of ``method_drift_top`` on one configuration (:data:`DRIFT_POINTS`
    and the base model's stream points)."""

    def __init__(self, top: str, cfg: PipelineConfig, prefix: str = "irnuc") -> None:
        super().__init__(top, cfg, prefix)
        for name, bins in DRIFT_POINTS.items():
            self.add_point(name, bins)

    def sample_frames_run(self, frames: Sequence[DriftFrame]) -> None:
        """The bins of one run of frames that was driven and checked."""
        for name, labels in drift_classes(frames, self.cfg).items():
            for b in sorted(labels):
                self.sample(name, b)
