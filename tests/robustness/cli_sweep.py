"""The robustness cases of ``irnuc sweep``."""

from __future__ import annotations

from robustness.harness import case, command, other_kind, out_is_file, ro_parent, user_folder

S = command("sweep", (("irnuc.reports.studies.sweep", "prepare"),))
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
case("sweep-out-file", S, "--out {t}/out", ("--out", "not a folder"), "--out is a file", setup=out_is_file)
case("sweep-out-user-folder", S, "--out {t}/out", ("--out", "other content"), "--out is a user's folder",
     setup=user_folder)
case("sweep-out-other-command", S, "--out {t}/out", ("--out", "irnuc correct"),
     "--out holds another command's output", setup=other_kind("correct"))
case("sweep-out-read-only-parent", S, "--out {t}/ro/out", ("--out", "no permission"),
     "--out inside a read-only folder", setup=ro_parent)
