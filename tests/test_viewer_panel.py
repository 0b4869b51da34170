"""The side panel under Xvfb, driven by real mouse events: sliders, settings, the scene tree."""
import sys
import time

import numpy as np
import pytest
from PIL import Image, ImageGrab

import sdfgl as sg
from sdfgl.camera import OrbitCamera
from sdfgl.compiler.generate import generate
from sdfgl.settings import Settings

from .test_viewer import display  # noqa: F401 - the Xvfb fixture
from .test_viewer_select import select_image
from .xserver import Driver

pytestmark = pytest.mark.window

SCENE = """import sdfgl as sg
r = sg.param(0.6, name="radius", range=(0.3, 1.2))
paint = sg.param((0.9, 0.3, 0.2), name="paint")
scene = (sg.sphere(r).translate((-1, 0, 0)) | sg.box(1.2).translate((1, 0, 0))).color(paint)
settings = {"shadows": False, "ao": False}
camera = sg.OrbitCamera(distance=6, yaw=0, pitch=0)
"""
W, H, PANEL = 820, 540, 300


@pytest.fixture()
def viewer(display, tmp_path):
    (tmp_path / "scene.py").write_text(SCENE)
    state = tmp_path / "state.json"
    drv = Driver(display, state)
    proc = drv.launch(str(tmp_path / "scene.py"), "--size", f"{W}x{H}", "--max-samples", "2",
                      "--screenshot-dir", str(tmp_path / "shots"))
    try:
        drv.wait_for(lambda s: s["samples"] >= 2 and not s["compiling"] and s["panel"].get("rects"),
                     timeout=120, what="the first image with the panel")
        yield drv, display, tmp_path
    finally:
        if proc.poll() is None:
            proc.kill()
        proc.wait(10)


def grab(drv, display):
    geo = dict(line.split("=") for line in drv.xdo("getwindowgeometry", "--shell", drv.window).split())
    x, y = int(geo["X"]), int(geo["Y"])
    return np.asarray(ImageGrab.grab(xdisplay=display).convert("RGB"))[y:y + H, x:x + W].astype(np.int16)


def still(drv, pred=lambda s: True, what="a still image"):
    return drv.wait_for(lambda s: not s["compiling"] and s["samples"] >= 2 and pred(s), timeout=60, what=what)


def test_slider_drag_changes_value_and_image_without_a_new_program(viewer):
    drv, display, tmp = viewer
    s0 = still(drv)
    before = grab(drv, display)
    x0, y0, x1, y1 = s0["panel"]["rects"]["radius"]
    y = int((y0 + y1) / 2)
    drv.xdo("mousemove", "--window", drv.window, str(int(x0) + 40), str(y), "mousedown", "1")
    for i in range(1, 9):
        drv.xdo("mousemove", "--window", drv.window, str(int(x0) + 40 + 12 * i), str(y))
        time.sleep(0.03)
    drv.xdo("mouseup", "1")
    s1 = still(drv, lambda s: s["panel"]["params"]["radius"] > 0.7 and s["param_edits"] > 0, "the slider")
    assert s1["compiles"] == s0["compiles"]          # a uniform, not a recompile
    assert s1["yaw"] == s0["yaw"] and s1["pitch"] == s0["pitch"]  # the drag went to the panel, not the camera
    after = grab(drv, display)
    scene_part = np.abs(after[:, PANEL:] - before[:, PANEL:]).max(axis=2) > 30
    assert scene_part.sum() > 200                    # the sphere grew on screen
    # "save JSON" writes the scene with the value the slider set, and the view's camera
    x0, y0, x1, y1 = s1["panel"]["rects"]["save JSON"]
    drv.xdo("mousemove", "--window", drv.window, str(int((x0 + x1) / 2)), str(int((y0 + y1) / 2)), "click", "1")
    s2 = drv.wait_for(lambda s: s["panel"]["message"].startswith("saved"), what="the JSON document")
    doc = sg.load_scene(tmp / "shots" / "scene.json")
    assert doc.params["radius"].value == pytest.approx(s2["panel"]["params"]["radius"], abs=1e-6)
    assert doc.camera.eye == pytest.approx(OrbitCamera(target=tuple(s2["target"]), distance=s2["distance"],
                                                       yaw=s2["yaw"], pitch=s2["pitch"]).eye)
    assert doc.settings["shadows"] is False


def test_tree_selection_tints_the_subtree(viewer):
    """The box's row tints the pixels where the box is the surface hit, in the window and in a P screenshot."""
    drv, display, tmp = viewer
    s0 = still(drv)
    rects = s0["panel"]["rects"]
    box_row = next(k for k in rects if k.startswith("tree:translate(offset=(1"))
    x0, y0, x1, y1 = rects[box_row]
    drv.xdo("mousemove", "--window", drv.window, str(int(x0) + 60), str(int((y0 + y1) / 2)), "click", "1")
    st = still(drv, lambda s: s["settings"].get("debug") == "select" and s["panel"]["selected"], "the tint")
    assert st["error"] == "" and st["compiles"] == s0["compiles"] + 1
    assert st["view"] == [PANEL, 0, W - PANEL, H]  # the image lies right of the panel
    img = grab(drv, display)
    tint = (img[..., 0] > img[..., 2] + 60)[:, PANEL:]
    drv.key("p")  # a screenshot of the select view: what the window shows, without panel and overlay
    shot = drv.wait_for(lambda s: len(s["screenshots"]) == 1, what="the screenshot")
    assert shot["error"] == ""
    png = np.asarray(Image.open(shot["screenshots"][0]).convert("RGB")).astype(np.int16)
    assert png.shape == (H, W - PANEL, 3)
    shot_tint = png[..., 0] > png[..., 2] + 60
    # the same view rendered headless: where the box is the surface hit
    scene = sg.sphere(0.6).translate((-1, 0, 0)) | sg.box(1.2).translate((1, 0, 0))
    cam = OrbitCamera(target=tuple(st["target"]), distance=st["distance"], yaw=st["yaw"], pitch=st["pitch"])
    ref, _ = select_image(scene, scene.children[1], cam, (W - PANEL, H))
    want = ref[..., 0] > ref[..., 2] + 60
    assert want.sum() > 500
    for got in (tint, shot_tint):
        iou = (got & want).sum() / (got | want).sum()
        assert iou > 0.9, iou


def test_select_view_needs_a_highlight_and_values_print_as_python():
    from sdfgl.errors import ParameterError
    from sdfgl.viewer.panel import colour_params, python_lines
    s = sg.sphere(1) | sg.box(1)
    with pytest.raises(ParameterError, match="highlighted subtree"):
        generate(s, Settings.build(debug="select"))
    with pytest.raises(ParameterError, match="needs debug='select'"):
        generate(s, Settings.build(), highlight=s.children[0])
    src = generate(s, Settings.build(debug="select"), highlight=s.children[1])
    assert src.text.count("gSel = min(gSel") == 1   # only the box's distance is recorded
    r = sg.param(0.5, name="radius", range=(0.1, 2))
    paint = sg.param((0.9, 0.3, 0.2), name="paint")
    scene = sg.sphere(r).color(paint)
    assert colour_params(scene) == {id(paint)}
    text = python_lines([r, paint])
    assert text == ("radius = sg.param(0.5, name='radius', range=(0.1, 2.0))\n"
                    "paint = sg.param((0.9, 0.3, 0.2), name='paint')")
    ns = {"sg": sg}
    exec(text, ns)  # the printed values are valid Python that rebuilds the params
    assert ns["radius"].value == 0.5 and ns["radius"].range == (0.1, 2.0)


def test_panel_key_hint_and_help(viewer):
    drv, _, _ = viewer
    s0 = still(drv)
    assert s0["panel"]["visible"] and s0["overlay"] == "H: help"
    drv.key("n")
    s1 = drv.wait_for(lambda s: not s["panel"]["visible"], what="the panel to hide")
    assert s1["overlay"] == ""  # the hint goes with the first key
    drv.key("h")
    drv.wait_for(lambda s: "anti-aliasing" in s["overlay"], what="the help overlay")
    drv.key("n")
    drv.wait_for(lambda s: s["panel"]["visible"], what="the panel to show again")


def test_without_the_gui_library_the_panel_says_what_to_install(monkeypatch):
    from sdfgl.viewer import panel
    monkeypatch.setitem(sys.modules, "imgui_bundle", None)
    assert "pip install 'sdfgl[panel]'" in panel.available()


def test_readouts_show_frame_time_and_mean_steps(viewer):
    """The panel's live figures: frame time, and the mean map() calls per pixel of the image shown,
    which match a headless render's steps output of the same view."""
    drv, _, _ = viewer
    st = still(drv, lambda s: s["panel"].get("readout", {}).get("samples", 0) >= 2)
    readout = st["panel"]["readout"]
    assert readout["frame_ms"] > 0
    scene = sg.sphere(0.6).translate((-1, 0, 0)) | sg.box(1.2).translate((1, 0, 0))
    cam = OrbitCamera(target=tuple(st["target"]), distance=st["distance"], yaw=st["yaw"], pitch=st["pitch"])
    ref = sg.render(scene, cam, (W - PANEL, H), shadows=False, ao=False, outputs=("color", "steps"))
    # (the window's frames start from the coarse pass, as render()'s do)
    want = float(ref.steps.mean())
    assert want > 0.5
    assert abs(readout["mean_steps"] - want) < 0.1 * want, (readout, want)
    plain = sg.render(scene, cam, (W - PANEL, H), shadows=False, ao=False, outputs=("color", "steps"), coarse=False)
    assert readout["mean_steps"] < 0.9 * float(plain.steps.mean())  # the coarse pass saved the way to the scene
