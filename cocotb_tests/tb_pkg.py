"""cocotb tests of ``hdl/irnuc_pkg.sv`` through ``cocotb_tests/hdl/irnuc_pkg_probe.sv``
(run by ``cocotb_tests/test_pkg.py``).

The package is the RTL's single source of the mode encodings, the coefficient word layout
and the DPC reciprocal table; here its values are read back from the simulated RTL and
compared with the Python side: ``nuc_fixed.config.ROUNDING_MODES`` / ``OVERFLOW_MODES``,
``nuc_fixed.pack_words`` / ``unpack_words`` and ``irnuc.nuc_fixed.dpc.reciprocal_table``.
"""

from __future__ import annotations

import cocotb
import numpy as np
from cocotb.triggers import Timer

from irnuc.cocotb_tests import tb_lib
from irnuc.nuc_fixed import pack_words, unpack_words
from irnuc.nuc_fixed.config import OVERFLOW_MODES, ROUNDING_MODES
from irnuc.nuc_fixed.dpc import reciprocal_table


async def _settle() -> None:
    await Timer(1, unit="ns")


@cocotb.test()
async def mode_enums(dut) -> None:
    """rounding_e / overflow_e: one literal per configuration mode, same codes, no more."""
    for prefix, modes in (("rounding", ROUNDING_MODES), ("overflow", OVERFLOW_MODES)):
        await _settle()
        count = int(getattr(dut, f"{prefix}_count_o").value)
        assert count == len(modes), f"{prefix}_e has {count} literals, Python {len(modes)}"
        for name, code in modes.items():
            port = getattr(dut, f"{prefix}_{name}_o", None)
            assert port is not None, f"no literal for {prefix} mode {name!r} in irnuc_pkg"
            assert int(port.value) == code, (
                f"{prefix} {name}: RTL {int(port.value)}, Python {code}")


@cocotb.test()
async def coefficient_word_layout(dut) -> None:
    """coef_word #(GW, OW)::word_t packs and unpacks exactly like pack_words / unpack_words."""
    cfg = tb_lib.config_from_env()
    gw, ow = cfg.gain_bits, cfg.offset_bits
    assert len(dut.word_o) == cfg.word_bits
    await _settle()
    assert int(dut.word_bits_o.value) == cfg.word_bits
    assert int(dut.offset_lsb_o.value) == gw
    assert int(dut.bad_bit_o.value) == gw + ow
    rng = np.random.default_rng(tb_lib.seed_from_env())
    half = 1 << (ow - 1)
    n = 200
    g = np.concatenate([[0, (1 << gw) - 1, 0, (1 << gw) - 1],
                        rng.integers(0, 1 << gw, n, dtype=np.int64)])
    o = np.concatenate([[-half, half - 1, -1, 0], rng.integers(-half, half, n, dtype=np.int64)])
    bad = np.concatenate([[True, False, True, False], rng.random(n) < 0.5])
    words = pack_words(g, o, bad, cfg)
    ug, uo, ub = unpack_words(words, cfg)
    for i in range(g.size):
        dut.gain_i.value = int(g[i])
        dut.offset_i.value = int(o[i]) & ((1 << ow) - 1)
        dut.bad_i.value = int(bad[i])
        dut.word_i.value = int(words[i])
        await _settle()
        got = int(dut.word_o.value)
        assert got == int(words[i]), (f"gain {g[i]} offset {o[i]} bad {bad[i]}: RTL word "
                                      f"{got:#x}, pack_words {int(words[i]):#x}")
        assert int(dut.gain_o.value) == int(ug[i])
        assert int(dut.offset_o.value) == int(uo[i]) & ((1 << ow) - 1)
        assert bool(int(dut.bad_o.value)) == bool(ub[i])


@cocotb.test()
async def reciprocal_table_matches(dut) -> None:
    """The DPC reciprocal table of the RTL is irnuc.nuc_fixed.dpc.reciprocal_table (proven exact)."""
    cfg = tb_lib.config_from_env()
    shift, table = reciprocal_table(cfg.out_bits)
    await _settle()
    assert int(dut.recip_shift_o.value) == shift
    assert len(dut.recip_o) == shift + 1
    for n in range(9):
        dut.recip_n_i.value = n
        await _settle()
        got = int(dut.recip_o.value)
        assert got == table[n], f"R[{n}]: RTL {got}, Python {table[n]}"
