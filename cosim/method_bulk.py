"""Bulk co-simulation of ``method_dpc_top``: every base method on long frame sequences.

The stimulus is what a camera's DMA and registers would give the core: per frame the
coefficient image (the method's memories; table_interp: the frame's tables j and j + 1)
and the frame word (:mod:`irnuc.cosim.stream`), the FPA reading of each frame deciding
both. :func:`run_method_bulk` streams the frames through the harness of
:func:`irnuc.cosim.bulk.build_bulk` (one image per distinct coefficient set, a frame
index into them), :func:`check_method_bulk` compares every output with
``nuc_fixed.method_top`` bit for bit (numpy first; the scoreboard's triage lines on a
difference).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from irnuc.common.errors import UserError
from irnuc.cosim.builds import Build
from irnuc.cosim.bulk import BulkResult, exact_stream, flag_lines, run_frames
from irnuc.cosim.methods import MethodScoreboard, golden_frames
from irnuc.cosim.scoreboard import ScoreResult
from irnuc.cosim.stream import frame_word, stream_limbs
from irnuc.nuc_fixed.config import PipelineConfig
from irnuc.nuc_fixed.method_top import FrameInputs, MethodCoefficients, method_top
from irnuc.nuc_fixed.tempcomp import interp_weight
from irnuc.nuc_fixed.validate import InputError, check_frame_shape, int_array

__all__ = ["check_method_bulk", "method_stimulus", "run_method_bulk"]


def _readings(coeffs: MethodCoefficients, n: int, readings: object | None) -> list[int | None]:
    cfg = coeffs.cfg
    if cfg.base_method not in ("tc_offset", "table_interp"):
        return [None] * n
    if readings is None:
        raise InputError(f"method {cfg.method!r} needs one FPA reading per frame")
    hi = (1 << int(cfg.reading_bits or 1)) - 1
    r = int_array("readings", readings, 0, hi).ravel()
    if r.size != n:
        raise InputError(f"readings holds {r.size} values for {n} frames")
    return [int(v) for v in r]


def method_stimulus(coeffs: MethodCoefficients, readings: list[int | None]
                    ) -> tuple[np.ndarray, np.ndarray]:
    """The harness's coefficient images (M, H, W, L) uint64 and per-frame (image, frame
    word) (N, 2): one image per distinct coefficient set (table_interp: per table pair)."""
    keys: dict[object, int] = {}
    images = []
    info = np.zeros((len(readings), 2), dtype=np.uint64)
    cfg = coeffs.cfg
    for i, rd in enumerate(readings):
        iw = (interp_weight(int(rd), coeffs.registers["table_readings"], cfg)  # type: ignore[arg-type]
              if cfg.base_method == "table_interp" else None)
        key = None if iw is None else iw.j
        if key not in keys:
            keys[key] = len(images)
            images.append(stream_limbs(coeffs, rd))
        info[i] = (keys[key], frame_word(coeffs, rd, iw))
    return np.stack(images), info


def run_method_bulk(bld: Build, coeffs: MethodCoefficients, raw: object,
                    readings: object | None = None, *, idle_percent: int = 0,
                    stall_percent: int = 0, seed: int = 1, work_dir: Path | None = None,
                    shards: int = 1) -> BulkResult:
    """Stream frames (N, H, W) corrected with ``coeffs`` (and one FPA reading per frame
    for tc_offset and table_interp) through the bulk harness of ``method_dpc_top``.

    Other arguments as :func:`irnuc.cosim.bulk.run_bulk`; check with
    :func:`check_method_bulk`.
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
                      stall_percent=stall_percent, seed=seed, work_dir=work_dir, shards=shards)


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
        inputs = FrameInputs(reading=None if rds[0] is None else np.asarray(rds))
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
