"""Progress of long-running commands on stderr: a tqdm bar on a terminal, one line per
quarter otherwise (so CI logs stay readable)."""

from __future__ import annotations

import sys
import time
from typing import TextIO


class ProgressBar:
    """``bar(done, total)`` reports progress; ``bar.close()`` ends a terminal bar."""

    def __init__(self, label: str, stream: TextIO | None = None) -> None:
        self.label = label
        self.stream = stream or sys.stderr
        self.start = time.perf_counter()
        self.tty = bool(getattr(self.stream, "isatty", lambda: False)())
        self._quarter = -1
        self._bar = None

    def __call__(self, done: int, total: int) -> None:
        if self.tty:
            if self._bar is None:
                from tqdm import tqdm

                self._bar = tqdm(total=total, desc=self.label, file=self.stream, leave=True,
                                 dynamic_ncols=True)
            self._bar.total = total
            self._bar.n = done
            self._bar.refresh()
            if done >= total:
                self.close()
            return
        frac = done / total if total else 1.0
        quarter = int(frac * 4)
        if quarter == self._quarter:
            return
        self._quarter = quarter
        elapsed = time.perf_counter() - self.start
        self.stream.write(f"{self.label} [{done}/{total}] {elapsed:.1f} s\n")
        self.stream.flush()

    def close(self) -> None:
        if self._bar is not None:
            self._bar.close()
            self._bar = None
