"""Values float32 and the GL limits cannot hold are refused at the setting or operation that gives them."""
from __future__ import annotations

import importlib
import math

import numpy as np
import pytest

import sdfgl as sg

ev = importlib.import_module("sdfgl.evaluate")  # the module: the package exports the function by that name
INF, NAN = float("inf"), float("nan")


@pytest.mark.parametrize("name, value, words", [
    ("max_dist", 1e39, "at most"),
    ("max_dist", INF, "finite"),
    ("ref_step", INF, "finite"),
    ("ref_step", 1e-45, "at least"),
    ("newton_cap", INF, "finite"),
    ("newton_cap", 1e300, "at most"),
    ("hit_scale", NAN, "finite"),
    ("hit_scale", 1e-40, "at least"),
    ("max_dist", -1.0, "> 0"),
])
def test_settings_beyond_float32_are_refused_by_name(name, value, words):
    settings = {name: value, **({"method": "reference"} if name == "ref_step" else {}),
                **({"method": "newton"} if name == "newton_cap" else {})}
    with pytest.raises(sg.ParameterError, match=f"setting '{name}'.*{words}"):
        sg.render(sg.sphere(1), size=(8, 8), **settings)


def test_largest_allowed_settings_compile_and_render(renderer):
    res = renderer.render(sg.sphere(1) | sg.plane(), size=(16, 12), max_dist=1e29, hit_scale=1e-30,
                          outputs=("color", "depth"))
    assert not np.isnan(res.depth).any()
    renderer.render(sg.sphere(1), size=(8, 8), method="newton", newton_cap=1e29)


@pytest.mark.parametrize("op, args, arg", [
    ("zoom", (INF,), "factor"), ("zoom", (NAN,), "factor"), ("zoom", (0.0,), "factor"),
    ("orbit", (NAN, 0.0), "dyaw"), ("orbit", (0.0, INF), "dpitch"),
    ("pan", (INF, 0.0), "dx"), ("pan", (0.0, NAN), "dy"), ("pan", (1e40, 0.0), "target"),
])
def test_camera_operations_refuse_nan_and_inf(op, args, arg):
    cam = sg.OrbitCamera(distance=5, yaw=30, pitch=20)
    before = (cam.distance, cam.yaw, cam.pitch, cam.eye.copy(), cam.target.copy())
    with pytest.raises(sg.ParameterError, match=f"OrbitCamera.{op}.*'{arg}'"):
        getattr(cam, op)(*args)
    assert (cam.distance, cam.yaw, cam.pitch) == before[:3]
    assert np.array_equal(cam.eye, before[3]) and np.array_equal(cam.target, before[4])


def test_repeated_zoom_out_stays_in_float32_range():
    cam = sg.OrbitCamera(distance=5)
    for _ in range(3000):
        try:
            cam.zoom(1 / 0.88)
        except sg.ParameterError as exc:
            assert "outside" in str(exc)
    assert math.isfinite(cam.distance) and cam.distance <= 1e29 and np.all(np.isfinite(cam.eye))


def test_cameras_beyond_float32_are_refused():
    with pytest.raises(sg.ParameterError, match="eye"):
        sg.Camera(eye=(1e39, 0, 0))
    with pytest.raises(sg.ParameterError, match="distance"):
        sg.OrbitCamera(distance=1e35)


def test_image_larger_than_the_gl_limits_is_refused():
    with pytest.raises(sg.ParameterError, match="size"):
        sg.render(sg.sphere(1), size=(16385, 4))


def test_evaluate_batches_large_inputs(renderer, monkeypatch):
    s = sg.sphere(1) | sg.box(0.8).translate((1, 0, 0))
    pts = np.random.default_rng(3).uniform(-2, 2, (10_007, 3))
    whole = sg.evaluate(s, pts, renderer=renderer)
    monkeypatch.setattr(ev, "BATCH_ROWS", 2)  # 2048 points a draw: 5 batches, the last one partial
    batched = sg.evaluate(s, pts, renderer=renderer)
    assert np.array_equal(whole, batched)
    assert np.abs(batched - s.distance(pts)).max() < 1e-5


@pytest.mark.slow
def test_evaluate_more_points_than_one_texture_holds(renderer):
    """17 M points (the texture side limit is 16384 rows of 1024) evaluate instead of failing."""
    n = 1024 * 16384 + 5
    pts = np.zeros((n, 3), dtype=np.float64)
    pts[:, 0] = np.linspace(-3, 3, n)
    d = sg.evaluate(sg.sphere(1), pts, renderer=renderer)
    assert d.shape == (n,) and d.dtype == np.float32
    idx = np.array([0, 1, n // 2, n - 2, n - 1])
    assert np.abs(d[idx] - sg.sphere(1).distance(pts[idx])).max() < 1e-5


def test_evaluate_refuses_points_beyond_float32():
    with pytest.raises(sg.ParameterError, match="float32"):
        sg.evaluate(sg.sphere(1), [[1e39, 0, 0]])
    with pytest.raises(sg.ParameterError, match="origin"):
        sg.evaluate(sg.sphere(1), [[0, 0, 0]], origin=(NAN, 0, 0))
