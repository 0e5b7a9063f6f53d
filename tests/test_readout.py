"""Skimming references taken from the right blind pixels, for any ring sizes."""

from __future__ import annotations

import numpy as np
import pytest

from irnuc import model
from irnuc.model.core.bolometer import STATUS_OK, STATUS_RUNAWAY
from irnuc.model.fpa import ArrayLayout
from irnuc.model.readout import integrate, skim_column, skim_none, skim_row


@pytest.fixture
def layout():
    # Asymmetric rings: the reference implementation's skimming index was off by the ring width.
    return ArrayLayout(4, 5, boundary=(1, 2, 0, 1), blind=(2, 1, 3, 1))


def test_row_reference_is_the_mean_of_the_blind_columns_of_the_same_row(layout):
    rng = np.random.default_rng(0)
    v = rng.normal(size=(2, layout.rows, layout.cols))
    status = np.zeros(v.shape, np.uint8)
    ref = skim_row(v, status, layout, 0.0)
    assert ref.shape == (2, 4, 1)
    for n in range(2):
        for r in range(4):
            full_row = r + 2 + 1  # blind top + boundary top
            blind = [v[n, full_row, c] for c in range(layout.cols) if c < 3 or c >= layout.cols - 1]
            assert ref[n, r, 0] == pytest.approx(np.mean(blind), rel=1e-15)


def test_column_reference_is_the_mean_of_the_blind_rows_of_the_same_column(layout):
    rng = np.random.default_rng(1)
    v = rng.normal(size=(1, layout.rows, layout.cols))
    ref = skim_column(v, np.zeros(v.shape, np.uint8), layout, 0.0)
    assert ref.shape == (1, 1, 5)
    for c in range(5):
        full_col = c + 3 + 0  # blind left + boundary left
        blind = [v[0, r, full_col] for r in range(layout.rows) if r < 2 or r >= layout.rows - 1]
        assert ref[0, 0, c] == pytest.approx(np.mean(blind), rel=1e-15)


def test_failed_blind_pixels_are_left_out(layout):
    v = np.ones((1, layout.rows, layout.cols))
    status = np.full(v.shape, STATUS_OK, np.uint8)
    row = 2 + 1
    v[0, row, 0] = 1e6
    status[0, row, 0] = STATUS_RUNAWAY
    ref = skim_row(v, status, layout, 0.0)
    assert ref[0, 0, 0] == 1.0
    status[0, row, :] = STATUS_RUNAWAY  # a row with no usable blind pixel: the fallback
    assert skim_row(v, status, layout, 0.75)[0, 0, 0] == 0.75


def test_none_and_integrator():
    ref = skim_none(np.zeros((3, 2, 2)), None, None, 1.25)
    assert ref.shape == (3, 1, 1) and (ref == 1.25).all()
    assert integrate(np.array([1.0]), np.array([1.5]), 40.0, 0.6)[0] == pytest.approx(20.6)


@pytest.mark.parametrize("tol", [0.1, 0.5, 1.0])
def test_large_tolerances_give_valid_codes(tol):
    # The reference implementation's normal spread gave ADC codes of -2 million at 0.1.
    cfg = model.load_preset("default", {"fpa.active_rows": 16, "fpa.active_cols": 16,
                                        "fpa.defects": {},
                                        "fpa.tolerance": {"R_ref": tol, "g": tol, "C": tol}})
    fr = model.simulate(cfg, [300.0], outputs=["codes", "params"])
    assert fr.codes.dtype == np.uint16 and fr.codes.max() <= 2**14 - 1
    assert all((p > 0).all() for p in fr.outputs["params"].values())
