"""Run time of the README's main job, ``irnuc report`` (default configuration), phase by phase.

Runs, each in a subprocess with its own output folder:

1. ``cold``: an empty irnuc cache (``IRNUC_CACHE_DIR`` a fresh folder: Verilator builds,
   syntheses, numba kernels and the work-precision study all made anew), with ``--hog``
   CPU-bound processes running beside it (default 1: a busy loop, as another engineer's
   job would be), to show the report passes on its first run on a loaded machine;
2. ``warm``: the same cache again, no hog (the goal: <= 90 s on 2 cores, every phase with
   the Temperature section's);
3. ``warm_hog``: the same cache, with the hog;
4. ``quick_first`` and ``quick``: ``--quick`` on the same cache, no hog, twice: the first
   makes what only the quick configuration needs (its syntheses, builds and study), the
   second is the warm quick run (the goal: <= 30 s);
4b. ``quick_cold``: ``--quick`` on a second empty cache of its own, no hog (issue 37: the
   goal is <= 3 min cold on a quiet 2-core machine);
5. ``baseline`` (measured in the same run): the same configuration with the same cache and
   ``--no-cosim``: the report's compute-only part (frames, calibration, sweep, cached
   syntheses, paper, temperature, cached precision), to normalize the co-simulation's share.

Each run's exit status, wall time, CPU time (``cpu_s``: user + system of the report and
every process it waited for), the phases of its ``summary.json`` (wall ``phases_s`` and CPU
``phases_cpu_s``, the report's own count over its live process tree) and the parts of the
``temperature`` phase (its sweep, anchors, synthesis, co-simulation, figures) are reported.
On a shared machine the wall times measure the neighbours as much as the report; the CPU
times do not: ``cpu_bound_2cores_s`` (the phases' CPU / 2) is what the run needs at least
on a quiet 2-core machine, and what it takes there when every phase keeps both cores busy;
the last line printed is one JSON object with ``warm_goal_ratio`` (warm total / 90 s),
``quick_goal_ratio`` (quick total / 30 s), ``cold_goal_ratio`` (cold total / 10 min: the
goal holds for a quiet machine, ``--hog 0``), ``quick_cold_goal_ratio`` (quick_cold total /
3 min) and ``warm_vs_baseline`` (warm total / baseline total).

``--timeout S`` stops a run after S seconds with everything it started (its own session)
and records ``timed_out_s``; every run records ``timeline_s``, the report's progress lines
(phases and background jobs started and finished), each as [seconds since its start, CPU
seconds of its process tree so far, line], so a stopped run still shows where the time and
the CPU went.

``--runs`` picks the runs (default all: ``cold,warm,warm_hog,quick,baseline``);
``--shared-cache`` uses the user's irnuc cache instead of a fresh one (no cold run then:
for timing the warm runs on a machine that already built everything).

Usage: ``python benchmarks/bench_report.py [--config default] [--hog 1] [--runs ...]
[--shared-cache] [--keep] [--timeout S]``
"""

from __future__ import annotations

import argparse
import json
import os
import resource
import shutil
import signal
import subprocess
import sys
import tempfile
import threading
import time
from pathlib import Path

from irnuc.common.cputime import tree_cpu_seconds

GOAL_WARM_S = 90.0
GOAL_QUICK_S = 30.0
GOAL_COLD_S = 600.0
GOAL_QUICK_COLD_S = 180.0
RUNS = ("cold", "warm", "warm_hog", "quick_first", "quick", "quick_cold", "baseline")
HOG = "import time\nt = time.time()\nwhile time.time() - t < 3600:\n    sum(i * i for i in range(10000))\n"


def _run(name: str, args: list[str], env: dict[str, str], out: Path, hog: int,
         timeout: float | None = None) -> dict:
    hogs = [subprocess.Popen([sys.executable, "-c", HOG]) for _ in range(hog)]
    try:
        t0 = time.perf_counter()
        r0 = resource.getrusage(resource.RUSAGE_CHILDREN)
        # not -q: the phases' start lines (stderr) say where a run stopped past --timeout
        proc = subprocess.Popen([str(Path(sys.executable).with_name("irnuc")), "report",
                                 "--out", str(out), *args], env=env, stdout=subprocess.PIPE,
                                stderr=subprocess.PIPE, text=True, start_new_session=True)
        # the phases' start lines, each with the seconds since the start (a timeline,
        # also of a run stopped by --timeout)
        marks: list[list] = []
        err_lines: list[str] = []

        def read_err() -> None:
            for line in proc.stderr:
                err_lines.append(line)
                if line.startswith("irnuc report: "):
                    # [wall s, CPU s of the report's process tree so far, the line]
                    marks.append([round(time.perf_counter() - t0, 1),
                                  round(tree_cpu_seconds(proc.pid), 1),
                                  line.split(": ", 1)[1].strip()])

        out_parts: list[str] = []
        readers = [threading.Thread(target=read_err, daemon=True),
                   threading.Thread(target=lambda: out_parts.append(proc.stdout.read()),
                                    daemon=True)]
        for th in readers:
            th.start()
        timed_out = False
        try:
            proc.wait(timeout=timeout)
        except subprocess.TimeoutExpired:
            # the report and everything it started (its own session): none left running
            timed_out = True
            marks.append([round(time.perf_counter() - t0, 1),
                          round(tree_cpu_seconds(proc.pid), 1), "stopped (--timeout)"])
            os.killpg(proc.pid, signal.SIGKILL)
            proc.wait()
        for th in readers:
            th.join(10)
        stdout, stderr = "".join(out_parts), "".join(err_lines)
        wall = time.perf_counter() - t0
        # the report's process and every process it waited for (not the hogs: reaped after)
        r1 = resource.getrusage(resource.RUSAGE_CHILDREN)
    finally:
        for h in hogs:
            h.kill()
            h.wait()
    rec: dict = {"run": name, "returncode": proc.returncode, "wall_s": round(wall, 1), "hogs": hog}
    rec["timeline_s"] = marks
    if timed_out:
        rec["timed_out_s"] = timeout
    rec["cpu_s"] = round(r1.ru_utime + r1.ru_stime - r0.ru_utime - r0.ru_stime, 1)
    summary = out / "summary.json"
    if summary.is_file():
        s = json.loads(summary.read_text())
        rec["status"] = s["status"]
        rec["phases_s"] = {k: round(v, 1) for k, v in s["phases"].items()}
        # CPU seconds per phase (the report's own count, the live process tree included):
        # with the phase's parallelism (2 cores) a bound on its wall time on a quiet machine
        rec["phases_cpu_s"] = {k: round(v, 1) for k, v in (s.get("phases_cpu") or {}).items()}
        rec["cpu_bound_2cores_s"] = round(sum(rec["phases_cpu_s"].values()) / 2, 1)
        rec["closing_line"] = stdout.strip().splitlines()[-1] if stdout.strip() else ""
        c = s["sections"].get("cosim") or {}
        rec["cosim"] = {k: c.get(k) for k in ("tests", "passed", "failed", "timeout", "pixels",
                                               "mismatches", "build_seconds")}
        t = s["sections"].get("temperature") or {}
        r = t.get("recommended") or {}
        rec["temperature_parts_s"] = t.get("seconds")
        rec["temperature_cached_study"] = t.get("cached")
        # work started beside the phases: when (s since the start) and how long waited for
        rec["temperature_background"] = t.get("background")
        rec["temperature_recommended"] = {k: r.get(k) for k in (
            "key", "worst_fpn_mK", "meets_tolerance", "memory_bits", "bandwidth_MBps")} | {
            "cosim_pixels": (r.get("cosim") or {}).get("pixels_compared"),
            "cosim_mismatches": (r.get("cosim") or {}).get("mismatches")} if r else None
    else:
        rec["stderr"] = stderr[-2000:]
    print(json.dumps(rec), flush=True)
    return rec


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--config", default="default")
    ap.add_argument("--hog", type=int, default=1, help="CPU-bound processes beside the cold run")
    ap.add_argument("--keep", action="store_true", help="keep the cache and output folders")
    ap.add_argument("--runs", default=",".join(RUNS),
                    help=f"comma-separated runs among {', '.join(RUNS)}")
    ap.add_argument("--timeout", type=float, default=None,
                    help="seconds after which a run is stopped (with everything it started) "
                         "and recorded as timed out")
    ap.add_argument("--shared-cache", action="store_true",
                    help="use the user's irnuc cache (no fresh one: the cold run is skipped)")
    args = ap.parse_args()
    runs = [r.strip() for r in args.runs.split(",") if r.strip()]
    unknown = sorted(set(runs) - set(RUNS))
    if unknown:
        ap.error(f"--runs: unknown {', '.join(unknown)} (known: {', '.join(RUNS)})")
    if args.shared_cache:
        runs = [r for r in runs if r not in ("cold", "quick_cold")]
    root = Path(tempfile.mkdtemp(prefix="bench_report_"))
    env = dict(os.environ)
    if not args.shared_cache:
        env["IRNUC_CACHE_DIR"] = str(root / "cache")
    cfg = ["--config", args.config]
    plan = {"cold": (cfg, args.hog), "warm": (cfg, 0), "warm_hog": (cfg, args.hog),
            "quick_first": ([*cfg, "--quick"], 0), "quick": ([*cfg, "--quick"], 0),
            "quick_cold": ([*cfg, "--quick"], 0), "baseline": ([*cfg, "--no-cosim"], 0)}
    # quick_cold: an empty cache of its own (the others share theirs)
    env_cold_quick = {**env, "IRNUC_CACHE_DIR": str(root / "cache_quick_cold")}
    got: dict[str, dict] = {}
    try:
        for name in RUNS:
            if name in runs:
                a, hog = plan[name]
                got[name] = _run(name, a, env_cold_quick if name == "quick_cold" else env,
                                 root / name, hog, args.timeout)
    finally:
        if not args.keep:
            shutil.rmtree(root, ignore_errors=True)

    def field(run: str, key: str):
        return got[run].get(key) if run in got else None

    warm, quick, base = field("warm", "wall_s"), field("quick", "wall_s"), field("baseline", "wall_s")
    cold, quick_cold = field("cold", "wall_s"), field("quick_cold", "wall_s")
    result = {
        "config": args.config, "cpu_count": os.cpu_count(), "hogs": args.hog,
        "cache": "shared" if args.shared_cache else "fresh", "runs": runs,
        "cold_s": field("cold", "wall_s"), "cold_rc": field("cold", "returncode"),
        "cold_phases_s": field("cold", "phases_s"),
        "warm_s": warm, "warm_rc": field("warm", "returncode"), "warm_phases_s": field("warm", "phases_s"),
        "warm_temperature_parts_s": field("warm", "temperature_parts_s"),
        "warm_hog_s": field("warm_hog", "wall_s"), "warm_hog_rc": field("warm_hog", "returncode"),
        "warm_hog_phases_s": field("warm_hog", "phases_s"),
        "quick_first_s": field("quick_first", "wall_s"),
        "quick_s": quick, "quick_rc": field("quick", "returncode"),
        "quick_cold_s": quick_cold, "quick_cold_rc": field("quick_cold", "returncode"),
        "quick_cold_phases_s": field("quick_cold", "phases_s"),
        "quick_cold_temperature_parts_s": field("quick_cold", "temperature_parts_s"),
        "quick_phases_s": field("quick", "phases_s"),
        "baseline_no_cosim_s": base, "baseline_phases_s": field("baseline", "phases_s"),
        "temperature_recommended": field("warm", "temperature_recommended"),
        "warm_goal_s": GOAL_WARM_S, "quick_goal_s": GOAL_QUICK_S,
        "warm_goal_ratio": round(warm / GOAL_WARM_S, 3) if warm else None,
        "quick_goal_ratio": round(quick / GOAL_QUICK_S, 3) if quick else None,
        "cold_goal_s": GOAL_COLD_S, "quick_cold_goal_s": GOAL_QUICK_COLD_S,
        "cold_goal_ratio": round(cold / GOAL_COLD_S, 3) if cold else None,
        "quick_cold_goal_ratio": round(quick_cold / GOAL_QUICK_COLD_S, 3) if quick_cold else None,
        "warm_vs_baseline": round(warm / base, 3) if warm and base else None,
    }
    # CPU seconds (process tree) and the quiet 2-core bound of each run that ran
    for name in got:
        result[f"{name}_cpu_s"] = field(name, "cpu_s")
        result[f"{name}_phases_cpu_s"] = field(name, "phases_cpu_s")
        result[f"{name}_cpu_bound_2cores_s"] = field(name, "cpu_bound_2cores_s")
        if field(name, "timed_out_s"):
            result[f"{name}_timed_out_s"] = field(name, "timed_out_s")
    print(json.dumps(result))


if __name__ == "__main__":
    main()
