"""Scheduling of the whole test suite over pytest-xdist workers (docs/testing.md).

``pyproject.toml`` runs the suite with ``-n auto --dist loadgroup``; every test of one
group runs in one worker, the groups spread over the workers. The groups, from the node
id (pytest-xdist's own ``xdist_group`` marks do not reach its scheduler under pytest 9,
so :func:`pytest_xdist_make_scheduler` gives it the groups):

* a co-simulation test whose parameters name a pipeline configuration (``minimal``,
  ``typical14+half_even+wrap``, ``tcoffset14``, ``ffc14``, ...) joins the group of that configuration,
  ``cosim-<configuration>``: the simulations and builds its tests share (one run of a
  testbench module per configuration, the coverage closure over them, a bulk build) stay
  in one worker;
* a test of ``tests/`` joins the group of its file, so that a module-scoped fixture (a
  whole report, a sweep) is computed once;
* anything else (a test that builds and runs on its own) is scheduled alone.

Slow tests go first (the order of collection otherwise), so that the long ones start
early and the many short ones fill the workers at the end. A simulation needed by tests
of several groups still runs once per session (``cocotb_tests/runs.py``: a file lock and a
done marker in the session's results folder).
"""

from __future__ import annotations

import functools
import re

import pytest


@functools.cache
def _configurations() -> frozenset[str]:
    from irnuc.nuc_fixed import pipeline_names

    # Every named configuration, the methods' and stages' too (method=None): the tests of
    # `tcoffset14` share one run of tb_method as those of `minimal` share one of tb_top.
    return frozenset(pipeline_names(method=None))


def group_of(nodeid: str) -> str:
    """The scheduling group of a test (its node id when it has none)."""
    path, _, rest = nodeid.partition("::")
    if path.startswith("tests/"):
        return f"file-{path}"
    params = re.search(r"\[(.*)\]$", rest)
    if path.startswith("cocotb_tests/") and params:
        for token in params.group(1).split("-"):
            if token.split("+", 1)[0] in _configurations():
                return f"cosim-{token}"
    return nodeid


def pytest_collection_modifyitems(config: pytest.Config, items: list[pytest.Item]) -> None:
    items.sort(key=lambda it: it.get_closest_marker("slow") is None)


def pytest_xdist_make_scheduler(config: pytest.Config, log):
    """``--dist loadgroup`` with the groups of :func:`group_of`, handed out in the order of
    the collection (slow first): xdist would sort them by their number of tests, so the lint
    file's 237 short tests went first and the tiny report's 90 s fixture (four tests) began
    with seven minutes gone, one worker idle at the end (what ``--no-loadscope-reorder``
    says)."""
    if config.getvalue("dist") != "loadgroup":
        return None
    from xdist.scheduler import LoadScopeScheduling

    config.option.loadscopereorder = False

    class GroupScheduling(LoadScopeScheduling):
        def _split_scope(self, nodeid: str) -> str:
            return group_of(nodeid)

    return GroupScheduling(config, log)
