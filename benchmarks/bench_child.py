"""Fixed cost of the child processes around every Verilator build and simulation.

Every cocotb build and simulation runs in a child Python process (``cosim._child``) that
imports ``irnuc.cosim._cocotb_adapter``; a build also runs two runtime-object steps
(``cosim._objcache`` seed and store). The suite starts about fifty builds and more than a
hundred simulations, so these imports are paid hundreds of times (docs/testing.md).

Measured (wall time of a fresh interpreter, best of ``--repeat``), in the same run:

* ``child``: what the child imports now (the adapter: ``irnuc.cosim`` gives its names on
  first use), against the baseline of what it imported before (the adapter with the whole
  ``irnuc.cosim`` package: builds, the golden model, numba);
* ``objcache``: the runtime-object step as it runs now (``python -P _objcache.py``, usage
  only), against the baseline of ``python -m irnuc.cosim._objcache`` with the package's
  former imports.

The last line printed is one JSON object.
"""

from __future__ import annotations

import argparse
import json
import subprocess
import sys
import time

from irnuc.cosim import _objcache

#: What the child imported before this change (``irnuc.cosim``'s ``__init__`` imported
#: ``builds``, ``bulk``, ``scoreboard``, ``sources``, ``verilator``).
_BEFORE = ("import irnuc.cosim.builds, irnuc.cosim.bulk, irnuc.cosim.scoreboard, "
           "irnuc.cosim._cocotb_adapter")


def _best(cmd: list[str], repeat: int) -> float:
    """Best wall time of ``repeat`` runs of ``cmd`` (seconds); a failing run is an error."""
    times = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        proc = subprocess.run(cmd, capture_output=True, text=True, check=False)
        times.append(time.perf_counter() - t0)
        if proc.returncode not in (0, 2):  # 2: _objcache's usage line, wanted here
            raise SystemExit(f"bench_child: {' '.join(cmd)} failed:\n{proc.stderr}")
    return min(times)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeat", type=int, default=5, help="runs per measurement (best of)")
    args = ap.parse_args()
    if args.repeat < 1:
        ap.error("--repeat: at least 1")
    py = [sys.executable, "-P"]
    child = _best([*py, "-c", "import irnuc.cosim._cocotb_adapter"], args.repeat)
    child_before = _best([*py, "-c", _BEFORE], args.repeat)
    step = _best([*py, _objcache.__file__], args.repeat)
    step_before = _best([*py, "-c", _BEFORE.replace("_cocotb_adapter", "_objcache")],
                        args.repeat)
    result = {
        "benchmark": "child processes of a build / simulation",
        "repeat": args.repeat,
        "child_import_s": round(child, 3),
        "baseline_child_import_s": round(child_before, 3),
        "child_speedup": round(child_before / child, 2),
        "objcache_step_s": round(step, 3),
        "baseline_objcache_step_s": round(step_before, 3),
        "objcache_speedup": round(step_before / step, 2),
        # One build: a child and two steps; one simulation: a child.
        "saved_per_build_s": round((child_before - child) + 2 * (step_before - step), 3),
        "saved_per_simulation_s": round(child_before - child, 3),
    }
    print(f"child {child:.3f} s (before {child_before:.3f} s); runtime-object step "
          f"{step:.3f} s (before {step_before:.3f} s)")
    print(json.dumps(result))


if __name__ == "__main__":
    main()
