"""The firmware's register sequence in Python: ``firmware/irnuc_driver.c`` function for
function, over the register model peakrdl-python generates from ``nuc_fixed/registers.rdl``
(:func:`irnuc.cosim.regfiles.python_model`; each access awaits the bus).

The co-simulation drives the RTL with it (``cocotb_tests/tb_axis_ffc.py``: the bring-up,
the flat-field correction and the status of a refresh, each access through
cocotbext-axi's AXI4-Lite master and checked against the register file's golden model);
``tests/test_firmware.py`` runs :func:`example` and the C example (built with gcc) against
the same golden model and compares their accesses one by one. Field positions and masks
come from the generated model (``regs.FRAME_SIZE.width.low``, ``register_value``), the
C driver's from the generated header: both from the one map.
"""

from __future__ import annotations

from collections.abc import Awaitable, Callable
from dataclasses import dataclass, field
from typing import Any

from irnuc.cosim.regfiles import python_model

#: The base methods by CONFIG.method code (``enum irnuc_method`` of the C driver,
#: ``irnuc_pkg::method_e``).
METHODS = ("one_point", "two_point", "piecewise", "quadratic", "tc_offset", "table_interp",
           "tc_housing")
#: The C driver's return codes.
OK, ERR_ID, ERR_VERSION, ERR_METHOD, ERR_SIZE, ERR_NO_FFC, ERR_TIMEOUT = 0, -1, -2, -3, -4, -5, -6


def _fld(reg: Any, name: str) -> Any:
    """A register's field by its SystemRDL name (peakrdl-python renames a field whose name
    is an attribute of its registers: ``width`` is ``field_width``)."""
    return getattr(reg, reg.systemrdl_python_child_name_map[name])


def _field(value: int, reg: Any, name: str) -> int:
    fld = _fld(reg, name)
    return (int(value) & fld.bitmask) >> fld.low


def _pack(reg: Any, **fields: int) -> int:
    """The register value with these fields (SystemRDL names), the others 0."""
    names = reg.systemrdl_python_child_name_map
    unknown = set(fields) - set(names)
    if unknown:
        raise KeyError(f"register {reg.inst_name} has no field {sorted(unknown)[0]!r}")
    return reg.register_value(**{py: int(fields.get(rdl, 0)) for rdl, py in names.items()})


@dataclass(frozen=True)
class Info:
    """What the core was built with (:func:`probe`): the raw registers."""

    version: int
    config: int
    format: int
    frame_max: int


@dataclass(frozen=True)
class Calibration:
    """A calibration's registers (None: not written), like ``irnuc_calibration_t``."""

    gain: int | None = None
    level: int | None = None
    t_ref: int | None = None
    blind_ref: int | None = None
    drift_gain: int | None = None
    ffc_target: int | None = None
    h_ref: int | None = None
    table_readings: tuple[int, ...] = ()


@dataclass(frozen=True)
class Status:
    """STATUS, IRQ_STATUS and the counters as :func:`read_status` read them."""

    status: int
    irq_status: int
    frames_in: int
    frames_out: int
    pixels_in: int
    pixels_out: int
    dropped: int
    padded: int
    sof_errors: int
    eol_errors: int
    coef_errors: int


@dataclass(frozen=True)
class Example:
    """What the bring-up sets (``irnuc_example_t``)."""

    method: str
    width: int
    height: int
    cal: Calibration = field(default_factory=Calibration)
    reading: int | None = None
    ffc_frames: int = 0
    max_polls: int = 1000
    ffc_period: int = 0  # the FFC request (frames, reading codes); both 0: none
    ffc_threshold: int = 0


def registers(read: Callable[[int], Awaitable[int]],
              write: Callable[[int, int], Awaitable[None]]) -> Any:
    """The generated register model on a bus: ``read(offset)`` and ``write(offset, data)``
    (32-bit accesses at byte offsets of the register window)."""
    pkg = python_model()

    async def read_cb(addr: int, width: int, accesswidth: int) -> int:
        return await read(addr)

    async def write_cb(addr: int, width: int, accesswidth: int, data: int) -> None:
        await write(addr, data)

    return pkg.reg_model.RegModel(callbacks=pkg.lib.AsyncCallbackSet(read_callback=read_cb,
                                                                     write_callback=write_cb))


async def probe(regs: Any) -> tuple[int, Info | None]:
    """ID and VERSION.major checked; CONFIG, FORMAT and FRAME_MAX read."""
    if await regs.ID.read() != _fld(regs.ID, "value").default:
        return ERR_ID, None
    version = await regs.VERSION.read()
    if _field(version, regs.VERSION, "major") != _fld(regs.VERSION, "major").default:
        return ERR_VERSION, None
    config = await regs.CONFIG.read()
    fmt = await regs.FORMAT.read()
    frame_max = await regs.FRAME_MAX.read()
    return OK, Info(version, config, fmt, frame_max)


def info_method(regs: Any, info: Info) -> str:
    return METHODS[_field(info.config, regs.CONFIG, "method")]


def info_has_ffc(regs: Any, info: Info) -> bool:
    return _field(info.config, regs.CONFIG, "ffc") != 0


def ctrl_default(regs: Any) -> int:
    """CTRL of normal operation: NUC and DPC on, the coefficient tlast checked."""
    return _pack(regs.CTRL, nuc_en=1, dpc_en=1, coef_sync=1)


async def configure(regs: Any, info: Info, method: str, width: int, height: int,
                    ctrl: int | None = None) -> int:
    """The core must be built for ``method``; FRAME_SIZE and CTRL written (shadowed)."""
    if info_method(regs, info) != method:
        return ERR_METHOD
    if not (1 <= width <= _field(info.frame_max, regs.FRAME_MAX, "width")
            and 1 <= height <= _field(info.frame_max, regs.FRAME_MAX, "height")):
        return ERR_SIZE
    await regs.FRAME_SIZE.write(_pack(regs.FRAME_SIZE, width=width, height=height))
    await regs.CTRL.write(ctrl_default(regs) if ctrl is None else ctrl)
    return OK


async def write64(slot: Any, value: int) -> None:
    """A 64-bit method register: its LO word, then its HI word."""
    await slot.LO.write(int(value) & 0xFFFF_FFFF)
    await slot.HI.write(int(value) >> 32 & 0xFFFF_FFFF)


async def load_calibration(regs: Any, cal: Calibration) -> None:
    """The calibration's registers, in map order."""
    for name in ("gain", "level", "t_ref", "blind_ref", "drift_gain", "ffc_target", "h_ref"):
        value = getattr(cal, name)
        if value is not None:
            await write64(getattr(regs, name.upper()), value)
    for k, value in enumerate(cal.table_readings[:16]):
        await regs.TABLE_READING[k].write(int(value))


async def set_reading(regs: Any, reading: int) -> None:
    """The FPA reading of the next frame (shadowed)."""
    await write64(regs.READING, reading)


async def set_housing_reading(regs: Any, reading: int) -> None:
    """The housing sensor's reading of the next frame (tc_housing; shadowed)."""
    await write64(regs.HOUSING_READING, reading)


async def enable_irq(regs: Any, **causes: int) -> None:
    """IRQ_ENABLE (``error=1, ffc_done=1``, ...)."""
    await regs.IRQ_ENABLE.write(_pack(regs.IRQ_ENABLE, **causes))


async def ffc_start(regs: Any, info: Info, frames: int) -> int:
    """A flat-field correction of ``frames`` shutter frames from the next frame start."""
    if not info_has_ffc(regs, info):
        return ERR_NO_FFC
    frames &= _fld(regs.FFC_CTRL, "frames").max_value
    await regs.FFC_CTRL.write(_pack(regs.FFC_CTRL, start=1, frames=frames))
    return OK


async def ffc_policy(regs: Any, info: Info, period: int, threshold: int) -> int:
    """The FFC request: FFC_PERIOD (frames since the last FFC) and FFC_THRESHOLD (FPA
    reading codes since it); 0 turns a trigger off."""
    if not info_has_ffc(regs, info):
        return ERR_NO_FFC
    await regs.FFC_PERIOD.write(period & _fld(regs.FFC_PERIOD, "frames").max_value)
    await regs.FFC_THRESHOLD.write(threshold & _fld(regs.FFC_THRESHOLD, "codes").max_value)
    return OK


async def ffc_wait(regs: Any, max_polls: int) -> int:
    """Poll FFC_STATUS.done; once it is 1 clear IRQ_STATUS.ffc_done (W1C)."""
    for _ in range(max_polls):
        if _field(await regs.FFC_STATUS.read(), regs.FFC_STATUS, "done"):
            await regs.IRQ_STATUS.write(_fld(regs.IRQ_STATUS, "ffc_done").bitmask)
            return OK
    return ERR_TIMEOUT


async def read_status(regs: Any) -> Status:
    """STATUS, IRQ_STATUS and the counters; the sticky bits read as 1 cleared (W1C)."""
    errors = sum(_fld(regs.STATUS, f).bitmask for f in (
        "sof_early", "sof_late", "eol_early", "eol_late", "coef_early", "coef_late"))
    values = [await getattr(regs, name).read() for name in (
        "STATUS", "IRQ_STATUS", "FRAMES_IN", "FRAMES_OUT", "PIXELS_IN", "PIXELS_OUT",
        "DROPPED", "PADDED", "SOF_ERRORS", "EOL_ERRORS", "COEF_ERRORS")]
    st = Status(*values)
    if st.status & errors:
        await regs.STATUS.write(st.status & errors)
    if st.irq_status:
        await regs.IRQ_STATUS.write(st.irq_status)
    return st


async def example(regs: Any, ex: Example) -> tuple[int, Status | None]:
    """The bring-up of ``irnuc_example()``: identify, configure, calibrate, enable the
    interrupts, set the FFC request (``ffc_period``, ``ffc_threshold``), run a flat-field
    correction (``ffc_frames``), read the status."""
    rc, info = await probe(regs)
    if rc != OK or info is None:
        return rc, None
    rc = await configure(regs, info, ex.method, ex.width, ex.height)
    if rc != OK:
        return rc, None
    await load_calibration(regs, ex.cal)
    if ex.reading is not None:
        await set_reading(regs, ex.reading)
    policy = bool(ex.ffc_period or ex.ffc_threshold)
    await enable_irq(regs, error=1, ffc_done=int(ex.ffc_frames > 0), ffc_request=int(policy))
    if policy:
        rc = await ffc_policy(regs, info, ex.ffc_period, ex.ffc_threshold)
    if rc == OK and ex.ffc_frames:
        rc = await ffc_start(regs, info, ex.ffc_frames)
        if rc == OK:
            rc = await ffc_wait(regs, ex.max_polls)
    return rc, await read_status(regs)


__all__ = ["ERR_ID", "ERR_METHOD", "ERR_NO_FFC", "ERR_SIZE", "ERR_TIMEOUT", "ERR_VERSION",
           "METHODS", "OK", "Calibration", "Example", "Info", "Status", "configure",
           "ctrl_default", "enable_irq", "example", "ffc_policy", "ffc_start", "ffc_wait", "info_has_ffc",
           "info_method", "load_calibration", "probe", "read_status", "registers",
           "set_housing_reading", "set_reading", "write64"]
