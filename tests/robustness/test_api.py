"""The API table (``api_cases.py``)."""

from __future__ import annotations

import numpy as np
import pytest

from robustness.api_cases import API_CASES, BYTE_ORDER_CASES, ApiCase, swap_byte_order


@pytest.mark.parametrize("c", [pytest.param(c, id=c.id) for c in API_CASES])
def test_api_case(c: ApiCase) -> None:
    with pytest.raises(ValueError) as info:
        c.call()
    msg = str(info.value)
    assert "\n" not in msg
    for name in c.names:
        assert name in msg, f"{name!r} not named in: {msg}"


@pytest.mark.parametrize("name", sorted(BYTE_ORDER_CASES))
@pytest.mark.parametrize("layout", ["other byte order", "strided view"])
def test_api_accepts_any_byte_order(name: str, layout: str) -> None:
    call = BYTE_ORDER_CASES[name]
    native = call(lambda a: a)
    if layout == "other byte order":
        changed = call(swap_byte_order)
    else:  # every other element of a twice-as-large array: not contiguous
        changed = call(lambda a: np.repeat(a, 2, axis=-1)[..., ::2])
    np.testing.assert_array_equal(changed, native)
    assert changed.dtype == native.dtype
