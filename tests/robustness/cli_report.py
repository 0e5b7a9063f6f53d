"""The robustness cases of ``irnuc report``."""

from __future__ import annotations

from robustness.harness import case, command, out_is_file, user_folder, write_file

P = command("report", (("irnuc.reports.report.run", "build_report"),))
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
case("report-config-dev-zero", P, "--config /dev/zero", ("--config", "/dev/zero", "larger than"),
     "an endless file as the configuration")
case("report-config-dev-null", P, "--config /dev/null", ("--config", "no phase to run"),
     "an empty file as the configuration (ran no phase and said PASS)")
case("report-config-only-name", P, "--config {w}/rep_only_name.toml", ("--config", "no phase to run"),
     "a configuration holding only its name (ran no phase and said PASS)")
case("report-config-cosim-only-skipped", P, "--config {w}/rep_cosim_only.toml --no-cosim",
     ("--config", "no phase to run", "--no-cosim"), "only [cosim], and --no-cosim")
case("report-config-sensor-pipeline", P, "--config {w}/rep_sensor_pipeline.toml --no-cosim",
     ("--config", "sensor.pipeline", "typicl14", "did you mean 'typical14'"),
     "a misspelled sensor.pipeline (found after progress lines, unnamed)")
case("report-config-sensor-preset", P, "--config {w}/rep_sensor_preset.toml --no-cosim",
     ("--config", "sensor.preset", "defualt", "did you mean 'default'"),
     "a misspelled sensor.preset (found after progress lines, unnamed)")
case("report-config-sensor-override", P, "--config {w}/rep_sensor_override.toml --no-cosim",
     ("--config", "sensor.overrides", "noise.enabeld", "did you mean"),
     "a misspelled field in sensor.overrides (found after progress lines)")
case("report-config-sensor-override-value", P,
     "--config {w}/rep_sensor_override_value.toml --no-cosim",
     ("--config", "sensor.overrides", "noise.enabled"), "an override of the wrong type")
case("report-config-sensor-override-rows", P, "--config {w}/rep_sensor_rows.toml --no-cosim",
     ("--config", "sensor.overrides['fpa.active_rows'] = 99", "sensor.rows = 48"),
     "fpa.active_rows overridden beside rows (ran 99 rows, recorded 48, passed)")
case("report-config-precision-component", P, "--config {w}/rep_precision.toml --no-cosim",
     ("--config", "precision.components", "radiance_x"),
     "a misspelled precision component (found after progress lines, unnamed)")
case("report-baseline-missing", P, f"{NC} --baseline {{t}}/none.json", ("--baseline", "none.json"),
     "a missing baseline")
case("report-baseline-folder", P, f"{NC} --baseline {{w}}", ("--baseline",), "a folder as baseline")
case("report-baseline-not-json", P, f"{NC} --baseline {{w}}/base_notjson.json", ("--baseline",),
     "a baseline that is not JSON")
case("report-baseline-empty", P, f"{NC} --baseline {{w}}/empty.npz", ("--baseline",), "an empty baseline")
case("report-baseline-binary", P, f"{NC} --baseline {{w}}/binary.toml", ("--baseline",),
     "binary garbage as baseline")
case("report-baseline-list", P, f"{NC} --baseline {{w}}/base_list.json", ("--baseline", "JSON object"),
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
case("report-baseline-dev-zero", P, f"{NC} --baseline /dev/zero", ("--baseline", "/dev/zero", "larger than"),
     "an endless file as baseline (grew to 13 GB in 44 s)", check_out=True)
case("report-baseline-provenance-text", P, f"{NC} --baseline {{w}}/base_provenance_text.json",
     ("--baseline", "provenance", "a table"),
     "\"provenance\": \"x\" (AttributeError after the whole report)")
case("report-baseline-no-provenance", P, f"{NC} --baseline {{w}}/base_no_provenance.json",
     ("--baseline", "provenance", "missing"), "no provenance (which run it is)")
case("report-baseline-deep", P, f"{NC} --baseline {{w}}/base_deep.json",
     ("--baseline", "nested too deeply"), "10^5 nested lists (RecursionError)")
case("report-baseline-digits", P, f"{NC} --baseline {{w}}/base_digits_5001.json",
     ("--baseline", "not a readable JSON"), "a 5001-digit integer (ValueError)")
case("report-baseline-value-huge", P, f"{NC} --baseline {{w}}/base_value_huge.json",
     ("--baseline", "calibration.bad_pixels.value", "allowed range"),
     "a 4001-digit integer value (would overflow the comparison)")
case("report-baseline-empty-metrics", P, f"{NC} --baseline {{w}}/base_empty_metrics.json",
     ("--baseline", "metrics is empty"), "no metric to compare (compared 0, said pass)")
case("report-baseline-schema-99", P, f"{NC} --baseline {{w}}/base_schema_99.json",
     ("--baseline", "schema_version = 99", "must be 2"), "a summary of a newer schema")
case("report-baseline-schema-1", P, f"{NC} --baseline {{w}}/base_schema_1.json",
     ("--baseline", "schema_version = 1"), "a summary of an older schema")
case("report-baseline-schema-text", P, f"{NC} --baseline {{w}}/base_schema_text.json",
     ("--baseline", "schema_version = '2'"), "schema_version as a string")
case("report-baseline-tool", P, f"{NC} --baseline {{w}}/base_tool_calibrate.json",
     ("--baseline", "tool = 'irnuc calibrate'", "'irnuc report'"), "another tool's summary")
case("report-baseline-other-config", P, f"{NC} --baseline {{w}}/base_other_config.json",
     ("--baseline", "configuration 'default'", "'small'"),
     "a baseline of another configuration (compared 0 metrics, said pass)")
case("report-baseline-edited-config", P, f"{NC} --baseline {{w}}/base_edited_config.json",
     ("--baseline", "hash 0000000000000000"), "a baseline of the same name, another content")
case("report-junit-missing", P, "--config small --junit {t}/none.xml", ("--junit", "none.xml"),
     "a missing JUnit file")
case("report-junit-folder", P, "--config small --junit {w}", ("--junit",), "a folder as --junit")
case("report-junit-malformed", P, "--config small --junit {w}/junit_bad.xml", ("--junit", "junit_bad.xml"),
     "a JUnit file that is not XML (read after the other phases)")
case("report-junit-root", P, "--config small --junit {w}/junit_root.xml", ("--junit", "junit_root.xml"),
     "XML that is not JUnit")
case("report-junit-dev-zero", P, "--config small --junit /dev/zero", ("--junit", "/dev/zero", "larger than"),
     "an endless file as JUnit results")
case("report-junit-empty-suite", P, "--config small --junit {t}/j.xml", ("--junit", "no <testcase>"),
     "a JUnit file without a test (reported 0 tests and passed)",
     setup=write_file("j.xml", '<testsuite name="s" tests="0"></testsuite>'))
case("report-scheduler-refused", P, f"{NC} --scheduler tcp://127.0.0.1:1", ("--scheduler",),
     "an unreachable Dask scheduler (noticed in the sweep phase)")
case("report-config-cosim-test-typo", P, "--config {w}/rep_cosim_typo.toml",
     ("--config", "cosim.tests", "corner_codes"), "a misspelled co-simulation test")
case("report-config-sweep-adc", P, "--config {w}/rep_sweep_adc.toml --no-cosim",
     ("--config", "sweep.pipeline", "adc_bits"), "a sweep whose sensor ADC is not the pipeline's")
case("report-config-cosim-recommended-no-sweep", P, "--config {w}/rep_rec_nosweep.toml",
     ("--config", "recommended", "[sweep]"), "co-simulating a recommendation without a sweep")
case("report-out-file", P, f"{NC} --out {{t}}/out", ("out",), "--out is a file", setup=out_is_file)
case("report-out-user-folder", P, f"{NC} --out {{t}}/out", ("--out",),
     "--out is a user's folder (written into)", setup=user_folder)
