"""Every live parameter of the gallery scenes (and of examples/live_params.py) has a working control in
the viewer's panel: its control's whole range is accepted by the nodes that use it and moves the
image without a new program (headless, the panel's own control logic); the window lists them all."""
from pathlib import Path

import numpy as np
import pytest

from sdfgl.render import Renderer
from sdfgl.scenefile import load_scene_file
from sdfgl.viewer.panel import colour_params, control

from .test_viewer import display  # noqa: F401 - the Xvfb fixture
from .xserver import Driver

ROOT = Path(__file__).resolve().parents[1]
SCENES = sorted((ROOT / "examples" / "gallery").glob("*.py")) + [ROOT / "examples" / "live_params.py"]


def scene_params(path: Path):
    sf = load_scene_file(path)
    from sdfgl.compiler.generate import generate
    from sdfgl.settings import Settings
    return sf, list(generate(sf.scene, Settings.build(**sf.settings)).params)


def test_the_gallery_has_live_parameters():
    with_params = [p.name for p in SCENES if scene_params(p)[1]]
    assert len(with_params) >= 3, with_params  # blends, domain, live_params at least


@pytest.mark.parametrize("path", [p for p in SCENES if scene_params(p)[1]], ids=lambda p: p.stem)
def test_every_param_control_works(path):
    sf, params = scene_params(path)
    colours = colour_params(sf.scene)
    r = Renderer()
    size = (96, 64)
    settings = {**sf.settings, "shadows": False, "ao": False}

    def image():
        res = r.render(sf.scene, sf.camera, size, **settings)
        assert np.isfinite(res.color).all()
        return res.color.astype(np.int16), res.source.text

    base, text = image()
    for p in params:
        kind, lo, hi = control(p, colours)
        assert kind == ("slider" if np.ndim(p.value) == 0 else "colour" if id(p) in colours else "vector")
        start = p.value
        ends = [(0.1, 0.9, 0.3)] if kind == "colour" else [lo, hi]
        if kind == "vector":
            ends = [np.full(3, lo), np.full(3, hi)]
        assert lo <= np.min(start) and np.max(start) <= hi, (p.name, start, lo, hi)
        try:
            for v in ends:
                p.value = v  # the control's ends: the nodes using it accept them
                img, t = image()
                assert t == text, f"{p.name}: a new program"  # a uniform, not a recompile
                assert np.abs(img - base).max() > 20, f"{p.name}={v} does not change the image"
        finally:
            p.value = start


@pytest.mark.window
def test_the_window_shows_a_control_for_each_param(display, tmp_path):
    path = ROOT / "examples" / "gallery" / "domain.py"
    state = tmp_path / "state.json"
    drv = Driver(display, state)
    proc = drv.launch(str(path), "--size", "820x400", "--max-samples", "1")
    try:
        st = drv.wait_for(lambda s: s["samples"] >= 1 and not s["compiling"] and s["panel"].get("controls"),
                          timeout=120, what="the panel")
        assert st["panel"]["controls"] == {"shell thickness": "slider", "rounding": "slider",
                                           "ring colour": "colour"}
        assert all(name in st["panel"]["rects"] for name in st["panel"]["controls"])
    finally:
        if proc.poll() is None:
            proc.kill()
        proc.wait(10)
