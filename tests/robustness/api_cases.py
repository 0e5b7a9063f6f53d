"""The API table: bad calls of the model and golden-model API, each raising one-line
``ValueError`` naming the argument, and calls that must accept any byte order."""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import numpy as np


@dataclass(frozen=True)
class ApiCase:
    """One bad call: it must raise ``ValueError`` whose message holds every one of ``names``
    (the argument first)."""

    id: str
    call: Callable[[], Any]
    names: tuple[str, ...]
    what: str


def _api() -> tuple[Any, ...]:
    """What the calls need, imported when the cases run (not at collection)."""
    from irnuc import model
    from irnuc.nuc_fixed import dpc_core, nuc_core, nuc_dpc_top, pack_words
    from irnuc.nuc_fixed.calibrate import calibrate

    return model, nuc_core, dpc_core, nuc_dpc_top, pack_words, calibrate


X = np.full((4, 5), 1000, np.int64) + np.arange(20).reshape(4, 5)
GAIN = np.full((4, 5), 1 << 14, np.int64)
OFFSET = np.zeros((4, 5), np.int64)
BAD = np.zeros((4, 5), bool)
BAD[1, 2] = True
LO = np.stack([X + 2000, X + 2003])
HI = LO + 5000
T14 = "typical14"


def _words() -> np.ndarray:
    return _api()[4](GAIN, OFFSET, BAD, T14)


def _nan(a: np.ndarray) -> np.ndarray:
    f = a.astype(np.float64)
    f.flat[3] = np.nan
    return f


def _sensor(**over: Any) -> dict[str, Any]:
    from irnuc import model

    return model.load_preset("default", {"fpa.active_rows": 6, "fpa.active_cols": 8, **over})


def _half_sensor() -> dict[str, Any]:
    cfg = _sensor()
    del cfg["fpa"]["active_rows"]
    return cfg


def _bad_sensor() -> dict[str, Any]:
    cfg = _sensor()
    cfg["fpa"]["active_rows"] = 0
    return cfg


def _nuc(*a: Any) -> Any:
    return _api()[1](*a)


def _dpc(*a: Any) -> Any:
    return _api()[2](*a)


def _top(*a: Any) -> Any:
    return _api()[3](*a)


def _pack(*a: Any) -> Any:
    return _api()[4](*a)


def _cal(*a: Any, **kw: Any) -> Any:
    return _api()[5](*a, **kw)


def _sim(*a: Any, **kw: Any) -> Any:
    return _api()[0].simulate(*a, **kw)


def _cos4(*a: Any) -> Any:
    return _api()[0].cos4_map(*a)


API_CASES: list[ApiCase] = []


def api(id: str, call: Callable[[], Any], names: tuple[str, ...] | str, what: str) -> None:
    API_CASES.append(ApiCase(id, call, (names,) if isinstance(names, str) else names, what))


api("nuc_core-x-float", lambda: _nuc(X.astype(float), GAIN, OFFSET, T14), ("x", "float64"), "float codes")
api("nuc_core-x-nan", lambda: _nuc(_nan(X), GAIN, OFFSET, T14), ("x", "NaN"), "a NaN code")
api("nuc_core-x-empty", lambda: _nuc(np.zeros(0, np.int64), GAIN, OFFSET, T14), ("x is empty",), "no codes")
api("nuc_core-x-shape", lambda: _nuc(np.zeros((3, 3), np.int64), GAIN, OFFSET, T14), ("x has shape",),
    "codes of another shape than the coefficients")
api("nuc_core-x-range", lambda: _nuc(X + 20000, GAIN, OFFSET, T14), ("x[", "[0, 16383]"), "codes above 2^A-1")
api("nuc_core-x-negative", lambda: _nuc(X - 5000, GAIN, OFFSET, T14), ("x[",), "negative codes")
api("nuc_core-x-bool", lambda: _nuc(X > 0, GAIN, OFFSET, T14), ("x", "bool"), "boolean codes")
api("nuc_core-x-ragged", lambda: _nuc([[1, 2], [3]], GAIN, OFFSET, T14), ("x",), "a ragged list")
api("nuc_core-x-text", lambda: _nuc(np.array([["a"]]), GAIN, OFFSET, T14), ("x", "<U1"), "strings")
api("nuc_core-gain-shape", lambda: _nuc(X, GAIN[:, :4], OFFSET, T14), ("gain has shape", "offset"),
    "gain and offset of different shapes")
api("nuc_core-gain-range", lambda: _nuc(X, GAIN * 8, OFFSET, T14), ("gain[",), "gain codes above 2^GW-1")
api("nuc_core-gain-empty", lambda: _nuc(X, GAIN[:0], OFFSET[:0], T14), ("gain is empty",), "no gain")
api("nuc_core-offset-float", lambda: _nuc(X, GAIN, OFFSET + 0.5, T14), ("offset", "float64"), "float offsets")
api("nuc_core-offset-inf", lambda: _nuc(X, GAIN, np.full((4, 5), np.inf), T14), ("offset",),
    "infinite offsets")
api("nuc_core-cfg-type", lambda: _nuc(X, GAIN, OFFSET, 3), ("cfg",), "a number as cfg")
api("nuc_core-cfg-name", lambda: _nuc(X, GAIN, OFFSET, "typical41"), ("pipeline 'typical41'", "typical14"),
    "a misspelled configuration")
api("dpc_core-y-1d", lambda: _dpc(X[0], BAD[0], T14), ("y has shape",), "one row")
api("dpc_core-y-4d", lambda: _dpc(X[None, None], BAD, T14), ("y has shape",), "a 4-D stack")
api("dpc_core-y-empty", lambda: _dpc(np.zeros((0, 5), np.int64), BAD, T14), ("y is empty",), "no pixels")
api("dpc_core-y-float", lambda: _dpc(X.astype(np.float32), BAD, T14), ("y", "float32"), "float codes")
api("dpc_core-y-range", lambda: _dpc(X + 20000, BAD, T14), ("y[",), "codes above 2^B-1")
api("dpc_core-y-too-large", lambda: _dpc(np.zeros((1, 2000), np.int64), np.zeros((1, 2000), bool), T14),
    ("y frame size", "1024"), "a frame wider than the pipeline allows")
api("dpc_core-bad-shape", lambda: _dpc(X, BAD[:3], T14), ("bad has shape",), "a map of another size")
api("dpc_core-bad-nan", lambda: _dpc(X, _nan(BAD.astype(np.int64)), T14), ("bad", "NaN"), "NaN in the map")
api("dpc_core-bad-two", lambda: _dpc(X, BAD.astype(np.int64) * 2, T14), ("bad[", "[0, 1]"),
    "2 in the bad-pixel map")
api("dpc_core-bad-empty", lambda: _dpc(X, np.zeros((0, 5), bool), T14), ("bad is empty",), "an empty map")
api("nuc_dpc_top-raw-4d", lambda: _top(X[None, None], _words(), T14), ("raw has shape",), "a 4-D stack")
api("nuc_dpc_top-raw-empty", lambda: _top(np.zeros((0, 4, 5), np.int64), _words(), T14), ("raw is empty",),
    "zero frames")
api("nuc_dpc_top-raw-float", lambda: _top(np.full((4, 5), np.inf), _words(), T14), ("raw", "float64"),
    "infinite float codes")
api("nuc_dpc_top-words-float", lambda: _top(X, _words().astype(float), T14), ("words", "float64"),
    "float words")
api("nuc_dpc_top-words-range", lambda: _top(X, _words() | np.uint64(1 << 40), T14), ("words[", "word_bits"),
    "words wider than the layout")
api("nuc_dpc_top-words-negative", lambda: _top(X, -_words().astype(np.int64), T14), ("words[",),
    "negative words")
api("nuc_dpc_top-words-shape", lambda: _top(X, _words()[:3], T14), ("words has shape",),
    "words of another size")
api("nuc_dpc_top-words-empty", lambda: _top(X, np.zeros((0, 5), np.uint64), T14), ("words is empty",),
    "no words")
api("pack_words-gain-nan", lambda: _pack(_nan(GAIN), OFFSET, BAD, T14), ("gain", "NaN"), "a NaN gain")
api("pack_words-offset-range", lambda: _pack(GAIN, OFFSET + (1 << 20), BAD, T14), ("offset[",),
    "offsets beyond the format")
api("pack_words-bad-shape", lambda: _pack(GAIN, OFFSET, BAD[:2], T14), ("bad has shape",),
    "a map of another size")
api("pack_words-gain-empty", lambda: _pack(GAIN[:0], OFFSET[:0], BAD[:0], T14), ("gain is empty",),
    "no pixels")
api("pack_words-bad-float", lambda: _pack(GAIN, OFFSET, BAD.astype(float), T14), ("bad", "float64"),
    "a float bad-pixel map")
api("calibrate-lo-empty", lambda: _cal(LO[:0], HI, T14), ("frames_lo",), "no low frames")
api("calibrate-hi-nan", lambda: _cal(LO, _nan(HI), T14), ("frames_hi", "NaN"), "NaN in the high frames")
api("calibrate-lo-1d", lambda: _cal(LO[0, 0], HI, T14), ("frames_lo has shape",), "one row of codes")
api("calibrate-shape-mismatch", lambda: _cal(LO, HI[:, :3], T14), ("frames_hi",), "stacks of different sizes")
api("calibrate-lo-float", lambda: _cal(LO.astype(float), HI, T14), ("frames_lo", "float64"), "float frames")
api("calibrate-rounding", lambda: _cal(LO, HI, T14, rounding="nearest"), ("rounding", "nearest"),
    "an unknown rounding")
api("calibrate-targets-nan", lambda: _cal(LO, HI, T14, targets=(np.nan, 9000)), ("targets",), "a NaN target")
api("calibrate-targets-text", lambda: _cal(LO, HI, T14, targets=("a", "b")), ("targets",), "targets as words")
api("calibrate-targets-one", lambda: _cal(LO, HI, T14, targets=(1,)), ("targets",), "one target")
api("calibrate-targets-range", lambda: _cal(LO, HI, T14, targets=(-5, 9000)), ("target low",),
    "a target below 0")
api("calibrate-all-stuck", lambda: _cal(np.full_like(LO, 5000), np.full_like(HI, 5000), T14),
    ("no usable pixel",), "every pixel stuck")
api("simulate-cfg-empty", lambda: _sim({}, [300]), ("cfg",), "an empty dict (was a KeyError)")
api("simulate-cfg-none", lambda: _sim(None, [300]), ("cfg = None",), "None")
api("simulate-cfg-list", lambda: _sim([], [300]), ("cfg = []",), "a list")
api("simulate-cfg-half", lambda: _sim(_half_sensor(), [300]), ("cfg", "fpa.active_rows"),
    "a configuration with a field removed")
api("simulate-cfg-bad-value", lambda: _sim(_bad_sensor(), [300]), ("cfg", "fpa.active_rows"),
    "a configuration edited after validation")
api("simulate-temps-nan", lambda: _sim(_sensor(), [300, np.nan]), ("temps",), "a NaN temperature")
api("simulate-temps-inf", lambda: _sim(_sensor(), [np.inf]), ("temps",), "an infinite temperature")
api("simulate-temps-negative", lambda: _sim(_sensor(), [-1.0]), ("temps",), "a negative temperature")
api("simulate-temps-empty", lambda: _sim(_sensor(), []), ("temps",), "no temperature")
api("simulate-temps-2d", lambda: _sim(_sensor(), [[300, 301]]), ("temps",), "a 2-D list")
api("simulate-temps-text", lambda: _sim(_sensor(), ["warm"]), ("temps",), "a word")
api("simulate-repeats-zero", lambda: _sim(_sensor(), [300], repeats=0), ("repeats",), "zero repeats")
api("simulate-repeats-float", lambda: _sim(_sensor(), [300], repeats=1.5), ("repeats",), "1.5 repeats")
api("simulate-seed-negative", lambda: _sim(_sensor(), [300], seed=-1), ("seed",), "a negative seed")
api("simulate-outputs-unknown", lambda: _sim(_sensor(), [300], outputs=("cods",)), ("outputs", "cods"),
    "a misspelled output")
api("simulate-scene-unknown", lambda: _sim(_sensor(), [300], "moon"), ("scene", "moon"), "an unknown scene")
api("simulate-memory", lambda: _sim(_sensor(**{"fpa.active_rows": 16384, "fpa.active_cols": 16384}),
                                    [300, 400], repeats=100_000), ("simulate", "needs an estimated"),
    "200000 frames of 16384 x 16384, refused before any allocation")
api("Pipeline-cfg-empty", lambda: _api()[0].Pipeline({}), ("cfg",), "an empty dict")
api("cos4_map-memory", lambda: _cos4(10**6, 10**6, 17e-6, 0.01), ("cos4_map", "needs an estimated"),
    "10^6 x 10^6 pixels, refused before the allocation")
api("cos4_map-rows-zero", lambda: _cos4(0, 8, 17e-6, 0.01), ("rows",), "zero rows")
api("cos4_map-rows-float", lambda: _cos4(8.0, 8, 17e-6, 0.01), ("rows",), "rows as a float")
api("cos4_map-cols-bool", lambda: _cos4(8, True, 17e-6, 0.01), ("cols",), "cols as True")
api("cos4_map-pitch-nan", lambda: _cos4(8, 8, np.nan, 0.01), ("pitch",), "a NaN pitch")
api("cos4_map-pitch-negative", lambda: _cos4(8, 8, -1e-6, 0.01), ("pitch",), "a negative pitch")
api("cos4_map-focal-inf", lambda: _cos4(8, 8, 17e-6, np.inf), ("focal_length",), "an infinite focal length")
api("cos4_map-centre-nan", lambda: _cos4(8, 8, 17e-6, 0.01, (np.nan, 1.0)), ("centre[0]",), "a NaN centre")
api("cos4_map-centre-short", lambda: _cos4(8, 8, 17e-6, 0.01, (1.0,)), ("centre",), "one coordinate")
api("cos4_map-centre-text", lambda: _cos4(8, 8, 17e-6, 0.01, ("a", "b")), ("centre[0]",), "words")



def swap_byte_order(a: np.ndarray) -> np.ndarray:
    """The same values in the other byte order."""
    return a.astype(a.dtype.newbyteorder("S"))


#: Calls given arrays of the other byte order (and non-contiguous views), each equal to
#: the call on native arrays.
BYTE_ORDER_CASES: dict[str, Callable[[Callable[[np.ndarray], np.ndarray]], Any]] = {
    "nuc_core": lambda f: _nuc(f(X.astype(np.uint16)), f(GAIN.astype(np.uint32)), f(OFFSET.astype(np.int16)),
                               T14),
    "dpc_core": lambda f: _dpc(f(X.astype(np.uint16)), f(BAD.astype(np.int16)), T14),
    "nuc_dpc_top": lambda f: _top(f(np.stack([X, X + 7]).astype(np.uint16)), f(_words()), T14),
    "pack_words": lambda f: _pack(f(GAIN.astype(np.uint32)), f(OFFSET.astype(np.int32)),
                                  f(BAD.astype(np.uint8)), T14),
    "calibrate": lambda f: _cal(f(LO.astype(np.uint16)), f(HI.astype(np.int32)), T14).words(),
    "simulate": lambda f: _sim(_sensor(), f(np.array([300.0, 350.0])), seed=3).codes,
    "cos4_map": lambda f: _cos4(6, 8, 17e-6, 0.01, f(np.array([2.5, 3.0]))),
}
