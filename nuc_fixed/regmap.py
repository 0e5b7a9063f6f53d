"""The AXI4-Lite register map of ``irnuc_axis_top`` and its golden model.

The map is written once, in SystemRDL: ``nuc_fixed/registers.rdl``. This module reads it
through systemrdl-compiler (:func:`elaborate`: the map for a configuration, as the PeakRDL
exporters take it; :func:`register_map`: the same as plain data, kept in the irnuc cache by
the digest of the file) and is the register file's golden model (:class:`RegisterModel`,
mirroring ``hdl/irnuc_axil_regs.sv`` and the register block generated from the map): the
testbenches take every address, field, reset value and response code from it. The
shared-constants spec (:mod:`irnuc.nuc_fixed.rtl_spec`) turns the map into constants of
``hdl/irnuc_pkg.sv`` (:func:`sv_constants`), and ``python -m irnuc.cosim.spec_files
--write`` into ``docs/registers.md`` (:func:`markdown`) and the other generated files
(:mod:`irnuc.cosim.regfiles`).

What the SystemRDL says and how it is read (docs/registers.md, "How the map is made"):

* a field's access: ``sw = r`` RO; ``sw = rw`` RW; ``sw = rw`` with ``onwrite = woclr``
  W1C; ``sw = w`` with ``singlepulse`` W1S (reads 0);
* a field's reset: a number, or a parameter of the address map (a value of the pipeline
  configuration, :func:`config_params`); which parameter is found by elaborating the map
  once per parameter with that one changed (an expression of parameters is refused);
* a field is *live* (the hardware changes it: a status bit, a counter) when it is
  hardware-writable (``hw = w``, ``hwset``, ``counter``, ``intr``) and its reset is not a
  parameter (those are constants of the build, read from the wrapper's parameters);
* the user-defined properties ``irnuc_requires``, ``irnuc_shadowed`` and
  ``irnuc_config_register`` of a register (or of the register file it is in), and
  ``irnuc_address_bits`` of the map (its window).

Responses (docs/registers.md): an offset outside the map is answered SLVERR (read data 0);
so is a write to a register without a writable field, a read of a register without a
readable field and a frame size of 0 or above ``FRAME_MAX``. A register of a method or stage
that is not configured reads 0 and ignores writes, with the response of its access type.
The slave never answers DECERR (that is the interconnect's answer for an address outside
every slave's window) nor EXOKAY (no exclusive access in AXI4-Lite).
"""

from __future__ import annotations

import json
import re
from dataclasses import dataclass, field
from functools import cache
from pathlib import Path
from typing import TYPE_CHECKING, Any

from irnuc.common.errors import ConfigError

if TYPE_CHECKING:  # config imports rtl_spec, which reads this map: no import cycle at run time
    from systemrdl.node import AddrmapNode, FieldNode, RegNode, RootNode

    from irnuc.nuc_fixed.config import PipelineConfig

REGISTERS_RDL = Path(__file__).with_name("registers.rdl")
#: The address map's type name in the file.
TOP = "irnuc_regs"
#: Bumped when the plain data read from the file changes shape (the cache key has it).
_EXTRACT_VERSION = 1

#: AXI response codes (BRESP / RRESP).
OKAY, EXOKAY, SLVERR, DECERR = 0, 1, 2, 3
RESP_NAMES = {OKAY: "OKAY", EXOKAY: "EXOKAY", SLVERR: "SLVERR", DECERR: "DECERR"}
#: Field access kinds: read only, read and write, written 1 clears, written 1 acts.
ACCESS = ("ro", "rw", "w1c", "w1s")
#: A method register's slot (bits): NAME.LO and NAME.HI.
SLOT_BITS = 64
DATA_BITS = 32


@dataclass(frozen=True)
class RegField:
    """One field of a 32-bit register: bits ``[lsb + bits - 1 : lsb]``."""

    name: str
    lsb: int
    bits: int
    access: str
    reset: int | str  # a number or a parameter of the map (a configuration value)
    doc: str
    live: bool = False
    counter: bool = False  # counts hardware events (cleared by COMMAND.clear_counters)

    @property
    def mask(self) -> int:
        return ((1 << self.bits) - 1) << self.lsb


@dataclass(frozen=True)
class Register:
    """One 32-bit register of the map (register files and arrays unrolled).

    ``name`` is its path in the map (``CTRL``, ``GAIN.LO``, ``TABLE_READING[3]``);
    ``group`` the top-level entry it belongs to (``GAIN``, ``TABLE_READING``).
    ``config_register``/``word``/``index`` bind it to a global register of the method
    (word ``lo``/``hi`` of a 64-bit slot, or entry ``index`` of an array). ``external``:
    implemented by hand behind the register block's hardware interface.
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
    external: bool = False

    def field(self, name: str) -> RegField:
        for f in self.fields:
            if f.name == name:
                return f
        raise KeyError(f"register {self.name} has no field {name!r}")

    @property
    def writable(self) -> bool:
        return any(f.access != "ro" for f in self.fields)

    @property
    def readable(self) -> bool:
        return any(f.access != "w1s" for f in self.fields)


@dataclass(frozen=True)
class Group:
    """A top-level entry of the map: a register (``kind`` ``reg``), a 64-bit slot of a method
    register (``slot``: registers LO, HI) or an array of registers (``array``)."""

    name: str
    kind: str
    offset: int
    doc: str
    registers: tuple[str, ...]
    stride: int = 4


@dataclass(frozen=True)
class RegisterMap:
    """The whole map: identification, version, window and the registers by offset, with
    the parameters of the map (the configuration values resets may name) and their
    defaults."""

    map_id: int
    major: int
    minor: int
    address_bits: int
    registers: tuple[Register, ...]
    groups: tuple[Group, ...]
    params: dict[str, int] = field(default_factory=dict, compare=False)

    def __getitem__(self, name: str) -> Register:
        for r in self.registers:
            if r.name == name:
                return r
        from irnuc.common.schema import nearest

        raise KeyError(f"no register {name!r}{nearest(name, [r.name for r in self.registers])}")

    def group(self, name: str) -> Group:
        for g in self.groups:
            if g.name == name:
                return g
        raise KeyError(f"no register group {name!r}")

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

    @property
    def counters(self) -> tuple[str, ...]:
        """The counter registers (cleared by COMMAND.clear_counters), in map order."""
        return tuple(r.name for r in self.registers if all(f.counter for f in r.fields))


# ---- reading the SystemRDL -------------------------------------------------------------

def _compiler(udps: tuple[type, ...] = ()) -> Any:
    """A systemrdl-compiler with the map compiled (and the extra UDP classes an exporter
    wants registered first)."""
    from systemrdl import RDLCompileError, RDLCompiler

    rdlc = RDLCompiler()
    for udp in udps:
        rdlc.register_udp(udp)
    try:
        rdlc.compile_file(str(REGISTERS_RDL))
    except RDLCompileError as exc:
        raise ConfigError(f"{REGISTERS_RDL}: {exc}") from None
    return rdlc


@cache
def _compiled(udps: tuple[type, ...] = ()) -> Any:
    return _compiler(udps)


def elaborate(params: dict[str, int] | None = None, udps: tuple[type, ...] = ()
              ) -> RootNode:
    """The map elaborated with the given parameter values (the others at their defaults):
    the systemrdl-compiler root node the PeakRDL exporters take."""
    from systemrdl import RDLCompileError

    rdlc = _compiled(tuple(udps))
    try:
        return rdlc.elaborate(TOP, parameters=dict(params or {}))
    except RDLCompileError as exc:
        raise ConfigError(f"{REGISTERS_RDL}: {exc} (parameters {params})") from None


def elaborate_for(cfg: PipelineConfig, udps: tuple[type, ...] = ()) -> RootNode:
    """The map of configuration ``cfg``: every reset value that is a configuration value
    is that build's (the C header, the IP-XACT and the Markdown of ``irnuc regmap``)."""
    return elaborate(_rdl_params(cfg), udps)


def _rdl_params(cfg: PipelineConfig) -> dict[str, int]:
    known = register_map().params
    values = config_params(cfg)
    missing = sorted(set(known) - set(values))
    if missing:
        raise ConfigError(f"{REGISTERS_RDL}: parameter {missing[0]} is not a value of the "
                          f"configuration (config_params gives {', '.join(sorted(values))})")
    return {k: values[k] for k in known}


def _udp(node: Any, name: str) -> Any:
    """A UDP of a register, else of the register file around it (None when unset)."""
    while node is not None and node.__class__.__name__ in ("RegNode", "RegfileNode"):
        if name in node.list_properties(include_udp=True, include_native=False):
            value = node.get_property(name)
            if value is not None:
                return value
        node = node.parent
    return None


def _access(f: FieldNode, where: str) -> str:
    from systemrdl.rdltypes import AccessType, OnWriteType

    sw, onwrite = f.get_property("sw"), f.get_property("onwrite")
    if sw == AccessType.r:
        return "ro"
    if sw == AccessType.rw and onwrite is None:
        return "rw"
    if sw == AccessType.rw and onwrite == OnWriteType.woclr:
        return "w1c"
    if sw == AccessType.w and f.get_property("singlepulse"):
        return "w1s"
    raise ConfigError(f"{REGISTERS_RDL}: {where}: sw = {sw.name}, onwrite = "
                      f"{getattr(onwrite, 'name', None)} is none of the map's access kinds "
                      "(r; rw; rw + woclr; w + singlepulse)")


def _live(f: FieldNode) -> bool:
    from systemrdl.rdltypes import AccessType

    return (f.get_property("hw") in (AccessType.w, AccessType.rw, AccessType.w1)
            or bool(f.get_property("hwset")) or bool(f.get_property("counter"))
            or bool(f.get_property("intr")))


def _doc(node: Any) -> str:
    text = node.get_property("desc") or node.get_property("name") or ""
    return " ".join(str(text).split())


def _reg_name(reg: RegNode, top: AddrmapNode) -> str:
    return reg.get_path(hier_separator=".", array_suffix="[{index:d}]").removeprefix(
        top.inst_name + ".")


def _reset_names(top_default: AddrmapNode, params: dict[str, int]) -> dict[str, str]:
    """Field path -> the parameter its reset is, found by elaborating the map with each
    parameter changed alone (its lowest bit flipped: it fits wherever the default did)."""
    base = {f.get_path(): f.get_property("reset") for f in top_default.descendants()
            if f.__class__.__name__ == "FieldNode"}
    named: dict[str, str] = {}
    for p, value in params.items():
        other = elaborate({p: value ^ 1}).top
        for f in other.descendants():
            if f.__class__.__name__ != "FieldNode":
                continue
            path, reset = f.get_path(), f.get_property("reset")
            if reset == base[path]:
                continue
            if reset != value ^ 1 or base[path] != value or path in named:
                raise ConfigError(f"{REGISTERS_RDL}: the reset of {path} is an expression "
                                  "of the map's parameters; give a number or one parameter")
            named[path] = p
    return named


def _extract() -> dict[str, Any]:
    """The map as plain data (what the cache holds)."""
    root = elaborate()
    top = root.top
    params = {p.name: int(p.get_value()) for p in top.inst.parameters}
    named = _reset_names(top, params)
    registers: list[dict[str, Any]] = []
    groups: list[dict[str, Any]] = []
    for child in top.children():
        if child.__class__.__name__ == "SignalNode":  # no address (the counters' clear)
            continue
        kind = ("array" if child.is_array else
                "slot" if child.__class__.__name__ == "RegfileNode" else "reg")
        regs = list(child.unrolled()) if child.is_array else (
            list(child.registers()) if kind == "slot" else [child])
        names = [_reg_name(r, top) for r in regs]
        groups.append({"name": child.inst_name, "kind": kind,
                       "offset": child.raw_absolute_address, "doc": _doc(child),
                       "registers": names,
                       "stride": int(child.array_stride) if child.is_array else 4})
        for k, reg in enumerate(regs):
            where = f"register {names[k]}"
            if reg.get_property("regwidth") != DATA_BITS:
                raise ConfigError(f"{REGISTERS_RDL}: {where} is not {DATA_BITS} bits")
            fields = []
            for f in reg.fields():
                reset = f.get_property("reset")
                reset = named.get(f.get_path(), 0 if reset is None else int(reset))
                fields.append({
                    "name": f.inst_name, "lsb": f.low, "bits": f.width,
                    "access": _access(f, f"{names[k]}.{f.inst_name}"), "reset": reset,
                    "doc": _doc(f), "live": _live(f) and not isinstance(reset, str),
                    "counter": bool(f.get_property("counter"))})
            cr = _udp(reg, "irnuc_config_register")
            registers.append({
                "name": names[k], "offset": reg.absolute_address - top.absolute_address,
                "doc": _doc(reg) if kind != "slot" else f"{_doc(child)} ({_doc(reg)})",
                "fields": fields, "group": child.inst_name,
                "shadowed": bool(_udp(reg, "irnuc_shadowed")),
                "requires": list(_udp(reg, "irnuc_requires") or ()),
                "config_register": cr,
                "word": ("lo", "hi")[k] if cr is not None and kind == "slot" else None,
                "index": k if kind == "array" else None,
                "external": bool(reg.external)})
    ident = {f["name"]: f["reset"] for r in registers if r["name"] in ("ID", "VERSION")
             for f in r["fields"]}
    bits = top.get_property("irnuc_address_bits")
    return {"map_id": ident["value"], "major": ident["major"], "minor": ident["minor"],
            "address_bits": int(bits), "params": params,
            "registers": sorted(registers, key=lambda r: r["offset"]), "groups": groups}


def _from_data(data: dict[str, Any]) -> RegisterMap:
    regs = tuple(Register(**{**r, "fields": tuple(RegField(**f) for f in r["fields"]),
                             "requires": tuple(r["requires"])}) for r in data["registers"])
    groups = tuple(Group(**{**g, "registers": tuple(g["registers"])}) for g in data["groups"])
    return RegisterMap(data["map_id"], data["major"], data["minor"], data["address_bits"],
                       regs, groups, dict(data["params"]))


def _cache_file() -> Path | None:
    """The cached plain map of this file and compiler (None without a writable cache)."""
    from importlib.metadata import version

    from irnuc.common.cache import cache_dir
    from irnuc.common.digest import digest

    key = digest({"rdl": REGISTERS_RDL.read_text(), "extract": _EXTRACT_VERSION,
                  "systemrdl": version("systemrdl-compiler")})
    try:
        return cache_dir("regmap") / f"{key}.json"
    except OSError:
        return None


@cache
def register_map() -> RegisterMap:
    """The register map (``nuc_fixed/registers.rdl``), checked; read through the cache."""
    from irnuc.common.io import write_text_atomic

    path = _cache_file()
    if path is not None and path.is_file():
        try:
            return _from_data(json.loads(path.read_text()))
        except (OSError, ValueError, TypeError, KeyError):
            pass  # a damaged entry: read the file again
    data = _extract()
    rmap = _from_data(data)
    _check_map(rmap)
    if path is not None:
        try:
            write_text_atomic(path, json.dumps(data, sort_keys=True))
        except OSError:
            pass  # an unwritable cache costs the next process a compile, nothing else
    return rmap


def _check_map(rmap: RegisterMap) -> None:
    seen: dict[int, str] = {}
    for r in rmap.registers:
        if r.offset % 4 or r.offset >= rmap.size:
            raise ConfigError(f"{REGISTERS_RDL}: register {r.name} at 0x{r.offset:03x} is not "
                              f"a word inside the {rmap.size}-byte window")
        if r.offset in seen:
            raise ConfigError(f"{REGISTERS_RDL}: registers {seen[r.offset]} and {r.name} share "
                              f"offset 0x{r.offset:03x}")
        seen[r.offset] = r.name
        if r.config_register is not None and [f.name for f in r.fields] != ["value"]:
            raise ConfigError(f"{REGISTERS_RDL}: register {r.name} holds a method register: "
                              "give it one field, `value`")


def check_requires(rmap: RegisterMap) -> None:
    """Every ``irnuc_requires`` names a base method, a stage or a reading (checked when a
    model is made: the configuration module reads the map through ``rtl_spec`` while it is
    being imported)."""
    from irnuc.nuc_fixed import methods

    known = set(methods.BASES) | set(methods.STAGES) | set(methods.READINGS)
    for r in rmap.registers:
        if set(r.requires) - known:
            raise ConfigError(f"{REGISTERS_RDL}: register {r.name}: irnuc_requires "
                              f"{sorted(set(r.requires) - known)[0]!r} is not a method, "
                              "reading or "
                              f"stage ({', '.join(sorted(known))})")


def _camel(name: str) -> str:
    return "".join(w.title() for w in re.split(r"_", name.lower()) if w)


# ---- the register file's golden model ----------------------------------------------------

def coef_layout_version(cfg: PipelineConfig) -> int:
    """The coefficient word layout version: the memory image version ``irnuc calibrate``
    writes for the method (1: two_point, 2: every other method)."""
    from irnuc.nuc_fixed.memimage import MEMIMAGE_VERSION, METHOD_IMAGE_VERSION

    return MEMIMAGE_VERSION if cfg.plain else METHOD_IMAGE_VERSION


def config_params(cfg: PipelineConfig) -> dict[str, int]:
    """The values of the map's parameters (the resets that are configuration values) for
    configuration ``cfg``: the RTL parameters of the same names."""
    from irnuc.nuc_fixed import methods
    from irnuc.nuc_fixed.axis import coef_word_bits

    p = cfg.rtl_parameters()
    return {**{k: p[k] for k in ("AdcBits", "OutBits", "Rounding", "Overflow", "MaxWidth",
                                 "MaxHeight", "GainIntBits", "GainFracBits", "OffsetIntBits",
                                 "OffsetFracBits")},
            "WordBits": coef_word_bits(cfg),
            "MethodCode": tuple(methods.BASES).index(cfg.base_method),
            "HasBlindDrift": int(cfg.has("blind_drift")), "HasFfc": int(cfg.has("ffc")),
            "FfcFrames": int(cfg.ffc_frames or 0),
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
        self.params = config_params(cfg)
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
        if r is None or offset >= self.map.size or not r.readable:
            return SLVERR, 0
        if not self.present(r):
            return OKAY, 0
        return OKAY, self._read_value(r)

    def write(self, offset: int, data: int, strb: int = 0xF) -> int:
        """The response of a write at byte ``offset`` with byte enables ``strb``; the
        model's state follows (commands are appended to :attr:`commands`)."""
        r = self.map.at(offset)
        if r is None or offset >= self.map.size or not r.writable:
            return SLVERR
        if not self.present(r):
            return OKAY
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
        for name in self.map.counters:
            self.values[name] = 0

    def reserved_offsets(self) -> list[int]:
        """Word offsets of the window that hold no register (answered SLVERR)."""
        used = {r.offset for r in self.map.registers}
        return [o for o in range(0, self.map.size, 4) if o not in used]


# ---- generated text ------------------------------------------------------------------------

def sv_constants(rmap: RegisterMap | None = None) -> list[tuple[str, int, str]]:
    """(name, value, doc) of every constant the map puts in ``irnuc_pkg``: the map's
    identity and window, each register's offset (a slot's LO and HI offsets; an array's
    first offset, stride and count) and each field's lsb, width and numeric reset."""
    rmap = rmap or register_map()
    out = [("RegMapId", rmap.map_id, "ID register value"),
           ("RegMapMajor", rmap.major, "register map major version"),
           ("RegMapMinor", rmap.minor, "register map minor version"),
           ("RegAddrBits", rmap.address_bits, "AXI4-Lite address bits of the register window"),
           ("RegSlotCount", sum(g.kind == "slot" for g in rmap.groups),
            "64-bit slots of the method registers (GAIN .. FFC_TARGET)")]
    for g in rmap.groups:
        name = _camel(g.name)
        if g.kind == "array":
            out += [(f"Reg{name}Offset", g.offset, f"{g.name}[0]: {g.doc}"),
                    (f"Reg{name}Stride", g.stride, f"{g.name}[k] spacing"),
                    (f"Reg{name}Count", len(g.registers), f"{g.name}[k] entries")]
            continue
        if g.kind == "slot":
            lo, hi = (rmap[n] for n in g.registers)
            out += [(f"Reg{name}LoOffset", lo.offset, f"{lo.name}: {g.doc}"),
                    (f"Reg{name}HiOffset", hi.offset, hi.name)]
            continue
        reg = rmap[g.registers[0]]
        out.append((f"Reg{name}Offset", reg.offset, f"{reg.name}: {reg.doc}"))
        for f in reg.fields:
            fname = f"Reg{name}{_camel(f.name)}"
            out.append((f"{fname}Lsb", f.lsb, f"{reg.name}.{f.name}"))
            if f.bits > 1:
                out.append((f"{fname}Bits", f.bits, f"{reg.name}.{f.name} width"))
            if isinstance(f.reset, int) and f.access in ("rw", "w1c"):
                out.append((f"{fname}Reset", f.reset, f"{reg.name}.{f.name} reset"))
    return out


_ACCESS_DOC = {"ro": "RO", "rw": "RW", "w1c": "W1C", "w1s": "W1S"}


def _number(value: int) -> str:
    return f"0x{value:x}" if value > 9 else str(value)


def _requires_text(name: str) -> str:
    """A ``requires`` entry for the page: a reading with the methods that take it."""
    from irnuc.nuc_fixed import methods

    if name not in methods.READINGS:
        return name
    takers = [m.name for m in methods.BASES.values() if name in m.readings]
    return f"reading {name} ({', '.join(takers)})"


def markdown(rmap: RegisterMap | None = None, build: PipelineConfig | None = None) -> str:
    """``docs/registers.md``: the register map as tables (generated; do not edit). With a
    ``build`` (``irnuc regmap``): that configuration's page, its reset values and which
    registers it has."""
    rmap = rmap or register_map()
    model = RegisterModel(build, rmap) if build is not None else None

    def reset_text(reset: int | str) -> str:
        if isinstance(reset, int):
            return _number(reset)
        return reset if model is None else f"{_number(model.params[reset])} ({reset})"

    title = "# Register map of `irnuc_axis_top` (AXI4-Lite)"
    source = ("<!-- Generated from nuc_fixed/registers.rdl by `python -m irnuc.cosim.spec_files "
              "--write`; do not edit. -->")
    if build is not None:
        title += f" built for pipeline `{build.name}`"
        source = (f"<!-- Generated from nuc_fixed/registers.rdl by `irnuc regmap --pipeline "
                  f"{build.name}`. Reserved below: a register this build does not have. -->")
    lines = [
        title,
        "",
        source,
        "",
        f"Map version {rmap.major}.{rmap.minor}, ID 0x{rmap.map_id:08x}. 32-bit registers at "
        f"byte offsets in a {rmap.size}-byte window ({rmap.address_bits} address bits; "
        "`s_axil_awaddr[1:0]`/`s_axil_araddr[1:0]` are ignored); `s_axil_wstrb` selects the "
        "bytes written; `s_axil_awprot`/`s_axil_arprot` are ignored. The source is the "
        "SystemRDL file `nuc_fixed/registers.rdl`; the C header, the IP-XACT description, "
        "the register block and the Python models are generated from it too "
        "([regmap.md](regmap.md): how the map is written, the register block, its hardware "
        "interface, adding a register).",
        "",
        "Access: **RO** read only, **RW** read and write, **W1C** written 1 clears the bit "
        "(an event in the same cycle wins), **W1S** written 1 acts once and reads 0 (a "
        "register of W1S fields only is write only). Bits outside the fields read 0 and "
        "ignore writes. *Shadowed*: a write takes effect at the next frame start (the first "
        "pixel of the next frame accepted on `s_axis_video`); the register reads back what "
        "was written at once, and `STATUS.pending` is 1 until then.",
        "",
        "Responses: **SLVERR** (read data 0) for an offset outside the table below, for a "
        "write to a register without RW, W1C or W1S fields, for a read of a write-only "
        "register, and for a `FRAME_SIZE` of 0 or above `FRAME_MAX` (the register keeps its "
        "value). The response depends on the offset and the access type only, the same on "
        "every build. A register of a method or stage that is not configured (column "
        "*requires*) is reserved: it reads 0 and ignores writes. The slave never answers "
        "EXOKAY or DECERR (DECERR is the interconnect's answer for an address outside every "
        "slave).",
        "",
        "Reset values named after a configuration value (`MaxWidth`, `AdcBits`, ...) are "
        "those of the pipeline the core is built for (`nuc_fixed/pipelines.toml`; "
        "`irnuc regmap --pipeline NAME` writes this page, the C header and the IP-XACT with "
        "that build's numbers).",
        "",
        "| offset | register | requires | shadowed | description |",
        "|---|---|---|---|---|",
    ]
    for g in rmap.groups:
        first = rmap[g.registers[0]]
        last = rmap[g.registers[-1]]
        off = f"0x{first.offset:03x}"
        name = g.name
        if g.kind == "array":
            off = f"0x{first.offset:03x}..0x{last.offset:03x}"
            name = f"{g.name}[0 .. {len(g.registers) - 1}]"
        elif g.kind == "slot":
            off = f"0x{first.offset:03x}, 0x{last.offset:03x}"
            name = f"{g.name}.LO, .HI"
        req = ", ".join(_requires_text(r) for r in first.requires) or "-"
        if model is not None and not model.present(first):
            req += " (reserved)"
        lines.append(f"| {off} | `{name}` | {req} | {'yes' if first.shadowed else '-'} | "
                     f"{g.doc} |")
    lines.append("")
    for g in rmap.groups:
        first = rmap[g.registers[0]]
        lines += [f"## `{g.name}` (0x{first.offset:03x})", "", g.doc + ".", ""]
        if first.config_register is not None:
            cr = first.config_register
            if g.kind == "array":
                lines.append(f"Entry k (k = 0 .. {len(g.registers) - 1}, at "
                             f"0x{first.offset:03x} + {g.stride} k) holds value k of the "
                             f"method register `{cr}` (`PipelineConfig.registers`), in bits "
                             "[width-1:0]; entries from the configured count on are reserved. "
                             "Reset 0; RW.")
            else:
                lines.append(f"The method register `{cr}` (`PipelineConfig.registers`): bits "
                             "[31:0] of its value in `.LO`, bits [63:32] in `.HI`; bits from "
                             "its configured width on read 0. Reset 0; RW.")
            lines.append("")
            continue
        lines += ["| bits | field | access | reset | description |", "|---|---|---|---|---|"]
        for f in first.fields:
            bits = f"{f.lsb}" if f.bits == 1 else f"{f.lsb + f.bits - 1}:{f.lsb}"
            live = " (hardware)" if f.live else ""
            lines.append(f"| {bits} | `{f.name}` | {_ACCESS_DOC[f.access]}{live} | "
                         f"{reset_text(f.reset)} | {f.doc} |")
        lines.append("")
    return "\n".join(lines)


__all__ = ["ACCESS", "DECERR", "EXOKAY", "OKAY", "REGISTERS_RDL", "RESP_NAMES", "SLVERR",
           "Group", "RegField", "Register", "RegisterMap", "RegisterModel", "config_params",
           "elaborate", "elaborate_for", "markdown", "register_map", "sv_constants"]
