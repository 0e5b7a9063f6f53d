"""The per-pixel cores of the correction methods, bit-exact to ``docs/datapath.md``.

One function per RTL module: :func:`drift_sub` (x' = (x << Df) - delta), :func:`lin_core`
(the ``lin`` kind: g*x + o), :func:`quad_core` (``quad``: g*x + o + q*(x/2^A)^2),
:func:`pwl_core` (``pwl``: level + g_sel*(x - knee)); :data:`CORES` by kind, the kind of a
method being ``MethodSpec.core``.
Every core takes its input with ``xfrac`` fraction bits (0 for raw codes, Df after the
blind drift, n = log2(ffc_frames) for the FFC accumulator in the refresh pass) and an
optional FFC offset correction, and returns :class:`CoreResult`: the aligned sum ``s``
(``F`` fraction bits), and, unless ``sum_only``, the rounded ``r`` and the output ``y``.

The arithmetic is numpy int64 (exact: :func:`irnuc.nuc_fixed.widths.method_widths` keeps
every intermediate within 62 bits); ROUND_F and OUT are the datapath's own kernels
(``_kernels.round_code`` / ``out_code``), shared with ``nuc_core``.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import dataclass
from typing import Any

import numpy as np

from irnuc.nuc_fixed import _kernels
from irnuc.nuc_fixed.config import PipelineConfig
from irnuc.nuc_fixed.validate import InputError, as_config, int_array
from irnuc.nuc_fixed.widths import core_frac, square_shift


@dataclass(frozen=True)
class CoreResult:
    """Outputs of one core (int64 arrays of the shape of the input).

    Attributes
    ----------
    s : aligned signed sum with ``frac`` fraction bits.
    r : ROUND_F(s) (None when only the sum was asked for).
    y : OUT(r), the corrected code, B bits unsigned (None likewise).
    frac : F, the fraction bits of ``s``.
    """

    s: np.ndarray
    r: np.ndarray | None
    y: np.ndarray | None
    frac: int


def code_range(cfg: PipelineConfig, name: str) -> tuple[int, int]:
    """[min_code, max_code] of a coefficient format of ``cfg``."""
    f = cfg.format(name)
    if f.signed:
        return -(1 << (f.bits - 1)), (1 << (f.bits - 1)) - 1
    return 0, (1 << f.bits) - 1


def coeff(cfg: PipelineConfig, name: str, value: object, arg: str | None = None) -> np.ndarray:
    """``value`` as int64 codes of the format ``name``, range-checked (InputError)."""
    lo, hi = code_range(cfg, name)
    return int_array(arg or name, value, lo, hi).astype(np.int64)


def round_out(s: np.ndarray, frac: int, cfg: PipelineConfig) -> tuple[np.ndarray, np.ndarray]:
    """(r, y) = (ROUND_F(s), OUT(r)) with the pipeline's rounding and overflow modes."""
    s = np.ascontiguousarray(s, dtype=np.int64)
    r = np.empty_like(s)
    y = np.empty_like(s)
    _kernels.round_out_codes(s, frac, cfg.rounding_code, cfg.overflow == "wrap",
                             (1 << cfg.out_bits) - 1, r, y)
    return r, y


def _align(v: np.ndarray, have: int, want: int) -> np.ndarray:
    """``v`` (``have`` fraction bits) at ``want`` fraction bits: a left shift, or a floor
    (arithmetic) right shift when ``want < have`` (TRUNC in docs/datapath.md)."""
    return v << (want - have) if want >= have else v >> (have - want)


def _x(x: object, xfrac: int, cfg: PipelineConfig, signed: bool) -> np.ndarray:
    if signed:
        return int_array("x", x, -(1 << 62), (1 << 62) - 1).astype(np.int64)
    return int_array("x", x, 0, ((1 << cfg.adc_bits) - 1) << xfrac).astype(np.int64)


def _finish(s: np.ndarray, f: int, cfg: PipelineConfig, sum_only: bool) -> CoreResult:
    if sum_only:
        return CoreResult(s=s, r=None, y=None, frac=f)
    r, y = round_out(s, f, cfg)
    return CoreResult(s=s, r=r, y=y, frac=f)


def _ffc_term(ffc: object | None, cfg: PipelineConfig, f: int, shape: tuple[int, ...]
              ) -> np.ndarray | int:
    if ffc is None:
        return 0
    d = coeff(cfg, "ffc", ffc, "ffc_offset")
    if d.shape != shape[len(shape) - d.ndim:]:
        raise InputError(f"ffc_offset has shape {d.shape}; the frames are {shape}")
    return d << (f - cfg.format("ffc").frac_bits)


def drift_sub(x: object, delta: object, cfg: PipelineConfig | str) -> np.ndarray:
    """``drift_sub``: x' = (x << Df) - delta, signed, Df fraction bits (blind_drift).

    Parameters
    ----------
    x : integer array_like, (H, W) or (N, H, W)
        Raw ADC codes in [0, 2^A - 1].
    delta : int, or (N,) integers with a stack
        The frame's drift code (format ``drift``: signed, Df fraction bits, ADC codes).
    """
    cfg = as_config(cfg)
    xa = int_array("x", x, 0, (1 << cfg.adc_bits) - 1).astype(np.int64)
    d = coeff(cfg, "drift", delta, "delta")
    if d.ndim:
        if xa.ndim != 3 or d.shape != (xa.shape[0],):
            raise InputError(f"delta has shape {d.shape}; one per frame of x {xa.shape}")
        d = d[:, None, None]
    return (xa << cfg.format("drift").frac_bits) - d


def lin_core(x: object, gain: object, offset: object, cfg: PipelineConfig | str, *,
             xfrac: int = 0, signed_x: bool = False, ffc: object | None = None,
             sum_only: bool = False) -> CoreResult:
    """``lin_core``: y = OUT(ROUND_F(x*g << (F - Gf - Xf) + o << (F - Of) [+ d << (F - Cf)])).

    With ``xfrac = 0`` and no ``ffc`` this is ``nuc_core`` bit for bit.

    Parameters
    ----------
    x : integer array_like
        Input codes with ``xfrac`` fraction bits: raw codes, x' of :func:`drift_sub`
        (``signed_x``) or the FFC accumulator.
    gain, offset : integer array_like
        Gain codes (U Gi.Gf) and offset codes (S Oi.Of), of the frame's shape (or
        broadcastable to it: one_point's global gain is a scalar).
    ffc : integer array_like, optional
        FFC offset correction codes (format ``ffc``), added to the sum.
    sum_only : bool
        Return only the aligned sum (the FFC refresh pass).
    """
    cfg = as_config(cfg)
    xa = _x(x, xfrac, cfg, signed_x)
    g = coeff(cfg, "gain", gain)
    o = coeff(cfg, "offset", offset)
    f = core_frac(cfg, xfrac, ffc is not None)
    s = ((xa * g) << (f - cfg.gain_frac_bits - xfrac)) + (o << (f - cfg.offset_frac_bits))
    s = s + _ffc_term(ffc, cfg, f, s.shape)
    return _finish(s, f, cfg, sum_only)


def quad_core(x: object, gain: object, offset: object, quad: object,
              cfg: PipelineConfig | str, *, xfrac: int = 0, ffc: object | None = None,
              sum_only: bool = False) -> CoreResult:
    """``quad_core``: the sum of :func:`lin_core` plus the quadratic term.

    xsq = x*x; xq = xsq >> (2*Xf + Sq) (floor; Sq = max(0, 2A - square_bits), so xq has at
    most square_bits bits); qp = q*xq with QPf = Qf + 2A - Sq fraction bits; qs = qp at F
    fraction bits (a floor shift when QPf > F). The value of the term is
    q * (x / 2^A)^2 output codes.
    """
    cfg = as_config(cfg)
    xa = _x(x, xfrac, cfg, False)
    g = coeff(cfg, "gain", gain)
    o = coeff(cfg, "offset", offset)
    q = coeff(cfg, "quad", quad)
    f = core_frac(cfg, xfrac, ffc is not None)
    sq = square_shift(cfg)
    xq = (xa * xa) >> (2 * xfrac + sq)
    qpf = cfg.format("quad").frac_bits + 2 * cfg.adc_bits - sq
    s = (((xa * g) << (f - cfg.gain_frac_bits - xfrac)) + (o << (f - cfg.offset_frac_bits))
         + _align(q * xq, qpf, f))
    s = s + _ffc_term(ffc, cfg, f, s.shape)
    return _finish(s, f, cfg, sum_only)


def pwl_core(x: object, gain_lo: object, gain_hi: object, knee: object, level: int,
             cfg: PipelineConfig | str, *, xfrac: int = 0, ffc: object | None = None,
             sum_only: bool = False) -> CoreResult:
    """``pwl_core``: two linear segments meeting at the pixel's knee.

    D = max(Kf, Xf); d = (x << (D - Xf)) - (k << (D - Kf)); g = gain_lo if d <= 0 else
    gain_hi; s = (d*g << (F - Gf - D)) + (level << (F - Lf)) [+ ffc << (F - Cf)].
    """
    cfg = as_config(cfg)
    xa = _x(x, xfrac, cfg, False)
    glo = coeff(cfg, "gain", gain_lo, "gain_lo")
    ghi = coeff(cfg, "gain", gain_hi, "gain_hi")
    k = coeff(cfg, "knee", knee)
    lvl = int(coeff(cfg, "level", level))
    kf = cfg.format("knee").frac_bits
    dd = max(kf, xfrac)
    f = core_frac(cfg, xfrac, ffc is not None)
    d = (xa << (dd - xfrac)) - (k << (dd - kf))
    g = np.where(d <= 0, glo, ghi)
    s = ((d * g) << (f - cfg.gain_frac_bits - dd)) + (lvl << (f - cfg.format("level").frac_bits))
    s = s + _ffc_term(ffc, cfg, f, s.shape)
    return _finish(s, f, cfg, sum_only)


def _lin(x: object, fc: Mapping[str, Any], cfg: PipelineConfig, *, signed_x: bool = False,
         **kw: Any) -> CoreResult:
    return lin_core(x, fc["gain"], fc["offset"], cfg, signed_x=signed_x, **kw)


def _quad(x: object, fc: Mapping[str, Any], cfg: PipelineConfig, *, signed_x: bool = False,
          **kw: Any) -> CoreResult:
    return quad_core(x, fc["gain"], fc["offset"], fc["quad"], cfg, **kw)


def _pwl(x: object, fc: Mapping[str, Any], cfg: PipelineConfig, *, signed_x: bool = False,
         **kw: Any) -> CoreResult:
    return pwl_core(x, fc["gain_lo"], fc["gain_hi"], fc["knee"], int(fc["level"]), cfg, **kw)


#: The inputs of each core kind, in the order the fused kernels take them: (name in the
#: frame's coefficients, its format).
CORE_INPUTS: dict[str, tuple[tuple[str, str], ...]] = {
    "lin": (("gain", "gain"), ("offset", "offset")),
    "quad": (("gain", "gain"), ("offset", "offset"), ("quad", "quad")),
    "pwl": (("gain_lo", "gain"), ("gain_hi", "gain"), ("knee", "knee"), ("level", "level")),
}
#: The kind codes of the fused kernels (``_fused_kernels.core_sum``).
KIND_CODES = {"lin": 0, "quad": 1, "pwl": 2}


def kernel_shifts(cfg: PipelineConfig, xfrac: int, with_ffc: bool
                  ) -> tuple[int, list[int], int]:
    """(F, the shifts of the core of ``cfg``'s kind as the fused kernel takes them
    (``_fused_kernels.core_sum``), the FFC term's shift F - Cf (0 without it)) for an input
    with ``xfrac`` fraction bits: the alignments of :func:`lin_core`, :func:`quad_core` and
    :func:`pwl_core`."""
    kind = cfg.base.core
    f = core_frac(cfg, xfrac, with_ffc)
    csh = f - cfg.format("ffc").frac_bits if with_ffc else 0
    if kind == "pwl":
        kf = cfg.format("knee").frac_bits
        dd = max(kf, xfrac)
        return f, [dd - xfrac, dd - kf, f - cfg.gain_frac_bits - dd,
                   f - cfg.format("level").frac_bits], csh
    out = [f - cfg.gain_frac_bits - xfrac, f - cfg.offset_frac_bits]
    if kind == "quad":
        sq = square_shift(cfg)
        qpf = cfg.format("quad").frac_bits + 2 * cfg.adc_bits - sq
        out += [2 * xfrac + sq, max(0, f - qpf), max(0, qpf - f)]
    return f, out, csh


#: The cores by kind (``MethodSpec.core``), each on the frame's coefficients of a method
#: (``MethodSpec.frame_coefficients``): lin (``lin_core``: gain, offset), quad
#: (``quad_core``: gain, offset, quad), pwl (``pwl_core``: gain_lo, gain_hi, knee, level).
#: Only the linear core takes a signed input (x' of blind_drift).
CORES: dict[str, Callable[..., CoreResult]] = {"lin": _lin, "quad": _quad, "pwl": _pwl}
