"""Defective pixels with a ground-truth map.

:func:`inject_defects` builds a :class:`DefectMap` over the active area from a
:class:`DefectSpec` and a seed. The signal chain then applies it in three places:

* ``resp`` multiplies the absorbed optical power (LOW_RESP, HIGH_RESP);
* :func:`apply_voltage_defects` acts on the integrator output voltage (DEAD, STUCK_*, HOT,
  COLD);
* :func:`noisy_sigma` gives the extra temporal noise of NOISY pixels.

Precedence when patterns overlap: listed > rows/cols > clusters > isolated rates. Each
stage writes only pixels that are still GOOD. See ``docs/fpa.md``.
"""

from __future__ import annotations

import hashlib
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from enum import IntEnum
from typing import Any

import numpy as np

from irnuc.model.validate import ConfigError, check_choice, check_int, check_scalar

__all__ = [
    "KIND_NAMES",
    "DefectKind",
    "DefectMap",
    "DefectPattern",
    "DefectSpec",
    "apply_voltage_defects",
    "inject_defects",
    "noisy_sigma",
]


class DefectKind(IntEnum):
    """Ground-truth defect kind of a pixel (uint8 code)."""

    GOOD = 0
    DEAD = 1  #: open circuit: reads the integrator reference (reset) level
    STUCK_LOW = 2  #: output at the low rail
    STUCK_HIGH = 3  #: output at the high rail
    STUCK_VALUE = 4  #: output at a fixed level (fraction of the ADC input range)
    HOT = 5  #: positive output offset
    COLD = 6  #: negative output offset
    LOW_RESP = 7  #: optical responsivity multiplied by a factor < 1
    HIGH_RESP = 8  #: optical responsivity multiplied by a factor > 1
    NOISY = 9  #: extra temporal noise


class DefectPattern(IntEnum):
    """How a defective pixel was placed (uint8 code)."""

    NONE = 0
    ISOLATED = 1
    CLUSTER = 2
    ROW = 3
    COLUMN = 4
    LISTED = 5


#: Lower-case config names of the defect kinds (GOOD excluded), in code order.
KIND_NAMES: tuple[str, ...] = tuple(k.name.lower() for k in DefectKind if k != DefectKind.GOOD)

_HIGH_RESP_MAX = 100.0
_MAX_CLUSTER_SIZE = 1 << 20

KNOWN_KEYS = (
    "rates",
    "clusters",
    "cluster_size",
    "cluster_kinds",
    "rows",
    "cols",
    "line_kind",
    "listed",
    "stuck_value",
    "offset",
    "low_resp",
    "high_resp",
    "noise",
)
_LISTED_KEYS = ("row", "col", "kind", "value")


def _kind(name: str) -> DefectKind:
    return DefectKind[name.upper()]


def _check_value(field_: str, kind: DefectKind, value: Any) -> float:
    """Check the kind-specific parameter of a defect (level, offset, factor or noise std)."""
    if kind == DefectKind.STUCK_VALUE:
        return check_scalar(field_, value, 0.0, 1.0)
    if kind in (DefectKind.HOT, DefectKind.COLD, DefectKind.NOISY):
        return check_scalar(field_, value, 0.0, 1.0, lo_open=True)
    if kind == DefectKind.LOW_RESP:
        return check_scalar(field_, value, 0.0, 1.0, lo_open=True, hi_open=True)
    if kind == DefectKind.HIGH_RESP:
        return check_scalar(field_, value, 1.0, _HIGH_RESP_MAX, lo_open=True)
    raise ConfigError(f"{field_} = {value!r}: a {kind.name.lower()} pixel takes no value")


def _int_tuple(field_: str, value: Any) -> tuple[int, ...]:
    if isinstance(value, (str, bytes, Mapping)) or not isinstance(value, Sequence | np.ndarray):
        raise ConfigError(f"{field_} = {value!r} is not a list of integers")
    return tuple(check_int(f"{field_}[{i}]", v, 0) for i, v in enumerate(value))


def _normalise(d: Mapping[str, Any], path: str) -> dict[str, Any]:
    """Validate the fields of a spec and return them in canonical form."""
    out: dict[str, Any] = {}

    rates = d.get("rates", {})
    if not isinstance(rates, Mapping):
        raise ConfigError(f"{path}.rates = {rates!r} is not a table of kind -> fraction")
    norm_rates: dict[str, float] = {}
    for name, r in rates.items():
        check_choice(f"{path}.rates.{name}", name, KIND_NAMES)
        norm_rates[name] = check_scalar(f"{path}.rates.{name}", r, 0.0, 1.0)
    total = sum(norm_rates.values())
    if total > 1.0:
        raise ConfigError(
            f"{path}.rates: the rates sum to {total:g}, outside the allowed range [0, 1]"
        )
    out["rates"] = norm_rates

    out["clusters"] = check_int(f"{path}.clusters", d.get("clusters", 0), 0)
    cs = d.get("cluster_size", (2, 5))
    if isinstance(cs, (str, bytes)) or not isinstance(cs, Sequence) or len(cs) != 2:
        raise ConfigError(f"{path}.cluster_size = {cs!r} must be [min, max] pixels per cluster")
    cmin = check_int(f"{path}.cluster_size[0]", cs[0], 1, _MAX_CLUSTER_SIZE)
    cmax = check_int(f"{path}.cluster_size[1]", cs[1], cmin, _MAX_CLUSTER_SIZE)
    out["cluster_size"] = (cmin, cmax)
    ck = d.get("cluster_kinds", ("dead",))
    if isinstance(ck, str):
        ck = (ck,)
    if not isinstance(ck, Sequence) or len(ck) == 0:
        raise ConfigError(f"{path}.cluster_kinds = {ck!r} must be a non-empty list of kind names")
    out["cluster_kinds"] = tuple(
        check_choice(f"{path}.cluster_kinds[{i}]", k, KIND_NAMES) for i, k in enumerate(ck)
    )

    out["rows"] = _int_tuple(f"{path}.rows", d.get("rows", ()))
    out["cols"] = _int_tuple(f"{path}.cols", d.get("cols", ()))
    out["line_kind"] = check_choice(f"{path}.line_kind", d.get("line_kind", "dead"), KIND_NAMES)

    listed = d.get("listed", ())
    if isinstance(listed, (str, bytes, Mapping)) or not isinstance(listed, Sequence):
        raise ConfigError(f"{path}.listed = {listed!r} is not a list of tables")
    norm_listed = []
    seen: dict[tuple[int, int], int] = {}
    for i, item in enumerate(listed):
        f = f"{path}.listed[{i}]"
        if not isinstance(item, Mapping):
            raise ConfigError(f"{f} = {item!r} is not a table with row, col, kind")
        for key in item:
            if key not in _LISTED_KEYS:
                raise ConfigError(f"{f}.{key} is not a known key; known keys: {list(_LISTED_KEYS)}")
        for key in ("row", "col", "kind"):
            if key not in item:
                raise ConfigError(f"{f}.{key} is missing")
        r = check_int(f"{f}.row", item["row"], 0)
        c = check_int(f"{f}.col", item["col"], 0)
        kname = check_choice(f"{f}.kind", item["kind"], KIND_NAMES)
        entry: dict[str, Any] = {"row": r, "col": c, "kind": kname}
        if "value" in item:
            entry["value"] = _check_value(f"{f}.value", _kind(kname), item["value"])
        if (r, c) in seen:
            raise ConfigError(
                f"{f}: pixel (row {r}, col {c}) is already listed as {path}.listed[{seen[(r, c)]}]"
            )
        seen[(r, c)] = i
        norm_listed.append(entry)
    out["listed"] = tuple(norm_listed)

    out["stuck_value"] = check_scalar(f"{path}.stuck_value", d.get("stuck_value", 0.5), 0.0, 1.0)
    out["offset"] = check_scalar(f"{path}.offset", d.get("offset", 0.05), 0.0, 1.0, lo_open=True)
    out["low_resp"] = check_scalar(
        f"{path}.low_resp", d.get("low_resp", 0.2), 0.0, 1.0, lo_open=True, hi_open=True
    )
    out["high_resp"] = check_scalar(
        f"{path}.high_resp", d.get("high_resp", 3.0), 1.0, _HIGH_RESP_MAX, lo_open=True
    )
    out["noise"] = check_scalar(f"{path}.noise", d.get("noise", 0.02), 0.0, 1.0, lo_open=True)
    return out


@dataclass(frozen=True)
class DefectSpec:
    """What defects to inject. All fractions are of the active pixel count or of the ADC
    input range (``v_high - v_low``).

    Parameters
    ----------
    rates : mapping of str to float
        Kind name (``"dead"``, ``"stuck_high"``, ``"hot"``, ...) -> fraction of active
        pixels made defective as isolated pixels, each in [0, 1], sum <= 1. The exact count
        ``round(rate * H * W)`` is placed (fewer only if the frame runs out of good pixels).
    clusters : int
        Number of clusters (>= 0).
    cluster_size : (int, int)
        Min and max pixels per cluster; each cluster's size is drawn uniformly in between.
        Clusters are 8-connected.
    cluster_kinds : tuple of str
        Each cluster's kind is drawn uniformly from these.
    rows, cols : tuple of int
        Whole active rows / columns made defective, of kind ``line_kind``.
    line_kind : str
        Kind of the whole rows and columns.
    listed : tuple of mappings
        Explicit pixels ``{"row": r, "col": c, "kind": k, "value": v}``; ``value``
        optional and kind-specific (level for stuck_value, offset magnitude for hot/cold,
        factor for low_resp/high_resp, std for noisy), else the defaults below.
    stuck_value : float
        Default STUCK_VALUE level, fraction of the range in [0, 1].
    offset : float
        HOT / COLD offset magnitude, fraction of the range in (0, 1].
    low_resp : float
        LOW_RESP responsivity factor in (0, 1).
    high_resp : float
        HIGH_RESP responsivity factor in (1, 100].
    noise : float
        NOISY extra temporal noise std, fraction of the range in (0, 1].
    """

    rates: Mapping[str, float] = field(default_factory=dict)
    clusters: int = 0
    cluster_size: tuple[int, int] = (2, 5)
    cluster_kinds: tuple[str, ...] = ("dead",)
    rows: tuple[int, ...] = ()
    cols: tuple[int, ...] = ()
    line_kind: str = "dead"
    listed: tuple[Mapping, ...] = ()
    stuck_value: float = 0.5
    offset: float = 0.05
    low_resp: float = 0.2
    high_resp: float = 3.0
    noise: float = 0.02

    def __post_init__(self) -> None:
        values = _normalise({k: getattr(self, k) for k in KNOWN_KEYS}, "fpa.defects")
        for k, v in values.items():
            object.__setattr__(self, k, v)

    @classmethod
    def from_dict(cls, d: Mapping[str, Any], path: str = "fpa.defects") -> DefectSpec:
        """Build a spec from a TOML table.

        Unknown keys and bad values raise :class:`ConfigError` naming ``f"{path}.{key}"``.
        """
        if not isinstance(d, Mapping):
            raise ConfigError(f"{path} = {d!r} is not a table")
        for key in d:
            if key not in KNOWN_KEYS:
                raise ConfigError(
                    f"{path}.{key} is not a known key; known keys: {list(KNOWN_KEYS)}"
                )
        return cls(**_normalise(d, path))

    def check_frame(self, shape: tuple[int, int], path: str = "fpa.defects") -> None:
        """Raise ConfigError if a row, column, listed pixel or cluster does not fit a
        frame of ``shape`` = (H, W)."""
        h, w = shape
        for i, r in enumerate(self.rows):
            check_int(f"{path}.rows[{i}]", r, 0, h - 1)
        for i, c in enumerate(self.cols):
            check_int(f"{path}.cols[{i}]", c, 0, w - 1)
        for i, item in enumerate(self.listed):
            check_int(f"{path}.listed[{i}].row", item["row"], 0, h - 1)
            check_int(f"{path}.listed[{i}].col", item["col"], 0, w - 1)
        if self.clusters > 0 and self.cluster_size[0] > h * w:
            raise ConfigError(
                f"{path}.cluster_size[0] = {self.cluster_size[0]} is outside the allowed range "
                f"[1, {h * w}] for a {h}x{w} frame"
            )

    @property
    def is_empty(self) -> bool:
        """True when the spec places no defect at all (then no random draw happens)."""
        return (
            not any(self.rates.values())
            and self.clusters == 0
            and not self.rows
            and not self.cols
            and not self.listed
        )

    def default_value(self, kind: DefectKind) -> float:
        """Kind-specific parameter used when none is given (0 for kinds without one)."""
        return {
            DefectKind.STUCK_VALUE: self.stuck_value,
            DefectKind.HOT: self.offset,
            DefectKind.COLD: self.offset,
            DefectKind.LOW_RESP: self.low_resp,
            DefectKind.HIGH_RESP: self.high_resp,
            DefectKind.NOISY: self.noise,
        }.get(kind, 0.0)


@dataclass(frozen=True)
class DefectMap:
    """Ground truth of the defects over the active area.

    Attributes
    ----------
    kind : numpy.ndarray
        ``(H, W)`` uint8 :class:`DefectKind` codes.
    pattern : numpy.ndarray
        ``(H, W)`` uint8 :class:`DefectPattern` codes.
    level : numpy.ndarray
        ``(H, W)`` float64, fractions of the ADC input range: STUCK_VALUE level, HOT/COLD
        signed offset, NOISY extra std; 0 elsewhere.
    resp : numpy.ndarray
        ``(H, W)`` float64 optical responsivity factor, 1.0 except LOW_RESP / HIGH_RESP.
    """

    kind: np.ndarray
    pattern: np.ndarray
    level: np.ndarray
    resp: np.ndarray

    def __post_init__(self) -> None:
        shape = np.shape(self.kind)
        if len(shape) != 2:
            raise ConfigError(f"DefectMap.kind has shape {shape}; expected (H, W)")
        for name in ("pattern", "level", "resp"):
            if np.shape(getattr(self, name)) != shape:
                raise ConfigError(
                    f"DefectMap.{name} has shape {np.shape(getattr(self, name))}; expected {shape}"
                )

    @property
    def shape(self) -> tuple[int, int]:
        """``(H, W)`` of the active area."""
        return self.kind.shape  # type: ignore[return-value]

    @property
    def mask(self) -> np.ndarray:
        """``(H, W)`` bool, True where the pixel is defective."""
        return self.kind != DefectKind.GOOD

    def counts(self) -> dict[str, int]:
        """Number of pixels of each defect kind (every kind name, GOOD excluded)."""
        bc = np.bincount(self.kind.ravel(), minlength=len(DefectKind))
        return {k.name.lower(): int(bc[k]) for k in DefectKind if k != DefectKind.GOOD}


# ---------------------------------------------------------------------------------------
# Injection
# ---------------------------------------------------------------------------------------


def _stream(seed: int, name: str) -> np.random.Generator:
    """Independent random stream per injection stage, derived from the seed and a name."""
    key = int.from_bytes(hashlib.blake2b(name.encode("utf-8"), digest_size=8).digest(), "little")
    return np.random.Generator(np.random.PCG64(np.random.SeedSequence(seed, spawn_key=(key,))))


# 8-connected neighbour offsets, in a fixed order (the growth order depends on it).
_NEIGHBOURS = ((-1, -1), (-1, 0), (-1, 1), (0, -1), (0, 1), (1, -1), (1, 0), (1, 1))


def _grow_cluster(free: np.ndarray, start: int, size: int, rng: np.random.Generator) -> list[int]:
    """Grow an 8-connected cluster of ``size`` pixels from flat index ``start``.

    Eden-type growth: each step adds a random free pixel adjacent to the cluster, picked
    from the frontier list, in which a pixel appears once per cluster pixel it touches (so
    compact shapes are favoured). Stops early if the cluster is boxed in.
    ``free`` (H, W) bool is updated in place.
    """
    h, w = free.shape
    flat = free.reshape(-1)
    cluster = [start]
    flat[start] = False
    frontier: list[int] = []

    def push(p: int) -> None:
        r, c = divmod(p, w)
        for dr, dc in _NEIGHBOURS:
            rr, cc = r + dr, c + dc
            if 0 <= rr < h and 0 <= cc < w and flat[rr * w + cc]:
                frontier.append(rr * w + cc)

    push(start)
    while len(cluster) < size and frontier:
        i = int(rng.integers(len(frontier)))
        frontier[i], frontier[-1] = frontier[-1], frontier[i]
        p = frontier.pop()
        if not flat[p]:
            continue  # already taken through another entry
        flat[p] = False
        cluster.append(p)
        push(p)
    return cluster


def _pick_free(flat_free: np.ndarray, n_free: int, rng: np.random.Generator) -> int:
    """A uniformly random free pixel (flat index).

    Rejection sampling over the whole frame (cheap while most pixels are free), then an
    exact pick among the free pixels in raster order.
    """
    for _ in range(32):
        p = int(rng.integers(flat_free.size))
        if flat_free[p]:
            return p
    return int(np.flatnonzero(flat_free)[int(rng.integers(n_free))])


def inject_defects(shape: tuple[int, int], spec: DefectSpec, seed: int) -> DefectMap:
    """Place defects over the active area and return their ground-truth map.

    Parameters
    ----------
    shape : (int, int)
        ``(H, W)`` of the active area, pixels.
    spec : DefectSpec
        What to place.
    seed : int
        Non-negative seed. Same spec and seed give the same bits. Clusters and isolated
        pixels draw from separate streams derived from the seed.

    Returns
    -------
    DefectMap

    Raises
    ------
    ConfigError
        If a row, column or listed pixel is outside the frame, or a cluster cannot fit.

    Notes
    -----
    Stages run in precedence order (listed, rows/cols, clusters, isolated rates), each
    writing only pixels still GOOD, so a higher-precedence pattern is never overwritten.
    """
    if isinstance(shape, (str, bytes)) or not hasattr(shape, "__len__") or len(shape) != 2:
        raise ConfigError(f"shape = {shape!r} must be (rows, cols) of the active area")
    h = check_int("shape[0]", shape[0], 1)
    w = check_int("shape[1]", shape[1], 1)
    if not isinstance(spec, DefectSpec):
        raise ConfigError(f"spec = {spec!r} is not a DefectSpec")
    seed = check_int("seed", seed, 0)
    spec.check_frame((h, w))

    kind = np.zeros((h, w), dtype=np.uint8)
    pattern = np.zeros((h, w), dtype=np.uint8)
    level = np.zeros((h, w), dtype=np.float64)
    resp = np.ones((h, w), dtype=np.float64)
    if spec.is_empty:
        return DefectMap(kind, pattern, level, resp)

    def put(
        rows: Any, cols: Any, k: DefectKind, pat: DefectPattern, value: float | None = None
    ) -> None:
        # Set pixels (index arrays or slices) to kind k with its parameter.
        v = spec.default_value(k) if value is None else value
        kind[rows, cols] = k
        pattern[rows, cols] = pat
        if k in (DefectKind.LOW_RESP, DefectKind.HIGH_RESP):
            resp[rows, cols] = v
        elif k == DefectKind.COLD:
            level[rows, cols] = -v
        else:
            level[rows, cols] = v  # 0 for kinds without a level

    # 1. Listed pixels (highest precedence).
    for item in spec.listed:
        put(item["row"], item["col"], _kind(item["kind"]), DefectPattern.LISTED, item.get("value"))

    # 2. Whole rows, then whole columns, on pixels still good.
    lk = _kind(spec.line_kind)
    for lines, pat, axis in (
        (spec.rows, DefectPattern.ROW, 0),
        (spec.cols, DefectPattern.COLUMN, 1),
    ):
        if not lines:
            continue
        sel = np.zeros((h, w), dtype=bool)
        idx = np.unique(np.asarray(lines, dtype=np.int64))
        if axis == 0:
            sel[idx, :] = True
        else:
            sel[:, idx] = True
        sel &= kind == DefectKind.GOOD
        put(*np.nonzero(sel), lk, pat)

    # 3. Clusters, grown through good pixels only.
    if spec.clusters > 0:
        rng = _stream(seed, "fpa.defects.clusters")
        free = kind == DefectKind.GOOD
        cmin, cmax = spec.cluster_size
        ckinds = [_kind(k) for k in spec.cluster_kinds]
        n_free = int(np.count_nonzero(free))
        flat_free = free.reshape(-1)
        for _ in range(spec.clusters):
            if n_free == 0:
                break
            size = int(rng.integers(cmin, cmax + 1))
            ck = ckinds[int(rng.integers(len(ckinds)))]
            start = _pick_free(flat_free, n_free, rng)
            pix = np.asarray(_grow_cluster(free, start, size, rng), dtype=np.int64)
            n_free -= pix.size
            put(*np.divmod(pix, w), ck, DefectPattern.CLUSTER)

    # 4. Isolated pixels: exact counts, distinct positions among the still-good pixels.
    counts = [
        (k, round(spec.rates.get(k.name.lower(), 0.0) * h * w))
        for k in DefectKind
        if k != DefectKind.GOOD
    ]
    n_total = sum(n for _, n in counts)
    if n_total > 0:
        rng = _stream(seed, "fpa.defects.isolated")
        flat_kind = kind.reshape(-1)
        n_taken = int(np.count_nonzero(flat_kind))
        # Draw n_total + n_taken distinct pixels in random order and keep the first n_total
        # good ones: a uniform random subset of the good pixels, without building the list
        # of all good pixels (memory for large frames).
        m = min(h * w, n_total + n_taken)
        cand = rng.choice(h * w, size=m, replace=False)
        cand = cand[flat_kind[cand] == DefectKind.GOOD][:n_total]
        start = 0
        for k, n in counts:
            if n == 0:
                continue
            pix = cand[start : start + n]
            start += n
            if pix.size:
                put(*np.divmod(pix, w), k, DefectPattern.ISOLATED)

    return DefectMap(kind, pattern, level, resp)


# ---------------------------------------------------------------------------------------
# Application in the signal chain
# ---------------------------------------------------------------------------------------


def _check_rails(v_low: float, v_high: float) -> tuple[float, float]:
    lo = check_scalar("v_low", v_low, unit="V")
    hi = check_scalar("v_high", v_high, lo, lo_open=True, unit="V")
    return lo, hi


def apply_voltage_defects(
    v: np.ndarray, defects: DefectMap, v_low: float, v_high: float, v_reset: float,
    *, copy: bool = True,
) -> np.ndarray:
    """Apply the output-voltage defects to integrator output voltages.

    Parameters
    ----------
    v : numpy.ndarray
        Integrator output voltages, V, shape ``(..., H, W)`` (a batch of active frames).
    defects : DefectMap
        Ground truth over ``(H, W)``.
    v_low, v_high : float
        Low and high rails of the ADC input range, V, ``v_low < v_high``.
    v_reset : float
        Integrator reference (reset) level, V, read by DEAD pixels.

    copy : bool
        False: change ``v`` in place (a float64 array the caller owns) instead of a copy.

    Returns
    -------
    numpy.ndarray
        float64 array (new unless ``copy`` is False), same shape: DEAD -> ``v_reset``, STUCK_LOW -> ``v_low``,
        STUCK_HIGH -> ``v_high``, STUCK_VALUE -> ``v_low + level * (v_high - v_low)``,
        HOT/COLD -> ``v + level * (v_high - v_low)``; other pixels unchanged. Not clipped.
    """
    if not isinstance(defects, DefectMap):
        raise ConfigError(f"defects = {defects!r} is not a DefectMap")
    lo, hi = _check_rails(v_low, v_high)
    vr = check_scalar("v_reset", v_reset, unit="V")
    out = np.array(v, dtype=np.float64, copy=True) if copy else v
    if out.ndim < 2 or out.shape[-2:] != defects.shape:
        raise ConfigError(
            f"v has shape {out.shape}; expected (..., {defects.shape[0]}, {defects.shape[1]})"
        )
    apply_voltage_defects_at(out, voltage_defect_index(defects), lo, hi, vr)
    return out


VoltageDefects = tuple[np.ndarray, np.ndarray, np.ndarray]


def voltage_defect_index(defects: DefectMap) -> VoltageDefects:
    """(flat index, kind, level) of the defective pixels of a map: what
    :func:`apply_voltage_defects_at` needs, computed once per sensor."""
    idx = np.flatnonzero(defects.kind)
    return idx, defects.kind.reshape(-1)[idx], defects.level.reshape(-1)[idx]


def apply_voltage_defects_at(out: np.ndarray, index: VoltageDefects, lo: float, hi: float,
                             vr: float) -> None:
    """:func:`apply_voltage_defects` in place on a float64 array ``out`` (..., H, W), with
    the defects given by :func:`voltage_defect_index` and checked rails lo, hi and reset
    level vr (V)."""
    idx, kind, level = index
    if idx.size == 0:
        return
    # Work on the defective pixels only: a handful out of a frame.
    flat = out.reshape(*out.shape[:-2], -1)
    span = hi - lo
    vals = flat[..., idx]
    vals = np.where(kind == DefectKind.DEAD, vr, vals)
    vals = np.where(kind == DefectKind.STUCK_LOW, lo, vals)
    vals = np.where(kind == DefectKind.STUCK_HIGH, hi, vals)
    vals = np.where(kind == DefectKind.STUCK_VALUE, lo + level * span, vals)
    offset = (kind == DefectKind.HOT) | (kind == DefectKind.COLD)
    vals = np.where(offset, vals + level * span, vals)
    flat[..., idx] = vals


def noisy_sigma(defects: DefectMap, v_low: float, v_high: float) -> np.ndarray | None:
    """Extra temporal noise std of NOISY pixels, V.

    Returns
    -------
    numpy.ndarray or None
        ``(H, W)`` float64, ``level * (v_high - v_low)`` on NOISY pixels and 0 elsewhere;
        None when there is no NOISY pixel (so the caller draws nothing).
    """
    if not isinstance(defects, DefectMap):
        raise ConfigError(f"defects = {defects!r} is not a DefectMap")
    lo, hi = _check_rails(v_low, v_high)
    m = defects.kind == DefectKind.NOISY
    if not m.any():
        return None
    return np.where(m, defects.level * (hi - lo), 0.0)
