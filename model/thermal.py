"""The camera's thermal network: the ambient drives the housing, the housing the FPA (and the
lens and the shutter), every node a first-order lag with its own time constant.

    tau_h dT_housing/dt = T_ambient + dT_h - T_housing      (housing_tau, housing_self_heating)
    tau_f dT_fpa/dt     = T_housing + dT_f - T_fpa          (fpa_tau, fpa_self_heating)
    tau_l dT_lens/dt    = T_housing - T_lens                (lens_tau; absent: at the housing)
    tau_s dT_shutter/dt = T_housing - T_shutter             (shutter_tau; absent: at the housing)

The self-heating terms are the rises once settled (the camera's own dissipation: the
housing dT_h above the ambient, the FPA dT_f above the housing); every node starts at
``start`` (power-on, default the ambient's first value), so a constant ambient gives the
warm-up of a camera just switched on. A housing given explicitly (a profile of the
sequence) replaces the housing node as the input of the others.

:meth:`ThermalNetwork.solve` advances the linear system x' = A x + B w(t) exactly for an
input w (the ambient, or the explicit housing) that is linear between the frame times (a
first-order hold): with the frames equally spaced by h, once per run,
exp(h [[A, B, 0], [0, 0, I], [0, 0, 0]]) = [[Phi, G1, G2], ...] (Van Loan) and every frame
x_(k+1) = Phi x_k + G1 w_k + G2 (w_(k+1) - w_k) / h, for an ambient ramp as exact as the
floating point (checked against ``scipy.integrate.solve_ivp``, tests/test_thermal.py).
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

import numpy as np

from irnuc.model.profiles import _number
from irnuc.model.validate import ConfigError

#: Keys of a ``[sequence.network]`` table: (required, optional).
NETWORK_KEYS: tuple[tuple[str, ...], tuple[str, ...]] = (
    ("housing_tau", "fpa_tau"),
    ("start", "housing_self_heating", "fpa_self_heating", "lens_tau", "shutter_tau"),
)
#: The nodes whose temperatures a network gives, in the order of its state vector.
NODES = ("housing", "fpa", "lens", "shutter")


@dataclass(frozen=True)
class ThermalNetwork:
    """The network of a sequence (see the module docstring); times in s, temperatures K."""

    housing_tau: float
    fpa_tau: float
    start: float | None = None
    housing_self_heating: float = 0.0
    fpa_self_heating: float = 0.0
    lens_tau: float | None = None
    shutter_tau: float | None = None
    path: str = "sequence.network"

    @classmethod
    def from_table(cls, table: Any, path: str = "sequence.network") -> ThermalNetwork:
        """A network from its TOML table; every key checked (one line naming it)."""
        from irnuc.common.schema import nearest

        if not isinstance(table, Mapping):
            raise ConfigError(f"{path} = {table!r} must be a table")
        required, optional = NETWORK_KEYS
        known = (*required, *optional)
        for key in table:
            if key not in known:
                raise ConfigError(f"{path}.{key} is not a known field{nearest(str(key), known)} "
                                  f"(known here: {', '.join(known)})")
        for key in required:
            if key not in table:
                raise ConfigError(f"{path}.{key} is required (s: the node's time constant)")
        kw: dict[str, Any] = {}
        for key in ("housing_tau", "fpa_tau", "lens_tau", "shutter_tau"):
            if key in table:
                kw[key] = _number(path, key, table[key], 0.0, 1e8, "s", lo_open=True)
        for key in ("housing_self_heating", "fpa_self_heating"):
            if key in table:
                kw[key] = _number(path, key, table[key], -100.0, 100.0, "K")
        if "start" in table:
            kw["start"] = _number(path, "start", table["start"], 0.0, 1e4, "K", lo_open=True)
        return cls(**kw, path=path)

    def to_dict(self) -> dict[str, Any]:
        return {k: getattr(self, k) for k in ("housing_tau", "fpa_tau", "start",
                                              "housing_self_heating", "fpa_self_heating",
                                              "lens_tau", "shutter_tau")}

    def solve(self, t: np.ndarray, ambient: np.ndarray,
              housing: np.ndarray | None = None) -> dict[str, np.ndarray]:
        """Every node's temperature at the times ``t`` (s, equally spaced), K.

        ``ambient`` (K at ``t``) drives the housing; ``housing`` (K at ``t``), when given,
        replaces the housing node. Returns ``housing``, ``fpa``, ``lens``, ``shutter`` (each
        (N,); the lens and shutter at the housing when they have no time constant).
        """
        t = np.asarray(t, dtype=np.float64)
        n = t.size
        if n == 0:
            return {k: np.empty(0) for k in NODES}
        start = float(ambient[0] if self.start is None else self.start)
        own_housing = housing is None
        u = np.asarray(ambient if own_housing else housing, dtype=np.float64)
        # the state: [housing (own only), fpa, lens (own tau), shutter (own tau)]
        names = (["housing"] if own_housing else []) + ["fpa"]
        names += [k for k in ("lens", "shutter") if getattr(self, f"{k}_tau") is not None]
        m = len(names)
        A = np.zeros((m, m))
        Bw = np.zeros((m, 2))  # inputs: u (the ambient or the housing), 1 (self-heating)
        idx = {k: i for i, k in enumerate(names)}

        def follows(node: str, tau: float, source: str, offset: float) -> None:
            i = idx[node]
            A[i, i] = -1.0 / tau
            if source == "input":
                Bw[i, 0] += 1.0 / tau
            else:
                A[i, idx[source]] += 1.0 / tau
            Bw[i, 1] += offset / tau

        if own_housing:
            follows("housing", self.housing_tau, "input", self.housing_self_heating)
        src = "housing" if own_housing else "input"
        follows("fpa", self.fpa_tau, src, self.fpa_self_heating)
        for k in ("lens", "shutter"):
            tau = getattr(self, f"{k}_tau")
            if tau is not None:
                follows(k, tau, src, 0.0)
        x = np.empty((n, m))
        x[0] = start
        if n > 1:
            h = float(t[1] - t[0])
            if not np.allclose(np.diff(t), h, rtol=1e-9, atol=0.0):
                raise ConfigError(f"{self.path}: frames must be equally spaced in time")
            Phi, G1, G2 = _foh(A, Bw, h)
            w = np.stack([u, np.ones(n)], axis=1)
            for k in range(n - 1):
                x[k + 1] = Phi @ x[k] + G1 @ w[k] + G2 @ ((w[k + 1] - w[k]) / h)
        out = {name: x[:, i].copy() for i, name in enumerate(names)}
        if not own_housing:
            out["housing"] = u.copy()
        for k in ("lens", "shutter"):
            out.setdefault(k, out["housing"].copy())
        return {k: out[k] for k in NODES}


def _foh(A: np.ndarray, Bw: np.ndarray, h: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Phi, G1, G2 of the first-order-hold discretization of x' = A x + Bw w over h (Van
    Loan's block exponential)."""
    from scipy.linalg import expm

    m, p = Bw.shape
    M = np.zeros((m + 2 * p, m + 2 * p))
    M[:m, :m] = A
    M[:m, m:m + p] = Bw
    M[m:m + p, m + p:] = np.eye(p)
    E = expm(M * h)
    return E[:m, :m], E[:m, m:m + p], E[:m, m + p:]


