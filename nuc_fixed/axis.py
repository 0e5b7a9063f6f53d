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
* ``nuc_en = False``: every field of the word but the bad flags takes its neutral value
  (:func:`neutral_word`: unity gain (:func:`neutral_gain`), zero offset and every other
  field 0) and the frame word its neutral one (:func:`neutral_frame`: one_point's gain 1.0,
  else 0); ``dpc_en = False``: the bad flags cleared.

The word is the configured method's coefficient word (``method_dpc_top``'s ``s_coef``:
the base method's calibration memories concatenated, the first at bit 0) and the frame
word its per-frame registers (:func:`frame_word`); two_point has the memory image's word
and no frame word.

:func:`axis_framer` turns the streams into the frames the core corrects
(:class:`CoreFrame`: raw codes and coefficient words) and the events the register file
counts; :func:`axis_top` adds the core (:func:`irnuc.nuc_fixed.nuc_dpc_top`) and gives the
output pixels of ``m_axis_video``. A transaction model: it follows the order of beats and
words, not cycles (the RTL's cycles do not change what it computes).
"""

from __future__ import annotations

import itertools
from collections.abc import Sequence
from dataclasses import dataclass, field

import numpy as np

from irnuc.nuc_fixed import streams
from irnuc.nuc_fixed.config import PipelineConfig
from irnuc.nuc_fixed.layout import unpack_memory
from irnuc.nuc_fixed.method_top import FrameInputs, MethodCoefficients, method_top
from irnuc.nuc_fixed.methods.blind_drift import FRAME_BLIND_DRIFT
from irnuc.nuc_fixed.regmap import register_map
from irnuc.nuc_fixed.streams import (  # the stream words, for the framer's users
    bad_mask,
    coef_stream_bits,
    frame_word_bits,
    neutral_frame,
    neutral_gain,
    neutral_word,
    stream_layouts,
)
from irnuc.nuc_fixed.tempcomp import interp_weight
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
    #: the method's registers as the frame word (:func:`frame_word`; 0 for two_point)
    frame_word: int = 0


@dataclass
class CoreFrame:
    """One frame as the core gets it: raw codes and coefficient words, (H, W) (uint64, or
    Python ints for words wider than 64 bits), and the frame word it starts with."""

    raw: np.ndarray
    words: np.ndarray
    settings: FrameSettings
    filler: np.ndarray  # bool (H, W): a filler pixel
    frame_word: int = 0


@dataclass
class FramerResult:
    """Frames handed to the core, what was counted, and whether a frame is still open."""

    frames: list[CoreFrame]
    counts: dict[str, int] = field(default_factory=dict)
    open_frame: bool = False
    words_taken: int = 0


def coef_word_bits(cfg: PipelineConfig) -> int:
    """Bits of one ``s_axis_coef`` word (CONFIG.word_bits): the method's coefficient word
    (``nuc_fixed.streams.coef_stream_bits``)."""
    return coef_stream_bits(cfg)


@dataclass(frozen=True)
class TableSel:
    """table_interp's selection from the pending READING and TABLE_READING[k] (the register
    TABLE_SEL once computed): the lower table ``j``, the ``weight`` of table j + 1 and
    ``error`` (the table readings do not increase strictly: j and weight 0)."""

    j: int
    weight: int
    error: bool = False

    def register(self, valid: bool = True) -> int:
        """What TABLE_SEL reads (every field 0 while not ``valid``: being computed, or no
        READING / TABLE_READING[k] written since reset)."""
        if not valid:
            return 0
        reg = register_map()["TABLE_SEL"]
        lsb = {f.name: f.lsb for f in reg.fields}
        return ((self.weight << lsb["weight"]) | (self.j << lsb["j"]) | (1 << lsb["valid"])
                | (int(self.error) << lsb["error"]))


def table_sel(cfg: PipelineConfig, registers: dict[str, object]) -> TableSel:
    """:class:`TableSel` of the register values ``reading`` and ``table_readings`` (the K
    values of TABLE_READING[k]): ``nuc_fixed.tempcomp.interp_weight``, or the error case."""
    rs = [int(v) for v in registers["table_readings"]]  # type: ignore[union-attr]
    if any(b <= a for a, b in itertools.pairwise(rs)):
        return TableSel(0, 0, True)
    iw = interp_weight(int(registers["reading"]), rs, cfg)  # type: ignore[call-overload]
    return TableSel(iw.j, iw.w)


def _table_pair(coeffs: MethodCoefficients, j: int) -> tuple[np.ndarray, np.ndarray, int]:
    """Tables j and j + 1's memory words (uint64, (H, W)) and the bits of one."""
    cfg = coeffs.cfg
    if "table0" not in cfg.memories or not 0 <= j <= int(cfg.tables or 0) - 2:
        raise ValueError(f"no table pair j = {j} in pipeline {cfg.name!r}")
    words = coeffs.words()
    return (np.asarray(words[f"table{j}"], np.uint64),
            np.asarray(words[f"table{j + 1}"], np.uint64), cfg.memories["table0"].word_bits)


def table_pair_words(coeffs: MethodCoefficients, j: int) -> np.ndarray:
    """The coefficient words (H, W, Python ints) a DMA streams for a frame whose
    TABLE_SEL.j is ``j``: table j's memory word at bit 0, table j + 1's above it, as in the
    memory image (``NAME.bin`` of tables ``table{j}`` and ``table{j+1}``)."""
    lo, hi, bits = _table_pair(coeffs, j)
    return lo.astype(object) | (hi.astype(object) << bits)


def table_pair_bin(coeffs: MethodCoefficients, j: int) -> bytes:
    """:func:`table_pair_words` as the DMA's image: one word per pixel in raster order,
    each in ceil(2 T / 8) bytes, little-endian (T < 64 the bits of a table's word); what
    ``irnuc calibrate`` writes as ``table_pair{j}.bin``."""
    lo, hi, bits = _table_pair(coeffs, j)
    lo, hi = lo.ravel(), hi.ravel()
    # The 2T-bit word as two little-endian uint64 limbs (vectorised: frames of 10^6 pixels).
    limbs = np.empty((lo.size, 2), "<u8")
    limbs[:, 0] = lo | (hi << np.uint64(bits))
    limbs[:, 1] = hi >> np.uint64(64 - bits)
    return limbs.view(np.uint8).reshape(-1, 16)[:, :(2 * bits + 7) // 8].tobytes()


def _blind_layout(cfg: PipelineConfig) -> dict[str, tuple[int, int]]:
    """The spec's frame_blind_drift layout: the base method's frame word (one_point's gain;
    two_point one unused bit), then BLIND_SUM, BLIND_REF and DRIFT_GAIN."""
    return FRAME_BLIND_DRIFT.layout(BaseBits=frame_word_bits(cfg), SumBits=cfg.blind_sum_bits,
                                    DriftGainBits=cfg.registers["drift_gain"].width)


def frame_word(cfg: PipelineConfig, registers: dict[str, object]) -> int:
    """The frame word the framer takes at a frame start, from the method's register values
    by name (``gain``, ``level``, ``reading``, ``t_ref``, ``table_readings``,
    ``blind_sum``, ``blind_ref``, ``drift_gain``; a signed register as its two's complement
    bits): the base method's (``nuc_fixed.streams.frame_word``: one_point the gain,
    piecewise the level, tc_offset the spec's frame_tc_offset (reading, t_ref),
    table_interp the weight (:func:`table_sel`); else 0). With blind_drift the spec's
    frame_blind_drift: that word, then the blind sum, the blind reference and the drift
    gain."""
    word = streams.frame_word(cfg, registers)
    if cfg.has("blind_drift"):
        for name, (lsb, bits) in _blind_layout(cfg).items():
            if name != "base":
                word |= (int(registers[name]) & ((1 << bits) - 1)) << lsb
    return word


def frame_method_inputs(f: CoreFrame, cfg: PipelineConfig
                        ) -> tuple[MethodCoefficients, FrameInputs]:
    """The calibration and per-frame inputs a frame of a method other than two_point is
    corrected with: its words split into the method's memories and the frame word into
    the method's registers and readings (``MethodSpec.from_frame_word`` where the method
    computes its frame word), and the blind sum."""
    from irnuc.nuc_fixed.methods import READINGS

    words = np.asarray(f.words, dtype=object)
    fields = {}
    for m, base in stream_layouts(cfg):
        mem = np.array([[(int(v) >> base) & ((1 << m.word_bits) - 1) for v in row]
                        for row in words], dtype=np.uint64).reshape(words.shape)
        fields[m.name] = unpack_memory(mem, m)
    word = f.frame_word
    regs: dict[str, object] = {}
    sums = None
    if cfg.has("blind_drift"):
        got = {n: (f.frame_word >> lsb) & ((1 << b) - 1)
               for n, (lsb, b) in _blind_layout(cfg).items()}
        word = got["base"]
        g = got["drift_gain"]
        gb = cfg.registers["drift_gain"].width
        regs["blind_ref"] = got["blind_ref"]
        regs["drift_gain"] = g - (1 << gb) if g >> (gb - 1) else g  # two's complement
        sums = np.array([got["blind_sum"]])
    values: dict[str, object] = dict(streams.frame_fields(cfg, word))
    alt = cfg.base.from_frame_word(cfg, fields, values)
    if alt is not None:
        fields, values = alt
    readings = {}
    for r in cfg.base.readings:
        reg = READINGS[r].register
        if reg is not None and reg(cfg).name in values:
            readings[READINGS[r].inputs_field] = np.array([values.pop(reg(cfg).name)])
    regs |= values
    inputs = FrameInputs(**readings, blind_sums=sums)  # type: ignore[arg-type]
    return MethodCoefficients(cfg=cfg, fields=fields, registers=regs), inputs


def core_output(f: CoreFrame, cfg: PipelineConfig) -> np.ndarray:
    """The corrected pixels (H, W) of a frame the framer handed to the core: the two-point
    core (:func:`irnuc.nuc_fixed.nuc_dpc_top`), or the method's (``method_top``)."""
    if cfg.plain:
        return nuc_dpc_top(f.raw, f.words, cfg)
    coeffs, inputs = frame_method_inputs(f, cfg)
    return method_top(f.raw[None], coeffs, inputs).y[0]


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
    words = np.asarray(words, dtype=object).ravel()
    wlast = np.asarray(word_last, dtype=bool).ravel()
    if not settings:
        raise ValueError("axis_framer needs the settings of at least one frame")
    counts = dict.fromkeys((*EVENTS, *COUNTS), 0)
    frames: list[CoreFrame] = []
    neutral, bad = neutral_word(cfg), bad_mask(cfg)
    wide = coef_word_bits(cfg) > 64

    st = {"j": 0, "fill": False}
    cur: dict = {}

    def open_frame() -> None:
        s = settings[min(counts["frames_in"], len(settings) - 1)]
        cur.update(s=s, raw=np.zeros((s.height, s.width), np.int64),
                   words=np.zeros((s.height, s.width), object if wide else np.uint64),
                   filler=np.zeros((s.height, s.width), bool), x=0, y=0,
                   frame=s.frame_word if s.nuc_en else neutral_frame(cfg))
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
        word = int(word)
        if not s.nuc_en:
            word = (word & bad) | (neutral & ~bad)
        if not s.dpc_en:
            word &= ~bad
        cur["raw"][y, x] = raw
        cur["words"][y, x] = word
        cur["filler"][y, x] = filler
        if filler:
            counts["padded"] += 1
        if x == s.width - 1:
            cur["x"], cur["y"] = 0, y + 1
        else:
            cur["x"] = x + 1
        if last:
            frames.append(CoreFrame(cur["raw"], cur["words"], s, cur["filler"], cur["frame"]))
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
    (:func:`core_output`) frame by frame."""
    fr = axis_framer(data, sof, eol, words, word_last, settings, cfg)
    outs, sofs, eols = [], [], []
    for f in fr.frames:
        h, w = f.raw.shape
        outs.append(core_output(f, cfg).astype(np.int64).ravel())
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
        words.append(np.asarray(im, object).ravel())
        last.append(np.arange(n) == n - 1)
    return np.concatenate(words), np.concatenate(last)


# ---- the FFC framing (Ffc = 1: irnuc_axis_top around method_ffc_top) ----------------------

@dataclass(frozen=True)
class FfcFraming:
    """Per frame of a sequence (in the order the frames start), what the FFC streams of
    ``irnuc_axis_top`` carry: ``shutter`` the frame's shutter flag (from FFC_CTRL), then
    whether the frame takes one word per pixel on ``s_axis_foff`` (every frame),
    ``s_axis_acc`` (the 2nd..N-th shutter frame of a run and the refresh frame), gives one on
    ``m_axis_acc`` (the 1st..N-th shutter frame of a run) and ``m_axis_foff`` (the refresh
    frame: the frame after a run's N-th shutter frame, whatever its own flag), and whether
    it is output on ``m_axis_video`` (``shown``: not with ``ffc_output = "hold"`` for a
    shutter frame once an open frame was taken). ``done`` is the frame in which
    FFC_STATUS.done rises for the last FFC_CTRL.start (None: not within the sequence):
    the first refresh frame once the start's first shutter frame began, as its last new
    offset is taken, or, for a run shorter than N (no refresh), the first open frame after
    it as it starts (the frame the start applies to with FFC_CTRL.frames = 0)."""

    shutter: tuple[bool, ...]
    foff_in: tuple[bool, ...]
    acc_in: tuple[bool, ...]
    acc_out: tuple[bool, ...]
    foff_out: tuple[bool, ...]
    shown: tuple[bool, ...]
    done: int | None


def ffc_shutter_flags(n_frames: int, starts: dict[int, int]) -> list[bool]:
    """The shutter flag of each of ``n_frames`` frames from FFC_CTRL: ``starts`` maps a
    frame to the FFC_CTRL.frames of a start written before that frame started (after the
    previous one started); that frame and the next frames, that many in all, are shutter
    frames (a later start counts again from its frame)."""
    flags, left = [], 0
    for i in range(n_frames):
        if i in starts:
            left = int(starts[i])
        flags.append(left > 0)
        left = max(left - 1, 0)
    return flags


def ffc_framing(cfg: PipelineConfig, shutter: Sequence[bool],
                start: int | None = None) -> FfcFraming:
    """The frames carrying words on each FFC stream for a sequence of shutter flags
    (:class:`FfcFraming`), by the sequencer's rules (docs/datapath.md "ffc"): a run's
    shutter frames are counted up to N = ``cfg.ffc_frames`` (an open frame restarts the
    count; a run shorter than N leaves the offsets as they were), the N-th is the mean
    pass and the next frame the refresh. ``start``: the frame the last FFC_CTRL.start
    applies to (its ``done``)."""
    n = int(cfg.ffc_frames or 1)
    hold = cfg.ffc_output == "hold"
    count, pending, opened = 0, False, False
    out: dict[str, list[bool]] = {k: [] for k in ("foff_in", "acc_in", "acc_out",
                                                  "foff_out", "shown")}
    done, begun = None, False
    for i, s in enumerate(bool(v) for v in shutter):
        first, add = s and count == 0, s and 0 < count < n
        out["foff_in"].append(True)
        out["acc_in"].append(add or pending)
        out["acc_out"].append(first or add)
        out["foff_out"].append(pending)
        out["shown"].append(not (hold and s and opened))
        if start is not None and i >= start and done is None:
            if i == start and not s:
                done = i  # FFC_CTRL.frames = 0
            elif not s and begun and count < n:
                done = i  # a run shorter than N ended
            else:
                begun = begun or s
                if begun and pending:
                    done = i
        mean = s and count == n - 1
        count = 0 if not s else count + 1 if count < n else count
        pending, opened = mean, opened or not s
    return FfcFraming(tuple(bool(v) for v in shutter), *(tuple(out[k]) for k in (
        "foff_in", "acc_in", "acc_out", "foff_out", "shown")), done)


__all__ = ["COUNTS", "EVENTS", "AxisOutput", "CoreFrame", "FfcFraming", "FrameSettings",
           "FramerResult", "TableSel", "axis_framer", "axis_top", "bad_mask", "coef_beats",
           "coef_word_bits", "core_output", "ffc_framing", "ffc_shutter_flags",
           "frame_method_inputs", "frame_word", "neutral_frame", "neutral_gain",
           "neutral_word", "stream_layouts", "table_pair_bin", "table_pair_words",
           "table_sel", "video_beats"]
