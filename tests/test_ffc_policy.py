"""The FFC trigger policy (nuc_fixed/ffc_policy.py) on hand-worked frame sequences: the
expected request frames are worked out below from the rule in the module's docstring
(docs/integration.md, "FFC requests"), not taken from the code."""

from __future__ import annotations

import numpy as np
import pytest

from irnuc.common.errors import ConfigError
from irnuc.nuc_fixed.ffc_policy import (
    FfcPolicy,
    closed_loop,
    ffc_trigger,
    period_bits,
    threshold_bits,
)


def test_widths_are_the_register_fields() -> None:
    # FFC_PERIOD.frames[23:0], FFC_THRESHOLD.codes[23:0] in nuc_fixed/registers.rdl.
    assert (period_bits(), threshold_bits()) == (24, 24)


def test_period_only() -> None:
    # since = 0, 1, 2, 3, ...: due from frame 3 on, one request there.
    t = ffc_trigger([0] * 8, [], FfcPolicy(period=3))
    assert t.since.tolist() == [0, 1, 2, 3, 4, 5, 6, 7]
    assert t.due.tolist() == [False] * 3 + [True] * 5
    assert t.request_frames == [3]
    assert not t.threshold_hit.any()


def test_period_rearmed_by_an_ffc() -> None:
    # A start applies to frame 5: since 0 1 2 3 4 | 0 1 2 3 4; due at 3, 4 and 8, 9.
    t = ffc_trigger([0] * 10, [5], FfcPolicy(period=3))
    assert t.since.tolist() == [0, 1, 2, 3, 4, 0, 1, 2, 3, 4]
    assert t.request_frames == [3, 8]


def test_threshold_crossings() -> None:
    # ref = 100 (frame 0); |r - ref| = 0 2 4 5 3 4 6 0: due at 3 and 6 (it fell at 4, so
    # frame 6 is a new crossing), requests at 3 and 6.
    r = [100, 102, 104, 105, 103, 96, 94, 100]
    t = ffc_trigger(r, [], FfcPolicy(threshold=5))
    assert t.ref.tolist() == [100] * 8
    assert t.due.tolist() == [False, False, False, True, False, False, True, False]
    assert t.request_frames == [3, 6]
    # An FFC at frame 4 takes 103 as the reference: |r - 103| at 5, 6, 7 = 7, 9, 3.
    t = ffc_trigger(r, [4], FfcPolicy(threshold=5))
    assert t.ref.tolist() == [100] * 4 + [103] * 4
    assert t.due.tolist() == [False, False, False, True, False, True, True, False]
    assert t.request_frames == [3, 5]


def test_both_triggers() -> None:
    # threshold 10 fires at frame 2 (|20 - 0|), falls at 3; the period 4 fires at 4.
    t = ffc_trigger([0, 0, 20, 0, 0, 0], [], FfcPolicy(period=4, threshold=10))
    assert t.threshold_hit.tolist() == [False, False, True, False, False, False]
    assert t.period_hit.tolist() == [False] * 4 + [True] * 2
    assert t.request_frames == [2, 4]


def test_disabled() -> None:
    rng = np.random.default_rng(1)
    t = ffc_trigger(rng.integers(0, 1 << 14, 50), [7, 20], FfcPolicy())
    assert not t.due.any() and not t.request.any()


def test_policy_range_and_bad_input() -> None:
    FfcPolicy(period=(1 << 24) - 1, threshold=(1 << 24) - 1)
    for kw in ({"period": 1 << 24}, {"threshold": -1}, {"period": 1.5}, {"period": True}):
        with pytest.raises(ConfigError, match="FfcPolicy"):
            FfcPolicy(**kw)
    with pytest.raises(ConfigError, match="readings"):
        ffc_trigger([1, -2], [], FfcPolicy(period=1))
    with pytest.raises(ConfigError, match="frame_rate"):
        FfcPolicy.from_physical(1.0, 1.0, 0.0, 0.01)


def test_from_physical() -> None:
    # The Lepton (about 9 Hz) with a 0.01 K sensor: 180 s x 9 = 1620 frames, 1.5 / 0.01 =
    # 150 codes; at 30 Hz and 0.05 K: 5400 frames, 30 codes; 0.12 K at 0.05 K: 2.4 -> 3.
    assert FfcPolicy.lepton(9.0, 0.01) == FfcPolicy(1620, 150)
    assert FfcPolicy.from_physical(180.0, 1.5, 30.0, 0.05) == FfcPolicy(5400, 30)
    assert FfcPolicy.from_physical(None, 0.12, 30.0, 0.05) == FfcPolicy(0, 3)
    assert FfcPolicy.from_physical(2.0, None, 30.0, 0.05) == FfcPolicy(60, 0)


def test_closed_loop() -> None:
    # Period 4, runs of 2 shutter frames + the refresh: the power-on run at 0; since 4 at
    # frame 4 -> request -> the start applies to frame 5; then 9 -> 10, 14 -> 15.
    assert closed_loop([0] * 16, FfcPolicy(period=4), 2) == [0, 5, 10, 15]
    # Period 1, runs of 3 + 1: a request at 1 waits for the power-on run (frames 0..3),
    # begins at 4; the next at 5 waits until 8; then 12.
    assert closed_loop([0] * 14, FfcPolicy(period=1), 3) == [0, 4, 8, 12]
    # No trigger: only the power-on FFC.
    assert closed_loop([5, 9, 200], FfcPolicy(), 8) == [0]


def test_shutter_cost_hand_worked() -> None:
    """A 0.1 K/frame ramp at 1 Hz read with a 0.1 K sensor (reading = frame), a 0.5 K
    threshold, N = 2, one settle frame, residual 10 + 100 x change mK. The power-on FFC at
    0; |reading - ref| = 5 at frames 5, 11, 17 -> FFCs at 6, 12, 18. Lost: 0-2, 6-8, 12-14,
    18-19 = 11 of 20 frames. Each FFC holds the mean FPA of its two shutter frames (300.05,
    300.65, 301.25 K) from its refresh frame; the shown frames 3-5, 9-11, 15-17 are 0.25,
    0.35, 0.45 K from it: 35, 45, 55 mK."""
    from irnuc.reports.studies.ffc_interval import residual_at, shutter_cost

    i = np.arange(20)
    c = shutter_cost(300.0 + 0.1 * i, i, 1.0, FfcPolicy(threshold=5), 2,
                     {"m": (np.array([0.0, 1.0]), np.array([10.0, 110.0]))})
    assert c["ffc_starts"] == 4
    assert c["events_per_hour"] == pytest.approx(4 / (20 / 3600))
    assert c["dead_frames"] == 11 and c["dead_time_pct"] == pytest.approx(55.0)
    assert c["worst_change_K"] == pytest.approx(0.45)
    r = c["residual"]["m"]
    assert r["worst_mK"] == pytest.approx(55.0) and r["mean_mK"] == pytest.approx(45.0)
    assert r["peaks_mK"] == pytest.approx([55.0, 55.0, 55.0])
    assert r["beyond_curve_frames"] == 0
    # Beyond the curve: linear from its last two points; the change's sign does not count.
    y, beyond = residual_at(np.array([3.0, -0.5]), np.array([0.0, 1.0, 2.0]),
                            np.array([0.0, 10.0, 30.0]))
    assert y.tolist() == pytest.approx([50.0, 5.0]) and beyond.tolist() == [True, False]
