"""Bad-pixel detection: each reason, the no-padding local median, and precision/recall
against the injected ground truth of the physics model (and of the synthetic generator)."""

from __future__ import annotations

import numpy as np
import pytest

from irnuc.model.defects import DefectKind
from irnuc.nuc_fixed import ConfigError, load_pipeline
from irnuc.nuc_fixed.badpix import Reason, load_thresholds, local_median, reason_names
from irnuc.nuc_fixed.calibrate import calibrate
from irnuc.nuc_fixed.synthetic import synth_frames

CFG = load_pipeline("typical14")

# Which reason must fire for each planted kind (a pixel may also carry others).
EXPECTED = {
    "DEAD": Reason.UNRESPONSIVE | Reason.STUCK | Reason.EQUAL_RESPONSE,
    "STUCK_LOW": Reason.RAIL,
    "STUCK_HIGH": Reason.RAIL,
    "STUCK_VALUE": Reason.STUCK | Reason.EQUAL_RESPONSE | Reason.UNRESPONSIVE,
    "HOT": Reason.OFFSET_OUTLIER,
    "COLD": Reason.OFFSET_OUTLIER,
    "LOW_RESP": Reason.UNRESPONSIVE,
    "HIGH_RESP": Reason.OVER_RESPONSIVE,
    "NOISY": Reason.NOISY,
}


def _score(bad: np.ndarray, kind: np.ndarray) -> tuple[float, float]:
    truth = kind != 0
    tp = int((bad & truth).sum())
    return tp / max(int(bad.sum()), 1), tp / max(int(truth.sum()), 1)


def test_synthetic_precision_recall_and_reasons() -> None:
    """Synthetic sensor (nuc_fixed.synth): every planted kind found, for its own reason."""
    m = 8
    s = synth_frames(shape=(48, 64), repeats=m, defect_fraction=0.05, seed=11)
    cal = calibrate(s.codes[:m], s.codes[m:], CFG)
    precision, recall = _score(cal.bad, s.defect_kind)
    assert precision >= 0.97 and recall >= 0.97, (precision, recall)
    for kind in DefectKind:
        if kind == DefectKind.GOOD:
            continue
        sel = s.defect_kind == kind
        assert sel.any()
        hit = (cal.reasons[sel] & int(EXPECTED[kind.name])) != 0
        assert hit.mean() >= 0.9, (kind.name, [reason_names(int(r)) for r in cal.reasons[sel]])


def test_model_precision_recall() -> None:
    """Physics model frames with injected defects of every kind (docs/fpa.md)."""
    model = pytest.importorskip("model")
    if not hasattr(model, "simulate"):
        pytest.skip("model.simulate not available")
    kinds = ["dead", "stuck_low", "stuck_high", "stuck_value", "hot", "cold", "low_resp",
             "high_resp", "noisy"]
    mcfg = model.load_preset("default", overrides={
        "fpa.active_rows": 48, "fpa.active_cols": 64, "noise.enabled": True,
        "fpa.defects": {"rates": dict.fromkeys(kinds, 0.004), "clusters": 2},
    })
    m = 8
    res = model.simulate(mcfg, temps=[300.0, 400.0], scene="uniform", repeats=m, seed=1)
    assert res.adc_bits == CFG.adc_bits
    cal = calibrate(res.codes[:m], res.codes[m:], CFG)
    precision, recall = _score(cal.bad, res.defect_kind)
    assert precision >= 0.95 and recall >= 0.9, (precision, recall)
    # Every kind except the offset ones (whose size is comparable to the fixed-pattern
    # spread, and which the two-point NUC corrects anyway) is found completely.
    for kind in DefectKind:
        sel = res.defect_kind == kind
        if kind == DefectKind.GOOD or not sel.any():
            continue
        found = cal.bad[sel].mean()
        assert found >= (0.75 if kind.name in ("HOT", "COLD") else 1.0), (kind.name, found)


def test_local_median_uses_in_frame_pixels_only() -> None:
    rng = np.random.default_rng(2)
    v = rng.normal(size=(7, 9))
    usable = rng.random((7, 9)) > 0.3
    got = local_median(v, usable, 5)
    for r in range(7):
        for c in range(9):
            vals = [v[i, j] for i in range(max(r - 2, 0), min(r + 3, 7))
                    for j in range(max(c - 2, 0), min(c + 3, 9)) if usable[i, j]]
            if vals:
                assert got[r, c] == pytest.approx(float(np.median(vals)))
            else:
                assert np.isnan(got[r, c])


def test_corner_and_border_defects_are_found() -> None:
    """An offset defect in a corner and in rows 1 and H-2 (where padding used to hide it)."""
    m = 4
    s = synth_frames(shape=(20, 24), repeats=m, defect_fraction=0.0, seed=5)
    codes = s.codes.astype(np.int64)
    spots = [(0, 0), (19, 23), (1, 10), (18, 10), (10, 1), (10, 22)]
    for p in spots:
        codes[:, p[0], p[1]] += 2500  # a hot pixel
    cal = calibrate(codes[:m], codes[m:], CFG)
    for p in spots:
        assert cal.reasons[p] & Reason.OFFSET_OUTLIER, p
    assert int(cal.bad.sum()) == len(spots)


def test_noisy_needs_several_frames() -> None:
    s = synth_frames(shape=(16, 16), repeats=1, defect_fraction=0.0, seed=3)
    cal = calibrate(s.codes[:1], s.codes[1:], CFG)
    assert cal.summary["reasons"]["NOISY"] == 0


def test_thresholds_file_and_errors(tmp_path) -> None:
    th = load_thresholds()
    assert 0 < th.low_response < 1 < th.high_response
    p = tmp_path / "t.toml"
    p.write_text("[default]\nlow_response = 0.4\n")
    with pytest.raises(ConfigError, match=r"default\.high_response is required but missing"):
        load_thresholds(p)
    with pytest.raises(ConfigError, match="offset_window = 4"):
        load_thresholds(overrides={"offset_window": 4})
    with pytest.raises(ConfigError, match="bogus is not a known field"):
        load_thresholds(overrides={"bogus": 1.0})
    with pytest.raises(ConfigError, match="did you mean 'noisy_factor'"):
        load_thresholds(overrides={"noisy_facter": 1.0})
    assert reason_names(int(Reason.RAIL | Reason.NOISY)) == ["RAIL", "NOISY"]
