"""CPU seconds (user + system) of this process and everything it started.

A phase's wall time on a shared machine says little about what it costs; its CPU time
does: divided by the parallelism the phase can use (2 sweep workers, 4 placer seeds on 2
cores, ...) it bounds the phase's wall time on a quiet machine. The executor's workers are
children of a forkserver, not of this process, so :func:`os.times` alone misses them while
the forkserver lives: on Linux the live process tree is read from ``/proc`` as well
(each live descendant's own and reaped children's time), elsewhere ``os.times`` only.
"""

from __future__ import annotations

import os
from pathlib import Path

_TICK = os.sysconf("SC_CLK_TCK") if hasattr(os, "sysconf") else 100


def _stat(pid: str) -> tuple[int, float] | None:
    """(parent pid, utime + stime + cutime + cstime in seconds) of a process, or None."""
    try:
        text = Path(f"/proc/{pid}/stat").read_text()
    except OSError:
        return None
    rest = text[text.rfind(")") + 2:].split()  # the name may hold spaces and parentheses
    # fields after the name: state ppid ... utime(12) stime(13) cutime(14) cstime(15)
    return int(rest[1]), sum(int(x) for x in rest[11:15]) / _TICK


def tree_cpu_seconds(root: int | None = None) -> float:
    """CPU seconds of this process (or of process ``root``), its reaped children and every
    live descendant (with the children those reaped): monotone over a run as long as no
    live descendant exits unreaped by this tree (a reaped one moves into its parent's
    children's time). Another process gone: 0."""
    if root is None or root == os.getpid():
        t = os.times()
        own = t.user + t.system + t.children_user + t.children_system
        me = os.getpid()
    else:
        st = _stat(str(root))
        if st is None:
            return 0.0
        own, me = st[1], int(root)
    if not Path("/proc/self/stat").is_file():
        return own
    parent: dict[int, int] = {}
    cpu: dict[int, float] = {}
    for d in os.listdir("/proc"):
        if d.isdigit():
            st = _stat(d)
            if st is not None:
                parent[int(d)], cpu[int(d)] = st
    kids: dict[int, list[int]] = {}
    for pid, pp in parent.items():
        kids.setdefault(pp, []).append(pid)
    total, todo = own, list(kids.get(me, []))
    while todo:
        pid = todo.pop()
        total += cpu.get(pid, 0.0)
        todo.extend(kids.get(pid, []))
    return total
