"""Memory checks made before a large allocation, so that an oversized request is one clear
line instead of a ``MemoryError`` (or the kernel's OOM killer) after minutes of work.

Estimates are deliberately generous (they count the temporaries of the code that runs);
:func:`check_memory` compares them with what the machine can give now.
"""

from __future__ import annotations

import os
from pathlib import Path

from irnuc.common.errors import UserError

#: Share of the available memory one request may plan to use (the rest is head room for
#: the interpreter, libraries and other processes).
USABLE_FRACTION = 0.8


class ResourceError(UserError):
    """A request needs more memory than the machine has available (a ``ValueError``)."""


def _meminfo_available(path: str = "/proc/meminfo") -> int | None:
    try:
        with open(path) as fh:
            for line in fh:
                if line.startswith("MemAvailable:"):
                    return int(line.split()[1]) * 1024  # the kernel reports kB
    except (OSError, ValueError, IndexError):
        return None
    return None


def _cgroup_available() -> int | None:
    """Room left under a cgroup v2 memory limit (containers), if there is one."""
    base = Path("/sys/fs/cgroup")
    try:
        limit = (base / "memory.max").read_text().strip()
        if limit == "max":
            return None
        return max(int(limit) - int((base / "memory.current").read_text()), 0)
    except (OSError, ValueError):
        return None


def available_bytes() -> int | None:
    """Memory the kernel can give without swapping (``MemAvailable``, bounded by a cgroup
    v2 limit); None where it cannot be read (then no check is made)."""
    found = [v for v in (_meminfo_available(), _cgroup_available()) if v is not None]
    return min(found) if found else None


def format_bytes(n: float) -> str:
    """``1536`` -> ``'1.5 KiB'``."""
    for unit in ("B", "KiB", "MiB", "GiB", "TiB", "PiB"):
        if abs(n) < 1024 or unit == "PiB":
            return f"{n:.0f} {unit}" if unit == "B" else f"{n:.1f} {unit}"
        n /= 1024
    return f"{n:.1f} PiB"  # not reached


def check_memory(need: float, what: str, hint: str = "") -> None:
    """Raise :class:`ResourceError` when ``need`` bytes exceed the usable available memory.

    Parameters
    ----------
    need : float
        Estimated peak bytes of the request.
    what : str
        The request, as the user gave it (flags or arguments), named first in the message.
    hint : str
        What to change, e.g. "use fewer frames".
    """
    if os.environ.get("IRNUC_NO_MEMORY_CHECK"):
        return
    avail = available_bytes()
    if avail is None or need <= USABLE_FRACTION * avail:
        return
    raise ResourceError(f"{what} needs an estimated {format_bytes(need)} of memory but only "
                        f"{format_bytes(avail)} is available"
                        + (f"; {hint}" if hint else ""))
