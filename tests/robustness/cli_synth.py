"""The robustness cases of ``irnuc synth``."""

from __future__ import annotations

from pathlib import Path

from robustness.harness import case, command, out_is_file, user_folder


def _pipeline_named(name: str):
    """A pipeline file holding ``minimal``'s fields under the table name ``name``."""
    def setup(w: Path, t: Path) -> None:
        from irnuc.nuc_fixed import load_pipeline

        text = load_pipeline("minimal").to_toml().replace("[minimal]", f"[{name!s}]")
        (t / "named.toml").write_text(text)
    return setup


Y = command("synth", (("irnuc.cosim.synth", "synth_configs"),))
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
     setup=out_is_file)
case("synth-out-user-folder", Y, "--pipeline minimal --out {t}/out", ("--out",),
     "--out is a user's folder (never deleted)", setup=user_folder)
case("synth-pipeline-name-up", Y, "--pipeline {t}/named.toml --pipeline minimal",
     ("--pipeline", "named.toml", "'../../x'", "plain name"),
     "a pipeline table named [\"../../x\"] (wrote x/synth.json outside --out)",
     setup=_pipeline_named('"../../x"'))
case("synth-pipeline-name-absolute", Y, "--pipeline {t}/named.toml --pipeline minimal",
     ("--pipeline", "'/tmp/x'", "plain name"),
     "a pipeline table named with an absolute path", setup=_pipeline_named('"/tmp/x"'))
case("synth-pipeline-name-hidden", Y, "--pipeline {t}/named.toml",
     ("--pipeline", "'.x'", "plain name"), "a pipeline table named as a hidden file",
     setup=_pipeline_named('".x"'))
case("synth-top-unknown", Y, "--pipeline minimal --top nuc_dpc_topp",
     ("--top", "nuc_dpc_topp", "irnuc_axis_top"), "a top module irnuc synth does not build")
def _piecewise_ffc(w: Path, t: Path) -> None:
    """A pipeline file of piecewise + ffc: a composition no stage top builds."""
    from irnuc.nuc_fixed import load_pipeline

    text = load_pipeline("piecewise14").to_toml().replace(
        'method = "piecewise"', 'method = "piecewise+ffc"\nffc_frames = 8\n'
        'ffc_output = "hold"\nformats.ffc = { int_bits = 12, frac_bits = 4, signed = true, '
        'rounding = "half_up", overflow = "saturate" }')
    (t / "pwffc.toml").write_text(text)


case("synth-top-axis-other-method", Y, "--pipeline {t}/pwffc.toml --top irnuc_axis_top",
     ("--top irnuc_axis_top", "piecewise+ffc", "no top"),
     "the AXI wrapper with a composition no stage top builds", setup=_piecewise_ffc)
case("synth-top-stage-on-methods-top", Y, "--pipeline drift14 --top method_dpc_top",
     ("--top method_dpc_top", "two_point+blind_drift", "method_drift_top"),
     "a configuration with a stage on the base methods' top, which has no stage")
