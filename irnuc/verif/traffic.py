"""Random register traffic on every configuration (``irnuc traffic``): the cocotb test of
``cocotb_tests/axil_traffic.py`` through ``irnuc_axis_top`` on each named configuration
the wrapper builds, by the suite runner (:func:`irnuc.verif.run_suite`), with coverage.

The test suite runs it on the configurations its wrapper testbenches already simulate
(minimal, typical14, tcoffset14, drift14, table14, ffc14, quadffc14, tcffc14); this runs
it on all of them (the others cost a Verilator build each).
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from pathlib import Path

from irnuc.cocotb_tests import tb_axis, tb_axis_ffc, tb_axis_method
from irnuc.verif.suite import SuiteCase, SuiteResult, run_suite

TOP = "irnuc_axis_top"


def traffic_case(cfg) -> SuiteCase:
    """The testbench and test that carry the traffic on ``cfg``: the two-point wrapper's
    (tb_axis), the FFC compositions' (tb_axis_ffc, with a second FFC run), the methods'
    and blind_drift's (tb_axis_method)."""
    if cfg.has("ffc"):
        return SuiteCase(TOP, cfg, tb_axis_ffc.__name__, tests=("ffc_second_run",))
    if cfg.method == "two_point":
        return SuiteCase(TOP, cfg, tb_axis.__name__, tests=("register_traffic",))
    return SuiteCase(TOP, cfg, tb_axis_method.__name__, tests=("method_register_traffic",))


def configurations(spec: str | None) -> list:
    """The named configurations of ``--configs`` (comma-separated; None: every one)."""
    from irnuc.common.errors import UserError
    from irnuc.common.schema import nearest
    from irnuc.nuc_fixed import load_pipeline, pipeline_names

    names = list(pipeline_names(method=None))
    if spec is None:
        return [load_pipeline(n) for n in names]
    words = [w.strip() for w in spec.split(",")]
    for w in words:
        if w not in names:
            raise UserError(f"--configs {w or repr(spec)}: no such configuration"
                            f"{nearest(w, names)} (allowed: {', '.join(names)})")
    return [load_pipeline(w) for w in dict.fromkeys(words)]


def run_traffic(configs: Sequence, out_dir: Path, *, coverage: bool = True,
                progress: Callable[[int, int], None] | None = None) -> SuiteResult:
    """The traffic on each configuration (builds first, then one test each)."""
    return run_suite([traffic_case(c) for c in configs], out_dir, coverage=coverage,
                     progress=progress)


__all__ = ["configurations", "run_traffic", "traffic_case"]
