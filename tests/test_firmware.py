"""The firmware kit: the C header (``firmware/irnuc_regs.h``, peakrdl-cheader) and the C
driver example compile with gcc (warnings are errors), and the example, run against the
register file's golden model (:class:`irnuc.nuc_fixed.regmap.RegisterModel`, served over
a pipe: every access of the C code is one line), makes the same accesses, in the same
order, with the same results, as its Python twin :func:`irnuc.cosim.driver.example` over
the register model peakrdl-python generates from the same map. The co-simulation runs the
Python twin against the RTL (``cocotb_tests/tb_axis_ffc.py``)."""

from __future__ import annotations

import asyncio
import shutil
import subprocess
from pathlib import Path

import pytest

from irnuc.cosim import driver
from irnuc.nuc_fixed import load_pipeline, regmap, rtl_spec
from irnuc.nuc_fixed.config import BASE_METHODS

ROOT = Path(__file__).resolve().parents[1]
FIRMWARE = ROOT / "firmware"
MOCK = Path(__file__).with_name("firmware") / "mock_main.c"
CFLAGS = ["-std=gnu11", "-Wall", "-Wextra", "-Werror", "-pedantic", f"-I{FIRMWARE}"]
#: Reads of FFC_STATUS before the model's FFC is done.
FFC_POLLS = 3


def _cc() -> str:
    cc = shutil.which("gcc") or shutil.which("cc")
    assert cc, "no C compiler (gcc) on PATH"
    return cc


@pytest.fixture(scope="module")
def mock_binary(tmp_path_factory) -> Path:
    out = tmp_path_factory.mktemp("firmware") / "mock"
    subprocess.run([_cc(), *CFLAGS, str(MOCK), "-o", str(out)], check=True)
    return out


class ModelBus:
    """The register file's golden model on a bus, with the hardware's part of a run: some
    status and counters set before, and an FFC that finishes after ``FFC_POLLS`` reads of
    FFC_STATUS (busy, then done and IRQ_STATUS.ffc_done). ``log``: (kind, offset, data,
    response) of every access."""

    def __init__(self, config: str) -> None:
        self.model = regmap.RegisterModel(load_pipeline(config))
        self.log: list[tuple[str, int, int, int]] = []
        self.polls = 0
        self.model.set_live("STATUS", "eol_late", 1)
        self.model.set_live("IRQ_STATUS", "error", 1)
        self.model.set_live("FRAMES_IN", "count", 5)
        self.model.set_live("EOL_ERRORS", "late", 2)
        self.ffc_offset = self.model.map["FFC_STATUS"].offset

    def read(self, offset: int) -> int:
        resp, data = self.model.read(offset)
        if offset == self.ffc_offset and self.model.present("FFC_STATUS"):
            self.polls += ("FFC_CTRL", "start") in self.model.commands
            if self.polls > FFC_POLLS:
                self.model.set_live("FFC_STATUS", "busy", 0)
                self.model.set_live("FFC_STATUS", "done", 1)
                self.model.set_live("IRQ_STATUS", "ffc_done", 1)
            elif self.polls:
                self.model.set_live("FFC_STATUS", "busy", 1)
            resp, data = self.model.read(offset)
        self.log.append(("R", offset, data, resp))
        return data

    def write(self, offset: int, data: int) -> None:
        self.log.append(("W", offset, data, self.model.write(offset, data)))


def _run_c(binary: Path, bus: ModelBus, args: list[str]) -> tuple[int, list[int]]:
    """The C example against ``bus``: its return code and status words."""
    proc = subprocess.Popen([str(binary), *args], stdin=subprocess.PIPE,
                            stdout=subprocess.PIPE, text=True)
    assert proc.stdin and proc.stdout
    try:
        for line in proc.stdout:
            kind, *rest = line.split()
            if kind == "R":
                proc.stdin.write(f"{bus.read(int(rest[0], 16)):x}\n")
                proc.stdin.flush()
            elif kind == "W":
                bus.write(int(rest[0], 16), int(rest[1], 16))
            elif kind == "END":
                return int(rest[0]), [int(v, 16) for v in rest[1:]]
    finally:
        proc.stdin.close()
        proc.wait(timeout=10)
    raise AssertionError(f"the C example ended without a result (exit {proc.returncode})")


def _run_py(bus: ModelBus, ex: driver.Example) -> tuple[int, list[int]]:
    async def rd(offset: int) -> int:
        return bus.read(offset)

    async def wr(offset: int, data: int) -> None:
        bus.write(offset, data)

    rc, st = asyncio.run(driver.example(driver.registers(rd, wr), ex))
    return rc, [] if st is None else list(vars(st).values())


def _example(config: str, **kw: object) -> tuple[driver.Example, list[str]]:
    """The example's settings for a configuration (its calibration registers set), as
    the Python driver takes them and as the C example's arguments."""
    cfg = load_pipeline(config)
    cal: dict[str, object] = {}
    args = [f"method={BASE_METHODS.index(cfg.base_method)}"]
    for k, name in enumerate(sorted(cfg.registers)):
        r = cfg.registers[name]
        if name == "table_readings":
            cal[name] = tuple(100 * (j + 1) for j in range(r.count))
            args += [f"table={v}" for v in cal[name]]  # type: ignore[attr-defined]
        elif name not in ("reading", "blind_sum"):  # per frame, not calibration
            cal[name] = (0x1234_5678_9A << k) & ((1 << r.width) - 1)
            args.append(f"{name}={cal[name]}")
    settings = {"width": 6, "height": 4, "reading": 0x2A5 if "reading" in cfg.registers
                else None, "ffc_frames": int(cfg.ffc_frames or 0), "max_polls": 10, **kw}
    args += [f"{k}={v}" for k, v in settings.items() if v is not None]
    ex = driver.Example(cfg.base_method, settings["width"], settings["height"],  # type: ignore[arg-type]
                        driver.Calibration(**cal), **{k: v for k, v in settings.items()  # type: ignore[arg-type]
                                                      if k not in ("width", "height")})
    return ex, args


@pytest.mark.parametrize("config", ["tcffc14", "table14", "onepoint14", "drift14"])
def test_c_example_is_the_python_driver(mock_binary: Path, config: str) -> None:
    """The same accesses in the same order with the same data and responses; every
    response OKAY; the bring-up's effect on the model (frame size, calibration, FFC start
    and its interrupt cleared, the sticky status cleared)."""
    ex, args = _example(config)
    c_bus, py_bus = ModelBus(config), ModelBus(config)
    c_rc, c_status = _run_c(mock_binary, c_bus, args)
    py_rc, py_status = _run_py(py_bus, ex)
    assert c_bus.log == py_bus.log
    assert (c_rc, c_status) == (py_rc, py_status) and c_rc == driver.OK
    assert all(resp == regmap.OKAY for *_rest, resp in c_bus.log)
    m = c_bus.model
    assert m.get("FRAME_SIZE") == ex.width | (ex.height << 16)
    assert m.get("CTRL") == 0x103 and m.pending
    assert c_status[0] & 0x8 and not m.get("STATUS", "eol_late"), "STATUS not read / cleared"
    assert c_status[2] == 5 and c_status[9] == 2 << 16  # FRAMES_IN, EOL_ERRORS.late
    assert not m.get("IRQ_STATUS")
    cfg = load_pipeline(config)
    for name, value in vars(ex.cal).items():
        if name == "table_readings":
            regs = [r for r in m.map.registers if r.config_register == "table_readings"]
            assert [m.get(r.name) for r in regs[:len(value)]] == list(value)
        elif value is not None:
            lo, hi = (r.name for r in m.map.registers if r.config_register == name)
            assert m.get(lo) | (m.get(hi) << 32) == value, name
    written = {o for kind, o, *_ in c_bus.log if kind == "W"}
    assert (m.map["FFC_CTRL"].offset in written) == cfg.has("ffc")
    if cfg.has("ffc"):
        assert m.commands == [("FFC_CTRL", "start")]
        assert m.get("FFC_CTRL", "frames") == cfg.ffc_frames
        assert sum(o == c_bus.ffc_offset for _k, o, *_ in c_bus.log) == FFC_POLLS + 1


@pytest.mark.parametrize(("config", "change", "code"), [
    ("tcffc14", {"method": 1}, driver.ERR_METHOD),
    ("typical14", {"width": 1025}, driver.ERR_SIZE),
    ("typical14", {"ffc_frames": 4}, driver.ERR_NO_FFC),
    ("tcffc14", {"max_polls": FFC_POLLS}, driver.ERR_TIMEOUT),
])
def test_c_example_errors(mock_binary: Path, config: str, change: dict, code: int) -> None:
    """The driver's checks: another method than the build's, a frame above FRAME_MAX, an
    FFC on a build without one, an FFC that does not finish in the polls given; the same
    return code from both."""
    kw = {k: v for k, v in change.items() if k != "method"}
    ex, args = _example(config, **kw)
    if "method" in change:
        ex = driver.Example(BASE_METHODS[change["method"]], ex.width, ex.height, ex.cal,
                            ex.reading, ex.ffc_frames, ex.max_polls)
        args = [f"method={change['method']}", *args[1:]]
    c_bus, py_bus = ModelBus(config), ModelBus(config)
    c_rc, _ = _run_c(mock_binary, c_bus, args)
    py_rc, _ = _run_py(py_bus, ex)
    assert c_rc == py_rc == code
    assert c_bus.log == py_bus.log


def test_method_codes_are_the_rtl_spec(mock_binary: Path) -> None:
    out = subprocess.run([str(mock_binary), "enum=1"], capture_output=True, text=True,
                         check=True).stdout.split()
    assert out[0] == "ENUM"
    assert [int(v) for v in out[1:]] == [rtl_spec.METHOD.codes[m] for m in driver.METHODS]
    assert driver.METHODS == BASE_METHODS


def test_bare_metal_example_compiles(tmp_path: Path) -> None:
    """The driver and the example with the default accessors (volatile loads and stores
    at IRNUC_BASE) compile and link."""
    out = tmp_path / "example"
    subprocess.run([_cc(), *CFLAGS, "-DIRNUC_BASE=0x43c00000", str(FIRMWARE / "irnuc_driver.c"),
                    str(FIRMWARE / "irnuc_example.c"), "-o", str(out)], check=True)
    assert out.is_file()


def test_header_offsets_are_the_map(tmp_path: Path) -> None:
    """offsetof() of every register in the generated header (compiled) is its offset in
    the map; the header's struct spans the map."""
    rmap = regmap.register_map()
    lines = ['#include <stddef.h>', '#include <stdio.h>', '#include "irnuc_regs.h"',
             "int main(void) {"]
    for r in rmap.registers:
        lines.append(f'    printf("%zu\\n", offsetof(irnuc_regs_t, {r.name}));')
    lines += ['    printf("%zu\\n", sizeof(irnuc_regs_t));', "    return 0;", "}"]
    src = tmp_path / "offsets.c"
    src.write_text("\n".join(lines) + "\n")
    subprocess.run([_cc(), *CFLAGS, str(src), "-o", str(tmp_path / "offsets")], check=True)
    got = [int(v) for v in subprocess.run([str(tmp_path / "offsets")], capture_output=True,
                                          text=True, check=True).stdout.split()]
    assert got[:-1] == [r.offset for r in rmap.registers]
    assert got[-1] == rmap.registers[-1].offset + 4
