"""The coarse pass in the viewer: each frame's march starts from the tile starts of render()'s
coarse pass, and the window's image is the one it shows without the pass (real window on Xvfb)."""
import numpy as np
import pytest
from PIL import Image

from sdfgl import xdisplay

from .xserver import Driver, start_xvfb

pytestmark = pytest.mark.window

SCENE = """import sdfgl as sg
scene = (sg.sphere(0.6).translate((-0.8, 0.6, 0)) | sg.box(0.9).translate((0.9, 0.45, 0.2))).color(0.9, 0.3, 0.2)
camera = sg.OrbitCamera(target=(0, 0.4, 0), distance=5, yaw=30, pitch=12)
settings = {'shadows': 'hard', 'ao': False, 'ground': True%s}
"""


@pytest.fixture(scope="module")
def display():
    proc, name = start_xvfb()
    yield name
    xdisplay.stop_xvfb(proc)


def shoot(display, tmp_path, text: str) -> tuple[dict, np.ndarray]:
    """The viewer's state and its screenshot of the refined image of the scene file ``text``."""
    tmp_path.mkdir(parents=True, exist_ok=True)
    scene = tmp_path / "scene.py"
    scene.write_text(text)
    drv = Driver(display, tmp_path / "state.json")
    proc = drv.launch(str(scene), "--size", "320x240", "--screenshot-dir", str(tmp_path / "shots"),
                      "--max-samples", "4")
    try:
        drv.wait_for(lambda s: s["frames"] > 0 and s["error"] == "", timeout=90.0, what="the first frame")
        drv.wait_for(lambda s: s["samples"] >= 4 and not s["moving"], timeout=90.0, what="refinement")
        drv.key("p")
        st = drv.wait_for(lambda s: len(s["screenshots"]) == 1, what="a screenshot")
    finally:
        if proc.poll() is None:
            proc.kill()
        proc.wait(10)
    return st, np.asarray(Image.open(st["screenshots"][0]).convert("RGB"), dtype=np.int16)


@pytest.mark.slow
def test_the_viewer_draws_the_coarse_pass_and_its_image_matches_the_one_without(display, tmp_path):
    import sdfgl as sg
    on_state, on = shoot(display, tmp_path / "on", SCENE % "")
    off_state, off = shoot(display, tmp_path / "off", SCENE % ", 'coarse': False")
    # the window's program on screen has its coarse pass (8-pixel tiles by default), or none when off
    assert on_state["coarse"] == 8
    assert off_state["coarse"] == 0
    # its tiles' rays start nearer their hits: fewer map() calls a pixel (the panel's readout)
    assert on_state["mean_steps"] < off_state["mean_steps"], (on_state["mean_steps"], off_state["mean_steps"])
    # the pass only moves where the march starts: the image is the same, jittered samples included
    diff = np.abs(on - off).max(-1)
    assert diff.mean() < 0.5, diff.mean()
    assert (diff > 24).mean() < 0.002, (diff > 24).mean()
    # and it is render()'s image (which has the pass) of the same view
    ns: dict = {}
    exec(SCENE % "", ns)  # noqa: S102 - the test's own scene text
    cam = sg.OrbitCamera(target=tuple(on_state["target"]), distance=on_state["distance"], yaw=on_state["yaw"],
                         pitch=on_state["pitch"])
    want = sg.render(ns["scene"], cam, (320, 240), aa=2, **ns["settings"]).color.astype(np.int16)
    assert np.abs(on - want).mean() < 4.0
    print(f"coarse on/off: mean steps {on_state['mean_steps']:.1f} / {off_state['mean_steps']:.1f}, "
          f"image difference mean {diff.mean():.3f}, max {diff.max()}; vs render() {np.abs(on - want).mean():.2f}")
