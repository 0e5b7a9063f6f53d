"""CPU seconds of the report's process tree (irnuc.common.cputime): the phase CPU in
summary.json must count the executor's workers, which are grandchildren (forkserver)."""

from __future__ import annotations

import subprocess
import sys
import time

import pytest

from irnuc.common.cputime import tree_cpu_seconds

BURN = "import time\nt = time.process_time()\nwhile time.process_time() - t < {s}:\n    pass\n"


@pytest.mark.skipif(not sys.platform.startswith("linux"), reason="reads /proc")
def test_a_live_grandchild_and_a_reaped_child_are_counted() -> None:
    before = tree_cpu_seconds()
    # a child that starts a grandchild burning 0.6 s of CPU, then waits for a signal
    code = ("import subprocess, sys\n"
            f"p = subprocess.Popen([sys.executable, '-c', {BURN.format(s=0.6)!r} + "
            "'import time\\ntime.sleep(30)\\n'])\n"
            "sys.stdin.readline()\np.kill()\np.wait()\n")
    child = subprocess.Popen([sys.executable, "-c", code], stdin=subprocess.PIPE, text=True)
    try:
        deadline = time.monotonic() + 30
        while tree_cpu_seconds() - before < 0.6 and time.monotonic() < deadline:
            time.sleep(0.05)
        alive = tree_cpu_seconds() - before  # the grandchild still running (sleeping)
        assert child.poll() is None and alive >= 0.6
    finally:
        child.communicate("\n")
    after = tree_cpu_seconds() - before  # reaped: in this process's children's time
    assert after >= 0.6
    # nothing counted twice: the burn plus two interpreters' start-up, not twice the burn
    assert after < 0.6 + 2 * 1.0 + 0.6


def test_another_process_tree_is_counted_with_its_live_grandchild() -> None:
    """tree_cpu_seconds(pid): the CPU of another process's tree, a live grandchild's spin
    included (bench_report samples the report's tree at each progress line); a process
    that is gone counts 0."""
    import subprocess
    import sys

    from irnuc.common.cputime import tree_cpu_seconds

    grand = ("import sys, time\n"
             "while time.process_time() < 0.5: pass\n"
             "print('spun', flush=True)\n"
             "time.sleep(30)\n")
    child = (f"import subprocess, sys\n"
             f"p = subprocess.Popen([sys.executable, '-c', {grand!r}], stdout=sys.stdout)\n"
             f"p.wait()\n")
    p = subprocess.Popen([sys.executable, "-c", child], stdout=subprocess.PIPE, text=True)
    try:
        assert p.stdout.readline().strip() == "spun"
        assert tree_cpu_seconds(p.pid) >= 0.5
    finally:
        import os
        import signal

        for q in subprocess.run(["pgrep", "-P", str(p.pid)], capture_output=True,
                                text=True).stdout.split():
            os.kill(int(q), signal.SIGKILL)
        p.wait()
    assert tree_cpu_seconds(p.pid) == 0.0
