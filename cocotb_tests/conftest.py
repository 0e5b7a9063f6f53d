"""pytest options of the co-simulation tests."""

from __future__ import annotations

import os

import pytest


def pytest_addoption(parser: pytest.Parser) -> None:
    parser.addoption("--waves", action="store_true", default=False,
                     help="record FST waveforms of the cocotb runs (out/cocotb_results/*.fst)")


def pytest_configure(config: pytest.Config) -> None:
    if config.getoption("--waves", default=False):
        os.environ["IRNUC_WAVES"] = "1"
