"""The sensor pipeline: a small graph of stages with declared inputs and outputs.

A request for some outputs runs only the stages those outputs need, each once: the stages
that do not depend on the scene (per-pixel parameters, defects, cos^4, housing radiance,
optical coupling, the solver's reference solution) once per configured sensor, the others
once per chunk of frames. The graph itself is built from the configuration and the run, so
only the configured skimming mode is computed, the noise stage exists only when noise is
configured, and the stages that depend on the substrate or housing temperature (their
radiance, the housing power, the nominal skim voltage) become per-frame stages only in a
run whose environment varies from frame to frame (a drift sequence, :mod:`model.sequence`).
:attr:`Pipeline.counts` records how often each stage ran and how many temperatures the
radiance series was evaluated at; the tests check "computes only what it needs" with these
counts.
"""

from __future__ import annotations

import json
import math
import warnings
from collections import Counter
from collections.abc import Callable, Iterator, Mapping, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

from irnuc.model import stages as st
from irnuc.model.config import config_digest
from irnuc.model.core import bolometer as _kb
from irnuc.model.core import stream as _ks
from irnuc.model.fpa import ArrayLayout
from irnuc.model.graph import ENV_FIELDS, RunContext, Stage, plan
from irnuc.model.scenes import Scene, check_temps
from irnuc.model.validate import ConfigError, check_choice, check_int

#: How the bolometer state goes from one frame to the next (docs/sequences.md):
#: ``steady``: every frame in equilibrium with its own scene and temperatures;
#: ``lagged``: the pre-pulse temperature of every pixel follows its equilibrium through its
#: own thermal time constant C/g (exact between pulses), the pulse as in ``steady``;
#: ``transient``: the time-domain model (:mod:`model.transient`), state carried.
THERMAL_MODES = ("steady", "lagged", "transient")

#: Names a caller can request from :func:`simulate`, and the product each one is.
OUTPUTS: dict[str, str] = {
    "codes": "codes",                 # (N, H, W) ADC codes
    "voltage": "v_out",               # (N, H, W) integrator output at the ADC input, V
    "bolometer_voltage": "v_bolo",    # (N, rows, cols) I R(T), V, full array
    "temperature_rise": "dT",         # (N, rows, cols) T - T_substrate, K
    "status": "status",               # (N, rows, cols) solver status codes
    "power": "Q",                     # (N, rows, cols) absorbed power, W
    "scene_radiance": "L_scene",      # (N,) or (N, rows, cols) W m^-2 sr^-1
    "scene_temperature": "T_scene",   # (N,) or (N, H, W) K
    "params": "params",               # per-pixel R_ref, g, C over the full array
    "defects": "defects",             # DefectMap (ground truth)
    "cos4": "cos4",                   # (rows, cols)
    "blind_codes": "blind_codes",     # (N, K) ADC codes of the reference pixels
    "blind_positions": "reference_positions",  # (K, 2) their full-array (row, col)
}




@dataclass(frozen=True)
class GraphKey:
    """What shapes a run's stage graph besides the configuration."""

    varying: frozenset[str] = frozenset()  # environment fields that vary per frame
    thermal: str = "steady"  # THERMAL_MODES
    shutter: bool = False  # some frame has its shutter closed
    lens: bool = False  # the lens is not at the housing temperature in some frame


def build_stages(cfg: Mapping[str, Any], key: GraphKey = GraphKey()) -> list[Stage]:
    """The stage graph for one validated configuration and one kind of run."""
    env_varies = bool(key.varying & {"T_substrate", "T_cam"})
    # The housing and substrate radiance of every frame replace the configuration's (which
    # the solve's reference still uses) when they vary; housing power and skim voltage follow.
    L_key = "L_env_frames" if env_varies else "L_env"
    power_in = ("L_scene", "k_scene", "q_env", "defect_resp")
    if key.shutter:
        power_in += ("shutter_view", L_key)
    if key.lens:
        power_in += ("lens_view", L_key)
    stages = [
        Stage("params", (), ("params",), False, st.stage_params),
        Stage("defects", (), ("defects",), False, st.stage_defects),
        Stage("cos4", (), ("cos4",), False, st.stage_cos4),
        Stage("env_radiance", (), ("L_env",), False, st.stage_env_radiance),
        Stage("coupling", ("cos4",), ("k_scene", "seen"), False, st.stage_coupling),
        Stage("scene", (), ("T_scene",), True, st.stage_scene),
        Stage("scene_radiance", ("T_scene",), ("L_scene",), True, st.stage_scene_radiance),
        Stage("power", power_in, ("Q",), True, st.env_input(st.stage_power, L_key)),
        Stage("solve_coefficients", ("params",), ("solve_coef",), False, st.stage_coefficients),
        Stage("solve_reference", ("L_env", "k_scene", "seen", "defects", "params", "solve_coef"),
              ("solve_reference",), False, st.stage_reference_solution),
        st.make_skim_stage(cfg["readout"]["skimming"]),
        Stage("integrator", ("v_sense", "v_ref", "defect_index", "status"), ("v_int",), True,
              st.stage_integrator),
        Stage("defect_index", ("defects",), ("defect_index", "defect_resp"), False,
              st.stage_defect_index),
        Stage("reference_layout", (), ("reference_positions",), False, st.stage_reference_layout),
        Stage("reference_pixels", ("v_sense", "status", "reference_positions"),
              ("blind_codes",), True, st.stage_reference_pixels),
    ]
    if env_varies:
        stages.append(Stage("env_frames", (), ("L_env_frames",), True, st.stage_env_frames))
    stages += [
        Stage("housing", ("seen", L_key), ("q_env",), env_varies, st.env_input(st.stage_housing, L_key)),
        Stage("v_skim", (L_key,), ("v_skim",), env_varies, st.env_input(st.stage_v_skim, L_key)),
    ]
    if key.shutter:
        stages.append(Stage("shutter_view", ("cos4",), ("shutter_view",), False,
                            st.stage_shutter_view))
    if key.lens:
        stages.append(Stage("lens_view", ("cos4",), ("lens_view",), False, st.stage_lens_view))
    bolo_out = ("v_bolo", "dT", "status", "iters")
    if key.thermal == "transient":
        stages.append(Stage("bolometer", ("Q", "params"), bolo_out, True,
                            st.stage_bolometer_transient))
    elif cfg["bolometer"]["pulse"] == "integrated":
        stages.append(Stage("pulse_reference", ("L_env", "k_scene", "seen", "defects", "params"),
                            ("pulse_ref",), False, st.stage_pulse_reference))
        fn = (st.stage_bolometer_train_lagged if key.thermal == "lagged"
              else st.stage_bolometer_periodic)
        stages.append(Stage("bolometer", ("Q", "params", "pulse_ref"), bolo_out, True, fn))
    else:
        fn = st.stage_bolometer_lagged if key.thermal == "lagged" else st.stage_bolometer
        stages.append(Stage("bolometer", ("Q", "params", "solve_coef", "solve_reference"),
                            bolo_out, True, fn))
    if st.bolometer_noise_on(cfg):
        stages.append(Stage("bolometer_noise", ("v_bolo", "dT", "status"), ("v_sense",), True,
                            st.stage_bolometer_noise))
    else:
        stages.append(Stage("no_bolometer_noise", ("v_bolo",), ("v_sense",), True,
                            lambda ctx, inp: {"v_sense": inp["v_bolo"]}))
    if st.noise_configured(cfg):
        stages.append(Stage("noisy_pixels", ("defects",), ("noisy_sigma",), False,
                            st.stage_noisy_pixels))
        stages.append(Stage("noise", ("v_int", "noisy_sigma"), ("v_out",), True,
                            st.stage_noise))
    else:
        stages.append(Stage("no_noise", ("v_int",), ("v_out",), True,
                            lambda ctx, inp: {"v_out": inp["v_int"]}))
    stages.append(Stage("adc", ("v_out",), ("codes",), True, st.stage_adc))
    return stages


@dataclass
class Frames:
    """Result of :func:`simulate`.

    Attributes
    ----------
    codes : ndarray or None
        (N, H, W) raw ADC codes (uint16 up to 16 bits).
    temps : ndarray
        (N,) scene base temperature of every frame, K.
    defect_kind, defect_pattern : ndarray or None
        (H, W) ground truth (model.defects.DefectKind / DefectPattern codes).
    outputs : dict
        Every requested output by name (see :data:`OUTPUTS`).
    diagnostics : dict
        Self-heating, solver failures, clipped codes.
    counts : dict
        Stage executions and radiance evaluations of this run.
    blind_codes : ndarray or None
        (N, K) ADC codes of the reference (shielded) pixels read out beside the image
        (``readout.reference_pixels``; K = 0 for ``none``).
    blind_positions : ndarray or None
        (K, 2) int32 full-array (row, col) of those pixels (the active area starts at
        ``layout.active_slice``).
    """

    codes: np.ndarray | None
    temps: np.ndarray
    defect_kind: np.ndarray | None
    defect_pattern: np.ndarray | None
    adc_bits: int
    config: dict[str, Any]
    seed: int
    scene: Scene
    outputs: dict[str, Any]
    diagnostics: dict[str, Any]
    counts: dict[str, int]
    blind_codes: np.ndarray | None = None
    blind_positions: np.ndarray | None = None

    def config_json(self) -> str:
        return json.dumps({"config": self.config, "scene": {"kind": self.scene.kind,
                           "params": _jsonable(self.scene.params)}, "seed": self.seed,
                           "config_digest": config_digest(self.config)}, sort_keys=True)


def _jsonable(params: Mapping[str, Any]) -> dict[str, Any]:
    return {k: (v.tolist() if isinstance(v, np.ndarray) else v) for k, v in params.items()}


class Pipeline:
    """A configured sensor: per-pixel parameters, defects and optics fixed by (config, seed).

    The scene-independent products are computed on first use and kept, so a sensor that
    produces frames call after call pays for them once. They depend only on the
    configuration and the seed, both fixed for the lifetime of the object.
    """

    def __init__(self, cfg: Mapping[str, Any], seed: int = 0) -> None:
        cfg = checked_config(cfg)
        self.cfg = cfg
        self.seed = check_int("seed", seed, 0, 2**63 - 1)
        f = cfg["fpa"]
        self.layout = ArrayLayout(f["active_rows"], f["active_cols"], tuple(f["boundary"]),
                                  tuple(f["blind"]))
        self._graphs: dict[GraphKey, list[Stage]] = {}
        self.stages = self.graph(GraphKey())
        self.counts: Counter = Counter()
        self._static: dict[str, Any] = {}

    def graph(self, key: GraphKey) -> list[Stage]:
        """The stage graph of one kind of run (built once)."""
        if key not in self._graphs:
            self._graphs[key] = build_stages(self.cfg, key)
        return self._graphs[key]

    def graph_key(self, env: Mapping[str, Any] | None, thermal: str = "steady") -> GraphKey:
        """The graph a run with this per-frame environment needs: a field is per-frame only
        if it differs from the configuration somewhere."""
        check_choice("thermal", thermal, THERMAL_MODES)
        if not env:
            return GraphKey(thermal=thermal)
        unknown = set(env) - set(ENV_FIELDS)
        if unknown:
            raise ConfigError(f"env: unknown field(s) {sorted(unknown)}; known {list(ENV_FIELDS)}")
        e = self.cfg["environment"]
        varying = frozenset(k for k in ("T_substrate", "T_cam")
                            if k in env and np.any(np.asarray(env[k]) != e[k]))
        shutter = bool("shutter" in env and np.any(env["shutter"]))
        lens = bool("T_lens" in env and np.any(np.asarray(env["T_lens"])
                                                != np.asarray(env.get("T_cam", e["T_cam"]))))
        return GraphKey(varying, thermal, shutter, lens)

    def iter_chunks(self, temps: np.ndarray, products: Sequence[str], scene: Scene | None = None,
                    *, env: Mapping[str, np.ndarray] | None = None, thermal: str = "steady",
                    frame_period: float | None = None, transient: Any = None,
                    chunk_frames: int | None = None,
                    progress: Callable[[int, int], None] | None = None,
                    first_frame: int = 0,
                    ) -> Iterator[tuple[int, dict[str, Any]]]:
        """Compute ``products`` chunk by chunk: yields (first frame, products of the chunk).

        Parameters
        ----------
        temps : ndarray
            (N,) scene base temperature of each frame, K.
        products : sequence of str
            Product names (values of :data:`OUTPUTS`, or any stage output).
        scene : Scene, optional
        env : dict of (N,) arrays, optional
            Per-frame environment (:data:`ENV_FIELDS`): T_substrate, T_cam, T_shutter (K)
            and shutter (bool). A field equal to the configuration everywhere stays static.
        thermal : str
            :data:`THERMAL_MODES`; ``lagged`` and ``transient`` carry the bolometer state
            from frame to frame and need ``frame_period`` (s).
        transient : TransientSettings, optional
            Settings of the ``transient`` mode.
        chunk_frames : int, optional
            Frames per chunk (default ``run.chunk_frames``).
        progress : callable, optional
            Called as ``progress(done, total)`` after each chunk.
        first_frame : int
            Index of the run's first frame in the noise streams (default 0): runs of one
            sensor given disjoint frame ranges draw independent noise, the same pixels.
        """
        first_frame = check_int("first_frame", first_frame, 0, 2**62)
        n = len(temps)
        key = self.graph_key(env, thermal)
        period = st.frame_period(self.cfg)
        if frame_period is not None and abs(frame_period - period) > 1e-12 * period:
            raise ConfigError(f"frame_period = {frame_period:g} s differs from the sensor's "
                              f"1 / readout.frame_rate = {period:g} s; configure the sensor "
                              "with the run's frame rate")
        if env is not None:
            for k, v in env.items():
                if np.shape(v) != (n,):
                    raise ConfigError(f"env.{k} has shape {np.shape(v)}; one value per frame "
                                      f"({n}) is required")
        stages = self.graph(key)
        order = plan(stages, products)
        chunked = [s for s in order if s.per_chunk]
        chunk_outputs = {o for s in stages if s.per_chunk for o in s.outputs}
        ctx = RunContext(self.cfg, self.layout, scene or Scene(), self.seed, counts=self.counts,
                         frame_period=period, transient=transient)
        for stage in order:
            if not stage.per_chunk and not all(o in self._static for o in stage.outputs):
                self.counts[stage.name] += 1
                self._static.update(stage.fn(ctx, {k: self._static[k] for k in stage.inputs}))
        step = chunk_frames or (self.cfg["run"]["chunk_frames"] if chunked else max(n, 1))
        for start in range(0, n, step):
            ctx.temps = temps[start:start + step]
            ctx.first_frame = first_frame + start
            if env is not None:
                ctx.env = {k: np.asarray(v)[start:start + step] for k, v in env.items()}
            chunk = {k: v for k, v in self._static.items() if k not in chunk_outputs}
            ctx.demand = self._demand(stages, ctx, chunk)
            for stage in chunked:
                self.counts[stage.name] += 1
                chunk.update(stage.fn(ctx, {k: chunk[k] for k in stage.inputs}))
            if progress is not None:
                progress(min(start + step, n), n)
            yield start, {p: chunk[p] for p in products}

    def _demand(self, stages: Sequence[Stage], ctx: RunContext, chunk: dict[str, Any]
                ) -> Callable[[str], Any]:
        """``demand(product)`` for one chunk: a product needed only on a rare path (the
        skimming fallback), static ones computed once per sensor."""
        def demand(product: str) -> Any:
            for stage in plan(stages, [product], chunk):
                self.counts[stage.name] += 1
                out = stage.fn(ctx, {k: chunk[k] for k in stage.inputs})
                chunk.update(out)
                if not stage.per_chunk:
                    self._static.update(out)
            return chunk[product]

        return demand

    def run(self, temps: np.ndarray, products: Sequence[str], scene: Scene | None = None,
            progress: Callable[[int, int], None] | None = None, **run: Any) -> dict[str, Any]:
        """Compute ``products`` for the frames of ``temps``; per-chunk products stacked.
        Keyword arguments as :meth:`iter_chunks`."""
        key = self.graph_key(run.get("env"), run.get("thermal", "steady"))
        chunk_products = {o for s in self.graph(key) if s.per_chunk for o in s.outputs}
        parts: dict[str, list] = {p: [] for p in products}
        last: dict[str, Any] = {}
        for _, values in self.iter_chunks(temps, products, scene, progress=progress, **run):
            for p in products:
                parts[p].append(values[p])
            last = values
        if not last:  # no frame: static products only
            return {p: self._static[p] for p in products if p not in chunk_products}
        out: dict[str, Any] = {}
        for p in products:
            if p in chunk_products:
                out[p] = np.concatenate(parts[p]) if len(parts[p]) > 1 else parts[p][0]
            else:
                out[p] = last[p]
        return out

    def simulate(self, temps: Sequence[float] | np.ndarray, scene: str | Scene = "uniform", *,
                 repeats: int = 1, outputs: Sequence[str] = ("codes",),
                 scene_params: Mapping[str, Any] | None = None,
                 progress: Callable[[int, int], None] | None = None,
                 first_frame: int = 0) -> Frames:
        """Frames of this sensor; see :func:`simulate` for the parameters."""
        if isinstance(scene, str):
            scene = Scene(scene, dict(scene_params or {}))
        t = check_temps(temps)
        repeats = check_int("repeats", repeats, 1, 1_000_000)
        t = np.repeat(t, repeats)
        unknown = [o for o in outputs if o not in OUTPUTS]
        if unknown:
            raise ConfigError(f"outputs: unknown name(s) {unknown}; known {sorted(OUTPUTS)}")
        check_simulation_memory(self.cfg, t.size, outputs)
        wanted = [OUTPUTS[o] for o in outputs]
        if "codes" in outputs:
            # ground truth, diagnostics and the reference pixels read beside the image
            wanted += ["defects", "status", "dT", "blind_codes", "reference_positions"]
        before = Counter(self.counts)
        values = self.run(t, list(dict.fromkeys(wanted)), scene, progress,
                          first_frame=first_frame)
        defects = values.get("defects")
        return Frames(
            codes=values.get("codes"),
            temps=t,
            defect_kind=defects.kind if defects is not None else None,
            defect_pattern=defects.pattern if defects is not None else None,
            adc_bits=self.cfg["adc"]["bits"],
            config=dict(self.cfg),
            seed=self.seed,
            scene=scene,
            outputs={o: values[OUTPUTS[o]] for o in outputs},
            diagnostics=_diagnostics(self, values) if "status" in values else {},
            counts=dict(self.counts - before),
            blind_codes=values.get("blind_codes"),
            blind_positions=values.get("reference_positions"),
        )


# ---- argument and size checks at the API boundary ---------------------------------------

def checked_config(cfg: Any) -> dict[str, Any]:
    """``cfg`` validated (a no-op copy for a configuration from ``load_preset``/``load_config``);
    a bare dict, ``None`` or a half-filled mapping is one :class:`ConfigError` naming ``cfg``
    and the field, instead of a ``KeyError`` deep inside a stage."""
    from irnuc.model.config import validate

    if not isinstance(cfg, Mapping):
        raise ConfigError(f"cfg = {cfg!r:.60} is not a sensor configuration; use "
                          "model.load_preset(...) or model.load_config(...)")
    return validate(cfg, source="cfg")


#: Generous bytes per pixel of the full array: kept per run (parameters, defects, optics),
#: per frame of a chunk (the stages' float64 products and temporaries), and per frame of
#: the result for codes (uint16 + status + dT kept for the diagnostics) and for each other
#: per-frame output (float64). Checked against measured peaks (docs/robustness.md).
_BYTES_STATIC, _BYTES_CHUNK, _BYTES_CODES = 200, 160, 11
_PER_FRAME_OUTPUTS = ("voltage", "bolometer_voltage", "power", "scene_radiance", "scene_temperature")


def simulation_bytes(cfg: Mapping[str, Any], n_frames: int, outputs: Sequence[str] = ("codes",)
                     ) -> int:
    """Estimated peak memory of simulating ``n_frames`` frames of ``cfg`` (bytes)."""
    f = cfg["fpa"]
    layout = ArrayLayout.from_dict({k: f[k] for k in ("active_rows", "active_cols", "boundary",
                                                      "blind") if k in f})
    pixels = layout.rows * layout.cols
    chunk = min(int(cfg["run"]["chunk_frames"]), n_frames)
    per_frame = _BYTES_CODES + 8 * sum(o in outputs for o in _PER_FRAME_OUTPUTS)
    # The result is concatenated from its chunks: twice its size at the peak.
    return pixels * (_BYTES_STATIC + _BYTES_CHUNK * chunk + 2 * n_frames * per_frame)


def check_simulation_memory(cfg: Mapping[str, Any], n_frames: int,
                            outputs: Sequence[str] = ("codes",), what: str = "") -> None:
    """:class:`~irnuc.common.memory.ResourceError` before any work when the frames would not fit."""
    from irnuc.common.memory import check_memory

    f = cfg["fpa"]
    check_memory(simulation_bytes(cfg, n_frames, outputs),
                 what or (f"simulate: {n_frames} frame(s) (temps x repeats) of fpa.active_rows x "
                          f"fpa.active_cols = {f['active_rows']} x {f['active_cols']} pixels"),
                 "use fewer or smaller frames")


def simulate(cfg: Mapping[str, Any], temps: Sequence[float] | np.ndarray, scene: str | Scene = "uniform",
             *, seed: int = 0, repeats: int = 1, outputs: Sequence[str] = ("codes",),
             scene_params: Mapping[str, Any] | None = None,
             progress: Callable[[int, int], None] | None = None,
             first_frame: int = 0) -> Frames:
    """Sensor frames for a batch of scene temperatures (a one-shot :class:`Pipeline`).

    Parameters
    ----------
    cfg : dict
        A validated configuration (:func:`model.load_preset` / :func:`model.load_config`).
    temps : sequence of float
        Scene base temperature of each frame, K (> 0).
    scene : str or Scene
        Scene kind (``uniform``, ``gradient``, ``disk``, ``map``) or a :class:`Scene`.
    seed : int
        Seed of every random draw (spread, defects, noise); same config and seed give the
        same bits.
    repeats : int
        Frames per temperature (temperature-major order), e.g. for calibration stacks.
    outputs : sequence of str
        Keys of :data:`OUTPUTS`; only the stages they need run.
    scene_params : dict, optional
        Parameters of the scene kind when ``scene`` is a name.
    progress : callable, optional
        Called as ``progress(done, total)`` after each chunk of frames.
    first_frame : int
        Index of the first frame in the noise streams (default 0): calls with the same
        configuration and seed but disjoint frame ranges image the same pixels with
        independent noise.
    """
    return Pipeline(cfg, seed).simulate(temps, scene, repeats=repeats, outputs=outputs,
                                        scene_params=scene_params, progress=progress,
                                        first_frame=first_frame)


def _diagnostics(pipe: Pipeline, values: Mapping[str, Any]) -> dict[str, Any]:
    status = values["status"]
    rs, cs = pipe.layout.active_slice
    # Failures are rare: count them only when there are any.
    counts = (np.bincount(status.reshape(-1), minlength=4) if np.count_nonzero(status)
              else np.zeros(4, np.int64))
    codes = values.get("codes")
    top = (1 << pipe.cfg["adc"]["bits"]) - 1
    # Invalid pixels hold 0 K (-T_s), no rise of the pixel's own: left out.
    lo, hi, total, count, n_low, n_high = _ks.frame_statistics(
        values["dT"], status, rs.start, rs.stop, cs.start, cs.stop,
        codes if codes is not None else np.zeros(0, np.uint16), top)
    diag: dict[str, Any] = {
        "temperature_rise_K": {"min": lo if count else math.nan,
                               "mean": total / count if count else math.nan,
                               "max": hi if count else math.nan},
        "solver_failures": {"no_convergence": int(counts[_kb.STATUS_NO_CONVERGENCE]),
                            "runaway": int(counts[_kb.STATUS_RUNAWAY]),
                            "invalid": int(counts[_kb.STATUS_INVALID])},
    }
    if codes is not None:
        diag["clipped_low"] = int(n_low)
        diag["clipped_high"] = int(n_high)
    failures = sum(diag["solver_failures"].values())
    if failures:
        warnings.warn(f"{failures} pixel solve(s) failed (thermal runaway or no convergence): "
                      f"{diag['solver_failures']}; those pixels read the high rail",
                      RuntimeWarning, stacklevel=3)
    return diag
