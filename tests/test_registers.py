"""The one register map (``nuc_fixed/registers.toml``) and its three readers agree.

The TOML is read here with :mod:`tomllib` directly and compared with what each side holds:
the constants of ``hdl/irnuc_pkg.sv`` (parsed from the SystemVerilog text), the tables of
``docs/registers.md`` (parsed from the Markdown), and the Python register model
(:class:`irnuc.nuc_fixed.regmap.RegisterModel`) the testbench checks the RTL against. The
model's access rules are checked on hand-made writes (W1C, byte strobes, SLVERR, reserved
registers). The RTL itself is checked against the model in ``cocotb_tests/tb_axis.py``.
"""

from __future__ import annotations

import re
import tomllib
from pathlib import Path

import pytest

from irnuc.nuc_fixed import load_pipeline, regmap

ROOT = Path(__file__).resolve().parents[1]
TOML = tomllib.loads((ROOT / "nuc_fixed" / "registers.toml").read_text())
PKG = (ROOT / "hdl" / "irnuc_pkg.sv").read_text()
DOC = (ROOT / "docs" / "registers.md").read_text()


def _camel(name: str) -> str:
    return "".join(p.capitalize() for p in name.lower().split("_"))


def _pkg_constants() -> dict[str, int]:
    return {m[1]: int(m[2]) for m in re.finditer(
        r"localparam int unsigned (Reg\w+) = (\d+);", PKG)}


def _plain_groups() -> list[dict]:
    return [g for g in TOML["register"] if "config_register" not in g and "count" not in g]


def test_package_constants_are_the_toml() -> None:
    sv = _pkg_constants()
    assert sv["RegMapId"] == TOML["map_id"] == int.from_bytes(b"IRNC", "big")
    assert (sv["RegMapMajor"], sv["RegMapMinor"]) == (TOML["major"], TOML["minor"])
    assert sv["RegAddrBits"] == TOML["address_bits"]
    checked = 0
    for g in TOML["register"]:
        name = _camel(g["name"])
        if "count" in g:
            assert sv[f"Reg{name}Offset"] == g["offset"]
            assert sv[f"Reg{name}Count"] == g["count"]
            continue
        if "config_register" in g:
            assert (sv[f"Reg{name}LoOffset"], sv[f"Reg{name}HiOffset"]) == (
                g["offset"], g["offset"] + 4)
            continue
        assert sv[f"Reg{name}Offset"] == g["offset"], g["name"]
        for f in g["fields"]:
            key = f"Reg{name}{_camel(f['name'])}"
            assert sv[f"{key}Lsb"] == f["lsb"], key
            if f["bits"] > 1:
                assert sv[f"{key}Bits"] == f["bits"], key
            checked += 1
    assert checked >= 40  # every field of the fixed registers


def test_docs_tables_are_the_toml() -> None:
    rows = dict(re.findall(r"^\| (0x[0-9a-f]{3})[^|]* \| `(\w+)", DOC, re.M))
    for g in TOML["register"]:
        assert rows.get(f"0x{g['offset']:03x}", "").startswith(g["name"]), g["name"]
    for g in _plain_groups():
        section = DOC.split(f"## `{g['name']}` (0x{g['offset']:03x})", 1)[1].split("\n## ")[0]
        for f in g["fields"]:
            hi = f["lsb"] + f["bits"] - 1
            bits = str(f["lsb"]) if f["bits"] == 1 else f"{hi}:{f['lsb']}"
            assert re.search(rf"^\| {bits} \| `{f['name']}` \| {f['access'].upper()}", section,
                             re.M), (g["name"], f["name"], bits)


@pytest.mark.parametrize("config", ["typical14", "minimal"])
def test_model_is_the_toml(config: str) -> None:
    cfg = load_pipeline(config)
    m = regmap.RegisterModel(cfg)
    params = {"MaxWidth": cfg.max_width, "MaxHeight": cfg.max_height,
              "AdcBits": cfg.adc_bits, "OutBits": cfg.out_bits, "MapId": TOML["map_id"]}
    for g in _plain_groups():
        reg = m.map[g["name"]]
        assert reg.offset == g["offset"]
        if not m.present(reg):
            continue
        want = 0
        for f in g["fields"]:
            r = f["reset"]
            value = r if isinstance(r, int) else params.get(r)
            if value is not None:
                want |= value << f["lsb"]
            else:  # a reset named after a value not listed above: compare the field alone
                want |= m.reset_value(reg) & (((1 << f["bits"]) - 1) << f["lsb"])
        resp, data = m.read(g["offset"])
        assert (resp, data) == (regmap.OKAY, want), (g["name"], hex(data), hex(want))


def test_model_access_rules_by_hand() -> None:
    cfg = load_pipeline("minimal")
    m = regmap.RegisterModel(cfg)
    ctrl, size = m.map["CTRL"].offset, m.map["FRAME_SIZE"].offset
    # CTRL: nuc_en (bit 0), dpc_en (1), coef_sync (8) reset 1; other bits read 0.
    assert m.read(ctrl) == (regmap.OKAY, 0x103)
    assert m.write(ctrl, 0xFFFF_FEFE) == regmap.OKAY and m.read(ctrl) == (regmap.OKAY, 0x002)
    # Byte strobes: only byte 1 written (coef_sync back to 1), byte 0 kept.
    assert m.write(ctrl, 0x0000_01FF, strb=0b0010) == regmap.OKAY
    assert m.read(ctrl)[1] == 0x102
    # FRAME_SIZE: 0 and above FRAME_MAX are refused and leave the register as it was.
    assert m.write(size, 5 | (7 << 16)) == regmap.OKAY
    for bad in (0 | (7 << 16), 5, (cfg.max_width + 1) | (7 << 16), 5 | ((cfg.max_height + 1) << 16)):
        assert m.write(size, bad) == regmap.SLVERR
        assert m.read(size) == (regmap.OKAY, 5 | (7 << 16))
    # Read-only register: SLVERR on write, value unchanged; outside the map: SLVERR, data 0.
    assert m.write(m.map["ID"].offset, 0) == regmap.SLVERR
    assert m.read(m.map["ID"].offset) == (regmap.OKAY, 0x49524E43)
    hole = m.reserved_offsets()[0]
    assert m.map.at(hole) is None
    assert m.read(hole) == (regmap.SLVERR, 0) and m.write(hole, 1) == regmap.SLVERR
    # W1C: an event sets STATUS.eol_late (bit 3); writing 0 keeps it, writing 1 clears it.
    status = m.map["STATUS"].offset
    m.set_live("STATUS", "eol_late", 1)
    assert m.write(status, 0) == regmap.OKAY and m.read(status)[1] & 0x8
    assert m.write(status, 0x8) == regmap.OKAY and not m.read(status)[1] & 0x8
    # A method register the two-point core does not have: reserved, reads 0, OKAY.
    gain = m.map["GAIN_LO"]
    assert not m.present(gain)
    assert m.write(gain.offset, 0x1234) == regmap.OKAY and m.read(gain.offset) == (regmap.OKAY, 0)
