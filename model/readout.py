"""Readout: blind-pixel skimming and the integrator (paper section 3.5, Table 1).

The ROIC subtracts, from every active pixel, a reference from the blind (skimming)
bolometers, which see only their shield (at the housing or at the substrate temperature,
``fpa.skim_shield``) and so follow the substrate temperature without the scene. The
reference is taken per row (blind columns at the ends of the row), per column (blind rows
at the top and bottom) or is a fixed voltage (``none``).
The integrator turns the difference into a voltage around ``v_reset``; the readout is
inverting, so a hotter scene (lower resistance for a negative TCR) gives a higher output.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np

from irnuc.model.core.bolometer import STATUS_OK

Fallback = float | Callable[[], float]


def _blind_mean(values: np.ndarray, ok: np.ndarray, axis: int, fallback: Fallback) -> np.ndarray:
    """Mean over the blind pixels along ``axis``, leaving out pixels whose solve failed.

    ``fallback`` (V) replaces a reference whose blind pixels all failed; a callable is
    called only then (the nominal skim voltage costs a solve that is rarely needed).
    """
    if ok.all():
        return values.mean(axis=axis)
    w = ok.astype(np.float64)
    total = np.where(ok, values, 0.0).sum(axis=axis)
    count = w.sum(axis=axis)
    if (count > 0).all():
        return total / count
    fb = fallback() if callable(fallback) else fallback
    if np.ndim(fb):  # one value per frame: broadcast over the lines
        fb = np.reshape(fb, (-1,) + (1,) * (count.ndim - 1))
    return np.where(count > 0, total / np.maximum(count, 1.0), fb)


def skim_none(v_bolo, status, layout, v_skim: Fallback):
    """A fixed reference voltage for every pixel (one per frame when given per frame), V:
    shape (N, 1, 1)."""
    v = v_skim() if callable(v_skim) else v_skim
    if np.ndim(v):
        return np.asarray(v, dtype=np.float64).reshape(-1, 1, 1)
    return np.full((v_bolo.shape[0], 1, 1), v)


def skim_row(v_bolo, status, layout, v_skim: Fallback):
    """Per-row reference: mean of the blind columns of each active row, V: (N, H, 1)."""
    rows = layout.active_slice[0]
    cols = layout.blind_col_indices
    ref = _blind_mean(v_bolo[:, rows][:, :, cols], status[:, rows][:, :, cols] == STATUS_OK,
                      axis=2, fallback=v_skim)
    return ref[:, :, None]


def skim_column(v_bolo, status, layout, v_skim: Fallback):
    """Per-column reference: mean of the blind rows of each active column, V: (N, 1, W)."""
    cols = layout.active_slice[1]
    rows = layout.blind_row_indices
    ref = _blind_mean(v_bolo[:, rows][:, :, cols], status[:, rows][:, :, cols] == STATUS_OK,
                      axis=1, fallback=v_skim)
    return ref[:, None, :]


def line_reference(v_bolo, status, layout, mode: str, lines: np.ndarray,
                   v_skim: Fallback) -> np.ndarray:
    """The skimming reference of some full-array rows (``row``) or columns (``column``), V.

    The mean of the blind columns of each row in ``lines`` (row skimming) or of the blind
    rows of each column (column skimming), as :func:`skim_row` / :func:`skim_column` take
    it for the active lines; ``none`` gives ``v_skim`` (a float, an (N,) array or a
    callable). Returns (N, len(lines)).
    """
    n = v_bolo.shape[0]
    if mode == "none":
        fb = v_skim() if callable(v_skim) else v_skim
        return np.broadcast_to(np.reshape(fb, (-1, 1)), (n, len(lines))).astype(np.float64)
    if mode == "row":
        cols = layout.blind_col_indices
        vals = v_bolo[:, :, cols][:, lines]
        ok = status[:, :, cols][:, lines] == STATUS_OK
        return _blind_mean(vals, ok, axis=2, fallback=v_skim)
    rows = layout.blind_row_indices
    vals = v_bolo[:, rows][:, :, lines]
    ok = status[:, rows][:, :, lines] == STATUS_OK
    return _blind_mean(vals, ok, axis=1, fallback=v_skim)


#: Skimming modes, selected by name (paper Table 1: "rows" and "columns").
SKIMMING_MODES = {"none": skim_none, "row": skim_row, "column": skim_column}


def integrate(v_active: np.ndarray, v_ref: np.ndarray, gain: float, v_reset: float) -> np.ndarray:
    """Integrator output, V: ``v_reset + gain * (v_ref - v_active)`` (not yet clipped)."""
    v = np.subtract(v_ref, v_active)  # in place from here: one new array
    v *= gain
    v += v_reset
    return v
