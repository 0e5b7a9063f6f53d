"""One call that co-simulates a configuration on a drifting sequence of the physics model.

:func:`cosim_sequence` is what the sign-off report calls for a configuration: it makes a
sequence of frames of the physics model with the FPA temperature ramping (and, for a
method with the ``ffc`` stage, the shutter closed for ``ffc_frames`` frames at every FFC
event), calibrates the method on the model, corrects the sequence in the RTL through the
C++ bulk harness and in the golden model, and compares every output bit for bit.

Base methods go through :func:`irnuc.cosim.method_drift.run_campaign` (``method_dpc_top``).
The stage tops take the same sequence through the bulk harness's stage streams
(:mod:`irnuc.cosim.method_bulk`): ``method_drift_top`` with each frame's reference pixels
as its blind codes, against :func:`irnuc.cosim.stages.drift_frames`; ``method_ffc_top``
from reset with the shutter closings, the harness writing the FFC accumulator and
corrections back as the external memory, against :func:`irnuc.cosim.stages.ffc_run`
(pixels, accumulator words and corrections).
"""

from __future__ import annotations

import math
import time
from typing import Any

import numpy as np

from irnuc.common.errors import UserError
from irnuc.nuc_fixed.config import PipelineConfig

__all__ = ["cosim_sequence", "shutter_flags"]


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


def shutter_flags(cfg: PipelineConfig, frames: int, ffc_every: int | None) -> np.ndarray:
    """(frames,) bool: the shutter closed for ``ffc_frames`` frames at frames 1,
    1 + ``ffc_every``, 1 + 2 ``ffc_every``, ... (after one open frame, so that a held
    shutter frame has an open frame to show); ``ffc_every`` None: max(N + 2, frames // 2),
    two FFC events in 20 frames of N = 8."""
    n = int(cfg.ffc_frames or 1)
    every = ffc_every or max(n + 2, frames // 2)
    closed = np.zeros(frames, bool)
    for start in range(1, frames, every):
        closed[start:start + n] = True
    return closed


def _stage_run(cfg: PipelineConfig, frames: int, shape: tuple[int, int], seed: int,
               ffc_every: int | None, fpa_K: tuple[float, float]) -> dict[str, Any]:
    from irnuc.cosim.bulk import build_bulk
    from irnuc.cosim.method_bulk import (
        check_drift_bulk,
        check_ffc_bulk,
        run_drift_bulk,
        run_ffc_bulk,
    )
    from irnuc.cosim.method_drift import calibrate_methods, drift_sequence
    from irnuc.cosim.stages import drift_frames, ffc_run
    from irnuc.cosim.synth import default_top

    ffc = cfg.has("ffc")
    flags = shutter_flags(cfg, frames, ffc_every) if ffc else None
    seq = drift_sequence(frames, shape, fpa_K=fpa_K, seed=seed, shutter=flags)
    cal = calibrate_methods([cfg], shape, seed=seed)[cfg.name]
    bld = build_bulk(cfg, top=default_top(cfg))
    out: dict[str, Any] = {"top": bld.top}
    if ffc:
        rd = [int(v) for v in seq.reading] if "fpa" in cfg.base.readings else None
        t0 = time.perf_counter()
        run = ffc_run(cal, list(seq.codes), [bool(v) for v in flags], readings=rd)  # type: ignore[union-attr]
        t_golden = time.perf_counter() - t0
        res = run_ffc_bulk(bld, run, seed=seed + 1)
        chk = check_ffc_bulk(res, run)
        pix = chk["m_pix"]
        out.update(pixels_compared=pix.compared,
                   words_compared=chk["m_acc"].compared + chk["m_foff"].compared,
                   mismatches=sum(c.mismatches + c.missing + c.extra for c in chk.values()),
                   ffc_events=sum(f is not None for f in run.foff_out),
                   shutter_frames=int(flags.sum()),  # type: ignore[union-attr]
                   held_frames=int(run.held.sum()),
                   passed=all(c.passed for c in chk.values()) and pix.compared > 0,
                   lines=[ln for c in chk.values() for ln in c.lines][:10])
    else:
        if seq.blind_codes is None:
            raise UserError(f"pipeline {cfg.name!r} needs reference pixels; the sensor has none")
        t0 = time.perf_counter()
        frs = drift_frames(cal, list(seq.codes), list(seq.blind_codes))
        t_golden = time.perf_counter() - t0
        res = run_drift_bulk(bld, frs, seed=seed + 1, shards=2)
        chk1 = check_drift_bulk(res, frs)
        out.update(pixels_compared=chk1.compared, words_compared=0,
                   mismatches=chk1.mismatches + chk1.missing + chk1.extra, ffc_events=0,
                   passed=chk1.passed and chk1.compared == seq.codes.size,
                   lines=list(chk1.lines[:10]),
                   blind_codes_per_frame=int(seq.blind_codes.shape[1]))
    out.update(harness_seconds=round(res.sim_seconds, 3), golden_seconds=round(t_golden, 3),
               cycles=res.cycles)
    return out


def cosim_sequence(cfg: PipelineConfig, frames: int = 20, shape: tuple[int, int] = (480, 640),
                   *, seed: int = 1, ffc_every: int | None = None,
                   fpa_K: tuple[float, float] = (289.0, 307.0)) -> dict[str, Any]:
    """Co-simulate ``cfg`` on ``frames`` frames of a drifting camera, bit for bit.

    Parameters
    ----------
    cfg : PipelineConfig
        A named configuration: a base method (``method_dpc_top``), or one with the
        ``blind_drift`` stage (``method_drift_top``) or the ``ffc`` stage
        (``method_ffc_top``).
    frames : int
        Frames of the sequence (1..100000).
    shape : (int, int)
        Frame rows and columns (pixels).
    seed : int
        Seed of the model (the same pixels drift in every frame) and of the harness.
    ffc_every : int, optional
        Frames from one shutter closing to the next, each closing ``ffc_frames`` frames
        long, the first at frame 1 (methods with ``ffc`` only; ignored by the others);
        None: ``max(ffc_frames + 2, frames // 2)`` (:func:`shutter_flags`).
    fpa_K : (float, float)
        FPA (and housing) temperature of the first and the last frame, K; the scene ramps
        from 295 K to 360 K.

    Returns
    -------
    dict
        ``pipeline`` (the configuration's name), ``method``, ``top`` (the RTL top),
        ``frames``, ``shape``, ``pixels_compared`` (output pixels compared bit for bit;
        ffc with ``hold``: the held shutter frames have none), ``words_compared`` (ffc:
        the m_acc and m_foff words), ``mismatches`` (outputs of every stream that differ,
        are missing or extra), ``ffc_events`` (offset refreshes in the sequence),
        ``seconds`` (wall time of the whole call, model and calibration included, s),
        ``harness_seconds`` and ``golden_seconds`` (the harness's and the golden
        reference's time on the sequence, s), ``cycles`` (clock cycles simulated),
        ``passed`` (every output compared and equal, no framing error) and ``lines`` (the
        first mismatches described); ffc adds ``shutter_frames`` and ``held_frames``,
        blind_drift ``blind_codes_per_frame``.
    """
    h, w = _check_args(cfg, frames, shape, seed, ffc_every, fpa_K)
    t0 = time.perf_counter()
    head = {"pipeline": cfg.name, "method": cfg.method, "frames": frames, "shape": [h, w]}
    if cfg.stages:
        if not all(s in ("blind_drift", "ffc") for s in cfg.stages):
            raise UserError(f"pipeline {cfg.name!r} ({cfg.method}): the bulk harness drives "
                            "the blind_drift and ffc stage tops only")
        run = _stage_run(cfg, frames, (h, w), seed, ffc_every,
                         (float(fpa_K[0]), float(fpa_K[1])))
        return {**head, **run, "seconds": round(time.perf_counter() - t0, 3)}
    from irnuc.cosim.method_drift import calibrate_methods, drift_sequence, run_campaign

    seq = drift_sequence(frames, (h, w), fpa_K=(float(fpa_K[0]), float(fpa_K[1])), seed=seed)
    cals = calibrate_methods([cfg], (h, w), seed=seed)
    run = run_campaign([cfg], shape=(h, w), sequence=seq, coeffs=cals, seed=seed)[0]
    return {**head, "top": "method_dpc_top", "pixels_compared": run.compared,
            "words_compared": 0, "mismatches": run.mismatches + run.missing + run.extra,
            "ffc_events": 0,
            "seconds": round(time.perf_counter() - t0, 3),
            "harness_seconds": round(run.sim_seconds, 3),
            "golden_seconds": round(run.golden_seconds, 3), "cycles": run.cycles,
            "passed": run.passed, "lines": run.lines[:10]}
