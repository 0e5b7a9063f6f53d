"""The FFC trigger policy: when the register file asks the host for a flat-field correction.

A camera does not run its shutter on a fixed schedule only: it runs one when the time since
the last FFC passes a period *or* the FPA temperature has moved by a threshold since then
(the FLIR Lepton: every 3 minutes or on a 1.5 degC change). :class:`FfcPolicy` holds the
two settings as the register file does (``FFC_PERIOD.frames``, ``FFC_THRESHOLD.codes``,
0 = that trigger off); :meth:`FfcPolicy.from_physical` converts a period in seconds and a
change in kelvin through the frame rate and the FPA sensor's LSB.

:func:`ffc_trigger` is the golden model of ``irnuc_ffc_trigger`` (the register file's
trigger, ``hdl/irnuc_ffc_trigger.sv``), bit-exact per frame. The rule (docs/integration.md,
"FFC requests"), with frames counted in the order they start (the framer's frame starts):

* the *reference* frame is the frame an ``FFC_CTRL.start`` applies to (the first frame
  that starts after the start command, the run's first shutter frame), and frame 0 (after
  reset the first frame is a reference, as if an FFC had begun there);
* ``since[n]`` = frames since the last reference frame (0 at a reference frame), saturating
  at ``2^PeriodBits - 1``; ``reading[n]`` = the frame's FPA reading (``READING``, the value
  the frame takes at its start; 0 on a build without the reading), ``ref[n]`` = the
  reading of the last reference frame;
* ``due[n] = (period != 0 and since[n] >= period) or
  (threshold != 0 and |reading[n] - ref[n]| >= threshold)``;
* the request (``IRQ_STATUS.ffc_request``, an event) is raised at frame n when ``due[n]`` and
  not ``due[n - 1]`` (``due[-1]`` = 0): once per crossing. It is re-armed when ``due``
  falls, which an FFC does (since and the difference restart from 0), as does raising the
  period or the threshold.
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Sequence
from dataclasses import dataclass

import numpy as np

from irnuc.common.errors import ConfigError


def _field_bits(reg: str, name: str) -> int:
    from irnuc.nuc_fixed.regmap import register_map

    return register_map()[reg].field(name).bits


def period_bits() -> int:
    """Bits of ``FFC_PERIOD.frames`` (and of the frame counter since the last FFC)."""
    return _field_bits("FFC_PERIOD", "frames")


def threshold_bits() -> int:
    """Bits of ``FFC_THRESHOLD.codes``."""
    return _field_bits("FFC_THRESHOLD", "codes")


@dataclass(frozen=True)
class FfcPolicy:
    """An FFC trigger policy in the register file's units.

    Attributes
    ----------
    period : int
        Frames since the last FFC at which one is requested (``FFC_PERIOD.frames``); 0: no
        time trigger.
    threshold : int
        FPA reading change since the last FFC, in reading codes, at which one is requested
        (``FFC_THRESHOLD.codes``); 0: no temperature trigger.
    """

    period: int = 0
    threshold: int = 0

    def __post_init__(self) -> None:
        for name, bits in (("period", period_bits()), ("threshold", threshold_bits())):
            v = getattr(self, name)
            if isinstance(v, bool) or not isinstance(v, (int, np.integer)) or not (
                    0 <= int(v) < 1 << bits):
                raise ConfigError(f"FfcPolicy.{name} = {v!r}: an integer 0 .. {(1 << bits) - 1} "
                                  f"(the register field's {bits} bits)")

    @classmethod
    def from_physical(cls, period_s: float | None, change_K: float | None,
                      frame_rate: float, lsb_K: float) -> FfcPolicy:
        """The policy of a period in seconds and an FPA temperature change in kelvin
        (None: that trigger off): ``period = round(period_s * frame_rate)`` frames and
        ``threshold = ceil(change_K / lsb_K)`` codes (the smallest reading change that is
        at least ``change_K``).

        Parameters
        ----------
        period_s : float or None
            Time between FFCs, s (> 0).
        change_K : float or None
            FPA temperature change that asks for an FFC, K (> 0).
        frame_rate : float
            Frames per second, Hz (> 0).
        lsb_K : float
            The FPA sensor's step of one reading code, K (``FpaSensor.lsb_K``; > 0).
        """
        for name, v in (("frame_rate", frame_rate), ("lsb_K", lsb_K),
                        ("period_s", period_s), ("change_K", change_K)):
            if v is not None and not (math.isfinite(v) and v > 0):
                raise ConfigError(f"FfcPolicy.from_physical: {name} = {v!r} must be > 0")
        period = 0 if period_s is None else max(1, round(period_s * frame_rate))
        # A tiny tolerance: 1.5 K / 0.01 K is 150 codes, not 151 through float rounding.
        threshold = 0 if change_K is None else max(1, math.ceil(change_K / lsb_K - 1e-9))
        return cls(period=int(period), threshold=int(threshold))

    @classmethod
    def lepton(cls, frame_rate: float, lsb_K: float) -> FfcPolicy:
        """The FLIR Lepton's default: an FFC every 3 minutes or on a 1.5 K change."""
        return cls.from_physical(180.0, 1.5, frame_rate, lsb_K)

    def describe(self, frame_rate: float | None = None, lsb_K: float | None = None) -> str:
        """A short name: ``period 1620 frames (180 s) | change 150 codes (1.5 K)``."""
        parts = []
        if self.period:
            s = f"period {self.period} frames"
            parts.append(s + (f" ({self.period / frame_rate:g} s)" if frame_rate else ""))
        if self.threshold:
            s = f"change {self.threshold} codes"
            parts.append(s + (f" ({self.threshold * lsb_K:g} K)" if lsb_K else ""))
        return " | ".join(parts) or "off"


@dataclass(frozen=True)
class FfcTrigger:
    """Per frame of :func:`ffc_trigger`: ``since`` (frames since the reference frame),
    ``ref`` (the reference reading), ``due`` (the request condition) and ``request``
    (``IRQ_STATUS.ffc_request`` raised at that frame), each an array over the frames;
    ``period_hit`` / ``threshold_hit``: which trigger holds."""

    since: np.ndarray
    ref: np.ndarray
    period_hit: np.ndarray
    threshold_hit: np.ndarray
    due: np.ndarray
    request: np.ndarray

    @property
    def request_frames(self) -> list[int]:
        return [int(i) for i in np.flatnonzero(self.request)]


class _Trigger:
    """The trigger's state from frame to frame (the flops of ``irnuc_ffc_trigger``)."""

    def __init__(self) -> None:
        self.sat = (1 << period_bits()) - 1
        self.since, self.ref, self.due, self.first = 0, 0, False, True

    def frame(self, reading: int, reference: bool, p: FfcPolicy) -> tuple[bool, bool, bool]:
        """A frame starts with ``reading`` (``reference``: an FFC_CTRL.start applies to
        it) under policy ``p``: (period_hit, threshold_hit, request)."""
        if reference or self.first:
            self.since, self.ref = 0, int(reading)
        else:
            self.since = min(self.since + 1, self.sat)
        self.first = False
        ph = p.period != 0 and self.since >= p.period
        th = p.threshold != 0 and abs(int(reading) - self.ref) >= p.threshold
        request = (ph or th) and not self.due
        self.due = ph or th
        return ph, th, request


def _codes(readings: Sequence[int] | np.ndarray, who: str) -> np.ndarray:
    r = np.asarray(readings)
    if r.ndim != 1 or (r.size and (not np.issubdtype(r.dtype, np.integer) or r.min() < 0)):
        raise ConfigError(f"{who}: readings must be a 1-D sequence of integer codes >= 0")
    return r.astype(np.int64)


def ffc_trigger(readings: Sequence[int] | np.ndarray, ffc_starts: Iterable[int],
                policy: FfcPolicy | Sequence[FfcPolicy]) -> FfcTrigger:
    """``irnuc_ffc_trigger``: the FFC request of each frame (module docstring's rule).

    Parameters
    ----------
    readings : sequence of int
        The FPA reading of each frame, in the order the frames start (codes, >= 0).
    ffc_starts : iterable of int
        The frames an ``FFC_CTRL.start`` applies to (the start written before that frame
        started and after the previous frame started; the keys of
        :func:`irnuc.nuc_fixed.axis.ffc_shutter_flags`' ``starts``).
    policy : FfcPolicy or sequence of FfcPolicy
        The period and threshold in force at each frame start (one for all frames, or one
        per frame: FFC_PERIOD / FFC_THRESHOLD written between frames; the state, due
        included, carries over a change).
    """
    r = _codes(readings, "ffc_trigger")
    policies = [policy] * r.size if isinstance(policy, FfcPolicy) else list(policy)
    if len(policies) != r.size:
        raise ConfigError(f"ffc_trigger: {len(policies)} policies for {r.size} frames")
    starts = {int(s) for s in ffc_starts}
    n = r.size
    out = {k: np.zeros(n, np.int64) for k in ("since", "ref")}
    flags = {k: np.zeros(n, bool) for k in ("period_hit", "threshold_hit", "due", "request")}
    t = _Trigger()
    for i in range(n):
        ph, th, req = t.frame(int(r[i]), i in starts, policies[i])
        out["since"][i], out["ref"][i] = t.since, t.ref
        flags["period_hit"][i], flags["threshold_hit"][i] = ph, th
        flags["due"][i], flags["request"][i] = t.due, req
    return FfcTrigger(**out, **flags)


def closed_loop(readings: Sequence[int] | np.ndarray, policy: FfcPolicy,
                ffc_frames: int) -> list[int]:
    """The frames FFCs begin at when the host answers every request as soon as it can: a
    request at frame n starts an FFC that applies to frame n + 1 (the host writes
    ``FFC_CTRL.start`` before the next frame starts) or, while a run is going (its
    ``ffc_frames`` shutter frames and the refresh frame), to the frame after the run.
    Frame 0 is the power-on FFC."""
    r = _codes(readings, "closed_loop")
    starts: list[int] = [0] if r.size else []
    t = _Trigger()
    pending, free_from = False, ffc_frames + 1
    for i in range(r.size):
        begin = i == 0 or (pending and i >= free_from)
        if begin and i > 0:
            starts.append(i)
            free_from, pending = i + ffc_frames + 1, False
        pending = t.frame(int(r[i]), begin, policy)[2] or pending
    return starts


__all__ = ["FfcPolicy", "FfcTrigger", "closed_loop", "ffc_trigger", "period_bits",
           "threshold_bits"]
