"""The fused golden path: a method's frames in one pass (docs/golden_model.md, "Fused path").

:class:`FusedMethod` corrects frames with a calibration as ``method_top``'s reference path
does (``MethodSpec.frame_coefficients``, the core of the method's kind, ``dpc_core``), bit
for bit, in one numba pass (``_fused_kernels.method_frames``): each frame's coefficients
come from the registry as expressions (``MethodSpec.frame_expressions``), which this module
checks and compiles to the kernel's integer tables; the core is chosen by the method's kind
(``MethodSpec.core``), never by its name. Frames whose tables differ only in the terms'
factors (tc_offset's u and u², table_interp's weight between the same two tables) go to
the kernel together, each evaluating its own coefficients row by row. The FFC mean and
refresh passes take the core's sums on the accumulator from
``_fused_kernels.method_sums``.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from irnuc.nuc_fixed import _fused_kernels
from irnuc.nuc_fixed.config import ROUNDING_MODES
from irnuc.nuc_fixed.cores import CORE_INPUTS, KIND_CODES, code_range, kernel_shifts
from irnuc.nuc_fixed.ffc import mean_from_sum, refresh_frac
from irnuc.nuc_fixed.spec import CoefExpr, FrameExpressions, Term
from irnuc.nuc_fixed.validate import InputError, bool_array, int_array

if TYPE_CHECKING:
    from irnuc.nuc_fixed.method_top import MethodCoefficients

_I64 = np.iinfo(np.int64)
#: The kernels' field arguments: a tuple of this many flat int64 arrays (one numba
#: signature for every method; the unused ones a one-element pad).
FIELD_SLOTS = 12
_PAD = np.zeros(1, np.int64)


def input_dtype(adc_bits: int) -> type[np.unsignedinteger]:
    """The dtype the fused kernels read raw codes in: uint16 up to 16 bits, else uint32."""
    return np.uint16 if adc_bits <= 16 else np.uint32


def _shifts(k: list[int]) -> np.ndarray:
    return np.array([*k, *[0] * (5 - len(k))], np.int64)


def _is_direct(e: CoefExpr) -> bool:
    """A stored code as it is (one field term, nothing applied): read from its field."""
    t = e.terms[0]
    return (len(e.terms) == 1 and t.field is not None and t.mul == 1 and t.shift == 0
            and e.round_bits == 0 and e.base is None and e.lo is None and e.hi is None)


@dataclass
class _Tables:
    """A frame's compiled expressions: what the kernel reads (``_fused_kernels``)."""

    rows: tuple[int, ...]  # ids of the field arrays, in the order of ``fields``
    fields: tuple[np.ndarray, ...]  # FIELD_SLOTS flat int64 arrays
    terms: np.ndarray  # (n_terms, 3)
    coefs: np.ndarray  # (n_coefs, 7)
    direct: np.ndarray  # (4,)
    bad: np.ndarray  # (H, W) bool
    bad_flat: np.ndarray
    bad_idx: np.ndarray

    def shares(self, o: _Tables) -> bool:
        """The same tables but for the terms' factors (one kernel call takes both)."""
        return (self.rows == o.rows and np.array_equal(self.terms[:, [0, 2]], o.terms[:, [0, 2]])
                and np.array_equal(self.coefs, o.coefs)
                and (self.bad is o.bad or np.array_equal(self.bad, o.bad)))


class FusedMethod:
    """The fused path of one calibration: :meth:`correct` frames with their readings,
    :meth:`sums` of the core on the FFC accumulator in a frame."""

    def __init__(self, c: MethodCoefficients) -> None:
        self.c = c
        self.cfg = c.cfg
        self.h, self.w = c.shape
        self.kind = KIND_CODES[self.cfg.base.core]
        self._checked: dict[int, object] = {}  # id -> checked array (kept alive)
        self._stack: tuple[tuple[int, ...], tuple[np.ndarray, ...]] | None = None
        self._tables: dict[tuple[tuple[str, int], ...], _Tables] = {}
        # The last sums on the FFC accumulator: (accumulator, xfrac, tables, (sums, F)).
        self._sums: list[tuple[np.ndarray, int, _Tables, tuple[np.ndarray, int]]] = []
        self._bad: tuple[tuple[int, ...], tuple[np.ndarray, ...],
                         tuple[np.ndarray, np.ndarray, np.ndarray]] | None = None

    # ---- a frame's coefficients ------------------------------------------------------------
    def tables(self, frame: Mapping[str, int]) -> _Tables:
        """The compiled expressions of a frame with these readings (cached)."""
        key = tuple(frame.items())
        if key not in self._tables:
            if len(self._tables) >= 64:
                self._tables.clear()
            self._tables[key] = self.compile(self.cfg.base.frame_expressions(self.c, frame))
        return self._tables[key]

    def _field(self, t: Term) -> np.ndarray:
        a = t.field
        if id(a) in self._checked:
            return a  # type: ignore[return-value]
        arr = np.asarray(a)
        if arr.shape != (self.h, self.w):
            raise InputError(f"coefficient {t.fmt or 'field'} has shape {arr.shape}; the "
                             f"frames are {(self.h, self.w)}")
        if t.fmt is not None:
            lo, hi = code_range(self.cfg, t.fmt)
            int_array(t.fmt, arr, lo, hi)
        elif not np.issubdtype(arr.dtype, np.integer):
            raise InputError(f"a coefficient field has dtype {arr.dtype}; integer codes are "
                             "required")
        self._checked[id(a)] = a
        return a  # type: ignore[return-value]

    def compile(self, fx: FrameExpressions) -> _Tables:
        """Check the expressions' fields and constants, and build the kernel's tables."""
        names = CORE_INPUTS[self.cfg.base.core]
        missing = [n for n, _ in names if n not in fx.coefs]
        if missing:
            raise InputError(f"the frame's coefficients lack {', '.join(missing)} (method "
                             f"{self.cfg.method!r})")
        rows: dict[int, int] = {}
        arrays: list[np.ndarray] = []

        def row(t: Term | None) -> int:
            if t is None or t.field is None:
                if t is not None and t.fmt is not None:
                    lo, hi = code_range(self.cfg, t.fmt)
                    int_array(t.fmt, np.int64(t.mul), lo, hi)
                return -1
            a = self._field(t)
            if id(a) not in rows:
                rows[id(a)] = len(arrays)
                arrays.append(a)
            return rows[id(a)]

        terms: list[list[int]] = []
        coefs: list[list[int]] = []
        direct = [-1] * 4
        for j, (name, _) in enumerate(names):
            e = fx.coefs[name]
            start = len(terms)
            terms += [[row(t), int(t.mul), int(t.shift)] for t in e.terms]
            coefs.append([start, len(terms), row(e.base), int(e.round_bits),
                          ROUNDING_MODES[e.rounding],
                          int(_I64.min if e.lo is None else e.lo),
                          int(_I64.max if e.hi is None else e.hi)])
            if _is_direct(e):
                direct[j] = terms[start][0]
        key = tuple(rows)
        if self._stack is None or self._stack[0] != key:
            if len(arrays) > FIELD_SLOTS:
                raise InputError(f"method {self.cfg.method!r}: a frame's coefficients read "
                                 f"{len(arrays)} fields; the fused kernels take at most "
                                 f"{FIELD_SLOTS}")
            # int64 contiguous writeable fields are passed as they are (views); others are
            # converted (one numba type for the tuple: a read-only array would be another).
            flat = tuple(f if f.flags.writeable else f.copy() for f in
                         (np.ascontiguousarray(a, np.int64).reshape(-1) for a in arrays))
            self._stack = (key, flat + (_PAD,) * (FIELD_SLOTS - len(flat)))
        b, flat, idx = self._bad_map(fx.bad)
        return _Tables(key, self._stack[1], np.array(terms, np.int64).reshape(-1, 3),
                       np.array(coefs, np.int64).reshape(-1, 7), np.array(direct, np.int64),
                       b, flat, idx)

    def _bad_map(self, bad: np.ndarray | tuple[np.ndarray, ...]
                 ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """The bad map (the OR of a tuple's), flat, and the flat indices of its pixels;
        cached by the arrays' identity (a frame's flags are usually those of the last)."""
        maps = bad if isinstance(bad, tuple) else (bad,)
        key = tuple(id(m) for m in maps)
        if self._bad is None or self._bad[0] != key:
            bs = [bool_array("bad", m) for m in maps]
            b = bs[0] if len(bs) == 1 else np.logical_or.reduce(bs)
            if b.shape != (self.h, self.w):
                raise InputError(f"bad has shape {b.shape} but the frames are "
                                 f"{(self.h, self.w)}; they must match")
            flat = np.ascontiguousarray(b).reshape(-1)
            self._bad = (key, maps, (b, flat, np.flatnonzero(flat)))
        return self._bad[2]

    def refresh(self, acc: np.ndarray, xfrac: int, frame: Mapping[str, int], target: int
                ) -> np.ndarray:
        """``ffc_refresh`` of the core's sums on ``acc`` in a frame with these readings
        towards ``target`` (the refresh pass): the new FFC correction (H, W) int64."""
        s, frac = self.sums(acc, xfrac, frame)
        c = self.cfg.format("ffc")
        lo, hi = code_range(self.cfg, "ffc")
        t = int(int_array("target", target, 0, (1 << (self.cfg.out_bits + c.frac_bits)) - 1))
        fr = refresh_frac(self.cfg, frac)
        out = np.empty(self.h * self.w, np.int64)
        _fused_kernels.ffc_refresh_codes(s.reshape(-1), t << (fr - c.frac_bits), fr - frac,
                                         fr - c.frac_bits, ROUNDING_MODES[c.rounding], lo, hi,
                                         c.overflow == "wrap", out)
        return out.reshape(self.h, self.w)

    def mean_target(self, acc: np.ndarray, xfrac: int, frame: Mapping[str, int],
                    then: Mapping[str, int] | None = None) -> int | None:
        """``ffc_mean_target`` of the core's sums on ``acc`` in a frame with these readings
        over its good pixels (the mean pass), the sum in one kernel; ``then``: the readings
        of the refresh pass's frame, whose sums come out of the same parallel pass."""
        s, frac = self.sums(acc, xfrac, frame, then)
        c = self.cfg.format("ffc")
        fr = refresh_frac(self.cfg, frac)
        total, n = _fused_kernels.good_rounded_sum(
            s.reshape(-1), fr - frac, fr - c.frac_bits, ROUNDING_MODES[c.rounding],
            self.tables(frame).bad_flat)
        return mean_from_sum(int(total), int(n), self.cfg)

    # ---- the passes -------------------------------------------------------------------------
    def correct(self, x: np.ndarray, out: np.ndarray, frames: list[dict[str, int]], *,
                delta: np.ndarray | None = None, ffc: np.ndarray | None = None) -> None:
        """Correct ``x`` (n, H, W) raw codes (``input_dtype``, checked by the caller) into
        ``out`` (n, H, W) (``out_dtype``), DPC included: frame f with the coefficients of
        its readings ``frames[f]``, on ``(x << Df) - delta`` with ``delta`` (n,)
        (blind_drift), plus the FFC correction ``ffc`` (H, W) (ffc)."""
        cfg = self.cfg
        tabs = [self.tables(fr) for fr in frames]
        xfrac = cfg.format("drift").frac_bits if delta is not None else 0
        f, k, csh = kernel_shifts(cfg, xfrac, ffc is not None)
        n = x.shape[0]
        d = np.zeros(n, np.int64) if delta is None else np.ascontiguousarray(delta, np.int64)
        fc = (np.zeros(self.h * self.w, np.int64) if ffc is None
              else np.ascontiguousarray(self._ffc(ffc), np.int64).reshape(-1))
        i = 0
        while i < n:
            t = tabs[i]
            j = i + 1
            while j < n and (tabs[j] is t or tabs[j].shares(t)):
                j += 1
            muls = np.ascontiguousarray(np.stack([tb.terms[:, 1] for tb in tabs[i:j]]))
            new = np.ones(j - i, bool)
            new[1:] = (muls[1:] != muls[:-1]).any(axis=1)
            _fused_kernels.method_frames(
                x[i:j].reshape(j - i, -1), t.fields, t.terms, muls, new, t.coefs, t.direct,
                self.kind, _shifts(k), d[i:j], xfrac, fc, csh, t.bad_idx, t.bad_flat, self.w,
                f, cfg.rounding_code, cfg.overflow == "wrap", (1 << cfg.out_bits) - 1,
                out[i:j].reshape(j - i, -1))
            i = j

    def _ffc(self, ffc: np.ndarray) -> np.ndarray:
        if id(ffc) not in self._checked:
            lo, hi = code_range(self.cfg, "ffc")
            a = int_array("ffc_offset", ffc, lo, hi)
            if a.shape != (self.h, self.w):
                raise InputError(f"ffc_offset has shape {a.shape}; the frames are "
                                 f"{(self.h, self.w)}")
            self._checked[id(ffc)] = ffc
        return ffc

    def sums(self, acc: np.ndarray, xfrac: int, frame: Mapping[str, int],
             then: Mapping[str, int] | None = None) -> tuple[np.ndarray, int]:
        """The core's aligned sums (H, W) on ``acc`` (codes with ``xfrac`` fraction bits:
        the FFC accumulator) with the coefficients of a frame with these readings, and
        their fraction bits F. With ``then`` (the readings of the refresh pass's frame) its
        sums are made in the same pass and kept for :meth:`refresh`."""
        t = self.tables(frame)
        # The refresh pass after the mean pass on the same accumulator: the sums made
        # beside the mean pass's, or the same sums when the two frames' coefficients are.
        for a, xf, u, res in self._sums:
            if a is acc and xf == xfrac and (u is t or (u.shares(t)
                                                        and np.array_equal(u.terms, t.terms))):
                return res
        tabs = [t]
        if then is not None:
            u = self.tables(then)
            if u is not t and u.shares(t) and not np.array_equal(u.terms, t.terms):
                tabs.append(u)
        f, k, _ = kernel_shifts(self.cfg, xfrac, False)
        a = np.ascontiguousarray(acc, np.int64).reshape(-1)
        s = np.empty((len(tabs), a.shape[0]), np.int64)
        muls = np.ascontiguousarray(np.stack([tb.terms[:, 1] for tb in tabs]))
        _fused_kernels.method_sums(a, t.fields, t.terms, muls, t.coefs, t.direct, self.kind,
                                   _shifts(k), self.w, s)
        self._sums = [(acc, xfrac, tb, (s[m].reshape(self.h, self.w), f))
                      for m, tb in enumerate(tabs)]
        return self._sums[0][3]


def accumulate(acc: np.ndarray | None, x: np.ndarray, cfg: object) -> np.ndarray:
    """``ffc_accumulate`` for the fused path: ``x`` (H, W) of checked raw codes added to
    the accumulator in place (a copy for the first frame). At most ffc_frames frames are
    added (``FfcState``), so the accumulator holds A + n bits as the reference's check
    asserts."""
    if acc is None:
        return np.array(x, dtype=np.int64)
    _fused_kernels.accumulate(acc, np.ascontiguousarray(x))
    return acc
