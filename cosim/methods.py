"""Expected outputs and the scoreboard of ``method_dpc_top`` (every base method).

The golden model is ``nuc_fixed.method_top`` (the composition of the method's RTL modules
and ``dpc_core``), one frame at a time with the frame's FPA reading; the streams the RTL
takes are :mod:`irnuc.cosim.stream`. :class:`MethodScoreboard` is the one in-order
scoreboard (:class:`~irnuc.cosim.scoreboard.Scoreboard`) with a triage line per mismatching
pixel: frame, x, y, raw code, reading, the pixel's coefficient fields, the frame's gain
and offset (tc_offset, table_interp), expected, got, the markers and the golden core's
sum s, rounded r and NUC output.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass

import numpy as np

from irnuc.cosim.scoreboard import Scoreboard
from irnuc.cosim.stream import FrameDrive, frame_drive
from irnuc.nuc_fixed.config import PipelineConfig
from irnuc.nuc_fixed.method_top import (
    FrameInputs,
    MethodCoefficients,
    base_core,
    frame_coefficients,
    method_top,
)

__all__ = ["MethodFrame", "MethodScoreboard", "golden_frames"]


@dataclass(frozen=True)
class MethodFrame:
    """One frame of stimulus for ``method_dpc_top`` and its golden output.

    ``coeffs`` is the calibration the frame is corrected with, ``reading`` its FPA reading
    (tc_offset, table_interp; else None), ``drive`` the frame word and coefficient words.
    """

    raw: np.ndarray
    coeffs: MethodCoefficients
    reading: int | None
    drive: FrameDrive
    expected: np.ndarray


def golden_frames(coeffs: MethodCoefficients, raws: list[np.ndarray] | np.ndarray,
                  readings: list[int | None] | None = None,
                  golden: PipelineConfig | None = None) -> list[MethodFrame]:
    """Frames (each (H, W), of the coefficients' size) with their readings, corrected by
    the golden model (``golden``: another configuration to check against on purpose)."""
    raws = [np.asarray(r) for r in raws]
    readings = list(readings) if readings is not None else [None] * len(raws)
    g = coeffs if golden is None else MethodCoefficients(golden, coeffs.fields,
                                                         coeffs.registers)
    out = []
    for raw, rd in zip(raws, readings, strict=True):
        inputs = FrameInputs.of_frames([rd])
        y = method_top(raw[None], g, inputs).y[0]
        out.append(MethodFrame(raw=raw, coeffs=coeffs, reading=rd,
                               drive=frame_drive(coeffs, rd), expected=y.astype(np.int64)))
    return out


class MethodScoreboard(Scoreboard):
    """The scoreboard of ``method_dpc_top``: data, sof and eol of every output pixel."""

    def __init__(self, golden: PipelineConfig, max_report: int = 10) -> None:
        super().__init__(("data", "sof", "eol"), self._describe, max_report)
        self.golden = golden
        self._frames: list[MethodFrame] = []
        self._starts: list[int] = []

    def expect_frame(self, fr: MethodFrame) -> None:
        h, w = fr.raw.shape
        pos = np.arange(h * w)
        self._starts.append(self.n_expected)
        self._frames.append(fr)
        self.expect(data=fr.expected.ravel(), sof=(pos == 0).astype(np.int64),
                    eol=(pos % w == w - 1).astype(np.int64))

    def _describe(self, index: int, got: Mapping[str, int]) -> str:
        f = int(np.searchsorted(self._starts, index, side="right")) - 1
        fr = self._frames[f]
        w = fr.raw.shape[1]
        off = index - self._starts[f]
        x, y = off % w, off // w
        c = MethodCoefficients(self.golden, fr.coeffs.fields, fr.coeffs.registers)
        fields = {f"{m}.{k}": int(v[y, x]) for m, vals in c.fields.items()
                  for k, v in vals.items()}
        fc = frame_coefficients(c, fr.reading)
        one = {k: (np.asarray(v)[y:y + 1, x:x + 1] if np.ndim(v) == 2 else v)
               for k, v in fc.items()}
        px = MethodCoefficients(self.golden,
                                {m: {k: v[y:y + 1, x:x + 1] for k, v in vals.items()}
                                 for m, vals in c.fields.items()}, c.registers)
        res = base_core(px, one, fr.raw[y:y + 1, x:x + 1].astype(np.int64))
        # A method whose coefficients follow its readings: the frame's gain and offset.
        frame_gain = "" if not self.golden.base.readings else (
            f" frame gain {int(np.ravel(one['gain'])[0])} offset {int(np.ravel(one['offset'])[0])}")
        return (f"frame {f} x {x} y {y}: raw {int(fr.raw[y, x])} reading {fr.reading} "
                f"frame word {fr.drive.frame_word:#x} {fields}{frame_gain} | expected "
                f"{int(fr.expected[y, x])} got {got['data']} | sof {got['sof']} eol "
                f"{got['eol']} (expected {int(off == 0)}, {int(x == w - 1)}) | golden s "
                f"{int(res.s.ravel()[0])} r {int(res.r.ravel()[0])} y_nuc "
                f"{int(res.y.ravel()[0])} (F = {res.frac})")
