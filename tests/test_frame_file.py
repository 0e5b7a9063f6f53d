"""The frame file: uncompressed .npz streamed in chunks, read memory-mapped, every field
returned by name by the one reader (irnuc.cli._files.load_frames)."""

from __future__ import annotations

import json
import zipfile

import numpy as np
import pytest

from irnuc.cli import main
from irnuc.cli._files import load_frames
from irnuc.common.errors import UserError
from irnuc.common.framefile import FrameWriter, open_member
from irnuc.model.fpa_sensor import FRAME_FIELDS, FpaSensor

SMALL = ["--set", "fpa.active_rows=10", "--set", "fpa.active_cols=12"]


def test_writer_streams_chunks_into_a_standard_uncompressed_npz(tmp_path):
    p = tmp_path / "f.npz"
    frames = np.arange(7 * 3 * 5, dtype=np.uint16).reshape(7, 3, 5)
    with FrameWriter(p, 7, (3, 5), np.uint16) as w:
        for start in (0, 3, 6):
            w.write(frames[start:start + 3])
        w.close({"temps": np.linspace(300, 306, 7), "note": np.array("x")})
    with np.load(p) as z:  # numpy reads it as any .npz
        np.testing.assert_array_equal(z["codes"], frames)
        assert str(z["note"]) == "x"
    with zipfile.ZipFile(p) as zf:
        assert {i.compress_type for i in zf.infolist()} == {zipfile.ZIP_STORED}
        mapped = open_member(p, zf, "codes")
        assert isinstance(mapped, np.memmap)
        np.testing.assert_array_equal(mapped, frames)


def test_writer_refuses_a_short_or_long_file(tmp_path):
    w = FrameWriter(tmp_path / "a.npz", 2, (2, 2), np.uint16)
    w.write(np.zeros((1, 2, 2), np.uint16))
    with pytest.raises(ValueError, match="1 of 2 frames"):
        w.close({})
    w = FrameWriter(tmp_path / "b.npz", 1, (2, 2), np.uint16)
    with pytest.raises(ValueError, match="more than the 1 frames"):
        w.write(np.zeros((2, 2, 2), np.uint16))
    w.abort()


def test_plain_frames_carry_constant_fields_sensor_and_reference_pixels(tmp_path):
    out = tmp_path / "f"
    assert main(["frames", *SMALL, "--set", "environment.T_substrate=301.5", "--temps",
                 "300,320", "--repeats", "2", "--seed", "3", "--out", str(out)]) == 0
    data = load_frames(str(out))
    n = 4
    assert isinstance(data["codes"], np.memmap) and data["codes"].shape == (n, 10, 12)
    for name, (dtype, _, _) in FRAME_FIELDS.items():
        assert data[name].shape == (n,) and data[name].dtype == np.dtype(dtype), name
    np.testing.assert_array_equal(data["scene_K"], [300.0, 300.0, 320.0, 320.0])
    np.testing.assert_array_equal(data["fpa_K"], 301.5)
    np.testing.assert_array_equal(data["T_cam_K"], 300.0)
    assert not data["shutter"].any() and not data["fields_synthesized"]
    np.testing.assert_allclose(np.diff(data["time_s"]), 1 / data["frame_rate"])
    sensor = data["fpa_sensor"]
    assert isinstance(sensor, FpaSensor) and sensor == FpaSensor()
    # the reading is the sensor's integer code of 301.5 K: (301.5 - 223.15) / 0.01
    np.testing.assert_array_equal(data["fpa_reading"], round((301.5 - 223.15) / 0.01))
    # the boundary ring (1 pixel wide) read out beside the image
    k = (10 + 2) * (12 + 2) - 10 * 12
    assert data["blind_codes"].shape == (n, k) and data["blind_positions"].shape == (k, 2)
    np.testing.assert_array_equal(data["active_origin"], [3, 3])
    meta = json.loads(str(data["config_json"]))
    assert meta["config"]["readout"]["reference_pixels"] == "boundary"


def test_an_older_compressed_file_gets_its_fields_from_its_configuration(tmp_path):
    p = tmp_path / "old.npz"
    cfg = {"config": {"environment": {"T_substrate": 299.0, "T_cam": 303.0}}}
    np.savez_compressed(p, codes=np.ones((3, 2, 2), np.uint16), temps=np.array([300.0] * 3),
                        adc_bits=np.int64(14), config_json=np.array(json.dumps(cfg)))
    data = load_frames(str(p))
    assert data["fields_synthesized"]
    np.testing.assert_array_equal(data["fpa_K"], 299.0)
    np.testing.assert_array_equal(data["T_cam_K"], 303.0)
    assert data["blind_codes"].shape == (3, 0)


@pytest.mark.parametrize(("change", "fragment"), [
    ({"fpa_K": np.array([300.0, np.nan])}, "fpa_K must hold finite numbers"),
    ({"shutter": np.array([0, 1])}, "shutter has dtype int64; bool is required"),
    ({"fpa_reading": np.array([0, 1 << 20])}, "fpa_reading spans 0..1048576"),
    ({"time_s": np.zeros(3)}, "time_s has shape (3,)"),
    ({"blind_codes": np.zeros((2, 3), np.uint16)}, "blind_positions has shape (0, 2)"),
    ({"fpa_sensor_bits": np.int64(99)}, "bad FPA sensor settings (fpa_sensor.bits = 99"),
])
def test_bad_fields_are_one_line_errors_naming_the_key(tmp_path, change, fragment):
    arrays = {"codes": np.ones((2, 2, 2), np.uint16), "temps": np.array([300.0, 300.0]),
              "adc_bits": np.int64(14), "time_s": np.array([0.0, 0.1]),
              "fpa_K": np.array([300.0, 300.0]), "fpa_reading": np.array([7000, 7000]),
              "T_cam_K": np.array([300.0, 300.0]), "scene_K": np.array([300.0, 300.0]),
              "shutter": np.array([False, False])}
    arrays.update(change)
    p = tmp_path / "bad.npz"
    np.savez(p, **arrays)
    with pytest.raises(UserError, match="--frames") as err:
        load_frames(str(p))
    assert fragment in str(err.value) and "\n" not in str(err.value)


def test_calibrate_and_correct_read_model_frames_and_sequences(tmp_path):
    """Calibrate on plain frames, correct a drift sequence, both through load_frames; the
    correction of a memory-mapped sequence is the golden model's of its codes."""
    from irnuc.nuc_fixed import nuc_dpc_top, read_memimage

    small = ["--set", "fpa.active_rows=12", "--set", "fpa.active_cols=16"]
    assert main(["frames", "-q", *small, "--temps", "300,340", "--repeats", "4", "--out",
                 str(tmp_path / "cal_frames")]) == 0
    assert main(["calibrate", "-q", "--frames", str(tmp_path / "cal_frames"), "--out",
                 str(tmp_path / "cal")]) == 0
    toml = tmp_path / "s.toml"
    toml.write_text('[sequence]\nframe_rate = 30.0\nduration = 1.0\nhousing = 300.0\n'
                    'scene = 320.0\n[sequence.fpa]\nprofile = "ramp"\nstart = 300.0\n'
                    'rate = 30.0\n[sequence.shutter]\nat = [0.5]\nframes = 2\n')
    assert main(["frames", "-q", *small, "--sequence", str(toml), "--params", "--out",
                 str(tmp_path / "seq")]) == 0
    assert main(["correct", "-q", "--frames", str(tmp_path / "seq"), "--coeffs",
                 str(tmp_path / "cal"), "--out", str(tmp_path / "corr")]) == 0
    seq = load_frames(str(tmp_path / "seq"))
    assert seq["param_R_ref"].shape == (12 + 6, 16 + 6)
    words, cfg = read_memimage(tmp_path / "cal", "typical14", source="hex")
    with np.load(tmp_path / "corr" / "corrected.npz") as z:
        np.testing.assert_array_equal(z["corrected"], nuc_dpc_top(np.asarray(seq["codes"]),
                                                                  words, cfg))
