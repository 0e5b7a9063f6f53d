"""The streams, golden frames and scoreboard of the stage tops (docs/rtl.md "Stages"):
``method_drift_top`` (one_point / two_point + blind_drift) and ``method_ffc_top`` (every
base method + ffc).

The pixel and coefficient streams are those of ``method_dpc_top`` for the base method
(:mod:`irnuc.cosim.stream`); the stages add theirs:

* ``s_blind`` (blind_drift): per frame its blind codes, or partial sums of them, the last
  flagged; :func:`blind_items` makes them, :func:`blind_codes_for` gives the golden model
  codes of the same sum;
* ``method_ffc_top``: ``s_foff`` (the offset correction in effect, every frame),
  ``s_acc`` (the accumulator, in the frames that add to it and in the refresh frame),
  ``m_acc`` and ``m_foff`` (the new accumulator and the new corrections), and the frames
  held (no output); :func:`ffc_run` makes them from one run of the golden model over the
  sequence.

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
from irnuc.nuc_fixed.ffc import FfcState
from irnuc.nuc_fixed.method_top import FrameInputs, MethodCoefficients, frame_coefficients, method_top

__all__ = ["DriftFrame", "FfcRun", "StageScoreboard", "blind_codes_for", "blind_items",
           "drift_frame_from_sum", "drift_frames", "ffc_run"]


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


def drift_frame_from_sum(coeffs: MethodCoefficients, raw: np.ndarray, inputs: FrameInputs,
                         golden: PipelineConfig | None = None) -> DriftFrame:
    """A frame whose blind sum comes as a register holds it (``inputs.blind_sums``,
    irnuc_axis_top's BLIND_SUM), corrected by the golden model (``golden``: another
    configuration to check against on purpose)."""
    g = coeffs if golden is None else MethodCoefficients(golden, coeffs.fields,
                                                         coeffs.registers)
    raw = np.asarray(raw)
    res = method_top(raw[None], g, inputs)
    return DriftFrame(raw=raw, coeffs=coeffs, reading=None, drive=frame_drive(coeffs),
                      expected=res.y[0].astype(np.int64),
                      blind=np.asarray(inputs.blind_sums, dtype=np.int64),
                      delta=int(res.delta[0]))  # type: ignore[index]


class StageScoreboard(MethodScoreboard):
    """The method scoreboard of a stage top: data, sof and eol of every output pixel, a
    triage line with the stage's values (blind_drift: delta, x' and the core's sum on x')."""

    def _describe(self, index: int, got: Mapping[str, int]) -> str:
        line = super()._describe(index, got)
        f = int(np.searchsorted(self._starts, index, side="right")) - 1
        fr = self._frames[f]
        if not isinstance(fr, DriftFrame):
            if self.golden.has("ffc"):
                return f"{line} | ffc: the golden s above is without the FFC term"
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


@dataclass(frozen=True)
class FfcRun:
    """A sequence of frames for ``method_ffc_top`` and the golden model's view of it.

    ``frames`` are the sequence's frames (``expected``: the golden output, or the repeated
    frame where it is held); ``held`` marks the frames with no output; ``foff_in`` and
    ``acc_in`` are the per-frame words of ``s_foff`` and ``s_acc`` (None: the frame reads
    no accumulator); ``acc_out`` and ``foff_out`` the expected ``m_acc`` and ``m_foff``
    words (None: none in that frame); ``targets`` the targets of the mean passes; ``kept``
    the mean passes (by frame index) without a good pixel, whose refresh kept the
    corrections.
    """

    frames: list[MethodFrame]
    shutter: np.ndarray
    held: np.ndarray
    foff_in: list[np.ndarray]
    acc_in: list[np.ndarray | None]
    acc_out: list[np.ndarray | None]
    foff_out: list[np.ndarray | None]
    targets: tuple[int, ...]
    kept: tuple[int, ...] = ()


def ffc_run(coeffs: MethodCoefficients, raws: list[np.ndarray], shutter: list[bool],
            readings: list[int | None] | None = None,
            golden: PipelineConfig | None = None,
            offset: np.ndarray | None = None) -> FfcRun:
    """The streams and expected outputs of a sequence of frames (each (H, W), one
    calibration) with these shutter flags and FPA readings (tc_offset), from one run of
    ``nuc_fixed.method_top`` over the whole sequence (``golden``: another configuration to
    check against on purpose; ``offset``: the corrections in the host's memory at the
    start, default 0).

    The accumulator words come from the golden model's sequencer
    (:class:`~irnuc.nuc_fixed.ffc.FfcState`), the refreshed corrections from
    ``MethodOutput.offsets`` (the k-th used from the frame after the k-th mean pass on; a
    mean pass in the last frame has no refresh frame here).
    """
    g = coeffs if golden is None else MethodCoefficients(golden, coeffs.fields,
                                                         coeffs.registers)
    x = np.stack([np.asarray(r, dtype=np.int64) for r in raws])
    sh = np.asarray(shutter, dtype=bool)
    rd = list(readings) if readings is not None else [None] * x.shape[0]
    offset = (np.zeros(x.shape[1:], np.int64) if offset is None
              else np.asarray(offset, dtype=np.int64))
    res = method_top(x, g, FrameInputs(
        shutter=sh, reading=None if rd[0] is None else np.asarray(rd, dtype=np.int64)),
        ffc_offset=offset)
    state = FfcState(cfg=g.cfg, offset=offset)
    acc_in: list[np.ndarray | None] = []
    acc_out: list[np.ndarray | None] = []
    foff_in: list[np.ndarray] = []
    foff_out: list[np.ndarray | None] = []
    pending: np.ndarray | None = None  # the accumulator of a mean pass, for its refresh
    k = 0
    frames = []
    for i in range(x.shape[0]):
        foff_in.append(offset)
        read = pending
        if pending is not None:
            offset = res.offsets[k]
            foff_out.append(offset)
            k += 1
            pending = None
        else:
            foff_out.append(None)
        before = None if state.acc is None else np.array(state.acc)
        count = state.count
        done = state.step(x[i], bool(sh[i]))
        added = bool(sh[i]) and state.count == count + 1
        if added and count > 0:
            read = before
        acc_in.append(read)
        acc_out.append(np.array(state.acc) if added else None)
        if done:
            pending = np.array(state.acc)
        frames.append(MethodFrame(raw=x[i], coeffs=coeffs, reading=rd[i],
                                  drive=frame_drive(coeffs, rd[i]),
                                  expected=np.asarray(res.y[i], dtype=np.int64)))
    held = np.zeros(x.shape[0], bool) if res.held is None else np.asarray(res.held, bool)
    return FfcRun(frames=frames, shutter=sh, held=held, foff_in=foff_in, acc_in=acc_in,
                  acc_out=acc_out, foff_out=foff_out, targets=tuple(res.targets),
                  kept=tuple(res.kept))
