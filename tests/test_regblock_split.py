"""The register block's retimed read-back split (``irnuc.cosim.regfiles._readback_split``).

The first read-back stage of the committed ``hdl/irnuc_axil_regblock.sv`` decodes the low
address bits its ``ad_low`` function returns (parsed from the SystemVerilog text) and
chooses among the registers of one bank, ``offset >> low`` (the offsets from the map,
``regmap.register_map``): that fan-in before the retiming flop was the wrapper's longest
path on ECP5 with peakrdl-regblock's own split (docs/regmap.md, "The register block").
"""

from __future__ import annotations

import re
from collections import Counter
from pathlib import Path

import pytest

from irnuc.cosim.regfiles import _readback_split
from irnuc.nuc_fixed import regmap

REGBLOCK = (Path(__file__).resolve().parents[1] / "hdl" / "irnuc_axil_regblock.sv").read_text()


@pytest.mark.parametrize(("span", "data_bytes", "low"), [
    (0x1c4, 4, 5),    # the map: 113 words need 7 word bits, 3 of them in the first stage
    (0x1000, 4, 7),   # the whole 4 KiB window: regblock's own split (5 of 10 word bits)
    (0x200, 4, 5),    # 128 words: 7 word bits
    (0x201, 4, 6),    # one byte more: 8 word bits, 4 in the first stage
    (0x10, 8, 4),     # 64-bit words: 3 byte bits, 1 word bit, taken as 2: 1 in the first
])
def test_split_halves_the_span_word_bits(span: int, data_bytes: int, low: int) -> None:
    assert _readback_split(span, data_bytes) == low


def test_committed_first_stage_fan_in() -> None:
    m = re.search(r"function automatic bit \[(\d+):0\] ad_low\(bit \[11:0\] addr\);\s*"
                  r"return addr\[(\d+):0\];", REGBLOCK)
    assert m, "no ad_low function in the register block (retime_read_fanin off?)"
    low = int(m.group(1)) + 1
    assert int(m.group(2)) + 1 == low
    assert f"readback_addr_rt[11:{low}]" in REGBLOCK
    readable = [r for r in regmap.register_map().registers
                if any(f.access != "w1s" for f in r.fields)]
    banks = Counter(r.offset >> low for r in readable)
    # At most 8 registers behind each bank's retiming flop (regblock's split: up to 32).
    assert max(banks.values()) <= 8, banks
