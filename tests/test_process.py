"""``irnuc.common.process``: a timed-out child group is gone, grandchildren included, by
the time :class:`ChildTimeout` reaches the caller."""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

from irnuc.common.process import ChildTimeout, _group_alive, run_child

pytestmark = pytest.mark.skipif(not sys.platform.startswith("linux"), reason="reads /proc")


def _running(pid: int) -> bool:
    try:
        state = Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()[0]
    except (OSError, IndexError):
        return False
    return state not in ("Z", "X")


def test_group_alive_counts_running_members_not_zombies() -> None:
    proc = subprocess.Popen(["sleep", "300"], start_new_session=True)
    try:
        assert _group_alive(proc.pid)
        os.kill(proc.pid, signal.SIGKILL)
        # Not reaped yet: a zombie until wait(); it no longer counts as running.
        for _ in range(500):
            if not _running(proc.pid):
                break
            time.sleep(0.01)
        assert Path(f"/proc/{proc.pid}").exists(), "the zombie should still be listed"
        assert not _group_alive(proc.pid)
    finally:
        proc.kill()
        proc.wait()
    assert not _group_alive(proc.pid)
    assert not _group_alive(2**22 + 7)  # no such group


def test_timeout_returns_after_the_grandchild_is_gone(tmp_path: Path) -> None:
    pid_file = tmp_path / "pid"
    # A foreign tool starting a child of its own (as make starts a compiler, or the
    # cocotb runner a simulator); the limit ends it while both run.
    script = f"sleep 300 & echo $! > {pid_file}; wait"
    with pytest.raises(ChildTimeout, match="was stopped"):
        run_child(["sh", "-c", script], timeout=1.0)
    grandchild = int(pid_file.read_text())
    # No polling here: run_child must not return while the grandchild still runs.
    assert not _running(grandchild), "the grandchild outlived the timeout"
