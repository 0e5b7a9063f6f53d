"""Shielded reference pixels read out beside the image (``blind_codes``) and what the
skimming and boundary pixels see (``fpa.skim_shield``, ``fpa.boundary_view``)."""

from __future__ import annotations

import numpy as np
import pytest

from irnuc import model
from irnuc.model.fpa import BLIND, BOUNDARY, ArrayLayout
from irnuc.model.optics import cone_factor

SMALL = {"fpa.active_rows": 24, "fpa.active_cols": 32, "fpa.defects": {}}


def _cfg(**over):
    return model.load_preset("default", {**SMALL, **over})


def _lsb(cfg):
    a = cfg["adc"]
    return (a["v_high"] - a["v_low"]) / 2 ** a["bits"]


@pytest.mark.parametrize(("mode", "kind"), [("boundary", BOUNDARY), ("blind", BLIND)])
def test_positions_are_the_named_ring_in_row_major_order(mode, kind):
    cfg = _cfg(**{"readout.reference_pixels": mode, "fpa.boundary": [1, 2, 1, 3],
                  "fpa.blind": [2, 1, 2, 2]})
    fr = model.simulate(cfg, [300.0, 310.0], seed=1)
    lay = ArrayLayout(24, 32, (1, 2, 1, 3), (2, 1, 2, 2))
    rows, cols = lay.shape
    # Count of the ring from the geometry alone (outer box minus inner box).
    if kind == BOUNDARY:
        expected = (24 + 3) * (32 + 4) - 24 * 32
    else:
        expected = rows * cols - (24 + 3) * (32 + 4)
    assert fr.blind_positions.shape == (expected, 2)
    assert fr.blind_codes.shape == (2, expected) and fr.blind_codes.dtype == np.uint16
    r, c = fr.blind_positions.T
    assert (lay.kind_map()[r, c] == kind).all()
    flat = r * cols + c
    assert (np.diff(flat) > 0).all()  # row-major, each once


def test_none_reads_no_reference_pixel():
    fr = model.simulate(_cfg(**{"readout.reference_pixels": "none"}), [300.0], seed=1)
    assert fr.blind_codes.shape == (1, 0) and fr.blind_positions.shape == (0, 2)


def test_skimming_pixels_read_against_their_own_mean_average_to_the_reset_level():
    """Row skimming takes each row's reference from its blind columns: read through the
    same integrator, those pixels average to v_reset exactly, so they carry no drift."""
    for Ts in (295.0, 305.0):
        cfg = _cfg(**{"readout.reference_pixels": "blind", "environment.T_substrate": Ts,
                      "fpa.tolerance": {"R_ref": 2e-3, "g": 2e-3, "C": 2e-3}})
        fr = model.simulate(cfg, [300.0], seed=3)
        lay = ArrayLayout(24, 32, (1, 1, 1, 1), (2, 2, 2, 2))
        r, c = fr.blind_positions.T
        in_blind_cols = np.isin(c, lay.blind_col_indices)
        codes = fr.blind_codes[0].astype(float)
        reset = cfg["readout"]["v_reset"] / _lsb(cfg)
        for row in np.unique(r):
            sel = in_blind_cols & (r == row)
            # Each code rounds its voltage: the mean is within half an LSB of v_reset.
            assert abs(codes[sel].mean() - reset) <= 0.5 + 1e-9
        assert codes.std() > 1.0  # the pixels differ (spread); only their mean is fixed


def _means(cfg, temps=(300.0,)):
    fr = model.simulate(cfg, list(temps), seed=2)
    return fr.codes.mean(axis=(1, 2)), fr.blind_codes.mean(axis=1)


def test_the_reference_ring_carries_the_fpa_drift_of_the_image():
    """Skimming pixels under an on-die shield at the substrate temperature: the image's
    offset drifts by many codes per kelvin of FPA temperature and the shielded boundary
    ring drifts with it, so subtracting the ring's change removes the drift."""
    a0, b0 = _means(_cfg())
    a1, b1 = _means(_cfg(**{"environment.T_substrate": 301.0}))
    drift = a1[0] - a0[0]
    assert abs(drift) > 100.0  # codes per kelvin
    assert abs((a1[0] - a0[0]) - (b1[0] - b0[0])) < 0.02 * abs(drift)


def test_with_the_skimming_shield_at_the_housing_the_ring_carries_nothing():
    over = {"fpa.skim_shield": "housing"}
    a0, b0 = _means(_cfg(**over))
    a1, b1 = _means(_cfg(**over, **{"environment.T_substrate": 301.0}))
    assert abs(b1[0] - b0[0]) < 1.0
    # and the skimming then already cancels the image's FPA drift (same shield, same pixel)
    assert abs(a1[0] - a0[0]) < 1.0


def test_housing_drift_of_image_and_ring_differ_by_the_scene_fraction():
    """A housing change reaches the ring over the whole hemisphere but an image pixel only
    outside its optical cone: the ratio of their drifts is 1 - tau sin^2(theta) <cos^4>
    (camera equation; sin(theta) = 1/(2N))."""
    cfg = _cfg()
    a0, b0 = _means(cfg)
    a1, b1 = _means(_cfg(**{"environment.T_cam": 300.5}))
    o = cfg["optics"]
    fr = model.simulate(cfg, [300.0], outputs=["cos4"])
    lay = ArrayLayout(24, 32, (1, 1, 1, 1), (2, 2, 2, 2))
    cos4 = fr.outputs["cos4"][lay.active_slice].mean()
    seen = o["transmission"] * cone_factor("f_number", f_number=o["f_number"]) * cos4
    ratio = (a1[0] - a0[0]) / (b1[0] - b0[0])
    assert ratio == pytest.approx(1.0 - seen, rel=0.02)


def test_skimming_shield_changes_nothing_when_housing_and_substrate_agree():
    """At T_cam = T_substrate the two shields radiate alike: the image is bit for bit the
    same (the default preset's frames at its default environment did not change)."""
    a = model.simulate(_cfg(**{"fpa.skim_shield": "housing"}), [280.0, 340.0], seed=5)
    b = model.simulate(_cfg(**{"fpa.skim_shield": "substrate"}), [280.0, 340.0], seed=5)
    np.testing.assert_array_equal(a.codes, b.codes)


def test_boundary_view_decides_whether_the_ring_sees_the_scene():
    cfg_h = _cfg(**{"fpa.boundary_view": "housing"})
    cfg_s = _cfg(**{"fpa.boundary_view": "scene"})
    _, bh = _means(cfg_h, (280.0, 340.0))
    _, bs = _means(cfg_s, (280.0, 340.0))
    assert abs(bh[1] - bh[0]) < 0.5  # shielded: blind to the scene
    assert bs[1] - bs[0] > 1000.0  # looking at it: follows the scene
    # the image itself does not depend on what the ring sees
    np.testing.assert_array_equal(model.simulate(cfg_h, [300.0], seed=1).codes,
                                  model.simulate(cfg_s, [300.0], seed=1).codes)


def test_reference_noise_has_the_image_statistics_and_its_own_stream():
    over = {"noise.enabled": True, "noise.johnson": False, "noise.readout_sigma": 1e-3}
    cfg = _cfg(**over)
    fr = model.simulate(cfg, [300.0] * 60, seed=7)
    lsb = _lsb(cfg)
    sigma = fr.blind_codes.astype(float).std(axis=0, ddof=1).mean()
    # white noise of 1e-3 V plus the ADC's uniform rounding error, in codes
    assert sigma == pytest.approx(np.sqrt((1e-3 / lsb) ** 2 + 1 / 12), rel=0.05)
    none = model.simulate(_cfg(**over, **{"readout.reference_pixels": "none"}), [300.0] * 60,
                          seed=7)
    np.testing.assert_array_equal(fr.codes, none.codes)


def test_column_skimming_reads_the_ring_against_its_columns():
    cfg = _cfg(**{"readout.skimming": "column", "readout.reference_pixels": "blind"})
    fr = model.simulate(cfg, [300.0], seed=4)
    lay = ArrayLayout(24, 32, (1, 1, 1, 1), (2, 2, 2, 2))
    r, c = fr.blind_positions.T
    reset = cfg["readout"]["v_reset"] / _lsb(cfg)
    codes = fr.blind_codes[0].astype(float)
    sel = np.isin(r, lay.blind_row_indices)
    for col in np.unique(c[sel]):
        assert abs(codes[sel & (c == col)].mean() - reset) <= 0.5 + 1e-9
