"""Bulk co-simulation (C++ harness) of the stage tops on drift sequences of the model.

``method_drift_top`` (drift14: the model's reference pixels as the blind codes) and
``method_ffc_top`` (ffc14: one FFC event, the harness writing the accumulator and the
corrections back as the external memory) against :mod:`irnuc.cosim.stages`' references,
through :func:`irnuc.cosim.sequence_bulk.cosim_sequence` and the lower calls; negative
controls: a corrupted coefficient and a dropped write-back of the FFC update must show as
mismatches where they act. Small frames: each run takes milliseconds, the two Verilator
builds (cached by content) the rest.
"""

from __future__ import annotations

import functools

import numpy as np
import pytest

from irnuc import cosim
from irnuc.common.errors import UserError
from irnuc.cosim.method_bulk import check_drift_bulk, check_ffc_bulk, run_drift_bulk, run_ffc_bulk
from irnuc.cosim.method_drift import calibrate_methods, drift_sequence
from irnuc.cosim.sequence_bulk import cosim_sequence, shutter_flags
from irnuc.cosim.stages import drift_frames, ffc_run
from irnuc.nuc_fixed import load_pipeline
from irnuc.nuc_fixed.method_top import MethodCoefficients

SHAPE = (16, 24)
HW = SHAPE[0] * SHAPE[1]
#: ffc14 (N = 8): open frame 0, shutter 1..8, refresh frame 9, open frame 10.
FFC_FRAMES = 11


@functools.cache
def _build(config: str) -> cosim.Build:
    return cosim.build_bulk(load_pipeline(config))


@functools.cache
def _sequence(config: str, frames: int):
    cfg = load_pipeline(config)
    flags = shutter_flags(cfg, frames, None) if cfg.has("ffc") else None
    seq = drift_sequence(frames, SHAPE, seed=3, shutter=flags)
    return cfg, seq, calibrate_methods([cfg], SHAPE, seed=3)[config]


@pytest.mark.cosim
@pytest.mark.slow
def test_sequence_bulk_drift14() -> None:
    """drift14 through the API: every pixel of every frame compared and exact."""
    r = cosim_sequence(load_pipeline("drift14"), 4, SHAPE, seed=3)
    assert r["top"] == "method_drift_top" and r["passed"], r
    assert (r["pixels_compared"], r["mismatches"], r["ffc_events"]) == (4 * HW, 0, 0)
    assert r["blind_codes_per_frame"] > 0


@pytest.mark.cosim
@pytest.mark.slow
def test_sequence_bulk_ffc14_one_event() -> None:
    """ffc14 (N = 8, hold) through the API: one refresh; the 8 shutter frames held, the
    other 3 output; m_acc in the 8 shutter frames and m_foff in the refresh frame."""
    r = cosim_sequence(load_pipeline("ffc14"), FFC_FRAMES, SHAPE, seed=3)
    assert r["top"] == "method_ffc_top" and r["passed"], r
    assert r["ffc_events"] == 1 and r["held_frames"] == 8 and r["mismatches"] == 0
    assert r["pixels_compared"] == 3 * HW and r["words_compared"] == 9 * HW


@pytest.mark.cosim
@pytest.mark.slow
def test_stage_bulk_streams_under_gaps_and_backpressure() -> None:
    """Idle inputs and back-pressured outputs on both tops, drift14 over two processes:
    exact; the FFC top takes s_foff every frame and s_acc in the 2nd..8th shutter frames
    and the refresh frame (8 frames), every blind item of every frame."""
    _, seq, cal = _sequence("drift14", 4)
    frames = drift_frames(cal, list(seq.codes), list(seq.blind_codes))
    assert len({f.delta for f in frames}) == 4, "the FPA drift moves no frame's delta"
    res = run_drift_bulk(_build("drift14"), frames, idle_percent=30, stall_percent=30,
                         seed=4, shards=2)
    chk = check_drift_bulk(res, frames)
    assert chk.passed and chk.compared == 4 * HW, chk.report()
    assert res.stage_taken[0] == seq.blind_codes.size
    _, seq, cal = _sequence("ffc14", FFC_FRAMES)
    run = ffc_run(cal, list(seq.codes), list(seq.shutter))
    res = run_ffc_bulk(_build("ffc14"), run, idle_percent=30, stall_percent=30, seed=5)
    out = check_ffc_bulk(res, run)
    assert all(c.passed for c in out.values()), [c.report() for c in out.values()]
    assert res.stage_taken == (FFC_FRAMES * HW, 8 * HW)


def _quiet_pixel(bad: np.ndarray) -> tuple[int, int]:
    """A good pixel whose 5 x 5 neighbourhood is good (the DPC never reads it)."""
    h, w = bad.shape
    for y in range(2, h - 2):
        for x in range(2, w - 2):
            if not bad[y - 2:y + 3, x - 2:x + 3].any():
                return y, x
    raise AssertionError("no good 5 x 5 neighbourhood")


@pytest.mark.cosim
@pytest.mark.slow
def test_stage_bulk_detects_corrupted_coefficient() -> None:
    """drift14 with one offset word corrupted in the RTL's stimulus (one bit flipped):
    the RTL follows it exactly, and against the true calibration exactly that pixel of
    every frame mismatches."""
    cfg, seq, cal = _sequence("drift14", 4)
    good = drift_frames(cal, list(seq.codes), list(seq.blind_codes))
    fields = {m: {k: np.array(v) for k, v in f.items()} for m, f in cal.fields.items()}
    y, x = _quiet_pixel(np.asarray(fields["coeffs"]["bad"], bool))
    fields["coeffs"]["offset"][y, x] ^= 1 << cfg.offset_frac_bits
    corrupt = drift_frames(MethodCoefficients(cfg, fields, cal.registers), list(seq.codes),
                           list(seq.blind_codes))
    res = run_drift_bulk(_build("drift14"), corrupt)
    assert check_drift_bulk(res, corrupt).passed
    chk = check_drift_bulk(res, good)
    assert chk.mismatches == 4 and chk.first_index == y * SHAPE[1] + x, chk.report()


@pytest.mark.cosim
@pytest.mark.slow
def test_stage_bulk_detects_dropped_ffc_update() -> None:
    """ffc14 with the write-back of the new corrections dropped: the DUT still computes
    the update (m_acc, m_foff exact) and the refresh frame uses it, but the next frame
    reads the old corrections: mismatches, the first in the frame after the refresh."""
    _, seq, cal = _sequence("ffc14", FFC_FRAMES)
    run = ffc_run(cal, list(seq.codes), list(seq.shutter))
    res = run_ffc_bulk(_build("ffc14"), run, writeback=False)
    out = check_ffc_bulk(res, run)
    assert out["m_acc"].passed and out["m_foff"].passed
    pix = out["m_pix"]
    assert pix.mismatches > 0, "a dropped FFC update went unseen"
    assert pix.first_index is not None and pix.first_index >= 2 * HW  # frames 0 and 9 exact


def test_sequence_bulk_refuses_bad_arguments() -> None:
    """One-line errors naming the argument, before any work."""
    cfg = load_pipeline("ffc14")
    for kwargs, word in (({"frames": 0}, "frames"), ({"shape": (2000, 10)}, "shape"),
                         ({"shape": "vga"}, "shape"), ({"ffc_every": 0}, "ffc_every"),
                         ({"fpa_K": (1.0, 2.0)}, "fpa_K"), ({"seed": -1}, "seed")):
        with pytest.raises(UserError, match=word):
            cosim_sequence(cfg, **kwargs)
    with pytest.raises(UserError, match="PipelineConfig"):
        cosim_sequence("ffc14")  # type: ignore[arg-type]


def test_shutter_flags_schedule() -> None:
    """Closings of N = 8 frames from frame 1, every ``ffc_every`` frames (default: two in
    20 frames)."""
    cfg = load_pipeline("ffc14")
    assert np.flatnonzero(shutter_flags(cfg, 20, None)).tolist() == [*range(1, 9),
                                                                      *range(11, 19)]
    assert np.flatnonzero(shutter_flags(cfg, 12, 9)).tolist() == [*range(1, 9), 10, 11]
