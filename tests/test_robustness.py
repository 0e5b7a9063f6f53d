"""Hostile and careless use of every command and of the API (issue 12).

Tables of cases, each run by one parametrized test:

* :data:`CLI_CASES`: bad arguments, configuration files, input files, manifests, baselines
  and output folders for every command. Each must end with exit status 2 and ONE line on
  stderr (``irnuc COMMAND: error: ...``) that names the flag, file or dotted field, with
  no traceback, before the command's work starts (the work is replaced by a tripwire),
  and with the output name exactly as it was (nothing created, nothing replaced, no
  temporary folder left).
* :data:`API_CASES`: the model and golden-model API raise ``ValueError`` naming the
  argument for bad shapes, dtypes, empty or non-finite input; any integer byte order is
  accepted and gives the native result.
* :data:`BYTE_ORDER_CASES`: the same calls with arrays of the other byte order or strided.
* :data:`FAULTS`: SIGKILL of ``irnuc calibrate`` at random points and two calibrations on
  one ``--out``: the folder is always the old result or the new one, whole.
* :data:`MEASURED`: the memory estimates checked before the work stay above measured peaks.

``docs/robustness.md`` is generated from these tables (``python tests/test_robustness.py``
rewrites it) and :func:`test_doc_lists_every_case` keeps it in step.
"""

from __future__ import annotations

import contextlib
import hashlib
import importlib
import io
import json
import os
import random
import shlex
import shutil
import signal
import subprocess
import sys
import time
import zipfile
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
import pytest

REPO = Path(__file__).resolve().parents[1]
DOC = REPO / "docs" / "robustness.md"

# ---------------------------------------------------------------------------------------
# The command-line table
# ---------------------------------------------------------------------------------------


@dataclass(frozen=True)
class Case:
    """One hostile command line.

    ``args`` is split like a shell line; ``{w}`` is the shared folder of valid and hostile
    input files (:func:`world`), ``{t}`` the case's own folder (also the current folder).
    ``--out {t}/out`` is added unless the case gives ``--out``. ``names`` must all appear in
    the one-line message. ``setup(w, t)`` prepares the case's own files.
    """

    id: str
    command: str
    args: str
    names: tuple[str, ...]
    what: str
    setup: Callable[[Path, Path], None] | None = None
    xfail: str | None = None
    before_work: bool = True  # False: the problem is only visible in the data being worked on
    check_out: bool = True    # False for --out values that are no path of the case's own


CLI_CASES: list[Case] = []


def case(id: str, command: str, args: str, names: tuple[str, ...] | str, what: str,
         **kw: Any) -> None:
    CLI_CASES.append(Case(id, command, args, (names,) if isinstance(names, str) else names,
                          what, **kw))


# ---- case setups (files in the case's own folder) --------------------------------------

def _write(name: str, content: str | bytes) -> Callable[[Path, Path], None]:
    def setup(w: Path, t: Path) -> None:
        p = t / name
        p.parent.mkdir(parents=True, exist_ok=True)
        p.write_bytes(content if isinstance(content, bytes) else content.encode())
    return setup


def _user_folder(w: Path, t: Path) -> None:
    (t / "out").mkdir()
    (t / "out" / "thesis.tex").write_text("years of work\n")


def _other_kind(kind: str) -> Callable[[Path, Path], None]:
    def setup(w: Path, t: Path) -> None:
        (t / "out").mkdir()
        (t / "out" / ".irnuc-output").write_text(f"irnuc {kind}\n")
        (t / "out" / "result.bin").write_bytes(b"\x00")
    return setup


def _link_out(w: Path, t: Path) -> None:
    (t / "elsewhere").mkdir()
    (t / "out").symlink_to(t / "elsewhere")


def _out_is_file(w: Path, t: Path) -> None:
    (t / "out").write_text("not a folder\n")


def _out_under_file(w: Path, t: Path) -> None:
    (t / "plain").write_text("a file\n")


def _frames_in_out(w: Path, t: Path) -> None:
    (t / "out").mkdir()
    shutil.copy(w / "good.npz", t / "out" / "frames.npz")
    (t / "out" / ".irnuc-output").write_text("irnuc calibrate\n")


def _coeffs_copy(mutate: Callable[[Path], None] | None = None, rehash: bool = False
                 ) -> Callable[[Path, Path], None]:
    """A copy of the valid calibration in ``{t}/cal``, changed by ``mutate``; with
    ``rehash`` the manifest's hashes are recomputed, so the deeper checks are reached."""
    def setup(w: Path, t: Path) -> None:
        shutil.copytree(w / "cal", t / "cal")
        if mutate is not None:
            mutate(t / "cal")
        if rehash:
            _rehash(t / "cal")
    return setup


def _manifest(folder: Path) -> dict[str, Any]:
    return json.loads((folder / "manifest.json").read_text())


def _set_manifest(folder: Path, m: Any) -> None:
    (folder / "manifest.json").write_text(json.dumps(m))


def _rehash(folder: Path) -> None:
    from irnuc.nuc_fixed.memimage import _FORMAT_FIELDS, _format_sha256

    m = _manifest(folder)
    m["files"] = {n: hashlib.sha256((folder / n).read_bytes()).hexdigest()
                  for n in m["files"] if (folder / n).is_file()}
    m["sha256"] = m["files"].get("coeffs.bin", m.get("sha256"))
    m["format_sha256"] = _format_sha256({k: m.get(k) for k in _FORMAT_FIELDS})
    _set_manifest(folder, m)


def _edit_manifest(**fields: Any) -> Callable[[Path], None]:
    def mutate(folder: Path) -> None:
        m = _manifest(folder)
        for k, v in fields.items():
            if v is _DELETE:
                m.pop(k, None)
            else:
                m[k] = v
        _set_manifest(folder, m)
    return mutate


_DELETE = object()


def _edit_file(name: str, change: Callable[[bytes], bytes]) -> Callable[[Path], None]:
    def mutate(folder: Path) -> None:
        p = folder / name
        p.write_bytes(change(p.read_bytes()))
    return mutate


def _flip_first_hex_digit(data: bytes) -> bytes:
    first = data[:1]
    return (b"1" if first != b"1" else b"2") + data[1:]


def _ro_parent(w: Path, t: Path) -> None:
    ro = t / "ro"
    ro.mkdir()
    _make_read_only(ro)


def _make_read_only(path: Path) -> None:
    """A folder nobody may write into: immutable when run as root (root ignores modes)."""
    if os.geteuid() == 0:
        r = subprocess.run(["chattr", "+i", str(path)], capture_output=True)
        if r.returncode != 0:
            pytest.skip("cannot make a read-only folder as root here (no chattr +i)")
    else:
        path.chmod(0o555)


def _undo_read_only(path: Path) -> None:
    if os.geteuid() == 0:
        subprocess.run(["chattr", "-i", str(path)], capture_output=True)
    with contextlib.suppress(OSError):
        path.chmod(0o755)


def _stale_tmp(w: Path, t: Path) -> None:
    # A killed run's temporary folder beside the output: ignored and removed safely.
    (t / ".out.tmp-killed").mkdir()
    (t / ".out.tmp-killed" / "coeffs.npz").write_bytes(b"half")


# ---- frames -----------------------------------------------------------------------------

F = "frames"
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
     setup=_write("map.npy", "hello"))
case("frames-scene-map-image-garbage", F, "--scene map --scene-param path={t}/map.png",
     ("scene.path", "not a readable image"), "garbage as the image map",
     setup=_write("map.png", b"\x89PNG garbage"))
case("frames-scene-map-shape", F, "--scene map --scene-param path={w}/map_3x3.npy",
     ("--scene-param", "shape (3, 3)"), "a map of the wrong size")
case("frames-scene-map-folder", F, "--scene map --scene-param path={w}",
     ("scene.path", "no such file"), "a folder as the map")
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
     setup=_out_is_file)
case("frames-out-user-folder", F, "--out {t}/out", ("--out", "other content", "new or empty folder"),
     "--out is a user's folder with files (never deleted)", setup=_user_folder)
case("frames-out-other-command", F, "--out {t}/out", ("--out", "irnuc calibrate", "another folder"),
     "--out holds another command's output", setup=_other_kind("calibrate"))
case("frames-out-link", F, "--out {t}/out", ("--out", "symbolic link"), "--out is a symbolic link",
     setup=_link_out)
case("frames-out-under-file", F, "--out {t}/plain/out", ("--out", "not a folder"),
     "--out below a regular file", setup=_out_under_file)
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
     "--out inside a read-only folder", setup=_ro_parent)

# ---- calibrate --------------------------------------------------------------------------

K = "calibrate"
G = "--frames {w}/good.npz"
case("calibrate-no-frames", K, "", ("--frames", "required"), "--frames missing")
case("calibrate-t-low-text", K, f"{G} --t-low warm", ("--t-low", "invalid float"), "--t-low not a number")
case("calibrate-rounding-unknown", K, f"{G} --coeff-rounding nearest",
     ("--coeff-rounding", "invalid choice"), "an unknown rounding")
case("calibrate-frames-missing", K, "--frames {t}/none.npz", ("--frames", "no such file"),
     "frames that do not exist")
case("calibrate-frames-folder-without", K, "--frames {t}", ("--frames", "without frames.npz"),
     "a folder without frames.npz")
case("calibrate-frames-empty-file", K, "--frames {w}/empty.npz", ("--frames", "not an .npz"),
     "an empty file")
case("calibrate-frames-text", K, "--frames {w}/text.npz", ("--frames", "not an .npz", "text"),
     "a text file as .npz (not called pickled data)")
case("calibrate-frames-npy", K, "--frames {w}/npy.npz", ("--frames", "not an .npz", ".npy"),
     "a .npy passed as .npz")
case("calibrate-frames-truncated", K, "--frames {w}/truncated.npz", ("--frames", "not an .npz"),
     "a truncated .npz")
case("calibrate-frames-corrupt-data", K, "--frames {w}/corrupt.npz", ("--frames", "damaged"),
     "an .npz whose compressed data is corrupt")
case("calibrate-frames-zip-of-text", K, "--frames {w}/zip_text.npz", ("--frames", "missing key"),
     "a zip archive without arrays")
case("calibrate-frames-no-codes", K, "--frames {w}/no_codes.npz", ("--frames", "missing key", "codes"),
     "no codes array")
case("calibrate-frames-no-temps", K, "--frames {w}/no_temps.npz", ("--frames", "temps"), "no temps array")
case("calibrate-frames-no-adc", K, "--frames {w}/no_adc.npz", ("--frames", "adc_bits"),
     "no adc_bits")
case("calibrate-codes-float", K, "--frames {w}/codes_float.npz", ("--frames", "codes", "integer"),
     "float codes")
case("calibrate-codes-bool", K, "--frames {w}/codes_bool.npz", ("--frames", "codes", "integer"),
     "boolean codes")
case("calibrate-codes-2d", K, "--frames {w}/codes_2d.npz", ("--frames", "codes", "(N, H, W)"),
     "one frame without the frame axis")
case("calibrate-codes-4d", K, "--frames {w}/codes_4d.npz", ("--frames", "codes", "(N, H, W)"),
     "a 4-D code array")
case("calibrate-codes-zero-frames", K, "--frames {w}/zero_frames.npz", ("--frames", "shape (0,"),
     "zero frames (not a numpy reduction error)")
case("calibrate-codes-zero-width", K, "--frames {w}/zero_width.npz", ("--frames", "codes", "N, H, W >= 1"),
     "frames of width 0")
case("calibrate-codes-object", K, "--frames {w}/codes_object.npz", ("--frames", "codes", "object array"),
     "an object (pickled) array")
case("calibrate-codes-negative", K, "--frames {w}/codes_negative.npz", ("--frames", "codes span", "outside"),
     "negative codes")
case("calibrate-codes-above-adc", K, "--frames {w}/codes_above.npz", ("--frames", "codes span", "adc_bits"),
     "codes above the ADC range")
case("calibrate-temps-strings", K, "--frames {w}/temps_str.npz", ("--frames", "temps", "numbers"),
     "temperatures stored as strings")
case("calibrate-temps-nan", K, "--frames {w}/temps_nan.npz", ("--frames", "temps[0]", "finite"),
     "a NaN frame temperature (not blamed on --t-low)")
case("calibrate-temps-negative", K, "--frames {w}/temps_neg.npz", ("--frames", "temps[", "above 0"),
     "a negative frame temperature")
case("calibrate-temps-length", K, "--frames {w}/temps_len.npz",
     ("--frames", "temps", "one temperature per frame"),
     "fewer temperatures than frames")
case("calibrate-temps-complex", K, "--frames {w}/temps_complex.npz", ("--frames", "temps", "numbers"),
     "complex temperatures")
case("calibrate-adc-array", K, "--frames {w}/adc_array.npz", ("--frames", "adc_bits", "one integer"),
     "adc_bits stored as an array")
case("calibrate-adc-float", K, "--frames {w}/adc_float.npz", ("--frames", "adc_bits", "one integer"),
     "adc_bits as a float")
case("calibrate-adc-zero", K, "--frames {w}/adc_zero.npz", ("--frames", "adc_bits", "1..24"), "0 ADC bits")
case("calibrate-adc-mismatch", K, "--frames {w}/adc_12.npz", ("--frames", "adc_bits = 12", "typical14"),
     "frames of another ADC width than the pipeline")
case("calibrate-one-temperature", K, "--frames {w}/one_temp.npz", ("--t-low", "--t-high", "two temperatures"),
     "frames at one temperature only")
case("calibrate-header-bomb", K, "--frames {w}/bomb.npz", ("--frames", "needs an estimated", "codes"),
     "an .npz whose header claims 10^5 frames of 16384 x 16384 (checked before loading)")
case("calibrate-frame-too-large", K, "--frames {w}/too_wide.npz --pipeline minimal",
     ("--frames", "frame size", "allows"), "frames wider than the pipeline's maximum", before_work=False)
case("calibrate-all-stuck", K, "--frames {w}/stuck.npz", ("--frames", "no usable pixel"),
     "every pixel stuck", before_work=False)
case("calibrate-swapped", K, "--frames {w}/swapped.npz", ("--frames", "median response", "swapped"),
     "low and high temperatures swapped", before_work=False)
case("calibrate-t-low-no-match", K, f"{G} --t-low 310", ("--t-low", "matches no frame"),
     "--t-low that no frame has")
case("calibrate-t-low-nan", K, f"{G} --t-low nan", ("--t-low", "finite"), "--t-low NaN")
case("calibrate-t-low-negative", K, f"{G} --t-low=-5", ("--t-low", "above 0"), "--t-low negative")
case("calibrate-t-high-zero", K, f"{G} --t-high 0", ("--t-high", "above 0"), "--t-high 0 K")
case("calibrate-t-reversed", K, f"{G} --t-low 400 --t-high 300", ("--t-low", "below --t-high"),
     "--t-low above --t-high")
case("calibrate-targets-one", K, f"{G} --targets 1000", ("--targets", "two numbers"), "one target")
case("calibrate-targets-three", K, f"{G} --targets 1,2,3", ("--targets", "two numbers"), "three targets")
case("calibrate-targets-text", K, f"{G} --targets a,b", ("--targets", "list of numbers"), "targets as words")
case("calibrate-targets-nan", K, f"{G} --targets nan,1000", ("--targets", "finite"), "a NaN target")
case("calibrate-targets-negative", K, f"{G} --targets=-1,1000", ("--targets", "0..16383"),
     "a negative target")
case("calibrate-targets-above", K, f"{G} --targets 0,99999", ("--targets", "0..16383"),
     "a target above the output range")
case("calibrate-set-no-equals", K, f"{G} --set low_response", ("--set", "KEY=VALUE"), "--set without =")
case("calibrate-set-typo", K, f"{G} --set low_respons=0.3", ("--set", "did you mean 'low_response'"),
     "a misspelled threshold")
case("calibrate-set-text", K, f"{G} --set low_response=high", ("--set", "low_response", "number"),
     "a threshold as a word")
case("calibrate-thresholds-missing", K, f"{G} --thresholds {{t}}/none.toml", ("--thresholds", "no such file"),
     "a thresholds file that does not exist")
case("calibrate-thresholds-folder", K, f"{G} --thresholds {{w}}", ("--thresholds", "is a folder"),
     "a folder as --thresholds")
case("calibrate-thresholds-malformed", K, f"{G} --thresholds {{w}}/bad.toml",
     ("--thresholds", "bad.toml", "not valid TOML"), "malformed thresholds TOML")
case("calibrate-thresholds-no-default", K, f"{G} --thresholds {{w}}/th_other.toml",
     ("--thresholds", "no [default] table"), "thresholds without [default]")
case("calibrate-thresholds-scalar", K, f"{G} --thresholds {{w}}/th_scalar.toml",
     ("--thresholds", "[default] must be a table"), "default = 3")
case("calibrate-thresholds-unknown", K, f"{G} --thresholds {{w}}/th_unknown.toml",
     ("--thresholds", "default.low_respons", "did you mean"), "a misspelled threshold in the file")
case("calibrate-thresholds-range", K, f"{G} --thresholds {{w}}/th_range.toml",
     ("--thresholds", "default.low_response"), "a threshold out of range in the file")
case("calibrate-pipeline-unknown", K, f"{G} --pipeline typical41", ("--pipeline", "did you mean 'typical14'"),
     "a misspelled pipeline")
case("calibrate-pipeline-missing", K, f"{G} --pipeline {{t}}/none.toml", ("--pipeline", "no such file"),
     "a pipeline file that does not exist")
case("calibrate-pipeline-malformed", K, f"{G} --pipeline {{w}}/bad.toml",
     ("--pipeline", "bad.toml", "not valid TOML"), "malformed pipeline TOML")
case("calibrate-pipeline-empty", K, f"{G} --pipeline {{w}}/empty.toml", ("--pipeline", "no pipeline table"),
     "an empty pipeline file")
case("calibrate-pipeline-two", K, f"{G} --pipeline {{w}}/pipe_two.toml", ("--pipeline", "holds 2 pipelines"),
     "two pipelines, none named")
case("calibrate-pipeline-no-table", K, f"{G} --pipeline {{w}}/pipe_two.toml:nope",
     ("--pipeline", "no pipeline [nope]"), "FILE:NAME with an unknown NAME")
case("calibrate-pipeline-scalar", K, f"{G} --pipeline {{w}}/pipe_scalar.toml",
     ("--pipeline", "must be a table"),
     "a pipeline that is a number")
case("calibrate-pipeline-unknown-field", K, f"{G} --pipeline {{w}}/pipe_unknown.toml",
     ("--pipeline", "adc_bitz", "did you mean"), "a misspelled pipeline field")
case("calibrate-pipeline-type", K, f"{G} --pipeline {{w}}/pipe_type.toml",
     ("--pipeline", "p.adc_bits", "integer"), "adc_bits as a string")
case("calibrate-pipeline-range", K, f"{G} --pipeline {{w}}/pipe_range.toml",
     ("--pipeline", "p.out_bits", "allowed range"), "out_bits out of range")
case("calibrate-out-file", K, f"{G} --out {{t}}/out", ("--out", "not a folder"), "--out is a regular file",
     setup=_out_is_file)
case("calibrate-out-user-folder", K, f"{G} --out {{t}}/out", ("--out", "other content"),
     "--out is a user's folder (never deleted)", setup=_user_folder)
case("calibrate-out-frames-output", K, f"{G} --out {{t}}/out", ("--out", "irnuc frames"),
     "--out holds the output of irnuc frames", setup=_other_kind("frames"))
case("calibrate-out-holds-frames", K, "--frames {t}/out/frames.npz --out {t}/out",
     ("--out", "--frames", "would replace"), "--out holds the frames it reads", setup=_frames_in_out)
case("calibrate-out-link", K, f"{G} --out {{t}}/out", ("--out", "symbolic link"), "--out is a link",
     setup=_link_out)
case("calibrate-out-cwd", K, f"{G} --out .", ("--out", "current folder"), "--out is the current folder",
     check_out=False)
case("calibrate-out-read-only-parent", K, f"{G} --out {{t}}/ro/out", ("--out", "no permission"),
     "--out inside a read-only folder", setup=_ro_parent)
case("calibrate-stale-tmp-and-bad-frames", K, "--frames {w}/text.npz --out {t}/out", ("--frames",),
     "a killed run's temporary folder beside --out, then a bad input", setup=_stale_tmp)

# ---- correct ----------------------------------------------------------------------------

R = "correct"
CF = "--frames {w}/good.npz --coeffs {t}/cal"
case("correct-no-coeffs", R, "--frames {w}/good.npz", ("--coeffs", "required"), "--coeffs missing")
case("correct-source-unknown", R, f"{CF} --source rom", ("--source", "invalid choice"), "an unknown --source",
     setup=_coeffs_copy())
case("correct-coeffs-missing", R, "--frames {w}/good.npz --coeffs {t}/none", ("--coeffs", "not a folder"),
     "a coefficient folder that does not exist")
case("correct-coeffs-file", R, "--frames {w}/good.npz --coeffs {w}/good.npz", ("--coeffs", "not a folder"),
     "a file as --coeffs")
case("correct-no-manifest", R, CF, ("--coeffs", "no manifest.json"), "a folder without manifest",
     setup=_coeffs_copy(lambda d: (d / "manifest.json").unlink()))
case("correct-manifest-list", R, CF, ("--coeffs", "manifest.json", "list"), "a manifest that is a JSON list",
     setup=_coeffs_copy(lambda d: _set_manifest(d, [])))
case("correct-manifest-not-json", R, CF, ("--coeffs", "manifest.json", "not a readable JSON"),
     "a manifest that is not JSON", setup=_coeffs_copy(lambda d: (d / "manifest.json").write_text("{")))
case("correct-manifest-binary", R, CF, ("--coeffs", "manifest.json", "not a readable JSON"),
     "binary garbage as manifest",
     setup=_coeffs_copy(lambda d: (d / "manifest.json").write_bytes(bytes(range(256)))))
case("correct-manifest-version", R, CF, ("--coeffs", "version = 2"), "a manifest of a newer version",
     setup=_coeffs_copy(_edit_manifest(version=2)))
case("correct-manifest-no-files", R, CF, ("--coeffs", "'files'"), "a manifest without files",
     setup=_coeffs_copy(_edit_manifest(files=_DELETE)))
case("correct-manifest-files-list", R, CF, ("--coeffs", "'files'", "JSON object"), "files is a list",
     setup=_coeffs_copy(_edit_manifest(files=["coeffs.bin"])))
case("correct-manifest-height-text", R, CF, ("--coeffs", "'height'", "an integer"), "height as a string",
     setup=_coeffs_copy(_edit_manifest(height="6")))
case("correct-manifest-bool-width", R, CF, ("--coeffs", "'width'", "an integer"), "width as true",
     setup=_coeffs_copy(_edit_manifest(width=True)))
case("correct-manifest-unhashed-hex", R, CF, ("--coeffs", "coeffs.hex", "hashed"),
     "a manifest that leaves the $readmemh file unhashed",
     setup=_coeffs_copy(lambda d: _edit_manifest(files={
         k: v for k, v in _manifest(d)["files"].items() if k != "coeffs.hex"})(d)))
case("correct-manifest-rounding-edited", R, CF, ("--coeffs", "format fields", "edited"),
     "rounding edited in manifest.json (would change every pixel)",
     setup=_coeffs_copy(_edit_manifest(rounding="truncate")))
case("correct-manifest-out-bits-edited", R, CF, ("--coeffs", "format fields", "edited"),
     "out_bits edited in manifest.json", setup=_coeffs_copy(_edit_manifest(out_bits=12)))
case("correct-manifest-adc-text-rehashed", R, CF, ("--coeffs", "adc_bits"),
     "adc_bits a string, hashes recomputed", setup=_coeffs_copy(_edit_manifest(adc_bits="14"), rehash=True))
case("correct-manifest-adc-list-rehashed", R, CF, ("--coeffs", "adc_bits"),
     "adc_bits a list, hashes recomputed", setup=_coeffs_copy(_edit_manifest(adc_bits=[14]), rehash=True))
case("correct-manifest-rounding-unknown-rehashed", R, CF, ("--coeffs", "rounding"),
     "an unknown rounding, hashes recomputed",
     setup=_coeffs_copy(_edit_manifest(rounding="stochastic"), rehash=True))
case("correct-manifest-word-bits", R, CF, ("--coeffs", "manifest.json", "word_bits = 64"),
     "word_bits that the formats contradict",
     setup=_coeffs_copy(_edit_manifest(word_bits=64)))
case("correct-manifest-size-rehashed", R, CF, ("--coeffs", "coeffs.bin", "bytes"),
     "height changed, hashes recomputed", setup=_coeffs_copy(_edit_manifest(height=7), rehash=True))
case("correct-manifest-config-missing", R, CF, ("--coeffs", "manifest.json", "['config']"), "no config name",
     setup=_coeffs_copy(_edit_manifest(config=_DELETE)))
case("correct-manifest-file-path", R, CF, ("--coeffs", "plain name"), "a file name with a path",
     setup=_coeffs_copy(lambda d: _edit_manifest(files={**_manifest(d)["files"], "../x": "0"})(d)))
case("correct-bin-missing", R, CF, ("--coeffs", "coeffs.bin", "missing"), "coeffs.bin deleted",
     setup=_coeffs_copy(lambda d: (d / "coeffs.bin").unlink()))
case("correct-bin-changed", R, CF, ("--coeffs", "coeffs.bin", "SHA-256"), "one byte of coeffs.bin changed",
     setup=_coeffs_copy(_edit_file("coeffs.bin", lambda b: bytes([b[0] ^ 1]) + b[1:])))
case("correct-bin-truncated", R, CF, ("--coeffs", "coeffs.bin", "SHA-256"), "coeffs.bin truncated",
     setup=_coeffs_copy(_edit_file("coeffs.bin", lambda b: b[:-3])))
case("correct-hex-changed", R, CF, ("--coeffs", "coeffs.hex", "SHA-256"),
     "the $readmemh file changed (checked with --source bin too)",
     setup=_coeffs_copy(_edit_file("coeffs.hex", _flip_first_hex_digit)))
case("correct-hex-missing", R, CF + " --source hex", ("--coeffs", "coeffs.hex", "missing"),
     "coeffs.hex deleted", setup=_coeffs_copy(lambda d: (d / "coeffs.hex").unlink()))
case("correct-hex-disagrees-rehashed", R, CF, ("--coeffs", "coeffs.hex", "differs from the binary"),
     "hex and binary disagree, hashes recomputed",
     setup=_coeffs_copy(_edit_file("coeffs.hex", _flip_first_hex_digit), rehash=True))
case("correct-hex-garbage-rehashed", R, CF, ("--coeffs", "coeffs.hex", "line 1"),
     "a non-hex line, hashes recomputed",
     setup=_coeffs_copy(_edit_file("coeffs.hex", lambda b: b"zz" + b[2:]), rehash=True))
case("correct-hex-negative-rehashed", R, CF, ("--coeffs", "coeffs.hex", "line 1", "not hexadecimal"),
     "a word with a minus sign (which int() would take), hashes recomputed",
     setup=_coeffs_copy(_edit_file("coeffs.hex", lambda b: b"-" + b[1:]), rehash=True))
case("correct-hex-binary-rehashed", R, CF, ("--coeffs", "coeffs.hex", "not ASCII"),
     "binary garbage as the hex file, hashes recomputed",
     setup=_coeffs_copy(_edit_file("coeffs.hex", lambda b: bytes(range(128, 256)) + b), rehash=True))
case("correct-npz-changed", R, CF, ("--coeffs", "coeffs.npz", "SHA-256"), "coeffs.npz of another run",
     setup=_coeffs_copy(_edit_file("coeffs.npz", lambda b: b + b"\0")))
case("correct-summary-changed", R, CF, ("--coeffs", "summary.json", "SHA-256"), "summary.json edited",
     setup=_coeffs_copy(_edit_file("summary.json", lambda b: b.replace(b"{", b"{ ", 1))))
case("correct-mixed-runs", R, CF, ("--coeffs", "coeffs.bin", "another run"),
     "coeffs.bin of another calibration beside this manifest (a mixed folder)",
     setup=lambda w, t: (_coeffs_copy()(w, t), shutil.copy(w / "cal2.bin", t / "cal" / "coeffs.bin")))
case("correct-pipeline-mismatch", R, CF + " --pipeline minimal",
     ("--coeffs", "differ from pipeline 'minimal'"),
     "coefficients made for another pipeline", setup=_coeffs_copy())
case("correct-pipeline-unknown", R, CF + " --pipeline nope", ("--pipeline", "nope"), "an unknown pipeline",
     setup=_coeffs_copy())
case("correct-frames-shape", R, "--frames {w}/other_shape.npz --coeffs {t}/cal",
     ("--frames", "7 x 8", "6 x 8"),
     "frames of another size than the coefficients", setup=_coeffs_copy())
case("correct-frames-adc", R, "--frames {w}/adc_12.npz --coeffs {t}/cal", ("--frames", "adc_bits = 12"),
     "frames of another ADC width", setup=_coeffs_copy())
case("correct-frames-missing", R, "--frames {t}/none.npz --coeffs {t}/cal", ("--frames", "no such file"),
     "frames that do not exist", setup=_coeffs_copy())
case("correct-frames-text", R, "--frames {w}/text.npz --coeffs {t}/cal", ("--frames", "not an .npz"),
     "a text file as frames", setup=_coeffs_copy())
case("correct-header-bomb", R, "--frames {w}/bomb.npz --coeffs {t}/cal", ("--frames", "needs an estimated"),
     "an .npz whose header claims petabytes", setup=_coeffs_copy())
case("correct-out-is-coeffs", R, CF + " --out {t}/cal", ("--out", "--coeffs", "would replace"),
     "--out is the coefficient folder it reads", setup=_coeffs_copy())
case("correct-out-file", R, CF + " --out {t}/out", ("--out", "not a folder"), "--out is a file",
     setup=lambda w, t: (_coeffs_copy()(w, t), _out_is_file(w, t)))
case("correct-out-user-folder", R, CF + " --out {t}/out", ("--out", "other content"),
     "--out is a user's folder", setup=lambda w, t: (_coeffs_copy()(w, t), _user_folder(w, t)))
case("correct-out-calibration", R, CF + " --out {t}/out", ("--out", "irnuc calibrate"),
     "--out holds a calibration", setup=lambda w, t: (_coeffs_copy()(w, t), _other_kind("calibrate")(w, t)))

# ---- sweep ------------------------------------------------------------------------------

S = "sweep"
case("sweep-gain-frac-huge", S, "--gain-frac 0:1000000000", ("--gain-frac", "at most 4096"),
     "a range of 10^9 values (refused before it is built)")
case("sweep-gain-frac-text", S, "--gain-frac x", ("--gain-frac", "LO:HI"), "a list that is a word")
case("sweep-gain-frac-empty", S, "--gain-frac ,", ("--gain-frac", "no value"), "an empty list")
case("sweep-gain-frac-reversed", S, "--gain-frac 5:3", ("--gain-frac", "no value"), "a reversed range")
case("sweep-gain-frac-step-zero", S, "--gain-frac 0:10:0", ("--gain-frac", "LO:HI:STEP"), "a zero step")
case("sweep-gain-frac-range", S, "--gain-frac 99", ("gain_frac_bits", "allowed range"), "99 fraction bits")
case("sweep-offset-frac-word", S, "--offset-frac many", ("--offset-frac", "same"), "an unknown word")
case("sweep-gain-int-negative", S, "--gain-int=-1", ("gain_int_bits", "allowed range"),
     "negative integer bits")
case("sweep-adc-bits-zero", S, "--adc-bits 0", ("adc_bits", "allowed range"), "0 ADC bits")
case("sweep-out-bits-huge", S, "--out-bits 99", ("out_bits", "allowed range"), "99 output bits")
case("sweep-rounding-unknown", S, "--rounding nearest", ("--rounding", "half_even"), "an unknown rounding")
case("sweep-coeff-rounding-empty", S, "--coeff-rounding ,", ("--coeff-rounding",), "no rounding")
case("sweep-metric-unknown", S, "--error-metric psnr", ("error metric", "err_max_lsb"), "an unknown metric")
case("sweep-max-error-nan", S, "--max-error nan", ("--max-error", "finite"), "a NaN error bound")
case("sweep-max-error-negative", S, "--max-error=-1", ("--max-error", "above 0"), "a negative bound")
case("sweep-workers-negative", S, "--workers=-1", ("--workers", "0..256"), "-1 workers")
case("sweep-workers-huge", S, "--workers 1000", ("--workers", "0..256"), "1000 workers")
case("sweep-scheduler-refused", S, "--scheduler tcp://127.0.0.1:1", ("--scheduler", "tcp://127.0.0.1:1"),
     "a Dask scheduler address nobody listens on (no 30 s wait)")
case("sweep-scheduler-no-port", S, "--scheduler tcp://localhost", ("--scheduler", "HOST:PORT"),
     "a scheduler address without a port")
case("sweep-rows-zero", S, "--rows 0", ("--rows", "1..16384"), "0 rows")
case("sweep-cols-negative", S, "--cols=-4", ("--cols", "1..16384"), "negative columns")
case("sweep-rows-huge", S, "--rows 100000", ("--rows", "1..16384"), "10^5 rows")
case("sweep-memory", S, "--rows 16384 --cols 16384 --repeats 10000",
     ("--rows x --cols", "needs an estimated", "available"), "16384 x 16384 frames, 2 x 10000 of them")
case("sweep-repeats-zero", S, "--repeats 0", ("repeats", "1..10000"), "zero repeats")
case("sweep-seed-negative", S, "--seed=-1", ("seed", "0..2^63-1"), "a negative seed")
case("sweep-t-low-nan", S, "--t-low nan", ("t_low", "allowed range"), "a NaN calibration temperature")
case("sweep-t-reversed", S, "--t-low 400 --t-high 300", ("t_low", "below"), "low above high")
case("sweep-t-eval-empty", S, "--t-eval ,", ("--t-eval", "no number"), "no evaluation temperature")
case("sweep-t-eval-text", S, "--t-eval warm", ("--t-eval", "list of numbers"), "a word")
case("sweep-t-eval-negative", S, "--t-eval=-1", ("t_eval", "allowed range"), "a negative temperature")
case("sweep-sensor-unknown", S, "--sensor nope", ("--sensor", "nope"), "an unknown preset")
case("sweep-sensor-missing", S, "--sensor {t}/none.toml", ("--sensor", "no such file"),
     "a missing sensor file")
case("sweep-sensor-malformed", S, "--sensor {w}/bad.toml", ("--sensor", "not valid TOML"), "malformed TOML")
case("sweep-sensor-unknown-key", S, "--sensor {w}/sensor_key.toml", ("--sensor", "fpa.activ_rows"),
     "a misspelled key in the sensor file")
case("sweep-pipeline-unknown", S, "--pipeline nope", ("--pipeline", "nope"), "an unknown pipeline")
case("sweep-pipeline-adc-mismatch", S, "--pipeline minimal", ("--pipeline", "adc_bits = 8", "--sensor"),
     "a pipeline whose ADC is not the sensor's (ran silently with the preset's widths)")
case("sweep-pipeline-malformed", S, "--pipeline {w}/bad.toml", ("--pipeline", "not valid TOML"),
     "malformed pipeline TOML")
case("sweep-set-typo", S, "--set fpa.activ_rows=1", ("fpa.activ_rows", "did you mean"), "a misspelled --set")
case("sweep-out-file", S, "--out {t}/out", ("--out", "not a folder"), "--out is a file", setup=_out_is_file)
case("sweep-out-user-folder", S, "--out {t}/out", ("--out", "other content"), "--out is a user's folder",
     setup=_user_folder)
case("sweep-out-other-command", S, "--out {t}/out", ("--out", "irnuc correct"),
     "--out holds another command's output", setup=_other_kind("correct"))
case("sweep-out-read-only-parent", S, "--out {t}/ro/out", ("--out", "no permission"),
     "--out inside a read-only folder", setup=_ro_parent)

# ---- report -------------------------------------------------------------------------------

P = "report"
NC = "--config small --no-cosim"
case("report-unknown-flag", P, "--cosim-off", ("--cosim-off", "unrecognized"), "an unknown flag")
case("report-config-no-value", P, "--config", ("--config", "expected one argument"), "--config without value")
case("report-config-missing", P, "--config {t}/none.toml", ("--config", "none.toml"), "a missing config file")
case("report-config-unknown-name", P, "--config smal", ("--config", "smal"), "an unknown embedded config")
case("report-config-folder", P, "--config {w}", ("--config",), "a folder as --config")
case("report-config-malformed", P, "--config {w}/bad.toml", ("--config", "bad.toml"), "malformed TOML")
case("report-config-binary", P, "--config {w}/binary.toml", ("--config", "binary.toml"),
     "binary garbage as TOML")
case("report-config-section-typo", P, "--config {w}/rep_section_typo.toml --no-cosim", ("--config", "sensr"),
     "a misspelled section (ran nothing and said PASS)")
case("report-config-key-typo", P, "--config {w}/rep_key_typo.toml --no-cosim", ("--config", "sensor.rowz"),
     "an unknown key beside the right ones")
case("report-config-missing-key", P, "--config {w}/rep_missing_key.toml --no-cosim", ("sensor.rows",),
     "a required key missing")
case("report-config-type", P, "--config {w}/rep_type.toml --no-cosim", ("sensor.rows",), "rows as a string")
case("report-config-range", P, "--config {w}/rep_range.toml --no-cosim", ("sensor.rows",), "rows = 1")
case("report-config-nan", P, "--config {w}/rep_nan.toml --no-cosim", ("sensor.t_low",), "t_low = nan")
case("report-config-section-scalar", P, "--config {w}/rep_scalar.toml --no-cosim", ("--config", "sensor"),
     "sensor = 3")
case("report-config-paper-lengths", P, "--config {w}/rep_paper.toml --no-cosim", ("paper.reference_nu",),
     "reference values and widths of different lengths")
case("report-config-quick-bad", P, "--config {w}/rep_quick.toml --quick --no-cosim", ("quick",),
     "a [quick] override into a non-table")
case("report-config-skimming", P, "--config {w}/rep_skim.toml --no-cosim", ("paper.table1.skimming",),
     "an unknown skimming mode")
case("report-baseline-missing", P, f"{NC} --baseline {{t}}/none.json", ("--baseline", "none.json"),
     "a missing baseline")
case("report-baseline-folder", P, f"{NC} --baseline {{w}}", ("--baseline",), "a folder as baseline")
case("report-baseline-not-json", P, f"{NC} --baseline {{w}}/base_notjson.json", ("--baseline",),
     "a baseline that is not JSON")
case("report-baseline-empty", P, f"{NC} --baseline {{w}}/empty.npz", ("--baseline",), "an empty baseline")
case("report-baseline-binary", P, f"{NC} --baseline {{w}}/binary.toml", ("--baseline",),
     "binary garbage as baseline")
case("report-baseline-list", P, f"{NC} --baseline {{w}}/base_list.json", ("--baseline", "metrics"),
     "a baseline that is a JSON list")
case("report-baseline-no-metrics", P, f"{NC} --baseline {{w}}/base_nometrics.json", ("--baseline", "metrics"),
     "a baseline without metrics")
case("report-baseline-metrics-list", P, f"{NC} --baseline {{w}}/base_metrics_list.json",
     ("--baseline", "metrics"), "metrics as a list")
case("report-baseline-metric-number", P, f"{NC} --baseline {{w}}/base_metric_number.json",
     ("--baseline",
     "calibration.bad_pixels"), "a metric that is a bare number (failed after the whole report)")
case("report-baseline-metric-string", P, f"{NC} --baseline {{w}}/base_metric_string.json",
     ("--baseline", "calibration.bad_pixels"), "a metric that is a string")
case("report-baseline-metric-list", P, f"{NC} --baseline {{w}}/base_metric_list.json",
     ("--baseline", "calibration.bad_pixels"), "a metric that is a list")
case("report-baseline-value-nan", P, f"{NC} --baseline {{w}}/base_nan.json",
     ("--baseline", "calibration.bad_pixels", "finite"), "a NaN baseline value (switched its comparison off)")
case("report-baseline-value-text", P, f"{NC} --baseline {{w}}/base_value_text.json",
     ("--baseline", "calibration.bad_pixels"), "a baseline value that is a string")
case("report-junit-missing", P, "--config small --junit {t}/none.xml", ("--junit", "none.xml"),
     "a missing JUnit file")
case("report-junit-folder", P, "--config small --junit {w}", ("--junit",), "a folder as --junit")
case("report-junit-malformed", P, "--config small --junit {w}/junit_bad.xml", ("--junit", "junit_bad.xml"),
     "a JUnit file that is not XML (read after the other phases)")
case("report-junit-root", P, "--config small --junit {w}/junit_root.xml", ("--junit", "junit_root.xml"),
     "XML that is not JUnit")
case("report-scheduler-refused", P, f"{NC} --scheduler tcp://127.0.0.1:1", ("--scheduler",),
     "an unreachable Dask scheduler (noticed in the sweep phase)")
case("report-config-cosim-test-typo", P, "--config {w}/rep_cosim_typo.toml",
     ("--config", "cosim.tests", "corner_codes"), "a misspelled co-simulation test")
case("report-config-sweep-adc", P, "--config {w}/rep_sweep_adc.toml --no-cosim",
     ("--config", "sweep.pipeline", "adc_bits"), "a sweep whose sensor ADC is not the pipeline's")
case("report-config-cosim-recommended-no-sweep", P, "--config {w}/rep_rec_nosweep.toml",
     ("--config", "recommended", "[sweep]"), "co-simulating a recommendation without a sweep")
case("report-out-file", P, f"{NC} --out {{t}}/out", ("out",), "--out is a file", setup=_out_is_file)
case("report-out-user-folder", P, f"{NC} --out {{t}}/out", ("--out",),
     "--out is a user's folder (written into)", setup=_user_folder)

# ---- precision (argument level only; being rewritten) -----------------------------------

Q = "precision"
case("precision-unknown-flag", Q, "--fast", ("--fast", "unrecognized"), "an unknown flag")
case("precision-only-no-value", Q, "--only", ("--only", "expected one argument"), "--only without value")
case("precision-extra-argument", Q, "--quick now", ("now", "unrecognized"), "a stray argument")
case("precision-only-unknown", Q, "--quick --only radiancee", ("--only", "band_radiance"),
     "an unknown component")
case("precision-out-file", Q, "--quick --out {t}/out", ("--out",), "--out is a file",
     setup=_out_is_file)
case("precision-out-user-folder", Q, "--quick --out {t}/out", ("--out",), "--out is a user's folder",
     setup=_user_folder)

# ---- synth ----------------------------------------------------------------------------

Y = "synth"
case("synth-no-pipeline", Y, "", ("--pipeline", "required"), "no --pipeline")
case("synth-pipeline-unknown", Y, "--pipeline typcal14", ("--pipeline", "did you mean"),
     "a misspelt configuration name")
case("synth-pipeline-missing-file", Y, "--pipeline {t}/none.toml", ("--pipeline", "no such file"),
     "a pipeline file that does not exist")
case("synth-pipeline-unknown-field", Y, "--pipeline {w}/pipe_unknown.toml",
     ("--pipeline", "adc_bitz"), "a pipeline file with an unknown field")
case("synth-pipeline-range", Y, "--pipeline {w}/pipe_range.toml", ("--pipeline", "out_bits"),
     "a pipeline field out of range")
case("synth-pipeline-twice", Y, "--pipeline minimal --pipeline minimal", ("--pipeline", "once"),
     "one configuration twice")
case("synth-max-width-zero", Y, "--pipeline minimal --max-width 0", ("--max-width", "1..65535"),
     "a zero line length")
case("synth-max-width-huge", Y, "--pipeline minimal --max-width 70000",
     ("--max-width", "1..65535"), "a line length beyond the RTL's range")
case("synth-max-height-text", Y, "--pipeline minimal --max-height tall",
     ("--max-height", "invalid int"), "a height that is a word")
case("synth-speed-grade", Y, "--pipeline minimal --speed 5", ("--speed", "invalid choice"),
     "a speed grade ECP5 does not have")
case("synth-freq-zero", Y, "--pipeline minimal --freq 0", ("--freq", "1..1000"),
     "a zero target clock")
case("synth-seed-negative", Y, "--pipeline minimal --seed -1", ("--seed", "0..2^31-1"),
     "a negative placer seed")
case("synth-workers-negative", Y, "--pipeline minimal --pipeline typical14 --workers -1",
     ("--workers", "0..256"), "a negative worker count")
case("synth-out-file", Y, "--pipeline minimal --out {t}/out", ("--out",), "--out is a file",
     setup=_out_is_file)
case("synth-out-user-folder", Y, "--pipeline minimal --out {t}/out", ("--out",),
     "--out is a user's folder (never deleted)", setup=_user_folder)

# ---- mutate ---------------------------------------------------------------------------

M = "mutate"
case("mutate-only-unknown", M, "--only spill_ready_halfrate",
     ("--only", "did you mean 'spill_ready_half_rate'"), "a misspelt mutant id")
case("mutate-only-twice", M, "--only dpc_no_rounding --only dpc_no_rounding",
     ("--only", "more than once"), "one mutant twice")
case("mutate-workers-negative", M, "--workers -1", ("--workers", "0..256"),
     "a negative worker count")
case("mutate-workers-text", M, "--workers many", ("--workers", "invalid int"),
     "a worker count that is a word")
case("mutate-scheduler-malformed", M, "--scheduler tcp://nohost", ("--scheduler", "tcp://HOST:PORT"),
     "a scheduler address without a port")
case("mutate-out-file", M, "--out {t}/out", ("--out",), "--out is a file", setup=_out_is_file)
case("mutate-out-user-folder", M, "--out {t}/out", ("--out",),
     "--out is a user's folder (never deleted)", setup=_user_folder)

# ---------------------------------------------------------------------------------------
# The shared input files
# ---------------------------------------------------------------------------------------

REPORT_SMALL = (REPO / "reports" / "report" / "report_small.toml").read_text()


def _npz(path: Path, **arrays: Any) -> None:
    np.savez(path, **arrays)


def _bomb(path: Path) -> None:
    """An .npz whose codes header claims 10^5 frames of 16384 x 16384 (data absent)."""
    from numpy.lib import format as npformat

    buf = io.BytesIO()
    npformat.write_array_header_1_0(buf, {"descr": "<u2", "fortran_order": False,
                                          "shape": (100_000, 16384, 16384)})
    buf.write(b"\0" * 64)
    with zipfile.ZipFile(path, "w") as zf:
        zf.writestr("codes.npy", buf.getvalue())
        for name, arr in (("temps", np.array([300.0])), ("adc_bits", np.int64(14))):
            b = io.BytesIO()
            np.save(b, arr)
            zf.writestr(f"{name}.npy", b.getvalue())


@pytest.fixture(scope="module")
def world(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """Valid and hostile input files shared by the cases (never written by a case)."""
    from irnuc.cli import main
    from irnuc.nuc_fixed import load_pipeline
    from irnuc.nuc_fixed.synthetic import synth_frames

    root = tmp_path_factory.mktemp("robustness")
    w = root / "w"
    w.mkdir()
    s = synth_frames(shape=(6, 8), temps=(300.0, 400.0), repeats=2, defect_fraction=0.05, seed=1)
    codes, temps, adc = s.codes, s.temps, np.int64(s.adc_bits)
    _npz(w / "good.npz", codes=codes, temps=temps, adc_bits=adc)
    s2 = synth_frames(shape=(6, 8), temps=(300.0, 400.0), repeats=2, defect_fraction=0.05, seed=2)
    _npz(w / "good2.npz", codes=s2.codes, temps=s2.temps, adc_bits=adc)
    variants: dict[str, dict[str, Any]] = {
        "no_codes": {"temps": temps, "adc_bits": adc},
        "no_temps": {"codes": codes, "adc_bits": adc},
        "no_adc": {"codes": codes, "temps": temps},
        "codes_float": {"codes": codes.astype(float)},
        "codes_bool": {"codes": codes > 5000},
        "codes_2d": {"codes": codes[0], "temps": temps[:1]},
        "codes_4d": {"codes": codes[None]},
        "zero_frames": {"codes": codes[:0], "temps": temps[:0]},
        "zero_width": {"codes": codes[:, :, :0]},
        "codes_negative": {"codes": codes.astype(np.int32) - 20000},
        "codes_above": {"codes": codes.astype(np.int32) + 20000},
        "temps_str": {"temps": np.array([str(t) for t in temps])},
        "temps_nan": {"temps": temps * np.nan},
        "temps_neg": {"temps": -temps},
        "temps_len": {"temps": temps[:-1]},
        "temps_complex": {"temps": temps.astype(complex)},
        "adc_array": {"adc_bits": np.array([14, 14])},
        "adc_float": {"adc_bits": np.float64(14)},
        "adc_zero": {"adc_bits": np.int64(0)},
        "adc_12": {"codes": codes >> 2, "adc_bits": np.int64(12)},
        "one_temp": {"temps": np.full_like(temps, 300.0)},
        "too_wide": {"codes": np.tile(codes, (1, 1, 40)) >> 6, "adc_bits": np.int64(8)},
        "stuck": {"codes": np.full_like(codes, 5000)},
        "swapped": {"temps": temps[::-1].copy()},
        "other_shape": {"codes": np.concatenate([codes, codes[:, :1]], axis=1)},
    }
    for name, change in variants.items():
        # The no_* variants hold exactly the arrays listed; the others change one array.
        arrays = dict(change) if name.startswith("no_") else {
            "codes": codes, "temps": temps, "adc_bits": adc, **change}
        _npz(w / f"{name}.npz", **arrays)
    with zipfile.ZipFile(w / "codes_object.npz", "w") as zf:
        for name, arr in (("codes", np.array([{"a": 1}], dtype=object)), ("temps", temps),
                          ("adc_bits", adc)):
            b = io.BytesIO()
            np.save(b, arr, allow_pickle=True)
            zf.writestr(f"{name}.npy", b.getvalue())
    (w / "empty.npz").write_bytes(b"")
    (w / "text.npz").write_text("codes,temps\n1,2\n")
    np.save(w / "npy.npy", codes)
    (w / "npy.npy").rename(w / "npy.npz")
    good = (w / "good.npz").read_bytes()
    (w / "truncated.npz").write_bytes(good[: len(good) // 2])
    np.savez_compressed(w / "compressed.npz", codes=codes, temps=temps, adc_bits=adc)
    comp = bytearray((w / "compressed.npz").read_bytes())
    mid = len(comp) // 3
    comp[mid:mid + 16] = bytes(16)
    (w / "corrupt.npz").write_bytes(bytes(comp))
    with zipfile.ZipFile(w / "zip_text.npz", "w") as zf:
        zf.writestr("readme.txt", "no arrays here")
    _bomb(w / "bomb.npz")
    np.save(w / "map_3x3.npy", np.full((3, 3), 300.0))

    files: dict[str, str | bytes] = {
        "bad.toml": "[x\n",
        "empty.toml": "",
        "binary.toml": bytes(range(256)),
        "sensor_ok.toml": 'base = "default"\n',
        "sensor_section.toml": 'base = "default"\n[fpaa]\nactive_rows = 8\n',
        "sensor_key.toml": 'base = "default"\n[fpa]\nactiv_rows = 8\n',
        "sensor_type.toml": 'base = "default"\n[fpa]\nactive_rows = "8"\n',
        "sensor_range.toml": 'base = "default"\n[fpa]\nactive_rows = 0\n',
        "sensor_base.toml": 'base = "nope"\n',
        "sensor_nan.toml": 'base = "default"\n[environment]\nT_cam = nan\n',
        "sensor_scalar.toml": 'base = "default"\nfpa = 3\n',
        "th_other.toml": "[other]\nlow_response = 0.5\n",
        "th_scalar.toml": "default = 3\n",
        "th_unknown.toml": "[default]\nlow_respons = 0.5\n",
        "th_range.toml": "[default]\nlow_response = -1.0\n",
        "base_notjson.json": "{",
        "base_list.json": "[]",
        "base_nometrics.json": "{}",
        "base_metrics_list.json": '{"metrics": []}',
        "base_metric_number.json": '{"metrics": {"calibration.bad_pixels": 1}}',
        "base_metric_string.json": '{"metrics": {"calibration.bad_pixels": "many"}}',
        "base_metric_list.json": '{"metrics": {"calibration.bad_pixels": [1]}}',
        "base_nan.json": '{"metrics": {"calibration.bad_pixels": {"value": NaN, "better": "lower"}}}',
        "base_value_text.json": '{"metrics": {"calibration.bad_pixels": {"value": "x", "better": "lower"}}}',
        "junit_bad.xml": "<testsuite",
        "junit_root.xml": "<html/>",
    }
    typ = load_pipeline("typical14").to_toml().replace("[typical14]", "[p]")
    files["pipe_two.toml"] = typ + typ.replace("[p]", "[q]")
    files["pipe_scalar.toml"] = "p = 3\n"
    files["pipe_unknown.toml"] = typ + "adc_bitz = 14\n"
    files["pipe_type.toml"] = typ.replace("adc_bits = 14", 'adc_bits = "14"')
    files["pipe_range.toml"] = typ.replace("out_bits = 14", "out_bits = 99")
    sm = REPORT_SMALL
    files["rep_section_typo.toml"] = sm.replace("[sensor]", "[sensr]").replace(
        "[sensor.overrides]", "[sensr.overrides]").replace("[sweep]", "[swep]").replace(
        "[paper]", "[papr]").replace("[paper.table1]", "[papr.table1]")
    files["rep_key_typo.toml"] = sm.replace("rows = 48\n", "rows = 48\nrowz = 12\n", 1)
    files["rep_missing_key.toml"] = sm.replace("rows = 48\n", "", 1)
    files["rep_type.toml"] = sm.replace("rows = 48\n", 'rows = "48"\n', 1)
    files["rep_range.toml"] = sm.replace("rows = 48\n", "rows = 1\n", 1)
    files["rep_nan.toml"] = sm.replace("t_low = 300.0\n", "t_low = nan\n", 1)
    files["rep_scalar.toml"] = 'name = "x"\nsensor = 3\n'
    files["rep_paper.toml"] = sm.replace("reference_nu = [0.0348, 0.0181, 0.0092, 0.0046]",
                                         "reference_nu = [0.0348]")
    files["rep_quick.toml"] = sm.replace("[quick]", '[quick]\n"name.rows" = 3')
    files["rep_cosim_typo.toml"] = sm.replace('tests = ["corner_codes"]', 'tests = ["corner_code"]')
    files["rep_sweep_adc.toml"] = sm.replace('pipeline = "typical14"\ngain_frac_bits',
                                             'pipeline = "minimal"\ngain_frac_bits')
    files["rep_rec_nosweep.toml"] = '[cosim]\npipelines = ["recommended"]\ntests = ["corner_codes"]\n'
    files["rep_skim.toml"] = sm.replace('skimming = ["row", "column"]', 'skimming = ["diagonal"]')
    for name, content in files.items():
        (w / name).write_bytes(content if isinstance(content, bytes) else content.encode())

    # A valid calibration (copied by the correct cases) and another run's binary image.
    assert main(["calibrate", "-q", "--frames", str(w / "good.npz"), "--out", str(w / "cal")]) == 0
    assert main(["calibrate", "-q", "--frames", str(w / "good2.npz"), "--out",
                 str(root / "cal2")]) == 0
    shutil.copy(root / "cal2" / "coeffs.bin", w / "cal2.bin")
    return w


# ---------------------------------------------------------------------------------------
# Running a case
# ---------------------------------------------------------------------------------------

#: The first function of each command's work: replaced by a tripwire, so a case passes only
#: if its error is found before the work (the report's and precision's are theirs to keep).
WORK: dict[str, tuple[tuple[str, str], ...]] = {
    "frames": (("irnuc.model", "simulate"),),
    "calibrate": (("irnuc.nuc_fixed.calibrate", "calibrate"),),
    "correct": (("irnuc.nuc_fixed.top", "nuc_dpc_top"),),
    "sweep": (("irnuc.reports.studies.sweep", "prepare"),),
    "report": (("irnuc.reports.report.run", "build_report"),),
    "precision": (("irnuc.reports.studies.precision", "run_precision"),),
    "synth": (("irnuc.cosim.synth", "synth_configs"),),
    "mutate": (("irnuc.verif.mutate", "baseline_check"), ("irnuc.verif.mutate", "run_mutant")),
}


class WorkStarted(AssertionError):
    """The command started its work although the error could be known before."""


def _tripwire(*_: Any, **__: Any) -> Any:
    raise WorkStarted("the command's work started before the error was reported")


def _snapshot(path: Path) -> Any:
    """Everything at ``path`` (kind, bytes, link target), to show it was left alone."""
    if path.is_symlink():
        return ("link", os.readlink(path))
    if not path.exists():
        return None
    if path.is_file():
        return ("file", path.read_bytes())
    return ("folder", {str(p.relative_to(path)): (p.read_bytes() if p.is_file() and not p.is_symlink()
                                                   else "folder" if p.is_dir() else "link")
                       for p in sorted(path.rglob("*"))})


def _argv(c: Case, w: Path, t: Path) -> list[str]:
    args = [a.format(w=w, t=t) for a in shlex.split(c.args)]
    if not any(a == "--out" or a.startswith("--out=") for a in args):
        args += ["--out", str(t / "out")]
    return [c.command, *args]


def _out_path(argv: list[str], t: Path) -> Path | None:
    for i, a in enumerate(argv):
        if a == "--out" and i + 1 < len(argv):
            value = argv[i + 1]
        elif a.startswith("--out="):
            value = a[len("--out="):]
        else:
            continue
        return (t / value) if value and not os.path.isabs(value) else Path(value) if value else None
    return None


def run_cli(argv: list[str]) -> int:
    from irnuc.cli import main

    try:
        return main(argv)
    except SystemExit as exc:  # argparse
        return int(exc.code or 0)


def _cli_params() -> list[Any]:
    out = []
    for c in CLI_CASES:
        marks = [pytest.mark.xfail(strict=True, reason=c.xfail)] if c.xfail else []
        out.append(pytest.param(c, id=c.id, marks=marks))
    return out


@pytest.mark.parametrize("c", _cli_params())
def test_cli_case(c: Case, world: Path, tmp_path: Path, monkeypatch: pytest.MonkeyPatch,
                  capsys: pytest.CaptureFixture[str]) -> None:
    t = tmp_path / "case"
    t.mkdir()
    try:
        if c.setup is not None:
            c.setup(world, t)
        argv = _argv(c, world, t)
        out = _out_path(argv, t) if c.check_out else None
        before = _snapshot(out) if out is not None else None
        monkeypatch.chdir(t)
        if c.before_work:
            for module, name in WORK[c.command]:
                monkeypatch.setattr(importlib.import_module(module), name, _tripwire, raising=False)
        code = run_cli(argv)
        err = capsys.readouterr().err
        assert "Traceback" not in err
        lines = [line for line in err.splitlines() if line.strip()]
        assert len(lines) == 1, f"expected one line on stderr, got:\n{err}"
        line = lines[0]
        assert line.startswith(f"irnuc {c.command}: error: "), line
        for name in c.names:
            assert name.format(w=world, t=t) in line, f"{name!r} not named in: {line}"
        assert code == 2, line
        if out is not None:
            assert _snapshot(out) == before, f"{out} was changed"
            assert not list(out.parent.glob(f".{out.name}.tmp-*")), "temporary folder left"
    finally:
        if (t / "ro").exists():
            _undo_read_only(t / "ro")


def test_table_is_large_and_unique() -> None:
    ids = [c.id for c in CLI_CASES]
    assert len(ids) == len(set(ids)), "case ids must be unique"
    assert len(CLI_CASES) >= 150
    assert {c.command for c in CLI_CASES} == set(WORK)


# ---------------------------------------------------------------------------------------
# The API table
# ---------------------------------------------------------------------------------------


@dataclass(frozen=True)
class ApiCase:
    """One bad call: it must raise ``ValueError`` whose message holds every one of ``names``
    (the argument first)."""

    id: str
    call: Callable[[], Any]
    names: tuple[str, ...]
    what: str


def _api() -> tuple[Any, ...]:
    """What the calls need, imported when the cases run (not at collection)."""
    from irnuc import model
    from irnuc.nuc_fixed import dpc_core, nuc_core, nuc_dpc_top, pack_words
    from irnuc.nuc_fixed.calibrate import calibrate

    return model, nuc_core, dpc_core, nuc_dpc_top, pack_words, calibrate


X = np.full((4, 5), 1000, np.int64) + np.arange(20).reshape(4, 5)
GAIN = np.full((4, 5), 1 << 14, np.int64)
OFFSET = np.zeros((4, 5), np.int64)
BAD = np.zeros((4, 5), bool)
BAD[1, 2] = True
LO = np.stack([X + 2000, X + 2003])
HI = LO + 5000
T14 = "typical14"


def _words() -> np.ndarray:
    return _api()[4](GAIN, OFFSET, BAD, T14)


def _nan(a: np.ndarray) -> np.ndarray:
    f = a.astype(np.float64)
    f.flat[3] = np.nan
    return f


def _sensor(**over: Any) -> dict[str, Any]:
    from irnuc import model

    return model.load_preset("default", {"fpa.active_rows": 6, "fpa.active_cols": 8, **over})


def _half_sensor() -> dict[str, Any]:
    cfg = _sensor()
    del cfg["fpa"]["active_rows"]
    return cfg


def _bad_sensor() -> dict[str, Any]:
    cfg = _sensor()
    cfg["fpa"]["active_rows"] = 0
    return cfg


def _nuc(*a: Any) -> Any:
    return _api()[1](*a)


def _dpc(*a: Any) -> Any:
    return _api()[2](*a)


def _top(*a: Any) -> Any:
    return _api()[3](*a)


def _pack(*a: Any) -> Any:
    return _api()[4](*a)


def _cal(*a: Any, **kw: Any) -> Any:
    return _api()[5](*a, **kw)


def _sim(*a: Any, **kw: Any) -> Any:
    return _api()[0].simulate(*a, **kw)


def _cos4(*a: Any) -> Any:
    return _api()[0].cos4_map(*a)


API_CASES: list[ApiCase] = []


def api(id: str, call: Callable[[], Any], names: tuple[str, ...] | str, what: str) -> None:
    API_CASES.append(ApiCase(id, call, (names,) if isinstance(names, str) else names, what))


api("nuc_core-x-float", lambda: _nuc(X.astype(float), GAIN, OFFSET, T14), ("x", "float64"), "float codes")
api("nuc_core-x-nan", lambda: _nuc(_nan(X), GAIN, OFFSET, T14), ("x", "NaN"), "a NaN code")
api("nuc_core-x-empty", lambda: _nuc(np.zeros(0, np.int64), GAIN, OFFSET, T14), ("x is empty",), "no codes")
api("nuc_core-x-shape", lambda: _nuc(np.zeros((3, 3), np.int64), GAIN, OFFSET, T14), ("x has shape",),
    "codes of another shape than the coefficients")
api("nuc_core-x-range", lambda: _nuc(X + 20000, GAIN, OFFSET, T14), ("x[", "[0, 16383]"), "codes above 2^A-1")
api("nuc_core-x-negative", lambda: _nuc(X - 5000, GAIN, OFFSET, T14), ("x[",), "negative codes")
api("nuc_core-x-bool", lambda: _nuc(X > 0, GAIN, OFFSET, T14), ("x", "bool"), "boolean codes")
api("nuc_core-x-ragged", lambda: _nuc([[1, 2], [3]], GAIN, OFFSET, T14), ("x",), "a ragged list")
api("nuc_core-x-text", lambda: _nuc(np.array([["a"]]), GAIN, OFFSET, T14), ("x", "<U1"), "strings")
api("nuc_core-gain-shape", lambda: _nuc(X, GAIN[:, :4], OFFSET, T14), ("gain has shape", "offset"),
    "gain and offset of different shapes")
api("nuc_core-gain-range", lambda: _nuc(X, GAIN * 8, OFFSET, T14), ("gain[",), "gain codes above 2^GW-1")
api("nuc_core-gain-empty", lambda: _nuc(X, GAIN[:0], OFFSET[:0], T14), ("gain is empty",), "no gain")
api("nuc_core-offset-float", lambda: _nuc(X, GAIN, OFFSET + 0.5, T14), ("offset", "float64"), "float offsets")
api("nuc_core-offset-inf", lambda: _nuc(X, GAIN, np.full((4, 5), np.inf), T14), ("offset",),
    "infinite offsets")
api("nuc_core-cfg-type", lambda: _nuc(X, GAIN, OFFSET, 3), ("cfg",), "a number as cfg")
api("nuc_core-cfg-name", lambda: _nuc(X, GAIN, OFFSET, "typical41"), ("pipeline 'typical41'", "typical14"),
    "a misspelled configuration")
api("dpc_core-y-1d", lambda: _dpc(X[0], BAD[0], T14), ("y has shape",), "one row")
api("dpc_core-y-4d", lambda: _dpc(X[None, None], BAD, T14), ("y has shape",), "a 4-D stack")
api("dpc_core-y-empty", lambda: _dpc(np.zeros((0, 5), np.int64), BAD, T14), ("y is empty",), "no pixels")
api("dpc_core-y-float", lambda: _dpc(X.astype(np.float32), BAD, T14), ("y", "float32"), "float codes")
api("dpc_core-y-range", lambda: _dpc(X + 20000, BAD, T14), ("y[",), "codes above 2^B-1")
api("dpc_core-y-too-large", lambda: _dpc(np.zeros((1, 2000), np.int64), np.zeros((1, 2000), bool), T14),
    ("y frame size", "1024"), "a frame wider than the pipeline allows")
api("dpc_core-bad-shape", lambda: _dpc(X, BAD[:3], T14), ("bad has shape",), "a map of another size")
api("dpc_core-bad-nan", lambda: _dpc(X, _nan(BAD.astype(np.int64)), T14), ("bad", "NaN"), "NaN in the map")
api("dpc_core-bad-two", lambda: _dpc(X, BAD.astype(np.int64) * 2, T14), ("bad[", "[0, 1]"),
    "2 in the bad-pixel map")
api("dpc_core-bad-empty", lambda: _dpc(X, np.zeros((0, 5), bool), T14), ("bad is empty",), "an empty map")
api("nuc_dpc_top-raw-4d", lambda: _top(X[None, None], _words(), T14), ("raw has shape",), "a 4-D stack")
api("nuc_dpc_top-raw-empty", lambda: _top(np.zeros((0, 4, 5), np.int64), _words(), T14), ("raw is empty",),
    "zero frames")
api("nuc_dpc_top-raw-float", lambda: _top(np.full((4, 5), np.inf), _words(), T14), ("raw", "float64"),
    "infinite float codes")
api("nuc_dpc_top-words-float", lambda: _top(X, _words().astype(float), T14), ("words", "float64"),
    "float words")
api("nuc_dpc_top-words-range", lambda: _top(X, _words() | np.uint64(1 << 40), T14), ("words[", "word_bits"),
    "words wider than the layout")
api("nuc_dpc_top-words-negative", lambda: _top(X, -_words().astype(np.int64), T14), ("words[",),
    "negative words")
api("nuc_dpc_top-words-shape", lambda: _top(X, _words()[:3], T14), ("words has shape",),
    "words of another size")
api("nuc_dpc_top-words-empty", lambda: _top(X, np.zeros((0, 5), np.uint64), T14), ("words is empty",),
    "no words")
api("pack_words-gain-nan", lambda: _pack(_nan(GAIN), OFFSET, BAD, T14), ("gain", "NaN"), "a NaN gain")
api("pack_words-offset-range", lambda: _pack(GAIN, OFFSET + (1 << 20), BAD, T14), ("offset[",),
    "offsets beyond the format")
api("pack_words-bad-shape", lambda: _pack(GAIN, OFFSET, BAD[:2], T14), ("bad has shape",),
    "a map of another size")
api("pack_words-gain-empty", lambda: _pack(GAIN[:0], OFFSET[:0], BAD[:0], T14), ("gain is empty",),
    "no pixels")
api("pack_words-bad-float", lambda: _pack(GAIN, OFFSET, BAD.astype(float), T14), ("bad", "float64"),
    "a float bad-pixel map")
api("calibrate-lo-empty", lambda: _cal(LO[:0], HI, T14), ("frames_lo",), "no low frames")
api("calibrate-hi-nan", lambda: _cal(LO, _nan(HI), T14), ("frames_hi", "NaN"), "NaN in the high frames")
api("calibrate-lo-1d", lambda: _cal(LO[0, 0], HI, T14), ("frames_lo has shape",), "one row of codes")
api("calibrate-shape-mismatch", lambda: _cal(LO, HI[:, :3], T14), ("frames_hi",), "stacks of different sizes")
api("calibrate-lo-float", lambda: _cal(LO.astype(float), HI, T14), ("frames_lo", "float64"), "float frames")
api("calibrate-rounding", lambda: _cal(LO, HI, T14, rounding="nearest"), ("rounding", "nearest"),
    "an unknown rounding")
api("calibrate-targets-nan", lambda: _cal(LO, HI, T14, targets=(np.nan, 9000)), ("targets",), "a NaN target")
api("calibrate-targets-text", lambda: _cal(LO, HI, T14, targets=("a", "b")), ("targets",), "targets as words")
api("calibrate-targets-one", lambda: _cal(LO, HI, T14, targets=(1,)), ("targets",), "one target")
api("calibrate-targets-range", lambda: _cal(LO, HI, T14, targets=(-5, 9000)), ("target low",),
    "a target below 0")
api("calibrate-all-stuck", lambda: _cal(np.full_like(LO, 5000), np.full_like(HI, 5000), T14),
    ("no usable pixel",), "every pixel stuck")
api("simulate-cfg-empty", lambda: _sim({}, [300]), ("cfg",), "an empty dict (was a KeyError)")
api("simulate-cfg-none", lambda: _sim(None, [300]), ("cfg = None",), "None")
api("simulate-cfg-list", lambda: _sim([], [300]), ("cfg = []",), "a list")
api("simulate-cfg-half", lambda: _sim(_half_sensor(), [300]), ("cfg", "fpa.active_rows"),
    "a configuration with a field removed")
api("simulate-cfg-bad-value", lambda: _sim(_bad_sensor(), [300]), ("cfg", "fpa.active_rows"),
    "a configuration edited after validation")
api("simulate-temps-nan", lambda: _sim(_sensor(), [300, np.nan]), ("temps",), "a NaN temperature")
api("simulate-temps-inf", lambda: _sim(_sensor(), [np.inf]), ("temps",), "an infinite temperature")
api("simulate-temps-negative", lambda: _sim(_sensor(), [-1.0]), ("temps",), "a negative temperature")
api("simulate-temps-empty", lambda: _sim(_sensor(), []), ("temps",), "no temperature")
api("simulate-temps-2d", lambda: _sim(_sensor(), [[300, 301]]), ("temps",), "a 2-D list")
api("simulate-temps-text", lambda: _sim(_sensor(), ["warm"]), ("temps",), "a word")
api("simulate-repeats-zero", lambda: _sim(_sensor(), [300], repeats=0), ("repeats",), "zero repeats")
api("simulate-repeats-float", lambda: _sim(_sensor(), [300], repeats=1.5), ("repeats",), "1.5 repeats")
api("simulate-seed-negative", lambda: _sim(_sensor(), [300], seed=-1), ("seed",), "a negative seed")
api("simulate-outputs-unknown", lambda: _sim(_sensor(), [300], outputs=("cods",)), ("outputs", "cods"),
    "a misspelled output")
api("simulate-scene-unknown", lambda: _sim(_sensor(), [300], "moon"), ("scene", "moon"), "an unknown scene")
api("simulate-memory", lambda: _sim(_sensor(**{"fpa.active_rows": 16384, "fpa.active_cols": 16384}),
                                    [300, 400], repeats=100_000), ("simulate", "needs an estimated"),
    "200000 frames of 16384 x 16384, refused before any allocation")
api("Pipeline-cfg-empty", lambda: _api()[0].Pipeline({}), ("cfg",), "an empty dict")
api("cos4_map-memory", lambda: _cos4(10**6, 10**6, 17e-6, 0.01), ("cos4_map", "needs an estimated"),
    "10^6 x 10^6 pixels, refused before the allocation")
api("cos4_map-rows-zero", lambda: _cos4(0, 8, 17e-6, 0.01), ("rows",), "zero rows")
api("cos4_map-rows-float", lambda: _cos4(8.0, 8, 17e-6, 0.01), ("rows",), "rows as a float")
api("cos4_map-cols-bool", lambda: _cos4(8, True, 17e-6, 0.01), ("cols",), "cols as True")
api("cos4_map-pitch-nan", lambda: _cos4(8, 8, np.nan, 0.01), ("pitch",), "a NaN pitch")
api("cos4_map-pitch-negative", lambda: _cos4(8, 8, -1e-6, 0.01), ("pitch",), "a negative pitch")
api("cos4_map-focal-inf", lambda: _cos4(8, 8, 17e-6, np.inf), ("focal_length",), "an infinite focal length")
api("cos4_map-centre-nan", lambda: _cos4(8, 8, 17e-6, 0.01, (np.nan, 1.0)), ("centre[0]",), "a NaN centre")
api("cos4_map-centre-short", lambda: _cos4(8, 8, 17e-6, 0.01, (1.0,)), ("centre",), "one coordinate")
api("cos4_map-centre-text", lambda: _cos4(8, 8, 17e-6, 0.01, ("a", "b")), ("centre[0]",), "words")


@pytest.mark.parametrize("c", [pytest.param(c, id=c.id) for c in API_CASES])
def test_api_case(c: ApiCase) -> None:
    with pytest.raises(ValueError) as info:
        c.call()
    msg = str(info.value)
    assert "\n" not in msg
    for name in c.names:
        assert name in msg, f"{name!r} not named in: {msg}"


def _swap(a: np.ndarray) -> np.ndarray:
    """The same values in the other byte order."""
    return a.astype(a.dtype.newbyteorder("S"))


#: Calls given arrays of the other byte order (and non-contiguous views), each equal to
#: the call on native arrays.
BYTE_ORDER_CASES: dict[str, Callable[[Callable[[np.ndarray], np.ndarray]], Any]] = {
    "nuc_core": lambda f: _nuc(f(X.astype(np.uint16)), f(GAIN.astype(np.uint32)), f(OFFSET.astype(np.int16)),
                               T14),
    "dpc_core": lambda f: _dpc(f(X.astype(np.uint16)), f(BAD.astype(np.int16)), T14),
    "nuc_dpc_top": lambda f: _top(f(np.stack([X, X + 7]).astype(np.uint16)), f(_words()), T14),
    "pack_words": lambda f: _pack(f(GAIN.astype(np.uint32)), f(OFFSET.astype(np.int32)),
                                  f(BAD.astype(np.uint8)), T14),
    "calibrate": lambda f: _cal(f(LO.astype(np.uint16)), f(HI.astype(np.int32)), T14).words(),
    "simulate": lambda f: _sim(_sensor(), f(np.array([300.0, 350.0])), seed=3).codes,
    "cos4_map": lambda f: _cos4(6, 8, 17e-6, 0.01, f(np.array([2.5, 3.0]))),
}


@pytest.mark.parametrize("name", sorted(BYTE_ORDER_CASES))
@pytest.mark.parametrize("layout", ["other byte order", "strided view"])
def test_api_accepts_any_byte_order(name: str, layout: str) -> None:
    call = BYTE_ORDER_CASES[name]
    native = call(lambda a: a)
    if layout == "other byte order":
        changed = call(_swap)
    else:  # every other element of a twice-as-large array: not contiguous
        changed = call(lambda a: np.repeat(a, 2, axis=-1)[..., ::2])
    np.testing.assert_array_equal(changed, native)
    assert changed.dtype == native.dtype


# ---------------------------------------------------------------------------------------
# Faults: kills and concurrent runs
# ---------------------------------------------------------------------------------------

#: Every fault test, named as in the documentation (``test_fault_<id>`` runs it).
FAULTS: dict[str, str] = {
    "kill_calibrate": "SIGKILL of `irnuc calibrate` writing over an earlier result, at a seeded "
                      "random time or once it has written a random number (1-8) of files, "
                      "wherever (6 trials): the folder is the old result or the new one, whole "
                      "(every file checked against both results, the manifest and the summary)",
    "concurrent_calibrate": "two `irnuc calibrate` runs (different frames) on one `--out`, "
                            "started a seeded random time apart (3 trials): each exits 0, or 2 with "
                            "'another irnuc run is writing it'; the folder is one run's result, whole",
    "stale_tmp_removed": "a killed run's temporary folder and a stale lock beside `--out`: the next "
                         "run removes the folder and writes a whole result",
    "children_die_with_parent": "SIGKILL of a process that started a child process group with "
                                "`run_child`, the child having started a grandchild; the child "
                                "either irnuc's own or a foreign tool (a shell, as make, run "
                                "under the reaper): both are gone",
    "single_process_child_dies_with_parent": "SIGKILL of a process that started a tool with "
                                             "`run_child(single_process=True)` (no reaper, the "
                                             "bulk harness): the tool, its direct child, is gone",
}

_MAIN = "import sys; from irnuc.cli import main; sys.exit(main(sys.argv[1:]))"


def _start(*args: str, cwd: Path) -> subprocess.Popen[str]:
    return subprocess.Popen([sys.executable, "-c", _MAIN, *args], cwd=cwd, text=True,
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE)


def _digest(folder: Path) -> dict[str, str]:
    """SHA-256 of every file under ``folder`` (hidden ones too), by relative path."""
    return {str(p.relative_to(folder)): hashlib.sha256(p.read_bytes()).hexdigest()
            for p in sorted(folder.rglob("*")) if p.is_file()}


@dataclass
class Faults:
    root: Path
    frames: dict[str, Path]       # "old", "new": two frame files
    results: dict[str, dict[str, str]]  # "old", "new": digest of each one's calibration
    seconds: float                # how long one calibration subprocess runs here


@pytest.fixture(scope="module")
def faults(tmp_path_factory: pytest.TempPathFactory) -> Faults:
    from irnuc.cli import main
    from irnuc.nuc_fixed.synthetic import synth_frames

    root = tmp_path_factory.mktemp("faults")
    frames, results = {}, {}
    for seed, key in ((1, "old"), (2, "new")):
        s = synth_frames(shape=(24, 32), temps=(300.0, 400.0), repeats=3, defect_fraction=0.03,
                         seed=seed)
        frames[key] = root / f"{key}.npz"
        np.savez(frames[key], codes=s.codes, temps=s.temps, adc_bits=np.int64(s.adc_bits))
        assert main(["calibrate", "-q", "--frames", str(frames[key]), "--out",
                     str(root / f"ref-{key}")]) == 0
        results[key] = _digest(root / f"ref-{key}")
    assert results["old"] != results["new"]
    # One undisturbed subprocess run: its result equals the in-process one, and its length
    # spreads the kill times over a whole run.
    t0 = time.monotonic()
    proc = _start("calibrate", "-q", "--frames", str(frames["new"]), "--out", str(root / "timed"),
                  cwd=root)
    assert proc.wait() == 0, proc.stderr.read() if proc.stderr else ""
    seconds = time.monotonic() - t0
    assert _digest(root / "timed") == results["new"]
    return Faults(root, frames, results, seconds)


def _which(folder: Path, f: Faults) -> str:
    """Which result the folder is, whole; fails on anything else (a mixed folder)."""
    from irnuc.nuc_fixed.memimage import read_memimage

    got = _digest(folder)
    matches = [k for k, want in f.results.items() if got == want]
    assert matches, f"{folder} is neither result, whole: {sorted(got)}"
    # And by the folder's own account: every file matches the manifest, and the summary
    # names the frames of that result.
    read_memimage(folder, "typical14", source="hex")
    summary = json.loads((folder / "summary.json").read_text())
    assert summary["frames_file"] == str(f.frames[matches[0]])
    return matches[0]


def _fresh(folder: Path, f: Faults, key: str) -> None:
    shutil.rmtree(folder, ignore_errors=True)
    shutil.copytree(f.root / f"ref-{key}", folder)


def _files(root: Path) -> set[tuple[str, int, int]]:
    """(path, inode, mtime) of every file under ``root``: what a run has written since."""
    out = set()
    for dirpath, _, names in os.walk(root):
        for name in names:
            with contextlib.suppress(OSError):
                st = os.stat(os.path.join(dirpath, name))
                out.add((os.path.join(dirpath, name), st.st_ino, st.st_mtime_ns))
    return out


@pytest.mark.parametrize("trial", range(6))
def test_fault_kill_calibrate(trial: int, faults: Faults, tmp_path: Path) -> None:
    rng = random.Random(1000 + trial)
    out = tmp_path / "cal"
    _fresh(out, faults, "old")
    before = _files(tmp_path)
    proc = _start("calibrate", "-q", "--frames", str(faults.frames["new"]), "--out", str(out),
                  cwd=tmp_path)
    if trial % 2 == 0:  # at a random time of the run
        deadline = time.monotonic() + rng.uniform(0.0, 1.2 * faults.seconds)
        while proc.poll() is None and time.monotonic() < deadline:
            time.sleep(0.005)
    else:  # while the result is being written: once k files were written, wherever
        k = rng.randint(1, 8)
        while proc.poll() is None and len(_files(tmp_path) - before) < k:
            time.sleep(0.0002)
    if proc.poll() is None:
        os.kill(proc.pid, signal.SIGKILL)
    proc.wait()
    assert _which(out, faults) in ("old", "new")
    if proc.returncode == 0:
        assert _which(out, faults) == "new"


@pytest.mark.parametrize("trial", range(3))
def test_fault_concurrent_calibrate(trial: int, faults: Faults, tmp_path: Path) -> None:
    rng = random.Random(2000 + trial)
    out = tmp_path / "cal"
    if trial == 2:
        _fresh(out, faults, "old")  # over an earlier result as well as into a new folder
    first, second = ("old", "new") if trial % 2 == 0 else ("new", "old")
    procs = {first: _start("calibrate", "-q", "--frames", str(faults.frames[first]), "--out",
                           str(out), cwd=tmp_path)}
    time.sleep(rng.uniform(0.0, 0.5 * faults.seconds))
    procs[second] = _start("calibrate", "-q", "--frames", str(faults.frames[second]), "--out",
                           str(out), cwd=tmp_path)
    codes = {k: p.wait() for k, p in procs.items()}
    errs = {k: p.stderr.read() if p.stderr else "" for k, p in procs.items()}
    for k, code in codes.items():
        assert code in (0, 2), errs[k]
        if code == 2:
            assert "another irnuc run is writing it" in errs[k], errs[k]
            assert len(errs[k].strip().splitlines()) == 1
    winners = [k for k, code in codes.items() if code == 0]
    assert winners
    got = _which(out, faults)
    assert got in winners
    assert not list(tmp_path.glob(".cal.tmp-*"))


def test_fault_stale_tmp_removed(faults: Faults, tmp_path: Path) -> None:
    from irnuc.cli import main

    out = tmp_path / "cal"
    _fresh(out, faults, "old")
    (tmp_path / ".cal.tmp-killed").mkdir()
    (tmp_path / ".cal.tmp-killed" / "coeffs.bin").write_bytes(b"half a file")
    (tmp_path / ".cal.tmp-link").symlink_to(tmp_path / "nowhere")
    (tmp_path / ".cal.lock").write_text("")
    assert main(["calibrate", "-q", "--frames", str(faults.frames["new"]), "--out", str(out)]) == 0
    assert _which(out, faults) == "new"
    assert not list(tmp_path.glob(".cal.tmp-*"))


_CHILD = """
import os, subprocess, sys
from irnuc.common.process import die_with_parent
die_with_parent()
g = subprocess.Popen(["sleep", "300"])
open(sys.argv[1], "w").write(f"{os.getpid()} {g.pid}")
g.wait()
"""
_PARENT = """
import sys
from irnuc.common.process import run_child
run_child([sys.executable, "-c", sys.argv[1], sys.argv[2]])
"""


def _alive(pid: int) -> bool:
    try:
        state = Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()[0]
    except (OSError, IndexError):
        return False
    return state not in ("Z", "X")  # a zombie is dead, only not yet reaped


_TOOL_PARENT = """
import sys
from irnuc.common.process import run_child
# A tool that is not irnuc's own and starts a child of its own (as make starts a compiler).
run_child(["sh", "-c", "sleep 300 & echo $$ $! > " + sys.argv[1] + "; wait"])
"""


@pytest.mark.skipif(not sys.platform.startswith("linux"), reason="PR_SET_PDEATHSIG is Linux's")
@pytest.mark.parametrize("kind", ["irnuc_child", "foreign_tool"])
def test_fault_children_die_with_parent(tmp_path: Path, kind: str) -> None:
    """SIGKILL of a process that started a child group: the child and the child's own
    child are gone, whether the child is irnuc's (it arms die_with_parent itself) or a
    foreign tool (run under the reaper)."""
    pids = tmp_path / "pids"
    argv = ([sys.executable, "-c", _PARENT, _CHILD, str(pids)] if kind == "irnuc_child"
            else [sys.executable, "-c", _TOOL_PARENT, str(pids)])
    parent = subprocess.Popen(argv)
    try:
        while not (pids.is_file() and pids.read_text().strip()):
            assert parent.poll() is None, "the parent ended early"
            time.sleep(0.02)
        child, grandchild = map(int, pids.read_text().split())
        assert _alive(child) and _alive(grandchild)
        parent.kill()
        parent.wait()
        # Wait (bounded) for the kernel's signal and the group kill to land.
        for _ in range(500):
            if not (_alive(child) or _alive(grandchild)):
                break
            time.sleep(0.02)
        assert not _alive(child), "the child outlived its parent"
        assert not _alive(grandchild), "the grandchild (e.g. a simulator) outlived irnuc"
    finally:
        if parent.poll() is None:
            parent.kill()
        if pids.is_file() and pids.read_text().strip():
            for pid in map(int, pids.read_text().split()):
                if _alive(pid):
                    with contextlib.suppress(ProcessLookupError):
                        os.kill(pid, signal.SIGKILL)


_SINGLE_PARENT = """
import sys
from irnuc.common.process import run_child
# A single-process tool (as the bulk harness): no reaper in between.
run_child(["sh", "-c", "echo $$ > " + sys.argv[1] + "; exec sleep 300"], single_process=True)
"""


@pytest.mark.skipif(not sys.platform.startswith("linux"), reason="PR_SET_PDEATHSIG is Linux's")
def test_fault_single_process_child_dies_with_parent(tmp_path: Path) -> None:
    """``run_child(single_process=True)`` starts the tool without the reaper: the tool is
    the direct child and still dies when its parent is killed (PR_SET_PDEATHSIG)."""
    pids = tmp_path / "pids"
    parent = subprocess.Popen([sys.executable, "-c", _SINGLE_PARENT, str(pids)])
    child = None
    try:
        while not (pids.is_file() and pids.read_text().strip()):
            assert parent.poll() is None, "the parent ended early"
            time.sleep(0.02)
        child = int(pids.read_text())
        ppid = int(Path(f"/proc/{child}/stat").read_text().rsplit(")", 1)[1].split()[1])
        assert ppid == parent.pid, "the tool must be the parent's direct child (no reaper)"
        parent.kill()
        parent.wait()
        for _ in range(500):
            if not _alive(child):
                break
            time.sleep(0.02)
        assert not _alive(child), "the tool outlived its parent"
    finally:
        if parent.poll() is None:
            parent.kill()
        if child is not None and _alive(child):
            with contextlib.suppress(ProcessLookupError):
                os.kill(child, signal.SIGKILL)


# ---------------------------------------------------------------------------------------
# Memory estimates against measured peaks
# ---------------------------------------------------------------------------------------


def _sim_estimate(rows: int, cols: int, n: int, outputs: tuple[str, ...]) -> float:
    from irnuc import model
    from irnuc.model.pipeline import simulation_bytes

    cfg = model.load_preset("default", {"fpa.active_rows": rows, "fpa.active_cols": cols,
                                        "noise.enabled": True})
    return simulation_bytes(cfg, n, outputs)


def _frames_estimate(n: int, h: int, w: int, work: dict[str, float]) -> float:
    from irnuc.cli._files import arrays_bytes, frames_work_bytes

    headers = {"codes": ((n, h, w), np.dtype(np.uint16)), "temps": ((n,), np.dtype(np.float64)),
               "adc_bits": ((), np.dtype(np.int64))}
    return arrays_bytes(headers) + frames_work_bytes((n, h, w), work["per_code"], work["per_pixel"])


def _calibrate_estimate(n: int, h: int, w: int) -> float:
    from irnuc.cli.calibrate import CALIBRATE_BYTES

    return _frames_estimate(n, h, w, CALIBRATE_BYTES)


def _correct_estimate(n: int, h: int, w: int) -> float:
    from irnuc.cli.calibrate import CORRECT_BYTES

    return _frames_estimate(n, h, w, CORRECT_BYTES)


def _sweep_estimate(rows: int, cols: int, repeats: int, workers: int) -> float:
    from irnuc import model
    from irnuc.cli.sweep import sweep_bytes

    cfg = model.load_preset("default", {"fpa.active_rows": rows, "fpa.active_cols": cols})
    return sweep_bytes(cfg, 2 * repeats, 1, 1, workers)


#: Peak memory of one request, measured once on the development machine as the growth of
#: ru_maxrss above a warm interpreter (MiB), and the estimate irnuc checks before it.
MEASURED: list[tuple[str, float, Callable[[], float]]] = [
    ("simulate, uniform scene, codes: 512 x 640, 8 frames", 237,
     lambda: _sim_estimate(512, 640, 8, ("codes",))),
    ("simulate, uniform scene, codes: 512 x 640, 64 frames", 655,
     lambda: _sim_estimate(512, 640, 64, ("codes",))),
    ("simulate, gradient scene, codes: 512 x 640, 64 frames", 748,
     lambda: _sim_estimate(512, 640, 64, ("codes",))),
    ("simulate, gradient, codes + voltage + params + temperature rise: 512 x 640, 32 frames",
     632, lambda: _sim_estimate(512, 640, 32, ("codes", "voltage", "params", "temperature_rise"))),
    ("simulate, uniform scene, codes: 256 x 320, 400 frames", 813,
     lambda: _sim_estimate(256, 320, 400, ("codes",))),
    ("irnuc calibrate: 512 x 640, 4 frames", 321, lambda: _calibrate_estimate(4, 512, 640)),
    ("irnuc calibrate: 512 x 640, 32 frames", 355, lambda: _calibrate_estimate(32, 512, 640)),
    ("irnuc calibrate: 256 x 320, 200 frames", 192, lambda: _calibrate_estimate(200, 256, 320)),
    ("irnuc correct: 512 x 640, 4 frames", 32, lambda: _correct_estimate(4, 512, 640)),
    ("irnuc correct: 512 x 640, 64 frames", 127, lambda: _correct_estimate(64, 512, 640)),
    ("irnuc sweep, 2 points in-process: 512 x 640, 4 repeats", 371,
     lambda: _sweep_estimate(512, 640, 4, 0)),
]


@pytest.mark.parametrize("what", [m[0] for m in MEASURED])
def test_memory_estimate_covers_measured_peak(what: str) -> None:
    measured, estimate = next((m[1], m[2]) for m in MEASURED if m[0] == what)
    assert estimate() >= measured * 2**20


def test_memory_check_names_estimate_and_available(monkeypatch: pytest.MonkeyPatch) -> None:
    from irnuc.common import memory

    monkeypatch.delenv("IRNUC_NO_MEMORY_CHECK", raising=False)
    monkeypatch.setattr(memory, "available_bytes", lambda: 1000)
    with pytest.raises(memory.ResourceError, match=r"^--x 3 needs an estimated 2.0 KiB of "
                       r"memory but only 1000 B is available; use less$"):
        memory.check_memory(2000, "--x 3", "use less")
    memory.check_memory(800, "--x 1")  # 80 % of what is available may be planned
    monkeypatch.setenv("IRNUC_NO_MEMORY_CHECK", "1")
    memory.check_memory(10**20, "--x 9")  # the user's choice
    monkeypatch.delenv("IRNUC_NO_MEMORY_CHECK")
    monkeypatch.setattr(memory, "available_bytes", lambda: None)
    memory.check_memory(10**20, "--x 9")  # nothing to compare with: no refusal


def test_meminfo_is_read(tmp_path: Path) -> None:
    from irnuc.common import memory

    f = tmp_path / "meminfo"
    f.write_text("MemTotal:       32000000 kB\nMemFree:  100 kB\nMemAvailable:   2048 kB\n")
    assert memory._meminfo_available(str(f)) == 2048 * 1024
    assert memory._meminfo_available(str(tmp_path / "none")) is None
    assert memory.available_bytes() is None or memory.available_bytes() > 0


# ---------------------------------------------------------------------------------------
# docs/robustness.md, generated from the tables above
# ---------------------------------------------------------------------------------------

_COMMAND_TITLES = {
    "frames": "irnuc frames", "calibrate": "irnuc calibrate", "correct": "irnuc correct",
    "sweep": "irnuc sweep", "report": "irnuc report",
    "precision": "irnuc precision",
    "synth": "irnuc synth",
    "mutate": "irnuc mutate",
}


def _cell(text: str) -> str:
    return text.replace("|", "\\|").replace("\n", " ")


def _outcome(c: Case) -> str:
    if c.xfail:
        return f"**xfail**: {c.xfail}"
    return "exit 2, one line" + ("" if c.before_work else " (found in the data, during the work)")


def render_doc() -> str:
    """The text of docs/robustness.md."""
    xfails = [c for c in CLI_CASES if c.xfail]
    out = [
        "# Robustness: hostile and careless use",
        "",
        "<!-- Generated from tests/test_robustness.py: run `.venv/bin/python "
        "tests/test_robustness.py` after changing its tables; a test checks this file. -->",
        "",
        "What irnuc promises when it is used wrongly (issue 12), and the cases that check it.",
        "",
        "* **A user error is one line and exit status 2**: `irnuc COMMAND: error: ...` naming the",
        "  flag, file or dotted field and what is allowed, with no traceback, found before the",
        "  command's work wherever it can be known before (the tests replace the work by a",
        "  tripwire). Usage errors are one line too. A failing external tool is one line and",
        "  status 3; anything else is a bug and keeps its traceback.",
        "* **Sizes are checked against the memory there is** (`MemAvailable` in /proc/meminfo,",
        "  `irnuc.common.memory`) before frames are simulated or loaded (an `.npz` is judged by",
        "  its headers before its data is read); the message gives the estimate and what is",
        "  available. `IRNUC_NO_MEMORY_CHECK=1` turns the check off (e.g. with swap).",
        "* **Every `--out` is written as a unit**: into a hidden sibling `.NAME.tmp-*`, swapped",
        "  into place when the command succeeds, under the lock `.NAME.lock`, which the command",
        "  takes before its work (a second run on the folder fails at once). Leftovers of killed",
        "  runs are removed by the next run. irnuc replaces only what it wrote: an existing",
        "  `--out` must be empty or hold the marker `.irnuc-output` of the same command; a",
        "  user's folder, the current folder, a link, or a folder holding one of the command's",
        "  inputs is refused.",
        "* **The calibration is checked whole**: the manifest hashes every file it names",
        "  (`coeffs.npz`, `coeffs.bin`, `coeffs.hex`, `badpix.csv`, the summaries) and the",
        "  format fields; `irnuc correct` checks all of them, the hex image against the binary",
        "  one, and the format against `--pipeline`.",
        "* **The API** (`nuc_core`, `dpc_core`, `nuc_dpc_top`, `pack_words`, `calibrate`,",
        "  `model.simulate`, `model.Pipeline`, `cos4_map`) raises `ValueError` naming the",
        "  argument for a bad shape, dtype, empty or non-finite input, and accepts integer",
        "  arrays of either byte order (converted once, at the boundary).",
        "* **Child processes** (builds, simulations, the bulk harness) run in their own process",
        "  group and die with the irnuc process that started them.",
        "",
        f"## Command line: {len(CLI_CASES)} cases",
        "",
        f"{len(CLI_CASES) - len(xfails)} end with exit status 2 and one line naming the "
        "flag, file or field"
        + (f"; {len(xfails)} are expected failures (`xfail`, strict), listed with their reason"
           if xfails else "") + ". Every case also checks that",
        "nothing was created or replaced at the output name and no temporary folder is left.",
        "",
    ]
    for command, title in _COMMAND_TITLES.items():
        cases = [c for c in CLI_CASES if c.command == command]
        out += [f"### {title}: {len(cases)} cases", "",
                "| case | hostile input | arguments | the message names | outcome |",
                "|---|---|---|---|---|"]
        for c in cases:
            args = c.args.replace("{w}/", "").replace("{t}/", "").replace("{w}", "FOLDER")
            args = args.replace("{t}", "FOLDER") or "(none)"
            out.append(f"| `{c.id}` | {_cell(c.what)} | `{_cell(args)}` | "
                       f"{', '.join(f'`{_cell(n)}`' for n in c.names)} | {_outcome(c)} |")
        out.append("")
    out += [f"## API: {len(API_CASES)} bad calls, {len(BYTE_ORDER_CASES)} functions in both byte orders",
            "", "Each bad call raises `ValueError` (one line) naming the argument.", "",
            "| case | bad input | the message names |", "|---|---|---|"]
    for a in API_CASES:
        out.append(f"| `{a.id}` | {_cell(a.what)} | {', '.join(f'`{_cell(n)}`' for n in a.names)} |")
    out += ["", "Given arrays of the other byte order, or strided views, these give the native "
            "result bit for bit: " + ", ".join(f"`{n}`" for n in sorted(BYTE_ORDER_CASES)) + ".",
            "", "## Faults", "", "| test | what happens | outcome |", "|---|---|---|"]
    for name, text in FAULTS.items():
        out.append(f"| `test_fault_{name}` | {_cell(text)} | passes |")
    out += ["", "## Memory estimates", "",
            "Checked before the work against `MemAvailable` (80 % of it may be planned). The",
            "estimates are generous: above the peaks measured for these requests (growth of",
            "the resident size above a warm interpreter), as a test checks.", "",
            "| request | measured peak | estimate |", "|---|---|---|"]
    for what, measured, estimate in MEASURED:
        out.append(f"| {what} | {measured:.0f} MiB | {estimate() / 2**20:.0f} MiB |")
    out += ["", "## Expected failures (commands being rewritten)", ""]
    for reason in sorted({c.xfail for c in xfails if c.xfail}):
        ids = [c.id for c in xfails if c.xfail == reason]
        out.append(f"* {reason}: {', '.join(f'`{i}`' for i in ids)}")
    out.append("")
    return "\n".join(out)


def test_doc_lists_every_case() -> None:
    assert DOC.read_text() == render_doc(), (
        "docs/robustness.md is out of step with the tables; run "
        "`.venv/bin/python tests/test_robustness.py`")
    faults = {n.removeprefix("test_fault_") for n in globals() if n.startswith("test_fault_")}
    assert faults == set(FAULTS)


if __name__ == "__main__":
    DOC.write_text(render_doc())
    print(f"wrote {DOC}")
