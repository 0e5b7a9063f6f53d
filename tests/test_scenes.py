"""Scenes: temperatures per pixel for each kind."""

from __future__ import annotations

import numpy as np
import pytest

from irnuc.model import ConfigError, Scene
from irnuc.model.scenes import scene_temperatures


def test_uniform_is_one_value_per_frame():
    t = scene_temperatures(Scene(), np.array([300.0, 310.0]), (4, 5))
    assert t.shape == (2,) and t.tolist() == [300.0, 310.0]


def test_gradient_spans_columns_and_rows():
    t = scene_temperatures(Scene("gradient", {"span": 40.0}), np.array([300.0]), (3, 5))
    np.testing.assert_allclose(t[0, 0], [300, 310, 320, 330, 340])
    assert (t[0] == t[0, :1]).all() or np.allclose(t[0], t[0, 0])
    t = scene_temperatures(Scene("gradient", {"span": 20.0, "axis": 0}), np.array([300.0]), (3, 2))
    np.testing.assert_allclose(t[0, :, 0], [300, 310, 320])


def test_disk_on_background():
    t = scene_temperatures(Scene("disk", {"disk_temperature": 400.0, "radius": 0.2}),
                           np.array([300.0]), (21, 21))
    assert t[0, 10, 10] == 400.0 and t[0, 0, 0] == 300.0
    assert set(np.unique(t)) == {300.0, 400.0}
    assert (t[0] == t[0, ::-1]).all()


def test_map_array_shifted_to_each_temperature(tmp_path):
    base = np.arange(12, dtype=float).reshape(3, 4) + 290.0
    t = scene_temperatures(Scene("map", {"map": base}), np.array([300.0, 350.0]), (3, 4))
    assert t.shape == (2, 3, 4)
    np.testing.assert_allclose(t.mean(axis=(1, 2)), [300.0, 350.0])
    np.save(tmp_path / "m.npy", base)
    t2 = scene_temperatures(Scene("map", {"path": str(tmp_path / "m.npy")}), np.empty(0), (3, 4))
    np.testing.assert_array_equal(t2[0], base)


def test_map_from_image_file(tmp_path):
    import matplotlib.image as mpimg

    img = np.tile(np.linspace(0, 1, 8), (4, 1))
    mpimg.imsave(tmp_path / "s.png", img, cmap="gray")
    t = scene_temperatures(Scene("map", {"path": str(tmp_path / "s.png"), "t_min": 280.0,
                                         "t_max": 380.0}), np.empty(0), (4, 8))
    assert t.min() == pytest.approx(280.0) and t.max() == pytest.approx(380.0)
    assert np.all(np.diff(t[0, 0]) > 0)


@pytest.mark.parametrize(
    ("scene", "fragment"),
    [
        (lambda: Scene("fog"), "scene = 'fog'"),
        (lambda: Scene("disk", {"colour": 1}), "unknown parameter"),
        (lambda: scene_temperatures(Scene("map", {"map": np.ones((2, 2)) * 300}),
                                    np.array([300.0]), (3, 3)), "shape"),
        (lambda: scene_temperatures(Scene("gradient", {"span": -400.0}), np.array([300.0]),
                                    (2, 2)), "<= 0 K"),
        (lambda: scene_temperatures(Scene("disk", {"disk_temperature": 0.0}),
                                    np.array([300.0]), (2, 2)), "scene.disk_temperature"),
    ],
)
def test_bad_scene(scene, fragment):
    with pytest.raises(ConfigError, match=fragment.replace("(", r"\(")):
        scene()
