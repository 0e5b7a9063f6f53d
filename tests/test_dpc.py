"""dpc_core against a slow pure-Python reference, and its properties."""

from __future__ import annotations

from fractions import Fraction

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from irnuc.nuc_fixed import InputError, dpc_core, load_pipeline
from irnuc.nuc_fixed.dpc import uncorrectable

CFG = load_pipeline("minimal")  # 6-bit output, max 64 x 64


def good_neighbours(bad: list[list[bool]], r: int, c: int) -> list[tuple[int, int]]:
    h, w = len(bad), len(bad[0])
    return [(r + dr, c + dc) for dr in (-1, 0, 1) for dc in (-1, 0, 1)
            if (dr or dc) and 0 <= r + dr < h and 0 <= c + dc < w and not bad[r + dr][c + dc]]


def ref_dpc(y: list[list[int]], bad: list[list[bool]]) -> list[list[int]]:
    out = [row[:] for row in y]
    for r in range(len(y)):
        for c in range(len(y[0])):
            nb = good_neighbours(bad, r, c)
            if bad[r][c] and nb:
                mean = Fraction(sum(y[i][j] for i, j in nb), len(nb))
                out[r][c] = (mean + Fraction(1, 2)).__floor__()  # half up
    return out


@st.composite
def frames(draw, max_h: int = 10, max_w: int = 10):
    h = draw(st.integers(1, max_h))
    w = draw(st.integers(1, max_w))
    top = 2**CFG.out_bits - 1
    y = draw(st.lists(st.lists(st.integers(0, top), min_size=w, max_size=w),
                      min_size=h, max_size=h))
    density = draw(st.sampled_from([0.0, 0.1, 0.3, 0.6, 1.0]))
    seed = draw(st.integers(0, 2**32 - 1))
    bad = np.random.default_rng(seed).random((h, w)) < density
    # Whole flagged rows / columns, often.
    if draw(st.booleans()):
        bad[draw(st.integers(0, h - 1)), :] = True
    if draw(st.booleans()):
        bad[:, draw(st.integers(0, w - 1))] = True
    return np.array(y, dtype=np.int64), bad


@settings(max_examples=200, deadline=None)
@given(frames())
def test_matches_reference(case: tuple[np.ndarray, np.ndarray]) -> None:
    y, bad = case
    out = dpc_core(y, bad, CFG)
    assert out.tolist() == ref_dpc(y.tolist(), bad.tolist())


@settings(max_examples=150, deadline=None)
@given(frames())
def test_good_untouched_and_within_neighbour_range(case: tuple[np.ndarray, np.ndarray]) -> None:
    y, bad = case
    out = dpc_core(y, bad, CFG).astype(np.int64)
    assert np.array_equal(out[~bad], y[~bad])
    for r, c in np.argwhere(bad).tolist():
        nb = good_neighbours(bad.tolist(), r, c)
        if nb:
            vals = [int(y[i, j]) for i, j in nb]
            assert min(vals) <= out[r, c] <= max(vals)
        else:
            assert out[r, c] == y[r, c]


def _frame(h: int, w: int, seed: int = 0) -> np.ndarray:
    return np.random.default_rng(seed).integers(0, 2**CFG.out_bits, (h, w))


@pytest.mark.parametrize(
    "positions",
    [
        [(0, 0)], [(0, 6)], [(5, 0)], [(5, 6)],          # corners
        [(1, 3)], [(4, 3)], [(2, 1)], [(2, 5)],          # rows 1 and N-2, cols 1 and N-2
        [(0, 3)], [(5, 3)], [(2, 0)], [(2, 6)],          # edges
        [(2, 2), (2, 3)], [(2, 2), (3, 3)], [(1, 1), (1, 3), (3, 1), (3, 3)],  # clusters
        [(0, 0), (0, 1), (1, 0)],                         # corner cluster: one good neighbour
    ],
)
def test_borders_corners_and_clusters(positions: list[tuple[int, int]]) -> None:
    y = _frame(6, 7)
    bad = np.zeros((6, 7), dtype=bool)
    for p in positions:
        bad[p] = True
    out = dpc_core(y, bad, CFG)
    assert out.tolist() == ref_dpc(y.tolist(), bad.tolist())
    # A defect at a border must be corrected from in-frame pixels only: a uniform frame
    # with a wild defect comes back uniform.
    flat = np.full((6, 7), 20)
    flat[bad] = 63
    assert (dpc_core(flat, bad, CFG) == 20).all()


@pytest.mark.parametrize("axis", [0, 1])
@pytest.mark.parametrize("index", [0, 1, 3, 4, 5])
def test_whole_rows_and_columns(axis: int, index: int) -> None:
    y = _frame(6, 6, seed=index)
    bad = np.zeros((6, 6), dtype=bool)
    if axis == 0:
        bad[index, :] = True
    else:
        bad[:, index] = True
    assert dpc_core(y, bad, CFG).tolist() == ref_dpc(y.tolist(), bad.tolist())


@pytest.mark.parametrize("shape", [(1, 1), (1, 5), (5, 1), (1, 2), (2, 1)])
def test_degenerate_frames(shape: tuple[int, int]) -> None:
    y = _frame(*shape, seed=3)
    for seed in range(4):
        bad = np.random.default_rng(seed).random(shape) < 0.5
        assert dpc_core(y, bad, CFG).tolist() == ref_dpc(y.tolist(), bad.tolist())
    # 1x1: no neighbour at all, the pixel passes through and is reported uncorrectable.
    if shape == (1, 1):
        assert dpc_core(y, np.ones(shape, bool), CFG).tolist() == y.tolist()
        assert uncorrectable(np.ones(shape, bool)).all()


def test_uncorrectable_matches_reference() -> None:
    bad = np.random.default_rng(9).random((9, 11)) < 0.6
    want = [[bool(bad[r, c]) and not good_neighbours(bad.tolist(), r, c) for c in range(11)]
            for r in range(9)]
    assert uncorrectable(bad).tolist() == want


def test_stack_of_frames() -> None:
    y = np.stack([_frame(5, 8, s) for s in range(3)]).astype(np.uint16)
    bad = np.random.default_rng(1).random((5, 8)) < 0.3
    out = dpc_core(y, bad, CFG)
    assert out.shape == (3, 5, 8) and out.dtype == np.uint16
    for k in range(3):
        assert out[k].tolist() == ref_dpc(y[k].tolist(), bad.tolist())


def test_largest_sum_at_full_scale() -> None:
    """Eight full-scale neighbours: the widest adder-tree sum and division by 8."""
    cfg = load_pipeline("wide16")
    y = np.full((3, 3), 2**cfg.out_bits - 1)
    bad = np.zeros((3, 3), bool)
    bad[1, 1] = True
    y[1, 1] = 0
    assert dpc_core(y, bad, cfg)[1, 1] == 2**cfg.out_bits - 1


@pytest.mark.parametrize(
    ("y", "bad", "match"),
    [
        (np.zeros((65, 4)), np.zeros((65, 4), bool), "dtype float64"),
        (np.zeros((65, 4), int), np.zeros((65, 4), bool), r"65 x 4 .*1..64 rows"),
        (np.zeros((4, 65), int), np.zeros((4, 65), bool), r"1..64 columns"),
        (np.zeros((4, 4), int), np.zeros((4, 5), bool), r"bad has shape \(4, 5\)"),
        (np.full((4, 4), 64), np.zeros((4, 4), bool), r"y\[0, 0\] = 64 .*\[0, 63\]"),
        (np.zeros(4, int), np.zeros(4, bool), r"\(H, W\) or \(N, H, W\)"),
        (np.zeros((4, 4), int), np.full((4, 4), 2), r"bad\[0, 0\] = 2 .*\[0, 1\]"),
    ],
)
def test_bad_inputs(y: np.ndarray, bad: np.ndarray, match: str) -> None:
    with pytest.raises(InputError, match=match):
        dpc_core(y, bad, CFG)
