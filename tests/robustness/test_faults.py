"""Faults: kills at random points, concurrent runs on one ``--out``, children that die
with their parent (described in ``faults.py``)."""

from __future__ import annotations

import contextlib
import hashlib
import json
import os
import random
import shutil
import signal
import subprocess
import sys
import time
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import pytest

from robustness.faults import FAULTS

_MAIN = "import sys; from irnuc.cli import main; sys.exit(main(sys.argv[1:]))"


def _start(*args: str, cwd: Path) -> subprocess.Popen[str]:
    return subprocess.Popen([sys.executable, "-c", _MAIN, *args], cwd=cwd, text=True,
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE)


def _digest(folder: Path) -> dict[str, str]:
    """SHA-256 of every file under ``folder`` (hidden ones too), by relative path."""
    return {str(p.relative_to(folder)): hashlib.sha256(p.read_bytes()).hexdigest()
            for p in sorted(folder.rglob("*")) if p.is_file()}


@dataclass
class Faults:
    root: Path
    frames: dict[str, Path]       # "old", "new": two frame files
    results: dict[str, dict[str, str]]  # "old", "new": digest of each one's calibration
    seconds: float                # how long one calibration subprocess runs here


@pytest.fixture(scope="module")
def faults(tmp_path_factory: pytest.TempPathFactory) -> Faults:
    from irnuc.cli import main
    from irnuc.nuc_fixed.synthetic import synth_frames

    root = tmp_path_factory.mktemp("faults")
    frames, results = {}, {}
    for seed, key in ((1, "old"), (2, "new")):
        s = synth_frames(shape=(24, 32), temps=(300.0, 400.0), repeats=3, defect_fraction=0.03,
                         seed=seed)
        frames[key] = root / f"{key}.npz"
        np.savez(frames[key], codes=s.codes, temps=s.temps, adc_bits=np.int64(s.adc_bits))
        assert main(["calibrate", "-q", "--frames", str(frames[key]), "--out",
                     str(root / f"ref-{key}")]) == 0
        results[key] = _digest(root / f"ref-{key}")
    assert results["old"] != results["new"]
    # One undisturbed subprocess run: its result equals the in-process one, and its length
    # spreads the kill times over a whole run.
    t0 = time.monotonic()
    proc = _start("calibrate", "-q", "--frames", str(frames["new"]), "--out", str(root / "timed"),
                  cwd=root)
    assert proc.wait() == 0, proc.stderr.read() if proc.stderr else ""
    seconds = time.monotonic() - t0
    assert _digest(root / "timed") == results["new"]
    return Faults(root, frames, results, seconds)


def _which(folder: Path, f: Faults) -> str:
    """Which result the folder is, whole; fails on anything else (a mixed folder)."""
    from irnuc.nuc_fixed.memimage import read_memimage

    got = _digest(folder)
    matches = [k for k, want in f.results.items() if got == want]
    assert matches, f"{folder} is neither result, whole: {sorted(got)}"
    # And by the folder's own account: every file matches the manifest, and the summary
    # names the frames of that result.
    read_memimage(folder, "typical14", source="hex")
    summary = json.loads((folder / "summary.json").read_text())
    assert summary["frames_file"] == str(f.frames[matches[0]])
    return matches[0]


def _fresh(folder: Path, f: Faults, key: str) -> None:
    shutil.rmtree(folder, ignore_errors=True)
    shutil.copytree(f.root / f"ref-{key}", folder)


def _files(root: Path) -> set[tuple[str, int, int]]:
    """(path, inode, mtime) of every file under ``root``: what a run has written since."""
    out = set()
    for dirpath, _, names in os.walk(root):
        for name in names:
            with contextlib.suppress(OSError):
                st = os.stat(os.path.join(dirpath, name))
                out.add((os.path.join(dirpath, name), st.st_ino, st.st_mtime_ns))
    return out


@pytest.mark.parametrize("trial", range(6))
def test_fault_kill_calibrate(trial: int, faults: Faults, tmp_path: Path) -> None:
    rng = random.Random(1000 + trial)
    out = tmp_path / "cal"
    _fresh(out, faults, "old")
    before = _files(tmp_path)
    proc = _start("calibrate", "-q", "--frames", str(faults.frames["new"]), "--out", str(out),
                  cwd=tmp_path)
    if trial % 2 == 0:  # at a random time of the run
        deadline = time.monotonic() + rng.uniform(0.0, 1.2 * faults.seconds)
        while proc.poll() is None and time.monotonic() < deadline:
            time.sleep(0.005)
    else:  # while the result is being written: once k files were written, wherever
        k = rng.randint(1, 8)
        while proc.poll() is None and len(_files(tmp_path) - before) < k:
            time.sleep(0.0002)
    if proc.poll() is None:
        os.kill(proc.pid, signal.SIGKILL)
    proc.wait()
    assert _which(out, faults) in ("old", "new")
    if proc.returncode == 0:
        assert _which(out, faults) == "new"


@pytest.mark.parametrize("trial", range(3))
def test_fault_concurrent_calibrate(trial: int, faults: Faults, tmp_path: Path) -> None:
    rng = random.Random(2000 + trial)
    out = tmp_path / "cal"
    if trial == 2:
        _fresh(out, faults, "old")  # over an earlier result as well as into a new folder
    first, second = ("old", "new") if trial % 2 == 0 else ("new", "old")
    procs = {first: _start("calibrate", "-q", "--frames", str(faults.frames[first]), "--out",
                           str(out), cwd=tmp_path)}
    time.sleep(rng.uniform(0.0, 0.5 * faults.seconds))
    procs[second] = _start("calibrate", "-q", "--frames", str(faults.frames[second]), "--out",
                           str(out), cwd=tmp_path)
    codes = {k: p.wait() for k, p in procs.items()}
    errs = {k: p.stderr.read() if p.stderr else "" for k, p in procs.items()}
    for k, code in codes.items():
        assert code in (0, 2), errs[k]
        if code == 2:
            assert "another irnuc run is writing it" in errs[k], errs[k]
            assert len(errs[k].strip().splitlines()) == 1
    winners = [k for k, code in codes.items() if code == 0]
    assert winners
    got = _which(out, faults)
    assert got in winners
    assert not list(tmp_path.glob(".cal.tmp-*"))


def test_fault_stale_tmp_removed(faults: Faults, tmp_path: Path) -> None:
    from irnuc.cli import main

    out = tmp_path / "cal"
    _fresh(out, faults, "old")
    (tmp_path / ".cal.tmp-killed").mkdir()
    (tmp_path / ".cal.tmp-killed" / "coeffs.bin").write_bytes(b"half a file")
    (tmp_path / ".cal.tmp-link").symlink_to(tmp_path / "nowhere")
    (tmp_path / ".cal.lock").write_text("")
    assert main(["calibrate", "-q", "--frames", str(faults.frames["new"]), "--out", str(out)]) == 0
    assert _which(out, faults) == "new"
    assert not list(tmp_path.glob(".cal.tmp-*"))


_CHILD = """
import os, subprocess, sys
from irnuc.common.process import die_with_parent
die_with_parent()
g = subprocess.Popen(["sleep", "300"])
open(sys.argv[1], "w").write(f"{os.getpid()} {g.pid}")
g.wait()
"""
_PARENT = """
import sys
from irnuc.common.process import run_child
run_child([sys.executable, "-c", sys.argv[1], sys.argv[2]])
"""


def _alive(pid: int) -> bool:
    try:
        state = Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()[0]
    except (OSError, IndexError):
        return False
    return state not in ("Z", "X")  # a zombie is dead, only not yet reaped


_TOOL_PARENT = """
import sys
from irnuc.common.process import run_child
# A tool that is not irnuc's own and starts a child of its own (as make starts a compiler).
run_child(["sh", "-c", "sleep 300 & echo $$ $! > " + sys.argv[1] + "; wait"])
"""


@pytest.mark.skipif(not sys.platform.startswith("linux"), reason="PR_SET_PDEATHSIG is Linux's")
@pytest.mark.parametrize("kind", ["irnuc_child", "foreign_tool"])
def test_fault_children_die_with_parent(tmp_path: Path, kind: str) -> None:
    """SIGKILL of a process that started a child group: the child and the child's own
    child are gone, whether the child is irnuc's (it arms die_with_parent itself) or a
    foreign tool (run under the reaper)."""
    pids = tmp_path / "pids"
    argv = ([sys.executable, "-c", _PARENT, _CHILD, str(pids)] if kind == "irnuc_child"
            else [sys.executable, "-c", _TOOL_PARENT, str(pids)])
    parent = subprocess.Popen(argv)
    try:
        while not (pids.is_file() and pids.read_text().strip()):
            assert parent.poll() is None, "the parent ended early"
            time.sleep(0.02)
        child, grandchild = map(int, pids.read_text().split())
        assert _alive(child) and _alive(grandchild)
        parent.kill()
        parent.wait()
        # Wait (bounded) for the kernel's signal and the group kill to land.
        for _ in range(500):
            if not (_alive(child) or _alive(grandchild)):
                break
            time.sleep(0.02)
        assert not _alive(child), "the child outlived its parent"
        assert not _alive(grandchild), "the grandchild (e.g. a simulator) outlived irnuc"
    finally:
        if parent.poll() is None:
            parent.kill()
        if pids.is_file() and pids.read_text().strip():
            for pid in map(int, pids.read_text().split()):
                if _alive(pid):
                    with contextlib.suppress(ProcessLookupError):
                        os.kill(pid, signal.SIGKILL)


_SINGLE_PARENT = """
import sys
from irnuc.common.process import run_child
# A single-process tool (as the bulk harness): no reaper in between.
run_child(["sh", "-c", "echo $$ > " + sys.argv[1] + "; exec sleep 300"], single_process=True)
"""


@pytest.mark.skipif(not sys.platform.startswith("linux"), reason="PR_SET_PDEATHSIG is Linux's")
def test_fault_single_process_child_dies_with_parent(tmp_path: Path) -> None:
    """``run_child(single_process=True)`` starts the tool without the reaper: the tool is
    the direct child and still dies when its parent is killed (PR_SET_PDEATHSIG)."""
    pids = tmp_path / "pids"
    parent = subprocess.Popen([sys.executable, "-c", _SINGLE_PARENT, str(pids)])
    child = None
    try:
        while not (pids.is_file() and pids.read_text().strip()):
            assert parent.poll() is None, "the parent ended early"
            time.sleep(0.02)
        child = int(pids.read_text())
        ppid = int(Path(f"/proc/{child}/stat").read_text().rsplit(")", 1)[1].split()[1])
        assert ppid == parent.pid, "the tool must be the parent's direct child (no reaper)"
        parent.kill()
        parent.wait()
        for _ in range(500):
            if not _alive(child):
                break
            time.sleep(0.02)
        assert not _alive(child), "the tool outlived its parent"
    finally:
        if parent.poll() is None:
            parent.kill()
        if child is not None and _alive(child):
            with contextlib.suppress(ProcessLookupError):
                os.kill(child, signal.SIGKILL)


def test_every_fault_is_described() -> None:
    tests = {n.removeprefix("test_fault_") for n in globals() if n.startswith("test_fault_")}
    assert tests == set(FAULTS)
