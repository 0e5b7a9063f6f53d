"""Coefficient words and memory image files: layout, round trips, corruption detection."""

from __future__ import annotations

import hashlib
import json
from pathlib import Path

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from irnuc.nuc_fixed import (
    ConfigError,
    InputError,
    MemImageError,
    load_pipeline,
    pack_words,
    pipeline_names,
    read_memimage,
    unpack_words,
    write_memimage,
)
from irnuc.nuc_fixed.memimage import seal_manifest

NAMES = pipeline_names()


def _coeffs(cfg, h: int, w: int, seed: int):
    rng = np.random.default_rng(seed)
    g = rng.integers(0, 2**cfg.gain_bits, (h, w))
    ow = cfg.offset_bits
    o = rng.integers(-(2 ** (ow - 1)), 2 ** (ow - 1), (h, w))
    # Put the extremes in.
    g.flat[:2] = [0, 2**cfg.gain_bits - 1]
    o.flat[:2] = [-(2 ** (ow - 1)), 2 ** (ow - 1) - 1]
    return g, o, rng.random((h, w)) < 0.2


@pytest.mark.parametrize("name", NAMES)
@settings(max_examples=60, deadline=None)
@given(g=st.integers(0), o=st.integers(), bad=st.booleans())
def test_word_layout_matches_python_ints(name: str, g: int, o: int, bad: bool) -> None:
    cfg = load_pipeline(name)
    gw, ow = cfg.gain_bits, cfg.offset_bits
    g %= 2**gw
    o = o % 2**ow - 2 ** (ow - 1)
    # Independent layout: concatenate bit strings, MSB first.
    bits = ("1" if bad else "0") + format(o % 2**ow, f"0{ow}b") + format(g, f"0{gw}b")
    word = pack_words(np.array([g]), np.array([o]), np.array([bad]), cfg)
    assert int(word[0]) == int(bits, 2) and len(bits) == cfg.word_bits
    g2, o2, b2 = unpack_words(word, cfg)
    assert (int(g2[0]), int(o2[0]), bool(b2[0])) == (g, o, bad)


@pytest.mark.parametrize("name", NAMES)
@pytest.mark.parametrize("source", ["bin", "hex"])
def test_round_trip(tmp_path: Path, name: str, source: str) -> None:
    cfg = load_pipeline(name)
    g, o, bad = _coeffs(cfg, 5, 9, 1)
    words = pack_words(g, o, bad, cfg)
    manifest = write_memimage(tmp_path, words, cfg)
    back, mcfg = read_memimage(tmp_path, cfg, source=source)
    assert back.dtype == np.uint64 and np.array_equal(back, words)
    assert mcfg == cfg
    g2, o2, b2 = unpack_words(back, mcfg)
    assert np.array_equal(g2, g) and np.array_equal(o2, o) and np.array_equal(b2, bad)
    # File formats as documented.
    lines = (tmp_path / "coeffs.hex").read_text().splitlines()
    assert len(lines) == 45 and all(len(s) == -(-cfg.word_bits // 4) for s in lines)
    assert [int(s, 16) for s in lines] == [int(v) for v in words.ravel()]
    assert lines[0] == lines[0].lower()
    raw = (tmp_path / "coeffs.bin").read_bytes()
    nb = -(-cfg.word_bits // 8)
    assert len(raw) == 45 * nb
    assert [int.from_bytes(raw[i * nb:(i + 1) * nb], "little") for i in range(45)] == lines_int(
        lines)
    assert manifest["version"] == 1 and manifest["word_bits"] == cfg.word_bits
    assert (manifest["width"], manifest["height"]) == (9, 5)
    assert json.loads((tmp_path / "manifest.json").read_text()) == manifest


def lines_int(lines: list[str]) -> list[int]:
    return [int(s, 16) for s in lines]


def _written(tmp_path: Path, name: str = "typical14") -> None:
    cfg = load_pipeline(name)
    write_memimage(tmp_path, pack_words(*_coeffs(cfg, 4, 4, 2), cfg), cfg)


def test_checksum_mismatch_detected(tmp_path: Path) -> None:
    _written(tmp_path)
    data = bytearray((tmp_path / "coeffs.bin").read_bytes())
    data[3] ^= 0x01
    (tmp_path / "coeffs.bin").write_bytes(bytes(data))
    with pytest.raises(MemImageError, match="SHA-256"):
        read_memimage(tmp_path)


def test_hex_corruption_detected(tmp_path: Path) -> None:
    _written(tmp_path)
    path = tmp_path / "coeffs.hex"
    lines = path.read_text().splitlines()
    lines[5] = format(int(lines[5], 16) ^ 1, f"0{len(lines[5])}x")
    path.write_text("\n".join(lines) + "\n")
    # The manifest hashes the hex file too: it is checked whichever file is read.
    for source in ("bin", "hex"):
        with pytest.raises(MemImageError, match=r"coeffs\.hex: SHA-256"):
            read_memimage(tmp_path, source=source)
    # A hex file that matches its (re-made) hash but not the binary is caught word by word.
    manifest = json.loads((tmp_path / "manifest.json").read_text())
    manifest["files"]["coeffs.hex"] = hashlib.sha256(path.read_bytes()).hexdigest()
    (tmp_path / "manifest.json").write_text(json.dumps(seal_manifest(manifest)))
    with pytest.raises(MemImageError, match=r"\(row, col\) \(1, 1\)"):
        read_memimage(tmp_path, source="hex")
    path.write_text("\n".join(lines[:-1]) + "\n")
    manifest["files"]["coeffs.hex"] = hashlib.sha256(path.read_bytes()).hexdigest()
    (tmp_path / "manifest.json").write_text(json.dumps(seal_manifest(manifest)))
    with pytest.raises(MemImageError, match="15 lines, expected 16"):
        read_memimage(tmp_path, source="hex")


def test_edited_format_field_detected(tmp_path: Path) -> None:
    _written(tmp_path)
    manifest = json.loads((tmp_path / "manifest.json").read_text())
    manifest["rounding"] = "truncate"
    (tmp_path / "manifest.json").write_text(json.dumps(manifest))
    with pytest.raises(MemImageError, match=r"format fields .* do not match"):
        read_memimage(tmp_path)


def test_manifest_mismatch_detected(tmp_path: Path) -> None:
    _written(tmp_path)
    with pytest.raises(MemImageError, match="format fields differ"):
        read_memimage(tmp_path, "wide16")
    m = json.loads((tmp_path / "manifest.json").read_text())
    m["version"] = 2
    (tmp_path / "manifest.json").write_text(json.dumps(seal_manifest(m)))
    with pytest.raises(MemImageError, match="version = 2"):
        read_memimage(tmp_path)


def test_pack_errors() -> None:
    cfg = load_pipeline("minimal")
    with pytest.raises(InputError, match=r"gain\[1\] = 16 .*\[0, 15\]"):
        pack_words(np.array([0, 16]), np.array([0, 0]), np.array([False, False]), cfg)
    with pytest.raises(InputError, match=r"bad has shape"):
        pack_words(np.array([0]), np.array([0]), np.array([False, True]), cfg)
    with pytest.raises(InputError, match=r"words\[0\] = 2048"):
        unpack_words(np.array([2048], dtype=np.uint64), cfg)
    too_wide = load_pipeline("wide16").replace(offset_int_bits=32, offset_frac_bits=10)
    with pytest.raises(ConfigError, match="word_bits = 67"):
        pack_words(np.array([0]), np.array([0]), np.array([False]), too_wide)


# ---- the manifest's integrity, the FPA sensor, the configuration (issue 42) -----------------

def _leaves(d: object, path: tuple = ()) -> list[tuple]:
    if isinstance(d, dict):
        return [p for k, v in d.items() for p in _leaves(v, (*path, k))] or [path]
    if isinstance(d, list):
        return [p for i, v in enumerate(d) for p in _leaves(v, (*path, i))] or [path]
    return [path]


def _changed(v: object) -> object:
    if isinstance(v, bool):
        return not v
    if isinstance(v, int | float):
        return v + 1
    if isinstance(v, str):
        return v + "x"
    return [] if v is None else None


@pytest.mark.parametrize("name", ["typical14", "tcoffset14", "table14", "drift14", "ffc14"])
def test_every_manifest_field_is_covered_by_the_integrity_hash(tmp_path: Path, name: str) -> None:
    """Any edit of any field of a manifest (a register, the FPA sensor, a file's hash, a
    layout, the description ...) is refused, and removing any top-level field too: an
    edited t_ref was taken, changing every temperature term."""
    from irnuc.cocotb_tests.method_stim import random_coefficients
    from irnuc.model.fpa_sensor import FpaSensor
    from irnuc.nuc_fixed.memimage import read_calibration, write_method_image

    cfg = load_pipeline(name)
    c = random_coefficients(cfg, 3, 4, np.random.default_rng(1))
    write_method_image(tmp_path, c, fpa_sensor=FpaSensor())
    text = (tmp_path / "manifest.json").read_text()
    read_calibration(tmp_path)  # the written folder reads
    good = json.loads(text)
    assert "fpa_sensor" in good and good.get("registers", {}) == {
        k: list(v) if isinstance(v, tuple) else v for k, v in c.registers.items()}
    leaves = _leaves(good)
    assert len(leaves) > 20
    for path, edit in [*((p, "change") for p in leaves), *(((k,), "remove") for k in good)]:
        m = json.loads(text)
        node = m
        for k in path[:-1]:
            node = node[k]
        if edit == "change":
            node[path[-1]] = _changed(node[path[-1]])
        else:
            del node[path[-1]]
        (tmp_path / "manifest.json").write_text(json.dumps(m))
        with pytest.raises(MemImageError):
            read_calibration(tmp_path)
    (tmp_path / "manifest.json").write_text(text)
    read_calibration(tmp_path)


def test_the_sensor_fields_that_change_the_codes_are_compared() -> None:
    """Every FpaSensor setting that changes the code a temperature reads (its noise does
    not: it changes frame by frame) is in SENSOR_CODE_FIELDS, and a difference in any is
    refused for the methods that read the sensor, for no other method."""
    from dataclasses import asdict, fields, replace

    from irnuc.model.fpa_sensor import FpaSensor
    from irnuc.nuc_fixed.memimage import SENSOR_CODE_FIELDS, check_sensor, sensor_record

    base = FpaSensor()
    temps = np.linspace(280.0, 320.0, 41)
    changes = {"bits": 12, "lsb_K": 0.02, "zero_K": 220.0, "offset_K": 0.5, "noise_K": 0.1,
               "lag_s": 5.0}
    assert set(changes) == {f.name for f in fields(FpaSensor)}
    moves_codes = {k for k, v in changes.items() if k != "noise_K"
                   and not np.array_equal(replace(base, **{k: v}).read(temps), base.read(temps))}
    assert moves_codes == set(SENSOR_CODE_FIELDS)
    rec = sensor_record(base)
    assert rec == asdict(base)
    for k, v in changes.items():
        other = replace(base, **{k: v})
        for name in ("tcoffset14", "table14", "tcffc14"):
            if k in SENSOR_CODE_FIELDS:
                with pytest.raises(MemImageError, match=f"FPA sensor.*{k}"):
                    check_sensor(rec, other, load_pipeline(name), "frames", "coeffs")
            else:
                check_sensor(rec, other, load_pipeline(name), "frames", "coeffs")
        for name in ("typical14", "ffc14", "drift14", "quadratic14"):
            check_sensor(rec, other, load_pipeline(name), "frames", "coeffs")
    with pytest.raises(MemImageError, match="does not record the FPA sensor"):
        check_sensor(None, base, load_pipeline("tcoffset14"), "frames", "coeffs")


def test_the_housing_sensor_is_recorded_and_compared(tmp_path: Path) -> None:
    """The housing sensor of the calibration is in the manifest and compared for the
    methods that read it (tc_housing), on every setting that moves its code and on its
    node (a sensor on the lens reads another temperature); no other method is refused."""
    from dataclasses import fields, replace

    from irnuc.cocotb_tests.method_stim import random_coefficients
    from irnuc.model.fpa_sensor import FpaSensor, HousingSensor
    from irnuc.nuc_fixed.memimage import (
        HOUSING_SENSOR_CODE_FIELDS,
        check_sensor,
        read_calibration,
        write_method_image,
    )

    base = HousingSensor()
    temps = np.linspace(280.0, 320.0, 41)
    changes = {"bits": 12, "lsb_K": 0.02, "zero_K": 220.0, "offset_K": 0.5, "noise_K": 0.1,
               "lag_s": 5.0, "node": "lens"}
    assert set(changes) == {f.name for f in fields(HousingSensor)}
    moves_codes = {k for k, v in changes.items() if k not in ("noise_K", "node")
                   and not np.array_equal(replace(base, **{k: v}).read(temps), base.read(temps))}
    assert moves_codes | {"node"} == set(HOUSING_SENSOR_CODE_FIELDS)

    cfg = load_pipeline("tchousing14")
    c = random_coefficients(cfg, 3, 4, np.random.default_rng(5))
    write_method_image(tmp_path, c, fpa_sensor=FpaSensor(), housing_sensor=base)
    _, manifest = read_calibration(tmp_path)
    rec = manifest["housing_sensor"]
    assert rec["node"] == "housing" and rec["bits"] == base.bits
    for k, v in changes.items():
        other = replace(base, **{k: v})
        if k in HOUSING_SENSOR_CODE_FIELDS:
            with pytest.raises(MemImageError, match=f"housing sensor.*{k}"):
                check_sensor(rec, other, cfg, "frames", "coeffs", kind="housing")
        else:
            check_sensor(rec, other, cfg, "frames", "coeffs", kind="housing")
        for name in ("tcoffset14", "tcffc14", "typical14"):  # they do not read it
            check_sensor(None, other, load_pipeline(name), "frames", "coeffs", kind="housing")
    with pytest.raises(MemImageError, match="does not record the housing sensor"):
        check_sensor(None, base, cfg, "frames", "coeffs", kind="housing")


def test_coefficients_are_read_only_for_their_whole_configuration(tmp_path: Path) -> None:
    """--pipeline is compared on every field (formats, method and stages, parameters), not
    the formats only: two-point coefficients were taken for ffc14 and its stage silently
    not applied. The same fields under another name are accepted."""
    from irnuc.cocotb_tests.method_stim import random_coefficients
    from irnuc.nuc_fixed.memimage import read_calibration, write_method_image

    for name in ("typical14", "tcoffset14"):
        cfg = load_pipeline(name)
        d = tmp_path / name
        write_method_image(d, random_coefficients(cfg, 3, 4, np.random.default_rng(2)))
        for other in pipeline_names(method=None):
            o = load_pipeline(other)
            same = o.to_dict() | {"name": "", "description": ""} == (
                cfg.to_dict() | {"name": "", "description": ""})
            if same:
                read_calibration(d, o)
            else:
                with pytest.raises(MemImageError, match=f"differ from pipeline '{other}'"):
                    read_calibration(d, o)
        read_calibration(d, cfg.replace(name="renamed", description="elsewhere"))
