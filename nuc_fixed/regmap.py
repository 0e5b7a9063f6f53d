"""The AXI4-Lite register map of ``irnuc_axis_top`` and its golden model.

The map is written once, in ``nuc_fixed/registers.toml``; this module reads it
(schema-checked, :func:`register_map`) and is the register file's golden model
(:class:`RegisterModel`, mirroring ``hdl/irnuc_axil_regs.sv``): the testbenches take every
address, field, reset value and response code from it. The shared-constants spec
(:mod:`irnuc.nuc_fixed.rtl_spec`) turns the map into constants of ``hdl/irnuc_pkg.sv``
(:func:`sv_constants`) and ``python -m irnuc.cosim.spec_files --write`` into
``docs/registers.md`` (:func:`markdown`).

Responses (docs/registers.md): an offset outside the map is answered SLVERR (read data
0); so is a write to a register without a writable field and a frame size of 0 or above
``FRAME_MAX``. A register of a method or stage that is not configured reads 0 and ignores
writes, answered OKAY. The slave never answers DECERR (that is the interconnect's answer
for an address outside every slave's window) nor EXOKAY (no exclusive access in AXI4-Lite).
"""

from __future__ import annotations

import re
from dataclasses import dataclass, field
from functools import cache
from pathlib import Path
from typing import TYPE_CHECKING, Any

from irnuc.common import schema
from irnuc.common.errors import ConfigError

if TYPE_CHECKING:  # config imports rtl_spec, which reads this map: no import cycle at run time
    from irnuc.nuc_fixed.config import PipelineConfig

REGISTERS_TOML = Path(__file__).with_name("registers.toml")

#: AXI response codes (BRESP / RRESP).
OKAY, EXOKAY, SLVERR, DECERR = 0, 1, 2, 3
RESP_NAMES = {OKAY: "OKAY", EXOKAY: "EXOKAY", SLVERR: "SLVERR", DECERR: "DECERR"}
ACCESS = ("ro", "rw", "w1c", "w1s")
#: Names a reset value may take: values of the configuration (:meth:`RegisterModel.params`).
PARAMS = ("AdcBits", "OutBits", "WordBits", "MethodCode", "HasBlindDrift", "HasFfc",
          "Rounding", "Overflow", "MaxWidth", "MaxHeight", "GainIntBits", "GainFracBits",
          "OffsetIntBits", "OffsetFracBits", "FfcFrames", "MapId", "MapMajor", "MapMinor",
          "CoefLayoutVersion")
#: A method register's slot (bits): NAME_LO and NAME_HI.
SLOT_BITS = 64
DATA_BITS = 32

_FIELD_SCHEMA = schema.table({
    "name": {"type": "string", "pattern": "^[a-z][a-z0-9_]*$"},
    "lsb": schema.number(0, 31, integer=True, unit="bit"),
    "bits": schema.number(1, 32, integer=True, unit="bits"),
    "access": {"enum": list(ACCESS)},
    "reset": {"anyOf": [schema.number(0, 2**32 - 1, integer=True), {"enum": list(PARAMS)}]},
    "live": {"type": "boolean"},
    "doc": {"type": "string", "minLength": 1},
}, required=["name", "lsb", "bits", "access", "reset", "doc"])
_REG_SCHEMA = schema.table({
    "name": {"type": "string", "pattern": "^[A-Z][A-Z0-9_]*$"},
    "offset": schema.number(0, 4095, integer=True, unit="bytes"),
    "doc": {"type": "string", "minLength": 1},
    "shadowed": {"type": "boolean"},
    "requires": {"type": "array", "items": {"type": "string"}, "minItems": 1},
    "config_register": {"type": "string"},
    "count": schema.number(1, 64, integer=True),
    "stride": schema.number(4, 256, integer=True, unit="bytes"),
    "fields": {"type": "array", "items": _FIELD_SCHEMA, "minItems": 1},
}, required=["name", "offset", "doc"])
MAP_SCHEMA = schema.table({
    "map_id": schema.number(0, 2**32 - 1, integer=True),
    "major": schema.number(0, 255, integer=True),
    "minor": schema.number(0, 255, integer=True),
    "address_bits": schema.number(3, 32, integer=True, unit="bits"),
    "register": {"type": "array", "items": _REG_SCHEMA, "minItems": 1},
}, required=["map_id", "major", "minor", "address_bits", "register"])


@dataclass(frozen=True)
class RegField:
    """One field of a 32-bit register: bits ``[lsb + bits - 1 : lsb]``."""

    name: str
    lsb: int
    bits: int
    access: str
    reset: int | str  # a number or a name in PARAMS
    doc: str
    live: bool = False

    @property
    def mask(self) -> int:
        return ((1 << self.bits) - 1) << self.lsb


@dataclass(frozen=True)
class Register:
    """One 32-bit register of the map (arrays and 64-bit slots already expanded).

    ``group`` is the entry of ``registers.toml`` it comes from (``GAIN`` for ``GAIN_LO``),
    ``config_register``/``word``/``index`` bind it to a global register of the method
    (word ``lo``/``hi`` of a 64-bit slot, or entry ``index`` of an array).
    """

    name: str
    offset: int
    doc: str
    fields: tuple[RegField, ...]
    group: str
    shadowed: bool = False
    requires: tuple[str, ...] = ()
    config_register: str | None = None
    word: str | None = None
    index: int | None = None

    def field(self, name: str) -> RegField:
        for f in self.fields:
            if f.name == name:
                return f
        raise KeyError(f"register {self.name} has no field {name!r}")

    @property
    def writable(self) -> bool:
        return any(f.access != "ro" for f in self.fields)


@dataclass(frozen=True)
class RegisterMap:
    """The whole map: identification, version and the registers by offset."""

    map_id: int
    major: int
    minor: int
    address_bits: int
    registers: tuple[Register, ...]
    groups: tuple[dict[str, Any], ...] = field(default=(), compare=False, repr=False)

    def __getitem__(self, name: str) -> Register:
        for r in self.registers:
            if r.name == name:
                return r
        from irnuc.common.schema import nearest

        raise KeyError(f"no register {name!r}{nearest(name, [r.name for r in self.registers])}")

    def at(self, offset: int) -> Register | None:
        """The register at byte ``offset`` (any byte of its word), or None."""
        word = int(offset) & ~3
        for r in self.registers:
            if r.offset == word:
                return r
        return None

    @property
    def size(self) -> int:
        """Bytes of the address window."""
        return 1 << self.address_bits


def _methods() -> tuple[str, ...]:
    from irnuc.nuc_fixed import methods

    return tuple(methods.BASES)


def check_requires(rmap: RegisterMap) -> None:
    """Every ``requires`` names a base method, a stage or a reading (checked when a model is
    made: the configuration module reads the map through ``rtl_spec`` while it is being
    imported)."""
    from irnuc.nuc_fixed import methods

    known = set(_methods()) | set(methods.STAGES) | set(methods.READINGS)
    for r in rmap.registers:
        if set(r.requires) - known:
            raise ConfigError(f"register {r.name}: requires "
                              f"{sorted(set(r.requires) - known)[0]!r} is not a method, "
                              "reading or "
                              f"stage ({', '.join(sorted(known))})")


def _camel(name: str) -> str:
    return "".join(w.title() for w in re.split(r"_", name.lower()) if w)


def _load(path: Path) -> RegisterMap:
    data = schema.read_toml(path)
    schema.check(data, MAP_SCHEMA, source=str(path))
    regs: list[Register] = []
    for g in data["register"]:
        src = f"{path}: register {g['name']}"
        reqs = tuple(g.get("requires", ()))
        common = {"group": g["name"], "doc": g["doc"], "shadowed": bool(g.get("shadowed")),
                  "requires": reqs}
        cr = g.get("config_register")
        if cr is None:
            if "fields" not in g or "count" in g:
                raise ConfigError(f"{src}: a register without config_register needs fields "
                                  "and no count")
            fields = tuple(RegField(**f) for f in g["fields"])
            regs.append(Register(g["name"], g["offset"], fields=fields, **common))
            continue
        if "fields" in g:
            raise ConfigError(f"{src}: a config_register register has the field `value`; "
                              "give no fields")
        value = RegField("value", 0, DATA_BITS, "rw", 0, "the register's value, "
                         "least significant bits first; bits above its width read 0")
        if "count" in g:
            stride = int(g.get("stride", 4))
            for k in range(int(g["count"])):
                regs.append(Register(f"{g['name']}_{k}", g["offset"] + k * stride,
                                     fields=(value,), config_register=cr, index=k, **common))
        else:
            for k, word in enumerate(("lo", "hi")):
                regs.append(Register(f"{g['name']}_{word.upper()}", g["offset"] + 4 * k,
                                     fields=(value,), config_register=cr, word=word, **common))
    rmap = RegisterMap(data["map_id"], data["major"], data["minor"], data["address_bits"],
                       tuple(sorted(regs, key=lambda r: r.offset)), tuple(data["register"]))
    _check_map(rmap, path)
    return rmap


def _check_map(rmap: RegisterMap, path: Path) -> None:
    seen: dict[int, str] = {}
    for r in rmap.registers:
        if r.offset % 4 or r.offset >= rmap.size:
            raise ConfigError(f"{path}: register {r.name} at 0x{r.offset:03x} is not a word "
                              f"inside the {rmap.size}-byte window")
        if r.offset in seen:
            raise ConfigError(f"{path}: registers {seen[r.offset]} and {r.name} share offset "
                              f"0x{r.offset:03x}")
        seen[r.offset] = r.name
        used = 0
        for f in r.fields:
            if f.lsb + f.bits > DATA_BITS:
                raise ConfigError(f"{path}: {r.name}.{f.name} ends past bit 31")
            if used & f.mask:
                raise ConfigError(f"{path}: {r.name}.{f.name} overlaps another field")
            used |= f.mask
            if isinstance(f.reset, int) and f.reset >> f.bits:
                raise ConfigError(f"{path}: {r.name}.{f.name} reset {f.reset} does not fit "
                                  f"{f.bits} bits")


@cache
def register_map(path: Path = REGISTERS_TOML) -> RegisterMap:
    """The register map (``nuc_fixed/registers.toml``), checked."""
    return _load(Path(path))


# ---- the register file's golden model ----------------------------------------------------

def coef_layout_version(cfg: PipelineConfig) -> int:
    """The coefficient word layout version: the memory image version ``irnuc calibrate``
    writes for the method (1: two_point, 2: every other method)."""
    from irnuc.nuc_fixed.memimage import MEMIMAGE_VERSION, METHOD_IMAGE_VERSION

    return MEMIMAGE_VERSION if cfg.plain else METHOD_IMAGE_VERSION


def _coef_word_bits(cfg: PipelineConfig) -> int:
    """Bits of one s_axis_coef word: the method's coefficient word (table_interp: the
    pair of tables j and j + 1)."""
    from irnuc.nuc_fixed.axis import coef_word_bits

    return coef_word_bits(cfg)


def config_params(cfg: PipelineConfig, rmap: RegisterMap | None = None) -> dict[str, int]:
    """The values a reset may name (:data:`PARAMS`) for configuration ``cfg``."""
    rmap = rmap or register_map()
    p = cfg.rtl_parameters()
    return {**{k: p[k] for k in ("AdcBits", "OutBits", "Rounding", "Overflow", "MaxWidth",
                                 "MaxHeight", "GainIntBits", "GainFracBits", "OffsetIntBits",
                                 "OffsetFracBits")},
            "WordBits": _coef_word_bits(cfg), "MethodCode": _methods().index(cfg.base_method),
            "HasBlindDrift": int(cfg.has("blind_drift")), "HasFfc": int(cfg.has("ffc")),
            "FfcFrames": int(cfg.ffc_frames or 0), "MapId": rmap.map_id,
            "MapMajor": rmap.major, "MapMinor": rmap.minor,
            "CoefLayoutVersion": coef_layout_version(cfg)}


class RegisterModel:
    """The register file of ``irnuc_axil_regs`` for one configuration, as a model.

    It holds what software wrote (the pending values of shadowed registers, the enables,
    the interrupt enables) and answers reads and writes as the RTL does: response code and
    read data. Live fields (status bits, counters) hold what :meth:`set_live` last gave
    them (their reset values until then); ``pending`` (STATUS) follows the writes and
    :meth:`frame_start`.
    """

    def __init__(self, cfg: PipelineConfig, rmap: RegisterMap | None = None) -> None:
        self.cfg = cfg
        self.map = rmap or register_map()
        check_requires(self.map)
        self.params = config_params(cfg, self.map)
        self.commands: list[tuple[str, str]] = []  # (register, field) of every w1s written
        self.reset()

    # ---- what the configuration has ------------------------------------------------------
    def present(self, reg: Register | str) -> bool:
        """Whether the configured method has the register (else it is reserved): its
        ``requires`` names the base method, a stage or a reading one of them takes."""
        r = self.map[reg] if isinstance(reg, str) else reg
        has = {self.cfg.base_method, *self.cfg.stages,
               *(x for part in self.cfg.parts for x in part.readings)}
        if r.requires and not (has & set(r.requires)):
            return False
        if r.config_register is not None:
            cr = self.cfg.registers.get(r.config_register)
            if cr is None:
                return False
            if r.index is not None and r.index >= cr.count:
                return False
        return True

    def value_bits(self, reg: Register | str) -> int:
        """Bits of the register's value that exist (a method register narrower than its
        slot reads 0 above its width; every other register: its fields)."""
        r = self.map[reg] if isinstance(reg, str) else reg
        if not self.present(r):
            return 0
        if r.config_register is None:
            return DATA_BITS
        width = self.cfg.registers[r.config_register].width
        if width > (DATA_BITS if r.index is not None else SLOT_BITS):
            raise ConfigError(f"pipeline {self.cfg.name!r}: register {r.config_register} of "
                              f"{width} bits does not fit its {r.group} slot")
        if r.word == "hi":
            return max(0, width - DATA_BITS)
        return min(width, DATA_BITS)

    def field_mask(self, reg: Register | str, access: tuple[str, ...] = ACCESS) -> int:
        """The bits of fields with the given access kinds that exist in this configuration."""
        r = self.map[reg] if isinstance(reg, str) else reg
        if not self.present(r):
            return 0
        m = sum(f.mask for f in r.fields if f.access in access)
        return m & ((1 << self.value_bits(r)) - 1)

    def field_reset(self, f: RegField) -> int:
        return self.params[f.reset] if isinstance(f.reset, str) else int(f.reset)

    def reset_value(self, reg: Register | str) -> int:
        """What the register reads right after reset (0 when reserved)."""
        r = self.map[reg] if isinstance(reg, str) else reg
        if not self.present(r):
            return 0
        v = 0
        for f in r.fields:
            if f.access != "w1s":
                v |= (self.field_reset(f) << f.lsb) & f.mask
        return v & self.field_mask(r)

    # ---- state ---------------------------------------------------------------------------
    def reset(self) -> None:
        """The state after ``rst_ni``."""
        self.values = {r.name: self.reset_value(r) for r in self.map.registers}
        self.pending = False

    def set_live(self, reg: str, field_name: str, value: int) -> None:
        """Set a live (hardware-driven) field to what the hardware is known to hold."""
        r = self.map[reg]
        f = r.field(field_name)
        if not f.live:
            raise ValueError(f"{reg}.{field_name} is not a live field")
        self.values[reg] = (self.values[reg] & ~f.mask) | ((int(value) << f.lsb) & f.mask)

    def get(self, reg: str, field_name: str | None = None) -> int:
        """The value the model holds (a field of it)."""
        v = self._read_value(self.map[reg])
        if field_name is None:
            return v
        f = self.map[reg].field(field_name)
        return (v & f.mask) >> f.lsb

    def frame_start(self) -> None:
        """A frame started: the shadowed registers took effect."""
        self.pending = False

    def _read_value(self, r: Register) -> int:
        v = self.values[r.name] & self.field_mask(r, ("ro", "rw", "w1c"))
        if r.name == "STATUS":
            f = r.field("pending")
            v = (v & ~f.mask) | (int(self.pending) << f.lsb)
        return v

    # ---- the bus -------------------------------------------------------------------------
    def read(self, offset: int) -> tuple[int, int]:
        """(response, data) of a read at byte ``offset``."""
        r = self.map.at(offset)
        if r is None or offset >= self.map.size:
            return SLVERR, 0
        if not self.present(r):
            return OKAY, 0
        return OKAY, self._read_value(r)

    def write(self, offset: int, data: int, strb: int = 0xF) -> int:
        """The response of a write at byte ``offset`` with byte enables ``strb``; the
        model's state follows (commands are appended to :attr:`commands`)."""
        r = self.map.at(offset)
        if r is None or offset >= self.map.size:
            return SLVERR
        if not self.present(r):
            return OKAY
        if not r.writable:
            return SLVERR
        bytes_ = sum(0xFF << (8 * i) for i in range(4) if strb >> i & 1)
        data &= bytes_
        old = self.values[r.name]
        rw = self.field_mask(r, ("rw",)) & bytes_
        new = (old & ~rw) | (data & rw)
        if r.name == "FRAME_SIZE":
            w = (new & r.field("width").mask) >> r.field("width").lsb
            h = (new & r.field("height").mask) >> r.field("height").lsb
            if not (1 <= w <= self.cfg.max_width and 1 <= h <= self.cfg.max_height):
                return SLVERR
        new &= ~(data & self.field_mask(r, ("w1c",)))
        self.values[r.name] = new
        for f in r.fields:
            if f.access == "w1s" and data & f.mask & self.field_mask(r):
                self.commands.append((r.name, f.name))
                if (r.name, f.name) == ("COMMAND", "clear_counters"):
                    self._clear_counters()
        if r.shadowed and rw:
            self.pending = True
        return OKAY

    def _clear_counters(self) -> None:
        for name in COUNTERS:
            self.values[name] = 0

    def reserved_offsets(self) -> list[int]:
        """Word offsets of the window that hold no register (answered SLVERR)."""
        used = {r.offset for r in self.map.registers}
        return [o for o in range(0, self.map.size, 4) if o not in used]


#: The counter registers (cleared by COMMAND.clear_counters).
COUNTERS = ("FRAMES_IN", "FRAMES_OUT", "PIXELS_IN", "PIXELS_OUT", "DROPPED", "PADDED",
            "SOF_ERRORS", "EOL_ERRORS", "COEF_ERRORS")


# ---- generated text ------------------------------------------------------------------------

def sv_constants(rmap: RegisterMap | None = None) -> list[tuple[str, int, str]]:
    """(name, value, doc) of every constant the map puts in ``irnuc_pkg``: the map's
    identity, each register's offset (an array's first offset, stride and count) and each
    field's lsb, width and numeric reset."""
    rmap = rmap or register_map()
    out = [("RegMapId", rmap.map_id, "ID register value"),
           ("RegMapMajor", rmap.major, "register map major version"),
           ("RegMapMinor", rmap.minor, "register map minor version"),
           ("RegAddrBits", rmap.address_bits, "AXI4-Lite address bits of the register window")]
    for g in rmap.groups:
        name = _camel(g["name"])
        if "count" in g:
            out += [(f"Reg{name}Offset", g["offset"], f"{g['name']}_0: {g['doc']}"),
                    (f"Reg{name}Stride", int(g.get("stride", 4)), f"{g['name']}_k spacing"),
                    (f"Reg{name}Count", int(g["count"]), f"{g['name']}_k entries")]
            continue
        if "config_register" in g:
            out += [(f"Reg{name}LoOffset", g["offset"], f"{g['name']}_LO: {g['doc']}"),
                    (f"Reg{name}HiOffset", g["offset"] + 4, f"{g['name']}_HI")]
            continue
        out.append((f"Reg{name}Offset", g["offset"], f"{g['name']}: {g['doc']}"))
        for f in g["fields"]:
            fname = f"Reg{name}{_camel(f['name'])}"
            out.append((f"{fname}Lsb", f["lsb"], f"{g['name']}.{f['name']}"))
            if f["bits"] > 1:
                out.append((f"{fname}Bits", f["bits"], f"{g['name']}.{f['name']} width"))
            if isinstance(f["reset"], int) and f["access"] in ("rw", "w1c"):
                out.append((f"{fname}Reset", f["reset"], f"{g['name']}.{f['name']} reset"))
    return out


def _requires_text(name: str) -> str:
    """A ``requires`` entry for the page: a reading with the methods that take it."""
    from irnuc.nuc_fixed import methods

    if name not in methods.READINGS:
        return name
    takers = [m.name for m in methods.BASES.values() if name in m.readings]
    return f"reading {name} ({', '.join(takers)})"


def markdown(rmap: RegisterMap | None = None) -> str:
    """``docs/registers.md``: the register map as tables (generated; do not edit)."""
    rmap = rmap or register_map()
    lines = [
        "# Register map of `irnuc_axis_top` (AXI4-Lite)",
        "",
        "<!-- Generated from nuc_fixed/registers.toml by `python -m irnuc.cosim.spec_files "
        "--write`; do not edit. -->",
        "",
        f"Map version {rmap.major}.{rmap.minor}, ID 0x{rmap.map_id:08x}. 32-bit registers at "
        f"byte offsets in a {rmap.size}-byte window ({rmap.address_bits} address bits; "
        "`s_axil_awaddr[1:0]`/`s_axil_araddr[1:0]` are ignored); `s_axil_wstrb` selects the "
        "bytes written; `s_axil_awprot`/`s_axil_arprot` are ignored.",
        "",
        "Access: **RO** read only, **RW** read and write, **W1C** written 1 clears the bit "
        "(an event in the same cycle wins), **W1S** written 1 acts once and reads 0. Bits "
        "outside the fields read 0 and ignore writes. *Shadowed*: a write takes effect at "
        "the next frame start (the first pixel of the next frame accepted on "
        "`s_axis_video`); the register reads back what was written at once, and "
        "`STATUS.pending` is 1 until then.",
        "",
        "Responses: **SLVERR** for an offset outside the table below (read data 0), for a "
        "write to a register without RW, W1C or W1S fields, and for a `FRAME_SIZE` of 0 "
        "or above `FRAME_MAX` (the register keeps its value). A register of a method or "
        "stage that is not configured (column *requires*) is reserved: it reads 0, ignores "
        "writes and answers **OKAY**. The slave never answers EXOKAY or DECERR (DECERR is "
        "the interconnect's answer for an address outside every slave).",
        "",
        "Reset values named after a configuration value (`MaxWidth`, `AdcBits`, ...) are "
        "those of the pipeline the core is built for (`nuc_fixed/pipelines.toml`).",
        "",
        "| offset | register | requires | shadowed | description |",
        "|---|---|---|---|---|",
    ]
    for g in rmap.groups:
        off = f"0x{g['offset']:03x}"
        name = g["name"]
        if "count" in g:
            last = g["offset"] + (int(g["count"]) - 1) * int(g.get("stride", 4))
            off = f"0x{g['offset']:03x}..0x{last:03x}"
            name = f"{g['name']}_0 .. _{int(g['count']) - 1}"
        elif "config_register" in g:
            off = f"0x{g['offset']:03x}, 0x{g['offset'] + 4:03x}"
            name = f"{g['name']}_LO, _HI"
        req = ", ".join(_requires_text(r) for r in g.get("requires", ())) or "-"
        lines.append(f"| {off} | `{name}` | {req} | {'yes' if g.get('shadowed') else '-'} | "
                     f"{g['doc']} |")
    lines.append("")
    for g in rmap.groups:
        lines += [f"## `{g['name']}` (0x{g['offset']:03x})", "", g["doc"] + ".", ""]
        if "config_register" in g:
            cr = g["config_register"]
            if "count" in g:
                lines.append(f"Entry k (k = 0 .. {int(g['count']) - 1}, at 0x{g['offset']:03x} "
                             f"+ {int(g.get('stride', 4))} k) holds value k of the method "
                             f"register `{cr}` (`PipelineConfig.registers`), in bits "
                             f"[width-1:0]; entries from the configured count on are reserved.")
            else:
                lines.append(f"The method register `{cr}` (`PipelineConfig.registers`): bits "
                             "[31:0] of its value in `_LO`, bits [63:32] in `_HI`; bits from "
                             "its configured width on read 0. Reset 0; RW.")
            lines.append("")
            continue
        lines += ["| bits | field | access | reset | description |", "|---|---|---|---|---|"]
        for f in g["fields"]:
            bits = (f"{f['lsb']}" if f["bits"] == 1 else f"{f['lsb'] + f['bits'] - 1}:{f['lsb']}")
            reset = f["reset"] if isinstance(f["reset"], str) else (
                f"0x{f['reset']:x}" if f["reset"] > 9 else str(f["reset"]))
            access = {"ro": "RO", "rw": "RW", "w1c": "W1C", "w1s": "W1S"}[f["access"]]
            live = " (hardware)" if f.get("live") else ""
            lines.append(f"| {bits} | `{f['name']}` | {access}{live} | {reset} | {f['doc']} |")
        lines.append("")
    return "\n".join(lines)


__all__ = ["ACCESS", "COUNTERS", "DECERR", "EXOKAY", "OKAY", "PARAMS", "REGISTERS_TOML",
           "RESP_NAMES", "SLVERR", "RegField", "Register", "RegisterMap", "RegisterModel",
           "config_params", "markdown", "register_map", "sv_constants"]
