"""``method_top``: every correction method and composition on a sequence of frames, then DPC.

The composition of the RTL modules per frame (docs/datapath.md, "Method top"):

1. per-frame inputs latched at the frame start: the FPA sensor reading (``tc_reading`` /
   ``interp_weight``), the blind drift (``blind_drift``), the shutter flag;
2. per-pixel coefficients: stored (one_point, two_point, piecewise, quadratic) or computed
   from the reading (``tc_poly``, ``table_interp``);
3. ``drift_sub`` (blind_drift), then the base core with the FFC offset correction (ffc);
4. ``dpc_core`` with the bad map, unchanged for every method;
5. ffc: the shutter frame is accumulated; after the N-th the target is taken (the
   mean pass, with that frame's coefficients) and the refresh pass runs in the next frame,
   with that frame's coefficients, whose correction already uses the new offsets;
   shutter frames are held or passed.

:class:`MethodCoefficients` holds a calibration's per-pixel codes and registers (from
:func:`irnuc.nuc_fixed.fit.calibrate_points` or read back from a memory image). What differs
between methods is the registry's (``nuc_fixed.methods``): the frame's coefficients
(``MethodSpec.frame_coefficients``) and the core of the method's kind
(``nuc_fixed.cores.CORES``).
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from irnuc.nuc_fixed.config import PipelineConfig
from irnuc.nuc_fixed.cores import CORES, CoreResult, drift_sub
from irnuc.nuc_fixed.dpc import dpc_core
from irnuc.nuc_fixed.drift import blind_drift, drift_from_sums
from irnuc.nuc_fixed.ffc import FfcState, ffc_mean_target, ffc_refresh
from irnuc.nuc_fixed.fused import FusedMethod, accumulate, input_dtype
from irnuc.nuc_fixed.layout import pack_memory, unpack_memory
from irnuc.nuc_fixed.nuc import out_dtype
from irnuc.nuc_fixed.validate import InputError, as_config, bool_array, check_frame_shape, int_array
from irnuc.nuc_fixed.widths import ffc_shift


@dataclass(frozen=True)
class MethodCoefficients:
    """A method's per-pixel coefficient codes and its calibration registers.

    Attributes
    ----------
    cfg : PipelineConfig
    fields : dict
        Per memory, per field: int64 codes (H, W) (``bad`` bool), e.g.
        ``fields["coeffs"]["gain"]``, ``fields["table1"]["offset"]``.
    registers : dict
        Calibration registers by name (an int, or a tuple for ``table_readings``).
    """

    cfg: PipelineConfig
    fields: dict[str, dict[str, np.ndarray]]
    registers: dict[str, Any] = field(default_factory=dict)

    @property
    def bad(self) -> np.ndarray:
        """The defective-pixel map: a pixel flagged in the ``bad`` field of any memory
        (table_interp: of any table; a frame's DPC replaces those of its two tables,
        :func:`frame_coefficients`)."""
        maps = [f["bad"] for f in self.fields.values() if "bad" in f]
        return maps[0] if len(maps) == 1 else np.logical_or.reduce(maps)

    @property
    def shape(self) -> tuple[int, int]:
        return tuple(self.bad.shape)  # type: ignore[return-value]

    def words(self) -> dict[str, np.ndarray]:
        """The calibration memories as uint64 words (H, W), by memory name."""
        mems = self.cfg.memories
        return {name: pack_memory(vals, mems[name]) for name, vals in self.fields.items()}

    @classmethod
    def from_words(cls, cfg: PipelineConfig | str, words: Mapping[str, object],
                   registers: Mapping[str, Any]) -> MethodCoefficients:
        """Unpack memory words by the layouts of ``cfg`` (every calibration memory needed)."""
        cfg = as_config(cfg)
        need = [m for m in cfg.memories.values() if m.source == "calibration"]
        missing = [m.name for m in need if m.name not in words]
        if missing:
            raise InputError(f"memory words of {', '.join(missing)} are missing "
                             f"(method {cfg.method!r})")
        fields_ = {m.name: unpack_memory(words[m.name], m) for m in need}
        out = cls(cfg=cfg, fields=fields_, registers=dict(registers))
        out.check()
        return out

    def check(self) -> None:
        """Every memory and register present, of one frame shape, in range."""
        cfg = self.cfg
        shapes = {next(iter(v.values())).shape for v in self.fields.values()}
        if len(shapes) != 1:
            raise InputError(f"coefficient memories differ in shape: {sorted(shapes)}")
        check_frame_shape("coefficients", next(iter(shapes)), cfg)
        for m in cfg.memories.values():
            if m.source != "calibration":
                continue
            if m.name not in self.fields:
                raise InputError(f"coefficients lack memory {m.name!r} (method {cfg.method!r})")
            pack_memory(self.fields[m.name], m)  # checks every field's range
        cfg.base.check_coefficients(self)
        for r in cfg.registers.values():
            if r.source != "calibration":
                continue
            if r.name not in self.registers:
                raise InputError(f"register {r.name!r} is missing (method {cfg.method!r})")
            vals = self.registers[r.name]
            vals = list(vals) if r.count != 1 else [vals]
            if len(vals) != r.count:
                raise InputError(f"register {r.name!r} holds {len(vals)} values; {r.count} "
                                 "expected")
            lo = -(1 << (r.width - 1)) if r.signed else 0
            hi = (1 << (r.width - 1)) - 1 if r.signed else (1 << r.width) - 1
            int_array(f"register {r.name}", np.asarray(vals), lo, hi)


@dataclass(frozen=True)
class FrameInputs:
    """Per-frame fields a method needs (N frames; None where the method needs none)."""

    reading: np.ndarray | None = None
    blind_codes: np.ndarray | None = None
    shutter: np.ndarray | None = None
    #: (N,) each frame's blind sum as a register holds it (BLIND_SUM of irnuc_axis_top),
    #: instead of ``blind_codes``
    blind_sums: np.ndarray | None = None
    #: (N,) the housing temperature sensor's reading of each frame (frame files'
    #: ``housing_reading``), for the methods that read the housing
    housing_reading: np.ndarray | None = None

    @classmethod
    def of_frames(cls, readings: list[Any]) -> FrameInputs:
        """The inputs of frames each with one reading: an FPA reading (an int), a mapping
        of readings by name (``{"fpa": t, "housing": h}``), or None (no reading)."""
        from irnuc.nuc_fixed.methods import READINGS

        if not readings or readings[0] is None:
            return cls()
        if isinstance(readings[0], Mapping):
            return cls(**{READINGS[k].inputs_field: np.asarray([int(r[k]) for r in readings])
                          for k in readings[0]})
        return cls(reading=np.asarray([int(r) for r in readings]))

    @classmethod
    def from_fields(cls, cfg: PipelineConfig, fields: Mapping[str, object]) -> FrameInputs:
        """The inputs of the readings ``cfg`` takes from a frame file's fields by name
        (``fpa_reading``, ...; ``ReadingSpec.frame_field`` -> ``inputs_field``)."""
        from irnuc.nuc_fixed.methods import READINGS

        by_field = {r.frame_field: r.inputs_field for r in READINGS.values()}
        return cls(**{by_field[k]: np.asarray(v) for k, v in fields.items()})


@dataclass(frozen=True)
class MethodOutput:
    """Result of :func:`method_top`.

    Attributes
    ----------
    y : (N, H, W) corrected frames after DPC (uint16 if B <= 16 else uint32).
    delta : (N,) int64 blind drift code of each frame (blind_drift), else None.
    ffc_offset : (H, W) the FFC correction after the last frame (ffc), else None.
    refreshes : indices of the frames after which an FFC refresh ran (the N-th frame of
        each complete shutter run; the refresh pass is the frame after it).
    held : (N,) bool, frames whose output repeats an earlier frame (ffc hold).
    targets : the target level T of every refresh (U B.Cf codes), in order.
    offsets : the correction every refresh wrote ((H, W) int64 each), in order. A refresh
        whose pass would come after the last frame is computed with the last frame's
        coefficients (``pending`` says so).
    pending : the last accumulation completed with the last frame, so its refresh pass
        (the next frame) was not seen.
    kept : the refreshes (by the index of their N-th shutter frame, as ``refreshes``) whose
        mean pass had no good pixel: no target (0 in ``targets``, as the RTL's target
        register reads), and the refresh pass kept every pixel's previous correction
        (``offsets`` repeats it).
    """

    y: np.ndarray
    delta: np.ndarray | None = None
    ffc_offset: np.ndarray | None = None
    refreshes: tuple[int, ...] = ()
    held: np.ndarray | None = None
    targets: tuple[int, ...] = ()
    offsets: tuple[np.ndarray, ...] = ()
    pending: bool = False
    kept: tuple[int, ...] = ()


def needs(cfg: PipelineConfig) -> tuple[str, ...]:
    """The per-frame fields the method reads (``fpa_reading``, ``blind_codes``, ``shutter``):
    those of the readings its base method and stages take (``nuc_fixed.methods.needs``)."""
    from irnuc.nuc_fixed import methods

    return methods.needs(cfg)


def frame_coefficients(c: MethodCoefficients, reading: int | Mapping[str, int] | None
                       ) -> dict[str, Any]:
    """The per-pixel coefficient codes (and registers) the core uses in a frame with this
    reading (the FPA reading, or a mapping of the frame's readings by name):
    ``MethodSpec.frame_coefficients``."""
    from irnuc.nuc_fixed import methods

    return c.cfg.base.frame_coefficients(c, methods.frame(c.cfg, reading))


def base_core(c: MethodCoefficients, fc: Mapping[str, Any], x: np.ndarray, *,
              xfrac: int = 0, signed_x: bool = False, ffc: np.ndarray | None = None,
              sum_only: bool = False) -> CoreResult:
    """The core of the base method's kind (``nuc_fixed.cores.CORES``) on ``x`` with the
    frame's coefficients ``fc``."""
    cfg = c.cfg
    return CORES[cfg.base.core](x, fc, cfg, xfrac=xfrac, signed_x=signed_x, ffc=ffc,
                                sum_only=sum_only)


def _per_frame(name: str, value: object, n: int, cfg: PipelineConfig) -> np.ndarray:
    if value is None:
        raise InputError(f"method {cfg.method!r} needs the per-frame field {name}; the "
                         "frames lack it")
    a = np.asarray(value)
    if a.shape[:1] != (n,):
        raise InputError(f"{name} has shape {a.shape}; one value per frame ({n}) is required")
    return a


def method_top(raw: object, coeffs: MethodCoefficients, inputs: FrameInputs | None = None, *,
               ffc_target: int | None = None, ffc_offset: object | None = None,
               reference: bool = False) -> MethodOutput:
    """Correct a sequence of frames with the configuration's method, then DPC.

    Parameters
    ----------
    raw : integer array_like, (N, H, W) or (H, W)
        Raw ADC codes in [0, 2^A - 1], in time order.
    coeffs : MethodCoefficients
    inputs : FrameInputs
        The per-frame fields the method needs (:func:`needs`).
    ffc_target : int, optional
        FFC target level (U B.Cf); default: the mean of the shutter image
        (:func:`irnuc.nuc_fixed.ffc.ffc_mean_target`).
    ffc_offset : integer array_like (H, W), optional
        FFC correction at the start (default 0: none yet).
    reference : bool
        Run the reference functions, one per RTL module (``MethodSpec.frame_coefficients``,
        the cores of ``nuc_fixed.cores``, ``dpc_core``), instead of the fused kernels
        (``nuc_fixed.fused``: the same bits, one pass per frame; docs/golden_model.md).
    """
    cfg = coeffs.cfg
    x = int_array("raw", raw, 0, (1 << cfg.adc_bits) - 1)
    h, w = check_frame_shape("raw", x.shape, cfg)
    if (h, w) != coeffs.shape:
        raise InputError(f"raw frames are {(h, w)} but the coefficients are {coeffs.shape}")
    if reference:
        x3 = x.reshape(-1, h, w).astype(np.int64)
        path: _Reference | FusedMethod = _Reference(coeffs)
    else:
        x3 = np.ascontiguousarray(x.reshape(-1, h, w), dtype=input_dtype(cfg.adc_bits))
        path = FusedMethod(coeffs)
    n = x3.shape[0]
    inputs = inputs or FrameInputs()
    from irnuc.nuc_fixed.methods import READINGS

    readings = {r: _per_frame(READINGS[r].frame_field, getattr(inputs, READINGS[r].inputs_field),
                              n, cfg)
                for r in cfg.base.readings}
    delta = None
    if cfg.has("blind_drift") and inputs.blind_sums is not None:
        delta = drift_from_sums(_per_frame("blind_sums", inputs.blind_sums, n, cfg),
                                int(coeffs.registers["blind_ref"]),
                                int(coeffs.registers["drift_gain"]), cfg).delta
    elif cfg.has("blind_drift"):
        b = _per_frame("blind_codes", inputs.blind_codes, n, cfg)
        delta = blind_drift(b, int(coeffs.registers["blind_ref"]),
                            int(coeffs.registers["drift_gain"]), cfg).delta
    shutter = None
    state = None
    if cfg.has("ffc"):
        shutter = bool_array("shutter", _per_frame("shutter", inputs.shutter, n, cfg))
        start = np.zeros((h, w), np.int64) if ffc_offset is None else np.asarray(ffc_offset)
        state = FfcState(cfg=cfg, offset=np.asarray(start, dtype=np.int64))
        if not reference:
            state.add = accumulate
    out = np.empty((n, h, w), dtype=out_dtype(cfg))
    held = np.zeros(n, dtype=bool)
    last: np.ndarray | None = None
    # Each frame's readings (its coefficients follow them).
    frames = [{r: int(readings[r][i]) for r in readings} for i in range(n)]
    # A completed accumulation waiting for its refresh pass: (accumulator, target). The
    # pass runs in the next frame with that frame's coefficients (the hardware evaluates
    # the accumulator beside that frame's pixels; docs/datapath.md "ffc").
    pending: tuple[np.ndarray, int | None] | None = None
    targets: list[int] = []
    kept: list[int] = []
    offsets: list[np.ndarray] = []
    i = 0
    while i < n:
        if state is not None and pending is not None:
            state.offset = _refresh(path, frames[i], *pending, state.offset, cfg)
            offsets.append(state.offset)
            pending = None
        # Frames i..j-1: the FFC correction is the same for each (a refresh pass starts a
        # run; a completed accumulation ends one); the sequencer takes their raw codes.
        j = i
        done = False
        while j < n and not done:
            if state is not None and shutter is not None:
                done = state.step(x3[j], bool(shutter[j]))
            j += 1
        path.correct(x3[i:j], out[i:j], frames[i:j],
                     delta=None if delta is None else delta[i:j],
                     ffc=None if state is None else state.offset)
        for k in range(i, j):
            if shutter is not None and shutter[k]:
                if cfg.ffc_output == "hold" and last is not None:
                    out[k] = last
                    held[k] = True
            else:
                last = out[k]
        if done and state is not None:
            # The mean pass: the target from the coefficients of the N-th shutter frame.
            k = j - 1
            if ffc_target is None:
                tgt = path.mean_target(state.acc, ffc_shift(cfg), frames[k])  # type: ignore[arg-type]
            else:
                tgt = int(ffc_target)
            if tgt is None:  # no good pixel: the refresh keeps the offsets
                kept.append(k)
            targets.append(0 if tgt is None else tgt)
            pending = (np.asarray(state.acc), tgt)
            state.refreshes.append(k)
        i = j
    if state is not None and pending is not None:
        # The refresh pass would be the next frame: its coefficients are not known here,
        # the last frame's stand in.
        state.offset = _refresh(path, frames[-1], *pending, state.offset, cfg)
        offsets.append(state.offset)
    return MethodOutput(y=out.reshape(x.shape), delta=delta,
                        ffc_offset=None if state is None else state.offset,
                        refreshes=tuple(state.refreshes) if state else (), held=held,
                        targets=tuple(targets), offsets=tuple(offsets),
                        pending=pending is not None, kept=tuple(kept))


class _Reference:
    """The reference path: one function per RTL module, used as :class:`FusedMethod` is
    (frames with their readings corrected, DPC included; the core's sums in a frame)."""

    def __init__(self, c: MethodCoefficients) -> None:
        self.c = c
        self._key: tuple[tuple[str, int], ...] | None = None
        self.fc: dict[str, Any] = {}

    def _frame(self, frame: Mapping[str, int]) -> dict[str, Any]:
        key = tuple(frame.items())
        if key != self._key:  # a reading usually repeats for many frames: keep one set
            self.fc = self.c.cfg.base.frame_coefficients(self.c, frame)
            self._key = key
        return self.fc

    def correct(self, x: np.ndarray, out: np.ndarray, frames: list[dict[str, int]], *,
                delta: np.ndarray | None = None, ffc: np.ndarray | None = None) -> None:
        cfg = self.c.cfg
        i = 0
        while i < len(frames):
            # Frames i..j-1 share their coefficients: one pass over the stack.
            j = i + 1
            while j < len(frames) and frames[j] == frames[i]:
                j += 1
            fc = self._frame(frames[i])
            if delta is not None:
                xi = drift_sub(x[i:j], delta[i:j], cfg)
                res = base_core(self.c, fc, xi, xfrac=cfg.format("drift").frac_bits,
                                signed_x=True)
            else:
                res = base_core(self.c, fc, x[i:j], ffc=ffc)
            out[i:j] = dpc_core(res.y, fc["bad"], cfg)
            i = j

    def sums(self, acc: np.ndarray, xfrac: int, frame: Mapping[str, int]
             ) -> tuple[np.ndarray, int]:
        ref = base_core(self.c, self._frame(frame), acc, xfrac=xfrac, sum_only=True)
        return ref.s, ref.frac

    def refresh(self, acc: np.ndarray, xfrac: int, frame: Mapping[str, int], target: int
                ) -> np.ndarray:
        s, frac = self.sums(acc, xfrac, frame)
        return ffc_refresh(s, frac, target, self.c.cfg)

    def mean_target(self, acc: np.ndarray, xfrac: int, frame: Mapping[str, int]) -> int | None:
        s, frac = self.sums(acc, xfrac, frame)
        return ffc_mean_target(s, frac, ~self._frame(frame)["bad"], self.c.cfg)


def _refresh(path: _Reference | FusedMethod, frame: Mapping[str, int], acc: np.ndarray,
             target: int | None, offset: np.ndarray, cfg: PipelineConfig) -> np.ndarray:
    """The refresh pass: the base core on the accumulator (with the coefficients of the
    frame the pass runs in), then ``ffc_refresh`` towards ``target``; without a target (no
    good pixel) every pixel keeps its correction ``offset``."""
    if target is None:
        return np.array(offset)
    return path.refresh(acc, ffc_shift(cfg), frame, target)
