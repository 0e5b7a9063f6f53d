"""The fused golden path (``nuc_fixed.fused``) bit for bit against the reference path.

``method_top`` runs every method's frames through the fused numba kernels; with
``reference=True`` it runs today's functions, one per RTL module (``frame_coefficients``,
the cores of ``nuc_fixed.cores``, ``dpc_core``, ``ffc_accumulate``), which
tests/test_methods.py checks against an exact integer reference written from
docs/datapath.md. Here the two paths meet on every named configuration of pipelines.toml,
the golden-only compositions, and every output rounding and overflow mode (with the
computed formats' modes changed too), on small frames with random codes biased to the
ends of every range, bad pixels on the edges and corners, readings around each method's
breakpoints, shutter runs complete and incomplete, and a start FFC correction.
"""

from __future__ import annotations

import numpy as np
import pytest

from irnuc.cocotb_tests.method_stim import random_coefficients, random_reading
from irnuc.nuc_fixed import load_pipeline, pipeline_names
from irnuc.nuc_fixed.config import PipelineConfig
from irnuc.nuc_fixed.fused import FusedMethod
from irnuc.nuc_fixed.method_top import FrameInputs, base_core, frame_coefficients, method_top
from irnuc.nuc_fixed.validate import InputError

NAMED = pipeline_names(method=None)
#: Compositions the golden model takes that no named configuration holds: (base
#: configuration, configuration whose stage keys are added).
COMPOSED = {"piecewise+ffc": ("piecewise14", "ffc14"), "table+ffc": ("table14", "ffc14"),
            "onepoint+drift": ("onepoint14", "drift14"), "quad+ffc_pass": ("quadffc14", None)}
MODES = [(r, o) for r in ("truncate", "half_up", "half_even") for o in ("saturate", "wrap")]
ROUNDINGS = ("truncate", "half_up", "half_even")


def _config(name: str, mode: int | None) -> PipelineConfig:
    """A named or composed configuration; ``mode``: output rounding and overflow
    ``MODES[mode]``, the computed formats (weight, drift, ffc) rounding the next mode and
    the same overflow (weight saturates: it cannot overflow)."""
    if name in COMPOSED:
        base, stage = COMPOSED[name]
        d = load_pipeline(base).to_dict()
        if stage is None:
            d["ffc_output"] = "pass"
        else:
            s = load_pipeline(stage).to_dict()
            extra = s["method"].split("+", 1)[1]
            d = {**{k: v for k, v in s.items() if k not in d or k == "formats"}, **d}
            d["formats"] = {**s["formats"], **load_pipeline(base).to_dict().get("formats", {})}
            d["method"] = f"{d['method']}+{extra}"
    else:
        d = load_pipeline(name).to_dict()
    if mode is not None:
        r, o = MODES[mode]
        d["rounding"], d["overflow"] = r, o
        for f, spec in d.get("formats", {}).items():
            if f in ("weight", "drift", "ffc"):
                spec["rounding"] = ROUNDINGS[(ROUNDINGS.index(r) + 1) % 3]
                spec["overflow"] = o if f != "weight" else "saturate"
    return PipelineConfig(**{**d, "name": f"{name.replace('+', '_')}_{mode}"})


def _stimulus(cfg: PipelineConfig, seed: int, h: int = 6, w: int = 7):
    rng = np.random.default_rng(seed)
    c = random_coefficients(cfg, h, w, rng, bad_fraction=0.15, biased=True)
    # Bad pixels on every corner and edge (DPC's neighbourhood is clipped there).
    for m in c.fields.values():
        if "bad" in m:
            b = m["bad"]
            b[0, 0] = b[-1, -1] = b[0, -1] = b[-1, 0] = True
            b[0, w // 2] = b[h // 2, 0] = True
    k = int(cfg.ffc_frames or 4)
    n = max(26, 2 * k + 14)  # with ffc: a complete run, an incomplete one, a pending one
    raw = rng.integers(0, 1 << cfg.adc_bits, (n, h, w))
    raw[0].flat[:4] = [0, (1 << cfg.adc_bits) - 1, 0, (1 << cfg.adc_bits) - 1]
    reading = housing = None
    if "fpa" in cfg.base.readings:
        # Runs of one reading (frames share their coefficients) and single frames around
        # the method's breakpoints (tc_housing: the housing reading drawn apart).
        drawn = [random_reading(cfg, c, rng, mark=k // 3) for k in range(n)]
        if isinstance(drawn[0], dict):
            housing = np.array([d["housing"] for d in drawn])
            housing[10:14] = housing[9]
            drawn = [d["fpa"] for d in drawn]
        reading = np.array(drawn)
        reading[10:14] = reading[9]
    blind = rng.integers(0, 1 << cfg.adc_bits, (n, 5))
    blind[1] = 0
    blind[2] = (1 << cfg.adc_bits) - 1
    shutter = np.zeros(n, bool)
    if cfg.has("ffc"):
        shutter[2:2 + k] = True           # a complete run: refresh in frame 2 + k
        shutter[12:12 + max(1, k - 1)] = True  # an incomplete run: no refresh
        shutter[n - k:] = True            # completes with the last frame: pending
    inputs = FrameInputs(reading=reading, blind_codes=blind, shutter=shutter,
                         housing_reading=housing)
    return c, raw, inputs, rng


def _same(a, b) -> None:
    assert a.y.dtype == b.y.dtype
    np.testing.assert_array_equal(a.y, b.y)
    for k in ("refreshes", "targets", "pending", "kept"):
        assert getattr(a, k) == getattr(b, k), k
    for k in ("delta", "ffc_offset", "held"):
        va, vb = getattr(a, k), getattr(b, k)
        assert (va is None) == (vb is None), k
        if va is not None:
            np.testing.assert_array_equal(va, vb)
    assert len(a.offsets) == len(b.offsets)
    for p, q in zip(a.offsets, b.offsets, strict=True):
        np.testing.assert_array_equal(p, q)


#: Each configuration as shipped and in two of MODES (one saturating, one wrapping, two
#: roundings), every mode on many configurations and each core kind.
CASES = [(name, mode) for i, name in enumerate([*NAMED, *COMPOSED])
         for mode in (None, i % len(MODES), (i + 3) % len(MODES))]


@pytest.mark.parametrize(("name", "mode"), CASES)
def test_fused_equals_reference(name: str, mode: int | None) -> None:
    cfg = _config(name, mode)
    c, raw, inputs, rng = _stimulus(cfg, abs(hash((name, mode))) % 2**32)
    kw = {}
    if cfg.has("ffc"):
        lo, hi = -(1 << (cfg.format("ffc").bits - 1)), (1 << (cfg.format("ffc").bits - 1)) - 1
        start = rng.integers(lo, hi + 1, c.shape)
        start.flat[:2] = [lo, hi]
        kw["ffc_offset"] = start
    fused = method_top(raw, c, inputs, **kw)
    ref = method_top(raw, c, inputs, reference=True, **kw)
    _same(fused, ref)
    if cfg.has("ffc"):
        assert fused.refreshes and fused.pending  # the stimulus reached both cases
        # A fixed target as well (no mean pass).
        _same(method_top(raw, c, inputs, ffc_target=3 << cfg.format("ffc").frac_bits, **kw),
              method_top(raw, c, inputs, ffc_target=3 << cfg.format("ffc").frac_bits,
                         reference=True, **kw))


@pytest.mark.parametrize("name", NAMED)
def test_fused_sums_equal_the_cores_sums(name: str) -> None:
    """The FFC passes' sums on an accumulator (xfrac > 0), every core kind."""
    cfg = _config(name, None)
    c, _raw, inputs, rng = _stimulus(cfg, 7)
    xfrac = 3
    acc = rng.integers(0, ((1 << cfg.adc_bits) - 1) << xfrac, c.shape)
    acc.flat[:2] = [0, ((1 << cfg.adc_bits) - 1) << xfrac]
    fm = FusedMethod(c)
    for k in range(4):
        fr = {} if inputs.reading is None else {"fpa": int(inputs.reading[k * 5])}
        if inputs.housing_reading is not None:
            fr["housing"] = int(inputs.housing_reading[k * 5])
        s, f = fm.sums(acc, xfrac, fr)
        ref = base_core(c, frame_coefficients(c, fr or None), acc, xfrac=xfrac, sum_only=True)
        assert f == ref.frac
        np.testing.assert_array_equal(s, ref.s)


def test_fused_refuses_a_code_out_of_range_as_the_reference_does() -> None:
    cfg = load_pipeline("tcoffset14")
    c, raw, inputs, _ = _stimulus(cfg, 3)
    c.fields["tc"]["tc1"][1, 2] = 1 << 20  # beyond S13.3
    for reference in (False, True):
        with pytest.raises(InputError, match=r"tc1\[1, 2\] = 1048576 is outside"):
            method_top(raw, c, inputs, reference=reference)


def test_fused_groups_frames_and_keeps_their_order() -> None:
    """Frames of different readings in one kernel call each take their own coefficients:
    reversing the frames reverses the output."""
    cfg = load_pipeline("tcgain14")
    c, raw, inputs, _ = _stimulus(cfg, 11)
    fwd = method_top(raw, c, inputs).y
    rev = method_top(raw[::-1], c, FrameInputs(reading=inputs.reading[::-1])).y
    np.testing.assert_array_equal(fwd, rev[::-1])
    assert len({int(v) for v in inputs.reading}) > 3
