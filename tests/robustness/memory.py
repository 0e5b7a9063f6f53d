"""Memory estimates checked before the work, against peaks measured once."""

from __future__ import annotations

from collections.abc import Callable

import numpy as np


def _sim_estimate(rows: int, cols: int, n: int, outputs: tuple[str, ...]) -> float:
    from irnuc import model
    from irnuc.model.pipeline import simulation_bytes

    cfg = model.load_preset("default", {"fpa.active_rows": rows, "fpa.active_cols": cols,
                                        "noise.enabled": True})
    return simulation_bytes(cfg, n, outputs)


def _frames_estimate(n: int, h: int, w: int, work: dict[str, float]) -> float:
    from irnuc.cli._files import arrays_bytes, frames_work_bytes

    headers = {"codes": ((n, h, w), np.dtype(np.uint16)), "temps": ((n,), np.dtype(np.float64)),
               "adc_bits": ((), np.dtype(np.int64))}
    return arrays_bytes(headers) + frames_work_bytes((n, h, w), work["per_code"], work["per_pixel"])


def _calibrate_estimate(n: int, h: int, w: int) -> float:
    from irnuc.nuc_fixed.calibrate import CALIBRATE_WORK_BYTES

    return _frames_estimate(n, h, w, CALIBRATE_WORK_BYTES)


def _correct_estimate(n: int, h: int, w: int) -> float:
    from irnuc.nuc_fixed.calibrate import CORRECT_WORK_BYTES

    return _frames_estimate(n, h, w, CORRECT_WORK_BYTES)


def _sweep_estimate(rows: int, cols: int, repeats: int, workers: int) -> float:
    from irnuc import model
    from irnuc.reports.studies.sweep import sweep_bytes

    cfg = model.load_preset("default", {"fpa.active_rows": rows, "fpa.active_cols": cols})
    return sweep_bytes(cfg, 2 * repeats, 1, 1, workers)


#: Peak memory of one request, measured once on the development machine as the growth of
#: ru_maxrss above a warm interpreter (MiB), and the estimate irnuc checks before it.
MEASURED: list[tuple[str, float, Callable[[], float]]] = [
    ("simulate, uniform scene, codes: 512 x 640, 8 frames", 237,
     lambda: _sim_estimate(512, 640, 8, ("codes",))),
    ("simulate, uniform scene, codes: 512 x 640, 64 frames", 655,
     lambda: _sim_estimate(512, 640, 64, ("codes",))),
    ("simulate, gradient scene, codes: 512 x 640, 64 frames", 748,
     lambda: _sim_estimate(512, 640, 64, ("codes",))),
    ("simulate, gradient, codes + voltage + params + temperature rise: 512 x 640, 32 frames",
     632, lambda: _sim_estimate(512, 640, 32, ("codes", "voltage", "params", "temperature_rise"))),
    ("simulate, uniform scene, codes: 256 x 320, 400 frames", 813,
     lambda: _sim_estimate(256, 320, 400, ("codes",))),
    ("irnuc calibrate: 512 x 640, 4 frames", 321, lambda: _calibrate_estimate(4, 512, 640)),
    ("irnuc calibrate: 512 x 640, 32 frames", 355, lambda: _calibrate_estimate(32, 512, 640)),
    ("irnuc calibrate: 256 x 320, 200 frames", 192, lambda: _calibrate_estimate(200, 256, 320)),
    ("irnuc correct: 512 x 640, 4 frames", 32, lambda: _correct_estimate(4, 512, 640)),
    ("irnuc correct: 512 x 640, 64 frames", 127, lambda: _correct_estimate(64, 512, 640)),
    ("irnuc sweep, 2 points in-process: 512 x 640, 4 repeats", 371,
     lambda: _sweep_estimate(512, 640, 4, 0)),
    # The whole process tree (workers and forkserver), sampled every 50 ms: each worker is
    # an interpreter of its own, which the estimate once left out (--workers 256 reached
    # the machine's memory).
    ("irnuc sweep, 55 points on 2 worker processes: 1024 x 1280, 4 repeats", 1983,
     lambda: _sweep_estimate(1024, 1280, 4, 2)),
    ("irnuc sweep, 55 points on 8 worker processes: 24 x 32, 4 repeats", 1458,
     lambda: _sweep_estimate(24, 32, 4, 8)),
]
