"""The register block's address decode a cycle ahead (``irnuc.cosim.regfiles._predecode``,
``_readback_ahead``).

The committed ``hdl/irnuc_axil_regblock.sv`` is parsed: each register's strobe is the
request ANDed with a flop (``predecode_strb_q``) loaded from the decode of the taken holding
register, read (``ahead_rd_strb_d``) or write (``ahead_wr_strb_d``); each side's decode,
evaluated at every word address of the window, must hit exactly the register's own offset
when its fields allow that direction (from the map, ``regmap.register_map``, not from the
generator). The cycle-level equality
with regblock's own decode is checked by simulation (``cocotb_tests/test_axis_top.py``) and
the register file's proofs (``irnuc formal``).
"""

from __future__ import annotations

import re
from pathlib import Path

import pytest

from irnuc.common.errors import ToolError
from irnuc.cosim import regfiles
from irnuc.nuc_fixed import regmap

REGBLOCK = (Path(__file__).resolve().parents[1] / "hdl" / "irnuc_axil_regblock.sv").read_text()
_AHEAD = re.compile(r"^( *)ahead_(rd|wr)_strb_d\.([\w.\[\]]+) = (.+);$", re.M)
_GATED = re.compile(r"^ *decoded_reg_strb\.([\w.\[\]]+) = cpuif_req_masked"
                    r" & predecode_strb_q\.([\w.\[\]]+);$", re.M)
_LOOP = re.compile(r"for\(int (i\d)=0; \1<(\d+); \1\+\+\) begin\n(.*?)\n *end", re.S)


def _hits(expr: str, side: str, loop: dict[str, int]) -> set[tuple[int, bool]]:
    """(word address, is write) where a side's decode expression of the generated form
    is 1."""
    py = (expr.replace("12'h", "0x").replace("(12)'", "").replace("!1'b", "not 1'b")
          .replace("1'b0", "False").replace("1'b1", "True")
          .replace(f"ahead_{side}_addr", "a").replace("&", " and "))
    return {(a, side == "wr") for a in range(0, 0x1000, 4)
            if eval(py, {}, {"a": a, **loop})}  # our own parsed text


def _expected() -> dict[str, set[tuple[int, bool]]]:
    out = {}
    for r in regmap.register_map().registers:
        access = {f.access for f in r.fields}
        readable = bool(access - {"w1s"})  # regblock: a write-1-to-set field reads as 0
        writable = bool(access - {"ro"})
        out[r.name] = {(r.offset, w) for w, ok in ((False, readable), (True, writable)) if ok}
    return out


def test_strobes_decoded_ahead_hit_their_register() -> None:
    got: dict[str, set[tuple[int, bool]]] = {}
    ahead = REGBLOCK[REGBLOCK.index("ahead_rd_strb_d."):REGBLOCK.index("ahead_wr_ext_d =")]
    for loop in _LOOP.finditer(ahead):
        var, count, body = loop.groups()
        for m in _AHEAD.finditer(body):
            name = m.group(3).replace(f"[{var}]", "[{}]")
            for i in range(int(count)):
                got.setdefault(name.format(i), set()).update(
                    _hits(m.group(4), m.group(2), {var: i}))
    for m in _AHEAD.finditer(_LOOP.sub("", ahead)):
        got.setdefault(m.group(3), set()).update(_hits(m.group(4), m.group(2), {}))
    assert got == _expected()
    gated = _GATED.findall(REGBLOCK)
    assert gated and all(a == b for a, b in gated)
    assert {a.replace("[i0]", "") for a, _ in gated} == {
        re.sub(r"\[\d+\]", "", n) for n in _expected()}
    assert "cpuif_addr ==" not in REGBLOCK  # no strobe left on the request's flops
    assert "predecode_strb_q <= ahead_rd_strb_q;" in REGBLOCK
    assert "predecode_strb_q <= ahead_wr_strb_q;" in REGBLOCK


def test_readback_compares_from_the_flop() -> None:
    stage1 = REGBLOCK[REGBLOCK.index("// readback stage 1"):REGBLOCK.index("readback_data_rt_c =")]
    assert "rd_mux_addr" not in stage1
    selects = re.findall(r"if\(readback_low_q\[ad_low\((12'h[0-9a-f]+)\)\]\) begin", stage1)
    assert len(selects) == len({int(s[4:], 16) for s in selects}) > 10
    assert "if(axil_take_rd) readback_low_q <= 32'(1) << ad_low(ahead_rd_addr);" in REGBLOCK


def test_unexpected_decode_is_refused() -> None:
    body = regfiles._DECODE_HEAD + "        decoded_reg_strb.X = (cpuif_addr == 12'h0);\n" \
        + regfiles._DECODE_TAIL
    with pytest.raises(ToolError, match="strobe line"):
        regfiles._predecode(body)
    with pytest.raises(ToolError, match="address decode is not"):
        regfiles._predecode("always_comb begin\nend\n")
    ok = regfiles._predecode(body.replace("= (cpuif", "= cpuif_req_masked & (cpuif"))
    assert "ahead_rd_strb_d.X = (ahead_rd_addr == 12'h0);" in ok
    assert "ahead_wr_strb_d.X = (ahead_wr_addr == 12'h0);" in ok
    assert "decoded_reg_strb.X = cpuif_req_masked & predecode_strb_q.X;" in ok


def test_unexpected_readback_is_refused() -> None:
    text = "// readback stage 1\nif(ad_low(rd_mux_addr) == ad_low(12'h4) && x) begin\n"
    with pytest.raises(ToolError, match="does not decode ahead"):
        regfiles._readback_ahead(text, 5)
    ok = regfiles._readback_ahead(text.replace(" && x", ""), 5)
    assert "if(readback_low_q[ad_low(12'h4)]) begin" in ok
