"""Directed stimulus: NUC corner codes and DPC bad-pixel patterns.

Every value is derived from the configuration's widths (``nuc_fixed.config``).
"""

from __future__ import annotations

from fractions import Fraction

import numpy as np

from irnuc.nuc_fixed import PipelineConfig


def corner_coefficients(cfg: PipelineConfig, rng: np.random.Generator
                        ) -> tuple[np.ndarray, np.ndarray, np.ndarray, list[str]]:
    """Raw codes, gain codes and offset codes of the NUC corner cases.

    Returns x, g, o (int64, same length) and the list of kinds covered: ``max_max``
    (largest code x largest gain), ``sat_high``/``sat_low`` (saturation or wrap at both
    ends) and ``tie`` (s exactly half-way between two integers, both parities).
    """
    a, gw, ow = cfg.adc_bits, cfg.gain_bits, cfg.offset_bits
    gi, gf, oi, of = (cfg.gain_int_bits, cfg.gain_frac_bits, cfg.offset_int_bits,
                      cfg.offset_frac_bits)
    f = cfg.frac_bits
    xmax, gmax = (1 << a) - 1, (1 << gw) - 1
    omin, omax = -(1 << (ow - 1)), (1 << (ow - 1)) - 1
    ymax = (1 << cfg.out_bits) - 1
    xs: list[int] = []
    gs: list[int] = []
    os_: list[int] = []
    kinds: list[str] = []

    def add(x: int, g: int, o: int, kind: str) -> None:
        xs.append(x)
        gs.append(g)
        os_.append(o)
        kinds.append(kind)

    # Extremes, full cross product.
    for x in (0, xmax):
        for g in (0, gmax):
            for o in sorted({v for v in (omin, -1, 0, 1, omax) if omin <= v <= omax}):
                add(x, g, o, "max_max" if (x, g) == (xmax, gmax) else "extreme")
    # The largest value reaches above 2^B - 1 only for some widths: claim it only then.
    top = Fraction(xmax * gmax, 1 << gf) + Fraction(omax, 1 << of)
    if top > ymax + 1:
        add(xmax, gmax, omax, "sat_high")
    add(0, 0, omin, "sat_low")  # value -2^(Oi-1) <= -1 rounds below zero in every mode

    if f > 0:
        xcap = max(1, min(xmax, 1 << cfg.out_bits))
        mlo, mhi = -(1 << (oi - 1)), (1 << (oi - 1)) - 1
        for i in range(32):
            # The last four ties get the most negative offset: s < 0 (visible in wrap
            # mode, 0 when saturating).
            if gf >= of:
                # g = (2k+1) 2^(Gf-1) with x odd: p has fraction exactly one half; the
                # offset is an integer, so s keeps that half.
                x = min(int(rng.integers(0, (xcap + 1) // 2)) * 2 + 1, xmax - 1 + xmax % 2)
                k = 0 if i % 2 == 0 else int(rng.integers(0, 1 << gi))
                g = (2 * k + 1) << (gf - 1)
                m = mlo if i >= 28 else max(mlo, min(mhi, int(rng.integers(-8, 9))))
                o = m << of
            else:
                # Integer gain (p has no fraction) and an offset of fraction one half.
                x = int(rng.integers(0, max(1, xcap // 2) + 1))
                g = min(1, (1 << gi) - 1) << gf
                m = mlo if i >= 28 else max(mlo, min(mhi, int(rng.integers(-4, 5))))
                o = (2 * m + 1) << (of - 1)
            add(x, g, o, "tie")
    arr = [np.asarray(v, dtype=np.int64) for v in (xs, gs, os_)]
    return arr[0], arr[1], arr[2], kinds


def dpc_bad_patterns(h: int, w: int) -> list[np.ndarray]:
    """Bad-pixel maps: border ring, corners, clusters, whole rows and columns, all bad,
    a random map, and the degenerate 1x1, 1xW and Hx1 frames."""
    maps: list[np.ndarray] = []

    def new(hh: int = h, ww: int = w) -> np.ndarray:
        return np.zeros((hh, ww), dtype=bool)

    b = new()
    b[0, :] = b[-1, :] = True
    b[:, 0] = b[:, -1] = True
    maps.append(b)  # border ring
    b = new()
    for r, c in ((0, 0), (0, w - 1), (h - 1, 0), (h - 1, w - 1)):
        b[r, c] = True
    if h > 1 and w > 1:
        b[1, 1] = b[0, 1] = True  # corner with a bad neighbour
    maps.append(b)  # corners
    b = new()
    b[1:4, 1:4] = True  # 3x3 cluster: its centre has n = 0 (uncorrectable)
    b[h - 2:, w - 2:] = True  # 2x2 cluster in the bottom-right corner
    b[h // 2, w // 2 - 1: w // 2 + 2] = True  # a short line
    maps.append(b)
    b = new()
    b[0, :] = True
    b[h // 2, :] = True
    b[-1, :] = True
    maps.append(b)  # whole rows
    b = new()
    b[:, 0] = b[:, w // 2] = b[:, -1] = True
    maps.append(b)  # whole columns
    maps.append(np.ones((h, w), dtype=bool))  # everything bad: all pass through
    rng = np.random.default_rng(h * 1000 + w)
    maps.append(rng.random((h, w)) < 0.3)
    maps.append(np.ones((1, 1), dtype=bool))
    b = new(1, w)
    b[0, ::2] = True
    maps.append(b)
    b = new(h, 1)
    b[1::2, 0] = True
    b[0, 0] = True
    maps.append(b)
    return maps


def neighbour_maps(h: int, w: int) -> list[np.ndarray]:
    """One bad map per (position, n): a bad pixel at a corner, an edge, the interior and
    in a one-pixel-wide frame with exactly n good in-frame neighbours, for every n the
    position allows (the frames are at most h x w, at least 3 x 3 where needed)."""
    maps: list[np.ndarray] = []
    hh, ww = max(3, min(h, 5)), max(3, min(w, 5))
    spots = {"corner": (0, 0), "edge": (0, ww // 2), "interior": (hh // 2, ww // 2)}
    for r, c in spots.values():
        nbs = [(r + dy, c + dx) for dy in (-1, 0, 1) for dx in (-1, 0, 1)
               if (dy, dx) != (0, 0) and 0 <= r + dy < hh and 0 <= c + dx < ww]
        for n in range(len(nbs) + 1):
            b = np.zeros((hh, ww), dtype=bool)
            b[r, c] = True
            for rr, cc in nbs[n:]:
                b[rr, cc] = True
            maps.append(b)
    ln = max(3, min(w, 5))
    for pos, n_bad in ((0, 0), (0, 1), (1, 0), (1, 1), (1, 2)):
        b = np.zeros((1, ln), dtype=bool)
        b[0, pos] = True
        nbs = [p for p in (pos - 1, pos + 1) if 0 <= p < ln]
        for p in nbs[:n_bad]:
            b[0, p] = True
        maps.append(b)
        maps.append(b.T.copy())
    return maps
