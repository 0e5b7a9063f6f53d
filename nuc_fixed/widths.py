"""Every intermediate width of every method's datapath (``docs/datapath.md``).

The closed forms of the datapath document, written once: the configuration check (no
intermediate above 62 bits, the golden model's int64 headroom), ``irnuc.nuc_fixed.nuc.widths``
and the RTL package generator read them from here. ``tests/test_methods_widths.py``
checks each against the exact range of its operands (interval arithmetic on Python ints).

A width is the number of bits of a two's-complement (signed) or plain binary (unsigned)
word; :func:`signed_width` turns an unsigned width into the signed width that holds it.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from irnuc.nuc_fixed.config import PipelineConfig


@dataclass(frozen=True)
class W:
    """A width and its signedness."""

    bits: int
    signed: bool

    def as_signed(self) -> int:
        return signed_width(self.bits, self.signed)

    def __str__(self) -> str:
        return f"{self.bits} ({'signed' if self.signed else 'unsigned'})"


def signed_width(bits: int, signed: bool) -> int:
    """Bits of the signed word holding a ``bits``-bit value (one more if unsigned)."""
    return bits if signed else bits + 1


def add(*terms: W) -> W:
    """Width of the sum (or difference, for the signed case) of ``terms``.

    All unsigned and added: max + ceil(log2(n)); otherwise every term as signed, then
    max + ceil(log2(n)), signed.
    """
    grow = math.ceil(math.log2(len(terms))) if len(terms) > 1 else 0
    if all(not t.signed for t in terms):
        return W(max(t.bits for t in terms) + grow, False)
    return W(max(t.as_signed() for t in terms) + grow, True)


def sub(a: W, b: W) -> W:
    """Width of a - b (always signed): max of both as signed, plus one."""
    return W(max(a.as_signed(), b.as_signed()) + 1, True)


def diff_unsigned(a: W, b: W) -> W:
    """Width of a - b of two unsigned words: max of both + 1, signed. Exact (|a - b| <=
    2^max - 1), one bit below :func:`sub`'s rule of sums; the RTL's blind-sum change and
    table gain difference take it (docs/datapath.md, "Notation")."""
    if a.signed or b.signed:
        raise ValueError("diff_unsigned takes two unsigned words")
    return W(max(a.bits, b.bits) + 1, True)


def mul(a: W, b: W) -> W:
    """Width of a * b: the sum of the widths (signed if either is)."""
    return W(a.bits + b.bits, a.signed or b.signed)


def shl(a: W, n: int) -> W:
    return W(a.bits + n, a.signed)


@dataclass(frozen=True)
class InputX:
    """The raw input as the core sees it: width, fraction bits."""

    w: W
    frac: int


def input_x(cfg: PipelineConfig, refresh: bool = False) -> InputX:
    """The core's input: x (A bits), x' = (x << Df) - delta (blind_drift) or the FFC
    accumulator (A + n bits, n fraction bits) in the refresh pass."""
    a = cfg.adc_bits
    if refresh:
        n = ffc_shift(cfg)
        return InputX(W(a + n, False), n)
    if cfg.has("blind_drift"):
        d = cfg.format("drift")
        return InputX(sub(W(a + d.frac_bits, False), W(d.bits, True)), d.frac_bits)
    return InputX(W(a, False), 0)


def ffc_shift(cfg: PipelineConfig) -> int:
    """n = log2(ffc_frames): the accumulator's extra bits and the mean's shift."""
    return (cfg.ffc_frames or 1).bit_length() - 1


def core_frac(cfg: PipelineConfig, xfrac: int, with_ffc: bool) -> int:
    """F: the fraction bits of the method's sum (docs/datapath.md, each core)."""
    base = cfg.base_method
    cf = [cfg.format("ffc").frac_bits] if with_ffc else []
    if base == "piecewise":
        d = max(cfg.format("knee").frac_bits, xfrac)
        return max(cfg.gain_frac_bits + d, cfg.format("level").frac_bits, *cf)
    if base == "one_point":
        return max(cfg.gain_frac_bits + xfrac, cfg.offset_frac_bits, *cf)
    return max(cfg.gain_frac_bits + xfrac, cfg.offset_frac_bits, *cf)


def square_shift(cfg: PipelineConfig) -> int:
    """Sq = max(0, 2A - square_bits): the bits the square drops (floor) to fit a DSP."""
    return max(0, 2 * cfg.adc_bits - int(cfg.square_bits or 0))


def core_widths(cfg: PipelineConfig, x: InputX, with_ffc: bool) -> dict[str, W | int]:
    """Widths of the base method's core for input ``x`` (the sum, rounded and output)."""
    base = cfg.base_method
    f = core_frac(cfg, x.frac, with_ffc)
    out: dict[str, W | int] = {"F": f}
    g = W(cfg.gain_bits, False)
    o = W(cfg.offset_bits, True)
    terms: list[W] = []
    if base == "piecewise":
        kf = cfg.format("knee")
        d = max(kf.frac_bits, x.frac)
        xa = shl(x.w, d - x.frac)
        ka = shl(W(kf.bits, False), d - kf.frac_bits)
        diff = sub(xa, ka)
        p = mul(diff, g)
        lf = cfg.format("level")
        out |= {"D": d, "d": diff, "p": p}
        terms += [shl(p, f - cfg.gain_frac_bits - d), shl(W(lf.bits, False), f - lf.frac_bits)]
    else:
        p = mul(x.w, g)
        out["p"] = p
        terms += [shl(p, f - cfg.gain_frac_bits - x.frac), shl(o, f - cfg.offset_frac_bits)]
    if base == "quadratic":
        q = cfg.format("quad")
        sq = mul(x.w, x.w)
        sq = W(sq.bits, False)
        sh = 2 * x.frac + square_shift(cfg)
        xq = W(sq.bits - sh, False)
        qp = mul(W(q.bits, True), xq)
        qpf = q.frac_bits + 2 * cfg.adc_bits - square_shift(cfg)
        qs = shl(qp, f - qpf) if qpf <= f else W(qp.bits - (qpf - f), True)
        out |= {"xsq": sq, "xq": xq, "qp": qp, "QPf": qpf, "qs": qs}
        terms.append(qs)
    if with_ffc:
        c = cfg.format("ffc")
        terms.append(shl(W(c.bits, True), f - c.frac_bits))
    s = add(*terms)
    out |= {"s": s, "r": W(s.as_signed() + 1 - f, True), "y": W(cfg.out_bits, False)}
    return out


def method_widths(cfg: PipelineConfig) -> dict[str, W | int]:
    """Every intermediate width of the configuration's method, by dotted name.

    Integers are fraction-bit counts (``core.F``) and other constants; :class:`W` are words.
    """
    out: dict[str, W | int] = {}
    x = input_x(cfg)
    a = cfg.adc_bits
    if cfg.has("blind_drift"):
        d, m = cfg.format("drift"), cfg.format("drift_gain")
        sb = W(cfg.blind_sum_bits, False)
        bd = diff_unsigned(sb, sb)
        dp = mul(bd, W(m.bits, True))
        out |= {"drift.bsum": sb, "drift.bd": bd, "drift.dp": dp,
                "drift.delta": W(d.bits, True), "drift.x": x.w}
    base = cfg.base_method
    if base == "tc_offset":
        ts = int(cfg.reading_range_bits or 1)
        r = int(cfg.reading_bits or 1)
        u = W(ts + 1, True)
        u2 = W(ts, False)
        out |= {"tc.diff": sub(W(r, False), W(r, False)), "tc.u": u, "tc.u2": u2}
        for kind, base_fmt, c1, c2 in (("o", cfg.format("offset"), "tc1", "tc2"),
                                       ("g", cfg.format("gain"), "tg1", "tg2")):
            if kind == "g" and not cfg.tc_gain:
                continue
            names = [c1, c2][: int(cfg.tc_order or 1)]
            fmts = [cfg.format(n) for n in names]
            fo = max(base_fmt.frac_bits, *(c.frac_bits + ts for c in fmts))
            terms = [shl(W(base_fmt.bits, base_fmt.signed), fo - base_fmt.frac_bits)]
            for c, v in zip(fmts, (u, u2), strict=False):
                prod = mul(W(c.bits, True), v)
                out[f"tc.{kind}.{c.name}_prod"] = prod
                terms.append(shl(prod, fo - c.frac_bits - ts))
            acc = add(*terms)
            out |= {f"tc.{kind}.F": fo, f"tc.{kind}.sum": acc,
                    f"tc.{kind}.rounded": W(acc.bits + 1 - (fo - base_fmt.frac_bits), True)}
    if base == "table_interp":
        wf = cfg.format("weight")
        r = int(cfg.reading_bits or 1)
        w = W(wf.frac_bits + 1, False)
        out |= {"interp.num": W(r + wf.frac_bits, False), "interp.span": W(r, False),
                "interp.w": w}
        for kind, bits in (("g", cfg.gain_bits), ("o", cfg.offset_bits)):
            diff = (sub(W(bits, True), W(bits, True)) if kind == "o"
                    else diff_unsigned(W(bits, False), W(bits, False)))
            prod = mul(diff, w)
            out |= {f"interp.{kind}.diff": diff, f"interp.{kind}.prod": prod}
    out |= {f"core.{k}": v for k, v in core_widths(cfg, x, cfg.has("ffc")).items()}
    if cfg.has("ffc"):
        n = ffc_shift(cfg)
        c = cfg.format("ffc")
        rx = input_x(cfg, refresh=True)
        ref = core_widths(cfg, rx, False)
        fr = max(int(ref["F"]), c.frac_bits)
        s_ref = ref["s"]
        assert isinstance(s_ref, W)
        s_ref = shl(s_ref, fr - int(ref["F"]))
        tgt = W(cfg.out_bits + c.frac_bits + fr - c.frac_bits, False)
        dr = sub(tgt, s_ref)
        out |= {"ffc.acc": W(a + n, False), "ffc.F": fr,
                **{f"ffc.refresh.{k}": v for k, v in ref.items() if isinstance(v, W)},
                "ffc.refresh.s_aligned": s_ref, "ffc.target": W(cfg.out_bits + c.frac_bits,
                                                                 False),
                "ffc.diff": dr, "ffc.rounded": W(dr.bits + 1 - (fr - c.frac_bits), True),
                "ffc.delta": W(c.bits, True)}
    return out


def widest(cfg: PipelineConfig) -> dict[str, int]:
    """Bits of every word of :func:`method_widths` (for the int64 headroom check)."""
    return {k: v.as_signed() for k, v in method_widths(cfg).items() if isinstance(v, W)}
