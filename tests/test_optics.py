"""Optics: cos^4 falloff against the angle formula, camera-equation cone factors."""

from __future__ import annotations

import math

import numpy as np
import pytest

from irnuc.model import ConfigError, cone_factor, cos4_map
from irnuc.model.fpa import ArrayLayout
from irnuc.model.optics import centre_pixel_power, focal_length_from_fov


def angle_reference(rows, cols, pitch, f, centre):
    """cos^4 of the angle at the exit pupil, computed with trigonometry."""
    y = (np.arange(rows)[:, None] - centre[0]) * pitch
    x = (np.arange(cols)[None, :] - centre[1]) * pitch
    beta = np.arctan(np.hypot(y, x) / f)
    return np.cos(beta) ** 4


@pytest.mark.parametrize(("rows", "cols"), [(1, 1), (1, 7), (5, 5), (6, 8), (7, 4), (480, 640),
                                            (481, 641)])
def test_cos4_matches_angle_formula(rows, cols):
    pitch, f = 17e-6, 5e-3
    got = cos4_map(rows, cols, pitch, f)
    ref = angle_reference(rows, cols, pitch, f, ((rows - 1) / 2, (cols - 1) / 2))
    np.testing.assert_allclose(got, ref, rtol=1e-13)


@pytest.mark.parametrize(("rows", "cols"), [(5, 7), (6, 8), (5, 8), (6, 7)])
def test_cos4_symmetric_and_peak_only_on_axis(rows, cols):
    got = cos4_map(rows, cols, 17e-6, 2e-3)
    np.testing.assert_array_equal(got, got[::-1, :])
    np.testing.assert_array_equal(got, got[:, ::-1])
    # Only a pixel exactly on the axis reads 1: the reference left a whole row at 1 for odd sizes.
    ones = np.argwhere(got == 1.0)
    if rows % 2 and cols % 2:
        assert ones.tolist() == [[rows // 2, cols // 2]]
    else:
        assert ones.size == 0
    assert (got < 1.0).sum() == got.size - len(ones)


def test_cos4_centred_on_active_area_with_asymmetric_rings():
    lay = ArrayLayout(6, 9, boundary=(0, 2, 1, 3), blind=(3, 1, 0, 2))
    full = cos4_map(lay.rows, lay.cols, 17e-6, 1e-3, lay.optical_centre)
    act = full[lay.active_slice]
    np.testing.assert_array_equal(act, act[::-1, ::-1])


def test_cone_factors():
    assert cone_factor("f_number", f_number=1.0) == pytest.approx(0.25, rel=1e-15)
    assert cone_factor("f_number", f_number=2.0) == pytest.approx(1 / 16, rel=1e-15)
    # The paper's eq. 12 as printed, FOV pi/6: sin^2(pi/12).
    assert cone_factor("paper_fov", fov=math.pi / 6) == pytest.approx(
        math.sin(math.pi / 12) ** 2, rel=1e-15)


def test_focal_length_inverts_fov():
    f = focal_length_from_fov(0.7, 10.88e-3)
    assert 2 * math.atan(10.88e-3 / (2 * f)) == pytest.approx(0.7, rel=1e-14)


def test_centre_pixel_power_camera_equation():
    p = centre_pixel_power(10.0, 2e-10, 0.25, 0.9)
    assert p == pytest.approx(math.pi * 0.9 * 10.0 * 2e-10 * 0.25, rel=1e-15)


@pytest.mark.parametrize(
    ("call", "field"),
    [
        (lambda: cone_factor("f_number", f_number=0.3), "optics.f_number"),
        (lambda: cone_factor("paper_fov", fov=4.0), "optics.fov"),
        (lambda: cone_factor("pinhole"), "optics.cone_method"),
        (lambda: cos4_map(0, 5, 17e-6, 1e-3), "rows"),
        (lambda: cos4_map(5, 5, -1.0, 1e-3), "fpa.pitch"),
        (lambda: cos4_map(5, 5, 17e-6, 0.0), "optics.focal_length"),
    ],
)
def test_bad_input_names_the_field(call, field):
    with pytest.raises(ConfigError, match=field.replace(".", r"\.")):
        call()
