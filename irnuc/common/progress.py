"""A minimal progress bar on stderr, shared by every long-running command."""

from __future__ import annotations

import sys
import time
from typing import TextIO


class ProgressBar:
    """``bar(done, total)`` redraws one line on a terminal.

    Into a log file (not a terminal) it writes one plain line per quarter instead, so CI
    logs stay readable.
    """

    def __init__(self, label: str, stream: TextIO | None = None, width: int = 30) -> None:
        self.label = label
        self.stream = stream or sys.stderr
        self.width = width
        self.start = time.perf_counter()
        self.tty = bool(getattr(self.stream, "isatty", lambda: False)())
        self._quarter = -1

    def __call__(self, done: int, total: int) -> None:
        frac = done / total if total else 1.0
        elapsed = time.perf_counter() - self.start
        if self.tty:
            filled = round(frac * self.width)
            bar = "#" * filled + "." * (self.width - filled)
            self.stream.write(f"\r{self.label} [{bar}] {done}/{total} {elapsed:6.1f} s")
            if done >= total:
                self.stream.write("\n")
        else:
            quarter = int(frac * 4)
            if quarter == self._quarter:
                return
            self._quarter = quarter
            self.stream.write(f"{self.label} [{done}/{total}] {elapsed:.1f} s\n")
        self.stream.flush()
