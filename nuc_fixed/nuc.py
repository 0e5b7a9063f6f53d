"""``nuc_core``: the two-point NUC datapath, bit-exact to ``docs/datapath.md``."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from irnuc.nuc_fixed import _kernels
from irnuc.nuc_fixed.config import PipelineConfig
from irnuc.nuc_fixed.fixed import gain_format, offset_format
from irnuc.nuc_fixed.validate import InputError, as_config, int_array


@dataclass(frozen=True)
class NucIntermediates:
    """Every stage of the NUC datapath (int64 arrays of the shape of ``x``).

    Attributes
    ----------
    y : corrected code, B bits unsigned (step 6).
    p : product x * g (step 1).
    s : aligned sum (x*g << (F-Gf)) + (o << (F-Of)) (step 4).
    r : rounded sum ROUND_F(s) (step 5), before saturation or wrap.
    """

    y: np.ndarray
    p: np.ndarray
    s: np.ndarray
    r: np.ndarray


def out_dtype(cfg: PipelineConfig) -> type[np.unsignedinteger]:
    """Smallest unsigned dtype of the corrected codes: uint16 up to 16 bits, else uint32."""
    return np.uint16 if cfg.out_bits <= 16 else np.uint32


def datapath_constants(cfg: PipelineConfig) -> tuple[int, int, int, int, bool, int]:
    """Kernel constants: gain shift F-Gf, offset shift F-Of, F, rounding code, wrap, 2^B-1."""
    f = cfg.frac_bits
    return (
        f - cfg.gain_frac_bits,
        f - cfg.offset_frac_bits,
        f,
        cfg.rounding_code,
        cfg.overflow == "wrap",
        (1 << cfg.out_bits) - 1,
    )


def check_coefficients(
    gain: object, offset: object, cfg: PipelineConfig
) -> tuple[np.ndarray, np.ndarray]:
    """Validate gain (unsigned Gi.Gf codes) and offset (signed Oi.Of codes) of one shape."""
    gf, of = gain_format(cfg), offset_format(cfg)
    g = int_array("gain", gain, gf.min_code, gf.max_code)
    o = int_array("offset", offset, of.min_code, of.max_code)
    if g.shape != o.shape:
        raise InputError(
            f"gain has shape {g.shape} but offset has shape {o.shape}; they must match"
        )
    return g, o


def _prepare(x: object, gain: object, offset: object, cfg: PipelineConfig):
    g, o = check_coefficients(gain, offset, cfg)
    xa = int_array("x", x, 0, (1 << cfg.adc_bits) - 1)
    if xa.shape != g.shape and xa.shape[xa.ndim - g.ndim:] != g.shape:
        raise InputError(
            f"x has shape {xa.shape} but gain/offset have shape {g.shape}; x must have the "
            "same shape, or be a stack whose trailing axes are that shape"
        )
    n_pix = g.size
    x2 = np.ascontiguousarray(xa).reshape(-1, n_pix) if n_pix else xa.reshape(0, 0)
    return xa.shape, x2, np.ascontiguousarray(g).reshape(-1), np.ascontiguousarray(o).reshape(-1)


def nuc_core(
    x: np.ndarray,
    gain: np.ndarray,
    offset: np.ndarray,
    cfg: PipelineConfig | str,
    intermediates: bool = False,
) -> np.ndarray | NucIntermediates:
    """Two-point NUC of raw codes, bit-exact to the ``nuc_core`` RTL module.

    Parameters
    ----------
    x : integer array_like
        Raw ADC codes in [0, 2^A - 1]; same shape as ``gain``, or a stack of frames whose
        trailing axes have that shape.
    gain : integer array_like
        Gain codes, unsigned Gi.Gf, in [0, 2^GW - 1].
    offset : integer array_like
        Offset codes, two's complement Oi.Of, in [-2^(OW-1), 2^(OW-1) - 1].
    cfg : PipelineConfig or str
        Pipeline configuration (or its name in ``pipelines.toml``).
    intermediates : bool
        Return :class:`NucIntermediates` (int64 y, p, s, r) instead of y.

    Returns
    -------
    ndarray or NucIntermediates
        Corrected codes of the shape of ``x``: uint16 if B <= 16 else uint32.
    """
    cfg = as_config(cfg)
    shape, x2, g, o = _prepare(x, gain, offset, cfg)
    k = datapath_constants(cfg)
    if intermediates:
        arrs = [np.empty(x2.shape, dtype=np.int64) for _ in range(4)]
        if x2.size:
            _kernels.nuc_flat_intermediates(x2, g, o, *arrs, *k)
        p, s, r, y = (a.reshape(shape) for a in arrs)
        return NucIntermediates(y=y, p=p, s=s, r=r)
    out = np.empty(x2.shape, dtype=out_dtype(cfg))
    if x2.size:
        _kernels.nuc_flat(x2, g, o, out, *k)
    return out.reshape(shape)


def widths(cfg: PipelineConfig | str) -> dict[str, int]:
    """Every intermediate width of the NUC datapath (docs/datapath.md, bits)."""
    cfg = as_config(cfg)
    f = cfg.frac_bits
    return {
        "x (A, unsigned)": cfg.adc_bits,
        "gain GW (unsigned)": cfg.gain_bits,
        "offset OW (signed)": cfg.offset_bits,
        "F = max(Gf, Of)": f,
        "p = x*g, PW (unsigned)": cfg.product_bits,
        "ps = p << (F-Gf) (unsigned)": cfg.adc_bits + cfg.gain_int_bits + f,
        "os = o << (F-Of) (signed)": cfg.offset_int_bits + f,
        "s, SW (signed)": cfg.sum_bits,
        "r = ROUND_F(s) (signed)": cfg.sum_bits + 1 - f,
        "y, B (unsigned)": cfg.out_bits,
        "coefficient word WW": cfg.word_bits,
    }

