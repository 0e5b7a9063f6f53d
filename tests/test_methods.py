"""The correction methods' datapaths against independent references (docs/datapath.md).

* An exact integer reference written here from the document alone, in Python ints with
  ``fractions.Fraction`` for the rounding (nothing from ``nuc_fixed`` but the
  configuration's field values), compared bit for bit with every core and stage on random
  codes plus the extremes of every format, for every shipped method configuration.
* A float reference (the real-valued formula of each method in numpy float64), within the
  bound the quantization allows.
* The widths of ``nuc_fixed/widths.py`` against the exact extremes of every intermediate.
"""

from __future__ import annotations

from fractions import Fraction

import numpy as np
import pytest

from irnuc.nuc_fixed import load_pipeline, nuc_core, pipeline_names
from irnuc.nuc_fixed.cores import drift_sub, lin_core, pwl_core, quad_core
from irnuc.nuc_fixed.drift import blind_drift
from irnuc.nuc_fixed.ffc import ffc_mean_target, ffc_refresh
from irnuc.nuc_fixed.method_top import (
    FrameInputs,
    MethodCoefficients,
    base_core,
    frame_coefficients,
    method_top,
)
from irnuc.nuc_fixed.tempcomp import interp_coeffs, interp_weight, tc_coeffs, tc_reading

METHOD_CONFIGS = [n for n in pipeline_names(method=None) if n not in pipeline_names()]
#: Variants the shipped file does not hold: a first-order polynomial, with and without gain.
VARIANTS = {"tcgain14_order1": ("tcgain14", {"tc_order": 1}),
            "tcffc14_order1": ("tcffc14", {"tc_order": 1, "tc_gain": False})}


def _config(name: str):
    """A shipped configuration, or a variant with the formats its method needs."""
    if name not in VARIANTS:
        return load_pipeline(name)
    from irnuc.nuc_fixed.config import PipelineConfig

    base, changes = VARIANTS[name]
    d = load_pipeline(base).to_dict() | changes
    order = d["tc_order"]
    names = ["tc1", "tc2"][:order] + (["tg1", "tg2"][:order] if d["tc_gain"] else [])
    names += ["ffc"] if "ffc" in d["method"] else []
    d["formats"] = {k: v for k, v in load_pipeline(base).to_dict()["formats"].items()
                    if k in names}
    return PipelineConfig(**{**d, "name": name})


# ---- the exact reference (Python ints), from docs/datapath.md ------------------------

def rdiv(a: int, b: int, mode: str) -> int:
    """a / b rounded (floor, ties up, ties to even), by Fraction."""
    q = Fraction(a, b)
    fl = q.numerator // q.denominator
    rem = q - fl
    if mode == "truncate" or rem < Fraction(1, 2):
        return fl
    if rem > Fraction(1, 2) or mode == "half_up":
        return fl + 1
    return fl + (fl % 2)


def rnd(v: int, k: int, mode: str) -> int:
    """ROUND_k: v / 2^k."""
    return rdiv(v, 1 << k, mode)


def sat(v: int, bits: int, signed: bool) -> int:
    lo, hi = (-(1 << (bits - 1)), (1 << (bits - 1)) - 1) if signed else (0, (1 << bits) - 1)
    return min(max(v, lo), hi)


def wrap(v: int, bits: int, signed: bool) -> int:
    m = v % (1 << bits)
    return m - (1 << bits) if signed and m >= 1 << (bits - 1) else m


def ovf(v: int, bits: int, signed: bool, mode: str) -> int:
    return sat(v, bits, signed) if mode == "saturate" else wrap(v, bits, signed)


def fmt(cfg, name):
    f = cfg.format(name)
    return f.int_bits, f.frac_bits, f.signed, f.rounding, f.overflow


def out(cfg, s: int, f: int) -> int:
    r = rnd(s, f, cfg.rounding)
    return ovf(r, cfg.out_bits, False, cfg.overflow)


def ref_core(cfg, x: int, xf: int, c: dict, ffc: int | None) -> tuple[int, int]:
    """(s, F) of the base method's core for one pixel, per docs/datapath.md."""
    gf, of = cfg.gain_frac_bits, cfg.offset_frac_bits
    cf = [cfg.format("ffc").frac_bits] if ffc is not None else []
    base = cfg.base_method
    if base == "piecewise":
        _, kf, *_ = fmt(cfg, "knee")
        _, lf, *_ = fmt(cfg, "level")
        d_ = max(kf, xf)
        f = max(gf + d_, lf, *cf)
        d = x * 2 ** (d_ - xf) - c["knee"] * 2 ** (d_ - kf)
        g = c["gain_lo"] if d <= 0 else c["gain_hi"]
        s = d * g * 2 ** (f - gf - d_) + c["level"] * 2 ** (f - lf)
    else:
        f = max(gf + xf, of, *cf)
        s = x * c["gain"] * 2 ** (f - gf - xf) + c["offset"] * 2 ** (f - of)
        if base == "quadratic":
            _, qf, *_ = fmt(cfg, "quad")
            sq = max(0, 2 * cfg.adc_bits - cfg.square_bits)
            xq = (x * x) // 2 ** (2 * xf + sq)
            qpf = qf + 2 * cfg.adc_bits - sq
            qp = c["quad"] * xq
            s += qp * 2 ** (f - qpf) if qpf <= f else qp // 2 ** (qpf - f)
    if ffc is not None:
        s += ffc * 2 ** (f - cfg.format("ffc").frac_bits)
    return s, f


def ref_tc(cfg, t: int, t_ref: int, c: dict, h: int | None = None) -> tuple[int, int]:
    ts = cfg.reading_range_bits
    lim = 2**ts - 1
    u = min(max(t - t_ref, -lim), lim)
    u2 = (u * u) // 2**ts
    terms = {"tc1": (u, ts), "tc2": (u2, ts), "tg1": (u, ts), "tg2": (u2, ts)}
    extra: tuple[str, ...] = ()
    if h is not None:  # tc_housing: w, v·w', w'^2 of the housing reading
        hs = cfg.housing_range_bits
        hl = 2**hs - 1
        w = min(max(h - c["h_ref"], -hl), hl)
        terms |= {"th1": (w, hs), "thx": ((u * w) // 2**hs, ts), "th2": ((w * w) // 2**hs, hs)}
        extra = ("th1", "thx", "th2")
    res = {}
    for kind, base, names in (("offset", "offset", ("tc1", "tc2")), ("gain", "gain", ("tg1", "tg2"))):
        names = names[: cfg.tc_order] + (extra if kind == "offset" else ())
        if kind == "gain" and not cfg.tc_gain:
            res[kind] = c["gain"]
            continue
        bi, bf, bs, *_ = (cfg.format(base).int_bits, cfg.format(base).frac_bits,
                          cfg.format(base).signed)
        fo = max(bf, *(cfg.format(n).frac_bits + terms[n][1] for n in names))
        acc = c[kind] * 2 ** (fo - bf)
        for n in names:
            v, vf = terms[n]
            acc += c[n] * v * 2 ** (fo - cfg.format(n).frac_bits - vf)
        res[kind] = sat(rnd(acc, fo - bf, cfg.rounding), bi + bf, bs)
    return res["gain"], res["offset"]


def ref_interp(cfg, t: int, readings: list[int], lo: dict, hi_: dict) -> tuple[int, int, int, int]:
    _, wf, _, wr, _ = fmt(cfg, "weight")
    j = 0
    for i in range(len(readings) - 1):
        if readings[i] <= t:
            j = i
    span = readings[j + 1] - readings[j]
    num = min(max(t - readings[j], 0), span)
    w = rdiv(num * 2**wf, span, wr)
    return j, w, wf, wr


def ref_drift(cfg, blind: list[int], ref: int, m: int) -> int:
    di, df, _, dr, do = fmt(cfg, "drift")
    _, mf, *_ = fmt(cfg, "drift_gain")
    return ovf(rnd((sum(blind) - ref) * m, mf - df, dr), di + df, True, do)


# ---- random coefficient sets ----------------------------------------------------------

def _rand_field(rng, width: int, signed: bool, shape) -> np.ndarray:
    lo, hi = (-(1 << (width - 1)), (1 << (width - 1)) - 1) if signed else (0, (1 << width) - 1)
    v = rng.integers(lo, hi + 1, shape)
    v.flat[:2] = [lo, hi]  # the extremes of every field
    return v


def random_coeffs(cfg, rng, shape=(5, 6)) -> MethodCoefficients:
    bad = rng.random(shape) < 0.2
    fields = {}
    for m in cfg.memories.values():
        if m.source != "calibration":
            continue
        fields[m.name] = {f.name: bad if f.name == "bad" else _rand_field(rng, f.width, f.signed, shape)
                          for f in m.fields}
    regs: dict = {}
    for r in cfg.registers.values():
        if r.source != "calibration":
            continue
        if r.count > 1:
            regs[r.name] = tuple(sorted(rng.choice(np.arange(1, 1 << r.width), r.count,
                                                   replace=False).tolist()))
        else:
            regs[r.name] = int(_rand_field(rng, r.width, r.signed, (2,))[rng.integers(0, 2)]
                               if rng.random() < 0.3 else
                               _rand_field(rng, r.width, r.signed, (3,))[2])
    return MethodCoefficients(cfg, fields, regs)


def _pix(c: MethodCoefficients, i: int) -> dict:
    out: dict = {}
    for mem, vals in c.fields.items():
        for k, v in vals.items():
            out[k if not mem.startswith("table") else f"{mem}.{k}"] = int(v.flat[i])
    for k, v in c.registers.items():
        out[k] = v
    return out


# ---- the cores, bit for bit -------------------------------------------------------------

@pytest.mark.parametrize("name", [*METHOD_CONFIGS, *VARIANTS])
def test_every_method_matches_the_exact_reference(name: str) -> None:
    cfg = _config(name)
    rng = np.random.default_rng(abs(hash(name)) % 2**32)
    c = random_coeffs(cfg, rng)
    n = 24
    h, w = c.shape
    x = rng.integers(0, 1 << cfg.adc_bits, (n, h, w))
    x[0].flat[:4] = [0, (1 << cfg.adc_bits) - 1, 1, (1 << cfg.adc_bits) - 2]
    r_bits = cfg.reading_bits or 14
    reading = rng.integers(0, 1 << r_bits, n)
    if "table_readings" in c.registers:
        rr = c.registers["table_readings"]
        reading[:6] = [rr[0] - 1 if rr[0] else 0, rr[0], rr[1], rr[-1], rr[-1] + 1, (rr[0] + rr[1]) // 2]
    blind = rng.integers(0, 1 << cfg.adc_bits, (n, 7))
    shutter = np.zeros(n, bool)
    if cfg.has("ffc"):
        shutter[3:3 + cfg.ffc_frames + 1] = True
    housing = rng.integers(0, 1 << (cfg.housing_bits or 14), n)
    inputs = FrameInputs(reading=reading, blind_codes=blind, shutter=shutter,
                         housing_reading=housing)
    res = method_top(x, c, inputs)
    hk = (lambda k: int(housing[k])) if cfg.base_method == "tc_housing" else (lambda k: None)
    # DPC is the unchanged dpc_core: check the NUC output before it, frame by frame.
    good = ~c.bad
    ffc = np.zeros((h, w), np.int64) if cfg.has("ffc") else None
    acc = np.zeros((h, w), np.int64)
    count = 0
    last = None
    pending = None  # (accumulator, target): the refresh pass is the next frame

    def acc_sums(k: int, acc: np.ndarray) -> tuple[list[int], int]:
        """The core's sums on the accumulator with frame k's coefficients, and F."""
        nbits = cfg.ffc_frames.bit_length() - 1
        sums, fr_list = [], []
        for i in range(h * w):
            p = _pix(c, i)
            if cfg.base_method in ("tc_offset", "tc_housing"):
                p["gain"], p["offset"] = ref_tc(cfg, int(reading[k]), p["t_ref"], p, hk(k))
            s, f = ref_core(cfg, int(acc.flat[i]), nbits, p, None)
            sums.append(s)
            fr_list.append(f)
        return sums, fr_list[0]

    for k in range(n):
        if pending is not None:
            # The refresh pass, with this frame's coefficients (docs/datapath.md "ffc").
            _, cf, _, cr, co = fmt(cfg, "ffc")
            sums, f0 = acc_sums(k, pending[0])
            fr = max(f0, cf)
            ffc = np.array([ovf(rnd(pending[1] * 2 ** (fr - cf) - s * 2 ** (fr - f0),
                                    fr - cf, cr), cfg.format("ffc").bits, True, co)
                            for s in sums]).reshape(h, w)
            pending = None
        want = np.empty((h, w), np.int64)
        for i in range(h * w):
            p = _pix(c, i)
            xi = int(x[k].flat[i])
            xf = 0
            if cfg.base_method in ("tc_offset", "tc_housing"):
                p["gain"], p["offset"] = ref_tc(cfg, int(reading[k]), p["t_ref"], p, hk(k))
            if cfg.base_method == "table_interp":
                j, wgt, wf, wr = ref_interp(cfg, int(reading[k]), list(p["table_readings"]), {}, {})
                for q in ("gain", "offset"):
                    a, b = p[f"table{j}.{q}"], p[f"table{j + 1}.{q}"]
                    p[q] = a + rnd(wgt * (b - a), wf, wr)
            if cfg.base_method == "one_point":
                p["gain"] = p["gain"] if isinstance(p["gain"], int) else int(p["gain"])
            if cfg.has("blind_drift"):
                d = ref_drift(cfg, [int(v) for v in blind[k]], p["blind_ref"], p["drift_gain"])
                xf = cfg.format("drift").frac_bits
                xi = xi * 2**xf - d
                assert int(res.delta[k]) == d
            s, f = ref_core(cfg, xi, xf, p, None if ffc is None else int(ffc.flat[i]))
            want.flat[i] = out(cfg, s, f)
        got = res.y[k]
        if cfg.has("ffc") and shutter[k] and cfg.ffc_output == "hold" and last is not None:
            assert np.array_equal(got, last)
        else:
            assert np.array_equal(got[good], want[good]), (name, k)
            if not (cfg.has("ffc") and shutter[k]):
                last = got
        if cfg.has("ffc") and shutter[k] and count < cfg.ffc_frames:
            acc = x[k].astype(np.int64) if count == 0 else acc + x[k]
            count += 1
            if count == cfg.ffc_frames:
                _, cf, _, cr, _ = fmt(cfg, "ffc")
                sums, f0 = acc_sums(k, acc)
                fr = max(f0, cf)
                vals = [rnd(s * 2 ** (fr - f0), fr - cf, cr) for s in sums]
                gv = [v for v, g in zip(vals, good.ravel(), strict=True) if g]
                tgt = min(max(rdiv(sum(gv), len(gv), "half_up"), 0),
                          2 ** (cfg.out_bits + cf) - 1)
                pending = (acc.copy(), tgt)
        elif cfg.has("ffc") and not shutter[k]:
            count = 0
    if cfg.has("ffc"):
        assert res.refreshes == (3 + cfg.ffc_frames - 1,)
        assert np.array_equal(res.ffc_offset, ffc)
        assert len(res.offsets) == 1 and np.array_equal(res.offsets[0], ffc)
        assert not res.pending


def test_ffc_refresh_pass_uses_the_next_frame_and_a_pending_one_the_last() -> None:
    """The refresh pass takes the coefficients of the frame after the N-th (tc_offset: its
    reading); a run that ends with the sequence is refreshed with the last frame's."""
    cfg = load_pipeline("tcffc14")
    rng = np.random.default_rng(11)
    h, w = 4, 6
    c = random_coeffs(cfg, rng)
    # Moderate codes (no saturation): unit gain, offsets of a few codes, an offset slope.
    z = np.zeros((h, w), np.int64)
    c = MethodCoefficients(cfg, {
        "coeffs": {"gain": z + 16384 + rng.integers(-300, 300, (h, w)),
                   "offset": rng.integers(-80, 80, (h, w)), "bad": z.astype(bool)},
        "tc": {"tc1": rng.integers(-400, 400, (h, w)), "tc2": z},
        "tg": {"tg1": z, "tg2": z}}, {**c.registers, "t_ref": 8000})
    n = cfg.ffc_frames
    x = rng.integers(3000, 9000, (n + 1, h, w))
    reading = np.r_[np.full(n, 8000), 8000 + 700]
    shut = np.r_[np.ones(n, bool), False]
    res = method_top(x, c, FrameInputs(reading=reading, shutter=shut))
    acc = x[:n].sum(axis=0)
    nb = n.bit_length() - 1
    fc_last = frame_coefficients(c, int(reading[n - 1]))
    fc_next = frame_coefficients(c, int(reading[n]))
    ref = base_core(c, fc_last, acc, xfrac=nb, sum_only=True)
    tgt = ffc_mean_target(ref.s, ref.frac, ~c.bad, cfg)
    nxt = base_core(c, fc_next, acc, xfrac=nb, sum_only=True)
    want = ffc_refresh(nxt.s, nxt.frac, tgt, cfg)
    assert res.targets == (tgt,) and not res.pending
    assert np.array_equal(res.ffc_offset, want) and np.array_equal(res.offsets[0], want)
    assert not np.array_equal(want, ffc_refresh(ref.s, ref.frac, tgt, cfg))
    # The sequence ends with the N-th frame: pending, the last frame's coefficients.
    end = method_top(x[:n], c, FrameInputs(reading=reading[:n], shutter=shut[:n]))
    assert end.pending and end.refreshes == (n - 1,)
    assert np.array_equal(end.ffc_offset, ffc_refresh(ref.s, ref.frac, tgt, cfg))


@pytest.mark.parametrize("name", ["ffc14", "tcffc14", "quadffc14"])
def test_ffc_without_a_good_pixel_keeps_the_corrections(name: str) -> None:
    """A mean frame whose every pixel is bad has no target: no error (the sequence goes
    on), the refresh keeps each pixel's correction (from nonzero ones), ``kept`` names the
    run, the target reads 0 as the RTL's register does; a good pixel again refreshes."""
    cfg = load_pipeline(name)
    rng = np.random.default_rng(5)
    c = random_coeffs(cfg, rng, (3, 4))
    bad = np.ones((3, 4), bool)
    c = MethodCoefficients(cfg, {m: {**v, "bad": bad} if "bad" in v else v
                                 for m, v in c.fields.items()}, c.registers)
    n = int(cfg.ffc_frames)
    lo = -(1 << (cfg.format("ffc").bits - 1))
    start = rng.integers(lo, -lo, (3, 4))
    shut = np.r_[np.zeros(1, bool), np.ones(n, bool), np.zeros(2, bool)]
    x = rng.integers(0, 1 << cfg.adc_bits, (shut.size, 3, 4))
    reading = np.full(shut.size, int(c.registers.get("t_ref", 0)))
    res = method_top(x, c, FrameInputs(reading=reading, shutter=shut), ffc_offset=start)
    assert res.kept == res.refreshes == (n,) and res.targets == (0,)
    assert np.array_equal(res.offsets[0], start) and np.array_equal(res.ffc_offset, start)
    # The same frames with one good pixel: a target, new corrections.
    good = bad.copy()
    good[1, 2] = False
    c2 = MethodCoefficients(cfg, {m: {**v, "bad": good} if "bad" in v else v
                                  for m, v in c.fields.items()}, c.registers)
    res2 = method_top(x, c2, FrameInputs(reading=reading, shutter=shut), ffc_offset=start)
    assert res2.kept == () and res2.refreshes == (n,)
    assert not np.array_equal(res2.ffc_offset, start)


def test_table_interp_dpc_replaces_a_pixel_bad_in_either_table_of_the_pair() -> None:
    """table_interp's DPC: a pixel flagged in table j or j + 1 (the frame's pair) is
    replaced by the mean of its good neighbours; flagged only in a table the frame does
    not use, it passes. The neighbours' mean is worked out here from the output."""
    cfg = load_pipeline("table14")
    rng = np.random.default_rng(8)
    c = random_coeffs(cfg, rng, (3, 3))
    clean = np.zeros((3, 3), bool)
    fields = {m: {**v, "bad": clean} for m, v in c.fields.items()}
    only2 = clean.copy()
    only2[1, 1] = True
    fields["table2"] = {**fields["table2"], "bad": only2}  # the centre, table 2 only
    rs = (1000, 2000, 3000)
    c = MethodCoefficients(cfg, fields, {"table_readings": rs})
    x = rng.integers(2000, 12000, (2, 3, 3))
    # Frame 0 reads between tables 0 and 1; frame 1 between tables 1 and 2.
    res = method_top(x, c, FrameInputs(reading=np.array([1500, 2500])))
    plain = method_top(x, MethodCoefficients(cfg, {m: {**v, "bad": clean}
                                                   for m, v in fields.items()}, c.registers),
                       FrameInputs(reading=np.array([1500, 2500])))
    assert np.array_equal(res.y[0], plain.y[0])  # table 2 not used: passes
    nb = np.delete(plain.y[1].ravel(), 4).astype(int)  # the 8 good neighbours
    assert int(res.y[1, 1, 1]) == (2 * nb.sum() + 8) // 16  # mean, half up
    assert np.array_equal(np.delete(res.y[1].ravel(), 4), nb)
    assert c.bad.tolist() == only2.tolist()  # the map of every table's flags


@pytest.mark.parametrize("name", pipeline_names())
def test_lin_core_is_nuc_core(name: str) -> None:
    cfg = load_pipeline(name)
    rng = np.random.default_rng(7)
    g = rng.integers(0, 1 << cfg.gain_bits, (4, 9))
    o = rng.integers(-(1 << (cfg.offset_bits - 1)), 1 << (cfg.offset_bits - 1), (4, 9))
    x = rng.integers(0, 1 << cfg.adc_bits, (3, 4, 9))
    a = nuc_core(x, g, o, cfg, intermediates=True)
    b = lin_core(x, g, o, cfg)
    assert np.array_equal(a.s, b.s) and np.array_equal(a.r, b.r) and np.array_equal(a.y, b.y)


# ---- the stages, bit for bit, one step at a time -----------------------------------------

def test_drift_sub_and_blind_drift_exact() -> None:
    cfg = load_pipeline("drift14")
    rng = np.random.default_rng(3)
    blind = rng.integers(0, 1 << 14, (40, 50))
    blind[0] = 0
    blind[1] = (1 << 14) - 1
    lo, hi = -(1 << 24), (1 << 24) - 1
    for ref, m in ((0, hi), (50 * 8000, lo), (400_000, 123_457), (12345, -7)):
        res = blind_drift(blind, ref, m, cfg)
        want = [ref_drift(cfg, [int(v) for v in row], ref, m) for row in blind]
        assert res.delta.tolist() == want
    x = rng.integers(0, 1 << 14, (3, 5))
    for d in (-(1 << 13), (1 << 13) - 1, 0, 37):
        assert drift_sub(x, d, cfg).tolist() == [[int(v) * 4 - d for v in row] for row in x]


@pytest.mark.parametrize("name", ["tcoffset14", "tcgain14"])
def test_tc_reading_clamps_and_tc_coeffs_exact(name: str) -> None:
    cfg = load_pipeline(name)
    rng = np.random.default_rng(5)
    c = random_coeffs(cfg, rng, (3, 4))
    t_ref = 8000
    lim = 2**cfg.reading_range_bits - 1
    for t in (0, t_ref - lim - 5, t_ref - lim, t_ref - 1, t_ref, t_ref + 1, t_ref + lim,
              t_ref + lim + 1, 2**14 - 1):
        tr = tc_reading(t, t_ref, cfg)
        assert tr.u == min(max(t - t_ref, -lim), lim) and tr.u2 == tr.u * tr.u // 2**cfg.reading_range_bits
        tc = {**c.fields["tc"], **c.fields.get("tg", {})}
        g, o = tc_coeffs(c.fields["coeffs"]["gain"], c.fields["coeffs"]["offset"], tc, tr, cfg)
        for i in range(12):
            p = _pix(c, i)
            assert (int(g.flat[i]), int(o.flat[i])) == ref_tc(cfg, t, t_ref, p)


def test_interp_weight_ends_and_between() -> None:
    cfg = load_pipeline("table14")
    rs = [6485, 7485, 8485]
    wf = cfg.format("weight").frac_bits
    assert interp_weight(0, rs, cfg) == interp_weight(6485, rs, cfg)
    assert (interp_weight(6485, rs, cfg).j, interp_weight(6485, rs, cfg).w) == (0, 0)
    assert (interp_weight(7485, rs, cfg).j, interp_weight(7485, rs, cfg).w) == (1, 0)
    top = interp_weight(2**14 - 1, rs, cfg)
    assert (top.j, top.w) == (1, 2**wf)
    # Half way: w = 2^(Wf - 1) exactly; a third: RDIV half up of 2^Wf / 3.
    assert interp_weight(6985, rs, cfg).w == 2 ** (wf - 1)
    iw = interp_weight(6485 + 1000 // 3, rs, cfg)
    assert iw.w == rdiv(333 * 2**wf, 1000, "half_up")
    g, o = interp_coeffs((np.array([0, 65535]), np.array([-(2**15), 2**15 - 1])),
                         (np.array([65535, 0]), np.array([2**15 - 1, -(2**15)])), iw, cfg)
    assert g.tolist() == [rnd(iw.w * 65535, wf, "half_up"), 65535 + rnd(-iw.w * 65535, wf, "half_up")]
    assert o.tolist() == [-(2**15) + rnd(iw.w * (2**16 - 1), wf, "half_up"),
                          2**15 - 1 + rnd(-iw.w * (2**16 - 1), wf, "half_up")]


def test_ffc_refresh_and_target_exact() -> None:
    cfg = load_pipeline("ffc14")
    rng = np.random.default_rng(11)
    s = rng.integers(-(1 << 30), 1 << 30, (4, 5))
    good = rng.random((4, 5)) < 0.8
    for frac in (14, 17, 20):
        t = ffc_mean_target(s, frac, good, cfg)
        cf = 4
        fr = max(frac, cf)
        vals = [rnd(int(v) * 2 ** (fr - frac), fr - cf, "half_up") for v in s[good]]
        assert t == min(max(rdiv(sum(vals), len(vals), "half_up"), 0), 2**18 - 1)
        for tgt in (0, t, 2**18 - 1):
            d = ffc_refresh(s, frac, tgt, cfg)
            want = [sat(rnd(tgt * 2 ** (fr - cf) - int(v) * 2 ** (fr - frac), fr - cf, "half_up"),
                        16, True) for v in s.ravel()]
            assert d.ravel().tolist() == want


# ---- float references --------------------------------------------------------------------

def _value(c, cfg, name):
    return c * 2.0 ** -cfg.format(name).frac_bits


@pytest.mark.parametrize("name", ["onepoint14", "quadratic14", "piecewise14", "tcgain14", "table14"])
def test_methods_follow_their_real_valued_formula(name: str) -> None:
    """The output lies within the rounding of every step of the float formula."""
    cfg = load_pipeline(name)
    rng = np.random.default_rng(2)
    h, w = 6, 8
    a = cfg.adc_bits
    # Coefficients in a realistic range, so that outputs do not saturate.
    g = rng.integers(int(0.8 * 2**14), int(1.2 * 2**14), (h, w))
    o = rng.integers(-500 * 16, 500 * 16, (h, w))
    x = rng.integers(3000, 12000, (h, w))
    if name == "onepoint14":
        c = MethodCoefficients(cfg, {"coeffs": {"offset": o, "bad": np.zeros((h, w), bool)}},
                               {"gain": 2**14})
        y_f = x * 1.0 + o / 16.0
        tol = 0.5
    elif name == "quadratic14":
        q = rng.integers(-300 * 64, 300 * 64, (h, w))
        c = MethodCoefficients(cfg, {"coeffs": {"gain": g, "offset": o, "bad": np.zeros((h, w), bool)},
                                     "quad": {"quad": q}})
        y_f = g / 2**14 * x + o / 16 + q / 64 * (x / 2.0**a) ** 2
        # + the floor of the truncated square (< q * 2^Sq / 2^2A) and of qs (< 2^-F).
        tol = 0.5 + 300 * 2.0 ** (2 * a - cfg.square_bits) / 2.0 ** (2 * a) + 2.0**-14
    elif name == "piecewise14":
        k = rng.integers(6000 * 4, 8000 * 4, (h, w))
        glo = rng.integers(int(0.8 * 2**14), int(1.2 * 2**14), (h, w))
        lvl = 7000 * 16 + 5
        c = MethodCoefficients(cfg, {"coeffs": {"gain_lo": glo, "gain_hi": g, "knee": k,
                                                "bad": np.zeros((h, w), bool)}}, {"level": lvl})
        kk = k / 4.0
        y_f = lvl / 16 + np.where(x <= kk, glo, g) / 2**14 * (x - kk)
        tol = 0.5
    elif name == "tcgain14":
        t1 = rng.integers(-3000 * 8, 3000 * 8, (h, w))
        t2 = rng.integers(-500 * 16, 500 * 16, (h, w))
        d1 = rng.integers(-2**14, 2**14, (h, w))
        d2 = rng.integers(-2**13, 2**13, (h, w))
        c = MethodCoefficients(cfg, {"coeffs": {"gain": g, "offset": o // 2, "bad": np.zeros((h, w), bool)},
                                     "tc": {"tc1": t1, "tc2": t2}, "tg": {"tg1": d1, "tg2": d2}},
                               {"t_ref": 7485})
        t = 7485 + 700
        v = 700 / 2**11
        gg = g / 2**14 + d1 / 2**14 * v + d2 / 2**14 * np.floor(700**2 / 2**11) / 2**11
        oo = o / 2 / 8 + t1 / 8 * v + t2 / 16 * np.floor(700**2 / 2**11) / 2**11
        y_f = gg * x + oo
        # The gain is rounded to 2^-15 (x < 2^14: 0.5 code), the offset to 2^-4, then 0.5.
        tol = 2.0**-15 * x + 2.0**-4 + 0.5
    else:  # table14
        g2 = g + rng.integers(-2000, 2000, (h, w))
        o2 = o // 2 + rng.integers(-4000, 4000, (h, w))
        tabs = {f"table{k}": {"gain": gg_, "offset": oo_, "bad": np.zeros((h, w), bool)}
                for k, (gg_, oo_) in enumerate(((g, o // 2), (g2, o2), (g, o // 2)))}
        c = MethodCoefficients(cfg, tabs, {"table_readings": (6485, 7485, 8485)})
        t = 7485 - 250
        wgt = 0.75
        y_f = ((1 - wgt) * g + wgt * g2) / 2**14 * x + ((1 - wgt) * (o // 2) + wgt * o2) / 8
        tol = 2.0**-15 * x + 2.0**-4 + 0.5
    reading = np.array([t]) if name in ("tcgain14", "table14") else None
    y = method_top(x[None], c, FrameInputs(reading=reading)).y[0]
    assert (y > 0).all() and (y < 2**14 - 1).all()
    assert np.all(np.abs(y - y_f) <= tol + 1e-9), np.abs(y - y_f).max()


def test_quad_core_reduces_to_lin_core_without_curvature() -> None:
    cfg = load_pipeline("quadratic14")
    rng = np.random.default_rng(4)
    g = rng.integers(0, 1 << 16, (5, 5))
    o = rng.integers(-(1 << 15), 1 << 15, (5, 5))
    x = rng.integers(0, 1 << 14, (2, 5, 5))
    a = quad_core(x, g, o, np.zeros((5, 5), int), cfg)
    b = lin_core(x, g, o, cfg)
    assert np.array_equal(a.y, b.y) and np.array_equal(a.s, b.s)


def test_pwl_core_is_continuous_at_the_knee() -> None:
    cfg = load_pipeline("piecewise14")
    k = np.array([[4 * 5000]])
    for glo, ghi in ((2**14, 2**15), (0, 65535)):
        r = pwl_core(np.array([[5000]]), np.array([[glo]]), np.array([[ghi]]), k, 5000 * 16, cfg)
        assert int(r.y[0, 0]) == 5000 and int(r.s[0, 0]) == 5000 * 2 ** r.frac


def test_drift_and_ffc_follow_their_real_valued_formula() -> None:
    rng = np.random.default_rng(8)
    h, w = 5, 6
    g = rng.integers(int(0.8 * 2**14), int(1.2 * 2**14), (h, w))
    o = rng.integers(-500 * 16, 500 * 16, (h, w))
    # blind_drift: y = g (x - k (mean b - mean b_ref)) + o, k = 0.8, K = 50 blind pixels.
    cfg = load_pipeline("drift14")
    k, kb = 0.8, 50
    m = round(k / kb * 2**24)
    ref = 50 * 3000
    blind = rng.integers(3100, 3300, (4, kb))
    x = rng.integers(4000, 9000, (4, h, w))
    c = MethodCoefficients(cfg, {"coeffs": {"gain": g, "offset": o, "bad": np.zeros((h, w), bool)}},
                           {"blind_ref": ref, "drift_gain": m})
    y = method_top(x, c, FrameInputs(blind_codes=blind)).y
    shift = k * (blind.mean(axis=1) - ref / kb)
    y_f = g / 2**14 * (x - shift[:, None, None]) + o / 16
    # delta rounds to 2^-3 codes; the gain (< 1.2) scales that; then the output's 0.5.
    assert np.abs(y - y_f).max() <= 0.5 + 1.2 * 2**-3 + 1.2 * 2 * abs(m / 2**24 - k / kb) * 200
    # ffc: after the refresh, the shutter's mean frame reads the target level.
    cfg = load_pipeline("ffc14")
    c = MethodCoefficients(cfg, {"coeffs": {"gain": g, "offset": o, "bad": np.zeros((h, w), bool)}})
    shutter = rng.integers(5000, 5100, (8, h, w))
    scene = rng.integers(4000, 9000, (1, h, w))
    target = 5000 * 16 + 5  # within the correction format of every pixel
    res = method_top(np.concatenate([scene, shutter, scene]), c,
                     FrameInputs(shutter=np.r_[False, np.ones(8, bool), False]),
                     ffc_target=target)
    delta = res.ffc_offset / 16
    flat = g / 2**14 * shutter.mean(axis=0) + o / 16 + delta
    assert np.abs(flat - target / 16).max() <= 2**-5 + 1e-9  # the correction's rounding
    y_f = g / 2**14 * scene[0] + o / 16 + delta
    assert np.abs(res.y[-1] - y_f).max() <= 0.5
    # The shutter frames repeat the frame before them (hold).
    assert res.held.tolist() == [False] + [True] * 8 + [False]
    assert (res.y[1:9] == res.y[0]).all()


def test_quadratic_term_error_bound_of_the_datapath_doc() -> None:
    """docs/datapath.md (`quad_core`): qs differs from the exact q (x / 2^A)^2 by less than
    |q| (2^Sq - 1) 2^-(2A + Qf) + 2^-F (when QPf > F), over every ADC code, at q's extremes
    and at random q; exact integers (the old bound, 2^-9, failed once the term is floored)."""
    from irnuc.nuc_fixed.widths import core_frac, square_shift

    cfg = load_pipeline("quadratic14")
    a, q = cfg.adc_bits, cfg.format("quad")
    sq, f = square_shift(cfg), core_frac(cfg, 0, False)
    assert q.frac_bits + 2 * a - sq > f  # the term is floored on this configuration
    x = np.arange(1 << a, dtype=np.int64).reshape(1, -1)
    lo, hi = -(1 << (q.bits - 1)), (1 << (q.bits - 1)) - 1
    rng = np.random.default_rng(2)
    worst = Fraction(0)
    for qv in (lo, hi, *rng.integers(lo, hi, 6).tolist()):
        zero = np.zeros_like(x)
        res = quad_core(x, zero, zero, np.full_like(x, qv), cfg, sum_only=True)
        assert res.frac == f
        scale = 1 << (2 * a + q.frac_bits)  # exact = qv x^2 / scale, qs = s / 2^F
        err = np.abs(qv * (x * x) * (1 << f) - res.s * scale)  # over scale * 2^F
        bound = abs(qv) * ((1 << sq) - 1) * (1 << f) + scale
        assert int(err.max()) < bound, qv
        worst = max(worst, Fraction(int(err.max()), scale << f))
    assert 0.00195 < float(worst) < 0.00201  # the figures the document gives
