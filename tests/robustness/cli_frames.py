"""The robustness cases of ``irnuc frames``."""

from __future__ import annotations

import io
import shutil
from pathlib import Path

import numpy as np

from robustness.harness import (
    case,
    command,
    link_out,
    other_kind,
    out_is_file,
    out_under_file,
    ro_parent,
    user_folder,
    write_file,
)


def _npy_header(path: Path, shape: tuple[int, ...]) -> None:
    """An .npy file of ``shape`` float64 whose data is absent (only the header)."""
    from numpy.lib import format as npformat

    buf = io.BytesIO()
    npformat.write_array_header_1_0(buf, {"descr": "<f8", "fortran_order": False,
                                          "shape": shape})
    path.write_bytes(buf.getvalue() + bytes(64))


F = command("frames", (("irnuc.model", "simulate"), ("irnuc.model.sequence", "prepare")))
case("frames-unknown-flag", F, "--bogus 1", ("--bogus", "unrecognized"), "an unknown flag")
case("frames-repeats-text", F, "--repeats x", ("--repeats", "invalid int"), "--repeats not a number")
case("frames-repeats-float", F, "--repeats 1.5", ("--repeats", "invalid int"), "--repeats not an integer")
case("frames-repeats-zero", F, "--repeats 0", ("--repeats", "1..100000"), "zero repeats")
case("frames-repeats-huge", F, "--repeats 100001", ("--repeats", "1..100000"), "too many repeats")
case("frames-seed-negative", F, "--seed -1", ("--seed", "0..2^63-1"), "a negative seed")
case("frames-seed-huge", F, f"--seed {2**64}", ("--seed", "0..2^63-1"), "a seed above 2^63-1")
case("frames-scene-unknown", F, "--scene moon", ("--scene", "invalid choice"), "an unknown scene")
case("frames-temps-missing-value", F, "--temps", ("--temps", "expected one argument"),
     "--temps without a value")
case("frames-temps-empty", F, "--temps ,", ("--temps", "no number"), "--temps with no number")
case("frames-temps-text", F, "--temps abc", ("--temps", "list of numbers"), "--temps not numbers")
case("frames-temps-nan", F, "--temps nan", ("--temps", "finite"), "a NaN temperature")
case("frames-temps-inf", F, "--temps 300,inf", ("--temps", "finite"), "an infinite temperature")
case("frames-temps-negative", F, "--temps=-5", ("temps", "(0, 100000] K"), "a negative temperature")
case("frames-temps-zero", F, "--temps 0", ("temps", "(0, 100000] K"), "0 K")
case("frames-temps-too-hot", F, "--temps 1e6", ("temps", "(0, 100000] K"), "10^6 K")
case("frames-set-no-equals", F, "--set fpa.active_rows", ("--set", "KEY=VALUE"), "--set without =")
case("frames-set-typo", F, "--set fpa.activ_rows=10", ("fpa.activ_rows", "did you mean 'active_rows'"),
     "a misspelled field")
case("frames-set-unknown-section", F, "--set fpaa.active_rows=10", ("fpaa", "not a known field"),
     "a misspelled section")
case("frames-set-zero-rows", F, "--set fpa.active_rows=0", ("fpa.active_rows", "allowed range"),
     "zero rows")
case("frames-set-text-rows", F, "--set fpa.active_rows=many", ("fpa.active_rows", "integer"),
     "rows as a word")
case("frames-set-float-rows", F, "--set fpa.active_rows=1.5", ("fpa.active_rows", "integer"),
     "fractional rows")
case("frames-set-section-scalar", F, "--set fpa=3", ("fpa", "table"), "a section set to a number")
case("frames-set-adc-bits", F, "--set adc.bits=99", ("adc.bits", "allowed range"), "99 ADC bits")
case("frames-set-nan", F, "--set environment.T_cam=nan", ("environment.T_cam", "finite"),
     "a NaN field")
case("frames-memory-huge", F,
     "--set fpa.active_rows=16384 --set fpa.active_cols=16384 --temps 300,400 --repeats 100000",
     ("--temps", "--repeats", "16384 x 16384", "needs an estimated", "available"),
     "200000 frames of 16384 x 16384 (petabytes), refused up front with the estimate")
case("frames-memory-frames", F, "--set fpa.active_rows=16384 --set fpa.active_cols=16384 "
     "--temps 300,310,320,330 --repeats 50", ("needs an estimated", "16384 x 16384"),
     "200 full-size frames, more than the memory there is")
case("frames-scene-param-no-equals", F, "--scene disk --scene-param radius",
     ("--scene-param", "KEY=VALUE"), "--scene-param without =")
case("frames-scene-param-unknown", F, "--scene disk --scene-param colour=1",
     ("scene 'disk'", "colour"), "an unknown scene parameter")
case("frames-scene-radius-negative", F, "--scene disk --scene-param radius=-1",
     ("--scene-param", "scene.radius"), "a negative disk radius")
case("frames-scene-map-no-source", F, "--scene map", ("scene 'map'", "path"),
     "a map scene without a map")
case("frames-scene-map-missing", F, "--scene map --scene-param path={t}/none.npy",
     ("scene.path", "no such file"), "a map file that does not exist")
case("frames-scene-map-text", F, "--scene map --scene-param path={t}/map.npy",
     ("scene.path", "no .npy header"), "a text file as the .npy map (not called pickled data)",
     setup=write_file("map.npy", "hello"))
case("frames-scene-map-image-garbage", F, "--scene map --scene-param path={t}/map.png",
     ("scene.path", "not a readable image"), "garbage as the image map",
     setup=write_file("map.png", b"\x89PNG garbage"))
case("frames-scene-map-shape", F, "--scene map --scene-param path={w}/map_3x3.npy",
     ("--scene-param", "shape (3, 3)"), "a map of the wrong size")
case("frames-scene-map-folder", F, "--scene map --scene-param path={w}",
     ("scene.path", "not a regular file"), "a folder as the map")
case("frames-scene-map-bool", F, "--scene map --scene-param path={t}/map.npy",
     ("scene.path", "dtype bool", "temperatures in K"),
     "a boolean .npy map (was taken as a 1 K scene)",
     setup=lambda w, t: np.save(t / "map.npy", np.ones((8, 8), bool)))
case("frames-scene-map-complex", F, "--scene map --scene-param path={t}/map.npy",
     ("scene.path", "complex128"), "a complex .npy map",
     setup=lambda w, t: np.save(t / "map.npy", np.full((8, 8), 300 + 1j)))
case("frames-scene-map-3d", F, "--scene map --scene-param path={t}/map.npy",
     ("scene.path", "shape (2, 8, 8)", "2-D"), "a 3-D .npy map",
     setup=lambda w, t: np.save(t / "map.npy", np.full((2, 8, 8), 300.0)))
case("frames-scene-map-header-bomb", F, "--scene map --scene-param path={t}/map.npy",
     ("scene.path", "needs an estimated"),
     "an .npy map whose header claims 10^6 x 10^6 (checked before reading)",
     setup=lambda w, t: _npy_header(t / "map.npy", (10**6, 10**6)))
case("frames-scene-map-dev-zero", F, "--scene map --scene-param path=/dev/zero",
     ("scene.path", "/dev/zero", "not a regular file"), "a device as the map")
case("frames-sensor-dev-zero", F, "--sensor /dev/zero", ("--sensor", "/dev/zero", "larger than"),
     "an endless file as the sensor (grew without bound)")
case("frames-every-solve-fails", F, "--set fpa.active_rows=4 --set fpa.active_cols=4 "
     "--set bolometer.tcr=0.02 --set bolometer.bias_current=1e-4",
     ("--set bolometer.tcr=0.02", "every pixel's solve failed", "runaway"),
     "a sensor where every pixel runs away (exit 0, a raw RuntimeWarning, frames of rail codes)",
     before_work=False)
case("frames-sensor-unknown-preset", F, "--sensor defualt", ("--sensor", "neither a preset"),
     "a misspelled preset")
case("frames-sensor-missing-file", F, "--sensor {t}/none.toml", ("--sensor", "none.toml", "no such file"),
     "a sensor file that does not exist")
case("frames-sensor-folder", F, "--sensor {w}/", ("--sensor", "is a folder"), "a folder as --sensor")
case("frames-sensor-malformed", F, "--sensor {w}/bad.toml", ("--sensor", "bad.toml", "not valid TOML"),
     "malformed TOML")
case("frames-sensor-binary", F, "--sensor {w}/binary.toml", ("--sensor", "binary.toml", "cannot be read"),
     "binary garbage as TOML")
case("frames-sensor-empty", F, "--sensor {w}/empty.toml", ("--sensor", "empty.toml", "required but missing"),
     "an empty sensor file")
case("frames-sensor-unknown-section", F, "--sensor {w}/sensor_section.toml",
     ("--sensor", "fpaa", "not a known field"), "a misspelled section in the sensor file")
case("frames-sensor-unknown-key", F, "--sensor {w}/sensor_key.toml",
     ("--sensor", "fpa.activ_rows", "did you mean"), "a misspelled key in the sensor file")
case("frames-sensor-type", F, "--sensor {w}/sensor_type.toml",
     ("--sensor", "fpa.active_rows", "integer"), "rows as a string in the sensor file")
case("frames-sensor-range", F, "--sensor {w}/sensor_range.toml",
     ("--sensor", "fpa.active_rows", "allowed range"), "zero rows in the sensor file")
case("frames-sensor-base", F, "--sensor {w}/sensor_base.toml", ("--sensor", "base = 'nope'"),
     "an unknown base preset")
case("frames-sensor-nan", F, "--sensor {w}/sensor_nan.toml", ("--sensor", "environment.T_cam", "finite"),
     "NaN in the sensor file")
case("frames-sensor-section-scalar", F, "--sensor {w}/sensor_scalar.toml", ("--sensor", "fpa", "table"),
     "a section that is a number")
case("frames-out-file", F, "--out {t}/out", ("--out", "not a folder"), "--out is a regular file",
     setup=out_is_file)
case("frames-out-user-folder", F, "--out {t}/out", ("--out", "other content", "new or empty folder"),
     "--out is a user's folder with files (never deleted)", setup=user_folder)
case("frames-out-other-command", F, "--out {t}/out", ("--out", "irnuc calibrate", "another folder"),
     "--out holds another command's output", setup=other_kind("calibrate"))
case("frames-out-link", F, "--out {t}/out", ("--out", "symbolic link"), "--out is a symbolic link",
     setup=link_out)
case("frames-out-under-file", F, "--out {t}/plain/out", ("--out", "not a folder"),
     "--out below a regular file", setup=out_under_file)
case("frames-out-cwd", F, "--out .", ("--out", "current folder"), "--out is the current folder",
     check_out=False)
case("frames-out-parent-of-cwd", F, "--out ..", ("--out", "current folder"),
     "--out holds the current folder", check_out=False)
case("frames-out-root", F, "--out /", ("--out", "root folder"), "--out is /", check_out=False)
case("frames-out-empty", F, "--out=", ("--out", "empty"), "--out is an empty string", check_out=False)


def _sensor_in_out(w: Path, t: Path) -> None:
    (t / "out").mkdir()
    shutil.copy(w / "sensor_ok.toml", t / "out" / "s.toml")
    (t / "out" / ".irnuc-output").write_text("irnuc frames\n")


case("frames-out-holds-sensor", F, "--sensor {t}/out/s.toml --out {t}/out",
     ("--out", "--sensor", "would replace"), "--out holds the sensor file it reads",
     setup=_sensor_in_out)
case("frames-out-read-only-parent", F, "--out {t}/ro/out", ("--out", "no permission"),
     "--out inside a read-only folder", setup=ro_parent)


# ---- drift sequences (issue 42) ------------------------------------------------------------
SEQ = ("[sequence]\nframe_rate = 30.0\nduration = 0.5\nfpa = 300.0\nhousing = 300.0\n"
       "scene = 300.0\n")
SQ = "--sequence s.toml --set fpa.active_rows=6 --set fpa.active_cols=8"


def _table_inside_out(w: Path, t: Path) -> None:
    (t / "out").mkdir()
    (t / "out" / ".irnuc-output").write_text("irnuc frames\n")
    (t / "out" / "t.csv").write_text("0,300\n1,310\n")
    (t / "s.toml").write_text(SEQ.replace("scene = 300.0\n", "[sequence.scene]\n"
                                          'profile = "table"\nfile = "out/t.csv"\n'))


def _table_huge(w: Path, t: Path) -> None:
    with (t / "big.csv").open("wb") as fh:
        fh.truncate(20 * 2**30)  # sparse: 20 GiB that take no room
    (t / "s.toml").write_text(SEQ.replace("scene = 300.0\n", "[sequence.scene]\n"
                                          'profile = "table"\nfile = "big.csv"\n'))


case("frames-sequence-table-inside-out", F, SQ, ("--out", "sequence.scene.file", "would replace"),
     "a sequence's table CSV inside --out (read, then deleted with the folder it replaced)",
     setup=_table_inside_out)
case("frames-sequence-table-huge", F, SQ, ("--sequence", "sequence.scene.file", "larger than"),
     "a 20 GB sparse file as a sequence's table CSV (read whole)", setup=_table_huge)
case("frames-sequence-rate-bool", F, SQ, ("--sequence", "sequence.frame_rate = True",
                                          "not a number"),
     "frame_rate = true (taken as 1 Hz)",
     setup=write_file("s.toml", SEQ.replace("frame_rate = 30.0", "frame_rate = true")))
case("frames-sequence-rate-string", F, SQ, ("--sequence", "sequence.frame_rate = '30'",
                                            "not a number"),
     'frame_rate = "30" (taken as 30 Hz)',
     setup=write_file("s.toml", SEQ.replace("frame_rate = 30.0", 'frame_rate = "30"')))
case("frames-sequence-sensor-bool", F, SQ, ("--sequence", "sequence.fpa_sensor.bits = True"),
     "fpa_sensor.bits = true (named without its sequence table)",
     setup=write_file("s.toml", SEQ + "[sequence.fpa_sensor]\nbits = true\n"))
case("frames-sequence-shutter-after-end", F, SQ,
     ("--sequence", "sequence.shutter.at[1] = 0.6 s", "after the last frame"),
     "a shutter closing after the sequence's end (never closed, exit 0)",
     setup=write_file("s.toml", SEQ + "[sequence.shutter]\nframes = 2\nat = [0.1, 0.6]\n"))
case("frames-sequence-shutter-start-after-end", F, SQ,
     ("--sequence", "sequence.shutter.start = 2 s", "after the last frame"),
     "a periodic shutter starting after the sequence's end",
     setup=write_file("s.toml", SEQ + "[sequence.shutter]\nframes = 2\nevery = 1.0\nstart = 2.0\n"))
