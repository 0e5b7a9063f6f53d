"""Every width of nuc_fixed/widths.py holds the exact range of its quantity.

The ranges are computed here by interval arithmetic on Python ints from the operands'
code ranges (docs/datapath.md), independently of the closed forms; a width is right when
the extremes fit and, for the core sums, the closed form is not wasteful by more than
the documented one or two bits.
"""

from __future__ import annotations

import itertools

import pytest

from irnuc.nuc_fixed import load_pipeline, pipeline_names
from irnuc.nuc_fixed.widths import W, method_widths

ALL = pipeline_names(method=None)


def rng_of(bits: int, signed: bool) -> tuple[int, int]:
    return (-(1 << (bits - 1)), (1 << (bits - 1)) - 1) if signed else (0, (1 << bits) - 1)


def iv_mul(a, b):
    p = [x * y for x, y in itertools.product(a, b)]
    return min(p), max(p)


def iv_add(*ts):
    return sum(t[0] for t in ts), sum(t[1] for t in ts)


def iv_shift(a, n):
    return (a[0] << n, a[1] << n) if n >= 0 else (a[0] >> -n, a[1] >> -n)


def fits(r: tuple[int, int], w: W) -> bool:
    lo, hi = rng_of(w.bits, w.signed)
    return lo <= r[0] and r[1] <= hi


def core_ranges(cfg, x, xf, with_ffc):
    """Exact ranges of the core's p and s for input range ``x`` with ``xf`` fraction bits."""
    g = rng_of(cfg.gain_bits, False)
    o = rng_of(cfg.offset_bits, True)
    gf, of = cfg.gain_frac_bits, cfg.offset_frac_bits
    cf = cfg.format("ffc").frac_bits if with_ffc else 0
    terms = []
    out = {}
    if cfg.base_method == "piecewise":
        k = cfg.format("knee")
        lv = cfg.format("level")
        d_ = max(k.frac_bits, xf)
        f = max(gf + d_, lv.frac_bits, cf)
        d = (x[0] * 2 ** (d_ - xf) - (2**k.bits - 1) * 2 ** (d_ - k.frac_bits), x[1] * 2 ** (d_ - xf))
        p = iv_mul(d, g)
        out |= {"core.d": d, "core.p": p}
        terms += [iv_shift(p, f - gf - d_), iv_shift(rng_of(lv.bits, False), f - lv.frac_bits)]
    else:
        f = max(gf + xf, of, cf)
        p = iv_mul(x, g)
        out["core.p"] = p
        terms += [iv_shift(p, f - gf - xf), iv_shift(o, f - of)]
        if cfg.base_method == "quadratic":
            q = cfg.format("quad")
            sq = max(0, 2 * cfg.adc_bits - cfg.square_bits)
            xsq = (0, max(x[0] ** 2, x[1] ** 2))
            xq = (0, xsq[1] >> (2 * xf + sq))
            qp = iv_mul(rng_of(q.bits, True), xq)
            qpf = q.frac_bits + 2 * cfg.adc_bits - sq
            qs = iv_shift(qp, f - qpf)
            out |= {"core.xsq": xsq, "core.xq": xq, "core.qp": qp, "core.qs": qs}
            terms.append(qs)
    if with_ffc:
        c = cfg.format("ffc")
        terms.append(iv_shift(rng_of(c.bits, True), f - c.frac_bits))
    s = iv_add(*terms)
    out |= {"core.s": s, "core.r": (s[0] >> f, (s[1] + (1 << f)) >> f if f else s[1]), "F": f}
    return out


@pytest.mark.parametrize("name", ALL)
def test_widths_hold_exact_ranges(name: str) -> None:
    cfg = load_pipeline(name)
    mw = method_widths(cfg)
    a = cfg.adc_bits
    x, xf = (0, (1 << a) - 1), 0
    checked = []
    if cfg.has("blind_drift"):
        d, m = cfg.format("drift"), cfg.format("drift_gain")
        sb = (0, cfg.blind_max * ((1 << a) - 1))
        bd = (sb[0] - ((1 << cfg.blind_sum_bits) - 1), sb[1])
        dp = iv_mul(bd, rng_of(m.bits, True))
        dl = rng_of(d.bits, True)
        x = (0 - dl[1], ((1 << a) - 1) * 2**d.frac_bits - dl[0])
        xf = d.frac_bits
        for k, r in (("drift.bsum", sb), ("drift.bd", bd), ("drift.dp", dp), ("drift.x", x)):
            assert fits(r, mw[k]), (k, r, mw[k])
            checked.append(k)
        # bd, the difference of two unsigned words, is exact (one bit below the rule of
        # sums, docs/datapath.md "Notation"; the RTL's BdBits): one bit fewer fails.
        assert not fits(bd, W(mw["drift.bd"].bits - 1, True))
        assert mw["drift.bd"].bits == cfg.blind_sum_bits + 1
    cr = core_ranges(cfg, x, xf, cfg.has("ffc"))
    assert cr["F"] == mw["core.F"]
    for k, r in cr.items():
        if k in mw and k != "F":
            assert fits(r, mw[k]), (k, r, mw[k])
            checked.append(k)
    # The sum is tight: one bit fewer would not hold both extremes' magnitude in general.
    s = cr["core.s"]
    assert mw["core.s"].bits - max(abs(s[0]), s[1] + 1).bit_length() - 1 <= 2
    if cfg.base_method == "tc_offset":
        ts = cfg.reading_range_bits
        u = (-(2**ts - 1), 2**ts - 1)
        u2 = (0, (2**ts - 1) ** 2 >> ts)
        assert fits(u, mw["tc.u"]) and fits(u2, mw["tc.u2"])
        for kind, base, names in (("o", "offset", ("tc1", "tc2")), ("g", "gain", ("tg1", "tg2"))):
            if kind == "g" and not cfg.tc_gain:
                continue
            bf = cfg.format(base)
            names = names[: cfg.tc_order]
            fo = mw[f"tc.{kind}.F"]
            terms = [iv_shift(rng_of(bf.bits, bf.signed), fo - bf.frac_bits)]
            for n, v in zip(names, (u, u2), strict=False):
                fm = cfg.format(n)
                prod = iv_mul(rng_of(fm.bits, True), v)
                assert fits(prod, mw[f"tc.{kind}.{n}_prod"])
                terms.append(iv_shift(prod, fo - fm.frac_bits - ts))
            assert fits(iv_add(*terms), mw[f"tc.{kind}.sum"])
            checked.append(f"tc.{kind}.sum")
    if cfg.base_method == "table_interp":
        wf = cfg.format("weight").frac_bits
        w = (0, 1 << wf)
        assert fits(w, mw["interp.w"])
        for kind, bits, signed in (("g", cfg.gain_bits, False), ("o", cfg.offset_bits, True)):
            lo, hi = rng_of(bits, signed)
            diff = (lo - hi, hi - lo)
            assert fits(diff, mw[f"interp.{kind}.diff"])
            # dg (unsigned gains) is exact, GW + 1 as the RTL's DgBits; do the rule of sums.
            assert not fits(diff, W(mw[f"interp.{kind}.diff"].bits - 1, True))
            assert mw[f"interp.{kind}.diff"].bits == bits + 1
            assert fits(iv_mul(diff, w), mw[f"interp.{kind}.prod"])
            checked.append(f"interp.{kind}.prod")
    if cfg.has("ffc"):
        n = cfg.ffc_frames.bit_length() - 1
        acc = (0, ((1 << a) - 1) * cfg.ffc_frames)
        assert fits(acc, mw["ffc.acc"])
        rr = core_ranges(cfg, acc, n, False)
        for k in ("core.p", "core.s"):
            assert fits(rr[k], mw[k.replace("core.", "ffc.refresh.")]), k
        c = cfg.format("ffc")
        fr = max(rr["F"], c.frac_bits)
        assert fr == mw["ffc.F"]
        sa = iv_shift(rr["core.s"], fr - rr["F"])
        tgt = (0, (2 ** (cfg.out_bits + c.frac_bits) - 1) << (fr - c.frac_bits))
        diff = (tgt[0] - sa[1], tgt[1] - sa[0])
        assert fits(diff, mw["ffc.diff"])
        checked.append("ffc.diff")
    assert all(v.bits <= 62 for v in mw.values() if isinstance(v, W))
    assert "core.s" in checked
