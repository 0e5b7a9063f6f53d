"""The robustness cases of ``irnuc correct``."""

from __future__ import annotations

import hashlib
import json
import shutil
from collections.abc import Callable
from pathlib import Path
from typing import Any

from robustness.harness import case, command, other_kind, out_is_file, user_folder

# ---- changing a copy of the valid calibration ----------------------------------------

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
    from irnuc.nuc_fixed.memimage import seal_manifest

    m = _manifest(folder)
    m["files"] = {n: hashlib.sha256((folder / n).read_bytes()).hexdigest()
                  for n in m["files"] if (folder / n).is_file()}
    m["sha256"] = m["files"].get("coeffs.bin", m.get("sha256"))
    _set_manifest(folder, seal_manifest(m))


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


def _sealed(mutate: Callable[[Path], None]) -> Callable[[Path], None]:
    """``mutate``, then the manifest's own hashes recomputed (not the files'), so that a
    forged manifest reaches the checks behind its integrity hash."""
    def sealed(folder: Path) -> None:
        from irnuc.nuc_fixed.memimage import seal_manifest

        mutate(folder)
        _set_manifest(folder, seal_manifest(_manifest(folder)))
    return sealed


def _edit_file(name: str, change: Callable[[bytes], bytes]) -> Callable[[Path], None]:
    def mutate(folder: Path) -> None:
        p = folder / name
        p.write_bytes(change(p.read_bytes()))
    return mutate


def _flip_first_hex_digit(data: bytes) -> bytes:
    first = data[:1]
    return (b"1" if first != b"1" else b"2") + data[1:]


R = command("correct", (("irnuc.nuc_fixed.top", "nuc_dpc_top"),
                       ("irnuc.nuc_fixed.method_top", "method_top")))
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
case("correct-manifest-deep", R, CF, ("--coeffs", "manifest.json", "nested too deeply"),
     "a manifest of 10^5 nested lists (RecursionError)",
     setup=_coeffs_copy(lambda d: (d / "manifest.json").write_text("[" * 100_000 + "]" * 100_000)))
case("correct-manifest-huge", R, CF, ("--coeffs", "manifest.json", "larger than"),
     "a 17 MiB manifest (read with a size cap)",
     setup=_coeffs_copy(lambda d: (d / "manifest.json").write_bytes(b" " * (17 * 2**20))))
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
     setup=_coeffs_copy(_sealed(_edit_manifest(word_bits=64))))
case("correct-manifest-size-swapped", R, CF, ("--coeffs", "format fields", "height", "width", "edited"),
     "width and height swapped in manifest.json (applied 8 x 6 coefficients to 6 x 8 frames, exit 0)",
     setup=_coeffs_copy(lambda d: _edit_manifest(width=_manifest(d)["height"],
                                                 height=_manifest(d)["width"])(d)))
case("correct-manifest-size-rehashed", R, CF, ("--coeffs", "coeffs.bin", "bytes"),
     "height changed, hashes recomputed", setup=_coeffs_copy(_edit_manifest(height=7), rehash=True))
case("correct-manifest-config-missing", R, CF, ("--coeffs", "manifest.json", "['config']"), "no config name",
     setup=_coeffs_copy(_sealed(_edit_manifest(config=_DELETE))))
case("correct-manifest-file-path", R, CF, ("--coeffs", "plain name"), "a file name with a path",
     setup=_coeffs_copy(_sealed(lambda d: _edit_manifest(files={**_manifest(d)["files"],
                                                                "../x": "0"})(d))))
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
     setup=_coeffs_copy(_edit_file("coeffs.hex", lambda b: bytes(range(128, 256)) + b[128:]),
                        rehash=True))
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
case("correct-out-inside-coeffs", R, CF + " --out {t}/cal/corr", ("--out", "is inside", "irnuc calibrate"),
     "--out nested inside the calibration it reads (the next irnuc calibrate --out there deleted it)",
     setup=_coeffs_copy())
case("correct-out-file", R, CF + " --out {t}/out", ("--out", "not a folder"), "--out is a file",
     setup=lambda w, t: (_coeffs_copy()(w, t), out_is_file(w, t)))
case("correct-out-user-folder", R, CF + " --out {t}/out", ("--out", "other content"),
     "--out is a user's folder", setup=lambda w, t: (_coeffs_copy()(w, t), user_folder(w, t)))
case("correct-out-calibration", R, CF + " --out {t}/out", ("--out", "irnuc calibrate"),
     "--out holds a calibration", setup=lambda w, t: (_coeffs_copy()(w, t), other_kind("calibrate")(w, t)))


# ---- the manifest's integrity, the FPA sensor, method and stages (issue 42) -------------------
TC = "--frames {w}/tc_frames.npz --coeffs {t}/tcal"


def _tcal_copy(mutate: Callable[[Path], None] | None = None) -> Callable[[Path, Path], None]:
    def setup(w: Path, t: Path) -> None:
        shutil.copytree(w / "tcal", t / "tcal")
        if mutate is not None:
            mutate(t / "tcal")
    return setup


def _edit_t_ref(folder: Path) -> None:
    m = _manifest(folder)
    m["registers"]["t_ref"] += 100
    _set_manifest(folder, m)


def _sparse_badpix(folder: Path) -> None:
    with (folder / "badpix.csv").open("r+b") as fh:
        fh.truncate(20 * 2**30)  # 20 GiB, sparse


case("correct-manifest-register-edited", R, TC, ("--coeffs", "registers", "manifest was edited"),
     "the register t_ref edited in manifest.json (taken: every temperature term shifted)",
     setup=_tcal_copy(_edit_t_ref))
case("correct-sensor-other", R, "--frames {w}/tc_frames_other.npz --coeffs {t}/tcal",
     ("--frames", "FPA sensor", "lsb_K = 0.02", "lsb_K = 0.01"),
     "frames of another FPA sensor than the calibration's (output off by thousands of codes)",
     setup=_tcal_copy())
case("correct-pipeline-stage-mismatch", R, f"{CF} --pipeline ffc14",
     ("--coeffs", "differ from pipeline 'ffc14'", "'two_point+ffc'"),
     "two-point coefficients for a pipeline with an FFC stage (the stage silently not applied)",
     setup=_coeffs_copy())
case("correct-manifest-file-huge", R, CF, ("--coeffs", "badpix.csv", "bytes, more than"),
     "a 20 GB sparse file named by the manifest (read whole)",
     setup=_coeffs_copy(_sparse_badpix))
