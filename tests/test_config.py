"""Configuration validation: every bad field is named with its value and range, before work."""

from __future__ import annotations

import pytest

from irnuc import model
from irnuc.common.errors import UserError
from irnuc.model.config import SCHEMA, apply_overrides, load_toml, validate


@pytest.mark.parametrize("name", ["default", "paper"])
def test_presets_validate(name):
    cfg = model.load_preset(name)
    assert set(cfg) == {k.split(".")[0] for k in SCHEMA}


@pytest.mark.parametrize(
    ("override", "fragment"),
    [
        ({"bolometer.t_int": 0.0}, "bolometer.t_int = 0 s is outside the allowed range (0, 10]"),
        ({"bolometer.t_int": -1e-3}, "bolometer.t_int"),
        ({"bolometer.g": 0.0}, "bolometer.g = 0 W/K"),
        ({"bolometer.C": -1.0}, "bolometer.C"),
        ({"bolometer.R_ref": float("nan")}, "bolometer.R_ref"),
        ({"bolometer.rtol": -1e-12}, "bolometer.rtol = -1e-12"),
        ({"radiometry.rtol": 0.0}, "radiometry.rtol"),
        ({"fpa.tolerance": {"R_ref": -0.1}}, "fpa.tolerance.R_ref = -0.1"),
        ({"fpa.tolerance": {"g": 1.5}}, "fpa.tolerance.g = 1.5"),
        ({"fpa.tolerance": {"Z": 0.1}}, "fpa.tolerance.Z is not a known field"),
        ({"fpa.blind": [1, 1, 1]}, "fpa.blind"),
        ({"fpa.blind": [5000, 1, 1, 1]}, "fpa.blind[0] = 5000"),
        ({"fpa.boundary": [0, -1, 0, 0]}, "fpa.boundary[1] = -1"),
        ({"fpa.active_rows": 0}, "fpa.active_rows = 0"),
        ({"fpa.active_cols": 2.5}, "fpa.active_cols"),
        ({"fpa.fill_factor": 1.2}, "fpa.fill_factor"),
        ({"environment.T_cam": 30.0}, "environment.T_cam = 30 K is outside the allowed range [100, 500]"),
        ({"environment.T_substrate": 0.0}, "environment.T_substrate"),
        ({"optics.f_number": 0.2}, "optics.f_number"),
        ({"optics.fov": None, "optics.focal_length": None}, "optics"),
        ({"readout.skimming": "diagonal"}, "readout.skimming"),
        ({"readout.v_reset": 5.0}, "readout.v_reset"),
        ({"adc.bits": 0}, "adc.bits = 0"),
        ({"adc.v_low": 4.0}, "adc.v_low"),
        ({"noise.enabled": "yes"}, "noise.enabled"),
        ({"bolometer.typo": 1.0}, "bolometer.typo is not a known field"),
        ({"bolometer.tcrr": 1e-3}, "bolometer.tcrr is not a known field; did you mean 'tcr'?"),
        ({"fpa.defects": {"rates": {"dead": 2.0}}}, "fpa.defects.rates.dead"),
        ({"fpa.defects": {"rows": [500]}}, "fpa.defects.rows[0] = 500"),
        ({"fpa.defects": {"listed": [{"row": 3, "col": 640, "kind": "dead"}]}},
         "fpa.defects.listed[0].col = 640"),
        ({"fpa.blind": [0, 0, 0, 0]}, "readout.skimming = 'row' needs blind columns"),
        ({"radiometry.band": [14e-6, 8e-6]}, "radiometry.band"),
    ],
)
def test_bad_field_is_named(override, fragment):
    with pytest.raises(model.ConfigError) as info:
        model.load_preset("default", override)
    assert fragment in str(info.value)


def test_bad_field_fails_before_any_work(monkeypatch):
    import irnuc.model.pipeline as p
    monkeypatch.setattr(p, "build_stages", lambda cfg: pytest.fail("work started"))
    with pytest.raises(model.ConfigError):
        model.load_preset("default", {"bolometer.t_int": 0.0})


def test_unknown_section_and_preset():
    with pytest.raises(model.ConfigError, match="lens is not a known field"):
        validate({**model.load_preset("default"), "lens": {}})
    with pytest.raises(model.ConfigError, match="did you mean 'optics'"):
        validate({**model.load_preset("default"), "opticz": {}})
    with pytest.raises(model.ConfigError, match="preset = 'nope'"):
        model.load_preset("nope")


def test_simulate_checks_its_arguments(small_cfg):
    cfg = small_cfg()
    for temps, fragment in ([[0.0], "temps = 0 K"], [[float("nan")], "temps"], [[], "temps"],
                            [[-3.0, 300.0], "temps = -3 K"]):
        with pytest.raises(model.ConfigError, match=fragment):
            model.simulate(cfg, temps)
    with pytest.raises(model.ConfigError, match="seed"):
        model.simulate(cfg, [300.0], seed=-1)
    with pytest.raises(model.ConfigError, match="outputs"):
        model.simulate(cfg, [300.0], outputs=["everything"])
    with pytest.raises(model.ConfigError, match="repeats"):
        model.simulate(cfg, [300.0], repeats=0)


def test_config_file_with_base(tmp_path):
    path = tmp_path / "mine.toml"
    path.write_text('base = "default"\n[fpa]\nactive_rows = 20\nactive_cols = 30\n')
    cfg = model.load_config(path)
    assert cfg["fpa"]["active_rows"] == 20 and cfg["bolometer"]["R_ref"] == 1e5
    assert load_toml(path)["fpa"]["pitch"] == 17e-6
    assert apply_overrides(cfg, {"fpa.pitch": 12e-6})["fpa"]["pitch"] == 12e-6
    with pytest.raises(UserError, match=r"missing\.toml: no such file"):
        model.load_config(tmp_path / "missing.toml")
    (tmp_path / "bad.toml").write_text("[fpa\n")
    with pytest.raises(UserError, match=r"bad\.toml: not valid TOML"):
        model.load_config(tmp_path / "bad.toml")


def test_pipeline_to_toml_round_trips_any_description(tmp_path) -> None:
    """A configuration written with to_toml reads back equal, quotes and backslashes too."""
    from irnuc.nuc_fixed.config import load_pipeline

    cfg = load_pipeline("minimal").replace(name="mine", out_bits=5,
                                           description='it\'s "quoted" \\ and \u00b5m')
    path = tmp_path / "mine.toml"
    path.write_text(cfg.to_toml())
    assert load_pipeline(path) == cfg
    assert load_pipeline(f"{path}:mine") == cfg
