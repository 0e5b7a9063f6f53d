"""nuc_dpc_top (fused, from coefficient words) against a pure-Python reference pipeline."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from irnuc.nuc_fixed import (
    InputError,
    dpc_core,
    load_pipeline,
    nuc_core,
    nuc_dpc_top,
    pack_words,
    pipeline_names,
)


def ref_nuc(x: int, g: int, o: int, cfg) -> int:
    """Integer-only reference: y = round((x*g*2^Of + o*2^Gf) / 2^(Gf+Of)) via divmod."""
    num = x * g * 2**cfg.offset_frac_bits + o * 2**cfg.gain_frac_bits
    den = 2 ** (cfg.gain_frac_bits + cfg.offset_frac_bits)
    q, rem = divmod(num, den)  # floor division, 0 <= rem < den
    if cfg.rounding == "half_up" and 2 * rem >= den:
        q += 1
    elif cfg.rounding == "half_even" and (2 * rem > den or (2 * rem == den and q % 2 == 1)):
        q += 1
    if cfg.overflow == "wrap":
        return q % 2**cfg.out_bits
    return min(max(q, 0), 2**cfg.out_bits - 1)


def ref_pipeline(raw: np.ndarray, g: np.ndarray, o: np.ndarray, bad: np.ndarray, cfg) -> list:
    h, w = g.shape
    y = [[ref_nuc(int(raw[r, c]), int(g[r, c]), int(o[r, c]), cfg) for c in range(w)]
         for r in range(h)]
    out = [row[:] for row in y]
    for r in range(h):
        for c in range(w):
            if not bad[r, c]:
                continue
            vals = [y[r + dr][c + dc] for dr in (-1, 0, 1) for dc in (-1, 0, 1)
                    if (dr or dc) and 0 <= r + dr < h and 0 <= c + dc < w
                    and not bad[r + dr, c + dc]]
            if vals:
                n = len(vals)
                out[r][c] = (2 * sum(vals) + n) // (2 * n)
    return out


def _coeffs(cfg, h: int, w: int, seed: int):
    rng = np.random.default_rng(seed)
    g = rng.integers(0, 2**cfg.gain_bits, (h, w))
    ow = cfg.offset_bits
    o = rng.integers(-(2 ** (ow - 1)), 2 ** (ow - 1), (h, w))
    bad = rng.random((h, w)) < rng.choice([0.0, 0.1, 0.5, 1.0])
    raw = rng.integers(0, 2**cfg.adc_bits, (2, h, w))
    return raw, g, o, bad


@pytest.mark.parametrize("name", pipeline_names())
@pytest.mark.parametrize("overflow", ["saturate", "wrap"])
@settings(max_examples=40, deadline=None)
@given(h=st.integers(1, 7), w=st.integers(1, 7), seed=st.integers(0, 2**32 - 1))
def test_top_matches_reference(name: str, overflow: str, h: int, w: int, seed: int) -> None:
    cfg = load_pipeline(name).replace(overflow=overflow)
    raw, g, o, bad = _coeffs(cfg, h, w, seed)
    words = pack_words(g, o, bad, cfg)
    out = nuc_dpc_top(raw, words, cfg)
    for k in range(raw.shape[0]):
        assert out[k].tolist() == ref_pipeline(raw[k], g, o, bad, cfg)
    # The fused pass equals the two RTL modules chained.
    assert np.array_equal(out, dpc_core(nuc_core(raw, g, o, cfg), bad, cfg))


def test_top_single_frame_and_dtypes() -> None:
    cfg = load_pipeline("typical14")
    raw, g, o, bad = _coeffs(cfg, 16, 20, 7)
    words = pack_words(g, o, bad, cfg)
    out = nuc_dpc_top(raw[0].astype(np.uint16), words, cfg)
    assert out.shape == (16, 20) and out.dtype == np.uint16
    assert out.tolist() == ref_pipeline(raw[0], g, o, bad, cfg)


@pytest.mark.parametrize(
    ("raw", "words", "match"),
    [
        (np.zeros((4, 4), np.int64), np.zeros((4, 5), np.uint64), r"words has shape \(4, 5\)"),
        (np.full((4, 4), 2**14), np.zeros((4, 4), np.uint64), r"raw\[0, 0\] = 16384"),
        (np.zeros((4, 4), np.int64), np.full((4, 4), 2**33, np.uint64),
         r"words\[0, 0\] = 8589934592 .*\[0, 8589934591\]"),
        (np.zeros((4, 4)), np.zeros((4, 4), np.uint64), "raw has dtype float64"),
        (np.zeros((1025, 1), np.int64), np.zeros((1025, 1), np.uint64), "1..1024 rows"),
    ],
)
def test_bad_inputs(raw: np.ndarray, words: np.ndarray, match: str) -> None:
    with pytest.raises(InputError, match=match):
        nuc_dpc_top(raw, words, "typical14")
