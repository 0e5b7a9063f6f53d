"""Temperature-dependent coefficients: ``tc_offset`` and ``table_interp`` (docs/datapath.md).

Both turn the frame's FPA sensor reading (an integer code latched at the frame start,
``model.fpa_sensor.FpaSensor``) into per-pixel gain and offset codes of the two-point
formats, which :func:`irnuc.nuc_fixed.cores.lin_core` then applies. One function per RTL
module: :func:`tc_reading` and :func:`interp_weight` run once per frame (global),
:func:`tc_coeffs` and :func:`interp_coeffs` per pixel.
"""

from __future__ import annotations

import itertools
from dataclasses import dataclass

import numpy as np

from irnuc.nuc_fixed.config import ConfigError, PipelineConfig
from irnuc.nuc_fixed.cores import code_range, coeff
from irnuc.nuc_fixed.fixed import apply_overflow, round_div, round_shift
from irnuc.nuc_fixed.spec import CoefExpr, Term
from irnuc.nuc_fixed.validate import InputError, as_config


def _reading(name: str, value: object, cfg: PipelineConfig, bits: str = "reading_bits") -> int:
    """A reading code checked against the configuration's width ``bits`` (the FPA's
    ``reading_bits`` or the housing's ``housing_bits``)."""
    width = getattr(cfg, bits)
    hi = (1 << int(width or 1)) - 1
    try:
        v = int(value)  # type: ignore[call-overload]
    except (TypeError, ValueError):
        raise InputError(f"{name} = {value!r} is not an integer reading code") from None
    if isinstance(value, bool) or v != value or not 0 <= v <= hi:
        raise InputError(f"{name} = {value!r} is outside the allowed range [0, {hi}] "
                         f"({bits} = {width})")
    return v


@dataclass(frozen=True)
class TcReading:
    """Per-frame values of ``tc_reading``: u (signed Ts + 1 bits), u2 (unsigned Ts bits);
    with the housing reading (tc_housing) also w (signed Hs + 1 bits), uw (signed Ts + 1
    bits, v·w at Ts fraction bits) and w2 (unsigned Hs bits); 0 without it."""

    u: int
    u2: int
    w: int = 0
    uw: int = 0
    w2: int = 0


def tc_reading(reading: int, t_ref: int, cfg: PipelineConfig | str,
               housing: int | None = None, h_ref: int | None = None) -> TcReading:
    """``tc_reading``: u = CLAMP(t - t_ref, +-(2^Ts - 1)), u2 = (u*u) >> Ts (floor).

    u is the reading's distance from the calibration centre with Ts = reading_range_bits
    fraction bits, so v = u / 2^Ts lies in (-1, 1); u2 is v^2 at Ts fraction bits.
    With the housing reading h and its centre h_ref (tc_housing, Hs = housing_range_bits):
    w = CLAMP(h - h_ref, +-(2^Hs - 1)) (w' = w / 2^Hs), uw = (u*w) >> Hs (v·w' at Ts
    fraction bits, floor), w2 = (w*w) >> Hs (w'^2 at Hs fraction bits, floor).
    """
    cfg = as_config(cfg)
    t = _reading("reading", reading, cfg)
    r = _reading("t_ref", t_ref, cfg)
    ts = int(cfg.reading_range_bits or 1)
    lim = (1 << ts) - 1
    u = min(max(t - r, -lim), lim)
    if housing is None:
        return TcReading(u=u, u2=(u * u) >> ts)
    h = _reading("housing_reading", housing, cfg, "housing_bits")
    hr = _reading("h_ref", h_ref, cfg, "housing_bits")
    hs = int(cfg.housing_range_bits or 1)
    hlim = (1 << hs) - 1
    w = min(max(h - hr, -hlim), hlim)
    return TcReading(u=u, u2=(u * u) >> ts, w=w, uw=(u * w) >> hs, w2=(w * w) >> hs)


#: The variable each polynomial coefficient multiplies (a TcReading field) and whose
#: fraction bits it has (``ts``: reading_range_bits, ``hs``: housing_range_bits).
VARIABLES = {"tc1": ("u", "ts"), "tc2": ("u2", "ts"), "tg1": ("u", "ts"), "tg2": ("u2", "ts"),
             "th1": ("w", "hs"), "thx": ("uw", "ts"), "th2": ("w2", "hs")}


def term_shift(name: str, cfg: PipelineConfig) -> int:
    """Fraction bits of coefficient ``name`` times its variable: Tf + Ts (or + Hs)."""
    frac = VARIABLES[name][1]
    vf = int((cfg.reading_range_bits if frac == "ts" else cfg.housing_range_bits) or 1)
    return cfg.format(name).frac_bits + vf


def variable(name: str, tr: TcReading) -> int:
    """The value of the variable coefficient ``name`` multiplies in this frame."""
    return int(getattr(tr, VARIABLES[name][0]))


def _poly_frac(base: str, names: list[str], cfg: PipelineConfig) -> int:
    """Fo = max(base frac, T1f + Ts, T2f + Ts, ...): the fraction bits of a polynomial's
    sum."""
    return max(cfg.format(base).frac_bits, *(term_shift(n, cfg) for n in names))


def _poly(c0: np.ndarray, base: str, terms: list[tuple[np.ndarray, str]], tr: TcReading,
          cfg: PipelineConfig) -> np.ndarray:
    """ROUND then SAT of c0 + c1*u + c2*u2 (+ h1*w + hx*uw + h2*w2) into the format
    ``base`` (gain or offset)."""
    bf = cfg.format(base)
    fo = _poly_frac(base, [n for _, n in terms], cfg)
    acc = c0 << (fo - bf.frac_bits)
    for c, n in terms:
        acc = acc + ((c * np.int64(variable(n, tr))) << (fo - term_shift(n, cfg)))
    r = np.asarray(round_shift(np.ascontiguousarray(acc), fo - bf.frac_bits, cfg.rounding))
    lo, hi = code_range(cfg, base)
    return np.asarray(apply_overflow(r, lo, hi, "saturate"), dtype=np.int64)


def _poly_expr(c0: object, base: str, terms: list[tuple[object, str]], tr: TcReading,
               cfg: PipelineConfig) -> CoefExpr:
    """:func:`_poly` as an expression of the fused path (``MethodSpec.frame_expressions``)."""
    bf = cfg.format(base)
    fo = _poly_frac(base, [n for _, n in terms], cfg)
    ts_ = [Term(np.asarray(c0), 1, fo - bf.frac_bits, base)]
    ts_ += [Term(np.asarray(c), variable(n, tr), fo - term_shift(n, cfg), n)
            for c, n in terms]
    lo, hi = code_range(cfg, base)
    return CoefExpr(tuple(ts_), fo - bf.frac_bits, cfg.rounding, lo=lo, hi=hi)


#: The housing terms of the offset polynomial (tc_housing): w, v·w, w^2.
HOUSING_TERMS = ("th1", "thx", "th2")


def _tc_names(tc: dict[str, object], cfg: PipelineConfig) -> tuple[list[str], list[str]]:
    """The offset's and the gain's polynomial coefficients (the gain's: [] without
    tc_gain; the offset's with the housing terms when the method reads the housing);
    InputError naming those ``tc`` lacks."""
    order = int(cfg.tc_order or 1)
    names = ["tc1", "tc2"][:order]
    if "housing" in cfg.base.readings:
        names += list(HOUSING_TERMS)
    gnames = ["tg1", "tg2"][:order] if cfg.tc_gain else []
    missing = [n for n in names + gnames if n not in tc]
    if missing:
        raise InputError(f"tc is missing {', '.join(missing)} (method {cfg.method!r}, "
                         f"tc_order = {order})")
    return names, gnames


def tc_coeffs(gain: object, offset: object, tc: dict[str, object], tr: TcReading,
              cfg: PipelineConfig | str) -> tuple[np.ndarray, np.ndarray]:
    """``tc_poly``: the frame's gain and offset codes of every pixel (tc_offset).

    o = SAT_O(ROUND(c0 << (Fo - Of) + (c1*u) << (Fo - T1f - Ts) [+ (c2*u2) << (Fo - T2f - Ts)]
    >> (Fo - Of))), Fo = max(Of, T1f + Ts, T2f + Ts); the gain likewise with tg1, tg2 when
    ``tc_gain`` (else the stored gain). ROUND is the pipeline's rounding mode. tc_housing's
    offset has three more terms, (h1*w) << (Fo - H1f - Hs), (hx*uw) << (Fo - Hxf - Ts),
    (h2*w2) << (Fo - H2f - Hs), Fo the largest of all the terms' fraction bits.

    Parameters
    ----------
    gain, offset : integer array_like (H, W)
        The stored gain (U Gi.Gf) and offset c0 (S Oi.Of) codes.
    tc : dict
        ``tc1`` (and ``tc2``; ``tg1``, ``tg2`` with tc_gain; ``th1``, ``thx``, ``th2`` of
        tc_housing) codes, each (H, W).
    tr : TcReading
        The frame's :func:`tc_reading`.
    """
    cfg = as_config(cfg)
    g = coeff(cfg, "gain", gain)
    o = coeff(cfg, "offset", offset)
    names, gnames = _tc_names(tc, cfg)
    oterms = [(coeff(cfg, n, tc[n]), n) for n in names]
    o_t = _poly(o, "offset", oterms, tr, cfg)
    if gnames:
        gterms = [(coeff(cfg, n, tc[n]), n) for n in gnames]
        g = _poly(g, "gain", gterms, tr, cfg)
    return g, o_t


def tc_exprs(gain: object, offset: object, tc: dict[str, object], tr: TcReading,
             cfg: PipelineConfig | str) -> tuple[CoefExpr, CoefExpr]:
    """:func:`tc_coeffs` as the fused path's expressions of the gain and the offset (the
    same terms, shifts, rounding and saturation; the fields' ranges are checked where the
    fused path compiles them)."""
    cfg = as_config(cfg)
    names, gnames = _tc_names(tc, cfg)
    o = _poly_expr(offset, "offset", [(tc[n], n) for n in names], tr, cfg)
    g = (_poly_expr(gain, "gain", [(tc[n], n) for n in gnames], tr, cfg) if gnames
         else CoefExpr.of(gain, "gain"))
    return g, o


@dataclass(frozen=True)
class InterpWeight:
    """Per-frame values of ``interp_weight``: the lower table j and the weight w of j + 1
    (unsigned, Wf fraction bits, 0 <= w <= 2^Wf)."""

    j: int
    w: int


def interp_weight(reading: int, table_readings: list[int] | tuple[int, ...],
                  cfg: PipelineConfig | str) -> InterpWeight:
    """``interp_weight``: the two tables nearest the reading and the weight between them.

    j = the largest i <= K - 2 with r_i <= t (0 below r_0); w = RDIV(CLAMP(t - r_j, 0,
    span) << Wf, span), span = r_(j+1) - r_j, rounded with the weight format's rounding
    (an exact division: once per frame). Outside [r_0, r_(K-1)] the end table is used
    (w = 0 below, w = 2^Wf above): no extrapolation.
    """
    cfg = as_config(cfg)
    t = _reading("reading", reading, cfg)
    rs = [_reading(f"table_readings[{i}]", v, cfg) for i, v in enumerate(table_readings)]
    if len(rs) != cfg.tables:
        raise InputError(f"table_readings has {len(rs)} values; tables = {cfg.tables}")
    if any(b <= a for a, b in itertools.pairwise(rs)):
        raise ConfigError(f"table_readings = {rs} must increase strictly")
    j = 0
    for i in range(len(rs) - 1):
        if rs[i] <= t:
            j = i
    span = rs[j + 1] - rs[j]
    num = min(max(t - rs[j], 0), span)
    wf = cfg.format("weight")
    return InterpWeight(j=j, w=round_div(num << wf.frac_bits, span, wf.rounding))


def _lerp(a: np.ndarray, b: np.ndarray, w: int, cfg: PipelineConfig) -> np.ndarray:
    wf = cfg.format("weight")
    prod = np.ascontiguousarray((b - a) * np.int64(w))
    return a + np.asarray(round_shift(prod, wf.frac_bits, wf.rounding), dtype=np.int64)


def interp_coeffs(lower: tuple[object, object], upper: tuple[object, object],
                  iw: InterpWeight, cfg: PipelineConfig | str) -> tuple[np.ndarray, np.ndarray]:
    """``table_interp``: g = g_j + ROUND_Wf(w*(g_(j+1) - g_j)), o likewise.

    The result lies between the two tables' codes (no overflow); ROUND is the weight
    format's rounding.

    Parameters
    ----------
    lower, upper : (gain, offset)
        Codes of tables j and j + 1, each (H, W).
    """
    cfg = as_config(cfg)
    g0, o0 = coeff(cfg, "gain", lower[0]), coeff(cfg, "offset", lower[1])
    g1, o1 = coeff(cfg, "gain", upper[0]), coeff(cfg, "offset", upper[1])
    wf = cfg.format("weight")
    if not 0 <= iw.w <= (1 << wf.frac_bits):
        raise InputError(f"weight = {iw.w} is outside [0, {1 << wf.frac_bits}]")
    return _lerp(g0, g1, iw.w, cfg), _lerp(o0, o1, iw.w, cfg)


def interp_exprs(lower: tuple[object, object], upper: tuple[object, object],
                 iw: InterpWeight, cfg: PipelineConfig | str) -> tuple[CoefExpr, CoefExpr]:
    """:func:`interp_coeffs` as the fused path's expressions: c_j + ROUND_Wf(w*c_(j+1) -
    w*c_j), the lower table the base (no clamp: the result lies between the two codes)."""
    cfg = as_config(cfg)
    wf = cfg.format("weight")
    if not 0 <= iw.w <= (1 << wf.frac_bits):
        raise InputError(f"weight = {iw.w} is outside [0, {1 << wf.frac_bits}]")

    def lerp(a: object, b: object, fmt: str) -> CoefExpr:
        a_, b_ = np.asarray(a), np.asarray(b)
        return CoefExpr((Term(b_, iw.w, 0, fmt), Term(a_, -iw.w, 0, fmt)), wf.frac_bits,
                        wf.rounding, base=Term(a_, fmt=fmt))

    return lerp(lower[0], upper[0], "gain"), lerp(lower[1], upper[1], "offset")
