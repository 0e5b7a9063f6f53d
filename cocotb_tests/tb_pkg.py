"""cocotb tests of ``hdl/irnuc_pkg.sv`` through the generated probe
``cosim/hdl/irnuc_pkg_probe.sv`` (run by ``cocotb_tests/test_pkg.py``).

Every item of the shared-constants spec (:mod:`irnuc.nuc_fixed.rtl_spec`) is read back from
the simulated RTL and compared with the spec: each constant, range end and enum literal
(and each enum's number of literals), each word layout (field positions, width, packing and
unpacking against ``pack_words`` / ``unpack_words`` for the coefficient word), the
package's width functions over their whole argument ranges and the DPC reciprocal table.
"""

from __future__ import annotations

import cocotb
import numpy as np
from cocotb.triggers import Timer

from irnuc.cocotb_tests import tb_lib
from irnuc.nuc_fixed import pack_words, rtl_spec, unpack_words
from irnuc.nuc_fixed.dpc import reciprocal_table


async def _settle() -> None:
    await Timer(1, unit="ns")


@cocotb.test()
async def constants_ranges_enums(dut) -> None:
    """Every constant, range end, enum literal and enum size of the spec, by name."""
    await _settle()
    want = rtl_spec.probe_values()
    wrong = []
    for port, value in want.items():
        handle = getattr(dut, port, None)
        if handle is None:
            wrong.append(f"{port}: no such port (regenerate: python -m irnuc.cosim.spec_files "
                         "--write)")
        elif int(handle.value) != value:
            wrong.append(f"{port}: RTL {int(handle.value)}, spec {value}")
    assert not wrong, "\n".join(wrong)
    assert len(want) >= len(rtl_spec.CONSTANTS) + 2 * len(rtl_spec.RANGES) + 5


@cocotb.test()
async def width_functions(dut) -> None:
    """mul_chunks(bits) for every operand width 1..64 and dpc_recip_shift(B) for every
    output width the ranges allow: the RTL's functions against the spec's."""
    await _settle()
    chunks = int(dut.mul_chunks_o.value)
    shifts = int(dut.dpc_recip_shift_o.value)
    for b in range(1, rtl_spec.PROBE_MUL_BITS + 1):
        got = (chunks >> (8 * (b - 1))) & 0xFF
        assert got == rtl_spec.mul_chunks(b), f"mul_chunks({b}): RTL {got}"
    for b in range(1, rtl_spec.PROBE_OUT_BITS + 1):
        got = (shifts >> (8 * (b - 1))) & 0xFF
        assert got == rtl_spec.dpc_recip_shift(b), f"dpc_recip_shift({b}): RTL {got}"
    assert rtl_spec.PROBE_OUT_BITS == rtl_spec.PIPELINE_RANGES["out_bits"][1]


@cocotb.test()
async def coefficient_word_layout(dut) -> None:
    """coef_word #(GW, OW)::word_t and its lsb functions: the spec's layout, and packing
    and unpacking exactly like pack_words / unpack_words."""
    cfg = tb_lib.config_from_env()
    lay = rtl_spec.COEF_WORD
    fields = lay.layout(GainBits=cfg.gain_bits, OffsetBits=cfg.offset_bits)
    assert fields == cfg.word_fields
    await _settle()
    assert int(getattr(dut, rtl_spec.layout_port(lay, "bits")).value) == cfg.word_bits
    for name, (lsb, width) in fields.items():
        assert int(getattr(dut, rtl_spec.layout_port(lay, "lsb", name)).value) == lsb, name
        assert len(getattr(dut, rtl_spec.layout_port(lay, "field_i", name))) == width, name
    gw, ow = cfg.gain_bits, cfg.offset_bits
    rng = np.random.default_rng(tb_lib.seed_from_env())
    half = 1 << (ow - 1)
    n = 200
    g = np.concatenate([[0, (1 << gw) - 1, 0, (1 << gw) - 1],
                        rng.integers(0, 1 << gw, n, dtype=np.int64)])
    o = np.concatenate([[-half, half - 1, -1, 0], rng.integers(-half, half, n, dtype=np.int64)])
    bad = np.concatenate([[True, False, True, False], rng.random(n) < 0.5])
    words = pack_words(g, o, bad, cfg)
    ug, uo, ub = unpack_words(words, cfg)

    def port(what: str, field: str = ""):
        return getattr(dut, rtl_spec.layout_port(lay, what, field))

    for i in range(g.size):
        port("field_i", "gain").value = int(g[i])
        port("field_i", "offset").value = int(o[i]) & ((1 << ow) - 1)
        port("field_i", "bad").value = int(bad[i])
        port("word_i").value = int(words[i])
        await _settle()
        got = int(port("word_o").value)
        assert got == int(words[i]), (f"gain {g[i]} offset {o[i]} bad {bad[i]}: RTL word "
                                      f"{got:#x}, pack_words {int(words[i]):#x}")
        assert int(port("field_o", "gain").value) == int(ug[i])
        assert int(port("field_o", "offset").value) == int(uo[i]) & ((1 << ow) - 1)
        assert bool(int(port("field_o", "bad").value)) == bool(ub[i])


@cocotb.test()
async def reciprocal_table_matches(dut) -> None:
    """The DPC reciprocal table of the RTL is irnuc.nuc_fixed.dpc.reciprocal_table (proven
    exact by cocotb_tests/test_dpc_core.py)."""
    cfg = tb_lib.config_from_env()
    shift, table = reciprocal_table(cfg.out_bits)
    assert len(dut.recip_o) == shift + 1
    for n in range(9):
        dut.recip_n_i.value = n
        await _settle()
        got = int(dut.recip_o.value)
        assert got == table[n], f"R[{n}]: RTL {got}, Python {table[n]}"


@cocotb.test()
async def method_word_layouts(dut) -> None:
    """Every other word layout of the spec (the methods' memories and frame word, generated
    into irnuc_pkg as packed structs): each field where the spec puts it, packing and
    unpacking through the struct (the spec's layouts are the configurations' memories:
    tests/test_method_spec.py)."""
    rng = np.random.default_rng(tb_lib.seed_from_env() + 7)
    await _settle()
    for lay in rtl_spec.LAYOUTS:
        if lay is rtl_spec.COEF_WORD:
            continue

        def port(what: str, field: str = "", lay=lay):
            return getattr(dut, rtl_spec.layout_port(lay, what, field))

        widths = {f.width: len(port("field_i", f.name)) for f in lay.fields
                  if isinstance(f.width, str)}
        fields = lay.layout(**widths)
        assert int(port("bits").value) == lay.bits(**widths), lay.name
        for name, (lsb, width) in fields.items():
            assert int(port("lsb", name).value) == lsb, (lay.name, name)
            assert len(port("field_i", name)) == width, (lay.name, name)
        for trial in range(40):
            vals = {n: (int(rng.integers(0, 1 << w)) if trial >= 2 else
                        (0 if trial == 0 else (1 << w) - 1)) for n, (_, w) in fields.items()}
            word = sum(v << fields[n][0] for n, v in vals.items())
            for n, v in vals.items():
                port("field_i", n).value = v
            port("word_i").value = word
            await _settle()
            assert int(port("word_o").value) == word, (lay.name, vals)
            for n, v in vals.items():
                assert int(port("field_o", n).value) == v, (lay.name, n)
