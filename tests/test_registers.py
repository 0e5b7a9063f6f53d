"""The one register map (``nuc_fixed/registers.rdl``) and its readers agree.

References independent of :mod:`irnuc.nuc_fixed.regmap`'s reading: the IP-XACT description
``hdl/irnuc_regs.xml`` (peakrdl-ipxact's walk of the compiled map, parsed here as XML)
against the constants of ``hdl/irnuc_pkg.sv`` (parsed from the SystemVerilog text), the
tables of ``docs/registers.md`` (parsed from the Markdown) and the Python register model;
the map elaborated by systemrdl-compiler with a configuration's values (its parameter
substitution) against the model's reset values (its name lookup). The model's access rules
are checked on hand-made writes (W1C, byte strobes, SLVERR, reserved registers). The RTL
itself is checked against the model in ``cocotb_tests/tb_axis.py``.
"""

from __future__ import annotations

import json
import re
import xml.etree.ElementTree as ET
from pathlib import Path

import pytest

from irnuc.common.errors import ConfigError
from irnuc.nuc_fixed import load_pipeline, regmap

ROOT = Path(__file__).resolve().parents[1]
PKG = (ROOT / "hdl" / "irnuc_pkg.sv").read_text()
DOC = (ROOT / "docs" / "registers.md").read_text()
NS = {"ipxact": "http://www.accellera.org/XMLSchema/IPXACT/1685-2014"}
ACCESS = {"read-only": "ro", "read-write": "rw", "write-only": "w1s"}


def _camel(name: str) -> str:
    return "".join(p.capitalize() for p in name.lower().split("_"))


def _num(text: str) -> int:
    return int(text.replace("'h", "0x"), 0)


def _ipxact() -> dict[str, dict]:
    """Register path -> {offset, fields: {name: (lsb, bits, access, reset, write action)}}
    from the IP-XACT file (register files and arrays unrolled)."""
    block = ET.parse(ROOT / "hdl" / "irnuc_regs.xml").find(
        ".//ipxact:addressBlock", NS)
    out: dict[str, dict] = {}

    def reg(el: ET.Element, prefix: str, base: int) -> None:
        name = el.findtext("ipxact:name", namespaces=NS)
        off = base + _num(el.findtext("ipxact:addressOffset", namespaces=NS))
        # IEEE 1685-2014: a register array's dimension; its elements are `size` bits apart
        dims = [int(d.text) for d in el.findall("ipxact:dim", NS)]
        stride = int(el.findtext("ipxact:size", namespaces=NS)) // 8
        fields = {}
        for f in el.findall("ipxact:field", NS):
            reset = f.findtext("ipxact:resets/ipxact:reset/ipxact:value", namespaces=NS)
            fields[f.findtext("ipxact:name", namespaces=NS)] = (
                int(f.findtext("ipxact:bitOffset", namespaces=NS)),
                int(f.findtext("ipxact:bitWidth", namespaces=NS)),
                f.findtext("ipxact:access", namespaces=NS),
                None if reset is None else _num(reset),
                f.findtext("ipxact:modifiedWriteValue", namespaces=NS))
        if dims:
            for k in range(dims[0]):
                out[f"{prefix}{name}[{k}]"] = {"offset": off + k * stride,
                                               "fields": fields}
        else:
            out[f"{prefix}{name}"] = {"offset": off, "fields": fields}

    for el in block:
        tag = el.tag.split("}")[1]
        if tag == "register":
            reg(el, "", 0)
        elif tag == "registerFile":
            base = _num(el.findtext("ipxact:addressOffset", namespaces=NS))
            for r in el.findall("ipxact:register", NS):
                reg(r, el.findtext("ipxact:name", namespaces=NS) + ".", base)
    return out


IPXACT = _ipxact()


def _pkg_constants() -> dict[str, int]:
    return {m[1]: int(m[2]) for m in re.finditer(
        r"localparam int unsigned (Reg\w+) = (\d+);", PKG)}


def test_model_is_the_ipxact() -> None:
    """Every register and field of the model at the offset, position, width and access of
    the IP-XACT; the reset values of the default build (typical14's parameters)."""
    rmap = regmap.register_map()
    assert [r.name for r in rmap.registers] == sorted(IPXACT, key=lambda n: IPXACT[n]["offset"])
    for r in rmap.registers:
        x = IPXACT[r.name]
        assert r.offset == x["offset"], r.name
        assert [f.name for f in r.fields] == list(x["fields"]), r.name
        for f in r.fields:
            lsb, bits, access, reset, action = x["fields"][f.name]
            want = "w1c" if action == "oneToClear" else ACCESS[access]
            assert (f.lsb, f.bits, f.access) == (lsb, bits, want), (r.name, f.name)
            default = rmap.params[f.reset] if isinstance(f.reset, str) else f.reset
            assert default == (reset or 0), (r.name, f.name)


def test_package_constants_are_the_ipxact() -> None:
    sv = _pkg_constants()
    assert sv["RegMapId"] == IPXACT["ID"]["fields"]["value"][3] == int.from_bytes(b"IRNC", "big")
    assert (sv["RegMapMajor"], sv["RegMapMinor"]) == (IPXACT["VERSION"]["fields"]["major"][3],
                                                      IPXACT["VERSION"]["fields"]["minor"][3])
    assert sv["RegAddrBits"] == 12
    checked = 0
    for name, x in IPXACT.items():
        if "[" in name:
            k = int(name.split("[")[1].rstrip("]"))
            group = _camel(name.split("[")[0])
            assert sv[f"Reg{group}Offset"] + k * sv[f"Reg{group}Stride"] == x["offset"]
            assert k < sv[f"Reg{group}Count"]
            continue
        if "." in name:
            group, word = name.split(".")
            assert sv[f"Reg{_camel(group)}{word.title()}Offset"] == x["offset"], name
            continue
        assert sv[f"Reg{_camel(name)}Offset"] == x["offset"], name
        for fname, (lsb, bits, *_rest) in x["fields"].items():
            key = f"Reg{_camel(name)}{_camel(fname)}"
            assert sv[f"{key}Lsb"] == lsb, key
            if bits > 1:
                assert sv[f"{key}Bits"] == bits, key
            checked += 1
    assert checked >= 40  # every field of the plain registers
    assert sv["RegSlotCount"] == sum(1 for n in IPXACT if n.endswith(".LO"))


def test_docs_tables_are_the_ipxact() -> None:
    rows = dict(re.findall(r"^\| (0x[0-9a-f]{3})[^|]* \| `([\w.\[]+)", DOC, re.M))
    for name, x in IPXACT.items():
        if "." in name or "[" in name:
            if name.endswith((".LO", "[0]")):
                assert rows[f"0x{x['offset']:03x}"].startswith(re.split(r"[.\[]", name)[0])
            continue
        assert rows.get(f"0x{x['offset']:03x}") == name, name
        section = DOC.split(f"## `{name}` (0x{x['offset']:03x})", 1)[1].split("\n## ")[0]
        for fname, (lsb, bits, access, _reset, action) in x["fields"].items():
            hi = lsb + bits - 1
            field_bits = str(lsb) if bits == 1 else f"{hi}:{lsb}"
            kind = {"read-only": "RO", "read-write": "W1C" if action else "RW",
                    "write-only": "W1S"}[access]
            assert re.search(rf"^\| {field_bits} \| `{fname}` \| {kind}", section, re.M), (
                name, fname)


@pytest.mark.parametrize("config", ["typical14", "minimal", "tcffc14", "table14"])
def test_model_resets_are_the_elaborated_map(config: str) -> None:
    """After reset every present register reads the reset values systemrdl-compiler gives
    the map elaborated with the configuration's parameters; absent ones read 0."""
    cfg = load_pipeline(config)
    m = regmap.RegisterModel(cfg)
    top = regmap.elaborate_for(cfg).top
    seen = 0
    for node in top.descendants(unroll=True):
        if node.__class__.__name__ != "RegNode":
            continue
        name = node.get_path().removeprefix(top.inst_name + ".")
        want = 0
        for f in node.fields():
            if f.is_sw_readable:
                want |= (f.get_property("reset") or 0) << f.low
        off = node.absolute_address
        resp, data = m.read(off)
        if not m.map[name].readable:
            assert (resp, data) == (regmap.SLVERR, 0), name
            continue
        assert resp == regmap.OKAY, name
        assert data == (want if m.present(name) else 0) & m.field_mask(name), (name, hex(data))
        seen += m.present(name)
    assert seen >= 19  # the 19 readable registers every build has, at least
    config_reg = m.read(m.map["CONFIG"].offset)[1]
    assert config_reg & 0xFF == cfg.adc_bits and (config_reg >> 8) & 0xFF == cfg.out_bits
    assert m.read(m.map["FRAME_MAX"].offset)[1] == cfg.max_width | (cfg.max_height << 16)


def test_model_access_rules_by_hand() -> None:
    cfg = load_pipeline("minimal")
    m = regmap.RegisterModel(cfg)
    ctrl, size = m.map["CTRL"].offset, m.map["FRAME_SIZE"].offset
    # CTRL: nuc_en (bit 0), dpc_en (1), coef_sync (8) reset 1; other bits read 0.
    assert m.read(ctrl) == (regmap.OKAY, 0x103)
    assert m.write(ctrl, 0xFFFF_FEFE) == regmap.OKAY and m.read(ctrl) == (regmap.OKAY, 0x002)
    assert m.pending
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
    # COMMAND is write only: a read is SLVERR; clear_counters clears every counter.
    m.set_live("FRAMES_IN", "count", 7)
    m.set_live("SOF_ERRORS", "late", 3)
    assert m.read(m.map["COMMAND"].offset) == (regmap.SLVERR, 0)
    assert m.write(m.map["COMMAND"].offset, 1) == regmap.OKAY
    assert m.get("FRAMES_IN") == 0 and m.get("SOF_ERRORS") == 0
    assert m.commands == [("COMMAND", "clear_counters")]
    # W1C: an event sets STATUS.eol_late (bit 3); writing 0 keeps it, writing 1 clears it.
    status = m.map["STATUS"].offset
    m.set_live("STATUS", "eol_late", 1)
    assert m.write(status, 0) == regmap.OKAY and m.read(status)[1] & 0x8
    assert m.write(status, 0x8) == regmap.OKAY and not m.read(status)[1] & 0x8
    # A method register the two-point core does not have: reserved, reads 0, OKAY.
    gain = m.map["GAIN.LO"]
    assert not m.present(gain)
    assert m.write(gain.offset, 0x1234) == regmap.OKAY and m.read(gain.offset) == (regmap.OKAY, 0)
    # A read-only register of a stage that is not built: reads 0, a write is SLVERR (the
    # response is its access type's on every build).
    ffc_status = m.map["FFC_STATUS"]
    assert not m.present(ffc_status)
    assert m.read(ffc_status.offset) == (regmap.OKAY, 0)
    assert m.write(ffc_status.offset, 1) == regmap.SLVERR


def test_model_method_register_widths() -> None:
    """A 64-bit slot reads back the configured width only, LO and HI; table entries past
    the configured tables are reserved."""
    cfg = load_pipeline("table14")
    m = regmap.RegisterModel(cfg)
    width = cfg.registers["reading"].width
    lo, hi = m.map["READING.LO"], m.map["READING.HI"]
    assert m.write(lo.offset, 0xFFFF_FFFF) == m.write(hi.offset, 0xFFFF_FFFF) == regmap.OKAY
    assert m.read(lo.offset)[1] == (1 << min(width, 32)) - 1
    assert m.read(hi.offset)[1] == (1 << max(width - 32, 0)) - 1
    tables = cfg.registers["table_readings"].count
    last = m.map[f"TABLE_READING[{tables}]"]
    assert not m.present(last) and m.write(last.offset, 5) == regmap.OKAY
    assert m.read(last.offset) == (regmap.OKAY, 0)
    assert m.present(f"TABLE_READING[{tables - 1}]")


def test_reset_must_be_a_number_or_a_parameter(tmp_path, monkeypatch) -> None:
    """A reset that is an expression of the map's parameters is refused with the field's
    path (the model could not name it); the shipped map has none."""
    text = regmap.REGISTERS_RDL.read_text()
    bad = text.replace("width[15:0] = MaxWidth;", "width[15:0] = MaxWidth - 1;", 1)
    assert bad != text
    path = tmp_path / "registers.rdl"
    path.write_text(bad)
    monkeypatch.setattr(regmap, "REGISTERS_RDL", path)
    regmap._compiled.cache_clear()
    try:
        with pytest.raises(ConfigError, match=r"FRAME_MAX\.width is an expression"):
            regmap._extract()
    finally:
        regmap._compiled.cache_clear()


def test_cache_holds_the_extracted_map(tmp_path, monkeypatch) -> None:
    """register_map() reads the plain map from the irnuc cache once it is there; a damaged
    entry is read from the file again."""
    monkeypatch.setenv("IRNUC_CACHE_DIR", str(tmp_path))
    regmap.register_map.cache_clear()
    try:
        fresh = regmap.register_map()
        entries = list((tmp_path / "regmap").glob("*.json"))
        assert len(entries) == 1
        data = json.loads(entries[0].read_text())
        assert data["map_id"] == fresh.map_id and len(data["registers"]) == len(fresh.registers)
        regmap.register_map.cache_clear()
        assert regmap.register_map() == fresh
        entries[0].write_text("{not json")
        regmap.register_map.cache_clear()
        assert regmap.register_map() == fresh
        assert json.loads(entries[0].read_text())["map_id"] == fresh.map_id
    finally:
        regmap.register_map.cache_clear()


def test_regmap_command_writes_one_build(tmp_path, capsys) -> None:
    """``irnuc regmap --pipeline tcffc14``: the build's reset values in the header and the
    IP-XACT (CONFIG.method 4, FFC_CTRL.frames N), its reserved registers marked in the
    tables; an unknown pipeline is one line naming the flag, exit 2, nothing written."""
    from irnuc.cli import main

    cfg = load_pipeline("tcffc14")
    out = tmp_path / "regmap"
    assert main(["regmap", "--pipeline", "tcffc14", "--out", str(out)]) == 0
    header = (out / "irnuc_regs.h").read_text()
    assert re.search(r"IRNUC_REGS__CONFIG__METHOD_reset 0x4\b", header)
    assert re.search(rf"IRNUC_REGS__FFC_CTRL__FRAMES_reset {cfg.ffc_frames:#x}\b", header)
    xml = ET.parse(out / "irnuc_regs.xml")
    ffc_ctrl = next(r for r in xml.iter(f"{{{NS['ipxact']}}}register")
                if r.findtext("ipxact:name", namespaces=NS) == "FFC_CTRL")
    resets = [_num(v.text) for v in ffc_ctrl.iter(f"{{{NS['ipxact']}}}value")]
    assert cfg.ffc_frames in resets
    md = (out / "registers.md").read_text()
    assert "built for pipeline `tcffc14`" in md
    assert re.search(r"`GAIN\.LO, \.HI` \| one_point \(reserved\)", md)
    assert not re.search(r"`T_REF\.LO, \.HI` \| tc_offset \(reserved\)", md)
    assert main(["regmap", "--pipeline", "nope", "--out", str(tmp_path / "bad")]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "--pipeline nope" in err[0]
    assert not (tmp_path / "bad").exists()
