"""The staged pipeline: only the needed stages run, determinism, skimming, presets."""

from __future__ import annotations

import numpy as np
import pytest

from irnuc import model
from irnuc.model.core.bolometer import STATUS_OK, STATUS_RUNAWAY
from irnuc.model.defects import DefectKind


def test_uniform_scene_evaluates_radiance_once_per_temperature(small_cfg):
    fr = model.simulate(small_cfg(), [300.0, 350.0, 400.0], seed=1)
    c = fr.counts
    # 3 scene temperatures + housing + substrate, never one per pixel
    assert c["radiance_points"] == 5
    for static in ("params", "defects", "cos4", "env_radiance", "coupling"):
        assert c[static] == 1
    assert c["bolometer"] == 1 and c["adc"] == 1


def test_static_stages_run_once_across_chunks(small_cfg):
    cfg = small_cfg(**{"run.chunk_frames": 2})
    fr = model.simulate(cfg, [300.0, 310.0, 320.0, 330.0, 340.0], seed=1)
    assert fr.counts["params"] == 1 and fr.counts["cos4"] == 1
    assert fr.counts["bolometer"] == 3 and fr.counts["scene_radiance"] == 3


def test_per_pixel_scenes_evaluate_each_distinct_temperature_once(small_cfg):
    cfg = small_cfg()
    disk = model.simulate(cfg, [300.0, 310.0], "disk", scene_params={"disk_temperature": 360.0})
    assert disk.counts["radiance_points"] == 2 + 3  # {300, 310, 360} + housing + substrate
    grad = model.simulate(cfg, [300.0], "gradient", scene_params={"span": 30.0})
    assert grad.counts["radiance_points"] == 2 + 16  # one per column


def test_no_noise_configured_means_no_random_draws(small_cfg, monkeypatch):
    created = []
    real = np.random.SeedSequence

    def counting(*args, **kwargs):
        created.append(args)
        return real(*args, **kwargs)

    monkeypatch.setattr(np.random, "SeedSequence", counting)
    cfg = small_cfg(**{"fpa.tolerance": {"R_ref": 0.0, "g": 0.0, "C": 0.0}})
    fr = model.simulate(cfg, [300.0, 400.0], seed=5)
    assert created == []
    assert "noise" not in fr.counts and fr.counts["no_noise"] == 1
    other = model.simulate(cfg, [300.0, 400.0], seed=6)
    np.testing.assert_array_equal(fr.codes, other.codes)


def test_noise_configured_draws_once_per_frame(small_cfg):
    fr = model.simulate(small_cfg(**{"noise.enabled": True}), [300.0, 300.0, 300.0], seed=5)
    assert fr.counts["noise"] == 1 and fr.counts["noise_frames"] == 3
    assert not np.array_equal(fr.codes[0], fr.codes[1])


@pytest.mark.parametrize("mode", ["none", "row", "column"])
def test_only_the_requested_skimming_mode_runs(small_cfg, mode):
    fr = model.simulate(small_cfg(**{"readout.skimming": mode}), [300.0])
    ran = {k for k in fr.counts if k.startswith("skimming_")}
    assert ran == {f"skimming_{mode}"}


def test_requesting_radiance_skips_the_readout(small_cfg):
    fr = model.simulate(small_cfg(), [300.0, 400.0], outputs=["scene_radiance"])
    assert "bolometer" not in fr.counts and "adc" not in fr.counts and "params" not in fr.counts
    np.testing.assert_allclose(fr.outputs["scene_radiance"], model.band_radiance([300.0, 400.0]))


def test_same_seed_same_bits_and_chunking_does_not_matter(small_cfg):
    over = {"noise.enabled": True, "noise.flicker_sigma": 1e-3,
            "fpa.defects": {"rates": {"dead": 0.02, "noisy": 0.02}, "clusters": 1}}
    a = model.simulate(small_cfg(**over), np.linspace(300, 400, 5), seed=11)
    b = model.simulate(small_cfg(**over, **{"run.chunk_frames": 2}), np.linspace(300, 400, 5),
                       seed=11)
    np.testing.assert_array_equal(a.codes, b.codes)
    np.testing.assert_array_equal(a.defect_kind, b.defect_kind)
    c = model.simulate(small_cfg(**over), np.linspace(300, 400, 5), seed=12)
    assert not np.array_equal(a.codes, c.codes)


def _stripe_strength(codes):
    f = codes.astype(float)
    return f.mean(axis=1).std(), f.mean(axis=0).std()  # (row-to-row, column-to-column)


def test_row_skimming_gives_row_stripes_and_column_skimming_column_stripes():
    over = {"fpa.active_rows": 64, "fpa.active_cols": 64, "fpa.defects": {},
            "fpa.blind": [1, 1, 1, 1], "fpa.tolerance": {"R_ref": 1e-3, "g": 0.0, "C": 0.0}}
    rows = model.simulate(model.load_preset("default", {**over, "readout.skimming": "row"}),
                          [300.0], seed=2).codes[0]
    cols = model.simulate(model.load_preset("default", {**over, "readout.skimming": "column"}),
                          [300.0], seed=2).codes[0]
    r_rows, r_cols = _stripe_strength(rows)
    c_rows, c_cols = _stripe_strength(cols)
    assert r_rows > 3 * r_cols
    assert c_cols > 3 * c_rows


@pytest.mark.parametrize("T", [250.0, 300.0, 400.0])
def test_default_preset_frames_stay_off_the_rails(T):
    cfg = model.load_preset("default")
    fr = model.simulate(cfg, [T], seed=0)
    good = fr.defect_kind == DefectKind.GOOD
    codes = fr.codes[0][good]
    assert codes.min() > 0 and codes.max() < 2**cfg["adc"]["bits"] - 1
    assert fr.codes.shape == (1, 480, 640) and fr.codes.dtype == np.uint16


def test_hotter_scene_gives_higher_codes(small_cfg):
    fr = model.simulate(small_cfg(), [280.0, 300.0, 320.0, 340.0])
    means = fr.codes.reshape(4, -1).mean(axis=1)
    assert np.all(np.diff(means) > 0)


def test_paper_preset_self_heating_is_reported():
    cfg = model.load_preset("paper", {"fpa.active_rows": 8, "fpa.active_cols": 8})
    fr = model.simulate(cfg, [300.0])
    assert fr.diagnostics["temperature_rise_K"]["mean"] > 100.0


def test_paper_variant_responds_less_to_the_scene(small_cfg):
    # Eq. 19 as printed switches the scene power on with the bias: the scene term is scaled by
    # the self-heating factor f(t/tau) << 1, while the equilibrium variant sees it fully.
    def response(variant):
        fr = model.simulate(small_cfg(**{"bolometer.variant": variant}), [300.0, 400.0],
                            outputs=["temperature_rise"])
        d = fr.outputs["temperature_rise"]
        return (d[1] - d[0])[6, 8]

    ratio = response("paper") / response("equilibrium")
    f = model.core.bolometer.self_heating_factor(6e-5 / 1e-2)
    assert ratio == pytest.approx(f, rel=0.05)


def test_runaway_pixels_are_reported_not_nan(small_cfg):
    cfg = small_cfg(**{"bolometer.tcr": 0.02, "bolometer.bias_current": 5e-4,
                       "bolometer.runaway_temperature": 600.0})
    with pytest.warns(RuntimeWarning, match="runaway"):
        fr = model.simulate(cfg, [300.0], outputs=["codes", "status"])
    assert fr.diagnostics["solver_failures"]["runaway"] > 0
    assert (fr.outputs["status"] == STATUS_RUNAWAY).any()
    assert fr.codes.dtype == np.uint16  # finite codes, the runaway pixels at the high rail


def test_solver_status_ok_on_presets():
    for name in ("default", "paper"):
        cfg = model.load_preset(name, {"fpa.active_rows": 8, "fpa.active_cols": 8})
        fr = model.simulate(cfg, [300.0, 400.0], outputs=["codes", "status"])
        assert (fr.outputs["status"] == STATUS_OK).all()


def test_a_sensor_keeps_its_static_products_and_matches_one_shot_runs(small_cfg):
    cfg = small_cfg(**{"fpa.defects": {"rates": {"hot": 0.05}}})
    sensor = model.Pipeline(cfg, seed=3)
    first = sensor.simulate([300.0])
    second = sensor.simulate([350.0])
    assert first.counts["params"] == 1 and "params" not in second.counts
    assert second.counts["bolometer"] == 1
    np.testing.assert_array_equal(second.codes, model.simulate(cfg, [350.0], seed=3).codes)
    np.testing.assert_array_equal(first.defect_kind, second.defect_kind)


def test_noise_enabled_with_every_sigma_zero_runs_no_noise_stage(small_cfg):
    quiet = {"noise.enabled": True, "noise.johnson": False, "noise.readout_sigma": 0.0,
             "noise.flicker_sigma": 0.0, "noise.flicker_coefficient": 0.0,
             "noise.thermal_fluctuation": False, "fpa.defects": {}}
    fr = model.simulate(small_cfg(**quiet), [300.0, 350.0], seed=2)
    off = model.simulate(small_cfg(**{**quiet, "noise.enabled": False}), [300.0, 350.0], seed=2)
    assert "noise" not in fr.counts and fr.counts["no_noise"] == 1
    assert fr.counts["no_bolometer_noise"] == 1
    assert not {"noise_frames", "bolometer_noise_frames", "thermal_noise_frames"} & set(fr.counts)
    np.testing.assert_array_equal(fr.codes, off.codes)


@pytest.mark.parametrize("mode", ["row", "column"])
def test_row_and_column_skimming_solve_no_reference_pixel(small_cfg, mode):
    # The nominal skim voltage (one steady solve) is only the fallback of a blind line
    # whose pixels all failed: with every blind pixel solved it is never computed.
    fr = model.simulate(small_cfg(**{"readout.skimming": mode}), [300.0], seed=1)
    assert f"skimming_{mode}" in fr.counts and "v_skim" not in fr.counts
    none = model.simulate(small_cfg(**{"readout.skimming": "none"}), [300.0], seed=1)
    assert none.counts["v_skim"] == 1


def test_skimming_fallback_is_computed_only_when_a_blind_line_failed():
    from irnuc.model.fpa import ArrayLayout
    from irnuc.model.readout import skim_row

    lay = ArrayLayout(3, 4, (0, 0, 0, 0), (0, 0, 2, 2))
    v = np.ones((1, 3, 8))
    status = np.zeros((1, 3, 8), np.uint8)
    calls = []

    def fallback():
        calls.append(1)
        return 7.0

    assert skim_row(v, status, lay, fallback)[0, :, 0].tolist() == [1.0, 1.0, 1.0]
    assert calls == []
    status[0, 1, lay.blind_col_indices] = STATUS_RUNAWAY
    assert skim_row(v, status, lay, fallback)[0, :, 0].tolist() == [1.0, 7.0, 1.0]
    assert calls == [1]
