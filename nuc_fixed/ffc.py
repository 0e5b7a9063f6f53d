"""``ffc``: flat-field (shutter) offset refresh, bit-exact to ``docs/datapath.md``.

While the shutter is closed the array sees a uniform source. The FFC unit adds the raw
codes of N = 2^n shutter frames per pixel into an accumulator of A + n bits
(:func:`ffc_accumulate`); after the N-th frame the target is taken (the mean pass,
:func:`ffc_mean_target`), and in the next frame (the refresh pass) it evaluates the base
method's sum on the accumulator (the mean of the N frames with n fraction bits: the same
core with its input widened by n bits, coefficients of that frame) and writes, per pixel,
the offset correction that brings that pixel to the target level (:func:`ffc_refresh`).
The correction is added to the sum of every frame from that one on. The
frames while the shutter is closed are held (the last corrected frame is repeated) or
passed, as ``ffc_output`` says (:class:`FfcState` models the sequencing).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np

from irnuc.nuc_fixed.config import PipelineConfig
from irnuc.nuc_fixed.cores import code_range
from irnuc.nuc_fixed.fixed import apply_overflow, round_div, round_shift
from irnuc.nuc_fixed.validate import InputError, as_config, int_array
from irnuc.nuc_fixed.widths import ffc_shift


def ffc_accumulate(acc: np.ndarray | None, x: object, cfg: PipelineConfig | str) -> np.ndarray:
    """``ffc_acc``: acc + x (acc = x for the first shutter frame, ``acc is None``).

    The accumulator holds A + n bits (n = log2 ffc_frames) and cannot overflow within N
    frames; adding more is an error.
    """
    cfg = as_config(cfg)
    xa = int_array("x", x, 0, (1 << cfg.adc_bits) - 1).astype(np.int64)
    out = xa.copy() if acc is None else np.asarray(acc, dtype=np.int64) + xa
    top = ((1 << cfg.adc_bits) - 1) << ffc_shift(cfg)
    if out.size and int(out.max()) > top:
        raise InputError(f"ffc accumulator exceeds {top}: more than ffc_frames = "
                         f"{cfg.ffc_frames} frames were added")
    return out


def refresh_frac(cfg: PipelineConfig, sum_frac: int) -> int:
    """F' = max(F_refresh, Cf): the fraction bits the refresh subtracts at."""
    return max(sum_frac, cfg.format("ffc").frac_bits)


def ffc_refresh(s_acc: np.ndarray, sum_frac: int, target: int,
                cfg: PipelineConfig | str) -> np.ndarray:
    """``ffc_refresh``: delta = OVF_C(ROUND_(F' - Cf)((T << (F' - Cf)) - (s << (F' - F)))).

    Parameters
    ----------
    s_acc : int64 array (H, W)
        The base method's sum evaluated on the accumulator (``sum_frac`` = F fraction
        bits), without an FFC term.
    target : int
        The target level T (unsigned, B integer and Cf fraction bits, output codes).

    Returns
    -------
    int64 array (H, W): offset correction codes of the ``ffc`` format (its rounding and
    overflow).
    """
    cfg = as_config(cfg)
    c = cfg.format("ffc")
    t = int(int_array("target", target, 0, (1 << (cfg.out_bits + c.frac_bits)) - 1))
    fr = refresh_frac(cfg, sum_frac)
    diff = (np.int64(t) << (fr - c.frac_bits)) - (np.asarray(s_acc, np.int64) << (fr - sum_frac))
    r = np.asarray(round_shift(np.ascontiguousarray(diff), fr - c.frac_bits, c.rounding),
                   dtype=np.int64)
    lo, hi = code_range(cfg, "ffc")
    return np.asarray(apply_overflow(r, lo, hi, c.overflow), dtype=np.int64)


def ffc_mean_target(s_acc: np.ndarray, sum_frac: int, good: np.ndarray,
                    cfg: PipelineConfig | str) -> int | None:
    """The target that keeps the shutter image's level: the mean over good pixels.

    T = CLAMP(RDIV(sum over good pixels of ROUND_(F - Cf)(s), n_good), 0, 2^(B + Cf) - 1),
    rounding half up, ROUND with the ffc format's rounding (a pass over the accumulator
    before the refresh pass, one division per FFC). None when no pixel is good
    (n_good = 0): there is no target, and the refresh keeps the previous offsets
    (docs/datapath.md "ffc"; the RTL's target register then reads 0).
    """
    cfg = as_config(cfg)
    c = cfg.format("ffc")
    fr = refresh_frac(cfg, sum_frac)
    s = np.asarray(s_acc, np.int64) << (fr - sum_frac)
    v = np.asarray(round_shift(np.ascontiguousarray(s), fr - c.frac_bits, c.rounding))
    g = np.asarray(good, bool)
    n = int(g.sum())
    return mean_from_sum(int(v[g].sum()) if n else 0, n, cfg)


def mean_from_sum(total: int, n_good: int, cfg: PipelineConfig) -> int | None:
    """The last step of :func:`ffc_mean_target`: T = CLAMP(RDIV(total, n_good)) from the sum
    of the good pixels' rounded values (None without a good pixel)."""
    if n_good == 0:
        return None
    t = round_div(total, n_good, "half_up")
    return min(max(t, 0), (1 << (cfg.out_bits + cfg.format("ffc").frac_bits)) - 1)


@dataclass
class FfcState:
    """The FFC sequencer: accumulation count, accumulator and the offset correction.

    Per frame (:meth:`step`): a shutter frame is accumulated while fewer than N frames of
    the current shutter run were; after the N-th the refresh pass runs in the next frame,
    and its new correction corrects that frame and the frames after it. A shutter run
    shorter than N leaves the correction as it was. A frame with the shutter open ends the
    run.
    """

    cfg: PipelineConfig
    offset: np.ndarray
    count: int = 0
    acc: np.ndarray | None = None
    refreshes: list[int] = field(default_factory=list)
    #: How a frame is added (:func:`ffc_accumulate`; the fused path's adds in place).
    add: Callable[[np.ndarray | None, np.ndarray, PipelineConfig], np.ndarray] = \
        field(default=lambda acc, x, cfg: ffc_accumulate(acc, x, cfg))

    def step(self, x: np.ndarray, shutter: bool) -> bool:
        """Take one raw frame; True when the accumulator is complete (refresh now)."""
        if not shutter:
            self.count = 0
            self.acc = None
            return False
        n = int(self.cfg.ffc_frames or 1)
        if self.count >= n:
            return False
        self.acc = self.add(self.acc if self.count else None, x, self.cfg)
        self.count += 1
        return self.count == n
