"""Golden model of the AXI4-Stream framing of ``irnuc_axis_top`` (``hdl/irnuc_axis_framer.sv``).

The video beats (tdata, tuser[0] = start of frame, tlast = end of line) are counted against
the programmed frame size; the core gets whole frames of that size (docs/integration.md,
"Frames and markers"):

* waiting for a frame, a beat without start of frame is dropped (``sof_late``, once per
  run of dropped beats);
* a start of frame inside a frame closes it with filler pixels (raw code 0) first
  (``sof_early``); an end of line before the line's last pixel completes the line with
  filler pixels (``eol_early``); no end of line on the line's last pixel ends the line
  there and drops the beats up to the next end of line (``eol_late``);
* coefficient words: one per pixel, fillers included; with ``coef_sync`` a word's tlast
  must mark its frame's last pixel: early, the frame's remaining pixels get the neutral
  word and take none (``coef_early``); late, the words up to the next tlast are dropped
  after the frame (``coef_late``);
* ``nuc_en = False``: unity gain (:func:`neutral_gain`) and zero offset; ``dpc_en = False``:
  the bad flag cleared.

:func:`axis_framer` turns the streams into the frames the core corrects
(:class:`CoreFrame`: raw codes and coefficient words) and the events the register file
counts; :func:`axis_top` adds the core (:func:`irnuc.nuc_fixed.nuc_dpc_top`) and gives the
output pixels of ``m_axis_video``. A transaction model: it follows the order of beats and
words, not cycles (the RTL's cycles do not change what it computes).
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field

import numpy as np

from irnuc.nuc_fixed.config import PipelineConfig
from irnuc.nuc_fixed.memimage import pack_words, unpack_words
from irnuc.nuc_fixed.top import nuc_dpc_top

#: The events counted by the register file (STATUS bits and *_ERRORS counters) and the
#: beat and frame counts (FRAMES_IN, PIXELS_IN, DROPPED, PADDED).
EVENTS = ("sof_early", "sof_late", "eol_early", "eol_late", "coef_early", "coef_late")
COUNTS = ("frames_in", "beats", "dropped", "padded")


@dataclass(frozen=True)
class FrameSettings:
    """The shadowed registers a frame starts with (CTRL, FRAME_SIZE)."""

    width: int
    height: int
    nuc_en: bool = True
    dpc_en: bool = True
    coef_sync: bool = True


@dataclass
class CoreFrame:
    """One frame as the core gets it: raw codes and coefficient words, (H, W)."""

    raw: np.ndarray
    words: np.ndarray
    settings: FrameSettings
    filler: np.ndarray  # bool (H, W): a filler pixel


@dataclass
class FramerResult:
    """Frames handed to the core, what was counted, and whether a frame is still open."""

    frames: list[CoreFrame]
    counts: dict[str, int] = field(default_factory=dict)
    open_frame: bool = False
    words_taken: int = 0


def neutral_gain(cfg: PipelineConfig) -> int:
    """The gain code of the neutral word: 1.0 (2^Gf) when the format holds it, else its
    largest code (U0.Gf)."""
    return (1 << cfg.gain_frac_bits) if cfg.gain_int_bits > 0 else (1 << cfg.gain_bits) - 1


def axis_framer(data: Sequence[int] | np.ndarray, sof: Sequence[int] | np.ndarray,
                eol: Sequence[int] | np.ndarray, words: Sequence[int] | np.ndarray,
                word_last: Sequence[int] | np.ndarray, settings: Sequence[FrameSettings],
                cfg: PipelineConfig) -> FramerResult:
    """The frames the core corrects from the beats of ``s_axis_video`` (``data``, ``sof`` =
    tuser[0], ``eol`` = tlast) and the words of ``s_axis_coef`` (``words``, ``word_last`` =
    tlast); ``settings[k]`` is what frame k starts with (the last one repeats).

    Every beat is used (the stream ends after the last one). Raises ``ValueError`` when the
    words run out before the last item.
    """
    data = np.asarray(data, dtype=np.int64).ravel()
    sof, eol = (np.asarray(a, dtype=bool).ravel() for a in (sof, eol))
    words = np.asarray(words, dtype=np.uint64).ravel()
    wlast = np.asarray(word_last, dtype=bool).ravel()
    if not settings:
        raise ValueError("axis_framer needs the settings of at least one frame")
    counts = dict.fromkeys((*EVENTS, *COUNTS), 0)
    frames: list[CoreFrame] = []
    gain_n = neutral_gain(cfg)
    neutral = int(pack_words(np.array([gain_n]), np.array([0]), np.array([False]), cfg)[0])

    st = {"j": 0, "fill": False}
    cur: dict = {}

    def open_frame() -> None:
        s = settings[min(counts["frames_in"], len(settings) - 1)]
        cur.update(s=s, raw=np.zeros((s.height, s.width), np.int64),
                   words=np.zeros((s.height, s.width), np.uint64),
                   filler=np.zeros((s.height, s.width), bool), x=0, y=0)
        counts["frames_in"] += 1

    def emit(raw: int, filler: bool) -> bool:
        """Send one item at the current position; True when it closed the frame."""
        s, x, y = cur["s"], cur["x"], cur["y"]
        last = x == s.width - 1 and y == s.height - 1
        if st["fill"]:
            word = neutral
            if last:
                st["fill"] = False
        else:
            j = st["j"]
            if j >= words.size:
                raise ValueError(f"the coefficient words ran out at frame {len(frames)} "
                                 f"x {x} y {y}")
            word, wl = int(words[j]), bool(wlast[j])
            st["j"] = j + 1
            if s.coef_sync and wl and not last:
                counts["coef_early"] += 1
                st["fill"] = True
            elif s.coef_sync and not wl and last:
                counts["coef_late"] += 1
                while st["j"] < words.size and not wlast[st["j"]]:
                    st["j"] += 1
                st["j"] = min(st["j"] + 1, words.size)
        g, o, b = (int(v[0]) for v in unpack_words(np.array([word], np.uint64), cfg))
        if not s.nuc_en:
            g, o = gain_n, 0
        if not s.dpc_en:
            b = 0
        cur["raw"][y, x] = raw
        cur["words"][y, x] = int(pack_words(np.array([g]), np.array([o]), np.array([bool(b)]),
                                            cfg)[0])
        cur["filler"][y, x] = filler
        if filler:
            counts["padded"] += 1
        if x == s.width - 1:
            cur["x"], cur["y"] = 0, y + 1
        else:
            cur["x"] = x + 1
        if last:
            frames.append(CoreFrame(cur["raw"], cur["words"], s, cur["filler"]))
            cur.clear()
        return last

    def pad(to_frame_end: bool) -> None:
        """Fillers up to the end of the line (or of the frame)."""
        while cur:
            at_line_end = cur["x"] == cur["s"].width - 1
            closed = emit(0, True)
            if closed or (at_line_end and not to_frame_end):
                return

    state, late, done = "wait", False, False
    i = 0
    while i < data.size:
        if state == "wait":
            if sof[i]:
                late = False
                open_frame()
                state = "frame"
                continue  # the beat is taken as the frame's first pixel below
            counts["dropped"] += 1
            counts["beats"] += 1
            if not late:
                counts["sof_late"] += 1
                late = True
            i += 1
        elif state == "frame":
            if sof[i] and (cur["x"], cur["y"]) != (0, 0):
                counts["sof_early"] += 1
                pad(to_frame_end=True)
                state = "wait"
                continue
            counts["beats"] += 1
            x_last = cur["x"] == cur["s"].width - 1
            y_last = cur["y"] == cur["s"].height - 1
            closed = emit(int(data[i]), False)
            if eol[i] and not x_last:
                counts["eol_early"] += 1
                pad(to_frame_end=False)
                state = "frame" if cur else "wait"
            elif not eol[i] and x_last:
                counts["eol_late"] += 1
                state, done = "drop", y_last
            else:
                state = "wait" if closed else "frame"
            i += 1
        else:  # drop
            if sof[i]:
                if not done:
                    counts["sof_early"] += 1
                    pad(to_frame_end=True)
                state = "wait"
                continue
            counts["dropped"] += 1
            counts["beats"] += 1
            if eol[i]:
                state = "wait" if done else "frame"
            i += 1
    return FramerResult(frames, counts, open_frame=bool(cur), words_taken=st["j"])


@dataclass
class AxisOutput:
    """The pixels of ``m_axis_video`` (``data``, ``sof`` = tuser[0], ``eol`` = tlast) of
    the frames the framer closed, and the framer's result."""

    data: np.ndarray
    sof: np.ndarray
    eol: np.ndarray
    framer: FramerResult


def axis_top(data: Sequence[int] | np.ndarray, sof: Sequence[int] | np.ndarray,
             eol: Sequence[int] | np.ndarray, words: Sequence[int] | np.ndarray,
             word_last: Sequence[int] | np.ndarray, settings: Sequence[FrameSettings],
             cfg: PipelineConfig) -> AxisOutput:
    """``irnuc_axis_top`` on whole streams: :func:`axis_framer`, then the core
    (:func:`irnuc.nuc_fixed.nuc_dpc_top`) frame by frame."""
    fr = axis_framer(data, sof, eol, words, word_last, settings, cfg)
    outs, sofs, eols = [], [], []
    for f in fr.frames:
        h, w = f.raw.shape
        outs.append(nuc_dpc_top(f.raw, f.words, cfg).astype(np.int64).ravel())
        pos = np.arange(h * w)
        sofs.append((pos == 0).astype(np.int64))
        eols.append((pos % w == w - 1).astype(np.int64))
    def cat(parts: list[np.ndarray]) -> np.ndarray:
        return np.concatenate(parts) if parts else np.zeros(0, np.int64)

    return AxisOutput(cat(outs), cat(sofs), cat(eols), fr)


def video_beats(frames: Sequence[np.ndarray]) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(data, sof, eol) of well-formed frames, each (H, W), one after the other."""
    data, sof, eol = [], [], []
    for f in frames:
        h, w = np.shape(f)
        pos = np.arange(h * w)
        data.append(np.asarray(f, np.int64).ravel())
        sof.append(pos == 0)
        eol.append(pos % w == w - 1)
    return np.concatenate(data), np.concatenate(sof), np.concatenate(eol)


def coef_beats(images: Sequence[np.ndarray]) -> tuple[np.ndarray, np.ndarray]:
    """(words, last) of coefficient images, each (H, W), tlast on each image's last word."""
    words, last = [], []
    for im in images:
        n = np.size(im)
        words.append(np.asarray(im, np.uint64).ravel())
        last.append(np.arange(n) == n - 1)
    return np.concatenate(words), np.concatenate(last)


__all__ = ["COUNTS", "EVENTS", "AxisOutput", "CoreFrame", "FrameSettings", "FramerResult",
           "axis_framer", "axis_top", "coef_beats", "neutral_gain", "video_beats"]
