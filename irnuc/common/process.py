"""Child processes that die with their parent and can be stopped as a whole.

Every child runs in its own session (process group), so a timeout kills it and whatever
it started (a simulator, a compiler). On Linux it also gets ``PR_SET_PDEATHSIG``: if the
irnuc process that started it is killed (even with SIGKILL), the child receives SIGTERM,
and :func:`die_with_parent` (called by irnuc's own child entry points) turns that into a
kill of the child's whole group. A command that is not irnuc's own (Verilator, make, a
harness, nextpnr) runs under a small reaper (``irnuc.common._reaper``) that does the same
for it, so the compilers ``make`` starts die too.
"""

from __future__ import annotations

import ctypes
import ctypes.util
import os
import signal
import subprocess
import sys
import threading
import time
from collections.abc import Mapping, Sequence
from pathlib import Path

from irnuc.common.errors import ToolError

_PR_SET_PDEATHSIG = 1


def _set_pdeathsig() -> None:  # runs in the child between fork and exec
    name = ctypes.util.find_library("c")
    if name:
        ctypes.CDLL(name, use_errno=True).prctl(_PR_SET_PDEATHSIG, signal.SIGTERM)


class ChildTimeout(ToolError):
    """A child process group ran past its time limit and was killed."""


def python_module(module: str, *args: str | Path) -> list[str]:
    """The command running ``python -m module args`` in this interpreter, without the
    current folder on ``sys.path`` (``-P``: a file there, an ``inspect.py`` say, must not
    shadow a module)."""
    return [sys.executable, "-P", "-m", module, *map(str, args)]


def python_script(path: str | Path, *args: str | Path) -> list[str]:
    """The command running the script ``path`` in this interpreter, its folder not on
    ``sys.path`` (``-P``): cheaper than :func:`python_module` for a module that needs
    none of its package's ``__init__`` imports."""
    return [sys.executable, "-P", str(path), *map(str, args)]


def _is_irnuc_child(cmd: Sequence[str]) -> bool:
    """An irnuc entry point that arms :func:`die_with_parent` itself."""
    return (len(cmd) >= 4 and cmd[:3] == [sys.executable, "-P", "-m"]
            and str(cmd[3]).startswith("irnuc."))


def run_child(cmd: Sequence[str], *, timeout: float | None = None,
              env: Mapping[str, str] | None = None, cwd: str | Path | None = None,
              log: str | Path | None = None, capture: bool = False,
              single_process: bool = False) -> subprocess.CompletedProcess:
    """Run ``cmd`` in its own process group; kill the group on timeout or interrupt.

    Output goes to ``log`` (stdout and stderr together) or is captured. Raises
    :class:`ChildTimeout` after killing the group when ``timeout`` seconds pass. The
    group also dies when this process dies (see the module docstring).
    ``single_process=True`` says ``cmd`` starts no processes of its own (e.g. the bulk
    harness): it then runs without the reaper, whose Python start-up costs tens of ms,
    and ``PR_SET_PDEATHSIG`` still stops it with this process.
    """
    args = [str(c) for c in cmd]
    if not single_process and not _is_irnuc_child(args):
        args = python_module("irnuc.common._reaper", *args)
    out = open(log, "w") if log is not None else (subprocess.PIPE if capture else None)
    try:
        proc = subprocess.Popen(args, stdout=out,
                                stderr=subprocess.STDOUT if log is not None else
                                (subprocess.PIPE if capture else None),
                                env=dict(env) if env is not None else None, cwd=cwd,
                                start_new_session=True, preexec_fn=_set_pdeathsig, text=True)
        try:
            stdout, stderr = proc.communicate(timeout=timeout)
        except subprocess.TimeoutExpired:
            _kill_group(proc)
            raise ChildTimeout(f"{Path(cmd[0]).name} ran longer than {timeout:g} s and was "
                               "stopped") from None
        except BaseException:
            _kill_group(proc)
            raise
    finally:
        if log is not None:
            out.close()
    return subprocess.CompletedProcess(proc.args, proc.returncode, stdout, stderr)


def _kill_group(proc: subprocess.Popen, settle: float = 10.0) -> None:
    """SIGKILL the child's group and return once none of its processes is left running.

    ``proc.wait()`` only reaps the direct child; a grandchild (the simulator) sent the same
    signal may still be tearing down its memory on a loaded machine, so a caller that looks
    right after would see it alive. Wait (at most ``settle`` seconds) until every member of
    the group is gone or a zombie.
    """
    try:
        os.killpg(proc.pid, signal.SIGKILL)
    except ProcessLookupError:
        pass
    proc.wait()
    deadline = time.monotonic() + settle
    while _group_alive(proc.pid) and time.monotonic() < deadline:
        time.sleep(0.02)


def _group_alive(pgid: int) -> bool:
    """Whether a process of group ``pgid`` is still running (not a zombie); Linux /proc,
    else what ``killpg(pgid, 0)`` says."""
    if not os.path.isdir("/proc/self"):
        try:
            os.killpg(pgid, 0)
        except (ProcessLookupError, PermissionError):
            return False
        return True
    for d in os.listdir("/proc"):
        if not d.isdigit():
            continue
        try:
            with open(f"/proc/{d}/stat", "rb") as f:
                stat = f.read()
        except OSError:
            continue
        # Fields after the command (which may hold spaces or parentheses): state ppid pgrp.
        fields = stat[stat.rfind(b")") + 2:].split()
        if len(fields) > 2 and int(fields[2]) == pgid and fields[0] != b"Z":
            return True
    return False


def die_with_parent() -> None:
    """In an irnuc child process: when the parent dies, kill this whole process group.

    The parent set ``PR_SET_PDEATHSIG`` to SIGTERM; the handler kills the group (this
    process and, say, the simulator it started). A watchdog thread covers a parent that
    died before the signal was armed.
    """
    parent = os.getppid()

    def kill_group(*_: object) -> None:
        os.killpg(os.getpgrp(), signal.SIGKILL)

    signal.signal(signal.SIGTERM, kill_group)

    def watch() -> None:
        while True:
            if os.getppid() != parent:
                kill_group()
            time.sleep(1.0)

    threading.Thread(target=watch, daemon=True).start()
