"""Stimulus for the correction methods in RTL: random calibrations over every code range,
FPA readings around the method's breakpoints, and corner frames chosen to hit every
coverage bin of the method (``irnuc.cosim.method_coverage``).

Every value comes from the configuration's formats and memory layouts
(``PipelineConfig.memories`` / ``registers``) and the method's hints (``MethodSpec``:
``draw_register`` for a register of a shape of its own, ``reading_marks``, ``corner``,
``corner_registers``); every draw takes the caller's generator.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from irnuc.cosim.method_coverage import frame_classes, method_points
from irnuc.nuc_fixed.config import PipelineConfig
from irnuc.nuc_fixed.layout import field_range
from irnuc.nuc_fixed.method_top import MethodCoefficients


@dataclass(frozen=True)
class FramePlan:
    """A frame to drive: its calibration, raw codes and FPA reading (or None)."""

    coeffs: MethodCoefficients
    raw: np.ndarray
    reading: int | dict[str, int] | None


def _codes(rng: np.random.Generator, lo: int, hi: int, shape: tuple[int, ...],
           biased: bool) -> np.ndarray:
    """Uniform codes in [lo, hi]; ``biased``: a quarter at the ends or 0, a quarter with
    their low bits cleared (sums then fall on exact halves: rounding ties)."""
    v = rng.integers(lo, hi + 1, size=shape, dtype=np.int64)
    if not biased:
        return v
    kind = rng.integers(0, 8, size=shape)
    ends = np.array([lo, hi, 0 if lo <= 0 <= hi else lo], dtype=np.int64)
    v = np.where(kind == 0, ends[rng.integers(0, 3, size=shape)], v)
    bits = max(1, int(hi - lo).bit_length())
    zeros = rng.integers(0, bits, size=shape)
    cleared = (v >> zeros) << zeros
    return np.where((kind == 1) | (kind == 2), np.clip(cleared, lo, hi), v)


def random_registers(cfg: PipelineConfig, rng: np.random.Generator,
                     biased: bool = False) -> dict[str, object]:
    """Calibration registers of the method, in their code ranges (table readings strictly
    increasing)."""
    out: dict[str, object] = {}
    for r in cfg.registers.values():
        if r.source != "calibration":
            continue
        lo, hi = field_range(r.width, r.signed)
        own = cfg.base.draw_register(r, rng, lo, hi)
        out[r.name] = own if own is not None else int(_codes(rng, lo, hi, (), biased))
    return out


def random_coefficients(cfg: PipelineConfig, h: int, w: int, rng: np.random.Generator,
                        bad_fraction: float = 0.05, biased: bool = False,
                        registers: dict[str, object] | None = None) -> MethodCoefficients:
    """Every calibration memory's fields drawn over their code ranges; one bad map, and
    where several memories have one (table_interp's tables) each memory's that one with a
    few more pixels of its own (a frame's DPC replaces the pixels flagged in either of its
    two tables)."""
    bad = rng.random((h, w)) < bad_fraction
    per_table = sum(1 for m in cfg.memories.values() if m.source == "calibration"
                    and any(f.name == "bad" for f in m.fields)) > 1
    fields: dict[str, dict[str, np.ndarray]] = {}
    for m in cfg.memories.values():
        if m.source != "calibration":
            continue
        vals: dict[str, np.ndarray] = {}
        for f in m.fields:
            if f.name == "bad":
                own = rng.random((h, w)) < bad_fraction / 2 if per_table else False
                vals[f.name] = bad | own
            else:
                lo, hi = field_range(f.width, f.signed)
                vals[f.name] = _codes(rng, lo, hi, (h, w), biased)
        fields[m.name] = vals
    regs = random_registers(cfg, rng, biased) if registers is None else registers
    return MethodCoefficients(cfg=cfg, fields=fields, registers=regs)


def reading_marks(cfg: PipelineConfig, coeffs: MethodCoefficients) -> list[int]:
    """The readings where the method's frame values change behaviour
    (``MethodSpec.reading_marks``: t_ref and the clamps of tc_offset, the table readings and
    the midpoints between them of table_interp: w = 1/2 on an even span, a rounding tie)."""
    return cfg.base.reading_marks(coeffs)


def _draw(rng: np.random.Generator, marks: list[int], hi: int, mark: int | None) -> int:
    if mark is not None:
        return int(np.clip(marks[mark % len(marks)], 0, hi))
    kind = int(rng.integers(0, 4))
    if kind == 0:
        return int(rng.integers(0, hi + 1))
    base = marks[int(rng.integers(0, len(marks)))]
    return int(np.clip(base + rng.integers(-3, 4) * (kind - 1), 0, hi))


def random_reading(cfg: PipelineConfig, coeffs: MethodCoefficients,
                   rng: np.random.Generator, mark: int | None = None
                   ) -> int | dict[str, int] | None:
    """An FPA reading for a frame (None for methods without one): anywhere, or near the
    method's breakpoints (:func:`reading_marks`); ``mark`` picks breakpoint ``mark``
    exactly (cyclically). A method that also takes the housing reading gets both,
    ``{"fpa": t, "housing": h}``, each drawn on its own (``MethodSpec.housing_marks``)."""
    if "fpa" not in cfg.base.readings:
        return None
    hi = (1 << int(cfg.reading_bits or 1)) - 1
    t = _draw(rng, reading_marks(cfg, coeffs), hi, mark)
    if "housing" not in cfg.base.readings:
        return t
    hhi = (1 << int(cfg.housing_bits or 1)) - 1
    hmarks = cfg.base.housing_marks(coeffs)
    h = _draw(rng, hmarks, hhi, None if mark is None else mark // 2 + mark % 2 * 3)
    return {"fpa": t, "housing": h}


def random_raw(cfg: PipelineConfig, h: int, w: int, rng: np.random.Generator,
               biased: bool = False) -> np.ndarray:
    return _codes(rng, 0, (1 << cfg.adc_bits) - 1, (h, w), biased)


def _corner_candidate(cfg: PipelineConfig, rng: np.random.Generator, h: int, w: int,
                      index: int) -> FramePlan:
    """A biased random frame; per method some pixels are put on its breakpoints, and every
    other candidate's reading is a breakpoint (:func:`reading_marks`, in turn)."""
    c = random_coefficients(cfg, h, w, rng, bad_fraction=0.0, biased=True)
    raw = random_raw(cfg, h, w, rng, biased=True)
    for name in cfg.base.corner_registers:  # at 0, their largest code, other
        r = cfg.registers[name]
        if index % 3 < 2:
            c.registers[name] = (0, (1 << r.width) - 1)[index % 3]
    cfg.base.corner(c, raw, rng, index)
    return FramePlan(coeffs=c, raw=raw, reading=random_reading(
        cfg, c, rng, mark=index // 2 if index % 2 == 0 else None))


def corner_frames(cfg: PipelineConfig, rng: np.random.Generator, h: int = 8, w: int = 8,
                  pool: int = 60) -> list[FramePlan]:
    """Frames that together hit every method bin of :func:`method_points` (but the
    frame-boundary one), chosen greedily from ``pool`` biased random frames.

    Raises AssertionError naming the bins the pool missed (the generator must reach them).
    """
    points, _ = method_points(cfg)
    want = {(p, b) for p, bins in points.items() if p != "method.frame_word" for b in bins}
    cands = []
    for i in range(pool):
        fp = _corner_candidate(cfg, rng, h, w, i)
        got = {(p, b) for p, bins in frame_classes(fp.coeffs, fp.raw, fp.reading).items()
               for b in bins}
        cands.append((fp, got & want))
    chosen: list[FramePlan] = []
    left = set(want)
    while left:
        fp, got = max(cands, key=lambda c: len(c[1] & left))
        if not got & left:
            break
        chosen.append(fp)
        left -= got
    assert not left, f"{cfg.name}: no corner frame reaches {sorted(left)}"
    return chosen


def ffc_calibration(cfg: PipelineConfig, h: int, w: int, rng: np.random.Generator,
                 kind: str) -> MethodCoefficients:
    """A calibration for an FFC sequence: ``random``: every field over its code range;
    ``camera``: gains near 1, small offsets and quadratic terms (the corrections then stay
    inside the ffc format)."""
    c = random_coefficients(cfg, h, w, rng, biased=kind == "random")
    fields = {m: dict(v) for m, v in c.fields.items()}
    co = fields["coeffs"]
    co["bad"] = co["bad"].copy()
    co["bad"][0, 0] = False  # a target needs a good pixel
    if kind == "random":
        return MethodCoefficients(cfg, fields, c.registers)
    if "gain" in co:
        one = 1 << cfg.gain_frac_bits
        co["gain"] = one + rng.integers(-one // 8, one // 8 + 1, size=(h, w))
    co["offset"] = rng.integers(-(1 << (cfg.offset_frac_bits + 6)),
                                1 << (cfg.offset_frac_bits + 6), size=(h, w))
    if "quad" in fields:
        fields["quad"]["quad"] = rng.integers(-(1 << 9), 1 << 9, size=(h, w))
    for m in ("tc", "tg"):
        for k in fields.get(m, {}):
            fields[m][k] = rng.integers(-64, 65, size=(h, w))
    regs = dict(c.registers)
    if "gain" in regs:
        regs["gain"] = 1 << cfg.gain_frac_bits
    return MethodCoefficients(cfg, fields, regs)


def ffc_raws(cfg: PipelineConfig, shutter: list[int], h: int, w: int, rng: np.random.Generator,
          kind: str) -> list[np.ndarray]:
    """The frames of an FFC sequence: scene frames (random codes) and shutter frames (a
    level with a fixed pattern and temporal noise; ``random``: any codes)."""
    top = (1 << cfg.adc_bits) - 1
    level = int(rng.integers(top // 4, 3 * top // 4))
    pattern = rng.integers(-200, 201, size=(h, w))
    out = []
    for s in shutter:
        if s and kind != "random":
            out.append(np.clip(level + pattern + rng.integers(-8, 9, size=(h, w)), 0, top))
        else:
            out.append(random_raw(cfg, h, w, rng, biased=kind == "random"))
    return out
