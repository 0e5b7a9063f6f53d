"""The per-module profile of the bulk model (irnuc.cosim.bulk_profile), on hand-written
fragments in the shape of callgrind_annotate's output and Verilator's generated C++: the
instructions of each line go to the instance whose signal the statement assigns, instances
to their module, other files by kind; call lines (inclusive counts) are left out."""

from __future__ import annotations

import pytest

from irnuc.cosim.bulk_profile import (
    OTHER,
    PORTS,
    SCHEDULER,
    annotated_lines,
    attribute,
    instance_of,
    module_map,
    total_instructions,
)

TOP = "top"

ANNOTATED = """\
--------------------------------------------------------------------------------
Ir
--------------------------------------------------------------------------------
1,000 (100.0%)  PROGRAM TOTALS

--------------------------------------------------------------------------------
-- Auto-annotated source: /b/Vtop___024root__0.cpp
--------------------------------------------------------------------------------
Ir

 10 ( 1.00%)  void Vtop___024root___nba_sequent__TOP__0(Vtop___024root* vlSelf) {
  .           auto& vlSelfRef = std::ref(*vlSelf).get();
200 (20.00%)      vlSelfRef.top__DOT__u_a__DOT__cnt_q
 50 ( 5.00%)          = (vlSelfRef.top__DOT__u_a__DOT__cnt_q + 1U);
 30 ( 3.00%)      if ((vlSelfRef.top__DOT__u_b__DOT__u_c__DOT__valid_q)) {
100 (10.00%)          vlSelfRef.__Vdly__top__DOT__u_b__DOT__u_c__DOT__data_q = vlSelfRef.in_i;
  .           }
  4 ( 0.40%)          Vtop___024root___nba_sequent__TOP__1(vlSelf);
400 (40.00%)  => /b/Vtop___024root__0.cpp:Vtop___024root___nba_sequent__TOP__1 (3x)
 40 ( 4.00%)      vlSelfRef.__VactTriggered[0U] = vlSelfRef.clk_i;
 20 ( 2.00%)      vlSelfRef.out_o = vlSelfRef.top__DOT__u_a__DOT__cnt_q;
 10 ( 1.00%)  }

--------------------------------------------------------------------------------
-- Auto-annotated source: /v/include/verilated_funcs.h
--------------------------------------------------------------------------------
Ir

 60 ( 6.00%)      return (-((lhs) & (1ULL << (lbits - 1))));

--------------------------------------------------------------------------------
-- Auto-annotated source: /r/cosim/harness/bulk_main.cpp
--------------------------------------------------------------------------------
Ir

 70 ( 7.00%)          top->clk_i = 1;
950 (95.00%)  events annotated
"""

PROF = """
void Vtop___024root___nba_sequent__TOP__0__PROF__counter__l12(Vtop___024root* vlSelf) {
    auto& vlSelfRef = std::ref(*vlSelf).get();
    vlSelfRef.top__DOT__u_a__DOT__cnt_q
        = (vlSelfRef.top__DOT__u_a__DOT__cnt_q + 1U);
}

void Vtop___024root___nba_sequent__TOP__1__PROF__pipe__l30(Vtop___024root* vlSelf) {
    auto& vlSelfRef = std::ref(*vlSelf).get();
    if (vlSelfRef.top__DOT__u_b__DOT__u_c__DOT__valid_q) {
        vlSelfRef.__Vdly__top__DOT__u_b__DOT__u_c__DOT__data_q = vlSelfRef.in_i;
    }
}
"""


def test_instance_of_names_the_hierarchy_and_the_scheduler():
    assert instance_of("top__DOT__u_a__DOT__cnt_q", TOP) == "u_a"
    assert instance_of("top__DOT__u_b__DOT__u_c__DOT__data_q", TOP) == "u_b/u_c"
    assert instance_of("__Vdly__top__DOT__u_b__DOT__u_c__DOT__data_q", TOP) == "u_b/u_c"
    assert instance_of("top__DOT__flag", TOP) == "(top)"
    assert instance_of("__VactTriggered", TOP) == SCHEDULER
    assert instance_of("__Vtrigprevexpr___TOP__clk_i__0", TOP) == SCHEDULER
    assert instance_of("out_o", TOP) == PORTS


def test_module_map_from_prof_cfuncs_names():
    assert module_map(PROF, TOP) == {"u_a": "counter", "u_b/u_c": "pipe"}


def test_annotated_lines_skip_call_lines_and_the_footer():
    lines = list(annotated_lines(ANNOTATED))
    assert sum(n for _, n, _ in lines) == 10 + 200 + 50 + 30 + 100 + 4 + 40 + 20 + 10 + 60 + 70
    assert not any(code.lstrip().startswith("=>") for _, _, code in lines)
    assert total_instructions(ANNOTATED) == 1000


def test_attribute_by_assigned_instance_module_and_file_kind():
    prof = attribute(ANNOTATED, "___024root__0.cpp", module_map(PROF, TOP), TOP, cycles=10)
    # The statement's continuation line goes with its left-hand side; the if's condition
    # with the signal it tests; the function's entry, exit and call with no instance.
    assert prof.instances["u_a"] == 250
    assert prof.instances["u_b/u_c"] == 130
    assert prof.instances[SCHEDULER] == 40
    assert prof.instances[PORTS] == 20
    assert prof.instances[OTHER] == 10 + 4 + 10  # entry, call, return
    assert prof.modules["counter"] == 250 and prof.modules["pipe"] == 130
    assert prof.outside == {"Verilator helpers (inlined)": 60, "harness": 70}
    rows = prof.shares(prof.modules)
    assert rows[0]["name"] == "counter" and rows[0]["percent"] == pytest.approx(25.0)
    assert {r["name"]: r["per_cycle"] for r in rows}["counter"] == 25.0


def test_total_is_required():
    with pytest.raises(ValueError, match="PROGRAM TOTALS"):
        total_instructions("no totals here")
