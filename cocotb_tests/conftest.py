"""pytest options and session set-up of the co-simulation tests."""

from __future__ import annotations

import os

import pytest


def pytest_addoption(parser: pytest.Parser) -> None:
    parser.addoption("--waves", action="store_true", default=False,
                     help="record FST waveforms of the cocotb runs (in the session's "
                          "<basetemp>/cocotb_results)")


def pytest_configure(config: pytest.Config) -> None:
    if config.getoption("--waves", default=False):
        os.environ["IRNUC_WAVES"] = "1"


@pytest.fixture(scope="session", autouse=True)
def _session_results(tmp_path_factory: pytest.TempPathFactory):
    """One results folder per pytest session, shared by the xdist workers (their basetemps
    are subfolders of the session's), so that each simulation runs once per session."""
    from irnuc.cocotb_tests import runs

    base = tmp_path_factory.getbasetemp()
    root = base.parent if os.environ.get("PYTEST_XDIST_WORKER") else base
    runs.set_results_root(root / "cocotb_results")
    yield
    runs.set_results_root(None)
