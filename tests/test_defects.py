"""Tests of model.defects: defect injection, ground truth and application."""

from __future__ import annotations

import re
import tomllib

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy import ndimage

from irnuc.model import defects as dm
from irnuc.model.defects import (
    KIND_NAMES,
    DefectKind,
    DefectMap,
    DefectPattern,
    DefectSpec,
    apply_voltage_defects,
    inject_defects,
    noisy_sigma,
)
from irnuc.model.validate import ConfigError

K = DefectKind
P = DefectPattern
EIGHT = np.ones((3, 3), dtype=int)  # 8-connectivity structure for ndimage.label

LEVEL_KINDS = {K.STUCK_VALUE, K.HOT, K.COLD, K.NOISY}
RESP_KINDS = {K.LOW_RESP, K.HIGH_RESP}


def check_consistent(m: DefectMap, spec: DefectSpec) -> None:
    """Invariants every map must satisfy, checked pixel-kind by pixel-kind."""
    assert m.kind.dtype == np.uint8 and m.pattern.dtype == np.uint8
    assert m.level.dtype == np.float64 and m.resp.dtype == np.float64
    np.testing.assert_array_equal(m.kind == K.GOOD, m.pattern == P.NONE)
    np.testing.assert_array_equal(m.mask, m.kind != K.GOOD)
    for k in K:
        sel = m.kind == k
        if k not in LEVEL_KINDS:
            assert np.all(m.level[sel] == 0.0)
        if k not in RESP_KINDS:
            assert np.all(m.resp[sel] == 1.0)
    assert np.all(m.level[m.kind == K.HOT] > 0)
    assert np.all(m.level[m.kind == K.COLD] < 0)
    assert np.all((m.resp[m.kind == K.LOW_RESP] > 0) & (m.resp[m.kind == K.LOW_RESP] < 1))
    assert np.all(m.resp[m.kind == K.HIGH_RESP] > 1)
    counts = m.counts()
    assert set(counts) == set(KIND_NAMES)
    for name, n in counts.items():
        assert n == int(np.sum(m.kind == K[name.upper()]))


# ---------------------------------------------------------------------------------------
# Isolated rates
# ---------------------------------------------------------------------------------------


@pytest.mark.parametrize("kind", KIND_NAMES)
def test_exact_count_each_kind(kind):
    h, w = 37, 41
    rate = 0.0123
    spec = DefectSpec(rates={kind: rate})
    m = inject_defects((h, w), spec, seed=4)
    expected = round(rate * h * w)  # 18.66... -> 19
    assert m.counts()[kind] == expected
    assert sum(m.counts().values()) == expected
    assert np.all(m.pattern[m.mask] == P.ISOLATED)
    check_consistent(m, spec)


def test_all_kinds_together_exact_and_defaults():
    h, w = 50, 60  # 3000 pixels
    rates = {name: (i + 1) / 300 for i, name in enumerate(KIND_NAMES)}  # 10, 20, ... 90 px
    spec = DefectSpec(rates=rates)
    m = inject_defects((h, w), spec, seed=1)
    for i, name in enumerate(KIND_NAMES):
        assert m.counts()[name] == 10 * (i + 1)
    assert np.all(m.level[m.kind == K.STUCK_VALUE] == 0.5)
    assert np.all(m.level[m.kind == K.HOT] == 0.05)
    assert np.all(m.level[m.kind == K.COLD] == -0.05)
    assert np.all(m.level[m.kind == K.NOISY] == 0.02)
    assert np.all(m.resp[m.kind == K.LOW_RESP] == 0.2)
    assert np.all(m.resp[m.kind == K.HIGH_RESP] == 3.0)
    check_consistent(m, spec)


def test_rates_sum_to_one_fills_frame():
    spec = DefectSpec(rates={"dead": 0.25, "hot": 0.25, "noisy": 0.5})
    m = inject_defects((8, 8), spec, seed=0)
    assert m.counts()["dead"] == 16 and m.counts()["hot"] == 16 and m.counts()["noisy"] == 32
    assert m.mask.all()


def test_isolated_positions_spread_uniformly():
    # Each position must be reachable: over many seeds, a 4x4 frame with 1 dead pixel
    # hits every pixel roughly equally (chi-square, loose bound).
    hits = np.zeros(16)
    n = 800
    for seed in range(n):
        m = inject_defects((4, 4), DefectSpec(rates={"dead": 1 / 16}), seed)
        hits += m.mask.ravel()
    assert hits.sum() == n
    chi2 = ((hits - n / 16) ** 2 / (n / 16)).sum()
    assert chi2 < 45  # 15 dof; P(chi2 > 45) ~ 1e-4


# ---------------------------------------------------------------------------------------
# Clusters
# ---------------------------------------------------------------------------------------


@pytest.mark.parametrize("size", [(1, 1), (2, 5), (7, 7), (20, 40)])
def test_single_cluster_connected_and_sized(size):
    seen = set()
    for seed in range(40):
        spec = DefectSpec(clusters=1, cluster_size=size)
        m = inject_defects((30, 30), spec, seed)
        n = int(m.mask.sum())
        assert size[0] <= n <= size[1]
        seen.add(n)
        _labels, ncomp = ndimage.label(m.mask, structure=EIGHT)
        assert ncomp == 1
        assert np.all(m.pattern[m.mask] == P.CLUSTER)
        assert np.all(m.kind[m.mask] == K.DEAD)
    # Both ends of the size range are drawn.
    assert size[0] in seen and size[1] in seen


def test_many_clusters_kinds_and_total():
    spec = DefectSpec(clusters=60, cluster_size=(3, 6), cluster_kinds=("hot", "stuck_low"))
    m = inject_defects((64, 80), spec, seed=9)
    n = int(m.mask.sum())
    assert 60 * 3 <= n <= 60 * 6
    assert set(np.unique(m.kind[m.mask])) == {K.HOT, K.STUCK_LOW}
    labels, _ncomp = ndimage.label(m.mask, structure=EIGHT)
    sizes = np.bincount(labels.ravel())[1:]
    assert np.all(sizes >= 3)  # touching clusters may merge, never shrink
    check_consistent(m, spec)


def test_cluster_fills_tiny_frame_and_stays_inside():
    m = inject_defects((3, 3), DefectSpec(clusters=1, cluster_size=(9, 9)), seed=2)
    assert m.mask.all()
    # 1xN: a cluster is a run of consecutive pixels.
    for seed in range(20):
        m = inject_defects((1, 12), DefectSpec(clusters=1, cluster_size=(4, 4)), seed)
        idx = np.flatnonzero(m.mask[0])
        assert idx.size == 4 and idx[-1] - idx[0] == 3


def test_cluster_boxed_in_stops_smaller():
    # Columns 1 and 3 dead: a cluster seeded in column 0, 2 or 4 can only grow vertically.
    spec = DefectSpec(clusters=1, cluster_size=(10, 10), cols=(1, 3))
    m = inject_defects((2, 5), spec, seed=3)
    cl = m.pattern == P.CLUSTER
    assert 1 <= cl.sum() <= 2
    assert np.all(m.pattern[:, [1, 3]] == P.COLUMN)


# ---------------------------------------------------------------------------------------
# Lines and listed pixels, precedence
# ---------------------------------------------------------------------------------------


def test_rows_and_cols():
    spec = DefectSpec(rows=(0, 5), cols=(3,), line_kind="stuck_high")
    m = inject_defects((6, 7), spec, seed=0)
    expected = np.zeros((6, 7), bool)
    expected[[0, 5], :] = True
    expected[:, 3] = True
    np.testing.assert_array_equal(m.mask, expected)
    assert m.counts()["stuck_high"] == 2 * 7 + 6 - 2
    assert np.all(m.pattern[[0, 5], :] == P.ROW)  # rows take the crossings
    assert np.all(m.pattern[1:5, 3] == P.COLUMN)
    check_consistent(m, spec)


def test_listed_values_and_defaults():
    listed = (
        {"row": 0, "col": 0, "kind": "stuck_value", "value": 0.7},
        {"row": 0, "col": 1, "kind": "stuck_value"},
        {"row": 1, "col": 0, "kind": "hot", "value": 0.1},
        {"row": 1, "col": 1, "kind": "cold", "value": 0.25},
        {"row": 2, "col": 0, "kind": "low_resp", "value": 0.5},
        {"row": 2, "col": 1, "kind": "high_resp", "value": 10.0},
        {"row": 3, "col": 0, "kind": "noisy", "value": 0.03},
        {"row": 3, "col": 1, "kind": "dead"},
        {"row": 3, "col": 2, "kind": "cold"},
    )
    spec = DefectSpec(listed=listed, stuck_value=0.9, offset=0.2)
    m = inject_defects((4, 3), spec, seed=0)
    assert m.kind[0, 0] == K.STUCK_VALUE and m.level[0, 0] == 0.7
    assert m.kind[0, 1] == K.STUCK_VALUE and m.level[0, 1] == 0.9
    assert m.kind[1, 0] == K.HOT and m.level[1, 0] == 0.1
    assert m.kind[1, 1] == K.COLD and m.level[1, 1] == -0.25
    assert m.kind[2, 0] == K.LOW_RESP and m.resp[2, 0] == 0.5
    assert m.kind[2, 1] == K.HIGH_RESP and m.resp[2, 1] == 10.0
    assert m.kind[3, 0] == K.NOISY and m.level[3, 0] == 0.03
    assert m.kind[3, 1] == K.DEAD
    assert m.kind[3, 2] == K.COLD and m.level[3, 2] == -0.2
    assert int(m.mask.sum()) == len(listed)
    assert np.all(m.pattern[m.mask] == P.LISTED)
    check_consistent(m, spec)


def test_precedence():
    # listed > rows/cols > clusters > isolated.
    spec = DefectSpec(
        listed=({"row": 2, "col": 4, "kind": "hot"},),
        rows=(2,),
        cols=(7,),
        line_kind="dead",
        clusters=10,
        cluster_size=(3, 5),
        cluster_kinds=("stuck_low",),
        rates={"noisy": 1.0},  # more than what is left: fills every remaining pixel
    )
    m = inject_defects((12, 16), spec, seed=6)
    assert m.kind[2, 4] == K.HOT and m.pattern[2, 4] == P.LISTED
    row = m.kind[2, :].copy()
    row[4] = K.DEAD
    assert np.all(row == K.DEAD)
    col = np.delete(m.kind[:, 7], 2)
    assert np.all(col == K.DEAD)
    cl = m.pattern == P.CLUSTER
    assert 30 <= cl.sum() <= 50
    assert np.all(m.kind[cl] == K.STUCK_LOW)
    assert not cl[2, :].any() and not cl[:, 7].any()
    iso = m.pattern == P.ISOLATED
    assert np.all(m.kind[iso] == K.NOISY)
    assert m.mask.all()  # isolated took every pixel left
    check_consistent(m, spec)


def test_stages_use_separate_streams():
    # Adding isolated rates does not move the clusters (drawn before, on their own stream).
    a = inject_defects((40, 40), DefectSpec(clusters=5), seed=8)
    b = inject_defects((40, 40), DefectSpec(clusters=5, rates={"hot": 0.05}), seed=8)
    np.testing.assert_array_equal(a.pattern == P.CLUSTER, b.pattern == P.CLUSTER)
    assert b.counts()["hot"] == 80


# ---------------------------------------------------------------------------------------
# Reproducibility, empty spec, sizes
# ---------------------------------------------------------------------------------------

FULL_SPEC = DefectSpec(
    rates={"dead": 0.01, "hot": 0.01, "noisy": 0.005, "low_resp": 0.002},
    clusters=8,
    cluster_kinds=("dead", "stuck_high", "cold"),
    rows=(3,),
    cols=(10,),
    listed=({"row": 5, "col": 5, "kind": "stuck_value", "value": 0.3},),
)


def test_reproducible():
    a = inject_defects((60, 80), FULL_SPEC, seed=123)
    b = inject_defects((60, 80), FULL_SPEC, seed=123)
    for name in ("kind", "pattern", "level", "resp"):
        assert getattr(a, name).tobytes() == getattr(b, name).tobytes()
    c = inject_defects((60, 80), FULL_SPEC, seed=124)
    assert not np.array_equal(a.kind, c.kind)
    check_consistent(a, FULL_SPEC)


def test_empty_spec_all_good_without_draws(monkeypatch):
    def no_stream(*_args, **_kwargs):
        raise AssertionError("a random stream was created")

    monkeypatch.setattr(dm, "_stream", no_stream)
    for spec in (DefectSpec(), DefectSpec(rates={"dead": 0.0, "hot": 0.0})):
        assert spec.is_empty
        m = inject_defects((5, 7), spec, seed=0)
        assert not m.mask.any()
        assert np.all(m.resp == 1.0) and np.all(m.level == 0.0)
        assert sum(m.counts().values()) == 0
    # Lines and listed pixels are deterministic: no draws either.
    m = inject_defects(
        (5, 7), DefectSpec(rows=(1,), listed=({"row": 0, "col": 0, "kind": "dead"},)), 0
    )
    assert m.mask.sum() == 8


@pytest.mark.parametrize(
    "spec",
    [
        DefectSpec(rates={"dead": 1.0}),
        DefectSpec(clusters=1, cluster_size=(1, 1)),
        DefectSpec(rows=(0,), cols=(0,)),
        DefectSpec(listed=({"row": 0, "col": 0, "kind": "noisy"},)),
    ],
)
def test_one_by_one(spec):
    m = inject_defects((1, 1), spec, seed=0)
    assert m.mask.all()
    check_consistent(m, spec)


def test_one_by_n():
    spec = DefectSpec(rates={"hot": 0.25}, rows=(0,), line_kind="cold")
    m = inject_defects((1, 16), spec, seed=0)
    assert np.all(m.kind == K.COLD)  # the row takes precedence
    m = inject_defects((1, 16), DefectSpec(rates={"hot": 0.25}, cols=(15,)), seed=0)
    assert m.counts()["hot"] == 4 and m.counts()["dead"] == 1
    m = inject_defects((16, 1), DefectSpec(rates={"hot": 0.25}, rows=(15,)), seed=0)
    assert m.counts()["hot"] == 4 and m.counts()["dead"] == 1


def test_large_frame():
    # 4096 x 4096: must run without building per-pixel index lists for every stage.
    spec = DefectSpec(rates={"dead": 0.001, "hot": 0.001}, clusters=100, rows=(7,), cols=(4000,))
    m = inject_defects((4096, 4096), spec, seed=1)
    n = 4096 * 4096
    assert m.counts()["hot"] == round(0.001 * n)
    assert m.kind.shape == (4096, 4096)


@settings(max_examples=40, deadline=None)
@given(
    h=st.integers(1, 12),
    w=st.integers(1, 12),
    rates=st.dictionaries(st.sampled_from(KIND_NAMES), st.floats(0, 0.1), max_size=4),
    clusters=st.integers(0, 3),
    seed=st.integers(0, 2**32),
)
def test_property_counts_and_invariants(h, w, rates, clusters, seed):
    spec = DefectSpec(rates=rates, clusters=clusters, cluster_size=(1, 3))
    m = inject_defects((h, w), spec, seed)
    check_consistent(m, spec)
    iso = m.pattern == P.ISOLATED
    for name, r in rates.items():
        n = int(np.sum(iso & (m.kind == K[name.upper()])))
        free = h * w - int(np.sum(m.pattern == P.CLUSTER))
        want = round(r * h * w)
        # Exact unless the frame ran out of good pixels.
        assert n == want or (n < want and iso.sum() == free)


# ---------------------------------------------------------------------------------------
# Application to voltages
# ---------------------------------------------------------------------------------------


def hand_map():
    """A 3x4 map with every kind, built by hand."""
    kinds = np.array(
        [
            [K.GOOD, K.DEAD, K.STUCK_LOW, K.STUCK_HIGH],
            [K.STUCK_VALUE, K.HOT, K.COLD, K.LOW_RESP],
            [K.HIGH_RESP, K.NOISY, K.GOOD, K.STUCK_VALUE],
        ],
        dtype=np.uint8,
    )
    level = np.zeros((3, 4))
    level[1, 0] = 0.7
    level[1, 1] = 0.1
    level[1, 2] = -0.05
    level[2, 1] = 0.02
    level[2, 3] = 0.0
    resp = np.ones((3, 4))
    resp[1, 3] = 0.2
    resp[2, 0] = 3.0
    pattern = np.where(kinds == K.GOOD, P.NONE, P.LISTED).astype(np.uint8)
    return DefectMap(kinds, pattern, level, resp)


@pytest.mark.parametrize("batch", [(), (2,), (2, 3)])
def test_apply_voltage_defects_by_hand(batch):
    m = hand_map()
    v_low, v_high, v_reset = 0.5, 2.5, 1.25
    rng = np.random.default_rng(0)
    v = rng.uniform(0.0, 3.0, size=(*batch, 3, 4))
    v_in = v.copy()
    out = apply_voltage_defects(v, m, v_low, v_high, v_reset)
    np.testing.assert_array_equal(v, v_in)  # input untouched
    assert out.shape == v.shape and out.dtype == np.float64
    for idx in np.ndindex(*batch):
        f, o = v[idx], out[idx]
        # Hand computation, pixel by pixel.
        assert o[0, 0] == f[0, 0]
        assert o[0, 1] == 1.25
        assert o[0, 2] == 0.5
        assert o[0, 3] == 2.5
        assert o[1, 0] == pytest.approx(0.5 + 0.7 * 2.0, abs=1e-15)
        assert o[1, 1] == pytest.approx(f[1, 1] + 0.2, abs=1e-15)
        assert o[1, 2] == pytest.approx(f[1, 2] - 0.1, abs=1e-15)
        assert o[1, 3] == f[1, 3]  # responsivity acts upstream
        assert o[2, 0] == f[2, 0]
        assert o[2, 1] == f[2, 1]  # noise acts in the noise stage
        assert o[2, 2] == f[2, 2]
        assert o[2, 3] == 0.5  # stuck at level 0 = low rail


def test_apply_does_not_clip():
    m = hand_map()
    out = apply_voltage_defects(np.full((3, 4), 2.45), m, 0.5, 2.5, 1.0)
    assert out[1, 1] == pytest.approx(2.65)  # HOT pushed above the rail, left unclipped


def test_noisy_sigma():
    m = hand_map()
    s = noisy_sigma(m, 0.5, 2.5)
    expected = np.zeros((3, 4))
    expected[2, 1] = 0.02 * 2.0
    np.testing.assert_allclose(s, expected, rtol=0, atol=1e-18)
    good = DefectMap(*(np.zeros((2, 2), np.uint8),) * 2, np.zeros((2, 2)), np.ones((2, 2)))
    assert noisy_sigma(good, 0.0, 1.0) is None


def test_apply_validation():
    m = hand_map()
    with pytest.raises(ConfigError, match=r"v has shape \(4, 3\)"):
        apply_voltage_defects(np.zeros((4, 3)), m, 0.0, 1.0, 0.5)
    with pytest.raises(ConfigError, match=r"^v_high = 0\.2 V is outside"):
        apply_voltage_defects(np.zeros((3, 4)), m, 0.5, 0.2, 0.5)
    with pytest.raises(ConfigError, match=r"^v_reset"):
        apply_voltage_defects(np.zeros((3, 4)), m, 0.0, 1.0, float("nan"))
    with pytest.raises(ConfigError, match=r"^v_high"):
        noisy_sigma(m, 1.0, 1.0)


# ---------------------------------------------------------------------------------------
# Validation
# ---------------------------------------------------------------------------------------


def test_from_dict_toml():
    text = """
    [fpa.defects]
    rates = { dead = 0.001, hot = 0.002 }
    clusters = 3
    cluster_size = [2, 4]
    cluster_kinds = ["dead", "stuck_low"]
    rows = [10]
    cols = [20, 21]
    line_kind = "stuck_high"
    listed = [{ row = 1, col = 2, kind = "stuck_value", value = 0.7 }]
    offset = 0.1
    """
    d = tomllib.loads(text)["fpa"]["defects"]
    spec = DefectSpec.from_dict(d)
    assert spec.cluster_size == (2, 4) and spec.cols == (20, 21)
    assert spec.cluster_kinds == ("dead", "stuck_low")
    assert spec.listed[0]["value"] == 0.7
    assert spec == DefectSpec(**{**d, "cluster_size": (2, 4)})


@pytest.mark.parametrize(
    ("d", "pattern"),
    [
        ({"bogus": 1}, r"^fpa\.defects\.bogus is not a known key"),
        ({"rates": {"dead": -0.1}}, r"^fpa\.defects\.rates\.dead = -0\.1 .*\[0, 1\]"),
        ({"rates": {"dead": 1.5}}, r"^fpa\.defects\.rates\.dead = 1\.5"),
        ({"rates": {"broken": 0.1}}, r"^fpa\.defects\.rates\.broken = 'broken' is not one of"),
        ({"rates": {"dead": 0.6, "hot": 0.5}}, r"^fpa\.defects\.rates: the rates sum to 1\.1"),
        ({"clusters": -1}, r"^fpa\.defects\.clusters = -1"),
        ({"clusters": 1.5}, r"^fpa\.defects\.clusters = 1\.5 is not an integer"),
        ({"cluster_size": [5, 2]}, r"^fpa\.defects\.cluster_size\[1\] = 2 .*\[5, "),
        ({"cluster_size": [0, 2]}, r"^fpa\.defects\.cluster_size\[0\] = 0"),
        ({"cluster_size": 3}, r"^fpa\.defects\.cluster_size = 3"),
        ({"cluster_kinds": []}, r"^fpa\.defects\.cluster_kinds = \[\]"),
        ({"cluster_kinds": ["dead", "warm"]}, r"^fpa\.defects\.cluster_kinds\[1\] = 'warm'"),
        ({"rows": [1, -2]}, r"^fpa\.defects\.rows\[1\] = -2"),
        ({"cols": 3}, r"^fpa\.defects\.cols = 3 is not a list"),
        ({"line_kind": "good"}, r"^fpa\.defects\.line_kind = 'good'"),
        ({"stuck_value": 1.2}, r"^fpa\.defects\.stuck_value = 1\.2 .*\[0, 1\]"),
        ({"offset": 0.0}, r"^fpa\.defects\.offset = 0 .*\(0, 1\]"),
        ({"low_resp": 1.0}, r"^fpa\.defects\.low_resp = 1 .*\(0, 1\)"),
        ({"high_resp": 0.5}, r"^fpa\.defects\.high_resp = 0\.5 .*\(1, 100\]"),
        ({"high_resp": 1000}, r"^fpa\.defects\.high_resp = 1000"),
        ({"noise": -0.01}, r"^fpa\.defects\.noise = -0\.01"),
        ({"listed": [{"row": 0, "col": 0}]}, r"^fpa\.defects\.listed\[0\]\.kind is missing"),
        ({"listed": [{"row": 0, "col": 0, "kind": "dead", "x": 1}]}, r"listed\[0\]\.x is not"),
        ({"listed": [{"row": 0, "col": 0, "kind": "dead", "value": 0.5}]}, r"listed\[0\]\.value"),
        ({"listed": [{"row": 0, "col": 0, "kind": "hot", "value": 2}]}, r"listed\[0\]\.value = 2"),
        ({"listed": [{"row": -1, "col": 0, "kind": "hot"}]}, r"listed\[0\]\.row = -1"),
        (
            {"listed": [{"row": 0, "col": 0, "kind": "hot"}, {"row": 0, "col": 0, "kind": "dead"}]},
            r"^fpa\.defects\.listed\[1\]: pixel \(row 0, col 0\) is already listed",
        ),
    ],
)
def test_spec_validation(d, pattern):
    with pytest.raises(ConfigError, match=pattern):
        DefectSpec.from_dict(d)


def test_spec_validation_custom_path_and_direct():
    with pytest.raises(ConfigError, match=r"^cam\.defects\.rates\.dead"):
        DefectSpec.from_dict({"rates": {"dead": 2}}, path="cam.defects")
    with pytest.raises(ConfigError, match=r"^fpa\.defects\.offset"):
        DefectSpec(offset=-1.0)


@pytest.mark.parametrize(
    ("spec", "shape", "pattern"),
    [
        (DefectSpec(rows=(0, 6)), (6, 8), r"^fpa\.defects\.rows\[1\] = 6 .*\[0, 5\]"),
        (DefectSpec(cols=(8,)), (6, 8), r"^fpa\.defects\.cols\[0\] = 8 .*\[0, 7\]"),
        (
            DefectSpec(listed=({"row": 2, "col": 9, "kind": "dead"},)),
            (6, 8),
            r"^fpa\.defects\.listed\[0\]\.col = 9 .*\[0, 7\]",
        ),
        (DefectSpec(clusters=1, cluster_size=(5, 6)), (2, 2), r"cluster_size\[0\] = 5 .*\[1, 4\]"),
        (DefectSpec(), (0, 4), r"^shape\[0\] = 0"),
        (DefectSpec(), (4,), r"^shape = \(4,\)"),
    ],
)
def test_inject_validation(spec, shape, pattern):
    with pytest.raises(ConfigError, match=pattern):
        inject_defects(shape, spec, seed=0)


def test_inject_validation_seed():
    with pytest.raises(ConfigError, match=re.escape("seed = -3")):
        inject_defects((4, 4), DefectSpec(rates={"dead": 0.1}), seed=-3)
