"""The shared input files of the command-line cases: valid and hostile frames, TOML
files, baselines, and a valid calibration (built once per session, never written by a
case). A case that needs a file of its own makes it in its ``setup``."""

from __future__ import annotations

import io
import shutil
import zipfile
from pathlib import Path
from typing import Any

import numpy as np

from robustness.harness import REPO

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




def baseline(metrics: Any = None, **top: Any) -> str:
    """A baseline summary of ``--config small`` as JSON text: valid but for the fields
    given (``metrics``, or top-level fields; ``_DROP`` removes one)."""
    import json

    from irnuc.reports.report.config import config_hash, load_report_config

    cfg = load_report_config("small")
    doc: dict[str, Any] = {
        "schema_version": 2, "tool": "irnuc report",
        "provenance": {"config_name": cfg["name"], "config_hash": config_hash(cfg),
                       "git_commit": None},
        "metrics": {"calibration.bad_pixels": {"value": 1, "better": "lower"}}
        if metrics is None else metrics}
    doc.update(top)
    return json.dumps({k: v for k, v in doc.items() if v is not _DROP})


_DROP = object()


def baselines() -> dict[str, str]:
    """The hostile baselines, by name (``base_<name>.json`` in the world folder)."""
    from irnuc.reports.report.config import config_hash, load_report_config

    other = load_report_config("default")
    bad = "calibration.bad_pixels"
    return {
        "metrics_list": baseline([]),
        "metric_number": baseline({bad: 1}),
        "metric_string": baseline({bad: "many"}),
        "metric_list": baseline({bad: [1]}),
        "nan": baseline({bad: {"value": float("nan"), "better": "lower"}}),
        "value_text": baseline({bad: {"value": "x", "better": "lower"}}),
        "value_huge": baseline({bad: {"value": 10**4000, "better": "lower"}}),
        "digits_5001": baseline().replace('"value": 1', '"value": 1' + "0" * 5000),
        "provenance_text": baseline(provenance="x"),
        "no_provenance": baseline(provenance=_DROP),
        "empty_metrics": baseline({}),
        "schema_99": baseline(schema_version=99),
        "schema_1": baseline(schema_version=1),
        "schema_text": baseline(schema_version="2"),
        "tool_calibrate": baseline(tool="irnuc calibrate"),
        "other_config": baseline(provenance={"config_name": "default",
                                             "config_hash": config_hash(other)}),
        "edited_config": baseline(provenance={"config_name": "small",
                                              "config_hash": "0" * 16}),
        "deep": '{"metrics": ' + "[" * 100_000 + "]" * 100_000 + "}",
    }


def _fields_npz(path: Path, codes: np.ndarray, scene_K: np.ndarray, fpa_K: np.ndarray,
                sensor: Any = None, **extra: Any) -> None:
    """A frames file with the per-frame fields (and the FPA sensor) of this version."""
    from irnuc.model.fpa_sensor import FpaSensor, frame_fields

    sensor = sensor or FpaSensor()
    n = codes.shape[0]
    fields = frame_fields(np.arange(n) / 30.0, fpa_K, fpa_K, scene_K, np.zeros(n, bool), sensor)
    _npz(path, codes=codes, temps=scene_K, adc_bits=np.int64(14), **fields,
         **sensor.arrays(), **extra)


def _method_world(w: Path) -> None:
    """A tc_offset calibration (``tcal``: random codes, the default FPA sensor), frames of
    that sensor and of another, frames of unequal calibration points, frames whose readings
    are all equal, and a frames file whose codes header disagrees with its stored size."""
    from irnuc.cocotb_tests.method_stim import random_coefficients
    from irnuc.model.fpa_sensor import FpaSensor
    from irnuc.nuc_fixed import load_pipeline
    from irnuc.nuc_fixed.memimage import write_method_image

    rng = np.random.default_rng(4)
    cfg = load_pipeline("tcoffset14")
    c = random_coefficients(cfg, 6, 8, rng, registers={"t_ref": 7500})
    write_method_image(w / "tcal", c, fpa_sensor=FpaSensor())
    codes = rng.integers(3000, 9000, (3, 6, 8)).astype(np.uint16)
    for name, sensor in (("tc_frames", FpaSensor()), ("tc_frames_other", FpaSensor(lsb_K=0.02))):
        _fields_npz(w / f"{name}.npz", codes, np.full(3, 320.0), np.full(3, 300.0), sensor)
    # Two scenes at one FPA temperature: 2 frames at 300 K, 3 at 400 K.
    x = rng.integers(3000, 9000, (5, 6, 8)).astype(np.uint16)
    _fields_npz(w / "unequal_points.npz", x, np.array([300.0] * 2 + [400.0] * 3), np.full(5, 300.0))
    # Three FPA points and three scenes, all read as one code (a 1-bit sensor).
    scene = np.tile([290.0, 330.0, 370.0], 3)
    fpa = np.repeat([288.0, 298.0, 308.0], 3)
    codes9 = (4000 + 40 * (scene - 290) + rng.integers(0, 20, (6, 8, 9))).T.swapaxes(1, 2)
    _fields_npz(w / "readings_equal.npz", codes9.astype(np.uint16), scene, fpa, FpaSensor(bits=1))
    # The codes header declares one frame more than the member stores.
    src = w / "good.npz"
    with zipfile.ZipFile(src) as zin, zipfile.ZipFile(w / "header_size.npz", "w") as zout:
        for info in zin.infolist():
            data = zin.read(info)
            if info.filename == "codes.npy":
                data = data.replace(b"'shape': (4, 6, 8)", b"'shape': (5, 6, 8)")
            zout.writestr(info.filename, data)


def build_world(root: Path) -> Path:
    """Valid and hostile input files shared by the cases (never written by a case)."""
    from irnuc.cli import main
    from irnuc.nuc_fixed import load_pipeline
    from irnuc.nuc_fixed.synthetic import synth_frames

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
        "junit_bad.xml": "<testsuite",
        "junit_root.xml": "<html/>",
    }
    files.update({f"base_{k}.json": v for k, v in baselines().items()})
    files.update({
    })
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
    files["rep_only_name.toml"] = 'name = "x"\n'
    files["rep_cosim_only.toml"] = '[cosim]\npipelines = ["minimal"]\ntests = ["corner_codes"]\n'
    files["rep_sensor_pipeline.toml"] = sm.replace('pipeline = "typical14"\n[sensor.overrides]',
                                                   'pipeline = "typicl14"\n[sensor.overrides]')
    files["rep_sensor_preset.toml"] = sm.replace('[sensor]\npreset = "default"',
                                                 '[sensor]\npreset = "defualt"')
    files["rep_sensor_override.toml"] = sm.replace('"noise.enabled" = true',
                                                   '"noise.enabeld" = true', 1)
    files["rep_sensor_override_value.toml"] = sm.replace('"noise.enabled" = true',
                                                         '"noise.enabled" = 3', 1)
    files["rep_sensor_rows.toml"] = sm.replace('"noise.enabled" = true',
                                               '"noise.enabled" = true\n"fpa.active_rows" = 99', 1)
    files["rep_precision.toml"] = sm.replace("[precision]\nquick = true",
                                             '[precision]\nquick = true\ncomponents = ["radiance_x"]')
    files["rep_skim.toml"] = sm.replace('skimming = ["row", "column"]', 'skimming = ["diagonal"]')
    for name, content in files.items():
        (w / name).write_bytes(content if isinstance(content, bytes) else content.encode())

    _method_world(w)
    # A valid calibration (copied by the correct cases) and another run's binary image.
    assert main(["calibrate", "-q", "--frames", str(w / "good.npz"), "--out", str(w / "cal")]) == 0
    assert main(["calibrate", "-q", "--frames", str(w / "good2.npz"), "--out",
                 str(root / "cal2")]) == 0
    shutil.copy(root / "cal2" / "coeffs.bin", w / "cal2.bin")
    return w
