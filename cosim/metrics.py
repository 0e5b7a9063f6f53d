"""Metrics a testbench records for whoever runs it (the suite runner, the report).

A testbench appends JSON lines to the file named by ``$IRNUC_TB_METRICS`` (set by the
runner: ``irnuc.verif.suite.run_suite``, ``irnuc.cocotb_tests.runs.run_module``); the
runner reads them back with :func:`read`.
"""

from __future__ import annotations

import json
import os
from pathlib import Path
from typing import Any

#: Environment variable naming the JSON-lines file a testbench records metrics into.
METRICS_ENV = "IRNUC_TB_METRICS"


def record(**metrics: object) -> None:
    """Append one JSON line of metrics, if the runner asked for them."""
    path = os.environ.get(METRICS_ENV)
    if path:
        with open(path, "a") as fh:
            fh.write(json.dumps(metrics, default=int) + "\n")


def read(path: Path) -> list[dict[str, Any]]:
    """The metric lines of a file (none if it is missing; a line cut by a killed simulator
    is skipped)."""
    path = Path(path)
    if not path.is_file():
        return []
    out = []
    for line in path.read_text().splitlines():
        try:
            out.append(json.loads(line))
        except json.JSONDecodeError:
            continue
    return out
