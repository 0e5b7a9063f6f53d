"""The streams, golden frames and scoreboard of the stage tops (docs/rtl.md "Stages"):
``method_drift_top`` (one_point / two_point + blind_drift) and ``method_ffc_top`` (every
base method + ffc).

The pixel and coefficient streams are those of ``method_dpc_top`` for the base method
(:mod:`irnuc.cosim.stream`); the stages add theirs:

* ``s_blind`` (blind_drift): per frame its blind codes, or partial sums of them, the last
  flagged; :func:`blind_items` makes them, :func:`blind_codes_for` gives the golden model
  codes of the same sum;
* the FFC streams and sequencing: :mod:`irnuc.cosim.ffc_seq`.

The golden model is ``nuc_fixed.method_top`` frame by frame (blind_drift has no state
between frames); :class:`StageScoreboard` is the method scoreboard with the stage's values
in its triage lines (the frame's drift code, x' = (x << Df) - delta and the core's sum on
it).
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass

import numpy as np

from irnuc.cosim.methods import MethodFrame, MethodScoreboard
from irnuc.cosim.stream import frame_drive
from irnuc.nuc_fixed.config import PipelineConfig
from irnuc.nuc_fixed.cores import drift_sub, lin_core
from irnuc.nuc_fixed.method_top import FrameInputs, MethodCoefficients, frame_coefficients, method_top

__all__ = ["DriftFrame", "StageScoreboard", "blind_codes_for", "blind_items", "drift_frames"]


@dataclass(frozen=True)
class DriftFrame(MethodFrame):
    """A frame of ``method_drift_top``: a :class:`~irnuc.cosim.methods.MethodFrame` and its
    blind items (``s_blind``, the last flagged), the golden codes of the same sum and the
    frame's drift code."""

    blind: np.ndarray | None = None
    blind_codes: np.ndarray | None = None
    delta: int = 0


def blind_codes_for(total: int, cfg: PipelineConfig) -> np.ndarray:
    """Blind codes (each in [0, 2^A - 1], at most ``blind_max``) that sum to ``total``: the
    golden model's view of a frame whose blind items are partial sums."""
    top = (1 << cfg.adc_bits) - 1
    k = max(1, -(-int(total) // top))
    if k > int(cfg.blind_max or 1) or total < 0:
        raise ValueError(f"a blind sum of {total} needs {k} codes; blind_max is {cfg.blind_max}")
    codes = np.full(k, top, dtype=np.int64)
    codes[-1] = int(total) - top * (k - 1)
    return codes


def blind_items(codes: np.ndarray, cfg: PipelineConfig, rng: np.random.Generator,
                kind: str = "codes") -> np.ndarray:
    """The ``s_blind`` items of a frame with these blind codes: the codes themselves, one
    item holding their sum (``sum``: the register path), or random partial sums
    (``partial``)."""
    codes = np.asarray(codes, dtype=np.int64).ravel()
    if kind == "codes":
        return codes
    if kind == "sum":
        return np.array([int(codes.sum())], dtype=np.int64)
    cuts = np.sort(rng.choice(np.arange(1, codes.size), size=min(3, codes.size - 1),
                              replace=False)) if codes.size > 1 else np.array([], int)
    return np.array([int(p.sum()) for p in np.split(codes, cuts)], dtype=np.int64)


def drift_frames(coeffs: MethodCoefficients, raws: list[np.ndarray], blinds: list[np.ndarray],
                 golden: PipelineConfig | None = None) -> list[DriftFrame]:
    """Frames (each (H, W)) with their ``s_blind`` items, corrected by the golden model
    (``golden``: another configuration to check against on purpose)."""
    cfg = coeffs.cfg
    g = coeffs if golden is None else MethodCoefficients(golden, coeffs.fields,
                                                         coeffs.registers)
    out = []
    for raw, items in zip(raws, blinds, strict=True):
        codes = blind_codes_for(int(np.sum(items)), cfg)
        res = method_top(np.asarray(raw)[None], g, FrameInputs(blind_codes=codes[None]))
        out.append(DriftFrame(raw=np.asarray(raw), coeffs=coeffs, reading=None,
                              drive=frame_drive(coeffs), expected=res.y[0].astype(np.int64),
                              blind=np.asarray(items, dtype=np.int64), blind_codes=codes,
                              delta=int(res.delta[0])))  # type: ignore[index]
    return out


class StageScoreboard(MethodScoreboard):
    """The method scoreboard of a stage top: data, sof and eol of every output pixel, a
    triage line with the stage's values (blind_drift: delta, x' and the core's sum on x')."""

    def _describe(self, index: int, got: Mapping[str, int]) -> str:
        line = super()._describe(index, got)
        f = int(np.searchsorted(self._starts, index, side="right")) - 1
        fr = self._frames[f]
        if not isinstance(fr, DriftFrame):
            return line
        w = fr.raw.shape[1]
        off = index - self._starts[f]
        x, y = off % w, off // w
        cfg = self.golden
        c = MethodCoefficients(cfg, fr.coeffs.fields, fr.coeffs.registers)
        fc = frame_coefficients(c, None)
        g = np.asarray(fc["gain"])
        g = g[y, x] if g.ndim == 2 else g
        xd = drift_sub(fr.raw[y:y + 1, x:x + 1], fr.delta, cfg)
        res = lin_core(xd, g, fc["offset"][y:y + 1, x:x + 1], cfg,
                       xfrac=cfg.format("drift").frac_bits, signed_x=True)
        return (f"{line} | blind_drift: delta {fr.delta} x' {int(xd.ravel()[0])} s' "
                f"{int(res.s.ravel()[0])} r' {int(res.r.ravel()[0])} (F = {res.frac})")
