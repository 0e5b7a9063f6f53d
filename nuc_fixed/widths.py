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
    """The core's input: x (A bits), x' = (x << Df) - delta after a stage acting on the
    input (blind_drift, ``StageSpec.input_x``) or the FFC accumulator (A + n bits, n
    fraction bits) in the refresh pass."""
    a = cfg.adc_bits
    if refresh:
        n = ffc_shift(cfg)
        return InputX(W(a + n, False), n)
    for part in cfg.parts[1:]:
        x = part.input_x(cfg)
        if x is not None:
            return x
    return InputX(W(a, False), 0)


def ffc_shift(cfg: PipelineConfig) -> int:
    """n = log2(ffc_frames): the accumulator's extra bits and the mean's shift."""
    return (cfg.ffc_frames or 1).bit_length() - 1


def core_frac(cfg: PipelineConfig, xfrac: int, with_ffc: bool) -> int:
    """F: the fraction bits of the method's sum (docs/datapath.md, each core kind)."""
    cf = [cfg.format("ffc").frac_bits] if with_ffc else []
    if cfg.base.core == "pwl":
        d = max(cfg.format("knee").frac_bits, xfrac)
        return max(cfg.gain_frac_bits + d, cfg.format("level").frac_bits, *cf)
    return max(cfg.gain_frac_bits + xfrac, cfg.offset_frac_bits, *cf)


def square_shift(cfg: PipelineConfig) -> int:
    """Sq = max(0, 2A - square_bits): the bits the square drops (floor) to fit a DSP."""
    return max(0, 2 * cfg.adc_bits - int(cfg.square_bits or 0))


def core_widths(cfg: PipelineConfig, x: InputX, with_ffc: bool) -> dict[str, W | int]:
    """Widths of the base method's core for input ``x`` (the sum, rounded and output), by
    the core's kind (``MethodSpec.core``)."""
    kind = cfg.base.core
    f = core_frac(cfg, x.frac, with_ffc)
    out: dict[str, W | int] = {"F": f}
    g = W(cfg.gain_bits, False)
    o = W(cfg.offset_bits, True)
    terms: list[W] = []
    if kind == "pwl":
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
    if kind == "quad":
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
    """Every intermediate width of the configuration's method, by dotted name: the stages
    acting on the input, the base method's own (``MethodSpec.widths``), its core, then the
    stages adding to the sum (``StageSpec.widths``).

    Integers are fraction-bit counts (``core.F``) and other constants; :class:`W` are words.
    """
    out: dict[str, W | int] = {}
    stages = cfg.parts[1:]
    for s in stages:
        if s.place == "input":
            out |= s.widths(cfg)
    out |= cfg.base.widths(cfg)
    out |= {f"core.{k}": v for k, v in core_widths(cfg, input_x(cfg), cfg.has("ffc")).items()}
    for s in stages:
        if s.place != "input":
            out |= s.widths(cfg)
    return out


def widest(cfg: PipelineConfig) -> dict[str, int]:
    """Bits of every word of :func:`method_widths` (for the int64 headroom check)."""
    return {k: v.as_signed() for k, v in method_widths(cfg).items() if isinstance(v, W)}
