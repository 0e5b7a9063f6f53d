"""The robustness cases of ``irnuc calibrate``."""

from __future__ import annotations

import shutil
from pathlib import Path

from robustness.harness import (
    case,
    command,
    link_out,
    other_kind,
    out_is_file,
    ro_parent,
    stale_tmp,
    user_folder,
    write_file,
)


def _frames_in_out(w: Path, t: Path) -> None:
    (t / "out").mkdir()
    shutil.copy(w / "good.npz", t / "out" / "frames.npz")
    (t / "out" / ".irnuc-output").write_text("irnuc calibrate\n")




def _nested_output(w: Path, t: Path) -> None:
    (t / "out" / "corr").mkdir(parents=True)
    (t / "out" / ".irnuc-output").write_text("irnuc calibrate\n")
    (t / "out" / "corr" / ".irnuc-output").write_text("irnuc correct\n")
    (t / "out" / "corr" / "frames.npz").write_bytes(b"results")


K = command("calibrate", (("irnuc.nuc_fixed.calibrate", "calibrate"),
                         ("irnuc.nuc_fixed.plan", "run_plan"),
                         ("irnuc.nuc_fixed.fit", "calibrate_points")))
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
case("calibrate-targets-reversed", K, f"{G} --targets 9000,1000", ("--targets", "LOW", "below HIGH"),
     "targets high to low (was blamed on the thresholds and the frames, after the work)")
case("calibrate-targets-equal", K, f"{G} --targets 5000,5000", ("--targets", "below HIGH"),
     "equal targets (a zero gain)")
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
case("calibrate-thresholds-dev-zero", K, f"{G} --thresholds /dev/zero",
     ("--thresholds", "/dev/zero", "not a regular file"), "a device as thresholds")
case("calibrate-pipeline-dev-zero", K, f"{G} --pipeline /dev/zero.toml",
     ("--pipeline", "/dev/zero.toml", "no such file"), "a device path that is no file")
case("calibrate-pipeline-dev-zero-file", K, f"{G} --pipeline /dev/zero",
     ("--pipeline", "/dev/zero", "larger than"), "an endless file as the pipeline")
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
     setup=out_is_file)
case("calibrate-out-user-folder", K, f"{G} --out {{t}}/out", ("--out", "other content"),
     "--out is a user's folder (never deleted)", setup=user_folder)
case("calibrate-out-frames-output", K, f"{G} --out {{t}}/out", ("--out", "irnuc frames"),
     "--out holds the output of irnuc frames", setup=other_kind("frames"))
case("calibrate-out-holds-frames", K, "--frames {t}/out/frames.npz --out {t}/out",
     ("--out", "--frames", "would replace"), "--out holds the frames it reads", setup=_frames_in_out)
case("calibrate-out-holds-other-output", K, f"{G} --out {{t}}/out", ("--out", "holds corr", "irnuc correct"),
     "--out is a calibration holding another command's output (deleted without a word)",
     setup=_nested_output)
case("calibrate-out-link", K, f"{G} --out {{t}}/out", ("--out", "symbolic link"), "--out is a link",
     setup=link_out)
case("calibrate-out-cwd", K, f"{G} --out .", ("--out", "current folder"), "--out is the current folder",
     check_out=False)
case("calibrate-out-read-only-parent", K, f"{G} --out {{t}}/ro/out", ("--out", "no permission"),
     "--out inside a read-only folder", setup=ro_parent)
case("calibrate-stale-tmp-and-bad-frames", K, "--frames {w}/text.npz --out {t}/out", ("--frames",),
     "a killed run's temporary folder beside --out, then a bad input", setup=stale_tmp)


# ---- plans, method frames (issue 42) ---------------------------------------------------------
PLAN = "[plan]\nscene = [290.0, 330.0, 370.0]\nfpa = [288.0, 298.0, 308.0]\nframes = 2\n"
PL = "--plan p.toml --set fpa.active_rows=6 --set fpa.active_cols=8"


def _pipeline(**fields: int) -> str:
    """tcoffset14 as a pipeline file [p] with these fields changed (as text: an illegal
    combination cannot be made as a configuration)."""
    from irnuc.nuc_fixed import load_pipeline

    cfg = load_pipeline("tcoffset14")
    text = cfg.to_toml().replace("[tcoffset14]", "[p]")
    for k, v in fields.items():
        text = text.replace(f"\n{k} = {getattr(cfg, k)}\n", f"\n{k} = {v}\n")
        assert f"\n{k} = {v}\n" in text, k
    return text


case("calibrate-plan-fpa-model-range", K, f"{PL} --pipeline tcoffset14",
     ("--plan", "plan.fpa[2] = 900 K", "[100, 500]"),
     "an FPA temperature the model refuses (accepted by the plan, refused after by the model "
     "without the plan's key)", setup=write_file("p.toml", PLAN.replace("308.0", "900.0")))
case("calibrate-plan-cam-model-range", K, f"{PL} --pipeline tcoffset14",
     ("--plan", "plan.cam[0] = 600 K"), "a housing temperature the model refuses",
     setup=write_file("p.toml", PLAN + "cam = [600.0, 300.0, 300.0]\n"))
case("calibrate-plan-sensor-coarse", K, f"{PL} --pipeline tcoffset14",
     ("--plan", "reads [1, 1, 2]", "too coarse"),
     "an FPA sensor too coarse for the plan (refused after the simulation: widen tc1 to 23 bits)",
     setup=write_file("p.toml", PLAN + "[fpa_sensor]\nlsb_K = 50.0\n"))
case("calibrate-plan-sensor-one-bit", K, f"{PL} --pipeline table14",
     ("--plan", "reads [1, 1, 1]", "table_interp"), "a 1-bit FPA sensor for table_interp",
     setup=write_file("p.toml", PLAN + "[fpa_sensor]\nbits = 1\n"))
case("calibrate-plan-reading-bits", K, f"{PL} --pipeline pipe.toml",
     ("--plan", "reading_bits = 8", "0..255"),
     "a pipeline whose readings are narrower than the sensor's (refused after the simulation)",
     setup=lambda w, t: (write_file("p.toml", PLAN)(w, t), write_file(
         "pipe.toml", _pipeline(reading_bits=8, reading_range_bits=8))(w, t)))
case("calibrate-plan-reading-range", K, f"{PL} --pipeline pipe.toml",
     ("--plan", "reading_range_bits = 8", "-1000 codes"),
     "FPA points farther from the reference than reading_range_bits holds",
     setup=lambda w, t: (write_file("p.toml", PLAN)(w, t), write_file(
         "pipe.toml", _pipeline(reading_range_bits=8))(w, t)))
case("calibrate-pipeline-reading-range-above", K, f"{PL} --pipeline pipe.toml",
     ("--pipeline", "reading_range_bits = 15", "at most reading_bits = 14"),
     "reading_range_bits above reading_bits (refused after the simulation with advice to "
     "widen tc1)",
     setup=lambda w, t: (write_file("p.toml", PLAN)(w, t), write_file(
         "pipe.toml", _pipeline(reading_range_bits=15))(w, t)))
case("calibrate-frames-header-size", K, "--frames {w}/header_size.npz",
     ("--frames", "damaged", "declares shape (5, 6, 8)"),
     "a frame file whose codes header disagrees with its stored size (read anyway)")
case("calibrate-frames-unequal-points", K, "--frames {w}/unequal_points.npz --pipeline onepoint14",
     ("--frames", "3 frames at scene 400 K", "the same number of frames"),
     "calibration points of different frame counts (frames silently dropped)")
case("calibrate-frames-readings-equal", K, "--frames {w}/readings_equal.npz --pipeline tcoffset14",
     ("--frames", "reads [1, 1, 1]", "too coarse"),
     "tc_offset from FPA readings that are all equal (exit 0, temperature terms not fitted)",
     before_work=False)
