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
from irnuc.nuc_fixed.validate import InputError, as_config


def _reading(name: str, value: object, cfg: PipelineConfig) -> int:
    hi = (1 << int(cfg.reading_bits or 1)) - 1
    try:
        v = int(value)  # type: ignore[call-overload]
    except (TypeError, ValueError):
        raise InputError(f"{name} = {value!r} is not an integer reading code") from None
    if isinstance(value, bool) or v != value or not 0 <= v <= hi:
        raise InputError(f"{name} = {value!r} is outside the allowed range [0, {hi}] "
                         f"(reading_bits = {cfg.reading_bits})")
    return v


@dataclass(frozen=True)
class TcReading:
    """Per-frame values of ``tc_reading``: u (signed Ts + 1 bits), u2 (unsigned Ts bits)."""

    u: int
    u2: int


def tc_reading(reading: int, t_ref: int, cfg: PipelineConfig | str) -> TcReading:
    """``tc_reading``: u = CLAMP(t - t_ref, +-(2^Ts - 1)), u2 = (u*u) >> Ts (floor).

    u is the reading's distance from the calibration centre with Ts = reading_range_bits
    fraction bits, so v = u / 2^Ts lies in (-1, 1); u2 is v^2 at Ts fraction bits.
    """
    cfg = as_config(cfg)
    t = _reading("reading", reading, cfg)
    r = _reading("t_ref", t_ref, cfg)
    ts = int(cfg.reading_range_bits or 1)
    lim = (1 << ts) - 1
    u = min(max(t - r, -lim), lim)
    return TcReading(u=u, u2=(u * u) >> ts)


def _poly(c0: np.ndarray, base: str, terms: list[tuple[np.ndarray, str]], tr: TcReading,
          cfg: PipelineConfig) -> np.ndarray:
    """ROUND then SAT of c0 + c1*u + c2*u2 into the format ``base`` (gain or offset)."""
    ts = int(cfg.reading_range_bits or 1)
    bf = cfg.format(base)
    fo = max(bf.frac_bits, *(cfg.format(n).frac_bits + ts for _, n in terms))
    acc = c0 << (fo - bf.frac_bits)
    for (c, n), v in zip(terms, (tr.u, tr.u2), strict=False):
        acc = acc + ((c * np.int64(v)) << (fo - cfg.format(n).frac_bits - ts))
    r = np.asarray(round_shift(np.ascontiguousarray(acc), fo - bf.frac_bits, cfg.rounding))
    lo, hi = code_range(cfg, base)
    return np.asarray(apply_overflow(r, lo, hi, "saturate"), dtype=np.int64)


def tc_coeffs(gain: object, offset: object, tc: dict[str, object], tr: TcReading,
              cfg: PipelineConfig | str) -> tuple[np.ndarray, np.ndarray]:
    """``tc_poly``: the frame's gain and offset codes of every pixel (tc_offset).

    o = SAT_O(ROUND(c0 << (Fo - Of) + (c1*u) << (Fo - T1f - Ts) [+ (c2*u2) << (Fo - T2f - Ts)]
    >> (Fo - Of))), Fo = max(Of, T1f + Ts, T2f + Ts); the gain likewise with tg1, tg2 when
    ``tc_gain`` (else the stored gain). ROUND is the pipeline's rounding mode.

    Parameters
    ----------
    gain, offset : integer array_like (H, W)
        The stored gain (U Gi.Gf) and offset c0 (S Oi.Of) codes.
    tc : dict
        ``tc1`` (and ``tc2``; ``tg1``, ``tg2`` with tc_gain) codes, each (H, W).
    tr : TcReading
        The frame's :func:`tc_reading`.
    """
    cfg = as_config(cfg)
    g = coeff(cfg, "gain", gain)
    o = coeff(cfg, "offset", offset)
    order = int(cfg.tc_order or 1)
    names = ["tc1", "tc2"][:order]
    missing = [n for n in names if n not in tc]
    if cfg.tc_gain:
        missing += [n for n in ["tg1", "tg2"][:order] if n not in tc]
    if missing:
        raise InputError(f"tc is missing {', '.join(missing)} (method {cfg.method!r}, "
                         f"tc_order = {order})")
    oterms = [(coeff(cfg, n, tc[n]), n) for n in names]
    o_t = _poly(o, "offset", oterms, tr, cfg)
    if cfg.tc_gain:
        gterms = [(coeff(cfg, n, tc[n]), n) for n in ["tg1", "tg2"][:order]]
        g = _poly(g, "gain", gterms, tr, cfg)
    return g, o_t


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
