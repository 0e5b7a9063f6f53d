"""One call that co-simulates a configuration on a drifting sequence of the physics model.

:func:`cosim_sequence` is what the sign-off report calls for a configuration: it makes a
sequence of frames of the physics model with the FPA temperature ramping (and, for a
method with the ``ffc`` stage, the shutter closed for ``ffc_frames`` frames at every FFC
event), calibrates the method on the model, corrects the sequence in the RTL through the
C++ bulk harness and in the golden model, and compares every output bit for bit.

Base methods go through :func:`irnuc.cosim.method_drift.run_campaign` (``method_dpc_top``).
"""

from __future__ import annotations

import math
import time
from typing import Any

from irnuc.common.errors import UserError
from irnuc.nuc_fixed.config import PipelineConfig

__all__ = ["cosim_sequence"]


def _check_args(cfg: PipelineConfig, frames: int, shape: Any, seed: int,
                ffc_every: int | None, fpa_K: Any) -> tuple[int, int]:
    """One-line errors naming the argument, before any work."""
    if not isinstance(cfg, PipelineConfig):
        raise UserError(f"cfg = {cfg!r} is not a PipelineConfig (irnuc.nuc_fixed.load_pipeline)")
    if isinstance(frames, bool) or not isinstance(frames, int) or not 1 <= frames <= 100_000:
        raise UserError(f"frames = {frames!r} is outside the allowed range 1..100000 (int)")
    try:
        h, w = (int(v) for v in shape)
    except (TypeError, ValueError):
        raise UserError(f"shape = {shape!r} is not a pair of ints (rows, columns)") from None
    if not (1 <= h <= cfg.max_height and 1 <= w <= cfg.max_width):
        raise UserError(f"shape = {(h, w)} is outside 1..{cfg.max_height} x 1..{cfg.max_width} "
                        f"(max_height x max_width of {cfg.name!r})")
    if isinstance(seed, bool) or not isinstance(seed, int) or not 0 <= seed < 1 << 32:
        raise UserError(f"seed = {seed!r} is outside the allowed range 0..2^32-1 (int)")
    if ffc_every is not None and (isinstance(ffc_every, bool) or not isinstance(ffc_every, int)
                                  or ffc_every < 1):
        raise UserError(f"ffc_every = {ffc_every!r} must be None or an int >= 1 (frames)")
    try:
        lo, hi = (float(v) for v in fpa_K)
    except (TypeError, ValueError):
        raise UserError(f"fpa_K = {fpa_K!r} is not a pair of temperatures (K)") from None
    if not all(math.isfinite(v) and 200.0 <= v <= 400.0 for v in (lo, hi)):
        raise UserError(f"fpa_K = {fpa_K!r} is outside 200..400 K")
    return h, w


def cosim_sequence(cfg: PipelineConfig, frames: int = 20, shape: tuple[int, int] = (480, 640),
                   *, seed: int = 1, ffc_every: int | None = None,
                   fpa_K: tuple[float, float] = (289.0, 307.0)) -> dict[str, Any]:
    """Co-simulate ``cfg`` on ``frames`` frames of a drifting camera, bit for bit.

    Parameters
    ----------
    cfg : PipelineConfig
        Any named configuration with a base method (``method_dpc_top``).
    frames : int
        Frames of the sequence (1..100000).
    shape : (int, int)
        Frame rows and columns (pixels).
    seed : int
        Seed of the model (the same pixels drift in every frame) and of the harness.
    ffc_every : int, optional
        Frames from one shutter closing to the next (methods with ``ffc`` only; ignored by
        the others).
    fpa_K : (float, float)
        FPA (and housing) temperature of the first and the last frame, K; the scene ramps
        from 295 K to 360 K.

    Returns
    -------
    dict
        ``pipeline`` (the configuration's name), ``method``, ``top`` (the RTL top),
        ``frames``, ``shape``, ``pixels_compared`` (output pixels compared bit for bit),
        ``mismatches`` (pixels that differ, are missing or extra), ``ffc_events`` (offset
        refreshes in the sequence), ``seconds`` (wall time of the whole call, s),
        ``harness_seconds`` and ``golden_seconds`` (the harness's and the golden model's
        time on the sequence, s), ``passed`` (every pixel compared and equal, no framing
        error) and ``lines`` (the first mismatches described).
    """
    h, w = _check_args(cfg, frames, shape, seed, ffc_every, fpa_K)
    if cfg.stages:
        raise UserError(f"pipeline {cfg.name!r} ({cfg.method}): the stage tops are not yet "
                        "in the bulk sequence co-simulation")
    t0 = time.perf_counter()
    from irnuc.cosim.method_drift import calibrate_methods, drift_sequence, run_campaign

    seq = drift_sequence(frames, (h, w), fpa_K=(float(fpa_K[0]), float(fpa_K[1])), seed=seed)
    cals = calibrate_methods([cfg], (h, w), seed=seed)
    run = run_campaign([cfg], shape=(h, w), sequence=seq, coeffs=cals, seed=seed)[0]
    return {"pipeline": cfg.name, "method": cfg.method, "top": "method_dpc_top",
            "frames": frames, "shape": [h, w], "pixels_compared": run.compared,
            "mismatches": run.mismatches + run.missing + run.extra, "ffc_events": 0,
            "seconds": round(time.perf_counter() - t0, 3),
            "harness_seconds": round(run.sim_seconds, 3),
            "golden_seconds": round(run.golden_seconds, 3), "passed": run.passed,
            "lines": run.lines[:10]}
