"""ADC: codes from voltages computed by hand, both clamps, dtype, non-finite input."""

from __future__ import annotations

import numpy as np
import pytest

from irnuc.model.adc import NonFiniteVoltageError, adc_convert
from irnuc.model.validate import ConfigError


def test_codes_by_hand():
    lsb = 3.3 / 2**14
    v = np.array([-1.0, 0.0, 0.49 * lsb, 0.51 * lsb, 100.5 * lsb, 3.3 - 0.6 * lsb, 3.3, 10.0])
    got = adc_convert(v, 14, 0.0, 3.3)
    assert got.dtype == np.uint16
    assert got.tolist() == [0, 0, 0, 1, 101, 16383, 16383, 16383]


def test_floor_rounding():
    lsb = 1.0 / 2**8
    v = np.array([0.99 * lsb, 1.0 * lsb, 7.5 * lsb])
    assert adc_convert(v, 8, 0.0, 1.0, "floor").tolist() == [0, 1, 7]


def test_offset_range_and_wide_dtype():
    got = adc_convert(np.array([-1.0, 0.0, 1.0]), 20, -1.0, 1.0)
    assert got.dtype == np.uint32
    assert got.tolist() == [0, 2**19, 2**20 - 1]


@pytest.mark.parametrize("bad", [np.nan, np.inf, -np.inf])
def test_non_finite_voltage_is_an_error(bad):
    with pytest.raises(NonFiniteVoltageError, match="non-finite"):
        adc_convert(np.array([[0.1, bad]]), 14, 0.0, 3.3)


@pytest.mark.parametrize(("args", "field"), [((0, 0.0, 1.0), "adc.bits"), ((25, 0.0, 1.0), "adc.bits"),
                                            ((8, 1.0, 1.0), "adc.v_low")])
def test_bad_settings(args, field):
    with pytest.raises(ConfigError, match=field.replace(".", r"\.")):
        adc_convert(np.zeros(3), *args)
