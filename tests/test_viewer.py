"""The interactive viewer in a real window on Xvfb, driven by real input events."""
import math
import time

import numpy as np
import pytest
from PIL import Image

from sdfgl import xdisplay

from .xserver import Driver, start_xvfb

pytestmark = pytest.mark.window

SCENE_A = "import sdfgl as sg\nscene = (sg.sphere(1) & sg.box(1.5)).color(0.9, 0.3, 0.2)\n" \
          "camera = sg.OrbitCamera(distance=5, yaw=30, pitch=20)\n"
SCENE_B = "import sdfgl as sg\nscene = sg.torus(1, 0.3).color(0.2, 0.6, 0.9)\n"


@pytest.fixture(scope="module")
def display():
    proc, name = start_xvfb()
    yield name
    xdisplay.stop_xvfb(proc)


@pytest.fixture()
def viewer(display, tmp_path):
    scene = tmp_path / "scene.py"
    scene.write_text(SCENE_A)
    state = tmp_path / "state.json"
    drv = Driver(display, state)
    proc = drv.launch(str(scene), "--size", "320x240", "--screenshot-dir", str(tmp_path / "shots"),
                      "--max-samples", "4")
    try:
        # the first compile (soft shadows, AO) takes a while on a loaded CPU rasteriser
        drv.wait_for(lambda s: s["frames"] > 0 and s["samples"] >= 1, timeout=60.0, what="the first frame")
        yield drv, proc, scene, tmp_path
    finally:
        if proc.poll() is None:
            proc.kill()
        proc.wait(10)


@pytest.mark.slow
def test_orbit_pan_zoom_move_the_camera(viewer):
    drv, proc, _, _ = viewer
    s0 = drv.state()
    drv.drag(1, 160, 120, 60, 20)
    s1 = drv.wait_for(lambda s: s["yaw"] != s0["yaw"], what="an orbit")
    assert s1["pitch"] != s0["pitch"]
    drv.drag(3, 160, 120, 40, 0)  # right drag pans the target
    s2 = drv.wait_for(lambda s: s["target"] != s1["target"], what="a pan")
    drv.scroll(up=True, times=3)
    # all three clicks (0.88 each), not just the first state written after one of them
    s3 = drv.wait_for(lambda s: s["distance"] < 0.75 * s2["distance"], what="a zoom")
    assert s3["distance"] > 0.6 * s2["distance"]
    # frames drawn while moving were at reduced or full resolution, then refined when still
    drv.wait_for(lambda s: not s["moving"] and s["samples"] >= 4, what="refinement after moving")
    # F frames the scene box for the window's aspect ratio, from the current direction
    drv.key("f")
    s4 = drv.wait_for(lambda s: s["target"] == [0.0, 0.0, 0.0], what="framing")
    import sdfgl as sg
    box = (sg.sphere(1) & sg.box(1.5)).bounds
    want = sg.OrbitCamera.framing(*box, yaw=s4["yaw"], pitch=s4["pitch"], fov=45, aspect=320 / 240)
    assert s4["distance"] == pytest.approx(want.distance, rel=1e-9)


def test_toggles_recompile_and_screenshots_differ_after_orbit(viewer):
    drv, proc, _, tmp = viewer
    c0 = drv.state()["compiles"]
    drv.key("s")  # soft -> off
    st = drv.wait_for(lambda s: s["settings"]["shadows"] is False, what="shadows off")
    assert st["compiles"] == c0 + 1
    drv.key("d")  # debug view: steps heat map
    drv.wait_for(lambda s: s["settings"].get("debug") == "steps", what="debug view")
    drv.key("d"), drv.key("d"), drv.key("d")  # back to the shaded image
    drv.wait_for(lambda s: s["settings"].get("debug") is None, what="debug off")
    drv.key("p")
    s1 = drv.wait_for(lambda s: len(s["screenshots"]) == 1, what="a screenshot")
    drv.drag(1, 160, 120, 80, 0)
    drv.wait_for(lambda s: s["yaw"] != s1["yaw"], what="an orbit")
    drv.key("p")
    s2 = drv.wait_for(lambda s: len(s["screenshots"]) == 2, what="a second screenshot")
    a = np.asarray(Image.open(s2["screenshots"][0]), dtype=np.int16)
    b = np.asarray(Image.open(s2["screenshots"][1]), dtype=np.int16)
    assert a.shape == b.shape == (240, 320, 3)
    assert np.abs(a - b).mean() > 1.0


def test_debug_views_report_finite_steps_per_pixel(viewer):
    """The steps view read "nan steps/pixel": its program left the steps output unwritten."""
    drv, _, _, _ = viewer
    shaded = drv.wait_for(lambda s: s["samples"] >= 4 and not s["compiling"], what="a finished image")
    assert shaded["mean_steps"] > 0
    drv.key("d")
    st = drv.wait_for(lambda s: s["settings"].get("debug") == "steps" and not s["compiling"] and s["samples"] >= 4,
                      what="the steps view, finished")
    assert math.isfinite(st["mean_steps"])
    assert st["mean_steps"] == pytest.approx(shaded["mean_steps"], rel=0.05)


@pytest.mark.slow
def test_hot_reload_and_errors_keep_last_good_scene(viewer):
    drv, proc, scene, _ = viewer
    s0 = drv.state()
    time.sleep(0.05)
    scene.write_text(SCENE_B)
    s1 = drv.wait_for(lambda s: s["reloads"] == s0["reloads"] + 1, what="a reload")
    assert "color" in s1["scene"] and s1["scene"] != s0["scene"] and s1["error"] == ""
    scene.write_text("import sdfgl as sg\nscene = sg.sphere(\n")
    s2 = drv.wait_for(lambda s: s["error"] != "", what="the error to show")
    assert "syntax error" in s2["error"] and s2["scene"] == s1["scene"]
    scene.write_text("import sdfgl as sg\nscene = sg.box(-1)\n")
    s3 = drv.wait_for(lambda s: "must be > 0" in s["error"], what="a parameter error")
    assert s3["scene"] == s1["scene"]
    scene.write_text(SCENE_A)
    drv.wait_for(lambda s: s["error"] == "" and s["reloads"] == s0["reloads"] + 2, what="recovery")


def test_idle_window_does_not_redraw_and_quit_exits_cleanly(viewer):
    drv, proc, _, _ = viewer
    st = drv.wait_for(lambda s: s["samples"] >= 4 and not s["moving"], what="idle")
    time.sleep(0.8)
    assert drv.state()["frames"] == st["frames"]  # nothing changed, nothing drawn
    drv.key("q")
    assert proc.wait(15) == 0


def test_resize_follows_the_framebuffer(viewer):
    drv, proc, _, _ = viewer
    drv.xdo("windowsize", drv.window, "400", "300")
    st = drv.wait_for(lambda s: s["size"] == [400, 300] and s["samples"] >= 1, what="the resize")
    assert st["error"] == ""


def test_help_is_legible_at_any_window_size(viewer):
    drv, proc, _, _ = viewer
    st = drv.state()
    assert st["overlay"] == "H: help"  # the hint, on first open
    drv.key("h")
    big = drv.wait_for(lambda s: "anti-aliasing" in s["overlay"], what="the help")
    assert big["overlay_fits"] and big["overlay_font"] >= 10
    for w, h in (("170", "130"), ("1200", "700")):
        drv.xdo("windowsize", drv.window, w, h)
        st = drv.wait_for(lambda s: s["overlay_size"] == [int(w), int(h)], what="the help laid out again")
        assert st["overlay_fits"] and st["overlay_font"] >= 10, st["overlay_font"]
    assert st["overlay_font"] > big["overlay_font"]  # a big window gets a bigger font


GRID_SCENE = """import numpy as np
import sdfgl as sg
rng = np.random.default_rng(3)
scene = sg.union(*[sg.sphere(0.25).translate(tuple(rng.uniform(-1.5, 1.5, 3))) for _ in range(60)])
camera = sg.OrbitCamera(distance=6, yaw=30, pitch=20)
settings = {'shadows': False, 'ao': False}
"""


@pytest.mark.slow
def test_a_union_kept_as_data_draws_in_the_window_as_headless(viewer):
    """The window's render thread reads the scene's data table (a buffer texture set through
    its own GL calls) like the headless renderer: the same spheres in the same places."""
    import sdfgl as sg
    drv, proc, scene, _ = viewer
    s0 = drv.state()
    time.sleep(0.05)
    scene.write_text(GRID_SCENE)
    drv.wait_for(lambda s: s["reloads"] == s0["reloads"] + 1 and s["error"] == "", what="the reload")
    drv.wait_for(lambda s: s["samples"] >= 4 and not s["moving"], what="refinement")
    drv.key("p")
    st = drv.wait_for(lambda s: len(s["screenshots"]) == 1, what="a screenshot")
    shot = np.asarray(Image.open(st["screenshots"][0]), dtype=np.int16)
    ns: dict = {}
    exec(GRID_SCENE, ns)  # noqa: S102 - the test's own scene text
    cam = sg.OrbitCamera(target=tuple(st["target"]), distance=st["distance"], yaw=st["yaw"], pitch=st["pitch"])
    head = sg.render(ns["scene"], cam, (320, 240), aa=2, **ns["settings"])
    assert head.settings.grid_min and "uData" in head.source.text  # the union is data
    want = head.color.astype(np.int16)
    background = sg.render(sg.sphere(0.01).translate((0, 50, 0)), cam, (320, 240), **ns["settings"]).color
    covered = lambda img: (np.abs(img - background.astype(np.int16)).sum(-1) > 30).mean()  # noqa: E731
    assert covered(want) > 0.1
    assert abs(covered(shot) - covered(want)) < 0.02
    assert np.abs(shot - want).mean() < 4.0
