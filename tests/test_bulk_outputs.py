"""The bulk harness's guard on registered outputs (irnuc.cosim.bulk.comb_outputs).

The harness evaluates the model once per cycle and reads the outputs as the previous
rising edge left them (bulk_main.cpp "Evals"); a top with an output that follows an input
combinationally must be refused at build time. Checked on hand-written fragments in the
shape of Verilator's output (a model header's port declarations, the root's
input-combinational functions).
"""

from __future__ import annotations

from irnuc.cosim.bulk import comb_outputs

HEADER = """
class alignas(VL_CACHE_LINE_BYTES) Vtop final {
    VL_IN8(&clk_i,0,0);
    VL_IN8(&s_valid_i,0,0);
    VL_OUT8(&s_ready_o,0,0);
    VL_OUT8(&m_valid_o,0,0);
    VL_OUTW(&m_data_o,65,0,3);
    VL_IN8(&m_ready_i,0,0);
};
"""

REGISTERED = """
void Vtop___024root___ico_sequent__TOP__0(Vtop___024root* vlSelf) {
    auto& vlSelfRef = std::ref(*vlSelf).get();
    vlSelfRef.top__DOT__u_out__DOT__main_load
        = (1U & ((~ (IData)(vlSelfRef.top__DOT__u_out__DOT__main_valid_q))
                 | (IData)(vlSelfRef.m_ready_i)));
    vlSelfRef.top__DOT__push = ((IData)(vlSelfRef.s_ready_o) & (IData)(vlSelfRef.s_valid_i));
}

void Vtop___024root___nba_comb__TOP__0(Vtop___024root* vlSelf) {
    auto& vlSelfRef = std::ref(*vlSelf).get();
    vlSelfRef.m_valid_o = vlSelfRef.top__DOT__u_out__DOT__main_valid_q;
}
"""

COMBINATIONAL = """
void Vtop___024root___ico_sequent__TOP__0(Vtop___024root* vlSelf) {
    auto& vlSelfRef = std::ref(*vlSelf).get();
    vlSelfRef.s_ready_o = ((IData)(vlSelfRef.m_ready_i) | (IData)(vlSelfRef.top__DOT__e));
    vlSelfRef.m_data_o[1U] = vlSelfRef.top__DOT__d[1U];
    if ((vlSelfRef.s_ready_o == vlSelfRef.m_valid_o)) {
        vlSelfRef.top__DOT__x = 1U;
    }
}
"""


def test_registered_outputs_pass() -> None:
    """Outputs read in the ico region, or assigned outside it, are not combinational."""
    assert comb_outputs(HEADER, REGISTERED) == []


def test_combinational_outputs_are_named() -> None:
    """An output (a narrow one and a word of a wide one) assigned in the ico region is
    named; a comparison (==) of outputs is not an assignment."""
    assert comb_outputs(HEADER, COMBINATIONAL) == ["m_data_o", "s_ready_o"]


def test_inputs_and_internal_signals_are_not_outputs() -> None:
    """Only the header's VL_OUT ports count (an input or an internal signal assigned in
    the region is not an output)."""
    text = COMBINATIONAL.replace("s_ready_o =", "s_valid_i =").replace("m_data_o[1U]",
                                                                        "top__DOT__d2[1U]")
    assert comb_outputs(HEADER, text) == []
