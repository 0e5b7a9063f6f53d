"""Bulk co-simulation of ``method_dpc_top``: every base method on long frame sequences.

The stimulus is what a camera's DMA and registers would give the core: per frame the
coefficient image (the method's memories; table_interp: the frame's tables j and j + 1)
and the frame word (:mod:`irnuc.cosim.stream`), the FPA reading of each frame deciding
both. :func:`run_method_bulk` streams the frames through the harness of
:func:`irnuc.cosim.bulk.build_bulk` (one image per distinct coefficient set, a frame
index into them), :func:`check_method_bulk` compares every output with
``nuc_fixed.method_top`` bit for bit (numpy first; the scoreboard's triage lines on a
difference).

The stage tops: :func:`run_drift_bulk` / :func:`check_drift_bulk` (``method_drift_top``,
the frames of :func:`irnuc.cosim.stages.drift_frames` with their blind items) and
:func:`run_ffc_bulk` / :func:`check_ffc_bulk` (``method_ffc_top``, a sequence of
:func:`irnuc.cosim.stages.ffc_run`; the harness writes the FFC accumulator and corrections
back and reads them in, as the camera's external memory would).
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from pathlib import Path
from typing import Any

import numpy as np

from irnuc.common.errors import UserError
from irnuc.cosim.builds import Build
from irnuc.cosim.bulk import BulkResult, StageStreams, exact_stream, flag_lines, run_frames
from irnuc.cosim.methods import MethodScoreboard, golden_frames
from irnuc.cosim.scoreboard import Scoreboard, ScoreResult
from irnuc.cosim.stages import DriftFrame, FfcRun, StageScoreboard
from irnuc.cosim.stream import frame_word, stream_limbs
from irnuc.nuc_fixed import methods
from irnuc.nuc_fixed.config import PipelineConfig
from irnuc.nuc_fixed.method_top import FrameInputs, MethodCoefficients, method_top
from irnuc.nuc_fixed.validate import InputError, check_frame_shape, int_array

__all__ = ["check_drift_bulk", "check_ffc_bulk", "check_method_bulk", "ffc_schedule",
           "method_stimulus", "run_drift_bulk", "run_ffc_bulk", "run_method_bulk"]


def _readings(coeffs: MethodCoefficients, n: int, readings: object | None
              ) -> list[Any]:
    """One FPA reading per frame for a method that takes it (``MethodSpec.readings``); for
    one that also takes the housing reading, ``readings`` is ``{"fpa": (N,), "housing":
    (N,)}`` (or one such mapping per frame) and each frame's is a mapping of both."""
    cfg = coeffs.cfg
    if "fpa" not in cfg.base.readings:
        return [None] * n
    if readings is None:
        raise InputError(f"method {cfg.method!r} needs one FPA reading per frame")
    named = ("housing" in cfg.base.readings)
    if named and isinstance(readings, list | tuple) and readings \
            and all(isinstance(r, Mapping) for r in readings):
        # one mapping per frame (method_stim.random_reading's): by reading
        readings = {k: [r[k] for r in readings] for k in ("fpa", "housing")}
    if named and not isinstance(readings, Mapping):
        raise InputError(f"method {cfg.method!r} needs readings = {{'fpa': ..., 'housing': "
                         "...}, one of each per frame")
    src = readings if isinstance(readings, Mapping) else {"fpa": readings}
    cols = {}
    for name in ("fpa", "housing") if named else ("fpa",):
        bits = cfg.reading_bits if name == "fpa" else cfg.housing_bits
        label = f"readings[{name!r}]" if named else "readings"
        r = int_array(label, src[name], 0, (1 << int(bits or 1)) - 1).ravel()
        if r.size != n:
            raise InputError(f"{label} holds {r.size} values for {n} frames")
        cols[name] = [int(v) for v in r]
    if not named:
        return cols["fpa"]
    return [{"fpa": t, "housing": h} for t, h in zip(cols["fpa"], cols["housing"], strict=True)]


def method_stimulus(coeffs: MethodCoefficients, readings: list[int | None]
                    ) -> tuple[np.ndarray, np.ndarray]:
    """The harness's coefficient images (M, H, W, L) uint64 and per-frame (image, frame
    word) (N, 2): one image per distinct coefficient set (table_interp: per table pair)."""
    keys: dict[object, int] = {}
    images = []
    info = np.zeros((len(readings), 2), dtype=np.uint64)
    cfg = coeffs.cfg
    for i, rd in enumerate(readings):
        # The method decides when the image changes (table_interp: with the table pair).
        key = cfg.base.stream_key(coeffs, methods.frame(cfg, rd))
        if key not in keys:
            keys[key] = len(images)
            images.append(stream_limbs(coeffs, rd))
        info[i] = (keys[key], frame_word(coeffs, rd))
    return np.stack(images), info


def run_method_bulk(bld: Build, coeffs: MethodCoefficients, raw: object,
                    readings: object | None = None, *, idle_percent: int = 0,
                    stall_percent: int = 0, seed: int = 1, work_dir: Path | None = None,
                    shards: int = 1, public_eval: bool = False,
                    wrapper: Sequence[str] = ()) -> BulkResult:
    """Stream frames (N, H, W) corrected with ``coeffs`` (and one FPA reading per frame
    for tc_offset and table_interp) through the bulk harness of ``method_dpc_top``.

    Other arguments as :func:`irnuc.cosim.bulk.run_bulk` (``wrapper``: see
    :func:`irnuc.cosim.bulk.run_frames`); check with :func:`check_method_bulk`.
    """
    if bld.top != "method_dpc_top":
        raise UserError(f"{bld.top} is not method_dpc_top; use cosim.build_bulk(cfg) of a "
                        "method configuration")
    cfg = bld.cfg
    if coeffs.cfg != cfg:
        raise InputError(f"the coefficients are of {coeffs.cfg.name!r}, the build of {cfg.name!r}")
    x = int_array("raw", raw, 0, (1 << cfg.adc_bits) - 1)
    h, w = check_frame_shape("raw", x.shape, cfg)
    if (h, w) != coeffs.shape:
        raise InputError(f"raw frames are {(h, w)} but the coefficients are {coeffs.shape}")
    frames = x.reshape(-1, h, w)
    rds = _readings(coeffs, frames.shape[0], readings)
    images, info = method_stimulus(coeffs, rds)
    return run_frames(bld, frames, images, info, idle_percent=idle_percent,
                      stall_percent=stall_percent, seed=seed, work_dir=work_dir, shards=shards,
                      public_eval=public_eval, wrapper=wrapper)


def check_method_bulk(res: BulkResult, coeffs: MethodCoefficients, raw: object,
                      readings: object | None = None, golden: PipelineConfig | None = None,
                      expected: np.ndarray | None = None, max_report: int = 10) -> ScoreResult:
    """Check a :func:`run_method_bulk` run bit for bit against ``nuc_fixed.method_top``
    (``golden``: another configuration to check against on purpose; ``expected``: its
    output if already computed)."""
    x = np.asarray(raw)
    h, w = x.shape[-2:]
    frames = x.reshape(-1, h, w)
    rds = _readings(coeffs, frames.shape[0], readings)
    g = coeffs if golden is None else MethodCoefficients(golden, coeffs.fields,
                                                         coeffs.registers)
    if expected is None:
        inputs = FrameInputs.of_frames(rds)
        expected = method_top(frames, g, inputs).y
    exp = np.asarray(expected, dtype=np.int64).ravel()
    if exact_stream(res, exp):
        return ScoreResult(compared=exp.size, mismatches=0, missing=0, extra=0, lines=[])
    sb = MethodScoreboard(g.cfg, max_report=max_report)
    for fr in golden_frames(coeffs, list(frames), rds, golden=g.cfg):
        sb.expect_frame(fr)
    sb.observe_arrays(data=res.data, sof=res.sof, eol=res.eol)
    r = sb.result()
    return ScoreResult(compared=r.compared, mismatches=r.mismatches, missing=r.missing,
                       extra=r.extra + res.extra, lines=[*r.lines, *flag_lines(res)],
                       first_index=r.first_index, flag_errors=int(res.frame_err))


# ---- the stage tops -------------------------------------------------------------------------

def _unsigned(value: int, bits: int) -> int:
    return int(value) & ((1 << bits) - 1)


def run_drift_bulk(bld: Build, frames: list[DriftFrame], *, idle_percent: int = 0,
                   stall_percent: int = 0, seed: int = 1, work_dir: Path | None = None,
                   shards: int = 1) -> BulkResult:
    """Stream :func:`irnuc.cosim.stages.drift_frames` (each frame's blind items, pixels and
    coefficient words; one calibration) through the bulk harness of ``method_drift_top``.

    The registers ``blind_ref`` and ``drift_gain`` are the calibration's. Other arguments
    as :func:`irnuc.cosim.bulk.run_bulk`; check with :func:`check_drift_bulk`.
    """
    if bld.top != "method_drift_top":
        raise UserError(f"{bld.top} is not method_drift_top; use cosim.build_bulk(cfg) of a "
                        "blind_drift configuration")
    if not frames:
        raise InputError("no frames to stream")
    coeffs = frames[0].coeffs
    cfg = bld.cfg
    if coeffs.cfg != cfg:
        raise InputError(f"the coefficients are of {coeffs.cfg.name!r}, the build of {cfg.name!r}")
    if any(f.coeffs is not coeffs for f in frames):
        raise InputError("the frames of one bulk run share one calibration")
    x = int_array("raw", np.stack([f.raw for f in frames]), 0, (1 << cfg.adc_bits) - 1)
    h, w = check_frame_shape("raw", x.shape, cfg)
    if (h, w) != coeffs.shape:
        raise InputError(f"raw frames are {(h, w)} but the coefficients are {coeffs.shape}")
    images, info = method_stimulus(coeffs, [None] * len(frames))
    counts = np.array([f.blind.size for f in frames], dtype=np.uint64)  # type: ignore[union-attr]
    regs = cfg.registers
    stage = StageStreams(
        blind=np.concatenate([f.blind for f in frames]).astype(np.uint64),  # type: ignore[misc]
        registers={"blind_ref": _unsigned(coeffs.registers["blind_ref"], regs["blind_ref"].width),
                   "drift_gain": _unsigned(coeffs.registers["drift_gain"],
                                           regs["drift_gain"].width)})
    return run_frames(bld, x, images, np.column_stack([info, counts]),
                      idle_percent=idle_percent, stall_percent=stall_percent, seed=seed,
                      work_dir=work_dir, shards=shards, stage=stage)


def check_drift_bulk(res: BulkResult, frames: list[DriftFrame],
                     max_report: int = 10) -> ScoreResult:
    """Check a :func:`run_drift_bulk` run bit for bit against the frames' golden outputs
    (:func:`irnuc.cosim.stages.drift_frames`, possibly of another configuration on
    purpose); every blind item must have been taken."""
    exp = np.concatenate([f.expected.ravel() for f in frames]).astype(np.int64)
    n_blind = sum(int(f.blind.size) for f in frames)  # type: ignore[union-attr]
    taken = [] if res.stage_taken[0] == n_blind else [
        f"s_blind took {res.stage_taken[0]} of {n_blind} items"]
    if exact_stream(res, exp) and not taken:
        return ScoreResult(compared=exp.size, mismatches=0, missing=0, extra=0, lines=[])
    golden = frames[0].coeffs.cfg if frames else None
    sb = StageScoreboard(golden, max_report=max_report)  # type: ignore[arg-type]
    for fr in frames:
        sb.expect_frame(fr)
    sb.observe_arrays(data=res.data, sof=res.sof, eol=res.eol)
    r = sb.result()
    return ScoreResult(compared=r.compared, mismatches=r.mismatches, missing=r.missing,
                       extra=r.extra + res.extra, lines=[*r.lines, *flag_lines(res), *taken],
                       first_index=r.first_index, flag_errors=int(res.frame_err) + len(taken))


def ffc_schedule(run: FfcRun) -> np.ndarray:
    """(N, 3) uint64 per frame: the shutter flag, the write-back frame s_foff reads (k + 1:
    the k-th refresh frame's m_foff words; 0: the zeros after reset) and the one s_acc
    reads (k + 1: the k-th m_acc frame; 0: none), from the golden run's streams."""
    n = len(run.frames)
    out = np.zeros((n, 3), dtype=np.uint64)
    refreshes = writes = 0
    last_acc: np.ndarray | None = None
    for i in range(n):
        out[i, 0] = bool(run.shutter[i])
        out[i, 1] = refreshes
        if run.acc_in[i] is not None:
            # The golden run reads the accumulator last written: so does the memory.
            if last_acc is None or not np.array_equal(run.acc_in[i], last_acc):
                raise InputError(f"frame {i} reads an accumulator no frame wrote")
            out[i, 2] = writes
        if run.foff_out[i] is not None:
            refreshes += 1
        if run.acc_out[i] is not None:
            writes += 1
            last_acc = run.acc_out[i]
    return out


def run_ffc_bulk(bld: Build, run: FfcRun, *, idle_percent: int = 0, stall_percent: int = 0,
                 seed: int = 1, work_dir: Path | None = None,
                 writeback: bool = True) -> BulkResult:
    """Stream an FFC sequence (:func:`irnuc.cosim.stages.ffc_run`: frames, shutter flags,
    readings, one calibration) through the bulk harness of ``method_ffc_top``, from reset.

    The harness is the external memory: ``s_foff`` reads the corrections the DUT wrote on
    ``m_foff`` (zeros before the first refresh), ``s_acc`` the accumulator it wrote on
    ``m_acc``, each word once written. ``writeback=False`` drops the corrections written
    back (s_foff streams the zeros after reset throughout: a camera whose write-back
    fails; the negative control of the check). Other arguments as
    :func:`irnuc.cosim.bulk.run_bulk` (one process); check with :func:`check_ffc_bulk`.
    """
    if bld.top != "method_ffc_top":
        raise UserError(f"{bld.top} is not method_ffc_top; use cosim.build_bulk(cfg) of an "
                        "ffc configuration")
    coeffs = run.frames[0].coeffs
    cfg = bld.cfg
    if coeffs.cfg != cfg:
        raise InputError(f"the coefficients are of {coeffs.cfg.name!r}, the build of {cfg.name!r}")
    x = int_array("raw", np.stack([f.raw for f in run.frames]), 0, (1 << cfg.adc_bits) - 1)
    h, w = check_frame_shape("raw", x.shape, cfg)
    rds = [f.reading for f in run.frames]
    images, info = method_stimulus(coeffs, _readings(coeffs, len(rds), None if rds[0] is None
                                                     else rds))
    pixels = h * w
    stage = StageStreams(outputs=int((~run.held).sum()) * pixels,
                         acc_n=sum(a is not None for a in run.acc_out) * pixels,
                         foff_n=sum(a is not None for a in run.foff_out) * pixels)
    sched = ffc_schedule(run)
    if not writeback:
        sched[:, 1] = 0
    return run_frames(bld, x, images, np.column_stack([info, sched]),
                      idle_percent=idle_percent, stall_percent=stall_percent, seed=seed,
                      work_dir=work_dir, stage=stage)


def _words(res: BulkResult, name: str, want: list[np.ndarray | None], bits: int,
           max_report: int) -> ScoreResult:
    got = getattr(res, name)
    parts = [np.asarray(a, dtype=np.int64).ravel() & ((1 << bits) - 1)
             for a in want if a is not None]
    exp = np.concatenate(parts) if parts else np.zeros(0, np.int64)
    got = np.zeros(0, np.int64) if got is None else got.astype(np.int64)
    if got.size == exp.size and np.array_equal(got, exp):
        return ScoreResult(compared=exp.size, mismatches=0, missing=0, extra=0, lines=[])
    sb = Scoreboard(("data",), max_report=max_report)
    sb.expect(data=exp)
    sb.observe_arrays(data=got)
    r = sb.result()
    return ScoreResult(compared=r.compared, mismatches=r.mismatches, missing=r.missing,
                       extra=r.extra, lines=[f"m_{name}: {line}" for line in r.lines],
                       first_index=r.first_index)


def check_ffc_bulk(res: BulkResult, run: FfcRun, max_report: int = 10
                   ) -> dict[str, ScoreResult]:
    """Check a :func:`run_ffc_bulk` run bit for bit against the golden run ``run``
    (possibly of another configuration or other stimulus on purpose): ``m_pix`` (every
    frame not held), ``m_acc`` and ``m_foff`` (their words, in order)."""
    shown = [f for f, held in zip(run.frames, run.held, strict=True) if not held]
    exp = (np.concatenate([f.expected.ravel() for f in shown]).astype(np.int64) if shown
           else np.zeros(0, np.int64))
    cfg = run.frames[0].coeffs.cfg
    mem = cfg.memories
    out = {"m_acc": _words(res, "acc", run.acc_out, mem["ffc_acc"].word_bits, max_report),
           "m_foff": _words(res, "foff", run.foff_out, mem["ffc_offset"].word_bits,
                            max_report)}
    if exact_stream(res, exp):
        out["m_pix"] = ScoreResult(compared=exp.size, mismatches=0, missing=0, extra=0,
                                   lines=[])
        return out
    sb = StageScoreboard(cfg, max_report=max_report)
    for fr in shown:
        sb.expect_frame(fr)
    sb.observe_arrays(data=res.data, sof=res.sof, eol=res.eol)
    r = sb.result()
    out["m_pix"] = ScoreResult(compared=r.compared, mismatches=r.mismatches, missing=r.missing,
                               extra=r.extra + res.extra, lines=[*r.lines, *flag_lines(res)],
                               first_index=r.first_index, flag_errors=int(res.frame_err))
    return out
