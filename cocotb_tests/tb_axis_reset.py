"""The AXI start after reset on ``irnuc_axis_top`` (run by ``cocotb_tests/test_axis_top.py``,
in a simulation of its own: the assertion stops it): a master that holds a slave port's
valid high across reset (a driver left from a test that failed mid-stream, without the
bench's :func:`~irnuc.cocotb_tests.streams.idle_inputs`) offers a stale item at the first
edge after reset, which the DUT would take; ``irnuc_axis_assert``'s ``a_reset_idle`` must
stop the simulation there. The legal start, the same junk idled by the bench's reset, is
``tb_axis.stale_inputs_idled``.
"""

from __future__ import annotations

import cocotb
from cocotb.clock import Clock
from cocotb.triggers import ClockCycles

from irnuc.cocotb_tests.streams import CLK_PERIOD_NS, reset

#: The message of a violation test that ran to its end.
NOT_FIRED = "no assertion fired"


@cocotb.test()
async def violation_valid_at_reset(dut) -> None:
    """s_axis_coef_tvalid high (with a word) through reset: a_reset_idle must fire."""
    Clock(dut.clk_i, CLK_PERIOD_NS, unit="ns").start()
    dut.s_axis_coef_tdata.value = 1
    dut.s_axis_coef_tvalid.value = 1
    await reset(dut, 2)
    await ClockCycles(dut.clk_i, 4)
    raise AssertionError(NOT_FIRED)
