"""The in-order scoreboard: every output of the RTL against the golden model, bit for bit.

One implementation (:class:`Scoreboard`) serves every cocotb testbench (outputs collected
by a sink), the bulk C++ harness (outputs read back as arrays) and the report (mismatch
triage lines). Expected values are queued as arrays, observed values are added as they
come, and the comparison is done in numpy when the result is asked for, field by field,
in stream order. Missing and extra outputs are counted; the first ``max_report``
mismatches get a full description from the ``describe`` callback.

A DUT's scoreboard only says what to expect and how to describe a mismatch, from the
golden model: :class:`TopScoreboard` (``nuc_dpc_top``: frame, x, y, the inputs, expected,
got and the golden intermediates p, s, r), :class:`NucScoreboard` (``nuc_core``) and
:class:`DpcScoreboard` (``dpc_core``: the 3 x 3 window). A scoreboard of a new stream (a
coefficient write-back, say) is a :class:`Scoreboard` with its fields and a ``describe``.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field

import numpy as np

from irnuc.nuc_fixed import PipelineConfig, dpc_core, nuc_core, nuc_dpc_top, unpack_words


@dataclass(frozen=True)
class ScoreResult:
    """What a scoreboard found.

    ``compared`` outputs were checked; ``mismatches`` of them differed in at least one
    field; ``missing`` expected outputs never came; ``extra`` outputs were not expected.
    ``lines`` describe the first mismatches (and the missing/extra counts).
    """

    compared: int
    mismatches: int
    missing: int
    extra: int
    lines: list[str]
    first_index: int | None = None
    flag_errors: int = 0  # status flags raised by the DUT (e.g. frame_err_o)

    @property
    def errors(self) -> int:
        return self.mismatches + self.missing + self.extra + self.flag_errors

    @property
    def passed(self) -> bool:
        return self.errors == 0

    def report(self, limit: int = 10) -> str:
        head = (f"{self.errors} error(s): {self.mismatches} mismatching, {self.missing} missing, "
                f"{self.extra} extra of {self.compared + self.missing} expected outputs")
        return "\n".join([head, *self.lines[:limit]])


@dataclass
class Scoreboard:
    """In-order scoreboard over named integer fields.

    Parameters
    ----------
    fields : sequence of str
        Names of the compared fields of one output (e.g. ``("data", "sof", "eol")``).
    describe : callable, optional
        ``describe(index, got)`` -> one line about expected output ``index`` (0-based in
        stream order) that came back as ``got`` (a mapping field -> int).
    max_report : int
        Mismatches described in full; the counts are always complete.
    """

    fields: Sequence[str]
    describe: Callable[[int, Mapping[str, int]], str] | None = None
    max_report: int = 10
    _expected: dict[str, list[np.ndarray]] = field(default_factory=dict)
    _observed: dict[str, list[np.ndarray]] = field(default_factory=dict)  # array chunks

    def __post_init__(self) -> None:
        self._expected = {f: [] for f in self.fields}
        self._observed = {f: [] for f in self.fields}

    # ---- feeding -------------------------------------------------------------------
    def expect(self, **arrays: np.ndarray) -> None:
        """Queue expected outputs: one 1-D array per field, all of one length."""
        lens = {np.asarray(a).size for a in arrays.values()}
        if set(arrays) != set(self.fields) or len(lens) != 1:
            raise ValueError(f"expect() needs equal-length arrays for {list(self.fields)}")
        for k, a in arrays.items():
            self._expected[k].append(np.asarray(a, dtype=np.int64).ravel())

    def observe_arrays(self, **arrays: np.ndarray) -> None:
        """Record outputs (stream order; a sink's ``outputs()``), kept as arrays."""
        for k in self.fields:
            self._observed[k].append(np.asarray(arrays[k], dtype=np.int64).ravel())

    @property
    def n_expected(self) -> int:
        return sum(a.size for a in self._expected[self.fields[0]])

    @property
    def n_observed(self) -> int:
        return sum(a.size for a in self._observed[self.fields[0]])

    # ---- result --------------------------------------------------------------------
    def result(self) -> ScoreResult:
        exp = {k: (np.concatenate(v) if v else np.zeros(0, np.int64))
               for k, v in self._expected.items()}
        got = {k: (np.concatenate(v) if v else np.zeros(0, np.int64))
               for k, v in self._observed.items()}
        n, m = self.n_expected, self.n_observed
        k = min(n, m)
        bad = np.zeros(k, dtype=bool)
        for f in self.fields:
            bad |= exp[f][:k] != got[f][:k]
        idx = np.flatnonzero(bad)
        lines: list[str] = []
        for i in idx[: self.max_report]:
            seen = {f: int(got[f][i]) for f in self.fields}
            if self.describe is not None:
                lines.append(self.describe(int(i), seen))
            else:
                want = {f: int(exp[f][i]) for f in self.fields}
                lines.append(f"output {int(i)}: expected {want} got {seen}")
        missing, extra = max(0, n - m), max(0, m - n)
        if missing:
            lines.append(f"{missing} output(s) missing (the stream ended after {m} of {n})")
        if extra:
            lines.append(f"{extra} extra output(s) after the {n} expected")
        return ScoreResult(compared=k, mismatches=int(idx.size), missing=missing, extra=extra,
                           lines=lines, first_index=int(idx[0]) if idx.size else None)


class TopScoreboard(Scoreboard):
    """The scoreboard of ``nuc_dpc_top``: frames of raw codes and coefficient words.

    Expected codes come from :func:`irnuc.nuc_fixed.nuc_dpc_top`; ``sof`` is expected
    exactly on (0, 0) and ``eol`` exactly on the last column. A mismatch line gives frame,
    x, y, the inputs (raw, gain, offset, bad), expected, got, the markers and the golden
    intermediates p, s, r and the NUC output.
    """

    def __init__(self, golden: PipelineConfig, max_report: int = 10) -> None:
        super().__init__(("data", "sof", "eol"), self._describe, max_report)
        self.golden = golden
        self._frames: list[tuple[np.ndarray, np.ndarray, np.ndarray]] = []  # raw, words, exp
        self._starts: list[int] = []

    def expect_frames(self, raw: np.ndarray, words: np.ndarray,
                      expected: np.ndarray | None = None) -> np.ndarray:
        """Queue frames (H, W) or (N, H, W) sharing one (H, W) coefficient image.

        ``expected`` (the golden output) is computed when not given. Returns it.
        """
        raw = np.asarray(raw)
        h, w = raw.shape[-2:]
        frames = raw.reshape(-1, h, w)
        if expected is None:
            expected = nuc_dpc_top(frames, words, self.golden)
        exp = np.asarray(expected, dtype=np.int64).reshape(-1, h, w)
        pos = np.arange(h * w)
        sof = (pos == 0).astype(np.int64)
        eol = (pos % w == w - 1).astype(np.int64)
        for f in range(frames.shape[0]):
            self._starts.append(self.n_expected)
            self._frames.append((frames[f], np.asarray(words), exp[f]))
            self.expect(data=exp[f].ravel(), sof=sof, eol=eol)
        return exp.reshape(raw.shape)

    def locate(self, index: int) -> tuple[int, int, int]:
        """(frame, x, y) of expected output ``index``."""
        f = int(np.searchsorted(self._starts, index, side="right")) - 1
        w = self._frames[f][0].shape[1]
        off = index - self._starts[f]
        return f, off % w, off // w

    def _describe(self, index: int, got: Mapping[str, int]) -> str:
        f, x, y = self.locate(index)
        raw, words, exp = self._frames[f]
        w = raw.shape[1]
        return describe_top_pixel(raw, words, self.golden, f, x, y, int(exp[y, x]), got,
                                  exp_sof=int(x == 0 and y == 0), exp_eol=int(x == w - 1))


def describe_top_pixel(raw: np.ndarray, words: np.ndarray, golden: PipelineConfig, frame: int,
                       x: int, y: int, expected: int, got: Mapping[str, int],
                       exp_sof: int, exp_eol: int) -> str:
    """One triage line for an output pixel of ``nuc_dpc_top``."""
    gain, offset, bad = unpack_words(words[y:y + 1, x:x + 1], golden)
    it = nuc_core(raw[y:y + 1, x:x + 1], gain, offset, golden, intermediates=True)
    return (f"frame {frame} x {x} y {y}: raw {int(raw[y, x])} gain {int(gain[0, 0])} "
            f"offset {int(offset[0, 0])} bad {int(bad[0, 0])} | expected {expected} "
            f"got {got['data']} | sof {got['sof']} (expected {exp_sof}) eol {got['eol']} "
            f"(expected {exp_eol}) | golden p {int(it.p[0, 0])} s {int(it.s[0, 0])} "
            f"r {int(it.r[0, 0])} y_nuc {int(it.y[0, 0])}")


class NucScoreboard(Scoreboard):
    """The scoreboard of ``nuc_core``: codes, gains and offsets in, ``pix_data`` and the
    ``user`` side band out (the side band passes unchanged).

    A mismatch line gives the item, x, gain, offset, user, expected, got and the golden
    intermediates p, s, r.
    """

    def __init__(self, golden: PipelineConfig, max_report: int = 10) -> None:
        super().__init__(("pix_data", "user"), self._describe, max_report)
        self.golden = golden
        self._inputs: list[np.ndarray] = []  # (4, n) blocks: x, g, o, user

    def expect_items(self, x: np.ndarray, g: np.ndarray, o: np.ndarray,
                     user: np.ndarray) -> None:
        """Queue items (1-D arrays of equal length; offsets signed)."""
        x, g, o, user = (np.asarray(a, dtype=np.int64).ravel() for a in (x, g, o, user))
        self._inputs.append(np.stack([x, g, o, user]))
        self.expect(pix_data=nuc_core(x, g, o, self.golden), user=user)

    def _describe(self, index: int, got: Mapping[str, int]) -> str:
        x, g, o, u = np.concatenate(self._inputs, axis=1)[:, index]
        it = nuc_core(np.array([x]), np.array([g]), np.array([o]), self.golden,
                      intermediates=True)
        return (f"item {index}: x {x} gain {g} offset {o} user {u} | expected {int(it.y[0])} "
                f"got {got['pix_data']} (user {got['user']}) | golden p {int(it.p[0])} "
                f"s {int(it.s[0])} r {int(it.r[0])}")


class DpcScoreboard(Scoreboard):
    """The scoreboard of ``dpc_core``: frames of NUC outputs y and bad maps in, ``pix_data``,
    ``sof`` and ``eol`` out. A mismatch line gives frame, x, y, the value and flag, the
    3 x 3 window of values and flags, expected and got, and the markers."""

    def __init__(self, golden: PipelineConfig, max_report: int = 10) -> None:
        super().__init__(("pix_data", "sof", "eol"), self._describe, max_report)
        self.golden = golden
        self._frames: list[tuple[np.ndarray, np.ndarray, np.ndarray]] = []  # y, bad, exp
        self._starts: list[int] = []

    def expect_frame(self, y: np.ndarray, bad: np.ndarray) -> None:
        y, bad = np.asarray(y, dtype=np.int64), np.asarray(bad, dtype=bool)
        exp = dpc_core(y, bad, self.golden).astype(np.int64)
        h, w = y.shape
        pos = np.arange(h * w)
        self._starts.append(self.n_expected)
        self._frames.append((y, bad, exp))
        self.expect(pix_data=exp.ravel(), sof=(pos == 0).astype(np.int64),
                    eol=(pos % w == w - 1).astype(np.int64))

    def _describe(self, index: int, got: Mapping[str, int]) -> str:
        f = int(np.searchsorted(self._starts, index, side="right")) - 1
        y, bad, exp = self._frames[f]
        w = y.shape[1]
        r, c = divmod(index - self._starts[f], w)
        win = np.s_[max(r - 1, 0): r + 2, max(c - 1, 0): c + 2]
        return (f"frame {f} x {c} y {r}: y {int(y[r, c])} bad {int(bad[r, c])} window "
                f"{y[win].tolist()} bad {bad[win].astype(int).tolist()} | expected "
                f"{int(exp[r, c])} got {got['pix_data']} | sof {got['sof']}/{int(r == c == 0)} "
                f"eol {got['eol']}/{int(c == w - 1)}")
