"""Stream protocol of ``nuc_core``, ``dpc_core`` and ``nuc_dpc_top``: registered boundaries
and the RTL's protocol assertions (``cocotb_tests/tb_protocol.py``).

* every output is a register: inputs changed or glitched between clock edges (the output
  ready included) move no output before the next edge, for every named configuration;
* deliberately broken protocol (valid dropped before ready, data changed while stalled,
  an illegal frame size) stops the simulation with the matching assertion
  (``hdl/irnuc_stream_assert.sv``, ``hdl/irnuc_frame_assert.sv``): the cocotb test fails
  and the simulator log names the assertion.

The static counterpart (no combinational input-to-output path in the netlist) is
``tests/test_comb_paths.py``.
"""

from __future__ import annotations

import functools

import pytest

from irnuc import cosim
from irnuc.cocotb_tests.runs import check_case, results_root
from irnuc.cocotb_tests.tb_protocol import NOT_FIRED
from irnuc.nuc_fixed import load_pipeline, pipeline_names

MODULE = "irnuc.cocotb_tests.tb_protocol"
TOPS = ("nuc_core", "dpc_core", "nuc_dpc_top")
#: cocotb tests that must pass (one simulation runs them all).
PASSING = ("registered_outputs", "clean_stall")
#: violation test -> the assertion label that must fire.
VIOLATIONS = {
    "violation_valid_dropped": "a_valid_held",
    "violation_data_changed": "a_data_stable",
    "violation_frame_size": "a_frame_size",
}

pytestmark = [pytest.mark.cosim, pytest.mark.slow]


def _results_xml(top: str, config: str, what: str):
    cfg = load_pipeline(config)
    return results_root() / f"{cfg.name}-{cfg.digest()[:8]}-{top}-protocol-{what}.xml"


@functools.cache
def _passing(top: str, config: str) -> dict[str, cosim.CaseResult]:
    cfg = load_pipeline(config)
    xml = cosim.run(cosim.build(top, cfg), MODULE, testcase=list(PASSING),
                  results_xml=_results_xml(top, config, "boundary"))
    results = cosim.read_results(xml)
    fired = cosim.assertion_failures(xml)
    if fired:
        results = {k: cosim.CaseResult(k, False, v.message + "\n" + "\n".join(fired))
                   for k, v in results.items()}
    return results


@pytest.mark.parametrize("case", PASSING)
@pytest.mark.parametrize("config", pipeline_names())
@pytest.mark.parametrize("top", TOPS)
def test_registered_boundary(top: str, config: str, case: str) -> None:
    check_case(_passing(top, config), case)


def _violation_params() -> list[tuple[str, str]]:
    return [(top, v) for top in TOPS for v in VIOLATIONS
            if not (v == "violation_frame_size" and top == "nuc_core")]


@pytest.mark.parametrize(("top", "violation"), _violation_params())
def test_assertion_fires(top: str, violation: str) -> None:
    """The broken protocol fails the cocotb test through the named RTL assertion."""
    cfg = load_pipeline("minimal")
    xml = cosim.run(cosim.build(top, cfg), MODULE, testcase=violation,
                  results_xml=_results_xml(top, "minimal", violation))
    res = cosim.read_results(xml)[violation]
    fired = cosim.assertion_failures(xml)
    assert not res.passed, "the protocol violation passed"
    assert NOT_FIRED not in res.message, f"{violation}: the simulation went on\n{res.message}"
    label = VIOLATIONS[violation]
    assert any(f"{top}." in ln and f".{label}:" in ln for ln in fired), (
        f"expected assertion {label} in {top}; the simulator log reports {fired}")
