"""The bins of the drift and AXI FFC coverage models against hand-made accounts of one run
(pure Python, no simulation): ``cosim.stage_coverage.drift_classes`` on frames whose
blind sums, drift codes and x' are worked out by hand, and
``cosim.axis_coverage.ffc_axis_classes`` on the shutter sequences ``tb_axis_ffc`` drives.
"""

from __future__ import annotations

import numpy as np

from irnuc.cosim.axis_coverage import FFC_AXIS_POINTS, ffc_axis_classes
from irnuc.cosim.stage_coverage import DRIFT_POINTS, DriftCoverageModel, drift_classes
from irnuc.cosim.stages import drift_frames
from irnuc.nuc_fixed import load_pipeline
from irnuc.nuc_fixed.axis import ffc_framing, ffc_shutter_flags
from irnuc.nuc_fixed.method_top import MethodCoefficients


def _unity(cfg, h: int, w: int, regs: dict[str, int]) -> MethodCoefficients:
    """Gain 1.0, offset 0, no bad pixel: the core's r is x' / 2^Df rounded."""
    fields = {"coeffs": {"gain": np.full((h, w), 1 << cfg.gain_frac_bits, np.int64),
                         "offset": np.zeros((h, w), np.int64),
                         "bad": np.zeros((h, w), bool)}}
    return MethodCoefficients(cfg, fields, regs)


def test_drift_classes_of_a_run_by_hand() -> None:
    """drift14 (A = 14, Df = 2, Mf = 24, delta S14.2: codes -32768..32767), blind_ref 1000,
    m = 2^22 (0.25: delta = (sum - 1000) * 2^22 >> 22 = sum - 1000, no rounding), four
    frames back to back:

    1. 2 x 3, blind items 100, 200 (several; sum 300): bd = -700, delta -700; x' = 4x + 700
       is 700 at x = 0 (in range) and 66232 at x = 16383 (above 65532 = 16383 << 2); r =
       x' / 4 = 16558 there, above 2^14 - 1;
    2. 2 x 3, items 16383, 16383, 7234 (sum 40000): bd = 39000 > 32767: delta saturates
       high at 32767; x' = -32767 at x = 0 (negative, r = -8192 below 0);
    3. 1 x 1, one item 1000: bd = 0, delta 0 (no bd bin), a tiny frame whose delta changed;
    4. 1 x 1, one item 1000 again: delta the same, the size the same.
    """
    cfg = load_pipeline("drift14")
    regs = {"blind_ref": 1000, "drift_gain": 1 << 22}
    big = [[0, 10, 100], [1000, 16383, 50]]
    frames = (drift_frames(_unity(cfg, 2, 3, regs), [np.array(big)] * 2,
                           [np.array([100, 200]), np.array([16383, 16383, 7234])])
              + drift_frames(_unity(cfg, 1, 1, regs), [np.array([[5]]), np.array([[7]])],
                             [np.array([1000]), np.array([1000])]))
    assert [f.delta for f in frames] == [-700, 32767, 0, 0]
    got = drift_classes(frames)
    assert got == {
        "drift.items": {"several", "one"},
        "drift.gain": {"positive"},
        "drift.bd": {"negative", "positive"},
        "drift.delta": {"negative", "sat_high", "zero"},
        "drift.x": {"in_range", "above_max", "negative"},
        "drift.range": {"in_range", "above_max", "below_zero"},
        "drift.update": {"changed", "changed_tiny", "same"},
        "drift.size": {"same", "changed"},
    }
    # Every bin the classes name is a bin of the model (a misspelt label would never hit).
    for point, labels in got.items():
        assert labels <= set(DRIFT_POINTS[point]), point


def test_drift_model_reports_a_missed_bin() -> None:
    """The run above leaves sat_low, m = 0, m < 0 and the reset unhit: the summary the
    closure test reads names them, so the closure can fail."""
    from irnuc.cosim import coverage

    cfg = load_pipeline("drift14")
    regs = {"blind_ref": 1000, "drift_gain": 1 << 22}
    frames = drift_frames(_unity(cfg, 1, 2, regs), [np.array([[3, 4]])], [np.array([9])])
    m = DriftCoverageModel("method_drift_top", cfg, prefix="drift_byhand")
    m.sample_frames_run(frames)
    snap = m.snapshot()
    label = coverage.config_label(cfg)
    points = snap["configurations"][label]["coverpoints"]
    snap["configurations"][label]["coverpoints"] = {
        k: v for k, v in points.items() if k.startswith(("drift.", "reset."))}
    s = coverage.summarize(snap)["configurations"][label]
    assert s["hit"] < s["total"]
    assert {"drift.delta:sat_low", "drift.gain:zero", "drift.gain:negative",
            "reset.mid_frame:reset"} <= set(s["uncovered"])


def test_ffc_axis_classes_by_hand() -> None:
    """tb_axis_ffc's sequences on ffc14 (N = 8): frames of 24 pixels, FFC_CTRL written
    with 36 beats taken (frame 1's middle), its shutter frames from frame 2.

    * frames = 8 at full rate: start mid_frame, frames n, words on m_axis_acc (frames 2-9)
      and m_axis_foff (frame 10, the refresh) at full rate, shutter frames at full rate,
      the refresh from the next frame start;
    * frames = 2 with idle and backpressure: short, m_axis_acc only, shutter frames under
      backpressure, no refresh;
    * the write's response after frame 2 started (beat 50): not mid frame of the frame
      before the run, no refresh bin; written exactly at a frame boundary (beat 48): not
      mid frame.
    """
    cfg = load_pipeline("ffc14")
    full = ffc_framing(cfg, ffc_shutter_flags(13, {2: 8}), start=2)
    assert full.shutter == (False,) * 2 + (True,) * 8 + (False,) * 3
    assert full.foff_out.index(True) == 10
    assert ffc_axis_classes(full, 8, 8, 2, 36, 24, "none", "none") == {
        "axis.ffc.start": {"mid_frame"}, "axis.ffc.frames": {"n"},
        "axis.ffc.acc_stream": {"full_rate"}, "axis.ffc.foff_stream": {"full_rate"},
        "axis.ffc.shutter": {"full_rate"}, "axis.ffc.refresh": {"next_frame_start"},
        "axis.ffc.drain": set()}
    short = ffc_framing(cfg, ffc_shutter_flags(7, {2: 2}), start=2)
    assert not any(short.foff_out)
    assert ffc_axis_classes(short, 8, 2, 2, 36, 24, "random", "random") == {
        "axis.ffc.start": {"mid_frame"}, "axis.ffc.frames": {"short"},
        "axis.ffc.acc_stream": {"idle_backpressure"}, "axis.ffc.foff_stream": set(),
        "axis.ffc.shutter": {"backpressure"}, "axis.ffc.refresh": set(),
        "axis.ffc.drain": set()}
    # FRAME_SIZE written in frame 4 (beat 108), after the held frames 2 and 3: the drain;
    # written in frame 1 (beat 30), before any: none.
    assert short.shown[2:4] == (False, False) and all(short.shown[:2])
    assert ffc_axis_classes(short, 8, 2, 2, 36, 24, "random", "random",
                            resize_beat=108)["axis.ffc.drain"] == {"after_held"}
    assert ffc_axis_classes(short, 8, 2, 2, 36, 24, "random", "random",
                            resize_beat=30)["axis.ffc.drain"] == set()
    # Another size written in frame 3 (beat 80), the run's last held frame: both bins; in
    # frame 4 (beat 108), an open frame after the run: the drain after held frames only.
    assert ffc_axis_classes(short, 8, 2, 2, 36, 24, "none", "none", resize_beat=80,
                            resized=True)["axis.ffc.drain"] == {"after_held", "new_size_in_run"}
    assert ffc_axis_classes(short, 8, 2, 2, 36, 24, "none", "none", resize_beat=108,
                            resized=True)["axis.ffc.drain"] == {"after_held"}
    # In frame 10 (beat 250), the full run's refresh frame (after the held frames 2..9).
    assert ffc_axis_classes(full, 8, 8, 2, 36, 24, "none", "none", resize_beat=250,
                            resized=True)["axis.ffc.drain"] == {"after_held",
                                                                "new_size_in_refresh"}
    for beat in (50, 48):
        late = ffc_axis_classes(full, 8, 8, 2, beat, 24, "none", "none")
        assert late["axis.ffc.start"] == set() and late["axis.ffc.refresh"] == set()
    for labels in ffc_axis_classes(full, 8, 8, 2, 36, 24, "none", "none").values():
        assert all(any(b in bins for bins in FFC_AXIS_POINTS.values()) for b in labels)
